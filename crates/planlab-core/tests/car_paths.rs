//! Dubins and Reeds-Shepp curves against hand-computed lengths, and Hybrid
//! A*'s paths checked independently of the planner: turning radius,
//! collisions at a fine resolution, the goal, determinism, typed errors.

use planlab_core::car::footprint::DiscChecker;
use planlab_core::car::hybrid_astar::{plan_hybrid_astar, HybridAStarConfig};
use planlab_core::car::{dubins, end_pose, reeds_shepp, sample, CarError, Pose};
use planlab_core::map::OccupancyGrid;
use proptest::prelude::*;
use std::f64::consts::PI;

#[test]
fn straight_line_is_the_distance_for_both_families() {
    let (a, b) = (Pose::new(0.0, 0.0, 0.0), Pose::new(7.5, 0.0, 0.0));
    assert!((dubins(a, b, 2.0).unwrap().length() - 7.5).abs() < 1e-9);
    assert!((reeds_shepp(a, b, 2.0).unwrap().length() - 7.5).abs() < 1e-9);
}

#[test]
fn a_half_circle_to_a_goal_two_radii_aside_is_pi_r() {
    let r = 1.5;
    let p = dubins(Pose::new(0.0, 0.0, 0.0), Pose::new(0.0, 2.0 * r, PI), r).unwrap();
    assert_eq!(p.word(), "L");
    assert!((p.length() - PI * r).abs() < 1e-9, "{}", p.length());
}

#[test]
fn a_hand_computed_lsl_is_two_quarter_turns_and_a_straight() {
    // R = 1, facing +x at the origin: a left quarter turn ends at (1, 1)
    // facing +y, 2 m straight reach (1, 3), a second left quarter turn
    // ends at (0, 4) facing −x: π/2 + 2 + π/2 = π + 2.
    let p = dubins(Pose::new(0.0, 0.0, 0.0), Pose::new(0.0, 4.0, PI), 1.0).unwrap();
    assert_eq!(p.word(), "LSL");
    assert!((p.length() - (PI + 2.0)).abs() < 1e-9, "{}", p.length());
}

#[test]
fn reeds_shepp_backs_up_to_a_goal_just_behind() {
    let (a, b) = (Pose::new(0.0, 0.0, 0.0), Pose::new(-0.5, 0.0, 0.0));
    let rs = reeds_shepp(a, b, 1.0).unwrap();
    assert_eq!(rs.word(), "S-");
    assert!((rs.length() - 0.5).abs() < 1e-9);
    // Forward only, the car must loop round: far longer.
    assert!(dubins(a, b, 1.0).unwrap().length() > 2.0 * PI);
}

#[test]
fn bad_radius_and_poses_are_typed_errors() {
    let (a, b) = (Pose::default(), Pose::new(1.0, 1.0, 0.0));
    for r in [f64::NAN, 0.0, -1.0, f64::INFINITY] {
        assert!(
            matches!(dubins(a, b, r), Err(CarError::InvalidParameter(_))),
            "{r}"
        );
        assert!(
            matches!(reeds_shepp(a, b, r), Err(CarError::InvalidParameter(_))),
            "{r}"
        );
    }
    assert!(matches!(
        dubins(Pose::new(f64::NAN, 0.0, 0.0), b, 1.0),
        Err(CarError::BadPose { .. })
    ));
}

proptest! {
    #[test]
    fn reeds_shepp_is_never_longer_than_dubins_and_both_end_at_the_goal(
        x in -6.0f64..6.0, y in -6.0f64..6.0, yaw in -PI..PI, r in 0.3f64..3.0,
    ) {
        let (a, b) = (Pose::new(0.3, -0.2, 0.4), Pose::new(x, y, yaw));
        let d = dubins(a, b, r).unwrap();
        let rs = reeds_shepp(a, b, r).unwrap();
        prop_assert!(rs.length() <= d.length() + 1e-9, "{} > {}", rs.length(), d.length());
        prop_assert!(d.length() + 1e-9 >= ((x - 0.3).powi(2) + (y + 0.2).powi(2)).sqrt());
        for p in [&d, &rs] {
            let poses = sample(a, p, 0.05, 1_000_000).unwrap();
            let e = poses.last().unwrap().0;
            prop_assert!((e.x - x).abs() < 1e-6 && (e.y - y).abs() < 1e-6);
            prop_assert!(planlab_core::num::wrap_angle(e.yaw - yaw).abs() < 1e-6);
            // Continuous: consecutive samples are at most a step apart.
            for w in poses.windows(2) {
                let gap = ((w[1].0.x - w[0].0.x).powi(2) + (w[1].0.y - w[0].0.y).powi(2)).sqrt();
                prop_assert!(gap <= 0.05 + 1e-9, "gap {gap}");
            }
            let e2 = end_pose(a, p);
            prop_assert!((e2.x - e.x).abs() < 1e-9);
        }
    }
}

