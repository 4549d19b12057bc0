//! Baseline Dynamic Window Approach (docs/algorithms.md §dwa; Fox, Burgard & Thrun 1997 as
//! restated in \[T\] eq 3-1…3-5), written as a reusable engine.
//!
//! One control step:
//! 1. **Window** V_r = V_s ∩ V_d: speeds within the robot's limits and
//!    reachable within one control period under its accelerations
//!    ([`crate::world::RobotLimits`]).
//! 2. **Samples** (v, ω) on the window at resolutions (`v_res`, `w_res`), or
//!    a fixed number per axis (`v_samples`, `w_samples`); 0 is added on an
//!    axis whose window contains it (stopping, driving straight).
//! 3. **Rollouts**: each sample is held for `predict_time`, stepping the
//!    docs/algorithms.md §robot Euler update of [`crate::world::robot::integrate`] every
//!    `sim_dt`.
//! 4. **Clearance** of every rollout point: the static map's
//!    [`StaticMap::clearance`] minus the footprint's circumscribed radius
//!    (and `safety_margin`), and the distance to every perceived mover disc —
//!    at its position at the rollout step's time when `predict_movers`
//!    (constant velocity, the default), else at its current position; a
//!    moving disc counts larger by the distance it covers in one control
//!    period (it may turn before the robot sees it again).
//!    A rollout whose clearance reaches 0 collides and is discarded (early
//!    exit); so is one breaking V_a: v ≤ √(2·dist·v̇_b), |ω| ≤ √(2·dist·ω̇_b)
//!    with dist, as in Fox et al., the distance the robot drives *along
//!    its arc* before the first contact (same contact test: map, movers
//!    where the rollout predicts them), for ω the angle it turns on the way
//!    ([`DwaCore`]'s `va_time` has the decision). Within the horizon the
//!    collision test has decided already; a fast sample whose braking
//!    outlasts the horizon has its arc followed on until it can stop.
//! 5. **Critics** on the admissible rollouts: heading = π − |bearing error
//!    to the goal at the rollout end|, dist = smallest clearance capped at
//!    `dist_cap`, velocity = v. Each is divided by its sum over the
//!    admissible samples (docs/algorithms.md §dwa) and G = α·head + ρ·β·dist + γ·vel
//!    picks the command (ρ = 1 for the baseline; \[T\] eq 3-8 sets it).
//!
//! A braking rollout is followed past the horizon until the robot stands.
//! A robot at rest starts off only on a sample it could brake out of before
//! any perceived mover, free to turn round at once, could reach it
//! (passive safety; docs/algorithms.md §dwa).
//!
//! With no admissible sample the robot brakes at its largest deceleration
//! and, for a circular footprint, turns in place toward the goal (mode
//! `"no-admissible"`; only when that braking turn hits nothing) — unless
//! braking itself would be hit or would stop the robot in a mover's
//! predicted path (a mover that keeps
//! coming): then it takes what Fox et al.'s DWA takes, the collision-free
//! sample with the best G, the critics normalised over those samples
//! (`"no-admissible-evade"`).
//! Nothing here panics or returns NaN.
//!
//! **Defaults.** \[T\] gives no numeric DWA parameters (its tables list only
//! map and APF settings). Its simulations, like \[S\]'s (whose §5 values
//! match exactly: v_max 1 m/s, ω_max 20, a_v 0.2 m/s², a_ω 50, Δt 0.1 s,
//! α 0.05, γ 0.1), descend from the widely copied MATLAB "Dynamic Window
//! Approach sample": α 0.05, β 0.2, γ 0.1, predict 3.0 s, v_res 0.01 m/s,
//! ω_res 1°/s, dist capped at 2·R = 1.0 m. Those are the defaults here; the
//! speed and acceleration limits come from [`crate::world::RobotSpec`].
//!
//! **Movers.** The improved variants reuse [`DwaCore`] with their own
//! [`GoalProvider`]: it picks the goal, the weight set, ρ and an optional
//! held linear speed (\[S\]'s dual-velocity model) every step.

use super::{GoalKind, LocalError, LocalPlanner, Observation, PlannerDebug, Rollout};
use crate::geom::closest_along;
use crate::num::{atan2, cos, hypot, sin, wrap_angle};
use crate::params::Params;
use crate::world::robot::integrate;
use crate::world::{Command, Footprint, RobotSpec, RobotState, StaticMap};

/// Critic names, in the order of [`Rollout::raw`] and [`Rollout::normalised`].
pub const CRITICS: [&str; 3] = ["heading", "dist", "velocity"];

/// Most samples on one axis of the window (a tiny resolution cannot make a
/// step take forever).
pub const MAX_SAMPLES_PER_AXIS: usize = 1001;

/// A braking rollout's rest point must stay out of every mover's predicted
/// path for this many rollout horizons.
pub const REST_HORIZONS: f64 = 4.0;

/// Most integration steps in one rollout (`predict_time / sim_dt`).
pub const MAX_ROLLOUT_STEPS: usize = 10_000;

