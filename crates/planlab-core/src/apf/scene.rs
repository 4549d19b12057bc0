//! A kinematic APF run: a point robot (or a sphere of
//! [`ApfConfig::robot_radius`]) follows the APF path point by point among
//! spheres (3D) / discs (2D) moving at constant velocity, as in \[T\]
//! Fig 4-6…4-12 and Table 4-1, and the metrics those report.
//!
//! One step of period `period` s: observe the obstacles at t, take one APF
//! step ([`Apf::step`]), move to the new point, then at t + period check
//! collision (the robot's surface touches an obstacle), the goal (within
//! `goal_tolerance`), stuck (the best distance to the goal did not improve
//! by `stuck_distance` within `stuck_steps` steps: basic APF oscillating in
//! a local minimum or stalled before an unreachable goal) and the step
//! limit. The dimension (2 or 3) is the number of the start's coordinates.

use glam::{DVec2, DVec3};
use serde::{Deserialize, Serialize};

use super::field::surface_distance;
use super::planner::{Apf, ApfStep, ObstacleObs};
use super::{ApfConfig, ApfError, ApfVector};
use crate::num::acos;
use crate::params::{check_param, Bound};
use crate::world::Outcome;

/// A path point is a spike when the path turns there by more than this,
/// rad (30°, docs/algorithms.md §metrics).
pub const SPIKE_ANGLE: f64 = std::f64::consts::PI / 6.0;

/// An obstacle of an APF scene: a sphere / disc moving at constant
/// velocity.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneObstacle {
    /// Identity (default: its index).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub id: Option<u32>,
    /// Centre at t = 0, m (2 or 3 coordinates, as the start).
    pub centre: Vec<f64>,
    /// Radius, m (0 = a point).
    #[serde(default)]
    pub radius: f64,
    /// Velocity, m/s (default at rest).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub velocity: Option<Vec<f64>>,
}

/// The `apf` section of a scenario: a kinematic APF run (see the module
/// doc).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ApfScene {
    /// Start, m: 2 or 3 coordinates (default: the scenario's start point).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub start: Option<Vec<f64>>,
    /// Goal, m (default: the scenario's goal point).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub goal: Option<Vec<f64>>,
    /// The obstacles.
    pub obstacles: Vec<SceneObstacle>,
    /// The field, the step and the variant.
    pub config: ApfConfig,
    /// Time per planning step, s.
    pub period: f64,
    /// Most planning steps before `timeout`.
    pub max_steps: u32,
    /// Reached when this close to the goal, m.
    pub goal_tolerance: f64,
    /// Stuck after this many steps without `stuck_distance` of progress.
    pub stuck_steps: u32,
    /// Progress toward the goal that counts, m.
    pub stuck_distance: f64,
}

impl Default for ApfScene {
    fn default() -> Self {
        Self {
            start: None,
            goal: None,
            obstacles: Vec::new(),
            config: ApfConfig::default(),
            period: 0.1,
            max_steps: 600,
            goal_tolerance: 0.01,
            stuck_steps: 40,
            stuck_distance: 0.02,
        }
    }
}

/// What an APF run measured (\[T\] Table 4-1 / 5-3). Field names are those
/// of `planlab run --json` and `planlab reproduce --json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ApfMetrics {
    /// How the run ended.
    pub outcome: Outcome,
    /// Length of the path polyline, m.
    pub path_length_m: f64,
    /// Number of path points, start included.
    pub path_points: u32,
    /// Path points turning by more than 30°.
    pub spikes: u32,
    /// Smallest distance between the robot's and an obstacle's surfaces, m.
    pub min_obstacle_distance_m: f64,
    /// Planning steps × period, s.
    pub time_s: f64,
}

impl ApfMetrics {
    /// The metrics of `path` (points of any dimension as 3D).
    pub fn of_path(path: &[DVec3], outcome: Outcome, min_dist: f64, time_s: f64) -> Self {
        let path_length_m = path.windows(2).map(|w| (w[1] - w[0]).length()).sum();
        ApfMetrics {
            outcome,
            path_length_m,
            path_points: path.len() as u32,
            spikes: spikes(path, SPIKE_ANGLE),
            min_obstacle_distance_m: if min_dist.is_finite() { min_dist } else { 0.0 },
            time_s,
        }
    }
}

