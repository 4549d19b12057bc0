//! `planlab generate`: a seeded random map (maze, rooms, random fill) as a
//! scenario JSON with the map inline, or as a Moving AI `.map`, so a
//! researcher can rebuild the exact map the page generated from the same
//! settings (the grid hash printed here is the page's).

use std::path::Path;

use planlab_core::map::generate::{generate, GenerateConfig};
use planlab_core::map::io::movingai;
use planlab_core::scenario::Scenario;
use serde::Serialize;

/// What `planlab generate --json` prints.
#[derive(Serialize)]
struct GenerateReport<'a> {
    kind: &'static str,
    seed: u64,
    width: usize,
    height: usize,
    resolution: f64,
    /// The grid's content hash as a decimal string (u64 does not fit a JS
    /// number).
    grid_hash: String,
    occupied: usize,
    start: [f64; 2],
    goal: [f64; 2],
    start_cell: [usize; 2],
    goal_cell: [usize; 2],
    out: &'a str,
}

/// The command line that rebuilds `c` (written into the scenario's
/// description).
pub fn command_line(c: &GenerateConfig) -> String {
    let mut s = format!(
        "planlab generate {} --width {} --height {} --resolution {} --seed {} --robot-radius {}",
        c.kind.as_str(),
        c.width_m,
        c.height_m,
        c.resolution,
        c.seed,
        c.robot_radius
    );
    match c.kind {
        planlab_core::map::generate::GeneratorKind::Maze => {
            s.push_str(&format!(" --corridor {} --wall {}", c.corridor_m, c.wall_m));
        }
        planlab_core::map::generate::GeneratorKind::Rooms => {
            s.push_str(&format!(
                " --corridor {} --wall {} --room {}",
                c.corridor_m, c.wall_m, c.room_m
            ));
        }
        planlab_core::map::generate::GeneratorKind::Random => {
            s.push_str(&format!(" --density {} --block {}", c.density, c.block_m));
        }
    }
    s
}

/// Generates the map and writes it to `out` (`.json` scenario or `.map`).
pub fn run(c: &GenerateConfig, out: &Path, json: bool) -> Result<(), String> {
    let g = generate(c).map_err(|e| e.to_string())?;
    let ext = out
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let text = match ext.as_deref() {
        Some("json") => {
            let mut s = Scenario::for_generated(
                &format!("{} seed {}", c.kind.as_str(), c.seed),
                &g,
                "improved-dwa",
            );
            s.description = format!(
                "Generated map: {}. Start and goal are joined for a robot of radius {} m.",
                command_line(c),
                c.robot_radius
            );
            s.to_json_pretty().map_err(|e| e.to_string())?
        }
        Some("map") => movingai::write_map(&g.grid),
        _ => {
            return Err(format!(
                "--out {}: the file name must end in .json (scenario) or .map (Moving AI)",
                out.display()
            ))
        }
    };
    crate::output::write_atomically(out, text.as_bytes())?;
    let report = GenerateReport {
        kind: c.kind.as_str(),
        seed: c.seed,
        width: g.grid.width(),
        height: g.grid.height(),
        resolution: g.grid.resolution(),
        grid_hash: g.grid.content_hash().to_string(),
        occupied: g.grid.counts().1,
        start: g.start,
        goal: g.goal,
        start_cell: [g.start_cell.0, g.start_cell.1],
        goal_cell: [g.goal_cell.0, g.goal_cell.1],
        out: &out.to_string_lossy(),
    };
    if json {
        outln!(
            "{}",
            serde_json::to_string(&report).map_err(|e| e.to_string())?
        );
    } else {
        outln!(
            "wrote {}: {} seed {}, {}×{} cells at {} m, {} occupied, start ({:.2}, {:.2}) m, goal ({:.2}, {:.2}) m, grid hash {}",
            report.out,
            report.kind,
            report.seed,
            report.width,
            report.height,
            report.resolution,
            report.occupied,
            g.start[0],
            g.start[1],
            g.goal[0],
            g.goal[1],
            report.grid_hash
        );
    }
    Ok(())
}
