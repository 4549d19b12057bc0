//! The two ROS trajectory generators: base_local_planner's
//! `TrajectoryPlanner` sampling with `dwa: true` ([`TrajectoryPlannerWindow`])
//! and Nav2 DWB's `StandardTrajectoryGenerator` ([`StandardGenerator`]).
//! Both roll a sample out from the robot's current velocity, accelerating
//! toward it at the robot's limits every step (the sources'
//! `computeNewVelocity`), and the rollout's first point is the current pose.

use crate::local::engine::generator::{
    axis, reachable, Sample, Trajectory, TrajectoryGenerator, Window, WindowRequest,
    MAX_ROLLOUT_STEPS,
};
use crate::local::Observation;
use crate::num::{atan2, cos, hypot, sin, wrap_angle};
use crate::world::{Command, RobotLimits};

/// `v` moved toward `goal` by at most `acc·dt` (`computeNewVelocity`).
fn toward(goal: f64, v: f64, acc: f64, dt: f64) -> f64 {
    if goal >= v {
        goal.min(v + acc * dt)
    } else {
        goal.max(v - acc * dt)
    }
}

/// Rolls `cmd` out from the observed state: `n` steps of `dt`, the speed
/// ramping toward `cmd` at `limits`' accelerations; points are the poses
/// before each step (`with_end`: and the pose after the last).
fn ramp_rollout(
    obs: &Observation<'_>,
    sample: Sample,
    limits: &RobotLimits,
    (n, dt, with_end): (usize, f64, bool),
    traj: &mut Trajectory,
) {
    let s = obs.state;
    traj.sample = sample;
    traj.dt = dt;
    traj.points.clear();
    traj.dirs.clear();
    traj.speeds.clear();
    traj.min_clearance = f64::INFINITY;
    let (mut x, mut y, mut th) = (s.x, s.y, s.theta);
    let (mut v, mut w) = (s.v, s.w);
    let push = |x: f64, y: f64, th: f64, v: f64, traj: &mut Trajectory| {
        traj.points.push([x, y]);
        traj.dirs.push([sin(th), cos(th)]);
        traj.speeds.push(v);
    };
    for _ in 0..n {
        push(x, y, th, v, traj);
        v = toward(sample.cmd.v, v, limits.acc_v, dt);
        w = toward(sample.cmd.w, w, limits.acc_w, dt);
        x += v * cos(th) * dt;
        y += v * sin(th) * dt;
        th = wrap_angle(th + w * dt);
    }
    if with_end {
        push(x, y, th, v, traj);
    }
    traj.final_speed = v;
    traj.horizon = traj.points.len();
    traj.end_theta = traj.dirs.last().map_or(s.theta, |&[sn, cs]| atan2(sn, cs));
}

/// Settings of [`TrajectoryPlannerWindow`] (validated by the planner).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrajectoryPlannerSettings {
    /// Forward speeds sampled.
    pub vx_samples: u32,
    /// Turn rates sampled.
    pub vtheta_samples: u32,
    /// Rollout horizon, s.
    pub sim_time: f64,
    /// Linear step of a rollout, m.
    pub sim_granularity: f64,
    /// Angular step term of a rollout, rad.
    pub angular_sim_granularity: f64,
    /// Slowest forward sample, m/s.
    pub min_vel_x: f64,
    /// Slowest in-place turn, rad/s.
    pub min_in_place_vel_theta: f64,
}

/// base_local_planner's `createTrajectories` with `dwa: true` for a
/// differential robot (`holonomic_robot: false`): the forward window
/// `[max(min_vel_x, v − a·T_p), max(min(v_max, d_goal/sim_time, v + a·T_p),
/// min_vel_x)]` × `[max(−ω_max, ω − α·T_p), min(ω_max, ω + α·T_p)]` with
/// T_p the control period, `vx_samples` speeds each with a straight
/// rollout and `vtheta_samples − 1` turn rates from the lowest up; then
/// `vtheta_samples` in-place rotations over the same turn rates, lifted to
/// at least `min_in_place_vel_theta` and skipped within one turn-rate step
/// of 0. While escaping (the planner sets it) only the rotations.
#[derive(Debug, Clone)]
pub struct TrajectoryPlannerWindow {
    limits: RobotLimits,
    set: TrajectoryPlannerSettings,
    escaping: bool,
}

