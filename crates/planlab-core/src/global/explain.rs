//! How each grid planner orders its open list, told from its recorded
//! events: what the grid page's "explain this step" panel needs to rebuild
//! the open list at any step of a recorded search
//! ([`crate::draw::SearchReplay::explain`]) from the replay's per-cell state
//! and the open events, without storing a snapshot per step.
//!
//! An open event carries the cell's g and its unweighted h; the planner's
//! priority (f = g + w·h, h alone, insertion order) and its tie-breaking
//! rule are the planner's own and live here beside it. The orders are
//! checked against the planners in `tests/explain_step.rs`: on every step
//! of whole searches, the first entry of the rebuilt list is the cell the
//! planner expands next.

use super::plan::{Algorithm, GridPlanOptions};
use super::search::STRAIGHT;
use super::{Diagonal, Heuristic};
use serde::Serialize;
use std::cmp::Ordering;

/// What a planner's open list is ordered by, from an open event's g and h.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Priority {
    /// f = g + w·h, smallest first.
    F {
        /// The heuristic weight w (1 but for weighted A*).
        weight: f64,
    },
    /// h alone, smallest first (greedy best-first).
    H,
    /// No priority: first in, first out (breadth-first).
    Fifo,
    /// A priority the events do not carry (safe A*'s safety term, D* Lite's
    /// keys).
    Unrecorded,
}

impl Priority {
    /// The priority of an entry with these `g` and `h`; `None` when it has none
    /// or the recording lacks it.
    pub fn of(self, g: f64, h: f64) -> Option<f64> {
        match self {
            Priority::F { weight } => Some(g + weight * h),
            Priority::H => Some(h),
            Priority::Fifo | Priority::Unrecorded => None,
        }
    }
}

/// How equal priorities are broken (each the planner's queue's own rule).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Ties {
    /// The bucket queue of A*, Dijkstra and JPS with a consistent heuristic
    /// and weight 1: equal fixed-point f, the cell opened last first.
    LatestOpened,
    /// The binary heap of A* and JPS otherwise: equal fixed-point f, larger
    /// g first (compared in steps of 2¹⁶ fixed-point units, ≈ 0.14 cell),
    /// then the cell later in row-major order.
    CoarseDeeperLaterCell,
    /// The heap of Theta*, 4-connected JPS and greedy best-first: equal
    /// priority, larger g first, then the cell earlier in row-major order.
    DeeperEarlierCell,
    /// Safe A*'s heap (admissible variant): equal f, smaller h first, then
    /// the cell earlier in row-major order.
    NearerEarlierCell,
    /// Breadth-first's queue: the cell opened first first.
    FirstOpened,
}

/// A planner's open-list order as far as its events tell it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct OpenOrder {
    /// What the list is ordered by.
    pub priority: Priority,
    /// How ties are broken; `None` when the list cannot be rebuilt from the
    /// events (`missing` says why).
    pub ties: Option<Ties>,
    /// What the recording does not carry for this planner (empty: nothing).
    pub missing: &'static str,
}

impl OpenOrder {
    const fn full(priority: Priority, ties: Ties) -> Self {
        OpenOrder {
            priority,
            ties: Some(ties),
            missing: "",
        }
    }

