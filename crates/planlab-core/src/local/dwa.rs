//! Baseline Dynamic Window Approach (docs/algorithms.md §dwa; Fox, Burgard & Thrun 1997 as
//! restated in \[T\] eq 3-1…3-5), as a composition of the local-planning
//! [engine](super::engine): Fox et al.'s dynamic window (or \[S\]'s
//! dual-velocity window) as the generator, the papers' safety screen, and
//! three critics normalised by their sums (docs/algorithms.md §dwa):
//! heading = π − |bearing error to the goal at the rollout end|, dist =
//! smallest clearance capped at `dist_cap`, velocity = v, and
//! G = α·head + ρ·β·dist + γ·vel (ρ = 1 for the baseline; \[T\] eq 3-8
//! sets it).
//!
//! One step:
//! 1. **Window** V_r = V_s ∩ V_d: speeds within the robot's limits and
//!    reachable within one control period under its accelerations
//!    ([`crate::world::RobotLimits`]).
//! 2. **Samples** (v, ω) on the window at resolutions (`v_res`, `w_res`), or
//!    a fixed number per axis (`v_samples`, `w_samples`); 0 is added on an
//!    axis whose window contains it (stopping, driving straight).
//! 3. **Rollouts**: each sample is held for `predict_time`, stepping the
//!    docs/algorithms.md §robot Euler update of [`crate::world::robot::integrate`] every
//!    `sim_dt`.
//! 4. **Screen** ([`super::engine::screen`]): collision with the map and
//!    the perceived movers (predicted at constant velocity when
//!    `predict_movers`), V_a, braking and passive safety.
//! 5. **Critics** on the admissible rollouts, normalised, weighted, the best
//!    G driven; with none admissible the screen's fallback.
//!
//! **Defaults.** \[T\] gives no numeric DWA parameters (its tables list only
//! map and APF settings). Its simulations, like \[S\]'s (whose §5 values
//! match exactly: v_max 1 m/s, ω_max 20, a_v 0.2 m/s², a_ω 50, Δt 0.1 s,
//! α 0.05, γ 0.1), descend from the widely copied MATLAB "Dynamic Window
//! Approach sample": α 0.05, β 0.2, γ 0.1, predict 3.0 s, v_res 0.01 m/s,
//! ω_res 1°/s, dist capped at 2·R = 1.0 m. Those are the defaults here; the
//! speed and acceleration limits come from [`crate::world::RobotSpec`].
//!
//! **Movers.** The improved variants reuse [`super::engine::Engine`] with their own
//! [`GoalProvider`]: it picks the goal, the weight set, ρ and an optional
//! held linear speed (\[S\]'s dual-velocity model) every step.

use super::engine::critic::{Clearance, Heading, Velocity};
use super::engine::generator::{DynamicWindow, MAX_ROLLOUT_STEPS, MAX_SAMPLES_PER_AXIS};
use super::engine::{CriticSlot, Engine, Scoring, ScreenConfig, StepRequest};
use super::{GoalKind, LocalError, LocalPlanner, Observation, PlannerDebug};
use crate::params::Params;
use crate::world::Command;
use crate::world::{RobotLimits, RobotSpec, RobotState, StaticMap};

crate::params::params! {
    /// Critic weights of G = α·head + β·dist + γ·vel.
    #[derive(Debug, Clone, Copy, PartialEq)]
    pub struct Weights {
        pub alpha: f64 = 0.05, "1" [>= 0.0] label "heading weight α" "α, weight of the heading critic";
        pub beta: f64 = 0.2, "1" [>= 0.0] label "clearance weight β" "β, weight of the clearance critic";
        pub gamma: f64 = 0.1, "1" [>= 0.0] label "speed weight γ" "γ, weight of the velocity critic";
    }
}

impl Weights {
    /// Checks every weight is finite and ≥ 0; errors name `prefix.alpha` etc.
    pub fn validate(&self, prefix: &str) -> Result<(), LocalError> {
        Ok(self.check_bounds(prefix)?)
    }
}

