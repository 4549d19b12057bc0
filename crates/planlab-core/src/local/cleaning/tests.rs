//! Unit tests of the cleaning DWA.

use super::odometry::mat_vec;
use super::path::l1_to_segment;
use super::step::{axis_samples, LoadWindow};
use super::*;
use crate::local::engine::generator::{Sample, Trajectory, TrajectoryGenerator};
use crate::local::testkit;
use crate::local::{GoalKind, LocalPlanner, Observation, OdometrySample};
use crate::num::{cos, sin, Rng};
use crate::world::terrain::{SlipSpec, Terrain, TerrainSpec, VehicleSpec, GRAVITY};
use crate::world::{Command, Drive, Footprint, RobotLimits};
use serde_json::json;

fn robot() -> RobotSpec {
    RobotSpec {
        drive: Drive::Omnidirectional,
        footprint: Footprint::Circle { radius: 0.35 },
        limits: RobotLimits {
            v_max: 0.4,
            v_min: -0.4,
            vy_max: 0.4,
            w_max: 1.0,
            acc_v: 2.0,
            acc_vy: 2.0,
            acc_w: 1.0,
        },
        wheel_base: 0.5,
    }
}

/// A 10 × 6 m walled yard at 0.05 m per cell, optionally with a box.
fn yard(with_box: bool) -> StaticMap {
    let (w, h) = (200, 120);
    let mut rows = Vec::new();
    for r in 0..h {
        let mut line = String::new();
        for c in 0..w {
            let edge = r == 0 || c == 0 || r == h - 1 || c == w - 1;
            // Box around (5, 3) m: cols 95–104, rows 55–64.
            let boxed = with_box && (95..105).contains(&c) && (55..65).contains(&r);
            line.push(if edge || boxed { '#' } else { '.' });
        }
        rows.push(line);
    }
    testkit::map(&rows.join("\n"), 0.05)
}

fn planner(
    name: &str,
    config: serde_json::Value,
    map: &StaticMap,
    start: &RobotState,
    goal: [f64; 2],
) -> CleaningDwa {
    let name: &'static str = if name == "cleaning-dwa" {
        "cleaning-dwa"
    } else {
        "traditional-dwa"
    };
    CleaningDwa::new(
        name,
        parse(name, &config).unwrap(),
        &robot(),
        map,
        start,
        goal,
    )
    .unwrap()
}

fn obs<'a>(state: &'a RobotState, map: &'a StaticMap, accel_z: f64) -> Observation<'a> {
    Observation {
        time: 0.0,
        dt: 0.1,
        state,
        goal: [8.0, 3.0],
        map,
        map_revision: 0,
        scan: None,
        movers: &[],
        odometry: None,
        accel_z,
    }
}

#[test]
fn least_squares_recovers_a_known_k() {
    let k_true = [[0.93, 0.02, 0.01], [0.06, 0.97, -0.02], [0.01, 0.0, 0.9]];
    let mut rng = Rng::new(4);
    let pairs: Vec<_> = (0..60)
        .map(|_| {
            let u = [
                rng.range(0.0, 0.04),
                rng.range(-0.03, 0.03),
                rng.range(-0.1, 0.1),
            ];
            let mut us = mat_vec(&k_true, u);
            for x in &mut us {
                *x += 2e-4 * rng.normal();
            }
            (u, us)
        })
        .collect();
    let k = fit_k(&pairs, &IDENTITY, 0.0, KStructure::Full).unwrap();
    for i in 0..3 {
        for j in 0..3 {
            assert!((k[i][j] - k_true[i][j]).abs() < 0.02, "{k:?}");
        }
    }
    // A small ridge changes little when every direction is excited.
    let kr = fit_k(&pairs, &IDENTITY, 0.01, KStructure::Full).unwrap();
    assert!((kr[1][0] - 0.06).abs() < 0.02, "{kr:?}");
}

