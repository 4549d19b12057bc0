//! Jump Point Search (Harabor & Grastien 2011; no-corner-cutting rules and
//! block-based jumps of Harabor & Grastien 2014, "Improving Jump Point
//! Search"): optimal 8-connected paths with the same costs as A*, expanding
//! only jump points.
//!
//! This is *online* JPS: no preprocessing. Straight jumps scan 64 cells per
//! step over the bit-packed rows (horizontal) and columns (vertical) that
//! [`PlanGrid`] keeps beside its bitmap; diagonal jumps step cell by cell and
//! run the two straight scans at each step. Only the Moving AI move rule
//! ([`Diagonal::NoCornerCutting`]) is implemented; other rules are refused
//! with [`PlanError::InvalidConfig`] (use A* for them).
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

use super::search::{
    check_size, scan_backward, scan_forward, trivial_path, unit_path_cost, with_space, xy, Entry,
    Estimate, FixedHeuristic, LineBits, OctileEstimate, SearchSpace, ZeroEstimate, DIAG, G_MASK,
    OPEN, STRAIGHT,
};
use super::{Diagonal, GridPlanner, GridPos, Heuristic, Path, PlanError, PlanGrid};
use serde::{Deserialize, Serialize};

/// Jump Point Search settings.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default)]
pub struct JpsConfig {
    /// Distance estimate to the goal (cells); octile by default.
    pub heuristic: Heuristic,
    /// Diagonal rule; only [`Diagonal::NoCornerCutting`] (the default) is
    /// supported.
    pub diagonal: Diagonal,
}

impl Default for JpsConfig {
    fn default() -> Self {
        Self {
            heuristic: Heuristic::Octile,
            diagonal: Diagonal::NoCornerCutting,
        }
    }
}

/// The Jump Point Search grid planner.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Jps {
    config: JpsConfig,
}

impl Jps {
    /// A JPS planner; refuses diagonal rules other than no corner cutting.
    pub fn new(config: JpsConfig) -> Result<Self, PlanError> {
        if config.diagonal != Diagonal::NoCornerCutting {
            return Err(PlanError::InvalidConfig(format!(
                "jump point search supports only the no_corner_cutting diagonal rule, \
                 not {:?}; use A* for other move rules",
                config.diagonal
            )));
        }
        Ok(Self { config })
    }

    /// The settings this planner was built with.
    pub fn config(&self) -> &JpsConfig {
        &self.config
    }
}

impl GridPlanner for Jps {
    fn plan_recording(
        &self,
        grid: &PlanGrid,
        start: GridPos,
        goal: GridPos,
        expanded: Option<&mut Vec<GridPos>>,
    ) -> Result<Path, PlanError> {
        grid.check_endpoints(start, goal)?;
        check_size(grid)?;
        if start == goal {
            return Ok(trivial_path(start));
        }
        let heuristic = self.config.heuristic;
        with_space(|space| match heuristic {
            Heuristic::Octile => run(grid, start, goal, space, expanded, OctileEstimate),
            Heuristic::Zero => run(grid, start, goal, space, expanded, ZeroEstimate),
            h => run(
                grid,
                start,
                goal,
                space,
                expanded,
                FixedHeuristic::new(h, 1.0),
            ),
        })
    }
}

/// Read-only view of the grid for jumping.
struct Jumper<'a> {
    free: &'a [bool],
    lines: &'a LineBits,
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
        let (l, w) = (&self.lines.rows, self.lines.row_words);
        if dx > 0 {
            scan_forward(l, w, y, x, target)
        } else {
            scan_backward(l, w, y, x, target)
        }
    }

    /// Straight jump along the column from `(x, y)`: the jump point's row.
    #[inline(always)]
    fn vertical(&self, x: usize, y: usize, dy: isize) -> Option<usize> {
        let target = if x == self.gx { self.gy } else { usize::MAX };
        let (l, w) = (&self.lines.cols, self.lines.col_words);
        if dy > 0 {
            scan_forward(l, w, x, y, target)
        } else {
            scan_backward(l, w, x, y, target)
        }
    }

    /// Diagonal jump from `(x, y)`: the jump point's padded index and the
    /// number of diagonal steps. A cell is a jump point when it is the goal
    /// or a straight jump from it (along either component) finds one.
    #[inline]
    fn diagonal(&self, x: usize, y: usize, dx: isize, dy: isize) -> Option<(usize, usize)> {
        let (mut x, mut y) = (x, y);
        let mut i = y * self.stride + x;
        let step_x = dx;
        let step_y = dy * self.stride as isize;
        let mut n = 0usize;
        loop {
            let side_x = i.wrapping_add_signed(step_x);
            let side_y = i.wrapping_add_signed(step_y);
            let next = side_x.wrapping_add_signed(step_y);
            if !(self.free(side_x) && self.free(side_y) && self.free(next)) {
                return None;
            }
            i = next;
            x = x.wrapping_add_signed(dx);
            y = y.wrapping_add_signed(dy);
            n += 1;
            if i == self.t
                || self.horizontal(x, y, dx).is_some()
                || self.vertical(x, y, dy).is_some()
            {
                return Some((i, n));
            }
        }
    }
}

#[inline(always)]
fn sign(a: usize, b: usize) -> isize {
    (a > b) as isize - (a < b) as isize
}

