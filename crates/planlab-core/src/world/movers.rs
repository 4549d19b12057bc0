//! Moving disc obstacles and their motion models (docs/algorithms.md §movers): constant velocity
//! bouncing off walls and the map edge (\[T\] Fig 3-11), back-and-forth between two points
//! (\[S\] Fig 12), a waypoint loop and a scripted time series.
//!
//! Each model is a function of time alone, so a mover's state at any instant
//! is exact and identical on replay, whatever the step size: the three
//! path models in closed form, the constant-velocity model as straight legs
//! between exactly computed bounces ([`MoverTrack`]). A constant-velocity
//! mover never enters a blocked cell or leaves the map: it is reflected;
//! [`MoverSpec::check_on`] refuses any mover that starts in a wall.

use serde::{Deserialize, Serialize};

use super::static_map::StaticMap;
use super::{check_min, check_point, check_positive, WorldError};

/// One sample of a scripted trajectory.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScriptSample {
    /// Time, seconds from the episode start.
    pub t: f64,
    /// Position x, metres.
    pub x: f64,
    /// Position y, metres.
    pub y: f64,
}

/// How a mover moves.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", tag = "model", deny_unknown_fields)]
pub enum MotionModel {
    /// Straight on at constant velocity from `start`, reflected off every
    /// wall (blocked cell) and map edge the disc touches: the velocity
    /// component along the contact normal flips, the speed is kept
    /// ([`MoverTrack`]).
    ConstantVelocity {
        /// Position at time `since`, metres.
        start: [f64; 2],
        /// Velocity (v_x, v_y) at time `since`, m/s.
        velocity: [f64; 2],
        /// Time the mover leaves `start`, s (it stands there before): a
        /// mover dropped into a running episode starts where and when it
        /// was dropped, so its bounces are those of its own path.
        #[serde(default, skip_serializing_if = "is_zero")]
        since: f64,
    },
    /// From `a` to `b` and back, forever, at `speed`.
    BackAndForth {
        /// First end (position at t = 0), metres.
        a: [f64; 2],
        /// Second end, metres.
        b: [f64; 2],
        /// Speed, m/s.
        speed: f64,
    },
    /// Around the closed polyline through `points` (starting at the first),
    /// forever, at `speed`.
    WaypointLoop {
        /// Corners, metres; at least two.
        points: Vec<[f64; 2]>,
        /// Speed, m/s.
        speed: f64,
    },
    /// Piecewise-linear through timed samples; holds the first position
    /// before the first sample and the last after the last.
    Scripted {
        /// Samples with strictly increasing times.
        samples: Vec<ScriptSample>,
    },
}

/// A moving disc obstacle.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MoverSpec {
    /// Identifier shown in traces and on the page.
    #[serde(default)]
    pub id: u32,
    /// Disc radius, metres.
    pub radius: f64,
    /// Motion model.
    pub motion: MotionModel,
}

/// Position and velocity of a mover at one instant.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, Default)]
pub struct MoverState {
    /// Position, metres.
    pub pos: [f64; 2],
    /// Velocity, m/s.
    pub vel: [f64; 2],
}

/// Axis-aligned world bounds (x_min, y_min, x_max, y_max), metres.
pub type Bounds = [f64; 4];

fn is_zero(v: &f64) -> bool {
    *v == 0.0
}

impl MoverSpec {
    /// Checks every number and the model's shape.
    pub fn validate(&self) -> Result<(), WorldError> {
        let who = format!("mover {}", self.id);
        check_positive(&format!("{who} radius (m)"), self.radius)?;
        match &self.motion {
            MotionModel::ConstantVelocity {
                start,
                velocity,
                since,
            } => {
                check_point(&format!("{who} start"), *start)?;
                check_point(&format!("{who} velocity"), *velocity)?;
                check_min(&format!("{who} since (s)"), *since, 0.0)
            }
            MotionModel::BackAndForth { a, b, speed } => {
                check_point(&format!("{who} a"), *a)?;
                check_point(&format!("{who} b"), *b)?;
                check_min(&format!("{who} speed (m/s)"), *speed, 0.0)
            }
            MotionModel::WaypointLoop { points, speed } => {
                if points.len() < 2 {
                    return Err(WorldError::InvalidParameter(format!(
                        "{who} waypoint loop: needs at least 2 points, got {}",
                        points.len()
                    )));
                }
                for (i, p) in points.iter().enumerate() {
                    check_point(&format!("{who} point {i}"), *p)?;
                }
                check_min(&format!("{who} speed (m/s)"), *speed, 0.0)
            }
            MotionModel::Scripted { samples } => {
                if samples.is_empty() {
                    return Err(WorldError::InvalidParameter(format!(
                        "{who} script: needs at least 1 sample"
                    )));
                }
                for (i, s) in samples.iter().enumerate() {
                    check_point(&format!("{who} sample {i}"), [s.x, s.y])?;
                    let late = s.t.abs() > crate::num::MAX_PARAM;
                    if !s.t.is_finite() || late || (i > 0 && s.t <= samples[i - 1].t) {
                        return Err(WorldError::InvalidParameter(format!(
                            "{who} sample {i} time {} s: times must be finite, within ±{} s and strictly increasing",
                            crate::num::fmt_num(s.t),
                            crate::num::fmt_num(crate::num::MAX_PARAM)
                        )));
                    }
                }
                Ok(())
            }
        }
    }

