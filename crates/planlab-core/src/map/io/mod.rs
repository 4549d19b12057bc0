//! Map and scenario file formats.
//!
//! Every reader takes text or bytes, never a path: core runs in WebAssembly
//! where there is no file system, so the caller (CLI, page) reads the files.
//! The scenario document itself is [`crate::scenario`]; its `map` section,
//! inline or by file reference, is [`map_spec`].

pub mod map_spec;
pub mod movingai;
pub mod ros;

use super::MapError;
use thiserror::Error;

/// Why a scenario could not be read or used. Defined with the file formats
/// (the `map` section reports it too) so that [`crate::sim::SimError`], a
/// layer below the scenario document, can carry it.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum ScenarioError {
    /// Malformed JSON, a wrong type, a missing or unknown field, or a bad
    /// inline map (serde reports where).
    #[error(
        "scenario JSON error at line {line}, column {column}: {}",
        crate::text::one_line(message)
    )]
    Json {
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// What is wrong.
        message: String,
    },
    /// The file's `version` is not one this build reads.
    #[error("scenario version {found} is not supported: this planlab reads version {supported}")]
    UnsupportedVersion {
        /// The version in the file.
        found: u64,
        /// [`crate::scenario::SCENARIO_VERSION`].
        supported: u32,
    },
    /// A value is out of range or inconsistent (message names the field).
    #[error("invalid scenario: {}", crate::text::one_line(.0))]
    Invalid(String),
    /// The map (inline or referenced) is unusable.
    #[error(transparent)]
    Map(#[from] MapError),
}

impl From<serde_json::Error> for ScenarioError {
    fn from(e: serde_json::Error) -> Self {
        // serde_json appends " at line L column C"; we show it up front.
        let full = e.to_string();
        let suffix = format!(" at line {} column {}", e.line(), e.column());
        let message = full.strip_suffix(&suffix).unwrap_or(&full).to_string();
        ScenarioError::Json {
            line: e.line(),
            column: e.column(),
            message,
        }
    }
}
