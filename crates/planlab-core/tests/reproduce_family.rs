//! Families of variants (`planlab reproduce --variants`): every variant of
//! every family can start, a variant's written-out scenario replays to the
//! trace hash its family run reported, and the summary counts what the
//! variants say. CI runs small families of a few ids; the whole sweep is
//! the README's command.

use planlab_core::apf::ApfMetrics;
use planlab_core::metrics::EpisodeMetrics;
use planlab_core::reproduce::{self, Experiment, RunMetrics};

/// Every variant 0…n−1 of `exp` builds (every run can start) and is the
/// same scene when drawn twice.
fn startable<M: RunMetrics>(exp: &Experiment<M>, n: u32) {
    for k in 0..n {
        let a = exp
            .variant(7, k, &[])
            .unwrap_or_else(|e| panic!("{} variant {k}: {e}", exp.id));
        let b = exp.variant(7, k, &[]).unwrap();
        assert_eq!(a, b, "{} variant {k} is not deterministic", exp.id);
        assert_eq!(a.trees.len(), exp.runs.len());
        for (_, tree) in &a.trees {
            M::check(tree).unwrap_or_else(|e| panic!("{} variant {k}: {e}", exp.id));
        }
    }
}

#[test]
fn every_variant_of_every_family_can_start() {
    for e in reproduce::all() {
        startable(&e, 12);
    }
    for e in reproduce::path_experiments() {
        startable(&e, 12);
    }
}

/// Runs variants 0…n−1 of `id`, replays each run from its tree as a file
/// would be read (JSON text → scenario) and compares trace hashes; returns
/// the summary.
fn replayed<M: RunMetrics>(exp: &Experiment<M>, n: u32) -> reproduce::FamilyResult {
    let results: Vec<_> = (0..n)
        .map(|k| reproduce::run_variant(exp, 3, k, &[]).unwrap())
        .collect();
    for r in &results {
        let scene = exp.variant(3, r.k, &[]).unwrap();
        for (name, tree) in &scene.trees {
            let text = serde_json::to_string_pretty(tree).unwrap();
            let back: serde_json::Value = serde_json::from_str(&text).unwrap();
            let (_, h) = M::run_tree(&back).unwrap();
            assert_eq!(
                format!("{h:016x}"),
                r.trace_hashes[*name],
                "{} variant {} run {name}",
                exp.id,
                r.k
            );
        }
    }
    let f = reproduce::summarise(exp, 3, None, &results);
    assert_eq!(f.variants, n);
    assert_eq!(f.rows.len(), n as usize);
    for (i, c) in f.clauses.iter().enumerate() {
        let k = results.iter().filter(|r| r.clauses[i]).count() as u32;
        assert_eq!(
            (c.holds.k, c.holds.n),
            (k, n),
            "{} {}",
            exp.id,
            c.clause.name
        );
    }
    let joint = results
        .iter()
        .filter(|r| r.clauses.iter().all(|&b| b))
        .count() as u32;
    assert_eq!(f.joint.k, joint);
    for (name, run) in &f.runs {
        let ok = results.iter().filter(|r| r.runs[name].succeeded()).count() as u32;
        assert_eq!(run.success.k, ok, "{} {name}", exp.id);
    }
    f
}

#[test]
fn small_families_replay_and_summarise() {
    for id in ["T-fig3-13b", "S-tab1", "L-sim2"] {
        let exp = reproduce::find(id).unwrap();
        let f = replayed::<EpisodeMetrics>(&exp, 4);
        // Variant 0 is the preset: its hashes are the preset run's.
        let r = reproduce::run(&exp).unwrap();
        assert_eq!(f.rows[0].trace_hashes, r.trace_hashes, "{id}");
    }
    for id in ["T-fig4-11", "T-tab5-3"] {
        let exp = reproduce::find_path(id).unwrap();
        replayed::<ApfMetrics>(&exp, 4);
    }
}

#[test]
fn variants_differ_from_the_preset_and_stay_paired() {
    let exp = reproduce::find("T-tab3-2").unwrap();
    let v0 = exp.variant(0, 0, &[]).unwrap();
    let v1 = exp.variant(0, 1, &[]).unwrap();
    assert_ne!(v0.trees[0].1["start"], v1.trees[0].1["start"]);
    assert_ne!(v0.trees[0].1["seed"], v1.trees[0].1["seed"]);
    // Both runs of a variant drive the same scene: only the planner differs.
    let strip = |t: &serde_json::Value| {
        let mut t = t.clone();
        t.as_object_mut().unwrap().remove("local_planner");
        t
    };
    assert_eq!(strip(&v1.trees[0].1), strip(&v1.trees[1].1));
    assert!(!v1.draws.is_empty());
}

#[test]
fn a_sweep_reaches_only_the_runs_that_have_the_field() {
    let exp = reproduce::find("T-fig3-11").unwrap();
    let extra = vec![(
        "local_planner.config.decelerate.alpha".to_string(),
        "0.5".to_string(),
    )];
    let s = exp.variant(0, 1, &extra).unwrap();
    assert_eq!(s.swept, vec!["fusion-53", "improved"]);
    let bad = vec![("local_planner.config.no_such".to_string(), "1".to_string())];
    let err = exp.variant(0, 1, &bad).unwrap_err().to_string();
    assert!(err.contains("no run accepts"), "{err}");
}
