//! A grid search as a Posthoc search trace: the format of ShortestPathLab's
//! search-trace visualiser (Monash University), version 1.4.0, so a search
//! planlab ran can be stepped through, filtered and compared there.
//!
//! A trace is one document: `version`, a `views.main` that draws every
//! event as a unit square at `(x, y)` coloured by its type, a `pivot` (where
//! the viewer centres an event) and the `events`. The events follow
//! Posthoc's vocabulary, built from planlab's [`SearchEvent`]s:
//!
//! - `source` and `destination`: the start and goal cells;
//! - `generating`: a cell entered the open list for the first time,
//!   `updating`: its g improved (both from [`SearchEvent::Open`]);
//! - `expanding`: a cell taken off the open list ([`SearchEvent::Close`]),
//!   `closing`: that cell done, written before the next `expanding` (so its
//!   `generating`/`updating` children sit between the two, as Posthoc's own
//!   A* traces have them);
//! - `end`: the goal, when the search reached it. For the searches that
//!   grow from the start (A*, Dijkstra, safe A*, BFS, greedy) its `pId`
//!   chain is the path; JPS's parents are the cells its jumps turned at,
//!   which it never generates, and Theta*'s are line-of-sight parents;
//!   bidirectional A* and D* Lite also search from the goal.
//!
//! Every event carries `id` (the cell's index, row × width + column), `x`
//! (column) and `y` (row, top row 0 as in Posthoc's own grid traces) and,
//! from `generating` on, `g`, `f` and `pId` (the parent's id, null for the
//! start). `f` is the search's priority: g + w·h for A* (w its weight),
//! h for greedy best-first, g + h for the rest. Line tests (JPS's scans,
//! Theta*'s line of sight, key-point checks) have no Posthoc counterpart
//! and are left out, so the number of `expanding` events is the search's
//! expanded count exactly.
//!
//! The trace is written as JSON, which every YAML reader (Posthoc's
//! included) reads; name it `NAME.trace.json`.

use std::collections::HashMap;

use serde::Serialize;
use thiserror::Error;

use super::events::{SearchEvent, SearchObserver};
use super::plan::{plan_on_map_observed, Algorithm, GridPlan, GridPlanError, GridPlanOptions};
use super::GridPos;
use crate::map::OccupancyGrid;

/// The Posthoc trace format version written.
pub const POSTHOC_VERSION: &str = "1.4.0";

/// Most events a trace holds by default: a search on a 512 × 512 Moving AI
/// map stays well below it; its JSON is about 100 bytes an event.
pub const DEFAULT_EVENT_LIMIT: usize = 4_000_000;

/// Why no trace was made.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum PosthocError {
    /// The plan failed (bad endpoint, no path, bad options).
    #[error(transparent)]
    Plan(#[from] GridPlanError),
    /// The search made more events than the limit allows.
    #[error(
        "the search makes more than {limit} trace events; trace a smaller map or a shorter query"
    )]
    TooLarge {
        /// The limit.
        limit: usize,
    },
}

/// One event of a trace (module doc).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PosthocEvent {
    /// `source`, `destination`, `generating`, `updating`, `expanding`,
    /// `closing` or `end`.
    #[serde(rename = "type")]
    pub kind: &'static str,
    /// The cell's index, row × width + column.
    pub id: u64,
    /// The parent's id (`Some(None)`: the start, written as null); absent
    /// on `source` and `destination`.
    #[serde(rename = "pId", skip_serializing_if = "Option::is_none")]
    pub p_id: Option<Option<u64>>,
    /// Cost from the start, cells.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub g: Option<f64>,
    /// The search's priority (module doc).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub f: Option<f64>,
    /// Column.
    pub x: u32,
    /// Row, top row 0.
    pub y: u32,
}

/// A whole trace document (module doc); `serde_json` writes it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PosthocTrace {
    /// [`POSTHOC_VERSION`].
    pub version: &'static str,
    /// How Posthoc draws an event.
    pub views: serde_json::Value,
    /// Where Posthoc centres an event.
    pub pivot: serde_json::Value,
    /// The events, in order.
    pub events: Vec<PosthocEvent>,
}

impl PosthocTrace {
    /// The number of events of kind `kind`.
    pub fn count(&self, kind: &str) -> usize {
        self.events.iter().filter(|e| e.kind == kind).count()
    }
}

/// Turns planlab's search events into Posthoc's as they come (module doc):
/// pass it as the observer of a plan, then [`PosthocRecorder::finish`].
/// [`posthoc_trace`] does both; the grid page's session, which keeps its
/// own planning grid, uses it directly.
#[derive(Debug, Clone)]
pub struct PosthocRecorder {
    goal: GridPos,
    width: u64,
    /// The weight on h in `f`, or `None` for f = h (greedy best-first).
    weight: Option<f64>,
    limit: usize,
    events: Vec<PosthocEvent>,
    /// g, f and parent of every cell generated so far.
    known: HashMap<u64, (f64, f64, Option<u64>)>,
    /// The cell expanding now, closed at the next expansion or the end.
    expanding: Option<GridPos>,
    overflow: bool,
}

