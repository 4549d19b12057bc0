//! Robot body and kinematics (docs/algorithms.md §robot): differential drive \[T\] eq 2-1…2-3
//! and omnidirectional / 4WIS \[C\] eq 12, circle or rectangle footprint.

use serde::{Deserialize, Serialize};

use super::{check_min, check_positive, WorldError};
use crate::num::{sin_cos, wrap_angle};

/// Drive type.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum Drive {
    /// Differential drive: commands (v, ω), no sideways motion.
    #[default]
    Differential,
    /// Omnidirectional / four-wheel independent steering: (v_x, v_y, ω) in
    /// the body frame.
    Omnidirectional,
}

/// Robot footprint, centred on the robot's reference point.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", tag = "shape", deny_unknown_fields)]
pub enum Footprint {
    /// A disc.
    Circle {
        /// Radius, metres.
        radius: f64,
    },
    /// A rectangle aligned with the heading.
    Rectangle {
        /// Extent along the heading, metres.
        length: f64,
        /// Extent across the heading, metres.
        width: f64,
    },
}

impl Default for Footprint {
    fn default() -> Self {
        Footprint::Circle { radius: 0.2 }
    }
}

impl Footprint {
    /// Radius of the smallest disc centred on the robot that contains it.
    pub fn circumscribed_radius(&self) -> f64 {
        match *self {
            Footprint::Circle { radius } => radius,
            Footprint::Rectangle { length, width } => {
                0.5 * (length * length + width * width).sqrt()
            }
        }
    }

    /// Radius of the largest disc centred on the robot inside it.
    pub fn inscribed_radius(&self) -> f64 {
        match *self {
            Footprint::Circle { radius } => radius,
            Footprint::Rectangle { length, width } => 0.5 * length.min(width),
        }
    }

    fn validate(&self) -> Result<(), WorldError> {
        match *self {
            Footprint::Circle { radius } => check_positive("robot.footprint.radius (m)", radius),
            Footprint::Rectangle { length, width } => {
                check_positive("robot.footprint.length (m)", length)?;
                check_positive("robot.footprint.width (m)", width)
            }
        }
    }
}

/// Kinematic limits of the robot. Defaults are a small indoor robot; each
/// paper's preset sets its own values.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RobotLimits {
    /// Largest forward speed, m/s.
    pub v_max: f64,
    /// Smallest forward speed (negative = may reverse), m/s.
    pub v_min: f64,
    /// Largest sideways speed |v_y| (omnidirectional only), m/s.
    pub vy_max: f64,
    /// Largest turn rate |ω|, rad/s.
    pub w_max: f64,
    /// Largest linear acceleration / deceleration, m/s².
    pub acc_v: f64,
    /// Largest sideways acceleration (omnidirectional only), m/s².
    pub acc_vy: f64,
    /// Largest angular acceleration, rad/s².
    pub acc_w: f64,
}

impl Default for RobotLimits {
    fn default() -> Self {
        Self {
            v_max: 1.0,
            v_min: 0.0,
            vy_max: 0.0,
            w_max: 40f64.to_radians(),
            acc_v: 0.2,
            acc_vy: 0.0,
            acc_w: 50f64.to_radians(),
        }
    }
}

/// The robot: drive, footprint, limits.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, Default)]
#[serde(default, deny_unknown_fields)]
pub struct RobotSpec {
    /// Drive type.
    pub drive: Drive,
    /// Body outline.
    pub footprint: Footprint,
    /// Kinematic limits.
    pub limits: RobotLimits,
    /// Distance between the drive wheels (differential drive), metres; used
    /// to report wheel speeds v_l, v_r.
    pub wheel_base: f64,
}

/// Pose and velocities of the robot at one instant.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, Default)]
pub struct RobotState {
    /// x, metres.
    pub x: f64,
    /// y, metres.
    pub y: f64,
    /// Heading, radians in (−π, π].
    pub theta: f64,
    /// Forward speed, m/s (body frame).
    pub v: f64,
    /// Sideways speed, m/s (body frame, left positive; 0 for differential).
    pub vy: f64,
    /// Turn rate, rad/s (counter-clockwise positive).
    pub w: f64,
}

/// A velocity command in the body frame.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, Default)]
pub struct Command {
    /// Forward speed, m/s.
    pub v: f64,
    /// Sideways speed, m/s (omnidirectional only).
    pub vy: f64,
    /// Turn rate, rad/s.
    pub w: f64,
}

