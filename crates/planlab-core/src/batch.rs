//! Batch experiments: seeded variants of one scenario (start, goal and
//! movers jittered; for an arm, [`arm_variant`]) and per-planner
//! statistics over their runs. The CLI's
//! `planlab batch` runs the episodes in parallel; everything here is pure
//! and deterministic, so a variant is the same whichever thread runs it.

mod arm;

pub use arm::{
    arm_metric_values, arm_planners, arm_variant, run_arm_variant, summarise_arm, ArmBatchRun,
    ARM_HAND_SPEED_REL, ARM_JITTER_M, ARM_METRIC_NAMES,
};

use std::collections::BTreeMap;

use serde::Serialize;
use thiserror::Error;

use crate::map::OccupancyGrid;
use crate::metrics::EpisodeMetrics;
use crate::num::Rng;
use crate::planners::{self, PlannerChoice};
use crate::scenario::{Scenario, ScenarioPoint, WorldPoint};
use crate::sim::{Episode, Outcome, SimError};
use crate::world::MotionModel;

/// Why a batch could not be set up.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum BatchError {
    /// The jitter radius is negative or not finite.
    #[error("jitter must be a finite number of metres from 0 to {}, got {}", crate::num::fmt_num(crate::num::MAX_PARAM), crate::num::fmt_num(*.0))]
    BadJitter(f64),
    /// No valid placement was found for a variant within the retry budget.
    #[error("variant {index}: no valid start/goal/mover placement in {tries} draws within {} m (last error: {last})", crate::num::fmt_num(*.jitter))]
    NoPlacement {
        /// Variant index.
        index: u32,
        /// Draws tried.
        tries: u32,
        /// Jitter radius, metres.
        jitter: f64,
        /// The last rejection.
        last: String,
    },
    /// The scenario is an APF one: variants jitter a robot's start, goal
    /// and movers, or an arm's start, goal and hand ([`arm_variant`]).
    #[error("{0} scenarios have no batch variants")]
    NoVariants(&'static str),
    /// The planner list names an unknown planner or one twice.
    #[error("{0}")]
    BadPlanners(String),
    /// The variant's arm episode could not be built or run.
    #[error("variant {index}, planner {planner}: {source}")]
    Arm {
        /// Variant index.
        index: u32,
        /// Planner name.
        planner: String,
        /// Why.
        source: crate::arm::ArmError,
    },
    /// The variant's episode could not be built.
    #[error("variant {index}, planner {planner}: {source}")]
    Episode {
        /// Variant index.
        index: u32,
        /// Planner name.
        planner: String,
        /// Why.
        source: SimError,
    },
}

/// The planner `name` in a batch of a scenario whose own planner is `own`:
/// the scenario's own keeps its tuning; others start from their papers'
/// defaults, as `planlab run --planner` does.
pub fn choice_for(own: &PlannerChoice, name: &str) -> PlannerChoice {
    if own.name == name {
        own.clone()
    } else {
        PlannerChoice::named(name)
    }
}

/// Refuses an APF scenario: its run has no robot, map start or movers to
/// jitter (drawn as a robot's, it failed with a placement at (0, 0)).
fn robot_only(base: &Scenario) -> Result<(), BatchError> {
    match base.apf {
        Some(_) => Err(BatchError::NoVariants(
            crate::scenario::ScenarioKind::Apf.name(),
        )),
        None => Ok(()),
    }
}

/// The planners of a batch of `base` by name (trimmed); none = the
/// scenario's own. Unknown names and repeats are refused.
pub fn planner_choices(
    base: &Scenario,
    names: &[String],
) -> Result<Vec<PlannerChoice>, BatchError> {
    robot_only(base)?;
    let own = base.local_planner.clone().unwrap_or_default();
    if names.is_empty() {
        return Ok(vec![own]);
    }
    let known: Vec<String> = planners::list().into_iter().map(|p| p.name).collect();
    let mut out: Vec<PlannerChoice> = Vec::new();
    for name in names {
        let name = name.trim();
        if !known.iter().any(|k| k == name) {
            return Err(BatchError::BadPlanners(format!(
                "unknown planner `{name}`; known: {}",
                known.join(", ")
            )));
        }
        if out.iter().any(|c| c.name == name) {
            return Err(BatchError::BadPlanners(format!("`{name}` is listed twice")));
        }
        out.push(choice_for(&own, name));
    }
    Ok(out)
}

