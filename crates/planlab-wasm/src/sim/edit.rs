//! The robot page's editing tools on a [`SimHandle`]: map shapes, start,
//! movers, generated maps, and the snapshots undo/redo restores. Every edit
//! builds a fresh core episode at t = 0 on the edited setup (the core
//! rebuilds the clearance field and the planner replans), so what the page
//! exports afterwards is the edited scenario; a refused edit (a wall over
//! the start, a goal sealed off) leaves the handle as it was.

use planlab_core::map::edit::MapEdit;
use planlab_core::map::generate::{generate, GenerateConfig};
use planlab_core::map::{Cell, OccupancyGrid, Pose2};
use planlab_core::sim::{Episode, SetupEdit, SimConfig};
use planlab_core::world::{MoverSpec, RobotState};
use serde::{Deserialize, Serialize};
use wasm_bindgen::prelude::*;

use super::{json_err, SimHandle};

/// Map frame of a snapshot.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct FrameJson {
    width: usize,
    height: usize,
    resolution: f64,
    origin: [f64; 2],
}

/// Everything an edit can change except the cells (which cross as bytes).
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct EditState {
    /// Start pose `[x, y, θ]`.
    start: [f64; 3],
    goal: [f64; 2],
    movers: Vec<MoverSpec>,
    map: FrameJson,
    sim: SimConfig,
}

impl SimHandle {
    /// Swaps in an edited episode, keeping the page's drawing settings.
    fn replace(&mut self, ep: Episode) {
        let (draw_fan, fan) = (self.draw_fan, self.fan);
        *self = SimHandle::wrap(ep);
        self.draw_fan = draw_fan;
        // The planner is the same: its critic k is still there.
        self.fan = fan;
        self.ep.set_record_rollouts(draw_fan);
    }
}

fn generate_config(json: &str) -> Result<GenerateConfig, JsError> {
    serde_json::from_str(json).map_err(|e| json_err("invalid generator settings", e))
}

#[wasm_bindgen]
impl SimHandle {
    /// Paints a shape into the map and restarts on it: `{"op": "stroke",
    /// "points": [[x, y], …], "radius": m, "cell": "occupied"|"free"}`,
    /// `{"op": "rect", "a": [x, y], "b": [x, y], "cell": …}` or `{"op":
    /// "disc", "centre": [x, y], "radius": m, "cell": …}`. Returns how many
    /// cells changed.
    #[wasm_bindgen(js_name = editMap)]
    pub fn edit_map(&mut self, json: &str) -> Result<u32, JsError> {
        let edit: MapEdit =
            serde_json::from_str(json).map_err(|e| json_err("invalid map edit", e))?;
        let (ep, changed) = self.ep.with_map_edit(&edit)?;
        self.replace(ep);
        Ok(changed as u32)
    }

    /// Moves the start to (x, y) with heading `yaw` (rad) and restarts.
    #[wasm_bindgen(js_name = setStart)]
    pub fn set_start(&mut self, x: f64, y: f64, yaw: f64) -> Result<(), JsError> {
        let ep = self.ep.edited(SetupEdit {
            start: Some(RobotState {
                x,
                y,
                theta: yaw,
                ..Default::default()
            }),
            ..Default::default()
        })?;
        self.replace(ep);
        Ok(())
    }

    /// Replaces the movers (JSON array of mover specs) and restarts.
    #[wasm_bindgen(js_name = editMovers)]
    pub fn edit_movers(&mut self, json: &str) -> Result<(), JsError> {
        let movers: Vec<MoverSpec> =
            serde_json::from_str(json).map_err(|e| json_err("invalid movers JSON", e))?;
        let ep = self.ep.edited(SetupEdit {
            movers: Some(movers),
            ..Default::default()
        })?;
        self.replace(ep);
        Ok(())
    }

    /// Restarts from t = 0 with every edit (map, start, goal, movers,
    /// planner) kept.
    pub fn restart(&mut self) -> Result<(), JsError> {
        let ep = self.ep.restarted()?;
        self.replace(ep);
        Ok(())
    }

    /// Replaces map, start and goal with a generated map (settings as
    /// `GenerateConfig` JSON: `kind`, `width_m`, `height_m`, `resolution`,
    /// `seed`, …), drops the movers and restarts. Returns the grid hash.
    #[wasm_bindgen(js_name = generateMap)]
    pub fn generate_map(&mut self, json: &str) -> Result<String, JsError> {
        let g = generate(&generate_config(json)?)?;
        let ep = self.ep.with_generated(&g)?;
        self.replace(ep);
        Ok(g.grid.content_hash().to_string())
    }

    /// The map's content hash (u64 as a decimal string), the number
    /// `planlab generate` prints.
    #[wasm_bindgen(js_name = gridHash)]
    pub fn grid_hash(&self) -> String {
        self.ep.map().grid().content_hash().to_string()
    }

    /// The editable setup as JSON (start `[x, y, θ]`, goal, movers, map
    /// frame, sim settings); with [`SimHandle::map`]'s cells it is an undo
    /// snapshot for [`SimHandle::restore_edit`].
    #[wasm_bindgen(js_name = editState)]
    pub fn edit_state(&self) -> Result<String, JsError> {
        let s = self.ep.start_pose();
        let g = self.ep.map().grid();
        let o = g.origin();
        let state = EditState {
            start: [s.x, s.y, s.theta],
            goal: self.ep.goal(),
            movers: self.ep.movers().to_vec(),
            map: FrameJson {
                width: g.width(),
                height: g.height(),
                resolution: g.resolution(),
                origin: [o.x, o.y],
            },
            sim: *self.ep.config(),
        };
        serde_json::to_string(&state).map_err(|e| json_err("edit state", e))
    }

    /// Restores a snapshot ([`SimHandle::edit_state`] JSON and the cells,
    /// one byte each: 0 free, 1 occupied, 2 unknown) and restarts.
    #[wasm_bindgen(js_name = restoreEdit)]
    pub fn restore_edit(&mut self, state: &str, cells: &[u8]) -> Result<(), JsError> {
        let s: EditState =
            serde_json::from_str(state).map_err(|e| json_err("invalid edit snapshot", e))?;
        let cells = cells
            .iter()
            .map(|&k| crate::cell_of(k))
            .collect::<Result<Vec<Cell>, _>>()?;
        let grid = OccupancyGrid::from_cells(s.map.width, s.map.height, cells)?.with_frame(
            s.map.resolution,
            Pose2 {
                x: s.map.origin[0],
                y: s.map.origin[1],
                yaw: 0.0,
            },
        )?;
        let ep = self.ep.edited(SetupEdit {
            grid: Some(grid),
            start: Some(RobotState {
                x: s.start[0],
                y: s.start[1],
                theta: s.start[2],
                ..Default::default()
            }),
            goal: Some(s.goal),
            movers: Some(s.movers),
            config: Some(s.sim),
        })?;
        self.replace(ep);
        Ok(())
    }
}

/// The content hash of the map `settings` (`GenerateConfig` JSON)
/// generate, without an episode: what `planlab generate` prints.
#[wasm_bindgen(js_name = generatedGridHash)]
pub fn generated_grid_hash(settings: &str) -> Result<String, JsError> {
    let g = generate(&generate_config(settings)?)?;
    Ok(g.grid.content_hash().to_string())
}
