//! The draw list of an episode: its live end ([`episode`]) or a past trace
//! row ([`trace_frame`]).

use super::{grid_frame, DrawList, Layer, Layers, Shape};
use crate::lidar::fog::SeenCells;
use crate::lidar::TargetKind;
use crate::local::{GoalKind, ObstacleClass, Rollout};
use crate::sim::{Episode, TraceStep};
use crate::world::{Footprint, MoverSpec, RobotState};

/// What to draw of an episode.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Request {
    /// The layers wanted.
    pub layers: Layers,
    /// First trace row of the [`Layer::Trail`] (a page keeps the trail and
    /// asks only for the rows since its last frame).
    pub trail_from: usize,
    /// What the `value` of each [`Layer::Fan`] item is.
    pub fan: FanColour,
}

/// What colours the fan: the number each [`Layer::Fan`] item carries as
/// its `value`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FanColour {
    /// The rollout's total score (higher is better).
    #[default]
    Total,
    /// Critic `k`'s normalised value, `k` indexing
    /// [`PlannerDebug::critics`](crate::local::PlannerDebug::critics); NaN
    /// for a rollout without one (a planner with fewer critics).
    ///
    /// Normalised rather than raw because the normalised value is what the
    /// critic's weight multiplies: the total is the weighted sum of them,
    /// so one critic's colours show its share in the choice on the same
    /// footing as the total's. Raw values are in each critic's own unit
    /// and scale (rad, m, m/s, a cost) and are not comparable across
    /// critics or with the score.
    Critic(usize),
}

impl FanColour {
    /// The number of `r` this choice colours by.
    pub fn of(self, r: &Rollout) -> f64 {
        match self {
            FanColour::Total => r.score,
            FanColour::Critic(k) => r.normalised.get(k).copied().unwrap_or(f64::NAN),
        }
    }
}

fn class_code(c: ObstacleClass) -> f64 {
    match c {
        ObstacleClass::OrdinaryDynamic => 0.0,
        ObstacleClass::OrdinaryStatic => 1.0,
        ObstacleClass::Special => 2.0,
    }
}

fn goal_kind_code(k: GoalKind) -> f64 {
    match k {
        GoalKind::Final => 0.0,
        GoalKind::Intermediate => 1.0,
        GoalKind::Virtual => 2.0,
        GoalKind::Temporary => 3.0,
    }
}

/// The class of mover `id` in `classes`, NaN when it has none.
fn class_of(classes: &[(u32, ObstacleClass)], id: u32) -> f64 {
    classes
        .iter()
        .find(|(i, _)| *i == id)
        .map_or(f64::NAN, |(_, c)| class_code(*c))
}

/// The footprint at `s` and its heading line.
fn robot(out: &mut DrawList, footprint: &Footprint, s: &RobotState) {
    let (sin, cos) = s.theta.sin_cos();
    let at = |f: f64, l: f64| [s.x + f * cos - l * sin, s.y + f * sin + l * cos];
    let nose = match *footprint {
        Footprint::Circle { radius } => {
            // The body-frame velocity turned into the world frame.
            let (vx, vy) = (s.v * cos - s.vy * sin, s.v * sin + s.vy * cos);
            let disc = [s.x, s.y, radius, vx, vy];
            out.push(Layer::Robot, Shape::Discs, disc, 0.0, 0.0);
            radius
        }
        Footprint::Rectangle { length, width } => {
            let (f, l) = (length / 2.0, width / 2.0);
            let corners = [at(-f, -l), at(f, -l), at(f, l), at(-f, l)];
            out.points(Layer::Robot, Shape::Polygon, &corners, 0.0, 0.0);
            f
        }
    };
    let tip = at(nose, 0.0);
    out.push(
        Layer::Robot,
        Shape::Segments,
        [s.x, s.y, tip[0], tip[1]],
        1.0,
        0.0,
    );
}

/// Start, final goal and the goal steered to.
fn goals(out: &mut DrawList, start: [f64; 2], goal: [f64; 2], current: ([f64; 2], GoalKind)) {
    out.points(Layer::Goals, Shape::Points, &[start], 0.0, 0.0);
    out.points(Layer::Goals, Shape::Points, &[goal], 1.0, 0.0);
    out.points(
        Layer::Goals,
        Shape::Points,
        &[current.0],
        2.0,
        goal_kind_code(current.1),
    );
}

fn start_of(ep: &Episode) -> [f64; 2] {
    ep.trace().steps.first().map_or([0.0; 2], |r| [r.x, r.y])
}

