//! Safe A* of Ge & Li (2022) §1 (docs/algorithms.md §safe-astar, paper key \[S\]).
//!
//! Two changes to A*: a 24-neighbourhood (every cell of the 5×5 block around
//! a node, so paths turn less) and a safety term in the heuristic,
//!
//! ```text
//! f(n) = g(n) + h′(n),   h′(n) = h(n) + ε·L(n),   L(n) = k / s        \[S\] eq 1
//! ```
//!
//! where `k` is the number of occupied cells in an evaluation window around
//! `n` and `s` the distance from `n` to the nearest of them; ε = 100.
//!
//! Decisions (the paper leaves these open):
//! - **Window**: the (2r+1)×(2r+1) block centred on `n`, r = 2 (5×5).
//! - **Occupied** means "not passable in the [`PlanGrid`]", and cells **off
//!   the map count as occupied**: the map edge is a wall to the robot, the
//!   same convention as [`PlanGrid`]'s blocked border.
//! - **s** is the Euclidean distance in cells between cell centres; `L = 0`
//!   when `k = 0`.
//! - **Moves**: a move `n → m` is legal only if every cell the straight
//!   segment crosses is free ([`PlanGrid::segment_is_free`] with
//!   [`Diagonal::NoCornerCutting`]); it costs its Euclidean length (times
//!   the largest weight among the cells it enters, on weighted cells).
//! - **Closed nodes are never reopened**, as in the paper's step 2–5.
//! - **h′(goal) = 0**: the goal's own `L` is never charged. A heuristic is 0
//!   at the goal by definition, and with the paper's form a goal beside a
//!   wall would otherwise carry `ε·L(goal)` in its `f`, so every penalised
//!   node with a smaller `g + h` (the wall-hugging shortest path) would be
//!   expanded before it and become its parent, undoing the safety term.
//! - **Safety index** `S(n) = 10 / (1 + L(n))` ([`safety_index`]): the paper
//!   plots an index S that "stays at 10" on a safe path but never defines it.
//!   This form is 10 exactly when no obstacle is in the window and falls
//!   strictly as the danger `L` grows.
//!
//! The paper's `h′` is inadmissible by design (the path is no longer the
//! shortest). [`SafeAStarConfig::admissible`] moves the safety term into the
//! edge cost instead; see there.

use super::events::emit;
use super::{Diagonal, GridPos, Heuristic, Path, PlanError, PlanGrid, SearchEvent, SearchObserver};
use serde::{Deserialize, Serialize};
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// Largest accepted [`SafeAStarConfig::window_radius`], in cells; bounds the
/// per-cell work of the safety term (a (2·64+1)² window is already far wider
/// than any robot's footprint on a planning grid).
pub const MAX_WINDOW_RADIUS: u32 = 64;

/// Value of the safety index [`safety_index`] when no obstacle is in the
/// evaluation window (the "10" of \[S\] Fig 3b).
pub const SAFETY_INDEX_MAX: f64 = 10.0;

/// Safe A* settings; `Default` is the paper's configuration.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct SafeAStarConfig {
    /// ε, weight of the safety term L(n), in cells of path length per unit of
    /// L (dimensionless k/s). Paper: 100. Must be finite and ≥ 0.
    pub epsilon: f64,
    /// Half-size of the evaluation window in cells: the window is
    /// (2r+1)×(2r+1). Decision: 2 (5×5). Must be in 1..=[`MAX_WINDOW_RADIUS`].
    pub window_radius: u32,
    /// `false` (paper): `f = g + h + ε·L(n)`, inadmissible, `g` = path length.
    /// `true`: the safety term is charged on arrival, each move `n → m` costs
    /// `|nm| + ε·L(m)`, and `f = g + h`. Every move then costs at least its
    /// Euclidean length, so a Euclidean (or Chebyshev/zero) `h` stays
    /// admissible and consistent w.r.t. these modified costs and the search
    /// returns a path minimising `length + ε·ΣL(nodes strictly between start
    /// and goal)`. With
    /// ε = 0 it is the shortest path over the chosen neighbourhood.
    pub admissible: bool,
    /// Base heuristic `h`, in cells. Default Euclidean: the paper does not
    /// say, and with 24-neighbour moves (e.g. the knight move (2, 1) of length
    /// √5 < octile 2 + (√2 − 1)) only Euclidean, Chebyshev and Zero are
    /// admissible; Octile and Manhattan are allowed but overestimate.
    pub heuristic: Heuristic,
    /// Successor set: 24 (every cell of the 5×5 block, paper), 8 or 4.
    pub neighbourhood: u32,
}

