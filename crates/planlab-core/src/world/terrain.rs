//! Ground truth of motion: how a command becomes the robot's true motion.
//!
//! Flat ground with no slip by default: the true motion is exactly the
//! commanded one ([`super::robot::integrate`]). The cleaning-robot paper [C]
//! adds a road model (vertical acceleration a_z from road roughness), wheel
//! slip (true increment = K_true·u + noise, [C] eq 15–18) and wheel loads
//! ([C] eq 8); those live here so the simulator calls one function per step.

use serde::{Deserialize, Serialize};

use super::robot::{integrate, Command, RobotState};
use super::WorldError;
use crate::local::OdometrySample;

/// Terrain and vehicle-dynamics settings of a scenario.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
#[serde(default, deny_unknown_fields)]
pub struct TerrainSpec {}

/// What the terrain did in one step.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct TerrainStep {
    /// The robot's true state after the step.
    pub next: RobotState,
    /// Wheel vs laser odometry of the step, when slip is modelled.
    pub odometry: Option<OdometrySample>,
    /// Vertical acceleration of the body during the step, m/s².
    pub accel_z: f64,
    /// Vertical load on each wheel (front-left, front-right, rear-left,
    /// rear-right), newtons, when a vehicle model is given.
    pub wheel_loads: Option<[f64; 4]>,
}

/// The terrain of one episode, with its own seeded noise stream.
#[derive(Debug, Clone)]
pub struct Terrain {
    #[allow(dead_code)]
    spec: TerrainSpec,
}

impl Terrain {
    /// Builds the terrain; `seed` drives its noise.
    pub fn new(spec: TerrainSpec, seed: u64) -> Result<Self, WorldError> {
        let _ = seed;
        Ok(Self { spec })
    }

    /// Applies `cmd` (already limited to what the motors can do) for `dt`.
    pub fn step(&mut self, state: &RobotState, cmd: Command, dt: f64) -> TerrainStep {
        TerrainStep {
            next: integrate(state, cmd, dt),
            ..Default::default()
        }
    }
}
