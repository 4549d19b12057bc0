//! Improved DWA + A\* fusion of \[T\] §3.2 (docs/algorithms.md §improved-dwa), and the "\[53\]"
//! baseline fusion \[T\] compares it with.
//!
//! - **Global guidance** (\[T\] §3.2.1): A\* on the static map inflated by
//!   the footprint radius + `inflate_margin`; its key points are the
//!   successive intermediate goals (the next one once the robot is within
//!   `switch_radius`).
//! - **Obstacle classification** (\[T\] Fig 3-10, Table 3-1) of the perceived
//!   movers whose surface is within `react_range` of the robot's centre
//!   (still discs are movers with zero velocity):
//!   *ordinary dynamic* (speed > `v_static`) → deceleration strategy
//!   (`decelerate` weights, large heading weight); *ordinary static* →
//!   detour strategy (`detour` weights, small heading weight); *special*:
//!   collinear with the robot and its current goal (perpendicular distance
//!   of the centre to the robot→goal segment < r_obs + r_robot, projection on
//!   the segment) → a **virtual goal** on the perpendicular through the
//!   obstacle, one robot diameter beyond its edge, on the side with more
//!   clearance, and detour weights. **Decision**: a mover faster than
//!   `v_static` is special only if it is still collinear `predict_time`
//!   later (moving along the line, e.g. head-on); one crossing the line
//!   stays ordinary dynamic, since it will have left. Any ordinary dynamic
//!   obstacle in range puts the deceleration strategy in force (\[T\]: "the
//!   deceleration strategy is the general one; if the obstacle is not
//!   ordinary dynamic, detour").
//! - **Near the goal** (\[T\] Fig 3-13 c–e): a special obstacle within
//!   `goal_region` of the current goal: if the robot is closer to the goal
//!   than to the obstacle's surface, no virtual goal (ρ lets it drive in);
//!   otherwise the virtual goal goes on the perpendicular through the goal,
//!   one robot diameter from it.
//! - **Relative distance factor** (\[T\] eq 3-7/3-8): ρ = (x_rg/x_ro)^n when
//!   x_rg ≤ x_ro else 1, with x_rg the distance to the current goal and x_ro
//!   the distance from the robot's centre to the nearest obstacle surface
//!   (map or mover); G = α·head + ρ·β·dist + γ·vel.
//! - A virtual goal stays until the robot is within `virtual_radius` of it,
//!   has passed its obstacle, or the obstacle is no longer perceived.
//!   *Passed* is measured along the robot→goal direction from which the
//!   virtual goal was placed (it lies on the perpendicular to that through
//!   the obstacle), not toward the current goal: the detour moves the robot
//!   off the line and turns that direction, so a disc already passed still
//!   counted as ahead and the robot turned back toward a virtual goal behind
//!   it, round and round the disc (T-fig3-11, `dwa_regressions`).
//!
//! \[T\] gives the two weight sets of Table 3-1 only in words ("a large
//! heading weight decelerates, a small one detours"); the defaults here are
//! the DWA sample's α 0.05 for the detour set and 1.0 (heading then
//! outweighs clearance, see the normalisation in [`super::dwa`]) for the
//! deceleration set, β and γ unchanged.
//!
//! **\[53\] baseline**: the same key points and DWA, with the deceleration
//! strategy (weights and braking rollouts) while a *moving* obstacle — one
//! observed faster than `v_static` — is in range, and the plain DWA weights
//! otherwise: no classification into static / special, no virtual goal, no
//! ρ. **Decision** (what \[T\] says of \[53\]): §3.2.3 "文献\[53\]所提算法能够
//! 较好地应对普通动静态障碍物" — it handles ordinary moving *and* still
//! obstacles well, and §3.1 (2) notes that a deceleration strategy alone
//! cannot get past still ones; what \[53\] lacks is the treatment of obstacles
//! on the robot–goal line (§3.2.2, Fig 3-12) and near the goal (§3.2.3,
//! Fig 3-14). So a still disc gets plain DWA, never a wait for it to leave:
//! \[53\] is never worse than `dwa` by construction, and whether it fails a
//! special obstacle is left to the simulation. `v_static` defaults to the
//! improved planner's (docs/algorithms.md §improved-dwa, 0.1 m/s) so the two differ only
//! in what \[T\] adds; \[53\] itself gives no threshold, and \[T\] §3.3's
//! account of it waiting at the 0.01 m/s obstacle 4 of Table 3-2 suggests a
//! lower one (a declared deviation; `fusion-53.v_static` sweeps it).

