//! Episode metrics (docs/algorithms.md §metrics): time, path length, clearance, turning,
//! speed drops, tracking error, wheel-load share — the quantities the
//! papers' tables compare, computed from a [`Trace`] the same way for every
//! planner.
//!
//! Definitions (chosen so they do not depend on the time step):
//! - **path length**: sum of the distances between consecutive trace
//!   positions.
//! - **clearance**: the trace's exact footprint clearance (capped at
//!   [`crate::sim::CLEARANCE_CAP`]), minimum and mean over all rows.
//! - **turning**: the driven path is resampled every
//!   [`TURN_RESAMPLE_M`] of arc length; the turning angle at each interior
//!   resampled point is |Δ heading| between the chords before and after it.
//!   Total = sum, max = largest. Turning on the spot adds nothing (the path
//!   does not move), so this is the path's geometric turning (\[L\] Table 2).
//! - **per-step turning** (\[L\] Table 2's "最大转折角度", maximum turning
//!   angle, read as the paper's path is sampled): the largest |Δ heading|
//!   between consecutive chords of the trace as recorded, one position per
//!   control period; steps that do not move are skipped, so a turn on the
//!   spot shows at the next chord. Unlike the resampled max it depends on
//!   the time step and the speed (at most ω_max·dt on a smooth drive).
//! - **speed drops**: with speed s = √(v² + v_y²) and peak P over the
//!   episode, a drop is a fall of more than [`SPEED_DROP_FRACTION`]·P below
//!   the running local maximum that is followed by a rise of the same amount
//!   above the following local minimum. A fall never followed by a rise (the
//!   final stop at the goal, or stopping for good) is not counted (\[S\]
//!   Fig 11 counts slow-downs on the way).
//! - **tracking error**: distance from every trace position to the global
//!   path polyline; mean, max and (population) variance. `None` without a
//!   global path (\[C\] Tables 3–4).
//! - **temporary-goal switches** (\[L\]): rows at which the steered-to
//!   goal changes between the final goal and a temporary one, or a
//!   temporary goal moves by more than [`TEMP_GOAL_JUMP_M`] from the
//!   previous row's (a new temporary goal, not the same one sliding along
//!   an obstacle as more of it comes into view).
//! - **load share**: share of the rows carrying wheel loads in which every
//!   wheel load exceeds the threshold (40 N in \[C\] Table 5); `None` without
//!   a vehicle model.

use serde::{Deserialize, Serialize};

/// Tracking error is the distance to the global path polyline; re-exported
/// here because callers that report it look for it with the metrics.
pub use crate::geom::distance_to_polyline;
use crate::num::{atan2, hypot, wrap_angle};
use crate::sim::{Collision, Episode, Outcome, Trace};

/// Arc-length step of the resampling used for turning angles, m.
pub const TURN_RESAMPLE_M: f64 = 0.1;

/// A temporary goal that moves farther than this between two rows is a
/// new one (a switch), m.
pub const TEMP_GOAL_JUMP_M: f64 = 1.0;

/// A speed drop is a fall by more than this share of the episode's peak
/// speed (then a rise by as much).
pub const SPEED_DROP_FRACTION: f64 = 0.3;

/// The wheel-load threshold of \[C\] Table 5, N.
pub const DEFAULT_LOAD_THRESHOLD_N: f64 = 40.0;

