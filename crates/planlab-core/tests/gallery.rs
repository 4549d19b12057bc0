//! The page's gallery (`assets/gallery.json`) against the reproduce
//! registry: every `planlab reproduce` id has exactly one entry, its paper,
//! scene, relation and runs are the registry's (so the gallery cannot drift
//! from the CLI), every run's preset exists and is the scenario the registry
//! runs, and each entry opens on the page that can run its scenario.

use std::collections::BTreeSet;
use std::path::PathBuf;

use planlab_core::reproduce::{self, RunSpec};
use serde::Deserialize;

#[derive(Debug, Deserialize)]
struct Gallery {
    version: u32,
    experiments: Vec<Entry>,
}

#[derive(Debug, Deserialize)]
struct Entry {
    id: String,
    title: String,
    page: String,
    paper: String,
    section: String,
    what: String,
    relation: String,
    explanation: String,
    runs: Vec<Run>,
}

#[derive(Debug, Deserialize, PartialEq)]
struct Run {
    name: String,
    preset: String,
    planner: Option<String>,
    set: Vec<(String, String)>,
}

fn assets() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../assets")
}

fn gallery() -> Gallery {
    let text = std::fs::read_to_string(assets().join("gallery.json")).expect("assets/gallery.json");
    serde_json::from_str(&text).expect("assets/gallery.json parses")
}

/// The registry's side of one experiment, in the gallery's terms.
struct Registered {
    id: &'static str,
    paper: &'static str,
    what: &'static str,
    relation: &'static str,
    runs: Vec<RunSpec>,
    /// `robot` for episode experiments, `apf` / `arm` for path experiments
    /// by their scenario's section.
    page: &'static str,
}

fn registry() -> Vec<Registered> {
    let mut v: Vec<Registered> = reproduce::all()
        .into_iter()
        .map(|e| Registered {
            id: e.id,
            paper: e.paper,
            what: e.what,
            relation: e.relation,
            runs: e.runs,
            page: "robot",
        })
        .collect();
    for e in reproduce::path_experiments() {
        let tree: serde_json::Value = serde_json::from_str(e.runs[0].scenario_json).unwrap();
        let page = if tree.get("arm").is_some() {
            "arm"
        } else {
            "apf"
        };
        v.push(Registered {
            id: e.id,
            paper: e.paper,
            what: e.what,
            relation: e.relation,
            runs: e.runs,
            page,
        });
    }
    v
}

#[test]
fn every_reproduce_id_has_one_gallery_entry_and_no_more() {
    let g = gallery();
    assert_eq!(g.version, 1);
    let ids: Vec<&str> = g.experiments.iter().map(|e| e.id.as_str()).collect();
    let unique: BTreeSet<&str> = ids.iter().copied().collect();
    assert_eq!(unique.len(), ids.len(), "an id appears twice: {ids:?}");
    let want: BTreeSet<&str> = registry().iter().map(|r| r.id).collect();
    let missing: Vec<_> = want.difference(&unique).collect();
    let extra: Vec<_> = unique.difference(&want).collect();
    assert!(
        missing.is_empty(),
        "gallery.json lacks reproduce ids {missing:?}"
    );
    assert!(
        extra.is_empty(),
        "gallery.json has ids reproduce does not know: {extra:?}"
    );
    // The registry's order (the CLI's), so the gallery reads like `planlab reproduce`.
    let order: Vec<&str> = registry().iter().map(|r| r.id).collect();
    assert_eq!(ids, order);
}

#[test]
fn entries_carry_the_registry_text_and_runs() {
    let g = gallery();
    let scenarios = assets().join("scenarios");
    for r in registry() {
        let e = g.experiments.iter().find(|e| e.id == r.id).unwrap();
        assert_eq!(e.paper, r.paper, "{}: paper", r.id);
        assert_eq!(e.what, r.what, "{}: what", r.id);
        assert_eq!(e.relation, r.relation, "{}: relation", r.id);
        assert_eq!(e.page, r.page, "{}: page", r.id);
        for (field, text) in [
            ("title", &e.title),
            ("section", &e.section),
            ("explanation", &e.explanation),
        ] {
            assert!(!text.trim().is_empty(), "{}: empty {field}", r.id);
        }
        // One paragraph that names its paper.
        let tag = &r.paper[..3];
        assert!(
            e.section.starts_with(tag),
            "{}: section `{}` should start with {tag}",
            r.id,
            e.section
        );
        assert!(!e.explanation.contains('\n'), "{}: one paragraph", r.id);
        assert!(
            e.explanation.len() >= 200,
            "{}: explanation too short",
            r.id
        );
        assert_eq!(e.runs.len(), r.runs.len(), "{}: runs", r.id);
        for (run, spec) in e.runs.iter().zip(&r.runs) {
            let want = Run {
                name: spec.name.into(),
                preset: run.preset.clone(),
                planner: spec.planner.map(Into::into),
                set: spec
                    .set
                    .iter()
                    .map(|&(p, v)| (p.into(), v.into()))
                    .collect(),
            };
            assert_eq!(*run, want, "{}: run {}", r.id, spec.name);
            let path = scenarios.join(&run.preset);
            let text = std::fs::read_to_string(&path)
                .unwrap_or_else(|e| panic!("{}: preset {}: {e}", r.id, path.display()));
            assert!(
                text == spec.scenario_json,
                "{}: run {} runs another scenario than {}",
                r.id,
                spec.name,
                run.preset
            );
        }
    }
}

