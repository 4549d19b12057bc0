//! Criterion benchmark of one DWA control step on the reference
//! scene: 20 × 40 (v, ω) samples, 3 s horizon at 0.1 s, a 200 × 200 map,
//! 20 movers (seeded). The bound to meet is absolute (< 1 ms native), so
//! there is no peer here; the chosen command is checked inside.

use criterion::{criterion_group, criterion_main, Criterion};
use planlab_core::local::dwa::{DwaConfig, DwaCore, StepRequest};
use planlab_core::local::{Observation, ObservedMover};
use planlab_core::map::{Cell, OccupancyGrid, Pose2};
use planlab_core::num::Rng;
use planlab_core::world::{RobotSpec, RobotState, StaticMap};
use std::hint::black_box;

struct Scene {
    map: StaticMap,
    movers: Vec<ObservedMover>,
    state: RobotState,
    goal: [f64; 2],
}

/// 200 × 200 cells at 0.1 m (20 m square): 60 seeded blocks of 3–8 cells
/// kept away from the robot, 20 movers of radius 0.2–0.4 m at 0–0.5 m/s.
fn scene() -> Scene {
    let mut rng = Rng::new(7);
    let (w, h) = (200usize, 200usize);
    let mut cells = vec![Cell::Free; w * h];
    let centre = (100.0, 100.0);
    for _ in 0..60 {
        let (c0, r0) = (
            rng.range(0.0, 190.0) as usize,
            rng.range(0.0, 190.0) as usize,
        );
        let (bw, bh) = (rng.range(3.0, 9.0) as usize, rng.range(3.0, 9.0) as usize);
        // Keep a 1.5 m disc around the robot free (centre-to-block distance).
        let gap = |lo: f64, len: f64, c: f64| (lo - c).max(c - (lo + len)).max(0.0);
        let (gx, gy) = (
            gap(c0 as f64, bw as f64, centre.0),
            gap(r0 as f64, bh as f64, centre.1),
        );
        if (gx * gx + gy * gy).sqrt() < 15.0 {
            continue;
        }
        for r in r0..(r0 + bh).min(h) {
            for c in c0..(c0 + bw).min(w) {
                cells[r * w + c] = Cell::Occupied;
            }
        }
    }
    let grid = OccupancyGrid::from_cells(w, h, cells)
        .expect("grid")
        .with_frame(0.1, Pose2::default())
        .expect("frame");
    let map = StaticMap::new(grid, true).expect("map");
    let state = RobotState {
        x: 10.0,
        y: 10.0,
        theta: 0.4,
        v: 0.3,
        vy: 0.0,
        w: 0.1,
    };
    let mut movers = Vec::new();
    while movers.len() < 20 {
        let pos = [rng.range(1.0, 19.0), rng.range(1.0, 19.0)];
        let r = rng.range(0.2, 0.4);
        if ((pos[0] - 10.0f64).powi(2) + (pos[1] - 10.0f64).powi(2)).sqrt() < 3.0 + r
            || map.clearance(pos[0], pos[1]) < r
        {
            continue;
        }
        let (speed, dir) = (
            rng.range(0.0, 0.5),
            rng.range(-std::f64::consts::PI, std::f64::consts::PI),
        );
        movers.push(ObservedMover {
            id: movers.len() as u32,
            pos,
            vel: [speed * dir.cos(), speed * dir.sin()],
            radius: r,
        });
    }
    Scene {
        map,
        movers,
        state,
        goal: [18.0, 16.0],
    }
}

fn bench(c: &mut Criterion) {
    let sc = scene();
    let robot = RobotSpec::default();
    let cfg = DwaConfig {
        v_samples: 20,
        w_samples: 40,
        predict_time: 3.0,
        sim_dt: 0.1,
        ..Default::default()
    };
    let mut core = DwaCore::new(cfg, &robot, "dwa").expect("config");
    let req = StepRequest {
        goal: sc.goal,
        weights: cfg.weights(),
        rho: 1.0,
        hold_v: None,
        braking: false,
    };
    let obs = Observation {
        time: 0.0,
        dt: 0.1,
        state: &sc.state,
        goal: sc.goal,
        map: &sc.map,
        movers: &sc.movers,
        odometry: None,
        accel_z: 0.0,
    };
    // The command is sane: inside the window, from an admissible sample.
    let r = core.plan(&obs, &req);
    let l = robot.limits;
    assert!(r.samples >= 800, "{} samples", r.samples);
    assert!(r.admissible > 0, "no admissible sample");
    assert!(
        (r.cmd.v - sc.state.v).abs() <= l.acc_v * 0.1 + 1e-9,
        "{:?}",
        r.cmd
    );
    assert!(
        (r.cmd.w - sc.state.w).abs() <= l.acc_w * 0.1 + 1e-9,
        "{:?}",
        r.cmd
    );
    eprintln!(
        "dwa step: {} samples, {} admissible, cmd v {:.3} w {:.3}",
        r.samples, r.admissible, r.cmd.v, r.cmd.w
    );
    c.bench_function("dwa_step_20x40_3s_200x200_20movers", |b| {
        b.iter(|| black_box(core.plan(black_box(&obs), &req)))
    });
    // Wall time counts the time other processes hold the core; on a shared
    // machine the thread's own CPU time per step is the figure to compare
    // with the 1 ms bound (Linux only: /proc/thread-self/schedstat).
    if let Some(t0) = thread_cpu_s() {
        let n = 2000;
        for _ in 0..n {
            black_box(core.plan(black_box(&obs), &req));
        }
        if let Some(t1) = thread_cpu_s() {
            eprintln!(
                "dwa step thread CPU time: {:.3} ms (mean of {n})",
                (t1 - t0) / n as f64 * 1e3
            );
        }
    }
    core.set_record(true);
    c.bench_function("dwa_step_20x40_recording", |b| {
        b.iter(|| black_box(core.plan(black_box(&obs), &req)))
    });
}

/// CPU time this thread has run, s (None where /proc is not available).
fn thread_cpu_s() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    let ns: f64 = text.split_whitespace().next()?.parse().ok()?;
    Some(ns * 1e-9)
}

criterion_group!(benches, bench);
criterion_main!(benches);
