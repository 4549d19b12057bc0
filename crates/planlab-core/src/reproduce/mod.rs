//! The papers' experiments (SPEC §7): presets, runs and the relation each
//! must show, for `planlab reproduce`, the native tests and the page's
//! gallery.
//!
//! An [`Experiment`] is a few named runs of embedded scenario presets
//! (`assets/scenarios/*.json`, inline maps, compiled in with `include_str!`
//! so the binary and the wasm module need no files), each possibly with a
//! different planner and `--set`-style overrides, and a predicate over their
//! [`EpisodeMetrics`] that states the paper's relation. The experiments of
//! each paper live in their own file: [`t_dwa`] (Wu 2022 ch. 3), [`s_dual`]
//! (Ge & Li 2022), [`c_clean`] (Zhang et al. 2020), [`l_lidar`] (Chang et
//! al. 2024). Path experiments ([`PathExperiment`], APF metrics) are in
//! [`t_apf`] (Wu 2022 ch. 4) and [`t_arm`] (the arm of Wu 2022 ch. 5).

pub mod c_clean;
pub mod l_lidar;
pub mod s_dual;
pub mod t_apf;
pub mod t_arm;
pub mod t_dwa;

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::apf::{AnyApfRun, ApfMetrics};
use crate::map::io::scenario::{set_json_path, set_planner_name, Scenario, ScenarioError};
use crate::metrics::{EpisodeMetrics, DEFAULT_LOAD_THRESHOLD_N};
use crate::sim::{Episode, SimError};

/// One run of an experiment.
#[derive(Debug, Clone, PartialEq)]
pub struct RunSpec {
    /// Name of the run in the results (e.g. `baseline`, `improved`).
    pub name: &'static str,
    /// The scenario JSON (an `include_str!` of a preset; inline map).
    pub scenario_json: &'static str,
    /// Local planner replacing the scenario's (config reset to `{}` when
    /// the name differs), as `planlab run --planner`.
    pub planner: Option<&'static str>,
    /// `(dotted.path, value)` edits applied before parsing, as
    /// `planlab run --set path=value` (value parsed as JSON, else a string).
    pub set: Vec<(&'static str, &'static str)>,
}

/// A paper's experiment and the relation it must show.
#[derive(Debug, Clone)]
pub struct Experiment {
    /// Stable id, e.g. `T-fig3-2`.
    pub id: &'static str,
    /// Paper and figure / table, e.g. `\[T\] Wu 2022, Fig 3-2`.
    pub paper: &'static str,
    /// What the scene is.
    pub what: &'static str,
    /// The relation in words (what [`Experiment::holds`] checks).
    pub relation: &'static str,
    /// The runs, each reported under its name.
    pub runs: Vec<RunSpec>,
    /// Whether the relation holds for the runs' metrics (keyed by run name).
    pub holds: fn(&BTreeMap<String, EpisodeMetrics>) -> bool,
}

/// The result of one experiment: `planlab reproduce --json` prints one per
/// line, in this field order.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ExperimentResult {
    /// [`Experiment::id`].
    pub id: String,
    /// [`Experiment::paper`].
    pub paper: String,
    /// [`Experiment::what`].
    pub what: String,
    /// Metrics of every run by name.
    pub runs: BTreeMap<String, EpisodeMetrics>,
    /// [`Experiment::relation`].
    pub relation: String,
    /// Whether it holds.
    pub holds: bool,
    /// Figures beyond the runs' metrics (e.g. the node counts of `S-fig6`),
    /// by name; left out of the JSON when there are none.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub figures: BTreeMap<String, f64>,
}

/// Every experiment, in a fixed order (\[T\], \[S\], \[C\], \[L\]).
pub fn all() -> Vec<Experiment> {
    let mut v = t_dwa::experiments();
    v.extend(s_dual::experiments());
    v.extend(c_clean::experiments());
    v.extend(l_lidar::experiments());
    v
}

/// The experiment with this id.
pub fn find(id: &str) -> Option<Experiment> {
    all().into_iter().find(|e| e.id == id)
}

/// The scenario of a run: the preset with the planner and overrides applied.
pub fn scenario_of(spec: &RunSpec) -> Result<Scenario, SimError> {
    let mut tree: serde_json::Value = serde_json::from_str(spec.scenario_json)
        .map_err(|e| SimError::Scenario(ScenarioError::from(e)))?;
    if let Some(p) = spec.planner {
        set_planner_name(&mut tree, p)?;
    }
    for (path, value) in &spec.set {
        set_json_path(&mut tree, path, value)?;
    }
    Ok(Scenario::from_value(&tree)?)
}

