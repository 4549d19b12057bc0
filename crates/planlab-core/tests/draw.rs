//! The draw list of an episode, layer by layer: each layer's items say
//! what the episode holds (the footprint's centre is the pose, the fan's
//! polylines are the rollouts, the movers are where the world puts them …).

use planlab_core::draw::{self, DrawList, FanColour, Item, Layer, Layers, Request, Shape};
use planlab_core::lidar::fog::SeenCells;
use planlab_core::local::GoalKind;
use planlab_core::map::{OccupancyGrid, Pose2};
use planlab_core::planners::PlannerChoice;
use planlab_core::sim::{Episode, EpisodeSetup, SimConfig};
use planlab_core::world::{Footprint, MotionModel, MoverSpec, RobotSpec, RobotState, StaticMap};

/// A 10 × 8 m room at 0.1 m per cell with a border wall and a block in
/// the middle, so planners detour and scans see edges.
fn room() -> StaticMap {
    let (cw, ch) = (100, 80);
    let mut rows = String::new();
    for r in 0..ch {
        for c in 0..cw {
            let border = r == 0 || c == 0 || r == ch - 1 || c == cw - 1;
            let block = (45..55).contains(&c) && (25..55).contains(&r);
            rows.push(if border || block { '#' } else { '.' });
        }
        rows.push('\n');
    }
    let g = OccupancyGrid::from_ascii(&rows)
        .unwrap()
        .with_frame(
            0.1,
            Pose2 {
                x: -1.0,
                y: 0.5,
                yaw: 0.0,
            },
        )
        .unwrap();
    StaticMap::new(g, true).unwrap()
}

fn episode(planner: &str, footprint: Footprint) -> Episode {
    let movers = vec![
        MoverSpec {
            id: 3,
            radius: 0.25,
            motion: MotionModel::ConstantVelocity {
                start: [6.0, 2.0],
                velocity: [-0.2, 0.1],
                since: 0.0,
            },
        },
        MoverSpec {
            id: 5,
            radius: 0.3,
            motion: MotionModel::ConstantVelocity {
                start: [2.0, 6.5],
                velocity: [0.0, 0.0],
                since: 0.0,
            },
        },
    ];
    Episode::new(EpisodeSetup {
        map: room(),
        robot: RobotSpec {
            footprint,
            ..Default::default()
        },
        start: RobotState {
            x: 0.5,
            y: 4.5,
            theta: 0.3,
            ..Default::default()
        },
        goal: [7.5, 4.5],
        movers,
        planner: PlannerChoice::named(planner),
        config: SimConfig::default(),
        terrain: Default::default(),
        seed: 11,
        perception: None,
        global_planner: None,
    })
    .unwrap()
}

fn stepped(planner: &str, n: usize) -> Episode {
    let mut ep = episode(planner, Footprint::default());
    ep.set_record_rollouts(true);
    for _ in 0..n {
        ep.step();
    }
    ep
}

/// The draw list of `layers` only.
fn draw_of(ep: &Episode, seen: Option<&SeenCells>, layers: &[Layer]) -> DrawList {
    let mut out = DrawList::default();
    let req = Request {
        layers: layers.iter().copied().collect(),
        trail_from: 0,
        ..Request::default()
    };
    draw::episode(ep, seen, req, &mut out);
    for i in &out.items {
        assert!(layers.contains(&i.layer), "{:?} not asked for", i.layer);
    }
    out
}

fn items(d: &DrawList, l: Layer) -> Vec<Item> {
    d.layer(l).copied().collect()
}

/// An item's numbers as points.
fn xy(d: &DrawList, i: &Item) -> Vec<[f64; 2]> {
    d.numbers(i).chunks(2).map(|p| [p[0], p[1]]).collect()
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-12
}

