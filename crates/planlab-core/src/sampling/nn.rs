//! Nearest-neighbour and radius queries over the planners' points, on
//! `rstar`'s R*-tree (dynamic inserts and removals, builds for wasm32, no
//! randomness: the same inserts in the same order give the same tree and
//! the same answers). Results are ordered by (distance, id) so that ties
//! are broken the same way everywhere.

use rstar::primitives::GeomWithData;
use rstar::RTree;

use super::Point;

type Entry = GeomWithData<[f64; 2], u32>;

/// Points with ids.
#[derive(Debug, Clone, Default)]
pub(crate) struct PointIndex {
    tree: RTree<Entry>,
}

fn d2(a: Point, b: Point) -> f64 {
    let (dx, dy) = (a[0] - b[0], a[1] - b[1]);
    dx * dx + dy * dy
}

impl PointIndex {
    pub(crate) fn insert(&mut self, p: Point, id: u32) {
        self.tree.insert(Entry::new(p, id));
    }

    pub(crate) fn remove(&mut self, p: Point, id: u32) {
        self.tree.remove(&Entry::new(p, id));
    }

    pub(crate) fn len(&self) -> usize {
        self.tree.size()
    }

    /// Rebuilds the index from scratch (bulk load: faster than inserts).
    pub(crate) fn rebuild(&mut self, points: impl Iterator<Item = (Point, u32)>) {
        self.tree = RTree::bulk_load(points.map(|(p, id)| Entry::new(p, id)).collect());
    }

    /// The nearest id; the smallest id among equally near ones.
    pub(crate) fn nearest(&self, p: Point) -> Option<u32> {
        let mut it = self.tree.nearest_neighbor_iter(p);
        let first = it.next()?;
        let best = d2(*first.geom(), p);
        let mut id = first.data;
        for e in it {
            if d2(*e.geom(), p) > best {
                break;
            }
            id = id.min(e.data);
        }
        Some(id)
    }

    /// Ids within `r` of `p` (inclusive), by (distance, id).
    pub(crate) fn within(&self, p: Point, r: f64, out: &mut Vec<(f64, u32)>) {
        out.clear();
        out.extend(
            self.tree
                .locate_within_distance(p, r * r)
                .map(|e| (d2(*e.geom(), p).sqrt(), e.data)),
        );
        out.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    }

    /// The `k` nearest ids, by (distance, id); ties at the k-th distance
    /// are all considered before cutting, so the cut does not depend on the
    /// tree's shape.
    pub(crate) fn k_nearest(&self, p: Point, k: usize, out: &mut Vec<(f64, u32)>) {
        out.clear();
        if k == 0 {
            return;
        }
        let mut last = f64::NEG_INFINITY;
        for e in self.tree.nearest_neighbor_iter(p) {
            let d = d2(*e.geom(), p).sqrt();
            if out.len() >= k && d > last {
                break;
            }
            last = d;
            out.push((d, e.data));
        }
        out.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        out.truncate(k);
    }
}
