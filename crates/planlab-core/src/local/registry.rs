//! Planner registry: names, config fields and construction of every local
//! planner, so scenarios, the CLI (`planlab planners`, `planlab run
//! --planner`) and the page pick planners by name.
//!
//! Adding a planner: one arm in [`build`], one entry in [`list`]. Its config
//! struct derives `Serialize + Deserialize + Default` with
//! `#[serde(default, deny_unknown_fields)]`; [`parse_config`] reads it from
//! the scenario's JSON with errors naming the field, and [`field_infos`]
//! derives the field list (with defaults) from `Default` plus a static
//! `(name, unit, doc)` table.

use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};

use super::cleaning;
use super::dual::{dual_fields, preliminary_fields, DualConfig, PreliminaryConfig, SafeDualDwa};
use super::dwa::{Dwa, DwaConfig, DWA_FIELDS};
use super::improved::{
    fusion53_fields, improved_fields, Fusion53Config, ImprovedConfig, ImprovedDwa,
};
use super::pursuit::{Pursuit, PursuitConfig};
use super::{LocalError, LocalPlanner};
use crate::apf::local::{self as apf_local, ApfLocal, ApfLocalConfig};
use crate::lidar::planner::{
    lidar_fields, motion_fields, LidarPlanner, LidarPlannerConfig, ScanBaselineConfig,
};
use crate::lidar::rrt_shortcut::{rrt_shortcut_fields, RrtShortcut, RrtShortcutConfig};
use crate::lidar::rs_apf::{rs_apf_fields, RsApf, RsApfConfig};
use crate::lidar::tangent_bug::{tangent_bug_fields, TangentBug, TangentBugConfig};
use crate::world::{RobotSpec, RobotState, StaticMap};

/// The planner a scenario without a `local_planner` section uses.
pub const DEFAULT_PLANNER: &str = "dwa";

/// A planner chosen by name with its config as JSON (fields left out take
/// the paper's defaults; unknown fields are refused, naming them).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlannerChoice {
    /// Registry name, e.g. `dwa`.
    pub name: String,
    /// Config object for that planner.
    #[serde(default = "empty_object")]
    pub config: serde_json::Value,
}

impl PlannerChoice {
    /// The planner `name` with its default config (`{}`).
    pub fn named(name: impl Into<String>) -> Self {
        Self {
            name: name.into(),
            config: empty_object(),
        }
    }
}

impl Default for PlannerChoice {
    /// [`DEFAULT_PLANNER`] with its default config.
    fn default() -> Self {
        Self::named(DEFAULT_PLANNER)
    }
}

fn empty_object() -> serde_json::Value {
    serde_json::Value::Object(Default::default())
}

/// One config field, for `planlab planners` and the page's parameter panel.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FieldInfo {
    /// Field name (dotted for nested fields).
    pub name: String,
    /// Unit ("m", "m/s", "rad", "1" …).
    pub unit: String,
    /// Default value (the paper's).
    pub default: serde_json::Value,
    /// What it does.
    pub doc: String,
}

/// A registered planner.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PlannerInfo {
    /// Registry name.
    pub name: String,
    /// Paper and section it follows.
    pub paper: String,
    /// One-line summary.
    pub summary: String,
    /// Config fields.
    pub fields: Vec<FieldInfo>,
}

