//! Bidirectional A* on a [`PlanGrid`] (docs/algorithms.md §classic), the
//! search behind [`super::classic::BidirectionalAStar`].
//!
//! Two searches, one from the start and one from the goal, each a plain A*
//! over the machinery of [`super::astar`]: fixed-point integer costs, one
//! search word per cell and direction behind a generation tag
//! ([`PairSpace`]), the bucket queue for consistent estimates.
//!
//! **The potential.** Each direction orders its open list by g plus the
//! *average potential* of Ikeda et al. (1994): forwards
//! p_f(v) = (h(v, goal) − h(v, start)) / 2, backwards p_b = −p_f. Both are
//! consistent whenever h is (a move u → v costs at least h(u, v), and h is a
//! metric), so each direction is Dijkstra's algorithm on non-negative
//! reduced costs: a cell is final when it is expanded, and the popped keys
//! never decrease. Keys are kept doubled, `2g + h(v, other end) −
//! h(v, own end) + off`, with `off = h(start, goal) + 1`, so they are
//! non-negative integers.
//!
//! **The meeting test and the stopping rule** (Goldberg & Harrelson 2005,
//! "Computing the shortest path: A* search meets graph theory", SODA).
//! μ is the cheapest start–goal path seen: g_f(v) + g_b(v) over every cell
//! v reached from both sides, tested when a direction reaches or improves a
//! cell and when it expands one. Because p_f + p_b = 0, the two keys of one
//! cell add up to 2(g_f + g_b) + 2·off, and the search stops as soon as
//! min key_f + min key_b ≥ 2(μ + off): every path not yet seen leaves the
//! forward search at a cell of key ≥ min key_f and enters the backward
//! search at one of key ≥ min key_b, so costs at least μ. Without the
//! shared offset this is their rule top_f + top_r ≥ μ + p_r(t).
//!
//! The direction expanded next is the one that has popped fewer entries
//! (Pohl's cardinality rule; the stop rule holds for any order): it
//! expands fewer cells than taking the smaller least key. Backwards the
//! moves are generated in the mirrored order so both searches follow the
//! same one of many equal-cost paths and meet halfway. Cells that cannot
//! lie on a path cheaper than μ are closed without expansion
//! (docs/algorithms.md §classic).

use super::astar::allowed_moves;
use super::events::emit;
use super::search::{
    cells, check_size, improves, path_of, trivial_path, with_pair_space, xy, Estimate,
    FixedHeuristic, OctileEstimate, OpenList, PairSpace, AHEAD, DIRS, DIR_MASK, G_MASK, G_SHIFT,
    OPEN, STRAIGHT,
};
use super::search::{diagonal_moves, straight_free, straight_moves};
use super::{Diagonal, GridPos, Heuristic, Path, PlanError, PlanGrid, SearchEvent, SearchObserver};

/// Bidirectional A* from `start` to `goal` under `diagonal`, with `heuristic`
/// towards the goal forwards and towards the start backwards, reporting its
/// events to `obs` (the backward search's parents point towards the goal).
pub(crate) fn search<O: SearchObserver + ?Sized>(
    grid: &PlanGrid,
    start: GridPos,
    goal: GridPos,
    diagonal: Diagonal,
    heuristic: Heuristic,
    obs: &mut O,
) -> Result<Path, PlanError> {
    search_with::<O, true>(grid, start, goal, diagonal, heuristic, obs)
}

/// [`search`]; `AHEAD_ONLY` false (tests only) relaxes all eight moves of
/// every expansion instead of leaving out those that cannot improve a
/// neighbour ([`AHEAD`]).
fn search_with<O: SearchObserver + ?Sized, const AHEAD_ONLY: bool>(
    grid: &PlanGrid,
    start: GridPos,
    goal: GridPos,
    diagonal: Diagonal,
    heuristic: Heuristic,
    obs: &mut O,
) -> Result<Path, PlanError> {
    grid.check_endpoints(start, goal)?;
    check_size(grid)?;
    if start == goal {
        return Ok(trivial_path(start));
    }
    // The corner rule is a runtime value: one copy of the loop per estimate
    // keeps the wasm modules small (a copy per rule and weighting grew them
    // by 200 kB). The weighting is too, except that the octile estimate on
    // a unit grid gets its own copy without the weighted-cost branch
    // (`Estimate::UNIT_COPY`): 10 % fewer instructions on random512.
    let allowed = allowed_moves(diagonal);
    with_pair_space(|space| {
        let q = Query {
            grid,
            s: grid.padded_index(start),
            t: grid.padded_index(goal),
            space,
            obs,
        };
        match heuristic {
            Heuristic::Octile => run::<_, _, AHEAD_ONLY>(q, allowed, OctileEstimate),
            // One general copy for the other estimates, zero included (as
            // in JPS: a copy per estimate costs kilobytes of wasm).
            h => run::<_, _, AHEAD_ONLY>(q, allowed, FixedHeuristic::new(h, 1.0)),
        }
    })
}

