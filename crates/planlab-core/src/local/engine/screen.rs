//! The DWA papers' safety screen: which rollouts are admissible.
//!
//! - **Collision** within the horizon: clearance of every rollout point —
//!   the static map's [`StaticMap::clearance`] minus the footprint's
//!   circumscribed radius (and `safety_margin`), and the distance to every
//!   perceived mover disc, at its position at the rollout step's time when
//!   `predict_movers` (constant velocity), else at its current position; a
//!   moving disc counts larger by the distance it covers in one control
//!   period (it may turn before the robot sees it again). A rollout whose
//!   clearance reaches the threshold collides (early exit).
//! - **V_a** (Fox, Burgard & Thrun 1997): v ≤ √(2·dist·v̇_b),
//!   |ω| ≤ √(2·dist·ω̇_b), dist the distance the robot drives *along its
//!   arc* before the first contact ([`va_time`]); past the horizon the arc
//!   is followed on as far as braking needs.
//! - **Braking rollouts** are followed past the horizon until the robot
//!   stands, and must not stop in a mover's predicted path
//!   ([`REST_HORIZONS`]); a constant-speed rollout that leaves the robot in
//!   one must be brakeable afterwards (stranding).
//! - **Passive safety**: a robot at rest starts off only on a sample it
//!   could brake out of before any perceived mover, free to turn round at
//!   once, could reach it.
//!
//! With no admissible sample the screen's fallback brakes at the largest
//! deceleration (the robot's own, when the planner is capped below it) and, for a circular footprint, turns in place toward the
//! goal (only when that braking turn hits nothing) — unless braking itself
//! would be hit or would stop the robot in a mover's predicted path: then
//! the engine takes the collision-free sample with the best G.

use super::generator::{Sample, Trajectory, Window, MAX_ROLLOUT_STEPS};
use crate::geom::closest_along;
use crate::local::{Observation, ObservedMover};
use crate::num::{atan2, hypot, sin_cos, wrap_angle};
use crate::world::robot::{integrate, integrate_turned};
use crate::world::{Command, Footprint, RobotLimits, RobotSpec, RobotState, StaticMap};

/// A braking rollout's rest point must stay out of every mover's predicted
/// path for this many rollout horizons.
pub const REST_HORIZONS: f64 = 4.0;

/// The screen's settings (fields of `DwaConfig`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScreenConfig {
    /// Clearance beyond this changes no decision, m.
    pub dist_cap: f64,
    /// Extra clearance kept beyond the footprint, m.
    pub safety_margin: f64,
    /// Movers move at their observed velocity along rollouts.
    pub predict_movers: bool,
    /// Apply V_a.
    pub admissible_window: bool,
    /// With no admissible sample, a round robot turns toward the goal.
    pub rotate_in_place: bool,
    /// The robot's own limits when the planner runs capped below them
    /// (`DwaConfig::max_accel` …): the fallback then brakes at the robot's
    /// full deceleration, since an emergency stop needs no comfort margin.
    /// `None`: the planner's limits are the robot's.
    pub emergency: Option<RobotLimits>,
}

/// How the screen judged one rollout.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Verdict {
    /// It collides within the horizon (or a braking rollout before rest).
    pub collided: bool,
    /// It passes every test.
    pub admissible: bool,
    /// Points worth drawing (up to the contact; V_a's look-ahead excluded).
    pub shown: usize,
}

