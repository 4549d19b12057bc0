//! The static map as geometry: a clearance field for fast queries inside
//! planner rollouts, and exact footprint collision (parry2d) for the
//! simulator's ground truth.

use parry2d_f64::math::{Pose, Rot2, Vector};
use parry2d_f64::query;
use parry2d_f64::shape::{Ball, Cuboid, Shape};

use super::movers::Bounds;
use super::robot::{Footprint, RobotState};
use super::WorldError;
use crate::map::costmap::distance_field;
use crate::map::{Cell, OccupancyGrid};
use crate::num::{cos, sin};

/// The static obstacles of a world: the occupancy grid (unknown cells count
/// as obstacles unless told otherwise, the map's outside always does) and a
/// precomputed clearance field.
#[derive(Debug, Clone)]
pub struct StaticMap {
    grid: OccupancyGrid,
    /// Per cell, rows bottom-up (u = h − 1 − row): whether it blocks.
    blocked_up: Vec<bool>,
    /// Per cell: distance (m) from the cell centre to the nearest blocked
    /// cell's boundary, conservative (centre distance − half a cell). Rows
    /// bottom-up with a border of one cell on every side repeating the
    /// edge cells, so [`StaticMap::clearance`]'s blend needs neither
    /// clamping nor row flipping for its four corners:
    /// `pad[(u + 1) * (w + 2) + c + 1]` for u in −1..=h, c in −1..=w holds
    /// the field at the nearest cell.
    pad: Vec<f64>,
    res: f64,
    ox: f64,
    oy: f64,
    /// Width and height in cells as f64 (exact): `usize as f64` is a
    /// branchy sequence on x86-64, and `clearance` needs both every call.
    wf: f64,
    hf: f64,
}

impl StaticMap {
    /// Builds the geometry of `grid`. `unknown_is_obstacle` decides how `?`
    /// cells count. Rotated map origins are refused.
    pub fn new(grid: OccupancyGrid, unknown_is_obstacle: bool) -> Result<Self, WorldError> {
        let origin = grid.origin();
        if origin.yaw != 0.0 {
            return Err(WorldError::UnsupportedMap(format!(
                "origin yaw {} rad: the simulator needs an unrotated map (yaw 0)",
                origin.yaw
            )));
        }
        // Grids are never empty (w, h ≥ 1).
        let (w, h) = (grid.width(), grid.height());
        let blocked_up: Vec<bool> = (0..h)
            .flat_map(|u| &grid.cells()[(h - 1 - u) * w..(h - u) * w])
            .map(|c| match c {
                Cell::Occupied => true,
                Cell::Unknown => unknown_is_obstacle,
                Cell::Free => false,
            })
            .collect();
        let mut solid = grid.clone();
        for (i, &b) in blocked_up.iter().enumerate() {
            let (c, r) = (i % w, h - 1 - i / w);
            let cell = if b { Cell::Occupied } else { Cell::Free };
            solid
                .set(c, r, cell)
                .map_err(|e| WorldError::UnsupportedMap(e.to_string()))?;
        }
        let res = grid.resolution();
        // In the field's own allocation (local maps are rebuilt every step,
        // and a second large buffer a step made the allocator return and
        // refetch memory from the system each time): rows bottom-up, the
        // margin applied, then spread out to the padded layout.
        let mut pad = distance_field(&solid);
        pad.reverse();
        for row in pad.chunks_exact_mut(w) {
            row.reverse();
        }
        for d in pad.iter_mut() {
            *d = (*d - 0.5 * res).max(0.0);
        }
        let row = w + 2;
        pad.resize(row * (h + 2), 0.0);
        // Last row first: each lands beyond every row still to move.
        for u in (0..h).rev() {
            let at = (u + 1) * row;
            pad.copy_within(u * w..u * w + w, at + 1);
            pad[at] = pad[at + 1];
            pad[at + w + 1] = pad[at + w];
        }
        pad.copy_within(row..2 * row, 0);
        pad.copy_within(h * row..(h + 1) * row, (h + 1) * row);
        Ok(Self {
            pad,
            blocked_up,
            res,
            ox: origin.x,
            oy: origin.y,
            wf: grid.width() as f64,
            hf: grid.height() as f64,
            grid,
        })
    }

