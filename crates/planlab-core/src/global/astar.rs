//! A* and Dijkstra on a [`PlanGrid`] (docs/algorithms.md §grid; Wu 2022 eq 3-6, f = g + w·h).
//!
//! 4- or 8-connected moves of cost 1 and √2 (times the weight of the cell
//! entered on a weighted grid, `global::weights`) under a [`Diagonal`] rule, any
//! [`Heuristic`] with a weight w ≥ 1 (cost ≤ w · optimum for a consistent
//! heuristic), Dijkstra as the zero heuristic.
//!
//! The search runs over flat arrays indexed by padded cell, in fixed-point
//! integer costs (exact ties, ties broken towards larger g), with a binary
//! heap and lazy deletion. Its buffers live in a per-thread search space
//! reused across queries and invalidated by a generation stamp, so a query
//! costs nothing for the cells it never touches; [`AStar`] itself is a plain
//! `Copy` value usable from `&self` on any thread.
//!
//! ```
//! use planlab_core::global::{astar::AStar, GridPlanner, GridPos, PlanGrid};
//! use planlab_core::map::OccupancyGrid;
//! let map = OccupancyGrid::from_ascii("
//! ....
//! .##.
//! ....
//! ").unwrap();
//! let grid = PlanGrid::new(&map, false);
//! let path = AStar::default().plan(&grid, GridPos::new(0, 1), GridPos::new(3, 1)).unwrap();
//! // No corner cutting: around the wall through the top row.
//! assert_eq!(path.cost, 5.0);
//! ```

use super::events::emit;
use super::search::{
    cells, check_size, finish, improves, trivial_path, with_space, xy, Estimate, FixedHeuristic,
    OctileEstimate, OpenList, SearchSpace, ZeroEstimate, AHEAD, DEFAULT_SPAN, DIR_MASK, G_MASK,
    G_SHIFT, OPEN,
};
use super::search::{diagonal_moves, dir_index, straight_free, straight_moves};
use super::{
    check_weight, Diagonal, GridPos, Heuristic, Path, PlanError, PlanGrid, SearchEvent,
    SearchObserver,
};
use serde::{Deserialize, Serialize};

/// A* settings.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct AStarConfig {
    /// Distance estimate to the goal (cells); octile by default.
    pub heuristic: Heuristic,
    /// Heuristic weight w in f = g + w·h (dimensionless, finite, ≥ 1; 1 =
    /// optimal with an admissible heuristic).
    pub weight: f64,
    /// Which diagonal moves are allowed; no corner cutting by default.
    pub diagonal: Diagonal,
}

impl Default for AStarConfig {
    fn default() -> Self {
        Self {
            heuristic: Heuristic::Octile,
            weight: 1.0,
            diagonal: Diagonal::NoCornerCutting,
        }
    }
}

/// The A* grid planner (and Dijkstra, with [`Heuristic::Zero`]).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct AStar {
    config: AStarConfig,
}

impl AStar {
    /// An A* planner; refuses a weight that is NaN, infinite or below 1.
    pub fn new(config: AStarConfig) -> Result<Self, PlanError> {
        check_weight(config.weight)?;
        Ok(Self { config })
    }

    /// Dijkstra's algorithm: A* with the zero heuristic.
    pub fn dijkstra(diagonal: Diagonal) -> Self {
        Self {
            config: AStarConfig {
                heuristic: Heuristic::Zero,
                weight: 1.0,
                diagonal,
            },
        }
    }

    /// The settings this planner was built with.
    pub fn config(&self) -> &AStarConfig {
        &self.config
    }
}

super::grid_planner_via_search!(AStar);

impl AStar {
    /// The search, reporting its events to `obs` (`()`: none, at no cost).
    pub fn search<O: SearchObserver + ?Sized>(
        &self,
        grid: &PlanGrid,
        start: GridPos,
        goal: GridPos,
        obs: &mut O,
    ) -> Result<Path, PlanError> {
        self.search_with::<O, true>(grid, start, goal, obs)
    }

