//! Hybrid A* (D. Dolgov, S. Thrun, M. Montemerlo, J. Diebel, "Practical
//! Search Techniques in Path Planning for Autonomous Driving", STAIR 2008),
//! shaped like Nav2's Smac Hybrid-A* planner.
//!
//! The search runs over **continuous poses**, but remembers one pose per
//! *slot*: a grid cell and one of `heading_bins` heading bins. From each
//! pose it drives short **motion primitives**: a left arc at the minimum
//! turning radius, a straight line and a right arc, all of the same length
//! (and, with `reverse`, the same three backwards). A primitive is kept
//! when the disc footprint is free along it and it ends in a slot not yet
//! closed, more cheaply than that slot's best pose so far.
//!
//! - **Cost** of a primitive: its length × `non_straight_penalty` when it
//!   turns (+ `change_penalty` when it turns the other way than its
//!   parent), × `reverse_penalty` when it reverses (Nav2's penalties).
//! - **Heuristic**: the larger of the obstacle-free Dubins (Reeds-Shepp with
//!   `reverse`) length to the goal and the obstacle-aware 2D distance of an
//!   8-connected Dijkstra from the goal over the cells a disc could touch.
//! - **Analytic expansion**: every `max(1, ⌊h / analytic_expansion_ratio⌋)`
//!   expansions (h in cells, Nav2's rule) the search tries the Dubins /
//!   Reeds-Shepp curve from the pose it expands to the exact goal and
//!   stops when that curve is collision-free. When the curve is blocked but
//!   the pose lies in the goal's slot (its cell and heading bin) the path
//!   ends there: that slot is the goal tolerance.
//! - **Collision checking**: the disc of radius `footprint_radius` (or the
//!   discs covering the `footprint_rect` rectangle, [`RectCover`]) at poses
//!   every half cell along every primitive and shot, grown by a quarter
//!   cell so the body swept between two checked poses is covered too.
//! - **Primitive length**: the arc of k heading bins at the turning
//!   radius, k the least that moves at least √2 cells (Nav2's rule), so
//!   each primitive leaves its cell.
//! - **Bounds**: at most `max_expansions` expansions (then
//!   [`CarError::SearchLimit`]), so memory is bounded; a goal the 2D
//!   distance cannot reach fails at once ([`CarError::Unreachable`] with 0
//!   expansions). Ties in the open list go to the pose made first, so the
//!   same input gives the same path.

use super::footprint::{DiscChecker, RectCover};
use super::{advance, check_radius, dubins, reeds_shepp, CarError, CurvePath, Pose, Steer};
use crate::map::OccupancyGrid;
use crate::num::{cos, sin, wrap_angle};
use serde::{Deserialize, Serialize};
use std::cmp::Ordering;
use std::collections::{BinaryHeap, HashMap};
use std::f64::consts::{PI, SQRT_2};

/// Most expansions a configuration may ask for.
pub const MAX_EXPANSIONS_LIMIT: usize = 5_000_000;

/// Hybrid A* settings. Defaults: Nav2's Smac Hybrid-A* where it has the
/// setting (72 bins, penalties 1.2 / 0.0 / 2.0, ratio 3.5), planlab's own
/// otherwise (radius 1 m, footprint 0.2 m, 200 000 expansions).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct HybridAStarConfig {
    /// Minimum turning radius, m.
    pub turning_radius: f64,
    /// Whether the car may reverse (Reeds-Shepp instead of Dubins).
    pub reverse: bool,
    /// Radius of the disc footprint, m (ignored with `footprint_rect`).
    pub footprint_radius: f64,
    /// A rectangular footprint instead of the disc: (length along the
    /// heading, width), m, centred on the pose; checked by the discs that
    /// cover it ([`super::footprint::RectCover`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub footprint_rect: Option<(f64, f64)>,
    /// Heading bins (Nav2 `angle_quantization_bins`).
    pub heading_bins: u32,
    /// Cost factor of a turning primitive, ≥ 1 (Nav2 `non_straight_penalty`).
    pub non_straight_penalty: f64,
    /// Added to the factor when the turn changes side, ≥ 0 (Nav2
    /// `change_penalty`).
    pub change_penalty: f64,
    /// Cost factor of a reversing primitive, ≥ 1 (Nav2 `reverse_penalty`).
    pub reverse_penalty: f64,
    /// Analytic expansion every ⌊h / ratio⌋ expansions, > 0 (Nav2
    /// `analytic_expansion_ratio`).
    pub analytic_expansion_ratio: f64,
    /// Expansions before giving up.
    pub max_expansions: usize,
    /// Treat unknown cells as free.
    pub allow_unknown: bool,
}

