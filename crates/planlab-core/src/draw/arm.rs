//! The draw list of an arm episode ([`arm_episode`]), in space (m, z up):
//! link capsules, the hand and forearm, the tool's and the hand's paths,
//! the hand's scripted motion, start and goal, the predicted hand
//! positions and the last step's sampled candidates.

use super::{DrawList, Layer, Layers, Shape};
use crate::arm::{ArmEpisode, Obstacle3};
use glam::DVec3;

/// The layers of `ep` in `layers`, appended to `out`: [`Layer::Trail`]
/// (the tool's path `tag` 0; with RRT-Connect, tag 1 the tool along the
/// joint-space plan still ahead), [`Layer::Goals`] (start `tag` 0, goal 1),
/// [`Layer::Predicted`], [`Layer::Candidates`], [`Layer::Links`],
/// [`Layer::Hand`] and [`Layer::HandPath`] (where the hand went, and with
/// `script` ≥ 2 its scripted motion sampled at that many instants up to its
/// end, or 10 s for an endless one).
pub fn arm_episode(ep: &ArmEpisode, script: usize, layers: Layers, out: &mut DrawList) {
    let want = |l| layers.has(l);
    let flat = |pts: &[DVec3]| pts.iter().flat_map(|p| p.to_array()).collect::<Vec<f64>>();
    if want(Layer::Trail) && !ep.tool_path().is_empty() {
        out.push(
            Layer::Trail,
            Shape::Polyline3,
            flat(ep.tool_path()),
            0.0,
            0.0,
        );
    }
    if want(Layer::Trail) {
        let ahead = ep.planned_tool_path();
        if ahead.len() >= 2 {
            out.push(Layer::Trail, Shape::Polyline3, flat(&ahead), 1.0, 0.0);
        }
    }
    if want(Layer::Goals) {
        let s = ep.scene();
        out.push(Layer::Goals, Shape::Points3, s.start, 0.0, 0.0);
        out.push(Layer::Goals, Shape::Points3, s.goal, 1.0, 0.0);
    }
    if let Some(s) = ep.last_step() {
        if want(Layer::Predicted) {
            for v in &s.predicted {
                let [x, y, z] = v.centre.to_array();
                out.push(
                    Layer::Predicted,
                    Shape::Spheres,
                    [x, y, z, v.range],
                    f64::from(v.k),
                    0.0,
                );
            }
        }
        if want(Layer::Candidates) {
            for (i, c) in s.candidates.iter().enumerate() {
                let chosen = f64::from(u8::from(s.chosen == Some(i)));
                out.push(
                    Layer::Candidates,
                    Shape::Points3,
                    c.point.to_array(),
                    chosen,
                    c.cost,
                );
            }
        }
    }
    // RRT-Connect has no APF step: its predicted hand (the centres it last
    // planned or checked against) is drawn with the hand's radius.
    if want(Layer::Predicted) && ep.last_step().is_none() {
        let r = ep.scene().hand.hand_radius_m;
        for (c, k) in ep.rrt_predicted() {
            let [x, y, z] = c.to_array();
            out.push(
                Layer::Predicted,
                Shape::Spheres,
                [x, y, z, r],
                f64::from(*k),
                0.0,
            );
        }
    }
    if want(Layer::Links) {
        let links = ep.links();
        let n = links.len();
        for (i, l) in links.iter().enumerate() {
            let [ax, ay, az] = l.a.to_array();
            let [bx, by, bz] = l.b.to_array();
            let tool = f64::from(u8::from(i + 1 == n));
            out.push(
                Layer::Links,
                Shape::Capsules,
                [ax, ay, az, bx, by, bz, l.radius],
                i as f64,
                tool,
            );
        }
    }
    if want(Layer::Hand) {
        for o in ep.hand_obstacles() {
            match o {
                Obstacle3::Sphere {
                    centre: [x, y, z],
                    radius,
                } => {
                    out.push(Layer::Hand, Shape::Spheres, [x, y, z, radius], 0.0, 0.0);
                }
                Obstacle3::Capsule { a, b, radius } => {
                    let c = [a[0], a[1], a[2], b[0], b[1], b[2], radius];
                    out.push(Layer::Hand, Shape::Capsules, c, 1.0, 0.0);
                }
            }
        }
    }
    if want(Layer::HandPath) {
        if !ep.hand_path().is_empty() {
            out.push(
                Layer::HandPath,
                Shape::Polyline3,
                flat(ep.hand_path()),
                0.0,
                0.0,
            );
        }
        if script >= 2 {
            let h = ep.hand();
            let end = if h.end_time().is_finite() {
                h.end_time().max(0.1)
            } else {
                10.0
            };
            let n = script.min(2000);
            let pts: Vec<DVec3> = (0..n)
                .map(|i| h.hand_at(end * i as f64 / (n - 1) as f64))
                .collect();
            out.push(Layer::HandPath, Shape::Polyline3, flat(&pts), 1.0, 0.0);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::arm::ArmScene;

    fn episode() -> ArmEpisode {
        let scene: ArmScene =
            serde_json::from_str(r#"{"start": [0.45, -0.05, 1.0], "goal": [0.6, 0.35, 0.82]}"#)
                .expect("an arm scene");
        ArmEpisode::new(scene, 3).expect("an episode")
    }

    #[test]
    fn arm_draw_has_a_capsule_per_link_the_hand_and_the_paths_in_space() {
        let mut ep = episode();
        for _ in 0..5 {
            ep.step().unwrap();
        }
        let mut out = DrawList::default();
        arm_episode(&ep, 30, Layers::ALL, &mut out);
        let links: Vec<_> = out.layer(Layer::Links).collect();
        let want = ep.links();
        assert_eq!(links.len(), want.len());
        for (i, (item, l)) in links.iter().zip(&want).enumerate() {
            assert_eq!(item.shape, Shape::Capsules);
            assert_eq!(item.tag, i as f64);
            assert_eq!(out.numbers(item)[..3], l.a.to_array());
            assert_eq!(out.numbers(item)[3..], [l.b.x, l.b.y, l.b.z, l.radius]);
        }
        assert_eq!(links.last().unwrap().value, 1.0, "the tool");
        assert_eq!(links[0].value, 0.0);
        let trail = out.layer(Layer::Trail).next().unwrap();
        assert_eq!(trail.shape, Shape::Polyline3);
        assert_eq!(out.numbers(trail).len(), 3 * ep.tool_path().len());
        let hand: Vec<Shape> = out.layer(Layer::Hand).map(|i| i.shape).collect();
        assert_eq!(hand, [Shape::Spheres, Shape::Capsules]);
        let paths: Vec<_> = out.layer(Layer::HandPath).collect();
        assert_eq!(paths.iter().map(|i| i.tag).collect::<Vec<_>>(), [0.0, 1.0]);
        assert_eq!(out.numbers(paths[0]).len(), 3 * ep.hand_path().len());
        assert_eq!(out.numbers(paths[1]).len(), 3 * 30);
        let goals: Vec<_> = out
            .layer(Layer::Goals)
            .map(|i| out.numbers(i).to_vec())
            .collect();
        assert_eq!(goals, [vec![0.45, -0.05, 1.0], vec![0.6, 0.35, 0.82]]);
        let s = ep.last_step().unwrap();
        assert_eq!(out.layer(Layer::Candidates).count(), s.candidates.len());
        assert_eq!(out.layer(Layer::Predicted).count(), s.predicted.len());
        let chosen: Vec<_> = out
            .layer(Layer::Candidates)
            .filter(|i| i.tag == 1.0)
            .collect();
        assert_eq!(chosen.len(), usize::from(s.chosen.is_some()));
        let codes: Vec<u8> = out.items.iter().map(|i| i.layer as u8).collect();
        assert!(codes.windows(2).all(|w| w[0] <= w[1]), "{codes:?}");
    }

    #[test]
    fn arm_draw_without_a_script_or_steps_has_no_step_layers() {
        let ep = episode();
        let mut out = DrawList::default();
        arm_episode(&ep, 0, Layers::ALL, &mut out);
        assert_eq!(out.layer(Layer::Candidates).count(), 0);
        assert_eq!(out.layer(Layer::Predicted).count(), 0);
        assert!(out.layer(Layer::HandPath).all(|i| i.tag == 0.0));
        let mut only = DrawList::default();
        arm_episode(&ep, 10, Layers::NONE.with(Layer::Links), &mut only);
        assert!(only.items.iter().all(|i| i.layer == Layer::Links));
        assert!(!only.items.is_empty());
    }
}