/// Sets `x` toward 0 by `d`, not past it.
fn toward_zero(x: f64, d: f64) -> f64 {
    if x > 0.0 {
        (x - d).max(0.0)
    } else {
        (x + d).min(0.0)
    }
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
pub fn va_time(v_abs: f64, w_abs: f64, l: &RobotLimits) -> f64 {
    (v_abs / (2.0 * l.acc_v)).max(w_abs / (2.0 * l.acc_w))
}

/// Clearance (m) of the robot's centre to the nearest static obstacle or
/// perceived mover surface, without the footprint.
pub fn centre_clearance(map: &StaticMap, movers: &[ObservedMover], p: [f64; 2]) -> f64 {
    let mut c = map.clearance(p[0], p[1]);
    for m in movers {
        c = c.min(hypot(m.pos[0] - p[0], m.pos[1] - p[1]) - m.radius);
    }
    c.max(0.0)
}

/// The safety screen of one engine (module doc); allocation-free per cycle
/// once warmed up.
#[derive(Debug, Clone)]
pub struct Screen {
    cfg: ScreenConfig,
    limits: RobotLimits,
    /// Footprint's circumscribed radius + safety margin, m.
    r_eff: f64,
    round: bool,
    /// Rollout horizon (steps) and step (s) of the generator.
    steps: usize,
    h: f64,
    /// Kept movers' positions per rollout step: `[k * m + j]`, k = 1..=steps.
    mover_pos: Vec<[f64; 2]>,
    mover_rad: Vec<f64>,
    kept: Vec<usize>,
    /// Rows of the mover table beyond the horizon: one control period, for
    /// braking checks that start after it.
    extra_rows: usize,
    /// Last rollout step V_a may look at.
    va_steps: usize,
    /// Last rollout step a braking rollout may reach.
    brake_steps: usize,
    /// Every perceived mover (position, velocity, radius), for rest checks.
    all_movers: Vec<([f64; 2], [f64; 2], f64)>,
    /// The movers of `all_movers` whose predicted path comes within reach
    /// of a rest point at most `rest_reach` m from the robot (in order): the
    /// others cannot make such a point unsafe.
    rest_movers: Vec<([f64; 2], [f64; 2], f64)>,
    /// Distance from the robot within which `rest_movers` decide, m.
    rest_reach: f64,
    /// Per chunk `q` of [`MoverCull`] in [`Self::check`] (rollout points
    /// 8q ..): the kept movers (bits) that may be near some rollout's chunk;
    /// [`Self::near_movers`] keeps a subset of these ([`Self::chunk_cands`]).
    cands: Vec<u64>,
    /// Collision threshold: 0, or the current clearance when the robot
    /// already sits inside the margin (it may leave, not go deeper).
    limit: f64,
    /// Static clearance at the robot (minus r_eff and slack).
    stat0: f64,
    horizon: f64,
    dt: f64,
    /// Half a map cell: allowance for the clearance field's error, m.
    slack: f64,
    /// The braking checks' headings ([`BrakeTurns`]).
    turns: std::cell::RefCell<BrakeTurns>,
}

impl Screen {
    /// The screen for `robot`, its rollouts `steps` long at `h` s.
    pub fn new(cfg: ScreenConfig, robot: &RobotSpec, (steps, h): (usize, f64)) -> Self {
        Self {
            cfg,
            limits: robot.limits,
            r_eff: robot.footprint.circumscribed_radius() + cfg.safety_margin,
            round: matches!(robot.footprint, Footprint::Circle { .. }),
            steps,
            h,
            mover_pos: Vec::new(),
            mover_rad: Vec::new(),
            kept: Vec::new(),
            extra_rows: 1,
            va_steps: 0,
            brake_steps: 0,
            all_movers: Vec::new(),
            rest_movers: Vec::new(),
            cands: Vec::new(),
            rest_reach: -1.0,
            limit: 0.0,
            stat0: 0.0,
            horizon: 0.0,
            dt: 0.1,
            slack: 0.0,
            turns: Default::default(),
        }
    }

    /// Number of movers the last cycle kept for the rollouts (the rest
    /// cannot come near them).
    pub fn kept_movers(&self) -> usize {
        self.mover_rad.len()
    }

    /// Footprint radius plus safety margin, m.
    pub fn effective_radius(&self) -> f64 {
        self.r_eff
    }

    /// Sets the cycle up: how far rollouts are followed, the movers'
    /// table, the collision threshold. `dt` is the control period.
    pub fn prepare(&mut self, obs: &Observation<'_>, window: &Window, dt: f64) {
        let s = obs.state;
        let l = self.limits;
        let h = self.h;
        self.turns.get_mut().clear();
        // Beyond this distance clearance changes nothing: the critic is
        // capped, and collisions and V_a only ask whether it reaches the
        // threshold.
        let v_abs = window.v.0.abs().max(window.v.1.abs());
        let w_abs = window.w.0.abs().max(window.w.1.abs());
        let horizon = self.cfg.dist_cap + 1e-6;
        // V_a follows an arc for as long as its braking needs.
        self.va_steps = if self.cfg.admissible_window {
            let t = va_time(v_abs, w_abs, &l) / h;
            // `as` saturates, and NaN cannot occur (limits are validated).
            (t.ceil().min(MAX_ROLLOUT_STEPS as f64) as usize + 1).min(MAX_ROLLOUT_STEPS)
        } else {
            0
        };
        self.brake_steps = window.brake_v.map_or(0, |v| {
            // `as` saturates; limits are validated (acc_v > 0).
            ((v / l.acc_v / h).ceil().min(MAX_ROLLOUT_STEPS as f64) as usize + 1)
                .min(MAX_ROLLOUT_STEPS)
        });
        let t_total = (self.steps.max(self.va_steps).max(self.brake_steps)) as f64 * h;
        self.extra_rows = ((dt / h).round() as usize).clamp(1, MAX_ROLLOUT_STEPS);
        self.prepare_movers(obs, s, v_abs * (t_total + dt), horizon, dt);
        // The clearance field may exceed the exact distance by up to about
        // a third of a cell: keep half a cell in hand so rollouts never touch.
        self.slack = 0.5 * obs.map.grid().resolution();
        let stat0 = obs.map.clearance(s.x, s.y) - self.r_eff - self.slack;
        let c0 = self.mover_clearance(stat0, s.x, s.y, 0, horizon);
        self.limit = c0.min(0.0);
        self.stat0 = stat0;
        self.dt = dt;
        self.horizon = horizon;
        // Rest points of this cycle's checks: a rollout's end, a braking
        // rollout's rest, the stranding check's braking after one period;
        // none is farther than this (a looser bound only keeps more movers;
        // a point beyond it is checked against every mover).
        self.rest_reach = v_abs * (t_total + dt) * (1.0 + 1e-6) + 1e-6;
        self.cull_rest_movers(s);
        self.chunk_cands(s, v_abs);
    }

    /// Fills `rest_movers`: the movers whose predicted path
    /// ([`Self::rest_unsafe`]) comes within their reach, plus `rest_reach`
    /// and a margin, of the robot.
    fn cull_rest_movers(&mut self, s: &RobotState) {
        self.rest_movers.clear();
        let t_rest = self.rest_time();
        for &(p, v, r) in &self.all_movers {
            let reach = r + self.r_eff + self.limit + 1e-9;
            let (q, _) = closest_along([s.x, s.y], p, [v[0] * t_rest, v[1] * t_rest]);
            let d = hypot(q[0] - s.x, q[1] - s.y);
            // Keep on NaN: only a mover surely out of reach is left out.
            if (d - self.rest_reach).partial_cmp(&(reach + 1e-6))
                != Some(std::cmp::Ordering::Greater)
            {
                self.rest_movers.push((p, v, r));
            }
        }
    }

    /// How far ahead a mover's path counts for a robot at rest, s.
    fn rest_time(&self) -> f64 {
        if self.cfg.predict_movers {
            REST_HORIZONS * self.steps as f64 * self.h
        } else {
            0.0
        }
    }

    /// [`Self::rest_unsafe`] for a rest point of this cycle's checks: only
    /// the movers that can reach it are asked (the answer is the same).
    fn rest_unsafe_near(&self, s: &RobotState, x: f64, y: f64) -> bool {
        let (dx, dy) = (x - s.x, y - s.y);
        if dx * dx + dy * dy <= self.rest_reach * self.rest_reach {
            self.rest_unsafe_among(&self.rest_movers, x, y)
        } else {
            self.rest_unsafe_among(&self.all_movers, x, y)
        }
    }

    /// How many steps to integrate `sample` for: the horizon, or as far as
    /// its braking or V_a needs.
    pub fn steps_for(&self, sample: &Sample) -> usize {
        if sample.decel > 0.0 {
            self.steps.max(self.brake_steps)
        } else if self.cfg.admissible_window && self.va_steps > self.steps {
            let t = va_time(sample.cmd.v.abs(), sample.cmd.w.abs(), &self.limits) / self.h;
            let need = (t.ceil().min(MAX_ROLLOUT_STEPS as f64) as usize + 1).min(self.va_steps);
            self.steps.max(need)
        } else {
            self.steps
        }
    }

    /// Judges `traj` (rolled out from `obs.state` for
    /// [`Self::steps_for`] steps) and sets its `min_clearance`.
    pub fn check(&self, obs: &Observation<'_>, traj: &mut Trajectory) -> Verdict {
        let map = obs.map;
        let s = obs.state;
        let h = traj.dt;
        let (v, w, decel) = (traj.sample.cmd.v, traj.sample.cmd.w, traj.sample.decel);
        let horizon = self.horizon;
        let limit = self.limit;
        let mut probe = Probe::new(map, self, horizon);
        let mut min_c = f64::INFINITY;
        let mut collided = false;
        let mut shown = traj.horizon;
        // Each step's length bound (constant for a constant speed).
        let (speeds, v0) = (&traj.speeds, traj.sample.cmd.v);
        let step_len = |i: usize| speeds.get(i).copied().unwrap_or(v0).abs() * h * (1.0 + 1e-9);
        let const_len = speeds.is_empty().then(|| step_len(0));
        let len_of = |i: usize| const_len.unwrap_or_else(|| step_len(i));
        let start = [s.x, s.y];
        let mut cull = MoverCull::new(self);
        // A chunk at a time ([`MoverCull`]; the rest at once without it):
        // where its mask asks no mover, the clearance is the static part
        // alone (what `mover_clearance_in` returns then), in a loop with
        // nothing else in it — most points of a cycle lie there.
        let points = &traj.points[..traj.horizon];
        let mut i = 0;
        'walk: while i < points.len() {
            self.cull_at(&mut cull, &traj.points, start, i, len_of);
            let end = if cull.on {
                cull.end.min(points.len())
            } else {
                points.len()
            };
            let mask = cull.mask();
            if self.no_movers(mask) {
                // A loop of its own for a constant step length (the
                // constant-speed rollouts, most of them).
                let part = &points[i..end];
                let hit = match const_len {
                    Some(len) => walk_static(&mut probe, part, |_| len, limit, &mut min_c),
                    None => walk_static(&mut probe, part, |j| step_len(i + j), limit, &mut min_c),
                };
                if let Some(j) = hit {
                    collided = true;
                    shown = i + j + 1;
                    break 'walk;
                }
            } else {
                for (j, &p) in points[i..end].iter().enumerate() {
                    let k = i + j;
                    let stat = probe.at(p, len_of(k));
                    let c = self.mover_clearance_in(stat, p[0], p[1], k + 1, horizon, mask);
                    if c < min_c {
                        min_c = c;
                    }
                    if c <= limit {
                        collided = true;
                        shown = k + 1;
                        break 'walk;
                    }
                }
            }
            i = end;
        }
        traj.min_clearance = min_c;
        let mut rest = traj.end();
        if decel > 0.0 && !collided {
            // A braking rollout is only safe if the robot stops before any
            // contact: follow it on past the horizon until it stands.
            let mut k = traj.horizon + 1;
            loop {
                let moving = traj.speeds.get(k - 1).map_or(traj.final_speed, |&s| s) > 0.0;
                if !moving {
                    break;
                }
                let Some(&p) = traj.points.get(k - 1).filter(|_| k <= self.brake_steps) else {
                    collided = true;
                    break;
                };
                rest = p;
                shown = k;
                // Only `≤ limit` is asked here: the skipping probe and the
                // culled movers give the same answer.
                self.cull_at(&mut cull, &traj.points, start, k - 1, len_of);
                let stat = probe.at(p, len_of(k - 1));
                if self.mover_clearance_in(stat, p[0], p[1], k, horizon, cull.mask()) <= limit {
                    collided = true;
                    break;
                }
                k += 1;
            }
        }
        if decel > 0.0 && !collided && self.rest_unsafe_near(s, rest[0], rest[1]) {
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
            && self.rest_unsafe_near(s, rest[0], rest[1])
        {
            let next = integrate(s, Command { v, vy: 0.0, w }, self.dt);
            stranded =
                self.braking_collides_from(map, &next, self.extra_rows, None, false, Some(s));
        }
        // V_a: the arc must be free of contact for the braking time. A
        // rollout that collides is out anyway, so within the horizon the
        // collision test has decided; past it the arc is followed on, with
        // the same contact test. A braking rollout stops by construction.
        let mut va_ok = true;
        if !collided && !stranded && decel == 0.0 && self.cfg.admissible_window {
            let t_need = va_time(v.abs(), w.abs(), &self.limits);
            // A contact at step k leaves (k − 1)·h of free arc.
            let mut k = traj.horizon + 1;
            while (k - 1) as f64 * h < t_need - 1e-12 {
                let Some(&p) = traj.points.get(k - 1).filter(|_| k <= self.va_steps) else {
                    // Not followed this far: only what was checked is free.
                    va_ok = false;
                    break;
                };
                self.cull_at(&mut cull, &traj.points, start, k - 1, len_of);
                let stat = probe.at(p, len_of(k - 1));
                if self.mover_clearance_in(stat, p[0], p[1], k, horizon, cull.mask()) <= limit {
                    va_ok = false;
                    break;
                }
                k += 1;
            }
        }
        let admissible = !collided && !stranded && va_ok && !self.passive_unsafe(s, v, w);
        Verdict {
            collided,
            admissible,
            shown,
        }
    }

    /// Whether braking at the largest deceleration (turn rate to 0 as well)
    /// from `s` hits something within the horizon, movers predicted as in
    /// the last cycle: then the fallback evades instead of braking.
    pub fn braking_collides(&self, map: &StaticMap, s: &RobotState) -> bool {
        self.braking_collides_from(map, s, 0, None, false, None)
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
        self.rest_unsafe_among(&self.all_movers, x, y)
    }

    /// [`Self::rest_unsafe`] against `movers` only.
    fn rest_unsafe_among(&self, movers: &[([f64; 2], [f64; 2], f64)], x: f64, y: f64) -> bool {
        let t_rest = self.rest_time();
        movers.iter().any(|&(p, v, r)| {
            // Distance from (x, y) to the segment p + v·t, t ∈ [0, t_rest].
            let (dx, dy) = (v[0] * t_rest, v[1] * t_rest);
            let len2 = dx * dx + dy * dy;
            // Cheap rejections first (no division or root; the margin dwarfs
            // rounding, so the answer is the exact test's): the segment lies
            // within L/2 of its midpoint and on its line.
            let reach = r + self.r_eff + self.limit + 1e-9;
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
            hypot(q[0] - x, q[1] - y) - r - self.r_eff <= self.limit
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
        let l = &self.limits;
        let h = self.h;
        let t_end = self.dt + v.abs() / l.acc_v;
        let travel = v.abs() * self.dt + 0.5 * v * v / l.acc_v;
        let reach0 = self.r_eff + self.limit.abs() + travel;
        let near = self.all_movers.iter().any(|&(p, mv, r)| {
            hypot(p[0] - s.x, p[1] - s.y) - r - hypot(mv[0], mv[1]) * t_end <= reach0
        });
        if !near {
            return false;
        }
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
                    <= self.limit
            });
            if caught {
                return true;
            }
        }
        false
    }

    /// As [`Self::braking_collides`], starting `row0` rollout steps into the
    /// movers' predicted future; with `turn_to`, the turn rate follows the
    /// fallback's turn toward that goal instead of braking to 0; with
    /// `to_rest`, followed until the robot stands even past the horizon.
    /// `near`: the cycle's robot state, when `s` is a state of this cycle's
    /// checks (the stranding check): the rest test then asks only the
    /// movers that can reach it, and the static look-ups start from the
    /// robot's.
    fn braking_collides_from(
        &self,
        map: &StaticMap,
        s: &RobotState,
        row0: usize,
        turn_to: Option<[f64; 2]>,
        to_rest: bool,
        near: Option<&RobotState>,
    ) -> bool {
        let l = &self.limits;
        let h = self.h;
        let rows = self.mover_rows();
        // From speed, or with a short horizon, the robot is still moving at
        // the horizon's end. (Only the fallback asks past it: for the
        // evade and stranding decisions, movers predicted at constant
        // velocity that far out misled more than they helped — S-fig12's
        // dual-velocity robot then stood beside a mover's turnaround.)
        let stop = (s.v.abs() / l.acc_v).max(s.w.abs() / l.acc_w) / h;
        let n = if to_rest {
            self.steps
                .max(stop.ceil().min(MAX_ROLLOUT_STEPS as f64) as usize + 1)
        } else {
            self.steps
        };
        let row_of = |k: usize| (k + row0).min(rows.saturating_sub(1));
        // Only `≤ limit` is asked of the clearance below, so skipping
        // look-ups far from walls ([`Probe`]) and movers out of reach
        // ([`MoverCull`]) gives the same answers.
        let mut probe = Probe::new(map, self, self.horizon);
        match near {
            Some(s0) => probe.since = hypot(s.x - s0.x, s.y - s0.y) * (1.0 + 1e-9) + 1e-9,
            None => {
                probe.last = f64::NEG_INFINITY;
                probe.free = f64::NEG_INFINITY;
            }
        }
        let mut cull = MoverCull::new(self);
        // Braking without a goal to turn to: the headings depend on the
        // start's heading and turn rate alone, shared by every speed.
        let mut turns = self.turns.borrow_mut();
        let turns = &mut *turns;
        let turn_row = turn_to.is_none().then(|| turns.row(s.theta, s.w));
        let dw = l.acc_w * h;
        // The answer is a contact on the way or an unsafe rest point; the
        // rest point needs the path alone (no look-up, no mover), so it is
        // asked first, and the path is kept for the contacts.
        let path = &mut turns.path;
        path.clear();
        let (mut st, mut v, mut w) = (*s, s.v, s.w);
        for k in 1..=n {
            v = toward_zero(v, l.acc_v * h);
            w = match turn_to {
                Some(g) => self.turn_toward(&st, g, h),
                None => toward_zero(w, dw),
            };
            st = if v == 0.0 && w == 0.0 && st.x != 0.0 && st.y != 0.0 {
                // At rest: `integrate` moves it by ±0, which leaves a nonzero
                // coordinate as it is, and turns it by 0 — without its sine
                // and cosine.
                RobotState {
                    theta: wrap_angle(st.theta + w * h),
                    v,
                    vy: 0.0,
                    w,
                    ..st
                }
            } else {
                let sc = match turn_row {
                    Some(r) => turns.rows[r].sin_cos(k, dw, h),
                    None => sin_cos(st.theta),
                };
                integrate_turned(&st, Command { v, vy: 0.0, w }, h, sc)
            };
            path.push([st.x, st.y, v]);
            // Turning on the spot moves no part of a round footprint.
            let still = v == 0.0 && (w == 0.0 || turn_to.is_some());
            if still && self.mover_rad.is_empty() {
                break;
            }
        }
        let rest_unsafe = match near {
            Some(s0) => self.rest_unsafe_near(s0, st.x, st.y),
            None => self.rest_unsafe(st.x, st.y),
        };
        if rest_unsafe {
            return true;
        }
        // `None`: above the threshold, and no mover was near.
        let mut stat = None;
        let (mut at, mut v_at) = ([s.x, s.y], s.v);
        for (i, &[x, y, v]) in path.iter().enumerate() {
            let k = i + 1;
            if cull.due(k - 1) {
                // |v| never grows while braking: the next steps stay
                // within this of the current position.
                let steps = CULL_CHUNK.min(n + 1 - k);
                let rho = (v_at.abs() * h * (1.0 + 1e-9) + 1e-9) * steps as f64;
                let (ka, kb) = (row_of(k), row_of(k + steps - 1));
                cull.mask = self.near_movers(at, rho, ka, kb, u64::MAX);
                cull.end = k - 1 + steps;
            }
            // Standing where the last step ended: the same static part (the
            // probe's value stands for it either way, and only `≤ limit` is
            // asked), without a look-up; no distance driven, so the probe
            // need not advance.
            let moved = k == 1 || x.to_bits() != at[0].to_bits() || y.to_bits() != at[1].to_bits();
            let mask = cull.mask();
            if moved || stat.is_none() {
                let len = if moved {
                    v.abs() * h * (1.0 + 1e-9) + 1e-9
                } else {
                    0.0
                };
                stat = probe.above([x, y], len, self.limit, self.no_movers(mask));
            }
            let row = row_of(k);
            if stat.is_some_and(|c| {
                self.mover_clearance_in(c, x, y, row, self.horizon, mask) <= self.limit
            }) {
                return true;
            }
            (at, v_at) = ([x, y], v);
        }
        // The rest point was asked first.
        false
    }

    /// The fallback's turn rate toward `goal`: the rate that closes the
    /// bearing error in one period `dt`, within the limits and the angular
    /// window.
    fn turn_toward(&self, s: &RobotState, goal: [f64; 2], dt: f64) -> f64 {
        let l = &self.limits;
        let dw = l.acc_w * dt;
        let err = wrap_angle(atan2(goal[1] - s.y, goal[0] - s.x) - s.theta);
        let want = (err / dt).clamp(-l.w_max, l.w_max);
        want.clamp(s.w - dw, s.w + dw)
    }

    /// Braking fallback: v toward 0 at the largest deceleration; a round
    /// robot also turns toward the goal (within its angular window) when
    /// that braking turn hits nothing, else its turn rate goes to 0 too.
    pub fn fallback(&self, map: &StaticMap, s: &RobotState, goal: [f64; 2], dt: f64) -> Command {
        let l = self.cfg.emergency.as_ref().unwrap_or(&self.limits);
        let v = toward_zero(s.v, l.acc_v * dt);
        // Turning while still moving sweeps a wider path than braking
        // straight: it may reach a wall that straight braking stops short
        // of (T-fig3-11 with a 1 s horizon drove into the side wall so).
        let turn = self.cfg.rotate_in_place
            && self.round
            && (s.v == 0.0
                || !self.braking_collides_from(map, s, 0, Some(goal), true, None)
                || self.braking_collides_from(map, s, 0, None, true, None));
        let w = if turn {
            self.turn_toward(s, goal, dt)
        } else {
            toward_zero(s.w, l.acc_w * dt)
        };
        Command { v, vy: 0.0, w }
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
        let t_total = (self.table_rows() - 1) as f64 * self.h;
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
            let t = if predict { k as f64 * self.h } else { 0.0 };
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
    // opt-level "s" it would otherwise stay a call.
    #[inline(always)]
    fn mover_clearance(&self, stat: f64, x: f64, y: f64, k: usize, horizon: f64) -> f64 {
        let mut best = stat;
        let n = self.mover_rad.len();
        if n > 0 {
            let row = &self.mover_pos[k * n..(k + 1) * n];
            for (&p, &r) in row.iter().zip(&self.mover_rad) {
                best = self.closer(best, p, r, x, y, horizon);
            }
        }
        best
    }

    /// `best`, or the clearance to the mover at `p` of radius `r` if that
    /// is smaller: one step of [`Self::mover_clearance`].
    #[inline(always)]
    fn closer(&self, best: f64, p: [f64; 2], r: f64, x: f64, y: f64, horizon: f64) -> f64 {
        let (dx, dy) = (p[0] - x, p[1] - y);
        let d2 = dx * dx + dy * dy;
        // `best.min(horizon)` as one comparison (the horizon is never NaN:
        // dist_cap is validated); `f64::min`'s NaN handling took five more
        // instructions in the screen's innermost loop.
        let lim = (if best < horizon { best } else { horizon }) + r + self.r_eff;
        // Only a closer mover needs the square root.
        if lim <= 0.0 || d2 < lim * lim {
            best.min(d2.sqrt() - r - self.r_eff)
        } else {
            best
        }
    }

    /// [`Self::mover_clearance`] over the movers of `mask` only (bit j:
    /// kept mover j; `None`: all), in the same order: the same value when
    /// the movers left out are those [`Self::near_movers`] rules out.
    #[inline(always)]
    fn mover_clearance_in(
        &self,
        stat: f64,
        x: f64,
        y: f64,
        k: usize,
        horizon: f64,
        mask: Option<u64>,
    ) -> f64 {
        let Some(mut mask) = mask else {
            return self.mover_clearance(stat, x, y, k, horizon);
        };
        let mut best = stat;
        let n = self.mover_rad.len();
        let row = &self.mover_pos[k * n..(k + 1) * n];
        while mask != 0 {
            let j = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            best = self.closer(best, row[j], self.mover_rad[j], x, y, horizon);
        }
        best
    }

    /// Whether [`Self::mover_clearance_in`] with `mask` asks no mover (its
    /// value is then the static part).
    #[inline(always)]
    fn no_movers(&self, mask: Option<u64>) -> bool {
        mask == Some(0) || self.mover_rad.is_empty()
    }

    /// The kept movers (bit j: mover j; 1 ≤ movers ≤ 64) that may come
    /// within `horizon` of a footprint centred within `rho` of `c` at
    /// rollout steps `ka..=kb` (rows of the table).
    ///
    /// A mover left out is farther than `horizon + r + r_eff` (plus a
    /// margin far above rounding) from every such centre, where
    /// [`Self::mover_clearance`]'s `lim` never exceeds that: it would not
    /// take its square root, or (deep in a collision, `lim ≤ 0`) would take
    /// one larger than the clearance it has, so leaving it out changes no
    /// bit. Its positions over the rows lie on the segment between rows
    /// `ka` and `kb` (constant velocity), so within their bounding box.
    ///
    /// Only the movers of `cands` are asked: the others are known to be out
    /// of reach ([`Self::chunk_cands`]), so the mask is the same.
    fn near_movers(&self, c: [f64; 2], rho: f64, ka: usize, kb: usize, cands: u64) -> u64 {
        let n = self.mover_rad.len();
        let all = u64::MAX >> (64 - n);
        if kb * n + n > self.mover_pos.len() {
            // Past the table (the full loop would index out of it too).
            return all;
        }
        let (a, b) = (
            &self.mover_pos[ka * n..ka * n + n],
            &self.mover_pos[kb * n..kb * n + n],
        );
        let margin = 1e-6 + 1e-9 * (c[0].abs() + c[1].abs());
        let base = rho + self.horizon + self.r_eff + margin;
        let mut mask = 0u64;
        let mut bits = cands & all;
        while bits != 0 {
            let j = bits.trailing_zeros() as usize;
            bits &= bits - 1;
            let (pa, pb, r) = (&a[j], &b[j], self.mover_rad[j]);
            // The gap between `c` and the box, with `f64::max`/`min` written
            // as comparisons (one instruction each, not six): the table holds
            // no NaN, a NaN centre still gives a gap of 0 (kept), and where a
            // ±0 tie could pick either zero, the square below is +0 anyway.
            let lo = |a: f64, b: f64| if a < b { a } else { b };
            let hi = |a: f64, b: f64| if a > b { a } else { b };
            let gx = hi(hi(lo(pa[0], pb[0]) - c[0], c[0] - hi(pa[0], pb[0])), 0.0);
            let gy = hi(hi(lo(pa[1], pb[1]) - c[1], c[1] - hi(pa[1], pb[1])), 0.0);
            let reach = base + r;
            // Kept on NaN: only a mover surely out of reach is left out.
            if (gx * gx + gy * gy).partial_cmp(&(reach * reach))
                != Some(std::cmp::Ordering::Greater)
            {
                mask |= 1 << j;
            }
        }
        mask
    }

    /// Fills `cands` for rollouts from `s` at speeds up to `v_abs`. Chunk q
    /// starts at rollout point i = 8q: its centre (the point before) lies
    /// within R = i·L of `s`, L bounding a step's length as
    /// [`Self::check`] does, and its reach is at most 8·(L + 1e-9). A mover
    /// farther from `s`, over the chunk's rows (a box holding every
    /// shorter chunk's), than R + reach + horizon + r_eff + its radius, plus
    /// [`Self::near_movers`]' margin at the farthest such centre and 1e-6
    /// for rounding, is farther than `near_movers`' reach from every
    /// centre, so it never enters a rollout's mask.
    fn chunk_cands(&mut self, s: &RobotState, v_abs: f64) {
        self.cands.clear();
        let n = self.mover_rad.len();
        if !(1..=64).contains(&n) {
            return;
        }
        let rows = self.mover_rows();
        let longest = self.steps.max(self.va_steps).max(self.brake_steps);
        let len = v_abs * self.h * (1.0 + 1e-9);
        let c = [s.x, s.y];
        let mut i = 0;
        while i < longest && i + 1 < rows {
            let kb = (i + CULL_CHUNK).min(rows - 1);
            let far = i as f64 * len * (1.0 + 1e-9);
            let rho = CULL_CHUNK as f64 * (len + 1e-9) * (1.0 + 1e-9);
            let margin = 1e-6 + 1e-9 * (c[0].abs() + c[1].abs() + 2.0 * far);
            let reach = far + rho + margin + 1e-6;
            // near_movers' own test from `s`, `reach` for its ρ.
            self.cands
                .push(self.near_movers(c, reach, i + 1, kb, u64::MAX));
            i += CULL_CHUNK;
        }
    }

    /// Starts a new chunk of [`MoverCull`] at rollout point `i` of
    /// `points` (rolled out from `start`, step `j` at most `step_len(j)`
    /// long) when the last one has run out.
    #[inline(always)]
    fn cull_at(
        &self,
        cull: &mut MoverCull,
        points: &[[f64; 2]],
        start: [f64; 2],
        i: usize,
        step_len: impl Fn(usize) -> f64,
    ) {
        if cull.due(i) {
            let c = if i == 0 { start } else { points[i - 1] };
            let end = (i + CULL_CHUNK).min(points.len());
            let mut rho = 0.0;
            for j in i..end {
                rho += step_len(j) + 1e-9;
            }
            // Chunks start every CULL_CHUNK points from the robot's state.
            let cands = match i % CULL_CHUNK {
                0 => self.cands.get(i / CULL_CHUNK).copied().unwrap_or(u64::MAX),
                _ => u64::MAX,
            };
            cull.mask = self.near_movers(c, rho, i + 1, end, cands);
            cull.end = end;
        }
    }
}

/// [`Screen::check`]'s walk over `points` where no mover is near: the
/// clearance is the static part alone. Lowers `min_c` to each point's
/// clearance (point `j` reached after a step of at most `len(j)` m) and
/// returns the first point at or below `limit`.
#[inline(always)]
fn walk_static(
    probe: &mut Probe<'_>,
    points: &[[f64; 2]],
    len: impl Fn(usize) -> f64,
    limit: f64,
    min_c: &mut f64,
) -> Option<usize> {
    for (j, &p) in points.iter().enumerate() {
        let c = probe.at(p, len(j));
        // `f64::min` less its NaN care: `min_c` starts at +∞ and only ever
        // takes a smaller (so not NaN) value, and on a tie it keeps `min_c`
        // as `min` does.
        if c < *min_c {
            *min_c = c;
        }
        if c <= limit {
            return Some(j);
        }
    }
    None
}

/// Most rows [`BrakeTurns`] keeps (a cycle asks one per turn rate).
const MAX_BRAKE_TURNS: usize = 1024;

/// (sin θ, cos θ) of braking checks' headings, per start heading and turn
/// rate: braking turns ω toward 0 by `acc_w·h` a step whatever the speed,
/// so the headings of every sample of one turn rate are the same, and one
/// sine and cosine a step serves them all (each the value `integrate`
/// computes). Cleared every cycle.
#[derive(Debug, Clone, Default)]
struct BrakeTurns {
    /// Rows in use: `rows[..used]` (the others keep their allocations).
    rows: Vec<BrakeTurn>,
    used: usize,
    /// Row of the last look-up (the next is usually it or the one after).
    last: usize,
    /// A braking check's path: (x, y, v) after each step.
    path: Vec<[f64; 3]>,
}

/// One start's headings.
#[derive(Debug, Clone, Default)]
struct BrakeTurn {
    /// Bits of the start heading and turn rate.
    key: (u64, u64),
    /// Heading and turn rate after `sc.len()` steps.
    theta: f64,
    w: f64,
    /// `sc[k]`: (sin, cos) of the heading after k steps.
    sc: Vec<(f64, f64)>,
}

impl BrakeTurns {
    fn clear(&mut self) {
        self.used = 0;
        self.last = 0;
    }

    /// The row of a braking check from heading `theta` at turn rate `w`.
    fn row(&mut self, theta: f64, w: f64) -> usize {
        let key = (theta.to_bits(), w.to_bits());
        let near = [self.last, self.last + 1];
        let found = near
            .into_iter()
            .filter(|&i| i < self.used)
            .chain(0..self.used)
            .find(|&i| self.rows[i].key == key);
        if let Some(i) = found {
            self.last = i;
            return i;
        }
        if self.used == MAX_BRAKE_TURNS {
            self.clear();
        }
        if self.used == self.rows.len() {
            self.rows.push(BrakeTurn::default());
        }
        let r = &mut self.rows[self.used];
        r.key = key;
        (r.theta, r.w) = (theta, w);
        r.sc.clear();
        self.used += 1;
        self.last = self.used - 1;
        self.last
    }
}

impl BrakeTurn {
    /// (sin, cos) of the heading before braking step `k` (1-based), the
    /// turn rate going toward 0 by `dw` a step of `h` s.
    #[inline(always)]
    fn sin_cos(&mut self, k: usize, dw: f64, h: f64) -> (f64, f64) {
        while self.sc.len() < k {
            self.sc.push(sin_cos(self.theta));
            self.w = toward_zero(self.w, dw);
            self.theta = wrap_angle(self.theta + self.w * h);
        }
        self.sc[k - 1]
    }
}

/// Rollout steps per chunk of [`MoverCull`]: long enough that the bound is
/// computed rarely, short enough that it stays tight.
const CULL_CHUNK: usize = 8;

/// The kept movers that can matter for the next few steps of a rollout
/// ([`Screen::near_movers`]), so the per-step clearance asks only those.
/// Off with no movers or more than 64 (one bit each).
struct MoverCull {
    on: bool,
    mask: u64,
    /// First step index the mask no longer covers.
    end: usize,
}

impl MoverCull {
    fn new(screen: &Screen) -> Self {
        Self {
            on: (1..=64).contains(&screen.mover_rad.len()),
            mask: 0,
            end: 0,
        }
    }

    /// Whether step index `i` needs a new mask.
    #[inline(always)]
    fn due(&self, i: usize) -> bool {
        self.on && i >= self.end
    }

    /// The mask for [`Screen::mover_clearance_in`].
    #[inline(always)]
    fn mask(&self) -> Option<u64> {
        self.on.then_some(self.mask)
    }
}

/// The static clearance along a rollout, skipping map lookups far from
/// walls: the clearance field is √2-Lipschitz (bilinear over samples
/// 1-Lipschitz per axis) up to a cell at blocked-cell borders, so while the
/// last looked-up value minus √2·(distance driven since) stays above
/// horizon + a cell, the point's value is above the horizon and every
/// decision (capped critic, V_a, collision) is the same as with the exact
/// value.
///
/// Where only comparisons with a floor are asked of the point's value and
/// no mover is near ([`Probe::above`]), the same bound spares look-ups
/// above that floor; the jump at blocked cells is left out of it within
/// `free` of the last look-up, where no point lies in a blocked cell or
/// off the map (the field exceeds the distance to them by under a cell:
/// ≤ 0.21 cell in the blend at the nearest blocked centre, ≤ 0.71 between
/// that centre and its cell's boundary).
struct Probe<'a> {
    map: &'a StaticMap,
    r_eff: f64,
    slack: f64,
    skip_above: f64,
    /// A cell, m: the field's jump at blocked-cell borders.
    cell: f64,
    last: f64,
    /// The map clearance at the last look-up less a cell and a margin.
    free: f64,
    since: f64,
}

