//! An experiment's family of scenes: its preset plus seeded variants, each
//! a set of named perturbations drawn from fixed ranges.
//!
//! A perturbation edits the preset's JSON tree before the run's planner
//! and `--set` edits are applied, so one variant is the same scene for
//! every run of an experiment (the runs are *paired* by variant) and a
//! variant can be written out as an ordinary scenario file that `planlab
//! run` replays. Variant 0 is the preset as written; variant k ≥ 1 draws
//! from an [`Rng`] seeded by the family seed, k and the preset, so the
//! same (seed, k) gives the same scene on every target and thread.
//!
//! The ranges are fixed per experiment in its module, each with the reason
//! it keeps the paper's scene the same situation ([`Range::why`]): start
//! or goal moved 5–50 cm, a mover ±20 % speed, a block moved, another
//! seed, scaled to each scene's size; the potential-field scenes move
//! their points across the part of the 0.15 m repulsion range (or the
//! mover's offset band) that still is the paper's situation, and an
//! experiment's scene check ([`super::Experiment::scene`]) states that
//! situation as a test.

use serde::Serialize;
use serde_json::{json, Value};

use crate::map::{Cell, OccupancyGrid};
use crate::num::Rng;
use crate::scenario::{Scenario, ScenarioError};

/// One named perturbation of a preset.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum Perturbation {
    /// The scenario's `start` (or `goal`) moved uniformly within a disc of
    /// `radius_m` (its `world` point and cell both rewritten).
    Endpoint {
        /// `start` or `goal`.
        which: &'static str,
        /// Largest shift, m.
        radius_m: f64,
    },
    /// Every mover's path shifted by its own offset, uniform in a disc of
    /// `radius_m`, and its speed scaled by a factor uniform in
    /// [1 − `speed_rel`, 1 + `speed_rel`] (a still disc stays still).
    Movers {
        /// Largest shift, m.
        radius_m: f64,
        /// Largest relative speed change.
        speed_rel: f64,
    },
    /// Every potential-field obstacle (`apf.obstacles`) moved by its own
    /// offset, uniform in a disc (2D: x, y) or ball (3D) of `radius_m`,
    /// and its velocity scaled as for movers.
    ApfObstacles {
        /// Largest shift, m.
        radius_m: f64,
        /// Largest relative speed change.
        speed_rel: f64,
    },
    /// Every free-standing block of the inline map (a 4-connected group of
    /// occupied cells not touching the map's edge: the edge-connected
    /// walls are the room) moved by a whole number of cells, each axis
    /// uniform in −`cells` … `cells`. Blocks are moved in order; a block
    /// whose target overlaps another block's cells keeps its place.
    Blocks {
        /// Largest shift per axis, cells.
        cells: u32,
    },
    /// A point given as an array at a dotted path (`arm.goal`,
    /// `apf.start`) moved uniformly within a disc/ball of `radius_m`.
    Point {
        /// Dotted path of the `[x, y]` or `[x, y, z]` array.
        path: &'static str,
        /// Largest shift, m.
        radius_m: f64,
    },
    /// A number at a dotted path scaled by a factor uniform in
    /// [1 − `rel`, 1 + `rel`].
    Scale {
        /// Dotted path of the number.
        path: &'static str,
        /// Largest relative change.
        rel: f64,
    },
    /// The episode seed (noise, the hand's variation) replaced by the
    /// variant's own seed.
    Seed,
    /// A point moved by an offset uniform in a box, each axis in its own
    /// `[lo, hi]` (m; a zero-width axis keeps that coordinate): `start` or
    /// `goal` (2D, the scenario's endpoints), `apf.obstacles` (every
    /// potential-field obstacle's centre, its velocity scaled by a factor
    /// uniform in [1 − `speed_rel`, 1 + `speed_rel`]) or the dotted path of
    /// an `[x, y(, z)]` array (`apf.start`). Unlike a disc it can keep a
    /// point on a line or an offset within a band.
    Box {
        /// `start`, `goal`, `apf.obstacles` or a dotted path.
        what: &'static str,
        /// Offset range along x, m.
        x: [f64; 2],
        /// Offset range along y, m.
        y: [f64; 2],
        /// Offset range along z, m (3D points only).
        z: [f64; 2],
        /// Largest relative speed change (`apf.obstacles` only).
        speed_rel: f64,
    },
}

