//! Safe A* ([S] §1), key points ([T] §3.2.1) and Bottom-Up segmentation
//! ([S] §4.1) through the public API: ASCII fixtures with obvious answers,
//! a brute-force Dijkstra as the optimum, Moving AI maps, and seeded
//! property tests on random maps.

use planlab_core::global::astar::{AStar, AStarConfig};
use planlab_core::global::bottom_up::bottom_up;
use planlab_core::global::keypoints::{key_points, prune, turning_points};
use planlab_core::global::safe_astar::{
    safety_index, safety_term, SafeAStar, SafeAStarConfig, MAX_WINDOW_RADIUS, SAFETY_INDEX_MAX,
};
use planlab_core::global::{
    Diagonal, Endpoint, GridPlanner, GridPos, Heuristic, ObservedGridPlanner, Path, PlanError,
    PlanGrid,
};
use planlab_core::map::OccupancyGrid;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// Root of the test data in the repository (`tests/data`).
const DATA: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../tests/data");

const NCC: Diagonal = Diagonal::NoCornerCutting;

fn p(col: u32, row: u32) -> GridPos {
    GridPos::new(col, row)
}

fn ascii(text: &str) -> PlanGrid {
    PlanGrid::new(&OccupancyGrid::from_ascii(text).unwrap(), false)
}

/// A Moving AI `.map` read by hand (`.`, `G`, `S` passable), so these tests do
/// not depend on the map reader under test elsewhere.
fn movingai(rel: &str) -> PlanGrid {
    let text = std::fs::read_to_string(format!("{DATA}/{rel}")).unwrap();
    let rows: Vec<&str> = text
        .lines()
        .skip_while(|l| l.trim() != "map")
        .skip(1)
        .map(str::trim_end)
        .filter(|l| !l.is_empty())
        .collect();
    let w = rows[0].len();
    PlanGrid::from_fn(w, rows.len(), |c, r| {
        matches!(rows[r].as_bytes()[c], b'.' | b'G' | b'S')
    })
}

/// (start, goal, optimal length) of a `.scen`'s rows.
fn scen(rel: &str) -> Vec<(GridPos, GridPos, f64)> {
    let text = std::fs::read_to_string(format!("{DATA}/{rel}")).unwrap();
    text.lines()
        .skip(1)
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let f: Vec<&str> = l.split('\t').collect();
            let n = |i: usize| f[i].parse::<u32>().unwrap();
            (p(n(4), n(5)), p(n(6), n(7)), f[8].parse().unwrap())
        })
        .collect()
}

/// Successor offsets of the 5×5 block (`reach` 2) or 3×3 block (`reach` 1).
fn block(reach: i64) -> Vec<(i64, i64)> {
    let mut v = Vec::new();
    for dr in -reach..=reach {
        for dc in -reach..=reach {
            if (dc, dr) != (0, 0) {
                v.push((dc, dr));
            }
        }
    }
    v
}

