//! LiDAR navigation through the public API: the navigator on synthetic
//! scans (temporary goals, hold, iteration), degenerate scans, and the
//! navigator planner on a map.

use planlab_core::lidar::nav::carry;
use planlab_core::lidar::planner::{LocalMapConfig, ScanNavigation, MOTION_GOAL};
use planlab_core::lidar::scan::{beam_angle, Lidar, LidarConfig};
use planlab_core::lidar::{LidarNavConfig, NavInput, Navigator, Scan, TargetKind, Velocity};
use planlab_core::local::dwa::{Dwa, DwaConfig};
use planlab_core::map::{OccupancyGrid, Pose2};
use planlab_core::planners::PlannerChoice;
use planlab_core::world::{Footprint, RobotLimits, RobotSpec, StaticMap};

const N: usize = 360;

/// The scan of straight wall x = `x` for |y| ≤ `half` (robot at the origin).
fn wall_scan(x: f64, y_lo: f64, y_hi: f64) -> Scan {
    let r: Vec<f64> = (0..N)
        .map(|i| {
            let a = beam_angle(i, N);
            let (c, s) = (a.cos(), a.sin());
            if c <= 1e-9 {
                return f64::INFINITY;
            }
            let t = x / c;
            let y = t * s;
            if y >= y_lo && y <= y_hi {
                t
            } else {
                f64::INFINITY
            }
        })
        .collect();
    Scan::new(r, 10.0)
}

fn input(scan: &Scan, goal: [f64; 2]) -> NavInput<'_> {
    NavInput {
        scan,
        velocity: Velocity::default(),
        goal,
        dt: 0.1,
    }
}

fn robot() -> RobotSpec {
    RobotSpec {
        footprint: Footprint::Circle { radius: 0.3 },
        limits: RobotLimits {
            v_max: 1.0,
            v_min: 0.0,
            vy_max: 0.0,
            w_max: 5.0 * std::f64::consts::PI / 3.0,
            acc_v: 0.5,
            acc_vy: 0.0,
            acc_w: 4.0 * std::f64::consts::PI,
        },
        ..Default::default()
    }
}

#[test]
fn a_wall_across_the_way_gives_a_temporary_goal_beyond_its_cheaper_end() {
    // Wall 3 m ahead from y = −1 to y = 4: the goal 8 m ahead is blocked;
    // the lower end is the cheaper way round.
    let scan = wall_scan(3.0, -1.0, 4.0);
    let mut nav = Navigator::new(LidarNavConfig::default(), "nav").unwrap();
    let t = nav.step(&input(&scan, [8.0, 0.0]));
    let d = nav.debug();
    assert_eq!(d.kind, TargetKind::Temporary);
    assert!(t[1] < -1.0, "below the wall's lower end: {t:?}");
    let c = &d.candidates;
    assert_eq!(c.len(), 2);
    let best = c.iter().map(|c| c.cost).fold(f64::INFINITY, f64::min);
    let chosen = c
        .iter()
        .find(|c| c.point == t)
        .expect("chosen is a candidate");
    assert_eq!(chosen.cost, best);
    // Eq 3: |robot → c| + |c → goal|.
    let eq3 = t[0].hypot(t[1]) + (t[0] - 8.0).hypot(t[1]);
    assert!((chosen.cost - eq3).abs() < 1e-9);
    // A goal in front of the wall is not blocked.
    let t = nav.step(&input(&scan, [2.0, 0.5]));
    assert_eq!(t, [2.0, 0.5]);
    assert_eq!(nav.debug().kind, TargetKind::Global);
}

#[test]
fn eq4_waits_for_a_near_or_wide_obstacle_and_dynamic_settings_do_not() {
    // A 2 m wall 8 m ahead: narrow (< 0.6π) and far (> T_do = 4 m).
    let scan = wall_scan(8.0, -1.0, 1.0);
    let mut nav = Navigator::new(LidarNavConfig::default(), "nav").unwrap();
    nav.step(&input(&scan, [9.5, 0.0]));
    assert_eq!(nav.debug().kind, TargetKind::Global);
    assert!(nav.debug().blocking.is_some());
    let mut dynamic = Navigator::new(LidarNavConfig::dynamic(), "nav").unwrap();
    dynamic.step(&input(&scan, [9.5, 0.0]));
    assert_eq!(dynamic.debug().kind, TargetKind::Temporary);
}