    /// Position and velocity at time `t` ≥ 0 on `map`. Computes a
    /// constant-velocity mover's bounces from its start on every call: an
    /// episode keeps a [`MoverTrack`] instead.
    pub fn state_at(&self, t: f64, map: &StaticMap) -> MoverState {
        MoverTrack::new(self, map).state_at(self, map, t)
    }

    /// Checks the mover against the static map: its disc must not start
    /// overlapping a blocked cell or the map edge (touching is allowed: a
    /// bouncing mover touches the wall it bounces off). A constant-velocity
    /// mover then never enters one ([`MoverTrack`]); the path models follow
    /// the path they are given, walls or not (docs/algorithms.md §movers).
    pub fn check_on(&self, map: &StaticMap) -> Result<(), WorldError> {
        let start = match &self.motion {
            MotionModel::ConstantVelocity { start, .. } => *start,
            _ => self.state_at(0.0, map).pos,
        };
        if overlaps(map, start, self.radius) {
            return Err(WorldError::MoverInWall {
                id: self.id,
                x: start[0],
                y: start[1],
                reason: "starts overlapping a wall or the map edge".into(),
            });
        }
        Ok(())
    }
}

/// Whether a disc at `c` of radius `r` overlaps a blocked cell or the map
/// edge by more than rounding (1e-9 m): touching is not overlapping.
pub(crate) fn overlaps(map: &StaticMap, c: [f64; 2], r: f64) -> bool {
    let b = map.bounds();
    let eps = 1e-9;
    if c[0] - r < b[0] - eps
        || c[1] - r < b[1] - eps
        || c[0] + r > b[2] + eps
        || c[1] + r > b[3] + eps
    {
        return true;
    }
    let g = map.grid();
    let res = g.resolution();
    let h = g.height() as i64;
    let cols = (((c[0] - r - b[0]) / res).floor() as i64).max(0)
        ..=(((c[0] + r - b[0]) / res).floor() as i64).min(g.width() as i64 - 1);
    for u in (((c[1] - r - b[1]) / res).floor() as i64).max(0)
        ..=(((c[1] + r - b[1]) / res).floor() as i64).min(h - 1)
    {
        for col in cols.clone() {
            if !map.is_blocked(col, h - 1 - u) {
                continue;
            }
            let (x0, y0) = (b[0] + col as f64 * res, b[1] + u as f64 * res);
            let dx = (x0 - c[0]).max(c[0] - (x0 + res)).max(0.0);
            let dy = (y0 - c[1]).max(c[1] - (y0 + res)).max(0.0);
            if dx * dx + dy * dy < (r - eps) * (r - eps) {
                return true;
            }
        }
    }
    false
}

/// One straight leg of a bouncing mover: from `pos` at time `t` with `vel`.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Leg {
    t: f64,
    pos: [f64; 2],
    vel: [f64; 2],
}

/// Bounces in a row at one instant after which a mover counts as jammed
/// and stops (a disc wedged where every way out is blocked).
const MAX_INSTANT_BOUNCES: u32 = 4;

/// The exact path of a mover on a map. For the constant-velocity model:
/// straight legs joined by bounces, each found as the disc's first contact
/// with a blocked cell or the map edge (closed-form time of impact of a
/// disc against a square: its sides pushed out by the radius and its
/// corners rounded), the velocity then reflected about the contact normal
/// (`v − 2(v·n)n`: a side flips one component exactly, a corner turns the
/// velocity about the line to its centre). Each leg is computed from the
/// previous one alone, so the path is the same however far and however
/// often it is extended. The other models need no track.
#[derive(Debug, Clone, PartialEq)]
pub struct MoverTrack {
    legs: Vec<Leg>,
    /// When the last leg ends in a bounce, and the contact normal there
    /// (`None`: it goes on forever).
    end: Option<(f64, [f64; 2])>,
    /// Bounces in a row at the same instant (see [`MAX_INSTANT_BOUNCES`]).
    instant: u32,
}

impl MoverTrack {
    /// The track of `spec` on `map`: its first leg.
    pub fn new(spec: &MoverSpec, map: &StaticMap) -> MoverTrack {
        let mut tr = MoverTrack {
            legs: Vec::new(),
            end: None,
            instant: 0,
        };
        if let MotionModel::ConstantVelocity {
            start,
            velocity,
            since,
        } = &spec.motion
        {
            let leg = Leg {
                t: *since,
                pos: *start,
                vel: *velocity,
            };
            tr.end = leg_contact(map, &leg, spec.radius);
            tr.legs.push(leg);
        }
        tr
    }

