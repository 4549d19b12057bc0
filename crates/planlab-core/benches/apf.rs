//! Criterion benchmark of one sampling-APF step with prediction (docs/algorithms.md §apf:
//! < 20 µs native): 3D, 13 sampled directions, 5 spheres of which 2 move
//! (t+1 / t+2 virtual copies), with the constant-velocity and the RNN
//! predictor; the basic step is measured beside it as the peer. Each
//! planner carries 10 observations of history, as in a run; the chosen
//! step is checked inside.

use criterion::{criterion_group, criterion_main, Criterion};
use glam::DVec3;
use planlab_core::apf::{Apf, ApfConfig, ApfMode, ObstacleObs, PredictorKind};
use std::hint::black_box;

fn obstacles(t: f64) -> Vec<ObstacleObs<DVec3>> {
    let moving = |id, c: DVec3, v: DVec3| ObstacleObs::moving(id, c + v * t, 0.05, v);
    vec![
        moving(0, DVec3::new(0.55, 0.0, 0.76), DVec3::new(-0.08, 0.0, 0.0)),
        moving(1, DVec3::new(0.4, 0.3, 0.9), DVec3::new(0.0, -0.1, 0.0)),
        ObstacleObs::fixed(2, DVec3::new(0.3, -0.2, 0.8), 0.05),
        ObstacleObs::fixed(3, DVec3::new(0.6, 0.2, 0.7), 0.04),
        ObstacleObs::fixed(4, DVec3::new(0.2, 0.1, 1.0), 0.06),
    ]
}

fn planner(mode: ApfMode, predictor: PredictorKind) -> Apf<DVec3> {
    let mut apf = Apf::new(ApfConfig {
        mode,
        predictor,
        ..ApfConfig::default()
    })
    .expect("config");
    for i in 0..10 {
        let t = i as f64 * 0.1;
        apf.observe(t, &obstacles(t));
    }
    apf
}

fn bench(c: &mut Criterion) {
    let pos = DVec3::new(0.3, 0.0, 0.8);
    let goal = DVec3::new(0.7, 0.0, 0.8);
    let obs = obstacles(1.0);
    let mut g = c.benchmark_group("apf_step");
    for (name, mode, pred) in [
        (
            "sampling_prediction_cv",
            ApfMode::SamplingPrediction,
            PredictorKind::ConstantVelocity,
        ),
        (
            "sampling_prediction_rnn",
            ApfMode::SamplingPrediction,
            PredictorKind::Rnn,
        ),
        (
            "sampling",
            ApfMode::Sampling,
            PredictorKind::ConstantVelocity,
        ),
        ("basic", ApfMode::Basic, PredictorKind::ConstantVelocity),
    ] {
        let mut apf = planner(mode, pred);
        let s = apf.step(1.0, pos, goal, &obs).expect("step");
        assert!(((s.next - pos).length() - 0.04).abs() < 1e-9);
        if mode == ApfMode::SamplingPrediction {
            assert_eq!(s.candidates.len(), 13);
            assert!(s.predicted.len() >= 4, "two movers × (t+1, t+2)");
        }
        g.bench_function(name, |b| {
            b.iter(|| black_box(apf.step(1.0, black_box(pos), goal, black_box(&obs))))
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
