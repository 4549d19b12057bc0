//! Two ROS local planners as compositions of the local-planning
//! [engine](super::engine) (docs/algorithms.md §move-base-dwa, §dwb):
//!
//! - [`move_base`]: ROS 1 move_base with base_local_planner's
//!   `TrajectoryPlannerROS` and `dwa: true`;
//! - [`dwb`]: Nav2's DWB controller with its default critics.
//!
//! What both share lives here: the costmap (the static map inflated as
//! costmap_2d's inflation layer does, [`Costmap::ros`], with the perceived
//! movers marked at their current positions as an obstacle layer would),
//! a NavFn-style global path on it ([`navfn`]), the plan handed to the
//! critics each cycle (pruned behind the robot and cut ahead, [`PlanTracker`])
//! and the footprint's cost.
//!
//! **Simplifications common to both** (everything else follows the
//! sources' defaults, documented per field):
//! - the simulator is 2D with exact movers; the costmap is the whole static
//!   map (not a rolling window), its layers the static map and the movers
//!   perceived this cycle (no sensor clearing/marking, no decay);
//! - NavFn's wavefront (4-connected, quadratic interpolation, gradient
//!   descent) is replaced by an 8-connected Dijkstra over the same cell
//!   costs (COST_NEUTRAL 50 + COST_FACTOR 0.8 · cost, cells ≥ 253
//!   impassable, no corner cutting); a start or goal cell swallowed by
//!   the inflation is moved to the nearest free cell (NavFn's
//!   `default_tolerance` is 0 and it would refuse);
//! - the controller's frequency is the scenario's control rate, so
//!   `sim_period` = the observation's `dt`;
//! - recovery behaviours (costmap clearing, spin, wait) are not modelled:
//!   with no legal trajectory move_base backs up as its planner does (the
//!   robot's `v_min` may make that a stop) and DWB stops; both replan.

pub mod critics;
pub mod dwb;
pub mod generators;
pub mod move_base;
#[cfg(test)]
mod tests;

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use super::engine::{Engine, StepRequest, TrajectoryGenerator};
use super::route::snap;
use super::{GoalKind, LocalError, LocalPlanner, Observation, PlannerDebug};
use crate::global::{GridPos, PlanGrid};
use crate::map::costmap::{Costmap, INSCRIBED, LETHAL, NO_INFORMATION};
use crate::map::{Cell, OccupancyGrid};
use crate::num::{cos, hypot, sin, wrap_angle};
use crate::world::{Command, Footprint, RobotSpec, RobotState, StaticMap};

crate::params::params! {
    /// The inflation layer of the costmap both baselines read (costmap_2d /
    /// nav2_costmap_2d `inflation_layer` defaults).
    #[derive(Debug, Clone, Copy, PartialEq)]
    pub struct CostmapParams {
        pub inflation_radius: f64 = 0.55, "m" [>= 0.0, <= 100.0]
            label "inflation radius" "inflation_radius: costs decay out to this distance from an obstacle (at least the robot's inscribed radius)";
        pub cost_scaling_factor: f64 = 10.0, "1/m" [>= 0.0, <= 1000.0]
            label "cost decay rate" "cost_scaling_factor: decay rate of the inflated cost, 252·exp(−k·(d − r_inscribed))";
        pub footprint_padding: f64 = 0.01, "m" [>= 0.0, <= 10.0]
            label "footprint padding" "footprint_padding: the footprint is grown by this much (a disc becomes a 16-gon of radius r + padding)";
    }
}

fn costmap_err(e: crate::map::MapError) -> LocalError {
    LocalError::InvalidParameter(format!("costmap: {e}"))
}

/// The costmap of one cycle: the static layer and the movers, inflated.
#[derive(Debug, Clone)]
pub struct Layers {
    solid: OccupancyGrid,
    stat: Costmap,
    cur: Costmap,
    inscribed: f64,
    inflation: f64,
    scaling: f64,
    padding: f64,
    /// Whether `cur` holds movers (else it equals `stat`).
    dirty: bool,
    /// The map revision the static layer was built from (see
    /// [`Observation::map_revision`]).
    revision: u64,
}

