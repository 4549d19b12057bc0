//! Occupancy grids, their file formats, inflation and costmaps (docs/algorithms.md §maps).
//!
//! Cells are addressed `(col, row)` with row 0 at the **top** of the image, as
//! in Moving AI files and in the PGM of a ROS map. The world frame is x right,
//! y up; [`OccupancyGrid::origin`] is the world pose of the **bottom-left
//! corner** of the image (the corner of cell `(0, height - 1)`), exactly what
//! the `origin` field of a ROS map_server YAML means.

pub mod costmap;
pub mod edit;
pub mod generate;
mod grid_pos;
pub mod io;
pub mod ray;
mod weights;

pub use grid_pos::{supercover, supercover_while, GridPos};
pub use weights::MAX_WEIGHT;

use serde::{Deserialize, Serialize};
use thiserror::Error;

/// The largest map planlab accepts, in cells; larger maps are refused with
/// [`MapError::TooLarge`] before anything is allocated.
pub const MAX_CELLS: u64 = 100_000_000;

/// State of one grid cell.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
#[repr(u8)]
pub enum Cell {
    /// Known to be free.
    #[default]
    Free = 0,
    /// Known to be occupied.
    Occupied = 1,
    /// Never observed (ROS value -1).
    Unknown = 2,
}

impl Cell {
    /// Whether a planner may enter this cell; unknown cells only when
    /// `allow_unknown` is set.
    #[inline]
    pub fn passable(self, allow_unknown: bool) -> bool {
        match self {
            Cell::Free => true,
            Cell::Occupied => false,
            Cell::Unknown => allow_unknown,
        }
    }
}

/// A planar pose: position in metres, yaw in radians.
#[derive(Clone, Copy, Debug, PartialEq, Default, Serialize, Deserialize)]
pub struct Pose2 {
    /// x in metres.
    pub x: f64,
    /// y in metres.
    pub y: f64,
    /// Heading in radians, counter-clockwise from +x.
    pub yaw: f64,
}

/// Errors from building, reading or editing maps.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum MapError {
    /// A dimension is zero.
    #[error("map is empty: {width}×{height} cells")]
    Empty {
        /// Width in cells.
        width: u64,
        /// Height in cells.
        height: u64,
    },
    /// More than [`MAX_CELLS`] cells.
    #[error("map too large: {width}×{height} = {cells} cells exceeds the limit of {max} cells")]
    TooLarge {
        /// Width in cells.
        width: u64,
        /// Height in cells.
        height: u64,
        /// width × height.
        cells: u64,
        /// The limit, [`MAX_CELLS`].
        max: u64,
    },
    /// The cell vector does not match width × height.
    #[error("map data has {got} cells, expected {width}×{height} = {expected}")]
    SizeMismatch {
        /// Width in cells.
        width: u64,
        /// Height in cells.
        height: u64,
        /// width × height.
        expected: u64,
        /// Cells actually given.
        got: u64,
    },
    /// Resolution not finite and positive, or above
    /// [`MAX_PARAM`](crate::num::MAX_PARAM).
    #[error("invalid resolution {}: must be a finite number > 0 and at most {} (metres per cell)", crate::num::fmt_num(*.0), crate::num::fmt_num(crate::num::MAX_PARAM))]
    BadResolution(f64),
    /// Origin not finite, or x or y beyond ±[`MAX_PARAM`](crate::num::MAX_PARAM).
    #[error("invalid origin ({}, {}, {}): x and y must be finite and within ±{} m, yaw finite", crate::num::fmt_num(*.x), crate::num::fmt_num(*.y), crate::num::fmt_num(*.yaw), crate::num::fmt_num(crate::num::MAX_PARAM))]
    BadOrigin {
        /// x in metres.
        x: f64,
        /// y in metres.
        y: f64,
        /// yaw in radians.
        yaw: f64,
    },
    /// A cell index outside the map.
    #[error("cell ({col}, {row}) is outside the {width}×{height} map")]
    OutOfBounds {
        /// Column.
        col: i64,
        /// Row.
        row: i64,
        /// Width in cells.
        width: usize,
        /// Height in cells.
        height: usize,
    },
    /// A file could not be parsed; `line` is 1-based, 0 when not applicable.
    #[error("{format} parse error{}: {}", if *line > 0 { format!(" at line {line}") } else { String::new() }, crate::text::one_line(message))]
    Parse {
        /// Which format ("Moving AI map", "ROS yaml", "PGM", …).
        format: &'static str,
        /// 1-based line, or 0.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// A numeric parameter (a radius, a factor) is out of range.
    #[error("invalid parameter: {}", crate::text::one_line(.0))]
    InvalidParameter(String),
    /// A referenced file could not be read.
    #[error(
        "cannot read {}: {}",
        crate::text::one_line(path),
        crate::text::one_line(message)
    )]
    Io {
        /// The path as given.
        path: String,
        /// The OS error.
        message: String,
    },
}

