//! Experiments of \[T\] Wu 2022 ch. 4 (potential fields): ids `T-fig4-6`,
//! `T-fig4-8`, `T-fig4-10`, `T-fig4-11`, `T-fig4-12`, `T-tab4-1`.
//!
//! The presets (`assets/scenarios/T-fig4-*.json`, `T-tab4-1.json`, made by
//! `scripts/gen_apf_scenarios.py`) are kinematic APF scenes (an `apf`
//! section): a point robot stepping 0.04 m among discs (2D) or a sphere
//! (3D, `T-tab4-1`). The runs switch the variant with `apf.config.mode`
//! (and the relative distance rule with `apf.config.relative_distance`).
//! The families move the discs by up to 2 cm (the scenes are 1 m across):
//! the local minimum of Fig 4-6 needs start, disc and goal exactly on one
//! line, and the family says how often it survives being a little off it.

use super::clause::{diff, effect, ok, outcome, reached};
use super::{Deviation, Family, PathExperiment, Perturbation, RunSpec, Runs};
use crate::apf::ApfMetrics;
use crate::sim::Outcome;

const FIG4_6: &str = include_str!("../../../../assets/scenarios/T-fig4-6.json");
const FIG4_8: &str = include_str!("../../../../assets/scenarios/T-fig4-8.json");
const FIG4_10: &str = include_str!("../../../../assets/scenarios/T-fig4-10.json");
const FIG4_11: &str = include_str!("../../../../assets/scenarios/T-fig4-11.json");
const FIG4_12: &str = include_str!("../../../../assets/scenarios/T-fig4-12.json");
const TAB4_1: &str = include_str!("../../../../assets/scenarios/T-tab4-1.json");

type R = Runs<ApfMetrics>;

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

fn length(r: &R, name: &str) -> f64 {
    r.get(name).map_or(f64::NAN, |m| m.path_length_m)
}

fn spikes(r: &R, name: &str) -> u32 {
    r.get(name).map_or(u32::MAX, |m| m.spikes)
}

/// Path length basic > sampling > sampling+prediction.
fn ordered(r: &R) -> bool {
    length(r, "apf") > length(r, "sampling")
        && length(r, "sampling") > length(r, "sampling+prediction")
}

/// "Path length basic > sampling > sampling+prediction", with the
/// prediction's gain over the basic path as its effect.
fn lengths_fall() -> super::Clause<ApfMetrics> {
    effect(
        "lengths fall",
        "path length basic > sampling > sampling+prediction",
        |r| all_ok(r) && ordered(r),
        diff("path prediction − basic", "m", |r| {
            all_ok(r).then(|| length(r, "sampling+prediction") - length(r, "apf"))
        }),
    )
}

fn all_ok(r: &R) -> bool {
    r.metrics.keys().all(|k| ok(r, k))
}

/// 2D scenes: start, goal and discs moved up to 2 cm, mover speeds ±20 %.
fn family_2d() -> Family {
    Family {
        perturbations: vec![
            Perturbation::start(0.02),
            Perturbation::goal(0.02),
            Perturbation::ApfObstacles {
                radius_m: 0.02,
                speed_rel: 0.2,
            },
        ],
    }
}

/// The 3D scene: its start, goal and sphere moved up to 2 cm, speed ±20 %.
fn family_3d() -> Family {
    Family {
        perturbations: vec![
            Perturbation::Point {
                path: "apf.start",
                radius_m: 0.02,
            },
            Perturbation::Point {
                path: "apf.goal",
                radius_m: 0.02,
            },
            Perturbation::ApfObstacles {
                radius_m: 0.02,
                speed_rel: 0.2,
            },
        ],
    }
}

