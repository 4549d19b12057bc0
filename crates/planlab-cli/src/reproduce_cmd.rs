//! `planlab reproduce`: the papers' experiments on their presets, or on a
//! family of N seeded variants with success rates, per-clause shares,
//! paired effects and a verdict; `--sweep` varies one declared value,
//! `--write-variants` writes every variant's scenarios for `planlab run`.

use std::collections::BTreeMap;
use std::path::Path;

use planlab_core::apf::ApfMetrics;
use planlab_core::metrics::EpisodeMetrics;
use planlab_core::reproduce::{
    self, ClauseInfo, Experiment, ExperimentResult, FamilyResult, RunMetrics, MAX_VARIANTS,
};
use rayon::prelude::*;

use crate::sim_cmds::{emit, opt};

/// Options of `planlab reproduce`.
pub struct ReproduceArgs<'a> {
    /// One id, or every experiment.
    pub id: Option<&'a str>,
    /// JSON lines.
    pub json: bool,
    /// Family size; `None` runs the presets alone.
    pub variants: Option<u32>,
    /// Family seed.
    pub seed: u64,
    /// `path=a,b,c`.
    pub sweep: Option<&'a str>,
    /// Write every variant's scenario files into this folder.
    pub write_variants: Option<&'a Path>,
    /// List the experiments' definitions instead of running them.
    pub list: bool,
    /// Show the family's sensitivity per perturbation (runs the family,
    /// [`EXPLAIN_VARIANTS`] variants unless `variants` says).
    pub explain: bool,
}

/// Family size of `--explain` without `--variants`: the README's verdict run.
pub const EXPLAIN_VARIANTS: u32 = 60;

/// `planlab reproduce`.
pub fn reproduce(args: &ReproduceArgs<'_>) -> Result<(), String> {
    let all = reproduce::all();
    let paths = reproduce::path_experiments();
    let (chosen, chosen_paths): (Vec<_>, Vec<_>) = match args.id {
        None => (all, paths),
        Some(id) => {
            if let Some(e) = all.iter().find(|e| e.id == id) {
                (vec![e.clone()], vec![])
            } else if let Some(e) = paths.iter().find(|e| e.id == id) {
                (vec![], vec![e.clone()])
            } else {
                return Err(format!(
                    "unknown experiment `{id}`; known ids: {}",
                    reproduce::ids().join(", ")
                ));
            }
        }
    };
    if args.list {
        for info in chosen
            .iter()
            .map(|e| e.info())
            .chain(chosen_paths.iter().map(|e| e.info()))
        {
            if args.json {
                emit(&(serde_json::to_string(&info).map_err(|e| e.to_string())? + "\n"))?;
            } else {
                emit(&format!(
                    "{}  {}\n  {}\n",
                    info.id, info.paper, info.relation
                ))?;
            }
        }
        return Ok(());
    }
    if let Some(n) = args.variants {
        if n == 0 || n > MAX_VARIANTS {
            return Err(format!(
                "--variants {n}: give 1 to {MAX_VARIANTS} (the preset is variant 0)"
            ));
        }
    }
    let sweep = match args.sweep {
        None => vec![None],
        Some(s) => parse_sweep(s)?.into_iter().map(Some).collect(),
    };
    if args.variants.is_none()
        && !args.explain
        && (args.sweep.is_some() || args.write_variants.is_some())
    {
        return Err("--sweep and --write-variants need --variants N".into());
    }
    if let Some(dir) = args.write_variants {
        if !dir.is_dir() {
            return Err(format!(
                "--write-variants {}: not an existing folder",
                dir.display()
            ));
        }
    }
    for extra in &sweep {
        let extra: Vec<(String, String)> = extra.iter().cloned().collect();
        for exp in &chosen {
            one(exp, args, &extra, experiment_table)?;
        }
        for exp in &chosen_paths {
            one(exp, args, &extra, path_experiment_table)?;
        }
    }
    Ok(())
}

/// `path=a,b,c` → [(path, a), (path, b), (path, c)].
fn parse_sweep(s: &str) -> Result<Vec<(String, String)>, String> {
    let Some((path, values)) = s.split_once('=') else {
        return Err(format!(
            "--sweep {s}: expected PATH=a,b,c, like apf.config.predict_dt=0.1,0.5,0.8"
        ));
    };
    let values: Vec<&str> = values
        .split(',')
        .map(str::trim)
        .filter(|v| !v.is_empty())
        .collect();
    if path.trim().is_empty() || values.is_empty() {
        return Err(format!("--sweep {s}: give a path and at least one value"));
    }
    Ok(values
        .into_iter()
        .map(|v| (path.trim().to_string(), v.to_string()))
        .collect())
}

