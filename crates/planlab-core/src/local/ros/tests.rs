//! Each ROS critic against a hand-computed case, each generator's window
//! and sample count, and the two planners on small maps.

use super::critics::*;
use super::generators::*;
use super::{navfn, CostmapParams, Layers, PlanTracker};
use crate::local::engine::critic::{Critic, CriticContext};
use crate::local::engine::generator::{
    Sample, Trajectory, TrajectoryGenerator, Window, WindowRequest,
};
use crate::local::testkit::{self, End};
use crate::local::{LocalPlanner, Observation};
use crate::num::{cos, sin};
use crate::world::{Command, Footprint, RobotLimits, RobotSpec, RobotState, StaticMap};

fn robot() -> RobotSpec {
    RobotSpec {
        footprint: Footprint::Circle { radius: 0.2 },
        limits: RobotLimits {
            v_max: 1.0,
            w_max: 40f64.to_radians(),
            acc_v: 0.4,
            acc_w: 100f64.to_radians(),
            ..Default::default()
        },
        ..Default::default()
    }
}

/// An open `w`×`h` map at 0.1 m, with walls `#` where `walls` says
/// (rows listed top first, each `w` wide).
fn open(w: usize, h: usize) -> StaticMap {
    testkit::map(&format!("{}\n", ".".repeat(w)).repeat(h), 0.1)
}

fn state(x: f64, y: f64, theta: f64, v: f64) -> RobotState {
    RobotState {
        x,
        y,
        theta,
        v,
        ..Default::default()
    }
}

fn obs<'a>(map: &'a StaticMap, s: &'a RobotState, goal: [f64; 2]) -> Observation<'a> {
    testkit::observation(s, goal, map)
}

fn ctx<'a>(
    o: &'a Observation<'a>,
    path: &'a [[f64; 2]],
    robot: &'a RobotSpec,
    window: &'a Window,
) -> CriticContext<'a> {
    CriticContext {
        obs: o,
        goal: o.goal,
        path,
        robot,
        samples: &[],
        window,
    }
}

/// A rollout of `cmd` through the poses `(x, y, θ)`.
fn traj(cmd: Command, poses: &[[f64; 3]]) -> Trajectory {
    Trajectory {
        sample: Sample { cmd, decel: 0.0 },
        dt: 0.1,
        points: poses.iter().map(|p| [p[0], p[1]]).collect(),
        dirs: poses.iter().map(|p| [sin(p[2]), cos(p[2])]).collect(),
        speeds: vec![cmd.v; poses.len()],
        final_speed: cmd.v,
        horizon: poses.len(),
        end_theta: poses.last().map_or(0.0, |p| p[2]),
        min_clearance: f64::INFINITY,
        with_dirs: true,
    }
}

fn cmd(v: f64, w: f64) -> Command {
    Command { v, vy: 0.0, w }
}

/// A straight plan along y = 1.05 from x = 0.55 to 3.55 (cell row 10 of 20).
fn straight() -> Vec<[f64; 2]> {
    (0..=30).map(|i| [0.55 + 0.1 * i as f64, 1.05]).collect()
}

#[test]
fn path_dist_is_the_manhattan_cells_to_the_plan() {
    let (map, r, w) = (open(40, 20), robot(), Window::default());
    let s = state(0.55, 1.05, 0.0, 0.0);
    let o = obs(&map, &s, [3.55, 1.05]);
    let plan = straight();
    let c = ctx(&o, &plan, &r, &w);
    let mut crit = PathDist::default();
    crit.prepare(&c);
    // End 0.5 m (5 cells) beside the plan.
    let t = traj(cmd(0.5, 0.0), &[[0.55, 1.05, 0.0], [2.05, 1.55, 0.0]]);
    assert_eq!(crit.score(&c, &t), Some(5.0));
    // On the plan: 0; off the map: illegal.
    let on = traj(cmd(0.5, 0.0), &[[2.05, 1.05, 0.0]]);
    assert_eq!(crit.score(&c, &on), Some(0.0));
    let off = traj(cmd(0.5, 0.0), &[[2.05, 1.05, 0.0], [5.0, 1.05, 0.0]]);
    assert_eq!(crit.score(&c, &off), None);
}

