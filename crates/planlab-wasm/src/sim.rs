//! The robot simulation for the page: a [`SimHandle`] wraps one core
//! [`Episode`] and converts at the boundary (ARCHITECTURE.md, "Crates").
//!
//! - What a frame shows leaves as one draw list (`draw`: the core's layers
//!   of polylines, points, discs … as typed arrays), and the plot series
//!   since a given row, so a frame costs a handful of boundary calls
//!   whatever the number of rollouts.
//! - Setups, movers and planner configs cross as JSON text in the core's
//!   serde formats; errors are `JsError`s with the core's message.
//! - The page draws; everything it draws (rollouts and their scores, goals,
//!   obstacle classes, clearance, metrics) is computed by the core.

use crate::draw_js::draw_arrays;
use planlab_core::draw::{self, DrawList, FanColour, Layers, Request};
use planlab_core::lidar::fog::SeenCells;
use planlab_core::metrics::{distance_to_polyline, EpisodeMetrics};
use planlab_core::planners::{self as registry, PlannerChoice};
use planlab_core::scenario::Scenario;
use planlab_core::sim::{Column, Edit, Episode, EpisodeSetup, Outcome, Recording, SimConfig};
use planlab_core::world::{MoverSpec, Placement, RobotSpec, RobotState, StaticMap, TerrainSpec};
use serde::Deserialize;
use std::cell::RefCell;
use wasm_bindgen::prelude::*;

use crate::{files_reader, MapHandle};

mod edit;
pub use edit::generated_grid_hash;

/// What [`SimHandle::from_map`] reads besides the map: the simulation
/// sections of a scenario, with start and goal in world metres.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct PageSetup {
    /// Start position (x, y), m.
    start: [f64; 2],
    /// Start heading, rad.
    #[serde(default)]
    start_yaw: f64,
    /// Goal (x, y), m.
    goal: [f64; 2],
    #[serde(default)]
    robot: RobotSpec,
    #[serde(default)]
    movers: Vec<MoverSpec>,
    #[serde(default)]
    local_planner: PlannerChoice,
    #[serde(default)]
    sim: SimConfig,
    #[serde(default)]
    terrain: TerrainSpec,
    #[serde(default)]
    seed: u64,
}

fn outcome_str(o: Outcome) -> String {
    o.as_str().to_string()
}

/// Tells runs apart: replays of one run share its number.
static NEXT_RUN: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(1);

fn json_err(what: &str, e: serde_json::Error) -> JsError {
    JsError::new(&format!("{what}: {e}"))
}

/// One running episode, owned on the wasm side.
#[wasm_bindgen]
pub struct SimHandle {
    ep: Episode,
    /// Record the rollouts of the last step of each `step(n)` for drawing.
    draw_fan: bool,
    /// What colours the fan in [`SimHandle::draw`].
    fan: FanColour,
    /// Cells the robot's scans have swept (LiDAR planners only).
    seen: SeenCells,
    /// The setup and the edits since, for exact replays (the timeline).
    /// Whatever replaces `ep` with another episode must start a new
    /// recording ([`SimHandle::wrap`]).
    rec: Recording,
    /// Which run this is (shared by its replays and branches).
    run: u64,
    /// The draw list's buffers, reused from frame to frame so a frame
    /// allocates nothing on the wasm side.
    drawn: RefCell<DrawList>,
}

impl SimHandle {
    fn wrap(mut ep: Episode) -> SimHandle {
        ep.set_record_rollouts(true);
        let seen = SeenCells::new(ep.map().grid());
        let rec = Recording::of(&ep);
        SimHandle {
            ep,
            draw_fan: true,
            fan: FanColour::Total,
            seen,
            rec,
            run: NEXT_RUN.fetch_add(1, std::sync::atomic::Ordering::Relaxed),
            drawn: RefCell::default(),
        }
    }