use super::dwa::{check_goal, DwaConfig, DwaPlanner, GoalProvider, Guidance, Weights};
use super::route::{dist, plan_route, Route, Waypoints};
use super::{GoalKind, LocalError, Observation, ObservedMover, ObstacleClass, PlannerDebug};
use crate::global::plan::GridPlanOptions;
use crate::num::{hypot, pow};
use crate::params::Params;
use crate::world::{RobotSpec, RobotState, StaticMap};

crate::params::params! {
    /// Settings of the improved DWA + A\* fusion (\[T\] §3.2).
    #[derive(Debug, Clone, Copy, PartialEq)]
    pub struct ImprovedConfig {
        /// Its α, β, γ are the weights with no mover in range.
        pub dwa: DwaConfig = DwaConfig::default(), "" [nested] "the DWA engine";
        pub inflate_margin: f64 = 0.1, "m" [>= 0.0] label "inflation margin" "A* inflation beyond the footprint radius";
        pub switch_radius: f64 = 1.0, "m" [> 0.0] label "key point switch radius" "advance to the next key point within this";
        pub virtual_radius: f64 = 0.3, "m" [> 0.0]
            label "virtual goal radius" "a virtual goal counts as reached within this";
        /// Measured from the robot's centre.
        pub react_range: f64 = 3.0, "m" [>= 0.0] label "reaction range" "classify movers whose surface is this close";
        pub v_static: f64 = 0.1, "m/s" [>= 0.0] label "static speed limit" "movers faster than this are ordinary dynamic";
        /// A special obstacle this close to the current goal is "near the
        /// goal" (\[T\] Fig 3-13 c–e).
        pub goal_region: f64 = 1.5, "m" [>= 0.0]
            label "goal region" "near-goal rules within this of the current goal (virtual goal beside it, drive-in)";
        /// \[T\] eq 3-7.
        pub rho_n: f64 = 2.0, "1" [>= 0.0] label "relative distance exponent n" "exponent n of the relative distance factor ρ";
        pub decelerate: Weights = Weights { alpha: 1.0, beta: 0.2, gamma: 0.1 }, "" [nested of]
            label "deceleration" "deceleration strategy (large heading weight)";
        pub detour: Weights = Weights { alpha: 0.05, beta: 0.2, gamma: 0.1 }, "" [nested of]
            label "detour" "detour strategy (small heading weight)";
    }
}

crate::params::params! {
    /// Settings of the "\[53\]" baseline fusion: key points + DWA with the
    /// deceleration strategy only.
    #[derive(Debug, Clone, Copy, PartialEq)]
    pub struct Fusion53Config {
        /// Its α, β, γ are the weights with no mover in range.
        pub dwa: DwaConfig = DwaConfig::default(), "" [nested] "the DWA engine";
        pub inflate_margin: f64 = 0.1, "m" [>= 0.0] label "inflation margin" "A* inflation beyond the footprint radius";
        pub switch_radius: f64 = 1.0, "m" [> 0.0] label "key point switch radius" "advance to the next key point within this";
        /// Measured from the robot's centre.
        pub react_range: f64 = 3.0, "m" [>= 0.0]
            label "reaction range" "decelerate while a moving obstacle's surface is this close";
        pub v_static: f64 = 0.1, "m/s" [>= 0.0]
            label "static speed limit" "obstacles faster than this are moving (decelerate); slower get plain DWA";
        pub decelerate: Weights = Weights { alpha: 1.0, beta: 0.2, gamma: 0.1 }, "" [nested of]
            label "deceleration" "deceleration strategy";
    }
}