#[test]
fn goal_dist_is_the_manhattan_cells_to_the_plans_end() {
    let (map, r, w) = (open(40, 20), robot(), Window::default());
    let s = state(0.55, 1.05, 0.0, 0.0);
    let o = obs(&map, &s, [3.55, 1.05]);
    let plan = straight();
    let c = ctx(&o, &plan, &r, &w);
    let mut crit = GoalDist::default();
    crit.prepare(&c);
    // 15 cells along x and 3 across.
    let t = traj(cmd(0.5, 0.0), &[[2.05, 1.35, 0.0]]);
    assert_eq!(crit.score(&c, &t), Some(18.0));
}

#[test]
fn path_align_reads_the_forward_point_and_halves_the_resolution() {
    let (map, r, w) = (open(40, 20), robot(), Window::default());
    let s = state(0.55, 1.05, 0.0, 0.0);
    let o = obs(&map, &s, [3.55, 1.05]);
    let plan = straight();
    let c = ctx(&o, &plan, &r, &w);
    let mut crit = PathAlign::new(0.325);
    crit.prepare(&c);
    // Ending on the plan facing along it: 0. Facing across (+y): the
    // forward point (2.05, 1.375) is 3 cells off, × 0.1/2.
    let along = traj(cmd(0.5, 0.0), &[[2.05, 1.05, 0.0]]);
    assert_eq!(crit.score(&c, &along), Some(0.0));
    let across = traj(cmd(0.5, 0.0), &[[2.05, 1.05, std::f64::consts::FRAC_PI_2]]);
    let got = crit.score(&c, &across).unwrap();
    assert!((got - 3.0 * 0.05).abs() < 1e-12, "{got}");
    // Within forward_point_distance of the goal the critic is off.
    let near = state(3.35, 1.05, 0.0, 0.0);
    let o2 = obs(&map, &near, [3.55, 1.05]);
    let c2 = ctx(&o2, &plan, &r, &w);
    crit.prepare(&c2);
    assert_eq!(crit.score(&c2, &across), Some(0.0));
}

#[test]
fn goal_align_measures_the_forward_point_to_the_shifted_goal() {
    let (map, r, w) = (open(40, 20), robot(), Window::default());
    let s = state(0.55, 1.05, 0.0, 0.0);
    let o = obs(&map, &s, [3.55, 1.05]);
    let plan = straight();
    let c = ctx(&o, &plan, &r, &w);
    let mut crit = GoalAlign::new(0.325);
    crit.prepare(&c);
    // Goal moved to x = 3.875 (col 38); forward point (2.375, 1.05) is col 23.
    let t = traj(cmd(0.5, 0.0), &[[2.05, 1.05, 0.0]]);
    assert_eq!(crit.score(&c, &t), Some(15.0));
    // Facing away puts the forward point at x = 1.725 (col 17): 21 cells.
    let back = traj(cmd(0.5, 0.0), &[[2.05, 1.05, std::f64::consts::PI]]);
    assert_eq!(crit.score(&c, &back), Some(21.0));
}

fn rotate_to_goal() -> RotateToGoal {
    RotateToGoal::new(RotateToGoalSettings {
        xy_goal_tolerance: 0.25,
        trans_stopped_velocity: 0.25,
        slowing_factor: 5.0,
        lookahead_time: -1.0,
        path_length_tolerance: 1.0,
    })
}

#[test]
fn rotate_to_goal_is_silent_far_slows_near_and_turns_when_stopped() {
    let (map, r, w) = (open(40, 20), robot(), Window::default());
    let plan = [[3.05, 1.05], [3.55, 1.05]];
    // Far from the goal: 0 whatever the rollout.
    let far = state(1.05, 1.05, 0.0, 0.5);
    let o = obs(&map, &far, [3.55, 1.05]);
    let mut crit = rotate_to_goal();
    crit.prepare(&ctx(&o, &plan, &r, &w));
    let t = traj(cmd(0.5, 0.3), &[[1.1, 1.05, 0.3]]);
    assert_eq!(crit.score(&ctx(&o, &plan, &r, &w), &t), Some(0.0));
    // 0.15 m from the goal at 0.5 m/s: must slow; v = 0.2 costs 5·0.04 +
    // |yaw error| 0.3 (the plan arrives along +x).
    let near = state(3.40, 1.05, 0.0, 0.5);
    let o = obs(&map, &near, [3.55, 1.05]);
    let mut crit = rotate_to_goal();
    let c = ctx(&o, &plan, &r, &w);
    crit.prepare(&c);
    assert_eq!(
        crit.score(&c, &traj(cmd(0.5, 0.0), &[[3.45, 1.05, 0.0]])),
        None
    );
    let slow = crit
        .score(&c, &traj(cmd(0.2, 0.3), &[[3.45, 1.05, 0.3]]))
        .unwrap();
    assert!((slow - (5.0 * 0.04 + 0.3)).abs() < 1e-12, "{slow}");
    // Stopped there: only rotations are legal, scored by the yaw error.
    let stopped = state(3.40, 1.05, 0.0, 0.1);
    let o = obs(&map, &stopped, [3.55, 1.05]);
    let c = ctx(&o, &plan, &r, &w);
    crit.prepare(&c);
    assert_eq!(
        crit.score(&c, &traj(cmd(0.05, 0.0), &[[3.42, 1.05, 0.0]])),
        None
    );
    let turn = crit
        .score(&c, &traj(cmd(0.0, -0.2), &[[3.40, 1.05, -0.25]]))
        .unwrap();
    assert!((turn - 0.25).abs() < 1e-12, "{turn}");
}

