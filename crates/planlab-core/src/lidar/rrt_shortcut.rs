//! `rrt-shortcut`: an RRT replanner with shortcutting on what the scan has
//! shown, the \[L\] sim 7 peer.
//!
//! \[L\] compares sim 7 with RL-RRT (its reference \[2\]): an RRT whose
//! sampling and steering are learned (reinforcement learning) and which
//! plans in an unknown map. The learned part cannot be built from \[L\]'s
//! description, so this is **plain RRT (LaValle 1998) with shortcutting,
//! standing in for RL-RRT, flagged as such**: no learned component, the
//! sampler is uniform with a goal bias.
//!
//! The robot knows its scan, its pose (odometry) and the goal, never the
//! map ([`super::scan_motion`]). Each control period:
//! - **Memory.** The scan is written into an occupancy grid
//!   ([`Memory`], `memory_resolution`): each beam's cells free up to its
//!   end, the cell it returned from occupied. A hit stays occupied (a ray
//!   grazing a wall at a shallow angle crosses the cells other beams hit;
//!   letting it clear them would erase walls), so movers leave traces.
//!   The grid covers the robot and the goal plus `memory_margin` each side
//!   (this box is also the RRT's sampling domain), grows when either
//!   leaves it or a plan fails, and is coarsened to stay within
//!   [`MAX_MEMORY_CELLS`].
//! - **Plan.** Unknown cells count as free (optimistic, as an RRT
//!   replanner in an unknown map is). The planning grid keeps cells whose
//!   centre lies more than the footprint's radius + `margin` from every
//!   occupied cell; within that distance of the robot or the goal, more
//!   than the radius + one cell suffices (so a robot that came close to a
//!   wall can still leave it). An RRT ([`rrt`]: `goal_bias`, `step`,
//!   `max_iterations`) grows from the robot to the goal over that grid,
//!   its sampler seeded from the episode seed; its path is shortened by
//!   the greedy line-of-sight shortcut `rs-apf` uses
//!   ([`regression_search`]).
//! - **Follow.** The next waypoint is the target; it is passed when the
//!   robot is within `waypoint_tolerance` of it or beyond it with the one
//!   after in sight.
//! - **Replan** when a newly seen obstacle cell comes within the planning
//!   clearance of the rest of the path, the robot is more than `deviation`
//!   off its current leg, or the remaining path length has not shrunk by
//!   `progress_distance` for `progress_time`. A failed plan leaves the
//!   robot driving at the goal and is retried after `retry_time`.
//!
//! **Motion layer**: the baseline DWA on the scan's local map, as for
//! `tangent-bug`; a waypoint nearer than `lookahead` is steered to along
//! its bearing at `lookahead`. The DWA never drives into what the scan
//! shows.

use super::planner::LocalMapConfig;
use super::scan::{beam_angle, polar, LidarConfig, Scan};
use super::scan_motion::{peer_dwa, regression_search, steer_point, ScanMotion};
use crate::geom::distance_to_polyline;
use crate::global::keypoints::segment_free;
use crate::global::{supercover, Diagonal, GridPos, PlanGrid};
use crate::local::dwa::DwaConfig;
use crate::local::{LocalError, LocalPlanner, Observation, PlannerDebug};
use crate::map::costmap::distance_field;
use crate::map::{Cell, OccupancyGrid, Pose2};
use crate::num::{hypot, Rng};
use crate::params::Params;
use crate::world::{Command, RobotSpec, RobotState, StaticMap};

/// Most cells of the memory grid (a coarser resolution is used beyond).
pub const MAX_MEMORY_CELLS: usize = 4_000_000;

/// Most RRT iterations a config may ask for (bounds one plan's work).
pub const MAX_ITERATIONS: u32 = 1_000_000;

/// Sub-stream of the episode seed the RRT's sampler draws from.
const RRT_STREAM: u64 = 0x0052_5254; // "RRT"

