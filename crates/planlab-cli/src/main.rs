//! `planlab`: command-line front end of planlab-core.
//!
//! Every failure prints one line `planlab: error: …` on stderr and exits
//! non-zero; usage errors exit 2 (clap's convention). Output goes through
//! `outln!`/`out!`: a reader that closes the pipe early (`planlab plan
//! --json | head -1`) ends the program quietly, where `println!` panics.

/// `print!` that ends the program quietly when stdout's reader went away.
macro_rules! out {
    ($($t:tt)*) => { $crate::write_out(&format!($($t)*)) };
}
/// `println!` that ends the program quietly when stdout's reader went away.
macro_rules! outln {
    ($($t:tt)*) => { $crate::write_out(&format!("{}\n", format_args!($($t)*))) };
}

mod arm_cmds;
mod barn_cmd;
mod batch_arm;
mod batch_cmd;
mod bench;
mod gen_cmd;
mod grid_cmds;
mod output;
mod peer;
mod reproduce_cmd;
mod serve;
mod sim_cmds;

/// File reading is shared with the Python package.
use planlab_files as load;

use clap::{Parser, Subcommand, ValueEnum};
use planlab_core::global::plan::{Algorithm, GridPlanOptions, GridPlanOverrides};
use planlab_core::global::{Diagonal, GridPos, Heuristic, PlanError};
use planlab_core::sampling::SamplingAlgorithm;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "planlab",
    version,
    about = "Robot path planning you can watch, poke and measure"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

/// A planner on the command line: every grid [`Algorithm`] by its name,
/// with its one-line description in `--help`, and `hybrid-astar` (a car
/// path over poses, `None` here).
#[derive(Clone, Copy)]
struct AlgoArg(Option<Algorithm>);

/// Every planner, in [`Algorithm::ALL`] order, then Hybrid A* (clap wants
/// a static slice).
const ALGO_ARGS: [AlgoArg; Algorithm::ALL.len() + 1] = {
    let mut out = [AlgoArg(None); Algorithm::ALL.len() + 1];
    let mut i = 0;
    while i < Algorithm::ALL.len() {
        out[i] = AlgoArg(Some(Algorithm::ALL[i].0));
        i += 1;
    }
    out
};

impl ValueEnum for AlgoArg {
    fn value_variants<'a>() -> &'a [Self] {
        &ALGO_ARGS
    }

    fn to_possible_value(&self) -> Option<clap::builder::PossibleValue> {
        Some(match self.0 {
            Some(a) => clap::builder::PossibleValue::new(a.name()).help(a.description()),
            None => clap::builder::PossibleValue::new("hybrid-astar").help(
                "Hybrid A*: a car path of arcs at --turning-radius over x,y,θ poses (plan only)",
            ),
        })
    }
}

impl AlgoArg {
    /// The grid planner, or why Hybrid A* is not one.
    fn grid(self) -> Result<Algorithm, String> {
        self.0.ok_or_else(|| {
            "hybrid-astar plans car poses, not grid cells; use it with `planlab plan`".to_string()
        })
    }
}

/// A planner of `planlab plan`: a grid planner, a sampling planner
/// (`planlab_core::sampling`), each by its name, or Hybrid A* for a car.
#[derive(Clone, Copy)]
enum PlanAlgoArg {
    Grid(Algorithm),
    Sampling(SamplingAlgorithm),
    HybridAStar,
}

/// Every grid planner, then every sampling planner, then Hybrid A*.
const PLAN_ALGO_ARGS: [PlanAlgoArg; Algorithm::ALL.len() + SamplingAlgorithm::ALL.len() + 1] = {
    let mut out =
        [PlanAlgoArg::HybridAStar; Algorithm::ALL.len() + SamplingAlgorithm::ALL.len() + 1];
    let mut i = 0;
    while i < Algorithm::ALL.len() {
        out[i] = PlanAlgoArg::Grid(Algorithm::ALL[i].0);
        i += 1;
    }
    let mut j = 0;
    while j < SamplingAlgorithm::ALL.len() {
        out[i + j] = PlanAlgoArg::Sampling(SamplingAlgorithm::ALL[j].0);
        j += 1;
    }
    out
};

impl ValueEnum for PlanAlgoArg {
    fn value_variants<'a>() -> &'a [Self] {
        &PLAN_ALGO_ARGS
    }

    fn to_possible_value(&self) -> Option<clap::builder::PossibleValue> {
        let (name, help) = match self {
            PlanAlgoArg::Grid(a) => (a.name(), a.description()),
            PlanAlgoArg::Sampling(a) => (a.name(), a.description()),
            PlanAlgoArg::HybridAStar => (
                "hybrid-astar",
                "Hybrid A*: a car path of arcs at --turning-radius over x,y,θ poses",
            ),
        };
        Some(clap::builder::PossibleValue::new(name).help(help))
    }
}

#[derive(Clone, Copy, ValueEnum)]
enum CurveKind {
    /// Forward only (Dubins 1957).
    Dubins,
    /// Forward and reverse (Reeds & Shepp 1990).
    #[value(name = "reeds-shepp")]
    ReedsShepp,
}

