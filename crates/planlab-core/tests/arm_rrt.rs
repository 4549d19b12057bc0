//! RRT-Connect for the 7-DOF arm (docs/algorithms.md §arm-rrt): paths
//! within limits and collision-free at a finer resolution than the
//! planner's, determinism, shortcutting never lengthens or invalidates,
//! replanning when the hand is placed on the path, typed errors.

use glam::DVec3;
use planlab_core::arm::episode::ARM_CLEARANCE_M;
use planlab_core::arm::rrt::{
    clearance_of, joint_path_length, rrt_connect, shortcut, within_limits, ArmChecker, RrtConfig,
};
use planlab_core::arm::{ArmEpisode, ArmError, ArmModel, ArmPlanner, IkConfig, Obstacle3};
use planlab_core::num::Rng;
use planlab_core::scenario::ArmScenario;
use planlab_core::world::Outcome;

const TAB5_3: &str = include_str!("../../../assets/scenarios/T-tab5-3.json");
const TABLE_Z: f64 = 0.72;

/// A posture putting the tool on `p` (IK from home).
fn posture(m: &ArmModel, p: [f64; 3]) -> Vec<f64> {
    let mut q = m.home().to_vec();
    let cfg = IkConfig {
        max_iters: 400,
        ..IkConfig::default()
    };
    let r = m.ik_solve(&mut q, DVec3::from_array(p), &cfg);
    assert!(r.converged, "IK to {p:?}: {r:?}");
    q
}

/// A hand sphere and forearm between the T-tab5-3 start and goal.
fn blocking_hand() -> Vec<Obstacle3> {
    vec![
        Obstacle3::Sphere {
            centre: [0.62, 0.1, 0.95],
            radius: 0.06,
        },
        Obstacle3::Capsule {
            a: [0.67, 0.13, 0.96],
            b: [0.9, 0.3, 0.98],
            radius: 0.045,
        },
    ]
}

/// Independent check of a path: every posture inside the limits, and
/// along every straight move, at most 1 mm of link sweep apart (a tenth of
/// the planner's 10 mm), no link touching the obstacles, the table or a
/// link three or more away.
fn assert_path_free(m: &ArmModel, path: &[Vec<f64>], obstacles: &[Obstacle3], table: Option<f64>) {
    let fine = ArmChecker::new(m, vec![], None, 0.0, 1e-3);
    let radii = m.link_radii();
    for w in path.windows(2) {
        let n = fine.checks_for(&w[0], &w[1]);
        for k in 0..=n {
            let f = k as f64 / n as f64;
            let q: Vec<f64> = w[0]
                .iter()
                .zip(&w[1])
                .map(|(a, b)| a + (b - a) * f)
                .collect();
            assert!(within_limits(m, &q), "outside the limits: {q:?}");
            let links = planlab_core::arm::link_capsules(&m.fk(&q), &radii);
            let d = clearance_of(&links, obstacles, table);
            assert!(d > 0.0, "contact at {q:?} (clearance {d})");
        }
    }
}

fn plan(seed: u64) -> (ArmModel, Vec<Vec<f64>>, Vec<Obstacle3>) {
    let m = ArmModel::tiago();
    let start = posture(&m, [0.45, -0.05, 1.0]);
    let goal = posture(&m, [0.6, 0.35, 0.82]);
    let obs = blocking_hand();
    let cfg = RrtConfig::default();
    let mut c = ArmChecker::new(
        &m,
        obs.clone(),
        Some(TABLE_Z),
        ARM_CLEARANCE_M,
        cfg.check_sweep_m,
    );
    let p = rrt_connect(&mut c, &start, &goal, &cfg, &mut Rng::new(seed)).expect("a path");
    assert_eq!(p.path.first().unwrap(), &start);
    assert_eq!(p.path.last().unwrap(), &goal);
    (m, p.path, obs)
}

#[test]
fn rrt_connect_paths_are_collision_free_at_a_finer_resolution_and_within_limits() {
    for seed in 0..4 {
        let (m, path, obs) = plan(seed);
        assert!(path.len() >= 2);
        assert_path_free(&m, &path, &obs, Some(TABLE_Z));
        // Every tree edge changes no joint by more than the step.
        for w in path.windows(2) {
            let largest = w[0]
                .iter()
                .zip(&w[1])
                .map(|(a, b)| (b - a).abs())
                .fold(0.0, f64::max);
            assert!(
                largest <= RrtConfig::default().step_rad + 1e-12,
                "{largest}"
            );
        }
    }
}

#[test]
fn the_same_seed_gives_the_same_path_and_another_seed_another() {
    let (_, a, _) = plan(7);
    let (_, b, _) = plan(7);
    let (_, c, _) = plan(8);
    assert_eq!(a, b);
    assert_ne!(a, c);
}

