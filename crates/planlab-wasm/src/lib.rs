//! wasm-bindgen layer over planlab-core for the browser playground.
//!
//! Converts at the boundary and forwards; no planning happens here
//! (ARCHITECTURE.md, "Crates"):
//! - [`MapHandle`] owns one [`OccupancyGrid`]; maps are read by the core's
//!   Moving AI, ROS and ASCII readers and edited cell by cell.
//! - [`plan`] forwards to [`plan_on_map`] with a [`GridPlanOptions`] that
//!   crosses as a plain JS object (serde); the [`PlanResult`] hands its bulk
//!   data out as typed arrays (`Uint32Array` of `col, row` pairs).
//! - [`ScenarioHandle`] reads planlab's scenario JSON (map, start, goal,
//!   planner options); a referenced map file is looked up among the files
//!   the user opened with it.
//! - Every core error becomes a `JsError` carrying the core's message.
//! - [`ScenBatch`] solves a whole Moving AI `.scen` in one call so the page
//!   can time it with `performance.now()` (core reads no clock) without
//!   per-query boundary overhead; the same [`batch::Batch`] runs natively in
//!   `planlab bench scen` for the wasm-vs-native comparison
//!   (`scripts/bench-browser.mjs`).
//!
//! - [`PlanSession`] keeps a map's planner and passability grid between
//!   plans for the grid page (edits update it cell by cell) and returns the
//!   search as events ([`RecordedPlan`]); [`DStarSession`] keeps a D* Lite
//!   search, repaired after edits and moved starts; see [`session`]. Both
//!   come with the `grid-search` feature (the grid page's module only),
//!   as do the whole-map tools of [`grid_tools`] (empty maps, clear walls,
//!   the seeded generators).
//!
//! - [`SamplingRun`] runs one seeded sampling planner (RRT … BIT*) on a
//!   copy of the page's map for the grid and race pages, stepped from JS
//!   (which owns the clock); its events cross as typed columns; see
//!   [`sampling`] (feature `grid-search`).
//!
//! - [`SimHandle`] runs one robot episode (core `sim::Episode`) for the
//!   robot page: steps, live edits (goal, movers, planner and its
//!   parameters) and everything drawn or plotted as typed arrays; see
//!   [`sim`].
//!
//! - [`ArmHandle`] runs one arm episode (core `arm::ArmEpisode`) for the
//!   arm page: the 7-DOF arm's links, joint angles, tool and hand paths,
//!   the hand's predicted positions and the minimum distance; see [`arm`].
//!
//! - [`barn`] gives the BARN page its worlds, a run's scenario (built into
//!   a [`SimHandle`] like any other), the BARN planners and the score.
//!
//! - [`ApfHandle`] runs one 2D potential-field scene (core `apf::ApfRun`)
//!   for the APF page: path, obstacles, field lattice, sampled directions,
//!   predictions; see [`apf`].
//!
//! Cell kinds cross as bytes: 0 free, 1 occupied, 2 unknown
//! ([`Cell`]'s `repr(u8)`).

#[cfg(feature = "robot")]
pub mod apf;
#[cfg(feature = "robot")]
pub mod barn;
pub mod batch;
mod draw_js;
#[cfg(feature = "grid-search")]
pub mod dstar;
#[cfg(feature = "robot")]
pub mod files;
#[cfg(feature = "grid-search")]
pub mod grid_tools;
#[cfg(feature = "grid-search")]
pub mod sampling;
#[cfg(feature = "grid-search")]
pub mod session;
#[cfg(feature = "robot")]
pub mod sim;

