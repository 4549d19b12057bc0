//! Fixed-step, seeded, deterministic episodes (docs/algorithms.md §episode): world + robot +
//! local planner → trace and outcome.
//!
//! One [`Episode::step`] is one control period of `dt`:
//! 1. **observe** the movers at time t (closed-form [`MoverSpec::state_at`])
//!    whose surface is within `sensing_range` of the robot's centre, with
//!    their true velocities;
//! 2. ask the planner for a command, clamp it to what the motors can do
//!    ([`RobotSpec::feasible`]);
//! 3. move the robot with the terrain model ([`Terrain::step`]: exact
//!    kinematics on flat ground, slip and road vibration when configured);
//! 4. at t + dt, check collisions exactly (footprint vs walls and map edge
//!    with parry2d, footprint vs mover discs in closed form), then the goal,
//!    then stuck and timeout. The first outcome other than
//!    [`Outcome::Running`] is final.
//!
//! Time is `steps × dt` (no accumulated rounding), nothing reads a clock and
//! all trigonometry goes through [`crate::num`], so the same setup and seed
//! give a bit-identical [`Trace`] natively and in WebAssembly.

mod edit;
mod live;
pub mod perception;
mod replay;
mod trace;

/// Every kind of run reports it, so it is a world type; named here too as
/// the episode's result.
pub use crate::world::{Collision, Outcome};
pub use edit::{
    generated_sim_config, is_start_collision, SetupEdit, GENERATED_MAX_TIME, GENERATED_STUCK_TIME,
};
pub use perception::{Perception, PerceptionSpec};
pub use replay::{Edit, Recording};
pub use trace::{Column, Trace, TraceStep};

use serde::{Deserialize, Serialize};
use thiserror::Error;

use crate::lidar::scan::Disc;
use crate::lidar::{Lidar, Scan};
use crate::local::car_guide::{CarGuide, GlobalPlannerSpec};
use crate::local::{GoalKind, LocalError, LocalPlanner, ObservedMover, PlannerDebug};
use crate::map::io::ScenarioError;
use crate::map::MapError;
use crate::num::{cos, fmt_num, hypot, sin};
use crate::params::param_problem;
use crate::planners::{self, PlannerChoice};
use crate::world::{
    Command, Footprint, MoverSpec, MoverState, MoverTrack, OdometrySample, RobotSpec, RobotState,
    StaticMap, Terrain, TerrainSpec, WorldError,
};

/// Clearance values in traces and metrics are capped here, metres: farther
/// obstacles do not matter to a local planner and an exact search beyond it
/// would cost time.
pub const CLEARANCE_CAP: f64 = 5.0;

/// The most steps one episode may take (`max_time / dt`), so a typo cannot
/// start an endless run. The trace keeps a row (a few hundred bytes) per
/// step, so this also bounds an episode's memory (~0.3 GB; the presets
/// take at most 8000 steps).
pub const MAX_STEPS: f64 = 1_000_000.0;

/// The longest control period, s. A step integrates the command over `dt`
/// and checks collisions only at its end, so a long period moves the robot
/// through walls (`sim.dt=1e9` once moved it 7.6·10⁸ m in one step).
pub const MAX_DT: f64 = 1.0;

/// The trace's `mode` of a step driven by [`Episode::step_with`].
pub const USER_MODE: &str = "user";

/// Simulation settings of an episode.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SimConfig {
    /// Control period and integration step, s.
    pub dt: f64,
    /// The episode ends as [`Outcome::Timeout`] at this time, s.
    pub max_time: f64,
    /// The goal is reached when the robot's centre is this close, m.
    pub goal_tolerance: f64,
    /// Stuck: the best distance to the goal so far did not improve by
    /// `stuck_distance` within this long, s.
    pub stuck_time: f64,
    /// Progress that counts against being stuck, m.
    pub stuck_distance: f64,
    /// Movers whose surface is within this distance of the robot's centre
    /// are observed, m.
    pub sensing_range: f64,
    /// Keep every rollout's points in the planner debug (for drawing);
    /// off makes batch runs faster.
    pub record_rollouts: bool,
    /// Unknown (`?`) map cells block the robot.
    pub unknown_is_obstacle: bool,
}

impl Default for SimConfig {
    fn default() -> Self {
        Self {
            dt: 0.1,
            max_time: 120.0,
            goal_tolerance: 0.2,
            stuck_time: 15.0,
            stuck_distance: 0.2,
            sensing_range: 5.0,
            record_rollouts: false,
            unknown_is_obstacle: true,
        }
    }
}

