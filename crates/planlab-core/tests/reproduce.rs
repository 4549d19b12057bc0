//! Every registered experiment of the papers (SPEC §7) runs and its
//! relation holds; the ids the issue names are the ones registered.

use planlab_core::reproduce;

/// The ids `planlab reproduce` must know once every paper's file is filled.
const ISSUE_IDS: [&str; 20] = [
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
fn every_registered_relation_holds() {
    let all = reproduce::all();
    for exp in &all {
        assert!(
            ISSUE_IDS.contains(&exp.id),
            "{} is not one of the issue's ids",
            exp.id
        );
        let r = reproduce::run(exp).unwrap_or_else(|e| panic!("{}: {e}", exp.id));
        assert!(
            r.holds,
            "{} does not hold: {}\n{}",
            exp.id,
            exp.relation,
            serde_json::to_string_pretty(&r.runs).unwrap_or_default()
        );
    }
}
