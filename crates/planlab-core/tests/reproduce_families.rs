//! Every experiment's family keeps its preset's scene: each range has its
//! reason written out, every variant can start (start and goal free), and
//! where an experiment states its situation as a scene check (the
//! potential-field scenes: the goal inside the disc's repulsion range, the
//! mover's line within its figure's offset band …) every variant passes it.

use planlab_core::reproduce::{self, Experiment, RunMetrics};

/// Variants checked per family: the size of the README's verdict run.
const VARIANTS: u32 = 60;

fn families_keep_their_scene<M: RunMetrics>(e: &Experiment<M>) {
    for r in &e.family.perturbations {
        assert!(
            r.why.len() > 20,
            "{}: the range of `{}` needs its reason",
            e.id,
            r.perturbation.name()
        );
    }
    for k in 0..VARIANTS {
        let v = e
            .variant(0, k, &[])
            .unwrap_or_else(|err| panic!("{} variant {k}: {err}", e.id));
        if let Some(scene) = e.scene {
            for (run, tree) in &v.trees {
                scene(tree).unwrap_or_else(|why| {
                    panic!(
                        "{} variant {k} run {run}: not the paper's scene: {why}",
                        e.id
                    )
                });
            }
        }
    }
}

#[test]
fn every_family_states_its_ranges_and_keeps_its_scene() {
    for e in &reproduce::all() {
        families_keep_their_scene(e);
    }
    for e in &reproduce::path_experiments() {
        families_keep_their_scene(e);
    }
}

#[test]
fn the_potential_field_scene_checks_reject_the_neighbouring_scenes() {
    // Fig 4-10's head-on check refuses Fig 4-11's preset (4 cm offset) and
    // Fig 4-11's refuses Fig 4-12's (0.1 m): the bands do not overlap.
    let paths = reproduce::path_experiments();
    let find = |id: &str| paths.iter().find(|e| e.id == id).unwrap();
    let preset = |id: &str| find(id).variant(0, 0, &[]).unwrap().trees[0].1.clone();
    for (check, other) in [
        ("T-fig4-10", "T-fig4-11"),
        ("T-fig4-11", "T-fig4-12"),
        ("T-fig4-12", "T-fig4-10"),
    ] {
        let scene = find(check).scene.unwrap();
        assert!(scene(&preset(check)).is_ok(), "{check} accepts its preset");
        assert!(scene(&preset(other)).is_err(), "{check} refuses {other}");
    }
    // Fig 4-8's goal moved 0.2 m toward the robot is outside the range.
    let mut far = preset("T-fig4-8");
    far["goal"]["world"]["x"] = serde_json::json!(0.7);
    assert!(find("T-fig4-8").scene.unwrap()(&far).is_err());
    // Fig 4-6's disc 1 cm off the line is another scene.
    let mut off = preset("T-fig4-6");
    off["apf"]["obstacles"][0]["centre"][1] = serde_json::json!(0.01);
    assert!(find("T-fig4-6").scene.unwrap()(&off).is_err());
}
