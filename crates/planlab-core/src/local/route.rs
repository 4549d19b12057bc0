//! Global guidance shared by the fusion planners: a grid path from the
//! robot to the goal on the inflated static map (A* or safe A*), reduced to
//! the waypoints the local planner steers to one after another — key points
//! (\[T\] §3.2.1), Bottom-Up feature nodes (\[S\] §4.1) or every path node.

use crate::global::plan::{plan_grid_for, plan_on_map, GridPlanError, GridPlanOptions};
use crate::global::{GridPos, PlanGrid};
use crate::num::hypot;
use crate::world::StaticMap;

use super::LocalError;

/// Which nodes of the grid path become waypoints.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Waypoints {
    /// Key points of \[T\] §3.2.1 (needs `options.keypoints`).
    KeyPoints,
    /// Bottom-Up feature nodes of \[S\] §4.1 (needs `options.bottom_up_eps`).
    FeatureNodes,
    /// Every node of the path.
    PathNodes,
}

/// A global route in world metres.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Route {
    /// The grid path through cell centres, start to goal.
    pub path: Vec<[f64; 2]>,
    /// Waypoints after the start; the last is the exact goal.
    pub waypoints: Vec<[f64; 2]>,
    /// Number of nodes of the grid path.
    pub path_nodes: usize,
}

/// Nearest cell to `p` that `grid` has free, searching rings of growing
/// size up to `max_ring` cells; `p` itself when it is free. Each ring walks
/// only its border, and no ring goes past the grid's larger side (beyond
/// it every cell is off the grid), so the work is bounded by the map, not
/// by `max_ring`.
pub(crate) fn snap(grid: &PlanGrid, p: GridPos, max_ring: i64) -> Option<GridPos> {
    if grid.is_free(p.col as i64, p.row as i64) {
        return Some(p);
    }
    let (c0, r0) = (p.col as i64, p.row as i64);
    let span = grid.width().max(grid.height()) as i64;
    for ring in 1..=max_ring.min(span) {
        let mut best: Option<(i64, GridPos)> = None;
        let mut visit = |dc: i64, dr: i64| {
            let (c, r) = (c0 + dc, r0 + dr);
            if c >= 0 && r >= 0 && grid.is_free(c, r) {
                let d2 = dc * dc + dr * dr;
                // Fixed scan order (rows, then columns) breaks ties
                // deterministically.
                if best.map_or(true, |(b, _)| d2 < b) {
                    best = Some((d2, GridPos::new(c as u32, r as u32)));
                }
            }
        };
        for dr in -ring..=ring {
            if dr.abs() == ring {
                for dc in -ring..=ring {
                    visit(dc, dr);
                }
            } else {
                visit(-ring, dr);
                visit(ring, dr);
            }
        }
        if let Some((_, q)) = best {
            return Some(q);
        }
    }
    None
}

/// Plans a route from `start` to `goal` (world metres) on `map` as
/// `options` say. A start or goal that inflation swallowed (the robot next
/// to a wall) is moved to the nearest free cell within twice the inflation
/// radius. Errors: [`LocalError::NoGlobalPath`] naming why.
pub fn plan_route(
    map: &StaticMap,
    start: [f64; 2],
    goal: [f64; 2],
    options: &GridPlanOptions,
    which: Waypoints,
) -> Result<Route, LocalError> {
    let grid = map.grid();
    let no_path = |m: String| LocalError::NoGlobalPath(m);
    let cell = |p: [f64; 2], what: &str| {
        grid.world_to_cell(p[0], p[1])
            .map(|(c, r)| GridPos::new(c as u32, r as u32))
            .ok_or_else(|| {
                no_path(format!(
                    "the {what} ({:.3}, {:.3}) m is off the map",
                    p[0], p[1]
                ))
            })
    };
    let (s, g) = (cell(start, "start")?, cell(goal, "goal")?);
    let plan_grid = plan_grid_for(grid, options).map_err(|e| no_path(e.to_string()))?;
    let ring = ((2.0 * options.inflate_m / grid.resolution()).ceil() as i64).max(2);
    let s = snap(&plan_grid, s, ring)
        .ok_or_else(|| no_path("no free cell near the start on the inflated map".into()))?;
    let g = snap(&plan_grid, g, ring)
        .ok_or_else(|| no_path("no free cell near the goal on the inflated map".into()))?;
    let plan = plan_on_map(grid, s, g, options).map_err(|e| match e {
        GridPlanError::Plan(p) => no_path(p.to_string()),
        other => no_path(other.to_string()),
    })?;
    let world = |p: &GridPos| {
        let (x, y) = grid.cell_to_world(p.col as usize, p.row as usize);
        [x, y]
    };
    let path: Vec<[f64; 2]> = plan.path.cells.iter().map(world).collect();
    let nodes: Vec<[f64; 2]> = match which {
        Waypoints::KeyPoints => plan.keypoints.iter().map(world).collect(),
        Waypoints::FeatureNodes => plan.feature_nodes.iter().map(world).collect(),
        Waypoints::PathNodes => path.clone(),
    };
    let mut waypoints: Vec<[f64; 2]> = nodes.into_iter().skip(1).collect();
    match waypoints.last_mut() {
        Some(last) => *last = goal,
        None => waypoints.push(goal),
    }
    Ok(Route {
        path_nodes: path.len(),
        path,
        waypoints,
    })
}

