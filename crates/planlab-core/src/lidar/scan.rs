//! The 2D LiDAR: a scan type that holds only ranges, and its simulation by
//! exact ray casting against the occupancy grid (Amanatides–Woo DDA) and the
//! moving discs, with optional seeded Gaussian range noise.

use super::LidarError;
use crate::local::Observation;
use crate::map::ray::axis;
use crate::num::{cos, hypot, sin, Rng};
use crate::world::StaticMap;

/// A 360° scan L = \[Θ, D\] (\[L\] assumption 3): beam i points at angle
/// θ_i = 2π·i/n counter-clockwise from the robot's heading; its range is in
/// \[0, `max_range`\] or "no return" (the paper's c ∉ \[0, d_lidar\],
/// stored as `f64::INFINITY`).
///
/// Construction sanitises the input so every consumer sees a defined scan:
/// NaN, negative, infinite or out-of-range values become "no return".
#[derive(Debug, Clone, PartialEq)]
pub struct Scan {
    ranges: Vec<f64>,
    max_range: f64,
}

impl Scan {
    /// A scan from raw ranges (beam i at 2π·i/n); see the type doc for how
    /// invalid values are read. A non-finite or negative `max_range` gives
    /// a scan with no returns.
    pub fn new(ranges: Vec<f64>, max_range: f64) -> Scan {
        let max_range = if max_range.is_finite() && max_range > 0.0 {
            max_range
        } else {
            0.0
        };
        let ranges = ranges
            .into_iter()
            .map(|d| {
                if d.is_finite() && d >= 0.0 && d <= max_range && max_range > 0.0 {
                    d
                } else {
                    f64::INFINITY
                }
            })
            .collect();
        Scan { ranges, max_range }
    }

    /// Number of beams n.
    pub fn len(&self) -> usize {
        self.ranges.len()
    }

    /// Whether the scan has no beams.
    pub fn is_empty(&self) -> bool {
        self.ranges.is_empty()
    }

    /// Ranges, m (`f64::INFINITY` = no return).
    pub fn ranges(&self) -> &[f64] {
        &self.ranges
    }

    /// Range limit d_lidar, m.
    pub fn max_range(&self) -> f64 {
        self.max_range
    }

    /// Angle of beam i in the robot frame, rad, in \[0, 2π).
    pub fn angle(&self, i: usize) -> f64 {
        beam_angle(i, self.ranges.len())
    }

    /// Whether beam i returned.
    pub fn hit(&self, i: usize) -> bool {
        self.ranges.get(i).is_some_and(|d| d.is_finite())
    }
}

/// Angle of beam i of n, rad.
#[inline]
pub fn beam_angle(i: usize, n: usize) -> f64 {
    if n == 0 {
        0.0
    } else {
        std::f64::consts::TAU * i as f64 / n as f64
    }
}

crate::params::params! {
    /// Settings of the simulated LiDAR.
    #[derive(Debug, Clone, Copy, PartialEq)]
    pub struct LidarConfig {
        pub beams: u32 = 360, "1" [] label "beam count n" "number of beams n over 360°";
        /// \[L\] Table 1: 10.
        pub range: f64 = 10.0, "m" [> 0.0] label "range d_lidar" "range limit d_lidar";
        /// Standard deviation.
        pub noise_std: f64 = 0.0, "m" [>= 0.0] label "range noise σ" "Gaussian range noise σ (0 = exact)";
        pub noise_seed: u64 = 0, "1" [] label "noise seed" "seed of the noise stream";
    }
}

/// Most beams a scan may have.
pub const MAX_BEAMS: u32 = 100_000;

impl LidarConfig {
    /// Checks every number; errors name `prefix.field`.
    pub fn validate(&self, prefix: &str) -> Result<(), LidarError> {
        if self.beams == 0 || self.beams > MAX_BEAMS {
            return Err(LidarError::InvalidParameter(format!(
                "{prefix}.beams = {}: must be 1 … {MAX_BEAMS}",
                self.beams
            )));
        }
        Ok(crate::params::Params::check_bounds(self, prefix)?)
    }
}

/// A disc the LiDAR sees (a mover at its current position).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Disc {
    /// Centre, m.
    pub centre: [f64; 2],
    /// Radius, m.
    pub radius: f64,
}

/// The simulated sensor: config plus its noise stream.
#[derive(Debug, Clone)]
pub struct Lidar {
    cfg: LidarConfig,
    rng: Rng,
    /// cos/sin of each beam's angle in the robot frame.
    dirs: Vec<(f64, f64)>,
}

