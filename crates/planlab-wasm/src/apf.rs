//! [`ApfHandle`]: one potential-field run (core `apf::ApfRun`) for the
//! APF page: steps, live edits (goal, variant, predictor) and everything
//! drawn as typed arrays — the path, obstacles, the force field on a
//! lattice, the sampled directions with their costs and the chosen one,
//! the predicted obstacles with their virtual ranges. A 3D scene (\[T\]
//! Table 4-1: the end effector and the hand) runs in 3D and is reported in
//! its side view (x, z), the plane its detours happen in: "x, y" below means
//! the page's two drawing coordinates. No field is computed here: every
//! number comes from the core.

use glam::{DVec2, DVec3};
use planlab_core::apf::{ApfMode, ApfRun, ApfScene, ApfVector, PredictorKind, StepKind};
use planlab_core::scenario::Scenario;
use wasm_bindgen::prelude::*;

fn js(e: impl std::fmt::Display) -> JsError {
    JsError::new(&e.to_string())
}

/// One run in its own dimension, with the start and goal it restarts from.
struct Core<V: ApfVector> {
    start: V,
    goal: V,
    run: ApfRun<V>,
}

/// The page's (x, y) of a point: the side view (x, z) of a 3D one.
use planlab_core::draw::{self, from_plane_xy as at_xy, plane_xy as xy};

impl<V: ApfVector> Core<V> {
    fn new(scene: &ApfScene, start: V, goal: V) -> Result<Self, JsError> {
        Ok(Core {
            start,
            goal,
            run: ApfRun::new(scene, start, goal).map_err(js)?,
        })
    }

    fn reset(&mut self, scene: &ApfScene) -> Result<(), JsError> {
        self.run = ApfRun::new(scene, self.start, self.goal).map_err(js)?;
        Ok(())
    }

    fn set_goal(&mut self, scene: &ApfScene, x: f64, y: f64) -> Result<(), JsError> {
        let goal = at_xy(self.goal, x, y);
        let run = ApfRun::new(scene, self.start, goal).map_err(js)?;
        self.goal = goal;
        self.run = run;
        Ok(())
    }

    fn step(&mut self, n: u32) -> Result<(), JsError> {
        for _ in 0..n {
            self.run.step().map_err(js)?;
        }
        Ok(())
    }

    fn endpoints(&self) -> Vec<f64> {
        let [sx, sy] = xy(self.start);
        let [gx, gy] = xy(self.goal);
        vec![sx, sy, gx, gy]
    }

    fn path(&self) -> Vec<f64> {
        self.run.path().iter().flat_map(|p| xy(*p)).collect()
    }

    fn obstacles(&self, p0: f64) -> Vec<f64> {
        self.run
            .obstacles_at(self.run.time())
            .iter()
            .flat_map(|o| {
                let [x, y] = xy(o.centre);
                [x, y, o.radius, o.radius + p0]
            })
            .collect()
    }

    fn predicted(&self) -> Vec<f64> {
        self.run
            .last_step()
            .map(|s| {
                s.predicted
                    .iter()
                    .flat_map(|v| {
                        let [x, y] = xy(v.centre);
                        [x, y, v.range, f64::from(v.k)]
                    })
                    .collect()
            })
            .unwrap_or_default()
    }

    fn candidates(&self) -> Vec<f64> {
        self.run
            .last_step()
            .map(|s| {
                s.candidates
                    .iter()
                    .flat_map(|c| {
                        let [x, y] = xy(c.point);
                        [x, y, c.cost]
                    })
                    .collect()
            })
            .unwrap_or_default()
    }

    fn chosen(&self) -> i32 {
        self.run
            .last_step()
            .and_then(|s| s.chosen)
            .map_or(-1, |i| i as i32)
    }

    fn step_kind(&self) -> Option<StepKind> {
        self.run.last_step().map(|s| s.kind)
    }

