//! The arm's description file: a URDF-style serial chain of revolute
//! joints (\[T\] §2.4.2, Fig 2-8) in JSON, with joint limits and the capsule
//! radius of every link. `assets/arm/tiago.json` is the TIAGo-like arm.
//!
//! Every joint `i` has a fixed transform from the previous joint's frame
//! (`xyz` in metres, then `rpy` in radians, URDF order: roll about x, pitch
//! about y, yaw about z, fixed axes), then rotates by `q_i` about its unit
//! `axis`. The tool point sits at `tool.xyz` in the last joint's frame.
//! Link `i` (capsule) runs from joint `i`'s origin to joint `i+1`'s (the last
//! one to the tool point); link 0 runs from the base frame to joint 1.

use glam::{DMat3, DVec3};
use serde::{Deserialize, Serialize};

use super::ArmError;
use crate::num::{cos, sin};

/// Most joints a chain may have (keeps the IK's dense 3×n algebra small).
pub const MAX_JOINTS: usize = 16;

/// A rigid transform: rotation then translation (`p_world = rot·p + pos`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    /// Orientation (columns are the frame's x, y, z axes in world).
    pub rot: DMat3,
    /// Origin in world, m.
    pub pos: DVec3,
}

impl Frame {
    /// The identity frame.
    pub const IDENTITY: Frame = Frame {
        rot: DMat3::IDENTITY,
        pos: DVec3::ZERO,
    };

    /// `self ∘ other`: `other` expressed in `self`'s parent frame.
    pub fn compose(&self, other: &Frame) -> Frame {
        Frame {
            rot: self.rot * other.rot,
            pos: self.pos + self.rot * other.pos,
        }
    }

    /// A point given in this frame, in the parent frame.
    pub fn apply(&self, p: DVec3) -> DVec3 {
        self.pos + self.rot * p
    }
}

/// URDF fixed-axis roll–pitch–yaw rotation `Rz(yaw)·Ry(pitch)·Rx(roll)`
/// (deterministic sines).
pub fn rpy_matrix(rpy: [f64; 3]) -> DMat3 {
    let (sr, cr) = (sin(rpy[0]), cos(rpy[0]));
    let (sp, cp) = (sin(rpy[1]), cos(rpy[1]));
    let (sy, cy) = (sin(rpy[2]), cos(rpy[2]));
    DMat3::from_cols(
        DVec3::new(cy * cp, sy * cp, -sp),
        DVec3::new(cy * sp * sr - sy * cr, sy * sp * sr + cy * cr, cp * sr),
        DVec3::new(cy * sp * cr + sy * sr, sy * sp * cr - cy * sr, cp * cr),
    )
}

/// Rotation by `angle` about the unit `axis` (Rodrigues, deterministic).
pub fn axis_angle_matrix(axis: DVec3, angle: f64) -> DMat3 {
    let (s, c) = (sin(angle), cos(angle));
    let t = 1.0 - c;
    let (x, y, z) = (axis.x, axis.y, axis.z);
    DMat3::from_cols(
        DVec3::new(t * x * x + c, t * x * y + s * z, t * x * z - s * y),
        DVec3::new(t * x * y - s * z, t * y * y + c, t * y * z + s * x),
        DVec3::new(t * x * z + s * y, t * y * z - s * x, t * z * z + c),
    )
}

/// A fixed transform as written in the file.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct OriginSpec {
    /// Translation, m.
    #[serde(default)]
    pub xyz: [f64; 3],
    /// Roll, pitch, yaw, rad (URDF convention).
    #[serde(default)]
    pub rpy: [f64; 3],
}

impl OriginSpec {
    /// The transform.
    pub fn frame(&self) -> Frame {
        Frame {
            rot: rpy_matrix(self.rpy),
            pos: DVec3::from_array(self.xyz),
        }
    }
}

/// One revolute joint as written in the file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JointSpec {
    /// Name shown in the page's readout.
    pub name: String,
    /// Offset from the previous joint frame, m.
    pub xyz: [f64; 3],
    /// Rotation from the previous joint frame, rad (roll, pitch, yaw).
    #[serde(default)]
    pub rpy: [f64; 3],
    /// Rotation axis in the joint frame (normalised on load; must not be 0).
    pub axis: [f64; 3],
    /// Lower limit, rad.
    pub min: f64,
    /// Upper limit, rad.
    pub max: f64,
    /// Radius of the capsule of the link starting at this joint, m.
    pub link_radius: f64,
}

