//! Grid global planners (docs/algorithms.md §grid–§bottom-up): shared types.
//!
//! Every planner searches a [`PlanGrid`] (the passability of an
//! [`OccupancyGrid`], built once and reused across queries) and returns a
//! [`Path`] with its cost in cells (moves of 1 and √2), the number of nodes
//! expanded, or a typed [`PlanError`].

pub mod astar;
mod bidir;
pub mod bottom_up;
pub mod classic;
pub mod dstar_lite;
pub mod events;
pub mod explain;
pub mod jps;
mod jump_table;
pub mod keypoints;
pub mod plan;
pub mod posthoc;
pub mod safe_astar;
pub mod search;
mod weights;

/// Cells and the supercover line live with the grid (the map layer paints
/// segments too); the planners' code names them from here as before.
pub use crate::map::{supercover, supercover_while, GridPos};
use crate::map::{Cell, OccupancyGrid};
pub use events::{SearchEvent, SearchLog, SearchObserver};
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// Which diagonal moves are allowed (PathFinding.js names in parentheses).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Diagonal {
    /// 4-connected: no diagonal moves (Never).
    Never,
    /// 8-connected; a diagonal needs both orthogonal side cells free — the
    /// Moving AI rule, so `.scen` optimal lengths hold (OnlyWhenNoObstacles).
    #[default]
    NoCornerCutting,
    /// 8-connected; a diagonal needs at least one side cell free
    /// (IfAtMostOneObstacle).
    OneSideFree,
    /// 8-connected; diagonals through any corner (Always).
    Always,
}

impl Diagonal {
    /// Whether a diagonal move is legal given whether its two orthogonal side
    /// cells are free.
    #[inline]
    pub fn allows(self, side_a_free: bool, side_b_free: bool) -> bool {
        match self {
            Diagonal::Never => false,
            Diagonal::NoCornerCutting => side_a_free && side_b_free,
            Diagonal::OneSideFree => side_a_free || side_b_free,
            Diagonal::Always => true,
        }
    }
}

/// Distance estimate from a cell to the goal, in cells.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Heuristic {
    /// |dx| + |dy|: exact for 4-connected moves, inadmissible with diagonals.
    Manhattan,
    /// Straight-line distance.
    Euclidean,
    /// max + (√2 − 1)·min: exact on an empty 8-connected grid.
    #[default]
    Octile,
    /// max(|dx|, |dy|).
    Chebyshev,
    /// Always 0: turns A* into Dijkstra.
    Zero,
}

impl Heuristic {
    /// The estimate for offsets `dx`, `dy` (in cells, any sign).
    #[inline]
    pub fn eval(self, dx: f64, dy: f64) -> f64 {
        let (ax, ay) = (dx.abs(), dy.abs());
        match self {
            Heuristic::Manhattan => ax + ay,
            Heuristic::Euclidean => (ax * ax + ay * ay).sqrt(),
            Heuristic::Octile => {
                let (lo, hi) = if ax < ay { (ax, ay) } else { (ay, ax) };
                hi + (std::f64::consts::SQRT_2 - 1.0) * lo
            }
            Heuristic::Chebyshev => ax.max(ay),
            Heuristic::Zero => 0.0,
        }
    }
}

/// Which end of a query an error is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Endpoint {
    /// The start cell.
    Start,
    /// The goal cell.
    Goal,
}

impl std::fmt::Display for Endpoint {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Endpoint::Start => "start",
            Endpoint::Goal => "goal",
        })
    }
}

/// Why a planner returned no path.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum PlanError {
    /// Start or goal lies outside the map.
    #[error("{which} ({col}, {row}) is off the {width}×{height} map")]
    OffMap {
        /// Start or goal.
        which: Endpoint,
        /// Column as given.
        col: i64,
        /// Row as given.
        row: i64,
        /// Map width.
        width: usize,
        /// Map height.
        height: usize,
    },
    /// Start or goal is an obstacle (or unknown, when unknown is blocked).
    #[error("{which} ({col}, {row}) is inside an obstacle")]
    Blocked {
        /// Start or goal.
        which: Endpoint,
        /// Column.
        col: u32,
        /// Row.
        row: u32,
    },
    /// Start or goal is an unknown cell of the map and unknown cells are
    /// blocked (`allow_unknown` is off).
    #[error("{which} ({col}, {row}) is an unknown cell, and unknown cells are blocked unless allow_unknown is set")]
    UnknownCell {
        /// Start or goal.
        which: Endpoint,
        /// Column.
        col: u32,
        /// Row.
        row: u32,
    },
    /// The search exhausted every reachable cell.
    #[error("goal is unreachable from start ({expanded} cells expanded)")]
    Unreachable {
        /// Nodes expanded before giving up.
        expanded: usize,
    },
    /// A configuration value is out of range.
    #[error("invalid planner configuration: {}", crate::text::one_line(.0))]
    InvalidConfig(String),
    /// The planner assumes every cell costs the same (Jump Point Search's
    /// pruning is valid only then) and the grid has weighted cells.
    #[error(
        "{planner} needs uniform cell costs, and this map has weighted cells; \
         plan with A* (or Dijkstra), which honours the weights"
    )]
    NeedsUniformCosts {
        /// The planner's name.
        planner: &'static str,
    },
    /// The search stopped at its bound on work (IDA*), before finding a
    /// path or proving there is none.
    #[error(
        "search limit reached: {expanded} expansions (limit {limit}) without a path; \
         A* finds it with one expansion per cell"
    )]
    SearchLimit {
        /// Nodes expanded when it stopped.
        expanded: usize,
        /// The bound.
        limit: usize,
    },
}

