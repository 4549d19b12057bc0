"""Plan on a Moving AI map with A* and JPS and plot both paths.

    python examples/python/plan_movingai.py MAP.map OUT.png [--row K]

Prints each planner's cost beside the .scen file's optimum (the same
numbers as `planlab plan`) and writes the map with both paths to OUT.png.
"""

import argparse

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import planlab  # noqa: E402


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("map", help="Moving AI .map (its .scen beside it)")
    ap.add_argument("out", help="PNG to write")
    ap.add_argument("--row", type=int, default=-1, help="scenario row (default: the last)")
    args = ap.parse_args()

    grid = planlab.load_map(args.map)
    rows = planlab.load_scen(args.map + ".scen")
    r = rows[args.row]
    start, goal, optimum = (int(r[0]), int(r[1])), (int(r[2]), int(r[3])), r[4]
    fig, ax = plt.subplots(figsize=(6, 6))
    ax.imshow(grid.occupancy == 1, cmap="gray_r", interpolation="nearest")
    for algo, style in [("astar", "-"), ("jps", "--")]:
        res = planlab.plan(grid, start, goal, algo=algo)
        p = res["path"]
        ax.plot(p[:, 0], p[:, 1], style, lw=2, label=f"{algo}: cost {res['cost']:.3f}")
        print(f"{algo}: cost {res['cost']:.4f} (optimum {optimum:.4f}), "
              f"{len(p)} cells, {res['expanded']} expanded")
    ax.plot(*start, "go")
    ax.plot(*goal, "r*", ms=12)
    ax.set_title(f"{args.map.split('/')[-1]}: row {args.row}")
    ax.legend(loc="lower right")
    fig.savefig(args.out, dpi=100, bbox_inches="tight")
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
