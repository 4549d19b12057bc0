//! BARN runs (docs/algorithms.md §barn): a world, a planner and a seed make
//! one scenario — the Jackal with its laser on the world, the map unknown
//! to the planner (a costmap built from the scans, [`crate::sim::perception`])
//! — run to the end and scored as the challenge scores; and the statistics
//! of many runs per planner.
//!
//! Declared choices that are not BARN's (every other value is in the
//! module's constants or the README of `assets/barn/`):
//! - control period 0.1 s for every planner (the baseline's controller runs
//!   at 20 Hz in the challenge);
//! - the Jackal's limits: 2 m/s, 4 rad/s, 20 m/s², 25 rad/s² (Clearpath's
//!   controller configuration), reversing at most 0.1 m/s (move_base's
//!   escape speed, so the baseline can back up);
//! - laser noise σ = 0.01 m (seeded per run; 0 is an option); no odometry
//!   noise: planners know their true pose;
//! - the \[L\] planners assume a 360° LiDAR (\[L\] assumption 3): they carry
//!   one with the UST-10's resolution and range; every other planner gets
//!   the 270° UST-10;
//! - the papers' DWA planners keep the speed and acceleration limits of
//!   their papers' robots as their own caps ([`paper_caps`]), as the
//!   baseline keeps its 0.5 m/s; the potential-field planners and DWB take
//!   the Jackal's limits;
//! - a run ends only by success, collision or the 100 s timeout (no
//!   early "stuck" cut).

use serde::{Deserialize, Serialize};

use super::{score, BarnError, BarnWorld, GOAL, GOAL_TOLERANCE, START, TIMEOUT};
use crate::map::OccupancyGrid;
use crate::metrics::EpisodeMetrics;
use crate::num::Rng;
use crate::planners::PlannerChoice;
use crate::reproduce::stats::Share;
use crate::scenario::{Scenario, ScenarioPoint, WorldPoint};
use crate::sim::perception::{LaserConfig, ScanCostmapConfig};
use crate::sim::{Episode, PerceptionSpec, SimConfig};
use crate::world::{Drive, Footprint, Outcome, RobotLimits, RobotSpec};
use thiserror::Error;

/// Control period of BARN runs, s (declared: module doc).
pub const DT: f64 = 0.1;
/// Laser noise σ of BARN runs unless chosen otherwise, m (declared).
pub const DEFAULT_NOISE: f64 = 0.01;

/// Every planner that can drive an unknown map, in the order tables list
/// them: the baselines first, then the global+local stacks on the scan
/// costmap, then the laser-only planners.
pub const PLANNERS: &[&str] = &[
    "move-base-dwa",
    "dwb",
    "dwa",
    "improved-dwa",
    "fusion-53",
    "safe-dual-dwa",
    "preliminary-fusion",
    "apf",
    "sampling-apf",
    "lidar-dwa",
    "lidar-apf",
    "scan-dwa",
    "scan-apf",
    "tangent-bug",
    "rs-apf",
    "rrt-shortcut",
];

/// The planners that assume a 360° LiDAR (\[L\] and its peers).
fn wants_full_circle(planner: &str) -> bool {
    matches!(
        planner,
        "lidar-dwa"
            | "lidar-apf"
            | "scan-dwa"
            | "scan-apf"
            | "tangent-bug"
            | "rs-apf"
            | "rrt-shortcut"
    )
}

/// The Jackal as BARN has it: the footprint rectangle, differential drive,
/// the limits declared in the module doc.
pub fn jackal() -> RobotSpec {
    RobotSpec {
        drive: Drive::Differential,
        footprint: Footprint::Rectangle {
            length: super::JACKAL_LENGTH,
            width: super::JACKAL_WIDTH,
        },
        limits: RobotLimits {
            v_max: 2.0,
            v_min: -0.1,
            vy_max: 0.0,
            w_max: 4.0,
            acc_v: 20.0,
            acc_vy: 0.0,
            acc_w: 25.0,
        },
        wheel_base: 0.37559,
    }
}

