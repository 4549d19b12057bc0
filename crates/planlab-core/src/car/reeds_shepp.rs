//! Reeds-Shepp curves (J. A. Reeds, L. A. Shepp, "Optimal paths for a car
//! that goes both forwards and backwards", Pacific Journal of Mathematics
//! 145(2), 1990): the shortest path between two poses for a car with a
//! minimum turning radius that may also reverse.
//!
//! The paper's formulas 8.1–8.11 solve eight base words in the normalised
//! problem (radius 1, start at the origin facing +x, goal `(x, y, φ)`):
//! L⁺S⁺L⁺, L⁺S⁺R⁺ (family CSC), L⁺R⁻L (CCC), L⁺R⁺L⁻R⁻ and L⁺R⁻L⁻R⁺ (CCCC),
//! L⁺R⁻S⁻L⁻ and L⁺R⁻S⁻R⁻ (CCSC, with a quarter turn), L⁺R⁻S⁻L⁻R⁺ (CCSCC,
//! two quarter turns). The other words of the 48 are their images under
//! three symmetries, applied to the goal before solving and undone on the
//! answer, as OMPL's `ReedsSheppStateSpace` does:
//!
//! - **time flip** `(−x, y, −φ)`: every segment driven the other way;
//! - **reflect** `(x, −y, −φ)`: left and right swapped;
//! - **backwards** `(x cos φ + y sin φ, x sin φ − y cos φ, φ)`: the
//!   segments in reverse order.
//!
//! planlab applies all eight combinations to every base word (a superset
//! of the paper's list: duplicates only cost time), keeps the candidates
//! whose segments, driven exactly, end at the goal, and returns the
//! shortest, ties to the first found.

use super::dubins::reaches;
use super::{check_poses, check_radius, local_goal, CarError, CurvePath, Pose, Segment, Steer};
use crate::num::{acos, asin, atan2, cos, hypot, sin, wrap_angle};
use std::f64::consts::{FRAC_PI_2, PI};

/// Slack of the sign conditions (OMPL's `ZERO` is 10 ε; planlab's is
/// looser, the endpoint check catches what it lets through).
const ZERO: f64 = 1e-10;

type Word = Vec<(Steer, f64)>;

/// A base formula: the normalised goal to its word, if it has one.
type Formula = fn(f64, f64, f64) -> Option<Word>;

fn polar(x: f64, y: f64) -> (f64, f64) {
    (hypot(x, y), atan2(y, x))
}

/// The τ, ω of formulas 8.7 and 8.8.
fn tau_omega(u: f64, v: f64, xi: f64, eta: f64, phi: f64) -> (f64, f64) {
    let delta = wrap_angle(u - v);
    let a = sin(u) - sin(delta);
    let b = cos(u) - cos(delta) - 1.0;
    let t1 = atan2(eta * a - xi * b, xi * a + eta * b);
    let t2 = 2.0 * (cos(delta) - cos(v) - cos(u)) + 3.0;
    let tau = if t2 < 0.0 {
        wrap_angle(t1 + PI)
    } else {
        wrap_angle(t1)
    };
    (tau, wrap_angle(tau - u + v - phi))
}

use Steer::{Left as L, Right as R, Straight as S};

/// 8.1: L⁺S⁺L⁺.
fn lsl(x: f64, y: f64, phi: f64) -> Option<Word> {
    let (u, t) = polar(x - sin(phi), y - 1.0 + cos(phi));
    let v = wrap_angle(phi - t);
    (t >= -ZERO && v >= -ZERO).then(|| vec![(L, t), (S, u), (L, v)])
}

/// 8.2: L⁺S⁺R⁺.
fn lsr(x: f64, y: f64, phi: f64) -> Option<Word> {
    let (u1, t1) = polar(x + sin(phi), y - 1.0 - cos(phi));
    let u1 = u1 * u1;
    if u1 < 4.0 {
        return None;
    }
    let u = (u1 - 4.0).sqrt();
    let t = wrap_angle(t1 + atan2(2.0, u));
    let v = wrap_angle(t - phi);
    (t >= -ZERO && v >= -ZERO).then(|| vec![(L, t), (S, u), (R, v)])
}

