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

/// The non-number a JSON writer (Python's `json.dump`, JavaScript's
/// `String(x)`) leaves where a number was NaN or infinite, when one starts
/// at 1-based `line`, `column` of `text` (where serde_json stopped).
pub fn non_json_number_at(text: &str, line: usize, column: usize) -> Option<&'static str> {
    let row = text.lines().nth(line.checked_sub(1)?)?;
    // serde_json points at the token or just after its first character.
    let from = row
        .char_indices()
        .nth(column.saturating_sub(2))
        .map_or(row.len(), |(i, _)| i);
    let rest = row[from..].trim_start_matches(|c: char| c == ':' || c.is_whitespace());
    ["-Infinity", "Infinity", "NaN"]
        .into_iter()
        .find(|t| rest.starts_with(t) || rest.get(1..).is_some_and(|r| r.starts_with(t)))
}

/// [`ScenarioError::Json`] for a syntax error in `text`, naming a NaN or
/// an infinity (serde_json only says "expected value" there).
pub fn json_syntax_error(text: &str, e: serde_json::Error) -> ScenarioError {
    let (line, column) = (e.line(), e.column());
    match non_json_number_at(text, line, column) {
        Some(t) => ScenarioError::Json {
            line,
            column,
            message: format!(
                "{t} is not a number JSON allows (JSON has no NaN or infinity): write a finite number, or leave the field out for its default"
            ),
        },
        None => e.into(),
    }
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
