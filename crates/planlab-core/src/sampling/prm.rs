//! Roadmaps: PRM (Kavraki et al. 1996) and Lazy PRM* (k-nearest PRM* of
//! Karaman & Frazzoli 2011, with the lazy edges of Bohlin & Kavraki 2000).
//!
//! Each iteration draws one sample; a free one becomes a node (nodes are
//! always checked at once) joined to its neighbours: PRM's 10 nearest
//! within the range, edges checked at once; Lazy PRM*'s k = ⌈e·(1 + 1/d)·ln n⌉
//! nearest, edges **not** checked. Shortest distances from the start are
//! kept up to date as edges arrive (they only shrink). When the goal's
//! distance beats the best path, Lazy PRM* checks that candidate path's
//! unchecked edges: a colliding one is removed and the distances are
//! recomputed (Dijkstra), until the candidate is valid or no longer better.

use std::cmp::Reverse;
use std::collections::BinaryHeap;

use super::nn::PointIndex;
use super::{Common, Event, Point};

const NONE: u32 = u32::MAX;
/// PRM's neighbours per node (OMPL's default).
const PRM_K: usize = 10;

#[derive(Debug, Clone, Copy, PartialEq)]
enum EdgeState {
    Unchecked,
    Valid,
    Invalid,
}

#[derive(Debug, Clone)]
struct Edge {
    a: u32,
    b: u32,
    w: f64,
    state: EdgeState,
}

