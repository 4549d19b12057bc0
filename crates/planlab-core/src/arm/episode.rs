//! An arm episode (\[T\] §5.3.3, Table 5-3): the end effector is planned in
//! 3D by the APF of [`crate::apf`] (with or without obstacle prediction)
//! among the moving hand and forearm, one 0.04 m step per planning period;
//! each step's point is reached by IK and the joints move there linearly
//! over the period. The hand is observed every sample period (0.1 s, the
//! thesis's rate), so predictors see a regular history.
//!
//! Metrics (docs/algorithms.md §metrics, Tables 4-1 / 5-3): outcome, path length and number of
//! points of the tool's path at the planning instants, spikes (interior
//! points turning more than 30°), the minimum distance between any link
//! capsule and the hand or forearm over every sample, and the time.

use glam::DVec3;
use serde::{Deserialize, Serialize};

use super::geometry::{link_capsules, link_distance, min_distance, LinkCapsule, Obstacle3};
use super::hand::{HandMotion, HandSpec};
use super::kinematics::IkConfig;
use super::model::{ArmModel, ArmSpec};
use super::ArmError;
use crate::apf::{Apf, ApfConfig, ApfMetrics, ApfMode, ApfStep, ObstacleObs, PredictorKind};
use crate::params::{check_param, Bound};
use crate::world::Outcome;

/// Points along a planned joint move at which the whole-arm check looks for
/// contact (a planned move is one 0.04 m tool step, so the links move
/// little between two checks).
pub const MOTION_CHECKS: usize = 4;

/// The whole-arm check keeps every link at least this far from the hand,
/// m: a move that ends nearer than this, and nearer than the arm is now, is
/// refused like one that touches. Without it the arm crept up to the hand
/// (each move ending a hair short of contact) until it pressed against it
/// 0.1 mm away, drawn inside it, every candidate refused, and the run ended
/// stuck. A move that gains distance is always allowed, so the margin
/// never traps an arm already inside it.
pub const ARM_CLEARANCE_M: f64 = 0.005;

/// Timing and end conditions of an arm episode.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ArmSimConfig {
    /// Time between planning steps (one APF step of `apf.step` each), s.
    pub plan_period_s: f64,
    /// Time between hand observations and distance checks, s; the plan
    /// period is rounded to a whole number of samples.
    pub sample_period_s: f64,
    /// Give up after this long, s.
    pub max_time_s: f64,
    /// The tool within this of the goal has arrived, m.
    pub goal_tolerance_m: f64,
    /// No 1 cm of progress towards the goal for this long: stuck, s.
    pub stuck_time_s: f64,
}

impl Default for ArmSimConfig {
    fn default() -> Self {
        Self {
            plan_period_s: 0.5,
            sample_period_s: 0.1,
            max_time_s: 60.0,
            goal_tolerance_m: 0.005,
            stuck_time_s: 15.0,
        }
    }
}

/// Which obstacle predictor the end-effector APF uses (the page's switch).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ArmPredictor {
    /// No prediction: sampling APF with the relative distance rule.
    None,
    /// Constant-velocity prediction at t+1, t+2.
    ConstantVelocity,
    /// The SimpleRNN of \[T\] §5.2 (shipped weights) at t+1, t+2.
    Rnn,
}

impl ArmPredictor {
    /// Every choice, in the page's order.
    pub const ALL: [ArmPredictor; 3] = [
        ArmPredictor::None,
        ArmPredictor::ConstantVelocity,
        ArmPredictor::Rnn,
    ];

