//! `planlab barn`: the planners on BARN worlds (the 250 the repository
//! holds, or a user's checkout), in parallel, scored as the challenge
//! scores, with per-planner and per-difficulty figures.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use planlab_core::barn::run::{self as barn_run, BarnOptions, BarnRun, BarnStats, PLANNERS};
use planlab_core::barn::BarnWorld;
use rayon::prelude::*;
use serde::Serialize;

/// Options of `planlab barn`.
pub struct BarnArgs<'a> {
    /// BARN folders or `.world` files; empty: the repository's 250 worlds.
    pub paths: &'a [PathBuf],
    /// World numbers to run (empty: all loaded).
    pub worlds: Option<&'a str>,
    /// Planner names (empty: every planner of [`PLANNERS`]).
    pub planners: &'a [String],
    /// Runs per world and planner.
    pub runs: u32,
    /// Seed of the sweep.
    pub seed: u64,
    /// Laser noise σ, m.
    pub noise: f64,
    /// JSON lines instead of a table.
    pub json: bool,
    /// Per-run CSV output.
    pub csv: Option<&'a Path>,
}

/// Most runs one sweep may ask for.
pub const MAX_RUNS: u32 = 100;

/// Whether `a` and `b` name the same file (or `b` lies inside folder `a`).
fn same_file(a: &Path, b: &Path) -> bool {
    let canon = |p: &Path| std::fs::canonicalize(p).ok();
    // The output may not exist yet: compare its folder's canonical path.
    let out = canon(b).or_else(|| {
        let parent = b.parent().filter(|p| !p.as_os_str().is_empty())?;
        Some(canon(parent)?.join(b.file_name()?))
    });
    match (canon(a), out) {
        (Some(a), Some(b)) => a == b || b.starts_with(&a) && a.is_dir(),
        _ => false,
    }
}

/// Parses `1,2,5-9` into world numbers: the single ones (which must be
/// loaded) and the ranges (of which the loaded ones run).
fn parse_worlds(text: &str) -> Result<(Vec<u32>, Vec<u32>), String> {
    let (mut out, mut ranged) = (Vec::new(), Vec::new());
    for part in text.split(',').map(str::trim).filter(|p| !p.is_empty()) {
        let num = |s: &str| {
            s.trim()
                .parse::<u32>()
                .map_err(|_| format!("--worlds {text}: `{s}` is not a world number"))
        };
        match part.split_once('-') {
            Some((a, b)) => {
                let (a, b) = (num(a)?, num(b)?);
                if a > b || b - a > 10_000 {
                    return Err(format!("--worlds {text}: bad range {part}"));
                }
                ranged.extend(a..=b);
            }
            None => out.push(num(part)?),
        }
    }
    if out.is_empty() && ranged.is_empty() {
        return Err(format!("--worlds {text}: no world numbers"));
    }
    Ok((out, ranged))
}

/// The worlds the arguments name.
fn load_worlds(args: &BarnArgs<'_>) -> Result<Vec<BarnWorld>, String> {
    let mut worlds = if args.paths.is_empty() {
        planlab_files::barn::builtin_worlds()?
    } else {
        let mut all = Vec::new();
        for p in args.paths {
            all.extend(planlab_files::barn::load_worlds(p)?);
        }
        all
    };
    worlds.sort_by_key(|w| w.id);
    worlds.dedup_by_key(|w| w.id);
    if let Some(list) = args.worlds {
        let (want, ranged) = parse_worlds(list)?;
        for id in &want {
            if !worlds.iter().any(|w| w.id == *id) {
                return Err(format!(
                    "--worlds: world {id} is not among the {} loaded{}",
                    worlds.len(),
                    if args.paths.is_empty() {
                        " (the repository holds the worlds N with N mod 6 ≠ 0)"
                    } else {
                        ""
                    }
                ));
            }
        }
        worlds.retain(|w| want.contains(&w.id) || ranged.contains(&w.id));
        if worlds.is_empty() {
            return Err(format!("--worlds {list}: none of these worlds is loaded"));
        }
    }
    Ok(worlds)
}