impl Default for HybridAStarConfig {
    fn default() -> Self {
        Self {
            turning_radius: 1.0,
            reverse: false,
            footprint_radius: 0.2,
            footprint_rect: None,
            heading_bins: 72,
            non_straight_penalty: 1.2,
            change_penalty: 0.0,
            reverse_penalty: 2.0,
            analytic_expansion_ratio: 3.5,
            max_expansions: 200_000,
            allow_unknown: false,
        }
    }
}

impl HybridAStarConfig {
    /// Checks every field; the error names it.
    pub fn check(&self) -> Result<(), CarError> {
        check_radius(self.turning_radius)?;
        let bad = |m: String| Err(CarError::InvalidParameter(m));
        let r = self.footprint_radius;
        if !(r.is_finite() && r >= 0.0) {
            return bad(format!(
                "footprint radius {r} must be a finite number ≥ 0 (metres)"
            ));
        }
        if let Some((l, w)) = self.footprint_rect {
            if !(l.is_finite() && l > 0.0 && w.is_finite() && w > 0.0) {
                return bad(format!(
                    "footprint rectangle {l} × {w} must be two finite numbers > 0 (metres)"
                ));
            }
        }
        if !(4..=720).contains(&self.heading_bins) {
            return bad(format!("heading_bins {} must be 4…720", self.heading_bins));
        }
        for (name, v) in [
            ("non_straight_penalty", self.non_straight_penalty),
            ("reverse_penalty", self.reverse_penalty),
        ] {
            if !(v.is_finite() && v >= 1.0) {
                return bad(format!("{name} {v} must be a finite number ≥ 1"));
            }
        }
        let c = self.change_penalty;
        if !(c.is_finite() && c >= 0.0) {
            return bad(format!("change_penalty {c} must be a finite number ≥ 0"));
        }
        let a = self.analytic_expansion_ratio;
        if !(a.is_finite() && a > 0.0) {
            return bad(format!(
                "analytic_expansion_ratio {a} must be a finite number > 0"
            ));
        }
        if !(1..=MAX_EXPANSIONS_LIMIT).contains(&self.max_expansions) {
            return bad(format!(
                "max_expansions {} must be 1…{MAX_EXPANSIONS_LIMIT}",
                self.max_expansions
            ));
        }
        Ok(())
    }

    /// The obstacle-free curve from `a` to `b` this car drives.
    pub fn curve(&self, a: Pose, b: Pose) -> Result<CurvePath, CarError> {
        if self.reverse {
            reeds_shepp(a, b, self.turning_radius)
        } else {
            dubins(a, b, self.turning_radius)
        }
    }
}

/// A Hybrid A* path in world metres.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct HybridPath {
    /// Poses from the start to the goal, at most half a cell apart.
    pub poses: Vec<Pose>,
    /// For each pose, whether it is reached driving forward.
    pub forward: Vec<bool>,
    /// Length driven, m.
    pub length: f64,
    /// Poses expanded.
    pub expanded: usize,
    /// Whether the path ends with an analytic (Dubins / Reeds-Shepp) shot at
    /// the exact goal; `false`: it ends in the goal's cell and heading bin.
    pub analytic: bool,
    /// Switches between forward and reverse.
    pub cusps: usize,
    /// Length of one motion primitive, m.
    pub primitive_length: f64,
}

/// One primitive: steering, direction, length.
#[derive(Clone, Copy, Debug)]
struct Prim {
    steer: Steer,
    forward: bool,
}

#[derive(Clone, Copy, Debug)]
struct Node {
    pose: Pose,
    g: f64,
    parent: u32,
    prim: Option<Prim>,
}

/// An open-list entry: lowest f first, then lowest h, then oldest.
#[derive(Clone, Copy, Debug)]
struct Open {
    f: f64,
    h: f64,
    node: u32,
}

