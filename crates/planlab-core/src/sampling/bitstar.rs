//! BIT* (Gammell, Srinivasa & Barfoot 2015): batches of samples (informed
//! once a path exists) form an implicit random geometric graph, searched
//! best-first like Lifelong Planning A*: a vertex queue ordered by
//! g_T(v) + ĥ(v) and an edge queue ordered by g_T(v) + ĉ(v, x) + ĥ(x).
//! Edges are collision-checked only when taken from the queue (lazy).
//! A batch ends when no queued edge can improve the solution; the next one
//! prunes what cannot (f̂ ≥ c_best) and adds `batch_size` new samples.
//!
//! Queue keys are computed when an entry is pushed; an edge whose key has
//! grown by the time it is taken (its source was rewired) is pushed back
//! with the current key, so edges are still taken in order of their
//! current keys' lower bounds.

use std::cmp::Reverse;
use std::collections::BinaryHeap;

use super::nn::PointIndex;
use super::{dist, informed, Common, Event, Point};

const NONE: u32 = u32::MAX;
/// Draws per sample before giving up on a free one (crowded maps).
const SAMPLE_TRIES: usize = 100;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum State {
    Sample,
    Vertex,
    Gone,
}

/// A heap key ordered by (value, ids).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Key(f64, u32, u32);
impl Eq for Key {}
impl PartialOrd for Key {
    fn partial_cmp(&self, o: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Key {
    fn cmp(&self, o: &Self) -> std::cmp::Ordering {
        self.0
            .total_cmp(&o.0)
            .then(self.1.cmp(&o.1))
            .then(self.2.cmp(&o.2))
    }
}

#[derive(Debug, Clone)]
pub(crate) struct BitStar {
    batch_size: usize,
    pts: Vec<Point>,
    state: Vec<State>,
    g: Vec<f64>,
    parent: Vec<u32>,
    children: Vec<Vec<u32>>,
    /// Vertices that existed when the batch began (BIT*'s V_old).
    old: Vec<bool>,
    expanded: Vec<bool>,
    samples: PointIndex,
    vertices: PointIndex,
    qv: BinaryHeap<Reverse<Key>>,
    qe: BinaryHeap<Reverse<Key>>,
    radius: f64,
    /// The radius constant: 2 η (1 + 1/d)^(1/d) (μ(X_free)/ζ_d)^(1/d), η = 1.1.
    gamma: f64,
    near: Vec<(f64, u32)>,
}

impl BitStar {
    pub(crate) fn new(c: &mut Common, batch_size: usize) -> Self {
        let gamma = 2.0 * 1.1 * 1.5f64.sqrt() * (c.space.free_area() / std::f64::consts::PI).sqrt();
        let mut s = Self {
            batch_size,
            pts: vec![c.start, c.goal],
            state: vec![State::Vertex, State::Sample],
            g: vec![0.0, f64::INFINITY],
            parent: vec![NONE, NONE],
            children: vec![Vec::new(), Vec::new()],
            old: vec![false, false],
            expanded: vec![false, false],
            samples: PointIndex::default(),
            vertices: PointIndex::default(),
            qv: BinaryHeap::new(),
            qe: BinaryHeap::new(),
            radius: 0.0,
            gamma,
            near: Vec::new(),
        };
        s.vertices.insert(c.start, 0);
        s.samples.insert(c.goal, 1);
        c.log_node(0, c.start);
        s
    }

    pub(crate) fn len(&self) -> usize {
        self.state.iter().filter(|s| **s != State::Gone).count()
    }

    fn h(&self, c: &Common, x: u32) -> f64 {
        dist(self.pts[x as usize], c.goal)
    }

    fn g_hat(&self, c: &Common, x: u32) -> f64 {
        dist(c.start, self.pts[x as usize])
    }

    fn c_hat(&self, a: u32, b: u32) -> f64 {
        dist(self.pts[a as usize], self.pts[b as usize])
    }

    fn vertex_key(&self, c: &Common, v: u32) -> f64 {
        self.g[v as usize] + self.h(c, v)
    }

    fn edge_key(&self, c: &Common, v: u32, x: u32) -> f64 {
        self.g[v as usize] + self.c_hat(v, x) + self.h(c, x)
    }

    pub(crate) fn iterate(&mut self, c: &mut Common) {
        if self.qe.is_empty() && self.qv.is_empty() {
            self.new_batch(c);
            return;
        }
        // Expand vertices while the best vertex could beat the best edge.
        loop {
            let bv = self.qv.peek().map_or(f64::INFINITY, |Reverse(k)| k.0);
            let be = self.qe.peek().map_or(f64::INFINITY, |Reverse(k)| k.0);
            if self.qv.is_empty() || bv > be {
                break;
            }
            let Some(Reverse(Key(_, v, _))) = self.qv.pop() else {
                break;
            };
            if self.state[v as usize] == State::Vertex && !self.expanded[v as usize] {
                self.expand(c, v);
            }
        }
        let Some(Reverse(Key(key, v, x))) = self.qe.pop() else {
            self.qv.clear();
            return;
        };
        if self.state[v as usize] != State::Vertex || self.state[x as usize] == State::Gone {
            return;
        }
        let now = self.edge_key(c, v, x);
        if now > key * (1.0 + 1e-12) {
            self.qe.push(Reverse(Key(now, v, x)));
            return;
        }
        if now >= c.best {
            // Nothing queued can improve the solution: the batch is over.
            self.qe.clear();
            self.qv.clear();
            return;
        }
        let (gv, cv) = (self.g[v as usize], self.c_hat(v, x));
        // Already the tree's edge, or no cheaper than x's current path.
        if self.parent[x as usize] == v || gv + cv >= self.g[x as usize] {
            return;
        }
        if self.g_hat(c, v) + cv + self.h(c, x) >= c.best {
            return;
        }
        if !c
            .space
            .segment_free(self.pts[v as usize], self.pts[x as usize])
        {
            return;
        }
        if self.state[x as usize] == State::Vertex {
            let old = self.parent[x as usize];
            self.reparent(x, v);
            c.log(Event::Rewire {
                node: x,
                old_parent: old,
                new_parent: v,
            });
        } else {
            self.samples.remove(self.pts[x as usize], x);
            self.vertices.insert(self.pts[x as usize], x);
            self.state[x as usize] = State::Vertex;
            self.expanded[x as usize] = false;
            self.old[x as usize] = false;
            self.reparent(x, v);
            c.log_node(x, self.pts[x as usize]);
            c.log(Event::Edge { from: v, to: x });
            let k = self.vertex_key(c, x);
            self.qv.push(Reverse(Key(k, x, 0)));
        }
        if self.state[1] == State::Vertex && c.improves(self.g[1]) {
            let path = self.branch(1);
            c.solved(self.g[1], path);
        }
    }

    fn reparent(&mut self, x: u32, v: u32) {
        let old = self.parent[x as usize];
        if old != NONE {
            self.children[old as usize].retain(|&y| y != x);
        }
        self.parent[x as usize] = v;
        self.children[v as usize].push(x);
        let mut stack = vec![x];
        while let Some(n) = stack.pop() {
            let p = self.parent[n as usize];
            self.g[n as usize] = self.g[p as usize] + self.c_hat(p, n);
            stack.extend_from_slice(&self.children[n as usize]);
        }
    }

    fn branch(&self, mut n: u32) -> Vec<Point> {
        let mut out = Vec::new();
        while n != NONE {
            out.push(self.pts[n as usize]);
            n = self.parent[n as usize];
        }
        out.reverse();
        out
    }

    /// Queues the edges out of `v` that could improve the solution: to the
    /// samples near it, and, the first time a new vertex is expanded, to
    /// the vertices near it that it could give a cheaper path.
    fn expand(&mut self, c: &mut Common, v: u32) {
        self.expanded[v as usize] = true;
        let p = self.pts[v as usize];
        let mut near = std::mem::take(&mut self.near);
        self.samples.within(p, self.radius, &mut near);
        let gv = self.g[v as usize];
        for &(d, x) in &near {
            if self.g_hat(c, v) + d + self.h(c, x) < c.best {
                let k = gv + d + self.h(c, x);
                self.qe.push(Reverse(Key(k, v, x)));
            }
        }
        if !self.old[v as usize] {
            self.vertices.within(p, self.radius, &mut near);
            for &(d, w) in &near {
                if w == v || self.parent[w as usize] == v || self.parent[v as usize] == w {
                    continue;
                }
                if self.g_hat(c, v) + d + self.h(c, w) < c.best && gv + d < self.g[w as usize] {
                    let k = gv + d + self.h(c, w);
                    self.qe.push(Reverse(Key(k, v, w)));
                }
            }
        }
        self.near = near;
    }

    fn new_batch(&mut self, c: &mut Common) {
        if c.best.is_finite() {
            self.prune(c);
        }
        for _ in 0..self.batch_size {
            for _ in 0..SAMPLE_TRIES {
                let q = informed::sample(c);
                if c.best.is_finite() && !informed::in_ellipse(c, q, c.best) {
                    continue;
                }
                if !c.space.point_free(q) {
                    continue;
                }
                let id = self.pts.len() as u32;
                self.pts.push(q);
                self.state.push(State::Sample);
                self.g.push(f64::INFINITY);
                self.parent.push(NONE);
                self.children.push(Vec::new());
                self.old.push(false);
                self.expanded.push(false);
                self.samples.insert(q, id);
                c.log_sample(q);
                break;
            }
        }
        let q = (self.samples.len() + self.vertices.len()).max(2) as f64;
        self.radius = self.gamma * (q.ln() / q).sqrt();
        for v in 0..self.pts.len() {
            if self.state[v] == State::Vertex {
                self.old[v] = true;
                self.expanded[v] = false;
                let k = self.vertex_key(c, v as u32);
                self.qv.push(Reverse(Key(k, v as u32, 0)));
            }
        }
    }

    /// Drops the samples and vertices that cannot improve the solution;
    /// vertices cut off from the tree that still could become samples again.
    fn prune(&mut self, c: &mut Common) {
        let best = c.best;
        let (start, goal) = (c.start, c.goal);
        let f_hat = |s: &Self, x: usize| dist(start, s.pts[x]) + dist(s.pts[x], goal);
        let mut changed = false;
        for x in 0..self.pts.len() {
            if self.state[x] == State::Sample && f_hat(self, x) >= best && x != 1 {
                self.state[x] = State::Gone;
                changed = true;
            }
        }
        // Vertices whose heuristic cost exceeds the solution, with their
        // subtrees; the goal and start stay.
        let mut cut = Vec::new();
        for x in 0..self.pts.len() {
            if self.state[x] == State::Vertex && x > 1 && f_hat(self, x) > best * (1.0 + 1e-9) {
                cut.push(x as u32);
            }
        }
        for root in cut {
            if self.state[root as usize] != State::Vertex {
                continue;
            }
            let p = self.parent[root as usize];
            if p != NONE {
                self.children[p as usize].retain(|&y| y != root);
            }
            let mut stack = vec![root];
            while let Some(n) = stack.pop() {
                let kids = std::mem::take(&mut self.children[n as usize]);
                stack.extend_from_slice(&kids);
                self.parent[n as usize] = NONE;
                self.g[n as usize] = f64::INFINITY;
                self.state[n as usize] = if f_hat(self, n as usize) < best {
                    State::Sample
                } else {
                    State::Gone
                };
                c.log(Event::Prune { node: n });
                changed = true;
            }
        }
        if changed {
            let keep = |want: State| {
                let (pts, state) = (&self.pts, &self.state);
                (0..pts.len())
                    .filter(move |&x| state[x] == want)
                    .map(move |x| (pts[x], x as u32))
            };
            let s: Vec<_> = keep(State::Sample).collect();
            let v: Vec<_> = keep(State::Vertex).collect();
            self.samples.rebuild(s.into_iter());
            self.vertices.rebuild(v.into_iter());
        }
    }
}
