//! `planlab reproduce --variants`: a family's JSON line has the verdict,
//! per-run success with intervals, per-clause shares and effects and the
//! deviations; every written-out variant replays through `planlab run` to
//! the trace hash the family reported; bad options are one-line errors.

use serde_json::Value;
use std::path::PathBuf;
use std::process::{Command, Output};

fn planlab(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_planlab"))
        .args(args)
        .output()
        .expect("run planlab")
}

fn json_lines(o: &Output) -> Vec<Value> {
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    String::from_utf8_lossy(&o.stdout)
        .lines()
        .map(|l| serde_json::from_str(l).expect("a JSON line"))
        .collect()
}

fn fresh_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("planlab-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Runs `id`'s family of `n`, writes its variants, and replays each run of
/// each variant with `planlab run FILE --json`.
fn replays(id: &str, n: u32) -> Value {
    let dir = fresh_dir(&format!("variants-{id}"));
    let ns = n.to_string();
    let lines = json_lines(&planlab(&[
        "reproduce",
        id,
        "--variants",
        &ns,
        "--seed",
        "5",
        "--json",
        "--write-variants",
        dir.to_str().unwrap(),
    ]));
    assert_eq!(lines.len(), 1);
    let f = lines[0].clone();
    let rows = f["rows"].as_array().unwrap();
    assert_eq!(rows.len(), n as usize);
    for row in rows {
        let k = row["k"].as_u64().unwrap();
        for (run, hash) in row["trace_hashes"].as_object().unwrap() {
            let file = dir.join(format!("{id}-v{k}-{run}.json"));
            let o = planlab(&["run", file.to_str().unwrap(), "--json"]);
            let v: Value = json_lines(&o).remove(0);
            assert_eq!(&v["trace_hash"], hash, "{id} variant {k} run {run}");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    f
}

#[test]
fn family_json_has_verdict_shares_effects_and_deviations() {
    let f = replays("T-fig3-13b", 3);
    assert!(
        ["reproduced", "partly", "not reproduced"].contains(&f["verdict"].as_str().unwrap()),
        "{f}"
    );
    assert_eq!(f["variants"], 3);
    for (_, r) in f["runs"].as_object().unwrap() {
        let s = &r["success"];
        let (lo, hi) = (
            s["ci95"][0].as_f64().unwrap(),
            s["ci95"][1].as_f64().unwrap(),
        );
        let rate = s["rate"].as_f64().unwrap();
        assert!(lo <= rate && rate <= hi, "{s}");
    }
    let clauses = f["clauses"].as_array().unwrap();
    assert!(clauses.len() >= 3);
    assert!(clauses.iter().any(|c| c["kind"] == "effect"));
    assert!(clauses.iter().all(|c| c["holds"]["n"] == 3));
    assert!(!f["deviations"].as_array().unwrap().is_empty());
}

#[test]
fn explain_names_every_perturbation_with_its_reason_and_split() {
    let o = planlab(&["reproduce", "T-fig4-8", "--explain", "--variants", "9"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = String::from_utf8_lossy(&o.stdout);
    let f = json_lines(&planlab(&[
        "reproduce",
        "T-fig4-8",
        "--variants",
        "9",
        "--json",
    ]))
    .remove(0);
    let sens = &f["sensitivity"];
    assert!(
        text.contains(&format!(
            "sensitivity: {}",
            sens["summary"].as_str().unwrap()
        )),
        "{text}"
    );
    assert!(text.contains("most sensitive: "), "{text}");
    let perts = sens["perturbations"].as_array().unwrap();
    assert_eq!(
        perts.len(),
        f["family"]["perturbations"].as_array().unwrap().len()
    );
    for p in perts {
        let why = p["why"].as_str().unwrap();
        assert!(!why.is_empty());
        assert!(text.contains(&format!("why: {why}")), "{why}\n{text}");
        if let Some(sp) = p["split"].as_object() {
            let below = format!("{}/{}", sp["below"]["k"], sp["below"]["n"]);
            assert!(text.contains(&below), "{below}\n{text}");
        }
    }
    // The verdict rule, with the interval: reproduced needs both.
    let (rate, lo) = (
        f["joint"]["rate"].as_f64().unwrap(),
        f["joint"]["ci95"][0].as_f64().unwrap(),
    );
    assert_eq!(
        f["verdict"] == "reproduced",
        rate >= 0.8 && lo >= 0.65,
        "{}",
        f["joint"]
    );
}

#[test]
fn path_and_arm_variants_replay_through_planlab_run() {
    replays("T-fig4-10", 3);
    replays("T-tab5-3", 2);
}

#[test]
fn a_sweep_prints_one_family_per_value() {
    let lines = json_lines(&planlab(&[
        "reproduce",
        "T-fig4-10",
        "--variants",
        "2",
        "--sweep",
        "apf.config.predict_dt=0.3,0.8",
        "--json",
    ]));
    assert_eq!(lines.len(), 2);
    assert_eq!(lines[0]["sweep"], "apf.config.predict_dt=0.3");
    assert_eq!(lines[1]["sweep"], "apf.config.predict_dt=0.8");
    assert_eq!(lines[0]["sweep_runs"].as_array().unwrap().len(), 3);
}

#[test]
fn bad_family_options_are_one_line_errors() {
    for (args, needle) in [
        (
            vec!["reproduce", "T-fig3-2", "--variants", "0"],
            "--variants 0",
        ),
        (
            vec!["reproduce", "T-fig3-2", "--variants", "4294967295"],
            "--variants 4294967295",
        ),
        (
            vec!["reproduce", "T-fig3-2", "--sweep", "a=1"],
            "--variants",
        ),
        (
            vec![
                "reproduce",
                "T-fig3-2",
                "--variants",
                "2",
                "--sweep",
                "nope",
            ],
            "PATH=a,b,c",
        ),
        (
            vec![
                "reproduce",
                "T-fig3-2",
                "--variants",
                "2",
                "--write-variants",
                "/nonexistent/dir",
            ],
            "not an existing folder",
        ),
    ] {
        let o = planlab(&args);
        assert!(!o.status.success(), "{args:?}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.contains(needle), "{args:?}: {err}");
    }
}

#[test]
fn list_prints_every_experiment_with_its_family() {
    let lines = json_lines(&planlab(&["reproduce", "--list", "--json"]));
    assert_eq!(lines.len(), 27);
    for l in &lines {
        assert!(!l["clauses"].as_array().unwrap().is_empty(), "{l}");
        assert!(
            !l["family"]["perturbations"].as_array().unwrap().is_empty(),
            "{l}"
        );
    }
}
