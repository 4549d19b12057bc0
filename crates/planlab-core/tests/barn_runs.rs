//! BARN runs: the planner knows only what the laser shows, runs are scored
//! as the challenge scores and repeat for a seed, and the cases where a
//! planner once hit a cylinder its laser had seen stay fixed.

use planlab_core::barn::run::{self, BarnOptions, BarnRun, BarnStats, MeanCi};
use planlab_core::barn::{parse_compact, score, BarnWorld, GOAL, GOAL_TOLERANCE};
use planlab_core::sim::Episode;
use planlab_core::world::Outcome;

const WORLDS: &str = include_str!("../../../assets/barn/worlds.txt");

fn world(id: u32) -> BarnWorld {
    parse_compact(WORLDS)
        .unwrap()
        .into_iter()
        .find(|w| w.id == id)
        .unwrap()
}

fn episode(id: u32, planner: &str, seed: u64) -> Episode {
    let (s, grid) = run::scenario(&world(id), planner, seed, &BarnOptions::default()).unwrap();
    Episode::from_scenario(&s, grid).unwrap()
}

#[test]
fn the_planner_starts_knowing_only_what_the_first_scan_shows() {
    let w = world(1);
    let mut ep = episode(1, "improved-dwa", 3);
    let p = ep.perception().expect("a BARN run perceives");
    let marked = |x: f64, y: f64| {
        let f = p.frame();
        f.world_to_cell(x, y)
            .is_some_and(|(c, r)| p.marks()[r * f.width() + c])
    };
    // Every cylinder beyond the obstacle range is unknown to the planner,
    // and none of its map cells is blocked...
    let far: Vec<[f64; 2]> = w
        .cylinders()
        .into_iter()
        .filter(|c| (c[0] + 2.25).hypot(c[1] - 3.0) > 2.6)
        .collect();
    assert!(far.len() > 100, "{}", far.len());
    assert!(far.iter().all(|c| !marked(c[0], c[1])));
    assert!(far.iter().all(|c| p.map().clearance(c[0], c[1]) > 0.0));
    // ... while the true map has them.
    assert!(far.iter().all(|c| ep.map().clearance(c[0], c[1]) == 0.0));
    // So the first global route runs straight through the unseen grid.
    ep.step();
    let route = &ep.planner_debug().global_path;
    assert!(!route.is_empty());
    let blocked_in_truth = route
        .iter()
        .filter(|p| ep.map().clearance(p[0], p[1]) == 0.0)
        .count();
    assert!(
        blocked_in_truth > 0,
        "the route avoided cylinders it cannot know"
    );
}

#[test]
fn a_run_is_scored_as_the_challenge_scores_and_repeats_for_its_seed() {
    let w = world(1);
    let a = run::run_one(&w, "dwb", 0, 5, &BarnOptions::default()).unwrap();
    let b = run::run_one(&w, "dwb", 0, 5, &BarnOptions::default()).unwrap();
    assert_eq!(a, b);
    assert_eq!(a.outcome, Outcome::Reached, "{a:?}");
    assert!(a.time > 0.0 && a.time < 100.0, "{a:?}");
    assert_eq!(a.score, score(true, a.time, a.optimal_time));
    assert!(a.score > 0.0 && a.score <= 0.5);
    // It drove at least the straight line to the goal's success circle.
    assert!(a.path_length > 10.0 - GOAL_TOLERANCE - 0.01, "{a:?}");
    // Another seed is other laser noise: another trace.
    let c = run::run_one(&w, "dwb", 0, 6, &BarnOptions::default()).unwrap();
    assert_ne!(a.trace_hash, c.trace_hash);
    // Without noise the seed does not matter.
    let exact = BarnOptions { noise_std: 0.0 };
    let d = run::run_one(&w, "dwb", 0, 5, &exact).unwrap();
    let e = run::run_one(&w, "dwb", 0, 6, &exact).unwrap();
    assert_eq!(d.trace_hash, e.trace_hash);
}

#[test]
fn barn_world_4_safe_dual_dwa_stops_before_a_cylinder_it_saw_2_5_m_ahead() {
    // Held at 0.79 m/s by the dual-velocity model, the robot drove into a
    // cylinder it had marked 2.5 m ahead: with no admissible sample the
    // fallback braked at [S]'s 0.2 m/s² (the planner's cap), not at the
    // robot's own deceleration.
    let mut ep = episode(4, "safe-dual-dwa", 10494417696885921743);
    let end = ep.run();
    assert_ne!(end, Outcome::Collision, "at t = {}", ep.time());
}

