//! RRT-Connect in joint space (Kuffner & LaValle, ICRA 2000; the default
//! planner of MoveIt through OMPL) and random path shortcutting, for the
//! 7-DOF arm among the hand, forearm and table (docs/algorithms.md
//! §arm-rrt).
//!
//! - Configurations are sampled uniformly inside the joint limits
//!   ([`crate::num::Rng`], seeded).
//! - Two trees, one from the start and one from the goal, grow towards each
//!   sample in turn: one *extends* a step of at most
//!   [`RrtConfig::step_rad`] (the largest single joint change), the other
//!   *connects* (extends repeatedly) towards the new node; they swap roles
//!   every iteration.
//! - A straight joint-space move is checked at interpolated configurations
//!   spaced so that no point of any link axis moves more than
//!   [`RrtConfig::check_sweep_m`] between two checks ([`ArmChecker::sweep_bound`]).
//!   A configuration is valid when it is inside the limits and every link
//!   keeps the margin from the obstacles, the table and the links at least
//!   three apart in the chain. With a sweep of at most twice the margin, a
//!   point between two valid checks is within half a sweep of a checked
//!   position, so the whole move is free of contact with static obstacles.
//! - Nearest neighbours by linear scan: trees stay in the hundreds to a few
//!   thousand nodes here, where a k-d tree in 7 dimensions saves little and
//!   each edge's ~30 whole-arm checks dominate the time.

use glam::DVec3;
use serde::{Deserialize, Serialize};

use super::geometry::{link_capsules, link_distance, LinkCapsule, Obstacle3};
use super::model::ArmModel;
use super::ArmError;
use crate::num::Rng;
use crate::params::{check_param, Bound};

/// Settings of RRT-Connect, shortcutting and the arm's motion along the
/// path (the `rrt` section of an arm scene).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RrtConfig {
    /// Largest change of any joint along one tree edge, rad.
    pub step_rad: f64,
    /// Largest sweep of any link point between two collision checks of a
    /// move, m (at most twice the clearance margin for the contact-free
    /// guarantee).
    pub check_sweep_m: f64,
    /// Outer iterations (one sample each) per plan at most.
    pub max_iterations: u32,
    /// Random shortcut attempts after a path is found.
    pub shortcut_attempts: u32,
    /// Largest joint speed while following the path, rad/s.
    pub max_joint_speed_rad_s: f64,
}

impl Default for RrtConfig {
    fn default() -> Self {
        Self {
            step_rad: 0.1,
            check_sweep_m: 2.0 * super::episode::ARM_CLEARANCE_M,
            max_iterations: 3000,
            shortcut_attempts: 100,
            max_joint_speed_rad_s: 0.3,
        }
    }
}

/// Nodes per tree at most (bounds memory whatever `max_iterations` is).
pub const MAX_TREE_NODES: usize = 50_000;

impl RrtConfig {
    /// Refuses non-finite or out-of-range values, naming the field.
    pub fn validate(&self) -> Result<(), ArmError> {
        check_param("rrt.step_rad", self.step_rad, Bound::above(0.0))?;
        check_param("rrt.check_sweep_m", self.check_sweep_m, Bound::above(0.0))?;
        check_param(
            "rrt.max_joint_speed_rad_s",
            self.max_joint_speed_rad_s,
            Bound::above(0.0),
        )?;
        if self.step_rad > 1.0 {
            return Err(ArmError::Invalid(format!(
                "rrt.step_rad = {}: at most 1 rad",
                crate::num::fmt_num(self.step_rad)
            )));
        }
        if self.check_sweep_m < 1e-4 {
            return Err(ArmError::Invalid(format!(
                "rrt.check_sweep_m = {}: at least 0.0001 m (finer checks would take too long)",
                crate::num::fmt_num(self.check_sweep_m)
            )));
        }
        if self.max_iterations == 0 || self.max_iterations > 1_000_000 {
            return Err(ArmError::Invalid(
                "rrt.max_iterations must be in 1..=1000000".into(),
            ));
        }
        if self.shortcut_attempts > 1_000_000 {
            return Err(ArmError::Invalid(
                "rrt.shortcut_attempts must be at most 1000000".into(),
            ));
        }
        Ok(())
    }
}

/// Pairs of links closer than this in the chain are not checked against
/// each other: neighbours share a joint, and TIAGo's zero-length wrist link
/// makes links two apart touch at every posture.
pub const SELF_GAP: usize = 3;

/// Collision and clearance of arm postures against a fixed set of
/// obstacles, a table and the arm itself; counts the postures it checks.
#[derive(Debug, Clone)]
pub struct ArmChecker<'a> {
    model: &'a ArmModel,
    radii: Vec<f64>,
    obstacles: Vec<Obstacle3>,
    table_z: Option<f64>,
    margin: f64,
    sweep: f64,
    /// Per joint: an upper bound of the distance from its origin to any
    /// point of the link axes beyond it (the chain's length from there), m.
    arm_reach: Vec<f64>,
    checks: u64,
}

