//! Exact replay of an episode with live edits (the page's timeline).
//!
//! An [`Episode`] is deterministic in its setup and seed, but the page
//! edits it while it runs (goal, movers, planner). A [`Recording`] keeps
//! the setup the episode started from plus every edit with the step count
//! at which it was made, so the same run can be rebuilt to any step:
//! replaying to step k builds the episode from the setup and, before each
//! step, applies the edits made at that step count; the edits made at k
//! itself are applied too (the state at frame k is what the user saw and
//! changed there). The rebuilt trace is bit-identical to the original's
//! first k + 1 rows.

use super::{Episode, EpisodeSetup, Outcome, SimError};
use crate::planners::PlannerChoice;
use crate::world::MoverSpec;

/// One live edit of a running episode.
#[derive(Debug, Clone, PartialEq)]
pub enum Edit {
    /// [`Episode::set_goal`] with this goal, m.
    Goal([f64; 2]),
    /// [`Episode::set_movers`] with these movers.
    Movers(Vec<MoverSpec>),
    /// [`Episode::set_planner`] with this choice.
    Planner(PlannerChoice),
}

impl Edit {
    /// Applies the edit to `ep` (the same call the page made).
    pub fn apply(&self, ep: &mut Episode) -> Result<(), SimError> {
        match self {
            Edit::Goal(g) => ep.set_goal(*g),
            Edit::Movers(m) => ep.set_movers(m.clone()),
            Edit::Planner(c) => ep.set_planner(c.clone()),
        }
    }
}

/// The setup an episode started from and the edits made to it since, each
/// with the step count ([`Episode::steps`]) at which it was made.
#[derive(Debug, Clone)]
pub struct Recording {
    origin: EpisodeSetup,
    edits: Vec<(u64, Edit)>,
}

impl Recording {
    /// Starts recording `ep` (before its first step or edit).
    pub fn of(ep: &Episode) -> Recording {
        Recording {
            origin: ep.setup(),
            edits: Vec::new(),
        }
    }

    /// Applies `edit` to `ep` and records it when it succeeds (a refused
    /// edit changes nothing, so it is not part of the run).
    pub fn edit(&mut self, ep: &mut Episode, edit: Edit) -> Result<(), SimError> {
        edit.apply(ep)?;
        self.edits.push((ep.steps(), edit));
        Ok(())
    }

    /// The edits so far with their step counts, in order.
    pub fn edits(&self) -> &[(u64, Edit)] {
        &self.edits
    }

    /// The setup the run started from.
    pub fn origin(&self) -> &EpisodeSetup {
        &self.origin
    }

    /// The recording of the run cut at step `steps`: the same origin and
    /// the edits made up to that step count (a branch continues from there).
    pub fn truncated(&self, steps: u64) -> Recording {
        Recording {
            origin: self.origin.clone(),
            edits: self
                .edits
                .iter()
                .filter(|(s, _)| *s <= steps)
                .cloned()
                .collect(),
        }
    }

    /// Rebuilds the run up to step `steps` (fewer when it ended earlier):
    /// the episode and how many edits it received.
    pub fn replay(&self, steps: u64) -> Result<(Episode, usize), SimError> {
        let mut ep = Episode::new(self.origin.clone())?;
        let mut applied = 0;
        self.advance(&mut ep, &mut applied, steps, |_, _| {}, |_| {})?;
        Ok((ep, applied))
    }

    /// Moves a replayed episode `ep` (that has received the first `applied`
    /// edits) on to step `steps`, applying the edits due on the way and
    /// those made at `steps`. Around every step `before(ep, last)` runs
    /// first (`last`: the step that reaches `steps`, e.g. to record what it
    /// draws) and `after(ep)` then. Stops early when the episode ends.
    pub fn advance(
        &self,
        ep: &mut Episode,
        applied: &mut usize,
        steps: u64,
        mut before: impl FnMut(&mut Episode, bool),
        mut after: impl FnMut(&mut Episode),
    ) -> Result<(), SimError> {
        loop {
            while let Some((at, e)) = self.edits.get(*applied) {
                if *at > ep.steps() {
                    break;
                }
                e.apply(ep)?;
                *applied += 1;
            }
            if ep.steps() >= steps || ep.outcome() != Outcome::Running {
                return Ok(());
            }
            before(ep, ep.steps() + 1 >= steps);
            ep.step();
            after(ep);
        }
    }