/// One search's inputs (padded start and goal indices).
struct Query<'a, O: ?Sized> {
    grid: &'a PlanGrid,
    s: usize,
    t: usize,
    space: &'a mut PairSpace,
    obs: &'a mut O,
}

fn run<E: Estimate, O: SearchObserver + ?Sized, const AHEAD_ONLY: bool>(
    q: Query<'_, O>,
    allowed: &'static [u8; 256],
    est: E,
) -> Result<Path, PlanError> {
    let Query {
        grid,
        s,
        t,
        space,
        obs,
    } = q;
    space.reset(grid.padded().len());
    let tag = space.tag;
    let PairSpace {
        words,
        buckets,
        binary,
        ..
    } = &mut *space;
    let ends = (s, t);
    let (meet, expanded) = if E::MONOTONE {
        if E::UNIT_COPY && !grid.is_weighted() {
            Bidir::<_, _, _, false, AHEAD_ONLY>::new(
                grid, ends, words, buckets, tag, est, obs, allowed,
            )
            .run()
        } else {
            Bidir::<_, _, _, true, AHEAD_ONLY>::new(
                grid, ends, words, buckets, tag, est, obs, allowed,
            )
            .run()
        }
    } else {
        Bidir::<_, _, _, true, AHEAD_ONLY>::new(grid, ends, words, binary, tag, est, obs, allowed)
            .run()
    };
    let Some(m) = meet else {
        return Err(PlanError::Unreachable { expanded });
    };
    // The chains cannot fail (every parent is a closed cell whose g is
    // final); an empty path would be a bug.
    let cells = path_through(grid, space, (s, t), m).unwrap_or_default();
    Ok(path_of(grid, cells, expanded))
}

/// The cells from `s` to `t` through the meeting cell `m`: back from `m`
/// to `s` along the forward arrival moves, then on from `m` to `t` along
/// the backward ones, into one vector allocated once (a path of cost g has
/// at most g / STRAIGHT moves; two vectors grown and joined were a sixth
/// of the instructions of a query on arena's 49 × 49 map). `None` if the
/// words are inconsistent (never, barring a bug).
fn path_through(
    grid: &PlanGrid,
    space: &PairSpace,
    (s, t): (usize, usize),
    m: usize,
) -> Option<Vec<GridPos>> {
    let stride = grid.stride() as isize;
    let cost = space.reached(0, m)?.0 + space.reached(1, m)?.0;
    let limit = (cost / STRAIGHT) as usize + 1;
    let mut out = Vec::with_capacity(limit);
    for (side, root) in [(0, s), (1, t)] {
        let mut c = m;
        if side == 0 {
            out.push(grid.pos_of(m));
        }
        while c != root {
            let (_, dir) = space.reached(side, c)?;
            let (dx, dy) = DIRS.get(dir as usize).copied()?;
            c = c.checked_add_signed(-(dy * stride + dx))?;
            out.push(grid.pos_of(c));
            // More cells than the cost allows would be a cycle.
            if out.len() > limit {
                return None;
            }
        }
        if side == 0 {
            out.reverse();
        }
    }
    Some(out)
}