crate::params::params! {
    /// Settings of the baseline DWA (docs/algorithms.md §dwa); `Default` is the MATLAB DWA
    /// sample both \[T\] and \[S\] build on (module doc).
    #[derive(Debug, Clone, Copy, PartialEq)]
    pub struct DwaConfig {
        pub alpha: f64 = 0.05, "1" [>= 0.0]
            label "heading weight α" "α, heading weight: π − |bearing error at the rollout end|";
        pub beta: f64 = 0.2, "1" [>= 0.0] label "clearance weight β" "β, clearance weight: smallest clearance, capped";
        pub gamma: f64 = 0.1, "1" [>= 0.0] label "speed weight γ" "γ, velocity weight: forward speed";
        pub v_res: f64 = 0.01, "m/s" [> 0.0]
            label "speed resolution" "linear-speed sampling resolution (when v_samples = 0)";
        pub w_res: f64 = 1f64.to_radians(), "rad/s" [> 0.0]
            label "turn-rate resolution" "turn-rate sampling resolution (when w_samples = 0)";
        pub v_samples: u32 = 0, "1" []
            label "speed samples" "linear speeds per step, evenly spread; 0 = by v_res";
        pub w_samples: u32 = 0, "1" [] label "turn-rate samples" "turn rates per step, evenly spread; 0 = by w_res";
        pub predict_time: f64 = 3.0, "s" [> 0.0] label "look-ahead time" "rollout horizon";
        pub sim_dt: f64 = 0.1, "s" [> 0.0] label "rollout time step" "rollout integration step";
        pub dist_cap: f64 = 1.0, "m" [> 0.0] label "clearance cap" "clearance critic saturates here";
        /// Rollouts closer than this to anything collide.
        pub safety_margin: f64 = 0.0, "m" [>= 0.0] label "safety margin" "extra clearance kept beyond the footprint";
        pub predict_movers: bool = true, "bool" []
            label "predict movers" "movers move at their observed velocity along rollouts";
        /// Fox et al.'s braking distance.
        pub admissible_window: bool = true, "bool" []
            label "admissible window V_a" "apply V_a: v ≤ √(2·dist·v̇_b), |ω| ≤ √(2·dist·ω̇_b), dist along the arc to the first contact";
        pub rotate_in_place: bool = true, "bool" []
            label "rotate in place" "with no admissible sample, a round robot turns toward the goal";
        /// A planner's own caps, as ROS planners have `max_vel_x`: the
        /// robot's limits when 0; never above them.
        pub max_speed: f64 = 0.0, "m/s" [>= 0.0, <= 100.0]
            label "top speed" "fastest forward speed sampled (0: the robot's v_max)";
        pub max_turn: f64 = 0.0, "rad/s" [>= 0.0, <= 100.0]
            label "top turn rate" "fastest turn rate sampled (0: the robot's ω_max)";
        pub max_accel: f64 = 0.0, "m/s²" [>= 0.0, <= 1000.0]
            label "acceleration" "linear acceleration of the window and of braking (0: the robot's a_v)";
        pub max_turn_accel: f64 = 0.0, "rad/s²" [>= 0.0, <= 1000.0]
            label "turn acceleration" "angular acceleration of the window and of braking (0: the robot's a_ω)";
    }
}

impl DwaConfig {
    /// The configured weights.
    pub fn weights(&self) -> Weights {
        Weights {
            alpha: self.alpha,
            beta: self.beta,
            gamma: self.gamma,
        }
    }

