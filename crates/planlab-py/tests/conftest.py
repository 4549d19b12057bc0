"""Shared fixtures: the repository's data and the `planlab` CLI the tests
compare against (PLANLAB_CLI, else target/release or target/debug)."""

from __future__ import annotations

import csv
import io
import json
import os
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]
DATA = REPO / "tests" / "data"
SCENARIOS = REPO / "assets" / "scenarios"
ROOM = REPO / "crates" / "planlab-py" / "python" / "planlab" / "data" / "room.json"


def _find_cli() -> Path:
    env = os.environ.get("PLANLAB_CLI")
    if env:
        return Path(env)
    roots = [REPO / "target"]
    if os.environ.get("CARGO_TARGET_DIR"):
        roots.insert(0, Path(os.environ["CARGO_TARGET_DIR"]))
    for root in roots:
        for profile in ("release", "debug"):
            p = root / profile / "planlab"
            if p.is_file():
                return p
    raise RuntimeError(
        "no planlab CLI to compare with: set PLANLAB_CLI or build it "
        "(cargo build -p planlab-cli)"
    )


class Cli:
    def __init__(self, path: Path) -> None:
        self.path = path

    def run(self, *args: str) -> str:
        p = subprocess.run([str(self.path), *map(str, args)], capture_output=True, text=True)
        if p.returncode != 0:
            raise AssertionError(f"planlab {' '.join(map(str, args))}: {p.stderr.strip()}")
        return p.stdout

    def json(self, *args: str):
        return json.loads(self.run(*args, "--json"))

    def json_lines(self, *args: str) -> list:
        return [json.loads(line) for line in self.run(*args, "--json").splitlines() if line]

    def csv(self, *args: str, out: Path) -> list:
        self.run(*args, "--csv", str(out))
        return list(csv.DictReader(io.StringIO(out.read_text())))


@pytest.fixture(scope="session")
def cli() -> Cli:
    return Cli(_find_cli())


@pytest.fixture(scope="module")
def ray_two_workers():
    import ray
    os.environ.setdefault("RAY_ENABLE_UV_RUN_RUNTIME_ENV", "0")
    ray.init(num_cpus=2, include_dashboard=False, log_to_driver=False,
             configure_logging=False)
    yield ray
    ray.shutdown()
