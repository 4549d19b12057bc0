//! Ground truth of motion: how a command becomes the robot's true motion.
//!
//! Flat ground with no slip by default: the true motion is exactly the
//! commanded one ([`super::robot::integrate`]). The cleaning-robot paper \[C\]
//! adds three things, all optional and all seeded:
//!
//! - **Road model** (vertical acceleration a_z from road roughness). The
//!   paper measured a_z with an IMU on asphalt and on hollow bricks but gives
//!   no numbers, so the process is ours: a_z = σ·(s / v_ref)·z, where s is
//!   the robot's true speed, z a unit-variance band-limited (first-order
//!   Gauss–Markov) process correlated over a *distance* `corr_length`
//!   (z ← ρz + √(1−ρ²)·n with ρ = exp(−Δs / corr_length), Δs the distance
//!   driven in the step). Correlating over distance rather than time makes
//!   the spectrum move with speed as a road profile's does; scaling by s
//!   makes a parked robot quiet. Presets (σ at v_ref, v_ref, corr_length):
//!   `flat` 0; `asphalt` 0.35 m/s² at 0.4 m/s over 0.10 m (small
//!   vibration); `hollow-brick` 1.3 m/s² at 0.3 m/s over 0.08 m (bricks with
//!   holes ~ 0.1 m apart: large, fast bumps).
//! - **Slip** (\[C\] eq 15–17): the true body-frame increment of a step is
//!   K_true·u + e, where u = (v_x, v_y, ω)·dt is the commanded (wheel
//!   odometry) increment and e is Gaussian noise whose standard deviation
//!   grows with the motion: σ_xy = `noise_xy`·‖(u_x, u_y)‖ on each
//!   translation axis, σ_θ = `noise_theta`·|u_θ| + `noise_theta_per_m`·
//!   ‖(u_x, u_y)‖. K_true = identity and zero noise (the default) is "no
//!   slip". When slip is on, every step reports the wheel and the true
//!   ("laser odometry") increments, which the cleaning DWA fits K from.
//! - **Bump drag**: hitting bumps costs speed. A step whose a_z is positive
//!   (the wheels unload, \[C\] §4.3: "颠簸打滑") loses `bump_drag`·a_z·dt of
//!   translational speed, in the true motion and in the wheel velocities the
//!   robot reports, so a planner must accelerate back — in the middle of the
//!   bumpy stretch. Default 0 (off).
//! - **Vehicle** (\[C\] eq 8, Table 1): the four wheel vertical loads from the
//!   body accelerations (a_x, a_y, a_z). a_x, a_y are the change of the true
//!   velocity between consecutive steps, in the body frame (what an IMU on
//!   the body measures, so turning adds its centripetal part).
//!
//! Sign of a_z: \[C\] eq 1 writes the force balance as ΣF_z = m(g − a_z), so
//! a positive a_z *lightens* the wheels; we keep the paper's convention.
//!
//! The robot's reported velocities (`RobotState::v, vy, w`) stay the wheel
//! (commanded) velocities: that is what the motor controllers hold and what
//! a ROS DWA centres its dynamic window on (wheel odometry). Only the pose
//! moves by the true increment, and the wheel loads use the true
//! accelerations (an IMU's).

use serde::{Deserialize, Serialize};

use super::robot::{integrate, Command, RobotState};
use super::{check_min, check_positive, OdometrySample, WorldError};
use crate::num::{cos, exp, sin, Rng};

/// Standard gravity used by the vehicle model, m/s².
pub const GRAVITY: f64 = 9.81;

/// Road surface: how much the body shakes vertically.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum Road {
    /// No vertical acceleration.
    #[default]
    Flat,
    /// Small vibration (\[C\]: asphalt parking lot).
    Asphalt,
    /// Large, fast bumps (\[C\]: hollow-brick paving).
    HollowBrick,
}

impl Road {
    /// (σ of a_z at the reference speed m/s², reference speed m/s,
    /// correlation length m) of the preset; see the module doc.
    pub fn preset(self) -> (f64, f64, f64) {
        match self {
            Road::Flat => (0.0, 1.0, 0.1),
            Road::Asphalt => (0.35, 0.4, 0.10),
            Road::HollowBrick => (1.3, 0.3, 0.08),
        }
    }
}