/// A heap key ordered by (distance, node).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Key(f64, u32);
impl Eq for Key {}
impl PartialOrd for Key {
    fn partial_cmp(&self, o: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Key {
    fn cmp(&self, o: &Self) -> std::cmp::Ordering {
        self.0.total_cmp(&o.0).then(self.1.cmp(&o.1))
    }
}

#[derive(Debug, Clone)]
pub(crate) struct PrmPlanner {
    lazy: bool,
    pts: Vec<Point>,
    adj: Vec<Vec<u32>>,
    edges: Vec<Edge>,
    index: PointIndex,
    /// Shortest distance from the start over edges not known to collide.
    d: Vec<f64>,
    /// The edge to each node's predecessor on that shortest path.
    pred: Vec<u32>,
    near: Vec<(f64, u32)>,
}

impl PrmPlanner {
    pub(crate) fn new(c: &mut Common, lazy: bool) -> Self {
        let mut s = Self {
            lazy,
            pts: Vec::new(),
            adj: Vec::new(),
            edges: Vec::new(),
            index: PointIndex::default(),
            d: Vec::new(),
            pred: Vec::new(),
            near: Vec::new(),
        };
        let (start, goal) = (c.start, c.goal);
        s.add_node(c, start);
        s.d[0] = 0.0;
        s.index.insert(start, 0);
        s.add_node(c, goal);
        s.connect(c, 1);
        s.settle(c);
        s
    }

    pub(crate) fn len(&self) -> usize {
        self.pts.len()
    }

    fn add_node(&mut self, c: &mut Common, p: Point) -> u32 {
        let id = self.pts.len() as u32;
        self.pts.push(p);
        self.adj.push(Vec::new());
        self.d.push(f64::INFINITY);
        self.pred.push(NONE);
        c.log_node(id, p);
        id
    }

    /// Joins node `n` to its neighbours (before it enters the index).
    fn connect(&mut self, c: &mut Common, n: u32) {
        let p = self.pts[n as usize];
        let mut near = std::mem::take(&mut self.near);
        if self.lazy {
            let count = (self.pts.len()) as f64;
            let k = (std::f64::consts::E * 1.5 * count.ln()).ceil().max(1.0) as usize;
            self.index.k_nearest(p, k, &mut near);
        } else {
            self.index.k_nearest(p, PRM_K, &mut near);
            near.retain(|&(d, _)| d <= c.range);
        }
        let mut heap = BinaryHeap::new();
        for &(w, m) in &near {
            let state = if self.lazy {
                EdgeState::Unchecked
            } else if c.space.segment_free(self.pts[m as usize], p) {
                EdgeState::Valid
            } else {
                continue;
            };
            let e = self.edges.len() as u32;
            self.edges.push(Edge {
                a: m,
                b: n,
                w,
                state,
            });
            self.adj[m as usize].push(e);
            self.adj[n as usize].push(e);
            c.log(Event::Edge { from: m, to: n });
            for (u, v) in [(m, n), (n, m)] {
                let through = self.d[u as usize] + w;
                if through < self.d[v as usize] {
                    self.d[v as usize] = through;
                    self.pred[v as usize] = e;
                    heap.push(Reverse(Key(through, v)));
                }
            }
        }
        self.near = near;
        self.index.insert(p, n);
        self.relax(&mut heap);
    }

    /// Dijkstra from the nodes on the heap over edges not known to collide.
    fn relax(&mut self, heap: &mut BinaryHeap<Reverse<Key>>) {
        while let Some(Reverse(Key(du, u))) = heap.pop() {
            if du > self.d[u as usize] {
                continue;
            }
            for &e in &self.adj[u as usize] {
                let edge = &self.edges[e as usize];
                if edge.state == EdgeState::Invalid {
                    continue;
                }
                let v = if edge.a == u { edge.b } else { edge.a };
                let through = du + edge.w;
                if through < self.d[v as usize] {
                    self.d[v as usize] = through;
                    self.pred[v as usize] = e;
                    heap.push(Reverse(Key(through, v)));
                }
            }
        }
    }

    /// Restores the shortest distances after the edges `broken` (all on
    /// the candidate path, so each is some node's predecessor edge) were
    /// found to collide: only the nodes whose shortest path ran through
    /// them, the subtrees hanging below them in the predecessor tree (found
    /// through the adjacency lists, so the work is local), are reset and
    /// re-seeded from their untouched neighbours, instead of a Dijkstra
    /// over the whole roadmap each time (which made Lazy PRM* slow: on
    /// cluttered maps most lazy edges collide). Removing edges only
    /// lengthens paths, so the untouched distances stay exact.
    fn repair(&mut self, broken: &[u32]) {
        let mut dirty: Vec<u32> = Vec::new();
        for &e in broken {
            let edge = &self.edges[e as usize];
            for w in [edge.a, edge.b] {
                if self.pred[w as usize] == e {
                    dirty.push(w);
                }
            }
        }
        // The subtrees: a node's children are the neighbours whose
        // predecessor edge is the edge to it.
        let mut i = 0;
        while i < dirty.len() {
            let u = dirty[i];
            i += 1;
            for &e in &self.adj[u as usize] {
                let edge = &self.edges[e as usize];
                let w = if edge.a == u { edge.b } else { edge.a };
                if self.pred[w as usize] == e && !broken.contains(&e) {
                    dirty.push(w);
                }
            }
        }
        for &v in &dirty {
            self.d[v as usize] = f64::INFINITY;
            self.pred[v as usize] = NONE;
        }
        let mut heap = BinaryHeap::new();
        for &v in &dirty {
            for &e in &self.adj[v as usize] {
                let edge = &self.edges[e as usize];
                if edge.state == EdgeState::Invalid {
                    continue;
                }
                let u = if edge.a == v { edge.b } else { edge.a };
                let through = self.d[u as usize] + edge.w;
                if through < self.d[v as usize] {
                    self.d[v as usize] = through;
                    self.pred[v as usize] = e;
                }
            }
            if self.d[v as usize].is_finite() {
                heap.push(Reverse(Key(self.d[v as usize], v)));
            }
        }
        self.relax(&mut heap);
    }

    /// The edges of the current shortest path to the goal, goal first.
    fn candidate(&self) -> Vec<u32> {
        let mut out = Vec::new();
        let mut v = 1u32;
        while v != 0 {
            let e = self.pred[v as usize];
            out.push(e);
            let edge = &self.edges[e as usize];
            v = if edge.a == v { edge.b } else { edge.a };
        }
        out
    }

    /// Turns a better candidate into a solution, checking lazy edges first.
    fn settle(&mut self, c: &mut Common) {
        while c.improves(self.d[1]) {
            let edges = self.candidate();
            let mut broken = Vec::new();
            for &e in &edges {
                let (a, b, state) = {
                    let edge = &self.edges[e as usize];
                    (edge.a, edge.b, edge.state)
                };
                if state == EdgeState::Unchecked {
                    if c.space
                        .segment_free(self.pts[a as usize], self.pts[b as usize])
                    {
                        self.edges[e as usize].state = EdgeState::Valid;
                    } else {
                        self.edges[e as usize].state = EdgeState::Invalid;
                        c.log(Event::RemoveEdge { from: a, to: b });
                        broken.push(e);
                    }
                }
            }
            if !broken.is_empty() {
                self.repair(&broken);
                continue;
            }
            let mut path = vec![self.pts[1]];
            let mut v = 1u32;
            for &e in &edges {
                let edge = &self.edges[e as usize];
                v = if edge.a == v { edge.b } else { edge.a };
                path.push(self.pts[v as usize]);
            }
            path.reverse();
            let cost = self.d[1];
            c.solved(cost, path);
        }
    }

    pub(crate) fn iterate(&mut self, c: &mut Common) {
        let q = c.uniform();
        c.log_sample(q);
        if !c.space.point_free(q) {
            return;
        }
        let n = self.add_node(c, q);
        self.connect(c, n);
        self.settle(c);
    }
}
