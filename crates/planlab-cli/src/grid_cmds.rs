//! `planlab scen` and `planlab plan`.

use crate::load;
use planlab_core::car::hybrid_astar::{plan_hybrid_astar, HybridAStarConfig};
use planlab_core::car::{dubins, reeds_shepp, Pose};
use planlab_core::global::plan::{
    build_planner, plan_on_map, Algorithm, GridPlanError, GridPlanOptions,
};
use planlab_core::global::posthoc::{posthoc_trace, PosthocError, DEFAULT_EVENT_LIMIT};
use planlab_core::global::{GridPos, PlanError, PlanGrid};
use planlab_core::map::io::movingai;
use planlab_core::map::OccupancyGrid;
use planlab_core::sampling::shortcut::shortcut;
use planlab_core::sampling::{
    self, cell_centre, path_cost, Point, SamplingAlgorithm, SamplingError, SamplingOptions,
    SpaceError,
};
use serde_json::json;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Parses `C,R` into a cell.
pub fn parse_cell(s: &str) -> Result<GridPos, String> {
    let bad =
        || format!("invalid cell {s:?}: expected COLUMN,ROW with non-negative integers, e.g. 12,7");
    let (c, r) = s.split_once(',').ok_or_else(bad)?;
    let col = c.trim().parse::<u32>().map_err(|_| bad())?;
    let row = r.trim().parse::<u32>().map_err(|_| bad())?;
    Ok(GridPos::new(col, row))
}

fn within_tolerance(cost: f64, optimal: f64) -> bool {
    (cost - optimal).abs() <= 1e-3 * optimal.max(1.0)
}

/// Solves every row of a Moving AI scenario; returns the number of rows
/// whose cost misses the optimum (the caller turns > 0 into a failure).
pub fn scen(
    map_path: &Path,
    scen_path: &Path,
    algo: Algorithm,
    json: bool,
) -> Result<usize, String> {
    let grid = load::load_movingai(map_path)?;
    let rows = load::load_scen(scen_path)?;
    movingai::check_scen_against_map(&rows, &grid).map_err(|e| {
        format!(
            "{} does not fit {}: {e}",
            scen_path.display(),
            map_path.display()
        )
    })?;
    if algo == Algorithm::SafeAStar {
        return Err("safe-astar is not an optimal planner; scen checks optimal costs (use astar, dijkstra or jps)".into());
    }
    let options = GridPlanOptions {
        algorithm: algo,
        ..Default::default()
    };
    let planner = build_planner(&options).map_err(|e| e.to_string())?;
    let plan_grid = PlanGrid::new(&grid, false);
    let (mut mismatches, mut total_micros) = (0usize, 0f64);
    for (i, row) in rows.iter().enumerate() {
        let t = Instant::now();
        let result = planner.plan(&plan_grid, row.start, row.goal);
        let micros = t.elapsed().as_secs_f64() * 1e6;
        total_micros += micros;
        let (cost, expanded) = match &result {
            Ok(p) => (Some(p.cost), p.expanded),
            Err(_) => (None, 0),
        };
        let ok = cost.is_some_and(|c| within_tolerance(c, row.optimal));
        if !ok {
            mismatches += 1;
        }
        if json {
            outln!(
                "{}",
                json!({
                    "row": i,
                    "start": [row.start.col, row.start.row],
                    "goal": [row.goal.col, row.goal.row],
                    "optimal": row.optimal,
                    "cost": cost,
                    "expanded": expanded,
                    "micros": (micros * 1000.0).round() / 1000.0,
                })
            );
        } else if !ok {
            let got = match &result {
                Ok(p) => format!("{:.5}", p.cost),
                Err(e) => e.to_string(),
            };
            outln!(
                "row {i}: ({},{}) -> ({},{}) optimal {:.5}, got {got}",
                row.start.col,
                row.start.row,
                row.goal.col,
                row.goal.row,
                row.optimal
            );
        }
    }
    let mean = if rows.is_empty() {
        0.0
    } else {
        total_micros / rows.len() as f64
    };
    if json {
        outln!(
            "{}",
            json!({"rows": rows.len(), "mismatches": mismatches, "mean_micros": (mean * 1000.0).round() / 1000.0})
        );
    } else {
        outln!(
            "{}: {} rows solved with {}, {} mismatches, mean {:.1} µs per query",
            scen_path.display(),
            rows.len(),
            algo.name(),
            mismatches,
            mean
        );
    }
    Ok(mismatches)
}