impl<'a> ArmChecker<'a> {
    /// A checker of `model` against `obstacles` and, when given, the table
    /// top at height `table_z` (every link must stay above it); valid
    /// postures keep `margin` (m) from all of them; moves are checked every
    /// `sweep` m of link motion.
    pub fn new(
        model: &'a ArmModel,
        obstacles: Vec<Obstacle3>,
        table_z: Option<f64>,
        margin: f64,
        sweep: f64,
    ) -> ArmChecker<'a> {
        let lens: Vec<f64> = model
            .origins
            .iter()
            .skip(1)
            .map(|o| o.pos.length())
            .chain(std::iter::once(model.tool.pos.length()))
            .collect();
        // Joint i's origin to the tool along the chain: links i..end.
        let arm_reach = (0..model.dof()).map(|i| lens[i..].iter().sum()).collect();
        ArmChecker {
            model,
            radii: model.link_radii(),
            obstacles,
            table_z,
            margin,
            sweep,
            arm_reach,
            checks: 0,
        }
    }

    /// Postures checked so far.
    pub fn checks(&self) -> u64 {
        self.checks
    }

    /// The clearance a valid posture keeps, m.
    pub fn margin(&self) -> f64 {
        self.margin
    }

    /// The obstacles checked against.
    pub fn obstacles(&self) -> &[Obstacle3] {
        &self.obstacles
    }

    /// The link capsules of `q`.
    pub fn links(&self, q: &[f64]) -> Vec<LinkCapsule> {
        link_capsules(&self.model.fk(q), &self.radii)
    }

    /// Smallest distance from any link to an obstacle, the table or a link
    /// at least [`SELF_GAP`] away in the chain (0 on contact), m. Counts
    /// one check.
    pub fn clearance(&mut self, q: &[f64]) -> f64 {
        self.checks += 1;
        clearance_of(&self.links(q), &self.obstacles, self.table_z)
    }

    /// Whether `q` is inside the limits and keeps the margin.
    pub fn valid(&mut self, q: &[f64]) -> bool {
        within_limits(self.model, q) && self.clearance(q) >= self.margin
    }

    /// An upper bound of how far any point of any link axis moves on the
    /// straight joint move from `a` to `b`: Σ |Δqᵢ| · (chain length beyond
    /// joint i), m. A rotation by δ moves a point at distance r from the
    /// axis by at most r·δ, and the moves of the joints add up.
    pub fn sweep_bound(&self, a: &[f64], b: &[f64]) -> f64 {
        a.iter()
            .zip(b)
            .zip(&self.arm_reach)
            .map(|((x, y), r)| (y - x).abs() * r)
            .sum()
    }

    /// Interpolated checks a move from `a` to `b` needs (the end included).
    pub fn checks_for(&self, a: &[f64], b: &[f64]) -> usize {
        let n = (self.sweep_bound(a, b) / self.sweep).ceil();
        if n.is_finite() {
            (n as usize).max(1)
        } else {
            usize::MAX
        }
    }

    /// Whether the straight joint move from `a` (assumed valid) to `b` is
    /// valid at every interpolated posture, `b` included.
    pub fn motion_valid(&mut self, a: &[f64], b: &[f64]) -> bool {
        let n = self.checks_for(a, b);
        if n > 1_000_000 {
            return false;
        }
        let mut q = a.to_vec();
        (1..=n).all(|k| {
            let f = k as f64 / n as f64;
            for (qi, (x, y)) in q.iter_mut().zip(a.iter().zip(b)) {
                *qi = x + (y - x) * f;
            }
            self.valid(&q)
        })
    }

    /// Whether every segment of `path` is a valid move (the first posture
    /// is not checked: it is where the arm is).
    pub fn path_valid(&mut self, path: &[Vec<f64>]) -> bool {
        path.windows(2).all(|w| self.motion_valid(&w[0], &w[1]))
    }
}

/// Whether `q` (right length) is inside the joint limits.
pub fn within_limits(model: &ArmModel, q: &[f64]) -> bool {
    q.len() == model.dof()
        && q.iter().enumerate().all(|(i, v)| {
            let (lo, hi) = model.limits(i);
            v.is_finite() && *v >= lo && *v <= hi
        })
}

