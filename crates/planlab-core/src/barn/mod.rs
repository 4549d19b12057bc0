//! The BARN benchmark (Perille, Truong, Xiao, Stone, "Benchmarking Metric
//! Ground Navigation", IEEE SSRR 2020; the BARN Challenge at ICRA
//! 2022–2025): its 300 cylinder worlds as planlab data, and its score.
//!
//! A BARN world is a 30 × 30 grid of 0.15 m cells; every occupied cell is a
//! static cylinder of radius 0.075 m, and a U of 96 cylinders (the
//! containment wall) closes the ground behind the start. The robot starts
//! at [`START`] below the grid and must reach [`GOAL`], 10 m ahead, beyond
//! it. The worlds come as Gazebo SDF files ([`BarnWorld::from_sdf`]) with a
//! reference path per world as a numpy array ([`BarnWorld::path_from_npy`]);
//! planlab keeps them in a compact text form ([`parse_compact`],
//! [`to_compact`]; the repository's `assets/barn/worlds.txt` holds the
//! 250 public worlds and says where they come from). [`run`] drives the
//! planners on them and [`run::BarnStats`] gives the challenge's figures
//! over a set of runs. This module reads no file: callers pass bytes or
//! text.
//!
//! The facts below come from the challenge repository
//! (`Daffan/the-barn-challenge`: its evaluation script, called "the run
//! script" below, and the Jackal's description and move_base
//! configuration) and from the world generator
//! (`dperille/jackal-map-creation`: its world writer and dataset script).

mod compact;
mod npy;
pub mod run;
mod sdf;

pub use compact::{parse_compact, to_compact};

use thiserror::Error;

use crate::map::{Cell, MapError, OccupancyGrid, Pose2};
use crate::world::Footprint;

/// Cells per side of a world's grid.
pub const GRID: usize = 30;
/// Width of a grid cell and spacing of the cylinders, metres.
pub const CELL: f64 = 0.15;
/// Radius of every cylinder, metres.
pub const RADIUS: f64 = 0.075;
/// World x of grid row 0 (row r sits at `GRID_X0 + CELL·r`;
/// the generator's world writer).
pub const GRID_X0: f64 = -4.425;
/// World y of grid column 0 (column c sits at `GRID_Y0 + CELL·c`).
pub const GRID_Y0: f64 = 5.175;
/// Cylinders below this y form the containment wall, not the grid.
pub const WALL_Y_MAX: f64 = 5.1;
/// World x of a reference-path cell's row 0 (the run script:
/// x = 0.15·row − 4.575). The path's frame is the grid's shifted by
/// (−0.15, −0.1) m; the run script measures the path length in it, so
/// planlab does too.
pub const PATH_X0: f64 = -4.575;
/// World y of a reference-path cell's column 0 (y = 0.15·col + 5.075).
pub const PATH_Y0: f64 = 5.075;

/// Start pose (x, y, yaw) of every world (the run script).
pub const START: Pose2 = Pose2 {
    x: -2.25,
    y: 3.0,
    yaw: 1.57,
};
/// Goal of every world: the start moved 10 m along y (the run script).
pub const GOAL: [f64; 2] = [-2.25, 13.0];
/// A run succeeds within this distance of [`GOAL`], metres (the run script).
pub const GOAL_TOLERANCE: f64 = 1.0;
/// A run times out after this much simulated time, seconds (the run script).
pub const TIMEOUT: f64 = 100.0;
/// The speed that turns a reference path length into the optimal time
/// OT, m/s (the run script: OT = path length / 2).
pub const OT_SPEED: f64 = 2.0;

