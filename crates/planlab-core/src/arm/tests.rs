use std::f64::consts::FRAC_PI_2;

use glam::DVec3;
use proptest::prelude::*;

use super::geometry::{collides, link_distance};
use super::model::TIAGO_JSON;
use super::*;
use crate::num::Rng;

/// z-axis joint at the origin, y-axis joint 0.3 m up, y-axis joint 0.4 m
/// further along x, tool 0.3 m along x: easy to work out by hand.
const SIMPLE: &str = r#"{
  "base_link_radius": 0.05,
  "joints": [
    {"name": "yaw", "xyz": [0, 0, 0], "axis": [0, 0, 1], "min": -3, "max": 3, "link_radius": 0.05},
    {"name": "shoulder", "xyz": [0, 0, 0.3], "axis": [0, 1, 0], "min": -3, "max": 3, "link_radius": 0.04},
    {"name": "elbow", "xyz": [0.4, 0, 0], "axis": [0, 1, 0], "min": -3, "max": 3, "link_radius": 0.03}
  ],
  "tool": {"xyz": [0.3, 0, 0]}
}"#;

fn close(a: DVec3, b: DVec3, tol: f64) -> bool {
    (a - b).length() < tol
}

#[test]
fn fk_matches_hand_computed_poses() {
    let m = ArmModel::from_json(SIMPLE).unwrap();
    // Straight out along x.
    let f = m.fk(&[0.0, 0.0, 0.0]);
    assert!(close(f.tool, DVec3::new(0.7, 0.0, 0.3), 1e-12));
    assert!(close(f.joints[2].pos, DVec3::new(0.4, 0.0, 0.3), 1e-12));
    // Yaw 90°: along y.
    let f = m.fk(&[FRAC_PI_2, 0.0, 0.0]);
    assert!(close(f.tool, DVec3::new(0.0, 0.7, 0.3), 1e-12));
    // Rotation about +y by +90° takes +x to −z: shoulder down.
    let f = m.fk(&[0.0, FRAC_PI_2, 0.0]);
    assert!(close(f.tool, DVec3::new(0.0, 0.0, 0.3 - 0.7), 1e-12));
    // Elbow −90°: forearm straight up from (0.4, 0, 0.3).
    let f = m.fk(&[0.0, 0.0, -FRAC_PI_2]);
    assert!(close(f.tool, DVec3::new(0.4, 0.0, 0.6), 1e-12));
    // All three: yaw 90°, shoulder −90° (up), elbow 90° (forward again).
    let f = m.fk(&[FRAC_PI_2, -FRAC_PI_2, FRAC_PI_2]);
    assert!(close(f.joints[2].pos, DVec3::new(0.0, 0.0, 0.7), 1e-12));
    assert!(close(f.tool, DVec3::new(0.0, 0.3, 0.7), 1e-12));
    assert_eq!(f.link_segments().len(), 4);
}

#[test]
fn tiago_home_and_zero_poses_are_plausible() {
    let m = ArmModel::tiago();
    assert_eq!(m.dof(), 7);
    let sh = m.shoulder();
    assert!(close(sh, DVec3::new(0.15505, 0.014, 0.849), 1e-9), "{sh}");
    // TIAGo's arm reaches about 0.87 m to the wrist, plus the gripper.
    assert!((0.8..1.0).contains(&m.reach()), "{}", m.reach());
    // Tucked home posture keeps the hand close to the torso.
    let home = m.tool_position(m.home());
    assert!((home - sh).length() < 0.5, "{home}");
    // Every link is at least as long as written, every tool point within reach.
    let mut rng = Rng::new(3);
    for _ in 0..200 {
        let q: Vec<f64> = (0..7)
            .map(|i| rng.range(m.limits(i).0, m.limits(i).1))
            .collect();
        let t = m.tool_position(&q);
        assert!((t - sh).length() <= m.reach() + 1e-9);
    }
}

#[test]
fn jacobian_matches_finite_differences() {
    let m = ArmModel::tiago();
    let mut rng = Rng::new(11);
    for _ in 0..50 {
        let q: Vec<f64> = (0..7)
            .map(|i| rng.range(m.limits(i).0, m.limits(i).1))
            .collect();
        let j = m.jacobian(&m.fk(&q));
        for i in 0..7 {
            let h = 1e-6;
            let mut qp = q.clone();
            let mut qm = q.clone();
            qp[i] += h;
            qm[i] -= h;
            let fd = (m.tool_position(&qp) - m.tool_position(&qm)) / (2.0 * h);
            assert!((fd - j[i]).length() < 1e-7, "joint {i}: {fd} vs {}", j[i]);
        }
    }
}