    /// The grid as the robot meets it: every blocked cell occupied
    /// (unknown ones too when they count as obstacles), every other free,
    /// in the same frame — what a costmap's static layer holds.
    pub fn solid(&self) -> OccupancyGrid {
        let mut g = self.grid.clone();
        let (w, h) = (g.width(), g.height());
        for (i, &b) in self.blocked_up.iter().enumerate() {
            let (c, r) = (i % w, h - 1 - i / w);
            // In bounds by construction.
            let _ = g.set(c, r, if b { Cell::Occupied } else { Cell::Free });
        }
        g
    }

    /// The occupancy grid.
    pub fn grid(&self) -> &OccupancyGrid {
        &self.grid
    }

    /// World extent (x_min, y_min, x_max, y_max), metres.
    pub fn bounds(&self) -> Bounds {
        [
            self.ox,
            self.oy,
            self.ox + self.grid.width() as f64 * self.res,
            self.oy + self.grid.height() as f64 * self.res,
        ]
    }

    /// Whether cell (col, row) blocks the robot; off the map counts as blocked.
    #[inline]
    pub fn is_blocked(&self, col: i64, row: i64) -> bool {
        if col < 0 || row < 0 || col >= self.grid.width() as i64 || row >= self.grid.height() as i64
        {
            return true;
        }
        let u = self.grid.height() - 1 - row as usize;
        self.blocked_up[u * self.grid.width() + col as usize]
    }

    /// The per-cell clearance field at (col, row), metres: the distance
    /// from the cell centre to the nearest blocked cell's centre less half
    /// a cell (so at least `d − 0.92·res` from any point of the cell to any
    /// blocked cell); 0 off the map. The map edge is not counted.
    #[inline]
    pub fn cell_clearance(&self, col: i64, row: i64) -> f64 {
        if col < 0 || row < 0 || col >= self.grid.width() as i64 || row >= self.grid.height() as i64
        {
            return 0.0;
        }
        let u = self.grid.height() - 1 - row as usize;
        self.pad[(u + 1) * (self.grid.width() + 2) + col as usize + 1]
    }

    /// Fractional cell coordinates of a world point (x right, y *up* from the
    /// bottom-left corner; not rows).
    #[inline(always)]
    fn local(&self, x: f64, y: f64) -> (f64, f64) {
        ((x - self.ox) / self.res, (y - self.oy) / self.res)
    }

    /// Distance (m) from a point to the nearest static obstacle or the map
    /// edge, ≥ 0. Bilinear in the per-cell field: O(1), continuous, within
    /// about a third of a cell of the exact value and never above it by more
    /// than that. Use it in rollouts; [`StaticMap::footprint_collides`] is
    /// the exact test.
    #[inline(always)]
    pub fn clearance(&self, x: f64, y: f64) -> f64 {
        let w = self.grid.width();
        let (lx, ly) = self.local(x, y);
        if !(lx > 0.0 && ly > 0.0 && lx < self.wf && ly < self.hf) {
            return 0.0;
        }
        // lx, ly are positive here, so truncation is floor (no libm call on
        // targets without SSE4.1; the values are the same), and below the
        // width and height (so the cell is on the map). Through i64: a
        // signed conversion is one instruction on x86-64, an unsigned one
        // a branchy sequence (so are the conversions back to f64 below,
        // exact either way).
        let (cx, cy) = (lx as i64, ly as i64);
        // Inside a blocked cell the distance is 0 whatever the neighbours say.
        if self.blocked_up[cy as usize * w + cx as usize] {
            return 0.0;
        }
        // No NaN reaches here (the comparisons above), and nothing is ±0, so
        // `<` picks what `f64::min` would, without its NaN handling.
        let lo = |a: f64, b: f64| if b < a { b } else { a };
        let edge = lo(lo(lo(lx, ly), self.wf - lx), self.hf - ly) * self.res;
        // Cell-centre lattice coordinates (u up from the bottom row). With
        // cx ≤ lx < cx + 1, fx = lx − 0.5 lies in [cx − ½, cx + ½], so its
        // floor is cx − 1 (−1 in the first half cell) below cx, else cx:
        // no second conversion.
        let (fx, fy) = (lx - 0.5, ly - 0.5);
        let ix = cx - i64::from(fx < cx as f64);
        let iy = cy - i64::from(fy < cy as f64);
        let (tx, ty) = (fx - ix as f64, fy - iy as f64);
        // ix ≥ −1 and iy ≥ −1: the padded field's corner (ix, iy), rows up.
        let row = w + 2;
        let i0 = (iy + 1) as usize * row + (ix + 1) as usize;
        let v00 = self.pad[i0];
        let v10 = self.pad[i0 + 1];
        let v01 = self.pad[i0 + row];
        let v11 = self.pad[i0 + row + 1];
        let v = (v00 * (1.0 - tx) + v10 * tx) * (1.0 - ty) + (v01 * (1.0 - tx) + v11 * tx) * ty;
        // `f64::min`: a NaN blend (an infinite field times 0) gives the edge.
        if v < edge {
            v
        } else {
            edge
        }
    }

