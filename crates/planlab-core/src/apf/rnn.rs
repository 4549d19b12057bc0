//! The thesis's obstacle predictor (\[T\] §5.2): a SimpleRNN, input 6
//! (position, velocity), 15 tanh units, output 3 (the position 5 samples =
//! 0.5 s ahead), 5 history steps sampled every 0.1 s; trained natively
//! (seeded, BPTT, Adam, batch 100, MSE) on synthetic hand-reaching
//! trajectories ([`hand_reaches`]).
//!
//! **Decision** (the thesis feeds raw positions): the network sees
//! positions relative to the newest one and predicts the displacement, so
//! it is translation invariant and serves 2D scenes (z = 0) as well as the
//! hand above the table. Inputs and output are scaled by constants stored
//! with the weights. Inference is pure and deterministic (`crate::num`
//! tanh); a track too short for 6 samples falls back to constant velocity,
//! and horizons other than 0.5 s scale the predicted displacement linearly.

// Matrix code reads clearer with explicit indices.
#![allow(clippy::needless_range_loop)]

use glam::DVec3;
use serde::{Deserialize, Serialize};

use super::predict::{ConstantVelocity, Predictor, Track};
use super::ApfError;
use crate::num::{sin, tanh, Rng};

/// Input width: relative position (3) and velocity (3).
pub const INPUT: usize = 6;
/// SimpleRNN units.
pub const HIDDEN: usize = 15;
/// Output width: the displacement 0.5 s ahead.
pub const OUTPUT: usize = 3;
/// History steps fed to the network.
pub const HISTORY: usize = 5;
/// Sample period of the history, s.
pub const SAMPLE_DT: f64 = 0.1;
/// Prediction horizon: 5 samples ahead, s.
pub const HORIZON: f64 = 0.5;
/// Format tag of the weights JSON.
pub const FORMAT: &str = "planlab-simple-rnn-1";

const SHIPPED: &str = include_str!("../../../../assets/predictor/rnn.json");

/// How the shipped weights were made and how well they predict.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
pub struct TrainReport {
    /// Seed of the data and the initial weights.
    pub seed: u64,
    /// Passes over the training set.
    pub epochs: u32,
    /// Training windows.
    pub train_samples: usize,
    /// Held-out windows (a different seed's trajectories).
    pub heldout_samples: usize,
    /// Training MSE at the end, m².
    pub train_mse: f64,
    /// Held-out MSE of the RNN, m².
    pub heldout_mse: f64,
    /// Held-out MSE of constant velocity, m².
    pub heldout_mse_constant_velocity: f64,
}

/// The network's parameters (row-major matrices) and scales, as stored in
/// `assets/predictor/rnn.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RnnWeights {
    /// Must be [`FORMAT`].
    pub format: String,
    /// Relative positions are multiplied by this, 1/m.
    pub pos_scale: f64,
    /// Velocities are multiplied by this, s/m.
    pub vel_scale: f64,
    /// The output is the displacement times this, 1/m.
    pub out_scale: f64,
    /// Input → hidden, HIDDEN × INPUT.
    pub w_xh: Vec<f64>,
    /// Hidden → hidden, HIDDEN × HIDDEN.
    pub w_hh: Vec<f64>,
    /// Hidden bias, HIDDEN.
    pub b_h: Vec<f64>,
    /// Hidden → output, OUTPUT × HIDDEN.
    pub w_hy: Vec<f64>,
    /// Output bias, OUTPUT.
    pub b_y: Vec<f64>,
    /// Training record.
    #[serde(default)]
    pub report: TrainReport,
}

impl RnnWeights {
    /// Checks the format, the shapes and that every number is finite.
    pub fn validate(&self) -> Result<(), ApfError> {
        if self.format != FORMAT {
            return Err(ApfError::BadWeights(format!(
                "format `{}`, expected `{FORMAT}`",
                self.format
            )));
        }
        for (name, v, n) in [
            ("w_xh", &self.w_xh, HIDDEN * INPUT),
            ("w_hh", &self.w_hh, HIDDEN * HIDDEN),
            ("b_h", &self.b_h, HIDDEN),
            ("w_hy", &self.w_hy, OUTPUT * HIDDEN),
            ("b_y", &self.b_y, OUTPUT),
        ] {
            if v.len() != n {
                return Err(ApfError::BadWeights(format!(
                    "{name} has {} numbers, expected {n}",
                    v.len()
                )));
            }
            if !v.iter().all(|x| x.is_finite()) {
                return Err(ApfError::BadWeights(format!("{name} is not finite")));
            }
        }
        for (name, s) in [
            ("pos_scale", self.pos_scale),
            ("vel_scale", self.vel_scale),
            ("out_scale", self.out_scale),
        ] {
            if !(s.is_finite() && s > 0.0) {
                return Err(ApfError::BadWeights(format!("{name} = {s}: must be > 0")));
            }
        }
        Ok(())
    }

