//! The local-planning engine every sampling planner of planlab is a
//! composition of: a [`TrajectoryGenerator`] (the velocity window, its
//! samples, the integration of a rollout), a list of weighted [`Critic`]s
//! (each scores a rollout or declares it illegal), a [`Scoring`] rule that
//! turns the scores into a choice and, for the DWA papers' planners, the
//! safety [`Screen`] (collision, Fox et al.'s V_a, braking, passive safety)
//! with its fallback. Nav2's DWB has the same shape (a generator plugin
//! and critic plugins with a scale each).
//!
//! One control cycle ([`Engine::plan`]):
//! 1. the generator samples its window;
//! 2. the screen (when there is one) and every critic prepare;
//! 3. each sample is rolled out, screened and scored by every critic;
//! 4. the scoring rule picks the best admissible rollout;
//! 5. with none admissible: when the cycle held the linear speed, again
//!    without the hold; then the screen's fallback (brake, turn toward the
//!    goal, or evade on the best collision-free rollout), or, without a
//!    screen, a stop;
//! 6. every critic is debriefed with the command driven.
//!
//! Nothing here panics or returns NaN; the engine allocates nothing per
//! cycle once warmed up unless rollouts are recorded.

pub mod catalogue;
pub mod critic;
pub mod generator;
pub mod screen;

pub use critic::{Critic, CriticContext, CriticSlot, Scoring};
pub use generator::{Sample, Trajectory, TrajectoryGenerator, Window, WindowRequest};
pub use screen::{Screen, ScreenConfig};

use super::{Observation, PlannerDebug, Rollout};
use crate::world::{Command, RobotSpec};

/// What one cycle of the engine is asked to do.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepRequest<'a> {
    /// The goal the critics steer to, m.
    pub goal: [f64; 2],
    /// The global path the critics may follow (empty: none).
    pub path: &'a [[f64; 2]],
    /// Each critic's weight for this cycle, in critic order; `None`: the
    /// weights the engine was built with.
    pub weights: Option<&'a [f64]>,
    /// Hold the linear speed at this value (\[S\] eq 9–12), for generators
    /// with that model; released when no sample at it is admissible.
    pub hold_v: Option<f64>,
    /// Also roll out braking manoeuvres (\[T\]'s deceleration strategy).
    pub braking: bool,
}

impl StepRequest<'_> {
    /// A request steering to `goal` with the built-in weights.
    pub fn to(goal: [f64; 2]) -> StepRequest<'static> {
        StepRequest {
            goal,
            path: &[],
            weights: None,
            hold_v: None,
            braking: false,
        }
    }
}

/// What one cycle of the engine chose.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepResult {
    /// The command.
    pub cmd: Command,
    /// Number of admissible samples (0: the fallback drove).
    pub admissible: usize,
    /// Number of samples evaluated.
    pub samples: usize,
    /// Whether the held speed had to be released (no admissible sample).
    pub hold_released: bool,
    /// The window the generator sampled.
    pub window: Window,
}

/// One evaluated sample.
#[derive(Debug, Clone, Copy)]
struct Cand {
    sample: Sample,
    admissible: bool,
    collided: bool,
    /// The weighted cost ([`Scoring::WeightedCost`]).
    cost: f64,
}

/// A generator, critics, a scoring rule and an optional screen (module
/// doc). The generator is a trait object by default; a planner that must
/// reach into its own generator every cycle (the cleaning DWA's odometry
/// correction) names its type.
#[derive(Debug)]
pub struct Engine<G: TrajectoryGenerator + ?Sized = dyn TrajectoryGenerator> {
    generator: Box<G>,
    critics: Vec<CriticSlot>,
    scoring: Scoring,
    screen: Option<Screen>,
    robot: RobotSpec,
    record: bool,
    /// Keep the chosen rollout in the debug even when not recording.
    keep_chosen: bool,
    samples: Vec<Sample>,
    cands: Vec<Cand>,
    /// Raw critic values, `[i * critics + k]`.
    raws: Vec<f64>,
    weights: Vec<f64>,
    traj: Trajectory,
    debug: PlannerDebug,
}

