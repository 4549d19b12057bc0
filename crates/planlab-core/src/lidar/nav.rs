//! The heuristic temporary-goal navigator of \[L\] §3, on a scan alone.
//!
//! Its input type, [`NavInput`], holds the scan, the robot's velocity and
//! the goal in the robot frame (\[L\] assumptions 2–3) and nothing else: the
//! navigator cannot read the map or the robot's world pose.
//!
//! One step (\[L\] Fig 12): edges → Algorithm 1 → Algorithm 2 → expansion
//! (eq 1) → is the goal blocked (eq 2, nearest blocking OP)? If not, steer
//! to the goal. If so: two candidates d_te beyond either end of the OP,
//! cost eq 3 = |robot → candidate| + |candidate → target|, the cheaper one
//! wins; while the winner is itself blocked, choose again around the OP
//! blocking it with the winner as the target (at most `max_iterations`
//! times, then this step steers to the goal).
//!
//! **Extra conditions** (§3.4, off in dynamic scenes): (1) eq 4 — leave the
//! goal for a temporary goal only when the blocking OP is wider than T_θo
//! or nearer than T_do (**Decision**: checked when switching from the goal;
//! while a temporary goal is in force the basic condition alone keeps it);
//! (2) hold — when the two first candidates' costs differ by less than
//! T_dc, keep the chosen temporary goal for t_h s while the goal stays
//! blocked. The navigator has no pose, so the held goal is carried along by
//! integrating the robot's own velocity (the simulator's Euler step: move
//! by (v, v_y)·dt, then turn by ω·dt).
//!
//! **Sampled selection** (**Decision**): \[L\] states the hold for a choice
//! made continuously. The two costs are continuous in the robot's pose, so
//! the cheaper side can only change where they are equal, and the current
//! side's lead falls below T_dc first — which starts the hold on the
//! current side. At 10 Hz, with candidates that jump with the beam grid (an
//! OP cut by a weak edge on a wall seen at a grazing angle moves by a metre
//! when the beams shift by one), the order can swap between two steps with
//! the lead never seen below T_dc. So when the previous step's first choice
//! (carried along) is still one of the two candidates — within T_gap of it,
//! the distance under which \[L\] joins scan points into one obstacle, so
//! the robot cannot pass between them — but the other one is now cheaper,
//! the costs crossed: the current candidate is kept and held for t_h. A
//! candidate farther than T_gap from the previous choice is a new one (the
//! blocking OP changed or grew): no crossing is assumed. A fresh choice
//! (from the goal, or when a hold ends) has no previous one.

use serde::{Deserialize, Serialize};

use super::edges::{self, Edge, GapPattern, ObstaclePattern};
use super::scan::{polar, Scan};
use super::LidarError;
/// Defined with the planner debug data in `local`, which names it.
pub use crate::local::scan_debug::TargetKind;
use crate::num::{atan2, cos, hypot, sin};

crate::params::params! {
    /// \[L\] Table 1 navigation parameters (defaults) and the switches of §3.4.
    #[derive(Debug, Clone, Copy, PartialEq)]
    pub struct LidarNavConfig {
        pub t_gap: f64 = 1.4, "m" [>= 0.0] label "gap threshold T_gap" "T_gap: weak edges and gap widths";
        pub theta_range: f64 = std::f64::consts::FRAC_PI_2, "rad" [>= 0.0]
            label "edge search angle θ_range" "θ_range: Algorithm 1 looks this far past a rising edge";
        pub d_oe: f64 = 0.5, "m" [>= 0.0] label "obstacle expansion d_oe" "d_oe: obstacle expansion (eq 1)";
        pub d_te: f64 = 0.5, "m" [>= 0.0] label "temporary goal offset d_te" "d_te: temporary goal offset beyond an OP end";
        pub t_do: f64 = 4.0, "m" [>= 0.0] label "switch distance T_do" "T_do (eq 4): switch when the blocking OP is nearer";
        pub t_theta_o: f64 = 0.6 * std::f64::consts::PI, "rad" [>= 0.0]
            label "switch angle T_θo" "T_θo (eq 4): … or wider than this";
        pub t_dc: f64 = 0.3, "m" [>= 0.0] label "hold cost difference T_dc" "T_dc: hold when the candidates' costs differ by less";
        pub t_h: f64 = 3.0, "s" [>= 0.0] label "hold period t_h" "t_h: hold period";
        pub max_iterations: u32 = 3, "1" [] label "most re-selections" "most re-selections of a blocked temporary goal";
        /// Extra condition 1.
        pub switch_condition: bool = true, "bool" []
            label "switch condition (eq 4)" "apply eq 4 before switching to a temporary goal";
        /// Extra condition 2.
        pub hold: bool = true, "bool" [] label "hold period on" "apply the hold period";
        /// 0 = to the point itself. **Decision**: a temporary goal is a
        /// waypoint to pass, not a place to stop; a DWA heading critic aimed
        /// at a point closer than its rollouts reach makes the robot circle
        /// it.
        pub lookahead: f64 = 3.0, "m" [>= 0.0]
            label "look-ahead distance" "steer to a temporary goal at least this far along its bearing";
    }
}

