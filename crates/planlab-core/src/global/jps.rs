//! Jump Point Search (Harabor & Grastien 2011; no-corner-cutting rules and
//! block-based jumps of Harabor & Grastien 2014, "Improving Jump Point
//! Search"): optimal 8-connected paths with the same costs as A*, expanding
//! only jump points.
//!
//! This is *online* JPS: no preprocessing. Straight jumps scan 64 cells per
//! step over the bit-packed rows (horizontal) and columns (vertical) that
//! [`PlanGrid`] keeps beside its bitmap; diagonal jumps step cell by cell and
//! run the two straight scans at each step. Two move rules are implemented:
//! the Moving AI rule ([`Diagonal::NoCornerCutting`]), and 4-connected moves
//! ([`Diagonal::Never`], the cell-by-cell jumps of
//! [`super::classic`]); the corner-cutting rules are refused with
//! [`PlanError::InvalidConfig`] (use A* for them).
//!
//! [`Path::cells`] lists every cell: each jump is expanded into its
//! intermediate cells, so consecutive cells are one legal move apart.
//! [`Path::expanded`] counts jump points taken off the open list. Search
//! buffers are per thread and reused, as for [`super::astar::AStar`].
//!
//! ```
//! use planlab_core::global::{jps::Jps, GridPlanner, GridPos, PlanGrid};
//! use planlab_core::map::OccupancyGrid;
//! let map = OccupancyGrid::from_ascii("
//! ......
//! .####.
//! ......
//! ").unwrap();
//! let grid = PlanGrid::new(&map, false);
//! let path = Jps::default().plan(&grid, GridPos::new(0, 1), GridPos::new(5, 1)).unwrap();
//! assert_eq!(path.cells.len(), 8);
//! assert!((path.cost - 7.0).abs() < 1e-9);
//! ```

use super::classic::jps4;
use super::events::emit;
use super::jump_table::JumpTable;
use super::search::{
    cells, check_size, dir_index, finish, improves, trivial_path, with_space, xy, Estimate,
    FixedHeuristic, LineBits, OctileEstimate, OpenList, SearchSpace, DEFAULT_SPAN, DIAG, DIRS,
    DIR_MASK, G_MASK, G_SHIFT, OPEN, STRAIGHT,
};
use super::{Diagonal, GridPos, Heuristic, Path, PlanError, PlanGrid, SearchEvent, SearchObserver};
use serde::{Deserialize, Serialize};

/// Jump Point Search settings.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default)]
pub struct JpsConfig {
    /// Distance estimate to the goal (cells); octile by default.
    pub heuristic: Heuristic,
    /// Diagonal rule: [`Diagonal::NoCornerCutting`] (the default) or
    /// [`Diagonal::Never`].
    pub diagonal: Diagonal,
    /// JPS+: read jump distances from a table built on the grid's first
    /// such query and kept with it (dropped by an edit), instead of scanning
    /// (see `global/jump_table.rs`). The same jump points and paths; faster
    /// where many queries share a map. Only with
    /// [`Diagonal::NoCornerCutting`] and the octile heuristic (exact on an
    /// open 8-connected grid; one compiled search keeps the web modules
    /// small).
    pub preprocess: bool,
}

impl Default for JpsConfig {
    fn default() -> Self {
        Self {
            heuristic: Heuristic::Octile,
            diagonal: Diagonal::NoCornerCutting,
            preprocess: false,
        }
    }
}

/// The Jump Point Search grid planner.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Jps {
    config: JpsConfig,
}

impl Jps {
    /// A JPS planner for 8-connected moves without corner cutting or for
    /// 4-connected moves ([`Diagonal::Never`]); refuses the corner-cutting
    /// rules, whose forced-neighbour conditions differ.
    pub fn new(config: JpsConfig) -> Result<Self, PlanError> {
        if matches!(config.diagonal, Diagonal::OneSideFree | Diagonal::Always) {
            return Err(PlanError::InvalidConfig(format!(
                "jump point search supports the no_corner_cutting and never diagonal rules, \
                 not {:?}; use A* for moves that cut corners",
                config.diagonal
            )));
        }
        if config.preprocess && config.diagonal != Diagonal::NoCornerCutting {
            return Err(PlanError::InvalidConfig(format!(
                "the JPS+ jump table is built for the no_corner_cutting diagonal rule, not {:?}; \
                 use jps",
                config.diagonal
            )));
        }
        if config.preprocess && config.heuristic != Heuristic::Octile {
            return Err(PlanError::InvalidConfig(format!(
                "JPS+ searches with the octile heuristic, not {:?}; use jps for other estimates",
                config.heuristic
            )));
        }
        Ok(Self { config })
    }

    /// The settings this planner was built with.
    pub fn config(&self) -> &JpsConfig {
        &self.config
    }
}

super::grid_planner_via_search!(Jps);

