//! Grid cells by column and row, and the cells a straight segment between
//! two cell centres crosses (supercover line): used by the map's painting
//! and by the grid planners' line-of-sight checks.

use serde::{Deserialize, Serialize};

/// A grid cell `(col, row)`, row 0 at the top.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub struct GridPos {
    /// Column (x).
    pub col: u32,
    /// Row (y, downwards).
    pub row: u32,
}

impl GridPos {
    /// `GridPos { col, row }`.
    #[inline]
    pub const fn new(col: u32, row: u32) -> Self {
        Self { col, row }
    }
}

impl From<(u32, u32)> for GridPos {
    fn from((col, row): (u32, u32)) -> Self {
        Self { col, row }
    }
}

/// Walks the cells crossed by the segment between cell centres `a` and `b`.
///
/// Calls `visit(col, row, None)` for each crossed cell and
/// `visit(_, _, Some((c1, r1, c2, r2)))` whenever the segment passes exactly
/// through a corner, naming the two side cells it squeezes between.
pub fn supercover(
    a: GridPos,
    b: GridPos,
    mut visit: impl FnMut(i64, i64, Option<(i64, i64, i64, i64)>),
) {
    supercover_while(a, b, |c, r, corner| {
        visit(c, r, corner);
        true
    });
}

/// As [`supercover`], stopping as soon as `visit` returns `false`; returns
/// whether the walk reached `b`.
pub fn supercover_while(
    a: GridPos,
    b: GridPos,
    mut visit: impl FnMut(i64, i64, Option<(i64, i64, i64, i64)>) -> bool,
) -> bool {
    let (mut x, mut y) = (a.col as i64, a.row as i64);
    let (x1, y1) = (b.col as i64, b.row as i64);
    let (dx, dy) = ((x1 - x).abs(), (y1 - y).abs());
    let (sx, sy) = ((x1 - x).signum(), (y1 - y).signum());
    if !visit(x, y, None) {
        return false;
    }
    // Integer walk in units of half-cells: error = dy·(2i+1) − dx·(2j+1)
    // compares where the line crosses the next vertical vs horizontal edge.
    let (mut ix, mut iy) = (0i64, 0i64);
    while ix < dx || iy < dy {
        let decision = (1 + 2 * ix) * dy - (1 + 2 * iy) * dx;
        if decision == 0 {
            if !visit(0, 0, Some((x + sx, y, x, y + sy))) {
                return false;
            }
            x += sx;
            y += sy;
            ix += 1;
            iy += 1;
        } else if decision < 0 {
            x += sx;
            ix += 1;
        } else {
            y += sy;
            iy += 1;
        }
        if !visit(x, y, None) {
            return false;
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cells_of(a: GridPos, b: GridPos) -> Vec<(i64, i64)> {
        let mut v = Vec::new();
        supercover(a, b, |c, r, corner| {
            if corner.is_none() {
                v.push((c, r))
            }
        });
        v
    }

    #[test]
    fn supercover_straight_diagonal_and_shallow() {
        assert_eq!(
            cells_of(GridPos::new(0, 0), GridPos::new(3, 0)),
            vec![(0, 0), (1, 0), (2, 0), (3, 0)]
        );
        assert_eq!(
            cells_of(GridPos::new(0, 0), GridPos::new(2, 2)),
            vec![(0, 0), (1, 1), (2, 2)]
        );
        // A 2:1 slope from (0,0) to (2,1) crosses (1,0) and (1,1) exactly at
        // their shared edge midpoint... it passes through the corner-free
        // points (0.5,0.25) and (1.5,0.75): cells (0,0),(1,0),(1,1),(2,1).
        assert_eq!(
            cells_of(GridPos::new(0, 0), GridPos::new(2, 1)),
            vec![(0, 0), (1, 0), (1, 1), (2, 1)]
        );
        assert_eq!(
            cells_of(GridPos::new(2, 1), GridPos::new(0, 0)),
            vec![(2, 1), (1, 1), (1, 0), (0, 0)]
        );
    }
}
