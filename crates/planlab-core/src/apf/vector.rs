//! The one abstraction over 2D and 3D: [`ApfVector`], implemented for glam's
//! `DVec2` (mobile robot) and `DVec3` (end effector). Everything else in
//! [`crate::apf`] is written once, generic over it; only the sampling of
//! candidate directions differs by dimension (\[T\] eq 4-6…4-10).

use std::fmt::Debug;
use std::ops::{Add, Mul, Neg, Sub};

use glam::{DVec2, DVec3};

use crate::num::{atan2, cos, hypot, sin};

/// A point / vector the potential field works in.
pub trait ApfVector:
    Copy
    + Debug
    + PartialEq
    + Default
    + Send
    + Sync
    + 'static
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<f64, Output = Self>
    + Neg<Output = Self>
{
    /// Number of coordinates (2 or 3).
    const DIM: usize;
    /// The zero vector.
    const ZERO: Self;
    /// Dot product.
    fn dot(self, other: Self) -> f64;
    /// Euclidean length.
    fn norm(self) -> f64 {
        self.dot(self).sqrt()
    }
    /// As a 3D vector (z = 0 in 2D), for predictors and drawing.
    fn to_xyz(self) -> DVec3;
    /// From a 3D vector (z dropped in 2D).
    fn from_xyz(v: DVec3) -> Self;
    /// From exactly [`ApfVector::DIM`] finite numbers, else `None`.
    fn from_slice(s: &[f64]) -> Option<Self> {
        if s.len() != Self::DIM || !s.iter().all(|x| x.is_finite()) {
            return None;
        }
        let z = if Self::DIM == 3 { s[2] } else { 0.0 };
        Some(Self::from_xyz(DVec3::new(s[0], s[1], z)))
    }
    /// The coordinates as a `Vec` of length [`ApfVector::DIM`].
    fn to_vec(self) -> Vec<f64> {
        let v = self.to_xyz();
        [v.x, v.y, v.z][..Self::DIM].to_vec()
    }
    /// Unit candidate directions around the unit vector `base`, appended to
    /// `out` as (angle from `base`, rad, direction), see [`Sampling`]. The
    /// first is `base` itself; the rest come in order of growing |angle|,
    /// positive (counter-clockwise / upward) before negative, so ties in
    /// cost resolve toward the resultant deterministically.
    fn sample_directions(base: Self, sampling: &Sampling, out: &mut Vec<(f64, Self)>);
}

/// How candidate directions are laid out around the resultant force.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sampling {
    /// Angular spacing, rad (\[T\]: 15°).
    pub step: f64,
    /// Largest deviation from the resultant, rad (\[T\]: 90°).
    pub half_range: f64,
    /// 3D only: sample the whole hemisphere around the resultant (rings
    /// every `step` from the axis, 12 azimuths each) instead of the
    /// vertical plane containing it (beyond the thesis).
    pub hemisphere: bool,
}

impl Sampling {
    /// The signed angles 0, +s, −s, +2s, −2s, … up to `half_range`.
    fn angles(&self) -> impl Iterator<Item = f64> + '_ {
        let n = if self.step > 0.0 {
            (self.half_range / self.step + 1e-9).floor() as i64
        } else {
            0
        };
        std::iter::once(0.0).chain((1..=n).flat_map(move |k| {
            let a = k as f64 * self.step;
            [a, -a]
        }))
    }
}

impl ApfVector for DVec2 {
    const DIM: usize = 2;
    const ZERO: Self = DVec2::ZERO;
    fn dot(self, other: Self) -> f64 {
        self.x * other.x + self.y * other.y
    }
    fn to_xyz(self) -> DVec3 {
        DVec3::new(self.x, self.y, 0.0)
    }
    fn from_xyz(v: DVec3) -> Self {
        DVec2::new(v.x, v.y)
    }
    fn sample_directions(base: Self, sampling: &Sampling, out: &mut Vec<(f64, Self)>) {
        let heading = atan2(base.y, base.x);
        for a in sampling.angles() {
            let h = heading + a;
            out.push((a, DVec2::new(cos(h), sin(h))));
        }
    }
}