/// 8.3/8.4: L⁺R⁻L.
fn lrl(x: f64, y: f64, phi: f64) -> Option<Word> {
    let (u1, th) = polar(x - sin(phi), y - 1.0 + cos(phi));
    if u1 > 4.0 {
        return None;
    }
    let u = -2.0 * asin(0.25 * u1);
    let t = wrap_angle(th + 0.5 * u + PI);
    let v = wrap_angle(phi - t + u);
    (t >= -ZERO && u <= ZERO).then(|| vec![(L, t), (R, u), (L, v)])
}

/// 8.7: L⁺R⁺L⁻R⁻.
fn lrlr_a(x: f64, y: f64, phi: f64) -> Option<Word> {
    let (xi, eta) = (x + sin(phi), y - 1.0 - cos(phi));
    let rho = 0.25 * (2.0 + hypot(xi, eta));
    if rho > 1.0 {
        return None;
    }
    let u = acos(rho);
    let (t, v) = tau_omega(u, -u, xi, eta, phi);
    (t >= -ZERO && v <= ZERO).then(|| vec![(L, t), (R, u), (L, -u), (R, v)])
}

/// 8.8: L⁺R⁻L⁻R⁺.
fn lrlr_b(x: f64, y: f64, phi: f64) -> Option<Word> {
    let (xi, eta) = (x + sin(phi), y - 1.0 - cos(phi));
    let rho = (20.0 - xi * xi - eta * eta) / 16.0;
    if !(0.0..=1.0).contains(&rho) {
        return None;
    }
    let u = -acos(rho);
    if u < -FRAC_PI_2 {
        return None;
    }
    let (t, v) = tau_omega(u, u, xi, eta, phi);
    (t >= -ZERO && v >= -ZERO).then(|| vec![(L, t), (R, u), (L, u), (R, v)])
}

/// 8.9: L⁺R⁻(π/2)S⁻L⁻.
fn lrsl(x: f64, y: f64, phi: f64) -> Option<Word> {
    let (rho, th) = polar(x - sin(phi), y - 1.0 + cos(phi));
    if rho < 2.0 {
        return None;
    }
    let r = (rho * rho - 4.0).sqrt();
    let u = 2.0 - r;
    let t = wrap_angle(th + atan2(r, -2.0));
    let v = wrap_angle(phi - FRAC_PI_2 - t);
    (t >= -ZERO && u <= ZERO && v <= ZERO).then(|| vec![(L, t), (R, -FRAC_PI_2), (S, u), (L, v)])
}

/// 8.10: L⁺R⁻(π/2)S⁻R⁻.
fn lrsr(x: f64, y: f64, phi: f64) -> Option<Word> {
    let (xi, eta) = (x + sin(phi), y - 1.0 - cos(phi));
    let (rho, th) = polar(-eta, xi);
    if rho < 2.0 {
        return None;
    }
    let (t, u) = (th, 2.0 - rho);
    let v = wrap_angle(t + FRAC_PI_2 - phi);
    (t >= -ZERO && u <= ZERO && v <= ZERO).then(|| vec![(L, t), (R, -FRAC_PI_2), (S, u), (R, v)])
}

/// 8.11: L⁺R⁻(π/2)S⁻L⁻(π/2)R⁺.
fn lrslr(x: f64, y: f64, phi: f64) -> Option<Word> {
    let (xi, eta) = (x + sin(phi), y - 1.0 - cos(phi));
    let (rho, _) = polar(xi, eta);
    if rho < 2.0 {
        return None;
    }
    let u = 4.0 - (rho * rho - 4.0).sqrt();
    if u > ZERO {
        return None;
    }
    let t = wrap_angle(atan2(
        (4.0 - u) * xi - 2.0 * eta,
        -2.0 * xi + (u - 4.0) * eta,
    ));
    let v = wrap_angle(t - phi);
    (t >= -ZERO && v >= -ZERO)
        .then(|| vec![(L, t), (R, -FRAC_PI_2), (S, u), (L, -FRAC_PI_2), (R, v)])
}