fn run<E: Estimate>(
    grid: &PlanGrid,
    start: GridPos,
    goal: GridPos,
    space: &mut SearchSpace,
    mut record: Option<&mut Vec<GridPos>>,
    est: E,
) -> Result<Path, PlanError> {
    let stride = grid.stride();
    let s = grid.padded_index(start);
    let t = grid.padded_index(goal);
    let (gx, gy) = xy(t, stride);
    let jumper = Jumper {
        free: grid.padded(),
        lines: grid.lines(),
        stride,
        t,
        gx,
        gy,
    };
    space.reset(jumper.free.len(), true);
    let word = space.open_word(0);
    let SearchSpace {
        g: words,
        parent: parents,
        open,
        ..
    } = &mut *space;
    let (words, parents) = (words.as_mut_slice(), parents.as_mut_slice());

    if let (Some(w), Some(p)) = (words.get_mut(s), parents.get_mut(s)) {
        *w = word;
        *p = s as u32;
    }
    let (sx, sy) = xy(s, stride);
    open.push(Entry::new(est.h(sx.abs_diff(gx), sy.abs_diff(gy)), 0, s));

    let mut expanded = 0usize;
    while let Some(Entry { idx, .. }) = open.pop() {
        let i = idx as usize;
        let (Some(w), Some(&parent)) = (words.get_mut(i), parents.get(i)) else {
            continue;
        };
        if *w & OPEN == 0 {
            continue;
        }
        *w &= !OPEN;
        let g = *w & G_MASK;
        let parent = parent as usize;
        expanded += 1;
        if let Some(r) = record.as_deref_mut() {
            r.push(grid.pos_of(i));
        }
        if i == t {
            let cells = reconstruct(grid, parents, s, t);
            return Ok(Path {
                cost: unit_path_cost(&cells),
                cells,
                expanded,
            });
        }
        let (x, y) = xy(i, stride);
        let (px, py) = xy(parent, stride);
        let (dx, dy) = (sign(x, px), sign(y, py));

        // Directions to jump in: all eight from the start; otherwise the
        // natural ones plus those forced by an obstacle beside the move.
        let mut dirs = [(0isize, 0isize); 8];
        let mut nd = 0usize;
        let mut add = |d: (isize, isize)| {
            if let Some(slot) = dirs.get_mut(nd) {
                *slot = d;
                nd += 1;
            }
        };
        if i == s {
            for d in [
                (1, 0),
                (-1, 0),
                (0, 1),
                (0, -1),
                (1, 1),
                (1, -1),
                (-1, 1),
                (-1, -1),
            ] {
                add(d);
            }
        } else if dx != 0 && dy != 0 {
            add((dx, 0));
            add((0, dy));
            add((dx, dy));
        } else if dx != 0 {
            add((dx, 0));
            for side in [-1isize, 1] {
                let beside = i.wrapping_add_signed(side * stride as isize);
                if jumper.free(beside) && !jumper.free(beside.wrapping_add_signed(-dx)) {
                    add((0, side));
                    add((dx, side));
                }
            }
        } else {
            add((0, dy));
            for side in [-1isize, 1] {
                let beside = i.wrapping_add_signed(side);
                if jumper.free(beside)
                    && !jumper.free(beside.wrapping_add_signed(-dy * stride as isize))
                {
                    add((side, 0));
                    add((side, dy));
                }
            }
        }

        for &(ddx, ddy) in dirs.iter().take(nd) {
            let found = if ddy == 0 {
                jumper
                    .horizontal(x, y, ddx)
                    .map(|jx| (y * stride + jx, STRAIGHT * jx.abs_diff(x) as u64))
            } else if ddx == 0 {
                jumper
                    .vertical(x, y, ddy)
                    .map(|jy| (jy * stride + x, STRAIGHT * jy.abs_diff(y) as u64))
            } else {
                jumper
                    .diagonal(x, y, ddx, ddy)
                    .map(|(j, n)| (j, DIAG * n as u64))
            };
            let Some((j, cost)) = found else { continue };
            let ng = g + cost;
            let new = word | ng;
            if let (Some(old), Some(p)) = (words.get_mut(j), parents.get_mut(j)) {
                if *old > new {
                    *old = new;
                    *p = idx;
                    let (jx, jy) = xy(j, stride);
                    let h = est.h(jx.abs_diff(gx), jy.abs_diff(gy));
                    open.push(Entry::new(ng.saturating_add(h), ng, j));
                }
            }
        }
    }
    Err(PlanError::Unreachable { expanded })
}

/// Follows parent links from `t` to `s` and fills in the cells of every
/// straight or diagonal jump between consecutive jump points.
fn reconstruct(grid: &PlanGrid, parents: &[u32], s: usize, t: usize) -> Vec<GridPos> {
    let stride = grid.stride();
    let mut jump_points = vec![t];
    let mut i = t;
    // Parents form a tree rooted at `s`; the bound guards the walk anyway.
    while i != s && jump_points.len() <= parents.len() {
        match parents.get(i) {
            Some(&p) => i = p as usize,
            None => break,
        }
        jump_points.push(i);
    }
    let mut cells = vec![grid.pos_of(s)];
    for w in jump_points.windows(2).rev() {
        let (from, to) = (w[1], w[0]);
        let ((fx, fy), (tx, ty)) = (xy(from, stride), xy(to, stride));
        let (dx, dy) = (sign(tx, fx), sign(ty, fy));
        let steps = fx.abs_diff(tx).max(fy.abs_diff(ty));
        let (mut x, mut y) = (fx, fy);
        for _ in 0..steps {
            x = x.wrapping_add_signed(dx);
            y = y.wrapping_add_signed(dy);
            cells.push(grid.pos_of(y * stride + x));
        }
    }
    cells
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::global::astar::AStar;
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

    #[test]
    fn refuses_other_move_rules() {
        for diagonal in [Diagonal::Never, Diagonal::OneSideFree, Diagonal::Always] {
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
