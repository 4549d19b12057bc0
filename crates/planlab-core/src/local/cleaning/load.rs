//! The peak-held a_z of \[C\] §3.2's vertical-load limit (eq 14's bound
//! and eq 8's wheel loads are the window's: `step::LoadWindow`).

use super::CleaningDwa;

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
}
