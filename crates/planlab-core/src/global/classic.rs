//! Textbook grid searches for teaching (docs/algorithms.md §grid): breadth-
//! first, greedy best-first, bidirectional A*, IDA*, Theta* and 4-connected
//! Jump Point Search. Each reports its events ([`super::events`]) and runs
//! on a [`PlanGrid`] with `f64` costs (1 per straight move, √2 per diagonal,
//! the Euclidean length for Theta*'s any-angle segments).
//!
//! They favour clarity over speed: the fast A* and JPS live in
//! [`super::astar`] and [`super::jps`]. Node tables are per thread, reused
//! across queries and invalidated by a generation stamp, so a query touches
//! only the cells it reaches.

use super::events::emit;
use super::{Diagonal, GridPos, Heuristic, Path, PlanError, PlanGrid, SearchEvent, SearchObserver};
use std::cell::RefCell;
use std::cmp::Ordering;
use std::collections::{BinaryHeap, VecDeque};

/// No parent.
const NONE: u32 = u32::MAX;

/// Most nodes IDA* expands (over all its iterations) before giving up with
/// [`PlanError::SearchLimit`]: IDA* keeps no open list, so on grids it
/// re-searches the same cells once per distinct f bound.
pub const IDA_STAR_MAX_EXPANSIONS: usize = 2_000_000;

/// Cells per page of a [`Nodes`] table.
const PAGE: usize = 256;

/// Search state of [`PAGE`] consecutive cells, valid for generation `gen`.
#[derive(Debug)]
struct Page {
    gen: u32,
    g: [f64; PAGE],
    parent: [u32; PAGE],
    /// Bit 0: seen this generation; bit 1: closed.
    flags: [u8; PAGE],
}

const SEEN: u8 = 1;
const CLOSED: u8 = 2;

/// Per-cell search state of one search direction, in pages allocated when
/// a search first reaches one of their cells and invalidated by a
/// generation stamp: memory and reset cost follow the cells a search
/// reaches, not the map's area (a search walled in after one expansion on
/// a 10⁸-cell map needs a few pages, not gigabytes).
#[derive(Debug, Default)]
pub(crate) struct Nodes {
    pages: Vec<Option<Box<Page>>>,
    cur: u32,
    cells: usize,
}

impl Nodes {
    /// Forgets the previous search, for a grid of `n` cells.
    pub fn reset(&mut self, n: usize) {
        self.cells = n;
        let want = n.div_ceil(PAGE);
        if self.pages.len() < want {
            self.pages.resize_with(want, || None);
        }
        self.cur = self.cur.wrapping_add(1);
        if self.cur == 0 {
            for p in self.pages.iter_mut().flatten() {
                p.gen = 0;
            }
            self.cur = 1;
        }
    }

    /// Cell `i`'s page when it holds this generation's state.
    #[inline]
    fn page(&self, i: usize) -> Option<&Page> {
        match self.pages.get(i / PAGE) {
            Some(Some(p)) if p.gen == self.cur => Some(p),
            _ => None,
        }
    }

    #[inline]
    fn flags(&self, i: usize) -> u8 {
        self.page(i).map_or(0, |p| p.flags[i % PAGE])
    }

    #[inline]
    pub fn seen(&self, i: usize) -> bool {
        self.flags(i) & SEEN != 0
    }

    /// Cost from this direction's root; infinite if unseen.
    #[inline]
    pub fn g(&self, i: usize) -> f64 {
        match self.page(i) {
            Some(p) if p.flags[i % PAGE] & SEEN != 0 => p.g[i % PAGE],
            _ => f64::INFINITY,
        }
    }

    /// The cell cell `i` was reached from, [`NONE`] for a root or an unseen
    /// cell.
    #[inline]
    pub fn parent(&self, i: usize) -> u32 {
        match self.page(i) {
            Some(p) if p.flags[i % PAGE] & SEEN != 0 => p.parent[i % PAGE],
            _ => NONE,
        }
    }

    #[inline]
    pub fn closed(&self, i: usize) -> bool {
        self.flags(i) == SEEN | CLOSED
    }