crate::params::params! {
    /// Critic weights of G = α·head + β·dist + γ·vel.
    #[derive(Debug, Clone, Copy, PartialEq)]
    pub struct Weights {
        pub alpha: f64 = 0.05, "1" [>= 0.0] "α, weight of the heading critic";
        pub beta: f64 = 0.2, "1" [>= 0.0] "β, weight of the clearance critic";
        pub gamma: f64 = 0.1, "1" [>= 0.0] "γ, weight of the velocity critic";
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
            "α, heading weight: π − |bearing error at the rollout end|";
        pub beta: f64 = 0.2, "1" [>= 0.0] "β, clearance weight: smallest clearance, capped";
        pub gamma: f64 = 0.1, "1" [>= 0.0] "γ, velocity weight: forward speed";
        pub v_res: f64 = 0.01, "m/s" [> 0.0]
            "linear-speed sampling resolution (when v_samples = 0)";
        pub w_res: f64 = 1f64.to_radians(), "rad/s" [> 0.0]
            "turn-rate sampling resolution (when w_samples = 0)";
        pub v_samples: u32 = 0, "1" []
            "linear speeds per step, evenly spread; 0 = by v_res";
        pub w_samples: u32 = 0, "1" [] "turn rates per step, evenly spread; 0 = by w_res";
        pub predict_time: f64 = 3.0, "s" [> 0.0] "rollout horizon";
        pub sim_dt: f64 = 0.1, "s" [> 0.0] "rollout integration step";
        pub dist_cap: f64 = 1.0, "m" [> 0.0] "clearance critic saturates here";
        /// Rollouts closer than this to anything collide.
        pub safety_margin: f64 = 0.0, "m" [>= 0.0] "extra clearance kept beyond the footprint";
        pub predict_movers: bool = true, "bool" []
            "movers move at their observed velocity along rollouts";
        /// Fox et al.'s braking distance.
        pub admissible_window: bool = true, "bool" []
            "apply V_a: v ≤ √(2·dist·v̇_b), |ω| ≤ √(2·dist·ω̇_b), dist along the arc to the first contact";
        pub rotate_in_place: bool = true, "bool" []
            "with no admissible sample, a round robot turns toward the goal";
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

    fn rollout_steps(&self) -> usize {
        ((self.predict_time / self.sim_dt - 1e-9).ceil() as usize).clamp(1, MAX_ROLLOUT_STEPS)
    }
}

/// What one step of the engine is asked to do.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepRequest {
    /// The goal the heading critic steers to, metres.
    pub goal: [f64; 2],
    /// Critic weights for this step.
    pub weights: Weights,
    /// Relative distance factor ρ multiplying β (\[T\] eq 3-8); 1 = off.
    pub rho: f64,
    /// Hold the linear speed at this value (\[S\] eq 9–12); `None` = the
    /// normal window. When no sample at the held speed is admissible the
    /// normal window is used instead.
    pub hold_v: Option<f64>,
    /// Also roll out braking manoeuvres: from the window's lowest speed
    /// down to a stop at the largest deceleration, one per sampled ω (the
    /// deceleration strategy of \[T\] Table 3-1: constant-speed rollouts
    /// cannot show that slowing down now avoids a mover later).
    pub braking: bool,
}

/// What one step of the engine chose.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepResult {
    /// The command.
    pub cmd: Command,
    /// Number of admissible samples (0: the braking fallback was used).
    pub admissible: usize,
    /// Number of samples evaluated.
    pub samples: usize,
    /// Whether the held speed had to be released (no admissible sample).
    pub hold_released: bool,
}

/// Per-sample scratch record.
#[derive(Debug, Clone, Copy, Default)]
struct Cand {
    v: f64,
    w: f64,
    /// heading, dist (capped), velocity.
    raw: [f64; 3],
    admissible: bool,
    /// Collides within the horizon.
    collided: bool,
}

/// One rollout step of `h` s at speed `v`: the position advances along
/// the heading whose (sin, cos) is `sc`, then the heading turns by the
/// exact rotation `rot` = (sin ωh, cos ωh) — the Euler update of
/// [`integrate`] without a sin/cos per step.
#[inline(always)]
fn arc_step(
    (x, y): (&mut f64, &mut f64),
    (sn, cs): (&mut f64, &mut f64),
    v: f64,
    (sd, cd): (f64, f64),
    h: f64,
) {
    *x += v * *cs * h;
    *y += v * *sn * h;
    let (ns, nc) = (*sn * cd + *cs * sd, *cs * cd - *sn * sd);
    *sn = ns;
    *cs = nc;
}

/// The DWA engine: window, sampling, rollouts, clearance, critics. Reused by
/// every DWA variant; allocation-free per step once warmed up unless
/// rollouts are recorded.
#[derive(Debug, Clone)]
pub struct DwaCore {
    cfg: DwaConfig,
    robot: RobotSpec,
    /// Footprint's circumscribed radius + safety margin, m.
    r_eff: f64,
    round: bool,
    steps: usize,
    record: bool,
    cands: Vec<Cand>,
    vs: Vec<f64>,
    ws: Vec<f64>,
    /// Kept movers' positions per rollout step: `[k * m + j]`, k = 1..=steps.
    mover_pos: Vec<[f64; 2]>,
    mover_rad: Vec<f64>,
    kept: Vec<usize>,
    /// Rows of the mover table beyond the horizon: one control period, for
    /// braking checks that start after it.
    extra_rows: usize,
    /// Last rollout step V_a may look at: the arc is followed past the
    /// horizon while the braking time needs it (see [`Self::rollout`]).
    va_steps: usize,
    /// Last rollout step a braking rollout may reach: it is followed past
    /// the horizon until the robot stands (see [`Self::rollout`]).
    brake_steps: usize,
    /// Every perceived mover (position, velocity, radius), for rest checks.
    all_movers: Vec<([f64; 2], [f64; 2], f64)>,
    /// Collision threshold and clearance horizon of the last evaluation.
    last_limit: f64,
    last_horizon: f64,
    last_dt: f64,
    /// Half a map cell: allowance for the clearance field's error, m.
    slack: f64,
    points: Vec<[f64; 2]>,
    debug: PlannerDebug,
}

impl DwaCore {
    /// Builds the engine; the config is validated (errors name `prefix.field`).
    pub fn new(cfg: DwaConfig, robot: &RobotSpec, prefix: &str) -> Result<Self, LocalError> {
        cfg.validate(prefix)?;
        robot
            .validate()
            .map_err(|e| LocalError::InvalidParameter(e.to_string()))?;
        let debug = PlannerDebug {
            critics: CRITICS.iter().map(|s| s.to_string()).collect(),
            mode: "normal".into(),
            ..Default::default()
        };
        Ok(Self {
            r_eff: robot.footprint.circumscribed_radius() + cfg.safety_margin,
            round: matches!(robot.footprint, Footprint::Circle { .. }),
            steps: cfg.rollout_steps(),
            cfg,
            robot: *robot,
            record: false,
            cands: Vec::new(),
            vs: Vec::new(),
            ws: Vec::new(),
            mover_pos: Vec::new(),
            mover_rad: Vec::new(),
            kept: Vec::new(),
            extra_rows: 1,
            va_steps: 0,
            brake_steps: 0,
            all_movers: Vec::new(),
            last_limit: 0.0,
            last_horizon: 0.0,
            last_dt: 0.1,
            slack: 0.0,
            points: Vec::new(),
            debug,
        })
    }

