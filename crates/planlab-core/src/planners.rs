//! The planner catalogue: names, config fields and construction of every
//! local planner, so scenarios, the CLI (`planlab planners`, `planlab run
//! --planner`) and the pages pick planners by name.
//!
//! It sits above [`crate::local`], [`crate::apf`] and [`crate::lidar`] (it
//! builds their planners; none of them looks it up) and below the
//! simulator. Adding a planner: one arm in [`build`], one entry in
//! [`list`]. Its config is declared with [`crate::params`]'s `params!`
//! (one line per field: doc, unit, default, bounds); [`parse_config`]
//! reads it from the scenario's JSON with errors naming the field, and
//! [`field_infos`] lists its fields with their defaults.

use serde::{Deserialize, Serialize};

use crate::apf::local::{ApfLocal, ApfLocalConfig};
use crate::lidar::planner::{LidarPlannerConfig, ScanBaselineConfig, MOTION_GOAL};
use crate::lidar::rrt_shortcut::{RrtShortcut, RrtShortcutConfig};
use crate::lidar::rs_apf::{RsApf, RsApfConfig};
use crate::lidar::tangent_bug::{TangentBug, TangentBugConfig};
use crate::lidar::LidarPlanner;
use crate::local::cleaning;
use crate::local::dual::{DualConfig, PreliminaryConfig, SafeDualDwa};
use crate::local::dwa::{Dwa, DwaConfig};
use crate::local::engine::catalogue::CriticCatalogue;
use crate::local::improved::{Fusion53Config, ImprovedConfig, ImprovedDwa};
use crate::local::pursuit::{Pursuit, PursuitConfig};
use crate::local::ros::{dwb, move_base};
use crate::local::{LocalError, LocalPlanner};
use crate::params::{field_infos, parse_config, FieldInfo, Params};
use crate::world::{RobotSpec, RobotState, StaticMap};

/// The planner a scenario without a `local_planner` section uses.
pub const DEFAULT_PLANNER: &str = "dwa";

/// A planner chosen by name with its config as JSON (fields left out take
/// the paper's defaults; unknown fields are refused, naming them).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlannerChoice {
    /// Registry name, e.g. `dwa`.
    pub name: String,
    /// Config object for that planner.
    #[serde(default = "empty_object")]
    pub config: serde_json::Value,
}

impl PlannerChoice {
    /// The planner `name` with its default config (`{}`).
    pub fn named(name: impl Into<String>) -> Self {
        Self {
            name: name.into(),
            config: empty_object(),
        }
    }
}

impl Default for PlannerChoice {
    /// [`DEFAULT_PLANNER`] with its default config.
    fn default() -> Self {
        Self::named(DEFAULT_PLANNER)
    }
}

fn empty_object() -> serde_json::Value {
    serde_json::Value::Object(Default::default())
}

/// A registered planner.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PlannerInfo {
    /// Registry name.
    pub name: String,
    /// Paper and section it follows.
    pub paper: String,
    /// One-line summary.
    pub summary: String,
    /// The same for a beginner, in plain words: what it does, when it
    /// fails, what to look at on the canvas ([`plain_words`]).
    #[serde(default)]
    pub plain: String,
    /// Config fields.
    pub fields: Vec<FieldInfo>,
}

/// Every registered planner, in a fixed order.
pub fn list() -> Vec<PlannerInfo> {
    let mut all = entries();
    for p in &mut all {
        p.plain = plain_words(&p.name).to_string();
    }
    all
}