#[test]
fn oscillation_flags_a_sign_flip_and_resets_after_the_distance() {
    let (map, r, w) = (open(40, 20), robot(), Window::default());
    let plan = straight();
    let mut crit = Oscillation::new(OscillationSettings {
        oscillation_reset_dist: 0.05,
        oscillation_reset_angle: 0.2,
        x_only_threshold: 0.05,
    });
    let left = traj(cmd(0.0, 0.5), &[[1.0, 1.0, 0.0]]);
    let at = |x: f64| state(x, 1.0, 0.0, 0.0);
    let s0 = at(1.0);
    let o = obs(&map, &s0, [3.0, 1.0]);
    let c = ctx(&o, &plan, &r, &w);
    crit.prepare(&c);
    crit.debrief(Some(&cmd(0.0, 0.5)));
    assert_eq!(crit.score(&c, &left), Some(0.0), "no flip yet");
    crit.prepare(&c);
    crit.debrief(Some(&cmd(0.0, -0.5)));
    // Turning left again would oscillate.
    assert_eq!(crit.score(&c, &left), None);
    // 0.04 m on: still flagged; 0.06 m on: cleared.
    let s1 = at(1.04);
    let o1 = obs(&map, &s1, [3.0, 1.0]);
    crit.prepare(&ctx(&o1, &plan, &r, &w));
    crit.debrief(Some(&cmd(0.3, -0.5)));
    assert_eq!(crit.score(&c, &left), None);
    let s2 = at(1.06);
    let o2 = obs(&map, &s2, [3.0, 1.0]);
    crit.prepare(&ctx(&o2, &plan, &r, &w));
    crit.debrief(Some(&cmd(0.3, 0.0)));
    assert_eq!(crit.score(&c, &left), Some(0.0));
}

/// A 20×10 map with a wall block at columns 10–11, rows 0–6 counted from
/// the top (x 1.0–1.2, y 0.3–1.0).
fn walled() -> StaticMap {
    let mut rows = Vec::new();
    for r in 0..10 {
        let mut row = String::new();
        for c in 0..20 {
            row.push(if (10..12).contains(&c) && r <= 6 {
                '#'
            } else {
                '.'
            });
        }
        rows.push(row);
    }
    testkit::map(&(rows.join("\n") + "\n"), 0.1)
}

fn layers(map: &StaticMap) -> Layers {
    Layers::new(map, &robot(), &CostmapParams::default()).unwrap()
}

#[test]
fn base_obstacle_is_illegal_on_a_lethal_or_inscribed_cell() {
    let (map, r, w) = (walled(), robot(), Window::default());
    let s = state(0.35, 0.55, 0.0, 0.0);
    let o = obs(&map, &s, [1.85, 0.55]);
    let c = ctx(&o, &[], &r, &w);
    let mut crit = BaseObstacle::new(layers(&map), false);
    crit.prepare(&c);
    let into = traj(cmd(0.5, 0.0), &[[0.35, 0.55, 0.0], [1.05, 0.55, 0.0]]);
    assert_eq!(crit.score(&c, &into), None, "lethal");
    let beside = traj(cmd(0.5, 0.0), &[[0.35, 0.55, 0.0], [0.85, 0.55, 0.0]]);
    assert_eq!(
        crit.score(&c, &beside),
        None,
        "within the 0.2 m inscribed radius"
    );
    // 0.5 m from the wall's cell centres, the inscribed radius that of
    // the 16-gon of radius 0.2 + 0.01 padding (0.206 m):
    // 252·exp(−10·(0.5 − 0.206)) = 13.3 → 13.
    let far = traj(cmd(0.5, 0.0), &[[0.55, 0.55, 0.0]]);
    assert_eq!(crit.score(&c, &far), Some(13.0));
}

