//! Weighted cells on a [`PlanGrid`] (docs/algorithms.md §weights).
//!
//! The move-cost model is PathFinding.js's: a move costs its length (1, √2,
//! or a longer segment's Euclidean length) times the traversal weight of
//! the cell it enters; a segment crossing several cells pays the largest
//! weight among the cells it enters. Every weight is ≥ 1, so every move
//! still costs at least its length and the octile and Euclidean estimates
//! stay admissible and consistent; on a unit-cost grid every cost is
//! exactly what it was before weights existed.

use super::{GridPos, PlanGrid};
use crate::map::{supercover, OccupancyGrid};

impl PlanGrid {
    /// Copies the traversal weights of `grid` (same size), if it has any
    /// above 1.
    pub(crate) fn take_weights_of(&mut self, grid: &OccupancyGrid) {
        self.weights = None;
        let Some(w) = grid.weights().filter(|_| grid.is_weighted()) else {
            return;
        };
        let mut padded = vec![1u8; self.padded().len()];
        for r in 0..self.height() {
            let src = &w[r * self.width()..(r + 1) * self.width()];
            let at = (r + 1) * self.stride() + 1;
            padded[at..at + self.width()].copy_from_slice(src);
        }
        self.weights = Some(padded);
    }

    /// This grid with the traversal weights of `grid` (the map it was
    /// built from, e.g. before inflation).
    pub fn with_weights_of(mut self, grid: &OccupancyGrid) -> Self {
        if grid.width() == self.width() && grid.height() == self.height() {
            self.take_weights_of(grid);
        }
        self
    }

    /// Whether some cell weighs more than 1.
    #[inline]
    pub fn is_weighted(&self) -> bool {
        self.weights.is_some()
    }

    /// Padded weight table (index as [`PlanGrid::padded`]), `None` on a
    /// unit-cost grid.
    #[inline]
    pub(crate) fn padded_weights(&self) -> Option<&[u8]> {
        self.weights.as_deref()
    }

    /// Traversal weight of `(col, row)`: 1 on a unit-cost grid or off the
    /// map.
    #[inline]
    pub fn weight(&self, col: i64, row: i64) -> u32 {
        match &self.weights {
            Some(w) if col >= 0 && row >= 0 => {
                let (c, r) = (col as usize, row as usize);
                if c < self.width() && r < self.height() {
                    u32::from(w[(r + 1) * self.stride() + c + 1])
                } else {
                    1
                }
            }
            _ => 1,
        }
    }

    /// Sets the traversal weight of an on-map cell (1..=9, clamped); a
    /// unit-cost grid gets its table on the first weight above 1.
    pub fn set_weight(&mut self, col: usize, row: usize, w: u8) {
        if col >= self.width() || row >= self.height() {
            return;
        }
        let w = w.clamp(1, crate::map::MAX_WEIGHT);
        if w == 1 && self.weights.is_none() {
            return;
        }
        let (n, i) = (self.padded().len(), (row + 1) * self.stride() + col + 1);
        let table = self.weights.get_or_insert_with(|| vec![1; n]);
        let old = std::mem::replace(&mut table[i], w);
        // The last weight erased: a unit-cost grid again (JPS may run).
        if w == 1 && old > 1 && table.iter().all(|&v| v == 1) {
            self.weights = None;
        }
    }

    /// Sum of the padded cells' weights: bounds the fixed-point cost of any
    /// simple path (see `search::check_size`).
    pub(crate) fn weight_total(&self) -> u64 {
        match &self.weights {
            Some(w) => w.iter().map(|&v| u64::from(v)).sum(),
            None => self.padded().len() as u64,
        }
    }

    /// Cost of the straight move from the centre of `a` to that of `b`: its
    /// Euclidean length times the largest weight among the cells it enters
    /// (the cells its supercover line crosses, `a` and corner touches
    /// excluded). For a move to a neighbour that is the weight of `b`.
    pub fn segment_cost(&self, a: GridPos, b: GridPos) -> f64 {
        let len = centre_distance(a, b);
        if self.weights.is_none() {
            return len;
        }
        let mut w = 1;
        supercover(a, b, |c, r, corner| {
            if corner.is_none() && (c, r) != (i64::from(a.col), i64::from(a.row)) {
                w = w.max(self.weight(c, r));
            }
        });
        len * f64::from(w)
    }

    /// Cost of a path through `cells` under the weights: the sum of
    /// [`PlanGrid::segment_cost`] over its moves; on a unit-cost grid its
    /// Euclidean length.
    pub fn path_cost(&self, cells: &[GridPos]) -> f64 {
        if self.weights.is_none() {
            return super::Path::polyline_length(cells);
        }
        cells
            .windows(2)
            .map(|w| self.segment_cost(w[0], w[1]))
            .sum()
    }
}

/// Euclidean distance between two cell centres, in cells.
#[inline]
fn centre_distance(a: GridPos, b: GridPos) -> f64 {
    super::Path::polyline_length(&[a, b])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_move_costs_its_length_times_the_weight_it_enters() {
        let map = OccupancyGrid::from_ascii("1.3\n.9.\n").unwrap();
        let g = PlanGrid::new(&map, false);
        assert!(g.is_weighted());
        let p = |c, r| GridPos::new(c, r);
        assert_eq!(g.segment_cost(p(0, 0), p(1, 0)), 1.0);
        assert_eq!(g.segment_cost(p(1, 0), p(2, 0)), 3.0);
        assert_eq!(g.segment_cost(p(2, 0), p(1, 0)), 1.0);
        assert!((g.segment_cost(p(0, 0), p(1, 1)) - 9.0 * 2f64.sqrt()).abs() < 1e-12);
        // A longer segment pays the heaviest cell it enters.
        assert_eq!(g.segment_cost(p(0, 0), p(2, 0)), 6.0);
        assert_eq!(g.path_cost(&[p(0, 0), p(1, 0), p(2, 0)]), 4.0);
        // A unit map: plain lengths.
        let unit = PlanGrid::new(&OccupancyGrid::from_ascii("...\n").unwrap(), false);
        assert!(!unit.is_weighted());
        assert_eq!(unit.segment_cost(p(0, 0), p(2, 0)), 2.0);
    }
}