#[test]
fn map_layer_is_the_grid_with_its_frame() {
    let ep = episode("dwa", Footprint::default());
    let d = draw_of(&ep, None, &[Layer::Map]);
    let [m] = items(&d, Layer::Map)[..] else {
        panic!("one map item");
    };
    assert_eq!(m.shape, Shape::Cells);
    assert_eq!(&d.numbers(&m)[..5], &[100.0, 80.0, 0.1, -1.0, 0.5]);
    let g = ep.map().grid();
    let bytes: Vec<u8> = g.cells().iter().map(|&c| c as u8).collect();
    assert_eq!(d.cell_bytes(&m), &bytes[..]);
    assert_eq!(
        bytes.iter().filter(|&&b| b == 1).count(),
        2 * 100 + 2 * 78 + 300
    );
}

#[test]
fn seen_layer_is_the_fog_with_its_count() {
    let mut ep = episode("lidar-dwa", Footprint::default());
    let mut seen = SeenCells::new(ep.map().grid());
    for _ in 0..3 {
        ep.step();
        let l = ep.planner_debug().lidar.as_ref().unwrap();
        seen.update(ep.map().grid(), l.pose, &l.ranges, &l.returns);
    }
    assert!(seen.count() > 100);
    let d = draw_of(&ep, Some(&seen), &[Layer::Seen]);
    let [s] = items(&d, Layer::Seen)[..] else {
        panic!("one seen item");
    };
    assert_eq!(s.value, seen.count() as f64);
    assert_eq!(d.cell_bytes(&s), seen.cells());
    // Without the caller's fog there is no layer.
    assert!(draw_of(&ep, None, &[Layer::Seen]).items.is_empty());
}

#[test]
fn global_path_and_key_points_are_the_planners() {
    let ep = stepped("improved-dwa", 2);
    let dbg = ep.planner_debug();
    assert!(dbg.global_path.len() > 2 && !dbg.keypoints.is_empty());
    let d = draw_of(&ep, None, &[Layer::GlobalPath, Layer::KeyPoints]);
    let [p] = items(&d, Layer::GlobalPath)[..] else {
        panic!("one path");
    };
    assert_eq!(p.shape, Shape::Polyline);
    assert_eq!(xy(&d, &p), dbg.global_path);
    let [k] = items(&d, Layer::KeyPoints)[..] else {
        panic!("one key-point set");
    };
    assert_eq!(k.shape, Shape::Points);
    assert_eq!(xy(&d, &k), dbg.keypoints);
    // The baseline has neither: no items.
    assert!(draw_of(
        &stepped("dwa", 1),
        None,
        &[Layer::GlobalPath, Layer::KeyPoints]
    )
    .items
    .is_empty());
}

#[test]
fn fan_items_are_the_rollouts_with_score_and_admissibility() {
    let ep = stepped("dwa", 3);
    let rs = &ep.planner_debug().rollouts;
    assert!(rs.len() > 10);
    let d = draw_of(&ep, None, &[Layer::Fan]);
    let fan = items(&d, Layer::Fan);
    assert_eq!(fan.len(), rs.len());
    for (i, r) in fan.iter().zip(rs) {
        assert_eq!(i.shape, Shape::Polyline);
        assert_eq!(xy(&d, i), r.points);
        assert_eq!(i.tag, f64::from(u8::from(r.admissible)));
        assert_eq!(i.value.to_bits(), r.score.to_bits());
    }
    assert!(fan.iter().any(|i| i.tag == 1.0));
}

#[test]
fn fan_coloured_by_a_critic_carries_its_normalised_values() {
    let ep = stepped("dwa", 3);
    let dbg = ep.planner_debug();
    assert_eq!(dbg.critics.len(), 3);
    let fan_of = |fan| {
        let mut d = DrawList::default();
        let req = Request {
            layers: Layers::NONE.with(Layer::Fan),
            trail_from: 0,
            fan,
        };
        draw::episode(&ep, None, req, &mut d);
        items(&d, Layer::Fan)
    };
    let total = fan_of(FanColour::Total);
    let per_critic: Vec<Vec<Item>> = (0..3).map(|k| fan_of(FanColour::Critic(k))).collect();
    for (k, fan) in per_critic.iter().enumerate() {
        assert_eq!(fan.len(), dbg.rollouts.len());
        for (i, r) in fan.iter().zip(&dbg.rollouts) {
            assert_eq!(i.value.to_bits(), r.normalised[k].to_bits(), "critic {k}");
            assert_eq!(i.tag, f64::from(u8::from(r.admissible)));
        }
    }
    // The total is the weighted sum of the values a critic colours by.
    let admissible = total.iter().enumerate().filter(|(_, i)| i.tag == 1.0);
    for (n, i) in admissible {
        let sum: f64 = (0..3)
            .map(|k| dbg.weights[k] * per_critic[k][n].value)
            .sum();
        assert!(
            (sum - i.value).abs() < 1e-12,
            "rollout {n}: {sum} vs {}",
            i.value
        );
    }
    // A critic the planner does not have: NaN, which a page greys out.
    assert!(fan_of(FanColour::Critic(3))
        .iter()
        .all(|i| i.value.is_nan()));
}

