"""floornav.factory_floor / shared_floor: a template on a floor generated from a seed, the same
floor as `floornav batch --floors` / `--shared-floors` runs for that seed; they pickle, step in
VecEnv and ParallelEnv, and refuse what they cannot make."""

from __future__ import annotations

import json
import pickle
import subprocess

import numpy as np
import pytest

import floornav
from conftest import SCENARIOS

FLOOR_TEMPLATE = SCENARIOS / "floor_template.yaml"
SHARED_TEMPLATE = SCENARIOS / "shared_floor_template.yaml"


def test_the_floor_of_a_seed_is_the_command_lines(cli, tmp_path):
    out = tmp_path / "floors"
    subprocess.run([cli, "batch", FLOOR_TEMPLATE, "--floors", "2", "--no-timing", "--no-optimum",
                    "--out", out], check=True, capture_output=True)
    lines = [json.loads(l) for l in (out / "results.jsonl").read_text().splitlines()]
    for seed, line in zip((1, 2), lines):
        s = floornav.factory_floor(FLOOR_TEMPLATE, seed)
        assert s.name == line["scenario"] == f"floor-floor{seed}"
        summary = floornav.run(s).summary
        assert summary["status"] == line["status"]
        assert summary["path_length"] == line["path_length"]  # bit for bit


def test_seeds_make_different_floors_and_the_same_seed_the_same():
    a, b, c = (floornav.factory_floor(FLOOR_TEMPLATE, k) for k in (5, 5, 6))
    assert a.robots[0]["start"] == b.robots[0]["start"] and a.robots[0]["goals"] == b.robots[0]["goals"]
    assert a.robots[0]["start"] != c.robots[0]["start"]
    assert a.robots[0]["preset"] == floornav.load_scenario(FLOOR_TEMPLATE).robots[0]["preset"]


def test_a_generated_floor_pickles_as_template_and_seed():
    s = floornav.factory_floor(FLOOR_TEMPLATE, 9).with_seed(4)
    back = pickle.loads(pickle.dumps(s))
    assert back.name == s.name and back.seed == 4
    assert back.robots[0]["goals"] == s.robots[0]["goals"]
    assert floornav.run(back).summary["path_length"] == floornav.run(s).summary["path_length"]
    fleet = floornav.shared_floor(SHARED_TEMPLATE, 3)
    again = pickle.loads(pickle.dumps(fleet))
    assert [r["start"] for r in again.robots] == [r["start"] for r in fleet.robots]


def test_vec_env_trains_on_generated_floors_with_the_planner_stack():
    # The template's preset is the planner stack on the known floor plan: a VecEnv copy gets the
    # map as Simulation does, and steps as Simulation does, bit for bit.
    floors = [floornav.factory_floor(FLOOR_TEMPLATE, k) for k in range(1, 5)]
    env = floornav.VecEnv(floors, 4, seed=0)
    obs, _ = env.reset()
    sims = [floornav.Simulation(s.with_seed(i)) for i, s in enumerate(floors)]
    for sim in sims:
        sim.reset()
    for _ in range(30):
        obs, *_ = env.step(None)
        for sim in sims:
            sim.step()
    assert np.array_equal(obs["pose"], np.array([sim.pose for sim in sims]))
    assert len({tuple(p[:2]) for p in obs["pose"]}) == 4


def test_parallel_env_on_a_shared_floor():
    s = floornav.shared_floor(SHARED_TEMPLATE, 2)
    env = floornav.ParallelEnv(s, seed=0)
    obs, _ = env.reset(seed=0)
    assert set(obs) == {r["name"] for r in s.robots}
    env.step({a: (0.05, 0.0) for a in env.agents})


def test_what_cannot_be_made_is_refused():
    s = floornav.factory_floor(FLOOR_TEMPLATE, 1)
    with pytest.raises(ValueError, match="already generated floor 1"):
        floornav.factory_floor(s, 2)
    with pytest.raises(ValueError, match="overrides apply to a template file"):
        floornav.factory_floor(floornav.load_scenario(FLOOR_TEMPLATE), 2, {"sim.dt": 0.02})
    # A fleet template on a factory floor would start every robot on one spot.
    with pytest.raises(floornav.InputError, match="floor 1"):
        floornav.factory_floor(SCENARIOS / "fleet_crossing.yaml", 1)
    with pytest.raises((ValueError, TypeError)):
        floornav.factory_floor(FLOOR_TEMPLATE, -1)
