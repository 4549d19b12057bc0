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

use std::collections::VecDeque;

use serde::{Deserialize, Serialize};

use super::registry::{check_param, field_infos, parse_config, FieldInfo};
use super::{GoalKind, LocalError, LocalPlanner, Observation, PlannerDebug, Rollout};
use crate::global::plan::{plan_on_map, Algorithm, GridPlanError, GridPlanOptions};
use crate::global::GridPos;
use crate::map::costmap::{Costmap, INSCRIBED};
use crate::map::{Cell, OccupancyGrid};
use crate::num::{cos, sin};
use crate::world::terrain::{VehicleSpec, GRAVITY, IDENTITY};
use crate::world::{Command, Drive, RobotSpec, RobotState, StaticMap};

/// Critic names, in the order of [`Rollout::raw`].
pub const CRITICS: [&str; 4] = [
    "obstacle_cost",
    "goal_distance_m",
    "path_distance_m",
    "twirl_rad_s",
];

/// Costmap costs are divided by this (the highest decaying cost, 252) so
/// one cell of the decay band weighs at most α, as one cell of distance
/// weighs β or γ.
pub const COST_SCALE: f64 = 252.0;

/// Most integration steps in one rollout (`sim_time / sim_dt`).
pub const MAX_ROLLOUT_STEPS: usize = 10_000;

/// How the vertical-load limit shapes the acceleration window.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum LoadRegion {
    /// Exact \[C\] eq 8 condition on all four wheels (a diamond
    /// |a_x| + |a_y| ≤ x₁ for the symmetric vehicle).
    #[default]
    Diamond,
    /// Each axis within eq 14's bound separately.
    Box,
}

/// Which entries of the odometry correction K are fitted.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum KStructure {
    /// Translation (2×2) and rotation (1×1) blocks; no cross terms (\[C\]
    /// appendix eqs 27–31: each is linear in its own wheel increment).
    #[default]
    Block,
    /// All nine entries (\[C\] eq 17 as written).
    Full,
}

/// Settings of `cleaning-dwa` / `traditional-dwa` (\[C\] Tables 1–2).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct CleaningDwaConfig {
    /// α, weight of the obstacle cost c_obs, 1.
    pub alpha: f64,
    /// β, weight of the distance to the local goal d_g (\[C\] Table 2's
    /// "local weight", see the module doc), 1.
    pub beta: f64,
    /// γ, weight of the distance to the global path d_p (\[C\] Table 2's
    /// "global weight"), 1.
    pub gamma: f64,
    /// Weight of |ω| (not in \[C\]; nav2 DWB's "twirling" critic), m·s/rad.
    pub twirl: f64,
    /// Linear velocity resolution (v_x and v_y), m/s.
    pub v_res: f64,
    /// Angular velocity resolution, rad/s.
    pub w_res: f64,
    /// Trajectory prediction time, s.
    pub sim_time: f64,
    /// Integration step of the prediction, s.
    pub sim_dt: f64,
    /// Most samples per velocity axis (a tiny resolution cannot stall a
    /// step), 1.
    pub max_samples_per_axis: usize,
    /// Largest translational speed √(v_x² + v_y²), m/s; 0 = the robot's
    /// v_max (\[C\] Table 1's single maximum linear speed).
    pub max_speed: f64,
    /// Robot inflation radius: costmap inscribed radius and A* inflation, m.
    pub inflation_radius: f64,
    /// Safety distance: costs decay from the inflation radius out to
    /// inflation_radius + safety_distance, m.
    pub safety_distance: f64,
    /// Cost decay factor of the costmap (ROS cost_scaling_factor), 1/m.
    pub cost_scaling: f64,
    /// Arc length from the robot's projection on the global path to the
    /// local goal, m (raised to 1.25·v_max·sim_time when shorter).
    pub lookahead: f64,
    /// Cleaning target points the global path passes through in order, m.
    pub waypoints: Vec<[f64; 2]>,
    /// Stop at every cleaning target point: the local goal does not pass
    /// the next waypoint until the robot is within `waypoint_tolerance` of
    /// it (\[C\] §2.1: many close targets, frequent acceleration and
    /// braking).
    pub stop_at_waypoints: bool,
    /// A waypoint is reached within this distance, m.
    pub waypoint_tolerance: f64,
    /// Vertical-load acceleration limit of \[C\] §3.2 on.
    pub load_limit: bool,
    /// j: every wheel must carry more than j·m·g (0 ≤ j < 1/4), 1.
    pub load_fraction: f64,
    /// Shape of the load limit: `diamond` (exact eq 8) or `box` (eq 14 per
    /// axis).
    pub load_region: LoadRegion,
    /// Vehicle of the load limit (\[C\] Table 1).
    pub vehicle: VehicleSpec,
    /// The a_z the load limit uses is the largest measured over this many
    /// control periods (a peak-hold filter: the next period's bumps are
    /// unknown, the recent worst is a cautious guess), periods.
    pub accel_z_hold: usize,
    /// Odometry error compensation of \[C\] §3.3 on.
    pub compensate: bool,
    /// Entries of K fitted: `block` (translation 2×2 + rotation) or `full`
    /// (3×3).
    pub k_structure: KStructure,
    /// Sliding window of odometry samples for the least-squares fit.
    pub window: usize,
    /// Samples needed before the first fit (K stays the identity until
    /// then).
    pub min_samples: usize,
    /// Ridge weight pulling K toward its previous value, relative to the
    /// mean excitation tr(Σuuᵀ)/3, 1.
    pub ridge: f64,
}

impl Default for CleaningDwaConfig {
    fn default() -> Self {
        Self {
            alpha: 0.1,
            beta: 0.3,
            gamma: 0.6,
            twirl: 0.1,
            v_res: 0.02,
            w_res: 0.01,
            sim_time: 2.0,
            sim_dt: 0.1,
            max_samples_per_axis: 41,
            max_speed: 0.0,
            inflation_radius: 0.35,
            safety_distance: 0.10,
            cost_scaling: 10.0,
            lookahead: 1.5,
            waypoints: Vec::new(),
            stop_at_waypoints: false,
            waypoint_tolerance: 0.1,
            load_limit: true,
            load_fraction: 0.2,
            load_region: LoadRegion::Diamond,
            vehicle: VehicleSpec::default(),
            accel_z_hold: 5,
            compensate: true,
            k_structure: KStructure::Block,
            window: 50,
            min_samples: 10,
            ridge: 0.3,
        }
    }
}

