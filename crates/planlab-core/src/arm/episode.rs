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
use super::rrt::{self, ArmChecker, RrtConfig};
use super::ArmError;
use crate::apf::{Apf, ApfConfig, ApfMetrics, ApfMode, ApfStep, ObstacleObs, PredictorKind};
use crate::num::Rng;
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

/// Random IK starts RRT-Connect tries for a free goal posture when the
/// hand blocks the one it had.
pub const GOAL_POSTURE_TRIES: usize = 20;

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

/// Smallest distance from `links` to the table top at `z` (infinite
/// without one), m.
fn table_distance(links: &[LinkCapsule], z: Option<f64>) -> f64 {
    z.map_or(f64::INFINITY, |z| {
        links
            .iter()
            .map(|l| (l.a.z.min(l.b.z) - l.radius - z).max(0.0))
            .fold(f64::INFINITY, f64::min)
    })
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

/// Which planner moves the arm.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum ArmPlanner {
    /// The thesis's end-effector APF (with the scene's predictor), one
    /// 0.04 m tool step per planning period, joints by IK.
    #[default]
    Apf,
    /// RRT-Connect in joint space with shortcutting ([`super::rrt`]),
    /// replanned when the hand (and its prediction) blocks the path.
    RrtConnect,
}

impl ArmPlanner {
    /// Every choice, in the page's order.
    pub const ALL: [ArmPlanner; 2] = [ArmPlanner::Apf, ArmPlanner::RrtConnect];

    /// The kebab-case name.
    pub fn name(self) -> &'static str {
        match self {
            ArmPlanner::Apf => "apf",
            ArmPlanner::RrtConnect => "rrt-connect",
        }
    }

    /// Parses a kebab-case name.
    pub fn parse(s: &str) -> Result<ArmPlanner, ArmError> {
        match s {
            "apf" => Ok(ArmPlanner::Apf),
            "rrt-connect" => Ok(ArmPlanner::RrtConnect),
            _ => Err(ArmError::Invalid(format!(
                "unknown arm planner `{s}`: use apf or rrt-connect"
            ))),
        }
    }

    fn is_apf(&self) -> bool {
        *self == ArmPlanner::Apf
    }
}

fn is_default_rrt(c: &RrtConfig) -> bool {
    *c == RrtConfig::default()
}

/// Planning effort of an episode (the core has no clock: effort is counted).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct PlanEffort {
    /// Plans made: APF steps, or RRT-Connect runs (the first and every
    /// replan).
    pub plans: u32,
    /// RRT-Connect runs after the first (the path was blocked).
    pub replans: u32,
    /// RRT-Connect runs that found no path (the arm held).
    pub failed_plans: u32,
    /// Planning instants at which the predicted hand reached the arm's
    /// posture, so the arm stopped instead of planning.
    pub holds: u32,
    /// Planner iterations: one per APF step, RRT-Connect's outer
    /// iterations (one sample each) summed over its runs.
    pub iterations: u64,
    /// Whole-arm postures checked for collision (the APF's move checks;
    /// RRT-Connect's tree edges, shortcuts and path checks).
    pub collision_checks: u64,
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
    /// Which planner moves the arm (default `apf`).
    #[serde(default, skip_serializing_if = "ArmPlanner::is_apf")]
    pub planner: ArmPlanner,
    /// RRT-Connect settings (with `planner: rrt-connect`).
    #[serde(default, skip_serializing_if = "is_default_rrt")]
    pub rrt: RrtConfig,
    /// Height of the table top, m: RRT-Connect keeps every link above it
    /// by the clearance margin; the APF does not know it (its smallest
    /// distance to it is measured).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub table_z_m: Option<f64>,
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
    /// Whole-arm postures the APF's move check looked at.
    apf_checks: std::cell::Cell<u64>,
    effort: PlanEffort,
    joint_len: f64,
    gripper_len: f64,
    min_table: f64,
    rrt: Option<RrtRun>,
}

