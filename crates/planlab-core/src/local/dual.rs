//! Safe A\* + Bottom-Up + dual-velocity DWA with detour replanning of \[S\]
//! Ge & Li 2022 §2–4 (docs/algorithms.md §safe-dual-dwa), and the "preliminary fusion" baseline
//! the paper improves on (\[S\] §2.4).
//!
//! - **Global guidance** (\[S\] §1, §4.1): safe A\* ([`crate::global::safe_astar`],
//!   24-neighbourhood, ε·L(n) safety term) on the static map inflated by the
//!   footprint radius + `inflate_margin`; the Bottom-Up feature nodes of its
//!   path ([`crate::global::bottom_up`], maximum error `bottom_up_error`)
//!   are the temporary goals, the next one taken once the robot is within
//!   `switch_radius`.
//! - **Dual velocity model** (\[S\] eq 9–12): while the temporary goal p is
//!   not the global goal G and dist(robot, p) < d (`hold_distance`, 3 m) the
//!   linear speed is held at the previous one (V_d for v collapses to
//!   {v_{t−Δt}}) and only ω is chosen by the critics; otherwise the normal
//!   window. The engine ([`super::engine::Engine`]) releases the hold when no
//!   sample at the held speed is admissible (mode `hold-v-released`).
//!   **Decision**: the hold needs a previous speed ≥ `hold_min_speed`; a
//!   robot at rest (or crawling, e.g. after giving way to a mover) would
//!   otherwise be held at that speed until the node is passed.
//! - **Detour replanning** (\[S\] §4.2, Fig 8): θa = the angle at the robot
//!   between the directions to the current and to the next temporary goal;
//!   θa ≥ `detour_angle` (90°) means the robot has passed the current one
//!   (after an avoidance manoeuvre, say), so the next becomes the temporary
//!   goal (mode `detour-replan` on that step). Without it the robot would
//!   turn back for a node it already left behind and loop (\[S\] Fig 7).
//!   **Decisions**: the switch needs a clear line from the robot to the new
//!   goal (a long segment round a wall's end has a Thales circle reaching
//!   behind the wall), and the pair after the current one is tested too
//!   (carried round a wall's end at a held speed, the robot may sweep past
//!   both corner nodes at once).
//!
//! **Preliminary fusion** (`preliminary-fusion`): the same safe A\* path,
//! every path node a temporary goal, the normal window, no detour
//! replanning: the DWA slows for each node (its heading critic favours
//! rollouts that end at the node), so the speed oscillates (\[S\] Fig 4, 11).
//!
//! **Defaults** are \[S\] §5: α 0.05, β 0.5, γ 0.1, Δt 0.1 s (the engine's
//! rollout step; the control period is the scenario's `sim.dt`). The robot's
//! v_max 1.0 m/s, ω_max "20", a_v 0.2 m/s², a_ω "50" belong to the
//! scenario's robot (the presets use 20°/s and 50°/s², the units of the
//! MATLAB DWA sample both papers follow; 20 rad/s would be a full turn in
//! 0.3 s). d = 3 m (\[S\] eq 12); ε = 100 and the 5×5 window of safe A\*.

use super::dwa::{check_goal, DwaConfig, DwaPlanner, GoalProvider, Guidance, Weights};
use super::route::{dist, plan_route, Route, Waypoints};
use super::{GoalKind, LocalError, Observation, PlannerDebug};
use crate::global::plan::{Algorithm, GridPlanOptions};
use crate::global::safe_astar::{SafeAStarConfig, MAX_WINDOW_RADIUS};
use crate::num::{acos, hypot};
use crate::params::Params;
use crate::world::{RobotSpec, RobotState, StaticMap};

/// The engine defaults of \[S\] §5: the DWA sample with β = 0.5.
fn s_dwa() -> DwaConfig {
    DwaConfig {
        alpha: 0.05,
        beta: 0.5,
        gamma: 0.1,
        sim_dt: 0.1,
        ..DwaConfig::default()
    }
}

/// Detour replanning tests the current temporary goal and this many - 1
/// after it (see [`DualGuide`]'s `passed`).
pub const DETOUR_LOOKAHEAD: usize = 2;