    /// Cell `i`'s page for writing, allocated or cleared for this
    /// generation as needed.
    #[inline]
    fn page_mut(&mut self, i: usize) -> &mut Page {
        let cur = self.cur;
        let slot = &mut self.pages[i / PAGE];
        let p = slot.get_or_insert_with(|| {
            Box::new(Page {
                gen: 0,
                g: [f64::INFINITY; PAGE],
                parent: [NONE; PAGE],
                flags: [0; PAGE],
            })
        });
        if p.gen != cur {
            p.gen = cur;
            p.flags = [0; PAGE];
        }
        p
    }

    /// Reaches cell `i` at cost `g` from `parent` (open, not closed).
    #[inline]
    pub fn set(&mut self, i: usize, g: f64, parent: u32) {
        let p = self.page_mut(i);
        let o = i % PAGE;
        p.g[o] = g;
        p.parent[o] = parent;
        p.flags[o] = SEEN;
    }

    /// Closes cell `i` (a cell already reached).
    #[inline]
    pub fn close(&mut self, i: usize) {
        self.page_mut(i).flags[i % PAGE] |= CLOSED;
    }

    /// The parent chain from `i` back to the root, root first.
    pub fn chain(&self, width: usize, i: usize) -> Vec<GridPos> {
        let mut out = vec![pos(width, i)];
        let mut c = i;
        // A chain longer than the table would be a cycle (a bug): stop.
        while self.parent(c) != NONE && out.len() <= self.cells {
            c = self.parent(c) as usize;
            out.push(pos(width, c));
        }
        out.reverse();
        out
    }
}

thread_local! {
    static NODES: RefCell<[Nodes; 2]> = RefCell::new([Nodes::default(), Nodes::default()]);
}

/// Runs `f` with this thread's two node tables, reset for `grid` (fresh ones
/// if they are in use).
fn with_nodes<R>(grid: &PlanGrid, f: impl FnOnce(&mut [Nodes; 2]) -> R) -> R {
    let n = grid.width() * grid.height();
    let run = |pair: &mut [Nodes; 2]| {
        pair.iter_mut().for_each(|t| t.reset(n));
        f(pair)
    };
    NODES.with(|cell| match cell.try_borrow_mut() {
        Ok(mut pair) => run(&mut pair),
        Err(_) => run(&mut [Nodes::default(), Nodes::default()]),
    })
}

#[inline]
pub(crate) fn pos(width: usize, i: usize) -> GridPos {
    GridPos::new((i % width) as u32, (i / width) as u32)
}

#[inline]
pub(crate) fn index(width: usize, p: GridPos) -> usize {
    p.row as usize * width + p.col as usize
}

/// The eight moves, straight ones first.
pub(crate) const MOVES: [(i64, i64); 8] = [
    (1, 0),
    (-1, 0),
    (0, 1),
    (0, -1),
    (1, 1),
    (1, -1),
    (-1, 1),
    (-1, -1),
];

/// Move `k` of [`MOVES`] from `p` if it is legal under `diagonal`: the
/// target cell and its cost.
#[inline]
pub(crate) fn step(
    grid: &PlanGrid,
    p: GridPos,
    k: usize,
    diagonal: Diagonal,
) -> Option<(GridPos, f64)> {
    let (dx, dy) = *MOVES.get(k)?;
    let (x, y) = (i64::from(p.col), i64::from(p.row));
    if !grid.is_free(x + dx, y + dy) {
        return None;
    }
    let q = GridPos::new((x + dx) as u32, (y + dy) as u32);
    // A move costs its length times the weight of the cell it enters.
    let w = f64::from(grid.weight(x + dx, y + dy));
    if dx == 0 || dy == 0 {
        return Some((q, w));
    }
    diagonal
        .allows(grid.is_free(x + dx, y), grid.is_free(x, y + dy))
        .then_some((q, std::f64::consts::SQRT_2 * w))
}

/// Calls `f` with each cell `q` from which a legal move leads into `p`, and
/// that move's cost (its length times the weight of `p`): the predecessors
/// a backward search relaxes. Moves are symmetric in legality, not in cost.
#[inline]
pub(crate) fn for_each_move_into(
    grid: &PlanGrid,
    p: GridPos,
    diagonal: Diagonal,
    mut f: impl FnMut(GridPos, f64),
) {
    let w = f64::from(grid.weight(i64::from(p.col), i64::from(p.row)));
    for_each_move(grid, p, diagonal, |q, _| {
        let len = if q.col != p.col && q.row != p.row {
            std::f64::consts::SQRT_2
        } else {
            1.0
        };
        f(q, len * w)
    });
}

