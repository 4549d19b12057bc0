//! Episodes end to end with the `pursuit` baseline: outcomes, exact
//! collision steps, determinism, live edits and bad input.

use planlab_core::map::{OccupancyGrid, Pose2};
use planlab_core::metrics::EpisodeMetrics;
use planlab_core::planners::PlannerChoice;
use planlab_core::sim::{Episode, EpisodeSetup, Outcome, SimConfig, SimError, Trace, TraceStep};
use planlab_core::world::{
    Footprint, MotionModel, MoverSpec, RobotSpec, RobotState, StaticMap, WorldError,
};

/// A `w`×`h` m room at 0.1 m per cell with a one-cell border wall, plus
/// `extra` blocked cells (col, row).
fn room(w: usize, h: usize, extra: &[(usize, usize)]) -> StaticMap {
    let (cw, ch) = (w * 10, h * 10);
    let mut rows = String::new();
    for r in 0..ch {
        for c in 0..cw {
            let wall = r == 0 || c == 0 || r == ch - 1 || c == cw - 1 || extra.contains(&(c, r));
            rows.push(if wall { '#' } else { '.' });
        }
        rows.push('\n');
    }
    let g = OccupancyGrid::from_ascii(&rows)
        .unwrap()
        .with_frame(0.1, Pose2::default())
        .unwrap();
    StaticMap::new(g, true).unwrap()
}

fn setup(map: StaticMap, start: [f64; 3], goal: [f64; 2]) -> EpisodeSetup {
    EpisodeSetup {
        map,
        robot: RobotSpec::default(),
        start: RobotState {
            x: start[0],
            y: start[1],
            theta: start[2],
            ..Default::default()
        },
        goal,
        movers: Vec::new(),
        planner: PlannerChoice::named("pursuit"),
        config: SimConfig::default(),
        terrain: Default::default(),
        seed: 7,
        perception: None,
        global_planner: None,
    }
}

fn metrics(ep: &Episode) -> EpisodeMetrics {
    EpisodeMetrics::from_trace(
        ep.trace(),
        &ep.planner_debug().global_path,
        ep.outcome(),
        40.0,
    )
}

#[test]
fn pursuit_reaches_the_goal_in_an_empty_room() {
    let mut ep = Episode::new(setup(room(10, 10, &[]), [1.0, 1.0, 0.0], [8.0, 7.0])).unwrap();
    assert_eq!(ep.run(), Outcome::Reached);
    let s = ep.state();
    assert!(((s.x - 8.0).powi(2) + (s.y - 7.0).powi(2)).sqrt() <= 0.2);
    let m = metrics(&ep);
    let straight = (7.0f64.powi(2) + 6.0f64.powi(2)).sqrt();
    // Turns toward the goal first, then a nearly straight run.
    assert!(
        m.path_length_m > straight - 0.25 && m.path_length_m < straight + 0.5,
        "{m:?}"
    );
    assert!(m.min_clearance_m > 0.5, "{m:?}");
    assert_eq!(m.speed_drops, 0);
    // It curves from heading 0 onto the 0.71 rad bearing and then runs
    // straight: the path turns by less than that bearing in total.
    assert!(m.total_turn_rad > 0.3 && m.total_turn_rad < 0.72, "{m:?}");
    // One row per step plus the start.
    assert_eq!(ep.trace().steps.len() as u64, ep.steps() + 1);
    assert_eq!(ep.trace().steps[0].t, 0.0);
    // Sticky outcome.
    let n = ep.steps();
    assert_eq!(ep.step(), Outcome::Reached);
    assert_eq!(ep.steps(), n);
}

#[test]
fn driving_into_a_wall_collides_at_the_exact_step() {
    // A wall in column 50 (x ∈ [5.0, 5.1]) up to y = 9 m; the gap above
    // keeps the goal reachable, but not straight ahead.
    let wall: Vec<(usize, usize)> = (10..100).map(|r| (50, r)).collect();
    let mut ep = Episode::new(setup(room(10, 10, &wall), [2.0, 5.05, 0.0], [9.5, 5.05])).unwrap();
    assert_eq!(ep.run(), Outcome::Collision);
    // Accelerating at 0.2 m/s² in 0.1 s steps: v_k = 0.02k up to 1 m/s at
    // k = 50 (x = 2 + 0.001·k(k+1) = 4.55), then 0.1 m per step: 4.65,
    // 4.75, 4.85. The 0.2 m disc touches x = 5.0 first at step 53.
    assert_eq!(ep.steps(), 53);
    let rows = &ep.trace().steps;
    let last = rows.last().unwrap();
    assert!((last.x - 4.85).abs() < 1e-9, "{}", last.x);
    assert_eq!(last.clearance, 0.0);
    let before = &rows[rows.len() - 2];
    assert!(before.x + 0.2 < 5.0 && (before.clearance - (5.0 - before.x - 0.2)).abs() < 1e-9);
    assert!((ep.time() - 5.3).abs() < 1e-12);
}

