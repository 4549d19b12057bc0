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

/// A robot slower than this (translational speed, m/s) when something hits
/// it counts as at rest (the pages call a stuck robot this slow "stopped").
pub const AT_REST_SPEED: f64 = 0.05;

/// What an episode that ended in [`Outcome::Collision`] ran into, and
/// whether the robot was at rest: a mover driving into a robot that stands
/// (or turns on the spot) is not the planner driving into it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", tag = "with")]
pub enum Collision {
    /// A wall (blocked cell) or the map edge.
    Wall {
        /// The robot's translational speed was below [`AT_REST_SPEED`].
        at_rest: bool,
    },
    /// A mover (the one overlapping deepest when several do).
    Mover {
        /// The mover's id.
        id: u32,
        /// The robot's translational speed was below [`AT_REST_SPEED`].
        at_rest: bool,
    },
    /// The robot's state stopped being a finite number.
    NonFinite,
}

impl std::fmt::Display for Collision {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            Collision::Wall { at_rest: false } => {
                f.write_str("collision with a wall or the map edge")
            }
            Collision::Wall { at_rest: true } => f.write_str(
                "collision with a wall or the map edge while at rest (turning on the spot)",
            ),
            Collision::Mover { id, at_rest: false } => write!(f, "collision with mover {id}"),
            Collision::Mover { id, at_rest: true } => write!(f, "hit by mover {id} while at rest"),
            Collision::NonFinite => f.write_str("the robot's state became non-finite"),
        }
    }
}
