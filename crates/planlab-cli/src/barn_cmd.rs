//! `planlab barn`: the planners on BARN worlds (the 250 the repository
//! holds, or a user's checkout), in parallel, scored as the challenge
//! scores, with per-planner and per-difficulty figures.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use planlab_core::barn::run::{self as barn_run, BarnOptions, BarnRun, BarnStats, PLANNERS};
use planlab_core::barn::{BarnWorld, Difficulty};
use planlab_core::reproduce::stats::Share;
use planlab_core::world::Outcome;
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
    /// How the figures are printed.
    pub format: Format,
    /// Per-run CSV output.
    pub csv: Option<&'a Path>,
    /// Summarise these earlier `--csv` files instead of running.
    pub from_csv: &'a [PathBuf],
}

/// Most runs one sweep may ask for.
pub const MAX_RUNS: u32 = 100;

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

/// The last JSON line of a sweep: what was run.
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

/// The last JSON line of a summary of CSV files: what was read.
#[derive(Serialize)]
struct CsvFooter<'a> {
    from_csv: Vec<String>,
    worlds: usize,
    planners: Vec<&'a str>,
    episodes: usize,
}

/// How the figures are printed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// An aligned text table.
    Text,
    /// One JSON line per planner and class, then a footer.
    Json,
    /// Markdown tables (overall, then success and score by class).
    Markdown,
}

/// `planlab barn`.
pub fn barn(args: &BarnArgs<'_>) -> Result<(), String> {
    if !args.from_csv.is_empty() {
        return summarise_csv(args);
    }
    if args.runs == 0 || args.runs > MAX_RUNS {
        return Err(format!(
            "--runs {}: must be from 1 to {MAX_RUNS}",
            args.runs
        ));
    }
    if !(args.noise.is_finite() && (0.0..=1.0).contains(&args.noise)) {
        return Err(format!("--noise {}: must be from 0 to 1 m", args.noise));
    }
    let planners = chosen_planners(args.planners)?;
    if let Some(csv) = args.csv {
        crate::output::refuse_input("--csv", csv, args.paths)?;
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
        crate::output::write_atomically(csv, &runs_csv(&runs, &worlds, &opts, &source)?)?;
    }
    let class_of = |id: u32| {
        worlds
            .iter()
            .find(|w| w.id == id)
            .map(BarnWorld::difficulty)
    };
    let mut out = String::new();
    let names: Vec<&str> = planners.iter().map(String::as_str).collect();
    if args.format == Format::Text {
        let _ = writeln!(
            out,
            "BARN: {} worlds × {} run(s), laser noise σ = {} m, seed {}",
            worlds.len(),
            args.runs,
            args.noise,
            args.seed
        );
    }
    out.push_str(&figures(&runs, &names, &class_of, args.format)?);
    match args.format {
        Format::Json => {
            let footer = Footer {
                worlds: worlds.len(),
                planners: names.clone(),
                runs: args.runs,
                seed: args.seed,
                noise_std_m: args.noise,
                episodes: total,
                threads: rayon::current_num_threads(),
                seconds,
            };
            out.push_str(&serde_json::to_string(&footer).map_err(|e| e.to_string())?);
            out.push('\n');
        }
        Format::Text | Format::Markdown => {
            let _ = writeln!(
                out,
                "\n{total} episodes in {seconds:.1} s on {} threads; score = success · OT / clip(T, 2·OT, 8·OT)",
                rayon::current_num_threads()
            );
        }
    }
    crate::sim_cmds::emit(&out)
}

/// The planners asked for, checked against [`PLANNERS`] (all of them when
/// none is named).
fn chosen_planners(asked: &[String]) -> Result<Vec<String>, String> {
    if asked.is_empty() {
        return Ok(PLANNERS.iter().map(|s| s.to_string()).collect());
    }
    for p in asked {
        if !PLANNERS.contains(&p.as_str()) {
            return Err(format!(
                "--planners: `{p}` cannot drive an unknown map on BARN; choose from {}",
                PLANNERS.join(", ")
            ));
        }
    }
    Ok(asked.to_vec())
}

