//! A disc footprint against an occupancy grid, in the map's own frame
//! (x right along the columns, y up along the rows, metres from the map's
//! origin corner): exact, with a distance field to skip the exact test
//! where the answer is clear.

use crate::map::costmap::distance_field;
use crate::map::{Cell, OccupancyGrid};
use std::f64::consts::SQRT_2;

/// Which cells block a disc of a given radius, and a fast test.
#[derive(Debug, Clone)]
pub struct DiscChecker {
    width: usize,
    height: usize,
    res: f64,
    radius: f64,
    /// Row-major, row 0 at the top (as [`OccupancyGrid::cells`]).
    blocked: Vec<bool>,
    /// Metres from each cell centre to the nearest blocked cell centre.
    dist: Vec<f64>,
}

impl DiscChecker {
    /// A checker for a disc of `radius` m on `grid`; unknown cells block
    /// unless `allow_unknown`. The map's edge blocks too.
    pub fn new(grid: &OccupancyGrid, radius: f64, allow_unknown: bool) -> Self {
        let blocked: Vec<bool> = grid
            .cells()
            .iter()
            .map(|c| !c.passable(allow_unknown))
            .collect();
        // The distance field counts occupied cells only: mark the unknown
        // ones occupied when they block.
        let solid = if allow_unknown || !grid.cells().contains(&Cell::Unknown) {
            None
        } else {
            let cells = blocked
                .iter()
                .map(|&b| if b { Cell::Occupied } else { Cell::Free })
                .collect();
            OccupancyGrid::from_cells(grid.width(), grid.height(), cells)
                .and_then(|g| g.with_frame(grid.resolution(), grid.origin()))
                .ok()
        };
        let dist = distance_field(solid.as_ref().unwrap_or(grid));
        Self {
            width: grid.width(),
            height: grid.height(),
            res: grid.resolution(),
            radius,
            blocked,
            dist,
        }
    }

    /// The disc's radius, m.
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// Cell size, m.
    pub fn resolution(&self) -> f64 {
        self.res
    }

    /// The map's size in its frame, m.
    pub fn extent(&self) -> (f64, f64) {
        (self.width as f64 * self.res, self.height as f64 * self.res)
    }

    /// The cell `(col, row)` holding map-frame point `(x, y)`, if on the map.
    pub fn cell_of(&self, x: f64, y: f64) -> Option<(usize, usize)> {
        let (c, u) = (x / self.res, y / self.res);
        if !(c >= 0.0 && u >= 0.0) || c >= self.width as f64 || u >= self.height as f64 {
            return None;
        }
        let (c, u) = (c as usize, u as usize);
        Some((c, self.height - 1 - u))
    }

    /// Whether cell `(col, row)` blocks.
    pub fn is_blocked(&self, col: usize, row: usize) -> bool {
        self.blocked[row * self.width + col]
    }

    /// Metres from the centre of `(col, row)` to the nearest blocked cell
    /// centre (∞ when nothing blocks).
    pub fn centre_distance(&self, col: usize, row: usize) -> f64 {
        self.dist[row * self.width + col]
    }

    /// Whether a disc of radius `r` at map-frame `(x, y)` lies on the map
    /// and overlaps no blocked cell.
    pub fn disc_free(&self, x: f64, y: f64, r: f64) -> bool {
        let (w, h) = self.extent();
        if !(x - r >= 0.0 && y - r >= 0.0 && x + r <= w && y + r <= h) {
            return false;
        }
        let Some((col, row)) = self.cell_of(x, y) else {
            return false;
        };
        let d = self.dist[row * self.width + col];
        // The point is within res/√2 of its cell centre, and a blocked
        // cell's square within res/√2 of its centre.
        if d - SQRT_2 * self.res >= r {
            return true;
        }
        if d + self.res / SQRT_2 < r {
            return false;
        }
        self.disc_free_exact(x, y, r)
    }

    /// [`Self::disc_free`] by scanning every cell the disc's box touches.
    pub fn disc_free_exact(&self, x: f64, y: f64, r: f64) -> bool {
        let (w, h) = self.extent();
        if !(x - r >= 0.0 && y - r >= 0.0 && x + r <= w && y + r <= h) {
            return false;
        }
        let res = self.res;
        let c0 = ((x - r) / res).floor().max(0.0) as usize;
        let c1 = (((x + r) / res).floor() as usize).min(self.width - 1);
        let u0 = ((y - r) / res).floor().max(0.0) as usize;
        let u1 = (((y + r) / res).floor() as usize).min(self.height - 1);
        for u in u0..=u1 {
            let row = self.height - 1 - u;
            for c in c0..=c1 {
                if !self.blocked[row * self.width + c] {
                    continue;
                }
                // Distance from the point to the cell's square.
                let dx = (c as f64 * res - x).max(x - (c + 1) as f64 * res).max(0.0);
                let dy = (u as f64 * res - y).max(y - (u + 1) as f64 * res).max(0.0);
                if dx * dx + dy * dy < r * r {
                    return false;
                }
            }
        }
        true
    }

    /// Whether the checker's disc at `(x, y)` is free.
    pub fn free(&self, x: f64, y: f64) -> bool {
        self.disc_free(x, y, self.radius)
    }
}