crate::params::params! {
    /// Settings of `rrt-shortcut`. The RRT's three numbers follow the RRT
    /// literature; the rest are planlab's choices, declared as such.
    #[derive(Debug, Clone, PartialEq)]
    pub struct RrtShortcutConfig {
        pub lidar: LidarConfig = LidarConfig::default(), "" [nested] "the simulated LiDAR";
        pub local: LocalMapConfig = LocalMapConfig::default(), "" [nested]
            "the local map built from the scan for the motion planner";
        /// 0.05: OMPL's RRT default; LaValle & Kuffner 2001 bias toward the
        /// goal by a few per cent.
        pub goal_bias: f64 = 0.05, "1" [>= 0.0, <= 1.0]
            label "goal bias" "probability a sample is the goal (OMPL's RRT default 0.05)";
        /// 1.0: "a few robot radii", ≈ 3.3 × \[L\]'s 0.3 m robot.
        pub step: f64 = 1.0, "m" [> 0.0]
            label "RRT step ε" "RRT step ε: most a new node extends toward its sample (a few robot radii)";
        pub max_iterations: u32 = 5000, "1" [] label "samples per plan" "samples per plan before it fails";
        /// 0.1: the \[L\] presets' map cells; below a millimetre the cell
        /// bound would coarsen it anyway.
        pub memory_resolution: f64 = 0.1, "m" [>= 1e-3] label "memory grid cell size" "cell size of the scan's memory grid";
        pub memory_margin: f64 = 5.0, "m" [>= 0.0]
            label "memory grid margin" "memory grid and sampling domain reach this far beyond robot and goal";
        /// 0.5: \[L\]'s d_oe, as `tangent-bug` and `rs-apf` use.
        pub margin: f64 = 0.5, "m" [>= 0.0]
            label "clearance margin" "the path keeps footprint radius + this from what the scan has shown";
        /// 3: as `tangent-bug` and `rs-apf`.
        pub lookahead: f64 = 3.0, "m" [>= 0.0]
            label "look-ahead distance" "the DWA steers this far along the waypoint's bearing";
        pub waypoint_tolerance: f64 = 0.5, "m" [> 0.0] label "waypoint tolerance" "a waypoint this near is passed";
        pub deviation: f64 = 1.0, "m" [> 0.0]
            label "replan deviation" "replan when the robot is farther than this from its leg";
        pub progress_time: f64 = 5.0, "s" [> 0.0]
            label "no-progress time" "replan when the remaining length has not shrunk by progress_distance for this long";
        pub progress_distance: f64 = 0.5, "m" [>= 0.0]
            label "progress distance" "progress that resets the progress_time clock";
        pub retry_time: f64 = 1.0, "s" [>= 0.0] label "retry wait" "wait after a failed plan before the next";
        /// [`peer_dwa`].
        pub motion: DwaConfig = peer_dwa(), "" [nested]
            "the baseline DWA driving toward the waypoint";
    }
}

impl RrtShortcutConfig {
    /// Checks every number; errors name `rrt-shortcut.field`.
    pub fn validate(&self) -> Result<(), LocalError> {
        self.check_bounds("rrt-shortcut")?;
        if self.max_iterations == 0 || self.max_iterations > MAX_ITERATIONS {
            return Err(LocalError::InvalidParameter(format!(
                "rrt-shortcut.max_iterations = {}: must be in 1 ..= {MAX_ITERATIONS}",
                self.max_iterations
            )));
        }
        Ok(())
    }
}

/// What the scans have shown: an occupancy grid (unknown, free, occupied)
/// over a box of the world, row 0 at the top.
#[derive(Debug, Clone, PartialEq)]
pub struct Memory {
    grid: OccupancyGrid,
}

impl Memory {
    /// All unknown over the box `lo`–`hi` (world m) at cell size `res`,
    /// doubled until the grid has at most [`MAX_MEMORY_CELLS`] cells, with
    /// what `old` knew copied in (an occupied cell wins a coarser cell).
    /// `None` when the box or `res` is not finite.
    pub fn covering(lo: [f64; 2], hi: [f64; 2], res: f64, old: Option<&Memory>) -> Option<Memory> {
        if !(lo.iter().chain(&hi).all(|v| v.is_finite()) && res.is_finite() && res > 0.0) {
            return None;
        }
        let (wm, hm) = ((hi[0] - lo[0]).max(res), (hi[1] - lo[1]).max(res));
        let mut res = res;
        while (wm / res).ceil() * (hm / res).ceil() > MAX_MEMORY_CELLS as f64 {
            res *= 2.0;
        }
        let (w, h) = ((wm / res).ceil() as usize, (hm / res).ceil() as usize);
        let origin = Pose2 {
            x: lo[0],
            y: lo[1],
            yaw: 0.0,
        };
        let grid = OccupancyGrid::from_cells(w, h, vec![Cell::Unknown; w * h])
            .and_then(|g| g.with_frame(res, origin))
            .ok()?;
        let mut m = Memory { grid };
        if let Some(old) = old {
            let g = &old.grid;
            for row in 0..g.height() {
                for col in 0..g.width() {
                    let c = g.cells()[g.index(col, row)];
                    if c == Cell::Unknown {
                        continue;
                    }
                    let (x, y) = g.cell_to_world(col, row);
                    if let Some((nc, nr)) = m.grid.world_to_cell(x, y) {
                        let was = m.grid.cells()[m.grid.index(nc, nr)];
                        if was == Cell::Unknown || c == Cell::Occupied {
                            m.grid.set(nc, nr, c).ok();
                        }
                    }
                }
            }
        }
        Some(m)
    }

