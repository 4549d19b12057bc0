//! Scenario files, the top of the data's road: the JSON documents that say
//! what to run, and the one way from a document to a finished run.
//!
//! Three kinds of file (`docs/scenario-schema.md`):
//! - a **robot** scenario ([`Scenario`]): map, start, goal, robot, movers,
//!   local planner, simulation settings; it runs as an [`Episode`];
//! - an **APF** scenario: the same document with an `apf` section; it runs
//!   as a kinematic potential-field run ([`AnyApfRun`], \[T\] ch. 4);
//! - an **arm** scenario ([`ArmScenario`]): an `arm` section and no map; it
//!   runs as an [`ArmEpisode`] (\[T\] §5.3.3).
//!
//! [`ScenarioKind::of`] tells them apart from the JSON tree (before edits
//! such as `--planner` that depend on the kind), [`AnyScenario`] parses any
//! of them, [`AnyScenario::start`] builds the run and [`AnyRun::run`] runs
//! it to its metrics ([`FinishedRun`], with its trace hash). `planlab run`, `planlab reproduce`
//! and the pages go through here; [`crate::batch`] varies robot scenarios.
//!
//! - [`document`]: the robot / APF document: strict, versioned, lossless
//!   JSON, `--set` edits on its tree.
//! - [`build`]: a scenario's episode or APF run, an episode back to a
//!   self-contained scenario, scenarios for bare maps.
//! - [`arm`]: the arm scenario file.
//!
//! The `map` section ([`MapSpec`]) and the error type ([`ScenarioError`])
//! are defined with the map formats in [`crate::map::io`] and named here.

pub mod arm;
pub mod build;
pub mod document;

pub use crate::map::io::map_spec::{
    join_relative, InlineMap, MapFileRef, MapFormat, MapSpec, RowEncoding, PLAIN_ROWS_MAX_SIDE,
};
pub use crate::map::io::ScenarioError;
pub use arm::{ArmScenario, ARM_SCENARIO_VERSION};
pub use build::{default_endpoints, ENDPOINT_MARGIN_M};
pub use document::{
    set_json_path, set_planner_name, Scenario, ScenarioPoint, WorldPoint, SCENARIO_VERSION,
    SET_PATH_MAX_NAMES,
};

use serde_json::Value;
use thiserror::Error;

use crate::apf::scene::path_hash;
use crate::apf::{AnyApfRun, ApfError, ApfMetrics};
use crate::arm::{ArmEpisode, ArmError};
use crate::map::OccupancyGrid;
use crate::metrics::EpisodeMetrics;
use crate::sim::{Episode, SimError};

/// The kind of a scenario file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ScenarioKind {
    /// A robot episode on a map.
    Robot,
    /// A kinematic potential-field run (an `apf` section).
    Apf,
    /// The arm among the moving hand (an `arm` section).
    Arm,
}

impl ScenarioKind {
    /// The kind of the JSON document `tree`: an `arm` section makes an arm
    /// scenario, an `apf` section (not `null`) an APF scenario, anything
    /// else a robot scenario. Agrees with [`AnyScenario::kind`] of the
    /// parsed document.
    pub fn of(tree: &Value) -> ScenarioKind {
        if tree.get("arm").is_some() {
            ScenarioKind::Arm
        } else if tree.get("apf").is_some_and(|a| !a.is_null()) {
            ScenarioKind::Apf
        } else {
            ScenarioKind::Robot
        }
    }

    /// `robot`, `APF` or `arm`, for messages.
    pub fn name(self) -> &'static str {
        match self {
            ScenarioKind::Robot => "robot",
            ScenarioKind::Apf => "APF",
            ScenarioKind::Arm => "arm",
        }
    }
}