#[derive(Clone, Copy, ValueEnum)]
enum HeuristicArg {
    Manhattan,
    Euclidean,
    Octile,
    Chebyshev,
}

impl From<HeuristicArg> for Heuristic {
    fn from(h: HeuristicArg) -> Self {
        match h {
            HeuristicArg::Manhattan => Heuristic::Manhattan,
            HeuristicArg::Euclidean => Heuristic::Euclidean,
            HeuristicArg::Octile => Heuristic::Octile,
            HeuristicArg::Chebyshev => Heuristic::Chebyshev,
        }
    }
}

#[derive(Clone, Copy, ValueEnum)]
enum DiagonalArg {
    /// 4-connected.
    Never,
    /// 8-connected, both side cells free (Moving AI rule).
    #[value(name = "no-corner-cutting")]
    NoCornerCutting,
    /// 8-connected, at least one side cell free.
    #[value(name = "one-side-free")]
    OneSideFree,
    /// 8-connected through any corner.
    Always,
}

impl From<DiagonalArg> for Diagonal {
    fn from(d: DiagonalArg) -> Self {
        match d {
            DiagonalArg::Never => Diagonal::Never,
            DiagonalArg::NoCornerCutting => Diagonal::NoCornerCutting,
            DiagonalArg::OneSideFree => Diagonal::OneSideFree,
            DiagonalArg::Always => Diagonal::Always,
        }
    }
}

#[derive(Clone, Copy, ValueEnum)]
enum GenKindArg {
    Maze,
    Rooms,
    Random,
}

impl From<GenKindArg> for planlab_core::map::generate::GeneratorKind {
    fn from(k: GenKindArg) -> Self {
        match k {
            GenKindArg::Maze => Self::Maze,
            GenKindArg::Rooms => Self::Rooms,
            GenKindArg::Random => Self::Random,
        }
    }
}

#[derive(Subcommand)]
enum BenchKind {
    /// Our A* and JPS against the `pathfinding` crate's astar on a Moving AI
    /// scenario, then every other `--algo` planner as a row (ms per query,
    /// ratio to A*, expansions, cost / optimum); prints one JSON line.
    Grid {
        /// Moving AI .map file.
        map: PathBuf,
        /// Its .scen file.
        scen: PathBuf,
        /// Least repetitions of the whole row set per planner (more run until
        /// each planner has been timed for 0.2 s; the fastest is kept).
        #[arg(long, default_value_t = 3)]
        reps: usize,
        /// Only these further planners beside A* and JPS, comma-separated
        /// `--algo` names (e.g. bidirectional-astar) [default: all].
        #[arg(long, value_delimiter = ',')]
        algo: Vec<String>,
    },
    /// Sampling planners on Moving AI rows against Theta*: per map and
    /// planner, runs solved, the median cost gap to Theta* and the median
    /// time per query. The answers depend only on the seeds.
    Sampling {
        /// Moving AI .map files, each with its MAP.scen beside it.
        #[arg(required = true)]
        maps: Vec<PathBuf>,
        /// Rows per map, spread evenly over the .scen file (shortest to
        /// longest query; the rows of bench_ompl.py).
        #[arg(long, default_value_t = 6)]
        rows: usize,
        /// Iterations per run (RRT and RRT-Connect stop at their first path).
        #[arg(long, default_value_t = 20_000)]
        iterations: u64,
        /// Planners, comma-separated [default: every sampling planner].
        #[arg(long, value_delimiter = ',')]
        algo: Vec<String>,
        /// Seeds per row: 0 … N−1.
        #[arg(long, default_value_t = 1)]
        seeds: u64,
        /// The disc's radius, metres (Moving AI maps: 1 m per cell).
        #[arg(long, default_value_t = 0.4, allow_hyphen_values = true)]
        radius: f64,
        /// One JSON document (every run and the summary) instead of a table.
        #[arg(long)]
        json: bool,
    },
    /// One DWA step of the reference scene (200 × 200 map, 20 movers,
    /// 20 × 40 samples, 3 s horizon), timed in blocks of STEPS steps; the
    /// native side of the browser benchmark. Prints one JSON line.
    Step {
        /// Steps per timed block.
        #[arg(long, default_value_t = 50)]
        steps: usize,
        /// Timed blocks (after one untimed warm-up block).
        #[arg(long, default_value_t = 5)]
        blocks: usize,
    },
    /// Every query of a Moving AI scenario planned with A* in one pass
    /// (planner and grid built once), timed per block of INNER passes; the
    /// native side of the browser benchmark's A* figure. Prints one JSON line.
    Scen {
        /// Moving AI .map file.
        map: PathBuf,
        /// Its .scen file (all rows are used).
        scen: PathBuf,
        /// Timed blocks (after one untimed pass).
        #[arg(long, default_value_t = 5)]
        reps: usize,
        /// Whole-scenario passes per timed block.
        #[arg(long, default_value_t = 1)]
        inner: usize,
    },
}

