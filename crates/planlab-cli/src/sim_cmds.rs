//! `planlab run`, `planlab planners` and `planlab reproduce`: simulated
//! episodes, the planner catalogue and the papers' experiments.

use std::path::{Path, PathBuf};

use planlab_core::apf::{AnyApfRun, ApfMetrics};
use planlab_core::map::OccupancyGrid;
use planlab_core::metrics::EpisodeMetrics;
use planlab_core::planners;
use planlab_core::recipe::{Recipe, RecipeError, VariantPick};
use planlab_core::scenario::{AnyRun, AnyScenario, FinishedRun, ScenarioKind};
use planlab_core::sim::Episode;
use serde::Serialize;

use crate::load;

/// Writes `text` to stdout. A closed pipe (`planlab reproduce --json | head
/// -1`) ends the program quietly with success: the reader has what it
/// wanted. Other write errors are returned.
pub(crate) fn emit(text: &str) -> Result<(), String> {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => std::process::exit(0),
        Err(e) => Err(format!("writing to stdout: {e}")),
    }
}

/// Options of `planlab run`.
pub struct RunArgs<'a> {
    /// Replaces `local_planner.name`.
    pub planner: Option<&'a str>,
    /// Replaces `seed`.
    pub seed: Option<u64>,
    /// `a.b.c=VALUE` edits, in order.
    pub set: &'a [String],
    /// One JSON object instead of a table.
    pub json: bool,
    /// Write the per-step trace CSV here.
    pub trace: Option<&'a Path>,
    /// Write the run as an MCAP file here (robot episodes).
    pub mcap: Option<&'a Path>,
    /// Run `planlab batch`'s variant K (with `seed` as the batch seed and
    /// this jitter) instead of the scenario as written.
    pub variant: Option<(u32, Option<f64>)>,
}

/// What `planlab run --json` prints: the run's identity, then the metrics.
#[derive(Serialize)]
struct RunReport<'a> {
    scenario: &'a str,
    planner: &'a str,
    seed: u64,
    steps: u64,
    /// FNV-1a hash of the trace, hex (the determinism check compares it).
    trace_hash: String,
    /// With a perception section and a collision: whether the laser had
    /// shown what the robot hit.
    #[serde(skip_serializing_if = "Option::is_none")]
    collision_seen: Option<bool>,
    /// With a `global_planner` section: the car path in force at the end.
    #[serde(skip_serializing_if = "Option::is_none")]
    global_path: Option<GlobalPathReport>,
    #[serde(flatten)]
    metrics: &'a EpisodeMetrics,
}

/// The `--set PATH=VALUE` edits as (path, value) pairs; a malformed one is
/// refused with an example fitting the scenario's `kind`.
pub(crate) fn parse_sets(
    sets: &[String],
    kind: ScenarioKind,
) -> Result<Vec<(String, String)>, String> {
    let like = if kind == ScenarioKind::Arm {
        "arm.hand.speed=2"
    } else {
        "sim.dt=0.05"
    };
    sets.iter()
        .map(|edit| {
            edit.split_once('=')
                .map(|(k, v)| (k.to_string(), v.to_string()))
                .ok_or_else(|| format!("--set {edit}: expected PATH=VALUE, like {like}"))
        })
        .collect()
}

/// The car path of a run with a `global_planner` section.
#[derive(Serialize)]
struct GlobalPathReport {
    algorithm: &'static str,
    /// Hybrid A*'s path length, m.
    length_m: f64,
    cusps: usize,
    /// Poses Hybrid A* expanded.
    expanded: usize,
    /// Paths planned after the first.
    replans: usize,
}

/// Reads the scenario at `path` (text `text`) with the run's edits applied
/// by the core's [`Recipe`] (planner, seed, `--set`, `--variant`, an arm
/// scenario's predictor), and its map (none for an arm scenario).
fn edited_scenario(
    path: &Path,
    text: &str,
    args: &RunArgs<'_>,
    read: &mut Vec<PathBuf>,
) -> Result<(AnyScenario, Option<OccupancyGrid>), String> {
    let at = |e: &dyn std::fmt::Display| format!("{}: {e}", path.display());
    let kind = serde_json::from_str::<serde_json::Value>(text)
        .map_or(ScenarioKind::Robot, |tree| ScenarioKind::of(&tree));
    let set = parse_sets(args.set, kind)?;
    let recipe = Recipe {
        planner: args.planner.map(str::to_string),
        seed: args.seed,
        set,
        variant: args.variant.map(|(index, jitter)| VariantPick {
            index,
            jitter: jitter.unwrap_or_else(|| planlab_core::batch::default_jitter(kind)),
        }),
    };
    // Errors in an edited tree point at lines of the re-written text, so
    // say so when edits were made (an arm file is always read as a tree;
    // a variant is drawn from the file with the `--set` edits only).
    let edited = !args.set.is_empty()
        || (args.variant.is_none() && (args.planner.is_some() || args.seed.is_some()));
    let done = recipe
        .apply(text, &mut noting_map_reader(path, read))
        .map_err(|e| match e {
            RecipeError::NoVariants(_) | RecipeError::VariantTooLarge(_) => e.to_string(),
            RecipeError::Document(_) if edited && kind != ScenarioKind::Arm => {
                format!("{} (after --planner/--seed/--set): {e}", path.display())
            }
            e => at(&e),
        })?;
    Ok((done.scenario, done.grid))
}

