//! [`ArmHandle`]: one arm episode (core `arm::ArmEpisode`) for the arm
//! page. Steps, live edits (goal, predictor; hand motion and speed restart
//! the episode) and everything drawn as the core's draw list
//! ([`ArmHandle::draw`]). No kinematics or
//! distances are computed here.
//!
//! A crate of its own so the arm page loads a wasm module with only the arm
//! (and parry3d) in it: with three.js next to it, the whole playground
//! module would not fit the page's 1.5 MB first-load budget. `planlab-wasm`
//! re-exports it (feature `arm`, on by default) as `planlab_wasm::arm`.

// The draw list's JS shape, shared with planlab-wasm (one file, two
// modules).
#[path = "../../planlab-wasm/src/draw_js.rs"]
mod draw_js;

use planlab_core::arm::{ArmEpisode, ArmPlanner, ArmPredictor, HandPreset, Obstacle3};
use planlab_core::draw;
use planlab_core::scenario::ArmScenario;
use serde::Serialize;
use wasm_bindgen::prelude::*;

fn js(e: impl std::fmt::Display) -> JsError {
    JsError::new(&e.to_string())
}

/// One arm episode and the scenario it restarts from.
#[wasm_bindgen]
pub struct ArmHandle {
    scenario: ArmScenario,
    ep: ArmEpisode,
    /// `t, arm distance, gripper distance` per sample since the start.
    distances: Vec<f64>,
}

#[derive(Serialize)]
struct Choices {
    hand_presets: Vec<&'static str>,
    predictors: Vec<&'static str>,
    planners: Vec<&'static str>,
}

/// The hand presets, predictors and planners the page offers, as JSON
/// `{hand_presets: [...], predictors: [...], planners: [...]}`.
#[wasm_bindgen(js_name = armChoices)]
pub fn arm_choices() -> String {
    serde_json::to_string(&Choices {
        hand_presets: HandPreset::ALL.iter().map(|p| p.name()).collect(),
        predictors: ArmPredictor::ALL.iter().map(|p| p.name()).collect(),
        planners: ArmPlanner::ALL.iter().map(|p| p.name()).collect(),
    })
    .unwrap_or_default()
}

/// The scenario JSON `text` with a run link's edits applied by the core's
/// `Recipe` (`recipe` is its JSON form, `{"planner": "dwa", "set":
/// [["sim.dt", "0.05"]]}`), as `planlab run` applies them; `text` itself
/// when there are none.
#[wasm_bindgen(js_name = editScenario)]
pub fn edit_scenario(text: &str, recipe: &str) -> Result<String, JsError> {
    Ok(planlab_core::recipe::Recipe::from_json(recipe)?.edit_text(text)?)
}

fn push3(out: &mut Vec<f32>, p: [f64; 3]) {
    out.extend(p.iter().map(|&x| x as f32));
}

impl ArmHandle {
    fn note_distances(&mut self) {
        self.distances.extend_from_slice(&[
            self.ep.time(),
            self.ep.distance_now(),
            self.ep.gripper_distance_now(),
        ]);
    }

    fn restart_series(&mut self) {
        self.distances.clear();
        self.note_distances();
    }
}

#[wasm_bindgen]
impl ArmHandle {
    /// Reads an arm scenario (JSON with an `arm` section) and builds its
    /// episode; errors carry the core's message.
    #[wasm_bindgen(constructor)]
    pub fn new(json: &str) -> Result<ArmHandle, JsError> {
        // This module has no start function (planlab-wasm, which links it
        // in, has one): a bug still shows as a readable console message.
        console_error_panic_hook::set_once();
        let scenario = ArmScenario::from_json(json).map_err(js)?;
        let ep = ArmEpisode::from_scenario(&scenario).map_err(js)?;
        let mut h = ArmHandle {
            scenario,
            ep,
            distances: Vec::new(),
        };
        h.restart_series();
        Ok(h)
    }

    /// Advances `n` samples (stops early at the end); returns the outcome.
    pub fn step(&mut self, n: u32) -> Result<String, JsError> {
        for _ in 0..n {
            if self.ep.outcome() != planlab_core::sim::Outcome::Running {
                break;
            }
            self.ep.step().map_err(js)?;
            self.note_distances();
        }
        Ok(self.ep.outcome().to_string())
    }

    /// Restarts from the scenario (with the edits made so far).
    pub fn reset(&mut self) -> Result<(), JsError> {
        self.ep = ArmEpisode::from_scenario(&self.scenario).map_err(js)?;
        self.restart_series();
        Ok(())
    }

    /// `running`, `reached`, `collision`, `timeout` or `stuck`.
    /// The core's draw list of the episode (`layers`, a bit per layer
    /// code; the hand's scripted motion at `script` instants, none below
    /// 2) as `{data, items, cells}`, in space (m, z up).
    #[wasm_bindgen(unchecked_return_type = "DrawArrays")]
    pub fn draw(&self, layers: u32, script: u32) -> Result<js_sys::Object, JsError> {
        let mut out = draw::DrawList::default();
        let layers = draw::Layers::from_bits(layers);
        draw::arm_episode(&self.ep, script as usize, layers, &mut out);
        draw_js::draw_arrays(&out)
    }