    /// Computes the legs up to time `t` (an episode calls it before it
    /// reads a new instant, so [`MoverTrack::state_at`] finds them).
    pub fn extend_to(&mut self, spec: &MoverSpec, map: &StaticMap, t: f64) {
        while let Some((te, n)) = self.end {
            if te > t {
                break;
            }
            let last = self.legs[self.legs.len() - 1];
            let tau = te - last.t;
            let pos = [
                last.pos[0] + last.vel[0] * tau,
                last.pos[1] + last.vel[1] * tau,
            ];
            let dot = last.vel[0] * n[0] + last.vel[1] * n[1];
            let mut vel = [
                last.vel[0] - 2.0 * dot * n[0],
                last.vel[1] - 2.0 * dot * n[1],
            ];
            self.instant = if tau == 0.0 { self.instant + 1 } else { 0 };
            if self.instant >= MAX_INSTANT_BOUNCES {
                vel = [0.0, 0.0];
            }
            let leg = Leg { t: te, pos, vel };
            self.end = leg_contact(map, &leg, spec.radius);
            self.legs.push(leg);
        }
    }

    /// Position and velocity of `spec` at time `t` ≥ 0 on `map` (the map
    /// and spec this track was made from). A time beyond the legs computed
    /// so far is computed on a copy, so the answer never depends on how far
    /// the track was extended.
    pub fn state_at(&self, spec: &MoverSpec, map: &StaticMap, t: f64) -> MoverState {
        let t = t.max(0.0);
        match &spec.motion {
            MotionModel::ConstantVelocity { start, .. } => {
                if self.end.is_some_and(|(te, _)| te <= t) {
                    let mut more = self.clone();
                    more.extend_to(spec, map, t);
                    return more.state_at(spec, map, t);
                }
                match self.legs.first() {
                    Some(first) if t >= first.t => {
                        let i = self.legs.partition_point(|l| l.t <= t) - 1;
                        let l = self.legs[i];
                        let dt = t - l.t;
                        MoverState {
                            pos: [l.pos[0] + l.vel[0] * dt, l.pos[1] + l.vel[1] * dt],
                            vel: l.vel,
                        }
                    }
                    // Before `since` it waits at its start.
                    _ => MoverState {
                        pos: *start,
                        vel: [0.0, 0.0],
                    },
                }
            }
            MotionModel::BackAndForth { a, b, speed } => back_and_forth(*a, *b, *speed, t),
            MotionModel::WaypointLoop { points, speed } => waypoint_loop(points, *speed, t),
            MotionModel::Scripted { samples } => scripted(samples, t),
        }
    }

    /// Bounces computed so far.
    pub fn bounces(&self) -> usize {
        self.legs.len().saturating_sub(1)
    }
}

/// When a leg meets a wall or the map edge: (absolute time, outward normal
/// there), or `None` for a mover at rest.
fn leg_contact(map: &StaticMap, leg: &Leg, r: f64) -> Option<(f64, [f64; 2])> {
    let speed = (leg.vel[0] * leg.vel[0] + leg.vel[1] * leg.vel[1]).sqrt();
    if speed == 0.0 {
        return None;
    }
    let u = [leg.vel[0] / speed, leg.vel[1] / speed];
    // The map edge is always ahead, so a moving disc always meets something.
    first_contact(map, leg.pos, u, r, f64::INFINITY).map(|(s, n)| (leg.t + s / speed, n))
}

/// The first contact of a disc of radius `r`, whose centre runs from `p`
/// along the unit vector `u`, with a blocked cell or the map edge within
/// `reach` metres of travel: (distance travelled, outward unit normal of
/// the obstacle at the contact). Only contacts the disc moves into count
/// (u·n < 0), so a disc just reflected off a wall does not meet it again;
/// a contact up to 1e-9 m behind `p` (rounding) counts as at `p`.
fn first_contact(
    map: &StaticMap,
    p: [f64; 2],
    u: [f64; 2],
    r: f64,
    reach: f64,
) -> Option<(f64, [f64; 2])> {
    const EPS: f64 = 1e-9;
    let b = map.bounds();
    let mut best: Option<(f64, [f64; 2])> = None;
    let offer = |s: f64, n: [f64; 2], best: &mut Option<(f64, [f64; 2])>| {
        if s >= -EPS && s <= reach && best.map_or(true, |(bs, _)| s.max(0.0) < bs) {
            *best = Some((s.max(0.0), n));
        }
    };
    // The map edge: the centre's box shrunk by r.
    for k in 0..2 {
        let mut n = [0.0, 0.0];
        if u[k] < 0.0 {
            n[k] = 1.0;
            offer((b[k] + r - p[k]) / u[k], n, &mut best);
        } else if u[k] > 0.0 {
            n[k] = -1.0;
            offer((b[k + 2] - r - p[k]) / u[k], n, &mut best);
        }
    }
    let g = map.grid();
    let res = g.resolution();
    let (w, h) = (g.width() as i64, g.height() as i64);
    // March in chunks: a cell first touched within a chunk lies in the
    // chunk's box grown by r, so once the best contact is no later than
    // the chunk's end, no later chunk can beat it.
    let chunk = (8.0 * res).max(r);
    let mut s0 = 0.0f64;
    loop {
        let limit = best.map_or(reach, |(bs, _)| bs.min(reach));
        if s0 > limit {
            break;
        }
        let s1 = s0 + chunk;
        let a = [p[0] + u[0] * (s0 - EPS), p[1] + u[1] * (s0 - EPS)];
        let e = [p[0] + u[0] * s1, p[1] + u[1] * s1];
        let lo = [a[0].min(e[0]) - r, a[1].min(e[1]) - r];
        let hi = [a[0].max(e[0]) + r, a[1].max(e[1]) + r];
        let c0 = (((lo[0] - b[0]) / res).floor() as i64).max(0);
        let c1 = (((hi[0] - b[0]) / res).floor() as i64).min(w - 1);
        let u0 = (((lo[1] - b[1]) / res).floor() as i64).max(0);
        let u1 = (((hi[1] - b[1]) / res).floor() as i64).min(h - 1);
        for uu in u0..=u1 {
            for c in c0..=c1 {
                if !map.is_blocked(c, h - 1 - uu) {
                    continue;
                }
                let x0 = b[0] + c as f64 * res;
                let y0 = b[1] + uu as f64 * res;
                if let Some((s, n)) = box_contact(p, u, r, [x0, y0], [x0 + res, y0 + res], EPS) {
                    offer(s, n, &mut best);
                }
            }
        }
        if best.is_some_and(|(bs, _)| bs <= s1) || s1 >= reach {
            break;
        }
        s0 = s1;
    }
    best
}