/// The state of one bidirectional search. Direction 0 searches forwards
/// from the start, 1 backwards from the goal.
/// `WEIGHTED`: whether the loop keeps the weighted-cost branch at all
/// (the octile estimate on a unit grid runs a copy without it).
/// `AHEAD_ONLY`: whether an expansion leaves out the moves [`AHEAD`] rules
/// out (false only in a test copy).
struct Bidir<'a, E, Q, O: ?Sized, const WEIGHTED: bool, const AHEAD_ONLY: bool> {
    grid: &'a PlanGrid,
    /// Neighbour bits per padded cell (`PlanGrid::neighbours`).
    neighbours: &'a [u8],
    weights: &'a [u8],
    stride: usize,
    words: &'a mut [[u64; 2]],
    open: &'a mut [Q; 2],
    /// Open word of cost 0 of this search (tag | OPEN).
    tag: u64,
    /// Words of this search lie below this ([`PairSpace::fresh_below`]).
    fresh: u64,
    est: E,
    obs: &'a mut O,
    /// Padded indices of the start and of the goal.
    roots: [usize; 2],
    /// Their padded (x, y).
    ends: [(usize, usize); 2],
    /// Key offset h(start, goal) + 1: keeps keys non-negative (h is a metric,
    /// so h(v, own end) ≤ h(start, goal) + h(v, other end); the 1 absorbs a
    /// rounded-down Euclidean estimate's slack).
    off: u64,
    /// Cheapest start–goal cost seen, and the cell it runs through.
    mu: u64,
    meet: usize,
    /// The stop rule's bound on min key_f + min key_b: 2(μ + off), or
    /// `u64::MAX` while no path is known.
    stop: u64,
    /// Cells each direction has reached but not yet expanded (its frontier;
    /// cells left out of the open list by the pruning count too).
    frontier: [usize; 2],
    /// Diagonal moves the corner rule allows, by neighbour bits
    /// ([`super::astar::moves_allowed`]).
    allowed: &'static [u8; 256],
    /// Whether moves cost by the weight of a cell (`global::weights`).
    weighted: bool,
}