    /// How many recorded edits were made after the first step (goal,
    /// movers or planner changed while the run went on).
    pub(crate) fn edits_after_start(&self) -> usize {
        self.rec.edits().iter().filter(|(k, _)| *k > 0).count()
    }

    /// Applies and records a live edit.
    fn edit(&mut self, e: Edit) -> Result<(), JsError> {
        Ok(self.rec.edit(&mut self.ep, e)?)
    }

    /// Takes `h` (a replay of this run) on to step `steps`, recording the
    /// last step's rollouts and every scan like [`SimHandle::step`].
    fn advance_replay_of(&self, h: &mut SimHandle, steps: u64) -> Result<(), JsError> {
        let mut applied = h.rec.edits().len();
        let draw = h.draw_fan;
        let seen = &mut h.seen;
        self.rec.advance(
            &mut h.ep,
            &mut applied,
            steps,
            |ep, last| ep.set_record_rollouts(draw && last),
            |ep| {
                if let Some(l) = ep.planner_debug().lidar.as_ref() {
                    seen.update(ep.map().grid(), l.pose, &l.ranges, &l.returns);
                }
            },
        )?;
        h.ep.set_record_rollouts(draw);
        h.rec = self.rec.truncated(h.ep.steps());
        debug_assert_eq!(h.rec.edits().len(), applied);
        Ok(())
    }

    /// The trace row `i`, if there is one.
    fn row(&self, i: u32) -> Option<&planlab_core::sim::TraceStep> {
        self.ep.trace().steps.get(i as usize)
    }

    /// Adds the last step's scan to the seen cells.
    fn note_scan(&mut self) {
        if let Some(l) = self.ep.planner_debug().lidar.as_ref() {
            self.seen
                .update(self.ep.map().grid(), l.pose, &l.ranges, &l.returns);
        }
    }

    /// The live end's draw list (what [`SimHandle::draw`] hands over).
    pub fn draw_list(&self, layers: u32, trail_from: u32) -> DrawList {
        let mut out = DrawList::default();
        self.draw_into(layers, trail_from, &mut out);
        out
    }

    fn draw_into(&self, layers: u32, trail_from: u32, out: &mut DrawList) {
        let req = Request {
            layers: Layers::from_bits(layers),
            trail_from: trail_from as usize,
            fan: self.fan,
        };
        draw::episode(&self.ep, Some(&self.seen), req, out);
    }

    /// Trace row `k`'s draw list (what [`SimHandle::draw_row`] hands
    /// over): mover radii from the specs in force, then the run's earlier
    /// ones (a mover removed since keeps its size).
    pub fn row_draw_list(&self, k: u32, layers: u32) -> DrawList {
        let mut specs = self.ep.movers().to_vec();
        specs.extend_from_slice(&self.rec.origin().movers);
        for (_, e) in self.rec.edits() {
            if let Edit::Movers(m) = e {
                specs.extend_from_slice(m);
            }
        }
        let mut out = DrawList::default();
        let layers = Layers::from_bits(layers);
        draw::trace_frame(&self.ep, k as usize, &specs, layers, &mut out);
        out
    }

    /// The wrapped episode (for Rust callers and tests).
    pub fn episode(&self) -> &Episode {
        &self.ep
    }
}

#[wasm_bindgen]
impl SimHandle {
    /// Builds the episode a scenario JSON describes. A map given by file
    /// name is looked up by base name in `files` (`{"room.map": Uint8Array}`,
    /// may be `undefined` for inline maps).
    #[wasm_bindgen(js_name = fromScenario)]
    pub fn from_scenario(json: &str, files: Option<js_sys::Object>) -> Result<SimHandle, JsError> {
        let scenario = Scenario::from_json(json)?;
        let files = files.unwrap_or_default();
        let grid = scenario.load_grid(&mut files_reader(&files))?;
        Ok(SimHandle::wrap(Episode::from_scenario(&scenario, grid)?))
    }