/// Calls `f` with each legal move from `p`: target and cost.
#[inline]
pub(crate) fn for_each_move(
    grid: &PlanGrid,
    p: GridPos,
    diagonal: Diagonal,
    mut f: impl FnMut(GridPos, f64),
) {
    let n = if diagonal == Diagonal::Never { 4 } else { 8 };
    for k in 0..n {
        if let Some((q, c)) = step(grid, p, k, diagonal) {
            f(q, c);
        }
    }
}

/// `h` from `a` to `b`.
#[inline]
pub(crate) fn estimate(h: Heuristic, a: GridPos, b: GridPos) -> f64 {
    h.eval(
        f64::from(a.col) - f64::from(b.col),
        f64::from(a.row) - f64::from(b.row),
    )
}

/// Open-list entry: smallest `key` first, ties to the largest `g` (the
/// deepest node), then the lowest index, so runs are deterministic.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Entry {
    pub key: f64,
    pub g: f64,
    pub idx: usize,
}

impl PartialEq for Entry {
    fn eq(&self, o: &Self) -> bool {
        self.cmp(o) == Ordering::Equal
    }
}
impl Eq for Entry {}
impl PartialOrd for Entry {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Entry {
    fn cmp(&self, o: &Self) -> Ordering {
        // Reversed: BinaryHeap is a max-heap.
        o.key
            .total_cmp(&self.key)
            .then_with(|| self.g.total_cmp(&o.g))
            .then_with(|| o.idx.cmp(&self.idx))
    }
}

/// Checks the endpoints and answers `start == goal`; `None` means search.
fn prelude(grid: &PlanGrid, start: GridPos, goal: GridPos) -> Result<Option<Path>, PlanError> {
    grid.check_endpoints(start, goal)?;
    Ok((start == goal).then(|| Path {
        cells: vec![start],
        cost: 0.0,
        expanded: 0,
    }))
}

fn open_event(cell: GridPos, parent: Option<GridPos>, g: f64, h: f64) -> SearchEvent {
    SearchEvent::Open { cell, parent, g, h }
}

fn path_of(grid: &PlanGrid, cells: Vec<GridPos>, expanded: usize) -> Path {
    Path {
        cost: grid.path_cost(&cells),
        cells,
        expanded,
    }
}

/// How a [`BestFirst`] search orders its open list.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Order {
    /// First in, first out: breadth-first.
    Fifo,
    /// By the heuristic alone: greedy best-first.
    Greedy,
}

/// Breadth-first search or greedy best-first search: cells are reached once
/// (the first time), expanded once, never improved.
fn best_first<O: SearchObserver + ?Sized>(
    grid: &PlanGrid,
    (start, goal): (GridPos, GridPos),
    diagonal: Diagonal,
    heuristic: Heuristic,
    order: Order,
    obs: &mut O,
) -> Result<Path, PlanError> {
    if let Some(p) = prelude(grid, start, goal)? {
        return Ok(p);
    }
    let w = grid.width();
    with_nodes(grid, |[nodes, _]| {
        let h = |p: GridPos| match order {
            Order::Fifo => 0.0,
            Order::Greedy => estimate(heuristic, p, goal),
        };
        let mut fifo = VecDeque::new();
        let mut heap = BinaryHeap::new();
        let s = index(w, start);
        nodes.set(s, 0.0, NONE);
        fifo.push_back(s);
        heap.push(Entry {
            key: h(start),
            g: 0.0,
            idx: s,
        });
        emit(obs, || open_event(start, None, 0.0, h(start)));
        let mut expanded = 0;
        loop {
            let next = match order {
                Order::Fifo => fifo.pop_front(),
                Order::Greedy => heap.pop().map(|e| e.idx),
            };
            let Some(i) = next else {
                return Err(PlanError::Unreachable { expanded });
            };
            nodes.close(i);
            expanded += 1;
            let here = pos(w, i);
            emit(obs, || SearchEvent::Close { cell: here });
            if here == goal {
                return Ok(path_of(grid, nodes.chain(w, i), expanded));
            }
            let g = nodes.g(i);
            for_each_move(grid, here, diagonal, |q, c| {
                let j = index(w, q);
                if nodes.seen(j) {
                    return;
                }
                nodes.set(j, g + c, i as u32);
                let hq = h(q);
                match order {
                    Order::Fifo => fifo.push_back(j),
                    Order::Greedy => heap.push(Entry {
                        key: hq,
                        g: g + c,
                        idx: j,
                    }),
                }
                emit(obs, || open_event(q, Some(here), g + c, hq));
            });
        }
    })
}

