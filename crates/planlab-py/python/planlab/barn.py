"""BARN: the planners on the BARN worlds (Perille et al. 2020; the BARN
Challenge), scored as the challenge scores, spread over local threads or
a Ray cluster — the episodes of ``planlab barn``, with the same seeds, so
every run's trace hash equals the CLI's."""

from __future__ import annotations

import math
import os
import time
from dataclasses import dataclass
from typing import Iterable, List, Optional, Sequence

from .sweep import fan_out


@dataclass
class BarnResult:
    """A finished BARN sweep: one row per run, one summary per planner and
    difficulty class (``class`` ``"all"`` first), and how it was run."""

    runs: List[dict]
    summaries: List[dict]
    backend: str
    tasks: int
    seconds: float


def _run_jobs(jobs, seed, noise, paths):
    """One task: a block of (world, planner, run) jobs. Imports planlab
    itself so it runs in any worker process."""
    import planlab

    return planlab.barn_runs([tuple(j) for j in jobs], seed, noise, list(paths))


def barn(
    worlds: Optional[Iterable[int]] = None,
    planners: Sequence[str] = (),
    runs: int = 1,
    seed: int = 0,
    noise: float = 0.01,
    paths: Sequence[str] = (),
    backend: str = "local",
    workers: Optional[int] = None,
    jobs_per_task: int = 4,
    ray_init: Optional[dict] = None,
) -> BarnResult:
    """``planlab barn``: every planner (default: every one that can drive
    an unknown map) on every world (default: all loaded) ``runs`` times.

    ``paths``: BARN folders or ``world_N.world`` files (default: the 250
    public worlds the package holds). ``noise``: the laser's range noise
    σ in metres (0: exact). ``backend``: ``"local"`` (a thread pool; the
    core releases the GIL) or ``"ray"`` (Ray tasks of ``jobs_per_task``
    runs; ``ray.init(**ray_init)`` when Ray is not initialised), through
    the same fan-out as :func:`planlab.sweep`.
    """
    import planlab

    if backend not in ("local", "ray"):
        raise planlab.ParamError(f'backend {backend!r}: expected "local" or "ray"')
    if not isinstance(runs, int) or not 1 <= runs <= 100:
        raise planlab.ParamError(f"runs {runs}: must be from 1 to 100")
    if not isinstance(jobs_per_task, int) or jobs_per_task < 1:
        raise planlab.ParamError(f"jobs_per_task {jobs_per_task}: must be ≥ 1")
    if not (isinstance(noise, (int, float)) and math.isfinite(noise) and 0 <= noise <= 1):
        raise planlab.ParamError(f"noise {noise}: must be from 0 to 1 m")
    paths = [os.fspath(p) for p in paths]
    info = planlab.barn_worlds_info(paths)
    known = {w["world"]: w for w in info}
    ids = sorted(known) if worlds is None else list(worlds)
    for w in ids:
        if w not in known:
            raise planlab.ParamError(f"world {w}: not among the {len(known)} BARN worlds loaded")
    names = list(planners) or list(planlab.barn_planners())
    todo = [(w, p, r) for w in ids for p in names for r in range(runs)]
    blocks = [todo[i:i + jobs_per_task] for i in range(0, len(todo), jobs_per_task)]
    started = time.perf_counter()
    tasks = [(_run_jobs, (b, seed, noise, paths)) for b in blocks]
    results = fan_out(tasks, backend, workers, ray_init)
    rows = [r for block in results for r in block]
    summaries = []
    for p in names:
        mine = [r for r in rows if r["planner"] == p]
        summaries.append(dict(planlab.barn_stats(mine), planner=p, **{"class": "all"}))
        for c in ("easy", "medium", "hard"):
            sub = [r for r in mine if r["difficulty"] == c]
            if sub:
                summaries.append(dict(planlab.barn_stats(sub), planner=p, **{"class": c}))
    return BarnResult(
        runs=rows,
        summaries=summaries,
        backend=backend,
        tasks=len(blocks),
        seconds=time.perf_counter() - started,
    )