    /// The kebab-case name.
    pub fn name(self) -> &'static str {
        match self {
            ArmPredictor::None => "none",
            ArmPredictor::ConstantVelocity => "constant-velocity",
            ArmPredictor::Rnn => "rnn",
        }
    }

    /// Parses a kebab-case name (`cv` is accepted for constant velocity).
    pub fn parse(s: &str) -> Result<ArmPredictor, ArmError> {
        match s {
            "none" => Ok(ArmPredictor::None),
            "constant-velocity" | "cv" => Ok(ArmPredictor::ConstantVelocity),
            "rnn" => Ok(ArmPredictor::Rnn),
            _ => Err(ArmError::Invalid(format!(
                "unknown predictor `{s}`: use none, constant-velocity or rnn"
            ))),
        }
    }

    /// The APF config with this predictor (mode and predictor set).
    pub fn apply(self, cfg: &mut ApfConfig) {
        match self {
            ArmPredictor::None => {
                if cfg.mode == ApfMode::SamplingPrediction {
                    cfg.mode = ApfMode::Sampling;
                }
            }
            ArmPredictor::ConstantVelocity => {
                cfg.mode = ApfMode::SamplingPrediction;
                cfg.predictor = PredictorKind::ConstantVelocity;
            }
            ArmPredictor::Rnn => {
                cfg.mode = ApfMode::SamplingPrediction;
                cfg.predictor = PredictorKind::Rnn;
            }
        }
    }

    /// The predictor an APF config uses.
    pub fn of(cfg: &ApfConfig) -> ArmPredictor {
        match cfg.mode {
            ApfMode::SamplingPrediction => match cfg.predictor {
                PredictorKind::ConstantVelocity => ArmPredictor::ConstantVelocity,
                PredictorKind::Rnn => ArmPredictor::Rnn,
            },
            _ => ArmPredictor::None,
        }
    }
}

/// The `arm` section of an arm scenario.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ArmScene {
    /// The arm (an arm file's content); default the built-in TIAGo-like
    /// arm.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub model: Option<ArmSpec>,
    /// Posture IK starts from to put the tool on `start`, rad (default
    /// the arm's home).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub start_q: Option<Vec<f64>>,
    /// Tool position at the start, m.
    pub start: [f64; 3],
    /// Tool goal, m.
    pub goal: [f64; 3],
    /// The moving hand.
    #[serde(default)]
    pub hand: HandSpec,
    /// The end-effector APF (mode, predictor, gains; step 0.04 m).
    #[serde(default = "arm_apf_default")]
    pub apf: ApfConfig,
    /// IK settings.
    #[serde(default)]
    pub ik: IkConfig,
    /// Timing and end conditions.
    #[serde(default)]
    pub sim: ArmSimConfig,
}

/// The APF defaults for the arm: the thesis's, with the tool's radius as
/// the robot radius.
pub fn arm_apf_default() -> ApfConfig {
    ApfConfig {
        robot_radius: 0.04,
        ..ApfConfig::default()
    }
}

/// What one arm episode measured: the APF metrics (`planlab run --json` /
/// `planlab reproduce --json` field names), with the minimum distance
/// taken between any link capsule and the hand or forearm.
pub type ArmMetrics = ApfMetrics;

/// One arm episode, stepped sample by sample.
pub struct ArmEpisode {
    model: ArmModel,
    scene: ArmScene,
    hand: HandMotion,
    apf: Apf<DVec3>,
    radii: Vec<f64>,
    /// Samples per planning period.
    per_plan: u64,
    dt: f64,
    tick: u64,
    q: Vec<f64>,
    q_from: Vec<f64>,
    q_to: Vec<f64>,
    path: Vec<DVec3>,
    hand_path: Vec<DVec3>,
    last_step: Option<ApfStep<DVec3>>,
    min_dist: f64,
    refusals: u32,
    dist_now: f64,
    outcome: Outcome,
    end_time: f64,
    best_goal_dist: f64,
    best_at: f64,
}

impl std::fmt::Debug for ArmEpisode {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ArmEpisode")
            .field("t", &self.time())
            .field("outcome", &self.outcome)
            .finish()
    }
}

fn check_pos(what: &str, v: f64) -> Result<(), ArmError> {
    Ok(check_param(what, v, Bound::above(0.0))?)
}