/// Smallest distance of `links` to `obstacles`, the table top `table_z`
/// and each other (pairs at least [`SELF_GAP`] apart), m.
pub fn clearance_of(links: &[LinkCapsule], obstacles: &[Obstacle3], table_z: Option<f64>) -> f64 {
    let mut d = f64::INFINITY;
    for (i, l) in links.iter().enumerate() {
        for o in obstacles {
            d = d.min(link_distance(l, o));
        }
        if let Some(z) = table_z {
            d = d.min((l.a.z.min(l.b.z) - l.radius - z).max(0.0));
        }
        for m in links.iter().skip(i + SELF_GAP) {
            let other = Obstacle3::Capsule {
                a: m.a.to_array(),
                b: m.b.to_array(),
                radius: m.radius,
            };
            d = d.min(link_distance(l, &other));
        }
    }
    d
}

/// Joint-space length of a path (Euclidean), rad.
pub fn joint_path_length(path: &[Vec<f64>]) -> f64 {
    path.windows(2).map(|w| dist(&w[0], &w[1])).sum()
}

/// Tool-point path length of a joint path, sampled densely enough that
/// each straight joint move is followed within 1 mm of sweep, m.
pub fn tool_path_length(model: &ArmModel, path: &[Vec<f64>]) -> f64 {
    let c = ArmChecker::new(model, vec![], None, 0.0, 1e-3);
    let mut len = 0.0;
    for w in path.windows(2) {
        let n = c.checks_for(&w[0], &w[1]).min(100_000);
        let mut prev: DVec3 = model.tool_position(&w[0]);
        for k in 1..=n {
            let f = k as f64 / n as f64;
            let q: Vec<f64> = w[0]
                .iter()
                .zip(&w[1])
                .map(|(a, b)| a + (b - a) * f)
                .collect();
            let p = model.tool_position(&q);
            len += (p - prev).length();
            prev = p;
        }
    }
    len
}

fn dist(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (y - x) * (y - x))
        .sum::<f64>()
        .sqrt()
}

/// What one plan cost and found.
#[derive(Debug, Clone, PartialEq)]
pub struct RrtPlan {
    /// Postures from start to goal (both included).
    pub path: Vec<Vec<f64>>,
    /// Outer iterations run.
    pub iterations: u32,
    /// Nodes of both trees at the end.
    pub nodes: usize,
}

/// A tree: postures stored flat (`dof` values each) with parent indices.
struct Tree {
    dof: usize,
    q: Vec<f64>,
    parent: Vec<usize>,
}

impl Tree {
    fn new(root: &[f64]) -> Tree {
        Tree {
            dof: root.len(),
            q: root.to_vec(),
            parent: vec![usize::MAX],
        }
    }
    fn len(&self) -> usize {
        self.parent.len()
    }
    fn node(&self, i: usize) -> &[f64] {
        &self.q[i * self.dof..(i + 1) * self.dof]
    }
    fn nearest(&self, q: &[f64]) -> usize {
        let mut best = (f64::INFINITY, 0);
        for i in 0..self.len() {
            let d: f64 = self
                .node(i)
                .iter()
                .zip(q)
                .map(|(a, b)| (a - b) * (a - b))
                .sum();
            if d < best.0 {
                best = (d, i);
            }
        }
        best.1
    }
    fn add(&mut self, q: &[f64], parent: usize) -> usize {
        self.q.extend_from_slice(q);
        self.parent.push(parent);
        self.len() - 1
    }
    /// Root to node `i`.
    fn branch(&self, mut i: usize) -> Vec<Vec<f64>> {
        let mut out = vec![self.node(i).to_vec()];
        while self.parent[i] != usize::MAX {
            i = self.parent[i];
            out.push(self.node(i).to_vec());
        }
        out.reverse();
        out
    }
}

#[derive(PartialEq)]
enum Grow {
    Trapped,
    Advanced(usize),
    Reached(usize),
}

/// One EXTEND of Kuffner & LaValle: a step of at most `step` (largest joint
/// change) from the nearest node towards `target`, added when the move is
/// valid.
fn extend(t: &mut Tree, target: &[f64], step: f64, c: &mut ArmChecker<'_>) -> Grow {
    if t.len() >= MAX_TREE_NODES {
        return Grow::Trapped;
    }
    let near = t.nearest(target);
    let from = t.node(near).to_vec();
    let largest = from
        .iter()
        .zip(target)
        .map(|(a, b)| (b - a).abs())
        .fold(0.0, f64::max);
    let (new, reached) = if largest <= step {
        (target.to_vec(), true)
    } else {
        let f = step / largest;
        let q = from
            .iter()
            .zip(target)
            .map(|(a, b)| a + (b - a) * f)
            .collect();
        (q, false)
    };
    if !c.motion_valid(&from, &new) {
        return Grow::Trapped;
    }
    let i = t.add(&new, near);
    if reached {
        Grow::Reached(i)
    } else {
        Grow::Advanced(i)
    }
}

/// CONNECT: extends towards `target` until reached or trapped.
fn connect(t: &mut Tree, target: &[f64], step: f64, c: &mut ArmChecker<'_>) -> Grow {
    loop {
        match extend(t, target, step, c) {
            Grow::Advanced(_) => continue,
            g => return g,
        }
    }
}