crate::params::params! {
    /// Settings of `safe-dual-dwa` (\[S\] §2–4).
    #[derive(Debug, Clone, Copy, PartialEq)]
    pub struct DualConfig {
        /// The DWA engine (\[S\] §5: α 0.05, β 0.5, γ 0.1, Δt 0.1 s).
        pub dwa: DwaConfig = s_dwa(), "" [nested] "the DWA engine";
        pub inflate_margin: f64 = 0.1, "m" [>= 0.0] label "inflation margin" "safe A* inflation beyond the footprint radius";
        /// Safe A\*'s L(n) = k/s (\[S\] eq 1).
        pub safe_epsilon: f64 = SafeAStarConfig::default().epsilon, "cells" [>= 0.0]
            label "safety weight ε" "ε, weight of safe A*'s safety term";
        /// r of the (2r+1)² window.
        pub safe_window: u32 = SafeAStarConfig::default().window_radius, "cells" []
            label "safety window" "half-size of safe A*'s evaluation window";
        pub switch_radius: f64 = 0.5, "m" [> 0.0] label "switch radius" "take the next temporary goal within this";
        /// \[S\] §4.1; divided by the map's resolution for the grid path.
        pub bottom_up_error: f64 = 1.0, "m" [>= 0.0]
            label "Bottom-Up error" "Bottom-Up maximum merge error (feature nodes)";
        /// d of \[S\] eq 12; not at the final goal.
        pub hold_distance: f64 = 3.0, "m" [>= 0.0]
            label "speed-hold distance d" "d: hold the speed within this of a temporary goal";
        /// A Decision (module doc).
        pub hold_min_speed: f64 = 0.3, "m/s" [>= 0.0] label "least held speed" "hold only a previous speed at least this";
        /// False: the normal window always.
        pub dual_velocity: bool = true, "bool" [] label "dual velocity model" "apply the dual velocity model";
        /// \[S\] §4.2; above π: never.
        pub detour_angle: f64 = std::f64::consts::FRAC_PI_2, "rad" [>= 0.0]
            label "detour angle θa" "θa at or above this switches to the next temporary goal";
    }
}

crate::params::params! {
    /// Settings of the `preliminary-fusion` baseline: safe A\* path nodes as
    /// temporary goals, the normal window.
    #[derive(Debug, Clone, Copy, PartialEq)]
    pub struct PreliminaryConfig {
        /// The DWA engine (\[S\] §5 weights).
        pub dwa: DwaConfig = s_dwa(), "" [nested] "the DWA engine";
        pub inflate_margin: f64 = 0.1, "m" [>= 0.0] label "inflation margin" "safe A* inflation beyond the footprint radius";
        pub safe_epsilon: f64 = SafeAStarConfig::default().epsilon, "cells" [>= 0.0]
            label "safety weight ε" "ε, weight of safe A*'s safety term";
        pub safe_window: u32 = SafeAStarConfig::default().window_radius, "cells" []
            label "safety window" "half-size of safe A*'s evaluation window";
        pub switch_radius: f64 = 0.5, "m" [> 0.0] label "switch radius" "take the next temporary goal within this";
    }
}

impl DualConfig {
    /// Checks every number; errors name `prefix.field`.
    pub fn validate(&self, prefix: &str) -> Result<(), LocalError> {
        self.dwa.validate(&format!("{prefix}.dwa"))?;
        self.check_bounds(prefix)?;
        if self.safe_window == 0 || self.safe_window > MAX_WINDOW_RADIUS {
            return Err(LocalError::InvalidParameter(format!(
                "{prefix}.safe_window = {}: must be in 1..={MAX_WINDOW_RADIUS}",
                self.safe_window
            )));
        }
        Ok(())
    }
}

/// Which planner a [`DualGuide`] makes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DualVariant {
    /// \[S\]'s planner (`safe-dual-dwa`).
    SafeDual,
    /// The preliminary fusion baseline (`preliminary-fusion`).
    Preliminary,
}

/// Goal provider of `safe-dual-dwa` and `preliminary-fusion`.
#[derive(Debug, Clone)]
pub struct DualGuide {
    cfg: DualConfig,
    variant: DualVariant,
    r_robot: f64,
    goal: [f64; 2],
    route: Route,
    idx: usize,
    /// Temporary goals skipped by detour replanning so far.
    detour_switches: u32,
    /// Set when the final goal moved and no new route could be planned.
    lost: bool,
}

/// \[S\]'s safe A\* + dual-velocity DWA (registry name `safe-dual-dwa`).
pub type SafeDualDwa = DwaPlanner<DualGuide>;

impl DualGuide {
    fn options(&self, map: &StaticMap) -> GridPlanOptions {
        grid_options(&self.cfg, self.r_robot, self.variant, map)
    }

    fn which(variant: DualVariant) -> Waypoints {
        match variant {
            DualVariant::SafeDual => Waypoints::FeatureNodes,
            DualVariant::Preliminary => Waypoints::PathNodes,
        }
    }

