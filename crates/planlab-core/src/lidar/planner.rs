//! The navigator over a pluggable motion planner, as local planners.
//!
//! [`ScanNavigation`] is the robot-side stack: it takes a [`NavInput`]
//! (scan, velocity, goal in the robot frame) and returns a command. The
//! navigator picks the target; the motion planner (a local planner built
//! by the crate's planner catalogue, e.g. `dwa`) drives to it on a **local
//! map built from the scan alone**: a grid in the robot frame centred on the robot whose occupied
//! cells are the scan's hit points, consecutive hits closer than the robot's
//! diameter joined (no robot fits between them and the beams' spacing must
//! not look like a gap). The motion planner is called with the robot at
//! the origin, heading 0, no movers: what moves is in the scan.
//!
//! [`LidarPlanner`] wraps it as a [`LocalPlanner`] for the simulator: its
//! only use of the world is the simulated sensor ([`Lidar::scan`] on the map
//! and the perceived movers) and the conversion of the goal into the robot
//! frame; its debug output goes back to world coordinates for drawing.

use super::edges::Edge;
use super::nav::{LidarNavConfig, NavInput, Navigator, TargetKind, Velocity};
use super::scan::{beam_angle, polar, Lidar, LidarConfig, Scan};
use super::LidarError;
/// The debug data lives in `local` (carried by [`PlannerDebug`]).
pub use crate::local::scan_debug::{CandidateMark, EdgeMark, LidarDebug};
use crate::local::{GoalKind, LocalError, LocalPlanner, Observation, PlannerDebug};
use crate::map::{Cell, OccupancyGrid, Pose2};
use crate::num::{cos, hypot, sin};
use crate::params::Params;
use crate::world::{Command, RobotSpec, RobotState, StaticMap};

crate::params::params! {
    /// The local map the motion planner sees.
    #[derive(Debug, Clone, Copy, PartialEq)]
    pub struct LocalMapConfig {
        /// Must exceed the motion planner's reach; its edge counts as a wall.
        pub half_size: f64 = 5.0, "m" [> 0.0] label "local map half size" "half side of the scan's local map (robot frame)";
        pub resolution: f64 = 0.05, "m" [> 0.0] label "local map cell size" "cell size of the scan's local map";
    }
}

/// Most cells per side of the local map.
pub const MAX_LOCAL_CELLS: f64 = 2000.0;

impl LocalMapConfig {
    pub(crate) fn validate(&self, prefix: &str) -> Result<(), LidarError> {
        self.check_bounds(prefix)?;
        if 2.0 * self.half_size / self.resolution > MAX_LOCAL_CELLS {
            return Err(LidarError::InvalidParameter(format!(
                "{prefix}: 2·half_size / resolution = {}: at most {MAX_LOCAL_CELLS} cells per side",
                2.0 * self.half_size / self.resolution
            )));
        }
        Ok(())
    }
}

crate::params::params! {
    /// Settings of a navigator planner (`lidar-dwa`, `lidar-apf`): sensor,
    /// navigator (\[L\] Table 1), local map and the motion planner's own config.
    #[derive(Debug, Clone, PartialEq)]
    pub struct LidarPlannerConfig<M> {
        pub lidar: LidarConfig = LidarConfig::default(), "" [nested] "the simulated LiDAR";
        pub nav: LidarNavConfig = LidarNavConfig::default(), "" [nested]
            "the temporary-goal navigator";
        pub local: LocalMapConfig = LocalMapConfig::default(), "" [nested]
            "the local map built from the scan";
        pub motion: M = M::default(), "" [nested] "the motion planner's config";
    }
}

crate::params::params! {
    /// Settings of a plain scan-only baseline (`scan-dwa`, `scan-apf`): the
    /// motion planner straight to the goal on the scan's local map.
    #[derive(Debug, Clone, PartialEq)]
    pub struct ScanBaselineConfig<M> {
        pub lidar: LidarConfig = LidarConfig::default(), "" [nested] "the simulated LiDAR";
        pub local: LocalMapConfig = LocalMapConfig::default(), "" [nested]
            "the local map built from the scan";
        pub motion: M = M::default(), "" [nested] "the motion planner's config";
    }
}

