"""Maps and grid plans: the CLI's numbers and the Moving AI optima."""

from __future__ import annotations

import numpy as np
import pytest

import planlab
from conftest import DATA, SCENARIOS

ARENA = DATA / "movingai" / "dao" / "arena.map"
MAZE = DATA / "movingai" / "maze" / "maze512-1-0.map"
RANDOM = DATA / "movingai" / "random" / "random512-10-0.map"


def rows_of(map_path, every=1):
    rows = planlab.load_scen(str(map_path) + ".scen")
    return rows[::every]


@pytest.mark.parametrize("algo", ["astar", "jps", "jps-plus", "dijkstra"])
def test_costs_equal_the_moving_ai_optimum_on_arena(algo):
    grid = planlab.load_map(ARENA)
    rows = rows_of(ARENA)
    assert len(rows) > 100
    for r in rows:
        start, goal = (int(r[0]), int(r[1])), (int(r[2]), int(r[3]))
        res = planlab.plan(grid, start, goal, algo=algo)
        assert res["cost"] == pytest.approx(r[4], rel=1e-3, abs=1e-3), (algo, r)
        path = res["path"]
        assert path.dtype == np.int64 and path.shape[1] == 2
        assert tuple(path[0]) == start and tuple(path[-1]) == goal
        # Every step is one of the 8 moves, onto a free cell.
        steps = np.abs(np.diff(path, axis=0))
        if algo not in ("jps", "jps-plus"):
            assert steps.max() <= 1
        assert not grid.occupancy[path[:, 1], path[:, 0]].any()


def test_jps_plus_returns_jps_paths_and_refuses_four_connected_moves():
    grid = planlab.load_map(ARENA)
    assert "jps-plus" in planlab.algorithms()
    for r in rows_of(ARENA, every=7):
        start, goal = (int(r[0]), int(r[1])), (int(r[2]), int(r[3]))
        jps = planlab.plan(grid, start, goal, algo="jps")
        plus = planlab.plan(grid, start, goal, algo="jps-plus")
        assert plus["path"].tolist() == jps["path"].tolist()
        assert plus["expanded"] == jps["expanded"]
        assert plus["cost"] == jps["cost"]
    with pytest.raises(planlab.ParamError, match="no_corner_cutting"):
        planlab.plan(grid, (1, 10), (10, 10), algo="jps-plus", diagonal="never")


@pytest.mark.parametrize("map_path", [MAZE, RANDOM])
def test_512_maps_match_the_optimum_and_the_cli(cli, map_path):
    grid = planlab.load_map(map_path)
    assert (grid.width, grid.height) == (512, 512)
    rows = rows_of(map_path, every=97)
    for r in rows:
        start, goal = (int(r[0]), int(r[1])), (int(r[2]), int(r[3]))
        res = planlab.plan(grid, start, goal)
        assert res["cost"] == pytest.approx(r[4], rel=1e-3, abs=1e-3)
    # The whole answer equals `planlab plan --json` on a few rows.
    for r in rows[:3]:
        start, goal = (int(r[0]), int(r[1])), (int(r[2]), int(r[3]))
        for algo in ("astar", "jps"):
            want = cli.json("plan", map_path, "--start", f"{start[0]},{start[1]}",
                            "--goal", f"{goal[0]},{goal[1]}", "--algo", algo)
            got = planlab.plan(grid, start, goal, algo=algo)
            assert got["cost"] == want["cost"]
            assert got["expanded"] == want["expanded"]
            assert got["length_m"] == want["length_m"]
            assert got["path"].tolist() == want["path"]


