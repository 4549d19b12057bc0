//! BARN for the BARN page (core `barn`, docs/algorithms.md §barn): the
//! worlds of the site's compact file, a run's scenario (the page builds
//! its episode with [`crate::SimHandle::from_scenario`], as `planlab run
//! barn:N` builds it from the same JSON), the planners that can drive an
//! unknown map and the challenge's score. The compact text crosses on
//! every call (the page keeps it; parsing ~100 kB is a millisecond), so
//! nothing here holds state.

use planlab_core::barn::run::{self as barn_run, BarnOptions, PLANNERS};
use planlab_core::barn::{self, parse_compact, BarnWorld};
use serde::Serialize;
use wasm_bindgen::prelude::*;

/// One world as the page lists it.
#[derive(Serialize)]
struct WorldInfo {
    id: u32,
    difficulty: &'static str,
    optimal_time: f64,
    cylinders: usize,
}

/// The world `id` of the compact `text`.
fn world(text: &str, id: u32) -> Result<BarnWorld, JsError> {
    let worlds = parse_compact(text)?;
    if worlds.is_empty() {
        return Err(JsError::new("the BARN worlds file holds no world"));
    }
    let (lo, hi) = worlds
        .iter()
        .fold((u32::MAX, 0), |(lo, hi), w| (lo.min(w.id), hi.max(w.id)));
    worlds.into_iter().find(|w| w.id == id).ok_or_else(|| {
        JsError::new(&format!(
            "BARN world {id} is not in the worlds file (it holds worlds {lo}–{hi} with N mod 6 ≠ 0; the others are the challenge's held-back test set)"
        ))
    })
}

/// Every world of the compact `text` (`assets/barn/worlds.txt`) as JSON:
/// `[{id, difficulty, optimal_time, cylinders}]`, in file order.
#[wasm_bindgen(js_name = barnWorlds)]
pub fn barn_worlds(text: &str) -> Result<String, JsError> {
    let list: Vec<WorldInfo> = parse_compact(text)?
        .iter()
        .map(|w| WorldInfo {
            id: w.id,
            difficulty: w.difficulty().name(),
            optimal_time: w.optimal_time(),
            cylinders: w.cylinders().len(),
        })
        .collect();
    Ok(serde_json::to_string(&list)?)
}

/// The centres of world `id`'s cylinders, `x, y` flat, m (what the page
/// shows on request as the truth the planner does not see); the radius is
/// [`barn::RADIUS`].
#[wasm_bindgen(js_name = barnCylinders)]
pub fn barn_cylinders(text: &str, id: u32) -> Result<Vec<f64>, JsError> {
    Ok(world(text, id)?.cylinders().into_iter().flatten().collect())
}

/// The scenario JSON of world `id` driven by `planner` with `seed` and
/// laser noise σ `noise` (m): the core's `barn::run::scenario`, written as
/// `planlab run barn:N --planner P --seed S` writes it, so the episode is
/// the CLI's (same trace hash).
#[wasm_bindgen(js_name = barnScenario)]
pub fn barn_scenario(
    text: &str,
    id: u32,
    planner: &str,
    seed: f64,
    noise: f64,
) -> Result<String, JsError> {
    // JS numbers are exact integers only up to 2^53.
    if !(seed.is_finite() && seed >= 0.0 && seed.fract() == 0.0 && seed <= 9_007_199_254_740_991.0)
    {
        return Err(JsError::new(&format!(
            "seed {seed} is not a whole number from 0 to 2^53 − 1"
        )));
    }
    if !PLANNERS.contains(&planner) {
        return Err(JsError::new(&format!(
            "`{planner}` cannot drive an unknown map on BARN; choose from {}",
            PLANNERS.join(", ")
        )));
    }
    let w = world(text, id)?;
    let opts = BarnOptions { noise_std: noise };
    let (s, _) = barn_run::scenario(&w, planner, seed as u64, &opts)?;
    // Bad noise (negative, NaN, above the laser's bound) is caught here
    // rather than when the page builds the episode (`Scenario::validate`
    // leaves the perception section to the episode).
    s.validate()?;
    if let Some(p) = &s.perception {
        p.validate()?;
    }
    Ok(serde_json::to_string(&s)?)
}

/// The planners that can drive an unknown map, in the order the tables
/// list them (`barn::run::PLANNERS`).
#[wasm_bindgen(js_name = barnPlanners)]
pub fn barn_planners() -> Vec<String> {
    PLANNERS.iter().map(|p| p.to_string()).collect()
}

/// The BARN score of a run: `success · OT / clip(T, 2·OT, 8·OT)`.
#[wasm_bindgen(js_name = barnScore)]
pub fn barn_score(success: bool, time: f64, ot: f64) -> f64 {
    barn::score(success, time, ot)
}
