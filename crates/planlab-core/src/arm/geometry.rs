//! The arm's links as capsules and their distance to obstacles (spheres
//! and capsules), by parry3d.

use glam::DVec3;
use parry3d_f64::math::Pose;
use parry3d_f64::query;
use parry3d_f64::shape::{Ball, Capsule};
use serde::{Deserialize, Serialize};

use super::kinematics::Frames;
use super::ArmError;

/// An obstacle in 3D.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", tag = "shape", deny_unknown_fields)]
pub enum Obstacle3 {
    /// A ball.
    Sphere {
        /// Centre, m.
        centre: [f64; 3],
        /// Radius, m.
        radius: f64,
    },
    /// A capsule: every point within `radius` of segment `a`–`b`.
    Capsule {
        /// One end of the axis, m.
        a: [f64; 3],
        /// The other end, m.
        b: [f64; 3],
        /// Radius, m.
        radius: f64,
    },
}

impl Obstacle3 {
    /// Refuses non-finite coordinates and negative radii.
    pub fn validate(&self, what: &str) -> Result<(), ArmError> {
        let (pts, r): (Vec<[f64; 3]>, f64) = match *self {
            Obstacle3::Sphere { centre, radius } => (vec![centre], radius),
            Obstacle3::Capsule { a, b, radius } => (vec![a, b], radius),
        };
        if pts.iter().flatten().any(|x| !x.is_finite()) || !r.is_finite() {
            return Err(ArmError::NotFinite(what.to_string()));
        }
        if let Some(p) = crate::params::param_problem(r, 0.0, false) {
            return Err(ArmError::Invalid(format!(
                "{what}: radius {} m: {p}",
                crate::num::fmt_num(r)
            )));
        }
        Ok(())
    }

    /// Its centre (sphere) or axis midpoint (capsule), m.
    pub fn centre(&self) -> DVec3 {
        match *self {
            Obstacle3::Sphere { centre, .. } => DVec3::from_array(centre),
            Obstacle3::Capsule { a, b, .. } => 0.5 * (DVec3::from_array(a) + DVec3::from_array(b)),
        }
    }

    /// Distance from point `p` to the obstacle's surface (0 inside), m.
    pub fn point_distance(&self, p: DVec3) -> f64 {
        match *self {
            Obstacle3::Sphere { centre, radius } => {
                ((p - DVec3::from_array(centre)).length() - radius).max(0.0)
            }
            Obstacle3::Capsule { a, b, radius } => {
                let (a, b) = (DVec3::from_array(a), DVec3::from_array(b));
                (segment_point_distance(a, b, p) - radius).max(0.0)
            }
        }
    }

    /// Translated by `d`.
    pub fn translated(&self, d: DVec3) -> Obstacle3 {
        let t = |p: [f64; 3]| (DVec3::from_array(p) + d).to_array();
        match *self {
            Obstacle3::Sphere { centre, radius } => Obstacle3::Sphere {
                centre: t(centre),
                radius,
            },
            Obstacle3::Capsule { a, b, radius } => Obstacle3::Capsule {
                a: t(a),
                b: t(b),
                radius,
            },
        }
    }
}

/// Distance from `p` to segment `a`–`b`, m.
pub fn segment_point_distance(a: DVec3, b: DVec3, p: DVec3) -> f64 {
    let ab = b - a;
    let l2 = ab.length_squared();
    let t = if l2 > 0.0 {
        ((p - a).dot(ab) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p - (a + ab * t)).length()
}

/// A link's capsule: axis from `a` to `b`, radius.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinkCapsule {
    /// Start of the axis, m.
    pub a: DVec3,
    /// End of the axis, m.
    pub b: DVec3,
    /// Radius, m.
    pub radius: f64,
}

/// The capsules of the links of a posture (`radii` from
/// [`super::ArmModel::link_radii`]).
pub fn link_capsules(frames: &Frames, radii: &[f64]) -> Vec<LinkCapsule> {
    frames
        .link_segments()
        .into_iter()
        .zip(radii)
        .map(|((a, b), &radius)| LinkCapsule { a, b, radius })
        .collect()
}

