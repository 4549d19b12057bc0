//! Experiments of \[S\] Ge & Li 2022 (safe A* + dual-velocity DWA): ids
//! `S-fig6`, `S-tab1`, `S-fig12`.
//!
//! The presets (`assets/scenarios/S-*.json`, made by
//! `scripts/gen_dwa_scenarios.py`) put the paper's kind of grid map (two
//! long walls that make the path an S, two blocks in the open) at 0.05 m for
//! Fig 6 and as a coarse 0.5 m grid, like the paper's, for Table 1 and
//! Fig 12. The runs compare `safe-dual-dwa` with the `preliminary-fusion`
//! baseline, each with its default config (\[S\] §5 parameters).

use std::collections::BTreeMap;

use super::clause::{diff, effect, ok, outcome, ratio};
use super::{Deviation, Experiment, Family, Perturbation, RunSpec, Runs};
use crate::global::plan::plan_on_map;
use crate::global::{Diagonal, GridPos};
use crate::local::dual::{grid_options, DualConfig, DualVariant};
use crate::metrics::EpisodeMetrics;
use crate::scenario::{Scenario, ScenarioError};
use crate::sim::SimError;
use crate::world::StaticMap;

const FIG6: &str = include_str!("../../../../assets/scenarios/S-fig6.json");
const TAB1: &str = include_str!("../../../../assets/scenarios/S-tab1.json");
const FIG12: &str = include_str!("../../../../assets/scenarios/S-fig12.json");

/// S-fig6: Bottom-Up keeps at most this share of the safe A\* nodes
/// (\[S\] Fig 6: 7 of 80 = 8.75 %, "far fewer than 10 %").
pub const FIG6_MAX_SHARE: f64 = 0.1;

/// S-tab1: the path lengths differ by at most this share ("almost no
/// change", \[S\] §5).
pub const TAB1_LENGTH_TOLERANCE: f64 = 0.1;

/// S-tab1: the dual-velocity run takes at most this share of the
/// preliminary fusion's time (paper: 108.85 / 202.24 = 0.54).
pub const TAB1_MAX_TIME_RATIO: f64 = 0.8;

/// S-fig12: the run among movers drives at most this multiple of the path
/// without movers.
pub const FIG12_MAX_DETOUR: f64 = 1.25;

/// Node counts of the safe A\* path and its Bottom-Up feature nodes on a
/// preset, as `safe-dual-dwa` plans them with its default config: (path
/// nodes, feature nodes, every feature segment free on the inflated map).
pub fn feature_nodes(scenario_json: &str) -> Result<(usize, usize, bool), SimError> {
    feature_nodes_of(&Scenario::from_json(scenario_json)?)
}

/// [`feature_nodes`] of a parsed scenario.
pub fn feature_nodes_of(sc: &Scenario) -> Result<(usize, usize, bool), SimError> {
    let grid = sc.inline_grid()?.ok_or_else(|| {
        SimError::Scenario(ScenarioError::Invalid(
            "the [S] presets have inline maps".into(),
        ))
    })?;
    let robot = sc.robot.unwrap_or_default();
    let map = StaticMap::new(grid.clone(), true).map_err(SimError::from)?;
    let opts = grid_options(
        &DualConfig::default(),
        robot.footprint.circumscribed_radius(),
        DualVariant::SafeDual,
        &map,
    );
    let cell = |p: [f64; 2]| {
        grid.world_to_cell(p[0], p[1])
            .map(|(c, r)| GridPos::new(c as u32, r as u32))
    };
    let (Some(s), Some(g)) = (cell(sc.start_world(&grid)), cell(sc.goal_world(&grid))) else {
        return Err(SimError::Scenario(ScenarioError::Invalid(
            "start or goal off the map".into(),
        )));
    };
    let plan = plan_on_map(&grid, s, g, &opts)
        .map_err(|e| SimError::Scenario(ScenarioError::Invalid(e.to_string())))?;
    let inflated = crate::global::plan::plan_grid_for(&grid, &opts)
        .map_err(|e| SimError::Scenario(ScenarioError::Invalid(e.to_string())))?;
    let free = plan
        .feature_nodes
        .windows(2)
        .all(|w| inflated.segment_is_free(w[0], w[1], Diagonal::NoCornerCutting));
    Ok((plan.path.cells.len(), plan.feature_nodes.len(), free))
}

/// Node counts of a variant's scene (figures `safe_astar_nodes`,
/// `feature_nodes`, `feature_share`, `feature_path_free`).
pub fn figures_of(tree: &serde_json::Value) -> Result<BTreeMap<String, f64>, SimError> {
    let (n, k, free) = feature_nodes_of(&Scenario::from_value(tree)?)?;
    Ok(BTreeMap::from([
        ("safe_astar_nodes".to_string(), n as f64),
        ("feature_nodes".to_string(), k as f64),
        ("feature_share".to_string(), k as f64 / n.max(1) as f64),
        (
            "feature_path_free".to_string(),
            if free { 1.0 } else { 0.0 },
        ),
    ]))
}