impl MapError {
    /// Shorthand for a [`MapError::Parse`].
    pub fn parse(format: &'static str, line: usize, message: impl Into<String>) -> Self {
        MapError::Parse {
            format,
            line,
            message: message.into(),
        }
    }
}

/// Checks that `width × height` is non-empty and at most [`MAX_CELLS`].
///
/// Readers call this on the header, before allocating anything.
pub fn check_dimensions(width: u64, height: u64) -> Result<usize, MapError> {
    if width == 0 || height == 0 {
        return Err(MapError::Empty { width, height });
    }
    let cells = width.saturating_mul(height);
    if cells > MAX_CELLS {
        return Err(MapError::TooLarge {
            width,
            height,
            cells,
            max: MAX_CELLS,
        });
    }
    Ok(cells as usize)
}

/// Checks a map's frame: metres per cell finite, > 0 and at most
/// [`MAX_PARAM`](crate::num::MAX_PARAM); the origin's x and y finite and
/// within ±`MAX_PARAM` m, its yaw finite. Every map's frame passes here (an
/// origin of 1e300 m used to swallow the map's own coordinates, so the goal
/// seemed to lie in a wall).
pub fn check_frame(resolution: f64, origin: Pose2) -> Result<(), MapError> {
    use crate::num::MAX_PARAM;
    if !(resolution.is_finite() && resolution > 0.0 && resolution <= MAX_PARAM) {
        return Err(MapError::BadResolution(resolution));
    }
    let within = |v: f64| v.is_finite() && v.abs() <= MAX_PARAM;
    if !(within(origin.x) && within(origin.y) && origin.yaw.is_finite()) {
        return Err(MapError::BadOrigin {
            x: origin.x,
            y: origin.y,
            yaw: origin.yaw,
        });
    }
    Ok(())
}

/// An occupancy grid with a metric frame.
#[derive(Clone, Debug, PartialEq)]
pub struct OccupancyGrid {
    width: usize,
    height: usize,
    resolution: f64,
    origin: Pose2,
    cells: Vec<Cell>,
    /// Traversal weight per cell (1..=[`MAX_WEIGHT`], row-major), or `None`
    /// for a unit-cost map (docs/algorithms.md §weights; `weights.rs`).
    weights: Option<Vec<u8>>,
}

impl OccupancyGrid {
    /// An all-free grid, 1 m per cell, origin at (0, 0).
    pub fn new(width: usize, height: usize) -> Result<Self, MapError> {
        let n = check_dimensions(width as u64, height as u64)?;
        Ok(Self {
            width,
            height,
            resolution: 1.0,
            origin: Pose2::default(),
            cells: vec![Cell::Free; n],
            weights: None,
        })
    }

    /// A grid from row-major cells (row 0 at the top).
    pub fn from_cells(width: usize, height: usize, cells: Vec<Cell>) -> Result<Self, MapError> {
        let n = check_dimensions(width as u64, height as u64)?;
        if cells.len() != n {
            return Err(MapError::SizeMismatch {
                width: width as u64,
                height: height as u64,
                expected: n as u64,
                got: cells.len() as u64,
            });
        }
        Ok(Self {
            width,
            height,
            resolution: 1.0,
            origin: Pose2::default(),
            cells,
            weights: None,
        })
    }

