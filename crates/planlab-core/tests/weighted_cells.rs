//! Weighted cells (docs/algorithms.md §weights): every optimal grid planner
//! against an independent Dijkstra on seeded random weighted maps, the
//! planners that cannot honour weights saying so, and repairs of D* Lite
//! after a weight edit.

use planlab_core::global::astar::{AStar, AStarConfig};
use planlab_core::global::classic::{Bfs, BidirectionalAStar, Greedy, IdaStar, ThetaStar};
use planlab_core::global::dstar_lite::{DStarLite, DStarLitePlanner};
use planlab_core::global::jps::{Jps, JpsConfig};
use planlab_core::global::plan::{plan_on_map, Algorithm, GridPlanOptions};
use planlab_core::global::safe_astar::{SafeAStar, SafeAStarConfig};
use planlab_core::global::{Diagonal, GridPlanner, GridPos, Heuristic, Path, PlanError, PlanGrid};
use planlab_core::map::{Cell, OccupancyGrid};
use std::cmp::Ordering;
use std::collections::BinaryHeap;

const SQRT2: f64 = std::f64::consts::SQRT_2;
const RULES: [Diagonal; 4] = [
    Diagonal::Never,
    Diagonal::NoCornerCutting,
    Diagonal::OneSideFree,
    Diagonal::Always,
];

fn p(col: u32, row: u32) -> GridPos {
    GridPos::new(col, row)
}

/// xorshift64: seeded, no dependency.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
}

/// A `w × h` map with ~20 % walls and weights 1–9 on ~half the free cells,
/// and two free cells.
fn random_map(seed: u64, w: usize, h: usize) -> (OccupancyGrid, GridPos, GridPos) {
    let mut rng = Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1);
    let mut cells = Vec::with_capacity(w * h);
    let mut weights = Vec::with_capacity(w * h);
    for _ in 0..w * h {
        let wall = rng.below(100) < 20;
        cells.push(if wall { Cell::Occupied } else { Cell::Free });
        weights.push(if rng.below(2) == 0 {
            1
        } else {
            1 + rng.below(9) as u8
        });
    }
    let map = OccupancyGrid::from_cells(w, h, cells)
        .unwrap()
        .with_weights(weights)
        .unwrap();
    let free: Vec<GridPos> = (0..h)
        .flat_map(|r| (0..w).map(move |c| p(c as u32, r as u32)))
        .filter(|q| map.get(q.col as usize, q.row as usize) == Some(Cell::Free))
        .collect();
    let a = free[rng.below(free.len() as u64) as usize];
    let b = free[rng.below(free.len() as u64) as usize];
    (map, a, b)
}

#[derive(PartialEq)]
struct Open(f64, usize);
impl Eq for Open {}
impl Ord for Open {
    fn cmp(&self, o: &Self) -> Ordering {
        o.0.total_cmp(&self.0)
    }
}
impl PartialOrd for Open {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}

/// A plain Dijkstra over the map itself (no planner code): a move costs its
/// length times the weight of the cell it enters.
fn reference_cost(
    map: &OccupancyGrid,
    start: GridPos,
    goal: GridPos,
    rule: Diagonal,
) -> Option<f64> {
    let (w, h) = (map.width() as i64, map.height() as i64);
    let free = |c: i64, r: i64| {
        c >= 0 && r >= 0 && c < w && r < h && map.get(c as usize, r as usize) == Some(Cell::Free)
    };
    let id = |c: i64, r: i64| (r * w + c) as usize;
    let mut dist = vec![f64::INFINITY; (w * h) as usize];
    let mut open = BinaryHeap::new();
    dist[id(start.col as i64, start.row as i64)] = 0.0;
    open.push(Open(0.0, id(start.col as i64, start.row as i64)));
    while let Some(Open(d, i)) = open.pop() {
        if d > dist[i] {
            continue;
        }
        let (c, r) = (i as i64 % w, i as i64 / w);
        if (c, r) == (goal.col as i64, goal.row as i64) {
            return Some(d);
        }
        for dr in -1..=1i64 {
            for dc in -1..=1i64 {
                let (nc, nr) = (c + dc, r + dr);
                if (dc, dr) == (0, 0) || !free(nc, nr) {
                    continue;
                }
                let len = if dc != 0 && dr != 0 {
                    if !rule.allows(free(nc, r), free(c, nr)) {
                        continue;
                    }
                    SQRT2
                } else {
                    1.0
                };
                let step = len * f64::from(map.weight(nc as usize, nr as usize));
                let j = id(nc, nr);
                if d + step < dist[j] {
                    dist[j] = d + step;
                    open.push(Open(d + step, j));
                }
            }
        }
    }
    None
}

