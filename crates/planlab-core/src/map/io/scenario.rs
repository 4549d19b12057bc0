//! planlab's own scenario file: a versioned JSON document holding a map
//! (inline or by file reference), a start and a goal, and the grid-planner
//! settings. `docs/scenario-schema.md` documents every field with an example.
//!
//! - **Versioned**: `version` is required and must be
//!   [`SCENARIO_VERSION`]; newer files are refused with a clear message
//!   before anything else is read.
//! - **Strict**: unknown fields are errors (`deny_unknown_fields`), so a typo
//!   such as `"heurisitc"` is reported, not silently ignored. New sections
//!   (robot, dynamic obstacles, local planners) are added as optional fields
//!   with defaults, so older files keep loading; a file using a newer section
//!   fails in an older planlab with "unknown field", naming the field.
//! - **Lossless**: [`Scenario::to_json_pretty`] then [`Scenario::from_json`]
//!   gives back an equal [`Scenario`], floats bit for bit.
//! - **Simulation sections** (all optional): `robot`, `start_yaw`,
//!   `movers`, `local_planner`, `sim`, `terrain`, `seed`; an episode is
//!   built from them by [`crate::sim::Episode::from_scenario`].
//! - **No file system**: a map referenced by path is read through a closure
//!   the caller supplies ([`Scenario::load_grid`]), so this works in wasm.

use crate::global::plan::{build_planner, GridPlanOptions};
use crate::global::GridPos;
use crate::map::io::{movingai, ros};
use crate::map::{check_dimensions, Cell, MapError, OccupancyGrid, Pose2};
use crate::num::fmt_num;
use crate::params::param_problem;
use crate::planners::{self as registry, PlannerChoice};
use crate::sim::SimConfig;
use crate::world::{MoverSpec, RobotSpec, TerrainSpec};
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// The scenario format version this build reads and writes.
pub const SCENARIO_VERSION: u32 = 1;

/// Inline maps at most this many cells wide and high are written as plain
/// rows by [`Scenario::with_inline_grid`] (easy to edit by hand); larger ones
/// run-length encoded.
pub const PLAIN_ROWS_MAX_SIDE: usize = 100;

/// Why a scenario could not be read or used.
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
        /// [`SCENARIO_VERSION`].
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

/// A start or goal: a grid cell, optionally with an exact world position
/// inside that cell.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScenarioPoint {
    /// Column, 0 at the left.
    pub col: u32,
    /// Row, 0 at the top.
    pub row: u32,
    /// World position in metres; when given it must lie in cell
    /// `(col, row)` of the map.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub world: Option<WorldPoint>,
}

impl ScenarioPoint {
    /// A point given by its cell only.
    pub const fn cell(col: u32, row: u32) -> Self {
        Self {
            col,
            row,
            world: None,
        }
    }

    /// The cell as a [`GridPos`].
    pub const fn pos(&self) -> GridPos {
        GridPos::new(self.col, self.row)
    }
}

impl From<GridPos> for ScenarioPoint {
    fn from(p: GridPos) -> Self {
        Self::cell(p.col, p.row)
    }
}

/// A world position in metres (x right, y up).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WorldPoint {
    /// x in metres.
    pub x: f64,
    /// y in metres.
    pub y: f64,
}

/// How inline map rows are written.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum RowEncoding {
    /// `cells`: one string per row, one character per cell.
    #[default]
    Plain,
    /// `rle`: one string per row of `<count><char>` runs (count omitted when
    /// 1), e.g. `"12.3#?"`.
    Rle,
}

/// A map stored in the scenario itself.
#[derive(Clone, Debug, PartialEq)]
pub struct InlineMap {
    /// The grid, with its resolution and origin.
    pub grid: OccupancyGrid,
    /// How its rows are written back.
    pub encoding: RowEncoding,
}

/// A map in a separate file, by path relative to the scenario file.
#[derive(Clone, Debug, PartialEq)]
pub struct MapFileRef {
    /// Path relative to the scenario file, `/`-separated: a ROS map_server
    /// `.yaml` (its image is relative to the YAML) or a Moving AI `.map`.
    pub file: String,
    /// Metres per cell replacing the file's (Moving AI maps have none and
    /// default to 1 m).
    pub resolution: Option<f64>,
    /// World pose of the bottom-left corner replacing the file's.
    pub origin: Option<Pose2>,
}