    /// Builds an episode on `map` (e.g. one the page edited) from a setup
    /// JSON: `{"start": [x, y], "goal": [x, y]}` plus the optional scenario
    /// sections `start_yaw`, `robot`, `movers`, `local_planner`, `sim`,
    /// `terrain`, `seed`.
    #[wasm_bindgen(js_name = fromMap)]
    pub fn from_map(map: &MapHandle, setup: &str) -> Result<SimHandle, JsError> {
        let s: PageSetup =
            serde_json::from_str(setup).map_err(|e| json_err("invalid simulation setup", e))?;
        let static_map = StaticMap::new(map.grid.clone(), s.sim.unknown_is_obstacle)?;
        let ep = Episode::new(EpisodeSetup {
            map: static_map,
            robot: s.robot,
            start: RobotState {
                x: s.start[0],
                y: s.start[1],
                theta: s.start_yaw,
                ..Default::default()
            },
            goal: s.goal,
            movers: s.movers,
            planner: s.local_planner,
            config: s.sim,
            terrain: s.terrain,
            seed: s.seed,
            perception: None,
            global_planner: None,
        })?;
        Ok(SimHandle::wrap(ep))
    }

    /// Runs up to `n` control steps (fewer when the episode ends) and
    /// returns the outcome: `running`, `reached`, `collision`, `timeout` or
    /// `stuck`. Only the last step records its rollouts for drawing.
    pub fn step(&mut self, n: u32) -> String {
        for i in 0..n {
            if self.draw_fan {
                self.ep.set_record_rollouts(i + 1 == n);
            }
            let o = self.ep.step();
            self.note_scan();
            if o != Outcome::Running {
                break;
            }
        }
        if self.draw_fan {
            self.ep.set_record_rollouts(true);
        }
        outcome_str(self.ep.outcome())
    }

    /// The outcome so far.
    #[wasm_bindgen(getter)]
    pub fn outcome(&self) -> String {
        outcome_str(self.ep.outcome())
    }

    /// What a collision was with, in the core's words ("hit by mover 3
    /// while at rest", "collision with a wall or the map edge"); undefined
    /// unless the outcome is a collision.
    #[wasm_bindgen(getter)]
    pub fn collision(&self) -> Option<String> {
        self.ep.collision().map(|c| c.to_string())
    }

    /// Simulated time, s.
    #[wasm_bindgen(getter)]
    pub fn time(&self) -> f64 {
        self.ep.time()
    }

    /// Control steps taken.
    #[wasm_bindgen(getter)]
    pub fn steps(&self) -> f64 {
        self.ep.steps() as f64
    }

    /// Control period, s.
    #[wasm_bindgen(getter)]
    pub fn dt(&self) -> f64 {
        self.ep.config().dt
    }

    /// The robot now: `[x, y, theta, v, vy, w]` (m, rad, m/s, rad/s).
    pub fn state(&self) -> Vec<f64> {
        let s = self.ep.state();
        vec![s.x, s.y, s.theta, s.v, s.vy, s.w]
    }

    /// The start pose `[x, y, theta]`.
    pub fn start(&self) -> Vec<f64> {
        self.ep
            .trace()
            .steps
            .first()
            .map_or_else(Vec::new, |r| vec![r.x, r.y, r.theta])
    }

    /// The robot (drive, footprint, limits) as JSON.
    pub fn robot(&self) -> Result<String, JsError> {
        serde_json::to_string(self.ep.robot()).map_err(|e| json_err("robot", e))
    }

    /// A copy of the static map, for drawing.
    pub fn map(&self) -> MapHandle {
        MapHandle {
            grid: self.ep.map().grid().clone(),
        }
    }

    /// The movers' specs (id, radius, motion model) as JSON.
    #[wasm_bindgen(js_name = moversJson)]
    pub fn movers_json(&self) -> Result<String, JsError> {
        serde_json::to_string(self.ep.movers()).map_err(|e| json_err("movers", e))
    }

