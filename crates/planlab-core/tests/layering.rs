//! The layering of `planlab-core` (ARCHITECTURE.md at the repository root):
//! a top-level module may use only modules of the layers below its own.
//!
//! The test reads `src/**/*.rs`, blanks comments (doc links may point
//! anywhere) and string and character literals, and finds every path that
//! leaves a module for another top-level one: `crate::x`, each head of
//! `crate::{x, y::z}`, and `super::` chains that climb to the crate root.
//! Test modules count too: a test that needs a higher layer lives in
//! `tests/`. Every use of a module of the same or a higher layer is
//! reported with its file, line and both layers.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// The layers, bottom first: (name, its modules). A module may use the
/// modules of every layer listed before its own; modules sharing a layer
/// stand alone.
const LAYERS: &[(&str, &[&str])] = &[
    ("text, num", &["text", "num"]),
    ("geom, params", &["geom", "params"]),
    ("map", &["map"]),
    ("global, sampling", &["global", "sampling"]),
    ("car", &["car"]),
    ("world", &["world"]),
    ("local", &["local"]),
    ("apf", &["apf"]),
    ("lidar, arm", &["lidar", "arm"]),
    ("planners", &["planners"]),
    ("sim", &["sim"]),
    ("metrics, draw", &["metrics", "draw"]),
    ("scenario", &["scenario"]),
    ("batch", &["batch"]),
    ("recipe", &["recipe"]),
    ("reproduce, bench", &["reproduce", "bench"]),
    ("barn", &["barn"]),
];

/// The layer index of top-level module `m`.
fn layer_of(m: &str) -> Option<usize> {
    LAYERS.iter().position(|(_, mods)| mods.contains(&m))
}

/// Whether a raw string's `r` at `i` starts a literal: not the end of an
/// identifier (`for"` cannot occur, but `br"…"` is a byte raw string).
fn starts_token(c: &[char], i: usize) -> bool {
    let ident = |k: usize| c.get(k).is_some_and(|p| p.is_alphanumeric() || *p == '_');
    match i.checked_sub(1) {
        None => true,
        Some(k) if c[k] == 'b' => k == 0 || !ident(k - 1),
        Some(k) => !ident(k),
    }
}

/// `src` with comments and the contents of string and character literals
/// replaced by spaces; newlines are kept, so lines still count.
fn blank_comments_and_literals(src: &str) -> String {
    let c: Vec<char> = src.chars().collect();
    let mut out = String::with_capacity(src.len());
    let blank = |ch: char| if ch == '\n' { '\n' } else { ' ' };
    let mut i = 0;
    while i < c.len() {
        let at = |k: usize| c.get(i + k).copied().unwrap_or('\0');
        if at(0) == '/' && at(1) == '/' {
            while i < c.len() && c[i] != '\n' {
                out.push(' ');
                i += 1;
            }
        } else if at(0) == '/' && at(1) == '*' {
            // Block comments nest in Rust.
            let mut depth = 0;
            while i < c.len() {
                if c[i] == '/' && c.get(i + 1) == Some(&'*') {
                    depth += 1;
                    out.push_str("  ");
                    i += 2;
                } else if c[i] == '*' && c.get(i + 1) == Some(&'/') {
                    depth -= 1;
                    out.push_str("  ");
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    out.push(blank(c[i]));
                    i += 1;
                }
            }
        } else if at(0) == 'r'
            && (at(1) == '"' || (at(1) == '#' && matches!(at(2), '"' | '#')))
            && starts_token(&c, i)
        {
            // Raw string r#"…"#: ends at a quote followed by as many #.
            let mut hashes = 0;
            let mut j = i + 1;
            while c.get(j) == Some(&'#') {
                hashes += 1;
                j += 1;
            }
            out.extend(std::iter::repeat(' ').take(j + 1 - i));
            i = j + 1;
            while i < c.len() {
                if c[i] == '"' && (1..=hashes).all(|k| c.get(i + k) == Some(&'#')) {
                    out.extend(std::iter::repeat(' ').take(hashes + 1));
                    i += hashes + 1;
                    break;
                }
                out.push(blank(c[i]));
                i += 1;
            }
        } else if at(0) == '"' {
            out.push(' ');
            i += 1;
            while i < c.len() && c[i] != '"' {
                if c[i] == '\\' {
                    out.push(' ');
                    i += 1;
                }
                if i < c.len() {
                    out.push(blank(c[i]));
                    i += 1;
                }
            }
            out.push(' ');
            i += 1;
        } else if at(0) == '\'' && (at(1) == '\\' || at(2) == '\'') {
            // A character literal ('x', '\n', '\u{1F600}'), not a lifetime.
            out.push(' ');
            i += 1;
            while i < c.len() && c[i] != '\'' {
                if c[i] == '\\' {
                    out.push(' ');
                    i += 1;
                }
                out.push(' ');
                i += 1;
            }
            out.push(' ');
            i += 1;
        } else {
            out.push(c[i]);
            i += 1;
        }
    }
    out
}

