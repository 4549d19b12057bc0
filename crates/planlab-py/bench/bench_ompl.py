"""planlab's sampling planners against OMPL's, in the same run, on the
same Moving AI maps, queries and disc robot.

    python crates/planlab-py/bench/bench_ompl.py [--per-map 10] [--seeds 5]
        [--radius 0.4] [--budgets 0.1,1] [--json out.json] [MAP ...]

Needs the `ompl` wheel (pinned in crates/planlab-py/requirements-dev.txt,
so scripts/setup.sh puts it in .venv) and planlab built optimised into the
same venv (maturin develop --profile py-release); docs/bench-ompl.md says
how and what was measured. A full run takes minutes per map: CI runs only
crates/planlab-py/tests/test_bench_ompl_smoke.py (two arena rows through
`run_map`) and the harness tests.

Metrics, medians over seeds per map and over all maps:
- RRT-Connect: wall (and CPU) time to the first solution; both stop there;
- RRT* and PRM*: best path cost (Euclidean length in cells) after each
  time budget.

Like for like: both plan for a disc of `--radius` cells in the continuous
plane of the grid (x = column, y = row, cell (c, r) the square
[c, c+1] x [r, r+1], a query's cells at their centres), centres in the box
[r, W − r] x [r, H − r]. A point is free when its distance to every
blocked cell's square and to the map edge is at least the radius —
planlab's rule; OMPL's state validity checker is `DiscClearance.is_free`
below, exact for that rule, and its motion validator by default
`DiscClearance.segment_free`, planlab's exact swept-disc test (or, with
--motion discrete, OMPL's DiscreteMotionValidator at --check-step). Both
get the same extension range. The two libraries alternate per
query/seed (who goes first too), so machine load falls on both alike.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import statistics
import sys
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[3]
MIN_RADIUS = 1e-9
HALF_DIAGONAL = math.sqrt(0.5)
D = REPO / "tests/data/movingai"
MAPS = [
    D / "dao/arena.map",
    D / "dao/arena2.map",
    D / "maze/maze512-1-0.map",
    D / "random/random512-10-0.map",
]


# ------------------------------------------------------------------ harness pieces
# (no OMPL or planlab here: crates/planlab-py/tests/test_bench_ompl_harness.py
# tests them in CI.)


def pick_rows(rows, k):
    """`k` rows spread evenly over the .scen file: row indices
    round(i·(n−1)/(k−1)), i = 0..k−1. Moving AI files are sorted by bucket
    (optimal length), so the sample runs from the shortest to the longest
    queries and is the same on every run."""
    n = len(rows)
    if k >= n:
        return list(range(n))
    if k == 1:
        return [0]
    return sorted({round(i * (n - 1) / (k - 1)) for i in range(k)})


def centre_distances(blocked):
    """Exact Euclidean distance from each cell's centre to the nearest
    blocked cell's centre (∞ without one): per column the 1-D distance,
    then per row the exact minimum over columns of (Δx² + that²), in
    chunks of rows to bound memory. numpy only."""
    blocked = np.asarray(blocked, dtype=bool)
    h, w = blocked.shape
    big = float(h + w) ** 2 * 4
    idx = np.arange(h, dtype=float)[:, None]
    # Nearest blocked row above and below each cell, per column.
    up = np.where(blocked, idx, -np.inf)
    up = np.maximum.accumulate(up, axis=0)
    down = np.where(blocked, idx, np.inf)
    down = np.minimum.accumulate(down[::-1], axis=0)[::-1]
    g = np.minimum(idx - up, down - idx)
    g2 = np.where(np.isfinite(g), g * g, big)
    dx2 = (np.arange(w)[:, None] - np.arange(w)[None, :]).astype(float) ** 2
    out = np.empty((h, w))
    chunk = max(1, 4_000_000 // (w * w))
    for r0 in range(0, h, chunk):
        # out[r, x] = min over x' of dx2[x, x'] + g2[r, x']
        out[r0:r0 + chunk] = (dx2[None, :, :] + g2[r0:r0 + chunk, None, :]).min(axis=2)
    return np.where(out >= big, np.inf, np.sqrt(out))


def point_square_distance(x, y, col, row):
    """Distance from (x, y) to the closed square of cell (col, row)."""
    dx = max(col - x, 0.0, x - (col + 1))
    dy = max(row - y, 0.0, y - (row + 1))
    return math.hypot(dx, dy)


def point_segment_distance(px, py, ax, ay, bx, by):
    dx, dy = bx - ax, by - ay
    len2 = dx * dx + dy * dy
    t = 0.0 if len2 == 0.0 else min(1.0, max(0.0, ((px - ax) * dx + (py - ay) * dy) / len2))
    return math.hypot(ax + t * dx - px, ay + t * dy - py)


def segment_square_distance(ax, ay, bx, by, col, row):
    """Distance from the segment a → b to the closed square of (col, row):
    0 when they meet (slab test), else the least of the ends' distances to
    the square and the corners' distances to the segment."""
    lo, hi = (float(col), float(row)), (col + 1.0, row + 1.0)
    a, d = (ax, ay), (bx - ax, by - ay)
    t0, t1, meets = 0.0, 1.0, True
    for k in (0, 1):
        if d[k] == 0.0:
            if a[k] < lo[k] or a[k] > hi[k]:
                meets = False
                break
        else:
            ta, tb = (lo[k] - a[k]) / d[k], (hi[k] - a[k]) / d[k]
            if ta > tb:
                ta, tb = tb, ta
            t0, t1 = max(t0, ta), min(t1, tb)
            if t0 > t1:
                meets = False
                break
    if meets:
        return 0.0
    best = min(point_square_distance(ax, ay, col, row), point_square_distance(bx, by, col, row))
    for cx, cy in ((lo[0], lo[1]), (hi[0], lo[1]), (lo[0], hi[1]), (hi[0], hi[1])):
        best = min(best, point_segment_distance(cx, cy, ax, ay, bx, by))
    return best


