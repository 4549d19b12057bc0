//! Dubins curves (L. E. Dubins, "On curves of minimal length with a
//! constraint on average curvature, and with prescribed initial and
//! terminal positions and tangents", American Journal of Mathematics
//! 79(3), 1957): the shortest forward-only path between two poses for a
//! car with a minimum turning radius is one of six words, LSL, RSR, LSR,
//! RSL, RLR, LRL. Each word's three lengths have a closed form in the
//! normalised problem (radius 1, the start–goal line along +x); the
//! shortest valid word wins, ties to the first in that order.

use super::{check_poses, check_radius, end_pose, local_goal, mod2pi, CarError, CurvePath, Pose};
use super::{Segment, Steer};
use crate::num::{acos, atan2, cos, hypot, sin};
use std::f64::consts::PI;

/// The six Dubins words, in the order ties are broken.
pub const WORDS: [[Steer; 3]; 6] = {
    use Steer::{Left as L, Right as R, Straight as S};
    [
        [L, S, L],
        [R, S, R],
        [L, S, R],
        [R, S, L],
        [R, L, R],
        [L, R, L],
    ]
};

/// The three normalised lengths (t, p, q) of word `w` (index into
/// [`WORDS`]) for distance `d` (in radii) and headings `a`, `b` relative
/// to the start–goal line; `None` when the word cannot join them.
fn word_lengths(w: usize, d: f64, a: f64, b: f64) -> Option<[f64; 3]> {
    let (sa, sb, ca, cb) = (sin(a), sin(b), cos(a), cos(b));
    let cab = cos(a - b);
    match w {
        // LSL: the outer tangent of the two left circles.
        0 => {
            let p2 = 2.0 + d * d - 2.0 * cab + 2.0 * d * (sa - sb);
            (p2 >= 0.0).then(|| {
                let th = atan2(cb - ca, d + sa - sb);
                [mod2pi(th - a), p2.sqrt(), mod2pi(b - th)]
            })
        }
        // RSR: the outer tangent of the two right circles.
        1 => {
            let p2 = 2.0 + d * d - 2.0 * cab + 2.0 * d * (sb - sa);
            (p2 >= 0.0).then(|| {
                let th = atan2(ca - cb, d - sa + sb);
                [mod2pi(a - th), p2.sqrt(), mod2pi(th - b)]
            })
        }
        // LSR: an inner tangent.
        2 => {
            let p2 = -2.0 + d * d + 2.0 * cab + 2.0 * d * (sa + sb);
            (p2 >= 0.0).then(|| {
                let p = p2.sqrt();
                let th = atan2(-ca - cb, d + sa + sb) - atan2(-2.0, p);
                [mod2pi(th - a), p, mod2pi(th - b)]
            })
        }
        // RSL: the other inner tangent.
        3 => {
            let p2 = -2.0 + d * d + 2.0 * cab - 2.0 * d * (sa + sb);
            (p2 >= 0.0).then(|| {
                let p = p2.sqrt();
                let th = atan2(ca + cb, d - sa - sb) - atan2(2.0, p);
                [mod2pi(a - th), p, mod2pi(b - th)]
            })
        }
        // RLR: a third circle tangent to both right circles.
        4 => {
            let c = (6.0 - d * d + 2.0 * cab + 2.0 * d * (sa - sb)) / 8.0;
            (c.abs() <= 1.0).then(|| {
                let th = atan2(ca - cb, d - sa + sb);
                let p = mod2pi(2.0 * PI - acos(c));
                let t = mod2pi(a - th + p / 2.0);
                [t, p, mod2pi(a - b - t + p)]
            })
        }
        // LRL: a third circle tangent to both left circles.
        _ => {
            let c = (6.0 - d * d + 2.0 * cab + 2.0 * d * (sb - sa)) / 8.0;
            (c.abs() <= 1.0).then(|| {
                let th = atan2(ca - cb, d + sa - sb);
                let p = mod2pi(2.0 * PI - acos(c));
                let t = mod2pi(-a - th + p / 2.0);
                [t, p, mod2pi(b - a - t + p)]
            })
        }
    }
}