    /// The global route (safe A\* path and temporary goals).
    pub fn route(&self) -> &Route {
        &self.route
    }

    /// Index of the current temporary goal in the route's waypoints.
    pub fn waypoint_index(&self) -> usize {
        self.idx
    }

    /// How many temporary goals detour replanning has skipped.
    pub fn detour_switches(&self) -> u32 {
        self.detour_switches
    }

    fn replan(
        &mut self,
        map: &StaticMap,
        from: [f64; 2],
        goal: [f64; 2],
    ) -> Result<(), LocalError> {
        self.route = plan_route(
            map,
            from,
            goal,
            &self.options(map),
            Self::which(self.variant),
        )?;
        self.idx = 0;
        self.goal = goal;
        self.lost = false;
        Ok(())
    }

    /// The temporary goal the robot has passed, if any (\[S\] §4.2): the
    /// current one (index `idx`) when θa ≥ `detour_angle` between it and
    /// the next, or the one after it by the same test. **Decisions**: the
    /// robot must see the goal it switches to (nothing static within the
    /// footprint radius of the straight line to it) — a long next segment
    /// round a wall's end has a Thales circle reaching behind the wall; and
    /// the second pair is tested because a robot carried round a wall's end
    /// at a held speed may sweep past both corner nodes at once (θa ≈ 0 for
    /// the first pair then).
    fn passed(&self, map: &StaticMap, robot: [f64; 2]) -> Option<usize> {
        let w = &self.route.waypoints;
        let end = (self.idx + DETOUR_LOOKAHEAD).min(w.len().saturating_sub(1));
        (self.idx..end).find(|&j| {
            Self::theta_a(robot, w[j], w[j + 1]) >= self.cfg.detour_angle
                && self.line_of_sight(map, robot, w[j + 1])
        })
    }

    /// Whether the straight line from `a` to `b` keeps the footprint
    /// radius from every static obstacle (sampled every half cell).
    fn line_of_sight(&self, map: &StaticMap, a: [f64; 2], b: [f64; 2]) -> bool {
        let step = 0.5 * map.grid().resolution();
        let n = ((dist(a, b) / step).ceil() as usize).min(100_000);
        (0..=n).all(|i| {
            let t = if n == 0 { 0.0 } else { i as f64 / n as f64 };
            let p = [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])];
            map.clearance(p[0], p[1]) > self.r_robot
        })
    }

    /// θa: the angle at `robot` between the directions to `a` and `b`, rad
    /// (0 when either is at the robot).
    fn theta_a(robot: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
        let (ax, ay) = (a[0] - robot[0], a[1] - robot[1]);
        let (bx, by) = (b[0] - robot[0], b[1] - robot[1]);
        let den = hypot(ax, ay) * hypot(bx, by);
        if den <= 1e-12 {
            return 0.0;
        }
        acos(((ax * bx + ay * by) / den).clamp(-1.0, 1.0))
    }
}

/// The grid planning options of `cfg` on `map` (shared with the
/// reproductions, which count the nodes).
pub fn grid_options(
    cfg: &DualConfig,
    r_robot: f64,
    variant: DualVariant,
    map: &StaticMap,
) -> GridPlanOptions {
    let res = map.grid().resolution();
    GridPlanOptions {
        algorithm: Algorithm::SafeAStar,
        inflate_m: r_robot + cfg.inflate_margin,
        bottom_up_eps: (variant == DualVariant::SafeDual).then_some(cfg.bottom_up_error / res),
        safe: SafeAStarConfig {
            epsilon: cfg.safe_epsilon,
            window_radius: cfg.safe_window,
            ..SafeAStarConfig::default()
        },
        ..Default::default()
    }
}