/// A perturbation with the reason its range keeps the paper's scene.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Range {
    /// The perturbation.
    #[serde(flatten)]
    pub perturbation: Perturbation,
    /// Why this range is the paper's situation (written before running).
    pub why: &'static str,
}

impl Perturbation {
    /// The scenario's start moved within `radius_m`.
    pub fn start(radius_m: f64) -> Perturbation {
        Perturbation::Endpoint {
            which: "start",
            radius_m,
        }
    }

    /// The scenario's goal moved within `radius_m`.
    pub fn goal(radius_m: f64) -> Perturbation {
        Perturbation::Endpoint {
            which: "goal",
            radius_m,
        }
    }

    /// This perturbation with the reason for its range.
    pub fn because(self, why: &'static str) -> Range {
        Range {
            perturbation: self,
            why,
        }
    }

    /// A short name for reports (`start`, `movers`, `arm.goal` …).
    pub fn name(&self) -> String {
        match self {
            Perturbation::Endpoint { which, .. } => (*which).to_string(),
            Perturbation::Box { what, .. } => (*what).to_string(),
            Perturbation::Movers { .. } => "movers".into(),
            Perturbation::ApfObstacles { .. } => "apf.obstacles".into(),
            Perturbation::Blocks { .. } => "blocks".into(),
            Perturbation::Point { path, .. } | Perturbation::Scale { path, .. } => {
                (*path).to_string()
            }
            Perturbation::Seed => "seed".into(),
        }
    }
}

/// A preset's variants: the perturbations applied to every variant k ≥ 1.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Family {
    /// Applied in order.
    pub perturbations: Vec<Range>,
}

/// Draws tried per variant before giving up: a draw is rejected when a
/// run cannot start (start or goal in a wall, on a mover …).
pub const MAX_DRAWS: u32 = 64;

/// Variants a family may have: enough for tight intervals, few enough
/// that a typo (`--variants 4294967295`) is an error, not hours of work.
pub const MAX_VARIANTS: u32 = 10_000;

/// The seed of variant `k` of a family seeded with `seed`; also the
/// variant's episode seed.
pub fn variant_seed(seed: u64, k: u32) -> u64 {
    crate::batch::variant_seed(seed, k)
}

/// FNV-1a of a text: separates the draws of an experiment's presets.
fn text_hash(s: &str) -> u64 {
    let mut h: u64 = 0xCBF2_9CE4_8422_2325;
    for &b in s.as_bytes() {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0000_0100_0000_01B3);
    }
    h
}

/// One drawn value, for the report of a variant.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Draw {
    /// What was changed (`start`, `mover 1 speed ×`, `block 2` …).
    pub what: String,
    /// The drawn value (an offset in m, a factor, a seed).
    pub value: Value,
    /// Index of the family's perturbation that drew it.
    pub of: usize,
}

impl Family {
    /// The perturbed tree of variant `k` (draw number `attempt`, 0 first)
    /// of `preset`, with the draws made. Variant 0 is the preset itself.
    pub fn apply(
        &self,
        preset: &Value,
        preset_text: &str,
        seed: u64,
        k: u32,
        attempt: u32,
    ) -> Result<(Value, Vec<Draw>), ScenarioError> {
        let mut tree = preset.clone();
        let mut draws = Vec::new();
        if k == 0 {
            return Ok((tree, draws));
        }
        let vseed = variant_seed(seed, k);
        let mut rng = Rng::new(vseed ^ text_hash(preset_text)).fork(u64::from(attempt));
        for (i, p) in self.perturbations.iter().enumerate() {
            let from = draws.len();
            apply_one(&p.perturbation, &mut tree, &mut rng, vseed, &mut draws)?;
            for d in &mut draws[from..] {
                d.of = i;
            }
        }
        Ok((tree, draws))
    }
}

fn bad(why: String) -> ScenarioError {
    ScenarioError::Invalid(why)
}

