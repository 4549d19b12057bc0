//! The malformed corpus (`tests/data/malformed/`): every file must be
//! refused with the typed error its line in `MANIFEST.tsv` names (the
//! error's kind and a fragment of its message), in one line.
//!
//! The reader is chosen by the file's suffix: `.map`, `.scen`, `.yaml`,
//! `.pgm`, `.scenario.json` (read, map loaded, episode built), `.arm.json`
//! (arm model), `.armscen.json` (arm scenario, episode built) and
//! `.rnn.json` (predictor weights).

use planlab_core::apf::rnn::SimpleRnn;
use planlab_core::arm::{ArmEpisode, ArmModel};
use planlab_core::map::io::{movingai, ros};
use planlab_core::scenario::{ArmScenario, Scenario};
use planlab_core::sim::Episode;
use std::collections::BTreeMap;
use std::path::PathBuf;

fn dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../tests/data/malformed")
}

/// The error of reading `name`, as (kind, message); `None` if it was
/// accepted.
fn error_of(name: &str, bytes: &[u8]) -> Option<(&'static str, String)> {
    let text = || std::str::from_utf8(bytes).expect("text corpus files are UTF-8");
    let err = |kind: &'static str, e: &dyn std::fmt::Display| Some((kind, e.to_string()));
    if name.ends_with(".scenario.json") {
        let s = match Scenario::from_json(text()) {
            Ok(s) => s,
            Err(e) => return err(kind_of_scenario_error(&e), &e),
        };
        let mut no_files = |_: &str| Err::<Vec<u8>, String>("no map files here".into());
        let grid = match s.load_grid(&mut no_files) {
            Ok(g) => g,
            Err(e) => return err(kind_of_scenario_error(&e), &e),
        };
        return Episode::from_scenario(&s, grid)
            .err()
            .and_then(|e| err("SimError", &e));
    }
    if name.ends_with(".armscen.json") {
        return match ArmScenario::from_json(text()) {
            Ok(s) => ArmEpisode::new(s.arm, 0)
                .err()
                .and_then(|e| err("ArmError", &e)),
            Err(e) => err("ArmError", &e),
        };
    }
    if name.ends_with(".arm.json") {
        return ArmModel::from_json(text())
            .err()
            .and_then(|e| err("ArmError", &e));
    }
    if name.ends_with(".rnn.json") {
        return SimpleRnn::from_json(text())
            .err()
            .and_then(|e| err("ApfError", &e));
    }
    if name.ends_with(".map") {
        return movingai::parse_map(text())
            .err()
            .and_then(|e| err("MapError", &e));
    }
    if name.ends_with(".scen") {
        return movingai::parse_scen(text())
            .err()
            .and_then(|e| err("MapError", &e));
    }
    if name.ends_with(".yaml") {
        return ros::parse_yaml(text())
            .err()
            .and_then(|e| err("MapError", &e));
    }
    if name.ends_with(".pgm") {
        return ros::parse_pgm(bytes)
            .err()
            .and_then(|e| err("MapError", &e));
    }
    panic!("{name}: no reader for this suffix");
}

fn kind_of_scenario_error(e: &planlab_core::scenario::ScenarioError) -> &'static str {
    use planlab_core::scenario::ScenarioError as E;
    match e {
        E::Map(_) => "ScenarioError::Map",
        E::Json { .. } => "ScenarioError::Json",
        E::UnsupportedVersion { .. } => "ScenarioError::UnsupportedVersion",
        E::Invalid(_) => "ScenarioError::Invalid",
        _ => "ScenarioError",
    }
}

#[test]
fn every_malformed_file_gives_its_typed_one_line_error() {
    let manifest = std::fs::read_to_string(dir().join("MANIFEST.tsv")).unwrap();
    let mut expected: BTreeMap<String, (String, String)> = BTreeMap::new();
    for line in manifest
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
    {
        let cols: Vec<&str> = line.split('\t').collect();
        assert_eq!(
            cols.len(),
            3,
            "MANIFEST.tsv: file, kind, fragment: {line:?}"
        );
        let old = expected.insert(cols[0].into(), (cols[1].into(), cols[2].into()));
        assert!(old.is_none(), "{} listed twice", cols[0]);
    }
    let mut seen = Vec::new();
    let mut failures = Vec::new();
    for entry in std::fs::read_dir(dir()).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        if name == "MANIFEST.tsv" || name == "README.md" {
            continue;
        }
        seen.push(name.clone());
        let got = error_of(&name, &std::fs::read(&path).unwrap());
        let Some((kind, message)) = got else {
            failures.push(format!("{name}: accepted, expected an error"));
            continue;
        };
        assert!(
            !message.contains('\n'),
            "{name}: multi-line error {message:?}"
        );
        match expected.get(&name) {
            None => failures.push(format!("{name}\t{kind}\t{message}  <- not in MANIFEST.tsv")),
            Some((k, fragment)) => {
                if k != kind || !message.contains(fragment.as_str()) {
                    failures.push(format!(
                        "{name}: expected {k} containing {fragment:?}, got {kind}: {message}"
                    ));
                }
            }
        }
    }
    for name in expected.keys() {
        if !seen.contains(name) {
            failures.push(format!("{name}: in MANIFEST.tsv but not in the folder"));
        }
    }
    assert!(seen.len() >= 40, "the corpus has only {} files", seen.len());
    assert!(failures.is_empty(), "\n{}", failures.join("\n"));
}