impl ImprovedConfig {
    /// Checks every number; errors name `prefix.field`.
    pub fn validate(&self, prefix: &str) -> Result<(), LocalError> {
        self.dwa.validate(&format!("{prefix}.dwa"))?;
        self.check_bounds(prefix)?;
        self.decelerate.validate(&format!("{prefix}.decelerate"))?;
        self.detour.validate(&format!("{prefix}.detour"))
    }
}

/// Which planner a [`FusionGuide`] makes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FusionVariant {
    /// \[T\]'s improved DWA (`improved-dwa`).
    Improved,
    /// The "\[53\]" baseline (`fusion-53`).
    Fusion53,
}

/// An active virtual goal.
#[derive(Debug, Clone, Copy, PartialEq)]
struct VirtualGoal {
    point: [f64; 2],
    obstacle: u32,
    /// Unit robot→goal direction when it was set: the virtual goal lies on
    /// the perpendicular to it through the obstacle.
    dir: [f64; 2],
}

/// Goal provider of `improved-dwa` and `fusion-53`.
#[derive(Debug, Clone)]
pub struct FusionGuide {
    cfg: ImprovedConfig,
    variant: FusionVariant,
    r_robot: f64,
    goal: [f64; 2],
    route: Route,
    idx: usize,
    virt: Option<VirtualGoal>,
    classes: Vec<(u32, ObstacleClass)>,
    /// Set when the final goal moved and no new route could be planned.
    lost: bool,
}

/// The improved DWA of \[T\] (registry name `improved-dwa`).
pub type ImprovedDwa = DwaPlanner<FusionGuide>;

fn grid_options(cfg: &ImprovedConfig, r_robot: f64) -> GridPlanOptions {
    GridPlanOptions {
        inflate_m: r_robot + cfg.inflate_margin,
        keypoints: true,
        ..Default::default()
    }
}

impl FusionGuide {
    fn build(
        cfg: ImprovedConfig,
        variant: FusionVariant,
        robot: &RobotSpec,
        map: &StaticMap,
        start: &RobotState,
        goal: [f64; 2],
    ) -> Result<DwaPlanner<FusionGuide>, LocalError> {
        let name = match variant {
            FusionVariant::Improved => "improved-dwa",
            FusionVariant::Fusion53 => "fusion-53",
        };
        cfg.validate(name)?;
        check_goal(goal)?;
        let engine = cfg.dwa.engine(robot, &format!("{name}.dwa"), false)?;
        let r_robot = robot.footprint.circumscribed_radius();
        let route = plan_route(
            map,
            [start.x, start.y],
            goal,
            &grid_options(&cfg, r_robot),
            Waypoints::KeyPoints,
        )?;
        Ok(DwaPlanner::from_parts(
            engine,
            cfg.dwa.weights(),
            FusionGuide {
                cfg,
                variant,
                r_robot,
                goal,
                route,
                idx: 0,
                virt: None,
                classes: Vec::new(),
                lost: false,
            },
        ))
    }

    /// The global route (path and key points).
    pub fn route(&self) -> &Route {
        &self.route
    }

    /// Index of the current key point in the route's waypoints.
    pub fn waypoint_index(&self) -> usize {
        self.idx
    }

    /// The current key point, or the final goal when lost.
    fn waypoint(&self) -> ([f64; 2], GoalKind) {
        match self.route.waypoints.get(self.idx) {
            Some(&p) if !self.lost => {
                let kind = if self.idx + 1 == self.route.waypoints.len() {
                    GoalKind::Final
                } else {
                    GoalKind::Intermediate
                };
                (p, kind)
            }
            _ => (self.goal, GoalKind::Final),
        }
    }

