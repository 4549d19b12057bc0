//! [`Apf`]: one planning step of the basic or improved APF (\[T\] §4.1–4.2).
//!
//! Each call to [`Apf::step`] gets the robot's position, the goal and the
//! obstacles as observed now, and returns the next path point (one step of
//! length d, or less to land on the goal) with everything the page draws:
//! forces, the sampled candidates with their costs, the chosen one, and
//! the predicted obstacles with their virtual ranges.
//!
//! Improved step (modes `sampling`, `sampling-prediction`):
//! 1. with prediction, every observed obstacle's track gives predicted
//!    centres at t+1 = now + Δ and t+2 = now + 2Δ (Δ =
//!    [`ApfConfig::predict_dt`]) with ranges s·R and s²·R (R = radius +
//!    robot radius + p₀, s = 0.75) and linear virtual repulsion;
//! 2. sample the directions around the resultant, cost each candidate
//!    point c by α‖F_attr(c)‖ + β‖F_rep(c)‖ (eq 4-11) and step to the
//!    cheapest; ties go to the smallest deviation, counter-clockwise /
//!    upward first. Where no candidate feels repulsion this is the step
//!    along the resultant (reported as [`StepKind::Resultant`]). Sampling
//!    every step, rather than only once repulsion acts at the robot,
//!    keeps the path on the edge of the repulsion range instead of
//!    zig-zagging across it (**Decision**, the thesis leaves the trigger
//!    open);
//! 4. relative distance rule: while the goal is nearer than every obstacle
//!    surface, β = 0 and the sampling is centred on the attraction.

use super::field::{attraction, repulsion, surface_distance, virtual_repulsion, VirtualObstacle};
use super::predict::{Predictor, Track};
use super::{ApfConfig, ApfError, ApfMode, ApfVector, Sampling};

/// An obstacle as observed at one planning step: a sphere (3D) / disc (2D).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ObstacleObs<V> {
    /// Stable identity (tracks for prediction are kept per id).
    pub id: u32,
    /// Centre now, m.
    pub centre: V,
    /// Radius, m (0 for a point).
    pub radius: f64,
    /// Velocity if the sensor measures it, m/s (else tracks difference
    /// positions). A measured velocity of exactly zero marks a static
    /// obstacle: it gets no track and no predicted copies.
    pub velocity: Option<V>,
}

impl<V: ApfVector> ObstacleObs<V> {
    /// A static obstacle.
    pub fn fixed(id: u32, centre: V, radius: f64) -> Self {
        Self {
            id,
            centre,
            radius,
            velocity: None,
        }
    }

    /// An obstacle with a measured velocity.
    pub fn moving(id: u32, centre: V, radius: f64, velocity: V) -> Self {
        Self {
            id,
            centre,
            radius,
            velocity: Some(velocity),
        }
    }
}

/// One sampled candidate of an improved step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Candidate<V> {
    /// Deviation from the sampling axis, rad (signed in 2D / the vertical
    /// plane).
    pub angle: f64,
    /// Unit direction.
    pub direction: V,
    /// Candidate point, m.
    pub point: V,
    /// ‖F_attr‖ at the point.
    pub attraction: f64,
    /// ‖F_rep‖ at the point (real and virtual).
    pub repulsion: f64,
    /// α‖F_attr‖ + β‖F_rep‖ (with β of the step, see [`ApfStep::beta`]).
    pub cost: f64,
}

/// How a step was chosen.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StepKind {
    /// Along the resultant force (basic APF, or no repulsion acting).
    Resultant,
    /// The cheapest sampled direction.
    Sampled,
    /// Sampled with β = 0 by the relative distance rule.
    RelativeDistance,
    /// The resultant vanished: basic APF stands still.
    Stalled,
    /// Already at the goal.
    Arrived,
}

/// The outcome of one [`Apf::step`].
#[derive(Debug, Clone, PartialEq)]
pub struct ApfStep<V> {
    /// The next path point, m.
    pub next: V,
    /// Unit direction of the step (zero when standing still).
    pub direction: V,
    /// Attraction at the robot.
    pub attraction: V,
    /// Repulsion at the robot (real plus virtual).
    pub repulsion: V,
    /// Their sum.
    pub resultant: V,
    /// Sampled candidates (empty for a resultant step).
    pub candidates: Vec<Candidate<V>>,
    /// Index of the chosen candidate.
    pub chosen: Option<usize>,
    /// Predicted obstacles of this step (prediction mode).
    pub predicted: Vec<VirtualObstacle<V>>,
    /// How the step was chosen.
    pub kind: StepKind,
    /// β used in the costs (0 under the relative distance rule).
    pub beta: f64,
}

