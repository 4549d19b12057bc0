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

/// One value of a trace row, in the row's column order: what the CSV
/// writer, the hash and the page's row export all walk, so the columns are
/// listed once ([`TraceStep::columns`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Column<'a> {
    /// A float column: its CSV name and value.
    Num(&'static str, f64),
    /// `goal_kind`.
    GoalKind(GoalKind),
    /// `mode`, the planner's strategy name.
    Mode(&'a str),
    /// `load_fl`, `load_fr`, `load_rl`, `load_rr` (N); `None` without a
    /// vehicle model.
    WheelLoads(Option<[f64; 4]>),
    /// `classes`: (mover id, class) pairs.
    Classes(&'a [(u32, ObstacleClass)]),
    /// `movers`: (mover id, centre) pairs.
    Movers(&'a [(u32, [f64; 2])]),
}

/// CSV names of the wheel-load columns.
const LOAD_NAMES: [&str; 4] = ["load_fl", "load_fr", "load_rl", "load_rr"];

impl Column<'_> {
    /// The CSV column names this value fills (four for the wheel loads).
    pub fn csv_names(&self) -> &[&'static str] {
        match self {
            Column::Num(name, _) => std::slice::from_ref(name),
            Column::GoalKind(_) => &["goal_kind"],
            Column::Mode(_) => &["mode"],
            Column::WheelLoads(_) => &LOAD_NAMES,
            Column::Classes(_) => &["classes"],
            Column::Movers(_) => &["movers"],
        }
    }
}

impl TraceStep {
    /// The row's values in column order (the CSV's, the hash's and the
    /// page's `traceRow`).
    pub fn columns(&self) -> [Column<'_>; 19] {
        use Column::Num;
        [
            Num("t", self.t),
            Num("x", self.x),
            Num("y", self.y),
            Num("theta", self.theta),
            Num("v", self.v),
            Num("vy", self.vy),
            Num("w", self.w),
            Num("cmd_v", self.cmd.v),
            Num("cmd_vy", self.cmd.vy),
            Num("cmd_w", self.cmd.w),
            Num("clearance", self.clearance),
            Num("goal_x", self.goal[0]),
            Num("goal_y", self.goal[1]),
            Column::GoalKind(self.goal_kind),
            Column::Mode(&self.mode),
            Num("accel_z", self.accel_z),
            Column::WheelLoads(self.wheel_loads),
            Column::Classes(&self.classes),
            Column::Movers(&self.movers),
        ]
    }
}

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

    /// One column: float bits, enum tags, option tags, list lengths and
    /// the mode's bytes.
    fn column(&mut self, c: &Column<'_>) {
        match *c {
            Column::Num(_, x) => self.f(x),
            Column::GoalKind(k) => self.u(k as u64),
            Column::Mode(m) => {
                self.u(m.len() as u64);
                self.bytes(m.as_bytes());
            }
            Column::WheelLoads(Some(l)) => {
                self.u(1);
                for x in l {
                    self.f(x);
                }
            }
            Column::WheelLoads(None) => self.u(0),
            Column::Classes(cs) => {
                self.u(cs.len() as u64);
                for (id, c) in cs {
                    self.u(u64::from(*id));
                    self.u(*c as u64);
                }
            }
            Column::Movers(ms) => {
                self.u(ms.len() as u64);
                for (id, p) in ms {
                    self.u(u64::from(*id));
                    self.f(p[0]);
                    self.f(p[1]);
                }
            }
        }
    }
}

/// Writes one column's CSV cells (without the separator after them).
fn write_csv(s: &mut String, c: &Column<'_>) {
    match *c {
        Column::Num(_, x) => {
            let _ = write!(s, "{x:?}");
        }
        Column::GoalKind(k) => s.push_str(goal_kind_str(k)),
        Column::Mode(m) => s.push_str(&csv_field(m)),
        Column::WheelLoads(Some(l)) => {
            let _ = write!(s, "{:?},{:?},{:?},{:?}", l[0], l[1], l[2], l[3]);
        }
        Column::WheelLoads(None) => s.push_str(",,,"),
        Column::Classes(cs) => {
            for (i, (id, c)) in cs.iter().enumerate() {
                let sep = if i > 0 { ";" } else { "" };
                let _ = write!(s, "{sep}{id}:{}", class_str(*c));
            }
        }
        Column::Movers(ms) => {
            for (i, (id, p)) in ms.iter().enumerate() {
                let sep = if i > 0 { ";" } else { "" };
                let _ = write!(s, "{sep}{id}:{:?}:{:?}", p[0], p[1]);
            }
        }
    }
}

impl Trace {
    /// The CSV header: every column's name in order.
    pub fn csv_header() -> String {
        let row = TraceStep::default();
        let names: Vec<&str> = row
            .columns()
            .iter()
            .flat_map(|c| c.csv_names().iter().copied())
            .collect();
        names.join(",")
    }

    /// The trace as CSV: [`Trace::csv_header`], then one line per row.
    /// Floats are written in Rust's shortest round-trip form (`{:?}`), so
    /// parsing them gives the same bits. `classes` is `id:class` joined by
    /// `;`, `movers` `id:x:y` joined by `;`; wheel loads are empty without
    /// a vehicle model.
    pub fn to_csv(&self) -> String {
        let mut s = String::with_capacity(64 + self.steps.len() * 200);
        s.push_str(&Trace::csv_header());
        s.push('\n');
        for r in &self.steps {
            for (i, c) in r.columns().iter().enumerate() {
                if i > 0 {
                    s.push(',');
                }
                write_csv(&mut s, c);
            }
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
            for c in &r.columns() {
                h.column(c);
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
        assert_eq!(
            lines[0],
            "t,x,y,theta,v,vy,w,cmd_v,cmd_vy,cmd_w,clearance,goal_x,goal_y,goal_kind,mode,accel_z,load_fl,load_fr,load_rl,load_rr,classes,movers"
        );
        let n = lines[0].split(',').count();
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