/// Options of `planlab plan` beyond the map and endpoints.
pub struct PlanArgs {
    /// Start cell.
    pub start: GridPos,
    /// Goal cell.
    pub goal: GridPos,
    /// Planner options.
    pub options: GridPlanOptions,
    /// JSON output.
    pub json: bool,
    /// Also write the search as a Posthoc trace here.
    pub trace_posthoc: Option<PathBuf>,
}

/// Plans once on any supported map file and prints the result.
pub fn plan(map_path: &Path, grid: &OccupancyGrid, args: &PlanArgs) -> Result<(), String> {
    if let Some(out) = &args.trace_posthoc {
        crate::output::refuse_input("--trace-posthoc", out, &[map_path.to_path_buf()])?;
    }
    let say = |e: GridPlanError| {
        match e {
        // The core names its option; here it is a flag.
        GridPlanError::Plan(PlanError::UnknownCell { which, col, row }) => format!(
            "{which} ({col}, {row}) is an unknown cell, and unknown cells are blocked unless --allow-unknown is given"
        ),
        e => e.to_string(),
    }
    };
    let t = Instant::now();
    let result = plan_on_map(grid, args.start, args.goal, &args.options).map_err(say)?;
    let micros = t.elapsed().as_secs_f64() * 1e6;
    if let Some(out) = &args.trace_posthoc {
        // Searched again, observed: the timing above stays the plain search's.
        let (trace, _) = posthoc_trace(
            grid,
            args.start,
            args.goal,
            &args.options,
            DEFAULT_EVENT_LIMIT,
        )
        .map_err(|e| match e {
            PosthocError::Plan(e) => say(e),
            e => format!("--trace-posthoc: {e}"),
        })?;
        let text = serde_json::to_vec(&trace).map_err(|e| e.to_string())?;
        crate::output::write_atomically(out, &text)?;
        eprintln!(
            "planlab: Posthoc trace ({} events, {} expansions) written to {}",
            trace.events.len(),
            trace.count("expanding"),
            out.display()
        );
    }
    let cells = |v: &[GridPos]| v.iter().map(|p| [p.col, p.row]).collect::<Vec<_>>();
    if args.json {
        let mut out = json!({
            "cost": result.path.cost,
            "length_m": result.length_m,
            "expanded": result.path.expanded,
            "path": cells(&result.path.cells),
            "keypoints": cells(&result.keypoints),
            "micros": (micros * 1000.0).round() / 1000.0,
        });
        if args.options.bottom_up_eps.is_some() {
            out["feature_nodes"] = json!(cells(&result.feature_nodes));
        }
        if !result.safety.is_empty() {
            out["safety"] = json!(result.safety);
        }
        if grid.is_weighted() {
            out["weighted"] = json!(true);
        }
        if let Some(note) = &result.note {
            out["note"] = json!(note);
        }
        outln!("{out}");
    } else {
        outln!(
            "{} on {} ({}×{} cells{}, {} m/cell): cost {:.4} cells, length {:.3} m, {} nodes, {} expanded, {:.1} µs",
            args.options.algorithm.name(),
            map_path.display(),
            grid.width(),
            grid.height(),
            // The cost is then weighted (docs/algorithms.md §weights).
            if grid.is_weighted() { ", weighted" } else { "" },
            grid.resolution(),
            result.path.cost,
            result.length_m,
            result.path.cells.len(),
            result.path.expanded,
            micros
        );
        if let Some(note) = &result.note {
            outln!("note: {note}");
        }
        if args.options.keypoints {
            outln!(
                "key points ({}): {:?}",
                result.keypoints.len(),
                cells(&result.keypoints)
            );
        }
        if args.options.bottom_up_eps.is_some() {
            outln!(
                "Bottom-Up feature nodes ({}): {:?}",
                result.feature_nodes.len(),
                cells(&result.feature_nodes)
            );
        }
    }
    Ok(())
}

/// Parses `X,Y,THETA` (metres, degrees) into a pose in radians.
pub fn parse_pose(s: &str, flag: &str) -> Result<Pose, String> {
    let bad = || {
        format!(
            "{flag} {s:?}: expected X,Y,THETA with finite numbers (metres, degrees), e.g. 1.5,2,90"
        )
    };
    let v: Vec<f64> = s
        .split(',')
        .map(|p| p.trim().parse::<f64>().map_err(|_| bad()))
        .collect::<Result<_, _>>()?;
    match v[..] {
        [x, y, deg] if x.is_finite() && y.is_finite() && deg.is_finite() => {
            Ok(Pose::new(x, y, deg.to_radians()))
        }
        _ => Err(bad()),
    }
}

