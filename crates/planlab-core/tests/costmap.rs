//! Inflation, the Euclidean distance field and the ROS-style costmap,
//! checked against brute force, hand-computed cases and a real map.

use planlab_core::map::costmap::{
    distance_field, inflate, Costmap, FREE_SPACE, INSCRIBED, LETHAL, NO_INFORMATION,
};
use planlab_core::map::io::movingai;
use planlab_core::map::{Cell, MapError, OccupancyGrid, Pose2};
use proptest::prelude::*;

/// O(N²) distance field: metres from each cell centre to the nearest
/// occupied cell centre.
fn brute_distance(g: &OccupancyGrid) -> Vec<f64> {
    let (w, h) = (g.width(), g.height());
    let occupied: Vec<(usize, usize)> = (0..h)
        .flat_map(|r| (0..w).map(move |c| (c, r)))
        .filter(|&(c, r)| g.get(c, r) == Some(Cell::Occupied))
        .collect();
    let mut out = Vec::with_capacity(w * h);
    for r in 0..h {
        for c in 0..w {
            let best = occupied
                .iter()
                .map(|&(oc, or)| {
                    let dx = oc as f64 - c as f64;
                    let dy = or as f64 - r as f64;
                    (dx * dx + dy * dy).sqrt() * g.resolution()
                })
                .fold(f64::INFINITY, f64::min);
            out.push(best);
        }
    }
    out
}

/// A random grid with all three states; `occ` is the chance of an obstacle.
fn arb_grid(max: usize) -> impl Strategy<Value = OccupancyGrid> {
    (1..=max, 1..=max, 0.0f64..0.5, 0.01f64..2.0).prop_flat_map(|(w, h, occ, res)| {
        proptest::collection::vec(0.0f64..1.0, w * h).prop_map(move |u| {
            let cells = u
                .iter()
                .map(|&x| {
                    if x < occ {
                        Cell::Occupied
                    } else if x < occ + 0.1 {
                        Cell::Unknown
                    } else {
                        Cell::Free
                    }
                })
                .collect();
            OccupancyGrid::from_cells(w, h, cells)
                .unwrap()
                .with_frame(res, Pose2::default())
                .unwrap()
        })
    })
}

fn occupied_set(g: &OccupancyGrid) -> Vec<bool> {
    g.cells().iter().map(|&c| c == Cell::Occupied).collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn distance_field_equals_brute_force(g in arb_grid(24)) {
        let fast = distance_field(&g);
        let slow = brute_distance(&g);
        prop_assert_eq!(fast.len(), slow.len());
        for (i, (a, b)) in fast.iter().zip(&slow).enumerate() {
            if b.is_infinite() {
                prop_assert!(a.is_infinite(), "cell {}: {} vs ∞", i, a);
            } else {
                prop_assert!((a - b).abs() <= 1e-9 * b.max(1.0), "cell {}: {} vs {}", i, a, b);
            }
        }
    }

    #[test]
    fn inflation_matches_brute_force_and_keeps_unknown(g in arb_grid(20), r in 0.0f64..6.0) {
        let radius = r * g.resolution();
        let inflated = inflate(&g, radius).unwrap();
        let slow = brute_distance(&g);
        prop_assert_eq!(inflated.resolution(), g.resolution());
        prop_assert_eq!(inflated.origin(), g.origin());
        for (i, (&before, &after)) in g.cells().iter().zip(inflated.cells()).enumerate() {
            let near = slow[i] <= radius * (1.0 + 1e-9);
            let expect = if near { Cell::Occupied } else { before };
            prop_assert_eq!(after, expect, "cell {} at distance {} (radius {})", i, slow[i], radius);
        }
    }

    #[test]
    fn inflation_is_monotone_in_radius(g in arb_grid(20), a in 0.0f64..5.0, b in 0.0f64..5.0) {
        let (lo, hi) = if a <= b { (a, b) } else { (b, a) };
        let small = occupied_set(&inflate(&g, lo * g.resolution()).unwrap());
        let big = occupied_set(&inflate(&g, hi * g.resolution()).unwrap());
        let orig = occupied_set(&g);
        for i in 0..orig.len() {
            prop_assert!(!orig[i] || small[i], "inflation removed an obstacle");
            prop_assert!(!small[i] || big[i], "cell {} occupied at {} but not at {}", i, lo, hi);
        }
    }

    #[test]
    fn radius_zero_is_identity(g in arb_grid(20)) {
        prop_assert_eq!(inflate(&g, 0.0).unwrap(), g);
    }

    #[test]
    fn costmap_is_consistent_with_inflation(g in arb_grid(16), ins in 0.0f64..3.0, extra in 0.0f64..3.0, k in 0.0f64..20.0) {
        let res = g.resolution();
        let (ins_m, infl_m) = (ins * res, (ins + extra) * res);
        let cm = Costmap::ros(&g, ins_m, infl_m, k).unwrap();
        let lethal_or_inscribed = inflate(&g, ins_m).unwrap();
        let dist = brute_distance(&g);
        for (i, &c) in cm.costs.iter().enumerate() {
            let cell = g.cells()[i];
            match c {
                LETHAL => prop_assert_eq!(cell, Cell::Occupied),
                INSCRIBED => {
                    prop_assert!(cell != Cell::Occupied);
                    prop_assert_eq!(lethal_or_inscribed.cells()[i], Cell::Occupied);
                }
                NO_INFORMATION => {
                    prop_assert_eq!(cell, Cell::Unknown);
                    prop_assert_ne!(lethal_or_inscribed.cells()[i], Cell::Occupied);
                }
                _ => {
                    prop_assert_eq!(cell, Cell::Free);
                    prop_assert_ne!(lethal_or_inscribed.cells()[i], Cell::Occupied);
                    if dist[i] > infl_m * (1.0 + 1e-9) {
                        prop_assert_eq!(c, FREE_SPACE);
                    } else {
                        let expect = (252.0 * (-k * (dist[i] - ins_m).max(0.0)).exp()).floor();
                        prop_assert!((f64::from(c) - expect).abs() <= 1.0, "cell {}: {} vs {}", i, c, expect);
                        prop_assert!(c <= 252);
                    }
                }
            }
        }
    }
}