impl LidarNavConfig {
    /// The dynamic-scene settings of \[L\] sim 9: d_oe 0.8 m, d_te 1 m, no
    /// extra switching conditions.
    pub fn dynamic() -> Self {
        Self {
            d_oe: 0.8,
            d_te: 1.0,
            switch_condition: false,
            hold: false,
            ..Default::default()
        }
    }

    /// Checks every number; errors name `prefix.field`.
    pub fn validate(&self, prefix: &str) -> Result<(), LidarError> {
        crate::params::Params::check_bounds(self, prefix)?;
        if self.max_iterations > 100 {
            return Err(LidarError::InvalidParameter(format!(
                "{prefix}.max_iterations = {}: at most 100",
                self.max_iterations
            )));
        }
        Ok(())
    }
}

/// The robot's own velocity (body frame).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Velocity {
    /// Forward speed, m/s.
    pub v: f64,
    /// Sideways speed, m/s.
    pub vy: f64,
    /// Turn rate, rad/s.
    pub w: f64,
}

/// Everything the navigator may know at one step (\[L\] assumptions 2–3).
#[derive(Debug, Clone, Copy)]
pub struct NavInput<'a> {
    /// The scan, robot frame.
    pub scan: &'a Scan,
    /// The robot's velocity during the last control period.
    pub velocity: Velocity,
    /// The global goal in the robot frame (x forward, y left), m.
    pub goal: [f64; 2],
    /// Control period, s.
    pub dt: f64,
}

/// One temporary-goal candidate, robot frame.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Candidate {
    /// Position, m.
    pub point: [f64; 2],
    /// Cost of eq 3, m.
    pub cost: f64,
    /// Iteration it belongs to (0 = around the OP blocking the goal).
    pub iteration: u32,
}

/// What one navigator step saw and decided, robot frame.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct NavDebug {
    /// Edges of the raw scan (def. 1).
    pub edges_raw: Vec<Edge>,
    /// Ranges after Algorithm 1 (`INFINITY` = no return).
    #[serde(skip)]
    pub ranges_mdf: Vec<f64>,
    /// Edges after Algorithm 1.
    pub edges_mdf: Vec<Edge>,
    /// Gap patterns Algorithm 1 removed.
    pub gaps: Vec<GapPattern>,
    /// Obstacle patterns after expansion (set the `ext_*` fields to 0 for
    /// the unexpanded ones).
    pub ops: Vec<ObstaclePattern>,
    /// Index into `ops` of the OP blocking the goal.
    pub blocking: Option<usize>,
    /// Every candidate evaluated this step.
    pub candidates: Vec<Candidate>,
    /// The cost difference d_c of the first two candidates, m.
    pub cost_gap: Option<f64>,
    /// Iterations used (re-selections of a blocked candidate).
    pub iterations: u32,
    /// The target, m.
    pub target: [f64; 2],
    /// Its kind.
    pub kind: TargetKind,
    /// Time left in the hold period, s (0 = none).
    pub hold_remaining: f64,
}

/// The navigator: state carried between steps (mode and hold).
#[derive(Debug, Clone)]
pub struct Navigator {
    cfg: LidarNavConfig,
    in_temp: bool,
    /// (time left, held goal in the current robot frame).
    hold: Option<(f64, [f64; 2])>,
    /// The first candidate chosen at the previous step, when that step
    /// chose (not held), current robot frame.
    last_choice: Option<[f64; 2]>,
    debug: NavDebug,
}

impl Navigator {
    /// A navigator; the config is validated (errors name `prefix.field`).
    pub fn new(cfg: LidarNavConfig, prefix: &str) -> Result<Navigator, LidarError> {
        cfg.validate(prefix)?;
        Ok(Navigator {
            cfg,
            in_temp: false,
            hold: None,
            last_choice: None,
            debug: NavDebug::default(),
        })
    }