impl SimConfig {
    /// Checks every number; the error names the field (`sim.dt`, …).
    pub fn validate(&self) -> Result<(), SimError> {
        let field = |name: &str, unit: &str, v: f64, min: f64, strict: bool| match param_problem(
            v, min, strict,
        ) {
            None => Ok(()),
            Some(p) => Err(SimError::InvalidConfig(format!(
                "sim.{name} = {} {unit}: {p}",
                fmt_num(v)
            ))),
        };
        // Before the general bound, whose limit is far above a control period.
        if self.dt.is_finite() && self.dt > MAX_DT {
            return Err(SimError::InvalidConfig(format!(
                "sim.dt = {} s: must be at most {MAX_DT} s (one control period)",
                fmt_num(self.dt)
            )));
        }
        field("dt", "s", self.dt, 0.0, true)?;
        field("max_time", "s", self.max_time, 0.0, true)?;
        field("goal_tolerance", "m", self.goal_tolerance, 0.0, true)?;
        field("stuck_time", "s", self.stuck_time, 0.0, true)?;
        field("stuck_distance", "m", self.stuck_distance, 0.0, false)?;
        field("sensing_range", "m", self.sensing_range, 0.0, false)?;
        if self.max_time / self.dt > MAX_STEPS {
            return Err(SimError::InvalidConfig(format!(
                "sim.max_time = {} s with sim.dt = {} s is more than {MAX_STEPS} steps",
                fmt_num(self.max_time),
                fmt_num(self.dt)
            )));
        }
        Ok(())
    }

    /// Number of steps until timeout: ⌈max_time / dt⌉.
    fn max_steps(&self) -> u64 {
        // The small slack keeps 120 / 0.1 = 1200.0000000000002 at 1200.
        (self.max_time / self.dt - 1e-9).ceil().max(1.0) as u64
    }
}