    /// The config.
    pub fn config(&self) -> &DwaConfig {
        &self.cfg
    }

    /// The robot.
    pub fn robot(&self) -> &RobotSpec {
        &self.robot
    }

    /// Footprint radius plus safety margin, m.
    pub fn effective_radius(&self) -> f64 {
        self.r_eff
    }

    /// Record every rollout in [`DwaCore::debug`] or not.
    pub fn set_record(&mut self, on: bool) {
        self.record = on;
        if !on {
            self.debug.rollouts.clear();
            self.debug.chosen = None;
        }
    }

    /// What the last step did.
    pub fn debug(&self) -> &PlannerDebug {
        &self.debug
    }

    /// Mutable access, so goal providers can add their own fields.
    pub fn debug_mut(&mut self) -> &mut PlannerDebug {
        &mut self.debug
    }

    /// Clearance (m) of the robot's centre to the nearest static obstacle or
    /// perceived mover surface, without the footprint.
    pub fn centre_clearance(map: &StaticMap, movers: &[super::ObservedMover], p: [f64; 2]) -> f64 {
        let mut c = map.clearance(p[0], p[1]);
        for m in movers {
            c = c.min(hypot(m.pos[0] - p[0], m.pos[1] - p[1]) - m.radius);
        }
        c.max(0.0)
    }

    /// One control step: the best admissible command toward `req.goal`.
    pub fn plan(&mut self, obs: &Observation<'_>, req: &StepRequest) -> StepResult {
        let s = *obs.state;
        let finite = [s.x, s.y, s.theta, s.v, s.w, req.goal[0], req.goal[1]]
            .iter()
            .all(|x| x.is_finite());
        if !finite {
            // A broken state: stop rather than compute with NaN.
            self.debug.mode = "invalid-state".into();
            self.debug.rollouts.clear();
            self.debug.chosen = None;
            return StepResult {
                cmd: Command::default(),
                admissible: 0,
                samples: 0,
                hold_released: false,
            };
        }
        let dt = if obs.dt.is_finite() && obs.dt > 0.0 {
            obs.dt
        } else {
            self.cfg.sim_dt
        };
        let mut res = self.evaluate(obs, req, dt, req.hold_v);
        if res.admissible == 0 && req.hold_v.is_some() {
            res = self.evaluate(obs, req, dt, None);
            res.hold_released = true;
        }
        if res.admissible == 0 {
            self.debug.chosen = None;
            let evade = if self.braking_collides(obs.map, &s) {
                // Braking will not avoid it (a mover keeps coming, or the
                // robot would stop in a mover's predicted path): fall back
                // on Fox et al.'s own rule, the best collision-free sample.
                // The rest and stranding checks that ruled every sample out
                // look 4 horizons ahead at constant velocity — wrong for a
                // mover that turns round — and the most-clearance choice
                // used before tied at the critic's cap whenever nothing came
                // within the horizon, so it turned the robot on the spot in
                // a mover's way until that arrived (dwa-demo variants).
                self.best_collision_free(req)
            } else {
                None
            };
            match evade {
                Some((i, _)) => {
                    let c = self.cands[i];
                    res.cmd = Command {
                        v: c.v,
                        vy: 0.0,
                        w: c.w,
                    };
                    self.debug.mode = "no-admissible-evade".into();
                    if self.record {
                        self.debug.chosen = Some(i);
                    }
                }
                None => {
                    res.cmd = self.fallback(obs.map, &s, req.goal, dt);
                    self.debug.mode = "no-admissible".into();
                }
            }
        }
        res
    }

    /// Number of rows in the movers' position table.
    fn mover_rows(&self) -> usize {
        self.mover_pos
            .len()
            .checked_div(self.mover_rad.len())
            .unwrap_or(self.table_rows())
    }

    /// Rows the movers' position table needs: the horizon plus one control
    /// period, or as far as V_a follows an arc or a braking rollout runs.
    fn table_rows(&self) -> usize {
        (self.steps + self.extra_rows)
            .max(self.va_steps)
            .max(self.brake_steps)
            + 1
    }

    /// Whether a robot standing at (x, y) lies in the predicted path of a
    /// mover within [`REST_HORIZONS`] rollout horizons: stopping is only safe
    /// out of the way of what keeps coming. Without mover prediction the
    /// movers stand still and only overlap counts.
    fn rest_unsafe(&self, x: f64, y: f64) -> bool {
        let t_rest = if self.cfg.predict_movers {
            REST_HORIZONS * self.steps as f64 * self.cfg.sim_dt
        } else {
            0.0
        };
        self.all_movers.iter().any(|&(p, v, r)| {
            // Distance from (x, y) to the segment p + v·t, t ∈ [0, t_rest].
            let (dx, dy) = (v[0] * t_rest, v[1] * t_rest);
            let len2 = dx * dx + dy * dy;
            // Cheap rejections first (no division or root; the margin dwarfs
            // rounding, so the answer is the exact test's): the segment lies
            // within L/2 of its midpoint and on its line.
            let reach = r + self.r_eff + self.last_limit + 1e-9;
            if reach < 0.0 {
                return false;
            }
            let (ex, ey) = (x - p[0], y - p[1]);
            let (mx, my) = (ex - 0.5 * dx, ey - 0.5 * dy);
            let disc = reach + 0.5 * len2.sqrt();
            if mx * mx + my * my > disc * disc {
                return false;
            }
            let cross = ex * dy - ey * dx;
            if cross * cross > reach * reach * len2 * (1.0 + 1e-9) {
                return false;
            }
            let (q, _) = closest_along([x, y], p, [dx, dy]);
            hypot(q[0] - x, q[1] - y) - r - self.r_eff <= self.last_limit
        })
    }