/// One line of the JSON output: a planner's figures, overall or in one
/// difficulty class.
#[derive(Serialize)]
struct StatsLine<'a> {
    planner: &'a str,
    class: &'a str,
    #[serde(flatten)]
    stats: &'a BarnStats,
}

/// The last JSON line: what was run.
#[derive(Serialize)]
struct Footer<'a> {
    worlds: usize,
    planners: Vec<&'a str>,
    runs: u32,
    seed: u64,
    noise_std_m: f64,
    episodes: usize,
    threads: usize,
    seconds: f64,
}

/// `planlab barn`.
pub fn barn(args: &BarnArgs<'_>) -> Result<(), String> {
    if args.runs == 0 || args.runs > MAX_RUNS {
        return Err(format!(
            "--runs {}: must be from 1 to {MAX_RUNS}",
            args.runs
        ));
    }
    if !(args.noise.is_finite() && (0.0..=1.0).contains(&args.noise)) {
        return Err(format!("--noise {}: must be from 0 to 1 m", args.noise));
    }
    let planners: Vec<String> = if args.planners.is_empty() {
        PLANNERS.iter().map(|s| s.to_string()).collect()
    } else {
        for p in args.planners {
            if !PLANNERS.contains(&p.as_str()) {
                return Err(format!(
                    "--planners: `{p}` cannot drive an unknown map on BARN; choose from {}",
                    PLANNERS.join(", ")
                ));
            }
        }
        args.planners.to_vec()
    };
    if let Some(csv) = args.csv {
        for p in args.paths {
            if same_file(p, csv) {
                return Err(format!(
                    "--csv {}: that is an input of the run",
                    csv.display()
                ));
            }
        }
    }
    let worlds = load_worlds(args)?;
    let opts = BarnOptions {
        noise_std: args.noise,
    };
    let jobs: Vec<(usize, usize, u32)> = (0..worlds.len())
        .flat_map(|w| (0..planners.len()).flat_map(move |p| (0..args.runs).map(move |r| (w, p, r))))
        .collect();
    let total = jobs.len();
    let done = AtomicUsize::new(0);
    let started = Instant::now();
    let results: Vec<Result<BarnRun, String>> = jobs
        .par_iter()
        .map(|&(w, p, r)| {
            let world = &worlds[w];
            let seed = barn_run::run_seed(args.seed, world.id, r);
            let out =
                barn_run::run_one(world, &planners[p], r, seed, &opts).map_err(|e| e.to_string());
            let n = done.fetch_add(1, Ordering::Relaxed) + 1;
            {
                eprint!(
                    "\r{n}/{total} runs, {:.0} s{}",
                    started.elapsed().as_secs_f64(),
                    if n == total { "\n" } else { "" }
                );
            }
            out
        })
        .collect();
    let runs: Vec<BarnRun> = results.into_iter().collect::<Result<_, _>>()?;
    let seconds = started.elapsed().as_secs_f64();
    if let Some(csv) = args.csv {
        let source = |id: u32| -> String {
            // A checkout's world replays from its file; a built-in one by number.
            args.paths
                .iter()
                .find_map(|p| {
                    let f = if p.is_dir() {
                        p.join(format!("world_{id}.world"))
                    } else {
                        p.clone()
                    };
                    let named = f.file_name()? == format!("world_{id}.world").as_str();
                    (named && f.is_file()).then(|| f.display().to_string())
                })
                .unwrap_or_else(|| id.to_string())
        };
        crate::sim_cmds::write_atomically(
            csv,
            runs_csv(&runs, &worlds, &opts, &source).as_bytes(),
        )?;
    }
    let classes = planlab_core::barn::Difficulty::ALL;
    let class_of = |id: u32| {
        worlds
            .iter()
            .find(|w| w.id == id)
            .map(BarnWorld::difficulty)
    };
    let mut out = String::new();
    if !args.json {
        let _ = writeln!(
            out,
            "BARN: {} worlds × {} run(s), laser noise σ = {} m, seed {}",
            worlds.len(),
            args.runs,
            args.noise,
            args.seed
        );
        let _ = writeln!(out, "{}", table_header());
    }
    for name in &planners {
        let mine: Vec<&BarnRun> = runs.iter().filter(|r| &r.planner == name).collect();
        let all = BarnStats::of(mine.iter().copied());
        let mut lines = vec![("all".to_string(), all)];
        for c in classes {
            let sub: Vec<&BarnRun> = mine
                .iter()
                .copied()
                .filter(|r| class_of(r.world) == Some(c))
                .collect();
            if !sub.is_empty() {
                lines.push((c.name().to_string(), BarnStats::of(sub)));
            }
        }
        for (class, s) in &lines {
            if args.json {
                let line = StatsLine {
                    planner: name,
                    class,
                    stats: s,
                };
                out.push_str(&serde_json::to_string(&line).map_err(|e| e.to_string())?);
                out.push('\n');
            } else {
                let _ = writeln!(out, "{}", table_row(name, class, s));
            }
        }
    }
    let footer = Footer {
        worlds: worlds.len(),
        planners: planners.iter().map(String::as_str).collect(),
        runs: args.runs,
        seed: args.seed,
        noise_std_m: args.noise,
        episodes: total,
        threads: rayon::current_num_threads(),
        seconds,
    };
    if args.json {
        out.push_str(&serde_json::to_string(&footer).map_err(|e| e.to_string())?);
        out.push('\n');
    } else {
        let _ = writeln!(
            out,
            "{total} episodes in {seconds:.1} s on {} threads; score = success · OT / clip(T, 2·OT, 8·OT)",
            footer.threads
        );
    }
    crate::sim_cmds::emit(&out)
}

