//! Obstacle inflation and a ROS-style decaying costmap (docs/algorithms.md §inflation).
//!
//! Both rest on [`distance_field`]: the exact Euclidean distance from every
//! cell centre to the nearest occupied cell centre, computed in O(N) with the
//! separable algorithm of Felzenszwalb & Huttenlocher ("Distance Transforms
//! of Sampled Functions", 2012). The first pass (along columns) is a pair of
//! row-by-row sweeps, the second the lower envelope of parabolas along each
//! row, so both passes read memory in order.
//!
//! "Within a radius" means distance ≤ radius with a relative tolerance of
//! 1e-9, so that a radius which is a whole number of cells in decimal (0.15 m
//! at 0.05 m per cell) includes the cell exactly that far away despite
//! binary rounding.

use crate::map::{Cell, MapError, OccupancyGrid};

/// Relative tolerance of the "within radius" test (see the module docs).
const RADIUS_TOLERANCE: f64 = 1e-9;

/// ROS `costmap_2d` cost of an occupied cell (LETHAL_OBSTACLE).
pub const LETHAL: u8 = 254;
/// ROS cost of a cell whose centre lies within the inscribed radius of an
/// obstacle (INSCRIBED_INFLATED_OBSTACLE): the robot centred there collides.
pub const INSCRIBED: u8 = 253;
/// ROS cost of an unknown cell (NO_INFORMATION).
pub const NO_INFORMATION: u8 = 255;
/// ROS cost of free space far from obstacles (FREE_SPACE).
pub const FREE_SPACE: u8 = 0;

/// Squared distance in cells from each cell centre to the nearest occupied
/// cell centre, `f64::INFINITY` when the grid has no occupied cell. Exact
/// (whole numbers), row-major; unknown cells are not obstacles.
pub fn squared_cell_distances(grid: &OccupancyGrid) -> Vec<f64> {
    let w = grid.width();
    let cells = grid.cells();
    // Pass 1, along columns: distance to the nearest occupied cell in the
    // same column, by a downward and an upward sweep over whole rows.
    let mut col = vec![f64::INFINITY; cells.len()];
    let mut run = vec![f64::INFINITY; w];
    for (out, row) in col.chunks_exact_mut(w).zip(cells.chunks_exact(w)) {
        for ((o, r), c) in out.iter_mut().zip(run.iter_mut()).zip(row) {
            *r = if *c == Cell::Occupied { 0.0 } else { *r + 1.0 };
            *o = *r;
        }
    }
    run.fill(f64::INFINITY);
    for (out, row) in col.chunks_exact_mut(w).zip(cells.chunks_exact(w)).rev() {
        for ((o, r), c) in out.iter_mut().zip(run.iter_mut()).zip(row) {
            *r = if *c == Cell::Occupied { 0.0 } else { *r + 1.0 };
            // Square here: pass 2 works on squared distances.
            let d = o.min(*r);
            *o = d * d;
        }
    }
    // Pass 2, along rows: lower envelope of parabolas.
    let mut f = vec![0.0; w];
    let mut v = Vec::with_capacity(w);
    let mut z = Vec::with_capacity(w);
    for row in col.chunks_exact_mut(w) {
        f.copy_from_slice(row);
        edt_1d(&f, row, &mut v, &mut z);
    }
    col
}

/// One-dimensional squared distance transform of `f` (Felzenszwalb &
/// Huttenlocher, Algorithm 1): `out[q] = min_p (q − p)² + f[p]`. Infinite
/// samples are not sites, so an all-infinite input gives all infinity.
/// `v` and `z` are scratch buffers, resized here.
fn edt_1d(f: &[f64], out: &mut [f64], v: &mut Vec<usize>, z: &mut Vec<f64>) {
    let n = f.len().min(out.len());
    v.clear();
    v.resize(n, 0);
    z.clear();
    z.resize(n + 1, f64::INFINITY);
    // v[..=k]: sites of the lower envelope; z[i]: where parabola i starts.
    let mut k: Option<usize> = None;
    for q in 0..n {
        let fq = f[q];
        if !fq.is_finite() {
            continue;
        }
        let qf = q as f64;
        let mut s = f64::NEG_INFINITY;
        while let Some(kk) = k {
            let p = v[kk];
            let pf = p as f64;
            s = ((fq + qf * qf) - (f[p] + pf * pf)) / (2.0 * (qf - pf));
            // z[0] is −∞, so the first parabola is never popped.
            if s <= z[kk] {
                k = kk.checked_sub(1);
                s = f64::NEG_INFINITY;
            } else {
                break;
            }
        }
        let kk = k.map_or(0, |kk| kk + 1);
        v[kk] = q;
        z[kk] = s;
        z[kk + 1] = f64::INFINITY;
        k = Some(kk);
    }
    let Some(last) = k else {
        out[..n].fill(f64::INFINITY);
        return;
    };
    let mut j = 0;
    for (q, o) in out[..n].iter_mut().enumerate() {
        let qf = q as f64;
        while j < last && z[j + 1] < qf {
            j += 1;
        }
        let p = v[j];
        let d = qf - p as f64;
        *o = d * d + f[p];
    }
}