/// The goal a motion planner under the navigator is built with, robot
/// frame; it is given the target every step.
pub const MOTION_GOAL: [f64; 2] = [1.0, 0.0];

pub(crate) fn lidar_err(e: LidarError) -> LocalError {
    LocalError::InvalidParameter(e.to_string())
}

/// The robot-side stack: navigator (optional) + motion planner on the
/// scan's local map. Sees nothing but [`NavInput`].
pub struct ScanNavigation {
    nav: Option<Navigator>,
    motion: Box<dyn LocalPlanner>,
    local: LocalMapConfig,
    /// Consecutive hits closer than this are joined, m.
    join: f64,
    time: f64,
    target: [f64; 2],
    /// The point the motion planner steers to (the target, or further
    /// along its bearing).
    steer: [f64; 2],
    kind: TargetKind,
}

impl std::fmt::Debug for ScanNavigation {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ScanNavigation")
            .field("motion", &self.motion.name())
            .field("target", &self.target)
            .finish_non_exhaustive()
    }
}

impl ScanNavigation {
    /// Builds the stack: `nav` (None = plain motion planner to the goal)
    /// over `motion`, a motion planner built for `robot` (and
    /// [`MOTION_GOAL`]), on the local map `local`.
    pub fn new(
        nav: Option<Navigator>,
        motion: Box<dyn LocalPlanner>,
        robot: &RobotSpec,
        local: LocalMapConfig,
    ) -> Result<ScanNavigation, LocalError> {
        local.validate("local").map_err(lidar_err)?;
        Ok(ScanNavigation {
            nav,
            motion,
            local,
            join: 2.0 * robot.footprint.circumscribed_radius(),
            time: 0.0,
            target: [0.0, 0.0],
            steer: [0.0, 0.0],
            kind: TargetKind::Global,
        })
    }

    /// One control period: the command.
    pub fn step(&mut self, input: &NavInput<'_>) -> Command {
        let target = match self.nav.as_mut() {
            Some(n) => {
                let t = n.step(input);
                self.kind = n.debug().kind;
                let d = hypot(t[0], t[1]);
                let look = n.config().lookahead;
                if self.kind != TargetKind::Global && d > 1e-9 && d < look {
                    self.steer = [t[0] * look / d, t[1] * look / d];
                } else {
                    self.steer = t;
                }
                t
            }
            None => {
                self.kind = TargetKind::Global;
                self.steer = input.goal;
                input.goal
            }
        };
        let steer = self.steer;
        let target = if target[0].is_finite() && target[1].is_finite() {
            target
        } else {
            [0.0, 0.0]
        };
        self.target = target;
        let goal = if steer[0].is_finite() && steer[1].is_finite() {
            steer
        } else {
            target
        };
        drive_on_scan(
            self.motion.as_mut(),
            input.scan,
            (&self.local, self.join),
            &input.velocity,
            input.dt,
            &mut self.time,
            goal,
        )
    }

    /// The navigator, when there is one.
    pub fn navigator(&self) -> Option<&Navigator> {
        self.nav.as_ref()
    }

    /// The motion planner's debug (robot frame).
    pub fn motion_debug(&self) -> &PlannerDebug {
        self.motion.debug()
    }

    /// Target of the last step, robot frame, and its kind.
    pub fn target(&self) -> ([f64; 2], TargetKind) {
        (self.target, self.kind)
    }

    /// Forget the navigator's mode and hold (the goal moved).
    pub fn reset(&mut self) {
        if let Some(n) = self.nav.as_mut() {
            n.reset();
        }
    }

    /// Record the motion planner's rollouts or not.
    pub fn set_record(&mut self, on: bool) {
        self.motion.set_record_rollouts(on);
    }
}