#[test]
fn robot_entries_open_presets_the_robot_page_lists() {
    // The robot page lists the scenarios with a `local_planner` section
    // (web/vite.config.ts); the APF and arm pages take `apf` / `arm` ones.
    for e in gallery().experiments {
        for run in &e.runs {
            let text =
                std::fs::read_to_string(assets().join("scenarios").join(&run.preset)).unwrap();
            let tree: serde_json::Value = serde_json::from_str(&text).unwrap();
            let section = match e.page.as_str() {
                "robot" => "local_planner",
                "apf" => "apf",
                "arm" => "arm",
                other => panic!("{}: unknown page {other}", e.id),
            };
            assert!(
                tree.get(section).is_some(),
                "{}: {} has no `{section}` section for the {} page",
                e.id,
                run.preset,
                e.page
            );
        }
    }
}

/// One line of `assets/reproduce-results.jsonl` (a `FamilyResult`), the
/// fields the gallery cards show.
#[derive(Debug, Deserialize)]
struct ResultLine {
    id: String,
    relation: String,
    verdict: reproduce::Verdict,
    variants: u32,
    seed: u64,
    runs: std::collections::BTreeMap<String, serde_json::Value>,
    clauses: Vec<serde_json::Value>,
    family: serde_json::Value,
    deviations: serde_json::Value,
}

/// The gallery's family results (`scripts/reproduce-results.sh`) are the
/// registry's: one line per id in `planlab reproduce` order, each with the
/// registry's relation, family, deviations, clauses and runs, so results
/// of an older registry fail here instead of showing on the cards.
#[test]
fn reproduce_results_match_the_registry() {
    let text = std::fs::read_to_string(assets().join("reproduce-results.jsonl"))
        .expect("assets/reproduce-results.jsonl (scripts/reproduce-results.sh writes it)");
    let lines: Vec<ResultLine> = text
        .lines()
        .filter(|l| !l.trim().is_empty())
        .enumerate()
        .map(|(i, l)| {
            serde_json::from_str(l)
                .unwrap_or_else(|e| panic!("reproduce-results.jsonl line {}: {e}", i + 1))
        })
        .collect();
    let ids: Vec<&str> = lines.iter().map(|l| l.id.as_str()).collect();
    assert_eq!(
        ids,
        reproduce::ids(),
        "reproduce-results.jsonl ids (rerun scripts/reproduce-results.sh)"
    );
    for l in &lines {
        let info = reproduce::find(&l.id)
            .map(|e| e.info())
            .or_else(|| reproduce::find_path(&l.id).map(|e| e.info()))
            .unwrap();
        let stale = |what: &str| {
            format!(
                "{}: {what} differs from the registry's (rerun scripts/reproduce-results.sh)",
                l.id
            )
        };
        assert_eq!(l.relation, info.relation, "{}", stale("relation"));
        assert_eq!(
            l.family,
            serde_json::to_value(&info.family).unwrap(),
            "{}",
            stale("family")
        );
        assert_eq!(
            l.deviations,
            serde_json::to_value(&info.deviations).unwrap(),
            "{}",
            stale("deviations")
        );
        let clauses: Vec<&str> = l
            .clauses
            .iter()
            .map(|c| c["name"].as_str().unwrap_or(""))
            .collect();
        let want: Vec<&str> = info.clauses.iter().map(|c| c.name.as_str()).collect();
        assert_eq!(clauses, want, "{}", stale("clauses"));
        let runs: BTreeSet<&str> = l.runs.keys().map(String::as_str).collect();
        let want: BTreeSet<&str> = info.runs.iter().map(|r| r.name.as_str()).collect();
        assert_eq!(runs, want, "{}", stale("runs"));
        // The verdict parsed as one of the three words.
        assert!(
            l.variants >= 1,
            "{}: {:?} on {} variants, seed {}",
            l.id,
            l.verdict,
            l.variants,
            l.seed
        );
    }
}