/// A planned grid path.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Path {
    /// Cells from start to goal inclusive.
    pub cells: Vec<GridPos>,
    /// Sum of move lengths in cells (1 straight, √2 diagonal, the Euclidean
    /// length for longer moves), each times the weight of the cell it
    /// enters on a weighted grid ([`PlanGrid::path_cost`]). For safe A*
    /// this is that weighted length, not the search's internal cost.
    pub cost: f64,
    /// Nodes taken off the open list and expanded.
    pub expanded: usize,
}

impl Path {
    /// Euclidean length of the polyline through `cells`, in cells.
    pub fn polyline_length(cells: &[GridPos]) -> f64 {
        cells
            .windows(2)
            .map(|w| {
                let dx = w[1].col as f64 - w[0].col as f64;
                let dy = w[1].row as f64 - w[0].row as f64;
                (dx * dx + dy * dy).sqrt()
            })
            .sum()
    }
}

/// What every grid planner offers.
pub trait GridPlanner {
    /// A path from `start` to `goal`, or why there is none.
    fn plan(&self, grid: &PlanGrid, start: GridPos, goal: GridPos) -> Result<Path, PlanError>;
}

/// A grid planner whose search can be watched. A trait of its own so that
/// a `dyn GridPlanner` (what the robot pages and the batch runs plan with)
/// does not pull the observed copy of every search into a wasm module.
pub trait ObservedGridPlanner: GridPlanner {
    /// As [`GridPlanner::plan`], reporting every search event to `obs`
    /// (same path, cost and expansions as the plain search).
    fn plan_observed(
        &self,
        grid: &PlanGrid,
        start: GridPos,
        goal: GridPos,
        obs: &mut dyn SearchObserver,
    ) -> Result<Path, PlanError>;

    /// As [`GridPlanner::plan`], and when `expanded` is given, pushes every
    /// expanded cell onto it in expansion order (for drawing the search).
    fn plan_recording(
        &self,
        grid: &PlanGrid,
        start: GridPos,
        goal: GridPos,
        expanded: Option<&mut Vec<GridPos>>,
    ) -> Result<Path, PlanError> {
        match expanded {
            None => self.plan(grid, start, goal),
            Some(cells) => self.plan_observed(grid, start, goal, &mut events::ClosedCells(cells)),
        }
    }
}

/// Implements [`GridPlanner`] and [`ObservedGridPlanner`] for a planner
/// with an inherent
/// `fn search<O: SearchObserver + ?Sized>(&self, grid, start, goal, obs: &mut O)`:
/// the plain search monomorphised for `()` (no events, full speed), the
/// observed one for `dyn SearchObserver`.
macro_rules! grid_planner_via_search {
    ($t:ty) => {
        impl $crate::global::GridPlanner for $t {
            fn plan(
                &self,
                grid: &$crate::global::PlanGrid,
                start: $crate::global::GridPos,
                goal: $crate::global::GridPos,
            ) -> Result<$crate::global::Path, $crate::global::PlanError> {
                self.search(grid, start, goal, &mut ())
            }
        }

        impl $crate::global::ObservedGridPlanner for $t {
            fn plan_observed(
                &self,
                grid: &$crate::global::PlanGrid,
                start: $crate::global::GridPos,
                goal: $crate::global::GridPos,
                obs: &mut dyn $crate::global::SearchObserver,
            ) -> Result<$crate::global::Path, $crate::global::PlanError> {
                self.search(grid, start, goal, obs)
            }
        }
    };
}
pub(crate) use grid_planner_via_search;

