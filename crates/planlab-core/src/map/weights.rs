//! Traversal weights of cells (docs/algorithms.md §weights): a free cell
//! may cost more to cross than 1, as PathFinding.js's weighted nodes and a
//! ROS `mode: scale` map's grey band. A grid without weights is a unit-cost
//! grid, and every weight 1 is the same as none.

use super::{Cell, MapError, OccupancyGrid};
use crate::map::GridPos;

/// The largest traversal weight a cell may carry. One digit: the grid
/// page's cost brush paints 2–9 and prints the weight in the cell, ASCII
/// maps write it as that digit, and a ROS scale map's grey band spreads
/// over 1–9.
pub const MAX_WEIGHT: u8 = 9;

/// Checks a weight: 1..=[`MAX_WEIGHT`].
fn check_weight(w: u8) -> Result<(), MapError> {
    if (1..=MAX_WEIGHT).contains(&w) {
        Ok(())
    } else {
        Err(MapError::InvalidParameter(format!(
            "cell weight {w} must be a whole number from 1 (free) to {MAX_WEIGHT}"
        )))
    }
}

impl OccupancyGrid {
    /// This grid with traversal weights (row-major, one per cell, each
    /// 1..=[`MAX_WEIGHT`]). All ones is a unit-cost grid: stored as none.
    pub fn with_weights(mut self, weights: Vec<u8>) -> Result<Self, MapError> {
        if weights.len() != self.cells.len() {
            return Err(MapError::SizeMismatch {
                width: self.width as u64,
                height: self.height as u64,
                expected: self.cells.len() as u64,
                got: weights.len() as u64,
            });
        }
        if let Some(&bad) = weights.iter().find(|&&w| check_weight(w).is_err()) {
            check_weight(bad)?;
        }
        self.weights = weights.iter().any(|&w| w > 1).then_some(weights);
        Ok(self)
    }

    /// The weights, row-major, or `None` on a unit-cost grid.
    #[inline]
    pub fn weights(&self) -> Option<&[u8]> {
        self.weights.as_deref()
    }

    /// Whether some cell weighs more than 1.
    pub fn is_weighted(&self) -> bool {
        self.weights
            .as_ref()
            .is_some_and(|w| w.iter().any(|&v| v > 1))
    }

    /// The weight of `(col, row)`: 1 on a unit-cost grid or off the map.
    #[inline]
    pub fn weight(&self, col: usize, row: usize) -> u8 {
        match &self.weights {
            Some(w) if col < self.width && row < self.height => w[row * self.width + col],
            _ => 1,
        }
    }

    /// Makes `(col, row)` a free cell of weight `w` (a wall painted over
    /// with a weight becomes free ground of that weight).
    pub fn set_weight(&mut self, col: usize, row: usize, w: u8) -> Result<(), MapError> {
        check_weight(w)?;
        self.set(col, row, Cell::Free)?;
        self.put_weight(row * self.width + col, w);
        Ok(())
    }

    /// Stores weight `w` at index `i` (allocating the table on the first
    /// weight above 1).
    fn put_weight(&mut self, i: usize, w: u8) {
        if w == 1 && self.weights.is_none() {
            return;
        }
        let n = self.cells.len();
        self.weights.get_or_insert_with(|| vec![1; n])[i] = w;
    }

    /// Paints every cell the segment between the centres of two cells
    /// crosses (as [`OccupancyGrid::paint_segment`]) free with weight `w`:
    /// the cost brush. Returns how many cells changed.
    pub fn paint_weight_segment(
        &mut self,
        (col0, row0): (usize, usize),
        (col1, row1): (usize, usize),
        w: u8,
    ) -> Result<usize, MapError> {
        check_weight(w)?;
        for (col, row) in [(col0, row0), (col1, row1)] {
            if col >= self.width || row >= self.height {
                return Err(MapError::OutOfBounds {
                    col: col as i64,
                    row: row as i64,
                    width: self.width,
                    height: self.height,
                });
            }
        }
        let mut changed = 0;
        let (a, b) = (
            GridPos::new(col0 as u32, row0 as u32),
            GridPos::new(col1 as u32, row1 as u32),
        );
        let mut touched = Vec::new();
        super::supercover(a, b, |c, r, corner| {
            if corner.is_none() {
                touched.push(r as usize * self.width + c as usize);
            }
        });
        for i in touched {
            if self.cells[i] != Cell::Free || self.weight_at(i) != w {
                self.cells[i] = Cell::Free;
                self.put_weight(i, w);
                changed += 1;
            }
        }
        Ok(changed)
    }

    #[inline]
    fn weight_at(&self, i: usize) -> u8 {
        self.weights.as_ref().map_or(1, |w| w[i])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ascii_digits_are_weighted_free_cells_and_round_trip() {
        let g = OccupancyGrid::from_ascii(".3#\n9.1\n").unwrap();
        assert!(g.is_weighted());
        assert_eq!(g.get(1, 0), Some(Cell::Free));
        assert_eq!((g.weight(1, 0), g.weight(0, 1), g.weight(2, 1)), (3, 9, 1));
        assert_eq!(g.to_ascii(), ".3#\n9..\n");
        // All ones is a unit map, equal (and hashing equal) to one without.
        let ones = OccupancyGrid::from_ascii("11\n").unwrap();
        assert!(!ones.is_weighted());
        assert_eq!(ones, OccupancyGrid::from_ascii("..\n").unwrap());
    }

    #[test]
    fn the_cost_brush_paints_weights_and_walls_clear_them() {
        let mut g = OccupancyGrid::from_ascii("....#\n").unwrap();
        let before = g.content_hash();
        assert_eq!(g.paint_weight_segment((0, 0), (4, 0), 5), Ok(5));
        assert_eq!(g.to_ascii(), "55555\n");
        assert_ne!(g.content_hash(), before);
        assert_eq!(g.paint_weight_segment((0, 0), (4, 0), 5), Ok(0));
        // Erasing (painting free) puts the weight back to 1.
        assert_eq!(g.paint_segment((0, 0), (1, 0), Cell::Free), Ok(2));
        assert_eq!(g.to_ascii(), "..555\n");
        g.set(2, 0, Cell::Occupied).unwrap();
        g.set(2, 0, Cell::Free).unwrap();
        assert_eq!(g.weight(2, 0), 1);
        assert!(matches!(
            g.paint_weight_segment((0, 0), (1, 0), 10),
            Err(MapError::InvalidParameter(_))
        ));
        assert!(matches!(
            g.set_weight(0, 0, 0),
            Err(MapError::InvalidParameter(_))
        ));
    }
}