    /// Checks every number; errors name `prefix.field`.
    pub fn validate(&self, prefix: &str) -> Result<(), LocalError> {
        self.check_bounds(prefix)?;
        for (name, n) in [("v_samples", self.v_samples), ("w_samples", self.w_samples)] {
            if n as usize > MAX_SAMPLES_PER_AXIS {
                return Err(LocalError::InvalidParameter(format!(
                    "{prefix}.{name} = {n}: at most {MAX_SAMPLES_PER_AXIS}"
                )));
            }
        }
        if self.predict_time / self.sim_dt > MAX_ROLLOUT_STEPS as f64 {
            return Err(LocalError::InvalidParameter(format!(
                "{prefix}.predict_time / {prefix}.sim_dt = {} steps: at most {MAX_ROLLOUT_STEPS}",
                self.predict_time / self.sim_dt
            )));
        }
        Ok(())
    }

    /// The composition: the dynamic window (\[S\]'s dual-velocity window
    /// when `dual`), the papers' screen, and heading, dist and velocity
    /// weighted α, β, γ under the normalised-sum rule. The config is
    /// validated (errors name `prefix.field`).
    pub fn engine(
        &self,
        robot: &RobotSpec,
        prefix: &str,
        dual: bool,
    ) -> Result<Engine, LocalError> {
        self.validate(prefix)?;
        robot
            .validate()
            .map_err(|e| LocalError::InvalidParameter(e.to_string()))?;
        let own = robot.limits;
        let robot = &RobotSpec {
            limits: capped_limits(
                robot.limits,
                [
                    self.max_speed,
                    self.max_turn,
                    self.max_accel,
                    self.max_turn_accel,
                ],
            ),
            ..*robot
        };
        let generator = DynamicWindow::new(
            robot.limits,
            (self.v_res, self.w_res),
            (self.v_samples, self.w_samples),
            (self.predict_time, self.sim_dt),
            dual,
        );
        let critics = vec![
            CriticSlot::new(Heading, self.alpha),
            CriticSlot::new(Clearance { cap: self.dist_cap }, self.beta),
            CriticSlot::new(Velocity, self.gamma),
        ];
        let screen = ScreenConfig {
            dist_cap: self.dist_cap,
            safety_margin: self.safety_margin,
            predict_movers: self.predict_movers,
            admissible_window: self.admissible_window,
            rotate_in_place: self.rotate_in_place,
            emergency: (own != robot.limits).then_some(own),
        };
        Ok(Engine::new(
            robot,
            Box::new(generator),
            critics,
            Scoring::NormalisedSum,
            Some(screen),
        ))
    }
}

/// `limits` with a planner's own caps `[v_max, ω_max, a_v, a_ω]` applied:
/// a cap of 0 keeps the robot's value, and a cap never raises it.
pub fn capped_limits(limits: RobotLimits, caps: [f64; 4]) -> RobotLimits {
    let cap = |own: f64, robot: f64| if own > 0.0 { own.min(robot) } else { robot };
    RobotLimits {
        v_max: cap(caps[0], limits.v_max),
        w_max: cap(caps[1], limits.w_max),
        acc_v: cap(caps[2], limits.acc_v),
        acc_w: cap(caps[3], limits.acc_w),
        ..limits
    }
}

/// What a [`GoalProvider`] decides for one step.
#[derive(Debug, Clone, PartialEq)]
pub struct Guidance {
    /// The goal to steer to.
    pub goal: [f64; 2],
    /// Why that goal.
    pub kind: GoalKind,
    /// Critic weights.
    pub weights: Weights,
    /// Relative distance factor ρ on β (1 = none).
    pub rho: f64,
    /// Held linear speed (\[S\] dual-velocity model), or `None`.
    pub hold_v: Option<f64>,
    /// Also roll out braking manoeuvres (deceleration strategy).
    pub braking: bool,
    /// Strategy name for the trace ("normal", "decelerate", …).
    pub mode: &'static str,
}