#[test]
fn singular_system_keeps_the_previous_k() {
    // Never turning, never moving sideways: Σuuᵀ has rank 1.
    let pairs: Vec<_> = (0..20)
        .map(|i| {
            let u = [0.03 + 1e-4 * i as f64, 0.0, 0.0];
            (u, [0.9 * u[0], 0.05 * u[0], 0.0])
        })
        .collect();
    assert_eq!(fit_k(&pairs, &IDENTITY, 0.0, KStructure::Full), None);
    assert_eq!(fit_k(&[], &IDENTITY, 0.0, KStructure::Block), None);
    // With the ridge the excited column is fitted, the others stay.
    let k = fit_k(&pairs, &IDENTITY, 0.01, KStructure::Full).unwrap();
    assert!(
        (k[0][0] - 0.9).abs() < 0.02 && (k[1][0] - 0.05).abs() < 0.01,
        "{k:?}"
    );
    assert_eq!([k[0][1], k[1][1], k[2][2]], [0.0, 1.0, 1.0]);
    // In the planner: ridge 0 and degenerate samples leave the identity.
    let map = yard(false);
    let s = RobotState {
        x: 1.0,
        y: 3.0,
        ..Default::default()
    };
    let mut p = planner("cleaning-dwa", json!({"ridge": 0.0}), &map, &s, [8.0, 3.0]);
    for (u, us) in &pairs {
        let mut o = obs(&s, &map, 0.0);
        o.odometry = Some(OdometrySample {
            wheel: *u,
            laser: *us,
        });
        let c = p.step(&o);
        assert!(c.v.is_finite() && c.vy.is_finite() && c.w.is_finite());
    }
    assert_eq!(p.k(), IDENTITY);
    // Non-finite samples are ignored.
    let mut o = obs(&s, &map, 0.0);
    o.odometry = Some(OdometrySample {
        wheel: [f64::NAN, 0.0, 0.0],
        laser: [0.0; 3],
    });
    p.step(&o);
    assert_eq!(p.k(), IDENTITY);
}

#[test]
fn compensated_rollout_predicts_the_slipping_motion() {
    let k_true = [[0.9, 0.03, 0.0], [0.08, 0.95, 0.0], [0.0, 0.0, 0.85]];
    let map = yard(false);
    let s = RobotState {
        x: 2.0,
        y: 3.0,
        theta: 0.4,
        ..Default::default()
    };
    let p = planner("cleaning-dwa", json!({}), &map, &s, [8.0, 3.0]);
    let mut gen = LoadWindow::new(p.config().clone(), &p.robot);
    gen.set_inputs(k_true, 0.0);
    let cmd = Command {
        v: 0.3,
        vy: -0.1,
        w: 0.5,
    };
    let o = obs(&s, &map, 0.0);
    let sample = Sample { cmd, decel: 0.0 };
    let mut traj = Trajectory::default();
    gen.rollout(&o, sample, 20, &mut traj);
    let pts = traj.points.clone();
    assert_eq!(pts.len(), 20);
    let spec = TerrainSpec {
        slip: SlipSpec {
            k_true,
            ..Default::default()
        },
        ..Default::default()
    };
    let mut t = Terrain::new(spec, 0).unwrap();
    let mut st = s;
    for q in &pts {
        st = t.step(&st, cmd, 0.1).next;
        assert!(
            (st.x - q[0]).abs() < 1e-9 && (st.y - q[1]).abs() < 1e-9,
            "{st:?} vs {q:?}"
        );
    }
    // The uncompensated prediction misses by centimetres.
    gen.set_inputs(IDENTITY, 0.0);
    gen.rollout(&o, sample, 20, &mut traj);
    let ideal = traj.points.clone();
    let (a, b) = (ideal[19], pts[19]);
    assert!((a[0] - b[0]).abs() + (a[1] - b[1]).abs() > 0.05);
}