/// FNV-1a (64 bit) of a path's points (the bit patterns of x, y, z, in
/// order, after the point count): the trace hash of a kinematic APF or arm
/// run, printed by `planlab run` and `planlab reproduce`, equal on every
/// target for the same run.
pub fn path_hash(path: &[DVec3]) -> u64 {
    let mut h: u64 = 0xCBF2_9CE4_8422_2325;
    let mut eat = |b: [u8; 8]| {
        for x in b {
            h ^= u64::from(x);
            h = h.wrapping_mul(0x0000_0100_0000_01B3);
        }
    };
    eat((path.len() as u64).to_le_bytes());
    for p in path {
        for v in [p.x, p.y, p.z] {
            eat(v.to_bits().to_le_bytes());
        }
    }
    h
}

/// Interior path points where the direction turns by more than `angle`
/// rad (zero-length segments skipped: standing still is not a turn).
pub fn spikes(path: &[DVec3], angle: f64) -> u32 {
    let segs: Vec<DVec3> = path
        .windows(2)
        .map(|w| w[1] - w[0])
        .filter(|d| d.length() > 1e-12)
        .collect();
    segs.windows(2)
        .filter(|w| {
            let c = w[0].dot(w[1]) / (w[0].length() * w[1].length());
            acos(c.clamp(-1.0, 1.0)) > angle
        })
        .count() as u32
}

fn point<V: ApfVector>(what: &str, v: &[f64]) -> Result<V, ApfError> {
    V::from_slice(v).ok_or_else(|| ApfError::BadPoint {
        what: what.into(),
        expected: V::DIM,
        got: v.to_vec(),
    })
}

/// A running APF scene of dimension `V`.
#[derive(Debug)]
pub struct ApfRun<V: ApfVector> {
    apf: Apf<V>,
    scene: ApfScene,
    /// (id, centre at t = 0, radius, velocity).
    obstacles: Vec<(u32, V, f64, V)>,
    goal: V,
    path: Vec<V>,
    steps: u64,
    outcome: Outcome,
    last: Option<ApfStep<V>>,
    min_dist: f64,
    best: f64,
    best_step: u64,
}

impl<V: ApfVector> ApfRun<V> {
    /// Checks the scene (numbers, dimensions, start / goal outside every
    /// obstacle at t = 0) and places the robot at the start.
    pub fn new(scene: &ApfScene, start: V, goal: V) -> Result<Self, ApfError> {
        let bad = |name: &str, v: f64, bound: Bound| check_param(&format!("apf.{name}"), v, bound);
        bad("period", scene.period, Bound::above(0.0))?;
        bad("goal_tolerance", scene.goal_tolerance, Bound::above(0.0))?;
        bad("stuck_distance", scene.stuck_distance, Bound::at_least(0.0))?;
        if scene.max_steps == 0 || scene.max_steps > 1_000_000 {
            return Err(ApfError::InvalidParameter(format!(
                "apf.max_steps = {}: must be 1…1000000",
                scene.max_steps
            )));
        }
        let apf = Apf::new(scene.config)?;
        let mut obstacles = Vec::new();
        for (i, o) in scene.obstacles.iter().enumerate() {
            let c: V = point(&format!("apf.obstacles[{i}].centre"), &o.centre)?;
            let v: V = match &o.velocity {
                Some(v) => point(&format!("apf.obstacles[{i}].velocity"), v)?,
                None => V::ZERO,
            };
            bad(
                &format!("obstacles[{i}].radius"),
                o.radius,
                Bound::at_least(0.0),
            )?;
            let id = o.id.unwrap_or(i as u32);
            if surface_distance(&scene.config, goal, c, o.radius) <= 0.0 && v == V::ZERO {
                return Err(ApfError::GoalInsideObstacle {
                    goal: goal.to_vec(),
                    id,
                });
            }
            if surface_distance(&scene.config, start, c, o.radius) <= 0.0 {
                return Err(ApfError::StartInsideObstacle {
                    start: start.to_vec(),
                    id,
                });
            }
            obstacles.push((id, c, o.radius, v));
        }
        let mut run = Self {
            apf,
            scene: scene.clone(),
            obstacles,
            goal,
            path: vec![start],
            steps: 0,
            outcome: Outcome::Running,
            last: None,
            min_dist: f64::INFINITY,
            best: (goal - start).norm(),
            best_step: 0,
        };
        run.min_dist = run.nearest(start, 0.0);
        if run.best <= scene.goal_tolerance {
            run.outcome = Outcome::Reached;
        }
        Ok(run)
    }

    /// The obstacles as observed at time `t`, s.
    pub fn obstacles_at(&self, t: f64) -> Vec<ObstacleObs<V>> {
        self.obstacles
            .iter()
            .map(|&(id, c, r, v)| ObstacleObs {
                id,
                centre: c + v * t,
                radius: r,
                velocity: if v == V::ZERO { None } else { Some(v) },
            })
            .collect()
    }

