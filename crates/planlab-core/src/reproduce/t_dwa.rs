//! Experiments of \[T\] Wu 2022 ch. 3 (improved DWA + A* fusion): ids
//! `T-fig3-2`, `T-fig3-11`, `T-fig3-13a`, `T-fig3-13b`, `T-tab3-2`.
//!
//! The presets (`assets/scenarios/T-*.json`, made by
//! `scripts/gen_dwa_scenarios.py`) resemble the thesis's figures; the runs
//! compare plain `dwa`, the "\[53\]" baseline `fusion-53` and
//! `improved-dwa`, each with its default config.

use std::collections::BTreeMap;

use super::{Experiment, RunSpec};
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

fn reached(m: &EpisodeMetrics) -> bool {
    m.outcome == Outcome::Reached
}

/// The improved run reaches the goal without touching anything.
fn improved_ok(r: &BTreeMap<String, EpisodeMetrics>) -> bool {
    r.get("improved")
        .is_some_and(|m| reached(m) && m.min_clearance_m > 0.0)
}

/// The baseline `name` did not reach the goal, or drove at least
/// [`CIRCLING_FACTOR`] times the improved planner's path.
fn fails_or_circles(r: &BTreeMap<String, EpisodeMetrics>, name: &str) -> bool {
    match (r.get(name), r.get("improved")) {
        (Some(b), Some(i)) => !reached(b) || b.path_length_m >= CIRCLING_FACTOR * i.path_length_m,
        _ => false,
    }
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
            relation: "plain DWA ends stuck in the trap; the improved fusion (A* key points) \
                       reaches the goal",
            runs: runs(FIG3_2, &all3),
            holds: |r| improved_ok(r) && r.get("dwa").is_some_and(|m| m.outcome == Outcome::Stuck),
        },
        Experiment {
            id: "T-fig3-11",
            paper: "[T] Wu 2022, Fig 3-11 / 3-12",
            what: "a mover crossing the start–goal line near the start (0.4 m/s, stops at \
                   the wall) and a still disc on the line near the goal",
            relation: "improved DWA decelerates for the mover, sets a virtual goal for the \
                       collinear disc and reaches the goal without collision (the trace's \
                       classes and goal kinds show it; see tests/reproduce_dwa.rs); the [53] \
                       baseline cannot pass the collinear disc",
            runs: runs(FIG3_11, &all3),
            holds: |r| improved_ok(r) && r.get("fusion-53").is_some_and(|m| !reached(m)),
        },
        Experiment {
            id: "T-fig3-13a",
            paper: "[T] Wu 2022, Fig 3-13 a–b / 3-14",
            what: "scene 1: the goal 0.11 m beyond the footprint from a disc, approached \
                   from the open side",
            relation: "plain DWA fails or circles (path ≥ 1.3 × the improved one's); the \
                       improved DWA (ρ, drive-in) reaches the goal",
            runs: runs(FIG3_13A, &all3),
            holds: |r| improved_ok(r) && fails_or_circles(r, "dwa"),
        },
        Experiment {
            id: "T-fig3-13b",
            paper: "[T] Wu 2022, Fig 3-13 c–e / 3-14",
            what: "scene 2: a disc on the start–goal line just before the goal",
            relation: "plain DWA and the [53] baseline fail or circle; the improved DWA \
                       (virtual goal beside the goal, then drive-in) reaches the goal",
            runs: runs(FIG3_13B, &all3),
            holds: |r| {
                improved_ok(r) && fails_or_circles(r, "dwa") && fails_or_circles(r, "fusion-53")
            },
        },
        Experiment {
            id: "T-tab3-2",
            paper: "[T] Wu 2022, Table 3-2 (19.01 m / 77.8 s vs 20.22 m / 114.0 s)",
            what: "office-like map, four movers at 0.40, 0.28, 0.07 and 0.01 m/s",
            relation: "the improved DWA reaches the goal in less time than the [53] baseline \
                       (which decelerates for every mover) over a path at most 5% longer; \
                       the paper's path is also shorter (−6%), ours is not (see the note)",
            runs: runs(
                TAB3_2,
                &[("fusion-53", "fusion-53"), ("improved", "improved-dwa")],
            ),
            holds: |r| match (r.get("improved"), r.get("fusion-53")) {
                (Some(i), Some(b)) => {
                    improved_ok(r)
                        && (!reached(b)
                            || (i.time_s < b.time_s && i.path_length_m <= 1.05 * b.path_length_m))
                }
                _ => false,
            },
        },
    ]
}
