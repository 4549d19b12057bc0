//! `planlab batch`: seeded variants of one scenario run by several planners
//! in parallel (rayon), summarised per planner.

use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

use planlab_core::batch::{self, metric_values, PlannerSummary};
use planlab_core::metrics::EpisodeMetrics;
use planlab_core::planners::PlannerChoice;
use planlab_core::recipe::{Recipe, RecipeError};
use planlab_core::scenario::{AnyScenario, Scenario, ScenarioKind};
use rayon::prelude::*;
use serde::Serialize;

use crate::load;

/// Options of `planlab batch`.
pub struct BatchArgs<'a> {
    /// Planner names; empty = the scenario's own.
    pub planners: &'a [String],
    /// Number of variants (≥ 1).
    pub variants: u32,
    /// Batch seed.
    pub seed: u64,
    /// Jitter radius, metres (default [`batch::default_jitter`]).
    pub jitter: Option<f64>,
    /// `--set PATH=VALUE` edits before the variants are drawn.
    pub set: &'a [String],
    /// Per-run CSV output.
    pub csv: Option<&'a Path>,
    /// JSON lines instead of a table.
    pub json: bool,
}

/// One episode's result.
struct RunRow {
    variant: u32,
    planner: usize,
    seed: u64,
    steps: u64,
    hash: u64,
    metrics: EpisodeMetrics,
}

/// The last JSON line: what was run.
#[derive(Serialize)]
pub(crate) struct BatchFooter<'a> {
    pub(crate) scenario: &'a str,
    pub(crate) variants: u32,
    pub(crate) planners: Vec<&'a str>,
    pub(crate) seed: u64,
    pub(crate) jitter_m: f64,
    pub(crate) episodes: usize,
    pub(crate) threads: usize,
    pub(crate) seconds: f64,
}

/// `planlab batch`.
pub fn batch(path: &Path, args: &BatchArgs<'_>) -> Result<(), String> {
    if args.variants == 0 || args.variants > batch::MAX_VARIANTS {
        return Err(format!(
            "--variants {}: must be from 1 to {}",
            args.variants,
            batch::MAX_VARIANTS
        ));
    }
    let text = load::read_text(path)?;
    let kind = serde_json::from_str::<serde_json::Value>(&text)
        .map_or(ScenarioKind::Robot, |tree| ScenarioKind::of(&tree));
    // An APF file is no robot scenario at all: say so, not "unknown field".
    if kind == ScenarioKind::Apf {
        let e = batch::BatchError::NoVariants(kind.name());
        return Err(format!("{}: {e}", path.display()));
    }
    let jitter = args.jitter.unwrap_or_else(|| batch::default_jitter(kind));
    let mut inputs = vec![path.to_path_buf()];
    let recipe = Recipe {
        set: crate::sim_cmds::parse_sets(args.set, kind)?,
        ..Recipe::default()
    };
    let edited = recipe
        .apply(
            &text,
            &mut crate::sim_cmds::noting_map_reader(path, &mut inputs),
        )
        .map_err(|e| match e {
            RecipeError::Document(_) if !args.set.is_empty() => {
                format!("{} (after --set): {e}", path.display())
            }
            e => format!("{}: {e}", path.display()),
        })?;
    if let Some(csv) = args.csv {
        crate::output::refuse_input("--csv", csv, &inputs)?;
    }
    let (base, grid) = match (edited.scenario, edited.grid) {
        (AnyScenario::Robot(base), Some(grid)) => (base, grid),
        (AnyScenario::Arm(base), _) => {
            return crate::batch_arm::batch_arm(path, &base, jitter, args);
        }
        (other, _) => {
            let e = batch::BatchError::NoVariants(other.kind().name());
            return Err(format!("{}: {e}", path.display()));
        }
    };
    let choices = batch::planner_choices(&base, args.planners).map_err(|e| match e {
        batch::BatchError::BadPlanners(_) => format!("--planners: {e}"),
        e => format!("{}: {e}", path.display()),
    })?;
    let started = Instant::now();
    // The CSV goes to a temporary file beside it (created first, so a bad
    // path fails fast), a chunk of variants at a time, and replaces the
    // file only when the whole batch has run: a failed batch leaves it.
    let mut csv = match args.csv {
        Some(p) => {
            let mut f = crate::output::AtomicFile::create(p)?;
            f.write(csv_header().as_bytes())?;
            Some(f)
        }
        None => None,
    };
    // Each chunk waits for its longest episode (they differ up to 7× in
    // length): with 4 variants a thread that idle tail cost ~5 % of the
    // wall time on 2 threads (dwa-crowd), with 32 under 1 %.
    let chunk = (rayon::current_num_threads() as u32 * 32).max(64);
    let mut rows: Vec<RunRow> = Vec::new();
    let mut from = 0u32;
    while from < args.variants {
        let to = from.saturating_add(chunk).min(args.variants);
        let chunk_rows = run_variants(path, &base, &grid, &choices, from..to, args.seed, jitter)?;
        if let Some(f) = csv.as_mut() {
            f.write(runs_csv(&chunk_rows, &choices, args.seed, jitter).as_bytes())?;
        }
        rows.extend(chunk_rows);
        from = to;
    }
    if let Some(f) = csv {
        f.commit()?;
    }
    let seconds = started.elapsed().as_secs_f64();

    let summaries: Vec<PlannerSummary> = choices
        .iter()
        .enumerate()
        .map(|(p, c)| {
            let runs: Vec<EpisodeMetrics> = rows
                .iter()
                .filter(|r| r.planner == p)
                .map(|r| r.metrics.clone())
                .collect();
            batch::summarise(&c.name, &runs)
        })
        .collect();

    let footer = BatchFooter {
        scenario: if base.name.is_empty() {
            path.to_str().unwrap_or("")
        } else {
            &base.name
        },
        variants: args.variants,
        planners: choices.iter().map(|c| c.name.as_str()).collect(),
        seed: args.seed,
        jitter_m: jitter,
        episodes: rows.len(),
        threads: rayon::current_num_threads(),
        seconds,
    };
    print_batch(&summaries, &footer, args.json, "")
}

