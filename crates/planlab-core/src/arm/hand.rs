//! The moving human hand and forearm (\[T\] §5.3.3: the participant reaches
//! for a mouse across the table while the robot reaches for a stapler):
//! a sphere for the hand and a capsule for the forearm, moved by scripted
//! reaching motions with seeded variation.
//!
//! Reaches follow the minimum-jerk profile s(τ) = 10τ³ − 15τ⁴ + 6τ⁵ (Flash
//! & Hogan 1985), the usual model of human point-to-point reaching, with
//! an optional sideways bow `arc` (offset 4·s(1−s)·arc). The forearm points
//! from the hand towards a fixed elbow anchor (the person's side).

use glam::DVec3;
use serde::{Deserialize, Serialize};

use super::geometry::Obstacle3;
use super::ArmError;
use crate::num::{cos, Rng};
use crate::params::{check_param, Bound};

/// A scripted motion.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum HandPreset {
    /// Reach across the robot's workspace from the person's side to an
    /// object beyond the robot's path (crosses it once), then stay.
    #[default]
    ReachAcross,
    /// Reach straight towards the robot's target area, then stay.
    ReachToward,
    /// Reach across, hold briefly, pull back to the start.
    ReachRetract,
    /// Move back and forth between start and end (sinusoidal).
    Wave,
    /// Keep still at the start.
    Still,
}

impl HandPreset {
    /// Every preset, in the page's order.
    pub const ALL: [HandPreset; 5] = [
        HandPreset::ReachAcross,
        HandPreset::ReachToward,
        HandPreset::ReachRetract,
        HandPreset::Wave,
        HandPreset::Still,
    ];

    /// The kebab-case name used in scenario files.
    pub fn name(self) -> &'static str {
        match self {
            HandPreset::ReachAcross => "reach-across",
            HandPreset::ReachToward => "reach-toward",
            HandPreset::ReachRetract => "reach-retract",
            HandPreset::Wave => "wave",
            HandPreset::Still => "still",
        }
    }

    /// Default start, end, bow and elbow anchor of the preset (world, m),
    /// and its nominal duration, s. The scene: robot base at the origin
    /// facing +x, the person across the table at x ≈ 1.3 m.
    fn geometry(self) -> ([f64; 3], [f64; 3], [f64; 3], [f64; 3], f64) {
        match self {
            HandPreset::ReachAcross | HandPreset::ReachRetract | HandPreset::Wave => (
                [1.0, 0.45, 0.9],
                [0.6, 0.05, 0.92],
                [0.0, 0.0, 0.05],
                [1.35, 0.45, 1.0],
                4.0,
            ),
            HandPreset::ReachToward => (
                [1.05, 0.2, 0.9],
                [0.55, 0.15, 0.84],
                [0.0, 0.0, 0.04],
                [1.4, 0.25, 1.0],
                3.0,
            ),
            HandPreset::Still => (
                [0.6, 0.1, 0.88],
                [0.6, 0.1, 0.88],
                [0.0, 0.0, 0.0],
                [1.2, 0.2, 1.0],
                1.0,
            ),
        }
    }
}

/// The hand section of an arm scenario.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct HandSpec {
    /// Scripted motion.
    pub preset: HandPreset,
    /// Speed factor: durations are divided by it, 1.
    pub speed: f64,
    /// Time before the motion starts, s.
    pub delay_s: f64,
    /// Replaces the preset's start point of the hand centre, m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub start: Option<[f64; 3]>,
    /// Replaces the preset's end point of the hand centre, m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub end: Option<[f64; 3]>,
    /// Seeded variation: start and end move by up to this in each axis, m;
    /// the duration varies by up to ±10 % × (jitter / 0.02 m).
    pub jitter_m: f64,
    /// Radius of the hand sphere, m.
    pub hand_radius_m: f64,
    /// Forearm length from the hand centre towards the elbow, m.
    pub forearm_length_m: f64,
    /// Forearm capsule radius, m.
    pub forearm_radius_m: f64,
    /// Hold time at the far end of `reach-retract`, s.
    pub hold_s: f64,
}