    /// The config.
    pub fn config(&self) -> &LidarNavConfig {
        &self.cfg
    }

    /// What the last step did.
    pub fn debug(&self) -> &NavDebug {
        &self.debug
    }

    /// Forgets the mode and any hold (the goal moved).
    pub fn reset(&mut self) {
        self.in_temp = false;
        self.hold = None;
        self.last_choice = None;
    }

    /// Scan processing alone (§2): edges, Algorithm 1, Algorithm 2 and the
    /// expansion, into the debug record.
    pub fn perceive(&mut self, scan: &Scan) {
        let d = &mut self.debug;
        edges::classify(scan.ranges(), self.cfg.t_gap, &mut d.edges_raw);
        d.ranges_mdf.clear();
        d.ranges_mdf.extend_from_slice(scan.ranges());
        d.edges_mdf.clear();
        d.edges_mdf.extend_from_slice(&d.edges_raw);
        edges::remove_gaps(
            &mut d.ranges_mdf,
            &mut d.edges_mdf,
            self.cfg.t_gap,
            self.cfg.theta_range,
            &mut d.gaps,
        );
        edges::extract_ops(&d.ranges_mdf, &d.edges_mdf, &mut d.ops);
        edges::expand(&mut d.ops, self.cfg.d_oe);
    }

    /// One step: the target to steer to, robot frame.
    pub fn step(&mut self, input: &NavInput<'_>) -> [f64; 2] {
        self.perceive(input.scan);
        let dt = if input.dt.is_finite() && input.dt > 0.0 {
            input.dt
        } else {
            0.0
        };
        if let Some((left, g)) = self.hold.as_mut() {
            *g = carry(*g, input.velocity, dt);
            *left -= dt;
        }
        if let Some(p) = self.last_choice.as_mut() {
            *p = carry(*p, input.velocity, dt);
        }
        let goal = input.goal;
        self.debug.candidates.clear();
        self.debug.cost_gap = None;
        self.debug.iterations = 0;
        self.debug.blocking = None;
        if !(goal[0].is_finite() && goal[1].is_finite()) {
            // No goal to go to: stay put (the motion planner brakes).
            self.reset();
            return self.finish([0.0, 0.0], TargetKind::Global);
        }
        self.decide(goal)
    }

    fn decide(&mut self, goal: [f64; 2]) -> [f64; 2] {
        let Some((blk, d_o)) = self.blocking(goal) else {
            self.reset();
            return self.finish(goal, TargetKind::Global);
        };
        self.debug.blocking = Some(blk);
        // The previous step's first choice; `None` after a hold or from the
        // goal (a fresh choice).
        let last_choice = self.last_choice.take();
        if let Some((left, g)) = self.hold {
            if left > 1e-9 {
                return self.finish(g, TargetKind::Held);
            }
            self.hold = None;
        }
        let n = self.debug.ranges_mdf.len();
        if self.cfg.switch_condition && !self.in_temp {
            let op = &self.debug.ops[blk];
            if !(op.width(n) > self.cfg.t_theta_o || d_o < self.cfg.t_do) {
                return self.finish(goal, TargetKind::Global);
            }
        }
        let holds = self.cfg.hold && self.cfg.t_h > 0.0;
        match self.choose(goal, blk, None) {
            Some(mut ch) => {
                self.in_temp = true;
                let mut hold = holds && ch.gap < self.cfg.t_dc;
                if let Some(prev) = last_choice.filter(|_| holds) {
                    let d = |q: [f64; 2]| hypot(q[0] - prev[0], q[1] - prev[1]);
                    let current = usize::from(d(ch.pair[1]) < d(ch.pair[0]));
                    if current != ch.side && d(ch.pair[current]) < self.cfg.t_gap {
                        // The costs crossed since the last step: keep the
                        // current side and hold it (module doc).
                        let seen = std::mem::take(&mut self.debug.candidates);
                        let its = self.debug.iterations;
                        if let Some(kept) = self.choose(goal, blk, Some(current)) {
                            ch = kept;
                            hold = true;
                        } else {
                            self.debug.candidates = seen;
                            self.debug.iterations = its;
                        }
                    }
                }
                if hold {
                    self.hold = Some((self.cfg.t_h, ch.point));
                } else {
                    self.last_choice = Some(ch.pair[ch.side]);
                }
                self.finish(ch.point, TargetKind::Temporary)
            }
            None => {
                self.in_temp = false;
                self.finish(goal, TargetKind::Global)
            }
        }
    }

