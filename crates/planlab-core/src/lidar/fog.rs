//! Fog of war: the map cells the robot's scans have swept so far (free
//! cells a beam crossed and the cell each returning beam hit), computed in
//! the core so the page never casts rays.

use crate::map::OccupancyGrid;
use crate::num::{cos, sin};

/// Seen flags per cell of a grid, row-major with row 0 at the top (the
/// grid's own layout).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SeenCells {
    width: usize,
    height: usize,
    seen: Vec<u8>,
    count: usize,
}

impl SeenCells {
    /// Nothing seen yet on `grid`.
    pub fn new(grid: &OccupancyGrid) -> SeenCells {
        SeenCells {
            width: grid.width(),
            height: grid.height(),
            seen: vec![0; grid.width() * grid.height()],
            count: 0,
        }
    }

    /// 1 per seen cell, 0 otherwise (row-major, row 0 at the top).
    pub fn cells(&self) -> &[u8] {
        &self.seen
    }

    /// Number of seen cells.
    pub fn count(&self) -> usize {
        self.count
    }

    /// Marks what a scan from `pose` (x, y, θ) swept: beam i at θ + 2π·i/n
    /// out to `ranges[i]` (m), plus the hit cell when `returns[i]`.
    /// Non-finite poses or ranges are skipped; a grid of another size
    /// resets the record.
    pub fn update(
        &mut self,
        grid: &OccupancyGrid,
        pose: [f64; 3],
        ranges: &[f64],
        returns: &[bool],
    ) {
        if grid.width() != self.width || grid.height() != self.height {
            *self = SeenCells::new(grid);
        }
        if !pose.iter().all(|v| v.is_finite()) {
            return;
        }
        let n = ranges.len();
        let res = grid.resolution();
        let o = grid.origin();
        let (w, h) = (self.width as i64, self.height as i64);
        let (lx, ly) = ((pose[0] - o.x) / res, (pose[1] - o.y) / res);
        for (i, &d) in ranges.iter().enumerate() {
            if !(d.is_finite() && d >= 0.0) {
                continue;
            }
            let a = pose[2] + std::f64::consts::TAU * i as f64 / n as f64;
            let (dx, dy) = (cos(a), sin(a));
            let hit = returns.get(i).copied().unwrap_or(false);
            // A returning beam ends just inside the cell it hit.
            let reach = if hit { d + 1e-6 } else { d };
            let (width, seen, count) = (self.width, &mut self.seen, &mut self.count);
            crate::map::ray::walk((w, h), res, (lx, ly), (dx, dy), reach, |c, r| {
                let k = r as usize * width + c as usize;
                if seen[k] == 0 {
                    seen[k] = 1;
                    *count += 1;
                }
                true
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::Pose2;

    #[test]
    fn a_beam_marks_the_cells_it_crosses() {
        let g = OccupancyGrid::new(10, 4)
            .unwrap()
            .with_frame(1.0, Pose2::default())
            .unwrap();
        let mut s = SeenCells::new(&g);
        // One beam forward 3.6 m from (0.5, 1.5) ends at x = 4.1: cells
        // 0 … 4 of the row (u = 1) are seen, cell 5 is not.
        s.update(&g, [0.5, 1.5, 0.0], &[3.6], &[true]);
        assert_eq!(s.count(), 5);
        let row = (4 - 1 - 1) * 10;
        assert_eq!(&s.cells()[row..row + 6], &[1, 1, 1, 1, 1, 0]);
        s.update(&g, [f64::NAN, 1.5, 0.0], &[3.6], &[true]);
        assert_eq!(s.count(), 5);
    }
}
