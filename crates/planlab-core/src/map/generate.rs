//! Seeded random maps for the playground and for experiments: a perfect
//! maze, rooms joined by doors, and random fill.
//!
//! Generation is pure and seeded with [`crate::num::Rng`], so the same
//! [`GenerateConfig`] gives the same grid natively and in WebAssembly
//! (compare [`OccupancyGrid::content_hash`]). Every map comes with a start
//! and a goal that a disc robot of `robot_radius` can drive between: both
//! are cells of the largest connected region of cells whose centre keeps
//! `robot_radius + resolution` from every wall and the map edge, the start
//! near the bottom-left corner, the goal near the top-right corner, each
//! moved from the corner cell up the clearance field to the middle of its
//! corridor or room (where the robot can turn and drive off).

use serde::{Deserialize, Serialize};
use thiserror::Error;

use super::costmap::distance_field;
use super::{check_dimensions, Cell, MapError, OccupancyGrid, Pose2};
use crate::num::Rng;

/// Generated maps are refused above this many cells (a slip of the
/// resolution field must not hang the page).
pub const GENERATE_MAX_CELLS: u64 = 4_000_000;

/// Which generator.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum GeneratorKind {
    /// A perfect maze (exactly one way between any two corridors),
    /// randomised depth-first carving.
    #[default]
    Maze,
    /// Rooms by recursive division, each dividing wall with a door.
    Rooms,
    /// Square blocks dropped independently with probability `density`.
    Random,
}

impl GeneratorKind {
    /// The kebab-case name (`maze`, `rooms`, `random`).
    pub fn as_str(self) -> &'static str {
        match self {
            GeneratorKind::Maze => "maze",
            GeneratorKind::Rooms => "rooms",
            GeneratorKind::Random => "random",
        }
    }
}

/// What to generate. Everything in metres, so the same numbers mean the
/// same world at any resolution.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct GenerateConfig {
    /// Which generator.
    pub kind: GeneratorKind,
    /// Map width, m.
    pub width_m: f64,
    /// Map height, m.
    pub height_m: f64,
    /// Cell size, m.
    pub resolution: f64,
    /// Seed of the generator; equal seeds give equal maps.
    pub seed: u64,
    /// Maze corridor width and rooms door width, m.
    pub corridor_m: f64,
    /// Wall thickness of mazes and rooms, m.
    pub wall_m: f64,
    /// Smallest room side for `rooms`, m.
    pub room_m: f64,
    /// Fraction of the area random fill covers, 0 to 0.6.
    pub density: f64,
    /// Side of one random-fill block, m.
    pub block_m: f64,
    /// Radius of the robot that must fit between start and goal, m.
    pub robot_radius: f64,
}

impl Default for GenerateConfig {
    fn default() -> Self {
        Self {
            kind: GeneratorKind::Maze,
            width_m: 10.0,
            height_m: 8.0,
            resolution: 0.1,
            seed: 0,
            corridor_m: 1.4,
            wall_m: 0.2,
            room_m: 2.5,
            density: 0.2,
            block_m: 0.4,
            robot_radius: 0.2,
        }
    }
}

/// Draws of a random fill before settling for the farthest start–goal pair.
const RANDOM_ATTEMPTS: u64 = 16;

/// The most random fill can cover: denser fills leave no room to drive.
pub const MAX_DENSITY: f64 = 0.6;

/// Why a map could not be generated.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum GenerateError {
    /// A number is NaN, infinite or out of range; the text names it.
    #[error("invalid generator setting: {}", crate::text::one_line(.0))]
    InvalidParameter(String),
    /// Random-fill density outside [0, [`MAX_DENSITY`]].
    #[error("density {}: must be a number from 0 to {MAX_DENSITY} (fraction of the area)", crate::num::fmt_num(*.0))]
    BadDensity(f64),
    /// The map is empty or larger than [`GENERATE_MAX_CELLS`].
    #[error(transparent)]
    Map(#[from] MapError),
    /// Corridors (or doors) too narrow for the robot.
    #[error("corridor {} m is too narrow for a robot of radius {} m at {} m per cell: at least {needed_m:.2} m", crate::num::fmt_num(*.corridor_m), crate::num::fmt_num(*.robot_radius), crate::num::fmt_num(*.resolution))]
    TooNarrow {
        /// The corridor width asked for, m.
        corridor_m: f64,
        /// The robot radius, m.
        robot_radius: f64,
        /// The resolution, m.
        resolution: f64,
        /// The narrowest corridor that works, m.
        needed_m: f64,
    },
    /// The map is too small for the structure asked for.
    #[error("a {} × {} m map is too small for {what}", crate::num::fmt_num(*.width_m), crate::num::fmt_num(*.height_m))]
    TooSmall {
        /// Map width, m.
        width_m: f64,
        /// Map height, m.
        height_m: f64,
        /// What does not fit.
        what: String,
    },
    /// No two cells the robot can stand on are connected.
    #[error("the generated map has no connected free space for a robot of radius {} m (seed {seed})", crate::num::fmt_num(*.robot_radius))]
    NoFreeSpace {
        /// The robot radius, m.
        robot_radius: f64,
        /// The seed.
        seed: u64,
    },
}

