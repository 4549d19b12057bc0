//! Edges, gap patterns and obstacle patterns of a scan (\[L\] §2).
//!
//! - **Edges** (def. 1), e_i between beams i and i+1 (cyclic): SR d_i in
//!   range ∧ d_{i+1} = c; WR both in range ∧ d_{i+1} − d_i > T_gap; SF
//!   d_i = c ∧ d_{i+1} in range; WF both in range ∧ d_i − d_{i+1} > T_gap;
//!   else Null.
//! - **Algorithm 1**: for each rising edge at i, scan back from
//!   i + θ_range to i + 1 for the first falling edge j whose gap pattern is
//!   narrower than T_gap (d_g = distance between the points of beams i and
//!   j + 1); replace the ranges of beams i+1 … j by the straight line
//!   joining those two points and erase edges i … j; continue after j.
//!   Indices wrap around the scan.
//! - **Algorithm 2**: an obstacle pattern (OP) starts at any edge but SR
//!   and ends at the next edge, which is any but SF: it covers beams
//!   start+1 … end. A scan with no edge whose beams all returned is one
//!   closed OP around the robot.
//! - **Expansion** (eq 1): each OP grows at both ends by
//!   2·asin(d_oe / (2·d_end)) (π when d_oe ≥ 2·d_end), keeping the end's
//!   range.

use serde::{Deserialize, Serialize};

use super::scan::{beam_angle, dist, polar};
/// The edge type is named by the planner debug data in `local`, so it is
/// defined there.
pub use crate::local::scan_debug::Edge;
use crate::num::{asin, cos, sin};

/// Edges of every beam pair (i, i+1 mod n) of `ranges` (`INFINITY` = no
/// return) with threshold `t_gap`, into `out`.
pub fn classify(ranges: &[f64], t_gap: f64, out: &mut Vec<Edge>) {
    let n = ranges.len();
    out.clear();
    out.extend((0..n).map(|i| {
        let (a, b) = (ranges[i], ranges[(i + 1) % n]);
        match (a.is_finite(), b.is_finite()) {
            (true, false) => Edge::SR,
            (false, true) => Edge::SF,
            (true, true) if b - a > t_gap => Edge::WR,
            (true, true) if a - b > t_gap => Edge::WF,
            _ => Edge::Null,
        }
    }));
}

/// A gap pattern Algorithm 1 removed: rising edge at `rise`, falling edge
/// at `fall` (beams rise+1 … fall were replaced), width d_g.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct GapPattern {
    /// Index of the rising edge.
    pub rise: usize,
    /// Index of the falling edge.
    pub fall: usize,
    /// Gap width d_g, m.
    pub width: f64,
}

/// Algorithm 1: removes every gap pattern narrower than `t_gap` within
/// `theta_range` of its rising edge, in place (ranges and edges); returns
/// the removed patterns.
pub fn remove_gaps(
    ranges: &mut [f64],
    edges: &mut [Edge],
    t_gap: f64,
    theta_range: f64,
    out: &mut Vec<GapPattern>,
) {
    out.clear();
    let n = ranges.len();
    if n < 3 || edges.len() != n {
        return;
    }
    let step = std::f64::consts::TAU / n as f64;
    let span = if theta_range.is_finite() && theta_range > 0.0 {
        ((theta_range / step).round() as usize).min(n - 2)
    } else {
        0
    };
    let mut i = 0;
    while i < n {
        if !edges[i].is_rising() || !ranges[i].is_finite() {
            i += 1;
            continue;
        }
        let p = polar(beam_angle(i, n), ranges[i]);
        let mut found = None;
        for k in (1..=span).rev() {
            let j = (i + k) % n;
            if !edges[j].is_falling() {
                continue;
            }
            let q_idx = (j + 1) % n;
            let dq = ranges[q_idx];
            if !dq.is_finite() {
                continue;
            }
            let q = polar(beam_angle(q_idx, n), dq);
            let dg = dist(p, q);
            if dg < t_gap {
                found = Some((k, q, dg));
                break;
            }
        }
        match found {
            Some((k, q, dg)) => {
                for m in 1..=k {
                    let idx = (i + m) % n;
                    ranges[idx] = line_range(
                        beam_angle(idx, n),
                        p,
                        q,
                        ranges[i],
                        ranges[(i + k + 1) % n],
                        m as f64 / (k + 1) as f64,
                    );
                }
                for m in 0..=k {
                    edges[(i + m) % n] = Edge::Null;
                }
                out.push(GapPattern {
                    rise: i,
                    fall: (i + k) % n,
                    width: dg,
                });
                i += k + 1;
            }
            None => i += 1,
        }
    }
}