/// Uniform in the disc (`dims` = 2) or ball (3) of radius `r`, by
/// rejection from the cube (at most a few draws on average).
fn in_ball(rng: &mut Rng, r: f64, dims: usize) -> [f64; 3] {
    loop {
        let mut p = [0.0; 3];
        for x in p.iter_mut().take(dims) {
            *x = rng.range(-1.0, 1.0);
        }
        if p.iter().map(|x| x * x).sum::<f64>() <= 1.0 {
            return p.map(|x| x * r);
        }
    }
}

fn factor(rng: &mut Rng, rel: f64) -> f64 {
    rng.range(1.0 - rel, 1.0 + rel)
}

fn num(v: f64) -> Value {
    json!(v)
}

/// Value at a dotted path (array indices allowed), mutably.
fn at_path<'a>(tree: &'a mut Value, path: &str) -> Option<&'a mut Value> {
    let mut here = tree;
    for part in path.split('.') {
        here = match here {
            Value::Object(m) => m.get_mut(part)?,
            Value::Array(a) => a.get_mut(part.parse::<usize>().ok()?)?,
            _ => return None,
        };
    }
    Some(here)
}

/// Adds `d` to the numbers of an `[x, y(, z)]` array.
fn shift_array(v: &mut Value, d: [f64; 3]) -> bool {
    let Value::Array(a) = v else { return false };
    for (i, x) in a.iter_mut().enumerate().take(3) {
        let Some(f) = x.as_f64() else { return false };
        *x = num(f + d[i]);
    }
    true
}

fn scale_array(v: &mut Value, f: f64) {
    if let Value::Array(a) = v {
        for x in a.iter_mut() {
            if let Some(y) = x.as_f64() {
                *x = num(y * f);
            }
        }
    }
}

fn apply_one(
    p: &Perturbation,
    tree: &mut Value,
    rng: &mut Rng,
    vseed: u64,
    draws: &mut Vec<Draw>,
) -> Result<(), ScenarioError> {
    match *p {
        Perturbation::Seed => {
            tree["seed"] = json!(vseed);
            draws.push(Draw {
                what: "seed".into(),
                value: json!(vseed),
                of: 0,
            });
        }
        Perturbation::Endpoint { which, radius_m } => {
            let d = in_ball(rng, radius_m, 2);
            move_endpoint(tree, which, d)?;
            draws.push(Draw {
                what: format!("{which} shift m"),
                value: json!([d[0], d[1]]),
                of: 0,
            });
        }
        Perturbation::Movers {
            radius_m,
            speed_rel,
        } => {
            let Some(Value::Array(movers)) = tree.get_mut("movers") else {
                return Ok(());
            };
            for (i, m) in movers.iter_mut().enumerate() {
                let d = in_ball(rng, radius_m, 2);
                let f = factor(rng, speed_rel);
                let id = m.get("id").cloned().unwrap_or(json!(i));
                if let Some(motion) = m.get_mut("motion") {
                    shift_motion(motion, d, f);
                }
                draws.push(Draw {
                    what: format!("mover {id} shift m, speed ×"),
                    value: json!([d[0], d[1], f]),
                    of: 0,
                });
            }
        }
        Perturbation::ApfObstacles {
            radius_m,
            speed_rel,
        } => {
            move_apf_obstacles(tree, draws, |dims| {
                (in_ball(rng, radius_m, dims), factor(rng, speed_rel))
            });
        }
        Perturbation::Box {
            what,
            x,
            y,
            z,
            speed_rel,
        } => {
            let in_box = |rng: &mut Rng| [x, y, z].map(|[lo, hi]| rng.range(lo, hi));
            match what {
                "start" | "goal" => {
                    let d = in_box(rng);
                    move_endpoint(tree, what, d)?;
                    draws.push(Draw {
                        what: format!("{what} shift m"),
                        value: json!([d[0], d[1]]),
                        of: 0,
                    });
                }
                "apf.obstacles" => move_apf_obstacles(tree, draws, |_| {
                    let d = in_box(rng);
                    (d, factor(rng, speed_rel))
                }),
                path => shift_point(tree, path, draws, |_| in_box(rng))?,
            }
        }
        Perturbation::Point { path, radius_m } => {
            shift_point(tree, path, draws, |dims| in_ball(rng, radius_m, dims))?
        }
        Perturbation::Scale { path, rel } => {
            let v = at_path(tree, path)
                .ok_or_else(|| bad(format!("family: the preset has no `{path}`")))?;
            let x = v
                .as_f64()
                .ok_or_else(|| bad(format!("family: `{path}` is not a number")))?;
            let f = factor(rng, rel);
            *v = num(x * f);
            draws.push(Draw {
                what: format!("{path} ×"),
                value: json!(f),
                of: 0,
            });
        }
        Perturbation::Blocks { cells } => {
            let sc = Scenario::from_value(tree)?;
            let grid = sc
                .inline_grid()?
                .ok_or_else(|| bad("a family's preset needs an inline map".into()))?;
            let (moved, offsets) = shift_blocks(&grid, cells, rng)?;
            let written = serde_json::to_value(sc.with_inline_grid(moved))
                .map_err(|e| bad(format!("family: {e}")))?;
            tree["map"] = written["map"].clone();
            for (i, o) in offsets.into_iter().enumerate() {
                draws.push(Draw {
                    what: format!("block {i} shift cells"),
                    value: json!(o),
                    of: 0,
                });
            }
        }
    }
    Ok(())
}

