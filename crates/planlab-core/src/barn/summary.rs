//! The challenge's figures over a set of runs: success, collision and
//! timeout shares (with Wilson 95 % intervals) and the mean score.

use super::score;
use crate::reproduce::stats::Share;
use crate::world::Outcome;

/// One BARN run: how it ended, its time T and its world's optimal time OT
/// (seconds).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunRecord {
    /// How the run ended.
    pub outcome: Outcome,
    /// Simulated time of the run, seconds.
    pub time: f64,
    /// The world's [`BarnWorld::optimal_time`](super::BarnWorld::optimal_time).
    pub ot: f64,
}

/// What the challenge reports over its runs.
///
/// BARN knows three endings: success (planlab's `Reached`), collision and
/// timeout; planlab's `Stuck` and an unfinished `Running` count as
/// timeouts, since the challenge would have run them to [`TIMEOUT`](super::TIMEOUT).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Summary {
    /// Runs that reached the goal.
    pub success: Share,
    /// Runs that collided.
    pub collision: Share,
    /// Runs that ran out of time (or were stuck or unfinished).
    pub timeout: Share,
    /// Mean time of the successful runs, seconds (`None` without one).
    pub mean_success_time: Option<f64>,
    /// Mean [`score`] over all runs (0 without runs).
    pub mean_score: f64,
}

impl Summary {
    /// The figures of `runs`.
    pub fn of(runs: &[RunRecord]) -> Summary {
        let n = u32::try_from(runs.len()).unwrap_or(u32::MAX);
        let count = |f: &dyn Fn(Outcome) -> bool| {
            u32::try_from(runs.iter().filter(|r| f(r.outcome)).count()).unwrap_or(u32::MAX)
        };
        let reached = |o| o == Outcome::Reached;
        let collided = |o| o == Outcome::Collision;
        let k = count(&reached);
        let times: Vec<f64> = runs
            .iter()
            .filter(|r| reached(r.outcome))
            .map(|r| r.time)
            .collect();
        let scores: f64 = runs
            .iter()
            .map(|r| score(reached(r.outcome), r.time, r.ot))
            .sum();
        Summary {
            success: Share::new(k, n),
            collision: Share::new(count(&collided), n),
            timeout: Share::new(count(&|o| !reached(o) && !collided(o)), n),
            mean_success_time: (!times.is_empty())
                .then(|| times.iter().sum::<f64>() / times.len() as f64),
            mean_score: if runs.is_empty() {
                0.0
            } else {
                scores / runs.len() as f64
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn summary_counts_endings_and_averages_scores_by_hand() {
        let run = |outcome, time| RunRecord {
            outcome,
            time,
            ot: 5.0,
        };
        let runs = [
            run(Outcome::Reached, 8.0),   // clipped to 10: 0.5
            run(Outcome::Reached, 20.0),  // 0.25
            run(Outcome::Collision, 3.0), // 0
            run(Outcome::Timeout, 100.0), // 0
            run(Outcome::Stuck, 40.0),    // 0, counted as a timeout
        ];
        let s = Summary::of(&runs);
        assert_eq!((s.success.k, s.success.n), (2, 5));
        assert_eq!((s.collision.k, s.timeout.k), (1, 2));
        assert_eq!(s.success.ci95, crate::reproduce::stats::wilson(2, 5));
        assert_eq!(s.mean_success_time, Some(14.0));
        assert!((s.mean_score - 0.75 / 5.0).abs() < 1e-15);
        let empty = Summary::of(&[]);
        assert_eq!(
            (empty.success.n, empty.mean_success_time, empty.mean_score),
            (0, None, 0.0)
        );
    }
}