    /// A grid from ASCII art, one text line per row, top row first.
    ///
    /// `.` ` ` `S` `G` are free, `#` `@` `T` `O` `W` occupied, `?` unknown,
    /// a digit `1`–`9` a free cell of that traversal weight.
    /// Leading and trailing blank lines are ignored; every row must have the
    /// same width. Handy for test fixtures:
    ///
    /// ```
    /// use planlab_core::map::{Cell, OccupancyGrid};
    /// let g = OccupancyGrid::from_ascii("
    /// ..#
    /// .?.
    /// ").unwrap();
    /// assert_eq!((g.width(), g.height()), (3, 2));
    /// assert_eq!(g.get(2, 0), Some(Cell::Occupied));
    /// assert_eq!(g.get(1, 1), Some(Cell::Unknown));
    /// ```
    pub fn from_ascii(text: &str) -> Result<Self, MapError> {
        let lines: Vec<&str> = text
            .lines()
            .map(|l| l.trim_end_matches('\r'))
            .skip_while(|l| l.trim().is_empty())
            .collect();
        let end = lines
            .iter()
            .rposition(|l| !l.trim().is_empty())
            .map_or(0, |i| i + 1);
        let lines = &lines[..end];
        let height = lines.len();
        let width = lines.first().map_or(0, |l| l.chars().count());
        let n = check_dimensions(width as u64, height as u64)?;
        let mut cells = Vec::with_capacity(n);
        let mut weights = Vec::with_capacity(n);
        for (r, line) in lines.iter().enumerate() {
            if line.chars().count() != width {
                return Err(MapError::parse(
                    "ASCII map",
                    r + 1,
                    format!(
                        "row has {} characters, expected {width}",
                        line.chars().count()
                    ),
                ));
            }
            for ch in line.chars() {
                // A digit 1–9 is a free cell of that weight.
                weights.push(ch.to_digit(10).filter(|&d| d >= 1).unwrap_or(1) as u8);
                cells.push(match ch {
                    '1'..='9' => Cell::Free,
                    '.' | ' ' | 'S' | 'G' => Cell::Free,
                    '#' | '@' | 'T' | 'O' | 'W' => Cell::Occupied,
                    '?' => Cell::Unknown,
                    other => {
                        return Err(MapError::parse(
                            "ASCII map",
                            r + 1,
                            format!("unexpected character {other:?}"),
                        ))
                    }
                });
            }
        }
        let grid = Self::from_cells(width, height, cells)?;
        if weights.iter().any(|&w| w > 1) {
            grid.with_weights(weights)
        } else {
            Ok(grid)
        }
    }

    /// Renders the grid as ASCII art (`.` free, `#` occupied, `?` unknown,
    /// a digit 2–9 a free cell of that weight).
    pub fn to_ascii(&self) -> String {
        let mut s = String::with_capacity((self.width + 1) * self.height);
        for (r, row) in self.cells.chunks(self.width).enumerate() {
            for (col, c) in row.iter().enumerate() {
                let w = self.weight(col, r);
                s.push(match c {
                    Cell::Free if w > 1 => char::from_digit(u32::from(w), 10).unwrap_or('.'),
                    Cell::Free => '.',
                    Cell::Occupied => '#',
                    Cell::Unknown => '?',
                });
            }
            s.push('\n');
        }
        s
    }

    /// Sets the metric frame: metres per cell and the pose of the
    /// bottom-left corner of the image.
    pub fn with_frame(mut self, resolution: f64, origin: Pose2) -> Result<Self, MapError> {
        check_frame(resolution, origin)?;
        self.resolution = resolution;
        self.origin = origin;
        Ok(self)
    }

    /// Width in cells (columns).
    #[inline]
    pub fn width(&self) -> usize {
        self.width
    }

    /// Height in cells (rows).
    #[inline]
    pub fn height(&self) -> usize {
        self.height
    }

    /// Metres per cell.
    #[inline]
    pub fn resolution(&self) -> f64 {
        self.resolution
    }

    /// World pose of the bottom-left corner of the image.
    #[inline]
    pub fn origin(&self) -> Pose2 {
        self.origin
    }

    /// Row-major cells, row 0 at the top.
    #[inline]
    pub fn cells(&self) -> &[Cell] {
        &self.cells
    }

    /// Whether `(col, row)` lies on the map.
    #[inline]
    pub fn in_bounds(&self, col: i64, row: i64) -> bool {
        col >= 0
            && row >= 0
            && (col as u64) < self.width as u64
            && (row as u64) < self.height as u64
    }

    /// Row-major index of `(col, row)`; the caller checks bounds.
    #[inline]
    pub fn index(&self, col: usize, row: usize) -> usize {
        row * self.width + col
    }

    /// The cell at `(col, row)`, or `None` off the map.
    #[inline]
    pub fn get(&self, col: usize, row: usize) -> Option<Cell> {
        if col < self.width && row < self.height {
            Some(self.cells[row * self.width + col])
        } else {
            None
        }
    }