/// Where the scenario's map comes from.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "MapSpecJson", into = "MapSpecJson")]
pub enum MapSpec {
    /// The map is in the scenario.
    Inline(InlineMap),
    /// The map is in another file.
    File(MapFileRef),
}

/// Map file formats a scenario can reference.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MapFormat {
    /// ROS map_server YAML (`.yaml`, `.yml`) with its PGM image.
    RosYaml,
    /// Moving AI `.map`.
    MovingAi,
}

impl MapFormat {
    /// The format implied by a path's extension (case-insensitive).
    pub fn from_path(path: &str) -> Option<MapFormat> {
        let ext = path.rsplit_once('.').map(|(_, e)| e.to_ascii_lowercase())?;
        if ext.contains('/') {
            return None;
        }
        match ext.as_str() {
            "yaml" | "yml" => Some(MapFormat::RosYaml),
            "map" => Some(MapFormat::MovingAi),
            _ => None,
        }
    }
}

/// `rel` resolved against the directory of `base` (both `/`-separated);
/// absolute `rel` (leading `/` or a `C:` drive) is returned as is. Used to
/// find a ROS map's image next to its YAML.
pub fn join_relative(base: &str, rel: &str) -> String {
    let absolute =
        rel.starts_with('/') || rel.starts_with('\\') || rel.as_bytes().get(1) == Some(&b':');
    if absolute {
        return rel.to_string();
    }
    match base.rfind(['/', '\\']) {
        Some(i) => format!("{}/{}", &base[..i], rel),
        None => rel.to_string(),
    }
}

/// The JSON shape of [`MapSpec`]: one object whose fields say which kind it
/// is (validated in `TryFrom`, which gives better messages than an untagged
/// enum).
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct MapSpecJson {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    file: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    width: Option<u64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    height: Option<u64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    resolution: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    origin: Option<Pose2>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    cells: Option<Vec<String>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    rle: Option<Vec<String>>,
}

/// The character of a cell in scenario rows.
fn cell_char(c: Cell) -> char {
    match c {
        Cell::Free => '.',
        Cell::Occupied => '#',
        Cell::Unknown => '?',
    }
}

/// The cell of a scenario row character.
fn char_cell(ch: char) -> Option<Cell> {
    match ch {
        '.' => Some(Cell::Free),
        '#' => Some(Cell::Occupied),
        '?' => Some(Cell::Unknown),
        _ => None,
    }
}

/// Appends one plain row (`r` 1-based for messages) to `cells`.
fn decode_plain(row: &str, r: usize, width: usize, cells: &mut Vec<Cell>) -> Result<(), String> {
    let mut n = 0usize;
    for ch in row.chars() {
        n += 1;
        if n > width {
            break;
        }
        cells.push(char_cell(ch).ok_or_else(|| {
            format!(
                "map.cells row {r}, column {n}: unexpected character {ch:?}; use '.' free, '#' occupied, '?' unknown"
            )
        })?);
    }
    if n != width {
        return Err(format!(
            "map.cells row {r} has {} characters, expected width {width}",
            row.chars().count()
        ));
    }
    Ok(())
}

/// Appends one run-length encoded row (`r` 1-based) to `cells`.
fn decode_rle(row: &str, r: usize, width: usize, cells: &mut Vec<Cell>) -> Result<(), String> {
    let mut n = 0usize;
    let mut count: Option<usize> = None;
    for ch in row.chars() {
        if let Some(d) = ch.to_digit(10) {
            // Saturating: any count above the width is refused below anyway.
            let c = count
                .unwrap_or(0)
                .saturating_mul(10)
                .saturating_add(d as usize);
            count = Some(c);
            continue;
        }
        let cell = char_cell(ch).ok_or_else(|| {
            format!(
                "map.rle row {r}: unexpected character {ch:?}; runs are <count><char> with char '.', '#' or '?'"
            )
        })?;
        let k = count.take().unwrap_or(1);
        if k == 0 {
            return Err(format!("map.rle row {r}: a run has count 0"));
        }
        if k > width - n {
            return Err(format!("map.rle row {r} is longer than the width {width}"));
        }
        n += k;
        cells.extend(std::iter::repeat(cell).take(k));
    }
    if count.is_some() {
        return Err(format!(
            "map.rle row {r} ends with a count but no cell character"
        ));
    }
    if n != width {
        return Err(format!(
            "map.rle row {r} has {n} cells, expected width {width}"
        ));
    }
    Ok(())
}

