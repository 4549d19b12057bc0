//! A planning session for the grid page: the planner and its passability
//! grid are built once from the map and the options and kept between calls,
//! and edits update the grid cell by cell, so a replan while the user drags
//! an endpoint or paints a wall costs about the search alone (a fresh
//! [`crate::plan`] rebuilds the `PlanGrid` and its bit-packed lines every
//! call: 2–3 ms on a 512 × 512 map).
//!
//! [`PlanSession::plan_recorded`] also returns the search as events for the
//! page's player ([`RecordedPlan`]).

use crate::{cell_of, options_from_js, paint_grid, MapHandle, PlanResult};
use planlab_core::draw;
use planlab_core::global::explain::OpenOrder;
use planlab_core::global::plan::{
    build_observed_planner, plan_grid_for, plan_on_grid_observed, GridPlan, GridPlanError,
    GridPlanOptions,
};
use planlab_core::global::posthoc::PosthocRecorder;
use planlab_core::global::{
    supercover, GridPos, ObservedGridPlanner, PlanError, PlanGrid, SearchEvent, SearchObserver,
};
use planlab_core::map::OccupancyGrid;
use wasm_bindgen::prelude::*;

/// Events kept at most per recording (each is ~40 bytes across the
/// boundary): a 512 × 512 Dijkstra records a few million.
pub const EVENT_LIMIT: usize = 4_000_000;

/// A map, options, planner and passability grid kept between plans.
#[wasm_bindgen]
pub struct PlanSession {
    map: OccupancyGrid,
    options: GridPlanOptions,
    /// The planner the options ask for, or why they cannot build one (shown
    /// at the next plan, as a fresh `plan` would).
    planner: Result<Box<dyn ObservedGridPlanner>, PlanError>,
    /// The passability grid; `None` until the next plan rebuilds it (first
    /// use, new options, or an edit under inflation, which can change cells
    /// up to the radius away).
    grid: Option<PlanGrid>,
    /// Grid rebuilds so far (the tests check that edits do not rebuild).
    rebuilds: u32,
}

impl PlanSession {
    /// A session over `map` (Rust callers and tests).
    pub fn with_options(map: OccupancyGrid, options: GridPlanOptions) -> Self {
        Self {
            planner: build_observed_planner(&options),
            map,
            options,
            grid: None,
            rebuilds: 0,
        }
    }

    /// Keeps the grid in step with one edited map cell.
    fn sync_cell(&mut self, col: usize, row: usize) {
        if self.options.inflate_m > 0.0 {
            self.grid = None;
        } else if let (Some(grid), Some(cell)) = (self.grid.as_mut(), self.map.get(col, row)) {
            grid.set_free(col, row, cell.passable(self.options.allow_unknown));
            grid.set_weight(col, row, self.map.weight(col, row));
        }
    }

    /// Plans on the kept grid, reporting the search's events (and key
    /// points' / Bottom-Up's segment checks) to `obs`: the core's
    /// `plan_on_grid_observed` on the kept grid and planner.
    pub fn plan_observed(
        &mut self,
        start: GridPos,
        goal: GridPos,
        obs: &mut dyn SearchObserver,
    ) -> Result<GridPlan, GridPlanError> {
        let planner = match &self.planner {
            Ok(p) => p,
            Err(e) => return Err(e.clone().into()),
        };
        // The kept grid, or a new one when an edit or new options dropped it.
        let grid = match self.grid.take() {
            Some(g) => g,
            None => {
                let built = plan_grid_for(&self.map, &self.options)?;
                self.rebuilds += 1;
                built
            }
        };
        let grid = &*self.grid.insert(grid);
        plan_on_grid_observed(
            &self.map,
            grid,
            planner.as_ref(),
            start,
            goal,
            &self.options,
            obs,
        )
    }
}

/// The expanded cells in order (the close events).
struct Closed(Vec<GridPos>);

impl SearchObserver for Closed {
    fn event(&mut self, e: SearchEvent) {
        if let SearchEvent::Close { cell } = e {
            self.0.push(cell);
        }
    }
}

/// The cells a painted segment between two cell centres covers (as
/// `OccupancyGrid::paint_segment` paints them).
pub(crate) fn segment_cells(col0: u32, row0: u32, col1: u32, row1: u32) -> Vec<(usize, usize)> {
    let mut cells = Vec::new();
    supercover(
        GridPos::new(col0, row0),
        GridPos::new(col1, row1),
        |c, r, _| cells.push((c as usize, r as usize)),
    );
    cells
}

