//! Every repository file the sources, docs and tests cite exists.
//!
//! The test reads the repository's `*.rs`, `*.ts`, `*.mjs`, `*.md`, `*.py`,
//! `*.sh` and `*.toml` files (build outputs left out) and picks from each
//! line the paths it cites: in prose (Markdown, comments) any `a/b.ext` with
//! a known file ending, a `dir/sub/` folder, and a bare `NAME.md`; in code
//! only a cited source or doc file (`a/b.rs`, `docs/x.md`), since a code
//! string naming a map, page or JSON file is data its own test reads (and
//! test fixtures name files that are made on the spot or are missing on
//! purpose). URLs and absolute paths are not citations. A cited path is
//! found when a file or folder of the repository ends with it, so a path
//! relative to a crate (`src/local/mod.rs`), to the core's sources
//! (`local/dwa.rs`) or to the data folder (`movingai/dao/arena.map`) counts;
//! `../` steps are dropped first, so a citation of something outside the
//! repository (`../shared/SPEC.md`) is found only if the repository has it.
//! Every citation that is not found is reported with its file and line.

use std::collections::BTreeSet;
use std::path::Path;

/// The file endings that are read for citations.
const SCANNED: &[&str] = &["rs", "ts", "mjs", "md", "py", "sh", "toml"];

/// Endings of a cited source or doc file: checked in code too.
const SOURCE: &[&str] = &["rs", "ts", "mjs", "md", "py", "sh", "toml"];

/// Endings of cited data, pages and images: checked in prose only.
const DATA: &[&str] = &[
    "html", "css", "js", "json", "jsonl", "csv", "txt", "map", "scen", "yaml", "yml", "pgm", "png",
    "svg", "wasm",
];

/// Build outputs and caches (the `.gitignore` files name them): a path in
/// them is cited legitimately before it is built, and they are not read.
const GENERATED: &[&str] = &[
    "target",
    "node_modules",
    "web/dist",
    "web/pkg",
    "web/pkg-grid",
    "web/pkg-arm",
    "web/pkg-reproduce",
    "crates/planlab-wasm/pkg",
    ".venv",
    "__pycache__",
    ".pytest_cache",
    "fuzz/corpus",
    "fuzz/artifacts",
    "fuzz/coverage",
    "tests/e2e/screenshots",
    ".git",
];

/// What the repository holds: every file and folder, relative to its root
/// with `/` separators.
struct Repo {
    paths: BTreeSet<String>,
}

impl Repo {
    fn new<'a>(files: impl IntoIterator<Item = &'a str>) -> Repo {
        let mut paths = BTreeSet::new();
        for f in files {
            let mut p = f;
            paths.insert(p.to_string());
            while let Some((dir, _)) = p.rsplit_once('/') {
                paths.insert(dir.to_string());
                p = dir;
            }
        }
        Repo { paths }
    }

    /// Whether some file or folder is `cited` or ends with `/cited`.
    fn has(&self, cited: &str) -> bool {
        self.paths
            .iter()
            .any(|p| p == cited || p.strip_suffix(cited).is_some_and(|h| h.ends_with('/')))
    }
}

/// Whether `path` (relative, `/` separators) is or lies in a build output.
fn generated(path: &str) -> bool {
    let path = format!("/{path}/");
    GENERATED
        .iter()
        .any(|g| path.contains(&format!("/{g}/")) || path.contains(&format!("/{g}-")))
}

/// The ending of a path's last segment, if it has one.
fn ending(path: &str) -> Option<&str> {
    let name = path.rsplit('/').next()?;
    let (stem, ext) = name.rsplit_once('.')?;
    (!stem.is_empty()).then_some(ext)
}

/// `line` split into its prose (a comment, or all of a Markdown line) and
/// its code, for a file with ending `ext`.
fn prose_and_code<'a>(ext: &str, line: &'a str) -> (&'a str, &'a str) {
    let marker = match ext {
        "md" => return (line, ""),
        "py" | "sh" | "toml" => "#",
        _ => "//",
    };
    let trimmed = line.trim_start();
    if trimmed.starts_with(marker) || (marker == "//" && trimmed.starts_with('*')) {
        return (line, "");
    }
    // A trailing comment; a URL's `://` has no space before it.
    match line.find(&format!(" {marker}")) {
        Some(i) => (&line[i..], &line[..i]),
        None => ("", line),
    }
}