    /// [`AStar::search`]; `AHEAD_ONLY` false (tests only) relaxes all eight
    /// moves of every expansion instead of leaving out those that cannot
    /// improve a neighbour ([`AHEAD`]).
    fn search_with<O: SearchObserver + ?Sized, const AHEAD_ONLY: bool>(
        &self,
        grid: &PlanGrid,
        start: GridPos,
        goal: GridPos,
        obs: &mut O,
    ) -> Result<Path, PlanError> {
        grid.check_endpoints(start, goal)?;
        check_size(grid)?;
        if start == goal {
            return Ok(trivial_path(start));
        }
        let c = self.config;
        let allowed = allowed_moves(c.diagonal);
        with_space(|space| {
            let q = Query {
                grid,
                start,
                goal,
                space,
                obs,
            };
            match (c.heuristic, c.weight == 1.0) {
                (Heuristic::Octile, true) => run::<_, _, AHEAD_ONLY>(q, allowed, OctileEstimate),
                (Heuristic::Zero, _) => run::<_, _, AHEAD_ONLY>(q, allowed, ZeroEstimate),
                _ => {
                    let est = FixedHeuristic::new(c.heuristic, c.weight);
                    run::<_, _, AHEAD_ONLY>(q, allowed, est)
                }
            }
        })
    }
}

/// One search's inputs.
struct Query<'a, O: ?Sized> {
    grid: &'a PlanGrid,
    start: GridPos,
    goal: GridPos,
    space: &'a mut SearchSpace,
    obs: &'a mut O,
}

pub(crate) const NEVER: u8 = 0;
pub(crate) const NO_CORNER_CUTTING: u8 = 1;
pub(crate) const ONE_SIDE_FREE: u8 = 2;
pub(crate) const ALWAYS: u8 = 3;

/// The neighbour bits the corner rule `diagonal` leaves ([`moves_allowed`]).
pub(crate) fn allowed_moves(diagonal: Diagonal) -> &'static [u8; 256] {
    let rule = match diagonal {
        Diagonal::Never => NEVER,
        Diagonal::NoCornerCutting => NO_CORNER_CUTTING,
        Diagonal::OneSideFree => ONE_SIDE_FREE,
        Diagonal::Always => ALWAYS,
    };
    &MOVES_ALLOWED[rule as usize]
}

/// [`moves_allowed`] for each corner rule, indexed by `NEVER` … `ALWAYS`.
pub(crate) static MOVES_ALLOWED: [[u8; 256]; 4] = [
    moves_allowed(NEVER),
    moves_allowed(NO_CORNER_CUTTING),
    moves_allowed(ONE_SIDE_FREE),
    moves_allowed(ALWAYS),
];

/// For every byte of neighbour bits ([`PlanGrid::neighbours`]), the same
/// bits with the diagonal moves the corner `rule` forbids cleared: the
/// relaxation then tests one bit a move whatever the rule, and the loop is
/// not copied per rule (code size: a copy of A*'s loop per rule took
/// 50 kB of every wasm module that plans on grids).
pub(crate) const fn moves_allowed(rule: u8) -> [u8; 256] {
    const fn bit(nb: usize, dx: isize, dy: isize) -> bool {
        nb & 1 << dir_index(dx, dy) != 0
    }
    let mut out = [0u8; 256];
    let mut nb = 0;
    while nb < 256 {
        let mut allowed = nb as u8 & 0x0F;
        let diagonals = [(1, 1), (1, -1), (-1, 1), (-1, -1)];
        let mut k = 0;
        while k < diagonals.len() {
            let (dx, dy) = diagonals[k];
            // The rules of docs/algorithms.md §grid (tested against a plain
            // statement of them).
            let (a, b) = (bit(nb, dx, 0), bit(nb, 0, dy));
            let sides = match rule {
                NO_CORNER_CUTTING => a && b,
                ONE_SIDE_FREE => a || b,
                ALWAYS => true,
                _ => false,
            };
            if sides && bit(nb, dx, dy) {
                allowed |= 1 << dir_index(dx, dy);
            }
            k += 1;
        }
        out[nb] = allowed;
        nb += 1;
    }
    out
}

