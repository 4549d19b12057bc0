//! `tangent-bug`: a Bug-family navigator from the scan, the \[L\] sim 6 peer.
//!
//! \[L\] compares its navigator with Critical-PointBug (Das 2016, its
//! reference \[21\]), described there only as a refinement of PointsBug /
//! E-Bug's rules for picking "sudden-change points" on the obstacles around
//! the robot. Those rules are not given in \[L\] and the paper itself could
//! not be read here, so this is **TangentBug** (Kamon, Rivlin & Rimon 1998),
//! the Bug algorithm PointsBug was measured against. **Difference from
//! Critical-PointBug**: its candidate points are every discontinuity of the
//! scan, chosen by the TangentBug heuristic, not Critical-PointBug's
//! filtered critical points.
//!
//! The robot knows its scan, its pose and velocity (odometry) and the goal,
//! never the map — `lidar-dwa`'s assumptions plus the pose, which the
//! boundary-following distances need. Each control period:
//! - **Motion to goal.** If a disc of the footprint's radius + `margin`
//!   can move straight toward the goal for min(d_goal, d_lidar), the target
//!   is the goal. Otherwise the target is the endpoint O_i of the local
//!   tangent graph minimising d(x, O_i) + d(O_i, goal); the endpoints are
//!   the scan's discontinuities (adjacent beams whose ranges differ by more
//!   than `t_jump`, or a hit beside no return), each moved sideways into
//!   the free side by the footprint's radius + `margin` so a disc can pass
//!   it (a point robot would graze it). When that heuristic distance stops
//!   decreasing (exceeds its best of this phase by more than `h_tolerance`),
//!   the robot switches to boundary following, on the side it was going
//!   round.
//! - **Boundary following.** Steer to the point `lookahead` ahead along
//!   the local tangent of the nearest obstacle, on the line
//!   `follow_clearance` off it (footprint to wall), on that side.
//!   d_followed is the smallest distance to the goal of any point of the
//!   followed obstacle sensed so far (the chain of hits joined to the
//!   nearest one by steps < `t_jump`); d_reach is the distance to the goal
//!   of the point the disc can reach straight toward the goal. The robot
//!   leaves when d_reach < d_followed.
//!
//! **Motion layer**: the target is handed to the baseline DWA (`motion`,
//! docs/algorithms.md §dwa, α 0.2 as `lidar-dwa` runs in the \[L\] presets)
//! on the local map built from the scan alone, as `lidar-dwa`
//! does ([`super::scan_motion`]); a target nearer than `lookahead` is
//! steered to along its bearing at `lookahead` (the same reason as
//! `lidar-dwa`'s: a DWA heading critic aimed at a point closer than its
//! rollouts reach makes the robot circle it). The DWA never drives into
//! what the scan shows.

use super::planner::LocalMapConfig;
use super::scan::LidarConfig;
use super::scan_motion::{free_length, peer_dwa, steer_point, world_points, ScanMotion};
use crate::local::dwa::DwaConfig;
use crate::local::{LocalError, LocalPlanner, Observation, PlannerDebug};
use crate::num::hypot;
use crate::params::Params;
use crate::world::{Command, RobotSpec, RobotState, StaticMap};