#[wasm_bindgen]
impl PlanSession {
    /// A session over a copy of `map` with `options` (a `GridPlanOptions`
    /// object; `undefined` = defaults). Bad options are reported by the
    /// first plan, as `plan` would.
    #[wasm_bindgen(constructor)]
    pub fn new(map: &MapHandle, options: JsValue) -> Result<PlanSession, JsError> {
        Ok(Self::with_options(
            map.grid().clone(),
            options_from_js(options)?,
        ))
    }

    /// New options: the planner is rebuilt, the grid only when the
    /// passability changes (inflation, unknown cells).
    #[wasm_bindgen(js_name = setOptions)]
    pub fn set_options(&mut self, options: JsValue) -> Result<(), JsError> {
        let options = options_from_js(options)?;
        let same_grid = options.inflate_m.to_bits() == self.options.inflate_m.to_bits()
            && options.allow_unknown == self.options.allow_unknown;
        if !same_grid {
            self.grid = None;
        }
        self.planner = build_observed_planner(&options);
        self.options = options;
        Ok(())
    }

    /// Replaces the map (e.g. "reset edits"); the grid is rebuilt.
    #[wasm_bindgen(js_name = setMap)]
    pub fn set_map(&mut self, map: &MapHandle) {
        self.map = map.grid().clone();
        self.grid = None;
    }

    /// Sets one cell (0 free, 1 occupied, 2 unknown).
    #[wasm_bindgen(js_name = setCell)]
    pub fn set_cell(&mut self, col: u32, row: u32, kind: u8) -> Result<(), JsError> {
        let cell = cell_of(kind)?;
        self.map.set(col as usize, row as usize, cell)?;
        self.sync_cell(col as usize, row as usize);
        Ok(())
    }

    /// Paints the cells the segment between two cell centres crosses, as
    /// `MapHandle.paintSegment`; returns how many changed.
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
            for (c, r) in segment_cells(col0, row0, col1, row1) {
                self.sync_cell(c, r);
            }
        }
        Ok(changed)
    }

    /// The cost brush, as `MapHandle.paintWeight`; returns how many cells
    /// changed.
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
            for (c, r) in segment_cells(col0, row0, col1, row1) {
                self.sync_cell(c, r);
            }
        }
        Ok(changed)
    }

    /// How many times the passability grid was built (edits without
    /// inflation do not rebuild it).
    #[wasm_bindgen(getter)]
    pub fn rebuilds(&self) -> u32 {
        self.rebuilds
    }

    /// Plans as the free function `plan` does, on the kept grid.
    pub fn plan(
        &mut self,
        start_col: u32,
        start_row: u32,
        goal_col: u32,
        goal_row: u32,
        record_expanded: bool,
    ) -> Result<PlanResult, JsError> {
        let (start, goal) = (
            GridPos::new(start_col, start_row),
            GridPos::new(goal_col, goal_row),
        );
        let plan = if record_expanded {
            let mut closed = Closed(Vec::new());
            let mut plan = self.plan_observed(start, goal, &mut closed)?;
            plan.expanded_cells = closed.0;
            plan
        } else {
            self.plan_observed(start, goal, &mut ())?
        };
        Ok(PlanResult { plan })
    }

    /// Plans and returns the search as events for the player.
    #[wasm_bindgen(js_name = planRecorded)]
    pub fn plan_recorded(
        &mut self,
        start_col: u32,
        start_row: u32,
        goal_col: u32,
        goal_row: u32,
    ) -> Result<RecordedPlan, JsError> {
        let mut events = EventColumns::with_limit(EVENT_LIMIT);
        let plan = self.plan_observed(
            GridPos::new(start_col, start_row),
            GridPos::new(goal_col, goal_row),
            &mut events,
        )?;
        Ok(RecordedPlan::new(PlanResult { plan }, events))
    }
}

#[wasm_bindgen]
impl PlanSession {
    /// Plans and returns the search as a Posthoc search trace (format
    /// 1.4.0, JSON text; the core's `global::posthoc`): what the grid
    /// page's "Posthoc" button saves.
    #[wasm_bindgen(js_name = posthocTrace)]
    pub fn posthoc_trace(
        &mut self,
        start_col: u32,
        start_row: u32,
        goal_col: u32,
        goal_row: u32,
    ) -> Result<String, JsError> {
        let (start, goal) = (
            GridPos::new(start_col, start_row),
            GridPos::new(goal_col, goal_row),
        );
        let mut rec =
            PosthocRecorder::new(self.map.width(), start, goal, &self.options, EVENT_LIMIT);
        self.plan_observed(start, goal, &mut rec)?;
        let trace = rec.finish()?;
        serde_json::to_string(&trace).map_err(|e| JsError::new(&e.to_string()))
    }
}

