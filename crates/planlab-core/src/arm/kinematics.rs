//! Forward kinematics (every joint frame and the tool point), the
//! positional Jacobian, and damped-least-squares inverse kinematics with
//! joint limits (docs/algorithms.md §arm; \[T\] §5.3.3 moves the end effector in
//! 0.04 m steps along the planned path).
//!
//! The IK is positional: the planners of \[T\] ch. 4 plan the end
//! effector's position only, so the 3×n Jacobian leaves the redundant
//! degrees of freedom to a null-space pull towards the rest posture, which
//! also keeps the joints away from their limits.

use glam::{DMat3, DVec3};
use serde::{Deserialize, Serialize};

use super::model::{axis_angle_matrix, ArmModel, Frame};
use super::ArmError;

/// Frames of one posture.
#[derive(Debug, Clone, PartialEq)]
pub struct Frames {
    /// World frame of every joint after its rotation, base to tip.
    pub joints: Vec<Frame>,
    /// World frame of the base.
    pub base: Frame,
    /// The tool point (end effector) in world, m.
    pub tool: DVec3,
}

impl Frames {
    /// Link segment end points: link 0 from the base to joint 1, link `i`
    /// from joint `i` to joint `i+1`, the last to the tool point.
    pub fn link_segments(&self) -> Vec<(DVec3, DVec3)> {
        let mut pts = Vec::with_capacity(self.joints.len() + 2);
        pts.push(self.base.pos);
        pts.extend(self.joints.iter().map(|f| f.pos));
        pts.push(self.tool);
        pts.windows(2).map(|w| (w[0], w[1])).collect()
    }
}

impl ArmModel {
    /// Forward kinematics of posture `q` (length [`ArmModel::dof`]; a
    /// shorter slice leaves the remaining joints at 0).
    pub fn fk(&self, q: &[f64]) -> Frames {
        let mut f = self.base;
        let mut joints = Vec::with_capacity(self.dof());
        for (i, (o, axis)) in self.origins.iter().zip(&self.axes).enumerate() {
            let qi = q.get(i).copied().unwrap_or(0.0);
            f = f.compose(o);
            f.rot *= axis_angle_matrix(*axis, qi);
            joints.push(f);
        }
        let tool = f.apply(self.tool.pos);
        Frames {
            joints,
            base: self.base,
            tool,
        }
    }

    /// The tool point of posture `q`, m.
    pub fn tool_position(&self, q: &[f64]) -> DVec3 {
        self.fk(q).tool
    }

    /// World axis of every joint in `frames` (the columns' directions).
    pub fn joint_axes(&self, frames: &Frames) -> Vec<DVec3> {
        frames
            .joints
            .iter()
            .zip(&self.axes)
            .map(|(f, a)| f.rot * *a)
            .collect()
    }

    /// Positional Jacobian ∂tool/∂q at `frames`: column `i` is
    /// `axis_i × (tool − origin_i)`.
    pub fn jacobian(&self, frames: &Frames) -> Vec<DVec3> {
        frames
            .joints
            .iter()
            .zip(&self.axes)
            .map(|(f, a)| (f.rot * *a).cross(frames.tool - f.pos))
            .collect()
    }
}

/// Damped-least-squares IK settings.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct IkConfig {
    /// Largest damping λ of (J Jᵀ + λ² I)⁻¹, used at a singularity, m.
    pub damping: f64,
    /// Manipulability √det(J Jᵀ) below which damping starts (above it the
    /// step is the exact pseudo-inverse, so the null-space pull does not
    /// leak into the task), m³.
    pub damping_threshold: f64,
    /// Iterations per solve at most.
    pub max_iters: u32,
    /// Position error accepted as solved, m.
    pub tolerance_m: f64,
    /// Largest change of one joint in one iteration, rad.
    pub max_joint_step_rad: f64,
    /// Gain of the null-space pull towards mid-range, 1/iteration.
    pub nullspace_gain: f64,
    /// Gain of the null-space turn of the gripper (last joint → tool point)
    /// towards pointing away from the shoulder horizontally, so the hand
    /// leads and the wrist trails as in a natural reach (0 = off),
    /// 1/iteration.
    pub approach_gain: f64,
}

impl Default for IkConfig {
    fn default() -> Self {
        Self {
            damping: 0.05,
            damping_threshold: 0.005,
            max_iters: 30,
            tolerance_m: 1e-4,
            max_joint_step_rad: 0.2,
            nullspace_gain: 0.05,
            approach_gain: 0.3,
        }
    }
}

impl IkConfig {
    /// Refuses non-finite or out-of-range values, naming the field.
    pub fn validate(&self) -> Result<(), ArmError> {
        let bad = |f: &str, v: f64| {
            ArmError::Invalid(format!(
                "ik.{f} = {}: must be > 0 and at most {}",
                crate::num::fmt_num(v),
                crate::num::fmt_num(crate::num::MAX_PARAM)
            ))
        };
        for (f, v) in [
            ("damping", self.damping),
            ("damping_threshold", self.damping_threshold),
            ("tolerance_m", self.tolerance_m),
            ("max_joint_step_rad", self.max_joint_step_rad),
        ] {
            if crate::params::param_problem(v, 0.0, true).is_some() {
                return Err(bad(f, v));
            }
        }
        if !self.nullspace_gain.is_finite() || !(0.0..=1.0).contains(&self.nullspace_gain) {
            return Err(ArmError::Invalid(format!(
                "ik.nullspace_gain must be in [0, 1], got {}",
                self.nullspace_gain
            )));
        }
        if !self.approach_gain.is_finite() || !(0.0..=1.0).contains(&self.approach_gain) {
            return Err(ArmError::Invalid(format!(
                "ik.approach_gain must be in [0, 1], got {}",
                self.approach_gain
            )));
        }
        if self.max_iters == 0 {
            return Err(ArmError::Invalid("ik.max_iters must be ≥ 1".into()));
        }
        Ok(())
    }
}