/// Options of `planlab plan --algo hybrid-astar`.
pub struct CarArgs {
    /// Start pose (world metres, radians).
    pub start: Pose,
    /// Goal pose.
    pub goal: Pose,
    /// Minimum turning radius, m.
    pub turning_radius: f64,
    /// May reverse.
    pub reverse: bool,
    /// Disc footprint radius, m (default the config's).
    pub radius: Option<f64>,
    /// Rectangular footprint (length, width), m, instead of the disc.
    pub rect: Option<(f64, f64)>,
    /// Unknown cells are free.
    pub allow_unknown: bool,
    /// JSON output.
    pub json: bool,
}

/// `--footprint LxW`: a rectangle's length and width, metres (checked by
/// Hybrid A*: finite, > 0).
pub fn parse_footprint(s: &str) -> Result<(f64, f64), String> {
    let bad = || format!("--footprint {s:?}: expected LENGTHxWIDTH in metres, like 0.6x0.4");
    let (l, w) = s.split_once(['x', 'X', '×']).ok_or_else(bad)?;
    let num = |t: &str| t.trim().parse::<f64>().map_err(|_| bad());
    Ok((num(l)?, num(w)?))
}

/// Plans a car path with Hybrid A* and prints it.
pub fn plan_car(map_path: &Path, grid: &OccupancyGrid, a: &CarArgs) -> Result<(), String> {
    let mut cfg = HybridAStarConfig {
        turning_radius: a.turning_radius,
        reverse: a.reverse,
        allow_unknown: a.allow_unknown,
        ..Default::default()
    };
    if let Some(r) = a.radius {
        cfg.footprint_radius = r;
    }
    cfg.footprint_rect = a.rect;
    let t = Instant::now();
    let p = plan_hybrid_astar(grid, a.start, a.goal, &cfg).map_err(|e| e.to_string())?;
    let micros = t.elapsed().as_secs_f64() * 1e6;
    if a.json {
        let poses: Vec<[f64; 3]> = p.poses.iter().map(|q| [q.x, q.y, q.yaw]).collect();
        outln!(
            "{}",
            json!({
                "length_m": p.length,
                "expanded": p.expanded,
                "analytic": p.analytic,
                "cusps": p.cusps,
                "poses": poses,
                "forward": p.forward,
                "micros": (micros * 1000.0).round() / 1000.0,
            })
        );
    } else {
        outln!(
            "hybrid-astar on {} ({}×{} cells, {} m/cell), turning radius {} m{}, footprint {}: length {:.3} m, {} poses, {} expanded, {} cusps, {}, {:.1} µs",
            map_path.display(),
            grid.width(),
            grid.height(),
            grid.resolution(),
            cfg.turning_radius,
            if cfg.reverse { ", reverse allowed" } else { "" },
            match cfg.footprint_rect {
                Some((l, w)) => format!("{l} × {w} m rectangle"),
                None => format!("{} m", cfg.footprint_radius),
            },
            p.length,
            p.poses.len(),
            p.expanded,
            p.cusps,
            if p.analytic { "exact goal" } else { "goal cell and heading bin" },
            micros
        );
    }
    Ok(())
}

/// `planlab curve`: the obstacle-free Dubins or Reeds-Shepp path.
pub fn curve(reverse: bool, from: Pose, to: Pose, radius: f64, json: bool) -> Result<(), String> {
    let p = if reverse {
        reeds_shepp(from, to, radius)
    } else {
        dubins(from, to, radius)
    }
    .map_err(|e| e.to_string())?;
    if json {
        let segs: Vec<_> = p
            .segments
            .iter()
            .map(|s| json!({"steer": s.steer.letter().to_string(), "length": s.length}))
            .collect();
        outln!(
            "{}",
            json!({"length": p.length(), "word": p.word(), "segments": segs})
        );
    } else {
        outln!(
            "{}: length {:.6} m, word {}",
            if reverse { "reeds-shepp" } else { "dubins" },
            p.length(),
            p.word()
        );
    }
    Ok(())
}

