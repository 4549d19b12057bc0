//! Experiments of \[T\] Wu 2022 ch. 4 (potential fields): ids `T-fig4-6`,
//! `T-fig4-8`, `T-fig4-10`, `T-fig4-11`, `T-fig4-12`, `T-tab4-1`.
//!
//! The presets (`assets/scenarios/T-fig4-*.json`, `T-tab4-1.json`, made by
//! `scripts/gen_apf_scenarios.py`) are kinematic APF scenes (an `apf`
//! section): a point robot stepping 0.04 m among discs (2D) or a sphere
//! (3D, `T-tab4-1`). The runs switch the variant with `apf.config.mode`
//! (and the relative distance rule with `apf.config.relative_distance`).

use std::collections::BTreeMap;

use super::{PathExperiment, RunSpec};
use crate::apf::ApfMetrics;
use crate::sim::Outcome;

const FIG4_6: &str = include_str!("../../../../assets/scenarios/T-fig4-6.json");
const FIG4_8: &str = include_str!("../../../../assets/scenarios/T-fig4-8.json");
const FIG4_10: &str = include_str!("../../../../assets/scenarios/T-fig4-10.json");
const FIG4_11: &str = include_str!("../../../../assets/scenarios/T-fig4-11.json");
const FIG4_12: &str = include_str!("../../../../assets/scenarios/T-fig4-12.json");
const TAB4_1: &str = include_str!("../../../../assets/scenarios/T-tab4-1.json");

/// The three variants of \[T\] Fig 4-10…4-12 / Table 4-1.
fn three(scenario: &'static str) -> Vec<RunSpec> {
    [
        ("apf", "basic"),
        ("sampling", "sampling"),
        ("sampling+prediction", "sampling-prediction"),
    ]
    .into_iter()
    .map(|(name, mode)| RunSpec {
        name,
        scenario_json: scenario,
        planner: None,
        set: vec![("apf.config.mode", mode)],
    })
    .collect()
}

fn reached(r: &BTreeMap<String, ApfMetrics>, name: &str) -> bool {
    r.get(name).is_some_and(|m| m.outcome == Outcome::Reached)
}

fn reached_safely(r: &BTreeMap<String, ApfMetrics>, name: &str) -> bool {
    r.get(name)
        .is_some_and(|m| m.outcome == Outcome::Reached && m.min_obstacle_distance_m > 0.0)
}

fn length(r: &BTreeMap<String, ApfMetrics>, name: &str) -> f64 {
    r.get(name).map_or(f64::NAN, |m| m.path_length_m)
}

fn spikes(r: &BTreeMap<String, ApfMetrics>, name: &str) -> u32 {
    r.get(name).map_or(u32::MAX, |m| m.spikes)
}

/// The \[T\] ch. 4 experiments.
pub fn experiments() -> Vec<PathExperiment> {
    vec![
        PathExperiment {
            id: "T-fig4-6",
            paper: "[T] Wu 2022, Fig 4-1 / 4-6",
            what: "start, a disc and the goal on one line (local minimum of the basic field)",
            relation: "basic APF oscillates in front of the disc and ends stuck; the sampling \
                       APF escapes around it and reaches the goal",
            runs: three(FIG4_6).into_iter().take(2).collect(),
            holds: |r| {
                r.get("apf").is_some_and(|m| m.outcome == Outcome::Stuck)
                    && reached_safely(r, "sampling")
            },
        },
        PathExperiment {
            id: "T-fig4-8",
            paper: "[T] Wu 2022, Fig 4-7 / 4-8",
            what: "the goal between the robot and a disc, inside its repulsion range",
            relation: "basic APF and the sampling APF without the relative distance rule stall \
                       before the goal; with the rule the sampling APF reaches it",
            runs: vec![
                RunSpec {
                    name: "apf",
                    scenario_json: FIG4_8,
                    planner: None,
                    set: vec![("apf.config.mode", "basic")],
                },
                RunSpec {
                    name: "sampling-no-rule",
                    scenario_json: FIG4_8,
                    planner: None,
                    set: vec![
                        ("apf.config.mode", "sampling"),
                        ("apf.config.relative_distance", "false"),
                    ],
                },
                RunSpec {
                    name: "sampling+rule",
                    scenario_json: FIG4_8,
                    planner: None,
                    set: vec![("apf.config.mode", "sampling")],
                },
            ],
            holds: |r| {
                !reached(r, "apf")
                    && !reached(r, "sampling-no-rule")
                    && reached_safely(r, "sampling+rule")
            },
        },
        PathExperiment {
            id: "T-fig4-10",
            paper: "[T] Wu 2022, Fig 4-10 (fails / 0.96 m / 0.84 m)",
            what: "a disc moving head-on along the robot's line",
            relation: "basic APF does not reach the goal; the sampling APF does; with \
                       prediction the path is shorter",
            runs: three(FIG4_10),
            holds: |r| {
                !reached(r, "apf")
                    && reached_safely(r, "sampling")
                    && reached_safely(r, "sampling+prediction")
                    && length(r, "sampling+prediction") < length(r, "sampling")
            },
        },
        PathExperiment {
            id: "T-fig4-11",
            paper: "[T] Wu 2022, Fig 4-11 (0.870 / 0.840 / 0.809 m)",
            what: "the mover's line offset 0.04 m from the robot's",
            relation: "all reach; path length basic > sampling > sampling+prediction; the \
                       basic path has the most spikes",
            runs: three(FIG4_11),
            holds: |r| {
                ["apf", "sampling", "sampling+prediction"]
                    .iter()
                    .all(|n| reached_safely(r, n))
                    && length(r, "apf") > length(r, "sampling")
                    && length(r, "sampling") > length(r, "sampling+prediction")
                    && spikes(r, "apf") > spikes(r, "sampling")
                    && spikes(r, "apf") > spikes(r, "sampling+prediction")
            },
        },
        PathExperiment {
            id: "T-fig4-12",
            paper: "[T] Wu 2022, Fig 4-12 (0.659 / 0.690 / 0.690 m)",
            what: "the mover's line offset 0.1 m: little overlap",
            relation: "all reach; the improvement is not evident: both improved paths are at \
                       least as long as the basic one (within 10 %)",
            runs: three(FIG4_12),
            holds: |r| {
                ["apf", "sampling", "sampling+prediction"]
                    .iter()
                    .all(|n| reached_safely(r, n))
                    && ["sampling", "sampling+prediction"].iter().all(|n| {
                        length(r, n) >= length(r, "apf") && length(r, n) <= 1.1 * length(r, "apf")
                    })
            },
        },
        PathExperiment {
            id: "T-tab4-1",
            paper: "[T] Wu 2022, Table 4-1 (1.018 / 0.816 / 0.768 m; spikes 4 / 1 / 0)",
            what: "3D: the end effector crosses the table while a hand (sphere) reaches \
                   toward it head-on, 0.04 m below its line",
            relation: "all reach; path length basic > sampling > sampling+prediction; spikes \
                       fall: basic > sampling > sampling+prediction = 0",
            runs: three(TAB4_1),
            holds: |r| {
                ["apf", "sampling", "sampling+prediction"]
                    .iter()
                    .all(|n| reached_safely(r, n))
                    && length(r, "apf") > length(r, "sampling")
                    && length(r, "sampling") > length(r, "sampling+prediction")
                    && spikes(r, "apf") > spikes(r, "sampling")
                    && spikes(r, "sampling") > spikes(r, "sampling+prediction")
                    && spikes(r, "sampling+prediction") == 0
            },
        },
    ]
}
