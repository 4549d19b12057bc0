//! Which perturbation a family's verdict is most sensitive to.
//!
//! Every number a variant drew (the goal's x shift, a mover's speed
//! factor, a block's row shift …) splits the family's variants at its
//! median into a lower and an upper half; the share of each half on which
//! the whole relation holds, with its Wilson interval, says whether the
//! relation fails mostly on one side ("fails mostly when the mover is
//! slower"). Per perturbation of the family the number with the largest
//! gap between its halves is kept. A median split needs no model of how the
//! relation depends on the value and reads the same for every kind of
//! perturbation; with 30–60 variants each half has 15–30, so only a large
//! gap is told apart from chance — the report says when the halves'
//! intervals overlap.

use serde::Serialize;
use serde_json::Value;

use super::family::{Draw, Family};
use super::stats::Share;

/// How the whole relation's holding splits at the median of one drawn number.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Split {
    /// The drawn number, e.g. `goal x shift m`, `mover 1 speed ×`.
    pub value: String,
    /// Its median over the variants: the split point.
    pub at: f64,
    /// Variants that drew less than `at`: where the relation holds.
    pub below: Share,
    /// Variants that drew `at` or more.
    pub above: Share,
}

impl Split {
    /// |below − above| of the holding rates.
    pub fn gap(&self) -> f64 {
        (self.below.rate - self.above.rate).abs()
    }

    /// Whether the two halves' Wilson intervals are apart.
    pub fn stands_out(&self) -> bool {
        self.below.ci95[1] < self.above.ci95[0] || self.above.ci95[1] < self.below.ci95[0]
    }

    /// In words: `fails mostly when goal x shift m is below 0.012 (holds
    /// on 3/15 below, 14/15 above)`.
    pub fn words(&self) -> String {
        let (side, worse) = if self.below.rate < self.above.rate {
            ("below", "fails mostly")
        } else if self.below.rate > self.above.rate {
            ("at or above", "fails mostly")
        } else {
            ("below", "holds alike")
        };
        format!(
            "{worse} when {} is {side} {} (holds on {}/{} below, {}/{} above)",
            self.value,
            crate::num::fmt_num(round3(self.at)),
            self.below.k,
            self.below.n,
            self.above.k,
            self.above.n
        )
    }
}

fn round3(x: f64) -> f64 {
    if x == 0.0 {
        return 0.0;
    }
    let p = 10f64.powi(2 - x.abs().log10().floor() as i32);
    (x * p).round() / p
}

/// One perturbation of the family and its most telling split.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PerturbationSplit {
    /// The perturbation's short name (`start`, `movers`, `apf.obstacles` …).
    pub perturbation: String,
    /// Why its range is the paper's situation.
    pub why: String,
    /// The drawn number with the largest gap; `None` when it draws no
    /// ordered number (a seed) or every variant drew the same.
    pub split: Option<Split>,
}

/// The sensitivity of a family's verdict.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Sensitivity {
    /// Per perturbation of the family, in its order.
    pub perturbations: Vec<PerturbationSplit>,
    /// In words: what the relation is most sensitive to.
    pub summary: String,
}

/// The labels of a draw's numbers, or `None` for a draw without an order
/// (a seed).
fn labels(d: &Draw) -> Option<Vec<String>> {
    let n = match &d.value {
        Value::Array(a) => a.len(),
        Value::Number(_) => 1,
        _ => return None,
    };
    let what = d.what.as_str();
    if what == "seed" || what.ends_with(": seed") {
        return None;
    }
    let axes = ["x", "y", "z"];
    let (base, comps): (&str, Vec<String>) = if let Some(b) = what.strip_suffix(" shift m, speed ×")
    {
        let mut c: Vec<String> = axes[..n - 1]
            .iter()
            .map(|a| format!("{a} shift m"))
            .collect();
        c.push("speed ×".into());
        (b, c)
    } else if let Some(b) = what.strip_suffix(" shift m") {
        (
            b,
            axes[..n.min(3)]
                .iter()
                .map(|a| format!("{a} shift m"))
                .collect(),
        )
    } else if let Some(b) = what.strip_suffix(" shift cells") {
        (
            b,
            ["column", "row"][..n.min(2)]
                .iter()
                .map(|a| format!("{a} shift cells"))
                .collect(),
        )
    } else if n == 1 {
        return Some(vec![what.to_string()]);
    } else {
        (what, (0..n).map(|i| format!("[{i}]")).collect())
    };
    Some(comps.into_iter().map(|c| format!("{base} {c}")).collect())
}

/// The numbers a variant drew for perturbation `of`, by label.
fn numbers(draws: &[Draw], of: usize) -> Vec<(String, f64)> {
    let mut out = Vec::new();
    for d in draws.iter().filter(|d| d.of == of) {
        let Some(names) = labels(d) else { continue };
        let vals: Vec<f64> = match &d.value {
            Value::Array(a) => a.iter().filter_map(Value::as_f64).collect(),
            v => v.as_f64().into_iter().collect(),
        };
        out.extend(names.into_iter().zip(vals));
    }
    out
}

/// The median split of one number over `(value, holds)` pairs; `None`
/// when a half would be empty.
fn split(value: &str, mut pairs: Vec<(f64, bool)>) -> Option<Split> {
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
    let n = pairs.len();
    if n < 2 {
        return None;
    }
    let at = if n % 2 == 1 {
        pairs[n / 2].0
    } else {
        0.5 * (pairs[n / 2 - 1].0 + pairs[n / 2].0)
    };
    let below = Share::of(pairs.iter().filter(|p| p.0 < at).map(|p| p.1));
    let above = Share::of(pairs.iter().filter(|p| p.0 >= at).map(|p| p.1));
    (below.n > 0 && above.n > 0).then(|| Split {
        value: value.to_string(),
        at,
        below,
        above,
    })
}

