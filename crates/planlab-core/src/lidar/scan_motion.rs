//! The sensing and motion layer the \[L\] peers (`tangent-bug`, `rs-apf`,
//! `rrt-shortcut`) share with `lidar-dwa`: the simulated LiDAR on the map
//! and the perceived movers, and the baseline DWA driving to a point on the
//! **local map built from the scan alone**
//! ([`scan_local_map`](super::planner::scan_local_map)), robot at the
//! origin, heading 0, no movers.
//!
//! Unlike `lidar-dwa`'s navigator, the peers also read the robot's pose
//! (odometry): Bug algorithms keep distances along their path. They never
//! read the map:
//! only [`ScanMotion::sense`] does, through the sensor.

use super::nav::Velocity;
use super::planner::{drive_on_scan, lidar_err, LocalMapConfig, MOTION_GOAL};
use super::scan::{beam_angle, polar, Lidar, LidarConfig, Scan};
use super::TargetKind;
use crate::local::dwa::{Dwa, DwaConfig};
use crate::local::{GoalKind, LocalError, LocalPlanner, Observation, PlannerDebug};
use crate::num::{cos, hypot, sin};
use crate::world::{Command, RobotSpec};

/// The DWA the peers drive with by default: the baseline DWA with α 0.2,
/// the weight the \[L\] presets run `lidar-dwa` with, so navigator and
/// peers differ only above the motion layer. (With the MATLAB sample's
/// α 0.05 the clearance and speed critics outweigh the heading and the
/// robot circles in open space.)
pub fn peer_dwa() -> DwaConfig {
    DwaConfig {
        alpha: 0.2,
        ..DwaConfig::default()
    }
}

/// Sensor + motion planner on the scan's local map (module doc).
pub struct ScanMotion {
    lidar: Lidar,
    motion: Box<dyn LocalPlanner>,
    local: LocalMapConfig,
    /// Consecutive hits closer than this are joined on the local map, m.
    join: f64,
    time: f64,
}

impl std::fmt::Debug for ScanMotion {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ScanMotion")
            .field("motion", &self.motion.name())
            .finish_non_exhaustive()
    }
}

impl ScanMotion {
    /// The sensor `lidar` and the baseline DWA `motion` on the local map
    /// `local` for `robot`, as the peers drive; configs are validated
    /// (errors name `lidar.field`, `local.field`, `dwa.field`).
    pub fn with_dwa(
        lidar: LidarConfig,
        local: LocalMapConfig,
        motion: DwaConfig,
        robot: &RobotSpec,
    ) -> Result<ScanMotion, LocalError> {
        let lidar = Lidar::new(lidar, "lidar").map_err(lidar_err)?;
        local.validate("local").map_err(lidar_err)?;
        let motion = Box::new(Dwa::new(motion, robot, MOTION_GOAL)?);
        Ok(ScanMotion {
            lidar,
            motion,
            local,
            join: 2.0 * robot.footprint.circumscribed_radius(),
            time: 0.0,
        })
    }

    /// The sensor's range limit, m.
    pub fn range(&self) -> f64 {
        self.lidar.config().range
    }

    /// Scans from the robot's pose: (pose (x, y, θ), scan).
    pub fn sense(&mut self, obs: &Observation<'_>) -> ([f64; 3], Scan) {
        let s = obs.state;
        ([s.x, s.y, s.theta], self.lidar.observe(obs))
    }

    /// One command of the motion planner steering to `steer` (world m) on
    /// the local map of `scan` taken at `pose`.
    pub fn drive(
        &mut self,
        obs: &Observation<'_>,
        pose: [f64; 3],
        scan: &Scan,
        steer: [f64; 2],
    ) -> Command {
        let (c, s) = (cos(pose[2]), sin(pose[2]));
        let (dx, dy) = (steer[0] - pose[0], steer[1] - pose[1]);
        let mut goal = [c * dx + s * dy, -s * dx + c * dy];
        if !(goal[0].is_finite() && goal[1].is_finite()) {
            goal = [0.0, 0.0];
        }
        let v = Velocity {
            v: obs.state.v,
            vy: obs.state.vy,
            w: obs.state.w,
        };
        drive_on_scan(
            self.motion.as_mut(),
            scan,
            (&self.local, self.join),
            &v,
            obs.dt,
            &mut self.time,
            goal,
        )
    }

    /// The motion planner's debug (robot frame).
    pub fn motion_debug(&self) -> &PlannerDebug {
        self.motion.debug()
    }

    /// Record the motion planner's rollouts or not.
    pub fn set_record(&mut self, on: bool) {
        self.motion.set_record_rollouts(on);
    }