/// Runs one experiment (presets, or its family) and prints it.
fn one<M: RunMetrics>(
    exp: &Experiment<M>,
    args: &ReproduceArgs<'_>,
    extra: &[(String, String)],
    table: fn(&ExperimentResult<M>) -> String,
) -> Result<(), String> {
    let at = |e: &dyn std::fmt::Display| format!("{}: {e}", exp.id);
    let variants = args.variants.or(args.explain.then_some(EXPLAIN_VARIANTS));
    let Some(n) = variants else {
        let r = reproduce::run(exp).map_err(|e| at(&e))?;
        return if args.json {
            emit(&(serde_json::to_string(&r).map_err(|e| e.to_string())? + "\n"))
        } else {
            emit(&table(&r))
        };
    };
    if let Some(dir) = args.write_variants {
        for k in 0..n {
            let scene = exp.variant(args.seed, k, extra).map_err(|e| at(&e))?;
            for (run, tree) in &scene.trees {
                let file = dir.join(format!("{}-v{k}-{run}.json", exp.id));
                let text = serde_json::to_string_pretty(tree).map_err(|e| e.to_string())?;
                // Replaces a link planted at the name instead of following it.
                crate::output::write_atomically(&file, (text + "\n").as_bytes())?;
            }
        }
    }
    let results: Result<Vec<_>, _> = (0..n)
        .into_par_iter()
        .map(|k| reproduce::run_variant(exp, args.seed, k, extra))
        .collect();
    let results = results.map_err(|e| at(&e))?;
    let label = extra.first().map(|(p, v)| format!("{p}={v}"));
    let f = reproduce::summarise(exp, args.seed, label, &results);
    if args.json {
        emit(&(serde_json::to_string(&f).map_err(|e| e.to_string())? + "\n"))
    } else if args.explain {
        emit(&(family_table(&f) + &explain_table(&f)))
    } else {
        emit(&family_table(&f))
    }
}

/// `--explain`: per perturbation its range, why, and the median split of
/// the drawn number that moves the relation most.
fn explain_table(f: &FamilyResult) -> String {
    let mut s = format!(
        "  sensitivity: {}\n  {:<16}{:<34}{:<18}{}\n",
        f.sensitivity.summary,
        "perturbation",
        "drawn number (split at median)",
        "holds below",
        "holds at/above"
    );
    for (p, r) in f
        .sensitivity
        .perturbations
        .iter()
        .zip(&f.family.perturbations)
    {
        let range = serde_json::to_value(r.perturbation)
            .ok()
            .and_then(|v| v.as_object().cloned())
            .map(|m| {
                m.iter()
                    .filter(|(k, _)| *k != "kind")
                    .map(|(k, v)| format!("{k} {v}"))
                    .collect::<Vec<_>>()
                    .join(", ")
            })
            .unwrap_or_default();
        match &p.split {
            Some(sp) => s.push_str(&format!(
                "  {:<16}{:<34}{:<18}{}\n",
                p.perturbation,
                format!("{} @ {}", sp.value, planlab_core::num::fmt_num(sp.at)),
                share_short(&sp.below),
                share_short(&sp.above)
            )),
            None => s.push_str(&format!(
                "  {:<16}{:<34}\n",
                p.perturbation, "(nothing ordered drawn: a seed, or nothing to move)"
            )),
        }
        s.push_str(&format!("      range: {range}\n      why: {}\n", p.why));
    }
    s.push('\n');
    s
}

fn share_short(s: &reproduce::Share) -> String {
    format!("{}/{} [{:.2}, {:.2}]", s.k, s.n, s.ci95[0], s.ci95[1])
}

fn share(s: &reproduce::Share) -> String {
    format!(
        "{:>3}/{:<3} {:>4.0} % [{:.2}, {:.2}]",
        s.k,
        s.n,
        100.0 * s.rate,
        s.ci95[0],
        s.ci95[1]
    )
}

/// A family's report: runs, clauses, verdict, deviations.
fn family_table(f: &FamilyResult) -> String {
    let mut s = format!(
        "{} — {}\n  verdict: {}   ({} variants, seed {}{})\n  relation: {}\n",
        f.id,
        f.paper,
        f.verdict.as_str().to_uppercase(),
        f.variants,
        f.seed,
        f.sweep
            .as_ref()
            .map_or(String::new(), |w| format!(", sweep {w}")),
        f.relation
    );
    s.push_str(&format!(
        "  {:<30}{:<28}outcomes\n",
        "run", "success (95 % Wilson)"
    ));
    for (name, r) in &f.runs {
        let outcomes: Vec<String> = r.outcomes.iter().map(|(k, v)| format!("{k} {v}")).collect();
        s.push_str(&format!(
            "  {:<30}{:<28}{}\n",
            name,
            share(&r.success),
            outcomes.join(", ")
        ));
    }
    s.push_str(&format!(
        "  {:<30}{:<28}paired effect: median [95 % CI] (n)\n",
        "clause", "holds on"
    ));
    for c in &f.clauses {
        let eff = c.effect.as_ref().map_or(String::new(), |e| match e.median {
            Some(m) => format!(
                "{}: {:+.3}{} {} (n {})",
                e.name,
                m.median,
                if e.unit == "1" {
                    String::new()
                } else {
                    format!(" {}", e.unit)
                },
                m.ci95.map_or("[n < 6]".to_string(), |[a, b]| format!(
                    "[{a:+.3}, {b:+.3}]"
                )),
                m.n
            ),
            None => format!("{}: no variant has it", e.name),
        });
        s.push_str(&format!(
            "  {:<30}{:<28}{}\n",
            format!("{} ({})", c.clause.name, kind(&c.clause)),
            share(&c.holds),
            eff
        ));
    }
    s.push_str(&format!("  {:<30}{}\n", "all clauses", share(&f.joint)));
    s.push_str(&format!("  most sensitive: {}\n", f.sensitivity.summary));
    if !f.deviations.is_empty() {
        s.push_str("  not from the paper:\n");
        for d in &f.deviations {
            s.push_str(&format!(
                "    {}: ours {}; paper {}{}\n",
                d.what,
                d.ours,
                d.paper,
                d.path
                    .map_or(String::new(), |p| format!(" (--sweep {p}=…)"))
            ));
        }
    }
    s.push('\n');
    s
}

