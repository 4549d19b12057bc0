//! Collision checking of a disc robot moving continuously on an occupancy
//! grid (docs/algorithms.md §sampling, the collision model).
//!
//! Coordinates are in cells: x grows with the column, y with the row (down
//! the image), and cell `(c, r)` is the closed square `[c, c+1] × [r, r+1]`.
//! A point is free when its Euclidean distance to every blocked cell's
//! square and to the map's edge is at least the radius. A radius of 0 is a
//! point robot, which must not touch a blocked square at all (the test runs
//! with a radius of 1e-9 then).

use crate::map::costmap::squared_cell_distances;
use crate::map::{Cell, MapError, OccupancyGrid};

/// Half the diagonal of a cell: every point of a square is this close to
/// its centre.
const HALF_DIAGONAL: f64 = std::f64::consts::FRAC_1_SQRT_2;

/// The smallest radius the tests use (see the module docs).
const MIN_RADIUS: f64 = 1e-9;

/// A point in cell coordinates (x = column direction, y = row direction).
pub type Point = [f64; 2];

/// The free space of a disc robot of one radius on one grid: the grid's
/// blocked cells and their exact distance field, built once and shared by
/// every planner on that (map, radius).
#[derive(Debug, Clone)]
pub struct DiscSpace {
    width: usize,
    height: usize,
    radius: f64,
    /// The radius the tests compare against (at least [`MIN_RADIUS`]).
    test_radius: f64,
    blocked: Vec<bool>,
    /// Distance from each cell centre to the nearest blocked cell centre,
    /// cells (exact Euclidean distance transform, `map::costmap`).
    centre_distance: Vec<f64>,
    free_cells: usize,
}

/// Why a [`DiscSpace`] cannot be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SpaceError {
    /// The radius is NaN, infinite, negative or wider than the map.
    #[error("radius {0}: must be a finite number of cells ≥ 0 and less than half the map's smaller side")]
    BadRadius(f64),
    /// The grid could not be copied.
    #[error(transparent)]
    Map(#[from] MapError),
}

impl DiscSpace {
    /// The free space of a disc of `radius` cells on `grid`; unknown cells
    /// are blocked unless `allow_unknown`.
    pub fn new(grid: &OccupancyGrid, radius: f64, allow_unknown: bool) -> Result<Self, SpaceError> {
        let (width, height) = (grid.width(), grid.height());
        if !radius.is_finite() || radius < 0.0 || 2.0 * radius >= width.min(height) as f64 {
            return Err(SpaceError::BadRadius(radius));
        }
        let blocked: Vec<bool> = grid
            .cells()
            .iter()
            .map(|c| !c.passable(allow_unknown))
            .collect();
        let solid = OccupancyGrid::from_cells(
            width,
            height,
            blocked
                .iter()
                .map(|&b| if b { Cell::Occupied } else { Cell::Free })
                .collect(),
        )?;
        let centre_distance = squared_cell_distances(&solid)
            .into_iter()
            .map(f64::sqrt)
            .collect();
        let free_cells = blocked.iter().filter(|b| !**b).count();
        Ok(Self {
            width,
            height,
            radius,
            test_radius: radius.max(MIN_RADIUS),
            blocked,
            centre_distance,
            free_cells,
        })
    }

    /// Width in cells.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Height in cells.
    pub fn height(&self) -> usize {
        self.height
    }

    /// The robot's radius, cells.
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// The number of unblocked cells: the free area the planners' radii
    /// (RRT*, BIT*) are computed from, in cells².
    pub fn free_area(&self) -> f64 {
        self.free_cells as f64
    }

    /// Whether cell `(col, row)` is blocked; outside the map counts as blocked.
    pub fn is_blocked(&self, col: i64, row: i64) -> bool {
        if col < 0 || row < 0 || col >= self.width as i64 || row >= self.height as i64 {
            return true;
        }
        self.blocked[row as usize * self.width + col as usize]
    }

    /// The box the disc's centre may occupy: `[lo, hi]` per axis.
    pub fn bounds(&self) -> (Point, Point) {
        let r = self.test_radius;
        ([r, r], [self.width as f64 - r, self.height as f64 - r])
    }

    fn inside(&self, p: Point) -> bool {
        let (lo, hi) = self.bounds();
        p[0] >= lo[0] && p[0] <= hi[0] && p[1] >= lo[1] && p[1] <= hi[1]
    }

    /// A lower bound on the clearance of `p` (inside the map) from the
    /// distance field: every blocked square is at least its centre's
    /// distance less half a diagonal away, and the centre is at least the
    /// field at `p`'s cell less `p`'s offset from that cell's centre.
    fn clearance_bound(&self, p: Point) -> f64 {
        let col = (p[0].floor() as i64).clamp(0, self.width as i64 - 1);
        let row = (p[1].floor() as i64).clamp(0, self.height as i64 - 1);
        let d = self.centre_distance[row as usize * self.width + col as usize];
        let off = (p[0] - (col as f64 + 0.5)).hypot(p[1] - (row as f64 + 0.5));
        let edge = p[0]
            .min(p[1])
            .min(self.width as f64 - p[0])
            .min(self.height as f64 - p[1]);
        (d - off - HALF_DIAGONAL).min(edge)
    }

