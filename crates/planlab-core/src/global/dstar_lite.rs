//! D* Lite (Koenig & Likhachev 2002, "D* Lite", AAAI; the optimised version
//! of their Figure 4): incremental replanning for a robot that discovers
//! obstacles while it moves.
//!
//! The search runs backwards, from the goal, keeping for every cell `g`
//! (its cost to the goal as last computed) and `rhs` (the one-step
//! lookahead `min over successors of c + g`). A cell is *consistent* when
//! `g = rhs`; the queue holds the inconsistent ones, keyed
//! `[min(g, rhs) + h(start, s) + km; min(g, rhs)]`. When a cell changes,
//! only the `rhs` of the cells whose moves it affects are recomputed, and
//! the next [`DStarLite::plan`] repairs just the region whose costs changed.
//! When the robot moves, `km` grows by `h(old start, new start)` instead of
//! re-keying the queue.
//!
//! ```
//! use planlab_core::global::dstar_lite::DStarLite;
//! use planlab_core::global::plan::GridPlanOptions;
//! use planlab_core::global::{GridPos, PlanGrid};
//! use planlab_core::map::OccupancyGrid;
//! let map = OccupancyGrid::from_ascii("
//! .......
//! .......
//! .......
//! ").unwrap();
//! let grid = PlanGrid::new(&map, false);
//! let (s, t) = (GridPos::new(0, 1), GridPos::new(6, 1));
//! let mut d = DStarLite::new(&grid, s, t, &GridPlanOptions::default()).unwrap();
//! assert_eq!(d.plan(&mut ()).unwrap().cost, 6.0);
//! d.set_blocked(GridPos::new(3, 0), true);
//! d.set_blocked(GridPos::new(3, 1), true);
//! let repaired = d.plan(&mut ()).unwrap();
//! assert!((repaired.cost - (4.0 + 2.0 * 2f64.sqrt())).abs() < 1e-9);
//! ```

use super::classic::{for_each_move, for_each_move_into, index, pos, MOVES};
use super::events::emit;
use super::plan::GridPlanOptions;
use super::{
    Diagonal, Endpoint, GridPos, Heuristic, Path, PlanError, PlanGrid, SearchEvent, SearchObserver,
};
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// A queue key `[k1; k2]`, compared lexicographically.
type Key = (f64, f64);

/// `a < b` lexicographically: the queue's order, and the stop test's (one
/// order for both: a tolerance in the stop test alone, tried before, let the
/// heap's top sort above a key the stop test counted as smaller, and a
/// repair stopped with a wrong g at the start). Keys are quantised
/// ([`quantise`]) so that `g + h` summed along different routes, equal but
/// for the last bits, compares equal in both.
fn key_less(a: Key, b: Key) -> bool {
    a.0 < b.0 || (a.0 == b.0 && a.1 < b.1)
}

/// `x` to the nearest multiple of 2⁻²⁰ (≈ 10⁻⁶): far above the rounding of
/// a sum of moves (≈ 10⁻¹² here), far below the smallest difference
/// between two different path costs on these grids (sums of 1 and √2 with
/// whole-number weights).
fn quantise(x: f64) -> f64 {
    const SCALE: f64 = (1u64 << 20) as f64;
    (x * SCALE).round() / SCALE
}

/// Queue entry; stale when its key is no longer the cell's queued key.
#[derive(Clone, Copy, Debug)]
struct Queued {
    key: Key,
    idx: usize,
}

impl PartialEq for Queued {
    fn eq(&self, o: &Self) -> bool {
        self.cmp(o) == Ordering::Equal
    }
}
impl Eq for Queued {}
impl PartialOrd for Queued {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Queued {
    fn cmp(&self, o: &Self) -> Ordering {
        // Reversed: BinaryHeap is a max-heap.
        o.key
            .0
            .total_cmp(&self.key.0)
            .then_with(|| o.key.1.total_cmp(&self.key.1))
            .then_with(|| o.idx.cmp(&self.idx))
    }
}

/// Cells per page of a [`Paged`] table.
const PAGE: usize = 256;

/// A per-cell table whose pages are allocated on the first write to one of
/// their cells; unwritten cells read as the default. D* Lite's state then
/// takes memory for the cells its searches reach, not for the whole map
/// (three dense tables were 4 GB on a legal 10⁸-cell map).
#[derive(Clone, Debug)]
struct Paged<T> {
    pages: Vec<Option<Box<[T]>>>,
    default: T,
    len: usize,
}

impl<T: Copy> Paged<T> {
    fn new(len: usize, default: T) -> Self {
        let mut pages = Vec::new();
        pages.resize_with(len.div_ceil(PAGE), || None);
        Self {
            pages,
            default,
            len,
        }
    }