    /// Whether driving (v, ω) for one control period and then braking at
    /// the largest deceleration could be caught, while still moving, by a
    /// perceived mover that changes course the moment after it was seen.
    ///
    /// Passive safety (Fraichard's "if a collision occurs, the robot is at
    /// rest"): a mover may turn round or toward the robot at any time —
    /// constant-velocity prediction cannot foresee a turnaround — so from
    /// its observed position it reaches |v_m|·t in time t (on top of its
    /// one-period allowance). A sample is refused when the robot, braking
    /// after this period, is still moving where such a mover could already
    /// be. A robot at rest is not checked: standing still is always allowed
    /// (the braking fallback). Without it the robot started off behind a
    /// mover 5 cm away that was about to turn round, and was hit at
    /// 0.08 m/s while braking (S-fig12, preliminary-fusion, variant 11).
    fn passive_unsafe(&self, s: &RobotState, v: f64, w: f64) -> bool {
        if self.all_movers.is_empty() || v == 0.0 || s.v != 0.0 {
            return false;
        }
        let l = &self.robot.limits;
        let h = self.cfg.sim_dt;
        let t_end = self.last_dt + v.abs() / l.acc_v;
        let travel = v.abs() * self.last_dt + 0.5 * v * v / l.acc_v;
        let reach0 = self.r_eff + self.last_limit.abs() + travel;
        let near = self.all_movers.iter().any(|&(p, mv, r)| {
            hypot(p[0] - s.x, p[1] - s.y) - r - hypot(mv[0], mv[1]) * t_end <= reach0
        });
        if !near {
            return false;
        }
        let toward_zero = |x: f64, d: f64| {
            if x > 0.0 {
                (x - d).max(0.0)
            } else {
                (x + d).min(0.0)
            }
        };
        let cmd_steps = self.extra_rows;
        let (mut st, mut vk, mut wk) = (*s, v, w);
        let mut k = 0usize;
        while k < cmd_steps || vk != 0.0 {
            if k >= cmd_steps {
                vk = toward_zero(vk, l.acc_v * h);
                wk = toward_zero(wk, l.acc_w * h);
            }
            st = integrate(
                &st,
                Command {
                    v: vk,
                    vy: 0.0,
                    w: wk,
                },
                h,
            );
            k += 1;
            if k > MAX_ROLLOUT_STEPS {
                return true;
            }
            // At rest at the end of the period: nothing more to check.
            if vk == 0.0 && k >= cmd_steps {
                break;
            }
            let t = k as f64 * h;
            let caught = self.all_movers.iter().any(|&(p, mv, r)| {
                hypot(p[0] - st.x, p[1] - st.y) - r - self.r_eff - hypot(mv[0], mv[1]) * t
                    <= self.last_limit
            });
            if caught {
                return true;
            }
        }
        false
    }

    /// Whether braking at the largest deceleration (turn rate to 0 as well)
    /// from `s` hits something within the horizon, movers predicted as in
    /// the last evaluation.
    fn braking_collides(&self, map: &StaticMap, s: &RobotState) -> bool {
        self.braking_collides_from(map, s, 0, None, false)
    }

    /// As [`Self::braking_collides`], starting `row0` rollout steps into the
    /// movers' predicted future; with `turn_to`, the turn rate follows the
    /// fallback's turn toward that goal instead of braking to 0; with
    /// `to_rest`, followed until the robot stands even past the horizon.
    fn braking_collides_from(
        &self,
        map: &StaticMap,
        s: &RobotState,
        row0: usize,
        turn_to: Option<[f64; 2]>,
        to_rest: bool,
    ) -> bool {
        let l = &self.robot.limits;
        let h = self.cfg.sim_dt;
        let (mut st, mut v, mut w) = (*s, s.v, s.w);
        let rows = self.mover_rows();
        let toward_zero = |x: f64, d: f64| {
            if x > 0.0 {
                (x - d).max(0.0)
            } else {
                (x + d).min(0.0)
            }
        };
        // From speed, or with a short horizon, the robot is still moving at
        // the horizon's end. (Only the fallback asks past it: for the
        // evade and stranding decisions, movers predicted at constant
        // velocity that far out misled more than they helped — S-fig12's
        // dual-velocity robot then stood beside a mover's turnaround.)
        let stop = (v.abs() / l.acc_v).max(w.abs() / l.acc_w) / h;
        let n = if to_rest {
            self.steps
                .max(stop.ceil().min(MAX_ROLLOUT_STEPS as f64) as usize + 1)
        } else {
            self.steps
        };
        for k in 1..=n {
            v = toward_zero(v, l.acc_v * h);
            w = match turn_to {
                Some(g) => self.turn_toward(&st, g, h),
                None => toward_zero(w, l.acc_w * h),
            };
            st = integrate(&st, Command { v, vy: 0.0, w }, h);
            let stat = map.clearance(st.x, st.y) - self.r_eff - self.slack;
            let row = (k + row0).min(rows.saturating_sub(1));
            if self.mover_clearance(stat, st.x, st.y, row, self.last_horizon) <= self.last_limit {
                return true;
            }
            // Turning on the spot moves no part of a round footprint.
            let still = v == 0.0 && (w == 0.0 || turn_to.is_some());
            if still && self.mover_rad.is_empty() {
                break;
            }
        }
        self.rest_unsafe(st.x, st.y)
    }

    /// The fallback's turn rate toward `goal`: the rate that closes the
    /// bearing error in one period `dt`, within the limits and the angular
    /// window.
    fn turn_toward(&self, s: &RobotState, goal: [f64; 2], dt: f64) -> f64 {
        let l = &self.robot.limits;
        let dw = l.acc_w * dt;
        let err = wrap_angle(atan2(goal[1] - s.y, goal[0] - s.x) - s.theta);
        let want = (err / dt).clamp(-l.w_max, l.w_max);
        want.clamp(s.w - dw, s.w + dw)
    }