    /// Exact test: does the footprint at `pose` overlap a blocked cell or
    /// leave the map? Geometry by parry2d.
    pub fn footprint_collides(&self, footprint: &Footprint, pose: &RobotState) -> bool {
        self.footprint_distance(footprint, pose, 1e-9) <= 0.0
    }

    /// Exact distance (m) from the footprint at `pose` to the nearest
    /// blocked cell or the map edge, looking no further than `max_range`
    /// beyond the footprint (returns `max_range` when nothing is closer).
    /// 0 when overlapping.
    pub fn footprint_distance(
        &self,
        footprint: &Footprint,
        pose: &RobotState,
        max_range: f64,
    ) -> f64 {
        let b = self.bounds();
        let reach = footprint.circumscribed_radius();
        let rot = Rot2::from_cos_sin_unchecked(cos(pose.theta), sin(pose.theta));
        let robot_pose = Pose::from_parts(Vector::new(pose.x, pose.y), rot);
        let (ball, cuboid);
        let shape: &dyn Shape = match *footprint {
            Footprint::Circle { radius } => {
                ball = Ball::new(radius);
                &ball
            }
            Footprint::Rectangle { length, width } => {
                cuboid = Cuboid::new(Vector::new(0.5 * length, 0.5 * width));
                &cuboid
            }
        };
        // The map edge: the footprint's corners against the bounds (exact
        // for a rectangle, and for a circle its extreme points).
        let edge = match *footprint {
            Footprint::Circle { radius } => {
                (pose.x - b[0])
                    .min(pose.y - b[1])
                    .min(b[2] - pose.x)
                    .min(b[3] - pose.y)
                    - radius
            }
            Footprint::Rectangle { length, width } => {
                let (c, s) = (rot.re, rot.im);
                let mut m = f64::INFINITY;
                for (sx, sy) in [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)] {
                    let (ax, ay) = (sx * 0.5 * length, sy * 0.5 * width);
                    let (px, py) = (pose.x + c * ax - s * ay, pose.y + s * ax + c * ay);
                    m = m
                        .min(px - b[0])
                        .min(py - b[1])
                        .min(b[2] - px)
                        .min(b[3] - py);
                }
                m
            }
        };
        let mut best = edge.max(0.0).min(max_range.max(0.0));
        if edge <= 0.0 {
            return 0.0;
        }
        let look = reach + best;
        let (x0, y0) = self.local(pose.x - look, pose.y - look);
        let (x1, y1) = self.local(pose.x + look, pose.y + look);
        let h = self.grid.height() as i64;
        let half = Cuboid::new(Vector::new(0.5 * self.res, 0.5 * self.res));
        for u in (y0.floor() as i64).max(0)..=(y1.floor() as i64).min(h - 1) {
            for c in
                (x0.floor() as i64).max(0)..=(x1.floor() as i64).min(self.grid.width() as i64 - 1)
            {
                if !self.is_blocked(c, h - 1 - u) {
                    continue;
                }
                let centre = Vector::new(
                    self.ox + (c as f64 + 0.5) * self.res,
                    self.oy + (u as f64 + 0.5) * self.res,
                );
                let cell_pose = Pose::from_translation(centre);
                let d = query::distance(&robot_pose, shape, &cell_pose, &half)
                    .map_or(0.0, |s| s.distance);
                if d < best {
                    best = d.max(0.0);
                    if best == 0.0 {
                        return 0.0;
                    }
                }
            }
        }
        best
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::Pose2;