    /// Whether a replay of this run's origin that holds the first
    /// `applied` edits and stands at step `at` is on this run's course, so
    /// [`Recording::advance`] can take it further instead of replaying from
    /// the start: `applied_edits` are this run's first ones and no edit of
    /// this run made before step `at` is missing.
    pub fn continues(&self, applied_edits: &[(u64, Edit)], at: u64) -> bool {
        let n = applied_edits.len();
        self.edits.len() >= n
            && self.edits[..n] == *applied_edits
            && !matches!(self.edits.get(n), Some((s, _)) if *s < at)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::world::{MotionModel, MoverSpec};

    fn episode() -> Episode {
        // A 6 × 3 m room, start on the left, goal on the right.
        crate::sim::walled_room(30, 15, Default::default(), 5)
    }

    fn mover(id: u32) -> MoverSpec {
        MoverSpec {
            id,
            radius: 0.2,
            motion: MotionModel::ConstantVelocity {
                start: [3.0, 2.6],
                velocity: [0.0, -0.3],
                since: 0.0,
            },
        }
    }

    /// A run with a goal move at step 0, a mover at step 10 and another
    /// goal move at step 25, to the end.
    fn edited_run() -> (Episode, Recording) {
        let mut ep = episode();
        let mut rec = Recording::of(&ep);
        rec.edit(&mut ep, Edit::Goal([5.4, 2.0])).unwrap();
        for _ in 0..10 {
            ep.step();
        }
        rec.edit(&mut ep, Edit::Movers(vec![mover(1)])).unwrap();
        for _ in 0..15 {
            ep.step();
        }
        rec.edit(&mut ep, Edit::Goal([5.4, 1.0])).unwrap();
        // A refused edit (goal in a wall) is not recorded.
        assert!(rec.edit(&mut ep, Edit::Goal([0.05, 0.05])).is_err());
        ep.run();
        (ep, rec)
    }

    #[test]
    fn replay_reproduces_an_edited_run_bit_for_bit() {
        let (ep, rec) = edited_run();
        assert_eq!(ep.outcome(), Outcome::Reached);
        assert_eq!(rec.edits().len(), 3);
        let (again, applied) = rec.replay(ep.steps()).unwrap();
        assert_eq!(applied, 3);
        assert_eq!(again.trace().hash(), ep.trace().hash());
        assert_eq!(again.outcome(), ep.outcome());
        // Without the edits the run is a different one.
        let (plain, _) = Recording::of(&episode()).replay(ep.steps()).unwrap();
        assert_ne!(plain.trace().hash(), ep.trace().hash());
    }

    #[test]
    fn replay_to_a_frame_matches_the_prefix_and_advances_incrementally() {
        let (ep, rec) = edited_run();
        for k in [0u64, 9, 10, 11, 30] {
            let (part, _) = rec.replay(k).unwrap();
            assert_eq!(part.steps(), k);
            assert_eq!(
                part.trace().steps[..],
                ep.trace().steps[..=k as usize],
                "k = {k}"
            );
        }
        // Stepping a replay on in pieces gives the same as one go.
        let (mut inc, mut applied) = rec.replay(5).unwrap();
        let (mut lasts, mut afters) = (0, 0);
        rec.advance(
            &mut inc,
            &mut applied,
            20,
            |_, last| lasts += usize::from(last),
            |_| afters += 1,
        )
        .unwrap();
        assert_eq!((lasts, afters), (1, 15));
        assert!(rec.continues(&rec.edits()[..applied], inc.steps()));
        rec.advance(&mut inc, &mut applied, ep.steps(), |_, _| {}, |_| {})
            .unwrap();
        assert_eq!(inc.trace().hash(), ep.trace().hash());
        // A branch at step 10 keeps the edits made up to then.
        let b = rec.truncated(10);
        assert_eq!(b.edits().len(), 2);
        assert_eq!(
            b.replay(10).unwrap().0.trace(),
            rec.replay(10).unwrap().0.trace()
        );
        // A replay at step 26 holding only the first two edits missed the
        // goal move made at 25: it cannot be taken further; at 25 it can.
        assert!(!rec.continues(&rec.edits()[..2], 26));
        assert!(rec.continues(&rec.edits()[..2], 25));
        // Edits that are not this run's first ones do not continue it.
        assert!(!rec.continues(&rec.edits()[1..2], 5));
    }
}
