//! The planner catalogue explains every planner to a beginner: beside the
//! paper it follows, a paragraph in plain words that says what to look at.

#[test]
fn every_planner_has_plain_words_beside_its_paper() {
    for p in planlab_core::planners::list() {
        assert!(!p.paper.is_empty(), "{}", p.name);
        // A paragraph: what it does, when it fails, what to watch.
        assert!(p.plain.len() > 150, "{}: {:?}", p.name, p.plain);
        assert!(
            p.plain.contains("Watch")
                || p.plain.contains("watch")
                || p.plain.contains("Use it")
                || p.plain.contains("Compare")
                || p.plain.contains("Run it")
                || p.plain.contains("Turn on"),
            "{}: nothing to look at",
            p.name
        );
    }
}

/// Every field a parameter panel or `planlab planners` shows has a name in
/// plain words, not only its config name (`alpha`, `v_res`), and no two
/// fields of one planner share it.
#[test]
fn every_planner_field_has_a_plain_label_unique_within_its_planner() {
    let mut problems = Vec::new();
    for p in planlab_core::planners::list() {
        let mut seen = std::collections::HashMap::new();
        for f in &p.fields {
            let leaf = f.name.rsplit('.').next().unwrap_or(&f.name);
            if f.label.trim().is_empty() {
                problems.push(format!("{}: {} has no label", p.name, f.name));
            } else if f.label == leaf {
                problems.push(format!("{}: {}'s label is its config name", p.name, f.name));
            }
            if let Some(other) = seen.insert(f.label.clone(), f.name.clone()) {
                problems.push(format!(
                    "{}: {other} and {} are both labelled {:?}",
                    p.name, f.name, f.label
                ));
            }
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

#[test]
fn the_dwa_weights_are_named_for_what_they_weigh_with_their_symbol() {
    let dwa = planlab_core::planners::list()
        .into_iter()
        .find(|p| p.name == "dwa")
        .expect("dwa");
    let label = |n: &str| {
        dwa.fields
            .iter()
            .find(|f| f.name == n)
            .map(|f| f.label.clone())
            .unwrap_or_default()
    };
    assert_eq!(label("alpha"), "heading weight α");
    assert_eq!(label("beta"), "clearance weight β");
    assert_eq!(label("gamma"), "speed weight γ");
    assert_eq!(label("v_res"), "speed resolution");
}