impl ArmEpisode {
    /// Builds an episode: validates everything, puts the tool on the start
    /// by IK and checks that start and goal are reachable and free.
    pub fn new(scene: ArmScene, seed: u64) -> Result<ArmEpisode, ArmError> {
        let model = match &scene.model {
            Some(spec) => ArmModel::from_spec(spec.clone())?,
            None => ArmModel::tiago(),
        };
        scene.ik.validate()?;
        scene
            .apf
            .validate()
            .map_err(|e| ArmError::Invalid(e.to_string()))?;
        let sim = scene.sim;
        check_pos("sim.plan_period_s", sim.plan_period_s)?;
        check_pos("sim.sample_period_s", sim.sample_period_s)?;
        check_pos("sim.max_time_s", sim.max_time_s)?;
        check_pos("sim.goal_tolerance_m", sim.goal_tolerance_m)?;
        check_pos("sim.stuck_time_s", sim.stuck_time_s)?;
        if sim.max_time_s / sim.sample_period_s > 1e6 {
            return Err(ArmError::Invalid(
                "sim.max_time_s / sim.sample_period_s exceeds a million samples".into(),
            ));
        }
        let hand = HandMotion::new(&scene.hand, seed)?;
        let start = DVec3::from_array(scene.start);
        let goal = DVec3::from_array(scene.goal);
        let sh = model.shoulder();
        for (what, p) in [("start", start), ("goal", goal)] {
            if !p.is_finite() {
                return Err(ArmError::NotFinite(what.into()));
            }
            let d = (p - sh).length();
            if d > model.reach() {
                return Err(ArmError::OutOfReach {
                    what: what.into(),
                    target: p.to_array(),
                    distance: d,
                    reach: model.reach(),
                });
            }
        }
        // A goal the hand covers at the start or once its motion is over
        // cannot be reached; a start inside the hand is a collision.
        let mut goal_checks = vec![0.0];
        if hand.end_time().is_finite() {
            goal_checks.push(hand.end_time());
        }
        for t in goal_checks {
            for (i, o) in hand.obstacles_at(t).iter().enumerate() {
                if o.point_distance(goal) <= 0.0 {
                    return Err(ArmError::InsideObstacle {
                        what: "goal".into(),
                        target: goal.to_array(),
                        obstacle: format!("{} at t = {t:.1} s", ["hand", "forearm"][i]),
                    });
                }
            }
        }
        for (i, o) in hand.obstacles_at(0.0).iter().enumerate() {
            if o.point_distance(start) <= 0.0 {
                return Err(ArmError::InsideObstacle {
                    what: "start".into(),
                    target: start.to_array(),
                    obstacle: ["hand", "forearm"][i].into(),
                });
            }
        }
        let mut q = match &scene.start_q {
            Some(q) => {
                model.check_q(q)?;
                q.clone()
            }
            None => model.home().to_vec(),
        };
        let deep = IkConfig {
            max_iters: scene.ik.max_iters.max(400),
            ..scene.ik
        };
        let r = model.ik_solve(&mut q, start, &deep);
        if !r.converged {
            return Err(ArmError::IkFailed {
                what: "start".into(),
                target: scene.start,
                error_m: r.error_m,
            });
        }
        let mut q_goal = q.clone();
        let r = model.ik_solve(&mut q_goal, goal, &deep);
        if !r.converged {
            return Err(ArmError::IkFailed {
                what: "goal".into(),
                target: scene.goal,
                error_m: r.error_m,
            });
        }
        let radii = model.link_radii();
        let links = link_capsules(&model.fk(&q), &radii);
        let d0 = min_distance(&links, &hand.obstacles_at(0.0)).map_or(f64::INFINITY, |d| d.0);
        if d0 <= 0.0 {
            return Err(ArmError::InsideObstacle {
                what: "start posture".into(),
                target: scene.start,
                obstacle: "hand or forearm".into(),
            });
        }
        let apf = Apf::<DVec3>::new(scene.apf).map_err(|e| ArmError::Invalid(e.to_string()))?;
        let per_plan = ((sim.plan_period_s / sim.sample_period_s).round() as u64).max(1);
        let tool = model.tool_position(&q);
        Ok(ArmEpisode {
            per_plan,
            dt: sim.sample_period_s,
            tick: 0,
            q_from: q.clone(),
            q_to: q.clone(),
            q,
            path: vec![tool],
            hand_path: vec![hand.hand_at(0.0)],
            last_step: None,
            min_dist: d0,
            refusals: 0,
            dist_now: d0,
            outcome: Outcome::Running,
            end_time: 0.0,
            best_goal_dist: (tool - goal).length(),
            best_at: 0.0,
            radii,
            hand,
            apf,
            model,
            scene,
        })
    }