    /// A memory that already knows `grid` (a known map, for tests and
    /// drawing).
    pub fn known(grid: OccupancyGrid) -> Memory {
        Memory { grid }
    }

    /// The grid.
    pub fn grid(&self) -> &OccupancyGrid {
        &self.grid
    }

    /// The box covered, \[x0, y0, x1, y1\] m.
    pub fn bounds(&self) -> [f64; 4] {
        let o = self.grid.origin();
        let r = self.grid.resolution();
        [
            o.x,
            o.y,
            o.x + self.grid.width() as f64 * r,
            o.y + self.grid.height() as f64 * r,
        ]
    }

    fn cell(&self, p: [f64; 2]) -> Option<GridPos> {
        self.grid
            .world_to_cell(p[0], p[1])
            .map(|(c, r)| GridPos::new(c as u32, r as u32))
    }

    /// Writes a scan taken at `pose` (x, y, θ): each beam's cells free up
    /// to its end (unknown cells only: a hit stays occupied, module doc),
    /// the cell it returned from occupied. Beams are cut at the box's edge.
    /// Returns the centres of the cells that became occupied.
    pub fn integrate(&mut self, pose: [f64; 3], scan: &Scan) -> Vec<[f64; 2]> {
        let x = [pose[0], pose[1]];
        let Some(a) = self.cell(x) else {
            return Vec::new();
        };
        let b = self.bounds();
        let n = scan.len();
        let mut fresh = Vec::new();
        for (i, &r) in scan.ranges().iter().enumerate() {
            let hit = r.is_finite();
            // The point just past a hit lies in the cell that returned it.
            let reach = if hit { r + 1e-6 } else { scan.max_range() };
            let u = polar(pose[2] + beam_angle(i, n), 1.0);
            let mut t = reach;
            for k in 0..2 {
                if u[k] > 1e-12 {
                    t = t.min((b[k + 2] - x[k]) / u[k]);
                } else if u[k] < -1e-12 {
                    t = t.min((b[k] - x[k]) / u[k]);
                }
            }
            let inside = t >= reach;
            // Stay a hair inside the box so the end has a cell.
            let t = if inside { t } else { (t - 1e-6).max(0.0) };
            let Some(end) = self.cell([x[0] + t * u[0], x[1] + t * u[1]]) else {
                continue;
            };
            let g = &mut self.grid;
            supercover(a, end, |c, r, corner| {
                if corner.is_none() {
                    let (c, r) = (c as usize, r as usize);
                    if g.get(c, r) == Some(Cell::Unknown) {
                        g.set(c, r, Cell::Free).ok();
                    }
                }
            });
            if hit && inside {
                let (c, r) = (end.col as usize, end.row as usize);
                if g.get(c, r) != Some(Cell::Occupied) {
                    g.set(c, r, Cell::Occupied).ok();
                    let (wx, wy) = g.cell_to_world(c, r);
                    fresh.push([wx, wy]);
                }
            }
        }
        fresh
    }

    /// The planning grid: a cell is free when its centre lies more than
    /// `rho` from every occupied cell's centre (unknown counts as free),
    /// or more than `hard` when within `rho` of a point of `keep` (robot,
    /// goal); the cell of `keep[0]` (the robot) is always free.
    pub fn free_space(&self, hard: f64, rho: f64, keep: &[[f64; 2]]) -> PlanGrid {
        let g = &self.grid;
        let d = distance_field(g);
        let robot = keep.first().and_then(|p| self.cell(*p));
        PlanGrid::from_fn(g.width(), g.height(), |c, r| {
            let dc = d[g.index(c, r)];
            if dc > rho {
                return true;
            }
            if robot == Some(GridPos::new(c as u32, r as u32)) {
                return true;
            }
            let (x, y) = g.cell_to_world(c, r);
            dc > hard && keep.iter().any(|p| hypot(p[0] - x, p[1] - y) <= rho)
        })
    }