    /// Replaces the movers with a JSON array of mover specs.
    #[wasm_bindgen(js_name = setMovers)]
    pub fn set_movers(&mut self, json: &str) -> Result<(), JsError> {
        let movers: Vec<MoverSpec> =
            serde_json::from_str(json).map_err(|e| json_err("invalid movers JSON", e))?;
        self.edit(Edit::Movers(movers))
    }

    /// Adds a mover that is at (x, y) moving with (vx, vy) now, following
    /// `model` (`constant-velocity`, `back-and-forth`, `waypoint-loop`;
    /// `span` m is the back-and-forth length / loop side). Returns its id.
    #[wasm_bindgen(js_name = placeMover)]
    #[allow(clippy::too_many_arguments)]
    pub fn place_mover(
        &mut self,
        model: &str,
        radius: f64,
        x: f64,
        y: f64,
        vx: f64,
        vy: f64,
        span: f64,
    ) -> Result<u32, JsError> {
        let how: Placement = serde_json::from_value(serde_json::Value::String(model.into()))
            .map_err(|_| {
                JsError::new(&format!(
                    "unknown motion model `{model}`: expected constant-velocity, back-and-forth or waypoint-loop"
                ))
            })?;
        let id = self.ep.movers().iter().map(|m| m.id + 1).max().unwrap_or(1);
        let spec = MoverSpec::placed(id, radius, how, [x, y], [vx, vy], span, self.ep.time())?;
        let mut movers = self.ep.movers().to_vec();
        movers.push(spec);
        self.edit(Edit::Movers(movers))?;
        Ok(id)
    }

    /// Moves the goal to (x, y), m.
    #[wasm_bindgen(js_name = setGoal)]
    pub fn set_goal(&mut self, x: f64, y: f64) -> Result<(), JsError> {
        self.edit(Edit::Goal([x, y]))
    }

    /// Swaps in planner `name` with `config` (JSON object; `{}` = the
    /// paper's defaults), built at the robot's current state.
    #[wasm_bindgen(js_name = setPlanner)]
    pub fn set_planner(&mut self, name: &str, config: &str) -> Result<(), JsError> {
        let config: serde_json::Value = serde_json::from_str(config)
            .map_err(|e| json_err(&format!("invalid {name} config JSON"), e))?;
        self.edit(Edit::Planner(PlannerChoice {
            name: name.into(),
            config,
        }))
    }

    /// The planner in force: `{"name", "config"}` JSON.
    #[wasm_bindgen(js_name = plannerChoice)]
    pub fn planner_choice(&self) -> Result<String, JsError> {
        serde_json::to_string(self.ep.planner_choice()).map_err(|e| json_err("planner", e))
    }

    /// Record the rollouts for drawing (on by default) or not (faster).
    #[wasm_bindgen(js_name = setRecordRollouts)]
    pub fn set_record_rollouts(&mut self, on: bool) {
        self.draw_fan = on;
        self.ep.set_record_rollouts(on);
    }

    /// The draw list of the live end (see `planlab_core::draw`): the
    /// layers in the bit set `layers` (bit `1 << code` per layer code),
    /// the trail from trace row `trail_from` on. `{data: Float64Array,
    /// items: Float64Array, cells: Uint8Array}`, items 6 numbers each:
    /// `layer, shape, start, end, tag, value`.
    #[wasm_bindgen(unchecked_return_type = "DrawArrays")]
    pub fn draw(&self, layers: u32, trail_from: u32) -> Result<js_sys::Object, JsError> {
        let mut d = self.drawn.borrow_mut();
        d.clear();
        self.draw_into(layers, trail_from, &mut d);
        draw_arrays(&d)
    }

    /// The draw list of trace row `k` (robot, movers, goals of that time;
    /// see `planlab_core::draw::trace_frame`), as [`SimHandle::draw`].
    #[wasm_bindgen(js_name = drawRow, unchecked_return_type = "DrawArrays")]
    pub fn draw_row(&self, k: u32, layers: u32) -> Result<js_sys::Object, JsError> {
        draw_arrays(&self.row_draw_list(k, layers))
    }

