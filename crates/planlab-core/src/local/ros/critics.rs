//! The ROS critics: Nav2 DWB's default list (`dwb_critics`) and
//! base_local_planner's trajectory costs (move_base). Costs: lower is
//! better, `None` is the sources' `IllegalTrajectoryException` / negative
//! cost. Distances on the grid are in cells, as in the sources.
//!
//! Where the source multiplies a critic's *scale* by something per cycle
//! (PathAlign: resolution/2, and 0 near the goal), the factor is applied to
//! the raw value here, so the product the choice uses is the source's.

use super::{plan_cells, Layers};
use crate::local::engine::critic::{Critic, CriticContext};
use crate::local::engine::generator::Trajectory;
use crate::map::costmap::INSCRIBED;
use crate::map::OccupancyGrid;
use crate::num::{atan2, cos, hypot, sin, wrap_angle};
use crate::world::{Command, Footprint};

/// The pose `d` m ahead of `(x, y, θ)` (`getForwardPose`).
fn forward([x, y, th]: [f64; 3], d: f64) -> [f64; 2] {
    [x + d * cos(th), y + d * sin(th)]
}

/// The rollout's last pose.
fn last_pose(traj: &Trajectory) -> Option<[f64; 3]> {
    let p = traj.points.last()?;
    let [sn, cs] = *traj.dirs.last()?;
    Some([p[0], p[1], atan2(sn, cs)])
}

/// DWB's BaseObstacleCritic: the costmap cost of the last pose (or the sum
/// over the poses with `sum_scores`); a pose off the map or on a lethal,
/// inscribed or unknown cell makes the rollout illegal.
#[derive(Debug, Clone)]
pub struct BaseObstacle {
    layers: Layers,
    sum_scores: bool,
}

impl BaseObstacle {
    /// The critic on `layers`.
    pub fn new(layers: Layers, sum_scores: bool) -> Self {
        Self { layers, sum_scores }
    }
}

impl Critic for BaseObstacle {
    fn name(&self) -> &str {
        "BaseObstacle"
    }
    fn prepare(&mut self, ctx: &CriticContext<'_>) {
        self.layers.update(ctx.obs);
    }
    fn score(&self, _ctx: &CriticContext<'_>, traj: &Trajectory) -> Option<f64> {
        let mut score = 0.0;
        for p in &traj.points {
            let c = self.layers.cost_at(p[0], p[1])?;
            if c >= INSCRIBED {
                return None;
            }
            let before = if self.sum_scores { score } else { 0.0 };
            score = before + f64::from(c);
        }
        Some(score)
    }
}

/// The targets of a DWB map-grid critic: a cell's value is the Manhattan
/// distance (cells) to the target nearest it (DWB's `MapGridQueue` lets
/// every cell through, obstacles included, so no search is needed);
/// `None` without a target (the source's "unreachable": illegal).
#[derive(Debug, Clone, Default)]
struct Targets {
    /// (column, row, order in the plan) — with column and row swapped when
    /// the targets spread more along rows — sorted: a query scans outwards
    /// from its own position on that axis and stops once the gap along it
    /// alone exceeds the best distance (the plain scan of every target per
    /// pose was a third of DWB's time).
    by_col: Vec<(i64, i64, u32)>,
    /// Whether `by_col` holds (row, column, order).
    swapped: bool,
}

impl Targets {
    fn new(cells: impl IntoIterator<Item = (i64, i64)>) -> Self {
        let mut by_col: Vec<(i64, i64, u32)> = cells
            .into_iter()
            .enumerate()
            .map(|(i, (c, r))| (c, r, i as u32))
            .collect();
        let spread = |key: fn(&(i64, i64, u32)) -> i64| {
            let lo = by_col.iter().map(key).min().unwrap_or(0);
            by_col.iter().map(key).max().unwrap_or(0) - lo
        };
        let swapped = spread(|t| t.1) > spread(|t| t.0);
        if swapped {
            for t in &mut by_col {
                *t = (t.1, t.0, t.2);
            }
        }
        by_col.sort_unstable();
        Self { by_col, swapped }
    }

