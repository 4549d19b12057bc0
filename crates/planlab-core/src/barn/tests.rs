use super::sdf::fill_interiors;
use super::*;
use crate::world::{RobotState, StaticMap};

/// A minimal SDF world with the given cylinders (x, y), declared under
/// `<world>` and again under `<state>` at `state` poses.
fn sdf(models: &[[f64; 2]], state: &[[f64; 2]]) -> String {
    let mut s = String::from("<sdf version='1.6'><world name='default'>");
    for (k, [x, y]) in models.iter().enumerate() {
        s += &format!(
            "<model name='unit_cylinder_{k}'><static>1</static>\
             <pose frame=''>{x:.6} {y:.6} 0 0 0 0</pose><link name='link'>\
             <collision name='collision'><geometry><cylinder><radius>0.075000</radius>\
             <length>1</length></cylinder></geometry></collision></link></model>"
        );
    }
    s += "<state world_name='default'><model name='ground_plane'><pose>0 0 0 0 0 0</pose></model>";
    for (k, [x, y]) in state.iter().enumerate() {
        s += &format!(
            "<model name='unit_cylinder_{k}'><pose frame=''>{x:.6} {y:.6} 0 0 0 0</pose></model>"
        );
    }
    s + "</state></world></sdf>"
}

/// A 3 × 3 block of cylinders at rows 5–7, columns 10–12 with its centre
/// left out, as the generator writes it, plus one wall cylinder.
fn block_world() -> Vec<[f64; 2]> {
    let mut m = vec![[-4.425, 0.075]];
    for r in 5..8 {
        for c in 10..13 {
            if (r, c) != (6, 11) {
                m.push(cell_centre(r, c));
            }
        }
    }
    m
}

#[test]
fn sdf_import_fills_the_left_out_centre_and_splits_off_the_wall() {
    let m = block_world();
    let w = BarnWorld::from_sdf(7, sdf(&m, &m).as_bytes()).unwrap();
    assert_eq!(w.id, 7);
    assert_eq!(w.wall, vec![[-4.425, 0.075]]);
    assert_eq!(w.occupied_cells(), 9);
    assert!(w.cells[6][11], "the block's centre is filled back");
    let cyl = w.cylinders();
    assert_eq!(cyl.len(), 10);
    assert!(
        cyl.iter()
            .any(|p| (p[0] - (GRID_X0 + 0.9)).abs() < 1e-12
                && (p[1] - (GRID_Y0 + 1.65)).abs() < 1e-12)
    );
}

#[test]
fn fill_interiors_fills_enclosed_groups_only() {
    // A ring of 16 cells (rows/cols 2..=6) around a free 3 × 3 pocket, and
    // a U (rows 10 and 14, columns 0..=3, closed at column 3) open to the
    // border at column 0.
    let ring = |r: usize, c: usize| {
        (2..=6).contains(&r) && (2..=6).contains(&c) && (r == 2 || r == 6 || c == 2 || c == 6)
    };
    let u =
        |r: usize, c: usize| ((r == 10 || r == 14) && c <= 3) || ((10..=14).contains(&r) && c == 3);
    let mut cells = [[false; GRID]; GRID];
    for (r, row) in cells.iter_mut().enumerate() {
        for (c, cell) in row.iter_mut().enumerate() {
            *cell = ring(r, c) || u(r, c);
        }
    }
    let before = cells;
    fill_interiors(&mut cells);
    for r in 0..GRID {
        for c in 0..GRID {
            let pocket = (3..=5).contains(&r) && (3..=5).contains(&c);
            assert_eq!(cells[r][c], before[r][c] || pocket, "cell ({r}, {c})");
        }
    }
    // A diagonal gap closes nothing: a cell next to the ring's corner
    // outside stays free.
    assert!(!cells[1][1]);
}