/// (name, unit, doc) of every field, for the registry.
pub const FIELDS: &[(&str, &str, &str)] = &[
    (
        "alpha",
        "1",
        "α: weight of the obstacle cost (sum of costmap costs crossed)",
    ),
    (
        "beta",
        "1",
        "β: weight of the Manhattan distance to the local goal",
    ),
    (
        "gamma",
        "1",
        "γ: weight of the Manhattan distance to the global path",
    ),
    (
        "twirl",
        "m·s/rad",
        "weight of |ω| (not in [C]; keeps the holonomic body from spinning, 0 = off)",
    ),
    ("v_res", "m/s", "linear velocity resolution (v_x and v_y)"),
    ("w_res", "rad/s", "angular velocity resolution"),
    ("sim_time", "s", "trajectory prediction time"),
    ("sim_dt", "s", "integration step of the prediction"),
    (
        "max_samples_per_axis",
        "1",
        "most samples per velocity axis",
    ),
    (
        "max_speed",
        "m/s",
        "largest translational speed √(v_x² + v_y²); 0 = the robot's v_max",
    ),
    (
        "inflation_radius",
        "m",
        "robot inflation radius: costmap inscribed radius and A* inflation",
    ),
    (
        "safety_distance",
        "m",
        "costs decay from the inflation radius out to inflation_radius + this",
    ),
    (
        "cost_scaling",
        "1/m",
        "costmap cost decay factor (ROS cost_scaling_factor)",
    ),
    (
        "lookahead",
        "m",
        "arc length from the robot's projection to the local goal (at least 1.25·v_max·sim_time)",
    ),
    (
        "waypoints",
        "m",
        "cleaning target points [[x, y], …] the global path passes through in order",
    ),
    (
        "stop_at_waypoints",
        "bool",
        "stop at every waypoint (the local goal waits there until it is reached)",
    ),
    (
        "waypoint_tolerance",
        "m",
        "a waypoint is reached within this distance",
    ),
    (
        "load_limit",
        "bool",
        "vertical-load acceleration limit ([C] eq 8, 14)",
    ),
    (
        "load_fraction",
        "1",
        "j: every wheel keeps more than j·m·g (0 ≤ j < 1/4)",
    ),
    (
        "load_region",
        "",
        "`diamond` (exact eq 8, |a_x|+|a_y| ≤ x₁) or `box` (eq 14 per axis)",
    ),
    ("vehicle.mass", "kg", "vehicle mass m"),
    ("vehicle.l_f", "m", "centre of gravity to front axle"),
    ("vehicle.l_r", "m", "centre of gravity to rear axle"),
    ("vehicle.b_f", "m", "front track"),
    ("vehicle.b_r", "m", "rear track"),
    ("vehicle.h", "m", "height of the centre of gravity"),
    (
        "accel_z_hold",
        "periods",
        "the load limit uses the largest a_z measured over this many periods (≥ 1)",
    ),
    (
        "compensate",
        "bool",
        "odometry error compensation: least-squares K used in rollouts ([C] eq 15–18)",
    ),
    (
        "k_structure",
        "",
        "`block` (translation 2×2 and rotation fitted separately) or `full` (3×3, eq 17)",
    ),
    (
        "window",
        "samples",
        "sliding window of odometry pairs for the fit",
    ),
    (
        "min_samples",
        "samples",
        "odometry pairs needed before the first fit (K = I until then)",
    ),
    (
        "ridge",
        "1",
        "pull of K toward its previous value, relative to the mean excitation",
    ),
];

/// The field list of `cleaning-dwa` (`traditional = false`) or
/// `traditional-dwa` (load limit and compensation off by default).
pub fn field_list(traditional: bool) -> Vec<FieldInfo> {
    let mut f = field_infos::<CleaningDwaConfig>(FIELDS);
    if traditional {
        for info in &mut f {
            if info.name == "load_limit" || info.name == "compensate" {
                info.default = serde_json::Value::Bool(false);
            }
        }
    }
    f
}

/// Reads the config of registry entry `planner`: `traditional-dwa` turns
/// `load_limit` and `compensate` off unless the JSON sets them.
pub fn parse(planner: &str, value: &serde_json::Value) -> Result<CleaningDwaConfig, LocalError> {
    if planner == "traditional-dwa" {
        let mut v = if value.is_null() {
            serde_json::Value::Object(Default::default())
        } else {
            value.clone()
        };
        if let serde_json::Value::Object(m) = &mut v {
            for key in ["load_limit", "compensate"] {
                m.entry(key).or_insert(serde_json::Value::Bool(false));
            }
        }
        parse_config(planner, &v)
    } else {
        parse_config(planner, value)
    }
}

impl CleaningDwaConfig {
    /// Checks every number; the error names `prefix.field`.
    pub fn validate(&self, prefix: &str) -> Result<(), LocalError> {
        let p = prefix;
        check_param(p, "alpha", self.alpha, 0.0, false)?;
        check_param(p, "beta", self.beta, 0.0, false)?;
        check_param(p, "gamma", self.gamma, 0.0, false)?;
        check_param(p, "twirl (m·s/rad)", self.twirl, 0.0, false)?;
        check_param(p, "v_res (m/s)", self.v_res, 0.0, true)?;
        check_param(p, "w_res (rad/s)", self.w_res, 0.0, true)?;
        check_param(p, "sim_time (s)", self.sim_time, 0.0, true)?;
        check_param(p, "sim_dt (s)", self.sim_dt, 0.0, true)?;
        if self.sim_time / self.sim_dt > MAX_ROLLOUT_STEPS as f64 {
            return Err(LocalError::InvalidParameter(format!(
                "{p}.sim_time / sim_dt = {}: at most {MAX_ROLLOUT_STEPS} rollout steps",
                self.sim_time / self.sim_dt
            )));
        }
        if self.max_samples_per_axis == 0 || self.max_samples_per_axis > 1001 {
            return Err(LocalError::InvalidParameter(format!(
                "{p}.max_samples_per_axis = {}: must be 1…1001",
                self.max_samples_per_axis
            )));
        }
        check_param(p, "max_speed (m/s)", self.max_speed, 0.0, false)?;
        check_param(p, "inflation_radius (m)", self.inflation_radius, 0.0, false)?;
        check_param(p, "safety_distance (m)", self.safety_distance, 0.0, false)?;
        check_param(p, "cost_scaling (1/m)", self.cost_scaling, 0.0, false)?;
        check_param(p, "lookahead (m)", self.lookahead, 0.0, true)?;
        for (i, w) in self.waypoints.iter().enumerate() {
            if !(w[0].is_finite() && w[1].is_finite()) {
                return Err(LocalError::InvalidParameter(format!(
                    "{p}.waypoints[{i}] = ({}, {}): must be finite",
                    w[0], w[1]
                )));
            }
        }
        check_param(
            p,
            "waypoint_tolerance (m)",
            self.waypoint_tolerance,
            0.0,
            true,
        )?;
        check_param(p, "load_fraction", self.load_fraction, 0.0, false)?;
        if self.load_fraction >= 0.25 {
            return Err(LocalError::InvalidParameter(format!(
                "{p}.load_fraction = {}: must be < 0.25 (four wheels share m·g)",
                self.load_fraction
            )));
        }
        self.vehicle
            .validate(&format!("{p}.vehicle"))
            .map_err(|e| LocalError::InvalidParameter(e.to_string()))?;
        if self.accel_z_hold == 0 || self.accel_z_hold > 10_000 {
            return Err(LocalError::InvalidParameter(format!(
                "{p}.accel_z_hold = {}: must be 1…10000 periods",
                self.accel_z_hold
            )));
        }
        if self.window < 3 {
            return Err(LocalError::InvalidParameter(format!(
                "{p}.window = {}: must be ≥ 3 samples",
                self.window
            )));
        }
        if self.min_samples > self.window {
            return Err(LocalError::InvalidParameter(format!(
                "{p}.min_samples = {}: must not exceed window = {}",
                self.min_samples, self.window
            )));
        }
        check_param(p, "ridge", self.ridge, 0.0, false)
    }
}

/// 3×3 matrix, row-major.
pub type Mat3 = [[f64; 3]; 3];

fn mat_vec(k: &Mat3, u: [f64; 3]) -> [f64; 3] {
    [
        k[0][0] * u[0] + k[0][1] * u[1] + k[0][2] * u[2],
        k[1][0] * u[0] + k[1][1] * u[1] + k[1][2] * u[2],
        k[2][0] * u[0] + k[2][1] * u[1] + k[2][2] * u[2],
    ]
}