/// The runs of path characters in `text` that are not part of a URL, an
/// absolute path, a `$VAR/…`, `~/…` or `user@host`: (byte offset, run).
fn runs(text: &str) -> Vec<&str> {
    let is_path = |c: char| c.is_ascii_alphanumeric() || "_.-/*".contains(c);
    let mut out = Vec::new();
    let mut start = None;
    for (i, c) in text.char_indices().chain([(text.len(), ' ')]) {
        match (start, is_path(c)) {
            (None, true) => start = Some(i),
            (Some(s), false) => {
                start = None;
                let before = text[..s].chars().next_back();
                let run = &text[s..i];
                if !run.starts_with('/') && !before.is_some_and(|b| ":@~$%{".contains(b)) {
                    out.push(run);
                }
            }
            _ => {}
        }
    }
    out
}

/// The paths `line` of a file with ending `ext` cites, each as written
/// (less a sentence's full stop).
fn citations(ext: &str, line: &str) -> Vec<String> {
    let (prose, code) = prose_and_code(ext, line);
    let mut out = Vec::new();
    for (text, in_prose) in [(prose, true), (code, false)] {
        for run in runs(text) {
            let run = run.trim_end_matches(['.', '-']);
            if run.contains('*')
                || run
                    .split('/')
                    .all(|s| s.is_empty() || s.chars().all(|c| c == '.'))
            {
                continue; // a glob, or `.`, `..`, `../..`
            }
            let cited = match ending(run) {
                _ if run.ends_with('/') => in_prose && run.trim_matches('/').contains('/'),
                Some(e) if run.contains('/') => {
                    SOURCE.contains(&e) || (in_prose && DATA.contains(&e))
                }
                // A bare file name: a doc by its upper-case name
                // (`ARCHITECTURE.md`), or in prose a source file.
                Some(e) => {
                    let stem = &run[..run.len() - e.len() - 1];
                    (e == "md" && stem.chars().all(|c| c.is_ascii_uppercase() || c == '_'))
                        || (in_prose && SOURCE.contains(&e))
                }
                // A folder outside the file's own, by `../name`.
                None => run.starts_with("../"),
            };
            if cited {
                out.push(run.to_string());
            }
        }
    }
    out
}

/// Whether the repository holds what `cited` names.
fn found(repo: &Repo, cited: &str) -> bool {
    let rel: Vec<&str> = cited
        .split('/')
        .filter(|s| !s.is_empty() && *s != "." && *s != "..")
        .collect();
    let rel = rel.join("/");
    if rel.is_empty() || generated(&rel) {
        return true;
    }
    // A folder named by `dir/sub/` whose first segment the repository does
    // not have is another project's (a data file's upstream source).
    if cited.ends_with('/') && !cited.starts_with('.') {
        let first = rel.split('/').next().unwrap_or_default();
        if !repo.has(first) {
            return true;
        }
    }
    if repo.has(&rel) {
        return true;
    }
    // An import names a module without its ending: `../shell/dom`.
    ending(&rel).is_none()
        && repo.paths.iter().any(|p| {
            p.rsplit_once('.')
                .is_some_and(|(stem, _)| stem == rel || stem.ends_with(&format!("/{rel}")))
        })
}

/// The repository's files, relative to `root`, build outputs left out.
fn files(root: &Path) -> Vec<String> {
    let mut out = Vec::new();
    let mut todo = vec![root.to_path_buf()];
    while let Some(dir) = todo.pop() {
        for entry in std::fs::read_dir(&dir).expect("read a repository folder") {
            let path = entry.expect("a folder entry").path();
            let rel = path
                .strip_prefix(root)
                .expect("below the root")
                .to_string_lossy()
                .replace('\\', "/");
            if generated(&rel) {
                continue;
            }
            if path.is_dir() {
                todo.push(path);
            } else {
                out.push(rel);
            }
        }
    }
    out.sort();
    out
}

