//! The one edit recipe: what `planlab run --planner --seed --set
//! --variant`, the Python package, the reproductions and the pages do to a
//! scenario before it runs, so the same edits give the same scenario
//! everywhere.
//!
//! A [`Recipe`] applies its parts in one fixed order:
//! 1. `planner` of a robot or APF scenario: the local planner by name
//!    ([`set_planner_name`]: the config is kept when the name is the
//!    scenario's own, else reset to `{}`);
//! 2. `seed`: the scenario's seed;
//! 3. every `set` edit, in order ([`set_json_path`], key trimmed);
//! 4. `planner` of an arm scenario: the hand predictor
//!    ([`ArmPredictor::apply`]), written into `arm.apf` last, so it wins
//!    over a `set` of the same fields.
//!
//! Steps 1–4 edit the JSON tree ([`Recipe::edit_tree`]), so an edited
//! document can be written out and replayed with no flags. With a
//! `variant`, only step 3 edits the tree; then [`batch::variant`] draws the
//! variant of the parsed robot scenario with `seed` as the *batch* seed, and
//! the planner is swapped in last ([`batch::choice_for`]), which is how
//! `planlab batch` builds a row, so a CSV row's trace is reproduced.

use serde::Deserialize;
use serde_json::Value;
use thiserror::Error;

use crate::apf::ApfConfig;
use crate::arm::episode::arm_apf_default;
use crate::arm::{ArmError, ArmPredictor};
use crate::batch::{self, BatchError, MAX_VARIANTS};
use crate::map::OccupancyGrid;
use crate::scenario::{
    set_json_path, set_planner_name, AnyScenario, AnyScenarioError, ScenarioError, ScenarioKind,
};

/// What to change in a scenario before it runs (see the module docs for
/// the order). The default changes nothing.
#[derive(Debug, Clone, Default, PartialEq, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Recipe {
    /// A robot or APF scenario's local planner by registry name; an arm
    /// scenario's hand predictor (`none`, `constant-velocity`, `rnn`).
    pub planner: Option<String>,
    /// The scenario's seed; with a `variant`, the batch's seed.
    pub seed: Option<u64>,
    /// `(dotted.path, value)` edits, in order ([`set_json_path`]).
    pub set: Vec<(String, String)>,
    /// Run a batch variant instead of the scenario as written.
    pub variant: Option<VariantPick>,
}

/// Which variant of `planlab batch --seed S --jitter J` to run.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VariantPick {
    /// Variant index (0 = the scenario's positions, the variant's seed).
    pub index: u32,
    /// The batch's jitter, metres.
    pub jitter: f64,
}

