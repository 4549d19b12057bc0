"""Sweeps: the episodes of ``planlab batch`` over many scenarios and
planners, spread over local threads or a Ray cluster.

Each task runs a block of variants through the core's batch functions
(``batch_episodes``), so every episode's trace hash equals the one
``planlab batch`` gives for the same scenario, seed and jitter, whichever
process or machine ran it. Blocks are sized from a timed first episode so a
task lasts at least ``min_task_seconds`` (Ray's per-task overhead is about a
millisecond; tasks of tens of milliseconds keep it small).
"""

from __future__ import annotations

import math
import os
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from typing import Any, Iterable, List, Optional, Sequence, Union


@dataclass
class SweepResult:
    """A finished sweep: one row per episode, one summary per (scenario,
    planner), and how it was run."""

    rows: List[dict]
    summaries: List[dict]
    backend: str
    tasks: int
    variants_per_task: int
    seconds: float
    episodes: int = field(init=False)

    def __post_init__(self) -> None:
        self.episodes = len(self.rows)

    @property
    def episodes_per_second(self) -> float:
        return self.episodes / self.seconds if self.seconds > 0 else math.inf

    def to_pandas(self):
        """The rows as a pandas DataFrame (metrics flattened to columns);
        needs pandas."""
        import pandas as pd  # optional dependency

        flat = []
        for r in self.rows:
            row = {k: v for k, v in r.items() if k != "metrics"}
            row.update(r["metrics"])
            flat.append(row)
        return pd.DataFrame(flat)


def _run_block(doc: dict, base_dir: str, variants: Sequence[int], planners: Sequence[str],
               seed: int, jitter: Optional[float]) -> List[dict]:
    """One task: the scenario document, a block of variant indices, every
    planner. Imports planlab itself so it runs in any worker process."""
    import planlab

    s = planlab.Scenario.from_dict(doc, base_dir)
    return planlab.batch_episodes(s, list(variants), list(planners), seed, jitter)


def fan_out(tasks: Sequence[tuple], backend: str, workers: Optional[int] = None,
            ray_init: Optional[dict] = None) -> List[Any]:
    """Runs ``fn(*args)`` for each ``(fn, args)`` of ``tasks`` on a local
    thread pool of ``workers`` threads (the core releases the GIL) or as
    Ray tasks of one CPU each (``ray.init(**ray_init)`` when Ray is not
    initialised yet); returns the results in task order. ``sweep`` and
    ``barn`` spread their episodes through it."""
    if backend == "local":
        with ThreadPoolExecutor(max_workers=workers or os.cpu_count() or 1) as pool:
            futures = [pool.submit(fn, *args) for fn, args in tasks]
            return [f.result() for f in futures]
    import ray

    if not ray.is_initialized():
        ray.init(**(ray_init or {}))
    # One CPU per task: the cluster's CPUs are the workers (`workers` is
    # for the local backend).
    remotes = {}
    refs = []
    for fn, args in tasks:
        remote = remotes.setdefault(fn, ray.remote(num_cpus=1)(fn))
        refs.append(remote.remote(*args))
    return ray.get(refs)


def _blocks(n: int, size: int) -> List[List[int]]:
    return [list(range(a, min(n, a + size))) for a in range(0, n, size)]


def sweep(
    scenarios: Union[Any, Iterable[Any]],
    planners: Sequence[str] = (),
    variants: int = 20,
    seed: int = 0,
    jitter: Optional[float] = None,
    backend: str = "local",
    workers: Optional[int] = None,
    min_task_seconds: float = 0.05,
    ray_init: Optional[dict] = None,
) -> SweepResult:
    """Runs ``variants`` seeded variants of every scenario with every
    planner (default: each scenario's own), as ``planlab batch --seed SEED
    --jitter JITTER`` would, and collects one row per episode.

    ``scenarios``: a path, dict or :class:`planlab.Scenario`, or a list of
    them (robot or arm scenarios). ``backend``: ``"local"`` (a thread pool of
    ``workers`` threads; the core releases the GIL) or ``"ray"`` (Ray
    tasks; when Ray is not initialised yet, ``ray.init(**ray_init)`` is
    called, which joins the cluster in ``RAY_ADDRESS`` when that is set and
    starts a local one otherwise). Rows are ordered by scenario, variant,
    planner, and carry a ``scenario`` index.
    """
    import planlab

    if backend not in ("local", "ray"):
        raise planlab.ParamError(f'backend {backend!r}: expected "local" or "ray"')
    if not isinstance(variants, int) or not 1 <= variants <= planlab.max_variants():
        raise planlab.ParamError(
            f"variants {variants}: must be from 1 to {planlab.max_variants()}"
        )
    if not (isinstance(min_task_seconds, (int, float)) and min_task_seconds >= 0
            and math.isfinite(min_task_seconds)):
        raise planlab.ParamError(f"min_task_seconds {min_task_seconds}: must be finite and ≥ 0")
    if isinstance(scenarios, (str, os.PathLike, dict, planlab.Scenario)):
        scenarios = [scenarios]
    # Inlined maps: the document alone is the whole scenario in any process.
    items = [planlab.as_scenario(s).inlined() for s in scenarios]
    planners = list(planners)
    started = time.perf_counter()

    # Variant 0 of the first scenario, timed, sizes the blocks (and is kept).
    t0 = time.perf_counter()
    first = planlab.batch_episodes(items[0], [0], planners, seed, jitter)
    per_variant = max(time.perf_counter() - t0, 1e-6)
    size = max(1, math.ceil(min_task_seconds / per_variant))
    size = min(size, variants)

    jobs = []  # (scenario index, variant block)
    for i in range(len(items)):
        start = 1 if i == 0 else 0
        for block in _blocks(variants - start, size):
            jobs.append((i, [start + k for k in block]))
    docs = [(s.to_dict(), str(s.base_dir)) for s in items]

    if backend == "local":
        tasks = [(batch_block, (items[i], block, planners, seed, jitter)) for i, block in jobs]
        results = fan_out(tasks, "local", workers)
    else:
        import ray

        if not ray.is_initialized():
            ray.init(**(ray_init or {}))
        refs = [ray.put(d) for d, _ in docs]
        tasks = [(_run_block, (refs[i], docs[i][1], block, planners, seed, jitter))
                 for i, block in jobs]
        results = fan_out(tasks, "ray", workers, ray_init)

    rows = [dict(r, scenario=0) for r in first]
    for (i, _), res in zip(jobs, results):
        rows.extend(dict(r, scenario=i) for r in res)
    order = {}
    for r in rows:
        order.setdefault(r["planner"], len(order))
    rows.sort(key=lambda r: (r["scenario"], r["variant"], order[r["planner"]]))
    summaries = []
    for i in range(len(items)):
        for p in order:
            ms = [r["metrics"] for r in rows if r["scenario"] == i and r["planner"] == p]
            if ms:
                summaries.append(dict(planlab.summarise(p, ms), scenario=i))
    return SweepResult(
        rows=rows,
        summaries=summaries,
        backend=backend,
        tasks=len(jobs) + 1,
        variants_per_task=size,
        seconds=time.perf_counter() - started,
    )


def batch_block(scenario, variants, planners, seed, jitter):
    """One block in this process (the local backend's task)."""
    import planlab

    return planlab.batch_episodes(scenario, list(variants), list(planners), seed, jitter)
