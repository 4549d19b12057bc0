"""Scenario runs and stepped episodes: `planlab run`'s trace hash and
metrics, from Python."""

from __future__ import annotations

import csv
import json

import numpy as np
import pytest

import planlab
from conftest import ROOM, SCENARIOS

DEMO = SCENARIOS / "dwa-demo.json"


def cli_run(cli, path, *flags):
    out = cli.json("run", path, *flags)
    head = {k: out.pop(k) for k in ("scenario", "planner", "seed", "steps", "trace_hash")}
    return head, out  # the rest is the metrics, flattened


@pytest.mark.parametrize(
    "kwargs,flags",
    [
        ({}, []),
        ({"planner": "improved-dwa", "seed": 3}, ["--planner", "improved-dwa", "--seed", "3"]),
        ({"set": {"sim.dt": 0.05, "local_planner.name": "dwa"}},
         ["--set", "sim.dt=0.05", "--set", "local_planner.name=dwa"]),
    ],
)
def test_run_equals_planlab_run(cli, kwargs, flags):
    head, metrics = cli_run(cli, DEMO, *flags)
    got = planlab.Scenario.from_file(DEMO).run(**kwargs)
    assert got["trace_hash"] == head["trace_hash"]
    assert (got["planner"], got["seed"], got["steps"]) == (
        head["planner"], head["seed"], head["steps"])
    assert got["metrics"] == metrics


def test_trace_columns_equal_the_cli_trace_csv(cli, tmp_path):
    out = tmp_path / "trace.csv"
    cli.run("run", DEMO, "--trace", out)
    rows = list(csv.DictReader(out.open()))
    trace = planlab.Scenario.from_file(DEMO).run()["trace"]
    for name in ("t", "x", "y", "theta", "v", "w", "cmd_v", "cmd_w", "clearance",
                 "goal_x", "goal_y", "accel_z"):
        col = trace[name]
        assert col.dtype == np.float64 and col.shape == (len(rows),)
        assert col.tolist() == [float(r[name]) for r in rows], name
    assert trace["mode"] == [r["mode"] for r in rows]
    assert trace["goal_kind"] == [r["goal_kind"] for r in rows]


def test_apf_and_arm_runs_equal_planlab_run(cli):
    for file in ("T-fig4-6.json", "T-tab5-3.json"):
        want = cli.json("run", SCENARIOS / file)
        got = planlab.Scenario.from_file(SCENARIOS / file).run()
        assert got["trace_hash"] == want["trace_hash"], file
        assert got["trace"]["path"].shape[1] == 3
        assert got["metrics"]["path_points"] == want["path_points"] == len(got["trace"]["path"])


def test_stepping_with_the_planner_gives_the_run(cli):
    head, metrics = cli_run(cli, DEMO, "--seed", "9")
    ep = planlab.Scenario.from_file(DEMO).episode(seed=9)
    outcomes = []
    while not ep.done:
        outcomes.append(ep.step())
    assert outcomes[-1] == metrics["outcome"] and set(outcomes[:-1]) == {"running"}
    assert ep.steps == head["steps"] == len(outcomes)
    assert ep.trace_hash() == head["trace_hash"]
    assert ep.metrics() == metrics
    # Observing (the LiDAR scan) does not disturb the episode.
    ep2 = planlab.Scenario.from_file(DEMO).episode(seed=9)
    while not ep2.done:
        ep2.observe()
        ep2.step()
    assert ep2.trace_hash() == head["trace_hash"]


def test_dicts_round_trip():
    s = planlab.Scenario.from_file(DEMO)
    d = s.to_dict()
    assert d == json.loads(DEMO.read_text())
    again = planlab.Scenario.from_dict(d)
    assert again.run()["trace_hash"] == s.run()["trace_hash"]
    d["seed"] = 8
    assert planlab.Scenario.from_dict(d).run()["trace_hash"] == s.run(seed=8)["trace_hash"]
    assert (s.kind, s.name, s.seed) == ("robot", "DWA demo room", 7)
    inl = planlab.Scenario.from_file(ROOM).inlined()
    assert inl.run()["trace_hash"] == planlab.Scenario.from_file(ROOM).run()["trace_hash"]


def test_batch_variant_matches_run_variant(cli):
    want = cli.json("run", DEMO, "--variant", "4", "--seed", "2", "--jitter", "0.4")
    v = planlab.Scenario.from_file(DEMO).variant(4, seed=2, jitter=0.4)
    assert v.run()["trace_hash"] == want["trace_hash"]


HYBRID = {"local_planner.name": "dwa", "global_planner.algorithm": "hybrid-astar",
          "global_planner.turning_radius_m": 1.0}


def test_a_hybrid_astar_global_planner_runs_as_planlab_run_and_reaches_the_goal(cli):
    path = SCENARIOS / "T-fig3-2.json"
    flags = [f for k, v in HYBRID.items() for f in ("--set", f"{k}={v}")]
    native = cli.json("run", path, *flags)
    got = planlab.Scenario.from_file(path).run(set=HYBRID)
    assert got["trace_hash"] == native["trace_hash"]
    assert got["metrics"]["outcome"] == "reached"
    assert got["metrics"].get("collision") is None
    assert got["global_path"] == native["global_path"]
    assert got["global_path"]["length_m"] > 9.0
    # Without the section there is no car path.
    assert "global_path" not in planlab.Scenario.from_file(path).run(planner="dwa")


@pytest.mark.parametrize("radius,needle", [(None, "turning_radius_m"), (-1.0, "turning_radius_m = -1"),
                                           (float("nan"), "turning_radius_m")])
def test_a_missing_or_bad_turning_radius_is_a_scenario_error(radius, needle):
    edits = {k: v for k, v in HYBRID.items() if radius is not None or "turning" not in k}
    if radius is not None:
        edits["global_planner.turning_radius_m"] = radius
    with pytest.raises(planlab.ScenarioError, match=needle):
        planlab.Scenario.from_file(SCENARIOS / "T-fig3-2.json").run(set=edits)