impl Layers {
    /// The layers of `map` for `robot` (inscribed radius = the footprint's).
    pub fn new(map: &StaticMap, robot: &RobotSpec, p: &CostmapParams) -> Result<Self, LocalError> {
        let solid = map.solid();
        let inscribed = padded(&robot.footprint, p.footprint_padding).inscribed_radius();
        let inscribed = match robot.footprint {
            // The padded disc's 16-gon.
            Footprint::Circle { .. } => inscribed * cos(std::f64::consts::PI / 16.0),
            Footprint::Rectangle { .. } => inscribed,
        };
        let inflation = p.inflation_radius.max(inscribed);
        let stat = Costmap::ros(&solid, inscribed, inflation, p.cost_scaling_factor)
            .map_err(costmap_err)?;
        Ok(Self {
            cur: stat.clone(),
            solid,
            stat,
            inscribed,
            inflation,
            scaling: p.cost_scaling_factor,
            padding: p.footprint_padding,
            dirty: false,
            revision: 0,
        })
    }

    /// Replaces the static layer by `map` (the known map changed).
    pub fn set_static(&mut self, map: &StaticMap) -> Result<(), LocalError> {
        let solid = map.solid();
        self.stat = Costmap::ros(&solid, self.inscribed, self.inflation, self.scaling)
            .map_err(costmap_err)?;
        self.solid = solid;
        self.cur.clone_from(&self.stat);
        self.dirty = false;
        Ok(())
    }

    /// Marks the movers of `obs` at their current positions (cells whose
    /// centre lies within a mover's disc, and the cell of its centre) and
    /// inflates; without movers the static costmap.
    /// A changed known map (a perceived one, [`Observation::map_revision`])
    /// replaces the static layer first.
    pub fn update(&mut self, obs: &Observation<'_>) {
        if obs.map_revision != self.revision {
            // A failed rebuild keeps the old layer (the map's frame does
            // not change, so it cannot fail in practice).
            if self.set_static(obs.map).is_ok() {
                self.revision = obs.map_revision;
            }
        }
        if obs.movers.is_empty() {
            if self.dirty {
                self.cur.costs.clone_from(&self.stat.costs);
                self.dirty = false;
            }
            return;
        }
        let mut g = self.solid.clone();
        let res = g.resolution();
        for m in obs.movers {
            if let Some((c0, r0)) = g.world_to_cell(m.pos[0], m.pos[1]) {
                let _ = g.set(c0, r0, Cell::Occupied);
            }
            let k = (m.radius / res).ceil() as i64 + 1;
            let Some((cc, rc)) = g.world_to_cell(m.pos[0], m.pos[1]) else {
                continue;
            };
            for dr in -k..=k {
                for dc in -k..=k {
                    let (c, r) = (cc as i64 + dc, rc as i64 + dr);
                    if !g.in_bounds(c, r) {
                        continue;
                    }
                    let (x, y) = g.cell_to_world(c as usize, r as usize);
                    if hypot(x - m.pos[0], y - m.pos[1]) <= m.radius {
                        let _ = g.set(c as usize, r as usize, Cell::Occupied);
                    }
                }
            }
        }
        if let Ok(cm) = Costmap::ros(&g, self.inscribed, self.inflation, self.scaling) {
            self.cur = cm;
            self.dirty = true;
        }
    }

    /// This cycle's costmap.
    pub fn costmap(&self) -> &Costmap {
        &self.cur
    }

    /// The grid whose frame the costmap has.
    pub fn frame(&self) -> &OccupancyGrid {
        &self.solid
    }