#[test]
fn a_mover_crossing_the_path_collides() {
    // Robot runs east along y = 5; a 0.3 m mover comes down x = 5.5 and
    // reaches y = 5 at about the time the robot does (t ≈ 5.9 s).
    let mut s = setup(room(10, 10, &[]), [1.0, 5.0, 0.0], [9.0, 5.0]);
    s.movers = vec![MoverSpec {
        id: 4,
        radius: 0.3,
        motion: MotionModel::ConstantVelocity {
            start: [5.5, 8.0],
            velocity: [0.0, -0.5],
            since: 0.0,
        },
    }];
    let mut ep = Episode::new(s).unwrap();
    assert_eq!(ep.run(), Outcome::Collision);
    let last = ep.trace().steps.last().unwrap().clone();
    let m = last.movers[0].1;
    let gap = ((last.x - m[0]).powi(2) + (last.y - m[1]).powi(2)).sqrt() - 0.5;
    assert!(gap <= 0.0, "{gap}");
    // Far from any wall: it was the mover.
    assert!(ep.map().clearance(last.x, last.y) > 1.0);
    // The step before, they were apart.
    let prev = &ep.trace().steps[ep.trace().steps.len() - 2];
    let pm = prev.movers[0].1;
    assert!(((prev.x - pm[0]).powi(2) + (prev.y - pm[1]).powi(2)).sqrt() > 0.5);
    // The mover was observed (within 5 m) and reported in movers_now.
    let now = ep.movers_now();
    assert_eq!(now.len(), 1);
    assert_eq!((now[0].0, now[0].1), (4, 0.3));
}

#[test]
fn a_robot_hit_by_a_mover_while_at_rest_is_reported_as_such() {
    // The robot stands (an external zero command every step) while mover
    // 3 drives into it from the east; mover 5 stays away.
    let mut s = setup(room(10, 10, &[]), [3.0, 5.0, 0.0], [9.0, 5.0]);
    let cv = |id, start, velocity| MoverSpec {
        id,
        radius: 0.3,
        motion: MotionModel::ConstantVelocity {
            start,
            velocity,
            since: 0.0,
        },
    };
    s.movers = vec![
        cv(5, [8.0, 8.0], [0.0, 0.0]),
        cv(3, [6.0, 5.0], [-0.5, 0.0]),
    ];
    let mut ep = Episode::new(s.clone()).unwrap();
    assert_eq!(ep.collision(), None);
    let stand = planlab_core::world::Command::default();
    while ep.outcome() == Outcome::Running {
        ep.step_with(stand).unwrap();
    }
    assert_eq!(ep.outcome(), Outcome::Collision);
    let c = ep.collision().expect("a collision says what with");
    assert_eq!(
        c,
        planlab_core::sim::Collision::Mover {
            id: 3,
            at_rest: true
        }
    );
    assert_eq!(c.to_string(), "hit by mover 3 while at rest");
    let m = EpisodeMetrics::of_episode(&ep);
    assert_eq!(m.collision, Some(c));
    let json = serde_json::to_value(&m).unwrap();
    assert_eq!(json["collision"]["with"], "mover");
    assert_eq!(json["collision"]["at_rest"], true);
    // The robot driving into a standing mover is an ordinary collision.
    s.movers = vec![cv(3, [6.0, 5.0], [0.0, 0.0])];
    let mut ep = Episode::new(s).unwrap();
    assert_eq!(ep.run(), Outcome::Collision);
    assert_eq!(
        ep.collision().unwrap().to_string(),
        "collision with mover 3"
    );
    // No collision, no field.
    let mut ep = Episode::new(setup(room(10, 10, &[]), [1.0, 1.0, 0.0], [8.0, 7.0])).unwrap();
    assert_eq!(ep.run(), Outcome::Reached);
    assert_eq!(ep.collision(), None);
    let json = serde_json::to_value(EpisodeMetrics::of_episode(&ep)).unwrap();
    assert!(json.get("collision").is_none(), "{json}");
}

