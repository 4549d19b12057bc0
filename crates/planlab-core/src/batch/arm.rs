//! Batches of an arm scenario (\[T\] §5.3.3): seeded variants of the
//! scene — the tool's start and goal moved, the hand faster or slower, the
//! hand's own seed — each run by several arm planners (the APF, RRT-Connect),
//! summarised per planner. What `planlab batch` does with an arm file, and
//! what the arm page's comparison runs; pure and deterministic, like the
//! robot batches.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use super::{variant_seed, BatchError, PlannerSummary, Stat, MAX_DRAWS};
use crate::apf::scene::path_hash;
use crate::arm::{ArmEpisode, ArmMetrics, ArmPlanner, PlanEffort};
use crate::num::Rng;
use crate::scenario::ArmScenario;
use crate::world::Outcome;

/// The default jitter of an arm batch, m: the largest move of the tool's
/// start and goal (uniform in a ball). 2 cm is the T-tab5-3 family's own
/// range (`planlab reproduce T-tab5-3`): the same reach, not another task.
pub const ARM_JITTER_M: f64 = 0.02;

/// The hand's speed of a variant is the scene's times a factor uniform in
/// 1 ± this: the ±20 % the T-tab5-3 family declares for the hand.
pub const ARM_HAND_SPEED_REL: f64 = 0.2;

/// The arm planners of a batch by name (`apf`, `rrt-connect`, trimmed);
/// none = the scenario's own. Unknown names and repeats are refused.
pub fn arm_planners(base: &ArmScenario, names: &[String]) -> Result<Vec<ArmPlanner>, BatchError> {
    if names.is_empty() {
        return Ok(vec![base.arm.planner]);
    }
    let mut out: Vec<ArmPlanner> = Vec::new();
    for name in names {
        let name = name.trim();
        let p = ArmPlanner::parse(name).map_err(|_| {
            let known: Vec<&str> = ArmPlanner::ALL.iter().map(|p| p.name()).collect();
            BatchError::BadPlanners(format!(
                "unknown arm planner `{name}`; known: {}",
                known.join(", ")
            ))
        })?;
        if out.contains(&p) {
            return Err(BatchError::BadPlanners(format!("`{name}` is listed twice")));
        }
        out.push(p);
    }
    Ok(out)
}

/// Variant `index` of an arm scenario: the tool's start and goal each moved
/// uniformly within a ball of `jitter` metres, the hand's speed scaled by a
/// factor uniform in 1 ± [`ARM_HAND_SPEED_REL`], and the scenario's seed
/// (the hand's jitter) replaced by [`variant_seed`]. Variant 0 keeps the
/// scene (only the seed changes). A draw whose episode cannot be built (a
/// start or goal out of reach) is redrawn, up to [`MAX_DRAWS`] times.
pub fn arm_variant(
    base: &ArmScenario,
    index: u32,
    seed: u64,
    jitter: f64,
) -> Result<ArmScenario, BatchError> {
    if !(jitter.is_finite() && (0.0..=crate::num::MAX_PARAM).contains(&jitter)) {
        return Err(BatchError::BadJitter(jitter));
    }
    let vseed = variant_seed(seed, index);
    let mut rng = Rng::new(vseed);
    let mut last = String::new();
    let tries = if index == 0 { 1 } else { MAX_DRAWS };
    for _ in 0..tries {
        let mut s = base.clone();
        s.seed = Some(vseed);
        if index > 0 {
            let ds = in_ball(&mut rng, jitter);
            let dg = in_ball(&mut rng, jitter);
            for i in 0..3 {
                s.arm.start[i] += ds[i];
                s.arm.goal[i] += dg[i];
            }
            s.arm.hand.speed *= rng.range(1.0 - ARM_HAND_SPEED_REL, 1.0 + ARM_HAND_SPEED_REL);
        }
        match ArmEpisode::from_scenario(&s) {
            Ok(_) => return Ok(s),
            Err(e) => last = e.to_string(),
        }
    }
    Err(BatchError::NoPlacement {
        index,
        tries,
        jitter,
        last,
    })
}

/// Uniform in the ball of radius `r`, by rejection from the cube.
fn in_ball(rng: &mut Rng, r: f64) -> [f64; 3] {
    loop {
        let p = [
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        ];
        if p.iter().map(|x| x * x).sum::<f64>() <= 1.0 {
            return p.map(|x| x * r);
        }
    }
}