/// Length of the Clearpath Jackal's footprint rectangle, metres (the
/// challenge's move_base costmap `footprint`:
/// `[[-0.21,-0.165],[-0.21,0.165],[0.21,0.165],[0.21,-0.165]]`).
pub const JACKAL_LENGTH: f64 = 0.42;
/// Width of the Jackal's footprint rectangle, metres (same source).
pub const JACKAL_WIDTH: f64 = 0.33;
/// The Jackal's footprint, a [`JACKAL_LENGTH`] × [`JACKAL_WIDTH`]
/// rectangle centred on the robot.
pub const JACKAL_FOOTPRINT: Footprint = Footprint::Rectangle {
    length: JACKAL_LENGTH,
    width: JACKAL_WIDTH,
};
/// The costmaps' `footprint_padding` around the Jackal, metres.
pub const JACKAL_PADDING: f64 = 0.1;
/// Field of view of the Jackal's Hokuyo UST-10 laser, degrees.
pub const LASER_FOV_DEG: f64 = 270.0;
/// Angular step of the UST-10 laser, degrees.
pub const LASER_STEP_DEG: f64 = 0.25;
/// Maximum range of the UST-10 laser, metres.
pub const LASER_RANGE: f64 = 30.0;

/// Default resolution of [`BarnWorld::grid`], metres per cell: a sixth of
/// a cylinder's diameter, fine enough that the conservative rasterisation
/// adds at most a cell diagonal (3.5 cm) to a cylinder.
pub const TRUTH_RESOLUTION: f64 = 0.025;
/// Free ground [`BarnWorld::grid`] keeps around every cylinder, the start
/// and the goal, metres: planlab counts the map's outside as a wall, while
/// BARN's ground is open there, and the goal region reaches 1 m beyond
/// the goal.
pub const MAP_MARGIN: f64 = 1.5;

/// Occupied cells (of 900, after filling interiors) up to which a world
/// is [`Difficulty::Easy`]: the lower tercile of the 250 public worlds.
pub const EASY_MAX_CELLS: usize = 138;
/// Occupied cells up to which a world is [`Difficulty::Medium`] (the upper
/// tercile boundary of the 250 public worlds); above it, `Hard`.
pub const MEDIUM_MAX_CELLS: usize = 206;

/// Errors of reading BARN worlds and paths.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum BarnError {
    /// The SDF bytes are not UTF-8.
    #[error("BARN world {id}: the SDF is not UTF-8 text")]
    NotUtf8 {
        /// World id.
        id: u32,
    },
    /// The SDF is not well-formed XML.
    #[error("BARN world {id}: bad XML: {message}")]
    Xml {
        /// World id.
        id: u32,
        /// The XML parser's message.
        message: String,
    },
    /// The SDF lacks an element BARN worlds have.
    #[error("BARN world {id}: no <{element}> element")]
    Missing {
        /// World id.
        id: u32,
        /// What is missing (`world`, a model's `pose` …).
        element: String,
    },
    /// A cylinder's pose or radius is not what BARN worlds hold.
    #[error("BARN world {id}: model '{model}': {message}")]
    BadModel {
        /// World id.
        id: u32,
        /// Model name.
        model: String,
        /// What is wrong.
        message: String,
    },
    /// The world has no cylinder.
    #[error("BARN world {id}: no unit_cylinder model")]
    NoCylinders {
        /// World id.
        id: u32,
    },
    /// A reference path file is not a numpy int64 (n, 2) array.
    #[error("BARN path: {0}")]
    Npy(String),
    /// A line of the compact form is malformed.
    #[error("BARN compact form, line {line}: {message}")]
    Compact {
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// The occupancy grid could not be built.
    #[error("BARN grid: {0}")]
    Map(#[from] MapError),
}

/// A BARN world: its grid of cylinders, containment wall and reference path.
#[derive(Debug, Clone, PartialEq)]
pub struct BarnWorld {
    /// The world's number N (`world_N.world`).
    pub id: u32,
    /// Occupied flags, `cells[row][col]`, after filling the interiors the
    /// generator leaves out (see [`BarnWorld::from_sdf`]).
    pub cells: [[bool; GRID]; GRID],
    /// Centres of the containment-wall cylinders (y < [`WALL_Y_MAX`]),
    /// world frame, sorted by x then y.
    pub wall: Vec<[f64; 2]>,
    /// Reference path cells (row, col) (`path_N.npy`); empty until set.
    pub path: Vec<[i64; 2]>,
}

/// A world's difficulty class, from how much of its grid is occupied.
///
/// The generator's dataset script drew each world from one of 12
/// parameter sets (initial fill 0.15–0.30, 2–4 smoothing iterations), but
/// the files do not record which. (The mean fill of the public worlds
/// rises with N / 75 — 0.146, 0.188, 0.226, 0.235 — as if the ids kept the
/// script's order, but the spread within a block is wide and the order is
/// documented nowhere, so the id is not used.) The class is defined from
/// what the files measure: the number of occupied grid cells after filling interiors
/// ([`BarnWorld::occupied_cells`], the two always-full side rows
/// included), cut at the terciles of the 250 public worlds: `Easy` up to
/// [`EASY_MAX_CELLS`], `Medium` up to [`MEDIUM_MAX_CELLS`], `Hard` above.
/// It is a measure of clutter only, not of the paper's path-based
/// difficulty metrics.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Difficulty {
    /// At most [`EASY_MAX_CELLS`] occupied cells.
    Easy,
    /// More than [`EASY_MAX_CELLS`], at most [`MEDIUM_MAX_CELLS`].
    Medium,
    /// More than [`MEDIUM_MAX_CELLS`] occupied cells.
    Hard,
}