#[test]
fn shortcutting_never_lengthens_or_invalidates_a_path() {
    for seed in 0..4 {
        let (m, path, obs) = plan(seed);
        let cfg = RrtConfig::default();
        let mut c = ArmChecker::new(
            &m,
            obs.clone(),
            Some(TABLE_Z),
            ARM_CLEARANCE_M,
            cfg.check_sweep_m,
        );
        let mut rng = Rng::new(seed);
        let mut p = path.clone();
        let before = joint_path_length(&path);
        // Attempt by attempt: never longer, same ends, still free.
        for _ in 0..20 {
            let next = shortcut(&mut c, &p, 5, &mut rng);
            assert!(joint_path_length(&next) <= joint_path_length(&p) + 1e-12);
            assert_eq!(next.first(), path.first());
            assert_eq!(next.last(), path.last());
            p = next;
        }
        assert_path_free(&m, &p, &obs, Some(TABLE_Z));
        assert!(
            joint_path_length(&p) < before,
            "100 attempts shorten an RRT path: {} vs {before}",
            joint_path_length(&p)
        );
    }
}

#[test]
fn bad_postures_are_typed_errors() {
    let m = ArmModel::tiago();
    let start = posture(&m, [0.45, -0.05, 1.0]);
    let goal = posture(&m, [0.6, 0.35, 0.82]);
    let cfg = RrtConfig::default();
    let mut rng = Rng::new(0);
    let mut c = ArmChecker::new(&m, blocking_hand(), Some(TABLE_Z), ARM_CLEARANCE_M, 0.01);
    // Goal outside the limits.
    let mut out = goal.clone();
    out[0] = 5.0;
    let e = rrt_connect(&mut c, &start, &out, &cfg, &mut rng).unwrap_err();
    assert!(matches!(e, ArmError::OutsideLimits { .. }), "{e}");
    // NaN.
    let mut nan = start.clone();
    nan[3] = f64::NAN;
    let e = rrt_connect(&mut c, &nan, &goal, &cfg, &mut rng).unwrap_err();
    assert!(matches!(e, ArmError::NotFinite(_)), "{e}");
    // Wrong length.
    let e = rrt_connect(&mut c, &start[..3], &goal, &cfg, &mut rng).unwrap_err();
    assert!(matches!(e, ArmError::WrongJointCount { .. }), "{e}");
    // Start in collision: a hand on the tool.
    let tool = m.tool_position(&start).to_array();
    let mut c = ArmChecker::new(
        &m,
        vec![Obstacle3::Sphere {
            centre: tool,
            radius: 0.05,
        }],
        None,
        ARM_CLEARANCE_M,
        0.01,
    );
    let e = rrt_connect(&mut c, &start, &goal, &cfg, &mut rng).unwrap_err();
    assert!(
        matches!(e, ArmError::PostureBlocked { ref what, .. } if what == "start posture"),
        "{e}"
    );
    assert!(e.to_string().contains("start posture is blocked"), "{e}");
    // Bad settings.
    let bad = RrtConfig {
        step_rad: f64::NAN,
        ..cfg
    };
    assert!(rrt_connect(&mut c, &start, &goal, &bad, &mut rng).is_err());
    // A goal posture with a hand on its tool.
    let on_goal = vec![Obstacle3::Sphere {
        centre: m.tool_position(&goal).to_array(),
        radius: 0.03,
    }];
    let mut under = ArmChecker::new(&m, on_goal, Some(TABLE_Z), ARM_CLEARANCE_M, 0.01);
    let e = rrt_connect(&mut under, &start, &goal, &cfg, &mut rng).unwrap_err();
    assert!(
        matches!(e, ArmError::PostureBlocked { ref what, .. } if what == "goal posture"),
        "{e}"
    );
}

#[test]
fn no_path_within_the_iterations_is_reported_with_them() {
    // The goal walled in by a shell of spheres around its tool point (the
    // posture itself free): the trees cannot meet in 40 iterations.
    let m = ArmModel::tiago();
    let start = posture(&m, [0.45, -0.05, 1.0]);
    let goal = posture(&m, [0.6, 0.35, 0.82]);
    let g = m.tool_position(&goal);
    let mut shell = Vec::new();
    for i in 0..12 {
        for j in 0..6 {
            let (th, ph) = (i as f64 * std::f64::consts::FRAC_PI_6, 0.3 + j as f64 * 0.5);
            let d = DVec3::new(ph.sin() * th.cos(), ph.sin() * th.sin(), ph.cos());
            let o = Obstacle3::Sphere {
                centre: (g + d * 0.2).to_array(),
                radius: 0.07,
            };
            // Only spheres that leave both end postures free.
            let free = |q: &[f64]| {
                let links = planlab_core::arm::link_capsules(&m.fk(q), &m.link_radii());
                clearance_of(&links, &[o], None) > 0.01
            };
            if free(&start) && free(&goal) {
                shell.push(o);
            }
        }
    }
    let cfg = RrtConfig {
        max_iterations: 40,
        ..RrtConfig::default()
    };
    let mut c = ArmChecker::new(&m, shell, None, ARM_CLEARANCE_M, cfg.check_sweep_m);
    match rrt_connect(&mut c, &start, &goal, &cfg, &mut Rng::new(1)) {
        Err(ArmError::NoPath { iterations }) => assert_eq!(iterations, 40),
        other => panic!("expected no path, got {other:?}"),
    }
}

