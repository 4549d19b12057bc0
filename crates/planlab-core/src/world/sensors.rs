//! What the simulated sensors report, as plain data: made by the world
//! (the terrain model's odometry) and read by the planners above it.

use serde::{Deserialize, Serialize};

/// One odometry sample for the last control period (\[C\] eq 15–18): the
/// body-frame increment (Δx, Δy, Δθ) the wheels report (what was commanded)
/// and the true one a laser odometry measures.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, Default)]
pub struct OdometrySample {
    /// Wheel-odometry increment (Δx, Δy, Δθ), body frame.
    pub wheel: [f64; 3],
    /// Laser-odometry (true) increment (Δx, Δy, Δθ), body frame.
    pub laser: [f64; 3],
}

/// One planar laser scan as the sensor reports it (the shape of ROS's
/// `sensor_msgs/LaserScan`): beam i points at `angle_min + i·angle_increment`
/// (rad, counter-clockwise from the robot's heading) and reads `ranges[i]`
/// metres, `f64::INFINITY` when nothing returned within `max_range`.
/// `pose` is where the sensor was (x, y, θ) when it scanned.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LaserScan {
    /// Sensor pose (x, y, θ) at the scan, world metres and rad.
    pub pose: [f64; 3],
    /// Angle of beam 0 in the robot frame, rad.
    pub angle_min: f64,
    /// Angle between neighbouring beams, rad.
    pub angle_increment: f64,
    /// Range of each beam, m (`INFINITY` = no return).
    pub ranges: Vec<f64>,
    /// Range limit, m.
    pub max_range: f64,
}

impl LaserScan {
    /// Angle of beam i in the robot frame, rad.
    pub fn angle(&self, i: usize) -> f64 {
        self.angle_min + i as f64 * self.angle_increment
    }

    /// The reading nearest to robot-frame angle `a` (rad, any turn), or
    /// `None` when `a` lies outside the field of view (more than half a
    /// beam beyond the first or last beam).
    pub fn at_angle(&self, a: f64) -> Option<f64> {
        let n = self.ranges.len();
        // NaN increments fail `>` too.
        let ok = self.angle_increment > 0.0;
        if n == 0 || !ok || !a.is_finite() {
            return None;
        }
        let tau = std::f64::consts::TAU;
        // The turn of `a` that is at or after angle_min.
        let rel = (a - self.angle_min).rem_euclid(tau);
        let k = (rel / self.angle_increment).round();
        if k < n as f64 {
            return self.ranges.get(k as usize).copied();
        }
        // Just before the first beam (within half a beam).
        if tau - rel <= 0.5 * self.angle_increment {
            return self.ranges.first().copied();
        }
        None
    }
}
