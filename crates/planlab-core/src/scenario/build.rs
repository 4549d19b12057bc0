//! Scenarios to runs and back: the episode (or APF run) a scenario
//! describes, episodes as scenario files, and scenarios for bare maps.
//!
//! - [`Episode::from_scenario`]: the robot episode of a scenario on its
//!   loaded map; [`Scenario::apf_run`]: the kinematic APF run of a scenario
//!   with an `apf` section.
//! - [`Scenario::from_setup`] / [`Episode::to_scenario`]: a complete,
//!   self-contained scenario (the map inline) that rebuilds the same setup,
//!   so `planlab run` on it gives the trace the page recorded, bit for bit.
//! - [`Scenario::for_map`]: a ROS or Moving AI map opened on its own gets
//!   a start and a goal placed in free space by [`default_endpoints`] (far
//!   apart along the free space, joined by it, with room for the robot) and
//!   the default robot.

use super::document::{Scenario, ScenarioPoint, WorldPoint};
use crate::apf::AnyApfRun;
use crate::global::GridPos;
use crate::map::generate::GeneratedMap;
use crate::map::io::ScenarioError;
use crate::map::OccupancyGrid;
use crate::sim::{Episode, EpisodeSetup, SimConfig, SimError};
use crate::world::{RobotSpec, RobotState, StaticMap};
use std::collections::VecDeque;

/// Room kept around the robot's circumscribed radius when placing default
/// endpoints, m: start and goal are not pressed against a wall.
pub const ENDPOINT_MARGIN_M: f64 = 0.15;

/// The scenario point of a world position on `grid` (its cell plus the
/// exact position); `what` names it in errors.
fn point_on(grid: &OccupancyGrid, what: &str, p: [f64; 2]) -> Result<ScenarioPoint, ScenarioError> {
    let (col, row) = grid.world_to_cell(p[0], p[1]).ok_or_else(|| {
        ScenarioError::Invalid(format!(
            "{what} ({}, {}) m is off the {}×{} map",
            p[0],
            p[1],
            grid.width(),
            grid.height()
        ))
    })?;
    Ok(ScenarioPoint {
        col: col as u32,
        row: row as u32,
        world: Some(WorldPoint { x: p[0], y: p[1] }),
    })
}

impl Scenario {
    /// The kinematic APF run of the `apf` section (\[T\] ch. 4) on `grid`,
    /// the scenario's loaded map: a 2D start or goal the section leaves out
    /// is the scenario's world point.
    pub fn apf_run(&self, grid: &OccupancyGrid) -> Result<AnyApfRun, SimError> {
        let apf = self.apf.as_ref().ok_or_else(|| {
            SimError::Scenario(ScenarioError::Invalid(
                "the scenario has no `apf` section".into(),
            ))
        })?;
        let s = self.start_world(grid);
        let g = self.goal_world(grid);
        AnyApfRun::new(apf, &s, &g).map_err(|e| SimError::InvalidConfig(e.to_string()))
    }

    /// The scenario that rebuilds `setup` exactly: map inline (plain rows up
    /// to 100 cells a side, run-length encoded above), start and goal as
    /// exact world positions, robot, start heading, movers, planner with its
    /// config, simulation settings, terrain and seed. `record_rollouts`
    /// (a drawing switch that does not change the trace) is written as
    /// `false`. A scenario starts at rest: a setup whose start velocities
    /// are not zero is refused.
    pub fn from_setup(
        setup: &EpisodeSetup,
        name: &str,
        description: &str,
    ) -> Result<Scenario, ScenarioError> {
        let s = &setup.start;
        if s.v != 0.0 || s.vy != 0.0 || s.w != 0.0 {
            return Err(ScenarioError::Invalid(format!(
                "the start velocities ({}, {}, {}) are not zero: a scenario starts at rest",
                s.v, s.vy, s.w
            )));
        }
        let grid = setup.map.grid().clone();
        let start = point_on(&grid, "start", [s.x, s.y])?;
        let goal = point_on(&grid, "goal", setup.goal)?;
        let mut scenario = Scenario::new(name, grid, start.pos(), goal.pos());
        scenario.description = description.to_string();
        scenario.start = start;
        scenario.goal = goal;
        scenario.robot = Some(setup.robot);
        scenario.start_yaw = Some(s.theta);
        scenario.movers = Some(setup.movers.clone());
        scenario.local_planner = Some(setup.planner.clone());
        scenario.sim = Some(SimConfig {
            record_rollouts: false,
            ..setup.config
        });
        scenario.terrain = Some(setup.terrain.clone());
        scenario.seed = Some(setup.seed);
        scenario.perception = setup.perception;
        scenario.global_planner = setup.global_planner;
        scenario.validate()?;
        Ok(scenario)
    }