/// [`load::map_reader`] that also notes each file it reads in `read`: the
/// inputs an output of the same command must not replace.
pub(crate) fn noting_map_reader<'a>(
    path: &'a Path,
    read: &'a mut Vec<PathBuf>,
) -> impl FnMut(&str) -> Result<Vec<u8>, String> + 'a {
    let dir = path.parent().unwrap_or_else(|| Path::new("."));
    move |rel: &str| {
        let file = dir.join(rel);
        let bytes = load::read_map_file(&file);
        read.push(file);
        bytes
    }
}

/// What `planlab run --json` prints for a scenario with an `apf` section.
#[derive(Serialize)]
struct ApfRunReport<'a> {
    scenario: &'a str,
    planner: String,
    dims: usize,
    steps: u64,
    /// FNV-1a of the path points, hex (what `planlab reproduce` reports).
    trace_hash: String,
    #[serde(flatten)]
    metrics: &'a ApfMetrics,
}

/// The report of a finished APF run (`--trace` writes the path points as
/// CSV).
fn report_apf(
    name: &str,
    title: &str,
    r: &AnyApfRun,
    m: &ApfMetrics,
    hash: u64,
    args: &RunArgs<'_>,
) -> Result<(), String> {
    let dims = match r {
        AnyApfRun::D2(_) => 2,
        AnyApfRun::D3(_) => 3,
    };
    if let Some(t) = args.trace {
        write_path_csv(t, r.path_xyz().iter().map(|p| [p.x, p.y, p.z]))?;
    }
    let report = ApfRunReport {
        scenario: name,
        planner: format!("apf:{}", r.mode_label()),
        dims,
        steps: r.steps(),
        trace_hash: format!("{hash:016x}"),
        metrics: m,
    };
    if args.json {
        outln!(
            "{}",
            serde_json::to_string(&report).map_err(|e| e.to_string())?
        );
    } else {
        outln!("{title} — {} ({dims}D)", report.planner);
        out!("{}", apf_metrics_table(m));
        outln!("{:<22}{}", "steps", report.steps);
        outln!("{:<22}{}", "trace hash", report.trace_hash);
    }
    Ok(())
}

/// Writes a path's points as CSV `i,x,y,z` (`--trace` of APF and arm runs).
pub(crate) fn write_path_csv(
    out: &Path,
    pts: impl IntoIterator<Item = [f64; 3]>,
) -> Result<(), String> {
    let mut csv = String::from("i,x,y,z\n");
    for (i, [x, y, z]) in pts.into_iter().enumerate() {
        csv.push_str(&format!("{i},{x},{y},{z}\n"));
    }
    crate::output::write_atomically(out, csv.as_bytes())
}

/// APF (and arm) metrics as `name value unit` lines.
pub fn apf_metrics_table(m: &ApfMetrics) -> String {
    format!(
        "{:<22}{}\n{:<22}{:.3} m\n{:<22}{}\n{:<22}{}\n{:<22}{:.3} m\n{:<22}{:.2} s\n",
        "outcome",
        m.outcome,
        "path length",
        m.path_length_m,
        "path points",
        m.path_points,
        "spikes (> 30°)",
        m.spikes,
        "min obstacle dist",
        m.min_obstacle_distance_m,
        "time",
        m.time_s
    )
}