/// Moves the scenario's `start` or `goal` by `d` (its world point and
/// cell); off the map the point stays, and the run check then rejects the
/// draw or not.
fn move_endpoint(tree: &mut Value, which: &str, d: [f64; 3]) -> Result<(), ScenarioError> {
    let sc = Scenario::from_value(tree)?;
    let grid = sc
        .inline_grid()?
        .ok_or_else(|| bad("a family's preset needs an inline map".into()))?;
    let w = if which == "start" {
        sc.start_world(&grid)
    } else {
        sc.goal_world(&grid)
    };
    let (x, y) = (w[0] + d[0], w[1] + d[1]);
    if let Some((col, row)) = grid.world_to_cell(x, y) {
        tree[which] = json!({"col": col, "row": row, "world": {"x": x, "y": y}});
    }
    Ok(())
}

/// Moves every obstacle of `apf.obstacles` (if the preset has any) by the
/// offset and speed factor `draw(dims)` gives it (`dims`: its centre's 2 or
/// 3 components) and records the draws.
fn move_apf_obstacles(
    tree: &mut Value,
    draws: &mut Vec<Draw>,
    mut draw: impl FnMut(usize) -> ([f64; 3], f64),
) {
    let Some(Value::Array(obs)) = at_path(tree, "apf.obstacles") else {
        return;
    };
    for (i, o) in obs.iter_mut().enumerate() {
        let dims = o
            .get("centre")
            .and_then(Value::as_array)
            .map_or(2, |a| a.len().clamp(2, 3));
        let (d, f) = draw(dims);
        move_apf_obstacle(o, d, f);
        draws.push(Draw {
            what: format!("apf obstacle {i} shift m, speed ×"),
            value: json!([d[0], d[1], d[2], f]),
            of: 0,
        });
    }
}

/// Shifts the point at dotted `path` of `tree` by `offset(dims)` (2 or 3
/// components, as the point has) and records the draw.
fn shift_point(
    tree: &mut Value,
    path: &str,
    draws: &mut Vec<Draw>,
    offset: impl FnOnce(usize) -> [f64; 3],
) -> Result<(), ScenarioError> {
    let v =
        at_path(tree, path).ok_or_else(|| bad(format!("family: the preset has no `{path}`")))?;
    let dims = v.as_array().map_or(2, |a| a.len().clamp(2, 3));
    let d = offset(dims);
    if !shift_array(v, d) {
        return Err(bad(format!("family: `{path}` is not a point")));
    }
    draws.push(Draw {
        what: format!("{path} shift m"),
        value: json!(&d[..dims]),
        of: 0,
    });
    Ok(())
}