/// Run-length encodes one row.
fn encode_rle(row: &[Cell]) -> String {
    let mut s = String::new();
    let mut i = 0;
    while let Some(&c) = row.get(i) {
        let run = row[i..].iter().take_while(|&&x| x == c).count();
        if run > 1 {
            s.push_str(&run.to_string());
        }
        s.push(cell_char(c));
        i += run;
    }
    s
}

impl TryFrom<MapSpecJson> for MapSpec {
    type Error = String;

    fn try_from(j: MapSpecJson) -> Result<Self, String> {
        if let Some(file) = j.file {
            if j.width.is_some() || j.height.is_some() || j.cells.is_some() || j.rle.is_some() {
                return Err("map: give either `file` or an inline map (`width`, `height`, `cells` or `rle`), not both".into());
            }
            return Ok(MapSpec::File(MapFileRef {
                file,
                resolution: j.resolution,
                origin: j.origin,
            }));
        }
        let (Some(w), Some(h)) = (j.width, j.height) else {
            return Err(
                "map: an inline map needs `width` and `height` (or give `file` instead)".into(),
            );
        };
        let n = check_dimensions(w, h).map_err(|e| format!("map: {e}"))?;
        let (w, h) = (w as usize, h as usize);
        let (rows, encoding) = match (j.cells, j.rle) {
            (Some(rows), None) => (rows, RowEncoding::Plain),
            (None, Some(rows)) => (rows, RowEncoding::Rle),
            (None, None) => {
                return Err("map: an inline map needs `cells` (rows of . # ?) or `rle`".into())
            }
            (Some(_), Some(_)) => return Err("map: give `cells` or `rle`, not both".into()),
        };
        let key = match encoding {
            RowEncoding::Plain => "cells",
            RowEncoding::Rle => "rle",
        };
        if rows.len() != h {
            return Err(format!(
                "map.{key} has {} rows, expected height {h}",
                rows.len()
            ));
        }
        let mut cells = Vec::with_capacity(n);
        for (i, row) in rows.iter().enumerate() {
            match encoding {
                RowEncoding::Plain => decode_plain(row, i + 1, w, &mut cells)?,
                RowEncoding::Rle => decode_rle(row, i + 1, w, &mut cells)?,
            }
        }
        let grid = OccupancyGrid::from_cells(w, h, cells)
            .and_then(|g| g.with_frame(j.resolution.unwrap_or(1.0), j.origin.unwrap_or_default()))
            .map_err(|e| format!("map: {e}"))?;
        Ok(MapSpec::Inline(InlineMap { grid, encoding }))
    }
}

impl From<MapSpec> for MapSpecJson {
    fn from(m: MapSpec) -> Self {
        match m {
            MapSpec::File(f) => MapSpecJson {
                file: Some(f.file),
                width: None,
                height: None,
                resolution: f.resolution,
                origin: f.origin,
                cells: None,
                rle: None,
            },
            MapSpec::Inline(InlineMap { grid, encoding }) => {
                let rows = grid.cells().chunks(grid.width().max(1));
                let rows: Vec<String> = match encoding {
                    RowEncoding::Plain => rows
                        .map(|r| r.iter().map(|&c| cell_char(c)).collect())
                        .collect(),
                    RowEncoding::Rle => rows.map(encode_rle).collect(),
                };
                let (cells, rle) = match encoding {
                    RowEncoding::Plain => (Some(rows), None),
                    RowEncoding::Rle => (None, Some(rows)),
                };
                MapSpecJson {
                    file: None,
                    width: Some(grid.width() as u64),
                    height: Some(grid.height() as u64),
                    resolution: Some(grid.resolution()),
                    origin: Some(grid.origin()),
                    cells,
                    rle,
                }
            }
        }
    }
}

/// A planlab scenario (format version 1).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scenario {
    /// Format version; must be [`SCENARIO_VERSION`].
    pub version: u32,
    /// Short title.
    #[serde(default)]
    pub name: String,
    /// Free text: what the scenario shows.
    #[serde(default)]
    pub description: String,
    /// The map.
    pub map: MapSpec,
    /// Where the robot starts.
    pub start: ScenarioPoint,
    /// Where it should go.
    pub goal: ScenarioPoint,
    /// Grid global planner settings (algorithm, heuristic, inflation, …).
    #[serde(default)]
    pub grid_planner: GridPlanOptions,
    /// The robot's drive, footprint and limits (default: a 0.2 m disc,
    /// differential drive, [`RobotSpec::default`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub robot: Option<RobotSpec>,
    /// Heading at the start, rad (default 0 = facing +x).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub start_yaw: Option<f64>,
    /// Moving disc obstacles (default none).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub movers: Option<Vec<MoverSpec>>,
    /// The local planner by registry name with its config (default
    /// [`registry::DEFAULT_PLANNER`] with the paper's values).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub local_planner: Option<PlannerChoice>,
    /// Simulation settings (default [`SimConfig::default`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sim: Option<SimConfig>,
    /// Terrain and vehicle dynamics (default flat, no slip).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub terrain: Option<TerrainSpec>,
    /// Seed of the episode's random streams (default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seed: Option<u64>,
    /// A kinematic potential-field run (\[T\] ch. 4) instead of a robot
    /// episode: `planlab run` runs it when present (see
    /// [`crate::apf::scene`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub apf: Option<crate::apf::ApfScene>,
}

