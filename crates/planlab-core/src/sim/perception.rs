//! What a robot with only a laser knows of the map (docs/algorithms.md
//! §perception): the laser is simulated against the true map each control
//! step, and a costmap is built from its scans as ROS `costmap_2d` builds
//! one — the obstacle layer marks the cell of every return within
//! `obstacle_range` and clears the cells each ray crossed up to
//! `raytrace_range`; the inflation layer grows the marks with its decay.
//!
//! An episode with a perception section gives its planner this map, not
//! the true one: [`Perception::map`] holds the marked cells as obstacles
//! and everything else (seen free or never seen) as free, as a navigation
//! stack that treats unknown space as traversable does. The laser scan
//! itself goes to the planner too ([`crate::local::Observation::scan`]),
//! so planners that read a LiDAR use the simulated sensor.
//!
//! Simplifications, declared: the scan is taken at the robot's centre at
//! the end of the control period (no sensor offset, no motion during the
//! sweep); a beam with no return clears nothing (`costmap_2d`'s default
//! `inf_is_valid: false`); the costmap is the whole map, not a rolling
//! window, with no marking decay.

use crate::lidar::scan::{cast_disc, cast_grid, Disc};
use crate::map::costmap::Costmap;
use crate::map::{Cell, OccupancyGrid, Pose2};
use crate::num::{cos, sin, Rng};
use crate::params::{params, Params};
use crate::world::{LaserScan, StaticMap};

use super::SimError;

params! {
    /// The simulated 2D laser (defaults: the Hokuyo UST-10 a BARN Jackal
    /// carries: 270°, 0.25°, 30 m).
    #[derive(Debug, Clone, Copy, PartialEq)]
    pub struct LaserConfig {
        pub fov_deg: f64 = 270.0, "°" [> 0.0, <= 360.0]
            label "field of view" "field of view, centred on the heading";
        pub resolution_deg: f64 = 0.25, "°" [>= 0.01, <= 90.0] label "beam spacing" "angle between neighbouring beams";
        pub range: f64 = 30.0, "m" [> 0.0, <= 1000.0] label "range" "range limit";
        /// planlab's choice, not BARN's: the usual Gazebo laser plugin σ.
        pub noise_std: f64 = 0.0, "m" [>= 0.0, <= 10.0]
            label "range noise σ" "Gaussian range noise σ (0 = exact); its stream is seeded by the episode's seed";
    }
}

params! {
    /// The costmap built from the scans: `costmap_2d`'s obstacle and
    /// inflation layers (defaults: BARN's Jackal configuration).
    #[derive(Debug, Clone, Copy, PartialEq)]
    pub struct ScanCostmapConfig {
        pub resolution: f64 = 0.05, "m" [>= 0.005, <= 1.0] label "map cell size" "cell size of the perceived map";
        pub obstacle_range: f64 = 2.5, "m" [>= 0.0, <= 1000.0]
            label "obstacle marking range" "returns within this range mark their cell";
        pub raytrace_range: f64 = 3.0, "m" [>= 0.0, <= 1000.0]
            label "clearing range" "rays clear the cells they cross up to this range";
        pub inflation_radius: f64 = 0.30, "m" [>= 0.0, <= 100.0]
            label "inflation radius" "the inflation layer's radius (drawn and reported; planners inflate as they do)";
        /// `costmap_2d`'s default.
        pub cost_scaling_factor: f64 = 10.0, "1/m" [>= 0.0, <= 1000.0]
            label "cost decay rate" "decay rate of the inflated cost";
        /// planlab's choice: a costmap updated at 5 Hz.
        pub update_period: f64 = 0.2, "s" [>= 0.0, <= 100.0]
            label "map update period" "the perceived map is rebuilt at most this often (0: every step)";
    }
}

/// The `perception` section of a scenario: the planner knows only what
/// this laser shows.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct PerceptionSpec {
    /// The laser.
    pub laser: LaserConfig,
    /// The costmap built from its scans.
    pub costmap: ScanCostmapConfig,
}

/// Most cells the perceived map may have (it covers the true map's extent
/// at its own resolution).
pub const MAX_PERCEIVED_CELLS: usize = 50_000_000;

/// Most beams a laser may have.
pub const MAX_LASER_BEAMS: usize = 100_000;

