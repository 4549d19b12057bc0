//! Driving an episode from outside (a Python controller, a gym agent):
//! stepping with a given command, the LiDAR scan and the perceived movers of
//! the current state, and one batch episode run on its own.

use planlab_core::batch;
use planlab_core::lidar::{Lidar, LidarConfig};
use planlab_core::map::OccupancyGrid;
use planlab_core::metrics::EpisodeMetrics;
use planlab_core::scenario::Scenario;
use planlab_core::sim::{Episode, Outcome, USER_MODE};
use planlab_core::world::Command;

fn preset(text: &str) -> (Scenario, OccupancyGrid) {
    let s = Scenario::from_json(text).unwrap();
    let g = s.inline_grid().unwrap().expect("an inline map");
    (s, g)
}

/// A 12 × 5 room of 0.2 m cells, walls around, goal 7 cells to the right.
fn room() -> (Scenario, OccupancyGrid) {
    let wall = "#".repeat(12);
    let inside = format!("#{}#", ".".repeat(10));
    let text = serde_json::json!({
        "version": 1, "name": "room", "seed": 4,
        "map": {"width": 12, "height": 5, "resolution": 0.2,
                "cells": [wall, inside, inside, inside, wall]},
        "start": {"col": 2, "row": 2}, "goal": {"col": 9, "row": 2},
    })
    .to_string();
    let s = Scenario::from_json(&text).unwrap();
    let g = s.inline_grid().unwrap().unwrap();
    (s, g)
}

/// Heads for the goal: turn towards it, drive when roughly facing it.
fn go_to_goal(ep: &Episode) -> Command {
    let s = ep.state();
    let g = ep.goal();
    let bearing = (g[1] - s.y).atan2(g[0] - s.x) - s.theta;
    let bearing = bearing.sin().atan2(bearing.cos());
    Command {
        v: if bearing.abs() < 0.5 { 0.5 } else { 0.0 },
        vy: 0.0,
        w: 2.0 * bearing,
    }
}

#[test]
fn a_user_controller_reaches_the_goal_and_is_measured_like_a_planner() {
    let (s, g) = room();
    let mut ep = Episode::from_scenario(&s, g).unwrap();
    let mut outcome = Outcome::Running;
    for _ in 0..2000 {
        let cmd = go_to_goal(&ep);
        outcome = ep.step_with(cmd).unwrap();
        if outcome != Outcome::Running {
            break;
        }
    }
    assert_eq!(outcome, Outcome::Reached);
    let rows = &ep.trace().steps;
    assert_eq!(rows.len() as u64, ep.steps() + 1);
    assert!(rows[1..]
        .iter()
        .all(|r| r.mode == USER_MODE && r.goal == ep.goal()));
    // The limits clamp the command: 0.5 m/s asked, acc_v = 0.2 m/s² at dt 0.1.
    assert!((rows[1].cmd.v - rows[0].v).abs() <= 0.02 + 1e-12);
    let m = EpisodeMetrics::of_episode(&ep);
    assert_eq!(m.outcome, Outcome::Reached);
    // Straight along the row: the path is about the 1.4 m between the cells.
    assert!((m.path_length_m - 1.4).abs() < 0.25, "{}", m.path_length_m);
    // Once ended, further commands change nothing.
    let n = rows.len();
    assert_eq!(ep.step_with(Command::default()).unwrap(), Outcome::Reached);
    assert_eq!(ep.trace().steps.len(), n);
}

#[test]
fn a_planner_step_and_a_user_step_share_the_world() {
    let (s, g) = room();
    let mut by_planner = Episode::from_scenario(&s, g.clone()).unwrap();
    by_planner.step();
    let cmd = by_planner.trace().steps[1].cmd;
    let mut by_user = Episode::from_scenario(&s, g).unwrap();
    by_user.step_with(cmd).unwrap();
    // The same (already feasible) command moves the robot the same way.
    assert_eq!(by_user.state(), by_planner.state());
    assert_eq!(by_user.time(), by_planner.time());
}