    /// The order of the planner `options` choose.
    pub fn of(options: &GridPlanOptions) -> OpenOrder {
        let w = options.weight;
        // A* and JPS take their fixed-point bucket queue for the two
        // consistent estimates they special-case, their heap otherwise
        // (astar.rs `AStar::search`, jps.rs).
        let bucketed = |h: Heuristic, weight: f64| {
            matches!(h, Heuristic::Zero) || (h == Heuristic::Octile && weight == 1.0)
        };
        let fixed = |weight: f64, h: Heuristic| {
            let ties = if bucketed(h, weight) {
                Ties::LatestOpened
            } else {
                Ties::CoarseDeeperLaterCell
            };
            OpenOrder::full(Priority::F { weight }, ties)
        };
        match options.algorithm {
            Algorithm::AStar => fixed(w, options.heuristic),
            Algorithm::Dijkstra => fixed(1.0, Heuristic::Zero),
            Algorithm::Jps | Algorithm::JpsPlus if options.diagonal == Diagonal::Never => {
                OpenOrder::full(Priority::F { weight: 1.0 }, Ties::DeeperEarlierCell)
            }
            Algorithm::Jps => fixed(1.0, options.heuristic),
            Algorithm::JpsPlus => fixed(1.0, Heuristic::Octile),
            Algorithm::ThetaStar => {
                OpenOrder::full(Priority::F { weight: 1.0 }, Ties::DeeperEarlierCell)
            }
            Algorithm::Greedy => OpenOrder::full(Priority::H, Ties::DeeperEarlierCell),
            Algorithm::Bfs => OpenOrder::full(Priority::Fifo, Ties::FirstOpened),
            Algorithm::SafeAStar if options.safe.admissible => {
                OpenOrder::full(Priority::F { weight: 1.0 }, Ties::NearerEarlierCell)
            }
            Algorithm::SafeAStar => OpenOrder {
                priority: Priority::Unrecorded,
                ties: None,
                missing: "its f = g + h + ε·L adds the safety term L of the cell, which the events do not carry, so neither f nor the order of the open list is known",
            },
            Algorithm::BidirectionalAStar => OpenOrder {
                priority: Priority::F { weight: 1.0 },
                ties: None,
                missing: "it keeps two open lists, one per direction, each ordered by g plus the average potential (h to the other end − h to its own end) / 2, and expands the side with the smaller least key; the events do not say which side a cell belongs to, so no open list is shown",
            },
            Algorithm::IdaStar => OpenOrder {
                priority: Priority::F { weight: 1.0 },
                ties: None,
                missing: "it keeps no open list: it walks depth-first along one path and backtracks where f passes the round's bound (the bound is not recorded)",
            },
            Algorithm::DStarLite => OpenOrder {
                priority: Priority::Unrecorded,
                ties: None,
                missing: "its events carry rhs and h, not g or the key modifier k_m, so its keys [min(g, rhs) + h + k_m, min(g, rhs)] are unknown; its queue also drops cells that become consistent without an event, so no open list is shown",
            },
        }
    }

    /// Whether entry `a` (g, h, row-major cell index, index of its open
    /// event) comes off the list before `b`.
    pub fn cmp(&self, a: &OpenKey, b: &OpenKey) -> Ordering {
        let Some(ties) = self.ties else {
            return Ordering::Equal;
        };
        let by_priority = match (self.priority, ties) {
            (Priority::Fifo, _) | (Priority::Unrecorded, _) => Ordering::Equal,
            // The fixed-point planners compare integers: rebuild them, so
            // equal costs tie exactly (the events' f64 sums may not).
            (Priority::F { weight }, Ties::LatestOpened | Ties::CoarseDeeperLaterCell) => {
                fixed(a.g)
                    .saturating_add(fixed(weight * a.h))
                    .cmp(&fixed(b.g).saturating_add(fixed(weight * b.h)))
            }
            (p, _) => {
                let (pa, pb) = (p.of(a.g, a.h), p.of(b.g, b.h));
                pa.unwrap_or(f64::NAN).total_cmp(&pb.unwrap_or(f64::NAN))
            }
        };
        by_priority.then_with(|| match ties {
            Ties::LatestOpened => b.event.cmp(&a.event),
            Ties::CoarseDeeperLaterCell => (fixed(b.g) >> 16)
                .cmp(&(fixed(a.g) >> 16))
                .then(b.cell.cmp(&a.cell)),
            Ties::DeeperEarlierCell => b.g.total_cmp(&a.g).then(a.cell.cmp(&b.cell)),
            Ties::NearerEarlierCell => a.h.total_cmp(&b.h).then(a.cell.cmp(&b.cell)),
            Ties::FirstOpened => a.event.cmp(&b.event),
        })
    }
}

/// An open-list entry as [`OpenOrder::cmp`] compares it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OpenKey {
    /// Cost from the start, cells.
    pub g: f64,
    /// Unweighted heuristic, cells.
    pub h: f64,
    /// Row-major cell index (`row · width + col`).
    pub cell: usize,
    /// Index of the open event that put it there.
    pub event: usize,
}

/// A cost in cells back in the fixed-point units of the fast planners
/// (exact: the events carry `units / STRAIGHT`).
fn fixed(cells: f64) -> u64 {
    (cells * STRAIGHT as f64).round() as u64
}

/// One planner's properties in plain words, for the help.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct Properties {
    /// Whether its path is a shortest one (on the grid it searches).
    pub optimal: bool,
    /// Whether it finds a path whenever one exists.
    pub complete: bool,
    /// Whether its path may turn at any angle (not only along grid moves).
    pub any_angle: bool,
    /// Whether it repairs its search after a change instead of starting over.
    pub incremental: bool,
    /// The four in one plain sentence.
    pub words: &'static str,
}