fn run<E: Estimate, O: SearchObserver + ?Sized, const AHEAD_ONLY: bool>(
    q: Query<'_, O>,
    allowed: &[u8; 256],
    est: E,
) -> Result<Path, PlanError> {
    let Query {
        grid,
        start,
        goal,
        space,
        obs,
    } = q;
    let s = grid.padded_index(start);
    let t = grid.padded_index(goal);
    // A move costs at most DIAG times the heaviest weight.
    let heaviest = if grid.is_weighted() {
        crate::map::MAX_WEIGHT
    } else {
        1
    };
    let span = DEFAULT_SPAN * u64::from(heaviest);
    space.reset(grid.padded().len(), span);
    let tag = space.open_word(0, 0);
    let SearchSpace {
        words,
        buckets,
        binary,
        ..
    } = &mut *space;
    // Weighted cells get their own copy of the loop, so unit grids pay
    // nothing for them.
    macro_rules! search {
        ($weighted:literal, $open:expr) => {
            search::<E, _, O, $weighted, AHEAD_ONLY>(
                grid,
                (s, t),
                allowed,
                words,
                $open,
                tag,
                est,
                obs,
            )
        };
    }
    let (reached, expanded) = match (E::MONOTONE, grid.is_weighted()) {
        (true, false) => search!(false, buckets),
        (true, true) => search!(true, buckets),
        (false, false) => search!(false, binary),
        (false, true) => search!(true, binary),
    };
    finish(grid, space, (s, t), reached, expanded)
}

/// The A* loop: whether `t` was reached, and how many cells were expanded.
/// `tag` is the open word of cost 0 (see [`SearchSpace::open_word`]).
/// `WEIGHTED`: a move costs its length times the weight of the cell it
/// enters (`global::weights`).
#[allow(clippy::too_many_arguments)]
fn search<
    E: Estimate,
    Q: OpenList,
    O: SearchObserver + ?Sized,
    const WEIGHTED: bool,
    const AHEAD_ONLY: bool,