    /// The planner's critics as a JSON array of `{"name", "weight"}`, in
    /// the order of the rollouts' critic values: the weight each had in
    /// the last step (planners such as improved-dwa switch weight sets
    /// from step to step), `null` before the first step or for a planner
    /// without weights.
    pub fn critics(&self) -> Result<String, JsError> {
        let d = self.ep.planner_debug();
        let list: Vec<_> = d
            .critics
            .iter()
            .enumerate()
            .map(|(k, name)| serde_json::json!({ "name": name, "weight": d.weights.get(k) }))
            .collect();
        serde_json::to_string(&list).map_err(|e| json_err("critics", e))
    }

    /// What colours the fan of [`SimHandle::draw`]: `undefined` the total
    /// score (the default), `k` critic `k`'s normalised value (the order
    /// of [`SimHandle::critics`]). A `k` the planner has no critic for is
    /// an error.
    #[wasm_bindgen(js_name = setFanColour)]
    pub fn set_fan_colour(&mut self, critic: Option<u32>) -> Result<(), JsError> {
        self.fan = match critic {
            None => FanColour::Total,
            Some(k) => {
                let names = &self.ep.planner_debug().critics;
                if k as usize >= names.len() {
                    let has = match names.len() {
                        0 => "no critics".to_string(),
                        n => format!("{n} ({})", names.join(", ")),
                    };
                    let planner = &self.ep.planner_choice().name;
                    return Err(JsError::new(&format!(
                        "no critic {k} to colour the fan by: {planner} has {has}"
                    )));
                }
                FanColour::Critic(k as usize)
            }
        };
        Ok(())
    }

    /// The car path the local planner follows (a scenario's
    /// `global_planner` section): `{"spec": {…}, "length_m", "cusps",
    /// "expanded", "replans"}` JSON, or `undefined` without one.
    #[wasm_bindgen(js_name = globalPath)]
    pub fn global_path(&self) -> Option<String> {
        let c = self.ep.car_guide()?;
        let r = c.route();
        Some(
            serde_json::json!({
                "spec": c.spec(),
                "length_m": r.length,
                "cusps": r.cusps,
                "expanded": r.expanded,
                "replans": c.replans(),
            })
            .to_string(),
        )
    }

    /// [`planlab_core::sim::Episode::route_note`]: one line when every way
    /// to the goal passes a gap narrower than the robot, else `undefined`.
    #[wasm_bindgen(js_name = routeNote)]
    pub fn route_note(&self) -> Option<String> {
        self.ep.route_note()
    }

    /// The planner's strategy in force ("" before the first step).
    #[wasm_bindgen(getter)]
    pub fn mode(&self) -> String {
        if self.ep.steps() == 0 {
            String::new()
        } else {
            self.ep.planner_debug().mode.clone()
        }
    }

    /// Rows in the trace (start row included).
    #[wasm_bindgen(getter, js_name = traceLen)]
    pub fn trace_len(&self) -> u32 {
        self.ep.trace().steps.len() as u32
    }

    /// Plot series from trace row `from` on, stride 5:
    /// `t (s), v (m/s), v_y (m/s, 0 unless omnidirectional), ω (rad/s),
    /// clearance (m)`.
    pub fn series(&self, from: u32) -> Vec<f64> {
        let rows = self.ep.trace().steps.get(from as usize..).unwrap_or(&[]);
        let mut out = Vec::with_capacity(rows.len() * 5);
        for r in rows {
            out.extend_from_slice(&[r.t, r.v, r.vy, r.w, r.clearance]);
        }
        out
    }

    /// The episode's metrics so far as JSON (the fields of `planlab run
    /// --json`).
    #[wasm_bindgen(js_name = metricsJson)]
    pub fn metrics_json(&self) -> Result<String, JsError> {
        // With what a collision was with (`collision`), for the status line.
        let m = EpisodeMetrics::of_episode(&self.ep);
        serde_json::to_string(&m).map_err(|e| json_err("metrics", e))
    }