    /// Braking fallback: v toward 0 at the largest deceleration; a round
    /// robot also turns toward the goal (within its angular window) when
    /// that braking turn hits nothing, else its turn rate goes to 0 too.
    fn fallback(&self, map: &StaticMap, s: &RobotState, goal: [f64; 2], dt: f64) -> Command {
        let l = &self.robot.limits;
        let dv = l.acc_v * dt;
        let v = if s.v > 0.0 {
            (s.v - dv).max(0.0)
        } else {
            (s.v + dv).min(0.0)
        };
        let dw = l.acc_w * dt;
        let toward_zero = if s.w > 0.0 {
            (s.w - dw).max(0.0)
        } else {
            (s.w + dw).min(0.0)
        };
        // Turning while still moving sweeps a wider path than braking
        // straight: it may reach a wall that straight braking stops short
        // of (T-fig3-11 with a 1 s horizon drove into the side wall so).
        let turn = self.cfg.rotate_in_place
            && self.round
            && (s.v == 0.0
                || !self.braking_collides_from(map, s, 0, Some(goal), true)
                || self.braking_collides_from(map, s, 0, None, true));
        let w = if turn {
            self.turn_toward(s, goal, dt)
        } else {
            toward_zero
        };
        Command { v, vy: 0.0, w }
    }

    /// Sample values on `[lo, hi]`.
    fn axis(out: &mut Vec<f64>, lo: f64, hi: f64, res: f64, count: u32) {
        out.clear();
        if hi - lo <= 1e-12 {
            out.push(lo);
            return;
        }
        if count > 0 {
            let n = count as usize;
            if n == 1 {
                out.push(0.5 * (lo + hi));
            } else {
                let step = (hi - lo) / (n - 1) as f64;
                out.extend((0..n).map(|i| if i + 1 == n { hi } else { lo + step * i as f64 }));
            }
        } else {
            let n = (((hi - lo) / res + 1e-9).floor() as usize + 1).min(MAX_SAMPLES_PER_AXIS);
            out.extend((0..n).map(|i| lo + res * i as f64));
            if let Some(&last) = out.last() {
                if hi - last > 1e-9 && out.len() < MAX_SAMPLES_PER_AXIS {
                    out.push(hi);
                }
            }
        }
        if lo < 0.0 && hi > 0.0 && !out.iter().any(|x| x.abs() < 1e-12) {
            out.push(0.0);
        }
    }

    /// The window [lo, hi] of one velocity component.
    fn window(cur: f64, acc: f64, min: f64, max: f64, dt: f64) -> (f64, f64) {
        let (a, b) = (cur - acc * dt, cur + acc * dt);
        let (lo, hi) = (a.max(min), b.min(max));
        if lo <= hi {
            (lo, hi)
        } else if b < min {
            (b, b)
        } else {
            (a, a)
        }
    }

    fn evaluate(
        &mut self,
        obs: &Observation<'_>,
        req: &StepRequest,
        dt: f64,
        hold_v: Option<f64>,
    ) -> StepResult {
        let s = *obs.state;
        let l = self.robot.limits;
        let (v_lo, v_hi) = match hold_v {
            Some(v) if v.is_finite() => {
                let v = v.clamp(l.v_min, l.v_max);
                (v, v)
            }
            _ => Self::window(s.v, l.acc_v, l.v_min, l.v_max, dt),
        };
        let (w_lo, w_hi) = Self::window(s.w, l.acc_w, -l.w_max, l.w_max, dt);
        let mut vs = std::mem::take(&mut self.vs);
        let mut ws = std::mem::take(&mut self.ws);
        Self::axis(&mut vs, v_lo, v_hi, self.cfg.v_res, self.cfg.v_samples);
        Self::axis(&mut ws, w_lo, w_hi, self.cfg.w_res, self.cfg.w_samples);

        // Beyond this distance clearance changes nothing: the critic is
        // capped, and collisions and V_a only ask whether it reaches the
        // threshold.
        let v_abs = v_lo.abs().max(v_hi.abs());
        let w_abs = w_lo.abs().max(w_hi.abs());
        let horizon = self.cfg.dist_cap + 1e-6;
        let h = self.cfg.sim_dt;
        // V_a follows an arc for as long as its braking needs (rollout).
        self.va_steps = if self.cfg.admissible_window {
            let t = Self::va_time(v_abs, w_abs, &l) / h;
            // `as` saturates, and NaN cannot occur (limits are validated).
            (t.ceil().min(MAX_ROLLOUT_STEPS as f64) as usize + 1).min(MAX_ROLLOUT_STEPS)
        } else {
            0
        };
        let brake_v = if req.braking && v_lo > 0.0 {
            Some(v_lo)
        } else {
            None
        };
        self.brake_steps = brake_v.map_or(0, |v| {
            // `as` saturates; limits are validated (acc_v > 0).
            ((v / l.acc_v / h).ceil().min(MAX_ROLLOUT_STEPS as f64) as usize + 1)
                .min(MAX_ROLLOUT_STEPS)
        });
        let t_total = (self.steps.max(self.va_steps).max(self.brake_steps)) as f64 * h;
        self.extra_rows = ((dt / h).round() as usize).clamp(1, MAX_ROLLOUT_STEPS);
        self.prepare_movers(obs, &s, v_abs * (t_total + dt), horizon, dt);

        // Threshold of collision: 0, or the current clearance when the
        // robot already sits inside the margin (it may leave, not go deeper).
        // The clearance field may exceed the exact distance by up to about
        // a third of a cell: keep half a cell in hand so rollouts never touch.
        self.slack = 0.5 * obs.map.grid().resolution();
        let stat0 = obs.map.clearance(s.x, s.y) - self.r_eff - self.slack;
        let c0 = self.mover_clearance(stat0, s.x, s.y, 0, horizon);
        let limit = c0.min(0.0);
        self.last_limit = limit;
        self.last_dt = dt;
        self.last_horizon = horizon;

        let (s0, c0t) = (sin(s.theta), cos(s.theta));
        let record = self.record;
        if record {
            self.debug.rollouts.clear();
        }
        self.cands.clear();
        let pairs = vs.len() * ws.len();
        let extra = if brake_v.is_some() { ws.len() } else { 0 };
        for i in 0..pairs + extra {
            let (v, w, decel) = if i < pairs {
                (vs[i / ws.len()], ws[i % ws.len()], 0.0)
            } else {
                (brake_v.unwrap_or(0.0), ws[i - pairs], l.acc_v)
            };
            {
                let cand = self.rollout(
                    obs.map,
                    &s,
                    (s0, c0t),
                    (v, w, decel),
                    (limit, stat0),
                    horizon,
                    req,
                );
                self.cands.push(cand);
                if record {
                    let mut r = Rollout {
                        cmd: Command { v, vy: 0.0, w },
                        points: Vec::with_capacity(self.points.len()),
                        admissible: cand.admissible,
                        raw: cand.raw.to_vec(),
                        normalised: vec![0.0; 3],
                        score: f64::NEG_INFINITY,
                    };
                    r.points.extend_from_slice(&self.points);
                    self.debug.rollouts.push(r);
                }
            }
        }
        self.vs = vs;
        self.ws = ws;

        // Normalise each critic by its sum over the admissible samples.
        let mut sum = [0.0f64; 3];
        let mut n_ok = 0usize;
        for c in self.cands.iter().filter(|c| c.admissible) {
            n_ok += 1;
            for (k, x) in sum.iter_mut().enumerate() {
                *x += c.raw[k];
            }
        }
        let wts = [
            req.weights.alpha,
            req.weights.beta * req.rho,
            req.weights.gamma,
        ];
        self.debug.weights.clear();
        self.debug.weights.extend_from_slice(&wts);
        let mut best: Option<(usize, f64)> = None;
        for (i, c) in self.cands.iter().enumerate() {
            if !c.admissible {
                continue;
            }
            let mut score = 0.0;
            let mut norm = [0.0f64; 3];
            for k in 0..3 {
                norm[k] = if sum[k] > 0.0 { c.raw[k] / sum[k] } else { 0.0 };
                score += wts[k] * norm[k];
            }
            if !score.is_finite() {
                score = f64::NEG_INFINITY;
            }
            if best.map_or(true, |(_, b)| score > b) {
                best = Some((i, score));
            }
            if record {
                if let Some(r) = self.debug.rollouts.get_mut(i) {
                    r.normalised.copy_from_slice(&norm);
                    r.score = score;
                }
            }
        }
        let samples = self.cands.len();
        self.debug.chosen = if record { best.map(|(i, _)| i) } else { None };
        self.debug.current_goal = req.goal;
        match best {
            Some((i, _)) => {
                let c = self.cands[i];
                StepResult {
                    cmd: Command {
                        v: c.v,
                        vy: 0.0,
                        w: c.w,
                    },
                    admissible: n_ok,
                    samples,
                    hold_released: false,
                }
            }
            None => StepResult {
                cmd: Command::default(),
                admissible: 0,
                samples,
                hold_released: false,
            },
        }
    }