/// A plain-language paragraph for a beginner on the planner `name` (empty
/// for an unknown name): what it does, when it fails, and what to look at
/// on the canvas. The paper reference stays in [`PlannerInfo::paper`].
pub fn plain_words(name: &str) -> &'static str {
    match name {
        "dwa" => "Every step the robot imagines driving each speed and turn it could reach in the next moment for a second or two (the fan), throws away the ones that would hit something, and picks the one that points most at the goal, stays far from walls and is fast. It only looks a few metres ahead and has no map of the way round, so a wall pocket or C-shape between it and the goal traps it: it drives in and stops or circles. Watch the fan: orange rollouts score high, the green one is driven; when every rollout in front is grey the robot brakes and turns.",
        "improved-dwa" => "DWA with a guide: before it moves, A* finds a route on the map (the red line) and keeps only its corners (key points, the purple marks). The DWA steers to one key point after another instead of straight at the goal, so it goes round traps, and it sorts moving obstacles into kinds (the coloured discs) to keep more room from people. It can still fail when a moving obstacle blocks a narrow passage, or when a door's key point is passed and the next one is behind the wall beside it. Watch the temporary goal jump from corner to corner and the fan bend round obstacles.",
        "fusion-53" => "The earlier fusion the thesis compares against: A* key points as intermediate goals and a plain DWA between them, without the improved obstacle handling. It goes round traps like the improved DWA but reacts later to moving obstacles. Compare its trail with improved-dwa's on the same scene.",
        "safe-dual-dwa" => "A* that prefers to stay away from walls (safe A*) draws the route; only its few bends (feature nodes) become temporary goals. Near a temporary goal the robot keeps its speed instead of braking (the dual velocity model) and skips a node it has already passed. It is fast on open maps; it can circle when the next node lies behind a wall corner. Watch the speed plot stay flat where the preliminary fusion dips, and the star of the temporary goal move on.",
        "preliminary-fusion" => "The baseline of the safe-dual paper: every cell of the safe A* route is a temporary goal, and the DWA slows down for each one. It gets there, but slowly, with many speed drops; on some scenes it ends circling near a node without getting closer (shown as \"no progress toward the goal, still moving\"). Watch the speed plot saw up and down.",
        "pursuit" => "Not a real planner: it drives straight at the goal and brakes as it arrives, ignoring every obstacle. Use it to see what happens without obstacle avoidance: the run ends in a collision as soon as something is in the way.",
        "cleaning-dwa" => "A DWA for an omnidirectional cleaning robot (it can slide sideways): it follows an A* path through a costmap that grows walls by the robot's size, keeps its wheels loaded on bumps and corrects its odometry drift. It fails when the costmap closes a gap the robot could just pass. Watch the trail hug the path and the wheel-load plot.",
        "traditional-dwa" => "The cleaning DWA without its two additions (wheel-load limit and odometry correction), as the paper's comparison. Run it next to cleaning-dwa on a bumpy scene and compare the wheel-load plot and the tracking error.",
        "apf" => "Artificial potential field: the goal pulls the robot, every obstacle pushes it away, and the robot steps along the sum. Simple and smooth, but where pull and push cancel (an obstacle right in front of the goal, a narrow gap) it stops or shakes in place: a local minimum. Watch the path end short of the goal.",
        "sampling-apf" => "The potential field with a way out: when the robot stops making progress it samples points around itself and jumps to the best one, escaping most local minima. It can still wander in a dead end. Watch for the sudden sideways steps where plain APF would have stopped.",
        "lidar-dwa" => "Navigation with only a laser scanner, no map: the robot sorts the scan into edges and obstacles, puts a temporary goal beside the obstacle that blocks the way to the goal, and drives there with a DWA. It can be fooled by long walls that hide the way round. Turn on LiDAR to see the scan, the coloured edges and the temporary goal star.",
        "lidar-apf" => "The same LiDAR temporary goals, driven with a potential field instead of a DWA. Smoother near gaps, more prone to stopping between two close obstacles. Compare its trail with lidar-dwa's.",
        "scan-apf" => "A potential field computed from the laser hits only (no map): each hit pushes, the goal pulls. Like APF it can stop where forces cancel. Turn on LiDAR to see which hits push.",
        "scan-dwa" => "A DWA that sees the world only through the laser scan (no map): rollouts are checked against the hit points. It avoids what it sees but, like plain DWA, has no plan for getting round long walls. Turn on LiDAR and watch the fan: rollouts end where the scan shows a hit.",
        "tangent-bug" => "A classic bug algorithm: drive straight at the goal; when the scan shows an obstacle in the way, head for the edge of it that promises the shortest way round, and follow the wall until the goal is in reach again. Complete on simple maps but long-winded. Watch it switch between going to the goal and wall-following.",
        "rs-apf" => "Plans a short virtual path with a potential field on the points the laser has seen, shortens it, and drives along it with a DWA; if the virtual path stalls it follows the obstacle. Watch the purple virtual path redraw as more of the map is seen.",
        "rrt-shortcut" => "Grows a random tree (RRT) over the map the laser has revealed so far, shortcuts the path it finds, and follows it; replans when new walls appear. Random but seeded: the same seed gives the same run. Watch the path change as the fog clears.",
        "move-base-dwa" => "The classic ROS 1 navigation stack: a global path is planned once on a costmap that grows every wall by the robot's size plus a fading band (the red line), and every step the robot tries a few forward speeds and many turn rates for a second, scoring each by how far its end lands from the path and from a point of the path a few metres ahead, plus how close it came to walls. If it faces the wrong way it turns on the spot first; if nothing is safe it backs up a little. It can hesitate in doorways narrower than the grown walls and stops short of movers that block the corridor. Watch the fan bend toward the path.",
        "dwb" => "The ROS 2 (Nav2) successor of the ROS 1 planner: the same idea of trying speeds and turns along a planned path, but scored by a list of critics you can change: stay on the path, point along it, head for its end, keep off walls, do not wobble, slow down and turn at the goal. The global path is replanned every second, so moving people are routed around. It stops when every trajectory is ruled out. Watch the fan: each rollout's colour is its total cost.",
        _ => "",
    }
}

