//! A 7-DOF arm beside a moving human hand (docs/algorithms.md §arm, \[T\] §2.4 and
//! §5.3.3).
//!
//! - [`model`]: the URDF-style arm file (`assets/arm/tiago.json`), parsed
//!   with typed errors.
//! - [`kinematics`]: forward kinematics of every joint frame, the positional
//!   Jacobian, damped-least-squares IK with joint limits.
//! - [`geometry`]: links as capsules, distance and collision against sphere
//!   and capsule obstacles (parry3d).
//! - [`hand`]: the moving hand and forearm with scripted reaching motions.
//! - [`rrt`]: RRT-Connect in joint space and path shortcutting, the
//!   alternative arm planner (docs/algorithms.md §arm-rrt).
//! - [`episode`]: the end effector planned by the 3D APF of [`crate::apf`]
//!   among the moving hand, followed by IK; the `arm` section of an arm
//!   scenario (the file is [`crate::scenario::ArmScenario`]) and metrics.

pub mod episode;
pub mod geometry;
pub mod hand;
pub mod kinematics;
pub mod model;
pub mod rrt;

pub use episode::{
    ArmEpisode, ArmMetrics, ArmPlanner, ArmPredictor, ArmScene, ArmSimConfig, PlanEffort,
};
pub use geometry::{link_capsules, min_distance, LinkCapsule, Obstacle3};
pub use hand::{HandMotion, HandPreset, HandSpec};
pub use kinematics::{Frames, IkConfig, IkReport};
pub use model::{ArmModel, ArmSpec, Frame, JointSpec};
pub use rrt::{rrt_connect, shortcut, ArmChecker, RrtConfig, RrtPlan};

use thiserror::Error;

/// Why an arm file, arm scenario or arm target is unusable.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum ArmError {
    /// Malformed JSON, a wrong type, a missing or unknown field.
    #[error("arm JSON error: {}", crate::text::one_line(.0))]
    Json(String),
    /// The chain has no joints.
    #[error("the arm has no joints: `joints` needs at least one")]
    NoJoints,
    /// The chain has more joints than supported.
    #[error("the arm has {found} joints; at most {max} are supported")]
    TooManyJoints {
        /// Joints in the file.
        found: usize,
        /// [`model::MAX_JOINTS`].
        max: usize,
    },
    /// A number is NaN or infinite (names the field).
    #[error("{} is not a finite number", crate::text::one_line(.0))]
    NotFinite(String),
    /// A joint's lower limit exceeds its upper limit.
    #[error("joint {}: lower limit {} rad exceeds upper limit {} rad", crate::text::one_line(.joint), crate::num::fmt_num(*.min), crate::num::fmt_num(*.max))]
    LimitsInverted {
        /// Joint name.
        joint: String,
        /// Lower limit, rad.
        min: f64,
        /// Upper limit, rad.
        max: f64,
    },
    /// A joint axis has zero length.
    #[error("joint {}: the axis must not be zero", crate::text::one_line(.0))]
    ZeroAxis(String),
    /// A joint vector has the wrong number of entries.
    #[error("{what} has {found} joint values; the arm has {expected} joints")]
    WrongJointCount {
        /// What vector.
        what: String,
        /// Joints of the arm.
        expected: usize,
        /// Values given.
        found: usize,
    },
    /// A joint value lies outside its limits.
    #[error("joint {}: {} rad is outside its limits [{}, {}] rad", crate::text::one_line(.joint), crate::num::fmt_num(*.value), crate::num::fmt_num(*.min), crate::num::fmt_num(*.max))]
    OutsideLimits {
        /// Joint name.
        joint: String,
        /// The value, rad.
        value: f64,
        /// Lower limit, rad.
        min: f64,
        /// Upper limit, rad.
        max: f64,
    },
    /// A target lies beyond the arm's reach.
    #[error("{what} {target:?} is out of reach: {distance:.3} m from the shoulder, the arm reaches {reach:.3} m")]
    OutOfReach {
        /// Which target (`goal`, `start`).
        what: String,
        /// The point, m.
        target: [f64; 3],
        /// Its distance from joint 1, m.
        distance: f64,
        /// The chain's reach, m.
        reach: f64,
    },
    /// A target lies inside an obstacle.
    #[error("{what} {target:?} lies inside an obstacle ({obstacle})")]
    InsideObstacle {
        /// Which target (`goal`, `start`).
        what: String,
        /// The point, m.
        target: [f64; 3],
        /// Which obstacle.
        obstacle: String,
    },
    /// IK could not bring the tool to a target (joint limits, or a pocket
    /// of the workspace the chain cannot enter).
    #[error("{what} {target:?} cannot be reached: IK stops {error_m:.3} m away")]
    IkFailed {
        /// Which target.
        what: String,
        /// The point, m.
        target: [f64; 3],
        /// Remaining error, m.
        error_m: f64,
    },
    /// A posture given to the joint-space planner is in contact or nearer
    /// than the margin to an obstacle, the table or the arm itself.
    #[error("{what} is blocked: {clearance_m:.4} m from the hand, table or arm, the planner keeps {margin_m:.4} m")]
    PostureBlocked {
        /// Which posture (`start posture`, `goal posture`).
        what: String,
        /// Its clearance, m.
        clearance_m: f64,
        /// The margin required, m.
        margin_m: f64,
    },
    /// RRT-Connect found no path within its iterations.
    #[error("RRT-Connect found no path in {iterations} iterations")]
    NoPath {
        /// Iterations run.
        iterations: u32,
    },
    /// Any other out-of-range or inconsistent value (names the field).
    #[error("invalid arm setting: {}", crate::text::one_line(.0))]
    Invalid(String),
}

impl From<crate::params::ParamError> for ArmError {
    fn from(e: crate::params::ParamError) -> Self {
        ArmError::Invalid(e.to_string())
    }
}

#[cfg(test)]
mod tests;