/// Chooses each step's goal, weights and velocity model: the part in which
/// the DWA variants differ.
pub trait GoalProvider {
    /// Registry name of the planner this provider makes.
    fn name(&self) -> &'static str;
    /// This step's guidance; `base` are the config's weights.
    fn guide(&mut self, obs: &Observation<'_>, base: Weights) -> Guidance;
    /// The final goal moved: replan what depends on it.
    fn retarget(
        &mut self,
        map: &StaticMap,
        state: &RobotState,
        goal: [f64; 2],
    ) -> Result<(), LocalError>;
    /// Adds the provider's own fields (global path, classes …) to the debug.
    fn annotate(&self, debug: &mut PlannerDebug);
    /// The global path critics may follow (empty: none).
    fn path(&self) -> &[[f64; 2]] {
        &[]
    }
    /// The global route the provider steers along (empty: none); when the
    /// known map changes and the route now runs through an obstacle, the
    /// planner replans ([`GoalProvider::retarget`]).
    fn route(&self) -> &[[f64; 2]] {
        &[]
    }
}

/// Whether a point of `route` lies closer than `room` m to an obstacle of
/// `map` (or off it): the route no longer fits what is known.
pub fn route_blocked(map: &StaticMap, route: &[[f64; 2]], room: f64) -> bool {
    route.iter().any(|p| map.clearance(p[0], p[1]) < room)
}

/// The baseline's goal provider: always the final goal, fixed weights.
#[derive(Debug, Clone)]
pub struct FinalGoal {
    goal: [f64; 2],
}

impl GoalProvider for FinalGoal {
    fn name(&self) -> &'static str {
        "dwa"
    }
    fn guide(&mut self, obs: &Observation<'_>, base: Weights) -> Guidance {
        self.goal = obs.goal;
        Guidance {
            goal: obs.goal,
            kind: GoalKind::Final,
            weights: base,
            rho: 1.0,
            hold_v: None,
            braking: false,
            mode: "normal",
        }
    }
    fn retarget(
        &mut self,
        _map: &StaticMap,
        _state: &RobotState,
        goal: [f64; 2],
    ) -> Result<(), LocalError> {
        check_goal(goal)?;
        self.goal = goal;
        Ok(())
    }
    fn annotate(&self, _debug: &mut PlannerDebug) {}
}

/// Checks a goal point is finite.
pub(crate) fn check_goal(goal: [f64; 2]) -> Result<(), LocalError> {
    if goal[0].is_finite() && goal[1].is_finite() {
        Ok(())
    } else {
        Err(LocalError::InvalidParameter(format!(
            "goal = ({}, {}): must be finite",
            goal[0], goal[1]
        )))
    }
}

/// A DWA planner of the papers: the engine plus a goal provider.
#[derive(Debug)]
pub struct DwaPlanner<G> {
    engine: Engine,
    base: Weights,
    guide: G,
    /// The map revision the route was last checked against.
    revision: u64,
}

/// The baseline DWA (registry name `dwa`).
pub type Dwa = DwaPlanner<FinalGoal>;

impl Dwa {
    /// Baseline DWA for `robot` heading to `goal`.
    pub fn new(cfg: DwaConfig, robot: &RobotSpec, goal: [f64; 2]) -> Result<Self, LocalError> {
        check_goal(goal)?;
        Ok(Self::from_parts(
            cfg.engine(robot, "dwa", false)?,
            cfg.weights(),
            FinalGoal { goal },
        ))
    }
}

impl<G: GoalProvider> DwaPlanner<G> {
    /// Assembles a planner from its parts: the engine, the config's
    /// weights (α, β, γ) and the goal provider.
    pub fn from_parts(engine: Engine, base: Weights, guide: G) -> Self {
        Self {
            engine,
            base,
            guide,
            revision: 0,
        }
    }

    /// The engine.
    pub fn engine(&self) -> &Engine {
        &self.engine
    }

    /// The goal provider.
    pub fn guide(&self) -> &G {
        &self.guide
    }
}

