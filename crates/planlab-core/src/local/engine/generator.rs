//! Trajectory generators: the velocity window of one control cycle, its
//! samples, and the integration of one sample into a rollout (Nav2 DWB's
//! `TrajectoryGenerator` plugin has the same two duties).
//!
//! A generator knows kinematics only: whether a rollout is safe is the
//! business of the engine's screen and critics.

use std::fmt;

use super::super::Observation;
use crate::num::{cos, sin, wrap_angle};
use crate::world::{Command, RobotLimits};

/// Most samples on one axis of the window (a tiny resolution cannot make a
/// step take forever).
pub const MAX_SAMPLES_PER_AXIS: usize = 1001;

/// Most integration steps in one rollout (`predict_time / sim_dt`).
pub const MAX_ROLLOUT_STEPS: usize = 10_000;

/// One sampled command of a control cycle.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Sample {
    /// The command held (or, braking, started from) over the rollout.
    pub cmd: Command,
    /// Linear deceleration along the rollout, m/s² (0: constant speed; a
    /// braking manoeuvre slows to a stop at this rate).
    pub decel: f64,
}

/// A rolled-out sample: positions, headings and speeds per integration step.
#[derive(Debug, Clone, Default)]
pub struct Trajectory {
    /// The sample.
    pub sample: Sample,
    /// Integration step, s.
    pub dt: f64,
    /// Positions (x, y) after each step, m.
    pub points: Vec<[f64; 2]>,
    /// (sin θ, cos θ) after each step, when `with_dirs` asked for them
    /// (else empty: most critics read only the end pose).
    pub dirs: Vec<[f64; 2]>,
    /// Linear speed during each step, m/s; empty when it is constant (the
    /// sample's v): see [`Trajectory::speed`].
    pub speeds: Vec<f64>,
    /// Fill `dirs` (the engine sets it when a critic needs every heading).
    pub with_dirs: bool,
    /// Linear speed after the last step, m/s.
    pub final_speed: f64,
    /// Number of points within the rollout horizon (more may follow: a
    /// braking rollout followed to rest, an arc followed for V_a).
    pub horizon: usize,
    /// Heading at the horizon's end, rad.
    pub end_theta: f64,
    /// Smallest clearance along the checked part, m (the engine's screen
    /// fills it; `INFINITY` without a screen).
    pub min_clearance: f64,
}

impl Trajectory {
    /// The position at the horizon's end (the start when empty).
    pub fn end(&self) -> [f64; 2] {
        self.points
            .get(self.horizon.saturating_sub(1))
            .copied()
            .unwrap_or([f64::NAN; 2])
    }

    /// The linear speed during step `i` (0-based), m/s.
    #[inline(always)]
    pub fn speed(&self, i: usize) -> f64 {
        self.speeds.get(i).copied().unwrap_or(self.sample.cmd.v)
    }

    /// The pose (x, y, θ) at the horizon's end.
    pub fn end_pose(&self) -> [f64; 3] {
        let e = self.end();
        [e[0], e[1], self.end_theta]
    }

    /// Empties the buffers for a rollout of `sample` at step `dt`.
    pub fn clear(&mut self, sample: Sample, dt: f64) {
        self.sample = sample;
        self.dt = dt;
        self.points.clear();
        self.dirs.clear();
        self.speeds.clear();
        self.horizon = 0;
        self.min_clearance = f64::INFINITY;
    }
}

/// What a cycle asks of the generator.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WindowRequest {
    /// Control period, s (the window is what the robot reaches in it).
    pub dt: f64,
    /// Hold the linear speed at this value (\[S\]'s dual-velocity model);
    /// generators without that model ignore it.
    pub hold_v: Option<f64>,
    /// Also roll out braking manoeuvres (\[T\]'s deceleration strategy).
    pub braking: bool,
}

