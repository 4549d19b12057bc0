//! Criterion benchmark of one LiDAR navigator step on a seeded scene: a
//! 360-beam scan ray-cast on a 200 × 200 map at 0.1 m (d_lidar 10 m), edge
//! extraction (def. 1, Algorithm 1, Algorithm 2, expansion) and the
//! temporary-goal choice. The bound to meet is absolute (< 100 µs native),
//! so the figure is reported, not asserted; the decision is checked inside
//! (the goal is blocked and a temporary goal is chosen).

use criterion::{criterion_group, criterion_main, Criterion};
use planlab_core::lidar::scan::Lidar;
use planlab_core::lidar::{LidarConfig, LidarNavConfig, NavInput, Navigator, TargetKind, Velocity};
use planlab_core::map::{Cell, OccupancyGrid, Pose2};
use planlab_core::num::Rng;
use planlab_core::world::StaticMap;
use std::hint::black_box;

/// 20 m square; 40 seeded blocks kept 1.5 m away from the robot at the
/// centre, and a 6 m wall 3 m in front of it across the goal's bearing.
fn scene() -> StaticMap {
    let mut rng = Rng::new(11);
    let (w, h) = (200usize, 200usize);
    let mut cells = vec![Cell::Free; w * h];
    for _ in 0..40 {
        let (c0, r0) = (
            rng.range(0.0, 190.0) as usize,
            rng.range(0.0, 190.0) as usize,
        );
        let (bw, bh) = (rng.range(3.0, 12.0) as usize, rng.range(3.0, 12.0) as usize);
        let near = |c: usize, r: usize| {
            let (dx, dy) = (c as f64 - 100.0, r as f64 - 100.0);
            (dx * dx + dy * dy).sqrt() < 15.0
        };
        for r in r0..(r0 + bh).min(h) {
            for c in c0..(c0 + bw).min(w) {
                if !near(c, r) {
                    cells[r * w + c] = Cell::Occupied;
                }
            }
        }
    }
    // The wall: columns 130–132, rows 70–130 (x 13–13.3 m, y 7–13 m).
    for r in 70..130 {
        for c in 130..133 {
            cells[r * w + c] = Cell::Occupied;
        }
    }
    let grid = OccupancyGrid::from_cells(w, h, cells)
        .expect("grid")
        .with_frame(0.1, Pose2::default())
        .expect("frame");
    StaticMap::new(grid, true).expect("map")
}

fn bench(c: &mut Criterion) {
    let map = scene();
    let pose = [10.05, 10.05, 0.0];
    let goal = [8.0, 0.3];
    let mut lidar = Lidar::new(LidarConfig::default(), "lidar").expect("lidar");
    let nav_cfg = LidarNavConfig {
        switch_condition: false,
        hold: false,
        ..Default::default()
    };
    let mut nav = Navigator::new(nav_cfg, "nav").expect("nav");
    let scan = lidar.scan(&map, pose, &[]);
    assert_eq!(scan.len(), 360);
    let input = NavInput {
        scan: &scan,
        velocity: Velocity::default(),
        goal,
        dt: 0.1,
    };
    nav.step(&input);
    assert_eq!(
        nav.debug().kind,
        TargetKind::Temporary,
        "the wall blocks the goal"
    );

    let mut g = c.benchmark_group("lidar");
    g.bench_function("scan360 + edges + temp goal", |b| {
        b.iter(|| {
            let scan = lidar.scan(black_box(&map), black_box(pose), &[]);
            let t = nav.step(&NavInput {
                scan: &scan,
                velocity: Velocity::default(),
                goal,
                dt: 0.1,
            });
            black_box(t)
        })
    });
    g.bench_function("ray cast 360 beams", |b| {
        b.iter(|| black_box(lidar.scan(black_box(&map), black_box(pose), &[])))
    });
    g.bench_function("edges + temp goal (given scan)", |b| {
        b.iter(|| black_box(nav.step(black_box(&input))))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