#[cfg(feature = "robot")]
pub use apf::ApfHandle;
#[cfg(feature = "robot")]
pub use barn::{barn_cylinders, barn_planners, barn_scenario, barn_score, barn_worlds};
#[cfg(feature = "grid-search")]
pub use dstar::{grid_algorithms, DStarSession};
#[cfg(feature = "grid-search")]
pub use grid_tools::{generate_grid, GeneratedGrid};
/// The arm page's handle, from its own crate (the arm page loads that
/// crate's smaller wasm module; the playground pages build this crate
/// without the feature).
#[cfg(feature = "arm")]
pub use planlab_wasm_arm as arm;
#[cfg(feature = "arm")]
pub use planlab_wasm_arm::{arm_choices, edit_scenario, ArmHandle};
/// The reproduce registry's variants, from their own crate (the pages load
/// that crate's module only for a variant link; the playground pages build
/// this crate without the feature).
#[cfg(feature = "reproduce")]
pub use planlab_wasm_reproduce::{reproduce_variant, reproduce_variant_info};
#[cfg(feature = "grid-search")]
pub use sampling::{sampling_algorithms, SamplingEvents, SamplingRun};
#[cfg(feature = "grid-search")]
pub use session::{PlanSession, RecordedPlan, SearchReplay};
#[cfg(feature = "robot")]
pub use sim::{generated_grid_hash, planners, SimHandle};

use planlab_core::draw;
use planlab_core::global::plan::{plan_grid_for, GridPlan, GridPlanOptions};
#[cfg(feature = "grid-search")]
use planlab_core::global::plan::{plan_on_map, plan_on_map_recording};
use planlab_core::global::{GridPos, PlanGrid};
use planlab_core::map::io::{movingai, ros};
use planlab_core::map::{Cell, OccupancyGrid};
use planlab_core::scenario::{MapSpec, Scenario};
use wasm_bindgen::prelude::*;
use wasm_bindgen::JsCast;

/// The draw layers' names, by code (`Layer as u8`): the page checks its
/// own table against them.
#[wasm_bindgen(js_name = drawLayerNames)]
pub fn draw_layer_names() -> Vec<String> {
    planlab_core::draw::Layer::ALL
        .iter()
        .map(|l| l.name().to_string())
        .collect()
}

/// Installs the panic hook once, when the module is instantiated, so a bug
/// shows up as a readable console message instead of `unreachable`.
#[wasm_bindgen(start)]
pub fn install_panic_hook() {
    console_error_panic_hook::set_once();
}

/// The cell kind of a byte from JS.
fn cell_of(kind: u8) -> Result<Cell, JsError> {
    match kind {
        0 => Ok(Cell::Free),
        1 => Ok(Cell::Occupied),
        2 => Ok(Cell::Unknown),
        k => Err(JsError::new(&format!(
            "cell kind {k} is not 0 (free), 1 (occupied) or 2 (unknown)"
        ))),
    }
}

/// Paints the segment `[col0, row0, col1, row1]` with cell kind `kind` (a
/// brush stroke between two pointer samples); returns how many cells changed.
pub(crate) fn paint_grid(
    grid: &mut OccupancyGrid,
    seg: [u32; 4],
    kind: u8,
) -> Result<u32, JsError> {
    let cell = cell_of(kind)?;
    let [c0, r0, c1, r1] = seg.map(|v| v as usize);
    Ok(grid.paint_segment((c0, r0), (c1, r1), cell)? as u32)
}

/// The cost brush: paints the segment `[col0, row0, col1, row1]` free with
/// traversal weight `weight` (1 erases a weight); returns how many cells
/// changed.
pub(crate) fn paint_weight(
    grid: &mut OccupancyGrid,
    seg: [u32; 4],
    weight: u8,
) -> Result<u32, JsError> {
    let [c0, r0, c1, r1] = seg.map(|v| v as usize);
    Ok(grid.paint_weight_segment((c0, r0), (c1, r1), weight)? as u32)
}

/// Flattens cells into `col, row` pairs for a `Uint32Array`.
fn flat(cells: &[GridPos]) -> Vec<u32> {
    let mut out = Vec::with_capacity(cells.len() * 2);
    for p in cells {
        out.push(p.col);
        out.push(p.row);
    }
    out
}

/// Plan options from a JS object; `undefined`/`null` mean the defaults and
/// missing fields take their default (the core config is `serde(default)`).
fn options_from_js(options: JsValue) -> Result<GridPlanOptions, JsError> {
    if options.is_undefined() || options.is_null() {
        return Ok(GridPlanOptions::default());
    }
    serde_wasm_bindgen::from_value(options)
        .map_err(|e| JsError::new(&format!("invalid plan options: {e}")))
}

