"""Bad input raises a PlanlabError subclass with the core's one-line
message; nothing crashes the interpreter."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

import planlab
from conftest import DATA, ROOM, SCENARIOS

ARENA = DATA / "movingai" / "dao" / "arena.map"


def test_the_hierarchy():
    for sub in (planlab.MapError, planlab.ScenarioError, planlab.PlanError, planlab.ParamError):
        assert issubclass(sub, planlab.PlanlabError) and sub is not planlab.PlanlabError
    assert issubclass(planlab.PlanlabError, Exception)


def one_line(e: pytest.ExceptionInfo) -> str:
    msg = str(e.value)
    assert msg and "\n" not in msg
    return msg


@pytest.mark.parametrize(
    "path,match",
    [
        ("/nonexistent/map.map", "cannot read"),
        ("/dev/zero", "unknown map format"),
        (str(DATA), "unknown map format"),
        (str(DATA / "movingai" / "dao"), "unknown map format"),
    ],
)
def test_missing_and_special_files(path, match):
    with pytest.raises(planlab.MapError, match=match) as e:
        planlab.load_map(path)
    one_line(e)


def test_special_files_with_a_known_extension(tmp_path):
    d = tmp_path / "folder.map"
    d.mkdir()
    with pytest.raises(planlab.MapError, match="not a regular file"):
        planlab.load_map(d)
    # A ROS yaml whose image is /dev/zero: refused, not read forever.
    y = tmp_path / "zero.yaml"
    y.write_text("image: /dev/zero\nresolution: 0.05\norigin: [0, 0, 0]\n"
                 "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n")
    with pytest.raises(planlab.MapError, match="not a regular file"):
        planlab.load_map(y)
    with pytest.raises(planlab.ScenarioError, match="not a regular file"):
        planlab.Scenario.from_file("/dev/zero")
    bad = tmp_path / "bad.map"
    bad.write_text("type octile\nheight 2\nwidth 2\nmap\n..\n")
    with pytest.raises(planlab.MapError) as e:
        planlab.load_map(bad)
    assert "bad.map" in one_line(e)


def test_bad_plan_parameters():
    grid = planlab.load_map(ARENA)
    free = (1, 4)
    goal = (3, 2)
    wall = (0, 0)
    cases = [
        (dict(start=wall, goal=goal), planlab.PlanError, "start (0, 0) is inside an obstacle"),
        (dict(start=free, goal=(99, 2)), planlab.PlanError, "off the 49×49 map"),
        (dict(start=(-1, 2), goal=goal), planlab.ParamError, "non-negative"),
        (dict(start=free, goal=goal, weight=math.nan), planlab.ParamError, "weight"),
        (dict(start=free, goal=goal, weight=0.5), planlab.ParamError, "weight"),
        (dict(start=free, goal=goal, inflate=math.nan), planlab.ParamError, "inflate NaN"),
        (dict(start=free, goal=goal, inflate=1e300), planlab.PlanError, "blocked after inflation"),
        (dict(start=free, goal=goal, algo="bogus"), planlab.ParamError, "unknown algorithm"),
        (dict(start=free, goal=goal, heuristic="nope"), planlab.ParamError, "heuristic"),
        (dict(start=free, goal=goal, diagonal="sometimes"), planlab.ParamError, "diagonal"),
        (dict(start=free, goal=goal, bottom_up=-1.0), planlab.ParamError, "Bottom-Up"),
        (dict(start=None, goal=goal), planlab.ParamError, "start (COLUMN, ROW) is required"),
    ]
    for kwargs, exc, match in cases:
        with pytest.raises(exc, match=re.escape(match)) as e:
            planlab.plan(grid, **kwargs)
        one_line(e)


def test_unreachable_goal():
    occ = np.zeros((3, 5), dtype=np.uint8)
    occ[:, 2] = 1
    with pytest.raises(planlab.PlanError, match="unreachable"):
        planlab.plan(planlab.Grid(occ), (0, 1), (4, 1))


def test_bad_scenarios_and_runs(tmp_path):
    s = planlab.Scenario.from_file(SCENARIOS / "dwa-demo.json")
    for kwargs, match in [
        (dict(set={"sim.dt": math.nan}), "sim.dt"),
        (dict(set={"sim.dt": 1e9}), "sim.dt"),
        (dict(set={"sim.max_time": 1e300}), "max_time"),
        (dict(planner="no-such-planner"), "no-such-planner"),
        (dict(set={"no_such_field": 1}), "no_such_field"),
    ]:
        with pytest.raises(planlab.ScenarioError, match=match) as e:
            s.run(**kwargs)
        one_line(e)
    doc = s.to_dict()
    doc["start"] = {"col": 0, "row": 0}  # in the outer wall
    with pytest.raises(planlab.ScenarioError, match="wall") as e:
        planlab.Scenario.from_dict(doc).run()
    one_line(e)
    with pytest.raises(planlab.ScenarioError, match="version"):
        planlab.Scenario.from_dict({"version": 99})
    p = tmp_path / "broken.json"
    p.write_text('{"version": 1,\n "map": ')
    with pytest.raises(planlab.ScenarioError, match="broken.json"):
        planlab.Scenario.from_file(p)
    with pytest.raises(planlab.ScenarioError, match="cannot read"):
        planlab.Scenario.from_file(tmp_path / "missing.json")
    # A map file the scenario names is read relative to it, and missing.
    doc = planlab.Scenario.from_file(ROOM).to_dict()
    doc["map"] = {"file": "nowhere.map"}
    with pytest.raises(planlab.ScenarioError, match="nowhere.map"):
        planlab.Scenario.from_dict(doc, str(tmp_path)).run()
    with pytest.raises(planlab.ParamError, match="not a JSON document"):
        planlab.Scenario.from_dict({"version": 1, "x": math.nan})


def test_bad_commands_and_episodes():
    s = planlab.Scenario.from_file(ROOM)
    ep = s.episode()
    for cmd, match in [((math.nan, 0.0), "command v = NaN"), ((0.1, math.inf), "command w"),
                       ((1.0,), "got 1 numbers")]:
        with pytest.raises(planlab.ParamError, match=match):
            ep.step(command=cmd)
    assert ep.steps == 0
    with pytest.raises(planlab.ParamError, match="lidar.beams"):
        s.episode(lidar={"beams": 0})
    with pytest.raises(planlab.ParamError, match="lidar.range"):
        s.episode(lidar={"range": -1.0})
    with pytest.raises(planlab.ScenarioError, match="only robot episodes step"):
        planlab.Scenario.from_file(SCENARIOS / "T-tab5-3.json").episode()


def test_bad_batches_and_reproductions():
    s = planlab.Scenario.from_file(ROOM)
    with pytest.raises(planlab.ParamError, match="unknown planner `nope`"):
        planlab.batch_episodes(s, [0], ["nope"])
    with pytest.raises(planlab.ParamError, match="listed twice"):
        planlab.batch(s, planners=["dwa", "dwa"], variants=1)
    with pytest.raises(planlab.ParamError, match="jitter"):
        planlab.batch(s, variants=2, jitter=math.nan)
    for n in (0, 10_001):
        with pytest.raises(planlab.ParamError, match="variants"):
            planlab.batch(s, variants=n)
    with pytest.raises(planlab.ParamError, match="variant -1"):
        planlab.batch_episodes(s, [-1])
    with pytest.raises(planlab.ParamError, match="unknown experiment `X`"):
        planlab.reproduce("X")
    with pytest.raises(planlab.ParamError, match="variants 0"):
        planlab.reproduce("T-fig3-2", variants=0)
    with pytest.raises(planlab.ParamError, match="backend"):
        planlab.sweep(s, backend="spark")