/// Why a recipe could not be applied. Each message is one line.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum RecipeError {
    /// The document is not JSON, or a planner or `set` edit does not fit
    /// its tree (the message names the path).
    #[error(transparent)]
    Edit(#[from] ScenarioError),
    /// An arm scenario's predictor name is unknown.
    #[error(transparent)]
    Predictor(#[from] ArmError),
    /// The edited document is not a valid scenario.
    #[error(transparent)]
    Document(AnyScenarioError),
    /// The scenario's map could not be read.
    #[error(transparent)]
    Map(ScenarioError),
    /// A variant of a scenario kind that has none (APF, arm).
    #[error("--variant: {0} scenarios have no batch variants")]
    NoVariants(&'static str),
    /// The variant index is past [`MAX_VARIANTS`].
    #[error("--variant {0}: must be below {MAX_VARIANTS}")]
    VariantTooLarge(u32),
    /// The variant could not be drawn.
    #[error(transparent)]
    Batch(#[from] BatchError),
    /// A recipe given as JSON (the pages') is malformed.
    #[error("edits: {0}")]
    BadRecipe(String),
    /// [`Recipe::edit_tree`] was given a variant, which needs the parsed
    /// scenario and its map.
    #[error("a batch variant is drawn on the parsed scenario and its map, not on the JSON tree")]
    VariantOnTree,
}

/// A scenario after its recipe, with its map (none for an arm scenario).
#[derive(Debug, Clone)]
pub struct Edited {
    /// The scenario to run.
    pub scenario: AnyScenario,
    /// Its loaded map.
    pub grid: Option<OccupancyGrid>,
}

impl Recipe {
    /// A recipe from its JSON form, `{"planner": "dwa", "seed": 3, "set":
    /// [["sim.dt", "0.05"]], "variant": {"index": 2, "jitter": 0.3}}`
    /// (every field optional): how the pages pass a run link's edits.
    pub fn from_json(text: &str) -> Result<Recipe, RecipeError> {
        serde_json::from_str(text).map_err(|e| RecipeError::BadRecipe(e.to_string()))
    }

    /// Whether it changes nothing.
    pub fn is_empty(&self) -> bool {
        self.planner.is_none()
            && self.seed.is_none()
            && self.set.is_empty()
            && self.variant.is_none()
    }

    /// Steps 1–4 on a scenario's JSON tree. Refuses a recipe with a
    /// variant ([`RecipeError::VariantOnTree`]; use [`Recipe::apply`]).
    pub fn edit_tree(&self, tree: &mut Value) -> Result<(), RecipeError> {
        if self.variant.is_some() {
            return Err(RecipeError::VariantOnTree);
        }
        let arm = ScenarioKind::of(tree) == ScenarioKind::Arm;
        if let (Some(p), false) = (&self.planner, arm) {
            set_planner_name(tree, p)?;
        }
        if let Some(seed) = self.seed {
            set_json_path(tree, "seed", &seed.to_string())?;
        }
        for (path, value) in &self.set {
            set_json_path(tree, path.trim(), value)?;
        }
        if let (Some(p), true) = (&self.planner, arm) {
            set_predictor(tree, ArmPredictor::parse(p)?);
        }
        Ok(())
    }

    /// The scenario text with the recipe applied (steps 1–4), re-written
    /// as JSON; `text` itself when the recipe is empty, so errors keep
    /// pointing at its lines. What a page does with a run link.
    pub fn edit_text(&self, text: &str) -> Result<String, RecipeError> {
        if self.is_empty() {
            return Ok(text.to_string());
        }
        let mut tree = parse_tree(text)?;
        self.edit_tree(&mut tree)?;
        Ok(tree.to_string())
    }

    /// The scenario file `text` with the recipe applied, parsed, with its
    /// map (read through `read`, as [`AnyScenario::load_grid`]). Unedited,
    /// it is parsed from `text`, so errors point at the file's lines.
    pub fn apply(
        &self,
        text: &str,
        read: &mut dyn FnMut(&str) -> Result<Vec<u8>, String>,
    ) -> Result<Edited, RecipeError> {
        let tree = parse_tree(text)?;
        self.apply_with(&tree, || AnyScenario::from_json(text), read)
    }

    /// [`Recipe::apply`] on a scenario's JSON tree.
    pub fn apply_tree(
        &self,
        tree: &Value,
        read: &mut dyn FnMut(&str) -> Result<Vec<u8>, String>,
    ) -> Result<Edited, RecipeError> {
        self.apply_with(tree, || AnyScenario::from_value(tree), read)
    }

    /// The recipe on `tree`; `unedited` parses the document as given.
    fn apply_with(
        &self,
        tree: &Value,
        unedited: impl FnOnce() -> Result<AnyScenario, AnyScenarioError>,
        read: &mut dyn FnMut(&str) -> Result<Vec<u8>, String>,
    ) -> Result<Edited, RecipeError> {
        let Some(pick) = self.variant else {
            let scenario = if self.is_empty() {
                unedited()
            } else {
                let mut tree = tree.clone();
                self.edit_tree(&mut tree)?;
                AnyScenario::from_value(&tree)
            }
            .map_err(RecipeError::Document)?;
            let grid = scenario.load_grid(read).map_err(RecipeError::Map)?;
            return Ok(Edited { scenario, grid });
        };
        if pick.index >= MAX_VARIANTS {
            return Err(RecipeError::VariantTooLarge(pick.index));
        }
        if ScenarioKind::of(tree) == ScenarioKind::Arm {
            return Err(RecipeError::NoVariants(ScenarioKind::Arm.name()));
        }
        // The base is the scenario with the `set` edits only: the planner
        // comes after the draw and the seed is the batch's.
        let base = Recipe {
            set: self.set.clone(),
            ..Recipe::default()
        }
        .apply_with(tree, unedited, read)?;
        let (AnyScenario::Robot(base), Some(grid)) = (&base.scenario, base.grid) else {
            return Err(RecipeError::NoVariants(base.scenario.kind().name()));
        };
        let mut s = batch::variant(base, &grid, pick.index, self.seed.unwrap_or(0), pick.jitter)?;
        if let Some(name) = &self.planner {
            let own = base.local_planner.clone().unwrap_or_default();
            s.local_planner = Some(batch::choice_for(&own, name));
        }
        Ok(Edited {
            scenario: AnyScenario::Robot(s),
            grid: Some(grid),
        })
    }
}

/// The JSON tree of a scenario file; a syntax error points at its line.
fn parse_tree(text: &str) -> Result<Value, RecipeError> {
    serde_json::from_str(text)
        .map_err(|e| RecipeError::Edit(crate::map::io::json_syntax_error(text, e)))
}

/// [`ArmPredictor::apply`] on an arm scenario's tree: `arm.apf.mode` and
/// `arm.apf.predictor` written as the parsed config would have them after
/// the predictor (mode only when it changes for `none`). A missing
/// `arm.apf` is written whole from the arm's default, which differs from a
/// bare [`ApfConfig`]; a section that does not parse is left for the
/// scenario's own parse to report.
fn set_predictor(tree: &mut Value, p: ArmPredictor) {
    let Some(arm) = tree.get_mut("arm").and_then(Value::as_object_mut) else {
        return;
    };
    let Some(apf) = arm.get("apf") else {
        let mut cfg = arm_apf_default();
        p.apply(&mut cfg);
        if let Ok(v) = serde_json::to_value(&cfg) {
            arm.insert("apf".into(), v);
        }
        return;
    };
    let Ok(before) = ApfConfig::deserialize(apf) else {
        return;
    };
    let mut after = before.clone();
    p.apply(&mut after);
    let Some(apf) = arm.get_mut("apf").and_then(Value::as_object_mut) else {
        return;
    };
    let chosen = p != ArmPredictor::None;
    if chosen || after.mode != before.mode {
        if let Ok(v) = serde_json::to_value(after.mode) {
            apf.insert("mode".into(), v);
        }
    }
    if chosen {
        if let Ok(v) = serde_json::to_value(after.predictor) {
            apf.insert("predictor".into(), v);
        }
    }
}