/// `planlab run`: one episode (or APF or arm run), metrics on stdout.
pub fn run(path: &Path, args: &RunArgs<'_>) -> Result<(), String> {
    let at = |e: &dyn std::fmt::Display| format!("{}: {e}", path.display());
    // `barn:N`: the BARN world's scenario for the planner and seed asked for.
    let barn = path
        .to_str()
        .map(|s| load::barn::scenario_json(s, args.planner, args.seed))
        .transpose()?
        .flatten();
    let text = match barn {
        Some(text) => text,
        None => load::read_text(path)?,
    };
    // What the run reads may not be what it writes: `--trace s.json`.
    let mut inputs = vec![path.to_path_buf()];
    if let Some(world) = path.to_str().and_then(|s| s.strip_prefix("barn:")) {
        inputs.push(PathBuf::from(world));
    }
    let (scenario, grid) = edited_scenario(path, &text, args, &mut inputs)?;
    if let Some(t) = args.trace {
        crate::output::refuse_input("--trace", t, &inputs)?;
    }
    if let Some(m) = args.mcap {
        crate::output::refuse_input("--mcap", m, &inputs)?;
    }
    let started = scenario.start(grid).map_err(|e| at(&e))?;
    let done = match (started, args.mcap) {
        (AnyRun::Robot(mut ep), Some(out)) => {
            // The same steps as `run`, logged as they happen.
            let (bytes, _) = planlab_mcap::record_episode(&mut ep).map_err(|e| at(&e))?;
            crate::output::write_atomically(out, &bytes)?;
            let m = EpisodeMetrics::of_episode(&ep);
            FinishedRun::Robot(ep, m)
        }
        (_, Some(_)) => {
            return Err(format!(
                "--mcap: {} is not a robot episode (APF and arm runs have no MCAP export)",
                path.display()
            ))
        }
        (run, None) => run.run().map_err(|e| at(&e))?,
    };
    let hash = done.trace_hash();
    // The name comes from the file: escape sequences in it must not reach
    // the terminal (JSON output escapes them itself).
    let title = if scenario.name().is_empty() {
        path.display().to_string()
    } else {
        planlab_core::text::one_line(scenario.name())
    };
    match &done {
        FinishedRun::Robot(ep, m) => {
            let seed = scenario.seed();
            report_episode(scenario.name(), &title, ep, m, seed, hash, args)
        }
        FinishedRun::Apf(r, m) => report_apf(scenario.name(), &title, r, m, hash, args),
        FinishedRun::Arm(ep, m) => crate::arm_cmds::report(&title, &scenario, ep, m, hash, args),
    }
}

/// The report of a finished robot episode (`--trace` writes its trace CSV).
fn report_episode(
    name: &str,
    title: &str,
    ep: &Episode,
    m: &EpisodeMetrics,
    seed: u64,
    hash: u64,
    args: &RunArgs<'_>,
) -> Result<(), String> {
    if let Some(t) = args.trace {
        crate::output::write_atomically(t, ep.trace().to_csv().as_bytes())?;
    }
    let report = RunReport {
        scenario: name,
        planner: &ep.planner_choice().name,
        seed,
        steps: ep.steps(),
        trace_hash: format!("{hash:016x}"),
        collision_seen: ep.collision_seen(),
        global_path: ep.car_guide().map(|c| GlobalPathReport {
            algorithm: "hybrid-astar",
            length_m: c.route().length,
            cusps: c.route().cusps,
            expanded: c.route().expanded,
            replans: c.replans(),
        }),
        metrics: m,
    };
    if args.json {
        emit(&(serde_json::to_string(&report).map_err(|e| e.to_string())? + "\n"))?;
    } else {
        emit(&(format!("{title} — planner {}, seed {}", report.planner, report.seed) + "\n"))?;
        emit(&metrics_table(m))?;
        emit(&(format!("{:<22}{}", "steps", report.steps) + "\n"))?;
        emit(&(format!("{:<22}{}", "trace hash", report.trace_hash) + "\n"))?;
        if let Some(g) = &report.global_path {
            let line = format!(
                "{:<22}{} {:.3} m, {} cusps, {} replans",
                "global path", g.algorithm, g.length_m, g.cusps, g.replans
            );
            emit(&(line + "\n"))?;
        }
        if let Some(seen) = report.collision_seen {
            let what = if seen {
                "yes (the laser had shown it)"
            } else {
                "no (out of the laser's sight)"
            };
            emit(&(format!("{:<22}{what}", "collision seen") + "\n"))?;
        }
    }
    Ok(())
}

pub(crate) fn opt(v: Option<f64>, digits: usize) -> String {
    v.map_or_else(|| "—".into(), |x| format!("{x:.digits$}"))
}

