//! The draw list of a potential-field run ([`apf_run`]): the path, start
//! and goal, the force field on a lattice, the obstacles with their
//! repulsion ranges, the predicted obstacles and the last step's sampled
//! candidates, in the page's plane: (x, y), or for a spatial run the
//! vertical (x, z) plane through the robot.

use super::{DrawList, Layer, Layers, Shape};
use crate::apf::{ApfRun, ApfVector, ObstacleObs};
use glam::DVec3;

/// How to draw an APF run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ApfDraw {
    /// The field's extent in the page's plane: x min, y min, x max, y max
    /// (m).
    pub bounds: [f64; 4],
    /// Field lattice columns and rows (clamped to 1…400).
    pub lattice: [usize; 2],
}

/// `v` in the page's plane: (x, y), or (x, z) for a 3D vector.
pub fn plane_xy<V: ApfVector>(v: V) -> [f64; 2] {
    let p = v.to_xyz();
    if V::DIM == 3 {
        [p.x, p.z]
    } else {
        [p.x, p.y]
    }
}

/// The point of the page's plane (`x`, `y`) as a vector like `like` (a 3D
/// one keeps `like`'s y).
pub fn from_plane_xy<V: ApfVector>(like: V, x: f64, y: f64) -> V {
    if V::DIM == 3 {
        V::from_xyz(DVec3::new(x, like.to_xyz().y, y))
    } else {
        V::from_xyz(DVec3::new(x, y, 0.0))
    }
}

/// The layers of `run` in `layers`, appended to `out`: [`Layer::Trail`]
/// (the path), [`Layer::Goals`] (start `tag` 0, goal 1), [`Layer::Field`]
/// (the resultant force, real and predicted obstacles included, at the
/// lattice's cell centres), [`Layer::Obstacles`] (now, `value` radius +
/// p₀), [`Layer::Predicted`] and [`Layer::Candidates`] of the last step.
pub fn apf_run<V: ApfVector>(run: &ApfRun<V>, d: ApfDraw, layers: Layers, out: &mut DrawList) {
    let want = |l| layers.has(l);
    let path = run.path();
    let last = run.last_step();
    let obstacles: Vec<ObstacleObs<V>> = run.obstacles_at(run.time());
    if want(Layer::Trail) && !path.is_empty() {
        let xy = path.iter().flat_map(|&p| plane_xy(p));
        out.push(Layer::Trail, Shape::Polyline, xy, 0.0, 0.0);
    }
    if want(Layer::Goals) {
        if let Some(&s) = path.first() {
            out.points(Layer::Goals, Shape::Points, &[plane_xy(s)], 0.0, 0.0);
        }
        out.points(
            Layer::Goals,
            Shape::Points,
            &[plane_xy(run.goal())],
            1.0,
            0.0,
        );
    }
    if want(Layer::Field) {
        field(run, &obstacles, d, out);
    }
    if want(Layer::Obstacles) {
        let p0 = run.planner().config().p0;
        for o in &obstacles {
            let [x, y] = plane_xy(o.centre);
            let [vx, vy] = o.velocity.map_or([0.0; 2], plane_xy);
            let disc = [x, y, o.radius, vx, vy];
            out.push(
                Layer::Obstacles,
                Shape::Discs,
                disc,
                f64::from(o.id),
                o.radius + p0,
            );
        }
    }
    let Some(s) = last else {
        return;
    };
    if want(Layer::Predicted) {
        for v in &s.predicted {
            let [x, y] = plane_xy(v.centre);
            let disc = [x, y, v.range, 0.0, 0.0];
            out.push(Layer::Predicted, Shape::Discs, disc, f64::from(v.k), 0.0);
        }
    }
    // Candidates fan out from the point the last step was taken from.
    if let (true, [.., from, _]) = (want(Layer::Candidates), path) {
        let [bx, by] = plane_xy(*from);
        for (i, c) in s.candidates.iter().enumerate() {
            let [x, y] = plane_xy(c.point);
            let chosen = f64::from(u8::from(s.chosen == Some(i)));
            out.push(
                Layer::Candidates,
                Shape::Segments,
                [bx, by, x, y],
                chosen,
                c.cost,
            );
        }
    }
}