#[test]
fn barn_world_121_move_base_dwa_hits_a_seen_cylinder_only_backing_up_blind() {
    // The one kind of seen collision the baseline keeps on purpose: with no
    // legal trajectory, base_local_planner's TrajectoryPlanner backs up at
    // escape_vel "even when the static map shows it as blocked" (its source
    // says so), and the Jackal's laser does not look behind. The contact
    // comes in escape mode, moving backwards.
    let mut ep = episode(121, "move-base-dwa", 457844488705524604);
    assert_eq!(ep.run(), Outcome::Collision);
    assert_eq!(ep.collision_seen(), Some(true));
    let steps = &ep.trace().steps;
    let last = steps.last().unwrap();
    assert_eq!(last.mode, "escape", "at t = {}", last.t);
    assert!(
        last.cmd.v < 0.0 && last.v < 0.0,
        "{:?} {}",
        last.cmd,
        last.v
    );
}

#[test]
fn barn_world_208_scan_apf_never_turns_a_corner_into_a_cylinder_it_sees() {
    // Stopped beside a cylinder (its circumscribed disc no longer clear),
    // the APF under scan-apf turned in place toward the goal and swept a
    // corner of the Jackal's rectangle into the cylinder: only driving was
    // checked, for the disc. The turn is now swept against the map first.
    let mut ep = episode(208, "scan-apf", 14352028815507708487);
    let end = ep.run();
    assert_ne!(end, Outcome::Collision, "at t = {}", ep.time());
}

#[test]
fn every_barn_planner_starts_on_a_world() {
    let w = world(2);
    for p in run::PLANNERS {
        let (s, grid) = run::scenario(&w, p, 0, &BarnOptions::default()).unwrap();
        let mut ep = Episode::from_scenario(&s, grid).unwrap_or_else(|e| panic!("{p}: {e}"));
        for _ in 0..5 {
            ep.step();
        }
        assert_eq!(ep.outcome(), Outcome::Running, "{p}");
        let d = (ep.state().x - GOAL[0]).hypot(ep.state().y - GOAL[1]);
        assert!(d > 5.0, "{p}");
    }
}

fn fake(outcome: Outcome, time: f64, ot: f64) -> BarnRun {
    BarnRun {
        world: 1,
        planner: "x".into(),
        run: 0,
        seed: 0,
        outcome,
        time,
        optimal_time: ot,
        score: score(outcome == Outcome::Reached, time, ot),
        path_length: 10.0,
        trace_hash: 0,
        collision_seen: (outcome == Outcome::Collision).then_some(true),
    }
}

#[test]
fn statistics_count_outcomes_and_give_intervals() {
    let runs = [
        fake(Outcome::Reached, 10.0, 6.0),
        fake(Outcome::Reached, 20.0, 6.0),
        fake(Outcome::Collision, 5.0, 6.0),
        fake(Outcome::Timeout, 100.0, 6.0),
    ];
    let s = BarnStats::of(runs.iter());
    assert_eq!(s.runs, 4);
    assert_eq!((s.success.k, s.collision.k, s.timeout.k), (2, 1, 1));
    assert_eq!((s.collisions_seen, s.collisions_unclassified), (1, 0));
    assert!(s.success.ci95[0] < 0.5 && s.success.ci95[1] > 0.5);
    assert_eq!(s.mean_time, Some(15.0));
    let m = s.score.unwrap();
    let want = (6.0 / 12.0 + 6.0 / 20.0) / 4.0;
    assert!((m.mean - want).abs() < 1e-12);
    assert!(m.ci95[0] <= m.mean && m.mean <= m.ci95[1] && m.ci95[0] >= 0.0);
    assert_eq!(MeanCi::of(&[0.2, 0.4]), MeanCi::of(&[0.2, 0.4]));
    // The order of the runs does not change the interval.
    let v: Vec<f64> = (0..40).map(|i| f64::from(i * 7 % 13) / 26.0).collect();
    let mut w = v.clone();
    w.reverse();
    assert_eq!(MeanCi::of(&v), MeanCi::of(&w));
    assert_eq!(MeanCi::of(&[]), None);
    assert_eq!(MeanCi::of(&[0.3]).unwrap().ci95, [0.3, 0.3]);
    assert_eq!(s.worlds, 1);
}