impl<G: TrajectoryGenerator + ?Sized> Engine<G> {
    /// Assembles an engine for `robot`. With `screen`, the DWA papers'
    /// safety screen judges admissibility and drives the fallback.
    pub fn new(
        robot: &RobotSpec,
        generator: Box<G>,
        critics: Vec<CriticSlot>,
        scoring: Scoring,
        screen: Option<ScreenConfig>,
    ) -> Self {
        let screen = screen.map(|c| Screen::new(c, robot, generator.horizon()));
        let traj = Trajectory {
            with_dirs: critics.iter().any(|c| c.critic.needs_headings()),
            ..Default::default()
        };
        let debug = PlannerDebug {
            critics: critics
                .iter()
                .map(|c| c.critic.name().to_string())
                .collect(),
            weights: critics.iter().map(|c| c.weight).collect(),
            mode: "normal".into(),
            ..Default::default()
        };
        Self {
            generator,
            critics,
            scoring,
            screen,
            robot: *robot,
            record: false,
            keep_chosen: false,
            samples: Vec::new(),
            cands: Vec::new(),
            raws: Vec::new(),
            weights: Vec::new(),
            traj,
            debug,
        }
    }

    /// Keep the chosen rollout in [`Engine::debug`] when rollouts are not
    /// recorded (for pages that draw only the driven one).
    pub fn keep_chosen(mut self, on: bool) -> Self {
        self.keep_chosen = on;
        self
    }

    /// The robot.
    pub fn robot(&self) -> &RobotSpec {
        &self.robot
    }

    /// The generator.
    pub fn generator(&self) -> &G {
        &self.generator
    }

    /// The generator, to set its per-cycle inputs.
    pub fn generator_mut(&mut self) -> &mut G {
        &mut self.generator
    }

    /// The safety screen, when the composition has one.
    pub fn screen(&self) -> Option<&Screen> {
        self.screen.as_ref()
    }

    /// The critics with their built-in weights.
    pub fn critics(&self) -> &[CriticSlot] {
        &self.critics
    }

    /// Footprint radius plus the screen's safety margin, m.
    pub fn effective_radius(&self) -> f64 {
        self.screen.as_ref().map_or_else(
            || self.robot.footprint.circumscribed_radius(),
            Screen::effective_radius,
        )
    }

    /// Record every rollout in [`Engine::debug`] or not.
    pub fn set_record(&mut self, on: bool) {
        self.record = on;
        if !on {
            self.debug.rollouts.clear();
            self.debug.chosen = None;
        }
    }

    /// What the last cycle did.
    pub fn debug(&self) -> &PlannerDebug {
        &self.debug
    }

    /// Mutable access, so planners can add their own fields.
    pub fn debug_mut(&mut self) -> &mut PlannerDebug {
        &mut self.debug
    }