#[derive(Subcommand)]
enum Command {
    /// Solve every row of a Moving AI scenario and compare with the optimum.
    Scen {
        /// Moving AI .map file.
        map: PathBuf,
        /// Its .scen file.
        scen: PathBuf,
        /// Planner.
        #[arg(long, value_enum, default_value = "astar")]
        algo: AlgoArg,
        /// One JSON line per row, then a summary line.
        #[arg(long)]
        json: bool,
    },
    /// Plan one path on a ROS .yaml, Moving AI .map or scenario .json.
    Plan {
        /// Map file.
        map: PathBuf,
        /// Start cell COLUMN,ROW (row 0 at the top of the image); a scenario
        /// .json supplies its own when omitted. With hybrid-astar: the pose
        /// X,Y,THETA (world metres, degrees).
        #[arg(long, allow_hyphen_values = true)]
        start: Option<String>,
        /// Goal cell COLUMN,ROW; a scenario .json supplies its own when omitted.
        /// With hybrid-astar: X,Y,THETA (world metres, degrees).
        #[arg(long, allow_hyphen_values = true)]
        goal: Option<String>,
        /// Planner [default: astar, or the scenario's]. The sampling
        /// planners (rrt … bit-star) plan a disc of --radius cells in
        /// continuous space, seeded by --seed, for --iterations.
        #[arg(long, value_enum)]
        algo: Option<PlanAlgoArg>,
        /// Sampling planners: iterations to run (RRT and RRT-Connect stop
        /// at their first path) [default: 10000].
        #[arg(long)]
        iterations: Option<u64>,
        /// Sampling planners: seed of the random stream [default: 0].
        #[arg(long)]
        seed: Option<u64>,
        /// Sampling planners and hybrid-astar: the robot's disc radius,
        /// metres [default: hybrid-astar 0.2 m; sampling planners 0.4 of a
        /// cell].
        #[arg(long, value_name = "r", allow_hyphen_values = true)]
        radius: Option<f64>,
        /// Sampling planners: shorten the path by seeded shortcuts.
        #[arg(long)]
        shortcut: bool,
        /// A*/JPS heuristic [default: octile, or the scenario's].
        #[arg(long, value_enum)]
        heuristic: Option<HeuristicArg>,
        /// A* heuristic weight, ≥ 1 [default: 1, or the scenario's].
        #[arg(long, allow_hyphen_values = true)]
        weight: Option<f64>,
        /// Diagonal move rule [default: no-corner-cutting, or the scenario's].
        #[arg(long, value_enum)]
        diagonal: Option<DiagonalArg>,
        /// Grow obstacles by this radius first, metres [default: 0, or the scenario's].
        #[arg(long, allow_hyphen_values = true)]
        inflate: Option<f64>,
        /// Treat unknown cells as free.
        #[arg(long)]
        allow_unknown: bool,
        /// Extract key points (Wu 2022 §3.2.1).
        #[arg(long)]
        keypoints: bool,
        /// Bottom-Up feature nodes with this maximum error, cells (Ge & Li 2022 §4.1).
        #[arg(long, value_name = "EPS", allow_hyphen_values = true)]
        bottom_up: Option<f64>,
        /// Safe A* safety weight ε.
        #[arg(long, allow_hyphen_values = true)]
        epsilon: Option<f64>,
        /// Hybrid A*: minimum turning radius, metres.
        #[arg(long, value_name = "R", allow_hyphen_values = true)]
        turning_radius: Option<f64>,
        /// Hybrid A*: the car may reverse (Reeds-Shepp).
        #[arg(long)]
        reverse: bool,
        /// Hybrid A*: a rectangular footprint LENGTHxWIDTH, metres, centred
        /// on the pose (instead of the --radius disc), e.g. 0.6x0.4.
        #[arg(long, value_name = "LxW", allow_hyphen_values = true)]
        footprint: Option<String>,
        /// JSON output.
        #[arg(long)]
        json: bool,
        /// Also write the search as a Posthoc search trace (format 1.4.0,
        /// JSON; open it in ShortestPathLab's Posthoc with the map).
        #[arg(long, value_name = "FILE")]
        trace_posthoc: Option<PathBuf>,
    },
    /// The shortest car path between two poses ignoring obstacles: its
    /// length and word (Dubins: forward only; Reeds-Shepp: with reverse).
    Curve {
        /// dubins or reeds-shepp.
        #[arg(value_enum)]
        kind: CurveKind,
        /// Start pose X,Y,THETA (metres, degrees).
        #[arg(long, allow_hyphen_values = true)]
        from: String,
        /// Goal pose X,Y,THETA (metres, degrees).
        #[arg(long, allow_hyphen_values = true)]
        to: String,
        /// Minimum turning radius, metres.
        #[arg(long, allow_hyphen_values = true)]
        radius: f64,
        /// JSON output.
        #[arg(long)]
        json: bool,
    },
    /// Run one simulated episode of a scenario .json and print its metrics
    /// (an arm scenario, with an `arm` section, runs the arm episode;
    /// `--planner` then picks its predictor: none, constant-velocity, rnn).
    Run {
        /// Scenario JSON (a referenced map file is found relative to it).
        scenario: PathBuf,
        /// Local planner by registry name (see `planlab planners`); its
        /// config is reset to the defaults when the name changes.
        #[arg(long)]
        planner: Option<String>,
        /// Seed of the episode's random streams (with --variant: the
        /// batch's seed, default 0).
        #[arg(long)]
        seed: Option<u64>,
        /// Run variant K of `planlab batch` (same --seed and --jitter) to
        /// replay a row of its CSV.
        #[arg(long, value_name = "K")]
        variant: Option<u32>,
        /// With --variant: the batch's jitter, metres [default: 0.3; an arm
        /// scenario 0.02].
        #[arg(long, allow_hyphen_values = true, requires = "variant")]
        jitter: Option<f64>,
        /// Edit the scenario before reading it: a dotted path and a JSON
        /// value (or plain text), e.g. `sim.dt=0.05`, `movers.0.radius=0.4`,
        /// `local_planner.config.alpha=0.2`. Repeatable.
        #[arg(long = "set", value_name = "PATH=VALUE", allow_hyphen_values = true)]
        set: Vec<String>,
        /// One JSON object instead of a table.
        #[arg(long)]
        json: bool,
        /// Write the per-step trace as CSV to this file.
        #[arg(long, value_name = "FILE.csv")]
        trace: Option<PathBuf>,
        /// Write the run as an MCAP file (Foxglove schemas, JSON): pose,
        /// laser scan, global and local paths, movers and the map per step.
        #[arg(long, value_name = "FILE.mcap")]
        mcap: Option<PathBuf>,
    },
    /// List the local planners with their config fields, units and defaults.
    Planners {
        /// JSON output (an array of planners).
        #[arg(long)]
        json: bool,
    },
    /// Run the papers' experiments (all, or one by id): on their presets,
    /// or with --variants N on a seeded family of scenes with success
    /// rates, per-clause shares, paired effects and a verdict (reproduced /
    /// partly / not reproduced). A relation that does not hold is a
    /// result, not an error: the exit status is 0 whenever the runs ran.
    Reproduce {
        /// Experiment id, e.g. T-fig3-2; all when omitted.
        id: Option<String>,
        /// One JSON line per experiment.
        #[arg(long)]
        json: bool,
        /// Run the family: variant 0 is the preset, 1…N−1 are perturbed
        /// (start/goal, obstacles, movers, speeds, seed), in parallel.
        #[arg(long)]
        variants: Option<u32>,
        /// Seed of the family.
        #[arg(long, default_value_t = 0)]
        seed: u64,
        /// PATH=a,b,c: run the family once per value of a declared value
        /// (e.g. apf.config.predict_dt=0.1,0.5,0.8), set on every run.
        #[arg(long)]
        sweep: Option<String>,
        /// Write every variant's scenario files (ID-vK-RUN.json) into this
        /// existing folder; `planlab run` replays each.
        #[arg(long, value_name = "DIR")]
        write_variants: Option<PathBuf>,
        /// List the experiments (clauses, family, deviations) without running.
        #[arg(long)]
        list: bool,
        /// Run the family (60 variants unless --variants says) and show,
        /// per perturbation, its range, the reason for it, and how the
        /// share of variants where the relation holds splits at the median
        /// of what it drew: which perturbation the verdict is most
        /// sensitive to.
        #[arg(long)]
        explain: bool,
    },
    /// Run the planners on BARN worlds (Perille et al. 2020; the BARN
    /// Challenge): the Jackal with only its laser in an unknown cluttered
    /// world, scored as the challenge scores (success · OT / clip(T, 2·OT,
    /// 8·OT)). Per planner: success, collision and timeout rates with
    /// Wilson 95% intervals, mean time, mean score with a bootstrap
    /// interval, overall and by difficulty class. `planlab run barn:N
    /// --planner P --seed S` replays one run.
    Barn {
        /// BARN folders (the challenge's jackal_helper/worlds/BARN) or
        /// world_N.world files; default: the 250 public worlds the
        /// repository holds.
        paths: Vec<PathBuf>,
        /// Worlds to run, e.g. `1,2,10-20` [default: all loaded].
        #[arg(long)]
        worlds: Option<String>,
        /// Comma-separated planner names [default: every planner that can
        /// drive an unknown map].
        #[arg(long, value_delimiter = ',')]
        planners: Vec<String>,
        /// Runs per world and planner (they differ by the laser's noise).
        #[arg(long, default_value_t = 1)]
        runs: u32,
        /// Seed of the sweep.
        #[arg(long, default_value_t = 0)]
        seed: u64,
        /// Laser range noise σ, metres (0: exact scans).
        #[arg(long, default_value_t = planlab_core::barn::run::DEFAULT_NOISE)]
        noise: f64,
        /// One JSON line per planner and class, then a footer line.
        #[arg(long, conflicts_with = "markdown")]
        json: bool,
        /// Markdown tables: every planner overall, then success and score
        /// by difficulty class.
        #[arg(long)]
        markdown: bool,
        /// Write one CSV row per run (with the command that replays it).
        #[arg(long, value_name = "FILE.csv")]
        csv: Option<PathBuf>,
        /// Run nothing: summarise the runs of earlier --csv files (chunks
        /// of one sweep merge; --worlds and --planners filter them).
        #[arg(long, value_name = "FILE.csv")]
        from_csv: Vec<PathBuf>,
    },
    /// Run N seeded variants of a scenario (start, goal and movers
    /// jittered; an arm scenario: the tool's start and goal and the hand's
    /// speed) with several planners in parallel; print the success rate
    /// and the mean, median and 95% confidence interval of every metric.
    Batch {
        /// Scenario JSON (a referenced map file is found relative to it).
        scenario: PathBuf,
        /// Comma-separated planner names [default: the scenario's].
        #[arg(long, value_delimiter = ',')]
        planners: Vec<String>,
        /// Number of variants; variant 0 is the scenario as written.
        #[arg(long, default_value_t = 20)]
        variants: u32,
        /// Seed of the variants (and of their episodes).
        #[arg(long, default_value_t = 0)]
        seed: u64,
        /// Largest shift of start, goal and each mover path per axis, metres
        /// [default: 0.3]. An arm scenario: the largest move of the tool's
        /// start and goal (in a ball) [default: 0.02]; its hand's speed
        /// varies by ±20 %.
        #[arg(long, allow_hyphen_values = true)]
        jitter: Option<f64>,
        /// Edit the scenario before the variants are drawn: a dotted path and
        /// a JSON value, as `planlab run --set` (e.g. `arm.table_z_m=0.72`).
        /// Repeatable.
        #[arg(long = "set", value_name = "PATH=VALUE", allow_hyphen_values = true)]
        set: Vec<String>,
        /// Write one CSV row per episode to this file.
        #[arg(long, value_name = "FILE.csv")]
        csv: Option<PathBuf>,
        /// JSON lines: one summary per planner, then a footer.
        #[arg(long)]
        json: bool,
    },
    /// Train the SimpleRNN obstacle predictor (Wu thesis §5.2) on synthetic
    /// hand-reaching trajectories (seeded) and write its weights; prints
    /// the held-out MSE beside constant velocity's.
    TrainPredictor {
        /// Seed of the data, initial weights and shuffling.
        #[arg(long, default_value_t = 7)]
        seed: u64,
        /// Passes over the training set.
        #[arg(long, default_value_t = 60)]
        epochs: u32,
        /// Training trajectories (6 reaches each).
        #[arg(long, default_value_t = 80)]
        trajectories: usize,
        /// Where to write the weights JSON.
        #[arg(long, default_value = "assets/predictor/rnn.json")]
        out: PathBuf,
        /// The report as one JSON object.
        #[arg(long)]
        json: bool,
    },
    /// Generate a seeded random map (maze, rooms or random fill) with a
    /// start and goal the robot can drive between; writes a scenario .json
    /// (map inline) or a Moving AI .map. Same settings, same map as the
    /// robot page's Generate.
    Generate {
        /// Generator.
        #[arg(value_enum)]
        kind: GenKindArg,
        /// Map width, metres.
        #[arg(long, default_value_t = 10.0, allow_hyphen_values = true)]
        width: f64,
        /// Map height, metres.
        #[arg(long, default_value_t = 8.0, allow_hyphen_values = true)]
        height: f64,
        /// Cell size, metres.
        #[arg(long, default_value_t = 0.1, allow_hyphen_values = true)]
        resolution: f64,
        /// Seed of the generator.
        #[arg(long, default_value_t = 0)]
        seed: u64,
        /// Maze corridor / rooms door width, metres.
        #[arg(long, default_value_t = 1.4, allow_hyphen_values = true)]
        corridor: f64,
        /// Wall thickness (maze, rooms), metres.
        #[arg(long, default_value_t = 0.2, allow_hyphen_values = true)]
        wall: f64,
        /// Smallest room side (rooms), metres.
        #[arg(long, default_value_t = 2.5, allow_hyphen_values = true)]
        room: f64,
        /// Covered fraction of the area (random), 0 to 0.6.
        #[arg(long, default_value_t = 0.2, allow_hyphen_values = true)]
        density: f64,
        /// Block side (random), metres.
        #[arg(long, default_value_t = 0.4, allow_hyphen_values = true)]
        block: f64,
        /// Radius of the robot that must fit from start to goal, metres.
        #[arg(long, default_value_t = 0.2, allow_hyphen_values = true)]
        robot_radius: f64,
        /// Output file: .json (scenario with the map inline) or .map.
        #[arg(long, value_name = "FILE")]
        out: PathBuf,
        /// Print a JSON line (sizes, grid hash, start, goal) instead of text.
        #[arg(long)]
        json: bool,
    },
    /// Benchmarks.
    Bench {
        #[command(subcommand)]
        kind: BenchKind,
    },
    /// Serve the playground (a built site folder) over HTTP on loopback.
    Serve {
        /// Site folder to serve (must contain index.html).
        #[arg(long, default_value = "web/dist")]
        dir: PathBuf,
        /// Loopback address to bind (127.0.0.1, ::1 or localhost).
        #[arg(long, default_value = "127.0.0.1")]
        host: String,
        /// Port; 0 picks a free one (printed on start).
        #[arg(long, default_value_t = 8080)]
        port: u16,
    },
}

