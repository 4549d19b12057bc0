//! Scenario edits (the page's editing tools): a new episode from this
//! one's setup with a different map, start, goal or movers, back at t = 0.
//! A new map rebuilds the clearance field ([`StaticMap::new`]) and the
//! planner replans its global path; every check of [`Episode::new`]
//! applies, so a wall drawn over the robot's start is refused with
//! [`WorldError::StartInCollision`] and the old episode stays as it was.

use super::{Episode, SimConfig, SimError};
use crate::global::plan::{plan_on_map, GridPlanError, GridPlanOptions};
use crate::global::GridPos;
use crate::map::edit::MapEdit;
use crate::map::generate::GeneratedMap;
use crate::map::OccupancyGrid;
use crate::world::{MoverSpec, RobotState, StaticMap, WorldError};

/// What an edit changes; `None` keeps the episode's own.
#[derive(Debug, Clone, Default)]
pub struct SetupEdit {
    /// A new static map.
    pub grid: Option<OccupancyGrid>,
    /// A new start pose (x, y, θ; velocities are taken as given).
    pub start: Option<RobotState>,
    /// A new goal, world metres.
    pub goal: Option<[f64; 2]>,
    /// New simulation settings.
    pub config: Option<SimConfig>,
    /// New movers.
    pub movers: Option<Vec<MoverSpec>>,
}

impl Episode {
    /// A fresh episode (t = 0) from this one's setup ([`Episode::setup`]:
    /// original start, current goal, movers and planner) with `edit`
    /// applied. Errors are [`Episode::new`]'s; `self` is untouched.
    pub fn edited(&self, edit: SetupEdit) -> Result<Episode, SimError> {
        let mut setup = self.setup();
        if let Some(grid) = edit.grid {
            setup.map = StaticMap::new(grid, setup.config.unknown_is_obstacle)?;
        }
        if let Some(s) = edit.start {
            setup.start = s;
        }
        if let Some(g) = edit.goal {
            setup.goal = g;
        }
        if let Some(m) = edit.movers {
            setup.movers = m;
        }
        if let Some(c) = edit.config {
            setup.config = c;
        }
        Episode::new(setup)
    }

    /// The episode restarted from its setup (t = 0), keeping every edit.
    pub fn restarted(&self) -> Result<Episode, SimError> {
        self.edited(SetupEdit::default())
    }

    /// Paints `edit` into a copy of the map and restarts on it; returns
    /// the new episode and how many cells changed. Painting a wall over
    /// the robot's start is [`WorldError::StartInCollision`].
    pub fn with_map_edit(&self, edit: &MapEdit) -> Result<(Episode, usize), SimError> {
        let mut grid = self.map().grid().clone();
        let changed = edit.apply(&mut grid)?;
        Ok((
            self.edited(SetupEdit {
                grid: Some(grid),
                ..Default::default()
            })?,
            changed,
        ))
    }

    /// Restarts on a generated map with its start (heading +x) and goal;
    /// the movers are dropped (they belonged to the old map) and the
    /// settings become [`generated_sim_config`]'s.
    pub fn with_generated(&self, g: &GeneratedMap) -> Result<Episode, SimError> {
        self.edited(SetupEdit {
            config: Some(generated_sim_config(self.config)),
            grid: Some(g.grid.clone()),
            start: Some(RobotState {
                x: g.start[0],
                y: g.start[1],
                ..Default::default()
            }),
            goal: Some(g.goal),
            movers: Some(Vec::new()),
        })
    }

    /// The start pose the episode began from.
    pub fn start_pose(&self) -> &RobotState {
        &self.start
    }
}

impl Episode {
    /// One line when the goal can be reached on the bare map but not on
    /// the map inflated by the robot's inscribed radius: every way there
    /// passes a gap narrower than the robot, so a planner whose global path
    /// ignores the robot's size (or plain DWA) will end stuck in it. `None`
    /// when a path fits the robot, when there is no path at all (the
    /// planner says so itself), or when the start or goal lies in the
    /// inflation (a robot parked by a wall).
    pub fn route_note(&self) -> Option<String> {
        let grid = self.map.grid();
        let radius = self.robot.footprint.inscribed_radius();
        let cell = |p: [f64; 2]| {
            grid.world_to_cell(p[0], p[1])
                .map(|(c, r)| GridPos::new(c as u32, r as u32))
        };
        let (s, g) = (cell([self.start.x, self.start.y])?, cell(self.goal)?);
        let inflated = GridPlanOptions {
            inflate_m: radius,
            ..Default::default()
        };
        match plan_on_map(grid, s, g, &inflated) {
            Err(GridPlanError::Plan(_)) => {}
            _ => return None,
        }
        plan_on_map(grid, s, g, &GridPlanOptions::default())
            .is_ok()
            .then(|| {
                format!(
                    "no way to the goal for a robot of radius {radius:.2} m: the only paths pass gaps narrower than the robot (a path exists only without inflation)"
                )
            })
    }
}

/// Shortest stuck time on generated maps, s: a maze detour runs away from
/// the goal for longer than the default 15 s without being stuck.
pub const GENERATED_STUCK_TIME: f64 = 60.0;
/// Shortest time limit on generated maps, s.
pub const GENERATED_MAX_TIME: f64 = 600.0;

/// `base` with the stuck time and time limit raised to
/// [`GENERATED_STUCK_TIME`] and [`GENERATED_MAX_TIME`] (what `planlab
/// generate` writes into its scenario and the page uses on a generated map).
pub fn generated_sim_config(base: SimConfig) -> SimConfig {
    SimConfig {
        stuck_time: base.stuck_time.max(GENERATED_STUCK_TIME),
        max_time: base.max_time.max(GENERATED_MAX_TIME),
        ..base
    }
}