impl<'a> Probe<'a> {
    fn new(map: &'a StaticMap, screen: &Screen, horizon: f64) -> Self {
        Self {
            map,
            r_eff: screen.r_eff,
            slack: screen.slack,
            skip_above: horizon + map.grid().resolution(),
            cell: map.grid().resolution(),
            last: screen.stat0,
            free: screen.stat0 + screen.r_eff + screen.slack - map.grid().resolution() - 1e-9,
            since: 0.0,
        }
    }

    /// The static clearance (minus the footprint) at `p`, reached after a
    /// step of at most `step_len` m. (`free` is not kept: a probe uses this
    /// or [`Self::above`], not both.)
    #[inline(always)]
    fn at(&mut self, p: [f64; 2], step_len: f64) -> f64 {
        self.since += step_len;
        if self.last - std::f64::consts::SQRT_2 * self.since > self.skip_above {
            self.skip_above
        } else {
            self.last = self.map.clearance(p[0], p[1]) - self.r_eff - self.slack;
            self.since = 0.0;
            self.last
        }
    }

    /// As [`Self::at`] — or, with `alone` (no mover to compare the value
    /// with), `None` when it is surely above `floor`.
    #[inline(always)]
    fn above(&mut self, p: [f64; 2], step_len: f64, floor: f64, alone: bool) -> Option<f64> {
        self.since += step_len;
        let b = self.last - std::f64::consts::SQRT_2 * self.since;
        if b > self.skip_above {
            return Some(self.skip_above);
        }
        if alone {
            let jump = if self.since < self.free {
                0.0
            } else {
                self.cell
            };
            if b - jump - 1e-9 >= floor {
                return None;
            }
        }
        let c = self.map.clearance(p[0], p[1]);
        self.last = c - self.r_eff - self.slack;
        self.free = c - self.cell - 1e-9;
        self.since = 0.0;
        Some(self.last)
    }
}

