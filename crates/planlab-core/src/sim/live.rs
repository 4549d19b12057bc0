//! Live changes to a running episode beyond goal and movers: swapping or
//! re-tuning the local planner (the page's planner select and sliders).

use super::{Episode, SimError};
use crate::planners::{self, PlannerChoice};

impl Episode {
    /// Replaces the local planner with `choice`, built at the robot's
    /// current state for the current goal (a re-tuned weight takes effect
    /// from the next step). On error (unknown name, bad config naming the
    /// field, no global path from here) the old planner stays in force.
    /// [`Episode::setup`] then restarts with the new choice.
    pub fn set_planner(&mut self, choice: PlannerChoice) -> Result<(), SimError> {
        if let Some(c) = &self.car {
            c.spec().check_follower(&choice.name)?;
        }
        let mut planner = planners::build(&choice, &self.robot, &self.map, &self.state, self.goal)?;
        planner.set_record_rollouts(self.config.record_rollouts);
        planner.set_seed(self.seed);
        if let Some(c) = &mut self.car {
            c.annotate(planner.debug());
        }
        self.planner = planner;
        self.choice = choice;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::Outcome;

    fn episode(planner: &str) -> Episode {
        // A 4 × 2 m room, start on the left, goal on the right.
        crate::sim::walled_room(20, 10, PlannerChoice::named(planner), 0)
    }

    #[test]
    fn set_planner_swaps_keeps_state_and_refuses_bad_configs() {
        let name = planners::list()
            .first()
            .map(|p| p.name.clone())
            .expect("a registered planner");
        let mut ep = episode(&name);
        for _ in 0..5 {
            ep.step();
        }
        let (t, s) = (ep.time(), *ep.state());
        ep.set_planner(PlannerChoice::named(name.clone())).unwrap();
        // Same place and time; the episode goes on from there.
        assert_eq!((ep.time(), *ep.state()), (t, s));
        assert_eq!(ep.planner_choice().name, name);
        let e = ep
            .set_planner(PlannerChoice {
                name: name.clone(),
                config: serde_json::json!({"no_such_field": 1}),
            })
            .unwrap_err();
        assert!(e.to_string().contains("no_such_field"), "{e}");
        let e = ep
            .set_planner(PlannerChoice::named("teleport"))
            .unwrap_err();
        assert!(e.to_string().contains("teleport"), "{e}");
        // The old planner is still in force and drives to the goal.
        assert_eq!(ep.planner_choice().name, name);
        assert_eq!(ep.run(), Outcome::Reached);
        // A restart keeps the chosen planner.
        assert_eq!(ep.setup().planner.name, name);
    }
}