enum Shape3 {
    Ball(Ball),
    Capsule(Capsule),
}

impl Shape3 {
    /// Shape and pose; a zero-length capsule becomes a ball (parry's
    /// capsule needs a direction).
    fn of(a: DVec3, b: DVec3, radius: f64) -> (Shape3, Pose) {
        if (b - a).length_squared() < 1e-18 {
            (Shape3::Ball(Ball::new(radius)), Pose::from_translation(a))
        } else {
            (
                Shape3::Capsule(Capsule::new(a, b, radius)),
                Pose::identity(),
            )
        }
    }

    fn dyn_shape(&self) -> &dyn parry3d_f64::shape::Shape {
        match self {
            Shape3::Ball(b) => b,
            Shape3::Capsule(c) => c,
        }
    }
}

fn obstacle_shape(o: &Obstacle3) -> (Shape3, Pose) {
    match *o {
        Obstacle3::Sphere { centre, radius } => (
            Shape3::Ball(Ball::new(radius)),
            Pose::from_translation(DVec3::from_array(centre)),
        ),
        Obstacle3::Capsule { a, b, radius } => {
            Shape3::of(DVec3::from_array(a), DVec3::from_array(b), radius)
        }
    }
}

/// Surface distance between a link capsule and an obstacle (0 when they
/// touch or overlap), m. parry3d's distance query.
pub fn link_distance(link: &LinkCapsule, obstacle: &Obstacle3) -> f64 {
    let (s1, p1) = Shape3::of(link.a, link.b, link.radius);
    let (s2, p2) = obstacle_shape(obstacle);
    match query::distance(&p1, s1.dyn_shape(), &p2, s2.dyn_shape()) {
        Ok(d) => d.distance.max(0.0),
        // Balls and capsules are always supported; keep a safe analytic
        // fallback (segment-to-centre) rather than a panic.
        Err(_) => {
            (segment_point_distance(link.a, link.b, obstacle.centre()) - link.radius).max(0.0)
        }
    }
}

/// A lower bound of [`link_distance`] from the shapes' bounding spheres
/// (centre the segment's midpoint, radius half its length plus the
/// capsule's): a few flops, where the exact query runs GJK. A minimum
/// that skips the exact query whenever this bound is not below the best
/// so far is the same minimum.
pub fn link_distance_lower_bound(link: &LinkCapsule, obstacle: &Obstacle3) -> f64 {
    let bound = |a: DVec3, b: DVec3, r: f64| (0.5 * (a + b), 0.5 * (b - a).length() + r);
    let (c1, r1) = bound(link.a, link.b, link.radius);
    let (c2, r2) = match *obstacle {
        Obstacle3::Sphere { centre, radius } => (DVec3::from_array(centre), radius),
        Obstacle3::Capsule { a, b, radius } => {
            bound(DVec3::from_array(a), DVec3::from_array(b), radius)
        }
    };
    ((c1 - c2).length() - r1 - r2).max(0.0)
}

/// Smallest distance between any link and any obstacle, with the link's
/// index (`None` without obstacles).
pub fn min_distance(links: &[LinkCapsule], obstacles: &[Obstacle3]) -> Option<(f64, usize)> {
    let mut best: Option<(f64, usize)> = None;
    for (i, l) in links.iter().enumerate() {
        for o in obstacles {
            if best.is_some_and(|(b, _)| link_distance_lower_bound(l, o) >= b) {
                continue; // cannot be nearer: `d < b` below would be false
            }
            let d = link_distance(l, o);
            if best.map_or(true, |(b, _)| d < b) {
                best = Some((d, i));
            }
        }
    }
    best
}

/// Whether any link touches any obstacle.
pub fn collides(links: &[LinkCapsule], obstacles: &[Obstacle3]) -> bool {
    min_distance(links, obstacles).is_some_and(|(d, _)| d <= 0.0)
}
