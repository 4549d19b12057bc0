//! A minimal closed loop for unit-testing local planners without `sim`:
//! observe movers (true velocities), plan, clamp to the limits, integrate,
//! check collisions exactly.

use super::{LocalPlanner, Observation, ObservedMover};
use crate::map::{OccupancyGrid, Pose2};
use crate::num::hypot;
use crate::world::robot::integrate;
use crate::world::{MoverSpec, RobotSpec, RobotState, StaticMap};

/// How a test run ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum End {
    Reached,
    Collision,
    Timeout,
}

#[derive(Debug, Clone)]
pub struct Run {
    pub end: End,
    pub time: f64,
    pub length: f64,
    pub states: Vec<RobotState>,
    pub modes: Vec<String>,
    pub min_clearance: f64,
}

pub fn map(ascii: &str, res: f64) -> StaticMap {
    let g = OccupancyGrid::from_ascii(ascii)
        .unwrap()
        .with_frame(res, Pose2::default())
        .unwrap();
    StaticMap::new(g, true).unwrap()
}

#[allow(clippy::too_many_arguments)]
pub fn run(
    planner: &mut dyn LocalPlanner,
    map: &StaticMap,
    robot: &RobotSpec,
    start: RobotState,
    goal: [f64; 2],
    movers: &[MoverSpec],
    max_time: f64,
    tol: f64,
) -> Run {
    let dt = 0.1;
    let mut s = start;
    let r = robot.footprint.circumscribed_radius();
    let mut out = Run {
        end: End::Timeout,
        time: 0.0,
        length: 0.0,
        states: vec![s],
        modes: Vec::new(),
        min_clearance: f64::INFINITY,
    };
    let steps = (max_time / dt).ceil() as usize;
    for i in 0..steps {
        let t = i as f64 * dt;
        let obs_movers: Vec<ObservedMover> = movers
            .iter()
            .map(|m| {
                let st = m.state_at(t, map);
                ObservedMover {
                    id: m.id,
                    pos: st.pos,
                    vel: st.vel,
                    radius: m.radius,
                }
            })
            .filter(|m| hypot(m.pos[0] - s.x, m.pos[1] - s.y) - m.radius < 5.0)
            .collect();
        let obs = Observation {
            time: t,
            dt,
            state: &s,
            goal,
            map,
            map_revision: 0,
            scan: None,
            movers: &obs_movers,
            odometry: None,
            accel_z: 0.0,
        };
        let cmd = planner.step(&obs);
        assert!(cmd.v.is_finite() && cmd.w.is_finite(), "{cmd:?}");
        out.modes.push(planner.debug().mode.clone());
        let cmd = robot.feasible(&s, cmd, dt);
        let next = integrate(&s, cmd, dt);
        out.length += hypot(next.x - s.x, next.y - s.y);
        s = next;
        out.states.push(s);
        out.time = t + dt;
        let mut c = map.footprint_distance(&robot.footprint, &s, 5.0);
        for m in movers {
            let st = m.state_at(t + dt, map);
            c = c.min(hypot(st.pos[0] - s.x, st.pos[1] - s.y) - r - m.radius);
        }
        out.min_clearance = out.min_clearance.min(c);
        if c <= 0.0 {
            out.end = End::Collision;
            return out;
        }
        if hypot(goal[0] - s.x, goal[1] - s.y) <= tol {
            out.end = End::Reached;
            return out;
        }
    }
    out
}

/// An observation at time 0 (dt 0.1 s) of `state` heading for `goal` on
/// `map`, with no scan, movers or odometry.
pub fn observation<'a>(
    state: &'a RobotState,
    goal: [f64; 2],
    map: &'a StaticMap,
) -> Observation<'a> {
    Observation {
        time: 0.0,
        dt: 0.1,
        state,
        goal,
        map,
        map_revision: 0,
        scan: None,
        movers: &[],
        odometry: None,
        accel_z: 0.0,
    }
}
