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

use super::{Experiment, RunSpec};
use crate::global::plan::plan_on_map;
use crate::global::{Diagonal, GridPos};
use crate::local::dual::{grid_options, DualConfig, DualVariant};
use crate::map::io::scenario::{Scenario, ScenarioError};
use crate::metrics::EpisodeMetrics;
use crate::sim::{Outcome, SimError};
use crate::world::StaticMap;

const FIG6: &str = include_str!("../../../../assets/scenarios/S-fig6.json");
const TAB1: &str = include_str!("../../../../assets/scenarios/S-tab1.json");
const FIG12: &str = include_str!("../../../../assets/scenarios/S-fig12.json");

/// S-fig6: Bottom-Up keeps at most this share of the safe A\* nodes
/// (\[S\] Fig 6: 7 of 80 = 8.75 %; SPEC: "≪ 10 %").
pub const FIG6_MAX_SHARE: f64 = 0.05;

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
    let sc = Scenario::from_json(scenario_json)?;
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
    let plan = plan_on_map(&grid, s, g, &opts, false)
        .map_err(|e| SimError::Scenario(ScenarioError::Invalid(e.to_string())))?;
    let inflated = crate::global::plan::plan_grid_for(&grid, &opts)
        .map_err(|e| SimError::Scenario(ScenarioError::Invalid(e.to_string())))?;
    let free = plan
        .feature_nodes
        .windows(2)
        .all(|w| inflated.segment_is_free(w[0], w[1], Diagonal::NoCornerCutting));
    Ok((plan.path.cells.len(), plan.feature_nodes.len(), free))
}

/// Figures beyond the runs' metrics, printed by `planlab reproduce`: the
/// node counts of `S-fig6` (and of the coarse map of `S-tab1`).
pub fn figures(id: &str) -> Result<BTreeMap<String, f64>, SimError> {
    let json = match id {
        "S-fig6" => FIG6,
        "S-tab1" => TAB1,
        _ => return Ok(BTreeMap::new()),
    };
    let (n, k, free) = feature_nodes(json)?;
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

/// Reached the goal without touching anything.
fn clean(m: Option<&EpisodeMetrics>) -> bool {
    m.is_some_and(|m| m.outcome == Outcome::Reached && m.min_clearance_m > 0.0)
}

/// The S-fig6 relation.
fn fig6_holds(r: &BTreeMap<String, EpisodeMetrics>) -> bool {
    clean(r.get("safe-dual-dwa"))
        && matches!(feature_nodes(FIG6), Ok((n, k, true)) if n > 0 && (k as f64) <= FIG6_MAX_SHARE * n as f64)
}

/// The S-tab1 relation.
pub fn tab1_holds(r: &BTreeMap<String, EpisodeMetrics>) -> bool {
    let (Some(d), Some(p)) = (r.get("dual"), r.get("preliminary")) else {
        return false;
    };
    clean(Some(d))
        && clean(Some(p))
        && (d.path_length_m - p.path_length_m).abs() <= TAB1_LENGTH_TOLERANCE * p.path_length_m
        && d.time_s <= TAB1_MAX_TIME_RATIO * p.time_s
        && d.speed_drops < p.speed_drops
}

/// The S-fig12 relation.
pub fn fig12_holds(r: &BTreeMap<String, EpisodeMetrics>) -> bool {
    let (Some(d), Some(s)) = (r.get("dual"), r.get("dual-no-movers")) else {
        return false;
    };
    clean(Some(d))
        && clean(Some(s))
        && d.path_length_m <= FIG12_MAX_DETOUR * s.path_length_m
        && d.total_turn_rad <= s.total_turn_rad + std::f64::consts::PI
}

/// The \[S\] experiments.
pub fn experiments() -> Vec<Experiment> {
    vec![
        Experiment {
            id: "S-fig6",
            paper: "[S] Ge & Li 2022, Fig 6 (80 → 7 nodes)",
            what: "the [S] map at 0.05 m: safe A* path, Bottom-Up feature nodes as \
                   temporary goals",
            relation: "Bottom-Up keeps at most 5 % of the safe A* nodes (figures: \
                       safe_astar_nodes, feature_nodes), every feature segment is free on \
                       the inflated map, and safe-dual-dwa reaches the goal along them \
                       without touching anything",
            runs: vec![run("safe-dual-dwa", FIG6, "safe-dual-dwa")],
            holds: fig6_holds,
        },
        Experiment {
            id: "S-tab1",
            paper: "[S] Ge & Li 2022, Table 1 / Fig 10–11 (202.24 s → 108.85 s)",
            what: "the [S] map as a 0.5 m grid, no movers: preliminary fusion (every \
                   safe A* node a temporary goal) vs dual-velocity DWA (feature nodes, \
                   speed held near them)",
            relation: "both reach the goal without collision; path lengths within 10 %; \
                       the dual-velocity run takes at most 0.8 × the preliminary fusion's \
                       time (paper 0.54) with fewer speed drops",
            runs: vec![
                run("preliminary", TAB1, "preliminary-fusion"),
                run("dual", TAB1, "safe-dual-dwa"),
            ],
            holds: tab1_holds,
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
            holds: fig12_holds,
        },
    ]
}