impl ApfVector for DVec3 {
    const DIM: usize = 3;
    const ZERO: Self = DVec3::ZERO;
    fn dot(self, other: Self) -> f64 {
        self.x * other.x + self.y * other.y + self.z * other.z
    }
    fn to_xyz(self) -> DVec3 {
        self
    }
    fn from_xyz(v: DVec3) -> Self {
        v
    }
    fn sample_directions(base: Self, sampling: &Sampling, out: &mut Vec<(f64, Self)>) {
        let horiz = hypot(base.x, base.y);
        // eq 4-7: azimuth θ_xy of the force in the XY plane and elevation
        // θ_yz in the vertical plane containing it; atan2 does the quadrant
        // bookkeeping of transCos / transTan (eq 4-8, 4-9). A vertical force
        // has no azimuth: take the x axis.
        let azimuth = if horiz > 1e-12 {
            atan2(base.y, base.x)
        } else {
            0.0
        };
        let elevation = atan2(base.z, horiz);
        if !sampling.hemisphere {
            for a in sampling.angles() {
                // Elevation past ±90° continues over the top in the same
                // vertical plane (trans, eq 4-10, is the angle wrap).
                let e = elevation + a;
                let (ce, se) = (cos(e), sin(e));
                out.push((a, DVec3::new(ce * cos(azimuth), ce * sin(azimuth), se)));
            }
            return;
        }
        // Hemisphere: an orthonormal frame (u, v) around the axis `base`.
        let axis = base * (1.0 / base.norm().max(1e-300));
        let helper = if axis.x.abs() < 0.9 {
            DVec3::X
        } else {
            DVec3::Y
        };
        let u = axis.cross(helper).normalize_or_zero();
        let v = axis.cross(u);
        out.push((0.0, axis));
        let n = if sampling.step > 0.0 {
            (sampling.half_range / sampling.step + 1e-9).floor() as i64
        } else {
            0
        };
        const AZIMUTHS: usize = 12;
        for k in 1..=n {
            let a = k as f64 * sampling.step;
            let (ca, sa) = (cos(a), sin(a));
            for j in 0..AZIMUTHS {
                let phi = j as f64 * std::f64::consts::TAU / AZIMUTHS as f64;
                let d = axis * ca + (u * cos(phi) + v * sin(phi)) * sa;
                out.push((a, d));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::FRAC_PI_2;

    const PLANE: Sampling = Sampling {
        step: 15.0 * std::f64::consts::PI / 180.0,
        half_range: FRAC_PI_2,
        hemisphere: false,
    };

    #[test]
    fn thirteen_unit_directions_in_2d_spanning_plus_minus_90() {
        let mut out = Vec::new();
        DVec2::sample_directions(DVec2::new(0.0, 1.0), &PLANE, &mut out);
        assert_eq!(out.len(), 13);
        assert_eq!(out[0].1, DVec2::new(cos(FRAC_PI_2), 1.0));
        for (a, d) in &out {
            assert!((d.norm() - 1.0).abs() < 1e-12);
            assert!((d.dot(DVec2::Y) - cos(*a)).abs() < 1e-12);
        }
        // ±90° are perpendicular to the force.
        assert!(out.iter().any(|(_, d)| (d.x + 1.0).abs() < 1e-12));
        assert!(out.iter().any(|(_, d)| (d.x - 1.0).abs() < 1e-12));
    }

    #[test]
    fn three_d_plane_sampling_stays_in_the_vertical_plane_of_the_force() {
        let f = DVec3::new(1.0, 1.0, 0.5);
        let mut out = Vec::new();
        DVec3::sample_directions(f.normalize(), &PLANE, &mut out);
        assert_eq!(out.len(), 13);
        let normal = f.cross(DVec3::Z).normalize();
        for (a, d) in &out {
            assert!(d.dot(normal).abs() < 1e-12, "{d:?} leaves the plane");
            assert!((d.dot(f.normalize()) - cos(*a)).abs() < 1e-12);
        }
        // The +15° candidate points higher than the force.
        assert!(out[1].1.z > f.normalize().z);
    }

    #[test]
    fn hemisphere_sampling_covers_the_half_space_around_the_force() {
        let s = Sampling {
            hemisphere: true,
            ..PLANE
        };
        let f = DVec3::new(0.0, 0.0, 2.0);
        let mut out = Vec::new();
        DVec3::sample_directions(f.normalize(), &s, &mut out);
        assert_eq!(out.len(), 1 + 6 * 12);
        assert!(out.iter().all(|(_, d)| d.z >= -1e-12));
        assert!((d_max(&out, DVec3::X) - 1.0).abs() < 1e-12);
    }

    fn d_max(v: &[(f64, DVec3)], dir: DVec3) -> f64 {
        v.iter().map(|(_, d)| d.dot(dir)).fold(f64::MIN, f64::max)
    }
}
