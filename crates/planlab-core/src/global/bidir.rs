//! Bidirectional A* on a [`PlanGrid`] (docs/algorithms.md §classic), the
//! search behind [`super::classic::BidirectionalAStar`].
//!
//! Two searches, one from the start and one from the goal, each a plain A*
//! over the machinery of [`super::astar`]: fixed-point integer costs, one
//! search word per cell and direction behind a generation tag
//! ([`PairSpace`]), the radix queue for consistent estimates.
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
//! The direction expanded next is the one with the smaller least key (on
//! a tie, the other one than last time), which grows the two searches
//! evenly in reduced cost.

use super::astar::{diagonal_ok, ALWAYS, NEVER, NO_CORNER_CUTTING, ONE_SIDE_FREE};
use super::events::emit;
use super::search::{
    cells, check_size, dir_index, improves, trivial_path, unit_path_cost, with_pair_space, xy,
    Estimate, FixedHeuristic, OctileEstimate, OpenList, PairSpace, ZeroEstimate, DIAG, DIRS,
    G_MASK, G_SHIFT, OPEN, STRAIGHT,
};
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
    grid.check_endpoints(start, goal)?;
    check_size(grid)?;
    if start == goal {
        return Ok(trivial_path(start));
    }
    with_pair_space(|space| {
        let q = Query {
            grid,
            s: grid.padded_index(start),
            t: grid.padded_index(goal),
            space,
            obs,
        };
        match heuristic {
            Heuristic::Octile => by_rule(q, diagonal, OctileEstimate),
            Heuristic::Zero => by_rule(q, diagonal, ZeroEstimate),
            h => by_rule(q, diagonal, FixedHeuristic::new(h, 1.0)),
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

fn by_rule<E: Estimate, O: SearchObserver + ?Sized>(
    q: Query<'_, O>,
    diagonal: Diagonal,
    est: E,
) -> Result<Path, PlanError> {
    match diagonal {
        Diagonal::Never => run::<E, NEVER, O>(q, est),
        Diagonal::NoCornerCutting => run::<E, NO_CORNER_CUTTING, O>(q, est),
        Diagonal::OneSideFree => run::<E, ONE_SIDE_FREE, O>(q, est),
        Diagonal::Always => run::<E, ALWAYS, O>(q, est),
    }
}

fn run<E: Estimate, const RULE: u8, O: SearchObserver + ?Sized>(
    q: Query<'_, O>,
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
        radix,
        binary,
        ..
    } = &mut *space;
    let (meet, expanded) = match (E::MONOTONE, grid.is_weighted()) {
        (true, false) => Bidir::new(grid, (s, t), words, radix, tag, est, obs).run::<RULE, false>(),
        (true, true) => Bidir::new(grid, (s, t), words, radix, tag, est, obs).run::<RULE, true>(),
        (false, false) => {
            Bidir::new(grid, (s, t), words, binary, tag, est, obs).run::<RULE, false>()
        }
        (false, true) => Bidir::new(grid, (s, t), words, binary, tag, est, obs).run::<RULE, true>(),
    };
    let Some(m) = meet else {
        return Err(PlanError::Unreachable { expanded });
    };
    // Start … m along the forward parents, then m … goal along the
    // backward ones. The chains cannot fail (every parent is a closed cell
    // whose g is final); an empty path would be a bug.
    let cells = match (chain(grid, space, 0, s, m), chain(grid, space, 1, t, m)) {
        (Some(mut cells), Some(back)) => {
            cells.extend(back.into_iter().rev().skip(1));
            cells
        }
        _ => Vec::new(),
    };
    Ok(Path {
        cost: if grid.is_weighted() {
            grid.path_cost(&cells)
        } else {
            unit_path_cost(&cells)
        },
        cells,
        expanded,
    })
}

/// The cells from `root` to `m` along direction `side`'s arrival moves,
/// root first; `None` if the words are inconsistent (never, barring a bug).
fn chain(
    grid: &PlanGrid,
    space: &PairSpace,
    side: usize,
    root: usize,
    m: usize,
) -> Option<Vec<GridPos>> {
    let stride = grid.stride() as isize;
    let mut out = vec![grid.pos_of(m)];
    let mut c = m;
    while c != root {
        let (_, dir) = space.reached(side, c)?;
        let (dx, dy) = DIRS.get(dir as usize).copied()?;
        c = c.checked_add_signed(-(dy * stride + dx))?;
        out.push(grid.pos_of(c));
        // A chain longer than the grid would be a cycle.
        if out.len() > space.words.len() {
            return None;
        }
    }
    out.reverse();
    Some(out)
}

/// The state of one bidirectional search. Direction 0 searches forwards
/// from the start, 1 backwards from the goal.
struct Bidir<'a, E, Q, O: ?Sized> {
    grid: &'a PlanGrid,
    free: &'a [bool],
    weights: &'a [u8],
    stride: usize,
    words: &'a mut [[u64; 2]],
    open: &'a mut [Q; 2],
    /// Open word of cost 0 of this search (tag | OPEN).
    tag: u64,
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
    meet: Option<usize>,
}

impl<'a, E: Estimate, Q: OpenList, O: SearchObserver + ?Sized> Bidir<'a, E, Q, O> {
    #[allow(clippy::too_many_arguments)]
    fn new(
        grid: &'a PlanGrid,
        (s, t): (usize, usize),
        words: &'a mut [[u64; 2]],
        open: &'a mut [Q; 2],
        tag: u64,
        est: E,
        obs: &'a mut O,
    ) -> Self {
        let stride = grid.stride();
        let ends = [xy(s, stride), xy(t, stride)];
        let span = est.h(ends[0].0.abs_diff(ends[1].0), ends[0].1.abs_diff(ends[1].1));
        Self {
            grid,
            free: grid.padded(),
            weights: grid.padded_weights().unwrap_or(&[]),
            stride,
            words,
            open,
            tag: tag | OPEN,
            est,
            obs,
            roots: [s, t],
            ends,
            off: span + 1,
            mu: u64::MAX,
            meet: None,
        }
    }

    /// Estimate from padded `(x, y)` to end `k` (0 start, 1 goal).
    #[inline(always)]
    fn h_to(&self, k: usize, x: usize, y: usize) -> u64 {
        let (ex, ey) = self.ends[k];
        self.est.h(x.abs_diff(ex), y.abs_diff(ey))
    }

    /// Direction `SIDE`'s key of `(x, y)` reached at cost `g`, and the
    /// estimate towards the other end (what the Open event reports).
    #[inline(always)]
    fn key<const SIDE: usize>(&self, x: usize, y: usize, g: u64) -> (u64, u64) {
        let towards = self.h_to(1 - SIDE, x, y);
        let back = self.h_to(SIDE, x, y);
        ((2 * g + towards + self.off).saturating_sub(back), towards)
    }

    /// Whether `word` (of either direction) belongs to this search.
    #[inline(always)]
    fn current(&self, word: u64) -> bool {
        PairSpace::current(self.tag, word)
    }

    /// Lowers μ to `g` plus the other direction's cost in `other`, if that
    /// word is this search's and the sum is cheaper.
    #[inline(always)]
    fn meet_at(&mut self, idx: usize, g: u64, other: u64) {
        if self.current(other) {
            let through = g + ((other >> G_SHIFT) & G_MASK);
            if through < self.mu {
                self.mu = through;
                self.meet = Some(idx);
            }
        }
    }

    /// The search: the meeting cell (`None`: no path) and the cells
    /// expanded. `WEIGHTED`: a move costs its length times the weight of the
    /// cell it enters (backwards: of the cell expanded).
    fn run<const RULE: u8, const WEIGHTED: bool>(mut self) -> (Option<usize>, usize) {
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
        let mut side = 1;
        // Until one direction has reached every cell it can (μ is then the
        // optimum, or there is no path) or the stop rule holds.
        while let (Some(kf), Some(kb)) = (self.open[0].min_key(), self.open[1].min_key()) {
            if self.mu != u64::MAX && kf + kb >= 2 * (self.mu + self.off) {
                break;
            }
            side = match kf.cmp(&kb) {
                std::cmp::Ordering::Less => 0,
                std::cmp::Ordering::Greater => 1,
                std::cmp::Ordering::Equal => 1 - side,
            };
            let Some(i) = self.open[side].pop() else {
                break;
            };
            let done = if side == 0 {
                self.expand::<0, RULE, WEIGHTED>(i)
            } else {
                self.expand::<1, RULE, WEIGHTED>(i)
            };
            expanded += usize::from(done);
        }
        (self.meet, expanded)
    }

    /// Expands cell `i` in direction `SIDE` unless it is a stale entry;
    /// whether it was expanded.
    #[inline(always)]
    fn expand<const SIDE: usize, const RULE: u8, const WEIGHTED: bool>(
        &mut self,
        i: usize,
    ) -> bool {
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
        let g = (w >> G_SHIFT) & G_MASK;
        self.meet_at(i, g, other);
        let grid = self.grid;
        emit(self.obs, || SearchEvent::Close {
            cell: grid.pos_of(i),
        });
        let stride = self.stride;
        let free = self.free;
        let is_free = |j: usize| free.get(j).copied().unwrap_or(false);
        let (x, y) = xy(i, stride);
        // Free cells are interior, so these never wrap; a wrapped index
        // would simply read as blocked.
        let up = i.wrapping_sub(stride);
        let down = i + stride;
        let n = is_free(up);
        let so = is_free(down);
        let we = is_free(i.wrapping_sub(1));
        let e = is_free(i + 1);
        let weights = self.weights;
        let weight = |j: usize| weights.get(j).map_or(1, |&w| u64::from(w));
        // Backwards, the move runs from the neighbour into `i`: `i` pays.
        let here_weight = if WEIGHTED && SIDE == 1 { weight(i) } else { 1 };

        macro_rules! relax {
            ($j:expr, $nx:expr, $ny:expr, $cost:expr, $dir:expr) => {{
                let j: usize = $j;
                let ng = if WEIGHTED {
                    let w = if SIDE == 0 { weight(j) } else { here_weight };
                    g + $cost * w
                } else {
                    g + $cost
                };
                let new = self.tag | ng << G_SHIFT | $dir;
                if let Some(pair) = self.words.get_mut(j) {
                    if improves(pair[SIDE], new) {
                        pair[SIDE] = new;
                        let other = pair[1 - SIDE];
                        self.meet_at(j, ng, other);
                        let (nx, ny) = ($nx, $ny);
                        let (key, towards) = self.key::<SIDE>(nx, ny, ng);
                        self.open[SIDE].push(key, ng, j);
                        let est = self.est;
                        emit(self.obs, || SearchEvent::Open {
                            cell: grid.pos_of(j),
                            parent: Some(grid.pos_of(i)),
                            g: cells(ng),
                            h: est.unweighted_cells(towards),
                        });
                    }
                }
            }};
        }

        if n {
            relax!(up, x, y - 1, STRAIGHT, dir_index(0, -1));
        }
        if so {
            relax!(down, x, y + 1, STRAIGHT, dir_index(0, 1));
        }
        if we {
            relax!(i - 1, x - 1, y, STRAIGHT, dir_index(-1, 0));
        }
        if e {
            relax!(i + 1, x + 1, y, STRAIGHT, dir_index(1, 0));
        }
        if RULE != NEVER {
            if diagonal_ok::<RULE>(n, we, is_free(up.wrapping_sub(1))) {
                relax!(up - 1, x - 1, y - 1, DIAG, dir_index(-1, -1));
            }
            if diagonal_ok::<RULE>(n, e, is_free(up.wrapping_add(1))) {
                relax!(up + 1, x + 1, y - 1, DIAG, dir_index(1, -1));
            }
            if diagonal_ok::<RULE>(so, we, is_free(down - 1)) {
                relax!(down - 1, x - 1, y + 1, DIAG, dir_index(-1, 1));
            }
            if diagonal_ok::<RULE>(so, e, is_free(down + 1)) {
                relax!(down + 1, x + 1, y + 1, DIAG, dir_index(1, 1));
            }
        }
        true
    }
}