impl PosthocRecorder {
    /// A recorder for a search from `start` to `goal` on a map `width`
    /// cells wide, planned with `options`, keeping at most `limit` events.
    pub fn new(
        width: usize,
        start: GridPos,
        goal: GridPos,
        options: &GridPlanOptions,
        limit: usize,
    ) -> Self {
        let weight = match options.algorithm {
            Algorithm::AStar => Some(options.weight),
            Algorithm::Greedy => None,
            _ => Some(1.0),
        };
        let mut rec = Self {
            goal,
            width: width as u64,
            weight,
            limit,
            events: Vec::new(),
            known: HashMap::new(),
            expanding: None,
            overflow: false,
        };
        for (kind, p) in [("source", start), ("destination", goal)] {
            let e = PosthocEvent {
                kind,
                id: rec.id(p),
                p_id: None,
                g: None,
                f: None,
                x: p.col,
                y: p.row,
            };
            rec.push(e);
        }
        rec
    }

    /// The trace of the search observed (an `end` event when it reached the
    /// goal); [`PosthocError::TooLarge`] when it outgrew the limit.
    pub fn finish(mut self) -> Result<PosthocTrace, PosthocError> {
        self.close_expanding();
        if self.known.contains_key(&self.id(self.goal)) {
            let e = self.about("end", self.goal);
            self.push(e);
        }
        if self.overflow {
            return Err(PosthocError::TooLarge { limit: self.limit });
        }
        Ok(PosthocTrace {
            version: POSTHOC_VERSION,
            views: serde_json::json!({
                "main": [{
                    "$": "rect",
                    "width": 1,
                    "height": 1,
                    "x": "${{ $.x }}",
                    "y": "${{ $.y }}",
                    "fill": "${{ color[$.type] }}",
                }]
            }),
            pivot: serde_json::json!({
                "x": "${{ $.x + 0.5 }}",
                "y": "${{ $.y + 0.5 }}",
                "scale": 1,
            }),
            events: self.events,
        })
    }

    fn id(&self, p: GridPos) -> u64 {
        u64::from(p.row) * self.width + u64::from(p.col)
    }

    fn push(&mut self, e: PosthocEvent) {
        if self.events.len() < self.limit {
            self.events.push(e);
        } else {
            self.overflow = true;
        }
    }

    /// An event about `cell` with what is known of it.
    fn about(&self, kind: &'static str, cell: GridPos) -> PosthocEvent {
        let id = self.id(cell);
        let (g, f, p) = self.known.get(&id).copied().unzip3();
        PosthocEvent {
            kind,
            id,
            p_id: p,
            g,
            f,
            x: cell.col,
            y: cell.row,
        }
    }

    fn close_expanding(&mut self) {
        if let Some(c) = self.expanding.take() {
            let e = self.about("closing", c);
            self.push(e);
        }
    }
}

/// `Option<(a, b, c)>` into three options.
trait Unzip3<A, B, C> {
    fn unzip3(self) -> (Option<A>, Option<B>, Option<C>);
}

impl<A, B, C> Unzip3<A, B, C> for Option<(A, B, C)> {
    fn unzip3(self) -> (Option<A>, Option<B>, Option<C>) {
        match self {
            Some((a, b, c)) => (Some(a), Some(b), Some(c)),
            None => (None, None, None),
        }
    }
}

impl SearchObserver for PosthocRecorder {
    fn event(&mut self, e: SearchEvent) {
        match e {
            SearchEvent::Open { cell, parent, g, h } => {
                let id = self.id(cell);
                let f = match self.weight {
                    Some(w) => g + w * h,
                    None => h,
                };
                let pid = parent.map(|p| self.id(p));
                let kind = if self.known.insert(id, (g, f, pid)).is_some() {
                    "updating"
                } else {
                    "generating"
                };
                let ev = self.about(kind, cell);
                self.push(ev);
            }
            SearchEvent::Close { cell } => {
                self.close_expanding();
                let ev = self.about("expanding", cell);
                self.push(ev);
                self.expanding = Some(cell);
            }
            SearchEvent::Line { .. } => {}
        }
    }

    fn enabled(&self) -> bool {
        !self.overflow
    }
}

/// Plans from `start` to `goal` as [`plan_on_map`](super::plan::plan_on_map)
/// does and returns the search as a Posthoc trace of at most `limit` events
/// (module doc), with the plan. The plan is the plain search's (recording
/// changes no planner's answer); the trace's `expanding` events number
/// `plan.path.expanded`.
pub fn posthoc_trace(
    map: &OccupancyGrid,
    start: GridPos,
    goal: GridPos,
    options: &GridPlanOptions,
    limit: usize,
) -> Result<(PosthocTrace, GridPlan), PosthocError> {
    let mut rec = PosthocRecorder::new(map.width(), start, goal, options, limit);
    let plan = plan_on_map_observed(map, start, goal, options, &mut rec)?;
    Ok((rec.finish()?, plan))
}
