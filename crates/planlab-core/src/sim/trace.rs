//! The per-step record of an episode, its CSV form and its hash.

use std::fmt::Write as _;

use serde::{Deserialize, Serialize};

use crate::local::{GoalKind, ObstacleClass};
use crate::world::Command;

/// One row of a trace: the state after a step and what led to it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
pub struct TraceStep {
    /// Time, s.
    pub t: f64,
    /// Position x, m.
    pub x: f64,
    /// Position y, m.
    pub y: f64,
    /// Heading, rad.
    pub theta: f64,
    /// Forward speed, m/s.
    pub v: f64,
    /// Sideways speed, m/s.
    pub vy: f64,
    /// Turn rate, rad/s.
    pub w: f64,
    /// The command sent to the motors this step (after the feasibility
    /// clamp); zero in the start row.
    pub cmd: Command,
    /// Exact distance from the footprint to the nearest wall, map edge or
    /// mover, m, capped at [`super::CLEARANCE_CAP`].
    pub clearance: f64,
    /// The goal the planner steered to (final, intermediate or virtual), m.
    pub goal: [f64; 2],
    /// What kind of goal that was.
    pub goal_kind: GoalKind,
    /// The planner's strategy name this step ("" in the start row).
    pub mode: String,
    /// Classes the planner gave the perceived movers: (id, class).
    pub classes: Vec<(u32, ObstacleClass)>,
    /// Vertical body acceleration during the step, m/s².
    pub accel_z: f64,
    /// Wheel loads (FL, FR, RL, RR), N, when a vehicle model is set.
    pub wheel_loads: Option<[f64; 4]>,
    /// Mover centres at this time: (id, [x, y]).
    pub movers: Vec<(u32, [f64; 2])>,
}

/// The trace of an episode: row 0 is the start (t = 0), then one row per
/// step.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
pub struct Trace {
    /// The rows, in time order.
    pub steps: Vec<TraceStep>,
}

/// The CSV header, in column order.
pub const CSV_HEADER: &str = "t,x,y,theta,v,vy,w,cmd_v,cmd_vy,cmd_w,clearance,goal_x,goal_y,goal_kind,mode,accel_z,load_fl,load_fr,load_rl,load_rr,classes,movers";

fn goal_kind_str(k: GoalKind) -> &'static str {
    match k {
        GoalKind::Final => "final",
        GoalKind::Intermediate => "intermediate",
        GoalKind::Virtual => "virtual",
        GoalKind::Temporary => "temporary",
    }
}

fn class_str(c: ObstacleClass) -> &'static str {
    match c {
        ObstacleClass::OrdinaryDynamic => "ordinary-dynamic",
        ObstacleClass::OrdinaryStatic => "ordinary-static",
        ObstacleClass::Special => "special",
    }
}

/// 64-bit FNV-1a.
struct Fnv(u64);

impl Fnv {
    fn bytes(&mut self, b: &[u8]) {
        for &x in b {
            self.0 ^= u64::from(x);
            self.0 = self.0.wrapping_mul(0x0000_0100_0000_01B3);
        }
    }
    fn f(&mut self, x: f64) {
        self.bytes(&x.to_bits().to_le_bytes());
    }
    fn u(&mut self, x: u64) {
        self.bytes(&x.to_le_bytes());
    }
}

impl Trace {
    /// The trace as CSV: [`CSV_HEADER`], then one line per row. Floats are
    /// written in Rust's shortest round-trip form (`{:?}`), so parsing them
    /// gives the same bits. `classes` is `id:class` joined by `;`, `movers`
    /// `id:x:y` joined by `;`; wheel loads are empty without a vehicle model.
    pub fn to_csv(&self) -> String {
        let mut s = String::with_capacity(64 + self.steps.len() * 200);
        s.push_str(CSV_HEADER);
        s.push('\n');
        for r in &self.steps {
            let _ = write!(
                s,
                "{:?},{:?},{:?},{:?},{:?},{:?},{:?},{:?},{:?},{:?},{:?},{:?},{:?},{},{},{:?},",
                r.t,
                r.x,
                r.y,
                r.theta,
                r.v,
                r.vy,
                r.w,
                r.cmd.v,
                r.cmd.vy,
                r.cmd.w,
                r.clearance,
                r.goal[0],
                r.goal[1],
                goal_kind_str(r.goal_kind),
                csv_field(&r.mode),
                r.accel_z,
            );
            match r.wheel_loads {
                Some(l) => {
                    let _ = write!(s, "{:?},{:?},{:?},{:?},", l[0], l[1], l[2], l[3]);
                }
                None => s.push_str(",,,,"),
            }
            let classes: Vec<String> = r
                .classes
                .iter()
                .map(|(id, c)| format!("{id}:{}", class_str(*c)))
                .collect();
            s.push_str(&classes.join(";"));
            s.push(',');
            let movers: Vec<String> = r
                .movers
                .iter()
                .map(|(id, p)| format!("{id}:{:?}:{:?}", p[0], p[1]))
                .collect();
            s.push_str(&movers.join(";"));
            s.push('\n');
        }
        s
    }

