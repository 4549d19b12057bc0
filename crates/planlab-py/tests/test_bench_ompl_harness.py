"""The OMPL benchmark's own pieces (crates/planlab-py/bench/bench_ompl.py)
that decide what OMPL may touch and which queries run. They need only
numpy; the benchmark itself (with the `ompl` wheel) is not run in CI."""

from __future__ import annotations

import importlib.util
import math

import numpy as np
import pytest

from conftest import REPO

_spec = importlib.util.spec_from_file_location(
    "bench_ompl", REPO / "crates" / "planlab-py" / "bench" / "bench_ompl.py")
bench = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(bench)


def brute_clearance(blocked, x, y):
    """Distance to every blocked square and the edge, no shortcuts."""
    h, w = blocked.shape
    best = min(x, y, w - x, h - y)
    for r, c in zip(*np.nonzero(blocked)):
        dx = max(c - x, 0.0, x - (c + 1))
        dy = max(r - y, 0.0, y - (r + 1))
        best = min(best, math.hypot(dx, dy))
    return max(best, 0.0)


def test_clearance_matches_hand_computed_values():
    blocked = np.zeros((3, 3), dtype=bool)
    blocked[1, 1] = True  # the square [1, 2) x [1, 2)
    world = bench.DiscClearance(blocked, 0.4)
    # Cell (0, 0)'s centre: 0.5 from the edge, hypot(0.5, 0.5) from the square.
    assert world.clearance(0.5, 0.5) == pytest.approx(0.5)
    # Beside the square's left side, midway down it: 0.3 from it.
    assert world.clearance(0.7, 1.5) == pytest.approx(0.3)
    # Diagonal to its corner (1, 1): the corner is the nearest point.
    assert world.clearance(0.8, 0.9) == pytest.approx(math.hypot(0.2, 0.1))
    # Inside the blocked cell and off the map: 0.
    assert world.clearance(1.5, 1.5) == 0.0
    assert world.clearance(-0.1, 1.0) == 0.0
    # Exactly the radius away is free (≥), a hair less is not.
    assert world.is_free(0.6, 1.5)
    assert not world.is_free(0.6 + 1e-9, 1.5)
    # The map edge counts like a blocked square: 0.4 from it is free.
    assert world.clearance(0.4, 0.5) == pytest.approx(0.4)
    assert world.is_free(0.4, 0.5) and not world.is_free(0.39, 0.5)


def test_is_free_agrees_with_the_exact_distance_everywhere():
    rng = np.random.default_rng(3)
    blocked = rng.random((14, 17)) < 0.25
    for radius in (0.0, 0.4, 1.0, 1.7):
        world = bench.DiscClearance(blocked, radius)
        pts = [(rng.uniform(-0.5, 17.5), rng.uniform(-0.5, 14.5)) for _ in range(3000)]
        # Points on cell borders and corners, where rounding bites.
        pts += [(c + f, r + g) for c in range(0, 18, 3) for r in range(0, 15, 3)
                for f in (0.0, 0.4, 0.5) for g in (0.0, 0.6)]
        disagree = []
        for x, y in pts:
            inside = 0 <= x < 17 and 0 <= y < 14
            d = brute_clearance(blocked, x, y) if inside else 0.0
            want = inside and not blocked[int(y), int(x)] and d >= world.radius
            if world.is_free(x, y) != want:
                disagree.append((radius, x, y, d))
            if inside:
                assert world.clearance(x, y) == pytest.approx(d, abs=1e-12), (x, y)
        assert disagree == []


def test_path_check_finds_a_wall_between_free_vertices():
    blocked = np.zeros((5, 9), dtype=bool)
    blocked[:4, 4] = True  # a wall with a gap in the bottom row only
    world = bench.DiscClearance(blocked, 0.4)
    a, b = (1.5, 1.5), (7.5, 1.5)
    assert world.is_free(*a) and world.is_free(*b)
    assert not world.path_free([a, b])
    # Through the gap (row 4, 1 cell high): a disc of 0.4 fits at its middle.
    assert world.path_free([a, (1.5, 4.5), (7.5, 4.5), b])
    # ... but not 0.15 off it (0.35 from the wall), nor with a radius
    # wider than half the gap.
    assert not world.path_free([(1.5, 4.35), (7.5, 4.35)])
    assert not bench.DiscClearance(blocked, 0.55).path_free([(1.5, 4.5), (7.5, 4.5)])
    assert bench.path_length([a, (1.5, 4.5), (7.5, 4.5), b]) == pytest.approx(12.0)


