//! Reference workloads for the benchmarks, defined once so that every
//! timing of them runs exactly the same code on exactly the same data:
//! natively (the criterion benches, `planlab bench step` and
//! `planlab bench scen`) and in WebAssembly (the browser benchmark,
//! `scripts/bench-browser.mjs`). Nothing here reads a clock; the callers
//! time [`DwaStepBench::run`] and [`ScenBatch::solve_all`] themselves.
//!
//! - [`DwaStepBench`]: one DWA control step of a fixed reference scene,
//!   20 × 40 (v, ω) samples, 3 s horizon at 0.1 s, a 200 × 200 map at
//!   0.1 m with 60 seeded blocks, 20 seeded movers.
//! - [`ScenBatch`]: every query of a Moving AI `.scen` planned once, with
//!   the planner and passability grid built beforehand.

use thiserror::Error;

use crate::global::plan::{build_planner, plan_grid_for, GridPlanError, GridPlanOptions};
use crate::global::{GridPlanner, GridPos, PlanError, PlanGrid};
use crate::local::dwa::DwaConfig;
use crate::local::engine::{Engine, StepRequest, StepResult};
use crate::local::{LocalError, Observation, ObservedMover};
use crate::map::io::movingai;
use crate::map::{Cell, MapError, OccupancyGrid, Pose2};
use crate::num::{self, Rng};
use crate::world::{RobotSpec, RobotState, StaticMap};

/// One DWA step on the reference scene, repeated (the state never
/// advances, so every step does the same work and picks the same command).
pub struct DwaStepBench {
    map: StaticMap,
    movers: Vec<ObservedMover>,
    state: RobotState,
    goal: [f64; 2],
    core: Engine,
    robot: RobotSpec,
}

impl DwaStepBench {
    /// The reference scene: 200 × 200 cells at 0.1 m (20 m square), 60
    /// seeded blocks of 3–8 cells kept 1.5 m away from the robot at the
    /// centre, 20 movers of radius 0.2–0.4 m at 0–0.5 m/s, goal (18, 16) m,
    /// the default robot, DWA with 20 × 40 samples over 3 s at 0.1 s.
    pub fn reference() -> Result<Self, LocalError> {
        let mut rng = Rng::new(7);
        let (w, h) = (200usize, 200usize);
        let mut cells = vec![Cell::Free; w * h];
        let centre = (100.0, 100.0);
        for _ in 0..60 {
            let (c0, r0) = (
                rng.range(0.0, 190.0) as usize,
                rng.range(0.0, 190.0) as usize,
            );
            let (bw, bh) = (rng.range(3.0, 9.0) as usize, rng.range(3.0, 9.0) as usize);
            // Keep a 1.5 m disc around the robot free (centre-to-block distance).
            let gap = |lo: f64, len: f64, c: f64| (lo - c).max(c - (lo + len)).max(0.0);
            let (gx, gy) = (
                gap(c0 as f64, bw as f64, centre.0),
                gap(r0 as f64, bh as f64, centre.1),
            );
            if num::hypot(gx, gy) < 15.0 {
                continue;
            }
            for r in r0..(r0 + bh).min(h) {
                for c in c0..(c0 + bw).min(w) {
                    cells[r * w + c] = Cell::Occupied;
                }
            }
        }
        let grid = OccupancyGrid::from_cells(w, h, cells)
            .and_then(|g| g.with_frame(0.1, Pose2::default()))
            .map_err(|e| LocalError::InvalidParameter(e.to_string()))?;
        let map =
            StaticMap::new(grid, true).map_err(|e| LocalError::InvalidParameter(e.to_string()))?;
        let state = RobotState {
            x: 10.0,
            y: 10.0,
            theta: 0.4,
            v: 0.3,
            vy: 0.0,
            w: 0.1,
        };
        let mut movers = Vec::new();
        while movers.len() < 20 {
            let pos = [rng.range(1.0, 19.0), rng.range(1.0, 19.0)];
            let r = rng.range(0.2, 0.4);
            if num::hypot(pos[0] - 10.0, pos[1] - 10.0) < 3.0 + r
                || map.clearance(pos[0], pos[1]) < r
            {
                continue;
            }
            let (speed, dir) = (
                rng.range(0.0, 0.5),
                rng.range(-std::f64::consts::PI, std::f64::consts::PI),
            );
            movers.push(ObservedMover {
                id: movers.len() as u32,
                pos,
                vel: [speed * num::cos(dir), speed * num::sin(dir)],
                radius: r,
            });
        }
        let robot = RobotSpec::default();
        let cfg = DwaConfig {
            v_samples: 20,
            w_samples: 40,
            predict_time: 3.0,
            sim_dt: 0.1,
            ..Default::default()
        };
        let core = cfg.engine(&robot, "dwa", false)?;
        let goal = [18.0, 16.0];
        Ok(Self {
            map,
            movers,
            state,
            goal,
            core,
            robot,
        })
    }

    /// The robot the scene plans for.
    pub fn robot(&self) -> &RobotSpec {
        &self.robot
    }

    /// The robot's state (start of every step).
    pub fn state(&self) -> &RobotState {
        &self.state
    }

    /// The movers of the scene.
    pub fn movers(&self) -> &[ObservedMover] {
        &self.movers
    }