#[test]
fn move_base_occupancy_is_the_highest_cost_under_the_footprint() {
    let (map, r, w) = (walled(), robot(), Window::default());
    let s = state(0.35, 0.55, 0.0, 0.0);
    let o = obs(&map, &s, [1.85, 0.55]);
    let c = ctx(&o, &[], &r, &w);
    let mut crit = Occupancy::new(layers(&map), r.footprint);
    crit.prepare(&c);
    // Centre at x = 0.55: the padded outline reaches x = 0.76 (cell 7),
    // 0.3 m from the wall's first cell centre (1.05): cost
    // 252·exp(−10·(0.3 − 0.206)) = 98.4 → 98.
    let t = traj(cmd(0.2, 0.0), &[[0.35, 0.55, 0.0], [0.55, 0.55, 0.0]]);
    assert_eq!(crit.score(&c, &t), Some(98.0));
    // The outline on the wall: illegal.
    let hit = traj(cmd(0.2, 0.0), &[[0.35, 0.55, 0.0], [0.9, 0.55, 0.0]]);
    assert_eq!(crit.score(&c, &hit), None);
}

#[test]
fn move_base_goal_distance_goes_round_the_inflated_wall() {
    let (map, r, w) = (walled(), robot(), Window::default());
    let s = state(0.35, 0.55, 0.0, 0.0);
    let o = obs(&map, &s, [1.85, 0.55]);
    let plan = [[1.85, 0.55]];
    let c = ctx(&o, &plan, &r, &w);
    let mut goal = GridDistance::new(layers(&map), Target::Goal, 0.2);
    goal.prepare(&c);
    // Goal cell (18, 4). The wall (cols 10–11, rows 0–6, top first) grows
    // by the 0.2 m inscribed radius to cols 8–13 down to row 6, cols 9–12
    // on row 7 and 10–11 on row 8: the way round is row 9. From (5, 4):
    // 5 down + 13 across + 5 up = 23.
    let t = traj(cmd(0.2, 0.0), &[[0.55, 0.55, 0.0]]);
    assert_eq!(goal.score(&c, &t), Some(23.0));
    // On the grown wall: illegal (the source's cost −2).
    let bad = traj(cmd(0.2, 0.0), &[[0.55, 0.55, 0.0], [0.95, 0.55, 0.0]]);
    assert_eq!(goal.score(&c, &bad), None);
    // The path distance to a plan along row 9 from (5, 9) is 5 cells.
    let plan = [[0.55, 0.05], [1.85, 0.05]];
    let c = ctx(&o, &plan, &r, &w);
    let mut path = GridDistance::new(layers(&map), Target::Path, 0.2);
    path.prepare(&c);
    assert_eq!(path.score(&c, &t), Some(5.0));
}

#[test]
fn move_base_oscillation_blocks_the_other_rotation_after_two_and_resets() {
    let (map, r, w) = (open(40, 20), robot(), Window::default());
    let mut crit = InPlaceOscillation::new(0.05);
    let s0 = state(1.0, 1.0, 0.0, 0.0);
    let o = obs(&map, &s0, [3.0, 1.0]);
    let c = ctx(&o, &[], &r, &w);
    let pos = traj(cmd(0.0, 0.4), &[[1.0, 1.0, 0.0]]);
    for _ in 0..2 {
        crit.prepare(&c);
        assert_eq!(crit.score(&c, &pos), Some(0.0));
        crit.debrief(Some(&cmd(0.0, -0.4)));
    }
    // Two right turns in place set stuck_right, which guards +ω.
    assert_eq!(crit.score(&c, &pos), None);
    let fwd = traj(cmd(0.3, 0.4), &[[1.0, 1.0, 0.0]]);
    assert_eq!(
        crit.score(&c, &fwd),
        Some(0.0),
        "forward samples unaffected"
    );
    let s1 = state(1.06, 1.0, 0.0, 0.0);
    let o1 = obs(&map, &s1, [3.0, 1.0]);
    crit.prepare(&ctx(&o1, &[], &r, &w));
    crit.debrief(Some(&cmd(0.3, 0.0)));
    assert_eq!(crit.score(&c, &pos), Some(0.0));
}