#[test]
fn every_cited_repository_file_exists() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let files = files(&root);
    let repo = Repo::new(files.iter().map(String::as_str));
    let this_file = file!().replace('\\', "/");
    let mut problems = Vec::new();
    let mut scanned = 0;
    for file in &files {
        let Some(ext) = ending(file).filter(|e| SCANNED.contains(e)) else {
            continue;
        };
        if *file == this_file {
            continue; // its matcher test plants bad citations
        }
        let Ok(text) = std::fs::read_to_string(root.join(file)) else {
            continue; // not UTF-8: no citations to read
        };
        scanned += 1;
        for (n, line) in text.lines().enumerate() {
            for cited in citations(ext, line) {
                if !found(&repo, &cited) {
                    problems.push(format!(
                        "{file}:{}: cites `{cited}`, which is not in the repository",
                        n + 1
                    ));
                }
            }
        }
    }
    assert!(
        scanned > 100,
        "read only {scanned} files: is the root right?"
    );
    assert!(
        problems.is_empty(),
        "{} citation(s) of files the repository does not have (point to the file \
         that exists, e.g. ARCHITECTURE.md or docs/algorithms.md, or drop them):\n{}",
        problems.len(),
        problems.join("\n")
    );
}

#[test]
fn the_matcher_finds_bad_citations_and_only_those() {
    let repo = Repo::new([
        "ARCHITECTURE.md",
        "docs/algorithms.md",
        "crates/planlab-core/src/local/dwa.rs",
        "crates/planlab-core/tests/layering.rs",
        "tests/data/movingai/dao/arena.map",
        "web/src/shell/dom.ts",
        "web/robot.html",
    ]);
    let bad = |ext: &str, line: &str| -> Vec<String> {
        citations(ext, line)
            .into_iter()
            .filter(|c| !found(&repo, c))
            .collect()
    };
    // Planted bad citations are reported.
    assert_eq!(
        bad("rs", "//! a page only paints (DESIGN.md convention 5)."),
        ["DESIGN.md"]
    );
    assert_eq!(
        bad("md", "The spec is ../shared/SPEC.md; see ../shared"),
        ["../shared/SPEC.md", "../shared"]
    );
    assert_eq!(
        bad(
            "rs",
            r#"    "the catalogue in src/local/registry.rs belongs","#
        ),
        ["src/local/registry.rs"]
    );
    assert_eq!(
        bad("ts", "x(); // drawn as in web/src/robot/old.ts"),
        ["web/src/robot/old.ts"]
    );
    assert_eq!(
        bad(
            "md",
            "Run `cargo test --test issue_14` (tests/issue_14.rs)."
        ),
        ["tests/issue_14.rs"]
    );
    assert_eq!(
        bad("sh", "# the maps in tests/data/gone/"),
        ["tests/data/gone/"]
    );
    // Legitimate text is not.
    for (ext, line) in [
        ("md", "See docs/algorithms.md §dwa and ARCHITECTURE.md."),
        (
            "md",
            "[DWA](docs/algorithms.md#dwa), `local/dwa.rs`, `tests/layering.rs`",
        ),
        (
            "md",
            "From https://example.com/a/DESIGN.md and /usr/share/x/y.md",
        ),
        (
            "rs",
            "//! The map `movingai/dao/arena.map`; run `cargo test`.",
        ),
        (
            "rs",
            r#"    std::fs::write(dir.join("out/trace.json"), b)?; let py = obj.py();"#,
        ),
        ("ts", "import { banner } from '../shell/dom';"),
        ("ts", "// web/pkg/planlab_wasm.js is built by scripts"),
        (
            "md",
            "The ROBOTIS map (`turtlebot3_navigation2/map/`); the page robot.html.",
        ),
        (
            "sh",
            "cd \"$(dirname \"$0\")/..\"; ls ../.. $HOME/x/y.md ~/z/w.md",
        ),
    ] {
        assert_eq!(bad(ext, line), Vec::<String>::new(), "{line}");
    }
    // The matcher does pick legitimate citations (found, not skipped).
    assert_eq!(
        citations("md", "See docs/algorithms.md §dwa and ARCHITECTURE.md."),
        ["docs/algorithms.md", "ARCHITECTURE.md"]
    );
}
