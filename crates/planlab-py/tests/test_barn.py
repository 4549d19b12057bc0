"""BARN from Python: the runs of `planlab barn` (same seeds, same trace
hashes) on local threads and on Ray, the figures of `planlab barn --json`,
and `barn:N` scenarios that replay a run."""

from __future__ import annotations

import pytest

import planlab

WORLDS = [1, 2]
PLANNERS = ["move-base-dwa", "dwb"]


def cli_rows(cli, tmp_path):
    rows = cli.csv("barn", "--worlds", ",".join(map(str, WORLDS)), "--planners",
                   ",".join(PLANNERS), out=tmp_path / "barn.csv")
    return {(int(r["world"]), r["planner"], int(r["run"])): (r["trace_hash"], r["outcome"])
            for r in rows}


def py_rows(runs):
    return {(r["world"], r["planner"], r["run"]): (r["trace_hash"], r["outcome"]) for r in runs}


def test_local_barn_equals_planlab_barn(cli, tmp_path):
    want = cli_rows(cli, tmp_path)
    res = planlab.barn(worlds=WORLDS, planners=PLANNERS, backend="local", workers=2)
    assert py_rows(res.runs) == want
    lines = cli.json_lines("barn", "--worlds", ",".join(map(str, WORLDS)), "--planners",
                           ",".join(PLANNERS))[:-1]
    for line in lines:
        got = [s for s in res.summaries
               if s["planner"] == line["planner"] and s["class"] == line["class"]]
        assert len(got) == 1, line
        assert got[0]["success"] == line["success"]
        assert got[0]["score"] == line["score"]


def test_a_barn_scenario_replays_a_run():
    res = planlab.barn(worlds=[1], planners=PLANNERS)
    by = {r["planner"]: r for r in res.runs}
    # "barn:1" alone is the baseline's scenario (planlab run barn:1).
    base = by["move-base-dwa"]
    done = planlab.as_scenario("barn:1").run(seed=base["seed"])
    assert done["trace_hash"] == base["trace_hash"]
    assert done["metrics"]["outcome"] == base["outcome"]
    # Another planner's run: its scenario carries its BARN settings.
    dwb = by["dwb"]
    again = planlab.Scenario.barn("barn:1", planner="dwb", seed=dwb["seed"]).run()
    assert again["trace_hash"] == dwb["trace_hash"]


def test_barn_runs_on_ray_equal_local(ray_two_workers):
    local = planlab.barn(worlds=[1], planners=PLANNERS, runs=2)
    remote = planlab.barn(worlds=[1], planners=PLANNERS, runs=2, backend="ray", jobs_per_task=1)
    assert remote.backend == "ray" and remote.tasks == 4
    assert py_rows(remote.runs) == py_rows(local.runs)


def test_bad_barn_requests_raise_typed_errors():
    with pytest.raises(planlab.ParamError, match="world 6"):
        planlab.barn(worlds=[6])
    with pytest.raises(planlab.ParamError, match="runs 0"):
        planlab.barn(worlds=[1], runs=0)
    with pytest.raises(planlab.ParamError, match="noise"):
        planlab.barn(worlds=[1], noise=float("nan"))
    with pytest.raises(planlab.ParamError, match="pursuit"):
        planlab.barn_runs([(1, "pursuit", 0)])
    with pytest.raises(planlab.ScenarioError, match="held-back"):
        planlab.Scenario.barn("barn:6")
    assert "move-base-dwa" in planlab.barn_planners()