    /// The scenario of a generated map, as `planlab generate` writes it and
    /// the robot page's Generate builds it: the generated start and goal
    /// (exact world points, heading 0), the planner `planner`, and the
    /// generated-map simulation settings ([`crate::sim::generated_sim_config`]).
    pub fn for_generated(name: &str, g: &GeneratedMap, planner: &str) -> Scenario {
        let cell = |(col, row): (usize, usize)| GridPos::new(col as u32, row as u32);
        let mut s = Scenario::new(name, g.grid.clone(), cell(g.start_cell), cell(g.goal_cell));
        let world = |p: [f64; 2]| Some(WorldPoint { x: p[0], y: p[1] });
        s.start.world = world(g.start);
        s.goal.world = world(g.goal);
        s.local_planner = Some(crate::planners::PlannerChoice::named(planner));
        s.sim = Some(crate::sim::generated_sim_config(SimConfig::default()));
        s
    }

    /// A scenario for a bare map (a ROS map_server map or a Moving AI map
    /// opened without a scenario): the default robot and planner, start and
    /// goal from [`default_endpoints`], start heading towards the goal.
    pub fn for_map(name: &str, grid: OccupancyGrid) -> Result<Scenario, ScenarioError> {
        let config = SimConfig::default();
        let robot = RobotSpec::default();
        let map = StaticMap::new(grid, config.unknown_is_obstacle)
            .map_err(|e| ScenarioError::Invalid(e.to_string()))?;
        let (start, goal) = default_endpoints(&map, &robot)?;
        let grid = map.grid().clone();
        let (a, b) = (
            point_on(&grid, "start", start)?,
            point_on(&grid, "goal", goal)?,
        );
        let mut s = Scenario::new(name, grid, a.pos(), b.pos());
        s.description = format!(
            "{name}: start and goal placed automatically, far apart in the largest free area"
        );
        s.start = a;
        s.goal = b;
        s.start_yaw = Some(crate::num::atan2(goal[1] - start[1], goal[0] - start[0]));
        s.validate()?;
        Ok(s)
    }
}

impl Episode {
    /// Builds the episode a scenario describes on `grid` (its map, already
    /// loaded: see [`Scenario::load_grid`]). Start and goal are the points'
    /// `world` positions when given, else their cell centres; sections left
    /// out take their defaults (the planner: [`crate::planners::DEFAULT_PLANNER`]).
    pub fn from_scenario(scenario: &Scenario, grid: OccupancyGrid) -> Result<Episode, SimError> {
        scenario.validate_against(&grid)?;
        let config = scenario.sim.unwrap_or_default();
        config.validate()?;
        let [x, y] = scenario.start_world(&grid);
        let goal = scenario.goal_world(&grid);
        let map = StaticMap::new(grid, config.unknown_is_obstacle)?;
        Episode::new(EpisodeSetup {
            map,
            robot: scenario.robot.unwrap_or_default(),
            start: RobotState {
                x,
                y,
                theta: scenario.start_yaw.unwrap_or(0.0),
                ..Default::default()
            },
            goal,
            movers: scenario.movers.clone().unwrap_or_default(),
            planner: scenario.local_planner.clone().unwrap_or_default(),
            config,
            terrain: scenario.terrain.clone().unwrap_or_default(),
            seed: scenario.seed.unwrap_or(0),
            perception: scenario.perception,
            global_planner: scenario.global_planner,
        })
    }