fn entries() -> Vec<PlannerInfo> {
    vec![
        PlannerInfo {
            plain: String::new(),
            name: "dwa".into(),
            paper: "[T] Wu 2022 §3.1, eq 3-1…3-5 (Fox, Burgard & Thrun 1997); \
                    docs/algorithms.md §dwa"
                .into(),
            summary: "Baseline dynamic window approach straight to the final goal: \
                      window V_s ∩ V_d ∩ V_a, rollouts, normalised heading / clearance / \
                      velocity critics."
                .into(),
            fields: field_infos::<DwaConfig>(),
        },
        PlannerInfo {
            plain: String::new(),
            name: "improved-dwa".into(),
            paper: "[T] Wu 2022 §3.2 (Table 3-1, eq 3-7/3-8); \
                    docs/algorithms.md §improved-dwa"
                .into(),
            summary: "A* key points as intermediate goals; movers classified ordinary \
                      dynamic / static / special with deceleration or detour weights and \
                      virtual goals; relative distance factor ρ near the goal."
                .into(),
            fields: field_infos::<ImprovedConfig>(),
        },
        PlannerInfo {
            plain: String::new(),
            name: "fusion-53".into(),
            paper: "[T] Wu 2022 §3.2–3.3, its reference [53]; docs/algorithms.md §fusion-53".into(),
            summary: "Baseline fusion: A* key points + DWA with the deceleration weights \
                      while a moving obstacle is near, plain DWA otherwise; no \
                      classification, virtual goal or ρ."
                .into(),
            fields: field_infos::<Fusion53Config>(),
        },
        PlannerInfo {
            plain: String::new(),
            name: "safe-dual-dwa".into(),
            paper: "[S] Ge & Li 2022 §2–4 (eq 9–12, §4.2, §5); \
                    docs/algorithms.md §safe-dual-dwa"
                .into(),
            summary: "Safe A* path → Bottom-Up feature nodes as temporary goals; dual \
                      velocity model (speed held within d of a temporary goal); detour \
                      replanning (θa ≥ 90° → next temporary goal)."
                .into(),
            fields: field_infos::<DualConfig>(),
        },
        PlannerInfo {
            plain: String::new(),
            name: "preliminary-fusion".into(),
            paper: "[S] Ge & Li 2022 §2.4 baseline; docs/algorithms.md §preliminary-fusion".into(),
            summary: "Baseline fusion: every safe A* path node a temporary goal, the normal \
                      DWA window (the robot slows at each)."
                .into(),
            fields: field_infos::<PreliminaryConfig>(),
        },
        PlannerInfo {
            plain: String::new(),
            name: "pursuit".into(),
            paper: "none (test baseline)".into(),
            summary: "Naive baseline: steers straight at the goal with a braking profile; \
                  no obstacle avoidance."
                .into(),
            fields: field_infos::<PursuitConfig>(),
        },
        PlannerInfo {
            plain: String::new(),
            name: "cleaning-dwa".into(),
            paper: "[C] Zhang et al. 2020 §2–3; docs/algorithms.md §cleaning-dwa".into(),
            summary: "Cleaning-robot DWA (omnidirectional v_x, v_y, ω) along an A* path: \
                      costmap + Manhattan goal / path costs, vertical-load acceleration \
                      limit, least-squares odometry compensation."
                .into(),
            fields: cleaning::field_list(false),
        },
        PlannerInfo {
            plain: String::new(),
            name: "traditional-dwa".into(),
            paper: "[C] Zhang et al. 2020 baseline; docs/algorithms.md §cleaning-dwa".into(),
            summary: "[C]'s traditional DWA: the cleaning DWA's cost without the load \
                      limit and without odometry compensation."
                .into(),
            fields: cleaning::field_list(true),
        },
        PlannerInfo {
            plain: String::new(),
            name: "move-base-dwa".into(),
            paper: "ROS 1 move_base + base_local_planner TrajectoryPlannerROS (dwa: true), \
                    NavFn-style global path; docs/algorithms.md §move-base-dwa"
                .into(),
            summary: "ROS baseline: window over one control period, vx × vtheta samples plus \
                      in-place rotations, cost 0.6·path + 0.8·goal distance (cells, MapGrid) \
                      + 0.01·footprint cost, oscillation flags and escape; plan on the \
                      inflated costmap."
                .into(),
            fields: field_infos::<move_base::MoveBaseConfig>(),
        },
        PlannerInfo {
            plain: String::new(),
            name: "dwb".into(),
            paper: "Nav2 DWB controller (dwb_core, dwb_critics, StandardTrajectoryGenerator), \
                    NavFn-style global path; docs/algorithms.md §dwb"
                .into(),
            summary: "ROS 2 baseline: 20 × 20 samples over one control period, rollouts of \
                      1.7 s, critics by name (BaseObstacle, GoalAlign, PathAlign, PathDist, \
                      GoalDist, RotateToGoal, Oscillation) with Nav2's scales, lowest cost wins."
                .into(),
            fields: field_infos::<dwb::DwbConfig>(),
        },
        PlannerInfo {
            plain: String::new(),
            name: "apf".into(),
            paper: "[T] Wu 2022 §4.1, eq 4-1…4-4; docs/algorithms.md §apf".into(),
            summary: "Basic artificial potential field: one fixed step along the resultant of \
                      goal attraction and mover / nearest-wall repulsion, pursued within the \
                      robot's limits."
                .into(),
            fields: field_infos::<ApfLocalConfig>(),
        },
        PlannerInfo {
            plain: String::new(),
            name: "sampling-apf".into(),
            paper: "[T] Wu 2022 §4.2, eq 4-5…4-14; docs/algorithms.md §apf".into(),
            summary: "Sampling-based improved APF: 13 directions ±90° around the resultant, \
                      cost 0.3‖F_attr‖ + 0.7‖F_rep‖, relative distance rule, predicted movers \
                      (t+1, t+2) with virtual repulsion; the APF point is pursued."
                .into(),
            fields: field_infos::<ApfLocalConfig>(),
        },
        PlannerInfo {
            plain: String::new(),
            name: "lidar-dwa".into(),
            paper: "[L] Chang et al. 2024 §2–4 (Alg. 1–2, eq 1–4, Table 1); \
                    docs/algorithms.md §lidar"
                .into(),
            summary: "Unknown map, LiDAR only: edges, gap removal, obstacle patterns and \
                      temporary goals around the OP blocking the goal; DWA drives to the \
                      target on a local map built from the scan."
                .into(),
            fields: field_infos::<LidarPlannerConfig<DwaConfig>>(),
        },
        PlannerInfo {
            plain: String::new(),
            name: "lidar-apf".into(),
            paper: "[L] Chang et al. 2024 §2–4, sims 8–9 (APF [9] underneath); \
                    docs/algorithms.md §lidar"
                .into(),
            summary: "The LiDAR temporary-goal navigator over the basic APF (eq 4-1…4-4) \
                      on a local map built from the scan."
                .into(),
            fields: field_infos::<LidarPlannerConfig<ApfLocalConfig>>(),
        },
        PlannerInfo {
            plain: String::new(),
            name: "scan-apf".into(),
            paper: "[L] Chang et al. 2024 §4.2 baseline (sim 8); \
                    docs/algorithms.md §scan-baselines"
                .into(),
            summary: "Plain APF straight to the goal on an unknown map: only the scan's \
                      local map, no temporary goals, no global path."
                .into(),
            fields: field_infos::<ScanBaselineConfig<ApfLocalConfig>>(),
        },
        PlannerInfo {
            plain: String::new(),
            name: "scan-dwa".into(),
            paper: "[L] Chang et al. 2024 §4.2 baseline; docs/algorithms.md §scan-baselines".into(),
            summary: "Plain DWA straight to the goal on an unknown map: only the scan's \
                      local map, no temporary goals, no global path."
                .into(),
            fields: field_infos::<ScanBaselineConfig<DwaConfig>>(),
        },
        PlannerInfo {
            plain: String::new(),
            name: "tangent-bug".into(),
            paper: "TangentBug (Kamon, Rivlin & Rimon 1998) standing in for \
                    Critical-PointBug, [L] Chang et al. 2024 ref [21], sim 6; \
                    docs/algorithms.md §tangent-bug"
                .into(),
            summary: "Unknown map, scan + pose: motion to the tangent-graph endpoint \
                      minimising d(x,O)+d(O,goal), boundary following when that stops \
                      decreasing, leaving when d_reach < d_followed; baseline DWA on the \
                      scan's local map drives."
                .into(),
            fields: field_infos::<TangentBugConfig>(),
        },
        PlannerInfo {
            plain: String::new(),
            name: "rs-apf".into(),
            paper: "RS-APF (Li, Tamura, Yamashita & Asama 2013), [L] Chang et al. 2024 \
                    ref [11], sim 8 — scan-only receding-horizon variant of an offline \
                    planner; docs/algorithms.md §rs-apf"
                .into(),
            summary: "Unknown map, scan + pose: every period a virtual point descends the \
                      basic APF on the scan (following the obstacle after a stall), the \
                      regression search shortens that path, and the baseline DWA on the \
                      scan's local map drives to its first corner."
                .into(),
            fields: field_infos::<RsApfConfig>(),
        },
        PlannerInfo {
            plain: String::new(),
            name: "rrt-shortcut".into(),
            paper: "RRT (LaValle 1998) with shortcutting standing in for RL-RRT, \
                    [L] Chang et al. 2024 ref [2], sim 7 — no learned component; \
                    docs/algorithms.md §rrt-shortcut"
                .into(),
            summary: "Unknown map, scan + pose: an occupancy memory of what the scan has \
                      shown (unknown counts as free); a goal-biased RRT over it, inflated by \
                      the robot, shortened by line-of-sight shortcuts and replanned when \
                      blocked, off course or stalled; the baseline DWA on the scan's local \
                      map drives to the next waypoint."
                .into(),
            fields: field_infos::<RrtShortcutConfig>(),
        },
    ]
}