/// The cost of `path` recomputed from the map: each king move's length
/// times the weight entered. Panics on a move that is not a king move.
fn recomputed(map: &OccupancyGrid, path: &Path) -> f64 {
    path.cells
        .windows(2)
        .map(|w| {
            let (dc, dr) = (w[0].col.abs_diff(w[1].col), w[0].row.abs_diff(w[1].row));
            let len = match (dc, dr) {
                (1, 0) | (0, 1) => 1.0,
                (1, 1) => SQRT2,
                other => panic!("not a king move: {other:?}"),
            };
            len * f64::from(map.weight(w[1].col as usize, w[1].row as usize))
        })
        .sum()
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * a.abs().max(1.0)
}

/// Every optimal planner equals the reference on weighted random maps:
/// five seeds × every diagonal rule × several queries, and the path it
/// returns really costs what it says.
#[test]
fn optimal_planners_equal_dijkstra_on_random_weighted_maps() {
    let mut compared = 0;
    for seed in 1..=5u64 {
        for (k, rule) in RULES.into_iter().enumerate() {
            let (map, start, goal) = random_map(seed * 10 + k as u64, 24, 18);
            let grid = PlanGrid::new(&map, false);
            assert!(grid.is_weighted());
            let best = reference_cost(&map, start, goal, rule);
            let ida_heuristic = if rule == Diagonal::Never {
                Heuristic::Manhattan
            } else {
                Heuristic::Octile
            };
            let planners: Vec<(&str, Box<dyn GridPlanner>)> = vec![
                (
                    "astar",
                    Box::new(
                        AStar::new(AStarConfig {
                            diagonal: rule,
                            ..Default::default()
                        })
                        .unwrap(),
                    ),
                ),
                (
                    "astar-euclidean",
                    Box::new(
                        AStar::new(AStarConfig {
                            diagonal: rule,
                            heuristic: Heuristic::Euclidean,
                            ..Default::default()
                        })
                        .unwrap(),
                    ),
                ),
                ("dijkstra", Box::new(AStar::dijkstra(rule))),
                (
                    "bidirectional-astar",
                    Box::new(BidirectionalAStar {
                        diagonal: rule,
                        heuristic: ida_heuristic,
                    }),
                ),
                (
                    "ida-star",
                    Box::new(IdaStar {
                        diagonal: rule,
                        heuristic: ida_heuristic,
                    }),
                ),
                ("dstar-lite", Box::new(DStarLitePlanner { diagonal: rule })),
            ];
            for (name, planner) in planners {
                let got = planner.plan(&grid, start, goal);
                match (best, got) {
                    (None, Err(PlanError::Unreachable { .. })) => {}
                    (Some(b), Ok(path)) => {
                        assert!(
                            close(path.cost, b),
                            "seed {seed} {rule:?} {name}: cost {} but optimum {b}",
                            path.cost
                        );
                        assert!(
                            close(recomputed(&map, &path), path.cost),
                            "seed {seed} {rule:?} {name}: path recomputes to {}",
                            recomputed(&map, &path)
                        );
                        assert_eq!(path.cells.first(), Some(&start));
                        assert_eq!(path.cells.last(), Some(&goal));
                        assert!(grid.path_is_free(&path.cells, rule), "{name} {rule:?}");
                        compared += 1;
                    }
                    (b, g) => panic!(
                        "seed {seed} {rule:?} {name}: reference {b:?}, planner {:?}",
                        g.map(|p| p.cost)
                    ),
                }
            }
        }
    }
    // The seeds must give real queries, not only unreachable ones.
    assert!(compared >= 60, "only {compared} comparisons");
}

