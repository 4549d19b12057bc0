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