#[test]
fn non_finite_commands_are_refused_before_moving() {
    let (s, g) = room();
    let mut ep = Episode::from_scenario(&s, g).unwrap();
    for bad in [f64::NAN, f64::INFINITY] {
        let e = ep
            .step_with(Command {
                v: 0.1,
                vy: 0.0,
                w: bad,
            })
            .unwrap_err();
        assert!(e.to_string().contains("command w"), "{e}");
    }
    assert_eq!(ep.steps(), 0);
}

#[test]
fn the_scan_sees_the_walls_of_the_room() {
    let (s, g) = room();
    let ep = Episode::from_scenario(&s, g).unwrap();
    let mut lidar = Lidar::new(
        LidarConfig {
            beams: 4,
            range: 5.0,
            ..LidarConfig::default()
        },
        "lidar",
    )
    .unwrap();
    let scan = ep.scan(&mut lidar);
    // Robot at the centre of cell (2, 2) = (0.5, 0.5) m facing +x; the free
    // cells span x 0.2 … 2.2 and y 0.2 … 0.8.
    let want = [2.2 - 0.5, 0.8 - 0.5, 0.5 - 0.2, 0.5 - 0.2];
    for (i, w) in want.iter().enumerate() {
        assert!(
            (scan.ranges()[i] - w).abs() < 1e-9,
            "beam {i}: {:?}",
            scan.ranges()
        );
    }
}

#[test]
fn the_scan_and_the_observation_see_the_movers() {
    let (s, g) = preset(include_str!("../../../assets/scenarios/dwa-crowd.json"));
    let ep = Episode::from_scenario(&s, g.clone()).unwrap();
    let observed = ep.observed_movers();
    let range = ep.config().sensing_range;
    let now = ep.movers_now();
    let st = ep.state();
    let near: Vec<u32> = now
        .iter()
        .filter(|(_, r, m)| (m.pos[0] - st.x).hypot(m.pos[1] - st.y) - r <= range)
        .map(|(id, _, _)| *id)
        .collect();
    assert_eq!(observed.iter().map(|m| m.id).collect::<Vec<_>>(), near);
    // Movers shorten beams: the same pose without them reads farther.
    let cfg = LidarConfig {
        beams: 720,
        range: 30.0,
        ..LidarConfig::default()
    };
    let with = ep.scan(&mut Lidar::new(cfg, "lidar").unwrap());
    let mut bare = s.clone();
    bare.movers = None;
    let ep2 = Episode::from_scenario(&bare, g).unwrap();
    let without = ep2.scan(&mut Lidar::new(cfg, "lidar").unwrap());
    let shorter = with
        .ranges()
        .iter()
        .zip(without.ranges())
        .filter(|(a, b)| a < b)
        .count();
    assert!(shorter > 0, "no beam hit a mover");
    assert!(with
        .ranges()
        .iter()
        .zip(without.ranges())
        .all(|(a, b)| a <= b));
}

#[test]
fn one_batch_episode_equals_the_episode_of_its_variant() {
    let (base, grid) = preset(include_str!("../../../assets/scenarios/dwa-demo.json"));
    let choices = batch::planner_choices(&base, &["dwa".into(), "improved-dwa".into()]).unwrap();
    for k in [0, 3] {
        let v = batch::variant(&base, &grid, k, 11, 0.3).unwrap();
        for c in &choices {
            let r = batch::run_variant(&v, &grid, k, c).unwrap();
            let mut s = v.clone();
            s.local_planner = Some(c.clone());
            let mut ep = Episode::from_scenario(&s, grid.clone()).unwrap();
            ep.run();
            assert_eq!(r.trace_hash, ep.trace().hash());
            assert_eq!((r.variant, r.planner.as_str()), (k, c.name.as_str()));
            assert_eq!(r.seed, batch::variant_seed(11, k));
            assert_eq!(r.metrics, EpisodeMetrics::of_episode(&ep));
        }
    }
    let e = batch::planner_choices(&base, &["nope".into()]).unwrap_err();
    assert!(
        e.to_string().starts_with("unknown planner `nope`; known: "),
        "{e}"
    );
    let e = batch::planner_choices(&base, &["dwa".into(), " dwa".into()]).unwrap_err();
    assert_eq!(e.to_string(), "`dwa` is listed twice");
    let own = batch::planner_choices(&base, &[]).unwrap();
    assert_eq!(own, vec![base.local_planner.clone().unwrap_or_default()]);
}