    #[wasm_bindgen(getter)]
    pub fn outcome(&self) -> String {
        self.ep.outcome().to_string()
    }

    /// Time now, s.
    #[wasm_bindgen(getter)]
    pub fn time(&self) -> f64 {
        self.ep.time()
    }

    /// Sample period, s.
    #[wasm_bindgen(getter)]
    pub fn dt(&self) -> f64 {
        self.scenario.arm.sim.sample_period_s
    }

    /// Link-to-hand distance now, m.
    #[wasm_bindgen(getter, js_name = distanceNow)]
    pub fn distance_now(&self) -> f64 {
        self.ep.distance_now()
    }

    /// Distances to the hand from sample `from` on (sample 0 is the
    /// start), stride 3: `t (s), arm (m, nearest link), gripper (m)`.
    #[wasm_bindgen(js_name = distanceSeries)]
    pub fn distance_series(&self, from: u32) -> Vec<f64> {
        self.distances
            .get(3 * from as usize..)
            .map_or_else(Vec::new, <[f64]>::to_vec)
    }

    /// Smallest link-to-hand distance so far, m.
    #[wasm_bindgen(getter, js_name = minDistance)]
    pub fn min_distance(&self) -> f64 {
        self.ep.min_distance()
    }

    /// The metrics so far as JSON (`planlab run --json` field names).
    #[wasm_bindgen(js_name = metricsJson)]
    pub fn metrics_json(&self) -> Result<String, JsError> {
        serde_json::to_string(&self.ep.metrics()).map_err(js)
    }

    /// The planner and its effort so far as JSON: `{planner, plans,
    /// replans, failed_plans, holds, iterations, collision_checks,
    /// joint_path_rad, gripper_path_m, min_table_m}` (`min_table_m` null
    /// without a table).
    #[wasm_bindgen(js_name = plannerJson)]
    pub fn planner_json(&self) -> Result<String, JsError> {
        let e = self.ep.effort();
        let table = self.ep.min_table_distance();
        serde_json::to_string(&serde_json::json!({
            "planner": self.ep.planner().name(),
            "plans": e.plans,
            "replans": e.replans,
            "failed_plans": e.failed_plans,
            "holds": e.holds,
            "iterations": e.iterations,
            "collision_checks": e.collision_checks,
            "joint_path_rad": self.ep.joint_path_length(),
            "gripper_path_m": self.ep.gripper_path_length(),
            "min_table_m": table.is_finite().then_some(table),
        }))
        .map_err(js)
    }

    /// The current scenario (with the page's edits) as pretty JSON.
    #[wasm_bindgen(js_name = scenarioJson)]
    pub fn scenario_json(&self) -> Result<String, JsError> {
        serde_json::to_string_pretty(&self.scenario).map_err(js)
    }

    /// Scenario name.
    #[wasm_bindgen(getter)]
    pub fn name(&self) -> String {
        self.scenario.name.clone()
    }

    /// Joint names as JSON.
    #[wasm_bindgen(js_name = jointNames)]
    pub fn joint_names(&self) -> String {
        serde_json::to_string(&self.ep.model().joint_names()).unwrap_or_default()
    }

    /// Joint angles now, rad.
    #[wasm_bindgen(js_name = jointAngles)]
    pub fn joint_angles(&self) -> Vec<f64> {
        self.ep.q().to_vec()
    }

    /// Joint limits as `min, max` pairs, rad.
    #[wasm_bindgen(js_name = jointLimits)]
    pub fn joint_limits(&self) -> Vec<f64> {
        let m = self.ep.model();
        (0..m.dof())
            .flat_map(|i| {
                let (lo, hi) = m.limits(i);
                [lo, hi]
            })
            .collect()
    }

    /// Link capsules now: `ax, ay, az, bx, by, bz, radius` per link.
    pub fn links(&self) -> Vec<f32> {
        let mut out = Vec::new();
        for l in self.ep.links() {
            push3(&mut out, l.a.to_array());
            push3(&mut out, l.b.to_array());
            out.push(l.radius as f32);
        }
        out
    }

    /// The tool's path at the planning instants, `x, y, z` per point.
    #[wasm_bindgen(js_name = toolPath)]
    pub fn tool_path(&self) -> Vec<f32> {
        let mut out = Vec::new();
        for p in self.ep.tool_path() {
            push3(&mut out, p.to_array());
        }
        out
    }

    /// The hand centre at every sample so far, `x, y, z` per point.
    #[wasm_bindgen(js_name = handPath)]
    pub fn hand_path(&self) -> Vec<f32> {
        let mut out = Vec::new();
        for p in self.ep.hand_path() {
            push3(&mut out, p.to_array());
        }
        out
    }

