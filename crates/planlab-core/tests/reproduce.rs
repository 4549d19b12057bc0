//! Every registered experiment of the papers runs on its presets and
//! reports each clause of its relation; each of those experiments is one
//! of the papers' figures and tables listed below. Whether a relation holds is a
//! result (see `planlab reproduce --variants`), not a test.

use planlab_core::reproduce;

/// The ids `planlab reproduce` must know once every paper's file is filled.
const EXPECTED_IDS: [&str; 20] = [
    "T-fig3-2",
    "T-fig3-11",
    "T-fig3-13a",
    "T-fig3-13b",
    "T-tab3-2",
    "S-fig6",
    "S-tab1",
    "S-fig12",
    "C-tab3",
    "C-tab5",
    "L-sim1",
    "L-sim2",
    "L-sim3",
    "L-sim4",
    "L-sim5",
    "L-sim6",
    "L-sim7",
    "L-sim8",
    "L-sim9",
    "L-tab2",
];

#[test]
fn every_experiment_runs_and_reports_each_clause() {
    let all = reproduce::all();
    for exp in &all {
        assert!(
            EXPECTED_IDS.contains(&exp.id),
            "{} is not one of the expected ids",
            exp.id
        );
        let r = reproduce::run(exp).unwrap_or_else(|e| panic!("{}: {e}", exp.id));
        assert_eq!(r.clauses.len(), exp.clauses.len(), "{}", exp.id);
        assert_eq!(r.holds, r.clauses.iter().all(|(_, h)| *h), "{}", exp.id);
        assert_eq!(r.runs.len(), exp.runs.len(), "{}", exp.id);
        assert!(r.trace_hashes.values().all(|h| h.len() == 16), "{}", exp.id);
    }
    assert_eq!(reproduce::ids().len(), 27);
}
