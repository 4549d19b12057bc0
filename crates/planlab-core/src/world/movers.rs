//! Moving disc obstacles and their motion models (docs/algorithms.md §movers): constant velocity
//! stopping at the map edge (\[T\] Fig 3-11), back-and-forth between two points
//! (\[S\] Fig 12), a waypoint loop and a scripted time series.
//!
//! Each model is a closed-form function of time, so a mover's state at any
//! instant is exact, cheap and identical on replay, whatever the step size.

use serde::{Deserialize, Serialize};

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
    /// Straight line at constant velocity from `start`; stops (velocity 0)
    /// when the disc touches the map boundary.
    ConstantVelocity {
        /// Position at t = 0, metres.
        start: [f64; 2],
        /// Velocity (v_x, v_y), m/s.
        velocity: [f64; 2],
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

/// Axis-aligned world bounds (x_min, y_min, x_max, y_max) a mover's centre
/// must stay within (the map shrunk by the mover's radius).
pub type Bounds = [f64; 4];

impl MoverSpec {
    /// Checks every number and the model's shape.
    pub fn validate(&self) -> Result<(), WorldError> {
        let who = format!("mover {}", self.id);
        check_positive(&format!("{who} radius (m)"), self.radius)?;
        match &self.motion {
            MotionModel::ConstantVelocity { start, velocity } => {
                check_point(&format!("{who} start"), *start)?;
                check_point(&format!("{who} velocity"), *velocity)
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

    /// Position and velocity at time `t` ≥ 0. `bounds` is the map's extent;
    /// only the constant-velocity model uses it (it stops at the edge).
    pub fn state_at(&self, t: f64, bounds: Bounds) -> MoverState {
        let t = t.max(0.0);
        match &self.motion {
            MotionModel::ConstantVelocity { start, velocity } => {
                constant_velocity(*start, *velocity, t, self.radius, bounds)
            }
            MotionModel::BackAndForth { a, b, speed } => back_and_forth(*a, *b, *speed, t),
            MotionModel::WaypointLoop { points, speed } => waypoint_loop(points, *speed, t),
            MotionModel::Scripted { samples } => scripted(samples, t),
        }
    }
}

fn constant_velocity(p0: [f64; 2], v: [f64; 2], t: f64, r: f64, b: Bounds) -> MoverState {
    // Time until the disc first touches an edge it is heading for.
    let mut t_stop = f64::INFINITY;
    for k in 0..2 {
        let (lo, hi) = (b[k] + r, b[k + 2] - r);
        if v[k] > 0.0 {
            t_stop = t_stop.min(((hi - p0[k]) / v[k]).max(0.0));
        } else if v[k] < 0.0 {
            t_stop = t_stop.min(((lo - p0[k]) / v[k]).max(0.0));
        }
    }
    let tt = t.min(t_stop);
    let moving = t < t_stop;
    MoverState {
        pos: [p0[0] + v[0] * tt, p0[1] + v[1] * tt],
        vel: if moving { v } else { [0.0, 0.0] },
    }
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
    /// Straight on at the given velocity, stopping at the map edge.
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
    /// mid-run needs its model shifted: the constant-velocity start is
    /// `pos − vel·t`; the back-and-forth ends and the loop's first point are
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
            }
        } else {
            let u = [vel[0] / speed, vel[1] / speed];
            let at = |p: [f64; 2], d: [f64; 2], s: f64| [p[0] + d[0] * s, p[1] + d[1] * s];
            match how {
                Placement::ConstantVelocity => MotionModel::ConstantVelocity {
                    start: [pos[0] - vel[0] * t, pos[1] - vel[1] * t],
                    velocity: vel,
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

    const B: Bounds = [0.0, 0.0, 10.0, 10.0];

    #[test]
    fn constant_velocity_stops_at_the_edge() {
        let m = MoverSpec {
            id: 1,
            radius: 0.5,
            motion: MotionModel::ConstantVelocity {
                start: [5.0, 5.0],
                velocity: [1.0, 0.0],
            },
        };
        let s = m.state_at(2.0, B);
        assert_eq!(s.pos, [7.0, 5.0]);
        assert_eq!(s.vel, [1.0, 0.0]);
        let s = m.state_at(100.0, B);
        assert_eq!(s.pos, [9.5, 5.0]);
        assert_eq!(s.vel, [0.0, 0.0]);
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
        assert_eq!(m.state_at(1.0, B).pos, [1.0, 0.0]);
        let s = m.state_at(3.0, B);
        assert!((s.pos[0] - 1.0).abs() < 1e-12 && s.vel[0] < 0.0);
        assert!((m.state_at(4.0, B).pos[0]).abs() < 1e-12);
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
        let s = m.state_at(1.5, B);
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
        assert_eq!(m.state_at(0.0, B).pos, [0.0, 0.0]);
        assert_eq!(
            m.state_at(2.0, B),
            MoverState {
                pos: [1.0, 0.0],
                vel: [1.0, 0.0]
            }
        );
        assert_eq!(m.state_at(9.0, B).pos, [2.0, 0.0]);
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
        let big: Bounds = [-100.0, -100.0, 100.0, 100.0];
        let pos = [3.0, -2.0];
        let vel = [0.6, 0.8];
        for how in [
            Placement::ConstantVelocity,
            Placement::BackAndForth,
            Placement::WaypointLoop,
        ] {
            for t in [0.0, 0.1, 1.7, 2.5, 4.0, 13.3, 57.9] {
                let m = MoverSpec::placed(4, 0.3, how, pos, vel, 2.0, t).unwrap();
                let s = m.state_at(t, big);
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
                let later = m.state_at(t + 0.01, big);
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
        let s = m.state_at(7.0 + 2.0 / 1.0 + 0.5, big);
        assert!(s.vel[0] < 0.0 && s.vel[1] < 0.0, "{s:?}");
        let m = MoverSpec::placed(1, 0.3, Placement::WaypointLoop, pos, vel, 2.0, 7.0).unwrap();
        let s = m.state_at(7.0 + 8.0, big);
        assert!((s.pos[0] - pos[0]).abs() < 1e-9 && (s.pos[1] - pos[1]).abs() < 1e-9);
        // Standing still, and bad numbers.
        let m =
            MoverSpec::placed(2, 0.3, Placement::WaypointLoop, pos, [0.0, 0.0], 2.0, 5.0).unwrap();
        assert_eq!(m.state_at(9.0, big).pos, pos);
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