    /// The cell of `(x, y)`, `None` off the map.
    pub fn cell(&self, x: f64, y: f64) -> Option<(usize, usize)> {
        self.solid.world_to_cell(x, y)
    }

    /// The cost at `(x, y)`, `None` off the map.
    pub fn cost_at(&self, x: f64, y: f64) -> Option<u8> {
        let (c, r) = self.cell(x, y)?;
        self.cur.get(c, r)
    }

    /// The highest cost under the outline of `footprint`, padded by
    /// `footprint_padding`, at pose `(x, y, θ)` (base_local_planner's
    /// `CostmapModel::footprintCost`: a disc is its 16-gon, as ROS makes a
    /// footprint from `robot_radius`; each edge is walked every half
    /// cell); `None` when the outline leaves the map or touches a lethal or
    /// unknown cell.
    pub fn footprint_cost(&self, footprint: &Footprint, [x, y, th]: [f64; 3]) -> Option<f64> {
        let corners: Vec<[f64; 2]> = match padded(footprint, self.padding) {
            Footprint::Circle { radius } => (0..16)
                .map(|i| {
                    let a = i as f64 * std::f64::consts::PI / 8.0;
                    [x + radius * cos(a), y + radius * sin(a)]
                })
                .collect(),
            Footprint::Rectangle { length, width } => {
                let (s, c) = (sin(th), cos(th));
                [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)]
                    .iter()
                    .map(|&(a, b)| {
                        let (lx, ly) = (0.5 * length * a, 0.5 * width * b);
                        [x + c * lx - s * ly, y + s * lx + c * ly]
                    })
                    .collect()
            }
        };
        let step = 0.5 * self.solid.resolution();
        let mut worst = 0u8;
        for (i, a) in corners.iter().enumerate() {
            let b = corners[(i + 1) % corners.len()];
            let n = ((hypot(b[0] - a[0], b[1] - a[1]) / step).ceil() as usize).max(1);
            for k in 0..=n {
                let t = k as f64 / n as f64;
                let c = self.cost_at(a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t)?;
                if c == LETHAL || c == NO_INFORMATION {
                    return None;
                }
                worst = worst.max(c);
            }
        }
        Some(f64::from(worst))
    }
}

/// `footprint` grown by `padding` on every side (costmap_2d's
/// `padFootprint`).
fn padded(footprint: &Footprint, padding: f64) -> Footprint {
    match *footprint {
        Footprint::Circle { radius } => Footprint::Circle {
            radius: radius + padding,
        },
        Footprint::Rectangle { length, width } => Footprint::Rectangle {
            length: length + 2.0 * padding,
            width: width + 2.0 * padding,
        },
    }
}

/// Whether a cost is one a robot centre may stand on (below inscribed).
pub fn passable(cost: u8) -> bool {
    cost < INSCRIBED
}

/// Heap entry of [`navfn`]: lowest cost first, then lowest index.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Open(f64, usize);

impl Eq for Open {}

impl Ord for Open {
    fn cmp(&self, o: &Self) -> Ordering {
        o.0.total_cmp(&self.0).then(o.1.cmp(&self.1))
    }
}

impl PartialOrd for Open {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}

/// NavFn's cell cost of a costmap cost (`None`: impassable).
fn navfn_cost(c: u8) -> Option<f64> {
    passable(c).then(|| 50.0 + 0.8 * f64::from(c))
}

