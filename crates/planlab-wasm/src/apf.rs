//! [`ApfHandle`]: one 2D potential-field run (core `apf::ApfRun`) for the
//! APF page: steps, live edits (goal, variant, predictor) and everything
//! drawn as typed arrays — the path, obstacles, the force field on a
//! lattice, the sampled directions with their costs and the chosen one,
//! the predicted obstacles with their virtual ranges. No field is
//! computed here: every number comes from the core.

use glam::DVec2;
use planlab_core::apf::{
    ApfMode, ApfRun, ApfScene, ApfVector, ObstacleObs, PredictorKind, StepKind,
};
use planlab_core::map::io::scenario::Scenario;
use wasm_bindgen::prelude::*;

fn js(e: impl std::fmt::Display) -> JsError {
    JsError::new(&e.to_string())
}

/// A 2D APF run and the scene it restarts from.
#[wasm_bindgen]
pub struct ApfHandle {
    scene: ApfScene,
    start: DVec2,
    goal: DVec2,
    bounds: [f64; 4],
    run: ApfRun<DVec2>,
}

fn mode_of(name: &str) -> Result<ApfMode, JsError> {
    match name {
        "basic" => Ok(ApfMode::Basic),
        "sampling" => Ok(ApfMode::Sampling),
        "sampling-prediction" => Ok(ApfMode::SamplingPrediction),
        _ => Err(JsError::new(&format!(
            "unknown APF variant `{name}`: use basic, sampling or sampling-prediction"
        ))),
    }
}

#[wasm_bindgen]
impl ApfHandle {
    /// Reads a scenario JSON with a 2D `apf` section (inline map).
    #[wasm_bindgen(constructor)]
    pub fn new(json: &str) -> Result<ApfHandle, JsError> {
        let sc = Scenario::from_json(json).map_err(js)?;
        let grid = sc
            .inline_grid()
            .map_err(js)?
            .ok_or_else(|| JsError::new("the APF page needs an inline map"))?;
        let scene = sc
            .apf
            .clone()
            .ok_or_else(|| JsError::new("the scenario has no `apf` section"))?;
        let pick = |given: &Option<Vec<f64>>, fallback: [f64; 2], what: &str| {
            let v = given.clone().unwrap_or(fallback.to_vec());
            <DVec2 as ApfVector>::from_slice(&v).ok_or_else(|| {
                JsError::new(&format!(
                    "apf.{what}: the APF page is 2D (2 coordinates), got {v:?}"
                ))
            })
        };
        let start = pick(&scene.start, sc.start_world(&grid), "start")?;
        let goal = pick(&scene.goal, sc.goal_world(&grid), "goal")?;
        let (w, h, r, o) = (
            grid.width() as f64,
            grid.height() as f64,
            grid.resolution(),
            grid.origin(),
        );
        let run = ApfRun::new(&scene, start, goal).map_err(js)?;
        Ok(ApfHandle {
            scene,
            start,
            goal,
            bounds: [o.x, o.y, o.x + w * r, o.y + h * r],
            run,
        })
    }

    /// Restarts from the start with the current goal, variant and predictor.
    pub fn reset(&mut self) -> Result<(), JsError> {
        self.run = ApfRun::new(&self.scene, self.start, self.goal).map_err(js)?;
        Ok(())
    }

    /// Switches the variant (`basic`, `sampling`, `sampling-prediction`)
    /// and restarts.
    #[wasm_bindgen(js_name = setMode)]
    pub fn set_mode(&mut self, mode: &str) -> Result<(), JsError> {
        self.scene.config.mode = mode_of(mode)?;
        self.reset()
    }

    /// Switches the predictor (`constant-velocity`, `rnn`) and restarts.
    #[wasm_bindgen(js_name = setPredictor)]
    pub fn set_predictor(&mut self, name: &str) -> Result<(), JsError> {
        self.scene.config.predictor = match name {
            "constant-velocity" => PredictorKind::ConstantVelocity,
            "rnn" => PredictorKind::Rnn,
            _ => return Err(JsError::new(&format!("unknown predictor `{name}`"))),
        };
        self.reset()
    }

    /// The variant's name.
    pub fn mode(&self) -> String {
        self.scene.config.mode.label().into()
    }

    /// Moves the goal (m) and restarts; a goal inside an obstacle is an
    /// error and leaves the run as it was.
    #[wasm_bindgen(js_name = setGoal)]
    pub fn set_goal(&mut self, x: f64, y: f64) -> Result<(), JsError> {
        let goal = DVec2::new(x, y);
        let run = ApfRun::new(&self.scene, self.start, goal).map_err(js)?;
        self.goal = goal;
        self.run = run;
        Ok(())
    }

    /// Up to `n` planning steps; the outcome after them (`running`,
    /// `reached`, `stuck`, `collision`, `timeout`).
    pub fn step(&mut self, n: u32) -> Result<String, JsError> {
        for _ in 0..n {
            self.run.step().map_err(js)?;
        }
        Ok(self.outcome())
    }