/// What one IK solve did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IkReport {
    /// Iterations run.
    pub iters: u32,
    /// Remaining distance from the tool to the target, m.
    pub error_m: f64,
    /// Whether `error_m ≤ tolerance_m`.
    pub converged: bool,
}

/// Inverts the symmetric positive-definite 3×3 `m` (J Jᵀ + λ² I is, for
/// λ > 0). `None` when it is numerically singular.
fn inverse_spd(m: DMat3) -> Option<DMat3> {
    let det = m.determinant();
    if !det.is_finite() || det.abs() < 1e-300 {
        return None;
    }
    Some(m.inverse())
}

impl ArmModel {
    /// One damped-least-squares iteration from `q` towards `target`:
    /// Δq = Jᵀ(J Jᵀ + λ²I)⁻¹ e + (I − J⁺J)·k(q_mid − q), each joint step
    /// capped, then clamped to the limits. Joints sitting at a limit and
    /// pushed outwards are frozen (their column removed) and the step is
    /// recomputed, so the others take over. Returns the new posture's error.
    pub fn ik_iteration(&self, q: &mut [f64], target: DVec3, cfg: &IkConfig) -> f64 {
        let n = self.dof().min(q.len());
        let frames = self.fk(q);
        let e = target - frames.tool;
        let mut cols = self.jacobian(&frames);
        let axes = self.joint_axes(&frames);
        let e_approach = match frames.joints.last() {
            Some(last) if cfg.approach_gain > 0.0 => {
                let have = (frames.tool - last.pos).normalize_or_zero();
                let mut want = frames.tool - self.shoulder();
                want.z = 0.0;
                have.cross(want.normalize_or_zero())
            }
            _ => DVec3::ZERO,
        };
        let mut dq = [0.0; super::model::MAX_JOINTS];
        for _pass in 0..2 {
            // A = J Jᵀ + λ² I (3×3), λ growing as the manipulability w
            // falls below its threshold w₀: λ² = λ₀²(1 − w/w₀)²
            // (Nakamura & Hanafusa 1986).
            let mut jjt = DMat3::ZERO;
            for c in cols.iter().take(n) {
                jjt += outer(*c, *c);
            }
            let w = jjt.determinant().max(0.0).sqrt();
            let lambda2 = if w < cfg.damping_threshold {
                let f = 1.0 - w / cfg.damping_threshold;
                cfg.damping * cfg.damping * f * f
            } else {
                0.0
            };
            let a = jjt + DMat3::from_diagonal(DVec3::splat(lambda2.max(1e-12)));
            let Some(a_inv) = inverse_spd(a) else {
                return e.length();
            };
            let w = a_inv * e;
            // Null-space projection of the rest-posture pull:
            // z − J⁺ (J z) with J⁺ = Jᵀ A⁻¹.
            let mut z = [0.0; super::model::MAX_JOINTS];
            let mut jz = DVec3::ZERO;
            for i in 0..n {
                z[i] = cfg.nullspace_gain * (self.rest[i] - q[i]);
                // Gradient step of the approach alignment: the rotation
                // vector taking the gripper axis onto the wanted one,
                // projected on each joint axis (J_ωᵀ e_ω).
                z[i] += cfg.approach_gain * axes[i].dot(e_approach);
                jz += cols[i] * z[i];
            }
            let u = a_inv * jz;
            let mut frozen = false;
            for i in 0..n {
                let mut d = cols[i].dot(w) + z[i] - cols[i].dot(u);
                if cols[i] == DVec3::ZERO {
                    d = 0.0;
                }
                dq[i] = d.clamp(-cfg.max_joint_step_rad, cfg.max_joint_step_rad);
                let (lo, hi) = self.limits(i);
                let at_lo = q[i] <= lo && dq[i] < 0.0;
                let at_hi = q[i] >= hi && dq[i] > 0.0;
                if (at_lo || at_hi) && cols[i] != DVec3::ZERO {
                    cols[i] = DVec3::ZERO;
                    frozen = true;
                }
            }
            if !frozen {
                break;
            }
        }
        for i in 0..n {
            let (lo, hi) = self.limits(i);
            q[i] = (q[i] + dq[i]).clamp(lo, hi);
        }
        (target - self.tool_position(q)).length()
    }

    /// Iterates [`ArmModel::ik_iteration`] until the tool is within
    /// `cfg.tolerance_m` of `target` or `cfg.max_iters` ran. `q` is updated
    /// in place and always stays inside the limits.
    pub fn ik_solve(&self, q: &mut [f64], target: DVec3, cfg: &IkConfig) -> IkReport {
        let mut err = (target - self.tool_position(q)).length();
        let mut iters = 0;
        while err > cfg.tolerance_m && iters < cfg.max_iters {
            err = self.ik_iteration(q, target, cfg);
            iters += 1;
        }
        IkReport {
            iters,
            error_m: err,
            converged: err <= cfg.tolerance_m,
        }
    }
}

fn outer(a: DVec3, b: DVec3) -> DMat3 {
    DMat3::from_cols(a * b.x, a * b.y, a * b.z)
}