fn run(cli: Cli) -> Result<(), String> {
    match cli.command {
        Command::Serve { dir, host, port } => serve::serve(&dir, &host, port),
        Command::Run {
            scenario,
            planner,
            seed,
            variant,
            jitter,
            set,
            json,
            trace,
            mcap,
        } => sim_cmds::run(
            &scenario,
            &sim_cmds::RunArgs {
                planner: planner.as_deref(),
                seed,
                set: &set,
                json,
                trace: trace.as_deref(),
                mcap: mcap.as_deref(),
                variant: variant.map(|k| (k, jitter)),
            },
        ),
        Command::Planners { json } => sim_cmds::planners(json),
        Command::Curve {
            kind,
            from,
            to,
            radius,
            json,
        } => grid_cmds::curve(
            matches!(kind, CurveKind::ReedsShepp),
            grid_cmds::parse_pose(&from, "--from")?,
            grid_cmds::parse_pose(&to, "--to")?,
            radius,
            json,
        ),
        Command::Barn {
            paths,
            worlds,
            planners,
            runs,
            seed,
            noise,
            json,
            markdown,
            csv,
            from_csv,
        } => barn_cmd::barn(&barn_cmd::BarnArgs {
            paths: &paths,
            worlds: worlds.as_deref(),
            planners: &planners,
            runs,
            seed,
            noise,
            format: if json {
                barn_cmd::Format::Json
            } else if markdown {
                barn_cmd::Format::Markdown
            } else {
                barn_cmd::Format::Text
            },
            csv: csv.as_deref(),
            from_csv: &from_csv,
        }),
        Command::Batch {
            scenario,
            planners,
            variants,
            seed,
            jitter,
            set,
            csv,
            json,
        } => batch_cmd::batch(
            &scenario,
            &batch_cmd::BatchArgs {
                planners: &planners,
                variants,
                seed,
                jitter,
                set: &set,
                csv: csv.as_deref(),
                json,
            },
        ),
        Command::TrainPredictor {
            seed,
            epochs,
            trajectories,
            out,
            json,
        } => sim_cmds::train_predictor(seed, epochs, trajectories, &out, json),
        Command::Generate {
            kind,
            width,
            height,
            resolution,
            seed,
            corridor,
            wall,
            room,
            density,
            block,
            robot_radius,
            out,
            json,
        } => gen_cmd::run(
            &planlab_core::map::generate::GenerateConfig {
                kind: kind.into(),
                width_m: width,
                height_m: height,
                resolution,
                seed,
                corridor_m: corridor,
                wall_m: wall,
                room_m: room,
                density,
                block_m: block,
                robot_radius,
            },
            &out,
            json,
        ),
        Command::Reproduce {
            id,
            json,
            variants,
            seed,
            sweep,
            write_variants,
            list,
            explain,
        } => reproduce_cmd::reproduce(&reproduce_cmd::ReproduceArgs {
            id: id.as_deref(),
            json,
            variants,
            seed,
            sweep: sweep.as_deref(),
            write_variants: write_variants.as_deref(),
            list,
            explain,
        }),
        Command::Scen {
            map,
            scen,
            algo,
            json,
        } => {
            let mismatches = grid_cmds::scen(&map, &scen, algo.grid()?, json)?;
            if mismatches > 0 {
                return Err(format!("{mismatches} rows missed the optimal cost"));
            }
            Ok(())
        }
        Command::Plan {
            map,
            start,
            goal,
            algo,
            iterations,
            seed,
            radius,
            shortcut,
            heuristic,
            weight,
            diagonal,
            inflate,
            allow_unknown,
            keypoints,
            bottom_up,
            epsilon,
            turning_radius,
            reverse,
            footprint,
            json,
            trace_posthoc,
        } => {
            let (grid, scenario) = load::load_any(&map)?;
            if let Some(PlanAlgoArg::HybridAStar) = algo {
                let foreign = [
                    ("--iterations", iterations.is_some()),
                    ("--seed", seed.is_some()),
                    ("--shortcut", shortcut),
                    ("--heuristic", heuristic.is_some()),
                    ("--keypoints", keypoints),
                    ("--trace-posthoc", trace_posthoc.is_some()),
                ];
                if let Some((flag, _)) = foreign.iter().find(|f| f.1) {
                    return Err(format!("{flag} does not apply to hybrid-astar"));
                }
                let (Some(start), Some(goal)) = (start, goal) else {
                    return Err("hybrid-astar needs --start X,Y,THETA and --goal X,Y,THETA (metres, degrees)".into());
                };
                if footprint.is_some() && radius.is_some() {
                    return Err(
                        "--footprint LxW and --radius r are two footprints: give one".into(),
                    );
                }
                let car = grid_cmds::CarArgs {
                    start: grid_cmds::parse_pose(&start, "--start")?,
                    goal: grid_cmds::parse_pose(&goal, "--goal")?,
                    turning_radius: turning_radius
                        .ok_or("hybrid-astar needs --turning-radius R (metres)")?,
                    reverse,
                    radius,
                    rect: footprint
                        .as_deref()
                        .map(grid_cmds::parse_footprint)
                        .transpose()?,
                    allow_unknown,
                    json,
                };
                return grid_cmds::plan_car(&map, &grid, &car);
            }
            if turning_radius.is_some() || reverse || footprint.is_some() {
                return Err(
                    "--turning-radius, --reverse and --footprint belong to --algo hybrid-astar"
                        .into(),
                );
            }
            let sampling_flags = [
                ("--iterations", iterations.is_some()),
                ("--seed", seed.is_some()),
                ("--radius", radius.is_some()),
                ("--shortcut", shortcut),
            ];
            let algo = match algo {
                Some(PlanAlgoArg::Sampling(algorithm)) => {
                    let grid_flags = [
                        ("--heuristic", heuristic.is_some()),
                        ("--weight", weight.is_some()),
                        ("--diagonal", diagonal.is_some()),
                        ("--inflate", inflate.is_some()),
                        ("--keypoints", keypoints),
                        ("--bottom-up", bottom_up.is_some()),
                        ("--epsilon", epsilon.is_some()),
                        ("--trace-posthoc", trace_posthoc.is_some()),
                    ];
                    if let Some((flag, _)) = grid_flags.iter().find(|f| f.1) {
                        return Err(format!(
                            "{flag} applies to the grid planners, not to {}",
                            algorithm.name()
                        ));
                    }
                    let cell = |flag: Option<String>, name: &str, from: Option<GridPos>| match (
                        flag, from,
                    ) {
                        (Some(s), _) => grid_cmds::parse_cell(&s),
                        (None, Some(p)) => Ok(p),
                        (None, None) => {
                            Err(format!("--{name} COLUMN,ROW is required for this map"))
                        }
                    };
                    let args = grid_cmds::SamplingArgs {
                        start: cell(start, "start", scenario.as_ref().map(|s| s.start.pos()))?,
                        goal: cell(goal, "goal", scenario.as_ref().map(|s| s.goal.pos()))?,
                        algorithm,
                        iterations: iterations.unwrap_or(10_000),
                        seed: seed.unwrap_or(0),
                        radius: radius.map_or(0.4, |r| r / grid.resolution()),
                        shortcut,
                        allow_unknown,
                        json,
                    };
                    return grid_cmds::plan_sampling(&map, &grid, &args);
                }
                Some(PlanAlgoArg::Grid(a)) => Some(a),
                Some(PlanAlgoArg::HybridAStar) | None => None,
            };
            if let Some((flag, _)) = sampling_flags.iter().find(|f| f.1) {
                return Err(format!(
                    "{flag} applies to the sampling planners (--algo rrt, rrt-connect, rrt-star, informed-rrt-star, prm, prm-star, bit-star){}",
                    if *flag == "--radius" { " and hybrid-astar" } else { "" }
                ));
            }
            // Flags override the scenario's planner section, which overrides
            // the defaults.
            let overrides = GridPlanOverrides {
                algorithm: algo,
                heuristic: heuristic.map(Into::into),
                weight,
                diagonal: diagonal.map(Into::into),
                inflate_m: inflate,
                allow_unknown,
                keypoints,
                bottom_up_eps: bottom_up,
                epsilon,
            };
            let options = scenario
                .as_ref()
                .map_or_else(GridPlanOptions::default, |s| s.grid_planner)
                .overridden(&overrides)
                .map_err(|e| match e {
                    // The flag's name: `--inflate NaN: must be …`.
                    PlanError::InvalidConfig(m) => format!("--{m}"),
                    e => e.to_string(),
                })?;
            let endpoint = |flag: Option<String>, name: &str, from_scenario: Option<GridPos>| match (
                flag,
                from_scenario,
            ) {
                (Some(s), _) => grid_cmds::parse_cell(&s),
                (None, Some(p)) => Ok(p),
                (None, None) => Err(format!("--{name} COLUMN,ROW is required for this map")),
            };
            // Said on stderr: stdout stays the plan (or its JSON).
            if let Some(note) =
                planlab_core::map::costmap::inflation_note(options.inflate_m, grid.resolution())
            {
                eprintln!("planlab: note: {note}");
            }
            let args = grid_cmds::PlanArgs {
                start: endpoint(start, "start", scenario.as_ref().map(|s| s.start.pos()))?,
                goal: endpoint(goal, "goal", scenario.as_ref().map(|s| s.goal.pos()))?,
                options,
                json,
                trace_posthoc,
            };
            grid_cmds::plan(&map, &grid, &args)
        }
        Command::Bench {
            kind:
                BenchKind::Grid {
                    map,
                    scen,
                    reps,
                    algo,
                },
        } => {
            let only = algo
                .iter()
                .map(|n| {
                    n.trim()
                        .parse::<Algorithm>()
                        .map_err(|e| format!("--algo: {e}"))
                })
                .collect::<Result<Vec<_>, _>>()?;
            let grid = load::load_movingai(&map)?;
            let rows = load::load_scen(&scen)?;
            planlab_core::map::io::movingai::check_scen_against_map(&rows, &grid)
                .map_err(|e| format!("{} does not fit {}: {e}", scen.display(), map.display()))?;
            let report = bench::bench_grid(&grid, &rows, reps.max(1), &only)?;
            outln!(
                "{}",
                serde_json::to_string(&report).map_err(|e| e.to_string())?
            );
            Ok(())
        }
        Command::Bench {
            kind:
                BenchKind::Sampling {
                    maps,
                    rows,
                    iterations,
                    algo,
                    seeds,
                    radius,
                    json,
                },
        } => {
            let algos = if algo.is_empty() {
                SamplingAlgorithm::ALL.iter().map(|(a, _)| *a).collect()
            } else {
                algo.iter()
                    .map(|n| {
                        SamplingAlgorithm::from_name(n.trim()).ok_or_else(|| {
                            format!(
                                "--algo {n:?}: not a sampling planner (one of {})",
                                SamplingAlgorithm::ALL
                                    .iter()
                                    .map(|(_, n)| *n)
                                    .collect::<Vec<_>>()
                                    .join(", ")
                            )
                        })
                    })
                    .collect::<Result<Vec<_>, _>>()?
            };
            if rows == 0 {
                return Err("--rows 0: must be at least 1".into());
            }
            let mut picked = Vec::new();
            let mut resolution = None;
            for map in &maps {
                let grid = load::load_movingai(map)?;
                let scen = PathBuf::from(format!("{}.scen", map.display()));
                let all = load::load_scen(&scen)?;
                planlab_core::map::io::movingai::check_scen_against_map(&all, &grid).map_err(
                    |e| format!("{} does not fit {}: {e}", scen.display(), map.display()),
                )?;
                if all.is_empty() {
                    return Err(format!("{} has no rows", scen.display()));
                }
                resolution.get_or_insert(grid.resolution());
                let rows = bench::pick_rows(all.len(), rows)
                    .into_iter()
                    .map(|i| (i, all[i].clone()))
                    .collect();
                picked.push(bench::SamplingMap {
                    name: map
                        .file_stem()
                        .map_or_else(|| map.display().to_string(), |s| s.to_string_lossy().into()),
                    grid,
                    rows,
                });
            }
            if !(radius.is_finite() && radius >= 0.0) {
                return Err(format!(
                    "--radius {radius}: must be a finite number of metres ≥ 0"
                ));
            }
            let cells = radius / resolution.unwrap_or(1.0);
            let report = bench::bench_sampling(&picked, &algos, iterations, seeds, cells)?;
            if json {
                outln!(
                    "{}",
                    serde_json::to_string(&report).map_err(|e| e.to_string())?
                );
            } else {
                out!("{}", bench::sampling_table(&report));
            }
            Ok(())
        }
        Command::Bench {
            kind: BenchKind::Step { steps, blocks },
        } => {
            let report = bench::bench_step(steps, blocks)?;
            outln!(
                "{}",
                serde_json::to_string(&report).map_err(|e| e.to_string())?
            );
            Ok(())
        }
        Command::Bench {
            kind:
                BenchKind::Scen {
                    map,
                    scen,
                    reps,
                    inner,
                },
        } => {
            let grid = load::load_movingai(&map)?;
            let text = load::read_text(&scen)?;
            let report = bench::bench_scen(&grid, &text, reps, inner)?;
            outln!(
                "{}",
                serde_json::to_string(&report).map_err(|e| e.to_string())?
            );
            Ok(())
        }
    }
}