/// Builds and runs one run to its end; returns the finished episode (for
/// its trace) and its metrics. The tracking error is measured against the
/// planner's global path, wheel loads against 40 N.
pub fn run_spec(spec: &RunSpec) -> Result<(Episode, EpisodeMetrics), SimError> {
    let scenario = scenario_of(spec)?;
    let grid = scenario.inline_grid()?.ok_or_else(|| {
        SimError::Scenario(ScenarioError::Invalid(format!(
            "run `{}`: an embedded preset needs an inline map, not a file reference",
            spec.name
        )))
    })?;
    let mut ep = Episode::from_scenario(&scenario, grid)?;
    let outcome = ep.run();
    let m = EpisodeMetrics::from_trace(
        ep.trace(),
        &ep.planner_debug().global_path,
        outcome,
        DEFAULT_LOAD_THRESHOLD_N,
    );
    Ok((ep, m))
}

/// Runs every run of `exp` and checks its relation.
pub fn run(exp: &Experiment) -> Result<ExperimentResult, SimError> {
    let mut runs = BTreeMap::new();
    for spec in &exp.runs {
        let (_, m) = run_spec(spec)?;
        runs.insert(spec.name.to_string(), m);
    }
    Ok(ExperimentResult {
        id: exp.id.to_string(),
        paper: exp.paper.to_string(),
        what: exp.what.to_string(),
        holds: (exp.holds)(&runs),
        runs,
        relation: exp.relation.to_string(),
        figures: s_dual::figures(exp.id)?,
    })
}

/// A paper's experiment over kinematic path runs (potential fields; \[T\]
/// ch. 4–5): like [`Experiment`], with [`ApfMetrics`] per run. Each run's
/// scenario has an `apf` section; variants are chosen with `set` (e.g.
/// `("apf.config.mode", "basic")`).
#[derive(Debug, Clone)]
pub struct PathExperiment {
    /// Stable id, e.g. `T-fig4-6`.
    pub id: &'static str,
    /// Paper and figure / table.
    pub paper: &'static str,
    /// What the scene is.
    pub what: &'static str,
    /// The relation in words (what [`PathExperiment::holds`] checks).
    pub relation: &'static str,
    /// The runs, each reported under its name.
    pub runs: Vec<RunSpec>,
    /// Whether the relation holds for the runs' metrics.
    pub holds: fn(&BTreeMap<String, ApfMetrics>) -> bool,
}

/// The result of one [`PathExperiment`]; the same JSON shape as
/// [`ExperimentResult`], with [`ApfMetrics`] per run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PathExperimentResult {
    /// [`PathExperiment::id`].
    pub id: String,
    /// [`PathExperiment::paper`].
    pub paper: String,
    /// [`PathExperiment::what`].
    pub what: String,
    /// Metrics of every run by name.
    pub runs: BTreeMap<String, ApfMetrics>,
    /// [`PathExperiment::relation`].
    pub relation: String,
    /// Whether it holds.
    pub holds: bool,
}

/// Every path experiment, in a fixed order.
pub fn path_experiments() -> Vec<PathExperiment> {
    let mut v = t_apf::experiments();
    v.extend(t_arm::experiments());
    v
}

/// The path experiment with this id.
pub fn find_path(id: &str) -> Option<PathExperiment> {
    path_experiments().into_iter().find(|e| e.id == id)
}

/// Builds the APF run of a scenario with an `apf` section (2D start / goal
/// default to the scenario's world points).
pub fn apf_run_of(
    scenario: &Scenario,
    grid: &crate::map::OccupancyGrid,
) -> Result<AnyApfRun, SimError> {
    let apf = scenario.apf.as_ref().ok_or_else(|| {
        SimError::Scenario(ScenarioError::Invalid(
            "the scenario has no `apf` section".into(),
        ))
    })?;
    let s = scenario.start_world(grid);
    let g = scenario.goal_world(grid);
    AnyApfRun::new(apf, &s, &g).map_err(|e| SimError::InvalidConfig(e.to_string()))
}

/// Runs one path run to its end: its metrics. An arm scenario (an `arm`
/// section) runs the arm episode, with `planner` naming its predictor.
pub fn run_path_spec(spec: &RunSpec) -> Result<ApfMetrics, SimError> {
    if let Ok(tree) = serde_json::from_str::<serde_json::Value>(spec.scenario_json) {
        if crate::arm::ArmScenario::is_arm(&tree) {
            return run_arm_spec(spec, tree);
        }
    }
    let scenario = scenario_of(spec)?;
    let grid = scenario.inline_grid()?.ok_or_else(|| {
        SimError::Scenario(ScenarioError::Invalid(format!(
            "run `{}`: an embedded preset needs an inline map",
            spec.name
        )))
    })?;
    apf_run_of(&scenario, &grid)?
        .run()
        .map_err(|e| SimError::InvalidConfig(e.to_string()))
}