#[test]
fn chosen_item_is_the_chosen_rollout() {
    let ep = stepped("dwa", 3);
    let dbg = ep.planner_debug();
    let k = dbg.chosen.unwrap();
    let d = draw_of(&ep, None, &[Layer::Chosen]);
    let [c] = items(&d, Layer::Chosen)[..] else {
        panic!("one chosen rollout");
    };
    assert_eq!(c.tag, k as f64);
    assert_eq!(xy(&d, &c), dbg.rollouts[k].points);
}

#[test]
fn trail_is_the_driven_positions_from_the_row_asked() {
    let ep = stepped("dwa", 6);
    let mut d = DrawList::default();
    let req = Request {
        layers: Layers::NONE.with(Layer::Trail),
        trail_from: 4,
        ..Request::default()
    };
    draw::episode(&ep, None, req, &mut d);
    let [t] = items(&d, Layer::Trail)[..] else {
        panic!("one trail");
    };
    assert_eq!(xy(&d, &t), ep.trace().positions()[4..]);
    // Past the end: nothing new.
    d.clear();
    draw::episode(
        &ep,
        None,
        Request {
            trail_from: 99,
            ..req
        },
        &mut d,
    );
    assert!(d.items.is_empty());
}

#[test]
fn movers_are_where_the_world_puts_them_with_classes_after_a_step() {
    let before = episode("improved-dwa", Footprint::default());
    let d = draw_of(&before, None, &[Layer::Movers]);
    assert!(
        items(&d, Layer::Movers).iter().all(|i| i.value.is_nan()),
        "no classes before a step"
    );
    let ep = stepped("improved-dwa", 4);
    let d = draw_of(&ep, None, &[Layer::Movers]);
    let movers = items(&d, Layer::Movers);
    let now = ep.movers_now();
    assert_eq!(movers.len(), 2);
    for (i, (id, r, s)) in movers.iter().zip(&now) {
        assert_eq!(i.shape, Shape::Discs);
        assert_eq!(i.tag, f64::from(*id));
        assert_eq!(d.numbers(i), &[s.pos[0], s.pos[1], *r, s.vel[0], s.vel[1]]);
    }
    assert!(close(d.numbers(&movers[0])[0], 6.0 - 0.2 * ep.time()));
    let classes = &ep.planner_debug().classes;
    assert!(!classes.is_empty());
    for (id, _) in classes {
        let i = movers.iter().find(|i| i.tag == f64::from(*id)).unwrap();
        assert!((0.0..=2.0).contains(&i.value), "class code {}", i.value);
    }
}