/// Wheel slip: true increment = K_true·u + noise (\[C\] eq 15–17).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SlipSpec {
    /// K_true, row-major: true (Δx, Δy, Δθ) = K_true · commanded
    /// (Δx, Δy, Δθ), body frame, 1. Identity = no systematic slip.
    pub k_true: [[f64; 3]; 3],
    /// Standard deviation of the noise on Δx and on Δy, as a share of the
    /// step's commanded translation, 1.
    pub noise_xy: f64,
    /// Standard deviation of the noise on Δθ as a share of the commanded
    /// |Δθ|, 1.
    pub noise_theta: f64,
    /// Extra standard deviation of the noise on Δθ per metre translated,
    /// rad/m.
    pub noise_theta_per_m: f64,
}

impl Default for SlipSpec {
    fn default() -> Self {
        Self {
            k_true: IDENTITY,
            noise_xy: 0.0,
            noise_theta: 0.0,
            noise_theta_per_m: 0.0,
        }
    }
}

/// The 3×3 identity.
pub const IDENTITY: [[f64; 3]; 3] = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

impl SlipSpec {
    /// Whether this models any slip (K_true ≠ identity or some noise).
    pub fn is_on(&self) -> bool {
        self.k_true != IDENTITY
            || self.noise_xy != 0.0
            || self.noise_theta != 0.0
            || self.noise_theta_per_m != 0.0
    }

    fn validate(&self) -> Result<(), WorldError> {
        for (i, row) in self.k_true.iter().enumerate() {
            for (j, &k) in row.iter().enumerate() {
                if !k.is_finite() {
                    return Err(WorldError::InvalidParameter(format!(
                        "terrain.slip.k_true[{i}][{j}] = {k}: must be a finite number"
                    )));
                }
            }
        }
        check_min("terrain.slip.noise_xy (1)", self.noise_xy, 0.0)?;
        check_min("terrain.slip.noise_theta (1)", self.noise_theta, 0.0)?;
        check_min(
            "terrain.slip.noise_theta_per_m (rad/m)",
            self.noise_theta_per_m,
            0.0,
        )
    }
}

crate::params::params! {
    /// Vehicle parameters for the wheel loads (\[C\] Table 1 defaults).
    #[derive(Debug, Clone, Copy, PartialEq)]
    pub struct VehicleSpec {
        pub mass: f64 = 20.0, "kg" [> 0.0] label "vehicle mass m" "vehicle mass m";
        /// l_f.
        pub l_f: f64 = 0.25, "m" [>= 0.0] label "centre of gravity to front axle l_f" "centre of gravity to front axle";
        /// l_r.
        pub l_r: f64 = 0.25, "m" [>= 0.0] label "centre of gravity to rear axle l_r" "centre of gravity to rear axle";
        /// b_f, the distance between the front wheels.
        pub b_f: f64 = 0.5, "m" [> 0.0] label "front track b_f" "front track";
        /// b_r.
        pub b_r: f64 = 0.5, "m" [> 0.0] label "rear track b_r" "rear track";
        /// h.
        pub h: f64 = 0.2, "m" [>= 0.0] label "centre-of-gravity height h" "height of the centre of gravity";
    }
}

impl VehicleSpec {
    /// Checks every number; `prefix` names the section in errors
    /// (`terrain.vehicle`, `cleaning-dwa.vehicle` …).
    pub fn validate(&self, prefix: &str) -> Result<(), WorldError> {
        crate::params::Params::check_bounds(self, prefix)?;
        check_positive(&format!("{prefix}.l_f + l_r (m)"), self.l_f + self.l_r)
    }

    /// Static load of each wheel (front-left, front-right, rear-left,
    /// rear-right) at rest on flat ground, N.
    pub fn static_loads(&self) -> [f64; 4] {
        self.wheel_loads(0.0, 0.0, 0.0)
    }