/// Every Dubins word's candidate from `from` to `to` at `radius`, as
/// paths in [`WORDS`] order (`None` for a word that cannot join them).
/// Errors: a bad radius or a non-finite pose.
pub fn dubins_words(from: Pose, to: Pose, radius: f64) -> Result<Vec<Option<CurvePath>>, CarError> {
    check_radius(radius)?;
    check_poses(from, to)?;
    let (x, y, phi) = local_goal(from, to, radius);
    let d = hypot(x, y);
    // The start–goal line's direction in the start frame (0 when the two
    // positions coincide: any direction works there).
    let th = if d > 0.0 { atan2(y, x) } else { 0.0 };
    let (a, b) = (mod2pi(-th), mod2pi(phi - th));
    Ok((0..WORDS.len())
        .map(|w| {
            word_lengths(w, d, a, b).map(|len| CurvePath {
                segments: WORDS[w]
                    .iter()
                    .zip(len)
                    .filter(|(_, l)| *l > 1e-12)
                    .map(|(&steer, l)| Segment {
                        steer,
                        length: l * radius,
                    })
                    .collect(),
                radius,
            })
        })
        .collect())
}

/// Whether `path` from `from` ends at `to` (1e-6 of the radius, 1e-6 rad):
/// a guard against the rounding of the closed forms near their limits.
pub(crate) fn reaches(from: Pose, to: Pose, path: &CurvePath) -> bool {
    let e = end_pose(from, path);
    let tol = 1e-6 * path.radius.max(1.0);
    hypot(e.x - to.x, e.y - to.y) <= tol && crate::num::wrap_angle(e.yaw - to.yaw).abs() <= 1e-6
}

/// The shortest forward-only path from `from` to `to` with turning radius
/// `radius` (m). Errors: a radius that is not a finite number > 0, or a
/// non-finite pose.
///
/// ```
/// use planlab_core::car::{dubins, Pose};
/// // A half circle: a U-turn to a goal 2R to the left is πR long.
/// let p = dubins(Pose::new(0.0, 0.0, 0.0), Pose::new(0.0, 2.0, std::f64::consts::PI), 1.0).unwrap();
/// assert_eq!(p.word(), "L");
/// assert!((p.length() - std::f64::consts::PI).abs() < 1e-9);
/// ```
pub fn dubins(from: Pose, to: Pose, radius: f64) -> Result<CurvePath, CarError> {
    let mut best: Option<CurvePath> = None;
    let words = dubins_words(from, to, radius)?;
    for p in words.into_iter().flatten().filter(|p| reaches(from, to, p)) {
        if best
            .as_ref()
            .map_or(true, |b| p.length() < b.length() - 1e-12)
        {
            best = Some(p);
        }
    }
    // LSL and RSR always exist (p² ≥ 0 by the triangle inequality); the
    // fallback guards only against rounding at their limit.
    best.ok_or_else(|| {
        CarError::InvalidParameter(format!(
            "no Dubins word joins ({:.3}, {:.3}) to ({:.3}, {:.3}) at radius {radius}: the numbers are too large to solve",
            from.x, from.y, to.x, to.y
        ))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn straight_ahead_is_the_distance() {
        let p = dubins(
            Pose::new(1.0, 2.0, 0.3),
            Pose::new(1.0 + 5.0 * cos(0.3), 2.0 + 5.0 * sin(0.3), 0.3),
            0.7,
        )
        .unwrap();
        assert!((p.length() - 5.0).abs() < 1e-9, "{p:?}");
        assert_eq!(p.word(), "S");
    }

    #[test]
    fn each_word_reaches_the_goal_when_it_exists_and_ccc_words_occur() {
        let mut ccc = [false; 2];
        for i in 0..400 {
            let f = i as f64;
            let to = Pose::new(sin(f * 1.3) * 3.0, cos(f * 0.7) * 3.0, f * 0.37);
            for (w, p) in dubins_words(Pose::default(), to, 1.0)
                .unwrap()
                .iter()
                .enumerate()
            {
                if let Some(p) = p {
                    assert!(reaches(Pose::default(), to, p));
                    if w >= 4 {
                        ccc[w - 4] = true;
                    }
                }
            }
        }
        assert_eq!(ccc, [true, true], "RLR and LRL must both join some poses");
    }
}