class DiscClearance:
    """The disc-clearance rule on a grid, exactly.

    `blocked[row, col]` is True for cells the robot may not touch. A point
    (x, y) is free when its Euclidean distance to the square of every
    blocked cell and to the map edge is ≥ `radius`.

    A blocked square at Chebyshev offset ≥ k + 1 cells from a point's cell
    is more than k cells away, so with k = ceil(radius) only the
    (2k+1)² window around the point's cell can make it unfree. The grid is
    padded with k rings of blocked cells: the nearest padding square is at
    exactly the distance to the map edge, so the edge needs no own test.
    Per cell, precomputed once: blocked (0), no blocked square in the
    window (1: every point of the cell is free), or the window's blocked
    squares to measure (2).
    """

    BLOCKED, SAFE, CHECK = 0, 1, 2

    def __init__(self, blocked, radius):
        blocked = np.asarray(blocked, dtype=bool)
        if blocked.ndim != 2 or 0 in blocked.shape:
            raise ValueError("blocked must be a non-empty 2-D array")
        if not (radius >= 0 and math.isfinite(radius)):
            raise ValueError(f"radius must be finite and >= 0, not {radius}")
        self.blocked = blocked
        self.h, self.w = blocked.shape
        # A radius of 0 is a point that must not touch a blocked square
        # (planlab tests with 1e-9 then; so does this).
        self.radius = max(float(radius), MIN_RADIUS)
        self.blocked_flat = blocked.ravel().tolist()
        # Lower bound of the clearance anywhere in a cell, before the
        # point's offset from the centre: every point of a blocked square
        # is within half a diagonal of its centre.
        self.bound_base = (centre_distances(blocked) - HALF_DIAGONAL).ravel().tolist()
        self.r2 = self.radius * self.radius
        k = max(1, math.ceil(self.radius))
        self.k = k
        padded = np.pad(blocked, k, constant_values=True)
        # Any blocked cell in the window: a 2-D sliding maximum via
        # cumulative sums (no SciPy needed).
        c = np.pad(padded.astype(np.int64).cumsum(0).cumsum(1), ((1, 0), (1, 0)))
        n = 2 * k + 1
        win = c[n:, n:] - c[:-n, n:] - c[n:, :-n] + c[:-n, :-n]
        kind = np.where(blocked, self.BLOCKED, np.where(win == 0, self.SAFE, self.CHECK))
        self.kind = kind.ravel().tolist()
        # The window's blocked squares of each CHECK cell, by their lower
        # corner in map coordinates (padding squares lie outside the map).
        self.squares = {}
        rows, cols = np.nonzero(kind == self.CHECK)
        for r, cc in zip(rows.tolist(), cols.tolist()):
            sub = padded[r:r + n, cc:cc + n]
            br, bc = np.nonzero(sub)
            # (x0, x1, y0, y1): each distance below is then one subtraction,
            # so a point exactly `radius` from a side counts as free.
            self.squares[r * self.w + cc] = tuple(
                (float(cc + j - k), float(cc + j - k + 1), float(r + i - k), float(r + i - k + 1))
                for i, j in zip(br.tolist(), bc.tolist())
            )

    def is_free(self, x, y):
        """Exact: True when the disc at (x, y) touches no blocked square
        and stays inside the map."""
        if not (0.0 <= x < self.w and 0.0 <= y < self.h):
            return False
        i = int(y) * self.w + int(x)
        kind = self.kind[i]
        if kind == 1:
            return True
        if kind == 0:
            return False
        r2 = self.r2
        for x0, x1, y0, y1 in self.squares[i]:
            dx = x0 - x if x < x0 else (x - x1 if x > x1 else 0.0)
            dy = y0 - y if y < y0 else (y - y1 if y > y1 else 0.0)
            if dx * dx + dy * dy < r2:
                return False
        return True

    def bounds(self):
        """The box the disc's centre may occupy, ((x_lo, y_lo), (x_hi, y_hi))."""
        r = self.radius
        return (r, r), (self.w - r, self.h - r)

    def _bound(self, x, y):
        """A lower bound of the clearance at (x, y) inside the map."""
        c, r = min(int(x), self.w - 1), min(int(y), self.h - 1)
        off = math.hypot(x - (c + 0.5), y - (r + 0.5))
        return min(self.bound_base[r * self.w + c] - off, x, y, self.w - x, self.h - y)

    def segment_free(self, ax, ay, bx, by):
        """Exact: whether the disc moving along a → b stays free — planlab's
        test (both ends free; the box of centres is convex, so the edge
        needs no more), sphere tracing on the distance field's lower bound
        and, where it comes within half a cell of the radius, the next
        cell-long piece measured against the blocked squares near it."""
        if not (self.is_free(ax, ay) and self.is_free(bx, by)):
            return False
        dx, dy = bx - ax, by - ay
        length = math.hypot(dx, dy)
        if length == 0.0:
            return True
        ux, uy = dx / length, dy / length
        r = self.radius
        t = 0.0
        while t < length:
            px, py = ax + ux * t, ay + uy * t
            jump = self._bound(px, py) - r
            if jump >= 0.5:
                t += jump
                continue
            t1 = min(t + 1.0, length)
            if not self._piece_free(px, py, ax + ux * t1, ay + uy * t1):
                return False
            t = t1
        return True

    def _piece_free(self, px, py, qx, qy):
        r, w, h = self.radius, self.w, self.h
        blocked = self.blocked_flat
        for row in range(max(0, math.floor(min(py, qy) - r)), min(h - 1, math.floor(max(py, qy) + r)) + 1):
            base = row * w
            for col in range(max(0, math.floor(min(px, qx) - r)),
                             min(w - 1, math.floor(max(px, qx) + r)) + 1):
                if blocked[base + col] and segment_square_distance(px, py, qx, qy, col, row) < r:
                    return False
        return True

    def clearance(self, x, y):
        """Exact distance from (x, y) to the nearest blocked square or the
        map edge (0 inside a blocked cell or off the map). Slow: for tests
        and checks, not for planning."""
        if not (0.0 <= x <= self.w and 0.0 <= y <= self.h):
            return 0.0
        best = min(x, y, self.w - x, self.h - y)
        cx, cy = min(int(x), self.w - 1), min(int(y), self.h - 1)
        ring = 0
        # Ring `ring` squares are more than ring − 1 away: stop once the
        # best distance so far is no more than that.
        while ring - 1 < best:
            for r in range(cy - ring, cy + ring + 1):
                if not 0 <= r < self.h:
                    continue
                for c in range(cx - ring, cx + ring + 1):
                    if max(abs(r - cy), abs(c - cx)) != ring or not 0 <= c < self.w:
                        continue
                    if self.blocked[r, c]:
                        dx = max(c - x, 0.0, x - (c + 1))
                        dy = max(r - y, 0.0, y - (r + 1))
                        best = min(best, math.hypot(dx, dy))
            ring += 1
        return best

    def path_free(self, path):
        """Whether the disc stays free along the whole polyline (exact)."""
        return all(self.segment_free(ax, ay, bx, by)
                   for (ax, ay), (bx, by) in zip(path[:-1], path[1:]))