/// The resultant on the lattice, row 0 at the bottom.
fn field<V: ApfVector>(
    run: &ApfRun<V>,
    obstacles: &[ObstacleObs<V>],
    d: ApfDraw,
    out: &mut DrawList,
) {
    let [x0, y0, x1, y1] = d.bounds;
    let [nx, ny] = d.lattice.map(|n| n.clamp(1, 400));
    let virtuals = run.last_step().map_or(&[][..], |s| &s.predicted[..]);
    let apf = run.planner();
    let (here, goal) = (run.position(), run.goal());
    let mut v = Vec::with_capacity(4 * nx * ny);
    for j in 0..ny {
        for i in 0..nx {
            let x = x0 + (i as f64 + 0.5) * (x1 - x0) / nx as f64;
            let y = y0 + (j as f64 + 0.5) * (y1 - y0) / ny as f64;
            let (a, r) = apf.forces_at(from_plane_xy(here, x, y), goal, obstacles, virtuals);
            let [fx, fy] = plane_xy(a + r);
            v.extend([x, y, fx, fy]);
        }
    }
    out.push(Layer::Field, Shape::Vectors, v, nx as f64, ny as f64);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::apf::{ApfScene, SceneObstacle};
    use glam::DVec2;

    fn run() -> ApfRun<DVec2> {
        let mut scene: ApfScene = serde_json::from_str(
            r#"{"obstacles": [{"centre": [2.0, 0.3], "radius": 0.2},
                              {"centre": [1.0, -1.0], "radius": 0.1, "velocity": [0.0, 0.5]}]}"#,
        )
        .expect("a scene");
        scene.obstacles.push(SceneObstacle {
            id: Some(7),
            ..scene.obstacles[0].clone()
        });
        scene.obstacles[2].centre = vec![3.0, -0.5];
        ApfRun::new(&scene, DVec2::new(0.0, 0.0), DVec2::new(4.0, 0.0)).expect("a run")
    }

    #[test]
    fn apf_draw_has_the_path_goals_obstacles_and_a_field_lattice() {
        let mut r = run();
        for _ in 0..3 {
            r.step().unwrap();
        }
        let d = ApfDraw {
            bounds: [-1.0, -2.0, 5.0, 2.0],
            lattice: [6, 4],
        };
        let mut out = DrawList::default();
        apf_run(&r, d, Layers::ALL, &mut out);
        let trail = out.layer(Layer::Trail).next().unwrap();
        assert_eq!(out.numbers(trail).len(), 2 * r.path().len());
        assert_eq!(&out.numbers(trail)[..2], &[0.0, 0.0]);
        let goals: Vec<_> = out
            .layer(Layer::Goals)
            .map(|i| (i.tag, out.numbers(i).to_vec()))
            .collect();
        assert_eq!(goals, [(0.0, vec![0.0, 0.0]), (1.0, vec![4.0, 0.0])]);
        let f = out.layer(Layer::Field).next().unwrap();
        assert_eq!((f.shape, f.tag, f.value), (Shape::Vectors, 6.0, 4.0));
        let v = out.numbers(f);
        assert_eq!(v.len(), 4 * 6 * 4);
        assert_eq!(&v[..2], &[-0.5, -1.5], "the first lattice cell's centre");
        // At (0.5, 0.5), far from the obstacles, the field points at the goal.
        let k = 4 * (2 * 6 + 1);
        assert!(v[k + 2] > 0.0, "{:?}", &v[k..k + 4]);
        let obs: Vec<_> = out.layer(Layer::Obstacles).collect();
        assert_eq!(obs.len(), 3);
        let p0 = r.planner().config().p0;
        assert_eq!(obs[0].value, 0.2 + p0, "radius + p0");
        assert_eq!(obs[2].tag, 7.0);
        let t = r.time();
        assert_eq!(out.numbers(obs[1]), &[1.0, -1.0 + 0.5 * t, 0.1, 0.0, 0.5]);
        // In layer order.
        let codes: Vec<u8> = out.items.iter().map(|i| i.layer as u8).collect();
        assert!(codes.windows(2).all(|w| w[0] <= w[1]), "{codes:?}");
    }

    #[test]
    fn candidates_fan_out_from_the_point_stepped_from_with_the_chosen_tagged() {
        let mut r = run();
        let mut out = DrawList::default();
        let d = ApfDraw {
            bounds: [0.0, 0.0, 1.0, 1.0],
            lattice: [1, 1],
        };
        for _ in 0..40 {
            r.step().unwrap();
            let s = r.last_step().unwrap();
            if !s.candidates.is_empty() {
                break;
            }
        }
        let s = r.last_step().unwrap().clone();
        assert!(!s.candidates.is_empty(), "no sampled step in 40");
        apf_run(&r, d, Layers::NONE.with(Layer::Candidates), &mut out);
        let c: Vec<_> = out.layer(Layer::Candidates).collect();
        assert_eq!(c.len(), s.candidates.len());
        let from = r.path()[r.path().len() - 2];
        for (i, item) in c.iter().enumerate() {
            let n = out.numbers(item);
            assert_eq!(&n[..2], &[from.x, from.y]);
            assert_eq!(&n[2..], &[s.candidates[i].point.x, s.candidates[i].point.y]);
            assert_eq!(item.tag == 1.0, s.chosen == Some(i));
            assert_eq!(item.value, s.candidates[i].cost);
        }
    }

    #[test]
    fn a_spatial_run_is_drawn_in_its_x_z_plane() {
        assert_eq!(plane_xy(DVec3::new(1.0, 2.0, 3.0)), [1.0, 3.0]);
        let p: DVec3 = from_plane_xy(DVec3::new(0.0, 2.0, 0.0), 5.0, 6.0);
        assert_eq!(p, DVec3::new(5.0, 2.0, 6.0));
        assert_eq!(plane_xy(DVec2::new(1.0, 2.0)), [1.0, 2.0]);
    }
}