/// What one episode measured. Field names are those of `planlab run --json`
/// and `planlab reproduce --json`; `None` (JSON `null`) where a metric does
/// not apply.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EpisodeMetrics {
    /// How the episode ended.
    pub outcome: Outcome,
    /// Episode duration, s.
    pub time_s: f64,
    /// Driven path length, m.
    pub path_length_m: f64,
    /// Smallest clearance, m.
    pub min_clearance_m: f64,
    /// Mean clearance over the rows, m.
    pub mean_clearance_m: f64,
    /// Total turning of the resampled path, rad.
    pub total_turn_rad: f64,
    /// Largest turning angle at one resampled point, rad.
    pub max_turn_rad: f64,
    /// Largest heading change between two consecutive moving steps of the
    /// trace (one point per control period), rad (\[L\] Table 2's maximum
    /// turning angle as its trajectories are sampled).
    pub max_turn_step_rad: f64,
    /// Number of speed drops on the way.
    pub speed_drops: u32,
    /// Mean distance to the global path, m.
    pub mean_tracking_error_m: Option<f64>,
    /// Largest distance to the global path, m.
    pub max_tracking_error_m: Option<f64>,
    /// Variance of the distance to the global path, m².
    pub tracking_error_var_m2: Option<f64>,
    /// Share (0–1) of rows with every wheel load above the threshold.
    pub load_ok_share: Option<f64>,
    /// Mean over the four wheels of each wheel's share (0–1) of rows with
    /// its load above the threshold: what \[C\] Table 5 reports ("the
    /// share of time each wheel's vertical load exceeds 40 N", averaged).
    pub wheel_load_share: Option<f64>,
    /// Temporary-goal switches (\[L\]; 0 for planners without them).
    pub temp_goal_switches: u32,
    /// What a collision was with and whether the robot was at rest (a
    /// mover hitting a standing robot); absent for other outcomes and for
    /// metrics computed from a trace alone.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub collision: Option<Collision>,
}

impl EpisodeMetrics {
    /// The metrics of episode `ep` so far (run it to its end first): its
    /// trace and outcome, tracking error against its planner's global path,
    /// wheel loads against [`DEFAULT_LOAD_THRESHOLD_N`]. What `planlab run`,
    /// `planlab batch` and `planlab reproduce` report.
    pub fn of_episode(ep: &Episode) -> EpisodeMetrics {
        EpisodeMetrics {
            collision: ep.collision(),
            ..EpisodeMetrics::from_trace(
                ep.trace(),
                &ep.planner_debug().global_path,
                ep.outcome(),
                DEFAULT_LOAD_THRESHOLD_N,
            )
        }
    }

    /// Computes every metric of `trace` (see the module doc for the
    /// definitions). `global_path` may be empty (no tracking error);
    /// `load_threshold_n` is the wheel-load threshold, N.
    pub fn from_trace(
        trace: &Trace,
        global_path: &[[f64; 2]],
        outcome: Outcome,
        load_threshold_n: f64,
    ) -> EpisodeMetrics {
        let rows = &trace.steps;
        let pts = trace.positions();
        let n = rows.len().max(1) as f64;
        let path_length_m = pts
            .windows(2)
            .map(|w| hypot(w[1][0] - w[0][0], w[1][1] - w[0][1]))
            .sum();
        let min_clearance_m = rows
            .iter()
            .map(|r| r.clearance)
            .fold(f64::INFINITY, f64::min);
        let mean_clearance_m = rows.iter().map(|r| r.clearance).sum::<f64>() / n;
        let (total_turn_rad, max_turn_rad) = turning(&pts, TURN_RESAMPLE_M);
        let max_turn_step_rad = max_step_turn(&pts);
        let speeds: Vec<f64> = rows.iter().map(|r| hypot(r.v, r.vy)).collect();
        let tracking = tracking_errors(&pts, global_path);
        let loads: Vec<bool> = rows
            .iter()
            .filter_map(|r| r.wheel_loads)
            .map(|l| l.iter().all(|&f| f > load_threshold_n))
            .collect();
        let wheel_rows: Vec<[f64; 4]> = rows.iter().filter_map(|r| r.wheel_loads).collect();
        let wheel_load_share = (!wheel_rows.is_empty()).then(|| {
            let above: usize = wheel_rows
                .iter()
                .map(|l| l.iter().filter(|&&f| f > load_threshold_n).count())
                .sum();
            above as f64 / (4 * wheel_rows.len()) as f64
        });
        EpisodeMetrics {
            outcome,
            time_s: rows.last().map_or(0.0, |r| r.t),
            path_length_m,
            min_clearance_m: if min_clearance_m.is_finite() {
                min_clearance_m
            } else {
                0.0
            },
            mean_clearance_m,
            total_turn_rad,
            max_turn_rad,
            max_turn_step_rad,
            speed_drops: speed_drops(&speeds, SPEED_DROP_FRACTION),
            mean_tracking_error_m: tracking.map(|t| t.0),
            max_tracking_error_m: tracking.map(|t| t.1),
            tracking_error_var_m2: tracking.map(|t| t.2),
            load_ok_share: if loads.is_empty() {
                None
            } else {
                Some(loads.iter().filter(|&&ok| ok).count() as f64 / loads.len() as f64)
            },
            wheel_load_share,
            temp_goal_switches: temp_goal_switches(trace),
            collision: None,
        }
    }