>(
    grid: &PlanGrid,
    (s, t): (usize, usize),
    allowed: &[u8; 256],
    words: &mut [u64],
    open: &mut Q,
    tag: u64,
    est: E,
    obs: &mut O,
) -> (bool, usize) {
    let stride = grid.stride();
    let (gx, gy) = xy(t, stride);
    let neighbours = grid.neighbours();
    let weights = grid.padded_weights().unwrap_or(&[]);

    if let Some(w) = words.get_mut(s) {
        *w = tag;
    }
    let (sx, sy) = xy(s, stride);
    let h0 = est.h(sx.abs_diff(gx), sy.abs_diff(gy));
    open.push(h0, 0, s);
    emit(obs, || SearchEvent::Open {
        cell: grid.pos_of(s),
        parent: None,
        g: 0.0,
        h: est.unweighted_cells(h0),
    });

    let mut expanded = 0usize;
    while let Some(i) = open.pop() {
        let Some(w) = words.get_mut(i) else { continue };
        if *w & OPEN == 0 {
            // Already expanded: a stale duplicate entry.
            continue;
        }
        *w &= !OPEN;
        let g = (*w >> G_SHIFT) & G_MASK;
        expanded += 1;
        emit(obs, || SearchEvent::Close {
            cell: grid.pos_of(i),
        });
        if i == t {
            return (true, expanded);
        }
        let (x, y) = xy(i, stride);
        // Free cells are interior, so these never wrap; a wrapped index
        // would simply read as blocked.
        let up = i.wrapping_sub(stride);
        let down = i + stride;
        // The cell relative to the goal: a neighbour's offset is then one
        // add and an absolute value. (Taking the six offsets once an
        // expansion ran 6 % more instructions: most neighbours are not
        // pushed.)
        let (rx, ry) = (x as isize - gx as isize, y as isize - gy as isize);
        // The corner rule folded into the neighbour bits: a diagonal move
        // is one bit like a straight one.
        let nb = allowed[usize::from(neighbours.get(i).copied().unwrap_or(0))];
        // Only the moves that can improve a neighbour (`AHEAD`; the other
        // copy, tests only, relaxes all eight to show it changes nothing).
        let nb = if AHEAD_ONLY && i != s {
            nb & AHEAD[(*w & DIR_MASK) as usize]
        } else {
            nb
        };
        let [n, so, we, e] = straight_free(nb);

        macro_rules! relax {
            ($j:expr, $dx:expr, $dy:expr, $cost:expr, $dir:expr) => {{
                let j: usize = $j;
                let ng = if WEIGHTED {
                    g + $cost * weights.get(j).map_or(1, |&w| u64::from(w))
                } else {
                    g + $cost
                };
                let new = tag | ng << G_SHIFT | $dir;
                if let Some(old) = words.get_mut(j) {
                    if improves(*old, new) {
                        *old = new;
                        let (nx, ny): (isize, isize) = (rx + $dx, ry + $dy);
                        let h = est.h(nx.unsigned_abs(), ny.unsigned_abs());
                        open.push(ng.saturating_add(h), ng, j);
                        emit(obs, || SearchEvent::Open {
                            cell: grid.pos_of(j),
                            parent: Some(grid.pos_of(i)),
                            g: cells(ng),
                            h: est.unweighted_cells(h),
                        });
                    }
                }
            }};
        }

        straight_moves!(relax, i, (up, down), [n, so, we, e]);
        if nb >> 4 != 0 {
            diagonal_moves!(relax, nb, (up, down));
        }
    }
    (false, expanded)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::global::GridPlanner;
    use crate::global::SearchLog;
    use crate::map::OccupancyGrid;

    /// Whether a diagonal move is legal under `RULE`, given its side cells
    /// and its target cell: the rules as docs/algorithms.md states them.
    fn diagonal_ok<const RULE: u8>(side_a: bool, side_b: bool, target: bool) -> bool {
        target
            && match RULE {
                NO_CORNER_CUTTING => side_a && side_b,
                ONE_SIDE_FREE => side_a || side_b,
                ALWAYS => true,
                _ => false,
            }
    }

    #[test]
    fn corner_rule_table_allows_what_diagonal_ok_allows_for_every_neighbour_byte() {
        let check = |rule: u8, ok: fn(bool, bool, bool) -> bool| {
            let table = moves_allowed(rule);
            for nb in 0..=255u8 {
                let bit = |dx: isize, dy: isize| nb & 1 << dir_index(dx, dy) != 0;
                let mut want = nb & 0x0F;
                for (dx, dy) in [(1, 1), (1, -1), (-1, 1), (-1, -1)] {
                    if ok(bit(dx, 0), bit(0, dy), bit(dx, dy)) {
                        want |= 1 << dir_index(dx, dy);
                    }
                }
                assert_eq!(table[nb as usize], want, "rule {rule} bits {nb:08b}");
            }
        };
        check(NEVER, diagonal_ok::<NEVER>);
        check(NO_CORNER_CUTTING, diagonal_ok::<NO_CORNER_CUTTING>);
        check(ONE_SIDE_FREE, diagonal_ok::<ONE_SIDE_FREE>);
        check(ALWAYS, diagonal_ok::<ALWAYS>);
    }

    fn grid(text: &str) -> PlanGrid {
        PlanGrid::new(&OccupancyGrid::from_ascii(text).unwrap(), false)
    }

    #[test]
    fn detours_around_a_wall_without_cutting_corners() {
        let g = grid(
            "
.....
.###.
.....
",
        );
        let p = AStar::default()
            .plan(&g, GridPos::new(0, 1), GridPos::new(4, 1))
            .unwrap();
        // The diagonal (0,1)→(1,0) would cut the wall's corner (1,1), so the
        // path goes up, along and down: 6 straight moves.
        assert!(g.path_is_free(&p.cells, Diagonal::NoCornerCutting));
        assert!((p.cost - 6.0).abs() < 1e-9);
        assert_eq!(p.cells.first(), Some(&GridPos::new(0, 1)));
        assert_eq!(p.cells.last(), Some(&GridPos::new(4, 1)));
    }

    #[test]
    fn corner_cutting_rules_change_the_cost() {
        let g = grid(
            "
.#
..
",
        );
        let (a, b) = (GridPos::new(0, 0), GridPos::new(1, 1));
        let strict = AStar::default().plan(&g, a, b).unwrap();
        assert!((strict.cost - 2.0).abs() < 1e-12);
        for rule in [Diagonal::OneSideFree, Diagonal::Always] {
            let cfg = AStarConfig {
                diagonal: rule,
                ..AStarConfig::default()
            };
            let p = AStar::new(cfg).unwrap().plan(&g, a, b).unwrap();
            assert!((p.cost - 2f64.sqrt()).abs() < 1e-12);
        }
    }

    #[test]
    fn dijkstra_expands_more_than_astar_for_the_same_cost() {
        let g = PlanGrid::from_fn(20, 20, |_, _| true);
        let (a, b) = (GridPos::new(0, 0), GridPos::new(19, 7));
        let astar = AStar::default().plan(&g, a, b).unwrap();
        let dijkstra = AStar::dijkstra(Diagonal::NoCornerCutting)
            .plan(&g, a, b)
            .unwrap();
        assert!((astar.cost - dijkstra.cost).abs() < 1e-9);
        assert!((astar.cost - (12.0 + 7.0 * 2f64.sqrt())).abs() < 1e-9);
        assert!(astar.expanded < dijkstra.expanded);
        // Octile is exact on an empty grid and ties go to the deepest node,
        // so A* expands only the path.
        assert_eq!(astar.expanded, astar.cells.len());
    }

    proptest::proptest! {
        /// Leaving out the relaxations `AHEAD` rules out changes nothing:
        /// the same events in the same order and the same path, for every
        /// corner rule and estimate, weighted A*, and weighted cells.
        #[test]
        fn relaxing_only_the_moves_ahead_gives_the_same_search_event_for_event(
            w in 1usize..24,
            h in 1usize..20,
            density in 0u64..45,
            seed in proptest::prelude::any::<u64>(),
            rule in 0usize..4,
            heuristic in 0usize..5,
            weighted_astar in proptest::prelude::any::<bool>(),
            heavy in proptest::collection::vec((0usize..24, 0usize..20, 2u8..=9), 0..10),
            ends in (0usize..480, 0usize..480),
        ) {
            let mut state = seed | 1;
            let mut grid = PlanGrid::from_fn(w, h, |_, _| {
                state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
                (state >> 33) % 100 >= density
            });
            for (c, r, wt) in heavy {
                grid.set_weight(c % w, r % h, wt);
            }
            let free: Vec<GridPos> = (0..h)
                .flat_map(|y| (0..w).map(move |x| GridPos::new(x as u32, y as u32)))
                .filter(|p| grid.is_free(p.col as i64, p.row as i64))
                .collect();
            proptest::prop_assume!(!free.is_empty());
            let (s, t) = (free[ends.0 % free.len()], free[ends.1 % free.len()]);
            let astar = AStar::new(AStarConfig {
                diagonal: [
                    Diagonal::Never,
                    Diagonal::NoCornerCutting,
                    Diagonal::OneSideFree,
                    Diagonal::Always,
                ][rule],
                heuristic: [
                    Heuristic::Octile,
                    Heuristic::Zero,
                    Heuristic::Euclidean,
                    Heuristic::Manhattan,
                    Heuristic::Chebyshev,
                ][heuristic],
                weight: if weighted_astar { 1.5 } else { 1.0 },
            })
            .unwrap();
            let mut ahead = SearchLog::with_limit(usize::MAX);
            let mut all = SearchLog::with_limit(usize::MAX);
            let a = astar.search_with::<_, true>(&grid, s, t, &mut ahead);
            let b = astar.search_with::<_, false>(&grid, s, t, &mut all);
            proptest::prop_assert_eq!(a, b);
            proptest::prop_assert_eq!(ahead, all);
        }
    }
}