/// The sensitivity of a family over its variants: `draws` and whether the
/// whole relation held, per variant (the preset, with no draws, counts in
/// no split).
pub fn of(family: &Family, variants: &[(&[Draw], bool)]) -> Sensitivity {
    let mut perturbations = Vec::new();
    for (i, r) in family.perturbations.iter().enumerate() {
        // Every label this perturbation drew, in first-seen order.
        let mut by_label: Vec<(String, Vec<(f64, bool)>)> = Vec::new();
        for (draws, holds) in variants {
            for (label, x) in numbers(draws, i) {
                match by_label.iter_mut().find(|(l, _)| *l == label) {
                    Some((_, v)) => v.push((x, *holds)),
                    None => by_label.push((label, vec![(x, *holds)])),
                }
            }
        }
        let best = by_label
            .into_iter()
            .filter(|(_, v)| v.iter().any(|p| p.0 != v[0].0))
            .filter_map(|(l, v)| split(&l, v))
            .fold(None::<Split>, |best, s| match best {
                Some(b) if b.gap() >= s.gap() => Some(b),
                _ => Some(s),
            });
        perturbations.push(PerturbationSplit {
            perturbation: r.perturbation.name(),
            why: r.why.to_string(),
            split: best,
        });
    }
    let joint = Share::of(variants.iter().filter(|v| !v.0.is_empty()).map(|v| v.1));
    let top =
        perturbations
            .iter()
            .filter_map(|p| p.split.as_ref())
            .fold(None::<&Split>, |best, s| match best {
                Some(b) if b.gap() >= s.gap() => Some(b),
                _ => Some(s),
            });
    let summary = if joint.n == 0 {
        "no perturbed variant".to_string()
    } else if joint.k == joint.n {
        "holds on every perturbed variant: no perturbation breaks it".to_string()
    } else if joint.k == 0 {
        "holds on no perturbed variant: no perturbation brings it back".to_string()
    } else {
        match top {
            None => "no drawn number to split the variants by".to_string(),
            Some(s) if s.stands_out() => s.words(),
            Some(s) => format!(
                "no perturbation stands out (the halves' 95 % intervals overlap); the largest gap: {}",
                s.words()
            ),
        }
    };
    Sensitivity {
        perturbations,
        summary,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reproduce::Perturbation;
    use serde_json::json;

    fn draw(what: &str, value: Value, of: usize) -> Draw {
        Draw {
            what: what.into(),
            value,
            of,
        }
    }

    #[test]
    fn a_relation_failing_when_the_mover_is_slower_is_told_by_its_speed() {
        let family = Family {
            perturbations: vec![
                Perturbation::start(0.1).because("test"),
                Perturbation::Movers {
                    radius_m: 0.1,
                    speed_rel: 0.2,
                }
                .because("test"),
                Perturbation::Seed.because("test"),
            ],
        };
        // 20 variants: the relation holds iff the speed factor ≥ 1; the
        // start shift is unrelated, the seed has no order.
        let mut all = Vec::new();
        for k in 0..20u32 {
            let f = 0.8 + 0.4 * f64::from(k) / 19.0;
            let sx = if k % 2 == 0 { 0.05 } else { -0.05 };
            all.push((
                vec![
                    draw("start shift m", json!([sx, 0.01 * f64::from(k % 3)]), 0),
                    draw("mover 1 shift m, speed ×", json!([0.0, 0.02, f]), 1),
                    draw("seed", json!(17 + k), 2),
                ],
                f >= 1.0,
            ));
        }
        let v: Vec<(&[Draw], bool)> = all.iter().map(|(d, h)| (d.as_slice(), *h)).collect();
        let s = of(&family, &v);
        assert_eq!(s.perturbations.len(), 3);
        let movers = s.perturbations[1].split.as_ref().unwrap();
        assert_eq!(movers.value, "mover 1 speed ×");
        assert_eq!((movers.below.k, movers.below.n), (0, 10));
        assert_eq!((movers.above.k, movers.above.n), (10, 10));
        assert!(movers.stands_out());
        assert!(s.perturbations[2].split.is_none(), "a seed has no order");
        let start = s.perturbations[0].split.as_ref().unwrap();
        assert!(start.gap() < 0.5, "{start:?}");
        assert!(
            s.summary
                .starts_with("fails mostly when mover 1 speed × is below 1"),
            "{}",
            s.summary
        );
    }

    #[test]
    fn a_relation_holding_everywhere_or_nowhere_says_so() {
        let family = Family {
            perturbations: vec![Perturbation::start(0.1).because("test")],
        };
        let d: Vec<Vec<Draw>> = (0..6)
            .map(|k| vec![draw("start shift m", json!([f64::from(k), 0.0]), 0)])
            .collect();
        let all: Vec<(&[Draw], bool)> = d.iter().map(|x| (x.as_slice(), true)).collect();
        assert!(of(&family, &all).summary.starts_with("holds on every"));
        let none: Vec<(&[Draw], bool)> = d.iter().map(|x| (x.as_slice(), false)).collect();
        assert!(of(&family, &none).summary.starts_with("holds on no"));
        // Holding on alternate variants: no number separates them.
        let alt: Vec<(&[Draw], bool)> = d
            .iter()
            .enumerate()
            .map(|(i, x)| (x.as_slice(), i % 2 == 0))
            .collect();
        assert!(
            of(&family, &alt)
                .summary
                .starts_with("no perturbation stands out"),
            "{}",
            of(&family, &alt).summary
        );
    }
}