#[test]
fn timeout_and_stuck() {
    let mut s = setup(room(10, 10, &[]), [1.0, 1.0, 0.0], [9.0, 9.0]);
    s.config.max_time = 3.0;
    let mut ep = Episode::new(s).unwrap();
    assert_eq!(ep.run(), Outcome::Timeout);
    assert_eq!(ep.steps(), 30);

    // Goal behind the robot, but it can barely turn: it spins in place
    // without getting closer, so after stuck_time it is stuck.
    let mut s = setup(room(10, 10, &[]), [5.0, 5.0, 0.0], [2.0, 5.0]);
    s.robot.limits.w_max = 0.01;
    let mut ep = Episode::new(s).unwrap();
    assert_eq!(ep.run(), Outcome::Stuck);
    assert!((ep.time() - 15.0).abs() < 1e-9, "{}", ep.time());
    assert!((ep.state().x - 5.0).abs() < 1e-12);
}

#[test]
fn same_setup_same_trace_different_movers_different_trace() {
    let mk = |speed: f64| {
        let mut s = setup(room(10, 10, &[]), [1.0, 1.0, 0.5], [8.0, 8.0]);
        s.movers = vec![MoverSpec {
            id: 1,
            radius: 0.2,
            motion: MotionModel::BackAndForth {
                a: [8.0, 2.0],
                b: [8.0, 5.0],
                speed,
            },
        }];
        let mut ep = Episode::new(s).unwrap();
        ep.run();
        ep
    };
    let (a, b, c) = (mk(0.4), mk(0.4), mk(0.5));
    assert_eq!(a.trace(), b.trace());
    assert_eq!(a.trace().hash(), b.trace().hash());
    assert_eq!(a.trace().to_csv(), b.trace().to_csv());
    assert_ne!(a.trace().hash(), c.trace().hash());
}

#[test]
fn moving_the_goal_mid_run() {
    let mut ep = Episode::new(setup(room(10, 10, &[]), [1.0, 1.0, 0.0], [8.0, 1.0])).unwrap();
    for _ in 0..30 {
        assert_eq!(ep.step(), Outcome::Running);
    }
    // Into a wall: refused, old goal kept.
    let e = ep.set_goal([0.05, 5.0]).unwrap_err();
    assert!(matches!(e, SimError::BadGoal { .. }), "{e}");
    assert!(e.to_string().contains("inside a wall"), "{e}");
    assert!(ep.set_goal([f64::NAN, 1.0]).is_err());
    assert!(ep
        .set_goal([20.0, 1.0])
        .unwrap_err()
        .to_string()
        .contains("off the map"));
    assert_eq!(ep.goal(), [8.0, 1.0]);
    ep.set_goal([3.0, 8.0]).unwrap();
    assert_eq!(ep.run(), Outcome::Reached);
    let s = ep.state();
    assert!(((s.x - 3.0).powi(2) + (s.y - 8.0).powi(2)).sqrt() <= 0.2);
    assert_eq!(ep.trace().steps.last().unwrap().goal, [3.0, 8.0]);
    assert_eq!(ep.setup().goal, [3.0, 8.0]);
}

#[test]
fn movers_can_be_replaced_live() {
    let mut ep = Episode::new(setup(room(10, 10, &[]), [1.0, 5.0, 0.0], [9.0, 5.0])).unwrap();
    for _ in 0..10 {
        ep.step();
    }
    let bad = MoverSpec {
        id: 2,
        radius: -1.0,
        motion: MotionModel::ConstantVelocity {
            start: [5.0, 5.0],
            velocity: [0.0, 0.0],
            since: 0.0,
        },
    };
    assert!(ep
        .set_movers(vec![bad])
        .unwrap_err()
        .to_string()
        .contains("mover 2 radius"));
    // A parked mover on the robot's line: pursuit drives into it.
    let parked = MoverSpec {
        id: 2,
        radius: 0.4,
        motion: MotionModel::ConstantVelocity {
            start: [5.0, 5.0],
            velocity: [0.0, 0.0],
            since: 0.0,
        },
    };
    ep.set_movers(vec![parked]).unwrap();
    assert_eq!(ep.run(), Outcome::Collision);
    assert!((ep.state().x - 4.4).abs() < 0.11, "{}", ep.state().x);
}