impl Default for SafeAStarConfig {
    fn default() -> Self {
        Self {
            epsilon: 100.0,
            window_radius: 2,
            admissible: false,
            heuristic: Heuristic::Euclidean,
            neighbourhood: 24,
        }
    }
}

/// Safe A* planner (\[S\] §1); build with [`SafeAStar::new`].
#[derive(Clone, Debug)]
pub struct SafeAStar {
    cfg: SafeAStarConfig,
    /// Successor offsets (dc, dr) and their Euclidean lengths.
    moves: Vec<(i64, i64, f64)>,
    /// Window offsets sorted by distance from the centre (centre excluded),
    /// so the first occupied one found gives `s`.
    window: Vec<(i64, i64, f64)>,
}

impl SafeAStar {
    /// A planner with validated settings.
    ///
    /// # Errors
    /// [`PlanError::InvalidConfig`] when ε is not finite or negative, the
    /// window radius is 0 or above [`MAX_WINDOW_RADIUS`], or the
    /// neighbourhood is not 4, 8 or 24.
    pub fn new(cfg: SafeAStarConfig) -> Result<Self, PlanError> {
        if !(cfg.epsilon.is_finite() && cfg.epsilon >= 0.0) {
            return Err(PlanError::InvalidConfig(format!(
                "safe A* epsilon {} must be a finite number ≥ 0",
                cfg.epsilon
            )));
        }
        if cfg.window_radius == 0 || cfg.window_radius > MAX_WINDOW_RADIUS {
            return Err(PlanError::InvalidConfig(format!(
                "safe A* window radius {} must be in 1..={MAX_WINDOW_RADIUS} cells",
                cfg.window_radius
            )));
        }
        let reach: i64 = match cfg.neighbourhood {
            4 | 8 => 1,
            24 => 2,
            n => {
                return Err(PlanError::InvalidConfig(format!(
                    "safe A* neighbourhood {n} must be 4, 8 or 24"
                )))
            }
        };
        let mut moves = Vec::new();
        for dr in -reach..=reach {
            for dc in -reach..=reach {
                if (dc, dr) == (0, 0) || (cfg.neighbourhood == 4 && dc != 0 && dr != 0) {
                    continue;
                }
                moves.push((dc, dr, ((dc * dc + dr * dr) as f64).sqrt()));
            }
        }
        Ok(Self {
            cfg,
            moves,
            window: window_offsets(cfg.window_radius),
        })
    }

    /// The settings this planner was built with.
    pub fn config(&self) -> &SafeAStarConfig {
        &self.cfg
    }
}

/// Offsets of a (2r+1)² window without its centre, nearest first.
fn window_offsets(radius: u32) -> Vec<(i64, i64, f64)> {
    let r = i64::from(radius);
    let mut v = Vec::with_capacity(((2 * r + 1) * (2 * r + 1)) as usize);
    for dr in -r..=r {
        for dc in -r..=r {
            if (dc, dr) != (0, 0) {
                v.push((dc, dr, ((dc * dc + dr * dr) as f64).sqrt()));
            }
        }
    }
    // Stable sort keeps a fixed scan order among equal distances.
    v.sort_by(|a, b| a.2.total_cmp(&b.2));
    v
}

/// The danger `L(n) = k/s` of \[S\] eq 1 at `p`: `k` = occupied cells (off-map
/// cells count as occupied) in the (2r+1)² window centred on `p`, `s` =
/// Euclidean distance in cells from `p` to the nearest of them; 0 when `k` = 0.
///
/// `p` itself is not counted (a planner only stands on free cells). Any `p`
/// is accepted, on or off the map. A `window_radius` of 0 gives an empty
/// window and L = 0; radii above [`MAX_WINDOW_RADIUS`] are clamped to it.
pub fn safety_term(grid: &PlanGrid, p: GridPos, window_radius: u32) -> f64 {
    let r = i64::from(window_radius.min(MAX_WINDOW_RADIUS));
    let (c, rw) = (i64::from(p.col), i64::from(p.row));
    let mut k = 0u64;
    let mut s2 = i64::MAX;
    for dr in -r..=r {
        for dc in -r..=r {
            if (dc, dr) != (0, 0) && !grid.is_free(c + dc, rw + dr) {
                k += 1;
                s2 = s2.min(dc * dc + dr * dr);
            }
        }
    }
    if k == 0 {
        0.0
    } else {
        k as f64 / (s2 as f64).sqrt()
    }
}