    /// One control cycle: the best admissible command toward `req.goal`.
    pub fn plan(&mut self, obs: &Observation<'_>, req: &StepRequest<'_>) -> StepResult {
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
                window: Window::default(),
            };
        }
        let dt = if obs.dt.is_finite() && obs.dt > 0.0 {
            obs.dt
        } else {
            self.generator.horizon().1
        };
        let mut res = self.evaluate(obs, req, dt, req.hold_v);
        if res.admissible == 0 && req.hold_v.is_some() {
            res = self.evaluate(obs, req, dt, None);
            res.hold_released = true;
        }
        if res.admissible == 0 {
            self.debug.chosen = None;
            res.cmd = self.fall_back(obs, req, dt);
        }
        let chosen = (res.admissible > 0).then_some(res.cmd);
        for c in &mut self.critics {
            c.critic.debrief(chosen.as_ref());
        }
        res
    }

    /// The command with no admissible sample (module doc, step 5).
    fn fall_back(&mut self, obs: &Observation<'_>, req: &StepRequest<'_>, dt: f64) -> Command {
        let Some(screen) = &self.screen else {
            self.debug.mode = "no-admissible".into();
            return Command::default();
        };
        // Braking will not avoid it (a mover keeps coming, or the robot
        // would stop in a mover's predicted path): fall back on Fox et
        // al.'s own rule, the best collision-free sample. The rest and
        // stranding checks that ruled every sample out look 4 horizons
        // ahead at constant velocity — wrong for a mover that turns round —
        // and the most-clearance choice used before tied at the critic's
        // cap whenever nothing came within the horizon, so it turned the
        // robot on the spot in a mover's way until that arrived (dwa-demo
        // variants).
        let evade = if screen.braking_collides(obs.map, obs.state) {
            self.best_collision_free()
        } else {
            None
        };
        match evade {
            Some(i) => {
                self.debug.mode = "no-admissible-evade".into();
                if self.record {
                    self.debug.chosen = Some(i);
                }
                self.cands[i].sample.cmd
            }
            None => {
                self.debug.mode = "no-admissible".into();
                screen.fallback(obs.map, obs.state, req.goal, dt)
            }
        }
    }

    fn evaluate(
        &mut self,
        obs: &Observation<'_>,
        req: &StepRequest<'_>,
        dt: f64,
        hold_v: Option<f64>,
    ) -> StepResult {
        let wreq = WindowRequest {
            dt,
            hold_v,
            braking: req.braking,
        };
        let mut samples = std::mem::take(&mut self.samples);
        let window = self.generator.samples(obs, &wreq, &mut samples);
        if let Some(sc) = &mut self.screen {
            sc.prepare(obs, &window, dt);
        }
        self.weights.clear();
        match req.weights {
            Some(w) if w.len() == self.critics.len() => self.weights.extend_from_slice(w),
            _ => self.weights.extend(self.critics.iter().map(|c| c.weight)),
        }
        let ctx = CriticContext {
            obs,
            goal: req.goal,
            path: req.path,
            robot: &self.robot,
            samples: &samples,
            window: &window,
        };
        for c in &mut self.critics {
            c.critic.prepare(&ctx);
        }
        let record = self.record;
        if record {
            self.debug.rollouts.clear();
        }
        self.cands.clear();
        self.raws.clear();
        let n_crit = self.critics.len();
        let horizon = self.generator.horizon().0;
        for &sample in &samples {
            let n = self
                .screen
                .as_ref()
                .map_or(horizon, |s| s.steps_for(&sample));
            self.generator.rollout(obs, sample, n, &mut self.traj);
            let verdict = match &self.screen {
                Some(sc) => sc.check(obs, &mut self.traj),
                None => screen::Verdict {
                    collided: false,
                    admissible: true,
                    shown: self.traj.horizon,
                },
            };
            let mut legal = true;
            let mut cost = 0.0;
            for (c, &w) in self.critics.iter().zip(&self.weights) {
                let raw = c.critic.score(&ctx, &self.traj);
                legal &= raw.is_some();
                let raw = raw.unwrap_or(f64::NAN);
                cost += w * raw;
                self.raws.push(raw);
            }
            let admissible = verdict.admissible
                && legal
                && (self.scoring == Scoring::NormalisedSum || cost.is_finite());
            self.cands.push(Cand {
                sample,
                admissible,
                collided: verdict.collided,
                cost,
            });
            if record {
                let i = self.cands.len() - 1;
                self.debug.rollouts.push(Rollout {
                    cmd: sample.cmd,
                    points: self.traj.points[..verdict.shown.min(self.traj.points.len())].to_vec(),
                    admissible,
                    raw: self.raws[i * n_crit..(i + 1) * n_crit].to_vec(),
                    normalised: vec![0.0; n_crit],
                    score: f64::NEG_INFINITY,
                });
            }
        }
        let best = self.choose(n_crit);
        let n_ok = self.cands.iter().filter(|c| c.admissible).count();
        self.debug.weights.clone_from(&self.weights);
        self.debug.chosen = if record { best } else { None };
        self.debug.current_goal = req.goal;
        if !record && self.keep_chosen {
            self.debug.rollouts.clear();
            if let Some(i) = best {
                self.keep_only(obs, i, n_crit);
            }
        }
        let cmd = best.map_or_else(Command::default, |i| self.cands[i].sample.cmd);
        self.samples = samples;
        StepResult {
            cmd,
            admissible: n_ok,
            samples: self.cands.len(),
            hold_released: false,
            window,
        }
    }

    /// The best admissible candidate under the scoring rule; fills the
    /// recorded rollouts' normalised values and scores.
    fn choose(&mut self, n_crit: usize) -> Option<usize> {
        // Each critic's sum over the admissible samples (the papers'
        // normalisation; shown for cost rules too).
        let mut sum = vec![0.0f64; n_crit];
        for (i, c) in self.cands.iter().enumerate() {
            if c.admissible {
                for (k, x) in sum.iter_mut().enumerate() {
                    *x += self.raws[i * n_crit + k];
                }
            }
        }
        let mut best: Option<(usize, f64)> = None;
        for (i, c) in self.cands.iter().enumerate() {
            if !c.admissible {
                continue;
            }
            let raw = &self.raws[i * n_crit..(i + 1) * n_crit];
            let norm = |k: usize| if sum[k] > 0.0 { raw[k] / sum[k] } else { 0.0 };
            let score = match self.scoring {
                Scoring::NormalisedSum => {
                    let mut g = 0.0;
                    for (k, w) in self.weights.iter().enumerate() {
                        g += w * norm(k);
                    }
                    if g.is_finite() {
                        g
                    } else {
                        f64::NEG_INFINITY
                    }
                }
                Scoring::WeightedCost => -c.cost,
            };
            // Ties keep the first sample.
            if best.map_or(true, |(_, b)| score > b) {
                best = Some((i, score));
            }
            if self.record {
                if let Some(r) = self.debug.rollouts.get_mut(i) {
                    for (k, x) in r.normalised.iter_mut().enumerate() {
                        *x = norm(k);
                    }
                    r.score = score;
                }
            }
        }
        best.map(|(i, _)| i)
    }

    /// The collision-free candidate with the best G, each critic normalised
    /// by its sum over the collision-free candidates.
    fn best_collision_free(&self) -> Option<usize> {
        let n_crit = self.critics.len();
        let mut sum = vec![0.0f64; n_crit];
        for (i, c) in self.cands.iter().enumerate() {
            if c.collided {
                continue;
            }
            for (k, x) in sum.iter_mut().enumerate() {
                *x += self.raws[i * n_crit + k];
            }
        }
        let mut best: Option<(usize, f64)> = None;
        for (i, _) in self.cands.iter().enumerate().filter(|(_, c)| !c.collided) {
            let mut score = 0.0;
            for (k, w) in self.weights.iter().enumerate() {
                if sum[k] > 0.0 {
                    score += w * self.raws[i * n_crit + k] / sum[k];
                }
            }
            if !score.is_finite() {
                score = f64::NEG_INFINITY;
            }
            if best.map_or(true, |(_, b)| score > b) {
                best = Some((i, score));
            }
        }
        best.map(|(i, _)| i)
    }

    /// Keeps only candidate `i` in the debug, rolled out again for its
    /// points.
    fn keep_only(&mut self, obs: &Observation<'_>, i: usize, n_crit: usize) {
        let c = self.cands[i];
        let horizon = self.generator.horizon().0;
        self.generator
            .rollout(obs, c.sample, horizon, &mut self.traj);
        let raw = &self.raws[i * n_crit..(i + 1) * n_crit];
        let mut sum = vec![0.0f64; n_crit];
        for (j, d) in self.cands.iter().enumerate() {
            if d.admissible {
                for (k, x) in sum.iter_mut().enumerate() {
                    *x += self.raws[j * n_crit + k];
                }
            }
        }
        self.debug.rollouts.push(Rollout {
            cmd: c.sample.cmd,
            points: self.traj.points.clone(),
            admissible: true,
            raw: raw.to_vec(),
            normalised: raw
                .iter()
                .zip(&sum)
                .map(|(r, s)| if *s > 0.0 { r / s } else { 0.0 })
                .collect(),
            score: -c.cost,
        });
        self.debug.chosen = Some(0);
    }
}