/// A 20 m × 12 m room at 0.2 m cells with a wall across the middle that
/// leaves a gap at the top.
fn room() -> OccupancyGrid {
    let (w, h) = (100usize, 60usize);
    let mut text = String::new();
    for row in 0..h {
        for col in 0..w {
            let wall = (48..52).contains(&col) && row >= 20;
            text.push(if wall { '#' } else { '.' });
        }
        text.push('\n');
    }
    OccupancyGrid::from_ascii(&text)
        .unwrap()
        .with_frame(0.2, Default::default())
        .unwrap()
}

fn cfg(reverse: bool) -> HybridAStarConfig {
    HybridAStarConfig {
        turning_radius: 1.5,
        reverse,
        footprint_radius: 0.3,
        ..Default::default()
    }
}

/// Checks a path independently: curvature between consecutive poses, the
/// disc free at every pose and every 1/10 cell between them (exact scan),
/// and the ends.
fn check_path(grid: &OccupancyGrid, start: Pose, goal: Pose, c: &HybridAStarConfig) -> usize {
    let p = plan_hybrid_astar(grid, start, goal, c).unwrap();
    let ck = DiscChecker::new(grid, c.footprint_radius, false);
    let first = p.poses[0];
    assert!((first.x - start.x).abs() < 1e-9 && (first.y - start.y).abs() < 1e-9);
    let last = *p.poses.last().unwrap();
    assert!(p.analytic, "the exact shot should reach this goal");
    assert!((last.x - goal.x).abs() < 1e-6 && (last.y - goal.y).abs() < 1e-6);
    assert!(planlab_core::num::wrap_angle(last.yaw - goal.yaw).abs() < 1e-6);
    for w in p.poses.windows(2) {
        let (a, b) = (w[0], w[1]);
        let chord = ((b.x - a.x).powi(2) + (b.y - a.y).powi(2)).sqrt();
        assert!(
            chord > 0.0 && chord <= 0.5 * grid.resolution() + 1e-9,
            "chord {chord}"
        );
        let kappa = planlab_core::car::max_curvature(&[a, b]);
        assert!(
            kappa <= 1.0 / c.turning_radius * (1.0 + 1e-6),
            "κ {kappa} at {a:?}"
        );
        for i in 0..=10 {
            let t = i as f64 / 10.0;
            let (x, y) = (a.x + t * (b.x - a.x), a.y + t * (b.y - a.y));
            assert!(
                ck.disc_free_exact(x, y, c.footprint_radius),
                "collision at ({x}, {y})"
            );
        }
    }
    p.expanded
}

#[test]
fn hybrid_astar_goes_through_the_gap_without_turning_tighter_than_its_radius() {
    let g = room();
    let (s, t) = (Pose::new(3.0, 3.0, 0.0), Pose::new(17.0, 3.0, 0.0));
    let e = check_path(&g, s, t, &cfg(false));
    assert!(e > 1);
    check_path(&g, s, Pose::new(17.0, 2.0, PI), &cfg(true));
}

#[test]
fn hybrid_astar_gives_the_same_path_for_the_same_input() {
    let g = room();
    let (s, t) = (Pose::new(3.0, 3.0, 0.5), Pose::new(16.0, 4.0, -1.0));
    let a = plan_hybrid_astar(&g, s, t, &cfg(true)).unwrap();
    let b = plan_hybrid_astar(&g, s, t, &cfg(true)).unwrap();
    assert_eq!(a, b);
}

#[test]
fn hybrid_astar_refuses_bad_input_and_a_walled_off_goal_quickly() {
    let g = room();
    let (s, t) = (Pose::new(3.0, 3.0, 0.0), Pose::new(17.0, 3.0, 0.0));
    for r in [f64::NAN, 0.0, -2.0] {
        let c = HybridAStarConfig {
            turning_radius: r,
            ..cfg(false)
        };
        assert!(matches!(
            plan_hybrid_astar(&g, s, t, &c),
            Err(CarError::InvalidParameter(_))
        ));
    }
    // Start inside the wall, goal touching the map edge.
    let e = plan_hybrid_astar(&g, Pose::new(10.0, 3.0, 0.0), t, &cfg(false)).unwrap_err();
    assert!(
        matches!(e, CarError::InCollision { which: "start", .. }),
        "{e}"
    );
    let e = plan_hybrid_astar(&g, s, Pose::new(19.9, 3.0, 0.0), &cfg(false)).unwrap_err();
    assert!(
        matches!(e, CarError::InCollision { which: "goal", .. }),
        "{e}"
    );
    let e = plan_hybrid_astar(&g, s, Pose::new(30.0, 3.0, 0.0), &cfg(false)).unwrap_err();
    assert!(matches!(e, CarError::OffMap { which: "goal", .. }), "{e}");
    // Close the gap: the 2D distance proves it before any expansion.
    let mut closed = g.clone();
    for row in 0..20 {
        for col in 48..52 {
            closed
                .set(col, row, planlab_core::map::Cell::Occupied)
                .unwrap();
        }
    }
    let e = plan_hybrid_astar(&closed, s, t, &cfg(true)).unwrap_err();
    assert_eq!(e, CarError::Unreachable { expanded: 0 });
    // A tiny expansion budget: a typed limit, not a hang.
    let c = HybridAStarConfig {
        max_expansions: 3,
        ..cfg(false)
    };
    let e = plan_hybrid_astar(&g, s, t, &c).unwrap_err();
    assert!(matches!(e, CarError::SearchLimit { limit: 3, .. }), "{e}");
}

