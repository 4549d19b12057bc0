//! A grid search as a stream of events, for watching it happen (the grid
//! page's animation, `planlab plan --events`).
//!
//! Every grid planner is generic over a [`SearchObserver`]. Plain searches
//! pass `()`, whose [`SearchObserver::enabled`] is a constant `false`: every
//! event and the work of building it compile away, so recording costs the
//! plain search nothing. [`SearchLog`] records the events, bounded.

use super::GridPos;
use serde::{Deserialize, Serialize};

/// One step of a grid search, in the order it happened.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum SearchEvent {
    /// `cell` entered the open set, or its g improved: parent, g, h (f = g + w·h).
    Open {
        /// The cell opened.
        cell: GridPos,
        /// The cell it was reached from (`None` for the start).
        parent: Option<GridPos>,
        /// Cost from the start, cells.
        g: f64,
        /// Heuristic estimate to the goal, cells (unweighted).
        h: f64,
    },
    /// `cell` was taken from the open set and expanded (now closed).
    Close {
        /// The cell expanded.
        cell: GridPos,
    },
    /// A straight-line test from `from` to `to`: a JPS jump scan, a Theta*
    /// line of sight, a key-point / Bottom-Up segment check. `clear`: it passed.
    Line {
        /// Where the test starts.
        from: GridPos,
        /// Where it ends (for a failed jump scan: the last free cell).
        to: GridPos,
        /// Whether it passed (a jump point was found, the line is free).
        clear: bool,
    },
}

/// Receives the events; `()` ignores them at zero cost (plain searches use it,
/// so `planlab bench grid` does not move).
pub trait SearchObserver {
    /// One event.
    fn event(&mut self, e: SearchEvent);

    /// Whether events are wanted now; planners skip building them (and any
    /// work done only for them) when `false`.
    #[inline(always)]
    fn enabled(&self) -> bool {
        true
    }
}

impl SearchObserver for () {
    #[inline(always)]
    fn event(&mut self, _: SearchEvent) {}

    #[inline(always)]
    fn enabled(&self) -> bool {
        false
    }
}

impl<O: SearchObserver + ?Sized> SearchObserver for &mut O {
    #[inline(always)]
    fn event(&mut self, e: SearchEvent) {
        (**self).event(e);
    }

    #[inline(always)]
    fn enabled(&self) -> bool {
        (**self).enabled()
    }
}

/// Sends the event `make` builds, only if `obs` wants events.
#[inline(always)]
pub(crate) fn emit<O: SearchObserver + ?Sized>(obs: &mut O, make: impl FnOnce() -> SearchEvent) {
    if obs.enabled() {
        obs.event(make());
    }
}

/// Records every event (bounded: at most `limit` events, then `truncated = true`).
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct SearchLog {
    /// The events, in order.
    pub events: Vec<SearchEvent>,
    /// Whether events were dropped at the limit.
    pub truncated: bool,
    /// Most events kept.
    limit: usize,
}

impl SearchLog {
    /// A log keeping at most `limit` events.
    pub fn with_limit(limit: usize) -> Self {
        Self {
            events: Vec::new(),
            truncated: false,
            limit,
        }
    }

    /// The most events this log keeps.
    pub fn limit(&self) -> usize {
        self.limit
    }
}

impl SearchObserver for SearchLog {
    fn event(&mut self, e: SearchEvent) {
        if self.events.len() < self.limit {
            self.events.push(e);
        } else {
            self.truncated = true;
        }
    }

    /// Stays on after the limit only to note the truncation once.
    fn enabled(&self) -> bool {
        !self.truncated
    }
}

/// Pushes the cell of every [`SearchEvent::Close`] onto a list: the expanded
/// cells in order, as [`super::GridPlanner::plan_recording`] returns them.
pub(crate) struct ClosedCells<'a>(pub &'a mut Vec<GridPos>);

impl SearchObserver for ClosedCells<'_> {
    fn event(&mut self, e: SearchEvent) {
        if let SearchEvent::Close { cell } = e {
            self.0.push(cell);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn log_stops_at_its_limit_and_says_so() {
        let mut log = SearchLog::with_limit(2);
        for c in 0..5 {
            emit(&mut log, || SearchEvent::Close {
                cell: GridPos::new(c, 0),
            });
        }
        assert_eq!(log.events.len(), 2);
        assert!(log.truncated);
        assert!(!log.enabled());
    }
}
