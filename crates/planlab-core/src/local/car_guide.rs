//! A car-like global path for the local planners (docs/algorithms.md
//! §car-global): a scenario's `global_planner` section plans a Hybrid A*
//! path ([`crate::car::hybrid_astar`]) from the robot's pose to the goal,
//! and the local planner steers to a point of it a look-ahead distance
//! ahead (a "carrot", as pure pursuit does) instead of straight at the goal.
//!
//! - **Path**: Hybrid A* on the map the planner knows, from the robot's
//!   pose (its heading too) to the goal with heading `goal_yaw` (default:
//!   the direction from the start to the goal), with the robot's footprint
//!   grown by `margin_m` on every side (a disc, or a rectangle checked by
//!   the discs covering it); the poses resampled every
//!   map cell (the scenario's resolution) are the waypoints, the last one
//!   the exact goal.
//! - **Carrot**: the robot's progress is the nearest waypoint at or after
//!   the previous progress, within the next `2 · lookahead_m` + (the
//!   robot's distance from the previous progress point) of path, and not
//!   past the next cusp; the carrot is the waypoint `lookahead_m` further
//!   along the path (the cusp or the goal when the path ends before).
//! - **Replanning**: when the goal moves, and when the planner's map
//!   changes (laser perception) so that a waypoint still ahead has less
//!   clearance than the robot's radius — the rule the DWA family's own
//!   routes follow. A failed replan after a map change keeps the old path.
//!
//! Only local planners that steer to the goal they are given and plan no
//! route of their own can follow the carrot ([`FOLLOWERS`]); the others are
//! refused with a typed error.

use super::{GoalKind, LocalError, PlannerDebug};
use crate::car::hybrid_astar::{plan_hybrid_astar, HybridAStarConfig};
use crate::car::{CarError, Pose};
use crate::num::{atan2, fmt_num, hypot};
use crate::world::{Footprint, RobotState, StaticMap};
use serde::{Deserialize, Serialize};

/// Local planners that steer to the observation's goal and keep no global
/// route of their own: the ones a car path can guide.
pub const FOLLOWERS: [&str; 8] = [
    "dwa",
    "apf",
    "sampling-apf",
    "lidar-dwa",
    "lidar-apf",
    "scan-dwa",
    "scan-apf",
    "tangent-bug",
];

/// Default extra clearance of the planned path over the robot's radius, m
/// (planlab's value): room for the local planner's tracking error.
pub const DEFAULT_MARGIN_M: f64 = 0.1;

/// Default look-ahead of the carrot, m (planlab's value: about what the
/// DWA's 2 s rollouts reach at its 0.5 m/s top speed).
pub const DEFAULT_LOOKAHEAD_M: f64 = 1.0;

/// Which global planner.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum GlobalAlgorithm {
    /// Hybrid A* over car poses (Dolgov et al. 2008).
    #[serde(rename = "hybrid-astar")]
    HybridAStar,
}

fn default_margin() -> f64 {
    DEFAULT_MARGIN_M
}

fn default_lookahead() -> f64 {
    DEFAULT_LOOKAHEAD_M
}

/// A scenario's `global_planner` section: a car-like global path the local
/// planner follows.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GlobalPlannerSpec {
    /// The planner: `hybrid-astar`.
    pub algorithm: GlobalAlgorithm,
    /// Minimum turning radius of the path, m (required: no default radius
    /// fits every robot).
    pub turning_radius_m: f64,
    /// Whether the path may reverse (Reeds-Shepp instead of Dubins curves).
    #[serde(default)]
    pub reverse: bool,
    /// Heading at the goal, rad; default: the direction from the start to
    /// the goal (from the robot to the new goal when it moves).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub goal_yaw: Option<f64>,
    /// Extra clearance over the robot's circumscribed radius, m
    /// (default [`DEFAULT_MARGIN_M`]).
    #[serde(default = "default_margin")]
    pub margin_m: f64,
    /// Carrot distance along the path, m (default [`DEFAULT_LOOKAHEAD_M`]).
    #[serde(default = "default_lookahead")]
    pub lookahead_m: f64,
}

impl GlobalPlannerSpec {
    /// A Hybrid A* section with `turning_radius_m` and the defaults.
    pub fn hybrid_astar(turning_radius_m: f64, reverse: bool) -> Self {
        Self {
            algorithm: GlobalAlgorithm::HybridAStar,
            turning_radius_m,
            reverse,
            goal_yaw: None,
            margin_m: DEFAULT_MARGIN_M,
            lookahead_m: DEFAULT_LOOKAHEAD_M,
        }
    }

    /// Checks every number; the error names the field
    /// (`global_planner.turning_radius_m`, …).
    pub fn validate(&self) -> Result<(), LocalError> {
        let bad = |name: &str, unit: &str, v: f64, what: &str| {
            Err(LocalError::InvalidParameter(format!(
                "global_planner.{name} = {} {unit}: must be {what}",
                fmt_num(v)
            )))
        };
        let r = self.turning_radius_m;
        if !(r.is_finite() && r > 0.0) {
            return bad("turning_radius_m", "m", r, "a finite number > 0");
        }
        if let Some(y) = self.goal_yaw {
            if !y.is_finite() {
                return bad("goal_yaw", "rad", y, "a finite number");
            }
        }
        let m = self.margin_m;
        if !(m.is_finite() && m >= 0.0) {
            return bad("margin_m", "m", m, "a finite number ≥ 0");
        }
        let l = self.lookahead_m;
        if !(l.is_finite() && l > 0.0) {
            return bad("lookahead_m", "m", l, "a finite number > 0");
        }
        Ok(())
    }