def path_length(path):
    p = np.asarray(path, dtype=float)
    if len(p) < 2:
        return 0.0
    return float(np.hypot(*np.diff(p, axis=0).T).sum())


def median(values):
    """Median that keeps infinities (an unsolved run counts as ∞ cost or
    time, so a planner failing half its runs has an infinite median)."""
    v = sorted(values)
    return statistics.median(v) if v else float("nan")


def ratio(a, b):
    if math.isnan(a) or math.isnan(b):
        return float("nan")
    if math.isinf(a) and math.isinf(b):
        return float("nan")
    if b == 0 or math.isinf(b):
        return 0.0 if not math.isinf(a) else float("inf")
    return a / b


def fmt(x, digits=4):
    if isinstance(x, float):
        if math.isnan(x):
            return "–"
        if math.isinf(x):
            return "∞"
        return f"{x:.{digits}g}"
    return str(x)


def markdown_table(rows):
    head = ["map", "planner", "metric", "planlab median", "OMPL median", "ratio", "solved planlab/OMPL", "n"]
    out = ["| " + " | ".join(head) + " |", "|" + "|".join(["---"] * 3 + ["---:"] * 5) + "|"]
    for r in rows:
        out.append("| " + " | ".join([
            r["map"], r["planner"], r["metric"], fmt(r["planlab"]), fmt(r["ompl"]),
            fmt(r["ratio"], 3), f"{r['solved_planlab']}/{r['solved_ompl']}", str(r["n"]),
        ]) + " |")
    return "\n".join(out)