/// A generated map with its start and goal.
#[derive(Debug, Clone, PartialEq)]
pub struct GeneratedMap {
    /// The grid (origin (0, 0), the configured resolution).
    pub grid: OccupancyGrid,
    /// Start cell `(col, row)`, row 0 at the top.
    pub start_cell: (usize, usize),
    /// Goal cell `(col, row)`.
    pub goal_cell: (usize, usize),
    /// Start, world metres (the start cell's centre).
    pub start: [f64; 2],
    /// Goal, world metres (the goal cell's centre).
    pub goal: [f64; 2],
}

fn positive(name: &str, unit: &str, v: f64) -> Result<(), GenerateError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(GenerateError::InvalidParameter(format!(
            "{name} = {v} {unit}: must be a finite number > 0"
        )))
    }
}

/// Metres to a whole number of cells, at least 1.
fn cells(m: f64, res: f64) -> usize {
    ((m / res).round() as usize).max(1)
}

/// Row-major cells addressed by `(col, up)` with `up` counted from the
/// bottom row, so the generators think in world orientation.
struct Canvas {
    w: usize,
    h: usize,
    cells: Vec<Cell>,
}

impl Canvas {
    fn new(w: usize, h: usize, fill: Cell) -> Canvas {
        Canvas {
            w,
            h,
            cells: vec![fill; w * h],
        }
    }

    /// Sets the cells of `[c0, c1) × [u0, u1)` (clipped to the map).
    fn rect(&mut self, c0: usize, u0: usize, c1: usize, u1: usize, cell: Cell) {
        for u in u0..u1.min(self.h) {
            let row = self.h - 1 - u;
            for c in c0..c1.min(self.w) {
                self.cells[row * self.w + c] = cell;
            }
        }
    }
}

/// Generates the map `config` describes.
///
/// ```
/// use planlab_core::map::generate::{generate, GenerateConfig, GeneratorKind};
/// let c = GenerateConfig { kind: GeneratorKind::Maze, seed: 7, ..Default::default() };
/// let a = generate(&c).unwrap();
/// assert_eq!(a.grid.content_hash(), generate(&c).unwrap().grid.content_hash());
/// assert_ne!(a.start, a.goal);
/// ```
pub fn generate(config: &GenerateConfig) -> Result<GeneratedMap, GenerateError> {
    let c = config;
    positive("width_m", "m", c.width_m)?;
    positive("height_m", "m", c.height_m)?;
    positive("resolution", "m", c.resolution)?;
    positive("robot_radius", "m", c.robot_radius)?;
    let res = c.resolution;
    let (wf, hf) = ((c.width_m / res).round(), (c.height_m / res).round());
    if wf * hf > GENERATE_MAX_CELLS as f64 {
        return Err(MapError::TooLarge {
            width: wf as u64,
            height: hf as u64,
            cells: (wf * hf) as u64,
            max: GENERATE_MAX_CELLS,
        }
        .into());
    }
    let (w, h) = (wf as usize, hf as usize);
    check_dimensions(w as u64, h as u64)?;
    let mut rng = Rng::new(c.seed);
    // Random fill may leave start and goal close together (a small free
    // region): draw again, up to a limit, until they are at least half the
    // diagonal apart, else keep the farthest pair. Mazes and rooms always
    // pass on the first draw.
    let half_diagonal_cells2 = (w * w + h * h) / 4;
    type Draw = (usize, OccupancyGrid, (usize, usize), (usize, usize));
    let mut best: Option<Draw> = None;
    for attempt in 0..RANDOM_ATTEMPTS {
        let mut r = rng.fork(attempt);
        let canvas = match c.kind {
            GeneratorKind::Maze => maze(c, w, h, &mut r)?,
            GeneratorKind::Rooms => rooms(c, w, h, &mut r)?,
            GeneratorKind::Random => random_fill(c, w, h, &mut r)?,
        };
        let grid =
            OccupancyGrid::from_cells(w, h, canvas.cells)?.with_frame(res, Pose2::default())?;
        let Some((s, g)) = endpoints(&grid, c.robot_radius) else {
            continue;
        };
        let d2 = s.0.abs_diff(g.0).pow(2) + s.1.abs_diff(g.1).pow(2);
        if best.as_ref().map_or(true, |b| d2 > b.0) {
            best = Some((d2, grid, s, g));
        }
        if d2 >= half_diagonal_cells2 {
            break;
        }
    }
    let (_, grid, start_cell, goal_cell) = best.ok_or(GenerateError::NoFreeSpace {
        robot_radius: c.robot_radius,
        seed: c.seed,
    })?;
    let world = |(col, row): (usize, usize)| {
        let (x, y) = grid.cell_to_world(col, row);
        [x, y]
    };
    Ok(GeneratedMap {
        start: world(start_cell),
        goal: world(goal_cell),
        start_cell,
        goal_cell,
        grid,
    })
}