    /// Vertical wheel loads (FL, FR, RL, RR), N, for body accelerations
    /// a_x (forward), a_y (left), a_z (the paper's sign: positive lightens),
    /// m/s² — \[C\] eq 8:
    ///
    /// F_fl = m/(l_f+l_r)·[½(g−a_z)l_r − ½a_x h − (l_r/b_f) a_y h], F_fr the
    /// same with +a_y, F_rl = m/(l_f+l_r)·[½(g−a_z)l_f + ½a_x h −
    /// (l_f/b_r) a_y h], F_rr with +a_y.
    pub fn wheel_loads(&self, a_x: f64, a_y: f64, a_z: f64) -> [f64; 4] {
        let k = self.mass / (self.l_f + self.l_r);
        let gz = GRAVITY - a_z;
        let front = 0.5 * gz * self.l_r - 0.5 * a_x * self.h;
        let rear = 0.5 * gz * self.l_f + 0.5 * a_x * self.h;
        let lat_f = self.l_r / self.b_f * a_y * self.h;
        let lat_r = self.l_f / self.b_r * a_y * self.h;
        [
            k * (front - lat_f),
            k * (front + lat_f),
            k * (rear - lat_r),
            k * (rear + lat_r),
        ]
    }
}

/// Terrain and vehicle-dynamics settings of a scenario.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
#[serde(default, deny_unknown_fields)]
pub struct TerrainSpec {
    /// Road surface preset (`flat`, `asphalt`, `hollow-brick`).
    pub road: Road,
    /// Overrides the preset's standard deviation of a_z at the reference
    /// speed, m/s².
    pub accel_z_std: Option<f64>,
    /// Overrides the preset's reference speed of the a_z amplitude, m/s.
    pub accel_z_ref_speed: Option<f64>,
    /// Overrides the preset's correlation length of the a_z process, m.
    pub accel_z_corr_length: Option<f64>,
    /// Wheel slip (default: none).
    pub slip: SlipSpec,
    /// Speed a bump takes away: a step with a_z > 0 loses
    /// `bump_drag`·a_z·dt of translational speed (wheels and body), 1.
    pub bump_drag: f64,
    /// Vehicle model for the wheel loads (default: none, no loads).
    pub vehicle: Option<VehicleSpec>,
}

impl TerrainSpec {
    /// (σ m/s², reference speed m/s, correlation length m) of the road
    /// process after overrides.
    pub fn road_params(&self) -> (f64, f64, f64) {
        let (s, v, l) = self.road.preset();
        (
            self.accel_z_std.unwrap_or(s),
            self.accel_z_ref_speed.unwrap_or(v),
            self.accel_z_corr_length.unwrap_or(l),
        )
    }

    /// Checks every number; the error names the field (`terrain.…`).
    pub fn validate(&self) -> Result<(), WorldError> {
        if let Some(s) = self.accel_z_std {
            check_min("terrain.accel_z_std (m/s²)", s, 0.0)?;
        }
        if let Some(v) = self.accel_z_ref_speed {
            check_positive("terrain.accel_z_ref_speed (m/s)", v)?;
        }
        if let Some(l) = self.accel_z_corr_length {
            check_positive("terrain.accel_z_corr_length (m)", l)?;
        }
        self.slip.validate()?;
        check_min("terrain.bump_drag (1)", self.bump_drag, 0.0)?;
        if let Some(v) = &self.vehicle {
            v.validate("terrain.vehicle")?;
        }
        Ok(())
    }
}

/// What the terrain did in one step.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct TerrainStep {
    /// The robot's true state after the step.
    pub next: RobotState,
    /// Wheel vs laser odometry of the step, when slip is modelled.
    pub odometry: Option<OdometrySample>,
    /// Vertical acceleration of the body during the step, m/s².
    pub accel_z: f64,
    /// Vertical load on each wheel (front-left, front-right, rear-left,
    /// rear-right), newtons, when a vehicle model is given.
    pub wheel_loads: Option<[f64; 4]>,
}

/// The terrain of one episode, with its own seeded noise stream.
#[derive(Debug, Clone)]
pub struct Terrain {
    spec: TerrainSpec,
    /// (σ, v_ref, corr_length) of the road process.
    road: (f64, f64, f64),
    slip_on: bool,
    /// Noise of the slip increments.
    slip_rng: Rng,
    /// Noise driving the road process.
    road_rng: Rng,
    /// The unit-variance road state z.
    z: f64,
    /// True world-frame velocity of the previous step, m/s (`None` before
    /// the first step: the start state's velocity is used).
    prev_vel: Option<[f64; 2]>,
}

