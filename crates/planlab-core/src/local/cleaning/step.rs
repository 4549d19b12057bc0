//! One control period as a composition of the local-planning engine: \[C\]'s
//! load-limited window with its slip-matrix rollout ([`LoadWindow`], eq 9–10,
//! 14, 18) as the generator, and the cost of eq 13 as four critics
//! ([`CostmapObstacle`], [`GoalDistanceL1`], [`PathDistanceL1`] and nav2
//! DWB's twirling) under the weighted-cost rule.

use super::odometry::mat_vec;
use super::path::l1_to_segment;
use super::{CleaningDwa, CleaningDwaConfig, LoadRegion, Mat3, COST_SCALE};
use crate::local::engine::critic::{Critic, CriticContext};
use crate::local::engine::generator::{
    Sample, Trajectory, TrajectoryGenerator, Window, WindowRequest, MAX_ROLLOUT_STEPS,
};
use crate::local::engine::StepRequest;
use crate::local::{LocalError, LocalPlanner, Observation, PlannerDebug};
use crate::map::costmap::{Costmap, INSCRIBED};
use crate::num::{cos, sin};
use crate::world::terrain::{GRAVITY, IDENTITY};
use crate::world::{Command, Drive, RobotSpec, RobotState, StaticMap};

/// Samples of one velocity axis: `now + i·res` within [lo, hi] (the window
/// ∩ the limits), plus lo and hi themselves; at most `max` (then evenly
/// spaced, `now` kept). `now` is clamped into [lo, hi] first.
pub(super) fn axis_samples(now: f64, lo: f64, hi: f64, res: f64, max: usize) -> Vec<f64> {
    if lo > hi || lo.is_nan() || hi.is_nan() {
        return vec![now];
    }
    let now = now.clamp(lo, hi);
    let span = (hi - now).max(now - lo);
    let mut res = res;
    let n = (span / res + 1e-9).floor();
    if 2.0 * n + 1.0 > max as f64 {
        let half = ((max.saturating_sub(1)) / 2).max(1) as f64;
        res = span / half;
    }
    let mut out = vec![lo];
    let below = ((now - lo) / res + 1e-9).floor() as i64;
    let above = ((hi - now) / res + 1e-9).floor() as i64;
    for i in -below..=above {
        let v = now + i as f64 * res;
        if v > lo && v < hi {
            out.push(v);
        }
    }
    if hi > lo {
        out.push(hi);
    }
    if !out.contains(&now) {
        out.push(now);
    }
    out.sort_by(f64::total_cmp);
    out.dedup();
    out
}

/// \[C\]'s window and rollout (module doc of [`super`]: **Window and
/// samples**, **Vertical-load limit**, **Rollouts**). The planner sets the
/// odometry correction K and the held a_z every period
/// ([`LoadWindow::set_inputs`]).
#[derive(Debug, Clone)]
pub struct LoadWindow {
    cfg: CleaningDwaConfig,
    robot: RobotSpec,
    steps: usize,
    k: Mat3,
    az: f64,
}

impl LoadWindow {
    /// The window of `robot` under the settings `cfg` (validated).
    pub fn new(cfg: CleaningDwaConfig, robot: &RobotSpec) -> Self {
        let steps = ((cfg.sim_time / cfg.sim_dt).round() as usize).clamp(1, MAX_ROLLOUT_STEPS);
        Self {
            cfg,
            robot: *robot,
            steps,
            k: IDENTITY,
            az: 0.0,
        }
    }

    /// This period's odometry correction and held vertical acceleration.
    pub fn set_inputs(&mut self, k: Mat3, az: f64) {
        self.k = k;
        self.az = az;
    }

    /// Eq 14's bound on |a_x|, |a_y| (None: no load limit).
    fn load_bound(&self) -> Option<f64> {
        self.cfg.load_limit.then(|| {
            let j = self.cfg.load_fraction;
            let veh = &self.cfg.vehicle;
            let b = if veh.h > 0.0 {
                (GRAVITY - 4.0 * j * GRAVITY - self.az) * veh.l_r / veh.h
            } else {
                f64::INFINITY
            };
            b.max(0.0)
        })
    }

    /// Smallest wheel load minus j·m·g (N) after accelerating to (vx, vy)
    /// in one period (\[C\] eq 8 with the measured a_z); ≥ 0 is allowed.
    /// Keeping the velocity is always allowed (+∞).
    fn load_margin(&self, obs: &Observation<'_>, vx: f64, vy: f64) -> f64 {
        let s = obs.state;
        if (vx == s.v && vy == s.vy) || obs.dt <= 0.0 {
            return f64::INFINITY;
        }
        let veh = &self.cfg.vehicle;
        let min = self.cfg.load_fraction * veh.mass * GRAVITY;
        let loads = veh.wheel_loads((vx - s.v) / obs.dt, (vy - s.vy) / obs.dt, self.az);
        loads.iter().fold(f64::INFINITY, |a, &f| a.min(f)) - min
    }