    /// Small random weights (seeded), Xavier-uniform.
    pub fn random(rng: &mut Rng) -> Self {
        let mut fill = |n: usize, fan_in: usize, fan_out: usize| -> Vec<f64> {
            let a = (6.0 / (fan_in + fan_out) as f64).sqrt();
            (0..n).map(|_| rng.range(-a, a)).collect()
        };
        RnnWeights {
            format: FORMAT.into(),
            pos_scale: 5.0,
            vel_scale: 2.0,
            out_scale: 5.0,
            w_xh: fill(HIDDEN * INPUT, INPUT, HIDDEN),
            w_hh: fill(HIDDEN * HIDDEN, HIDDEN, HIDDEN)
                .into_iter()
                .map(|x| 0.5 * x)
                .collect(),
            b_h: vec![0.0; HIDDEN],
            w_hy: fill(OUTPUT * HIDDEN, HIDDEN, OUTPUT),
            b_y: vec![0.0; OUTPUT],
            report: TrainReport::default(),
        }
    }

    /// Network inputs of a window of 6 positions (oldest first, spaced by
    /// [`SAMPLE_DT`]): 5 steps of (relative position, velocity).
    pub fn features(&self, window: &[DVec3; HISTORY + 1]) -> [[f64; INPUT]; HISTORY] {
        let last = window[HISTORY];
        let mut x = [[0.0; INPUT]; HISTORY];
        for (t, xt) in x.iter_mut().enumerate() {
            let p = window[t + 1];
            let r = (p - last) * self.pos_scale;
            let v = (p - window[t]) * (self.vel_scale / SAMPLE_DT);
            *xt = [r.x, r.y, r.z, v.x, v.y, v.z];
        }
        x
    }

    /// Forward pass: the hidden states h_1…h_5 (h_0 = 0) and the output.
    fn forward(
        &self,
        x: &[[f64; INPUT]; HISTORY],
    ) -> ([[f64; HIDDEN]; HISTORY + 1], [f64; OUTPUT]) {
        let mut h = [[0.0; HIDDEN]; HISTORY + 1];
        for t in 0..HISTORY {
            for i in 0..HIDDEN {
                let mut a = self.b_h[i];
                for (j, xj) in x[t].iter().enumerate() {
                    a += self.w_xh[i * INPUT + j] * xj;
                }
                for j in 0..HIDDEN {
                    a += self.w_hh[i * HIDDEN + j] * h[t][j];
                }
                h[t + 1][i] = tanh(a);
            }
        }
        let mut y = [0.0; OUTPUT];
        for (k, yk) in y.iter_mut().enumerate() {
            let mut a = self.b_y[k];
            for j in 0..HIDDEN {
                a += self.w_hy[k * HIDDEN + j] * h[HISTORY][j];
            }
            *yk = a;
        }
        (h, y)
    }

    /// The predicted position [`HORIZON`] after the newest of `window`.
    pub fn predict_window(&self, window: &[DVec3; HISTORY + 1]) -> DVec3 {
        let (_, y) = self.forward(&self.features(window));
        window[HISTORY] + DVec3::new(y[0], y[1], y[2]) * (1.0 / self.out_scale)
    }
}

/// The SimpleRNN predictor (validated weights).
#[derive(Debug, Clone, PartialEq)]
pub struct SimpleRnn {
    w: RnnWeights,
}

impl SimpleRnn {
    /// From validated weights.
    pub fn new(w: RnnWeights) -> Result<Self, ApfError> {
        w.validate()?;
        Ok(Self { w })
    }

    /// From a weights JSON text.
    pub fn from_json(text: &str) -> Result<Self, ApfError> {
        let w: RnnWeights =
            serde_json::from_str(text).map_err(|e| ApfError::BadWeights(e.to_string()))?;
        Self::new(w)
    }

    /// The weights shipped in `assets/predictor/rnn.json` (compiled in).
    pub fn shipped() -> Result<Self, ApfError> {
        Self::from_json(SHIPPED)
    }

