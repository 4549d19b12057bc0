//! BARN worlds from disk: the repository's 250 (compiled in) or a user's
//! checkout of the challenge (`world_N.world` files with
//! `path_files/path_N.npy` beside them).

use std::path::Path;

use planlab_core::barn::{parse_compact, BarnWorld};

/// The compact form of the 250 public BARN worlds (`assets/barn/`).
pub const BUILTIN: &str = include_str!("../../../assets/barn/worlds.txt");

/// The largest BARN `.world` file: the public ones are about 120 kB.
pub const MAX_WORLD_BYTES: u64 = 16 << 20;

/// The largest `path_N.npy`: a 30 × 30 grid's path is at most 900 cells.
pub const MAX_NPY_BYTES: u64 = 1 << 20;

/// The 250 worlds the repository holds.
pub fn builtin_worlds() -> Result<Vec<BarnWorld>, String> {
    parse_compact(BUILTIN).map_err(|e| format!("the built-in BARN worlds: {e}"))
}

/// The number N of a `world_N.world` file name.
fn world_number(path: &Path) -> Option<u32> {
    let name = path.file_name()?.to_str()?;
    name.strip_prefix("world_")?
        .strip_suffix(".world")?
        .parse()
        .ok()
}

/// One `world_N.world` with its reference path from
/// `path_files/path_N.npy` in the same folder.
pub fn load_world(path: &Path) -> Result<BarnWorld, String> {
    let id = world_number(path).ok_or_else(|| {
        format!(
            "{}: not a BARN world file (expected a name like world_17.world)",
            path.display()
        )
    })?;
    let bytes = crate::read_capped(path, MAX_WORLD_BYTES, "BARN world")?;
    let mut world =
        BarnWorld::from_sdf(id, &bytes).map_err(|e| format!("{}: {e}", path.display()))?;
    let npy = path
        .parent()
        .unwrap_or(Path::new("."))
        .join("path_files")
        .join(format!("path_{id}.npy"));
    let bytes = crate::read_capped(&npy, MAX_NPY_BYTES, "BARN path")
        .map_err(|e| format!("{e} (every BARN world needs its reference path)"))?;
    world.path = BarnWorld::path_from_npy(&bytes).map_err(|e| format!("{}: {e}", npy.display()))?;
    Ok(world)
}

/// The worlds at `path`: a `.world` file, or a folder holding
/// `world_N.world` files (a checkout's `jackal_helper/worlds/BARN/`).
pub fn load_worlds(path: &Path) -> Result<Vec<BarnWorld>, String> {
    let meta =
        std::fs::metadata(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    if !meta.is_dir() {
        return Ok(vec![load_world(path)?]);
    }
    let mut files: Vec<_> = std::fs::read_dir(path)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| world_number(p).is_some())
        .collect();
    if files.is_empty() {
        return Err(format!(
            "{}: no world_N.world files (point at the BARN folder of the challenge's jackal_helper/worlds)",
            path.display()
        ));
    }
    files.sort_by_key(|p| world_number(p));
    files.iter().map(|p| load_world(p)).collect()
}

/// The planner a `barn:` scenario gets when none is named: the challenge's
/// baseline.
pub const DEFAULT_PLANNER: &str = "move-base-dwa";

/// The scenario JSON a `barn:N` (a built-in world) or `barn:PATH`
/// (a `world_N.world` file) source names, driven by `planner` (default
/// [`DEFAULT_PLANNER`]) with `seed` and the default laser noise — the
/// episode `planlab barn` ran for that world, planner and seed. `None`
/// when `source` does not start with `barn:`.
pub fn scenario_json(
    source: &str,
    planner: Option<&str>,
    seed: Option<u64>,
) -> Result<Option<String>, String> {
    let Some(rest) = source.strip_prefix("barn:") else {
        return Ok(None);
    };
    let world = match rest.parse::<u32>() {
        Ok(id) => builtin_worlds()?
            .into_iter()
            .find(|w| w.id == id)
            .ok_or_else(|| {
                format!(
                    "{source}: the repository holds the BARN worlds 0–299 with N mod 6 ≠ 0 (the others are the challenge's held-back test set); give a world_{id}.world file instead"
                )
            })?,
        Err(_) => load_world(Path::new(rest))?,
    };
    let planner = planner.unwrap_or(DEFAULT_PLANNER);
    if !planlab_core::barn::run::PLANNERS.contains(&planner) {
        return Err(format!(
            "{source}: `{planner}` cannot drive an unknown map on BARN; choose from {}",
            planlab_core::barn::run::PLANNERS.join(", ")
        ));
    }
    let opts = planlab_core::barn::run::BarnOptions::default();
    let (scenario, _) =
        planlab_core::barn::run::scenario(&world, planner, seed.unwrap_or(0), &opts)
            .map_err(|e| e.to_string())?;
    serde_json::to_string(&scenario)
        .map(Some)
        .map_err(|e| format!("{source}: {e}"))
}