/// The joint-space planner's state in an episode.
#[derive(Debug, Clone)]
struct RrtRun {
    cfg: RrtConfig,
    q_goal: Vec<f64>,
    /// Postures still ahead (the current one excluded).
    ahead: Vec<Vec<f64>>,
    rng: Rng,
    /// Predicted hand centres planned against, with k (1 = t+1, 2 = t+2).
    predicted: Vec<(DVec3, u8)>,
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
        scene.rrt.validate()?;
        if let Some(z) = scene.table_z_m {
            if !z.is_finite() {
                return Err(ArmError::NotFinite("table_z_m".into()));
            }
        }
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
        let rrt = match scene.planner {
            ArmPlanner::Apf => None,
            ArmPlanner::RrtConnect => {
                // The table and the arm itself are fixed: a start or goal
                // posture they block is bad input, not a moment to wait.
                let mut c = ArmChecker::new(
                    &model,
                    vec![],
                    scene.table_z_m,
                    ARM_CLEARANCE_M,
                    scene.rrt.check_sweep_m,
                );
                for (what, q) in [("start posture", &q), ("goal posture", &q_goal)] {
                    let d = c.clearance(q);
                    if d < ARM_CLEARANCE_M {
                        return Err(ArmError::PostureBlocked {
                            what: what.into(),
                            clearance_m: d,
                            margin_m: ARM_CLEARANCE_M,
                        });
                    }
                }
                Some(RrtRun {
                    cfg: scene.rrt,
                    q_goal: q_goal.clone(),
                    ahead: Vec::new(),
                    rng: Rng::new(seed ^ 0x5252_5443), // "RRTC"
                    predicted: Vec::new(),
                })
            }
        };
        let min_table = table_distance(&links, scene.table_z_m);
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
            apf_checks: std::cell::Cell::new(0),
            effort: PlanEffort::default(),
            joint_len: 0.0,
            gripper_len: 0.0,
            min_table,
            rrt,
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
        if let Some(r) = &mut self.rrt {
            r.q_goal = q;
            r.ahead.clear();
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
            self.apf_checks.set(self.apf_checks.get() + 1);
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

    /// RRT-Connect at a planning instant: the hand now and, with a
    /// predictor, its sweep through its predicted places at t+1 and t+2
    /// (capsules of the hand's radius, the forearm at each place) are the
    /// obstacles; the path still ahead is checked against them and, when
    /// blocked (or at the start), planned afresh from the current posture.
    /// With no path found, or the predicted hand on the arm's posture, the
    /// arm holds and tries again next period.
    fn rrt_plan(&mut self, t: f64, obs: &[ObstacleObs<DVec3>]) {
        let Some(mut run) = self.rrt.take() else {
            return;
        };
        let hand_now = self.hand.obstacles_at(t);
        let links = self.links();
        let mut obstacles = hand_now.to_vec();
        let mut reaches_arm = false;
        run.predicted.clear();
        if ArmPredictor::of(&self.scene.apf) != ArmPredictor::None {
            // The hand sweeps from where it is through its predicted
            // places: each stretch is a capsule of the hand's radius, and
            // the forearm is added at each predicted place.
            let mut prev = self.hand.hand_at(t);
            let mut preds: Vec<_> = self
                .apf
                .predictions(obs)
                .into_iter()
                .filter(|v| v.id == 0)
                .collect();
            preds.sort_by_key(|v| v.k);
            for v in preds {
                let [hand, forearm] = self.hand.obstacles_for(v.centre);
                let swept = Obstacle3::Capsule {
                    a: prev.to_array(),
                    b: v.centre.to_array(),
                    radius: self.hand.spec.hand_radius_m,
                };
                let pred = [swept, hand, forearm];
                prev = v.centre;
                reaches_arm |= rrt::clearance_of(&links, &pred, None) < ARM_CLEARANCE_M;
                obstacles.extend(pred);
                run.predicted.push((v.centre, v.k));
            }
        }
        if reaches_arm {
            // The hand is predicted to come onto the arm where it is: no
            // path from here avoids that, so the arm stops (a protective
            // stop, as the APF holds) and plans again next period.
            self.effort.holds += 1;
            run.ahead.clear();
            self.rrt = Some(run);
            return;
        }
        let mut c = ArmChecker::new(
            &self.model,
            obstacles,
            self.scene.table_z_m,
            ARM_CLEARANCE_M,
            run.cfg.check_sweep_m,
        );
        // An arm the hand came nearer than the margin plans with half its
        // clearance as the margin (and checks finely enough for it), so it
        // can still move away.
        let root = c.clearance(&self.q);
        if root < ARM_CLEARANCE_M {
            let m = 0.5 * root;
            c = ArmChecker::new(
                &self.model,
                c.obstacles().to_vec(),
                self.scene.table_z_m,
                m,
                run.cfg.check_sweep_m.min(2.0 * m),
            );
        }
        let at_goal = run
            .q_goal
            .iter()
            .zip(&self.q)
            .all(|(a, b)| (a - b).abs() < 1e-12);
        let mut path = vec![self.q.clone()];
        path.extend(run.ahead.iter().cloned());
        let blocked = if run.ahead.is_empty() {
            !at_goal
        } else {
            !c.path_valid(&path)
        };
        if blocked {
            if self.effort.plans > 0 {
                self.effort.replans += 1;
            }
            self.effort.plans += 1;
            run.ahead.clear();
            // The goal posture the hand now blocks is replaced by another
            // IK solution for the same tool point, as MoveIt samples goal
            // states: from the current posture, then from seeded random
            // ones.
            if c.margin() > 1e-4 && !c.valid(&run.q_goal) {
                if let Some(q) = self.free_goal_posture(&mut c, &mut run.rng) {
                    run.q_goal = q;
                }
            }
            if c.margin() > 1e-4 {
                match rrt::rrt_connect(&mut c, &self.q, &run.q_goal, &run.cfg, &mut run.rng) {
                    Ok(plan) => {
                        self.effort.iterations += u64::from(plan.iterations);
                        let short = rrt::shortcut(
                            &mut c,
                            &plan.path,
                            run.cfg.shortcut_attempts,
                            &mut run.rng,
                        );
                        run.ahead = short[1..].to_vec();
                    }
                    Err(e) => {
                        if let ArmError::NoPath { iterations } = e {
                            self.effort.iterations += u64::from(iterations);
                        }
                        self.effort.failed_plans += 1;
                    }
                }
            } else {
                self.effort.failed_plans += 1;
            }
        }
        self.effort.collision_checks += c.checks();
        self.rrt = Some(run);
    }

    /// An IK posture putting the tool on the goal that `c` finds valid:
    /// IK from the current posture, then from up to
    /// [`GOAL_POSTURE_TRIES`] seeded random postures.
    fn free_goal_posture(&self, c: &mut ArmChecker<'_>, rng: &mut Rng) -> Option<Vec<f64>> {
        let goal = DVec3::from_array(self.scene.goal);
        let deep = IkConfig {
            max_iters: self.scene.ik.max_iters.max(400),
            ..self.scene.ik
        };
        let tol = self.scene.sim.goal_tolerance_m;
        for k in 0..=GOAL_POSTURE_TRIES {
            let mut q = if k == 0 {
                self.q.clone()
            } else {
                (0..self.model.dof())
                    .map(|i| {
                        let (lo, hi) = self.model.limits(i);
                        rng.range(lo, hi)
                    })
                    .collect()
            };
            let r = self.model.ik_solve(&mut q, goal, &deep);
            if r.error_m <= tol && c.valid(&q) {
                return Some(q);
            }
        }
        None
    }

    /// Moves the joints along the path ahead for one sample period, no
    /// joint faster than the speed limit (the postures are followed in
    /// order, the largest joint change setting the pace).
    fn rrt_advance(&mut self) {
        let Some(run) = &mut self.rrt else {
            return;
        };
        let mut budget = run.cfg.max_joint_speed_rad_s * self.dt;
        while budget > 0.0 && !run.ahead.is_empty() {
            let next = &run.ahead[0];
            let largest = next
                .iter()
                .zip(&self.q)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            if largest <= budget {
                self.q.clone_from(next);
                budget -= largest;
                run.ahead.remove(0);
            } else {
                let f = budget / largest;
                for (qi, n) in self.q.iter_mut().zip(next) {
                    *qi += (n - *qi) * f;
                }
                budget = 0.0;
            }
        }
    }

    /// The planner moving the arm.
    pub fn planner(&self) -> ArmPlanner {
        self.scene.planner
    }

    /// Planning effort so far.
    pub fn effort(&self) -> PlanEffort {
        self.effort
    }

    /// Joint-space distance travelled so far (Euclidean, sample by
    /// sample), rad.
    pub fn joint_path_length(&self) -> f64 {
        self.joint_len
    }

    /// Distance the tool point travelled so far, sample by sample (0.1 s;
    /// the metrics' `path_length_m` joins the planning instants only), m.
    pub fn gripper_path_length(&self) -> f64 {
        self.gripper_len
    }

    /// Smallest distance from any link to the table top so far (infinite
    /// without a table), m.
    pub fn min_table_distance(&self) -> f64 {
        self.min_table
    }

    /// RRT-Connect's postures still ahead, from the current one (empty
    /// with the APF or while holding).
    pub fn planned_path(&self) -> Vec<Vec<f64>> {
        match &self.rrt {
            Some(r) if !r.ahead.is_empty() => {
                let mut p = vec![self.q.clone()];
                p.extend(r.ahead.iter().cloned());
                p
            }
            _ => Vec::new(),
        }
    }

    /// The tool point along [`ArmEpisode::planned_path`], each straight
    /// joint move sampled at 8 points, m.
    pub fn planned_tool_path(&self) -> Vec<DVec3> {
        let p = self.planned_path();
        let mut out = Vec::new();
        if let Some(first) = p.first() {
            out.push(self.model.tool_position(first));
        }
        for w in p.windows(2) {
            for k in 1..=8 {
                let f = k as f64 / 8.0;
                let q: Vec<f64> = w[0]
                    .iter()
                    .zip(&w[1])
                    .map(|(a, b)| a + (b - a) * f)
                    .collect();
                out.push(self.model.tool_position(&q));
            }
        }
        out
    }

    /// The predicted hand centres RRT-Connect last planned or checked
    /// against, with k (1 = t+1, 2 = t+2).
    pub fn rrt_predicted(&self) -> &[(DVec3, u8)] {
        self.rrt.as_ref().map_or(&[], |r| &r.predicted)
    }

    /// The goal posture RRT-Connect plans to (`None` with the APF).
    pub fn goal_posture(&self) -> Option<&[f64]> {
        self.rrt.as_ref().map(|r| r.q_goal.as_slice())
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
        let q_before = self.q.clone();
        let tool_before = self.model.tool_position(&self.q);
        if self.rrt.is_some() {
            self.apf.observe(t, &obs);
            if phase == 0 {
                self.rrt_plan(t, &obs);
            }
            self.rrt_advance();
        } else if phase == 0 {
            self.effort.plans += 1;
            self.effort.iterations += 1;
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
            self.effort.collision_checks = self.apf_checks.get();
        } else {
            self.apf.observe(t, &obs);
        }
        self.tick += 1;
        if self.rrt.is_none() {
            // Joints move linearly from q_from to q_to over the period.
            let f = (phase + 1) as f64 / self.per_plan as f64;
            for i in 0..self.q.len() {
                self.q[i] = self.q_from[i] + (self.q_to[i] - self.q_from[i]) * f;
            }
        }
        self.joint_len += q_before
            .iter()
            .zip(&self.q)
            .map(|(a, b)| (b - a) * (b - a))
            .sum::<f64>()
            .sqrt();
        let t = self.time();
        let hand_obs = self.hand.obstacles_at(t);
        self.hand_path.push(self.hand.hand_at(t));
        let links = link_capsules(&self.model.fk(&self.q), &self.radii);
        let d = min_distance(&links, &hand_obs).map_or(f64::INFINITY, |d| d.0);
        self.dist_now = d;
        self.min_dist = self.min_dist.min(d);
        self.min_table = self
            .min_table
            .min(table_distance(&links, self.scene.table_z_m));
        let tool = self.model.tool_position(&self.q);
        self.gripper_len += (tool - tool_before).length();
        let rrt_done = self.rrt.as_ref().is_some_and(|r| r.ahead.is_empty());
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
        } else if (phase + 1 == self.per_plan || rrt_done) && to_goal <= sim.goal_tolerance_m {
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
