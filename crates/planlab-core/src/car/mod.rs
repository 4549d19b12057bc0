//! Car-like robots (docs/algorithms.md §car-curves, §hybrid-astar): paths
//! made of circular arcs of a minimum turning radius and straight lines.
//!
//! - [`dubins()`]: the shortest forward-only path between two poses (Dubins
//!   1957: six words LSL, RSR, LSR, RSL, RLR, LRL);
//! - [`reeds_shepp()`]: the shortest path when the car may also reverse
//!   (Reeds & Shepp 1990: the five families CSC, CCC, CCCC, CCSC, CCSCC and
//!   their time-flipped, reflected and backwards words);
//! - [`hybrid_astar`]: Hybrid A* (Dolgov et al. 2008, as in Nav2's Smac
//!   Hybrid-A*) over continuous poses on an occupancy grid, with a disc
//!   footprint ([`footprint`]).
//!
//! A [`CurvePath`] is a list of [`Segment`]s (left arc, straight, right
//! arc; a negative length drives it in reverse), in metres; [`sample`]
//! turns it into poses every `step` metres.

pub mod dubins;
pub mod footprint;
pub mod hybrid_astar;
pub mod reeds_shepp;

pub use dubins::dubins;
pub use reeds_shepp::reeds_shepp;

use crate::num::{cos, sin, wrap_angle};
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// A planar pose: position in metres, heading in radians counter-clockwise
/// from +x.
#[derive(Clone, Copy, Debug, PartialEq, Default, Serialize, Deserialize)]
pub struct Pose {
    /// x, m.
    pub x: f64,
    /// y, m.
    pub y: f64,
    /// Heading, rad.
    pub yaw: f64,
}

impl Pose {
    /// A pose from its parts.
    pub const fn new(x: f64, y: f64, yaw: f64) -> Self {
        Self { x, y, yaw }
    }

    /// Whether every part is a finite number.
    pub fn is_finite(&self) -> bool {
        self.x.is_finite() && self.y.is_finite() && self.yaw.is_finite()
    }
}

/// How a segment steers.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Steer {
    /// Counter-clockwise arc at the minimum radius.
    Left,
    /// Straight line.
    Straight,
    /// Clockwise arc at the minimum radius.
    Right,
}

impl Steer {
    /// `L`, `S` or `R`.
    pub fn letter(self) -> char {
        match self {
            Steer::Left => 'L',
            Steer::Straight => 'S',
            Steer::Right => 'R',
        }
    }

    /// +1 left, 0 straight, −1 right: the sign of the curvature when
    /// driving forward.
    pub fn sign(self) -> f64 {
        match self {
            Steer::Left => 1.0,
            Steer::Straight => 0.0,
            Steer::Right => -1.0,
        }
    }
}

/// One piece of a car path.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Segment {
    /// Left, straight or right.
    pub steer: Steer,
    /// Signed length along the path, m: negative drives in reverse.
    pub length: f64,
}

/// A path of arcs and straight lines for a given turning radius.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CurvePath {
    /// The segments, first to last (zero-length ones dropped).
    pub segments: Vec<Segment>,
    /// Minimum turning radius the arcs use, m.
    pub radius: f64,
}

impl CurvePath {
    /// Total length, m (reverse segments count positive).
    pub fn length(&self) -> f64 {
        self.segments.iter().map(|s| s.length.abs()).sum()
    }

    /// The word: one letter per segment (`LSL`), a `-` after each segment
    /// driven in reverse (`LR-L`).
    pub fn word(&self) -> String {
        let mut w = String::new();
        for s in &self.segments {
            w.push(s.steer.letter());
            if s.length < 0.0 {
                w.push('-');
            }
        }
        w
    }

    /// Number of switches between forward and reverse.
    pub fn cusps(&self) -> usize {
        self.segments
            .windows(2)
            .filter(|w| (w[0].length < 0.0) != (w[1].length < 0.0))
            .count()
    }
}