#[test]
fn malformed_sdf_gives_typed_errors() {
    let m = block_world();
    let mut moved = m.clone();
    moved[3][0] += 0.01;
    let off_grid = vec![[GRID_X0 + 0.07, GRID_Y0]];
    let outside = vec![[GRID_X0 + CELL * 30.0, GRID_Y0]];
    let twice = vec![cell_centre(3, 3), cell_centre(3, 3)];
    let cases: Vec<(Vec<u8>, &str)> = vec![
        (vec![0xff, 0xfe, b'<'], "not UTF-8"),
        (b"<sdf><world>".to_vec(), "bad XML"),
        (b"<sdf version='1.6'/>".to_vec(), "no <sdf><world>"),
        (b"<gazebo><world/></gazebo>".to_vec(), "no <sdf><world>"),
        (sdf(&[], &[]).into_bytes(), "no unit_cylinder"),
        (sdf(&m, &moved).into_bytes(), "differs from the model's"),
        (
            sdf(&m, &[m.clone(), vec![[0.0, 6.0]]].concat()).into_bytes(),
            "not declared",
        ),
        (sdf(&off_grid, &[]).into_bytes(), "no grid cell centre"),
        (sdf(&outside, &[]).into_bytes(), "no grid cell centre"),
        (sdf(&twice, &[]).into_bytes(), "second cylinder"),
        (
            sdf(&m, &[])
                .replacen("0.075000</radius>", "0.2</radius>", 1)
                .into_bytes(),
            "radius 0.2",
        ),
        (
            sdf(&m, &[])
                .replacen("0 0 0 0</pose>", "0 0 0</pose>", 1)
                .into_bytes(),
            "not six numbers",
        ),
        (
            sdf(&m, &[])
                .replacen("0 0 0 0</pose>", "0 0 nan 0</pose>", 1)
                .into_bytes(),
            "not six numbers",
        ),
        (
            sdf(&m, &[])
                .replacen("<pose frame=''>-4.425000 0.075000 0 0 0 0</pose>", "", 1)
                .into_bytes(),
            "no <pose> of 'unit_cylinder_0'",
        ),
    ];
    for (bytes, needle) in cases {
        let e = BarnWorld::from_sdf(3, &bytes).expect_err(needle);
        let text = e.to_string();
        assert!(text.contains(needle), "{text:?} lacks {needle:?}");
        assert!(text.starts_with("BARN world 3"), "{text}");
    }
}

#[test]
fn score_matches_hand_computed_cases() {
    let ot = 6.0;
    // Below 2·OT the time counts as 2·OT: 6 / 12.
    assert_eq!(score(true, 5.0, ot), 0.5);
    assert_eq!(score(true, 0.0, ot), 0.5);
    assert_eq!(score(true, -3.0, ot), 0.5);
    // Between: 6 / 24.
    assert_eq!(score(true, 24.0, ot), 0.25);
    // Above 8·OT it counts as 8·OT: 6 / 48.
    assert_eq!(score(true, 100.0, ot), 0.125);
    assert_eq!(score(true, f64::INFINITY, ot), 0.125);
    // Failures and nonsense score 0, never NaN.
    assert_eq!(score(false, 24.0, ot), 0.0);
    assert_eq!(score(true, f64::NAN, ot), 0.0);
    for bad_ot in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert_eq!(score(true, 24.0, bad_ot), 0.0, "ot {bad_ot}");
    }
}

#[test]
fn reference_path_maps_cells_by_the_run_script_formula() {
    let w = BarnWorld {
        id: 0,
        cells: [[false; GRID]; GRID],
        wall: Vec::new(),
        // x = 0.15·15 − 4.575 = −2.325; y = 0.15·0 + 5.075 and 0.15·4 + 5.075.
        path: vec![[15, 0], [15, 4]],
    };
    let p = w.reference_path();
    assert_eq!(p.len(), 4);
    assert!((p[1][0] + 2.325).abs() < 1e-12 && (p[1][1] - 5.075).abs() < 1e-12);
    assert!((p[2][1] - 5.675).abs() < 1e-12);
    // start (−2.25, 3) → (−2.325, 5.075) → (−2.325, 5.675) → goal (−2.25, 13).
    let want = 0.075f64.hypot(2.075) + 0.6 + 0.075f64.hypot(7.325);
    assert!((w.path_length() - want).abs() < 1e-12);
    assert!((w.optimal_time() - want / 2.0).abs() < 1e-12);
}

#[test]
fn difficulty_cuts_at_the_documented_cell_counts() {
    let mut w = BarnWorld {
        id: 0,
        cells: [[false; GRID]; GRID],
        wall: Vec::new(),
        path: Vec::new(),
    };
    let mut set = |n: usize| {
        for i in 0..GRID * GRID {
            w.cells[i / GRID][i % GRID] = i < n;
        }
        w.difficulty()
    };
    assert_eq!(set(EASY_MAX_CELLS), Difficulty::Easy);
    assert_eq!(set(EASY_MAX_CELLS + 1), Difficulty::Medium);
    assert_eq!(set(MEDIUM_MAX_CELLS), Difficulty::Medium);
    assert_eq!(set(MEDIUM_MAX_CELLS + 1), Difficulty::Hard);
}

