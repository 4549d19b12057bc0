//! Critics: each scores one trajectory (or declares it illegal), in the
//! shape of Nav2 DWB's `TrajectoryCritic` plugin — prepared once per
//! control cycle, asked for a score per rollout, debriefed with the chosen
//! command — with a name and a weight the engine holds.
//!
//! Adding a critic is one type implementing [`Critic`] and one line in a
//! composition (see ARCHITECTURE.md, "Adding a critic").

use std::fmt;

use super::generator::{Sample, Trajectory, Window};
use crate::local::Observation;
use crate::num::{atan2, wrap_angle};
use crate::world::{Command, RobotSpec};

/// What every critic may read in one control cycle.
#[derive(Debug, Clone, Copy)]
pub struct CriticContext<'a> {
    /// The observation of this cycle.
    pub obs: &'a Observation<'a>,
    /// The goal this cycle steers to (a local goal for guided planners), m.
    pub goal: [f64; 2],
    /// The global path being followed (world points; empty without one).
    pub path: &'a [[f64; 2]],
    /// The robot.
    pub robot: &'a RobotSpec,
    /// Every sample of this cycle.
    pub samples: &'a [Sample],
    /// The window they were drawn from.
    pub window: &'a Window,
}

/// A trajectory critic.
pub trait Critic: Send + fmt::Debug {
    /// Name in the parameter panel and the rollouts' critic list.
    fn name(&self) -> &str;
    /// Called once per control cycle before any [`Critic::score`].
    fn prepare(&mut self, _ctx: &CriticContext<'_>) {}
    /// The raw score of `traj`; `None` declares it illegal (it is then not
    /// chosen, whatever the other critics say).
    fn score(&self, ctx: &CriticContext<'_>, traj: &Trajectory) -> Option<f64>;
    /// Whether it reads the headings of a rollout (`Trajectory::dirs`).
    /// True unless a critic says otherwise, so a new critic always finds
    /// them; critics that read only positions, the end pose or the command
    /// say false, and a rollout then skips storing them.
    fn needs_headings(&self) -> bool {
        true
    }
    /// Called after the choice with the command driven (`None`: the
    /// fallback drove).
    fn debrief(&mut self, _chosen: Option<&Command>) {}
}

/// How the engine turns critic scores into a choice.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scoring {
    /// The DWA papers' rule (docs/algorithms.md §dwa): each critic's raw
    /// value divided by its sum over the admissible rollouts,
    /// G = Σ weightₖ·normalisedₖ, the highest G wins.
    NormalisedSum,
    /// ROS's rule (base_local_planner, DWB): cost = Σ weightₖ·rawₖ, the
    /// lowest cost wins; the rollout's score is reported as −cost.
    WeightedCost,
}

/// A critic with its weight (DWB's `scale`).
#[derive(Debug)]
pub struct CriticSlot {
    /// The critic.
    pub critic: Box<dyn Critic>,
    /// Its weight when a cycle does not set one.
    pub weight: f64,
}

impl CriticSlot {
    /// `critic` weighted `weight`.
    pub fn new(critic: impl Critic + 'static, weight: f64) -> Self {
        Self {
            critic: Box::new(critic),
            weight,
        }
    }
}

/// \[T\] eq 3-2's heading: π − |bearing error to the goal at the rollout's
/// end| (higher is better).
#[derive(Debug, Clone, Default)]
pub struct Heading;

impl Critic for Heading {
    fn name(&self) -> &str {
        "heading"
    }
    fn needs_headings(&self) -> bool {
        false
    }
    fn score(&self, ctx: &CriticContext<'_>, traj: &Trajectory) -> Option<f64> {
        let [x, y, theta] = traj.end_pose();
        let bearing = atan2(ctx.goal[1] - y, ctx.goal[0] - x);
        Some(std::f64::consts::PI - wrap_angle(bearing - theta).abs())
    }
}

/// \[T\] eq 3-3's dist: the smallest clearance along the rollout (the
/// screen's), capped at `cap` (higher is better).
#[derive(Debug, Clone)]
pub struct Clearance {
    /// Saturation, m.
    pub cap: f64,
}

impl Critic for Clearance {
    fn name(&self) -> &str {
        "dist"
    }
    fn needs_headings(&self) -> bool {
        false
    }
    fn score(&self, _ctx: &CriticContext<'_>, traj: &Trajectory) -> Option<f64> {
        Some(traj.min_clearance.max(0.0).min(self.cap))
    }
}

/// \[T\] eq 3-4's velocity: the forward speed (higher is better).
#[derive(Debug, Clone, Default)]
pub struct Velocity;

impl Critic for Velocity {
    fn name(&self) -> &str {
        "velocity"
    }
    fn needs_headings(&self) -> bool {
        false
    }
    fn score(&self, _ctx: &CriticContext<'_>, traj: &Trajectory) -> Option<f64> {
        Some(traj.sample.cmd.v.max(0.0))
    }
}

/// Nav2 DWB's TwirlingCritic: |ω| (rad/s), a cost on spinning (lower is
/// better; for the weighted-cost rule).
#[derive(Debug, Clone)]
pub struct Twirling {
    name: &'static str,
}

impl Twirling {
    /// The critic under the name `name`.
    pub fn named(name: &'static str) -> Self {
        Self { name }
    }
}

impl Critic for Twirling {
    fn name(&self) -> &str {
        self.name
    }
    fn needs_headings(&self) -> bool {
        false
    }
    fn score(&self, _ctx: &CriticContext<'_>, traj: &Trajectory) -> Option<f64> {
        Some(traj.sample.cmd.w.abs())
    }
}