impl Lidar {
    /// A sensor; the config is validated (errors name `prefix.field`).
    pub fn new(cfg: LidarConfig, prefix: &str) -> Result<Lidar, LidarError> {
        cfg.validate(prefix)?;
        let n = cfg.beams as usize;
        let dirs = (0..n)
            .map(|i| {
                let a = beam_angle(i, n);
                (cos(a), sin(a))
            })
            .collect();
        Ok(Lidar {
            rng: Rng::new(cfg.noise_seed),
            cfg,
            dirs,
        })
    }

    /// The config.
    pub fn config(&self) -> &LidarConfig {
        &self.cfg
    }

    /// This step's scan from the robot's pose: the observation's laser scan
    /// resampled to this sensor's beams and range when the episode
    /// simulates one (nearest beam; a direction outside the laser's field
    /// of view reads "no return"), else cast on the observation's map and
    /// movers as [`Lidar::scan`] does.
    pub fn observe(&mut self, obs: &Observation<'_>) -> Scan {
        let s = obs.state;
        let pose = [s.x, s.y, s.theta];
        if let Some(laser) = obs.scan {
            let r = self.cfg.range;
            let n = self.dirs.len();
            let ranges = (0..n)
                .map(|i| match laser.at_angle(beam_angle(i, n)) {
                    Some(d) if d <= r => d,
                    _ => f64::INFINITY,
                })
                .collect();
            return Scan::new(ranges, r);
        }
        let discs: Vec<Disc> = obs
            .movers
            .iter()
            .map(|m| Disc {
                centre: m.pos,
                radius: m.radius,
            })
            .collect();
        self.scan(obs.map, pose, &discs)
    }

    /// Scans from pose (x, y, θ) against the map and the discs. Exact
    /// ranges (then noise when configured, clamped to \[0, range\]); a
    /// sensor inside an obstacle reads 0 on every beam.
    pub fn scan(&mut self, map: &StaticMap, pose: [f64; 3], discs: &[Disc]) -> Scan {
        let (ct, st) = (cos(pose[2]), sin(pose[2]));
        let r = self.cfg.range;
        let mut ranges = Vec::with_capacity(self.dirs.len());
        for &(c, s) in &self.dirs {
            // Beam direction in the world: heading rotated by the beam angle.
            let (dx, dy) = (ct * c - st * s, st * c + ct * s);
            let mut d = cast_grid(map, pose[0], pose[1], dx, dy, r);
            for disc in discs {
                d = d.min(cast_disc(pose[0], pose[1], dx, dy, disc));
            }
            if d.is_finite() && self.cfg.noise_std > 0.0 {
                d = (d + self.cfg.noise_std * self.rng.normal()).clamp(0.0, r);
            }
            ranges.push(if d <= r { d } else { f64::INFINITY });
        }
        Scan::new(ranges, r)
    }
}

/// Distance along the ray (x, y) + t·(dx, dy) (unit direction) to the first
/// blocked cell or the map edge, exact (grid traversal of every crossed
/// cell); `INFINITY` when nothing is met within `max`.
pub fn cast_grid(map: &StaticMap, x: f64, y: f64, dx: f64, dy: f64, max: f64) -> f64 {
    let g = map.grid();
    let res = g.resolution();
    let o = g.origin();
    let (w, h) = (g.width() as i64, g.height() as i64);
    if !(x.is_finite() && y.is_finite() && dx.is_finite() && dy.is_finite()) {
        return 0.0;
    }
    // Local cell coordinates, u up from the bottom row.
    let (lx, ly) = ((x - o.x) / res, (y - o.y) / res);
    let mut cx = lx.floor() as i64;
    let mut cu = ly.floor() as i64;
    let blocked =
        |c: i64, u: i64| c < 0 || u < 0 || c >= w || u >= h || map.is_blocked(c, h - 1 - u);
    if blocked(cx, cu) {
        return 0.0;
    }
    let (sx, tdx, mut tmx) = axis(lx, dx, res);
    let (su, tdu, mut tmu) = axis(ly, dy, res);
    // Sphere tracing: where the clearance field says no blocked cell is
    // near, jump along the ray by less than that distance (it cannot pass
    // a blocked cell or the map edge), then resume the exact traversal.
    // Rays cross mostly open space, so this visits a few cells instead of
    // every one up to the range.
    let (wf, hf) = (w as f64, h as f64);
    let (dxr, dyr) = (dx / res, dy / res);
    let mut t_cur = 0.0;
    loop {
        let (px, pu) = (lx + t_cur * dxr, ly + t_cur * dyr);
        let edge = px.min(pu).min(wf - px).min(hf - pu) * res;
        let s = (map.cell_clearance(cx, h - 1 - cu) - 0.95 * res).min(edge - 0.05 * res);
        if s > 2.0 * res {
            t_cur += s;
            if t_cur > max {
                return f64::INFINITY;
            }
            // Inside the map (the jump stops short of its edge), so the
            // coordinates are positive and truncation is floor (no libm
            // call on targets without SSE4.1).
            let (qx, qu) = (lx + t_cur * dxr, ly + t_cur * dyr);
            cx = qx as i64;
            cu = qu as i64;
            tmx = next_crossing(qx, dx, res, t_cur);
            tmu = next_crossing(qu, dy, res, t_cur);
            continue;
        }
        let t;
        if tmx < tmu {
            t = tmx;
            cx += sx;
            tmx += tdx;
        } else {
            t = tmu;
            cu += su;
            tmu += tdu;
        }
        if t > max {
            return f64::INFINITY;
        }
        if blocked(cx, cu) {
            return t;
        }
        t_cur = t;
    }
}

