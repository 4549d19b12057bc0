//! `planlab plan --algo hybrid-astar` and `planlab curve`: results and
//! one-line errors.

use std::process::Command;

const REPO: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");

fn planlab(args: &[&str]) -> (bool, String, String) {
    let o = Command::new(env!("CARGO_BIN_EXE_planlab"))
        .args(args)
        .output()
        .expect("run planlab");
    (
        o.status.success(),
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

#[test]
fn curve_prints_the_hand_computed_lsl_and_a_reverse() {
    let (ok, out, err) = planlab(&[
        "curve", "dubins", "--from", "0,0,0", "--to", "0,4,180", "--radius", "1",
    ]);
    assert!(ok, "{err}");
    assert_eq!(out.trim(), "dubins: length 5.141593 m, word LSL");
    let (ok, out, _) = planlab(&[
        "curve",
        "reeds-shepp",
        "--from",
        "0,0,0",
        "--to",
        "-0.5,0,0",
        "--radius",
        "1",
    ]);
    assert!(ok);
    assert_eq!(out.trim(), "reeds-shepp: length 0.500000 m, word S-");
    let (ok, _, err) = planlab(&[
        "curve", "dubins", "--from", "0,0,0", "--to", "1,1,0", "--radius", "NaN",
    ]);
    assert!(
        !ok && err.trim().lines().count() == 1 && err.contains("turning radius"),
        "{err}"
    );
}

#[test]
fn hybrid_astar_plans_on_the_turtlebot_map_and_refuses_bad_input_in_one_line() {
    let map = format!("{REPO}/assets/maps/turtlebot3.yaml");
    let base = [
        "plan",
        &map,
        "--algo",
        "hybrid-astar",
        "--start",
        "-2,-0.5,0",
        "--goal",
        "2,0.5,90",
    ];
    let run = |extra: &[&str]| {
        let mut a: Vec<&str> = base.to_vec();
        a.extend_from_slice(extra);
        planlab(&a)
    };
    let (ok, out, err) = run(&["--turning-radius", "0.3", "--radius", "0.1", "--json"]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(out.trim()).unwrap();
    assert_eq!(v["analytic"], true);
    let poses = v["poses"].as_array().unwrap();
    let last = poses.last().unwrap();
    assert!((last[0].as_f64().unwrap() - 2.0).abs() < 1e-6);
    assert!((last[2].as_f64().unwrap() - std::f64::consts::FRAC_PI_2).abs() < 1e-6);
    for (extra, needle) in [
        (vec!["--turning-radius", "-1"], "turning radius"),
        (vec![], "--turning-radius"),
        (
            vec!["--turning-radius", "0.3", "--radius", "nan"],
            "footprint radius",
        ),
    ] {
        let (ok, _, err) = run(&extra);
        assert!(
            !ok && err.trim().lines().count() == 1 && err.contains(needle),
            "{extra:?}: {err}"
        );
    }
}

#[test]
fn run_with_a_hybrid_astar_global_planner_reaches_the_goal_on_the_path_plan_gives() {
    let scenario = format!("{REPO}/assets/scenarios/T-fig3-2.json");
    let run = |extra: &[&str]| {
        let mut a = vec!["run", &scenario, "--planner", "dwa", "--json"];
        a.extend_from_slice(extra);
        planlab(&a)
    };
    let (ok, out, err) = run(&[
        "--set",
        "global_planner.algorithm=hybrid-astar",
        "--set",
        "global_planner.turning_radius_m=1",
    ]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(out.trim()).unwrap();
    assert_eq!(v["outcome"], "reached", "{out}");
    assert_eq!(v["collision"], serde_json::Value::Null);
    let g = &v["global_path"];
    assert_eq!(g["algorithm"], "hybrid-astar");
    assert_eq!(g["replans"], 0);
    // The same query through `planlab plan`: T-fig3-2's start (1.5, 4) and
    // goal (10.5, 4) m, heading 0 (the start's, and start → goal), the
    // robot's 0.25 m radius + the 0.1 m default margin.
    let (ok, plan, err) = planlab(&[
        "plan",
        &scenario,
        "--algo",
        "hybrid-astar",
        "--start",
        "1.5,4,0",
        "--goal",
        "10.5,4,0",
        "--turning-radius",
        "1",
        "--radius",
        "0.35",
        "--json",
    ]);
    assert!(ok, "{err}");
    let p: serde_json::Value = serde_json::from_str(plan.trim()).unwrap();
    assert_eq!(g["length_m"], p["length_m"]);
    assert!(g["length_m"].as_f64().unwrap() > 9.0);
    // Without the section the report has no global path.
    let (ok, out, _) = run(&[]);
    assert!(ok);
    assert!(!out.contains("global_path"), "{out}");
    // A missing turning radius: one line naming the field.
    let (ok, _, err) = run(&["--set", "global_planner.algorithm=hybrid-astar"]);
    assert!(!ok);
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    assert!(err.contains("turning_radius_m"), "{err}");
    let (ok, _, err) = run(&[
        "--set",
        "global_planner.algorithm=hybrid-astar",
        "--set",
        "global_planner.turning_radius_m=-2",
    ]);
    assert!(!ok);
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    assert!(
        err.contains("global_planner.turning_radius_m = -2"),
        "{err}"
    );
}

#[test]
fn hybrid_astar_plans_a_rectangular_footprint_and_refuses_bad_ones_in_one_line() {
    let map = format!("{REPO}/assets/maps/turtlebot3.yaml");
    let run = |extra: &[&str]| {
        let mut a = vec![
            "plan",
            &map,
            "--algo",
            "hybrid-astar",
            "--start",
            "-2,-0.5,0",
            "--goal",
            "2,0.5,90",
            "--turning-radius",
            "0.3",
        ];
        a.extend_from_slice(extra);
        planlab(&a)
    };
    let (ok, out, err) = run(&["--footprint", "0.3x0.2"]);
    assert!(ok, "{err}");
    assert!(out.contains("footprint 0.3 × 0.2 m rectangle"), "{out}");
    let (ok, out, err) = run(&["--footprint", "0.3x0.2", "--json"]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(out.trim()).unwrap();
    assert_eq!(v["analytic"], true);
    for (extra, needle) in [
        (vec!["--footprint", "0.3by0.2"], "LENGTHxWIDTH"),
        (vec!["--footprint", "nanx0.2"], "footprint rectangle"),
        (vec!["--footprint", "0.3x-1"], "footprint rectangle"),
        (
            vec!["--footprint", "0.3x0.2", "--radius", "0.1"],
            "give one",
        ),
    ] {
        let (ok, _, err) = run(&extra);
        assert!(!ok, "{extra:?}");
        assert_eq!(err.trim().lines().count(), 1, "{err}");
        assert!(err.contains(needle), "{extra:?}: {err}");
    }
    let (ok, _, err) = planlab(&["plan", &map, "--footprint", "0.3x0.2"]);
    assert!(!ok);
    assert!(err.contains("belong to --algo hybrid-astar"), "{err}");
}