    fn replan(
        &mut self,
        map: &StaticMap,
        from: [f64; 2],
        goal: [f64; 2],
    ) -> Result<(), LocalError> {
        let route = plan_route(
            map,
            from,
            goal,
            &grid_options(&self.cfg, self.r_robot),
            Waypoints::KeyPoints,
        )?;
        self.route = route;
        self.idx = 0;
        self.virt = None;
        self.goal = goal;
        self.lost = false;
        Ok(())
    }

    /// Whether mover `m` is collinear with `robot` and `goal`: its centre
    /// is closer than r_obs + r_robot to the segment and projects onto it.
    fn collinear(&self, robot: [f64; 2], goal: [f64; 2], c: [f64; 2], radius: f64) -> bool {
        let (dx, dy) = (goal[0] - robot[0], goal[1] - robot[1]);
        let len2 = dx * dx + dy * dy;
        if len2 <= 1e-12 {
            return false;
        }
        let t = ((c[0] - robot[0]) * dx + (c[1] - robot[1]) * dy) / len2;
        if !(0.0..=1.0).contains(&t) {
            return false;
        }
        let (px, py) = (robot[0] + t * dx, robot[1] + t * dy);
        hypot(c[0] - px, c[1] - py) < radius + self.r_robot
    }

    fn classify(&self, robot: [f64; 2], goal: [f64; 2], m: &ObservedMover) -> ObstacleClass {
        let speed = hypot(m.vel[0], m.vel[1]);
        let now = self.collinear(robot, goal, m.pos, m.radius);
        if speed <= self.cfg.v_static {
            return if now {
                ObstacleClass::Special
            } else {
                ObstacleClass::OrdinaryStatic
            };
        }
        let t = self.cfg.dwa.predict_time;
        let later = [m.pos[0] + m.vel[0] * t, m.pos[1] + m.vel[1] * t];
        if now && self.collinear(robot, goal, later, m.radius) {
            ObstacleClass::Special
        } else {
            ObstacleClass::OrdinaryDynamic
        }
    }

    /// Free space around point `p`, m: the map clearance and the distance to
    /// every perceived mover's surface except `skip`.
    fn room(map: &StaticMap, movers: &[ObservedMover], p: [f64; 2], skip: u32) -> f64 {
        let mut c = map.clearance(p[0], p[1]);
        for m in movers.iter().filter(|m| m.id != skip) {
            c = c.min(dist(p, m.pos) - m.radius);
        }
        c
    }

    /// The virtual goal `offset` from `base` along the normal of robot→goal,
    /// on the side with more room (the robot's side on a near tie); `None`
    /// when neither side leaves room for the robot.
    #[allow(clippy::too_many_arguments)]
    fn place_virtual(
        &self,
        map: &StaticMap,
        movers: &[ObservedMover],
        robot: [f64; 2],
        goal: [f64; 2],
        base: [f64; 2],
        offset: f64,
        skip: u32,
    ) -> Option<[f64; 2]> {
        let (dx, dy) = (goal[0] - robot[0], goal[1] - robot[1]);
        let len = hypot(dx, dy);
        if len <= 1e-9 {
            return None;
        }
        let n = [-dy / len, dx / len];
        let left = [base[0] + n[0] * offset, base[1] + n[1] * offset];
        let right = [base[0] - n[0] * offset, base[1] - n[1] * offset];
        let (rl, rr) = (
            Self::room(map, movers, left, skip),
            Self::room(map, movers, right, skip),
        );
        // On a near tie, pass on the side where `base` (the obstacle) leaves
        // the wider gap: opposite to its offset from the robot→goal line.
        let lean = (robot[0] - base[0]) * n[0] + (robot[1] - base[1]) * n[1];
        let tie = 0.05;
        let pick_left = if (rl - rr).abs() <= tie {
            lean >= 0.0
        } else {
            rl > rr
        };
        let (p, room) = if pick_left { (left, rl) } else { (right, rr) };
        (room > self.r_robot).then_some(p)
    }