/// The live end of `ep`: the layers `req` asks for, appended to `out`.
/// `seen` is the fog of war the caller keeps (LiDAR planners).
pub fn episode(ep: &Episode, seen: Option<&SeenCells>, req: Request, out: &mut DrawList) {
    let want = |l| req.layers.has(l);
    let grid = ep.map().grid();
    let d = ep.planner_debug();
    let stepped = ep.steps() > 0;
    if want(Layer::Map) {
        let cells: Vec<u8> = grid.cells().iter().map(|&c| c as u8).collect();
        out.grid(Layer::Map, grid_frame(grid), &cells, 0.0, 0.0);
    }
    if let (true, Some(s)) = (want(Layer::Seen), seen) {
        out.grid(
            Layer::Seen,
            grid_frame(grid),
            s.cells(),
            0.0,
            s.count() as f64,
        );
    }
    if want(Layer::GlobalPath) && !d.global_path.is_empty() {
        out.points(Layer::GlobalPath, Shape::Polyline, &d.global_path, 0.0, 0.0);
    }
    if want(Layer::KeyPoints) && !d.keypoints.is_empty() {
        out.points(Layer::KeyPoints, Shape::Points, &d.keypoints, 0.0, 0.0);
    }
    if want(Layer::Fan) {
        for r in &d.rollouts {
            let tag = f64::from(u8::from(r.admissible));
            out.points(Layer::Fan, Shape::Polyline, &r.points, tag, req.fan.of(r));
        }
    }
    if want(Layer::Chosen) {
        if let Some((i, r)) = d.chosen.and_then(|i| Some((i, d.rollouts.get(i)?))) {
            out.points(Layer::Chosen, Shape::Polyline, &r.points, i as f64, 0.0);
        }
    }
    let rows = &ep.trace().steps;
    if want(Layer::Trail) {
        let trail = rows.get(req.trail_from..).unwrap_or(&[]);
        if !trail.is_empty() {
            let xy = trail.iter().flat_map(|r| [r.x, r.y]);
            out.push(Layer::Trail, Shape::Polyline, xy, 0.0, 0.0);
        }
    }
    if want(Layer::Movers) {
        let classes: &[_] = if stepped { &d.classes } else { &[] };
        for (id, r, s) in ep.movers_now() {
            out.push(
                Layer::Movers,
                Shape::Discs,
                [s.pos[0], s.pos[1], r, s.vel[0], s.vel[1]],
                f64::from(id),
                class_of(classes, id),
            );
        }
    }
    if want(Layer::Robot) {
        robot(out, &ep.robot().footprint, ep.state());
    }
    if want(Layer::Goals) {
        let current = match rows.last() {
            Some(r) if stepped => (r.goal, r.goal_kind),
            _ => (ep.goal(), GoalKind::Final),
        };
        goals(out, start_of(ep), ep.goal(), current);
    }
    if let (true, Some(l)) = (stepped, d.lidar.as_ref()) {
        lidar(out, l, ep.state(), req.layers);
    } else if let (true, Some(p)) = (want(Layer::LidarRays), ep.perception()) {
        laser(out, p.scan());
    }
    if let (true, Some(p)) = (want(Layer::Costmap), ep.perception()) {
        let inscribed = ep.robot().footprint.inscribed_radius();
        if let Ok(cm) = p.costmap(inscribed) {
            let frame = grid_frame(p.frame());
            out.grid(Layer::Costmap, frame, &cm.costs, 0.0, p.revision() as f64);
        }
    }
}

/// The episode's simulated laser scan as [`Layer::LidarRays`] (a robot
/// whose planner keeps no LiDAR debug of its own).
fn laser(out: &mut DrawList, scan: &crate::world::LaserScan) {
    let [sx, sy, yaw] = scan.pose;
    if !(sx.is_finite() && sy.is_finite() && yaw.is_finite()) {
        return;
    }
    for hit in [false, true] {
        let rays: Vec<f64> = scan
            .ranges
            .iter()
            .enumerate()
            .filter(|&(_, r)| r.is_finite() == hit)
            .flat_map(|(i, &r)| {
                let a = yaw + scan.angle(i);
                let r = if hit { r } else { scan.max_range };
                [sx, sy, sx + r * a.cos(), sy + r * a.sin()]
            })
            .collect();
        if !rays.is_empty() {
            out.push(
                Layer::LidarRays,
                Shape::Segments,
                rays,
                f64::from(u8::from(hit)),
                0.0,
            );
        }
    }
}

