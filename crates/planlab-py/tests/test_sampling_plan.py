"""planlab.plan with the sampling planners (algo="rrt" … "bit-star"): the
answer of `planlab plan --algo NAME --json`, seeded repeatability, the
solutions list, the time limit and the typed errors."""

from __future__ import annotations

import math

import numpy as np
import pytest

import planlab
from conftest import DATA

ARENA = DATA / "movingai" / "dao" / "arena.map"
ARENA2 = DATA / "movingai" / "dao" / "arena2.map"

# A row of arena2 that needs turns (the bench's rows: round(i·(n−1)/5),
# i = 2), with the disc of the core's tests.
RADIUS = 0.4


def arena2_row():
    rows = planlab.load_scen(str(ARENA2) + ".scen")
    r = rows[round(2 * (len(rows) - 1) / 5)]
    return (int(r[0]), int(r[1])), (int(r[2]), int(r[3]))


def flags(start, goal, algo, iterations, seed, *extra):
    return ["--start", f"{start[0]},{start[1]}", "--goal", f"{goal[0]},{goal[1]}",
            "--algo", algo, "--iterations", str(iterations), "--seed", str(seed),
            "--radius", str(RADIUS), *extra]


def test_sampling_algorithms_are_the_clis_sampling_planners():
    assert planlab.sampling_algorithms() == [
        "rrt", "rrt-connect", "rrt-star", "informed-rrt-star", "prm", "prm-star", "bit-star"]
    assert not set(planlab.sampling_algorithms()) & set(planlab.algorithms())


@pytest.mark.parametrize("algo", ["rrt", "rrt-connect", "rrt-star", "informed-rrt-star",
                                  "prm", "prm-star", "bit-star"])
def test_every_sampling_planner_gives_the_clis_answer_for_the_same_seed(cli, algo):
    grid = planlab.load_map(ARENA2)
    start, goal = arena2_row()
    iterations = 6000
    want = cli.json("plan", ARENA2, *flags(start, goal, algo, iterations, 3))
    got = planlab.plan(grid, start, goal, algo=algo, iterations=iterations, seed=3,
                       radius=RADIUS)
    for key in ("algorithm", "cost", "length_m", "iterations", "first_solution_iteration",
                "nodes", "seed", "radius"):
        assert got[key] == want[key], key
    assert got["path"].dtype == np.float64 and got["path"].shape == (len(want["path"]), 2)
    assert got["path"].tolist() == want["path"]
    # From the start cell's centre to the goal cell's.
    assert tuple(got["path"][0]) == (start[0] + 0.5, start[1] + 0.5)
    assert tuple(got["path"][-1]) == (goal[0] + 0.5, goal[1] + 0.5)
    # A map file's path plans the same as its loaded grid.
    again = planlab.plan(str(ARENA2), start, goal, algo=algo, iterations=iterations, seed=3,
                         radius=RADIUS)
    assert again["path"].tolist() == want["path"]


def test_shortcut_gives_the_clis_shortcut_path(cli):
    grid = planlab.load_map(ARENA2)
    start, goal = arena2_row()
    want = cli.json("plan", ARENA2, *flags(start, goal, "rrt-connect", 20000, 5, "--shortcut"))
    got = planlab.plan(grid, start, goal, algo="rrt-connect", iterations=20000, seed=5,
                       radius=RADIUS, shortcut=True)
    assert got["path"].tolist() == want["path"]
    assert got["cost"] == want["cost"]
    assert got["cost_before_shortcut"] == want["cost_before_shortcut"]
    assert got["cost"] <= got["cost_before_shortcut"]


@pytest.mark.parametrize("algo", ["rrt-star", "informed-rrt-star", "prm-star", "bit-star"])
def test_the_solutions_list_only_falls_and_ends_at_the_returned_cost(algo):
    grid = planlab.load_map(ARENA2)
    start, goal = arena2_row()
    res = planlab.plan(grid, start, goal, algo=algo, iterations=20000, seed=2)
    sols = res["solutions"]
    assert len(sols) >= 2, sols  # it improved at least once
    iters = [i for i, _ in sols]
    costs = [c for _, c in sols]
    assert iters == sorted(set(iters))
    assert all(b < a for a, b in zip(costs, costs[1:])), costs
    assert res["first_solution_iteration"] == iters[0]
    assert iters[-1] <= res["iterations"] <= 20000
    assert costs[-1] == pytest.approx(res["cost"], rel=1e-9)
    path = res["path"]
    assert float(np.hypot(*np.diff(path, axis=0).T).sum()) == pytest.approx(res["cost"])
    # No path is shorter than the straight line.
    assert res["cost"] >= math.hypot(goal[0] - start[0], goal[1] - start[1]) - 1e-9


def test_the_same_seed_repeats_and_a_generous_time_limit_changes_nothing():
    grid = planlab.load_map(ARENA2)
    start, goal = arena2_row()
    # Seeds 6 and 8 find a path within 8000 iterations on this row.
    kw = dict(algo="rrt-star", iterations=8000, radius=RADIUS)
    a = planlab.plan(grid, start, goal, seed=6, **kw)
    b = planlab.plan(grid, start, goal, seed=6, **kw)
    # Stepped in chunks under a limit it never reaches: the same run.
    c = planlab.plan(grid, start, goal, seed=6, time_limit=1e6, **kw)
    d = planlab.plan(grid, start, goal, seed=8, **kw)
    for other in (b, c):
        assert other["path"].tolist() == a["path"].tolist()
        assert other["solutions"] == a["solutions"]
        assert (other["iterations"], other["nodes"]) == (a["iterations"], a["nodes"])
    assert d["path"].tolist() != a["path"].tolist()