    fn map() -> StaticMap {
        let g = OccupancyGrid::from_ascii(
            "..........\n..........\n.....#....\n..........\n..........\n",
        )
        .unwrap()
        .with_frame(1.0, Pose2::default())
        .unwrap();
        StaticMap::new(g, true).unwrap()
    }

    /// `clearance` as written before its conversions and minima were
    /// trimmed: the reference its values must match bit for bit.
    fn clearance_reference(m: &StaticMap, x: f64, y: f64) -> f64 {
        let (w, h) = (m.grid.width(), m.grid.height());
        let (lx, ly) = m.local(x, y);
        if !(lx > 0.0 && ly > 0.0 && lx < w as f64 && ly < h as f64) {
            return 0.0;
        }
        let (cx, cy) = (lx as i64 as usize, ly as i64 as usize);
        // The per-cell arrays as they were (rows top-down, no border).
        let blocked = |i: usize| m.is_blocked((i % w) as i64, (i / w) as i64);
        let clear = |i: usize| m.cell_clearance((i % w) as i64, (i / w) as i64);
        if blocked((h - 1 - cy.min(h - 1)) * w + cx.min(w - 1)) {
            return 0.0;
        }
        let edge = lx.min(ly).min(w as f64 - lx).min(h as f64 - ly) * m.res;
        let (fx, fy) = (lx - 0.5, ly - 0.5);
        let ix = if fx < 0.0 { -1 } else { fx as isize };
        let iy = if fy < 0.0 { -1 } else { fy as isize };
        let (tx, ty) = (fx - ix as f64, fy - iy as f64);
        let (c0, c1) = (ix.max(0) as usize, ((ix + 1) as usize).min(w - 1));
        let (u0, u1) = (iy.max(0) as usize, ((iy + 1) as usize).min(h - 1));
        let (r0, r1) = ((h - 1 - u0) * w, (h - 1 - u1) * w);
        let v00 = clear(r0 + c0);
        let v10 = clear(r0 + c1);
        let v01 = clear(r1 + c0);
        let v11 = clear(r1 + c1);
        let v = (v00 * (1.0 - tx) + v10 * tx) * (1.0 - ty) + (v01 * (1.0 - tx) + v11 * tx) * ty;
        v.min(edge)
    }

    #[test]
    fn clearance_keeps_every_bit_of_the_reference_blend() {
        let mut rng = crate::num::Rng::new(5);
        let rows =
            "#.........##\n....#.......\n.....#......\n..........#.\n............\n..#.........\n";
        let walled = OccupancyGrid::from_ascii(rows)
            .unwrap()
            .with_frame(
                0.1,
                Pose2 {
                    x: -0.35,
                    y: 1.2,
                    yaw: 0.0,
                },
            )
            .unwrap();
        // No blocked cell: an infinite field, whose blend can be NaN.
        let open = OccupancyGrid::from_ascii("....\n....\n")
            .unwrap()
            .with_frame(0.5, Pose2::default())
            .unwrap();
        for (g, x0, y0, side) in [(walled, -0.4, 1.15, 1.3), (open, -0.1, -0.1, 2.3)] {
            let m = StaticMap::new(g, true).unwrap();
            let res = m.res;
            // The per-cell field and flags, against the grid they come from.
            let w = m.grid.width();
            let field = distance_field(&m.solid());
            for (i, d) in field.iter().enumerate() {
                let (c, r) = ((i % w) as i64, (i / w) as i64);
                let want = (d - 0.5 * res).max(0.0);
                assert_eq!(m.cell_clearance(c, r).to_bits(), want.to_bits(), "cell {i}");
                let cell = m.grid.cells()[i];
                assert_eq!(m.is_blocked(c, r), cell != Cell::Free, "cell {i}");
            }
            let mut points: Vec<(f64, f64)> = (0..200_000)
                .map(|_| (rng.range(x0, x0 + side), rng.range(y0, y0 + side)))
                .collect();
            // Cell borders and centres, where the floors change.
            for i in 0..30 {
                for j in 0..30 {
                    let (x, y) = (m.ox + i as f64 * 0.5 * res, m.oy + j as f64 * 0.5 * res);
                    points.push((x, y));
                    points.push((x.next_up_compat(), y.next_down_compat()));
                }
            }
            for (x, y) in points {
                let (a, b) = (m.clearance(x, y), clearance_reference(&m, x, y));
                assert_eq!(a.to_bits(), b.to_bits(), "({x}, {y}): {a} vs {b}");
            }
        }
    }