/// One finished arm episode of a batch (its JSON is the Python package's
/// arm batch row, read back by its `summarise`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ArmBatchRun {
    /// Variant index.
    pub variant: u32,
    /// Planner name (`apf`, `rrt-connect`).
    pub planner: String,
    /// The episode's seed ([`variant_seed`]).
    pub seed: u64,
    /// FNV-1a of the tool's path (`planlab run`'s arm trace hash).
    pub trace_hash: u64,
    /// Outcome, tool path length, smallest distance to the hand, time.
    pub metrics: ArmMetrics,
    /// Joint-space distance travelled, rad.
    pub joint_path_length_rad: f64,
    /// Tool distance travelled sample by sample, m.
    pub gripper_path_length_m: f64,
    /// Smallest distance of the arm to the table top, m (no table: none).
    pub min_table_distance_m: Option<f64>,
    /// Planning effort (plans, iterations, collision checks).
    pub effort: PlanEffort,
}

/// Runs arm variant `index` (built by [`arm_variant`]) with `planner`; the
/// episode `planlab run --variant` replays.
pub fn run_arm_variant(
    variant_scenario: &ArmScenario,
    index: u32,
    planner: ArmPlanner,
) -> Result<ArmBatchRun, BatchError> {
    let mut s = variant_scenario.clone();
    s.arm.planner = planner;
    let fail = |source| BatchError::Arm {
        index,
        planner: planner.name().to_string(),
        source,
    };
    let mut ep = ArmEpisode::from_scenario(&s).map_err(fail)?;
    ep.run().map_err(fail)?;
    let table = s.arm.table_z_m.map(|_| ep.min_table_distance());
    Ok(ArmBatchRun {
        variant: index,
        planner: planner.name().to_string(),
        seed: s.seed.unwrap_or(0),
        trace_hash: path_hash(ep.tool_path()),
        metrics: ep.metrics(),
        joint_path_length_rad: ep.joint_path_length(),
        gripper_path_length_m: ep.gripper_path_length(),
        min_table_distance_m: table,
        effort: ep.effort(),
    })
}

/// The names [`arm_metric_values`] returns, in its order (CSV columns).
pub const ARM_METRIC_NAMES: [&str; 9] = [
    "time_s",
    "joint_path_length_rad",
    "gripper_path_length_m",
    "min_hand_distance_m",
    "min_table_distance_m",
    "plans",
    "replans",
    "iterations",
    "collision_checks",
];

/// The numeric metrics of one arm run by name.
pub fn arm_metric_values(r: &ArmBatchRun) -> [(&'static str, Option<f64>); 9] {
    [
        ("time_s", Some(r.metrics.time_s)),
        ("joint_path_length_rad", Some(r.joint_path_length_rad)),
        ("gripper_path_length_m", Some(r.gripper_path_length_m)),
        (
            "min_hand_distance_m",
            Some(r.metrics.min_obstacle_distance_m),
        ),
        ("min_table_distance_m", r.min_table_distance_m),
        ("plans", Some(f64::from(r.effort.plans))),
        ("replans", Some(f64::from(r.effort.replans))),
        ("iterations", Some(r.effort.iterations as f64)),
        ("collision_checks", Some(r.effort.collision_checks as f64)),
    ]
}

/// Summarises one arm planner's runs: success is reaching the goal; the
/// metric statistics are over the runs that did, as for the robot batches,
/// except the smallest distance to the hand, which is over every run (a
/// run that touched the hand is what it is about). `extra` adds per-run
/// values measured outside the core (the CLI's compute time), by name.
pub fn summarise_arm(
    planner: &str,
    runs: &[ArmBatchRun],
    extra: &[(&'static str, Vec<f64>)],
) -> PlannerSummary {
    let mut outcomes = BTreeMap::new();
    let mut columns: BTreeMap<&'static str, Vec<f64>> = BTreeMap::new();
    let mut reached = 0;
    for r in runs {
        *outcomes
            .entry(r.metrics.outcome.as_str().to_string())
            .or_insert(0) += 1;
        let ok = r.metrics.outcome == Outcome::Reached;
        reached += usize::from(ok);
        for (k, v) in arm_metric_values(r) {
            if let (Some(v), true) = (v, ok || k == "min_hand_distance_m") {
                columns.entry(k).or_default().push(v);
            }
        }
    }
    for (k, v) in extra {
        columns.insert(k, v.clone());
    }
    PlannerSummary {
        planner: planner.to_string(),
        runs: runs.len(),
        reached,
        outcomes,
        success_rate: if runs.is_empty() {
            0.0
        } else {
            reached as f64 / runs.len() as f64
        },
        metrics: columns
            .into_iter()
            .filter_map(|(k, v)| Stat::of(&v).map(|s| (k.to_string(), s)))
            .collect(),
    }
}