impl<
        'a,
        E: Estimate,
        Q: OpenList,
        O: SearchObserver + ?Sized,
        const WEIGHTED: bool,
        const AHEAD_ONLY: bool,
    > Bidir<'a, E, Q, O, WEIGHTED, AHEAD_ONLY>
{
    #[allow(clippy::too_many_arguments)]
    fn new(
        grid: &'a PlanGrid,
        (s, t): (usize, usize),
        words: &'a mut [[u64; 2]],
        open: &'a mut [Q; 2],
        tag: u64,
        est: E,
        obs: &'a mut O,
        allowed: &'static [u8; 256],
    ) -> Self {
        let stride = grid.stride();
        let ends = [xy(s, stride), xy(t, stride)];
        let span = est.h(ends[0].0.abs_diff(ends[1].0), ends[0].1.abs_diff(ends[1].1));
        Self {
            grid,
            neighbours: grid.neighbours(),
            weights: grid.padded_weights().unwrap_or(&[]),
            stride,
            words,
            open,
            tag: tag | OPEN,
            fresh: PairSpace::fresh_below(tag),
            est,
            obs,
            roots: [s, t],
            ends,
            off: span + 1,
            mu: u64::MAX,
            meet: usize::MAX,
            stop: u64::MAX,
            frontier: [1, 1],
            allowed,
            weighted: grid.is_weighted(),
        }
    }

    /// Estimate from padded `(x, y)` to end `k` (0 start, 1 goal).
    #[inline(always)]
    fn h_to(&self, k: usize, x: usize, y: usize) -> u64 {
        let (ex, ey) = self.ends[k];
        self.est.h(x.abs_diff(ex), y.abs_diff(ey))
    }

    /// The search: the meeting cell (`None`: no path) and the cells
    /// expanded. On a weighted grid a move costs its length times the
    /// weight of the cell it enters (backwards: of the cell expanded).
    fn run(mut self) -> (Option<usize>, usize) {
        for side in 0..2 {
            let root = self.roots[side];
            if let Some(pair) = self.words.get_mut(root) {
                pair[side] = self.tag;
            }
            let (x, y) = self.ends[side];
            let towards = self.h_to(1 - side, x, y);
            self.open[side].push(towards + self.off, 0, root);
            let est = self.est;
            emit(self.obs, || SearchEvent::Open {
                cell: self.grid.pos_of(root),
                parent: None,
                g: 0.0,
                h: est.unweighted_cells(towards),
            });
        }
        let mut expanded = 0usize;
        // Each side's least key; expanding one side pushes only onto its
        // own list, so only that side's needs reading again.
        let (mut kf, mut kb) = (self.open[0].min_key(), self.open[1].min_key());
        // Until one direction has reached every cell it can (μ is then the
        // optimum, or there is no path) or the stop rule holds.
        while let (Some(f), Some(b)) = (kf, kb) {
            if f + b >= self.stop {
                break;
            }
            if self.frontier[0] <= self.frontier[1] {
                if let Some(i) = self.open[0].pop() {
                    expanded += usize::from(self.expand::<0>(i));
                }
                kf = self.open[0].min_key();
            } else {
                if let Some(i) = self.open[1].pop() {
                    expanded += usize::from(self.expand::<1>(i));
                }
                kb = self.open[1].min_key();
            }
        }
        ((self.mu != u64::MAX).then_some(self.meet), expanded)
    }

    /// Closes cell `i` in direction `SIDE` and, unless pruned, generates
    /// its neighbours; `false` for a stale entry.
    #[inline(always)]
    fn expand<const SIDE: usize>(&mut self, i: usize) -> bool {
        let Some(pair) = self.words.get_mut(i) else {
            return false;
        };
        let w = pair[SIDE];
        if w & OPEN == 0 {
            // Already expanded: a stale duplicate entry.
            return false;
        }
        pair[SIDE] = w & !OPEN;
        let other = pair[1 - SIDE];
        self.frontier[SIDE] -= 1;
        let g = (w >> G_SHIFT) & G_MASK;
        // No meeting test here: g_f + g_b of a cell was tested whenever
        // either word last changed (see `relax`), and expanding changes
        // neither cost.
        let grid = self.grid;
        emit(self.obs, || SearchEvent::Close {
            cell: grid.pos_of(i),
        });
        // Pruning: closed from the other side as well, both costs are final
        // and their sum is in μ already, and a path through a neighbour
        // that is cheaper than through `i` reaches that neighbour from the
        // other side too. The cell still counts as closed, like A*'s goal,
        // whose neighbours are not generated either. (A test of
        // g + h(i, other end) ≥ μ here would be redundant: by consistency
        // every neighbour then fails the same test at its push.)
        if other < self.fresh && other & OPEN == 0 {
            return true;
        }
        let stride = self.stride;
        let (x, y) = xy(i, stride);
        // Free cells are interior, so these never wrap; a wrapped index
        // would simply read as blocked.
        let up = i.wrapping_sub(stride);
        let down = i + stride;
        // The corner rule folded into the neighbour bits: one table load,
        // no branch on the rule a diagonal.
        let raw = self.neighbours.get(i).copied().unwrap_or(0);
        let nb = self.allowed[raw as usize];
        // Only the moves that can improve a neighbour, as in A*: the
        // backward words keep the move's direction the same way (the
        // parent is `i` minus it), and the argument holds backwards too (a
        // move pays the weight of the cell it runs into, here the parent's
        // for the side cells' straight moves). Not at an end, which has no
        // parent.
        let nb = if AHEAD_ONLY && i != self.roots[SIDE] {
            nb & AHEAD[(w & DIR_MASK) as usize]
        } else {
            nb
        };
        let [n, so, we, e] = straight_free(nb);
        let weights = self.weights;
        let weight = |j: usize| weights.get(j).map_or(1, |&w| u64::from(w));
        // Backwards, the move runs from the neighbour into `i`: `i` pays.
        let weighted = WEIGHTED && self.weighted;
        let here_weight = if weighted && SIDE == 1 { weight(i) } else { 1 };
        // Everything the relaxations touch in locals: stores through the
        // words slice would otherwise make the compiler reload fields.
        let (tag, fresh, off, est) = (self.tag, self.fresh, self.off, self.est);
        // Coordinates relative to the other end (what the estimate towards
        // it reads), and that end relative to this side's own end: four
        // values live across the relaxations instead of six.
        let ((ox, oy), (mx, my)) = (self.ends[1 - SIDE], self.ends[SIDE]);
        let (rx, ry) = (x as isize - ox as isize, y as isize - oy as isize);
        let (cx, cy) = (ox as isize - mx as isize, oy as isize - my as isize);
        let (mut mu, mut meet) = (self.mu, self.meet);
        let mut reached = 0usize;
        let words = &mut *self.words;
        let open = &mut self.open[SIDE];
        let obs = &mut *self.obs;

        macro_rules! relax {
            ($j:expr, $dx:expr, $dy:expr, $cost:expr, $dir:expr) => {{
                let j: usize = $j;
                let ng = if weighted {
                    let w = if SIDE == 0 { weight(j) } else { here_weight };
                    g + $cost * w
                } else {
                    g + $cost
                };
                let new = tag | ng << G_SHIFT | $dir;
                if let Some(pair) = words.get_mut(j) {
                    let old = pair[SIDE];
                    if improves(old, new) {
                        reached += usize::from(old >= fresh);
                        pair[SIDE] = new;
                        let other = pair[1 - SIDE];
                        // The meeting test.
                        if other < fresh {
                            let through = ng + ((other >> G_SHIFT) & G_MASK);
                            if through < mu {
                                mu = through;
                                meet = j;
                            }
                        }
                        let (nx, ny): (isize, isize) = (rx + $dx, ry + $dy);
                        let towards = est.h(nx.unsigned_abs(), ny.unsigned_abs());
                        // Left out of the open list when no path through it
                        // can beat μ (its word stays, for the meeting test).
                        if ng + towards < mu {
                            let back = est.h((nx + cx).unsigned_abs(), (ny + cy).unsigned_abs());
                            let key = (2 * ng + towards + off).saturating_sub(back);
                            // The bucket queue breaks ties by push order and
                            // ignores g: 0 saves packing it.
                            open.push(key, if E::MONOTONE { 0 } else { ng }, j);
                            emit(obs, || SearchEvent::Open {
                                cell: grid.pos_of(j),
                                parent: Some(grid.pos_of(i)),
                                g: cells(ng),
                                h: est.unweighted_cells(towards),
                            });
                        }
                    }
                }
            }};
        }

        // `nb` already holds only the diagonal moves the rule allows.
        macro_rules! straight {
            () => {
                straight_moves!(relax, i, (up, down), [n, so, we, e])
            };
        }
        macro_rules! diagonal {
            () => {
                if nb >> 4 != 0 {
                    diagonal_moves!(relax, nb, (up, down));
                }
            };
        }
        // Among equal keys the open list pops the latest pushed, so the
        // forward search takes diagonal moves first. Backwards, straight
        // moves go first: the two searches then trace the same one of the
        // many equal-cost paths (diagonal moves first from the start, last
        // towards the goal) and meet halfway instead of running past each
        // other along the two sides of their parallelogram.
        if SIDE == 0 {
            straight!();
            diagonal!();
        } else {
            diagonal!();
            straight!();
        }
        if mu != self.mu {
            self.mu = mu;
            self.stop = 2 * (mu + off);
            self.meet = meet;
        }
        self.frontier[SIDE] += reached;
        true
    }
}