/// Distance between two points, m.
#[inline]
pub(crate) fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    hypot(a[0] - b[0], a[1] - b[1])
}

#[cfg(test)]
mod tests {
    use super::super::testkit;
    use super::*;

    /// The nearest free cell by scanning every ring's whole square (the
    /// reference the border walk must agree with, ties included).
    fn snap_by_squares(grid: &PlanGrid, p: GridPos, max_ring: i64) -> Option<GridPos> {
        if grid.is_free(p.col as i64, p.row as i64) {
            return Some(p);
        }
        let (c0, r0) = (p.col as i64, p.row as i64);
        for ring in 1..=max_ring {
            let mut best: Option<(i64, GridPos)> = None;
            for dr in -ring..=ring {
                for dc in -ring..=ring {
                    let (c, r) = (c0 + dc, r0 + dr);
                    let on_border = dr.abs() == ring || dc.abs() == ring;
                    if on_border && c >= 0 && r >= 0 && grid.is_free(c, r) {
                        let d2 = dc * dc + dr * dr;
                        if best.map_or(true, |(b, _)| d2 < b) {
                            best = Some((d2, GridPos::new(c as u32, r as u32)));
                        }
                    }
                }
            }
            if let Some((_, q)) = best {
                return Some(q);
            }
        }
        None
    }

    #[test]
    fn snap_walks_ring_borders_and_agrees_with_the_square_scan_ties_included() {
        // Free cells on a sparse lattice: many equidistant candidates.
        let grid = PlanGrid::from_fn(23, 17, |c, r| (c * 7 + r * 3) % 11 == 0);
        for c in 0..23u32 {
            for r in 0..17u32 {
                let p = GridPos::new(c, r);
                assert_eq!(snap(&grid, p, 30), snap_by_squares(&grid, p, 30), "{p:?}");
            }
        }
    }

    #[test]
    fn snap_with_a_huge_ring_on_a_blocked_map_stops_at_the_map_edge() {
        // An inflation of 10⁶ m makes the ring 10⁸ cells: the search must be
        // bounded by the map, not by the ring (it once scanned every ring's
        // whole square: cubic, and never ended).
        let grid = PlanGrid::from_fn(40, 30, |_, _| false);
        assert_eq!(snap(&grid, GridPos::new(5, 5), 100_000_000), None);
        let grid = PlanGrid::from_fn(40, 30, |c, r| c == 39 && r == 29);
        assert_eq!(
            snap(&grid, GridPos::new(0, 0), 100_000_000),
            Some(GridPos::new(39, 29))
        );
    }

    #[test]
    fn key_points_route_around_a_wall_and_end_at_the_exact_goal() {
        let map = testkit::map(
            "..........\n..........\n....#.....\n....#.....\n....#.....\n..........\n",
            0.5,
        );
        let opts = GridPlanOptions {
            inflate_m: 0.3,
            keypoints: true,
            ..Default::default()
        };
        let r = plan_route(&map, [0.75, 1.75], [4.6, 1.7], &opts, Waypoints::KeyPoints).unwrap();
        assert_eq!(*r.waypoints.last().unwrap(), [4.6, 1.7]);
        assert!(r.waypoints.len() >= 2, "{:?}", r.waypoints);
        assert!(r.path_nodes > r.waypoints.len());
        // Walled-off goal: a typed error.
        let map = testkit::map("..#..\n..#..\n..#..\n", 1.0);
        let e = plan_route(
            &map,
            [0.5, 0.5],
            [4.5, 0.5],
            &GridPlanOptions::default(),
            Waypoints::PathNodes,
        )
        .unwrap_err();
        assert!(matches!(e, LocalError::NoGlobalPath(_)), "{e}");
    }
}