/// The APF planner of one robot; keeps per-obstacle tracks for prediction.
pub struct Apf<V: ApfVector> {
    cfg: ApfConfig,
    sampling: Sampling,
    predictor: Box<dyn Predictor>,
    tracks: Vec<(u32, Track)>,
    dirs: Vec<(f64, V)>,
}

impl<V: ApfVector> std::fmt::Debug for Apf<V> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Apf")
            .field("cfg", &self.cfg)
            .field("predictor", &self.predictor.name())
            .field("tracks", &self.tracks.len())
            .finish()
    }
}

impl<V: ApfVector> Apf<V> {
    /// A planner with the predictor named in the config.
    pub fn new(cfg: ApfConfig) -> Result<Self, ApfError> {
        cfg.validate()?;
        let predictor = cfg.predictor.build()?;
        Self::with_predictor(cfg, predictor)
    }

    /// A planner with a given predictor (overrides `cfg.predictor`).
    pub fn with_predictor(cfg: ApfConfig, predictor: Box<dyn Predictor>) -> Result<Self, ApfError> {
        cfg.validate()?;
        Ok(Self {
            sampling: cfg.sampling(),
            cfg,
            predictor,
            tracks: Vec::new(),
            dirs: Vec::with_capacity(80),
        })
    }

    /// The config.
    pub fn config(&self) -> &ApfConfig {
        &self.cfg
    }