/// Whether an error says the robot's start overlaps something: the page
/// names the tool that caused it.
pub fn is_start_collision(e: &SimError) -> bool {
    matches!(e, SimError::World(WorldError::StartInCollision { .. }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::{Cell, Pose2};
    use crate::planners::PlannerChoice;
    use crate::sim::{EpisodeSetup, Outcome, SimConfig, GENERATED_STUCK_TIME};
    use crate::world::RobotSpec;

    fn episode() -> Episode {
        let grid = OccupancyGrid::new(60, 40)
            .unwrap()
            .with_frame(0.1, Pose2::default())
            .unwrap();
        Episode::new(EpisodeSetup {
            map: StaticMap::new(grid, true).unwrap(),
            robot: RobotSpec::default(),
            start: RobotState {
                x: 0.5,
                y: 2.0,
                ..Default::default()
            },
            goal: [5.5, 2.0],
            movers: Vec::new(),
            planner: PlannerChoice::named("cleaning-dwa"),
            config: SimConfig::default(),
            terrain: Default::default(),
            seed: 0,
            perception: None,
            global_planner: None,
        })
        .unwrap()
    }

    #[test]
    fn a_wall_across_the_route_is_driven_around() {
        let mut ep = episode();
        ep.step();
        // Straight run first: the global path is a straight line.
        let straight_max_dy = ep
            .planner_debug()
            .global_path
            .iter()
            .map(|p| (p[1] - 2.0).abs())
            .fold(0.0, f64::max);
        // A wall at x = 3 from y = 0.8 to 3.2, leaving gaps near the edges.
        let wall = MapEdit::Stroke {
            points: vec![[3.0, 0.9], [3.0, 3.1]],
            radius: 0.1,
            cell: Cell::Occupied,
        };
        let (mut edited, changed) = ep.with_map_edit(&wall).unwrap();
        assert!(changed > 20);
        assert_eq!(edited.steps(), 0, "an edit restarts the episode");
        edited.step();
        assert!(edited.map().clearance(3.0, 2.0) < 1e-9);
        // The clearance field was rebuilt: 0.4 m left of the wall is ≈ 0.35 m.
        assert!(edited.map().clearance(2.6, 2.0) < 0.45);
        let detour = edited
            .planner_debug()
            .global_path
            .iter()
            .map(|p| (p[1] - 2.0).abs())
            .fold(0.0, f64::max);
        assert!(detour > 1.0 && straight_max_dy < 0.1, "{detour}");
        assert_eq!(edited.run(), Outcome::Reached);
        let ys: Vec<f64> = edited
            .trace()
            .steps
            .iter()
            .filter(|r| (r.x - 3.0).abs() < 0.2)
            .map(|r| r.y)
            .collect();
        assert!(!ys.is_empty() && ys.iter().all(|y| (y - 2.0).abs() > 1.0));
    }

    #[test]
    fn a_wall_over_the_start_is_refused() {
        let ep = episode();
        let blob = MapEdit::Disc {
            centre: [0.6, 2.0],
            radius: 0.3,
            cell: Cell::Occupied,
        };
        let e = ep.with_map_edit(&blob).unwrap_err();
        assert!(is_start_collision(&e), "{e}");
        assert!(e.to_string().contains("a wall"));
        // The episode is untouched.
        assert_eq!(ep.map().grid().counts().1, 0);
        // A start moved into a wall is refused the same way.
        let boxed = MapEdit::Rect {
            a: [4.0, 0.0],
            b: [4.5, 1.0],
            cell: Cell::Occupied,
        };
        let (walled, _) = ep.with_map_edit(&boxed).unwrap();
        let inside = walled.edited(SetupEdit {
            start: Some(RobotState {
                x: 4.2,
                y: 0.5,
                ..Default::default()
            }),
            ..Default::default()
        });
        assert!(is_start_collision(&inside.unwrap_err()));
        // A wall over the goal is a goal error, one sealing it off too.
        let over_goal = MapEdit::Disc {
            centre: [5.5, 2.0],
            radius: 0.2,
            cell: Cell::Occupied,
        };
        assert!(matches!(
            ep.with_map_edit(&over_goal).unwrap_err(),
            SimError::BadGoal { .. }
        ));
        let seal = MapEdit::Stroke {
            points: vec![[3.0, -1.0], [3.0, 5.0]],
            radius: 0.1,
            cell: Cell::Occupied,
        };
        assert!(matches!(
            ep.with_map_edit(&seal).unwrap_err(),
            SimError::Unreachable { .. }
        ));
    }

    #[test]
    fn start_goal_and_generated_maps() {
        let ep = episode();
        let moved = ep
            .edited(SetupEdit {
                start: Some(RobotState {
                    x: 1.0,
                    y: 1.0,
                    theta: 1.0,
                    ..Default::default()
                }),
                goal: Some([5.0, 3.0]),
                ..Default::default()
            })
            .unwrap();
        assert_eq!(moved.start_pose().theta, 1.0);
        assert_eq!(moved.goal(), [5.0, 3.0]);
        let g = crate::map::generate::generate(&crate::map::generate::GenerateConfig {
            kind: crate::map::generate::GeneratorKind::Rooms,
            seed: 0,
            ..Default::default()
        })
        .unwrap();
        let mut on_rooms = moved.with_generated(&g).unwrap();
        assert_eq!(on_rooms.config().stuck_time, GENERATED_STUCK_TIME);
        on_rooms
            .set_planner(PlannerChoice::named("improved-dwa"))
            .unwrap();
        assert_eq!(on_rooms.map().grid().content_hash(), g.grid.content_hash());
        assert_eq!(on_rooms.run(), Outcome::Reached);
    }
}