/// Sets the value at dotted `path` (`sim.dt`, `movers.0.radius`) in a
/// scenario's JSON tree, before it is parsed: what `planlab run --set` and
/// the reproduction presets use. `value` is parsed as JSON (`0.5`, `true`,
/// `{"k": 1}`, `[1, 2]`), else taken as a string (`astar`). Missing object
/// keys along the way are created; array indices must exist. Errors name
/// the path.
pub fn set_json_path(
    root: &mut serde_json::Value,
    path: &str,
    value: &str,
) -> Result<(), ScenarioError> {
    use serde_json::Value;
    let bad = |why: String| ScenarioError::Invalid(format!("--set {path}: {why}"));
    let parts: Vec<&str> = path.split('.').collect();
    if path.is_empty() || parts.iter().any(|p| p.is_empty()) {
        return Err(bad(
            "the path needs names separated by single dots, like sim.dt".into(),
        ));
    }
    let lower = value
        .trim()
        .trim_start_matches(['+', '-'])
        .to_ascii_lowercase();
    if matches!(lower.as_str(), "nan" | "inf" | "infinity") {
        return Err(bad(format!(
            "{value} is not a number JSON can hold; give a finite number"
        )));
    }
    let new: Value =
        serde_json::from_str(value).unwrap_or_else(|_| Value::String(value.to_string()));
    let mut here = root;
    let mut done = String::new();
    for (i, part) in parts.iter().enumerate() {
        let last = i + 1 == parts.len();
        here = match here {
            Value::Object(m) => {
                if last {
                    m.insert(part.to_string(), new);
                    return Ok(());
                }
                m.entry(part.to_string())
                    .or_insert_with(|| Value::Object(Default::default()))
            }
            Value::Array(a) => {
                let len = a.len();
                let idx: usize = part.parse().map_err(|_| {
                    bad(format!(
                        "`{done}` is a list: `{part}` must be an index 0…{len}"
                    ))
                })?;
                let slot = a
                    .get_mut(idx)
                    .ok_or_else(|| bad(format!("`{done}` has {len} entries: no index {idx}")))?;
                if last {
                    *slot = new;
                    return Ok(());
                }
                slot
            }
            other => {
                let kind = match other {
                    Value::Null => "null",
                    Value::Bool(_) => "a boolean",
                    Value::Number(_) => "a number",
                    Value::String(_) => "a string",
                    _ => "a value",
                };
                return Err(bad(format!("`{done}` is {kind}: it has no field `{part}`")));
            }
        };
        if !done.is_empty() {
            done.push('.');
        }
        done.push_str(part);
    }
    Ok(())
}

/// Chooses local planner `name` in a scenario's JSON tree: its config is
/// kept when the name does not change and reset to `{}` when it does.
pub fn set_planner_name(root: &mut serde_json::Value, name: &str) -> Result<(), ScenarioError> {
    use serde_json::Value;
    let Value::Object(top) = root else {
        return Err(ScenarioError::Invalid(
            "a scenario is a JSON object `{ \"version\": 1, … }`".into(),
        ));
    };
    let lp = top
        .entry("local_planner")
        .or_insert_with(|| Value::Object(Default::default()));
    let Value::Object(lp) = lp else {
        return Err(ScenarioError::Invalid(
            "local_planner must be an object `{ \"name\": …, \"config\": { … } }`".into(),
        ));
    };
    if lp.get("name").and_then(Value::as_str) != Some(name) {
        lp.insert("name".into(), Value::String(name.into()));
        lp.insert("config".into(), Value::Object(Default::default()));
    }
    Ok(())
}

