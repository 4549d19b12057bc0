//! Artificial potential fields (docs/algorithms.md §apf, \[T\] Wu 2022 ch. 4–5), in 2D and
//! 3D from one generic implementation over [`ApfVector`] (glam `DVec2` /
//! `DVec3`).
//!
//! - [`field`]: attraction eq 4-1/4-2 (quadratic within ρ of the goal,
//!   conic beyond, k_b = ρ·k_a), repulsion eq 4-3/4-4 inside p₀, and the
//!   linear virtual repulsion of predicted obstacles eq 4-13/4-14.
//! - [`planner`]: [`Apf`], one fixed-length step per call: basic (along the
//!   resultant), sampling (13 directions −90°…+90° every 15° around the
//!   resultant, in 3D in the vertical plane of the force, eq 4-6…4-12, cost
//!   α‖F_attr‖ + β‖F_rep‖), the relative distance rule (§4.2.2) and dynamic
//!   obstacle prediction at t+1 and t+2 (§4.2.3).
//! - [`predict`]: the [`Predictor`] trait, [`ConstantVelocity`]; [`rnn`]:
//!   the thesis's SimpleRNN (6 → 15 tanh → 3, §5.2) with native training.
//! - [`scene`]: a kinematic APF run of a point robot among (moving)
//!   spheres / discs, the `apf` section of a scenario, and [`ApfMetrics`].
//! - [`local`]: the 2D APF as a [`crate::local::LocalPlanner`] (`apf`,
//!   `sampling-apf`).
//!
//! ```
//! use glam::DVec2;
//! use planlab_core::apf::{Apf, ApfConfig, ApfMode, ObstacleObs};
//!
//! let cfg = ApfConfig { mode: ApfMode::Sampling, ..ApfConfig::default() };
//! let mut apf = Apf::<DVec2>::new(cfg).unwrap();
//! let obstacle = ObstacleObs::fixed(0, DVec2::new(0.5, 0.0), 0.05);
//! let mut p = DVec2::ZERO;
//! let goal = DVec2::new(1.0, 0.0);
//! for i in 0..60 {
//!     let s = apf.step(i as f64 * 0.1, p, goal, &[obstacle]).unwrap();
//!     p = s.next;
//! }
//! assert!((p - goal).length() < 0.05);
//! ```

pub mod field;
pub mod local;
pub mod planner;
pub mod predict;
pub mod rnn;
pub mod scene;
pub mod vector;

use serde::{Deserialize, Serialize};
use thiserror::Error;

pub use field::VirtualObstacle;
pub use planner::{Apf, ApfStep, Candidate, ObstacleObs, StepKind};
pub use predict::{ConstantVelocity, Predictor, PredictorKind, Track};
pub use rnn::SimpleRnn;
pub use scene::{AnyApfRun, ApfMetrics, ApfRun, ApfScene, SceneObstacle};
pub use vector::{ApfVector, Sampling};

/// Errors of the APF planners, predictors and scenes.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum ApfError {
    /// A config value is NaN, infinite or out of range; the text names it.
    #[error("invalid APF parameter: {}", crate::text::one_line(.0))]
    InvalidParameter(String),
    /// The goal lies inside an obstacle (unreachable).
    #[error("the goal {goal:?} is inside obstacle {id} (unreachable)")]
    GoalInsideObstacle {
        /// The goal's coordinates.
        goal: Vec<f64>,
        /// The obstacle's id.
        id: u32,
    },
    /// The start lies inside an obstacle.
    #[error("the start {start:?} is inside obstacle {id}")]
    StartInsideObstacle {
        /// The start's coordinates.
        start: Vec<f64>,
        /// The obstacle's id.
        id: u32,
    },
    /// A point has the wrong number of coordinates or a non-finite one.
    #[error("{what}: expected {expected} finite coordinates, got {got:?}")]
    BadPoint {
        /// Which point.
        what: String,
        /// 2 or 3.
        expected: usize,
        /// What was given.
        got: Vec<f64>,
    },
    /// Predictor weights are malformed.
    #[error("predictor weights: {}", crate::text::one_line(.0))]
    BadWeights(String),
}

