"""planlab.plan per query against the native `planlab bench grid` on the
same Moving AI rows (A* and JPS, default options), both measured in this
run the same way: every row once per repetition, repeated until each
planner ran ≥ 0.2 s, the fastest repetition kept.

    python crates/planlab-py/bench/bench_plan.py [--cli target/release/planlab] [MAP ...]

Build the package optimised first (maturin develop --profile py-release).
Prints one JSON line per map: ms per query of each and the Python call
overhead in percent.
"""

import argparse
import json
import subprocess
import time
from pathlib import Path

import planlab

REPO = Path(__file__).resolve().parents[3]
MAPS = [
    REPO / "tests/data/movingai/random/random512-10-0.map",
    REPO / "tests/data/movingai/maze/maze512-1-0.map",
]


def time_rows(grid, rows, algo, min_seconds=0.2, reps=3):
    queries = [((int(r[0]), int(r[1])), (int(r[2]), int(r[3])), r[4]) for r in rows]
    # The first query also builds the map's passability grid once.
    planlab.plan(grid, queries[0][0], queries[0][1], algo=algo)
    best, total, done = float("inf"), 0.0, 0
    while done < reps or total < min_seconds:
        t = time.perf_counter()
        for s, g, optimum in queries:
            cost = planlab.plan(grid, s, g, algo=algo)["cost"]
            if abs(cost - optimum) > 1e-3 * max(optimum, 1.0):
                raise SystemExit(f"{algo}: cost {cost} differs from the optimum {optimum}")
        dt = time.perf_counter() - t
        best, total, done = min(best, dt), total + dt, done + 1
    return best * 1e3 / len(queries)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("maps", nargs="*", type=Path, default=MAPS)
    ap.add_argument("--cli", default=str(REPO / "target/release/planlab"))
    args = ap.parse_args()
    for m in args.maps:
        scen = Path(str(m) + ".scen")
        native = json.loads(subprocess.run([args.cli, "bench", "grid", str(m), str(scen)],
                                           capture_output=True, text=True, check=True).stdout)
        grid = planlab.load_map(m)
        rows = planlab.load_scen(scen)
        py = {a: time_rows(grid, rows, a) for a in ("astar", "jps")}
        print(json.dumps({
            "map": m.name,
            "rows": len(rows),
            "cli_astar_ms": round(native["astar_ms"], 5),
            "py_astar_ms": round(py["astar"], 5),
            "astar_overhead_pct": round(100 * (py["astar"] / native["astar_ms"] - 1), 2),
            "cli_jps_ms": round(native["jps_ms"], 5),
            "py_jps_ms": round(py["jps"], 5),
            "jps_overhead_pct": round(100 * (py["jps"] / native["jps_ms"] - 1), 2),
        }))


if __name__ == "__main__":
    main()