impl Jps {
    /// The search, reporting its events to `obs` (`()`: none, at no cost):
    /// every expanded jump point, every jump point opened, and every jump
    /// scan as a [`SearchEvent::Line`].
    pub fn search<O: SearchObserver + ?Sized>(
        &self,
        grid: &PlanGrid,
        start: GridPos,
        goal: GridPos,
        obs: &mut O,
    ) -> Result<Path, PlanError> {
        // Pruning symmetric paths assumes they all cost the same; on
        // weighted cells they do not, and a silent fallback to A* would
        // show A*'s search under JPS's name.
        if grid.is_weighted() {
            return Err(PlanError::NeedsUniformCosts {
                planner: "jump point search",
            });
        }
        if self.config.diagonal == Diagonal::Never {
            return jps4(grid, start, goal, self.config.heuristic, obs);
        }
        grid.check_endpoints(start, goal)?;
        check_size(grid)?;
        if start == goal {
            return Ok(trivial_path(start));
        }
        let ends = (start, goal);
        let stride = grid.stride();
        if self.config.preprocess {
            JumpTable::check(grid)?;
            let table = grid.jump_table();
            let scans = AnyScans::Table(TableScans { table, stride });
            return with_space(|space| run(grid, ends, space, obs, OctileEstimate, scans));
        }
        let scans = AnyScans::Lines(LineScans {
            lines: grid.lines(),
            free: grid.padded(),
            stride,
        });
        // The octile estimate gets its own copy of the search (with the
        // bucket queue); every other one, the zero estimate included, shares
        // the general copy: a copy costs ~35 kB of every wasm module that
        // links the grid planners, and those estimates are for teaching, not
        // speed.
        with_space(|space| match self.config.heuristic {
            Heuristic::Octile => run(grid, ends, space, obs, OctileEstimate, scans),
            h => run(grid, ends, space, obs, FixedHeuristic::new(h, 1.0), scans),
        })
    }
}

const CORNERS: bool = true;
const MARK_EVERY: usize = 8;

/// Online JPS: scans over [`LineBits`], 64 cells a word.
struct LineScans<'a> {
    lines: &'a LineBits,
    free: &'a [bool],
    stride: usize,
}

impl LineScans<'_> {
    #[inline(always)]
    fn horizontal(&self, x: usize, y: usize, dx: isize, target: usize) -> Option<usize> {
        if dx > 0 {
            self.lines.rows.jump_forward(y, x, target)
        } else {
            self.lines.rows.jump_backward(y, x, target)
        }
    }

    #[inline(always)]
    fn vertical(&self, x: usize, y: usize, dy: isize, target: usize) -> Option<usize> {
        if dy > 0 {
            self.lines.cols.jump_forward(x, y, target)
        } else {
            self.lines.cols.jump_backward(x, y, target)
        }
    }

    #[inline(always)]
    fn diagonal_run<const DX: isize, const DY: isize>(
        &self,
        i: usize,
        _: usize,
        _: usize,
        _: (usize, usize),
    ) -> Result<usize, usize> {
        let free = |i: usize| self.free.get(i).copied().unwrap_or(false);
        let side_x = i.wrapping_add_signed(DX);
        let side_y = i.wrapping_add_signed(DY * self.stride as isize);
        if free(side_x) && free(side_y) && free(side_y.wrapping_add_signed(DX)) {
            Ok(1)
        } else {
            Err(0)
        }
    }
}

/// JPS+: the jump distances of a [`JumpTable`].
struct TableScans<'a> {
    table: &'a JumpTable,
    stride: usize,
}

impl TableScans<'_> {
    /// The straight jump from `pos` along a line towards `d` (±1) whose
    /// table entry is `e`, with the goal at `target` on that line.
    #[inline(always)]
    fn straight(pos: usize, d: isize, e: i16, target: usize) -> Option<usize> {
        let stop = pos.wrapping_add_signed(d * e.unsigned_abs() as isize);
        let before = if d > 0 {
            target > pos && target < stop
        } else {
            target < pos && target > stop
        };
        if before {
            Some(target)
        } else if e > 0 {
            Some(stop)
        } else {
            None
        }
    }

    #[inline(always)]
    fn horizontal(&self, x: usize, y: usize, dx: isize, target: usize) -> Option<usize> {
        let e = self.table.get(y * self.stride + x, (dx < 0) as usize);
        Self::straight(x, dx, e, target)
    }

    #[inline(always)]
    fn vertical(&self, x: usize, y: usize, dy: isize, target: usize) -> Option<usize> {
        let e = self.table.get(y * self.stride + x, 2 + (dy < 0) as usize);
        Self::straight(y, dy, e, target)
    }

    #[inline(always)]
    fn diagonal_run<const DX: isize, const DY: isize>(
        &self,
        i: usize,
        x: usize,
        y: usize,
        (gx, gy): (usize, usize),
    ) -> Result<usize, usize> {
        let e = self.table.get(i, dir_index(DX, DY) as usize);
        // Steps to the goal's column and row, if ahead (the straight scans
        // there see the goal, which the table leaves out).
        let ahead = |from: usize, to: usize, d: isize| {
            let k = if d > 0 {
                to.wrapping_sub(from)
            } else {
                from.wrapping_sub(to)
            };
            if k == 0 {
                usize::MAX
            } else {
                k
            }
        };
        let goal = ahead(x, gx, DX).min(ahead(y, gy, DY));
        let d = e.unsigned_abs() as usize;
        if e > 0 {
            Ok(d.min(goal))
        } else if goal < d {
            Ok(goal)
        } else {
            Err(d - 1)
        }
    }
}