/// The dotted path (`robot.limits.v_max`, `movers[0].radius`) of the JSON
/// value at 1-based `line` / `column` of `text`: where serde_json stopped.
/// Empty at the top level.
fn json_path_at(text: &str, line: usize, column: usize) -> String {
    enum Frame {
        Obj { key: Option<String>, want_key: bool },
        Arr(usize),
    }
    let mut stack: Vec<Frame> = Vec::new();
    let (mut l, mut c) = (1usize, 0usize);
    let mut chars = text.chars();
    while let Some(ch) = chars.next() {
        if ch == '\n' {
            l += 1;
            c = 0;
        } else {
            c += 1;
        }
        if l > line || (l == line && c >= column) {
            break;
        }
        match ch {
            '{' => stack.push(Frame::Obj {
                key: None,
                want_key: true,
            }),
            '[' => stack.push(Frame::Arr(0)),
            '}' | ']' => {
                stack.pop();
            }
            ',' => match stack.last_mut() {
                Some(Frame::Obj { want_key, .. }) => *want_key = true,
                Some(Frame::Arr(i)) => *i += 1,
                None => {}
            },
            ':' => {
                if let Some(Frame::Obj { want_key, .. }) = stack.last_mut() {
                    *want_key = false;
                }
            }
            '"' => {
                let mut s = String::new();
                let mut escaped = false;
                for ch in chars.by_ref() {
                    c += 1;
                    if escaped {
                        escaped = false;
                        s.push(ch);
                    } else if ch == '\\' {
                        escaped = true;
                    } else if ch == '"' {
                        break;
                    } else {
                        s.push(ch);
                    }
                }
                if let Some(Frame::Obj { key, want_key }) = stack.last_mut() {
                    if *want_key {
                        *key = Some(s);
                    }
                }
            }
            _ => {}
        }
    }
    let mut path = String::new();
    for f in &stack {
        match f {
            Frame::Obj { key: Some(k), .. } => {
                if !path.is_empty() {
                    path.push('.');
                }
                path.push_str(k);
            }
            Frame::Obj { key: None, .. } => {}
            Frame::Arr(i) => path.push_str(&format!("[{i}]")),
        }
    }
    path
}

/// Refuses fields the typed parse ignored. Sections defined elsewhere (the
/// planner options) need not opt into `deny_unknown_fields`: every key of the
/// input must reappear when the parsed scenario is written back, otherwise
/// it was not read. Reports the dotted path and the line of the key.
fn check_no_unknown_fields(
    text: &str,
    input: &serde_json::Value,
    parsed: &Scenario,
) -> Result<(), ScenarioError> {
    use serde_json::Value;
    /// The dotted path of the first problem and what it is.
    fn walk(input: &Value, known: &Value, path: &str) -> Option<(String, &'static str)> {
        match (input, known) {
            (Value::Object(a), Value::Object(b)) => a.iter().find_map(|(k, v)| {
                let here = if path.is_empty() {
                    k.clone()
                } else {
                    format!("{path}.{k}")
                };
                match b.get(k) {
                    None => Some((here, "unknown field")),
                    Some(w) => walk(v, w, &here),
                }
            }),
            // serde accepts a struct written as an array of its fields; the
            // format does not.
            (Value::Array(_), Value::Object(_)) => {
                Some((path.to_string(), "expected an object at"))
            }
            (Value::Array(a), Value::Array(b)) => a
                .iter()
                .zip(b)
                .enumerate()
                .find_map(|(i, (v, w))| walk(v, w, &format!("{path}[{i}]"))),
            _ => None,
        }
    }
    let known = serde_json::to_value(parsed)?;
    let Some((path, what)) = walk(input, &known, "") else {
        return Ok(());
    };
    let key = path.rsplit('.').next().unwrap_or(&path);
    let needle = format!("\"{key}\"");
    let (line, column) = text
        .lines()
        .enumerate()
        .find_map(|(i, l)| l.find(&needle).map(|c| (i + 1, c + 1)))
        .unwrap_or((0, 0));
    let hint = if what == "unknown field" {
        " (check its spelling and section)"
    } else {
        ""
    };
    Err(ScenarioError::Json {
        line,
        column,
        message: format!("{what} `{path}`{hint}"),
    })
}