/// Breadth-first search (Moore 1959): expands cells in order of the number
/// of moves from the start.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Bfs {
    /// Diagonal move rule.
    pub diagonal: Diagonal,
}

impl Bfs {
    /// The search, reporting its events to `obs`. Finds a path with the
    /// fewest moves: the shortest one on a 4-connected grid, not in general
    /// with diagonals (a diagonal counts as one move but costs √2).
    pub fn search<O: SearchObserver + ?Sized>(
        &self,
        grid: &PlanGrid,
        start: GridPos,
        goal: GridPos,
        obs: &mut O,
    ) -> Result<Path, PlanError> {
        let q = (start, goal);
        best_first(grid, q, self.diagonal, Heuristic::Zero, Order::Fifo, obs)
    }
}
super::grid_planner_via_search!(Bfs);

/// Greedy best-first search (Doran & Michie 1966): always expands the open
/// cell that looks closest to the goal, ignoring the cost so far.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Greedy {
    /// Diagonal move rule.
    pub diagonal: Diagonal,
    /// The estimate it follows.
    pub heuristic: Heuristic,
}

impl Greedy {
    /// The search, reporting its events to `obs`. Finds a path whenever one
    /// exists (every cell is expanded at most once), of no guaranteed length.
    pub fn search<O: SearchObserver + ?Sized>(
        &self,
        grid: &PlanGrid,
        start: GridPos,
        goal: GridPos,
        obs: &mut O,
    ) -> Result<Path, PlanError> {
        let q = (start, goal);
        best_first(grid, q, self.diagonal, self.heuristic, Order::Greedy, obs)
    }
}
super::grid_planner_via_search!(Greedy);

/// Bidirectional A* (Pohl 1971): one A* from the start towards the goal and
/// one from the goal towards the start, each ordered by the average
/// potential of Ikeda et al. (1994) so that both are consistent, with the
/// meeting test on every relaxation and expansion and the stopping rule of
/// Goldberg & Harrelson (2005): optimal with a consistent heuristic. It
/// runs on the fast planners' fixed-point search machinery
/// (`global::bidir`; docs/algorithms.md §classic).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct BidirectionalAStar {
    /// Diagonal move rule.
    pub diagonal: Diagonal,
    /// Estimate, towards the goal forwards and towards the start backwards.
    pub heuristic: Heuristic,
}

impl BidirectionalAStar {
    /// The search, reporting its events to `obs` (the backward search's
    /// parents point towards the goal).
    pub fn search<O: SearchObserver + ?Sized>(
        &self,
        grid: &PlanGrid,
        start: GridPos,
        goal: GridPos,
        obs: &mut O,
    ) -> Result<Path, PlanError> {
        super::bidir::search(grid, start, goal, self.diagonal, self.heuristic, obs)
    }
}
super::grid_planner_via_search!(BidirectionalAStar);

/// Iterative-deepening A* (Korf 1985): depth-first searches bounded by f,
/// each bound the smallest f that exceeded the last one. Optimal with an
/// admissible heuristic; keeps only the current path, so it re-expands
/// cells (a per-iteration table of the best g prunes repeated visits), and
/// gives up with [`PlanError::SearchLimit`] after
/// [`IDA_STAR_MAX_EXPANSIONS`] expansions.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct IdaStar {
    /// Diagonal move rule.
    pub diagonal: Diagonal,
    /// Estimate to the goal (admissible for an optimal path).
    pub heuristic: Heuristic,
}

impl IdaStar {
    /// The search, reporting its events to `obs`: an Open when a cell joins
    /// the current path, a Close when it is expanded (again on every
    /// iteration that reaches it).
    pub fn search<O: SearchObserver + ?Sized>(
        &self,
        grid: &PlanGrid,
        start: GridPos,
        goal: GridPos,
        obs: &mut O,
    ) -> Result<Path, PlanError> {
        self.search_limited(grid, (start, goal), IDA_STAR_MAX_EXPANSIONS, obs)
    }