impl GoalProvider for DualGuide {
    fn name(&self) -> &'static str {
        match self.variant {
            DualVariant::SafeDual => "safe-dual-dwa",
            DualVariant::Preliminary => "preliminary-fusion",
        }
    }

    fn guide(&mut self, obs: &Observation<'_>, base: Weights) -> Guidance {
        let robot = [obs.state.x, obs.state.y];
        if dist(obs.goal, self.goal) > 1e-9 {
            // The final goal moved without set_goal: replan from here.
            if self.replan(obs.map, robot, obs.goal).is_err() {
                self.goal = obs.goal;
                self.lost = true;
            }
        }
        let n = self.route.waypoints.len();
        let mut mode = "normal";
        if !self.lost {
            // Reached the temporary goal: take the next one.
            while self.idx + 1 < n
                && dist(robot, self.route.waypoints[self.idx]) < self.cfg.switch_radius
            {
                self.idx += 1;
            }
            // Detour replanning, [S] §4.2: the current temporary goal lies
            // behind the robot relative to the next one.
            if self.variant == DualVariant::SafeDual {
                while let Some(j) = self.passed(obs.map, robot) {
                    self.detour_switches += (j + 1 - self.idx) as u32;
                    self.idx = j + 1;
                    mode = "detour-replan";
                }
            }
        }
        let (goal, kind) = match self.route.waypoints.get(self.idx) {
            Some(&p) if !self.lost && self.idx + 1 < n => (p, GoalKind::Intermediate),
            _ => (self.goal, GoalKind::Final),
        };
        // Dual velocity model, [S] eq 9–12.
        let v_prev = obs.state.v;
        let hold = self.variant == DualVariant::SafeDual
            && self.cfg.dual_velocity
            && kind == GoalKind::Intermediate
            && dist(robot, goal) < self.cfg.hold_distance
            && v_prev.is_finite()
            && v_prev >= self.cfg.hold_min_speed;
        if hold && mode == "normal" {
            mode = "hold-v";
        }
        Guidance {
            goal,
            kind,
            weights: base,
            rho: 1.0,
            hold_v: hold.then_some(v_prev),
            braking: false,
            mode,
        }
    }

    fn retarget(
        &mut self,
        map: &StaticMap,
        state: &RobotState,
        goal: [f64; 2],
    ) -> Result<(), LocalError> {
        check_goal(goal)?;
        self.replan(map, [state.x, state.y], goal)
    }

    fn route(&self) -> &[[f64; 2]] {
        &self.route.path
    }

    fn annotate(&self, debug: &mut PlannerDebug) {
        debug.global_path.clone_from(&self.route.path);
        // Feature nodes (or path nodes) with the start, as [S] Fig 6 draws
        // them.
        debug.keypoints.clear();
        debug.keypoints.extend(self.route.path.first().copied());
        debug.keypoints.extend_from_slice(&self.route.waypoints);
    }
}

impl SafeDualDwa {
    /// \[S\]'s planner for `robot` on `map` from `start` to `goal`. Errors:
    /// an invalid config (naming the field) or no global path.
    pub fn safe_dual(
        cfg: DualConfig,
        robot: &RobotSpec,
        map: &StaticMap,
        start: &RobotState,
        goal: [f64; 2],
    ) -> Result<Self, LocalError> {
        Self::build(cfg, DualVariant::SafeDual, robot, map, start, goal)
    }

    /// The preliminary fusion baseline.
    pub fn preliminary(
        cfg: PreliminaryConfig,
        robot: &RobotSpec,
        map: &StaticMap,
        start: &RobotState,
        goal: [f64; 2],
    ) -> Result<Self, LocalError> {
        let full = DualConfig {
            dwa: cfg.dwa,
            inflate_margin: cfg.inflate_margin,
            safe_epsilon: cfg.safe_epsilon,
            safe_window: cfg.safe_window,
            switch_radius: cfg.switch_radius,
            dual_velocity: false,
            ..DualConfig::default()
        };
        Self::build(full, DualVariant::Preliminary, robot, map, start, goal)
    }