/// The arm file's JSON document.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ArmSpec {
    /// Short name.
    #[serde(default)]
    pub name: String,
    /// Free text: where the numbers come from.
    #[serde(default)]
    pub description: String,
    /// World pose of the chain's base frame.
    #[serde(default)]
    pub base: OriginSpec,
    /// Radius of link 0 (base frame to joint 1), m.
    pub base_link_radius: f64,
    /// The joints, base to tip.
    pub joints: Vec<JointSpec>,
    /// Tool point (end effector) in the last joint's frame.
    pub tool: OriginSpec,
    /// Starting posture, rad, one per joint (default: mid-range).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub home: Option<Vec<f64>>,
}

/// A validated serial arm, ready for kinematics.
#[derive(Debug, Clone, PartialEq)]
pub struct ArmModel {
    /// The file it was built from (axes as written).
    pub spec: ArmSpec,
    pub(crate) base: Frame,
    /// Per joint: fixed origin transform.
    pub(crate) origins: Vec<Frame>,
    /// Per joint: unit axis in the joint frame.
    pub(crate) axes: Vec<DVec3>,
    pub(crate) tool: Frame,
    pub(crate) home: Vec<f64>,
    /// Per joint: middle of the range (the IK's null-space target).
    pub(crate) rest: Vec<f64>,
}

/// The built-in TIAGo-like arm file.
pub const TIAGO_JSON: &str = include_str!("../../../../assets/arm/tiago.json");

fn finite3(what: &str, v: [f64; 3]) -> Result<(), ArmError> {
    if v.iter().all(|x| x.is_finite()) {
        Ok(())
    } else {
        Err(ArmError::NotFinite(what.to_string()))
    }
}

impl ArmModel {
    /// Parses and validates an arm file.
    pub fn from_json(text: &str) -> Result<ArmModel, ArmError> {
        let spec: ArmSpec =
            serde_json::from_str(text).map_err(|e| ArmError::Json(e.to_string()))?;
        ArmModel::from_spec(spec)
    }

    /// The built-in TIAGo-like arm (`assets/arm/tiago.json`).
    pub fn tiago() -> ArmModel {
        // The shipped file is checked by a test; fall back to nothing
        // partial: a failure here is a build defect, not user input.
        ArmModel::from_json(TIAGO_JSON).expect("assets/arm/tiago.json is valid")
    }