    /// The predictor's name.
    pub fn predictor_name(&self) -> &'static str {
        self.predictor.name()
    }

    /// Forgets every obstacle track.
    pub fn reset(&mut self) {
        self.tracks.clear();
    }

    /// Records the obstacles observed at time `t` (s) in their tracks;
    /// [`Apf::step`] does this itself.
    pub fn observe(&mut self, t: f64, obstacles: &[ObstacleObs<V>]) {
        for o in obstacles.iter().filter(|o| o.velocity != Some(V::ZERO)) {
            let vel = o.velocity.map(|v| v.to_xyz());
            match self.tracks.iter_mut().find(|(id, _)| *id == o.id) {
                Some((_, tr)) => tr.push(t, o.centre.to_xyz(), vel),
                None => {
                    let mut tr = Track::new();
                    tr.push(t, o.centre.to_xyz(), vel);
                    self.tracks.push((o.id, tr));
                }
            }
        }
        // Obstacles no longer seen lose their track.
        self.tracks.retain(|(id, _)| {
            obstacles
                .iter()
                .any(|o| o.id == *id && o.velocity != Some(V::ZERO))
        });
    }

    /// Predicted obstacles (t+1, t+2) of the current tracks.
    pub fn predictions(&self, obstacles: &[ObstacleObs<V>]) -> Vec<VirtualObstacle<V>> {
        let mut out = Vec::new();
        for o in obstacles {
            let Some((_, tr)) = self.tracks.iter().find(|(id, _)| *id == o.id) else {
                continue;
            };
            let here = o.centre.to_xyz();
            let reach = o.radius + self.cfg.robot_radius + self.cfg.p0;
            let dt = self.cfg.predict_dt;
            let preds = self.predictor.predict_many(tr, &[dt, 2.0 * dt]);
            let mut scale = 1.0;
            for (k, p) in (1..=2u8).zip(preds) {
                scale *= self.cfg.predict_scale;
                if !p.is_finite() || (p - here).length() < self.cfg.predict_min_motion {
                    continue;
                }
                out.push(VirtualObstacle {
                    id: o.id,
                    k,
                    centre: V::from_xyz(p),
                    range: scale * reach,
                    gain: self.cfg.predict_gains[k as usize - 1],
                });
            }
        }
        out
    }

    /// Attraction and total repulsion (real and virtual) at `x`: the field
    /// the page draws.
    pub fn forces_at(
        &self,
        x: V,
        goal: V,
        obstacles: &[ObstacleObs<V>],
        virtuals: &[VirtualObstacle<V>],
    ) -> (V, V) {
        let fa = attraction(&self.cfg, x, goal);
        let fa_mag = fa.norm();
        let mut fr = V::ZERO;
        for o in obstacles {
            fr = fr + repulsion(&self.cfg, x, o.centre, o.radius);
        }
        for v in virtuals {
            fr = fr + virtual_repulsion(x, v, fa_mag);
        }
        (fa, fr)
    }

    /// One planning step at time `t` (s) from `pos` toward `goal` among
    /// `obstacles` (see the module doc). Errors only on non-finite input.
    pub fn step(
        &mut self,
        t: f64,
        pos: V,
        goal: V,
        obstacles: &[ObstacleObs<V>],
    ) -> Result<ApfStep<V>, ApfError> {
        for (what, p) in [("position", pos), ("goal", goal)] {
            if !p.to_xyz().is_finite() {
                return Err(ApfError::BadPoint {
                    what: what.into(),
                    expected: V::DIM,
                    got: p.to_vec(),
                });
            }
        }
        if !t.is_finite() {
            return Err(ApfError::InvalidParameter(format!(
                "time {t} s must be finite"
            )));
        }
        if let Some(o) = obstacles
            .iter()
            .find(|o| !(o.centre.to_xyz().is_finite() && o.radius >= 0.0 && o.radius.is_finite()))
        {
            return Err(ApfError::InvalidParameter(format!(
                "obstacle {}: centre {:?} / radius {} must be finite (radius ≥ 0)",
                o.id,
                o.centre.to_vec(),
                o.radius
            )));
        }
        let predicting = self.cfg.mode == ApfMode::SamplingPrediction;
        let predicted = if predicting {
            self.observe(t, obstacles);
            self.predictions(obstacles)
        } else {
            Vec::new()
        };
        let (fa, fr) = self.forces_at(pos, goal, obstacles, &predicted);
        let resultant = fa + fr;
        let to_goal = (goal - pos).norm();
        let mut out = ApfStep {
            next: pos,
            direction: V::ZERO,
            attraction: fa,
            repulsion: fr,
            resultant,
            candidates: Vec::new(),
            chosen: None,
            predicted,
            kind: StepKind::Arrived,
            beta: self.cfg.beta,
        };
        if to_goal <= 1e-12 {
            out.next = goal;
            return Ok(out);
        }
        let len = self.cfg.step.min(to_goal);
        let rn = resultant.norm();
        if self.cfg.mode == ApfMode::Basic {
            if rn <= self.cfg.stall_force {
                out.kind = StepKind::Stalled;
                return Ok(out);
            }
            out.direction = resultant * (1.0 / rn);
            out.next = pos + out.direction * len;
            out.kind = StepKind::Resultant;
            return Ok(out);
        }
        // Relative distance rule (§4.2.2).
        let nearest = obstacles
            .iter()
            .map(|o| surface_distance(&self.cfg, pos, o.centre, o.radius))
            .fold(f64::INFINITY, f64::min);
        let relative = self.cfg.relative_distance && to_goal < nearest;
        let beta = if relative { 0.0 } else { self.cfg.beta };
        let axis = if relative || rn <= 1e-12 {
            fa * (1.0 / fa.norm().max(1e-300))
        } else {
            resultant * (1.0 / rn)
        };
        let mut dirs = std::mem::take(&mut self.dirs);
        dirs.clear();
        V::sample_directions(axis, &self.sampling, &mut dirs);
        let mut best: Option<(usize, f64)> = None;
        out.candidates.reserve(dirs.len());
        for &(angle, d) in &dirs {
            let c = pos + d * len;
            let (a, r) = self.forces_at(c, goal, obstacles, &out.predicted);
            let (a, r) = (a.norm(), r.norm());
            let cost = self.cfg.alpha * a + beta * r;
            let i = out.candidates.len();
            out.candidates.push(Candidate {
                angle,
                direction: d,
                point: c,
                attraction: a,
                repulsion: r,
                cost,
            });
            // Strictly cheaper (beyond rounding) wins; ties keep the earlier,
            // smaller deviation.
            if best.map_or(true, |(_, b)| cost < b - 1e-12 * b.abs().max(1e-12)) {
                best = Some((i, cost));
            }
        }
        self.dirs = dirs;
        let (i, _) = best.ok_or_else(|| {
            ApfError::InvalidParameter("no sampled direction (sample_step too large)".into())
        })?;
        out.chosen = Some(i);
        out.direction = out.candidates[i].direction;
        out.next = out.candidates[i].point;
        let felt = fr.norm() > 0.0 || out.candidates.iter().any(|c| c.repulsion > 0.0);
        out.kind = if !felt {
            StepKind::Resultant
        } else if relative {
            StepKind::RelativeDistance
        } else {
            StepKind::Sampled
        };
        out.beta = beta;
        Ok(out)
    }
}