#[test]
fn heads_along_the_path_whatever_the_heading() {
    let map = yard(false);
    for theta in [0.0, std::f64::consts::FRAC_PI_2, 2.5] {
        let s = RobotState {
            x: 1.0,
            y: 3.0,
            theta,
            ..Default::default()
        };
        let mut p = planner("cleaning-dwa", json!({}), &map, &s, [8.0, 3.0]);
        p.set_record_rollouts(true);
        let c = p.step(&obs(&s, &map, 0.0));
        // World velocity of the command: east, at the window's edge.
        let (sn, cs) = (sin(theta), cos(theta));
        let (ve, vn) = (c.v * cs - c.vy * sn, c.v * sn + c.vy * cs);
        assert!(
            ve > 0.15 && vn.abs() < 0.05,
            "θ {theta}: {c:?} → ({ve}, {vn})"
        );
        let d = p.debug();
        assert_eq!(d.goal_kind, GoalKind::Intermediate);
        assert!((d.current_goal[0] - 2.5).abs() < 0.01 && (d.current_goal[1] - 3.0).abs() < 0.05);
        assert!(d.rollouts.len() > 1000, "{}", d.rollouts.len());
        let ch = &d.rollouts[d.chosen.unwrap()];
        assert_eq!(ch.cmd, c);
        assert!(d
            .rollouts
            .iter()
            .filter(|r| r.admissible)
            .all(|r| r.score <= ch.score));
        assert_eq!(ch.raw.len(), 4);
        assert!(
            (ch.score + 0.1 * ch.raw[0] + 0.3 * ch.raw[1] + 0.6 * ch.raw[2] + 0.1 * ch.raw[3])
                .abs()
                < 1e-9
        );
    }
}

#[test]
fn global_path_goes_through_the_waypoints_around_the_box() {
    let map = yard(true);
    let s = RobotState {
        x: 1.0,
        y: 3.0,
        ..Default::default()
    };
    let p = planner(
        "cleaning-dwa",
        json!({"waypoints": [[3.0, 1.5]]}),
        &map,
        &s,
        [8.0, 3.0],
    );
    let path = &p.debug().global_path;
    assert_eq!(path[0], [1.0, 3.0]);
    assert_eq!(*path.last().unwrap(), [8.0, 3.0]);
    let near = |q: [f64; 2]| {
        path.windows(2)
            .any(|w| crate::geom::distance_to_polyline(q, w).unwrap() < 0.05)
    };
    assert!(near([3.0, 1.5]));
    // Every vertex keeps the robot radius from the box (and walls).
    for q in path {
        assert!(map.clearance(q[0], q[1]) >= 0.3, "{q:?}");
    }
}

#[test]
fn stops_at_every_waypoint_when_asked() {
    let map = yard(false);
    let s = RobotState {
        x: 1.0,
        y: 3.0,
        ..Default::default()
    };
    let wps = json!({"waypoints": [[3.0, 3.0], [5.0, 3.0]], "stop_at_waypoints": true});
    let mut p = planner("cleaning-dwa", wps, &map, &s, [8.0, 3.0]);
    let r = testkit::run(&mut p, &map, &robot(), s, [8.0, 3.0], &[], 60.0, 0.2);
    assert_eq!(r.end, testkit::End::Reached);
    // Near each waypoint the robot slowed almost to a stop.
    for w in [3.0, 5.0] {
        let slowest = r
            .states
            .iter()
            .filter(|st| (st.x - w).abs() < 0.15)
            .map(|st| st.v.hypot(st.vy))
            .fold(f64::INFINITY, f64::min);
        assert!(slowest < 0.08, "at x = {w}: {slowest}");
    }
    // Passing through, it keeps its speed there.
    let mut p = planner(
        "cleaning-dwa",
        json!({"waypoints": [[3.0, 3.0], [5.0, 3.0]]}),
        &map,
        &s,
        [8.0, 3.0],
    );
    let r = testkit::run(&mut p, &map, &robot(), s, [8.0, 3.0], &[], 60.0, 0.2);
    let at3 = r
        .states
        .iter()
        .filter(|st| (st.x - 3.0).abs() < 0.15)
        .map(|st| st.v.hypot(st.vy))
        .fold(f64::INFINITY, f64::min);
    assert!(at3 > 0.3, "{at3}");
}