    /// Checks that local planner `name` can follow the path.
    pub fn check_follower(&self, name: &str) -> Result<(), LocalError> {
        if FOLLOWERS.contains(&name) {
            Ok(())
        } else {
            Err(LocalError::InvalidParameter(format!(
                "global_planner hybrid-astar guides a local planner that steers to the goal it is given ({}); `{name}` plans its own global route",
                FOLLOWERS.join(", ")
            )))
        }
    }
}

/// A planned car path.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CarRoute {
    /// Waypoints: the path's poses every map cell, first the robot's pose,
    /// last the exact goal.
    pub poses: Vec<Pose>,
    /// For each waypoint, whether it is reached driving forward.
    pub forward: Vec<bool>,
    /// Length of the Hybrid A* path, m.
    pub length: f64,
    /// Forward/reverse switches.
    pub cusps: usize,
    /// Poses Hybrid A* expanded.
    pub expanded: usize,
    /// The margin planned with, m: the section's, or 0 when the start was
    /// too close to a wall for it.
    pub margin_m: f64,
}

impl CarRoute {
    /// The waypoints' positions.
    pub fn points(&self) -> Vec<[f64; 2]> {
        self.poses.iter().map(|p| [p.x, p.y]).collect()
    }
}

/// Plans the car path of `spec` on `map` from `from` to `goal` with heading
/// `goal_yaw`, for a robot of footprint `body` grown by the margin. A start
/// too close to a wall for the margin (the robot drove there) is planned
/// again without the margin. Errors: [`LocalError::NoGlobalPath`] naming
/// Hybrid A*'s reason.
pub fn plan_car_route(
    map: &StaticMap,
    spec: &GlobalPlannerSpec,
    body: &Footprint,
    from: Pose,
    goal: [f64; 2],
    goal_yaw: f64,
) -> Result<CarRoute, LocalError> {
    spec.validate()?;
    let grid = map.solid();
    let cfg = |margin: f64| {
        let (footprint_radius, footprint_rect) = match *body {
            Footprint::Circle { radius } => (radius + margin, None),
            Footprint::Rectangle { length, width } => (
                body.circumscribed_radius() + margin,
                Some((length + 2.0 * margin, width + 2.0 * margin)),
            ),
        };
        HybridAStarConfig {
            turning_radius: spec.turning_radius_m,
            reverse: spec.reverse,
            footprint_radius,
            footprint_rect,
            ..HybridAStarConfig::default()
        }
    };
    let to = Pose::new(goal[0], goal[1], goal_yaw);
    let (path, margin) = match plan_hybrid_astar(&grid, from, to, &cfg(spec.margin_m)) {
        Err(CarError::InCollision { .. }) if spec.margin_m > 0.0 => {
            (plan_hybrid_astar(&grid, from, to, &cfg(0.0)), 0.0)
        }
        other => (other, spec.margin_m),
    };
    let path = path.map_err(|e| LocalError::NoGlobalPath(format!("hybrid-astar: {e}")))?;
    // Resample every cell of arc length; cusps are kept (the path turns
    // back there).
    let step = grid.resolution();
    let mut poses = vec![path.poses[0]];
    let mut forward = vec![path.forward[0]];
    let mut since = 0.0;
    for i in 1..path.poses.len() {
        let (a, b) = (path.poses[i - 1], path.poses[i]);
        since += hypot(b.x - a.x, b.y - a.y);
        let cusp = path
            .forward
            .get(i + 1)
            .is_some_and(|&f| f != path.forward[i]);
        if since >= step - 1e-9 || cusp || i + 1 == path.poses.len() {
            poses.push(b);
            forward.push(path.forward[i]);
            since = 0.0;
        }
    }
    // A path ending in the goal's cell and heading bin (no exact shot)
    // stops short of the goal: the goal itself is the last waypoint.
    let last = poses[poses.len() - 1];
    if hypot(last.x - goal[0], last.y - goal[1]) > 1e-9 {
        poses.push(to);
        forward.push(true);
    }
    Ok(CarRoute {
        poses,
        forward,
        length: path.length,
        cusps: path.cusps,
        expanded: path.expanded,
        margin_m: margin,
    })
}

/// Follows a [`CarRoute`]: the carrot each step, replans on goal and map
/// changes (see the module doc). Kept by the episode beside its local
/// planner.
#[derive(Clone, Debug)]
pub struct CarGuide {
    spec: GlobalPlannerSpec,
    body: Footprint,
    robot_radius: f64,
    goal_yaw: f64,
    route: CarRoute,
    /// Waypoint the robot has reached.
    progress: usize,
    /// The carrot's waypoint.
    carrot: usize,
    revision: u64,
    /// Paths planned after the first (goal moves, map changes).
    replans: usize,
    /// The local planner's debug with the car path in it.
    debug: PlannerDebug,
}