#[cfg(test)]
mod tests {
    use super::super::generator::{DynamicWindow, TrajectoryGenerator, WindowRequest};
    use super::*;
    use crate::local::testkit;
    use crate::num::Rng;

    fn walled() -> StaticMap {
        let mut ascii = "#".repeat(60) + "\n";
        for r in 0..38 {
            let inner: String = (0..58)
                .map(|c| {
                    let block = (r == 12 || r == 25) && (10..30).contains(&c);
                    if block || (c == 40 && (5..20).contains(&r)) {
                        '#'
                    } else {
                        '.'
                    }
                })
                .collect();
            ascii += &format!("#{inner}#\n");
        }
        ascii += &"#".repeat(60);
        testkit::map(&ascii, 0.1)
    }

    /// Every rollout of a cycle judged with the per-chunk candidates and
    /// with every kept mover asked: the same verdict and the same
    /// clearance, bit for bit.
    #[test]
    fn chunk_candidates_change_no_verdict_and_no_bit() {
        let map = walled();
        let robot = RobotSpec::default();
        let cfg = ScreenConfig {
            dist_cap: 1.0,
            safety_margin: 0.05,
            predict_movers: true,
            admissible_window: true,
            rotate_in_place: true,
            emergency: None,
        };
        let mut rng = Rng::new(29);
        let mut kept_out = 0u32;
        for scene in 0..60 {
            let (movers, s) = random_scene(&mut rng, 2 + scene % 30, (1.0, 5.0));
            let mut obs = testkit::observation(&s, [5.5, 2.0], &map);
            obs.movers = &movers;
            let (gen, samples, screen) = windowed(&robot, cfg, &obs, scene % 2 == 0);
            let mut all = screen.clone();
            all.cands.clear();
            let n = screen.kept_movers();
            kept_out += screen
                .cands
                .iter()
                .map(|c| (u64::MAX >> (64 - n.clamp(1, 64))).count_ones() - c.count_ones())
                .sum::<u32>();
            let mut traj = Trajectory::default();
            for sample in samples {
                gen.rollout(&obs, sample, screen.steps_for(&sample), &mut traj);
                let mut again = traj.clone();
                let (a, b) = (screen.check(&obs, &mut traj), all.check(&obs, &mut again));
                assert_eq!(a, b, "scene {scene} {sample:?}");
                assert_eq!(traj.min_clearance.to_bits(), again.min_clearance.to_bits());
            }
        }
        assert!(kept_out > 100, "{kept_out}");
    }

