//! Key-point extraction of Wu (2022) §3.2.1 (docs/algorithms.md §key-points, paper key \[T\]).
//!
//! A grid path is reduced to the few points a local planner needs as
//! intermediate goals, in two steps:
//!
//! 1. [`turning_points`]: of every run of nodes in the same search direction
//!    keep only the run's last node (\[T\] Fig 3-8: 46 → 11 nodes).
//! 2. [`prune`]: drop a turning point whenever the straight segment between
//!    its neighbours is collision-free, until none can go (\[T\] Fig 3-9:
//!    11 → 3).
//!
//! Decision (the thesis only states the rule "deleting a turning point must
//! not make the updated path cross an obstacle; keep as few as possible"):
//! pruning sweeps forward from the start; each interior point is removed when
//! the segment from the last point kept before it to the point after it is
//! free, so a removal is seen at once by the next test. Sweeps repeat until
//! one removes nothing. Start and goal are never removed.

use super::events::emit;
use super::{Diagonal, GridPos, PlanGrid, SearchEvent, SearchObserver};

/// `b − a` reduced by the gcd of its components, so steps of (2, 0) and
/// (1, 0) — or (4, 2) and (2, 1) — count as the same direction; (0, 0) for a
/// repeated cell.
fn direction(a: GridPos, b: GridPos) -> (i64, i64) {
    let dx = i64::from(b.col) - i64::from(a.col);
    let dy = i64::from(b.row) - i64::from(a.row);
    let g = gcd(dx.unsigned_abs(), dy.unsigned_abs()).max(1) as i64;
    (dx / g, dy / g)
}

fn gcd(mut a: u64, mut b: u64) -> u64 {
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a
}

/// [`PlanGrid::segment_is_free`], answering `false` at once when an end lies
/// off the map or in an obstacle (so garbage far-off coordinates are not
/// walked cell by cell).
pub(crate) fn segment_free(grid: &PlanGrid, a: GridPos, b: GridPos, diagonal: Diagonal) -> bool {
    let free = |q: GridPos| grid.is_free(i64::from(q.col), i64::from(q.row));
    free(a) && free(b) && grid.segment_is_free(a, b, diagonal)
}

/// Step 1 of \[T\] §3.2.1: the start, every node where the direction of travel
/// changes, and the goal.
///
/// Directions are compared after reducing each step by its gcd, so this also
/// works for safe-A* paths with 2-cell moves. Consecutive repeated cells are
/// collapsed first. Empty in, empty out; a single cell gives that cell.
pub fn turning_points(cells: &[GridPos]) -> Vec<GridPos> {
    let mut dedup: Vec<GridPos> = Vec::with_capacity(cells.len());
    for &p in cells {
        if dedup.last() != Some(&p) {
            dedup.push(p);
        }
    }
    let Some((&first, _)) = dedup.split_first() else {
        return Vec::new();
    };
    let mut out = vec![first];
    for w in dedup.windows(3) {
        if direction(w[0], w[1]) != direction(w[1], w[2]) {
            out.push(w[1]);
        }
    }
    if let Some(&last) = dedup.last() {
        if dedup.len() > 1 {
            out.push(last);
        }
    }
    out
}

/// Step 2 of \[T\] §3.2.1: removes points whose neighbours see each other.
///
/// A point is removed when `grid.segment_is_free(prev, next, diagonal)` holds
/// for its current neighbours (on the inflated grid, typically); forward
/// sweeps repeat until one removes nothing (module doc). First and last
/// points always stay. Segments already in `points` are not checked: a
/// collision-free input gives a collision-free output. Fewer than three
/// points are returned unchanged.
pub fn prune(grid: &PlanGrid, points: &[GridPos], diagonal: Diagonal) -> Vec<GridPos> {
    prune_observed(grid, points, diagonal, &mut ())
}

/// As [`prune`], reporting each segment check as a [`SearchEvent::Line`].
pub fn prune_observed<O: SearchObserver + ?Sized>(
    grid: &PlanGrid,
    points: &[GridPos],
    diagonal: Diagonal,
    obs: &mut O,
) -> Vec<GridPos> {
    let mut pts = points.to_vec();
    loop {
        if pts.len() < 3 {
            return pts;
        }
        let mut kept: Vec<GridPos> = Vec::with_capacity(pts.len());
        kept.extend(pts.first());
        let mut removed = false;
        for w in pts.windows(3) {
            // The last point kept before w[1]: w[0] unless w[0] was removed.
            let prev = kept.last().copied().unwrap_or(w[0]);
            let clear = segment_free(grid, prev, w[2], diagonal);
            emit(obs, || SearchEvent::Line {
                from: prev,
                to: w[2],
                clear,
            });
            if clear {
                removed = true;
            } else {
                kept.push(w[1]);
            }
        }
        if let Some(&last) = pts.last() {
            kept.push(last);
        }
        pts = kept;
        if !removed {
            return pts;
        }
    }
}

/// Both steps: [`prune`] applied to the [`turning_points`] of `cells`.
pub fn key_points(grid: &PlanGrid, cells: &[GridPos], diagonal: Diagonal) -> Vec<GridPos> {
    prune(grid, &turning_points(cells), diagonal)
}

/// As [`key_points`], reporting each segment check as a [`SearchEvent::Line`].
pub fn key_points_observed<O: SearchObserver + ?Sized>(
    grid: &PlanGrid,
    cells: &[GridPos],
    diagonal: Diagonal,
    obs: &mut O,
) -> Vec<GridPos> {
    prune_observed(grid, &turning_points(cells), diagonal, obs)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(c: u32, r: u32) -> GridPos {
        GridPos::new(c, r)
    }

    #[test]
    fn direction_reduces_by_gcd() {
        assert_eq!(direction(p(0, 0), p(4, 2)), (2, 1));
        assert_eq!(direction(p(4, 2), p(0, 0)), (-2, -1));
        assert_eq!(direction(p(3, 3), p(3, 3)), (0, 0));
        assert_eq!(direction(p(0, 5), p(0, 0)), (0, -1));
    }

    #[test]
    fn turning_points_handle_tiny_inputs() {
        assert!(turning_points(&[]).is_empty());
        assert_eq!(turning_points(&[p(1, 1)]), vec![p(1, 1)]);
        assert_eq!(turning_points(&[p(1, 1), p(1, 1)]), vec![p(1, 1)]);
        assert_eq!(turning_points(&[p(1, 1), p(2, 1)]), vec![p(1, 1), p(2, 1)]);
    }
}