    /// Distance from the robot's centre to the nearest obstacle surface, m.
    fn nearest_obstacle(map: &StaticMap, movers: &[ObservedMover], p: [f64; 2]) -> f64 {
        super::engine::screen::centre_clearance(map, movers, p)
    }
}

impl GoalProvider for FusionGuide {
    fn name(&self) -> &'static str {
        match self.variant {
            FusionVariant::Improved => "improved-dwa",
            FusionVariant::Fusion53 => "fusion-53",
        }
    }

    fn guide(&mut self, obs: &Observation<'_>, base: Weights) -> Guidance {
        let robot = [obs.state.x, obs.state.y];
        if dist(obs.goal, self.goal) > 1e-9 {
            // The final goal moved without set_goal: replan from here.
            if self.replan(obs.map, robot, obs.goal).is_err() {
                self.goal = obs.goal;
                self.lost = true;
            }
        }
        // Advance along the key points.
        while self.idx + 1 < self.route.waypoints.len()
            && dist(robot, self.route.waypoints[self.idx]) < self.cfg.switch_radius
        {
            self.idx += 1;
        }
        let (wp, wp_kind) = self.waypoint();
        let in_range = |m: &&ObservedMover| dist(robot, m.pos) - m.radius <= self.cfg.react_range;

        if self.variant == FusionVariant::Fusion53 {
            // Deceleration for moving obstacles only (module doc, Decision).
            self.classes.clear();
            let any = obs
                .movers
                .iter()
                .filter(in_range)
                .any(|m| hypot(m.vel[0], m.vel[1]) > self.cfg.v_static);
            let (weights, mode) = if any {
                (self.cfg.decelerate, "decelerate")
            } else {
                (base, "normal")
            };
            return Guidance {
                goal: wp,
                kind: wp_kind,
                weights,
                rho: 1.0,
                hold_v: None,
                braking: any,
                mode,
            };
        }

        // Classification of the movers in range.
        self.classes.clear();
        let mut any_dynamic = false;
        let mut any = false;
        let mut special: Option<&ObservedMover> = None;
        for m in obs.movers.iter().filter(in_range) {
            let class = self.classify(robot, wp, m);
            any = true;
            match class {
                ObstacleClass::OrdinaryDynamic => any_dynamic = true,
                ObstacleClass::Special => {
                    // The nearest special obstacle gets the virtual goal.
                    if special.map_or(true, |s| dist(robot, m.pos) < dist(robot, s.pos)) {
                        special = Some(m);
                    }
                }
                ObstacleClass::OrdinaryStatic => {}
            }
            self.classes.push((m.id, class));
        }

        let x_rg_wp = dist(robot, wp);
        let x_ro = Self::nearest_obstacle(obs.map, obs.movers, robot);
        // Near the goal and closer to it than to anything (\[T\] §3.2.3: "if
        // the robot is closer to the goal, ρ takes it there directly").
        let drive_in = x_rg_wp <= self.cfg.goal_region && x_rg_wp <= x_ro;
        // Keep or drop the active virtual goal: reached, its obstacle behind
        // the robot (along the direction it was placed from) or gone, or
        // driving in.
        if let Some(v) = self.virt {
            let obstacle = obs.movers.iter().find(|m| m.id == v.obstacle);
            let reached = dist(robot, v.point) < self.cfg.virtual_radius;
            let passed = obstacle.map_or(true, |m| {
                (m.pos[0] - robot[0]) * v.dir[0] + (m.pos[1] - robot[1]) * v.dir[1] < 0.0
            });
            if reached || passed || drive_in {
                self.virt = None;
            }
        }
        let mut mode = if any_dynamic {
            "decelerate"
        } else if any {
            "detour"
        } else {
            "normal"
        };
        if self.virt.is_none() && !drive_in {
            if let Some(m) = special {
                let diameter = 2.0 * self.r_robot;
                let obstacle_near_goal = dist(m.pos, wp) <= self.cfg.goal_region;
                // Fig 3-13 a–b: the robot closer to the goal than to the
                // obstacle needs no virtual goal (drive-in below).
                if !(obstacle_near_goal && x_rg_wp <= dist(robot, m.pos) - m.radius) {
                    // Fig 3-13 c–e near the goal: beside the goal; else
                    // beside the obstacle.
                    let (base_pt, offset) = if obstacle_near_goal {
                        (wp, diameter)
                    } else {
                        (m.pos, m.radius + diameter)
                    };
                    if let Some(p) =
                        self.place_virtual(obs.map, obs.movers, robot, wp, base_pt, offset, m.id)
                    {
                        let len = x_rg_wp.max(1e-9);
                        self.virt = Some(VirtualGoal {
                            point: p,
                            obstacle: m.id,
                            dir: [(wp[0] - robot[0]) / len, (wp[1] - robot[1]) / len],
                        });
                    }
                }
            }
        }
        // Driving in: the general (deceleration) weights, ρ weakening the
        // clearance term.
        if drive_in && mode != "normal" {
            mode = "drive-in";
        }
        let (goal, kind) = match self.virt {
            Some(v) => (v.point, GoalKind::Virtual),
            None => (wp, wp_kind),
        };
        let weights = match mode {
            "decelerate" | "drive-in" => self.cfg.decelerate,
            "normal" => base,
            _ => self.cfg.detour,
        };
        if self.virt.is_some() && mode != "decelerate" {
            mode = "virtual-goal";
        }
        // Relative distance factor, eq 3-7.
        let x_rg = dist(robot, goal);
        let rho = if x_ro > 0.0 && x_rg <= x_ro {
            pow(x_rg / x_ro, self.cfg.rho_n)
        } else {
            1.0
        };
        Guidance {
            goal,
            kind,
            weights,
            rho,
            hold_v: None,
            braking: mode == "decelerate" || mode == "drive-in",
            mode,
        }
    }

    fn retarget(
        &mut self,
        map: &StaticMap,
        state: &RobotState,
        goal: [f64; 2],
    ) -> Result<(), LocalError> {
        check_goal(goal)?;
        self.replan(map, [state.x, state.y], goal)
    }

    fn route(&self) -> &[[f64; 2]] {
        &self.route.path
    }

    fn annotate(&self, debug: &mut PlannerDebug) {
        debug.global_path.clone_from(&self.route.path);
        debug.keypoints.clone_from(&self.route.waypoints);
        debug.classes.clone_from(&self.classes);
    }
}