/// Options of `planlab plan` with a sampling planner.
pub struct SamplingArgs {
    /// Start cell (the disc starts at its centre).
    pub start: GridPos,
    /// Goal cell (the disc ends at its centre).
    pub goal: GridPos,
    /// The planner.
    pub algorithm: SamplingAlgorithm,
    /// Iterations to run.
    pub iterations: u64,
    /// Seed of the planner's (and the shortcut's) random stream.
    pub seed: u64,
    /// The disc's radius, cells.
    pub radius: f64,
    /// Shortcut the path afterwards.
    pub shortcut: bool,
    /// Unknown cells are free.
    pub allow_unknown: bool,
    /// JSON output.
    pub json: bool,
}

/// Plans once with a sampling planner and prints the result: the cost (the
/// path's length in cells) and length in metres, the iterations run and the
/// first one with a path, the planner's nodes, and with --json the path's
/// points (cell coordinates, x along the columns, y down the rows).
pub fn plan_sampling(
    map_path: &Path,
    grid: &OccupancyGrid,
    args: &SamplingArgs,
) -> Result<(), String> {
    if args.iterations == 0 {
        return Err("--iterations 0: must be at least 1".into());
    }
    let start = cell_centre(args.start.col, args.start.row);
    let goal = cell_centre(args.goal.col, args.goal.row);
    let options = SamplingOptions {
        algorithm: args.algorithm,
        seed: args.seed,
        ..SamplingOptions::default()
    };
    let say = |e: SamplingError| {
        match e {
        SamplingError::Space(SpaceError::BadRadius(r)) => format!(
            "--radius {}: must be a finite number of metres ≥ 0 and less than half the map's smaller side", r * grid.resolution()
        ),
        e => e.to_string(),
    }
    };
    let t = Instant::now();
    let planner = sampling::plan_on_grid(
        grid,
        args.radius,
        args.allow_unknown,
        start,
        goal,
        &options,
        args.iterations,
    )
    .map_err(say)?;
    let Some(raw_cost) = planner.best_cost() else {
        return Err(format!(
            "{}: no path after {} iterations ({} nodes); try more --iterations or another --seed",
            args.algorithm.name(),
            planner.iterations(),
            planner.node_count()
        ));
    };
    let path: Vec<Point> = if args.shortcut {
        shortcut(planner.space(), planner.path(), args.seed, 200)
    } else {
        planner.path().to_vec()
    };
    let micros = t.elapsed().as_secs_f64() * 1e6;
    let cost = path_cost(&path);
    let length_m = cost * grid.resolution();
    let first = planner.first_solution_iteration().unwrap_or(0);
    if args.json {
        let mut out = json!({
            "algorithm": args.algorithm.name(),
            "cost": cost,
            "length_m": length_m,
            "iterations": planner.iterations(),
            "first_solution_iteration": first,
            "nodes": planner.node_count(),
            "seed": args.seed,
            "radius": args.radius,
            "path": path.iter().map(|p| [p[0], p[1]]).collect::<Vec<_>>(),
            "micros": (micros * 1000.0).round() / 1000.0,
        });
        if args.shortcut {
            out["cost_before_shortcut"] = json!(raw_cost);
        }
        outln!("{out}");
    } else {
        outln!(
            "{} on {} ({}×{} cells, {} m/cell, disc radius {} cells, seed {}): cost {:.4} cells, length {:.3} m, {} iterations (first path at {}), {} nodes, {} points{}, {:.1} µs",
            args.algorithm.name(),
            map_path.display(),
            grid.width(),
            grid.height(),
            grid.resolution(),
            args.radius,
            args.seed,
            cost,
            length_m,
            planner.iterations(),
            first,
            planner.node_count(),
            path.len(),
            if args.shortcut {
                format!(" (shortcut from {raw_cost:.4})")
            } else {
                String::new()
            },
            micros
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_cells() {
        assert_eq!(parse_cell("3,4"), Ok(GridPos::new(3, 4)));
        assert_eq!(parse_cell(" 3 , 4 "), Ok(GridPos::new(3, 4)));
        for bad in ["3", "3,", "-1,2", "a,b", "1,2,3", "99999999999,1"] {
            assert!(parse_cell(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn parses_poses_in_degrees() {
        let p = parse_pose("1.5, -2, 90", "--start").unwrap();
        assert_eq!((p.x, p.y), (1.5, -2.0));
        assert!((p.yaw - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
        for bad in ["1,2", "1,2,3,4", "a,1,2", "nan,1,2", "1,inf,0"] {
            assert!(parse_pose(bad, "--start").is_err(), "{bad}");
        }
    }
}