    /// Moves the goal during the episode (the page's target drag): checked
    /// like at the start (reach, inside the hand now or at rest, IK from
    /// the current posture). A finished episode resumes.
    pub fn set_goal(&mut self, goal: [f64; 3]) -> Result<(), ArmError> {
        let g = DVec3::from_array(goal);
        if !g.is_finite() {
            return Err(ArmError::NotFinite("goal".into()));
        }
        let d = (g - self.model.shoulder()).length();
        if d > self.model.reach() {
            return Err(ArmError::OutOfReach {
                what: "goal".into(),
                target: goal,
                distance: d,
                reach: self.model.reach(),
            });
        }
        let mut times = vec![self.time()];
        if self.hand.end_time().is_finite() {
            times.push(self.hand.end_time().max(self.time()));
        }
        for t in times {
            for (i, o) in self.hand.obstacles_at(t).iter().enumerate() {
                if o.point_distance(g) <= 0.0 {
                    return Err(ArmError::InsideObstacle {
                        what: "goal".into(),
                        target: goal,
                        obstacle: format!("{} at t = {t:.1} s", ["hand", "forearm"][i]),
                    });
                }
            }
        }
        let mut q = self.q.clone();
        let deep = IkConfig {
            max_iters: self.scene.ik.max_iters.max(400),
            ..self.scene.ik
        };
        let r = self.model.ik_solve(&mut q, g, &deep);
        if !r.converged {
            return Err(ArmError::IkFailed {
                what: "goal".into(),
                target: goal,
                error_m: r.error_m,
            });
        }
        self.scene.goal = goal;
        if matches!(
            self.outcome,
            Outcome::Reached | Outcome::Stuck | Outcome::Timeout
        ) {
            self.outcome = Outcome::Running;
        }
        self.best_goal_dist = (self.model.tool_position(&self.q) - g).length();
        self.best_at = self.time();
        Ok(())
    }

    /// Switches the predictor during the episode (the APF is rebuilt; the
    /// hand's track starts afresh).
    pub fn set_predictor(&mut self, p: ArmPredictor) -> Result<(), ArmError> {
        let mut cfg = self.scene.apf;
        p.apply(&mut cfg);
        self.apf = Apf::<DVec3>::new(cfg).map_err(|e| ArmError::Invalid(e.to_string()))?;
        self.scene.apf = cfg;
        Ok(())
    }

    /// Time now, s.
    pub fn time(&self) -> f64 {
        self.tick as f64 * self.dt
    }

    /// The hand obstacles as the APF sees them: the hand sphere (id 0) and
    /// the forearm as three spheres along its axis (ids 1–3), each with its
    /// measured velocity.
    fn observed(&self, t: f64) -> Vec<ObstacleObs<DVec3>> {
        let h = 1e-3;
        let now = self.hand.obstacles_at(t);
        let (a, b) = (self.hand.obstacles_at(t - h), self.hand.obstacles_at(t + h));
        let spheres = |o: &[Obstacle3; 2]| -> Vec<(DVec3, f64)> {
            let mut v = Vec::with_capacity(4);
            if let Obstacle3::Sphere { centre, radius } = o[0] {
                v.push((DVec3::from_array(centre), radius));
            }
            if let Obstacle3::Capsule { a, b, radius } = o[1] {
                let (a, b) = (DVec3::from_array(a), DVec3::from_array(b));
                for k in 0..3 {
                    let f = (k as f64 + 0.5) / 3.0;
                    v.push((a + (b - a) * f, radius));
                }
            }
            v
        };
        let (sn, sa, sb) = (spheres(&now), spheres(&a), spheres(&b));
        sn.iter()
            .zip(sa.iter().zip(&sb))
            .enumerate()
            .map(|(i, (&(c, r), (&(ca, _), &(cb, _))))| {
                ObstacleObs::moving(i as u32, c, r, (cb - ca) / (2.0 * h))
            })
            .collect()
    }