/// The same check across many start/goal pairs on one larger map, for A*
/// and Dijkstra (the fast fixed-point search), plus weighted A*'s bound.
#[test]
fn astar_is_optimal_and_weighted_astar_bounded_on_many_weighted_queries() {
    for seed in [7u64, 8, 9] {
        let (map, _, _) = random_map(seed, 60, 40);
        let grid = PlanGrid::new(&map, false);
        let mut rng = Rng(seed);
        let mut found = 0;
        for _ in 0..40 {
            let pick = |rng: &mut Rng| loop {
                let q = p(rng.below(60) as u32, rng.below(40) as u32);
                if map.get(q.col as usize, q.row as usize) == Some(Cell::Free) {
                    break q;
                }
            };
            let (s, t) = (pick(&mut rng), pick(&mut rng));
            let best = reference_cost(&map, s, t, Diagonal::NoCornerCutting);
            let a = AStar::default().plan(&grid, s, t);
            let d = AStar::dijkstra(Diagonal::NoCornerCutting).plan(&grid, s, t);
            let w = AStar::new(AStarConfig {
                weight: 2.0,
                ..Default::default()
            })
            .unwrap()
            .plan(&grid, s, t);
            match (best, a, d, w) {
                (Some(b), Ok(a), Ok(d), Ok(w)) => {
                    assert!(close(a.cost, b) && close(d.cost, b), "{s:?}→{t:?}");
                    assert!(close(recomputed(&map, &a), a.cost));
                    assert!(w.cost <= 2.0 * b + 1e-9 && w.cost >= b - 1e-9);
                    assert!(close(recomputed(&map, &w), w.cost));
                    found += 1;
                }
                (None, Err(_), Err(_), Err(_)) => {}
                (b, a, d, w) => panic!(
                    "{s:?}→{t:?}: {b:?} {:?} {:?} {:?}",
                    a.map(|p| p.cost),
                    d.map(|p| p.cost),
                    w.map(|p| p.cost)
                ),
            }
        }
        assert!(found > 20, "seed {seed}: {found} reachable queries");
    }
}

/// Safe A* with no safety term, over the 8-neighbourhood, is A* with a
/// Euclidean estimate: on weighted cells it must find the optimum too.
#[test]
fn safe_astar_without_its_safety_term_is_optimal_on_weighted_cells() {
    let safe = SafeAStar::new(SafeAStarConfig {
        epsilon: 0.0,
        admissible: true,
        neighbourhood: 8,
        ..Default::default()
    })
    .unwrap();
    for seed in 1..=5u64 {
        let (map, s, t) = random_map(seed + 100, 20, 20);
        let grid = PlanGrid::new(&map, false);
        let best = reference_cost(&map, s, t, Diagonal::NoCornerCutting);
        match (best, safe.plan(&grid, s, t)) {
            (Some(b), Ok(path)) => {
                assert!(close(path.cost, b), "seed {seed}: {} vs {b}", path.cost)
            }
            (None, Err(_)) => {}
            (b, r) => panic!("seed {seed}: {b:?} vs {:?}", r.map(|p| p.cost)),
        }
    }
}