/// Builds the planner `choice` names for `robot` on `map`, starting at
/// `start` and heading for `goal` (world metres). Config errors name the
/// field; an unknown name is [`LocalError::UnknownPlanner`].
pub fn build(
    choice: &PlannerChoice,
    robot: &RobotSpec,
    map: &StaticMap,
    start: &RobotState,
    goal: [f64; 2],
) -> Result<Box<dyn LocalPlanner>, LocalError> {
    match choice.name.as_str() {
        "dwa" => configured(choice, |c| Dwa::new(c, robot, goal)),
        "improved-dwa" => configured(choice, |c| {
            ImprovedDwa::improved(c, robot, map, start, goal)
        }),
        "fusion-53" => configured(choice, |c| {
            ImprovedDwa::fusion53(c, robot, map, start, goal)
        }),
        "safe-dual-dwa" => configured(choice, |c| {
            SafeDualDwa::safe_dual(c, robot, map, start, goal)
        }),
        "preliminary-fusion" => configured(choice, |c| {
            SafeDualDwa::preliminary(c, robot, map, start, goal)
        }),
        "pursuit" => configured(choice, |c| Pursuit::new(c, robot, goal)),
        name @ ("cleaning-dwa" | "traditional-dwa") => {
            let name = if name == "cleaning-dwa" {
                "cleaning-dwa"
            } else {
                "traditional-dwa"
            };
            let cfg = cleaning::parse(name, &choice.config)?;
            let planner = cleaning::CleaningDwa::new(name, cfg, robot, map, start, goal)?;
            Ok(Box::new(planner))
        }
        "move-base-dwa" => configured(choice, |c| {
            move_base::build(&c, robot, map, [start.x, start.y], goal)
        }),
        "dwb" => configured(choice, |c| {
            dwb::build(
                &c,
                &CriticCatalogue::standard(),
                robot,
                map,
                [start.x, start.y],
                goal,
            )
        }),
        name @ ("apf" | "sampling-apf") => {
            configured(choice, |c| ApfLocal::new(name == "apf", c, robot, goal))
        }
        "lidar-dwa" => navigator("lidar-dwa", choice, robot, dwa_motion),
        "lidar-apf" => navigator("lidar-apf", choice, robot, apf_motion),
        "scan-apf" => scan_baseline("scan-apf", choice, robot, apf_motion),
        "scan-dwa" => scan_baseline("scan-dwa", choice, robot, dwa_motion),
        "tangent-bug" => configured(choice, |c| TangentBug::new(c, robot)),
        "rs-apf" => configured(choice, |c| RsApf::new(c, robot)),
        "rrt-shortcut" => configured(choice, |c| RrtShortcut::new(c, robot)),
        _ => Err(LocalError::UnknownPlanner(choice.name.clone())),
    }
}