/// Range along the beam at `angle` to the line through p and q; the linear
/// blend of the end ranges (`dp`, `dq` at fraction `f`) when the beam misses
/// it (degenerate geometry).
fn line_range(angle: f64, p: [f64; 2], q: [f64; 2], dp: f64, dq: f64, f: f64) -> f64 {
    let u = [cos(angle), sin(angle)];
    let e = [q[0] - p[0], q[1] - p[1]];
    let den = u[0] * e[1] - u[1] * e[0];
    let t = (p[0] * e[1] - p[1] * e[0]) / den;
    if t.is_finite() && t >= 0.0 && t <= dp.max(dq) + 1e-9 {
        t
    } else {
        dp + (dq - dp) * f
    }
}

/// An obstacle pattern: beams `first` … `first + len − 1` (cyclic) with
/// expansion angles at both ends.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ObstaclePattern {
    /// First beam.
    pub first: usize,
    /// Number of beams (≥ 1).
    pub len: usize,
    /// Edge that starts it (SF, WR, WF; Null for a closed OP).
    pub start_edge: Edge,
    /// Edge that ends it (SR, WR, WF; Null for a closed OP).
    pub end_edge: Edge,
    /// Range at the first beam, m.
    pub d_first: f64,
    /// Range at the last beam, m.
    pub d_last: f64,
    /// Expansion before the first beam, rad (eq 1; 0 before expansion).
    pub ext_start: f64,
    /// Expansion after the last beam, rad.
    pub ext_end: f64,
    /// Covers the whole circle (no edge in the scan, every beam returned).
    pub closed: bool,
}

impl ObstaclePattern {
    /// Angle of the first beam minus the start expansion, rad (robot frame,
    /// may be negative).
    pub fn start_angle(&self, n: usize) -> f64 {
        beam_angle(self.first, n) - self.ext_start
    }

    /// Angular width θ_o including the expansion, rad (≤ 2π).
    pub fn width(&self, n: usize) -> f64 {
        if self.closed {
            return std::f64::consts::TAU;
        }
        let step = std::f64::consts::TAU / n.max(1) as f64;
        ((self.len - 1) as f64 * step + self.ext_start + self.ext_end).min(std::f64::consts::TAU)
    }

    /// Angle of the end of the pattern (last beam plus expansion), rad.
    pub fn end_angle(&self, n: usize) -> f64 {
        self.start_angle(n) + self.width(n)
    }

    /// The OP's range d_o at bearing `phi` (robot frame), or `None` when
    /// `phi` is outside its angular range. Inside the expansions it is the
    /// end's range; between beams, the nearest beam's.
    pub fn range_at(&self, phi: f64, ranges: &[f64]) -> Option<f64> {
        let n = ranges.len();
        if n == 0 || !phi.is_finite() {
            return None;
        }
        let tau = std::f64::consts::TAU;
        let step = tau / n as f64;
        if self.closed {
            let k = (phi.rem_euclid(tau) / step).round() as usize % n;
            return Some(ranges[k]);
        }
        let off = (phi - self.start_angle(n)).rem_euclid(tau);
        if off > self.width(n) + 1e-12 {
            return None;
        }
        let rel = off - self.ext_start;
        if rel <= 0.0 {
            return Some(self.d_first);
        }
        let k = (rel / step).round() as usize;
        if k >= self.len - 1 {
            return Some(self.d_last);
        }
        Some(ranges[(self.first + k) % n])
    }