/// Which APF variant steps.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum ApfMode {
    /// Basic APF: one step along the resultant (\[T\] §4.1).
    Basic,
    /// Sampling-based improved APF with the relative distance rule
    /// (§4.2.1–4.2.2).
    Sampling,
    /// Sampling APF plus dynamic obstacle prediction (§4.2.3).
    #[default]
    SamplingPrediction,
}

impl ApfMode {
    /// Short label for tables and the page.
    pub fn label(self) -> &'static str {
        match self {
            ApfMode::Basic => "basic",
            ApfMode::Sampling => "sampling",
            ApfMode::SamplingPrediction => "sampling-prediction",
        }
    }
}

/// Settings of the potential field and its step. Defaults: the thesis's
/// values where it gives them (α, β, 15°/±90°, 0.75, 0.75·F / 0.5·F, step
/// 0.04 m); gains and ranges (not given) chosen for its ~1 m scenes.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ApfConfig {
    /// Variant: `basic`, `sampling` or `sampling-prediction`.
    pub mode: ApfMode,
    /// Attraction gain k_a (eq 4-1), force units per m.
    pub k_a: f64,
    /// Radius ρ around the goal inside which attraction is quadratic, m.
    pub rho: f64,
    /// Repulsion gain k_r (eq 4-3), force units·m³.
    pub k_r: f64,
    /// Repulsion influence range p₀ beyond an obstacle's surface, m.
    pub p0: f64,
    /// Step length d per planning step (\[T\] §5.3.3), m.
    pub step: f64,
    /// Attraction weight α of the sampling cost (eq 4-5), 1.
    pub alpha: f64,
    /// Repulsion weight β of the sampling cost (eq 4-5), 1.
    pub beta: f64,
    /// Relative distance rule (§4.2.2): β = 0 while the goal is nearer than
    /// every obstacle surface (sampling modes).
    pub relative_distance: bool,
    /// Spacing of the sampled directions, rad (15°).
    pub sample_step: f64,
    /// Largest sampled deviation from the resultant, rad (90°).
    pub sample_half_range: f64,
    /// 3D only: sample the whole hemisphere around the resultant instead of
    /// its vertical plane (beyond the thesis).
    pub hemisphere: bool,
    /// Predictor of obstacle positions (prediction mode).
    pub predictor: predict::PredictorKind,
    /// Time between predicted instants t+1 and t+2 (and from now to t+1), s.
    pub predict_dt: f64,
    /// Range scale of the predicted obstacles: s at t+1, s² at t+2, 1.
    pub predict_scale: f64,
    /// Virtual repulsion at the predicted centre, as a share of the
    /// attraction there, at t+1 (0.75) and t+2 (0.5), 1.
    pub predict_gains: [f64; 2],
    /// Obstacles predicted to move less than this are not given virtual
    /// copies (still obstacles), m.
    pub predict_min_motion: f64,
    /// Radius of the robot (point = 0): distances are to its surface, m.
    pub robot_radius: f64,
    /// Basic APF does not move when the resultant is weaker than this
    /// (the exact local minimum of \[T\] Fig 4-1), force units.
    pub stall_force: f64,
}

impl Default for ApfConfig {
    fn default() -> Self {
        Self {
            mode: ApfMode::SamplingPrediction,
            k_a: 5.0,
            rho: 1.0,
            k_r: 0.002,
            p0: 0.15,
            step: 0.04,
            alpha: 0.3,
            beta: 0.7,
            relative_distance: true,
            sample_step: 15f64.to_radians(),
            sample_half_range: 90f64.to_radians(),
            hemisphere: false,
            predictor: predict::PredictorKind::ConstantVelocity,
            predict_dt: 0.5,
            predict_scale: 0.75,
            predict_gains: [0.75, 0.5],
            predict_min_motion: 0.005,
            robot_radius: 0.0,
            stall_force: 1e-9,
        }
    }
}