/// The eight base formulas with their family names.
const BASE: [(&str, Formula); 8] = [
    ("CSC", lsl),
    ("CSC", lsr),
    ("CCC", lrl),
    ("CCCC", lrlr_a),
    ("CCCC", lrlr_b),
    ("CCSC", lrsl),
    ("CCSC", lrsr),
    ("CCSCC", lrslr),
];

/// Every candidate path from `from` to `to` at `radius`: each base word
/// under each of the eight symmetry combinations, before the endpoint
/// check, with its family name.
pub fn reeds_shepp_candidates(
    from: Pose,
    to: Pose,
    radius: f64,
) -> Result<Vec<(&'static str, CurvePath)>, CarError> {
    check_radius(radius)?;
    check_poses(from, to)?;
    let (x, y, phi) = local_goal(from, to, radius);
    let (xb, yb) = (x * cos(phi) + y * sin(phi), x * sin(phi) - y * cos(phi));
    let mut out = Vec::new();
    for (family, f) in BASE {
        for backwards in [false, true] {
            let (bx, by) = if backwards { (xb, yb) } else { (x, y) };
            for (flip, reflect) in [(false, false), (true, false), (false, true), (true, true)] {
                let gx = if flip { -bx } else { bx };
                let gy = if reflect { -by } else { by };
                let gphi = if flip != reflect { -phi } else { phi };
                let Some(mut word) = f(gx, gy, gphi) else {
                    continue;
                };
                if backwards {
                    word.reverse();
                }
                let segments = word
                    .into_iter()
                    .filter(|(_, l)| l.abs() > 1e-12)
                    .map(|(steer, l)| Segment {
                        steer: match (reflect, steer) {
                            (true, L) => R,
                            (true, R) => L,
                            (_, s) => s,
                        },
                        length: if flip { -l } else { l } * radius,
                    })
                    .collect();
                out.push((family, CurvePath { segments, radius }));
            }
        }
    }
    Ok(out)
}

/// The shortest path from `from` to `to` with turning radius `radius`
/// (m) when reversing is allowed. Errors: a radius that is not a finite
/// number > 0, or a non-finite pose.
///
/// ```
/// use planlab_core::car::{reeds_shepp, Pose};
/// // A goal 1 m straight behind: back up.
/// let p = reeds_shepp(Pose::new(0.0, 0.0, 0.0), Pose::new(-1.0, 0.0, 0.0), 2.0).unwrap();
/// assert_eq!(p.word(), "S-");
/// assert!((p.length() - 1.0).abs() < 1e-9);
/// ```
pub fn reeds_shepp(from: Pose, to: Pose, radius: f64) -> Result<CurvePath, CarError> {
    let mut best: Option<CurvePath> = None;
    for (_, p) in reeds_shepp_candidates(from, to, radius)? {
        if reaches(from, to, &p)
            && best
                .as_ref()
                .map_or(true, |b| p.length() < b.length() - 1e-12)
        {
            best = Some(p);
        }
    }
    // CSC always has a solution for some symmetry; the error guards only
    // against numbers too large to solve.
    best.ok_or_else(|| {
        CarError::InvalidParameter(format!(
            "no Reeds-Shepp word joins ({:.3}, {:.3}) to ({:.3}, {:.3}) at radius {radius}: the numbers are too large to solve",
            from.x, from.y, to.x, to.y
        ))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base_words_that_pass_their_sign_conditions_reach_the_goal() {
        // Every candidate the formulas accept must end at the goal: a
        // wrong formula fails here, not just loses to another word.
        let mut families = std::collections::BTreeSet::new();
        let (mut ok, mut total) = (0, 0);
        for i in 0..600 {
            let f = i as f64;
            let to = Pose::new(sin(f * 1.3) * 4.0, cos(f * 0.7) * 4.0, f * 0.37);
            for (fam, p) in reeds_shepp_candidates(Pose::default(), to, 1.0).unwrap() {
                total += 1;
                if reaches(Pose::default(), to, &p) {
                    ok += 1;
                    families.insert(fam);
                }
            }
        }
        assert_eq!(
            ok,
            total,
            "{} of {total} candidates miss the goal",
            total - ok
        );
        assert_eq!(families.len(), 5, "{families:?}");
    }
}