/// One command of `motion` driving to `goal` (robot frame) on the local
/// map of `scan` (`local` config, hits closer than `join` joined): robot at
/// the origin, heading 0, no movers. Non-finite velocities count as 0 and
/// a bad `dt` as 0.1 s; `time` advances by the step. What `lidar-dwa`'s
/// stack and the \[L\] peers' [`super::scan_motion::ScanMotion`] share.
pub(crate) fn drive_on_scan(
    motion: &mut dyn LocalPlanner,
    scan: &Scan,
    (local, join): (&LocalMapConfig, f64),
    velocity: &Velocity,
    dt: f64,
    time: &mut f64,
    goal: [f64; 2],
) -> Command {
    let Ok(map) = scan_local_map(scan, local, join) else {
        return Command::default();
    };
    let state = RobotState {
        v: finite_or_zero(velocity.v),
        vy: finite_or_zero(velocity.vy),
        w: finite_or_zero(velocity.w),
        ..Default::default()
    };
    let dt = if dt.is_finite() && dt > 0.0 { dt } else { 0.1 };
    let obs = Observation {
        time: *time,
        dt,
        state: &state,
        goal,
        map: &map,
        map_revision: 0,
        scan: None,
        movers: &[],
        odometry: None,
        accel_z: 0.0,
    };
    *time += dt;
    motion.step(&obs)
}

fn finite_or_zero(x: f64) -> f64 {
    if x.is_finite() {
        x
    } else {
        0.0
    }
}

fn local_dims(cfg: &LocalMapConfig) -> usize {
    ((2.0 * cfg.half_size / cfg.resolution).ceil() as usize).max(1)
}

/// The local map of a scan: robot frame, robot at the centre; hit points
/// occupied, consecutive hits closer than `join` joined by a line.
pub fn scan_local_map(
    scan: &Scan,
    cfg: &LocalMapConfig,
    join: f64,
) -> Result<StaticMap, LocalError> {
    let n = local_dims(cfg);
    let res = cfg.resolution;
    let half = cfg.half_size;
    let mut cells = vec![Cell::Free; n * n];
    let mut mark = |p: [f64; 2]| {
        let (c, u) = (((p[0] + half) / res).floor(), ((p[1] + half) / res).floor());
        if c >= 0.0 && u >= 0.0 && (c as usize) < n && (u as usize) < n {
            cells[(n - 1 - u as usize) * n + c as usize] = Cell::Occupied;
        }
    };
    let m = scan.len();
    let r = scan.ranges();
    let pt = |i: usize| polar(beam_angle(i, m), r[i]);
    for i in 0..m {
        if !r[i].is_finite() {
            continue;
        }
        let p = pt(i);
        mark(p);
        let j = (i + 1) % m;
        if j != i && r[j].is_finite() {
            let q = pt(j);
            let len = super::scan::dist(p, q);
            if len < join {
                let steps = (len / (0.5 * res)).ceil() as usize;
                for k in 1..steps {
                    let f = k as f64 / steps as f64;
                    mark([p[0] + (q[0] - p[0]) * f, p[1] + (q[1] - p[1]) * f]);
                }
            }
        }
    }
    let grid = OccupancyGrid::from_cells(n, n, cells)
        .and_then(|g| {
            g.with_frame(
                res,
                Pose2 {
                    x: -half,
                    y: -half,
                    yaw: 0.0,
                },
            )
        })
        .map_err(|e| LocalError::InvalidParameter(format!("local map: {e}")))?;
    StaticMap::new(grid, true).map_err(|e| LocalError::InvalidParameter(format!("local map: {e}")))
}

/// The navigator stack as a simulator local planner (see the module doc).
#[derive(Debug)]
pub struct LidarPlanner {
    name: &'static str,
    lidar: Lidar,
    stack: ScanNavigation,
    record: bool,
    debug: PlannerDebug,
    /// Sensor pose and scan of the last step.
    last: Option<([f64; 3], Scan)>,
}