/// How a search finds where jumps stop: by scanning the bit-packed lines
/// (online JPS, [`LineScans`]) or by reading the precomputed distances of
/// JPS+ ([`TableScans`]), chosen per query. Both stop at the same cells, so
/// the two searches expand the same jump points and return the same paths.
/// One search serves both (the branch is the same every call, so it
/// predicts perfectly): a second copy of the search for JPS+ added 20 kB to
/// every wasm module that links the grid planners.
enum AnyScans<'a> {
    Lines(LineScans<'a>),
    Table(TableScans<'a>),
}

impl AnyScans<'_> {
    /// Straight jump along row `y` from column `x` (towards `dx`): the
    /// column of the first jump point, or of `target` if it comes first;
    /// `None` when the jump runs into an obstacle.
    #[inline(always)]
    fn horizontal(&self, x: usize, y: usize, dx: isize, target: usize) -> Option<usize> {
        match self {
            Self::Lines(s) => s.horizontal(x, y, dx, target),
            Self::Table(s) => s.horizontal(x, y, dx, target),
        }
    }

    /// As [`AnyScans::horizontal`], along column `x` from row `y`.
    #[inline(always)]
    fn vertical(&self, x: usize, y: usize, dy: isize, target: usize) -> Option<usize> {
        match self {
            Self::Lines(s) => s.vertical(x, y, dy, target),
            Self::Table(s) => s.vertical(x, y, dy, target),
        }
    }

    /// Diagonal jump from padded cell `i` = `(x, y)` along `(DX, DY)`:
    /// `Ok(k)` when the `k`-th step (k ≥ 1) is a cell where the straight
    /// scans must run (it may be a jump point, or in the goal's row or
    /// column), `Err(k)` when the move after `k` free steps is illegal and
    /// nothing before it needs a look. One step at a time online; whole runs
    /// with the table.
    #[inline(always)]
    fn diagonal_run<const DX: isize, const DY: isize>(
        &self,
        i: usize,
        x: usize,
        y: usize,
        goal: (usize, usize),
    ) -> Result<usize, usize> {
        match self {
            Self::Lines(s) => s.diagonal_run::<DX, DY>(i, x, y, goal),
            Self::Table(s) => s.diagonal_run::<DX, DY>(i, x, y, goal),
        }
    }
}

/// Read-only view of the grid for jumping.
struct Jumper<'a> {
    free: &'a [bool],
    scans: AnyScans<'a>,
    stride: usize,
    /// Goal, padded index and coordinates.
    t: usize,
    gx: usize,
    gy: usize,
}

impl Jumper<'_> {
    #[inline(always)]
    fn free(&self, i: usize) -> bool {
        self.free.get(i).copied().unwrap_or(false)
    }

    /// Straight jump along the row from `(x, y)`: the jump point's column.
    #[inline(always)]
    fn horizontal(&self, x: usize, y: usize, dx: isize) -> Option<usize> {
        let target = if y == self.gy { self.gx } else { usize::MAX };
        self.scans.horizontal(x, y, dx, target)
    }

    /// Straight jump along the column from `(x, y)`: the jump point's row.
    #[inline(always)]
    fn vertical(&self, x: usize, y: usize, dy: isize) -> Option<usize> {
        let target = if x == self.gx { self.gy } else { usize::MAX };
        self.scans.vertical(x, y, dy, target)
    }
}

/// Map cell of a padded index (free cells are interior, so no wrap).
#[inline(always)]
fn padded_pos(i: usize, stride: usize) -> GridPos {
    let (x, y) = xy(i, stride);
    GridPos::new(x.wrapping_sub(1) as u32, y.wrapping_sub(1) as u32)
}

/// One search's mutable state.
struct Search<'a, E, Q, O: ?Sized> {
    jumper: Jumper<'a>,
    words: &'a mut [u64],
    open: &'a mut Q,
    /// Open word of cost 0 (see [`SearchSpace::open_word`]).
    tag: u64,
    est: E,
    /// `f` of the node being expanded.
    f_now: u64,
    obs: &'a mut O,
}