/// The default plan options (the papers' values) as a plain JS object, so
/// the page builds its controls from the core's defaults.
#[wasm_bindgen(js_name = defaultPlanOptions)]
pub fn default_plan_options() -> Result<JsValue, JsError> {
    serde_wasm_bindgen::to_value(&GridPlanOptions::default())
        .map_err(|e| JsError::new(&e.to_string()))
}

/// The `image:` file name a ROS map YAML refers to, so the page can pick the
/// matching `.pgm` among the files the user opened.
#[wasm_bindgen(js_name = rosImageName)]
pub fn ros_image_name(yaml: &str) -> Result<String, JsError> {
    Ok(ros::parse_yaml(yaml)?.image)
}

/// The scenario JSON `text` with a run link's edits applied by the core's
/// `Recipe` (`recipe` is its JSON form, `{"planner": "dwa", "set":
/// [["sim.dt", "0.05"]]}`), as `planlab run` applies them; `text` itself
/// when there are none. With the `arm` feature it is the arm crate's (one
/// export of the name per module).
#[cfg(all(feature = "robot", not(feature = "arm")))]
#[wasm_bindgen(js_name = editScenario)]
pub fn edit_scenario(text: &str, recipe: &str) -> Result<String, JsError> {
    Ok(planlab_core::recipe::Recipe::from_json(recipe)?.edit_text(text)?)
}

/// One occupancy grid, owned on the wasm side.
#[wasm_bindgen]
#[derive(Clone, Debug)]
pub struct MapHandle {
    grid: OccupancyGrid,
}

impl MapHandle {
    /// The wrapped grid (for Rust callers and tests).
    pub fn grid(&self) -> &OccupancyGrid {
        &self.grid
    }
}

#[wasm_bindgen]
impl MapHandle {
    /// Reads a Moving AI `.map` (1 m per cell).
    #[wasm_bindgen(js_name = fromMovingAi)]
    pub fn from_movingai(text: &str) -> Result<MapHandle, JsError> {
        Ok(MapHandle {
            grid: movingai::parse_map(text)?,
        })
    }

    /// Reads a ROS map_server map from its YAML text and PGM bytes.
    #[wasm_bindgen(js_name = fromRos)]
    pub fn from_ros(yaml: &str, pgm: &[u8]) -> Result<MapHandle, JsError> {
        let meta = ros::parse_yaml(yaml)?;
        let image = ros::parse_pgm(pgm)?;
        Ok(MapHandle {
            grid: ros::grid_from_pgm(&meta, &image)?,
        })
    }

    /// Reads ASCII art (`.` free, `#` occupied, `?` unknown; 1 m per cell).
    #[wasm_bindgen(js_name = fromAscii)]
    pub fn from_ascii(text: &str) -> Result<MapHandle, JsError> {
        Ok(MapHandle {
            grid: OccupancyGrid::from_ascii(text)?,
        })
    }

    /// Width in cells.
    #[wasm_bindgen(getter)]
    pub fn width(&self) -> u32 {
        self.grid.width() as u32
    }

    /// Height in cells.
    #[wasm_bindgen(getter)]
    pub fn height(&self) -> u32 {
        self.grid.height() as u32
    }

    /// Metres per cell.
    #[wasm_bindgen(getter)]
    pub fn resolution(&self) -> f64 {
        self.grid.resolution()
    }

    /// World pose of the bottom-left image corner: `[x, y, yaw]`.
    pub fn origin(&self) -> Vec<f64> {
        let o = self.grid.origin();
        vec![o.x, o.y, o.yaw]
    }

    /// Row-major cell kinds (row 0 at the top), one byte each.
    pub fn cells(&self) -> Vec<u8> {
        self.grid.cells().iter().map(|&c| c as u8).collect()
    }