def test_centre_distances_are_the_exact_transform():
    rng = np.random.default_rng(5)
    blocked = rng.random((23, 31)) < 0.05
    got = bench.centre_distances(blocked)
    br, bc = np.nonzero(blocked)
    rr, cc = np.mgrid[0:23, 0:31]
    want = np.sqrt(((rr[..., None] - br) ** 2 + (cc[..., None] - bc) ** 2).min(axis=2))
    assert np.array_equal(got, want)
    assert np.isinf(bench.centre_distances(np.zeros((3, 4), dtype=bool))).all()


def test_segment_check_agrees_with_dense_sampling():
    rng = np.random.default_rng(7)
    blocked = rng.random((20, 26)) < 0.12
    for radius in (0.0, 0.4, 0.9):
        world = bench.DiscClearance(blocked, radius)
        # Dense sampling settles a segment unless it grazes: free with a
        # margin (free for a disc 0.01 wider) or blocked with one.
        wider = bench.DiscClearance(blocked, world.radius + 0.01)
        narrower = bench.DiscClearance(blocked, max(world.radius - 0.01, 0.0))
        (xl, yl), (xh, yh) = world.bounds()
        free = blocked_seen = 0
        for _ in range(300):
            a = (rng.uniform(xl, xh), rng.uniform(yl, yh))
            b = (a[0] + rng.normal(0, 4), a[1] + rng.normal(0, 4))
            # Inside the box by a margin: its sides are grazing cases too.
            b = (min(max(b[0], xl + 0.01), xh - 0.01), min(max(b[1], yl + 0.01), yh - 0.01))
            n = max(1, int(math.hypot(b[0] - a[0], b[1] - a[1]) / 0.002))
            pts = [(a[0] + (b[0] - a[0]) * i / n, a[1] + (b[1] - a[1]) * i / n) for i in range(n + 1)]
            got = world.segment_free(*a, *b)
            if all(wider.is_free(*p) for p in pts):
                assert got, (radius, a, b)
                free += 1
            elif not all(narrower.is_free(*p) for p in pts):
                assert not got, (radius, a, b)
                blocked_seen += 1
        assert free > 30 and blocked_seen > 30, (free, blocked_seen)


def test_rows_are_spread_over_the_file_from_first_to_last():
    assert bench.pick_rows(list(range(161)), 10) == [0, 18, 36, 53, 71, 89, 107, 124, 142, 160]
    assert bench.pick_rows(list(range(5)), 10) == [0, 1, 2, 3, 4]
    assert bench.pick_rows(list(range(7)), 1) == [0]


def test_median_counts_unsolved_runs_as_infinite():
    inf = float("inf")
    assert bench.median([1.0, 2.0, inf]) == 2.0
    assert bench.median([1.0, inf, inf]) == inf
    assert bench.ratio(2.0, 4.0) == 0.5
    assert bench.ratio(inf, 4.0) == inf
    assert math.isnan(bench.ratio(inf, inf))


def test_table_has_one_line_per_metric_and_marks_infinity():
    inf = float("inf")
    runs = [dict(map="m", algo="rrt-connect", budget=5.0, lib=lib, cost=cost, wall=wall, cpu=wall)
            for lib, cost, wall in (("planlab", 10.0, 0.01), ("ompl", 12.0, 0.02),
                                    ("ompl", inf, 5.0), ("planlab", inf, 5.0))]
    table = bench.summarise(runs)
    first = [r for r in table if r["map"] == "m" and r["metric"] == "first-solution wall s"][0]
    # Medians of (0.01, ∞) and (0.02, ∞): the mean of the middle pair is ∞.
    assert first["planlab"] == inf and first["ompl"] == inf
    assert (first["solved_planlab"], first["solved_ompl"], first["n"]) == (1, 1, 2)
    text = bench.markdown_table(table)
    assert "| m | rrt-connect | first-solution wall s | ∞ | ∞ | – | 1/1 | 2 |" in text
    cost = [r for r in table if r["map"] == "all" and r["metric"] == "path cost (cells)"][0]
    assert (cost["planlab"], cost["ompl"]) == (inf, inf)
