//! Direct sampling of the informed set (Gammell et al. 2014): the points
//! whose straight-line distance through them from start to goal is below
//! the best cost, an ellipse with the start and goal as foci, intersected
//! with the box of allowed centres.

use super::{dist, Common, Point};
use crate::num::{cos, sin};

/// Tries before giving up on one sample (the caller then samples the box).
const TRIES: usize = 1000;

/// Whether `p` could lie on a path cheaper than `best`.
pub(crate) fn in_ellipse(c: &Common, p: Point, best: f64) -> bool {
    dist(c.start, p) + dist(p, c.goal) < best
}

/// The area of the informed ellipse for a best cost `best`, cells².
pub(crate) fn area(c: &Common, best: f64) -> f64 {
    let c_min = dist(c.start, c.goal);
    let a = 0.5 * best;
    let b = 0.5 * (best * best - c_min * c_min).max(0.0).sqrt();
    std::f64::consts::PI * a * b
}

/// A uniform point of the informed set when a solution exists, else of the
/// box. The smaller of the ellipse and the box is sampled, rejecting what
/// falls outside the other.
pub(crate) fn sample(c: &mut Common) -> Point {
    let best = c.best;
    if !best.is_finite() {
        return c.uniform();
    }
    let (lo, hi) = c.space.bounds();
    let c_min = dist(c.start, c.goal);
    let a = 0.5 * best;
    let b = 0.5 * (best * best - c_min * c_min).max(0.0).sqrt();
    let box_area = (hi[0] - lo[0]) * (hi[1] - lo[1]);
    let centre = [
        0.5 * (c.start[0] + c.goal[0]),
        0.5 * (c.start[1] + c.goal[1]),
    ];
    let (ux, uy) = if c_min > 0.0 {
        (
            (c.goal[0] - c.start[0]) / c_min,
            (c.goal[1] - c.start[1]) / c_min,
        )
    } else {
        (1.0, 0.0)
    };
    if std::f64::consts::PI * a * b < box_area {
        for _ in 0..TRIES {
            let rho = c.rng.uniform().sqrt();
            let th = 2.0 * std::f64::consts::PI * c.rng.uniform();
            let (ex, ey) = (a * rho * cos(th), b * rho * sin(th));
            let p = [centre[0] + ux * ex - uy * ey, centre[1] + uy * ex + ux * ey];
            if p[0] >= lo[0] && p[0] <= hi[0] && p[1] >= lo[1] && p[1] <= hi[1] {
                return p;
            }
        }
    } else {
        for _ in 0..TRIES {
            let p = c.uniform();
            if in_ellipse(c, p, best) {
                return p;
            }
        }
    }
    c.uniform()
}
