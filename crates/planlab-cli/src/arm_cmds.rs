//! `planlab run` of an arm scenario (a JSON file with an `arm` section):
//! the 7-DOF arm's end effector among the moving hand, \[T\] §5.3.3. The
//! scenario is read, edited and run by `sim_cmds::run`; this is its report.

use planlab_core::arm::{ArmEpisode, ArmMetrics, ArmPredictor, PlanEffort};
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
    /// Joint-space distance travelled, rad.
    joint_path_length_rad: f64,
    /// Tool distance travelled sample by sample, m.
    gripper_path_length_m: f64,
    /// Planning effort (plans, iterations, collision checks).
    effort: PlanEffort,
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
        planner: format!(
            "arm-{}:{}",
            ep.planner().name(),
            ArmPredictor::of(&ep.scene().apf).name()
        ),
        seed: scenario.seed(),
        trace_hash: format!("{hash:016x}"),
        metrics: m,
        joint_path_length_rad: ep.joint_path_length(),
        gripper_path_length_m: ep.gripper_path_length(),
        effort: ep.effort(),
    };
    if args.json {
        outln!(
            "{}",
            serde_json::to_string(&report).map_err(|e| e.to_string())?
        );
    } else {
        outln!("{title} — {}, seed {}", report.planner, report.seed);
        out!("{}", crate::sim_cmds::apf_metrics_table(m));
        let e = report.effort;
        outln!(
            "joint path {:.3} rad, gripper path {:.3} m; {} plans ({} replans, {} failed, {} holds), {} iterations, {} collision checks",
            report.joint_path_length_rad,
            report.gripper_path_length_m,
            e.plans,
            e.replans,
            e.failed_plans,
            e.holds,
            e.iterations,
            e.collision_checks
        );
    }
    Ok(())
}
