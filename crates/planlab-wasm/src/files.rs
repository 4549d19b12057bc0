//! The robot page's Files menu: the episode in force saved as a
//! self-contained scenario, its metrics as CSV, and scenarios for bare maps
//! (ROS map_server, Moving AI) with default start and goal. Everything is
//! computed by the core ([`Scenario::from_setup`], [`Scenario::for_map`],
//! [`EpisodeMetrics::to_csv`]); this file converts at the boundary.

use planlab_core::metrics::{EpisodeMetrics, DEFAULT_LOAD_THRESHOLD_N};
use planlab_core::scenario::Scenario;
use wasm_bindgen::prelude::*;

use crate::{MapHandle, SimHandle};

#[wasm_bindgen]
impl SimHandle {
    /// The episode in force as scenario JSON (pretty, map inline): the
    /// current map, goal, movers, planner and config, robot, simulation
    /// settings, terrain and seed, from the start pose. `planlab run` on
    /// it and `fromScenario` both rebuild the trace this episode records
    /// when run from its start.
    #[wasm_bindgen(js_name = scenarioJson)]
    pub fn scenario_json(&self, name: &str, description: &str) -> Result<String, JsError> {
        Ok(self
            .episode()
            .to_scenario(name, description)?
            .to_json_pretty()?)
    }

    /// Edits made to this run after its first step. The saved scenario
    /// holds the goal, movers and planner as they are now, from t = 0, so
    /// when this is not 0 its run differs from this one (edits made before
    /// the first step reproduce exactly); the page says so on Save.
    #[wasm_bindgen(getter, js_name = liveEdits)]
    pub fn live_edits(&self) -> u32 {
        u32::try_from(self.edits_after_start()).unwrap_or(u32::MAX)
    }

    /// The metrics so far as `name,value,unit` CSV (the `planlab run`
    /// metrics, full precision).
    #[wasm_bindgen(js_name = metricsCsv)]
    pub fn metrics_csv(&self) -> String {
        let ep = self.episode();
        EpisodeMetrics::from_trace(
            ep.trace(),
            &ep.planner_debug().global_path,
            ep.outcome(),
            DEFAULT_LOAD_THRESHOLD_N,
        )
        .to_csv()
    }
}

/// Scenario JSON for a bare map (opened without a scenario): the map
/// inline, the default robot and planner, start and goal placed far apart
/// in the largest free area. Errors when no free cell has room for the
/// robot.
#[wasm_bindgen(js_name = scenarioForMap)]
pub fn scenario_for_map(map: &MapHandle, name: &str) -> Result<String, JsError> {
    Ok(Scenario::for_map(name, map.grid().clone())?.to_json_pretty()?)
}