/// Ray distance of the first cell-boundary crossing on one axis after the
/// point at ray distance `t` whose local coordinate is `q` (≥ 0).
#[inline]
fn next_crossing(q: f64, d: f64, res: f64, t: f64) -> f64 {
    let fl = (q as i64) as f64;
    if d > 0.0 {
        t + (fl + 1.0 - q) * res / d
    } else if d < 0.0 {
        t + (q - fl) * res / -d
    } else {
        f64::INFINITY
    }
}

/// Distance along the ray to the disc (0 from inside), `INFINITY` on a miss.
pub fn cast_disc(x: f64, y: f64, dx: f64, dy: f64, disc: &Disc) -> f64 {
    let (px, py) = (x - disc.centre[0], y - disc.centre[1]);
    let c = px * px + py * py - disc.radius * disc.radius;
    if c <= 0.0 {
        return 0.0;
    }
    let b = px * dx + py * dy;
    let disc2 = b * b - c;
    if b >= 0.0 || disc2 < 0.0 || !disc2.is_finite() {
        return f64::INFINITY;
    }
    let t = -b - disc2.sqrt();
    if t >= 0.0 {
        t
    } else {
        f64::INFINITY
    }
}

/// Point of beam i at range d in the robot frame.
#[inline]
pub fn polar(angle: f64, d: f64) -> [f64; 2] {
    [d * cos(angle), d * sin(angle)]
}