/// clap's usage error as one line: its message and the list under it
/// (missing arguments, valid values, the tip), without the usage block.
fn usage_error_line(e: &clap::Error) -> String {
    let text = e.render().to_string();
    let body = text.split("\nUsage:").next().unwrap_or(&text);
    let body = body.split("\nFor more information").next().unwrap_or(body);
    let body = body.trim().strip_prefix("error:").unwrap_or(body).trim();
    let mut line = body.split_whitespace().collect::<Vec<_>>().join(" ");
    line = line.replace(" tip:", "; tip:");
    format!("{line} (see --help)")
}

/// Writes to stdout (see `sim_cmds::emit`: a closed pipe exits 0); any
/// other write error is the usual one-line error, exit 1.
fn write_out(text: &str) {
    if let Err(e) = sim_cmds::emit(text) {
        eprintln!("planlab: error: {e}");
        std::process::exit(1);
    }
}

fn main() -> ExitCode {
    use clap::error::ErrorKind;
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) if matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion) => {
            e.exit()
        }
        Err(e) => {
            let line = if e.kind() == ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand {
                "a command is required (see planlab --help)".to_string()
            } else {
                usage_error_line(&e)
            };
            eprintln!("planlab: error: {line}");
            return ExitCode::from(2);
        }
    };
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            // One line whatever the message quotes (the core escapes its
            // own; this covers file names and I/O errors).
            eprintln!("planlab: error: {}", planlab_core::text::one_line(&e));
            ExitCode::FAILURE
        }
    }
}
