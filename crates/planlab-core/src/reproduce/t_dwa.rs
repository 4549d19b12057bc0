//! Experiments of \[T\] Wu 2022 ch. 3 (improved DWA + A* fusion): ids
//! `T-fig3-2`, `T-fig3-11`, `T-fig3-13a`, `T-fig3-13b`, `T-tab3-2`.
//!
//! The presets (`assets/scenarios/T-*.json`, made by
//! `scripts/gen_dwa_scenarios.py`) resemble the thesis's figures; the runs
//! compare plain `dwa`, the "\[53\]" baseline `fusion-53` and
//! `improved-dwa`, each with its default config. Each relation is the
//! thesis's, clause by clause: §3.1 (Fig 3-2), §3.2.2 (Fig 3-11/3-12),
//! §3.2.3 (Fig 3-13/3-14: the goal near an obstacle, where the thesis says
//! both plain DWA and \[53\] fail), §3.3 (Table 3-2: shorter *and* faster,
//! both planners arriving).

use super::clause::{self, diff, effect, ok, outcome, ratio, reached};
use super::{Deviation, Experiment, Family, Perturbation, RunSpec, Runs};
use crate::metrics::EpisodeMetrics;
use crate::sim::Outcome;

const FIG3_2: &str = include_str!("../../../../assets/scenarios/T-fig3-2.json");
const FIG3_11: &str = include_str!("../../../../assets/scenarios/T-fig3-11.json");
const FIG3_13A: &str = include_str!("../../../../assets/scenarios/T-fig3-13a.json");
const FIG3_13B: &str = include_str!("../../../../assets/scenarios/T-fig3-13b.json");
const TAB3_2: &str = include_str!("../../../../assets/scenarios/T-tab3-2.json");

/// A baseline "circles" when its driven path is this many times the
/// improved planner's.
pub const CIRCLING_FACTOR: f64 = 1.3;

type R = Runs<EpisodeMetrics>;

fn runs(scenario: &'static str, planners: &[(&'static str, &'static str)]) -> Vec<RunSpec> {
    planners
        .iter()
        .map(|&(name, planner)| RunSpec {
            name,
            scenario_json: scenario,
            planner: Some(planner),
            set: vec![],
        })
        .collect()
}

/// The baseline `name` did not reach the goal, or drove at least
/// [`CIRCLING_FACTOR`] times the improved planner's path.
fn fails_or_circles(r: &R, name: &str) -> bool {
    match (r.get(name), r.get("improved")) {
        (Some(b), Some(i)) => {
            b.outcome != Outcome::Reached || b.path_length_m >= CIRCLING_FACTOR * i.path_length_m
        }
        _ => false,
    }
}

/// Path of `name` over the improved one's, when both reached.
fn length_ratio(r: &R, name: &str) -> Option<f64> {
    let (b, i) = (r.get(name)?, r.get("improved")?);
    (b.outcome == Outcome::Reached && i.outcome == Outcome::Reached)
        .then(|| b.path_length_m / i.path_length_m)
}

/// The family of the open-room scenes: start, goal and movers moved, mover
/// speeds ±20 %, free-standing blocks up to 2 cells (0.2 m), a new seed.
fn room_family(goal_m: f64, goal_why: &'static str, movers_m: f64) -> Family {
    Family {
        perturbations: vec![
            Perturbation::start(0.2).because(
                "up to 0.2 m, less than the robot's 0.25 m radius: it starts where the figure \
                 starts it, facing the same obstacles",
            ),
            Perturbation::goal(goal_m).because(goal_why),
            Perturbation::Movers {
                radius_m: movers_m,
                speed_rel: 0.2,
            }
            .because(
                "mover paths shifted a little (0.2 m; 0.05 m in the Fig 3-13 scenes, whose \
                 gaps are tight) and speeds ±20 %: they still cross or block the robot's way \
                 as drawn, at the speeds the thesis's classes (static, slow, ordinary) name",
            ),
            Perturbation::Blocks { cells: 2 }.because(
                "free-standing obstacles moved by up to 2 cells (0.2 m) per axis: the same \
                 layout as drawn, not the same pixels (the room's walls stay)",
            ),
            Perturbation::Seed.because("another noise seed: the scene itself is unchanged"),
        ],
    }
}

/// The goal range of the scenes where the goal is anywhere in the open.
const GOAL_OPEN: &str = "up to 0.2 m: the goal stays in the same open part of the room";
/// The goal range of Fig 3-13, whose goal lies 0.36 m from a disc.
const GOAL_NEAR_DISC: &str = "up to 5 cm: the goal's 0.36 m gap to the disc's surface (Fig 3-13) \
     stays 0.31–0.41 m, beyond the robot's footprint and within the disc's reach";

