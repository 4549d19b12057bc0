//! How a run ended. Every kind of run (a robot episode, a kinematic APF
//! run, an arm episode) reports it, so it lives below them all.

use serde::{Deserialize, Serialize};

/// How an episode ended (or that it has not).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum Outcome {
    /// Still going.
    #[default]
    Running,
    /// The robot's centre came within `goal_tolerance` of the goal.
    Reached,
    /// The footprint touched a wall, the map edge or a mover.
    Collision,
    /// `max_time` passed.
    Timeout,
    /// No progress toward the goal for `stuck_time`.
    Stuck,
}

impl Outcome {
    /// The kebab-case name (`reached`, `collision`, …).
    pub fn as_str(self) -> &'static str {
        match self {
            Outcome::Running => "running",
            Outcome::Reached => "reached",
            Outcome::Collision => "collision",
            Outcome::Timeout => "timeout",
            Outcome::Stuck => "stuck",
        }
    }
}

impl std::fmt::Display for Outcome {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}
