"""Sweep throughput in episodes per second on Ray with 1 and 2 workers
(and the local thread backend), on the same episodes; every run's hashes
are checked equal.

    python crates/planlab-py/bench/bench_sweep.py [--variants 40] [SCENARIO]

Each Ray size runs in its own process (Ray is initialised once per
process) with `ray.init(num_cpus=N)`.
"""

import argparse
import hashlib
import json
import os
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[3]


def one(scenario, variants, backend, workers):
    import planlab

    if backend == "ray":
        import ray

        os.environ.setdefault("RAY_ENABLE_UV_RUN_RUNTIME_ENV", "0")
        ray.init(num_cpus=workers, include_dashboard=False, log_to_driver=False)
        planlab.sweep(scenario, variants=2, backend="ray")  # warm the workers up
    res = planlab.sweep(scenario, planners=["dwa", "improved-dwa"], variants=variants, seed=1,
                        backend=backend, workers=workers)
    hashes = sorted((r["variant"], r["planner"], r["trace_hash"]) for r in res.rows)
    print(json.dumps({"backend": backend, "workers": workers, "episodes": res.episodes,
                      "seconds": round(res.seconds, 3),
                      "episodes_per_s": round(res.episodes_per_second, 2),
                      "tasks": res.tasks, "variants_per_task": res.variants_per_task,
                      "hashes": hashlib.sha1(json.dumps(hashes).encode()).hexdigest()[:12]}))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scenario", nargs="?", default=str(REPO / "assets/scenarios/dwa-demo.json"))
    ap.add_argument("--variants", type=int, default=40)
    ap.add_argument("--one", nargs=2, metavar=("BACKEND", "WORKERS"))
    args = ap.parse_args()
    if args.one:
        one(args.scenario, args.variants, args.one[0], int(args.one[1]))
        return
    lines = []
    for backend, workers in [("ray", 1), ("ray", 2), ("local", 1), ("local", 2)]:
        out = subprocess.run([sys.executable, __file__, args.scenario, "--variants",
                              str(args.variants), "--one", backend, str(workers)],
                             capture_output=True, text=True, check=True).stdout
        line = json.loads(out.strip().splitlines()[-1])
        lines.append(line)
        print(json.dumps(line))
    if len({line["hashes"] for line in lines}) != 1:
        raise SystemExit("the runs' trace hashes differ")


if __name__ == "__main__":
    main()