#[test]
fn robot_footprint_is_centred_on_the_pose_and_points_along_the_heading() {
    let ep = stepped("dwa", 5);
    let s = *ep.state();
    let d = draw_of(&ep, None, &[Layer::Robot]);
    let [body, nose] = items(&d, Layer::Robot)[..] else {
        panic!("footprint and heading");
    };
    assert_eq!((body.shape, body.tag), (Shape::Discs, 0.0));
    let n = d.numbers(&body);
    assert_eq!(&n[..3], &[s.x, s.y, 0.2]);
    assert!(close(n[3].hypot(n[4]), s.v.hypot(s.vy)));
    assert_eq!((nose.shape, nose.tag), (Shape::Segments, 1.0));
    let h = d.numbers(&nose);
    assert_eq!(&h[..2], &[s.x, s.y]);
    assert!(close((h[3] - h[1]).atan2(h[2] - h[0]), s.theta));
    assert!(close((h[2] - h[0]).hypot(h[3] - h[1]), 0.2));

    // A rectangle: four corners around the pose, the nose to its front.
    let rect = Footprint::Rectangle {
        length: 0.6,
        width: 0.4,
    };
    let ep = episode("dwa", rect);
    let s = *ep.state();
    let d = draw_of(&ep, None, &[Layer::Robot]);
    let [body, nose] = items(&d, Layer::Robot)[..] else {
        panic!("footprint and heading");
    };
    assert_eq!(body.shape, Shape::Polygon);
    let c = xy(&d, &body);
    assert_eq!(c.len(), 4);
    let centre = c
        .iter()
        .fold([0.0; 2], |a, p| [a[0] + p[0] / 4.0, a[1] + p[1] / 4.0]);
    assert!(close(centre[0], s.x) && close(centre[1], s.y));
    assert!(close((c[1][0] - c[0][0]).hypot(c[1][1] - c[0][1]), 0.6));
    assert!(close((c[2][0] - c[1][0]).hypot(c[2][1] - c[1][1]), 0.4));
    let h = d.numbers(&nose);
    assert!(close((h[2] - h[0]).hypot(h[3] - h[1]), 0.3));
    assert!(close((h[3] - h[1]).atan2(h[2] - h[0]), 0.3));
}

#[test]
fn goals_are_start_final_and_the_goal_steered_to() {
    let ep = episode("improved-dwa", Footprint::default());
    let d = draw_of(&ep, None, &[Layer::Goals]);
    let g = items(&d, Layer::Goals);
    let pts: Vec<_> = g.iter().map(|i| (i.tag, xy(&d, i)[0])).collect();
    assert_eq!(
        pts,
        [(0.0, [0.5, 4.5]), (1.0, [7.5, 4.5]), (2.0, [7.5, 4.5])]
    );
    assert_eq!(g[2].value, 0.0, "final before the first step");
    let ep = stepped("improved-dwa", 3);
    let row = ep.trace().steps.last().unwrap();
    assert_ne!(row.goal_kind, GoalKind::Final, "steers to a key point");
    let d = draw_of(&ep, None, &[Layer::Goals]);
    let g = items(&d, Layer::Goals);
    assert_eq!(xy(&d, &g[2]), [row.goal]);
    assert_eq!(g[2].value, row.goal_kind as u8 as f64);
}

#[test]
fn lidar_layers_are_the_scan_and_what_the_navigator_made_of_it() {
    // The six LiDAR layers, LidarRays to LidarTarget.
    let lidar = &Layer::ALL[Layer::LidarRays as usize..=Layer::LidarTarget as usize];
    assert_eq!(lidar.len(), 6);
    // Nothing before the first step, nor for a planner without a LiDAR.
    let ep = episode("lidar-dwa", Footprint::default());
    assert!(draw_of(&ep, None, lidar).items.is_empty());
    assert!(draw_of(&stepped("dwa", 2), None, lidar).items.is_empty());

    let ep = stepped("lidar-dwa", 3);
    let l = ep.planner_debug().lidar.clone().unwrap();
    let d = draw_of(&ep, None, lidar);
    // Rays: every beam once, from the sensor, to its range.
    let rays = items(&d, Layer::LidarRays);
    let mut beams = 0;
    for r in &rays {
        let hit = r.tag == 1.0;
        for s in d.numbers(r).chunks(4) {
            assert_eq!(&s[..2], &l.pose[..2]);
            let len = (s[2] - s[0]).hypot(s[3] - s[1]);
            assert!(l.ranges.iter().any(|&x| (x - len).abs() < 1e-9));
            assert!(hit || (len - l.max_range).abs() < 1e-9);
            beams += 1;
        }
    }
    assert_eq!(beams, l.ranges.len());
    assert_eq!(
        rays.iter().filter(|r| r.tag == 1.0).count(),
        1,
        "the room returns"
    );
    let edges = items(&d, Layer::LidarEdges);
    assert_eq!(edges.len(), l.edges.len());
    for (i, e) in edges.iter().zip(&l.edges) {
        assert_eq!((xy(&d, i)[0], i.tag), (e.point, f64::from(e.kind.code())));
    }
    let raw = items(&d, Layer::LidarOpsRaw);
    assert_eq!(raw.iter().map(|i| xy(&d, i)).collect::<Vec<_>>(), l.ops_raw);
    let ops = items(&d, Layer::LidarOps);
    assert_eq!(ops.iter().map(|i| xy(&d, i)).collect::<Vec<_>>(), l.ops);
    for (k, i) in ops.iter().enumerate() {
        assert_eq!(i.value == 1.0, l.blocking == Some(k));
    }
    let cands = items(&d, Layer::LidarCandidates);
    assert_eq!(cands.len(), l.candidates.len());
    for (i, c) in cands.iter().zip(&l.candidates) {
        assert_eq!(
            (xy(&d, i)[0], i.tag, i.value),
            (c.point, f64::from(c.iteration), c.cost)
        );
    }
    let target = items(&d, Layer::LidarTarget);
    assert_eq!(xy(&d, &target[0]), [l.target]);
    assert_eq!(target.len(), 1 + usize::from(l.hold_remaining > 0.0));
}