/// First contact of a disc (centre `p` moving along unit `u`, radius `r`)
/// with the square [lo, hi] it moves into: (distance, outward normal). The
/// disc touches the square when its centre reaches the square grown by r:
/// two slabs (the sides pushed out by r) and four corner circles of radius r.
fn box_contact(
    p: [f64; 2],
    u: [f64; 2],
    r: f64,
    lo: [f64; 2],
    hi: [f64; 2],
    eps: f64,
) -> Option<(f64, [f64; 2])> {
    let mut best: Option<(f64, [f64; 2])> = None;
    let mut keep = |s: f64, n: [f64; 2]| {
        if s >= -eps && best.map_or(true, |(bs, _)| s.max(0.0) < bs) {
            best = Some((s.max(0.0), n));
        }
    };
    // Sides: axis k's face at lo[k] − r (moving +) or hi[k] + r (moving −),
    // met where the other coordinate is within the square's span.
    for k in 0..2 {
        let o = 1 - k;
        let (face, nk) = if u[k] > 0.0 {
            (lo[k] - r, -1.0)
        } else if u[k] < 0.0 {
            (hi[k] + r, 1.0)
        } else {
            continue;
        };
        let s = (face - p[k]) / u[k];
        let q = p[o] + u[o] * s.max(0.0);
        if q >= lo[o] && q <= hi[o] {
            let mut n = [0.0, 0.0];
            n[k] = nk;
            keep(s, n);
        }
    }
    // Corners: the entering root of |p + u·s − c| = r.
    for c in [lo, [hi[0], lo[1]], [lo[0], hi[1]], hi] {
        let d = [p[0] - c[0], p[1] - c[1]];
        let bq = d[0] * u[0] + d[1] * u[1];
        let disc = bq * bq - (d[0] * d[0] + d[1] * d[1] - r * r);
        if disc <= 0.0 {
            continue;
        }
        let s = -bq - disc.sqrt();
        let sc = s.max(0.0);
        let m = [d[0] + u[0] * sc, d[1] + u[1] * sc];
        let len = (m[0] * m[0] + m[1] * m[1]).sqrt();
        if len == 0.0 {
            continue;
        }
        let n = [m[0] / len, m[1] / len];
        // Moving into the corner at the contact, not out of it.
        if n[0] * u[0] + n[1] * u[1] < 0.0 {
            keep(s, n);
        }
    }
    best
}

fn lerp(a: [f64; 2], b: [f64; 2], s: f64) -> [f64; 2] {
    [a[0] + (b[0] - a[0]) * s, a[1] + (b[1] - a[1]) * s]
}

fn back_and_forth(a: [f64; 2], b: [f64; 2], speed: f64, t: f64) -> MoverState {
    let d = [b[0] - a[0], b[1] - a[1]];
    let len = (d[0] * d[0] + d[1] * d[1]).sqrt();
    if len == 0.0 || speed == 0.0 {
        return MoverState {
            pos: a,
            vel: [0.0, 0.0],
        };
    }
    let s = (speed * t) % (2.0 * len);
    let u = [d[0] / len * speed, d[1] / len * speed];
    if s < len {
        MoverState {
            pos: lerp(a, b, s / len),
            vel: u,
        }
    } else {
        MoverState {
            pos: lerp(a, b, (2.0 * len - s) / len),
            vel: [-u[0], -u[1]],
        }
    }
}

