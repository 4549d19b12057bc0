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

use crate::params::{check_param, Bound, ParamError, Params};

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

impl From<ParamError> for ApfError {
    fn from(e: ParamError) -> Self {
        ApfError::InvalidParameter(e.to_string())
    }
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

crate::params::params! {
    /// Settings of the potential field and its step. Defaults: the thesis's
    /// values where it gives them (α, β, 15°/±90°, 0.75, 0.75·F / 0.5·F, step
    /// 0.04 m); gains and ranges (not given) chosen for its ~1 m scenes.
    #[derive(Debug, Clone, Copy, PartialEq)]
    pub struct ApfConfig {
        pub mode: ApfMode = ApfMode::SamplingPrediction, "" []
            label "method" "basic | sampling | sampling-prediction";
        /// Force units per m.
        pub k_a: f64 = 5.0, "1/m" [> 0.0] label "attraction gain k_a" "attraction gain k_a (eq 4-1)";
        pub rho: f64 = 1.0, "m" [> 0.0] label "attraction switch distance ρ" "quadratic attraction within ρ of the goal, conic beyond";
        /// Force units·m³.
        pub k_r: f64 = 0.002, "m³" [>= 0.0] label "repulsion gain k_r" "repulsion gain k_r (eq 4-3)";
        pub p0: f64 = 0.15, "m" [> 0.0] label "repulsion range p₀" "repulsion range p₀ beyond an obstacle's surface";
        /// \[T\] §5.3.3.
        pub step: f64 = 0.04, "m" [> 0.0] label "step length d" "step length d per planning step";
        /// Eq 4-5.
        pub alpha: f64 = 0.3, "1" [>= 0.0] label "attraction weight α" "attraction weight α of the sampling cost";
        /// Eq 4-5.
        pub beta: f64 = 0.7, "1" [>= 0.0] label "repulsion weight β" "repulsion weight β of the sampling cost";
        /// Sampling modes only.
        pub relative_distance: bool = true, "" []
            label "relative distance rule" "β = 0 while the goal is nearer than every obstacle (§4.2.2)";
        pub sample_step: f64 = 15f64.to_radians(), "rad" [> 0.0]
            label "sampling step" "spacing of the sampled directions (15°)";
        /// From the resultant; at most π.
        pub sample_half_range: f64 = 90f64.to_radians(), "rad" [>= 0.0]
            label "sampling half-range" "largest sampled deviation (90°)";
        /// Instead of the vertical plane of the force (beyond the thesis).
        pub hemisphere: bool = false, "" [] label "whole hemisphere (3D)" "3D: sample the whole hemisphere";
        /// Prediction mode only.
        pub predictor: predict::PredictorKind = predict::PredictorKind::ConstantVelocity, "" []
            label "obstacle motion predictor" "constant-velocity | rnn";
        pub predict_dt: f64 = 0.5, "s" [> 0.0] label "prediction step" "time to t+1 and between t+1 and t+2";
        pub predict_scale: f64 = 0.75, "1" [> 0.0] label "prediction range scale s" "virtual range scale s (t+1) and s² (t+2)";
        /// 0.75 at t+1, 0.5 at t+2.
        pub predict_gains: [f64; 2] = [0.75, 0.5], "1" []
            label "prediction gains" "virtual repulsion at the predicted centre / attraction (t+1, t+2)";
        /// They stay plain obstacles.
        pub predict_min_motion: f64 = 0.005, "m" [>= 0.0]
            label "least predicted motion" "no virtual copies for obstacles predicted to move less";
        /// 0 = a point.
        pub robot_radius: f64 = 0.0, "m" [>= 0.0] label "robot radius" "robot radius; distances to its surface";
        /// The exact local minimum of \[T\] Fig 4-1; force units.
        pub stall_force: f64 = 1e-9, "1" [>= 0.0] label "stall force" "basic APF stands still below this resultant";
    }
}

impl ApfConfig {
    /// Checks every number; the error names the field.
    pub fn validate(&self) -> Result<(), ApfError> {
        self.check_bounds("apf")?;
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
        for (i, &g) in self.predict_gains.iter().enumerate() {
            check_param(&format!("apf.predict_gains[{i}]"), g, Bound::at_least(0.0))?;
        }
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