    /// Records every rollout for drawing from now on (slower), or stops.
    pub fn set_record(&mut self, on: bool) {
        self.core.set_record(on);
    }

    /// One control step.
    pub fn step(&mut self) -> StepResult {
        let obs = Observation {
            time: 0.0,
            dt: 0.1,
            state: &self.state,
            goal: self.goal,
            map: &self.map,
            map_revision: 0,
            scan: None,
            movers: &self.movers,
            odometry: None,
            accel_z: 0.0,
        };
        self.core.plan(&obs, &StepRequest::to(self.goal))
    }

    /// `n` steps; the sum of the chosen v + ω over them, a checksum both
    /// sides of a comparison must agree on (and that keeps the work from
    /// being optimised away).
    pub fn run(&mut self, n: usize) -> f64 {
        (0..n)
            .map(|_| {
                let r = self.step();
                r.cmd.v + r.cmd.w
            })
            .sum()
    }
}

/// Why a [`ScenBatch`] could not be built or solved.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum ScenBatchError {
    /// The `.scen` is malformed or does not fit the map.
    #[error(transparent)]
    Map(#[from] MapError),
    /// The options are invalid or a query failed.
    #[error(transparent)]
    Plan(#[from] PlanError),
    /// The plan grid could not be built (e.g. a bad inflation radius).
    #[error(transparent)]
    Grid(#[from] GridPlanError),
    /// A query failed; `row` is 1-based.
    #[error("scenario query {row}: {source}")]
    Query {
        /// 1-based query number.
        row: usize,
        /// The planner's error.
        source: PlanError,
    },
}

/// Queries of one `.scen` with the planner and passability grid built once.
pub struct ScenBatch {
    grid: PlanGrid,
    planner: Box<dyn GridPlanner>,
    queries: Vec<(GridPos, GridPos)>,
    optimal_sum: f64,
}

impl ScenBatch {
    /// Parses `scen_text`, checks it against `map` and builds the planner.
    pub fn new(
        map: &OccupancyGrid,
        scen_text: &str,
        options: &GridPlanOptions,
    ) -> Result<Self, ScenBatchError> {
        let rows = movingai::parse_scen(scen_text)?;
        movingai::check_scen_against_map(&rows, map)?;
        Ok(Self {
            grid: plan_grid_for(map, options)?,
            planner: build_planner(options)?,
            optimal_sum: rows.iter().map(|r| r.optimal).sum(),
            queries: rows.iter().map(|r| (r.start, r.goal)).collect(),
        })
    }

    /// Number of queries.
    pub fn len(&self) -> usize {
        self.queries.len()
    }

    /// Whether there are no queries.
    pub fn is_empty(&self) -> bool {
        self.queries.is_empty()
    }

    /// Sum of the scenario's optimal lengths, to check [`ScenBatch::solve_all`].
    pub fn optimal_sum(&self) -> f64 {
        self.optimal_sum
    }

    /// Plans every query once; the summed path cost.
    pub fn solve_all(&self) -> Result<f64, ScenBatchError> {
        let mut total = 0.0;
        for (i, &(s, g)) in self.queries.iter().enumerate() {
            let path = self
                .planner
                .plan(&self.grid, s, g)
                .map_err(|source| ScenBatchError::Query { row: i + 1, source })?;
            total += path.cost;
        }
        Ok(total)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dwa_reference_step_is_sane_and_repeatable() {
        let mut b = DwaStepBench::reference().unwrap();
        assert_eq!(b.movers().len(), 20);
        let r = b.step();
        let l = b.robot().limits;
        assert!(r.samples >= 800, "{} samples", r.samples);
        assert!(r.admissible > 0, "no admissible sample");
        // Inside the dynamic window of one 0.1 s period.
        assert!(
            (r.cmd.v - b.state().v).abs() <= l.acc_v * 0.1 + 1e-9,
            "{:?}",
            r.cmd
        );
        assert!(
            (r.cmd.w - b.state().w).abs() <= l.acc_w * 0.1 + 1e-9,
            "{:?}",
            r.cmd
        );
        // The state never advances: three steps are three times one.
        let one = r.cmd.v + r.cmd.w;
        assert_eq!(b.run(3), one * 3.0);
    }

    #[test]
    fn scen_batch_solves_to_the_optimum_and_names_a_bad_row() {
        let map = OccupancyGrid::from_ascii("....\n.##.\n....\n").unwrap();
        let scen = "version 1\n0\tm.map\t4\t3\t0\t0\t3\t2\t5\n";
        let b = ScenBatch::new(&map, scen, &GridPlanOptions::default()).unwrap();
        assert_eq!(b.len(), 1);
        assert!((b.solve_all().unwrap() - b.optimal_sum()).abs() < 1e-6);
        // Row 2 starts in a wall.
        let scen2 = format!("{scen}0\tm.map\t4\t3\t1\t1\t3\t2\t1\n");
        let err = match ScenBatch::new(&map, &scen2, &GridPlanOptions::default()) {
            Ok(b) => b.solve_all().unwrap_err().to_string(),
            Err(e) => e.to_string(),
        };
        assert!(err.contains('2') || err.contains("(1, 1)"), "{err}");
    }
}