/// The speed and acceleration caps `[v_max, ω_max, a_v, a_ω]` of the
/// robot in each paper's own experiments (the scenarios of
/// `assets/scenarios/`), which its planners keep on the Jackal as a ROS
/// planner keeps its `max_vel_x`: \[T\]'s (dwa, improved-dwa, fusion-53),
/// \[S\]'s (safe-dual-dwa, preliminary-fusion), \[L\]'s (the DWA under
/// lidar-dwa and the peers). `None`: the planner takes the Jackal's limits.
pub fn paper_caps(planner: &str) -> Option<[f64; 4]> {
    let deg = |d: f64| d.to_radians();
    match planner {
        "dwa" | "improved-dwa" | "fusion-53" => Some([1.0, deg(40.0), 0.2, deg(50.0)]),
        "safe-dual-dwa" | "preliminary-fusion" => Some([1.0, deg(20.0), 0.2, deg(50.0)]),
        "lidar-dwa" | "scan-dwa" | "tangent-bug" | "rs-apf" | "rrt-shortcut" => {
            Some([1.0, deg(300.0), 0.5, deg(720.0)])
        }
        _ => None,
    }
}

/// The planner `name` as it runs on BARN: the baseline with the challenge's
/// move_base parameters, the papers' DWAs capped at their papers' robot
/// limits ([`paper_caps`]), every other field its paper's or source's
/// default.
pub fn planner_choice(name: &str) -> PlannerChoice {
    use serde_json::json;
    let caps = paper_caps(name).map(|[v, w, a, aw]| {
        json!({ "max_speed": v, "max_turn": w, "max_accel": a, "max_turn_accel": aw })
    });
    let config = match (name, caps) {
        ("move-base-dwa", _) => json!({
            "max_vel_x": 0.5,
            "min_vel_x": 0.1,
            "max_vel_theta": 1.57,
            "acc_lim_x": 10.0,
            "acc_lim_theta": 20.0,
            "sim_time": 2.0,
            "sim_granularity": 0.02,
            "vx_samples": 6,
            "vtheta_samples": 20,
            "meter_scoring": true,
            "pdist_scale": 0.75,
            "gdist_scale": 1.0,
            "occdist_scale": 0.1,
            "costmap": {
                "inflation_radius": 0.30,
                "footprint_padding": super::JACKAL_PADDING,
            },
        }),
        ("dwb", _) => json!({
            "costmap": {
                "inflation_radius": 0.30,
                "footprint_padding": super::JACKAL_PADDING,
            },
        }),
        ("dwa", Some(c)) => c,
        ("improved-dwa" | "fusion-53" | "safe-dual-dwa" | "preliminary-fusion", Some(c)) => {
            json!({ "dwa": c })
        }
        (_, Some(c)) => json!({ "motion": c }),
        (_, None) => json!({}),
    };
    PlannerChoice {
        name: name.into(),
        config,
    }
}

/// Why a BARN run could not be made.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum RunError {
    /// The world itself is bad.
    #[error(transparent)]
    World(#[from] BarnError),
    /// The scenario cannot hold the world (a point off its map).
    #[error("BARN world {world}: {why}")]
    Scenario {
        /// World id.
        world: u32,
        /// What went wrong.
        why: String,
    },
    /// The episode could not start.
    #[error("BARN world {world}, {planner}: {why}")]
    Run {
        /// World id.
        world: u32,
        /// Planner name.
        planner: String,
        /// The simulator's or planner's error.
        why: String,
    },
}

/// How BARN runs are made.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct BarnOptions {
    /// Laser range noise σ, m (0: exact scans).
    pub noise_std: f64,
}

impl Default for BarnOptions {
    fn default() -> Self {
        BarnOptions {
            noise_std: DEFAULT_NOISE,
        }
    }
}

/// The seed of run `run` on world `world` in a sweep seeded `seed`: every
/// planner gets the same noise on the same world and run.
pub fn run_seed(seed: u64, world: u32, run: u32) -> u64 {
    let mut r = Rng::new(seed ^ (u64::from(world) << 32) ^ u64::from(run));
    r.next_u64()
}