    /// [`IdaStar::search`] with a chosen expansion limit.
    pub fn search_limited<O: SearchObserver + ?Sized>(
        &self,
        grid: &PlanGrid,
        (start, goal): (GridPos, GridPos),
        limit: usize,
        obs: &mut O,
    ) -> Result<Path, PlanError> {
        if let Some(p) = prelude(grid, start, goal)? {
            return Ok(p);
        }
        let w = grid.width();
        let moves = if self.diagonal == Diagonal::Never {
            4
        } else {
            8
        };
        let h = |p: GridPos| estimate(self.heuristic, p, goal);
        let tol = |b: f64| 1e-9 * b.max(1.0);
        with_nodes(grid, |[best, _]| {
            let mut bound = h(start);
            let mut expanded = 0usize;
            // The current path: (cell, g, next move to try).
            let mut stack: Vec<(GridPos, f64, usize)> = Vec::new();
            loop {
                best.reset(w * grid.height());
                best.set(index(w, start), 0.0, NONE);
                stack.clear();
                stack.push((start, 0.0, 0));
                emit(obs, || open_event(start, None, 0.0, h(start)));
                expanded += 1;
                emit(obs, || SearchEvent::Close { cell: start });
                let mut next = f64::INFINITY;
                while let Some(top) = stack.last_mut() {
                    if top.2 >= moves {
                        stack.pop();
                        continue;
                    }
                    let (here, g, k) = *top;
                    top.2 += 1;
                    let Some((q, c)) = step(grid, here, k, self.diagonal) else {
                        continue;
                    };
                    let (ng, hq) = (g + c, h(q));
                    if ng + hq > bound + tol(bound) {
                        next = next.min(ng + hq);
                        continue;
                    }
                    let j = index(w, q);
                    if best.g(j) <= ng + tol(ng) {
                        continue;
                    }
                    best.set(j, ng, index(w, here) as u32);
                    emit(obs, || open_event(q, Some(here), ng, hq));
                    if q == goal {
                        let mut cells: Vec<GridPos> = stack.iter().map(|f| f.0).collect();
                        cells.push(q);
                        return Ok(path_of(grid, cells, expanded));
                    }
                    if expanded >= limit {
                        return Err(PlanError::SearchLimit { expanded, limit });
                    }
                    expanded += 1;
                    emit(obs, || SearchEvent::Close { cell: q });
                    stack.push((q, ng, 0));
                }
                if !next.is_finite() {
                    return Err(PlanError::Unreachable { expanded });
                }
                bound = next;
            }
        })
    }
}
super::grid_planner_via_search!(IdaStar);

/// Basic Theta* (Nash, Daniel, Koenig & Felner 2007): A* whose cells may
/// take their parent's parent as their own when the straight segment between
/// them is free, so paths turn at any angle, not only at multiples of 45°.
/// The cost is the Euclidean length of that polyline: never more than the
/// 8-connected optimum, not always the true any-angle optimum.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct ThetaStar {
    /// Moves searched and the rule at exact corner crossings of a segment.
    pub diagonal: Diagonal,
}

impl ThetaStar {
    /// The search, reporting its events to `obs`, each line-of-sight test as
    /// a [`SearchEvent::Line`]. [`Path::cells`] are the turning points.
    pub fn search<O: SearchObserver + ?Sized>(
        &self,
        grid: &PlanGrid,
        start: GridPos,
        goal: GridPos,
        obs: &mut O,
    ) -> Result<Path, PlanError> {
        let w = grid.width();
        let diagonal = self.diagonal;
        // Each line-of-sight test costs up to the map's side, so a search
        // that must close every reachable cell to prove the goal
        // unreachable would cost cells × side (minutes on a 2000² open
        // map). A flood fill over the same moves, one bit a cell, settles
        // reachability first in one visit a cell.
        if prelude(grid, start, goal)?.is_none() && !reaches(grid, start, goal, diagonal) {
            return Err(PlanError::Unreachable { expanded: 0 });
        }
        let h = |p: GridPos| estimate(Heuristic::Euclidean, p, goal);
        let weighted = grid.is_weighted();
        let segment = |a: GridPos, b: GridPos| {
            if weighted {
                grid.segment_cost(a, b)
            } else {
                estimate(Heuristic::Euclidean, a, b)
            }
        };
        lowest_f_first(
            grid,
            (start, goal),
            h,
            obs,
            |_, chain| chain,
            |nodes, i, here, obs, offer| {
                let g = nodes.g(i);
                let grand = nodes.parent(i);
                for_each_move(grid, here, diagonal, |q, c| {
                    if nodes.closed(index(w, q)) {
                        return;
                    }
                    // Path 2: straight from the parent's parent, if visible.
                    let (mut par, mut ng) = (i, g + c);
                    if grand != NONE {
                        let gp = pos(w, grand as usize);
                        let clear = grid.segment_is_free(gp, q, diagonal);
                        emit(obs, || SearchEvent::Line {
                            from: gp,
                            to: q,
                            clear,
                        });
                        if clear {
                            // On weighted cells the straight segment pays
                            // the heaviest cell it enters, so it is taken
                            // only where that is no dearer (on a unit grid
                            // it never is).
                            let through = nodes.g(grand as usize) + segment(gp, q);
                            if !weighted || through <= ng {
                                (par, ng) = (grand as usize, through);
                            }
                        }
                    }
                    offer.push((q, ng, par));
                });
            },
        )
    }
}
super::grid_planner_via_search!(ThetaStar);

