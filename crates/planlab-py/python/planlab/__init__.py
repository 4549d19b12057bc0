"""planlab in Python: grid planning, robot episodes and sweeps on the
planlab core (Rust, through pyo3).

The numbers are those of the ``planlab`` CLI: ``plan`` is ``planlab plan``
(grid searches and, with ``algo="rrt-star"`` etc., the sampling planners),
``Scenario.run`` is ``planlab run`` (same trace hash), ``batch`` is
``planlab batch``, ``reproduce`` is ``planlab reproduce --json``. Every
error is a :class:`PlanlabError` carrying the core's one-line message.
"""

from __future__ import annotations

import os
from typing import Iterable, Optional, Union

from ._planlab import (  # noqa: F401  (re-exported API)
    Episode,
    Grid,
    MapError,
    ParamError,
    PlanError,
    PlanlabError,
    Scenario,
    ScenarioError,
    __version__,
    algorithms,
    barn_planners,
    barn_runs,
    barn_stats,
    barn_worlds_info,
    batch_episodes,
    load_map,
    load_scen,
    max_variants,
    dubins,
    plan,
    plan_car,
    reeds_shepp,
    reproduce,
    reproduce_ids,
    sampling_algorithms,
    summarise,
)
from ._planlab import planner_catalogue as _planner_catalogue
from .sweep import SweepResult, sweep  # noqa: F401
from .barn import BarnResult, barn  # noqa: F401

ScenarioLike = Union[str, "os.PathLike[str]", Scenario, dict]


def as_scenario(scenario: ScenarioLike) -> Scenario:
    """A :class:`Scenario` from a path, a dict (the JSON document) or a
    scenario (returned as is)."""
    if isinstance(scenario, Scenario):
        return scenario
    if isinstance(scenario, dict):
        return Scenario.from_dict(scenario)
    if isinstance(scenario, str) and scenario.startswith("barn:"):
        return Scenario.barn(scenario)
    if isinstance(scenario, (str, os.PathLike)):
        return Scenario.from_file(os.fspath(scenario))
    raise ParamError(
        f"scenario: expected a path, a dict or a planlab.Scenario, got {type(scenario).__name__}"
    )


def planners() -> list:
    """The local planners' names (``planlab planners``); the full catalogue
    with every parameter is :func:`planner_catalogue`."""
    return [p["name"] for p in _planner_catalogue()]


def planner_catalogue() -> list:
    """The local planner catalogue (``planlab planners --json``): each
    planner's fields with ``name`` (the config name), ``label`` (the same in
    plain words, e.g. "heading weight α"), ``unit``, ``default`` and ``doc``."""
    return _planner_catalogue()


def batch(
    scenario: ScenarioLike,
    planners: Iterable[str] = (),
    variants: int = 20,
    seed: int = 0,
    jitter: Optional[float] = None,
) -> dict:
    """``planlab batch``: ``variants`` seeded variants of a robot or arm
    scenario run by each planner (default: the scenario's own; an arm's
    planners are ``apf`` and ``rrt-connect``). ``jitter`` (m) defaults to
    the kind's: 0.3 for a robot (start, goal and movers), 0.02 for an arm
    (the tool's start and goal; the hand's speed varies by ±20 %).

    Returns ``{"runs": [...], "summaries": [...]}``: one dict per episode
    (``variant``, ``planner``, ``seed``, ``steps``, ``trace_hash``,
    ``metrics``; the rows of ``planlab batch --csv``) and one summary per
    planner (the lines of ``planlab batch --json``). Runs in this thread;
    :func:`sweep` spreads the same episodes over threads or Ray.
    """
    if not isinstance(variants, int) or not 1 <= variants <= max_variants():
        raise ParamError(f"variants {variants}: must be from 1 to {max_variants()}")
    s = as_scenario(scenario)
    names = list(planners)
    runs = batch_episodes(s, list(range(variants)), names, seed, jitter)
    order = list(dict.fromkeys(r["planner"] for r in runs))
    summaries = [
        summarise(p, [r["metrics"] for r in runs if r["planner"] == p]) for p in order
    ]
    return {"runs": runs, "summaries": summaries}


__all__ = [
    "BarnResult",
    "barn",
    "barn_planners",
    "barn_runs",
    "barn_stats",
    "barn_worlds_info",
    "Episode",
    "Grid",
    "MapError",
    "ParamError",
    "PlanError",
    "PlanlabError",
    "Scenario",
    "ScenarioError",
    "SweepResult",
    "algorithms",
    "as_scenario",
    "batch",
    "batch_episodes",
    "load_map",
    "load_scen",
    "max_variants",
    "dubins",
    "plan",
    "plan_car",
    "planner_catalogue",
    "reeds_shepp",
    "planners",
    "reproduce",
    "reproduce_ids",
    "sampling_algorithms",
    "summarise",
    "sweep",
]
