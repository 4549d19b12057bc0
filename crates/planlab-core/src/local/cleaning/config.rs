//! `cleaning-dwa` / `traditional-dwa` settings (\[C\] Tables 1–2), their
//! field list and their parsing.

use serde::{Deserialize, Serialize};

use crate::local::engine::generator::MAX_ROLLOUT_STEPS;
use crate::local::LocalError;
use crate::params::{field_infos, parse_config, FieldInfo, Params};
use crate::world::terrain::VehicleSpec;

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

crate::params::params! {
    /// Settings of `cleaning-dwa` / `traditional-dwa` (\[C\] Tables 1–2).
    #[derive(Debug, Clone, PartialEq)]
    pub struct CleaningDwaConfig {
        pub alpha: f64 = 0.1, "1" [>= 0.0]
            label "obstacle cost weight α" "α: weight of the obstacle cost (sum of costmap costs crossed)";
        /// \[C\] Table 2's "local weight", see the module doc.
        pub beta: f64 = 0.3, "1" [>= 0.0] label "goal distance weight β" "β: weight of the Manhattan distance to the local goal";
        /// \[C\] Table 2's "global weight".
        pub gamma: f64 = 0.6, "1" [>= 0.0]
            label "path distance weight γ" "γ: weight of the Manhattan distance to the global path";
        /// nav2 DWB's "twirling" critic.
        pub twirl: f64 = 0.1, "m·s/rad" [>= 0.0]
            label "spin weight" "weight of |ω| (not in \\[C\\]; keeps the holonomic body from spinning, 0 = off)";
        pub v_res: f64 = 0.02, "m/s" [> 0.0] label "speed resolution" "linear velocity resolution (v_x and v_y)";
        pub w_res: f64 = 0.01, "rad/s" [> 0.0] label "turn-rate resolution" "angular velocity resolution";
        pub sim_time: f64 = 2.0, "s" [> 0.0] label "look-ahead time" "trajectory prediction time";
        pub sim_dt: f64 = 0.1, "s" [> 0.0] label "rollout time step" "integration step of the prediction";
        /// A tiny resolution cannot stall a step.
        pub max_samples_per_axis: usize = 41, "1" [] label "samples per axis" "most samples per velocity axis";
        /// \[C\] Table 1's single maximum linear speed.
        pub max_speed: f64 = 0.0, "m/s" [>= 0.0]
            label "top speed" "largest translational speed √(v_x² + v_y²); 0 = the robot's v_max";
        pub inflation_radius: f64 = 0.35, "m" [>= 0.0]
            label "inflation radius" "robot inflation radius: costmap inscribed radius and A* inflation";
        pub safety_distance: f64 = 0.10, "m" [>= 0.0]
            label "cost decay distance" "costs decay from the inflation radius out to inflation_radius + this";
        pub cost_scaling: f64 = 10.0, "1/m" [>= 0.0]
            label "cost decay rate" "costmap cost decay factor (ROS cost_scaling_factor)";
        pub lookahead: f64 = 1.5, "m" [> 0.0]
            label "local goal distance" "arc length from the robot's projection to the local goal (at least 1.25·v_max·sim_time)";
        pub waypoints: Vec<[f64; 2]> = Vec::new(), "m" []
            label "cleaning waypoints" "cleaning target points [[x, y], …] the global path passes through in order";
        /// \[C\] §2.1: many close targets, frequent acceleration and braking.
        pub stop_at_waypoints: bool = false, "bool" []
            label "stop at waypoints" "stop at every waypoint (the local goal waits there until it is reached)";
        pub waypoint_tolerance: f64 = 0.1, "m" [> 0.0] label "waypoint tolerance" "a waypoint is reached within this distance";
        /// \[C\] §3.2.
        pub load_limit: bool = true, "bool" []
            label "wheel load limit" "vertical-load acceleration limit (\\[C\\] eq 8, 14)";
        pub load_fraction: f64 = 0.2, "1" [>= 0.0]
            label "least wheel load j" "j: every wheel keeps more than j·m·g (0 ≤ j < 1/4)";
        pub load_region: LoadRegion = LoadRegion::Diamond, "" []
            label "load limit shape" "`diamond` (exact eq 8, |a_x|+|a_y| ≤ x₁) or `box` (eq 14 per axis)";
        pub vehicle: VehicleSpec = VehicleSpec::default(), "" [nested]
            "vehicle of the load limit (\\[C\\] Table 1)";
        /// A peak-hold filter: the next period's bumps are unknown, the
        /// recent worst is a cautious guess.
        pub accel_z_hold: usize = 5, "periods" []
            label "vertical acceleration memory" "the load limit uses the largest a_z measured over this many periods (≥ 1)";
        /// \[C\] §3.3.
        pub compensate: bool = true, "bool" []
            label "odometry compensation" "odometry error compensation: least-squares K used in rollouts (\\[C\\] eq 15–18)";
        pub k_structure: KStructure = KStructure::Block, "" []
            label "compensation matrix form" "`block` (translation 2×2 and rotation fitted separately) or `full` (3×3, eq 17)";
        pub window: usize = 50, "samples" [] label "fit window" "sliding window of odometry pairs for the fit";
        pub min_samples: usize = 10, "samples" []
            label "samples before first fit" "odometry pairs needed before the first fit (K = I until then)";
        /// Relative to the mean excitation tr(Σuuᵀ)/3.
        pub ridge: f64 = 0.3, "1" [>= 0.0]
            label "fit damping" "pull of K toward its previous value, relative to the mean excitation";
    }
}

/// The field list of `cleaning-dwa` (`traditional = false`) or
/// `traditional-dwa` (load limit and compensation off by default).
pub fn field_list(traditional: bool) -> Vec<FieldInfo> {
    let mut f = field_infos::<CleaningDwaConfig>();
    if traditional {
        for info in &mut f {
            if info.name == "load_limit" || info.name == "compensate" {
                info.default = serde_json::Value::Bool(false);
            }
        }
    }
    f
}

/// Reads the config of catalogue entry `planner`: `traditional-dwa` turns
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
        Ok(parse_config(planner, &v)?)
    } else {
        Ok(parse_config(planner, value)?)
    }
}

impl CleaningDwaConfig {
    /// Checks every number; the error names `prefix.field`.
    pub fn validate(&self, prefix: &str) -> Result<(), LocalError> {
        let p = prefix;
        self.check_bounds(p)?;
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
        for (i, w) in self.waypoints.iter().enumerate() {
            if !(w[0].is_finite() && w[1].is_finite()) {
                return Err(LocalError::InvalidParameter(format!(
                    "{p}.waypoints[{i}] = ({}, {}): must be finite",
                    w[0], w[1]
                )));
            }
        }
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
        Ok(())
    }
}