    fn nearest(&self, x: V, t: f64) -> f64 {
        super::planner::nearest_surface(&self.scene.config, x, &self.obstacles_at(t))
    }

    /// Time now, s.
    pub fn time(&self) -> f64 {
        self.steps as f64 * self.scene.period
    }

    /// The robot's position.
    pub fn position(&self) -> V {
        *self.path.last().unwrap_or(&self.goal)
    }

    /// The goal.
    pub fn goal(&self) -> V {
        self.goal
    }

    /// Moves the goal (the page's drag); the run continues from here.
    pub fn set_goal(&mut self, goal: V) -> Result<(), ApfError> {
        if !goal.to_xyz().is_finite() {
            return Err(ApfError::BadPoint {
                what: "goal".into(),
                expected: V::DIM,
                got: goal.to_vec(),
            });
        }
        self.goal = goal;
        self.best = (goal - self.position()).norm();
        self.best_step = self.steps;
        if matches!(self.outcome, Outcome::Reached | Outcome::Stuck) {
            self.outcome = Outcome::Running;
        }
        Ok(())
    }

    /// The path so far, start first.
    pub fn path(&self) -> &[V] {
        &self.path
    }

    /// The last APF step (forces, candidates, predictions).
    pub fn last_step(&self) -> Option<&ApfStep<V>> {
        self.last.as_ref()
    }

    /// The planner (for its config and field queries).
    pub fn planner(&self) -> &Apf<V> {
        &self.apf
    }

    /// The outcome so far.
    pub fn outcome(&self) -> Outcome {
        self.outcome
    }

    /// Planning steps taken.
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// One planning step (nothing once the run has ended).
    pub fn step(&mut self) -> Result<Outcome, ApfError> {
        if self.outcome != Outcome::Running {
            return Ok(self.outcome);
        }
        let t = self.time();
        let obs = self.obstacles_at(t);
        let pos = self.position();
        let s = self.apf.step(t, pos, self.goal, &obs)?;
        let next = s.next;
        self.last = Some(s);
        self.steps += 1;
        if next != pos {
            self.path.push(next);
        }
        let t1 = self.time();
        let d = self.nearest(next, t1);
        self.min_dist = self.min_dist.min(d);
        let to_goal = (self.goal - next).norm();
        if d <= 0.0 {
            self.outcome = Outcome::Collision;
        } else if to_goal <= self.scene.goal_tolerance {
            self.outcome = Outcome::Reached;
        } else {
            if to_goal < self.best - self.scene.stuck_distance {
                self.best = to_goal;
                self.best_step = self.steps;
            }
            if self.steps - self.best_step >= u64::from(self.scene.stuck_steps) {
                self.outcome = Outcome::Stuck;
            } else if self.steps >= u64::from(self.scene.max_steps) {
                self.outcome = Outcome::Timeout;
            }
        }
        Ok(self.outcome)
    }

    /// Steps until the run ends.
    pub fn run(&mut self) -> Result<Outcome, ApfError> {
        while self.outcome == Outcome::Running {
            self.step()?;
        }
        Ok(self.outcome)
    }

    /// The metrics so far.
    pub fn metrics(&self) -> ApfMetrics {
        let pts: Vec<DVec3> = self.path.iter().map(|p| p.to_xyz()).collect();
        ApfMetrics::of_path(&pts, self.outcome, self.min_dist, self.time())
    }
}

/// An APF run in 2D or 3D, as the scene's start decides.
#[derive(Debug)]
pub enum AnyApfRun {
    /// A planar run.
    D2(ApfRun<DVec2>),
    /// A spatial run.
    D3(ApfRun<DVec3>),
}

impl AnyApfRun {
    /// Builds the run of `scene`; `start` / `goal` are used where the scene
    /// leaves them out (a scenario's world points, 2D).
    pub fn new(scene: &ApfScene, start: &[f64], goal: &[f64]) -> Result<Self, ApfError> {
        let start = scene.start.as_deref().unwrap_or(start);
        let goal = scene.goal.as_deref().unwrap_or(goal);
        Ok(match start.len() {
            3 => AnyApfRun::D3(ApfRun::new(
                scene,
                point("apf.start", start)?,
                point("apf.goal", goal)?,
            )?),
            _ => AnyApfRun::D2(ApfRun::new(
                scene,
                point("apf.start", start)?,
                point("apf.goal", goal)?,
            )?),
        })
    }