impl PerceptionSpec {
    /// Checks every number; errors name `perception.…`.
    pub fn validate(&self) -> Result<(), SimError> {
        let bad = |e: crate::params::ParamError| SimError::InvalidConfig(e.unit_named());
        self.laser.check_bounds("perception.laser").map_err(bad)?;
        self.costmap
            .check_bounds("perception.costmap")
            .map_err(bad)?;
        if beams(&self.laser) > MAX_LASER_BEAMS {
            return Err(SimError::InvalidConfig(format!(
                "perception.laser: {}° at {}° is more than {MAX_LASER_BEAMS} beams",
                self.laser.fov_deg, self.laser.resolution_deg
            )));
        }
        Ok(())
    }
}

/// Number of beams of a laser: fov / resolution, plus the closing beam
/// when the field of view is not a full turn.
fn beams(l: &LaserConfig) -> usize {
    let n = (l.fov_deg / l.resolution_deg).round().max(1.0);
    if l.fov_deg >= 360.0 {
        n as usize
    } else {
        n as usize + 1
    }
}

/// The perceived world of one episode: the laser, its last scan, the
/// marks of the obstacle layer and the map the planner is given.
#[derive(Debug, Clone)]
pub struct Perception {
    spec: PerceptionSpec,
    rng: Rng,
    /// cos/sin of each beam's angle in the robot frame.
    dirs: Vec<(f64, f64)>,
    scan: LaserScan,
    /// Obstacle-layer marks (row-major, row 0 at the top, like the grid).
    marks: Vec<bool>,
    /// Cells a ray or a return has touched.
    seen: Vec<bool>,
    frame: OccupancyGrid,
    map: StaticMap,
    revision: u64,
    dirty: bool,
    next_update: f64,
}

impl Perception {
    /// Nothing perceived yet over the extent of `truth`; the noise stream
    /// is seeded by `seed`.
    pub fn new(spec: PerceptionSpec, truth: &StaticMap, seed: u64) -> Result<Self, SimError> {
        spec.validate()?;
        let g = truth.grid();
        let res = spec.costmap.resolution;
        let (wm, hm) = (
            g.width() as f64 * g.resolution(),
            g.height() as f64 * g.resolution(),
        );
        let (w, h) = ((wm / res).ceil().max(1.0), (hm / res).ceil().max(1.0));
        if w * h > MAX_PERCEIVED_CELLS as f64 {
            return Err(SimError::InvalidConfig(format!(
                "perception.costmap.resolution = {res} m: the perceived map would have {:.0} cells (at most {MAX_PERCEIVED_CELLS})",
                w * h
            )));
        }
        let o = g.origin();
        let frame = OccupancyGrid::new(w as usize, h as usize)
            .and_then(|f| f.with_frame(res, Pose2 { yaw: 0.0, ..o }))
            .map_err(|e| SimError::InvalidConfig(format!("perception: {e}")))?;
        let map = StaticMap::new(frame.clone(), false)
            .map_err(|e| SimError::InvalidConfig(format!("perception: {e}")))?;
        let l = &spec.laser;
        let n = beams(l);
        let inc = l.resolution_deg.to_radians();
        let angle_min = if l.fov_deg >= 360.0 {
            0.0
        } else {
            -0.5 * l.fov_deg.to_radians()
        };
        let dirs = (0..n)
            .map(|i| {
                let a = angle_min + i as f64 * inc;
                (cos(a), sin(a))
            })
            .collect();
        let cells = frame.width() * frame.height();
        Ok(Perception {
            spec,
            // Its own stream: the seed's other streams (movers, slip) are
            // untouched by adding a laser.
            rng: Rng::new(seed ^ 0x1A5E_5CA1_0000_0001),
            dirs,
            scan: LaserScan {
                pose: [f64::NAN; 3],
                angle_min,
                angle_increment: inc,
                ranges: Vec::with_capacity(n),
                max_range: l.range,
            },
            marks: vec![false; cells],
            seen: vec![false; cells],
            frame,
            map,
            revision: 1,
            dirty: false,
            next_update: 0.0,
        })
    }

    /// The section this was built from.
    pub fn spec(&self) -> &PerceptionSpec {
        &self.spec
    }

    /// The last scan.
    pub fn scan(&self) -> &LaserScan {
        &self.scan
    }

    /// The map the planner is given: marked cells are obstacles.
    pub fn map(&self) -> &StaticMap {
        &self.map
    }

    /// Changes whenever [`Perception::map`] changes.
    pub fn revision(&self) -> u64 {
        self.revision
    }

    /// Obstacle-layer marks, row-major with row 0 at the top.
    pub fn marks(&self) -> &[bool] {
        &self.marks
    }