/// Whether `goal` can be reached from `start` by the moves `diagonal`
/// allows (a depth-first flood over free cells, one bit of memory a cell,
/// allocated zeroed so untouched pages cost nothing).
fn reaches(grid: &PlanGrid, start: GridPos, goal: GridPos, diagonal: Diagonal) -> bool {
    let w = grid.width();
    let mut seen = vec![0u64; (w * grid.height()).div_ceil(64)];
    let mark = |seen: &mut [u64], i: usize| {
        let (word, bit) = (i / 64, 1u64 << (i % 64));
        let fresh = seen[word] & bit == 0;
        seen[word] |= bit;
        fresh
    };
    mark(&mut seen, index(w, start));
    let mut stack = vec![start];
    while let Some(p) = stack.pop() {
        if p == goal {
            return true;
        }
        for_each_move(grid, p, diagonal, |q, _| {
            if mark(&mut seen, index(w, q)) {
                stack.push(q);
            }
        });
    }
    false
}

/// Jump Point Search on a 4-connected grid (the canonical-ordering rules of
/// PathFinding.js's `JPFNeverMoveDiagonally`, after Harabor & Grastien
/// 2011): horizontal jumps stop where a cell above or below opens up behind
/// an obstacle; vertical jumps also stop where a horizontal jump would find
/// a jump point. Optimal 4-connected paths; [`Path::cells`] lists every cell.
pub(crate) fn jps4<O: SearchObserver + ?Sized>(
    grid: &PlanGrid,
    start: GridPos,
    goal: GridPos,
    heuristic: Heuristic,
    obs: &mut O,
) -> Result<Path, PlanError> {
    let w = grid.width();
    let h = |p: GridPos| estimate(heuristic, p, goal);
    lowest_f_first(
        grid,
        (start, goal),
        h,
        obs,
        // The jump points, joined by the straight runs between them.
        |start, points| {
            let mut cells = vec![start];
            for pair in points.windows(2) {
                fill_straight(&mut cells, pair[0], pair[1]);
            }
            cells
        },
        |nodes, i, here, obs, offer| {
            let g = nodes.g(i);
            let dirs: &[(i64, i64)] = match nodes.parent(i) {
                NONE => &[(1, 0), (-1, 0), (0, 1), (0, -1)],
                p => {
                    let from = pos(w, p as usize);
                    let dx = (i64::from(here.col) - i64::from(from.col)).signum();
                    let dy = (i64::from(here.row) - i64::from(from.row)).signum();
                    if dx != 0 {
                        &[(dx, 0), (0, 1), (0, -1)]
                    } else {
                        &[(0, dy), (1, 0), (-1, 0)]
                    }
                }
            };
            for &(dx, dy) in dirs {
                if let Some(q) = jump4(grid, here, (dx, dy), goal, obs) {
                    offer.push((q, g + estimate(Heuristic::Manhattan, here, q), i));
                }
            }
        },
    )
}