    /// The field on the lattice, in the plane of the robot's height (3D).
    fn field(&self, bounds: [f64; 4], nx: u32, ny: u32) -> Vec<f64> {
        let mut out = draw::DrawList::default();
        self.draw(
            bounds,
            [nx, ny],
            draw::Layers::NONE.with(draw::Layer::Field),
            &mut out,
        );
        // The vectors of the lattice's `x, y, fx, fy` samples.
        out.data.chunks(4).flat_map(|s| [s[2], s[3]]).collect()
    }

    fn draw(
        &self,
        bounds: [f64; 4],
        lattice: [u32; 2],
        layers: draw::Layers,
        out: &mut draw::DrawList,
    ) {
        let d = draw::ApfDraw {
            bounds,
            lattice: lattice.map(|n| n as usize),
        };
        draw::apf_run(&self.run, d, layers, out);
    }

    fn forces(&self) -> Vec<f64> {
        self.run
            .last_step()
            .map(|s| {
                [s.attraction, s.repulsion, s.resultant]
                    .into_iter()
                    .flat_map(xy)
                    .collect()
            })
            .unwrap_or_else(|| vec![0.0; 6])
    }
}

enum AnyCore {
    D2(Core<DVec2>),
    D3(Core<DVec3>),
}

/// The same expression on either dimension's run.
macro_rules! on {
    ($self:expr, $c:ident => $e:expr) => {
        match $self {
            AnyCore::D2($c) => $e,
            AnyCore::D3($c) => $e,
        }
    };
}