crate::params::params! {
    /// Settings of `tangent-bug`. TangentBug has no numeric parameters (a
    /// point robot, exact sensing): every threshold here is planlab's choice
    /// for a disc robot with a sampled scan, declared as such.
    #[derive(Debug, Clone, PartialEq)]
    pub struct TangentBugConfig {
        pub lidar: LidarConfig = LidarConfig::default(), "" [nested] "the simulated LiDAR";
        pub local: LocalMapConfig = LocalMapConfig::default(), "" [nested]
            "the local map built from the scan for the motion planner";
        /// Adjacent beams.
        pub t_jump: f64 = 1.0, "m" [> 0.0]
            label "range jump threshold" "adjacent ranges differing by more mark a tangent-graph endpoint";
        /// 0.5: \[L\]'s d_oe, the same safety expansion; at 0.2 the robot
        /// grazes corners and its DWA, braking for the wall, stalls there.
        pub margin: f64 = 0.5, "m" [>= 0.0]
            label "clearance margin" "endpoints and the goal ray are for a disc of footprint radius + this";
        /// Compared with its best of the motion-to-goal phase.
        pub h_tolerance: f64 = 0.2, "m" [>= 0.0]
            label "boundary-following tolerance" "boundary following once d(x,O)+d(O,goal) exceeds its best by this";
        /// Between the footprint and the followed obstacle.
        pub follow_clearance: f64 = 0.3, "m" [>= 0.0] label "wall-following clearance" "clearance kept to the followed obstacle";
        pub lookahead: f64 = 3.0, "m" [>= 0.0]
            label "look-ahead distance" "the DWA steers this far along the target's bearing (along the wall when following)";
        /// [`peer_dwa`].
        pub motion: DwaConfig = peer_dwa(), "" [nested]
            "the baseline DWA under the navigator";
    }
}

impl TangentBugConfig {
    /// Checks every number; errors name `tangent-bug.field`.
    pub fn validate(&self) -> Result<(), LocalError> {
        Ok(self.check_bounds("tangent-bug")?)
    }
}

/// An endpoint of the local tangent graph (world m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Endpoint {
    /// The obstacle point at the discontinuity.
    pub edge: [f64; 2],
    /// The point the robot heads for: `edge` moved into the free side.
    pub point: [f64; 2],
}

