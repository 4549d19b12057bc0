//! The benchmark peer: the `pathfinding` crate's A* with the same
//! 8-connected, no-corner-cutting successors and octile heuristic as ours,
//! over cell indices. Shared by `planlab bench grid` and the core's
//! criterion bench (included there by path), so both time the same peer.

use planlab_core::global::{GridPos, PlanGrid};

/// Fixed-point move costs (the crate needs an `Ord` cost): 1 and √2 scaled
/// so rounding stays far below the 1e-3 optimum tolerance.
const STRAIGHT: u64 = 1_000_000;
const DIAG: u64 = 1_414_214;

/// Cost in cells of pathfinding's A* path from `start` to `goal`, or `None`.
pub fn pathfinding_cost(grid: &PlanGrid, start: GridPos, goal: GridPos) -> Option<f64> {
    let w = grid.width() as u32;
    let (gc, gr) = (goal.col as i64, goal.row as i64);
    let goal_idx = goal.row * w + goal.col;
    let result = pathfinding::directed::astar::astar(
        &(start.row * w + start.col),
        |&i| {
            let (c, r) = ((i % w) as i64, (i / w) as i64);
            let mut out: Vec<(u32, u64)> = Vec::with_capacity(8);
            for (dc, dr) in [(1, 0), (-1, 0), (0, 1), (0, -1)] {
                if grid.is_free(c + dc, r + dr) {
                    out.push((((r + dr) as u32) * w + (c + dc) as u32, STRAIGHT));
                }
            }
            for (dc, dr) in [(1, 1), (1, -1), (-1, 1), (-1, -1)] {
                if grid.is_free(c + dc, r + dr)
                    && grid.is_free(c + dc, r)
                    && grid.is_free(c, r + dr)
                {
                    out.push((((r + dr) as u32) * w + (c + dc) as u32, DIAG));
                }
            }
            out
        },
        |&i| {
            let (c, r) = ((i % w) as i64, (i / w) as i64);
            let (dx, dy) = ((c - gc).unsigned_abs(), (r - gr).unsigned_abs());
            let (lo, hi) = (dx.min(dy), dx.max(dy));
            // Octile, rounded down so it stays admissible in fixed point.
            (hi - lo) * STRAIGHT + lo * (DIAG - 1)
        },
        |&i| i == goal_idx,
    );
    result.map(|(_, c)| c as f64 / STRAIGHT as f64)
}