    /// `n` movers at random in the 6 × 4 m walled room and a robot state
    /// with x in `xs` (drawn in that order from `rng`).
    fn random_scene(rng: &mut Rng, n: u32, xs: (f64, f64)) -> (Vec<ObservedMover>, RobotState) {
        let movers = (0..n)
            .map(|id| ObservedMover {
                id,
                pos: [rng.range(0.3, 5.7), rng.range(0.3, 3.7)],
                vel: [rng.range(-0.8, 0.8), rng.range(-0.8, 0.8)],
                radius: rng.range(0.05, 0.4),
            })
            .collect();
        let s = RobotState {
            x: rng.range(xs.0, xs.1),
            y: rng.range(0.5, 3.5),
            theta: rng.range(-3.1, 3.1),
            v: rng.range(0.0, 1.0),
            w: rng.range(-0.5, 0.5),
            ..Default::default()
        };
        (movers, s)
    }

    /// A dynamic window's samples for `obs` (braking ones if `braking`) and
    /// a screen prepared for them.
    fn windowed(
        robot: &RobotSpec,
        cfg: ScreenConfig,
        obs: &Observation,
        braking: bool,
    ) -> (DynamicWindow, Vec<Sample>, Screen) {
        let mut gen = DynamicWindow::new(robot.limits, (0.05, 0.05), (7, 11), (3.0, 0.1), false);
        let req = WindowRequest {
            dt: 0.1,
            hold_v: None,
            braking,
        };
        let mut samples = Vec::new();
        let window = gen.samples(obs, &req, &mut samples);
        let mut screen = Screen::new(cfg, robot, gen.horizon());
        screen.prepare(obs, &window, 0.1);
        (gen, samples, screen)
    }