# ------------------------------------------------------------------ OMPL side


class OmplRunner:
    """One map's OMPL problem: R² over the box of allowed centres (planlab's
    box: [r, W − r] × [r, H − r]), the exact disc checker as OMPL's state
    validity checker, and a motion validator; a new planner per run.

    motion="exact": a Python MotionValidator running the same exact swept
    disc test as planlab (`DiscClearance.segment_free`). motion="discrete":
    OMPL's own DiscreteMotionValidator, states at most `check_step` cells
    apart (its StateValidityCheckingResolution = check_step / the space's
    maximum extent); a disc of radius r may then cut a corner by up to
    r − √(r² − check_step²/4) between two checked states."""

    def __init__(self, world: DiscClearance, motion="exact", check_step=0.1, range_cells=None):
        from ompl import base as ob, geometric as og

        self.ob, self.og = ob, og
        self.world = world
        self.space = ob.RealVectorStateSpace(2)
        (xl, yl), (xh, yh) = world.bounds()
        b = ob.RealVectorBounds(2)
        b.setLow(0, xl)
        b.setHigh(0, xh)
        b.setLow(1, yl)
        b.setHigh(1, yh)
        self.space.setBounds(b)
        self.ss = og.SimpleSetup(self.space)
        self.state_checks = 0
        self.motion_checks = 0
        self.python_seconds = 0.0
        free, seg = world.is_free, world.segment_free
        clock = time.perf_counter

        def valid(s):
            t = clock()
            ok = free(s[0], s[1])
            self.python_seconds += clock() - t
            self.state_checks += 1
            return ok

        self.ss.setStateValidityChecker(valid)
        self.si = self.ss.getSpaceInformation()
        self.si.setStateValidityCheckingResolution(check_step / self.si.getMaximumExtent())
        if motion == "exact":
            runner = self

            class ExactMotion(ob.MotionValidator):
                def checkMotion(self, a, b, *last_valid):
                    t = clock()
                    ok = seg(a[0], a[1], b[0], b[1])
                    runner.python_seconds += clock() - t
                    runner.motion_checks += 1
                    return ok

            self._motion = ExactMotion(self.si)  # kept alive: OMPL holds a raw reference
            self.si.setMotionValidator(self._motion)
        elif motion != "discrete":
            raise ValueError(f"motion must be exact or discrete, not {motion!r}")
        self.motion = motion
        self.check_step = check_step
        self.range_cells = range_cells

    def close(self):
        """Drops the OMPL objects and the validator subclass that refers
        back to this runner: nanobind cannot collect such a cycle, and
        reports it as leaked at exit."""
        self.ss = self.si = self.space = self._motion = None

    def planner(self, name):
        og = self.og
        p = {"rrt-connect": og.RRTConnect, "rrt-star": og.RRTstar, "prm-star": og.PRMstar}[name](self.si)
        if self.range_cells is not None and hasattr(p, "setRange"):
            p.setRange(self.range_cells)
        return p

    def run(self, name, start, goal, seconds):
        """Plans from cell `start` to cell `goal` (their centres) for at most
        `seconds` (RRT-Connect stops at its first solution, RRT* and PRM*
        use the whole budget). Returns wall and CPU seconds, the path
        (cells) or None, and the checks made."""
        ss = self.ss
        ss.clear()
        s, g = self.space.allocState(), self.space.allocState()
        s[0], s[1] = start[0] + 0.5, start[1] + 0.5
        g[0], g[1] = goal[0] + 0.5, goal[1] + 0.5
        self.state_checks = self.motion_checks = 0
        self.python_seconds = 0.0
        t0, c0 = time.perf_counter(), time.process_time()
        ss.setStartAndGoalStates(s, g)
        p = self.planner(name)
        ss.setPlanner(p)
        ss.setup()
        status = ss.solve(seconds)
        wall, cpu = time.perf_counter() - t0, time.process_time() - c0
        path = None
        if status and ss.haveExactSolutionPath():
            sp = ss.getSolutionPath()
            path = [(sp.getState(i)[0], sp.getState(i)[1]) for i in range(sp.getStateCount())]
        return {"wall": wall, "cpu": cpu, "path": path, "state_checks": self.state_checks,
                "motion_checks": self.motion_checks, "python_seconds": self.python_seconds,
                "range": p.getRange() if hasattr(p, "getRange") else None,
                "goal_bias": p.getGoalBias() if hasattr(p, "getGoalBias") else None}