fn tab5_3(planner: ArmPlanner) -> ArmScenario {
    let mut s = ArmScenario::from_json(TAB5_3).unwrap();
    s.arm.planner = planner;
    // The preset has no table (its reproduction's variants are pinned to
    // its text); the comparison sets this one.
    s.arm.table_z_m = Some(TABLE_Z);
    s
}

#[test]
fn the_tab5_3_episode_with_rrt_connect_reaches_without_touching_the_hand_or_table() {
    let s = tab5_3(ArmPlanner::RrtConnect);
    let mut ep = ArmEpisode::from_scenario(&s).unwrap();
    assert_eq!(ep.run().unwrap(), Outcome::Reached);
    let m = ep.metrics();
    assert!(m.min_obstacle_distance_m > 0.0, "{m:?}");
    assert!(ep.min_table_distance() > 0.0);
    let e = ep.effort();
    assert!(
        e.plans >= 1 && e.iterations >= 1 && e.collision_checks > 100,
        "{e:?}"
    );
    assert!(ep.joint_path_length() > 0.1);
    // The tool ends on the goal posture's tool point.
    let goal = DVec3::from_array(s.arm.goal);
    assert!((ep.model().tool_position(ep.q()) - goal).length() <= s.arm.sim.goal_tolerance_m);
    // Same seed, same run.
    let mut again = ArmEpisode::from_scenario(&s).unwrap();
    again.run().unwrap();
    assert_eq!(again.tool_path(), ep.tool_path());
    assert_eq!(again.effort(), ep.effort());
}

#[test]
fn a_hand_placed_on_the_path_makes_the_arm_replan_and_still_reach() {
    // A probe run with the hand still, far from the arm, gives the first
    // plan; the real run's hand starts at the same place, waits, then
    // moves onto the middle of that path and stays there.
    let far = [0.95, 0.5, 0.95];
    let mut s = tab5_3(ArmPlanner::RrtConnect);
    s.arm.hand.jitter_m = 0.0;
    s.arm.hand.preset = planlab_core::arm::HandPreset::Still;
    s.arm.hand.start = Some(far);
    s.arm.hand.end = Some(far);
    let mut probe = ArmEpisode::from_scenario(&s).unwrap();
    probe.step().unwrap();
    let tools = probe.planned_tool_path();
    // 40 % of the way along the tool's path.
    let total: f64 = tools.windows(2).map(|w| (w[1] - w[0]).length()).sum();
    let mut run = 0.0;
    let mut mid = tools[0];
    for w in tools.windows(2) {
        run += (w[1] - w[0]).length();
        mid = w[1];
        if run >= 0.4 * total {
            break;
        }
    }
    s.arm.hand.preset = planlab_core::arm::HandPreset::ReachAcross;
    s.arm.hand.speed = 2.0;
    s.arm.hand.end = Some(mid.to_array());
    let mut ep = ArmEpisode::from_scenario(&s).unwrap();
    ep.step().unwrap();
    let first = ep.planned_path();
    assert_eq!(ep.planned_tool_path(), tools, "the same first plan");
    // The hand's final place blocks that first path.
    let rest = ep.hand().obstacles_at(100.0);
    let model = ep.model().clone();
    let mut c = ArmChecker::new(&model, rest.to_vec(), None, 1e-9, 0.01);
    assert!(
        !c.path_valid(&first),
        "the hand's final place must block the first path"
    );
    let out = ep.run().unwrap();
    let e = ep.effort();
    assert!(e.replans >= 1, "replanned: {e:?}");
    assert_eq!(out, Outcome::Reached, "{e:?} min {}", ep.min_distance());
    assert!(ep.min_distance() > 0.0);
    // Where the hand rests, the path the arm took avoided it.
    assert!(ep.tool_path().iter().all(|p| (*p - mid).length() > 0.06));
}

#[test]
fn bad_rrt_scenes_are_typed_errors() {
    // Start posture under the table.
    let mut s = tab5_3(ArmPlanner::RrtConnect);
    s.arm.table_z_m = Some(0.95);
    let e = ArmEpisode::from_scenario(&s).unwrap_err();
    assert!(matches!(e, ArmError::PostureBlocked { .. }), "{e}");
    // NaN table, bad step.
    let mut s = tab5_3(ArmPlanner::RrtConnect);
    s.arm.table_z_m = Some(f64::NAN);
    assert!(matches!(
        ArmEpisode::from_scenario(&s).unwrap_err(),
        ArmError::NotFinite(_)
    ));
    let mut s = tab5_3(ArmPlanner::RrtConnect);
    s.arm.rrt.step_rad = -0.1;
    assert!(matches!(
        ArmEpisode::from_scenario(&s).unwrap_err(),
        ArmError::Invalid(_)
    ));
    // Unknown planner name in the file.
    let t = TAB5_3.replace("\"arm\": {", "\"arm\": { \"planner\": \"prm\",");
    assert!(ArmScenario::from_json(&t).is_err());
    let t = TAB5_3.replace("\"arm\": {", "\"arm\": { \"planner\": \"rrt-connect\",");
    assert_eq!(
        ArmScenario::from_json(&t).unwrap().arm.planner,
        ArmPlanner::RrtConnect
    );
}