/// Why an episode could not be set up or changed.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum SimError {
    /// Bad robot, mover, start or map geometry.
    #[error(transparent)]
    World(#[from] WorldError),
    /// The planner's config is invalid, its name unknown, or it found no
    /// global path.
    #[error(transparent)]
    Planner(#[from] LocalError),
    /// The scenario is invalid.
    #[error(transparent)]
    Scenario(#[from] ScenarioError),
    /// The map is invalid.
    #[error(transparent)]
    Map(#[from] MapError),
    /// A simulation setting is out of range; the text names it.
    #[error("invalid simulation setting: {}", crate::text::one_line(.0))]
    InvalidConfig(String),
    /// The goal is not a free point of the map.
    #[error("the goal ({x:.3}, {y:.3}) m {reason}")]
    BadGoal {
        /// Goal x, metres.
        x: f64,
        /// Goal y, metres.
        y: f64,
        /// What is wrong ("is off the map", "is inside a wall", …).
        reason: String,
    },
    /// No free path joins the robot's cell and the goal's: walls enclose
    /// one of them.
    #[error("the goal ({x:.3}, {y:.3}) m cannot be reached from ({from_x:.3}, {from_y:.3}) m: no free path of map cells joins them")]
    Unreachable {
        /// Goal x, metres.
        x: f64,
        /// Goal y, metres.
        y: f64,
        /// Robot x, metres.
        from_x: f64,
        /// Robot y, metres.
        from_y: f64,
    },
}

/// Everything an episode starts from.
#[derive(Debug, Clone)]
pub struct EpisodeSetup {
    /// Static obstacles.
    pub map: StaticMap,
    /// The robot's body and limits.
    pub robot: RobotSpec,
    /// Start pose and velocities.
    pub start: RobotState,
    /// Goal, world metres.
    pub goal: [f64; 2],
    /// Moving obstacles (motion models run on episode time).
    pub movers: Vec<MoverSpec>,
    /// The local planner and its config.
    pub planner: PlannerChoice,
    /// Simulation settings.
    pub config: SimConfig,
    /// Terrain / vehicle dynamics.
    pub terrain: TerrainSpec,
    /// Seed of every random stream of the episode.
    pub seed: u64,
    /// When present the planner does not get the true map: it gets what
    /// this laser has shown ([`perception`]).
    pub perception: Option<PerceptionSpec>,
    /// When present the local planner follows a car-like global path
    /// ([`crate::local::car_guide`]) instead of steering at the goal.
    pub global_planner: Option<GlobalPlannerSpec>,
}

/// Exact distance (m) from a footprint at `pose` to a disc; ≤ 0 when they
/// overlap (minus the penetration depth). Closed form (point to rotated
/// rectangle, or centre distance for a circle): the same value parry2d's
/// ball–cuboid query gives, without its dispatch cost per mover per step.
pub fn footprint_disc_distance(
    footprint: &Footprint,
    pose: &RobotState,
    centre: [f64; 2],
    radius: f64,
) -> f64 {
    let (dx, dy) = (centre[0] - pose.x, centre[1] - pose.y);
    match *footprint {
        Footprint::Circle { radius: r } => hypot(dx, dy) - r - radius,
        Footprint::Rectangle { length, width } => {
            let (s, c) = (sin(pose.theta), cos(pose.theta));
            // Disc centre in the body frame.
            let (lx, ly) = (c * dx + s * dy, -s * dx + c * dy);
            let (ex, ey) = (lx.abs() - 0.5 * length, ly.abs() - 0.5 * width);
            let d = if ex > 0.0 || ey > 0.0 {
                hypot(ex.max(0.0), ey.max(0.0))
            } else {
                ex.max(ey)
            };
            d - radius
        }
    }
}

/// Exact distance (m) from the footprint at `pose` to the nearest wall or
/// the map edge, capped at [`CLEARANCE_CAP`]. The O(1) clearance field
/// bounds the exact value from above (centre distance − inscribed radius,
/// plus the field's error of under a cell), so the exact parry2d search
/// never looks further than that bound.
pub fn static_clearance(map: &StaticMap, footprint: &Footprint, pose: &RobotState) -> f64 {
    let bound =
        map.clearance(pose.x, pose.y) + map.grid().resolution() - footprint.inscribed_radius();
    let look = CLEARANCE_CAP.min(bound.max(0.0));
    map.footprint_distance(footprint, pose, look)
        .clamp(0.0, CLEARANCE_CAP)
}

/// One running episode.
pub struct Episode {
    map: StaticMap,
    robot: RobotSpec,
    start: RobotState,
    state: RobotState,
    goal: [f64; 2],
    movers: Vec<MoverSpec>,
    /// The movers' bounces computed so far (constant velocity), extended
    /// step by step.
    tracks: Vec<MoverTrack>,
    choice: PlannerChoice,
    planner: Box<dyn LocalPlanner>,
    config: SimConfig,
    terrain_spec: TerrainSpec,
    terrain: Terrain,
    seed: u64,
    steps: u64,
    max_steps: u64,
    outcome: Outcome,
    /// What the robot ran into, when the outcome is a collision.
    collision: Option<Collision>,
    trace: Trace,
    odometry: Option<OdometrySample>,
    accel_z: f64,
    /// Best distance to the goal that counted as progress, and when.
    progress: (f64, f64),
    /// The laser and the map built from it, when the planner does not get
    /// the true map.
    perception: Option<Perception>,
    /// The car-like global path the planner follows, when the setup has a
    /// `global_planner`.
    car: Option<CarGuide>,
}

impl std::fmt::Debug for Episode {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Episode")
            .field("planner", &self.choice.name)
            .field("time", &self.time())
            .field("state", &self.state)
            .field("outcome", &self.outcome)
            .finish_non_exhaustive()
    }
}

/// Checks a goal is a finite point in a free cell of the map.
fn check_goal(map: &StaticMap, goal: [f64; 2]) -> Result<(), SimError> {
    let bad = |reason: &str| SimError::BadGoal {
        x: goal[0],
        y: goal[1],
        reason: reason.to_string(),
    };
    if !(goal[0].is_finite() && goal[1].is_finite()) {
        return Err(bad("is not a finite point"));
    }
    let Some((col, row)) = map.grid().world_to_cell(goal[0], goal[1]) else {
        return Err(bad("is off the map"));
    };
    if map.is_blocked(col as i64, row as i64) {
        return Err(bad(&format!(
            "is inside a wall (cell ({col}, {row}) is blocked)"
        )));
    }
    Ok(())
}

/// Checks that the goal's cell is connected to the robot's cell through
/// free cells (4-neighbours: two cells touching only at a corner let no
/// robot through). Ignores the robot's size and the movers, so it only
/// refuses goals that no planner could reach.
fn check_reachable(map: &StaticMap, from: [f64; 2], goal: [f64; 2]) -> Result<(), SimError> {
    let grid = map.grid();
    let (w, h) = (grid.width(), grid.height());
    let (Some(a), Some(b)) = (
        grid.world_to_cell(from[0], from[1]),
        grid.world_to_cell(goal[0], goal[1]),
    ) else {
        // Off-map points are reported by the other checks.
        return Ok(());
    };
    let idx = |(c, r): (usize, usize)| r * w + c;
    let mut seen = vec![false; w * h];
    let mut stack = vec![a];
    if let Some(s) = seen.get_mut(idx(a)) {
        *s = true;
    }
    while let Some((c, r)) = stack.pop() {
        if (c, r) == b {
            return Ok(());
        }
        let next = [
            (c.wrapping_sub(1), r),
            (c + 1, r),
            (c, r.wrapping_sub(1)),
            (c, r + 1),
        ];
        for (nc, nr) in next {
            if nc >= w || nr >= h || map.is_blocked(nc as i64, nr as i64) {
                continue;
            }
            if let Some(s) = seen.get_mut(idx((nc, nr))) {
                if !*s {
                    *s = true;
                    stack.push((nc, nr));
                }
            }
        }
    }
    Err(SimError::Unreachable {
        x: goal[0],
        y: goal[1],
        from_x: from[0],
        from_y: from[1],
    })
}

fn check_state(s: &RobotState) -> Result<(), SimError> {
    for (name, v) in [
        ("x", s.x),
        ("y", s.y),
        ("theta", s.theta),
        ("v", s.v),
        ("vy", s.vy),
        ("w", s.w),
    ] {
        if !v.is_finite() {
            return Err(WorldError::InvalidParameter(format!(
                "start.{name} = {v}: must be a finite number"
            ))
            .into());
        }
    }
    Ok(())
}

/// The car path of `spec` for the robot at `start`, once `choice` is known
/// to follow it.
fn car_guide(
    spec: GlobalPlannerSpec,
    choice: &PlannerChoice,
    robot: &RobotSpec,
    map: &StaticMap,
    start: &RobotState,
    goal: [f64; 2],
) -> Result<CarGuide, SimError> {
    spec.validate()?;
    spec.check_follower(&choice.name)?;
    Ok(CarGuide::new(spec, robot.footprint, map, start, goal)?)
}

/// Mover states at time `t` on `map`.
fn movers_at(
    movers: &[MoverSpec],
    tracks: &[MoverTrack],
    map: &StaticMap,
    t: f64,
) -> Vec<MoverState> {
    movers
        .iter()
        .zip(tracks)
        .map(|(m, tr)| tr.state_at(m, map, t))
        .collect()
}

/// Validates movers against the map (numbers, no mover in or through a
/// wall) and starts their tracks, computed up to time `t`.
fn tracks_of(movers: &[MoverSpec], map: &StaticMap, t: f64) -> Result<Vec<MoverTrack>, SimError> {
    movers
        .iter()
        .map(|m| {
            m.validate()?;
            m.check_on(map)?;
            let mut tr = MoverTrack::new(m, map);
            tr.extend_to(m, map, t);
            Ok(tr)
        })
        .collect()
}

/// The movers as discs a laser sees.
fn discs_of(movers: &[MoverSpec], now: &[MoverState]) -> Vec<Disc> {
    movers
        .iter()
        .zip(now)
        .map(|(m, ms)| Disc {
            centre: ms.pos,
            radius: m.radius,
        })
        .collect()
}

impl Episode {
    /// Validates the setup and builds the planner. Errors: invalid numbers
    /// (naming the field), a start pose overlapping a wall, the map edge or
    /// a mover ([`WorldError::StartInCollision`]), a goal off the map or in
    /// a wall ([`SimError::BadGoal`]), a goal walled off from the start
    /// ([`SimError::Unreachable`]), and the planner's own errors (bad
    /// config, no global path).
    pub fn new(setup: EpisodeSetup) -> Result<Episode, SimError> {
        let EpisodeSetup {
            map,
            robot,
            start,
            goal,
            movers,
            planner: choice,
            config,
            terrain: terrain_spec,
            seed,
            perception: perception_spec,
            global_planner,
        } = setup;
        config.validate()?;
        robot.validate()?;
        let tracks = tracks_of(&movers, &map, 0.0)?;
        check_state(&start)?;
        check_goal(&map, goal)?;
        let start = RobotState {
            theta: crate::num::wrap_angle(start.theta),
            ..start
        };
        let fp = robot.footprint;
        if map.footprint_collides(&fp, &start) {
            let b = map.bounds();
            let r = fp.circumscribed_radius();
            let pokes_out = start.x - r < b[0]
                || start.y - r < b[1]
                || start.x + r > b[2]
                || start.y + r > b[3];
            let centre_free = map
                .grid()
                .world_to_cell(start.x, start.y)
                .is_some_and(|(c, r)| !map.is_blocked(c as i64, r as i64));
            let with = if pokes_out && centre_free {
                "the map edge or a wall"
            } else {
                "a wall"
            };
            return Err(WorldError::StartInCollision {
                x: start.x,
                y: start.y,
                with: with.into(),
            }
            .into());
        }
        for (m, tr) in movers.iter().zip(&tracks) {
            let s = tr.state_at(m, &map, 0.0);
            if footprint_disc_distance(&fp, &start, s.pos, m.radius) <= 0.0 {
                return Err(WorldError::StartInCollision {
                    x: start.x,
                    y: start.y,
                    with: format!("mover {}", m.id),
                }
                .into());
            }
        }
        check_reachable(&map, [start.x, start.y], goal)?;
        let terrain = Terrain::new(terrain_spec.clone(), seed)?;
        let perception = match perception_spec {
            Some(spec) => {
                let mut p = Perception::new(spec, &map, seed)?;
                let discs = discs_of(&movers, &movers_at(&movers, &tracks, &map, 0.0));
                p.sense(&map, [start.x, start.y, start.theta], &discs, 0.0);
                Some(p)
            }
            None => None,
        };
        // The planner is built on what it knows: the perceived map when
        // there is one.
        let known = perception.as_ref().map_or(&map, |p| p.map());
        let mut planner = planners::build(&choice, &robot, known, &start, goal)?;
        planner.set_record_rollouts(config.record_rollouts);
        planner.set_seed(seed);
        let car = match global_planner {
            Some(spec) => {
                let mut c = car_guide(spec, &choice, &robot, known, &start, goal)?;
                c.annotate(planner.debug());
                Some(c)
            }
            None => None,
        };
        let mut ep = Episode {
            max_steps: config.max_steps(),
            progress: (hypot(goal[0] - start.x, goal[1] - start.y), 0.0),
            map,
            robot,
            start,
            state: start,
            goal,
            movers,
            tracks,
            choice,
            planner,
            config,
            terrain_spec,
            terrain,
            seed,
            steps: 0,
            outcome: Outcome::Running,
            collision: None,
            trace: Trace::default(),
            odometry: None,
            accel_z: 0.0,
            perception,
            car,
        };
        let first = ep.trace_row(Default::default(), None, &ep.movers_at(0.0));
        ep.trace.steps.push(first);
        Ok(ep)
    }

    /// The setup this episode would restart from: the original start, map,
    /// robot, planner, settings and seed with the *current* goal and movers
    /// (after [`Episode::set_goal`] / [`Episode::set_movers`]).
    pub fn setup(&self) -> EpisodeSetup {
        EpisodeSetup {
            map: self.map.clone(),
            robot: self.robot,
            start: self.start,
            goal: self.goal,
            movers: self.movers.clone(),
            planner: self.choice.clone(),
            config: self.config,
            terrain: self.terrain_spec.clone(),
            seed: self.seed,
            perception: self.perception.as_ref().map(|p| *p.spec()),
            global_planner: self.car.as_ref().map(|c| *c.spec()),
        }
    }

    /// Mover positions and velocities at time `t`.
    fn movers_at(&self, t: f64) -> Vec<MoverState> {
        movers_at(&self.movers, &self.tracks, &self.map, t)
    }

    /// The laser and the map built from it, when the episode has a
    /// perception section.
    pub fn perception(&self) -> Option<&Perception> {
        self.perception.as_ref()
    }

    /// For an episode with a perception section that ended in a
    /// collision: whether the laser had shown what the robot hit — the
    /// footprint at its final pose touches a cell its scans had marked by
    /// then (the static part), or the mover it hit was in the last scan's
    /// field of view. `None` for any other episode. A collision with a seen
    /// obstacle is a planner's bug; one with an unseen obstacle (behind a
    /// 270° laser, hidden) is not.
    pub fn collision_seen(&self) -> Option<bool> {
        if self.outcome != Outcome::Collision {
            return None;
        }
        let p = self.perception.as_ref()?;
        let fp = &self.robot.footprint;
        let static_seen = self.map.footprint_collides(fp, &self.state)
            && p.marked_map()
                .is_some_and(|m| m.footprint_collides(fp, &self.state));
        let mover_seen = self
            .movers
            .iter()
            .zip(self.movers_at(self.time()))
            .any(|(m, ms)| {
                footprint_disc_distance(fp, &self.state, ms.pos, m.radius) <= 0.0
                    && p.in_view(&self.state, ms.pos)
            });
        Some(static_seen || mover_seen)
    }

    /// Exact clearance of the robot at its current pose (capped).
    fn clearance(&self, movers: &[MoverState]) -> f64 {
        let fp = &self.robot.footprint;
        let s = &self.state;
        let mut c = static_clearance(&self.map, fp, s);
        for (m, ms) in self.movers.iter().zip(movers) {
            c = c.min(footprint_disc_distance(fp, s, ms.pos, m.radius));
        }
        c.clamp(0.0, CLEARANCE_CAP)
    }

    fn trace_row(
        &self,
        cmd: crate::world::Command,
        ts: Option<&crate::world::TerrainStep>,
        movers: &[MoverState],
    ) -> TraceStep {
        let s = &self.state;
        let d = self.planner_debug();
        let goal = if self.steps == 0 {
            self.goal
        } else {
            d.current_goal
        };
        TraceStep {
            t: self.time(),
            x: s.x,
            y: s.y,
            theta: s.theta,
            v: s.v,
            vy: s.vy,
            w: s.w,
            cmd,
            clearance: self.clearance(movers),
            goal,
            goal_kind: if self.steps == 0 {
                Default::default()
            } else {
                d.goal_kind
            },
            mode: if self.steps == 0 {
                String::new()
            } else {
                d.mode.clone()
            },
            classes: if self.steps == 0 {
                Vec::new()
            } else {
                d.classes.clone()
            },
            accel_z: ts.map_or(0.0, |t| t.accel_z),
            wheel_loads: ts.and_then(|t| t.wheel_loads),
            movers: self
                .movers
                .iter()
                .zip(movers)
                .map(|(m, ms)| (m.id, ms.pos))
                .collect(),
        }
    }

    /// The movers the robot perceives now: those whose surface is within
    /// `sensing_range` of its centre, with their true velocities (what the
    /// planner is given each step).
    pub fn observed_movers(&self) -> Vec<ObservedMover> {
        let now = self.movers_at(self.time());
        let range = self.config.sensing_range;
        self.movers
            .iter()
            .zip(&now)
            .filter(|(m, ms)| {
                hypot(ms.pos[0] - self.state.x, ms.pos[1] - self.state.y) - m.radius <= range
            })
            .map(|(m, ms)| ObservedMover {
                id: m.id,
                pos: ms.pos,
                vel: ms.vel,
                radius: m.radius,
            })
            .collect()
    }

    /// A LiDAR scan from the robot's current pose against the map and every
    /// mover (as discs at their current positions). The sensor is the
    /// caller's, so its noise stream goes on across calls.
    pub fn scan(&self, lidar: &mut Lidar) -> Scan {
        let s = &self.state;
        let discs: Vec<Disc> = self
            .movers
            .iter()
            .zip(self.movers_at(self.time()))
            .map(|(m, ms)| Disc {
                centre: ms.pos,
                radius: m.radius,
            })
            .collect();
        lidar.scan(&self.map, [s.x, s.y, s.theta], &discs)
    }

    /// Advances one control period with the scenario's planner and returns
    /// the outcome (unchanged once the episode has ended).
    pub fn step(&mut self) -> Outcome {
        self.advance(None)
    }

    /// Advances one control period with `command` instead of the planner's
    /// (an external controller drives the robot): the command is clamped to
    /// the robot's limits like the planner's, the world, collisions, goal
    /// and trace go on as in [`Episode::step`], so the metrics are the same
    /// measure. The trace row's goal is the final goal and its mode `user`.
    /// A non-finite component is refused before anything moves.
    pub fn step_with(&mut self, command: Command) -> Result<Outcome, SimError> {
        for (name, v) in [("v", command.v), ("vy", command.vy), ("w", command.w)] {
            if !v.is_finite() {
                return Err(SimError::InvalidConfig(format!(
                    "command {name} = {}: must be a finite number",
                    fmt_num(v)
                )));
            }
        }
        Ok(self.advance(Some(command)))
    }

    /// One control period with the planner's command (`None`) or the
    /// given one.
    fn advance(&mut self, user: Option<Command>) -> Outcome {
        if self.outcome != Outcome::Running {
            return self.outcome;
        }
        let dt = self.config.dt;
        let t = self.time();
        let raw = match user {
            Some(cmd) => cmd,
            None => {
                let observed = self.observed_movers();
                let (map, map_revision, scan) = match &self.perception {
                    Some(p) => (p.map(), p.revision(), Some(p.scan())),
                    None => (&self.map, 0, None),
                };
                // With a car path the planner steers to its carrot.
                let goal = match &mut self.car {
                    Some(c) => c.carrot(map, map_revision, &self.state, self.goal),
                    None => self.goal,
                };
                let obs = crate::local::Observation {
                    time: t,
                    dt,
                    state: &self.state,
                    goal,
                    map,
                    map_revision,
                    scan,
                    movers: &observed,
                    odometry: self.odometry,
                    accel_z: self.accel_z,
                };
                let cmd = self.planner.step(&obs);
                if let Some(c) = &mut self.car {
                    c.annotate(self.planner.debug());
                }
                cmd
            }
        };
        let cmd = self.robot.feasible(&self.state, raw, dt);
        let ts = self.terrain.step(&self.state, cmd, dt);
        self.state = ts.next;
        self.odometry = ts.odometry;
        self.accel_z = ts.accel_z;
        self.steps += 1;
        let t1 = self.time();
        for (tr, m) in self.tracks.iter_mut().zip(&self.movers) {
            tr.extend_to(m, &self.map, t1);
        }
        let next = self.movers_at(t1);
        if let Some(p) = &mut self.perception {
            let s = &self.state;
            p.sense(
                &self.map,
                [s.x, s.y, s.theta],
                &discs_of(&self.movers, &next),
                t1,
            );
        }
        let fp = self.robot.footprint;
        let hit_wall = self.map.footprint_collides(&fp, &self.state);
        // The mover overlapping deepest, if any.
        let hit_mover = self
            .movers
            .iter()
            .zip(&next)
            .map(|(m, ms)| {
                (
                    m.id,
                    footprint_disc_distance(&fp, &self.state, ms.pos, m.radius),
                )
            })
            .filter(|&(_, d)| d <= 0.0)
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(id, _)| id);
        let at_rest = hypot(self.state.v, self.state.vy) < crate::world::AT_REST_SPEED;
        let d_goal = hypot(self.goal[0] - self.state.x, self.goal[1] - self.state.y);
        if d_goal < self.progress.0 - self.config.stuck_distance {
            self.progress = (d_goal, t1);
        }
        let finite = [self.state.x, self.state.y, self.state.theta]
            .iter()
            .all(|v| v.is_finite());
        self.collision = if !finite {
            Some(Collision::NonFinite)
        } else if let Some(id) = hit_mover {
            Some(Collision::Mover { id, at_rest })
        } else if hit_wall {
            Some(Collision::Wall { at_rest })
        } else {
            None
        };
        self.outcome = if self.collision.is_some() {
            Outcome::Collision
        } else if d_goal <= self.config.goal_tolerance {
            Outcome::Reached
        } else if self.steps >= self.max_steps {
            Outcome::Timeout
        } else if t1 - self.progress.1 >= self.config.stuck_time {
            Outcome::Stuck
        } else {
            Outcome::Running
        };
        let mut row = self.trace_row(cmd, Some(&ts), &next);
        if user.is_some() {
            // The planner did not run: its debug is stale.
            row.goal = self.goal;
            row.goal_kind = GoalKind::Final;
            row.mode = USER_MODE.to_string();
            row.classes.clear();
        }
        self.trace.steps.push(row);
        self.outcome
    }

    /// Steps until the episode ends; returns the outcome.
    pub fn run(&mut self) -> Outcome {
        while self.outcome == Outcome::Running {
            self.step();
        }
        self.outcome
    }

    /// The outcome so far.
    pub fn outcome(&self) -> Outcome {
        self.outcome
    }

    /// What the robot ran into and whether it was at rest, once the
    /// outcome is [`Outcome::Collision`]; `None` before and otherwise.
    pub fn collision(&self) -> Option<Collision> {
        self.collision
    }

    /// Simulated time, s (steps × dt).
    pub fn time(&self) -> f64 {
        self.steps as f64 * self.config.dt
    }

    /// Steps taken.
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// The robot's true state.
    pub fn state(&self) -> &RobotState {
        &self.state
    }

    /// The robot.
    pub fn robot(&self) -> &RobotSpec {
        &self.robot
    }

    /// The static map.
    pub fn map(&self) -> &StaticMap {
        &self.map
    }

    /// The final goal, metres.
    pub fn goal(&self) -> [f64; 2] {
        self.goal
    }

    /// Simulation settings.
    pub fn config(&self) -> &SimConfig {
        &self.config
    }

    /// The planner choice (name and config).
    pub fn planner_choice(&self) -> &PlannerChoice {
        &self.choice
    }

    /// The movers' specs.
    pub fn movers(&self) -> &[MoverSpec] {
        &self.movers
    }

    /// Every mover now: (id, radius, position and velocity).
    pub fn movers_now(&self) -> Vec<(u32, f64, MoverState)> {
        self.movers
            .iter()
            .zip(self.movers_at(self.time()))
            .map(|(m, s)| (m.id, m.radius, s))
            .collect()
    }

    /// What the planner did in its last step (with the car path, when the
    /// episode has one).
    pub fn planner_debug(&self) -> &PlannerDebug {
        match &self.car {
            Some(c) => c.debug(),
            None => self.planner.debug(),
        }
    }

    /// The car-like global path the planner follows, when the episode has
    /// a `global_planner`.
    pub fn car_guide(&self) -> Option<&CarGuide> {
        self.car.as_ref()
    }

    /// The trace so far: the start (t = 0) and one row per step.
    pub fn trace(&self) -> &Trace {
        &self.trace
    }

    /// Records (or stops recording) every rollout for drawing.
    pub fn set_record_rollouts(&mut self, on: bool) {
        self.config.record_rollouts = on;
        self.planner.set_record_rollouts(on);
    }

    /// Moves the goal (the user dragged it): checked like the start goal,
    /// then the planner re-targets (it may replan and fail with
    /// [`LocalError::NoGlobalPath`], leaving the old goal in force). The
    /// stuck timer restarts. Before the first step the planner is built
    /// afresh instead, so the episode equals one set up with this goal.
    pub fn set_goal(&mut self, goal: [f64; 2]) -> Result<(), SimError> {
        check_goal(&self.map, goal)?;
        check_reachable(&self.map, [self.state.x, self.state.y], goal)?;
        if self.steps == 0 {
            // Before the first step a new goal is a new episode: the planner
            // is built afresh, as from a scenario with this goal, so a saved
            // scenario replays the edited episode exactly.
            let mut planner =
                planners::build(&self.choice, &self.robot, &self.map, &self.state, goal)?;
            planner.set_record_rollouts(self.config.record_rollouts);
            planner.set_seed(self.seed);
            let car = match &self.car {
                Some(c) => {
                    let mut c = car_guide(
                        *c.spec(),
                        &self.choice,
                        &self.robot,
                        &self.map,
                        &self.state,
                        goal,
                    )?;
                    c.annotate(planner.debug());
                    Some(c)
                }
                None => None,
            };
            self.planner = planner;
            self.car = car;
        } else {
            // The car path first: a goal it cannot reach leaves everything
            // as it was.
            let mut car = self.car.clone();
            if let Some(c) = &mut car {
                c.retarget(&self.map, &self.state, goal)?;
            }
            self.planner.set_goal(&self.map, &self.state, goal)?;
            self.car = car;
        }
        self.goal = goal;
        let d = hypot(goal[0] - self.state.x, goal[1] - self.state.y);
        self.progress = (d, self.time());
        self.rewrite_start_row();
        Ok(())
    }

    /// Before the first step, rewrites the start row of the trace after an
    /// edit (goal, movers: their positions and the clearance are in it), so
    /// the trace is the one the edited setup gives from the start.
    fn rewrite_start_row(&mut self) {
        if self.steps == 0 {
            let row = self.trace_row(Default::default(), None, &self.movers_at(0.0));
            self.trace.steps = vec![row];
        }
    }

    /// Replaces the movers (the page edits them live). Their motion models
    /// run on episode time: a constant-velocity mover placed at p with
    /// velocity u at time t has `start` = p and `since` = t. Each is
    /// validated, also against the map ([`MoverSpec::check_on`]); a mover
    /// dropped onto the robot is a collision at the next step.
    pub fn set_movers(&mut self, movers: Vec<MoverSpec>) -> Result<(), SimError> {
        self.tracks = tracks_of(&movers, &self.map, self.time())?;
        self.movers = movers;
        self.rewrite_start_row();
        Ok(())
    }
}

/// A walled room of `width` × `height` cells of 0.2 m, the robot at rest
/// on cell (2, height / 2) facing +x and the goal on the cell as far from
/// the right wall: the episode the sim's unit tests drive (the scenario file
/// is a layer above, so they build the setup directly).
#[cfg(test)]
pub(crate) fn walled_room(
    width: usize,
    height: usize,
    planner: PlannerChoice,
    seed: u64,
) -> Episode {
    let wall = "#".repeat(width);
    let inside = format!("#{}#", ".".repeat(width - 2));
    let mut rows = vec![wall.clone()];
    rows.extend(vec![inside; height - 2]);
    rows.push(wall);
    let grid = crate::map::OccupancyGrid::from_ascii(&rows.join("\n"))
        .and_then(|g| g.with_frame(0.2, crate::map::Pose2::default()))
        .expect("a valid room");
    let (x, y) = grid.cell_to_world(2, height / 2);
    let (gx, gy) = grid.cell_to_world(width - 3, height / 2);
    Episode::new(EpisodeSetup {
        map: StaticMap::new(grid, true).expect("a simulable map"),
        robot: RobotSpec::default(),
        start: RobotState {
            x,
            y,
            ..Default::default()
        },
        goal: [gx, gy],
        movers: Vec::new(),
        planner,
        config: SimConfig::default(),
        terrain: TerrainSpec::default(),
        seed,
        perception: None,
        global_planner: None,
    })
    .expect("the room episode starts")
}

#[cfg(test)]
mod tests {
    use super::*;
    use parry2d_f64::math::{Pose, Rot2, Vector};
    use parry2d_f64::query;
    use parry2d_f64::shape::{Ball, Cuboid};

    #[test]
    fn disc_distance_matches_parry() {
        let rect = Footprint::Rectangle {
            length: 0.8,
            width: 0.4,
        };
        let mut rng = crate::num::Rng::new(3);
        for _ in 0..200 {
            let pose = RobotState {
                x: rng.range(-1.0, 1.0),
                y: rng.range(-1.0, 1.0),
                theta: rng.range(-3.0, 3.0),
                ..Default::default()
            };
            let c = [rng.range(-2.0, 2.0), rng.range(-2.0, 2.0)];
            let r = rng.range(0.05, 0.5);
            let ours = footprint_disc_distance(&rect, &pose, c, r);
            let rot = Rot2::from_cos_sin_unchecked(cos(pose.theta), sin(pose.theta));
            let p1 = Pose::from_parts(Vector::new(pose.x, pose.y), rot);
            let p2 = Pose::from_translation(Vector::new(c[0], c[1]));
            let theirs =
                query::distance(&p1, &Cuboid::new(Vector::new(0.4, 0.2)), &p2, &Ball::new(r))
                    .unwrap()
                    .distance;
            if theirs > 0.0 {
                assert!((ours - theirs).abs() < 1e-9, "{ours} vs {theirs}");
            } else {
                assert!(ours <= 1e-12, "{ours} vs {theirs}");
            }
        }
        let circle = Footprint::Circle { radius: 0.3 };
        let d = footprint_disc_distance(&circle, &RobotState::default(), [1.0, 0.0], 0.2);
        assert!((d - 0.5).abs() < 1e-15);
    }

    #[test]
    fn bounded_clearance_equals_the_full_search() {
        let g = crate::map::OccupancyGrid::from_ascii(
            "....................\n....#...............\n....#.......##......\n\
             ....#.......##......\n....................\n..........#.........\n\
             ..........#.........\n....................\n",
        )
        .unwrap()
        .with_frame(0.25, crate::map::Pose2::default())
        .unwrap();
        let map = StaticMap::new(g, true).unwrap();
        let mut rng = crate::num::Rng::new(11);
        let shapes = [
            Footprint::Circle { radius: 0.2 },
            Footprint::Rectangle {
                length: 0.5,
                width: 0.3,
            },
        ];
        let mut checked = 0;
        for _ in 0..2000 {
            let pose = RobotState {
                x: rng.range(0.0, 5.0),
                y: rng.range(0.0, 2.0),
                theta: rng.range(-3.2, 3.2),
                ..Default::default()
            };
            for fp in &shapes {
                let full = map.footprint_distance(fp, &pose, CLEARANCE_CAP);
                let fast = static_clearance(&map, fp, &pose);
                assert!(
                    (full - fast).abs() < 1e-12,
                    "{pose:?} {fp:?}: {full} vs {fast}"
                );
                checked += usize::from(full > 0.0);
            }
        }
        assert!(checked > 1000);
    }

    #[test]
    fn config_validation_names_the_field() {
        let c = SimConfig {
            dt: -0.1,
            ..Default::default()
        };
        assert!(c.validate().unwrap_err().to_string().contains("sim.dt"));
        let c = SimConfig {
            stuck_distance: f64::NAN,
            ..Default::default()
        };
        assert!(c
            .validate()
            .unwrap_err()
            .to_string()
            .contains("sim.stuck_distance"));
        let c = SimConfig {
            max_time: 1e9,
            dt: 1e-3,
            ..Default::default()
        };
        assert!(c
            .validate()
            .unwrap_err()
            .to_string()
            .contains("sim.max_time"));
        assert_eq!(SimConfig::default().max_steps(), 1200);
        assert_eq!(
            SimConfig {
                max_time: 0.25,
                ..Default::default()
            }
            .max_steps(),
            3
        );
    }
}
