//! Deterministic numerics: transcendental functions and a seeded RNG.
//!
//! `f64::sin` and friends call the platform's libm natively and a different
//! implementation in WebAssembly, and the two may differ in the last bit.
//! Simulation code calls these wrappers (the pure-Rust `libm` crate on every
//! target) so the same scenario and seed give bit-identical traces natively
//! and in the browser. `+ - * / sqrt` are exactly rounded by IEEE 754 on both
//! and need no wrapper.

use std::f64::consts::PI;

/// The largest value any time (s), speed (m/s, rad/s), acceleration,
/// size or distance (m) parameter of a scenario may take. Far above any
/// robot's (a million metres, 11 days), low enough that products of a few
/// of them stay finite and that sizes derived from them are refused before
/// anything is allocated.
pub const MAX_PARAM: f64 = 1e6;

/// `x` for an error message: the shortest decimal that reads back as `x`,
/// in exponent form when that is shorter for huge or tiny magnitudes
/// (`1e308`, not 309 digits).
///
/// ```
/// use planlab_core::num::fmt_num;
/// assert_eq!(fmt_num(0.05), "0.05");
/// assert_eq!(fmt_num(1e308), "1e308");
/// assert_eq!(fmt_num(-2.5e-12), "-2.5e-12");
/// assert_eq!(fmt_num(f64::NAN), "NaN");
/// ```
pub fn fmt_num(x: f64) -> String {
    let plain = format!("{x}");
    let exp = format!("{x:e}");
    if x.is_finite() && exp.len() < plain.len() {
        exp
    } else {
        plain
    }
}

/// Sine (deterministic across targets).
#[inline]
pub fn sin(x: f64) -> f64 {
    libm::sin(x)
}

/// Cosine (deterministic across targets).
#[inline]
pub fn cos(x: f64) -> f64 {
    libm::cos(x)
}

/// `(sin(x), cos(x))`, bit for bit, with one argument reduction instead of
/// two: libm's `sincos` runs the same reduction and kernels as its `sin`
/// and `cos`. (Its tiny-argument shortcut starts at 2⁻²⁷·√2, `sin`'s at
/// 2⁻²⁶; in between `sin` returns x and the kernel x + x³·(…), which
/// rounds to x since x³/6 is below half an ulp of x.)
#[inline]
pub fn sin_cos(x: f64) -> (f64, f64) {
    libm::sincos(x)
}

/// Two-argument arctangent (deterministic across targets).
#[inline]
pub fn atan2(y: f64, x: f64) -> f64 {
    libm::atan2(y, x)
}

/// Arcsine (deterministic across targets).
#[inline]
pub fn asin(x: f64) -> f64 {
    libm::asin(x)
}

/// Arccosine (deterministic across targets).
#[inline]
pub fn acos(x: f64) -> f64 {
    libm::acos(x)
}

/// e^x (deterministic across targets).
#[inline]
pub fn exp(x: f64) -> f64 {
    libm::exp(x)
}

/// Hyperbolic tangent (deterministic across targets).
#[inline]
pub fn tanh(x: f64) -> f64 {
    libm::tanh(x)
}

/// Natural logarithm (deterministic across targets).
#[inline]
pub fn ln(x: f64) -> f64 {
    libm::log(x)
}

/// x^y (deterministic across targets).
#[inline]
pub fn pow(x: f64, y: f64) -> f64 {
    libm::pow(x, y)
}

/// √(x² + y²) by plain arithmetic (exactly rounded sqrt), deterministic.
#[inline]
pub fn hypot(x: f64, y: f64) -> f64 {
    (x * x + y * y).sqrt()
}

/// Wraps an angle to (−π, π].
#[inline]
pub fn wrap_angle(a: f64) -> f64 {
    if a > -PI && a <= PI {
        return a;
    }
    let two_pi = 2.0 * PI;
    let mut r = a - two_pi * libm::floor((a + PI) / two_pi);
    if r <= -PI {
        r += two_pi;
    }
    if r > PI {
        r -= two_pi;
    }
    r
}

/// Small seeded random generator (SplitMix64): deterministic on every
/// target, no global state. Good enough for noise and jitter, not crypto.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Rng {
    state: u64,
}

impl Rng {
    /// A generator seeded with `seed`; equal seeds give equal streams.
    pub fn new(seed: u64) -> Self {
        Self { state: seed }
    }

    /// Next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    pub fn uniform(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// Uniform in [lo, hi).
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.uniform()
    }

    /// Standard normal sample (Box–Muller with the deterministic libm).
    pub fn normal(&mut self) -> f64 {
        let u1 = 1.0 - self.uniform(); // (0, 1]: ln is finite
        let u2 = self.uniform();
        (-2.0 * ln(u1)).sqrt() * cos(2.0 * PI * u2)
    }

    /// An independent generator for a sub-stream (e.g. one per mover).
    pub fn fork(&mut self, stream: u64) -> Rng {
        Rng::new(self.next_u64() ^ stream.wrapping_mul(0xD6E8_FEB8_6659_FD93))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sin_cos_keeps_every_bit_of_sin_and_cos() {
        let mut rng = Rng::new(11);
        let mut xs: Vec<f64> = vec![
            0.0,
            -0.0,
            f64::MIN_POSITIVE,
            f64::from_bits(1),
            PI,
            -PI,
            0.5 * PI,
            0.25 * PI,
            1e300,
            f64::INFINITY,
            f64::NAN,
        ];
        // Every scale, across the tiny-argument thresholds and π/4.
        for e in -60..12 {
            for _ in 0..2_000 {
                let x = rng.range(-1.0, 1.0) * 2f64.powi(e);
                xs.push(x);
            }
        }
        for b in [0x3e46_a09e_u64, 0x3e50_0000, 0x3fe9_21fb] {
            for lo in [0u64, 1, 0x7fff_ffff, 0xffff_ffff] {
                let x = f64::from_bits((b << 32) | lo);
                xs.extend([x, -x, f64::from_bits(x.to_bits() - 1)]);
            }
        }
        for x in xs {
            let (s, c) = sin_cos(x);
            assert_eq!(s.to_bits(), sin(x).to_bits(), "sin {x:e}");
            assert_eq!(c.to_bits(), cos(x).to_bits(), "cos {x:e}");
        }
    }

    #[test]
    fn wrap_angle_lands_in_half_open_interval() {
        for k in -20..20 {
            let a = k as f64 * 0.7;
            let w = wrap_angle(a);
            assert!(w > -PI && w <= PI, "{a} -> {w}");
            assert!((cos(w) - cos(a)).abs() < 1e-9 && (sin(w) - sin(a)).abs() < 1e-9);
        }
        assert_eq!(wrap_angle(-PI), PI);
    }

    #[test]
    fn rng_is_seeded_and_normal_has_unit_variance() {
        let mut a = Rng::new(7);
        let mut b = Rng::new(7);
        assert_eq!(a.next_u64(), b.next_u64());
        let n = 20_000;
        let xs: Vec<f64> = (0..n).map(|_| a.normal()).collect();
        let mean = xs.iter().sum::<f64>() / n as f64;
        let var = xs.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / n as f64;
        assert!(mean.abs() < 0.03, "mean {mean}");
        assert!((var - 1.0).abs() < 0.05, "var {var}");
    }
}