/// The global path from `start` to `goal` (world metres) on the layers'
/// costmap: Dijkstra over NavFn's cell costs (module doc), through cell
/// centres, ending on the exact goal. Errors: [`LocalError::NoGlobalPath`].
pub fn navfn(
    layers: &Layers,
    start: [f64; 2],
    goal: [f64; 2],
) -> Result<Vec<[f64; 2]>, LocalError> {
    let grid = layers.frame();
    let cm = layers.costmap();
    let (w, h) = (cm.width, cm.height);
    let no = |m: &str| LocalError::NoGlobalPath(m.to_string());
    let free = PlanGrid::from_fn(w, h, |c, r| cm.get(c, r).is_some_and(passable));
    let ring = ((2.0 * layers.inflation / grid.resolution()).ceil() as i64).max(2);
    let at = |p: [f64; 2], what: &str| {
        let (c, r) = layers
            .cell(p[0], p[1])
            .ok_or_else(|| no(&format!("the {what} is off the map")))?;
        snap(&free, GridPos::new(c as u32, r as u32), ring)
            .ok_or_else(|| no(&format!("no free costmap cell near the {what}")))
    };
    let (s, g) = (at(start, "start")?, at(goal, "goal")?);
    let idx = |p: GridPos| p.row as usize * w + p.col as usize;
    let (si, gi) = (idx(s), idx(g));
    let mut dist = vec![f64::INFINITY; w * h];
    let mut parent = vec![usize::MAX; w * h];
    let mut heap = BinaryHeap::new();
    dist[si] = 0.0;
    heap.push(Open(0.0, si));
    while let Some(Open(d, i)) = heap.pop() {
        if d > dist[i] {
            continue;
        }
        if i == gi {
            break;
        }
        let (c, r) = ((i % w) as i64, (i / w) as i64);
        for (dc, dr) in [
            (1, 0),
            (-1, 0),
            (0, 1),
            (0, -1),
            (1, 1),
            (1, -1),
            (-1, 1),
            (-1, -1),
        ] {
            let (nc, nr) = (c + dc, r + dr);
            if !free.is_free(nc, nr) {
                continue;
            }
            if dc != 0 && dr != 0 && !(free.is_free(c + dc, r) && free.is_free(c, r + dr)) {
                continue;
            }
            let j = nr as usize * w + nc as usize;
            let Some(step) = cm.costs.get(j).copied().and_then(navfn_cost) else {
                continue;
            };
            let len = if dc != 0 && dr != 0 {
                std::f64::consts::SQRT_2
            } else {
                1.0
            };
            let nd = d + step * len;
            if nd < dist[j] {
                dist[j] = nd;
                parent[j] = i;
                heap.push(Open(nd, j));
            }
        }
    }
    if !dist[gi].is_finite() {
        return Err(no("the goal is not reachable on the costmap"));
    }
    let mut cells = vec![gi];
    while let Some(&i) = cells.last() {
        if i == si {
            break;
        }
        cells.push(parent[i]);
    }
    cells.reverse();
    let mut path: Vec<[f64; 2]> = cells
        .iter()
        .map(|&i| {
            let (x, y) = grid.cell_to_world(i % w, i / w);
            [x, y]
        })
        .collect();
    path.push(goal);
    Ok(path)
}

/// The global plan and how much of it the critics see (base_local_planner's
/// `prunePlan` + `transformGlobalPlan`, DWB's pruning): from the plan
/// point nearest the robot, searched forward only so the robot's past
/// never captures it, to the last point within `reach` m of the robot.
#[derive(Debug, Clone, Default)]
pub struct PlanTracker {
    path: Vec<[f64; 2]>,
    closest: usize,
    window: Vec<[f64; 2]>,
}

impl PlanTracker {
    /// A new plan, followed from its start.
    pub fn set(&mut self, path: Vec<[f64; 2]>) {
        self.path = path;
        self.closest = 0;
    }

    /// The whole plan.
    pub fn path(&self) -> &[[f64; 2]] {
        &self.path
    }

    /// Prunes the plan at the robot `pos` and returns the part within
    /// `reach` of it.
    pub fn window(&mut self, pos: [f64; 2], reach: f64) -> &[[f64; 2]] {
        let d = |p: &[f64; 2]| hypot(p[0] - pos[0], p[1] - pos[1]);
        let mut best = (self.closest, f64::INFINITY);
        for (i, p) in self.path.iter().enumerate().skip(self.closest) {
            let di = d(p);
            if di < best.1 {
                best = (i, di);
            }
            if di > best.1 + 2.0 * reach {
                break;
            }
        }
        self.closest = best.0;
        self.window.clear();
        for p in self.path.iter().skip(self.closest) {
            if d(p) > reach && !self.window.is_empty() {
                break;
            }
            self.window.push(*p);
        }
        &self.window
    }
}

