//! "Explain this step" of a replayed search ([`SearchReplay::explain`]):
//! the expansion the current event belongs to, the neighbours it opened or
//! improved (old g → new g) and the first entries of the open list after
//! it, in the planner's order ([`OpenOrder`]).
//!
//! Nothing is stored per step: the open list is rebuilt on demand from the
//! replay's per-cell state (which cells are open, each one's latest open
//! event) plus the open events still to come in this expansion, so the
//! memory stays the replay's own (O(cells + events)) and a query costs one
//! pass over the map's cells.

use super::{CellState, SearchReplay, NONE};
use crate::global::explain::{OpenKey, OpenOrder};
use crate::global::{GridPos, SearchEvent};
use serde::Serialize;

/// What the current event is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum StepKind {
    /// Nothing played yet.
    None,
    /// The start (or D* Lite's goal) entered the open list.
    Start,
    /// A cell was taken off the open list and expanded.
    Expand,
    /// A neighbour was opened or its g improved.
    Open,
    /// A straight-line check (jump scan, line of sight).
    Line,
}

/// A cell with the g and h of its open event and its priority.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct OpenEntry {
    /// The cell.
    pub cell: GridPos,
    /// Cost from the start (D* Lite: rhs), cells.
    pub g: f64,
    /// Unweighted heuristic, cells.
    pub h: f64,
    /// The planner's priority ([`crate::global::explain::Priority::of`]);
    /// NaN where it has none or the events lack it.
    pub priority: f64,
}

/// A neighbour opened or improved by the expansion.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Relaxed {
    /// The cell and its new g, h and priority.
    pub entry: OpenEntry,
    /// Its g before (NaN: newly opened).
    pub old_g: f64,
    /// The cell it now comes from.
    pub parent: Option<GridPos>,
    /// Whether the player has applied this event yet.
    pub played: bool,
}

/// The current step of a replayed search, explained.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StepExplanation {
    /// What the current event (the last one applied) is.
    pub kind: StepKind,
    /// 1-based step of the expansion this event belongs to (its close
    /// event), if any.
    pub expanded_at: Option<usize>,
    /// The cell expanded, with the g and h it was opened with.
    pub expanded: Option<OpenEntry>,
    /// The neighbours this expansion opened or improved, in order (those
    /// after the current step too, marked unplayed).
    pub relaxed: Vec<Relaxed>,
    /// Line checks this expansion made.
    pub lines: usize,
    /// The first entries of the open list once this expansion is done, in
    /// the planner's order (empty when it cannot be rebuilt).
    pub open: Vec<OpenEntry>,
    /// The open list's size then.
    pub open_len: usize,
    /// The cell the planner expands next (from the recording), if any.
    pub next_expanded: Option<GridPos>,
    /// 1-based step of that expansion.
    pub next_at: Option<usize>,
}

impl SearchReplay {
    fn entry(&self, i: usize, order: &OpenOrder) -> Option<OpenEntry> {
        match self.events.get(i)? {
            &SearchEvent::Open { cell, g, h, .. } => Some(OpenEntry {
                cell,
                g,
                h,
                priority: order.priority.of(g, h).unwrap_or(f64::NAN),
            }),
            _ => None,
        }
    }