    /// Number of `[free, occupied, unknown]` cells.
    pub fn counts(&self) -> Vec<u32> {
        let (f, o, u) = self.grid.counts();
        vec![f as u32, o as u32, u as u32]
    }

    /// World coordinates `[x, y]` (metres) of the centre of a cell.
    #[wasm_bindgen(js_name = cellToWorld)]
    pub fn cell_to_world(&self, col: u32, row: u32) -> Result<Vec<f64>, JsError> {
        self.check_on_map(col, row)?;
        let (x, y) = self.grid.cell_to_world(col as usize, row as usize);
        Ok(vec![x, y])
    }

    /// Sets one cell; errors off the map or for an unknown kind.
    #[wasm_bindgen(js_name = setCell)]
    pub fn set_cell(&mut self, col: u32, row: u32, kind: u8) -> Result<(), JsError> {
        let cell = cell_of(kind)?;
        Ok(self.grid.set(col as usize, row as usize, cell)?)
    }

    /// Sets every cell the straight segment between two cell centres crosses
    /// (a brush stroke between two pointer samples); returns how many cells
    /// changed. Both ends must be on the map.
    #[wasm_bindgen(js_name = paintSegment)]
    pub fn paint_segment(
        &mut self,
        col0: u32,
        row0: u32,
        col1: u32,
        row1: u32,
        kind: u8,
    ) -> Result<u32, JsError> {
        paint_grid(&mut self.grid, [col0, row0, col1, row1], kind)
    }

    /// The cost brush: paints the cells the segment between two cell
    /// centres crosses free with traversal weight `weight` (1–9; 1 erases
    /// a weight); returns how many cells changed.
    #[wasm_bindgen(js_name = paintWeight)]
    pub fn paint_weight(
        &mut self,
        col0: u32,
        row0: u32,
        col1: u32,
        row1: u32,
        weight: u8,
    ) -> Result<u32, JsError> {
        paint_weight(&mut self.grid, [col0, row0, col1, row1], weight)
    }

    /// The traversal weight of a cell (1 = ordinary; off the map 1).
    #[wasm_bindgen(js_name = weightAt)]
    pub fn weight_at(&self, col: u32, row: u32) -> u8 {
        self.grid.weight(col as usize, row as usize)
    }

    /// Whether some cell weighs more than 1.
    #[wasm_bindgen(getter)]
    pub fn weighted(&self) -> bool {
        self.grid.is_weighted()
    }

    /// The map as a Moving AI `.map` (unknown written as blocked).
    #[wasm_bindgen(js_name = toMovingAi)]
    pub fn to_movingai(&self) -> String {
        movingai::write_map(&self.grid)
    }

    /// The map as ASCII art.
    #[wasm_bindgen(js_name = toAscii)]
    pub fn to_ascii(&self) -> String {
        self.grid.to_ascii()
    }

    /// An independent copy (the page keeps the loaded map for "reset").
    #[wasm_bindgen(js_name = clone)]
    pub fn duplicate(&self) -> MapHandle {
        self.clone()
    }

    /// The core's draw list of the map (`layers`, a bit per layer code):
    /// the map, the `inflation` mask given (from `inflationMask`) and the
    /// `start` and `goal` cells (`[col, row]`) given, as
    /// `{data, items, cells}`.
    #[wasm_bindgen(unchecked_return_type = "DrawArrays")]
    pub fn draw(
        &self,
        layers: u32,
        inflation: Option<Vec<u8>>,
        start: Option<Vec<u32>>,
        goal: Option<Vec<u32>>,
    ) -> Result<js_sys::Object, JsError> {
        let cell = |v: Option<Vec<u32>>| match v.as_deref() {
            None => Ok(None),
            Some(&[col, row]) => Ok(Some(GridPos { col, row })),
            Some(other) => Err(JsError::new(&format!(
                "a cell is [col, row], got {other:?}"
            ))),
        };
        let plan = draw::GridPlanDraw {
            grid: &self.grid,
            inflation: inflation.as_deref(),
            path: &[],
            key_points: &[],
            feature_nodes: &[],
            start: cell(start)?,
            goal: cell(goal)?,
        };
        if plan
            .inflation
            .is_some_and(|m| m.len() != self.grid.cells().len())
        {
            return Err(JsError::new("the inflation mask is not this map's size"));
        }
        let mut out = draw::DrawList::default();
        draw::grid_plan(&plan, draw::Layers::from_bits(layers), &mut out);
        draw_js::draw_arrays(&out)
    }
}

