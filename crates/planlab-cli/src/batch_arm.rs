//! `planlab batch` of an arm scenario: seeded variants of the scene
//! ([`batch::arm_variant`]) run by the arm planners (the APF, RRT-Connect)
//! in parallel, summarised per planner with the compute time of each
//! episode, which only the CLI can measure (the core has no clock).

use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

use planlab_core::arm::ArmPlanner;
use planlab_core::batch::{self, arm_metric_values, ArmBatchRun, PlannerSummary};
use planlab_core::scenario::ArmScenario;
use rayon::prelude::*;

use crate::batch_cmd::{print_batch, BatchArgs, BatchFooter};

/// One arm episode and its compute time, ms (wall time of the thread that
/// ran it: the episode's planning, IK and simulation).
struct ArmRow {
    run: ArmBatchRun,
    compute_ms: f64,
}

/// `planlab batch` of an arm scenario `base` (the `--set` edits applied).
pub fn batch_arm(
    path: &Path,
    base: &ArmScenario,
    jitter: f64,
    args: &BatchArgs<'_>,
) -> Result<(), String> {
    let at = |e: &dyn std::fmt::Display| format!("{}: {e}", path.display());
    let planners = batch::arm_planners(base, args.planners).map_err(|e| match e {
        batch::BatchError::BadPlanners(_) => format!("--planners: {e}"),
        e => at(&e),
    })?;
    // The CSV is created first, so a bad path fails before the work.
    let csv = args
        .csv
        .map(crate::output::AtomicFile::create)
        .transpose()?;
    let started = Instant::now();
    let variants: Vec<ArmScenario> = (0..args.variants)
        .into_par_iter()
        .map(|i| batch::arm_variant(base, i, args.seed, jitter))
        .collect::<Result<_, _>>()
        .map_err(|e| at(&e))?;
    let jobs: Vec<(u32, ArmPlanner)> = (0..args.variants)
        .flat_map(|v| planners.iter().map(move |&p| (v, p)))
        .collect();
    let rows: Vec<ArmRow> = jobs
        .par_iter()
        .map(|&(v, p)| {
            let t = Instant::now();
            let run = batch::run_arm_variant(&variants[v as usize], v, p).map_err(|e| at(&e))?;
            Ok(ArmRow {
                run,
                compute_ms: t.elapsed().as_secs_f64() * 1e3,
            })
        })
        .collect::<Result<_, String>>()?;
    if let Some(mut f) = csv {
        f.write(runs_csv(&rows, args.seed, jitter).as_bytes())?;
        f.commit()?;
    }
    let seconds = started.elapsed().as_secs_f64();
    let summaries: Vec<PlannerSummary> = planners
        .iter()
        .map(|p| {
            let mine: Vec<&ArmRow> = rows.iter().filter(|r| r.run.planner == p.name()).collect();
            let runs: Vec<ArmBatchRun> = mine.iter().map(|r| r.run.clone()).collect();
            let ms: Vec<f64> = mine.iter().map(|r| r.compute_ms).collect();
            batch::summarise_arm(p.name(), &runs, &[("compute_ms", ms)])
        })
        .collect();
    let footer = BatchFooter {
        scenario: if base.name.is_empty() {
            path.to_str().unwrap_or("")
        } else {
            &base.name
        },
        variants: args.variants,
        planners: planners.iter().map(|p| p.name()).collect(),
        seed: args.seed,
        jitter_m: jitter,
        episodes: rows.len(),
        threads: rayon::current_num_threads(),
        seconds,
    };
    print_batch(
        &summaries,
        &footer,
        args.json,
        "\nmin_hand_distance_m is over every run; compute_ms (wall time of an episode, \
         planning and simulation) over every run; the others over the reached runs.\n",
    )
}

/// The CSV: a header and one row per episode. `batch_seed` and `jitter_m`
/// with `variant` and `planner` replay a row: `planlab run SCENARIO
/// --planner P --variant K --seed BATCH_SEED --jitter J` (with the same
/// `--set` edits).
fn runs_csv(rows: &[ArmRow], seed: u64, jitter: f64) -> String {
    let mut s = format!(
        "variant,planner,seed,batch_seed,jitter_m,trace_hash,outcome,{},compute_ms\n",
        batch::ARM_METRIC_NAMES.join(",")
    );
    for r in rows {
        let _ = write!(
            s,
            "{},{},{},{},{:?},{:016x},{}",
            r.run.variant,
            r.run.planner,
            r.run.seed,
            seed,
            jitter,
            r.run.trace_hash,
            r.run.metrics.outcome.as_str()
        );
        for (_, v) in arm_metric_values(&r.run) {
            match v {
                Some(v) => {
                    let _ = write!(s, ",{v}");
                }
                None => s.push(','),
            }
        }
        let _ = writeln!(s, ",{:.3}", r.compute_ms);
    }
    s
}