    /// The trace as CSV.
    #[wasm_bindgen(js_name = traceCsv)]
    pub fn trace_csv(&self) -> String {
        self.ep.trace().to_csv()
    }

    /// Number of seen cells.
    #[wasm_bindgen(getter, js_name = seenCount)]
    pub fn seen_count(&self) -> u32 {
        self.seen.count() as u32
    }

    /// The trace hash (u64) as a decimal string, to compare with `planlab
    /// run --json`'s `trace_hash`.
    #[wasm_bindgen(js_name = traceHash)]
    pub fn trace_hash(&self) -> String {
        self.ep.trace().hash().to_string()
    }

    // ------------------------------------------------------- timeline

    /// This run rebuilt from its setup up to step `steps` (fewer when it
    /// ended earlier), with the live edits made up to then applied at the
    /// steps they were made: its trace is bit-identical to this one's
    /// first rows, and its fan, LiDAR and fog are those of that step. A
    /// handle of its own (a scratch view of the past, or a branch that
    /// continues from there).
    #[wasm_bindgen(js_name = replayTo)]
    pub fn replay_to(&self, steps: f64) -> Result<SimHandle, JsError> {
        let ep = Episode::new(self.rec.origin().clone())?;
        let mut h = SimHandle {
            seen: SeenCells::new(ep.map().grid()),
            rec: Recording::of(&ep),
            ep,
            draw_fan: self.draw_fan,
            fan: self.fan,
            run: self.run,
            drawn: RefCell::default(),
        };
        self.advance_replay_of(&mut h, steps.max(0.0) as u64)?;
        h.check_against(self)?;
        Ok(h)
    }

    /// A replay's last row must be this run's row: otherwise the
    /// recording missed something and the timeline would show a
    /// different run.
    fn check_against(&self, run: &SimHandle) -> Result<(), JsError> {
        let k = self.ep.steps() as usize;
        if run.ep.trace().steps.get(k) != self.ep.trace().steps.last() {
            return Err(JsError::new(&format!(
                "the replay of this run differs from it at step {k}: the recording is incomplete"
            )));
        }
        Ok(())
    }

    /// Takes `scratch` (from [`SimHandle::replay_to`] of this run) on to
    /// step `steps` without starting over; false (and `scratch` untouched)
    /// when it cannot: another run, past `steps`, or an edit made since
    /// that it missed.
    #[wasm_bindgen(js_name = advanceReplay)]
    pub fn advance_replay(&self, scratch: &mut SimHandle, steps: f64) -> Result<bool, JsError> {
        let steps = steps.max(0.0) as u64;
        if scratch.run != self.run
            || scratch.ep.steps() > steps
            || !self.rec.continues(scratch.rec.edits(), scratch.ep.steps())
        {
            return Ok(false);
        }
        self.advance_replay_of(scratch, steps)?;
        scratch.check_against(self)?;
        Ok(true)
    }

    /// Which run this is: a new number when the handle is built or an
    /// edit restarts it at t = 0 (map, start, movers, restart); replays
    /// and branches keep their run's.
    #[wasm_bindgen(getter, js_name = runId)]
    pub fn run_id(&self) -> f64 {
        self.run as f64
    }

    /// Step counts at which live edits were made, in order.
    #[wasm_bindgen(js_name = editSteps)]
    pub fn edit_steps(&self) -> Vec<f64> {
        self.rec.edits().iter().map(|(s, _)| *s as f64).collect()
    }

