//! What a scan-based navigator (\[L\], [`crate::lidar`]) saw and chose in
//! its last step, world frame, as plain data for drawing. It is carried by
//! [`super::PlannerDebug`], the base of the planner layer, so it is defined
//! here rather than in `lidar` (which re-exports every name).

use serde::{Deserialize, Serialize};

/// Edge type of \[L\] definition 1.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
pub enum Edge {
    /// No edge.
    #[default]
    Null,
    /// Strong rising: in range → no return.
    SR,
    /// Weak rising: range jumps up by more than T_gap.
    WR,
    /// Strong falling: no return → in range.
    SF,
    /// Weak falling: range drops by more than T_gap.
    WF,
}

impl Edge {
    /// SR or WR.
    pub fn is_rising(self) -> bool {
        matches!(self, Edge::SR | Edge::WR)
    }
    /// SF or WF.
    pub fn is_falling(self) -> bool {
        matches!(self, Edge::SF | Edge::WF)
    }
    /// Small integer code for typed arrays: Null 0, SR 1, WR 2, SF 3, WF 4.
    pub fn code(self) -> u8 {
        match self {
            Edge::Null => 0,
            Edge::SR => 1,
            Edge::WR => 2,
            Edge::SF => 3,
            Edge::WF => 4,
        }
    }
}

/// What the navigator steers to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum TargetKind {
    /// The global goal (not blocked, or no usable temporary goal).
    #[default]
    Global,
    /// A temporary goal chosen this step.
    Temporary,
    /// A temporary goal kept from an earlier step (hold period).
    Held,
}

/// An edge for drawing: beam, type and the in-range point it marks (world).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct EdgeMark {
    /// Beam index i of e_i.
    pub beam: usize,
    /// Type.
    pub kind: Edge,
    /// The obstacle point on the edge's in-range side, m.
    pub point: [f64; 2],
}

/// A temporary-goal candidate for drawing (world).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CandidateMark {
    /// Position, m.
    pub point: [f64; 2],
    /// Cost (eq 3), m.
    pub cost: f64,
    /// Iteration (0 = around the OP blocking the goal).
    pub iteration: u32,
}

/// What the LiDAR navigator saw and chose in its last step, world frame,
/// for the page. `pose`, `ranges`, `returns`, `kind` and the hold timer are
/// filled every step; the geometry only while rollouts are recorded.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct LidarDebug {
    /// Sensor pose (x, y, θ) of the scan.
    pub pose: [f64; 3],
    /// Range limit, m.
    pub max_range: f64,
    /// Raw ranges, m; beams with no return hold `max_range`.
    pub ranges: Vec<f64>,
    /// Whether each beam returned.
    pub returns: Vec<bool>,
    /// Edges of the raw scan.
    pub edges_raw: Vec<EdgeMark>,
    /// Edges after gap removal (Algorithm 1).
    pub edges: Vec<EdgeMark>,
    /// Removed gap patterns: the straight line that replaced each.
    pub gaps: Vec<[[f64; 2]; 2]>,
    /// Obstacle patterns before expansion (polylines through their beams).
    pub ops_raw: Vec<Vec<[f64; 2]>>,
    /// Obstacle patterns after expansion (eq 1).
    pub ops: Vec<Vec<[f64; 2]>>,
    /// Index into `ops` of the OP blocking the goal.
    pub blocking: Option<usize>,
    /// Every temporary-goal candidate evaluated.
    pub candidates: Vec<CandidateMark>,
    /// The target steered to.
    pub target: [f64; 2],
    /// Its kind.
    pub kind: TargetKind,
    /// Time left in the hold period, s.
    pub hold_remaining: f64,
    /// The hold period t_h, s.
    pub hold_period: f64,
}
