//! LiDAR heuristic navigation in unknown maps (\[L\] Chang et al. 2024;
//! docs/algorithms.md §lidar).
//!
//! - [`scan`]: the 2D LiDAR — n beams over 360°, range limit, exact ray
//!   casting against the grid (DDA) and the moving discs, seeded noise.
//! - [`edges`]: edges SR / WR / SF / WF / Null (def. 1), Algorithm 1 (gap
//!   pattern removal, with wrap-around), Algorithm 2 (obstacle pattern
//!   extraction), expansion (eq 1).
//! - [`nav`]: temporary goals — blocking condition (eq 2), two candidates,
//!   cost (eq 3), iteration, extra switching condition (eq 4), hold period;
//!   \[L\] Table 1 defaults in [`LidarNavConfig`].
//! - [`planner`]: the navigator over a pluggable motion planner (DWA, APF)
//!   fed a local map built from the scan alone, registered as local
//!   planners `lidar-dwa`, `scan-dwa` (the plain baseline) and friends.
//! - [`fog`]: the cells the robot has seen so far, from its scans.
//! - The \[L\] sims 5–8 peers on the same sensor and motion layer
//!   ([`scan_motion`]): [`tangent_bug`] (TangentBug standing in for
//!   Critical-PointBug \[21\]), [`rs_apf`] (a scan-only RS-APF \[11\]),
//!   [`rrt_shortcut`] (RRT + shortcutting on the scan's memory, standing in
//!   for RL-RRT \[2\]).
//!
//! The navigator's input type [`NavInput`] holds the scan, the robot's
//! velocity and the goal in the robot frame only, so neither the navigator
//! nor the motion planner under it can read the map: only the simulated
//! sensor does.

pub mod edges;
pub mod fog;
pub mod nav;
pub mod planner;
pub mod rrt_shortcut;
pub mod rs_apf;
pub mod scan;
pub mod scan_motion;
pub mod tangent_bug;

pub use edges::{Edge, GapPattern, ObstaclePattern};
pub use nav::{LidarNavConfig, NavDebug, NavInput, Navigator, TargetKind, Velocity};
pub use planner::{LidarDebug, LidarPlanner, LidarPlannerConfig, LocalMapConfig, ScanNavigation};
pub use scan::{Lidar, LidarConfig, Scan};

use thiserror::Error;

/// Invalid LiDAR or navigator settings.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum LidarError {
    /// A parameter is NaN, infinite or out of range; the text names it.
    #[error("invalid LiDAR parameter: {}", crate::text::one_line(.0))]
    InvalidParameter(String),
}

impl From<crate::params::ParamError> for LidarError {
    fn from(e: crate::params::ParamError) -> Self {
        LidarError::InvalidParameter(e.to_string())
    }
}