impl Scenario {
    /// A scenario with an inline map, default planner settings and no
    /// description.
    pub fn new(
        name: impl Into<String>,
        grid: OccupancyGrid,
        start: GridPos,
        goal: GridPos,
    ) -> Scenario {
        Scenario {
            version: SCENARIO_VERSION,
            name: name.into(),
            description: String::new(),
            map: MapSpec::Inline(InlineMap {
                encoding: Self::encoding_for(&grid),
                grid,
            }),
            start: start.into(),
            goal: goal.into(),
            grid_planner: GridPlanOptions::default(),
            robot: None,
            start_yaw: None,
            movers: None,
            local_planner: None,
            sim: None,
            terrain: None,
            seed: None,
            apf: None,
        }
    }

    /// World position of a point: its `world` position when given, else
    /// the centre of its cell.
    fn point_world(pt: &ScenarioPoint, grid: &OccupancyGrid) -> [f64; 2] {
        match pt.world {
            Some(w) => [w.x, w.y],
            None => {
                let (x, y) = grid.cell_to_world(pt.col as usize, pt.row as usize);
                [x, y]
            }
        }
    }

    /// The start in world metres on `grid`: `start.world`, else the start
    /// cell's centre.
    pub fn start_world(&self, grid: &OccupancyGrid) -> [f64; 2] {
        Self::point_world(&self.start, grid)
    }

    /// The goal in world metres on `grid`: `goal.world`, else the goal
    /// cell's centre.
    pub fn goal_world(&self, grid: &OccupancyGrid) -> [f64; 2] {
        Self::point_world(&self.goal, grid)
    }

    /// Plain rows for small maps, run-length encoding for large ones.
    fn encoding_for(grid: &OccupancyGrid) -> RowEncoding {
        if grid.width() <= PLAIN_ROWS_MAX_SIDE && grid.height() <= PLAIN_ROWS_MAX_SIDE {
            RowEncoding::Plain
        } else {
            RowEncoding::Rle
        }
    }

    /// Reads and validates a scenario ([`Scenario::validate`]). Unknown
    /// fields anywhere are errors naming their dotted path.
    pub fn from_json(text: &str) -> Result<Scenario, ScenarioError> {
        // Untyped first: syntax errors, the top-level shape and the version
        // come before field errors (a newer file gets a version message, not
        // "unknown field").
        let value: serde_json::Value = serde_json::from_str(text)?;
        let Some(object) = value.as_object() else {
            return Err(ScenarioError::Json {
                line: 1,
                column: 1,
                message: "a scenario is a JSON object `{ \"version\": 1, … }`".into(),
            });
        };
        if let Some(v) = object.get("version").and_then(serde_json::Value::as_u64) {
            if v != u64::from(SCENARIO_VERSION) {
                return Err(ScenarioError::UnsupportedVersion {
                    found: v,
                    supported: SCENARIO_VERSION,
                });
            }
        }
        let s: Scenario = serde_json::from_str(text).map_err(|e| {
            // serde_json says where, not which field: name it.
            let path = json_path_at(text, e.line(), e.column());
            match ScenarioError::from(e) {
                ScenarioError::Json {
                    line,
                    column,
                    message,
                } if !path.is_empty() => ScenarioError::Json {
                    line,
                    column,
                    message: format!("`{path}`: {message}"),
                },
                other => other,
            }
        })?;
        check_no_unknown_fields(text, &value, &s)?;
        s.validate()?;
        Ok(s)
    }

    /// Reads a scenario from an already parsed JSON tree (after
    /// [`set_json_path`] edits), with the same checks and messages as
    /// [`Scenario::from_json`].
    pub fn from_value(value: &serde_json::Value) -> Result<Scenario, ScenarioError> {
        Scenario::from_json(&serde_json::to_string_pretty(value)?)
    }

    /// Validates, then writes pretty-printed JSON that
    /// [`Scenario::from_json`] reads back to an equal scenario.
    pub fn to_json_pretty(&self) -> Result<String, ScenarioError> {
        self.validate()?;
        let mut s = serde_json::to_string_pretty(self)?;
        s.push('\n');
        Ok(s)
    }

    /// The inline map, or `None` when the map is a file reference (use
    /// [`Scenario::load_grid`]).
    pub fn inline_grid(&self) -> Result<Option<OccupancyGrid>, ScenarioError> {
        Ok(match &self.map {
            MapSpec::Inline(m) => Some(m.grid.clone()),
            MapSpec::File(_) => None,
        })
    }

    /// This scenario with `grid` as its inline map (plain rows up to
    /// [`PLAIN_ROWS_MAX_SIDE`] cells a side, run-length encoded above).
    pub fn with_inline_grid(mut self, grid: OccupancyGrid) -> Scenario {
        self.map = MapSpec::Inline(InlineMap {
            encoding: Self::encoding_for(&grid),
            grid,
        });
        self
    }