    /// Sets the cell at `(col, row)`.
    pub fn set(&mut self, col: usize, row: usize, cell: Cell) -> Result<(), MapError> {
        if col < self.width && row < self.height {
            self.cells[row * self.width + col] = cell;
            // A wall painted or erased takes the cell's weight with it.
            if let Some(w) = self.weights.as_mut() {
                w[row * self.width + col] = 1;
            }
            Ok(())
        } else {
            Err(MapError::OutOfBounds {
                col: col as i64,
                row: row as i64,
                width: self.width,
                height: self.height,
            })
        }
    }

    /// Sets every cell the straight segment between the centres of
    /// `(col0, row0)` and `(col1, row1)` crosses — one brush stroke between
    /// two pointer samples. Both ends must be on the map. Returns how many
    /// cells changed.
    pub fn paint_segment(
        &mut self,
        (col0, row0): (usize, usize),
        (col1, row1): (usize, usize),
        cell: Cell,
    ) -> Result<usize, MapError> {
        for (col, row) in [(col0, row0), (col1, row1)] {
            if col >= self.width || row >= self.height {
                return Err(MapError::OutOfBounds {
                    col: col as i64,
                    row: row as i64,
                    width: self.width,
                    height: self.height,
                });
            }
        }
        let mut changed = 0;
        let (a, b) = (
            GridPos::new(col0 as u32, row0 as u32),
            GridPos::new(col1 as u32, row1 as u32),
        );
        supercover(a, b, |c, r, corner| {
            // Crossed cells lie in the endpoints' bounding box, so on the map.
            if corner.is_none() {
                let i = r as usize * self.width + c as usize;
                let weighted = self.weights.as_ref().is_some_and(|w| w[i] > 1);
                if self.cells[i] != cell || weighted {
                    self.cells[i] = cell;
                    if let Some(w) = self.weights.as_mut() {
                        w[i] = 1;
                    }
                    changed += 1;
                }
            }
        });
        Ok(changed)
    }

    /// Number of cells of each kind: (free, occupied, unknown).
    pub fn counts(&self) -> (usize, usize, usize) {
        let mut c = (0, 0, 0);
        for cell in &self.cells {
            match cell {
                Cell::Free => c.0 += 1,
                Cell::Occupied => c.1 += 1,
                Cell::Unknown => c.2 += 1,
            }
        }
        c
    }

    /// FNV-1a hash of the size, frame and cells: equal grids hash equal on
    /// every target, so a map generated in the browser can be compared
    /// with the CLI's by one number.
    pub fn content_hash(&self) -> u64 {
        const PRIME: u64 = 0x0000_0100_0000_01B3;
        let mut h: u64 = 0xCBF2_9CE4_8422_2325;
        let mut eat = |bytes: &[u8]| {
            for &b in bytes {
                h ^= u64::from(b);
                h = h.wrapping_mul(PRIME);
            }
        };
        eat(&(self.width as u64).to_le_bytes());
        eat(&(self.height as u64).to_le_bytes());
        eat(&self.resolution.to_bits().to_le_bytes());
        for v in [self.origin.x, self.origin.y, self.origin.yaw] {
            eat(&v.to_bits().to_le_bytes());
        }
        for c in &self.cells {
            eat(&[*c as u8]);
        }
        // Only a weighted map hashes its weights: unit maps keep their hash.
        if let Some(w) = self.weights.as_ref().filter(|w| w.iter().any(|&v| v > 1)) {
            eat(b"weights");
            eat(w);
        }
        h
    }

    /// World coordinates (metres) of the centre of cell `(col, row)`.
    pub fn cell_to_world(&self, col: usize, row: usize) -> (f64, f64) {
        let lx = (col as f64 + 0.5) * self.resolution;
        let ly = ((self.height - 1 - row.min(self.height - 1)) as f64 + 0.5) * self.resolution;
        let (s, c) = self.origin.yaw.sin_cos();
        if self.origin.yaw == 0.0 {
            (self.origin.x + lx, self.origin.y + ly)
        } else {
            (
                self.origin.x + c * lx - s * ly,
                self.origin.y + s * lx + c * ly,
            )
        }
    }