/// Metres from each cell centre to the nearest occupied cell centre,
/// row-major like [`OccupancyGrid::cells`]; 0 on occupied cells and
/// `f64::INFINITY` everywhere when nothing is occupied. Unknown cells are not
/// obstacles. Exact (no chamfer approximation) and O(width × height).
///
/// ```
/// use planlab_core::map::{costmap::distance_field, OccupancyGrid};
/// let g = OccupancyGrid::from_ascii("#...\n....\n").unwrap();
/// let d = distance_field(&g);
/// assert_eq!(d[0], 0.0);
/// assert_eq!(d[3], 3.0);
/// assert!((d[4 + 2] - 5f64.sqrt()).abs() < 1e-12);
/// ```
pub fn distance_field(grid: &OccupancyGrid) -> Vec<f64> {
    let res = grid.resolution();
    let mut d = squared_cell_distances(grid);
    for x in &mut d {
        *x = x.sqrt() * res;
    }
    d
}

/// A one-line note when inflating by `radius_m` changes nothing on a grid
/// of `resolution` m cells: inflation marks cells whose *centre* lies within
/// the radius of an occupied cell's centre, and the nearest centres are one
/// cell apart, so 0 < radius < 1 cell is silently a no-op otherwise.
///
/// ```
/// use planlab_core::map::costmap::inflation_note;
/// assert_eq!(inflation_note(0.8, 1.0).unwrap(), "0.8 m inflation < 1 cell (1 m): no effect");
/// assert_eq!(inflation_note(0.0, 1.0), None);
/// assert_eq!(inflation_note(1.0, 1.0), None);
/// ```
pub fn inflation_note(radius_m: f64, resolution: f64) -> Option<String> {
    let r = radius_m / resolution;
    (radius_m > 0.0 && r * r * (1.0 + RADIUS_TOLERANCE) < 1.0).then(|| {
        format!(
            "{} m inflation < 1 cell ({} m): no effect",
            crate::num::fmt_num(radius_m),
            crate::num::fmt_num(resolution)
        )
    })
}

/// Checks that a radius is finite and ≥ 0.
fn check_radius(what: &str, r: f64) -> Result<(), MapError> {
    if r.is_finite() && r >= 0.0 {
        Ok(())
    } else {
        Err(MapError::InvalidParameter(format!(
            "{what} {r} m must be a finite number ≥ 0"
        )))
    }
}

/// `radius_m` in cells, squared and widened by the tolerance, for comparing
/// against squared cell distances.
fn squared_cells(radius_m: f64, resolution: f64) -> f64 {
    let r = radius_m / resolution;
    r * r * (1.0 + RADIUS_TOLERANCE)
}

/// Grows obstacles by `radius_m`: every cell whose centre is within
/// `radius_m` of an occupied cell's centre becomes occupied. Unknown cells
/// stay unknown unless they are inflated. Radius 0 returns the grid
/// unchanged; a radius that is NaN, infinite or negative is an error.
///
/// ```
/// use planlab_core::map::{costmap::inflate, OccupancyGrid};
/// let g = OccupancyGrid::from_ascii(".....\n..#..\n.....\n").unwrap();
/// assert_eq!(inflate(&g, 1.0).unwrap().to_ascii(), "..#..\n.###.\n..#..\n");
/// ```
pub fn inflate(grid: &OccupancyGrid, radius_m: f64) -> Result<OccupancyGrid, MapError> {
    check_radius("inflate radius", radius_m)?;
    if radius_m == 0.0 {
        return Ok(grid.clone());
    }
    let limit = squared_cells(radius_m, grid.resolution());
    let d2 = squared_cell_distances(grid);
    let cells = grid
        .cells()
        .iter()
        .zip(&d2)
        .map(|(&c, &d)| if d <= limit { Cell::Occupied } else { c })
        .collect();
    let out = OccupancyGrid::from_cells(grid.width(), grid.height(), cells)?
        .with_frame(grid.resolution(), grid.origin())?;
    // The cells left free keep their traversal weights.
    match grid.weights() {
        Some(w) => out.with_weights(w.to_vec()),
        None => Ok(out),
    }
}