/// The window a generator sampled.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Window {
    /// Linear speeds [lo, hi], m/s.
    pub v: (f64, f64),
    /// Turn rates [lo, hi], rad/s.
    pub w: (f64, f64),
    /// Start speed of the braking rollouts, when there are any.
    pub brake_v: Option<f64>,
    /// A bound on how far any rollout point gets from the start, m
    /// (`INFINITY`: not bounded), for critics that skip work far from
    /// everything.
    pub reach: f64,
    /// Whether a limit beyond the motors' (a load limit) narrowed it.
    pub limited: bool,
}

/// Samples a velocity window and integrates rollouts.
pub trait TrajectoryGenerator: Send + fmt::Debug {
    /// Name shown in parameter panels.
    fn name(&self) -> &'static str;
    /// Rollout horizon: (integration steps, step length in s).
    fn horizon(&self) -> (usize, f64);
    /// The window of this cycle: its samples go to `out` (cleared first).
    fn samples(
        &mut self,
        obs: &Observation<'_>,
        req: &WindowRequest,
        out: &mut Vec<Sample>,
    ) -> Window;
    /// Rolls `sample` out from the observed state over `steps` steps into `traj` (its buffers are reused,
    /// `dirs` filled when `traj.with_dirs`); `traj.horizon` is set to
    /// `min(steps, horizon().0)`.
    fn rollout(&self, obs: &Observation<'_>, sample: Sample, steps: usize, traj: &mut Trajectory);
}

/// Sample values on `[lo, hi]`: `count` evenly spread, or every `res`
/// (ending on `hi`), plus 0 when the interval straddles it.
pub fn axis(out: &mut Vec<f64>, lo: f64, hi: f64, res: f64, count: u32) {
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

/// The window [lo, hi] of one velocity component: `cur ± acc·dt` within
/// [min, max]; when the two do not meet, the reachable end nearest them.
pub fn reachable(cur: f64, acc: f64, min: f64, max: f64, dt: f64) -> (f64, f64) {
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

/// Rollout steps of a horizon `time` integrated every `dt`.
pub fn horizon_steps(time: f64, dt: f64) -> usize {
    ((time / dt - 1e-9).ceil() as usize).clamp(1, MAX_ROLLOUT_STEPS)
}

/// Fox, Burgard & Thrun's dynamic window (V_s ∩ V_d) of a differential
/// drive robot, sampled on a (v, ω) grid, rollouts by the Euler update of
/// [`crate::world::robot::integrate`]. With `dual`, \[S\]'s dual-velocity
/// window: a held linear speed collapses the v axis to that speed.
#[derive(Debug, Clone)]
pub struct DynamicWindow {
    limits: RobotLimits,
    v_res: f64,
    w_res: f64,
    v_samples: u32,
    w_samples: u32,
    sim_dt: f64,
    steps: usize,
    dual: bool,
    vs: Vec<f64>,
    ws: Vec<f64>,
    /// The rollouts' headings per turn rate for the last start heading.
    headings: std::cell::RefCell<Headings>,
}

/// Most (sin, cos) pairs [`Headings`] keeps (1 MiB); a window with more
/// samples × steps rolls out past it (same values, computed per rollout).
const MAX_HEADING_ENTRIES: usize = 1 << 16;

/// The headings (sin θ_k, cos θ_k) of the rollouts from one start heading
/// θ_0, per turn rate ω: θ_k depends on θ_0 and ω only, so every speed of
/// the window shares a turn rate's row. The rotation recurrence (a chain of
/// dependent multiplies, the rollout's critical path) then runs once per
/// ω instead of once per sample; each value is the one it would compute.
#[derive(Debug, Clone, Default)]
struct Headings {
    /// θ_0 (its bits; `None`: no row yet) and its (sin, cos): one sin/cos a
    /// cycle, not one a rollout.
    start: Option<(u64, f64, f64)>,
    /// Rows in use: `rows[..used]` (the others keep their allocations).
    rows: Vec<HeadingRow>,
    used: usize,
    /// Row of the last rollout: samples run through the turn rates in the
    /// same order for every speed, so the next is usually the one after.
    last: usize,
    /// Pairs held by the rows in use.
    entries: usize,
    /// One rollout's row when the table is full.
    spare: HeadingRow,
}

/// One turn rate's headings: `dirs[k]` before step k.
#[derive(Debug, Clone, Default)]
struct HeadingRow {
    /// ω's bits.
    w: u64,
    /// (sin ωh, cos ωh): the exact rotation of one step.
    rot: (f64, f64),
    dirs: Vec<[f64; 2]>,
}

impl HeadingRow {
    fn reset(&mut self, w: f64, h: f64, start: [f64; 2]) {
        self.w = w.to_bits();
        self.rot = (sin(w * h), cos(w * h));
        self.dirs.clear();
        self.dirs.push(start);
    }

    /// Extends the row to `len` headings; returns how many it added.
    fn extend_to(&mut self, len: usize) -> usize {
        let before = self.dirs.len();
        let (sd, cd) = self.rot;
        while self.dirs.len() < len {
            let [sn, cs] = self.dirs[self.dirs.len() - 1];
            self.dirs.push([sn * cd + cs * sd, cs * cd - sn * sd]);
        }
        self.dirs.len() - before
    }
}

impl Headings {
    /// The headings of a rollout from `theta` at turn rate `w`, step `h`
    /// (the same for every call), at least `len` of them.
    fn row(&mut self, theta: f64, w: f64, h: f64, len: usize) -> &[[f64; 2]] {
        let (s0, c0) = match self.start {
            Some((bits, s0, c0)) if bits == theta.to_bits() => (s0, c0),
            _ => {
                let d = (sin(theta), cos(theta));
                self.start = Some((theta.to_bits(), d.0, d.1));
                self.used = 0;
                self.entries = 0;
                d
            }
        };
        let wb = w.to_bits();
        let next = if self.last + 1 < self.used {
            self.last + 1
        } else {
            0
        };
        let found = if next < self.used && self.rows[next].w == wb {
            Some(next)
        } else {
            self.rows[..self.used].iter().position(|r| r.w == wb)
        };
        let i = match found {
            Some(i) => i,
            None if self.entries + len <= MAX_HEADING_ENTRIES => {
                if self.used == self.rows.len() {
                    self.rows.push(HeadingRow::default());
                }
                self.rows[self.used].reset(w, h, [s0, c0]);
                self.entries += 1;
                self.used += 1;
                self.used - 1
            }
            None => {
                self.spare.reset(w, h, [s0, c0]);
                self.spare.extend_to(len);
                return &self.spare.dirs;
            }
        };
        if self.rows[i].dirs.len() < len && self.entries + len > MAX_HEADING_ENTRIES {
            // Full: this rollout's row outside the table.
            let start = self.rows[i].dirs[0];
            self.spare.reset(w, h, start);
            self.spare.extend_to(len);
            return &self.spare.dirs;
        }
        self.last = i;
        self.entries += self.rows[i].extend_to(len);
        &self.rows[i].dirs
    }
}

impl DynamicWindow {
    /// The window of `limits` sampled at (`v_res`, `w_res`) or
    /// (`v_samples`, `w_samples`) per axis, rolled out over `predict_time`
    /// every `sim_dt`; `dual` makes it \[S\]'s dual-velocity window.
    /// Values are assumed validated.
    pub fn new(
        limits: RobotLimits,
        (v_res, w_res): (f64, f64),
        (v_samples, w_samples): (u32, u32),
        (predict_time, sim_dt): (f64, f64),
        dual: bool,
    ) -> Self {
        Self {
            limits,
            v_res,
            w_res,
            v_samples,
            w_samples,
            sim_dt,
            steps: horizon_steps(predict_time, sim_dt),
            dual,
            vs: Vec::new(),
            ws: Vec::new(),
            headings: std::cell::RefCell::new(Headings::default()),
        }
    }
}

impl TrajectoryGenerator for DynamicWindow {
    fn name(&self) -> &'static str {
        if self.dual {
            "dual-velocity window"
        } else {
            "dynamic window"
        }
    }

    fn horizon(&self) -> (usize, f64) {
        (self.steps, self.sim_dt)
    }

    fn samples(
        &mut self,
        obs: &Observation<'_>,
        req: &WindowRequest,
        out: &mut Vec<Sample>,
    ) -> Window {
        let s = obs.state;
        let l = self.limits;
        let (v_lo, v_hi) = match req.hold_v {
            Some(v) if self.dual && v.is_finite() => {
                let v = v.clamp(l.v_min, l.v_max);
                (v, v)
            }
            _ => reachable(s.v, l.acc_v, l.v_min, l.v_max, req.dt),
        };
        let (w_lo, w_hi) = reachable(s.w, l.acc_w, -l.w_max, l.w_max, req.dt);
        axis(&mut self.vs, v_lo, v_hi, self.v_res, self.v_samples);
        axis(&mut self.ws, w_lo, w_hi, self.w_res, self.w_samples);
        let brake_v = (req.braking && v_lo > 0.0).then_some(v_lo);
        out.clear();
        for &v in &self.vs {
            for &w in &self.ws {
                out.push(Sample {
                    cmd: Command { v, vy: 0.0, w },
                    decel: 0.0,
                });
            }
        }
        if let Some(v) = brake_v {
            // The deceleration strategy of [T] Table 3-1: constant-speed
            // rollouts cannot show that slowing down now avoids a mover
            // later.
            out.extend(self.ws.iter().map(|&w| Sample {
                cmd: Command { v, vy: 0.0, w },
                decel: l.acc_v,
            }));
        }
        Window {
            v: (v_lo, v_hi),
            w: (w_lo, w_hi),
            brake_v,
            limited: false,
            reach: f64::INFINITY,
        }
    }

    fn rollout(&self, obs: &Observation<'_>, sample: Sample, steps: usize, traj: &mut Trajectory) {
        let h = self.sim_dt;
        traj.clear(sample, h);
        let s = obs.state;
        let (v, w, decel) = (sample.cmd.v, sample.cmd.w, sample.decel);
        // cos/sin of θ_k = θ_0 + kωh advance by an exact rotation, shared by
        // the samples of one ω ([`Headings`]; deterministic). The Euler
        // update x += v·cos θ_k·h, y += v·sin θ_k·h of `integrate`.
        let mut headings = self.headings.borrow_mut();
        let dirs = headings.row(s.theta, w, h, steps + 1);
        let mut p = [s.x, s.y];
        let mut vk = v;
        if decel > 0.0 {
            for k in 0..steps {
                traj.speeds.push(vk);
                let [sn, cs] = dirs[k];
                p[0] += vk * cs * h;
                p[1] += vk * sn * h;
                vk = (vk - decel * h).max(0.0);
                traj.points.push(p);
                if traj.with_dirs {
                    traj.dirs.push(dirs[k + 1]);
                }
                if vk == 0.0 && traj.points.len() >= self.steps {
                    // At rest past the horizon: nothing more moves.
                    break;
                }
            }
        } else {
            // Constant speed: `speeds` stays empty ([`Trajectory::speed`]).
            // (`extend` over an exact-size iterator: one reservation, no
            // capacity check a step.)
            traj.points.extend(dirs[..steps].iter().map(|&[sn, cs]| {
                p[0] += vk * cs * h;
                p[1] += vk * sn * h;
                p
            }));
            if traj.with_dirs {
                traj.dirs.extend_from_slice(&dirs[1..=steps]);
            }
        }
        traj.final_speed = vk;
        traj.horizon = self.steps.min(traj.points.len());
        traj.end_theta = wrap_angle(s.theta + w * h * self.steps as f64);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::local::testkit;
    use crate::world::RobotState;

    /// The rollout as integrated before [`Headings`]: the rotation
    /// recurrence run along each rollout.
    fn recurrence(s: &RobotState, sample: Sample, steps: usize, h: f64) -> Vec<[f64; 4]> {
        let (sd, cd) = (sin(sample.cmd.w * h), cos(sample.cmd.w * h));
        let (mut sn, mut cs) = (sin(s.theta), cos(s.theta));
        let (mut p, mut vk) = ([s.x, s.y], sample.cmd.v);
        let mut out = Vec::new();
        for _ in 0..steps {
            p[0] += vk * cs * h;
            p[1] += vk * sn * h;
            (sn, cs) = (sn * cd + cs * sd, cs * cd - sn * sd);
            if sample.decel > 0.0 {
                vk = (vk - sample.decel * h).max(0.0);
            }
            out.push([p[0], p[1], sn, cs]);
        }
        out
    }

    fn rolled(g: &DynamicWindow, s: &RobotState, sample: Sample, steps: usize) -> Vec<[f64; 4]> {
        let map = testkit::map(&".".repeat(40), 0.1);
        let obs = testkit::observation(s, [3.0, 0.05], &map);
        let mut traj = Trajectory {
            with_dirs: true,
            ..Default::default()
        };
        g.rollout(&obs, sample, steps, &mut traj);
        let n = traj.points.len();
        (0..n)
            .map(|k| {
                let (p, d) = (traj.points[k], traj.dirs[k]);
                [p[0], p[1], d[0], d[1]]
            })
            .collect()
    }

    #[test]
    fn rollouts_sharing_a_turn_rate_keep_every_bit_of_their_own_recurrence() {
        let limits = RobotLimits::default();
        let g = DynamicWindow::new(limits, (0.01, 0.01), (4, 7), (3.0, 0.1), false);
        let states = [
            RobotState {
                x: 1.0,
                y: 2.0,
                theta: 0.4,
                ..Default::default()
            },
            RobotState {
                x: -3.0,
                y: 0.5,
                theta: -2.9,
                ..Default::default()
            },
        ];
        for s in &states {
            for v in [0.1, 0.35, 0.6] {
                for w in [-0.7, -0.1, 0.0, 0.3, 0.7] {
                    for (decel, steps) in [(0.0, 30), (0.5, 45), (0.0, 12)] {
                        let sample = Sample {
                            cmd: Command { v, vy: 0.0, w },
                            decel,
                        };
                        let mut want = recurrence(s, sample, steps, 0.1);
                        let got = rolled(&g, s, sample, steps);
                        // A braking rollout stops once at rest past the horizon.
                        want.truncate(got.len());
                        assert_eq!(
                            got.iter()
                                .flatten()
                                .map(|x| x.to_bits())
                                .collect::<Vec<_>>(),
                            want.iter()
                                .flatten()
                                .map(|x| x.to_bits())
                                .collect::<Vec<_>>(),
                            "v {v} w {w} decel {decel}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn a_full_heading_table_rolls_out_the_same_values() {
        let limits = RobotLimits::default();
        let g = DynamicWindow::new(limits, (0.01, 0.01), (4, 7), (3.0, 0.1), false);
        let s = RobotState {
            theta: 1.1,
            ..Default::default()
        };
        let sample = |w| Sample {
            cmd: Command { v: 0.4, vy: 0.0, w },
            decel: 0.0,
        };
        let first = rolled(&g, &s, sample(0.2), 30);
        g.headings.borrow_mut().entries = MAX_HEADING_ENTRIES - 10;
        // A new turn rate, and a known one grown past its row, both spill.
        let spilled = rolled(&g, &s, sample(-0.4), 30);
        let grown = rolled(&g, &s, sample(0.2), 60);
        assert_eq!(spilled, recurrence(&s, sample(-0.4), 30, 0.1));
        assert_eq!(grown, recurrence(&s, sample(0.2), 60, 0.1));
        assert_eq!(&grown[..30], &first[..]);
    }
}
