//! Planner registry: names, config fields and construction of every local
//! planner, so scenarios, the CLI (`planlab planners`, `planlab run
//! --planner`) and the page pick planners by name.

use serde::{Deserialize, Serialize};

use super::{LocalError, LocalPlanner};
use crate::world::{RobotSpec, RobotState, StaticMap};

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

/// Every registered planner.
pub fn list() -> Vec<PlannerInfo> {
    Vec::new()
}

/// Builds the planner `choice` names for `robot` on `map`, starting at
/// `start` and heading for `goal` (world metres).
pub fn build(
    choice: &PlannerChoice,
    robot: &RobotSpec,
    map: &StaticMap,
    start: &RobotState,
    goal: [f64; 2],
) -> Result<Box<dyn LocalPlanner>, LocalError> {
    let _ = (robot, map, start, goal);
    Err(LocalError::UnknownPlanner(choice.name.clone()))
}
