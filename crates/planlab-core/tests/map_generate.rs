//! Generated maps checked by the grid planner: the generator (map layer)
//! cannot use the planner (global layer) in its own unit tests, so the
//! independent connectivity check lives here.

use planlab_core::global::plan::{plan_on_map, GridPlanOptions};
use planlab_core::map::generate::{generate, GenerateConfig, GeneratedMap, GeneratorKind};
use planlab_core::map::{Cell, GridPos};

/// Start and goal joined by a grid path on the map inflated by the
/// robot radius (an independent check: A* on the inflated grid).
fn connected_for_robot(g: &GeneratedMap, radius: f64) -> bool {
    let opts = GridPlanOptions {
        inflate_m: radius,
        ..Default::default()
    };
    let (s, t) = (g.start_cell, g.goal_cell);
    plan_on_map(
        &g.grid,
        GridPos::new(s.0 as u32, s.1 as u32),
        GridPos::new(t.0 as u32, t.1 as u32),
        &opts,
    )
    .is_ok()
}

#[test]
fn start_and_goal_connected_for_the_robot() {
    for kind in [
        GeneratorKind::Maze,
        GeneratorKind::Rooms,
        GeneratorKind::Random,
    ] {
        for seed in 0..12 {
            for radius in [0.15, 0.25] {
                let c = GenerateConfig {
                    kind,
                    seed,
                    robot_radius: radius,
                    ..Default::default()
                };
                let g = generate(&c).unwrap();
                let free = |(c, r): (usize, usize)| g.grid.get(c, r) == Some(Cell::Free);
                assert!(free(g.start_cell) && free(g.goal_cell));
                assert!(
                    connected_for_robot(&g, radius),
                    "{kind:?} seed {seed} r {radius}"
                );
                // Far apart: corners of the free space, not neighbours.
                let d =
                    ((g.start[0] - g.goal[0]).powi(2) + (g.start[1] - g.goal[1]).powi(2)).sqrt();
                assert!(d > 3.0, "{kind:?} seed {seed}: start–goal {d} m");
            }
        }
    }
}