impl<G: GoalProvider + Send> LocalPlanner for DwaPlanner<G> {
    fn name(&self) -> &'static str {
        self.guide.name()
    }

    fn step(&mut self, obs: &Observation<'_>) -> Command {
        if obs.map_revision != self.revision {
            self.revision = obs.map_revision;
            // The route was planned with at least this much room.
            let r = self.engine.robot().footprint.circumscribed_radius();
            if route_blocked(obs.map, self.guide.route(), r) {
                // A failed replan keeps the old route.
                let _ = self.guide.retarget(obs.map, obs.state, obs.goal);
            }
        }
        let g = self.guide.guide(obs, self.base);
        let rho = if g.rho.is_finite() && g.rho >= 0.0 {
            g.rho
        } else {
            1.0
        };
        // Critic order: heading, dist, velocity ([`DwaConfig::engine`]).
        let weights = [g.weights.alpha, g.weights.beta * rho, g.weights.gamma];
        let req = StepRequest {
            goal: g.goal,
            path: self.guide.path(),
            weights: Some(&weights),
            hold_v: g.hold_v,
            braking: g.braking,
        };
        let res = self.engine.plan(obs, &req);
        let d = self.engine.debug_mut();
        d.goal_kind = g.kind;
        d.current_goal = g.goal;
        if res.admissible > 0 {
            d.mode = if res.hold_released {
                format!("{}-released", g.mode)
            } else {
                g.mode.to_string()
            };
        }
        self.guide.annotate(self.engine.debug_mut());
        res.cmd
    }

    fn set_goal(
        &mut self,
        map: &StaticMap,
        state: &RobotState,
        goal: [f64; 2],
    ) -> Result<(), LocalError> {
        self.guide.retarget(map, state, goal)
    }

    fn debug(&self) -> &PlannerDebug {
        self.engine.debug()
    }

    fn set_record_rollouts(&mut self, on: bool) {
        self.engine.set_record(on);
    }
}

#[cfg(test)]
mod tests {
    use super::super::testkit::{self, End};
    use super::super::ObservedMover;
    use super::*;
    use crate::num::hypot;
    use crate::world::{Footprint, MotionModel, MoverSpec, RobotLimits};

    fn robot() -> RobotSpec {
        RobotSpec {
            footprint: Footprint::Circle { radius: 0.2 },
            limits: RobotLimits {
                v_max: 1.0,
                v_min: 0.0,
                w_max: 20f64.to_radians(),
                acc_v: 0.2,
                acc_w: 50f64.to_radians(),
                ..Default::default()
            },
            ..Default::default()
        }
    }

    fn open(w: usize, h: usize) -> StaticMap {
        let row = ".".repeat(w);
        let text: Vec<String> = (0..h).map(|_| row.clone()).collect();
        testkit::map(&(text.join("\n") + "\n"), 0.1)
    }

    fn at(x: f64, y: f64, theta: f64) -> RobotState {
        RobotState {
            x,
            y,
            theta,
            ..Default::default()
        }
    }

    #[test]
    fn drives_to_a_goal_in_the_open() {
        let map = open(100, 60);
        let mut p = Dwa::new(DwaConfig::default(), &robot(), [8.0, 4.5]).unwrap();
        let r = testkit::run(
            &mut p,
            &map,
            &robot(),
            at(1.0, 1.0, 0.0),
            [8.0, 4.5],
            &[],
            80.0,
            0.3,
        );
        assert_eq!(r.end, End::Reached, "{:?}", r.states.last());
        assert!(r.length < 1.3 * hypot(7.0, 3.5), "{}", r.length);
    }