    /// The rollout walk of [`Screen::check`] (chunks without movers walked
    /// on the static part alone, map look-ups skipped by [`Probe`], movers
    /// culled) against a look-up and every kept mover at every point: the
    /// same collision, at the same point, and the same smallest clearance
    /// below the horizon, bit for bit.
    #[test]
    fn the_rollout_walk_matches_every_point_looked_up() {
        let map = walled();
        let robot = RobotSpec::default();
        let cfg = ScreenConfig {
            dist_cap: 1.0,
            safety_margin: 0.05,
            predict_movers: true,
            admissible_window: true,
            rotate_in_place: true,
            emergency: None,
        };
        let mut rng = Rng::new(41);
        let (mut hits, mut below) = (0u32, 0u32);
        for scene in 0..60 {
            let (movers, s) = random_scene(&mut rng, scene % 12, (0.5, 5.5));
            let mut obs = testkit::observation(&s, [5.5, 2.0], &map);
            obs.movers = &movers;
            let (gen, samples, screen) = windowed(&robot, cfg, &obs, scene % 2 == 0);
            let mut traj = Trajectory::default();
            for sample in samples {
                gen.rollout(&obs, sample, screen.steps_for(&sample), &mut traj);
                let v = screen.check(&obs, &mut traj);
                let (mut min_c, mut hit) = (f64::INFINITY, None);
                for (i, p) in traj.points[..traj.horizon].iter().enumerate() {
                    let stat = map.clearance(p[0], p[1]) - screen.r_eff - screen.slack;
                    let c = screen.mover_clearance(stat, p[0], p[1], i + 1, screen.horizon);
                    min_c = min_c.min(c);
                    if c <= screen.limit {
                        hit = Some(i + 1);
                        break;
                    }
                }
                let within = |c: f64| c.min(screen.horizon).to_bits();
                assert_eq!(within(traj.min_clearance), within(min_c), "scene {scene}");
                if let Some(shown) = hit {
                    assert!(v.collided && v.shown == shown, "scene {scene}: {v:?}");
                    hits += 1;
                } else if sample.decel == 0.0 {
                    assert!(!v.collided, "scene {scene}: {v:?}");
                }
                below += u32::from(min_c < screen.horizon);
            }
        }
        assert!(hits > 100 && below > 1000, "{hits} {below}");
    }

