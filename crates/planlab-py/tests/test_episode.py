"""Episodes driven by a Python controller: observation, commands, the
core's metrics."""

from __future__ import annotations

import math

import numpy as np
import pytest

import planlab
from conftest import ROOM, SCENARIOS


def go_to_goal(obs, v_max):
    """Turn towards the goal; drive when roughly facing it."""
    x, y, th = obs["pose"]
    gx, gy = obs["goal"]
    bearing = math.atan2(gy - y, gx - x) - th
    bearing = math.atan2(math.sin(bearing), math.cos(bearing))
    v = v_max if abs(bearing) < 0.4 else 0.0
    return v, 2.0 * bearing


def test_a_user_controller_reaches_the_goal_and_is_measured_by_the_core():
    s = planlab.Scenario.from_file(ROOM)
    # Without the mover: the straight controller does not dodge.
    ep = s.episode(set={"movers": []})
    lim = ep.limits
    while not ep.done:
        ep.step(command=go_to_goal(ep.observe(), lim["v_max"]))
    assert ep.outcome == "reached"
    m = ep.metrics()
    tr = ep.trace()
    assert m["outcome"] == "reached"
    assert m["time_s"] == pytest.approx(ep.steps * lim["dt"])
    # The core's path length is the polyline of the trace.
    seg = np.hypot(np.diff(tr["x"]), np.diff(tr["y"]))
    assert m["path_length_m"] == pytest.approx(seg.sum(), rel=1e-9)
    assert m["min_clearance_m"] == pytest.approx(tr["clearance"].min())
    assert set(tr["mode"][1:]) == {"user"}
    # The commands were clamped to the limits: never above v_max, and the
    # speed grows by at most acc_v·dt a step.
    assert tr["v"].max() <= lim["v_max"] + 1e-12
    assert np.diff(tr["v"]).max() <= lim["acc_v"] * lim["dt"] + 1e-12
    # The goal ends within the tolerance.
    gx, gy = ep.observe()["goal"]
    assert math.hypot(tr["x"][-1] - gx, tr["y"][-1] - gy) <= lim["goal_tolerance"]


def test_the_built_in_planner_and_a_controller_are_compared_on_one_scale():
    s = planlab.Scenario.from_file(ROOM)
    planner = s.run(planner="improved-dwa", set={"movers": []})["metrics"]
    ep = s.episode(set={"movers": []})
    while not ep.done:
        ep.step(command=go_to_goal(ep.observe(), ep.limits["v_max"]))
    mine = ep.metrics()
    assert planner.keys() == mine.keys()
    assert planner["outcome"] == mine["outcome"] == "reached"


def test_observation_scan_and_movers():
    s = planlab.Scenario.from_file(ROOM)
    lidar = {"beams": 4, "range": 8.0}
    o = s.episode(set={"movers": []}, lidar=lidar).observe()
    x, y, th = o["pose"]
    assert th == pytest.approx(0.0)
    # Free cells span 0.1 … 3.9 m in x and 0.1 … 2.9 m in y.
    walls = [3.9 - x, 2.9 - y, x - 0.1, y - 0.1]
    assert o["scan"] == pytest.approx(walls, abs=1e-9)
    assert o["scan_angles"] == pytest.approx([0, math.pi / 2, math.pi, 3 * math.pi / 2])
    assert o["movers"].shape == (0, 6)
    # With the room's mover (within the 3 m sensing range): id, x, y, vx,
    # vy, r; the beam ahead stops at its disc.
    o = s.episode(lidar=lidar).observe()
    mv = o["movers"]
    assert mv.shape == (1, 6) and mv[0, 0] == 1 and mv[0, 5] == pytest.approx(0.2)
    assert abs(mv[0, 4]) == pytest.approx(0.3)
    _, cx, cy, _, _, r = mv[0]
    assert o["scan"][0] == pytest.approx(cx - x - math.sqrt(r * r - (cy - y) ** 2), abs=1e-9)
    assert o["scan"][1:] == pytest.approx(walls[1:], abs=1e-9)
    assert o["velocity"].tolist() == [0.0, 0.0, 0.0]


def test_steps_after_the_end_change_nothing():
    ep = planlab.Scenario.from_file(SCENARIOS / "dwa-demo.json").episode()
    assert ep.run() == "reached"
    n, h = ep.steps, ep.trace_hash()
    assert ep.step(command=(1.0, 0.0)) == "reached"
    assert (ep.steps, ep.trace_hash()) == (n, h)


def test_an_episode_may_be_used_from_another_thread():
    from concurrent.futures import ThreadPoolExecutor

    s = planlab.Scenario.from_file(SCENARIOS / "dwa-demo.json")
    want = s.run()["trace_hash"]
    ep = s.episode()
    ep.step()
    with ThreadPoolExecutor(max_workers=1) as pool:
        assert pool.submit(ep.run).result() == "reached"
    assert ep.trace_hash() == want
    # Runs of several threads at once give each its own episode's hash.
    with ThreadPoolExecutor(max_workers=2) as pool:
        hashes = list(pool.map(lambda p: s.run(planner=p)["trace_hash"],
                               ["dwa", "improved-dwa", "dwa"]))
    assert hashes[0] == hashes[2] == want and hashes[1] != want