fn waypoint_loop(points: &[[f64; 2]], speed: f64, t: f64) -> MoverState {
    let n = points.len();
    let seg_len = |i: usize| {
        let (p, q) = (points[i], points[(i + 1) % n]);
        ((q[0] - p[0]).powi(2) + (q[1] - p[1]).powi(2)).sqrt()
    };
    let total: f64 = (0..n).map(seg_len).sum();
    if total == 0.0 || speed == 0.0 {
        return MoverState {
            pos: points[0],
            vel: [0.0, 0.0],
        };
    }
    let mut s = (speed * t) % total;
    for i in 0..n {
        let l = seg_len(i);
        if s < l || i == n - 1 {
            let (p, q) = (points[i], points[(i + 1) % n]);
            if l == 0.0 {
                continue;
            }
            let f = (s / l).min(1.0);
            return MoverState {
                pos: lerp(p, q, f),
                vel: [(q[0] - p[0]) / l * speed, (q[1] - p[1]) / l * speed],
            };
        }
        s -= l;
    }
    MoverState {
        pos: points[0],
        vel: [0.0, 0.0],
    }
}

fn scripted(samples: &[ScriptSample], t: f64) -> MoverState {
    let first = samples[0];
    if t <= first.t {
        return MoverState {
            pos: [first.x, first.y],
            vel: [0.0, 0.0],
        };
    }
    for w in samples.windows(2) {
        let (p, q) = (w[0], w[1]);
        if t < q.t {
            let dt = q.t - p.t;
            let f = (t - p.t) / dt;
            return MoverState {
                pos: lerp([p.x, p.y], [q.x, q.y], f),
                vel: [(q.x - p.x) / dt, (q.y - p.y) / dt],
            };
        }
    }
    let last = samples[samples.len() - 1];
    MoverState {
        pos: [last.x, last.y],
        vel: [0.0, 0.0],
    }
}

/// The motion model of a mover placed by hand while an episode runs (the
/// page's "press = position, drag = velocity" gesture), see
/// [`MoverSpec::placed`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Placement {
    /// Straight on at the given velocity from the drop time, bouncing off
    /// walls and the map edge.
    ConstantVelocity,
    /// Along the velocity for `span` metres, back, and again.
    BackAndForth,
    /// Around a square of side `span` turning left, the drop point in the
    /// middle of the side run along the velocity.
    WaypointLoop,
}