# ------------------------------------------------------------------ planlab side


class PlanlabRunner:
    """planlab.plan with a sampling algorithm on one map."""

    def __init__(self, grid, radius, range_cells=None, max_iterations=2_000_000):
        import planlab

        self.planlab = planlab
        self.grid = grid
        self.radius = radius
        self.range_cells = range_cells
        self.max_iterations = max_iterations

    def warm(self, start, goal):
        """Builds the grid's free space for the disc (an exact distance
        transform, kept by the `Grid` for later calls) outside the timed
        runs, as OMPL's checker is built before them; returns seconds."""
        t = time.perf_counter()
        try:
            self.planlab.plan(self.grid, tuple(start), tuple(goal), algo="rrt-connect",
                              iterations=1, radius=self.radius)
        except self.planlab.PlanError:
            pass
        return time.perf_counter() - t

    def run(self, name, start, goal, seconds, seed):
        kw = dict(algo=name, iterations=self.max_iterations, seed=seed, radius=self.radius,
                  shortcut=False, time_limit=seconds)
        if self.range_cells is not None:
            kw["range"] = self.range_cells
        t0, c0 = time.perf_counter(), time.process_time()
        try:
            res = self.planlab.plan(self.grid, tuple(start), tuple(goal), **kw)
        except self.planlab.PlanError as e:
            # No path within the budget (the endpoints, cell centres of free
            # cells, are free for a disc under half a cell).
            if "no path after" not in str(e):
                raise
            res = {}
        wall, cpu = time.perf_counter() - t0, time.process_time() - c0
        path = res.get("path")
        if path is not None and len(path) and math.isfinite(res.get("cost", math.inf)):
            path = [(float(x), float(y)) for x, y in np.asarray(path, dtype=float)]
        else:
            path = None
        return {"wall": wall, "cpu": cpu, "path": path, "reported_cost": res.get("cost"),
                "iterations": res.get("iterations"),
                "first_solution_iteration": res.get("first_solution_iteration")}


# ------------------------------------------------------------------ the benchmark


def default_range(w, h):
    """planlab's default extension step: a tenth of the map's diagonal,
    at least 2 cells."""
    return max(2.0, math.hypot(w, h) / 10.0)


