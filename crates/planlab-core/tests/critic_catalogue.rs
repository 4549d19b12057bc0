//! Adding a critic is one file and one catalogue line: a critic defined
//! here, registered under a name and listed in DWB's `critics`, changes
//! the command DWB chooses.

use std::sync::Arc;

use planlab_core::local::engine::catalogue::CriticCatalogue;
use planlab_core::local::engine::generator::Trajectory;
use planlab_core::local::engine::{Critic, CriticContext, CriticSlot};
use planlab_core::local::ros::dwb::{self, DwbConfig};
use planlab_core::local::{LocalError, LocalPlanner, Observation};
use planlab_core::map::{OccupancyGrid, Pose2};
use planlab_core::params::{check_param, Bound};
use planlab_core::world::{RobotSpec, RobotState, StaticMap};
use serde_json::json;

/// Prefers turning left: the cost falls as ω rises (default scale 1e5,
/// enough to outweigh the path critics).
#[derive(Debug)]
struct PreferLeft;

impl Critic for PreferLeft {
    fn name(&self) -> &str {
        "PreferLeft"
    }
    fn score(&self, _ctx: &CriticContext<'_>, traj: &Trajectory) -> Option<f64> {
        Some(-traj.sample.cmd.w)
    }
}

fn open_map() -> StaticMap {
    let g = OccupancyGrid::from_ascii(&format!("{}\n", ".".repeat(60)).repeat(40))
        .unwrap()
        .with_frame(0.1, Pose2::default())
        .unwrap();
    StaticMap::new(g, true).unwrap()
}

/// The first command of DWB driving along +x toward a goal straight ahead.
fn first_command(cfg: &DwbConfig, cat: &CriticCatalogue) -> Result<f64, LocalError> {
    let map = open_map();
    let robot = RobotSpec::default();
    let state = RobotState {
        x: 1.0,
        y: 2.0,
        v: 0.3,
        ..Default::default()
    };
    let goal = [5.0, 2.0];
    let mut p = dwb::build(cfg, cat, &robot, &map, [state.x, state.y], goal)?;
    let cmd = p.step(&Observation {
        time: 0.0,
        dt: 0.1,
        state: &state,
        goal,
        map: &map,
        map_revision: 0,
        scan: None,
        movers: &[],
        odometry: None,
        accel_z: 0.0,
    });
    Ok(cmd.w)
}

#[test]
fn a_registered_critic_changes_the_dwb_choice() {
    let mut cat = CriticCatalogue::standard();
    cat.register(
        "PreferLeft",
        Arc::new(|_env, prefix, config| {
            let scale = config.get("scale").and_then(|v| v.as_f64()).unwrap_or(1e5);
            check_param(&format!("{prefix}.scale"), scale, Bound::at_least(0.0))?;
            Ok(CriticSlot::new(PreferLeft, scale))
        }),
    );
    let plain = DwbConfig::default();
    let w_plain = first_command(&plain, &cat).unwrap();
    let mut with = DwbConfig::default();
    with.critics.push("PreferLeft".into());
    let w_left = first_command(&with, &cat).unwrap();
    // Without it DWB keeps close to straight ahead; with it the top turn
    // rate of the window (the robot's ω_max, 40°/s) wins.
    let w_max = RobotSpec::default().limits.w_max;
    assert!(w_plain.abs() < 0.1, "without PreferLeft ω = {w_plain}");
    assert!(
        (w_left - w_max).abs() < 1e-9,
        "with PreferLeft ω = {w_left}"
    );
    // Its config is read and checked like any other critic's.
    with.critic_config = json!({"PreferLeft": {"scale": f64::MAX}});
    let e = first_command(&with, &cat).unwrap_err().to_string();
    assert!(e.contains("PreferLeft.scale"), "{e}");
    // Not registered: the name is refused with the known ones listed.
    let e = first_command(&with, &CriticCatalogue::standard())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("unknown critic `PreferLeft`") && e.contains("PathAlign"),
        "{e}"
    );
}