/// Shifts a potential-field obstacle's centre by `d` and scales its
/// velocity by `f`.
fn move_apf_obstacle(o: &mut Value, d: [f64; 3], f: f64) {
    if let Some(c) = o.get_mut("centre") {
        shift_array(c, d);
    }
    if let Some(v) = o.get_mut("velocity") {
        scale_array(v, f);
    }
}

/// Shifts a mover's motion by `d` and scales its speed by `f`.
fn shift_motion(motion: &mut Value, d: [f64; 3], f: f64) {
    let model = motion
        .get("model")
        .and_then(Value::as_str)
        .unwrap_or("")
        .to_string();
    match model.as_str() {
        "constant-velocity" => {
            if let Some(s) = motion.get_mut("start") {
                shift_array(s, d);
            }
            if let Some(v) = motion.get_mut("velocity") {
                scale_array(v, f);
            }
        }
        "back-and-forth" => {
            for k in ["a", "b"] {
                if let Some(p) = motion.get_mut(k) {
                    shift_array(p, d);
                }
            }
        }
        "waypoint-loop" => {
            if let Some(Value::Array(pts)) = motion.get_mut("points") {
                for p in pts.iter_mut() {
                    shift_array(p, d);
                }
            }
        }
        "scripted" => {
            if let Some(Value::Array(samples)) = motion.get_mut("samples") {
                for s in samples.iter_mut() {
                    for (k, dk) in [("x", d[0]), ("y", d[1])] {
                        if let Some(x) = s.get(k).and_then(Value::as_f64) {
                            s[k] = num(x + dk);
                        }
                    }
                }
            }
        }
        _ => {}
    }
    if matches!(model.as_str(), "back-and-forth" | "waypoint-loop") {
        if let Some(s) = motion.get("speed").and_then(Value::as_f64) {
            motion["speed"] = num(s * f);
        }
    }
}

/// The free-standing blocks of `grid` (4-connected occupied cells not
/// touching the edge), each as its cell list, in scan order.
fn blocks(grid: &OccupancyGrid) -> Vec<Vec<(usize, usize)>> {
    let (w, h) = (grid.width(), grid.height());
    let occupied = |c: usize, r: usize| grid.get(c, r) == Some(Cell::Occupied);
    let mut seen = vec![false; w * h];
    let mut out = Vec::new();
    for r0 in 0..h {
        for c0 in 0..w {
            if seen[r0 * w + c0] || !occupied(c0, r0) {
                continue;
            }
            let mut cells = Vec::new();
            let mut edge = false;
            let mut stack = vec![(c0, r0)];
            seen[r0 * w + c0] = true;
            while let Some((c, r)) = stack.pop() {
                cells.push((c, r));
                edge |= c == 0 || r == 0 || c + 1 == w || r + 1 == h;
                let mut push = |cc: usize, rr: usize| {
                    if !seen[rr * w + cc] && occupied(cc, rr) {
                        seen[rr * w + cc] = true;
                        stack.push((cc, rr));
                    }
                };
                if c > 0 {
                    push(c - 1, r);
                }
                if c + 1 < w {
                    push(c + 1, r);
                }
                if r > 0 {
                    push(c, r - 1);
                }
                if r + 1 < h {
                    push(c, r + 1);
                }
            }
            if !edge {
                out.push(cells);
            }
        }
    }
    out
}