/// The endpoints of the scan's hit points `pts` (world, beam order,
/// counter-clockwise) seen from `x`: discontinuities larger than `t_jump`
/// or between a hit and no return, moved `offset` into the free side.
pub fn endpoints(x: [f64; 2], pts: &[Option<[f64; 2]>], t_jump: f64, offset: f64) -> Vec<Endpoint> {
    let n = pts.len();
    let mut out = Vec::new();
    if n < 2 {
        return out;
    }
    let unit = |p: [f64; 2]| {
        let d = hypot(p[0] - x[0], p[1] - x[1]).max(1e-12);
        [(p[0] - x[0]) / d, (p[1] - x[1]) / d]
    };
    // Counter-clockwise (free side after beam i) or clockwise (before j).
    let push = |out: &mut Vec<Endpoint>, p: [f64; 2], ccw: bool| {
        let u = unit(p);
        let side = if ccw { [-u[1], u[0]] } else { [u[1], -u[0]] };
        out.push(Endpoint {
            edge: p,
            point: [p[0] + offset * side[0], p[1] + offset * side[1]],
        });
    };
    for i in 0..n {
        let j = (i + 1) % n;
        match (pts[i], pts[j]) {
            (Some(a), Some(b)) => {
                let (ra, rb) = (
                    hypot(a[0] - x[0], a[1] - x[1]),
                    hypot(b[0] - x[0], b[1] - x[1]),
                );
                if (ra - rb).abs() > t_jump {
                    if ra < rb {
                        push(&mut out, a, true);
                    } else {
                        push(&mut out, b, false);
                    }
                }
            }
            (Some(a), None) => push(&mut out, a, true),
            (None, Some(b)) => push(&mut out, b, false),
            (None, None) => {}
        }
    }
    out
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Mode {
    ToGoal,
    Follow {
        /// The followed obstacle is on the robot's right.
        right: bool,
        d_followed: f64,
        /// The followed point of the last step (None: just started).
        last: Option<[f64; 2]>,
    },
}

/// The `tangent-bug` planner (module doc).
#[derive(Debug)]
pub struct TangentBug {
    cfg: TangentBugConfig,
    io: ScanMotion,
    radius: f64,
    mode: Mode,
    /// Best heuristic distance of this motion-to-goal phase, m.
    h_best: f64,
    /// The last motion-to-goal target was left of the goal ray.
    went_left: bool,
    record: bool,
    debug: PlannerDebug,
}

impl TangentBug {
    /// Builds the planner for `robot`; errors name the bad field.
    pub fn new(cfg: TangentBugConfig, robot: &RobotSpec) -> Result<TangentBug, LocalError> {
        cfg.validate()?;
        let io = ScanMotion::with_dwa(cfg.lidar, cfg.local, cfg.motion, robot)?;
        Ok(TangentBug {
            radius: robot.footprint.circumscribed_radius(),
            cfg,
            io,
            mode: Mode::ToGoal,
            h_best: f64::INFINITY,
            went_left: true,
            record: false,
            debug: PlannerDebug::default(),
        })
    }

    /// Whether the robot is following a boundary.
    pub fn following(&self) -> bool {
        matches!(self.mode, Mode::Follow { .. })
    }

    /// The target of this step (world) and whether it is the goal.
    fn decide(
        &mut self,
        x: [f64; 2],
        goal: [f64; 2],
        pts: &[Option<[f64; 2]>],
    ) -> ([f64; 2], bool) {
        let rho = self.radius + self.cfg.margin;
        let (gx, gy) = (goal[0] - x[0], goal[1] - x[1]);
        let d_goal = hypot(gx, gy);
        if d_goal < 1e-9 {
            return (goal, true);
        }
        let u = [gx / d_goal, gy / d_goal];
        // Free straight run toward the goal, within what the sensor shows.
        let ell = free_length(x, u, pts, rho).min(self.io.range());
        let clear = ell >= d_goal.min(self.io.range()) - 1e-9;
        let goal_visible = ell >= d_goal - 1e-9;
        let eps = endpoints(x, pts, self.cfg.t_jump, rho);
        let cross = |p: [f64; 2]| gx * (p[1] - x[1]) - gy * (p[0] - x[0]);
        self.debug.keypoints = eps.iter().map(|e| e.point).collect();
        if let Mode::Follow {
            right,
            d_followed,
            last,
        } = self.mode
        {
            // The same obstacle: the nearest hit within t_jump of the point
            // followed last step (a wall across a narrow passage must not
            // take over and reverse the direction), else the nearest.
            let near = last
                .and_then(|l| nearest_within(x, pts, l, self.cfg.t_jump))
                .or_else(|| nearest(x, pts));
            let Some((m, pm)) = near else {
                self.enter_to_goal();
                return self.decide(x, goal, pts);
            };
            let d_chain = chain(pts, m, self.cfg.t_jump)
                .iter()
                .map(|p| hypot(p[0] - goal[0], p[1] - goal[1]))
                .fold(f64::INFINITY, f64::min);
            let d_followed = d_followed.min(d_chain);
            let d_reach = d_goal - ell.min(d_goal);
            if goal_visible || d_reach < d_followed {
                self.enter_to_goal();
                return self.decide(x, goal, pts);
            }
            self.mode = Mode::Follow {
                right,
                d_followed,
                last: Some(pm),
            };
            let dist = hypot(x[0] - pm[0], x[1] - pm[1]).max(1e-9);
            let nrm = [(x[0] - pm[0]) / dist, (x[1] - pm[1]) / dist];
            let tan = if right {
                [nrm[1], -nrm[0]]
            } else {
                [-nrm[1], nrm[0]]
            };
            // Steer along the wall's offset line, `lookahead` ahead of the
            // nearest point: parallel to a straight wall, round a corner
            // as the nearest point moves onto its other side.
            let off = self.radius + self.cfg.follow_clearance;
            let look = self.cfg.lookahead.max(self.radius);
            return (
                [
                    pm[0] + off * nrm[0] + look * tan[0],
                    pm[1] + off * nrm[1] + look * tan[1],
                ],
                false,
            );
        }
        let (target, h, is_goal) = if clear {
            (goal, d_goal, true)
        } else {
            let best = eps
                .iter()
                .map(|e| {
                    let p = e.point;
                    let h = hypot(p[0] - x[0], p[1] - x[1]) + hypot(p[0] - goal[0], p[1] - goal[1]);
                    (p, h)
                })
                .fold(None::<([f64; 2], f64)>, |b, c| match b {
                    Some(b) if b.1 <= c.1 => Some(b),
                    _ => Some(c),
                });
            match best {
                Some((p, h)) => (p, h, false),
                None => (goal, d_goal, true),
            }
        };
        if h > self.h_best + self.cfg.h_tolerance {
            // A local minimum of the heuristic: follow the obstacle round
            // the side the robot was heading for.
            let right = if is_goal {
                nearest(x, pts).is_some_and(|(_, p)| cross(p) < 0.0)
            } else {
                cross(target) > 0.0
            };
            self.mode = Mode::Follow {
                right,
                d_followed: f64::INFINITY,
                last: None,
            };
            return self.decide(x, goal, pts);
        }
        self.h_best = self.h_best.min(h);
        if !is_goal {
            self.went_left = cross(target) > 0.0;
        }
        (target, is_goal)
    }

    fn enter_to_goal(&mut self) {
        self.mode = Mode::ToGoal;
        self.h_best = f64::INFINITY;
    }
}

/// The nearest hit: (beam, point).
fn nearest(x: [f64; 2], pts: &[Option<[f64; 2]>]) -> Option<(usize, [f64; 2])> {
    let mut best: Option<(usize, [f64; 2], f64)> = None;
    for (i, p) in pts.iter().enumerate() {
        if let Some(p) = *p {
            let d = hypot(p[0] - x[0], p[1] - x[1]);
            if best.map_or(true, |b| d < b.2) {
                best = Some((i, p, d));
            }
        }
    }
    best.map(|(i, p, _)| (i, p))
}

/// The hit nearest to `x` among those within `r` of `around`.
fn nearest_within(
    x: [f64; 2],
    pts: &[Option<[f64; 2]>],
    around: [f64; 2],
    r: f64,
) -> Option<(usize, [f64; 2])> {
    let mut best: Option<(usize, [f64; 2], f64)> = None;
    for (i, p) in pts.iter().enumerate() {
        if let Some(p) = *p {
            if hypot(p[0] - around[0], p[1] - around[1]) > r {
                continue;
            }
            let d = hypot(p[0] - x[0], p[1] - x[1]);
            if best.map_or(true, |b| d < b.2) {
                best = Some((i, p, d));
            }
        }
    }
    best.map(|(i, p, _)| (i, p))
}

/// The hits joined to beam `m` by steps shorter than `join` (the sensed
/// part of the obstacle the robot follows).
fn chain(pts: &[Option<[f64; 2]>], m: usize, join: f64) -> Vec<[f64; 2]> {
    let n = pts.len();
    let Some(pm) = pts.get(m).copied().flatten() else {
        return Vec::new();
    };
    let mut out = vec![pm];
    for dir in [1usize, n - 1] {
        let (mut i, mut prev) = (m, pm);
        for _ in 1..n {
            i = (i + dir) % n;
            if i == m {
                break;
            }
            match pts[i] {
                Some(p) if hypot(p[0] - prev[0], p[1] - prev[1]) < join => {
                    out.push(p);
                    prev = p;
                }
                _ => break,
            }
        }
    }
    out
}

impl LocalPlanner for TangentBug {
    fn name(&self) -> &'static str {
        "tangent-bug"
    }

    fn step(&mut self, obs: &Observation<'_>) -> Command {
        let (pose, scan) = self.io.sense(obs);
        let x = [pose[0], pose[1]];
        let pts = world_points(pose, &scan);
        let (target, is_goal) = self.decide(x, obs.goal, &pts);
        let steer = steer_point(x, target, self.cfg.lookahead, !is_goal && !self.following());
        let cmd = self.io.drive(obs, pose, &scan, steer);
        let phase = if self.following() {
            "boundary-following"
        } else {
            "motion-to-goal"
        };
        let mut d = std::mem::take(&mut self.debug);
        self.io
            .report(&mut d, phase, pose, &scan, target, is_goal, self.record);
        self.debug = d;
        cmd
    }

    fn set_goal(
        &mut self,
        _map: &StaticMap,
        _state: &RobotState,
        goal: [f64; 2],
    ) -> Result<(), LocalError> {
        crate::local::dwa::check_goal(goal)?;
        self.enter_to_goal();
        Ok(())
    }

    fn debug(&self) -> &PlannerDebug {
        &self.debug
    }

    fn set_record_rollouts(&mut self, on: bool) {
        self.record = on;
        self.io.set_record(on);
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::local::testkit::{self, End};
    use crate::world::{Footprint, RobotLimits};

    /// \[L\] Table 1's robot.
    pub(crate) fn l_robot() -> RobotSpec {
        RobotSpec {
            footprint: Footprint::Circle { radius: 0.3 },
            limits: RobotLimits {
                v_max: 1.0,
                v_min: 0.0,
                vy_max: 0.0,
                w_max: 5.0 * std::f64::consts::PI / 3.0,
                acc_v: 0.5,
                acc_vy: 0.0,
                acc_w: 4.0 * std::f64::consts::PI,
            },
            ..Default::default()
        }
    }

    /// A walled room `w` × `h` m (0.1 m cells) with the wall rectangles
    /// `walls` ([x0, y0, x1, y1], m) inside.
    /// The error of planner `name` (built by `new`) with `cfg`, or "" when
    /// it builds.
    pub(crate) fn build_error<C: Params, P: LocalPlanner + 'static>(
        name: &str,
        cfg: serde_json::Value,
        new: fn(C, &RobotSpec) -> Result<P, LocalError>,
    ) -> String {
        build_on_room(name, cfg, new)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default()
    }

    /// Planner `name` with `cfg` (JSON, parsed as the catalogue does),
    /// built by `new` for \[L\]'s robot.
    pub(crate) fn build_on_room<C: Params, P: LocalPlanner + 'static>(
        name: &str,
        cfg: serde_json::Value,
        new: fn(C, &RobotSpec) -> Result<P, LocalError>,
    ) -> Result<Box<dyn LocalPlanner>, LocalError> {
        let cfg = crate::params::parse_config(name, &cfg)?;
        Ok(Box::new(new(cfg, &l_robot())?))
    }

    /// A walled room `w` × `h` m (0.1 m cells) with the wall rectangles
    /// `walls` ([x0, y0, x1, y1], m) inside.
    pub(crate) fn room(w: f64, h: f64, walls: &[[f64; 4]]) -> StaticMap {
        let (cols, rows) = ((w * 10.0).round() as usize, (h * 10.0).round() as usize);
        let mut text = String::new();
        for r in 0..rows {
            for c in 0..cols {
                let (x, y) = ((c as f64 + 0.5) / 10.0, h - (r as f64 + 0.5) / 10.0);
                let edge = r == 0 || c == 0 || r + 1 == rows || c + 1 == cols;
                let wall = walls
                    .iter()
                    .any(|b| x >= b[0] && x <= b[2] && y >= b[1] && y <= b[3]);
                text.push(if edge || wall { '#' } else { '.' });
            }
            text.push('\n');
        }
        testkit::map(&text, 0.1)
    }

    pub(crate) fn run_on(
        planner: &mut dyn LocalPlanner,
        map: &StaticMap,
        start: [f64; 2],
        goal: [f64; 2],
        max_time: f64,
    ) -> testkit::Run {
        let s = RobotState {
            x: start[0],
            y: start[1],
            ..Default::default()
        };
        testkit::run(planner, map, &l_robot(), s, goal, &[], max_time, 0.3)
    }

    fn bug(cfg: serde_json::Value) -> Box<dyn LocalPlanner> {
        build_on_room("tangent-bug", cfg, TangentBug::new).unwrap()
    }

    #[test]
    fn endpoints_sit_beside_range_jumps_on_the_free_side() {
        // Beams 0–2 hit a near wall 2 m ahead, beam 3 sees 6 m, beam 4 none.
        let x = [0.0, 0.0];
        let pts = vec![
            Some([2.0, -0.1]),
            Some([2.0, 0.0]),
            Some([2.0, 0.1]),
            Some([6.0, 0.4]),
            None,
        ];
        let e = endpoints(x, &pts, 1.0, 0.5);
        // 2 → 3 (jump 4 m, near side first, free side counter-clockwise),
        // 3 → 4 (hit beside no return), 4 → 0 (no return beside a hit).
        assert_eq!(e.len(), 3);
        assert_eq!(e[0].edge, [2.0, 0.1]);
        assert!(e[0].point[1] > 0.1 + 0.45, "moved up, off the wall: {e:?}");
        assert_eq!(e[2].edge, [2.0, -0.1]);
        assert!(e[2].point[1] < -0.1 - 0.45, "moved down: {e:?}");
        assert!(endpoints(x, &[None, None], 1.0, 0.5).is_empty());
    }

    #[test]
    fn tangent_bug_reaches_the_goal_round_a_wall_without_collision() {
        // A 3 m wall across the way in a 10 × 6 m room.
        let map = room(10.0, 6.0, &[[5.0, 1.5, 5.3, 4.5]]);
        let mut p = bug(serde_json::json!({}));
        let r = run_on(p.as_mut(), &map, [1.5, 3.0], [8.5, 3.0], 60.0);
        assert_eq!(r.end, End::Reached, "{:?}", r.states.last());
        assert!(r.min_clearance > 0.0);
        // It went round an end of the wall, not through it.
        assert!(r.states.iter().any(|s| s.y > 4.5 || s.y < 1.5));
        assert!(r.modes.iter().all(|m| !m.contains("no-admissible")));
    }

    #[test]
    fn tangent_bug_follows_a_wall_longer_than_its_range() {
        // With a 3 m sensor the 11 m wall's ends are out of sight: the
        // heuristic through the endpoint at the range limit stops
        // decreasing and the robot follows the wall round its end.
        let map = room(12.0, 16.0, &[[5.0, 2.0, 5.3, 13.0]]);
        let mut p = bug(serde_json::json!({"lidar": {"range": 3.0}}));
        let r = run_on(p.as_mut(), &map, [2.0, 7.0], [10.0, 7.0], 150.0);
        assert_eq!(r.end, End::Reached, "{:?}", r.states.last());
        assert!(r.min_clearance > 0.0);
        assert!(
            r.modes.iter().any(|m| m.starts_with("boundary-following")),
            "never followed the wall"
        );
    }

    #[test]
    fn tangent_bug_is_deterministic() {
        let map = room(10.0, 6.0, &[[5.0, 1.5, 5.3, 4.5]]);
        let runs: Vec<testkit::Run> = (0..2)
            .map(|_| {
                let mut p = bug(serde_json::json!({}));
                run_on(p.as_mut(), &map, [1.5, 3.2], [8.5, 2.8], 60.0)
            })
            .collect();
        assert_eq!(runs[0].states, runs[1].states);
        assert_eq!(runs[0].modes, runs[1].modes);
    }

    #[test]
    fn bad_tangent_bug_settings_name_the_field() {
        let build = |cfg| build_error("tangent-bug", cfg, TangentBug::new);
        assert!(build(serde_json::json!({"margin": -1.0})).contains("tangent-bug.margin"));
        assert!(build(serde_json::json!({"t_jump": 0.0})).contains("tangent-bug.t_jump"));
        assert!(build(serde_json::json!({"lidar": {"range": 0.0}})).contains("lidar.range"));
        assert!(build(serde_json::json!({"motion": {"alpha": -1.0}})).contains("alpha"));
        assert!(build(serde_json::json!({"nope": 1})).contains("unknown field"));
    }
}