    #[test]
    fn commands_stay_inside_the_window_and_critics_normalise() {
        let map = open(200, 200);
        let mut p = Dwa::new(
            DwaConfig {
                v_samples: 7,
                w_samples: 9,
                ..Default::default()
            },
            &robot(),
            [5.0, 5.0],
        )
        .unwrap();
        p.set_record_rollouts(true);
        let l = robot().limits;
        // 10 m from the walls V_a allows up to √(2·6·0.2) ≈ 1.5 m/s.
        for (v, w) in [(0.0, 0.0), (0.5, 0.2), (1.0, -0.3), (0.05, 0.34)] {
            let s = RobotState {
                v,
                w,
                ..at(10.0, 10.0, 0.3)
            };
            let obs = testkit::observation(&s, [19.0, 19.0], &map);
            let c = p.step(&obs);
            assert!(
                c.v >= (v - l.acc_v * 0.1 - 1e-12).max(0.0)
                    && c.v <= (v + l.acc_v * 0.1 + 1e-12).min(1.0)
            );
            assert!(c.w >= w - l.acc_w * 0.1 - 1e-12 && c.w <= w + l.acc_w * 0.1 + 1e-12);
            let d = p.debug();
            assert!(d.rollouts.len() >= 63);
            let chosen = d.chosen.expect("chosen");
            assert_eq!(d.rollouts[chosen].cmd.v, c.v);
            for k in 0..3 {
                let sum: f64 = d
                    .rollouts
                    .iter()
                    .filter(|r| r.admissible)
                    .map(|r| r.normalised[k])
                    .sum();
                assert!(sum == 0.0 || (sum - 1.0).abs() < 1e-9, "critic {k}: {sum}");
            }
            assert!(d.rollouts.iter().all(|r| r.points.len() == 30));
        }
    }

    #[test]
    fn boxed_in_robot_brakes_and_turns_without_nan() {
        // A 5×5-cell room at 0.1 m: the robot (r 0.2) just fits.
        let map = testkit::map(
            "#######\n#.....#\n#.....#\n#.....#\n#.....#\n#.....#\n#######\n",
            0.1,
        );
        let mut p = Dwa::new(DwaConfig::default(), &robot(), [5.0, 5.0]).unwrap();
        let s = RobotState {
            v: 0.3,
            ..at(0.35, 0.35, 0.0)
        };
        let obs = testkit::observation(&s, [0.35, 5.0], &map);
        let c = p.step(&obs);
        assert_eq!(p.debug().mode, "no-admissible");
        assert!((c.v - 0.28).abs() < 1e-12, "{c:?}");
        assert!(c.w > 0.0, "turns left toward the goal: {c:?}");
    }

    #[test]
    fn nan_config_names_the_field() {
        let e = Dwa::new(
            DwaConfig {
                beta: f64::NAN,
                ..Default::default()
            },
            &robot(),
            [1.0, 1.0],
        )
        .unwrap_err();
        assert!(
            matches!(&e, LocalError::InvalidParameter(m) if m.contains("dwa.beta")),
            "{e}"
        );
        let e = Dwa::new(
            DwaConfig {
                predict_time: -1.0,
                ..Default::default()
            },
            &robot(),
            [1.0, 1.0],
        )
        .unwrap_err();
        assert!(e.to_string().contains("dwa.predict_time"), "{e}");
    }

    #[test]
    fn predicted_movers_are_not_hit() {
        // A mover crosses the straight line to the goal; with prediction the
        // robot never touches it (it slows, waits or swerves).
        let map = open(160, 80);
        for (start, vel) in [
            ([6.0, 0.6], [0.0, 0.4]),
            ([6.0, 7.4], [0.0, -0.4]),
            ([12.0, 4.0], [-0.3, 0.0]),
        ] {
            let mover = MoverSpec {
                id: 1,
                radius: 0.3,
                motion: MotionModel::ConstantVelocity {
                    start,
                    velocity: vel,
                    since: 0.0,
                },
            };
            let mut p = Dwa::new(DwaConfig::default(), &robot(), [14.0, 4.0]).unwrap();
            let r = testkit::run(
                &mut p,
                &map,
                &robot(),
                at(1.0, 4.0, 0.0),
                [14.0, 4.0],
                &[mover],
                150.0,
                0.3,
            );
            assert_ne!(r.end, End::Collision, "mover from {start:?}");
            assert!(r.min_clearance > 0.0);
        }
    }