#[derive(PartialEq)]
struct Item(f64, usize);
impl Eq for Item {}
impl PartialOrd for Item {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Item {
    fn cmp(&self, o: &Self) -> Ordering {
        o.0.total_cmp(&self.0).then(o.1.cmp(&self.1))
    }
}

/// Brute-force Dijkstra: every free cell, moves to the offsets of `moves`
/// when the straight segment is free (no corner cutting), cost = Euclidean
/// length. Returns the optimum and one optimal path.
fn dijkstra(
    grid: &PlanGrid,
    s: GridPos,
    t: GridPos,
    moves: &[(i64, i64)],
) -> Option<(f64, Vec<GridPos>)> {
    let (w, h) = (grid.width(), grid.height());
    let mut dist = vec![f64::INFINITY; w * h];
    let mut parent = vec![usize::MAX; w * h];
    let si = s.row as usize * w + s.col as usize;
    dist[si] = 0.0;
    let mut heap = BinaryHeap::from([Item(0.0, si)]);
    while let Some(Item(d, i)) = heap.pop() {
        if d > dist[i] {
            continue;
        }
        let here = p((i % w) as u32, (i / w) as u32);
        if here == t {
            let mut cells = vec![here];
            let mut cur = i;
            while parent[cur] != usize::MAX {
                cur = parent[cur];
                cells.push(p((cur % w) as u32, (cur / w) as u32));
            }
            cells.reverse();
            return Some((d, cells));
        }
        for &(dc, dr) in moves {
            let (c, r) = (here.col as i64 + dc, here.row as i64 + dr);
            if c < 0 || r < 0 || c >= w as i64 || r >= h as i64 || !grid.is_free(c, r) {
                continue;
            }
            let next = p(c as u32, r as u32);
            if !grid.segment_is_free(here, next, NCC) {
                continue;
            }
            let nd = d + ((dc * dc + dr * dr) as f64).sqrt();
            let j = r as usize * w + c as usize;
            if nd < dist[j] {
                dist[j] = nd;
                parent[j] = i;
                heap.push(Item(nd, j));
            }
        }
    }
    None
}

/// An 8-connected shortest path (no corner cutting): the paths key points and
/// Bottom-Up are fed with, as an A* would give.
fn grid_path(grid: &PlanGrid, s: GridPos, t: GridPos) -> Option<Vec<GridPos>> {
    dijkstra(grid, s, t, &block(1)).map(|(_, cells)| cells)
}

/// Euclidean distance in cells from `q` to the nearest blocked cell, cells
/// off the map counting as blocked (the border ring is the nearest of them).
fn clearance(grid: &PlanGrid, q: GridPos) -> f64 {
    let (w, h) = (grid.width() as i64, grid.height() as i64);
    let mut best = f64::INFINITY;
    for r in -1..=h {
        for c in -1..=w {
            if !grid.is_free(c, r) {
                let (dx, dy) = ((c - q.col as i64) as f64, (r - q.row as i64) as f64);
                best = best.min((dx * dx + dy * dy).sqrt());
            }
        }
    }
    best
}

fn mean(v: impl Iterator<Item = f64>) -> f64 {
    let (s, n) = v.fold((0.0, 0usize), |(s, n), x| (s + x, n + 1));
    s / n as f64
}

/// splitmix64: seeded randomness for generated maps.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A random map with obstacle `density` and two free cells far apart when
/// possible (the best of a few draws), or `None` if the map is all blocked.
fn random_case(
    seed: u64,
    w: usize,
    h: usize,
    density: f64,
) -> Option<(PlanGrid, GridPos, GridPos)> {
    let mut rng = Rng(seed);
    let cells: Vec<bool> = (0..w * h).map(|_| rng.unit() >= density).collect();
    let grid = PlanGrid::from_fn(w, h, |c, r| cells[r * w + c]);
    let free: Vec<GridPos> = (0..w * h)
        .filter(|&i| cells[i])
        .map(|i| p((i % w) as u32, (i / w) as u32))
        .collect();
    if free.is_empty() {
        return None;
    }
    let mut best = (free[0], free[0], -1i64);
    for _ in 0..8 {
        let (a, b) = (free[rng.below(free.len())], free[rng.below(free.len())]);
        let d = (a.col as i64 - b.col as i64).abs() + (a.row as i64 - b.row as i64).abs();
        if d > best.2 {
            best = (a, b, d);
        }
    }
    Some((grid, best.0, best.1))
}

fn proptest_config(cases: u32) -> Config {
    Config {
        cases,
        rng_seed: RngSeed::Fixed(0x5eed_91a7),
        failure_persistence: None,
        ..Config::default()
    }
}

fn is_subsequence(sub: &[GridPos], of: &[GridPos]) -> Option<Vec<usize>> {
    let mut idx = Vec::with_capacity(sub.len());
    let mut j = 0;
    for q in sub {
        while j < of.len() && of[j] != *q {
            j += 1;
        }
        if j == of.len() {
            return None;
        }
        idx.push(j);
        j += 1;
    }
    Some(idx)
}

/// Largest distance from `cells[i+1..k]` to the segment `cells[i] cells[k]`.
fn deviation(cells: &[GridPos], i: usize, k: usize) -> f64 {
    let (a, b) = (cells[i], cells[k]);
    let (ax, ay, bx, by) = (a.col as f64, a.row as f64, b.col as f64, b.row as f64);
    let (abx, aby) = (bx - ax, by - ay);
    let len2 = abx * abx + aby * aby;
    cells[i + 1..k]
        .iter()
        .map(|q| {
            let (qx, qy) = (q.col as f64, q.row as f64);
            let t = if len2 == 0.0 {
                0.0
            } else {
                (((qx - ax) * abx + (qy - ay) * aby) / len2).clamp(0.0, 1.0)
            };
            let (ex, ey) = (qx - ax - t * abx, qy - ay - t * aby);
            (ex * ex + ey * ey).sqrt()
        })
        .fold(0.0, f64::max)
}

fn assert_segments_free(grid: &PlanGrid, pts: &[GridPos]) {
    for w in pts.windows(2) {
        assert!(
            grid.segment_is_free(w[0], w[1], NCC),
            "segment {:?} -> {:?} hits an obstacle",
            w[0],
            w[1]
        );
    }
}

fn safe(cfg: SafeAStarConfig) -> SafeAStar {
    SafeAStar::new(cfg).unwrap()
}

fn admissible_eps0(neighbourhood: u32) -> SafeAStar {
    safe(SafeAStarConfig {
        epsilon: 0.0,
        admissible: true,
        neighbourhood,
        ..SafeAStarConfig::default()
    })
}

// ---------------------------------------------------------------- safe A*

#[test]
fn safe_astar_defaults_are_the_papers_and_serde_fills_missing_fields() {
    let d = SafeAStarConfig::default();
    assert_eq!(d.epsilon, 100.0);
    assert_eq!(d.window_radius, 2);
    assert_eq!(d.neighbourhood, 24);
    assert!(!d.admissible);
    assert_eq!(d.heuristic, Heuristic::Euclidean);
    let partial: SafeAStarConfig = serde_json::from_str(r#"{"epsilon": 5.0}"#).unwrap();
    assert_eq!(partial, SafeAStarConfig { epsilon: 5.0, ..d });
    let back: SafeAStarConfig = serde_json::from_str(&serde_json::to_string(&d).unwrap()).unwrap();
    assert_eq!(back, d);
}

#[test]
fn safe_astar_rejects_bad_configs() {
    let bad = [
        SafeAStarConfig {
            epsilon: f64::NAN,
            ..Default::default()
        },
        SafeAStarConfig {
            epsilon: f64::INFINITY,
            ..Default::default()
        },
        SafeAStarConfig {
            epsilon: -1.0,
            ..Default::default()
        },
        SafeAStarConfig {
            window_radius: 0,
            ..Default::default()
        },
        SafeAStarConfig {
            window_radius: MAX_WINDOW_RADIUS + 1,
            ..Default::default()
        },
        SafeAStarConfig {
            neighbourhood: 16,
            ..Default::default()
        },
    ];
    for cfg in bad {
        assert!(
            matches!(SafeAStar::new(cfg), Err(PlanError::InvalidConfig(_))),
            "{cfg:?} accepted"
        );
    }
    for neighbourhood in [4, 8, 24] {
        assert!(SafeAStar::new(SafeAStarConfig {
            neighbourhood,
            window_radius: MAX_WINDOW_RADIUS,
            epsilon: 0.0,
            ..Default::default()
        })
        .is_ok());
    }
}

#[test]
fn safe_astar_typed_errors_for_bad_endpoints() {
    let g = ascii(
        "...#...\n\
         ...#...\n\
         ...#...\n",
    );
    let planner = safe(SafeAStarConfig::default());
    assert!(matches!(
        planner.plan(&g, p(7, 0), p(0, 0)),
        Err(PlanError::OffMap {
            which: Endpoint::Start,
            col: 7,
            ..
        })
    ));
    assert!(matches!(
        planner.plan(&g, p(0, 0), p(0, 3)),
        Err(PlanError::OffMap {
            which: Endpoint::Goal,
            ..
        })
    ));
    assert_eq!(
        planner.plan(&g, p(0, 0), p(3, 1)),
        Err(PlanError::Blocked {
            which: Endpoint::Goal,
            col: 3,
            row: 1
        })
    );
    // The wall is one cell thick; 2-cell moves must not jump it.
    match planner.plan(&g, p(2, 1), p(4, 1)) {
        Err(PlanError::Unreachable { expanded }) => assert_eq!(expanded, 9),
        other => panic!("expected Unreachable, got {other:?}"),
    }
    let empty = PlanGrid::from_fn(0, 0, |_, _| true);
    assert!(matches!(
        planner.plan(&empty, p(0, 0), p(0, 0)),
        Err(PlanError::OffMap { .. })
    ));
}

#[test]
fn safe_astar_start_equals_goal() {
    let g = ascii("...\n...\n");
    let path = safe(SafeAStarConfig::default())
        .plan(&g, p(1, 1), p(1, 1))
        .unwrap();
    assert_eq!(path.cells, vec![p(1, 1)]);
    assert_eq!(path.cost, 0.0);
    assert_eq!(path.expanded, 1);
}

/// A 40×9 corridor between two walls; start and goal two cells below the top
/// wall.
fn corridor() -> PlanGrid {
    let mut rows = vec![".".repeat(40); 9];
    rows[0] = "#".repeat(40);
    rows[8] = "#".repeat(40);
    ascii(&rows.join("\n"))
}

#[test]
fn safe_astar_keeps_farther_from_walls_than_shortest_paths() {
    let g = corridor();
    let (s, t) = (p(2, 2), p(37, 2));
    let shortest8 = grid_path(&g, s, t).unwrap();
    let shortest24 = admissible_eps0(24).plan(&g, s, t).unwrap().cells;
    for variant in [false, true] {
        let planner = safe(SafeAStarConfig {
            admissible: variant,
            ..Default::default()
        });
        let path = planner.plan(&g, s, t).unwrap();
        assert_eq!(path.cells.first(), Some(&s));
        assert_eq!(path.cells.last(), Some(&t));
        assert!(g.path_is_free(&path.cells, NCC));
        let interior = |c: &[GridPos]| c[1..c.len() - 1].to_vec();
        let min_clear = |c: &[GridPos]| {
            interior(c)
                .iter()
                .map(|&q| clearance(&g, q))
                .fold(f64::INFINITY, f64::min)
        };
        let mean_clear = |c: &[GridPos]| mean(c.iter().map(|&q| clearance(&g, q)));
        for other in [&shortest8, &shortest24] {
            assert!(
                mean_clear(&path.cells) > mean_clear(other),
                "admissible={variant}: mean clearance {} vs {}",
                mean_clear(&path.cells),
                mean_clear(other)
            );
            assert!(
                min_clear(&path.cells) > min_clear(other),
                "admissible={variant}: min clearance {} vs {}",
                min_clear(&path.cells),
                min_clear(other)
            );
        }
        // Its safety index reaches the maximum somewhere and never drops below
        // the shortest path's (which hugs the wall all along).
        let si = safety_index(&g, &path.cells, 2);
        let si_short = safety_index(&g, &shortest8, 2);
        assert!(si.contains(&SAFETY_INDEX_MAX));
        assert!(si_short[1..si_short.len() - 1]
            .iter()
            .all(|&x| x < SAFETY_INDEX_MAX));
        assert!(mean(si.iter().copied()) > mean(si_short.iter().copied()));
    }
}

#[test]
fn safe_astar_rounds_a_wall_tip_at_a_distance() {
    // A wall hangs from the top to row 5; the shortest path skims its tip.
    let mut rows = Vec::new();
    for r in 0..12 {
        let row: String = (0..30)
            .map(|c| if c == 15 && r <= 5 { '#' } else { '.' })
            .collect();
        rows.push(row);
    }
    let g = ascii(&rows.join("\n"));
    let (s, t) = (p(3, 3), p(27, 3));
    let shortest = grid_path(&g, s, t).unwrap();
    let path = safe(SafeAStarConfig::default()).plan(&g, s, t).unwrap();
    assert!(g.path_is_free(&path.cells, NCC));
    let min_clear = |c: &[GridPos]| {
        c.iter()
            .map(|&q| clearance(&g, q))
            .fold(f64::INFINITY, f64::min)
    };
    assert_eq!(min_clear(&shortest), 1.0);
    assert!(min_clear(&path.cells) > min_clear(&shortest));
    assert!(
        mean(path.cells.iter().map(|&q| clearance(&g, q)))
            > mean(shortest.iter().map(|&q| clearance(&g, q)))
    );
}

#[test]
fn safe_astar_path_uses_24_neighbour_moves_and_reports_geometric_cost() {
    let (g, s, t) = random_case(7, 40, 30, 0.2).unwrap();
    let planner = safe(SafeAStarConfig::default());
    let mut rec = Vec::new();
    let path = planner.plan_recording(&g, s, t, Some(&mut rec)).unwrap();
    assert_eq!(rec.len(), path.expanded);
    assert_eq!(rec.first(), Some(&s));
    assert_eq!(rec.last(), Some(&t));
    assert!((path.cost - Path::polyline_length(&path.cells)).abs() < 1e-9);
    for w in path.cells.windows(2) {
        let (dc, dr) = (
            (w[1].col as i64 - w[0].col as i64).abs(),
            (w[1].row as i64 - w[0].row as i64).abs(),
        );
        assert!(dc <= 2 && dr <= 2 && (dc, dr) != (0, 0), "{w:?}");
    }
    assert!(g.path_is_free(&path.cells, NCC));
}

#[test]
fn admissible_eps0_matches_moving_ai_optima_with_8_neighbours() {
    let g = movingai("movingai/dao/arena.map");
    let planner = admissible_eps0(8);
    let rows = scen("movingai/dao/arena.map.scen");
    assert!(rows.len() > 50);
    for (s, t, opt) in rows.into_iter().step_by(5) {
        let path = planner.plan(&g, s, t).unwrap();
        assert!(
            (path.cost - opt).abs() < 1e-3,
            "{s:?}->{t:?}: {} vs {opt}",
            path.cost
        );
        assert!(g.path_is_free(&path.cells, NCC));
    }
}

#[test]
fn admissible_eps0_matches_brute_force_24_neighbour_optimum_on_a_real_map() {
    let g = movingai("movingai/dao/arena.map");
    let planner = admissible_eps0(24);
    for (s, t, opt8) in scen("movingai/dao/arena.map.scen").into_iter().step_by(7) {
        let (opt24, _) = dijkstra(&g, s, t, &block(2)).unwrap();
        let path = planner.plan(&g, s, t).unwrap();
        assert!((path.cost - opt24).abs() < 1e-9, "{} vs {opt24}", path.cost);
        // Knight moves can only shorten an 8-connected optimum.
        assert!(opt24 <= opt8 + 1e-3);
    }
}

#[test]
fn safe_astar_plans_on_a_512_map() {
    let g = movingai("movingai/random/random512-10-0.map");
    let rows = scen("movingai/random/random512-10-0.map.scen");
    let (s, t, opt8) = *rows.last().unwrap();
    let path = safe(SafeAStarConfig::default()).plan(&g, s, t).unwrap();
    assert!(g.path_is_free(&path.cells, NCC));
    assert_eq!((path.cells[0], *path.cells.last().unwrap()), (s, t));
    // The detour for safety is real but bounded on this open random map.
    assert!(
        path.cost >= opt8 * 0.9 && path.cost < opt8 * 2.0,
        "{} vs {opt8}",
        path.cost
    );
}

#[test]
fn safety_term_and_index_follow_their_definitions() {
    // 11×11 with obstacles at (5, 5) and (6, 6); the probed cells are ≥ 3
    // from the map edge except where noted.
    let mut rows = vec![".".repeat(11); 11];
    rows[5].replace_range(5..6, "#");
    rows[6].replace_range(6..7, "#");
    let g = ascii(&rows.join("\n"));
    assert_eq!(safety_term(&g, p(5, 3), 2), 1.0 / 2.0); // k 1, s 2
    assert_eq!(safety_term(&g, p(4, 4), 2), 2.0 / 2f64.sqrt()); // k 2, s √2
    assert_eq!(safety_term(&g, p(6, 5), 2), 2.0); // k 2, s 1
    assert_eq!(safety_term(&g, p(5, 2), 2), 0.0); // obstacle 3 rows away
    assert_eq!(safety_term(&g, p(5, 3), 1), 0.0); // outside a 3×3 window
                                                  // Off-map cells count: (5, 1) sees row −1 (5 cells at distance 2).
    assert_eq!(safety_term(&g, p(5, 1), 2), 5.0 / 2.0);
    // Radius 0 is an empty window; huge radii are clamped, not looped over.
    assert_eq!(safety_term(&g, p(5, 3), 0), 0.0);
    assert!(safety_term(&g, p(5, 3), u32::MAX) > 0.0);
    // Off-map queries are answered, not refused.
    assert!(safety_term(&g, p(u32::MAX, u32::MAX), 2) > 0.0);

    let cells = [p(5, 2), p(5, 3), p(4, 4), p(6, 5)];
    let si = safety_index(&g, &cells, 2);
    assert_eq!(si.len(), cells.len());
    assert_eq!(si[0], SAFETY_INDEX_MAX);
    assert!(si[1] < si[0] && si[2] < si[1] && si[3] < si[2], "{si:?}");
    for (q, s) in cells.iter().zip(&si) {
        assert!((s - SAFETY_INDEX_MAX / (1.0 + safety_term(&g, *q, 2))).abs() < 1e-12);
    }
    assert!(safety_index(&g, &[], 2).is_empty());
}

// -------------------------------------------------------------- key points

/// An L-shaped corridor: along the top, then down the right-hand side.
const L_CORRIDOR: &str = "\
.......
######.
######.
######.
";

#[test]
fn l_corridor_gives_start_corner_goal() {
    let g = ascii(L_CORRIDOR);
    let path = grid_path(&g, p(0, 0), p(6, 3)).unwrap();
    assert_eq!(path.len(), 10);
    assert_eq!(turning_points(&path), vec![p(0, 0), p(6, 0), p(6, 3)]);
    assert_eq!(key_points(&g, &path, NCC), vec![p(0, 0), p(6, 0), p(6, 3)]);
}

#[test]
fn s_corridor_keeps_both_corners_and_prunes_the_open_room() {
    // S-bend: right along row 0, down column 6, left along row 4.
    let g = ascii(
        ".......\n\
         ######.\n\
         ######.\n\
         ######.\n\
         .......\n",
    );
    let path = grid_path(&g, p(0, 0), p(0, 4)).unwrap();
    assert_eq!(
        key_points(&g, &path, NCC),
        vec![p(0, 0), p(6, 0), p(6, 4), p(0, 4)]
    );
    // In an open room every zig-zag goes: only start and goal are left.
    let open = ascii(&vec![".".repeat(12); 10].join("\n"));
    let zigzag = [
        p(0, 0),
        p(1, 0),
        p(2, 1),
        p(2, 2),
        p(3, 2),
        p(4, 3),
        p(4, 4),
        p(9, 9),
    ];
    let tp = turning_points(&zigzag);
    assert!(tp.len() > 2);
    assert_eq!(prune(&open, &tp, NCC), vec![p(0, 0), p(9, 9)]);
}

#[test]
fn turning_points_of_a_hand_path() {
    // Right 3, diagonal 2, down 2: 8 cells, 4 turning points.
    let path = [
        p(0, 0),
        p(1, 0),
        p(2, 0),
        p(3, 0),
        p(4, 1),
        p(5, 2),
        p(5, 3),
        p(5, 4),
    ];
    assert_eq!(
        turning_points(&path),
        vec![p(0, 0), p(3, 0), p(5, 2), p(5, 4)]
    );
    // 2-cell moves in the same direction as 1-cell moves are one run.
    let mixed = [p(0, 0), p(2, 1), p(4, 2), p(6, 3), p(7, 3), p(9, 3)];
    assert_eq!(turning_points(&mixed), vec![p(0, 0), p(6, 3), p(9, 3)]);
    assert!(turning_points(&[]).is_empty());
    let g = ascii("..\n..\n");
    assert!(key_points(&g, &[], NCC).is_empty());
    assert_eq!(key_points(&g, &[p(1, 1)], NCC), vec![p(1, 1)]);
}

#[test]
fn prune_never_cuts_a_corner_the_diagonal_rule_forbids() {
    let g = ascii(
        ".#\n\
         ..\n",
    );
    let pts = [p(0, 0), p(0, 1), p(1, 1)];
    assert_eq!(prune(&g, &pts, Diagonal::NoCornerCutting), pts.to_vec());
    assert_eq!(
        prune(&g, &pts, Diagonal::OneSideFree),
        vec![p(0, 0), p(1, 1)]
    );
}

#[test]
fn key_points_are_far_fewer_on_open_maps_with_a_few_obstacles() {
    for seed in 0..10u64 {
        let mut rng = Rng(seed);
        let mut blocked = vec![false; 40 * 40];
        for _ in 0..5 {
            let (c0, r0) = (5 + rng.below(28), 5 + rng.below(28));
            for r in r0..r0 + 3 {
                for c in c0..c0 + 3 {
                    blocked[r * 40 + c] = true;
                }
            }
        }
        let g = PlanGrid::from_fn(40, 40, |c, r| !blocked[r * 40 + c]);
        for (s, t) in [
            (p(0, 0), p(39, 39)),
            (p(0, 39), p(39, 0)),
            (p(0, 20), p(39, 17)),
        ] {
            let path = grid_path(&g, s, t).unwrap();
            let kp = key_points(&g, &path, NCC);
            assert!(
                4 * kp.len() <= path.len(),
                "seed {seed}: {} key points for {} nodes",
                kp.len(),
                path.len()
            );
            assert_segments_free(&g, &kp);
        }
    }
}

#[test]
fn key_points_of_astar_paths_on_a_real_map() {
    let g = movingai("movingai/dao/arena2.map");
    let astar = AStar::new(AStarConfig::default()).unwrap();
    for (s, t, _) in scen("movingai/dao/arena2.map.scen").into_iter().step_by(40) {
        let path = astar.plan(&g, s, t).unwrap().cells;
        let kp = key_points(&g, &path, NCC);
        assert_eq!((kp[0], kp[kp.len() - 1]), (s, t));
        assert!(kp.len() <= turning_points(&path).len());
        assert_segments_free(&g, &kp);
        if path.len() > 40 {
            assert!(4 * kp.len() <= path.len(), "{} of {}", kp.len(), path.len());
        }
    }
}

fn check_key_points(grid: &PlanGrid, path: &[GridPos]) -> Result<(), TestCaseError> {
    let tp = turning_points(path);
    let kp = key_points(grid, path, NCC);
    prop_assert_eq!(kp.first(), path.first());
    prop_assert_eq!(kp.last(), path.last());
    prop_assert!(kp.len() <= tp.len() && tp.len() <= path.len());
    prop_assert!(is_subsequence(&tp, path).is_some());
    prop_assert!(is_subsequence(&kp, &tp).is_some());
    for w in kp.windows(2) {
        prop_assert!(grid.segment_is_free(w[0], w[1], NCC), "{:?}", w);
    }
    // Pruning has run to completion: no remaining point can go.
    for w in kp.windows(3) {
        prop_assert!(
            !grid.segment_is_free(w[0], w[2], NCC),
            "{:?} removable",
            w[1]
        );
    }
    Ok(())
}

proptest! {
    #![proptest_config(proptest_config(96))]

    #[test]
    fn key_points_properties_on_random_maps(
        seed in any::<u64>(), w in 2usize..45, h in 2usize..45, density in 0.0f64..0.4,
    ) {
        if let Some((g, s, t)) = random_case(seed, w, h, density) {
            if let Some(path) = grid_path(&g, s, t) {
                check_key_points(&g, &path)?;
            }
            // Safe A* paths (2-cell moves) go through the same pipeline.
            if let Ok(path) = SafeAStar::new(SafeAStarConfig::default()).unwrap().plan(&g, s, t) {
                check_key_points(&g, &path.cells)?;
            }
        }
    }

    #[test]
    fn safe_astar_properties_on_random_maps(
        seed in any::<u64>(), w in 2usize..30, h in 2usize..30, density in 0.0f64..0.4,
        admissible in any::<bool>(), n_idx in 0usize..3,
    ) {
        let neighbourhood = [4u32, 8, 24][n_idx];
        if let Some((g, s, t)) = random_case(seed, w, h, density) {
            let moves = match neighbourhood {
                4 => vec![(1, 0), (-1, 0), (0, 1), (0, -1)],
                8 => block(1),
                _ => block(2),
            };
            let optimum = dijkstra(&g, s, t, &moves);
            let planner = SafeAStar::new(SafeAStarConfig {
                admissible, neighbourhood, ..Default::default()
            }).unwrap();
            match (planner.plan(&g, s, t), &optimum) {
                (Ok(path), Some((opt, _))) => {
                    prop_assert_eq!(path.cells.first(), Some(&s));
                    prop_assert_eq!(path.cells.last(), Some(&t));
                    prop_assert!(g.path_is_free(&path.cells, NCC));
                    prop_assert!(path.cost >= opt - 1e-9);
                    prop_assert!((path.cost - Path::polyline_length(&path.cells)).abs() < 1e-9);
                }
                (Err(PlanError::Unreachable { .. }), None) => {}
                (got, want) => prop_assert!(false, "{:?} vs optimum {:?}", got, want),
            }
            // ε = 0, admissible: exactly the optimum over the neighbourhood.
            let exact = SafeAStar::new(SafeAStarConfig {
                epsilon: 0.0, admissible: true, neighbourhood, ..Default::default()
            }).unwrap();
            if let (Ok(path), Some((opt, _))) = (exact.plan(&g, s, t), &optimum) {
                prop_assert!((path.cost - opt).abs() < 1e-9, "{} vs {}", path.cost, opt);
            }
        }
    }
}

// --------------------------------------------------------------- Bottom-Up

fn open(w: usize, h: usize) -> PlanGrid {
    PlanGrid::from_fn(w, h, |_, _| true)
}

#[test]
fn bottom_up_straight_path_collapses_to_its_ends() {
    let g = open(12, 3);
    let line: Vec<GridPos> = (0..12).map(|c| p(c, 1)).collect();
    for e in [0.0, 0.5, 3.0] {
        assert_eq!(
            bottom_up(&g, &line, e, NCC).unwrap(),
            vec![p(0, 1), p(11, 1)]
        );
    }
}

#[test]
fn bottom_up_staircase_collapses_with_small_error() {
    let g = open(8, 8);
    let mut stair = vec![p(0, 0)];
    for i in 0..6 {
        stair.push(p(i + 1, i));
        stair.push(p(i + 1, i + 1));
    }
    assert_eq!(stair.len(), 13);
    // Each stair corner lies 1/√2 ≈ 0.71 cells off the diagonal.
    assert_eq!(
        bottom_up(&g, &stair, 0.75, NCC).unwrap(),
        vec![p(0, 0), p(6, 6)]
    );
    let fine = bottom_up(&g, &stair, 0.7, NCC).unwrap();
    assert!(fine.len() > 2, "{fine:?}");
    // max_error 0: only exact collinear merges, which a staircase has none of.
    assert_eq!(bottom_up(&g, &stair, 0.0, NCC).unwrap(), stair);
}

#[test]
fn bottom_up_does_not_merge_through_walls() {
    let g = ascii(L_CORRIDOR);
    let path = grid_path(&g, p(0, 0), p(6, 3)).unwrap();
    assert_eq!(
        bottom_up(&g, &path, 1e6, NCC).unwrap(),
        vec![p(0, 0), p(6, 0), p(6, 3)]
    );
}

#[test]
fn bottom_up_rejects_bad_error_and_passes_tiny_inputs_through() {
    let g = open(3, 3);
    let path = [p(0, 0), p(1, 1), p(2, 2)];
    for e in [f64::NAN, f64::INFINITY, -0.1] {
        assert!(matches!(
            bottom_up(&g, &path, e, NCC),
            Err(PlanError::InvalidConfig(_))
        ));
    }
    assert!(bottom_up(&g, &[], 1.0, NCC).unwrap().is_empty());
    assert_eq!(bottom_up(&g, &path[..1], 1.0, NCC).unwrap(), path[..1]);
    assert_eq!(bottom_up(&g, &path[..2], 1.0, NCC).unwrap(), path[..2]);
    // Garbage coordinates far off the map: no panic, nothing merged across.
    let junk = [p(0, 0), p(u32::MAX, 7), p(2, u32::MAX), p(1, 1)];
    assert_eq!(bottom_up(&g, &junk, 1e9, NCC).unwrap(), junk);
}

#[test]
fn bottom_up_keeps_few_feature_nodes_of_a_long_path_on_a_real_map() {
    // [S] Fig 6: 80 A* nodes -> 7 feature nodes; docs/algorithms.md §experiments asks for ≪ 10%.
    let g = movingai("movingai/dao/arena2.map");
    let rows = scen("movingai/dao/arena2.map.scen");
    let (s, t, opt) = *rows.iter().rev().find(|r| r.2 > 150.0).unwrap();
    let path = AStar::new(AStarConfig::default())
        .unwrap()
        .plan(&g, s, t)
        .unwrap();
    assert!((path.cost - opt).abs() < 1e-3);
    let path = path.cells;
    let feats = bottom_up(&g, &path, 1.5, NCC).unwrap();
    assert!(
        10 * feats.len() < path.len(),
        "{} feature nodes of {}",
        feats.len(),
        path.len()
    );
    assert_segments_free(&g, &feats);
    let safe_path = safe(SafeAStarConfig::default()).plan(&g, s, t).unwrap();
    let safe_feats = bottom_up(&g, &safe_path.cells, 1.5, NCC).unwrap();
    // Safe A* already halves the node count with its 2-cell moves, so its
    // features are < 10% of the A* nodes and < 20% of its own.
    assert!(
        10 * safe_feats.len() < path.len() && 5 * safe_feats.len() < safe_path.cells.len(),
        "{} feature nodes of {} safe A* nodes ({} A* nodes)",
        safe_feats.len(),
        safe_path.cells.len(),
        path.len()
    );
    let feats = safe_feats;
    assert_segments_free(&g, &feats);
}

#[test]
fn bottom_up_keeps_far_fewer_nodes_on_long_paths() {
    // Long corner-to-corner paths on 120×120 maps with 3% random obstacles.
    for seed in 0..12u64 {
        let mut rng = Rng(seed);
        let g = PlanGrid::from_fn(120, 120, |c, r| {
            let corner = !(2..=117).contains(&c) && !(2..=117).contains(&r);
            corner || rng.unit() >= 0.03
        });
        for (s, t) in [(p(0, 0), p(119, 119)), (p(0, 119), p(119, 0))] {
            let path = grid_path(&g, s, t).unwrap();
            let feats = bottom_up(&g, &path, 1.5, NCC).unwrap();
            assert!(
                10 * feats.len() < path.len(),
                "seed {seed}: {} feature nodes of {}",
                feats.len(),
                path.len()
            );
            assert_segments_free(&g, &feats);
        }
    }
}

fn check_bottom_up(grid: &PlanGrid, path: &[GridPos], max_error: f64) -> Result<(), TestCaseError> {
    let out = bottom_up(grid, path, max_error, NCC).unwrap();
    prop_assert_eq!(out.first(), path.first());
    prop_assert_eq!(out.last(), path.last());
    let idx = is_subsequence(&out, path);
    prop_assert!(idx.is_some(), "not a subsequence");
    let idx = idx.unwrap_or_default();
    for w in idx.windows(2) {
        let dev = deviation(path, w[0], w[1]);
        prop_assert!(
            dev < max_error || dev == 0.0,
            "deviation {} ≥ {}",
            dev,
            max_error
        );
        prop_assert!(grid.segment_is_free(path[w[0]], path[w[1]], NCC));
    }
    Ok(())
}

proptest! {
    #![proptest_config(proptest_config(96))]

    #[test]
    fn bottom_up_properties_on_random_maps(
        seed in any::<u64>(), w in 2usize..60, h in 2usize..60, density in 0.0f64..0.35,
        max_error in 0.0f64..4.0,
    ) {
        if let Some((g, s, t)) = random_case(seed, w, h, density) {
            if let Some(path) = grid_path(&g, s, t) {
                check_bottom_up(&g, &path, max_error)?;
                // max_error 0 merges exactly the collinear runs.
                prop_assert_eq!(bottom_up(&g, &path, 0.0, NCC).unwrap(), turning_points(&path));
            }
            if let Ok(path) = SafeAStar::new(SafeAStarConfig::default()).unwrap().plan(&g, s, t) {
                check_bottom_up(&g, &path.cells, max_error)?;
            }
        }
    }
}

/// A passability grid built once gives every query exactly what
/// `plan_on_map` gives (the Python package plans this way).
#[test]
fn planning_on_a_prepared_grid_equals_plan_on_map() {
    use planlab_core::global::plan::{
        plan_grid_for, plan_on_map, plan_on_plan_grid, Algorithm, GridPlanOptions,
    };
    use planlab_core::map::io::movingai;
    let dir =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/data/movingai/dao");
    let grid = movingai::parse_map(&std::fs::read_to_string(dir.join("arena.map")).unwrap())
        .unwrap()
        .with_frame(0.5, Default::default())
        .unwrap();
    let rows = movingai::parse_scen(&std::fs::read_to_string(dir.join("arena.map.scen")).unwrap())
        .unwrap();
    let cases = [
        GridPlanOptions::default(),
        GridPlanOptions {
            algorithm: Algorithm::Jps,
            keypoints: true,
            ..Default::default()
        },
        GridPlanOptions {
            algorithm: Algorithm::SafeAStar,
            bottom_up_eps: Some(1.0),
            ..Default::default()
        },
        GridPlanOptions {
            inflate_m: 0.5,
            ..Default::default()
        },
        GridPlanOptions {
            weight: f64::NAN,
            ..Default::default()
        },
    ];
    let mut planned = 0;
    for options in &cases {
        let prepared = plan_grid_for(&grid, options).unwrap();
        for r in rows.iter().step_by(7) {
            let want = plan_on_map(&grid, r.start, r.goal, options);
            let got = plan_on_plan_grid(&grid, &prepared, r.start, r.goal, options);
            assert_eq!(got, want, "{options:?} {r:?}");
            planned += usize::from(got.is_ok());
        }
    }
    // The cases plan most rows, and the NaN weight refuses every one.
    assert!(planned > 50, "{planned}");
}