impl Algorithm {
    /// Its properties with the default options (octile heuristic, weight 1).
    pub fn properties(self) -> Properties {
        let (complete, any_angle, incremental, words) = match self {
            Algorithm::AStar => (true, false, false, "finds a shortest path (with the octile heuristic and weight 1; a weight w > 1 gives up to w times longer); always finds a path if one exists; moves along the grid; not incremental"),
            Algorithm::Dijkstra => (true, false, false, "finds a shortest path; always finds a path if one exists; moves along the grid; not incremental"),
            Algorithm::Jps => (true, false, false, "finds a shortest path (the same cost as A*); always finds a path if one exists; moves along the grid, jumping over straight runs; not incremental"),
            Algorithm::JpsPlus => (true, false, false, "finds a shortest path (the same path as JPS); always finds a path if one exists; moves along the grid, jumping over straight runs by precomputed distances; not incremental (the table is rebuilt after an edit)"),
            Algorithm::SafeAStar => (true, false, false, "not the shortest: trades length for distance from walls; always finds a path if one exists; moves from grid cell to grid cell, up to two cells at a time (24 directions); not incremental"),
            Algorithm::Bfs => (true, false, false, "fewest moves, which is the shortest path only without diagonals; always finds a path if one exists; moves along the grid; not incremental"),
            Algorithm::Greedy => (true, false, false, "not the shortest: follows the estimate alone; always finds a path if one exists (each cell is expanded at most once); moves along the grid; not incremental"),
            Algorithm::BidirectionalAStar => (true, false, false, "finds a shortest path; always finds a path if one exists; moves along the grid; not incremental"),
            Algorithm::IdaStar => (false, false, false, "finds a shortest path when it finishes; would find a path if one exists given time, but this version stops after 2 million expansions, so it can give up; moves along the grid; not incremental"),
            Algorithm::ThetaStar => (true, true, false, "not always the shortest: never longer than the grid's shortest path, not always the shortest straight-line one; always finds a path if one exists; any-angle: turns only where it must; not incremental"),
            Algorithm::DStarLite => (true, false, true, "finds a shortest path; always finds a path if one exists; moves along the grid; incremental: after a wall is painted or the start moves it repairs only the affected part of its search"),
        };
        Properties {
            optimal: self.optimal(),
            complete,
            any_angle,
            incremental,
            words,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn key(g: f64, h: f64, cell: usize, event: usize) -> OpenKey {
        OpenKey { g, h, cell, event }
    }

    #[test]
    fn each_order_breaks_ties_by_its_queue_rule() {
        let astar = OpenOrder::of(&GridPlanOptions::default());
        assert_eq!(astar.ties, Some(Ties::LatestOpened));
        // Equal f: the later open event first; lower f beats both.
        let (a, b) = (key(1.0, 2.0, 5, 3), key(2.0, 1.0, 9, 7));
        assert_eq!(astar.cmp(&b, &a), Ordering::Less);
        assert_eq!(astar.cmp(&key(0.5, 2.0, 1, 0), &b), Ordering::Less);
        let greedy = OpenOrder::of(&GridPlanOptions {
            algorithm: Algorithm::Greedy,
            ..Default::default()
        });
        // Equal h: the deeper first, then the earlier cell.
        assert_eq!(
            greedy.cmp(&key(3.0, 2.0, 9, 0), &key(1.0, 2.0, 1, 1)),
            Ordering::Less
        );
        assert_eq!(
            greedy.cmp(&key(1.0, 2.0, 1, 5), &key(1.0, 2.0, 9, 1)),
            Ordering::Less
        );
        let bfs = OpenOrder::of(&GridPlanOptions {
            algorithm: Algorithm::Bfs,
            ..Default::default()
        });
        assert_eq!(
            bfs.cmp(&key(9.0, 0.0, 9, 1), &key(0.0, 0.0, 0, 2)),
            Ordering::Less
        );
    }

    #[test]
    fn every_planner_has_its_four_properties_in_words() {
        for (a, name) in Algorithm::ALL {
            let p = a.properties();
            for word in ["shortest", "path if one exists", "incremental"] {
                assert!(p.words.contains(word), "{name}: {word:?} in {:?}", p.words);
            }
            assert_eq!(p.any_angle, p.words.contains("any-angle"), "{name}");
            assert_eq!(
                p.incremental,
                !p.words.contains("not incremental"),
                "{name}"
            );
        }
    }
}