    /// Braking checks share one row of headings per start heading and turn
    /// rate ([`BrakeTurns`]): each speed's braking gets the very states
    /// its own sines and cosines give.
    #[test]
    fn braking_headings_shared_across_speeds_are_each_speed_s_own() {
        let l = RobotSpec::default().limits;
        let h = 0.1;
        let dw = l.acc_w * h;
        let mut rng = Rng::new(5);
        let mut turns = BrakeTurns::default();
        for _ in 0..200 {
            let (theta, w) = (rng.range(-4.0, 4.0), rng.range(-1.5, 1.5));
            for _ in 0..5 {
                let start = RobotState {
                    x: rng.range(-2.0, 2.0),
                    y: rng.range(-2.0, 2.0),
                    theta,
                    v: rng.range(0.0, 1.0),
                    w,
                    ..Default::default()
                };
                let r = turns.row(theta, w);
                let (mut own, mut shared) = (start, start);
                let (mut v, mut wk) = (start.v, start.w);
                for k in 1..40 {
                    v = toward_zero(v, l.acc_v * h);
                    wk = toward_zero(wk, dw);
                    let cmd = Command { v, vy: 0.0, w: wk };
                    own = integrate(&own, cmd, h);
                    let sc = turns.rows[r].sin_cos(k, dw, h);
                    shared = integrate_turned(&shared, cmd, h, sc);
                    for (a, b) in [
                        (own.x, shared.x),
                        (own.y, shared.y),
                        (own.theta, shared.theta),
                    ] {
                        assert_eq!(a.to_bits(), b.to_bits(), "step {k}");
                    }
                }
            }
        }
        assert!(turns.used <= 200);
    }