    /// The OP's points in the robot frame (beams only, no expansion).
    pub fn points(&self, ranges: &[f64]) -> Vec<[f64; 2]> {
        let n = ranges.len();
        (0..self.len)
            .map(|k| {
                let i = (self.first + k) % n;
                polar(beam_angle(i, n), ranges[i])
            })
            .collect()
    }
}

/// Algorithm 2: the obstacle patterns of (modified) `ranges` and `edges`,
/// into `out` (unexpanded).
pub fn extract_ops(ranges: &[f64], edges: &[Edge], out: &mut Vec<ObstaclePattern>) {
    out.clear();
    let n = ranges.len();
    if n == 0 || edges.len() != n {
        return;
    }
    let marks: Vec<usize> = (0..n).filter(|&i| edges[i] != Edge::Null).collect();
    if marks.is_empty() {
        if ranges.iter().all(|d| d.is_finite()) {
            out.push(ObstaclePattern {
                first: 0,
                len: n,
                start_edge: Edge::Null,
                end_edge: Edge::Null,
                d_first: ranges[0],
                d_last: ranges[n - 1],
                ext_start: 0.0,
                ext_end: 0.0,
                closed: true,
            });
        }
        return;
    }
    for (k, &a) in marks.iter().enumerate() {
        let ea = edges[a];
        if ea == Edge::SR {
            continue;
        }
        let b = marks[(k + 1) % marks.len()];
        let eb = edges[b];
        if eb == Edge::SF {
            continue;
        }
        // Beams a+1 … b (cyclic); b == a: the whole circle from a+1.
        let len = if b > a { b - a } else { b + n - a };
        let first = (a + 1) % n;
        let last = (first + len - 1) % n;
        if !(ranges[first].is_finite() && ranges[last].is_finite()) {
            continue;
        }
        out.push(ObstaclePattern {
            first,
            len,
            start_edge: ea,
            end_edge: eb,
            d_first: ranges[first],
            d_last: ranges[last],
            ext_start: 0.0,
            ext_end: 0.0,
            closed: false,
        });
    }
}

/// Expansion angle of eq 1 for distance `d_oe` at range `d`, rad.
pub fn expansion_angle(d_oe: f64, d: f64) -> f64 {
    if !d_oe.is_finite() || d_oe <= 0.0 {
        return 0.0;
    }
    let x = d_oe / (2.0 * d);
    if x.is_nan() || x >= 1.0 {
        std::f64::consts::PI
    } else {
        2.0 * asin(x)
    }
}

