//! The `map` section of planlab's scenario files: a grid stored inline
//! (plain rows of `.` `#` `?`, or run-length encoded rows) or a ROS
//! map_server / Moving AI file referenced by path and read through the
//! caller's reader (no file system in wasm). `docs/scenario-schema.md`
//! documents the fields.

use super::{movingai, ros, ScenarioError};
use crate::map::{check_dimensions, Cell, MapError, OccupancyGrid, Pose2};
use serde::{Deserialize, Serialize};

/// Inline maps at most this many cells wide and high are written as plain
/// rows by [`RowEncoding::for_grid`] (easy to edit by hand); larger ones
/// run-length encoded.
pub const PLAIN_ROWS_MAX_SIDE: usize = 100;

/// How inline map rows are written.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum RowEncoding {
    /// `cells`: one string per row, one character per cell.
    #[default]
    Plain,
    /// `rle`: one string per row of `<count><char>` runs (count omitted when
    /// 1), e.g. `"12.3#?"`.
    Rle,
}

/// A map stored in the scenario itself.
#[derive(Clone, Debug, PartialEq)]
pub struct InlineMap {
    /// The grid, with its resolution and origin.
    pub grid: OccupancyGrid,
    /// How its rows are written back.
    pub encoding: RowEncoding,
}

/// A map in a separate file, by path relative to the scenario file.
#[derive(Clone, Debug, PartialEq)]
pub struct MapFileRef {
    /// Path relative to the scenario file, `/`-separated: a ROS map_server
    /// `.yaml` (its image is relative to the YAML) or a Moving AI `.map`.
    pub file: String,
    /// Metres per cell replacing the file's (Moving AI maps have none and
    /// default to 1 m).
    pub resolution: Option<f64>,
    /// World pose of the bottom-left corner replacing the file's.
    pub origin: Option<Pose2>,
}

/// Where the scenario's map comes from.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "MapSpecJson", into = "MapSpecJson")]
pub enum MapSpec {
    /// The map is in the scenario.
    Inline(InlineMap),
    /// The map is in another file.
    File(MapFileRef),
}

/// Map file formats a scenario can reference.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MapFormat {
    /// ROS map_server YAML (`.yaml`, `.yml`) with its PGM image.
    RosYaml,
    /// Moving AI `.map`.
    MovingAi,
}

impl MapFormat {
    /// The format implied by a path's extension (case-insensitive).
    pub fn from_path(path: &str) -> Option<MapFormat> {
        let ext = path.rsplit_once('.').map(|(_, e)| e.to_ascii_lowercase())?;
        if ext.contains('/') {
            return None;
        }
        match ext.as_str() {
            "yaml" | "yml" => Some(MapFormat::RosYaml),
            "map" => Some(MapFormat::MovingAi),
            _ => None,
        }
    }
}

impl RowEncoding {
    /// Plain rows for small maps (easy to edit by hand), run-length encoding
    /// for large ones.
    pub fn for_grid(grid: &OccupancyGrid) -> RowEncoding {
        if grid.width() <= PLAIN_ROWS_MAX_SIDE && grid.height() <= PLAIN_ROWS_MAX_SIDE {
            RowEncoding::Plain
        } else {
            RowEncoding::Rle
        }
    }
}

impl InlineMap {
    /// `grid`, to be written in the encoding [`RowEncoding::for_grid`] picks.
    pub fn new(grid: OccupancyGrid) -> InlineMap {
        InlineMap {
            encoding: RowEncoding::for_grid(&grid),
            grid,
        }
    }
}

impl MapFileRef {
    /// The referenced file's format, by its extension.
    pub fn format(&self) -> Result<MapFormat, ScenarioError> {
        MapFormat::from_path(&self.file).ok_or_else(|| {
            ScenarioError::Invalid(format!(
                "map.file {:?}: unknown map format; use a ROS map_server .yaml or a Moving AI .map",
                self.file
            ))
        })
    }

    /// Checks the reference without reading the file: a known format, and
    /// the resolution and origin when given ([`crate::map::check_frame`]).
    pub fn validate(&self) -> Result<(), ScenarioError> {
        self.format()?;
        let default = (1.0, Pose2::default());
        crate::map::check_frame(
            self.resolution.unwrap_or(default.0),
            self.origin.unwrap_or(default.1),
        )?;
        Ok(())
    }
}

