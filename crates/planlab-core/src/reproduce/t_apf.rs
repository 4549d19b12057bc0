//! Experiments of \[T\] Wu 2022 ch. 4 (potential fields): ids `T-fig4-6`,
//! `T-fig4-8`, `T-fig4-10`, `T-fig4-11`, `T-fig4-12`, `T-tab4-1`.
//!
//! The presets (`assets/scenarios/T-fig4-*.json`, `T-tab4-1.json`, made by
//! `scripts/gen_apf_scenarios.py`) are kinematic APF scenes (an `apf`
//! section): a point robot stepping 0.04 m among discs (2D) or a sphere
//! (3D, `T-tab4-1`). The runs switch the variant with `apf.config.mode`
//! (and the relative distance rule with `apf.config.relative_distance`).
//! Each family perturbs across what still is the figure's situation, with
//! its scene check as a test: Fig 4-6's points slide along their line (the
//! local minimum is the collinear scene; off the line the field has a
//! sideways part); Fig 4-8's goal sits anywhere in the disc's 0.15 m
//! repulsion range on the robot's side; the moving disc's line lies in the
//! band of offsets around each figure's (head-on ≤ 1 cm, Fig 4-11 2–7 cm,
//! Fig 4-12 7–13 cm), its start ±5 cm along its line, its speed ±20 %.

use super::clause::{diff, effect, ok, outcome, reached};
use super::{Deviation, Family, PathExperiment, Perturbation, RunSpec, Runs};
use crate::apf::ApfMetrics;
use crate::sim::Outcome;
use serde_json::Value;

const FIG4_6: &str = include_str!("../../../../assets/scenarios/T-fig4-6.json");
const FIG4_8: &str = include_str!("../../../../assets/scenarios/T-fig4-8.json");
const FIG4_10: &str = include_str!("../../../../assets/scenarios/T-fig4-10.json");
const FIG4_11: &str = include_str!("../../../../assets/scenarios/T-fig4-11.json");
const FIG4_12: &str = include_str!("../../../../assets/scenarios/T-fig4-12.json");
const TAB4_1: &str = include_str!("../../../../assets/scenarios/T-tab4-1.json");

type R = Runs<ApfMetrics>;

/// The three variants of \[T\] Fig 4-10…4-12 / Table 4-1.
fn three(scenario: &'static str) -> Vec<RunSpec> {
    [
        ("apf", "basic"),
        ("sampling", "sampling"),
        ("sampling+prediction", "sampling-prediction"),
    ]
    .into_iter()
    .map(|(name, mode)| RunSpec {
        name,
        scenario_json: scenario,
        planner: None,
        set: vec![("apf.config.mode", mode)],
    })
    .collect()
}

fn length(r: &R, name: &str) -> f64 {
    r.get(name).map_or(f64::NAN, |m| m.path_length_m)
}

fn spikes(r: &R, name: &str) -> u32 {
    r.get(name).map_or(u32::MAX, |m| m.spikes)
}

/// Path length basic > sampling > sampling+prediction.
fn ordered(r: &R) -> bool {
    length(r, "apf") > length(r, "sampling")
        && length(r, "sampling") > length(r, "sampling+prediction")
}

/// "Path length basic > sampling > sampling+prediction", with the
/// prediction's gain over the basic path as its effect.
fn lengths_fall() -> super::Clause<ApfMetrics> {
    effect(
        "lengths fall",
        "path length basic > sampling > sampling+prediction",
        |r| all_ok(r) && ordered(r),
        diff("path prediction − basic", "m", |r| {
            all_ok(r).then(|| length(r, "sampling+prediction") - length(r, "apf"))
        }),
    )
}

fn all_ok(r: &R) -> bool {
    r.metrics.keys().all(|k| ok(r, k))
}

/// Start or goal slid along the robot's line (the x axis) by up to 5 cm:
/// the scenes are defined by where the disc is relative to that line, so
/// sliding keeps them; the disc's offset is the disc's own range.
fn slide(which: &'static str, why: &'static str) -> super::Range {
    Perturbation::Box {
        what: which,
        x: [-0.05, 0.05],
        y: [0.0, 0.0],
        z: [0.0, 0.0],
        speed_rel: 0.0,
    }
    .because(why)
}

/// A mover whose line is offset from the robot's by `offset` ∈ [lo, hi]
/// m (the preset's offset is `at`), started up to 5 cm earlier or later
/// along its line, at ±20 % speed.
fn mover_band(at: f64, lo: f64, hi: f64, why: &'static str) -> super::Range {
    Perturbation::Box {
        what: "apf.obstacles",
        x: [-0.05, 0.05],
        y: [lo - at, hi - at],
        z: [0.0, 0.0],
        speed_rel: 0.2,
    }
    .because(why)
}