    /// Exact clearance of `p` (inside the map) to the blocked squares, or
    /// `cap` when none is closer than `cap` (the map edge excluded).
    fn clearance_exact(&self, p: Point, cap: f64) -> f64 {
        let mut best = cap;
        for row in (p[1] - cap).floor() as i64..=(p[1] + cap).floor() as i64 {
            for col in (p[0] - cap).floor() as i64..=(p[0] + cap).floor() as i64 {
                if self.is_blocked(col, row) {
                    best = best.min(point_square_distance(p, col, row));
                }
            }
        }
        best
    }

    /// Clearance of `p`: its distance to the nearest blocked square or the
    /// map's edge (0 outside the map), exact up to `cap`, and `cap` beyond.
    pub fn clearance(&self, p: Point, cap: f64) -> f64 {
        if !(p[0] >= 0.0 && p[1] >= 0.0 && p[0] <= self.width as f64 && p[1] <= self.height as f64)
        {
            return 0.0;
        }
        let edge = p[0]
            .min(p[1])
            .min(self.width as f64 - p[0])
            .min(self.height as f64 - p[1]);
        if self.clearance_bound(p) >= cap {
            return cap.min(edge);
        }
        self.clearance_exact(p, cap).min(edge)
    }

    /// Whether the disc centred at `p` is free.
    pub fn point_free(&self, p: Point) -> bool {
        if !self.inside(p) {
            return false;
        }
        let r = self.test_radius;
        self.clearance_bound(p) >= r || self.clearance_exact(p, r) >= r
    }

    /// Whether the disc moving along the segment `a → b` stays free: both
    /// ends free (the box of allowed centres is convex), then sphere
    /// tracing on the distance field's lower bound, which is exact to
    /// trust: far from obstacles it jumps by the bound less the radius;
    /// where the bound comes within half a cell of the radius, the next
    /// cell-long piece is tested exactly against the blocked squares near it.
    pub fn segment_free(&self, a: Point, b: Point) -> bool {
        if !self.point_free(a) || !self.point_free(b) {
            return false;
        }
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let len = dx.hypot(dy);
        if len == 0.0 {
            return true;
        }
        let (ux, uy) = (dx / len, dy / len);
        let r = self.test_radius;
        let mut t = 0.0;
        while t < len {
            let p = [a[0] + ux * t, a[1] + uy * t];
            let jump = self.clearance_bound(p) - r;
            if jump >= 0.5 {
                t += jump;
                continue;
            }
            let t1 = (t + 1.0).min(len);
            let q = [a[0] + ux * t1, a[1] + uy * t1];
            if !self.piece_free(p, q) {
                return false;
            }
            t = t1;
        }
        true
    }

    /// The farthest point of the segment `a → b` (`a` free) that the disc
    /// is known to reach from `a` without collision: `b` when the whole
    /// segment is free, else a point before the first collision, found by
    /// the same sphere tracing as [`DiscSpace::segment_free`] refined to
    /// pieces of an eighth of a cell. `a` itself when nothing beyond it is
    /// known free (or `a` is not free).
    pub fn free_prefix(&self, a: Point, b: Point) -> Point {
        if !self.point_free(a) {
            return a;
        }
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let len = dx.hypot(dy);
        if len == 0.0 {
            return a;
        }
        let (ux, uy) = (dx / len, dy / len);
        let at = |t: f64| {
            if t >= len {
                b
            } else {
                [a[0] + ux * t, a[1] + uy * t]
            }
        };
        let r = self.test_radius;
        let mut t = 0.0;
        while t < len {
            let p = at(t);
            let jump = self.clearance_bound(p) - r;
            if jump >= 0.5 {
                let t1 = (t + jump).min(len);
                if !self.point_free(at(t1)) {
                    // Only the map's edge (outside the box of centres) can
                    // stop a jump; refine with pieces.
                } else {
                    t = t1;
                    continue;
                }
            }
            let t1 = (t + 0.125).min(len);
            let q = at(t1);
            if !self.point_free(q) || !self.piece_free(p, q) {
                return p;
            }
            t = t1;
        }
        b
    }

    /// Exact test of a short piece against every blocked square within the
    /// radius of its bounding box.
    fn piece_free(&self, p: Point, q: Point) -> bool {
        let r = self.test_radius;
        let (x0, x1) = (p[0].min(q[0]) - r, p[0].max(q[0]) + r);
        let (y0, y1) = (p[1].min(q[1]) - r, p[1].max(q[1]) + r);
        for row in y0.floor() as i64..=y1.floor() as i64 {
            for col in x0.floor() as i64..=x1.floor() as i64 {
                if col < 0 || row < 0 || col >= self.width as i64 || row >= self.height as i64 {
                    // The edge is the ends' business (convex box).
                    continue;
                }
                if self.blocked[row as usize * self.width + col as usize]
                    && segment_square_distance(p, q, col, row) < r
                {
                    return false;
                }
            }
        }
        true
    }
}