    /// The metrics as CSV: a `name,value,unit` header, then one row per
    /// metric in the order of `planlab run`'s table, named by the JSON
    /// field, values in full precision (an empty value where a metric does
    /// not apply; the outcome as its name). What the page's "Metrics CSV"
    /// saves.
    pub fn to_csv(&self) -> String {
        let num = |x: f64| format!("{x}");
        let opt = |x: Option<f64>| x.map_or_else(String::new, num);
        let rows: [(&str, String, &str); 15] = [
            ("outcome", self.outcome.as_str().to_string(), ""),
            ("time_s", num(self.time_s), "s"),
            ("path_length_m", num(self.path_length_m), "m"),
            ("min_clearance_m", num(self.min_clearance_m), "m"),
            ("mean_clearance_m", num(self.mean_clearance_m), "m"),
            ("total_turn_rad", num(self.total_turn_rad), "rad"),
            ("max_turn_rad", num(self.max_turn_rad), "rad"),
            ("max_turn_step_rad", num(self.max_turn_step_rad), "rad"),
            ("speed_drops", self.speed_drops.to_string(), ""),
            (
                "temp_goal_switches",
                self.temp_goal_switches.to_string(),
                "",
            ),
            (
                "mean_tracking_error_m",
                opt(self.mean_tracking_error_m),
                "m",
            ),
            ("max_tracking_error_m", opt(self.max_tracking_error_m), "m"),
            (
                "tracking_error_var_m2",
                opt(self.tracking_error_var_m2),
                "m^2",
            ),
            ("load_ok_share", opt(self.load_ok_share), "1"),
            ("wheel_load_share", opt(self.wheel_load_share), "1"),
        ];
        let mut out = String::from("name,value,unit\n");
        for (k, v, u) in rows {
            out.push_str(&format!("{k},{v},{u}\n"));
        }
        out
    }
}

/// Number of temporary-goal switches in `trace` (see the module doc).
pub fn temp_goal_switches(trace: &Trace) -> u32 {
    use crate::local::GoalKind;
    let mut n = 0;
    for w in trace.steps.windows(2) {
        let (a, b) = (&w[0], &w[1]);
        let (ta, tb) = (
            a.goal_kind == GoalKind::Temporary,
            b.goal_kind == GoalKind::Temporary,
        );
        let jump = hypot(b.goal[0] - a.goal[0], b.goal[1] - a.goal[1]) > TEMP_GOAL_JUMP_M;
        if ta != tb || (ta && tb && jump) {
            n += 1;
        }
    }
    n
}

/// The most points [`resample`] returns (plus the first): a 7.6·10⁸ m
/// step (`sim.dt=1e9`) resampled every 0.1 m aborted on allocation.
pub const MAX_RESAMPLE_POINTS: usize = 1_000_000;

/// Points every `ds` of arc length along the polyline, from its start
/// (the remainder shorter than `ds` at the end is dropped); at most
/// [`MAX_RESAMPLE_POINTS`] spacings (a longer path is sampled coarser).
pub fn resample(pts: &[[f64; 2]], ds: f64) -> Vec<[f64; 2]> {
    let Some(&first) = pts.first() else {
        return Vec::new();
    };
    let mut out = vec![first];
    if ds.is_nan() || ds <= 0.0 {
        return out;
    }
    // A path longer than MAX_RESAMPLE_POINTS spacings is sampled coarser, so
    // the output (and memory) stays bounded whatever the path; normal paths
    // are far below the cap and keep `ds`.
    let total: f64 = pts
        .windows(2)
        .map(|w| hypot(w[1][0] - w[0][0], w[1][1] - w[0][1]))
        .sum();
    if !total.is_finite() {
        return out;
    }
    let ds = ds.max(total / MAX_RESAMPLE_POINTS as f64);
    // Distance still to go from the segment start to the next sample.
    let mut need = ds;
    for w in pts.windows(2) {
        let (a, b) = (w[0], w[1]);
        let len = hypot(b[0] - a[0], b[1] - a[1]);
        let mut at = 0.0;
        while len - at >= need {
            at += need;
            let f = at / len;
            out.push([a[0] + (b[0] - a[0]) * f, a[1] + (b[1] - a[1]) * f]);
            need = ds;
        }
        need -= len - at;
    }
    out
}