    /// The sampled axes (v_x, v_y, ω lists) and the load bound.
    fn axes(&self, obs: &Observation<'_>) -> (Vec<f64>, Vec<f64>, Vec<f64>, Option<f64>) {
        let l = &self.robot.limits;
        let s = obs.state;
        let dt = obs.dt.max(0.0);
        let max = self.cfg.max_samples_per_axis;
        let bound = self.load_bound();
        let (mut ax, mut ay) = (l.acc_v, l.acc_vy);
        if let (Some(b), LoadRegion::Box) = (bound, self.cfg.load_region) {
            ax = ax.min(b);
            ay = ay.min(b);
        }
        let vx = axis_samples(
            s.v,
            l.v_min.max(s.v - ax * dt),
            l.v_max.min(s.v + ax * dt),
            self.cfg.v_res,
            max,
        );
        let vy = match self.robot.drive {
            Drive::Differential => vec![0.0],
            Drive::Omnidirectional => axis_samples(
                s.vy,
                (-l.vy_max).max(s.vy - ay * dt),
                l.vy_max.min(s.vy + ay * dt),
                self.cfg.v_res,
                max,
            ),
        };
        let w = axis_samples(
            s.w,
            (-l.w_max).max(s.w - l.acc_w * dt),
            l.w_max.min(s.w + l.acc_w * dt),
            self.cfg.w_res,
            max,
        );
        (vx, vy, w, bound)
    }

    /// Translational samples: the (v_x, v_y) grid, with samples faster than
    /// the speed limit scaled back onto the circle |v| = vmax (dropping those
    /// that then leave the window) so every direction offers the full speed
    /// and no body heading is favoured by the grid; with the diamond load
    /// region, only samples that keep every wheel loaded.
    fn pairs(
        &self,
        obs: &Observation<'_>,
        vxs: &[f64],
        vys: &[f64],
        diamond: bool,
    ) -> Vec<(f64, f64)> {
        let s = obs.state;
        let vmax = if self.cfg.max_speed > 0.0 {
            self.cfg.max_speed
        } else {
            self.robot.limits.v_max
        };
        let (xlo, xhi) = (
            vxs.first().copied().unwrap_or(s.v),
            vxs.last().copied().unwrap_or(s.v),
        );
        let (ylo, yhi) = (
            vys.first().copied().unwrap_or(s.vy),
            vys.last().copied().unwrap_or(s.vy),
        );
        let mut pairs: Vec<(f64, f64)> = Vec::with_capacity(vxs.len() * vys.len());
        // The sample that keeps the most load, in case none keeps enough.
        let mut least_bad: Option<(f64, (f64, f64))> = None;
        for &vx in vxs {
            for &vy in vys {
                let n2 = vx * vx + vy * vy;
                let (vx, vy) = if n2 > vmax * vmax && (vx, vy) != (s.v, s.vy) {
                    let f = vmax / n2.sqrt();
                    (vx * f, vy * f)
                } else {
                    (vx, vy)
                };
                let eps = 1e-12;
                if vx < xlo - eps || vx > xhi + eps || vy < ylo - eps || vy > yhi + eps {
                    continue;
                }
                if pairs.contains(&(vx, vy)) {
                    continue;
                }
                if diamond {
                    let margin = self.load_margin(obs, vx, vy);
                    if margin < 0.0 {
                        if least_bad.map_or(true, |(m, _)| margin > m) {
                            least_bad = Some((margin, (vx, vy)));
                        }
                        continue;
                    }
                }
                pairs.push((vx, vy));
            }
        }
        if pairs.is_empty() {
            // Even holding the velocity overloads (a_z beyond g(1 − 4j)):
            // take the gentlest sample rather than braking hard.
            if let Some((_, p)) = least_bad {
                pairs.push(p);
            }
        }
        pairs
    }
}

