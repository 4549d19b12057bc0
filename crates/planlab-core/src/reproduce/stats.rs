//! Statistics of an experiment's family of variants: success rates with
//! Wilson score intervals and paired effects as a median with a
//! distribution-free (order-statistic) interval.
//!
//! Both intervals are exact closed forms (no resampling), so the figures
//! are the same on every target and can be checked by hand.

use serde::{Deserialize, Serialize};

/// z of a two-sided 95 % normal interval.
const Z95: f64 = 1.959_963_984_540_054;

/// A count of successes over trials with its Wilson 95 % interval.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Share {
    /// Successes.
    pub k: u32,
    /// Trials.
    pub n: u32,
    /// k / n (0 when n = 0).
    pub rate: f64,
    /// Wilson score 95 % interval of the rate ([0, 1] when n = 0).
    pub ci95: [f64; 2],
}

impl Share {
    /// The share of `k` successes in `n` trials.
    pub fn new(k: u32, n: u32) -> Share {
        let k = k.min(n);
        Share {
            k,
            n,
            rate: if n == 0 {
                0.0
            } else {
                f64::from(k) / f64::from(n)
            },
            ci95: wilson(k, n),
        }
    }

    /// The share of `true` values.
    pub fn of(values: impl IntoIterator<Item = bool>) -> Share {
        let (mut k, mut n) = (0u32, 0u32);
        for v in values {
            n += 1;
            k += u32::from(v);
        }
        Share::new(k, n)
    }

    /// The share of successes in runs that come in clusters (a
    /// benchmark's worlds, each run several times): `groups` holds each
    /// cluster's (successes, runs). The rate is k / n over all runs; the
    /// Wilson interval is taken at the effective sample size n / deff, with
    /// deff the design effect of the ratio estimator (Kish 1965), kept
    /// between the number of clusters and n — runs of one world tend to
    /// agree, and counting them as independent trials would narrow the
    /// interval falsely. With no variation to estimate deff from (rate 0
    /// or 1) each cluster counts once. With one run per cluster this is
    /// [`Share::new`].
    pub fn clustered(groups: &[(u32, u32)]) -> Share {
        let groups: Vec<(f64, f64)> = groups
            .iter()
            .filter(|g| g.1 > 0)
            .map(|&(k, m)| (f64::from(k.min(m)), f64::from(m)))
            .collect();
        let k: f64 = groups.iter().map(|g| g.0).sum();
        let n: f64 = groups.iter().map(|g| g.1).sum();
        let w = groups.len() as f64;
        let share = Share::new(k as u32, n as u32);
        if groups.iter().all(|g| g.1 == 1.0) {
            return share;
        }
        let p = k / n;
        let n_eff = if k == 0.0 || k == n || w < 2.0 {
            w
        } else {
            let var = w / (w - 1.0) * groups.iter().map(|g| (g.0 - p * g.1).powi(2)).sum::<f64>()
                / (n * n);
            let deff = var / (p * (1.0 - p) / n);
            (n / deff).clamp(w, n)
        };
        Share {
            ci95: wilson_f(p * n_eff, n_eff),
            ..share
        }
    }
}

/// Wilson score 95 % interval of a binomial proportion k / n (Wilson
/// 1927): centre (k + z²/2)/(n + z²), half width
/// z·√(k(n−k)/n + z²/4)/(n + z²). Unlike the normal interval it stays
/// inside [0, 1] and is not empty at k = 0 or k = n.
pub fn wilson(k: u32, n: u32) -> [f64; 2] {
    wilson_f(f64::from(k.min(n)), f64::from(n))
}

/// [`wilson`] for an effective (fractional) count: k successes of n, 0 ≤ k ≤ n.
fn wilson_f(k: f64, n: f64) -> [f64; 2] {
    if n <= 0.0 {
        return [0.0, 1.0];
    }
    let z2 = Z95 * Z95;
    let centre = (k + z2 / 2.0) / (n + z2);
    let half = Z95 * (k * (n - k) / n + z2 / 4.0).sqrt() / (n + z2);
    // At k = 0 and k = n the bounds are exactly 0 and 1; rounding would
    // leave 1 − 1e-16.
    let lo = if k == 0.0 {
        0.0
    } else {
        (centre - half).max(0.0)
    };
    let hi = if k == n {
        1.0
    } else {
        (centre + half).min(1.0)
    };
    [lo, hi]
}

/// How a paired effect compares two runs of the same variant.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum EffectKind {
    /// a − b, in the metric's unit.
    Difference,
    /// a / b.
    Ratio,
}

/// The median of per-variant paired effects with its 95 % interval.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct MedianCi {
    /// Variants with a value (both runs had the metric).
    pub n: u32,
    /// Median (mean of the two middle values for even n).
    pub median: f64,
    /// Distribution-free 95 % interval of the median: order statistics
    /// x₍ₗ₎ … x₍ₙ₊₁₋ₗ₎ with l the largest rank where P(Bin(n, ½) < l) ≤
    /// 2.5 %; `None` when n < 6 (no such interval reaches 95 %).
    pub ci95: Option<[f64; 2]>,
}