/// Event kinds as they cross (`kinds` bytes).
pub mod kind {
    /// A cell entered the open set or its g improved.
    pub const OPEN: u8 = 0;
    /// A cell was expanded (closed).
    pub const CLOSE: u8 = 1;
    /// A straight-line check that passed.
    pub const LINE_CLEAR: u8 = 2;
    /// A straight-line check that failed.
    pub const LINE_BLOCKED: u8 = 3;
}

/// "No cell" in the `others` column (an open event without a parent).
pub const NO_CELL: u32 = u32::MAX;

/// Search events as columns, one entry per event (bounded like the core's
/// `SearchLog`: at most `limit`, then `truncated`).
#[derive(Clone, Debug, Default)]
pub struct EventColumns {
    limit: usize,
    kinds: Vec<u8>,
    /// The event's cell (open, close) or the line's start, `col, row`.
    cells: Vec<u32>,
    /// The parent (open) or the line's end, `col, row`; [`NO_CELL`] twice
    /// when there is none.
    others: Vec<u32>,
    g: Vec<f64>,
    h: Vec<f64>,
    truncated: bool,
}

impl EventColumns {
    fn push(&mut self, k: u8, cell: GridPos, other: Option<GridPos>, g: f64, h: f64) {
        self.kinds.push(k);
        self.cells.extend([cell.col, cell.row]);
        let o = other.map_or([NO_CELL, NO_CELL], |p| [p.col, p.row]);
        self.others.extend(o);
        self.g.push(g);
        self.h.push(h);
    }

    /// Columns keeping at most `limit` events.
    pub fn with_limit(limit: usize) -> Self {
        Self {
            limit,
            ..Self::default()
        }
    }

    /// Number of events.
    pub fn len(&self) -> usize {
        self.kinds.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.kinds.is_empty()
    }
}

impl SearchObserver for EventColumns {
    fn event(&mut self, e: SearchEvent) {
        if self.len() >= self.limit {
            self.truncated = true;
            return;
        }
        match e {
            SearchEvent::Open { cell, parent, g, h } => self.push(kind::OPEN, cell, parent, g, h),
            SearchEvent::Close { cell } => self.push(kind::CLOSE, cell, None, f64::NAN, f64::NAN),
            SearchEvent::Line { from, to, clear } => {
                let k = if clear {
                    kind::LINE_CLEAR
                } else {
                    kind::LINE_BLOCKED
                };
                self.push(k, from, Some(to), f64::NAN, f64::NAN);
            }
        }
    }

    /// Off once full: the planner stops building events nobody keeps.
    fn enabled(&self) -> bool {
        !self.truncated
    }
}

/// A plan with its search as events: `kinds[i]` (see [`kind`]),
/// `cells`/`others` as `col, row` pairs, `g`/`h` (NaN where they do not
/// apply).
#[wasm_bindgen]
pub struct RecordedPlan {
    result: PlanResult,
    events: EventColumns,
}

impl RecordedPlan {
    /// A plan and the events of its search.
    pub fn new(result: PlanResult, events: EventColumns) -> Self {
        Self { result, events }
    }
}

#[wasm_bindgen]
impl RecordedPlan {
    /// The plan (path, cost, expanded count …); an independent copy.
    #[wasm_bindgen(getter)]
    pub fn plan(&self) -> PlanResult {
        self.result.clone()
    }

    /// Number of events.
    #[wasm_bindgen(getter)]
    pub fn length(&self) -> u32 {
        self.events.len() as u32
    }

    /// Whether the recording stopped at [`EVENT_LIMIT`] events.
    #[wasm_bindgen(getter)]
    pub fn truncated(&self) -> bool {
        self.events.truncated
    }

    /// Event kinds.
    pub fn kinds(&self) -> Vec<u8> {
        self.events.kinds.clone()
    }

    /// Each event's cell as `col, row`.
    pub fn cells(&self) -> Vec<u32> {
        self.events.cells.clone()
    }

    /// Each event's parent / line end as `col, row`.
    pub fn others(&self) -> Vec<u32> {
        self.events.others.clone()
    }

    /// g per event.
    pub fn g(&self) -> Vec<f64> {
        self.events.g.clone()
    }

    /// h per event.
    pub fn h(&self) -> Vec<f64> {
        self.events.h.clone()
    }
}

impl EventColumns {
    /// Event `i` as the core's [`SearchEvent`].
    fn event(&self, i: usize) -> SearchEvent {
        let at = |v: &[u32]| GridPos::new(v[2 * i], v[2 * i + 1]);
        let (cell, other) = (at(&self.cells), at(&self.others));
        match self.kinds[i] {
            kind::OPEN => SearchEvent::Open {
                cell,
                parent: (other.col != NO_CELL).then_some(other),
                g: self.g[i],
                h: self.h[i],
            },
            kind::CLOSE => SearchEvent::Close { cell },
            k => SearchEvent::Line {
                from: cell,
                to: other,
                clear: k == kind::LINE_CLEAR,
            },
        }
    }
}

