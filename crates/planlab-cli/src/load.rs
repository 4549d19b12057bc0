//! Reading maps from disk for the CLI: the core parses bytes, this module
//! finds and reads the files (the core never touches the file system).

use planlab_core::map::io::scenario::Scenario;
use planlab_core::map::io::{movingai, ros};
use planlab_core::map::OccupancyGrid;
use std::path::Path;

/// Reads a whole text file, naming it in the error.
pub fn read_text(path: &Path) -> Result<String, String> {
    std::fs::read_to_string(path).map_err(|e| format!("cannot read {}: {e}", path.display()))
}

/// Reads a whole binary file, naming it in the error.
pub fn read_bytes(path: &Path) -> Result<Vec<u8>, String> {
    std::fs::read(path).map_err(|e| format!("cannot read {}: {e}", path.display()))
}

/// Loads a ROS map_server map: the YAML, then the image it names (relative
/// to the YAML's folder).
pub fn load_ros(yaml_path: &Path) -> Result<OccupancyGrid, String> {
    let meta = ros::parse_yaml(&read_text(yaml_path)?)
        .map_err(|e| format!("{}: {e}", yaml_path.display()))?;
    let image = yaml_path
        .parent()
        .unwrap_or_else(|| Path::new("."))
        .join(&meta.image);
    let pgm =
        ros::parse_pgm(&read_bytes(&image)?).map_err(|e| format!("{}: {e}", image.display()))?;
    ros::grid_from_pgm(&meta, &pgm).map_err(|e| format!("{}: {e}", yaml_path.display()))
}

/// Loads a Moving AI `.map`.
pub fn load_movingai(path: &Path) -> Result<OccupancyGrid, String> {
    movingai::parse_map(&read_text(path)?).map_err(|e| format!("{}: {e}", path.display()))
}

/// Loads the scenario rows of a Moving AI `.scen`.
pub fn load_scen(path: &Path) -> Result<Vec<movingai::ScenRow>, String> {
    movingai::parse_scen(&read_text(path)?).map_err(|e| format!("{}: {e}", path.display()))
}

/// File kinds `planlab plan` accepts.
pub enum MapKind {
    /// ROS map_server YAML (+ image).
    Ros,
    /// Moving AI `.map`.
    MovingAi,
    /// planlab scenario JSON.
    Scenario,
}

/// The kind of map file, by extension.
pub fn kind_of(path: &Path) -> Result<MapKind, String> {
    match path
        .extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase())
        .as_deref()
    {
        Some("yaml") | Some("yml") => Ok(MapKind::Ros),
        Some("map") => Ok(MapKind::MovingAi),
        Some("json") => Ok(MapKind::Scenario),
        _ => Err(format!(
            "{}: unknown map format; expected a ROS .yaml, a Moving AI .map or a scenario .json",
            path.display()
        )),
    }
}

/// Loads a scenario JSON and its map (inline, or a file relative to it).
pub fn load_scenario(path: &Path) -> Result<(OccupancyGrid, Scenario), String> {
    let scenario =
        Scenario::from_json(&read_text(path)?).map_err(|e| format!("{}: {e}", path.display()))?;
    let grid = grid_of(path, &scenario)?;
    Ok((grid, scenario))
}

/// The map of the scenario read from `path`: inline, or the referenced file
/// resolved relative to the scenario's folder.
pub fn grid_of(path: &Path, scenario: &Scenario) -> Result<OccupancyGrid, String> {
    let dir = path.parent().unwrap_or_else(|| Path::new("."));
    let mut read = |rel: &str| std::fs::read(dir.join(rel)).map_err(|e| e.to_string());
    scenario
        .load_grid(&mut read)
        .map_err(|e| format!("{}: {e}", path.display()))
}

/// Loads a map of any supported kind; scenarios come with their scenario.
pub fn load_any(path: &Path) -> Result<(OccupancyGrid, Option<Scenario>), String> {
    match kind_of(path)? {
        MapKind::Ros => Ok((load_ros(path)?, None)),
        MapKind::MovingAi => Ok((load_movingai(path)?, None)),
        MapKind::Scenario => load_scenario(path).map(|(g, s)| (g, Some(s))),
    }
}