#[cfg(test)]
mod tests {
    use super::search_with;
    use crate::global::astar::{AStar, AStarConfig};
    use crate::global::classic::BidirectionalAStar;
    use crate::global::SearchLog;
    use crate::global::{Diagonal, GridPlanner, GridPos, Heuristic, PlanGrid, SearchEvent};
    use crate::map::OccupancyGrid;
    use proptest::prelude::*;

    /// Collects the cells closed, in order.
    #[derive(Default)]
    struct Closed(Vec<GridPos>);

    impl crate::global::SearchObserver for Closed {
        fn event(&mut self, e: SearchEvent) {
            if let SearchEvent::Close { cell } = e {
                self.0.push(cell);
            }
        }
    }

    #[test]
    fn bidirectional_expands_the_side_with_the_smaller_frontier() {
        // An open room (columns 0..=20) and a corridor one cell wide along
        // row 10 to the goal at its dead end. After the start's first
        // expansion the forward frontier holds 8 cells, the backward one a
        // single corridor cell, and it stays at one while the backward
        // search walks the corridor: all nine corridor cells are closed
        // next. Alternating by entries popped would interleave room cells.
        let grid = PlanGrid::from_fn(30, 21, |c, r| c <= 20 || r == 10);
        let (s, t) = (GridPos::new(5, 10), GridPos::new(29, 10));
        let mut closed = Closed::default();
        let b = BidirectionalAStar::default()
            .search(&grid, s, t, &mut closed)
            .unwrap();
        assert!((b.cost - 24.0).abs() < 1e-9);
        assert_eq!(closed.0.first(), Some(&s));
        let next: Vec<GridPos> = closed.0.iter().skip(1).take(9).copied().collect();
        let corridor: Vec<GridPos> = (21..=29).rev().map(|c| GridPos::new(c, 10)).collect();
        assert_eq!(next, corridor);
    }