def run_map(map_path, args, log):
    import planlab

    grid = planlab.load_map(map_path)
    rows = planlab.load_scen(Path(str(map_path) + ".scen"))
    picked = pick_rows(rows, args.per_map)
    t = time.perf_counter()
    world = DiscClearance(grid.occupancy != 0, args.radius)
    prep = time.perf_counter() - t
    if args.range == "planlab":
        rng = default_range(grid.width, grid.height)
    elif args.range == "own":
        rng = None
    else:
        rng = float(args.range)
    ompl = OmplRunner(world, args.motion, args.check_step, rng) if "ompl" in args.libs else None
    mine = PlanlabRunner(grid, args.radius, rng) if "planlab" in args.libs else None
    name = map_path.stem
    r0 = rows[picked[0]]
    warm = mine.warm((int(r0[0]), int(r0[1])), (int(r0[2]), int(r0[3]))) if mine else float("nan")
    log(f"{name}: rows {picked}; range {rng}; OMPL checker built in {prep:.2f} s, "
        f"planlab's space in {warm:.3f} s")
    runs = []
    jobs = [("rrt-connect", args.first_cap)] + [(p, b) for p in ("rrt-star", "prm-star") for b in args.budgets]
    jobs = [j for j in jobs if j[0] in args.planners]
    for qi, ri in enumerate(picked):
        r = rows[ri]
        start, goal = (int(r[0]), int(r[1])), (int(r[2]), int(r[3]))
        for algo, seconds in jobs:
            for seed in range(args.seeds):
                order = ("planlab", "ompl") if (qi + seed) % 2 == 0 else ("ompl", "planlab")
                for lib in (x for x in order if x in args.libs):
                    out = (mine.run(algo, start, goal, seconds, seed) if lib == "planlab"
                           else ompl.run(algo, start, goal, seconds))
                    path = out.pop("path")
                    cost = path_length(path) if path else float("inf")
                    valid = bool(path) and world.path_free(path)
                    runs.append(dict(out, map=name, row=ri, start=start, goal=goal,
                                     grid_optimum=float(r[4]), algo=algo, budget=seconds,
                                     seed=seed, lib=lib, cost=cost, path_valid=valid))
            done = [x for x in runs if x["row"] == ri and x["algo"] == algo and x["budget"] == seconds]
            log(f"  row {ri} {algo} {seconds:g}s: " + "; ".join(
                f"{lib} cost {fmt(median([x['cost'] for x in done if x['lib'] == lib]))}"
                f" wall {fmt(median([x['wall'] for x in done if x['lib'] == lib]))} s"
                for lib in ("planlab", "ompl")))
    if ompl is not None:
        ompl.close()
    return runs, {"rows": picked, "range": rng, "checker_build_s": prep, "planlab_space_s": warm}


