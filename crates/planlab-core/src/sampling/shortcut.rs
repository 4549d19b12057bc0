//! Path shortcutting, a separate optional step after any planner: seeded
//! random pairs of the path's vertices are joined by a straight segment
//! when the disc can move along it, dropping the vertices between. A
//! shortcut is kept only when it is collision-free and shortens the path,
//! so the result is never invalid (given a valid input) nor longer.

use super::{dist, DiscSpace, Point};
use crate::num::Rng;

/// The path with up to `attempts` random shortcuts tried (seeded), then a
/// greedy pass that joins each vertex to the farthest one it sees.
pub fn shortcut(space: &DiscSpace, path: &[Point], seed: u64, attempts: usize) -> Vec<Point> {
    let mut p = path.to_vec();
    let mut rng = Rng::new(seed);
    for _ in 0..attempts {
        if p.len() < 3 {
            break;
        }
        let n = p.len() as u64;
        let i = (rng.next_u64() % n) as usize;
        let j = (rng.next_u64() % n) as usize;
        let (i, j) = (i.min(j), i.max(j));
        if j < i + 2 {
            continue;
        }
        try_join(space, &mut p, i, j);
    }
    let mut i = 0;
    while i + 2 < p.len() {
        let mut j = p.len() - 1;
        while j > i + 1 && !try_join(space, &mut p, i, j) {
            j -= 1;
        }
        i += 1;
    }
    p
}

/// Replaces `p[i..=j]` by the segment `p[i] → p[j]` when that is free and
/// shorter; returns whether it did.
fn try_join(space: &DiscSpace, p: &mut Vec<Point>, i: usize, j: usize) -> bool {
    let old: f64 = p[i..=j].windows(2).map(|w| dist(w[0], w[1])).sum();
    if dist(p[i], p[j]) < old && space.segment_free(p[i], p[j]) {
        p.drain(i + 1..j);
        true
    } else {
        false
    }
}
