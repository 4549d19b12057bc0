//! Plane geometry on `[f64; 2]` points in metres: the point of a segment
//! closest to a point, and the distance to a segment or a polyline.
//!
//! One implementation for every layer (map painting, the DWA's rest check,
//! tracking error, the LiDAR peers' path checks): the same operations in the
//! same order, so each caller gets the bits it got from its own copy before.

use crate::num::hypot;

/// The point `a + t·d` (t ∈ [0, 1]) closest to `p`, and `t`; `t = 0` when
/// `d` is zero. Takes the direction `d` rather than the end point where the
/// caller has it (`a + d` would round).
#[inline]
pub fn closest_along(p: [f64; 2], a: [f64; 2], d: [f64; 2]) -> ([f64; 2], f64) {
    let len2 = d[0] * d[0] + d[1] * d[1];
    let t = if len2 > 0.0 {
        (((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    ([a[0] + t * d[0], a[1] + t * d[1]], t)
}

/// The point of segment `a`–`b` closest to `p`, and its parameter t ∈ [0, 1]
/// from `a`.
#[inline]
pub fn closest_on_segment(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> ([f64; 2], f64) {
    closest_along(p, a, [b[0] - a[0], b[1] - a[1]])
}

/// Distance from `p` to segment `a`–`b`.
#[inline]
pub fn segment_distance(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (q, _) = closest_on_segment(p, a, b);
    hypot(p[0] - q[0], p[1] - q[1])
}

/// Distance² from `p` to segment `a`–`b` (no square root, for comparisons
/// against a squared radius).
#[inline]
pub fn segment_distance2(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (q, _) = closest_on_segment(p, a, b);
    let (ex, ey) = (q[0] - p[0], q[1] - p[1]);
    ex * ex + ey * ey
}

/// Distance from `p` to the polyline `path` (a single point counts as one);
/// `None` for an empty path.
pub fn distance_to_polyline(p: [f64; 2], path: &[[f64; 2]]) -> Option<f64> {
    match path {
        [] => None,
        [a] => Some(hypot(p[0] - a[0], p[1] - a[1])),
        _ => path
            .windows(2)
            .map(|w| segment_distance(p, w[0], w[1]))
            .reduce(f64::min),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn closest_points_and_distances() {
        let (a, b) = ([0.0, 0.0], [4.0, 0.0]);
        assert_eq!(closest_on_segment([1.0, 2.0], a, b), ([1.0, 0.0], 0.25));
        // Beyond either end: the end point.
        assert_eq!(closest_on_segment([-3.0, 4.0], a, b), ([0.0, 0.0], 0.0));
        assert_eq!(segment_distance([7.0, 4.0], a, b), 5.0);
        assert_eq!(segment_distance2([7.0, 4.0], a, b), 25.0);
        // A zero-length segment is its point.
        assert_eq!(segment_distance([3.0, 4.0], a, a), 5.0);
        assert_eq!(closest_along([1.0, 1.0], a, [0.0, 2.0]), ([0.0, 1.0], 0.5));
    }

    #[test]
    fn polyline_distance_takes_the_nearest_segment() {
        let path = [[0.0, 0.0], [10.0, 0.0], [10.0, 10.0]];
        assert_eq!(distance_to_polyline([5.0, -2.0], &path), Some(2.0));
        assert_eq!(distance_to_polyline([12.0, 5.0], &path), Some(2.0));
        assert_eq!(distance_to_polyline([3.0, 4.0], &[[0.0, 0.0]]), Some(5.0));
        assert_eq!(distance_to_polyline([3.0, 4.0], &[]), None);
    }
}