    fn finish(&mut self, target: [f64; 2], kind: TargetKind) -> [f64; 2] {
        self.debug.target = target;
        self.debug.kind = kind;
        self.debug.hold_remaining = self.hold.map_or(0.0, |(l, _)| l.max(0.0));
        target
    }

    /// The nearest OP blocking `p` (eq 2) and its range at p's bearing.
    fn blocking(&self, p: [f64; 2]) -> Option<(usize, f64)> {
        let d_tar = hypot(p[0], p[1]);
        if d_tar.is_nan() || d_tar <= 0.0 {
            return None;
        }
        let th = atan2(p[1], p[0]);
        let r = &self.debug.ranges_mdf;
        self.debug
            .ops
            .iter()
            .enumerate()
            .filter_map(|(i, op)| op.range_at(th, r).map(|d| (i, d)))
            .filter(|&(_, d)| d_tar > d)
            .fold(None, |best: Option<(usize, f64)>, (i, d)| match best {
                Some((_, bd)) if bd <= d => best,
                _ => Some((i, d)),
            })
    }

    /// §3.2–3.3: the temporary goal around OP `blk` for `goal`; `side`
    /// forces the side of the first choice (0 = before the OP's start, 1 =
    /// after its end) instead of the cheaper one. `None` when the iteration
    /// limit is exceeded or the OP has no ends.
    fn choose(&mut self, goal: [f64; 2], blk: usize, side: Option<usize>) -> Option<Choice> {
        let n = self.debug.ranges_mdf.len();
        let mut target = goal;
        let mut op_i = blk;
        let mut first: Option<([[f64; 2]; 2], usize, f64)> = None;
        for it in 0..=self.cfg.max_iterations {
            let op = self.debug.ops[op_i];
            if op.closed {
                return None;
            }
            let a0 = op.start_angle(n) - edges::expansion_angle(self.cfg.d_te, op.d_first);
            let a1 = op.end_angle(n) + edges::expansion_angle(self.cfg.d_te, op.d_last);
            let c = [polar(a0, op.d_first), polar(a1, op.d_last)];
            let cost = |p: [f64; 2]| hypot(p[0], p[1]) + hypot(p[0] - target[0], p[1] - target[1]);
            let k = [cost(c[0]), cost(c[1])];
            for (p, &kk) in c.iter().zip(&k) {
                self.debug.candidates.push(Candidate {
                    point: *p,
                    cost: kk,
                    iteration: it,
                });
            }
            let cheaper = usize::from(k[1] < k[0]);
            let pick = match (it, side) {
                (0, Some(s)) => s.min(1),
                _ => cheaper,
            };
            if it == 0 {
                let gap = (k[0] - k[1]).abs();
                first = Some((c, pick, gap));
                self.debug.cost_gap = Some(gap);
            }
            let chosen = c[pick];
            self.debug.iterations = it;
            match self.blocking(chosen) {
                None => {
                    let (pair, side, gap) = first?;
                    return Some(Choice {
                        point: chosen,
                        pair,
                        side,
                        gap,
                    });
                }
                Some((next, _)) => {
                    target = chosen;
                    op_i = next;
                }
            }
        }
        None
    }
}

/// A temporary goal and how it was chosen.
#[derive(Debug, Clone, Copy)]
struct Choice {
    /// The temporary goal (after any iteration), robot frame, m.
    point: [f64; 2],
    /// The two first candidates (around the OP blocking the goal): before
    /// its start, after its end.
    pair: [[f64; 2]; 2],
    /// Which of them was chosen.
    side: usize,
    /// Their cost difference d_c, m.
    gap: f64,
}

/// A point fixed in the world, expressed in the robot frame after the
/// robot moved with `vel` for `dt` (Euler: translate, then rotate).
pub fn carry(p: [f64; 2], vel: Velocity, dt: f64) -> [f64; 2] {
    let ok = vel.v.is_finite() && vel.vy.is_finite() && vel.w.is_finite();
    if !ok || dt == 0.0 {
        return p;
    }
    let (x, y) = (p[0] - vel.v * dt, p[1] - vel.vy * dt);
    let a = -vel.w * dt;
    let (s, c) = (sin(a), cos(a));
    [c * x - s * y, s * x + c * y]
}