/// Distance from `p` to the closed square of cell `(col, row)`.
pub fn point_square_distance(p: Point, col: i64, row: i64) -> f64 {
    let (c, r) = (col as f64, row as f64);
    let dx = (c - p[0]).max(0.0).max(p[0] - (c + 1.0));
    let dy = (r - p[1]).max(0.0).max(p[1] - (r + 1.0));
    dx.hypot(dy)
}

/// Distance from the segment `a → b` to the closed square of `(col, row)`:
/// 0 when they meet (slab test), else the least of the ends' distances to
/// the square and the square's corners' distances to the segment.
pub fn segment_square_distance(a: Point, b: Point, col: i64, row: i64) -> f64 {
    let lo = [col as f64, row as f64];
    let hi = [lo[0] + 1.0, lo[1] + 1.0];
    let d = [b[0] - a[0], b[1] - a[1]];
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    let mut meets = true;
    for k in 0..2 {
        if d[k] == 0.0 {
            if a[k] < lo[k] || a[k] > hi[k] {
                meets = false;
                break;
            }
        } else {
            let (mut ta, mut tb) = ((lo[k] - a[k]) / d[k], (hi[k] - a[k]) / d[k]);
            if ta > tb {
                std::mem::swap(&mut ta, &mut tb);
            }
            t0 = t0.max(ta);
            t1 = t1.min(tb);
            if t0 > t1 {
                meets = false;
                break;
            }
        }
    }
    if meets {
        return 0.0;
    }
    let mut best = point_square_distance(a, col, row).min(point_square_distance(b, col, row));
    for corner in [lo, [hi[0], lo[1]], [lo[0], hi[1]], hi] {
        best = best.min(point_segment_distance(corner, a, b));
    }
    best
}

/// Distance from `p` to the segment `a → b`.
pub fn point_segment_distance(p: Point, a: Point, b: Point) -> f64 {
    let d = [b[0] - a[0], b[1] - a[1]];
    let len2 = d[0] * d[0] + d[1] * d[1];
    let t = if len2 == 0.0 {
        0.0
    } else {
        (((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / len2).clamp(0.0, 1.0)
    };
    (a[0] + t * d[0] - p[0]).hypot(a[1] + t * d[1] - p[1])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn space(text: &str, r: f64) -> DiscSpace {
        DiscSpace::new(&OccupancyGrid::from_ascii(text).unwrap(), r, false).unwrap()
    }

    #[test]
    fn segment_square_distance_matches_dense_sampling() {
        let cases = [
            ([0.2, 0.3], [3.7, 2.9]),
            ([-1.0, 0.5], [-0.2, 3.0]),
            ([2.5, -0.5], [2.5, -0.1]),
            ([-0.5, -0.5], [-0.5, -0.5]),
        ];
        for (a, b) in cases {
            let mut dense = f64::INFINITY;
            for i in 0..=20_000 {
                let t = i as f64 / 20_000.0;
                let p = [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])];
                dense = dense.min(point_square_distance(p, 1, 1));
            }
            let exact = segment_square_distance(a, b, 1, 1);
            assert!(
                (exact - dense).abs() < 1e-3,
                "{a:?}→{b:?}: {exact} vs {dense}"
            );
        }
    }

    #[test]
    fn a_disc_passes_a_gap_only_when_it_fits() {
        // A one-cell gap in a wall across row 2.
        let map = ".....\n.....\n##.##\n.....\n.....\n";
        let thin = space(map, 0.45);
        assert!(thin.segment_free([2.5, 0.5], [2.5, 4.5]));
        let fat = space(map, 0.55);
        assert!(!fat.segment_free([2.5, 0.6], [2.5, 4.4]));
        // Diagonal through the gap's corner: blocked even for a point.
        let point = space(map, 0.0);
        assert!(!point.segment_free([0.5, 0.5], [4.5, 4.5]));
        assert!(point.segment_free([2.5, 0.5], [2.5, 4.5]));
    }

    #[test]
    fn clearance_is_exact_near_walls_and_at_the_edge() {
        let s = space("....\n....\n..#.\n....\n", 0.3);
        assert!((s.clearance([0.5, 0.5], 5.0) - 0.5).abs() < 1e-12);
        let d = s.clearance([1.5, 1.5], 5.0);
        assert!((d - 0.5f64.hypot(0.5)).abs() < 1e-12, "{d}");
        assert!(s.point_free([1.5, 1.5]));
        assert!(
            !s.point_free([0.2, 1.5]),
            "the edge is closer than the radius"
        );
        assert!(!s.point_free([2.5, 2.5]), "inside a wall");
    }

    #[test]
    fn bad_radii_are_refused() {
        let g = OccupancyGrid::from_ascii("....\n....\n").unwrap();
        for r in [f64::NAN, -0.1, f64::INFINITY, 1.0, 5.0] {
            assert!(matches!(
                DiscSpace::new(&g, r, false),
                Err(SpaceError::BadRadius(_))
            ));
        }
        assert!(DiscSpace::new(&g, 0.9, false).is_ok());
    }
}