/// A grid of ROS `costmap_2d` costs (0–255), row-major, row 0 at the top.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Costmap {
    /// Width in cells.
    pub width: usize,
    /// Height in cells.
    pub height: usize,
    /// One cost per cell: [`FREE_SPACE`] … 252 decaying, [`INSCRIBED`],
    /// [`LETHAL`], [`NO_INFORMATION`].
    pub costs: Vec<u8>,
}

impl Costmap {
    /// The costmap ROS `costmap_2d`'s inflation layer would build over a
    /// static layer holding `grid`, with distances in metres:
    ///
    /// - occupied → [`LETHAL`] (254);
    /// - centre within `inscribed_radius_m` of an obstacle → [`INSCRIBED`]
    ///   (253), unknown cells included (ROS default `inflate_unknown: false`
    ///   overwrites unknown only with inscribed or lethal costs);
    /// - free within `inflation_radius_m` → ⌊252·exp(−k·(d − r_inscribed))⌋
    ///   with `k = cost_scaling_factor` (1/m);
    /// - other free cells → [`FREE_SPACE`] (0), other unknown cells →
    ///   [`NO_INFORMATION`] (255).
    ///
    /// ROS stops inflating at ⌈r_inflation / resolution⌉ cells; here the cut
    /// is the exact radius, so a cell just beyond it costs 0 rather than a
    /// small positive value.
    ///
    /// Radii and `k` must be finite and ≥ 0, and the inscribed radius must
    /// not exceed the inflation radius.
    pub fn ros(
        grid: &OccupancyGrid,
        inscribed_radius_m: f64,
        inflation_radius_m: f64,
        cost_scaling_factor: f64,
    ) -> Result<Costmap, MapError> {
        check_radius("inscribed radius", inscribed_radius_m)?;
        check_radius("inflation radius", inflation_radius_m)?;
        if !(cost_scaling_factor.is_finite() && cost_scaling_factor >= 0.0) {
            return Err(MapError::InvalidParameter(format!(
                "cost scaling factor {cost_scaling_factor} must be a finite number ≥ 0 (1/m)"
            )));
        }
        if inscribed_radius_m > inflation_radius_m {
            return Err(MapError::InvalidParameter(format!(
                "inscribed radius {inscribed_radius_m} m must not exceed the inflation radius {inflation_radius_m} m"
            )));
        }
        let res = grid.resolution();
        let inscribed2 = squared_cells(inscribed_radius_m, res);
        let inflation2 = squared_cells(inflation_radius_m, res);
        let d2 = squared_cell_distances(grid);
        let costs = grid
            .cells()
            .iter()
            .zip(&d2)
            .map(|(&c, &d2)| match c {
                Cell::Occupied => LETHAL,
                _ if d2 <= inscribed2 => INSCRIBED,
                Cell::Unknown => NO_INFORMATION,
                Cell::Free if d2 <= inflation2 => {
                    let excess = (d2.sqrt() * res - inscribed_radius_m).max(0.0);
                    let factor = crate::num::exp(-cost_scaling_factor * excess);
                    // Truncation, as ROS's cast to unsigned char.
                    (f64::from(INSCRIBED - 1) * factor) as u8
                }
                Cell::Free => FREE_SPACE,
            })
            .collect();
        Ok(Costmap {
            width: grid.width(),
            height: grid.height(),
            costs,
        })
    }

    /// The cost at `(col, row)`, or `None` off the map.
    pub fn get(&self, col: usize, row: usize) -> Option<u8> {
        if col < self.width && row < self.height {
            self.costs.get(row * self.width + col).copied()
        } else {
            None
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edt_1d_matches_brute_force() {
        let inf = f64::INFINITY;
        let f = [inf, 4.0, inf, inf, 0.0, inf, 9.0, inf];
        let mut out = [0.0; 8];
        edt_1d(&f, &mut out, &mut Vec::new(), &mut Vec::new());
        for (q, &got) in out.iter().enumerate() {
            let brute = (0..8)
                .filter(|&p| f[p] < inf)
                .map(|p| (q as f64 - p as f64).powi(2) + f[p])
                .fold(inf, f64::min);
            assert_eq!(got, brute, "q = {q}");
        }
        edt_1d(&[inf; 3], &mut out[..3], &mut Vec::new(), &mut Vec::new());
        assert!(out[..3].iter().all(|x| x.is_infinite()));
    }
}
