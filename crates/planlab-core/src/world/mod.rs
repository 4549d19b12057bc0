//! The simulated world (docs/algorithms.md §robot, §movers): the robot's
//! body and kinematics, moving
//! disc obstacles with their motion models, and the static map's geometry.
//!
//! Everything here is a pure function of its inputs and of simulated time, so
//! an episode replays bit for bit (see [`crate::num`] for why trigonometry
//! goes through `libm`).

pub mod movers;
mod outcome;
pub mod robot;
mod sensors;
pub mod static_map;
pub mod terrain;

pub use movers::{MotionModel, MoverSpec, MoverState, MoverTrack, Placement, ScriptSample};
pub use outcome::{Collision, Outcome, AT_REST_SPEED};
pub use robot::{Command, Drive, Footprint, RobotLimits, RobotSpec, RobotState};
pub use sensors::{LaserScan, OdometrySample};
pub use static_map::StaticMap;
pub use terrain::{Road, SlipSpec, Terrain, TerrainSpec, TerrainStep, VehicleSpec};

use thiserror::Error;

use crate::params::{check_param, Bound, ParamError};

/// Invalid world description: bad robot, mover or map geometry.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum WorldError {
    /// A parameter is NaN, infinite or out of its range; the text names it.
    #[error("invalid {}", crate::text::one_line(.0))]
    InvalidParameter(String),
    /// The map cannot be simulated (e.g. a rotated origin).
    #[error("map not supported by the simulator: {}", crate::text::one_line(.0))]
    UnsupportedMap(String),
    /// The robot starts overlapping an obstacle.
    #[error("the robot starts in collision at ({x:.3}, {y:.3}) m: {with}")]
    StartInCollision {
        /// Start x, metres.
        x: f64,
        /// Start y, metres.
        y: f64,
        /// What it overlaps ("a wall", "mover 2", "the map edge").
        with: String,
    },
    /// A mover starts overlapping a wall or the map edge.
    #[error("mover {id} at ({x:.3}, {y:.3}) m {reason}")]
    MoverInWall {
        /// The mover's id.
        id: u32,
        /// Where, x, metres.
        x: f64,
        /// Where, y, metres.
        y: f64,
        /// What is wrong ("starts overlapping a wall or the map edge", …).
        reason: String,
    },
}

impl From<ParamError> for WorldError {
    fn from(e: ParamError) -> Self {
        WorldError::InvalidParameter(e.unit_named())
    }
}

/// Checks that `value` is finite, ≥ `min` and not huge; the error names `what`.
pub(crate) fn check_min(what: &str, value: f64, min: f64) -> Result<(), WorldError> {
    Ok(check_param(what, value, Bound::at_least(min))?)
}

/// Checks that `value` is finite, > 0 and not huge; the error names `what`.
pub(crate) fn check_positive(what: &str, value: f64) -> Result<(), WorldError> {
    Ok(check_param(what, value, Bound::above(0.0))?)
}

/// Checks that both coordinates of a point (metres, or m/s for a
/// velocity) are finite and within ±[`MAX_PARAM`](crate::num::MAX_PARAM),
/// as every distance and speed is.
pub(crate) fn check_point(what: &str, p: [f64; 2]) -> Result<(), WorldError> {
    use crate::num::{fmt_num, MAX_PARAM};
    if p.iter().all(|v| v.is_finite() && v.abs() <= MAX_PARAM) {
        Ok(())
    } else {
        Err(WorldError::InvalidParameter(format!(
            "{what} = ({}, {}): coordinates must be finite numbers within ±{}",
            fmt_num(p[0]),
            fmt_num(p[1]),
            fmt_num(MAX_PARAM)
        )))
    }
}