    proptest! {
        #[test]
        fn bidirectional_cost_equals_astar_on_random_weighted_grids(
            query in weighted_queries(28),
            rule in 0usize..4,
        ) {
            let Some((grid, s, t)) = query else { return Err(TestCaseError::reject("no free cell")) };
            let diagonal = RULES[rule];
            let astar = AStar::new(AStarConfig { diagonal, ..AStarConfig::default() }).unwrap();
            let bidir = BidirectionalAStar { diagonal, heuristic: Heuristic::Octile };
            match (astar.plan(&grid, s, t), bidir.plan(&grid, s, t)) {
                (Ok(a), Ok(b)) => {
                    prop_assert!((a.cost - b.cost).abs() < 1e-9, "A* {} bidirectional {}", a.cost, b.cost);
                    prop_assert!(grid.path_is_free(&b.cells, diagonal));
                    prop_assert_eq!((b.cells.first(), b.cells.last()), (Some(&s), Some(&t)));
                }
                (Err(_), Err(_)) => {}
                (a, b) => prop_assert!(false, "{:?} vs {:?}", a, b),
            }
        }
    }

    proptest! {
        /// Leaving out the relaxations `AHEAD` rules out changes nothing,
        /// in either direction: the same events in the same order and the
        /// same path, for every corner rule and consistent estimate, on
        /// weighted cells too.
        #[test]
        fn relaxing_only_the_moves_ahead_gives_the_same_bidirectional_search_event_for_event(
            query in weighted_queries(26),
            rule in 0usize..4,
            heuristic in 0usize..4,
        ) {
            let Some((grid, s, t)) = query else { return Err(TestCaseError::reject("no free cell")) };
            let diagonal = RULES[rule];
            // Manhattan is consistent only without diagonal moves.
            let heuristic = if diagonal == Diagonal::Never && heuristic == 3 {
                Heuristic::Manhattan
            } else {
                [Heuristic::Octile, Heuristic::Zero, Heuristic::Euclidean, Heuristic::Chebyshev][heuristic]
            };
            let mut ahead = SearchLog::with_limit(usize::MAX);
            let mut all = SearchLog::with_limit(usize::MAX);
            let a = search_with::<_, true>(&grid, s, t, diagonal, heuristic, &mut ahead);
            let b = search_with::<_, false>(&grid, s, t, diagonal, heuristic, &mut all);
            prop_assert_eq!(a, b);
            prop_assert_eq!(ahead, all);
        }
    }

    const RULES: [Diagonal; 4] = [
        Diagonal::Never,
        Diagonal::NoCornerCutting,
        Diagonal::OneSideFree,
        Diagonal::Always,
    ];

    /// Seeded grids of 2 to `max_w − 1` columns and 2 to 19 rows (up to
    /// 45 % blocked, `random_grid`) with up to 12 cells weighted 2–9, and
    /// two of their free cells; `None` for a grid without a free cell.
    fn weighted_queries(max_w: u32) -> impl Strategy<Value = Option<(PlanGrid, GridPos, GridPos)>> {
        (
            (2..max_w, 2u32..20, 0u64..45, any::<u64>()),
            prop::collection::vec((0..max_w as usize, 0usize..20, 2u8..=9), 0..12),
            (any::<prop::sample::Index>(), any::<prop::sample::Index>()),
        )
            .prop_map(|((w, h, density, seed), heavy, ends)| {
                let mut grid = random_grid(w as usize, h as usize, density, seed);
                for (c, r, wt) in heavy {
                    grid.set_weight(c % w as usize, r % h as usize, wt);
                }
                let free: Vec<GridPos> = (0..h)
                    .flat_map(|y| (0..w).map(move |x| GridPos::new(x, y)))
                    .filter(|&p| grid.is_free(p.col as i64, p.row as i64))
                    .collect();
                if free.is_empty() {
                    return None;
                }
                Some((grid, *ends.0.get(&free), *ends.1.get(&free)))
            })
    }

