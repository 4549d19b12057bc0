//! One control period: the sampled window (\[C\] eq 9–10), the rollouts
//! and their cost (eq 12–13, 18), and the choice.

use super::odometry::mat_vec;
use super::path::l1_to_segment;
use super::{CleaningDwa, LoadRegion, COST_SCALE, MAX_ROLLOUT_STEPS};
use crate::local::{LocalError, LocalPlanner, Observation, PlannerDebug, Rollout};
use crate::map::costmap::INSCRIBED;
use crate::num::{cos, sin};
use crate::world::{Command, Drive, RobotState, StaticMap};

/// One evaluated sample.
#[derive(Debug, Clone, Copy)]
struct Sample {
    cmd: Command,
    admissible: bool,
    raw: [f64; 4],
    cost: f64,
}

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

impl CleaningDwa {
    /// The sampled window (v_x, v_y, ω lists) and whether the load limit
    /// bound; samples violating the diamond are dropped later.
    fn window(&self, obs: &Observation<'_>) -> (Vec<f64>, Vec<f64>, Vec<f64>, Option<f64>) {
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

    /// Rolls `cmd` out; returns (admissible, raw critics) and fills
    /// `points` when given.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn rollout(
        &self,
        obs: &Observation<'_>,
        cmd: Command,
        steps: usize,
        goal: [f64; 2],
        local: &[[f64; 2]],
        radius: f64,
        free: bool,
        mut points: Option<&mut Vec<[f64; 2]>>,
    ) -> (bool, [f64; 3]) {
        let dt = self.cfg.sim_dt;
        let inc = mat_vec(&self.k, [cmd.v * dt, cmd.vy * dt, cmd.w * dt]);
        let s = obs.state;
        let (mut x, mut y) = (s.x, s.y);
        let (mut sn, mut cs) = (sin(s.theta), cos(s.theta));
        let (sd, cd) = (sin(inc[2]), cos(inc[2]));
        let (w, h) = (self.costmap.width as i64, self.costmap.height as i64);
        let mut c_obs = 0.0;
        let mut ok = true;
        for k in 1..=steps {
            x += cs * inc[0] - sn * inc[1];
            y += sn * inc[0] + cs * inc[1];
            (sn, cs) = (sn * cd + cs * sd, cs * cd - sn * sd);
            if let Some(p) = points.as_deref_mut() {
                p.push([x, y]);
            }
            if free || !ok {
                continue;
            }
            let t = k as f64 * dt;
            let col = ((x - self.origin[0]) / self.res).floor();
            let row_b = ((y - self.origin[1]) / self.res).floor();
            let on_map = col >= 0.0 && row_b >= 0.0 && (col as i64) < w && (row_b as i64) < h;
            ok = on_map
                && obs.map.clearance(x, y) > radius
                && obs.movers.iter().all(|m| {
                    let (mx, my) = (m.pos[0] + m.vel[0] * t, m.pos[1] + m.vel[1] * t);
                    let r = radius + m.radius;
                    (mx - x) * (mx - x) + (my - y) * (my - y) > r * r
                });
            if !ok {
                if points.is_none() {
                    break;
                }
                continue;
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
        let d_g = (x - goal[0]).abs() + (y - goal[1]).abs();
        let d_p = local
            .windows(2)
            .map(|sgm| l1_to_segment([x, y], sgm[0], sgm[1]))
            .fold(f64::INFINITY, f64::min);
        let d_p = if d_p.is_finite() {
            d_p
        } else {
            local
                .first()
                .map_or(0.0, |q| (x - q[0]).abs() + (y - q[1]).abs())
        };
        (ok, [c_obs, d_g, d_p])
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
        self.debug.current_goal = goal;
        self.debug.goal_kind = kind;
        let steps =
            ((self.cfg.sim_time / self.cfg.sim_dt).round() as usize).clamp(1, MAX_ROLLOUT_STEPS);
        // The clearance field may overestimate by up to a third of a cell:
        // half a cell of margin keeps "admissible" collision-free.
        let radius = self.robot.footprint.circumscribed_radius() + 0.5 * self.res;
        let (vxs, vys, ws, bound) = self.window(obs);
        let diamond = bound.is_some() && self.cfg.load_region == LoadRegion::Diamond;
        // Shown as mode "load-limited" when eq 14's bound is tighter than
        // the motors' acceleration limit.
        let limited =
            bound.is_some_and(|b| b < self.robot.limits.acc_v.max(self.robot.limits.acc_vy));
        let vmax = if self.cfg.max_speed > 0.0 {
            self.cfg.max_speed
        } else {
            self.robot.limits.v_max
        };
        // Translational samples: the (v_x, v_y) grid, with samples faster
        // than vmax scaled back onto the circle |v| = vmax (dropping those
        // that then leave the window) so every direction offers the full
        // speed and no body heading is favoured by the grid.
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
        for &vx in &vxs {
            for &vy in &vys {
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
                        let better = match least_bad {
                            None => true,
                            Some((m, _)) => margin > m,
                        };
                        if better {
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
        // Far from every wall and mover no rollout can collide or enter the
        // cost band: skip the per-point checks (same result, much faster in
        // open yards). Reach ≤ ‖K_xy‖_F·|(v_x, v_y, ω)|·T.
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
        let reach = kf * (vt + wm).sqrt() * steps as f64 * self.cfg.sim_dt;
        let band = self.cfg.inflation_radius + self.cfg.safety_distance;
        let free = obs.movers.is_empty()
            && obs.map.clearance(s.x, s.y) > reach + radius + band + 2.0 * self.res;
        let mut samples: Vec<Sample> = Vec::with_capacity(pairs.len() * ws.len());
        let mut all_points: Vec<Vec<[f64; 2]>> = Vec::new();
        for &w in &ws {
            for &(vx, vy) in &pairs {
                {
                    let cmd = Command { v: vx, vy, w };
                    let mut pts = self.record.then(|| Vec::with_capacity(steps));
                    let (ok, r) =
                        self.rollout(obs, cmd, steps, goal, &local, radius, free, pts.as_mut());
                    let raw = [r[0], r[1], r[2], w.abs()];
                    let cost = self.cfg.alpha * raw[0]
                        + self.cfg.beta * raw[1]
                        + self.cfg.gamma * raw[2]
                        + self.cfg.twirl * raw[3];
                    samples.push(Sample {
                        cmd,
                        admissible: ok && cost.is_finite(),
                        raw,
                        cost,
                    });
                    if let Some(p) = pts {
                        all_points.push(p);
                    }
                }
            }
        }
        let best = samples
            .iter()
            .enumerate()
            .filter(|(_, c)| c.admissible)
            .fold(None::<(usize, f64)>, |b, (i, c)| match b {
                Some((_, bc)) if bc <= c.cost => b,
                _ => Some((i, c.cost)),
            })
            .map(|(i, _)| i);
        let mut sums = [0.0; 4];
        for c in samples.iter().filter(|c| c.admissible) {
            for (s, r) in sums.iter_mut().zip(c.raw) {
                *s += r;
            }
        }
        let to_rollout = |c: &Sample, points: Vec<[f64; 2]>| Rollout {
            cmd: c.cmd,
            points,
            admissible: c.admissible,
            raw: c.raw.to_vec(),
            normalised: c
                .raw
                .iter()
                .zip(sums)
                .map(|(r, s)| if s > 0.0 { r / s } else { 0.0 })
                .collect(),
            score: -c.cost,
        };
        self.debug.weights = vec![
            self.cfg.alpha,
            self.cfg.beta,
            self.cfg.gamma,
            self.cfg.twirl,
        ];
        self.debug.mode = match (best, limited) {
            (None, _) => "no-admissible",
            (Some(_), true) => "load-limited",
            (Some(_), false) => "normal",
        }
        .into();
        if self.record {
            self.debug.rollouts = samples
                .iter()
                .zip(all_points)
                .map(|(c, p)| to_rollout(c, p))
                .collect();
            self.debug.chosen = best;
        } else {
            self.debug.rollouts.clear();
            self.debug.chosen = None;
            if let Some(i) = best {
                let c = samples[i];
                let mut pts = Vec::with_capacity(steps);
                self.rollout(
                    obs,
                    c.cmd,
                    steps,
                    goal,
                    &local,
                    radius,
                    free,
                    Some(&mut pts),
                );
                self.debug.rollouts.push(to_rollout(&c, pts));
                self.debug.chosen = Some(0);
            }
        }
        match best {
            Some(i) => samples[i].cmd,
            // Nothing admissible: brake (the motors' limits shape it).
            None => Command::default(),
        }
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
        self.debug.keypoints.clear();
        self.debug.current_goal = goal;
        Ok(())
    }

    fn debug(&self) -> &PlannerDebug {
        &self.debug
    }

    fn set_record_rollouts(&mut self, on: bool) {
        self.record = on;
    }
}
