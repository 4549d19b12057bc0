"""Batches and sweeps (local threads, Ray with 2 workers) give
`planlab batch`'s per-episode trace hashes; `reproduce` gives `planlab
reproduce --json`."""

from __future__ import annotations


import pytest

import planlab
from conftest import ROOM, SCENARIOS

DEMO = SCENARIOS / "dwa-demo.json"
CROWD = ROOM  # small and quick, one mover
PLANNERS = ["dwa", "improved-dwa"]


def cli_hashes(cli, path, tmp_path, variants, seed, jitter, planners=PLANNERS):
    rows = cli.csv("batch", path, "--planners", ",".join(planners), "--variants", str(variants),
                   "--seed", str(seed), "--jitter", str(jitter), out=tmp_path / "b.csv")
    assert len(rows) == variants * len(planners)
    return {(int(r["variant"]), r["planner"]): (r["trace_hash"], int(r["steps"]), r["outcome"])
            for r in rows}


def hashes(rows):
    return {(r["variant"], r["planner"]): (r["trace_hash"], r["steps"], r["metrics"]["outcome"])
            for r in rows}


def test_batch_equals_planlab_batch(cli, tmp_path):
    want = cli_hashes(cli, DEMO, tmp_path, 5, 3, 0.4)
    got = planlab.batch(DEMO, planners=PLANNERS, variants=5, seed=3, jitter=0.4)
    assert hashes(got["runs"]) == want
    summaries = cli.json_lines("batch", DEMO, "--planners", ",".join(PLANNERS),
                               "--variants", "5", "--seed", "3", "--jitter", "0.4")[:-1]
    assert got["summaries"] == summaries


def test_local_sweep_equals_planlab_batch(cli, tmp_path):
    want = cli_hashes(cli, CROWD, tmp_path, 6, 1, 0.3)
    res = planlab.sweep([CROWD], planners=PLANNERS, variants=6, seed=1, jitter=0.3,
                        backend="local", workers=2, min_task_seconds=0.0)
    assert hashes(res.rows) == want
    assert res.tasks == 6 and res.variants_per_task == 1  # one variant per block
    assert [r["variant"] for r in res.rows] == [v for v in range(6) for _ in PLANNERS]


def test_ray_sweep_with_two_workers_equals_planlab_batch(cli, tmp_path, ray_two_workers):
    assert ray_two_workers.cluster_resources()["CPU"] == 2
    want_demo = cli_hashes(cli, DEMO, tmp_path, 8, 4, 0.3)
    want_crowd = cli_hashes(cli, CROWD, tmp_path, 8, 4, 0.3)
    res = planlab.sweep([DEMO, CROWD], planners=PLANNERS, variants=8, seed=4, jitter=0.3,
                        backend="ray", min_task_seconds=0.05)
    assert res.backend == "ray" and res.episodes == 2 * 8 * 2
    assert hashes([r for r in res.rows if r["scenario"] == 0]) == want_demo
    assert hashes([r for r in res.rows if r["scenario"] == 1]) == want_crowd
    # Blocks of several variants: fewer tasks than variants × scenarios.
    assert res.variants_per_task >= 1 and res.tasks <= 2 * 8
    assert {s["planner"] for s in res.summaries} == set(PLANNERS)


@pytest.mark.parametrize("args", [("T-fig3-2", 3), ("T-fig3-2", None), ("T-fig4-6", 2)])
def test_reproduce_equals_planlab_reproduce(cli, args):
    exp, n = args
    flags = [exp] + (["--variants", str(n)] if n else [])
    want = cli.json_lines("reproduce", *flags)
    assert len(want) == 1
    assert planlab.reproduce(exp, variants=n) == want[0]
    assert exp in planlab.reproduce_ids()


def test_reproduce_family_carries_interval_and_sensitivity():
    fam = planlab.reproduce("T-fig4-6", variants=8)
    joint = fam["joint"]
    lo, hi = joint["ci95"]
    assert 0 <= lo <= joint["rate"] <= hi <= 1 and joint["n"] == 8
    # The rule: reproduced needs >= 80 % and a Wilson lower bound >= 0.65.
    if fam["verdict"] == "reproduced":
        assert joint["rate"] >= 0.8 and lo >= 0.65
    sens = fam["sensitivity"]
    assert sens["summary"]
    # One entry per perturbation, each with the reason for its range.
    assert len(sens["perturbations"]) == len(fam["family"]["perturbations"])
    assert [p["why"] for p in sens["perturbations"]] == [p["why"] for p in fam["family"]["perturbations"]]
    assert all(p["why"] for p in sens["perturbations"])



ARM = SCENARIOS / "T-tab5-3.json"


def test_arm_batch_equals_planlab_batch_of_the_arm_scenario(cli, tmp_path):
    """An arm scenario's batch (APF and RRT-Connect on variants of T-tab5-3
    with the table top) is `planlab batch`'s, row for row, and its
    summaries are the CLI's without the CLI's compute time."""
    import json

    doc = json.loads(ARM.read_text())
    doc["arm"]["table_z_m"] = 0.72
    planners = ["apf", "rrt-connect"]
    got = planlab.batch(doc, planners=planners, variants=2, seed=5)
    rows = cli.csv("batch", ARM, "--planners", ",".join(planners), "--variants", "2",
                   "--seed", "5", "--set", "arm.table_z_m=0.72", out=tmp_path / "arm.csv")
    assert {(int(r["variant"]), r["planner"]): (r["trace_hash"], r["outcome"]) for r in rows} == {
        (r["variant"], r["planner"]): (r["trace_hash"], r["metrics"]["metrics"]["outcome"])
        for r in got["runs"]
    }
    lines = cli.json_lines("batch", ARM, "--planners", ",".join(planners), "--variants", "2",
                           "--seed", "5", "--set", "arm.table_z_m=0.72")
    assert lines[-1]["jitter_m"] == 0.02
    for mine, theirs in zip(got["summaries"], lines[:-1]):
        del theirs["metrics"]["compute_ms"]
        assert mine == theirs
    with pytest.raises(planlab.ParamError, match="unknown arm planner `dwa`"):
        planlab.batch(doc, planners=["dwa"], variants=1)
