//! Local planners (docs/algorithms.md §local): the DWA family. Each planner is built complete
//! from its config, the robot and the static map, then called once per
//! control period with an [`Observation`] and returns a [`Command`].
//!
//! Planners see the world only through the observation: the robot's own
//! state, the goal, the static map and the movers within sensing range (with
//! their observed velocities). They never read the simulator's future.

pub mod car_guide;
pub mod cleaning;
pub mod dual;
pub mod dwa;
pub mod engine;
pub mod improved;
pub mod pursuit;
pub mod ros;
pub mod route;
pub mod scan_debug;
#[cfg(test)]
pub(crate) mod testkit;

use serde::{Deserialize, Serialize};
use thiserror::Error;

/// Sensor samples are world data (the terrain model makes them); named
/// here too because planners read them in their [`Observation`].
pub use crate::world::OdometrySample;
use crate::world::{Command, LaserScan, RobotState, StaticMap};

/// A mover as the robot perceives it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ObservedMover {
    /// Identifier (the scenario's mover id).
    pub id: u32,
    /// Centre, metres.
    pub pos: [f64; 2],
    /// Velocity, m/s.
    pub vel: [f64; 2],
    /// Radius, metres.
    pub radius: f64,
}

/// What a local planner may know at one control step.
#[derive(Debug, Clone, Copy)]
pub struct Observation<'a> {
    /// Simulated time, seconds.
    pub time: f64,
    /// Control period, seconds.
    pub dt: f64,
    /// The robot's pose and current velocities.
    pub state: &'a RobotState,
    /// The final goal, metres.
    pub goal: [f64; 2],
    /// The map the planner knows (grid, clearance field, exact collision):
    /// the true static map, or, when the episode has a perception section,
    /// what the laser has shown so far (`sim::perception`).
    pub map: &'a StaticMap,
    /// Changes whenever `map` changed since an earlier step (0 for a map
    /// that never changes): planners that keep a global path replan on it.
    pub map_revision: u64,
    /// The laser scan of this step, when the episode simulates one for the
    /// planner (`sim::perception`); planners that read a LiDAR use it
    /// instead of casting rays on `map`.
    pub scan: Option<&'a LaserScan>,
    /// Movers within sensing range.
    pub movers: &'a [ObservedMover],
    /// Odometry of the last period, when the simulator models slip.
    pub odometry: Option<OdometrySample>,
    /// Measured vertical acceleration a_z of the body (road roughness),
    /// m/s², 0 on flat ground.
    pub accel_z: f64,
}

/// How the current local goal was chosen, for traces and drawing.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum GoalKind {
    /// The final goal.
    #[default]
    Final,
    /// A key point / feature node of the global path.
    Intermediate,
    /// A virtual goal placed beside a special obstacle (\[T\] §3.2).
    Virtual,
    /// A temporary goal beside an obstacle pattern (\[L\] §3).
    Temporary,
}

/// Obstacle class of \[T\] Fig 3-10 / Table 3-1.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ObstacleClass {
    /// Moving faster than v_static: deceleration strategy.
    OrdinaryDynamic,
    /// Slow or still: detour strategy.
    OrdinaryStatic,
    /// Collinear with robot and goal: virtual goal.
    Special,
}

/// One sampled rollout of a DWA step, for drawing and inspection.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
pub struct Rollout {
    /// The sampled command.
    pub cmd: Command,
    /// Predicted positions (x, y), one per rollout step.
    pub points: Vec<[f64; 2]>,
    /// False when it collides or breaks the admissible-velocity rule.
    pub admissible: bool,
    /// Raw critic values, in the order of [`PlannerDebug::critics`].
    pub raw: Vec<f64>,
    /// Normalised critic values, same order.
    pub normalised: Vec<f64>,
    /// Total score (higher is better; cost-minimising planners report the
    /// negated cost).
    pub score: f64,
}

/// What a planner did in its last step, for traces and the page.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
pub struct PlannerDebug {
    /// Critic names, e.g. `["heading", "dist", "velocity"]`.
    pub critics: Vec<String>,
    /// The weight each critic had in the last step's choice (after any
    /// per-step factor such as \[T\]'s ρ), in the order of `critics`;
    /// empty for a planner without weighted critics.
    #[serde(default)]
    pub weights: Vec<f64>,
    /// Every sampled rollout of the last step (may be empty when recording
    /// is off, see [`LocalPlanner::set_record_rollouts`]).
    pub rollouts: Vec<Rollout>,
    /// Index of the chosen rollout in `rollouts`.
    pub chosen: Option<usize>,
    /// Global path (world points), when the planner uses one.
    pub global_path: Vec<[f64; 2]>,
    /// Key points / feature nodes (world points).
    pub keypoints: Vec<[f64; 2]>,
    /// The goal the last step steered to.
    pub current_goal: [f64; 2],
    /// Why that goal.
    pub goal_kind: GoalKind,
    /// Classes of the perceived movers: (mover id, class).
    pub classes: Vec<(u32, ObstacleClass)>,
    /// Strategy in force ("normal", "decelerate", "detour", "hold-v" …).
    pub mode: String,
    /// What the LiDAR navigator saw and chose (\[L\]), for its planners.
    pub lidar: Option<scan_debug::LidarDebug>,
}

/// A local planner: called once per control period.
pub trait LocalPlanner: Send {
    /// The planner's registry name.
    fn name(&self) -> &'static str;
    /// Chooses the command for this period.
    fn step(&mut self, obs: &Observation<'_>) -> Command;
    /// Moves the final goal (the user dragged it): replan what depends on it.
    fn set_goal(
        &mut self,
        map: &StaticMap,
        state: &RobotState,
        goal: [f64; 2],
    ) -> Result<(), LocalError>;
    /// What the last step did.
    fn debug(&self) -> &PlannerDebug;
    /// Record every rollout's points (for drawing) or not (faster batches).
    fn set_record_rollouts(&mut self, on: bool);
    /// The episode's seed, for planners that sample (the episode calls this
    /// once after building the planner; the rest ignore it).
    fn set_seed(&mut self, _seed: u64) {}
}

/// Errors building or re-targeting a local planner.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum LocalError {
    /// A config value is NaN, infinite or out of range; the text names it.
    #[error("invalid planner parameter: {}", crate::text::one_line(.0))]
    InvalidParameter(String),
    /// No name in the registry matches.
    #[error("unknown planner `{}` (see `planlab planners`)", crate::text::one_line(.0))]
    UnknownPlanner(String),
    /// The global planner found no path.
    #[error("no global path: {}", crate::text::one_line(.0))]
    NoGlobalPath(String),
}

impl From<crate::params::ParamError> for LocalError {
    fn from(e: crate::params::ParamError) -> Self {
        LocalError::InvalidParameter(e.to_string())
    }
}