/// A band of weight-9 cells across the straight line: A* goes round it
/// (cheaper than crossing), at Dijkstra's cost; BFS crosses it, and the
/// plan says BFS ignores weights.
#[test]
fn astar_goes_round_a_heavy_band_that_bfs_crosses() {
    let map = OccupancyGrid::from_ascii(
        "
...........
...........
.....9.....
.....9.....
.....9.....
.....9.....
.....9.....
...........
...........
",
    )
    .unwrap();
    let (s, t) = (p(1, 4), p(9, 4));
    let plan = |algorithm| {
        plan_on_map(
            &map,
            s,
            t,
            &GridPlanOptions {
                algorithm,
                ..Default::default()
            },
        )
        .unwrap()
    };
    let astar = plan(Algorithm::AStar);
    let dijkstra = plan(Algorithm::Dijkstra);
    let bfs = plan(Algorithm::Bfs);
    assert!(close(astar.path.cost, dijkstra.path.cost));
    assert_eq!(astar.path.cells.first(), Some(&s));
    assert_eq!(astar.path.cells.last(), Some(&t));
    assert!(close(recomputed(&map, &astar.path), astar.path.cost));
    assert!(
        astar
            .path
            .cells
            .iter()
            .all(|c| map.weight(c.col as usize, c.row as usize) == 1),
        "A* crossed the band: {:?}",
        astar.path.cells
    );
    // Round the band's end: dearer than the 8 of the straight line, cheaper
    // than the 7 + 9 of going straight over.
    assert!(
        astar.path.cost > 8.0 && astar.path.cost < 16.0,
        "{}",
        astar.path.cost
    );
    assert!(astar.note.is_none());
    // BFS goes straight through the weight-9 cell: 7 moves of 1, one of 9.
    assert!(bfs.path.cells.contains(&p(5, 4)), "{:?}", bfs.path.cells);
    assert!(close(bfs.path.cost, 16.0), "{}", bfs.path.cost);
    let note = bfs.note.expect("BFS on weighted cells says so");
    assert!(note.contains("ignores cell weights"), "{note}");
    // The geometric length is not the weighted cost.
    assert!(close(bfs.length_m, 8.0), "{}", bfs.length_m);
    // Unit map: no note, BFS as before.
    let unit = OccupancyGrid::from_ascii("....\n").unwrap();
    let bfs_unit = plan_on_map(
        &unit,
        p(0, 0),
        p(3, 0),
        &GridPlanOptions {
            algorithm: Algorithm::Bfs,
            ..Default::default()
        },
    )
    .unwrap();
    assert!(bfs_unit.note.is_none());
}

/// Jump Point Search prunes by symmetry of equal-cost paths, so it refuses
/// weighted cells with a typed error instead of a wrong answer; on the same
/// map without weights it plans as before.
#[test]
fn jump_point_search_refuses_weighted_cells_with_a_typed_error() {
    let map = OccupancyGrid::from_ascii(".....\n..5..\n.....\n").unwrap();
    let grid = PlanGrid::new(&map, false);
    for diagonal in [Diagonal::NoCornerCutting, Diagonal::Never] {
        let jps = Jps::new(JpsConfig {
            diagonal,
            ..Default::default()
        })
        .unwrap();
        let err = jps.plan(&grid, p(0, 1), p(4, 1)).unwrap_err();
        assert!(
            matches!(err, PlanError::NeedsUniformCosts { .. }),
            "{err:?}"
        );
        assert!(err.to_string().contains("weighted cells"), "{err}");
        let unit = PlanGrid::new(
            &OccupancyGrid::from_ascii(".....\n.....\n.....\n").unwrap(),
            false,
        );
        assert_eq!(jps.plan(&unit, p(0, 1), p(4, 1)).unwrap().cost, 4.0);
    }
}