    /// Checks everything that does not need a referenced map file: version,
    /// file reference, planner settings (the planner is built once to check
    /// them), finite world points, and for an inline map that start and goal
    /// fit it ([`Scenario::validate_against`]).
    pub fn validate(&self) -> Result<(), ScenarioError> {
        if self.version != SCENARIO_VERSION {
            return Err(ScenarioError::UnsupportedVersion {
                found: u64::from(self.version),
                supported: SCENARIO_VERSION,
            });
        }
        let p = &self.grid_planner;
        build_planner(p).map_err(|e| ScenarioError::Invalid(format!("grid_planner: {e}")))?;
        if let Some(problem) = param_problem(p.inflate_m, 0.0, false) {
            return Err(ScenarioError::Invalid(format!(
                "grid_planner.inflate_m is {} (metres): it {problem}",
                fmt_num(p.inflate_m)
            )));
        }
        if let Some(eps) = p.bottom_up_eps {
            if let Some(problem) = param_problem(eps, 0.0, false) {
                return Err(ScenarioError::Invalid(format!(
                    "grid_planner.bottom_up_eps is {} (cells): it {problem}",
                    fmt_num(eps)
                )));
            }
        }
        for (what, pt) in [("start", &self.start), ("goal", &self.goal)] {
            if let Some(w) = pt.world {
                if !(w.x.is_finite() && w.y.is_finite()) {
                    return Err(ScenarioError::Invalid(format!(
                        "{what}.world ({}, {}) must be finite",
                        w.x, w.y
                    )));
                }
            }
        }
        self.validate_sim_sections()?;
        match &self.map {
            MapSpec::Inline(m) => self.validate_against(&m.grid)?,
            MapSpec::File(f) => {
                if MapFormat::from_path(&f.file).is_none() {
                    return Err(ScenarioError::Invalid(format!(
                        "map.file {:?}: unknown map format; use a ROS map_server .yaml or a Moving AI .map",
                        f.file
                    )));
                }
                if let Some(r) = f.resolution {
                    if !(r.is_finite() && r > 0.0) {
                        return Err(MapError::BadResolution(r).into());
                    }
                }
                if let Some(o) = f.origin {
                    if !(o.x.is_finite() && o.y.is_finite() && o.yaw.is_finite()) {
                        return Err(MapError::BadOrigin {
                            x: o.x,
                            y: o.y,
                            yaw: o.yaw,
                        }
                        .into());
                    }
                }
            }
        }
        Ok(())
    }

    /// Checks the simulation sections' numbers and the planner's name (its
    /// config is checked when the planner is built, which needs the map).
    fn validate_sim_sections(&self) -> Result<(), ScenarioError> {
        let invalid = |e: &dyn std::fmt::Display| ScenarioError::Invalid(e.to_string());
        if let Some(r) = &self.robot {
            r.validate().map_err(|e| invalid(&e))?;
        }
        if let Some(yaw) = self.start_yaw {
            if !yaw.is_finite() {
                return Err(ScenarioError::Invalid(format!(
                    "start_yaw = {}: must be a finite number (rad)",
                    fmt_num(yaw)
                )));
            }
        }
        for (i, m) in self.movers.iter().flatten().enumerate() {
            m.validate()
                .map_err(|e| ScenarioError::Invalid(format!("movers[{i}]: {e}")))?;
        }
        if let Some(c) = &self.sim {
            c.validate().map_err(|e| invalid(&e))?;
        }
        if let Some(a) = &self.apf {
            a.config.validate().map_err(|e| invalid(&e))?;
        }
        if let Some(p) = &self.local_planner {
            if !registry::is_registered(&p.name) {
                let names: Vec<String> = registry::list().into_iter().map(|p| p.name).collect();
                return Err(ScenarioError::Invalid(format!(
                    "local_planner.name: unknown planner `{}`; known: {}",
                    p.name,
                    names.join(", ")
                )));
            }
            if !(p.config.is_object() || p.config.is_null()) {
                return Err(ScenarioError::Invalid(format!(
                    "local_planner.config must be an object of fields, got {}",
                    p.config
                )));
            }
        }
        Ok(())
    }