    /// Trace row `i`: its numeric columns in the trace's column order (`t,
    /// x, y, theta, v, vy, w, cmd_v, cmd_vy, cmd_w, clearance, goal_x,
    /// goal_y, goal_kind, accel_z, load_fl, load_fr, load_rl, load_rr`;
    /// goal_kind 0 final, 1 intermediate, 2 virtual, 3 temporary; loads NaN
    /// without a vehicle model); empty past the end.
    #[wasm_bindgen(js_name = traceRow)]
    pub fn trace_row(&self, i: u32) -> Vec<f64> {
        let Some(r) = self.row(i) else {
            return Vec::new();
        };
        let mut out = Vec::with_capacity(19);
        for c in r.columns() {
            match c {
                Column::Num(_, x) => out.push(x),
                Column::GoalKind(k) => out.push(f64::from(k as u8)),
                Column::WheelLoads(l) => out.extend(l.unwrap_or([f64::NAN; 4])),
                // Text and lists have getters of their own.
                Column::Mode(_) | Column::Classes(_) | Column::Movers(_) => {}
            }
        }
        out
    }

    /// The planner's strategy in trace row `i` ("" in the start row).
    #[wasm_bindgen(js_name = traceMode)]
    pub fn trace_mode(&self, i: u32) -> String {
        self.row(i).map(|r| r.mode.clone()).unwrap_or_default()
    }

    /// Whether the scenario has a vehicle model (the trace carries wheel
    /// loads from the first step on).
    #[wasm_bindgen(getter, js_name = hasVehicle)]
    pub fn has_vehicle(&self) -> bool {
        self.rec.origin().terrain.vehicle.is_some()
    }

    /// Wheel loads from trace row `from` on, stride 5: `t (s), FL, FR, RL,
    /// RR (N)`, NaN where a row has none (the start row).
    #[wasm_bindgen(js_name = wheelLoads)]
    pub fn wheel_loads(&self, from: u32) -> Vec<f64> {
        let rows = self.ep.trace().steps.get(from as usize..).unwrap_or(&[]);
        let mut out = Vec::with_capacity(rows.len() * 5);
        for r in rows {
            out.push(r.t);
            out.extend_from_slice(&r.wheel_loads.unwrap_or([f64::NAN; 4]));
        }
        out
    }

    /// Tracking error from trace row `from` on, one value per row: the
    /// distance (m) from the driven position to the planner's current
    /// global path, as `planlab run` averages it for
    /// `mean_tracking_error_m`; empty without a global path.
    #[wasm_bindgen(js_name = trackingErrors)]
    pub fn tracking_errors(&self, from: u32) -> Vec<f64> {
        let path = &self.ep.planner_debug().global_path;
        if path.is_empty() {
            return Vec::new();
        }
        let rows = self.ep.trace().steps.get(from as usize..).unwrap_or(&[]);
        rows.iter()
            .filter_map(|r| distance_to_polyline([r.x, r.y], path))
            .collect()
    }
}

/// Every registered local planner as JSON: name, paper, summary and config
/// fields (name, unit, default, doc) plus each field's `kind` (`int`,
/// `float`, `bool`, `string`, `json`) from its default, for the page's
/// parameter panel.
#[wasm_bindgen]
pub fn planners() -> Result<String, JsError> {
    let mut v = serde_json::to_value(registry::list()).map_err(|e| json_err("planners", e))?;
    if let Some(list) = v.as_array_mut() {
        for p in list {
            let Some(fields) = p.get_mut("fields").and_then(|f| f.as_array_mut()) else {
                continue;
            };
            for f in fields {
                let kind = match f.get("default") {
                    Some(d) if d.is_u64() || d.is_i64() => "int",
                    Some(d) if d.is_f64() => "float",
                    Some(d) if d.is_boolean() => "bool",
                    Some(d) if d.is_string() => "string",
                    _ => "json",
                };
                if let Some(o) = f.as_object_mut() {
                    o.insert("kind".into(), kind.into());
                }
            }
        }
    }
    serde_json::to_string(&v).map_err(|e| json_err("planners", e))
}

/// The local planners a `global_planner` car path can guide
/// ([`planlab_core::local::car_guide::FOLLOWERS`]), as a JSON list.
#[wasm_bindgen(js_name = globalFollowers)]
pub fn global_followers() -> String {
    serde_json::to_string(&planlab_core::local::car_guide::FOLLOWERS).unwrap_or_default()
}