/// Every registered planner, in a fixed order.
pub fn list() -> Vec<PlannerInfo> {
    vec![
        PlannerInfo {
            name: "dwa".into(),
            paper: "[T] Wu 2022 §3.1, eq 3-1…3-5 (Fox, Burgard & Thrun 1997); \
                    docs/algorithms.md §dwa"
                .into(),
            summary: "Baseline dynamic window approach straight to the final goal: \
                      window V_s ∩ V_d ∩ V_a, rollouts, normalised heading / clearance / \
                      velocity critics."
                .into(),
            fields: field_infos::<DwaConfig>(DWA_FIELDS),
        },
        PlannerInfo {
            name: "improved-dwa".into(),
            paper: "[T] Wu 2022 §3.2 (Table 3-1, eq 3-7/3-8); \
                    docs/algorithms.md §improved-dwa"
                .into(),
            summary: "A* key points as intermediate goals; movers classified ordinary \
                      dynamic / static / special with deceleration or detour weights and \
                      virtual goals; relative distance factor ρ near the goal."
                .into(),
            fields: owned_field_infos::<ImprovedConfig>(&improved_fields()),
        },
        PlannerInfo {
            name: "fusion-53".into(),
            paper: "[T] Wu 2022 §3.2–3.3, its reference [53]; docs/algorithms.md §fusion-53".into(),
            summary: "Baseline fusion: A* key points + DWA with the deceleration weights \
                      while a moving obstacle is near, plain DWA otherwise; no \
                      classification, virtual goal or ρ."
                .into(),
            fields: owned_field_infos::<Fusion53Config>(&fusion53_fields()),
        },
        PlannerInfo {
            name: "safe-dual-dwa".into(),
            paper: "[S] Ge & Li 2022 §2–4 (eq 9–12, §4.2, §5); \
                    docs/algorithms.md §safe-dual-dwa"
                .into(),
            summary: "Safe A* path → Bottom-Up feature nodes as temporary goals; dual \
                      velocity model (speed held within d of a temporary goal); detour \
                      replanning (θa ≥ 90° → next temporary goal)."
                .into(),
            fields: owned_field_infos::<DualConfig>(&dual_fields()),
        },
        PlannerInfo {
            name: "preliminary-fusion".into(),
            paper: "[S] Ge & Li 2022 §2.4 baseline; docs/algorithms.md §preliminary-fusion".into(),
            summary: "Baseline fusion: every safe A* path node a temporary goal, the normal \
                      DWA window (the robot slows at each)."
                .into(),
            fields: owned_field_infos::<PreliminaryConfig>(&preliminary_fields()),
        },
        PlannerInfo {
            name: "pursuit".into(),
            paper: "none (test baseline)".into(),
            summary: "Naive baseline: steers straight at the goal with a braking profile; \
                  no obstacle avoidance."
                .into(),
            fields: field_infos::<PursuitConfig>(PursuitConfig::FIELDS),
        },
        PlannerInfo {
            name: "cleaning-dwa".into(),
            paper: "[C] Zhang et al. 2020 §2–3; docs/algorithms.md §cleaning-dwa".into(),
            summary: "Cleaning-robot DWA (omnidirectional v_x, v_y, ω) along an A* path: \
                      costmap + Manhattan goal / path costs, vertical-load acceleration \
                      limit, least-squares odometry compensation."
                .into(),
            fields: cleaning::field_list(false),
        },
        PlannerInfo {
            name: "traditional-dwa".into(),
            paper: "[C] Zhang et al. 2020 baseline; docs/algorithms.md §cleaning-dwa".into(),
            summary: "[C]'s traditional DWA: the cleaning DWA's cost without the load \
                      limit and without odometry compensation."
                .into(),
            fields: cleaning::field_list(true),
        },
        PlannerInfo {
            name: "apf".into(),
            paper: "[T] Wu 2022 §4.1, eq 4-1…4-4; docs/algorithms.md §apf".into(),
            summary: "Basic artificial potential field: one fixed step along the resultant of \
                      goal attraction and mover / nearest-wall repulsion, pursued within the \
                      robot's limits."
                .into(),
            fields: owned_field_infos::<ApfLocalConfig>(&apf_local::field_table()),
        },
        PlannerInfo {
            name: "sampling-apf".into(),
            paper: "[T] Wu 2022 §4.2, eq 4-5…4-14; docs/algorithms.md §apf".into(),
            summary: "Sampling-based improved APF: 13 directions ±90° around the resultant, \
                      cost 0.3‖F_attr‖ + 0.7‖F_rep‖, relative distance rule, predicted movers \
                      (t+1, t+2) with virtual repulsion; the APF point is pursued."
                .into(),
            fields: owned_field_infos::<ApfLocalConfig>(&apf_local::field_table()),
        },
        PlannerInfo {
            name: "lidar-dwa".into(),
            paper: "[L] Chang et al. 2024 §2–4 (Alg. 1–2, eq 1–4, Table 1); \
                    docs/algorithms.md §lidar"
                .into(),
            summary: "Unknown map, LiDAR only: edges, gap removal, obstacle patterns and \
                      temporary goals around the OP blocking the goal; DWA drives to the \
                      target on a local map built from the scan."
                .into(),
            fields: {
                let mut f = lidar_fields(true);
                f.extend(motion_fields(DWA_FIELDS));
                owned_field_infos::<LidarPlannerConfig<DwaConfig>>(&f)
            },
        },
        PlannerInfo {
            name: "lidar-apf".into(),
            paper: "[L] Chang et al. 2024 §2–4, sims 8–9 (APF [9] underneath); \
                    docs/algorithms.md §lidar"
                .into(),
            summary: "The LiDAR temporary-goal navigator over the basic APF (eq 4-1…4-4) \
                      on a local map built from the scan."
                .into(),
            fields: {
                let mut f = lidar_fields(true);
                f.extend(
                    apf_local::field_table()
                        .into_iter()
                        .map(|(n, u, d)| (format!("motion.{n}"), u, d)),
                );
                owned_field_infos::<LidarPlannerConfig<ApfLocalConfig>>(&f)
            },
        },
        PlannerInfo {
            name: "scan-apf".into(),
            paper: "[L] Chang et al. 2024 §4.2 baseline (sim 8); \
                    docs/algorithms.md §scan-baselines"
                .into(),
            summary: "Plain APF straight to the goal on an unknown map: only the scan's \
                      local map, no temporary goals, no global path."
                .into(),
            fields: {
                let mut f = lidar_fields(false);
                f.extend(
                    apf_local::field_table()
                        .into_iter()
                        .map(|(n, u, d)| (format!("motion.{n}"), u, d)),
                );
                owned_field_infos::<ScanBaselineConfig<ApfLocalConfig>>(&f)
            },
        },
        PlannerInfo {
            name: "scan-dwa".into(),
            paper: "[L] Chang et al. 2024 §4.2 baseline; docs/algorithms.md §scan-baselines".into(),
            summary: "Plain DWA straight to the goal on an unknown map: only the scan's \
                      local map, no temporary goals, no global path."
                .into(),
            fields: {
                let mut f = lidar_fields(false);
                f.extend(motion_fields(DWA_FIELDS));
                owned_field_infos::<ScanBaselineConfig<DwaConfig>>(&f)
            },
        },
        PlannerInfo {
            name: "tangent-bug".into(),
            paper: "TangentBug (Kamon, Rivlin & Rimon 1998) standing in for \
                    Critical-PointBug, [L] Chang et al. 2024 ref [21], sim 6; \
                    docs/algorithms.md §tangent-bug"
                .into(),
            summary: "Unknown map, scan + pose: motion to the tangent-graph endpoint \
                      minimising d(x,O)+d(O,goal), boundary following when that stops \
                      decreasing, leaving when d_reach < d_followed; baseline DWA on the \
                      scan's local map drives."
                .into(),
            fields: owned_field_infos::<TangentBugConfig>(&tangent_bug_fields()),
        },
        PlannerInfo {
            name: "rs-apf".into(),
            paper: "RS-APF (Li, Tamura, Yamashita & Asama 2013), [L] Chang et al. 2024 \
                    ref [11], sim 8 — scan-only receding-horizon variant of an offline \
                    planner; docs/algorithms.md §rs-apf"
                .into(),
            summary: "Unknown map, scan + pose: every period a virtual point descends the \
                      basic APF on the scan (following the obstacle after a stall), the \
                      regression search shortens that path, and the baseline DWA on the \
                      scan's local map drives to its first corner."
                .into(),
            fields: owned_field_infos::<RsApfConfig>(&rs_apf_fields()),
        },
        PlannerInfo {
            name: "rrt-shortcut".into(),
            paper: "RRT (LaValle 1998) with shortcutting standing in for RL-RRT, \
                    [L] Chang et al. 2024 ref [2], sim 7 — no learned component; \
                    docs/algorithms.md §rrt-shortcut"
                .into(),
            summary: "Unknown map, scan + pose: an occupancy memory of what the scan has \
                      shown (unknown counts as free); a goal-biased RRT over it, inflated by \
                      the robot, shortened by line-of-sight shortcuts and replanned when \
                      blocked, off course or stalled; the baseline DWA on the scan's local \
                      map drives to the next waypoint."
                .into(),
            fields: owned_field_infos::<RrtShortcutConfig>(&rrt_shortcut_fields()),
        },
    ]
}