/// The nearest-surface distance from `x` to `obstacles` (∞ when none), m.
pub fn nearest_surface<V: ApfVector>(cfg: &ApfConfig, x: V, obstacles: &[ObstacleObs<V>]) -> f64 {
    obstacles
        .iter()
        .map(|o| surface_distance(cfg, x, o.centre, o.radius))
        .fold(f64::INFINITY, f64::min)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DVec2, DVec3};

    fn run<V: ApfVector>(
        mode: ApfMode,
        start: V,
        goal: V,
        obs: &[ObstacleObs<V>],
        n: usize,
    ) -> Vec<V> {
        let cfg = ApfConfig {
            mode,
            ..ApfConfig::default()
        };
        let mut apf = Apf::<V>::new(cfg).unwrap();
        let mut path = vec![start];
        let mut p = start;
        for i in 0..n {
            p = apf.step(i as f64 * 0.1, p, goal, obs).unwrap().next;
            path.push(p);
        }
        path
    }

    #[test]
    fn free_space_steps_straight_to_the_goal_in_both_dimensions() {
        let p2 = run(ApfMode::Basic, DVec2::ZERO, DVec2::new(0.5, 0.2), &[], 30);
        assert!((*p2.last().unwrap() - DVec2::new(0.5, 0.2)).length() < 1e-9);
        let p3 = run(
            ApfMode::Sampling,
            DVec3::ZERO,
            DVec3::new(0.3, -0.2, 0.4),
            &[],
            30,
        );
        assert!((*p3.last().unwrap() - DVec3::new(0.3, -0.2, 0.4)).length() < 1e-9);
        // Fixed step length until the last one.
        assert!(((p3[1] - p3[0]).length() - 0.04).abs() < 1e-12);
    }

    #[test]
    fn collinear_obstacle_traps_basic_but_not_sampling_in_2d_and_3d() {
        let o2 = [ObstacleObs::fixed(0, DVec2::new(0.5, 0.0), 0.05)];
        let basic = run(ApfMode::Basic, DVec2::ZERO, DVec2::new(1.0, 0.0), &o2, 80);
        assert!((*basic.last().unwrap() - DVec2::new(1.0, 0.0)).length() > 0.4);
        assert!(basic.iter().all(|p| p.y == 0.0));
        let samp = run(
            ApfMode::Sampling,
            DVec2::ZERO,
            DVec2::new(1.0, 0.0),
            &o2,
            80,
        );
        assert!((*samp.last().unwrap() - DVec2::new(1.0, 0.0)).length() < 1e-9);
        let o3 = [ObstacleObs::fixed(0, DVec3::new(0.5, 0.0, 0.0), 0.05)];
        let samp3 = run(
            ApfMode::Sampling,
            DVec3::ZERO,
            DVec3::new(1.0, 0.0, 0.0),
            &o3,
            80,
        );
        assert!((*samp3.last().unwrap() - DVec3::new(1.0, 0.0, 0.0)).length() < 1e-9);
        // Escaped through the vertical plane, never touching the sphere.
        assert!(samp3.iter().all(|p| (*p - o3[0].centre).length() > 0.05));
    }

    #[test]
    fn a_sampled_step_has_13_candidates_and_picks_the_cheapest() {
        let o = [ObstacleObs::fixed(0, DVec2::new(0.15, 0.01), 0.05)];
        let mut apf = Apf::<DVec2>::new(ApfConfig {
            mode: ApfMode::Sampling,
            ..ApfConfig::default()
        })
        .unwrap();
        let s = apf
            .step(0.0, DVec2::ZERO, DVec2::new(1.0, 0.0), &o)
            .unwrap();
        assert_eq!(s.kind, StepKind::Sampled);
        assert_eq!(s.candidates.len(), 13);
        let i = s.chosen.unwrap();
        assert!(s.candidates.iter().all(|c| c.cost >= s.candidates[i].cost));
        assert_eq!(s.next, s.candidates[i].point);
    }

    #[test]
    fn prediction_places_two_shrinking_virtual_obstacles_ahead_of_a_mover() {
        let mut apf = Apf::<DVec2>::new(ApfConfig::default()).unwrap();
        let v = DVec2::new(-0.3, 0.0);
        let o = [ObstacleObs::moving(7, DVec2::new(0.6, 0.0), 0.05, v)];
        let s = apf
            .step(0.0, DVec2::ZERO, DVec2::new(1.0, 0.0), &o)
            .unwrap();
        assert_eq!(s.predicted.len(), 2);
        let (a, b) = (s.predicted[0], s.predicted[1]);
        assert!((a.centre - DVec2::new(0.45, 0.0)).length() < 1e-12);
        assert!((b.centre - DVec2::new(0.3, 0.0)).length() < 1e-12);
        assert!((a.range - 0.75 * 0.2).abs() < 1e-12 && (b.range - 0.5625 * 0.2).abs() < 1e-12);
        assert_eq!((a.gain, b.gain), (0.75, 0.5));
    }

    #[test]
    fn non_finite_input_is_an_error_not_a_panic() {
        let mut apf = Apf::<DVec3>::new(ApfConfig::default()).unwrap();
        assert!(apf
            .step(0.0, DVec3::new(f64::NAN, 0.0, 0.0), DVec3::X, &[])
            .is_err());
        let bad = [ObstacleObs::fixed(0, DVec3::ZERO, f64::NAN)];
        assert!(apf.step(0.0, DVec3::Z, DVec3::X, &bad).is_err());
        let cfg = ApfConfig {
            k_a: f64::NAN,
            ..ApfConfig::default()
        };
        assert!(Apf::<DVec3>::new(cfg)
            .unwrap_err()
            .to_string()
            .contains("k_a"));
    }
}
