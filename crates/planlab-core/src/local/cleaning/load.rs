//! The vertical-load acceleration limit of \[C\] §3.2 (eq 8 and 14): the
//! peak-held a_z, eq 14's bound on the acceleration window and eq 8's
//! smallest wheel load of a sample.

use super::CleaningDwa;
use crate::local::Observation;
use crate::world::terrain::GRAVITY;

impl CleaningDwa {
    /// Takes this period's measured a_z (non-finite: 0) into the peak-hold
    /// over the last `accel_z_hold` periods that the load limit uses.
    pub(super) fn hold_accel_z(&mut self, accel_z: f64) {
        let az = if accel_z.is_finite() { accel_z } else { 0.0 };
        self.az_recent.push_back(az);
        while self.az_recent.len() > self.cfg.accel_z_hold {
            self.az_recent.pop_front();
        }
        self.az_estimate = self
            .az_recent
            .iter()
            .copied()
            .fold(f64::NEG_INFINITY, f64::max);
    }

    /// Eq 14's bound on |a_x|, |a_y| (None: no load limit).
    pub(super) fn load_bound(&self) -> Option<f64> {
        self.cfg.load_limit.then(|| {
            let j = self.cfg.load_fraction;
            let veh = &self.cfg.vehicle;
            let az = self.az_estimate;
            let b = if veh.h > 0.0 {
                (GRAVITY - 4.0 * j * GRAVITY - az) * veh.l_r / veh.h
            } else {
                f64::INFINITY
            };
            b.max(0.0)
        })
    }

    /// Smallest wheel load minus j·m·g (N) after accelerating to (vx, vy)
    /// in one period (\[C\] eq 8 with the measured a_z); ≥ 0 is allowed.
    /// Keeping the velocity is always allowed (+∞).
    pub(super) fn load_margin(&self, obs: &Observation<'_>, vx: f64, vy: f64) -> f64 {
        let s = obs.state;
        if (vx == s.v && vy == s.vy) || obs.dt <= 0.0 {
            return f64::INFINITY;
        }
        let az = self.az_estimate;
        let veh = &self.cfg.vehicle;
        let min = self.cfg.load_fraction * veh.mass * GRAVITY;
        let loads = veh.wheel_loads((vx - s.v) / obs.dt, (vy - s.vy) / obs.dt, az);
        loads.iter().fold(f64::INFINITY, |a, &f| a.min(f)) - min
    }
}