impl LidarPlanner {
    /// The navigator `nav` (None: plain baseline) over the motion planner
    /// `motion` (built for `robot` and [`MOTION_GOAL`]) with the sensor
    /// `lidar`, registered as `name`.
    pub fn new(
        name: &'static str,
        lidar: LidarConfig,
        nav: Option<LidarNavConfig>,
        local: LocalMapConfig,
        motion: Box<dyn LocalPlanner>,
        robot: &RobotSpec,
    ) -> Result<LidarPlanner, LocalError> {
        let lidar = Lidar::new(lidar, "lidar").map_err(lidar_err)?;
        let nav = nav
            .map(|c| Navigator::new(c, "nav"))
            .transpose()
            .map_err(lidar_err)?;
        let stack = ScanNavigation::new(nav, motion, robot, local)?;
        Ok(LidarPlanner {
            name,
            lidar,
            stack,
            record: false,
            debug: PlannerDebug::default(),
            last: None,
        })
    }

    /// A navigator planner of config `cfg` over `motion` (built from
    /// `cfg.motion` by the catalogue).
    pub fn with_nav<M>(
        name: &'static str,
        cfg: &LidarPlannerConfig<M>,
        motion: Box<dyn LocalPlanner>,
        robot: &RobotSpec,
    ) -> Result<LidarPlanner, LocalError> {
        Self::new(name, cfg.lidar, Some(cfg.nav), cfg.local, motion, robot)
    }

    /// A scan-only baseline of config `cfg` over `motion` (built from
    /// `cfg.motion` by the catalogue).
    pub fn baseline<M>(
        name: &'static str,
        cfg: &ScanBaselineConfig<M>,
        motion: Box<dyn LocalPlanner>,
        robot: &RobotSpec,
    ) -> Result<LidarPlanner, LocalError> {
        Self::new(name, cfg.lidar, None, cfg.local, motion, robot)
    }

    /// The robot-side stack.
    pub fn stack(&self) -> &ScanNavigation {
        &self.stack
    }

    /// The last scan and the pose it was taken from.
    pub fn last_scan(&self) -> Option<&([f64; 3], Scan)> {
        self.last.as_ref()
    }