def test_options_reach_the_core_like_the_cli_flags(cli):
    grid = planlab.load_map(ARENA)
    rows = rows_of(ARENA)
    r = rows[int(np.argmax(rows[:, 4]))]  # the longest query
    start, goal = (int(r[0]), int(r[1])), (int(r[2]), int(r[3]))
    s, g = f"{start[0]},{start[1]}", f"{goal[0]},{goal[1]}"
    cases = [
        (dict(algo="astar", heuristic="euclidean", weight=1.5, diagonal="one-side-free"),
         ["--algo", "astar", "--heuristic", "euclidean", "--weight", "1.5",
          "--diagonal", "one-side-free"]),
        (dict(algo="dijkstra", diagonal="never", keypoints=True),
         ["--algo", "dijkstra", "--diagonal", "never", "--keypoints"]),
        (dict(algo="safe-astar", bottom_up=1.0), ["--algo", "safe-astar", "--bottom-up", "1.0"]),
    ]
    for kwargs, flags in cases:
        want = cli.json("plan", ARENA, "--start", s, "--goal", g, *flags)
        got = planlab.plan(grid, start, goal, **kwargs)
        assert (got["cost"], got["expanded"]) == (want["cost"], want["expanded"]), kwargs
        assert got["path"].tolist() == want["path"]
        assert got["keypoints"].tolist() == want["keypoints"]
        if "feature_nodes" in want:
            assert got["feature_nodes"].tolist() == want["feature_nodes"]
        if "safety" in want:
            assert got["safety"].tolist() == want["safety"]
    # The heuristic really is passed: the core's `zero` (not a CLI choice)
    # turns A* into Dijkstra, which expands far more for the same cost.
    a = planlab.plan(grid, start, goal, heuristic="zero")
    b = planlab.plan(grid, start, goal, heuristic="octile")
    assert a["cost"] == b["cost"] and a["expanded"] > 5 * b["expanded"]


def test_a_ros_map_and_a_scenario_map(cli):
    ros = planlab.load_map(DATA / "rosmaps" / "turtlebot3" / "map.yaml")
    occ = ros.occupancy
    assert occ.shape == (ros.height, ros.width) and occ.dtype == np.uint8
    assert set(np.unique(occ)) <= {0, 1, 2} and (occ == 2).any()
    assert ros.resolution == pytest.approx(0.05)
    # A scenario brings its start, goal and grid planner options.
    path = SCENARIOS / "grid-demo.json"
    grid = planlab.load_map(path)
    want = cli.json("plan", path)
    got = planlab.plan(grid)
    assert got["path"].tolist() == want["path"] and got["cost"] == want["cost"]
    assert grid.start == tuple(want["path"][0]) and grid.goal == tuple(want["path"][-1])


def test_a_grid_from_numpy():
    occ = np.zeros((5, 7), dtype=bool)
    occ[1:4, 3] = True
    grid = planlab.Grid(occ, resolution=0.5, origin=(1.0, 2.0, 0.0))
    assert grid.occupancy.tolist() == occ.astype(np.uint8).tolist()
    assert (grid.resolution, grid.origin) == (0.5, (1.0, 2.0, 0.0))
    res = planlab.plan(grid, (0, 2), (6, 2), diagonal="never")
    # Round the wall through row 0 or row 4: 6 across + 2 up + 2 down.
    assert res["cost"] == 10 and res["length_m"] == 5.0
    with pytest.raises(planlab.MapError, match="occupancy value 7"):
        planlab.Grid(np.full((2, 2), 7))
    # 4·10⁸ cells (a zero-copy view): refused before any allocation.
    with pytest.raises(planlab.MapError, match="100000000"):
        planlab.Grid(np.broadcast_to(np.uint8(0), (20000, 20000)))
    for bad, match in [(np.zeros((0, 3), dtype=int), "empty"), (np.zeros(5, dtype=int), "2-D"),
                       ([[0.5, 1]], "bool or integer"), ([[0, -1]], "value -1"),
                       ([[0, 256]], "value 256"), (np.array([[0, 2**62]]), "value 4611686018427387904")]:
        with pytest.raises(planlab.MapError, match=match):
            planlab.Grid(bad)


def test_a_scale_map_is_weighted_and_plan_honours_the_weights():
    # tests/data/weights/band.yaml: an 11 × 5 scale-mode map, a weight-9
    # band at column 5 in rows 0–3 (docs/algorithms.md §weights).
    grid = planlab.load_map(DATA / "weights" / "band.yaml")
    assert grid.weights[0:4, 5].tolist() == [9, 9, 9, 9]
    assert grid.weights[4, 5] == 1 and grid.weights[2, 0] == 1
    astar = planlab.plan(grid, (1, 2), (9, 2), diagonal="never")
    # Round the band's end (12 moves of 1), not through it (7 + 9).
    assert astar["cost"] == pytest.approx(12.0)
    assert astar["note"] is None
    bfs = planlab.plan(grid, (1, 2), (9, 2), algo="bfs", diagonal="never")
    assert bfs["cost"] == pytest.approx(16.0)
    assert "ignores cell weights" in bfs["note"]
    with pytest.raises(planlab.PlanError, match="needs uniform cell costs"):
        planlab.plan(grid, (1, 2), (9, 2), algo="jps")
    # A unit map: all ones.
    assert (planlab.load_map(ARENA).weights == 1).all()