    #[cfg(test)]
    fn len(&self) -> usize {
        self.len
    }
}

impl<T: Copy> std::ops::Index<usize> for Paged<T> {
    type Output = T;
    #[inline]
    fn index(&self, i: usize) -> &T {
        assert!(i < self.len, "cell {i} outside a table of {}", self.len);
        match &self.pages[i / PAGE] {
            Some(p) => &p[i % PAGE],
            None => &self.default,
        }
    }
}

impl<T: Copy> std::ops::IndexMut<usize> for Paged<T> {
    #[inline]
    fn index_mut(&mut self, i: usize) -> &mut T {
        assert!(i < self.len, "cell {i} outside a table of {}", self.len);
        let d = self.default;
        &mut self.pages[i / PAGE].get_or_insert_with(|| vec![d; PAGE].into_boxed_slice())[i % PAGE]
    }
}

/// Incremental shortest paths on a grid whose cells may change (module doc).
#[derive(Clone, Debug)]
pub struct DStarLite {
    /// The planner's own copy of the passability, edited by `set_blocked`.
    grid: PlanGrid,
    diagonal: Diagonal,
    heuristic: Heuristic,
    start: GridPos,
    goal: GridPos,
    /// Start when `km` was last updated.
    last: GridPos,
    km: f64,
    g: Paged<f64>,
    rhs: Paged<f64>,
    /// The key a cell is queued with, if it is queued.
    queued: Paged<Option<Key>>,
    queue: BinaryHeap<Queued>,
    /// Whether the goal's Open event was sent.
    announced: bool,
}

impl DStarLite {
    /// A planner for `start` → `goal` on a copy of `grid`, with the diagonal
    /// rule of `options` (octile estimate; Manhattan on 4-connected grids).
    pub fn new(
        grid: &PlanGrid,
        start: GridPos,
        goal: GridPos,
        options: &GridPlanOptions,
    ) -> Result<Self, PlanError> {
        grid.check_endpoints(start, goal)?;
        let n = grid.width() * grid.height();
        let heuristic = if options.diagonal == Diagonal::Never {
            Heuristic::Manhattan
        } else {
            Heuristic::Octile
        };
        let mut d = Self {
            grid: grid.clone(),
            diagonal: options.diagonal,
            heuristic,
            start,
            goal,
            last: start,
            km: 0.0,
            g: Paged::new(n, f64::INFINITY),
            rhs: Paged::new(n, f64::INFINITY),
            queued: Paged::new(n, None),
            queue: BinaryHeap::new(),
            announced: false,
        };
        let t = d.at(goal);
        d.rhs[t] = 0.0;
        let k = d.key(t);
        d.push(t, k);
        Ok(d)
    }

    fn at(&self, p: GridPos) -> usize {
        index(self.grid.width(), p)
    }

    fn h(&self, a: GridPos, b: GridPos) -> f64 {
        super::classic::estimate(self.heuristic, a, b)
    }

    fn key(&self, i: usize) -> Key {
        let m = self.g[i].min(self.rhs[i]);
        let p = pos(self.grid.width(), i);
        (quantise(m + self.h(self.start, p) + self.km), quantise(m))
    }

    fn push(&mut self, i: usize, key: Key) {
        self.queued[i] = Some(key);
        self.queue.push(Queued { key, idx: i });
    }

    /// The smallest live queue entry, dropping stale ones.
    fn top(&mut self) -> Option<Queued> {
        while let Some(&q) = self.queue.peek() {
            if self.queued[q.idx] == Some(q.key) {
                return Some(q);
            }
            self.queue.pop();
        }
        None
    }

    /// `min over successors s' of c(s, s') + g(s')`, and that successor.
    fn best_successor(&self, p: GridPos) -> (f64, Option<GridPos>) {
        let mut best = (f64::INFINITY, None);
        if !self.grid.is_free(i64::from(p.col), i64::from(p.row)) {
            return best;
        }
        for_each_move(&self.grid, p, self.diagonal, |q, c| {
            let v = c + self.g[self.at(q)];
            if v < best.0 {
                best = (v, Some(q));
            }
        });
        best
    }