#[test]
fn small_ascii_cases() {
    let g = OccupancyGrid::from_ascii(
        "
.......
.......
...#...
.......
.......
",
    )
    .unwrap();
    // Radius 1 cell: the 4-neighbours.
    assert_eq!(
        inflate(&g, 1.0).unwrap().to_ascii(),
        ".......\n...#...\n..###..\n...#...\n.......\n"
    );
    // Radius √2: the 3×3 block.
    assert_eq!(
        inflate(&g, 2f64.sqrt()).unwrap().to_ascii(),
        ".......\n..###..\n..###..\n..###..\n.......\n"
    );
    // Radius 2: adds the cells two away in a straight line; (2,1) at √5
    // stays free.
    assert_eq!(
        inflate(&g, 2.0).unwrap().to_ascii(),
        "...#...\n..###..\n.#####.\n..###..\n...#...\n"
    );
    // Metres, not cells: 0.15 m at 0.05 m/cell is exactly 3 cells.
    let fine = g.clone().with_frame(0.05, Pose2::default()).unwrap();
    let three = inflate(&fine, 0.15).unwrap();
    assert_eq!(three.get(0, 2), Some(Cell::Occupied));
    assert_eq!(three.get(6, 2), Some(Cell::Occupied));
    assert_eq!(three.get(1, 0), Some(Cell::Occupied)); // √8 ≈ 2.83 cells
    assert_eq!(three.get(0, 1), Some(Cell::Free)); // √10 ≈ 3.16 cells
    assert_eq!(three.get(0, 0), Some(Cell::Free)); // √13
    assert_eq!(three.resolution(), 0.05);
}

#[test]
fn unknown_cells_stay_unknown_unless_inflated() {
    let g = OccupancyGrid::from_ascii("#.??\n....\n").unwrap();
    let out = inflate(&g, 1.0).unwrap();
    assert_eq!(out.to_ascii(), "##??\n#...\n");
    let out = inflate(&g, 2.0).unwrap();
    assert_eq!(out.to_ascii(), "###?\n##..\n");
}

#[test]
fn empty_and_full_grids() {
    let free = OccupancyGrid::new(5, 4).unwrap();
    assert!(distance_field(&free).iter().all(|d| d.is_infinite()));
    assert_eq!(inflate(&free, 3.0).unwrap(), free);
    let cm = Costmap::ros(&free, 1.0, 2.0, 10.0).unwrap();
    assert!(cm.costs.iter().all(|&c| c == FREE_SPACE));
    let full = OccupancyGrid::from_ascii("##\n##\n").unwrap();
    assert!(distance_field(&full).iter().all(|&d| d == 0.0));
    let cm = Costmap::ros(&full, 0.0, 0.0, 1.0).unwrap();
    assert!(cm.costs.iter().all(|&c| c == LETHAL));
}