/// Builds the planner `choice` names for `robot` on `map`, starting at
/// `start` and heading for `goal` (world metres). Config errors name the
/// field; an unknown name is [`LocalError::UnknownPlanner`].
pub fn build(
    choice: &PlannerChoice,
    robot: &RobotSpec,
    map: &StaticMap,
    start: &RobotState,
    goal: [f64; 2],
) -> Result<Box<dyn LocalPlanner>, LocalError> {
    match choice.name.as_str() {
        "dwa" => Ok(Box::new(Dwa::new(
            parse_config(&choice.name, &choice.config)?,
            robot,
            goal,
        )?)),
        "improved-dwa" => Ok(Box::new(ImprovedDwa::improved(
            parse_config(&choice.name, &choice.config)?,
            robot,
            map,
            start,
            goal,
        )?)),
        "fusion-53" => Ok(Box::new(ImprovedDwa::fusion53(
            parse_config(&choice.name, &choice.config)?,
            robot,
            map,
            start,
            goal,
        )?)),
        "safe-dual-dwa" => Ok(Box::new(SafeDualDwa::safe_dual(
            parse_config(&choice.name, &choice.config)?,
            robot,
            map,
            start,
            goal,
        )?)),
        "preliminary-fusion" => Ok(Box::new(SafeDualDwa::preliminary(
            parse_config(&choice.name, &choice.config)?,
            robot,
            map,
            start,
            goal,
        )?)),
        "pursuit" => Ok(Box::new(Pursuit::new(
            parse_config(&choice.name, &choice.config)?,
            robot,
            goal,
        )?)),
        name @ ("cleaning-dwa" | "traditional-dwa") => {
            let name = if name == "cleaning-dwa" {
                "cleaning-dwa"
            } else {
                "traditional-dwa"
            };
            Ok(Box::new(cleaning::CleaningDwa::new(
                name,
                cleaning::parse(name, &choice.config)?,
                robot,
                map,
                start,
                goal,
            )?))
        }
        name @ ("apf" | "sampling-apf") => Ok(Box::new(ApfLocal::new(
            name == "apf",
            parse_config(&choice.name, &choice.config)?,
            robot,
            goal,
        )?)),
        "lidar-dwa" => Ok(Box::new(LidarPlanner::with_nav(
            "lidar-dwa",
            "dwa",
            &parse_config::<LidarPlannerConfig<DwaConfig>>(&choice.name, &choice.config)?,
            robot,
        )?)),
        "lidar-apf" => Ok(Box::new(LidarPlanner::with_nav(
            "lidar-apf",
            "apf",
            &parse_config::<LidarPlannerConfig<ApfLocalConfig>>(&choice.name, &choice.config)?,
            robot,
        )?)),
        "scan-apf" => Ok(Box::new(LidarPlanner::baseline(
            "scan-apf",
            "apf",
            &parse_config::<ScanBaselineConfig<ApfLocalConfig>>(&choice.name, &choice.config)?,
            robot,
        )?)),
        "scan-dwa" => Ok(Box::new(LidarPlanner::baseline(
            "scan-dwa",
            "dwa",
            &parse_config::<ScanBaselineConfig<DwaConfig>>(&choice.name, &choice.config)?,
            robot,
        )?)),
        "tangent-bug" => Ok(Box::new(TangentBug::new(
            parse_config(&choice.name, &choice.config)?,
            robot,
        )?)),
        "rs-apf" => Ok(Box::new(RsApf::new(
            parse_config(&choice.name, &choice.config)?,
            robot,
        )?)),
        "rrt-shortcut" => Ok(Box::new(RrtShortcut::new(
            parse_config(&choice.name, &choice.config)?,
            robot,
        )?)),
        _ => Err(LocalError::UnknownPlanner(choice.name.clone())),
    }
}