    /// The weights.
    pub fn weights(&self) -> &RnnWeights {
        &self.w
    }
}

impl Predictor for SimpleRnn {
    fn name(&self) -> &'static str {
        "rnn"
    }
    fn predict(&self, track: &Track, ahead: f64) -> Option<DVec3> {
        let Some(ps) = track.resample(SAMPLE_DT, HISTORY + 1) else {
            return ConstantVelocity.predict(track, ahead);
        };
        let window: [DVec3; HISTORY + 1] = ps.try_into().ok()?;
        let last = window[HISTORY];
        let p = self.w.predict_window(&window);
        Some(last + (p - last) * (ahead / HORIZON))
    }
    fn predict_many(&self, track: &Track, aheads: &[f64]) -> Vec<DVec3> {
        let Some(ps) = track.resample(SAMPLE_DT, HISTORY + 1) else {
            return ConstantVelocity.predict_many(track, aheads);
        };
        let Ok(window) = <[DVec3; HISTORY + 1]>::try_from(ps) else {
            return Vec::new();
        };
        let last = window[HISTORY];
        let d = self.w.predict_window(&window) - last;
        aheads.iter().map(|a| last + d * (a / HORIZON)).collect()
    }
}

/// One training / test example: 6 positions spaced by [`SAMPLE_DT`] and the
/// position [`HORIZON`] after the newest.
pub type Window = ([DVec3; HISTORY + 1], DVec3);

/// Synthetic hand-reaching trajectories sampled every [`SAMPLE_DT`]
/// (seeded): each of `n` trajectories is 6 reaches between random points
/// over a table (x 0.6…1.1, y −0.3…0.3, z 0.7…1.0 m), each a
/// minimum-jerk profile of 0.8–2 s with a sideways bow of up to 0.08 m,
/// followed by a pause of 0–0.6 s; positions carry 2 mm Gaussian noise
/// (a tracker's).
pub fn hand_reaches(seed: u64, n: usize) -> Vec<Vec<DVec3>> {
    let mut rng = Rng::new(seed);
    let point = |rng: &mut Rng| {
        DVec3::new(
            rng.range(0.6, 1.1),
            rng.range(-0.3, 0.3),
            rng.range(0.7, 1.0),
        )
    };
    let mut out = Vec::with_capacity(n);
    for _ in 0..n {
        let mut traj = Vec::new();
        let mut from = point(&mut rng);
        let mut t_in = 0.0; // time into the current segment
        for _ in 0..6 {
            let to = point(&mut rng);
            let dur = rng.range(0.8, 2.0);
            let pause = rng.range(0.0, 0.6);
            let d = to - from;
            let side = d.cross(DVec3::Z).normalize_or(DVec3::Y);
            let bow = side * rng.range(-0.08, 0.08);
            while t_in < dur + pause {
                let s = (t_in / dur).min(1.0);
                let m = s * s * s * (10.0 - 15.0 * s + 6.0 * s * s);
                let p = from + d * m + bow * sin(std::f64::consts::PI * m);
                traj.push(p);
                t_in += SAMPLE_DT;
            }
            t_in -= dur + pause;
            from = to;
        }
        for p in &mut traj {
            *p += DVec3::new(rng.normal(), rng.normal(), rng.normal()) * 0.002;
        }
        out.push(traj);
    }
    out
}

/// Every window of every trajectory.
pub fn windows(trajs: &[Vec<DVec3>]) -> Vec<Window> {
    let ahead = (HORIZON / SAMPLE_DT).round() as usize;
    let mut out = Vec::new();
    for tr in trajs {
        for k in HISTORY..tr.len().saturating_sub(ahead) {
            let mut w = [DVec3::ZERO; HISTORY + 1];
            w.copy_from_slice(&tr[k - HISTORY..=k]);
            out.push((w, tr[k + ahead]));
        }
    }
    out
}

/// Mean squared error (over samples and the 3 coordinates), m², of a
/// predictor given as a function of the window.
pub fn mse(data: &[Window], f: impl Fn(&[DVec3; HISTORY + 1]) -> DVec3) -> f64 {
    if data.is_empty() {
        return 0.0;
    }
    let s: f64 = data.iter().map(|(w, y)| (f(w) - *y).length_squared()).sum();
    s / (3 * data.len()) as f64
}