/// The safety index `S = 10 / (1 + L)` of each cell of `cells` (see the
/// module doc for why this form), `L` from [`safety_term`] (same window
/// rules). 10 means no obstacle within the window; lower is more dangerous.
/// Empty in, empty out.
pub fn safety_index(grid: &PlanGrid, cells: &[GridPos], window_radius: u32) -> Vec<f64> {
    cells
        .iter()
        .map(|&p| SAFETY_INDEX_MAX / (1.0 + safety_term(grid, p, window_radius)))
        .collect()
}

/// `L(n)` for every cell of a grid, computed lazily: `k` from a summed-area
/// table of occupied cells (O(1) per cell), `s` by scanning the window
/// nearest-first only when `k > 0` (stops at the first occupied cell).
struct SafetyField<'a> {
    grid: &'a PlanGrid,
    r: usize,
    /// Width of the summed-area table: width + 2r + 1.
    sat_w: usize,
    /// Occupied-cell prefix sums over the map extended by r on every side
    /// (the extension is off-map, hence occupied).
    sat: Vec<u32>,
    /// Cached L per cell (row-major on the map); NaN = not yet computed.
    cache: Vec<f64>,
}

impl<'a> SafetyField<'a> {
    fn new(grid: &'a PlanGrid, radius: u32) -> Self {
        let r = radius as usize;
        let (w, h) = (grid.width(), grid.height());
        let (ew, eh) = (w + 2 * r, h + 2 * r);
        let sat_w = ew + 1;
        let mut sat = vec![0u32; sat_w * (eh + 1)];
        for y in 0..eh {
            let mut row_sum = 0u32;
            for x in 0..ew {
                let occ = !grid.is_free(x as i64 - r as i64, y as i64 - r as i64);
                row_sum += u32::from(occ);
                sat[(y + 1) * sat_w + x + 1] = sat[y * sat_w + x + 1] + row_sum;
            }
        }
        Self {
            grid,
            r,
            sat_w,
            sat,
            cache: vec![f64::NAN; w * h],
        }
    }

    /// L at on-map cell `(col, row)`.
    fn at(&mut self, col: usize, row: usize, window: &[(i64, i64, f64)]) -> f64 {
        let i = row * self.grid.width() + col;
        let cached = self.cache[i];
        if !cached.is_nan() {
            return cached;
        }
        // Window [col, col + 2r] × [row, row + 2r] in extended coordinates.
        let (x0, y0, x1, y1) = (col, row, col + 2 * self.r + 1, row + 2 * self.r + 1);
        let w = self.sat_w;
        let total = self.sat[y1 * w + x1] + self.sat[y0 * w + x0]
            - self.sat[y0 * w + x1]
            - self.sat[y1 * w + x0];
        let centre_occ = u32::from(!self.grid.is_free(col as i64, row as i64));
        let k = total - centre_occ;
        let l = if k == 0 {
            0.0
        } else {
            let (c, r) = (col as i64, row as i64);
            let s = window
                .iter()
                .find(|&&(dc, dr, _)| !self.grid.is_free(c + dc, r + dr))
                .map_or(1.0, |&(_, _, d)| d);
            f64::from(k) / s
        };
        self.cache[i] = l;
        l
    }
}

/// Open-list entry: smallest `f` first, then smallest `h` (closer to the
/// goal), then lowest index, so the search order is fully deterministic.
#[derive(Clone, Copy, Debug)]
struct Open {
    f: f64,
    h: f64,
    idx: usize,
}

