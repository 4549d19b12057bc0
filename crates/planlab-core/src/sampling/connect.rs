//! RRT-Connect (Kuffner & LaValle 2000): a tree from each end; each
//! iteration extends one tree a step towards a random sample and then
//! greedily extends the other towards the new node until it reaches it
//! (the trees meet: done) or is blocked; then the trees swap roles.

use super::tree::Tree;
use super::{dist, extend_free, path_cost, Common, Event, Point};

const NONE: u32 = u32::MAX;

#[derive(Debug, Clone)]
pub(crate) struct ConnectPlanner {
    /// Tree 0 grows from the start, tree 1 from the goal.
    trees: [Tree; 2],
    /// Event ids of each tree's nodes (one id space for both trees).
    ids: [Vec<u32>; 2],
    next_id: u32,
    /// The tree extended towards the sample this iteration.
    active: usize,
}

enum Extend {
    Trapped,
    Advanced(u32),
    Reached(u32),
}

impl ConnectPlanner {
    pub(crate) fn new(c: &mut Common) -> Self {
        let mut s = Self {
            trees: [Tree::default(), Tree::default()],
            ids: [Vec::new(), Vec::new()],
            next_id: 0,
            active: 0,
        };
        s.add(c, 0, c.start, NONE);
        s.add(c, 1, c.goal, NONE);
        s
    }

    pub(crate) fn len(&self) -> usize {
        self.trees[0].pts.len() + self.trees[1].pts.len()
    }

    fn add(&mut self, c: &mut Common, t: usize, p: Point, parent: u32) -> u32 {
        let n = self.trees[t].add(p, parent);
        let id = self.next_id;
        self.next_id += 1;
        self.ids[t].push(id);
        c.log_node(id, p);
        if parent != NONE {
            c.log(Event::Edge {
                from: self.ids[t][parent as usize],
                to: id,
            });
        }
        n
    }

    fn extend(&mut self, c: &mut Common, t: usize, q: Point) -> Extend {
        let Some(near) = self.trees[t].index.nearest(q) else {
            return Extend::Trapped;
        };
        let from = self.trees[t].pts[near as usize];
        if from == q {
            return Extend::Reached(near);
        }
        let Some(x_new) = extend_free(&c.space, from, q, c.range) else {
            return Extend::Trapped;
        };
        let n = self.add(c, t, x_new, near);
        if x_new == q {
            Extend::Reached(n)
        } else {
            Extend::Advanced(n)
        }
    }

    pub(crate) fn iterate(&mut self, c: &mut Common) {
        let q = c.uniform();
        c.log_sample(q);
        let a = self.active;
        let b = 1 - a;
        self.active = b;
        let new = match self.extend(c, a, q) {
            Extend::Trapped => return,
            Extend::Advanced(n) | Extend::Reached(n) => n,
        };
        let target = self.trees[a].pts[new as usize];
        // Connect: as many steps as the distance needs, plus one.
        let steps = (dist(target, c.start).max(dist(target, c.goal)) / c.range).ceil() as usize
            + (c.space.width() + c.space.height()) / c.range.max(1.0) as usize
            + 2;
        for _ in 0..steps {
            match self.extend(c, b, target) {
                Extend::Trapped => return,
                Extend::Advanced(_) => {}
                Extend::Reached(m) => {
                    // Tree b's node m sits on tree a's node `new`.
                    let (s_node, g_node) = if a == 0 { (new, m) } else { (m, new) };
                    let mut path = self.trees[0].branch(s_node);
                    let mut back = self.trees[1].branch(g_node);
                    back.reverse();
                    // The meeting point is in both halves.
                    back.remove(0);
                    path.extend(back);
                    c.log(Event::Connect {
                        a: self.ids[0][s_node as usize],
                        b: self.ids[1][g_node as usize],
                    });
                    let cost = path_cost(&path);
                    if c.improves(cost) {
                        c.solved(cost, path);
                    }
                    return;
                }
            }
        }
    }
}
