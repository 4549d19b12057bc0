//! The forces of the potential field (\[T\] eq 4-1…4-4, 4-13/4-14).
//!
//! Distances to obstacles are to their surface (and the robot's surface,
//! [`ApfConfig::robot_radius`]): an obstacle is a sphere (3D) or disc (2D)
//! with a centre and a radius, a point obstacle has radius 0.

use super::{ApfConfig, ApfVector};

/// A predicted obstacle position with its virtual repulsion range.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VirtualObstacle<V> {
    /// The obstacle's id.
    pub id: u32,
    /// 1 for t+1, 2 for t+2.
    pub k: u8,
    /// Predicted centre, m.
    pub centre: V,
    /// Virtual range from the centre, m.
    pub range: f64,
    /// Virtual repulsion at the centre as a share of the attraction, 1.
    pub gain: f64,
}

/// Surface distances below this count as this (the repulsion of eq 4-4
/// grows as 1/p³ and must stay finite), m.
pub const MIN_DISTANCE: f64 = 1e-3;

/// Attraction toward `goal` at `x` (eq 4-2): k_a·(X_g − X) within ρ of the
/// goal, k_b·(X_g − X)/‖X_g − X‖ beyond it, with k_b = ρ·k_a so the two
/// pieces meet at ρ.
#[inline]
pub fn attraction<V: ApfVector>(cfg: &ApfConfig, x: V, goal: V) -> V {
    let d = goal - x;
    let r = d.norm();
    if r <= cfg.rho {
        d * cfg.k_a
    } else {
        d * (cfg.rho * cfg.k_a / r)
    }
}

/// Distance from `x` (with the robot's radius) to the surface of the
/// obstacle at `centre` with `radius`; negative when overlapping, m.
#[inline]
pub fn surface_distance<V: ApfVector>(cfg: &ApfConfig, x: V, centre: V, radius: f64) -> f64 {
    (x - centre).norm() - radius - cfg.robot_radius
}

/// Repulsion of one obstacle at `x` (eq 4-4): k_r·(1/p − 1/p₀)/p² away from
/// its centre while the surface distance p ≤ p₀, else 0. p is clamped to
/// [`MIN_DISTANCE`].
#[inline]
pub fn repulsion<V: ApfVector>(cfg: &ApfConfig, x: V, centre: V, radius: f64) -> V {
    let off = x - centre;
    let dc = off.norm();
    let p = dc - radius - cfg.robot_radius;
    if p > cfg.p0 || dc <= 0.0 {
        return V::ZERO;
    }
    let p = p.max(MIN_DISTANCE);
    let mag = cfg.k_r * (1.0 / p - 1.0 / cfg.p0) / (p * p);
    off * (mag / dc)
}

/// Virtual repulsion of a predicted obstacle at `x` (eq 4-13/4-14): linear
/// in the distance r from the predicted centre, `gain`·`f_at` at the centre
/// and 0 at the virtual range's edge, pointing away from the centre.
/// `f_at` is the attraction's magnitude at `x`.
#[inline]
pub fn virtual_repulsion<V: ApfVector>(x: V, v: &VirtualObstacle<V>, f_at: f64) -> V {
    let off = x - v.centre;
    let r = off.norm();
    if r >= v.range || r <= 0.0 {
        return V::ZERO;
    }
    off * (v.gain * f_at * (1.0 - r / v.range) / r)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DVec2, DVec3};

    #[test]
    fn attraction_is_continuous_at_rho_and_points_to_the_goal() {
        let cfg = ApfConfig::default();
        let g = DVec2::new(1.0, 0.0);
        let inside = attraction(&cfg, DVec2::new(1.0 - cfg.rho + 1e-9, 0.0), g);
        let outside = attraction(&cfg, DVec2::new(1.0 - cfg.rho - 1e-9, 0.0), g);
        assert!((inside - outside).length() < 1e-6);
        assert!((outside.length() - cfg.rho * cfg.k_a).abs() < 1e-9);
        let far = attraction(&cfg, DVec2::new(-5.0, 0.0), g);
        assert!((far.length() - cfg.rho * cfg.k_a).abs() < 1e-12 && far.x > 0.0);
        let near = attraction(&cfg, DVec2::new(0.9, 0.0), g);
        assert!((near.x - 0.1 * cfg.k_a).abs() < 1e-12);
    }

    #[test]
    fn repulsion_follows_eq_4_4_and_vanishes_beyond_p0() {
        let cfg = ApfConfig::default();
        let c = DVec3::new(0.0, 0.0, 0.0);
        let r = 0.05;
        let p = 0.05;
        let f = repulsion(&cfg, DVec3::new(0.0, 0.0, r + p), c, r);
        let expect = cfg.k_r * (1.0 / p - 1.0 / cfg.p0) / (p * p);
        assert!((f.z - expect).abs() < 1e-9 * expect && f.x == 0.0);
        assert_eq!(
            repulsion(&cfg, DVec3::new(0.0, 0.0, r + cfg.p0 + 1e-6), c, r),
            DVec3::ZERO
        );
        // Stronger when closer.
        let g = repulsion(&cfg, DVec3::new(0.0, 0.0, r + 0.02), c, r);
        assert!(g.z > f.z);
    }

    #[test]
    fn virtual_repulsion_is_linear_from_gain_at_centre_to_zero_at_edge() {
        let v = VirtualObstacle {
            id: 0,
            k: 1,
            centre: DVec2::ZERO,
            range: 0.2,
            gain: 0.75,
        };
        let f = |x: f64| virtual_repulsion(DVec2::new(x, 0.0), &v, 2.0).x;
        assert!((f(1e-9) - 1.5).abs() < 1e-6);
        assert!((f(0.1) - 0.75).abs() < 1e-12);
        assert_eq!(f(0.2), 0.0);
        assert!(f(-0.1) < 0.0);
    }
}