/// Inverse of `a`, or `None` when it is (numerically) singular: |det| at
/// most 1e-12 × the product of its row norms.
fn inverse(a: &Mat3) -> Option<Mat3> {
    let c00 = a[1][1] * a[2][2] - a[1][2] * a[2][1];
    let c01 = a[1][2] * a[2][0] - a[1][0] * a[2][2];
    let c02 = a[1][0] * a[2][1] - a[1][1] * a[2][0];
    let det = a[0][0] * c00 + a[0][1] * c01 + a[0][2] * c02;
    let norms: f64 = a
        .iter()
        .map(|r| (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt())
        .product();
    if !(det.is_finite() && norms.is_finite()) || det.abs() <= 1e-12 * norms || norms == 0.0 {
        return None;
    }
    let inv = 1.0 / det;
    Some([
        [
            c00 * inv,
            (a[0][2] * a[2][1] - a[0][1] * a[2][2]) * inv,
            (a[0][1] * a[1][2] - a[0][2] * a[1][1]) * inv,
        ],
        [
            c01 * inv,
            (a[0][0] * a[2][2] - a[0][2] * a[2][0]) * inv,
            (a[0][2] * a[1][0] - a[0][0] * a[1][2]) * inv,
        ],
        [
            c02 * inv,
            (a[0][1] * a[2][0] - a[0][0] * a[2][1]) * inv,
            (a[0][0] * a[1][1] - a[0][1] * a[1][0]) * inv,
        ],
    ])
}

/// Least-squares K with u* ≈ K u over `pairs` (wheel u, laser u*), pulled
/// toward `prior` with weight `ridge`·tr(Σuuᵀ)/3 (\[C\] eq 17). With
/// `structure` = [`KStructure::Block`] the translation (Δx, Δy) and the
/// rotation Δθ are fitted separately (the cross terms are 0). `None` when
/// the system is singular or the result not finite: keep the prior.
pub fn fit_k(
    pairs: &[([f64; 3], [f64; 3])],
    prior: &Mat3,
    ridge: f64,
    structure: KStructure,
) -> Option<Mat3> {
    let mut a = [[0.0; 3]; 3]; // Σ u uᵀ
    let mut b = [[0.0; 3]; 3]; // Σ u* uᵀ
    for (u, us) in pairs {
        for i in 0..3 {
            for j in 0..3 {
                a[i][j] += u[i] * u[j];
                b[i][j] += us[i] * u[j];
            }
        }
    }
    let mut prior = *prior;
    if structure == KStructure::Block {
        // Block-diagonal normal equations give a block-diagonal K.
        for i in 0..2 {
            for m in [&mut a, &mut b, &mut prior] {
                m[i][2] = 0.0;
                m[2][i] = 0.0;
            }
        }
    }
    let lambda = ridge * (a[0][0] + a[1][1] + a[2][2]) / 3.0;
    for i in 0..3 {
        a[i][i] += lambda;
        for j in 0..3 {
            b[i][j] += lambda * prior[i][j];
        }
    }
    let ai = inverse(&a)?;
    let mut k = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            k[i][j] = b[i][0] * ai[0][j] + b[i][1] * ai[1][j] + b[i][2] * ai[2][j];
        }
    }
    k.iter().flatten().all(|x| x.is_finite()).then_some(k)
}

/// Samples of one velocity axis: `now + i·res` within [lo, hi] (the window
/// ∩ the limits), plus lo and hi themselves; at most `max` (then evenly
/// spaced, `now` kept). `now` is clamped into [lo, hi] first.
fn axis_samples(now: f64, lo: f64, hi: f64, res: f64, max: usize) -> Vec<f64> {
    if lo > hi || lo.is_nan() || hi.is_nan() {
        return vec![now];
    }
    let now = now.clamp(lo, hi);
    let span = (hi - now).max(now - lo);
    let mut res = res;
    let n = (span / res + 1e-9).floor();
    if 2.0 * n + 1.0 > max as f64 {
        let half = ((max.saturating_sub(1)) / 2).max(1) as f64;
        res = span / half;
    }
    let mut out = vec![lo];
    let below = ((now - lo) / res + 1e-9).floor() as i64;
    let above = ((hi - now) / res + 1e-9).floor() as i64;
    for i in -below..=above {
        let v = now + i as f64 * res;
        if v > lo && v < hi {
            out.push(v);
        }
    }
    if hi > lo {
        out.push(hi);
    }
    if !out.contains(&now) {
        out.push(now);
    }
    out.sort_by(f64::total_cmp);
    out.dedup();
    out
}

/// L1 (Manhattan) distance from `p` to segment a–b: the convex piecewise
/// linear |p − a − t·d|₁ is smallest at t = 0, 1 or where one coordinate
/// crosses.
fn l1_to_segment(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let d = [b[0] - a[0], b[1] - a[1]];
    let f = |t: f64| (p[0] - a[0] - t * d[0]).abs() + (p[1] - a[1] - t * d[1]).abs();
    let mut best = f(0.0).min(f(1.0));
    for k in 0..2 {
        if d[k] != 0.0 {
            let t = ((p[k] - a[k]) / d[k]).clamp(0.0, 1.0);
            best = best.min(f(t));
        }
    }
    best
}

/// The global path as straight segments with cumulative arc length.
#[derive(Debug, Clone, Default)]
struct GlobalPath {
    pts: Vec<[f64; 2]>,
    /// Arc length at each point.
    s: Vec<f64>,
}