impl MapSpec {
    /// The map: the inline grid, or the referenced file read through `read`
    /// (given a path relative to the scenario file, it returns the bytes or
    /// an error message) and parsed by its extension, with `resolution` /
    /// `origin` overrides applied.
    pub fn load(
        &self,
        read: &mut dyn FnMut(&str) -> Result<Vec<u8>, String>,
    ) -> Result<OccupancyGrid, ScenarioError> {
        let f = match self {
            MapSpec::Inline(m) => return Ok(m.grid.clone()),
            MapSpec::File(f) => f,
        };
        let format = f.format()?;
        let mut fetch = |path: &str| {
            read(path).map_err(|message| MapError::Io {
                path: path.to_string(),
                message,
            })
        };
        let text = |bytes: Vec<u8>, path: &str| {
            String::from_utf8(bytes).map_err(|_| MapError::Io {
                path: path.to_string(),
                message: "not UTF-8 text".into(),
            })
        };
        let grid = match format {
            MapFormat::RosYaml => {
                let meta = ros::parse_yaml(&text(fetch(&f.file)?, &f.file)?)?;
                let image = join_relative(&f.file, &meta.image);
                ros::grid_from_pgm(&meta, &ros::parse_pgm(&fetch(&image)?)?)?
            }
            MapFormat::MovingAi => movingai::parse_map(&text(fetch(&f.file)?, &f.file)?)?,
        };
        let (res, origin) = (
            f.resolution.unwrap_or(grid.resolution()),
            f.origin.unwrap_or(grid.origin()),
        );
        Ok(grid.with_frame(res, origin)?)
    }
}

/// `rel` resolved against the directory of `base` (both `/`-separated);
/// absolute `rel` (leading `/` or a `C:` drive) is returned as is. Used to
/// find a ROS map's image next to its YAML.
pub fn join_relative(base: &str, rel: &str) -> String {
    let absolute =
        rel.starts_with('/') || rel.starts_with('\\') || rel.as_bytes().get(1) == Some(&b':');
    if absolute {
        return rel.to_string();
    }
    match base.rfind(['/', '\\']) {
        Some(i) => format!("{}/{}", &base[..i], rel),
        None => rel.to_string(),
    }
}

/// The JSON shape of [`MapSpec`]: one object whose fields say which kind it
/// is (validated in `TryFrom`, which gives better messages than an untagged
/// enum).
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct MapSpecJson {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    file: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    width: Option<u64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    height: Option<u64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    resolution: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    origin: Option<Pose2>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    cells: Option<Vec<String>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    rle: Option<Vec<String>>,
}

/// The character of a cell in scenario rows.
fn cell_char(c: Cell) -> char {
    match c {
        Cell::Free => '.',
        Cell::Occupied => '#',
        Cell::Unknown => '?',
    }
}

/// The cell of a scenario row character.
fn char_cell(ch: char) -> Option<Cell> {
    match ch {
        '.' => Some(Cell::Free),
        '#' => Some(Cell::Occupied),
        '?' => Some(Cell::Unknown),
        _ => None,
    }
}

/// Appends one plain row (`r` 1-based for messages) to `cells`.
fn decode_plain(row: &str, r: usize, width: usize, cells: &mut Vec<Cell>) -> Result<(), String> {
    let mut n = 0usize;
    for ch in row.chars() {
        n += 1;
        if n > width {
            break;
        }
        cells.push(char_cell(ch).ok_or_else(|| {
            format!(
                "map.cells row {r}, column {n}: unexpected character {ch:?}; use '.' free, '#' occupied, '?' unknown"
            )
        })?);
    }
    if n != width {
        return Err(format!(
            "map.cells row {r} has {} characters, expected width {width}",
            row.chars().count()
        ));
    }
    Ok(())
}

/// Appends one run-length encoded row (`r` 1-based) to `cells`.
fn decode_rle(row: &str, r: usize, width: usize, cells: &mut Vec<Cell>) -> Result<(), String> {
    let mut n = 0usize;
    let mut count: Option<usize> = None;
    for ch in row.chars() {
        if let Some(d) = ch.to_digit(10) {
            // Saturating: any count above the width is refused below anyway.
            let c = count
                .unwrap_or(0)
                .saturating_mul(10)
                .saturating_add(d as usize);
            count = Some(c);
            continue;
        }
        let cell = char_cell(ch).ok_or_else(|| {
            format!(
                "map.rle row {r}: unexpected character {ch:?}; runs are <count><char> with char '.', '#' or '?'"
            )
        })?;
        let k = count.take().unwrap_or(1);
        if k == 0 {
            return Err(format!("map.rle row {r}: a run has count 0"));
        }
        if k > width - n {
            return Err(format!("map.rle row {r} is longer than the width {width}"));
        }
        n += k;
        cells.extend(std::iter::repeat(cell).take(k));
    }
    if count.is_some() {
        return Err(format!(
            "map.rle row {r} ends with a count but no cell character"
        ));
    }
    if n != width {
        return Err(format!(
            "map.rle row {r} has {n} cells, expected width {width}"
        ));
    }
    Ok(())
}

/// Run-length encodes one row.
fn encode_rle(row: &[Cell]) -> String {
    let mut s = String::new();
    let mut i = 0;
    while let Some(&c) = row.get(i) {
        let run = row[i..].iter().take_while(|&&x| x == c).count();
        if run > 1 {
            s.push_str(&run.to_string());
        }
        s.push(cell_char(c));
        i += run;
    }
    s
}