/// Whether `name` is a registered planner.
pub fn is_registered(name: &str) -> bool {
    list().iter().any(|p| p.name == name)
}

/// Builds a LiDAR planner's motion planner from its config.
type MotionBuilder<M> = fn(M, &RobotSpec) -> Result<Box<dyn LocalPlanner>, LocalError>;

/// The baseline DWA as the motion planner under a LiDAR navigator.
fn dwa_motion(cfg: DwaConfig, robot: &RobotSpec) -> Result<Box<dyn LocalPlanner>, LocalError> {
    Ok(Box::new(Dwa::new(cfg, robot, MOTION_GOAL)?))
}

/// The basic APF (`apf`) as the motion planner under a LiDAR navigator.
fn apf_motion(cfg: ApfLocalConfig, robot: &RobotSpec) -> Result<Box<dyn LocalPlanner>, LocalError> {
    Ok(Box::new(ApfLocal::new(true, cfg, robot, MOTION_GOAL)?))
}

/// `new` applied to `choice`'s config read as `C` (errors name the field),
/// boxed.
fn configured<C: Params, P: LocalPlanner + 'static>(
    choice: &PlannerChoice,
    new: impl FnOnce(C) -> Result<P, LocalError>,
) -> Result<Box<dyn LocalPlanner>, LocalError> {
    Ok(Box::new(new(parse_config(&choice.name, &choice.config)?)?))
}