#[test]
fn score_intervals_resample_worlds_not_runs() {
    // Three identical runs of each world carry no more information than
    // one: the cluster bootstrap gives the one-run interval, where
    // resampling the 3·40 runs as independent draws would narrow it.
    let v: Vec<f64> = (0..40).map(|i| f64::from(i * 7 % 13) / 26.0).collect();
    let tripled: Vec<Vec<f64>> = v.iter().map(|&x| vec![x; 3]).collect();
    let one = MeanCi::of(&v).unwrap();
    let three = MeanCi::of_clusters(&tripled).unwrap();
    let close = |a: f64, b: f64| (a - b).abs() < 1e-12;
    assert!(close(three.mean, one.mean), "{three:?} {one:?}");
    assert!(close(three.ci95[0], one.ci95[0]) && close(three.ci95[1], one.ci95[1]));
    let flat: Vec<f64> = tripled.concat();
    let naive = MeanCi::of(&flat).unwrap();
    assert!(naive.ci95[1] - naive.ci95[0] < 0.8 * (one.ci95[1] - one.ci95[0]));
    // BarnStats groups runs by world: three runs of one outcome per world
    // give the one-run success interval.
    let mut runs = Vec::new();
    for w in 0..40 {
        for r in 0..3 {
            let outcome = if w % 4 == 0 {
                Outcome::Timeout
            } else {
                Outcome::Reached
            };
            runs.push(BarnRun {
                world: w,
                run: r,
                ..fake(outcome, 10.0, 6.0)
            });
        }
    }
    let s = BarnStats::of(runs.iter());
    assert_eq!((s.runs, s.worlds, s.success.k), (120, 40, 90));
    assert_eq!(
        s.success.ci95,
        planlab_core::reproduce::stats::wilson(30, 40)
    );
}

#[test]
fn sweep_seeds_are_shared_by_planners_and_differ_by_world_and_run() {
    assert_eq!(run::run_seed(0, 1, 0), run::run_seed(0, 1, 0));
    assert_ne!(run::run_seed(0, 1, 0), run::run_seed(0, 1, 1));
    assert_ne!(run::run_seed(0, 1, 0), run::run_seed(0, 2, 0));
    assert_ne!(run::run_seed(0, 1, 0), run::run_seed(1, 1, 0));
}

/// Drives `ep` with a constant command until the episode ends.
fn drive_until_end(ep: &mut Episode, v: f64) -> Outcome {
    let cmd = planlab_core::world::Command { v, vy: 0.0, w: 0.0 };
    for _ in 0..5000 {
        let o = ep.step_with(cmd).unwrap();
        if o != Outcome::Running {
            return o;
        }
    }
    Outcome::Running
}

#[test]
fn a_collision_is_seen_when_the_scans_had_marked_what_was_hit() {
    // Straight ahead into the cylinders: the laser looks that way.
    let mut ahead = episode(1, "dwa", 0);
    assert_eq!(ahead.collision_seen(), None, "not before a collision");
    assert_eq!(drive_until_end(&mut ahead, 1.0), Outcome::Collision);
    assert_eq!(ahead.collision_seen(), Some(true));
    // Backing straight into the containment wall: in the 90° the UST-10
    // does not cover, so never marked.
    let mut behind = episode(1, "dwa", 0);
    assert_eq!(drive_until_end(&mut behind, -1.0), Outcome::Collision);
    assert_eq!(behind.collision_seen(), Some(false));
    // A run that does not collide has no such verdict.
    let r = run::run_one(&world(1), "dwa", 0, 1, &BarnOptions::default()).unwrap();
    assert!(r.outcome != Outcome::Collision || r.collision_seen.is_some());
    if r.outcome != Outcome::Collision {
        assert_eq!(r.collision_seen, None);
    }
}

#[test]
fn the_readme_tables_runs_replay_to_their_trace_hashes() {
    // docs/barn-runs-seed{0,1,2}.csv hold every run of the README's BARN
    // table; a change to a planner or the simulation that alters them must
    // come with new sweeps. The shortest successful run of each planner in
    // each sweep is replayed (columns: world, difficulty, planner, run,
    // seed of the run, outcome, time_s, …, trace_hash at 10).
    let sweeps = [
        include_str!("../../../docs/barn-runs-seed0.csv"),
        include_str!("../../../docs/barn-runs-seed1.csv"),
        include_str!("../../../docs/barn-runs-seed2.csv"),
    ];
    for (sweep, text) in sweeps.iter().enumerate() {
        // The shortest successful run of each planner in this sweep.
        let mut shortest = std::collections::BTreeMap::<&str, (f64, &str)>::new();
        for line in text.lines().skip(1) {
            let f: Vec<&str> = line.split(',').collect();
            let (planner, outcome, time) = (f[2], f[5], f[6].parse::<f64>().unwrap());
            if outcome == "reached" && shortest.get(planner).is_none_or(|&(t, _)| time < t) {
                shortest.insert(planner, (time, line));
            }
        }
        assert_eq!(
            shortest.len(),
            run::PLANNERS.len(),
            "seed {sweep}: {shortest:?}"
        );
        for (_, line) in shortest.values() {
            let f: Vec<&str> = line.split(',').collect();
            let (id, run, seed): (u32, _, u64) = (
                f[0].parse().unwrap(),
                f[3].parse().unwrap(),
                f[4].parse().unwrap(),
            );
            let r = run::run_one(&world(id), f[2], run, seed, &BarnOptions::default()).unwrap();
            assert_eq!(format!("{:016x}", r.trace_hash), f[10], "{line}");
        }
    }
}
