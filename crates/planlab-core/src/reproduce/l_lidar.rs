//! Experiments of \[L\] Chang et al. 2024 (LiDAR heuristic navigation in
//! unknown maps): ids `L-sim1` … `L-sim9` and `L-tab2`.
//!
//! The presets (`assets/scenarios/L-*.json`, made by
//! `scripts/gen_lidar_scenarios.py`) resemble the paper's figures 13–19;
//! the robot is \[L\] Table 1's. `lidar` runs the navigator over DWA
//! (`lidar-dwa`, the preset's config; `lidar-apf` over the basic APF in sims
//! 8–9 as in the paper); the comparison runs use plain DWA (plain APF in
//! sim 8) on
//! the same unknown map — straight to the goal with only the scan's local
//! map and no global path (`scan-dwa` with its default config, the MATLAB
//! DWA sample weights every DWA in planlab starts from).

use std::collections::BTreeMap;

use super::{Experiment, RunSpec};
use crate::metrics::EpisodeMetrics;
use crate::sim::Outcome;

const SIM1: &str = include_str!("../../../../assets/scenarios/L-sim1.json");
const SIM2: &str = include_str!("../../../../assets/scenarios/L-sim2.json");
const SIM3: &str = include_str!("../../../../assets/scenarios/L-sim3.json");
const SIM4: &str = include_str!("../../../../assets/scenarios/L-sim4.json");
const SIM5: &str = include_str!("../../../../assets/scenarios/L-sim5.json");
const SIM6: &str = include_str!("../../../../assets/scenarios/L-sim6.json");
const SIM7: &str = include_str!("../../../../assets/scenarios/L-sim7.json");
const SIM8: &str = include_str!("../../../../assets/scenarios/L-sim8.json");
const SIM9: &str = include_str!("../../../../assets/scenarios/L-sim9.json");

/// At most this many temporary-goal switches in sims 1–4: a few new
/// temporary goals as obstacles come into view, no back and forth.
pub const MAX_SWITCHES: u32 = 8;

/// The comparison scenes: (sim number, preset).
const COMPARED: [(u32, &str); 4] = [(5, SIM5), (6, SIM6), (7, SIM7), (8, SIM8)];

fn lidar(name: &'static str, scenario: &'static str) -> RunSpec {
    RunSpec {
        name,
        scenario_json: scenario,
        planner: None,
        set: vec![],
    }
}

fn plain(name: &'static str, scenario: &'static str) -> RunSpec {
    RunSpec {
        name,
        scenario_json: scenario,
        planner: Some("scan-dwa"),
        set: vec![],
    }
}

/// Plain APF on the scan (the baseline of sim 8, whose navigator runs APF).
fn plain_apf(name: &'static str, scenario: &'static str) -> RunSpec {
    RunSpec {
        name,
        scenario_json: scenario,
        planner: Some("scan-apf"),
        set: vec![],
    }
}

/// Reached the goal without touching anything.
fn reached_safely(m: &EpisodeMetrics) -> bool {
    m.outcome == Outcome::Reached && m.min_clearance_m > 0.0
}

/// Sims 1–4: the navigator reaches safely without chattering.
fn navigates(r: &BTreeMap<String, EpisodeMetrics>) -> bool {
    r.get("lidar")
        .is_some_and(|m| reached_safely(m) && m.temp_goal_switches <= MAX_SWITCHES)
}

/// Sims 5–8: the navigator reaches safely; plain DWA either does not reach,
/// or drives a longer path with more total turning.
pub fn better(ours: Option<&EpisodeMetrics>, plain: Option<&EpisodeMetrics>) -> bool {
    match (ours, plain) {
        (Some(o), Some(p)) => {
            reached_safely(o)
                && (p.outcome != Outcome::Reached
                    || (o.path_length_m < p.path_length_m && o.total_turn_rad < p.total_turn_rad))
        }
        _ => false,
    }
}