/// Fig 4-6: start, disc and goal on one line.
fn family_collinear() -> Family {
    Family {
        perturbations: vec![
            slide(
                "start",
                "along the line, ±5 cm: the scene is start, disc and goal on one line (Fig 4-1); \
                 the start stays ≥ 0.1 m outside the disc's 0.15 m repulsion range",
            ),
            slide(
                "goal",
                "along the line, ±5 cm: the goal stays ≥ 0.15 m beyond the disc's range",
            ),
            Perturbation::Box {
                what: "apf.obstacles",
                x: [-0.1, 0.1],
                y: [0.0, 0.0],
                z: [0.0, 0.0],
                speed_rel: 0.0,
            }
            .because(
                "the still disc anywhere on the middle of the line (±0.1 m): off the line it is \
                 another scene, where the field has a sideways part and no minimum",
            ),
        ],
    }
}

/// Fig 4-8: the goal inside the disc's repulsion range, on the robot's side.
fn family_goal_in_range() -> Family {
    Family {
        perturbations: vec![
            Perturbation::start(0.05)
                .because("within 5 cm: the start is 0.85 m from the disc, far outside its range"),
            Perturbation::Box {
                what: "goal",
                x: [-0.09, 0.04],
                y: [-0.02, 0.02],
                z: [0.0, 0.0],
                speed_rel: 0.0,
            }
            .because(
                "the goal's gap to the disc's surface (0.05 m in the preset) anywhere from about \
                 0.01 to 0.14 m: the whole 0.15 m repulsion range on the robot's side, which is \
                 the situation of Fig 4-7 (the goal where repulsion and attraction meet)",
            ),
        ],
    }
}

/// Fig 4-10: a disc moving head-on along the robot's line.
fn family_head_on() -> Family {
    Family {
        perturbations: vec![
            slide("start", "along the line, ±5 cm: the same head-on approach"),
            slide(
                "goal",
                "along the line, ±5 cm: the goal stays behind the mover's start",
            ),
            mover_band(
                0.0,
                -0.01,
                0.01,
                "head-on: the mover's line within 1 cm of the robot's (a quarter of Fig 4-11's \
                 4 cm offset, which is the next figure's scene); its start ±5 cm along the \
                 line, its speed ±20 %",
            ),
        ],
    }
}

/// Fig 4-11: the mover's line offset 4 cm.
fn family_offset() -> Family {
    Family {
        perturbations: vec![
            slide("start", "along the line, ±5 cm: the same crossing"),
            slide("goal", "along the line, ±5 cm: the same crossing"),
            mover_band(
                0.04,
                0.02,
                0.07,
                "the mover's line offset 2–7 cm: from halfway to head-on (Fig 4-10, 0) to \
                 halfway to little overlap (Fig 4-12, 0.1 m); start ±5 cm, speed ±20 %",
            ),
        ],
    }
}

/// Fig 4-12: the mover's line offset 0.1 m.
fn family_little_overlap() -> Family {
    Family {
        perturbations: vec![
            slide("start", "along the line, ±5 cm: the same passing"),
            slide("goal", "along the line, ±5 cm: the same passing"),
            mover_band(
                0.1,
                0.07,
                0.13,
                "the mover's line offset 7–13 cm: beyond Fig 4-11's band, and the disc's \
                 repulsion range (0.05 + 0.15 m) still reaches the robot's line, the little \
                 overlap of Fig 4-12; start ±5 cm, speed ±20 %",
            ),
        ],
    }
}

/// Table 4-1 (3D): the hand reaching head-on, 4 cm below the gripper's line.
fn family_3d() -> Family {
    let along = |path: &'static str, why: &'static str| {
        Perturbation::Box {
            what: path,
            x: [-0.05, 0.05],
            y: [0.0, 0.0],
            z: [0.0, 0.0],
            speed_rel: 0.0,
        }
        .because(why)
    };
    Family {
        perturbations: vec![
            along(
                "apf.start",
                "along the gripper's line, ±5 cm: the same crossing",
            ),
            along(
                "apf.goal",
                "along the gripper's line, ±5 cm: the same crossing",
            ),
            Perturbation::Box {
                what: "apf.obstacles",
                x: [-0.05, 0.05],
                y: [-0.01, 0.01],
                z: [-0.03, 0.02],
                speed_rel: 0.2,
            }
            .because(
                "the hand 2–7 cm below the gripper's line (4 cm in the table; the band of Fig \
                 4-11's offset), within 1 cm sideways, its start ±5 cm along the line, its \
                 speed ±20 %",
            ),
        ],
    }
}