impl Default for HandSpec {
    fn default() -> Self {
        Self {
            preset: HandPreset::ReachAcross,
            speed: 1.0,
            delay_s: 0.0,
            start: None,
            end: None,
            jitter_m: 0.0,
            hand_radius_m: 0.06,
            forearm_length_m: 0.3,
            forearm_radius_m: 0.045,
            hold_s: 1.0,
        }
    }
}

/// A hand motion with its variation drawn: positions over time.
#[derive(Debug, Clone, PartialEq)]
pub struct HandMotion {
    /// The settings it was built from.
    pub spec: HandSpec,
    start: DVec3,
    end: DVec3,
    arc: DVec3,
    anchor: DVec3,
    duration: f64,
    delay: f64,
}

/// Minimum-jerk position profile on τ ∈ [0, 1].
fn min_jerk(t: f64) -> f64 {
    let t = t.clamp(0.0, 1.0);
    t * t * t * (10.0 + t * (-15.0 + 6.0 * t))
}

impl HandMotion {
    /// Validates `spec` and draws its variation from `seed`.
    pub fn new(spec: &HandSpec, seed: u64) -> Result<HandMotion, ArmError> {
        let pos = |f: &str, v: f64| check_param(&format!("hand.{f}"), v, Bound::above(0.0));
        let nonneg = |f: &str, v: f64| check_param(&format!("hand.{f}"), v, Bound::at_least(0.0));
        pos("speed", spec.speed)?;
        pos("hand_radius_m", spec.hand_radius_m)?;
        pos("forearm_radius_m", spec.forearm_radius_m)?;
        nonneg("forearm_length_m", spec.forearm_length_m)?;
        nonneg("delay_s", spec.delay_s)?;
        nonneg("jitter_m", spec.jitter_m)?;
        nonneg("hold_s", spec.hold_s)?;
        for (f, p) in [("start", spec.start), ("end", spec.end)] {
            if p.is_some_and(|p| p.iter().any(|x| !x.is_finite())) {
                return Err(ArmError::NotFinite(format!("hand.{f}")));
            }
        }
        let (s, e, arc, anchor, dur) = spec.preset.geometry();
        let mut rng = Rng::new(seed ^ 0x4841_4E44); // "HAND"
        let j = spec.jitter_m;
        let mut jit = |p: [f64; 3]| {
            DVec3::from_array(p) + DVec3::new(rng.range(-j, j), rng.range(-j, j), rng.range(-j, j))
        };
        let start = jit(spec.start.unwrap_or(s));
        let end = jit(spec.end.unwrap_or(e));
        let dur_scale = 1.0 + rng.range(-0.1, 0.1) * (j / 0.02).min(1.0);
        Ok(HandMotion {
            spec: spec.clone(),
            start,
            end,
            arc: DVec3::from_array(arc),
            anchor: DVec3::from_array(anchor),
            duration: dur * dur_scale / spec.speed,
            delay: spec.delay_s,
        })
    }

    /// One reach's duration, s.
    pub fn duration(&self) -> f64 {
        self.duration
    }

    /// Time at which the motion is over (for the `wave` preset: never,
    /// `f64::INFINITY`), s.
    pub fn end_time(&self) -> f64 {
        match self.spec.preset {
            HandPreset::Wave => f64::INFINITY,
            HandPreset::Still => 0.0,
            HandPreset::ReachRetract => self.delay + 2.0 * self.duration + self.spec.hold_s,
            _ => self.delay + self.duration,
        }
    }

    fn along(&self, s: f64) -> DVec3 {
        self.start + (self.end - self.start) * s + self.arc * (4.0 * s * (1.0 - s))
    }

    /// Hand centre at time `t`, m.
    pub fn hand_at(&self, t: f64) -> DVec3 {
        let tau = (t - self.delay) / self.duration;
        let s = match self.spec.preset {
            HandPreset::Still => 0.0,
            HandPreset::ReachAcross | HandPreset::ReachToward => min_jerk(tau),
            HandPreset::ReachRetract => {
                let back = 1.0 + self.spec.hold_s / self.duration;
                if tau <= 1.0 {
                    min_jerk(tau)
                } else if tau <= back {
                    1.0
                } else {
                    1.0 - min_jerk(tau - back)
                }
            }
            HandPreset::Wave => {
                if tau <= 0.0 {
                    0.0
                } else {
                    // One reach's duration per half period.
                    0.5 - 0.5 * cos(std::f64::consts::PI * tau)
                }
            }
        };
        self.along(s)
    }