#[test]
fn ik_reaches_reachable_targets_inside_the_limits() {
    let m = ArmModel::tiago();
    let cfg = IkConfig {
        max_iters: 400,
        ..IkConfig::default()
    };
    let mut rng = Rng::new(5);
    let mut solved = 0;
    let n = 100;
    for _ in 0..n {
        // Targets the arm provably reaches: tool points of random postures
        // away from the limits.
        let q_true: Vec<f64> = (0..7)
            .map(|i| {
                let (lo, hi) = m.limits(i);
                let pad = 0.1 * (hi - lo);
                rng.range(lo + pad, hi - pad)
            })
            .collect();
        let target = m.tool_position(&q_true);
        let mut q = m.home().to_vec();
        let r = m.ik_solve(&mut q, target, &cfg);
        m.check_q(&q).unwrap();
        assert!((m.tool_position(&q) - target).length() - r.error_m < 1e-12);
        if r.converged {
            solved += 1;
        }
    }
    // From the tucked home posture a few far targets lie behind joint-limit
    // folds that local IK cannot leave; nearly all converge.
    assert!(solved >= 90, "{solved} of {n}");
}

#[test]
fn ik_follows_a_path_in_small_steps() {
    // [T] §5.3.3: the end effector moves 0.04 m per step; each step is one
    // IK solve from the previous posture.
    let m = ArmModel::tiago();
    let cfg = IkConfig::default();
    let mut q = m.home().to_vec();
    let start = DVec3::new(0.45, 0.0, 1.0);
    let r = m.ik_solve(
        &mut q,
        start,
        &IkConfig {
            max_iters: 400,
            ..cfg
        },
    );
    assert!(r.converged, "{r:?}");
    let goal = DVec3::new(0.6, 0.35, 0.8);
    let steps = ((goal - start).length() / 0.04).ceil() as usize;
    for k in 1..=steps {
        let p = start + (goal - start) * (k as f64 / steps as f64);
        let r = m.ik_solve(&mut q, p, &cfg);
        assert!(r.converged, "step {k}: {r:?}");
        m.check_q(&q).unwrap();
    }
}

#[test]
fn ik_respects_limits_when_the_target_is_out_of_reach() {
    let m = ArmModel::tiago();
    let mut q = m.home().to_vec();
    let far = m.shoulder() + DVec3::new(2.0, 0.0, 0.0);
    let cfg = IkConfig {
        max_iters: 200,
        ..IkConfig::default()
    };
    let before = (m.tool_position(&q) - far).length();
    let r = m.ik_solve(&mut q, far, &cfg);
    assert!(!r.converged);
    m.check_q(&q).unwrap();
    // It stretches towards the target (damped near the singular straight
    // arm, so not all the way: the best is 2 m − reach).
    assert!(r.error_m < before - 0.2, "{before} {r:?}");
    assert!(r.error_m >= 2.0 - m.reach());
}

#[test]
fn capsule_distances_agree_with_geometry() {
    let link = LinkCapsule {
        a: DVec3::ZERO,
        b: DVec3::new(1.0, 0.0, 0.0),
        radius: 0.1,
    };
    let ball = Obstacle3::Sphere {
        centre: [0.5, 0.5, 0.0],
        radius: 0.2,
    };
    assert!((link_distance(&link, &ball) - 0.2).abs() < 1e-9);
    let cap = Obstacle3::Capsule {
        a: [2.0, -1.0, 0.3],
        b: [2.0, 1.0, 0.3],
        radius: 0.05,
    };
    let want = (1.0f64 + 0.09).sqrt() - 0.15;
    // parry's capsule–capsule distance is iterative (GJK): close, not exact.
    assert!((link_distance(&link, &cap) - want).abs() < 1e-6);
    let touching = Obstacle3::Sphere {
        centre: [0.5, 0.0, 0.0],
        radius: 0.05,
    };
    assert_eq!(link_distance(&link, &touching), 0.0);
    assert!(collides(&[link], &[touching]));
    assert!(!collides(&[link], &[ball, cap]));
    // A zero-length link is a ball.
    let dot = LinkCapsule {
        a: DVec3::ONE,
        b: DVec3::ONE,
        radius: 0.1,
    };
    let d = link_distance(
        &dot,
        &Obstacle3::Sphere {
            centre: [1.0, 1.0, 2.0],
            radius: 0.5,
        },
    );
    assert!((d - 0.4).abs() < 1e-9);
    assert!((ball.point_distance(DVec3::new(0.5, 1.0, 0.0)) - 0.3).abs() < 1e-12);
}