/// Passability of a map as planners see it: a row-major bitmap with a
/// one-cell blocked border, so neighbour lookups need no bounds checks.
#[derive(Clone, Debug)]
pub struct PlanGrid {
    width: usize,
    height: usize,
    /// Padded width = width + 2.
    stride: usize,
    /// (width + 2) × (height + 2); `true` = passable.
    free: Vec<bool>,
    /// The same bitmap packed 64 cells a word, by rows and by columns, with
    /// the stop masks of Jump Point Search; built on JPS's first use (most
    /// grids, e.g. the ones planners build every replan, never need it) and
    /// then kept in step with `free`.
    lines: std::sync::OnceLock<search::LineBits>,
    /// Per padded cell, which of its eight neighbours are passable (bit
    /// `k`: the move [`search::DIRS`]`[k]`); built on A*'s first use and
    /// then kept in step with `free`, so an expansion reads one byte
    /// instead of eight.
    neighbours: std::sync::OnceLock<Vec<u8>>,
    /// JPS+'s jump distances, built on its first query; an edit drops them
    /// (the next query rebuilds them).
    jump_table: std::sync::OnceLock<jump_table::JumpTable>,
    /// Traversal weight per padded cell (1..=9; the border 1), or `None` on
    /// a unit-cost grid: a move costs its length times the weight of the
    /// cell it enters (docs/algorithms.md §weights; `weights.rs`).
    weights: Option<Vec<u8>>,
}

impl PlanGrid {
    /// Passability of `grid`; unknown cells are passable only with
    /// `allow_unknown`.
    pub fn new(grid: &OccupancyGrid, allow_unknown: bool) -> Self {
        let mut out = Self::from_fn(grid.width(), grid.height(), |c, r| {
            grid.cells()[r * grid.width() + c].passable(allow_unknown)
        });
        out.take_weights_of(grid);
        out
    }

    /// A grid whose cell `(c, r)` is passable when `f(c, r)`.
    pub fn from_fn(width: usize, height: usize, mut f: impl FnMut(usize, usize) -> bool) -> Self {
        let stride = width + 2;
        let mut free = vec![false; stride * (height + 2)];
        for r in 0..height {
            for c in 0..width {
                free[(r + 1) * stride + c + 1] = f(c, r);
            }
        }
        Self {
            width,
            height,
            stride,
            free,
            lines: std::sync::OnceLock::new(),
            neighbours: std::sync::OnceLock::new(),
            jump_table: std::sync::OnceLock::new(),
            weights: None,
        }
    }

    /// The bit-packed rows and columns (see [`search::LineBits`]).
    #[inline]
    pub(crate) fn lines(&self) -> &search::LineBits {
        self.lines
            .get_or_init(|| search::LineBits::new(&self.free, self.stride, self.height + 2))
    }

    /// The passable neighbours of every padded cell (see the field).
    #[inline]
    pub(crate) fn neighbours(&self) -> &[u8] {
        self.neighbours
            .get_or_init(|| search::neighbour_bits(&self.free, self.stride))
    }

    /// JPS+'s jump distances (see the field); callers check the size first
    /// ([`jump_table::JumpTable::check`]).
    #[inline]
    pub(crate) fn jump_table(&self) -> &jump_table::JumpTable {
        self.jump_table
            .get_or_init(|| jump_table::JumpTable::new(&self.free, self.stride))
    }

    /// Builds JPS+'s jump table now, if it is not built yet (otherwise the
    /// first JPS+ query builds it): to time it apart from the queries, or to
    /// pay for it before an interactive session's first query. Fails on a
    /// grid too large for the table.
    pub fn build_jps_plus_table(&self) -> Result<(), PlanError> {
        jump_table::JumpTable::check(self)?;
        self.jump_table();
        Ok(())
    }

    /// Width in cells.
    #[inline]
    pub fn width(&self) -> usize {
        self.width
    }

    /// Height in cells.
    #[inline]
    pub fn height(&self) -> usize {
        self.height
    }

    /// Whether `(col, row)` is on the map and passable (`false` off the map).
    #[inline]
    pub fn is_free(&self, col: i64, row: i64) -> bool {
        if col < -1 || row < -1 || col > self.width as i64 || row > self.height as i64 {
            return false;
        }
        self.free[(row + 1) as usize * self.stride + (col + 1) as usize]
    }

    /// Marks a cell passable or blocked (no-op off the map).
    pub fn set_free(&mut self, col: usize, row: usize, free: bool) {
        if col < self.width && row < self.height {
            let i = (row + 1) * self.stride + col + 1;
            self.free[i] = free;
            if let Some(lines) = self.lines.get_mut() {
                lines.set(col + 1, row + 1, free);
            }
            if let Some(bits) = self.neighbours.get_mut() {
                search::set_neighbour_bit(bits, i, self.stride, free);
            }
            self.jump_table.take();
        }
    }