/// Constant velocity on a window (last difference).
pub fn constant_velocity(w: &[DVec3; HISTORY + 1]) -> DVec3 {
    let v = (w[HISTORY] - w[HISTORY - 1]) / SAMPLE_DT;
    w[HISTORY] + v * HORIZON
}

/// Gradients of the batch loss, laid out like the weights.
#[derive(Debug, Clone, PartialEq)]
pub struct Grads {
    /// d loss / d w_xh.
    pub w_xh: Vec<f64>,
    /// d loss / d w_hh.
    pub w_hh: Vec<f64>,
    /// d loss / d b_h.
    pub b_h: Vec<f64>,
    /// d loss / d w_hy.
    pub w_hy: Vec<f64>,
    /// d loss / d b_y.
    pub b_y: Vec<f64>,
}

impl Grads {
    fn zero() -> Self {
        Grads {
            w_xh: vec![0.0; HIDDEN * INPUT],
            w_hh: vec![0.0; HIDDEN * HIDDEN],
            b_h: vec![0.0; HIDDEN],
            w_hy: vec![0.0; OUTPUT * HIDDEN],
            b_y: vec![0.0; OUTPUT],
        }
    }
}

/// The training loss of a batch (MSE of the scaled output, mean over
/// samples and coordinates) and its gradient by backpropagation through
/// time.
pub fn loss_and_grads(w: &RnnWeights, batch: &[Window]) -> (f64, Grads) {
    let mut g = Grads::zero();
    let mut loss = 0.0;
    let norm = 1.0 / (OUTPUT * batch.len().max(1)) as f64;
    for (win, target) in batch {
        let x = w.features(win);
        let (h, y) = w.forward(&x);
        let t = (*target - win[HISTORY]) * w.out_scale;
        let t = [t.x, t.y, t.z];
        let mut dy = [0.0; OUTPUT];
        for k in 0..OUTPUT {
            let e = y[k] - t[k];
            loss += e * e * norm;
            dy[k] = 2.0 * e * norm;
        }
        let mut dh = [0.0; HIDDEN];
        for k in 0..OUTPUT {
            g.b_y[k] += dy[k];
            for j in 0..HIDDEN {
                g.w_hy[k * HIDDEN + j] += dy[k] * h[HISTORY][j];
                dh[j] += w.w_hy[k * HIDDEN + j] * dy[k];
            }
        }
        for step in (0..HISTORY).rev() {
            let mut da = [0.0; HIDDEN];
            for i in 0..HIDDEN {
                let hi = h[step + 1][i];
                da[i] = dh[i] * (1.0 - hi * hi);
            }
            let mut dprev = [0.0; HIDDEN];
            for i in 0..HIDDEN {
                g.b_h[i] += da[i];
                for j in 0..INPUT {
                    g.w_xh[i * INPUT + j] += da[i] * x[step][j];
                }
                for j in 0..HIDDEN {
                    g.w_hh[i * HIDDEN + j] += da[i] * h[step][j];
                    dprev[j] += w.w_hh[i * HIDDEN + j] * da[i];
                }
            }
            dh = dprev;
        }
    }
    (loss, g)
}

/// Most passes over the training set (the shipped weights take 60).
pub const MAX_TRAIN_EPOCHS: usize = 10_000;
/// Most training (or held-out) trajectories (the shipped weights take 80).
pub const MAX_TRAIN_TRAJECTORIES: usize = 10_000;
/// Largest Adam batch.
pub const MAX_TRAIN_BATCH: usize = 100_000;

/// Training settings of `planlab train-predictor`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct TrainConfig {
    /// Seed of the data, the initial weights and the shuffling.
    pub seed: u64,
    /// Training trajectories (6 reaches each).
    pub trajectories: usize,
    /// Held-out trajectories (seed + 1).
    pub heldout_trajectories: usize,
    /// Passes over the training set.
    pub epochs: u32,
    /// Samples per Adam step (\[T\]: 100).
    pub batch: usize,
    /// Adam step size.
    pub learning_rate: f64,
}

impl Default for TrainConfig {
    fn default() -> Self {
        Self {
            seed: 7,
            trajectories: 80,
            heldout_trajectories: 30,
            epochs: 60,
            batch: 100,
            learning_rate: 0.003,
        }
    }
}