/// An arm run: `set` edits, then the predictor named by `planner`.
fn run_arm_spec(spec: &RunSpec, mut tree: serde_json::Value) -> Result<ApfMetrics, SimError> {
    use crate::arm::{ArmEpisode, ArmPredictor, ArmScenario};
    for (path, value) in &spec.set {
        set_json_path(&mut tree, path, value)?;
    }
    let arm =
        |e: crate::arm::ArmError| SimError::InvalidConfig(format!("run `{}`: {e}", spec.name));
    let mut s = ArmScenario::from_value(&tree).map_err(arm)?;
    if let Some(p) = spec.planner {
        ArmPredictor::parse(p).map_err(arm)?.apply(&mut s.arm.apf);
    }
    let mut ep = ArmEpisode::from_scenario(&s).map_err(arm)?;
    ep.run().map_err(arm)?;
    Ok(ep.metrics())
}

/// Runs every run of `exp` and checks its relation.
pub fn run_path(exp: &PathExperiment) -> Result<PathExperimentResult, SimError> {
    let mut runs = BTreeMap::new();
    for spec in &exp.runs {
        runs.insert(spec.name.to_string(), run_path_spec(spec)?);
    }
    Ok(PathExperimentResult {
        id: exp.id.to_string(),
        paper: exp.paper.to_string(),
        what: exp.what.to_string(),
        holds: (exp.holds)(&runs),
        runs,
        relation: exp.relation.to_string(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::Outcome;

    const DEMO: &str = include_str!("../../../../assets/scenarios/pursuit-demo.json");

    fn demo_experiment() -> Experiment {
        Experiment {
            id: "X-demo",
            paper: "none",
            what: "pursuit in the demo room, fast and slow",
            relation: "the faster robot arrives sooner over the same path",
            runs: vec![
                RunSpec {
                    name: "fast",
                    scenario_json: DEMO,
                    planner: Some("pursuit"),
                    set: vec![],
                },
                RunSpec {
                    name: "slow",
                    scenario_json: DEMO,
                    planner: None,
                    set: vec![("robot.limits.v_max", "0.5"), ("seed", "9")],
                },
            ],
            holds: |r| {
                let (f, s) = (&r["fast"], &r["slow"]);
                f.outcome == Outcome::Reached
                    && s.outcome == Outcome::Reached
                    && f.time_s < s.time_s
                    && (f.path_length_m - s.path_length_m).abs() < 0.5
            },
        }
    }

    #[test]
    fn an_experiment_runs_and_reports_its_relation() {
        let r = run(&demo_experiment()).unwrap();
        assert!(r.holds, "{r:?}");
        let line = serde_json::to_string(&r).unwrap();
        let keys: Vec<usize> = [
            "\"id\"",
            "\"paper\"",
            "\"what\"",
            "\"runs\"",
            "\"relation\"",
            "\"holds\"",
        ]
        .iter()
        .map(|k| line.find(k).unwrap())
        .collect();
        assert!(keys.windows(2).all(|w| w[0] < w[1]), "{line}");
        assert!(line.contains("\"time_s\"") && line.contains("\"load_ok_share\":null"));
    }

    #[test]
    fn overrides_reach_the_scenario_and_errors_name_the_path() {
        let mut e = demo_experiment();
        e.runs[1].set = vec![("sim.dt", "-1")];
        assert!(run(&e).unwrap_err().to_string().contains("sim.dt"));
        e.runs[1].set = vec![("movers.3.radius", "1")];
        assert!(run(&e).unwrap_err().to_string().contains("no index 3"));
        e.runs[1].set = vec![];
        e.runs[1].planner = Some("warp");
        assert!(run(&e).unwrap_err().to_string().contains("warp"));
    }

    #[test]
    fn every_registered_experiment_is_well_formed() {
        let all = all();
        for e in &all {
            assert!(!e.runs.is_empty(), "{}", e.id);
            assert_eq!(all.iter().filter(|f| f.id == e.id).count(), 1, "{}", e.id);
            for r in &e.runs {
                scenario_of(r).unwrap_or_else(|err| panic!("{} / {}: {err}", e.id, r.name));
            }
        }
    }
}