/// The best-first loop on f = g + h that Theta* and 4-connected JPS share:
/// open the start, take the lowest f, skip stale entries, close and report
/// it, stop at the goal (`finish(start, chain)` turns the parent chain into
/// the path's cells), else let `expand` offer successors as (cell, g,
/// parent index); an offer is taken when the cell is open or unseen and its
/// g improves.
fn lowest_f_first<O: SearchObserver + ?Sized>(
    grid: &PlanGrid,
    (start, goal): (GridPos, GridPos),
    h: impl Fn(GridPos) -> f64,
    obs: &mut O,
    finish: impl Fn(GridPos, Vec<GridPos>) -> Vec<GridPos>,
    mut expand: impl FnMut(&Nodes, usize, GridPos, &mut O, &mut Vec<(GridPos, f64, usize)>),
) -> Result<Path, PlanError> {
    if let Some(p) = prelude(grid, start, goal)? {
        return Ok(p);
    }
    let w = grid.width();
    with_nodes(grid, |[nodes, _]| {
        let mut heap = BinaryHeap::new();
        let s = index(w, start);
        nodes.set(s, 0.0, NONE);
        heap.push(Entry {
            key: h(start),
            g: 0.0,
            idx: s,
        });
        emit(obs, || open_event(start, None, 0.0, h(start)));
        let mut expanded = 0;
        let mut offers = Vec::new();
        while let Some(Entry { idx: i, g: ge, .. }) = heap.pop() {
            if nodes.closed(i) || ge > nodes.g(i) {
                continue;
            }
            nodes.close(i);
            expanded += 1;
            let here = pos(w, i);
            emit(obs, || SearchEvent::Close { cell: here });
            if here == goal {
                return Ok(path_of(grid, finish(start, nodes.chain(w, i)), expanded));
            }
            offers.clear();
            expand(nodes, i, here, obs, &mut offers);
            for &(q, ng, par) in &offers {
                let j = index(w, q);
                if nodes.closed(j) || ng >= nodes.g(j) {
                    continue;
                }
                nodes.set(j, ng, par as u32);
                heap.push(Entry {
                    key: ng + h(q),
                    g: ng,
                    idx: j,
                });
                emit(obs, || open_event(q, Some(pos(w, par)), ng, h(q)));
            }
        }
        Err(PlanError::Unreachable { expanded })
    })
}

/// Appends the cells after `a` up to `b` (on one row or column) to `cells`.
fn fill_straight(cells: &mut Vec<GridPos>, a: GridPos, b: GridPos) {
    let (mut x, mut y) = (i64::from(a.col), i64::from(a.row));
    let dx = (i64::from(b.col) - x).signum();
    let dy = (i64::from(b.row) - y).signum();
    while (x, y) != (i64::from(b.col), i64::from(b.row)) && (dx, dy) != (0, 0) {
        x += dx;
        y += dy;
        cells.push(GridPos::new(x as u32, y as u32));
    }
}

/// The 4-connected jump from `from` in direction `(dx, dy)`: the jump point
/// found, if any; reports the scan (and the horizontal scans a vertical
/// jump makes) as [`SearchEvent::Line`].
fn jump4<O: SearchObserver + ?Sized>(
    grid: &PlanGrid,
    from: GridPos,
    (dx, dy): (i64, i64),
    goal: GridPos,
    obs: &mut O,
) -> Option<GridPos> {
    let free = |x: i64, y: i64| grid.is_free(x, y);
    let (mut x, mut y) = (i64::from(from.col), i64::from(from.row));
    let at = |x: i64, y: i64| GridPos::new(x as u32, y as u32);
    let found = loop {
        if !free(x + dx, y + dy) {
            break None;
        }
        x += dx;
        y += dy;
        if at(x, y) == goal {
            break Some(at(x, y));
        }
        let forced = if dx != 0 {
            (free(x, y - 1) && !free(x - dx, y - 1)) || (free(x, y + 1) && !free(x - dx, y + 1))
        } else {
            (free(x - 1, y) && !free(x - 1, y - dy))
                || (free(x + 1, y) && !free(x + 1, y - dy))
                || jump4(grid, at(x, y), (1, 0), goal, obs).is_some()
                || jump4(grid, at(x, y), (-1, 0), goal, obs).is_some()
        };
        if forced {
            break Some(at(x, y));
        }
    };
    if at(x, y) != from {
        emit(obs, || SearchEvent::Line {
            from,
            to: at(x, y),
            clear: found.is_some(),
        });
    }
    found
}