/// `planlab barn --from-csv`: the figures of runs written earlier by
/// `--csv` (chunks of one sweep merge; a run found in two files counts
/// once), filtered by `--worlds` and `--planners`.
fn summarise_csv(args: &BarnArgs<'_>) -> Result<(), String> {
    if args.csv.is_some() || !args.paths.is_empty() {
        return Err(
            "--from-csv summarises earlier runs: it takes no BARN paths and no --csv".into(),
        );
    }
    let planners = chosen_planners(args.planners)?;
    let wanted = args.worlds.map(parse_worlds).transpose()?;
    let mut rows: Vec<(BarnRun, Difficulty)> = Vec::new();
    // (world, planner, run, seed) → its row's index: a run found twice is
    // checked in constant time (a merged sweep has thousands of rows).
    let mut seen: std::collections::HashMap<(u32, String, u32, u64), usize> =
        std::collections::HashMap::new();
    for path in args.from_csv {
        let text = planlab_files::read_text(path)?;
        for row in parse_runs_csv(&text).map_err(|e| format!("{}: {e}", path.display()))? {
            let r = &row.0;
            let key = (r.world, r.planner.clone(), r.run, r.seed);
            match seen.get(&key) {
                Some(&i) if rows[i].0.trace_hash == r.trace_hash => {}
                Some(_) => {
                    return Err(format!(
                        "{}: world {} planner {} run {} seed {} appears with two different trace hashes",
                        path.display(),
                        r.world,
                        r.planner,
                        r.run,
                        r.seed
                    ))
                }
                None => {
                    seen.insert(key, rows.len());
                    rows.push(row);
                }
            }
        }
    }
    rows.retain(|(r, _)| {
        planners.contains(&r.planner)
            && wanted
                .as_ref()
                .map_or(true, |(a, b)| a.contains(&r.world) || b.contains(&r.world))
    });
    if rows.is_empty() {
        return Err("--from-csv: no run matches the planners and worlds asked for".into());
    }
    let names: Vec<&str> = planners
        .iter()
        .map(String::as_str)
        .filter(|p| rows.iter().any(|(r, _)| r.planner == *p))
        .collect();
    let class: std::collections::HashMap<u32, Difficulty> =
        rows.iter().map(|(r, d)| (r.world, *d)).collect();
    let runs: Vec<BarnRun> = rows.into_iter().map(|(r, _)| r).collect();
    let mut out = figures(&runs, &names, &|id| class.get(&id).copied(), args.format)?;
    let files: Vec<String> = args
        .from_csv
        .iter()
        .map(|p| p.display().to_string())
        .collect();
    if args.format == Format::Json {
        let footer = CsvFooter {
            from_csv: files,
            worlds: class.len(),
            planners: names,
            episodes: runs.len(),
        };
        out.push_str(&serde_json::to_string(&footer).map_err(|e| e.to_string())?);
        out.push('\n');
    } else {
        let _ = writeln!(
            out,
            "\n{} runs on {} worlds from {}; score = success · OT / clip(T, 2·OT, 8·OT)",
            runs.len(),
            class.len(),
            files.join(", ")
        );
    }
    crate::sim_cmds::emit(&out)
}

/// The figures of `runs` for each planner of `names`, overall and by
/// difficulty class, in `format` (without a footer).
fn figures(
    runs: &[BarnRun],
    names: &[&str],
    class_of: &dyn Fn(u32) -> Option<Difficulty>,
    format: Format,
) -> Result<String, String> {
    let mut rows: Vec<(&str, Vec<(&str, BarnStats)>)> = Vec::new();
    for &name in names {
        let mine: Vec<&BarnRun> = runs.iter().filter(|r| r.planner == name).collect();
        let mut lines = vec![("all", BarnStats::of(mine.iter().copied()))];
        for c in Difficulty::ALL {
            let sub: Vec<&BarnRun> = mine
                .iter()
                .copied()
                .filter(|r| class_of(r.world) == Some(c))
                .collect();
            if !sub.is_empty() {
                lines.push((c.name(), BarnStats::of(sub)));
            }
        }
        rows.push((name, lines));
    }
    let mut out = String::new();
    match format {
        Format::Json => {
            for (planner, lines) in &rows {
                for (class, stats) in lines {
                    let line = StatsLine {
                        planner,
                        class,
                        stats,
                    };
                    out.push_str(&serde_json::to_string(&line).map_err(|e| e.to_string())?);
                    out.push('\n');
                }
            }
        }
        Format::Text => {
            let _ = writeln!(out, "{}", table_header());
            for (planner, lines) in &rows {
                for (class, s) in lines {
                    let _ = writeln!(out, "{}", table_row(planner, class, s));
                }
            }
        }
        Format::Markdown => out.push_str(&markdown(&rows)),
    }
    Ok(out)
}