    /// The collision-free candidate with the best G, each critic normalised
    /// by its sum over the collision-free candidates.
    fn best_collision_free(&self, req: &StepRequest) -> Option<(usize, f64)> {
        let mut sum = [0.0f64; 3];
        for c in self.cands.iter().filter(|c| !c.collided) {
            for (k, x) in sum.iter_mut().enumerate() {
                *x += c.raw[k];
            }
        }
        let wts = [
            req.weights.alpha,
            req.weights.beta * req.rho,
            req.weights.gamma,
        ];
        let mut best: Option<(usize, f64)> = None;
        for (i, c) in self.cands.iter().enumerate().filter(|(_, c)| !c.collided) {
            let mut score = 0.0;
            for k in 0..3 {
                if sum[k] > 0.0 {
                    score += wts[k] * c.raw[k] / sum[k];
                }
            }
            if !score.is_finite() {
                score = f64::NEG_INFINITY;
            }
            if best.map_or(true, |(_, b)| score > b) {
                best = Some((i, score));
            }
        }
        best
    }

    /// Keeps the movers that can come within `horizon` of a rollout and
    /// tabulates their positions per rollout step.
    ///
    /// A moving disc counts `|v|·dt` larger, `dt` the control period: its
    /// motion may change between two observations (a turnaround, a corner
    /// of its loop) and the robot reacts one period later, so that much is
    /// kept in hand. With the bare radius the constant-velocity prediction
    /// let the robot wait, or creep, within millimetres of a mover's path
    /// and be hit when the mover turned round (dwa-demo variants).
    fn prepare_movers(
        &mut self,
        obs: &Observation<'_>,
        s: &RobotState,
        reach: f64,
        horizon: f64,
        dt: f64,
    ) {
        self.mover_pos.clear();
        self.mover_rad.clear();
        self.all_movers.clear();
        let t_total = (self.table_rows() - 1) as f64 * self.cfg.sim_dt;
        let predict = self.cfg.predict_movers;
        let mut kept = std::mem::take(&mut self.kept);
        kept.clear();
        for (j, m) in obs.movers.iter().enumerate() {
            let finite =
                m.pos.iter().chain(m.vel.iter()).all(|x| x.is_finite()) && m.radius.is_finite();
            if !finite {
                continue;
            }
            let radius = m.radius + hypot(m.vel[0], m.vel[1]) * dt;
            self.all_movers.push((m.pos, m.vel, radius));
            let d0 = hypot(m.pos[0] - s.x, m.pos[1] - s.y) - radius - self.r_eff;
            let travel = if predict {
                hypot(m.vel[0], m.vel[1]) * t_total
            } else {
                0.0
            };
            if d0 - reach - travel <= horizon {
                kept.push(j);
            }
        }
        let n = kept.len();
        if n == 0 {
            self.kept = kept;
            return;
        }
        self.mover_rad.extend(kept.iter().map(|&j| {
            let m = &obs.movers[j];
            m.radius + hypot(m.vel[0], m.vel[1]) * dt
        }));
        let rows = self.table_rows();
        self.mover_pos.resize(rows * n, [0.0, 0.0]);
        for k in 0..rows {
            let t = if predict {
                k as f64 * self.cfg.sim_dt
            } else {
                0.0
            };
            for (jj, &j) in kept.iter().enumerate() {
                let m = &obs.movers[j];
                self.mover_pos[k * n + jj] = [m.pos[0] + m.vel[0] * t, m.pos[1] + m.vel[1] * t];
            }
        }
        self.kept = kept;
    }