    /// The Manhattan distance to the target nearest (c, r) by Euclidean
    /// distance, the earliest in the plan among equals.
    fn value(&self, c: i64, r: i64) -> Option<f64> {
        let (c, r) = if self.swapped { (r, c) } else { (c, r) };
        // (d², order, Manhattan) of the best target so far.
        let mut best: Option<(i64, u32, i64)> = None;
        let split = self.by_col.partition_point(|t| t.0 < c);
        Self::scan(self.by_col[split..].iter(), c, r, &mut best);
        Self::scan(self.by_col[..split].iter().rev(), c, r, &mut best);
        best.map(|(_, _, m)| m as f64)
    }

    /// Offers the targets of `side` (moving away from column `c`) until
    /// the column gap alone is worse than `best`.
    fn scan<'a>(
        side: impl Iterator<Item = &'a (i64, i64, u32)>,
        c: i64,
        r: i64,
        best: &mut Option<(i64, u32, i64)>,
    ) {
        for &(tc, tr, i) in side {
            if best.is_some_and(|(b, _, _)| (tc - c).pow(2) > b) {
                break;
            }
            let d2 = (tc - c).pow(2) + (tr - r).pow(2);
            if best.map_or(true, |(b, bi, _)| d2 < b || (d2 == b && i < bi)) {
                *best = Some((d2, i, (tc - c).abs() + (tr - r).abs()));
            }
        }
    }

    /// The value at world point `p`; `None` off the map or without target.
    fn at(&self, grid: &OccupancyGrid, p: [f64; 2]) -> Option<f64> {
        let (c, r) = grid.world_to_cell(p[0], p[1])?;
        self.value(c as i64, r as i64)
    }
}

/// The plan's cells as targets (PathDist).
fn path_targets(grid: &OccupancyGrid, plan: &[[f64; 2]]) -> Targets {
    Targets::new(
        plan_cells(grid, plan)
            .into_iter()
            .map(|(c, r)| (c as i64, r as i64)),
    )
}

/// The last plan cell on the map as the target (GoalDist).
fn goal_targets(grid: &OccupancyGrid, plan: &[[f64; 2]]) -> Targets {
    Targets::new(
        plan_cells(grid, plan)
            .last()
            .map(|&(c, r)| (c as i64, r as i64)),
    )
}

/// Scores every pose for legality (off the map or no target: illegal),
/// the last pose's `at` as the value (aggregation `last`). Positions only:
/// the map-grid critics never read a pose's heading (an atan2 a pose was
/// a quarter of DWB's time).
fn last_of(traj: &Trajectory, mut at: impl FnMut([f64; 2]) -> Option<f64>) -> Option<f64> {
    let mut v = None;
    for p in &traj.points {
        v = Some(at([p[0], p[1]])?);
    }
    v
}

/// DWB's PathDistCritic: Manhattan cells from the rollout's last pose to
/// the nearest cell of the pruned plan.
#[derive(Debug, Clone, Default)]
pub struct PathDist {
    targets: Targets,
}

impl Critic for PathDist {
    fn name(&self) -> &str {
        "PathDist"
    }
    fn prepare(&mut self, ctx: &CriticContext<'_>) {
        self.targets = path_targets(ctx.obs.map.grid(), ctx.path);
    }
    fn score(&self, ctx: &CriticContext<'_>, traj: &Trajectory) -> Option<f64> {
        let g = ctx.obs.map.grid();
        last_of(traj, |p| self.targets.at(g, p))
    }
}

/// DWB's GoalDistCritic: Manhattan cells from the rollout's last pose to
/// the last cell of the pruned plan (the local goal).
#[derive(Debug, Clone, Default)]
pub struct GoalDist {
    targets: Targets,
}

impl Critic for GoalDist {
    fn name(&self) -> &str {
        "GoalDist"
    }
    fn prepare(&mut self, ctx: &CriticContext<'_>) {
        self.targets = goal_targets(ctx.obs.map.grid(), ctx.path);
    }
    fn score(&self, ctx: &CriticContext<'_>, traj: &Trajectory) -> Option<f64> {
        let g = ctx.obs.map.grid();
        last_of(traj, |p| self.targets.at(g, p))
    }
}

/// DWB's PathAlignCritic: PathDist of the point `forward_point_distance`
/// ahead of the last pose, times resolution/2 (the source's scale factor),
/// 0 within `forward_point_distance` of the goal. Not a stop-on-failure
/// critic: only the last pose is scored.
#[derive(Debug, Clone)]
pub struct PathAlign {
    targets: Targets,
    forward_point_distance: f64,
    zero: bool,
}