impl PartialEq for Open {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}
impl Eq for Open {}
impl PartialOrd for Open {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Open {
    fn cmp(&self, other: &Self) -> Ordering {
        // Reversed: BinaryHeap is a max-heap.
        other
            .f
            .total_cmp(&self.f)
            .then_with(|| other.h.total_cmp(&self.h))
            .then_with(|| other.idx.cmp(&self.idx))
    }
}

const NO_PARENT: usize = usize::MAX;

super::grid_planner_via_search!(SafeAStar);

impl SafeAStar {
    /// The search, reporting its events to `obs` (`()`: none, at no cost).
    /// Open events carry the search's own g (length plus safety terms when
    /// admissible).
    pub fn search<O: SearchObserver + ?Sized>(
        &self,
        grid: &PlanGrid,
        start: GridPos,
        goal: GridPos,
        obs: &mut O,
    ) -> Result<Path, PlanError> {
        grid.check_endpoints(start, goal)?;
        let (w, h) = (grid.width(), grid.height());
        let cfg = &self.cfg;
        let mut field = SafetyField::new(grid, cfg.window_radius);
        let weighted = grid.is_weighted();
        let n = w * h;
        let mut g = vec![f64::INFINITY; n];
        let mut parent = vec![NO_PARENT; n];
        let mut closed = vec![false; n];
        let mut open = BinaryHeap::new();
        let index = |p: GridPos| p.row as usize * w + p.col as usize;
        let heur = |col: usize, row: usize| {
            cfg.heuristic.eval(
                col as f64 - f64::from(goal.col),
                row as f64 - f64::from(goal.row),
            )
        };
        let (si, gi) = (index(start), index(goal));
        g[si] = 0.0;
        let h0 = heur(start.col as usize, start.row as usize);
        open.push(Open {
            f: h0,
            h: h0,
            idx: si,
        });
        emit(obs, || SearchEvent::Open {
            cell: start,
            parent: None,
            g: 0.0,
            h: h0,
        });
        let mut n_expanded = 0usize;
        while let Some(Open { idx, .. }) = open.pop() {
            if closed[idx] {
                continue; // stale duplicate entry
            }
            closed[idx] = true;
            n_expanded += 1;
            let (col, row) = (idx % w, idx / w);
            let here = GridPos::new(col as u32, row as u32);
            emit(obs, || SearchEvent::Close { cell: here });
            if idx == gi {
                let mut cells = vec![here];
                let mut cur = idx;
                while parent[cur] != NO_PARENT {
                    cur = parent[cur];
                    cells.push(GridPos::new((cur % w) as u32, (cur / w) as u32));
                }
                cells.reverse();
                let cost = grid.path_cost(&cells);
                return Ok(Path {
                    cells,
                    cost,
                    expanded: n_expanded,
                });
            }
            for &(dc, dr, len) in &self.moves {
                let (mc, mr) = (col as i64 + dc, row as i64 + dr);
                if mc < 0 || mr < 0 || mc >= w as i64 || mr >= h as i64 {
                    continue;
                }
                let (mc, mr) = (mc as usize, mr as usize);
                let mi = mr * w + mc;
                if closed[mi] {
                    continue;
                }
                let next = GridPos::new(mc as u32, mr as u32);
                if !grid.segment_is_free(here, next, Diagonal::NoCornerCutting) {
                    continue;
                }
                // The goal's own danger is not charged: every path ends
                // there, and charging it would let penalised nodes with a
                // small g + h be expanded first and win the goal (module doc).
                let safety = if mi == gi {
                    0.0
                } else {
                    cfg.epsilon * field.at(mc, mr, &self.window)
                };
                // On weighted cells the move's length is weighted as every
                // planner weighs it (the heaviest cell it enters).
                let len = if weighted {
                    grid.segment_cost(here, next)
                } else {
                    len
                };
                let (step, extra) = if cfg.admissible {
                    (len + safety, 0.0)
                } else {
                    (len, safety)
                };
                let tentative = g[idx] + step;
                if tentative < g[mi] {
                    g[mi] = tentative;
                    parent[mi] = idx;
                    let hm = heur(mc, mr);
                    open.push(Open {
                        f: tentative + hm + extra,
                        h: hm,
                        idx: mi,
                    });
                    emit(obs, || SearchEvent::Open {
                        cell: next,
                        parent: Some(here),
                        g: tentative,
                        h: hm,
                    });
                }
            }
        }
        Err(PlanError::Unreachable {
            expanded: n_expanded,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::OccupancyGrid;

    fn grid(ascii: &str) -> PlanGrid {
        PlanGrid::new(&OccupancyGrid::from_ascii(ascii).unwrap(), false)
    }

    #[test]
    fn safety_field_matches_direct_term() {
        let pg = grid(
            "..........\n\
             ...#......\n\
             ......##..\n\
             .#........\n\
             ........#.\n\
             ..........\n",
        );
        for radius in 1..=3 {
            let window = window_offsets(radius);
            let mut field = SafetyField::new(&pg, radius);
            for row in 0..pg.height() {
                for col in 0..pg.width() {
                    let direct = safety_term(&pg, GridPos::new(col as u32, row as u32), radius);
                    let lazy = field.at(col, row, &window);
                    assert!((direct - lazy).abs() < 1e-12, "({col},{row}) r{radius}");
                }
            }
        }
    }

    #[test]
    fn safety_term_counts_off_map_as_occupied() {
        let pg = grid(".....\n.....\n.....\n.....\n.....\n");
        assert_eq!(safety_term(&pg, GridPos::new(2, 2), 2), 0.0);
        // Corner cell: 25 − 9 = 16 off-map cells in the 5×5 window, nearest 1.
        assert_eq!(safety_term(&pg, GridPos::new(0, 0), 2), 16.0);
        // One cell in from the top: 5 off-map cells on row −1, nearest at 2.
        assert_eq!(safety_term(&pg, GridPos::new(2, 1), 2), 2.5);
    }
}