impl MapHandle {
    fn check_on_map(&self, col: u32, row: u32) -> Result<(), JsError> {
        if self.grid.in_bounds(i64::from(col), i64::from(row)) {
            Ok(())
        } else {
            Err(JsError::new(&format!(
                "cell ({col}, {row}) is outside the {}×{} map",
                self.grid.width(),
                self.grid.height()
            )))
        }
    }
}

/// A planlab scenario (JSON, version 1): map, start, goal, planner options.
#[wasm_bindgen]
#[derive(Clone, Debug)]
pub struct ScenarioHandle {
    scenario: Scenario,
}

#[wasm_bindgen]
impl ScenarioHandle {
    /// Reads and validates scenario JSON.
    #[wasm_bindgen(js_name = fromJson)]
    pub fn from_json(text: &str) -> Result<ScenarioHandle, JsError> {
        Ok(ScenarioHandle {
            scenario: Scenario::from_json(text)?,
        })
    }

    /// Short title.
    #[wasm_bindgen(getter)]
    pub fn name(&self) -> String {
        self.scenario.name.clone()
    }

    /// What the scenario shows.
    #[wasm_bindgen(getter)]
    pub fn description(&self) -> String {
        self.scenario.description.clone()
    }

    /// Start cell `[col, row]`.
    pub fn start(&self) -> Vec<u32> {
        let p = self.scenario.start.pos();
        vec![p.col, p.row]
    }

    /// Goal cell `[col, row]`.
    pub fn goal(&self) -> Vec<u32> {
        let p = self.scenario.goal.pos();
        vec![p.col, p.row]
    }

    /// The scenario's grid planner options as a plain JS object.
    #[wasm_bindgen(js_name = plannerOptions)]
    pub fn planner_options(&self) -> Result<JsValue, JsError> {
        serde_wasm_bindgen::to_value(&self.scenario.grid_planner)
            .map_err(|e| JsError::new(&e.to_string()))
    }

    /// The referenced map file, or `undefined` for an inline map.
    #[wasm_bindgen(js_name = mapFile)]
    pub fn map_file(&self) -> Option<String> {
        match &self.scenario.map {
            MapSpec::File(f) => Some(f.file.clone()),
            MapSpec::Inline(_) => None,
        }
    }

    /// The scenario's map. `files` maps file names to their bytes
    /// (`{"map.yaml": Uint8Array, …}`); a referenced file is looked up by
    /// its base name, since the browser gives no directories.
    #[wasm_bindgen(js_name = loadMap)]
    pub fn load_map(&self, files: &js_sys::Object) -> Result<MapHandle, JsError> {
        Ok(MapHandle {
            grid: self.scenario.load_grid(&mut files_reader(files))?,
        })
    }
}

/// Reads a file a scenario refers to from `files` (`{"name": Uint8Array}`),
/// by base name since the browser gives no directories.
pub(crate) fn files_reader(
    files: &js_sys::Object,
) -> impl FnMut(&str) -> Result<Vec<u8>, String> + '_ {
    move |path: &str| {
        let base = path.rsplit(['/', '\\']).next().unwrap_or(path);
        let v = js_sys::Reflect::get(files, &JsValue::from_str(base))
            .map_err(|_| format!("cannot look up {base}"))?;
        if v.is_undefined() {
            return Err(format!(
                "not among the opened files: open {base} together with the scenario"
            ));
        }
        v.dyn_into::<js_sys::Uint8Array>()
            .map(|a| a.to_vec())
            .map_err(|_| format!("{base} was not passed as bytes"))
    }
}

/// A finished plan; bulk data leaves as typed arrays.
#[wasm_bindgen]
#[derive(Clone, Debug)]
pub struct PlanResult {
    plan: GridPlan,
}