#[test]
fn drives_around_an_obstacle_to_the_goal() {
    let map = yard(true);
    for name in ["cleaning-dwa", "traditional-dwa"] {
        let s = RobotState {
            x: 1.0,
            y: 3.0,
            ..Default::default()
        };
        let mut p = planner(name, json!({}), &map, &s, [8.5, 3.0]);
        let r = testkit::run(&mut p, &map, &robot(), s, [8.5, 3.0], &[], 60.0, 0.2);
        assert_eq!(
            r.end,
            testkit::End::Reached,
            "{name}: {:?}",
            r.states.last()
        );
        assert!(r.min_clearance > 0.05, "{name}: {}", r.min_clearance);
    }
}

#[test]
fn load_limit_shrinks_the_window() {
    let map = yard(false);
    let s = RobotState {
        x: 1.0,
        y: 3.0,
        ..Default::default()
    };
    let veh = VehicleSpec::default();
    let jmg = 0.2 * veh.mass * GRAVITY;
    for az in [0.0, 0.8, 1.5] {
        let mut trad = planner("traditional-dwa", json!({}), &map, &s, [8.0, 3.0]);
        let mut clean = planner("cleaning-dwa", json!({}), &map, &s, [8.0, 3.0]);
        let ct = trad.step(&obs(&s, &map, az));
        let cc = clean.step(&obs(&s, &map, az));
        // From rest the baseline jumps to the full 2 m/s².
        assert!((ct.v - 0.2).abs() < 1e-9, "{ct:?}");
        let loads = veh.wheel_loads(cc.v / 0.1, cc.vy / 0.1, az);
        assert!(
            loads.iter().all(|&f| f >= jmg - 1e-9),
            "a_z {az}: {cc:?} {loads:?}"
        );
        let bound = (GRAVITY - 0.8 * GRAVITY - az) * 1.25;
        assert!(
            cc.v / 0.1 <= bound.min(2.0) + 1e-9 && cc.v > 0.0,
            "a_z {az}: {cc:?}"
        );
        if az > 0.5 {
            assert_eq!(clean.debug().mode, "load-limited");
        }
    }
    // Beyond g(1 − 4j) no acceleration is allowed: keep the velocity.
    let moving = RobotState {
        v: 0.25,
        vy: 0.05,
        ..s
    };
    let mut clean = planner("cleaning-dwa", json!({}), &map, &moving, [8.0, 3.0]);
    let c = clean.step(&obs(&moving, &map, 2.5));
    assert_eq!((c.v, c.vy), (0.25, 0.05));
    // The per-axis (eq 14) variant allows up to the bound on each axis.
    let mut boxed = planner(
        "cleaning-dwa",
        json!({"load_region": "box"}),
        &map,
        &s,
        [8.0, 3.0],
    );
    let c = boxed.step(&obs(&s, &map, 1.5));
    assert!(c.v / 0.1 <= (0.2 * GRAVITY - 1.5) * 1.25 + 1e-9, "{c:?}");
}

#[test]
fn axis_samples_are_centred_and_bounded() {
    let s = axis_samples(0.1, -0.1, 0.3, 0.02, 41);
    assert!(s.contains(&0.1) && s.contains(&-0.1) && s.contains(&0.3));
    assert_eq!(s.len(), 21);
    let s = axis_samples(0.29, 0.09, 0.3, 0.02, 41);
    assert_eq!(*s.last().unwrap(), 0.3);
    assert!(s.contains(&0.29));
    let s = axis_samples(0.0, -0.2, 0.2, 0.0001, 41);
    assert!(s.len() <= 43 && s.contains(&0.0));
    assert_eq!(axis_samples(0.5, 0.0, 0.0, 0.02, 41), vec![0.0]);
    assert!((l1_to_segment([1.0, 2.0], [0.0, 0.0], [4.0, 0.0]) - 2.0).abs() < 1e-12);
    assert!((l1_to_segment([1.0, 1.0], [0.0, 0.0], [2.0, 2.0])).abs() < 1e-12);
    assert!((l1_to_segment([-1.0, 1.0], [0.0, 0.0], [2.0, 0.0]) - 2.0).abs() < 1e-12);
}