impl TrajectoryPlannerWindow {
    /// The window of `limits` under `set`.
    pub fn new(limits: RobotLimits, set: TrajectoryPlannerSettings) -> Self {
        Self {
            limits,
            set,
            escaping: false,
        }
    }

    /// Escape mode: no forward samples.
    pub fn set_escaping(&mut self, on: bool) {
        self.escaping = on;
    }

    /// Whether escape mode is on.
    pub fn escaping(&self) -> bool {
        self.escaping
    }
}

impl TrajectoryGenerator for TrajectoryPlannerWindow {
    fn name(&self) -> &'static str {
        "base_local_planner window (dwa: true)"
    }

    fn horizon(&self) -> (usize, f64) {
        // Steps vary per sample (`rollout`); 0.05 s is move_base's
        // controller_frequency 20 Hz, used only without a valid `dt`.
        (1, 0.05)
    }

    fn samples(
        &mut self,
        obs: &Observation<'_>,
        req: &WindowRequest,
        out: &mut Vec<Sample>,
    ) -> Window {
        let s = obs.state;
        let l = &self.limits;
        let set = &self.set;
        let tp = req.dt;
        let min_x = set.min_vel_x.min(l.v_max);
        let goal_d = hypot(obs.goal[0] - s.x, obs.goal[1] - s.y);
        let max_x = l.v_max.min(goal_d / set.sim_time);
        let max_x = max_x.min(s.v + l.acc_v * tp).max(min_x);
        let lo_x = min_x.max(s.v - l.acc_v * tp);
        let max_th = l.w_max.min(s.w + l.acc_w * tp);
        let min_th = (-l.w_max).max(s.w - l.acc_w * tp);
        let step = |lo: f64, hi: f64, n: u32| {
            if n > 1 {
                (hi - lo) / f64::from(n - 1)
            } else {
                f64::INFINITY
            }
        };
        let dvx = step(lo_x, max_x, set.vx_samples);
        let dvth = step(min_th, max_th, set.vtheta_samples);
        let cmd = |v: f64, w: f64| Sample {
            cmd: Command { v, vy: 0.0, w },
            decel: 0.0,
        };
        out.clear();
        if !self.escaping {
            for i in 0..set.vx_samples {
                let vx = if i == 0 {
                    lo_x
                } else {
                    lo_x + dvx * f64::from(i)
                };
                out.push(cmd(vx, 0.0));
                for j in 0..set.vtheta_samples.saturating_sub(1) {
                    out.push(cmd(vx, min_th + dvth * f64::from(j)));
                }
            }
        }
        for i in 0..set.vtheta_samples {
            let w = if i == 0 {
                min_th
            } else {
                min_th + dvth * f64::from(i)
            };
            if w > dvth || w < -dvth {
                let lifted = if w > 0.0 {
                    w.max(set.min_in_place_vel_theta)
                } else {
                    w.min(-set.min_in_place_vel_theta)
                };
                out.push(cmd(0.0, lifted));
            }
        }
        Window {
            v: (lo_x, max_x),
            w: (min_th, max_th),
            brake_v: None,
            reach: f64::INFINITY,
            limited: false,
        }
    }

    fn rollout(&self, obs: &Observation<'_>, sample: Sample, _steps: usize, traj: &mut Trajectory) {
        // `generateTrajectory`'s step count (the angular term has no
        // sim_time factor in the source).
        let set = &self.set;
        let vmag = sample.cmd.v.abs();
        let n = (((vmag * set.sim_time) / set.sim_granularity)
            .max(sample.cmd.w.abs() / set.angular_sim_granularity)
            + 0.5) as usize;
        let n = n.clamp(1, MAX_ROLLOUT_STEPS);
        ramp_rollout(
            obs,
            sample,
            &self.limits,
            (n, set.sim_time / n as f64, false),
            traj,
        );
    }
}

