//! What the simulated sensors report, as plain data: made by the world
//! (the terrain model's odometry) and read by the planners above it.

use serde::{Deserialize, Serialize};

/// One odometry sample for the last control period (\[C\] eq 15–18): the
/// body-frame increment (Δx, Δy, Δθ) the wheels report (what was commanded)
/// and the true one a laser odometry measures.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, Default)]
pub struct OdometrySample {
    /// Wheel-odometry increment (Δx, Δy, Δθ), body frame.
    pub wheel: [f64; 3],
    /// Laser-odometry (true) increment (Δx, Δy, Δθ), body frame.
    pub laser: [f64; 3],
}