    /// A seeded grid of `w × h` cells, about `density` of them blocked.
    fn random_grid(w: usize, h: usize, density: u64, seed: u64) -> PlanGrid {
        let mut state = seed.wrapping_mul(6364136223846793005).wrapping_add(1);
        let text = (0..h)
            .map(|_| {
                (0..w)
                    .map(|_| {
                        state = state
                            .wrapping_mul(6364136223846793005)
                            .wrapping_add(1442695040888963407);
                        if (state >> 33) % 100 < density {
                            '#'
                        } else {
                            '.'
                        }
                    })
                    .collect::<String>()
            })
            .collect::<Vec<_>>()
            .join("\n");
        PlanGrid::new(&OccupancyGrid::from_ascii(&text).unwrap(), false)
    }

    #[test]
    fn equals_astar_under_every_corner_rule_and_consistent_estimate() {
        let rules = [
            Diagonal::Never,
            Diagonal::NoCornerCutting,
            Diagonal::OneSideFree,
            Diagonal::Always,
        ];
        let mut compared = 0;
        for seed in 0..12 {
            let grid = random_grid(23, 17, 30, seed);
            let free: Vec<GridPos> = (0..17)
                .flat_map(|y| (0..23).map(move |x| GridPos::new(x, y)))
                .filter(|&p| grid.is_free(p.col as i64, p.row as i64))
                .collect();
            for (k, diagonal) in rules.into_iter().enumerate() {
                // Manhattan is consistent only without diagonal moves.
                let estimates: &[Heuristic] = if diagonal == Diagonal::Never {
                    &[Heuristic::Manhattan, Heuristic::Octile, Heuristic::Zero]
                } else {
                    &[
                        Heuristic::Octile,
                        Heuristic::Euclidean,
                        Heuristic::Chebyshev,
                        Heuristic::Zero,
                    ]
                };
                for &heuristic in estimates {
                    let astar = AStar::new(AStarConfig {
                        heuristic,
                        weight: 1.0,
                        diagonal,
                    })
                    .unwrap();
                    let bidir = BidirectionalAStar {
                        diagonal,
                        heuristic,
                    };
                    for q in 0..6 {
                        let s = free[(q * 37 + k * 11 + seed as usize) % free.len()];
                        let t = free[(q * 53 + k * 7 + 5) % free.len()];
                        match (astar.plan(&grid, s, t), bidir.plan(&grid, s, t)) {
                            (Ok(a), Ok(b)) => {
                                assert!(
                                    (a.cost - b.cost).abs() < 1e-9,
                                    "seed {seed} {diagonal:?} {heuristic:?} {s:?}->{t:?}: A* {} bidirectional {}",
                                    a.cost,
                                    b.cost
                                );
                                assert!(grid.path_is_free(&b.cells, diagonal));
                                assert_eq!((b.cells.first(), b.cells.last()), (Some(&s), Some(&t)));
                                compared += 1;
                            }
                            (Err(_), Err(_)) => {}
                            (a, b) => {
                                panic!("seed {seed} {diagonal:?} {s:?}->{t:?}: {a:?} vs {b:?}")
                            }
                        }
                    }
                }
            }
        }
        assert!(compared > 500, "only {compared} reachable queries");
    }

    #[test]
    fn meets_halfway_on_an_open_grid_expanding_about_the_path_only() {
        // Many equal-cost paths join the corners of an open grid; the two
        // searches must follow the same one and meet, not run past each
        // other along two sides of the parallelogram.
        let grid = PlanGrid::from_fn(60, 30, |_, _| true);
        for (s, t) in [
            (GridPos::new(0, 0), GridPos::new(59, 17)),
            (GridPos::new(3, 29), GridPos::new(50, 2)),
            (GridPos::new(59, 0), GridPos::new(10, 29)),
        ] {
            let a = AStar::default().plan(&grid, s, t).unwrap();
            let b = BidirectionalAStar::default().plan(&grid, s, t).unwrap();
            assert!((a.cost - b.cost).abs() < 1e-9);
            assert!(
                b.expanded <= b.cells.len() + 2,
                "{s:?}->{t:?}: {} expanded for a path of {} cells",
                b.expanded,
                b.cells.len()
            );
        }
    }
}