    /// Whether the straight segment `a`–`b` crosses only free cells of
    /// `free` (false when an end is off the memory).
    pub fn segment_free(&self, free: &PlanGrid, a: [f64; 2], b: [f64; 2]) -> bool {
        match (self.cell(a), self.cell(b)) {
            (Some(a), Some(b)) => segment_free(free, a, b, Diagonal::NoCornerCutting),
            _ => false,
        }
    }
}

/// The RRT's numbers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RrtParams {
    /// Probability a sample is the goal.
    pub goal_bias: f64,
    /// Most a new node extends toward its sample, m.
    pub step: f64,
    /// Samples before giving up.
    pub max_iterations: u32,
}

/// RRT (LaValle 1998) from `start` to `goal` in the box `bounds` (\[x0,
/// y0, x1, y1\] m): each iteration samples the goal with probability
/// `goal_bias`, else a uniform point of the box; extends the nearest node
/// (first of equals) by at most `step` toward it when `free` allows that
/// segment; and when the new node is within `step` of the goal with the
/// segment to it free, returns the tree's path start … goal. A straight
/// free line from start to goal is returned at once (the shortcut would
/// reduce any path to it). `None` after `max_iterations` samples.
pub fn rrt(
    start: [f64; 2],
    goal: [f64; 2],
    bounds: [f64; 4],
    p: &RrtParams,
    rng: &mut Rng,
    free: impl Fn([f64; 2], [f64; 2]) -> bool,
) -> Option<Vec<[f64; 2]>> {
    if free(start, goal) {
        return Some(vec![start, goal]);
    }
    let mut nodes = vec![start];
    let mut parent = vec![0usize];
    let path_to = |nodes: &[[f64; 2]], parent: &[usize], mut i: usize| {
        let mut out = vec![goal];
        loop {
            out.push(nodes[i]);
            if i == 0 {
                break;
            }
            i = parent[i];
        }
        out.reverse();
        out
    };
    for _ in 0..p.max_iterations {
        let q = if rng.uniform() < p.goal_bias {
            goal
        } else {
            [
                rng.range(bounds[0], bounds[2]),
                rng.range(bounds[1], bounds[3]),
            ]
        };
        let mut near = 0;
        let mut best = f64::INFINITY;
        for (i, n) in nodes.iter().enumerate() {
            let d = hypot(q[0] - n[0], q[1] - n[1]);
            if d < best {
                best = d;
                near = i;
            }
        }
        if best < 1e-9 {
            continue;
        }
        let k = (p.step / best).min(1.0);
        let a = nodes[near];
        let new = [a[0] + k * (q[0] - a[0]), a[1] + k * (q[1] - a[1])];
        if !free(a, new) {
            continue;
        }
        nodes.push(new);
        parent.push(near);
        let last = nodes.len() - 1;
        if hypot(goal[0] - new[0], goal[1] - new[1]) <= p.step && free(new, goal) {
            return Some(path_to(&nodes, &parent, last));
        }
    }
    None
}

/// Length of a polyline, m.
pub fn path_length(path: &[[f64; 2]]) -> f64 {
    path.windows(2)
        .map(|w| hypot(w[1][0] - w[0][0], w[1][1] - w[0][1]))
        .sum()
}

/// The `rrt-shortcut` planner (module doc).
#[derive(Debug)]
pub struct RrtShortcut {
    cfg: RrtShortcutConfig,
    io: ScanMotion,
    radius: f64,
    rng: Rng,
    memory: Option<Memory>,
    /// The planning grid of the last plan.
    free: Option<PlanGrid>,
    /// The raw RRT path and its shortcut (world m); empty: no plan.
    raw: Vec<[f64; 2]>,
    path: Vec<[f64; 2]>,
    /// Index in `path` of the waypoint steered to.
    next: usize,
    /// The goal the path was planned for.
    planned_for: Option<[f64; 2]>,
    /// Best remaining length and when it was reached (s).
    progress: (f64, f64),
    /// No plan before this time (after a failed one), s.
    retry_at: f64,
    replans: u32,
    record: bool,
    debug: PlannerDebug,
}

