//! `planlab run` on scenarios the robot page saves (Files menu): an edited
//! episode written by `Episode::to_scenario` runs to the same trace hash
//! in the CLI as in the core (the page runs the core in wasm, and the e2e
//! test `files.test.mjs` checks the page against this CLI too).

use planlab_core::scenario::Scenario;
use planlab_core::sim::Episode;
use planlab_core::world::{MoverSpec, Placement};
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;

fn run_json(path: &Path) -> Value {
    let o = Command::new(env!("CARGO_BIN_EXE_planlab"))
        .args(["run", path.to_str().unwrap(), "--json"])
        .output()
        .expect("run planlab");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    serde_json::from_slice(&o.stdout).expect("one JSON object")
}

#[test]
fn saved_edited_scenario_runs_to_the_same_trace_in_the_cli() {
    let assets = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../assets/scenarios");
    let text = std::fs::read_to_string(assets.join("dwa-demo.json")).unwrap();
    let s = Scenario::from_json(&text).unwrap();
    let grid = s.load_grid(&mut |p| Err(p.to_string())).unwrap();
    let mut ep = Episode::from_scenario(&s, grid).unwrap();
    ep.set_goal([10.6, 1.2]).unwrap();
    let mut movers = ep.movers().to_vec();
    movers.push(
        MoverSpec::placed(
            7,
            0.3,
            Placement::BackAndForth,
            [2.5, 4.5],
            [0.6, -0.3],
            3.0,
            0.0,
        )
        .unwrap(),
    );
    ep.set_movers(movers).unwrap();
    let json = ep
        .to_scenario("edited demo", "goal moved, mover added")
        .unwrap()
        .to_json_pretty()
        .unwrap();
    let dir = std::env::temp_dir().join(format!("planlab-export-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("exported.json");
    std::fs::write(&file, &json).unwrap();

    let outcome = ep.run();
    let out = run_json(&file);
    assert_eq!(out["scenario"], "edited demo");
    assert_eq!(out["outcome"], outcome.as_str());
    assert_eq!(out["steps"], ep.steps());
    assert_eq!(
        out["trace_hash"].as_str().unwrap(),
        format!("{:016x}", ep.trace().hash())
    );
    std::fs::remove_dir_all(&dir).ok();
}