impl PathAlign {
    /// The critic looking `forward_point_distance` m ahead.
    pub fn new(forward_point_distance: f64) -> Self {
        Self {
            targets: Targets::default(),
            forward_point_distance,
            zero: false,
        }
    }
}

impl Critic for PathAlign {
    fn name(&self) -> &str {
        "PathAlign"
    }
    fn prepare(&mut self, ctx: &CriticContext<'_>) {
        let s = ctx.obs.state;
        self.zero =
            hypot(s.x - ctx.obs.goal[0], s.y - ctx.obs.goal[1]) <= self.forward_point_distance;
        if !self.zero {
            self.targets = path_targets(ctx.obs.map.grid(), ctx.path);
        }
    }
    fn score(&self, ctx: &CriticContext<'_>, traj: &Trajectory) -> Option<f64> {
        let g = ctx.obs.map.grid();
        let end = last_pose(traj)?;
        g.world_to_cell(end[0], end[1])?;
        if self.zero {
            return Some(0.0);
        }
        let v = self
            .targets
            .at(g, forward(end, self.forward_point_distance))?;
        Some(v * 0.5 * g.resolution())
    }
}

/// DWB's GoalAlignCritic: GoalDist of the point `forward_point_distance`
/// ahead of the last pose, the local goal itself moved that far along the
/// bearing from the robot to the final goal.
#[derive(Debug, Clone)]
pub struct GoalAlign {
    targets: Targets,
    forward_point_distance: f64,
}

impl GoalAlign {
    /// The critic looking `forward_point_distance` m ahead.
    pub fn new(forward_point_distance: f64) -> Self {
        Self {
            targets: Targets::default(),
            forward_point_distance,
        }
    }
}

impl Critic for GoalAlign {
    fn name(&self) -> &str {
        "GoalAlign"
    }
    fn prepare(&mut self, ctx: &CriticContext<'_>) {
        let s = ctx.obs.state;
        let a = atan2(ctx.obs.goal[1] - s.y, ctx.obs.goal[0] - s.x);
        let mut plan = ctx.path.to_vec();
        if let Some(last) = plan.last_mut() {
            *last = forward([last[0], last[1], a], self.forward_point_distance);
        }
        self.targets = goal_targets(ctx.obs.map.grid(), &plan);
    }
    fn score(&self, ctx: &CriticContext<'_>, traj: &Trajectory) -> Option<f64> {
        let g = ctx.obs.map.grid();
        let end = last_pose(traj)?;
        g.world_to_cell(end[0], end[1])?;
        self.targets
            .at(g, forward(end, self.forward_point_distance))
    }
}

/// Settings of [`RotateToGoal`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RotateToGoalSettings {
    /// Within this distance of the goal the critic acts, m.
    pub xy_goal_tolerance: f64,
    /// Below this speed the robot counts as stopped, m/s.
    pub trans_stopped_velocity: f64,
    /// Weight of the squared speed while slowing down.
    pub slowing_factor: f64,
    /// Time at which the heading is read (< 0: the last pose), s.
    pub lookahead_time: f64,
    /// The remaining plan must be at most this long, m.
    pub path_length_tolerance: f64,
}

/// DWB's RotateToGoalCritic. Our goals have no orientation: the goal yaw is
/// the direction of the plan's last segment (the heading the robot
/// arrives with). The source's window test compares the squared distance
/// with a boolean (a bug); here it is the intended
/// `d ≤ xy_goal_tolerance && plan length ≤ path_length_tolerance`.
#[derive(Debug, Clone)]
pub struct RotateToGoal {
    set: RotateToGoalSettings,
    in_window: bool,
    rotating: bool,
    speed_sq: f64,
    goal_yaw: f64,
}

impl RotateToGoal {
    /// The critic with `set`.
    pub fn new(set: RotateToGoalSettings) -> Self {
        Self {
            set,
            in_window: false,
            rotating: false,
            speed_sq: 0.0,
            goal_yaw: 0.0,
        }
    }