/// Whether a `length` × `width` rectangle centred on `p` overlaps a blocked
/// cell or leaves `grid` (map frame at the origin, unrotated): exact, by
/// separating axes (the rectangle's two and the cell's two).
fn rect_hits(grid: &OccupancyGrid, p: Pose, length: f64, width: f64) -> bool {
    let res = grid.resolution();
    let (c, s) = (p.yaw.cos(), p.yaw.sin());
    let (hl, hw) = (0.5 * length, 0.5 * width);
    let corners = [(hl, hw), (hl, -hw), (-hl, -hw), (-hl, hw)]
        .map(|(a, b)| (p.x + a * c - b * s, p.y + a * s + b * c));
    let (w, h) = (grid.width() as f64 * res, grid.height() as f64 * res);
    if corners
        .iter()
        .any(|&(x, y)| x < 0.0 || y < 0.0 || x > w || y > h)
    {
        return true;
    }
    let (x0, x1) = corners
        .iter()
        .fold((f64::MAX, f64::MIN), |m, q| (m.0.min(q.0), m.1.max(q.0)));
    let (y0, y1) = corners
        .iter()
        .fold((f64::MAX, f64::MIN), |m, q| (m.0.min(q.1), m.1.max(q.1)));
    let cols = (x0 / res).floor().max(0.0) as usize..=((x1 / res) as usize).min(grid.width() - 1);
    for col in cols {
        let ups =
            (y0 / res).floor().max(0.0) as usize..=((y1 / res) as usize).min(grid.height() - 1);
        for up in ups {
            let row = grid.height() - 1 - up;
            if grid.cells()[row * grid.width() + col] != planlab_core::map::Cell::Occupied {
                continue;
            }
            let sq = [
                (col as f64 * res, up as f64 * res),
                ((col + 1) as f64 * res, up as f64 * res),
                ((col + 1) as f64 * res, (up + 1) as f64 * res),
                (col as f64 * res, (up + 1) as f64 * res),
            ];
            // Separated on some axis: no overlap (touching counts as free).
            let separated = [(1.0, 0.0), (0.0, 1.0), (c, s), (-s, c)]
                .iter()
                .any(|&(ax, ay)| {
                    let proj = |q: &(f64, f64)| q.0 * ax + q.1 * ay;
                    let (a0, a1) = corners
                        .iter()
                        .map(proj)
                        .fold((f64::MAX, f64::MIN), |m, v| (m.0.min(v), m.1.max(v)));
                    let (b0, b1) = sq
                        .iter()
                        .map(proj)
                        .fold((f64::MAX, f64::MIN), |m, v| (m.0.min(v), m.1.max(v)));
                    a1 <= b0 + 1e-12 || b1 <= a0 + 1e-12
                });
            if !separated {
                return true;
            }
        }
    }
    false
}

#[test]
fn a_rectangular_car_never_puts_its_rectangle_in_a_wall() {
    let g = room();
    let (l, w) = (1.2, 0.6);
    for (reverse, goal) in [
        (false, Pose::new(17.0, 3.0, 0.0)),
        (true, Pose::new(17.0, 2.0, PI)),
    ] {
        let c = HybridAStarConfig {
            footprint_rect: Some((l, w)),
            ..cfg(reverse)
        };
        let p = plan_hybrid_astar(&g, Pose::new(3.0, 3.0, 0.0), goal, &c).unwrap();
        assert!(p.analytic);
        // Every pose and 1/10 of the way between poses (the heading too).
        for win in p.poses.windows(2) {
            let (a, b) = (win[0], win[1]);
            let turn = planlab_core::num::wrap_angle(b.yaw - a.yaw);
            for i in 0..=10 {
                let t = i as f64 / 10.0;
                let q = Pose::new(
                    a.x + t * (b.x - a.x),
                    a.y + t * (b.y - a.y),
                    a.yaw + t * turn,
                );
                assert!(!rect_hits(&g, q, l, w), "rectangle in a wall at {q:?}");
            }
        }
        // It turns within its radius and reaches the goal as the disc does.
        assert!(
            planlab_core::car::max_curvature(&p.poses) <= 1.0 / c.turning_radius * (1.0 + 1e-6)
        );
        let last = p.poses.last().unwrap();
        assert!((last.x - goal.x).abs() < 1e-6 && (last.y - goal.y).abs() < 1e-6);
    }
    // A bad rectangle is a typed error.
    for r in [(f64::NAN, 0.5), (1.0, 0.0), (-1.0, 0.5)] {
        let c = HybridAStarConfig {
            footprint_rect: Some(r),
            ..cfg(false)
        };
        let e = plan_hybrid_astar(&g, Pose::new(3.0, 3.0, 0.0), Pose::new(17.0, 3.0, 0.0), &c)
            .unwrap_err();
        assert!(
            matches!(&e, CarError::InvalidParameter(m) if m.contains("rectangle")),
            "{e}"
        );
    }
}
