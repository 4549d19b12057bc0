//! D* Lite for the grid page (core `global::dstar_lite::DStarLite`): the
//! search state stays between calls, so after a painted wall or a moved
//! start the next plan repairs only what changed (Koenig & Likhachev 2002),
//! and each call's events and expanded count are its own. The page shows
//! the repair's expansions beside a fresh A*'s on the same edited map.

use crate::session::{segment_cells, EventColumns, RecordedPlan, EVENT_LIMIT};
use crate::{cell_of, options_from_js, paint_grid, MapHandle, PlanResult};
use planlab_core::global::dstar_lite::DStarLite;
use planlab_core::global::plan::{plan_grid_for, Algorithm, GridPlan, GridPlanOptions};
use planlab_core::global::{GridPos, PlanGrid};
use planlab_core::map::OccupancyGrid;
use wasm_bindgen::prelude::*;

/// One D* Lite search kept between plans.
#[wasm_bindgen]
pub struct DStarSession {
    map: OccupancyGrid,
    options: GridPlanOptions,
    /// Passability as the search knows it (inflated when asked for).
    known: PlanGrid,
    dstar: DStarLite,
}

impl DStarSession {
    /// A session for `start` → `goal` on `map` (Rust callers and tests).
    pub fn with_options(
        map: OccupancyGrid,
        options: GridPlanOptions,
        start: GridPos,
        goal: GridPos,
    ) -> Result<Self, JsError> {
        let grid = plan_grid_for(&map, &options)?;
        grid.check_endpoints(start, goal)?;
        let dstar = DStarLite::new(&grid, start, goal, &options)?;
        Ok(Self {
            map,
            options,
            known: grid,
            dstar,
        })
    }

    /// Tells the search about the cells an edit changed: the touched cells,
    /// or under inflation every cell whose inflated passability changed
    /// (a wall grows by the radius).
    fn sync(&mut self, touched: &[(usize, usize)]) -> Result<(), JsError> {
        // Weights first: a cell freed by the cost brush is entered at its
        // new weight.
        for &(c, r) in touched {
            let w = self.map.weight(c, r);
            if self.known.weight(c as i64, r as i64) != u32::from(w) {
                self.known.set_weight(c, r, w);
                self.dstar.set_weight(GridPos::new(c as u32, r as u32), w);
            }
        }
        let set = |dstar: &mut DStarLite, known: &mut PlanGrid, c: usize, r: usize, free: bool| {
            if known.is_free(c as i64, r as i64) != free {
                known.set_free(c, r, free);
                dstar.set_blocked(GridPos::new(c as u32, r as u32), !free);
            }
        };
        if self.options.inflate_m > 0.0 {
            let now = plan_grid_for(&self.map, &self.options)?;
            for r in 0..now.height() {
                for c in 0..now.width() {
                    set(
                        &mut self.dstar,
                        &mut self.known,
                        c,
                        r,
                        now.is_free(c as i64, r as i64),
                    );
                }
            }
        } else {
            for &(c, r) in touched {
                if let Some(cell) = self.map.get(c, r) {
                    set(
                        &mut self.dstar,
                        &mut self.known,
                        c,
                        r,
                        cell.passable(self.options.allow_unknown),
                    );
                }
            }
        }
        Ok(())
    }
}

#[wasm_bindgen]
impl DStarSession {
    /// A D* Lite search on a copy of `map` with `options` (inflation is
    /// applied once, here: later edits are taken cell by cell).
    #[wasm_bindgen(constructor)]
    pub fn new(
        map: &MapHandle,
        options: JsValue,
        start_col: u32,
        start_row: u32,
        goal_col: u32,
        goal_row: u32,
    ) -> Result<DStarSession, JsError> {
        Self::with_options(
            map.grid().clone(),
            options_from_js(options)?,
            GridPos::new(start_col, start_row),
            GridPos::new(goal_col, goal_row),
        )
    }

    /// Computes or repairs the path; the events and expanded count are
    /// this call's only.
    pub fn plan(&mut self) -> Result<RecordedPlan, JsError> {
        let mut events = EventColumns::with_limit(EVENT_LIMIT);
        let path = self.dstar.plan(&mut events)?;
        let length_m = if self.known.is_weighted() {
            planlab_core::global::Path::polyline_length(&path.cells) * self.map.resolution()
        } else {
            path.cost * self.map.resolution()
        };
        let plan = GridPlan {
            length_m,
            path,
            keypoints: Vec::new(),
            feature_nodes: Vec::new(),
            expanded_cells: Vec::new(),
            safety: Vec::new(),
            note: None,
        };
        Ok(RecordedPlan::new(PlanResult { plan }, events))
    }

    /// Sets one cell (0 free, 1 occupied, 2 unknown); the next plan repairs.
    #[wasm_bindgen(js_name = setCell)]
    pub fn set_cell(&mut self, col: u32, row: u32, kind: u8) -> Result<(), JsError> {
        let cell = cell_of(kind)?;
        self.map.set(col as usize, row as usize, cell)?;
        self.sync(&[(col as usize, row as usize)])
    }

    /// Paints a segment as `MapHandle.paintSegment`; returns the cells changed.
    #[wasm_bindgen(js_name = paintSegment)]
    pub fn paint_segment(
        &mut self,
        col0: u32,
        row0: u32,
        col1: u32,
        row1: u32,
        kind: u8,
    ) -> Result<u32, JsError> {
        let changed = paint_grid(&mut self.map, [col0, row0, col1, row1], kind)?;
        if changed > 0 {
            self.sync(&segment_cells(col0, row0, col1, row1))?;
        }
        Ok(changed)
    }

    /// The cost brush, as `MapHandle.paintWeight`; the next plan repairs.
    #[wasm_bindgen(js_name = paintWeight)]
    pub fn paint_weight(
        &mut self,
        col0: u32,
        row0: u32,
        col1: u32,
        row1: u32,
        weight: u8,
    ) -> Result<u32, JsError> {
        let changed = crate::paint_weight(&mut self.map, [col0, row0, col1, row1], weight)?;
        if changed > 0 {
            self.sync(&segment_cells(col0, row0, col1, row1))?;
        }
        Ok(changed)
    }

    /// The robot moved: the search now starts at `(col, row)`.
    #[wasm_bindgen(js_name = moveStart)]
    pub fn move_start(&mut self, col: u32, row: u32) -> Result<(), JsError> {
        Ok(self.dstar.move_start(GridPos::new(col, row))?)
    }
}

/// One grid planner as the help shows it.
#[derive(serde::Serialize)]
struct AlgorithmInfo {
    name: &'static str,
    optimal: bool,
    reference: &'static str,
    summary: &'static str,
    /// Optimal, complete, any-angle, incremental, and the four in words.
    properties: planlab_core::global::explain::Properties,
}

/// The core's grid planners (`Algorithm::ALL`): JSON name, whether it is
/// optimal, its reference, plain-language summary and properties, for the
/// page's menu and help.
#[wasm_bindgen(js_name = gridAlgorithms)]
pub fn grid_algorithms() -> Result<JsValue, JsError> {
    let all: Vec<AlgorithmInfo> = Algorithm::ALL
        .iter()
        .map(|&(a, name)| AlgorithmInfo {
            name,
            optimal: a.optimal(),
            reference: a.reference(),
            summary: a.summary(),
            properties: a.properties(),
        })
        .collect();
    serde_wasm_bindgen::to_value(&all).map_err(|e| JsError::new(&e.to_string()))
}