    /// Ends a peer's step in `d`: mode `phase/<motion planner's mode>`,
    /// the target (world) as the current goal, final when `is_goal`, and
    /// [`ScanMotion::fill_debug`].
    #[allow(clippy::too_many_arguments)]
    pub fn report(
        &self,
        d: &mut PlannerDebug,
        phase: &str,
        pose: [f64; 3],
        scan: &Scan,
        target: [f64; 2],
        is_goal: bool,
        record: bool,
    ) {
        d.mode = format!("{phase}/{}", self.motion.debug().mode);
        d.current_goal = target;
        let kind = if is_goal {
            d.goal_kind = GoalKind::Final;
            TargetKind::Global
        } else {
            d.goal_kind = GoalKind::Temporary;
            TargetKind::Temporary
        };
        self.fill_debug(d, pose, scan, target, kind, record);
    }

    /// Fills `d` for drawing: the motion planner's critics and (when
    /// `record`) rollouts in world coordinates, and the scan.
    pub fn fill_debug(
        &self,
        d: &mut PlannerDebug,
        pose: [f64; 3],
        scan: &Scan,
        target: [f64; 2],
        kind: TargetKind,
        record: bool,
    ) {
        let (c, s) = (cos(pose[2]), sin(pose[2]));
        let world = |p: [f64; 2]| [pose[0] + c * p[0] - s * p[1], pose[1] + s * p[0] + c * p[1]];
        let md = self.motion.debug();
        d.critics.clone_from(&md.critics);
        d.weights.clone_from(&md.weights);
        d.chosen = md.chosen;
        d.rollouts.clear();
        if record {
            for r in &md.rollouts {
                let mut r = r.clone();
                for p in &mut r.points {
                    *p = world(*p);
                }
                d.rollouts.push(r);
            }
        }
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
        ld.target = target;
        ld.kind = kind;
        d.lidar = Some(ld);
    }
}

/// The point the motion planner steers to for `target` seen from `x`: a
/// waypoint (`extend`) nearer than `lookahead` is pushed out to
/// `lookahead` along its bearing (a DWA heading critic aimed at a point
/// nearer than its rollouts reach makes the robot circle it).
pub fn steer_point(x: [f64; 2], target: [f64; 2], lookahead: f64, extend: bool) -> [f64; 2] {
    let d = hypot(target[0] - x[0], target[1] - x[1]);
    if extend && d > 1e-9 && d < lookahead {
        let k = lookahead / d;
        [x[0] + (target[0] - x[0]) * k, x[1] + (target[1] - x[1]) * k]
    } else {
        target
    }
}

/// The hit points of `scan` taken at `pose`, world m (None: no return).
pub fn world_points(pose: [f64; 3], scan: &Scan) -> Vec<Option<[f64; 2]>> {
    let n = scan.len();
    scan.ranges()
        .iter()
        .enumerate()
        .map(|(i, &r)| {
            r.is_finite().then(|| {
                let p = polar(pose[2] + beam_angle(i, n), r);
                [pose[0] + p[0], pose[1] + p[1]]
            })
        })
        .collect()
}

/// How far a disc of radius `rho` centred at `x` can move along the unit
/// direction `u` before it touches a point of `pts` (`INFINITY` if none is
/// in the way).
pub fn free_length(x: [f64; 2], u: [f64; 2], pts: &[Option<[f64; 2]>], rho: f64) -> f64 {
    let mut best = f64::INFINITY;
    for p in pts.iter().flatten() {
        let (dx, dy) = (p[0] - x[0], p[1] - x[1]);
        let along = dx * u[0] + dy * u[1];
        let across = dx * u[1] - dy * u[0];
        if across.abs() >= rho {
            continue;
        }
        let back = (rho * rho - across * across).sqrt();
        if along + back <= 0.0 {
            continue; // wholly behind
        }
        best = best.min((along - back).max(0.0));
    }
    best
}

/// \[11\]'s regression search, the greedy line-of-sight shortcut `rs-apf`
/// and `rrt-shortcut` share: from the last point back to the first, join
/// each point to the earliest one `free` says is reachable straight (the
/// previous point when none is). The result keeps the ends and is never
/// longer than `path` (each join replaces a sub-path by a straight line).
pub fn regression_search<P: Copy>(path: &[P], free: impl Fn(P, P) -> bool) -> Vec<P> {
    let Some(&last) = path.last() else {
        return Vec::new();
    };
    let mut out = vec![last];
    let mut j = path.len() - 1;
    while j > 0 {
        let i = (0..j).find(|&i| free(path[i], path[j])).unwrap_or(j - 1);
        out.push(path[i]);
        j = i;
    }
    out.reverse();
    out
}