    /// [`Probe`]'s bound: the static clearance at a point is above its
    /// value at an earlier one less √2 times the distance between them,
    /// and less a cell unless the point is closer to the earlier one than
    /// that one's clearance less a cell.
    #[test]
    fn the_clearance_field_keeps_the_probe_s_bound() {
        let map = walled();
        let mut rng = Rng::new(3);
        let res = map.grid().resolution();
        let mut near = 0;
        for _ in 0..400_000 {
            let q = [rng.range(-0.2, 6.2), rng.range(-0.2, 4.2)];
            let len = rng.range(0.0, 1.0) * rng.uniform();
            let a = rng.range(0.0, std::f64::consts::TAU);
            let p = [
                q[0] + len * crate::num::cos(a),
                q[1] + len * crate::num::sin(a),
            ];
            let (cq, cp) = (map.clearance(q[0], q[1]), map.clearance(p[0], p[1]));
            let since = len * (1.0 + 1e-9);
            let jump = if since < cq - res - 1e-9 { 0.0 } else { res };
            near += usize::from(jump == 0.0 && cp < cq);
            let bound = cq - std::f64::consts::SQRT_2 * since - jump - 1e-9;
            assert!(cp > bound, "{q:?} -> {p:?}: {cp} vs {bound}");
        }
        assert!(near > 10_000, "{near}");
    }
}