impl RrtShortcut {
    /// Builds the planner for `robot`; errors name the bad field.
    pub fn new(cfg: RrtShortcutConfig, robot: &RobotSpec) -> Result<RrtShortcut, LocalError> {
        cfg.validate()?;
        let io = ScanMotion::with_dwa(cfg.lidar, cfg.local, cfg.motion, robot)?;
        Ok(RrtShortcut {
            radius: robot.footprint.circumscribed_radius(),
            cfg,
            io,
            rng: Rng::new(0).fork(RRT_STREAM),
            memory: None,
            free: None,
            raw: Vec::new(),
            path: Vec::new(),
            next: 0,
            planned_for: None,
            progress: (f64::INFINITY, 0.0),
            retry_at: f64::NEG_INFINITY,
            replans: 0,
            record: false,
            debug: PlannerDebug::default(),
        })
    }

    /// The shortened path being followed (empty: none).
    pub fn path(&self) -> &[[f64; 2]] {
        &self.path
    }

    /// The raw RRT path of the last plan.
    pub fn raw_path(&self) -> &[[f64; 2]] {
        &self.raw
    }

    /// Plans made so far.
    pub fn replans(&self) -> u32 {
        self.replans
    }

    /// The memory of what the scans have shown.
    pub fn memory(&self) -> Option<&Memory> {
        self.memory.as_ref()
    }

    /// The planning clearances: (near robot or goal, elsewhere), m.
    fn clearances(&self, res: f64) -> (f64, f64) {
        (self.radius + res, self.radius + self.cfg.margin)
    }

    /// Makes the memory cover `x` and `goal` with half the margin to
    /// spare; `widen` grows it by the margin each side (a failed plan).
    fn cover(&mut self, x: [f64; 2], goal: [f64; 2], widen: bool) {
        let m = self.cfg.memory_margin;
        let mut lo = [x[0].min(goal[0]) - m, x[1].min(goal[1]) - m];
        let mut hi = [x[0].max(goal[0]) + m, x[1].max(goal[1]) + m];
        if let Some(mem) = &self.memory {
            let b = mem.bounds();
            let inside = |p: [f64; 2]| {
                p[0] - 0.5 * m >= b[0]
                    && p[0] + 0.5 * m <= b[2]
                    && p[1] - 0.5 * m >= b[1]
                    && p[1] + 0.5 * m <= b[3]
            };
            if inside(x) && inside(goal) && !widen {
                return;
            }
            let w = if widen { m } else { 0.0 };
            lo = [lo[0].min(b[0] - w), lo[1].min(b[1] - w)];
            hi = [hi[0].max(b[2] + w), hi[1].max(b[3] + w)];
        }
        self.memory = Memory::covering(lo, hi, self.cfg.memory_resolution, self.memory.as_ref());
    }

    /// Plans from `x` to `goal` at time `t`; true when a path was found.
    fn plan(&mut self, x: [f64; 2], goal: [f64; 2], t: f64) -> bool {
        self.replans += 1;
        self.planned_for = Some(goal);
        self.next = 1;
        let Some(mem) = &self.memory else {
            self.path.clear();
            return false;
        };
        let (hard, rho) = self.clearances(mem.grid().resolution());
        let free = mem.free_space(hard, rho, &[x, goal]);
        let params = RrtParams {
            goal_bias: self.cfg.goal_bias,
            step: self.cfg.step,
            max_iterations: self.cfg.max_iterations,
        };
        let seg = |a: [f64; 2], b: [f64; 2]| mem.segment_free(&free, a, b);
        let raw = rrt(x, goal, mem.bounds(), &params, &mut self.rng, seg);
        match raw {
            Some(raw) => {
                self.path = regression_search(&raw, seg);
                self.raw = raw;
                self.progress = (self.remaining(x), t);
                self.free = Some(free);
                true
            }
            None => {
                self.path.clear();
                self.raw.clear();
                self.retry_at = t + self.cfg.retry_time;
                self.free = Some(free);
                false
            }
        }
    }

    /// Length left from `x` along the path.
    fn remaining(&self, x: [f64; 2]) -> f64 {
        match self.path.get(self.next) {
            Some(w) => hypot(w[0] - x[0], w[1] - x[1]) + path_length(&self.path[self.next..]),
            None => 0.0,
        }
    }

