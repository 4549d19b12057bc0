//! `planlab run` of an arm scenario (a JSON file with an `arm` section):
//! the 7-DOF arm's end effector among the moving hand, \[T\] §5.3.3. The
//! scenario is read, edited and run by `sim_cmds::run`; this is its report.

use planlab_core::arm::{ArmEpisode, ArmMetrics, ArmPredictor};
use planlab_core::scenario::AnyScenario;
use serde::Serialize;

use crate::sim_cmds::RunArgs;

/// What `planlab run --json` prints for an arm scenario.
#[derive(Serialize)]
struct ArmRunReport<'a> {
    scenario: &'a str,
    planner: String,
    seed: u64,
    /// FNV-1a of the tool path, hex (what `planlab reproduce` reports).
    trace_hash: String,
    #[serde(flatten)]
    metrics: &'a ArmMetrics,
}

/// The report of a finished arm episode of `scenario`: the predictor in
/// force as the planner, the seed, the metrics; `--trace` writes the tool's
/// path as CSV.
pub fn report(
    title: &str,
    scenario: &AnyScenario,
    ep: &ArmEpisode,
    m: &ArmMetrics,
    hash: u64,
    args: &RunArgs<'_>,
) -> Result<(), String> {
    if let Some(t) = args.trace {
        let path = ep.tool_path().iter().map(|p| [p.x, p.y, p.z]);
        crate::sim_cmds::write_path_csv(t, path)?;
    }
    let report = ArmRunReport {
        scenario: scenario.name(),
        planner: format!("arm-apf:{}", ArmPredictor::of(&ep.scene().apf).name()),
        seed: scenario.seed(),
        trace_hash: format!("{hash:016x}"),
        metrics: m,
    };
    if args.json {
        outln!(
            "{}",
            serde_json::to_string(&report).map_err(|e| e.to_string())?
        );
    } else {
        outln!("{title} — {}, seed {}", report.planner, report.seed);
        out!("{}", crate::sim_cmds::apf_metrics_table(m));
    }
    Ok(())
}