fn tiago_tree() -> serde_json::Value {
    serde_json::from_str(TIAGO_JSON).unwrap()
}

#[test]
fn bad_arm_files_are_typed_errors() {
    let with = |f: &dyn Fn(&mut serde_json::Value)| {
        let mut t = tiago_tree();
        f(&mut t);
        ArmModel::from_json(&t.to_string()).unwrap_err()
    };
    assert!(matches!(
        with(&|t| t["joints"] = serde_json::json!([])),
        ArmError::NoJoints
    ));
    assert!(matches!(
        with(&|t| { t.as_object_mut().unwrap().remove("joints"); }),
        ArmError::Json(m) if m.contains("joints")
    ));
    assert!(matches!(
        with(&|t| t["joints"][2]["min"] = serde_json::json!(2.0)),
        ArmError::LimitsInverted { joint, .. } if joint == "arm_3"
    ));
    assert!(matches!(
        with(&|t| t["joints"][1]["axis"] = serde_json::json!([0, 0, 0])),
        ArmError::ZeroAxis(j) if j == "arm_2"
    ));
    assert!(matches!(
        with(&|t| t["home"] = serde_json::json!([0.0, 0.0])),
        ArmError::WrongJointCount {
            expected: 7,
            found: 2,
            ..
        }
    ));
    assert!(matches!(
        with(&|t| t["home"][0] = serde_json::json!(3.0)),
        ArmError::OutsideLimits { .. }
    ));
    assert!(matches!(
        with(&|t| t["joints"][0]["link_radius"] = serde_json::json!(-0.1)),
        ArmError::Invalid(m) if m.contains("link_radius")
    ));
    assert!(matches!(
        with(&|t| t["joints"][0]["typo"] = serde_json::json!(1)),
        ArmError::Json(m) if m.contains("typo")
    ));
    // JSON has no NaN; 1e999 overflows to infinity in some parsers and is
    // an error in serde_json. Either way: an error, not a panic.
    let text = TIAGO_JSON.replacen("0.15505", "1e999", 1);
    assert!(ArmModel::from_json(&text).is_err());
    let spec = ArmSpec {
        joints: vec![JointSpec {
            name: "j".into(),
            xyz: [f64::NAN, 0.0, 0.0],
            rpy: [0.0; 3],
            axis: [0.0, 0.0, 1.0],
            min: -1.0,
            max: 1.0,
            link_radius: 0.1,
        }],
        ..serde_json::from_str(TIAGO_JSON).unwrap()
    };
    assert!(matches!(ArmModel::from_spec(spec), Err(ArmError::NotFinite(f)) if f.contains("xyz")));
    assert!(ArmError::NoJoints.to_string().contains("no joints"));
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    /// Malformed arm files never panic: random bytes, and the real file
    /// with a slice cut out or replaced.
    #[test]
    fn malformed_arm_files_never_panic(
        junk in ".{0,200}",
        cut_at in 0usize..2000,
        cut_len in 0usize..80,
        insert in prop::sample::select(vec!["", "-", "1e308", "NaN", "null", "[", "}", "\"", "0", "99"]),
    ) {
        let _ = ArmModel::from_json(&junk);
        let bytes = TIAGO_JSON.as_bytes();
        let a = cut_at.min(bytes.len());
        let b = (a + cut_len).min(bytes.len());
        let mut s = String::from_utf8_lossy(&bytes[..a]).into_owned();
        s.push_str(insert);
        s.push_str(&String::from_utf8_lossy(&bytes[b..]));
        if let Ok(m) = ArmModel::from_json(&s) {
            // Whatever parses is usable: FK and IK run without panic.
            let mut q = m.home().to_vec();
            let _ = m.fk(&q);
            let _ = m.ik_solve(&mut q, DVec3::new(0.5, 0.0, 0.9), &IkConfig::default());
        }
    }
}