/// An APF run (2D, or 3D shown in its side view) and the scene it restarts
/// from.
#[wasm_bindgen]
pub struct ApfHandle {
    scene: ApfScene,
    bounds: [f64; 4],
    core: AnyCore,
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
    /// Reads a scenario JSON with an `apf` section (inline map); a 3D scene
    /// gives 3-coordinate `apf.start` / `apf.goal`.
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
        let start = scene
            .start
            .clone()
            .unwrap_or_else(|| sc.start_world(&grid).to_vec());
        let goal = scene
            .goal
            .clone()
            .unwrap_or_else(|| sc.goal_world(&grid).to_vec());
        let bad = |what: &str, v: &[f64]| {
            JsError::new(&format!(
                "apf.{what}: give 2 (plane) or 3 (space) finite coordinates, like the other, got {v:?}"
            ))
        };
        let core = match start.len() {
            3 => AnyCore::D3(Core::new(
                &scene,
                <DVec3 as ApfVector>::from_slice(&start).ok_or_else(|| bad("start", &start))?,
                <DVec3 as ApfVector>::from_slice(&goal).ok_or_else(|| bad("goal", &goal))?,
            )?),
            _ => AnyCore::D2(Core::new(
                &scene,
                <DVec2 as ApfVector>::from_slice(&start).ok_or_else(|| bad("start", &start))?,
                <DVec2 as ApfVector>::from_slice(&goal).ok_or_else(|| bad("goal", &goal))?,
            )?),
        };
        let (w, h, r, o) = (
            grid.width() as f64,
            grid.height() as f64,
            grid.resolution(),
            grid.origin(),
        );
        // The side view of a 3D scene spans the map's x and as much height
        // as the map's depth, centred on the start.
        let bounds = match &core {
            AnyCore::D3(c) => {
                let zc = c.start.z;
                [o.x, zc - h * r / 2.0, o.x + w * r, zc + h * r / 2.0]
            }
            AnyCore::D2(_) => [o.x, o.y, o.x + w * r, o.y + h * r],
        };
        Ok(ApfHandle {
            scene,
            bounds,
            core,
        })
    }

    /// Restarts from the start with the current goal, variant and predictor.
    pub fn reset(&mut self) -> Result<(), JsError> {
        on!(&mut self.core, c => c.reset(&self.scene))
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

    /// Moves the goal (m; a 3D goal moves in its side view, keeping y) and restarts; a goal
    /// inside an obstacle is an error and leaves the run as it was.
    #[wasm_bindgen(js_name = setGoal)]
    pub fn set_goal(&mut self, x: f64, y: f64) -> Result<(), JsError> {
        on!(&mut self.core, c => c.set_goal(&self.scene, x, y))
    }

    /// Up to `n` planning steps; the outcome after them (`running`,
    /// `reached`, `stuck`, `collision`, `timeout`).
    pub fn step(&mut self, n: u32) -> Result<String, JsError> {
        on!(&mut self.core, c => c.step(n))?;
        Ok(self.outcome())
    }

    /// The outcome so far.
    pub fn outcome(&self) -> String {
        on!(&self.core, c => c.run.outcome().to_string())
    }

    /// Time of the run, s.
    pub fn time(&self) -> f64 {
        on!(&self.core, c => c.run.time())
    }

    /// Drawing extent (x_min, y_min, x_max, y_max), m: the map's, or for a
    /// 3D scene its x and a height range around the start.
    pub fn bounds(&self) -> Vec<f64> {
        self.bounds.to_vec()
    }

    /// Start and goal (x, y, x, y), m.
    pub fn endpoints(&self) -> Vec<f64> {
        on!(&self.core, c => c.endpoints())
    }

    /// The path so far as (x, y) pairs, m.
    pub fn path(&self) -> Vec<f64> {
        on!(&self.core, c => c.path())
    }

    /// The obstacles now as (x, y, radius, range) quadruples, m (range =
    /// radius + p₀, where repulsion ends).
    pub fn obstacles(&self) -> Vec<f64> {
        let p0 = self.scene.config.p0;
        on!(&self.core, c => c.obstacles(p0))
    }

    /// Predicted obstacles of the last step as (x, y, virtual range, k)
    /// quadruples (k = 1 for t+1, 2 for t+2).
    pub fn predicted(&self) -> Vec<f64> {
        on!(&self.core, c => c.predicted())
    }

    /// Sampled candidates of the last step as (x, y, cost) triples.
    pub fn candidates(&self) -> Vec<f64> {
        on!(&self.core, c => c.candidates())
    }

    /// Index of the chosen candidate of the last step, −1 for none.
    pub fn chosen(&self) -> i32 {
        on!(&self.core, c => c.chosen())
    }

    /// How the last step was chosen (`resultant`, `sampled`,
    /// `relative-distance`, `stalled`, `arrived`, or `none`).
    #[wasm_bindgen(js_name = stepKind)]
    pub fn step_kind(&self) -> String {
        match on!(&self.core, c => c.step_kind()) {
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
    /// point, real and predicted obstacles included (3D: (F_x, F_z) in the
    /// vertical x–z plane through the robot).
    pub fn field(&self, nx: u32, ny: u32) -> Vec<f64> {
        let (nx, ny) = (nx.clamp(1, 400), ny.clamp(1, 400));
        on!(&self.core, c => c.field(self.bounds, nx, ny))
    }

    /// The core's draw list of the run (`layers`, a bit per layer code;
    /// the field on an `nx` × `ny` lattice over [`ApfHandle::bounds`]) as
    /// `{data, items, cells}`.
    #[wasm_bindgen(unchecked_return_type = "DrawArrays")]
    pub fn draw(&self, layers: u32, nx: u32, ny: u32) -> Result<js_sys::Object, JsError> {
        let mut out = draw::DrawList::default();
        let layers = draw::Layers::from_bits(layers);
        on!(&self.core, c => c.draw(self.bounds, [nx, ny], layers, &mut out));
        crate::draw_js::draw_arrays(&out)
    }

    /// Attraction, repulsion and resultant at the robot (6 numbers: x, y
    /// of each).
    pub fn forces(&self) -> Vec<f64> {
        on!(&self.core, c => c.forces())
    }

    /// The metrics as JSON (`outcome`, `path_length_m`, `path_points`,
    /// `spikes`, `min_obstacle_distance_m`, `time_s`).
    pub fn metrics(&self) -> String {
        serde_json::to_string(&on!(&self.core, c => c.run.metrics())).unwrap_or_default()
    }

    /// The robot's position in the page's (x, y), m.
    pub fn position(&self) -> Vec<f64> {
        on!(&self.core, c => xy(c.run.position()).to_vec())
    }

    /// Number of coordinates of the scene (2, or 3 for a spatial scene).
    pub fn dims(&self) -> u32 {
        match self.core {
            AnyCore::D2(_) => 2,
            AnyCore::D3(_) => 3,
        }
    }
}