    /// Clearance of the footprint (as a disc of radius `r_eff`) centred at
    /// (x, y) at rollout step k, exact up to `horizon`, given its static
    /// part `stat` (map clearance minus `r_eff`): map and movers.
    // Always inlined: the rollout's innermost call; at the wasm build's
    // opt-level "s" it would otherwise stay a call (issue 6 speed ratio).
    #[inline(always)]
    fn mover_clearance(&self, stat: f64, x: f64, y: f64, k: usize, horizon: f64) -> f64 {
        let mut best = stat;
        let n = self.mover_rad.len();
        if n > 0 {
            let row = &self.mover_pos[k * n..(k + 1) * n];
            for (p, &r) in row.iter().zip(&self.mover_rad) {
                let (dx, dy) = (p[0] - x, p[1] - y);
                let d2 = dx * dx + dy * dy;
                let lim = best.min(horizon) + r + self.r_eff;
                // Only a closer mover needs the square root.
                if lim <= 0.0 || d2 < lim * lim {
                    best = best.min(d2.sqrt() - r - self.r_eff);
                }
            }
        }
        best
    }

    /// How long an arc driven at (|v|, |ω|) must stay free of contact for
    /// V_a, s.
    ///
    /// Fox, Burgard & Thrun (1997) admit (v, ω) when the robot can stop
    /// before the closest obstacle on its arc: v ≤ √(2·dist(v,ω)·v̇_b) and
    /// ω ≤ √(2·dist(v,ω)·ω̇_b), dist(v,ω) the distance to that obstacle
    /// *along the arc* (not the nearest wall in any direction: a corridor's
    /// side walls do not slow a robot driving down it). The paper writes one
    /// dist for both bounds; **Decision**: for ω we read it as the angle
    /// the robot turns on the arc before the contact, dist·|ω|/|v| (the
    /// only reading in which the units agree; for v = 0, turning on the
    /// spot, it is |ω| times the time until a mover arrives). With t_hit
    /// the time to the first contact at constant (v, ω), dist = |v|·t_hit
    /// and the angle = |ω|·t_hit, so both bounds read
    /// t_hit ≥ max(|v|/(2·v̇_b), |ω|/(2·ω̇_b)), the braking decelerations
    /// being the robot's `acc_v`, `acc_w`.
    fn va_time(v_abs: f64, w_abs: f64, l: &crate::world::RobotLimits) -> f64 {
        (v_abs / (2.0 * l.acc_v)).max(w_abs / (2.0 * l.acc_w))
    }