    /// Validates a parsed file: at least one and at most [`MAX_JOINTS`]
    /// joints, finite numbers, non-zero axes, `min ≤ max`, non-negative
    /// radii, a home posture of the right length inside the limits.
    pub fn from_spec(spec: ArmSpec) -> Result<ArmModel, ArmError> {
        if spec.joints.is_empty() {
            return Err(ArmError::NoJoints);
        }
        if spec.joints.len() > MAX_JOINTS {
            return Err(ArmError::TooManyJoints {
                found: spec.joints.len(),
                max: MAX_JOINTS,
            });
        }
        finite3("base.xyz", spec.base.xyz)?;
        finite3("base.rpy", spec.base.rpy)?;
        finite3("tool.xyz", spec.tool.xyz)?;
        finite3("tool.rpy", spec.tool.rpy)?;
        check_radius("base_link_radius", spec.base_link_radius)?;
        let mut origins = Vec::with_capacity(spec.joints.len());
        let mut axes = Vec::with_capacity(spec.joints.len());
        for (i, j) in spec.joints.iter().enumerate() {
            let at = |f: &str| format!("joints[{i}] ({}).{f}", j.name);
            finite3(&at("xyz"), j.xyz)?;
            finite3(&at("rpy"), j.rpy)?;
            finite3(&at("axis"), j.axis)?;
            if !j.min.is_finite() || !j.max.is_finite() {
                return Err(ArmError::NotFinite(at("min/max")));
            }
            if j.min > j.max {
                return Err(ArmError::LimitsInverted {
                    joint: j.name.clone(),
                    min: j.min,
                    max: j.max,
                });
            }
            check_radius(&at("link_radius"), j.link_radius)?;
            let axis = DVec3::from_array(j.axis);
            let len = axis.length();
            if len.is_nan() || len < 1e-9 {
                return Err(ArmError::ZeroAxis(j.name.clone()));
            }
            axes.push(axis / len);
            origins.push(Frame {
                rot: rpy_matrix(j.rpy),
                pos: DVec3::from_array(j.xyz),
            });
        }
        let home = match &spec.home {
            None => spec.joints.iter().map(|j| 0.5 * (j.min + j.max)).collect(),
            Some(h) => {
                if h.len() != spec.joints.len() {
                    return Err(ArmError::WrongJointCount {
                        what: "home".into(),
                        expected: spec.joints.len(),
                        found: h.len(),
                    });
                }
                for (q, j) in h.iter().zip(&spec.joints) {
                    if !q.is_finite() {
                        return Err(ArmError::NotFinite(format!("home ({})", j.name)));
                    }
                    if *q < j.min || *q > j.max {
                        return Err(ArmError::OutsideLimits {
                            joint: j.name.clone(),
                            value: *q,
                            min: j.min,
                            max: j.max,
                        });
                    }
                }
                h.clone()
            }
        };
        Ok(ArmModel {
            base: spec.base.frame(),
            tool: spec.tool.frame(),
            origins,
            axes,
            home,
            rest: spec.joints.iter().map(|j| 0.5 * (j.min + j.max)).collect(),
            spec,
        })
    }

    /// Number of joints.
    pub fn dof(&self) -> usize {
        self.axes.len()
    }

    /// Joint names, base to tip.
    pub fn joint_names(&self) -> Vec<String> {
        self.spec.joints.iter().map(|j| j.name.clone()).collect()
    }

    /// Lower and upper limit of joint `i`, rad.
    pub fn limits(&self, i: usize) -> (f64, f64) {
        let j = &self.spec.joints[i];
        (j.min, j.max)
    }

    /// The starting posture, rad.
    pub fn home(&self) -> &[f64] {
        &self.home
    }

    /// Capsule radius of each link (link 0 = base to joint 1), m.
    pub fn link_radii(&self) -> Vec<f64> {
        std::iter::once(self.spec.base_link_radius)
            .chain(self.spec.joints.iter().map(|j| j.link_radius))
            .collect()
    }

    /// Checks a joint vector: right length, finite, inside the limits.
    pub fn check_q(&self, q: &[f64]) -> Result<(), ArmError> {
        if q.len() != self.dof() {
            return Err(ArmError::WrongJointCount {
                what: "joint vector".into(),
                expected: self.dof(),
                found: q.len(),
            });
        }
        for (v, j) in q.iter().zip(&self.spec.joints) {
            if !v.is_finite() {
                return Err(ArmError::NotFinite(format!("joint {}", j.name)));
            }
            if *v < j.min || *v > j.max {
                return Err(ArmError::OutsideLimits {
                    joint: j.name.clone(),
                    value: *v,
                    min: j.min,
                    max: j.max,
                });
            }
        }
        Ok(())
    }

    /// Distance from joint 1's origin to the tool point summed along the
    /// chain (an upper bound of how far the tool can get from joint 1), m.
    pub fn reach(&self) -> f64 {
        self.origins
            .iter()
            .skip(1)
            .map(|o| o.pos.length())
            .sum::<f64>()
            + self.tool.pos.length()
    }

    /// World position of joint 1's origin (fixed: joint 1 rotates about
    /// it), m.
    pub fn shoulder(&self) -> DVec3 {
        self.base.compose(&self.origins[0]).pos
    }
}

fn check_radius(what: &str, r: f64) -> Result<(), ArmError> {
    if !r.is_finite() {
        return Err(ArmError::NotFinite(what.to_string()));
    }
    match crate::params::param_problem(r, 0.0, false) {
        None => Ok(()),
        Some(p) => Err(ArmError::Invalid(format!(
            "{what} = {} m: {p}",
            crate::num::fmt_num(r)
        ))),
    }
}