fn kind(c: &ClauseInfo) -> &'static str {
    match c.kind {
        reproduce::ClauseKind::Outcome => "outcome",
        reproduce::ClauseKind::Effect => "effect",
    }
}

/// The relation and each clause of a preset run.
fn clause_lines(relation: &str, holds: bool, clauses: &[(ClauseInfo, bool)]) -> String {
    let mut s = format!("  relation: {relation}\n");
    for (c, h) in clauses {
        s.push_str(&format!(
            "    [{}] {} — {}\n",
            if *h { "x" } else { " " },
            c.name,
            c.text
        ));
    }
    s.push_str(&format!(
        "  holds: {}\n\n",
        if holds { "yes" } else { "no" }
    ));
    s
}

/// A paper-style table of one path experiment (\[T\] Table 4-1 columns).
fn path_experiment_table(r: &ExperimentResult<ApfMetrics>) -> String {
    let mut s = format!("{} — {}\n  {}\n", r.id, r.paper, r.what);
    s.push_str(&format!(
        "  {:<22}{:<11}{:>10}{:>8}{:>8}{:>12}{:>9}\n",
        "run", "outcome", "length m", "points", "spikes", "min dist m", "time s"
    ));
    for (name, m) in &r.runs {
        s.push_str(&format!(
            "  {:<22}{:<11}{:>10.3}{:>8}{:>8}{:>12.3}{:>9.2}\n",
            name,
            m.outcome.to_string(),
            m.path_length_m,
            m.path_points,
            m.spikes,
            m.min_obstacle_distance_m,
            m.time_s
        ));
    }
    s.push_str(&clause_lines(&r.relation, r.holds, &r.clauses));
    s
}

/// A paper-style table of one experiment: runs as rows, metrics as columns.
fn experiment_table(r: &ExperimentResult<EpisodeMetrics>) -> String {
    let mut s = format!("{} — {}\n  {}\n", r.id, r.paper, r.what);
    let head = [
        "run",
        "outcome",
        "time s",
        "length m",
        "min clr m",
        "mean clr m",
        "turn rad",
        "max turn",
        "drops",
        "tg sw",
        "track m",
        "track max",
        "load %",
    ];
    let mut rows: Vec<Vec<String>> = vec![head.iter().map(|h| h.to_string()).collect()];
    let runs: &BTreeMap<String, EpisodeMetrics> = &r.runs;
    for (name, m) in runs {
        rows.push(vec![
            name.clone(),
            m.outcome.to_string(),
            format!("{:.2}", m.time_s),
            format!("{:.2}", m.path_length_m),
            format!("{:.3}", m.min_clearance_m),
            format!("{:.3}", m.mean_clearance_m),
            format!("{:.2}", m.total_turn_rad),
            format!("{:.2}", m.max_turn_rad),
            m.speed_drops.to_string(),
            m.temp_goal_switches.to_string(),
            opt(m.mean_tracking_error_m, 3),
            opt(m.max_tracking_error_m, 3),
            opt(m.load_ok_share.map(|x| 100.0 * x), 1),
        ]);
    }
    let widths: Vec<usize> = (0..head.len())
        .map(|c| rows.iter().map(|r| r[c].chars().count()).max().unwrap_or(0))
        .collect();
    for row in &rows {
        s.push_str("  ");
        for (c, cell) in row.iter().enumerate() {
            let pad = widths[c] - cell.chars().count();
            if c == 0 || c == 1 {
                s.push_str(cell);
                s.push_str(&" ".repeat(pad + 2));
            } else {
                s.push_str(&" ".repeat(pad));
                s.push_str(cell);
                s.push_str("  ");
            }
        }
        s.truncate(s.trim_end_matches(' ').len());
        s.push('\n');
    }
    for (k, v) in &r.figures {
        let v = if v.fract() == 0.0 && v.abs() < 1e15 {
            format!("{v:.0}")
        } else {
            format!("{v:.4}")
        };
        s.push_str(&format!("  {k}: {v}\n"));
    }
    s.push_str(&clause_lines(&r.relation, r.holds, &r.clauses));
    s
}