/// Whether `name` is a registered planner.
pub fn is_registered(name: &str) -> bool {
    list().iter().any(|p| p.name == name)
}

/// Reads a planner config from JSON: `null` and `{}` give `T::default()`,
/// left-out fields their defaults. On error the message names the planner
/// and the offending field (`dwa.config.alpha: invalid type: string "x",
/// expected f64`). `T` should be `#[serde(default, deny_unknown_fields)]`.
pub fn parse_config<T>(planner: &str, value: &serde_json::Value) -> Result<T, LocalError>
where
    T: DeserializeOwned + Serialize + Default,
{
    use serde_json::Value;
    if value.is_null() {
        return Ok(T::default());
    }
    // serde would also take a struct written as an array of its fields.
    let Value::Object(input) = value else {
        return Err(LocalError::InvalidParameter(format!(
            "{planner}.config must be a JSON object of fields, got {value}"
        )));
    };
    let err = match T::deserialize(value) {
        Ok(t) => return Ok(t),
        Err(e) => e,
    };
    // serde_json does not say which field a type error is in: put the input
    // fields one at a time on top of the defaults; the first that fails is it.
    if let Ok(Value::Object(mut probe)) = serde_json::to_value(T::default()) {
        for (k, v) in input {
            probe.insert(k.clone(), v.clone());
            if let Err(e) = T::deserialize(&Value::Object(probe.clone())) {
                let msg = e.to_string();
                let named = if msg.starts_with("unknown field") {
                    format!(": {msg}")
                } else {
                    format!(".{k}: {msg}")
                };
                return Err(LocalError::InvalidParameter(format!(
                    "{planner}.config{named}"
                )));
            }
        }
    }
    Err(LocalError::InvalidParameter(format!(
        "{planner}.config: {err}"
    )))
}

