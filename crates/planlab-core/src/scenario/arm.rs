//! The arm scenario file (\[T\] §5.3.3): `version`, `name`, `description`,
//! `seed` and the `arm` section ([`ArmScene`], defined by [`crate::arm`]),
//! and the arm episode it describes.

use serde::{Deserialize, Serialize};

use crate::arm::{ArmEpisode, ArmError, ArmScene};

/// The arm scenario file's format version.
pub const ARM_SCENARIO_VERSION: u32 = 1;

/// An arm scenario file: `version`, `name`, `description`, `seed` and the
/// `arm` section (documented in `docs/scenario-schema.md`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ArmScenario {
    /// Must be [`ARM_SCENARIO_VERSION`].
    pub version: u32,
    /// Short title.
    #[serde(default)]
    pub name: String,
    /// Free text.
    #[serde(default)]
    pub description: String,
    /// Seed of the hand motion's variation (default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seed: Option<u64>,
    /// The scene.
    pub arm: ArmScene,
}

impl ArmScenario {
    /// Parses an arm scenario.
    pub fn from_json(text: &str) -> Result<ArmScenario, ArmError> {
        let v: serde_json::Value = serde_json::from_str(text)
            .map_err(|e| ArmError::Json(crate::map::io::json_syntax_error(text, e).to_string()))?;
        ArmScenario::from_value(&v)
    }

    /// Parses an arm scenario from a JSON tree (after `--set` edits).
    pub fn from_value(v: &serde_json::Value) -> Result<ArmScenario, ArmError> {
        if let Some(ver) = v.get("version").and_then(|x| x.as_u64()) {
            if ver != ARM_SCENARIO_VERSION as u64 {
                return Err(ArmError::Invalid(format!(
                    "scenario version {ver} is not supported: this planlab reads version {ARM_SCENARIO_VERSION}"
                )));
            }
        }
        serde_json::from_value(v.clone()).map_err(|e| ArmError::Json(e.to_string()))
    }
}

impl ArmEpisode {
    /// Builds the episode of a scenario (seed from the file, default 0).
    pub fn from_scenario(s: &ArmScenario) -> Result<ArmEpisode, ArmError> {
        ArmEpisode::new(s.arm.clone(), s.seed.unwrap_or(0))
    }
}