impl<E: Estimate, Q: OpenList, O: SearchObserver + ?Sized> Search<'_, E, Q, O> {
    /// Records cell `j` at `(jx, jy)` reached at cost `g` by a move in
    /// direction `dir` from the jump that started at padded cell `parent`,
    /// and opens it, if that improves on what it has.
    #[inline(always)]
    fn relax(&mut self, j: usize, jx: usize, jy: usize, g: u64, dir: u64, parent: usize) {
        let new = self.tag | g << G_SHIFT | dir;
        if let Some(old) = self.words.get_mut(j) {
            if improves(*old, new) {
                *old = new;
                let (gx, gy) = (self.jumper.gx, self.jumper.gy);
                let h = self.est.h(jx.abs_diff(gx), jy.abs_diff(gy));
                self.open.push(g.saturating_add(h), g, j);
                let stride = self.jumper.stride;
                emit(self.obs, || SearchEvent::Open {
                    cell: padded_pos(j, stride),
                    parent: Some(padded_pos(parent, stride)),
                    g: cells(g),
                    h: cells(h),
                });
            }
        }
    }

    /// Reports the straight scan from padded `(x, y)` along `(dx, dy)` that
    /// found `found` (a position along the line) or ran into an obstacle.
    #[inline(always)]
    fn scan_event(&mut self, x: usize, y: usize, dx: isize, dy: isize, found: Option<usize>) {
        if !self.obs.enabled() {
            return;
        }
        let stride = self.jumper.stride;
        let (tx, ty) = match found {
            Some(k) if dy == 0 => (k, y),
            Some(k) => (x, k),
            None => {
                // The last free cell before the obstacle.
                let (mut tx, mut ty) = (x, y);
                while self
                    .jumper
                    .free((ty.wrapping_add_signed(dy)) * stride + tx.wrapping_add_signed(dx))
                {
                    tx = tx.wrapping_add_signed(dx);
                    ty = ty.wrapping_add_signed(dy);
                }
                (tx, ty)
            }
        };
        self.obs.event(SearchEvent::Line {
            from: padded_pos(y * stride + x, stride),
            to: padded_pos(ty * stride + tx, stride),
            clear: found.is_some(),
        });
    }

    /// Reports a diagonal jump from padded cell `from` to `to`.
    #[inline(always)]
    fn diagonal_event(&mut self, from: usize, to: usize, clear: bool) {
        let stride = self.jumper.stride;
        if from != to {
            emit(self.obs, || SearchEvent::Line {
                from: padded_pos(from, stride),
                to: padded_pos(to, stride),
                clear,
            });
        }
    }

    /// Straight jump from `(x, y)` (cost `g`) in direction `(dx, dy)`, one of
    /// them 0; relaxes the jump point found.
    #[inline(always)]
    fn straight(&mut self, x: usize, y: usize, g: u64, dx: isize, dy: isize) {
        let stride = self.jumper.stride;
        let (mut x, mut y, mut g, mut dx, mut dy) = (x, y, g, dx, dy);
        let mut corners = 0usize;
        loop {
            let (j, jx, jy, jg) = if dy == 0 {
                let found = self.jumper.horizontal(x, y, dx);
                self.scan_event(x, y, dx, dy, found);
                let Some(jx) = found else {
                    return;
                };
                (y * stride + jx, jx, y, g + STRAIGHT * jx.abs_diff(x) as u64)
            } else {
                let found = self.jumper.vertical(x, y, dy);
                self.scan_event(x, y, dx, dy, found);
                let Some(jy) = found else {
                    return;
                };
                (jy * stride + x, x, jy, g + STRAIGHT * jy.abs_diff(y) as u64)
            };
            let dir = dir_index(dx, dy);
            if CORNERS && j != self.jumper.t {
                // A corridor corner (ahead blocked, one side open) has a
                // single successor, the jump along that side: follow it now
                // instead of queueing the corner.
                let (sx, sy) = (dy, dx); // a perpendicular
                let ahead = j.wrapping_add_signed(dy * stride as isize + dx);
                let side_a = j.wrapping_add_signed(sy * stride as isize + sx);
                let side_b = j.wrapping_add_signed(-(sy * stride as isize + sx));
                let (fa, fb) = (self.jumper.free(side_a), self.jumper.free(side_b));
                if !self.jumper.free(ahead) && fa != fb {
                    // Only every MARK_EVERY-th corner is recorded: the path is
                    // walked back through the others (see `walk_back`), and the
                    // records still stop a chain that comes round a loop.
                    corners += 1;
                    if corners % MARK_EVERY == 0 && !self.mark(j, jg, dir) {
                        return;
                    }
                    (x, y, g) = (jx, jy, jg);
                    (dx, dy) = if fa { (sx, sy) } else { (-sx, -sy) };
                    continue;
                }
            }
            self.relax(j, jx, jy, jg, dir, y * stride + x);
            return;
        }
    }

    /// Diagonal jump from `(x, y)` (cost `g`) in direction `(DX, DY)`.
    ///
    /// As in plain JPS, a cell of the jump from which a straight jump along
    /// either component finds a jump point is a jump point itself. Those
    /// straight jump points are relaxed right away, reusing the scans that
    /// found them (Harabor & Grastien's 2014 intermediate-point pruning).
    /// The cell itself would only continue the diagonal when expanded (see
    /// [`Search::expand`]); when it is no worse than the node being expanded
    /// (`f` ≤ `f_now`, the usual case heading towards the goal), the open
    /// list would hand it back next anyway, so the jump records it and goes
    /// on instead of queueing it. Otherwise it is queued and the jump ends.
    /// The jump also ends at the goal and at a blocked step. Monomorphised
    /// per direction: this is the innermost loop in open terrain.
    #[inline(always)]
    fn diagonal<const DX: isize, const DY: isize>(&mut self, x: usize, y: usize, g: u64) {
        let (stride, t) = (self.jumper.stride, self.jumper.t);
        let goal = (self.jumper.gx, self.jumper.gy);
        let step = DY * stride as isize + DX;
        let (mut x, mut y, mut n) = (x, y, 0u64);
        let from = y * stride + x;
        let mut i = from;
        loop {
            let k = match self.jumper.scans.diagonal_run::<DX, DY>(i, x, y, goal) {
                Ok(k) => k,
                Err(k) => {
                    let last = i.wrapping_add_signed(step * k as isize);
                    self.diagonal_event(from, last, false);
                    return;
                }
            };
            i = i.wrapping_add_signed(step * k as isize);
            x = x.wrapping_add_signed(DX * k as isize);
            y = y.wrapping_add_signed(DY * k as isize);
            n += k as u64;
            if i == t {
                break;
            }
            let h = self.jumper.horizontal(x, y, DX);
            self.scan_event(x, y, DX, 0, h);
            let v = self.jumper.vertical(x, y, DY);
            self.scan_event(x, y, 0, DY, v);
            if (h.is_some() || v.is_some())
                && !self.diagonal_hit::<DX, DY>(i, x, y, g + n * DIAG, h, v, from)
            {
                self.diagonal_event(from, i, true);
                return;
            }
        }
        self.diagonal_event(from, i, true);
        self.relax(i, x, y, g + n * DIAG, dir_index(DX, DY), from);
    }

    /// A jump point `i` = `(x, y)` (cost `g`) of a diagonal jump, where the
    /// straight jumps found `h` (a column) and/or `v` (a row): relaxes
    /// those, then records the cell and returns whether the jump goes on
    /// past it, or queues it and returns `false` (see [`Search::diagonal`]).
    /// `from`: where the diagonal jump started. Kept out of line so the
    /// sweep stays tight.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn diagonal_hit<const DX: isize, const DY: isize>(
        &mut self,
        i: usize,
        x: usize,
        y: usize,
        g: u64,
        h: Option<usize>,
        v: Option<usize>,
        from: usize,
    ) -> bool {
        let stride = self.jumper.stride;
        if let Some(jx) = h {
            let cost = STRAIGHT * jx.abs_diff(x) as u64;
            self.relax(y * stride + jx, jx, y, g + cost, dir_index(DX, 0), i);
        }
        if let Some(jy) = v {
            let cost = STRAIGHT * jy.abs_diff(y) as u64;
            self.relax(jy * stride + x, x, jy, g + cost, dir_index(0, DY), i);
        }
        let (gx, gy) = (self.jumper.gx, self.jumper.gy);
        let f = g.saturating_add(self.est.h(x.abs_diff(gx), y.abs_diff(gy)));
        if f <= self.f_now {
            // Stops, like a failed relax would, if the cell is already
            // reached as cheaply (or expanded).
            self.mark(i, g, dir_index(DX, DY))
        } else {
            self.relax(i, x, y, g, dir_index(DX, DY), from);
            false
        }
    }

    /// [`Search::diagonal`] for a direction known only at run time.
    #[inline]
    fn diagonal_to(&mut self, x: usize, y: usize, g: u64, dx: isize, dy: isize) {
        match (dx > 0, dy > 0) {
            (true, true) => self.diagonal::<1, 1>(x, y, g),
            (true, false) => self.diagonal::<1, -1>(x, y, g),
            (false, true) => self.diagonal::<-1, 1>(x, y, g),
            (false, false) => self.diagonal::<-1, -1>(x, y, g),
        }
    }

    /// Records cell `j` reached at cost `g` by a move in direction `dir`
    /// without queueing it, if that improves on what it has; whether it did.
    /// The cell stays marked open, so a cheaper route found later still
    /// queues it.
    #[inline(always)]
    fn mark(&mut self, j: usize, g: u64, dir: u64) -> bool {
        let new = self.tag | g << G_SHIFT | dir;
        match self.words.get_mut(j) {
            Some(old) if improves(*old, new) => {
                *old = new;
                true
            }
            _ => false,
        }
    }

    /// Generates the successors of cell `i` at `(x, y)`, reached at cost `g`
    /// by the move [`DIRS`]`[dir]`, or by none for the start (`dir ≥ 8`).
    #[inline]
    fn expand(&mut self, i: usize, x: usize, y: usize, g: u64, dir: u64) {
        match dir {
            0 => self.after_straight(i, x, y, g, 1, 0),
            1 => self.after_straight(i, x, y, g, -1, 0),
            2 => self.after_straight(i, x, y, g, 0, 1),
            3 => self.after_straight(i, x, y, g, 0, -1),
            // Reached diagonally: its straight successors were relaxed when
            // it was found (see `diagonal`); only the diagonal goes on. (No
            // forced neighbours after a diagonal move without corner cutting.)
            4 => self.diagonal::<1, 1>(x, y, g),
            5 => self.diagonal::<1, -1>(x, y, g),
            6 => self.diagonal::<-1, 1>(x, y, g),
            7 => self.diagonal::<-1, -1>(x, y, g),
            _ => {
                for (dx, dy) in DIRS.iter().take(4) {
                    self.straight(x, y, g, *dx, *dy);
                }
                self.diagonal::<1, 1>(x, y, g);
                self.diagonal::<1, -1>(x, y, g);
                self.diagonal::<-1, 1>(x, y, g);
                self.diagonal::<-1, -1>(x, y, g);
            }
        }
    }

    /// Successors after a straight move `(dx, dy)`: the jump ahead, and for
    /// each forced neighbour — a free cell beside this one whose counterpart
    /// beside the previous cell is blocked, so the parent could not reach it
    /// more directly — the jumps towards it and diagonally past it.
    #[inline]
    fn after_straight(&mut self, i: usize, x: usize, y: usize, g: u64, dx: isize, dy: isize) {
        let stride = self.jumper.stride as isize;
        self.straight(x, y, g, dx, dy);
        for side in [-1isize, 1] {
            let (sx, sy) = if dx != 0 { (0, side) } else { (side, 0) };
            let beside = i.wrapping_add_signed(sy * stride + sx);
            let behind = beside.wrapping_add_signed(-(dy * stride + dx));
            if self.jumper.free(beside) && !self.jumper.free(behind) {
                self.straight(x, y, g, sx, sy);
                // The diagonal past the forced neighbour needs the cell
                // ahead and the one beyond both free (no corner cutting);
                // in corridors it rarely has them, and a jump that cannot
                // take its first step reports nothing, so test before the
                // out-of-line call.
                let ahead = i.wrapping_add_signed(dy * stride + dx);
                if self.jumper.free(ahead)
                    && self
                        .jumper
                        .free(ahead.wrapping_add_signed(sy * stride + sx))
                {
                    self.diagonal_to(x, y, g, dx + sx, dy + sy);
                }
            }
        }
    }
}