/// Why a curve or a car plan could not be made.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum CarError {
    /// A parameter is out of range (NaN, ≤ 0 radius …); the text names it.
    #[error("{}", crate::text::one_line(.0))]
    InvalidParameter(String),
    /// The start or goal pose has a non-finite part.
    #[error("the {which} pose ({x}, {y}, {yaw}) must be finite numbers")]
    BadPose {
        /// `start` or `goal`.
        which: &'static str,
        /// x as given.
        x: f64,
        /// y as given.
        y: f64,
        /// Heading as given.
        yaw: f64,
    },
    /// The start or goal lies off the map.
    #[error("the {which} ({x:.3}, {y:.3}) m is off the map")]
    OffMap {
        /// `start` or `goal`.
        which: &'static str,
        /// x, m.
        x: f64,
        /// y, m.
        y: f64,
    },
    /// The robot's footprint at the start or goal overlaps an obstacle (or
    /// the map's edge).
    #[error("the {which} ({x:.3}, {y:.3}) m is in collision: a disc of radius {radius} m there overlaps an obstacle or the map's edge")]
    InCollision {
        /// `start` or `goal`.
        which: &'static str,
        /// x, m.
        x: f64,
        /// y, m.
        y: f64,
        /// Footprint radius, m.
        radius: f64,
    },
    /// No path: the obstacle-aware distance says the goal cannot be
    /// reached, or the search ran out of poses.
    #[error("goal is unreachable from start for this car ({expanded} poses expanded)")]
    Unreachable {
        /// Poses expanded before giving up (0: proved by the 2D distance).
        expanded: usize,
    },
    /// The search stopped at its expansion limit.
    #[error("search limit reached: {expanded} poses expanded (limit {limit}) without a path")]
    SearchLimit {
        /// Poses expanded.
        expanded: usize,
        /// The limit.
        limit: usize,
    },
}

/// Checks a turning radius: finite and > 0.
pub fn check_radius(radius: f64) -> Result<(), CarError> {
    if radius.is_finite() && radius > 0.0 {
        Ok(())
    } else {
        Err(CarError::InvalidParameter(format!(
            "turning radius {radius} must be a finite number > 0 (metres)"
        )))
    }
}

/// Checks both poses are finite.
pub(crate) fn check_poses(from: Pose, to: Pose) -> Result<(), CarError> {
    for (which, p) in [("start", from), ("goal", to)] {
        if !p.is_finite() {
            return Err(CarError::BadPose {
                which,
                x: p.x,
                y: p.y,
                yaw: p.yaw,
            });
        }
    }
    Ok(())
}

/// The pose after driving `length` metres (signed) of `steer` at `radius`
/// from `p`: exact arcs, no integration error.
pub fn advance(p: Pose, steer: Steer, length: f64, radius: f64) -> Pose {
    match steer {
        Steer::Straight => Pose::new(p.x + length * cos(p.yaw), p.y + length * sin(p.yaw), p.yaw),
        Steer::Left | Steer::Right => {
            let k = steer.sign();
            let turn = k * length / radius;
            let yaw = p.yaw + turn;
            // Centre of the turning circle is at radius·k to the left.
            Pose::new(
                p.x + k * radius * (sin(yaw) - sin(p.yaw)),
                p.y - k * radius * (cos(yaw) - cos(p.yaw)),
                wrap_angle(yaw),
            )
        }
    }
}

/// The end pose of `path` driven from `from`.
pub fn end_pose(from: Pose, path: &CurvePath) -> Pose {
    path.segments
        .iter()
        .fold(from, |p, s| advance(p, s.steer, s.length, path.radius))
}

/// Poses along `path` from `from`, one at the start, then every `step`
/// metres within each segment and one at each segment's end (so cusps and
/// the final pose are exact). Each pose comes with `true` when it is
/// reached driving forward. `step` must be finite and > 0; at most
/// `max_poses` are made (an error beyond, so memory stays bounded).
pub fn sample(
    from: Pose,
    path: &CurvePath,
    step: f64,
    max_poses: usize,
) -> Result<Vec<(Pose, bool)>, CarError> {
    if !(step.is_finite() && step > 0.0) {
        return Err(CarError::InvalidParameter(format!(
            "sampling step {step} must be a finite number > 0 (metres)"
        )));
    }
    let need: f64 = path
        .segments
        .iter()
        .map(|s| (s.length.abs() / step).ceil() + 1.0)
        .sum::<f64>()
        + 1.0;
    if need > max_poses as f64 {
        return Err(CarError::InvalidParameter(format!(
            "sampling a {:.3} m path every {step} m makes {need} poses; at most {max_poses} are allowed",
            path.length()
        )));
    }
    let mut out = vec![(
        from,
        path.segments.first().map_or(true, |s| s.length >= 0.0),
    )];
    let mut at = from;
    for s in &path.segments {
        let n = (s.length.abs() / step).ceil().max(1.0) as usize;
        let forward = s.length >= 0.0;
        for i in 1..=n {
            let p = advance(at, s.steer, s.length * i as f64 / n as f64, path.radius);
            out.push((p, forward));
        }
        at = advance(at, s.steer, s.length, path.radius);
    }
    Ok(out)
}