/// Settings of [`StandardGenerator`] (validated by the planner).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StandardSettings {
    /// Forward speeds sampled.
    pub vx_samples: u32,
    /// Turn rates sampled.
    pub vtheta_samples: u32,
    /// Rollout horizon, s.
    pub sim_time: f64,
    /// Linear step of a rollout, m.
    pub linear_granularity: f64,
    /// Angular step of a rollout, rad.
    pub angular_granularity: f64,
    /// Append the final pose once more (the source's `include_last_point`).
    pub include_last_point: bool,
}

/// Nav2 DWB's `StandardTrajectoryGenerator` with its `XYThetaIterator`:
/// each axis's window is what the robot reaches within `sim_time` (the
/// source's iterator is started with `sim_time`, not the control period)
/// from its current velocity (v in `[v_min, v_max]`, ω in `±ω_max`),
/// `vx_samples` × `vtheta_samples` evenly spread samples (0 added on an
/// axis whose window straddles it), speed outer, turn rate inner; a
/// rollout lasts `sim_time` in `⌈max(|v|·T/linear_granularity,
/// |ω|·T/angular_granularity)⌉` equal steps; the poses are the start and
/// the pose after each step (with `include_last_point` the last twice, as
/// the source appends it again).
#[derive(Debug, Clone)]
pub struct StandardGenerator {
    limits: RobotLimits,
    set: StandardSettings,
    vs: Vec<f64>,
    ws: Vec<f64>,
}

impl StandardGenerator {
    /// The generator of `limits` under `set`.
    pub fn new(limits: RobotLimits, set: StandardSettings) -> Self {
        Self {
            limits,
            set,
            vs: Vec::new(),
            ws: Vec::new(),
        }
    }
}

impl TrajectoryGenerator for StandardGenerator {
    fn name(&self) -> &'static str {
        "DWB StandardTrajectoryGenerator"
    }

    fn horizon(&self) -> (usize, f64) {
        // Steps vary per sample; 0.05 s is Nav2's controller_frequency
        // 20 Hz, used only without a valid `dt`.
        (1, 0.05)
    }

    fn samples(
        &mut self,
        obs: &Observation<'_>,
        req: &WindowRequest,
        out: &mut Vec<Sample>,
    ) -> Window {
        let s = obs.state;
        let l = &self.limits;
        // DWB's iterator projects the velocity over sim_time, not over one
        // control period (`startNewIteration(current_velocity, sim_time_)`).
        let _ = req;
        let t = self.set.sim_time;
        let (v_lo, v_hi) = reachable(s.v, l.acc_v, l.v_min, l.v_max, t);
        let (w_lo, w_hi) = reachable(s.w, l.acc_w, -l.w_max, l.w_max, t);
        axis(&mut self.vs, v_lo, v_hi, 0.0, self.set.vx_samples.max(1));
        axis(
            &mut self.ws,
            w_lo,
            w_hi,
            0.0,
            self.set.vtheta_samples.max(1),
        );
        out.clear();
        for &v in &self.vs {
            for &w in &self.ws {
                out.push(Sample {
                    cmd: Command { v, vy: 0.0, w },
                    decel: 0.0,
                });
            }
        }
        Window {
            v: (v_lo, v_hi),
            w: (w_lo, w_hi),
            brake_v: None,
            reach: f64::INFINITY,
            limited: false,
        }
    }

    fn rollout(&self, obs: &Observation<'_>, sample: Sample, _steps: usize, traj: &mut Trajectory) {
        let set = &self.set;
        let lin = sample.cmd.v.abs() * set.sim_time / set.linear_granularity;
        let ang = sample.cmd.w.abs() * set.sim_time / set.angular_granularity;
        let n = (lin.max(ang).ceil() as usize).clamp(1, MAX_ROLLOUT_STEPS);
        ramp_rollout(
            obs,
            sample,
            &self.limits,
            (n, set.sim_time / n as f64, true),
            traj,
        );
        if set.include_last_point {
            // The source appends the final pose a second time.
            if let (Some(&p), Some(&d)) = (traj.points.last(), traj.dirs.last()) {
                traj.points.push(p);
                traj.dirs.push(d);
                traj.speeds.push(traj.final_speed);
                traj.horizon = traj.points.len();
            }
        }
    }
}