    /// The scripted hand path from 0 to the end of its motion (or 10 s),
    /// `n` points, `x, y, z` each.
    #[wasm_bindgen(js_name = handScript)]
    pub fn hand_script(&self, n: u32) -> Vec<f32> {
        let h = self.ep.hand();
        let end = if h.end_time().is_finite() {
            h.end_time().max(0.1)
        } else {
            10.0
        };
        let n = n.clamp(2, 2000);
        let mut out = Vec::new();
        for i in 0..n {
            push3(
                &mut out,
                h.hand_at(end * i as f64 / (n - 1) as f64).to_array(),
            );
        }
        out
    }

    /// The hand and forearm now: `cx, cy, cz, r` (hand sphere) then `ax,
    /// ay, az, bx, by, bz, r` (forearm capsule).
    pub fn hand(&self) -> Vec<f32> {
        let mut out = Vec::new();
        for o in self.ep.hand_obstacles() {
            match o {
                Obstacle3::Sphere { centre, radius } => {
                    push3(&mut out, centre);
                    out.push(radius as f32);
                }
                Obstacle3::Capsule { a, b, radius } => {
                    push3(&mut out, a);
                    push3(&mut out, b);
                    out.push(radius as f32);
                }
            }
        }
        out
    }

    /// Predicted obstacle positions of the last planning step: `x, y, z,
    /// range, k` per virtual obstacle (k = 1 for t+1, 2 for t+2; id 0 is
    /// the hand, 1–3 the forearm).
    pub fn predictions(&self) -> Vec<f32> {
        let mut out = Vec::new();
        if let Some(s) = self.ep.last_step() {
            for v in &s.predicted {
                push3(&mut out, v.centre.to_array());
                out.push(v.range as f32);
                out.push(v.k as f32);
            }
        }
        out
    }

    /// The sampled candidate points of the last step, `x, y, z` each (the
    /// chosen one is [`ArmHandle::chosen`]).
    pub fn candidates(&self) -> Vec<f32> {
        let mut out = Vec::new();
        if let Some(s) = self.ep.last_step() {
            for c in &s.candidates {
                push3(&mut out, c.point.to_array());
            }
        }
        out
    }

    /// Index of the chosen candidate, −1 for a resultant step.
    #[wasm_bindgen(getter)]
    pub fn chosen(&self) -> i32 {
        self.ep
            .last_step()
            .and_then(|s| s.chosen)
            .map_or(-1, |i| i as i32)
    }

    /// Goal `x, y, z`, m.
    pub fn goal(&self) -> Vec<f64> {
        self.ep.scene().goal.to_vec()
    }

    /// Start `x, y, z`, m.
    pub fn start(&self) -> Vec<f64> {
        self.ep.scene().start.to_vec()
    }

    /// Moves the goal (live; errors for unreachable targets leave it).
    #[wasm_bindgen(js_name = setGoal)]
    pub fn set_goal(&mut self, x: f64, y: f64, z: f64) -> Result<(), JsError> {
        self.ep.set_goal([x, y, z]).map_err(js)?;
        self.scenario.arm.goal = [x, y, z];
        Ok(())
    }

    /// Switches the predictor (`none`, `constant-velocity`, `rnn`) live.
    #[wasm_bindgen(js_name = setPredictor)]
    pub fn set_predictor(&mut self, name: &str) -> Result<(), JsError> {
        let p = ArmPredictor::parse(name).map_err(js)?;
        self.ep.set_predictor(p).map_err(js)?;
        p.apply(&mut self.scenario.arm.apf);
        Ok(())
    }

    /// The predictor in use.
    #[wasm_bindgen(getter)]
    pub fn predictor(&self) -> String {
        ArmPredictor::of(&self.ep.scene().apf).name().to_string()
    }

    /// Changes the hand's motion (preset name, speed factor, seed) and
    /// restarts; on error nothing changes.
    #[wasm_bindgen(js_name = setHand)]
    pub fn set_hand(&mut self, preset: &str, speed: f64, seed: f64) -> Result<(), JsError> {
        let p = HandPreset::ALL
            .into_iter()
            .find(|p| p.name() == preset)
            .ok_or_else(|| JsError::new(&format!("unknown hand preset `{preset}`")))?;
        if !(seed.is_finite() && seed >= 0.0) {
            return Err(JsError::new("seed must be a non-negative number"));
        }
        let mut s = self.scenario.clone();
        s.arm.hand.preset = p;
        s.arm.hand.speed = speed;
        s.seed = Some(seed as u64);
        let ep = ArmEpisode::from_scenario(&s).map_err(js)?;
        self.scenario = s;
        self.ep = ep;
        self.restart_series();
        Ok(())
    }

    /// The hand's preset name.
    #[wasm_bindgen(getter, js_name = handPreset)]
    pub fn hand_preset(&self) -> String {
        self.scenario.arm.hand.preset.name().to_string()
    }

    /// The hand's speed factor.
    #[wasm_bindgen(getter, js_name = handSpeed)]
    pub fn hand_speed(&self) -> f64 {
        self.scenario.arm.hand.speed
    }

    /// The scenario's seed.
    #[wasm_bindgen(getter)]
    pub fn seed(&self) -> f64 {
        self.scenario.seed.unwrap_or(0) as f64
    }
}