fn deviations(prediction: bool) -> Vec<Deviation> {
    let mut v = vec![
        Deviation {
            what: "scene geometry (discs, start, goal)",
            path: None,
            ours: "assets/scenarios/T-fig4-*.json, T-tab4-1.json, drawn from the figures",
            paper: "drawn, not given",
        },
        Deviation {
            what: "attraction / repulsion gains and repulsion range",
            path: Some("apf.config.k_r"),
            ours: "the ApfConfig defaults",
            paper: "not given",
        },
        Deviation {
            what: "a spike: a path point turning by more than",
            path: None,
            ours: "30°",
            paper: "not defined",
        },
    ];
    if prediction {
        v.push(Deviation {
            what: "time step between the predicted positions t+1, t+2",
            path: Some("apf.config.predict_dt"),
            ours: "0.8 s in these presets (the config default is 0.5 s)",
            paper: "not given",
        });
    }
    v
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
            clauses: vec![
                outcome(
                    "sampling reaches",
                    "the sampling APF escapes the local minimum and reaches the goal",
                    |r| ok(r, "sampling"),
                ),
                effect(
                    "basic stuck",
                    "basic APF is caught in the local minimum (stuck before the disc)",
                    |r| r.get("apf").is_some_and(|m| m.outcome == Outcome::Stuck),
                    None,
                ),
            ],
            family: family_2d(),
            deviations: deviations(false),
            figures: None,
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
            clauses: vec![
                outcome(
                    "with the rule reaches",
                    "with the relative distance rule the sampling APF reaches the goal",
                    |r| ok(r, "sampling+rule"),
                ),
                effect(
                    "basic stalls",
                    "basic APF does not reach the goal (goal unreachable near the obstacle)",
                    |r| !reached(r, "apf"),
                    None,
                ),
                effect(
                    "no rule stalls",
                    "the sampling APF without the rule does not reach it either",
                    |r| !reached(r, "sampling-no-rule"),
                    None,
                ),
            ],
            family: family_2d(),
            deviations: deviations(false),
            figures: None,
        },
        PathExperiment {
            id: "T-fig4-10",
            paper: "[T] Wu 2022, Fig 4-10 (fails / 0.96 m / 0.84 m)",
            what: "a disc moving head-on along the robot's line",
            relation: "basic APF does not reach the goal; the sampling APF does; with \
                       prediction the path is shorter",
            runs: three(FIG4_10),
            clauses: vec![
                outcome(
                    "improved reach",
                    "the sampling APF reaches, with and without prediction",
                    |r| ok(r, "sampling") && ok(r, "sampling+prediction"),
                ),
                effect(
                    "basic fails",
                    "basic APF does not reach the goal",
                    |r| !reached(r, "apf"),
                    None,
                ),
                effect(
                    "prediction shorter",
                    "with prediction the path is shorter (paper 0.84 vs 0.96 m)",
                    |r| {
                        ok(r, "sampling")
                            && ok(r, "sampling+prediction")
                            && length(r, "sampling+prediction") < length(r, "sampling")
                    },
                    diff("path prediction − sampling", "m", |r| {
                        (ok(r, "sampling") && ok(r, "sampling+prediction"))
                            .then(|| length(r, "sampling+prediction") - length(r, "sampling"))
                    }),
                ),
            ],
            family: family_2d(),
            deviations: deviations(true),
            figures: None,
        },
        PathExperiment {
            id: "T-fig4-11",
            paper: "[T] Wu 2022, Fig 4-11 (0.870 / 0.840 / 0.809 m)",
            what: "the mover's line offset 0.04 m from the robot's",
            relation: "all reach; path length basic > sampling > sampling+prediction; the \
                       basic path has the most spikes",
            runs: three(FIG4_11),
            clauses: vec![
                outcome(
                    "all reach",
                    "all three reach the goal without collision",
                    all_ok,
                ),
                lengths_fall(),
                effect(
                    "basic most spikes",
                    "the basic path has the most spikes",
                    |r| {
                        spikes(r, "apf") > spikes(r, "sampling")
                            && spikes(r, "apf") > spikes(r, "sampling+prediction")
                    },
                    None,
                ),
            ],
            family: family_2d(),
            deviations: deviations(true),
            figures: None,
        },
        PathExperiment {
            id: "T-fig4-12",
            paper: "[T] Wu 2022, Fig 4-12 (0.659 / 0.690 / 0.690 m)",
            what: "the mover's line offset 0.1 m: little overlap",
            relation: "all reach; the improvement is not evident: both improved paths are at \
                       least as long as the basic one (within 10 %)",
            runs: three(FIG4_12),
            clauses: vec![
                outcome(
                    "all reach",
                    "all three reach the goal without collision",
                    all_ok,
                ),
                effect(
                    "no gain",
                    "both improved paths are at least as long as the basic one, within 10 %",
                    |r| {
                        all_ok(r)
                            && ["sampling", "sampling+prediction"].iter().all(|n| {
                                length(r, n) >= length(r, "apf")
                                    && length(r, n) <= 1.1 * length(r, "apf")
                            })
                    },
                    diff("path prediction − basic", "m", |r| {
                        all_ok(r).then(|| length(r, "sampling+prediction") - length(r, "apf"))
                    }),
                ),
            ],
            family: family_2d(),
            deviations: deviations(true),
            figures: None,
        },
        PathExperiment {
            id: "T-tab4-1",
            paper: "[T] Wu 2022, Table 4-1 (1.018 / 0.816 / 0.768 m; spikes 4 / 1 / 0)",
            what: "3D: the end effector crosses the table while a hand (sphere) reaches \
                   toward it head-on, 0.04 m below its line",
            relation: "all reach; path length basic > sampling > sampling+prediction; spikes \
                       fall: basic > sampling > sampling+prediction = 0",
            runs: three(TAB4_1),
            clauses: vec![
                outcome(
                    "all reach",
                    "all three reach the goal without collision",
                    all_ok,
                ),
                lengths_fall(),
                effect(
                    "spikes fall to 0",
                    "spikes basic > sampling > sampling+prediction = 0",
                    |r| {
                        spikes(r, "apf") > spikes(r, "sampling")
                            && spikes(r, "sampling") > spikes(r, "sampling+prediction")
                            && spikes(r, "sampling+prediction") == 0
                    },
                    None,
                ),
            ],
            family: family_3d(),
            deviations: deviations(true),
            figures: None,
        },
    ]
}