#[test]
fn heading_lookahead_prefers_the_rotation_facing_the_goal() {
    let (map, r, w) = (open(40, 20), robot(), Window::default());
    let s = state(1.05, 1.05, 0.0, 0.0);
    let o = obs(&map, &s, [3.05, 1.05]);
    let plan = [[3.05, 1.05]];
    let c = ctx(&o, &plan, &r, &w);
    let mut crit = HeadingLookahead::new(layers(&map), 0.3, 0.2);
    crit.prepare(&c);
    let facing = crit
        .score(&c, &traj(cmd(0.0, 0.4), &[[1.05, 1.05, 0.0]]))
        .unwrap();
    let away = crit
        .score(
            &c,
            &traj(cmd(0.0, 0.4), &[[1.05, 1.05, std::f64::consts::PI]]),
        )
        .unwrap();
    // Forward point (1.35, 1.05) is 17 cells from the goal; (0.75, 1.05) 23.
    assert_eq!((facing, away), (17.0, 23.0));
    assert_eq!(
        crit.score(&c, &traj(cmd(0.3, 0.0), &[[1.05, 1.05, 0.0]])),
        Some(0.0)
    );
}

#[test]
fn standard_generator_window_and_samples() {
    let map = open(40, 20);
    let r = robot();
    let mut g = StandardGenerator::new(
        r.limits,
        StandardSettings {
            vx_samples: 20,
            vtheta_samples: 20,
            sim_time: 1.7,
            linear_granularity: 0.05,
            angular_granularity: 0.025,
            include_last_point: true,
        },
    );
    let s = state(1.0, 1.0, 0.0, 0.5);
    let o = obs(&map, &s, [3.0, 1.0]);
    let mut out = Vec::new();
    let win = g.samples(
        &o,
        &WindowRequest {
            dt: 0.1,
            hold_v: None,
            braking: false,
        },
        &mut out,
    );
    // Projected over sim_time 1.7 s: v 0.5 ± 0.4·1.7 within [0, 1],
    // ω ± 1.745·1.7 within ±ω_max.
    let wm = 40f64.to_radians();
    assert_eq!(win.v, (0.0, 1.0));
    assert!((win.w.0 + wm).abs() < 1e-12 && (win.w.1 - wm).abs() < 1e-12);
    // 20 speeds × (20 turn rates + 0, which the window straddles).
    assert_eq!(out.len(), 20 * 21);
    // A 0.5 m/s straight rollout: ⌈0.5·1.7/0.05⌉ = 17 steps; the start,
    // 17 poses and the last again; it ends 0.85 m ahead.
    let mut t = Trajectory::default();
    g.rollout(
        &o,
        Sample {
            cmd: cmd(0.5, 0.0),
            decel: 0.0,
        },
        0,
        &mut t,
    );
    assert_eq!(t.points.len(), 19);
    assert_eq!(t.points[17], t.points[18]);
    assert!((t.end()[0] - 1.85).abs() < 1e-9, "{:?}", t.end());
}

#[test]
fn trajectory_planner_window_and_samples() {
    let map = open(40, 20);
    let r = robot();
    let mut g = TrajectoryPlannerWindow::new(
        r.limits,
        TrajectoryPlannerSettings {
            vx_samples: 3,
            vtheta_samples: 20,
            sim_time: 1.0,
            sim_granularity: 0.025,
            angular_sim_granularity: 0.025,
            min_vel_x: 0.1,
            min_in_place_vel_theta: 0.4,
        },
    );
    let s = state(1.0, 1.0, 0.0, 0.5);
    let o = obs(&map, &s, [3.0, 1.0]);
    let mut out = Vec::new();
    let req = WindowRequest {
        dt: 0.1,
        hold_v: None,
        braking: false,
    };
    let win = g.samples(&o, &req, &mut out);
    assert!((win.v.0 - 0.46).abs() < 1e-12 && (win.v.1 - 0.54).abs() < 1e-12);
    // 3 speeds × (straight + 19 turn rates) and the 18 rotations whose
    // turn rate is more than one step (0.349/19) from 0, lifted to 0.4.
    let rotations: Vec<_> = out.iter().filter(|s| s.cmd.v == 0.0).collect();
    assert_eq!(out.len(), 3 * 20 + 18);
    assert_eq!(rotations.len(), 18);
    assert!(rotations.iter().all(|s| s.cmd.w.abs() >= 0.4 - 1e-12));
    // Near the goal the top speed is d/sim_time: 0.3 m away → 0.3 m/s;
    // the source then samples down from the reachable 0.46 to it.
    let s2 = state(2.7, 1.0, 0.0, 0.5);
    let o2 = obs(&map, &s2, [3.0, 1.0]);
    let w2 = g.samples(&o2, &req, &mut out);
    assert!((w2.v.1 - 0.3).abs() < 1e-12, "{:?}", w2.v);
    assert!((out[20].cmd.v - 0.38).abs() < 1e-12);
    // Escaping: rotations only.
    g.set_escaping(true);
    g.samples(&o, &req, &mut out);
    assert_eq!(out.len(), 18);
    // Step count: max(0.5·1.0/0.025, 0.4/0.025) + 0.5 → 20 points, the
    // first the current pose.
    let mut t = Trajectory::default();
    g.rollout(
        &o,
        Sample {
            cmd: cmd(0.5, 0.4),
            decel: 0.0,
        },
        0,
        &mut t,
    );
    assert_eq!(t.points.len(), 20);
    assert_eq!(t.points[0], [1.0, 1.0]);
}