    fn rotation(&self, traj: &Trajectory) -> Option<f64> {
        let yaw = if self.set.lookahead_time >= 0.0 && traj.dt > 0.0 {
            let i = ((self.set.lookahead_time / traj.dt).round() as usize)
                .min(traj.dirs.len().checked_sub(1)?);
            let [sn, cs] = traj.dirs[i];
            atan2(sn, cs)
        } else {
            last_pose(traj)?[2]
        };
        Some(wrap_angle(self.goal_yaw - yaw).abs())
    }
}

impl Critic for RotateToGoal {
    fn name(&self) -> &str {
        "RotateToGoal"
    }
    fn prepare(&mut self, ctx: &CriticContext<'_>) {
        let s = ctx.obs.state;
        let goal = ctx.obs.goal;
        let len: f64 = ctx
            .path
            .windows(2)
            .map(|w| hypot(w[1][0] - w[0][0], w[1][1] - w[0][1]))
            .sum();
        let d = hypot(s.x - goal[0], s.y - goal[1]);
        self.in_window |= d <= self.set.xy_goal_tolerance && len <= self.set.path_length_tolerance;
        self.speed_sq = s.v * s.v + s.vy * s.vy;
        let stopped = self.set.trans_stopped_velocity * self.set.trans_stopped_velocity;
        self.rotating |= self.in_window && self.speed_sq <= stopped;
        let n = ctx.path.len();
        self.goal_yaw = if n >= 2 {
            let (a, b) = (ctx.path[n - 2], ctx.path[n - 1]);
            atan2(b[1] - a[1], b[0] - a[0])
        } else {
            atan2(goal[1] - s.y, goal[0] - s.x)
        };
    }
    fn score(&self, _ctx: &CriticContext<'_>, traj: &Trajectory) -> Option<f64> {
        if !self.in_window {
            return Some(0.0);
        }
        let c = traj.sample.cmd;
        if !self.rotating {
            let sq = c.v * c.v + c.vy * c.vy;
            if sq >= self.speed_sq {
                return None;
            }
            return Some(sq * self.set.slowing_factor + self.rotation(traj)?);
        }
        if c.v != 0.0 || c.vy != 0.0 {
            return None;
        }
        self.rotation(traj)
    }
}

/// Settings of [`Oscillation`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OscillationSettings {
    /// Moving this far from where a flag was set clears the flags, m (< 0: off).
    pub oscillation_reset_dist: f64,
    /// Turning this far clears them, rad (< 0: off).
    pub oscillation_reset_angle: f64,
    /// Turn-rate flags only while |v| is at most this, m/s (< 0: always).
    pub x_only_threshold: f64,
}

/// Sign memory of one velocity component (`CommandTrend`).
#[derive(Debug, Clone, Copy, Default)]
struct Trend {
    sign: i8,
    positive_only: bool,
    negative_only: bool,
}

impl Trend {
    fn update(&mut self, v: f64) -> bool {
        let mut flag = false;
        if v < 0.0 {
            if self.sign > 0 {
                self.negative_only = true;
                flag = true;
            }
            self.sign = -1;
        } else if v > 0.0 {
            if self.sign < 0 {
                self.positive_only = true;
                flag = true;
            }
            self.sign = 1;
        }
        flag
    }
    fn oscillating(&self, v: f64) -> bool {
        (self.positive_only && v < 0.0) || (self.negative_only && v > 0.0)
    }
    fn flipped(&self) -> bool {
        self.positive_only || self.negative_only
    }
}

/// DWB's OscillationCritic: once a driven velocity component changed sign,
/// a rollout changing it back is illegal until the robot has moved
/// `oscillation_reset_dist` or turned `oscillation_reset_angle` from where
/// the flag was set (`oscillation_reset_time` is off, its default).
#[derive(Debug, Clone)]
pub struct Oscillation {
    set: OscillationSettings,
    x: Trend,
    y: Trend,
    th: Trend,
    pose: [f64; 3],
    flagged_at: [f64; 3],
}

impl Oscillation {
    /// The critic with `set`.
    pub fn new(set: OscillationSettings) -> Self {
        Self {
            set,
            x: Trend::default(),
            y: Trend::default(),
            th: Trend::default(),
            pose: [0.0; 3],
            flagged_at: [0.0; 3],
        }
    }
}