    /// The current step explained for a planner ordering its open list by
    /// `order`, with the open list's first `top` entries.
    pub fn explain(&self, order: &OpenOrder, top: usize) -> StepExplanation {
        let n = self.events.len();
        let cur = self.step.checked_sub(1);
        let is_close = |i: usize| matches!(self.events[i], SearchEvent::Close { .. });
        // The expansion: the last close at or before the current event, up
        // to the next close.
        let close = cur.and_then(|c| (0..=c).rev().find(|&i| is_close(i)));
        let from = close.map_or(0, |c| c + 1);
        let next = (self.step..n).find(|&i| is_close(i));
        let end = next.unwrap_or(n);

        let kind = match cur.map(|i| self.events[i]) {
            None => StepKind::None,
            Some(SearchEvent::Close { .. }) => StepKind::Expand,
            Some(SearchEvent::Line { .. }) => StepKind::Line,
            Some(SearchEvent::Open { parent: None, .. }) => StepKind::Start,
            Some(SearchEvent::Open { .. }) => StepKind::Open,
        };

        let expanded = close.and_then(|c| {
            let k = self.index(c);
            // The cell's latest open event before its close (a later
            // reopening, in D* Lite, does not count).
            let mut i = self.last_open[k];
            while i != NONE && i as usize > c {
                i = self.prev_index[i as usize];
            }
            let mut e = if i == NONE {
                None
            } else {
                self.entry(i as usize, order)
            }?;
            if let SearchEvent::Close { cell } = self.events[c] {
                e.cell = cell;
            }
            Some(e)
        });

        // Opens of this expansion, with what each overwrote; later ones in
        // the expansion see the earlier ones.
        let mut relaxed = Vec::new();
        let mut pending: Vec<(usize, usize)> = Vec::new(); // (cell index, event) not yet applied
        let mut lines = 0;
        for i in from..end {
            match self.events[i] {
                SearchEvent::Line { .. } => lines += 1,
                SearchEvent::Open { parent, .. } => {
                    let k = self.index(i);
                    let before = if i < self.step {
                        self.prev_index[i]
                    } else {
                        pending
                            .iter()
                            .rev()
                            .find(|&&(pk, _)| pk == k)
                            .map_or(self.last_open[k], |&(_, e)| e as u32)
                    };
                    if i >= self.step {
                        pending.push((k, i));
                    }
                    let old_g = if before == NONE {
                        f64::NAN
                    } else {
                        self.entry(before as usize, order).map_or(f64::NAN, |e| e.g)
                    };
                    if let Some(entry) = self.entry(i, order) {
                        relaxed.push(Relaxed {
                            entry,
                            old_g,
                            parent,
                            played: i < self.step,
                        });
                    }
                }
                SearchEvent::Close { .. } => {}
            }
        }

        // The open list once the expansion is done: the cells open now, each
        // by its latest open event, with the pending opens applied.
        let mut latest = pending;
        latest.sort_unstable();
        // The last pending event of each cell wins (descending order).
        latest.reverse();
        latest.dedup_by_key(|p| p.0);
        let key_of = |k: usize, i: usize| match self.events[i] {
            SearchEvent::Open { g, h, .. } => Some(OpenKey {
                g,
                h,
                cell: k,
                event: i,
            }),
            _ => None,
        };
        let now_open = self
            .state
            .iter()
            .enumerate()
            .filter(|&(k, &s)| {
                s == CellState::Open as u8 && latest.binary_search_by(|p| k.cmp(&p.0)).is_err()
            })
            .filter_map(|(k, _)| key_of(k, self.last_open[k] as usize));
        let all = now_open.chain(latest.iter().filter_map(|&(k, i)| key_of(k, i)));
        let mut open_len = 0;
        let mut best: Vec<OpenKey> = Vec::with_capacity(top + 1);
        let ordered = order.ties.is_some() && top > 0;
        for key in all {
            open_len += 1;
            if !ordered || (best.len() == top && order.cmp(&key, &best[top - 1]).is_ge()) {
                continue;
            }
            let at = best.partition_point(|b| order.cmp(b, &key).is_le());
            best.insert(at, key);
            best.truncate(top);
        }
        let open = best
            .iter()
            .filter_map(|k| self.entry(k.event, order))
            .collect();
        StepExplanation {
            kind,
            expanded_at: close.map(|c| c + 1),
            expanded,
            relaxed,
            lines,
            open,
            open_len,
            next_expanded: next.and_then(|i| match self.events[i] {
                SearchEvent::Close { cell } => Some(cell),
                _ => None,
            }),
            next_at: next.map(|i| i + 1),
        }
    }
}