/// Euclidean distance between two points.
#[inline]
pub fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    hypot(a[0] - b[0], a[1] - b[1])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::{Cell, OccupancyGrid, Pose2};

    fn room() -> StaticMap {
        // 10 × 6 cells at 0.5 m; a block at cols 6–7, rows 2–3.
        let g = OccupancyGrid::from_ascii(
            "..........\n..........\n......##..\n......##..\n..........\n..........\n",
        )
        .unwrap()
        .with_frame(0.5, Pose2::default())
        .unwrap();
        StaticMap::new(g, true).unwrap()
    }

    /// The plain traversal of every crossed cell, for checking the
    /// sphere-traced [`cast_grid`].
    fn cast_every_cell(map: &StaticMap, x: f64, y: f64, dx: f64, dy: f64, max: f64) -> f64 {
        let g = map.grid();
        let res = g.resolution();
        let (w, h) = (g.width() as i64, g.height() as i64);
        let (lx, ly) = ((x - g.origin().x) / res, (y - g.origin().y) / res);
        let (mut cx, mut cu) = (lx.floor() as i64, ly.floor() as i64);
        let blocked =
            |c: i64, u: i64| c < 0 || u < 0 || c >= w || u >= h || map.is_blocked(c, h - 1 - u);
        if blocked(cx, cu) {
            return 0.0;
        }
        let (sx, tdx, mut tmx) = axis(lx, dx, res);
        let (su, tdu, mut tmu) = axis(ly, dy, res);
        loop {
            let t;
            if tmx < tmu {
                t = tmx;
                cx += sx;
                tmx += tdx;
            } else {
                t = tmu;
                cu += su;
                tmu += tdu;
            }
            if t > max {
                return f64::INFINITY;
            }
            if blocked(cx, cu) {
                return t;
            }
        }
    }

    #[test]
    fn sphere_tracing_meets_the_same_cell_as_the_full_traversal() {
        let mut rng = Rng::new(5);
        let (w, h) = (150usize, 120usize);
        let mut cells = vec![Cell::Free; w * h];
        for _ in 0..30 {
            let (c0, r0) = (
                rng.range(0.0, 140.0) as usize,
                rng.range(0.0, 110.0) as usize,
            );
            let (bw, bh) = (rng.range(1.0, 10.0) as usize, rng.range(1.0, 10.0) as usize);
            for r in r0..(r0 + bh).min(h) {
                for c in c0..(c0 + bw).min(w) {
                    cells[r * w + c] = Cell::Occupied;
                }
            }
        }
        let grid = OccupancyGrid::from_cells(w, h, cells)
            .unwrap()
            .with_frame(0.1, Pose2::default())
            .unwrap();
        let m = StaticMap::new(grid, true).unwrap();
        let mut jumped = 0;
        for _ in 0..400 {
            let (x, y) = (rng.range(0.0, 15.0), rng.range(0.0, 12.0));
            let a = rng.range(-3.2, 3.2);
            let (dx, dy) = (a.cos(), a.sin());
            for max in [3.0, 10.0, 30.0] {
                let fast = cast_grid(&m, x, y, dx, dy, max);
                let slow = cast_every_cell(&m, x, y, dx, dy, max);
                if fast.is_finite() || slow.is_finite() {
                    assert!(
                        (fast - slow).abs() < 1e-9,
                        "({x}, {y}) at {a}: {fast} vs {slow}"
                    );
                } else {
                    assert_eq!(fast, slow);
                }
                if slow.is_finite() && slow > 1.0 {
                    jumped += 1;
                }
            }
        }
        assert!(jumped > 200, "few long rays: {jumped}");
    }

    #[test]
    fn dda_hits_cells_and_the_map_edge_exactly() {
        let m = room();
        // Block spans x 3..4, y 1..2 (rows 2–3 of 6 at 0.5 m: y from 1 to 2).
        let d = cast_grid(&m, 1.0, 1.5, 1.0, 0.0, 20.0);
        assert!((d - 2.0).abs() < 1e-12, "{d}");
        // Up to the top edge (y = 3).
        let d = cast_grid(&m, 1.0, 1.5, 0.0, 1.0, 20.0);
        assert!((d - 1.5).abs() < 1e-12, "{d}");
        // Diagonal to the block's corner region: exact against brute force.
        let (dx, dy) = (0.8f64, 0.6f64);
        let d = cast_grid(&m, 1.0, 0.2, dx, dy, 20.0);
        let mut t = 0.0;
        while t < 20.0 {
            let (x, y) = (1.0 + dx * t, 0.2 + dy * t);
            let (c, u) = ((x / 0.5).floor() as i64, (y / 0.5).floor() as i64);
            if c < 0 || u < 0 || c >= 10 || u >= 6 || m.is_blocked(c, 5 - u) {
                break;
            }
            t += 1e-5;
        }
        assert!((d - t).abs() < 2e-5, "{d} vs {t}");
        // Beyond the range: no return.
        assert_eq!(cast_grid(&m, 1.0, 1.5, 1.0, 0.0, 1.5), f64::INFINITY);
        // Inside a block: 0.
        assert_eq!(cast_grid(&m, 3.5, 1.5, 1.0, 0.0, 5.0), 0.0);
    }

    #[test]
    fn discs_and_noise() {
        let disc = Disc {
            centre: [3.0, 0.0],
            radius: 0.5,
        };
        assert!((cast_disc(0.0, 0.0, 1.0, 0.0, &disc) - 2.5).abs() < 1e-12);
        assert_eq!(cast_disc(0.0, 0.0, -1.0, 0.0, &disc), f64::INFINITY);
        assert_eq!(cast_disc(3.1, 0.0, -1.0, 0.0, &disc), 0.0);
        let m = room();
        let cfg = LidarConfig {
            beams: 8,
            noise_std: 0.05,
            noise_seed: 3,
            ..Default::default()
        };
        let mut a = Lidar::new(cfg, "lidar").unwrap();
        let mut b = Lidar::new(cfg, "lidar").unwrap();
        let sa = a.scan(&m, [1.0, 1.5, 0.0], &[]);
        let sb = b.scan(&m, [1.0, 1.5, 0.0], &[]);
        assert_eq!(sa, sb, "same seed, same scan");
        assert!((sa.ranges()[0] - 2.0).abs() < 0.3);
        assert!(Lidar::new(
            LidarConfig {
                range: f64::NAN,
                ..cfg
            },
            "lidar"
        )
        .unwrap_err()
        .to_string()
        .contains("lidar.range"));
    }

    #[test]
    fn scan_sanitises_ranges() {
        let s = Scan::new(vec![1.0, f64::NAN, -1.0, 11.0, f64::INFINITY, 10.0], 10.0);
        assert_eq!(s.len(), 6);
        assert!(s.hit(0) && s.hit(5));
        assert!((1..5).all(|i| !s.hit(i)));
        let s = Scan::new(vec![1.0], f64::NAN);
        assert!(!s.hit(0));
    }
}