#[wasm_bindgen]
impl RecordedPlan {
    /// The search played back on `map` (the map searched), at step 0; f =
    /// g + `weight`·h (weighted A*'s weight, else 1).
    pub fn replay(&self, map: &MapHandle, weight: f64) -> SearchReplay {
        let events = (0..self.events.len())
            .map(|i| self.events.event(i))
            .collect();
        SearchReplay {
            inner: draw::SearchReplay::new(map.grid(), events, weight),
        }
    }
}

/// A recorded search played back for the page's player (the core's
/// [`draw::SearchReplay`]): seek, counters, what a cell holds, and the
/// search layers of the draw list, which carry only the cells changed since
/// the last draw.
#[wasm_bindgen]
pub struct SearchReplay {
    inner: draw::SearchReplay,
}

/// Where a count is missing, as a number.
fn or_nan(v: Option<usize>) -> f64 {
    v.map_or(f64::NAN, |x| x as f64)
}

#[wasm_bindgen]
impl SearchReplay {
    /// Events in the recording.
    #[wasm_bindgen(getter)]
    pub fn length(&self) -> u32 {
        self.inner.len() as u32
    }

    /// Events applied.
    #[wasm_bindgen(getter)]
    pub fn step(&self) -> u32 {
        self.inner.step() as u32
    }

    /// Whether every event is applied.
    #[wasm_bindgen(getter)]
    pub fn done(&self) -> bool {
        self.inner.done()
    }

    /// Moves to `step` (clamped), forward or back.
    pub fn seek(&mut self, step: f64) {
        self.inner.seek(if step > 0.0 { step as usize } else { 0 });
    }

    /// The counters at `step` (clamped): step, events, expanded, open, f
    /// (NaN before the first expansion), lines.
    #[wasm_bindgen(js_name = countersAt)]
    pub fn counters_at(&self, step: u32) -> Vec<f64> {
        let c = self.inner.counters_at(step as usize);
        [c.step, c.events, c.expanded, c.open]
            .map(|x| x as f64)
            .into_iter()
            .chain([c.f, c.lines as f64])
            .collect()
    }

    /// The cell being expanded as `[col, row]`, or `undefined`.
    pub fn expanding(&self) -> Option<Vec<u32>> {
        self.inner.expanding().map(|p| vec![p.col, p.row])
    }

    /// What cell (`col`, `row`) holds now: state (0 unseen, 1 open, 2
    /// closed), g, h, f, parent col, parent row, opened at, closed at
    /// (NaN where none); `undefined` off the map.
    pub fn info(&self, col: u32, row: u32) -> Option<Vec<f64>> {
        let i = self.inner.info(col as usize, row as usize)?;
        let (pc, pr) = i.parent.map_or((f64::NAN, f64::NAN), |p| {
            (f64::from(p.col), f64::from(p.row))
        });
        Some(vec![
            f64::from(i.state as u8),
            i.g,
            i.h,
            i.f,
            pc,
            pr,
            or_nan(i.opened_at),
            or_nan(i.closed_at),
        ])
    }

    /// The search layers in `layers` at the current step as `{data, items,
    /// cells}`: every cell on the first draw and after a reset, then only
    /// those changed since the last draw.
    #[wasm_bindgen(unchecked_return_type = "DrawArrays")]
    pub fn draw(&mut self, layers: u32) -> Result<js_sys::Object, JsError> {
        let mut out = draw::DrawList::default();
        self.inner.draw(draw::Layers::from_bits(layers), &mut out);
        crate::draw_js::draw_arrays(&out)
    }
}

/// A step explained, with the order it was explained in (for the page's
/// explain panel).
#[derive(serde::Serialize)]
struct Explained {
    #[serde(flatten)]
    step: draw::StepExplanation,
    order: OpenOrder,
}

#[wasm_bindgen]
impl SearchReplay {
    /// The current step explained (core `SearchReplay::explain`) for the
    /// planner `options` (a `GridPlanOptions` object) choose: the expansion
    /// with g, h and priority, its neighbours (old g → new g), the open
    /// list's first `top` entries in that planner's order, and the order
    /// itself (`order.missing`: what the events do not carry).
    pub fn explain(&self, options: JsValue, top: u32) -> Result<JsValue, JsError> {
        let order = OpenOrder::of(&crate::options_from_js(options)?);
        let step = self.inner.explain(&order, top as usize);
        // Flattened fields go through a map: make it a plain object.
        let out = serde_wasm_bindgen::Serializer::new().serialize_maps_as_objects(true);
        serde::Serialize::serialize(&Explained { step, order }, &out)
            .map_err(|e| JsError::new(&e.to_string()))
    }
}