#[wasm_bindgen]
impl PlanResult {
    /// Path cells as `col, row` pairs, start to goal.
    pub fn path(&self) -> Vec<u32> {
        flat(&self.plan.path.cells)
    }

    /// Number of path cells.
    #[wasm_bindgen(getter, js_name = pathLen)]
    pub fn path_len(&self) -> u32 {
        self.plan.path.cells.len() as u32
    }

    /// Expanded cells in expansion order as `col, row` pairs (empty unless
    /// recording was asked for).
    pub fn expanded(&self) -> Vec<u32> {
        flat(&self.plan.expanded_cells)
    }

    /// Key points as `col, row` pairs (empty unless asked for).
    #[wasm_bindgen(js_name = keyPoints)]
    pub fn key_points(&self) -> Vec<u32> {
        flat(&self.plan.keypoints)
    }

    /// Bottom-Up feature nodes as `col, row` pairs (empty unless asked for).
    #[wasm_bindgen(js_name = featureNodes)]
    pub fn feature_nodes(&self) -> Vec<u32> {
        flat(&self.plan.feature_nodes)
    }

    /// The core's draw list of the plan on `map` (`layers`, a bit per
    /// layer code): its path, key points and feature nodes, as
    /// `{data, items, cells}`.
    #[wasm_bindgen(unchecked_return_type = "DrawArrays")]
    pub fn draw(&self, map: &MapHandle, layers: u32) -> Result<js_sys::Object, JsError> {
        let plan = draw::GridPlanDraw {
            grid: &map.grid,
            inflation: None,
            path: &self.plan.path.cells,
            key_points: &self.plan.keypoints,
            feature_nodes: &self.plan.feature_nodes,
            start: None,
            goal: None,
        };
        let keep = draw::Layers::from_bits(layers).bits()
            & [
                draw::Layer::GlobalPath,
                draw::Layer::KeyPoints,
                draw::Layer::FeatureNodes,
            ]
            .into_iter()
            .collect::<draw::Layers>()
            .bits();
        let mut out = draw::DrawList::default();
        draw::grid_plan(&plan, draw::Layers::from_bits(keep), &mut out);
        draw_js::draw_arrays(&out)
    }

    /// Safety index per path node (safe A* only, else empty).
    pub fn safety(&self) -> Vec<f64> {
        self.plan.safety.clone()
    }

    /// Path cost in cells (moves of 1 and √2, each times the weight of the
    /// cell entered on weighted cells).
    #[wasm_bindgen(getter)]
    pub fn cost(&self) -> f64 {
        self.plan.path.cost
    }

    /// What the plan should say, e.g. that BFS ignored the cell weights
    /// (`undefined` when nothing).
    #[wasm_bindgen(getter)]
    pub fn note(&self) -> Option<String> {
        self.plan.note.clone()
    }

    /// Path length in metres (the polyline's; cost × resolution on a
    /// unit-cost map).
    #[wasm_bindgen(getter, js_name = lengthM)]
    pub fn length_m(&self) -> f64 {
        self.plan.length_m
    }

    /// Nodes the search expanded.
    #[wasm_bindgen(getter, js_name = expandedCount)]
    pub fn expanded_count(&self) -> u32 {
        self.plan.path.expanded as u32
    }
}

/// Plans from `(start_col, start_row)` to `(goal_col, goal_row)` on `map`.
///
/// `options` is a [`GridPlanOptions`] as a JS object (missing fields take
/// their defaults), e.g. `{algorithm: "jps", diagonal: "no_corner_cutting"}`.
/// With `record_expanded` the result also lists the expanded cells. In the
/// grid pages' module only (feature `grid-search`): recording links every
/// planner's observed search, which the robot pages do not need.
#[cfg(feature = "grid-search")]
#[wasm_bindgen]
pub fn plan(
    map: &MapHandle,
    start_col: u32,
    start_row: u32,
    goal_col: u32,
    goal_row: u32,
    options: JsValue,
    record_expanded: bool,
) -> Result<PlanResult, JsError> {
    let options = options_from_js(options)?;
    let (start, goal) = (
        GridPos::new(start_col, start_row),
        GridPos::new(goal_col, goal_row),
    );
    let plan = if record_expanded {
        plan_on_map_recording(&map.grid, start, goal, &options)?
    } else {
        plan_on_map(&map.grid, start, goal, &options)?
    };
    Ok(PlanResult { plan })
}

