//! Reading maps and scenarios from disk for the native front ends (the
//! `planlab` CLI and the Python package): the core parses bytes, this crate
//! finds and reads the files (the core never touches the file system), so
//! both refuse devices, folders and oversized files the same way.

pub mod barn;
pub mod output;

use planlab_core::map::io::{movingai, ros};
use planlab_core::map::{OccupancyGrid, MAX_CELLS};
use planlab_core::scenario::Scenario;
use std::path::Path;

/// The largest text input (scenario JSON, Moving AI `.map` / `.scen`, arm
/// model): a `.map` of [`MAX_CELLS`] cells with a newline per row is under
/// twice that, and no other text input needs more.
pub const MAX_TEXT_BYTES: u64 = 2 * MAX_CELLS + (1 << 20);

/// The largest ROS map YAML: map_server files are a few hundred bytes.
pub const MAX_YAML_BYTES: u64 = 1 << 20;

/// Opens `path` if it is a regular file (not a device, FIFO or folder,
/// which could be endless: `image: /dev/zero`) and returns its length.
fn open_regular(path: &Path) -> Result<(std::fs::File, u64), String> {
    let cannot = |e: std::io::Error| format!("cannot read {}: {e}", path.display());
    let meta = std::fs::metadata(path).map_err(cannot)?;
    if !meta.is_file() {
        return Err(format!(
            "cannot read {}: not a regular file",
            path.display()
        ));
    }
    Ok((std::fs::File::open(path).map_err(cannot)?, meta.len()))
}

/// Reads at most `max` bytes of a regular file; a longer file is refused
/// before anything is allocated for it. `what` names the kind in the error.
pub fn read_capped(path: &Path, max: u64, what: &str) -> Result<Vec<u8>, String> {
    use std::io::Read;
    let (file, len) = open_regular(path)?;
    let too_big = || {
        format!(
            "{}: too large for a {what} ({len} bytes; at most {max})",
            path.display()
        )
    };
    if len > max {
        return Err(too_big());
    }
    // `take`: the file may grow between the check and the read.
    let mut bytes = Vec::with_capacity(len as usize);
    file.take(max + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    if bytes.len() as u64 > max {
        return Err(too_big());
    }
    Ok(bytes)
}

/// Reads a whole text file (at most [`MAX_TEXT_BYTES`]), naming it in the
/// error.
pub fn read_text(path: &Path) -> Result<String, String> {
    text_of(path, read_capped(path, MAX_TEXT_BYTES, "text file")?)
}

fn text_of(path: &Path, bytes: Vec<u8>) -> Result<String, String> {
    String::from_utf8(bytes).map_err(|_| format!("cannot read {}: not UTF-8 text", path.display()))
}

/// Reads a PGM image: its header first, then no more bytes than the
/// header's width × height can use ([`ros::pgm_byte_limit`]).
pub fn read_pgm(path: &Path) -> Result<Vec<u8>, String> {
    use std::io::Read;
    let (file, len) = open_regular(path)?;
    let cannot = |e: std::io::Error| format!("cannot read {}: {e}", path.display());
    let mut head = Vec::new();
    let mut file = file;
    (&mut file)
        .take(ros::PGM_HEADER_MAX_BYTES as u64)
        .read_to_end(&mut head)
        .map_err(cannot)?;
    let limit = ros::pgm_byte_limit(&head).map_err(|e| {
        // Only a header still unfinished at the end of what was read is
        // too long; any other fault is named as it is.
        if head.len() == ros::PGM_HEADER_MAX_BYTES
            && len > head.len() as u64
            && ros::pgm_header_is_cut(&head)
        {
            format!(
                "{}: PGM header longer than {} bytes",
                path.display(),
                ros::PGM_HEADER_MAX_BYTES
            )
        } else {
            format!("{}: {e}", path.display())
        }
    })?;
    // P5 bytes after the last pixel are ignored, so reading `limit` bytes
    // is exact; a P2's spacing is free-form, so a longer P2 is refused
    // rather than cut short.
    if head.starts_with(b"P2") && len > limit {
        return Err(format!(
            "{}: too large for an ASCII PGM of its width × height ({len} bytes; at most {limit})",
            path.display()
        ));
    }
    let want = len.min(limit);
    let mut bytes = Vec::with_capacity(want as usize);
    bytes.extend_from_slice(&head[..head.len().min(want as usize)]);
    if (bytes.len() as u64) < want {
        file.take(want - bytes.len() as u64)
            .read_to_end(&mut bytes)
            .map_err(cannot)?;
    }
    Ok(bytes)
}

/// Reads a map file referenced by a scenario or a YAML, with the bound of
/// its format (by extension).
pub fn read_map_file(path: &Path) -> Result<Vec<u8>, String> {
    match ext_of(path).as_deref() {
        Some("pgm") => read_pgm(path),
        Some("yaml" | "yml") => read_capped(path, MAX_YAML_BYTES, "ROS map YAML"),
        _ => read_capped(path, MAX_TEXT_BYTES, "map file"),
    }
}

fn ext_of(path: &Path) -> Option<String> {
    path.extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase())
}

/// Loads a ROS map_server map: the YAML, then the image it names (relative
/// to the YAML's folder).
pub fn load_ros(yaml_path: &Path) -> Result<OccupancyGrid, String> {
    let yaml = read_capped(yaml_path, MAX_YAML_BYTES, "ROS map YAML")?;
    let meta = ros::parse_yaml(&text_of(yaml_path, yaml)?)
        .map_err(|e| format!("{}: {e}", yaml_path.display()))?;
    let image = yaml_path
        .parent()
        .unwrap_or_else(|| Path::new("."))
        .join(&meta.image);
    let pgm =
        ros::parse_pgm(&read_pgm(&image)?).map_err(|e| format!("{}: {e}", image.display()))?;
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
    match ext_of(path).as_deref() {
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
    scenario
        .load_grid(&mut map_reader(path))
        .map_err(|e| format!("{}: {e}", path.display()))
}

/// Reads the map files a scenario at `path` refers to, by paths relative
/// to its folder (what the core's `load_grid` asks for).
pub fn map_reader(path: &Path) -> impl FnMut(&str) -> Result<Vec<u8>, String> + '_ {
    let dir = path.parent().unwrap_or_else(|| Path::new("."));
    move |rel: &str| read_map_file(&dir.join(rel))
}

/// Loads a map of any supported kind; scenarios come with their scenario.
pub fn load_any(path: &Path) -> Result<(OccupancyGrid, Option<Scenario>), String> {
    match kind_of(path)? {
        MapKind::Ros => Ok((load_ros(path)?, None)),
        MapKind::MovingAi => Ok((load_movingai(path)?, None)),
        MapKind::Scenario => load_scenario(path).map(|(g, s)| (g, Some(s))),
    }
}
