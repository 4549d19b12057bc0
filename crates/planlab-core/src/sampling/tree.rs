//! One tree from the start: RRT (LaValle 1998), RRT* (Karaman & Frazzoli
//! 2011, the radius version: r = min(γ·√(ln n / n), range) with γ 10 %
//! above their bound) and Informed RRT* (Gammell et al. 2014: RRT* whose
//! samples come from the informed ellipse once a path exists; no pruning).

use super::nn::PointIndex;
use super::{dist, extend_free, informed, Common, Event, Point};

/// Which member of the family.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Variant {
    Rrt,
    Star,
    Informed,
}

const NONE: u32 = u32::MAX;

/// A tree of points with parents, costs-to-come and children.
#[derive(Debug, Clone, Default)]
pub(crate) struct Tree {
    pub(crate) pts: Vec<Point>,
    pub(crate) parent: Vec<u32>,
    pub(crate) cost: Vec<f64>,
    pub(crate) children: Vec<Vec<u32>>,
    pub(crate) index: PointIndex,
}

impl Tree {
    pub(crate) fn add(&mut self, p: Point, parent: u32) -> u32 {
        let id = self.pts.len() as u32;
        let cost = if parent == NONE {
            0.0
        } else {
            self.cost[parent as usize] + dist(self.pts[parent as usize], p)
        };
        self.pts.push(p);
        self.parent.push(parent);
        self.cost.push(cost);
        self.children.push(Vec::new());
        if parent != NONE {
            self.children[parent as usize].push(id);
        }
        self.index.insert(p, id);
        id
    }

    /// Makes `new_parent` the parent of `node` and updates the costs of its
    /// subtree.
    pub(crate) fn reparent(&mut self, node: u32, new_parent: u32) {
        let old = self.parent[node as usize];
        if old != NONE {
            self.children[old as usize].retain(|&c| c != node);
        }
        self.parent[node as usize] = new_parent;
        self.children[new_parent as usize].push(node);
        let mut stack = vec![node];
        while let Some(n) = stack.pop() {
            let p = self.parent[n as usize];
            self.cost[n as usize] =
                self.cost[p as usize] + dist(self.pts[p as usize], self.pts[n as usize]);
            stack.extend_from_slice(&self.children[n as usize]);
        }
    }

    /// The points from the root to `node`.
    pub(crate) fn branch(&self, node: u32) -> Vec<Point> {
        let mut out = Vec::new();
        let mut n = node;
        while n != NONE {
            out.push(self.pts[n as usize]);
            n = self.parent[n as usize];
        }
        out.reverse();
        out
    }
}

#[derive(Debug, Clone)]
pub(crate) struct TreePlanner {
    variant: Variant,
    tree: Tree,
    goal_node: u32,
    /// γ of the RRT* radius.
    gamma: f64,
    near: Vec<(f64, u32)>,
}

impl TreePlanner {
    pub(crate) fn new(c: &mut Common, variant: Variant) -> Self {
        let mut tree = Tree::default();
        tree.add(c.start, NONE);
        c.log_node(0, c.start);
        // Karaman & Frazzoli's γ* = 2 (1 + 1/d)^(1/d) (μ(X_free)/ζ_d)^(1/d), d = 2.
        let gamma = 1.1 * 2.0 * 1.5f64.sqrt() * (c.space.free_area() / std::f64::consts::PI).sqrt();
        Self {
            variant,
            tree,
            goal_node: NONE,
            gamma,
            near: Vec::new(),
        }
    }

    pub(crate) fn len(&self) -> usize {
        self.tree.pts.len()
    }

    /// The RRT* connection radius. Informed RRT* measures the space it
    /// samples, the informed ellipse, not the whole map (Gammell et al.
    /// 2014, eq. 9 with λ(X_f̂) in place of λ(X_free)): with the map's area
    /// the radius stays map-sized while the samples crowd into a thin
    /// ellipse, and every new node then rewires against thousands.
    fn radius(&self, c: &Common) -> f64 {
        let n = (self.tree.pts.len() + 1) as f64;
        let mut gamma = self.gamma;
        if self.variant == Variant::Informed && c.best.is_finite() {
            let ellipse = informed::area(c, c.best);
            let free = c.space.free_area();
            if ellipse < free {
                gamma *= (ellipse / free).sqrt();
            }
        }
        (gamma * (n.ln() / n).sqrt()).min(c.range)
    }