#[test]
fn ros_costs_by_hand() {
    // One obstacle at (0, 0); resolution 1 m; inscribed 1 m, inflation 3 m,
    // k = 1 /m.
    let g = OccupancyGrid::from_ascii("#....\n.....\n.....\n.....\n").unwrap();
    let cm = Costmap::ros(&g, 1.0, 3.0, 1.0).unwrap();
    assert_eq!(cm.get(0, 0), Some(LETHAL));
    assert_eq!(cm.get(1, 0), Some(INSCRIBED)); // d = 1
    assert_eq!(cm.get(0, 1), Some(INSCRIBED));
    // d = √2: 252·e^(−0.41421) = 166.6… → 166.
    assert_eq!(cm.get(1, 1), Some(166));
    // d = 2: 252·e^(−1) = 92.70… → 92.
    assert_eq!(cm.get(2, 0), Some(92));
    // d = √5: 252·e^(−1.23607) = 73.2… → 73.
    assert_eq!(cm.get(2, 1), Some(73));
    // d = 3: 252·e^(−2) = 34.10… → 34.
    assert_eq!(cm.get(3, 0), Some(34));
    // d = √10 > 3: free.
    assert_eq!(cm.get(3, 1), Some(FREE_SPACE));
    assert_eq!(cm.get(4, 3), Some(FREE_SPACE));
    assert_eq!(cm.get(5, 0), None);
    assert_eq!((cm.width, cm.height, cm.costs.len()), (5, 4, 20));
}

#[test]
fn ros_unknown_cells() {
    let g = OccupancyGrid::from_ascii("#??\n???\n").unwrap();
    let cm = Costmap::ros(&g, 1.0, 3.0, 1.0).unwrap();
    // Within the inscribed radius unknown becomes INSCRIBED; beyond it stays
    // NO_INFORMATION even inside the inflation radius (ROS default).
    assert_eq!(
        cm.costs,
        vec![
            LETHAL,
            INSCRIBED,
            NO_INFORMATION,
            INSCRIBED,
            NO_INFORMATION,
            NO_INFORMATION
        ]
    );
}

#[test]
fn invalid_radii_are_errors() {
    let g = OccupancyGrid::from_ascii("#.\n").unwrap();
    for r in [f64::NAN, -0.1, f64::INFINITY, f64::NEG_INFINITY] {
        let e = inflate(&g, r).unwrap_err();
        assert!(matches!(e, MapError::InvalidParameter(_)), "{e:?}");
        assert!(e.to_string().contains("inflate radius"), "{e}");
        assert!(Costmap::ros(&g, r, 1.0, 1.0).is_err());
        assert!(Costmap::ros(&g, 0.0, r, 1.0).is_err());
        assert!(Costmap::ros(&g, 0.0, 1.0, r).is_err());
    }
    let e = Costmap::ros(&g, 2.0, 1.0, 1.0).unwrap_err();
    assert!(e.to_string().contains("must not exceed"), "{e}");
}

#[test]
fn real_map_inflation_matches_windowed_brute_force() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../tests/data/movingai/dao/arena2.map"
    ))
    .unwrap();
    let g = movingai::parse_map(&text).unwrap();
    let r = 2.5;
    let inflated = inflate(&g, r).unwrap();
    let (w, h) = (g.width() as i64, g.height() as i64);
    for row in 0..h {
        for col in 0..w {
            let mut near = false;
            for dr in -2..=2i64 {
                for dc in -2..=2i64 {
                    let (c, rr) = (col + dc, row + dr);
                    if g.in_bounds(c, rr)
                        && ((dc * dc + dr * dr) as f64) <= r * r
                        && g.get(c as usize, rr as usize) == Some(Cell::Occupied)
                    {
                        near = true;
                    }
                }
            }
            let got = inflated.get(col as usize, row as usize) == Some(Cell::Occupied);
            assert_eq!(got, near, "cell ({col}, {row})");
        }
    }
    let (f0, o0, _) = g.counts();
    let (f1, o1, _) = inflated.counts();
    assert!(o1 > o0 && f1 < f0 && f1 + o1 == f0 + o0);
}
