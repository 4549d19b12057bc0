//! `rs-apf`: APF plus regression-search shortening, the \[L\] sim 8 peer.
//!
//! \[L\] compares sim 8 with RS-APF (Li, Tamura, Yamashita & Asama 2013,
//! its reference \[11\]): an improved APF produces a path of sequential
//! points, and a **regression search** shortens it by connecting them
//! ("uses regression search to further smooth and shorten the path APF
//! produces", \[L\] §4.2). \[11\] is a path *planner*: the field is
//! descended by a virtual point on a map before the robot moves (its
//! conference version plans in "complete known environments"). **This is
//! the closest scan-only variant, flagged as such**: every control period
//! the path is planned afresh from the robot on the current scan only (the
//! obstacles are the scan's hit points), out to the sensor's range, and
//! the robot drives toward the first corner of the shortened path; the map
//! is never read.
//!
//! - **APF path.** A virtual point steps `apf.step` along the resultant of
//!   the basic field (\[T\] eq 4-1…4-4, the field `apf` and `lidar-apf`
//!   use; its gains are `apf`'s defaults), repelled by the nearest hit
//!   point, the robot's radius added to every distance.
//! - **Local minima.** \[11\]'s redefined potentials and "improved
//!   wall-following" are not given in \[L\]; here, when the virtual point
//!   makes no progress toward the goal for `stall_steps` steps, it follows
//!   the nearest obstacle (at the footprint's radius + `margin` from the
//!   hit points) on the side the attraction leans to — kept across periods
//!   while stalls recur — until it is nearer the goal than where it
//!   stalled, then descends again.
//! - **Regression search.** From the path's last point P_N back to the
//!   robot: the earliest P_i whose straight segment to P_j (first j = N)
//!   a disc of the footprint's radius + `margin` clears joins them; repeat
//!   from P_i until P_0. The shortened path's first corner is the target.
//!
//! **Motion layer**: the baseline DWA on the scan's local map, as for
//! `tangent-bug` ([`super::scan_motion`]); a target nearer than
//! `lookahead` is steered to along its bearing at `lookahead`.

use super::planner::LocalMapConfig;
use super::scan::LidarConfig;
use super::scan_motion::{
    free_length, peer_dwa, regression_search, steer_point, world_points, ScanMotion,
};
use crate::apf::field::{attraction, repulsion};
use crate::apf::{ApfConfig, ApfMode};
use crate::local::dwa::DwaConfig;
use crate::local::{LocalError, LocalPlanner, Observation, PlannerDebug};
use crate::num::hypot;
use crate::params::Params;
use crate::world::{Command, RobotSpec, RobotState, StaticMap};
use glam::DVec2;

/// Most points of one virtual APF path.
pub const MAX_PATH_POINTS: usize = 400;

crate::params::params! {
    /// Settings of `rs-apf`.
    #[derive(Debug, Clone, PartialEq)]
    pub struct RsApfConfig {
        pub lidar: LidarConfig = LidarConfig::default(), "" [nested] "the simulated LiDAR";
        pub local: LocalMapConfig = LocalMapConfig::default(), "" [nested]
            "the local map built from the scan for the motion planner";
        /// Path segments and wall following keep this clear of the hit points.
        pub margin: f64 = 0.5, "m" [>= 0.0]
            label "clearance margin" "segments and wall following keep footprint radius + this from hits";
        /// Steps toward the goal.
        pub stall_steps: u32 = 3, "1" []
            label "stall steps" "virtual steps without progress before following the obstacle";
        pub lookahead: f64 = 3.0, "m" [>= 0.0] label "look-ahead distance" "the DWA steers this far along the target's bearing";
        /// [`peer_dwa`].
        pub motion: DwaConfig = peer_dwa(), "" [nested]
            "the baseline DWA driving toward the target";
        /// `mode` is forced to `basic`, `robot_radius` to the footprint's;
        /// `apf`'s defaults.
        pub apf: ApfConfig = crate::apf::local::ApfLocalConfig::default().apf, "" [nested]
            "the basic potential field of the virtual path";
    }
}