impl Critic for Oscillation {
    fn name(&self) -> &str {
        "Oscillation"
    }
    fn prepare(&mut self, ctx: &CriticContext<'_>) {
        let s = ctx.obs.state;
        self.pose = [s.x, s.y, s.theta];
    }
    fn score(&self, _ctx: &CriticContext<'_>, traj: &Trajectory) -> Option<f64> {
        let c = traj.sample.cmd;
        let bad = self.x.oscillating(c.v) || self.y.oscillating(c.vy) || self.th.oscillating(c.w);
        (!bad).then_some(0.0)
    }
    fn debrief(&mut self, chosen: Option<&Command>) {
        // DWB debriefs only a driven trajectory (none: an exception).
        let Some(c) = chosen else { return };
        let mut flag = self.x.update(c.v);
        if self.set.x_only_threshold < 0.0 || c.v.abs() <= self.set.x_only_threshold {
            flag |= self.y.update(c.vy);
            flag |= self.th.update(c.w);
        }
        if flag {
            self.flagged_at = self.pose;
        }
        if self.x.flipped() || self.y.flipped() || self.th.flipped() {
            let [x, y, th] = self.pose;
            let [fx, fy, fth] = self.flagged_at;
            let moved = self.set.oscillation_reset_dist >= 0.0
                && hypot(x - fx, y - fy) > self.set.oscillation_reset_dist;
            let turned = self.set.oscillation_reset_angle >= 0.0
                && (th - fth).abs() > self.set.oscillation_reset_angle;
            if moved || turned {
                self.x = Trend::default();
                self.y = Trend::default();
                self.th = Trend::default();
            }
        }
    }
}

/// base_local_planner's `MapGrid`: 4-connected breadth-first distances
/// (cells) from target cells, not through cells of cost ≥ inscribed (or
/// unknown), which get `obstacle` = width·height, except the cells under
/// the robot's footprint now; cells never reached keep `obstacle + 1`.
#[derive(Debug, Clone, Default)]
pub struct MapGrid {
    values: Vec<f64>,
    width: usize,
    obstacle: f64,
}

impl MapGrid {
    /// Distances from `targets` on `layers`' costmap, the robot at `pos`
    /// with circumscribed radius `radius`.
    pub fn compute(
        &mut self,
        layers: &Layers,
        targets: &[(usize, usize)],
        pos: [f64; 2],
        radius: f64,
    ) {
        let cm = layers.costmap();
        let (w, h) = (cm.width, cm.height);
        let grid = layers.frame();
        self.width = w;
        self.obstacle = (w * h) as f64;
        self.values.clear();
        self.values.resize(w * h, self.obstacle + 1.0);
        let mut visited = vec![false; w * h];
        let mut queue = std::collections::VecDeque::new();
        for &(c, r) in targets {
            let i = r * w + c;
            if !visited[i] {
                visited[i] = true;
                self.values[i] = 0.0;
                queue.push_back(i);
            }
        }
        let under_robot = |c: usize, r: usize| {
            let (x, y) = grid.cell_to_world(c, r);
            hypot(x - pos[0], y - pos[1]) <= radius
        };
        while let Some(i) = queue.pop_front() {
            let (c, r) = (i % w, i / w);
            let d = self.values[i] + 1.0;
            let near = [
                (c.wrapping_sub(1), r),
                (c + 1, r),
                (c, r.wrapping_sub(1)),
                (c, r + 1),
            ];
            for (nc, nr) in near {
                if nc >= w || nr >= h {
                    continue;
                }
                let j = nr * w + nc;
                if visited[j] {
                    continue;
                }
                visited[j] = true;
                let blocked = cm.costs[j] >= INSCRIBED && !under_robot(nc, nr);
                if blocked {
                    self.values[j] = self.obstacle;
                    continue;
                }
                self.values[j] = d;
                queue.push_back(j);
            }
        }
    }

    /// The value at world point `p`; `None` off the map.
    pub fn at(&self, grid: &OccupancyGrid, p: [f64; 2]) -> Option<f64> {
        let (c, r) = grid.world_to_cell(p[0], p[1])?;
        self.values.get(r * self.width + c).copied()
    }

    /// Whether `v` is the obstacle or unreachable value.
    pub fn impossible(&self, v: f64) -> bool {
        v >= self.obstacle
    }
}