    /// The outcome so far.
    pub fn outcome(&self) -> String {
        self.run.outcome().to_string()
    }

    /// Time of the run, s.
    pub fn time(&self) -> f64 {
        self.run.time()
    }

    /// Map extent (x_min, y_min, x_max, y_max), m.
    pub fn bounds(&self) -> Vec<f64> {
        self.bounds.to_vec()
    }

    /// Start and goal (x, y, x, y), m.
    pub fn endpoints(&self) -> Vec<f64> {
        vec![self.start.x, self.start.y, self.goal.x, self.goal.y]
    }

    /// The path so far as (x, y) pairs, m.
    pub fn path(&self) -> Vec<f64> {
        self.run.path().iter().flat_map(|p| [p.x, p.y]).collect()
    }

    /// The obstacles now as (x, y, radius, range) quadruples, m (range =
    /// radius + p₀, where repulsion ends).
    pub fn obstacles(&self) -> Vec<f64> {
        let p0 = self.scene.config.p0;
        self.run
            .obstacles_at(self.run.time())
            .iter()
            .flat_map(|o| [o.centre.x, o.centre.y, o.radius, o.radius + p0])
            .collect()
    }

    /// Predicted obstacles of the last step as (x, y, virtual range, k)
    /// quadruples (k = 1 for t+1, 2 for t+2).
    pub fn predicted(&self) -> Vec<f64> {
        self.run
            .last_step()
            .map(|s| {
                s.predicted
                    .iter()
                    .flat_map(|v| [v.centre.x, v.centre.y, v.range, f64::from(v.k)])
                    .collect()
            })
            .unwrap_or_default()
    }

    /// Sampled candidates of the last step as (x, y, cost) triples.
    pub fn candidates(&self) -> Vec<f64> {
        self.run
            .last_step()
            .map(|s| {
                s.candidates
                    .iter()
                    .flat_map(|c| [c.point.x, c.point.y, c.cost])
                    .collect()
            })
            .unwrap_or_default()
    }

    /// Index of the chosen candidate of the last step, −1 for none.
    pub fn chosen(&self) -> i32 {
        self.run
            .last_step()
            .and_then(|s| s.chosen)
            .map_or(-1, |i| i as i32)
    }

    /// How the last step was chosen (`resultant`, `sampled`,
    /// `relative-distance`, `stalled`, `arrived`, or `none`).
    #[wasm_bindgen(js_name = stepKind)]
    pub fn step_kind(&self) -> String {
        match self.run.last_step().map(|s| s.kind) {
            Some(StepKind::Resultant) => "resultant",
            Some(StepKind::Sampled) => "sampled",
            Some(StepKind::RelativeDistance) => "relative-distance",
            Some(StepKind::Stalled) => "stalled",
            Some(StepKind::Arrived) => "arrived",
            None => "none",
        }
        .into()
    }

    /// The force field now on an `nx` × `ny` lattice of cell centres over
    /// the map (row 0 at the bottom): (F_x, F_y) of the resultant per
    /// point, real and predicted obstacles included.
    pub fn field(&self, nx: u32, ny: u32) -> Vec<f64> {
        let (nx, ny) = (nx.clamp(1, 400), ny.clamp(1, 400));
        let [x0, y0, x1, y1] = self.bounds;
        let obs: Vec<ObstacleObs<DVec2>> = self.run.obstacles_at(self.run.time());
        let virtuals = self
            .run
            .last_step()
            .map(|s| s.predicted.clone())
            .unwrap_or_default();
        let apf = self.run.planner();
        let mut out = Vec::with_capacity((2 * nx * ny) as usize);
        for j in 0..ny {
            for i in 0..nx {
                let p = DVec2::new(
                    x0 + (i as f64 + 0.5) * (x1 - x0) / nx as f64,
                    y0 + (j as f64 + 0.5) * (y1 - y0) / ny as f64,
                );
                let (a, r) = apf.forces_at(p, self.goal, &obs, &virtuals);
                let f = a + r;
                out.extend([f.x, f.y]);
            }
        }
        out
    }

    /// Attraction, repulsion and resultant at the robot (6 numbers).
    pub fn forces(&self) -> Vec<f64> {
        self.run
            .last_step()
            .map(|s| {
                vec![
                    s.attraction.x,
                    s.attraction.y,
                    s.repulsion.x,
                    s.repulsion.y,
                    s.resultant.x,
                    s.resultant.y,
                ]
            })
            .unwrap_or_else(|| vec![0.0; 6])
    }

    /// The metrics as JSON (`outcome`, `path_length_m`, `path_points`,
    /// `spikes`, `min_obstacle_distance_m`, `time_s`).
    pub fn metrics(&self) -> String {
        serde_json::to_string(&self.run.metrics()).unwrap_or_default()
    }

    /// The robot's position (x, y), m.
    pub fn position(&self) -> Vec<f64> {
        let p = self.run.position();
        vec![p.x, p.y]
    }

    /// Number of coordinates of the scene (always 2 here).
    pub fn dims(&self) -> u32 {
        DVec2::DIM as u32
    }
}