impl ImprovedDwa {
    /// \[T\]'s improved DWA + A\* fusion for `robot` on `map` from `start`
    /// to `goal`. Errors: an invalid config (naming the field) or no
    /// global path.
    pub fn improved(
        cfg: ImprovedConfig,
        robot: &RobotSpec,
        map: &StaticMap,
        start: &RobotState,
        goal: [f64; 2],
    ) -> Result<Self, LocalError> {
        FusionGuide::build(cfg, FusionVariant::Improved, robot, map, start, goal)
    }

    /// The "\[53\]" baseline fusion.
    pub fn fusion53(
        cfg: Fusion53Config,
        robot: &RobotSpec,
        map: &StaticMap,
        start: &RobotState,
        goal: [f64; 2],
    ) -> Result<Self, LocalError> {
        let full = ImprovedConfig {
            dwa: cfg.dwa,
            inflate_margin: cfg.inflate_margin,
            switch_radius: cfg.switch_radius,
            react_range: cfg.react_range,
            v_static: cfg.v_static,
            decelerate: cfg.decelerate,
            ..Default::default()
        };
        FusionGuide::build(full, FusionVariant::Fusion53, robot, map, start, goal)
    }
}

#[cfg(test)]
mod tests {
    use super::super::testkit;
    use super::super::LocalPlanner;
    use super::*;
    use crate::world::{Footprint, RobotLimits};