impl CarGuide {
    /// Plans the path from `start` to `goal` on `map` for a robot of
    /// footprint `body`.
    pub fn new(
        spec: GlobalPlannerSpec,
        body: Footprint,
        map: &StaticMap,
        start: &RobotState,
        goal: [f64; 2],
    ) -> Result<Self, LocalError> {
        spec.validate()?;
        let goal_yaw = spec
            .goal_yaw
            .unwrap_or_else(|| atan2(goal[1] - start.y, goal[0] - start.x));
        let from = Pose::new(start.x, start.y, start.theta);
        let route = plan_car_route(map, &spec, &body, from, goal, goal_yaw)?;
        Ok(Self {
            spec,
            body,
            robot_radius: body.circumscribed_radius(),
            goal_yaw,
            route,
            progress: 0,
            carrot: 0,
            revision: 0,
            replans: 0,
            debug: PlannerDebug::default(),
        })
    }

    /// The section it follows.
    pub fn spec(&self) -> &GlobalPlannerSpec {
        &self.spec
    }

    /// The path in force.
    pub fn route(&self) -> &CarRoute {
        &self.route
    }

    /// Paths planned after the first (goal moves, map changes).
    pub fn replans(&self) -> usize {
        self.replans
    }

    /// The goal heading the path ends with, rad.
    pub fn goal_yaw(&self) -> f64 {
        self.goal_yaw
    }

    /// Replans from `state` to a moved `goal` (heading: the section's
    /// `goal_yaw`, else from the robot to the goal). On error the old path
    /// stays.
    pub fn retarget(
        &mut self,
        map: &StaticMap,
        state: &RobotState,
        goal: [f64; 2],
    ) -> Result<(), LocalError> {
        let yaw = self
            .spec
            .goal_yaw
            .unwrap_or_else(|| atan2(goal[1] - state.y, goal[0] - state.x));
        let from = Pose::new(state.x, state.y, state.theta);
        self.route = plan_car_route(map, &self.spec, &self.body, from, goal, yaw)?;
        self.goal_yaw = yaw;
        self.progress = 0;
        self.carrot = 0;
        self.replans += 1;
        Ok(())
    }

    /// The goal the local planner steers to this step: the carrot for the
    /// robot at `state` on `map` (revision `revision`), replanning first
    /// when the map changed under the path ahead.
    pub fn carrot(
        &mut self,
        map: &StaticMap,
        revision: u64,
        state: &RobotState,
        goal: [f64; 2],
    ) -> [f64; 2] {
        if revision != self.revision {
            self.revision = revision;
            let ahead: Vec<[f64; 2]> = self.route.poses[self.progress..]
                .iter()
                .map(|p| [p.x, p.y])
                .collect();
            if super::dwa::route_blocked(map, &ahead, self.robot_radius) {
                let from = Pose::new(state.x, state.y, state.theta);
                if let Ok(r) =
                    plan_car_route(map, &self.spec, &self.body, from, goal, self.goal_yaw)
                {
                    self.route = r;
                    self.progress = 0;
                    self.replans += 1;
                }
            }
        }
        let wp = &self.route.poses;
        let last = wp.len() - 1;
        // Not past the next cusp: the robot turns back there.
        let fwd = &self.route.forward;
        let cusp = (self.progress + 1..=last)
            .find(|&i| i < last && fwd[i + 1] != fwd[i])
            .unwrap_or(last);
        let at = |i: usize| hypot(wp[i].x - state.x, wp[i].y - state.y);
        let step = |i: usize| hypot(wp[i].x - wp[i - 1].x, wp[i].y - wp[i - 1].y);
        // A robot thrown off the path looks as far ahead as it is off.
        let reach = 2.0 * self.spec.lookahead_m + at(self.progress);
        let mut along = 0.0;
        let mut best = (at(self.progress), self.progress);
        for i in self.progress + 1..=cusp {
            along += step(i);
            if along > reach {
                break;
            }
            let d = at(i);
            if d < best.0 {
                best = (d, i);
            }
        }
        self.progress = best.1;
        // The carrot: look-ahead along the path from the progress point.
        let mut along = 0.0;
        self.carrot = cusp;
        for i in self.progress + 1..=cusp {
            along += step(i);
            if along >= self.spec.lookahead_m {
                self.carrot = i;
                break;
            }
        }
        if self.carrot == last {
            goal
        } else {
            [wp[self.carrot].x, wp[self.carrot].y]
        }
    }

    /// Copies the local planner's debug of this step with the car path and
    /// the carrot's kind in it.
    pub fn annotate(&mut self, inner: &PlannerDebug) {
        self.debug.clone_from(inner);
        self.debug.global_path = self.route.points();
        if self.carrot + 1 < self.route.poses.len() {
            self.debug.goal_kind = GoalKind::Intermediate;
        }
    }

    /// The local planner's last debug with the car path.
    pub fn debug(&self) -> &PlannerDebug {
        &self.debug
    }
}