    /// A straight corridor `len` cells long (0.1 m), 1.5 m between the
    /// walls; `block` closes it at that column.
    fn corridor(len: usize, block: Option<usize>) -> StaticMap {
        let mut rows = vec!["#".repeat(len)];
        for _ in 0..15 {
            let mut r: Vec<u8> = format!("#{}#", ".".repeat(len - 2)).into_bytes();
            if let Some(c) = block {
                r[c..].iter_mut().for_each(|b| *b = b'#');
            }
            rows.push(String::from_utf8(r).unwrap());
        }
        rows.push("#".repeat(len));
        testkit::map(&(rows.join("\n") + "\n"), 0.1)
    }

    #[test]
    fn va_does_not_slow_a_robot_down_an_open_corridor() {
        // A long corridor: 1.5 m wide, 18 m from start to goal, 3.9 m
        // of corridor beyond it. With V_a measured to the nearest wall in
        // any direction (0.55 m away all along) dwa crawled at 0.42 m/s
        // (45 s); along the arc nothing is ahead, so V_a must not cost time.
        let map = corridor(230, None);
        let robot = RobotSpec::default();
        let (start, goal) = (at(1.05, 0.85, 0.0), [19.05, 0.85]);
        let mut times = Vec::new();
        for va in [true, false] {
            let cfg = DwaConfig {
                admissible_window: va,
                ..Default::default()
            };
            let mut p = Dwa::new(cfg, &robot, goal).unwrap();
            let r = testkit::run(&mut p, &map, &robot, start, goal, &[], 120.0, 0.2);
            assert_eq!(r.end, End::Reached, "V_a {va}: {:?}", r.states.last());
            assert!(r.min_clearance > 0.0);
            let peak = r.states.iter().map(|s| s.v).fold(0.0, f64::max);
            assert!(peak >= 0.95 * robot.limits.v_max, "V_a {va}: peak {peak}");
            times.push(r.time);
        }
        assert!(
            times[0] <= 1.1 * times[1],
            "V_a on {} s, off {} s",
            times[0],
            times[1]
        );
    }

    #[test]
    fn va_brakes_before_a_wall_straight_ahead() {
        // The corridor closed at x = 12 m, the goal just in front of the
        // wall. At 1 m/s braking takes 2.5 m: with a 1 s horizon only V_a
        // (which follows the arc on until the robot could stop) sees the
        // wall in time; with 3 s the rollouts see it too.
        let map = corridor(160, Some(120));
        let robot = RobotSpec::default();
        let a = robot.limits.acc_v;
        let r0 = robot.footprint.circumscribed_radius();
        let (start, goal) = (at(1.05, 0.85, 0.0), [11.7, 0.85]);
        // Speed where the gap to the wall first falls to 0.5 m.
        let speed_at_half_metre = |r: &testkit::Run| {
            r.states
                .iter()
                .find(|s| 12.0 - s.x - r0 <= 0.5)
                .map(|s| s.v)
        };
        // One control period of driving before braking can start, and the
        // clearance field's half cell, make the slack.
        let bound = (2.0 * 0.5 * a).sqrt() + 0.05;
        for predict_time in [1.0, 3.0] {
            let cfg = DwaConfig {
                predict_time,
                ..Default::default()
            };
            let mut p = Dwa::new(cfg, &robot, goal).unwrap();
            let r = testkit::run(&mut p, &map, &robot, start, goal, &[], 40.0, 0.1);
            assert_ne!(r.end, End::Collision, "horizon {predict_time}");
            assert!(r.min_clearance > 0.0, "horizon {predict_time}");
            let peak = r.states.iter().map(|s| s.v).fold(0.0, f64::max);
            assert!(peak >= 0.95, "horizon {predict_time}: peak {peak}");
            let v = speed_at_half_metre(&r).expect("comes within 0.5 m of the wall");
            assert!(v <= bound, "horizon {predict_time}: {v} m/s at 0.5 m");
        }
        // Without V_a the 1 s horizon arrives too fast to stop: V_a is what
        // keeps the braking distance here.
        let cfg = DwaConfig {
            predict_time: 1.0,
            admissible_window: false,
            ..Default::default()
        };
        let mut p = Dwa::new(cfg, &robot, goal).unwrap();
        let r = testkit::run(&mut p, &map, &robot, start, goal, &[], 40.0, 0.1);
        let v = speed_at_half_metre(&r).expect("comes within 0.5 m of the wall");
        assert!(v > bound, "{v} m/s at 0.5 m without V_a");
    }