/// Which target a move_base distance critic measures to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Target {
    /// Every cell of the pruned plan (`path_map_`).
    Path,
    /// The last plan cell on the map, the local goal (`goal_map_`).
    Goal,
}

/// base_local_planner's path or goal distance: the [`MapGrid`] value of
/// the rollout's last point (cells); a point whose value is the obstacle or
/// unreachable value, or off the map, makes the rollout illegal (`cost −2`).
#[derive(Debug, Clone)]
pub struct GridDistance {
    layers: Layers,
    grid: MapGrid,
    target: Target,
    radius: f64,
}

impl GridDistance {
    /// The critic measuring to `target` on `layers`, for a robot of
    /// circumscribed radius `radius`.
    pub fn new(layers: Layers, target: Target, radius: f64) -> Self {
        Self {
            layers,
            grid: MapGrid::default(),
            target,
            radius,
        }
    }
}

impl Critic for GridDistance {
    fn name(&self) -> &str {
        match self.target {
            Target::Path => "path_dist",
            Target::Goal => "goal_dist",
        }
    }
    fn prepare(&mut self, ctx: &CriticContext<'_>) {
        self.layers.update(ctx.obs);
        let mut cells = plan_cells(self.layers.frame(), ctx.path);
        if self.target == Target::Goal {
            cells = cells.last().map(|&c| vec![c]).unwrap_or_default();
        }
        let s = ctx.obs.state;
        self.grid
            .compute(&self.layers, &cells, [s.x, s.y], self.radius);
    }
    fn score(&self, _ctx: &CriticContext<'_>, traj: &Trajectory) -> Option<f64> {
        let mut v = None;
        for p in &traj.points {
            let d = self.grid.at(self.layers.frame(), *p)?;
            if self.grid.impossible(d) {
                return None;
            }
            v = Some(d);
        }
        v
    }
}

/// base_local_planner's occupancy cost: the highest cost met along the
/// rollout, under the footprint's outline and at its centre; illegal when
/// the outline touches a lethal or unknown cell or leaves the map.
#[derive(Debug, Clone)]
pub struct Occupancy {
    layers: Layers,
    footprint: Footprint,
}

impl Occupancy {
    /// The critic on `layers` for `footprint`.
    pub fn new(layers: Layers, footprint: Footprint) -> Self {
        Self { layers, footprint }
    }
}

impl Critic for Occupancy {
    fn name(&self) -> &str {
        "occ_cost"
    }
    fn prepare(&mut self, ctx: &CriticContext<'_>) {
        self.layers.update(ctx.obs);
    }
    fn score(&self, _ctx: &CriticContext<'_>, traj: &Trajectory) -> Option<f64> {
        let mut worst = 0.0f64;
        for (p, &[sn, cs]) in traj.points.iter().zip(&traj.dirs) {
            let f = self
                .layers
                .footprint_cost(&self.footprint, [p[0], p[1], atan2(sn, cs)])?;
            let c = f64::from(self.layers.cost_at(p[0], p[1])?);
            worst = worst.max(f).max(c);
        }
        Some(worst)
    }
}

/// base_local_planner's choice among in-place rotations: the goal
/// distance ([`MapGrid`]) `heading_lookahead` m ahead of the rotation's
/// end pose, lowest first; 0 for every other sample. Weighted by a tiny
/// scale it only orders rotations of equal cost, as the source's separate
/// loop does; a rotation whose lookahead point is off the map is not
/// taken (illegal).
#[derive(Debug, Clone)]
pub struct HeadingLookahead {
    layers: Layers,
    grid: MapGrid,
    lookahead: f64,
    radius: f64,
}

impl HeadingLookahead {
    /// The critic looking `lookahead` m ahead.
    pub fn new(layers: Layers, lookahead: f64, radius: f64) -> Self {
        Self {
            layers,
            grid: MapGrid::default(),
            lookahead,
            radius,
        }
    }
}

impl Critic for HeadingLookahead {
    fn name(&self) -> &str {
        "heading_lookahead"
    }
    fn prepare(&mut self, ctx: &CriticContext<'_>) {
        self.layers.update(ctx.obs);
        let cells = plan_cells(self.layers.frame(), ctx.path);
        let goal: Vec<_> = cells.last().copied().into_iter().collect();
        let s = ctx.obs.state;
        self.grid
            .compute(&self.layers, &goal, [s.x, s.y], self.radius);
    }
    fn score(&self, _ctx: &CriticContext<'_>, traj: &Trajectory) -> Option<f64> {
        if traj.sample.cmd.v != 0.0 {
            return Some(0.0);
        }
        let ahead = forward(last_pose(traj)?, self.lookahead);
        self.grid.at(self.layers.frame(), ahead)
    }
}