/// A token of blanked source: an identifier or one punctuation character
/// (`::` is two `:`), with its 1-based line.
#[derive(Debug, Clone, PartialEq)]
struct Token {
    text: String,
    line: usize,
}

fn tokens(code: &str) -> Vec<Token> {
    let mut out = Vec::new();
    let mut line = 1;
    let mut word = String::new();
    for ch in code.chars() {
        if ch.is_alphanumeric() || ch == '_' {
            word.push(ch);
            continue;
        }
        if !word.is_empty() {
            out.push(Token {
                text: std::mem::take(&mut word),
                line,
            });
        }
        if ch == '\n' {
            line += 1;
        } else if !ch.is_whitespace() {
            out.push(Token {
                text: ch.to_string(),
                line,
            });
        }
    }
    if !word.is_empty() {
        out.push(Token { text: word, line });
    }
    out
}

fn is_ident(t: &str) -> bool {
    t.chars()
        .next()
        .is_some_and(|c| c.is_alphabetic() || c == '_')
}

/// The top-level modules named by paths in `code`, with their lines, for a
/// file whose module path is `module` (`["local", "dwa"]` for
/// `src/local/dwa.rs`). Paths inside the file's own top-level module are
/// left out.
fn uses(code: &str, module: &[String]) -> Vec<(String, usize)> {
    let t = tokens(code);
    let text = |k: usize| t.get(k).map_or("", |x| x.text.as_str());
    let sep = |k: usize| text(k) == ":" && text(k + 1) == ":";
    let mut found = Vec::new();
    // Inline `mod name { … }` blocks: (name, brace depth inside them).
    let mut inline: Vec<(String, usize)> = Vec::new();
    let mut depth = 0usize;
    let mut k = 0;
    while k < t.len() {
        match text(k) {
            "{" => depth += 1,
            "}" => {
                depth = depth.saturating_sub(1);
                while inline.last().is_some_and(|(_, d)| *d > depth) {
                    inline.pop();
                }
            }
            "mod" if is_ident(text(k + 1)) && text(k + 2) == "{" => {
                inline.push((text(k + 1).to_string(), depth + 1));
            }
            // `$crate` in a macro is another crate's root.
            "crate" if sep(k + 1) && !(k > 0 && text(k - 1) == "$") => {
                if is_ident(text(k + 3)) {
                    found.push((text(k + 3).to_string(), t[k].line));
                } else if text(k + 3) == "{" {
                    // Each item's head: after `{` or `,` at the group's level.
                    let mut level = 0usize;
                    let mut j = k + 3;
                    let mut head = true;
                    while j < t.len() {
                        match text(j) {
                            "{" => {
                                level += 1;
                                head = level == 1;
                            }
                            "}" => {
                                level -= 1;
                                if level == 0 {
                                    break;
                                }
                            }
                            "," => head = level == 1,
                            w if head && is_ident(w) => {
                                found.push((w.to_string(), t[j].line));
                                head = false;
                            }
                            _ => head = false,
                        }
                        j += 1;
                    }
                }
            }
            "super" if !(k >= 2 && sep(k - 2)) => {
                // A chain super::super::x: where does it land?
                let mut n = 0;
                let mut j = k;
                while text(j) == "super" && sep(j + 1) {
                    n += 1;
                    j += 3;
                }
                let here = module.len() + inline.len();
                if n > 0 && n >= here && is_ident(text(j)) {
                    found.push((text(j).to_string(), t[j].line));
                }
            }
            _ => {}
        }
        k += 1;
    }
    let own = module.first().map(String::as_str).unwrap_or("");
    found.retain(|(m, _)| m != own);
    found
}