    /// Checks start and goal against `grid`: on the map, and any world
    /// position inside its cell. (Whether the cells are free is the
    /// planner's question, answered with a typed error.)
    pub fn validate_against(&self, grid: &OccupancyGrid) -> Result<(), ScenarioError> {
        for (what, pt) in [("start", &self.start), ("goal", &self.goal)] {
            if !grid.in_bounds(i64::from(pt.col), i64::from(pt.row)) {
                return Err(ScenarioError::Invalid(format!(
                    "{what} ({}, {}) is outside the {}×{} map",
                    pt.col,
                    pt.row,
                    grid.width(),
                    grid.height()
                )));
            }
            if let Some(w) = pt.world {
                let cell = grid.world_to_cell(w.x, w.y);
                if cell != Some((pt.col as usize, pt.row as usize)) {
                    let where_ = match cell {
                        Some((c, r)) => format!("lies in cell ({c}, {r})"),
                        None => "is off the map".to_string(),
                    };
                    return Err(ScenarioError::Invalid(format!(
                        "{what}.world ({}, {}) {where_}, not in the {what} cell ({}, {})",
                        fmt_num(w.x),
                        fmt_num(w.y),
                        pt.col,
                        pt.row
                    )));
                }
            }
        }
        Ok(())
    }

    /// The scenario's map: the inline grid, or the referenced file read
    /// through `read` (given a path relative to the scenario file, it returns
    /// the bytes or an error message) and parsed by its extension, with
    /// `resolution` / `origin` overrides applied. Start and goal are checked
    /// against the result.
    pub fn load_grid(
        &self,
        read: &mut dyn FnMut(&str) -> Result<Vec<u8>, String>,
    ) -> Result<OccupancyGrid, ScenarioError> {
        let grid = match &self.map {
            MapSpec::Inline(m) => m.grid.clone(),
            MapSpec::File(f) => {
                let mut fetch = |path: &str| {
                    read(path).map_err(|message| MapError::Io {
                        path: path.to_string(),
                        message,
                    })
                };
                let text = |bytes: Vec<u8>, path: &str| {
                    String::from_utf8(bytes).map_err(|_| MapError::Io {
                        path: path.to_string(),
                        message: "not UTF-8 text".into(),
                    })
                };
                let grid = match MapFormat::from_path(&f.file) {
                    Some(MapFormat::RosYaml) => {
                        let meta = ros::parse_yaml(&text(fetch(&f.file)?, &f.file)?)?;
                        let image = join_relative(&f.file, &meta.image);
                        ros::grid_from_pgm(&meta, &ros::parse_pgm(&fetch(&image)?)?)?
                    }
                    Some(MapFormat::MovingAi) => {
                        movingai::parse_map(&text(fetch(&f.file)?, &f.file)?)?
                    }
                    None => {
                        return Err(ScenarioError::Invalid(format!(
                            "map.file {:?}: unknown map format; use a ROS map_server .yaml or a Moving AI .map",
                            f.file
                        )))
                    }
                };
                let (res, origin) = (
                    f.resolution.unwrap_or(grid.resolution()),
                    f.origin.unwrap_or(grid.origin()),
                );
                grid.with_frame(res, origin)?
            }
        };
        self.validate_against(&grid)?;
        Ok(grid)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rle_encode_decode() {
        let row = [
            Cell::Free,
            Cell::Free,
            Cell::Occupied,
            Cell::Unknown,
            Cell::Unknown,
            Cell::Unknown,
        ];
        let s = encode_rle(&row);
        assert_eq!(s, "2.#3?");
        let mut out = Vec::new();
        decode_rle(&s, 1, 6, &mut out).unwrap();
        assert_eq!(out, row);
        for bad in ["2.#3", "2.#4?", "0.6#", "2.x3?", "99999999999999999999999."] {
            assert!(decode_rle(bad, 1, 6, &mut Vec::new()).is_err(), "{bad}");
        }
    }

    #[test]
    fn paths_join_and_formats() {
        assert_eq!(join_relative("maps/tb3.yaml", "tb3.pgm"), "maps/tb3.pgm");
        assert_eq!(join_relative("tb3.yaml", "tb3.pgm"), "tb3.pgm");
        assert_eq!(join_relative("maps/tb3.yaml", "/abs/x.pgm"), "/abs/x.pgm");
        assert_eq!(MapFormat::from_path("a/B.YML"), Some(MapFormat::RosYaml));
        assert_eq!(MapFormat::from_path("arena.map"), Some(MapFormat::MovingAi));
        assert_eq!(MapFormat::from_path("x.map/readme"), None);
        assert_eq!(MapFormat::from_path("noext"), None);
    }
}