    /// Runs to the end; the metrics.
    pub fn run(&mut self) -> Result<ApfMetrics, ApfError> {
        Ok(match self {
            AnyApfRun::D2(r) => {
                r.run()?;
                r.metrics()
            }
            AnyApfRun::D3(r) => {
                r.run()?;
                r.metrics()
            }
        })
    }

    /// The path as 3D points.
    pub fn path_xyz(&self) -> Vec<DVec3> {
        match self {
            AnyApfRun::D2(r) => r.path().iter().map(|p| p.to_xyz()).collect(),
            AnyApfRun::D3(r) => r.path().to_vec(),
        }
    }

    /// Planning steps taken.
    pub fn steps(&self) -> u64 {
        match self {
            AnyApfRun::D2(r) => r.steps(),
            AnyApfRun::D3(r) => r.steps(),
        }
    }

    /// The variant's label (`basic`, `sampling`, `sampling-prediction`).
    pub fn mode_label(&self) -> &'static str {
        match self {
            AnyApfRun::D2(r) => r.planner().config().mode.label(),
            AnyApfRun::D3(r) => r.planner().config().mode.label(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::apf::ApfMode;

    #[test]
    fn spikes_count_turns_above_30_degrees_only() {
        let p = |x: f64, y: f64| DVec3::new(x, y, 0.0);
        let path = [
            p(0.0, 0.0),
            p(1.0, 0.0),
            p(2.0, 0.2),
            p(2.0, 1.0),
            p(2.0, 1.0),
            p(1.0, 1.0),
        ];
        // Turns: ~11° (no), ~79° (yes), standing still (skipped), 90° (yes).
        assert_eq!(spikes(&path, SPIKE_ANGLE), 2);
        let m = ApfMetrics::of_path(&path, Outcome::Reached, 0.1, 0.5);
        assert_eq!(m.path_points, 6);
        assert!((m.path_length_m - (1.0 + 0.2f64.hypot(1.0) + 0.8 + 1.0)).abs() < 1e-12);
    }

    #[test]
    fn scene_errors_are_typed() {
        let scene = ApfScene {
            obstacles: vec![SceneObstacle {
                id: None,
                centre: vec![1.0, 0.0],
                radius: 0.1,
                velocity: None,
            }],
            ..ApfScene::default()
        };
        let e = AnyApfRun::new(&scene, &[0.0, 0.0], &[1.05, 0.0]).unwrap_err();
        assert!(
            matches!(e, ApfError::GoalInsideObstacle { id: 0, .. }),
            "{e}"
        );
        let e = AnyApfRun::new(&scene, &[0.95, 0.0], &[0.0, 0.0]).unwrap_err();
        assert!(matches!(e, ApfError::StartInsideObstacle { .. }), "{e}");
        let e = AnyApfRun::new(&scene, &[0.0, 0.0, 0.0], &[0.0, 1.0, 0.0]).unwrap_err();
        assert!(e.to_string().contains("obstacles[0].centre"), "{e}");
        let nan = ApfScene {
            period: f64::NAN,
            ..ApfScene::default()
        };
        assert!(AnyApfRun::new(&nan, &[0.0, 0.0], &[1.0, 0.0])
            .unwrap_err()
            .to_string()
            .contains("period"));
        assert!(AnyApfRun::new(&ApfScene::default(), &[0.0, f64::NAN], &[1.0, 0.0]).is_err());
    }

    #[test]
    fn basic_apf_is_stuck_on_a_collinear_obstacle_and_sampling_reaches() {
        let mut scene = ApfScene {
            obstacles: vec![SceneObstacle {
                id: None,
                centre: vec![0.5, 0.0, 0.3],
                radius: 0.05,
                velocity: None,
            }],
            ..ApfScene::default()
        };
        scene.config.mode = ApfMode::Basic;
        let mut r = AnyApfRun::new(&scene, &[0.0, 0.0, 0.3], &[1.0, 0.0, 0.3]).unwrap();
        let m = r.run().unwrap();
        assert_eq!(m.outcome, Outcome::Stuck, "{m:?}");
        scene.config.mode = ApfMode::Sampling;
        let mut r = AnyApfRun::new(&scene, &[0.0, 0.0, 0.3], &[1.0, 0.0, 0.3]).unwrap();
        let m = r.run().unwrap();
        assert_eq!(m.outcome, Outcome::Reached, "{m:?}");
        assert!(m.min_obstacle_distance_m > 0.0 && m.path_length_m < 1.3);
    }
}