/// base_local_planner's oscillation flags for in-place rotation: after two
/// chosen in-place rotations in one direction (with no forward motion
/// between) the source stops taking rotations of the *other* sign (its
/// `stuck_left` guards negative turn rates, `stuck_right` positive ones);
/// the flags clear once the robot is `oscillation_reset_dist` m from where
/// the last in-place command was chosen.
#[derive(Debug, Clone)]
pub struct InPlaceOscillation {
    reset_dist: f64,
    rotating_left: bool,
    rotating_right: bool,
    stuck_left: bool,
    stuck_right: bool,
    pos: [f64; 2],
    prev: [f64; 2],
}

impl InPlaceOscillation {
    /// The flags, cleared after `reset_dist` m.
    pub fn new(reset_dist: f64) -> Self {
        Self {
            reset_dist,
            rotating_left: false,
            rotating_right: false,
            stuck_left: false,
            stuck_right: false,
            pos: [0.0; 2],
            prev: [0.0; 2],
        }
    }
}

impl Critic for InPlaceOscillation {
    fn name(&self) -> &str {
        "oscillation"
    }
    fn prepare(&mut self, ctx: &CriticContext<'_>) {
        self.pos = [ctx.obs.state.x, ctx.obs.state.y];
    }
    fn score(&self, _ctx: &CriticContext<'_>, traj: &Trajectory) -> Option<f64> {
        let c = traj.sample.cmd;
        if c.v != 0.0 {
            return Some(0.0);
        }
        let stuck = (c.w < 0.0 && self.stuck_left) || (c.w > 0.0 && self.stuck_right);
        (!stuck).then_some(0.0)
    }
    fn debrief(&mut self, chosen: Option<&Command>) {
        if let Some(c) = chosen {
            if c.v <= 0.0 {
                if c.w < 0.0 {
                    self.stuck_right |= self.rotating_right;
                    self.rotating_right = true;
                } else if c.w > 0.0 {
                    self.stuck_left |= self.rotating_left;
                    self.rotating_left = true;
                }
                self.prev = self.pos;
            }
        }
        if hypot(self.pos[0] - self.prev[0], self.pos[1] - self.prev[1]) > self.reset_dist {
            self.rotating_left = false;
            self.rotating_right = false;
            self.stuck_left = false;
            self.stuck_right = false;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn targets_by_column_give_the_plain_scans_value_ties_included() {
        // The plain scan: the first target (in plan order) at the least
        // Euclidean distance, its Manhattan distance.
        let plain = |cells: &[(i64, i64)], c: i64, r: i64| {
            let mut best: Option<(i64, i64)> = None;
            for &(tc, tr) in cells {
                let d2 = (tc - c).pow(2) + (tr - r).pow(2);
                if best.map_or(true, |(b, _)| d2 < b) {
                    best = Some((d2, (tc - c).abs() + (tr - r).abs()));
                }
            }
            best.map(|(_, m)| m as f64)
        };
        let mut rng = crate::num::Rng::new(7);
        for (n, w, h) in [
            (0usize, 30.0, 30.0),
            (1, 30.0, 30.0),
            (2, 30.0, 30.0),
            (5, 30.0, 30.0),
            (40, 30.0, 30.0),
            (200, 30.0, 30.0),
            (60, 3.0, 30.0),
            (60, 30.0, 3.0),
        ] {
            // Square clouds, and tall and wide bands (paths run both ways).
            let cells: Vec<(i64, i64)> = (0..n)
                .map(|_| ((rng.uniform() * w) as i64, (rng.uniform() * h) as i64))
                .collect();
            let t = Targets::new(cells.iter().copied());
            for c in -3..33 {
                for r in -3..33 {
                    assert_eq!(
                        t.value(c, r),
                        plain(&cells, c, r),
                        "{n} targets at ({c}, {r})"
                    );
                }
            }
        }
    }
}
