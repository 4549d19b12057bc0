//! The scenario of any variant of a `planlab reproduce` experiment, for the
//! robot, APF and arm pages' variant links (`…&exp=T-fig3-2&as=improved
//! &variant=3&seed=0`): the page runs the same tree that `planlab reproduce
//! ID --variants N --seed S` runs as variant k, so its trace hash is the
//! CLI's. Thin: the core's registry draws the variant
//! (`Experiment::variant`); nothing is perturbed here.
//!
//! A crate of its own because the registry embeds every preset (~0.7 MB of
//! JSON) and the path and arm runs: linked into the playground module it
//! would break the pages' 1.5 MB first-load budget, so the pages load this
//! module only when a variant link asks for it. `planlab-wasm` re-exports it
//! (feature `reproduce`, on by default) for its browser tests. For the same
//! reason it also holds the robot page's MCAP export ([`scenario_mcap`]).

use planlab_core::reproduce::{self, VariantScene, MAX_VARIANTS};
use serde::Serialize;
use wasm_bindgen::prelude::*;

/// One variant of an experiment: the trees of its runs and what was drawn.
fn scene(id: &str, k: u32, seed: u64) -> Result<VariantScene, String> {
    if k >= MAX_VARIANTS {
        return Err(format!(
            "variant {k}: a family has variants 0 to {} (0 is the preset)",
            MAX_VARIANTS - 1
        ));
    }
    let r = if let Some(e) = reproduce::find(id) {
        e.variant(seed, k, &[])
    } else if let Some(e) = reproduce::find_path(id) {
        e.variant(seed, k, &[])
    } else {
        return Err(format!(
            "unknown experiment `{id}`; known ids: {}",
            reproduce::ids().join(", ")
        ));
    };
    r.map_err(|e| format!("{id}: {e}"))
}

/// The tree of run `run` of `scene`, or an error naming the runs there are.
fn tree_of<'a>(
    id: &str,
    scene: &'a VariantScene,
    run: &str,
) -> Result<&'a serde_json::Value, String> {
    scene
        .trees
        .iter()
        .find(|(name, _)| *name == run)
        .map(|(_, t)| t)
        .ok_or_else(|| {
            let names: Vec<&str> = scene.trees.iter().map(|(n, _)| *n).collect();
            format!("{id} has no run `{run}`; its runs: {}", names.join(", "))
        })
}

/// Native form of [`reproduce_variant`]: the pretty scenario JSON of run
/// `run` of variant `k` of experiment `id`'s family seeded `seed`.
pub fn variant_json(id: &str, run: &str, k: u32, seed: u64) -> Result<String, String> {
    let s = scene(id, k, seed)?;
    serde_json::to_string_pretty(tree_of(id, &s, run)?).map_err(|e| e.to_string())
}

#[derive(Serialize)]
struct Info<'a> {
    id: &'a str,
    k: u32,
    /// The family's seed.
    seed: String,
    /// The variant's own seed (also its episode seed), as a decimal string:
    /// a u64 does not fit a JS number.
    variant_seed: String,
    /// Draws rejected before this one (a run could not start).
    redraws: u32,
    /// What was drawn: `{what, value}`.
    draws: &'a [reproduce::Draw],
    /// The run names, in run order.
    runs: Vec<&'a str>,
}

/// Native form of [`reproduce_variant_info`].
pub fn variant_info_json(id: &str, k: u32, seed: u64) -> Result<String, String> {
    let s = scene(id, k, seed)?;
    serde_json::to_string(&Info {
        id,
        k,
        seed: seed.to_string(),
        variant_seed: s.seed.to_string(),
        redraws: s.redraws,
        draws: &s.draws,
        runs: s.trees.iter().map(|(n, _)| *n).collect(),
    })
    .map_err(|e| e.to_string())
}

fn js(e: String) -> JsError {
    // This module has no start function (planlab-wasm, which links it for
    // its tests, has its own), so the hook is set at the first call.
    console_error_panic_hook::set_once();
    JsError::new(&e)
}

/// The pretty scenario JSON of run `run` of variant `k` (0 = the preset,
/// k < `MAX_VARIANTS`) of experiment `id`'s family seeded `seed`: what
/// `planlab reproduce ID --variants N --seed SEED --write-variants DIR`
/// writes as `ID-vK-RUN.json`. Unknown ids and runs, and k out of range,
/// are errors with the core's message.
#[wasm_bindgen(js_name = reproduceVariant)]
pub fn reproduce_variant(id: &str, run: &str, k: u32, seed: u64) -> Result<String, JsError> {
    variant_json(id, run, k, seed).map_err(js)
}

