//! Odometry error compensation of \[C\] §3.3 (eq 15–18): the least-squares
//! correction K fitted over a sliding window of wheel / laser odometry
//! pairs, and the planner's window of them.

use super::{CleaningDwa, KStructure};
use crate::local::Observation;

/// 3×3 matrix, row-major.
pub type Mat3 = [[f64; 3]; 3];

pub(super) fn mat_vec(k: &Mat3, u: [f64; 3]) -> [f64; 3] {
    [
        k[0][0] * u[0] + k[0][1] * u[1] + k[0][2] * u[2],
        k[1][0] * u[0] + k[1][1] * u[1] + k[1][2] * u[2],
        k[2][0] * u[0] + k[2][1] * u[1] + k[2][2] * u[2],
    ]
}

/// Inverse of `a`, or `None` when it is (numerically) singular: |det| at
/// most 1e-12 × the product of its row norms.
pub(super) fn inverse(a: &Mat3) -> Option<Mat3> {
    let c00 = a[1][1] * a[2][2] - a[1][2] * a[2][1];
    let c01 = a[1][2] * a[2][0] - a[1][0] * a[2][2];
    let c02 = a[1][0] * a[2][1] - a[1][1] * a[2][0];
    let det = a[0][0] * c00 + a[0][1] * c01 + a[0][2] * c02;
    let norms: f64 = a
        .iter()
        .map(|r| (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt())
        .product();
    if !(det.is_finite() && norms.is_finite()) || det.abs() <= 1e-12 * norms || norms == 0.0 {
        return None;
    }
    let inv = 1.0 / det;
    Some([
        [
            c00 * inv,
            (a[0][2] * a[2][1] - a[0][1] * a[2][2]) * inv,
            (a[0][1] * a[1][2] - a[0][2] * a[1][1]) * inv,
        ],
        [
            c01 * inv,
            (a[0][0] * a[2][2] - a[0][2] * a[2][0]) * inv,
            (a[0][2] * a[1][0] - a[0][0] * a[1][2]) * inv,
        ],
        [
            c02 * inv,
            (a[0][1] * a[2][0] - a[0][0] * a[2][1]) * inv,
            (a[0][0] * a[1][1] - a[0][1] * a[1][0]) * inv,
        ],
    ])
}

/// Least-squares K with u* ≈ K u over `pairs` (wheel u, laser u*), pulled
/// toward `prior` with weight `ridge`·tr(Σuuᵀ)/3 (\[C\] eq 17). With
/// `structure` = [`KStructure::Block`] the translation (Δx, Δy) and the
/// rotation Δθ are fitted separately (the cross terms are 0). `None` when
/// the system is singular or the result not finite: keep the prior.
pub fn fit_k(
    pairs: &[([f64; 3], [f64; 3])],
    prior: &Mat3,
    ridge: f64,
    structure: KStructure,
) -> Option<Mat3> {
    let mut a = [[0.0; 3]; 3]; // Σ u uᵀ
    let mut b = [[0.0; 3]; 3]; // Σ u* uᵀ
    for (u, us) in pairs {
        for i in 0..3 {
            for j in 0..3 {
                a[i][j] += u[i] * u[j];
                b[i][j] += us[i] * u[j];
            }
        }
    }
    let mut prior = *prior;
    if structure == KStructure::Block {
        // Block-diagonal normal equations give a block-diagonal K.
        for i in 0..2 {
            for m in [&mut a, &mut b, &mut prior] {
                m[i][2] = 0.0;
                m[2][i] = 0.0;
            }
        }
    }
    let lambda = ridge * (a[0][0] + a[1][1] + a[2][2]) / 3.0;
    for i in 0..3 {
        a[i][i] += lambda;
        for j in 0..3 {
            b[i][j] += lambda * prior[i][j];
        }
    }
    let ai = inverse(&a)?;
    let mut k = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            k[i][j] = b[i][0] * ai[0][j] + b[i][1] * ai[1][j] + b[i][2] * ai[2][j];
        }
    }
    k.iter().flatten().all(|x| x.is_finite()).then_some(k)
}
impl CleaningDwa {
    /// Adds the last period's odometry pair to the window and refits K
    /// once there are enough (a singular fit keeps the previous K).
    pub(super) fn push_odometry(&mut self, obs: &Observation<'_>) {
        let Some(o) = obs.odometry else { return };
        let finite = o.wheel.iter().chain(&o.laser).all(|x| x.is_finite());
        let moved = o.wheel.iter().map(|x| x * x).sum::<f64>() > 1e-12;
        if !(finite && moved) {
            return;
        }
        self.odo.push_back((o.wheel, o.laser));
        while self.odo.len() > self.cfg.window {
            self.odo.pop_front();
        }
        if self.odo.len() >= self.cfg.min_samples.max(3) {
            let pairs: Vec<_> = self.odo.iter().copied().collect();
            if let Some(k) = fit_k(&pairs, &self.k, self.cfg.ridge, self.cfg.k_structure) {
                self.k = k;
            }
        }
    }
}