    /// Cells the laser has touched (cleared or marked), same layout.
    pub fn seen(&self) -> &[bool] {
        &self.seen
    }

    /// The perceived map's frame (size, resolution, origin).
    pub fn frame(&self) -> &OccupancyGrid {
        &self.frame
    }

    /// The costmap of the marks with the inflation layer (lethal marks,
    /// inscribed band of `inscribed_radius` m, decaying band out to the
    /// inflation radius); unseen cells read [`crate::map::costmap::NO_INFORMATION`]
    /// unless inflated.
    pub fn costmap(&self, inscribed_radius: f64) -> Result<Costmap, SimError> {
        let c = &self.spec.costmap;
        let cells = self
            .marks
            .iter()
            .zip(&self.seen)
            .map(|(&m, &s)| match (m, s) {
                (true, _) => Cell::Occupied,
                (false, true) => Cell::Free,
                (false, false) => Cell::Unknown,
            })
            .collect();
        let g = OccupancyGrid::from_cells(self.frame.width(), self.frame.height(), cells)
            .and_then(|g| g.with_frame(self.frame.resolution(), self.frame.origin()))
            .map_err(|e| SimError::InvalidConfig(format!("perception: {e}")))?;
        Costmap::ros(
            &g,
            inscribed_radius.min(c.inflation_radius),
            c.inflation_radius,
            c.cost_scaling_factor,
        )
        .map_err(|e| SimError::InvalidConfig(format!("perception: {e}")))
    }

    /// Scans from `pose` at time `t` against the true map and the discs,
    /// updates the obstacle layer, and rebuilds the planner's map when
    /// marks changed and the update period has passed.
    pub fn sense(&mut self, truth: &StaticMap, pose: [f64; 3], discs: &[Disc], t: f64) {
        let l = self.spec.laser;
        let (ct, st) = (cos(pose[2]), sin(pose[2]));
        self.scan.pose = pose;
        self.scan.ranges.clear();
        for &(c, s) in &self.dirs {
            let (dx, dy) = (ct * c - st * s, st * c + ct * s);
            let mut d = cast_grid(truth, pose[0], pose[1], dx, dy, l.range);
            for disc in discs {
                d = d.min(cast_disc(pose[0], pose[1], dx, dy, disc));
            }
            if d.is_finite() && l.noise_std > 0.0 {
                d = (d + l.noise_std * self.rng.normal()).clamp(0.0, l.range);
            }
            self.scan
                .ranges
                .push(if d <= l.range { d } else { f64::INFINITY });
        }
        self.update_layer(pose);
        if self.dirty && t + 1e-9 >= self.next_update {
            self.rebuild();
            self.next_update = t + self.spec.costmap.update_period;
        }
    }

    /// Clearing then marking, as `costmap_2d`'s obstacle layer does.
    fn update_layer(&mut self, pose: [f64; 3]) {
        let c = self.spec.costmap;
        let (ct, st) = (cos(pose[2]), sin(pose[2]));
        let res = self.frame.resolution();
        let o = self.frame.origin();
        let (w, h) = (self.frame.width() as i64, self.frame.height() as i64);
        // Cell (col, row) of a world point, or None off the map.
        let cell = |x: f64, y: f64| -> Option<(i64, i64)> {
            let (cx, cu) = (((x - o.x) / res).floor(), ((y - o.y) / res).floor());
            if !(cx >= 0.0 && cu >= 0.0 && cx < w as f64 && cu < h as f64) {
                return None;
            }
            Some((cx as i64, h - 1 - cu as i64))
        };
        let mut changed = false;
        let mut ends = Vec::new();
        for (i, &(bc, bs)) in self.dirs.iter().enumerate() {
            let d = self.scan.ranges[i];
            if !d.is_finite() {
                continue;
            }
            let (dx, dy) = (ct * bc - st * bs, st * bc + ct * bs);
            let end = [pose[0] + d * dx, pose[1] + d * dy];
            let end_cell = cell(end[0], end[1]);
            // Clear along the ray up to the raytrace range, sparing the
            // return's own cell: a grid traversal of every crossed cell.
            let reach = d.min(c.raytrace_range);
            let local = ((pose[0] - o.x) / res, (pose[1] - o.y) / res);
            let end = end_cell.unwrap_or((-1, -1));
            let (marks, seen) = (&mut self.marks, &mut self.seen);
            crate::map::ray::walk((w, h), res, local, (dx, dy), reach, |cx, row| {
                if (cx, row) == end {
                    return false;
                }
                let idx = (row * w + cx) as usize;
                seen[idx] = true;
                if marks[idx] {
                    marks[idx] = false;
                    changed = true;
                }
                true
            });
            if d <= c.obstacle_range {
                if let Some(cr) = end_cell {
                    ends.push((cr.1 * w + cr.0) as usize);
                }
            }
        }
        for idx in ends {
            self.seen[idx] = true;
            if !self.marks[idx] {
                self.marks[idx] = true;
                changed = true;
            }
        }
        self.dirty |= changed;
    }