/// Markdown tables: every planner overall, then success and score by
/// difficulty class.
fn markdown(rows: &[(&str, Vec<(&str, BarnStats)>)]) -> String {
    let mut out = String::from(
        "| planner | runs | success [95% CI] | collision | of which seen | timeout | mean time of successes, s | score [95% CI] |\n|---|---:|---|---:|---:|---:|---:|---|\n",
    );
    let rate = |s: &Share| format!("{:.3} [{:.2}, {:.2}]", s.rate, s.ci95[0], s.ci95[1]);
    let score = |s: &BarnStats| {
        s.score.map_or("—".into(), |m| {
            format!("{:.3} [{:.3}, {:.3}]", m.mean, m.ci95[0], m.ci95[1])
        })
    };
    // Collisions with what the laser had shown, of all collisions ("?"
    // counts runs from a CSV without the column).
    let seen = |s: &BarnStats| {
        let unknown = if s.collisions_unclassified > 0 {
            format!(" (+{}?)", s.collisions_unclassified)
        } else {
            String::new()
        };
        format!("{}/{}{unknown}", s.collisions_seen, s.collision.k)
    };
    for (planner, lines) in rows {
        let Some((_, s)) = lines.iter().find(|(c, _)| *c == "all") else {
            continue;
        };
        let _ = writeln!(
            out,
            "| {planner} | {} | {} | {:.3} | {} | {:.3} | {} | {} |",
            s.runs,
            rate(&s.success),
            s.collision.rate,
            seen(s),
            s.timeout.rate,
            s.mean_time.map_or("—".into(), |t| format!("{t:.1}")),
            score(s)
        );
    }
    let classes: Vec<&str> = Difficulty::ALL
        .iter()
        .map(|c| c.name())
        .filter(|c| rows.iter().any(|(_, l)| l.iter().any(|(k, _)| k == c)))
        .collect();
    if classes.is_empty() {
        return out;
    }
    let _ = write!(out, "\n| planner |");
    for c in &classes {
        let _ = write!(out, " success, {c} |");
    }
    for c in &classes {
        let _ = write!(out, " score, {c} |");
    }
    let _ = writeln!(out, "\n|---|{}", "---|".repeat(2 * classes.len()));
    for (planner, lines) in rows {
        let _ = write!(out, "| {planner} |");
        let of = |c: &str| lines.iter().find(|(k, _)| *k == c).map(|(_, s)| s);
        for c in &classes {
            let cell = of(c).map_or("—".into(), |s| {
                format!("{:.2} ({}/{})", s.success.rate, s.success.k, s.success.n)
            });
            let _ = write!(out, " {cell} |");
        }
        for c in &classes {
            let cell = of(c)
                .and_then(|s| s.score)
                .map_or("—".into(), |m| format!("{:.3}", m.mean));
            let _ = write!(out, " {cell} |");
        }
        out.push('\n');
    }
    out
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
    let share = |x: &Share| format!("{:.3}", x.rate);
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

/// Columns of the runs CSV, in order.
const CSV_HEADER: [&str; 13] = [
    "world",
    "difficulty",
    "planner",
    "run",
    "seed",
    "outcome",
    "time_s",
    "optimal_time_s",
    "score",
    "path_length_m",
    "trace_hash",
    "replay",
    "collision_seen",
];

/// The CSV of every run, with the command that replays each (fields
/// quoted where they need it: a world's path may hold a comma).
fn runs_csv(
    runs: &[BarnRun],
    worlds: &[BarnWorld],
    opts: &BarnOptions,
    source: &dyn Fn(u32) -> String,
) -> Result<Vec<u8>, String> {
    let noise = if opts.noise_std == barn_run::DEFAULT_NOISE {
        String::new()
    } else {
        format!(" --set perception.laser.noise_std={}", opts.noise_std)
    };
    let mut w = csv::Writer::from_writer(Vec::new());
    let err = |e: csv::Error| format!("writing the CSV: {e}");
    w.write_record(CSV_HEADER).map_err(err)?;
    for r in runs {
        let class = worlds
            .iter()
            .find(|w| w.id == r.world)
            .map_or("", |w| w.difficulty().name());
        w.write_record([
            r.world.to_string(),
            class.to_string(),
            r.planner.clone(),
            r.run.to_string(),
            r.seed.to_string(),
            r.outcome.as_str().to_string(),
            format!("{:.2}", r.time),
            format!("{:.3}", r.optimal_time),
            format!("{:.4}", r.score),
            format!("{:.3}", r.path_length),
            format!("{:016x}", r.trace_hash),
            format!(
                "planlab run barn:{} --planner {} --seed {}{}",
                source(r.world),
                r.planner,
                r.seed,
                noise
            ),
            match r.collision_seen {
                Some(true) => "yes",
                Some(false) => "no",
                None => "",
            }
            .to_string(),
        ])
        .map_err(err)?;
    }
    w.into_inner().map_err(|e| format!("writing the CSV: {e}"))
}

/// Reads a runs CSV written by `--csv`: each run with its world's class.
/// Scores are read as written (4 decimals), not recomputed.
fn parse_runs_csv(text: &str) -> Result<Vec<(BarnRun, Difficulty)>, String> {
    let mut r = csv::Reader::from_reader(text.as_bytes());
    let header = r.headers().map_err(|e| format!("not a runs CSV: {e}"))?;
    // Files from before the collision_seen column read as unclassified.
    let columns = header.len();
    if !(columns == CSV_HEADER.len() || columns == CSV_HEADER.len() - 1)
        || header.iter().ne(CSV_HEADER.into_iter().take(columns))
    {
        return Err(format!(
            "not a runs CSV of planlab barn (its header should be {})",
            CSV_HEADER.join(",")
        ));
    }
    let mut out = Vec::new();
    for (i, rec) in r.records().enumerate() {
        let line = i + 2;
        let rec = rec.map_err(|e| format!("line {line}: {e}"))?;
        let field = |k: usize| rec.get(k).unwrap_or("");
        let bad = |k: usize| format!("line {line}: bad {} `{}`", CSV_HEADER[k], field(k));
        let num = |k: usize| -> Result<f64, String> {
            field(k)
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| bad(k))
        };
        let class = Difficulty::ALL
            .into_iter()
            .find(|c| c.name() == field(1))
            .ok_or_else(|| bad(1))?;
        let outcome = [Outcome::Reached, Outcome::Collision, Outcome::Timeout]
            .into_iter()
            .find(|o| o.as_str() == field(5))
            .ok_or_else(|| bad(5))?;
        let run = BarnRun {
            world: field(0).parse().map_err(|_| bad(0))?,
            planner: field(2).to_string(),
            run: field(3).parse().map_err(|_| bad(3))?,
            seed: field(4).parse().map_err(|_| bad(4))?,
            outcome,
            time: num(6)?,
            optimal_time: num(7)?,
            score: num(8)?,
            path_length: num(9)?,
            trace_hash: u64::from_str_radix(field(10), 16).map_err(|_| bad(10))?,
            collision_seen: match field(12) {
                "yes" => Some(true),
                "no" => Some(false),
                "" => None,
                _ => return Err(bad(12)),
            },
        };
        if !(0.0..=0.5).contains(&run.score) {
            return Err(bad(8));
        }
        out.push((run, class));
    }
    Ok(out)
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