    fn fill_debug(&mut self, pose: [f64; 3], scan: &Scan) {
        let (c, s) = (cos(pose[2]), sin(pose[2]));
        let world = |p: [f64; 2]| [pose[0] + c * p[0] - s * p[1], pose[1] + s * p[0] + c * p[1]];
        let md = self.stack.motion_debug();
        let d = &mut self.debug;
        d.critics.clone_from(&md.critics);
        d.weights.clone_from(&md.weights);
        d.chosen = md.chosen;
        d.rollouts.clear();
        if self.record {
            for r in &md.rollouts {
                let mut r = r.clone();
                for p in &mut r.points {
                    *p = world(*p);
                }
                d.rollouts.push(r);
            }
        }
        let (target, kind) = self.stack.target();
        d.current_goal = world(target);
        d.goal_kind = match kind {
            TargetKind::Global => GoalKind::Final,
            TargetKind::Temporary | TargetKind::Held => GoalKind::Temporary,
        };
        let motion_mode = &md.mode;
        d.mode = match kind {
            TargetKind::Global => motion_mode.clone(),
            TargetKind::Temporary => format!("temp-goal/{motion_mode}"),
            TargetKind::Held => format!("hold/{motion_mode}"),
        };
        let mut ld = d.lidar.take().unwrap_or_default();
        ld.pose = pose;
        ld.max_range = scan.max_range();
        ld.ranges.clear();
        ld.returns.clear();
        for &r in scan.ranges() {
            ld.returns.push(r.is_finite());
            ld.ranges
                .push(if r.is_finite() { r } else { scan.max_range() });
        }
        ld.target = d.current_goal;
        ld.kind = kind;
        ld.edges_raw.clear();
        ld.edges.clear();
        ld.gaps.clear();
        ld.ops_raw.clear();
        ld.ops.clear();
        ld.candidates.clear();
        ld.blocking = None;
        ld.hold_remaining = 0.0;
        ld.hold_period = 0.0;
        if let Some(nav) = self.stack.navigator() {
            let nd = nav.debug();
            ld.hold_remaining = nd.hold_remaining;
            ld.hold_period = if nav.config().hold {
                nav.config().t_h
            } else {
                0.0
            };
            if self.record {
                let n = scan.len();
                let point = |r: &[f64], i: usize| {
                    let i = i % n.max(1);
                    world(polar(beam_angle(i, n), r[i]))
                };
                let marks = |edges: &[Edge], r: &[f64]| -> Vec<EdgeMark> {
                    edges
                        .iter()
                        .enumerate()
                        .filter(|(_, e)| **e != Edge::Null)
                        .map(|(i, &e)| EdgeMark {
                            beam: i,
                            kind: e,
                            point: if e.is_rising() {
                                point(r, i)
                            } else {
                                point(r, i + 1)
                            },
                        })
                        .collect()
                };
                ld.edges_raw = marks(&nd.edges_raw, scan.ranges());
                ld.edges = marks(&nd.edges_mdf, &nd.ranges_mdf);
                ld.gaps = nd
                    .gaps
                    .iter()
                    .map(|g| {
                        [
                            point(scan.ranges(), g.rise),
                            point(scan.ranges(), g.fall + 1),
                        ]
                    })
                    .collect();
                for op in &nd.ops {
                    let pts: Vec<[f64; 2]> =
                        op.points(&nd.ranges_mdf).into_iter().map(world).collect();
                    let mut ext = Vec::with_capacity(pts.len() + 10);
                    if !op.closed {
                        let a0 = beam_angle(op.first, n);
                        for k in (1..=4).rev() {
                            let a = a0 - op.ext_start * k as f64 / 4.0;
                            ext.push(world(polar(a, op.d_first)));
                        }
                    }
                    ext.extend_from_slice(&pts);
                    if !op.closed {
                        let a1 = beam_angle(op.first + op.len - 1, n);
                        for k in 1..=4 {
                            let a = a1 + op.ext_end * k as f64 / 4.0;
                            ext.push(world(polar(a, op.d_last)));
                        }
                    }
                    ld.ops_raw.push(pts);
                    ld.ops.push(ext);
                }
                ld.blocking = nd.blocking;
                ld.candidates = nd
                    .candidates
                    .iter()
                    .map(|c| CandidateMark {
                        point: world(c.point),
                        cost: c.cost,
                        iteration: c.iteration,
                    })
                    .collect();
            }
        }
        d.lidar = Some(ld);
    }
}

impl LocalPlanner for LidarPlanner {
    fn name(&self) -> &'static str {
        self.name
    }

    fn step(&mut self, obs: &Observation<'_>) -> Command {
        let s = obs.state;
        let pose = [s.x, s.y, s.theta];
        let scan = self.lidar.observe(obs);
        // Assumption 2: the goal in the robot frame.
        let (c, sn) = (cos(s.theta), sin(s.theta));
        let (dx, dy) = (obs.goal[0] - s.x, obs.goal[1] - s.y);
        let goal = [c * dx + sn * dy, -sn * dx + c * dy];
        let input = NavInput {
            scan: &scan,
            velocity: Velocity {
                v: s.v,
                vy: s.vy,
                w: s.w,
            },
            goal,
            dt: obs.dt,
        };
        let cmd = self.stack.step(&input);
        self.fill_debug(pose, &scan);
        self.last = Some((pose, scan));
        cmd
    }

    fn set_goal(
        &mut self,
        _map: &StaticMap,
        _state: &RobotState,
        goal: [f64; 2],
    ) -> Result<(), LocalError> {
        crate::local::dwa::check_goal(goal)?;
        self.stack.reset();
        Ok(())
    }

    fn debug(&self) -> &PlannerDebug {
        &self.debug
    }

    fn set_record_rollouts(&mut self, on: bool) {
        self.record = on;
        self.stack.set_record(on);
    }
}
