//! The episode's route note: when the global path exists only on the bare
//! map (the inflated one has none), the robot's radius is said, not a
//! silent "no path".

use planlab_core::planners::PlannerChoice;
use planlab_core::sim::{Episode, SimConfig};

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
        perception: None,
        global_planner: None,
    })
    .unwrap()
}

#[test]
fn a_path_only_without_inflation_is_said() {
    // Gap of 0.2 m for a robot 0.4 m across: only the bare map has a path.
    let note = split_room(2).route_note().expect("a note");
    assert!(note.contains("only without inflation"), "{note}");
    assert!(note.contains("radius 0.20 m"), "{note}");
    // A 1.5 m gap: the robot fits, nothing to say.
    assert_eq!(split_room(15).route_note(), None);
}