    fn robot() -> RobotSpec {
        RobotSpec {
            footprint: Footprint::Circle { radius: 0.25 },
            limits: RobotLimits::default(),
            ..Default::default()
        }
    }

    fn room() -> StaticMap {
        let row = ".".repeat(100);
        let rows: Vec<String> = (0..60).map(|_| row.clone()).collect();
        testkit::map(&(rows.join("\n") + "\n"), 0.1)
    }

    fn at(x: f64, y: f64) -> RobotState {
        RobotState {
            x,
            y,
            ..Default::default()
        }
    }

    fn mover(id: u32, pos: [f64; 2], vel: [f64; 2]) -> ObservedMover {
        ObservedMover {
            id,
            pos,
            vel,
            radius: 0.2,
        }
    }

    fn step(p: &mut ImprovedDwa, map: &StaticMap, s: &RobotState, movers: &[ObservedMover]) {
        let obs = Observation {
            time: 0.0,
            dt: 0.1,
            state: s,
            goal: [9.0, 3.0],
            map,
            map_revision: 0,
            scan: None,
            movers,
            odometry: None,
            accel_z: 0.0,
        };
        let c = p.step(&obs);
        assert!(c.v.is_finite() && c.w.is_finite());
    }

    #[test]
    fn classes_follow_speed_and_collinearity() {
        let map = room();
        let s = at(1.0, 3.0);
        let mut p =
            ImprovedDwa::improved(ImprovedConfig::default(), &robot(), &map, &s, [9.0, 3.0])
                .unwrap();
        let movers = [
            mover(1, [2.5, 3.1], [0.0, 0.0]),  // still, on the line: special
            mover(2, [3.0, 5.0], [0.0, -0.4]), // crossing fast: ordinary dynamic
            mover(3, [4.0, 3.0], [-0.3, 0.0]), // head-on along the line: special
            mover(4, [2.0, 1.5], [0.05, 0.0]), // slow, off the line: ordinary static
        ];
        step(&mut p, &map, &s, &movers);
        let d = p.debug();
        assert_eq!(
            d.classes,
            vec![
                (1, ObstacleClass::Special),
                (2, ObstacleClass::OrdinaryDynamic),
                (3, ObstacleClass::Special),
                (4, ObstacleClass::OrdinaryStatic),
            ]
        );
        // The nearest special one got a virtual goal beside it (the mode is
        // the braking fallback's: the head-on mover leaves nowhere to stop).
        assert!(d.mode == "decelerate" || d.mode.starts_with("no-admissible"));
        assert_eq!(d.goal_kind, GoalKind::Virtual);
        assert!(
            (d.current_goal[0] - 2.5).abs() < 1e-9,
            "{:?}",
            d.current_goal
        );
        assert!((d.current_goal[1] - 3.0).abs() > 0.6);
        assert!(!d.global_path.is_empty() && d.keypoints.last() == Some(&[9.0, 3.0]));
    }

    #[test]
    fn virtual_goal_goes_to_the_roomier_side() {
        // A wall 0.8 m above the line: the virtual goal goes below.
        let mut rows: Vec<String> = (0..60).map(|_| ".".repeat(100)).collect();
        rows[60 - 1 - 38] = "#".repeat(100);
        let map = testkit::map(&(rows.join("\n") + "\n"), 0.1);
        let s = at(1.0, 3.0);
        let mut p =
            ImprovedDwa::improved(ImprovedConfig::default(), &robot(), &map, &s, [9.0, 3.0])
                .unwrap();
        step(&mut p, &map, &s, &[mover(7, [3.0, 3.05], [0.0, 0.0])]);
        let d = p.debug();
        assert_eq!(d.goal_kind, GoalKind::Virtual);
        assert!(d.current_goal[1] < 3.0 - 0.6, "{:?}", d.current_goal);
        assert_eq!(d.mode, "virtual-goal");
    }