/// One finished episode of a batch.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BatchRun {
    /// Variant index.
    pub variant: u32,
    /// Planner name.
    pub planner: String,
    /// The episode's own seed ([`variant_seed`]).
    pub seed: u64,
    /// Steps taken.
    pub steps: u64,
    /// FNV-1a of the trace (what `planlab batch --csv` writes).
    pub trace_hash: u64,
    /// What it measured.
    pub metrics: EpisodeMetrics,
}

/// Runs variant `index` (built by [`variant`]) with `choice`: the episode
/// `planlab batch` runs for that row, so any process (a thread, a Ray
/// task) that calls this gets the same trace hash.
pub fn run_variant(
    variant_scenario: &Scenario,
    grid: &OccupancyGrid,
    index: u32,
    choice: &PlannerChoice,
) -> Result<BatchRun, BatchError> {
    let mut s = variant_scenario.clone();
    s.local_planner = Some(choice.clone());
    let mut ep =
        Episode::from_scenario(&s, grid.clone()).map_err(|source| BatchError::Episode {
            index,
            planner: choice.name.clone(),
            source,
        })?;
    ep.run();
    Ok(BatchRun {
        variant: index,
        planner: choice.name.clone(),
        seed: s.seed.unwrap_or(0),
        steps: ep.steps(),
        trace_hash: ep.trace().hash(),
        metrics: EpisodeMetrics::of_episode(&ep),
    })
}

/// The default jitter of a robot batch, m: start, goal and each mover's
/// path move by up to this per axis (planlab's value: a few robot radii,
/// the same corridor, not another route).
pub const ROBOT_JITTER_M: f64 = 0.3;

/// The default jitter of a batch of a scenario of `kind`, m: the robot's
/// [`ROBOT_JITTER_M`] or the arm's [`ARM_JITTER_M`].
pub fn default_jitter(kind: crate::scenario::ScenarioKind) -> f64 {
    match kind {
        crate::scenario::ScenarioKind::Arm => ARM_JITTER_M,
        _ => ROBOT_JITTER_M,
    }
}

/// The most variants one batch may ask for: each is an episode per planner,
/// so this is hours of work already; more is a typo (`--variants
/// 4294967295` once ran for minutes with no output).
pub const MAX_VARIANTS: u32 = 10_000;

/// Draws tried per variant before giving up: a draw is rejected when the
/// episode cannot start (start or goal in a wall, robot on a mover …).
pub const MAX_DRAWS: u32 = 64;

/// The seed of variant `index` of a batch seeded with `seed`, also used as
/// the variant episode's own seed (so noise streams differ per variant).
pub fn variant_seed(seed: u64, index: u32) -> u64 {
    let mut r = Rng::new(seed ^ (u64::from(index) + 1).wrapping_mul(0x9E37_79B9_7F4A_7C15));
    r.next_u64()
}

/// Variant `index` of `base`: start and goal moved by up to `jitter` metres
/// (uniform in the square, each coordinate), every mover's path shifted by
/// its own offset of up to `jitter`, and the episode seed replaced by
/// [`variant_seed`]. Variant 0 keeps the positions of `base` (only the seed
/// changes), so the batch always contains the scenario as written. A draw
/// whose episode cannot start is redrawn, up to [`MAX_DRAWS`] times.
pub fn variant(
    base: &Scenario,
    grid: &OccupancyGrid,
    index: u32,
    seed: u64,
    jitter: f64,
) -> Result<Scenario, BatchError> {
    robot_only(base)?;
    if !(jitter.is_finite() && (0.0..=crate::num::MAX_PARAM).contains(&jitter)) {
        return Err(BatchError::BadJitter(jitter));
    }
    let vseed = variant_seed(seed, index);
    let mut rng = Rng::new(vseed);
    let mut last = String::new();
    for _ in 0..MAX_DRAWS {
        let mut s = base.clone();
        s.seed = Some(vseed);
        if index > 0 && jitter > 0.0 {
            let mut off = || [rng.range(-jitter, jitter), rng.range(-jitter, jitter)];
            let ds = off();
            let dg = off();
            s.start = shifted(grid, &base.start, base.start_world(grid), ds);
            s.goal = shifted(grid, &base.goal, base.goal_world(grid), dg);
            if let Some(movers) = s.movers.as_mut() {
                for m in movers.iter_mut() {
                    let d = off();
                    shift_motion(&mut m.motion, d);
                }
            }
        }
        match Episode::from_scenario(&s, grid.clone()) {
            Ok(_) => return Ok(s),
            Err(e) => last = e.to_string(),
        }
        if index == 0 || jitter == 0.0 {
            break; // nothing is random: a redraw would fail the same way
        }
    }
    Err(BatchError::NoPlacement {
        index,
        tries: if index == 0 || jitter == 0.0 {
            1
        } else {
            MAX_DRAWS
        },
        jitter,
        last,
    })
}

