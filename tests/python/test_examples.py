"""The examples in examples/python run (in their --quick form) and produce what they promise."""

from __future__ import annotations

import csv
import json
import os
import subprocess
import sys

import pytest

from conftest import EXAMPLES, ROOT


def run_example(name, tmp_path):
    env = dict(os.environ, MPLBACKEND="Agg")
    p = subprocess.run([sys.executable, str(EXAMPLES / name), "--quick", "--out", str(tmp_path)],
                       cwd=ROOT, env=env, capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stderr
    return p.stdout


def test_examples_are_numbered():
    names = sorted(p.name for p in EXAMPLES.glob("*.py"))
    assert names == ["01_chapter_simulation.py", "02_week7_supervisor.py",
                     "03_parameter_sweep.py", "04_vec_env.py", "05_train_ppo.py"]


def test_01_the_chapter_simulation(tmp_path):
    out = run_example("01_chapter_simulation.py", tmp_path)
    lines = {l.split()[0] + " " + l.split()[1]: l for l in out.splitlines() if l.startswith("  ")}
    assert "collision" in lines["go to"]  # go-to-goal alone drives into the cylinder
    assert "reached" in lines["GTG +"] and "reached" in lines["wall following"]
    assert "reached" in lines["built-in hybrid"]
    assert (tmp_path / "01_chapter_simulation.png").stat().st_size > 10_000


def test_02_the_week7_supervisor(tmp_path):
    out = run_example("02_week7_supervisor.py", tmp_path)
    first = out.splitlines()[0]
    assert "reached in" in first
    t = float(first.split("reached in ")[1].split(" s")[0])
    assert t < 30.0  # the course's requirement
    assert "(sliding_left)" in out or "(sliding_right)" in out
    assert (tmp_path / "02_week7_supervisor.gif").stat().st_size > 1_000


def test_03_the_parameter_sweep(tmp_path):
    out = run_example("03_parameter_sweep.py", tmp_path)
    assert out.startswith("8 runs in")
    with open(tmp_path / "03_parameter_sweep.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    assert len(rows) == 8
    assert {r["scenario"] for r in rows} == {"rectangle", "convex-obstacle"}
    assert all(r["status"] in ("reached", "collision", "timeout", "stuck") for r in rows)
    assert (tmp_path / "03_parameter_sweep.png").exists()


def test_04_the_vec_env_loop(tmp_path):
    out = run_example("04_vec_env.py", tmp_path)
    assert "32 copies x 400 steps = 12,800 robot-steps" in out
    assert "episodes ended" in out


def test_05_ppo_trains_a_few_iterations(tmp_path):
    # The smoke test: three small PPO iterations on randomized VecEnv episodes, the held-out
    # evaluation, the curve and the policy written (the full training is the example's, not a
    # test's). Debian's python3-torch (scripts/quickstart.sh installs it with the test tools).
    out = run_example("05_train_ppo.py", tmp_path)
    rows = [json.loads(l) for l in out.splitlines() if l.startswith("{")]
    assert [r["iteration"] for r in rows] == [0, 1, 2, 3]  # 0: the untrained policy
    assert all(r["steps"] == r["iteration"] * 16 * 32 for r in rows)
    assert "held_out_success" in rows[0]
    assert 0.0 <= rows[-1]["held_out_success"] <= 1.0
    assert "held-out success" in out.splitlines()[-1]
    curve = json.loads((tmp_path / "05_train_ppo.json").read_text())
    assert curve == rows
    assert (tmp_path / "05_train_ppo.png").stat().st_size > 5_000
    assert (tmp_path / "05_train_ppo.pt").stat().st_size > 1_000