/// Cells that are passable on `map` but blocked for the planner under
/// `options` (grown obstacles from `inflate_m`): one byte per cell, 1 =
/// blocked by inflation, row-major.
#[wasm_bindgen(js_name = inflationMask)]
pub fn inflation_mask(map: &MapHandle, options: JsValue) -> Result<Vec<u8>, JsError> {
    let options = options_from_js(options)?;
    let planned = plan_grid_for(&map.grid, &options)?;
    let raw = PlanGrid::new(&map.grid, options.allow_unknown);
    let (w, h) = (map.grid.width(), map.grid.height());
    let mut mask = vec![0u8; w * h];
    for (i, m) in mask.iter_mut().enumerate() {
        let (c, r) = ((i % w) as i64, (i / w) as i64);
        *m = u8::from(raw.is_free(c, r) && !planned.is_free(c, r));
    }
    Ok(mask)
}

/// The core's word when `radius_m` of inflation cannot change a map of
/// `resolution` m cells (less than one cell), else `undefined`: the grid
/// page shows it beside the plan, as `planlab plan --inflate` prints it.
#[wasm_bindgen(js_name = inflationNote)]
pub fn inflation_note(radius_m: f64, resolution: f64) -> Option<String> {
    planlab_core::map::costmap::inflation_note(radius_m, resolution)
}

/// Every query of a Moving AI `.scen` on one map, ready to be solved in a
/// single call (for timing from JS).
#[wasm_bindgen]
pub struct ScenBatch {
    inner: batch::Batch,
}

#[wasm_bindgen]
impl ScenBatch {
    /// Parses `scen_text`, checks its rows against `map`, builds the planner
    /// from `options` (a [`GridPlanOptions`] object, `undefined` = A*).
    #[wasm_bindgen(constructor)]
    pub fn new(map: &MapHandle, scen_text: &str, options: JsValue) -> Result<ScenBatch, JsError> {
        let options = options_from_js(options)?;
        Ok(ScenBatch {
            inner: batch::Batch::new(&map.grid, scen_text, &options)?,
        })
    }

    /// Number of queries.
    #[wasm_bindgen(getter)]
    pub fn rows(&self) -> u32 {
        self.inner.len() as u32
    }

    /// Sum of the `.scen` optimal lengths.
    #[wasm_bindgen(getter, js_name = optimalSum)]
    pub fn optimal_sum(&self) -> f64 {
        self.inner.optimal_sum()
    }

    /// Solves every query once; returns the summed path cost.
    #[wasm_bindgen(js_name = solveAll)]
    pub fn solve_all(&self) -> Result<f64, JsError> {
        Ok(self.inner.solve_all()?)
    }
}

/// The DWA step of the reference benchmark scene
/// ([`planlab_core::bench::DwaStepBench`]), for timing from JS: the same
/// work `planlab bench step` times natively.
#[cfg(feature = "robot")]
#[wasm_bindgen]
pub struct DwaBench {
    inner: planlab_core::bench::DwaStepBench,
}

#[cfg(feature = "robot")]
#[wasm_bindgen]
impl DwaBench {
    /// Builds the reference scene (200 × 200 map, 20 movers, 20 × 40 samples, 3 s).
    #[wasm_bindgen(constructor)]
    pub fn new() -> Result<DwaBench, JsError> {
        Ok(DwaBench {
            inner: planlab_core::bench::DwaStepBench::reference()?,
        })
    }

    /// Runs `n` steps; returns the sum of the chosen v + ω (a checksum).
    pub fn run(&mut self, n: u32) -> f64 {
        self.inner.run(n as usize)
    }
}