/// (total, max) turning angle of the path resampled every `ds`, rad.
pub fn turning(pts: &[[f64; 2]], ds: f64) -> (f64, f64) {
    let r = resample(pts, ds);
    let headings: Vec<f64> = r
        .windows(2)
        .map(|w| atan2(w[1][1] - w[0][1], w[1][0] - w[0][0]))
        .collect();
    headings
        .windows(2)
        .map(|h| wrap_angle(h[1] - h[0]).abs())
        .fold((0.0, 0.0), |(tot, mx), a| (tot + a, f64::max(mx, a)))
}

/// Largest |Δ heading| between consecutive chords of `pts` as sampled,
/// rad; chords shorter than [`STILL_M`] (the robot did not move) are
/// skipped. 0 with fewer than two moving chords.
pub fn max_step_turn(pts: &[[f64; 2]]) -> f64 {
    let mut last: Option<f64> = None;
    let mut max = 0.0;
    for w in pts.windows(2) {
        let (dx, dy) = (w[1][0] - w[0][0], w[1][1] - w[0][1]);
        let chord = hypot(dx, dy);
        // A NaN chord is skipped like a still one.
        if chord.is_nan() || chord < STILL_M {
            continue;
        }
        let h = atan2(dy, dx);
        if let Some(p) = last {
            max = f64::max(max, wrap_angle(h - p).abs());
        }
        last = Some(h);
    }
    max
}

/// A step shorter than this did not move (its heading is noise), m.
pub const STILL_M: f64 = 1e-6;

/// Number of drops of `speeds` by more than `fraction` of its peak that are
/// followed by a rise of the same amount (see the module doc).
pub fn speed_drops(speeds: &[f64], fraction: f64) -> u32 {
    let peak = speeds.iter().copied().fold(0.0, f64::max);
    let thr = fraction * peak;
    if thr.is_nan() || thr <= 0.0 {
        return 0;
    }
    let mut count = 0;
    let mut high = f64::NEG_INFINITY; // running local maximum while rising
    let mut low = f64::INFINITY; // running local minimum after a fall
    let mut fallen = false;
    for &s in speeds {
        if fallen {
            low = low.min(s);
            if s > low + thr {
                count += 1;
                fallen = false;
                high = s;
            }
        } else {
            high = high.max(s);
            if s < high - thr {
                fallen = true;
                low = s;
            }
        }
    }
    count
}