    /// This episode as a self-contained scenario ([`Scenario::from_setup`]
    /// of [`Episode::setup`]): the current map, goal, movers and planner,
    /// from the original start.
    pub fn to_scenario(&self, name: &str, description: &str) -> Result<Scenario, ScenarioError> {
        Scenario::from_setup(&self.setup(), name, description)
    }
}

/// A start and a goal for `robot` on `map`, world metres: cell centres with
/// room for the robot (clearance of at least its circumscribed radius plus
/// [`ENDPOINT_MARGIN_M`], also from the map edge), in the largest
/// 4-connected area of such cells, as far apart along that area as a double
/// sweep of breadth-first searches finds (the first from the area's first
/// cell finds one end, the second from there the other end). Deterministic.
/// Errors when no cell has room for the robot.
pub fn default_endpoints(
    map: &StaticMap,
    robot: &RobotSpec,
) -> Result<([f64; 2], [f64; 2]), ScenarioError> {
    let grid = map.grid();
    let (w, h) = (grid.width(), grid.height());
    let res = grid.resolution();
    let need = robot.footprint.circumscribed_radius() + ENDPOINT_MARGIN_M;
    let roomy: Vec<bool> = (0..w * h)
        .map(|i| {
            let (c, r) = (i % w, i / w);
            // Cell centre to the map edge, m.
            let edge = res * ((c.min(w - 1 - c).min(r).min(h - 1 - r)) as f64 + 0.5);
            !map.is_blocked(c as i64, r as i64)
                && edge >= need
                && map.cell_clearance(c as i64, r as i64) >= need
        })
        .collect();
    // Largest 4-connected area of roomy cells (first found wins ties).
    let mut label = vec![u32::MAX; w * h];
    let mut best: Option<(usize, usize)> = None; // (size, first cell)
    let mut queue = VecDeque::new();
    for seed in 0..w * h {
        if !roomy[seed] || label[seed] != u32::MAX {
            continue;
        }
        let id = seed as u32;
        label[seed] = id;
        queue.push_back(seed);
        let mut size = 0usize;
        while let Some(i) = queue.pop_front() {
            size += 1;
            for j in neighbours(i, w, h) {
                if roomy[j] && label[j] == u32::MAX {
                    label[j] = id;
                    queue.push_back(j);
                }
            }
        }
        if best.map_or(true, |(n, _)| size > n) {
            best = Some((size, seed));
        }
    }
    let Some((_, first)) = best else {
        return Err(ScenarioError::Invalid(format!(
            "no free cell of the {w}×{h} map has room for the robot (clearance ≥ {need:.2} m): cannot place a start and a goal"
        )));
    };
    let area = label[first];
    let farthest = |from: usize| -> usize {
        let mut dist = vec![u32::MAX; w * h];
        dist[from] = 0;
        let mut q = VecDeque::from([from]);
        let mut last = from;
        while let Some(i) = q.pop_front() {
            last = i;
            for j in neighbours(i, w, h) {
                if label[j] == area && dist[j] == u32::MAX {
                    dist[j] = dist[i] + 1;
                    q.push_back(j);
                }
            }
        }
        last
    };
    let a = farthest(first);
    let b = farthest(a);
    let centre = |i: usize| {
        let (x, y) = grid.cell_to_world(i % w, i / w);
        [x, y]
    };
    Ok((centre(a), centre(b)))
}

/// The 4-neighbours of cell index `i` on a `w`×`h` grid.
fn neighbours(i: usize, w: usize, h: usize) -> impl Iterator<Item = usize> {
    let (c, r) = (i % w, i / w);
    [
        (c > 0).then(|| i - 1),
        (c + 1 < w).then(|| i + 1),
        (r > 0).then(|| i - w),
        (r + 1 < h).then(|| i + w),
    ]
    .into_iter()
    .flatten()
}