/// The cells of `plan` in order (segments walked every half cell, repeats
/// dropped), from its first point on the map to the last before it leaves
/// the map again (base_local_planner's `adjustPlanResolution` and
/// `setTargetCells`).
pub fn plan_cells(grid: &OccupancyGrid, plan: &[[f64; 2]]) -> Vec<(usize, usize)> {
    let step = 0.5 * grid.resolution();
    let mut out: Vec<(usize, usize)> = Vec::new();
    let mut started = false;
    let mut push = |p: [f64; 2], out: &mut Vec<(usize, usize)>| -> bool {
        match grid.world_to_cell(p[0], p[1]) {
            Some(c) => {
                started = true;
                if out.last() != Some(&c) {
                    out.push(c);
                }
                true
            }
            None => !started,
        }
    };
    for (i, a) in plan.iter().enumerate() {
        let b = plan.get(i + 1).copied().unwrap_or(*a);
        let n = ((hypot(b[0] - a[0], b[1] - a[1]) / step).ceil() as usize).max(1);
        for k in 0..n {
            let t = k as f64 / n as f64;
            if !push(
                [a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t],
                &mut out,
            ) {
                return out;
            }
        }
    }
    if let Some(last) = plan.last() {
        push(*last, &mut out);
    }
    out
}

/// A generator a ROS planner drives: the move_base window has an escape
/// mode, DWB's generator ignores it.
pub trait RosGenerator: TrajectoryGenerator {
    /// Escape mode on or off.
    fn set_escaping(&mut self, _on: bool) {}
}

impl RosGenerator for generators::TrajectoryPlannerWindow {
    fn set_escaping(&mut self, on: bool) {
        generators::TrajectoryPlannerWindow::set_escaping(self, on);
    }
}

impl RosGenerator for generators::StandardGenerator {}

/// base_local_planner's escape: with no legal trajectory, back up at
/// `vel` until `reset_dist` m or `reset_theta` rad from where it began,
/// sampling only in-place rotations meanwhile.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Escape {
    /// Backing-up speed (≤ 0), m/s; the robot's `v_min` bounds it.
    pub vel: f64,
    /// Distance that ends the escape, m.
    pub reset_dist: f64,
    /// Turn that ends the escape, rad.
    pub reset_theta: f64,
}

/// How a ROS planner follows its global plan and what it does without a
/// legal trajectory.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Following {
    /// The plan the critics see ends at the last point within this
    /// distance of the robot, m.
    pub reach: f64,
    /// Replan every this many seconds (0: only after a failure).
    pub replan_period: f64,
    /// move_base's escape; `None`: stop (DWB).
    pub escape: Option<Escape>,
}

/// A ROS local planner: the engine (generator, critics, weighted cost),
/// a NavFn-style global plan on the costmap, pruned as the robot goes, and
/// the fallback of [`Following`].
#[derive(Debug)]
pub struct RosPlanner<G: RosGenerator> {
    name: &'static str,
    engine: Engine<G>,
    layers: Layers,
    plan: PlanTracker,
    follow: Following,
    robot: RobotSpec,
    next_replan: f64,
    failed: bool,
    /// Where the escape began (x, y, θ), while escaping.
    escaping: Option<[f64; 3]>,
    /// The map revision the plan was last checked against.
    revision: u64,
}