fn run<E: Estimate, O: SearchObserver + ?Sized>(
    grid: &PlanGrid,
    (start, goal): (GridPos, GridPos),
    space: &mut SearchSpace,
    obs: &mut O,
    est: E,
    scans: AnyScans<'_>,
) -> Result<Path, PlanError> {
    // A jump raises f by up to twice its cost: a window of ~9 cells' moves
    // holds most of random512's jumps (4 × A*'s span measured fewest
    // instructions there); longer ones wait in the overflow heap.
    space.reset(grid.padded().len(), DEFAULT_SPAN * 4);
    let tag = space.open_word(0, 0);
    let (s, t) = (grid.padded_index(start), grid.padded_index(goal));
    let SearchSpace {
        words,
        buckets,
        binary,
        ..
    } = &mut *space;
    let q = Query {
        grid,
        s,
        t,
        words,
        tag,
        est,
    };
    let (reached, expanded) = if E::MONOTONE {
        search(q, buckets, obs, scans)
    } else {
        search(q, binary, obs, scans)
    };
    finish(grid, space, (s, t), reached, expanded)
}

/// One query's grid, padded start and goal, search words and their open
/// tag, and estimate.
struct Query<'a, E> {
    grid: &'a PlanGrid,
    s: usize,
    t: usize,
    words: &'a mut [u64],
    tag: u64,
    est: E,
}