    /// The cell containing world point `(x, y)`, or `None` off the map.
    pub fn world_to_cell(&self, x: f64, y: f64) -> Option<(usize, usize)> {
        if !(x.is_finite() && y.is_finite()) {
            return None;
        }
        let (dx, dy) = (x - self.origin.x, y - self.origin.y);
        let (lx, ly) = if self.origin.yaw == 0.0 {
            (dx, dy)
        } else {
            let (s, c) = self.origin.yaw.sin_cos();
            (c * dx + s * dy, -s * dx + c * dy)
        };
        let (col, up) = (lx / self.resolution, ly / self.resolution);
        // Negative (or NaN) first: on what is left truncation is floor,
        // without a libm call on targets lacking SSE4.1 (a hot path of the
        // costmap critics).
        if !(col >= 0.0 && up >= 0.0) || col >= self.width as f64 || up >= self.height as f64 {
            return None;
        }
        Some((col as usize, self.height - 1 - up as usize))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn world_cell_round_trip() {
        let g = OccupancyGrid::new(10, 5)
            .unwrap()
            .with_frame(
                0.05,
                Pose2 {
                    x: -1.0,
                    y: 2.0,
                    yaw: 0.0,
                },
            )
            .unwrap();
        // Bottom-left cell's centre is half a cell from the origin.
        let (x, y) = g.cell_to_world(0, 4);
        assert!((x - (-0.975)).abs() < 1e-12 && (y - 2.025).abs() < 1e-12);
        for (c, r) in [(0, 0), (9, 4), (3, 2)] {
            let (x, y) = g.cell_to_world(c, r);
            assert_eq!(g.world_to_cell(x, y), Some((c, r)));
        }
        assert_eq!(g.world_to_cell(-1.01, 2.0), None);
        assert_eq!(g.world_to_cell(f64::NAN, 2.0), None);
    }

    #[test]
    fn rotated_frame_round_trip() {
        let g = OccupancyGrid::new(7, 9)
            .unwrap()
            .with_frame(
                0.1,
                Pose2 {
                    x: 1.0,
                    y: -2.0,
                    yaw: 0.7,
                },
            )
            .unwrap();
        for r in 0..9 {
            for c in 0..7 {
                let (x, y) = g.cell_to_world(c, r);
                assert_eq!(g.world_to_cell(x, y), Some((c, r)));
            }
        }
    }

    #[test]
    fn refuses_bad_sizes_and_frames() {
        assert!(matches!(
            OccupancyGrid::new(0, 3),
            Err(MapError::Empty { .. })
        ));
        assert!(matches!(
            OccupancyGrid::new(100_000, 100_001),
            Err(MapError::TooLarge { .. })
        ));
        assert!(matches!(
            OccupancyGrid::from_cells(2, 2, vec![Cell::Free; 3]),
            Err(MapError::SizeMismatch { .. })
        ));
        let g = OccupancyGrid::new(2, 2).unwrap();
        assert!(matches!(
            g.clone().with_frame(f64::NAN, Pose2::default()),
            Err(MapError::BadResolution(_))
        ));
        assert!(matches!(
            g.with_frame(
                0.1,
                Pose2 {
                    x: f64::INFINITY,
                    y: 0.0,
                    yaw: 0.0
                }
            ),
            Err(MapError::BadOrigin { .. })
        ));
    }

    #[test]
    fn paint_segment_marks_the_crossed_cells() {
        let mut g = OccupancyGrid::new(5, 3).unwrap();
        assert_eq!(g.paint_segment((0, 0), (4, 2), Cell::Occupied), Ok(7));
        // The supercover: every cell the segment touches.
        assert_eq!(g.to_ascii(), "##...\n.###.\n...##\n");
        // Painting again changes nothing; erasing restores.
        assert_eq!(g.paint_segment((0, 0), (4, 2), Cell::Occupied), Ok(0));
        assert_eq!(g.paint_segment((4, 2), (0, 0), Cell::Free), Ok(7));
        assert!(matches!(
            g.paint_segment((0, 0), (5, 0), Cell::Occupied),
            Err(MapError::OutOfBounds { col: 5, .. })
        ));
    }

    #[test]
    fn ascii_round_trip_and_errors() {
        let g = OccupancyGrid::from_ascii("\n.#?\n#..\n\n").unwrap();
        assert_eq!(g.to_ascii(), ".#?\n#..\n");
        assert_eq!(g.counts(), (3, 2, 1));
        assert!(matches!(
            OccupancyGrid::from_ascii("..\n...\n"),
            Err(MapError::Parse { line: 2, .. })
        ));
        assert!(matches!(
            OccupancyGrid::from_ascii(".x\n"),
            Err(MapError::Parse { .. })
        ));
        assert!(matches!(
            OccupancyGrid::from_ascii("\n\n"),
            Err(MapError::Empty { .. })
        ));
    }
}