impl Difficulty {
    /// Every class, easiest first.
    pub const ALL: [Difficulty; 3] = [Difficulty::Easy, Difficulty::Medium, Difficulty::Hard];

    /// Lower-case name: `easy`, `medium`, `hard`.
    pub fn name(self) -> &'static str {
        match self {
            Difficulty::Easy => "easy",
            Difficulty::Medium => "medium",
            Difficulty::Hard => "hard",
        }
    }
}

/// World centre of grid cell (row, col).
pub fn cell_centre(row: usize, col: usize) -> [f64; 2] {
    [GRID_X0 + CELL * row as f64, GRID_Y0 + CELL * col as f64]
}

/// The BARN score of one run: `success · OT / clip(T, 2·OT, 8·OT)`
/// (the run script), at most 0.5.
///
/// A failed run scores 0. So does a run whose time or optimal time makes
/// no sense (NaN time, OT not a positive finite number), rather than
/// spreading NaN into a mean; a time below 2·OT (even ≤ 0) counts as
/// 2·OT and an infinite one as 8·OT, as the clip says.
pub fn score(success: bool, time: f64, ot: f64) -> f64 {
    if !success || time.is_nan() || !(ot.is_finite() && ot > 0.0) {
        return 0.0;
    }
    ot / time.clamp(2.0 * ot, 8.0 * ot)
}

impl BarnWorld {
    /// Centres of every cylinder, world frame: the grid's occupied cells
    /// (filled interiors included) row by row, then the wall.
    pub fn cylinders(&self) -> Vec<[f64; 2]> {
        let mut out = Vec::with_capacity(self.occupied_cells() + self.wall.len());
        for (r, row) in self.cells.iter().enumerate() {
            for (c, &occ) in row.iter().enumerate() {
                if occ {
                    out.push(cell_centre(r, c));
                }
            }
        }
        out.extend_from_slice(&self.wall);
        out
    }

    /// Number of occupied grid cells (of 900).
    pub fn occupied_cells(&self) -> usize {
        self.cells.iter().flatten().filter(|&&o| o).count()
    }

    /// Occupied share of the grid, 0…1.
    pub fn fill_fraction(&self) -> f64 {
        self.occupied_cells() as f64 / (GRID * GRID) as f64
    }

    /// The difficulty class (see [`Difficulty`] for its definition).
    pub fn difficulty(&self) -> Difficulty {
        match self.occupied_cells() {
            n if n <= EASY_MAX_CELLS => Difficulty::Easy,
            n if n <= MEDIUM_MAX_CELLS => Difficulty::Medium,
            _ => Difficulty::Hard,
        }
    }

