//! `planlab run` of an arm scenario (a JSON file with an `arm` section):
//! the 7-DOF arm's end effector among the moving hand, \[T\] §5.3.3.

use std::path::Path;

use planlab_core::arm::{ArmEpisode, ArmMetrics, ArmPredictor, ArmScenario};
use planlab_core::map::io::scenario::set_json_path;
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

/// Runs the arm scenario `tree` (read from `path`) with the CLI's edits:
/// `--planner` picks the predictor (`none`, `constant-velocity`, `rnn`), `--seed`
/// the hand's variation, `--set` edits the tree; `--trace` writes the
/// tool's path as CSV.
pub fn run(path: &Path, mut tree: serde_json::Value, args: &RunArgs<'_>) -> Result<(), String> {
    let at = |e: &dyn std::fmt::Display| format!("{}: {e}", path.display());
    if let Some(seed) = args.seed {
        set_json_path(&mut tree, "seed", &seed.to_string()).map_err(|e| at(&e))?;
    }
    for edit in args.set {
        let Some((key, value)) = edit.split_once('=') else {
            return Err(format!(
                "--set {edit}: expected PATH=VALUE, like arm.hand.speed=2"
            ));
        };
        set_json_path(&mut tree, key.trim(), value).map_err(|e| at(&e))?;
    }
    let mut scenario = ArmScenario::from_value(&tree).map_err(|e| at(&e))?;
    if let Some(p) = args.planner {
        let p = ArmPredictor::parse(p).map_err(|e| at(&e))?;
        p.apply(&mut scenario.arm.apf);
    }
    let mut ep = ArmEpisode::from_scenario(&scenario).map_err(|e| at(&e))?;
    ep.run().map_err(|e| at(&e))?;
    let m = ep.metrics();
    if let Some(t) = args.trace {
        let mut csv = String::from("i,x,y,z\n");
        for (i, p) in ep.tool_path().iter().enumerate() {
            csv.push_str(&format!("{i},{},{},{}\n", p.x, p.y, p.z));
        }
        std::fs::write(t, csv).map_err(|e| format!("cannot write {}: {e}", t.display()))?;
    }
    let report = ArmRunReport {
        scenario: &scenario.name,
        planner: format!("arm-apf:{}", ArmPredictor::of(&ep.scene().apf).name()),
        seed: scenario.seed.unwrap_or(0),
        trace_hash: format!(
            "{:016x}",
            planlab_core::apf::scene::path_hash(ep.tool_path())
        ),
        metrics: &m,
    };
    if args.json {
        println!(
            "{}",
            serde_json::to_string(&report).map_err(|e| e.to_string())?
        );
    } else {
        let title = if scenario.name.is_empty() {
            path.display().to_string()
        } else {
            scenario.name.clone()
        };
        println!("{title} — {}, seed {}", report.planner, report.seed);
        print!("{}", crate::sim_cmds::apf_metrics_table(&m));
    }
    Ok(())
}