/// The values of the \[T\] ch. 3 planners that the thesis does not give.
fn planner_deviations() -> Vec<Deviation> {
    vec![
        Deviation {
            what: "scene geometry (the thesis draws its maps, gives no file)",
            path: None,
            ours: "assets/scenarios/T-*.json, drawn to resemble the figure",
            paper: "not given",
        },
        Deviation {
            what: "DWA weights α, β, γ (plain and detour strategy)",
            path: Some("local_planner.config.dwa.alpha"),
            ours: "0.05, 0.2, 0.1",
            paper: "not given",
        },
        Deviation {
            what: "deceleration strategy heading weight (\"large\")",
            path: Some("local_planner.config.decelerate.alpha"),
            ours: "1.0",
            paper: "not given",
        },
        Deviation {
            what: "speed above which a mover is ordinary dynamic",
            path: Some("local_planner.config.v_static"),
            ours: "0.1 m/s (0.07 m/s is treated as static in §3.3)",
            paper: "not given",
        },
        Deviation {
            what: "range within which movers are classified",
            path: Some("local_planner.config.react_range"),
            ours: "3.0 m",
            paper: "not given",
        },
        Deviation {
            what: "rollout horizon",
            path: Some("local_planner.config.dwa.predict_time"),
            ours: "3.0 s",
            paper: "not given",
        },
        Deviation {
            what: "radius within which a virtual goal counts as reached",
            path: Some("local_planner.config.virtual_radius"),
            ours: "0.3 m",
            paper: "not given (the thesis gives no reach rule for virtual goals)",
        },
        Deviation {
            what: "radius within which the next key point is taken",
            path: Some("local_planner.config.switch_radius"),
            ours: "1.0 m",
            paper: "not given",
        },
        Deviation {
            what: "distance from the current goal within which the near-goal rules apply",
            path: Some("local_planner.config.goal_region"),
            ours: "1.5 m",
            paper: "not given (Fig 3-13 c–e draws the cases)",
        },
        Deviation {
            what: "A* inflation beyond the footprint for the key-point path",
            path: Some("local_planner.config.inflate_margin"),
            ours: "0.1 m",
            paper: "not given",
        },
        Deviation {
            what: "still obstacle near the goal, robot closer to the goal than to it (drive-in)",
            path: None,
            ours: "no virtual goal; deceleration weights with ρ",
            paper: "detour for any obstacle that is not ordinary dynamic (§3.2)",
        },
    ]
}

/// "Baseline `run` fails or circles near the goal" (\[T\] §3.2.3: plain
/// DWA and \[53\] both), with the path ratio as its effect.
fn circles_clause(run: &str) -> super::Clause<EpisodeMetrics> {
    if run == "dwa" {
        effect(
            "dwa fails or circles",
            "plain DWA cannot reach a goal this close to an obstacle (fails, or circles: \
             path ≥ 1.3 × the improved one's)",
            |r| fails_or_circles(r, "dwa"),
            ratio("path dwa / improved (both reached)", |r| {
                length_ratio(r, "dwa")
            }),
        )
    } else {
        effect(
            "[53] fails or circles",
            "the [53] baseline cannot reach it either (Fig 3-14)",
            |r| fails_or_circles(r, "fusion-53"),
            ratio("path fusion-53 / improved (both reached)", |r| {
                length_ratio(r, "fusion-53")
            }),
        )
    }
}

fn improved_reaches() -> super::Clause<EpisodeMetrics> {
    outcome(
        "improved reaches",
        "the improved DWA reaches the goal without collision",
        |r| ok(r, "improved"),
    )
}