/// Eq 1: expands every OP by `d_oe` at both ends (closed OPs stay).
pub fn expand(ops: &mut [ObstaclePattern], d_oe: f64) {
    for op in ops.iter_mut().filter(|o| !o.closed) {
        op.ext_start = expansion_angle(d_oe, op.d_first);
        op.ext_end = expansion_angle(d_oe, op.d_last);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const C: f64 = f64::INFINITY;

    #[test]
    fn definition_1() {
        let mut e = Vec::new();
        classify(&[1.0, C, C, 2.0, 5.0, 3.0, 1.0], 1.4, &mut e);
        assert_eq!(
            e,
            vec![
                Edge::SR,
                Edge::Null,
                Edge::SF,
                Edge::WR,
                Edge::WF,
                Edge::WF,
                Edge::Null
            ]
        );
    }

    #[test]
    fn narrow_gap_is_removed_with_wrap_around() {
        // 36 beams (10°). A wall at 2 m over beams 30..=35 and 0..=3 with
        // a one-beam hole at beam 34 (no return): the hole's gap is
        // 2·2·sin(10°) ≈ 0.69 m < 1.4 → removed; the wall becomes one OP
        // across the wrap.
        let mut r = vec![C; 36];
        for i in (30..36).chain(0..4) {
            r[i] = 2.0;
        }
        r[34] = C;
        let mut e = Vec::new();
        classify(&r, 1.4, &mut e);
        assert_eq!(e[33], Edge::SR);
        assert_eq!(e[34], Edge::SF);
        let mut gaps = Vec::new();
        remove_gaps(&mut r, &mut e, 1.4, std::f64::consts::FRAC_PI_2, &mut gaps);
        assert_eq!(gaps.len(), 1);
        assert!(r[34].is_finite() && (r[34] - 2.0 * (10f64.to_radians()).cos()).abs() < 1e-9);
        let mut ops = Vec::new();
        extract_ops(&r, &e, &mut ops);
        assert_eq!(ops.len(), 1, "{ops:?}");
        assert_eq!((ops[0].first, ops[0].len), (30, 10));
    }

    #[test]
    fn wide_gap_stays() {
        // A 4-beam hole at 5 m: 2·5·sin(25°) ≈ 4.2 m > 1.4.
        let mut r = vec![5.0; 36];
        for d in &mut r[10..14] {
            *d = C;
        }
        let mut e = Vec::new();
        classify(&r, 1.4, &mut e);
        let mut gaps = Vec::new();
        remove_gaps(&mut r, &mut e, 1.4, std::f64::consts::FRAC_PI_2, &mut gaps);
        assert!(gaps.is_empty());
        let mut ops = Vec::new();
        extract_ops(&r, &e, &mut ops);
        assert_eq!(ops.len(), 1);
        assert_eq!((ops[0].first, ops[0].len), (14, 32));
        assert_eq!((ops[0].start_edge, ops[0].end_edge), (Edge::SF, Edge::SR));
    }

    #[test]
    fn occluding_obstacles_share_edges() {
        // Far wall 6 m, near post at 2 m over beams 5..=7.
        let mut r = vec![C; 36];
        for d in &mut r[0..12] {
            *d = 6.0;
        }
        for d in &mut r[5..8] {
            *d = 2.0;
        }
        let mut e = Vec::new();
        classify(&r, 1.4, &mut e);
        let mut ops = Vec::new();
        extract_ops(&r, &e, &mut ops);
        // In scan order from the first start edge; the OP that starts at
        // the SF of beam 35 comes last.
        let spans: Vec<(usize, usize)> = ops.iter().map(|o| (o.first, o.len)).collect();
        assert_eq!(spans, vec![(5, 3), (8, 4), (0, 5)]);
        ops.rotate_right(1);
        expand(&mut ops, 0.5);
        let a = ops[1].ext_start;
        assert!((a - 2.0 * (0.125f64).asin()).abs() < 1e-12);
        // Range lookups inside, in the expansion and outside.
        assert_eq!(ops[1].range_at(beam_angle(6, 36), &r), Some(2.0));
        assert_eq!(ops[1].range_at(beam_angle(5, 36) - 0.5 * a, &r), Some(2.0));
        assert_eq!(ops[1].range_at(beam_angle(20, 36), &r), None);
    }

    #[test]
    fn closed_and_degenerate() {
        let mut ops = Vec::new();
        let mut e = Vec::new();
        let r = vec![3.0; 10];
        classify(&r, 1.4, &mut e);
        extract_ops(&r, &e, &mut ops);
        assert!(ops.len() == 1 && ops[0].closed);
        assert_eq!(ops[0].range_at(1.0, &r), Some(3.0));
        let r = vec![C; 10];
        classify(&r, 1.4, &mut e);
        extract_ops(&r, &e, &mut ops);
        assert!(ops.is_empty());
        let r: Vec<f64> = vec![];
        classify(&r, 1.4, &mut e);
        extract_ops(&r, &e, &mut ops);
        assert!(ops.is_empty());
        assert_eq!(expansion_angle(0.5, 0.0), std::f64::consts::PI);
        assert_eq!(expansion_angle(f64::NAN, 1.0), 0.0);
    }
}