/// `p` (at world `w`) moved by `d`; off-map points keep the original, which
/// the episode check then accepts or the next draw replaces.
fn shifted(grid: &OccupancyGrid, p: &ScenarioPoint, w: [f64; 2], d: [f64; 2]) -> ScenarioPoint {
    let (x, y) = (w[0] + d[0], w[1] + d[1]);
    match grid.world_to_cell(x, y) {
        Some((col, row)) => ScenarioPoint {
            col: col as u32,
            row: row as u32,
            world: Some(WorldPoint { x, y }),
        },
        None => *p,
    }
}

fn shift_motion(m: &mut MotionModel, d: [f64; 2]) {
    let mv = |p: &mut [f64; 2]| {
        p[0] += d[0];
        p[1] += d[1];
    };
    match m {
        MotionModel::ConstantVelocity { start, .. } => mv(start),
        MotionModel::BackAndForth { a, b, .. } => {
            mv(a);
            mv(b);
        }
        MotionModel::WaypointLoop { points, .. } => points.iter_mut().for_each(mv),
        MotionModel::Scripted { samples } => samples.iter_mut().for_each(|s| {
            s.x += d[0];
            s.y += d[1];
        }),
    }
}

/// Mean, median and the 95% confidence interval of the mean of one metric
/// over a planner's runs.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Stat {
    /// Number of values.
    pub n: usize,
    /// Arithmetic mean.
    pub mean: f64,
    /// Median (mean of the two middle values for even n).
    pub median: f64,
    /// 95% confidence interval of the mean, Student t (the mean itself
    /// twice when n < 2).
    pub ci95: [f64; 2],
    /// Smallest value.
    pub min: f64,
    /// Largest value.
    pub max: f64,
}

impl Stat {
    /// Statistics of `values` (non-finite values are left out); `None`
    /// when no finite value remains.
    pub fn of(values: &[f64]) -> Option<Stat> {
        let mut v: Vec<f64> = values.iter().copied().filter(|x| x.is_finite()).collect();
        if v.is_empty() {
            return None;
        }
        v.sort_by(f64::total_cmp);
        let n = v.len();
        let mean = v.iter().sum::<f64>() / n as f64;
        let median = if n % 2 == 1 {
            v[n / 2]
        } else {
            0.5 * (v[n / 2 - 1] + v[n / 2])
        };
        let half = if n < 2 {
            0.0
        } else {
            let var = v.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / (n - 1) as f64;
            t95(n - 1) * (var / n as f64).sqrt()
        };
        Some(Stat {
            n,
            mean,
            median,
            ci95: [mean - half, mean + half],
            min: v[0],
            max: v[n - 1],
        })
    }
}

/// Two-sided 95% quantile of Student's t with `dof` degrees of freedom
/// (table to 30, then the normal approximation with a 1/dof correction).
fn t95(dof: usize) -> f64 {
    const T: [f64; 30] = [
        12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228, 2.201, 2.179, 2.160,
        2.145, 2.131, 2.120, 2.110, 2.101, 2.093, 2.086, 2.080, 2.074, 2.069, 2.064, 2.060, 2.056,
        2.052, 2.048, 2.045, 2.042,
    ];
    match dof {
        0 => f64::INFINITY,
        1..=30 => T[dof - 1],
        _ => 1.960 + 2.4 / dof as f64,
    }
}