    /// Whether `point` lies in the laser's field of view and range from
    /// the robot at `state`.
    pub fn in_view(&self, state: &crate::world::RobotState, point: [f64; 2]) -> bool {
        let l = &self.spec.laser;
        let (dx, dy) = (point[0] - state.x, point[1] - state.y);
        let bearing = crate::num::wrap_angle(crate::num::atan2(dy, dx) - state.theta);
        crate::num::hypot(dx, dy) <= l.range
            && (l.fov_deg >= 360.0 || bearing.abs() <= 0.5 * l.fov_deg.to_radians())
    }

    /// The marks as they stand now, as a map (what [`Perception::map`]
    /// becomes at its next rebuild); `None` only if the frame were invalid,
    /// which construction rules out.
    pub fn marked_map(&self) -> Option<StaticMap> {
        let cells: Vec<Cell> = self
            .marks
            .iter()
            .map(|&m| if m { Cell::Occupied } else { Cell::Free })
            .collect();
        OccupancyGrid::from_cells(self.frame.width(), self.frame.height(), cells)
            .and_then(|g| g.with_frame(self.frame.resolution(), self.frame.origin()))
            .ok()
            .and_then(|g| StaticMap::new(g, false).ok())
    }

    fn rebuild(&mut self) {
        // If the map could not be built the planner keeps the previous one.
        if let Some(map) = self.marked_map() {
            self.map = map;
            self.revision += 1;
        }
        self.dirty = false;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::costmap::{INSCRIBED, LETHAL, NO_INFORMATION};

    /// A 6 × 6 m open map at 0.025 m with a square block of `side` m
    /// centred at (x, y) (none when `side` is 0).
    fn truth(x: f64, y: f64, side: f64) -> StaticMap {
        let res = 0.025;
        let n = 240;
        let mut g = OccupancyGrid::new(n, n)
            .unwrap()
            .with_frame(res, Pose2::default())
            .unwrap();
        for r in 0..n {
            for c in 0..n {
                let (cx, cy) = g.cell_to_world(c, r);
                if (cx - x).abs() <= side / 2.0 && (cy - y).abs() <= side / 2.0 && side > 0.0 {
                    g.set(c, r, Cell::Occupied).unwrap();
                }
            }
        }
        StaticMap::new(g, true).unwrap()
    }

    fn marked_at(p: &Perception, x: f64, y: f64) -> bool {
        let (c, r) = p.frame().world_to_cell(x, y).unwrap();
        p.marks()[r * p.frame().width() + c]
    }

    /// A face at x: its return lands in the cell on either side of the
    /// boundary, as rounding goes.
    fn face_marked(p: &Perception, x: f64, y: f64) -> bool {
        marked_at(p, x - 0.02, y) || marked_at(p, x + 0.02, y)
    }

    fn perceive(t: &StaticMap, spec: PerceptionSpec, pose: [f64; 3]) -> Perception {
        let mut p = Perception::new(spec, t, 7).unwrap();
        p.sense(t, pose, &[], 0.0);
        p
    }

    #[test]
    fn a_block_ahead_is_marked_inflated_and_the_planner_map_has_it() {
        let t = truth(4.0, 3.0, 0.3);
        let p = perceive(&t, PerceptionSpec::default(), [2.0, 3.0, 0.0]);
        // The face of the block is 1.85 m ahead: marked.
        assert!(face_marked(&p, 3.85, 3.0));
        // The cells in front of it were cleared, not marked.
        assert!(!marked_at(&p, 3.5, 3.0));
        assert!(
            p.map()
                .clearance(3.87, 3.0)
                .min(p.map().clearance(3.83, 3.0))
                == 0.0
        );
        assert!(p.map().clearance(3.0, 3.0) > 0.75);
        assert!(p.revision() > 1);
        // Inflation: lethal on the mark, inscribed within the inscribed
        // radius, decaying out to 0.30 m, nothing beyond it.
        let cm = p.costmap(0.165).unwrap();
        let cost = |x: f64, y: f64| {
            let (c, r) = p.frame().world_to_cell(x, y).unwrap();
            cm.get(c, r).unwrap()
        };
        assert_eq!(cost(3.87, 3.0).max(cost(3.83, 3.0)), LETHAL);
        assert_eq!(cost(3.72, 3.0), INSCRIBED);
        let (near, far) = (cost(3.62, 3.0), cost(3.57, 3.0));
        assert!(near < INSCRIBED && near > far && far > 0, "{near} {far}");
        assert_eq!(cost(3.4, 3.0), 0);
        // Behind the block: never seen.
        assert_eq!(cost(4.6, 3.0), NO_INFORMATION);
    }

    #[test]
    fn a_mark_is_cleared_when_a_ray_passes_through_its_former_cell() {
        let with = truth(3.5, 3.0, 0.2);
        let mut p = perceive(&with, PerceptionSpec::default(), [2.0, 3.0, 0.0]);
        assert!(face_marked(&p, 3.4, 3.0));
        let without = truth(0.0, 0.0, 0.0);
        p.sense(&without, [2.0, 3.0, 0.0], &[], 1.0);
        assert!(!face_marked(&p, 3.4, 3.0));
        assert!(p.map().clearance(3.4, 3.0) > 1.0);
    }

    #[test]
    fn returns_beyond_the_obstacle_range_clear_but_do_not_mark() {
        // Face at 2.7 m: beyond 2.5 m obstacle range, within 3 m raytrace.
        let t = truth(4.85, 3.0, 0.3);
        let p = perceive(&t, PerceptionSpec::default(), [2.0, 3.0, 0.0]);
        assert!(!face_marked(&p, 4.7, 3.0));
        assert!(
            p.seen()[{
                let (c, r) = p.frame().world_to_cell(4.5, 3.0).unwrap();
                r * p.frame().width() + c
            }]
        );
    }

    #[test]
    fn the_laser_is_blind_behind_its_field_of_view() {
        let t = truth(1.0, 3.0, 0.3);
        // Block 1 m behind the robot, which faces +x: outside 270°.
        let p = perceive(&t, PerceptionSpec::default(), [2.0, 3.0, 0.0]);
        assert!(!face_marked(&p, 1.15, 3.0));
        let n = p.scan().ranges.len();
        assert_eq!(n, 1081);
        // A 360° laser sees it.
        let mut spec = PerceptionSpec::default();
        spec.laser.fov_deg = 360.0;
        let p = perceive(&t, spec, [2.0, 3.0, 0.0]);
        assert_eq!(p.scan().ranges.len(), 1440);
        assert!(face_marked(&p, 1.15, 3.0));
        let back = p.scan().at_angle(std::f64::consts::PI).unwrap();
        assert!((back - 0.85).abs() < 0.03, "{back}");
    }

    #[test]
    fn noisy_scans_repeat_for_a_seed_and_differ_between_seeds() {
        let t = truth(4.0, 3.0, 0.3);
        let mut spec = PerceptionSpec::default();
        spec.laser.noise_std = 0.01;
        let scan = |seed: u64| {
            let mut p = Perception::new(spec, &t, seed).unwrap();
            p.sense(&t, [2.0, 3.0, 0.0], &[], 0.0);
            p.scan().ranges.clone()
        };
        assert_eq!(scan(1), scan(1));
        assert_ne!(scan(1), scan(2));
    }

    #[test]
    fn bad_sections_are_refused_naming_the_field() {
        let t = truth(0.0, 0.0, 0.0);
        let mut spec = PerceptionSpec::default();
        spec.laser.fov_deg = f64::NAN;
        let e = Perception::new(spec, &t, 0).unwrap_err().to_string();
        assert!(e.contains("perception.laser.fov_deg"), "{e}");
        let mut spec = PerceptionSpec::default();
        spec.laser.resolution_deg = 0.01;
        spec.laser.fov_deg = 360.0;
        assert!(Perception::new(spec, &t, 0).is_ok());
        let mut spec = PerceptionSpec::default();
        spec.costmap.resolution = 0.005;
        let big = StaticMap::new(
            OccupancyGrid::new(1000, 1000)
                .unwrap()
                .with_frame(1.0, Pose2::default())
                .unwrap(),
            true,
        )
        .unwrap();
        let e = Perception::new(spec, &big, 0).unwrap_err().to_string();
        assert!(e.contains("perception.costmap.resolution"), "{e}");
    }
}