/// Corridor width in cells, checked against the robot.
fn corridor_cells(c: &GenerateConfig) -> Result<usize, GenerateError> {
    positive("corridor_m", "m", c.corridor_m)?;
    let k = cells(c.corridor_m, c.resolution);
    // A corridor of k cells has a middle cell keeping r + res from the
    // wall cells' centres when k ≥ 2·⌈r/res⌉ + 1 (see `endpoints`).
    let need = 2 * ((c.robot_radius / c.resolution).ceil() as usize) + 1;
    if k < need {
        return Err(GenerateError::TooNarrow {
            corridor_m: c.corridor_m,
            robot_radius: c.robot_radius,
            resolution: c.resolution,
            needed_m: need as f64 * c.resolution,
        });
    }
    Ok(k)
}

fn too_small(c: &GenerateConfig, what: String) -> GenerateError {
    GenerateError::TooSmall {
        width_m: c.width_m,
        height_m: c.height_m,
        what,
    }
}

/// A perfect maze: corridors `k` cells wide on a lattice of pitch
/// `k + t` (t = wall cells), carved by a randomised depth-first search.
fn maze(c: &GenerateConfig, w: usize, h: usize, rng: &mut Rng) -> Result<Canvas, GenerateError> {
    let k = corridor_cells(c)?;
    positive("wall_m", "m", c.wall_m)?;
    let t = cells(c.wall_m, c.resolution);
    let p = k + t;
    let nx = w.saturating_sub(t) / p;
    let ny = h.saturating_sub(t) / p;
    if nx * ny < 2 {
        return Err(too_small(
            c,
            format!("a maze with {} m corridors", c.corridor_m),
        ));
    }
    // Centre the lattice; the leftover margin stays wall.
    let ox = (w - (nx * p + t)) / 2 + t;
    let oy = (h - (ny * p + t)) / 2 + t;
    let mut canvas = Canvas::new(w, h, Cell::Occupied);
    let mut seen = vec![false; nx * ny];
    let mut stack = vec![(0usize, 0usize)];
    seen[0] = true;
    canvas.rect(ox, oy, ox + k, oy + k, Cell::Free);
    while let Some(&(i, j)) = stack.last() {
        let mut next = [(0usize, 0usize); 4];
        let mut n = 0;
        for (di, dj) in [(1i64, 0i64), (-1, 0), (0, 1), (0, -1)] {
            let (a, b) = (i as i64 + di, j as i64 + dj);
            if a >= 0 && b >= 0 && (a as usize) < nx && (b as usize) < ny {
                let (a, b) = (a as usize, b as usize);
                if !seen[b * nx + a] {
                    next[n] = (a, b);
                    n += 1;
                }
            }
        }
        if n == 0 {
            stack.pop();
            continue;
        }
        let (a, b) = next[(rng.next_u64() % n as u64) as usize];
        seen[b * nx + a] = true;
        let (x0, y0) = (ox + i.min(a) * p, oy + j.min(b) * p);
        // The cell, the neighbour and the wall between them.
        let (x1, y1) = (ox + i.max(a) * p + k, oy + j.max(b) * p + k);
        canvas.rect(x0, y0, x1, y1, Cell::Free);
        stack.push((a, b));
    }
    Ok(canvas)
}

