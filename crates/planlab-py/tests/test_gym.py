"""The gymnasium environment: check_env, seeding, reward terms, endings."""

from __future__ import annotations

import math

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import planlab
import planlab.gym as pgym
from conftest import ROOM, SCENARIOS


# The action is (v, ω) in the robot's own units and limits, by design; the
# checker's advice to normalise it to [-1, 1] is not a failure.
@pytest.mark.filterwarnings("ignore:.*symmetric and normalized space:UserWarning")
def test_check_env_passes_on_the_default_and_a_preset():
    check_env(pgym.PlanlabEnv(), skip_render_check=True)
    check_env(pgym.PlanlabEnv(SCENARIOS / "dwa-crowd.json", beams=16, jitter=0.3),
              skip_render_check=True)


def test_registered_id_and_spaces():
    env = gym.make("planlab/Nav-v0", beams=12)
    obs, info = env.reset(seed=1)
    assert obs.shape == (12 + 4,) and obs.dtype == np.float32
    assert env.observation_space.contains(obs)
    lim = env.unwrapped.limits
    assert env.action_space.low.tolist() == pytest.approx([lim["v_min"], -lim["w_max"]])
    assert env.action_space.high.tolist() == pytest.approx([lim["v_max"], lim["w_max"]])
    env.close()


def test_reset_is_seeded():
    env = pgym.PlanlabEnv(ROOM, jitter=0.3)
    a, _ = env.reset(seed=5)
    b, _ = env.reset(seed=5)
    c, _ = env.reset(seed=6)
    assert np.array_equal(a, b) and not np.array_equal(a, c)
    act = np.array([0.5, 0.2], dtype=np.float32)
    env.reset(seed=5)
    r1 = [env.step(act)[:2] for _ in range(5)]
    env.reset(seed=5)
    r2 = [env.step(act)[:2] for _ in range(5)]
    assert all(np.array_equal(x[0], y[0]) and x[1] == y[1] for x, y in zip(r1, r2))


def goal_frame(obs, beams):
    return obs[beams], obs[beams + 1]


def test_reward_terms_and_the_goal_in_the_robot_frame():
    env = pgym.PlanlabEnv(ROOM, beams=8, time_weight=0.1, progress_weight=1.0)
    obs, _ = env.reset(seed=0)
    s = planlab.Scenario.from_file(ROOM).episode().observe()
    x, y, th = s["pose"]
    gx, gy = s["goal"]
    # Robot faces +x: the goal's frame coordinates are the world offsets.
    assert goal_frame(obs, 8) == pytest.approx((gx - x, gy - y), abs=1e-5)
    d0 = math.hypot(gx - x, gy - y)
    # Standing still: no progress, only the time term.
    _, r, term, trunc, info = env.step(np.zeros(2, dtype=np.float32))
    assert r == pytest.approx(-0.1 * 0.1) and not term and not trunc
    # Driving ahead (towards +x, the goal is ahead-left): progress counts.
    obs, r, *_ = env.step(np.array([0.8, 0.0], dtype=np.float32))
    d1 = math.hypot(*goal_frame(obs, 8))
    assert r == pytest.approx((d0 - d1) - 0.01, abs=1e-5) and d1 < d0


def test_collision_terminates_with_the_penalty():
    env = pgym.PlanlabEnv(ROOM, beams=8, collision_penalty=7.0)
    env.reset(seed=0)
    # Turn to face the wall below (−y) and drive into it.
    for _ in range(200):
        obs, r, term, trunc, info = env.step(np.array([0.8, -1.5], dtype=np.float32))
        if term or trunc:
            break
    assert info["outcome"] == "collision" and term and not trunc
    assert r < -6.0
    assert env.episode_metrics()["outcome"] == "collision"


def room(**sim):
    doc = planlab.Scenario.from_file(ROOM).to_dict()
    doc["movers"] = []
    doc["sim"].update(sim)
    return doc


def test_a_controller_reaches_the_goal_with_the_bonus():
    env = pgym.PlanlabEnv(room(), beams=8, reached_bonus=10.0, time_weight=0.0)
    obs, _ = env.reset(seed=0)
    d0 = math.hypot(*goal_frame(obs, 8))
    total = 0.0
    for _ in range(3000):
        gx, gy = goal_frame(obs, 8)
        bearing = math.atan2(gy, gx)
        act = np.array([0.8 if abs(bearing) < 0.3 else 0.0, 2.0 * bearing], dtype=np.float32)
        obs, r, term, trunc, info = env.step(np.clip(act, env.action_space.low,
                                                     env.action_space.high))
        total += r
        if term or trunc:
            break
    assert info["outcome"] == "reached" and term and not trunc
    # Progress telescopes to the distance covered, plus the bonus.
    d1 = math.hypot(*goal_frame(obs, 8))
    assert total == pytest.approx(d0 - d1 + 10.0, abs=1e-4)
    assert env.episode_metrics()["outcome"] == "reached"


def test_truncated_on_timeout():
    env = pgym.PlanlabEnv(room(max_time=0.5), beams=8)
    env.reset(seed=0)
    out = [env.step(np.zeros(2, dtype=np.float32)) for _ in range(5)]
    assert out[-1][4]["outcome"] == "timeout" and out[-1][3] and not out[-1][2]
    assert [o[4]["outcome"] for o in out[:4]] == ["running"] * 4


def test_bad_settings_raise():
    with pytest.raises(planlab.ParamError, match="time_weight"):
        pgym.PlanlabEnv(time_weight=math.nan)
    with pytest.raises(planlab.ScenarioError, match="arm"):
        pgym.PlanlabEnv(SCENARIOS / "T-tab5-3.json")
    env = pgym.PlanlabEnv()
    env.reset(seed=0)
    with pytest.raises(planlab.ParamError, match="action"):
        env.step(np.array([np.nan, 0.0]))