    /// FNV-1a (64 bit) over every value of every row in column order: the
    /// bit patterns of the floats (little-endian), ids, enum tags, option
    /// tags, list lengths and the mode's bytes. Equal traces hash equal on
    /// every target; one flipped bit anywhere changes it.
    pub fn hash(&self) -> u64 {
        let mut h = Fnv(0xCBF2_9CE4_8422_2325);
        h.u(self.steps.len() as u64);
        for r in &self.steps {
            for x in [
                r.t,
                r.x,
                r.y,
                r.theta,
                r.v,
                r.vy,
                r.w,
                r.cmd.v,
                r.cmd.vy,
                r.cmd.w,
                r.clearance,
                r.goal[0],
                r.goal[1],
            ] {
                h.f(x);
            }
            h.u(r.goal_kind as u64);
            h.u(r.mode.len() as u64);
            h.bytes(r.mode.as_bytes());
            h.f(r.accel_z);
            match r.wheel_loads {
                Some(l) => {
                    h.u(1);
                    for x in l {
                        h.f(x);
                    }
                }
                None => h.u(0),
            }
            h.u(r.classes.len() as u64);
            for (id, c) in &r.classes {
                h.u(u64::from(*id));
                h.u(*c as u64);
            }
            h.u(r.movers.len() as u64);
            for (id, p) in &r.movers {
                h.u(u64::from(*id));
                h.f(p[0]);
                h.f(p[1]);
            }
        }
        h.0
    }

    /// Driven positions (x, y), one per row.
    pub fn positions(&self) -> Vec<[f64; 2]> {
        self.steps.iter().map(|r| [r.x, r.y]).collect()
    }
}

/// Quotes a CSV field when it holds a comma, quote or newline.
fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(t: f64) -> TraceStep {
        TraceStep {
            t,
            x: 1.5,
            y: -0.25,
            mode: "detour".into(),
            classes: vec![(2, ObstacleClass::Special)],
            movers: vec![(2, [0.1, 0.2])],
            ..Default::default()
        }
    }

    #[test]
    fn csv_has_fixed_columns_and_round_trip_floats() {
        let tr = Trace {
            steps: vec![row(0.0), row(0.1 + 0.2)],
        };
        let csv = tr.to_csv();
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(lines[0], CSV_HEADER);
        let n = CSV_HEADER.split(',').count();
        for l in &lines[1..] {
            assert_eq!(l.split(',').count(), n, "{l}");
        }
        let t: f64 = lines[2].split(',').next().unwrap().parse().unwrap();
        assert_eq!(t.to_bits(), (0.1f64 + 0.2).to_bits());
        assert!(lines[1].contains("2:special") && lines[1].contains("2:0.1:0.2"));
    }

    #[test]
    fn hash_is_stable_and_sensitive() {
        let tr = Trace {
            steps: vec![row(0.0), row(0.1)],
        };
        // A fixed value: changing the hash layout breaks the recorded
        // native-vs-wasm goldens, so it must be deliberate.
        let h = tr.hash();
        assert_eq!(h, tr.clone().hash());
        let mut t2 = tr.clone();
        t2.steps[1].x = f64::from_bits(1.5f64.to_bits() + 1);
        assert_ne!(h, t2.hash());
        let mut t3 = tr.clone();
        t3.steps[1].mode.push('x');
        assert_ne!(h, t3.hash());
        assert_ne!(Trace::default().hash(), h);
    }
}