/// The navigator planner `name` (`lidar-dwa`, `lidar-apf`) of `choice`
/// over the motion planner `motion` builds from its config.
fn navigator<M: Params + Clone>(
    name: &'static str,
    choice: &PlannerChoice,
    robot: &RobotSpec,
    motion: MotionBuilder<M>,
) -> Result<Box<dyn LocalPlanner>, LocalError> {
    configured(choice, |cfg: LidarPlannerConfig<M>| {
        let motion = motion(cfg.motion.clone(), robot)?;
        LidarPlanner::with_nav(name, &cfg, motion, robot)
    })
}

/// The scan-only baseline `name` (`scan-dwa`, `scan-apf`) of `choice`
/// over the motion planner `motion` builds from its config.
fn scan_baseline<M: Params + Clone>(
    name: &'static str,
    choice: &PlannerChoice,
    robot: &RobotSpec,
    motion: MotionBuilder<M>,
) -> Result<Box<dyn LocalPlanner>, LocalError> {
    configured(choice, |cfg: ScanBaselineConfig<M>| {
        let motion = motion(cfg.motion.clone(), robot)?;
        LidarPlanner::baseline(name, &cfg, motion, robot)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::local::testkit;
    use serde_json::json;

    #[test]
    fn every_field_documented_and_names_unique() {
        let all = list();
        for p in &all {
            for f in &p.fields {
                assert!(!f.doc.is_empty(), "{}.{} has no doc", p.name, f.name);
                assert!(!f.default.is_null(), "{}.{} has no default", p.name, f.name);
            }
            assert_eq!(all.iter().filter(|q| q.name == p.name).count(), 1);
        }
        assert!(is_registered("pursuit"));
    }

    /// Table and struct agree: every listed field, set to its listed
    /// default at its dotted name, is a field the planner's config accepts
    /// (unknown fields are refused), and the planner builds from them.
    #[test]
    fn the_table_written_back_as_a_config_builds_the_planner() {
        let map = testkit::map(&format!("{}\n", ".".repeat(40)).repeat(30), 0.1);
        let start = RobotState {
            x: 0.5,
            y: 1.5,
            ..Default::default()
        };
        for p in list() {
            let mut config = json!({});
            for f in &p.fields {
                let mut at = &mut config;
                for k in f.name.split('.') {
                    at = &mut at[k];
                }
                *at = f.default.clone();
            }
            let choice = PlannerChoice {
                name: p.name.clone(),
                config,
            };
            let built = build(&choice, &RobotSpec::default(), &map, &start, [3.5, 1.5]);
            assert!(built.is_ok(), "{}: {:?}", p.name, built.err());
        }
        // A name the config does not have is refused.
        let choice = PlannerChoice {
            name: "dwa".into(),
            config: json!({"dwa": {"alpha": 1.0}}),
        };
        let e = build(&choice, &RobotSpec::default(), &map, &start, [3.5, 1.5]);
        assert!(e.is_err());
    }
}