/// Exact distance from a footprint at `pose` to a disc of radius
/// [`RADIUS`] at `c` (negative inside).
fn gap(fp: &Footprint, pose: &RobotState, c: [f64; 2]) -> f64 {
    let (dx, dy) = (c[0] - pose.x, c[1] - pose.y);
    match *fp {
        Footprint::Circle { radius } => dx.hypot(dy) - radius - RADIUS,
        Footprint::Rectangle { length, width } => {
            let (s, co) = pose.theta.sin_cos();
            let (u, v) = (co * dx + s * dy, -s * dx + co * dy);
            let (ex, ey) = (
                (u.abs() - 0.5 * length).max(0.0),
                (v.abs() - 0.5 * width).max(0.0),
            );
            ex.hypot(ey) - RADIUS
        }
    }
}

/// A pose of `fp` at heading `theta` whose footprint is `clearance` away
/// from the disc at `c`, approached from direction `phi`.
fn pose_at(fp: &Footprint, c: [f64; 2], phi: f64, theta: f64, clearance: f64) -> RobotState {
    let mut pose = RobotState {
        theta,
        ..RobotState::default()
    };
    // Bisect the distance along the ray: the gap grows with it.
    let (mut lo, mut hi) = (0.0, 2.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        pose.x = c[0] + mid * phi.cos();
        pose.y = c[1] + mid * phi.sin();
        if gap(fp, &pose, c) < clearance {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    pose.x = c[0] + hi * phi.cos();
    pose.y = c[1] + hi * phi.sin();
    pose
}

#[test]
fn conservative_grid_collides_exactly_when_the_robot_touches_a_cylinder() {
    // A block, a lone cylinder and the wall of block_world.
    let mut m = block_world();
    m.push(cell_centre(20, 20));
    let w = BarnWorld::from_sdf(1, sdf(&m, &m).as_bytes()).unwrap();
    let res = TRUTH_RESOLUTION;
    let map = StaticMap::new(w.grid(res).unwrap(), false).unwrap();
    let b = map.bounds();
    // The margin: every disc, the start and the goal lie ≥ 1.5 m inside the map.
    let discs = w.cylinders().into_iter().map(|p| (p, RADIUS));
    for (p, r) in discs.chain([([START.x, START.y], 0.0), (GOAL, 0.0)]) {
        let room = [
            p[0] - r - b[0],
            p[1] - r - b[1],
            b[2] - p[0] - r,
            b[3] - p[1] - r,
        ];
        assert!(
            room.iter().all(|&m| m >= MAP_MARGIN - 1e-9),
            "{p:?}: {room:?}"
        );
    }
    // Conservative: every point of every disc (sampled on its rim, where
    // a cell is most easily lost) lies in an occupied cell.
    let grid = map.grid();
    for c in w.cylinders() {
        for k in 0..720 {
            let a = k as f64 * std::f64::consts::TAU / 720.0;
            let (x, y) = (
                c[0] + RADIUS * (1.0 - 1e-6) * a.cos(),
                c[1] + RADIUS * (1.0 - 1e-6) * a.sin(),
            );
            let (col, row) = grid.world_to_cell(x, y).unwrap();
            assert_eq!(
                grid.get(col, row),
                Some(crate::map::Cell::Occupied),
                "rim of {c:?} at {a} rad"
            );
        }
    }
    let cyl = w.cylinders();
    let diag = res * std::f64::consts::SQRT_2;
    let footprints = [Footprint::Circle { radius: 0.05 }, JACKAL_FOOTPRINT];
    let targets = [
        cell_centre(20, 20),
        cell_centre(5, 11),
        cell_centre(7, 12),
        [-4.425, 0.075],
    ];
    let (mut touched, mut cleared) = (0, 0);
    for fp in &footprints {
        for c in targets {
            for k in 0..24 {
                let phi = k as f64 * std::f64::consts::TAU / 24.0;
                for theta in [0.0, 0.4, 1.3] {
                    let touch = pose_at(fp, c, phi, theta, -1e-7);
                    assert!(
                        map.footprint_collides(fp, &touch),
                        "{fp:?} touching {c:?} at {touch:?}"
                    );
                    touched += 1;
                    let clear = pose_at(fp, c, phi, theta, diag + 1e-7);
                    let nearest = cyl
                        .iter()
                        .map(|&o| gap(fp, &clear, o))
                        .fold(f64::INFINITY, f64::min);
                    if nearest > diag {
                        assert!(
                            !map.footprint_collides(fp, &clear),
                            "{fp:?} clear of {c:?} at {clear:?}"
                        );
                        cleared += 1;
                    }
                }
            }
        }
    }
    assert_eq!(touched, 2 * 4 * 24 * 3);
    assert!(cleared > 200, "only {cleared} clear poses checked");
}

#[test]
fn grid_refuses_bad_resolutions() {
    let m = block_world();
    let w = BarnWorld::from_sdf(1, sdf(&m, &[]).as_bytes()).unwrap();
    for r in [0.0, -0.1, f64::NAN] {
        assert!(matches!(w.grid(r), Err(BarnError::Map(_))));
    }
    // A resolution so fine the map would be too large is refused, not allocated.
    assert!(matches!(
        w.grid(1e-5),
        Err(BarnError::Map(MapError::TooLarge { .. }))
    ));
}

#[test]
fn compact_form_round_trips_and_rejects_malformed_lines() {
    let m = block_world();
    let mut a = BarnWorld::from_sdf(4, sdf(&m, &m).as_bytes()).unwrap();
    a.path = vec![[26, 0], [26, 0], [-1, 31]];
    let mut b = a.clone();
    b.id = 5;
    b.path.clear();
    b.cells[0][0] = true;
    let mut c = b.clone();
    c.id = 9;
    c.wall = vec![[-4.275000000000001, 0.1]];
    let worlds = vec![a, b, c];
    let text = to_compact(&worlds);
    assert_eq!(
        text.matches("\nwall").count(),
        2,
        "the wall is written when it changes:\n{text}"
    );
    assert_eq!(parse_compact(&text).unwrap(), worlds);

    let hex = "0".repeat(225);
    let bad = [
        (format!("1 {hex} -"), 1, "before any `wall`"),
        (format!("wall 1,2\n1 {hex}"), 2, "expected `id grid path`"),
        (format!("wall 1,2\nx {hex} -"), 2, "not a number"),
        (format!("wall 1,2\n1 {hex}0 -"), 2, "226 characters"),
        (
            format!("wall 1,2\n1 {}g -", "0".repeat(224)),
            2,
            "not a hex digit",
        ),
        (format!("wall 1,2\n1 {hex} 1,2;3"), 2, "row,col"),
        (format!("# c\nwall 1,x\n1 {hex} -"), 2, "wall centre"),
        (format!("wall 1,2\n1 {hex} -\n1 {hex} -"), 3, "twice"),
    ];
    for (text, line, needle) in bad {
        match parse_compact(&text) {
            Err(e @ BarnError::Compact { line: l, .. }) => {
                assert_eq!(l, line, "{e}");
                assert!(e.to_string().contains(needle), "{e} lacks {needle:?}");
            }
            other => panic!("{text:?}: expected a Compact error, got {other:?}"),
        }
    }
}

#[test]
fn grid_covers_every_disc_and_reaches_at_most_a_diagonal_beyond_at_any_resolution() {
    let m = block_world();
    let w = BarnWorld::from_sdf(1, sdf(&m, &[]).as_bytes()).unwrap();
    let cyl = w.cylinders();
    for res in [0.04, 0.05, 0.07, 0.1] {
        let g = w.grid(res).unwrap();
        for c in &cyl {
            for k in 0..360 {
                let a = k as f64 * std::f64::consts::TAU / 360.0;
                let r = RADIUS * (1.0 - 1e-6);
                let (col, row) = g
                    .world_to_cell(c[0] + r * a.cos(), c[1] + r * a.sin())
                    .unwrap();
                assert_eq!(
                    g.get(col, row),
                    Some(Cell::Occupied),
                    "res {res}: rim of {c:?}"
                );
            }
        }
        let mut occupied = 0;
        for row in 0..g.height() {
            for col in 0..g.width() {
                if g.get(col, row) == Some(Cell::Occupied) {
                    occupied += 1;
                    let (x, y) = g.cell_to_world(col, row);
                    // The cell's centre lies within radius + half a diagonal.
                    let near = cyl
                        .iter()
                        .map(|c| (c[0] - x).hypot(c[1] - y))
                        .fold(f64::INFINITY, f64::min);
                    assert!(
                        near <= RADIUS + res * std::f64::consts::FRAC_1_SQRT_2 + 1e-9,
                        "res {res}: ({col}, {row})"
                    );
                }
            }
        }
        assert!(occupied >= cyl.len(), "res {res}");
    }
}