/// Theta*, greedy and BFS are not optimal, but the cost they report is the
/// weighted cost of the path they return, and Theta* never pays more than
/// its grid moves would.
#[test]
fn suboptimal_planners_report_the_weighted_cost_of_their_path() {
    for seed in 1..=5u64 {
        let (map, s, t) = random_map(seed + 200, 20, 16);
        let grid = PlanGrid::new(&map, false);
        let Some(best) = reference_cost(&map, s, t, Diagonal::NoCornerCutting) else {
            continue;
        };
        for planner in [
            Box::new(Bfs::default()) as Box<dyn GridPlanner>,
            Box::new(Greedy {
                diagonal: Diagonal::NoCornerCutting,
                heuristic: Heuristic::Octile,
            }),
        ] {
            let path = planner.plan(&grid, s, t).unwrap();
            assert!(close(recomputed(&map, &path), path.cost));
            assert!(path.cost >= best - 1e-9);
        }
        let theta = ThetaStar::default().plan(&grid, s, t).unwrap();
        assert!(close(grid.path_cost(&theta.cells), theta.cost));
        assert!(theta.cost > 0.0 || s == t);
    }
}

/// D* Lite repairs after weight edits to the same cost as a fresh A* on
/// the edited grid.
#[test]
fn dstar_lite_repairs_weight_edits_to_the_fresh_optimum() {
    let (map, s, t) = random_map(42, 30, 20);
    let mut grid = PlanGrid::new(&map, false);
    let mut d = DStarLite::new(&grid, s, t, &GridPlanOptions::default()).unwrap();
    let mut rng = Rng(4242);
    let mut first = d.plan(&mut ());
    for round in 0..12 {
        // Paint weights on cells of the current path (the repair's hard case).
        if let Ok(path) = &first {
            for _ in 0..4 {
                let c = path.cells[rng.below(path.cells.len() as u64) as usize];
                let w = 1 + rng.below(9) as u8;
                grid.set_weight(c.col as usize, c.row as usize, w);
                d.set_weight(c, w);
            }
        }
        let fresh = AStar::default().plan(&grid, s, t);
        first = d.plan(&mut ());
        match (&fresh, &first) {
            (Ok(f), Ok(r)) => assert!(
                close(f.cost, r.cost),
                "round {round}: {} vs {}",
                f.cost,
                r.cost
            ),
            (Err(_), Err(_)) => {}
            _ => panic!("round {round}: {:?} vs {:?}", fresh.is_ok(), first.is_ok()),
        }
    }
}

/// Inflation keeps the weights of the cells it leaves free.
#[test]
fn inflation_keeps_the_weights_of_free_cells() {
    let map = OccupancyGrid::from_ascii("#......\n...9...\n.......\n").unwrap();
    let inflated = planlab_core::map::costmap::inflate(&map, 1.0).unwrap();
    assert_eq!(inflated.weight(3, 1), 9);
    assert_eq!(inflated.get(1, 0), Some(Cell::Occupied));
}

/// The grid page draws what the core lists: a weighted map brings a
/// weights layer with one byte per cell; a unit map brings none.
#[test]
fn a_weighted_map_draws_its_weights_layer() {
    use planlab_core::draw::{grid_plan, DrawList, GridPlanDraw, Layer, Layers, Shape};
    let draw = |map: &OccupancyGrid| {
        let mut d = DrawList::default();
        let p = GridPlanDraw {
            grid: map,
            inflation: None,
            path: &[],
            key_points: &[],
            feature_nodes: &[],
            start: None,
            goal: None,
        };
        grid_plan(&p, Layers::ALL, &mut d);
        d
    };
    let map = OccupancyGrid::from_ascii(".4#\n9..\n").unwrap();
    let d = draw(&map);
    let item = d.layer(Layer::Weights).next().expect("a weights item");
    assert_eq!(item.shape, Shape::Cells);
    assert_eq!(d.cell_bytes(item), &[1, 4, 1, 9, 1, 1]);
    let unit = OccupancyGrid::from_ascii(".##\n...\n").unwrap();
    assert_eq!(draw(&unit).layer(Layer::Weights).count(), 0);
}