impl RobotSpec {
    /// Checks every number (finite, in range).
    pub fn validate(&self) -> Result<(), WorldError> {
        self.footprint.validate()?;
        let l = &self.limits;
        check_positive("robot.limits.v_max (m/s)", l.v_max)?;
        if !(l.v_min.is_finite() && l.v_min <= l.v_max && l.v_min >= -crate::num::MAX_PARAM) {
            return Err(WorldError::InvalidParameter(format!(
                "robot.limits.v_min = {} m/s: must be finite, ≥ -{} and ≤ v_max",
                crate::num::fmt_num(l.v_min),
                crate::num::fmt_num(crate::num::MAX_PARAM)
            )));
        }
        check_min("robot.limits.vy_max (m/s)", l.vy_max, 0.0)?;
        check_positive("robot.limits.w_max (rad/s)", l.w_max)?;
        check_positive("robot.limits.acc_v (m/s²)", l.acc_v)?;
        check_min("robot.limits.acc_vy (m/s²)", l.acc_vy, 0.0)?;
        check_positive("robot.limits.acc_w (rad/s²)", l.acc_w)?;
        check_min("robot.wheel_base (m)", self.wheel_base, 0.0)
    }

    /// Clamps a command to the speed limits and to what the accelerations
    /// allow from `state` within `dt`: what the motors can actually do.
    pub fn feasible(&self, state: &RobotState, cmd: Command, dt: f64) -> Command {
        let l = &self.limits;
        let clamp = |x: f64, lo: f64, hi: f64| {
            if x.is_nan() {
                lo.max(0.0).min(hi)
            } else {
                x.max(lo).min(hi)
            }
        };
        let v = clamp(cmd.v, l.v_min, l.v_max);
        let v = clamp(v, state.v - l.acc_v * dt, state.v + l.acc_v * dt);
        let w = clamp(cmd.w, -l.w_max, l.w_max);
        let w = clamp(w, state.w - l.acc_w * dt, state.w + l.acc_w * dt);
        let vy = match self.drive {
            Drive::Differential => 0.0,
            Drive::Omnidirectional => {
                let vy = clamp(cmd.vy, -l.vy_max, l.vy_max);
                clamp(vy, state.vy - l.acc_vy * dt, state.vy + l.acc_vy * dt)
            }
        };
        Command { v, vy, w }
    }

    /// Wheel speeds (v_l, v_r) of a differential drive for (v, ω):
    /// v = (v_l + v_r)/2, ω = (v_r − v_l)/L, positive ω turning left.
    pub fn wheel_speeds(&self, v: f64, w: f64) -> (f64, f64) {
        let half = 0.5 * w * self.wheel_base;
        (v - half, v + half)
    }
}

/// Advances a state by one step of `dt` under `cmd` (docs/algorithms.md §robot Euler update,
/// the same one DWA rollouts use): x += (v cosθ − v_y sinθ)Δt,
/// y += (v sinθ + v_y cosθ)Δt, θ += ωΔt. The command becomes the new velocity.
#[inline]
pub fn integrate(state: &RobotState, cmd: Command, dt: f64) -> RobotState {
    integrate_turned(state, cmd, dt, sin_cos(state.theta))
}

/// [`integrate`] given `(sin θ, cos θ)` of the state's heading (computed
/// once for many steps from the same heading).
#[inline(always)]
pub fn integrate_turned(
    state: &RobotState,
    cmd: Command,
    dt: f64,
    (s, c): (f64, f64),
) -> RobotState {
    RobotState {
        x: state.x + (cmd.v * c - cmd.vy * s) * dt,
        y: state.y + (cmd.v * s + cmd.vy * c) * dt,
        theta: wrap_angle(state.theta + cmd.w * dt),
        v: cmd.v,
        vy: cmd.vy,
        w: cmd.w,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn positive_omega_turns_left_and_wheels_match() {
        let spec = RobotSpec {
            wheel_base: 0.4,
            ..Default::default()
        };
        let (vl, vr) = spec.wheel_speeds(0.5, 1.0);
        assert!(vr > vl);
        assert!(((vl + vr) / 2.0 - 0.5).abs() < 1e-12);
        assert!(((vr - vl) / 0.4 - 1.0).abs() < 1e-12);
        let mut s = RobotState::default();
        for _ in 0..10 {
            s = integrate(
                &s,
                Command {
                    v: 0.5,
                    vy: 0.0,
                    w: 1.0,
                },
                0.1,
            );
        }
        assert!(s.y > 0.0 && s.theta > 0.9);
    }

    #[test]
    fn feasible_respects_acceleration_and_nan() {
        let spec = RobotSpec::default();
        let s = RobotState::default();
        let c = spec.feasible(
            &s,
            Command {
                v: 5.0,
                vy: 3.0,
                w: f64::NAN,
            },
            0.1,
        );
        assert!((c.v - 0.02).abs() < 1e-12, "{c:?}");
        assert_eq!(c.vy, 0.0);
        assert!(c.w.is_finite());
    }

    #[test]
    fn validate_rejects_nan_and_negative() {
        let mut spec = RobotSpec::default();
        spec.limits.v_max = f64::NAN;
        assert!(spec.validate().is_err());
        let spec = RobotSpec {
            footprint: Footprint::Circle { radius: -1.0 },
            ..Default::default()
        };
        assert!(spec.validate().is_err());
        assert!(RobotSpec::default().validate().is_ok());
    }
}