/// The field list of config `T`: each `(name, unit, doc)` of `table` (in
/// its order) with the default taken from `T::default()` (dotted names reach
/// into nested objects), then any field the table forgot, with empty unit
/// and doc (a unit test per planner checks there are none).
pub fn field_infos<T: Serialize + Default>(table: &[(&str, &str, &str)]) -> Vec<FieldInfo> {
    let defaults = serde_json::to_value(T::default()).unwrap_or(serde_json::Value::Null);
    let lookup = |name: &str| {
        name.split('.')
            .try_fold(&defaults, |v, k| v.get(k))
            .cloned()
            .unwrap_or(serde_json::Value::Null)
    };
    let mut out: Vec<FieldInfo> = table
        .iter()
        .map(|&(name, unit, doc)| FieldInfo {
            name: name.to_string(),
            unit: unit.to_string(),
            default: lookup(name),
            doc: doc.to_string(),
        })
        .collect();
    if let serde_json::Value::Object(m) = &defaults {
        for (k, v) in m {
            let covered = table
                .iter()
                .any(|&(n, _, _)| n == k || n.starts_with(&format!("{k}.")));
            if !covered {
                out.push(FieldInfo {
                    name: k.clone(),
                    unit: String::new(),
                    default: v.clone(),
                    doc: String::new(),
                });
            }
        }
    }
    out
}

/// [`field_infos`] for a table of owned strings (tables built at run time,
/// e.g. a nested engine's fields under a prefix).
pub fn owned_field_infos<T: Serialize + Default>(
    table: &[(String, String, String)],
) -> Vec<FieldInfo> {
    let refs: Vec<(&str, &str, &str)> = table
        .iter()
        .map(|(n, u, d)| (n.as_str(), u.as_str(), d.as_str()))
        .collect();
    field_infos::<T>(&refs)
}

/// Checks a planner parameter is finite and ≥ `min` (or > `min` when
/// `strict`); the error names `planner.field`.
pub fn check_param(
    planner: &str,
    field: &str,
    value: f64,
    min: f64,
    strict: bool,
) -> Result<(), LocalError> {
    let ok = value.is_finite() && if strict { value > min } else { value >= min };
    if ok {
        Ok(())
    } else {
        let rel = if strict { ">" } else { "≥" };
        Err(LocalError::InvalidParameter(format!(
            "{planner}.{field} = {value}: must be a finite number {rel} {min}"
        )))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn every_field_documented_and_names_unique() {
        let all = list();
        for p in &all {
            for f in &p.fields {
                assert!(!f.doc.is_empty(), "{}.{} has no doc", p.name, f.name);
                assert!(!f.default.is_null(), "{}.{} has no default", p.name, f.name);
            }
            assert_eq!(all.iter().filter(|q| q.name == p.name).count(), 1);
        }
        assert!(is_registered("pursuit"));
    }

    #[test]
    fn parse_config_names_the_field() {
        let c: PursuitConfig = parse_config("pursuit", &json!({"k_w": 3.0})).unwrap();
        assert_eq!(c.k_w, 3.0);
        let e = parse_config::<PursuitConfig>("pursuit", &json!({"k_w": 1, "turn_angle": "x"}))
            .unwrap_err()
            .to_string();
        assert!(e.contains("pursuit.config.turn_angle"), "{e}");
        let e = parse_config::<PursuitConfig>("pursuit", &json!({"kw": 1}))
            .unwrap_err()
            .to_string();
        assert!(e.contains("unknown field `kw`"), "{e}");
        let e = parse_config::<PursuitConfig>("pursuit", &json!([1]))
            .unwrap_err()
            .to_string();
        assert!(e.contains("object"), "{e}");
        assert_eq!(
            parse_config::<PursuitConfig>("pursuit", &serde_json::Value::Null).unwrap(),
            PursuitConfig::default()
        );
    }
}