/// The \[T\] experiments.
pub fn experiments() -> Vec<Experiment> {
    let all3 = [
        ("dwa", "dwa"),
        ("fusion-53", "fusion-53"),
        ("improved", "improved-dwa"),
    ];
    vec![
        Experiment {
            id: "T-fig3-2",
            paper: "[T] Wu 2022, Fig 3-2",
            what: "C-shaped trap between start and goal, open toward the robot",
            relation: "plain DWA ends trapped in the C (does not reach); the improved fusion \
                       (A* key points) reaches the goal without collision",
            runs: runs(FIG3_2, &all3),
            clauses: vec![
                improved_reaches(),
                effect(
                    "dwa trapped",
                    "plain DWA falls into the C-shaped local optimum and does not reach",
                    |r| {
                        r.get("dwa")
                            .is_some_and(|m| !matches!(m.outcome, Outcome::Reached))
                    },
                    None,
                ),
            ],
            family: room_family(0.2, GOAL_OPEN, 0.2),
            deviations: planner_deviations(),
            figures: None,
            scene: None,
        },
        Experiment {
            id: "T-fig3-11",
            paper: "[T] Wu 2022, Fig 3-11 / 3-12",
            what: "a mover crossing the start–goal line near the start (0.4 m/s, stops at \
                   the wall) and a still disc on the line near the goal",
            relation: "improved DWA decelerates for the mover, sets a virtual goal for the \
                       collinear disc and reaches the goal without collision (the trace's \
                       classes and goal kinds show it; see tests/reproduce_dwa.rs); the [53] \
                       baseline, which has no special-obstacle rule, does not pass the \
                       collinear disc",
            runs: runs(FIG3_11, &all3),
            clauses: vec![
                improved_reaches(),
                effect(
                    "[53] does not pass",
                    "the [53] baseline cannot cope with the special (collinear) obstacle and \
                     does not reach",
                    |r| !reached(r, "fusion-53"),
                    None,
                ),
            ],
            family: room_family(0.2, GOAL_OPEN, 0.2),
            deviations: planner_deviations(),
            figures: None,
            scene: None,
        },
        Experiment {
            id: "T-fig3-13a",
            paper: "[T] Wu 2022, Fig 3-13 a–b / 3-14",
            what: "scene 1: the goal 0.11 m beyond the footprint from a disc, approached \
                   from the open side",
            relation: "plain DWA and the [53] baseline fail or circle (path ≥ 1.3 × the \
                       improved one's) near the goal; the improved DWA (ρ, drive-in) reaches \
                       it",
            runs: runs(FIG3_13A, &all3),
            clauses: vec![
                improved_reaches(),
                circles_clause("dwa"),
                circles_clause("fusion-53"),
            ],
            // The scene is the goal's distance to the disc: goal and disc move
            // by at most 5 cm so a variant stays a "goal near an obstacle".
            family: room_family(0.05, GOAL_NEAR_DISC, 0.05),
            deviations: planner_deviations(),
            figures: None,
            scene: None,
        },
        Experiment {
            id: "T-fig3-13b",
            paper: "[T] Wu 2022, Fig 3-13 c–e / 3-14",
            what: "scene 2: a disc on the start–goal line just before the goal",
            relation: "plain DWA and the [53] baseline fail or circle; the improved DWA \
                       (virtual goal beside the goal, then drive-in) reaches the goal",
            runs: runs(FIG3_13B, &all3),
            clauses: vec![
                improved_reaches(),
                circles_clause("dwa"),
                circles_clause("fusion-53"),
            ],
            family: room_family(0.05, GOAL_NEAR_DISC, 0.05),
            deviations: planner_deviations(),
            figures: None,
            scene: None,
        },
        Experiment {
            id: "T-tab3-2",
            paper: "[T] Wu 2022, Table 3-2 (19.01 m / 77.8 s vs 20.22 m / 114.0 s)",
            what: "office-like map, four movers at 0.40, 0.28, 0.07 and 0.01 m/s",
            relation: "both reach the goal; the improved DWA's path is shorter and its time \
                       shorter than the [53] baseline's (paper: 19.01 vs 20.22 m, 77.8 vs \
                       114.0 s)",
            runs: runs(
                TAB3_2,
                &[("fusion-53", "fusion-53"), ("improved", "improved-dwa")],
            ),
            clauses: vec![
                improved_reaches(),
                outcome(
                    "[53] reaches",
                    "the [53] baseline reaches the goal too (Table 3-2 has its length and time)",
                    |r| ok(r, "fusion-53"),
                ),
                effect(
                    "shorter",
                    "the improved DWA's path is shorter",
                    |r| match (r.get("improved"), r.get("fusion-53")) {
                        (Some(i), Some(b)) => {
                            ok(r, "improved")
                                && ok(r, "fusion-53")
                                && i.path_length_m < b.path_length_m
                        }
                        _ => false,
                    },
                    diff("path improved − fusion-53 (both reached)", "m", |r| {
                        both(r).map(|(i, b)| i.path_length_m - b.path_length_m)
                    }),
                ),
                effect(
                    "faster",
                    "the improved DWA takes less time",
                    |r| match (r.get("improved"), r.get("fusion-53")) {
                        (Some(i), Some(b)) => {
                            ok(r, "improved") && ok(r, "fusion-53") && i.time_s < b.time_s
                        }
                        _ => false,
                    },
                    diff("time improved − fusion-53 (both reached)", "s", |r| {
                        both(r).map(|(i, b)| i.time_s - b.time_s)
                    }),
                ),
            ],
            family: room_family(0.2, GOAL_OPEN, 0.2),
            deviations: planner_deviations(),
            figures: None,
            scene: None,
        },
    ]
}

/// The improved and \[53\] runs when both succeeded.
fn both(r: &R) -> Option<(&EpisodeMetrics, &EpisodeMetrics)> {
    (clause::ok(r, "improved") && clause::ok(r, "fusion-53"))
        .then(|| Some((r.get("improved")?, r.get("fusion-53")?)))
        .flatten()
}
