//! Cleaning-robot DWA of \[C\] (Zhang, Song & Zhang 2020, §2–3;
//! docs/algorithms.md §cleaning-dwa)
//! and its "traditional DWA" baseline, for the omnidirectional / 4WIS robot.
//! `traditional-dwa` is the same planner and cost with `load_limit` and
//! `compensate` off.
//!
//! **Global path.** A* ([`crate::global::plan::plan_on_map`]) on the map
//! inflated by `inflation_radius + safety_distance` (\[C\] Table 2: robot
//! radius plus the safety distance with obstacles; the plain radius, then no
//! inflation, when an endpoint lies in that band), from the start through
//! the cleaning target points `waypoints` in order (\[C\] §3.4 step 1 sends
//! target points to A*) to the goal. The cells become world points (exact
//! start, waypoints and goal) merged into straight segments.
//!
//! **Local goal.** Each step the robot is projected onto the global path;
//! the search only moves forward and looks at most 2·lookahead of arc ahead,
//! so a zig-zag's next leg cannot capture it. The local goal is the point
//! `lookahead` metres of arc further, raised to 1.25·v_max·sim_time when
//! shorter: with the cost looking only at rollout ends, a reachable local
//! goal would let any wandering rollout that ends on it win. With
//! `stop_at_waypoints` the local goal does not pass the next waypoint until
//! the robot is within `waypoint_tolerance` of it, so the robot brakes and
//! restarts there (\[C\] §2.1: many close targets, frequent acceleration
//! and braking). The "local path" used by d_p is the global path from the
//! projection to the local goal (ROS's pruned plan).
//!
//! **Window and samples** (\[C\] eq 9–10). Body-frame (v_x, v_y, ω)
//! reachable in one control period under the robot's accelerations and
//! within its speed limits, sampled every `v_res` / `w_res` on a grid centred
//! on the current (wheel) velocity, so "keep the velocity" is always a
//! sample, with the window edges added. (v_x, v_y) samples faster than
//! `max_speed` in translation (default the robot's v_max, \[C\] Table 1's
//! single linear speed limit) are scaled back onto that circle (dropped if
//! that leaves the window): a turned body cannot gain speed by driving
//! diagonally, and no direction of travel is favoured by the grid.
//!
//! **Vertical-load limit** (\[C\] §3.2, eq 8 and 14, `load_limit`). With
//! a_z the peak of the last `accel_z_hold` measurements (`Observation::
//! accel_z`; \[C\] uses the filtered IMU value, and a peak-hold is the
//! cautious filter since the coming period's bumps are unknown), a sample
//! whose acceleration (v − v_now)/dt would leave a wheel with less than
//! j·m·g by eq 8 is dropped (`load_region = "diamond"`: the exact eq 8
//! region, |a_x| + |a_y| ≤ (g − 4jg − a_z)·l_r/h for the symmetric Table 1
//! vehicle, whose corners are eq 14's x₁ = y₁), or each axis is held to
//! eq 14's bound (`"box"`). Keeping the velocity is always allowed; if even
//! that overloads, the least overloading sample is kept, so the window never
//! empties (braking hard would unload the wheels most). Mode
//! `"load-limited"` is shown while eq 14's bound is below the robot's
//! acceleration limit.
//!
//! **Rollouts** (\[C\] eq 12 / 18): each sample is held for `sim_time`,
//! stepping every `sim_dt` by the body increment K·(v_x, v_y, ω)·sim_dt
//! rotated into the world (K = I without compensation). **Odometry
//! compensation** (\[C\] eq 15–18, `compensate`): every period's wheel /
//! laser odometry pair (u, u*) enters a sliding window of `window` samples;
//! from `min_samples` on, K minimises Σ‖u* − K u‖² + λ‖K − K_prev‖²_F, i.e.
//! K = (Σu*uᵀ + λK_prev)(Σuuᵀ + λI)⁻¹ with λ = `ridge`·tr(Σuuᵀ)/3. The ridge
//! keeps directions the robot has not excited (it rarely turns or moves
//! sideways) at the previous estimate instead of fitting noise: with a weak
//! ridge, nearly collinear commands gave K entries of ±0.2 that sent the
//! robot sideways. `k_structure = "block"` (default) fits the translation
//! 2×2 and the rotation separately, as the paper's appendix (eqs 27–31)
//! derives them; with the full 3×3 of eq 17, spurious ω → translation terms
//! let the planner "gain" speed by spinning. A singular or non-finite system
//! keeps the previous K (identity at first).
//!
//! **Cost** (\[C\] eq 13, minimised): G = α·c_obs + β·d_g + γ·d_p
//! (+ `twirl`·|ω|, below) with c_obs the costmap cost ([`Costmap::ros`] with
//! inscribed radius `inflation_radius`, decay out to `inflation_radius +
//! safety_distance`, factor `cost_scaling`) of the cells the rollout passes
//! through, and d_g, d_p the Manhattan distances (m) from the rollout end to
//! the local goal and to the local path. A rollout is inadmissible when a
//! point comes within the robot's circumscribed radius (plus half a cell:
//! the clearance field's error) of a wall or the map edge, or of a perceived
//! mover moved on at constant velocity. Ties keep the first sample (ω outer,
//! then v_x, then v_y, ascending): deterministic.
//!
//! **Decisions** where \[C\] is silent or self-contradictory:
//! - Weights: eq 13 pairs β with the local goal and γ with the global path,
//!   but Table 2 labels β (0.6) "global weight" and γ (0.3) "local weight".
//!   We follow Table 2's labels — 0.6 on the distance to the global path,
//!   0.3 on the distance to the local goal, as ROS's defaults also weight
//!   the path above the goal (32 vs 24) — so `beta` (on d_g) defaults to 0.3
//!   and `gamma` (on d_p) to 0.6. With eq 13's reading the Manhattan goal
//!   term pays for cutting every corner (40+ cm off the path at a 45° bend),
//!   far beyond the paper's 7–12 cm maxima.
//! - Units: distances in metres, costs scaled to 0–1 (÷ 252, [`COST_SCALE`])
//!   and summed over the rollout's points (one per `sim_dt`), i.e. over the
//!   cells crossed weighted by the time spent in them; counting each cell
//!   once would make standing still inside the band the cheapest choice and
//!   freeze the robot there.
//! - `twirl` (default 0.1 m·s/rad, 0 = the paper's cost): a small cost on
//!   |ω|, as nav2 DWB's TwirlingCritic, because nothing in eq 13 cares about
//!   the heading of a holonomic robot; without it the planner drifts into
//!   curved rollouts that end on the path but start off it, and meanders.
//!
//! Files: `config` (settings, field list), `path` (global path, local
//! goal), `step` (the window, rollouts and cost as an engine
//! composition), `load` (the held a_z), `odometry` (compensation), `tests`.