#[cfg(test)]
mod tests {
    use super::critic::{Critic, CriticContext, Twirling};
    use super::generator::DynamicWindow;
    use super::*;
    use crate::local::testkit;
    use crate::world::RobotState;

    /// Prefers turning left: the raw score is ω + 1 (positive, as the
    /// normalised sum needs; under the cost rule it prefers turning right).
    #[derive(Debug)]
    struct TurnRate;

    impl Critic for TurnRate {
        fn name(&self) -> &str {
            "turn_rate"
        }
        fn score(&self, _ctx: &CriticContext<'_>, traj: &Trajectory) -> Option<f64> {
            Some(traj.sample.cmd.w + 1.0)
        }
    }

    /// Declares every rollout turning right illegal.
    #[derive(Debug)]
    struct NoRightTurns;

    impl Critic for NoRightTurns {
        fn name(&self) -> &str {
            "no_right_turns"
        }
        fn score(&self, _ctx: &CriticContext<'_>, traj: &Trajectory) -> Option<f64> {
            (traj.sample.cmd.w >= 0.0).then_some(0.0)
        }
    }

    fn engine(critics: Vec<CriticSlot>, scoring: Scoring) -> Engine {
        let robot = RobotSpec::default();
        let gen = DynamicWindow::new(robot.limits, (0.01, 0.01), (3, 5), (1.0, 0.1), false);
        Engine::new(&robot, Box::new(gen), critics, scoring, None)
    }