    /// Why the path must be replanned this period, if it must.
    fn why_replan(
        &self,
        x: [f64; 2],
        goal: [f64; 2],
        fresh: &[[f64; 2]],
        t: f64,
    ) -> Option<&'static str> {
        if self.path.is_empty() {
            return (t >= self.retry_at).then_some("none");
        }
        if self.planned_for != Some(goal) {
            return Some("goal");
        }
        let res = self.memory.as_ref().map_or(0.0, |m| m.grid().resolution());
        let (hard, rho) = self.clearances(res);
        let mut rest = vec![x];
        rest.extend_from_slice(&self.path[self.next..]);
        let near = |q: [f64; 2], p: [f64; 2]| hypot(q[0] - p[0], q[1] - p[1]) <= rho;
        let blocked = fresh.iter().any(|&q| {
            let limit = if near(q, x) || near(q, goal) {
                hard
            } else {
                rho
            };
            distance_to_polyline(q, &rest).is_some_and(|d| d <= limit)
        });
        if blocked {
            return Some("blocked");
        }
        let leg = &self.path[self.next - 1..=self.next];
        if distance_to_polyline(x, leg).is_some_and(|d| d > self.cfg.deviation) {
            return Some("deviated");
        }
        if t - self.progress.1 > self.cfg.progress_time {
            return Some("no-progress");
        }
        None
    }

    /// Passes waypoints the robot at `x` has reached.
    fn advance(&mut self, x: [f64; 2]) {
        while self.next + 1 < self.path.len() {
            let (w, after) = (self.path[self.next], self.path[self.next + 1]);
            let near = hypot(w[0] - x[0], w[1] - x[1]) < self.cfg.waypoint_tolerance;
            let beyond =
                (x[0] - w[0]) * (after[0] - w[0]) + (x[1] - w[1]) * (after[1] - w[1]) > 0.0;
            let sees = || match (&self.memory, &self.free) {
                (Some(m), Some(f)) => m.segment_free(f, x, after),
                _ => false,
            };
            if near || (beyond && sees()) {
                self.next += 1;
            } else {
                break;
            }
        }
    }
}