impl GlobalPath {
    fn new(raw: Vec<[f64; 2]>) -> Self {
        // Merge collinear runs (an A* path is mostly unit steps).
        let mut pts: Vec<[f64; 2]> = Vec::new();
        for p in raw {
            if let Some(&last) = pts.last() {
                if last == p {
                    continue;
                }
            }
            if pts.len() >= 2 {
                let (a, b) = (pts[pts.len() - 2], pts[pts.len() - 1]);
                let (d1, d2) = ([b[0] - a[0], b[1] - a[1]], [p[0] - b[0], p[1] - b[1]]);
                let cross = d1[0] * d2[1] - d1[1] * d2[0];
                let dot = d1[0] * d2[0] + d1[1] * d2[1];
                let scale = (d1[0] * d1[0] + d1[1] * d1[1]) * (d2[0] * d2[0] + d2[1] * d2[1]);
                if dot > 0.0 && cross * cross <= 1e-18 * scale {
                    let n = pts.len();
                    pts[n - 1] = p;
                    continue;
                }
            }
            pts.push(p);
        }
        let mut s = Vec::with_capacity(pts.len());
        let mut acc = 0.0;
        for (i, p) in pts.iter().enumerate() {
            if i > 0 {
                let q = pts[i - 1];
                acc += ((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1])).sqrt();
            }
            s.push(acc);
        }
        Self { pts, s }
    }

    fn length(&self) -> f64 {
        self.s.last().copied().unwrap_or(0.0)
    }

    /// The point at arc length `s` (clamped) and the segment it lies on.
    fn at(&self, s: f64) -> ([f64; 2], usize) {
        let n = self.pts.len();
        if n == 0 {
            return ([0.0, 0.0], 0);
        }
        if n == 1 || s <= 0.0 {
            return (self.pts[0], 0);
        }
        for i in 0..n - 1 {
            if s <= self.s[i + 1] || i == n - 2 {
                let len = self.s[i + 1] - self.s[i];
                let t = if len > 0.0 {
                    ((s - self.s[i]) / len).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                let (a, b) = (self.pts[i], self.pts[i + 1]);
                return ([a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])], i);
            }
        }
        (self.pts[n - 1], n - 2)
    }

    /// Projection of `p` onto segments `from..` within arc `s_max`:
    /// (segment, arc length, distance).
    fn project(&self, p: [f64; 2], from: usize, s_max: f64) -> Option<(usize, f64)> {
        let mut best: Option<(usize, f64, f64)> = None;
        for i in from..self.pts.len().saturating_sub(1) {
            if self.s[i] > s_max {
                break;
            }
            let (a, b) = (self.pts[i], self.pts[i + 1]);
            let d = [b[0] - a[0], b[1] - a[1]];
            let len2 = d[0] * d[0] + d[1] * d[1];
            let t = if len2 > 0.0 {
                (((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let q = [a[0] + t * d[0], a[1] + t * d[1]];
            let dist = ((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1])).sqrt();
            let s = self.s[i] + t * (self.s[i + 1] - self.s[i]);
            let better = match best {
                None => true,
                Some((_, _, bd)) => dist < bd,
            };
            if better {
                best = Some((i, s, dist));
            }
        }
        best.map(|(i, s, _)| (i, s))
    }
}

/// One evaluated sample.
#[derive(Debug, Clone, Copy)]
struct Sample {
    cmd: Command,
    admissible: bool,
    raw: [f64; 4],
    cost: f64,
}

/// The `cleaning-dwa` / `traditional-dwa` planner (see the module doc).
#[derive(Debug, Clone)]
pub struct CleaningDwa {
    name: &'static str,
    cfg: CleaningDwaConfig,
    robot: RobotSpec,
    /// Walls and unknown-as-obstacle cells of the map, as a grid.
    solid: OccupancyGrid,
    costmap: Costmap,
    res: f64,
    origin: [f64; 2],
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
    record: bool,
    debug: PlannerDebug,
}

impl CleaningDwa {
    /// Builds the planner registered as `name` (`cleaning-dwa` or
    /// `traditional-dwa`, used in error messages and [`LocalPlanner::name`])
    /// for `robot` on `map`, planning the global path from `start` through
    /// the waypoints to `goal`.
    pub fn new(
        name: &'static str,
        cfg: CleaningDwaConfig,
        robot: &RobotSpec,
        map: &StaticMap,
        start: &RobotState,
        goal: [f64; 2],
    ) -> Result<Self, LocalError> {
        cfg.validate(name)?;
        let grid = map.grid();
        let (w, h) = (grid.width(), grid.height());
        let cells = (0..h)
            .flat_map(|r| (0..w).map(move |c| (c, r)))
            .map(|(c, r)| {
                if map.is_blocked(c as i64, r as i64) {
                    Cell::Occupied
                } else {
                    Cell::Free
                }
            })
            .collect();
        let solid = OccupancyGrid::from_cells(w, h, cells)
            .and_then(|g| g.with_frame(grid.resolution(), grid.origin()))
            .map_err(|e| LocalError::InvalidParameter(format!("{name}: map: {e}")))?;
        let costmap = Costmap::ros(
            &solid,
            cfg.inflation_radius,
            cfg.inflation_radius + cfg.safety_distance,
            cfg.cost_scaling,
        )
        .map_err(|e| LocalError::InvalidParameter(format!("{name}: costmap: {e}")))?;
        let origin = grid.origin();
        let mut me = Self {
            name,
            res: grid.resolution(),
            origin: [origin.x, origin.y],
            solid,
            costmap,
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
            record: false,
            debug: PlannerDebug {
                critics: CRITICS.iter().map(|s| s.to_string()).collect(),
                current_goal: goal,
                keypoints: cfg.waypoints.clone(),
                mode: "normal".into(),
                ..Default::default()
            },
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

    fn cell_of(&self, p: [f64; 2], what: &str) -> Result<GridPos, LocalError> {
        self.solid
            .world_to_cell(p[0], p[1])
            .map(|(c, r)| GridPos::new(c as u32, r as u32))
            .ok_or_else(|| {
                LocalError::NoGlobalPath(format!(
                    "{what} ({:.3}, {:.3}) is off the map",
                    p[0], p[1]
                ))
            })
    }

    /// A* from `start` through `via` to `goal` on the inflated map (falling
    /// back to smaller inflations when an endpoint lies in the inflation).
    fn replan(
        &mut self,
        start: [f64; 2],
        via: &[[f64; 2]],
        goal: [f64; 2],
    ) -> Result<(), LocalError> {
        let mut stops = vec![(start, "start".to_string())];
        for (i, w) in via.iter().enumerate() {
            stops.push((*w, format!("{}.waypoints[{i}]", self.name)));
        }
        stops.push((goal, "goal".to_string()));
        let mut raw: Vec<[f64; 2]> = vec![start];
        let mut arcs = Vec::new();
        for leg in stops.windows(2) {
            let (a, b) = (&leg[0], &leg[1]);
            let (ca, cb) = (self.cell_of(a.0, &a.1)?, self.cell_of(b.0, &b.1)?);
            let radii = [
                self.cfg.inflation_radius + self.cfg.safety_distance,
                self.cfg.inflation_radius,
                0.0,
            ];
            let mut result = None;
            for r in radii {
                let opts = GridPlanOptions {
                    algorithm: Algorithm::AStar,
                    inflate_m: r,
                    ..Default::default()
                };
                match plan_on_map(&self.solid, ca, cb, &opts, false) {
                    Err(GridPlanError::BlockedByInflation { .. }) => continue,
                    other => {
                        result = Some(other);
                        break;
                    }
                }
            }
            let plan = result
                .unwrap_or_else(|| {
                    Err(GridPlanError::Plan(
                        crate::global::PlanError::InvalidConfig("no inflation radius works".into()),
                    ))
                })
                .map_err(|e| LocalError::NoGlobalPath(format!("{} → {}: {e}", a.1, b.1)))?;
            let cells = &plan.path.cells;
            // Interior cells as centres; the leg's end is the exact point.
            for c in cells.iter().skip(1).take(cells.len().saturating_sub(2)) {
                let (x, y) = self.solid.cell_to_world(c.col as usize, c.row as usize);
                raw.push([x, y]);
            }
            raw.push(b.0);
            arcs.push((raw.len() - 1, b.0));
        }
        // Arc length of each leg end along the raw path (merging collinear
        // points below keeps lengths).
        let mut cum = vec![0.0; raw.len()];
        for i in 1..raw.len() {
            let (p, q) = (raw[i - 1], raw[i]);
            cum[i] =
                cum[i - 1] + ((q[0] - p[0]) * (q[0] - p[0]) + (q[1] - p[1]) * (q[1] - p[1])).sqrt();
        }
        self.stops = arcs
            .iter()
            .take(via.len())
            .map(|&(i, p)| (cum[i], p))
            .collect();
        self.next_stop = 0;
        self.path = GlobalPath::new(raw);
        self.seg = 0;
        self.s_robot = 0.0;
        self.goal = goal;
        self.debug.global_path = self.path.pts.clone();
        Ok(())
    }

    /// Local goal, its kind and the local path (projection → local goal).
    fn local_goal(&mut self, p: [f64; 2]) -> ([f64; 2], GoalKind, Vec<[f64; 2]>) {
        let la = self.lookahead();
        let (seg, s) = self
            .path
            .project(p, self.seg, self.s_robot + 2.0 * la)
            .unwrap_or((self.seg, self.s_robot));
        self.seg = seg;
        self.s_robot = s;
        let mut total = self.path.length();
        if self.cfg.stop_at_waypoints {
            let tol = self.cfg.waypoint_tolerance;
            while let Some(&(_, w)) = self.stops.get(self.next_stop) {
                if (w[0] - p[0]) * (w[0] - p[0]) + (w[1] - p[1]) * (w[1] - p[1]) <= tol * tol {
                    self.next_stop += 1;
                } else {
                    break;
                }
            }
            if let Some(&(arc, _)) = self.stops.get(self.next_stop) {
                total = total.min(arc);
            }
        }
        let s_goal = (s + la).min(total);
        let (proj, _) = self.path.at(s);
        let (g, g_seg) = self.path.at(s_goal);
        let mut local = vec![proj];
        for i in seg + 1..=g_seg {
            if let Some(&q) = self.path.pts.get(i) {
                local.push(q);
            }
        }
        local.push(g);
        let kind = if s_goal >= self.path.length() {
            GoalKind::Final
        } else {
            GoalKind::Intermediate
        };
        (g, kind, local)
    }

    /// The lookahead in force: the configured one, but at least 1.25 times
    /// the farthest a rollout reaches (v_max·sim_time), so the local goal
    /// stays out of reach and progress, not an exact hit, decides.
    fn lookahead(&self) -> f64 {
        let l = &self.robot.limits;
        let reach = l.v_max.max(-l.v_min).max(l.vy_max) * self.cfg.sim_time;
        self.cfg.lookahead.max(1.25 * reach)
    }

    fn push_odometry(&mut self, obs: &Observation<'_>) {
        let Some(o) = obs.odometry else { return };
        let finite = o.wheel.iter().chain(&o.laser).all(|x| x.is_finite());
        let moved = o.wheel.iter().map(|x| x * x).sum::<f64>() > 1e-12;
        if !(finite && moved) {
            return;
        }
        self.odo.push_back((o.wheel, o.laser));
        while self.odo.len() > self.cfg.window {
            self.odo.pop_front();
        }
        if self.odo.len() >= self.cfg.min_samples.max(3) {
            let pairs: Vec<_> = self.odo.iter().copied().collect();
            if let Some(k) = fit_k(&pairs, &self.k, self.cfg.ridge, self.cfg.k_structure) {
                self.k = k;
            }
        }
    }

    /// The sampled window (v_x, v_y, ω lists) and whether the load limit
    /// bound; samples violating the diamond are dropped later.
    fn window(&self, obs: &Observation<'_>) -> (Vec<f64>, Vec<f64>, Vec<f64>, Option<f64>) {
        let l = &self.robot.limits;
        let s = obs.state;
        let dt = obs.dt.max(0.0);
        let max = self.cfg.max_samples_per_axis;
        // Eq 14 bound on |a_x|, |a_y| (None: no load limit).
        let bound = self.cfg.load_limit.then(|| {
            let j = self.cfg.load_fraction;
            let veh = &self.cfg.vehicle;
            let az = self.az_estimate;
            let b = if veh.h > 0.0 {
                (GRAVITY - 4.0 * j * GRAVITY - az) * veh.l_r / veh.h
            } else {
                f64::INFINITY
            };
            b.max(0.0)
        });
        let (mut ax, mut ay) = (l.acc_v, l.acc_vy);
        if let (Some(b), LoadRegion::Box) = (bound, self.cfg.load_region) {
            ax = ax.min(b);
            ay = ay.min(b);
        }
        let vx = axis_samples(
            s.v,
            l.v_min.max(s.v - ax * dt),
            l.v_max.min(s.v + ax * dt),
            self.cfg.v_res,
            max,
        );
        let vy = match self.robot.drive {
            Drive::Differential => vec![0.0],
            Drive::Omnidirectional => axis_samples(
                s.vy,
                (-l.vy_max).max(s.vy - ay * dt),
                l.vy_max.min(s.vy + ay * dt),
                self.cfg.v_res,
                max,
            ),
        };
        let w = axis_samples(
            s.w,
            (-l.w_max).max(s.w - l.acc_w * dt),
            l.w_max.min(s.w + l.acc_w * dt),
            self.cfg.w_res,
            max,
        );
        (vx, vy, w, bound)
    }

    /// Smallest wheel load minus j·m·g (N) after accelerating to (vx, vy)
    /// in one period (\[C\] eq 8 with the measured a_z); ≥ 0 is allowed.
    /// Keeping the velocity is always allowed (+∞).
    fn load_margin(&self, obs: &Observation<'_>, vx: f64, vy: f64) -> f64 {
        let s = obs.state;
        if (vx == s.v && vy == s.vy) || obs.dt <= 0.0 {
            return f64::INFINITY;
        }
        let az = self.az_estimate;
        let veh = &self.cfg.vehicle;
        let min = self.cfg.load_fraction * veh.mass * GRAVITY;
        let loads = veh.wheel_loads((vx - s.v) / obs.dt, (vy - s.vy) / obs.dt, az);
        loads.iter().fold(f64::INFINITY, |a, &f| a.min(f)) - min
    }

    /// Rolls `cmd` out; returns (admissible, raw critics) and fills
    /// `points` when given.
    #[allow(clippy::too_many_arguments)]
    fn rollout(
        &self,
        obs: &Observation<'_>,
        cmd: Command,
        steps: usize,
        goal: [f64; 2],
        local: &[[f64; 2]],
        radius: f64,
        free: bool,
        mut points: Option<&mut Vec<[f64; 2]>>,
    ) -> (bool, [f64; 3]) {
        let dt = self.cfg.sim_dt;
        let inc = mat_vec(&self.k, [cmd.v * dt, cmd.vy * dt, cmd.w * dt]);
        let s = obs.state;
        let (mut x, mut y) = (s.x, s.y);
        let (mut sn, mut cs) = (sin(s.theta), cos(s.theta));
        let (sd, cd) = (sin(inc[2]), cos(inc[2]));
        let (w, h) = (self.costmap.width as i64, self.costmap.height as i64);
        let mut c_obs = 0.0;
        let mut ok = true;
        for k in 1..=steps {
            x += cs * inc[0] - sn * inc[1];
            y += sn * inc[0] + cs * inc[1];
            (sn, cs) = (sn * cd + cs * sd, cs * cd - sn * sd);
            if let Some(p) = points.as_deref_mut() {
                p.push([x, y]);
            }
            if free || !ok {
                continue;
            }
            let t = k as f64 * dt;
            let col = ((x - self.origin[0]) / self.res).floor();
            let row_b = ((y - self.origin[1]) / self.res).floor();
            let on_map = col >= 0.0 && row_b >= 0.0 && (col as i64) < w && (row_b as i64) < h;
            ok = on_map
                && obs.map.clearance(x, y) > radius
                && obs.movers.iter().all(|m| {
                    let (mx, my) = (m.pos[0] + m.vel[0] * t, m.pos[1] + m.vel[1] * t);
                    let r = radius + m.radius;
                    (mx - x) * (mx - x) + (my - y) * (my - y) > r * r
                });
            if !ok {
                if points.is_none() {
                    break;
                }
                continue;
            }
            let idx = (h - 1 - row_b as i64) * w + col as i64;
            let c = self
                .costmap
                .costs
                .get(idx as usize)
                .copied()
                .unwrap_or(INSCRIBED);
            c_obs += f64::from(c) / COST_SCALE;
        }
        let d_g = (x - goal[0]).abs() + (y - goal[1]).abs();
        let d_p = local
            .windows(2)
            .map(|sgm| l1_to_segment([x, y], sgm[0], sgm[1]))
            .fold(f64::INFINITY, f64::min);
        let d_p = if d_p.is_finite() {
            d_p
        } else {
            local
                .first()
                .map_or(0.0, |q| (x - q[0]).abs() + (y - q[1]).abs())
        };
        (ok, [c_obs, d_g, d_p])
    }
}

impl LocalPlanner for CleaningDwa {
    fn name(&self) -> &'static str {
        self.name
    }

    fn step(&mut self, obs: &Observation<'_>) -> Command {
        if self.cfg.compensate {
            self.push_odometry(obs);
        }
        let az = if obs.accel_z.is_finite() {
            obs.accel_z
        } else {
            0.0
        };
        self.az_recent.push_back(az);
        while self.az_recent.len() > self.cfg.accel_z_hold {
            self.az_recent.pop_front();
        }
        self.az_estimate = self
            .az_recent
            .iter()
            .copied()
            .fold(f64::NEG_INFINITY, f64::max);
        let s = obs.state;
        let (goal, kind, local) = self.local_goal([s.x, s.y]);
        self.debug.current_goal = goal;
        self.debug.goal_kind = kind;
        let steps =
            ((self.cfg.sim_time / self.cfg.sim_dt).round() as usize).clamp(1, MAX_ROLLOUT_STEPS);
        // The clearance field may overestimate by up to a third of a cell:
        // half a cell of margin keeps "admissible" collision-free.
        let radius = self.robot.footprint.circumscribed_radius() + 0.5 * self.res;
        let (vxs, vys, ws, bound) = self.window(obs);
        let diamond = bound.is_some() && self.cfg.load_region == LoadRegion::Diamond;
        // Shown as mode "load-limited" when eq 14's bound is tighter than
        // the motors' acceleration limit.
        let limited =
            bound.is_some_and(|b| b < self.robot.limits.acc_v.max(self.robot.limits.acc_vy));
        let vmax = if self.cfg.max_speed > 0.0 {
            self.cfg.max_speed
        } else {
            self.robot.limits.v_max
        };
        // Translational samples: the (v_x, v_y) grid, with samples faster
        // than vmax scaled back onto the circle |v| = vmax (dropping those
        // that then leave the window) so every direction offers the full
        // speed and no body heading is favoured by the grid.
        let (xlo, xhi) = (
            vxs.first().copied().unwrap_or(s.v),
            vxs.last().copied().unwrap_or(s.v),
        );
        let (ylo, yhi) = (
            vys.first().copied().unwrap_or(s.vy),
            vys.last().copied().unwrap_or(s.vy),
        );
        let mut pairs: Vec<(f64, f64)> = Vec::with_capacity(vxs.len() * vys.len());
        // The sample that keeps the most load, in case none keeps enough.
        let mut least_bad: Option<(f64, (f64, f64))> = None;
        for &vx in &vxs {
            for &vy in &vys {
                let n2 = vx * vx + vy * vy;
                let (vx, vy) = if n2 > vmax * vmax && (vx, vy) != (s.v, s.vy) {
                    let f = vmax / n2.sqrt();
                    (vx * f, vy * f)
                } else {
                    (vx, vy)
                };
                let eps = 1e-12;
                if vx < xlo - eps || vx > xhi + eps || vy < ylo - eps || vy > yhi + eps {
                    continue;
                }
                if pairs.contains(&(vx, vy)) {
                    continue;
                }
                if diamond {
                    let margin = self.load_margin(obs, vx, vy);
                    if margin < 0.0 {
                        let better = match least_bad {
                            None => true,
                            Some((m, _)) => margin > m,
                        };
                        if better {
                            least_bad = Some((margin, (vx, vy)));
                        }
                        continue;
                    }
                }
                pairs.push((vx, vy));
            }
        }
        if pairs.is_empty() {
            // Even holding the velocity overloads (a_z beyond g(1 − 4j)):
            // take the gentlest sample rather than braking hard.
            if let Some((_, p)) = least_bad {
                pairs.push(p);
            }
        }
        // Far from every wall and mover no rollout can collide or enter the
        // cost band: skip the per-point checks (same result, much faster in
        // open yards). Reach ≤ ‖K_xy‖_F·|(v_x, v_y, ω)|·T.
        let vt = pairs
            .iter()
            .map(|&(a, b)| a * a + b * b)
            .fold(0.0, f64::max);
        let wm = ws.iter().map(|w| w * w).fold(0.0, f64::max);
        let kf = self.k[..2]
            .iter()
            .flatten()
            .map(|k| k * k)
            .sum::<f64>()
            .sqrt();
        let reach = kf * (vt + wm).sqrt() * steps as f64 * self.cfg.sim_dt;
        let band = self.cfg.inflation_radius + self.cfg.safety_distance;
        let free = obs.movers.is_empty()
            && obs.map.clearance(s.x, s.y) > reach + radius + band + 2.0 * self.res;
        let mut samples: Vec<Sample> = Vec::with_capacity(pairs.len() * ws.len());
        let mut all_points: Vec<Vec<[f64; 2]>> = Vec::new();
        for &w in &ws {
            for &(vx, vy) in &pairs {
                {
                    let cmd = Command { v: vx, vy, w };
                    let mut pts = self.record.then(|| Vec::with_capacity(steps));
                    let (ok, r) =
                        self.rollout(obs, cmd, steps, goal, &local, radius, free, pts.as_mut());
                    let raw = [r[0], r[1], r[2], w.abs()];
                    let cost = self.cfg.alpha * raw[0]
                        + self.cfg.beta * raw[1]
                        + self.cfg.gamma * raw[2]
                        + self.cfg.twirl * raw[3];
                    samples.push(Sample {
                        cmd,
                        admissible: ok && cost.is_finite(),
                        raw,
                        cost,
                    });
                    if let Some(p) = pts {
                        all_points.push(p);
                    }
                }
            }
        }
        let best = samples
            .iter()
            .enumerate()
            .filter(|(_, c)| c.admissible)
            .fold(None::<(usize, f64)>, |b, (i, c)| match b {
                Some((_, bc)) if bc <= c.cost => b,
                _ => Some((i, c.cost)),
            })
            .map(|(i, _)| i);
        let mut sums = [0.0; 4];
        for c in samples.iter().filter(|c| c.admissible) {
            for (s, r) in sums.iter_mut().zip(c.raw) {
                *s += r;
            }
        }
        let to_rollout = |c: &Sample, points: Vec<[f64; 2]>| Rollout {
            cmd: c.cmd,
            points,
            admissible: c.admissible,
            raw: c.raw.to_vec(),
            normalised: c
                .raw
                .iter()
                .zip(sums)
                .map(|(r, s)| if s > 0.0 { r / s } else { 0.0 })
                .collect(),
            score: -c.cost,
        };
        self.debug.mode = match (best, limited) {
            (None, _) => "no-admissible",
            (Some(_), true) => "load-limited",
            (Some(_), false) => "normal",
        }
        .into();
        if self.record {
            self.debug.rollouts = samples
                .iter()
                .zip(all_points)
                .map(|(c, p)| to_rollout(c, p))
                .collect();
            self.debug.chosen = best;
        } else {
            self.debug.rollouts.clear();
            self.debug.chosen = None;
            if let Some(i) = best {
                let c = samples[i];
                let mut pts = Vec::with_capacity(steps);
                self.rollout(
                    obs,
                    c.cmd,
                    steps,
                    goal,
                    &local,
                    radius,
                    free,
                    Some(&mut pts),
                );
                self.debug.rollouts.push(to_rollout(&c, pts));
                self.debug.chosen = Some(0);
            }
        }
        match best {
            Some(i) => samples[i].cmd,
            // Nothing admissible: brake (the motors' limits shape it).
            None => Command::default(),
        }
    }

    fn set_goal(
        &mut self,
        _map: &StaticMap,
        state: &RobotState,
        goal: [f64; 2],
    ) -> Result<(), LocalError> {
        if !(goal[0].is_finite() && goal[1].is_finite()) {
            return Err(LocalError::InvalidParameter(format!(
                "goal ({}, {}) must be finite",
                goal[0], goal[1]
            )));
        }
        // The cleaning targets belonged to the old route: go straight there
        // (on error nothing changes).
        self.replan([state.x, state.y], &[], goal)?;
        self.debug.keypoints.clear();
        self.debug.current_goal = goal;
        Ok(())
    }

    fn debug(&self) -> &PlannerDebug {
        &self.debug
    }

    fn set_record_rollouts(&mut self, on: bool) {
        self.record = on;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::local::registry::{build, PlannerChoice};
    use crate::local::testkit;
    use crate::local::OdometrySample;
    use crate::num::Rng;
    use crate::world::terrain::{SlipSpec, Terrain, TerrainSpec};
    use crate::world::{Footprint, RobotLimits};
    use serde_json::json;

    fn robot() -> RobotSpec {
        RobotSpec {
            drive: Drive::Omnidirectional,
            footprint: Footprint::Circle { radius: 0.35 },
            limits: RobotLimits {
                v_max: 0.4,
                v_min: -0.4,
                vy_max: 0.4,
                w_max: 1.0,
                acc_v: 2.0,
                acc_vy: 2.0,
                acc_w: 1.0,
            },
            wheel_base: 0.5,
        }
    }

    /// A 10 × 6 m walled yard at 0.05 m per cell, optionally with a box.
    fn yard(with_box: bool) -> StaticMap {
        let (w, h) = (200, 120);
        let mut rows = Vec::new();
        for r in 0..h {
            let mut line = String::new();
            for c in 0..w {
                let edge = r == 0 || c == 0 || r == h - 1 || c == w - 1;
                // Box around (5, 3) m: cols 95–104, rows 55–64.
                let boxed = with_box && (95..105).contains(&c) && (55..65).contains(&r);
                line.push(if edge || boxed { '#' } else { '.' });
            }
            rows.push(line);
        }
        testkit::map(&rows.join("\n"), 0.05)
    }

    fn planner(
        name: &str,
        config: serde_json::Value,
        map: &StaticMap,
        start: &RobotState,
        goal: [f64; 2],
    ) -> CleaningDwa {
        let name: &'static str = if name == "cleaning-dwa" {
            "cleaning-dwa"
        } else {
            "traditional-dwa"
        };
        CleaningDwa::new(
            name,
            parse(name, &config).unwrap(),
            &robot(),
            map,
            start,
            goal,
        )
        .unwrap()
    }

    fn obs<'a>(state: &'a RobotState, map: &'a StaticMap, accel_z: f64) -> Observation<'a> {
        Observation {
            time: 0.0,
            dt: 0.1,
            state,
            goal: [8.0, 3.0],
            map,
            movers: &[],
            odometry: None,
            accel_z,
        }
    }

    #[test]
    fn least_squares_recovers_a_known_k() {
        let k_true = [[0.93, 0.02, 0.01], [0.06, 0.97, -0.02], [0.01, 0.0, 0.9]];
        let mut rng = Rng::new(4);
        let pairs: Vec<_> = (0..60)
            .map(|_| {
                let u = [
                    rng.range(0.0, 0.04),
                    rng.range(-0.03, 0.03),
                    rng.range(-0.1, 0.1),
                ];
                let mut us = mat_vec(&k_true, u);
                for x in &mut us {
                    *x += 2e-4 * rng.normal();
                }
                (u, us)
            })
            .collect();
        let k = fit_k(&pairs, &IDENTITY, 0.0, KStructure::Full).unwrap();
        for i in 0..3 {
            for j in 0..3 {
                assert!((k[i][j] - k_true[i][j]).abs() < 0.02, "{k:?}");
            }
        }
        // A small ridge changes little when every direction is excited.
        let kr = fit_k(&pairs, &IDENTITY, 0.01, KStructure::Full).unwrap();
        assert!((kr[1][0] - 0.06).abs() < 0.02, "{kr:?}");
    }

    #[test]
    fn singular_system_keeps_the_previous_k() {
        // Never turning, never moving sideways: Σuuᵀ has rank 1.
        let pairs: Vec<_> = (0..20)
            .map(|i| {
                let u = [0.03 + 1e-4 * i as f64, 0.0, 0.0];
                (u, [0.9 * u[0], 0.05 * u[0], 0.0])
            })
            .collect();
        assert_eq!(fit_k(&pairs, &IDENTITY, 0.0, KStructure::Full), None);
        assert_eq!(fit_k(&[], &IDENTITY, 0.0, KStructure::Block), None);
        // With the ridge the excited column is fitted, the others stay.
        let k = fit_k(&pairs, &IDENTITY, 0.01, KStructure::Full).unwrap();
        assert!(
            (k[0][0] - 0.9).abs() < 0.02 && (k[1][0] - 0.05).abs() < 0.01,
            "{k:?}"
        );
        assert_eq!([k[0][1], k[1][1], k[2][2]], [0.0, 1.0, 1.0]);
        // In the planner: ridge 0 and degenerate samples leave the identity.
        let map = yard(false);
        let s = RobotState {
            x: 1.0,
            y: 3.0,
            ..Default::default()
        };
        let mut p = planner("cleaning-dwa", json!({"ridge": 0.0}), &map, &s, [8.0, 3.0]);
        for (u, us) in &pairs {
            let mut o = obs(&s, &map, 0.0);
            o.odometry = Some(OdometrySample {
                wheel: *u,
                laser: *us,
            });
            let c = p.step(&o);
            assert!(c.v.is_finite() && c.vy.is_finite() && c.w.is_finite());
        }
        assert_eq!(p.k(), IDENTITY);
        // Non-finite samples are ignored.
        let mut o = obs(&s, &map, 0.0);
        o.odometry = Some(OdometrySample {
            wheel: [f64::NAN, 0.0, 0.0],
            laser: [0.0; 3],
        });
        p.step(&o);
        assert_eq!(p.k(), IDENTITY);
    }

    #[test]
    fn compensated_rollout_predicts_the_slipping_motion() {
        let k_true = [[0.9, 0.03, 0.0], [0.08, 0.95, 0.0], [0.0, 0.0, 0.85]];
        let map = yard(false);
        let s = RobotState {
            x: 2.0,
            y: 3.0,
            theta: 0.4,
            ..Default::default()
        };
        let mut p = planner("cleaning-dwa", json!({}), &map, &s, [8.0, 3.0]);
        p.k = k_true;
        let cmd = Command {
            v: 0.3,
            vy: -0.1,
            w: 0.5,
        };
        let mut pts = Vec::new();
        let o = obs(&s, &map, 0.0);
        let (ok, _) = p.rollout(
            &o,
            cmd,
            20,
            [8.0, 3.0],
            &[[2.0, 3.0], [8.0, 3.0]],
            0.35,
            false,
            Some(&mut pts),
        );
        assert!(ok);
        let spec = TerrainSpec {
            slip: SlipSpec {
                k_true,
                ..Default::default()
            },
            ..Default::default()
        };
        let mut t = Terrain::new(spec, 0).unwrap();
        let mut st = s;
        for q in &pts {
            st = t.step(&st, cmd, 0.1).next;
            assert!(
                (st.x - q[0]).abs() < 1e-9 && (st.y - q[1]).abs() < 1e-9,
                "{st:?} vs {q:?}"
            );
        }
        // The uncompensated prediction misses by centimetres.
        p.k = IDENTITY;
        let mut ideal = Vec::new();
        p.rollout(
            &o,
            cmd,
            20,
            [8.0, 3.0],
            &[[2.0, 3.0], [8.0, 3.0]],
            0.35,
            false,
            Some(&mut ideal),
        );
        let (a, b) = (ideal[19], pts[19]);
        assert!((a[0] - b[0]).abs() + (a[1] - b[1]).abs() > 0.05);
    }

    #[test]
    fn heads_along_the_path_whatever_the_heading() {
        let map = yard(false);
        for theta in [0.0, std::f64::consts::FRAC_PI_2, 2.5] {
            let s = RobotState {
                x: 1.0,
                y: 3.0,
                theta,
                ..Default::default()
            };
            let mut p = planner("cleaning-dwa", json!({}), &map, &s, [8.0, 3.0]);
            p.set_record_rollouts(true);
            let c = p.step(&obs(&s, &map, 0.0));
            // World velocity of the command: east, at the window's edge.
            let (sn, cs) = (sin(theta), cos(theta));
            let (ve, vn) = (c.v * cs - c.vy * sn, c.v * sn + c.vy * cs);
            assert!(
                ve > 0.15 && vn.abs() < 0.05,
                "θ {theta}: {c:?} → ({ve}, {vn})"
            );
            let d = p.debug();
            assert_eq!(d.goal_kind, GoalKind::Intermediate);
            assert!(
                (d.current_goal[0] - 2.5).abs() < 0.01 && (d.current_goal[1] - 3.0).abs() < 0.05
            );
            assert!(d.rollouts.len() > 1000, "{}", d.rollouts.len());
            let ch = &d.rollouts[d.chosen.unwrap()];
            assert_eq!(ch.cmd, c);
            assert!(d
                .rollouts
                .iter()
                .filter(|r| r.admissible)
                .all(|r| r.score <= ch.score));
            assert_eq!(ch.raw.len(), 4);
            assert!(
                (ch.score + 0.1 * ch.raw[0] + 0.3 * ch.raw[1] + 0.6 * ch.raw[2] + 0.1 * ch.raw[3])
                    .abs()
                    < 1e-9
            );
        }
    }

    #[test]
    fn global_path_goes_through_the_waypoints_around_the_box() {
        let map = yard(true);
        let s = RobotState {
            x: 1.0,
            y: 3.0,
            ..Default::default()
        };
        let p = planner(
            "cleaning-dwa",
            json!({"waypoints": [[3.0, 1.5]]}),
            &map,
            &s,
            [8.0, 3.0],
        );
        let path = &p.debug().global_path;
        assert_eq!(path[0], [1.0, 3.0]);
        assert_eq!(*path.last().unwrap(), [8.0, 3.0]);
        let near = |q: [f64; 2]| {
            path.windows(2)
                .any(|w| crate::geom::distance_to_polyline(q, w).unwrap() < 0.05)
        };
        assert!(near([3.0, 1.5]));
        // Every vertex keeps the robot radius from the box (and walls).
        for q in path {
            assert!(map.clearance(q[0], q[1]) >= 0.3, "{q:?}");
        }
    }

    #[test]
    fn stops_at_every_waypoint_when_asked() {
        let map = yard(false);
        let s = RobotState {
            x: 1.0,
            y: 3.0,
            ..Default::default()
        };
        let wps = json!({"waypoints": [[3.0, 3.0], [5.0, 3.0]], "stop_at_waypoints": true});
        let mut p = planner("cleaning-dwa", wps, &map, &s, [8.0, 3.0]);
        let r = testkit::run(&mut p, &map, &robot(), s, [8.0, 3.0], &[], 60.0, 0.2);
        assert_eq!(r.end, testkit::End::Reached);
        // Near each waypoint the robot slowed almost to a stop.
        for w in [3.0, 5.0] {
            let slowest = r
                .states
                .iter()
                .filter(|st| (st.x - w).abs() < 0.15)
                .map(|st| st.v.hypot(st.vy))
                .fold(f64::INFINITY, f64::min);
            assert!(slowest < 0.08, "at x = {w}: {slowest}");
        }
        // Passing through, it keeps its speed there.
        let mut p = planner(
            "cleaning-dwa",
            json!({"waypoints": [[3.0, 3.0], [5.0, 3.0]]}),
            &map,
            &s,
            [8.0, 3.0],
        );
        let r = testkit::run(&mut p, &map, &robot(), s, [8.0, 3.0], &[], 60.0, 0.2);
        let at3 = r
            .states
            .iter()
            .filter(|st| (st.x - 3.0).abs() < 0.15)
            .map(|st| st.v.hypot(st.vy))
            .fold(f64::INFINITY, f64::min);
        assert!(at3 > 0.3, "{at3}");
    }

    #[test]
    fn drives_around_an_obstacle_to_the_goal() {
        let map = yard(true);
        for name in ["cleaning-dwa", "traditional-dwa"] {
            let s = RobotState {
                x: 1.0,
                y: 3.0,
                ..Default::default()
            };
            let mut p = planner(name, json!({}), &map, &s, [8.5, 3.0]);
            let r = testkit::run(&mut p, &map, &robot(), s, [8.5, 3.0], &[], 60.0, 0.2);
            assert_eq!(
                r.end,
                testkit::End::Reached,
                "{name}: {:?}",
                r.states.last()
            );
            assert!(r.min_clearance > 0.05, "{name}: {}", r.min_clearance);
        }
    }

    #[test]
    fn load_limit_shrinks_the_window() {
        let map = yard(false);
        let s = RobotState {
            x: 1.0,
            y: 3.0,
            ..Default::default()
        };
        let veh = VehicleSpec::default();
        let jmg = 0.2 * veh.mass * GRAVITY;
        for az in [0.0, 0.8, 1.5] {
            let mut trad = planner("traditional-dwa", json!({}), &map, &s, [8.0, 3.0]);
            let mut clean = planner("cleaning-dwa", json!({}), &map, &s, [8.0, 3.0]);
            let ct = trad.step(&obs(&s, &map, az));
            let cc = clean.step(&obs(&s, &map, az));
            // From rest the baseline jumps to the full 2 m/s².
            assert!((ct.v - 0.2).abs() < 1e-9, "{ct:?}");
            let loads = veh.wheel_loads(cc.v / 0.1, cc.vy / 0.1, az);
            assert!(
                loads.iter().all(|&f| f >= jmg - 1e-9),
                "a_z {az}: {cc:?} {loads:?}"
            );
            let bound = (GRAVITY - 0.8 * GRAVITY - az) * 1.25;
            assert!(
                cc.v / 0.1 <= bound.min(2.0) + 1e-9 && cc.v > 0.0,
                "a_z {az}: {cc:?}"
            );
            if az > 0.5 {
                assert_eq!(clean.debug().mode, "load-limited");
            }
        }
        // Beyond g(1 − 4j) no acceleration is allowed: keep the velocity.
        let moving = RobotState {
            v: 0.25,
            vy: 0.05,
            ..s
        };
        let mut clean = planner("cleaning-dwa", json!({}), &map, &moving, [8.0, 3.0]);
        let c = clean.step(&obs(&moving, &map, 2.5));
        assert_eq!((c.v, c.vy), (0.25, 0.05));
        // The per-axis (eq 14) variant allows up to the bound on each axis.
        let mut boxed = planner(
            "cleaning-dwa",
            json!({"load_region": "box"}),
            &map,
            &s,
            [8.0, 3.0],
        );
        let c = boxed.step(&obs(&s, &map, 1.5));
        assert!(c.v / 0.1 <= (0.2 * GRAVITY - 1.5) * 1.25 + 1e-9, "{c:?}");
    }

    #[test]
    fn axis_samples_are_centred_and_bounded() {
        let s = axis_samples(0.1, -0.1, 0.3, 0.02, 41);
        assert!(s.contains(&0.1) && s.contains(&-0.1) && s.contains(&0.3));
        assert_eq!(s.len(), 21);
        let s = axis_samples(0.29, 0.09, 0.3, 0.02, 41);
        assert_eq!(*s.last().unwrap(), 0.3);
        assert!(s.contains(&0.29));
        let s = axis_samples(0.0, -0.2, 0.2, 0.0001, 41);
        assert!(s.len() <= 43 && s.contains(&0.0));
        assert_eq!(axis_samples(0.5, 0.0, 0.0, 0.02, 41), vec![0.0]);
        assert!((l1_to_segment([1.0, 2.0], [0.0, 0.0], [4.0, 0.0]) - 2.0).abs() < 1e-12);
        assert!((l1_to_segment([1.0, 1.0], [0.0, 0.0], [2.0, 2.0])).abs() < 1e-12);
        assert!((l1_to_segment([-1.0, 1.0], [0.0, 0.0], [2.0, 0.0]) - 2.0).abs() < 1e-12);
    }

    #[test]
    fn bad_config_names_the_field() {
        let map = yard(false);
        let s = RobotState {
            x: 1.0,
            y: 3.0,
            ..Default::default()
        };
        let err = |name: &str, cfg: serde_json::Value, want: &str| {
            let choice = PlannerChoice {
                name: name.into(),
                config: cfg,
            };
            let e = build(&choice, &robot(), &map, &s, [8.0, 3.0])
                .err()
                .unwrap()
                .to_string();
            assert!(e.contains(want), "{e} / {want}");
        };
        err("cleaning-dwa", json!({"alpha": -1.0}), "cleaning-dwa.alpha");
        err("cleaning-dwa", json!({"v_res": 0.0}), "cleaning-dwa.v_res");
        err(
            "traditional-dwa",
            json!({"lookahead": -0.5}),
            "traditional-dwa.lookahead",
        );
        err(
            "cleaning-dwa",
            json!({"load_fraction": 0.3}),
            "cleaning-dwa.load_fraction",
        );
        err(
            "cleaning-dwa",
            json!({"vehicle": {"mass": -1.0}}),
            "cleaning-dwa.vehicle.mass",
        );
        err("cleaning-dwa", json!({"window": 1}), "cleaning-dwa.window");
        err(
            "cleaning-dwa",
            json!({"min_samples": 60}),
            "cleaning-dwa.min_samples",
        );
        err(
            "cleaning-dwa",
            json!({"accel_z_hold": 0}),
            "cleaning-dwa.accel_z_hold",
        );
        err(
            "cleaning-dwa",
            json!({"twirl": f64::NAN}),
            "cleaning-dwa.config",
        );
        err("cleaning-dwa", json!({"twirl": -1.0}), "cleaning-dwa.twirl");
        err(
            "cleaning-dwa",
            json!({"waypoint_tolerance": 0.0}),
            "cleaning-dwa.waypoint_tolerance",
        );
        err(
            "cleaning-dwa",
            json!({"max_speed": -0.1}),
            "cleaning-dwa.max_speed",
        );
        err(
            "cleaning-dwa",
            json!({"window": -4}),
            "cleaning-dwa.config.window",
        );
        err(
            "cleaning-dwa",
            json!({"load_region": "circle"}),
            "cleaning-dwa.config.load_region",
        );
        err(
            "cleaning-dwa",
            json!({"sim_time": 1e9}),
            "cleaning-dwa.sim_time",
        );
        err(
            "cleaning-dwa",
            json!({"waypoints": [[50.0, 1.0]]}),
            "waypoints[0]",
        );
        err(
            "cleaning-dwa",
            json!({"waypoints": [[0.02, 3.0]]}),
            "no global path",
        );
        let cfg = CleaningDwaConfig {
            gamma: f64::NAN,
            ..Default::default()
        };
        assert!(cfg
            .validate("cleaning-dwa")
            .unwrap_err()
            .to_string()
            .contains("cleaning-dwa.gamma"));
        // Defaults of the two entries.
        let t = parse("traditional-dwa", &serde_json::Value::Null).unwrap();
        assert!(!t.load_limit && !t.compensate);
        let t = parse("traditional-dwa", &json!({"compensate": true})).unwrap();
        assert!(t.compensate && !t.load_limit);
        assert_eq!(
            parse("cleaning-dwa", &json!({})).unwrap(),
            CleaningDwaConfig::default()
        );
        let f = field_list(true);
        assert!(f
            .iter()
            .any(|i| i.name == "compensate" && i.default == json!(false)));
    }
}