impl<G: RosGenerator> RosPlanner<G> {
    /// The planner `name` around `engine`, planning from `start` to `goal`
    /// on `layers`' costmap. Errors: no global path.
    pub fn new(
        name: &'static str,
        engine: Engine<G>,
        layers: Layers,
        follow: Following,
        start: [f64; 2],
        goal: [f64; 2],
    ) -> Result<Self, LocalError> {
        super::dwa::check_goal(goal)?;
        let robot = *engine.robot();
        let mut me = Self {
            name,
            engine,
            layers,
            plan: PlanTracker::default(),
            follow,
            robot,
            next_replan: 0.0,
            failed: false,
            escaping: None,
            revision: 0,
        };
        me.replan(start, goal)?;
        Ok(me)
    }

    /// The engine.
    pub fn engine(&self) -> &Engine<G> {
        &self.engine
    }

    /// The global plan.
    pub fn plan(&self) -> &[[f64; 2]] {
        self.plan.path()
    }

    fn replan(&mut self, start: [f64; 2], goal: [f64; 2]) -> Result<(), LocalError> {
        let path = navfn(&self.layers, start, goal)?;
        self.engine.debug_mut().global_path.clone_from(&path);
        self.plan.set(path);
        Ok(())
    }
}

impl<G: RosGenerator> LocalPlanner for RosPlanner<G> {
    fn name(&self) -> &'static str {
        self.name
    }

    fn step(&mut self, obs: &Observation<'_>) -> Command {
        let s = *obs.state;
        let pos = [s.x, s.y];
        let mut due = self.follow.replan_period > 0.0 && obs.time >= self.next_replan;
        if obs.map_revision != self.revision {
            self.revision = obs.map_revision;
            // The known map changed (a perceived map): a new plan when the
            // old one now crosses an inscribed cell.
            self.layers.update(obs);
            due |= self.plan.path().iter().any(|p| {
                self.layers
                    .cost_at(p[0], p[1])
                    .map_or(true, |c| c >= INSCRIBED)
            });
        }
        if due || self.failed {
            self.layers.update(obs);
            // A failed replan keeps the old plan.
            let _ = self.replan(pos, obs.goal);
            self.next_replan = obs.time + self.follow.replan_period;
            self.failed = false;
        }
        let window = self.plan.window(pos, self.follow.reach).to_vec();
        self.engine
            .generator_mut()
            .set_escaping(self.escaping.is_some());
        let res = self.engine.plan(
            obs,
            &StepRequest {
                path: &window,
                ..StepRequest::to(obs.goal)
            },
        );
        let mut cmd = res.cmd;
        let mut mode = "normal";
        if res.admissible == 0 {
            self.failed = true;
            mode = "no-legal-trajectory";
            if let Some(e) = self.follow.escape {
                cmd = Command {
                    v: e.vel.max(self.robot.limits.v_min).min(0.0),
                    vy: 0.0,
                    w: 0.0,
                };
                mode = "escape";
                if self.escaping.is_none() {
                    self.escaping = Some([s.x, s.y, s.theta]);
                }
            }
        }
        if let (Some([x, y, th]), Some(e)) = (self.escaping, self.follow.escape) {
            if hypot(s.x - x, s.y - y) > e.reset_dist
                || wrap_angle(s.theta - th).abs() > e.reset_theta
            {
                self.escaping = None;
            }
        }
        let local = window.last().copied().unwrap_or(obs.goal);
        let d = self.engine.debug_mut();
        d.mode = mode.into();
        d.current_goal = local;
        d.goal_kind = if local == obs.goal {
            GoalKind::Final
        } else {
            GoalKind::Intermediate
        };
        cmd
    }

    fn set_goal(
        &mut self,
        _map: &StaticMap,
        state: &RobotState,
        goal: [f64; 2],
    ) -> Result<(), LocalError> {
        super::dwa::check_goal(goal)?;
        self.replan([state.x, state.y], goal)
    }

    fn debug(&self) -> &PlannerDebug {
        self.engine.debug()
    }

    fn set_record_rollouts(&mut self, on: bool) {
        self.engine.set_record(on);
    }
}