impl LocalPlanner for RrtShortcut {
    fn name(&self) -> &'static str {
        "rrt-shortcut"
    }

    fn step(&mut self, obs: &Observation<'_>) -> Command {
        let (pose, scan) = self.io.sense(obs);
        let x = [pose[0], pose[1]];
        let goal = obs.goal;
        let t = obs.time;
        self.cover(x, goal, false);
        let fresh = match self.memory.as_mut() {
            Some(m) => m.integrate(pose, &scan),
            None => Vec::new(),
        };
        let mut phase = "follow";
        if let Some(why) = self.why_replan(x, goal, &fresh, t) {
            let mut found = self.plan(x, goal, t);
            if !found {
                // The sampling domain may be too small: widen it once.
                self.cover(x, goal, true);
                found = self.plan(x, goal, t);
            }
            phase = if found { why } else { "no-path" };
        } else if self.path.is_empty() {
            phase = "no-path";
        }
        self.advance(x);
        let rem = self.remaining(x);
        if rem < self.progress.0 - self.cfg.progress_distance {
            self.progress = (rem, t);
        }
        let (target, is_goal) = match self.path.get(self.next) {
            Some(&w) => (w, self.next + 1 == self.path.len()),
            None => (goal, true),
        };
        let steer = steer_point(x, target, self.cfg.lookahead, !is_goal);
        let cmd = self.io.drive(obs, pose, &scan, steer);
        let mode = if phase == "follow" || phase == "no-path" {
            format!("rrt-{phase}")
        } else {
            format!("rrt-replan-{phase}")
        };
        self.debug.global_path.clone_from(&self.path);
        self.debug.keypoints = if self.record {
            self.raw.clone()
        } else {
            Vec::new()
        };
        let mut dbg = std::mem::take(&mut self.debug);
        self.io
            .report(&mut dbg, &mode, pose, &scan, target, is_goal, self.record);
        self.debug = dbg;
        cmd
    }

    fn set_goal(
        &mut self,
        _map: &StaticMap,
        _state: &RobotState,
        goal: [f64; 2],
    ) -> Result<(), LocalError> {
        crate::local::dwa::check_goal(goal)?;
        self.path.clear();
        self.raw.clear();
        self.planned_for = None;
        self.retry_at = f64::NEG_INFINITY;
        Ok(())
    }

    fn debug(&self) -> &PlannerDebug {
        &self.debug
    }

    fn set_record_rollouts(&mut self, on: bool) {
        self.record = on;
        self.io.set_record(on);
    }

    fn set_seed(&mut self, seed: u64) {
        self.rng = Rng::new(seed).fork(RRT_STREAM);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lidar::tangent_bug::tests::{build_error, build_on_room, room, run_on};
    use crate::local::testkit::End;

    fn planner(cfg: serde_json::Value) -> Box<dyn LocalPlanner> {
        build_on_room("rrt-shortcut", cfg, RrtShortcut::new).unwrap()
    }

    /// L-sim7's scene: 20 × 14 m, walls x 6–6.3 (y 2–10) and x 12–12.3
    /// (y 4–12).
    fn sim7_room() -> StaticMap {
        room(
            20.0,
            14.0,
            &[[6.0, 2.0, 6.3, 10.0], [12.0, 4.0, 12.3, 12.0]],
        )
    }

    /// A 10 × 8 m room with a 4 m wall across the way, known (2 m gaps
    /// at its ends: room for the 0.8 m planning clearance each side).
    fn walled() -> Memory {
        Memory::known(room(10.0, 8.0, &[[5.0, 2.0, 5.3, 6.0]]).grid().clone())
    }

    const PARAMS: RrtParams = RrtParams {
        goal_bias: 0.05,
        step: 1.0,
        max_iterations: 5000,
    };

    fn plan_on(m: &Memory, seed: u64) -> (PlanGrid, Option<Vec<[f64; 2]>>) {
        let (start, goal) = ([1.5, 4.0], [8.5, 4.0]);
        let free = m.free_space(0.4, 0.8, &[start, goal]);
        let mut rng = Rng::new(seed).fork(RRT_STREAM);
        let raw = rrt(start, goal, m.bounds(), &PARAMS, &mut rng, |a, b| {
            m.segment_free(&free, a, b)
        });
        (free, raw)
    }

    #[test]
    fn rrt_finds_a_path_round_a_wall_on_a_known_map() {
        let m = walled();
        let (free, raw) = plan_on(&m, 7);
        let raw = raw.expect("a path");
        assert_eq!(raw.first(), Some(&[1.5, 4.0]));
        assert_eq!(raw.last(), Some(&[8.5, 4.0]));
        assert!(raw.len() > 3, "not a straight line: {raw:?}");
        for w in raw.windows(2) {
            assert!(hypot(w[1][0] - w[0][0], w[1][1] - w[0][1]) <= 1.0 + 1e-9);
            assert!(m.segment_free(&free, w[0], w[1]), "{w:?}");
        }
        // Round an end of the wall, not through it.
        assert!(raw.iter().any(|p| p[1] > 6.0 || p[1] < 2.0), "{raw:?}");
    }

    #[test]
    fn the_shortcut_path_is_free_and_no_longer_than_the_raw_path() {
        let m = walled();
        for seed in 0..5 {
            let (free, raw) = plan_on(&m, seed);
            let raw = raw.expect("a path");
            let s = regression_search(&raw, |a, b| m.segment_free(&free, a, b));
            assert_eq!(s.first(), raw.first());
            assert_eq!(s.last(), raw.last());
            assert!(s.len() <= raw.len() && s.len() >= 3, "{s:?}");
            for w in s.windows(2) {
                assert!(m.segment_free(&free, w[0], w[1]), "seed {seed}: {w:?}");
            }
            assert!(path_length(&s) <= path_length(&raw) + 1e-9, "seed {seed}");
            // Round one end of the wall (≈ 9.3 m past its corner at the
            // planning clearance): not a wandering tree path.
            assert!(path_length(&s) < 11.0, "seed {seed}: {}", path_length(&s));
        }
    }

    #[test]
    fn rrt_is_deterministic_for_a_seed() {
        let m = walled();
        let a = plan_on(&m, 3).1.unwrap();
        assert_eq!(a, plan_on(&m, 3).1.unwrap());
        assert_ne!(a, plan_on(&m, 4).1.unwrap(), "the seed drives the sampler");
    }

    #[test]
    fn the_memory_holds_hits_as_occupied_and_rays_as_free() {
        let mut m = Memory::covering([0.0, 0.0], [10.0, 4.0], 0.1, None).unwrap();
        // Beam 0 (east) hits at 3 m, beam 1 (north) has no return (2 m range).
        let scan = Scan::new(vec![3.0, f64::INFINITY, f64::INFINITY, f64::INFINITY], 2.0);
        let fresh = m.integrate([1.05, 1.05, 0.0], &scan);
        assert!(fresh.is_empty(), "3 m is beyond the 2 m range: no return");
        let scan = Scan::new(vec![3.0, f64::INFINITY, f64::INFINITY, f64::INFINITY], 5.0);
        let fresh = m.integrate([1.05, 1.05, 0.0], &scan);
        assert_eq!(fresh.len(), 1);
        assert!((fresh[0][0] - 4.05).abs() < 1e-9 && (fresh[0][1] - 1.05).abs() < 1e-9);
        let g = m.grid();
        let at = |x: f64, y: f64| {
            let (c, r) = g.world_to_cell(x, y).unwrap();
            g.get(c, r).unwrap()
        };
        assert_eq!(at(4.05, 1.05), Cell::Occupied);
        assert_eq!(at(2.5, 1.05), Cell::Free);
        assert_eq!(at(1.05, 3.5), Cell::Free, "the north beam, cut at the box");
        assert_eq!(at(6.0, 3.0), Cell::Unknown);
        // Seen again: nothing new; a later ray does not clear the hit.
        assert!(m.integrate([1.05, 1.05, 0.0], &scan).is_empty());
        let through = Scan::new(vec![5.0, f64::INFINITY, f64::INFINITY, f64::INFINITY], 5.0);
        m.integrate([1.05, 1.05, 0.0], &through);
        assert_eq!(m.grid().get(40, 29), Some(Cell::Occupied));
        // Growing the box keeps what was seen.
        let big = Memory::covering([-5.0, -5.0], [15.0, 9.0], 0.1, Some(&m)).unwrap();
        let (c, r) = big.grid().world_to_cell(4.05, 1.05).unwrap();
        assert_eq!(big.grid().get(c, r), Some(Cell::Occupied));
    }

    #[test]
    fn rrt_shortcut_reaches_the_goal_past_two_offset_walls_without_collision() {
        // Unknown to the planner: it sees it only through the scan.
        let map = sim7_room();
        for seed in [0, 1] {
            let mut p = planner(serde_json::json!({}));
            p.set_seed(seed);
            let r = run_on(p.as_mut(), &map, [2.0, 6.0], [18.0, 8.0], 150.0);
            assert_eq!(r.end, End::Reached, "seed {seed}: {:?}", r.states.last());
            assert!(r.min_clearance > 0.0, "seed {seed}");
            assert!(r.modes.iter().any(|m| m.starts_with("rrt-follow")));
            assert!(
                r.modes.iter().all(|m| !m.starts_with("rrt-no-path")),
                "seed {seed}"
            );
        }
    }

    #[test]
    fn rrt_shortcut_is_deterministic() {
        let map = sim7_room();
        let runs: Vec<_> = (0..2)
            .map(|_| {
                let mut p = planner(serde_json::json!({}));
                p.set_seed(9);
                run_on(p.as_mut(), &map, [2.0, 6.0], [18.0, 8.0], 150.0)
            })
            .collect();
        assert_eq!(runs[0].states, runs[1].states);
        assert_eq!(runs[0].modes, runs[1].modes);
    }

    #[test]
    fn bad_rrt_shortcut_settings_name_the_field() {
        let build = |cfg| build_error("rrt-shortcut", cfg, RrtShortcut::new);
        assert!(build(serde_json::json!({"goal_bias": 1.5})).contains("rrt-shortcut.goal_bias"));
        assert!(build(serde_json::json!({"goal_bias": -0.1})).contains("rrt-shortcut.goal_bias"));
        assert!(build(serde_json::json!({"step": 0.0})).contains("rrt-shortcut.step"));
        assert!(build(serde_json::json!({"max_iterations": 0})).contains("max_iterations"));
        assert!(build(serde_json::json!({"memory_resolution": 0.0})).contains("memory_resolution"));
        assert!(build(serde_json::json!({"deviation": -1.0})).contains("rrt-shortcut.deviation"));
        assert!(build(serde_json::json!({"step": "x"})).contains("rrt-shortcut.config.step"));
        assert!(build(serde_json::json!({"lidar": {"range": 0.0}})).contains("lidar.range"));
        assert!(build(serde_json::json!({"nope": 1})).contains("unknown field"));
    }
}
