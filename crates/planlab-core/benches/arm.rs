//! Criterion benchmark of the arm's inverse kinematics: one IK step is one
//! damped-least-squares solve that moves the TIAGo-like arm's tool 0.04 m
//! along a path (\[T\] §5.3.3), from the posture of the previous step. The
//! bound to meet is absolute (< 50 µs native); a single DLS iteration and
//! forward kinematics are measured beside it. Every solve is checked to
//! converge.

use criterion::{criterion_group, criterion_main, Criterion};
use glam::DVec3;
use planlab_core::arm::{ArmModel, IkConfig};
use std::hint::black_box;

/// Postures along a 0.04 m-step path across the robot's front, with the
/// step target of each.
fn path() -> (ArmModel, Vec<(Vec<f64>, DVec3)>) {
    let m = ArmModel::tiago();
    let cfg = IkConfig::default();
    let start = DVec3::new(0.45, 0.0, 1.0);
    let goal = DVec3::new(0.6, 0.35, 0.8);
    let mut q = m.home().to_vec();
    let r = m.ik_solve(
        &mut q,
        start,
        &IkConfig {
            max_iters: 400,
            ..cfg
        },
    );
    assert!(r.converged, "{r:?}");
    let n = ((goal - start).length() / 0.04).ceil() as usize;
    let mut steps = Vec::new();
    for k in 1..=n {
        let p = start + (goal - start) * (k as f64 / n as f64);
        steps.push((q.clone(), p));
        let r = m.ik_solve(&mut q, p, &cfg);
        assert!(r.converged, "{r:?}");
    }
    (m, steps)
}

fn bench(c: &mut Criterion) {
    let (m, steps) = path();
    let cfg = IkConfig::default();
    let mut g = c.benchmark_group("arm");
    g.bench_function("ik_step_0.04m", |b| {
        let mut i = 0;
        b.iter(|| {
            let (q0, p) = &steps[i % steps.len()];
            i += 1;
            let mut q = q0.clone();
            let r = m.ik_solve(&mut q, *p, &cfg);
            assert!(r.converged);
            black_box(q)
        })
    });
    g.bench_function("ik_iteration", |b| {
        let (q0, p) = &steps[steps.len() / 2];
        b.iter(|| {
            let mut q = q0.clone();
            black_box(m.ik_iteration(&mut q, *p, &cfg))
        })
    });
    g.bench_function("fk", |b| {
        let (q0, _) = &steps[0];
        b.iter(|| black_box(m.fk(black_box(q0)).tool))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
