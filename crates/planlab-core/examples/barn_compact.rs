//! Prints the compact form of a BARN world folder (the challenge's
//! `jackal_helper/worlds/BARN/`: `world_N.world` and
//! `path_files/path_N.npy`), the text of `assets/barn/worlds.txt`:
//!
//! ```text
//! cargo run -p planlab-core --example barn_compact -- <BARN folder> > assets/barn/worlds.txt
//! ```

use std::path::Path;
use std::process::ExitCode;

use planlab_core::barn::{to_compact, BarnWorld};

/// Provenance and licence, printed above the worlds.
const HEADER: &str = "\
# BARN worlds (Perille, Truong, Xiao, Stone, \"Benchmarking Metric Ground Navigation\",
# IEEE SSRR 2020), derived from the BARN Challenge repository Daffan/the-barn-challenge,
# commit bf5a226f6088ec96bf0d2dbee3253a8ea6119b83, folder jackal_helper/worlds/BARN/
# (world_N.world, path_files/path_N.npy). MIT licence, (c) 2022 Zifan Xu: see LICENSE
# beside this file. Only the worlds with N mod 6 != 0 are here (the others are the
# challenge's held-back test set). Written by crates/planlab-core/examples/barn_compact.rs;
# read by planlab_core::barn::parse_compact. See README.md beside this file.
";

fn run(dir: &Path) -> Result<String, String> {
    let mut ids: Vec<u32> = std::fs::read_dir(dir)
        .map_err(|e| format!("{}: {e}", dir.display()))?
        .filter_map(|e| {
            let name = e.ok()?.file_name().into_string().ok()?;
            name.strip_prefix("world_")?
                .strip_suffix(".world")?
                .parse()
                .ok()
        })
        .collect();
    ids.sort_unstable();
    if ids.is_empty() {
        return Err(format!("{}: no world_N.world files", dir.display()));
    }
    let read = |p: &Path| std::fs::read(p).map_err(|e| format!("{}: {e}", p.display()));
    let mut worlds = Vec::with_capacity(ids.len());
    for id in ids {
        let sdf = read(&dir.join(format!("world_{id}.world")))?;
        let npy = read(&dir.join(format!("path_files/path_{id}.npy")))?;
        let mut w = BarnWorld::from_sdf(id, &sdf).map_err(|e| e.to_string())?;
        w.path = BarnWorld::path_from_npy(&npy).map_err(|e| format!("world {id}: {e}"))?;
        worlds.push(w);
    }
    Ok(format!("{HEADER}{}", to_compact(&worlds)))
}

fn main() -> ExitCode {
    let Some(dir) = std::env::args_os().nth(1) else {
        eprintln!("usage: barn_compact <BARN folder>");
        return ExitCode::from(2);
    };
    match run(Path::new(&dir)) {
        Ok(text) => {
            print!("{text}");
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("barn_compact: {e}");
            ExitCode::FAILURE
        }
    }
}