    /// Hand velocity at `t` by central difference over 1 ms, m/s.
    pub fn velocity_at(&self, t: f64) -> DVec3 {
        let h = 1e-3;
        (self.hand_at(t + h) - self.hand_at(t - h)) / (2.0 * h)
    }

    /// The obstacles of a hand centred at `hand`: the hand sphere and the
    /// forearm capsule from the wrist (hand surface) to the elbow.
    pub fn obstacles_for(&self, hand: DVec3) -> [Obstacle3; 2] {
        let to_elbow = self.anchor - hand;
        let len = to_elbow.length();
        let dir = if len > 1e-9 { to_elbow / len } else { DVec3::Z };
        let wrist = hand + dir * self.spec.hand_radius_m;
        let elbow = hand + dir * self.spec.forearm_length_m.max(self.spec.hand_radius_m);
        [
            Obstacle3::Sphere {
                centre: hand.to_array(),
                radius: self.spec.hand_radius_m,
            },
            Obstacle3::Capsule {
                a: wrist.to_array(),
                b: elbow.to_array(),
                radius: self.spec.forearm_radius_m,
            },
        ]
    }

    /// The obstacles at time `t`.
    pub fn obstacles_at(&self, t: f64) -> [Obstacle3; 2] {
        self.obstacles_for(self.hand_at(t))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reach_starts_and_ends_at_rest_on_its_points() {
        let m = HandMotion::new(&HandSpec::default(), 1).unwrap();
        let (s, e, ..) = HandPreset::ReachAcross.geometry();
        assert!((m.hand_at(0.0) - DVec3::from_array(s)).length() < 1e-12);
        assert!((m.hand_at(m.end_time() + 1.0) - DVec3::from_array(e)).length() < 1e-12);
        assert!(m.velocity_at(0.0).length() < 1e-3);
        // Peak speed of min-jerk is 1.875 × mean speed, mid-way.
        let mid = m.velocity_at(0.5 * m.duration()).length();
        let mean = (DVec3::from_array(e) - DVec3::from_array(s)).length() / m.duration();
        assert!((mid / mean - 1.875).abs() < 0.1, "{mid} {mean}");
    }

    #[test]
    fn speed_and_seed_change_the_motion_and_retract_returns() {
        let base = HandSpec {
            jitter_m: 0.03,
            ..HandSpec::default()
        };
        let a = HandMotion::new(&base, 1).unwrap();
        let b = HandMotion::new(&base, 2).unwrap();
        assert_ne!(a.hand_at(0.0), b.hand_at(0.0));
        assert_eq!(a, HandMotion::new(&base, 1).unwrap());
        let fast = HandMotion::new(
            &HandSpec {
                speed: 2.0,
                ..base.clone()
            },
            1,
        )
        .unwrap();
        assert!((fast.duration() * 2.0 - a.duration()).abs() < 1e-12);
        let r = HandMotion::new(
            &HandSpec {
                preset: HandPreset::ReachRetract,
                ..HandSpec::default()
            },
            0,
        )
        .unwrap();
        assert!((r.hand_at(r.end_time() + 0.1) - r.hand_at(0.0)).length() < 1e-12);
        assert!((r.hand_at(r.duration() + 0.5) - r.end).length() < 1e-12);
    }

    #[test]
    fn bad_specs_are_errors() {
        for spec in [
            HandSpec {
                speed: 0.0,
                ..HandSpec::default()
            },
            HandSpec {
                speed: f64::NAN,
                ..HandSpec::default()
            },
            HandSpec {
                hand_radius_m: -1.0,
                ..HandSpec::default()
            },
            HandSpec {
                start: Some([f64::INFINITY, 0.0, 0.0]),
                ..HandSpec::default()
            },
        ] {
            assert!(HandMotion::new(&spec, 0).is_err(), "{spec:?}");
        }
    }
}