    /// UpdateVertex: re-queues `i` if it is inconsistent, drops it if not.
    fn update<O: SearchObserver + ?Sized>(&mut self, i: usize, obs: &mut O) {
        if self.g[i] != self.rhs[i] {
            let k = self.key(i);
            self.push(i, k);
            let p = pos(self.grid.width(), i);
            emit(obs, || SearchEvent::Open {
                cell: p,
                parent: self.best_successor(p).1,
                g: self.rhs[i],
                h: self.h(self.start, p),
            });
        } else {
            self.queued[i] = None;
        }
    }

    /// Recomputes `rhs` of `i` from its successors (not for the goal).
    fn recompute_rhs(&mut self, i: usize) {
        let p = pos(self.grid.width(), i);
        if p != self.goal {
            self.rhs[i] = self.best_successor(p).0;
        }
    }

    /// Computes (or repairs) the shortest path; expanded = cells expanded by THIS call.
    pub fn plan(&mut self, obs: &mut impl SearchObserver) -> Result<Path, PlanError> {
        let w = self.grid.width();
        let s = self.at(self.start);
        let mut expanded = 0usize;
        if !self.announced {
            // The goal was queued by `new`, before anyone listened.
            self.announced = true;
            let (goal, h) = (self.goal, self.h(self.start, self.goal));
            emit(obs, || SearchEvent::Open {
                cell: goal,
                parent: None,
                g: 0.0,
                h,
            });
        }
        while let Some(top) = self.top() {
            // Until the start itself is consistent (Fig. 3's rule; stopping while
            // it is only overconsistent leaves g(start) unset for the next repair).
            if !(key_less(top.key, self.key(s)) || self.rhs[s] != self.g[s]) {
                break;
            }
            let u = top.idx;
            let k_new = self.key(u);
            if key_less(top.key, k_new) {
                self.push(u, k_new);
                continue;
            }
            expanded += 1;
            let up = pos(w, u);
            emit(obs, || SearchEvent::Close { cell: up });
            self.queued[u] = None;
            if self.g[u] > self.rhs[u] {
                // Overconsistent: settle it, and offer it to its predecessors
                // (moves are symmetric, so they are its neighbours).
                self.g[u] = self.rhs[u];
                let gu = self.g[u];
                let mut preds = Vec::with_capacity(8);
                // A move q → u costs the weight of u (moves are symmetric in
                // legality, not in cost).
                for_each_move_into(&self.grid, up, self.diagonal, |q, c| preds.push((q, c)));
                for (q, c) in preds {
                    let j = self.at(q);
                    if q != self.goal && c + gu < self.rhs[j] {
                        self.rhs[j] = c + gu;
                    }
                    self.update(j, obs);
                }
            } else {
                // Underconsistent: raise it, and let every cell that relied
                // on it look again.
                self.g[u] = f64::INFINITY;
                let mut preds = Vec::with_capacity(9);
                for_each_move(&self.grid, up, self.diagonal, |q, _| preds.push(q));
                preds.push(up);
                for q in preds {
                    let j = self.at(q);
                    self.recompute_rhs(j);
                    self.update(j, obs);
                }
            }
        }
        if !self.rhs[s].is_finite() {
            return Err(PlanError::Unreachable { expanded });
        }
        // Follow the cheapest successor from the start to the goal.
        let mut cells = vec![self.start];
        let mut cur = self.start;
        let limit = w * self.grid.height();
        while cur != self.goal {
            let (_, Some(next)) = self.best_successor(cur) else {
                return Err(PlanError::Unreachable { expanded });
            };
            cells.push(next);
            cur = next;
            if cells.len() > limit {
                // Cannot happen with consistent values; never loop forever.
                return Err(PlanError::Unreachable { expanded });
            }
        }
        Ok(Path {
            cost: self.grid.path_cost(&cells),
            cells,
            expanded,
        })
    }