#[test]
fn bad_input_is_refused_with_clear_errors() {
    let base = || setup(room(10, 10, &[]), [1.0, 1.0, 0.0], [8.0, 8.0]);
    let err = |s: EpisodeSetup| Episode::new(s).unwrap_err();

    let mut s = base();
    s.robot.limits.v_max = f64::NAN;
    let e = err(s);
    assert!(matches!(
        e,
        SimError::World(WorldError::InvalidParameter(_))
    ));
    assert!(e.to_string().contains("robot.limits.v_max"), "{e}");

    let mut s = base();
    s.robot.footprint = Footprint::Circle { radius: -0.2 };
    assert!(err(s).to_string().contains("robot.footprint.radius"));

    let mut s = base();
    s.start.x = f64::NAN;
    assert!(err(s).to_string().contains("start.x"));

    let mut s = base();
    s.config.dt = 0.0;
    assert!(err(s).to_string().contains("sim.dt"));

    // Start overlapping the border wall.
    let mut s = base();
    s.start.x = 0.2;
    let e = err(s);
    assert!(
        matches!(e, SimError::World(WorldError::StartInCollision { .. })),
        "{e}"
    );
    assert!(e.to_string().contains("starts in collision"), "{e}");

    // Start overlapping a mover.
    let mut s = base();
    s.movers = vec![MoverSpec {
        id: 9,
        radius: 0.3,
        motion: MotionModel::ConstantVelocity {
            start: [1.3, 1.0],
            velocity: [0.0, 0.0],
            since: 0.0,
        },
    }];
    assert!(err(s).to_string().contains("mover 9"));

    // Goal in a wall / off the map.
    let wall: Vec<(usize, usize)> = (40..60)
        .flat_map(|c| (40..60).map(move |r| (c, r)))
        .collect();
    let mut s = setup(room(10, 10, &wall), [1.0, 1.0, 0.0], [5.0, 5.0]);
    assert!(err(s.clone()).to_string().contains("inside a wall"));
    s.goal = [5.0, 11.0];
    assert!(err(s).to_string().contains("off the map"));

    // A goal in a closed box (free inside, walls around).
    let ring: Vec<(usize, usize)> = (40..60)
        .flat_map(|c| (40..60).map(move |r| (c, r)))
        .filter(|&(c, r)| c == 40 || c == 59 || r == 40 || r == 59)
        .collect();
    let s = setup(room(10, 10, &ring), [1.0, 1.0, 0.0], [5.0, 5.0]);
    let e = err(s);
    assert!(matches!(e, SimError::Unreachable { .. }), "{e}");
    assert!(e.to_string().contains("cannot be reached"), "{e}");

    // Unknown planner and a bad planner config.
    let mut s = base();
    s.planner = PlannerChoice::named("nope");
    assert!(err(s).to_string().contains("unknown planner `nope`"));
    let mut s = base();
    s.planner.config = serde_json::json!({"k_w": -1.0});
    assert!(err(s).to_string().contains("pursuit.k_w"));
    let mut s = base();
    s.planner.config = serde_json::json!({"kw": 1.0});
    assert!(err(s).to_string().contains("unknown field `kw`"));

    // A mover with a NaN speed.
    let mut s = base();
    s.movers = vec![MoverSpec {
        id: 1,
        radius: 0.3,
        motion: MotionModel::BackAndForth {
            a: [5.0, 5.0],
            b: [6.0, 5.0],
            speed: f64::NAN,
        },
    }];
    assert!(err(s).to_string().contains("mover 1 speed"));
}

#[test]
fn trace_hash_is_stable() {
    // The hash layout is part of the native-vs-wasm determinism check:
    // this golden only changes when the layout is changed on purpose.
    let tr = Trace {
        steps: vec![
            TraceStep::default(),
            TraceStep {
                t: 0.1,
                x: 1.0,
                y: 2.0,
                theta: 0.5,
                v: 0.25,
                mode: "pursuit".into(),
                wheel_loads: Some([50.0, 51.0, 52.0, 53.0]),
                movers: vec![(3, [1.5, -2.5])],
                ..Default::default()
            },
        ],
    };
    assert_eq!(tr.hash(), GOLDEN);
}

const GOLDEN: u64 = 12_546_789_755_311_034_996;