fn run(name: &'static str, json: &'static str, planner: &'static str) -> RunSpec {
    RunSpec {
        name,
        scenario_json: json,
        planner: Some(planner),
        set: vec![],
    }
}

type R = Runs<EpisodeMetrics>;

/// Start and goal moved up to 0.2 m, movers up to 0.3 m and ±20 % speed,
/// free-standing blocks up to `cells`, a new seed.
fn family(cells: u32) -> Family {
    Family {
        perturbations: vec![
            Perturbation::start(0.2)
                .because("up to 0.2 m, the robot's radius: the same start area of the [S] map"),
            Perturbation::goal(0.2).because("up to 0.2 m: the same goal area of the [S] map"),
            Perturbation::Movers {
                radius_m: 0.3,
                speed_rel: 0.2,
            }
            .because(
                "the pacing discs' paths shifted up to 0.3 m (their radius) and speeds ±20 %: \
                 they still pace across the path",
            ),
            Perturbation::Blocks { cells }.because(
                "free-standing obstacles moved by whole cells (none on the maps whose corridors \
                 are the scene): the same layout, not the same pixels",
            ),
            Perturbation::Seed.because("another noise seed: the scene itself is unchanged"),
        ],
    }
}

fn deviations() -> Vec<Deviation> {
    vec![
        Deviation {
            what: "scene geometry (the paper draws its grid map)",
            path: None,
            ours: "assets/scenarios/S-*.json, drawn to resemble Fig 6/10/12",
            paper: "not given",
        },
        Deviation {
            what: "turn-rate limit and turn acceleration",
            path: Some("robot.limits.w_max"),
            ours: "20 °/s (0.349 rad/s) and 50 °/s² (0.873 rad/s²), the MATLAB DWA sample's",
            paper: "20 rad/s and 50 rad/s² (§5)",
        },
        Deviation {
            what: "smallest previous speed the dual velocity model holds",
            path: Some("local_planner.config.hold_min_speed"),
            ours: "0.3 m/s",
            paper: "not given",
        },
        Deviation {
            what: "radius within which the next temporary goal is taken",
            path: Some("local_planner.config.switch_radius"),
            ours: "0.5 m",
            paper: "not given",
        },
        Deviation {
            what: "safe A* inflation beyond the footprint",
            path: Some("local_planner.config.inflate_margin"),
            ours: "0.1 m",
            paper: "not given",
        },
        Deviation {
            what: "rollout horizon",
            path: Some("local_planner.config.dwa.predict_time"),
            ours: "3.0 s",
            paper: "not given",
        },
        Deviation {
            what: "\"much shorter time\" (Table 1), as a bound",
            path: None,
            ours: "≤ 0.8 × the preliminary fusion's time",
            paper: "202.24 → 108.85 s (0.54)",
        },
        Deviation {
            what: "\"almost no change\" of path length, as a bound",
            path: None,
            ours: "within 10 %",
            paper: "not quantified",
        },
        Deviation {
            what: "\"no looping after detours\" (Fig 12), as bounds",
            path: None,
            ours: "path ≤ 1.25 × and total turning ≤ π more than without movers",
            paper: "not quantified",
        },
    ]
}

/// Both runs' metrics when both succeeded.
fn pair<'a>(r: &'a R, a: &str, b: &str) -> Option<(&'a EpisodeMetrics, &'a EpisodeMetrics)> {
    (ok(r, a) && ok(r, b))
        .then(|| Some((r.get(a)?, r.get(b)?)))
        .flatten()
}