impl PartialEq for Open {
    fn eq(&self, o: &Self) -> bool {
        self.cmp(o) == Ordering::Equal
    }
}
impl Eq for Open {}
impl PartialOrd for Open {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Open {
    fn cmp(&self, o: &Self) -> Ordering {
        // Reversed: BinaryHeap pops the greatest.
        o.f.total_cmp(&self.f)
            .then(o.h.total_cmp(&self.h))
            .then(o.node.cmp(&self.node))
    }
}

/// The map frame: world poses relative to the grid's origin corner.
struct Frame {
    ox: f64,
    oy: f64,
    oyaw: f64,
}

impl Frame {
    fn to_map(&self, p: Pose) -> Pose {
        let (dx, dy) = (p.x - self.ox, p.y - self.oy);
        let (c, s) = (cos(self.oyaw), sin(self.oyaw));
        Pose::new(
            c * dx + s * dy,
            -s * dx + c * dy,
            wrap_angle(p.yaw - self.oyaw),
        )
    }
    fn to_world(&self, p: Pose) -> Pose {
        let (c, s) = (cos(self.oyaw), sin(self.oyaw));
        Pose::new(
            self.ox + c * p.x - s * p.y,
            self.oy + s * p.x + c * p.y,
            wrap_angle(p.yaw + self.oyaw),
        )
    }
}

/// The obstacle-aware 2D distance to the goal, m, per cell (row-major,
/// ∞ where the disc cannot go): 8-connected Dijkstra from the goal cell
/// over the cells some point of which may hold the disc, no corner cutting.
fn distance_to_goal(ck: &DiscChecker, goal: (usize, usize), w: usize, h: usize) -> Vec<f64> {
    let res = ck.resolution();
    let r = ck.radius();
    let open_cell = |c: usize, row: usize| {
        !ck.is_blocked(c, row) && ck.centre_distance(c, row) + res / SQRT_2 >= r
    };
    let mut dist = vec![f64::INFINITY; w * h];
    let mut heap = BinaryHeap::new();
    let gi = goal.1 * w + goal.0;
    dist[gi] = 0.0;
    heap.push(Open {
        f: 0.0,
        h: 0.0,
        node: gi as u32,
    });
    while let Some(Open { f: d, node, .. }) = heap.pop() {
        let i = node as usize;
        if d > dist[i] {
            continue;
        }
        let (c, row) = ((i % w) as i64, (i / w) as i64);
        for (dc, dr) in [
            (-1, 0),
            (1, 0),
            (0, -1),
            (0, 1),
            (-1, -1),
            (-1, 1),
            (1, -1),
            (1, 1),
        ] {
            let (nc, nr) = (c + dc, row + dr);
            if nc < 0 || nr < 0 || nc >= w as i64 || nr >= h as i64 {
                continue;
            }
            if !open_cell(nc as usize, nr as usize) {
                continue;
            }
            let diag = dc != 0 && dr != 0;
            if diag
                && !(open_cell((c + dc) as usize, row as usize)
                    && open_cell(c as usize, (row + dr) as usize))
            {
                continue;
            }
            let nd = d + if diag { SQRT_2 * res } else { res };
            let ni = nr as usize * w + nc as usize;
            if nd < dist[ni] {
                dist[ni] = nd;
                heap.push(Open {
                    f: nd,
                    h: 0.0,
                    node: ni as u32,
                });
            }
        }
    }
    dist
}

/// Plans a car path from `start` to `goal` (world metres, radians) on
/// `grid`. Errors: a bad configuration or pose, an endpoint off the map or
/// in collision, an unreachable goal, the expansion limit.
pub fn plan_hybrid_astar(
    grid: &OccupancyGrid,
    start: Pose,
    goal: Pose,
    cfg: &HybridAStarConfig,
) -> Result<HybridPath, CarError> {
    cfg.check()?;
    super::check_poses(start, goal)?;
    let o = grid.origin();
    let frame = Frame {
        ox: o.x,
        oy: o.y,
        oyaw: o.yaw,
    };
    let (s, g) = (frame.to_map(start), frame.to_map(goal));
    let res = grid.resolution();
    let (w, h) = (grid.width(), grid.height());
    // Poses are checked every half cell with the disc grown by a quarter
    // cell: every point between two checked poses is within a quarter cell
    // of one of them.
    let check_step = 0.5 * res;
    // The body: one disc, or the discs covering the rectangle; each grown
    // by a quarter cell for the motion between checked poses.
    let cover = match cfg.footprint_rect {
        Some((l, wd)) => RectCover::new(l, wd, res),
        None => RectCover::disc(cfg.footprint_radius),
    };
    let ck = DiscChecker::new(grid, cover.radius + 0.25 * res, cfg.allow_unknown);
    let body_free = |p: Pose| cover.centres(p).all(|(x, y)| ck.free(x, y));
    for (which, p) in [("start", s), ("goal", g)] {
        let off = ck.cell_of(p.x, p.y).is_none();
        let world = if which == "start" { start } else { goal };
        if off {
            return Err(CarError::OffMap {
                which,
                x: world.x,
                y: world.y,
            });
        }
        if !cover
            .centres(p)
            .all(|(x, y)| ck.disc_free(x, y, cover.radius))
        {
            return Err(CarError::InCollision {
                which,
                x: world.x,
                y: world.y,
                radius: cover.radius,
            });
        }
    }
    let goal_cell = ck.cell_of(g.x, g.y).unwrap_or((0, 0));
    // The 2D estimate needs only where some body could be: the disc, or
    // the rectangle's inscribed disc (half its smaller side).
    let inner = match cfg.footprint_rect {
        Some((l, wd)) => 0.5 * l.min(wd),
        None => cfg.footprint_radius,
    };
    let h2d = distance_to_goal(
        &DiscChecker::new(grid, inner + 0.25 * res, cfg.allow_unknown),
        goal_cell,
        w,
        h,
    );
    let bins = cfg.heading_bins as usize;
    let bin_angle = 2.0 * PI / bins as f64;
    let bin_of = |yaw: f64| ((wrap_angle(yaw) + PI) / bin_angle).floor() as usize % bins;
    let slot_of = |p: Pose| -> Option<u64> {
        let (c, row) = ck.cell_of(p.x, p.y)?;
        Some(((row * w + c) * bins + bin_of(p.yaw)) as u64)
    };
    let heuristic = |p: Pose| -> Option<f64> {
        let (c, row) = ck.cell_of(p.x, p.y)?;
        let d2 = h2d[row * w + c];
        if !d2.is_finite() {
            return None;
        }
        let curve = cfg.curve(p, g).map(|c| c.length()).unwrap_or(0.0);
        Some(curve.max(d2))
    };
    let Some(h0) = heuristic(s) else {
        return Err(CarError::Unreachable { expanded: 0 });
    };
    let radius = cfg.turning_radius;
    let k = ((SQRT_2 * res) / (radius * bin_angle)).ceil().max(1.0);
    let prim_len = radius * bin_angle * k;
    let mut prims = Vec::with_capacity(6);
    for forward in [true, false] {
        if !forward && !cfg.reverse {
            continue;
        }
        for steer in [Steer::Left, Steer::Straight, Steer::Right] {
            prims.push(Prim { steer, forward });
        }
    }
    // Poses along a motion of `len` (signed) from `p`, every check step,
    // the first excluded, the last included.
    let along = |p: Pose, steer: Steer, len: f64| {
        let n = (len.abs() / check_step).ceil().max(1.0) as usize;
        (1..=n).map(move |i| advance(p, steer, len * i as f64 / n as f64, radius))
    };
    let goal_slot = slot_of(g);
    let mut nodes = vec![Node {
        pose: s,
        g: 0.0,
        parent: u32::MAX,
        prim: None,
    }];
    // Slot → (best g, node, closed).
    let mut slots: HashMap<u64, (f64, u32, bool)> = HashMap::new();
    if let Some(k) = slot_of(s) {
        slots.insert(k, (0.0, 0, false));
    }
    let mut open = BinaryHeap::new();
    open.push(Open {
        f: h0,
        h: h0,
        node: 0,
    });
    let (mut expanded, mut since_shot) = (0usize, 0usize);
    while let Some(Open { h: hn, node, .. }) = open.pop() {
        let n = nodes[node as usize];
        let Some(key) = slot_of(n.pose) else { continue };
        match slots.get_mut(&key) {
            Some(e) if e.2 || e.1 != node => continue,
            Some(e) => e.2 = true,
            None => continue,
        }
        expanded += 1;
        if expanded > cfg.max_expansions {
            return Err(CarError::SearchLimit {
                expanded: expanded - 1,
                limit: cfg.max_expansions,
            });
        }
        // Analytic expansion (Nav2's interval), and always in the goal's cell.
        since_shot += 1;
        let interval = ((hn / res) / cfg.analytic_expansion_ratio).floor().max(1.0) as usize;
        let in_goal_cell = ck.cell_of(n.pose.x, n.pose.y) == Some(goal_cell);
        if since_shot >= interval || in_goal_cell {
            since_shot = 0;
            if let Ok(shot) = cfg.curve(n.pose, g) {
                let mut at = n.pose;
                let mut free = true;
                'segs: for seg in &shot.segments {
                    for p in along(at, seg.steer, seg.length) {
                        if !body_free(p) {
                            free = false;
                            break 'segs;
                        }
                    }
                    at = advance(at, seg.steer, seg.length, radius);
                }
                if free {
                    return Ok(finish(
                        &nodes,
                        node,
                        Some(&shot),
                        cfg,
                        &frame,
                        check_step,
                        expanded,
                        prim_len,
                        g,
                    ));
                }
            }
            if goal_slot == Some(key) {
                return Ok(finish(
                    &nodes, node, None, cfg, &frame, check_step, expanded, prim_len, g,
                ));
            }
        }
        for prim in &prims {
            let len = if prim.forward { prim_len } else { -prim_len };
            let mut end = n.pose;
            let mut free = true;
            for p in along(n.pose, prim.steer, len) {
                if !body_free(p) {
                    free = false;
                    break;
                }
                end = p;
            }
            if !free {
                continue;
            }
            let Some(nk) = slot_of(end) else { continue };
            if nk == key {
                continue;
            }
            let mut factor = 1.0;
            if prim.steer != Steer::Straight {
                factor = cfg.non_straight_penalty;
                if let Some(pp) = n.prim {
                    if pp.steer != Steer::Straight && pp.steer != prim.steer {
                        factor += cfg.change_penalty;
                    }
                }
            }
            if !prim.forward {
                factor *= cfg.reverse_penalty;
            }
            let ng = n.g + prim_len * factor;
            if let Some(&(bg, _, closed)) = slots.get(&nk) {
                if closed || bg <= ng {
                    continue;
                }
            }
            let Some(nh) = heuristic(end) else { continue };
            let id = nodes.len() as u32;
            nodes.push(Node {
                pose: end,
                g: ng,
                parent: node,
                prim: Some(*prim),
            });
            slots.insert(nk, (ng, id, false));
            open.push(Open {
                f: ng + nh,
                h: nh,
                node: id,
            });
        }
    }
    Err(CarError::Unreachable { expanded })
}