    #[test]
    fn near_the_goal_closer_to_it_than_to_the_obstacle_drives_in_with_rho() {
        let map = room();
        let s = at(8.5, 3.0);
        let mut p =
            ImprovedDwa::improved(ImprovedConfig::default(), &robot(), &map, &s, [9.0, 3.0])
                .unwrap();
        step(&mut p, &map, &s, &[mover(1, [9.7, 3.0], [0.0, 0.0])]);
        assert_eq!(p.debug().mode, "drive-in");
        assert_eq!(p.debug().goal_kind, GoalKind::Final);
        // The [53] baseline has no such rule: plain DWA for a still disc,
        // the deceleration strategy for a moving one.
        let mut b =
            ImprovedDwa::fusion53(Fusion53Config::default(), &robot(), &map, &s, [9.0, 3.0])
                .unwrap();
        step(&mut b, &map, &s, &[mover(1, [9.7, 3.0], [0.0, 0.0])]);
        assert_eq!(b.debug().mode, "normal");
        assert!(b.debug().classes.is_empty());
        step(&mut b, &map, &s, &[mover(1, [9.7, 3.0], [0.0, 0.3])]);
        assert_eq!(b.debug().mode, "decelerate");
    }

    #[test]
    fn bad_config_and_unreachable_goal_are_typed_errors() {
        let map = room();
        let s = at(1.0, 3.0);
        let cfg = ImprovedConfig {
            switch_radius: -1.0,
            ..Default::default()
        };
        let e = ImprovedDwa::improved(cfg, &robot(), &map, &s, [9.0, 3.0]).unwrap_err();
        assert!(e.to_string().contains("improved-dwa.switch_radius"), "{e}");
        let mut cfg = Fusion53Config::default();
        cfg.decelerate.alpha = f64::NAN;
        let e = ImprovedDwa::fusion53(cfg, &robot(), &map, &s, [9.0, 3.0]).unwrap_err();
        assert!(e.to_string().contains("fusion-53.decelerate.alpha"), "{e}");
        let walled = testkit::map("....#....\n....#....\n....#....\n", 1.0);
        let e = ImprovedDwa::improved(
            ImprovedConfig::default(),
            &robot(),
            &walled,
            &at(0.5, 1.5),
            [8.5, 1.5],
        )
        .unwrap_err();
        assert!(matches!(e, LocalError::NoGlobalPath(_)), "{e}");
    }

    #[test]
    fn key_points_advance_and_the_goal_can_move() {
        // A wall from the top down to y = 2 m at x = 5 m: go round below it.
        let rows: Vec<String> = (0..60)
            .map(|r| {
                if r < 40 {
                    format!("{}###{}", ".".repeat(50), ".".repeat(47))
                } else {
                    ".".repeat(100)
                }
            })
            .collect();
        let map = testkit::map(&(rows.join("\n") + "\n"), 0.1);
        let s = at(1.0, 4.0);
        let mut p =
            ImprovedDwa::improved(ImprovedConfig::default(), &robot(), &map, &s, [9.0, 4.0])
                .unwrap();
        let n = p.guide().route().waypoints.len();
        assert!(n >= 2, "{:?}", p.guide().route().waypoints);
        let first = p.guide().route().waypoints[0];
        step(&mut p, &map, &at(first[0], first[1]), &[]);
        assert_eq!(p.guide().waypoint_index(), 1);
        p.set_goal(&map, &at(1.0, 4.0), [2.0, 5.0]).unwrap();
        assert_eq!(*p.guide().route().waypoints.last().unwrap(), [2.0, 5.0]);
        assert_eq!(p.guide().waypoint_index(), 0);
    }
}