    /// Rolls (v, ω) out and scores it; fills `self.points` when recording.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn rollout(
        &mut self,
        map: &StaticMap,
        s: &RobotState,
        (sin0, cos0): (f64, f64),
        (v, w, decel): (f64, f64, f64),
        (limit, stat0): (f64, f64),
        horizon: f64,
        req: &StepRequest,
    ) -> Cand {
        let h = self.cfg.sim_dt;
        let record = self.record;
        if record {
            self.points.clear();
        }
        // The Euler update of `integrate`: x += v·cos θ·h, y += v·sin θ·h,
        // θ += ω·h. cos/sin of θ_k = θ_0 + kωh advance by an exact rotation
        // (one sin/cos per sample instead of per step; deterministic).
        let (sd, cd) = (sin(w * h), cos(w * h));
        let (mut sn, mut cs) = (sin0, cos0);
        let (mut x, mut y) = (s.x, s.y);
        let mut min_c = f64::INFINITY;
        let mut collided = false;
        // Skipping map lookups far from walls: the clearance field is
        // √2-Lipschitz (bilinear over samples 1-Lipschitz per axis) up to a
        // cell at blocked-cell borders, so while the last looked-up value
        // minus √2·(distance driven since) stays above horizon + a cell, the
        // point's value is above the horizon and every decision (capped
        // critic, V_a, collision) is the same as with the exact value.
        let res = map.grid().resolution();
        let skip_above = horizon + res;
        let mut vk = v;
        let mut last = stat0;
        let mut since = 0.0;
        for k in 1..=self.steps {
            let step_len = vk.abs() * h * (1.0 + 1e-9);
            arc_step((&mut x, &mut y), (&mut sn, &mut cs), vk, (sd, cd), h);
            if decel > 0.0 {
                vk = (vk - decel * h).max(0.0);
            }
            if record {
                self.points.push([x, y]);
            }
            since += step_len;
            let stat = if last - std::f64::consts::SQRT_2 * since > skip_above {
                skip_above
            } else {
                last = map.clearance(x, y) - self.r_eff - self.slack;
                since = 0.0;
                last
            };
            let c = self.mover_clearance(stat, x, y, k, horizon);
            min_c = min_c.min(c);
            if c <= limit {
                collided = true;
                break;
            }
        }
        let theta = wrap_angle(s.theta + w * h * self.steps as f64);
        let bearing = atan2(req.goal[1] - y, req.goal[0] - x);
        let heading = std::f64::consts::PI - wrap_angle(bearing - theta).abs();
        if decel > 0.0 && !collided {
            // A braking rollout is only safe if the robot stops before any
            // contact: follow it on past the horizon until it stands (with a
            // short horizon or from speed it is still moving at the end).
            let mut k = self.steps + 1;
            while vk > 0.0 {
                if k > self.brake_steps {
                    collided = true;
                    break;
                }
                arc_step((&mut x, &mut y), (&mut sn, &mut cs), vk, (sd, cd), h);
                vk = (vk - decel * h).max(0.0);
                if record {
                    self.points.push([x, y]);
                }
                let stat = map.clearance(x, y) - self.r_eff - self.slack;
                if self.mover_clearance(stat, x, y, k, horizon) <= limit {
                    collided = true;
                    break;
                }
                k += 1;
            }
        }
        if decel > 0.0 && !collided && self.rest_unsafe(x, y) {
            // Stopping here would leave the robot in a mover's way.
            collided = true;
        }
        // A constant-speed rollout that does not get the robot out of every
        // mover's way is only worth taking if the robot can still brake
        // safely after it: DWA re-plans every period, and a run of ever
        // slower "safe" choices must not end standing in a mover's path.
        let mut stranded = false;
        if decel == 0.0
            && !collided
            && self.cfg.predict_movers
            && !self.all_movers.is_empty()
            && self.rest_unsafe(x, y)
        {
            let next = integrate(s, Command { v, vy: 0.0, w }, self.last_dt);
            stranded = self.braking_collides_from(map, &next, self.extra_rows, None, false);
        }
        let dist = min_c.max(0.0);
        // V_a (Fox et al.; see `va_time`): the arc must be free of contact
        // for the braking time. A rollout that collides is out anyway, so
        // within the horizon the collision test has decided; past it the
        // arc is followed on, with the same contact test (map, movers
        // where the rollout's prediction puts them). A braking rollout
        // stops by construction: V_a does not apply.
        let mut va_ok = true;
        if !collided && !stranded && decel == 0.0 && self.cfg.admissible_window {
            let t_need = Self::va_time(v.abs(), w.abs(), &self.robot.limits);
            // A contact at step k leaves (k − 1)·h of free arc.
            let mut k = self.steps + 1;
            while (k - 1) as f64 * h < t_need - 1e-12 {
                if k > self.va_steps {
                    // Not followed this far: only what was checked is free.
                    va_ok = false;
                    break;
                }
                arc_step((&mut x, &mut y), (&mut sn, &mut cs), vk, (sd, cd), h);
                since += vk.abs() * h * (1.0 + 1e-9);
                let stat = if last - std::f64::consts::SQRT_2 * since > skip_above {
                    skip_above
                } else {
                    last = map.clearance(x, y) - self.r_eff - self.slack;
                    since = 0.0;
                    last
                };
                if self.mover_clearance(stat, x, y, k, horizon) <= limit {
                    va_ok = false;
                    break;
                }
                k += 1;
            }
        }
        let admissible = !collided && !stranded && va_ok && !self.passive_unsafe(s, v, w);
        Cand {
            v,
            w,
            raw: [heading, dist.min(self.cfg.dist_cap), v.max(0.0)],
            admissible,
            collided,
        }
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
    fn guide(&mut self, obs: &Observation<'_>, base: Weights, core: &DwaCore) -> Guidance;
    /// The final goal moved: replan what depends on it.
    fn retarget(
        &mut self,
        map: &StaticMap,
        state: &RobotState,
        goal: [f64; 2],
        core: &DwaCore,
    ) -> Result<(), LocalError>;
    /// Adds the provider's own fields (global path, classes …) to the debug.
    fn annotate(&self, debug: &mut PlannerDebug);
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
    fn guide(&mut self, obs: &Observation<'_>, base: Weights, _core: &DwaCore) -> Guidance {
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
        _core: &DwaCore,
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

/// A DWA planner: the engine plus a goal provider.
#[derive(Debug, Clone)]
pub struct DwaPlanner<G> {
    core: DwaCore,
    guide: G,
}

/// The baseline DWA (registry name `dwa`).
pub type Dwa = DwaPlanner<FinalGoal>;

impl Dwa {
    /// Baseline DWA for `robot` heading to `goal`.
    pub fn new(cfg: DwaConfig, robot: &RobotSpec, goal: [f64; 2]) -> Result<Self, LocalError> {
        check_goal(goal)?;
        Ok(Self {
            core: DwaCore::new(cfg, robot, "dwa")?,
            guide: FinalGoal { goal },
        })
    }
}

impl<G: GoalProvider> DwaPlanner<G> {
    /// Assembles a planner from its parts.
    pub fn from_parts(core: DwaCore, guide: G) -> Self {
        Self { core, guide }
    }

    /// The engine.
    pub fn core(&self) -> &DwaCore {
        &self.core
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
        let base = self.core.config().weights();
        let g = self.guide.guide(obs, base, &self.core);
        let req = StepRequest {
            goal: g.goal,
            weights: g.weights,
            rho: if g.rho.is_finite() && g.rho >= 0.0 {
                g.rho
            } else {
                1.0
            },
            hold_v: g.hold_v,
            braking: g.braking,
        };
        let res = self.core.plan(obs, &req);
        let d = self.core.debug_mut();
        d.goal_kind = g.kind;
        d.current_goal = g.goal;
        if res.admissible > 0 {
            d.mode = if res.hold_released {
                format!("{}-released", g.mode)
            } else {
                g.mode.to_string()
            };
        }
        self.guide.annotate(self.core.debug_mut());
        res.cmd
    }

    fn set_goal(
        &mut self,
        map: &StaticMap,
        state: &RobotState,
        goal: [f64; 2],
    ) -> Result<(), LocalError> {
        self.guide.retarget(map, state, goal, &self.core)
    }

    fn debug(&self) -> &PlannerDebug {
        self.core.debug()
    }

    fn set_record_rollouts(&mut self, on: bool) {
        self.core.set_record(on);
    }
}

#[cfg(test)]
mod tests {
    use super::super::testkit::{self, End};
    use super::super::ObservedMover;
    use super::*;
    use crate::world::{MotionModel, MoverSpec, RobotLimits};

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
            let obs = Observation {
                time: 0.0,
                dt: 0.1,
                state: &s,
                goal: [19.0, 19.0],
                map: &map,
                movers: &[],
                odometry: None,
                accel_z: 0.0,
            };
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
        let obs = Observation {
            time: 0.0,
            dt: 0.1,
            state: &s,
            goal: [0.35, 5.0],
            map: &map,
            movers: &[],
            odometry: None,
            accel_z: 0.0,
        };
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
        // Issue 13's corridor: 1.5 m wide, 18 m from start to goal, 3.9 m
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
        let mut core = DwaCore::new(DwaConfig::default(), &robot(), "dwa").unwrap();
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
            movers: &movers,
            odometry: None,
            accel_z: 0.0,
        };
        let req = StepRequest {
            goal: [5.0, 3.0],
            weights: Weights::default(),
            rho: 1.0,
            hold_v: None,
            braking: false,
        };
        let res = core.plan(&obs, &req);
        assert_eq!(core.mover_rad.len(), 1, "only the near mover is kept");
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