    /// Whether moving the joints linearly from the current configuration to
    /// `q_to` brings any link into contact with `obstacles` (checked at
    /// [`MOTION_CHECKS`] points along the move, the end included) or ends
    /// it nearer than [`ARM_CLEARANCE_M`] and nearer than now.
    fn motion_touches(&self, q_to: &[f64], obstacles: &[Obstacle3; 2]) -> bool {
        let dist = |q: &[f64]| {
            let links = link_capsules(&self.model.fk(q), &self.radii);
            min_distance(&links, obstacles).map_or(f64::INFINITY, |(d, _)| d)
        };
        let now = dist(&self.q);
        let mut q = self.q.clone();
        (1..=MOTION_CHECKS).any(|k| {
            let f = k as f64 / MOTION_CHECKS as f64;
            for (qi, (a, b)) in q.iter_mut().zip(self.q.iter().zip(q_to)) {
                *qi = a + (b - a) * f;
            }
            let d = dist(&q);
            d <= 0.0 || (k == MOTION_CHECKS && d < ARM_CLEARANCE_M && d < now)
        })
    }

    /// Planned moves the whole-arm check refused so far (another
    /// candidate was taken, or the arm held).
    pub fn refusals(&self) -> u32 {
        self.refusals
    }

    /// Advances one sample period (plans at the start of each planning
    /// period). Returns the outcome (`Running` until the end).
    pub fn step(&mut self) -> Result<Outcome, ArmError> {
        if self.outcome != Outcome::Running {
            return Ok(self.outcome);
        }
        let t = self.time();
        let goal = DVec3::from_array(self.scene.goal);
        let obs = self.observed(t);
        let phase = self.tick % self.per_plan;
        if phase == 0 {
            let tool = self.model.tool_position(&self.q);
            let mut s = self
                .apf
                .step(t, tool, goal, &obs)
                .map_err(|e| ArmError::Invalid(e.to_string()))?;
            let mut q_to = self.q.clone();
            // The IK result is used even when it falls short (a joint
            // limit): the next step plans from where the tool really is.
            self.model.ik_solve(&mut q_to, s.next, &self.scene.ik);
            // The APF plans the tool only; the other links follow by IK and
            // can swing into the hand. A move that would touch the hand
            // where it is now is not taken: the next sampled candidate by
            // cost whose move is free is, and with none the arm holds (a
            // protective stop) and plans again next period.
            let hand_now = self.hand.obstacles_at(t);
            if self.motion_touches(&q_to, &hand_now) {
                self.refusals += 1;
                let mut order: Vec<usize> = (0..s.candidates.len())
                    .filter(|&i| Some(i) != s.chosen)
                    .collect();
                order.sort_by(|&a, &b| s.candidates[a].cost.total_cmp(&s.candidates[b].cost));
                let free = order.into_iter().find_map(|i| {
                    let mut q = self.q.clone();
                    self.model
                        .ik_solve(&mut q, s.candidates[i].point, &self.scene.ik);
                    (!self.motion_touches(&q, &hand_now)).then_some((i, q))
                });
                // The step kept (and drawn on the page) is the one taken.
                match free {
                    Some((i, q)) => {
                        s.chosen = Some(i);
                        s.next = s.candidates[i].point;
                        s.direction = s.candidates[i].direction;
                        q_to = q;
                    }
                    None => {
                        s.chosen = None;
                        s.next = tool;
                        s.direction = DVec3::ZERO;
                        q_to = self.q.clone();
                    }
                }
            }
            self.q_from = self.q.clone();
            self.q_to = q_to;
            self.last_step = Some(s);
        } else {
            self.apf.observe(t, &obs);
        }
        // Joints move linearly from q_from to q_to over the period.
        self.tick += 1;
        let f = (phase + 1) as f64 / self.per_plan as f64;
        for i in 0..self.q.len() {
            self.q[i] = self.q_from[i] + (self.q_to[i] - self.q_from[i]) * f;
        }
        let t = self.time();
        let hand_obs = self.hand.obstacles_at(t);
        self.hand_path.push(self.hand.hand_at(t));
        let links = link_capsules(&self.model.fk(&self.q), &self.radii);
        let d = min_distance(&links, &hand_obs).map_or(f64::INFINITY, |d| d.0);
        self.dist_now = d;
        self.min_dist = self.min_dist.min(d);
        let tool = self.model.tool_position(&self.q);
        if phase + 1 == self.per_plan {
            self.path.push(tool);
        }
        let to_goal = (tool - goal).length();
        if to_goal < self.best_goal_dist - 0.01 {
            self.best_goal_dist = to_goal;
            self.best_at = t;
        }
        let sim = &self.scene.sim;
        self.outcome = if d <= 0.0 {
            Outcome::Collision
        } else if phase + 1 == self.per_plan && to_goal <= sim.goal_tolerance_m {
            Outcome::Reached
        } else if t >= sim.max_time_s - 1e-9 {
            Outcome::Timeout
        } else if t - self.best_at >= sim.stuck_time_s {
            Outcome::Stuck
        } else {
            Outcome::Running
        };
        if self.outcome != Outcome::Running {
            self.end_time = t;
            if phase + 1 != self.per_plan {
                self.path.push(tool);
            }
        }
        Ok(self.outcome)
    }