/// The largest curvature between consecutive poses, 1/m: for each pair,
/// that of the circle through both positions tangent to the first heading
/// turned by half the heading change, 2·sin(|Δθ|/2) / chord (exactly 1/r
/// for two poses on an arc of radius r; 0 on a line). Pairs at the same
/// position (a cusp) are skipped. Checks that a path never turns tighter
/// than a turning radius without knowing how it was made.
pub fn max_curvature(poses: &[Pose]) -> f64 {
    poses
        .windows(2)
        .filter_map(|w| {
            let (a, b) = (w[0], w[1]);
            let chord = crate::num::hypot(b.x - a.x, b.y - a.y);
            (chord > 1e-12).then(|| 2.0 * sin(wrap_angle(b.yaw - a.yaw).abs() / 2.0) / chord)
        })
        .fold(0.0, f64::max)
}

/// `a` modulo 2π, in [0, 2π).
#[inline]
pub(crate) fn mod2pi(a: f64) -> f64 {
    let two_pi = 2.0 * std::f64::consts::PI;
    let r = a - two_pi * libm::floor(a / two_pi);
    if r >= two_pi {
        0.0
    } else {
        r
    }
}

/// `(x, y, φ)` of `to` in the frame of `from`, scaled by 1/`radius`: the
/// normalised problem both curve families solve.
pub(crate) fn local_goal(from: Pose, to: Pose, radius: f64) -> (f64, f64, f64) {
    let (dx, dy) = (to.x - from.x, to.y - from.y);
    let (c, s) = (cos(from.yaw), sin(from.yaw));
    (
        (c * dx + s * dy) / radius,
        (-s * dx + c * dy) / radius,
        wrap_angle(to.yaw - from.yaw),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn advance_on_a_left_quarter_circle_ends_at_the_circle_top() {
        // Radius 2, facing +x, a quarter left turn: centre (0, 2), end (2, 2)
        // facing +y.
        let p = advance(Pose::new(0.0, 0.0, 0.0), Steer::Left, PI, 2.0);
        assert!(
            (p.x - 2.0).abs() < 1e-12 && (p.y - 2.0).abs() < 1e-12,
            "{p:?}"
        );
        assert!((p.yaw - PI / 2.0).abs() < 1e-12);
        // Reversing the same arc comes back.
        let q = advance(p, Steer::Left, -PI, 2.0);
        assert!(
            q.x.abs() < 1e-12 && q.y.abs() < 1e-12 && q.yaw.abs() < 1e-12,
            "{q:?}"
        );
        let r = advance(Pose::new(0.0, 0.0, 0.0), Steer::Right, PI, 2.0);
        assert!(
            (r.x - 2.0).abs() < 1e-12 && (r.y + 2.0).abs() < 1e-12,
            "{r:?}"
        );
    }

    #[test]
    fn sampling_refuses_a_bad_step_and_too_many_poses() {
        let path = CurvePath {
            segments: vec![Segment {
                steer: Steer::Straight,
                length: 10.0,
            }],
            radius: 1.0,
        };
        assert!(sample(Pose::default(), &path, f64::NAN, 100).is_err());
        assert!(sample(Pose::default(), &path, 0.0, 100).is_err());
        assert!(sample(Pose::default(), &path, 1e-6, 100).is_err());
        let s = sample(Pose::default(), &path, 1.0, 100).unwrap();
        assert_eq!(s.len(), 11);
        assert_eq!(s.last().unwrap().0, Pose::new(10.0, 0.0, 0.0));
    }

    #[test]
    fn mod2pi_stays_in_range() {
        for a in [-7.0, -PI, 0.0, 1.0, 2.0 * PI, 13.0] {
            let m = mod2pi(a);
            assert!((0.0..2.0 * PI).contains(&m), "{a} -> {m}");
            assert!(wrap_angle(m - a).abs() < 1e-12);
        }
    }
}