    fn plan(e: &mut Engine, weights: Option<&[f64]>) -> StepResult {
        let map = testkit::map(&".".repeat(40), 0.1);
        let s = RobotState {
            x: 1.0,
            y: 0.05,
            v: 0.5,
            w: 0.0,
            ..Default::default()
        };
        let obs = testkit::observation(&s, [3.0, 0.05], &map);
        e.plan(
            &obs,
            &StepRequest {
                weights,
                ..StepRequest::to([3.0, 0.05])
            },
        )
    }

    #[test]
    fn the_normalised_sum_takes_the_highest_and_the_cost_rule_the_lowest() {
        let mut hi = engine(vec![CriticSlot::new(TurnRate, 1.0)], Scoring::NormalisedSum);
        let mut lo = engine(vec![CriticSlot::new(TurnRate, 1.0)], Scoring::WeightedCost);
        let (a, b) = (plan(&mut hi, None), plan(&mut lo, None));
        let w_max = a.window.w.1;
        assert!(w_max > 0.0);
        assert_eq!(a.cmd.w, w_max);
        assert_eq!(b.cmd.w, a.window.w.0);
        assert_eq!(a.samples, 15);
        assert_eq!(hi.debug().critics, ["turn_rate"]);
    }

    #[test]
    fn a_cycle_s_weights_override_the_built_in_ones() {
        let critics = vec![
            CriticSlot::new(TurnRate, 1.0),
            CriticSlot::new(Twirling::named("twirl"), 0.0),
        ];
        let mut e = engine(critics, Scoring::WeightedCost);
        assert!(plan(&mut e, None).cmd.w < 0.0);
        // A heavy twirl weight makes driving straight the cheapest.
        let r = plan(&mut e, Some(&[1.0, 10.0]));
        assert_eq!(r.cmd.w, 0.0);
        assert_eq!(e.debug().weights, [1.0, 10.0]);
    }

    #[test]
    fn an_illegal_rollout_is_never_chosen_and_none_legal_stops() {
        let critics = vec![
            CriticSlot::new(TurnRate, 1.0),
            CriticSlot::new(NoRightTurns, 1.0),
        ];
        let mut e = engine(critics, Scoring::WeightedCost);
        e.set_record(true);
        let r = plan(&mut e, None);
        assert_eq!(r.cmd.w, 0.0, "the lowest legal turn rate");
        let d = e.debug();
        let illegal = d.rollouts.iter().filter(|r| !r.admissible).count();
        assert_eq!(illegal, 6, "the two right-turn columns of 3 speeds");
        assert!(d.rollouts.iter().all(|r| r.admissible == (r.cmd.w >= 0.0)));
        let chosen = d.chosen.map(|i| d.rollouts[i].score);
        assert_eq!(chosen, Some(-1.0));
        // Nothing legal: without a screen the engine stops.
        let mut none = engine(
            vec![CriticSlot::new(NoRightTurns, 1.0)],
            Scoring::NormalisedSum,
        );
        let map = testkit::map("....", 0.1);
        let s = RobotState {
            w: -1.0,
            ..Default::default()
        };
        let obs = testkit::observation(&s, [1.0, 0.0], &map);
        let r = none.plan(&obs, &StepRequest::to([1.0, 0.0]));
        assert_eq!(r.admissible, 0);
        assert_eq!(r.cmd, Command::default());
        assert_eq!(none.debug().mode, "no-admissible");
    }
}