/// The module path of a source file relative to `src/`.
fn module_path(rel: &Path) -> Vec<String> {
    let mut parts: Vec<String> = rel
        .iter()
        .map(|p| p.to_string_lossy().trim_end_matches(".rs").to_string())
        .collect();
    if parts.last().is_some_and(|p| p == "mod" || p == "lib") {
        parts.pop();
    }
    parts
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("cannot list {}: {e}", dir.display()))
        .map(|e| e.expect("directory entry").path())
        .collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|e| e == "rs") {
            out.push(p);
        }
    }
}

/// The top-level modules `lib.rs` declares.
fn declared_modules(lib: &str) -> Vec<String> {
    let t = tokens(&blank_comments_and_literals(lib));
    t.windows(3)
        .filter(|w| w[0].text == "mod" && is_ident(&w[1].text) && w[2].text == ";")
        .map(|w| w[1].text.clone())
        .collect()
}

#[test]
fn modules_use_only_lower_layers() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let lib = std::fs::read_to_string(src.join("lib.rs")).expect("src/lib.rs");
    let declared = declared_modules(&lib);
    let unplaced: Vec<&String> = declared.iter().filter(|m| layer_of(m).is_none()).collect();
    assert!(
        unplaced.is_empty(),
        "modules {unplaced:?} are declared in lib.rs but have no layer: add them to LAYERS \
         here and to ARCHITECTURE.md"
    );
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let mut problems = Vec::new();
    let mut pairs = BTreeSet::new();
    for file in &files {
        let rel = file.strip_prefix(&src).expect("under src");
        let module = module_path(rel);
        let Some(own) = module.first() else {
            continue; // lib.rs only declares the modules
        };
        let Some(own_layer) = layer_of(own) else {
            continue; // reported above when declared
        };
        let code = blank_comments_and_literals(&std::fs::read_to_string(file).expect("source"));
        for (used, line) in uses(&code, &module) {
            let Some(used_layer) = layer_of(&used) else {
                continue; // not a top-level module (an item re-exported at the root)
            };
            if used_layer >= own_layer {
                let how = if used_layer == own_layer {
                    "a module of its own layer"
                } else {
                    "a layer above it"
                };
                problems.push(format!(
                    "  src/{}:{line}: `{own}` (layer {}) uses `{used}` (layer {}), {how}",
                    rel.display(),
                    LAYERS[own_layer].0,
                    LAYERS[used_layer].0,
                ));
                pairs.insert(format!("{own} -> {used}"));
            }
        }
    }
    assert!(
        problems.is_empty(),
        "{} use(s) against the layering of ARCHITECTURE.md ({}):\n{}\n\
         Move the used item down, or the using code up (as the planner catalogue went up \
         from `local` to `crate::planners`, and its helpers down to `crate::params`).",
        problems.len(),
        pairs.into_iter().collect::<Vec<_>>().join(", "),
        problems.join("\n")
    );
}

#[test]
fn the_scanner_finds_paths_in_code_only() {
    let module = vec!["local".to_string(), "dwa".to_string()];
    let src = r##"
//! [`crate::sim::Episode`] in a doc comment is a link, not a use.
/// Also [`crate::metrics`].
use crate::{map::Cell, world::{Command, RobotState}, num};
use crate::local::Observation;
fn f() -> &'static str {
    let _c = '"';
    let _s = "crate::sim";
    let _r = r#"crate::apf "quoted""#;
    let _b = br#"crate::bench"#;
    /* crate::lidar /* nested */ crate::arm */
    crate::global::plan::x()
}
mod tests {
    use super::super::testkit;
    use super::super::super::scenario::Thing;
}
macro_rules! m { () => { $crate::reproduce::x() } }
"##;
    let code = blank_comments_and_literals(src);
    assert_eq!(code.lines().count(), src.lines().count());
    let got: Vec<(String, usize)> = uses(&code, &module);
    let want: Vec<(String, usize)> = [
        ("map", 4),
        ("world", 4),
        ("num", 4),
        ("global", 12),
        ("scenario", 16),
    ]
    .iter()
    .map(|(m, l)| (m.to_string(), *l))
    .collect();
    assert_eq!(got, want);
    assert_eq!(module_path(Path::new("local/mod.rs")), vec!["local"]);
    assert_eq!(module_path(Path::new("num.rs")), vec!["num"]);
    assert_eq!(
        declared_modules("//! pub mod nope;\npub mod map;\nmod sim;\n"),
        vec!["map", "sim"]
    );
    // A use of a higher layer is what the main test reports.
    assert!(layer_of("local") < layer_of("lidar"));
    assert!(layer_of("map") < layer_of("global"));
    assert_eq!(layer_of("lidar"), layer_of("arm"));
}