/// The \[S\] experiments.
pub fn experiments() -> Vec<Experiment> {
    vec![
        Experiment {
            id: "S-fig6",
            paper: "[S] Ge & Li 2022, Fig 6 (80 → 7 nodes)",
            what: "the [S] map at 0.05 m: safe A* path, Bottom-Up feature nodes as \
                   temporary goals",
            relation: "Bottom-Up keeps under 10 % of the safe A* nodes (paper 7 of 80), every \
                       feature segment is free on the inflated map, and safe-dual-dwa reaches \
                       the goal along them without touching anything",
            runs: vec![run("safe-dual-dwa", FIG6, "safe-dual-dwa")],
            clauses: vec![
                effect(
                    "few feature nodes",
                    "Bottom-Up keeps far fewer than 10 % of the safe A* path's nodes",
                    |r| {
                        r.figure("safe_astar_nodes").is_some_and(|n| n > 0.0)
                            && r.figure("feature_share")
                                .is_some_and(|s| s <= FIG6_MAX_SHARE)
                    },
                    ratio("feature nodes / safe A* nodes", |r| {
                        r.figure("feature_share")
                    }),
                ),
                outcome(
                    "segments free",
                    "every segment between feature nodes is free on the inflated map",
                    |r| r.figure("feature_path_free") == Some(1.0),
                ),
                outcome(
                    "reaches",
                    "safe-dual-dwa reaches the goal along them without collision",
                    |r| ok(r, "safe-dual-dwa"),
                ),
            ],
            family: family(2),
            deviations: deviations(),
            figures: Some(figures_of),
            scene: None,
        },
        Experiment {
            id: "S-tab1",
            paper: "[S] Ge & Li 2022, Table 1 / Fig 10–11 (202.24 s → 108.85 s)",
            what: "the [S] map as a 0.5 m grid, no movers: preliminary fusion (every \
                   safe A* node a temporary goal) vs dual-velocity DWA (feature nodes, \
                   speed held near them)",
            relation: "both reach the goal without collision; path lengths almost equal \
                       (within 10 %); the dual-velocity run takes much less time (≤ 0.8 × \
                       the preliminary fusion's; paper 0.54) with fewer speed drops",
            runs: vec![
                run("preliminary", TAB1, "preliminary-fusion"),
                run("dual", TAB1, "safe-dual-dwa"),
            ],
            clauses: tab1_clauses(),
            family: family(0),
            deviations: deviations(),
            figures: Some(figures_of),
            scene: None,
        },
        Experiment {
            id: "S-fig12",
            paper: "[S] Ge & Li 2022, Fig 12–13",
            what: "the S-tab1 map with three discs pacing back and forth across the path \
                   (0.3 m/s); the same run without them for reference",
            relation: "safe-dual-dwa avoids the three movers and reaches the goal; no \
                       looping after the detours: path ≤ 1.25 × and total turning ≤ π more \
                       than without movers (a loop adds 2π)",
            runs: vec![
                run("dual", FIG12, "safe-dual-dwa"),
                RunSpec {
                    name: "dual-no-movers",
                    scenario_json: FIG12,
                    planner: Some("safe-dual-dwa"),
                    set: vec![("movers", "[]")],
                },
                run("preliminary", FIG12, "preliminary-fusion"),
            ],
            clauses: vec![
                outcome(
                    "avoids and reaches",
                    "safe-dual-dwa avoids the movers and reaches the goal",
                    |r| ok(r, "dual"),
                ),
                effect(
                    "no looping",
                    "no looping after the detours: path ≤ 1.25 × and total turning ≤ π \
                     more than the same run without movers",
                    fig12_holds,
                    diff("total turning dual − dual without movers", "rad", |r| {
                        pair(r, "dual", "dual-no-movers")
                            .map(|(d, s)| d.total_turn_rad - s.total_turn_rad)
                    }),
                ),
            ],
            family: family(0),
            deviations: deviations(),
            figures: None,
            scene: None,
        },
    ]
}

fn tab1_clauses() -> Vec<super::Clause<EpisodeMetrics>> {
    vec![
        outcome("both reach", "both reach the goal without collision", |r| {
            ok(r, "dual") && ok(r, "preliminary")
        }),
        effect(
            "equal length",
            "the path lengths are almost equal (within 10 %)",
            |r| {
                pair(r, "dual", "preliminary").is_some_and(|(d, p)| {
                    (d.path_length_m - p.path_length_m).abs()
                        <= TAB1_LENGTH_TOLERANCE * p.path_length_m
                })
            },
            ratio("path dual / preliminary", |r| {
                pair(r, "dual", "preliminary").map(|(d, p)| d.path_length_m / p.path_length_m)
            }),
        ),
        effect(
            "much faster",
            "the dual-velocity run takes at most 0.8 × the preliminary fusion's time",
            |r| {
                pair(r, "dual", "preliminary")
                    .is_some_and(|(d, p)| d.time_s <= TAB1_MAX_TIME_RATIO * p.time_s)
            },
            ratio("time dual / preliminary", |r| {
                pair(r, "dual", "preliminary").map(|(d, p)| d.time_s / p.time_s)
            }),
        ),
        effect(
            "fewer speed drops",
            "the dual-velocity run has fewer speed drops",
            |r| pair(r, "dual", "preliminary").is_some_and(|(d, p)| d.speed_drops < p.speed_drops),
            diff("speed drops dual − preliminary", "1", |r| {
                pair(r, "dual", "preliminary")
                    .map(|(d, p)| f64::from(d.speed_drops) - f64::from(p.speed_drops))
            }),
        ),
    ]
}

/// The S-fig12 no-looping clause.
pub fn fig12_holds(r: &R) -> bool {
    pair(r, "dual", "dual-no-movers").is_some_and(|(d, s)| {
        d.path_length_m <= FIG12_MAX_DETOUR * s.path_length_m
            && d.total_turn_rad <= s.total_turn_rad + std::f64::consts::PI
    })
}
