//! Criterion benchmark of the simulator's own cost per step (observation,
//! feasibility clamp, terrain, exact collision and clearance, trace row)
//! with the trivial `pursuit` planner, on a 200 × 200 map at 0.05 m with
//! 20 movers: the overhead every DWA step pays on top of its planner.

use criterion::{criterion_group, criterion_main, Criterion};
use planlab_core::map::{OccupancyGrid, Pose2};
use planlab_core::planners::PlannerChoice;
use planlab_core::sim::{Episode, EpisodeSetup, Outcome, SimConfig};
use planlab_core::world::{MotionModel, MoverSpec, RobotSpec, RobotState, StaticMap};
use std::hint::black_box;

fn setup() -> EpisodeSetup {
    let n: usize = 200;
    let mut text = String::new();
    for r in 0..n {
        for c in 0..n {
            let border = r == 0 || c == 0 || r == n - 1 || c == n - 1;
            // Scattered 0.5 m pillars away from the robot's diagonal line.
            let pillar = (r / 10) % 4 == 1 && (c / 10) % 4 == 3 && r.abs_diff(n - c) > 30;
            text.push(if border || pillar { '#' } else { '.' });
        }
        text.push('\n');
    }
    let grid = OccupancyGrid::from_ascii(&text)
        .expect("grid")
        .with_frame(0.05, Pose2::default())
        .expect("frame");
    let movers = (0..20)
        .map(|i| MoverSpec {
            id: i,
            radius: 0.2,
            motion: MotionModel::BackAndForth {
                a: [1.0 + 0.4 * i as f64, 8.0],
                b: [1.0 + 0.4 * i as f64, 9.5],
                speed: 0.3,
            },
        })
        .collect();
    EpisodeSetup {
        map: StaticMap::new(grid, true).expect("map"),
        robot: RobotSpec::default(),
        start: RobotState {
            x: 1.0,
            y: 1.0,
            theta: 0.78,
            ..Default::default()
        },
        goal: [7.0, 7.0],
        movers,
        planner: PlannerChoice::named("pursuit"),
        config: SimConfig::default(),
        terrain: Default::default(),
        seed: 1,
        perception: None,
        global_planner: None,
    }
}

fn bench(c: &mut Criterion) {
    let s = setup();
    c.bench_function("sim/step-200x200-20movers-pursuit", |b| {
        b.iter_batched(
            || Episode::new(s.clone()).expect("episode"),
            |mut ep| {
                for _ in 0..50 {
                    black_box(ep.step());
                }
                assert_eq!(ep.outcome(), Outcome::Running);
                ep
            },
            criterion::BatchSize::LargeInput,
        )
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
