//! \[T\] ch. 4 reproductions (docs/algorithms.md §experiments): every APF relation holds, with the
//! paper's claims checked run by run.

use planlab_core::reproduce::{self, find_path, run_path, PathExperimentResult};
use planlab_core::sim::Outcome;

fn holds(id: &str) -> PathExperimentResult {
    let exp = find_path(id).unwrap_or_else(|| panic!("{id} is not registered"));
    let r = run_path(&exp).unwrap_or_else(|e| panic!("{id}: {e}"));
    // The preset's own clauses: the scene as drawn shows each effect.
    assert!(
        r.holds,
        "{id}: {}\n{}",
        exp.relation,
        serde_json::to_string_pretty(&r.runs).unwrap_or_default()
    );
    r
}

#[test]
fn fig4_6_basic_apf_oscillates_and_sampling_escapes() {
    let r = holds("T-fig4-6");
    let basic = &r.runs["apf"];
    assert_eq!(basic.outcome, Outcome::Stuck);
    // Oscillating back and forth: many points, each a reversal.
    assert!(basic.spikes >= 10, "{basic:?}");
    assert!(r.runs["sampling"].spikes <= 2);
}

#[test]
fn fig4_8_relative_distance_rule_reaches_the_goal_near_the_obstacle() {
    let r = holds("T-fig4-8");
    assert_ne!(r.runs["sampling-no-rule"].outcome, Outcome::Reached);
    assert_eq!(r.runs["sampling+rule"].outcome, Outcome::Reached);
}

#[test]
fn fig4_10_to_4_12_head_on_mover() {
    let r = holds("T-fig4-10");
    assert_ne!(r.runs["apf"].outcome, Outcome::Reached);
    let r = holds("T-fig4-11");
    assert!(r.runs["apf"].path_length_m > r.runs["sampling+prediction"].path_length_m);
    holds("T-fig4-12");
}

#[test]
fn tab4_1_lengths_fall_and_spikes_vanish_with_prediction() {
    let r = holds("T-tab4-1");
    let (a, s, p) = (
        &r.runs["apf"],
        &r.runs["sampling"],
        &r.runs["sampling+prediction"],
    );
    assert!(a.path_length_m > s.path_length_m && s.path_length_m > p.path_length_m);
    assert!(a.path_points >= s.path_points && s.path_points >= p.path_points);
    assert_eq!(p.spikes, 0);
    assert!(p.min_obstacle_distance_m > a.min_obstacle_distance_m);
    // The JSON of `planlab reproduce --json` carries the table's metrics.
    let line = serde_json::to_string(&r).unwrap();
    for k in [
        "outcome",
        "path_length_m",
        "path_points",
        "spikes",
        "min_obstacle_distance_m",
        "time_s",
    ] {
        assert!(line.contains(&format!("\"{k}\"")), "{k} missing: {line}");
    }
}

#[test]
fn the_apf_figures_and_table_are_registered() {
    let ids: Vec<&str> = reproduce::path_experiments().iter().map(|e| e.id).collect();
    for id in [
        "T-fig4-6",
        "T-fig4-8",
        "T-fig4-10",
        "T-fig4-11",
        "T-fig4-12",
        "T-tab4-1",
    ] {
        assert!(ids.contains(&id), "{id} missing from {ids:?}");
    }
}

#[test]
fn fig4_6_minimum_is_a_saddle_one_millimetre_off_the_line_basic_apf_reaches() {
    // The README's reading of T-fig4-6: basic APF is stuck only with start,
    // disc and goal exactly on one line; a disc 1 mm off it is slid round.
    use planlab_core::apf::ApfMetrics;
    use planlab_core::reproduce::RunMetrics;
    let exp = find_path("T-fig4-6").unwrap();
    let basic = exp.runs.iter().find(|r| r.name == "apf").unwrap();
    let preset: serde_json::Value = serde_json::from_str(basic.scenario_json).unwrap();
    for (y, want) in [
        ("0", Outcome::Stuck),
        ("0.001", Outcome::Reached),
        ("0.02", Outcome::Reached),
    ] {
        let extra = [("apf.obstacles.0.centre".to_string(), format!("[0.5,{y}]"))];
        let tree = reproduce::run_tree(basic, &preset, &extra).unwrap();
        let (m, _) = ApfMetrics::run_tree(&tree).unwrap();
        assert_eq!(m.outcome, want, "disc at y = {y}: {m:?}");
        assert!(m.min_obstacle_distance_m > 0.0, "disc at y = {y}: {m:?}");
    }
}