/// A scene's first obstacle's centre and radius, and the robot's start and
/// goal.
type Geometry = ([f64; 3], f64, [f64; 3], [f64; 3]);

/// The scene's first obstacle: centre, radius and the robot's start and goal
/// (2D from the scenario's endpoints, 3D from `apf.start`/`apf.goal`).
fn geometry(tree: &Value) -> Result<Geometry, String> {
    let num = |v: &Value| v.as_f64().ok_or("not a number".to_string());
    let point = |v: &Value| -> Result<[f64; 3], String> {
        let a = v.as_array().ok_or("not a point")?;
        let mut p = [0.0; 3];
        for (i, x) in a.iter().take(3).enumerate() {
            p[i] = num(x)?;
        }
        Ok(p)
    };
    let o = &tree["apf"]["obstacles"][0];
    let (c, r) = (point(&o["centre"])?, num(&o["radius"])?);
    let world = |k: &str| -> Result<[f64; 3], String> {
        let w = &tree[k]["world"];
        Ok([num(&w["x"])?, num(&w["y"])?, 0.0])
    };
    let (s, g) = if tree["apf"].get("start").is_some() {
        (point(&tree["apf"]["start"])?, point(&tree["apf"]["goal"])?)
    } else {
        (world("start")?, world("goal")?)
    };
    Ok((c, r, s, g))
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// The disc's distance from the start–goal line (2D: |y| offset from the
/// line through start and goal, which the families keep on y = start's).
fn offset(c: [f64; 3], s: [f64; 3], g: [f64; 3]) -> f64 {
    let d = [g[0] - s[0], g[1] - s[1], g[2] - s[2]];
    let v = [c[0] - s[0], c[1] - s[1], c[2] - s[2]];
    let len2 = d.iter().map(|x| x * x).sum::<f64>();
    let t = (v[0] * d[0] + v[1] * d[1] + v[2] * d[2]) / len2;
    dist(c, [s[0] + t * d[0], s[1] + t * d[1], s[2] + t * d[2]])
}

/// The repulsion range p₀ of the presets (the `ApfConfig` default).
const P0: f64 = 0.15;

fn check(ok: bool, why: impl FnOnce() -> String) -> Result<(), String> {
    if ok {
        Ok(())
    } else {
        Err(why())
    }
}

/// Fig 4-6: collinear, start and goal outside the disc's range.
fn scene_collinear(tree: &Value) -> Result<(), String> {
    let (c, r, s, g) = geometry(tree)?;
    check(offset(c, s, g) < 1e-9, || {
        format!("disc {:.4} m off the line", offset(c, s, g))
    })?;
    check(dist(s, c) - r > P0 && dist(g, c) - r > P0, || {
        "start or goal inside the disc's range".into()
    })?;
    check(s[0] < c[0] && c[0] < g[0], || {
        "the disc is not between start and goal".into()
    })
}

/// Fig 4-8: the goal within the disc's range, nearer the start than the disc.
fn scene_goal_in_range(tree: &Value) -> Result<(), String> {
    let (c, r, s, g) = geometry(tree)?;
    let gap = dist(g, c) - r;
    check(gap > 0.0 && gap < P0, || {
        format!("goal gap {gap:.3} m outside (0, {P0})")
    })?;
    check(dist(s, g) < dist(s, c), || {
        "the goal is not on the robot's side".into()
    })
}

/// A moving obstacle whose line lies `lo`…`hi` m off the robot's line and
/// which comes toward the robot, starting between start and goal.
fn scene_mover_band(tree: &Value, lo: f64, hi: f64) -> Result<(), String> {
    let (c, _, s, g) = geometry(tree)?;
    let off = offset(c, s, g);
    check(off >= lo - 1e-9 && off <= hi + 1e-9, || {
        format!("the mover's line is {off:.3} m off the robot's, outside [{lo}, {hi}]")
    })?;
    let v = tree["apf"]["obstacles"][0]["velocity"][0]
        .as_f64()
        .unwrap_or(0.0);
    check(v < 0.0, || {
        "the mover does not come toward the robot".into()
    })?;
    check(s[0] < c[0] && c[0] < g[0], || {
        "the mover does not start between start and goal".into()
    })
}

fn scene_head_on(tree: &Value) -> Result<(), String> {
    scene_mover_band(tree, 0.0, 0.01)
}

fn scene_offset(tree: &Value) -> Result<(), String> {
    scene_mover_band(tree, 0.02, 0.07)
}

fn scene_little_overlap(tree: &Value) -> Result<(), String> {
    scene_mover_band(tree, 0.07, 0.13)
}

fn scene_3d(tree: &Value) -> Result<(), String> {
    let (c, _, s, _) = geometry(tree)?;
    let below = s[2] - c[2];
    check((0.02 - 1e-9..=0.07 + 1e-9).contains(&below), || {
        format!("the hand is {below:.3} m below the line, outside [0.02, 0.07]")
    })?;
    check((c[1] - s[1]).abs() <= 0.01 + 1e-9, || {
        "the hand is over 1 cm sideways".into()
    })?;
    scene_mover_band(tree, 0.0, 0.0708)
}

fn deviations(prediction: bool) -> Vec<Deviation> {
    let mut v = vec![
        Deviation {
            what: "scene geometry (discs, start, goal)",
            path: None,
            ours: "assets/scenarios/T-fig4-*.json, T-tab4-1.json, drawn from the figures",
            paper: "drawn, not given",
        },
        Deviation {
            what: "attraction / repulsion gains and repulsion range",
            path: Some("apf.config.k_r"),
            ours: "the ApfConfig defaults",
            paper: "not given",
        },
        Deviation {
            what: "a spike: a path point turning by more than",
            path: None,
            ours: "30°",
            paper: "not defined",
        },
    ];
    if prediction {
        v.push(Deviation {
            what: "time step between the predicted positions t+1, t+2",
            path: Some("apf.config.predict_dt"),
            ours: "0.8 s in these presets (the config default is 0.5 s)",
            paper: "not given",
        });
    }
    v
}

/// The \[T\] ch. 4 experiments.
pub fn experiments() -> Vec<PathExperiment> {
    vec![
        PathExperiment {
            id: "T-fig4-6",
            paper: "[T] Wu 2022, Fig 4-1 / 4-6",
            what: "start, a disc and the goal on one line (local minimum of the basic field)",
            relation: "basic APF oscillates in front of the disc and ends stuck; the sampling \
                       APF escapes around it and reaches the goal",
            runs: three(FIG4_6).into_iter().take(2).collect(),
            clauses: vec![
                outcome(
                    "sampling reaches",
                    "the sampling APF escapes the local minimum and reaches the goal",
                    |r| ok(r, "sampling"),
                ),
                effect(
                    "basic stuck",
                    "basic APF is caught in the local minimum (stuck before the disc)",
                    |r| r.get("apf").is_some_and(|m| m.outcome == Outcome::Stuck),
                    None,
                ),
            ],
            family: family_collinear(),
            deviations: deviations(false),
            figures: None,
            scene: Some(scene_collinear),
        },
        PathExperiment {
            id: "T-fig4-8",
            paper: "[T] Wu 2022, Fig 4-7 / 4-8",
            what: "the goal between the robot and a disc, inside its repulsion range",
            relation: "basic APF and the sampling APF without the relative distance rule stall \
                       before the goal; with the rule the sampling APF reaches it",
            runs: vec![
                RunSpec {
                    name: "apf",
                    scenario_json: FIG4_8,
                    planner: None,
                    set: vec![("apf.config.mode", "basic")],
                },
                RunSpec {
                    name: "sampling-no-rule",
                    scenario_json: FIG4_8,
                    planner: None,
                    set: vec![
                        ("apf.config.mode", "sampling"),
                        ("apf.config.relative_distance", "false"),
                    ],
                },
                RunSpec {
                    name: "sampling+rule",
                    scenario_json: FIG4_8,
                    planner: None,
                    set: vec![("apf.config.mode", "sampling")],
                },
            ],
            clauses: vec![
                outcome(
                    "with the rule reaches",
                    "with the relative distance rule the sampling APF reaches the goal",
                    |r| ok(r, "sampling+rule"),
                ),
                effect(
                    "basic stalls",
                    "basic APF does not reach the goal (goal unreachable near the obstacle)",
                    |r| !reached(r, "apf"),
                    None,
                ),
                effect(
                    "no rule stalls",
                    "the sampling APF without the rule does not reach it either",
                    |r| !reached(r, "sampling-no-rule"),
                    None,
                ),
            ],
            family: family_goal_in_range(),
            deviations: deviations(false),
            figures: None,
            scene: Some(scene_goal_in_range),
        },
        PathExperiment {
            id: "T-fig4-10",
            paper: "[T] Wu 2022, Fig 4-10 (fails / 0.96 m / 0.84 m)",
            what: "a disc moving head-on along the robot's line",
            relation: "basic APF does not reach the goal; the sampling APF does; with \
                       prediction the path is shorter",
            runs: three(FIG4_10),
            clauses: vec![
                outcome(
                    "improved reach",
                    "the sampling APF reaches, with and without prediction",
                    |r| ok(r, "sampling") && ok(r, "sampling+prediction"),
                ),
                effect(
                    "basic fails",
                    "basic APF does not reach the goal",
                    |r| !reached(r, "apf"),
                    None,
                ),
                effect(
                    "prediction shorter",
                    "with prediction the path is shorter (paper 0.84 vs 0.96 m)",
                    |r| {
                        ok(r, "sampling")
                            && ok(r, "sampling+prediction")
                            && length(r, "sampling+prediction") < length(r, "sampling")
                    },
                    diff("path prediction − sampling", "m", |r| {
                        (ok(r, "sampling") && ok(r, "sampling+prediction"))
                            .then(|| length(r, "sampling+prediction") - length(r, "sampling"))
                    }),
                ),
            ],
            family: family_head_on(),
            deviations: deviations(true),
            figures: None,
            scene: Some(scene_head_on),
        },
        PathExperiment {
            id: "T-fig4-11",
            paper: "[T] Wu 2022, Fig 4-11 (0.870 / 0.840 / 0.809 m)",
            what: "the mover's line offset 0.04 m from the robot's",
            relation: "all reach; path length basic > sampling > sampling+prediction; the \
                       basic path has the most spikes",
            runs: three(FIG4_11),
            clauses: vec![
                outcome(
                    "all reach",
                    "all three reach the goal without collision",
                    all_ok,
                ),
                lengths_fall(),
                effect(
                    "basic most spikes",
                    "the basic path has the most spikes",
                    |r| {
                        spikes(r, "apf") > spikes(r, "sampling")
                            && spikes(r, "apf") > spikes(r, "sampling+prediction")
                    },
                    None,
                ),
            ],
            family: family_offset(),
            deviations: deviations(true),
            figures: None,
            scene: Some(scene_offset),
        },
        PathExperiment {
            id: "T-fig4-12",
            paper: "[T] Wu 2022, Fig 4-12 (0.659 / 0.690 / 0.690 m)",
            what: "the mover's line offset 0.1 m: little overlap",
            relation: "all reach; the improvement is not evident: both improved paths are at \
                       least as long as the basic one (within 10 %)",
            runs: three(FIG4_12),
            clauses: vec![
                outcome(
                    "all reach",
                    "all three reach the goal without collision",
                    all_ok,
                ),
                effect(
                    "no gain",
                    "both improved paths are at least as long as the basic one, within 10 %",
                    |r| {
                        all_ok(r)
                            && ["sampling", "sampling+prediction"].iter().all(|n| {
                                length(r, n) >= length(r, "apf")
                                    && length(r, n) <= 1.1 * length(r, "apf")
                            })
                    },
                    diff("path prediction − basic", "m", |r| {
                        all_ok(r).then(|| length(r, "sampling+prediction") - length(r, "apf"))
                    }),
                ),
            ],
            family: family_little_overlap(),
            deviations: deviations(true),
            figures: None,
            scene: Some(scene_little_overlap),
        },
        PathExperiment {
            id: "T-tab4-1",
            paper: "[T] Wu 2022, Table 4-1 (1.018 / 0.816 / 0.768 m; spikes 4 / 1 / 0)",
            what: "3D: the end effector crosses the table while a hand (sphere) reaches \
                   toward it head-on, 0.04 m below its line",
            relation: "all reach; path length basic > sampling > sampling+prediction; spikes \
                       fall: basic > sampling > sampling+prediction = 0",
            runs: three(TAB4_1),
            clauses: vec![
                outcome(
                    "all reach",
                    "all three reach the goal without collision",
                    all_ok,
                ),
                lengths_fall(),
                effect(
                    "spikes fall to 0",
                    "spikes basic > sampling > sampling+prediction = 0",
                    |r| {
                        spikes(r, "apf") > spikes(r, "sampling")
                            && spikes(r, "sampling") > spikes(r, "sampling+prediction")
                            && spikes(r, "sampling+prediction") == 0
                    },
                    None,
                ),
            ],
            family: family_3d(),
            deviations: deviations(true),
            figures: None,
            scene: Some(scene_3d),
        },
    ]
}