/// Prints a batch's summaries and footer: JSON lines, or the table
/// followed by `note` (what the statistics are over, when that differs).
pub(crate) fn print_batch(
    summaries: &[PlannerSummary],
    footer: &BatchFooter<'_>,
    json: bool,
    note: &str,
) -> Result<(), String> {
    let mut out = String::new();
    if json {
        for s in summaries {
            out += &serde_json::to_string(s).map_err(|e| e.to_string())?;
            out.push('\n');
        }
        out += &serde_json::to_string(footer).map_err(|e| e.to_string())?;
        out.push('\n');
    } else {
        out = table(summaries, footer) + note;
    }
    // A closed pipe (`| head`) is not an error worth a panic.
    let _ = std::io::Write::write_all(&mut std::io::stdout().lock(), out.as_bytes());
    Ok(())
}

/// Variants `range` (built in parallel, identical for every planner), then
/// every (variant, planner) episode in parallel.
fn run_variants(
    path: &Path,
    base: &Scenario,
    grid: &planlab_core::map::OccupancyGrid,
    choices: &[PlannerChoice],
    range: std::ops::Range<u32>,
    seed: u64,
    jitter: f64,
) -> Result<Vec<RunRow>, String> {
    let variants: Vec<Scenario> = range
        .clone()
        .into_par_iter()
        .map(|i| batch::variant(base, grid, i, seed, jitter))
        .collect::<Result<_, _>>()
        .map_err(|e| format!("{}: {e}", path.display()))?;
    let jobs: Vec<(u32, usize)> = range
        .flat_map(|v| (0..choices.len()).map(move |p| (v, p)))
        .collect();
    let first = jobs.first().map_or(0, |j| j.0);
    jobs.par_iter()
        .map(|&(v, p)| {
            let r = batch::run_variant(&variants[(v - first) as usize], grid, v, &choices[p])
                .map_err(|e| format!("{}: {e}", path.display()))?;
            Ok(RunRow {
                variant: v,
                planner: p,
                seed: r.seed,
                steps: r.steps,
                hash: r.trace_hash,
                metrics: r.metrics,
            })
        })
        .collect()
}

/// The CSV's first line. `batch_seed` and `jitter_m` with `variant` and
/// `planner` replay a row: `planlab run SCENARIO --planner P --variant K
/// --seed BATCH_SEED --jitter J` (`seed` is the episode's own seed).
fn csv_header() -> String {
    format!(
        "variant,planner,seed,batch_seed,jitter_m,steps,trace_hash,outcome,{}\n",
        batch::METRIC_NAMES.join(",")
    )
}

/// One CSV row per episode (no header).
fn runs_csv(rows: &[RunRow], choices: &[PlannerChoice], seed: u64, jitter: f64) -> String {
    let mut s = String::new();
    for r in rows {
        let _ = write!(
            s,
            "{},{},{},{},{:?},{},{:016x},{}",
            r.variant,
            choices[r.planner].name,
            r.seed,
            seed,
            jitter,
            r.steps,
            r.hash,
            r.metrics.outcome.as_str()
        );
        for (_, v) in metric_values(&r.metrics) {
            match v {
                Some(v) => {
                    let _ = write!(s, ",{v}");
                }
                None => s.push(','),
            }
        }
        s.push('\n');
    }
    s
}

/// Per planner: success and each metric's mean, median and 95% interval.
fn table(summaries: &[PlannerSummary], f: &BatchFooter<'_>) -> String {
    // The name comes from the file: no escape sequence reaches the terminal.
    let mut s = format!(
        "{} — {} variants (seed {}, jitter {} m), {} episodes on {} threads in {:.1} s\n",
        planlab_core::text::one_line(f.scenario),
        f.variants,
        f.seed,
        f.jitter_m,
        f.episodes,
        f.threads,
        f.seconds
    );
    for p in summaries {
        let outcomes: Vec<String> = p.outcomes.iter().map(|(k, n)| format!("{k} {n}")).collect();
        let _ = writeln!(
            s,
            "\n{}: success {:.1}% ({}/{}; {})",
            p.planner,
            100.0 * p.success_rate,
            p.reached,
            p.runs,
            outcomes.join(", ")
        );
        if p.metrics.is_empty() {
            s += "  no run reached the goal: no metric statistics\n";
            continue;
        }
        let _ = writeln!(
            s,
            "  {:<22}{:>10}{:>10}  {:<22}  (over {} reached runs)",
            "metric", "mean", "median", "95% CI of the mean", p.reached
        );
        for (k, st) in &p.metrics {
            let _ = writeln!(
                s,
                "  {k:<22}{:>10.3}{:>10.3}  [{:.3}, {:.3}]",
                st.mean, st.median, st.ci95[0], st.ci95[1]
            );
        }
    }
    s
}