    /// Padded width (width + 2), the step between rows in [`Self::padded`].
    #[inline]
    pub fn stride(&self) -> usize {
        self.stride
    }

    /// The padded bitmap: index `(row + 1) * stride + col + 1`.
    #[inline]
    pub fn padded(&self) -> &[bool] {
        &self.free
    }

    /// Padded index of an on-map cell.
    #[inline]
    pub fn padded_index(&self, p: GridPos) -> usize {
        (p.row as usize + 1) * self.stride + p.col as usize + 1
    }

    /// On-map cell of a padded index.
    #[inline]
    pub fn pos_of(&self, idx: usize) -> GridPos {
        GridPos::new(
            (idx % self.stride - 1) as u32,
            (idx / self.stride - 1) as u32,
        )
    }

    /// Checks that start and goal are on the map and passable.
    pub fn check_endpoints(&self, start: GridPos, goal: GridPos) -> Result<(), PlanError> {
        for (which, p) in [(Endpoint::Start, start), (Endpoint::Goal, goal)] {
            if p.col as usize >= self.width || p.row as usize >= self.height {
                return Err(PlanError::OffMap {
                    which,
                    col: p.col as i64,
                    row: p.row as i64,
                    width: self.width,
                    height: self.height,
                });
            }
            if !self.is_free(p.col as i64, p.row as i64) {
                return Err(PlanError::Blocked {
                    which,
                    col: p.col,
                    row: p.row,
                });
            }
        }
        Ok(())
    }

    /// Whether every move of `cells` stays on passable cells, checking the
    /// cells each straight segment passes through (supercover line) and,
    /// for exact diagonal corner crossings, the `diagonal` rule.
    pub fn path_is_free(&self, cells: &[GridPos], diagonal: Diagonal) -> bool {
        cells
            .iter()
            .all(|p| self.is_free(p.col as i64, p.row as i64))
            && cells
                .windows(2)
                .all(|w| self.segment_is_free(w[0], w[1], diagonal))
    }

    /// Whether the straight segment between the centres of `a` and `b`
    /// crosses only passable cells. Where the segment passes exactly through
    /// a cell corner, the two cells touching that corner are judged by
    /// `diagonal` (as for a single diagonal move).
    pub fn segment_is_free(&self, a: GridPos, b: GridPos, diagonal: Diagonal) -> bool {
        supercover_while(a, b, |c, r, corner| match corner {
            None => self.is_free(c, r),
            Some((ac, ar, bc, br)) => diagonal.allows(self.is_free(ac, ar), self.is_free(bc, br)),
        })
    }
}

/// Checks a heuristic weight: finite and ≥ 1 (not a cell's traversal
/// weight: see [`PlanGrid::weight`]).
pub fn check_weight(weight: f64) -> Result<(), PlanError> {
    if weight.is_finite() && weight >= 1.0 {
        Ok(())
    } else {
        Err(PlanError::InvalidConfig(format!(
            "heuristic weight {weight} must be a finite number ≥ 1"
        )))
    }
}

/// Builds a [`PlanGrid`] that treats `Cell::Unknown` as given and everything
/// else by its kind; a convenience for callers holding only cells.
pub fn plan_grid_from_cells(
    width: usize,
    height: usize,
    cells: &[Cell],
    allow_unknown: bool,
) -> PlanGrid {
    PlanGrid::from_fn(width, height, |c, r| {
        cells[r * width + c].passable(allow_unknown)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn segment_respects_corner_rule() {
        let g = OccupancyGrid::from_ascii(".#\n..\n").unwrap();
        let pg = PlanGrid::new(&g, false);
        let (a, b) = (GridPos::new(0, 0), GridPos::new(1, 1));
        assert!(!pg.segment_is_free(a, b, Diagonal::NoCornerCutting));
        assert!(pg.segment_is_free(a, b, Diagonal::OneSideFree));
    }

    #[test]
    fn heuristics() {
        assert_eq!(Heuristic::Manhattan.eval(3.0, -4.0), 7.0);
        assert_eq!(Heuristic::Euclidean.eval(3.0, -4.0), 5.0);
        assert_eq!(Heuristic::Chebyshev.eval(3.0, -4.0), 4.0);
        assert!(
            (Heuristic::Octile.eval(3.0, -4.0) - (4.0 + 3.0 * (2f64.sqrt() - 1.0))).abs() < 1e-12
        );
    }
}