/// (name, unit, doc) of every [`ApfConfig`] field, for registries and the
/// page's parameter panel.
pub const APF_FIELDS: &[(&str, &str, &str)] = &[
    ("mode", "", "basic | sampling | sampling-prediction"),
    ("k_a", "1/m", "attraction gain k_a (eq 4-1)"),
    (
        "rho",
        "m",
        "quadratic attraction within ρ of the goal, conic beyond",
    ),
    ("k_r", "m³", "repulsion gain k_r (eq 4-3)"),
    ("p0", "m", "repulsion range p₀ beyond an obstacle's surface"),
    ("step", "m", "step length d per planning step"),
    ("alpha", "1", "attraction weight α of the sampling cost"),
    ("beta", "1", "repulsion weight β of the sampling cost"),
    (
        "relative_distance",
        "",
        "β = 0 while the goal is nearer than every obstacle (§4.2.2)",
    ),
    (
        "sample_step",
        "rad",
        "spacing of the sampled directions (15°)",
    ),
    (
        "sample_half_range",
        "rad",
        "largest sampled deviation (90°)",
    ),
    ("hemisphere", "", "3D: sample the whole hemisphere"),
    ("predictor", "", "constant-velocity | rnn"),
    ("predict_dt", "s", "time to t+1 and between t+1 and t+2"),
    (
        "predict_scale",
        "1",
        "virtual range scale s (t+1) and s² (t+2)",
    ),
    (
        "predict_gains",
        "1",
        "virtual repulsion at the predicted centre / attraction (t+1, t+2)",
    ),
    (
        "predict_min_motion",
        "m",
        "no virtual copies for obstacles predicted to move less",
    ),
    (
        "robot_radius",
        "m",
        "robot radius; distances to its surface",
    ),
    (
        "stall_force",
        "1",
        "basic APF stands still below this resultant",
    ),
];

impl ApfConfig {
    /// Checks every number; the error names the field.
    pub fn validate(&self) -> Result<(), ApfError> {
        let check = |name: &str, v: f64, min: f64, strict: bool| {
            let ok = v.is_finite() && if strict { v > min } else { v >= min };
            if ok {
                Ok(())
            } else {
                let rel = if strict { ">" } else { "≥" };
                Err(ApfError::InvalidParameter(format!(
                    "apf.{name} = {v}: must be a finite number {rel} {min}"
                )))
            }
        };
        check("k_a", self.k_a, 0.0, true)?;
        check("rho", self.rho, 0.0, true)?;
        check("k_r", self.k_r, 0.0, false)?;
        check("p0", self.p0, 0.0, true)?;
        check("step", self.step, 0.0, true)?;
        check("alpha", self.alpha, 0.0, false)?;
        check("beta", self.beta, 0.0, false)?;
        check("sample_step", self.sample_step, 0.0, true)?;
        check("sample_half_range", self.sample_half_range, 0.0, false)?;
        if self.sample_half_range > std::f64::consts::PI + 1e-12 {
            return Err(ApfError::InvalidParameter(format!(
                "apf.sample_half_range = {}: must be ≤ π",
                self.sample_half_range
            )));
        }
        if self.sample_half_range / self.sample_step > 1000.0 {
            return Err(ApfError::InvalidParameter(format!(
                "apf.sample_step = {}: more than 1000 directions",
                self.sample_step
            )));
        }
        check("predict_dt", self.predict_dt, 0.0, true)?;
        check("predict_scale", self.predict_scale, 0.0, true)?;
        check("predict_gains[0]", self.predict_gains[0], 0.0, false)?;
        check("predict_gains[1]", self.predict_gains[1], 0.0, false)?;
        check("predict_min_motion", self.predict_min_motion, 0.0, false)?;
        check("robot_radius", self.robot_radius, 0.0, false)?;
        check("stall_force", self.stall_force, 0.0, false)?;
        Ok(())
    }

    /// The sampling layout of this config.
    pub fn sampling(&self) -> Sampling {
        Sampling {
            step: self.sample_step,
            half_range: self.sample_half_range,
            hemisphere: self.hemisphere,
        }
    }
}