/// The path through the chain of nodes ending at `last`, then `shot`.
#[allow(clippy::too_many_arguments)]
fn finish(
    nodes: &[Node],
    last: u32,
    shot: Option<&CurvePath>,
    cfg: &HybridAStarConfig,
    frame: &Frame,
    step: f64,
    expanded: usize,
    prim_len: f64,
    goal: Pose,
) -> HybridPath {
    let radius = cfg.turning_radius;
    let mut chain = Vec::new();
    let mut i = last;
    while i != u32::MAX {
        chain.push(i);
        i = nodes[i as usize].parent;
    }
    chain.reverse();
    let mut moves: Vec<(Steer, f64)> = chain
        .iter()
        .filter_map(|&i| nodes[i as usize].prim)
        .map(|p| (p.steer, if p.forward { prim_len } else { -prim_len }))
        .collect();
    if let Some(shot) = shot {
        moves.extend(shot.segments.iter().map(|s| (s.steer, s.length)));
    }
    let start = nodes[0].pose;
    let first_forward = moves.first().map_or(true, |m| m.1 >= 0.0);
    let (mut poses, mut forward) = (vec![start], vec![first_forward]);
    let mut at = start;
    let mut length = 0.0;
    for &(steer, len) in &moves {
        let n = (len.abs() / step).ceil().max(1.0) as usize;
        for k in 1..=n {
            poses.push(advance(at, steer, len * k as f64 / n as f64, radius));
            forward.push(len >= 0.0);
        }
        at = advance(at, steer, len, radius);
        length += len.abs();
    }
    if shot.is_some() {
        // The exact goal, not its rounding through the segments.
        if let Some(p) = poses.last_mut() {
            *p = goal;
        }
    }
    let cusps = moves
        .windows(2)
        .filter(|w| (w[0].1 < 0.0) != (w[1].1 < 0.0))
        .count();
    HybridPath {
        poses: poses.into_iter().map(|p| frame.to_world(p)).collect(),
        forward,
        length,
        expanded,
        analytic: shot.is_some(),
        cusps,
        primitive_length: prim_len,
    }
}
