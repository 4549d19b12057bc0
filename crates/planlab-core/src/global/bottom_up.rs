//! Bottom-Up segmentation of a grid path, Ge & Li (2022) §4.1 (docs/algorithms.md §bottom-up,
//! paper key \[S\]), after Keogh et al.'s time-series Bottom-Up algorithm.
//!
//! Start from the finest piecewise-linear segmentation (every consecutive
//! pair of path cells is a segment) and repeatedly merge the adjacent pair of
//! segments whose merged segment has the lowest error, while that error is
//! below `max_error` and the merged segment is collision-free. The surviving
//! segment end points are the *feature nodes* used as temporary goals
//! (\[S\] Fig 6: 80 → 7 nodes).
//!
//! Decisions:
//! - **Error** of a segment `(p_i, p_k)` = the largest Euclidean distance, in
//!   cells, from an original point `p_j` (i < j < k) to the closed segment
//!   `p_i p_k` (not the infinite line, so a path that doubles back is not
//!   mistaken for a straight one).
//! - **Threshold**: a merge is taken when `error < max_error`, or when
//!   `error == 0` (an exactly collinear merge loses nothing). Hence
//!   `max_error = 0` keeps exactly the turning points.
//! - **Collisions**: a merge whose segment fails
//!   [`PlanGrid::segment_is_free`] is skipped, not a stopping point; it is
//!   reconsidered if a neighbouring merge later changes its end points.
//! - Cost: a binary heap with lazy invalidation; each merge recomputes two
//!   errors in time linear in their segment's length, so the worst case is
//!   O(n²) and typical paths run in O(n log n).

use super::events::emit;
use super::keypoints::segment_free;
use super::{Diagonal, GridPos, PlanError, PlanGrid, SearchEvent, SearchObserver};
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// Distance in cells from `p` to the closed segment `a b`; exact 0 for points
/// on the segment (integer arithmetic decides the projection).
fn point_segment_distance(p: GridPos, a: GridPos, b: GridPos) -> f64 {
    // i128 so that any u32 coordinates square and multiply without overflow.
    let (ax, ay) = (i128::from(a.col), i128::from(a.row));
    let (abx, aby) = (i128::from(b.col) - ax, i128::from(b.row) - ay);
    let (apx, apy) = (i128::from(p.col) - ax, i128::from(p.row) - ay);
    let len2 = abx * abx + aby * aby;
    let dot = apx * abx + apy * aby;
    let hyp = |x: i128, y: i128| ((x * x + y * y) as f64).sqrt();
    if len2 == 0 || dot <= 0 {
        hyp(apx, apy)
    } else if dot >= len2 {
        hyp(
            i128::from(p.col) - i128::from(b.col),
            i128::from(p.row) - i128::from(b.row),
        )
    } else {
        let cross = abx * apy - aby * apx;
        (cross.abs() as f64) / (len2 as f64).sqrt()
    }
}

/// Error of replacing `cells[i..=k]` by the segment `cells[i] cells[k]`: the
/// largest distance of an interior point to it (0 with no interior point).
/// Out-of-range indices give 0 (callers pass valid ones).
fn segment_error(cells: &[GridPos], i: usize, k: usize) -> f64 {
    let (Some(&a), Some(&b)) = (cells.get(i), cells.get(k)) else {
        return 0.0;
    };
    cells
        .get(i + 1..k)
        .unwrap_or(&[])
        .iter()
        .map(|&p| point_segment_distance(p, a, b))
        .fold(0.0, f64::max)
}

/// Heap entry: merge that removes boundary `idx`, valid while `version`
/// matches. Smallest cost first, then lowest index (deterministic order).
#[derive(Clone, Copy, Debug)]
struct Candidate {
    cost: f64,
    idx: usize,
    version: u32,
}