def test_the_grids_kept_disc_space_follows_the_radius_and_unknown_flag():
    # The space is cached per grid for the last (radius, allow_unknown):
    # changing either must not reuse it.
    occ = np.zeros((12, 12), dtype=np.uint8)
    occ[0:9, 5] = 1
    occ[9, 5] = 2  # unknown: blocked unless allowed
    grid = planlab.Grid(occ)
    kw = dict(algo="rrt-connect", iterations=20000, seed=1)
    a = planlab.plan(grid, (1, 1), (10, 1), radius=0.3, **kw)
    wide = planlab.plan(grid, (1, 1), (10, 1), radius=0.45, **kw)
    assert wide["radius"] == 0.45 and a["radius"] == 0.3
    assert wide["path"].tolist() != a["path"].tolist()
    through = planlab.plan(grid, (1, 1), (10, 1), radius=0.3, allow_unknown=True, **kw)
    again = planlab.plan(grid, (1, 1), (10, 1), radius=0.3, **kw)
    assert again["path"].tolist() == a["path"].tolist()
    # Allowed, the unknown cell opens a second gap, row 9, nearer the ends.
    assert through["path"].tolist() != a["path"].tolist()
    assert max(y for _, y in a["path"]) > 10  # the only gap without it: rows 10-11


def test_a_short_time_limit_stops_before_the_iterations():
    grid = planlab.load_map(ARENA2)
    start, goal = arena2_row()
    # 2 000 000 RRT* iterations take minutes; a millisecond allows far fewer.
    try:
        res = planlab.plan(grid, start, goal, algo="rrt-star", iterations=2_000_000,
                           seed=1, time_limit=1e-3)
        assert res["iterations"] < 2_000_000
    except planlab.PlanError as e:
        assert "no path after" in str(e)


def test_radius_is_in_metres_like_the_cli():
    occ = np.zeros((20, 30), dtype=np.uint8)
    occ[5:15, 12] = 1
    grid = planlab.Grid(occ, resolution=0.5)
    res = planlab.plan(grid, (2, 10), (25, 10), algo="rrt-connect", radius=0.2, seed=1)
    assert res["radius"] == pytest.approx(0.4)
    assert res["length_m"] == pytest.approx(res["cost"] * 0.5)


def one_line(excinfo):
    msg = str(excinfo.value)
    assert msg and "\n" not in msg
    return msg


@pytest.mark.parametrize("kw, match", [
    (dict(radius=float("nan")), "radius"),
    (dict(radius=-1.0), "radius"),
    (dict(radius=float("inf")), "radius"),
    (dict(radius=30.0), "half the map"),
    (dict(iterations=0), "iterations 0"),
    (dict(iterations=-5), "iterations -5"),
    (dict(iterations=2_000_001), "iterations"),
    (dict(seed=-1), "seed -1"),
    (dict(range=float("nan")), "range"),
    (dict(range=0.0), "range"),
    (dict(time_limit=0.0), "time_limit"),
    (dict(time_limit=float("nan")), "time_limit"),
    (dict(heuristic="octile"), "heuristic applies to the grid planners"),
    (dict(inflate=0.5), "inflate applies to the grid planners"),
    (dict(start=(-1, 3)), "start"),
])
def test_bad_sampling_parameters_are_one_line_param_errors(kw, match):
    grid = planlab.load_map(ARENA)
    args = dict(start=(3, 3), goal=(40, 44), algo="rrt-star", iterations=100)
    args.update(kw)
    with pytest.raises(planlab.ParamError) as e:
        planlab.plan(grid, **args)
    assert match in one_line(e)


@pytest.mark.parametrize("kw", [dict(iterations=10), dict(seed=1), dict(radius=0.4),
                                dict(shortcut=True), dict(time_limit=1.0), dict(range=3.0)])
def test_sampling_parameters_with_a_grid_planner_are_refused(kw):
    grid = planlab.load_map(ARENA)
    with pytest.raises(planlab.ParamError) as e:
        planlab.plan(grid, (3, 3), (40, 44), algo="astar", **kw)
    assert "applies to the sampling planners" in one_line(e)


def test_an_endpoint_in_a_wall_or_off_the_map_and_no_path_are_plan_errors():
    grid = planlab.load_map(ARENA)
    occ = grid.occupancy
    wall = next((c, r) for r in range(grid.height) for c in range(grid.width) if occ[r, c])
    for start, goal in [(wall, (40, 44)), ((3, 3), wall), ((3, 3), (grid.width, 3))]:
        with pytest.raises(planlab.PlanError) as e:
            planlab.plan(grid, start, goal, algo="rrt-connect", iterations=100)
        assert "in collision" in one_line(e)
    walled = planlab.Grid(np.array([[0, 0, 1, 0, 0]] * 3, dtype=np.uint8))
    for algo in planlab.sampling_algorithms():
        with pytest.raises(planlab.PlanError) as e:
            planlab.plan(walled, (0, 0), (4, 2), algo=algo, iterations=500, radius=0.3)
        assert "no path after" in one_line(e)