#[test]
fn navfn_goes_round_the_wall_and_the_tracker_prunes_behind() {
    let map = walled();
    let l = layers(&map);
    let p = navfn(&l, [0.35, 0.55], [1.85, 0.55]).unwrap();
    assert_eq!(*p.last().unwrap(), [1.85, 0.55]);
    // Every point off the grown wall, and the path passes under it
    // (the wall spans y 0.3–1.0, grown by 0.2 m).
    assert!(p
        .iter()
        .all(|q| l.cost_at(q[0], q[1]).is_some_and(super::passable)));
    assert!(p.iter().any(|q| q[1] < 0.15));
    let mut t = PlanTracker::default();
    t.set(p.clone());
    let far = t.window([0.35, 0.55], 0.3).to_vec();
    assert!(far
        .iter()
        .all(|q| (q[0] - 0.35).hypot(q[1] - 0.55) <= 0.3 + 1e-9));
    let mid = p[p.len() / 2];
    let w = t.window(mid, 0.3).to_vec();
    assert_eq!(w[0], mid, "pruned to the point nearest the robot");
}

#[test]
fn both_planners_drive_round_a_pillar_to_the_goal() {
    // A 0.5 × 1 m pillar between start and goal in a walled 6 × 4 m room.
    let mut rows = vec![format!("#{}#", ".".repeat(58)); 40];
    rows[0] = "#".repeat(60);
    rows[39] = "#".repeat(60);
    for (r, row) in rows.iter_mut().enumerate() {
        if (15..25).contains(&r) {
            row.replace_range(28..33, "#####");
        }
    }
    let map = testkit::map(&(rows.join("\n") + "\n"), 0.1);
    // base_local_planner's default limits (max_vel_x 0.5, max_vel_theta 1,
    // acc_lim_x 2.5, acc_lim_theta 3.2), which its defaults are tuned for,
    // and a base that can back up at its escape_vel.
    let r = RobotSpec {
        limits: RobotLimits {
            v_max: 0.5,
            v_min: -0.1,
            w_max: 1.0,
            acc_v: 2.5,
            acc_w: 3.2,
            ..Default::default()
        },
        ..robot()
    };
    let start = state(1.0, 2.0, 0.0, 0.0);
    let goal = [5.0, 2.0];
    let cat = crate::local::engine::catalogue::CriticCatalogue::standard();
    let mut d = super::dwb::build(&Default::default(), &cat, &r, &map, [1.0, 2.0], goal).unwrap();
    let run = testkit::run(&mut d, &map, &r, start, goal, &[], 120.0, 0.2);
    assert_eq!(
        run.end,
        End::Reached,
        "dwb: {:?} {:?}",
        run.modes.last(),
        run.states.last()
    );
    assert!(run.min_clearance > 0.0);
    // move_base, facing away from a goal in the open beside the pillar:
    // it turns in place, then drives there.
    let start = state(1.0, 0.6, std::f64::consts::PI, 0.0);
    let goal = [5.0, 0.6];
    let mut mb = super::move_base::build(&Default::default(), &r, &map, [1.0, 0.6], goal).unwrap();
    let run = testkit::run(&mut mb, &map, &r, start, goal, &[], 120.0, 0.2);
    assert_eq!(
        run.end,
        End::Reached,
        "move-base-dwa: {:?} {:?}",
        run.modes.last(),
        run.states.last()
    );
    let first = &run.states[..10];
    assert!(
        first.iter().all(|s| s.x == 1.0 && s.y == 0.6),
        "turns on the spot first"
    );
    assert!(crate::num::wrap_angle(first[9].theta - std::f64::consts::PI).abs() > 0.2);
    assert_eq!(d.name(), "dwb");
}