impl MoverSpec {
    /// A mover that is at `pos` moving with `vel` at episode time `t` ≥ 0.
    ///
    /// Motion models run on episode time from t = 0, so a mover dropped in
    /// mid-run needs its model shifted: the constant-velocity mover starts
    /// at `pos` at time `t` (`since`); the back-and-forth ends and the loop's first point are
    /// chosen so that the model's phase at `t` is exactly `pos`, heading
    /// along `vel`. `span` (m, > 0) is the back-and-forth length and the
    /// loop's side; unused for constant velocity. A zero velocity gives a
    /// mover standing at `pos`. Errors name the bad number.
    pub fn placed(
        id: u32,
        radius: f64,
        how: Placement,
        pos: [f64; 2],
        vel: [f64; 2],
        span: f64,
        t: f64,
    ) -> Result<MoverSpec, WorldError> {
        let who = format!("mover {id}");
        check_positive(&format!("{who} radius (m)"), radius)?;
        check_point(&format!("{who} position"), pos)?;
        check_point(&format!("{who} velocity"), vel)?;
        check_min(&format!("{who} placement time (s)"), t, 0.0)?;
        if how != Placement::ConstantVelocity {
            check_positive(&format!("{who} span (m)"), span)?;
        }
        let speed = (vel[0] * vel[0] + vel[1] * vel[1]).sqrt();
        let motion = if speed == 0.0 {
            MotionModel::ConstantVelocity {
                start: pos,
                velocity: [0.0, 0.0],
                since: 0.0,
            }
        } else {
            let u = [vel[0] / speed, vel[1] / speed];
            let at = |p: [f64; 2], d: [f64; 2], s: f64| [p[0] + d[0] * s, p[1] + d[1] * s];
            match how {
                Placement::ConstantVelocity => MotionModel::ConstantVelocity {
                    start: pos,
                    velocity: vel,
                    since: t,
                },
                Placement::BackAndForth => {
                    // The same phase the model computes: s in [0, 2·span).
                    let s = (speed * t) % (2.0 * span);
                    let (a, b) = if s < span {
                        // Outbound leg: s past `a`, heading for `b` along u.
                        let a = at(pos, u, -s);
                        (a, at(a, u, span))
                    } else {
                        // Return leg runs b → a, so b → a must point along u.
                        let a = at(pos, u, 2.0 * span - s);
                        (a, at(a, u, -span))
                    };
                    MotionModel::BackAndForth { a, b, speed }
                }
                Placement::WaypointLoop => {
                    let n = [-u[1], u[0]];
                    // Corners in travel order; `pos` is the middle of the
                    // first side (not a corner, where the heading is
                    // ambiguous), at arc length span/2.
                    let q0 = at(pos, u, -0.5 * span);
                    let q1 = at(q0, u, span);
                    let q2 = at(q1, n, span);
                    let q3 = at(q0, n, span);
                    let corners = [q0, q1, q2, q3];
                    // At t the model has gone s along the loop from its first
                    // point, so that point lies s before `pos`.
                    let total = 4.0 * span;
                    let s = (speed * t) % total;
                    let back = (0.5 * span - s).rem_euclid(total);
                    let k = ((back / span) as usize).min(3);
                    let f = back - k as f64 * span;
                    let q = corners[k];
                    let e = corners[(k + 1) % 4];
                    let first = [
                        q[0] + (e[0] - q[0]) * f / span,
                        q[1] + (e[1] - q[1]) * f / span,
                    ];
                    let mut points = vec![first];
                    for j in 1..=4 {
                        let c = corners[(k + j) % 4];
                        // Skip a corner the first point sits on.
                        if j < 4 || f > 0.0 {
                            points.push(c);
                        }
                    }
                    MotionModel::WaypointLoop { points, speed }
                }
            }
        };
        let m = MoverSpec { id, radius, motion };
        m.validate()?;
        Ok(m)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::map::{OccupancyGrid, Pose2};

    /// A map from ASCII rows (top row first) at `res` m per cell, its
    /// bottom-left corner at `origin`.
    fn map_of(rows: &[&str], res: f64, origin: [f64; 2]) -> StaticMap {
        let g = OccupancyGrid::from_ascii(&rows.join("\n"))
            .unwrap()
            .with_frame(
                res,
                Pose2 {
                    x: origin[0],
                    y: origin[1],
                    yaw: 0.0,
                },
            )
            .unwrap();
        StaticMap::new(g, true).unwrap()
    }

    /// An open square map of side `side` m (1 m cells) from `origin`.
    fn open(side: usize, origin: [f64; 2]) -> StaticMap {
        let row = ".".repeat(side);
        map_of(&vec![row.as_str(); side], 1.0, origin)
    }

    fn cv(id: u32, radius: f64, start: [f64; 2], velocity: [f64; 2]) -> MoverSpec {
        MoverSpec {
            id,
            radius,
            motion: MotionModel::ConstantVelocity {
                start,
                velocity,
                since: 0.0,
            },
        }
    }

    /// Samples `m` on `map` every `dt` for `steps` steps through one track
    /// extended step by step (as an episode does), checking at each that
    /// the disc neither overlaps a wall nor leaves the map, keeps its speed,
    /// and is where a fresh evaluation puts it.
    fn run_checked(m: &MoverSpec, map: &StaticMap, dt: f64, steps: usize) -> MoverTrack {
        let mut tr = MoverTrack::new(m, map);
        let MotionModel::ConstantVelocity { velocity, .. } = m.motion else {
            panic!("constant velocity only");
        };
        let speed = velocity[0].hypot(velocity[1]);
        for k in 0..=steps {
            let t = k as f64 * dt;
            tr.extend_to(m, map, t);
            let s = tr.state_at(m, map, t);
            assert!(
                !overlaps(map, s.pos, m.radius),
                "mover {} at t = {t} is in a wall or off the map: {:?}",
                m.id,
                s.pos
            );
            let v = s.vel[0].hypot(s.vel[1]);
            assert!((v - speed).abs() < 1e-9, "speed {v} at t = {t}");
            if k % 97 == 0 {
                assert_eq!(m.state_at(t, map), s, "fresh evaluation at t = {t}");
            }
        }
        tr
    }

    #[test]
    fn a_mover_heading_off_the_map_bounces_off_its_edge_and_stays_on_it() {
        let map = open(10, [0.0, 0.0]);
        let m = cv(1, 0.5, [5.0, 5.0], [1.0, 0.0]);
        let s = m.state_at(2.0, &map);
        assert_eq!(s.pos, [7.0, 5.0]);
        assert_eq!(s.vel, [1.0, 0.0]);
        // Touches the right edge at t = 4.5 (centre at 9.5), comes back.
        let s = m.state_at(6.5, &map);
        assert!((s.pos[0] - 7.5).abs() < 1e-12 && s.pos[1] == 5.0, "{s:?}");
        assert_eq!(s.vel, [-1.0, 0.0]);
        // Back and forth between the two edges for good.
        let s = m.state_at(4.5 + 9.0 + 1.0, &map);
        assert!((s.pos[0] - 1.5).abs() < 1e-9, "{s:?}");
        assert_eq!(s.vel, [1.0, 0.0]);
        let tr = run_checked(&cv(2, 0.3, [2.0, 3.0], [-0.7, 0.45]), &map, 0.1, 3000);
        assert!(tr.bounces() > 20, "{}", tr.bounces());
    }

    #[test]
    fn a_mover_heading_into_a_wall_bounces_and_never_enters_it() {
        // 0.1 m cells; a wall block from x = 3.0 to 3.5, y = 1.0 to 2.0.
        let mut rows = vec![".".repeat(60); 30];
        for row in rows.iter_mut().skip(10).take(10) {
            row.replace_range(30..35, "#####");
        }
        let rows: Vec<&str> = rows.iter().map(String::as_str).collect();
        let map = map_of(&rows, 0.1, [0.0, 0.0]);
        // Head-on into the block's left side: bounces at x = 3.0 − 0.25.
        let m = cv(3, 0.25, [1.0, 1.5], [0.5, 0.0]);
        let s = m.state_at(3.0, &map);
        assert!((s.pos[0] - 2.5).abs() < 1e-12, "{s:?}");
        assert_eq!(s.vel, [0.5, 0.0]);
        let s = m.state_at(4.0, &map);
        assert!((s.pos[0] - 2.5).abs() < 1e-9, "{s:?}");
        assert_eq!(s.vel, [-0.5, 0.0]);
        // Onto the convex corner (3.0, 2.0) from the upper left at 45°, the
        // centre's line through it: it meets the corner, not a side, and
        // is sent straight back (the normal is along the motion).
        let d = 0.25 / 2f64.sqrt();
        let m = cv(4, 0.25, [2.2, 2.8], [0.3, -0.3]);
        let t_hit = (3.0 - d - 2.2) / 0.3;
        let s = m.state_at(t_hit, &map);
        assert!((s.pos[0] - (3.0 - d)).abs() < 1e-9 && (s.pos[1] - (2.0 + d)).abs() < 1e-9);
        let s = m.state_at(t_hit + 0.5, &map);
        assert!(
            (s.vel[0] + 0.3).abs() < 1e-9 && (s.vel[1] - 0.3).abs() < 1e-9,
            "{s:?}"
        );
        // A long run of movers at many headings never enters the block or
        // leaves the map, and bounces often.
        for (k, (x, y)) in [(0.5, 0.5), (4.5, 2.5), (2.0, 2.6), (5.0, 0.4)]
            .into_iter()
            .enumerate()
        {
            for a in 0..12 {
                let th = 0.37 + a as f64 * std::f64::consts::PI / 6.0;
                let m = cv(k as u32, 0.2, [x, y], [0.8 * th.cos(), 0.8 * th.sin()]);
                let tr = run_checked(&m, &map, 0.1, 2000);
                assert!(tr.bounces() > 30, "{} bounces", tr.bounces());
            }
        }
    }

    #[test]
    fn the_bounces_do_not_depend_on_the_step() {
        let map = map_of(
            &[
                "..........",
                "...##.....",
                "...##..#..",
                ".......#..",
                "..........",
            ],
            0.5,
            [-1.0, 2.0],
        );
        let m = cv(1, 0.2, [-0.5, 2.3], [0.61, 0.37]);
        let fine = run_checked(&m, &map, 0.01, 6000);
        let coarse = run_checked(&m, &map, 0.7, 86);
        for t in [0.0, 3.3, 17.0, 42.42, 59.99] {
            assert_eq!(fine.state_at(&m, &map, t), coarse.state_at(&m, &map, t));
        }
    }

    #[test]
    fn a_mover_starting_in_a_wall_or_over_the_map_edge_is_refused() {
        let map = map_of(&["....", ".#..", "...."], 1.0, [0.0, 0.0]);
        // Centre in the wall cell (1..2, 1..2).
        let e = cv(5, 0.2, [1.5, 1.5], [1.0, 0.0])
            .check_on(&map)
            .unwrap_err();
        assert!(matches!(e, WorldError::MoverInWall { id: 5, .. }), "{e:?}");
        assert!(
            e.to_string()
                .starts_with("mover 5 at (1.500, 1.500) m starts"),
            "{e}"
        );
        // Overlapping the map edge.
        assert!(cv(6, 0.3, [0.2, 2.5], [0.0, 0.0]).check_on(&map).is_err());
        // Touching the wall is fine (a bounce touches it).
        cv(7, 0.5, [0.5, 1.5], [1.0, 0.0]).check_on(&map).unwrap();
        // A path model is checked where it is at t = 0.
        let bf = |a: [f64; 2], b: [f64; 2]| MoverSpec {
            id: 8,
            radius: 0.2,
            motion: MotionModel::BackAndForth { a, b, speed: 1.0 },
        };
        assert!(bf([1.5, 1.4], [3.5, 0.5]).check_on(&map).is_err());
        bf([0.5, 0.5], [3.5, 0.5]).check_on(&map).unwrap();
    }

    #[test]
    fn back_and_forth_returns() {
        let m = MoverSpec {
            id: 0,
            radius: 0.2,
            motion: MotionModel::BackAndForth {
                a: [0.0, 0.0],
                b: [2.0, 0.0],
                speed: 1.0,
            },
        };
        assert_eq!(m.state_at(1.0, &open(10, [0.0, 0.0])).pos, [1.0, 0.0]);
        let s = m.state_at(3.0, &open(10, [0.0, 0.0]));
        assert!((s.pos[0] - 1.0).abs() < 1e-12 && s.vel[0] < 0.0);
        assert!((m.state_at(4.0, &open(10, [0.0, 0.0])).pos[0]).abs() < 1e-12);
    }

    #[test]
    fn waypoint_loop_and_script() {
        let m = MoverSpec {
            id: 0,
            radius: 0.2,
            motion: MotionModel::WaypointLoop {
                points: vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]],
                speed: 1.0,
            },
        };
        let s = m.state_at(1.5, &open(10, [0.0, 0.0]));
        assert!((s.pos[0] - 1.0).abs() < 1e-12 && (s.pos[1] - 0.5).abs() < 1e-12);
        let m = MoverSpec {
            id: 0,
            radius: 0.2,
            motion: MotionModel::Scripted {
                samples: vec![
                    ScriptSample {
                        t: 1.0,
                        x: 0.0,
                        y: 0.0,
                    },
                    ScriptSample {
                        t: 3.0,
                        x: 2.0,
                        y: 0.0,
                    },
                ],
            },
        };
        assert_eq!(m.state_at(0.0, &open(10, [0.0, 0.0])).pos, [0.0, 0.0]);
        assert_eq!(
            m.state_at(2.0, &open(10, [0.0, 0.0])),
            MoverState {
                pos: [1.0, 0.0],
                vel: [1.0, 0.0]
            }
        );
        assert_eq!(m.state_at(9.0, &open(10, [0.0, 0.0])).pos, [2.0, 0.0]);
    }

    #[test]
    fn validation_catches_bad_input() {
        let bad = MoverSpec {
            id: 3,
            radius: 0.2,
            motion: MotionModel::Scripted {
                samples: vec![
                    ScriptSample {
                        t: 1.0,
                        x: 0.0,
                        y: 0.0,
                    },
                    ScriptSample {
                        t: 1.0,
                        x: 2.0,
                        y: 0.0,
                    },
                ],
            },
        };
        assert!(bad.validate().is_err());
        let nan = MoverSpec {
            id: 3,
            radius: f64::NAN,
            motion: MotionModel::BackAndForth {
                a: [0.0, 0.0],
                b: [1.0, 0.0],
                speed: 1.0,
            },
        };
        assert!(nan
            .validate()
            .unwrap_err()
            .to_string()
            .contains("mover 3 radius"));
    }

    #[test]
    fn placed_movers_are_where_they_were_dropped() {
        let big = open(200, [-100.0, -100.0]);
        let pos = [3.0, -2.0];
        let vel = [0.6, 0.8];
        for how in [
            Placement::ConstantVelocity,
            Placement::BackAndForth,
            Placement::WaypointLoop,
        ] {
            for t in [0.0, 0.1, 1.7, 2.5, 4.0, 13.3, 57.9] {
                let m = MoverSpec::placed(4, 0.3, how, pos, vel, 2.0, t).unwrap();
                let s = m.state_at(t, &big);
                let (dx, dy) = (s.pos[0] - pos[0], s.pos[1] - pos[1]);
                assert!(
                    dx.abs() < 1e-9 && dy.abs() < 1e-9,
                    "{how:?} t={t}: {:?}",
                    s.pos
                );
                let (ex, ey) = (s.vel[0] - vel[0], s.vel[1] - vel[1]);
                assert!(
                    ex.abs() < 1e-9 && ey.abs() < 1e-9,
                    "{how:?} t={t}: vel {:?}",
                    s.vel
                );
                // It keeps moving along its velocity just afterwards.
                let later = m.state_at(t + 0.01, &big);
                let (lx, ly) = (later.pos[0] - pos[0] - 0.006, later.pos[1] - pos[1] - 0.008);
                assert!(
                    lx.abs() < 1e-9 && ly.abs() < 1e-9,
                    "{how:?} t={t}: {:?}",
                    later.pos
                );
            }
        }
        // Back-and-forth turns around within `span`; the loop comes back
        // to the drop point after 4·span.
        let m = MoverSpec::placed(1, 0.3, Placement::BackAndForth, pos, vel, 2.0, 7.0).unwrap();
        let s = m.state_at(7.0 + 2.0 / 1.0 + 0.5, &big);
        assert!(s.vel[0] < 0.0 && s.vel[1] < 0.0, "{s:?}");
        let m = MoverSpec::placed(1, 0.3, Placement::WaypointLoop, pos, vel, 2.0, 7.0).unwrap();
        let s = m.state_at(7.0 + 8.0, &big);
        assert!((s.pos[0] - pos[0]).abs() < 1e-9 && (s.pos[1] - pos[1]).abs() < 1e-9);
        // Standing still, and bad numbers.
        let m =
            MoverSpec::placed(2, 0.3, Placement::WaypointLoop, pos, [0.0, 0.0], 2.0, 5.0).unwrap();
        assert_eq!(m.state_at(9.0, &big).pos, pos);
        let e = MoverSpec::placed(2, 0.3, Placement::BackAndForth, pos, vel, 0.0, 1.0).unwrap_err();
        assert!(e.to_string().contains("span"), "{e}");
        let e = MoverSpec::placed(2, f64::NAN, Placement::BackAndForth, pos, vel, 1.0, 1.0)
            .unwrap_err();
        assert!(e.to_string().contains("radius"), "{e}");
        let e = MoverSpec::placed(
            2,
            0.3,
            Placement::ConstantVelocity,
            pos,
            [f64::INFINITY, 0.0],
            1.0,
            1.0,
        )
        .unwrap_err();
        assert!(e.to_string().contains("velocity"), "{e}");
    }
}