impl TryFrom<MapSpecJson> for MapSpec {
    type Error = String;

    fn try_from(j: MapSpecJson) -> Result<Self, String> {
        if let Some(file) = j.file {
            if j.width.is_some() || j.height.is_some() || j.cells.is_some() || j.rle.is_some() {
                return Err("map: give either `file` or an inline map (`width`, `height`, `cells` or `rle`), not both".into());
            }
            return Ok(MapSpec::File(MapFileRef {
                file,
                resolution: j.resolution,
                origin: j.origin,
            }));
        }
        let (Some(w), Some(h)) = (j.width, j.height) else {
            return Err(
                "map: an inline map needs `width` and `height` (or give `file` instead)".into(),
            );
        };
        let n = check_dimensions(w, h).map_err(|e| format!("map: {e}"))?;
        let (w, h) = (w as usize, h as usize);
        let (rows, encoding) = match (j.cells, j.rle) {
            (Some(rows), None) => (rows, RowEncoding::Plain),
            (None, Some(rows)) => (rows, RowEncoding::Rle),
            (None, None) => {
                return Err("map: an inline map needs `cells` (rows of . # ?) or `rle`".into())
            }
            (Some(_), Some(_)) => return Err("map: give `cells` or `rle`, not both".into()),
        };
        let key = match encoding {
            RowEncoding::Plain => "cells",
            RowEncoding::Rle => "rle",
        };
        if rows.len() != h {
            return Err(format!(
                "map.{key} has {} rows, expected height {h}",
                rows.len()
            ));
        }
        let mut cells = Vec::with_capacity(n);
        for (i, row) in rows.iter().enumerate() {
            match encoding {
                RowEncoding::Plain => decode_plain(row, i + 1, w, &mut cells)?,
                RowEncoding::Rle => decode_rle(row, i + 1, w, &mut cells)?,
            }
        }
        let grid = OccupancyGrid::from_cells(w, h, cells)
            .and_then(|g| g.with_frame(j.resolution.unwrap_or(1.0), j.origin.unwrap_or_default()))
            .map_err(|e| format!("map: {e}"))?;
        Ok(MapSpec::Inline(InlineMap { grid, encoding }))
    }
}

impl From<MapSpec> for MapSpecJson {
    fn from(m: MapSpec) -> Self {
        match m {
            MapSpec::File(f) => MapSpecJson {
                file: Some(f.file),
                width: None,
                height: None,
                resolution: f.resolution,
                origin: f.origin,
                cells: None,
                rle: None,
            },
            MapSpec::Inline(InlineMap { grid, encoding }) => {
                let rows = grid.cells().chunks(grid.width().max(1));
                let rows: Vec<String> = match encoding {
                    RowEncoding::Plain => rows
                        .map(|r| r.iter().map(|&c| cell_char(c)).collect())
                        .collect(),
                    RowEncoding::Rle => rows.map(encode_rle).collect(),
                };
                let (cells, rle) = match encoding {
                    RowEncoding::Plain => (Some(rows), None),
                    RowEncoding::Rle => (None, Some(rows)),
                };
                MapSpecJson {
                    file: None,
                    width: Some(grid.width() as u64),
                    height: Some(grid.height() as u64),
                    resolution: Some(grid.resolution()),
                    origin: Some(grid.origin()),
                    cells,
                    rle,
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rle_encode_decode() {
        let row = [
            Cell::Free,
            Cell::Free,
            Cell::Occupied,
            Cell::Unknown,
            Cell::Unknown,
            Cell::Unknown,
        ];
        let s = encode_rle(&row);
        assert_eq!(s, "2.#3?");
        let mut out = Vec::new();
        decode_rle(&s, 1, 6, &mut out).unwrap();
        assert_eq!(out, row);
        for bad in ["2.#3", "2.#4?", "0.6#", "2.x3?", "99999999999999999999999."] {
            assert!(decode_rle(bad, 1, 6, &mut Vec::new()).is_err(), "{bad}");
        }
    }

    #[test]
    fn paths_join_and_formats() {
        assert_eq!(join_relative("maps/tb3.yaml", "tb3.pgm"), "maps/tb3.pgm");
        assert_eq!(join_relative("tb3.yaml", "tb3.pgm"), "tb3.pgm");
        assert_eq!(join_relative("maps/tb3.yaml", "/abs/x.pgm"), "/abs/x.pgm");
        assert_eq!(MapFormat::from_path("a/B.YML"), Some(MapFormat::RosYaml));
        assert_eq!(MapFormat::from_path("arena.map"), Some(MapFormat::MovingAi));
        assert_eq!(MapFormat::from_path("x.map/readme"), None);
        assert_eq!(MapFormat::from_path("noext"), None);
    }
}
