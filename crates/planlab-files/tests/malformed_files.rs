//! The malformed corpus read from disk: a file reader must give the same
//! message as the core's parser of its bytes (`MANIFEST.tsv`'s fragment),
//! however long the file. The core side is planlab-core's
//! `tests/malformed.rs`.

use planlab_core::map::io::ros;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

fn corpus() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../tests/data/malformed")
}

/// File name → fragment of its expected message.
fn manifest() -> BTreeMap<String, String> {
    let text = std::fs::read_to_string(corpus().join("MANIFEST.tsv")).unwrap();
    text.lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(|l| {
            let cols: Vec<&str> = l.split('\t').collect();
            (cols[0].to_string(), cols[2].to_string())
        })
        .collect()
}

/// What loading a PGM from disk says: the reader's error or the parser's.
fn pgm_error(path: &Path) -> Option<String> {
    match planlab_files::read_pgm(path) {
        Err(e) => Some(e),
        Ok(bytes) => ros::parse_pgm(&bytes).err().map(|e| e.to_string()),
    }
}

#[test]
fn pgm_files_over_64_kib_name_their_real_problem() {
    // Before: every rejected PGM over 64 KiB said "PGM header longer than
    // 65536 bytes" (a PNG, a PPM, a 20000×20000 P5 with a 19-byte header).
    let expected = manifest();
    let mut checked = 0;
    for entry in std::fs::read_dir(corpus()).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        if !name.ends_with(".pgm") {
            continue;
        }
        let fragment = &expected[&name];
        let e = pgm_error(&path).unwrap_or_else(|| panic!("{name}: accepted"));
        assert!(e.contains(fragment.as_str()), "{name}: {e}");
        assert!(!e.contains('\n'), "{name}: {e:?}");
        checked += 1;
    }
    assert!(checked >= 3, "only {checked} PGM files");
}

#[test]
fn a_pgm_header_longer_than_64_kib_is_still_named() {
    // A comment that fills the first 64 KiB: the header really is too long.
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("files-long-header");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("long.pgm");
    let mut bytes = b"P5\n# ".to_vec();
    bytes.extend(std::iter::repeat_n(b'x', ros::PGM_HEADER_MAX_BYTES));
    bytes.extend_from_slice(b"\n2 2\n255\n\0\0\0\0");
    std::fs::write(&path, &bytes).unwrap();
    let e = pgm_error(&path).expect("refused");
    assert!(e.contains("PGM header longer than 65536 bytes"), "{e}");
}