#[test]
fn a_trace_frame_is_the_row_with_mover_velocities_from_the_next() {
    let ep = stepped("improved-dwa", 8);
    let rows = &ep.trace().steps;
    let (k, r) = (5, &ep.trace().steps[5]);
    let mut d = DrawList::default();
    let layers = [Layer::Movers, Layer::Robot, Layer::Goals]
        .into_iter()
        .collect();
    draw::trace_frame(&ep, k, ep.movers(), layers, &mut d);
    let body = items(&d, Layer::Robot)[0];
    assert_eq!(&d.numbers(&body)[..2], &[r.x, r.y]);
    let movers = items(&d, Layer::Movers);
    assert_eq!(movers.len(), r.movers.len());
    let dt = ep.config().dt;
    for (i, (id, p)) in movers.iter().zip(&r.movers) {
        let next = rows[k + 1].movers.iter().find(|m| m.0 == *id).unwrap().1;
        let n = d.numbers(i);
        assert_eq!(&n[..2], p);
        assert_eq!(n[2], if *id == 3 { 0.25 } else { 0.3 });
        assert!(close(n[3], (next[0] - p[0]) / dt) && close(n[4], (next[1] - p[1]) / dt));
    }
    assert!(
        close(d.numbers(&movers[0])[3], -0.2),
        "the constant velocity"
    );
    let g = items(&d, Layer::Goals);
    assert_eq!(xy(&d, &g[2]), [r.goal]);
    // The last row takes its velocities from the row before; a mover
    // without a spec gets the default radius; past the end, nothing.
    d.clear();
    draw::trace_frame(&ep, rows.len() - 1, &[], layers, &mut d);
    let m = d.numbers(&items(&d, Layer::Movers)[0]).to_vec();
    assert_eq!(m[2], 0.2);
    assert!(close(m[3], -0.2));
    d.clear();
    draw::trace_frame(&ep, rows.len(), ep.movers(), layers, &mut d);
    assert!(d.items.is_empty());
}

#[test]
fn items_come_in_layer_order_and_only_for_the_layers_asked() {
    let ep = stepped("improved-dwa", 3);
    let mut d = DrawList::default();
    let all = Request {
        layers: Layers::ALL,
        trail_from: 0,
        ..Request::default()
    };
    draw::episode(&ep, None, all, &mut d);
    let codes: Vec<u8> = d.items.iter().map(|i| i.layer as u8).collect();
    assert!(codes.windows(2).all(|w| w[0] <= w[1]), "{codes:?}");
    for i in &d.items {
        assert_eq!((i.end - i.start) % i.shape.stride(), 0, "{i:?}");
        assert!(i.end <= d.data.len());
    }
    d.clear();
    draw::episode(&ep, None, Request::default(), &mut d);
    assert!(d.items.is_empty());
}
