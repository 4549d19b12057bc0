//! Issue 16 §2 (fix what breaks in class). §2.1: a generated map can be driven. Every generator kind, on
//! several seeds, built as the page and `planlab generate` build it (the
//! generated start and goal, heading 0, the generated-map sim settings),
//! is driven to the goal by the DWA family.

use planlab_core::map::generate::{generate, GenerateConfig, GeneratorKind};
use planlab_core::metrics::EpisodeMetrics;
use planlab_core::planners::PlannerChoice;
use planlab_core::scenario::Scenario;
use planlab_core::sim::{Episode, Outcome, SimConfig};

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
fn item1_generated_maps_are_drivable() {
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
                // Every run drives off its start (the issue: "stuck" after
                // 0.00 m from a start wedged in a corner).
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
fn item1_start_and_goal_are_mid_corridor() {
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
fn item1_cli_maze_seed_7_example() {
    // What `planlab generate maze --seed 7 --out m.json` + `planlab run
    // m.json` does (the scenario's planner is improved-dwa).
    assert_eq!(
        drive(GeneratorKind::Maze, 7, "improved-dwa").0,
        Outcome::Reached
    );
}

#[test]
fn item8_nan_in_scenario_json_is_named() {
    let text = r#"{ "version": 1, "name": "n", "map": { "width": 3, "height": 1, "resolution": 1.0, "cells": ["..."] },
  "start": { "col": 0, "row": 0 }, "goal": { "col": 2, "row": 0 },
  "sim": { "dt": NaN } }"#;
    let e = planlab_core::scenario::Scenario::from_json(text)
        .unwrap_err()
        .to_string();
    assert!(e.contains("NaN is not a number JSON allows"), "{e}");
    assert!(e.contains("line 3"), "{e}");
    let any = planlab_core::scenario::AnyScenario::from_json(&text.replace("NaN", "-Infinity"))
        .unwrap_err()
        .to_string();
    assert!(
        any.contains("-Infinity is not a number JSON allows"),
        "{any}"
    );
}

#[test]
fn item8_garbage_map_is_not_echoed() {
    use planlab_core::map::io::movingai::parse_map;
    let e = parse_map("\u{1}PNG\u{1a}\u{0}\u{0}garbage\nmore")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("not a Moving AI map: the first line should be `type octile`"),
        "{e}"
    );
    assert!(!e.contains("\\u{") && !e.contains("PNG"), "{e}");
}

#[test]
fn s3_every_planner_has_plain_words_beside_its_paper() {
    for p in planlab_core::planners::list() {
        assert!(!p.paper.is_empty(), "{}", p.name);
        // A paragraph: what it does, when it fails, what to watch.
        assert!(p.plain.len() > 150, "{}: {:?}", p.name, p.plain);
        assert!(
            p.plain.contains("Watch")
                || p.plain.contains("watch")
                || p.plain.contains("Use it")
                || p.plain.contains("Compare")
                || p.plain.contains("Run it")
                || p.plain.contains("Turn on"),
            "{}: nothing to look at",
            p.name
        );
    }
}

/// A 6 × 4 m room split by a wall at x = 3 m with a gap `gap_cells` tall.
fn split_room(gap_cells: usize) -> Episode {
    use planlab_core::map::{Cell, OccupancyGrid, Pose2};
    use planlab_core::sim::EpisodeSetup;
    use planlab_core::world::{RobotSpec, RobotState, StaticMap};
    let (w, h) = (60, 40);
    let mut cells = vec![Cell::Free; w * h];
    for row in 0..h {
        if !(20..20 + gap_cells).contains(&row) {
            cells[row * w + 30] = Cell::Occupied;
        }
    }
    let grid = OccupancyGrid::from_cells(w, h, cells)
        .unwrap()
        .with_frame(0.1, Pose2::default())
        .unwrap();
    Episode::new(EpisodeSetup {
        map: StaticMap::new(grid, true).unwrap(),
        robot: RobotSpec::default(),
        start: RobotState {
            x: 1.0,
            y: 2.0,
            ..Default::default()
        },
        goal: [5.0, 2.0],
        movers: Vec::new(),
        planner: PlannerChoice::named("dwa"),
        config: SimConfig::default(),
        terrain: Default::default(),
        seed: 0,
    })
    .unwrap()
}

#[test]
fn item2_a_path_only_without_inflation_is_said() {
    // Gap of 0.2 m for a robot 0.4 m across: only the bare map has a path.
    let note = split_room(2).route_note().expect("a note");
    assert!(note.contains("only without inflation"), "{note}");
    assert!(note.contains("radius 0.20 m"), "{note}");
    // A 1.5 m gap: the robot fits, nothing to say.
    assert_eq!(split_room(15).route_note(), None);
}