    /// Changes one cell's traversal weight (1..=9); the next plan() repairs
    /// only what it affects: the moves into the cell, from its neighbours.
    pub fn set_weight(&mut self, cell: GridPos, weight: u8) {
        let (w, h) = (self.grid.width(), self.grid.height());
        if cell.col as usize >= w || cell.row as usize >= h {
            return;
        }
        let (x, y) = (i64::from(cell.col), i64::from(cell.row));
        if self.grid.weight(x, y) == u32::from(weight) {
            return;
        }
        self.grid
            .set_weight(cell.col as usize, cell.row as usize, weight);
        for (dx, dy) in MOVES {
            let (nx, ny) = (x + dx, y + dy);
            if nx >= 0 && ny >= 0 && (nx as usize) < w && (ny as usize) < h {
                let j = self.at(GridPos::new(nx as u32, ny as u32));
                self.recompute_rhs(j);
                self.update(j, &mut ());
            }
        }
    }

    /// Changes one cell (true = blocked); the next plan() repairs only what it affects.
    pub fn set_blocked(&mut self, cell: GridPos, blocked: bool) {
        let (w, h) = (self.grid.width(), self.grid.height());
        if cell.col as usize >= w || cell.row as usize >= h {
            return;
        }
        let (x, y) = (i64::from(cell.col), i64::from(cell.row));
        if self.grid.is_free(x, y) != blocked {
            return;
        }
        self.grid
            .set_free(cell.col as usize, cell.row as usize, !blocked);
        let i = self.at(cell);
        if blocked {
            self.g[i] = f64::INFINITY;
        }
        // The cell's own moves and every move into it or past its corner
        // start at the cell or one of its 8 neighbours.
        let mut touched = vec![cell];
        for (dx, dy) in MOVES {
            let (nx, ny) = (x + dx, y + dy);
            if nx >= 0 && ny >= 0 && (nx as usize) < w && (ny as usize) < h {
                touched.push(GridPos::new(nx as u32, ny as u32));
            }
        }
        for p in touched {
            let j = self.at(p);
            self.recompute_rhs(j);
            self.update(j, &mut ());
        }
    }

    /// The robot moved: the search start is now `cell` (km update of Koenig & Likhachev 2002).
    pub fn move_start(&mut self, cell: GridPos) -> Result<(), PlanError> {
        self.grid
            .check_endpoints(cell, self.goal)
            .map_err(|e| match e {
                PlanError::OffMap {
                    col,
                    row,
                    width,
                    height,
                    ..
                } => PlanError::OffMap {
                    which: Endpoint::Start,
                    col,
                    row,
                    width,
                    height,
                },
                e => e,
            })?;
        self.km += self.h(self.last, cell);
        self.last = cell;
        self.start = cell;
        Ok(())
    }

    /// The current start.
    pub fn start(&self) -> GridPos {
        self.start
    }

    /// Whether `cell` is passable in the planner's copy of the grid.
    pub fn is_free(&self, cell: GridPos) -> bool {
        self.grid.is_free(i64::from(cell.col), i64::from(cell.row))
    }
}

/// D* Lite as a one-shot [`super::GridPlanner`]: a backward search from the
/// goal, like A* run from the goal with the same estimate.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct DStarLitePlanner {
    /// Diagonal move rule.
    pub diagonal: Diagonal,
}

