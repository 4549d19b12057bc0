"""The examples in examples/python run (small N) and print/write what they
say."""

from __future__ import annotations

import re
import subprocess
import sys

from conftest import DATA, REPO, ROOM, SCENARIOS

EX = REPO / "examples" / "python"
PNG = b"\x89PNG\r\n\x1a\n"


def run(script, *args):
    p = subprocess.run([sys.executable, str(EX / script), *map(str, args)],
                       capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stderr
    return p.stdout


def is_png(path):
    return path.read_bytes()[:8] == PNG and path.stat().st_size > 2000


def test_plan_movingai(tmp_path):
    out = tmp_path / "plan.png"
    text = run("plan_movingai.py", DATA / "movingai" / "dao" / "arena.map", out, "--row", "5")
    costs = re.findall(r"(astar|jps): cost ([\d.]+) \(optimum ([\d.]+)\)", text)
    assert [c[0] for c in costs] == ["astar", "jps"]
    for _, cost, optimum in costs:
        assert abs(float(cost) - float(optimum)) < 1e-3
    assert is_png(out)


def test_success_rates(tmp_path):
    out = tmp_path / "rates.png"
    text = run("success_rates.py", ROOM, out, "--variants", "4")
    rates = re.findall(r"^(dwa|improved-dwa): success ([\d.]+)% \((\d+)/4;", text, re.M)
    assert [r[0] for r in rates] == ["dwa", "improved-dwa"]
    assert "8 episodes" in text and is_png(out)


def test_controller_vs_planner(tmp_path):
    out = tmp_path / "cmp.png"
    text = run("controller_vs_planner.py", ROOM, out)
    line = re.search(r"^outcome\s+(\w+)\s+(\w+)$", text, re.M)
    assert line and line.groups() == ("reached", "reached"), text
    assert re.search(r"^path_length_m\s+[\d.]+\s+[\d.]+$", text, re.M)
    assert is_png(out)


def test_gym_train(tmp_path):
    out = tmp_path / "curve.png"
    text = run("gym_train.py", "--iterations", "3", "--episodes", "2", "--out", out)
    best = [float(x) for x in
            re.findall(r"^iteration \d+: best mean return (-?[\d.]+)", text, re.M)]
    assert len(best) == 3 and best == sorted(best)  # random search keeps the best
    pol = float(re.search(r"tiny policy: mean return (-?[\d.]+)", text).group(1))
    assert pol == best[-1]
    assert re.search(r"random actions: mean return -?[\d.]+ \(reached \d/2\)", text)
    assert is_png(out)