/// RRT-Connect from `start` to `goal` (both checked first: a typed error
/// when outside the limits, not finite or not valid).
pub fn rrt_connect(
    c: &mut ArmChecker<'_>,
    start: &[f64],
    goal: &[f64],
    cfg: &RrtConfig,
    rng: &mut Rng,
) -> Result<RrtPlan, ArmError> {
    cfg.validate()?;
    let model = c.model;
    for (what, q) in [("start posture", start), ("goal posture", goal)] {
        model.check_q(q).map_err(|e| match e {
            ArmError::WrongJointCount {
                expected, found, ..
            } => ArmError::WrongJointCount {
                what: what.into(),
                expected,
                found,
            },
            other => other,
        })?;
        let d = c.clearance(q);
        if d < c.margin {
            return Err(ArmError::PostureBlocked {
                what: what.into(),
                clearance_m: d,
                margin_m: c.margin,
            });
        }
    }
    let mut ta = Tree::new(start);
    let mut tb = Tree::new(goal);
    // Which tree grows from the start (`ta` first).
    let mut a_is_start = true;
    let lims: Vec<(f64, f64)> = (0..model.dof()).map(|i| model.limits(i)).collect();
    let mut sample = vec![0.0; model.dof()];
    for it in 1..=cfg.max_iterations {
        for (s, (lo, hi)) in sample.iter_mut().zip(&lims) {
            *s = rng.range(*lo, *hi);
        }
        let new = match extend(&mut ta, &sample, cfg.step_rad, c) {
            Grow::Trapped => None,
            Grow::Advanced(i) | Grow::Reached(i) => Some(i),
        };
        if let Some(i) = new {
            let q = ta.node(i).to_vec();
            if let Grow::Reached(j) = connect(&mut tb, &q, cfg.step_rad, c) {
                let mut a = ta.branch(i);
                let mut b = tb.branch(j);
                // `b` ends at `q` too: drop the duplicate, then join.
                b.pop();
                b.reverse();
                a.extend(b);
                if !a_is_start {
                    a.reverse();
                }
                return Ok(RrtPlan {
                    path: a,
                    iterations: it,
                    nodes: ta.len() + tb.len(),
                });
            }
        }
        std::mem::swap(&mut ta, &mut tb);
        a_is_start = !a_is_start;
    }
    Err(ArmError::NoPath {
        iterations: cfg.max_iterations,
    })
}

/// Random shortcutting: `attempts` times, two points drawn uniformly along
/// the path's joint-space length are joined straight when that move is
/// valid and shorter, replacing the stretch between them. The path never
/// grows longer and every new segment is checked like a tree edge.
pub fn shortcut(
    c: &mut ArmChecker<'_>,
    path: &[Vec<f64>],
    attempts: u32,
    rng: &mut Rng,
) -> Vec<Vec<f64>> {
    let mut p = path.to_vec();
    for _ in 0..attempts {
        if p.len() < 3 {
            break;
        }
        let cum: Vec<f64> = std::iter::once(0.0)
            .chain(p.windows(2).scan(0.0, |s, w| {
                *s += dist(&w[0], &w[1]);
                Some(*s)
            }))
            .collect();
        let total = cum[cum.len() - 1];
        if total <= 0.0 {
            break;
        }
        let (mut s1, mut s2) = (rng.range(0.0, total), rng.range(0.0, total));
        if s1 > s2 {
            std::mem::swap(&mut s1, &mut s2);
        }
        // Segment index and posture at arc length s.
        let at = |s: f64| -> (usize, Vec<f64>) {
            let i = cum.partition_point(|&x| x <= s).clamp(1, p.len() - 1) - 1;
            let len = cum[i + 1] - cum[i];
            let f = if len > 0.0 { (s - cum[i]) / len } else { 0.0 };
            let q = p[i]
                .iter()
                .zip(&p[i + 1])
                .map(|(a, b)| a + (b - a) * f)
                .collect();
            (i, q)
        };
        let ((i, qa), (j, qb)) = (at(s1), at(s2));
        if i == j {
            continue; // within one straight segment: nothing to gain
        }
        let old = dist(&qa, &p[i + 1]) + joint_path_length(&p[i + 1..=j]) + dist(&p[j], &qb);
        if dist(&qa, &qb) >= old - 1e-12 || !c.motion_valid(&qa, &qb) {
            continue;
        }
        let mut next = p[..=i].to_vec();
        next.push(qa);
        next.push(qb);
        next.extend_from_slice(&p[j + 1..]);
        // Drop repeated postures (a draw landing on a vertex).
        next.dedup_by(|b, a| dist(a, b) < 1e-12);
        p = next;
    }
    p
}