    trait Ulp {
        fn next_up_compat(self) -> Self;
        fn next_down_compat(self) -> Self;
    }

    impl Ulp for f64 {
        // (f64::next_up is newer than the crate's MSRV.) Finite here.
        fn next_up_compat(self) -> f64 {
            if self == 0.0 {
                f64::from_bits(1)
            } else if self > 0.0 {
                f64::from_bits(self.to_bits() + 1)
            } else {
                f64::from_bits(self.to_bits() - 1)
            }
        }
        fn next_down_compat(self) -> f64 {
            -(-self).next_up_compat()
        }
    }

    #[test]
    fn clearance_tracks_the_exact_distance() {
        let m = map();
        // Blocked cell (5, row 2) spans x 5..6, y 2..3.
        for (x, y, exact) in [
            (3.0f64, 2.5f64, 2.0f64),
            (5.5, 0.5, 1.5),
            (8.5, 2.5, 2.5),
            (5.5, 4.2, 0.8),
        ] {
            let c = m.clearance(x, y);
            assert!(
                (c - exact.min(x).min(10.0 - x).min(y).min(5.0 - y)).abs() < 0.4,
                "({x},{y}): {c} vs {exact}"
            );
        }
        assert_eq!(m.clearance(5.5, 2.5), 0.0);
        assert_eq!(m.clearance(-1.0, 2.0), 0.0);
    }

    #[test]
    fn footprint_collision_is_exact() {
        let m = map();
        let circle = Footprint::Circle { radius: 0.5 };
        let at = |x, y, theta| RobotState {
            x,
            y,
            theta,
            ..Default::default()
        };
        assert!(!m.footprint_collides(&circle, &at(4.45, 2.5, 0.0)));
        assert!(m.footprint_collides(&circle, &at(4.55, 2.5, 0.0)));
        let d = m.footprint_distance(&circle, &at(3.0, 2.5, 0.0), 10.0);
        assert!((d - 1.5).abs() < 1e-9, "{d}");
        // A long thin rectangle: along x it hits, turned 90° it fits.
        let rect = Footprint::Rectangle {
            length: 2.4,
            width: 0.2,
        };
        assert!(m.footprint_collides(&rect, &at(4.0, 2.5, 0.0)));
        assert!(!m.footprint_collides(&rect, &at(4.0, 2.5, std::f64::consts::FRAC_PI_2)));
        // The map edge counts.
        assert!(m.footprint_collides(&circle, &at(0.3, 2.5, 0.0)));
    }

    #[test]
    fn rotated_maps_are_refused() {
        let g = OccupancyGrid::from_ascii("..\n..\n")
            .unwrap()
            .with_frame(
                1.0,
                Pose2 {
                    x: 0.0,
                    y: 0.0,
                    yaw: 0.3,
                },
            )
            .unwrap();
        assert!(matches!(
            StaticMap::new(g, true),
            Err(WorldError::UnsupportedMap(_))
        ));
    }
}
