//! Obstacle position predictors (\[T\] §4.2.3, §5.2) behind one trait.
//!
//! A [`Track`] is the observed history of one obstacle (time, 3D position;
//! z = 0 in 2D). A [`Predictor`] answers "where will it be `ahead` seconds
//! after the last observation?". Two are provided: [`ConstantVelocity`]
//! and the thesis's recurrent network [`SimpleRnn`].

use glam::DVec3;
use serde::{Deserialize, Serialize};

use super::rnn::SimpleRnn;
use super::ApfError;

/// How many observations a track keeps (older ones are dropped).
pub const TRACK_CAPACITY: usize = 64;

/// Observed positions of one obstacle, oldest first, strictly increasing
/// times.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Track {
    samples: Vec<(f64, DVec3)>,
    /// Velocity reported by the sensor with the newest sample, if any.
    velocity: Option<DVec3>,
}

impl Track {
    /// An empty track.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds an observation at time `t` (s) with an optional measured
    /// velocity (m/s). An observation not later than the newest replaces it
    /// (re-planning at the same instant).
    pub fn push(&mut self, t: f64, pos: DVec3, velocity: Option<DVec3>) {
        if let Some(last) = self.samples.last_mut() {
            if t <= last.0 {
                *last = (last.0, pos);
                self.velocity = velocity;
                return;
            }
        }
        if self.samples.len() == TRACK_CAPACITY {
            self.samples.remove(0);
        }
        self.samples.push((t, pos));
        self.velocity = velocity;
    }

    /// The observations, oldest first.
    pub fn samples(&self) -> &[(f64, DVec3)] {
        &self.samples
    }

    /// The newest observation.
    pub fn last(&self) -> Option<(f64, DVec3)> {
        self.samples.last().copied()
    }

    /// The measured velocity of the newest observation, if the sensor gave
    /// one.
    pub fn measured_velocity(&self) -> Option<DVec3> {
        self.velocity
    }

    /// Velocity from the newest two observations (finite difference).
    pub fn difference_velocity(&self) -> Option<DVec3> {
        let n = self.samples.len();
        if n < 2 {
            return None;
        }
        let (t1, p1) = self.samples[n - 1];
        let (t0, p0) = self.samples[n - 2];
        Some((p1 - p0) / (t1 - t0))
    }

    /// `n` positions evenly spaced by `period` s ending at the newest
    /// observation (oldest first), linearly interpolated between
    /// observations; `None` when the track does not reach back far enough.
    pub fn resample(&self, period: f64, n: usize) -> Option<Vec<DVec3>> {
        let (t_end, _) = self.last()?;
        let t_start = t_end - period * (n.saturating_sub(1)) as f64;
        if self.samples[0].0 > t_start + 1e-9 {
            return None;
        }
        let mut out = Vec::with_capacity(n);
        let mut j = 0;
        for i in 0..n {
            let t = t_start + period * i as f64;
            while j + 1 < self.samples.len() && self.samples[j + 1].0 < t {
                j += 1;
            }
            let (ta, pa) = self.samples[j];
            let p = match self.samples.get(j + 1) {
                Some(&(tb, pb)) if tb > ta => {
                    let s = ((t - ta) / (tb - ta)).clamp(0.0, 1.0);
                    pa + (pb - pa) * s
                }
                _ => pa,
            };
            out.push(p);
        }
        Some(out)
    }
}

/// Predicts where an obstacle will be.
pub trait Predictor: Send + Sync {
    /// Registry name (`constant-velocity`, `rnn`).
    fn name(&self) -> &'static str;
    /// Position `ahead` seconds after the newest observation of `track`;
    /// `None` when the track is empty.
    fn predict(&self, track: &Track, ahead: f64) -> Option<DVec3>;
    /// Positions `ahead` seconds later for each of `aheads`, in order
    /// (predictors that do one inference for several horizons override
    /// it); empty when the track is empty.
    fn predict_many(&self, track: &Track, aheads: &[f64]) -> Vec<DVec3> {
        aheads
            .iter()
            .filter_map(|&a| self.predict(track, a))
            .collect()
    }
}

/// Constant velocity: p + v·ahead, with the sensor's velocity when given,
/// else the finite difference of the last two observations (0 for a single
/// observation).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ConstantVelocity;

impl Predictor for ConstantVelocity {
    fn name(&self) -> &'static str {
        "constant-velocity"
    }
    fn predict(&self, track: &Track, ahead: f64) -> Option<DVec3> {
        let (_, p) = track.last()?;
        let v = track
            .measured_velocity()
            .or_else(|| track.difference_velocity())
            .unwrap_or(DVec3::ZERO);
        Some(p + v * ahead)
    }
}

/// Which predictor an APF config uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum PredictorKind {
    /// [`ConstantVelocity`].
    #[default]
    ConstantVelocity,
    /// [`SimpleRnn`] with the shipped weights (`assets/predictor/rnn.json`).
    Rnn,
}

impl PredictorKind {
    /// Builds the predictor (the RNN from the weights compiled into the
    /// crate).
    pub fn build(self) -> Result<Box<dyn Predictor>, ApfError> {
        Ok(match self {
            PredictorKind::ConstantVelocity => Box::new(ConstantVelocity),
            PredictorKind::Rnn => Box::new(SimpleRnn::shipped()?),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn resample_interpolates_and_refuses_short_tracks() {
        let mut t = Track::new();
        for i in 0..5 {
            t.push(i as f64 * 0.2, DVec3::new(i as f64, 0.0, 0.0), None);
        }
        let r = t.resample(0.1, 5).unwrap();
        let xs: Vec<f64> = r.iter().map(|p| p.x).collect();
        for (a, b) in xs.iter().zip([2.0, 2.5, 3.0, 3.5, 4.0]) {
            assert!((a - b).abs() < 1e-9, "{xs:?}");
        }
        assert!(t.resample(0.1, 9).is_some());
        assert!(t.resample(0.1, 10).is_none());
    }

    #[test]
    fn constant_velocity_extrapolates_linearly() {
        let mut t = Track::new();
        t.push(0.0, DVec3::new(0.0, 0.0, 0.0), None);
        t.push(0.1, DVec3::new(0.02, -0.01, 0.0), None);
        let p = ConstantVelocity.predict(&t, 0.5).unwrap();
        assert!((p - DVec3::new(0.12, -0.06, 0.0)).length() < 1e-12);
        t.push(
            0.2,
            DVec3::new(0.04, -0.02, 0.0),
            Some(DVec3::new(1.0, 0.0, 0.0)),
        );
        let p = ConstantVelocity.predict(&t, 0.5).unwrap();
        assert!((p - DVec3::new(0.54, -0.02, 0.0)).length() < 1e-12);
        assert!(ConstantVelocity.predict(&Track::new(), 0.5).is_none());
    }
}
