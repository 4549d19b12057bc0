//! A generated map can be driven. Every generator kind, on several seeds,
//! built as the page and `planlab generate` build it (the generated start
//! and goal, heading 0, the generated-map sim settings), is driven to the
//! goal by the DWA family.

use planlab_core::map::generate::{generate, GenerateConfig, GeneratorKind};
use planlab_core::metrics::EpisodeMetrics;
use planlab_core::scenario::Scenario;
use planlab_core::sim::{Episode, Outcome};

fn drive(kind: GeneratorKind, seed: u64, planner: &str) -> (Outcome, f64) {
    let c = GenerateConfig {
        kind,
        seed,
        ..Default::default()
    };
    let g = generate(&c).unwrap();
    let s = Scenario::for_generated("gen", &g, planner);
    let mut ep = Episode::from_scenario(&s, g.grid).unwrap();
    let outcome = ep.run();
    (outcome, EpisodeMetrics::of_episode(&ep).path_length_m)
}

/// Runs that do not reach the goal, each for a reason of the planner, not
/// of the map (the start and goal are mid-corridor; the robot drives off):
/// - plain `dwa` has no global path: it steers straight at the goal and
///   settles in the first dead end or wall pocket facing it (a local
///   minimum, the textbook failure of a purely local planner);
/// - `improved-dwa` / `safe-dual-dwa` take the next temporary goal once
///   within the switch radius of a door's key point / feature node; when
///   that next goal lies behind the wall beside the door, the heading
///   critic pulls the robot into the corner next to the door and it
///   circles there. This is the papers' switching rule, kept as published
///   (the reproduce traces depend on it).
///
/// A run in this list that starts reaching fails the test, so the list is
/// kept exact.
const KNOWN: &[(GeneratorKind, u64, &str)] = &[
    (GeneratorKind::Maze, 0, "dwa"),
    (GeneratorKind::Maze, 7, "dwa"),
    (GeneratorKind::Rooms, 0, "safe-dual-dwa"),
    (GeneratorKind::Rooms, 3, "improved-dwa"),
    (GeneratorKind::Rooms, 3, "safe-dual-dwa"),
    (GeneratorKind::Rooms, 7, "dwa"),
    (GeneratorKind::Rooms, 7, "improved-dwa"),
    (GeneratorKind::Rooms, 7, "safe-dual-dwa"),
    (GeneratorKind::Random, 3, "dwa"),
    (GeneratorKind::Random, 3, "improved-dwa"),
    (GeneratorKind::Random, 3, "safe-dual-dwa"),
    (GeneratorKind::Random, 7, "safe-dual-dwa"),
];

#[test]
fn every_generator_kind_is_driven_by_the_dwa_family() {
    let mut wrong = Vec::new();
    let mut reached = 0;
    for kind in [
        GeneratorKind::Maze,
        GeneratorKind::Rooms,
        GeneratorKind::Random,
    ] {
        for seed in [0, 3, 7] {
            for planner in ["dwa", "improved-dwa", "safe-dual-dwa"] {
                let (o, len) = drive(kind, seed, planner);
                let known = KNOWN.contains(&(kind, seed, planner));
                reached += usize::from(o == Outcome::Reached);
                // Every run drives off its start (a start wedged in a
                // corner once ended "stuck" after 0.00 m).
                if len < 2.0 || (o == Outcome::Reached) == known {
                    wrong.push(format!(
                        "{kind:?} seed {seed} {planner}: {o} after {len:.2} m (known failure: {known})"
                    ));
                }
            }
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
    assert_eq!(reached, 27 - KNOWN.len());
}

#[test]
fn generated_start_and_goal_are_mid_corridor() {
    // In a maze of 1.4 m corridors the middle keeps 0.7 m from both walls:
    // start and goal keep at least 0.6 m (a cell less), not the 0.3 m of a
    // corner cell.
    for seed in 0..8 {
        let g = generate(&GenerateConfig {
            seed,
            ..Default::default()
        })
        .unwrap();
        let d = planlab_core::map::costmap::distance_field(&g.grid);
        let w = g.grid.width();
        for (what, (c, r)) in [("start", g.start_cell), ("goal", g.goal_cell)] {
            assert!(
                d[r * w + c] >= 0.6,
                "seed {seed} {what}: clearance {}",
                d[r * w + c]
            );
        }
    }
}

#[test]
fn the_generated_maze_of_seed_7_is_reached_by_improved_dwa() {
    // What `planlab generate maze --seed 7 --out m.json` + `planlab run
    // m.json` does (the scenario's planner is improved-dwa).
    assert_eq!(
        drive(GeneratorKind::Maze, 7, "improved-dwa").0,
        Outcome::Reached
    );
}