    /// The reference path as world points: the start, each path cell
    /// mapped by x = 0.15·row − 4.575, y = 0.15·col + 5.075, the goal
    /// (the run script).
    pub fn reference_path(&self) -> Vec<[f64; 2]> {
        let mut pts = Vec::with_capacity(self.path.len() + 2);
        pts.push([START.x, START.y]);
        pts.extend(
            self.path
                .iter()
                .map(|&[r, c]| [PATH_X0 + CELL * r as f64, PATH_Y0 + CELL * c as f64]),
        );
        pts.push(GOAL);
        pts
    }

    /// Length of [`BarnWorld::reference_path`], metres.
    pub fn path_length(&self) -> f64 {
        self.reference_path()
            .windows(2)
            .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]))
            .sum()
    }

    /// The optimal time OT = path length / [`OT_SPEED`], seconds.
    pub fn optimal_time(&self) -> f64 {
        self.path_length() / OT_SPEED
    }

    /// The world as an occupancy grid at `resolution` metres per cell,
    /// unrotated, covering every cylinder, the start and the goal with
    /// [`MAP_MARGIN`] of free ground around them.
    ///
    /// The cylinders are rasterised conservatively: a cell is occupied
    /// when its square comes within the radius of a centre, so every
    /// point of every cylinder lies in an occupied cell, and the occupied
    /// cells reach at most one cell diagonal beyond a cylinder. (Cells
    /// that would touch a disc only at a tangent point are left out — a
    /// nanometre of tolerance, so floating point does not decide them at
    /// random; the neighbouring cell covers that point.)
    /// Use [`TRUTH_RESOLUTION`] for ground truth.
    pub fn grid(&self, resolution: f64) -> Result<OccupancyGrid, BarnError> {
        if !(resolution.is_finite() && resolution > 0.0) {
            return Err(MapError::BadResolution(resolution).into());
        }
        let cyl = self.cylinders();
        let (mut lo, mut hi) = (
            [START.x.min(GOAL[0]), START.y.min(GOAL[1])],
            [START.x.max(GOAL[0]), START.y.max(GOAL[1])],
        );
        for p in &cyl {
            for k in 0..2 {
                lo[k] = lo[k].min(p[k] - RADIUS);
                hi[k] = hi[k].max(p[k] + RADIUS);
            }
        }
        // The frame snaps to whole cells so equal worlds give equal grids.
        let first = lo.map(|v| ((v - MAP_MARGIN) / resolution).floor());
        let last = hi.map(|v| ((v + MAP_MARGIN) / resolution).ceil());
        let (w, h) = (last[0] - first[0], last[1] - first[1]);
        crate::map::check_dimensions(w as u64, h as u64)?;
        let (w, h) = (w as usize, h as usize);
        let origin = Pose2 {
            x: first[0] * resolution,
            y: first[1] * resolution,
            yaw: 0.0,
        };
        let mut cells = vec![Cell::Free; w * h];
        let reach = RADIUS - 1e-9;
        for p in &cyl {
            // Cell columns/"ups" (counted from the bottom) the disc can touch.
            let span = |k: usize, o: f64| {
                let a = ((p[k] - RADIUS - o) / resolution).floor().max(0.0) as usize;
                let b = ((p[k] + RADIUS - o) / resolution).floor() as usize;
                (a, b)
            };
            let ((c0, c1), (u0, u1)) = (span(0, origin.x), span(1, origin.y));
            for u in u0..=u1.min(h - 1) {
                let (y0, y1) = (
                    origin.y + u as f64 * resolution,
                    origin.y + (u + 1) as f64 * resolution,
                );
                let dy = (y0 - p[1]).max(p[1] - y1).max(0.0);
                for c in c0..=c1.min(w - 1) {
                    let (x0, x1) = (
                        origin.x + c as f64 * resolution,
                        origin.x + (c + 1) as f64 * resolution,
                    );
                    let dx = (x0 - p[0]).max(p[0] - x1).max(0.0);
                    if dx.hypot(dy) < reach {
                        cells[(h - 1 - u) * w + c] = Cell::Occupied;
                    }
                }
            }
        }
        Ok(OccupancyGrid::from_cells(w, h, cells)?.with_frame(resolution, origin)?)
    }
}

#[cfg(test)]
mod tests;