/// Why a scenario of any kind could not be read, built or run: the error of
/// the stage that failed, with its own message.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum AnyScenarioError {
    /// Reading a robot or APF document, or its map.
    #[error(transparent)]
    Scenario(#[from] ScenarioError),
    /// Building a robot episode or an APF run.
    #[error(transparent)]
    Sim(#[from] SimError),
    /// Reading, building or running an arm scenario.
    #[error(transparent)]
    Arm(#[from] ArmError),
    /// Running an APF run.
    #[error(transparent)]
    Apf(#[from] ApfError),
}

/// A scenario file of any kind, parsed and validated.
#[derive(Debug, Clone, PartialEq)]
pub enum AnyScenario {
    /// A robot scenario.
    Robot(Scenario),
    /// A robot document with an `apf` section.
    Apf(Scenario),
    /// An arm scenario.
    Arm(ArmScenario),
}

impl AnyScenario {
    /// Parses a scenario file of any kind. Errors point at lines of `text`.
    pub fn from_json(text: &str) -> Result<AnyScenario, AnyScenarioError> {
        let tree: Value =
            serde_json::from_str(text).map_err(|e| crate::map::io::json_syntax_error(text, e))?;
        match ScenarioKind::of(&tree) {
            ScenarioKind::Arm => Ok(AnyScenario::Arm(ArmScenario::from_value(&tree)?)),
            _ => Ok(AnyScenario::of_document(Scenario::from_json(text)?)),
        }
    }

    /// Parses a scenario of any kind from a JSON tree (after
    /// [`set_json_path`] edits); errors point at lines of its pretty print.
    pub fn from_value(tree: &Value) -> Result<AnyScenario, AnyScenarioError> {
        match ScenarioKind::of(tree) {
            ScenarioKind::Arm => Ok(AnyScenario::Arm(ArmScenario::from_value(tree)?)),
            _ => Ok(AnyScenario::of_document(Scenario::from_value(tree)?)),
        }
    }

    /// A robot document as the kind its sections make it.
    fn of_document(s: Scenario) -> AnyScenario {
        if s.apf.is_some() {
            AnyScenario::Apf(s)
        } else {
            AnyScenario::Robot(s)
        }
    }

    /// Its kind.
    pub fn kind(&self) -> ScenarioKind {
        match self {
            AnyScenario::Robot(_) => ScenarioKind::Robot,
            AnyScenario::Apf(_) => ScenarioKind::Apf,
            AnyScenario::Arm(_) => ScenarioKind::Arm,
        }
    }

    /// Its short title (may be empty).
    pub fn name(&self) -> &str {
        match self {
            AnyScenario::Robot(s) | AnyScenario::Apf(s) => &s.name,
            AnyScenario::Arm(s) => &s.name,
        }
    }

    /// Its seed (default 0).
    pub fn seed(&self) -> u64 {
        match self {
            AnyScenario::Robot(s) | AnyScenario::Apf(s) => s.seed,
            AnyScenario::Arm(s) => s.seed,
        }
        .unwrap_or(0)
    }

    /// The map of a robot or APF scenario ([`Scenario::load_grid`]: inline,
    /// or its files through `read`); `None` for an arm scenario, which has
    /// none.
    pub fn load_grid(
        &self,
        read: &mut dyn FnMut(&str) -> Result<Vec<u8>, String>,
    ) -> Result<Option<OccupancyGrid>, ScenarioError> {
        match self {
            AnyScenario::Robot(s) | AnyScenario::Apf(s) => s.load_grid(read).map(Some),
            AnyScenario::Arm(_) => Ok(None),
        }
    }

    /// Builds the run: the robot episode ([`Episode::from_scenario`]), the
    /// APF run ([`Scenario::apf_run`]) or the arm episode
    /// ([`ArmEpisode::from_scenario`]). `grid` is the scenario's loaded map
    /// ([`AnyScenario::load_grid`]); an arm scenario ignores it.
    pub fn start(&self, grid: Option<OccupancyGrid>) -> Result<AnyRun, AnyScenarioError> {
        let map = |grid: Option<OccupancyGrid>| {
            grid.ok_or_else(|| {
                ScenarioError::Invalid("the scenario's map is not loaded: load_grid first".into())
            })
        };
        Ok(match self {
            AnyScenario::Robot(s) => {
                AnyRun::Robot(Box::new(Episode::from_scenario(s, map(grid)?)?))
            }
            AnyScenario::Apf(s) => AnyRun::Apf(Box::new(s.apf_run(&map(grid)?)?)),
            AnyScenario::Arm(s) => AnyRun::Arm(Box::new(ArmEpisode::from_scenario(s)?)),
        })
    }
}

/// A built run of any kind.
#[derive(Debug)]
pub enum AnyRun {
    /// A robot episode.
    Robot(Box<Episode>),
    /// A kinematic APF run.
    Apf(Box<AnyApfRun>),
    /// An arm episode.
    Arm(Box<ArmEpisode>),
}

/// A run that has ended, with what it measured.
#[derive(Debug)]
pub enum FinishedRun {
    /// A robot episode and its metrics.
    Robot(Box<Episode>, EpisodeMetrics),
    /// An APF run and its path metrics.
    Apf(Box<AnyApfRun>, ApfMetrics),
    /// An arm episode and its path metrics (the tool's path, the minimum
    /// link-to-hand distance).
    Arm(Box<ArmEpisode>, ApfMetrics),
}

impl AnyRun {
    /// Runs to the end and measures the run.
    pub fn run(self) -> Result<FinishedRun, AnyScenarioError> {
        Ok(match self {
            AnyRun::Robot(mut ep) => {
                ep.run();
                let m = EpisodeMetrics::of_episode(&ep);
                FinishedRun::Robot(ep, m)
            }
            AnyRun::Apf(mut r) => {
                let m = r.run()?;
                FinishedRun::Apf(r, m)
            }
            AnyRun::Arm(mut ep) => {
                ep.run()?;
                let m = ep.metrics();
                FinishedRun::Arm(ep, m)
            }
        })
    }
}

impl FinishedRun {
    /// FNV-1a of the episode's trace, or of the path points of an APF or
    /// arm run: the hash `planlab run` and `planlab reproduce` print.
    pub fn trace_hash(&self) -> u64 {
        match self {
            FinishedRun::Robot(ep, _) => ep.trace().hash(),
            FinishedRun::Apf(r, _) => path_hash(&r.path_xyz()),
            FinishedRun::Arm(ep, _) => path_hash(ep.tool_path()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_kind_comes_from_the_sections() {
        let kind = |s: &str| ScenarioKind::of(&serde_json::from_str(s).unwrap());
        assert_eq!(kind(r#"{"version": 1}"#), ScenarioKind::Robot);
        assert_eq!(kind(r#"{"version": 1, "apf": null}"#), ScenarioKind::Robot);
        assert_eq!(kind(r#"{"version": 1, "apf": {}}"#), ScenarioKind::Apf);
        assert_eq!(kind(r#"{"version": 1, "arm": {}}"#), ScenarioKind::Arm);
        assert_eq!(ScenarioKind::Apf.name(), "APF");
    }

    #[test]
    fn every_kind_parses_builds_and_runs() {
        let wall = "#".repeat(12);
        let inside = format!("#{}#", ".".repeat(10));
        let robot = serde_json::json!({
            "version": 1, "name": "room", "seed": 4,
            "map": {"width": 12, "height": 5, "resolution": 0.2,
                    "cells": [wall, inside, inside, inside, wall]},
            "start": {"col": 2, "row": 2}, "goal": {"col": 9, "row": 2},
        })
        .to_string();
        let robot = robot.as_str();
        let s = AnyScenario::from_json(robot).unwrap();
        assert_eq!(
            (s.kind(), s.name(), s.seed()),
            (ScenarioKind::Robot, "room", 4)
        );
        let grid = s.load_grid(&mut |_| Err("inline".into())).unwrap();
        let done = s.start(grid).unwrap().run().unwrap();
        let hash = done.trace_hash();
        assert!(matches!(done, FinishedRun::Robot(_, ref e) if e.path_length_m > 0.5));
        // The same episode built directly has the same trace.
        let AnyScenario::Robot(doc) = &s else {
            unreachable!()
        };
        let mut ep = Episode::from_scenario(doc, doc.inline_grid().unwrap().unwrap()).unwrap();
        ep.run();
        assert_eq!(ep.trace().hash(), hash);
        // A robot scenario without its map is an error, not a panic.
        assert!(matches!(
            s.start(None),
            Err(AnyScenarioError::Scenario(ScenarioError::Invalid(_)))
        ));

        let mut tree: Value = serde_json::from_str(robot).unwrap();
        set_json_path(&mut tree, "apf.obstacles", "[]").unwrap();
        let s = AnyScenario::from_value(&tree).unwrap();
        assert_eq!(s.kind(), ScenarioKind::Apf);
        assert_eq!(s.kind(), ScenarioKind::of(&tree));
        let grid = s.load_grid(&mut |_| Err("inline".into())).unwrap();
        let done = s.start(grid).unwrap().run().unwrap();
        assert!(matches!(done, FinishedRun::Apf(_, ref p) if p.path_points > 1));

        let arm = include_str!("../../../../assets/scenarios/T-tab5-3.json");
        let s = AnyScenario::from_json(arm).unwrap();
        assert_eq!(s.kind(), ScenarioKind::Arm);
        assert_eq!(s.load_grid(&mut |_| Err("no map".into())).unwrap(), None);
        let done = s.start(None).unwrap().run().unwrap();
        assert!(matches!(done, FinishedRun::Arm(_, ref p) if p.path_points > 1));
        let e = AnyScenario::from_json(r#"{"version": 2, "arm": {}}"#).unwrap_err();
        assert!(e.to_string().contains("version 2"), "{e}");
    }
}