impl DStarLitePlanner {
    /// The search, reporting its events to `obs`.
    pub fn search<O: SearchObserver + ?Sized>(
        &self,
        grid: &PlanGrid,
        start: GridPos,
        goal: GridPos,
        obs: &mut O,
    ) -> Result<Path, PlanError> {
        let options = GridPlanOptions {
            diagonal: self.diagonal,
            ..GridPlanOptions::default()
        };
        let mut d = DStarLite::new(grid, start, goal, &options)?;
        let mut obs = obs;
        d.plan(&mut obs)
    }
}
super::grid_planner_via_search!(DStarLitePlanner);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::global::astar::AStar;
    use crate::global::GridPlanner;
    use crate::map::io::movingai::{parse_map, parse_scen};

    impl DStarLite {
        /// Every free cell's rhs is its one-step lookahead, and every
        /// inconsistent cell is queued with its current key or less.
        fn check(&self) -> Result<(), String> {
            let w = self.grid.width();
            for i in 0..self.g.len() {
                let p = pos(w, i);
                if p != self.goal {
                    let want = self.best_successor(p).0;
                    if want != self.rhs[i] {
                        return Err(format!("{p:?}: rhs {} but lookahead {want}", self.rhs[i]));
                    }
                }
                if self.g[i] != self.rhs[i] && self.queued[i].is_none() {
                    return Err(format!(
                        "{p:?}: g {} rhs {} not queued",
                        self.g[i], self.rhs[i]
                    ));
                }
            }
            Ok(())
        }
    }

    struct Rng(u64);
    impl Rng {
        fn below(&mut self, n: usize) -> usize {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            (self.0 % n as u64) as usize
        }
    }

    /// Random walls painted and erased and starts moved on arena2, under
    /// three move rules: after every edit and every plan the invariants
    /// hold, and every answer equals a fresh A*'s on the edited grid.
    #[test]
    fn invariants_hold_through_random_edits() {
        let dir = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../tests/data/movingai/dao/"
        );
        let map = parse_map(&std::fs::read_to_string(format!("{dir}arena2.map")).unwrap()).unwrap();
        let rows =
            parse_scen(&std::fs::read_to_string(format!("{dir}arena2.map.scen")).unwrap()).unwrap();
        let base = PlanGrid::new(&map, false);
        let mut rng = Rng(0x5eed_d57a);
        for (round, diagonal) in [Diagonal::NoCornerCutting, Diagonal::Never, Diagonal::Always]
            .into_iter()
            .cycle()
            .take(60)
            .enumerate()
        {
            let options = GridPlanOptions {
                diagonal,
                ..GridPlanOptions::default()
            };
            let astar = AStar::new(crate::global::astar::AStarConfig {
                diagonal,
                ..Default::default()
            })
            .unwrap();
            let mut grid = base.clone();
            let row = &rows[rng.below(rows.len())];
            let (mut s, t) = (row.start, row.goal);
            let mut d = DStarLite::new(&grid, s, t, &options).unwrap();
            let mut path = d.plan(&mut ()).unwrap().cells;
            d.check().unwrap();
            for step in 0..15 {
                let what = rng.below(4);
                match what {
                    // (The path may be an old one, walled over since: only onto free cells.)
                    0 if path.len() > 4 => {
                        let next = path[1 + rng.below(3)];
                        if grid.is_free(i64::from(next.col), i64::from(next.row)) {
                            s = next;
                            d.move_start(s).unwrap();
                        }
                    }
                    1 | 2 => {
                        let at = path[rng.below(path.len())];
                        let horizontal = rng.below(2) == 0;
                        for o in -3i64..=3 {
                            let (c, r) = if horizontal {
                                (at.col as i64 + o, at.row as i64)
                            } else {
                                (at.col as i64, at.row as i64 + o)
                            };
                            let q = GridPos::new(c.max(0) as u32, r.max(0) as u32);
                            if grid.is_free(c, r) && q != s && q != t {
                                grid.set_free(q.col as usize, q.row as usize, false);
                                d.set_blocked(q, true);
                            }
                        }
                    }
                    _ => {
                        for _ in 0..20 {
                            let (c, r) = (rng.below(grid.width()), rng.below(grid.height()));
                            if !grid.is_free(c as i64, r as i64) && base.is_free(c as i64, r as i64)
                            {
                                grid.set_free(c, r, true);
                                d.set_blocked(GridPos::new(c as u32, r as u32), false);
                            }
                        }
                    }
                }
                d.check()
                    .unwrap_or_else(|e| panic!("round {round} step {step} after edit {what}: {e}"));
                let fresh = astar.plan(&grid, s, t);
                let r = d.plan(&mut ());
                d.check()
                    .unwrap_or_else(|e| panic!("round {round} step {step} after plan: {e}"));
                match (fresh, r) {
                    (Ok(f), Ok(r)) => {
                        assert!(
                            (f.cost - r.cost).abs() < 1e-9 * f.cost.max(1.0),
                            "{diagonal:?} round {round} step {step}: A* {} D* Lite {}",
                            f.cost,
                            r.cost
                        );
                        path = r.cells;
                    }
                    (Err(_), Err(_)) => {}
                    (f, r) => panic!(
                        "{diagonal:?} round {round} step {step} edit {what}: A* {:?}, D* Lite {:?}",
                        f.map(|p| p.cost),
                        r.map(|p| p.cost)
                    ),
                }
            }
        }
    }
}