mod config;
mod load;
mod odometry;
mod path;
mod step;
#[cfg(test)]
mod tests;

use std::collections::VecDeque;

pub use config::{field_list, parse, CleaningDwaConfig, KStructure, LoadRegion};
pub use odometry::{fit_k, Mat3};

use super::engine::critic::Twirling;
use super::engine::{CriticSlot, Engine, Scoring};
use super::LocalError;
use crate::map::costmap::Costmap;
use crate::map::OccupancyGrid;
use crate::world::terrain::IDENTITY;
use crate::world::{RobotSpec, RobotState, StaticMap};
use path::GlobalPath;
pub use step::{CostmapObstacle, GoalDistanceL1, LoadWindow, PathDistanceL1};

/// Costmap costs are divided by this (the highest decaying cost, 252) so
/// one cell of the decay band weighs at most α, as one cell of distance
/// weighs β or γ.
pub const COST_SCALE: f64 = 252.0;

/// The `cleaning-dwa` / `traditional-dwa` planner (see the module doc).
#[derive(Debug)]
pub struct CleaningDwa {
    name: &'static str,
    cfg: CleaningDwaConfig,
    robot: RobotSpec,
    /// Walls and unknown-as-obstacle cells of the map, as a grid.
    solid: OccupancyGrid,
    path: GlobalPath,
    /// Segment of the last projection (never decreases).
    seg: usize,
    /// Arc length of the last projection, m.
    s_robot: f64,
    /// Waypoints as stops: (arc length on the path, point).
    stops: Vec<(f64, [f64; 2])>,
    /// Index of the next stop not yet reached.
    next_stop: usize,
    goal: [f64; 2],
    k: Mat3,
    odo: VecDeque<([f64; 3], [f64; 3])>,
    /// Recent measured a_z, newest last.
    az_recent: VecDeque<f64>,
    /// The a_z the load limit uses this step (peak of `az_recent`).
    az_estimate: f64,
    /// \[C\]'s window and cost as an engine composition (`step`).
    engine: Engine<LoadWindow>,
}

impl CleaningDwa {
    /// Builds the planner catalogued as `name` (`cleaning-dwa` or
    /// `traditional-dwa`, used in error messages and
    /// [`LocalPlanner::name`](crate::local::LocalPlanner::name)) for `robot`
    /// on `map`, planning the global path from `start` through the
    /// waypoints to `goal`.
    pub fn new(
        name: &'static str,
        cfg: CleaningDwaConfig,
        robot: &RobotSpec,
        map: &StaticMap,
        start: &RobotState,
        goal: [f64; 2],
    ) -> Result<Self, LocalError> {
        cfg.validate(name)?;
        let solid = map.solid();
        let costmap = Costmap::ros(
            &solid,
            cfg.inflation_radius,
            cfg.inflation_radius + cfg.safety_distance,
            cfg.cost_scaling,
        )
        .map_err(|e| LocalError::InvalidParameter(format!("{name}: costmap: {e}")))?;
        let critics = vec![
            CriticSlot::new(
                CostmapObstacle::new(
                    costmap,
                    map,
                    robot,
                    cfg.inflation_radius + cfg.safety_distance,
                ),
                cfg.alpha,
            ),
            CriticSlot::new(GoalDistanceL1, cfg.beta),
            CriticSlot::new(PathDistanceL1, cfg.gamma),
            CriticSlot::new(Twirling::named("twirl_rad_s"), cfg.twirl),
        ];
        let mut engine = Engine::new(
            robot,
            Box::new(LoadWindow::new(cfg.clone(), robot)),
            critics,
            Scoring::WeightedCost,
            None,
        )
        .keep_chosen(true);
        let d = engine.debug_mut();
        d.current_goal = goal;
        d.keypoints = cfg.waypoints.clone();
        let mut me = Self {
            name,
            solid,
            path: GlobalPath::default(),
            seg: 0,
            s_robot: 0.0,
            stops: Vec::new(),
            next_stop: 0,
            goal,
            k: IDENTITY,
            odo: VecDeque::new(),
            az_recent: VecDeque::new(),
            az_estimate: 0.0,
            engine,
            robot: *robot,
            cfg,
        };
        let waypoints = me.cfg.waypoints.clone();
        me.replan([start.x, start.y], &waypoints, goal)?;
        Ok(me)
    }

    /// The current odometry correction K (identity until fitted).
    pub fn k(&self) -> Mat3 {
        self.k
    }

    /// The config.
    pub fn config(&self) -> &CleaningDwaConfig {
        &self.cfg
    }
}