/// The scenario of `world` driven by `planner` with `seed`: the map is the
/// world at [`super::TRUTH_RESOLUTION`], inline.
pub fn scenario(
    world: &BarnWorld,
    planner: &str,
    seed: u64,
    opts: &BarnOptions,
) -> Result<(Scenario, OccupancyGrid), RunError> {
    let grid = world.grid(super::TRUTH_RESOLUTION)?;
    let point = |p: [f64; 2], what: &str| -> Result<ScenarioPoint, RunError> {
        let (col, row) = grid
            .world_to_cell(p[0], p[1])
            .ok_or_else(|| RunError::Scenario {
                world: world.id,
                why: format!("the {what} is off the world's map"),
            })?;
        Ok(ScenarioPoint {
            col: col as u32,
            row: row as u32,
            world: Some(WorldPoint { x: p[0], y: p[1] }),
        })
    };
    let mut s = Scenario::new(
        format!("BARN world {}", world.id),
        grid.clone(),
        crate::global::GridPos { col: 0, row: 0 },
        crate::global::GridPos { col: 0, row: 0 },
    );
    s.description = format!(
        "BARN world {} (Perille et al. 2020), {planner} with only the laser; OT = {:.2} s",
        world.id,
        world.optimal_time()
    );
    s.start = point([START.x, START.y], "start")?;
    s.goal = point(GOAL, "goal")?;
    s.start_yaw = Some(START.yaw);
    s.robot = Some(jackal());
    s.local_planner = Some(planner_choice(planner));
    s.sim = Some(SimConfig {
        dt: DT,
        max_time: TIMEOUT,
        goal_tolerance: GOAL_TOLERANCE,
        stuck_time: TIMEOUT,
        stuck_distance: 0.0,
        sensing_range: 30.0,
        record_rollouts: false,
        unknown_is_obstacle: false,
    });
    s.seed = Some(seed);
    s.perception = Some(PerceptionSpec {
        laser: LaserConfig {
            fov_deg: if wants_full_circle(planner) {
                360.0
            } else {
                super::LASER_FOV_DEG
            },
            resolution_deg: super::LASER_STEP_DEG,
            range: super::LASER_RANGE,
            noise_std: opts.noise_std,
        },
        costmap: ScanCostmapConfig::default(),
    });
    Ok((s, grid))
}

/// One scored BARN run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BarnRun {
    /// World number.
    pub world: u32,
    /// Planner name.
    pub planner: String,
    /// Run number (0-based).
    pub run: u32,
    /// The episode's seed.
    pub seed: u64,
    /// How the episode ended (`reached`, `collision`, `timeout`).
    pub outcome: Outcome,
    /// Simulated time at the end, s.
    pub time: f64,
    /// The world's optimal time OT, s.
    pub optimal_time: f64,
    /// The challenge's score.
    pub score: f64,
    /// Path length driven, m.
    pub path_length: f64,
    /// FNV-1a of the trace (what `planlab run` prints).
    pub trace_hash: u64,
    /// For a collision: whether the laser had shown what the robot hit
    /// ([`Episode::collision_seen`]; a seen one is a planner's bug);
    /// `None` otherwise, or when not known (a CSV from before the column).
    #[serde(default)]
    pub collision_seen: Option<bool>,
}

impl BarnRun {
    /// Whether the run succeeded.
    pub fn success(&self) -> bool {
        self.outcome == Outcome::Reached
    }
}

/// Runs `planner` on `world` once with `seed`.
pub fn run_one(
    world: &BarnWorld,
    planner: &str,
    run: u32,
    seed: u64,
    opts: &BarnOptions,
) -> Result<BarnRun, RunError> {
    let (s, grid) = scenario(world, planner, seed, opts)?;
    let mut ep = Episode::from_scenario(&s, grid).map_err(|e| RunError::Run {
        world: world.id,
        planner: planner.into(),
        why: e.to_string(),
    })?;
    ep.run();
    let m = EpisodeMetrics::of_episode(&ep);
    // BARN knows three endings; "stuck" cannot happen with the stuck time
    // at the timeout, and counts as a timeout if it does.
    let outcome = match m.outcome {
        Outcome::Stuck => Outcome::Timeout,
        o => o,
    };
    let ot = world.optimal_time();
    Ok(BarnRun {
        world: world.id,
        planner: planner.into(),
        run,
        seed,
        outcome,
        time: m.time_s,
        optimal_time: ot,
        score: score(outcome == Outcome::Reached, m.time_s, ot),
        path_length: m.path_length_m,
        trace_hash: ep.trace().hash(),
        collision_seen: ep.collision_seen(),
    })
}

/// A mean with a bootstrap 95 % interval.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct MeanCi {
    /// The mean.
    pub mean: f64,
    /// Percentile bootstrap 95 % interval of the mean.
    pub ci95: [f64; 2],
}

/// Bootstrap resamples of a mean's interval.
pub const BOOTSTRAP_RESAMPLES: usize = 2000;

impl MeanCi {
    /// The mean of `values` with a percentile bootstrap interval from
    /// [`BOOTSTRAP_RESAMPLES`] resamples drawn with a fixed seed (so the
    /// figures repeat); `None` for no values.
    pub fn of(values: &[f64]) -> Option<MeanCi> {
        let groups: Vec<Vec<f64>> = values.iter().map(|&v| vec![v]).collect();
        MeanCi::of_clusters(&groups)
    }