    fn build(
        cfg: DualConfig,
        variant: DualVariant,
        robot: &RobotSpec,
        map: &StaticMap,
        start: &RobotState,
        goal: [f64; 2],
    ) -> Result<Self, LocalError> {
        let name = match variant {
            DualVariant::SafeDual => "safe-dual-dwa",
            DualVariant::Preliminary => "preliminary-fusion",
        };
        cfg.validate(name)?;
        check_goal(goal)?;
        let dual = variant == DualVariant::SafeDual;
        let engine = cfg.dwa.engine(robot, &format!("{name}.dwa"), dual)?;
        let r_robot = robot.footprint.circumscribed_radius();
        let route = plan_route(
            map,
            [start.x, start.y],
            goal,
            &grid_options(&cfg, r_robot, variant, map),
            DualGuide::which(variant),
        )?;
        Ok(DwaPlanner::from_parts(
            engine,
            cfg.dwa.weights(),
            DualGuide {
                cfg,
                variant,
                r_robot,
                goal,
                route,
                idx: 0,
                detour_switches: 0,
                lost: false,
            },
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::super::testkit::{self, End};
    use super::super::LocalPlanner;
    use super::*;
    use crate::world::{Footprint, RobotLimits};

    fn robot() -> RobotSpec {
        RobotSpec {
            footprint: Footprint::Circle { radius: 0.2 },
            limits: RobotLimits {
                w_max: 20f64.to_radians(),
                acc_w: 50f64.to_radians(),
                ..RobotLimits::default()
            },
            ..Default::default()
        }
    }

    /// 12 × 8 m at 0.25 m with a wall to go around.
    fn room() -> StaticMap {
        let mut rows = Vec::new();
        for r in 0..32 {
            let row: String = (0..48)
                .map(|c| {
                    if (22..24).contains(&c) && r >= 10 {
                        '#'
                    } else {
                        '.'
                    }
                })
                .collect();
            rows.push(row);
        }
        testkit::map(&(rows.join("\n") + "\n"), 0.25)
    }

    fn at(x: f64, y: f64) -> RobotState {
        RobotState {
            x,
            y,
            ..Default::default()
        }
    }

    const GOAL: [f64; 2] = [11.0, 1.0];

    fn planner(map: &StaticMap) -> SafeDualDwa {
        SafeDualDwa::safe_dual(DualConfig::default(), &robot(), map, &at(1.0, 1.0), GOAL).unwrap()
    }

    fn obs<'a>(s: &'a RobotState, map: &'a StaticMap) -> Observation<'a> {
        testkit::observation(s, GOAL, map)
    }

    #[test]
    fn theta_a_is_the_angle_at_the_robot() {
        let t = DualGuide::theta_a([0.0, 0.0], [1.0, 0.0], [0.0, 2.0]);
        assert!((t - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
        let t = DualGuide::theta_a([0.0, 0.0], [-1.0, 0.0], [3.0, 0.1]);
        assert!(t > 3.0);
        assert_eq!(DualGuide::theta_a([0.0, 0.0], [0.0, 0.0], [1.0, 0.0]), 0.0);
    }

    #[test]
    fn feature_nodes_are_few_and_the_robot_gets_round_the_wall() {
        let map = room();
        let goal = [11.0, 1.0];
        let mut p =
            SafeDualDwa::safe_dual(DualConfig::default(), &robot(), &map, &at(1.0, 1.0), goal)
                .unwrap();
        let route = p.guide().route().clone();
        assert!(route.waypoints.len() * 4 < route.path_nodes, "{route:?}");
        let r = testkit::run(&mut p, &map, &robot(), at(1.0, 1.0), goal, &[], 120.0, 0.2);
        assert_eq!(r.end, End::Reached, "{:?}", r.states.last());
        assert!(r.min_clearance > 0.0);
        assert!(r.modes.iter().any(|m| m == "hold-v"), "{:?}", r.modes);
        let d = p.debug();
        assert_eq!(d.keypoints.len(), route.waypoints.len() + 1);
        assert!(!d.global_path.is_empty());
    }

    #[test]
    fn detour_replanning_skips_a_passed_goal() {
        let map = room();
        let mut p = planner(&map);
        let wps = p.guide().route().waypoints.clone();
        assert!(wps.len() >= 2, "{wps:?}");
        // Put the robot beyond the first temporary goal, on the way to the
        // second: θa ≥ 90°, so the planner steers to the second.
        let (a, b) = (wps[0], wps[1]);
        let beyond = [a[0] + 0.6 * (b[0] - a[0]), a[1] + 0.6 * (b[1] - a[1])];
        let s = at(beyond[0], beyond[1]);
        p.step(&obs(&s, &map));
        assert!(p.guide().waypoint_index() >= 1);
        assert_eq!(p.debug().current_goal, wps[p.guide().waypoint_index()]);
        assert_eq!(p.debug().goal_kind, GoalKind::Intermediate);
    }

    #[test]
    fn held_speed_near_a_temporary_goal_and_nan_config_refused() {
        let map = room();
        let mut p = planner(&map);
        let wp = p.guide().route().waypoints[0];
        // 2 m short of the first temporary goal at 0.35 m/s: v stays 0.35.
        let (dx, dy) = (wp[0] - 1.0, wp[1] - 1.0);
        let l = hypot(dx, dy);
        let s = RobotState {
            v: 0.35,
            theta: crate::num::atan2(dy, dx),
            ..at(wp[0] - 2.0 * dx / l, wp[1] - 2.0 * dy / l)
        };
        let c = p.step(&obs(&s, &map));
        assert_eq!(p.debug().mode, "hold-v", "{wp:?}");
        assert_eq!(c.v, 0.35);
        let e = SafeDualDwa::safe_dual(
            DualConfig {
                hold_distance: f64::NAN,
                ..Default::default()
            },
            &robot(),
            &map,
            &at(1.0, 1.0),
            [11.0, 1.0],
        )
        .unwrap_err();
        assert!(e.to_string().contains("safe-dual-dwa.hold_distance"), "{e}");
    }
}