/// The JPS loop: whether `t` was reached, and how many jump points were
/// expanded.
fn search<E: Estimate, Q: OpenList, O: SearchObserver + ?Sized>(
    q: Query<'_, E>,
    open: &mut Q,
    obs: &mut O,
    scans: AnyScans<'_>,
) -> (bool, usize) {
    let Query {
        grid,
        s,
        t,
        words,
        tag,
        est,
    } = q;
    let stride = grid.stride();
    let (gx, gy) = xy(t, stride);
    let mut search = Search {
        jumper: Jumper {
            free: grid.padded(),
            scans,
            stride,
            t,
            gx,
            gy,
        },
        words,
        open,
        tag,
        est,
        f_now: 0,
        obs,
    };
    if let Some(w) = search.words.get_mut(s) {
        *w = tag;
    }
    let (sx, sy) = xy(s, stride);
    let h0 = est.h(sx.abs_diff(gx), sy.abs_diff(gy));
    search.open.push(h0, 0, s);
    emit(search.obs, || SearchEvent::Open {
        cell: grid.pos_of(s),
        parent: None,
        g: 0.0,
        h: cells(h0),
    });

    let mut expanded = 0usize;
    while let Some(i) = search.open.pop() {
        let Some(w) = search.words.get_mut(i) else {
            continue;
        };
        if *w & OPEN == 0 {
            // Already expanded: a stale duplicate entry.
            continue;
        }
        *w &= !OPEN;
        let (g, dir) = ((*w >> G_SHIFT) & G_MASK, *w & DIR_MASK);
        expanded += 1;
        emit(search.obs, || SearchEvent::Close {
            cell: grid.pos_of(i),
        });
        if i == t {
            return (true, expanded);
        }
        let (x, y) = xy(i, stride);
        search.f_now = g.saturating_add(est.h(x.abs_diff(gx), y.abs_diff(gy)));
        search.expand(i, x, y, g, if i == s { 8 } else { dir });
    }
    (false, expanded)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::global::astar::AStar;
    use crate::global::GridPlanner;
    use crate::map::OccupancyGrid;

    fn grid(text: &str) -> PlanGrid {
        PlanGrid::new(&OccupancyGrid::from_ascii(text).unwrap(), false)
    }

    #[test]
    fn matches_astar_and_expands_fewer_nodes_in_the_open() {
        let text = (0..30)
            .map(|r| {
                (0..40)
                    .map(|c| if c == 20 && r > 3 { '#' } else { '.' })
                    .collect::<String>()
            })
            .collect::<Vec<_>>()
            .join("\n");
        let g = grid(&text);
        let (a, b) = (GridPos::new(2, 25), GridPos::new(37, 28));
        let jps = Jps::default().plan(&g, a, b).unwrap();
        let astar = AStar::default().plan(&g, a, b).unwrap();
        assert!((jps.cost - astar.cost).abs() < 1e-9);
        assert!(jps.expanded < astar.expanded / 4);
        assert!(g.path_is_free(&jps.cells, Diagonal::NoCornerCutting));
        assert!(jps
            .cells
            .windows(2)
            .all(|w| w[0].col.abs_diff(w[1].col) <= 1 && w[0].row.abs_diff(w[1].row) <= 1));
    }

    /// Random grids whose padded widths straddle the 64-cell words the
    /// straight scans read (width + 2 = 64, 65, 66, 67, 129, 131), with
    /// densities from open to cluttered, and queries including start =
    /// goal, goals beside the start and blocked goals: JPS costs what A*
    /// costs, with legal paths, and agrees on unreachable and blocked.
    #[test]
    fn costs_match_astar_on_grids_straddling_word_boundaries() {
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut rnd = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        let mut solved = 0;
        for (width, height) in [
            (62, 9),
            (63, 7),
            (64, 11),
            (65, 6),
            (127, 5),
            (129, 8),
            (5, 70),
        ] {
            for density in [0u64, 5, 15, 30, 45] {
                let grid = PlanGrid::from_fn(width, height, |_, _| rnd() % 100 >= density);
                let cell = |k: u64| {
                    GridPos::new(
                        (k % width as u64) as u32,
                        (k / width as u64 % height as u64) as u32,
                    )
                };
                for q in 0..40 {
                    let a = cell(rnd());
                    let b = match q % 4 {
                        0 => a,
                        1 => GridPos::new((a.col + 1).min(width as u32 - 1), a.row),
                        2 => GridPos::new(a.col, (a.row + 1).min(height as u32 - 1)),
                        _ => cell(rnd()),
                    };
                    let what = format!("{width}x{height} density {density}: {a:?} -> {b:?}");
                    match (
                        AStar::default().plan(&grid, a, b),
                        Jps::default().plan(&grid, a, b),
                    ) {
                        (Ok(x), Ok(y)) => {
                            assert!((x.cost - y.cost).abs() < 1e-9, "{what}: {x:?} {y:?}");
                            assert_eq!(y.cells.first(), Some(&a), "{what}");
                            assert_eq!(y.cells.last(), Some(&b), "{what}");
                            assert!(
                                grid.path_is_free(&y.cells, Diagonal::NoCornerCutting),
                                "{what}"
                            );
                            solved += 1;
                        }
                        // Same kind of error (expansion counts differ).
                        (Err(x), Err(y)) => assert_eq!(
                            std::mem::discriminant(&x),
                            std::mem::discriminant(&y),
                            "{what}: {x} / {y}"
                        ),
                        (x, y) => panic!("{what}: A* {x:?}, JPS {y:?}"),
                    }
                }
            }
        }
        assert!(solved > 500, "only {solved} queries had paths");
    }

    /// A random grid of `width × height` with `density` % blocked cells.
    fn random_grid(width: usize, height: usize, density: u64, seed: u64) -> PlanGrid {
        let mut state = seed | 1;
        PlanGrid::from_fn(width, height, |_, _| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state % 100 >= density
        })
    }

    /// Follows the online diagonal from padded cell `i` = `(x, y)` one step
    /// at a time to its first stop (a cell where a straight scan finds a jump
    /// point, or the goal's row or column) and checks that the table's run
    /// ends at the same step.
    fn check_diagonal<const DX: isize, const DY: isize>(
        online: &LineScans,
        table: &TableScans,
        (i, x, y): (usize, usize, usize),
        goal: (usize, usize),
    ) {
        let (mut j, mut cx, mut cy, mut k) = (i, x, y, 0usize);
        let expected = loop {
            if online.diagonal_run::<DX, DY>(j, cx, cy, goal).is_err() {
                break Err(k);
            }
            j = j.wrapping_add_signed(DY * online.stride as isize + DX);
            cx = cx.wrapping_add_signed(DX);
            cy = cy.wrapping_add_signed(DY);
            k += 1;
            if cx == goal.0
                || cy == goal.1
                || online.horizontal(cx, cy, DX, usize::MAX).is_some()
                || online.vertical(cx, cy, DY, usize::MAX).is_some()
            {
                break Ok(k);
            }
        };
        assert_eq!(
            table.diagonal_run::<DX, DY>(i, x, y, goal),
            expected,
            "diagonal ({DX}, {DY}) from ({x}, {y}) goal {goal:?}"
        );
    }

    /// Every straight scan and diagonal run read from the JPS+ table stops
    /// where the online scans over the bit-packed lines stop, from every
    /// free cell, in every direction, with the goal on the line ahead,
    /// behind or elsewhere; the open and sparse grids have jumps longer
    /// than one table step (127 cells), which chain.
    #[test]
    fn jump_table_stops_where_the_line_scans_stop() {
        for (width, height, density) in [
            (62, 9, 10),
            (63, 7, 30),
            (130, 6, 5),
            (7, 66, 20),
            (300, 5, 0),
            (300, 6, 1),
            (5, 300, 1),
            (140, 140, 0),
            (140, 140, 1),
        ] {
            let grid = random_grid(width, height, density, width as u64 * 31 + density);
            let stride = grid.stride();
            let online = LineScans {
                lines: grid.lines(),
                free: grid.padded(),
                stride,
            };
            let table = TableScans {
                table: &JumpTable::new(grid.padded(), stride),
                stride,
            };
            for (i, _) in grid.padded().iter().enumerate().filter(|(_, &f)| f) {
                let (x, y) = xy(i, stride);
                for target in [
                    usize::MAX,
                    0,
                    x.saturating_sub(3),
                    x + 2,
                    y + 1,
                    y.saturating_sub(2),
                ] {
                    for d in [-1isize, 1] {
                        let what = format!("{width}x{height} ({x}, {y}) d {d} target {target}");
                        assert_eq!(
                            online.horizontal(x, y, d, target),
                            table.horizontal(x, y, d, target),
                            "horizontal {what}"
                        );
                        assert_eq!(
                            online.vertical(x, y, d, target),
                            table.vertical(x, y, d, target),
                            "vertical {what}"
                        );
                    }
                }
                for goal in [
                    (stride + 9, 9999),
                    (x + 3, y + 5),
                    (x.saturating_sub(2), y + 2),
                ] {
                    let pos = (i, x, y);
                    check_diagonal::<1, 1>(&online, &table, pos, goal);
                    check_diagonal::<1, -1>(&online, &table, pos, goal);
                    check_diagonal::<-1, 1>(&online, &table, pos, goal);
                    check_diagonal::<-1, -1>(&online, &table, pos, goal);
                }
            }
        }
    }

    /// JPS+ expands the same jump points and returns the same paths as
    /// online JPS, on grids straddling the scans' 64-cell words, from open
    /// to cluttered, including after edits (which drop the table).
    #[test]
    fn jps_plus_finds_the_same_paths_and_expansions_as_jps_before_and_after_edits() {
        let plus = Jps::new(JpsConfig {
            preprocess: true,
            ..JpsConfig::default()
        })
        .unwrap();
        let mut compared = 0;
        for (width, height) in [(62, 9), (65, 6), (129, 8), (5, 70), (40, 40)] {
            for density in [0u64, 10, 25, 40] {
                let mut grid = random_grid(width, height, density, (width + 7 * height) as u64);
                let mut state = 0x2545_f491_4f6c_dd1du64;
                let mut rnd = move || {
                    state ^= state << 13;
                    state ^= state >> 7;
                    state ^= state << 17;
                    state
                };
                for q in 0..60 {
                    if q % 10 == 9 {
                        // An edit, so the next queries need a rebuilt table.
                        let (c, r) = (rnd() as usize % width, rnd() as usize % height);
                        let free = grid.is_free(c as i64, r as i64);
                        grid.set_free(c, r, !free);
                    }
                    let cell = |k: u64| {
                        GridPos::new((k % width as u64) as u32, (k / 7 % height as u64) as u32)
                    };
                    let (a, b) = (cell(rnd()), cell(rnd()));
                    let what =
                        format!("{width}x{height} density {density} query {q}: {a:?} -> {b:?}");
                    match (Jps::default().plan(&grid, a, b), plus.plan(&grid, a, b)) {
                        (Ok(x), Ok(y)) => {
                            assert_eq!(x.cells, y.cells, "{what}");
                            assert_eq!(x.expanded, y.expanded, "{what}");
                            assert!((x.cost - y.cost).abs() < 1e-12, "{what}");
                            compared += 1;
                        }
                        (Err(x), Err(y)) => assert_eq!(x.to_string(), y.to_string(), "{what}"),
                        (x, y) => panic!("{what}: JPS {x:?}, JPS+ {y:?}"),
                    }
                }
            }
        }
        assert!(compared > 400, "only {compared} queries had paths");
    }

    #[test]
    fn jps_plus_refuses_grids_too_large_for_its_table_and_other_move_rules() {
        let grid = PlanGrid::from_fn(2100, 2100, |_, _| true);
        let plus = Jps::new(JpsConfig {
            preprocess: true,
            ..JpsConfig::default()
        })
        .unwrap();
        let err = plus
            .plan(&grid, GridPos::new(0, 0), GridPos::new(2099, 2099))
            .unwrap_err();
        assert!(
            matches!(&err, PlanError::InvalidConfig(m) if m.contains("too large for the JPS+")),
            "{err}"
        );
        // Online JPS needs no table.
        assert!(Jps::default()
            .plan(&grid, GridPos::new(0, 0), GridPos::new(2099, 2099))
            .is_ok());
        let err = Jps::new(JpsConfig {
            preprocess: true,
            diagonal: Diagonal::Never,
            ..JpsConfig::default()
        })
        .unwrap_err();
        assert!(matches!(err, PlanError::InvalidConfig(m) if m.contains("no_corner_cutting")));
        let err = Jps::new(JpsConfig {
            preprocess: true,
            heuristic: Heuristic::Euclidean,
            ..JpsConfig::default()
        })
        .unwrap_err();
        assert!(matches!(err, PlanError::InvalidConfig(m) if m.contains("octile")));
    }

    #[test]
    fn refuses_other_move_rules() {
        for diagonal in [Diagonal::OneSideFree, Diagonal::Always] {
            let err = Jps::new(JpsConfig {
                diagonal,
                ..JpsConfig::default()
            })
            .unwrap_err();
            assert!(matches!(err, PlanError::InvalidConfig(_)));
        }
    }

    #[test]
    fn unreachable_goal_is_reported() {
        let g = grid(
            "
..#..
..#..
..#..
",
        );
        let err = Jps::default()
            .plan(&g, GridPos::new(0, 0), GridPos::new(4, 2))
            .unwrap_err();
        assert!(matches!(err, PlanError::Unreachable { .. }));
    }
}