/// Discs that cover a rectangle centred on a pose (length along the
/// heading, width across): `n` equal discs centred on the rectangle's
/// longer axis, each covering a 1/n slice of it, so the radius is
/// √((long / 2n)² + (short / 2)²). `n` is the least for which the discs bulge past the long
/// sides by at most a quarter cell. The cover is conservative (it contains
/// the rectangle): at most a quarter cell larger across the long sides, and
/// past each short end by √((long / 2n)² + (short / 2)²) − long / 2n ≤
/// short / 2 at the end's middle (a disc cannot have a flat end). A disc
/// footprint is the cover with one disc.
#[derive(Debug, Clone, PartialEq)]
pub struct RectCover {
    /// Radius of each disc, m.
    pub radius: f64,
    /// Each disc centre in the body frame (along the heading, to its
    /// left), m.
    pub offsets: Vec<(f64, f64)>,
}

/// Most discs a rectangle cover may use (the bound keeps a hostile size,
/// 1 km × 1 cm, finite; the cover then bulges more than a quarter cell).
pub const MAX_COVER_DISCS: usize = 64;

impl RectCover {
    /// One disc of radius `r` at the pose.
    pub fn disc(r: f64) -> Self {
        Self {
            radius: r,
            offsets: vec![(0.0, 0.0)],
        }
    }

    /// The cover of a `length` × `width` rectangle (finite, > 0) on a map
    /// of cells `res` m.
    pub fn new(length: f64, width: f64, res: f64) -> Self {
        let (long, short) = (length.max(width), length.min(width));
        let half_s = 0.5 * short;
        let bulge = 0.25 * res;
        // Half a slice may be at most this long for the bulge to hold.
        let half_slice = ((half_s + bulge).powi(2) - half_s * half_s).sqrt();
        let n = ((0.5 * long / half_slice).ceil().max(1.0) as usize).min(MAX_COVER_DISCS);
        let slice = long / n as f64;
        let radius = crate::num::hypot(0.5 * slice, half_s);
        let offsets = (0..n)
            .map(|i| {
                let o = -0.5 * long + slice * (i as f64 + 0.5);
                if length >= width {
                    (o, 0.0)
                } else {
                    (0.0, o)
                }
            })
            .collect();
        Self { radius, offsets }
    }

    /// The disc centres for the body at `p` (map frame).
    pub fn centres(&self, p: super::Pose) -> impl Iterator<Item = (f64, f64)> + '_ {
        let (c, s) = (crate::num::cos(p.yaw), crate::num::sin(p.yaw));
        self.offsets
            .iter()
            .map(move |&(a, b)| (p.x + a * c - b * s, p.y + a * s + b * c))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_fast_test_agrees_with_the_exact_scan() {
        let g = OccupancyGrid::from_ascii(
            "..........\n...#......\n..........\n......##..\n..........\n#.........\n",
        )
        .unwrap()
        .with_frame(0.5, Default::default())
        .unwrap();
        let ck = DiscChecker::new(&g, 0.3, false);
        for i in 0..60 {
            for j in 0..36 {
                let (x, y) = (i as f64 * 0.0833, j as f64 * 0.0833);
                for r in [0.05, 0.3, 0.7] {
                    assert_eq!(
                        ck.disc_free(x, y, r),
                        ck.disc_free_exact(x, y, r),
                        "({x}, {y}) r {r}"
                    );
                }
            }
        }
        // A disc touching the map edge or a wall is not free; one clear of both is.
        assert!(!ck.disc_free(0.2, 1.0, 0.3));
        assert!(ck.disc_free(4.0, 2.7, 0.3));
        // The wall at column 3, row 1 spans x 1.5..2, y 2..2.5.
        assert!(!ck.disc_free(1.75, 1.8, 0.3));
    }

    #[test]
    fn the_rectangle_cover_contains_the_rectangle_and_bulges_at_most_a_quarter_cell() {
        for (l, w) in [(0.6, 0.4), (2.0, 0.3), (0.3, 0.9), (0.1, 0.1)] {
            let res = 0.1;
            let c = RectCover::new(l, w, res);
            let p = super::super::Pose::new(1.0, 2.0, 0.7);
            let centres: Vec<(f64, f64)> = c.centres(p).collect();
            let (co, si) = (0.7f64.cos(), 0.7f64.sin());
            // Every point of the rectangle is in some disc.
            for i in 0..=40 {
                for j in 0..=20 {
                    let (a, b) = (l * (i as f64 / 40.0 - 0.5), w * (j as f64 / 20.0 - 0.5));
                    let (x, y) = (1.0 + a * co - b * si, 2.0 + a * si + b * co);
                    assert!(
                        centres
                            .iter()
                            .any(|&(cx, cy)| (x - cx).hypot(y - cy) <= c.radius + 1e-12),
                        "{l}×{w}: ({a}, {b}) uncovered"
                    );
                }
            }
            assert!(
                c.radius - 0.5 * l.min(w) <= 0.25 * res + 1e-12,
                "{l}×{w}: {c:?}"
            );
        }
    }
}