/// `grid` with every free-standing block moved by up to `k` cells per axis;
/// the offsets drawn, in block order.
fn shift_blocks(
    grid: &OccupancyGrid,
    k: u32,
    rng: &mut Rng,
) -> Result<(OccupancyGrid, Vec<[i64; 2]>), ScenarioError> {
    let (w, h) = (grid.width() as i64, grid.height() as i64);
    let mut out = grid.clone();
    let mut offsets = Vec::new();
    let k = i64::from(k);
    let draw = |rng: &mut Rng| -> i64 {
        // Whole cells uniform in −k … k.
        let span = (2 * k + 1) as f64;
        ((rng.uniform() * span).floor() as i64).clamp(0, 2 * k) - k
    };
    let all = blocks(grid);
    for cells in &all {
        let (dc, dr) = (draw(rng), draw(rng));
        offsets.push([dc, dr]);
        let target: Vec<(i64, i64)> = cells
            .iter()
            .map(|&(c, r)| (c as i64 + dc, r as i64 - dr))
            .collect();
        // The block's own cells may be overwritten; anything else occupied
        // (another block, a wall) or off the map keeps the block in place.
        let own = |c: i64, r: i64| cells.iter().any(|&(a, b)| a as i64 == c && b as i64 == r);
        let fits = target.iter().all(|&(c, r)| {
            c > 0
                && r > 0
                && c + 1 < w
                && r + 1 < h
                && (own(c, r) || out.get(c as usize, r as usize) == Some(Cell::Free))
        });
        if !fits || (dc == 0 && dr == 0) {
            continue;
        }
        let map_err = |e: crate::map::MapError| bad(format!("family: {e}"));
        for &(c, r) in cells {
            out.set(c, r, Cell::Free).map_err(map_err)?;
        }
        for &(c, r) in &target {
            out.set(c as usize, r as usize, Cell::Occupied)
                .map_err(map_err)?;
        }
    }
    Ok((out, offsets))
}

#[cfg(test)]
mod tests {
    use super::*;

    const DEMO: &str = include_str!("../../../../assets/scenarios/T-fig3-11.json");

    fn family() -> Family {
        Family {
            perturbations: vec![
                Perturbation::start(0.2).because("test"),
                Perturbation::goal(0.2).because("test"),
                Perturbation::Movers {
                    radius_m: 0.2,
                    speed_rel: 0.2,
                }
                .because("test"),
                Perturbation::Seed.because("test"),
            ],
        }
    }

    #[test]
    fn variant_zero_is_the_preset_and_others_stay_in_their_ranges() {
        let preset: Value = serde_json::from_str(DEMO).unwrap();
        let f = family();
        let (t0, d0) = f.apply(&preset, DEMO, 3, 0, 0).unwrap();
        assert_eq!(t0, preset);
        assert!(d0.is_empty());
        for k in 1..20 {
            let (t, draws) = f.apply(&preset, DEMO, 3, k, 0).unwrap();
            assert_eq!(
                t,
                f.apply(&preset, DEMO, 3, k, 0).unwrap().0,
                "deterministic"
            );
            let s = Scenario::from_value(&t).unwrap();
            let g = s.inline_grid().unwrap().unwrap();
            let (a, b) = (s.start_world(&g), [1.0, 3.0]);
            assert!(crate::num::hypot(a[0] - b[0], a[1] - b[1]) <= 0.2 + 1e-12);
            let v0 = t["movers"][0]["motion"]["velocity"][1].as_f64().unwrap();
            assert!((-0.48..=-0.32).contains(&v0), "{v0}");
            // The still disc stays still.
            assert_eq!(t["movers"][1]["motion"]["velocity"], json!([0.0, 0.0]));
            assert_eq!(t["seed"], json!(variant_seed(3, k)));
            assert_eq!(draws.len(), 5);
        }
        assert_ne!(
            f.apply(&preset, DEMO, 3, 1, 0).unwrap().0,
            f.apply(&preset, DEMO, 3, 2, 0).unwrap().0
        );
    }

    #[test]
    fn blocks_move_whole_and_walls_stay() {
        let g = OccupancyGrid::from_ascii(
            "##########\n\
             #........#\n\
             #..##....#\n\
             #..##....#\n\
             #........#\n\
             ##########",
        )
        .unwrap();
        assert_eq!(blocks(&g).len(), 1);
        let mut rng = Rng::new(5);
        for _ in 0..20 {
            let (m, off) = shift_blocks(&g, 1, &mut rng).unwrap();
            assert_eq!(m.counts(), g.counts(), "same number of occupied cells");
            let [dc, dr] = off[0];
            assert!(dc.abs() <= 1 && dr.abs() <= 1);
            // The outer wall is untouched.
            for c in 0..10 {
                assert_eq!(m.get(c, 0), Some(Cell::Occupied));
                assert_eq!(m.get(c, 5), Some(Cell::Occupied));
            }
            assert_eq!(
                m.get((3 + dc) as usize, (2 - dr) as usize),
                Some(Cell::Occupied)
            );
        }
    }
}