fn table_header() -> String {
    format!(
        "{:<20}{:<8}{:>5}  {:<22}{:>11}{:>11}{:>9}  {}",
        "planner",
        "class",
        "runs",
        "success [95% CI]",
        "collision",
        "timeout",
        "time s",
        "score [95% CI]"
    )
}

fn table_row(name: &str, class: &str, s: &BarnStats) -> String {
    let share = |x: &planlab_core::reproduce::stats::Share| format!("{:.3}", x.rate);
    format!(
        "{:<20}{:<8}{:>5}  {:<22}{:>11}{:>11}{:>9}  {}",
        name,
        class,
        s.runs,
        format!(
            "{:.3} [{:.2}, {:.2}]",
            s.success.rate, s.success.ci95[0], s.success.ci95[1]
        ),
        share(&s.collision),
        share(&s.timeout),
        s.mean_time.map_or("—".into(), |t| format!("{t:.2}")),
        s.score.map_or("—".into(), |m| format!(
            "{:.4} [{:.3}, {:.3}]",
            m.mean, m.ci95[0], m.ci95[1]
        )),
    )
}

/// The CSV of every run, with the command that replays each.
fn runs_csv(
    runs: &[BarnRun],
    worlds: &[BarnWorld],
    opts: &BarnOptions,
    source: &dyn Fn(u32) -> String,
) -> String {
    let mut s = String::from(
        "world,difficulty,planner,run,seed,outcome,time_s,optimal_time_s,score,path_length_m,trace_hash,replay\n",
    );
    let noise = if opts.noise_std == barn_run::DEFAULT_NOISE {
        String::new()
    } else {
        format!(" --set perception.laser.noise_std={}", opts.noise_std)
    };
    for r in runs {
        let class = worlds
            .iter()
            .find(|w| w.id == r.world)
            .map_or("", |w| w.difficulty().name());
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{:.2},{:.3},{:.4},{:.3},{:016x},planlab run barn:{} --planner {} --seed {}{}",
            r.world,
            class,
            r.planner,
            r.run,
            r.seed,
            r.outcome.as_str(),
            r.time,
            r.optimal_time,
            r.score,
            r.path_length,
            r.trace_hash,
            source(r.world),
            r.planner,
            r.seed,
            noise
        );
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn world_lists_take_numbers_and_ranges() {
        assert_eq!(
            parse_worlds("1,3-5, 9").unwrap(),
            (vec![1, 9], vec![3, 4, 5])
        );
        assert!(parse_worlds("x")
            .unwrap_err()
            .contains("not a world number"));
        assert!(parse_worlds("5-3").unwrap_err().contains("bad range"));
        assert!(parse_worlds(",").unwrap_err().contains("no world numbers"));
    }
}