    pub(crate) fn iterate(&mut self, c: &mut Common) {
        let q = if c.rng.uniform() < c.goal_bias {
            c.goal
        } else if self.variant == Variant::Informed {
            informed::sample(c)
        } else {
            c.uniform()
        };
        c.log_sample(q);
        let Some(nearest) = self.tree.index.nearest(q) else {
            return;
        };
        let from = self.tree.pts[nearest as usize];
        let Some(x_new) = extend_free(&c.space, from, q, c.range) else {
            return;
        };
        if x_new == c.goal && self.goal_node != NONE {
            // The goal is in the tree already; RRT* improves it by rewiring.
            return;
        }
        let new = if self.variant == Variant::Rrt {
            self.tree.add(x_new, nearest)
        } else {
            self.add_star(c, nearest, x_new)
        };
        c.log_node(new, x_new);
        c.log(Event::Edge {
            from: self.tree.parent[new as usize],
            to: new,
        });
        if x_new == c.goal {
            self.goal_node = new;
        } else if self.variant != Variant::Rrt {
            self.rewire(c, new);
        }
        if self.goal_node == NONE
            && dist(x_new, c.goal) <= c.range
            && c.space.segment_free(x_new, c.goal)
        {
            let g = if self.variant == Variant::Rrt {
                self.tree.add(c.goal, new)
            } else {
                self.add_star(c, new, c.goal)
            };
            c.log_node(g, c.goal);
            c.log(Event::Edge {
                from: self.tree.parent[g as usize],
                to: g,
            });
            self.goal_node = g;
        }
        if self.goal_node != NONE {
            let cost = self.tree.cost[self.goal_node as usize];
            if c.improves(cost) {
                let path = self.tree.branch(self.goal_node);
                c.solved(cost, path);
            }
        }
    }

    /// Adds `x_new` under its cheapest collision-free parent among the
    /// nodes within the RRT* radius (`nearest` is known to reach it).
    fn add_star(&mut self, c: &mut Common, nearest: u32, x_new: Point) -> u32 {
        let r = self.radius(c);
        let mut near = std::mem::take(&mut self.near);
        self.tree.index.within(x_new, r, &mut near);
        let mut cands: Vec<(f64, u32)> = near
            .iter()
            .map(|&(d, n)| (self.tree.cost[n as usize] + d, n))
            .collect();
        cands.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        let via_nearest =
            self.tree.cost[nearest as usize] + dist(self.tree.pts[nearest as usize], x_new);
        let mut parent = nearest;
        for &(cost, n) in &cands {
            if cost >= via_nearest {
                break;
            }
            if c.space.segment_free(self.tree.pts[n as usize], x_new) {
                parent = n;
                break;
            }
        }
        self.near = near;
        self.tree.add(x_new, parent)
    }

    /// Gives the nodes near `new` a cheaper path through it where one exists.
    fn rewire(&mut self, c: &mut Common, new: u32) {
        let r = self.radius(c);
        let p = self.tree.pts[new as usize];
        let mut near = std::mem::take(&mut self.near);
        self.tree.index.within(p, r, &mut near);
        for &(d, n) in &near {
            if n == new || n == 0 || n == self.tree.parent[new as usize] {
                continue;
            }
            let through = self.tree.cost[new as usize] + d;
            if through < self.tree.cost[n as usize] * (1.0 - 1e-12)
                && c.space.segment_free(p, self.tree.pts[n as usize])
            {
                let old_parent = self.tree.parent[n as usize];
                self.tree.reparent(n, new);
                c.log(Event::Rewire {
                    node: n,
                    old_parent,
                    new_parent: new,
                });
            }
        }
        self.near = near;
    }
}
