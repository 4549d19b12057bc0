//! `planlab barn`: a small sweep with sane figures, CSV rows that replay
//! with `planlab run barn:N` to their trace hash, and one-line errors.

mod common;

use common::{assert_error, planlab};
use serde_json::Value;

#[test]
fn a_small_sweep_has_sane_figures_and_its_rows_replay() {
    let dir = std::env::temp_dir().join(format!("planlab-barn-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let csv = dir.join("runs.csv");
    let o = planlab(&[
        "barn",
        "--worlds",
        "1,2",
        "--planners",
        "move-base-dwa,dwb",
        "--json",
        "--csv",
        csv.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let lines: Vec<Value> = String::from_utf8_lossy(&o.stdout)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    let overall: Vec<&Value> = lines.iter().filter(|l| l["class"] == "all").collect();
    assert_eq!(overall.len(), 2);
    for l in &overall {
        assert_eq!(l["runs"], 2);
        let k = |f: &str| l[f]["k"].as_u64().unwrap();
        assert_eq!(k("success") + k("collision") + k("timeout"), 2, "{l}");
        let ci = &l["success"]["ci95"];
        assert!(ci[0].as_f64().unwrap() <= l["success"]["rate"].as_f64().unwrap());
        if let Some(m) = l["score"]["mean"].as_f64() {
            assert!((0.0..=0.5).contains(&m), "{l}");
        }
    }
    let footer = lines.last().unwrap();
    assert_eq!(footer["episodes"], 4);
    let text = std::fs::read_to_string(&csv).unwrap();
    let rows: Vec<&str> = text.lines().skip(1).collect();
    assert_eq!(rows.len(), 4);
    // The first row replays to its trace hash.
    let cols: Vec<&str> = rows[0].split(',').collect();
    let replay = cols[11];
    let args: Vec<&str> = replay.split_whitespace().skip(1).collect();
    let mut with_json = args.clone();
    with_json.push("--json");
    let r = planlab(&with_json);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let report: Value = serde_json::from_slice(&r.stdout).unwrap();
    assert_eq!(report["trace_hash"], cols[10], "{replay}");
    assert_eq!(report["outcome"], cols[5]);

    // The CSV summarised again (twice: a run found in two files counts
    // once) gives the sweep's figures; scores are read at 4 decimals.
    let csv_arg = csv.to_str().unwrap();
    let again = planlab(&[
        "barn",
        "--from-csv",
        csv_arg,
        "--from-csv",
        csv_arg,
        "--json",
    ]);
    assert!(
        again.status.success(),
        "{}",
        String::from_utf8_lossy(&again.stderr)
    );
    let summary: Vec<Value> = String::from_utf8_lossy(&again.stdout)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    for (live, read) in lines.iter().zip(&summary).take(lines.len() - 1) {
        assert_eq!(live["planner"], read["planner"]);
        assert_eq!(live["class"], read["class"]);
        assert_eq!(live["success"], read["success"], "{live} vs {read}");
        assert_eq!(live["collision"], read["collision"]);
        let (a, b) = (&live["score"]["mean"], &read["score"]["mean"]);
        match (a.as_f64(), b.as_f64()) {
            (Some(a), Some(b)) => assert!((a - b).abs() < 1e-4, "{a} vs {b}"),
            _ => assert_eq!(a, b),
        }
    }
    assert_eq!(summary.last().unwrap()["episodes"], 4);
    // Markdown: a row per planner in the overall table and the class table.
    let md = planlab(&[
        "barn",
        "--from-csv",
        csv_arg,
        "--markdown",
        "--planners",
        "dwb",
    ]);
    assert!(
        md.status.success(),
        "{}",
        String::from_utf8_lossy(&md.stderr)
    );
    let md = String::from_utf8_lossy(&md.stdout).into_owned();
    assert_eq!(
        md.lines().filter(|l| l.starts_with("| dwb |")).count(),
        2,
        "{md}"
    );
    assert!(!md.contains("move-base-dwa"), "{md}");

    // Not a runs CSV, a row with a bad outcome: one-line errors.
    let other = dir.join("other.csv");
    std::fs::write(&other, "a,b\n1,2\n").unwrap();
    assert_error(
        &planlab(&["barn", "--from-csv", other.to_str().unwrap()]),
        &["not a runs CSV"],
    );
    let bad = text
        .replacen(",reached,", ",landed,", 1)
        .replacen(",collision,", ",landed,", 1)
        .replacen(",timeout,", ",landed,", 1);
    // The same run with another trace hash is refused, not counted twice.
    let hash = cols[10];
    let changed = text.replacen(hash, &"0".repeat(hash.len()), 1);
    std::fs::write(&other, changed).unwrap();
    assert_error(
        &planlab(&[
            "barn",
            "--from-csv",
            csv_arg,
            "--from-csv",
            other.to_str().unwrap(),
        ]),
        &["two different trace hashes"],
    );
    std::fs::write(&other, bad).unwrap();
    assert_error(
        &planlab(&["barn", "--from-csv", other.to_str().unwrap()]),
        &["line 2", "outcome", "landed"],
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn bad_requests_get_one_line_errors() {
    assert_error(&planlab(&["barn", "--runs", "0"]), &["--runs 0"]);
    assert_error(
        &planlab(&["barn", "--worlds", "6"]),
        &["world 6", "N mod 6"],
    );
    assert_error(
        &planlab(&["barn", "--worlds", "1", "--planners", "pursuit"]),
        &["pursuit", "unknown map"],
    );
    assert_error(
        &planlab(&["barn", "--worlds", "x"]),
        &["not a world number"],
    );
    assert_error(&planlab(&["barn", "--noise", "NaN"]), &["--noise"]);
    assert_error(&planlab(&["run", "barn:6"]), &["held-back"]);
    assert_error(
        &planlab(&["run", "barn:/nonexistent/world_3.world"]),
        &["world_3"],
    );
}
