"""A gymnasium environment over any planlab robot scenario.

``PlanlabEnv(scenario)`` drives the scenario's robot with the agent's
(v, ω) commands through :meth:`planlab.Episode.step`, so the world, the
limits, collisions and the outcome are the core's. Registered as
``planlab/Nav-v0`` (a small room with one crossing mover by default;
``gymnasium.make("planlab/Nav-v0", scenario="my.json")`` for another).

Observation (float32 vector): the LiDAR scan (``beams`` ranges, metres,
"no return" as the range limit), the goal in the robot frame (x ahead,
y left, metres), the velocity (v, ω).

Action (float32): (v, ω) inside the robot's limits (``v_min … v_max``
m/s, ``−w_max … w_max`` rad/s); the core also clamps to the acceleration
limits, as it does a planner's command.

Reward per step::

    r = progress_weight · (d_before − d_after)     # metres gained on the goal
        − time_weight · dt                         # time spent
        + reached_bonus   if the goal was reached
        − collision_penalty if the robot collided

``terminated`` when the goal is reached or the robot collides;
``truncated`` on the scenario's timeout (``sim.max_time``) or when it is
stuck (no progress for ``sim.stuck_time``). ``reset(seed=…)`` is
deterministic: the episode seed comes from the seed, and with
``jitter > 0`` the start, goal and movers are those of a ``planlab batch``
variant drawn from the seed.
"""

from __future__ import annotations

import math
import os
from typing import Any, Optional

import numpy as np

try:
    import gymnasium as gym
    from gymnasium import spaces
except ImportError as e:  # pragma: no cover - depends on the install
    raise ImportError("planlab.gym needs gymnasium: pip install gymnasium") from e

import planlab

DEFAULT_SCENARIO = os.path.join(os.path.dirname(__file__), "data", "room.json")


class PlanlabEnv(gym.Env):
    """See the module docstring for observation, action and reward."""

    metadata = {"render_modes": []}

    def __init__(
        self,
        scenario: Any = DEFAULT_SCENARIO,
        beams: int = 36,
        lidar_range: Optional[float] = None,
        jitter: float = 0.0,
        progress_weight: float = 1.0,
        time_weight: float = 0.1,
        reached_bonus: float = 10.0,
        collision_penalty: float = 10.0,
        render_mode: Optional[str] = None,
    ) -> None:
        super().__init__()
        if render_mode is not None:
            raise planlab.ParamError(f"render_mode {render_mode!r}: PlanlabEnv draws nothing")
        self.render_mode = None
        for name, v in [("progress_weight", progress_weight), ("time_weight", time_weight),
                        ("reached_bonus", reached_bonus), ("collision_penalty", collision_penalty),
                        ("jitter", jitter)]:
            if not (isinstance(v, (int, float)) and math.isfinite(v)):
                raise planlab.ParamError(f"{name} {v}: must be a finite number")
        self.base = planlab.as_scenario(scenario)
        if self.base.kind != "robot":
            raise planlab.ScenarioError(f"{self.base.kind} scenarios have no robot to drive")
        self.jitter = float(jitter)
        self.weights = (float(progress_weight), float(time_weight), float(reached_bonus),
                        float(collision_penalty))
        lidar = {"beams": int(beams)}
        if lidar_range is not None:
            lidar["range"] = float(lidar_range)
        self._lidar = lidar
        # Built once to read the limits and check the lidar settings.
        self._ep = self.base.episode(lidar=lidar)
        lim = self._ep.limits
        self.limits = lim
        self.range = lim["lidar_range"]
        self.beams = int(lim["lidar_beams"])
        reach = self._reach()
        low = np.concatenate([
            np.zeros(self.beams),
            [-reach, -reach, lim["v_min"] - 1e-6, -lim["w_max"] - 1e-6],
        ]).astype(np.float32)
        high = np.concatenate([
            np.full(self.beams, self.range),
            [reach, reach, lim["v_max"] + 1e-6, lim["w_max"] + 1e-6],
        ]).astype(np.float32)
        self.observation_space = spaces.Box(low, high, dtype=np.float32)
        self.action_space = spaces.Box(
            np.array([lim["v_min"], -lim["w_max"]], dtype=np.float32),
            np.array([lim["v_max"], lim["w_max"]], dtype=np.float32),
            dtype=np.float32,
        )
        self._dist = 0.0

    def _reach(self) -> float:
        """A bound on the goal's distance: the map's diagonal."""
        x0, y0, x1, y1 = self._ep.bounds
        return float(math.hypot(x1 - x0, y1 - y0))

    def _obs(self) -> np.ndarray:
        o = self._ep.observe()
        scan = np.where(np.isfinite(o["scan"]), o["scan"], self.range)
        x, y, th = o["pose"]
        dx, dy = o["goal"][0] - x, o["goal"][1] - y
        c, s = math.cos(th), math.sin(th)
        goal = [c * dx + s * dy, -s * dx + c * dy]
        v = o["velocity"]
        self._dist = math.hypot(dx, dy)
        out = np.concatenate([scan, goal, [v[0], v[2]]]).astype(np.float32)
        return np.clip(out, self.observation_space.low, self.observation_space.high)

    def reset(self, *, seed: Optional[int] = None, options: Optional[dict] = None):
        super().reset(seed=seed)
        episode_seed = int(self.np_random.integers(0, 2**63 - 1))
        if self.jitter > 0:
            k = int(self.np_random.integers(1, planlab.max_variants()))
            scen = self.base.variant(k, episode_seed, self.jitter)
        else:
            scen = self.base
        self._ep = scen.episode(seed=episode_seed, lidar=self._lidar)
        return self._obs(), {"outcome": self._ep.outcome}

    def step(self, action):
        a = np.asarray(action, dtype=np.float64).reshape(-1)
        if a.shape != (2,) or not np.all(np.isfinite(a)):
            raise planlab.ParamError(f"action {action!r}: expected two finite numbers (v, omega)")
        a = np.clip(a, self.action_space.low, self.action_space.high)
        before = self._dist
        outcome = self._ep.step(command=(float(a[0]), float(a[1])))
        obs = self._obs()
        kp, kt, bonus, penalty = self.weights
        reward = kp * (before - self._dist) - kt * self.limits["dt"]
        if outcome == "reached":
            reward += bonus
        elif outcome == "collision":
            reward -= penalty
        terminated = outcome in ("reached", "collision")
        truncated = outcome in ("timeout", "stuck")
        return obs, float(reward), terminated, truncated, {"outcome": outcome}

    def episode_metrics(self) -> dict:
        """The core's metrics of the current episode (as ``planlab run``)."""
        return self._ep.metrics()


def register() -> None:
    """Registers ``planlab/Nav-v0`` (idempotent)."""
    if "planlab/Nav-v0" not in gym.registry:
        gym.register(id="planlab/Nav-v0", entry_point="planlab.gym:PlanlabEnv")


register()