/// Trains the SimpleRNN (Adam, BPTT, MSE, shuffled batches; learning rate
/// halved for the last third) and evaluates it and constant velocity on
/// held-out trajectories. Deterministic for a config.
pub fn train(cfg: &TrainConfig) -> Result<RnnWeights, ApfError> {
    for (name, n, max) in [
        ("epochs", cfg.epochs as usize, MAX_TRAIN_EPOCHS),
        ("trajectories", cfg.trajectories, MAX_TRAIN_TRAJECTORIES),
        (
            "heldout_trajectories",
            cfg.heldout_trajectories,
            MAX_TRAIN_TRAJECTORIES,
        ),
        ("batch", cfg.batch, MAX_TRAIN_BATCH),
    ] {
        if n == 0 || n > max {
            return Err(ApfError::InvalidParameter(format!(
                "train: {name} = {n}: must be from 1 to {max}"
            )));
        }
    }
    if !(cfg.learning_rate.is_finite() && cfg.learning_rate > 0.0) {
        return Err(ApfError::InvalidParameter(format!(
            "train: learning_rate = {} must be > 0",
            cfg.learning_rate
        )));
    }
    let data = windows(&hand_reaches(cfg.seed, cfg.trajectories));
    let heldout = windows(&hand_reaches(
        cfg.seed.wrapping_add(1),
        cfg.heldout_trajectories,
    ));
    let mut rng = Rng::new(cfg.seed ^ 0x5EED);
    let mut w = RnnWeights::random(&mut rng);
    let n_params = HIDDEN * INPUT + HIDDEN * HIDDEN + HIDDEN + OUTPUT * HIDDEN + OUTPUT;
    let (mut m, mut v) = (vec![0.0; n_params], vec![0.0; n_params]);
    let (b1, b2, eps) = (0.9, 0.999, 1e-8);
    let mut order: Vec<usize> = (0..data.len()).collect();
    let mut step = 0i32;
    let mut batch = Vec::with_capacity(cfg.batch);
    for epoch in 0..cfg.epochs {
        // Fisher–Yates with the seeded generator.
        for i in (1..order.len()).rev() {
            let j = (rng.next_u64() % (i as u64 + 1)) as usize;
            order.swap(i, j);
        }
        let lr = if epoch >= cfg.epochs * 2 / 3 {
            0.5 * cfg.learning_rate
        } else {
            cfg.learning_rate
        };
        for chunk in order.chunks(cfg.batch) {
            batch.clear();
            batch.extend(chunk.iter().map(|&i| data[i]));
            let (_, g) = loss_and_grads(&w, &batch);
            step += 1;
            let (c1, c2) = (
                1.0 - crate::num::pow(b1, step as f64),
                1.0 - crate::num::pow(b2, step as f64),
            );
            let params = [
                (&mut w.w_xh, &g.w_xh),
                (&mut w.w_hh, &g.w_hh),
                (&mut w.b_h, &g.b_h),
                (&mut w.w_hy, &g.w_hy),
                (&mut w.b_y, &g.b_y),
            ];
            let mut k = 0;
            for (p, gp) in params {
                for (pi, gi) in p.iter_mut().zip(gp) {
                    m[k] = b1 * m[k] + (1.0 - b1) * gi;
                    v[k] = b2 * v[k] + (1.0 - b2) * gi * gi;
                    *pi -= lr * (m[k] / c1) / ((v[k] / c2).sqrt() + eps);
                    k += 1;
                }
            }
        }
    }
    w.report = TrainReport {
        seed: cfg.seed,
        epochs: cfg.epochs,
        train_samples: data.len(),
        heldout_samples: heldout.len(),
        train_mse: mse(&data, |x| w.predict_window(x)),
        heldout_mse: mse(&heldout, |x| w.predict_window(x)),
        heldout_mse_constant_velocity: mse(&heldout, constant_velocity),
    };
    w.validate()?;
    Ok(w)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn param(w: &mut RnnWeights, which: usize) -> &mut Vec<f64> {
        match which {
            0 => &mut w.w_xh,
            1 => &mut w.w_hh,
            2 => &mut w.b_h,
            3 => &mut w.w_hy,
            _ => &mut w.b_y,
        }
    }

    fn grad(g: &Grads, which: usize) -> &[f64] {
        match which {
            0 => &g.w_xh,
            1 => &g.w_hh,
            2 => &g.b_h,
            3 => &g.w_hy,
            _ => &g.b_y,
        }
    }

    #[test]
    fn bptt_gradient_matches_finite_differences() {
        let mut rng = Rng::new(3);
        let w = RnnWeights::random(&mut rng);
        let batch: Vec<Window> = windows(&hand_reaches(11, 2)).into_iter().take(7).collect();
        let (_, g) = loss_and_grads(&w, &batch);
        let h = 1e-6;
        let mut checked = 0;
        for which in 0..5 {
            let n = grad(&g, which).len();
            // A spread of entries of every parameter (all of the small ones).
            for i in (0..n).step_by((n / 9).max(1)) {
                let analytic = grad(&g, which)[i];
                let mut wp = w.clone();
                let base = param(&mut wp, which)[i];
                param(&mut wp, which)[i] = base + h;
                let lp = loss_and_grads(&wp, &batch).0;
                param(&mut wp, which)[i] = base - h;
                let lm = loss_and_grads(&wp, &batch).0;
                let numeric = (lp - lm) / (2.0 * h);
                let rel = (numeric - analytic).abs() / numeric.abs().max(analytic.abs()).max(1e-7);
                assert!(
                    rel < 1e-5,
                    "param {which}[{i}]: numeric {numeric}, bptt {analytic}"
                );
                checked += 1;
            }
        }
        assert!(checked > 40);
    }

    #[test]
    fn a_short_training_run_lowers_the_loss_and_is_deterministic() {
        let cfg = TrainConfig {
            trajectories: 8,
            heldout_trajectories: 4,
            epochs: 4,
            ..TrainConfig::default()
        };
        let a = train(&cfg).unwrap();
        let b = train(&cfg).unwrap();
        assert_eq!(a, b);
        let data = windows(&hand_reaches(cfg.seed, cfg.trajectories));
        let init = RnnWeights::random(&mut Rng::new(cfg.seed ^ 0x5EED));
        let before = mse(&data, |x| init.predict_window(x));
        assert!(
            a.report.train_mse < 0.7 * before,
            "{} vs {before}",
            a.report.train_mse
        );
        assert!(train(&TrainConfig { batch: 0, ..cfg }).is_err());
    }

    #[test]
    fn shipped_rnn_beats_constant_velocity_on_unseen_reaches() {
        let rnn = SimpleRnn::shipped().unwrap();
        // A seed neither training (7) nor its held-out set (8) used.
        let test = windows(&hand_reaches(4242, 12));
        let m_rnn = mse(&test, |w| rnn.weights().predict_window(w));
        let m_cv = mse(&test, constant_velocity);
        assert!(m_rnn < 0.8 * m_cv, "RNN {m_rnn} vs CV {m_cv}");
        let r = &rnn.weights().report;
        assert!(r.heldout_mse < r.heldout_mse_constant_velocity, "{r:?}");
    }

    #[test]
    fn the_predictor_reads_tracks_and_scales_other_horizons() {
        let rnn = SimpleRnn::shipped().unwrap();
        let traj = &hand_reaches(5, 1)[0];
        let mut track = Track::new();
        for (i, p) in traj.iter().take(12).enumerate() {
            track.push(i as f64 * SAMPLE_DT, *p, None);
        }
        let mut w = [DVec3::ZERO; HISTORY + 1];
        w.copy_from_slice(&traj[6..12]);
        let direct = rnn.weights().predict_window(&w);
        let via = rnn.predict(&track, HORIZON).unwrap();
        assert!((direct - via).length() < 1e-9);
        let half = rnn.predict(&track, 0.5 * HORIZON).unwrap();
        assert!((half - (w[HISTORY] + (direct - w[HISTORY]) * 0.5)).length() < 1e-9);
        // Too short for the network: constant velocity.
        let mut short = Track::new();
        short.push(0.0, DVec3::ZERO, None);
        short.push(0.1, DVec3::X * 0.01, None);
        assert!((rnn.predict(&short, 0.5).unwrap() - DVec3::X * 0.06).length() < 1e-9);
    }

    #[test]
    fn bad_weights_are_typed_errors() {
        let mut w = RnnWeights::random(&mut Rng::new(1));
        w.b_h.pop();
        assert!(SimpleRnn::new(w.clone())
            .unwrap_err()
            .to_string()
            .contains("b_h"));
        w.b_h.push(f64::NAN);
        assert!(SimpleRnn::new(w)
            .unwrap_err()
            .to_string()
            .contains("finite"));
        assert!(SimpleRnn::from_json("{").is_err());
        assert!(SimpleRnn::from_json(r#"{"format":"x"}"#).is_err());
    }
}