impl RsApfConfig {
    /// Checks every number; errors name `rs-apf.field`.
    pub fn validate(&self) -> Result<(), LocalError> {
        self.check_bounds("rs-apf")?;
        if self.stall_steps == 0 {
            return Err(LocalError::InvalidParameter(
                "rs-apf.stall_steps = 0: must be at least 1".into(),
            ));
        }
        self.apf
            .validate()
            .map_err(|e| LocalError::InvalidParameter(format!("rs-apf.apf: {e}")))
    }
}

/// A virtual APF path and its regression-search shortening (world m).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct RsPath {
    /// The APF points P_0 (the robot) … P_N.
    pub points: Vec<[f64; 2]>,
    /// The shortened path: P_0, its corners, P_N.
    pub shortened: Vec<[f64; 2]>,
    /// The side the virtual point follows obstacles on (+1 counter-
    /// clockwise round them, −1 clockwise), kept for the next period.
    pub side: Option<f64>,
    /// Whether the virtual point stalled and followed an obstacle.
    pub stalled: bool,
}

/// The geometry the path is planned in: hit points and the disc radius.
struct Scene<'a> {
    pts: &'a [Option<[f64; 2]>],
    /// Footprint radius, m.
    radius: f64,
    /// Footprint radius + margin, m.
    rho: f64,
}

impl Scene<'_> {
    fn nearest(&self, p: DVec2) -> Option<DVec2> {
        let mut best: Option<(DVec2, f64)> = None;
        for q in self.pts.iter().flatten() {
            let q = DVec2::from(*q);
            let d = (q - p).length();
            if best.map_or(true, |b| d < b.1) {
                best = Some((q, d));
            }
        }
        best.map(|b| b.0)
    }

    /// Whether a disc of radius `rho` can slide from `a` to `b`.
    fn segment_free(&self, a: DVec2, b: DVec2) -> bool {
        let d = (b - a).length();
        if d < 1e-9 {
            return true;
        }
        let u = (b - a) / d;
        free_length(a.into(), u.into(), self.pts, self.rho) >= d
    }
}

/// Plans the virtual APF path from `x` to `goal` on the hit points `pts`
/// (out to `horizon` from `x`) and shortens it by regression search.
/// `side` is the wall-following side to keep (None: choose).
#[allow(clippy::too_many_arguments)]
pub fn plan(
    cfg: &RsApfConfig,
    radius: f64,
    x: [f64; 2],
    goal: [f64; 2],
    pts: &[Option<[f64; 2]>],
    horizon: f64,
    side: Option<f64>,
) -> RsPath {
    let scene = Scene {
        pts,
        radius,
        rho: radius + cfg.margin,
    };
    let field = ApfConfig {
        mode: ApfMode::Basic,
        robot_radius: radius,
        ..cfg.apf
    };
    let (x0, g) = (DVec2::from(x), DVec2::from(goal));
    let step = cfg.apf.step;
    let mut path = vec![x0];
    let mut p = x0;
    let mut side = side;
    let mut best = (g - p).length();
    let mut since_best = 0u32;
    // Some(d_hit): following an obstacle since a stall at goal distance d_hit.
    let mut follow: Option<f64> = None;
    let mut stalled = false;
    while path.len() < MAX_PATH_POINTS {
        let dg = (g - p).length();
        if dg <= step {
            if scene.segment_free(p, g) {
                path.push(g);
            }
            break;
        }
        if (p - x0).length() > horizon {
            break;
        }
        let q = scene.nearest(p);
        if let Some(d_hit) = follow {
            if dg < d_hit - step {
                follow = None;
                best = dg;
                since_best = 0;
            }
        }
        let next = match (follow, q) {
            (Some(_), Some(q)) => {
                let s = side.unwrap_or(1.0);
                let off = p - q;
                let n = off / off.length().max(1e-9);
                let t = DVec2::new(-n.y, n.x) * s;
                // On the offset line, one step along the tangent.
                q + n * scene.rho + t * step
            }
            _ => {
                let mut f = attraction(&field, p, g);
                if let Some(q) = q {
                    f += repulsion(&field, p, q, 0.0);
                }
                let fl = f.length();
                if !(fl.is_finite() && fl > cfg.apf.stall_force) {
                    since_best = cfg.stall_steps;
                    p
                } else {
                    p + f * (step / fl)
                }
            }
        };
        // The virtual robot never enters what the scan shows: a step into
        // it is a stall too (the field's balance point lies closer to the
        // wall than one step).
        let clear = pts
            .iter()
            .flatten()
            .all(|h| (DVec2::from(*h) - next).length() > scene.radius);
        if follow.is_none() {
            let dn = (g - next).length();
            if !clear {
                since_best = cfg.stall_steps;
            } else if dn < best - 0.25 * step {
                best = dn;
                since_best = 0;
            } else {
                since_best += 1;
            }
            if since_best >= cfg.stall_steps {
                if let Some(q) = q {
                    // Go round on the side the attraction leans to (ties:
                    // counter-clockwise), then keep that side.
                    let n = (p - q) / (p - q).length().max(1e-9);
                    let s = side.unwrap_or_else(|| {
                        let t = DVec2::new(-n.y, n.x);
                        if t.dot(g - p) >= 0.0 {
                            1.0
                        } else {
                            -1.0
                        }
                    });
                    side = Some(s);
                    follow = Some(dg);
                    stalled = true;
                    since_best = 0;
                    continue;
                }
                break;
            }
        }
        if !clear || (next - p).length() < 1e-9 {
            break;
        }
        p = next;
        path.push(p);
    }
    let reached = path.last().is_some_and(|p| (*p - g).length() < 1e-9);
    let points: Vec<[f64; 2]> = path.iter().map(|v| (*v).into()).collect();
    RsPath {
        shortened: regression_search(&path, |a, b| scene.segment_free(a, b))
            .into_iter()
            .map(Into::into)
            .collect(),
        points,
        // The side is kept until a plan reaches the goal without a stall.
        side: if stalled || !reached { side } else { None },
        stalled,
    }
}