impl Terrain {
    /// Builds the terrain; `seed` drives its noise. Invalid numbers give
    /// [`WorldError::InvalidParameter`] naming the field.
    pub fn new(spec: TerrainSpec, seed: u64) -> Result<Self, WorldError> {
        spec.validate()?;
        let mut root = Rng::new(seed ^ 0x7E88_A1C0_0DE5_EED5);
        let slip_rng = root.fork(1);
        let mut road_rng = root.fork(2);
        // Start the road process in its stationary distribution.
        let z = road_rng.normal();
        Ok(Self {
            road: spec.road_params(),
            slip_on: spec.slip.is_on(),
            spec,
            slip_rng,
            road_rng,
            z,
            prev_vel: None,
        })
    }

    /// The settings.
    pub fn spec(&self) -> &TerrainSpec {
        &self.spec
    }

    /// Applies `cmd` (already limited to what the motors can do) for `dt`.
    pub fn step(&mut self, state: &RobotState, cmd: Command, dt: f64) -> TerrainStep {
        let dt_ok = dt > 0.0;
        let u = [cmd.v * dt, cmd.vy * dt, cmd.w * dt];
        let mut truth = if self.slip_on && dt_ok {
            self.slipped(u)
        } else {
            u
        };
        // Road: a_z over this step at the speed actually driven.
        let trans = (truth[0] * truth[0] + truth[1] * truth[1]).sqrt();
        let speed = if dt_ok { trans / dt } else { 0.0 };
        let accel_z = self.road_step(speed, dt);
        // Bumps sap speed: the wheels slow with the body.
        let mut keep = 1.0;
        let drag = self.spec.bump_drag;
        if drag > 0.0 && accel_z > 0.0 && speed > 0.0 {
            keep = (1.0 - drag * accel_z * dt / speed).max(0.0);
            truth[0] *= keep;
            truth[1] *= keep;
        }
        let modelled = self.slip_on || drag > 0.0;
        let (next, odometry) = if modelled && dt_ok {
            let moved = integrate(
                state,
                Command {
                    v: truth[0] / dt,
                    vy: truth[1] / dt,
                    w: truth[2] / dt,
                },
                dt,
            );
            // The velocities stay the wheel ones (what the motors hold,
            // after a bump slowed them): ROS's DWA centres its window on
            // wheel odometry.
            let next = RobotState {
                v: cmd.v * keep,
                vy: cmd.vy * keep,
                w: cmd.w,
                ..moved
            };
            (
                next,
                Some(OdometrySample {
                    wheel: u,
                    laser: truth,
                }),
            )
        } else {
            (integrate(state, cmd, dt), None)
        };
        // True world-frame velocity of this step (Euler: the step moves
        // along the heading it started with).
        let (s0, c0) = (sin(state.theta), cos(state.theta));
        let vel = if dt_ok {
            [(next.x - state.x) / dt, (next.y - state.y) / dt]
        } else {
            [0.0, 0.0]
        };
        let prev = self
            .prev_vel
            .unwrap_or([state.v * c0 - state.vy * s0, state.v * s0 + state.vy * c0]);
        self.prev_vel = Some(vel);
        let wheel_loads = self.spec.vehicle.map(|veh| {
            let (a_x, a_y) = if dt_ok {
                let (ax_w, ay_w) = ((vel[0] - prev[0]) / dt, (vel[1] - prev[1]) / dt);
                // Into the body frame at the step's start heading.
                (c0 * ax_w + s0 * ay_w, -s0 * ax_w + c0 * ay_w)
            } else {
                (0.0, 0.0)
            };
            veh.wheel_loads(a_x, a_y, accel_z)
        });
        TerrainStep {
            next,
            odometry,
            accel_z,
            wheel_loads,
        }
    }

