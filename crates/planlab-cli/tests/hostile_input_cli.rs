//! Hostile and malformed input, CLI side: one regression test per defect
//! found by fuzzing and hostile use (the core side is planlab-core's
//! `tests/hostile_input.rs`). Scratch files live under this crate's
//! `CARGO_TARGET_TMPDIR` (inside the repository's target/), never outside.

mod common;

use common::{asset, planlab};
use serde_json::Value;
use std::path::PathBuf;
use std::process::{Command, Output};
use std::time::Instant;

/// A fresh scratch folder for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("hostile-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The one error line of a failed run (asserted to be one line, prefixed,
/// with exit status `code`).
fn error_line(o: &Output, code: i32) -> String {
    assert_eq!(o.status.code(), Some(code), "{o:?}");
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(err.lines().count(), 1, "one error line expected: {err:?}");
    assert!(err.starts_with("planlab: error: "), "{err}");
    err
}

#[test]
fn dt_1e9_is_refused() {
    // Before: one step moved the robot 7.6·10⁸ m and resampling aborted
    // (exit 134).
    let demo = asset("scenarios/dwa-demo.json");
    let o = planlab(&["run", &demo, "--set", "sim.dt=1e9"]);
    let e = error_line(&o, 1);
    assert!(e.contains("sim.dt = 1e9 s: must be at most 1 s"), "{e}");
}

fn mkfifo(path: &std::path::Path) {
    let ok = Command::new("mkfifo").arg(path).status().unwrap().success();
    assert!(ok, "mkfifo {}", path.display());
}

#[test]
fn non_regular_map_files_are_refused() {
    // Before: `image: /dev/zero` read until memory ran out. A FIFO here
    // stands for any endless non-file (a read would block forever).
    let dir = scratch("fifo");
    mkfifo(&dir.join("endless.pgm"));
    std::fs::write(
        dir.join("map.yaml"),
        "image: endless.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n",
    )
    .unwrap();
    let yaml = dir.join("map.yaml").display().to_string();
    let e = error_line(
        &planlab(&["plan", &yaml, "--start", "0,0", "--goal", "1,1"]),
        1,
    );
    assert!(e.contains("endless.pgm: not a regular file"), "{e}");
    // Through a scenario's map.file, and a folder named as the image.
    let demo: Value =
        serde_json::from_str(&std::fs::read_to_string(asset("scenarios/grid-demo.json")).unwrap())
            .unwrap();
    let mut s = demo.clone();
    s["map"] = serde_json::json!({ "file": "map.yaml" });
    std::fs::write(dir.join("s.json"), s.to_string()).unwrap();
    let sp = dir.join("s.json").display().to_string();
    let e = error_line(&planlab(&["plan", &sp]), 1);
    assert!(e.contains("not a regular file"), "{e}");
    std::fs::create_dir_all(dir.join("folder.pgm")).unwrap();
    std::fs::write(
        dir.join("map.yaml"),
        "image: folder.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n",
    )
    .unwrap();
    let e = error_line(
        &planlab(&["plan", &yaml, "--start", "0,0", "--goal", "1,1"]),
        1,
    );
    assert!(e.contains("folder.pgm: not a regular file"), "{e}");
}