/// One planner's results over all variants.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PlannerSummary {
    /// Registry name.
    pub planner: String,
    /// Episodes run.
    pub runs: usize,
    /// Episodes that reached the goal.
    pub reached: usize,
    /// Episodes per outcome name (`reached`, `collision`, `timeout`, `stuck`).
    pub outcomes: BTreeMap<String, usize>,
    /// reached / runs.
    pub success_rate: f64,
    /// Statistics per metric name ([`EpisodeMetrics`] fields), over the
    /// runs that reached the goal: a time or length of a run that never
    /// arrived is not comparable.
    pub metrics: BTreeMap<String, Stat>,
}

/// The names [`metric_values`] returns, in its order (CSV columns).
pub const METRIC_NAMES: [&str; 13] = [
    "time_s",
    "path_length_m",
    "min_clearance_m",
    "mean_clearance_m",
    "total_turn_rad",
    "max_turn_rad",
    "max_turn_step_rad",
    "speed_drops",
    "mean_tracking_error_m",
    "max_tracking_error_m",
    "load_ok_share",
    "wheel_load_share",
    "temp_goal_switches",
];

/// The numeric metrics of one run by their `planlab run` names.
pub fn metric_values(m: &EpisodeMetrics) -> [(&'static str, Option<f64>); 13] {
    [
        ("time_s", Some(m.time_s)),
        ("path_length_m", Some(m.path_length_m)),
        ("min_clearance_m", Some(m.min_clearance_m)),
        ("mean_clearance_m", Some(m.mean_clearance_m)),
        ("total_turn_rad", Some(m.total_turn_rad)),
        ("max_turn_rad", Some(m.max_turn_rad)),
        ("max_turn_step_rad", Some(m.max_turn_step_rad)),
        ("speed_drops", Some(f64::from(m.speed_drops))),
        ("mean_tracking_error_m", m.mean_tracking_error_m),
        ("max_tracking_error_m", m.max_tracking_error_m),
        ("load_ok_share", m.load_ok_share),
        ("wheel_load_share", m.wheel_load_share),
        ("temp_goal_switches", Some(f64::from(m.temp_goal_switches))),
    ]
}

/// Summarises one planner's runs.
pub fn summarise(planner: &str, runs: &[EpisodeMetrics]) -> PlannerSummary {
    let mut outcomes = BTreeMap::new();
    for m in runs {
        *outcomes.entry(m.outcome.as_str().to_string()).or_insert(0) += 1;
    }
    let ok: Vec<&EpisodeMetrics> = runs
        .iter()
        .filter(|m| m.outcome == Outcome::Reached)
        .collect();
    let mut columns: BTreeMap<&'static str, Vec<f64>> = BTreeMap::new();
    for m in &ok {
        for (k, v) in metric_values(m) {
            if let Some(v) = v {
                columns.entry(k).or_default().push(v);
            }
        }
    }
    let metrics = columns
        .into_iter()
        .filter_map(|(k, v)| Stat::of(&v).map(|s| (k.to_string(), s)))
        .collect();
    PlannerSummary {
        planner: planner.to_string(),
        runs: runs.len(),
        reached: ok.len(),
        outcomes,
        success_rate: if runs.is_empty() {
            0.0
        } else {
            ok.len() as f64 / runs.len() as f64
        },
        metrics,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stat_of_known_values() {
        let s = Stat::of(&[1.0, 2.0, 3.0, 4.0, f64::NAN]).unwrap();
        assert_eq!(s.n, 4);
        assert_eq!(s.mean, 2.5);
        assert_eq!(s.median, 2.5);
        // sd = 1.29099, t(3) = 3.182 → half width 2.054
        assert!((s.ci95[1] - 2.5 - 3.182 * 1.290_994_448_7 / 2.0).abs() < 1e-9);
        assert_eq!((s.min, s.max), (1.0, 4.0));
        assert!(Stat::of(&[f64::NAN]).is_none());
        let one = Stat::of(&[7.0]).unwrap();
        assert_eq!(one.ci95, [7.0, 7.0]);
    }

    #[test]
    fn t_quantiles_decrease_towards_normal() {
        assert!(t95(1) > t95(2));
        assert!((t95(30) - 2.042).abs() < 1e-12);
        assert!(t95(31) < t95(30) && t95(10_000) > 1.96);
    }

    #[test]
    fn variant_seeds_differ_and_repeat() {
        assert_eq!(variant_seed(5, 3), variant_seed(5, 3));
        assert_ne!(variant_seed(5, 3), variant_seed(5, 4));
        assert_ne!(variant_seed(5, 3), variant_seed(6, 3));
    }
}
