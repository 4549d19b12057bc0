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
use crate::arm::{ArmError, ArmPlanner, ArmPredictor};
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
    /// scenario's hand predictor (`none`, `constant-velocity`, `rnn`) or
    /// arm planner (`apf`, `rrt-connect`).
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
            // An arm planner's name (`apf`, `rrt-connect`) picks the
            // planner and keeps the predictor; a predictor's name picks it.
            match ArmPlanner::parse(p) {
                Ok(planner) => {
                    if let Some(a) = tree.get_mut("arm").and_then(Value::as_object_mut) {
                        a.insert("planner".into(), Value::from(planner.name()));
                    }
                }
                Err(_) => set_predictor(tree, ArmPredictor::parse(p)?),
            }
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
        if let Ok(v) = serde_json::to_value(cfg) {
            arm.insert("apf".into(), v);
        }
        return;
    };
    let Ok(before) = ApfConfig::deserialize(apf) else {
        return;
    };
    let mut after = before;
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenario::ArmScenario;

    const ROBOT: &str = include_str!("../../../assets/scenarios/T-fig3-2.json");
    const ARM: &str = include_str!("../../../assets/scenarios/T-tab5-3.json");

    fn no_files(_: &str) -> Result<Vec<u8>, String> {
        Err("inline maps only".into())
    }

    fn edits(set: &[(&str, &str)]) -> Vec<(String, String)> {
        set.iter()
            .map(|(p, v)| (p.to_string(), v.to_string()))
            .collect()
    }

    fn tree(text: &str) -> Value {
        serde_json::from_str(text).unwrap()
    }

    fn robot(r: &Recipe, text: &str) -> crate::scenario::Scenario {
        match r.apply(text, &mut no_files).unwrap().scenario {
            AnyScenario::Robot(s) => s,
            other => panic!("not a robot scenario: {other:?}"),
        }
    }

    fn arm(r: &Recipe, text: &str) -> ArmScenario {
        match r.apply(text, &mut no_files).unwrap().scenario {
            AnyScenario::Arm(s) => s,
            other => panic!("not an arm scenario: {other:?}"),
        }
    }

    #[test]
    fn the_planner_comes_first_then_the_seed_then_the_set_edits() {
        // A `set` of the new planner's config survives the planner swap
        // (which resets the config), and a `set` of the seed beats `seed`.
        let r = Recipe {
            planner: Some("dwa".into()),
            seed: Some(5),
            set: edits(&[
                ("local_planner.config.alpha", "0.3"),
                (" seed ", "9"),
                ("sim.dt", "0.05"),
                ("sim.dt", "0.08"),
            ]),
            variant: None,
        };
        let s = robot(&r, ROBOT);
        let lp = s.local_planner.unwrap();
        assert_eq!(lp.name, "dwa");
        assert_eq!(lp.config, serde_json::json!({"alpha": 0.3}));
        assert_eq!(s.seed, Some(9));
        assert_eq!(s.sim.unwrap().dt, 0.08);
        // The planner the scenario already has keeps its tuning.
        let mut own = tree(ROBOT);
        set_json_path(&mut own, "local_planner.config", r#"{"alpha": 0.2}"#).unwrap();
        let r = Recipe {
            planner: Some("improved-dwa".into()),
            ..Recipe::default()
        };
        r.edit_tree(&mut own).unwrap();
        assert_eq!(
            own["local_planner"],
            serde_json::json!({"name": "improved-dwa", "config": {"alpha": 0.2}})
        );
    }

    #[test]
    fn an_empty_recipe_leaves_the_document_as_written() {
        let r = Recipe::from_json("{}").unwrap();
        assert!(r.is_empty());
        assert_eq!(r.edit_text(ROBOT).unwrap(), ROBOT);
        assert_eq!(
            r.apply(ROBOT, &mut no_files).unwrap().scenario,
            AnyScenario::from_json(ROBOT).unwrap()
        );
        let r = Recipe::from_json(r#"{"planner": null, "set": [["seed", "3"]]}"#).unwrap();
        let edited = r.edit_text(ROBOT).unwrap();
        assert_eq!(tree(&edited)["seed"], 3);
    }

    #[test]
    fn bad_edits_are_typed_one_line_errors() {
        let r = Recipe {
            set: edits(&[("movers.99.radius", "0.5")]),
            ..Recipe::default()
        };
        let e = r.apply(ROBOT, &mut no_files).unwrap_err();
        assert!(
            matches!(e, RecipeError::Edit(ScenarioError::Invalid(_))),
            "{e:?}"
        );
        let msg = e.to_string();
        assert!(
            msg.ends_with("--set movers.99.radius: `movers` has 0 entries: no index 99"),
            "{msg}"
        );
        assert!(!msg.contains('\n'), "{msg}");
        // A value the document refuses is the document's error, after edits.
        let r = Recipe {
            set: edits(&[("sim.dt", "-1")]),
            ..Recipe::default()
        };
        let e = r.apply(ROBOT, &mut no_files).unwrap_err();
        assert!(matches!(e, RecipeError::Document(_)), "{e:?}");
        assert!(!e.to_string().contains('\n'), "{e}");
        // An unknown predictor, a malformed recipe.
        let r = Recipe {
            planner: Some("psychic".into()),
            ..Recipe::default()
        };
        let e = r.apply(ARM, &mut no_files).unwrap_err();
        assert!(matches!(e, RecipeError::Predictor(_)), "{e:?}");
        assert!(e.to_string().contains("unknown predictor `psychic`"), "{e}");
        let e = Recipe::from_json(r#"{"planer": "dwa"}"#).unwrap_err();
        assert!(
            e.to_string().starts_with("edits: unknown field `planer`"),
            "{e}"
        );
    }

    #[test]
    fn ten_thousand_set_edits_apply_to_one_tree_in_order() {
        // Half the edits add a field each, half rewrite the same field: all
        // land in the one tree, and the last write of a field wins.
        let mut set = Vec::new();
        for i in 0..5_000 {
            set.push((format!("local_planner.config.k{i}"), i.to_string()));
            set.push(("sim.dt".to_string(), format!("0.0{}", 1 + i % 9)));
        }
        let r = Recipe {
            set,
            ..Recipe::default()
        };
        let s = robot(&r, ROBOT);
        let config = s.local_planner.unwrap().config;
        let config = config.as_object().unwrap();
        assert_eq!(config.len(), 5_000);
        for i in 0..5_000 {
            assert_eq!(config[&format!("k{i}")], serde_json::json!(i), "k{i}");
        }
        // 4999 % 9 = 4: the last dt written is 0.05.
        assert_eq!(s.sim.unwrap().dt, 0.05);
    }

    /// The arm scenario parsed from `text`, then `p` applied to the parsed
    /// config: what `planlab run --planner` and Python did before the
    /// recipe.
    fn struct_way(text: &str, p: ArmPredictor) -> ArmScenario {
        let mut s = ArmScenario::from_value(&tree(text)).unwrap();
        p.apply(&mut s.arm.apf);
        s
    }

    #[test]
    fn the_arm_predictor_in_the_tree_parses_as_the_struct_edit_gives() {
        // The preset (mode and predictor written), a section without a
        // mode, another mode, and no `apf` section at all (the arm's own
        // default, whose robot radius a bare APF config lacks).
        let mut variants = vec![ARM.to_string()];
        for (path, value) in [
            ("arm.apf", r#"{"robot_radius": 0.05}"#),
            ("arm.apf.mode", "sampling"),
            ("arm.apf.mode", "basic"),
        ] {
            let mut t = tree(ARM);
            set_json_path(&mut t, path, value).unwrap();
            variants.push(t.to_string());
        }
        let mut t = tree(ARM);
        t["arm"].as_object_mut().unwrap().remove("apf");
        variants.push(t.to_string());
        for text in &variants {
            for p in ArmPredictor::ALL {
                let r = Recipe {
                    planner: Some(p.name().into()),
                    ..Recipe::default()
                };
                assert_eq!(arm(&r, text), struct_way(text, p), "{} on {text}", p.name());
            }
        }
    }

    #[test]
    fn the_arm_predictor_writes_what_reproduce_wrote() {
        // The edits the reproductions applied to the preset's tree before
        // the recipe (its `apf` section names mode and predictor).
        let cases = [
            ("none", "sampling", "constant-velocity"),
            (
                "constant-velocity",
                "sampling-prediction",
                "constant-velocity",
            ),
            ("cv", "sampling-prediction", "constant-velocity"),
            ("rnn", "sampling-prediction", "rnn"),
        ];
        for (name, mode, predictor) in cases {
            let mut t = tree(ARM);
            Recipe {
                planner: Some(name.into()),
                ..Recipe::default()
            }
            .edit_tree(&mut t)
            .unwrap();
            assert_eq!(t["arm"]["apf"]["mode"], mode, "{name}");
            assert_eq!(t["arm"]["apf"]["predictor"], predictor, "{name}");
            assert_eq!(t["arm"]["apf"]["robot_radius"], 0.04, "{name}");
        }
        // The predictor is applied after the `set` edits, so it wins.
        let r = Recipe {
            planner: Some("rnn".into()),
            set: edits(&[("arm.apf.mode", "basic"), ("arm.hand.speed", "2")]),
            ..Recipe::default()
        };
        let s = arm(&r, ARM);
        assert_eq!(ArmPredictor::of(&s.arm.apf), ArmPredictor::Rnn);
        assert_eq!(
            serde_json::to_value(&s.arm.hand).unwrap()["speed"],
            serde_json::json!(2.0)
        );
        // It never touches a local planner.
        let mut t = tree(ARM);
        r.edit_tree(&mut t).unwrap();
        assert!(t.get("local_planner").is_none());
    }

    #[test]
    fn a_variant_is_the_batch_row_with_the_planner_swapped_in() {
        let set = edits(&[("sim.max_time", "30")]);
        let r = Recipe {
            planner: Some("dwa".into()),
            seed: Some(7),
            set: set.clone(),
            variant: Some(VariantPick {
                index: 3,
                jitter: 0.3,
            }),
        };
        let done = r.apply(ROBOT, &mut no_files).unwrap();
        let AnyScenario::Robot(got) = &done.scenario else {
            panic!("{:?}", done.scenario.kind())
        };
        // By hand: the `set` edits, the batch's variant 3 of seed 7, then
        // the planner as `planlab batch` runs it.
        let mut t = tree(ROBOT);
        set_json_path(&mut t, "sim.max_time", "30").unwrap();
        let base = crate::scenario::Scenario::from_value(&t).unwrap();
        let grid = base.inline_grid().unwrap().unwrap();
        let mut want = batch::variant(&base, &grid, 3, 7, 0.3).unwrap();
        want.local_planner = Some(batch::choice_for(
            base.local_planner.as_ref().unwrap(),
            "dwa",
        ));
        assert_eq!(got, &want);
        assert_eq!(got.seed, Some(batch::variant_seed(7, 3)));
        assert_ne!(got.start, base.start);
        assert_eq!(done.grid, Some(grid));

        let far = Recipe {
            variant: Some(VariantPick {
                index: MAX_VARIANTS,
                jitter: 0.0,
            }),
            ..Recipe::default()
        };
        assert_eq!(
            far.apply(ROBOT, &mut no_files).unwrap_err(),
            RecipeError::VariantTooLarge(MAX_VARIANTS)
        );
        let zero = Recipe {
            variant: Some(VariantPick {
                index: 0,
                jitter: 0.0,
            }),
            ..Recipe::default()
        };
        let e = zero.apply(ARM, &mut no_files).unwrap_err();
        assert_eq!(
            e.to_string(),
            "--variant: arm scenarios have no batch variants"
        );
        let mut t = tree(ROBOT);
        assert_eq!(
            zero.edit_tree(&mut t).unwrap_err(),
            RecipeError::VariantOnTree
        );
        assert_eq!(t, tree(ROBOT));
    }
}
