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
use crate::map::io::map_spec::{InlineMap, MapSpec};
use crate::map::io::ScenarioError;
use crate::map::OccupancyGrid;
use crate::num::fmt_num;
use crate::params::param_problem;
use crate::planners::{self as registry, PlannerChoice};
use crate::sim::SimConfig;
use crate::world::{MoverSpec, RobotSpec, TerrainSpec};
use serde::{Deserialize, Serialize};

/// The scenario format version this build reads and writes.
pub const SCENARIO_VERSION: u32 = 1;

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
    /// The planner knows only what a laser shows: a costmap built from its
    /// scans replaces the true map in every observation (see
    /// [`crate::sim::perception`]; default: the planner gets the map).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub perception: Option<crate::sim::PerceptionSpec>,
    /// A car-like global path the local planner follows: Hybrid A* with
    /// `turning_radius_m` (required), `reverse`, `goal_yaw`, `margin_m`,
    /// `lookahead_m` (see [`crate::local::car_guide`]; default: none, the
    /// local planner steers as it does alone).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub global_planner: Option<crate::local::car_guide::GlobalPlannerSpec>,
}

/// Most names in a [`set_json_path`] path. No scenario field is nested
/// more than 6 deep (`movers.0.motion.points.0.0`); the bound keeps a
/// hostile path (`a.a.a…` 20 000 deep) from building a tree as deep.
pub const SET_PATH_MAX_NAMES: usize = 64;

/// Sets the value at dotted `path` (`sim.dt`, `movers.0.radius`) in a
/// scenario's JSON tree, before it is parsed: what `planlab run --set` and
/// the reproduction presets use. `value` is parsed as JSON (`0.5`, `true`,
/// `{"k": 1}`, `[1, 2]`), else taken as a string (`astar`). Missing object
/// keys along the way are created; array indices must exist; a path has at
/// most [`SET_PATH_MAX_NAMES`] names. Errors name the path (its start, when
/// it is long).
pub fn set_json_path(
    root: &mut serde_json::Value,
    path: &str,
    value: &str,
) -> Result<(), ScenarioError> {
    use serde_json::Value;
    let shown = abbreviated(path);
    let bad = |why: String| ScenarioError::Invalid(format!("--set {shown}: {why}"));
    let names = path.split('.').count();
    if names > SET_PATH_MAX_NAMES {
        return Err(bad(format!(
            "the path has {names} names; at most {SET_PATH_MAX_NAMES} are allowed"
        )));
    }
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

/// `path` for an error message: whole up to 80 bytes, else its start and `…`
/// (an argument can be megabytes long; a message stays one short line).
fn abbreviated(path: &str) -> std::borrow::Cow<'_, str> {
    const MAX: usize = 80;
    if path.len() <= MAX {
        return path.into();
    }
    let mut end = MAX;
    while !path.is_char_boundary(end) {
        end -= 1;
    }
    format!("{}…", &path[..end]).into()
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

/// The first field the typed parse ignored, as its dotted path and what is
/// wrong with it. Sections defined elsewhere (the planner options) need not
/// opt into `deny_unknown_fields`: every key of the input must reappear when
/// the parsed scenario is written back, otherwise it was not read.
fn unread_field(
    input: &serde_json::Value,
    parsed: &Scenario,
) -> Result<Option<(String, &'static str)>, ScenarioError> {
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
    Ok(walk(input, &known, ""))
}

/// Refuses fields the typed parse ignored ([`unread_field`]), reporting the
/// dotted path and the line of the key in `text`.
fn check_no_unknown_fields(
    text: &str,
    input: &serde_json::Value,
    parsed: &Scenario,
) -> Result<(), ScenarioError> {
    let Some((path, what)) = unread_field(input, parsed)? else {
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
            map: MapSpec::Inline(InlineMap::new(grid)),
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
            perception: None,
            global_planner: None,
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

    /// Reads and validates a scenario ([`Scenario::validate`]). Unknown
    /// fields anywhere are errors naming their dotted path.
    pub fn from_json(text: &str) -> Result<Scenario, ScenarioError> {
        // Untyped first: syntax errors, the top-level shape and the version
        // come before field errors (a newer file gets a version message, not
        // "unknown field").
        let value: serde_json::Value =
            serde_json::from_str(text).map_err(|e| crate::map::io::json_syntax_error(text, e))?;
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
    /// [`Scenario::from_json`]; a message with a line points at the tree's
    /// pretty print.
    pub fn from_value(value: &serde_json::Value) -> Result<Scenario, ScenarioError> {
        // Straight from the tree when it reads cleanly: printing it and
        // parsing the text again costs time and memory on every run (the
        // floats come out the same: serde_json's `float_roundtrip`). Only a
        // document that does not parse is printed, once, for a message that
        // names its line.
        let version_ok = !matches!(
            value.get("version").and_then(serde_json::Value::as_u64),
            Some(v) if v != u64::from(SCENARIO_VERSION)
        );
        if value.is_object() && version_ok {
            if let Ok(s) = Scenario::deserialize(value) {
                if unread_field(value, &s)?.is_none() {
                    s.validate()?;
                    return Ok(s);
                }
            }
        }
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
    /// [`crate::map::io::map_spec::PLAIN_ROWS_MAX_SIDE`] cells a side,
    /// run-length encoded above).
    pub fn with_inline_grid(mut self, grid: OccupancyGrid) -> Scenario {
        self.map = MapSpec::Inline(InlineMap::new(grid));
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
            MapSpec::File(f) => f.validate()?,
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
        if let Some(g) = &self.global_planner {
            g.validate().map_err(|e| invalid(&e))?;
            let name = self
                .local_planner
                .as_ref()
                .map_or(registry::DEFAULT_PLANNER, |p| p.name.as_str());
            if registry::is_registered(name) {
                g.check_follower(name).map_err(|e| invalid(&e))?;
            }
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

    /// The scenario's map ([`MapSpec::load`]: the inline grid, or the
    /// referenced file read through `read`, given a path relative to the
    /// scenario file), with start and goal checked against it.
    pub fn load_grid(
        &self,
        read: &mut dyn FnMut(&str) -> Result<Vec<u8>, String>,
    ) -> Result<OccupancyGrid, ScenarioError> {
        let grid = self.map.load(read)?;
        self.validate_against(&grid)?;
        Ok(grid)
    }
}