/// Rooms by recursive division: split the longer side with a wall of `t`
/// cells at a random place leaving rooms of at least `room_m` on both
/// sides, cut a door of `corridor_m` in it, recurse. Doors are cleared
/// `k` cells deep on both sides at the end, so a later wall meeting one
/// cannot close it (clearing only adds passages).
fn rooms(c: &GenerateConfig, w: usize, h: usize, rng: &mut Rng) -> Result<Canvas, GenerateError> {
    let k = corridor_cells(c)?;
    positive("wall_m", "m", c.wall_m)?;
    positive("room_m", "m", c.room_m)?;
    let t = cells(c.wall_m, c.resolution);
    let m = cells(c.room_m, c.resolution).max(k);
    if w < 2 * m + t && h < 2 * m + t {
        return Err(too_small(c, format!("two rooms of {} m", c.room_m)));
    }
    let mut canvas = Canvas::new(w, h, Cell::Free);
    // Doors as rectangles [c0, c1) × [u0, u1) to clear at the end.
    let mut doors: Vec<[usize; 4]> = Vec::new();
    let mut regions = vec![[0usize, 0usize, w, h]];
    while let Some([c0, u0, c1, u1]) = regions.pop() {
        let (rw, rh) = (c1 - c0, u1 - u0);
        let can_v = rw >= 2 * m + t && rh >= k;
        let can_h = rh >= 2 * m + t && rw >= k;
        let vertical = match (can_v, can_h) {
            (false, false) => continue,
            (true, false) => true,
            (false, true) => false,
            (true, true) => {
                if rw == rh {
                    rng.next_u64() % 2 == 0
                } else {
                    rw > rh
                }
            }
        };
        let pick = |rng: &mut Rng, lo: usize, hi: usize| {
            lo + (rng.next_u64() % (hi - lo + 1) as u64) as usize
        };
        if vertical {
            // Wall columns [x, x + t), rooms of ≥ m on both sides.
            let x = pick(rng, c0 + m, c1 - m - t);
            canvas.rect(x, u0, x + t, u1, Cell::Occupied);
            let d = pick(rng, u0, u1 - k);
            canvas.rect(x, d, x + t, d + k, Cell::Free);
            doors.push([x.saturating_sub(k), d, x + t + k, d + k]);
            regions.push([c0, u0, x, u1]);
            regions.push([x + t, u0, c1, u1]);
        } else {
            let y = pick(rng, u0 + m, u1 - m - t);
            canvas.rect(c0, y, c1, y + t, Cell::Occupied);
            let d = pick(rng, c0, c1 - k);
            canvas.rect(d, y, d + k, y + t, Cell::Free);
            doors.push([d, y.saturating_sub(k), d + k, y + t + k]);
            regions.push([c0, u0, c1, y]);
            regions.push([c0, y + t, c1, u1]);
        }
    }
    for [c0, u0, c1, u1] in doors {
        canvas.rect(c0, u0, c1, u1, Cell::Free);
    }
    Ok(canvas)
}

/// Random fill: a lattice of `block_m` squares, each occupied with
/// probability `density`.
fn random_fill(
    c: &GenerateConfig,
    w: usize,
    h: usize,
    rng: &mut Rng,
) -> Result<Canvas, GenerateError> {
    if !(c.density.is_finite() && (0.0..=MAX_DENSITY).contains(&c.density)) {
        return Err(GenerateError::BadDensity(c.density));
    }
    positive("block_m", "m", c.block_m)?;
    let b = cells(c.block_m, c.resolution);
    let mut canvas = Canvas::new(w, h, Cell::Free);
    for u in (0..h).step_by(b) {
        for col in (0..w).step_by(b) {
            if rng.uniform() < c.density {
                canvas.rect(col, u, col + b, u + b, Cell::Occupied);
            }
        }
    }
    Ok(canvas)
}