fn compared(n: u32, scenario: &'static str) -> Experiment {
    let (id, paper, what) = match n {
        5 => (
            "L-sim5",
            "[L] Chang et al. 2024, sim 5 / Fig 15",
            "a long wall hooked at its upper end across the way",
        ),
        6 => (
            "L-sim6",
            "[L] Chang et al. 2024, sim 6 / Fig 16",
            "scattered rectangular blocks",
        ),
        7 => (
            "L-sim7",
            "[L] Chang et al. 2024, sim 7 / Fig 17",
            "two offset free-standing walls",
        ),
        _ => (
            "L-sim8",
            "[L] Chang et al. 2024, sim 8 / Fig 18",
            "blocks across the way",
        ),
    };
    Experiment {
        id,
        paper,
        what,
        relation: "the navigator (temporary goals over DWA; over APF in sim 8) reaches the goal \
                   without collision; plain DWA (plain APF in sim 8) on the same unknown map \
                   either does not reach it or drives a longer path with more total turning (the \
                   paper's peer is replaced by the plain motion planner)",
        runs: vec![
            lidar("lidar", scenario),
            if n == 8 {
                plain_apf("apf", scenario)
            } else {
                plain("dwa", scenario)
            },
        ],
        holds: |r| better(r.get("lidar"), r.get("dwa").or_else(|| r.get("apf"))),
    }
}

/// The \[L\] experiments.
pub fn experiments() -> Vec<Experiment> {
    let mut v = vec![
        Experiment {
            id: "L-sim1",
            paper: "[L] Chang et al. 2024, sim 1 / Fig 13a",
            what: "goal inside a U open away from the robot; start, U and goal symmetric",
            relation: "the navigator reaches the goal without collision and without target \
                       chattering (the hold period settles the symmetric choice); plain DWA \
                       is shown for contrast",
            runs: vec![lidar("lidar", SIM1), plain("dwa", SIM1)],
            holds: navigates,
        },
        Experiment {
            id: "L-sim2",
            paper: "[L] Chang et al. 2024, sim 2 / Fig 13b",
            what: "goal behind a shallow U open toward the robot; symmetric",
            relation: "the navigator reaches the goal without collision and without target \
                       chattering; plain DWA is shown for contrast",
            runs: vec![lidar("lidar", SIM2), plain("dwa", SIM2)],
            holds: navigates,
        },
        Experiment {
            id: "L-sim3",
            paper: "[L] Chang et al. 2024, sim 3 / Fig 14a",
            what: "start in a bay behind a long wall reaching the map edge; asymmetric",
            relation: "the navigator reaches the goal without collision and without target \
                       chattering; plain DWA is shown for contrast",
            runs: vec![lidar("lidar", SIM3), plain("dwa", SIM3)],
            holds: navigates,
        },
        Experiment {
            id: "L-sim4",
            paper: "[L] Chang et al. 2024, sim 4 / Fig 14b",
            what: "Z-shaped channel whose walls have 0.4 m holes (< robot, < T_gap)",
            relation: "the navigator reaches the goal without collision and without target \
                       chattering; the holes do not attract it",
            runs: vec![lidar("lidar", SIM4)],
            holds: navigates,
        },
    ];
    v.extend(COMPARED.iter().map(|&(n, s)| compared(n, s)));
    v.push(Experiment {
        id: "L-sim9",
        paper: "[L] Chang et al. 2024, sim 9 / Fig 19",
        what: "three moving discs across the way; dynamic settings (d_oe 0.8 m, d_te 1 m, no \
               extra switching conditions)",
        relation: "the navigator reaches the goal without collision",
        runs: vec![lidar("lidar", SIM9)],
        holds: |r| r.get("lidar").is_some_and(reached_safely),
    });
    v.push(Experiment {
        id: "L-tab2",
        paper: "[L] Chang et al. 2024, Table 2 (sims 5–8)",
        what: "path length, total and max turning of sims 5–8, navigator vs plain DWA",
        relation: "in every one of sims 5–8 the navigator reaches the goal and plain DWA does \
                   not, or drives a longer path with more total turning (paper: 14.65 vs \
                   24.32 m, 24.35 vs 28.50, 11.15 vs 13.08, 26.28 vs 25.66; total turning \
                   lower in all four)",
        runs: COMPARED
            .iter()
            .flat_map(|&(n, s)| {
                let (a, b) = match n {
                    5 => ("sim5-lidar", "sim5-dwa"),
                    6 => ("sim6-lidar", "sim6-dwa"),
                    7 => ("sim7-lidar", "sim7-dwa"),
                    _ => ("sim8-lidar", "sim8-apf"),
                };
                [
                    lidar(a, s),
                    if n == 8 { plain_apf(b, s) } else { plain(b, s) },
                ]
            })
            .collect(),
        holds: |r| {
            (5..=8).all(|n| {
                better(
                    r.get(&format!("sim{n}-lidar")),
                    r.get(&format!("sim{n}-dwa"))
                        .or_else(|| r.get(&format!("sim{n}-apf"))),
                )
            })
        },
    });
    v
}