    /// Steps to the end.
    pub fn run(&mut self) -> Result<Outcome, ArmError> {
        while self.outcome == Outcome::Running {
            self.step()?;
        }
        Ok(self.outcome)
    }

    /// The metrics so far (final after [`ArmEpisode::run`]).
    pub fn metrics(&self) -> ArmMetrics {
        let time_s = if self.outcome == Outcome::Running {
            self.time()
        } else {
            self.end_time
        };
        // Spikes: path points turning more than 30° (docs/algorithms.md §metrics).
        ApfMetrics::of_path(&self.path, self.outcome, self.min_dist, time_s)
    }

    /// How it stands.
    pub fn outcome(&self) -> Outcome {
        self.outcome
    }

    /// The arm.
    pub fn model(&self) -> &ArmModel {
        &self.model
    }

    /// The scene.
    pub fn scene(&self) -> &ArmScene {
        &self.scene
    }

    /// The hand motion.
    pub fn hand(&self) -> &HandMotion {
        &self.hand
    }

    /// Joint angles now, rad.
    pub fn q(&self) -> &[f64] {
        &self.q
    }

    /// Link capsules now.
    pub fn links(&self) -> Vec<LinkCapsule> {
        link_capsules(&self.model.fk(&self.q), &self.radii)
    }

    /// The tool's path (planning instants), m.
    pub fn tool_path(&self) -> &[DVec3] {
        &self.path
    }

    /// The hand centre at every sample so far, m.
    pub fn hand_path(&self) -> &[DVec3] {
        &self.hand_path
    }

    /// The hand and forearm now.
    pub fn hand_obstacles(&self) -> [Obstacle3; 2] {
        self.hand.obstacles_at(self.time())
    }

    /// The last planning step (forces, candidates, predictions).
    pub fn last_step(&self) -> Option<&ApfStep<DVec3>> {
        self.last_step.as_ref()
    }

    /// Link-to-hand distance now, m.
    pub fn distance_now(&self) -> f64 {
        self.dist_now
    }

    /// Distance from the gripper (the last link capsule) to the hand and
    /// forearm now, m; the whole arm's distance is
    /// [`ArmEpisode::distance_now`].
    pub fn gripper_distance_now(&self) -> f64 {
        let links = self.links();
        let obs = self.hand_obstacles();
        links.last().map_or(f64::INFINITY, |l| {
            obs.iter()
                .map(|o| link_distance(l, o))
                .fold(f64::INFINITY, f64::min)
        })
    }

    /// Smallest link-to-hand distance so far, m.
    pub fn min_distance(&self) -> f64 {
        self.min_dist
    }
}
