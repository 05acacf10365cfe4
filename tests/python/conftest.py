"""Shared fixtures of the Python tests: where the repository, its scenarios and the command-line
tool are, and a helper that runs the tool. The tests import floornav from PYTHONPATH (ctest sets
it to build/python; by hand: PYTHONPATH=build/python /usr/bin/python3 -m pytest tests/python)."""

from __future__ import annotations

import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
SCENARIOS = ROOT / "scenarios"
BAD = ROOT / "tests" / "data" / "bad"
EXAMPLES = ROOT / "examples" / "python"


def cli_path() -> pathlib.Path:
    path = pathlib.Path(os.environ.get("FLOORNAV_CLI", ROOT / "build" / "floornav"))
    if not path.exists():
        pytest.skip(f"the floornav executable is not built ({path}); set FLOORNAV_CLI")
    return path


@pytest.fixture(scope="session")
def cli() -> pathlib.Path:
    return cli_path()


def run_cli(*args: str, cwd: pathlib.Path = ROOT) -> subprocess.CompletedProcess:
    """Runs the floornav executable; returns the finished process (text output)."""
    return subprocess.run([str(cli_path()), *map(str, args)], cwd=cwd, capture_output=True,
                          text=True, timeout=600)


@pytest.fixture()
def scenario_path():
    return lambda name: SCENARIOS / name