impl MedianCi {
    /// The median of the finite `values` and its interval; `None` when no
    /// value is finite.
    pub fn of(values: &[f64]) -> Option<MedianCi> {
        let mut v: Vec<f64> = values.iter().copied().filter(|x| x.is_finite()).collect();
        if v.is_empty() {
            return None;
        }
        v.sort_by(f64::total_cmp);
        let n = v.len();
        let median = if n % 2 == 1 {
            v[n / 2]
        } else {
            0.5 * (v[n / 2 - 1] + v[n / 2])
        };
        let ci95 = median_rank(n).map(|l| [v[l - 1], v[n - l]]);
        Some(MedianCi {
            n: n as u32,
            median,
            ci95,
        })
    }
}

/// The 1-based rank l of the lower end of the distribution-free 95 %
/// interval of a median of n values: the largest l with
/// P(Bin(n, ½) ≤ l − 1) ≤ 0.025; `None` when even l = 1 does not qualify
/// (n < 6).
pub fn median_rank(n: usize) -> Option<usize> {
    // P(X ≤ j) summed exactly in f64: n stays in the hundreds here and
    // the terms C(n, j)/2ⁿ are built by ratios, so nothing overflows.
    let mut term = 0.5f64.powi(n as i32); // P(X = 0)
    let mut cdf = 0.0;
    let mut best = None;
    for j in 0..n {
        cdf += term;
        if cdf > 0.025 {
            break;
        }
        best = Some(j + 1);
        term *= (n - j) as f64 / (j + 1) as f64;
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clustered_share_with_one_run_per_cluster_is_the_plain_wilson_interval() {
        let groups: Vec<(u32, u32)> = (0..40).map(|i| (u32::from(i % 3 == 0), 1)).collect();
        assert_eq!(Share::clustered(&groups), Share::new(14, 40));
        assert_eq!(Share::clustered(&[]), Share::new(0, 0));
    }

    #[test]
    fn clustered_share_of_worlds_whose_runs_agree_counts_each_world_once() {
        // 30 worlds succeeded on all 3 runs, 10 failed all 3: the runs
        // add nothing, so the interval is that of 30 / 40 worlds.
        let mut groups = vec![(3, 3); 30];
        groups.extend([(0, 3); 10]);
        let s = Share::clustered(&groups);
        assert_eq!((s.k, s.n), (90, 120));
        assert_eq!(s.rate, 0.75);
        let want = wilson(30, 40);
        assert!((s.ci95[0] - want[0]).abs() < 1e-12 && (s.ci95[1] - want[1]).abs() < 1e-12);
        // Independent-looking runs (every world 2 of 3, i.e. no world
        // effect) narrow it towards the interval of 120 trials.
        let mixed = Share::clustered(&[(2, 3); 40]);
        let runs = wilson(80, 120);
        assert!(mixed.ci95[1] - mixed.ci95[0] <= wilson(27, 40)[1] - wilson(27, 40)[0]);
        assert!(mixed.ci95[1] - mixed.ci95[0] >= runs[1] - runs[0] - 1e-12);
        // No variation to estimate from: each world once.
        let none = Share::clustered(&[(0, 3); 40]);
        assert_eq!(none.ci95, wilson(0, 40));
    }

    #[test]
    fn wilson_matches_hand_computed_cases() {
        // k = 8, n = 10: centre (8 + 1.92)/(13.84) = 0.7168; half
        // 1.96·√(1.6 + 0.96)/13.84 = 0.2266 → [0.4902, 0.9433].
        let [lo, hi] = wilson(8, 10);
        assert!(
            (lo - 0.4902).abs() < 1e-3 && (hi - 0.9433).abs() < 1e-3,
            "{lo} {hi}"
        );
        // k = 0, n = 30: [0, z²/(n + z²)] = [0, 0.1135].
        let [lo, hi] = wilson(0, 30);
        assert_eq!(lo, 0.0);
        assert!((hi - 3.8415 / 33.8415).abs() < 1e-4, "{hi}");
        // k = n is the mirror image.
        let [lo, hi] = wilson(30, 30);
        assert!((lo - 30.0 / 33.8415).abs() < 1e-4 && hi == 1.0, "{lo} {hi}");
        assert_eq!(wilson(0, 0), [0.0, 1.0]);
        let s = Share::of([true, false, true, true]);
        assert_eq!((s.k, s.n, s.rate), (3, 4, 0.75));
    }

    #[test]
    fn median_ranks_match_the_binomial_table() {
        // n = 6: P(X = 0) = 1/64 = 0.0156 ≤ 0.025, P(X ≤ 1) = 7/64 > it.
        assert_eq!(median_rank(5), None);
        assert_eq!(median_rank(6), Some(1));
        // n = 10: P(X ≤ 1) = 11/1024 = 0.0107, P(X ≤ 2) = 56/1024 = 0.0547.
        assert_eq!(median_rank(10), Some(2));
        // n = 30: P(X ≤ 9) = 0.0214, P(X ≤ 10) = 0.0494 (standard table: 10th
        // and 21st order statistics).
        assert_eq!(median_rank(30), Some(10));
    }

    #[test]
    fn median_interval_of_known_values() {
        let v: Vec<f64> = (1..=10).map(f64::from).collect();
        let m = MedianCi::of(&v).unwrap();
        assert_eq!((m.n, m.median, m.ci95), (10, 5.5, Some([2.0, 9.0])));
        let m = MedianCi::of(&[3.0, f64::NAN, 1.0, 2.0]).unwrap();
        assert_eq!((m.n, m.median, m.ci95), (3, 2.0, None));
        assert!(MedianCi::of(&[f64::NAN]).is_none());
    }
}