#[test]
fn oversized_files_are_refused_before_reading() {
    let dir = scratch("big");
    // Sparse files: huge on paper, no disk used, never read.
    let big = |name: &str, len: u64| {
        let p = dir.join(name);
        std::fs::File::create(&p).unwrap().set_len(len).unwrap();
        p.display().to_string()
    };
    let t = Instant::now();
    let map = big("huge.map", 300_000_000);
    let e = error_line(
        &planlab(&["plan", &map, "--start", "0,0", "--goal", "1,1"]),
        1,
    );
    assert!(e.contains("too large for a text file"), "{e}");
    let yaml = big("huge.yaml", 2 << 20);
    let e = error_line(
        &planlab(&["plan", &yaml, "--start", "0,0", "--goal", "1,1"]),
        1,
    );
    assert!(e.contains("too large for a ROS map YAML"), "{e}");
    // A PGM is read only as far as its header's width × height needs: a
    // 2×2 image followed by 1 GB of padding loads.
    let pgm = dir.join("small.pgm");
    std::fs::write(&pgm, b"P5\n2 2\n255\n\xfe\xfe\xfe\xfe").unwrap();
    std::fs::OpenOptions::new()
        .append(true)
        .open(&pgm)
        .unwrap()
        .set_len(1 << 30)
        .unwrap();
    std::fs::write(
        dir.join("small.yaml"),
        "image: small.pgm\nresolution: 1\norigin: [0, 0, 0]\n",
    )
    .unwrap();
    let small = dir.join("small.yaml").display().to_string();
    let o = planlab(&["plan", &small, "--start", "0,0", "--goal", "1,1", "--json"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // A header that asks for more than the map limit is refused.
    std::fs::write(dir.join("small.pgm"), b"P5\n100000 100000\n255\n\0").unwrap();
    let e = error_line(
        &planlab(&["plan", &small, "--start", "0,0", "--goal", "1,1"]),
        1,
    );
    assert!(e.contains("map too large"), "{e}");
    assert!(t.elapsed().as_secs_f64() < 20.0, "{:?}", t.elapsed());
}

#[test]
fn train_predictor_checks_before_writing() {
    let dir = scratch("train");
    let out = dir.join("rnn.json");
    let shipped = std::fs::read(asset("predictor/rnn.json")).unwrap();
    std::fs::write(&out, &shipped).unwrap();
    let o = out.display().to_string();
    // Weights that fail the quality check (before: written, then refused).
    let e = error_line(
        &planlab(&[
            "train-predictor",
            "--epochs",
            "1",
            "--trajectories",
            "1",
            "--out",
            &o,
        ]),
        1,
    );
    assert!(
        e.contains("does not beat constant velocity") && e.contains("not written"),
        "{e}"
    );
    assert_eq!(
        std::fs::read(&out).unwrap(),
        shipped,
        "the old weights stay"
    );
    let e = error_line(
        &planlab(&["train-predictor", "--epochs", "0", "--out", &o]),
        1,
    );
    assert!(e.contains("epochs = 0"), "{e}");
    assert_eq!(std::fs::read(&out).unwrap(), shipped);
    // A missing folder is an error, not created (before: create_dir_all).
    let missing = dir.join("no/such/r.json").display().to_string();
    let e = error_line(
        &planlab(&["train-predictor", "--epochs", "1", "--out", &missing]),
        1,
    );
    assert!(e.contains("does not exist"), "{e}");
    assert!(!dir.join("no").exists());
    // A good run replaces the file whole and leaves no temporary file.
    let ok = planlab(&["train-predictor", "--epochs", "1", "--out", &o, "--json"]);
    assert!(
        ok.status.success(),
        "{}",
        String::from_utf8_lossy(&ok.stderr)
    );
    let written: Value = serde_json::from_slice(&std::fs::read(&out).unwrap()).unwrap();
    assert_eq!(written["report"]["epochs"], 1);
    let names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names, ["rnn.json"]);
}

#[test]
fn batch_variants_are_bounded() {
    // Before: built variants one by one for minutes with no output.
    let demo = asset("scenarios/pursuit-demo.json");
    let t = Instant::now();
    let e = error_line(&planlab(&["batch", &demo, "--variants", "4294967295"]), 1);
    assert!(
        e.contains("--variants 4294967295: must be from 1 to 10000"),
        "{e}"
    );
    assert!(t.elapsed().as_secs_f64() < 5.0);
}

#[test]
fn batch_csv_rows_replay_with_run_variant() {
    // Before: the CSV's seed replayed variant 0 only (the jittered start,
    // goal and movers were lost).
    let dir = scratch("replay");
    let csv = dir.join("runs.csv");
    let demo = asset("scenarios/pursuit-demo.json");
    let o = planlab(&[
        "batch",
        &demo,
        "--planners",
        "pursuit,dwa",
        "--variants",
        "4",
        "--seed",
        "11",
        "--jitter",
        "0.4",
        "--csv",
        csv.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = std::fs::read_to_string(&csv).unwrap();
    let header: Vec<&str> = text.lines().next().unwrap().split(',').collect();
    let col = |n: &str| header.iter().position(|h| *h == n).unwrap();
    let rows: Vec<Vec<&str>> = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').collect())
        .collect();
    assert_eq!(rows.len(), 8);
    let mut hashes = std::collections::BTreeSet::new();
    for r in &rows {
        let run = planlab(&[
            "run",
            &demo,
            "--planner",
            r[col("planner")],
            "--variant",
            r[col("variant")],
            "--seed",
            r[col("batch_seed")],
            "--jitter",
            r[col("jitter_m")],
            "--json",
        ]);
        assert!(
            run.status.success(),
            "{}",
            String::from_utf8_lossy(&run.stderr)
        );
        let v: Value = serde_json::from_slice(&run.stdout).unwrap();
        assert_eq!(v["trace_hash"], r[col("trace_hash")], "row {r:?}");
        assert_eq!(v["seed"].to_string(), r[col("seed")], "row {r:?}");
        hashes.insert(r[col("trace_hash")].to_string());
    }
    assert_eq!(hashes.len(), 8, "every row is its own episode");
    // --jitter without --variant is a usage error.
    error_line(&planlab(&["run", &demo, "--jitter", "0.4"]), 2);
}

#[test]
fn usage_errors_are_one_line() {
    // Before: clap printed 4–20 lines (usage, tips) for these.
    for args in [
        &["run"][..],
        &["bogus"],
        &[],
        &["plan", "x.map", "--algo", "foo"],
        &["run", "x.json", "--frob"],
        &["batch", "x.json", "--variants", "-1"],
        &["batch", "x.json", "--variants", "4294967296"],
    ] {
        let o = planlab(args);
        let e = error_line(&o, 2);
        assert!(e.len() < 300, "{args:?}: {e}");
    }
    // Help and version still print in full, successfully.
    let o = planlab(&["--help"]);
    assert!(o.status.success());
    assert!(String::from_utf8_lossy(&o.stdout).lines().count() > 5);
}

#[test]
fn huge_numbers_print_compactly() {
    // Before: `--inflate 1e308` printed 309 digits.
    let demo = asset("scenarios/dwa-demo.json");
    let e = error_line(&planlab(&["plan", &demo, "--inflate", "1e308"]), 1);
    assert!(e.contains("within 1e308 m"), "{e}");
    assert!(e.len() < 150, "{e}");
    let e = error_line(&planlab(&["plan", &demo, "--inflate", "-1e308"]), 1);
    assert!(e.contains("--inflate -1e308"), "{e}");
    let e = error_line(
        &planlab(&["run", &demo, "--set", "robot.limits.v_max=1e300"]),
        1,
    );
    assert!(e.contains("1e300") && e.len() < 250, "{e}");
}

#[test]
fn a_spacious_p2_map_is_refused_not_cut() {
    // cargo fuzz (pgm) found that a valid P2 with long runs of whitespace
    // between pixels exceeded the per-pixel read bound and was cut short,
    // giving a misleading "truncated" error: it is refused by size instead.
    let dir = scratch("p2");
    let mut p2 = b"P2\n3 1\n255\n254".to_vec();
    p2.extend(std::iter::repeat_n(b'\r', 100));
    p2.extend_from_slice(b" 254 254\n");
    std::fs::write(dir.join("m.pgm"), &p2).unwrap();
    std::fs::write(
        dir.join("m.yaml"),
        "image: m.pgm\nresolution: 1\norigin: [0, 0, 0]\n",
    )
    .unwrap();
    let yaml = dir.join("m.yaml").display().to_string();
    let e = error_line(
        &planlab(&["plan", &yaml, "--start", "0,0", "--goal", "1,0"]),
        1,
    );
    assert!(e.contains("too large for an ASCII PGM"), "{e}");
    // The same pixels with ordinary spacing load.
    std::fs::write(dir.join("m.pgm"), b"P2\n3 1\n255\n254 254 254\n").unwrap();
    let o = planlab(&["plan", &yaml, "--start", "0,0", "--goal", "2,0", "--json"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// `assets/scenarios/NAME` copied into `dir` as `as_name` (its map is
/// inline, so the copy runs on its own).
fn scenario_copy(dir: &std::path::Path, name: &str, as_name: &str) -> PathBuf {
    let p = dir.join(as_name);
    std::fs::copy(asset(&format!("scenarios/{name}")), &p).unwrap();
    p
}

#[test]
fn batch_csv_keeps_an_existing_file_when_the_batch_fails() {
    // Before: the CSV was truncated before the first episode, so a batch
    // that then failed left only the header of the user's file.
    let dir = scratch("batch-keeps");
    let s = scenario_copy(&dir, "dwa-demo.json", "s.json");
    let mut tree: Value = serde_json::from_str(&std::fs::read_to_string(&s).unwrap()).unwrap();
    tree["start"] = serde_json::json!({ "col": 0, "row": 0 }); // in the wall
    std::fs::write(&s, tree.to_string()).unwrap();
    let csv = dir.join("existing.csv");
    std::fs::write(&csv, "precious\n").unwrap();
    let o = planlab(&[
        "batch",
        s.to_str().unwrap(),
        "--variants",
        "2",
        "--csv",
        csv.to_str().unwrap(),
    ]);
    common::assert_error(&o, &["starts in collision"]);
    assert_eq!(std::fs::read_to_string(&csv).unwrap(), "precious\n");
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(names, ["existing.csv", "s.json"], "no temporary file left");
}

#[test]
fn outputs_that_are_inputs_of_the_command_are_refused() {
    // Before: `batch s.json --csv s.json` and `run s.json --trace s.json`
    // exited 0 having replaced the scenario with CSV.
    let dir = scratch("out-is-in");
    let s = scenario_copy(&dir, "dwa-demo.json", "s.json");
    let before = std::fs::read(&s).unwrap();
    let sp = s.to_str().unwrap();
    let o = planlab(&["batch", sp, "--variants", "1", "--csv", sp]);
    common::assert_error(&o, &["--csv", "s.json", "input"]);
    let o = planlab(&["run", sp, "--trace", sp]);
    common::assert_error(&o, &["--trace", "s.json", "input"]);
    // The same file by another spelling.
    let other = dir.join(".").join("s.json");
    let o = planlab(&["run", sp, "--trace", other.to_str().unwrap()]);
    common::assert_error(&o, &["--trace", "input"]);
    assert_eq!(std::fs::read(&s).unwrap(), before, "the scenario is intact");
    // A map file the scenario reads is an input too.
    let mut pgm = b"P5\n40 40\n255\n".to_vec();
    pgm.extend(std::iter::repeat_n(254u8, 40 * 40));
    std::fs::write(dir.join("m.pgm"), &pgm).unwrap();
    std::fs::write(
        dir.join("m.yaml"),
        "image: m.pgm\nresolution: 0.1\norigin: [0, 0, 0]\n",
    )
    .unwrap();
    let mut tree: Value = serde_json::from_str(&std::fs::read_to_string(&s).unwrap()).unwrap();
    tree["map"] = serde_json::json!({ "file": "m.yaml" });
    tree["start"] = serde_json::json!({ "col": 5, "row": 34 });
    tree["goal"] = serde_json::json!({ "col": 34, "row": 5 });
    tree["movers"] = serde_json::json!([]);
    let g = dir.join("g.json");
    std::fs::write(&g, tree.to_string()).unwrap();
    let gp = g.to_str().unwrap();
    let o = planlab(&["run", gp, "--json"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let yaml_before = std::fs::read(dir.join("m.yaml")).unwrap();
    let yaml = dir.join("m.yaml");
    let o = planlab(&[
        "batch",
        gp,
        "--variants",
        "1",
        "--csv",
        yaml.to_str().unwrap(),
    ]);
    common::assert_error(&o, &["--csv", "m.yaml", "input"]);
    let image = dir.join("m.pgm");
    let o = planlab(&["run", gp, "--trace", image.to_str().unwrap()]);
    common::assert_error(&o, &["--trace", "m.pgm", "input"]);
    assert_eq!(std::fs::read(&image).unwrap(), pgm);
    assert_eq!(std::fs::read(dir.join("m.yaml")).unwrap(), yaml_before);
}

#[cfg(unix)]
#[test]
fn write_variants_replaces_a_planted_symlink_not_its_target() {
    // Before: a symlink planted at an output name was followed and the
    // file it points to (outside the folder) overwritten.
    let dir = scratch("variants-link");
    let out = dir.join("out");
    std::fs::create_dir_all(&out).unwrap();
    let outside = dir.join("outside.txt");
    std::fs::write(&outside, "secret\n").unwrap();
    let link = out.join("S-fig6-v0-safe-dual-dwa.json");
    std::os::unix::fs::symlink(&outside, &link).unwrap();
    let o = planlab(&[
        "reproduce",
        "S-fig6",
        "--variants",
        "1",
        "--write-variants",
        out.to_str().unwrap(),
        "--json",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(
        std::fs::read_to_string(&outside).unwrap() == "secret\n",
        "the link's target was overwritten"
    );
    let meta = std::fs::symlink_metadata(&link).unwrap();
    assert!(meta.is_file(), "the link was replaced by the file");
    let written: Value = serde_json::from_slice(&std::fs::read(&link).unwrap()).unwrap();
    assert!(written.is_object());
}

#[test]
fn a_start_on_an_unknown_cell_says_so_and_names_allow_unknown() {
    // Before: "start (0, 0) is inside an obstacle", in trinary and raw
    // mode alike, with no word of --allow-unknown.
    let dir = scratch("unknown-start");
    // 4×1: unknown, then free (trinary 205 is unknown, 254 free; raw
    // above 100 is unknown, 0 free).
    for (mode, pixels) in [("trinary", [205u8, 254, 254, 254]), ("raw", [255, 0, 0, 0])] {
        let mut pgm = b"P5\n4 1\n255\n".to_vec();
        pgm.extend_from_slice(&pixels);
        std::fs::write(dir.join("m.pgm"), &pgm).unwrap();
        std::fs::write(
            dir.join("m.yaml"),
            format!("image: m.pgm\nresolution: 1\norigin: [0, 0, 0]\nmode: {mode}\n"),
        )
        .unwrap();
        let yaml = dir.join("m.yaml").display().to_string();
        let o = planlab(&["plan", &yaml, "--start", "0,0", "--goal", "3,0"]);
        common::assert_error(&o, &["start (0, 0)", "unknown cell", "--allow-unknown"]);
        let o = planlab(&["plan", &yaml, "--start", "3,0", "--goal", "0,0"]);
        common::assert_error(&o, &["goal (0, 0)", "unknown cell", "--allow-unknown"]);
        let o = planlab(&[
            "plan",
            &yaml,
            "--start",
            "0,0",
            "--goal",
            "3,0",
            "--allow-unknown",
        ]);
        assert!(
            o.status.success(),
            "{mode}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
}

#[test]
fn batch_of_an_apf_scenario_says_it_has_no_variants() {
    // Before: APF "variant 0: no valid start/goal/mover placement … at
    // (0.000, 0.000) m: a wall". (An arm scenario has variants: arm_cli.rs.)
    let s = asset("scenarios/T-fig4-6.json");
    let o = planlab(&["batch", &s, "--variants", "2"]);
    common::assert_error(
        &o,
        &["T-fig4-6.json", "APF scenarios have no batch variants"],
    );
}

#[test]
fn map_frames_and_mover_coordinates_beyond_1e6_are_refused() {
    // Before: an origin of 1e300 said "the goal (1000…000.000, 8.050) m is
    // inside a wall" (300 digits); a resolution of 1e300 or a mover at
    // 1e300 m ran.
    let demo = asset("scenarios/dwa-demo.json");
    for (edit, needles) in [
        (
            "map.origin.x=1e300",
            &["invalid origin (1e300, 0, 0)", "1e6"][..],
        ),
        ("map.resolution=1e300", &["invalid resolution 1e300", "1e6"]),
        (
            "movers.0.motion.a=[1e300, 2]",
            &["mover 1 a = (1e300, 2)", "1e6"],
        ),
    ] {
        let o = planlab(&["run", &demo, "--set", edit]);
        common::assert_error(&o, needles);
        let e = String::from_utf8_lossy(&o.stderr).into_owned();
        assert!(!e.contains("wall") && e.len() < 300, "{edit}: {e}");
    }
    // A ROS YAML's resolution, through plan.
    let dir = scratch("huge-resolution");
    std::fs::write(dir.join("m.pgm"), b"P5\n2 1\n255\n\xfe\xfe").unwrap();
    std::fs::write(
        dir.join("m.yaml"),
        "image: m.pgm\nresolution: 1e300\norigin: [0, 0, 0]\n",
    )
    .unwrap();
    let yaml = dir.join("m.yaml").display().to_string();
    let o = planlab(&["plan", &yaml, "--start", "0,0", "--goal", "1,0"]);
    common::assert_error(&o, &["`resolution` is 1e300", "at most 1e6"]);
}

#[test]
fn scenario_names_are_printed_with_control_characters_escaped() {
    // Before: the text table printed the name raw, so an escape sequence
    // in a file (here: clear screen, bell) reached the terminal.
    let dir = scratch("escape-name");
    let s = scenario_copy(&dir, "pursuit-demo.json", "s.json");
    let mut tree: Value = serde_json::from_str(&std::fs::read_to_string(&s).unwrap()).unwrap();
    tree["name"] = Value::from("evil\u{1b}[2J\u{7}\u{9b}name");
    std::fs::write(&s, tree.to_string()).unwrap();
    let sp = s.to_str().unwrap();
    for args in [&["run", sp][..], &["batch", sp, "--variants", "1"]] {
        let o = planlab(args);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let out = String::from_utf8_lossy(&o.stdout).into_owned();
        assert!(
            !out.chars().any(|c| c.is_control() && c != '\n'),
            "{args:?}: {out:?}"
        );
        assert!(
            out.contains(r"evil\u{1b}[2J\u{7}\u{9b}name"),
            "{args:?}: {out}"
        );
    }
}

#[test]
fn a_set_path_deeper_than_the_limit_is_refused_in_one_line() {
    // Before: 0.8 GB and a "recursion limit exceeded" at a line of a text
    // the user never saw.
    let demo = asset("scenarios/dwa-demo.json");
    let deep = format!("{}=1", vec!["a"; 20_000].join("."));
    let e = error_line(&planlab(&["run", &demo, "--set", &deep]), 1);
    assert!(
        e.contains("the path has 20000 names; at most 64 are allowed"),
        "{e}"
    );
    assert!(e.len() < 300, "{e}");
}
