"""A controller written in Python against improved-dwa on one scenario:
both drive the same episode (same world, limits and metrics); the plot
shows both trajectories.

    python examples/python/controller_vs_planner.py SCENARIO.json OUT.png

The controller turns towards the goal and steers away from the closest
LiDAR return in front of it (a few lines of numpy, no planning).
"""

import argparse
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import planlab  # noqa: E402


def controller(obs: dict, lim: dict) -> tuple:
    x, y, th = obs["pose"]
    gx, gy = obs["goal"]
    bearing = math.atan2(gy - y, gx - x) - th
    bearing = math.atan2(math.sin(bearing), math.cos(bearing))
    scan, ang = obs["scan"], obs["scan_angles"]
    ang = np.where(ang > math.pi, ang - 2 * math.pi, ang)
    ahead = np.abs(ang) < 1.2
    near = np.min(np.where(ahead, scan, np.inf))
    w = 1.5 * bearing
    v = lim["v_max"] * max(0.0, math.cos(bearing))
    if near < 1.2:
        # Something close in front: slow down and turn to the freer side.
        left = np.mean(np.minimum(scan[(ang > 0) & (ang < 1.5)], 3.0))
        right = np.mean(np.minimum(scan[(ang < 0) & (ang > -1.5)], 3.0))
        w += 1.5 if left > right else -1.5
        v *= max(0.0, (near - 0.35) / 0.85)
    return v, w


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scenario")
    ap.add_argument("out")
    args = ap.parse_args()

    s = planlab.Scenario.from_file(args.scenario)
    ep = s.episode(lidar={"beams": 72, "range": 4.0})
    lim = ep.limits
    while not ep.done:
        ep.step(command=controller(ep.observe(), lim))
    mine, mine_trace = ep.metrics(), ep.trace()
    theirs = s.run(planner="improved-dwa")
    rows = ["outcome", "time_s", "path_length_m", "min_clearance_m", "total_turn_rad"]
    print(f"{'metric':<18}{'controller':>14}{'improved-dwa':>14}")
    for k in rows:
        a, b = mine[k], theirs["metrics"][k]
        fmt = (lambda v: f"{v:>14.3f}") if isinstance(a, float) else (lambda v: f"{v:>14}")
        print(f"{k:<18}{fmt(a)}{fmt(b)}")
    fig, ax = plt.subplots(figsize=(6, 5))
    x0, y0, x1, y1 = ep.bounds
    grid = planlab.load_map(args.scenario)
    ax.imshow(grid.occupancy == 1, cmap="gray_r", origin="upper",
              extent=(x0, x1, y0, y1), interpolation="nearest")
    ax.plot(mine_trace["x"], mine_trace["y"], label=f"controller ({mine['outcome']})")
    t = theirs["trace"]
    ax.plot(t["x"], t["y"], label=f"improved-dwa ({theirs['metrics']['outcome']})")
    ax.plot(*ep.observe()["goal"], "r*", ms=12)
    ax.set_aspect("equal")
    ax.legend(loc="best")
    fig.savefig(args.out, dpi=100, bbox_inches="tight")
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