    /// The mean of all values of `groups` with a cluster bootstrap
    /// interval: each resample draws whole groups (a benchmark's worlds
    /// with all their runs) with replacement, so runs of one world are not
    /// taken for independent draws. With one value per group this is
    /// [`MeanCi::of`]; `None` for no values.
    pub fn of_clusters(groups: &[Vec<f64>]) -> Option<MeanCi> {
        // Sorted first, so the same runs give the same interval in any
        // order (a sweep's CSV rows, merged chunks).
        let mut groups: Vec<Vec<f64>> = groups
            .iter()
            .filter(|g| !g.is_empty())
            .map(|g| {
                let mut g = g.clone();
                g.sort_by(f64::total_cmp);
                g
            })
            .collect();
        groups.sort_by(|a, b| {
            a.iter()
                .zip(b)
                .map(|(x, y)| x.total_cmp(y))
                .find(|o| o.is_ne())
                .unwrap_or(a.len().cmp(&b.len()))
        });
        let w = groups.len();
        if w == 0 {
            return None;
        }
        let sums: Vec<(f64, usize)> = groups.iter().map(|g| (g.iter().sum(), g.len())).collect();
        let total = sums.iter().map(|s| s.1).sum::<usize>();
        let mean = sums.iter().map(|s| s.0).sum::<f64>() / total as f64;
        let mut rng = Rng::new(0xB00_757A9);
        let mut means: Vec<f64> = (0..BOOTSTRAP_RESAMPLES)
            .map(|_| {
                let (s, c) = (0..w).fold((0.0, 0usize), |(s, c), _| {
                    let g = sums[(rng.next_u64() % w as u64) as usize];
                    (s + g.0, c + g.1)
                });
                s / c as f64
            })
            .collect();
        means.sort_by(f64::total_cmp);
        let at = |q: f64| means[((q * (BOOTSTRAP_RESAMPLES - 1) as f64).round()) as usize];
        Some(MeanCi {
            mean,
            ci95: [at(0.025), at(0.975)],
        })
    }
}

/// One planner's figures over a set of runs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BarnStats {
    /// Runs counted.
    pub runs: u32,
    /// Worlds the runs were on.
    pub worlds: u32,
    /// Success rate with its Wilson interval (over worlds: see
    /// [`Share::clustered`]).
    pub success: Share,
    /// Collision rate.
    pub collision: Share,
    /// Timeout rate.
    pub timeout: Share,
    /// Collisions with something the laser had shown (planners' bugs).
    pub collisions_seen: u32,
    /// Collisions not known to be seen or not (runs without the column).
    pub collisions_unclassified: u32,
    /// Mean time of the successful runs, s.
    pub mean_time: Option<f64>,
    /// Mean score with its bootstrap interval (resampling worlds: see
    /// [`MeanCi::of_clusters`]).
    pub score: Option<MeanCi>,
}

impl BarnStats {
    /// The figures of `runs`.
    pub fn of<'a>(runs: impl IntoIterator<Item = &'a BarnRun> + Clone) -> BarnStats {
        let all: Vec<&BarnRun> = runs.into_iter().collect();
        let times: Vec<f64> = all.iter().filter(|r| r.success()).map(|r| r.time).collect();
        // Runs of one world are not independent draws: the intervals
        // resample worlds.
        let mut by_world = std::collections::BTreeMap::<u32, Vec<&BarnRun>>::new();
        for r in &all {
            by_world.entry(r.world).or_default().push(r);
        }
        let share = |hit: &dyn Fn(&BarnRun) -> bool| {
            let groups: Vec<(u32, u32)> = by_world
                .values()
                .map(|rs| (rs.iter().filter(|r| hit(r)).count() as u32, rs.len() as u32))
                .collect();
            Share::clustered(&groups)
        };
        let scores: Vec<Vec<f64>> = by_world
            .values()
            .map(|rs| rs.iter().map(|r| r.score).collect())
            .collect();
        BarnStats {
            runs: all.len() as u32,
            worlds: by_world.len() as u32,
            success: share(&|r| r.success()),
            collision: share(&|r| r.outcome == Outcome::Collision),
            timeout: share(&|r| r.outcome == Outcome::Timeout),
            collisions_seen: all
                .iter()
                .filter(|r| r.collision_seen == Some(true))
                .count() as u32,
            collisions_unclassified: all
                .iter()
                .filter(|r| r.outcome == Outcome::Collision && r.collision_seen.is_none())
                .count() as u32,
            mean_time: (!times.is_empty()).then(|| times.iter().sum::<f64>() / times.len() as f64),
            score: MeanCi::of_clusters(&scores),
        }
    }
}