    #[test]
    fn va_follows_the_arc_past_the_horizon_to_a_mover() {
        // A still disc 1.9 m ahead (surface to surface 1.4 m); at 1 m/s the
        // robot needs 2.5 m to stop and a 1 s rollout sees only 1 m: the
        // straight fast samples collide with nothing within the horizon,
        // yet V_a must reject them (and every sample of this narrow window
        // curves into the disc before it could stop).
        let map = open(200, 100);
        let s = RobotState {
            v: 1.0,
            ..at(2.0, 5.0, 0.0)
        };
        let movers = [ObservedMover {
            id: 1,
            pos: [3.9, 5.0],
            vel: [0.0, 0.0],
            radius: 0.3,
        }];
        let straight_fast = |va: bool| {
            let cfg = DwaConfig {
                predict_time: 1.0,
                admissible_window: va,
                v_samples: 3,
                w_samples: 5,
                ..Default::default()
            };
            let mut p = Dwa::new(cfg, &RobotSpec::default(), [15.0, 5.0]).unwrap();
            p.set_record_rollouts(true);
            let obs = Observation {
                time: 0.0,
                dt: 0.1,
                state: &s,
                goal: [15.0, 5.0],
                map: &map,
                map_revision: 0,
                scan: None,
                movers: &movers,
                odometry: None,
                accel_z: 0.0,
            };
            p.step(&obs);
            let d = p.debug();
            let r = d
                .rollouts
                .iter()
                .find(|r| r.cmd.w == 0.0 && r.cmd.v >= 0.98)
                .expect("a straight fast sample");
            (r.admissible, d.rollouts.iter().any(|r| r.admissible))
        };
        assert_eq!(straight_fast(false), (true, true));
        assert_eq!(straight_fast(true), (false, false));
    }

    #[test]
    fn movers_far_away_are_culled_but_near_ones_count() {
        let map = open(60, 60);
        let mut core = DwaConfig::default().engine(&robot(), "dwa", true).unwrap();
        let s = at(1.0, 3.0, 0.0);
        let movers = [
            ObservedMover {
                id: 1,
                pos: [1.9, 3.0],
                vel: [0.0, 0.0],
                radius: 0.3,
            },
            ObservedMover {
                id: 2,
                pos: [5.5, 5.5],
                vel: [0.0, 0.0],
                radius: 0.3,
            },
        ];
        let obs = Observation {
            time: 0.0,
            dt: 0.1,
            state: &s,
            goal: [5.0, 3.0],
            map: &map,
            map_revision: 0,
            scan: None,
            movers: &movers,
            odometry: None,
            accel_z: 0.0,
        };
        let req = StepRequest::to([5.0, 3.0]);
        let res = core.plan(&obs, &req);
        let kept = core.screen().map(|s| s.kept_movers());
        assert_eq!(kept, Some(1), "only the near mover is kept");
        assert!(res.admissible > 0);
        // Held speed: the v axis collapses.
        let s2 = RobotState { v: 0.3, ..s };
        let obs2 = Observation {
            state: &s2,
            movers: &[],
            ..obs
        };
        let res = core.plan(
            &obs2,
            &StepRequest {
                hold_v: Some(0.3),
                ..req
            },
        );
        assert_eq!(res.cmd.v, 0.3);
        assert_eq!(res.samples, 11);
    }
}