/// The `rs-apf` planner (module doc).
#[derive(Debug)]
pub struct RsApf {
    cfg: RsApfConfig,
    io: ScanMotion,
    radius: f64,
    side: Option<f64>,
    path: RsPath,
    record: bool,
    debug: PlannerDebug,
}

impl RsApf {
    /// Builds the planner for `robot`; errors name the bad field.
    pub fn new(cfg: RsApfConfig, robot: &RobotSpec) -> Result<RsApf, LocalError> {
        cfg.validate()?;
        let io = ScanMotion::with_dwa(cfg.lidar, cfg.local, cfg.motion, robot)?;
        Ok(RsApf {
            radius: robot.footprint.circumscribed_radius(),
            cfg,
            io,
            side: None,
            path: RsPath::default(),
            record: false,
            debug: PlannerDebug::default(),
        })
    }

    /// The path planned in the last step.
    pub fn path(&self) -> &RsPath {
        &self.path
    }
}

impl LocalPlanner for RsApf {
    fn name(&self) -> &'static str {
        "rs-apf"
    }

    fn step(&mut self, obs: &Observation<'_>) -> Command {
        let (pose, scan) = self.io.sense(obs);
        let x = [pose[0], pose[1]];
        let pts = world_points(pose, &scan);
        let path = plan(
            &self.cfg,
            self.radius,
            x,
            obs.goal,
            &pts,
            self.io.range(),
            self.side,
        );
        self.side = path.side;
        let target = path.shortened.get(1).copied().unwrap_or(obs.goal);
        let is_goal = hypot(target[0] - obs.goal[0], target[1] - obs.goal[1]) < 1e-9;
        let steer = steer_point(x, target, self.cfg.lookahead, !is_goal);
        let cmd = self.io.drive(obs, pose, &scan, steer);
        let phase = if path.stalled {
            "rs-apf-follow"
        } else {
            "rs-apf"
        };
        self.debug.global_path.clone_from(&path.shortened);
        self.debug.keypoints = if self.record {
            path.points.clone()
        } else {
            Vec::new()
        };
        self.path = path;
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
        self.side = None;
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
mod tests {
    use super::*;
    use crate::apf::local::{ApfLocal, ApfLocalConfig};
    use crate::lidar::planner::{LidarPlanner, ScanBaselineConfig, MOTION_GOAL};
    use crate::lidar::tangent_bug::tests::{build_error, build_on_room, l_robot, room, run_on};
    use crate::local::testkit::End;

    fn rs(cfg: serde_json::Value) -> Box<dyn LocalPlanner> {
        build_on_room("rs-apf", cfg, RsApf::new).unwrap()
    }

    fn length(p: &[[f64; 2]]) -> f64 {
        p.windows(2)
            .map(|w| hypot(w[1][0] - w[0][0], w[1][1] - w[0][1]))
            .sum()
    }

    #[test]
    fn regression_search_shortens_the_apf_path_round_a_wall() {
        // Hit points of a wall x = 3, |y| ≤ 2, seen from the origin; the
        // goal 6 m ahead behind it: the field's balance point lies on the
        // line, the virtual point follows the wall round an end.
        let pts: Vec<Option<[f64; 2]>> = (0..=80)
            .map(|k| Some([3.0, -2.0 + 0.05 * k as f64]))
            .collect();
        let cfg = RsApfConfig::default();
        let p = plan(&cfg, 0.3, [0.0, 0.0], [6.0, 0.0], &pts, 10.0, None);
        assert!(p.stalled, "the basic field stalls in front of the wall");
        assert_eq!(p.points.last(), Some(&[6.0, 0.0]), "reaches the goal");
        let s = &p.shortened;
        assert_eq!(s.first(), Some(&[0.0, 0.0]));
        assert_eq!(s.last(), Some(&[6.0, 0.0]));
        assert!(s.len() >= 3 && s.len() < p.points.len() / 4, "{s:?}");
        assert!(length(s) < length(&p.points));
        // Every shortened leg is clear for the disc, and the first corner
        // passes an end of the wall.
        let scene = Scene {
            pts: &pts,
            radius: 0.3,
            rho: 0.8,
        };
        for w in s.windows(2) {
            assert!(scene.segment_free(w[0].into(), w[1].into()), "{w:?}");
        }
        assert!(s[1][1].abs() > 2.0, "{s:?}");
        // The side is kept for the next period.
        let again = plan(&cfg, 0.3, [0.1, 0.0], [6.0, 0.0], &pts, 10.0, p.side);
        assert_eq!(again.side, p.side);
    }

    #[test]
    fn rs_apf_reaches_the_goal_behind_a_wall_on_the_line_without_collision() {
        // The wall straddles the start–goal line symmetrically: plain APF
        // on the same scan stalls in its local minimum.
        let map = room(10.0, 10.0, &[[5.0, 3.0, 5.3, 7.0]]);
        let mut p = rs(serde_json::json!({}));
        let r = run_on(p.as_mut(), &map, [1.5, 5.0], [8.5, 5.0], 60.0);
        assert_eq!(r.end, End::Reached, "{:?}", r.states.last());
        assert!(r.min_clearance > 0.0);
        assert!(r.modes.iter().any(|m| m.starts_with("rs-apf-follow")));
        // `scan-apf`: the basic APF on the scan's local map.
        let cfg = ScanBaselineConfig::<ApfLocalConfig>::default();
        let apf = ApfLocal::new(true, cfg.motion, &l_robot(), MOTION_GOAL).unwrap();
        let mut plain =
            LidarPlanner::baseline("scan-apf", &cfg, Box::new(apf), &l_robot()).unwrap();
        let r = run_on(&mut plain, &map, [1.5, 5.0], [8.5, 5.0], 60.0);
        assert_ne!(r.end, End::Reached);
    }

    #[test]
    fn rs_apf_is_deterministic() {
        let map = room(10.0, 10.0, &[[5.0, 3.0, 5.3, 7.0]]);
        let runs: Vec<_> = (0..2)
            .map(|_| {
                let mut p = rs(serde_json::json!({}));
                run_on(p.as_mut(), &map, [1.5, 5.1], [8.5, 4.9], 60.0)
            })
            .collect();
        assert_eq!(runs[0].states, runs[1].states);
        assert_eq!(runs[0].modes, runs[1].modes);
    }

    #[test]
    fn bad_rs_apf_settings_name_the_field() {
        let build = |cfg| build_error("rs-apf", cfg, RsApf::new);
        assert!(build(serde_json::json!({"margin": f64::NAN.to_string()})).contains("margin"));
        assert!(build(serde_json::json!({"margin": -0.1})).contains("rs-apf.margin"));
        assert!(build(serde_json::json!({"stall_steps": 0})).contains("rs-apf.stall_steps"));
        assert!(build(serde_json::json!({"apf": {"step": 0.0}})).contains("step"));
        assert!(build(serde_json::json!({"lidar": {"beams": 0}})).contains("lidar.beams"));
    }
}