/// Start and goal cells for a disc robot of `radius`: in the largest
/// 4-connected region of cells whose centres keep `radius + res` from
/// every occupied cell's centre and from the map edge (so the robot fits
/// anywhere in it with a cell of margin): from the region's cells nearest
/// the bottom-left and the top-right corner, each climbed (8-neighbour
/// steps to a larger clearance, same region) to a local top of the clearance field.
/// `None` when that region has fewer than two cells.
pub fn endpoints(grid: &OccupancyGrid, radius: f64) -> Option<((usize, usize), (usize, usize))> {
    let (w, h, res) = (grid.width(), grid.height(), grid.resolution());
    let need = radius + res;
    let dist = distance_field(grid);
    // Clearance of each cell's centre from walls and from the map edge.
    let clear: Vec<f64> = (0..w * h)
        .map(|i| {
            let (col, row) = (i % w, i / w);
            let edge = [col, w - 1 - col, row, h - 1 - row]
                .into_iter()
                .min()
                .unwrap_or(0) as f64
                + 0.5;
            dist[i].min(edge * res)
        })
        .collect();
    let ok: Vec<bool> = (0..w * h)
        .map(|i| grid.cells()[i] == Cell::Free && clear[i] >= need)
        .collect();
    let mut label = vec![usize::MAX; w * h];
    let mut best: Option<(usize, usize)> = None; // (label, size)
    let mut stack = Vec::new();
    let mut n_labels = 0;
    for s in 0..w * h {
        if !ok[s] || label[s] != usize::MAX {
            continue;
        }
        let id = n_labels;
        n_labels += 1;
        label[s] = id;
        stack.push(s);
        let mut size = 0;
        while let Some(i) = stack.pop() {
            size += 1;
            let (col, row) = (i % w, i / w);
            let mut visit = |j: usize| {
                if ok[j] && label[j] == usize::MAX {
                    label[j] = id;
                    stack.push(j);
                }
            };
            if col > 0 {
                visit(i - 1);
            }
            if col + 1 < w {
                visit(i + 1);
            }
            if row > 0 {
                visit(i - w);
            }
            if row + 1 < h {
                visit(i + w);
            }
        }
        if best.map_or(true, |(_, n)| size > n) {
            best = Some((id, size));
        }
    }
    let (id, size) = best?;
    if size < 2 {
        return None;
    }
    let mut start = (usize::MAX, 0usize);
    let mut goal = (usize::MAX, 0usize);
    for (i, _) in label.iter().enumerate().filter(|(_, &l)| l == id) {
        let (col, up) = (i % w, h - 1 - i / w);
        let d_start = col * col + up * up;
        let (gc, gu) = (w - 1 - col, h - 1 - up);
        let d_goal = gc * gc + gu * gu;
        if d_start < start.0 {
            start = (d_start, i);
        }
        if d_goal < goal.0 {
            goal = (d_goal, i);
        }
    }
    // The corner cells only just keep the margin (a robot there starts
    // wedged against two walls, and the DWA family sees no admissible
    // rollout): climb the clearance field to its local top, the middle of
    // the corridor or room.
    let climb = |mut i: usize| loop {
        let (col, row) = (i % w, i / w);
        let mut next = i;
        // 8 neighbours: off a corner only a diagonal step gains clearance.
        for (dc, dr) in [
            (-1i64, 0i64),
            (1, 0),
            (0, -1),
            (0, 1),
            (-1, -1),
            (1, -1),
            (-1, 1),
            (1, 1),
        ] {
            let (c, r) = (col as i64 + dc, row as i64 + dr);
            if c < 0 || r < 0 || c >= w as i64 || r >= h as i64 {
                continue;
            }
            let j = r as usize * w + c as usize;
            if label[j] == id && clear[j] > clear[next] {
                next = j;
            }
        }
        if next == i {
            return i;
        }
        i = next;
    };
    let (s, g) = (climb(start.1), climb(goal.1));
    let cell = |i: usize| (i % w, i / w);
    if s == g {
        return None;
    }
    Some((cell(s), cell(g)))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cfg(kind: GeneratorKind, seed: u64) -> GenerateConfig {
        GenerateConfig {
            kind,
            seed,
            ..Default::default()
        }
    }

    #[test]
    fn same_seed_same_map_other_seed_other_map() {
        for kind in [
            GeneratorKind::Maze,
            GeneratorKind::Rooms,
            GeneratorKind::Random,
        ] {
            let a = generate(&cfg(kind, 7)).unwrap();
            let b = generate(&cfg(kind, 7)).unwrap();
            let c = generate(&cfg(kind, 8)).unwrap();
            assert_eq!(a, b, "{kind:?}");
            assert_eq!(a.grid.content_hash(), b.grid.content_hash());
            assert_ne!(a.grid.content_hash(), c.grid.content_hash(), "{kind:?}");
        }
    }

    #[test]
    fn maze_is_perfect() {
        // A perfect maze on an nx × ny lattice is a spanning tree: with
        // corridor k and wall t the free cells number nx·ny·k² plus
        // (nx·ny − 1) passages of k·t cells.
        let c = GenerateConfig {
            width_m: 6.2,
            height_m: 4.2,
            corridor_m: 0.8,
            wall_m: 0.2,
            ..cfg(GeneratorKind::Maze, 3)
        };
        let g = generate(&c).unwrap();
        let (k, t) = (8usize, 2usize);
        let (nx, ny) = ((62 - t) / (k + t), (42 - t) / (k + t));
        assert_eq!((nx, ny), (6, 4));
        let free = g.grid.counts().0;
        assert_eq!(free, nx * ny * k * k + (nx * ny - 1) * k * t);
    }

    #[test]
    fn density_within_tolerance() {
        for density in [0.0, 0.1, 0.3, 0.5] {
            let c = GenerateConfig {
                width_m: 20.0,
                height_m: 20.0,
                density,
                ..cfg(GeneratorKind::Random, 5)
            };
            let g = generate(&c).unwrap();
            let (_, occ, _) = g.grid.counts();
            let got = occ as f64 / (g.grid.width() * g.grid.height()) as f64;
            assert!((got - density).abs() < 0.03, "{density}: {got}");
        }
    }

    #[test]
    fn bad_settings_are_typed_errors() {
        let bad = |c: GenerateConfig| generate(&c).unwrap_err();
        assert!(matches!(
            bad(GenerateConfig {
                density: 0.9,
                ..cfg(GeneratorKind::Random, 0)
            }),
            GenerateError::BadDensity(_)
        ));
        assert!(matches!(
            bad(GenerateConfig {
                density: f64::NAN,
                ..cfg(GeneratorKind::Random, 0)
            }),
            GenerateError::BadDensity(_)
        ));
        assert!(matches!(
            bad(GenerateConfig {
                width_m: -1.0,
                ..Default::default()
            }),
            GenerateError::InvalidParameter(_)
        ));
        assert!(matches!(
            bad(GenerateConfig {
                resolution: f64::NAN,
                ..Default::default()
            }),
            GenerateError::InvalidParameter(_)
        ));
        assert!(matches!(
            bad(GenerateConfig {
                width_m: 1e4,
                height_m: 1e4,
                ..Default::default()
            }),
            GenerateError::Map(MapError::TooLarge { .. })
        ));
        assert!(matches!(
            bad(GenerateConfig {
                corridor_m: 0.3,
                ..Default::default()
            }),
            GenerateError::TooNarrow { .. }
        ));
        assert!(matches!(
            bad(GenerateConfig {
                width_m: 1.0,
                height_m: 1.0,
                ..Default::default()
            }),
            GenerateError::TooSmall { .. }
        ));
        assert!(matches!(
            bad(GenerateConfig {
                width_m: 3.0,
                height_m: 3.0,
                ..cfg(GeneratorKind::Rooms, 0)
            }),
            GenerateError::TooSmall { .. }
        ));
        // A robot too big for any free space.
        assert!(matches!(
            bad(GenerateConfig {
                robot_radius: 3.0,
                density: 0.0,
                width_m: 4.0,
                height_m: 4.0,
                ..cfg(GeneratorKind::Random, 0)
            }),
            GenerateError::NoFreeSpace { .. }
        ));
    }

    #[test]
    fn rooms_have_walls_and_doors() {
        let g = generate(&GenerateConfig {
            width_m: 12.0,
            height_m: 10.0,
            ..cfg(GeneratorKind::Rooms, 2)
        })
        .unwrap();
        let (free, occ, _) = g.grid.counts();
        assert!(occ > 0 && free > occ);
    }
}