impl PartialEq for Candidate {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}
impl Eq for Candidate {}
impl PartialOrd for Candidate {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Candidate {
    fn cmp(&self, other: &Self) -> Ordering {
        // Reversed for BinaryHeap's max-heap.
        other
            .cost
            .total_cmp(&self.cost)
            .then_with(|| other.idx.cmp(&self.idx))
            .then_with(|| other.version.cmp(&self.version))
    }
}

/// Feature nodes of the path `cells` by Bottom-Up segmentation (module doc).
///
/// `max_error` is in cells. The result is a subsequence of `cells` that keeps
/// the first and last cell; each of its segments deviates from the original
/// points it replaces by less than `max_error` (or not at all) and, where it
/// replaces more than one original step, passes
/// `grid.segment_is_free(_, _, diagonal)`. Original single steps are kept as
/// given, unchecked. An empty `cells` gives an empty result; one or two cells
/// are returned unchanged.
///
/// # Errors
/// [`PlanError::InvalidConfig`] when `max_error` is negative or not finite.
pub fn bottom_up(
    grid: &PlanGrid,
    cells: &[GridPos],
    max_error: f64,
    diagonal: Diagonal,
) -> Result<Vec<GridPos>, PlanError> {
    bottom_up_observed(grid, cells, max_error, diagonal, &mut ())
}

/// As [`bottom_up`], reporting each segment check as a [`SearchEvent::Line`].
///
/// # Errors
/// As [`bottom_up`].
pub fn bottom_up_observed<O: SearchObserver + ?Sized>(
    grid: &PlanGrid,
    cells: &[GridPos],
    max_error: f64,
    diagonal: Diagonal,
    obs: &mut O,
) -> Result<Vec<GridPos>, PlanError> {
    if !(max_error.is_finite() && max_error >= 0.0) {
        return Err(PlanError::InvalidConfig(format!(
            "Bottom-Up max_error {max_error} must be a finite number ≥ 0 (cells)"
        )));
    }
    let n = cells.len();
    if n <= 2 {
        return Ok(cells.to_vec());
    }
    let accept = |cost: f64| cost < max_error || cost == 0.0;
    // Doubly linked list of surviving boundaries (indices into `cells`).
    let mut prev: Vec<usize> = (0..n).map(|i| i.saturating_sub(1)).collect();
    let mut next: Vec<usize> = (0..n).map(|i| (i + 1).min(n - 1)).collect();
    let mut alive = vec![true; n];
    let mut version = vec![0u32; n];
    let mut heap: BinaryHeap<Candidate> = (1..n - 1)
        .map(|i| Candidate {
            cost: segment_error(cells, i - 1, i + 1),
            idx: i,
            version: 0,
        })
        .collect();
    while let Some(Candidate {
        cost,
        idx,
        version: v,
    }) = heap.pop()
    {
        if !alive[idx] || version[idx] != v {
            continue; // stale
        }
        if !accept(cost) {
            break; // every live candidate costs at least this much
        }
        let (a, b) = (prev[idx], next[idx]);
        let clear = segment_free(grid, cells[a], cells[b], diagonal);
        emit(obs, || SearchEvent::Line {
            from: cells[a],
            to: cells[b],
            clear,
        });
        if !clear {
            continue; // re-queued only if a neighbour's merge changes a or b
        }
        alive[idx] = false;
        next[a] = b;
        prev[b] = a;
        for j in [a, b] {
            if j == 0 || j == n - 1 {
                continue; // start and goal always stay
            }
            version[j] = version[j].wrapping_add(1);
            heap.push(Candidate {
                cost: segment_error(cells, prev[j], next[j]),
                idx: j,
                version: version[j],
            });
        }
    }
    Ok(cells
        .iter()
        .zip(&alive)
        .filter_map(|(&p, &keep)| keep.then_some(p))
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(c: u32, r: u32) -> GridPos {
        GridPos::new(c, r)
    }

    #[test]
    fn distance_to_segment() {
        let (a, b) = (p(0, 0), p(4, 0));
        assert_eq!(point_segment_distance(p(2, 0), a, b), 0.0);
        assert_eq!(point_segment_distance(p(2, 3), a, b), 3.0);
        // Beyond the end: distance to the end point, not to the line.
        assert_eq!(point_segment_distance(p(7, 4), a, b), 5.0);
        assert_eq!(point_segment_distance(p(3, 4), a, a), 5.0);
        let d = point_segment_distance(p(1, 0), p(0, 0), p(2, 2));
        assert!((d - std::f64::consts::FRAC_1_SQRT_2).abs() < 1e-12);
        // Extreme coordinates do not overflow.
        let far = point_segment_distance(p(u32::MAX, 0), p(0, u32::MAX), p(0, 0));
        assert_eq!(far, f64::from(u32::MAX));
    }

    #[test]
    fn error_ignores_bad_indices() {
        let c = [p(0, 0), p(1, 1), p(2, 0)];
        assert_eq!(segment_error(&c, 0, 9), 0.0);
        assert_eq!(segment_error(&c, 2, 0), 0.0);
        assert_eq!(segment_error(&c, 0, 2), 1.0);
    }
}