def summarise(runs):
    table = []
    maps = list(dict.fromkeys(x["map"] for x in runs))
    order = {"rrt-connect": 0, "rrt-star": 1, "prm-star": 2}
    keys = sorted({(x["algo"], x["budget"]) for x in runs}, key=lambda k: (order[k[0]], k[1]))
    for key in keys:
        for m in maps + ["all"]:
            xs = [x for x in runs if (x["algo"], x["budget"]) == key and (m == "all" or x["map"] == m)]
            if not xs:
                continue
            algo, budget = key
            by = {lib: [x for x in xs if x["lib"] == lib] for lib in ("planlab", "ompl")}
            solved = {lib: sum(x["cost"] < math.inf for x in v) for lib, v in by.items()}
            n = max(len(by["planlab"]), len(by["ompl"]))
            if algo == "rrt-connect":
                metrics = [("first-solution wall s", lambda x: x["wall"] if x["cost"] < math.inf else math.inf),
                           ("first-solution CPU s", lambda x: x["cpu"] if x["cost"] < math.inf else math.inf),
                           ("path cost (cells)", lambda x: x["cost"])]
            else:
                metrics = [(f"cost after {budget:g} s (cells)", lambda x: x["cost"]),
                           ("CPU s used", lambda x: x["cpu"])]
            for metric, f in metrics:
                a = median([f(x) for x in by["planlab"]])
                b = median([f(x) for x in by["ompl"]])
                table.append(dict(map=m, planner=algo, metric=metric, planlab=a, ompl=b,
                                  ratio=ratio(a, b), solved_planlab=solved["planlab"],
                                  solved_ompl=solved["ompl"], n=n))
            # Where both solved the same query with the same seed index:
            # the median of planlab's cost / OMPL's, a figure that the
            # unsolved runs (∞ medians) do not hide.
            pairs = {}
            for x in xs:
                if x["cost"] < math.inf and "row" in x:
                    pairs.setdefault((x["map"], x["row"], x["seed"]), {})[x["lib"]] = x["cost"]
            both = [v["planlab"] / v["ompl"] for v in pairs.values() if len(v) == 2 and v["ompl"] > 0]
            if both:
                table.append(dict(map=m, planner=algo, metric=f"cost planlab/OMPL where both solved"
                                  f"{'' if algo == 'rrt-connect' else f' ({budget:g} s)'}",
                                  planlab=float("nan"), ompl=float("nan"), ratio=median(both),
                                  solved_planlab=solved["planlab"], solved_ompl=solved["ompl"],
                                  n=len(both)))
            if by["ompl"] and "python_seconds" in by["ompl"][0]:
                share = median([x["python_seconds"] / x["wall"] for x in by["ompl"] if x["wall"] > 0])
                table.append(dict(map=m, planner=algo, metric="OMPL: share of wall time in Python checks",
                                  planlab=float("nan"), ompl=share, ratio=float("nan"),
                                  solved_planlab=solved["planlab"], solved_ompl=solved["ompl"], n=n))
    return table


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("maps", nargs="*", type=Path, default=MAPS)
    ap.add_argument("--per-map", type=int, default=10, help="queries per map (spread over the .scen file)")
    ap.add_argument("--seeds", type=int, default=5)
    ap.add_argument("--radius", type=float, default=0.4, help="robot radius, cells")
    ap.add_argument("--motion", choices=["exact", "discrete"], default="exact",
                    help="OMPL's motion check: planlab's exact swept-disc test, or OMPL's discrete one")
    ap.add_argument("--check-step", type=float, default=0.1,
                    help="--motion discrete: states at most this many cells apart")
    ap.add_argument("--range", default="planlab",
                    help="extension step given to both: 'planlab' (its default, a tenth of the "
                         "map's diagonal), 'own' (each library's default) or cells")
    ap.add_argument("--planners", default="rrt-connect,rrt-star,prm-star")
    ap.add_argument("--budgets", default="0.1,1", help="RRT*/PRM* time budgets, seconds")
    ap.add_argument("--first-cap", type=float, default=5.0, help="RRT-Connect time cap, seconds")
    ap.add_argument("--libs", default="planlab,ompl", help="run only these (profiling one side)")
    ap.add_argument("--json", type=Path, default=None, help="write every run and the table here")
    ap.add_argument("--ompl-seed", type=int, default=1, help="OMPL's global RNG seed (set once)")
    ap.add_argument("--table-from", type=Path, default=None,
                    help="print the table of a saved --json run and exit")
    args = ap.parse_args()
    if args.table_from:
        print(markdown_table(summarise(json.loads(args.table_from.read_text())["runs"])))
        return
    args.budgets = [float(b) for b in args.budgets.split(",")]
    args.planners = args.planners.split(",")
    args.libs = args.libs.split(",")

    from ompl import util as ou
    import planlab

    ou.setLogLevel(ou.LogLevel.LOG_ERROR)
    # OMPL seeds each planner's generator from one process-wide sequence:
    # set once, the run is repeatable up to timing (seeds cannot be set
    # per run after the first generator exists).
    ou.RNG.setSeed(args.ompl_seed)

    def log(msg):
        print(msg, file=sys.stderr, flush=True)

    all_runs, info = [], {}
    for m in args.maps:
        runs, info[m.stem] = run_map(m, args, log)
        all_runs += runs
    table = summarise(all_runs)
    print(markdown_table(table))
    invalid = [(x["lib"], x["map"], x["row"], x["algo"], x["seed"]) for x in all_runs
               if x["cost"] < math.inf and not x["path_valid"]]
    print(f"\npaths failing the exact disc check: {len(invalid)} {invalid[:10]}")
    versions = {"planlab": planlab.__version__, "ompl": _dist_version("ompl"),
                "numpy": np.__version__, "python": sys.version.split()[0]}
    print(f"versions: {versions}")
    if args.json:
        args.json.write_text(json.dumps({
            "command": " ".join(sys.argv),
            "args": {k: (str(v) if isinstance(v, Path) else v) for k, v in vars(args).items()
                     if k != "maps"},
            "maps": [str(m) for m in args.maps],
            "versions": versions, "maps_info": info, "table": table,
            "runs": all_runs, "invalid_paths": invalid,
        }, indent=1, default=str))
    sys.stdout.flush()
    sys.stderr.flush()
    # OMPL's nanobind module reports "leaked" instances at interpreter exit
    # (its own reference cycles, harmless here): skip that teardown noise.
    os._exit(0)


def _dist_version(name):
    from importlib.metadata import version

    return version(name)


if __name__ == "__main__":
    main()