impl TrajectoryGenerator for LoadWindow {
    fn name(&self) -> &'static str {
        "load-limited window"
    }

    fn horizon(&self) -> (usize, f64) {
        (self.steps, self.cfg.sim_dt)
    }

    fn samples(
        &mut self,
        obs: &Observation<'_>,
        _req: &WindowRequest,
        out: &mut Vec<Sample>,
    ) -> Window {
        let (vxs, vys, ws, bound) = self.axes(obs);
        let diamond = bound.is_some() && self.cfg.load_region == LoadRegion::Diamond;
        let pairs = self.pairs(obs, &vxs, &vys, diamond);
        out.clear();
        for &w in &ws {
            for &(v, vy) in &pairs {
                out.push(Sample {
                    cmd: Command { v, vy, w },
                    decel: 0.0,
                });
            }
        }
        // Reach ≤ ‖K_xy‖_F·|(v_x, v_y, ω)|·T.
        let vt = pairs
            .iter()
            .map(|&(a, b)| a * a + b * b)
            .fold(0.0, f64::max);
        let wm = ws.iter().map(|w| w * w).fold(0.0, f64::max);
        let kf = self.k[..2]
            .iter()
            .flatten()
            .map(|k| k * k)
            .sum::<f64>()
            .sqrt();
        let l = &self.robot.limits;
        let span = |xs: &[f64], d: f64| {
            (
                xs.first().copied().unwrap_or(d),
                xs.last().copied().unwrap_or(d),
            )
        };
        Window {
            v: span(&vxs, obs.state.v),
            w: span(&ws, obs.state.w),
            brake_v: None,
            // Eq 14's bound tighter than the motors' acceleration limit.
            limited: bound.is_some_and(|b| b < l.acc_v.max(l.acc_vy)),
            reach: kf * (vt + wm).sqrt() * self.steps as f64 * self.cfg.sim_dt,
        }
    }

    fn rollout(&self, obs: &Observation<'_>, sample: Sample, steps: usize, traj: &mut Trajectory) {
        let dt = self.cfg.sim_dt;
        let cmd = sample.cmd;
        let inc = mat_vec(&self.k, [cmd.v * dt, cmd.vy * dt, cmd.w * dt]);
        let s = obs.state;
        traj.clear(sample, dt);
        let (mut x, mut y) = (s.x, s.y);
        let (mut sn, mut cs) = (sin(s.theta), cos(s.theta));
        let (sd, cd) = (sin(inc[2]), cos(inc[2]));
        let speed = (inc[0] * inc[0] + inc[1] * inc[1]).sqrt() / dt;
        for _ in 0..steps {
            x += cs * inc[0] - sn * inc[1];
            y += sn * inc[0] + cs * inc[1];
            (sn, cs) = (sn * cd + cs * sd, cs * cd - sn * sd);
            traj.points.push([x, y]);
            if traj.with_dirs {
                traj.dirs.push([sn, cs]);
            }
            traj.speeds.push(speed);
        }
        traj.final_speed = speed;
        traj.horizon = steps.min(self.steps);
        traj.end_theta = crate::num::atan2(sn, cs);
    }
}

/// \[C\] eq 13's c_obs: the costmap cost of the cells the rollout passes
/// through, summed over its points (÷ [`COST_SCALE`]); illegal when a point
/// comes within the robot's circumscribed radius (plus half a cell: the
/// clearance field's error) of a wall or the map edge, or of a perceived
/// mover moved on at constant velocity.
#[derive(Debug, Clone)]
pub struct CostmapObstacle {
    costmap: Costmap,
    origin: [f64; 2],
    res: f64,
    radius: f64,
    /// Cost band beyond the footprint: inflation radius + safety distance.
    band: f64,
    /// This cycle: far from every wall and mover, nothing to check.
    free: bool,
}

impl CostmapObstacle {
    /// The critic on `costmap` (its frame is `map`'s) for `robot`, whose
    /// costs reach `band` m beyond the inflation.
    pub fn new(costmap: Costmap, map: &StaticMap, robot: &RobotSpec, band: f64) -> Self {
        let grid = map.grid();
        let o = grid.origin();
        Self {
            costmap,
            origin: [o.x, o.y],
            res: grid.resolution(),
            radius: robot.footprint.circumscribed_radius() + 0.5 * grid.resolution(),
            band,
            free: false,
        }
    }
}

impl Critic for CostmapObstacle {
    fn name(&self) -> &str {
        "obstacle_cost"
    }

    fn needs_headings(&self) -> bool {
        false
    }

    fn prepare(&mut self, ctx: &CriticContext<'_>) {
        // Far from every wall and mover no rollout can collide or enter the
        // cost band: skip the per-point checks (same result, much faster in
        // open yards).
        let s = ctx.obs.state;
        self.free = ctx.obs.movers.is_empty()
            && ctx.obs.map.clearance(s.x, s.y)
                > ctx.window.reach + self.radius + self.band + 2.0 * self.res;
    }