#[test]
fn symmetric_candidates_start_a_hold_that_follows_the_robot() {
    let scan = wall_scan(3.0, -2.5, 2.5);
    let cfg = LidarNavConfig::default();
    let mut nav = Navigator::new(cfg, "nav").unwrap();
    let first = nav.step(&input(&scan, [8.0, 0.0]));
    let d = nav.debug();
    assert!(
        d.cost_gap.unwrap() < cfg.t_dc,
        "symmetric: {:?}",
        d.cost_gap
    );
    assert!((d.hold_remaining - cfg.t_h).abs() < 1e-12);
    // The robot drives 0.1 s at 1 m/s turning 0.5 rad/s: the held goal is
    // the same world point in the new robot frame.
    let vel = Velocity {
        v: 1.0,
        vy: 0.0,
        w: 0.5,
    };
    let t = nav.step(&NavInput {
        velocity: vel,
        ..input(&scan, [8.0, 0.0])
    });
    assert_eq!(nav.debug().kind, TargetKind::Held);
    assert_eq!(t, carry(first, vel, 0.1));
    // Back in world terms: translate by (0.1, 0), rotate by 0.05 rad.
    let (s, c) = (0.05f64.sin(), 0.05f64.cos());
    let back = [c * t[0] - s * t[1] + 0.1, s * t[0] + c * t[1]];
    assert!((back[0] - first[0]).abs() < 1e-9 && (back[1] - first[1]).abs() < 1e-9);
}

#[test]
fn a_swap_of_sides_between_two_steps_holds_the_current_side() {
    // Step 1: the wall's lower end is cheaper by far more than T_dc. Step
    // 2: the wall's upper part is gone, so its upper end is cheaper by more
    // than T_dc while the lower candidate stays where it was. The costs
    // crossed between the two steps without ever being seen within T_dc:
    // the lower candidate is kept and held, as a continuous check would.
    let cfg = LidarNavConfig::default();
    let long = wall_scan(3.0, -1.0, 4.0);
    let short = wall_scan(3.0, -1.0, 0.2);
    let goal = [8.0, 0.0];
    let mut nav = Navigator::new(cfg, "nav").unwrap();
    let t1 = nav.step(&input(&long, goal));
    assert!(t1[1] < -1.0, "{t1:?}");
    assert!(nav.debug().cost_gap.unwrap() > cfg.t_dc);
    assert_eq!(nav.debug().hold_remaining, 0.0);
    let t2 = nav.step(&input(&short, goal));
    let d = nav.debug();
    assert!(d.cost_gap.unwrap() > cfg.t_dc, "{:?}", d.candidates);
    assert!(d.candidates.iter().any(|c| c.point[1] > 0.2));
    assert_eq!(d.kind, TargetKind::Temporary);
    assert_eq!(t2, t1, "kept below the wall");
    assert!((d.hold_remaining - cfg.t_h).abs() < 1e-12);
    assert_eq!(nav.step(&input(&short, goal)), t2);
    assert_eq!(nav.debug().kind, TargetKind::Held);
    // Without the hold the cheaper end wins at once.
    let free_cfg = LidarNavConfig { hold: false, ..cfg };
    let mut free = Navigator::new(free_cfg, "nav").unwrap();
    free.step(&input(&long, goal));
    let t = free.step(&input(&short, goal));
    assert!(t[1] > 0.2, "{t:?}");
    // A fresh choice after the hold has no previous one: the upper end.
    let mut nav = Navigator::new(cfg, "nav").unwrap();
    nav.step(&input(&long, goal));
    nav.step(&input(&short, goal));
    for _ in 0..31 {
        nav.step(&input(&short, goal));
    }
    let t = nav.step(&input(&short, goal));
    assert_eq!(nav.debug().kind, TargetKind::Temporary);
    assert!(t[1] > 0.2, "after the hold: {t:?}");
    // A wall whose lower end moved by more than T_gap gives new candidates:
    // a fresh choice, no hold.
    let mut nav = Navigator::new(cfg, "nav").unwrap();
    nav.step(&input(&long, goal));
    let t = nav.step(&input(&wall_scan(3.0, -4.0, 1.0), goal));
    assert!(t[1] > 1.0, "{t:?}");
    assert_eq!(nav.debug().hold_remaining, 0.0);
}

#[test]
fn a_blocked_candidate_is_chosen_again_around_the_next_obstacle() {
    // Wall A 6 m ahead (y −1 … 3) blocks the goal; a post 2.5 m ahead at
    // bearings −30° … −17° (clear of the goal's bearing even expanded)
    // covers A's cheaper, lower candidate (≈ −19°): the temporary goal is
    // chosen again around the post.
    let a = wall_scan(6.0, -1.0, 3.0);
    let post = wall_scan(2.5, -1.44, -0.76);
    let r: Vec<f64> = a
        .ranges()
        .iter()
        .zip(post.ranges())
        .map(|(x, y)| x.min(*y))
        .collect();
    let scan = Scan::new(r, 10.0);
    let cfg = LidarNavConfig {
        switch_condition: false,
        ..Default::default()
    };
    let mut nav = Navigator::new(cfg, "nav").unwrap();
    nav.step(&input(&scan, [10.0, 0.0]));
    let d = nav.debug();
    assert_eq!(d.kind, TargetKind::Temporary);
    assert_eq!(
        d.blocking.map(|b| d.ops[b].d_first > 5.0),
        Some(true),
        "{:?}",
        d.ops
    );
    assert!(d.iterations >= 1, "{:?}", d.candidates);
    assert!(d.candidates.iter().any(|c| c.iteration == 1));
}