/// The metrics as `name value unit` lines.
fn metrics_table(m: &EpisodeMetrics) -> String {
    let rows = [
        (
            "outcome",
            match m.collision {
                Some(c) => format!("{} ({c})", m.outcome),
                None => m.outcome.to_string(),
            },
            "",
        ),
        ("time", format!("{:.2}", m.time_s), "s"),
        ("path length", format!("{:.3}", m.path_length_m), "m"),
        ("min clearance", format!("{:.3}", m.min_clearance_m), "m"),
        ("mean clearance", format!("{:.3}", m.mean_clearance_m), "m"),
        ("total turning", format!("{:.3}", m.total_turn_rad), "rad"),
        ("max turning", format!("{:.3}", m.max_turn_rad), "rad"),
        ("speed drops", m.speed_drops.to_string(), ""),
        ("temp-goal switches", m.temp_goal_switches.to_string(), ""),
        ("mean tracking error", opt(m.mean_tracking_error_m, 3), "m"),
        ("max tracking error", opt(m.max_tracking_error_m, 3), "m"),
        ("tracking error var", opt(m.tracking_error_var_m2, 4), "m²"),
        (
            "wheel loads > 40 N",
            opt(m.load_ok_share.map(|x| 100.0 * x), 1),
            "%",
        ),
    ];
    rows.iter()
        .map(|(k, v, u)| {
            let u = if v == "—" { "" } else { u };
            format!("{k:<22}{v} {u}").trim_end().to_string() + "\n"
        })
        .collect()
}

/// `planlab planners`: the catalogue.
pub fn planners(json: bool) -> Result<(), String> {
    let list = planners::list();
    if json {
        emit(&(serde_json::to_string(&list).map_err(|e| e.to_string())? + "\n"))?;
        return Ok(());
    }
    for p in &list {
        emit(&(format!("{} — {}", p.name, p.summary) + "\n"))?;
        emit(&(format!("  paper: {}", p.paper) + "\n"))?;
        let w = p.fields.iter().map(|f| f.name.len()).max().unwrap_or(0);
        for f in &p.fields {
            let default = match f.default.as_f64() {
                Some(x) if f.default.is_f64() => {
                    let t = format!("{x:.4}");
                    let t = t.trim_end_matches('0');
                    if t.ends_with('.') {
                        format!("{t}0")
                    } else {
                        t.to_string()
                    }
                }
                _ => f.default.to_string(),
            };
            let unit = if f.unit.is_empty() || f.unit == "1" {
                String::new()
            } else {
                format!(" {}", f.unit)
            };
            // The plain name first, then the doc (with the paper's symbol).
            let doc = if f.label.is_empty() {
                f.doc.clone()
            } else {
                format!("{} — {}", f.label, f.doc)
            };
            emit(&(format!("  {:<w$}  {:>10}{unit:<7}  {doc}", f.name, default) + "\n"))?;
        }
        emit("\n")?;
    }
    Ok(())
}

/// `planlab train-predictor`: trains the SimpleRNN, writes its weights,
/// prints the held-out MSE beside constant velocity's.
pub fn train_predictor(
    seed: u64,
    epochs: u32,
    trajectories: usize,
    out: &Path,
    json: bool,
) -> Result<(), String> {
    use planlab_core::apf::rnn::{train, TrainConfig};
    let cfg = TrainConfig {
        seed,
        epochs,
        trajectories,
        ..TrainConfig::default()
    };
    // The folder must exist: a typo in --out should not create folders.
    let dir = out
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or_else(|| Path::new("."));
    if !dir.is_dir() {
        return Err(format!(
            "--out {}: the folder {} does not exist",
            out.display(),
            dir.display()
        ));
    }
    let w = train(&cfg).map_err(|e| e.to_string())?;
    let r = &w.report;
    // Weights that fail the quality check never replace the file (a NaN
    // MSE fails too).
    let beats = r.heldout_mse < r.heldout_mse_constant_velocity;
    if !beats {
        return Err(format!(
            "the RNN does not beat constant velocity on the held-out set (MSE {:.3e} vs {:.3e} m²); {} not written",
            r.heldout_mse,
            r.heldout_mse_constant_velocity,
            out.display()
        ));
    }
    let text = serde_json::to_string_pretty(&w).map_err(|e| e.to_string())? + "\n";
    crate::output::write_atomically(out, text.as_bytes())?;
    let r = &w.report;
    if json {
        outln!("{}", serde_json::to_string(r).map_err(|e| e.to_string())?);
    } else {
        outln!(
            "SimpleRNN 6 → 15 tanh → 3, 5 steps of 0.1 s, 0.5 s ahead; seed {}",
            r.seed
        );
        outln!("{:<34}{}", "epochs", r.epochs);
        outln!(
            "{:<34}{} / {}",
            "windows train / held-out",
            r.train_samples,
            r.heldout_samples
        );
        outln!("{:<34}{:.3e} m²", "train MSE", r.train_mse);
        outln!("{:<34}{:.3e} m²", "held-out MSE, RNN", r.heldout_mse);
        outln!(
            "{:<34}{:.3e} m²",
            "held-out MSE, constant velocity",
            r.heldout_mse_constant_velocity
        );
        outln!("weights written to {}", out.display());
    }
    Ok(())
}
