//! The global path (A\* through the cleaning targets) and the local goal
//! and path along it (module doc: **Global path**, **Local goal**).

use super::CleaningDwa;
use crate::global::plan::{plan_on_map, Algorithm, GridPlanError, GridPlanOptions};
use crate::global::GridPos;
use crate::local::{GoalKind, LocalError};

/// L1 (Manhattan) distance from `p` to segment a–b: the convex piecewise
/// linear |p − a − t·d|₁ is smallest at t = 0, 1 or where one coordinate
/// crosses.
pub(super) fn l1_to_segment(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let d = [b[0] - a[0], b[1] - a[1]];
    let f = |t: f64| (p[0] - a[0] - t * d[0]).abs() + (p[1] - a[1] - t * d[1]).abs();
    let mut best = f(0.0).min(f(1.0));
    for k in 0..2 {
        if d[k] != 0.0 {
            let t = ((p[k] - a[k]) / d[k]).clamp(0.0, 1.0);
            best = best.min(f(t));
        }
    }
    best
}

/// The global path as straight segments with cumulative arc length.
#[derive(Debug, Clone, Default)]
pub(super) struct GlobalPath {
    pub(super) pts: Vec<[f64; 2]>,
    /// Arc length at each point.
    s: Vec<f64>,
}

impl GlobalPath {
    pub(super) fn new(raw: Vec<[f64; 2]>) -> Self {
        // Merge collinear runs (an A* path is mostly unit steps).
        let mut pts: Vec<[f64; 2]> = Vec::new();
        for p in raw {
            if let Some(&last) = pts.last() {
                if last == p {
                    continue;
                }
            }
            if pts.len() >= 2 {
                let (a, b) = (pts[pts.len() - 2], pts[pts.len() - 1]);
                let (d1, d2) = ([b[0] - a[0], b[1] - a[1]], [p[0] - b[0], p[1] - b[1]]);
                let cross = d1[0] * d2[1] - d1[1] * d2[0];
                let dot = d1[0] * d2[0] + d1[1] * d2[1];
                let scale = (d1[0] * d1[0] + d1[1] * d1[1]) * (d2[0] * d2[0] + d2[1] * d2[1]);
                if dot > 0.0 && cross * cross <= 1e-18 * scale {
                    let n = pts.len();
                    pts[n - 1] = p;
                    continue;
                }
            }
            pts.push(p);
        }
        let mut s = Vec::with_capacity(pts.len());
        let mut acc = 0.0;
        for (i, p) in pts.iter().enumerate() {
            if i > 0 {
                let q = pts[i - 1];
                acc += ((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1])).sqrt();
            }
            s.push(acc);
        }
        Self { pts, s }
    }

    pub(super) fn length(&self) -> f64 {
        self.s.last().copied().unwrap_or(0.0)
    }

    /// The point at arc length `s` (clamped) and the segment it lies on.
    pub(super) fn at(&self, s: f64) -> ([f64; 2], usize) {
        let n = self.pts.len();
        if n == 0 {
            return ([0.0, 0.0], 0);
        }
        if n == 1 || s <= 0.0 {
            return (self.pts[0], 0);
        }
        for i in 0..n - 1 {
            if s <= self.s[i + 1] || i == n - 2 {
                let len = self.s[i + 1] - self.s[i];
                let t = if len > 0.0 {
                    ((s - self.s[i]) / len).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                let (a, b) = (self.pts[i], self.pts[i + 1]);
                return ([a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])], i);
            }
        }
        (self.pts[n - 1], n - 2)
    }

    /// Projection of `p` onto segments `from..` within arc `s_max`:
    /// (segment, arc length, distance).
    pub(super) fn project(&self, p: [f64; 2], from: usize, s_max: f64) -> Option<(usize, f64)> {
        let mut best: Option<(usize, f64, f64)> = None;
        for i in from..self.pts.len().saturating_sub(1) {
            if self.s[i] > s_max {
                break;
            }
            let (a, b) = (self.pts[i], self.pts[i + 1]);
            let d = [b[0] - a[0], b[1] - a[1]];
            let len2 = d[0] * d[0] + d[1] * d[1];
            let t = if len2 > 0.0 {
                (((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let q = [a[0] + t * d[0], a[1] + t * d[1]];
            let dist = ((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1])).sqrt();
            let s = self.s[i] + t * (self.s[i + 1] - self.s[i]);
            let better = match best {
                None => true,
                Some((_, _, bd)) => dist < bd,
            };
            if better {
                best = Some((i, s, dist));
            }
        }
        best.map(|(i, s, _)| (i, s))
    }
}

impl CleaningDwa {
    fn cell_of(&self, p: [f64; 2], what: &str) -> Result<GridPos, LocalError> {
        self.solid
            .world_to_cell(p[0], p[1])
            .map(|(c, r)| GridPos::new(c as u32, r as u32))
            .ok_or_else(|| {
                LocalError::NoGlobalPath(format!(
                    "{what} ({:.3}, {:.3}) is off the map",
                    p[0], p[1]
                ))
            })
    }

    /// A* from `start` through `via` to `goal` on the inflated map (falling
    /// back to smaller inflations when an endpoint lies in the inflation).
    pub(super) fn replan(
        &mut self,
        start: [f64; 2],
        via: &[[f64; 2]],
        goal: [f64; 2],
    ) -> Result<(), LocalError> {
        let mut stops = vec![(start, "start".to_string())];
        for (i, w) in via.iter().enumerate() {
            stops.push((*w, format!("{}.waypoints[{i}]", self.name)));
        }
        stops.push((goal, "goal".to_string()));
        let mut raw: Vec<[f64; 2]> = vec![start];
        let mut arcs = Vec::new();
        for leg in stops.windows(2) {
            let (a, b) = (&leg[0], &leg[1]);
            let (ca, cb) = (self.cell_of(a.0, &a.1)?, self.cell_of(b.0, &b.1)?);
            let radii = [
                self.cfg.inflation_radius + self.cfg.safety_distance,
                self.cfg.inflation_radius,
                0.0,
            ];
            let mut result = None;
            for r in radii {
                let opts = GridPlanOptions {
                    algorithm: Algorithm::AStar,
                    inflate_m: r,
                    ..Default::default()
                };
                match plan_on_map(&self.solid, ca, cb, &opts) {
                    Err(GridPlanError::BlockedByInflation { .. }) => continue,
                    other => {
                        result = Some(other);
                        break;
                    }
                }
            }
            let plan = result
                .unwrap_or_else(|| {
                    Err(GridPlanError::Plan(
                        crate::global::PlanError::InvalidConfig("no inflation radius works".into()),
                    ))
                })
                .map_err(|e| LocalError::NoGlobalPath(format!("{} → {}: {e}", a.1, b.1)))?;
            let cells = &plan.path.cells;
            // Interior cells as centres; the leg's end is the exact point.
            for c in cells.iter().skip(1).take(cells.len().saturating_sub(2)) {
                let (x, y) = self.solid.cell_to_world(c.col as usize, c.row as usize);
                raw.push([x, y]);
            }
            raw.push(b.0);
            arcs.push((raw.len() - 1, b.0));
        }
        // Arc length of each leg end along the raw path (merging collinear
        // points below keeps lengths).
        let mut cum = vec![0.0; raw.len()];
        for i in 1..raw.len() {
            let (p, q) = (raw[i - 1], raw[i]);
            cum[i] =
                cum[i - 1] + ((q[0] - p[0]) * (q[0] - p[0]) + (q[1] - p[1]) * (q[1] - p[1])).sqrt();
        }
        self.stops = arcs
            .iter()
            .take(via.len())
            .map(|&(i, p)| (cum[i], p))
            .collect();
        self.next_stop = 0;
        self.path = GlobalPath::new(raw);
        self.seg = 0;
        self.s_robot = 0.0;
        self.goal = goal;
        self.engine.debug_mut().global_path = self.path.pts.clone();
        Ok(())
    }

    /// Local goal, its kind and the local path (projection → local goal).
    pub(super) fn local_goal(&mut self, p: [f64; 2]) -> ([f64; 2], GoalKind, Vec<[f64; 2]>) {
        let la = self.lookahead();
        let (seg, s) = self
            .path
            .project(p, self.seg, self.s_robot + 2.0 * la)
            .unwrap_or((self.seg, self.s_robot));
        self.seg = seg;
        self.s_robot = s;
        let mut total = self.path.length();
        if self.cfg.stop_at_waypoints {
            let tol = self.cfg.waypoint_tolerance;
            while let Some(&(_, w)) = self.stops.get(self.next_stop) {
                if (w[0] - p[0]) * (w[0] - p[0]) + (w[1] - p[1]) * (w[1] - p[1]) <= tol * tol {
                    self.next_stop += 1;
                } else {
                    break;
                }
            }
            if let Some(&(arc, _)) = self.stops.get(self.next_stop) {
                total = total.min(arc);
            }
        }
        let s_goal = (s + la).min(total);
        let (proj, _) = self.path.at(s);
        let (g, g_seg) = self.path.at(s_goal);
        let mut local = vec![proj];
        for i in seg + 1..=g_seg {
            if let Some(&q) = self.path.pts.get(i) {
                local.push(q);
            }
        }
        local.push(g);
        let kind = if s_goal >= self.path.length() {
            GoalKind::Final
        } else {
            GoalKind::Intermediate
        };
        (g, kind, local)
    }

    /// The lookahead in force: the configured one, but at least 1.25 times
    /// the farthest a rollout reaches (v_max·sim_time), so the local goal
    /// stays out of reach and progress, not an exact hit, decides.
    fn lookahead(&self) -> f64 {
        let l = &self.robot.limits;
        let reach = l.v_max.max(-l.v_min).max(l.vy_max) * self.cfg.sim_time;
        self.cfg.lookahead.max(1.25 * reach)
    }
}