    /// True body increment K_true·u + noise.
    fn slipped(&mut self, u: [f64; 3]) -> [f64; 3] {
        let k = &self.spec.slip.k_true;
        let s = &self.spec.slip;
        let trans = (u[0] * u[0] + u[1] * u[1]).sqrt();
        let sd_xy = s.noise_xy * trans;
        let sd_th = s.noise_theta * u[2].abs() + s.noise_theta_per_m * trans;
        // Always draw three numbers so the stream does not depend on
        // which axes are quiet.
        let n = [
            self.slip_rng.normal(),
            self.slip_rng.normal(),
            self.slip_rng.normal(),
        ];
        let mut out = [0.0; 3];
        for (i, o) in out.iter_mut().enumerate() {
            *o = k[i][0] * u[0] + k[i][1] * u[1] + k[i][2] * u[2];
        }
        out[0] += sd_xy * n[0];
        out[1] += sd_xy * n[1];
        out[2] += sd_th * n[2];
        out
    }

    /// Advances the road process over a step driven at `speed` and returns
    /// a_z.
    fn road_step(&mut self, speed: f64, dt: f64) -> f64 {
        let (sigma, v_ref, corr) = self.road;
        if sigma == 0.0 {
            return 0.0;
        }
        let ds = speed * dt.max(0.0);
        let rho = exp(-ds / corr);
        let n = self.road_rng.normal();
        self.z = rho * self.z + (1.0 - rho * rho).max(0.0).sqrt() * n;
        sigma * (speed / v_ref) * self.z
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cmd(v: f64, vy: f64, w: f64) -> Command {
        Command { v, vy, w }
    }

    #[test]
    fn flat_no_slip_is_exact_integration() {
        let mut t = Terrain::new(TerrainSpec::default(), 3).unwrap();
        let s = RobotState {
            x: 1.0,
            y: 2.0,
            theta: 0.3,
            ..Default::default()
        };
        let c = cmd(0.5, 0.1, 0.2);
        let r = t.step(&s, c, 0.1);
        assert_eq!(r.next, integrate(&s, c, 0.1));
        assert_eq!(r.odometry, None);
        assert_eq!(r.accel_z, 0.0);
        assert_eq!(r.wheel_loads, None);
    }

    #[test]
    fn static_loads_are_a_quarter_of_the_weight() {
        let v = VehicleSpec::default();
        for f in v.static_loads() {
            assert!((f - 20.0 * GRAVITY / 4.0).abs() < 1e-12, "{f}");
        }
        // Sum of loads is always m(g − a_z) (eq 1).
        let l = v.wheel_loads(1.3, -0.7, 0.4);
        assert!((l.iter().sum::<f64>() - 20.0 * (GRAVITY - 0.4)).abs() < 1e-9);
    }

    #[test]
    fn known_accelerations_give_known_loads() {
        let v = VehicleSpec::default();
        // Table 1 vehicle: F = 40·[0.125(g − a_z) ∓ 0.1 a_x ∓ 0.1 a_y].
        let [fl, fr, rl, rr] = v.wheel_loads(2.0, 0.0, 0.0);
        assert!((fl - (5.0 * GRAVITY - 8.0)).abs() < 1e-9);
        assert!((fr - fl).abs() < 1e-12);
        assert!((rl - (5.0 * GRAVITY + 8.0)).abs() < 1e-9);
        assert!((rr - rl).abs() < 1e-12);
        // Left acceleration (turning left) unloads the left wheels.
        let [fl, fr, rl, rr] = v.wheel_loads(0.0, 1.0, 0.0);
        assert!((fl - (5.0 * GRAVITY - 4.0)).abs() < 1e-9);
        assert!((fr - (5.0 * GRAVITY + 4.0)).abs() < 1e-9);
        assert!((rl - fl).abs() < 1e-12 && (rr - fr).abs() < 1e-12);
        // a_z (paper's sign) lightens every wheel by m·a_z/4.
        let l = v.wheel_loads(0.0, 0.0, 2.0);
        assert!(l.iter().all(|f| (f - 5.0 * (GRAVITY - 2.0)).abs() < 1e-9));
        // Eq 14: at |a_x| = (g − 4jg − a_z)·l_r/h the front wheels carry
        // exactly j·m·g.
        let (j, az) = (0.2, 0.5);
        let ax = (GRAVITY - 4.0 * j * GRAVITY - az) * 0.25 / 0.2;
        let l = v.wheel_loads(ax, 0.0, az);
        assert!((l[0] - j * 20.0 * GRAVITY).abs() < 1e-9, "{l:?}");
    }

    #[test]
    fn loads_follow_the_true_acceleration() {
        let spec = TerrainSpec {
            vehicle: Some(VehicleSpec::default()),
            ..Default::default()
        };
        let mut t = Terrain::new(spec, 1).unwrap();
        let s0 = RobotState::default();
        // From rest to 0.2 m/s forward in 0.1 s: a_x = 2 m/s².
        let r = t.step(&s0, cmd(0.2, 0.0, 0.0), 0.1);
        let l = r.wheel_loads.unwrap();
        assert!((l[0] - (5.0 * GRAVITY - 8.0)).abs() < 1e-9, "{l:?}");
        // Cruising: static loads again.
        let r2 = t.step(&r.next, cmd(0.2, 0.0, 0.0), 0.1);
        let l = r2.wheel_loads.unwrap();
        assert!((l[0] - 5.0 * GRAVITY).abs() < 1e-9, "{l:?}");
        // Heading 90°, starting to move sideways to the left in the body
        // frame (−x in the world): a body a_y of +1 m/s².
        let mut t = Terrain::new(
            TerrainSpec {
                vehicle: Some(VehicleSpec::default()),
                ..Default::default()
            },
            1,
        )
        .unwrap();
        let s = RobotState {
            theta: std::f64::consts::FRAC_PI_2,
            ..Default::default()
        };
        let l = t.step(&s, cmd(0.0, 0.1, 0.0), 0.1).wheel_loads.unwrap();
        assert!((l[0] - (5.0 * GRAVITY - 4.0)).abs() < 1e-9, "{l:?}");
        assert!((l[1] - (5.0 * GRAVITY + 4.0)).abs() < 1e-9, "{l:?}");
    }

    #[test]
    fn slip_reports_odometry_and_moves_by_k_true() {
        let k = [[0.9, 0.0, 0.0], [0.05, 1.0, 0.0], [0.0, 0.0, 0.8]];
        let spec = TerrainSpec {
            slip: SlipSpec {
                k_true: k,
                ..Default::default()
            },
            ..Default::default()
        };
        let mut t = Terrain::new(spec, 5).unwrap();
        let s = RobotState::default();
        let r = t.step(&s, cmd(1.0, 0.0, 1.0), 0.1);
        let o = r.odometry.unwrap();
        assert_eq!(o.wheel, [0.1, 0.0, 0.1]);
        let want = [0.09, 0.005, 0.08];
        for (got, want) in o.laser.iter().zip(want) {
            assert!((got - want).abs() < 1e-12, "{o:?}");
        }
        assert!((r.next.x - 0.09).abs() < 1e-12 && (r.next.y - 0.005).abs() < 1e-12);
        assert!((r.next.theta - 0.08).abs() < 1e-12);
        // The state keeps the wheel velocities.
        assert_eq!((r.next.v, r.next.vy, r.next.w), (1.0, 0.0, 1.0));
    }

    #[test]
    fn bumps_sap_speed_in_motion_and_wheels() {
        let spec = TerrainSpec {
            road: Road::HollowBrick,
            bump_drag: 1.0,
            ..Default::default()
        };
        let mut t = Terrain::new(spec, 3).unwrap();
        let mut s = RobotState::default();
        let (mut lost, mut bumps) = (0.0, 0);
        for _ in 0..200 {
            let c = cmd(0.3, 0.0, 0.0);
            let r = t.step(&s, c, 0.1);
            let o = r.odometry.expect("bump drag reports odometry");
            let want = if r.accel_z > 0.0 {
                bumps += 1;
                (0.3 - r.accel_z * 0.1).max(0.0)
            } else {
                0.3
            };
            assert!((r.next.v - want).abs() < 1e-12, "{} vs {want}", r.next.v);
            assert!((o.laser[0] - want * 0.1).abs() < 1e-12);
            lost += 0.3 - r.next.v;
            s = r.next;
        }
        assert!(bumps > 50 && lost > 1.0, "{bumps} {lost}");
    }

    #[test]
    fn noise_is_seeded_and_deterministic() {
        let spec = TerrainSpec {
            road: Road::HollowBrick,
            slip: SlipSpec {
                noise_xy: 0.05,
                noise_theta: 0.05,
                noise_theta_per_m: 0.02,
                ..Default::default()
            },
            vehicle: Some(VehicleSpec::default()),
            ..Default::default()
        };
        let run = |seed| {
            let mut t = Terrain::new(spec.clone(), seed).unwrap();
            let mut s = RobotState::default();
            let mut out = Vec::new();
            for _ in 0..50 {
                let r = t.step(&s, cmd(0.3, 0.05, 0.1), 0.1);
                s = r.next;
                out.push((s.x, s.y, s.theta, r.accel_z, r.wheel_loads));
            }
            out
        };
        assert_eq!(run(7), run(7));
        assert_ne!(run(7), run(8));
        // Parked on hollow brick: no bumps.
        let mut t = Terrain::new(spec.clone(), 1).unwrap();
        let r = t.step(&RobotState::default(), Command::default(), 0.1);
        assert_eq!(r.accel_z, 0.0);
    }

    #[test]
    fn road_amplitudes_follow_the_presets() {
        let stats = |road: Road, v: f64| {
            let spec = TerrainSpec {
                road,
                ..Default::default()
            };
            let mut t = Terrain::new(spec, 11).unwrap();
            let mut s = RobotState::default();
            let n = 20_000;
            let mut sum2 = 0.0;
            for _ in 0..n {
                let r = t.step(&s, cmd(v, 0.0, 0.0), 0.1);
                s = r.next;
                sum2 += r.accel_z * r.accel_z;
            }
            (sum2 / n as f64).sqrt()
        };
        assert_eq!(stats(Road::Flat, 0.3), 0.0);
        let a = stats(Road::Asphalt, 0.4);
        let b = stats(Road::HollowBrick, 0.3);
        assert!((a - 0.35).abs() < 0.05, "asphalt rms {a}");
        assert!((b - 1.3).abs() < 0.1, "brick rms {b}");
        // Amplitude grows with speed.
        assert!(stats(Road::HollowBrick, 0.15) < 0.7 * b);
    }

    #[test]
    fn bad_numbers_name_the_field() {
        let bad = |spec: TerrainSpec, want: &str| {
            let e = Terrain::new(spec, 0).unwrap_err().to_string();
            assert!(e.contains(want), "{e} / {want}");
        };
        bad(
            TerrainSpec {
                accel_z_std: Some(f64::NAN),
                ..Default::default()
            },
            "terrain.accel_z_std",
        );
        bad(
            TerrainSpec {
                accel_z_corr_length: Some(0.0),
                ..Default::default()
            },
            "terrain.accel_z_corr_length",
        );
        let mut slip = SlipSpec::default();
        slip.k_true[1][2] = f64::INFINITY;
        bad(
            TerrainSpec {
                slip,
                ..Default::default()
            },
            "terrain.slip.k_true[1][2]",
        );
        bad(
            TerrainSpec {
                slip: SlipSpec {
                    noise_xy: -0.1,
                    ..Default::default()
                },
                ..Default::default()
            },
            "terrain.slip.noise_xy",
        );
        bad(
            TerrainSpec {
                bump_drag: f64::NAN,
                ..Default::default()
            },
            "terrain.bump_drag",
        );
        bad(
            TerrainSpec {
                vehicle: Some(VehicleSpec {
                    mass: -20.0,
                    ..Default::default()
                }),
                ..Default::default()
            },
            "terrain.vehicle.mass",
        );
        bad(
            TerrainSpec {
                vehicle: Some(VehicleSpec {
                    h: f64::NAN,
                    ..Default::default()
                }),
                ..Default::default()
            },
            "terrain.vehicle.h",
        );
        let e: Result<TerrainSpec, _> = serde_json::from_str(r#"{"road": "gravel"}"#);
        assert!(e.is_err());
        let t: TerrainSpec =
            serde_json::from_str(r#"{"road": "hollow-brick", "vehicle": {}}"#).unwrap();
        assert_eq!(t.road, Road::HollowBrick);
        assert_eq!(t.vehicle, Some(VehicleSpec::default()));
    }
}