/// The LiDAR layers of the last step.
fn lidar(out: &mut DrawList, l: &crate::lidar::LidarDebug, robot: &RobotState, want: Layers) {
    if want.has(Layer::LidarRays) {
        let n = l.ranges.len();
        let [sx, sy, yaw] = l.pose;
        for hit in [false, true] {
            let rays: Vec<f64> = l
                .ranges
                .iter()
                .enumerate()
                .filter(|&(i, _)| l.returns.get(i).copied().unwrap_or(false) == hit)
                .flat_map(|(i, &r)| {
                    let a = yaw + std::f64::consts::TAU * i as f64 / n as f64;
                    [sx, sy, sx + r * a.cos(), sy + r * a.sin()]
                })
                .collect();
            if !rays.is_empty() {
                let tag = f64::from(u8::from(hit));
                out.push(Layer::LidarRays, Shape::Segments, rays, tag, 0.0);
            }
        }
    }
    if want.has(Layer::LidarEdges) {
        for e in &l.edges {
            let tag = f64::from(e.kind.code());
            out.points(Layer::LidarEdges, Shape::Points, &[e.point], tag, 0.0);
        }
    }
    if want.has(Layer::LidarOpsRaw) {
        for (k, op) in l.ops_raw.iter().enumerate() {
            out.points(Layer::LidarOpsRaw, Shape::Polyline, op, k as f64, 0.0);
        }
    }
    if want.has(Layer::LidarOps) {
        for (k, op) in l.ops.iter().enumerate() {
            let blocking = f64::from(u8::from(l.blocking == Some(k)));
            out.points(Layer::LidarOps, Shape::Polyline, op, k as f64, blocking);
        }
    }
    if want.has(Layer::LidarCandidates) {
        for c in &l.candidates {
            let tag = f64::from(c.iteration);
            out.points(
                Layer::LidarCandidates,
                Shape::Points,
                &[c.point],
                tag,
                c.cost,
            );
        }
    }
    if want.has(Layer::LidarTarget) {
        let kind = match l.kind {
            TargetKind::Global => 0.0,
            TargetKind::Temporary => 1.0,
            TargetKind::Held => 2.0,
        };
        out.points(Layer::LidarTarget, Shape::Points, &[l.target], kind, 0.0);
        if l.hold_remaining > 0.0 {
            let timer = [robot.x, robot.y, l.hold_remaining, l.hold_period];
            out.push(Layer::LidarTarget, Shape::Timer, timer, kind, 0.0);
        }
    }
}

/// Trace row `k` of `ep` (nothing past the end): the robot at that row's
/// pose ([`Layer::Robot`]), the movers where they were with their classes
/// and their velocities from the neighbouring row ([`Layer::Movers`]), and
/// the start, final goal and the goal steered to then ([`Layer::Goals`]).
/// A mover's radius is that of the first spec in `specs` with its id (0.2 m
/// when none has it): give the specs in force and those the run had before.
pub fn trace_frame(
    ep: &Episode,
    k: usize,
    specs: &[MoverSpec],
    layers: Layers,
    out: &mut DrawList,
) {
    let rows = &ep.trace().steps;
    let Some(r) = rows.get(k) else {
        return;
    };
    if layers.has(Layer::Movers) {
        trace_movers(out, rows, k, specs, ep.config().dt);
    }
    if layers.has(Layer::Robot) {
        let s = RobotState {
            x: r.x,
            y: r.y,
            theta: r.theta,
            v: r.v,
            vy: r.vy,
            w: r.w,
        };
        robot(out, &ep.robot().footprint, &s);
    }
    if layers.has(Layer::Goals) {
        goals(out, start_of(ep), ep.goal(), (r.goal, r.goal_kind));
    }
}

/// Movers of row `k`, velocities by difference with the next row (the
/// previous one at the end).
fn trace_movers(out: &mut DrawList, rows: &[TraceStep], k: usize, specs: &[MoverSpec], dt: f64) {
    let r = &rows[k];
    let ahead = k + 1 < rows.len();
    let nb = &rows[if ahead { k + 1 } else { k.saturating_sub(1) }];
    let sign = if ahead { 1.0 } else { -1.0 };
    for &(id, p) in &r.movers {
        let vel = nb
            .movers
            .iter()
            .find(|(i, _)| *i == id)
            .map_or([0.0; 2], |(_, q)| {
                [sign * (q[0] - p[0]) / dt, sign * (q[1] - p[1]) / dt]
            });
        let radius = specs.iter().find(|m| m.id == id).map_or(0.2, |m| m.radius);
        out.push(
            Layer::Movers,
            Shape::Discs,
            [p[0], p[1], radius, vel[0], vel[1]],
            f64::from(id),
            class_of(&r.classes, id),
        );
    }
}