#[test]
fn degenerate_scans_have_defined_behaviour() {
    let cfgs = [LidarNavConfig::default(), LidarNavConfig::dynamic()];
    let goal = [5.0, 1.0];
    let cases: Vec<(&str, Vec<f64>)> = vec![
        ("no beams", vec![]),
        ("all empty", vec![f64::INFINITY; N]),
        ("all blocked", vec![0.5; N]),
        ("single beam", vec![2.0]),
        ("NaN ranges", vec![f64::NAN; N]),
        (
            "mixed garbage",
            (0..N)
                .map(|i| match i % 4 {
                    0 => f64::NAN,
                    1 => -1.0,
                    2 => 1e300,
                    _ => 2.0,
                })
                .collect(),
        ),
    ];
    let mut sn = ScanNavigation::new(
        Some(Navigator::new(LidarNavConfig::default(), "nav").unwrap()),
        Box::new(Dwa::new(DwaConfig::default(), &robot(), MOTION_GOAL).unwrap()),
        &robot(),
        LocalMapConfig::default(),
    )
    .unwrap();
    for cfg in cfgs {
        for (what, r) in &cases {
            let scan = Scan::new(r.clone(), 10.0);
            let mut nav = Navigator::new(cfg, "nav").unwrap();
            let t = nav.step(&input(&scan, goal));
            // No usable obstacle pattern end: the goal itself.
            assert_eq!(t, goal, "{what}");
            assert_eq!(nav.debug().kind, TargetKind::Global, "{what}");
            if *what == "all blocked" || *what == "single beam" {
                let ops = &nav.debug().ops;
                assert!(ops.len() == 1 && ops[0].closed, "{what}: {ops:?}");
            }
            if *what == "NaN ranges" || *what == "all empty" || *what == "no beams" {
                assert!(nav.debug().ops.is_empty(), "{what}");
            }
            // The full stack gives a finite command inside the limits.
            let c = sn.step(&input(&scan, goal));
            assert!(c.v.is_finite() && c.w.is_finite(), "{what}: {c:?}");
            assert!(c.v.abs() <= 1.0 + 1e-9, "{what}: {c:?}");
        }
    }
    // Garbage goal, time step and velocity: a defined stop-or-steer.
    let scan = wall_scan(3.0, -1.0, 1.0);
    let mut nav = Navigator::new(LidarNavConfig::default(), "nav").unwrap();
    let t = nav.step(&NavInput {
        scan: &scan,
        velocity: Velocity {
            v: f64::NAN,
            vy: 0.0,
            w: f64::INFINITY,
        },
        goal: [f64::NAN, 1.0],
        dt: f64::NAN,
    });
    assert_eq!(t, [0.0, 0.0]);
    let c = sn.step(&NavInput {
        scan: &scan,
        velocity: Velocity {
            v: f64::NAN,
            vy: 0.0,
            w: 0.0,
        },
        goal: [f64::NAN, f64::NAN],
        dt: f64::NAN,
    });
    assert!(c.v.is_finite() && c.w.is_finite());
}

#[test]
fn bad_configs_name_the_field() {
    let e = Navigator::new(
        LidarNavConfig {
            d_oe: f64::NAN,
            ..Default::default()
        },
        "nav",
    )
    .unwrap_err();
    assert!(e.to_string().contains("nav.d_oe"), "{e}");
    let e = Lidar::new(
        LidarConfig {
            beams: 0,
            ..Default::default()
        },
        "lidar",
    )
    .unwrap_err();
    assert!(e.to_string().contains("lidar.beams"), "{e}");
    let e = planlab_core::planners::build(
        &PlannerChoice {
            name: "lidar-dwa".into(),
            config: serde_json::json!({"nav": {"t_gap": -1.0}}),
        },
        &robot(),
        &open_map(),
        &Default::default(),
        [1.0, 1.0],
    )
    .err()
    .expect("refused");
    assert!(e.to_string().contains("t_gap"), "{e}");
}

fn open_map() -> StaticMap {
    let g = OccupancyGrid::new(40, 40)
        .unwrap()
        .with_frame(0.25, Pose2::default())
        .unwrap();
    StaticMap::new(g, true).unwrap()
}

#[test]
fn the_scan_sees_walls_and_the_map_edge() {
    let map = open_map(); // 10 m square
    let mut lidar = Lidar::new(LidarConfig::default(), "lidar").unwrap();
    let s = lidar.scan(&map, [2.0, 5.0, 0.0], &[]);
    assert_eq!(s.len(), 360);
    // Beam 0 looks along +x: the edge at x = 10 is 8 m away; beam 180 at
    // x = 0 is 2 m away.
    assert!((s.ranges()[0] - 8.0).abs() < 1e-9);
    assert!((s.ranges()[180] - 2.0).abs() < 1e-9);
}
