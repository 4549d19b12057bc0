"""Car paths: Dubins / Reeds-Shepp lengths and Hybrid A* (the CLI's numbers)."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

import planlab

TURTLEBOT = Path(__file__).resolve().parents[3] / "assets" / "maps" / "turtlebot3.yaml"


def test_curves_match_hand_computed_lengths():
    d = planlab.dubins((0.0, 0.0, 0.0), (0.0, 4.0, math.pi), 1.0)
    assert d["word"] == "LSL"
    assert d["length"] == pytest.approx(math.pi + 2.0, abs=1e-9)
    rs = planlab.reeds_shepp((0.0, 0.0, 0.0), (-0.5, 0.0, 0.0), 1.0)
    assert rs["word"] == "S-" and rs["length"] == pytest.approx(0.5)
    with pytest.raises(planlab.ParamError, match="turning radius"):
        planlab.dubins((0.0, 0.0, 0.0), (1.0, 1.0, 0.0), float("nan"))


def test_plan_car_reaches_the_exact_goal_and_refuses_a_goal_off_the_map():
    g = planlab.load_map(str(TURTLEBOT))
    r = planlab.plan_car(g, (-2.0, -0.5, 0.0), (2.0, 0.5, math.pi / 2), turning_radius=0.3, radius=0.1)
    assert r["analytic"] and r["poses"].shape[1] == 3
    assert r["poses"][-1][0] == pytest.approx(2.0) and r["poses"][-1][2] == pytest.approx(math.pi / 2)
    with pytest.raises(planlab.PlanError, match="off the map"):
        planlab.plan_car(g, (-2.0, -0.5, 0.0), (50.0, 0.5, 0.0), turning_radius=0.3)


def test_plan_car_with_a_rectangle_is_the_cli_s_footprint_path(cli):
    g = planlab.load_map(str(TURTLEBOT))
    r = planlab.plan_car(g, (-2.0, -0.5, 0.0), (2.0, 0.5, math.pi / 2), turning_radius=0.3,
                         footprint=(0.3, 0.2))
    native = cli.json("plan", TURTLEBOT, "--algo", "hybrid-astar", "--start", "-2,-0.5,0",
                      "--goal", "2,0.5,90", "--turning-radius", "0.3", "--footprint", "0.3x0.2")
    assert r["length_m"] == native["length_m"]
    assert r["analytic"]
    with pytest.raises(planlab.ParamError, match="rectangle"):
        planlab.plan_car(g, (-2.0, -0.5, 0.0), (2.0, 0.5, 0.0), turning_radius=0.3, footprint=(0.3, -1.0))
    with pytest.raises(planlab.ParamError, match="give one"):
        planlab.plan_car(g, (-2.0, -0.5, 0.0), (2.0, 0.5, 0.0), turning_radius=0.3, radius=0.1,
                         footprint=(0.3, 0.2))