/// (mean, max, variance) of the distances from `pts` to `path`.
fn tracking_errors(pts: &[[f64; 2]], path: &[[f64; 2]]) -> Option<(f64, f64, f64)> {
    if pts.is_empty() {
        return None;
    }
    let d: Vec<f64> = pts
        .iter()
        .map(|&p| distance_to_polyline(p, path))
        .collect::<Option<_>>()?;
    let n = d.len() as f64;
    let mean = d.iter().sum::<f64>() / n;
    let max = d.iter().copied().fold(0.0, f64::max);
    let var = d.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / n;
    Some((mean, max, var))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::TraceStep;
    use std::f64::consts::FRAC_PI_2;

    fn trace(rows: &[(f64, f64, f64, f64)]) -> Trace {
        // (x, y, v, clearance), 0.1 s apart.
        Trace {
            steps: rows
                .iter()
                .enumerate()
                .map(|(i, &(x, y, v, c))| TraceStep {
                    t: i as f64 * 0.1,
                    x,
                    y,
                    v,
                    clearance: c,
                    ..Default::default()
                })
                .collect(),
        }
    }

    #[test]
    fn length_clearance_and_time() {
        let tr = trace(&[
            (0.0, 0.0, 0.0, 1.0),
            (3.0, 4.0, 1.0, 0.5),
            (3.0, 5.0, 1.0, 1.5),
        ]);
        let m = EpisodeMetrics::from_trace(&tr, &[], Outcome::Reached, 40.0);
        assert_eq!(m.path_length_m, 6.0);
        assert_eq!(m.min_clearance_m, 0.5);
        assert_eq!(m.mean_clearance_m, 1.0);
        assert!((m.time_s - 0.2).abs() < 1e-12);
        assert_eq!(m.mean_tracking_error_m, None);
        assert_eq!(m.load_ok_share, None);
        let j = serde_json::to_value(&m).unwrap();
        assert_eq!(j["outcome"], "reached");
        assert!(j["load_ok_share"].is_null());
    }

    #[test]
    fn right_angle_turn_counts_once_whatever_the_step() {
        // An L: 2 m east then 2 m north, sampled coarsely and finely.
        for n in [4usize, 40] {
            let mut pts = Vec::new();
            for i in 0..=n {
                pts.push((2.0 * i as f64 / n as f64, 0.0, 1.0, 1.0));
            }
            for i in 1..=n {
                pts.push((2.0, 2.0 * i as f64 / n as f64, 1.0, 1.0));
            }
            let m = EpisodeMetrics::from_trace(&trace(&pts), &[], Outcome::Reached, 40.0);
            assert!((m.total_turn_rad - FRAC_PI_2).abs() < 1e-9, "{n}: {m:?}");
            // The corner falls between resampled points, so it shows as two
            // 45° turns at 0.1 m resolution.
            assert!(m.max_turn_rad <= FRAC_PI_2 + 1e-9 && m.max_turn_rad >= FRAC_PI_2 / 2.0 - 1e-9);
        }
        // A straight line: no turning.
        let straight: Vec<_> = (0..30).map(|i| (i as f64 * 0.07, 1.0, 1.0, 1.0)).collect();
        let m = EpisodeMetrics::from_trace(&trace(&straight), &[], Outcome::Reached, 40.0);
        assert!(m.total_turn_rad < 1e-12);
    }

    #[test]
    fn per_step_turn_is_the_largest_heading_change_between_samples() {
        // East 0.1 m a step, turn 0.3 rad, two steps, turn on the spot
        // (a repeated point) by 0.5 rad more, then straight on.
        let mut h = 0.0f64;
        let mut p = [0.0f64, 0.0];
        let mut pts = vec![p];
        let mut go = |h: f64, pts: &mut Vec<[f64; 2]>| {
            p = [p[0] + 0.1 * h.cos(), p[1] + 0.1 * h.sin()];
            pts.push(p);
        };
        for _ in 0..3 {
            go(h, &mut pts);
        }
        h += 0.3;
        for _ in 0..2 {
            go(h, &mut pts);
        }
        pts.push(*pts.last().unwrap());
        h += 0.5;
        for _ in 0..3 {
            go(h, &mut pts);
        }
        assert!((max_step_turn(&pts) - 0.5).abs() < 1e-12);
        let rows: Vec<_> = pts.iter().map(|q| (q[0], q[1], 1.0, 1.0)).collect();
        let m = EpisodeMetrics::from_trace(&trace(&rows), &[], Outcome::Reached, 40.0);
        assert!((m.max_turn_step_rad - 0.5).abs() < 1e-12);
        assert!((m.total_turn_rad - 0.8).abs() < 1e-9, "{m:?}");
        // The same path on 0.05 m steps: the corners are the same angles.
        let fine: Vec<[f64; 2]> = pts
            .windows(2)
            .flat_map(|w| [w[0], [(w[0][0] + w[1][0]) / 2.0, (w[0][1] + w[1][1]) / 2.0]])
            .chain(pts.last().copied())
            .collect();
        assert!((max_step_turn(&fine) - 0.5).abs() < 1e-12);
        // A wrap across ±π is the small angle; fewer than two moves give 0.
        let wrap = [[0.0, 0.0], [-1.0, 0.01], [-2.0, -0.01]];
        let a = max_step_turn(&wrap);
        assert!(a < 0.031 && a > 0.029, "{a}");
        assert_eq!(max_step_turn(&[[0.0, 0.0], [1.0, 0.0]]), 0.0);
        assert_eq!(max_step_turn(&[[0.0, 0.0]; 4]), 0.0);
        assert_eq!(max_step_turn(&[]), 0.0);
    }

    #[test]
    fn resample_is_capped() {
        // 7.6·10⁸ m at 0.1 m would be 7.6·10⁹ points.
        let r = resample(&[[0.0, 0.0], [7.6e8, 0.0]], 0.1);
        assert!(r.len() <= MAX_RESAMPLE_POINTS + 2, "{}", r.len());
        assert!(r.len() >= MAX_RESAMPLE_POINTS - 1, "{}", r.len());
        assert_eq!(resample(&[[0.0, 0.0], [f64::INFINITY, 0.0]], 0.1).len(), 1);
    }

    #[test]
    fn resample_spacing() {
        let r = resample(&[[0.0, 0.0], [0.25, 0.0], [0.25, 0.3]], 0.1);
        assert_eq!(r.len(), 6); // 0.55 m → samples at 0, 0.1 … 0.5
        for w in r.windows(2) {
            let d = hypot(w[1][0] - w[0][0], w[1][1] - w[0][1]);
            assert!(d <= 0.1 + 1e-12 && d > 0.07, "{d}");
        }
    }

    #[test]
    fn speed_drops_ignore_the_final_stop() {
        let s = [
            0.0, 0.5, 1.0, 1.0, 0.5, 0.2, 0.6, 1.0, 0.95, 1.0, 0.4, 0.9, 1.0, 0.5, 0.0,
        ];
        // Falls 1.0→0.2 (rise after), 1.0→0.4 (rise after), final stop
        // (no rise): 2. The 1.0→0.95 wobble is below 30 %.
        assert_eq!(speed_drops(&s, 0.3), 2);
        assert_eq!(speed_drops(&[0.0, 0.3, 0.6, 0.6, 0.3, 0.0], 0.3), 0);
        assert_eq!(speed_drops(&[], 0.3), 0);
        assert_eq!(speed_drops(&[0.0; 5], 0.3), 0);
    }

    #[test]
    fn tracking_error_against_a_polyline() {
        let path = [[0.0, 0.0], [10.0, 0.0]];
        let tr = trace(&[
            (1.0, 0.0, 1.0, 1.0),
            (2.0, 1.0, 1.0, 1.0),
            (3.0, -2.0, 1.0, 1.0),
            (12.0, 0.0, 1.0, 1.0),
        ]);
        let m = EpisodeMetrics::from_trace(&tr, &path, Outcome::Reached, 40.0);
        // Distances 0, 1, 2, 2 (the last beyond the end).
        assert_eq!(m.mean_tracking_error_m, Some(1.25));
        assert_eq!(m.max_tracking_error_m, Some(2.0));
        // Variance: ((1.25)² + (0.25)² + 0.75² + 0.75²) / 4 = 0.6875.
        assert!((m.tracking_error_var_m2.unwrap() - 0.6875).abs() < 1e-12);
        assert_eq!(distance_to_polyline([3.0, 4.0], &[[0.0, 0.0]]), Some(5.0));
    }

    #[test]
    fn load_share_counts_rows_with_loads() {
        let mut tr = trace(&[(0.0, 0.0, 0.0, 1.0); 5]);
        tr.steps[1].wheel_loads = Some([50.0; 4]);
        tr.steps[2].wheel_loads = Some([50.0, 39.0, 50.0, 50.0]);
        tr.steps[3].wheel_loads = Some([41.0; 4]);
        tr.steps[4].wheel_loads = Some([40.0; 4]);
        let m = EpisodeMetrics::from_trace(&tr, &[], Outcome::Reached, 40.0);
        assert_eq!(m.load_ok_share, Some(0.5));
        // Per wheel: 4 + 3 + 4 + 0 of 16 wheel-rows above 40 N.
        assert_eq!(m.wheel_load_share, Some(11.0 / 16.0));
    }
}