#[test]
fn bad_config_names_the_field() {
    let map = yard(false);
    let s = RobotState {
        x: 1.0,
        y: 3.0,
        ..Default::default()
    };
    let err = |name: &'static str, cfg: serde_json::Value, want: &str| {
        let e = parse(name, &cfg)
            .and_then(|c| CleaningDwa::new(name, c, &robot(), &map, &s, [8.0, 3.0]))
            .err()
            .unwrap()
            .to_string();
        assert!(e.contains(want), "{e} / {want}");
    };
    err("cleaning-dwa", json!({"alpha": -1.0}), "cleaning-dwa.alpha");
    err("cleaning-dwa", json!({"v_res": 0.0}), "cleaning-dwa.v_res");
    err(
        "traditional-dwa",
        json!({"lookahead": -0.5}),
        "traditional-dwa.lookahead",
    );
    err(
        "cleaning-dwa",
        json!({"load_fraction": 0.3}),
        "cleaning-dwa.load_fraction",
    );
    err(
        "cleaning-dwa",
        json!({"vehicle": {"mass": -1.0}}),
        "cleaning-dwa.vehicle.mass",
    );
    err("cleaning-dwa", json!({"window": 1}), "cleaning-dwa.window");
    err(
        "cleaning-dwa",
        json!({"min_samples": 60}),
        "cleaning-dwa.min_samples",
    );
    err(
        "cleaning-dwa",
        json!({"accel_z_hold": 0}),
        "cleaning-dwa.accel_z_hold",
    );
    err(
        "cleaning-dwa",
        json!({"twirl": f64::NAN}),
        "cleaning-dwa.config",
    );
    err("cleaning-dwa", json!({"twirl": -1.0}), "cleaning-dwa.twirl");
    err(
        "cleaning-dwa",
        json!({"waypoint_tolerance": 0.0}),
        "cleaning-dwa.waypoint_tolerance",
    );
    err(
        "cleaning-dwa",
        json!({"max_speed": -0.1}),
        "cleaning-dwa.max_speed",
    );
    err(
        "cleaning-dwa",
        json!({"window": -4}),
        "cleaning-dwa.config.window",
    );
    err(
        "cleaning-dwa",
        json!({"load_region": "circle"}),
        "cleaning-dwa.config.load_region",
    );
    err(
        "cleaning-dwa",
        json!({"sim_time": 1e9}),
        "cleaning-dwa.sim_time",
    );
    err(
        "cleaning-dwa",
        json!({"waypoints": [[50.0, 1.0]]}),
        "waypoints[0]",
    );
    err(
        "cleaning-dwa",
        json!({"waypoints": [[0.02, 3.0]]}),
        "no global path",
    );
    let cfg = CleaningDwaConfig {
        gamma: f64::NAN,
        ..Default::default()
    };
    assert!(cfg
        .validate("cleaning-dwa")
        .unwrap_err()
        .to_string()
        .contains("cleaning-dwa.gamma"));
    // Defaults of the two entries.
    let t = parse("traditional-dwa", &serde_json::Value::Null).unwrap();
    assert!(!t.load_limit && !t.compensate);
    let t = parse("traditional-dwa", &json!({"compensate": true})).unwrap();
    assert!(t.compensate && !t.load_limit);
    assert_eq!(
        parse("cleaning-dwa", &json!({})).unwrap(),
        CleaningDwaConfig::default()
    );
    let f = field_list(true);
    assert!(f
        .iter()
        .any(|i| i.name == "compensate" && i.default == json!(false)));
}
