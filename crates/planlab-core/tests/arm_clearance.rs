//! The arm episode's whole-arm check keeps the links off the hand
//! (docs/algorithms.md §arm, whole-arm check).

use planlab_core::arm::episode::ARM_CLEARANCE_M;
use planlab_core::arm::{ArmEpisode, ArmPredictor, HandPreset};
use planlab_core::scenario::arm::ArmScenario;
use planlab_core::sim::Outcome;

/// T-tab5-3 with the target dragged 0.1 m down (the page's sliders), the
/// hand reaching toward the robot, RNN predictor: the links used to creep
/// up to the hand, each planned move ending a hair short of contact, until
/// the arm pressed against it (0.0005 m away, drawn inside it, every
/// candidate refused) and the run ended stuck. Now no move ends nearer than
/// `ARM_CLEARANCE_M` (5 mm) while getting nearer; it stays over 2 mm away.
#[test]
fn an_arm_blocked_by_the_hand_keeps_its_clearance_instead_of_pressing_against_it() {
    let text = include_str!("../../../assets/scenarios/T-tab5-3.json");
    let mut s = ArmScenario::from_json(text).unwrap();
    s.arm.hand.preset = HandPreset::ReachToward;
    s.arm.goal[2] -= 0.1;
    ArmPredictor::Rnn.apply(&mut s.arm.apf);
    let mut ep = ArmEpisode::from_scenario(&s).unwrap();
    let mut closest_end = f64::INFINITY;
    while ep.outcome() == Outcome::Running {
        ep.step().unwrap();
        closest_end = closest_end.min(ep.distance_now());
    }
    assert!(
        ep.min_distance() > 0.002,
        "the arm came {} m from the hand ({:?} after {} refusals)",
        ep.min_distance(),
        ep.outcome(),
        ep.refusals()
    );
    assert!(
        !(ep.outcome() == Outcome::Stuck && ep.distance_now() < 0.002),
        "stuck pressed against the hand, {} m away",
        ep.distance_now()
    );
    assert!(closest_end > 0.002, "{closest_end}");
    const { assert!(ARM_CLEARANCE_M > 0.002) };
}