    fn score(&self, ctx: &CriticContext<'_>, traj: &Trajectory) -> Option<f64> {
        if self.free {
            return Some(0.0);
        }
        let obs = ctx.obs;
        let (w, h) = (self.costmap.width as i64, self.costmap.height as i64);
        let radius = self.radius;
        let mut c_obs = 0.0;
        for (i, &[x, y]) in traj.points.iter().enumerate() {
            let t = (i + 1) as f64 * traj.dt;
            let col = ((x - self.origin[0]) / self.res).floor();
            let row_b = ((y - self.origin[1]) / self.res).floor();
            let on_map = col >= 0.0 && row_b >= 0.0 && (col as i64) < w && (row_b as i64) < h;
            let ok = on_map
                && obs.map.clearance(x, y) > radius
                && obs.movers.iter().all(|m| {
                    let (mx, my) = (m.pos[0] + m.vel[0] * t, m.pos[1] + m.vel[1] * t);
                    let r = radius + m.radius;
                    (mx - x) * (mx - x) + (my - y) * (my - y) > r * r
                });
            if !ok {
                return None;
            }
            let idx = (h - 1 - row_b as i64) * w + col as i64;
            let c = self
                .costmap
                .costs
                .get(idx as usize)
                .copied()
                .unwrap_or(INSCRIBED);
            c_obs += f64::from(c) / COST_SCALE;
        }
        Some(c_obs)
    }
}

/// \[C\] eq 13's d_g: the Manhattan distance (m) from the rollout's end to
/// the goal.
#[derive(Debug, Clone, Default)]
pub struct GoalDistanceL1;

impl Critic for GoalDistanceL1 {
    fn name(&self) -> &str {
        "goal_distance_m"
    }
    fn needs_headings(&self) -> bool {
        false
    }

    fn score(&self, ctx: &CriticContext<'_>, traj: &Trajectory) -> Option<f64> {
        let [x, y] = traj.end();
        Some((x - ctx.goal[0]).abs() + (y - ctx.goal[1]).abs())
    }
}

/// \[C\] eq 13's d_p: the Manhattan distance (m) from the rollout's end to
/// the local path (to its one point when it has no segment).
#[derive(Debug, Clone, Default)]
pub struct PathDistanceL1;

impl Critic for PathDistanceL1 {
    fn name(&self) -> &str {
        "path_distance_m"
    }
    fn needs_headings(&self) -> bool {
        false
    }

    fn score(&self, ctx: &CriticContext<'_>, traj: &Trajectory) -> Option<f64> {
        let [x, y] = traj.end();
        let d_p = ctx
            .path
            .windows(2)
            .map(|sgm| l1_to_segment([x, y], sgm[0], sgm[1]))
            .fold(f64::INFINITY, f64::min);
        Some(if d_p.is_finite() {
            d_p
        } else {
            ctx.path
                .first()
                .map_or(0.0, |q| (x - q[0]).abs() + (y - q[1]).abs())
        })
    }
}

impl LocalPlanner for CleaningDwa {
    fn name(&self) -> &'static str {
        self.name
    }

    fn step(&mut self, obs: &Observation<'_>) -> Command {
        if self.cfg.compensate {
            self.push_odometry(obs);
        }
        self.hold_accel_z(obs.accel_z);
        let s = obs.state;
        let (goal, kind, local) = self.local_goal([s.x, s.y]);
        let (k, az) = (self.k, self.az_estimate);
        self.engine.generator_mut().set_inputs(k, az);
        let res = self.engine.plan(
            obs,
            &StepRequest {
                path: &local,
                ..StepRequest::to(goal)
            },
        );
        let d = self.engine.debug_mut();
        d.current_goal = goal;
        d.goal_kind = kind;
        d.mode = match (res.admissible > 0, res.window.limited) {
            (false, _) => "no-admissible",
            (true, true) => "load-limited",
            (true, false) => "normal",
        }
        .into();
        res.cmd
    }

    fn set_goal(
        &mut self,
        _map: &StaticMap,
        state: &RobotState,
        goal: [f64; 2],
    ) -> Result<(), LocalError> {
        if !(goal[0].is_finite() && goal[1].is_finite()) {
            return Err(LocalError::InvalidParameter(format!(
                "goal ({}, {}) must be finite",
                goal[0], goal[1]
            )));
        }
        // The cleaning targets belonged to the old route: go straight there
        // (on error nothing changes).
        self.replan([state.x, state.y], &[], goal)?;
        let d = self.engine.debug_mut();
        d.keypoints.clear();
        d.current_goal = goal;
        Ok(())
    }

    fn debug(&self) -> &PlannerDebug {
        self.engine.debug()
    }

    fn set_record_rollouts(&mut self, on: bool) {
        self.engine.set_record(on);
    }
}
