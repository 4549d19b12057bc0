"""MCAP export: `Scenario.run(mcap=...)` and `planlab run --mcap` write a
file that Foxglove's own reader (the `mcap` package) reads back, with
every step's pose equal to the trace and Foxglove's schemas."""

from __future__ import annotations

import json
from collections import Counter

import pytest
from mcap.reader import make_reader

import planlab
from conftest import SCENARIOS

DEMO = SCENARIOS / "dwa-demo.json"
LIDAR = SCENARIOS / "L-sim1.json"


def messages(path):
    with open(path, "rb") as f:
        reader = make_reader(f)
        return [
            (channel.topic, schema.name, message.log_time, json.loads(message.data))
            for schema, channel, message in reader.iter_messages()
        ]


@pytest.mark.parametrize("scenario,extra", [(DEMO, "/movers"), (LIDAR, "/scan")])
def test_run_writes_an_mcap_file_foxglove_reads_back(tmp_path, scenario, extra):
    out = tmp_path / "run.mcap"
    got = planlab.Scenario.from_file(scenario).run(mcap=out)
    plain = planlab.Scenario.from_file(scenario).run()
    assert got["trace_hash"] == plain["trace_hash"], "recording changed the run"
    msgs = messages(out)
    counts = Counter(topic for topic, *_ in msgs)
    rows = len(got["trace"]["t"])
    assert counts["/map"] == 1
    assert counts["/robot/pose"] == rows and counts["/goal"] == rows
    assert counts[extra] > 0 and counts["/plan/local"] > 0
    assert all(name.startswith("foxglove.") for _, name, _, _ in msgs)
    poses = [(t, m) for topic, _, t, m in msgs if topic == "/robot/pose"]
    for k, (t, m) in enumerate(poses):
        assert t == round(got["trace"]["t"][k] * 1e9)
        assert m["pose"]["position"]["x"] == got["trace"]["x"][k]
        assert m["pose"]["position"]["y"] == got["trace"]["y"][k]
    grid = next(m for topic, _, _, m in msgs if topic == "/map")
    assert grid["fields"] == [{"name": "occupancy", "offset": 0, "type": 1}]


def test_cli_mcap_equals_python_mcap(cli, tmp_path):
    a, b = tmp_path / "cli.mcap", tmp_path / "py.mcap"
    cli.json("run", DEMO, "--mcap", a)
    planlab.Scenario.from_file(DEMO).run(mcap=b)
    assert messages(a) == messages(b)


def test_mcap_of_an_apf_run_is_refused_with_a_clear_error(tmp_path):
    apf = SCENARIOS / "T-fig4-8.json"
    with pytest.raises(planlab.ScenarioError, match="only robot episodes"):
        planlab.Scenario.from_file(apf).run(mcap=tmp_path / "x.mcap")
    assert not (tmp_path / "x.mcap").exists()
