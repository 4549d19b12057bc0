"""Ray on an existing cluster: a head started apart (`ray start --head`,
as on a cluster's head node) and a fresh interpreter with only RAY_ADDRESS
set. In a file of its own so that no Ray of another test is running when
`ray stop` ends the head."""

from __future__ import annotations

import json
import os
import shutil
import socket
import subprocess
import sys
import tempfile
from pathlib import Path

from conftest import ROOM
from test_sweep import PLANNERS, cli_hashes

CROWD = ROOM
def test_ray_sweep_joins_an_existing_cluster_through_ray_address(cli, tmp_path):
    """A Ray head started apart (`ray start --head`, as on a cluster's head
    node), then a fresh interpreter with only RAY_ADDRESS set: the sweep's
    `ray.init()` joins that cluster and gives `planlab batch`'s hashes."""

    ray_cli = Path(sys.executable).with_name("ray")
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    # Token authentication off on both sides (a local test cluster; a real
    # one shares its token with RAY_AUTH_TOKEN, see the README).
    env = {**os.environ, "RAY_ENABLE_UV_RUN_RUNTIME_ENV": "0", "RAY_USAGE_STATS_ENABLED": "0",
           "RAY_AUTH_MODE": "disabled"}
    env.pop("RAY_ADDRESS", None)
    # A session folder of its own, short: Ray's socket paths must fit 107 bytes.
    temp = tempfile.mkdtemp(prefix="ray-", dir="/tmp")
    head = subprocess.run([str(ray_cli), "start", "--head", "--node-ip-address=127.0.0.1",
                           f"--port={port}", "--num-cpus=2", "--include-dashboard=false",
                           "--disable-usage-stats", f"--temp-dir={temp}"],
                          env=env, capture_output=True, text=True, timeout=120)
    assert head.returncode == 0, head.stderr
    try:
        want = cli_hashes(cli, CROWD, tmp_path, 4, 2, 0.3)
        code = (
            "import json, ray, planlab\n"
            f"res = planlab.sweep([{str(CROWD)!r}], planners={PLANNERS!r}, variants=4, seed=2,"
            " jitter=0.3, backend='ray', min_task_seconds=0.0)\n"
            "print(json.dumps({'address': ray.get_runtime_context().gcs_address,"
            " 'rows': [[r['variant'], r['planner'], r['trace_hash'], r['steps'],"
            " r['metrics']['outcome']] for r in res.rows]}))\n"
        )
        run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                             env={**env, "RAY_ADDRESS": f"127.0.0.1:{port}"}, timeout=300)
        assert run.returncode == 0, run.stderr[-2000:]
        out = json.loads(run.stdout.strip().splitlines()[-1])
        # Joined the head (its GCS port; Ray names the node by its own IP),
        # did not start a cluster of its own.
        assert out["address"].endswith(f":{port}"), out["address"]
        got = {(v, p): (h, s, o) for v, p, h, s, o in out["rows"]}
        assert got == want
    finally:
        subprocess.run([str(ray_cli), "stop", "--force"], env=env, capture_output=True, timeout=120)
        shutil.rmtree(temp, ignore_errors=True)