/// What variant `k` of `id`'s family seeded `seed` drew, as JSON
/// `{id, k, seed, variant_seed, redraws, draws: [{what, value}], runs}`
/// (seeds as decimal strings).
#[wasm_bindgen(js_name = reproduceVariantInfo)]
pub fn reproduce_variant_info(id: &str, k: u32, seed: u64) -> Result<String, JsError> {
    variant_info_json(id, k, seed).map_err(js)
}

/// The largest variant index plus one (`MAX_VARIANTS`).
#[wasm_bindgen(js_name = maxVariants)]
pub fn max_variants() -> u32 {
    MAX_VARIANTS
}

/// The run of a robot scenario (self-contained JSON with an inline map, as
/// the robot page's Files menu saves it) as an MCAP file: the messages of
/// `planlab run SCENARIO --mcap FILE` (`planlab-mcap`). Here, not in the
/// playground module, because the pages load this module only on demand:
/// the MCAP writer stays out of their first load.
#[wasm_bindgen(js_name = scenarioMcap)]
pub fn scenario_mcap(json: &str) -> Result<Vec<u8>, JsError> {
    mcap_of(json).map_err(js)
}

/// [`scenario_mcap`] with a plain error.
pub fn mcap_of(json: &str) -> Result<Vec<u8>, String> {
    use planlab_core::scenario::{AnyRun, AnyScenario};
    let s = AnyScenario::from_json(json).map_err(|e| e.to_string())?;
    let grid = s
        .load_grid(&mut |p| {
            Err(format!(
                "the page cannot read `{p}`: save the scenario with its map inline"
            ))
        })
        .map_err(|e| e.to_string())?;
    match s.start(grid).map_err(|e| e.to_string())? {
        AnyRun::Robot(mut ep) => planlab_mcap::record_episode(&mut ep)
            .map(|(bytes, _)| bytes)
            .map_err(|e| e.to_string()),
        _ => Err("only robot episodes have an MCAP export".into()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn variant_equals_the_core_tree() {
        let text = variant_json("T-fig3-2", "improved", 3, 0).unwrap();
        let got: serde_json::Value = serde_json::from_str(&text).unwrap();
        let want = reproduce::find("T-fig3-2")
            .unwrap()
            .variant(0, 3, &[])
            .unwrap();
        assert_eq!(&got, tree_of("T-fig3-2", &want, "improved").unwrap());
        // A path experiment too.
        assert!(variant_json("T-fig4-6", "sampling", 2, 0).is_ok());
    }

    #[test]
    fn bad_input_is_an_error() {
        assert!(variant_json("T-nope", "improved", 3, 0)
            .unwrap_err()
            .contains("unknown experiment"));
        assert!(variant_json("T-fig3-2", "nope", 3, 0)
            .unwrap_err()
            .contains("no run `nope`"));
        assert!(variant_json("T-fig3-2", "improved", MAX_VARIANTS, 0).is_err());
        assert!(variant_json("T-fig3-2", "improved", u32::MAX, 0).is_err());
    }
}

/// Native form of [`reproduce_check`]: `planlab reproduce ID --json`'s line
/// for experiment `id` on its presets (every run, every clause and whether
/// it holds), for robot-page and potential-field experiments.
pub fn check_json(id: &str) -> Result<String, String> {
    let text = if let Some(exp) = reproduce::find(id) {
        serde_json::to_string(&reproduce::run(&exp).map_err(|e| e.to_string())?)
    } else if let Some(exp) = reproduce::find_path(id) {
        serde_json::to_string(&reproduce::run_path(&exp).map_err(|e| e.to_string())?)
    } else {
        return Err(format!(
            "{id}: no robot or potential-field experiment of this id"
        ));
    };
    text.map_err(|e| e.to_string())
}

/// Runs experiment `id` on its presets as `planlab reproduce ID --json`
/// does and returns that JSON line (`holds`, `clauses`, `runs`): what a
/// gallery run shows as the ✓/✗ of the paper's relation when it ends.
#[wasm_bindgen(js_name = reproduceCheck)]
pub fn reproduce_check(id: &str) -> Result<String, JsError> {
    check_json(id).map_err(js)
}
