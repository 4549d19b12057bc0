"""planlab against OMPL for real, small: the benchmark's whole pipeline
(crates/planlab-py/bench/bench_ompl.py: both libraries on the same arena
queries and disc, its table) on two rows with short budgets. Needs the
`ompl` wheel (requirements-dev.txt pins it). What is checked is that both
sides plan the same problem, not how fast: every path either returns must
pass the exact disc check, start and end at the query's cell centres and
be no shorter than the straight line."""

from __future__ import annotations

import argparse
import importlib.util
import math

import pytest

from conftest import DATA, REPO

from ompl import util as ou

_spec = importlib.util.spec_from_file_location(
    "bench_ompl", REPO / "crates" / "planlab-py" / "bench" / "bench_ompl.py")
bench = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(bench)

ARENA = DATA / "movingai" / "dao" / "arena.map"


def test_planlab_and_ompl_plan_the_same_arena_queries_with_valid_paths():
    ou.setLogLevel(ou.LogLevel.LOG_ERROR)
    ou.RNG.setSeed(1)
    args = argparse.Namespace(
        per_map=2, seeds=1, radius=0.4, motion="exact", check_step=0.1, range="planlab",
        planners=["rrt-connect", "rrt-star", "prm-star"], budgets=[0.2], first_cap=10.0,
        libs=["planlab", "ompl"])
    runs, info = bench.run_map(ARENA, args, lambda msg: None)
    # Rows 0 and n − 1: the shortest query and the longest.
    assert info["rows"][0] == 0 and len(info["rows"]) == 2
    assert info["range"] == pytest.approx(math.hypot(49, 49) / 10)
    assert len(runs) == 2 * 3 * 2
    for lib in ("planlab", "ompl"):
        mine = [r for r in runs if r["lib"] == lib]
        assert {(r["row"], r["algo"]) for r in mine} == {
            (row, algo) for row in info["rows"] for algo in args.planners}
        # RRT-Connect takes milliseconds here; the 10 s cap is a hang guard.
        assert all(r["cost"] < math.inf for r in mine if r["algo"] == "rrt-connect"), lib
        for r in mine:
            if r["cost"] < math.inf:
                assert r["path_valid"], (lib, r["row"], r["algo"])
                (sc, sr), (gc, gr) = r["start"], r["goal"]
                assert r["cost"] >= math.hypot(gc - sc, gr - sr) - 1e-9, (lib, r)
    planlab_runs = [r for r in runs if r["lib"] == "planlab" and r["cost"] < math.inf]
    for r in planlab_runs:
        # planlab's own cost is the length of the path it returned.
        assert r["reported_cost"] == pytest.approx(r["cost"], rel=1e-9)
    table = bench.summarise(runs)
    assert {r["planner"] for r in table} == set(args.planners)
    assert "| arena | rrt-connect | first-solution wall s |" in bench.markdown_table(table)
