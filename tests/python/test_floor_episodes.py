"""VecEnv(randomize={"floor": "factory_floor", ...}): every episode of every copy, at reset and at
autoreset, runs on a generated floor drawn from the episode's seed (from `floor_seeds`, or any
seed), the same for the same seed, and each such episode equals floornav.factory_floor's scenario
of that floor run on its own."""

from __future__ import annotations

import numpy as np
import pytest

import floornav
from conftest import SCENARIOS

TEMPLATE = SCENARIOS / "floor_template.yaml"


def template(**sets):
    return floornav.load_scenario(TEMPLATE, {"sim.t_max": 2, **sets})


def floor_env(n=8, seed=0, **randomize):
    return floornav.VecEnv(template(), n, seed=seed,
                           randomize={"floor": "factory_floor", **randomize})


def run_until_every_copy_ended_once(env, steps=400):
    """Steps with zero commands (t_max 2 s: every copy times out) and gathers the floors each
    copy was on, episode after episode."""
    obs, info = env.reset()
    floors = [[f] for f in info["floor_seeds"]]
    for _ in range(steps):
        obs, _, terminated, truncated, info = env.step(np.zeros((env.num_envs, 2)))
        for i in np.flatnonzero(terminated | truncated):
            floors[i].append(info["floor_seeds"][i])
    return floors


def test_every_episode_gets_a_new_floor_at_reset_and_autoreset():
    env = floor_env(4)
    floors = run_until_every_copy_ended_once(env, 450)  # two episodes of 200 steps each, at least
    assert all(len(f) >= 3 for f in floors)
    seen = [f for copy in floors for f in copy]
    assert len(set(seen)) == len(seen)  # 64-bit seeds: no floor twice
    _, info = env.reset()  # a reset without a seed goes on to new episodes: new floors
    assert not set(info["floor_seeds"]) & set(seen)


def test_the_same_seed_gives_the_same_floors_and_runs():
    a, b = floor_env(6, seed=5), floor_env(6, seed=5)
    obs_a, info_a = a.reset()
    obs_b, info_b = b.reset()
    np.testing.assert_array_equal(info_a["floor_seeds"], info_b["floor_seeds"])
    for k in obs_a:
        np.testing.assert_array_equal(obs_a[k], obs_b[k])
    assert run_until_every_copy_ended_once(a) == run_until_every_copy_ended_once(b)
    # Another seed, other floors (episode e of copy i has seed `seed + i + e * n_envs`: seeds
    # 6 apart would share five of their six first episodes, as their sensor noise does).
    _, info_c = floor_env(6, seed=1000).reset()
    assert not set(info_c["floor_seeds"]) & set(info_a["floor_seeds"])
    # reset(seed=...) starts the same floors over.
    _, again = a.reset(seed=5)
    np.testing.assert_array_equal(again["floor_seeds"], info_a["floor_seeds"])


def test_the_floors_differ_and_hold_the_robot():
    env = floor_env(16, seed=1)
    obs, info = env.reset()
    # Different floors: different starts and tours, each the floor's own.
    assert len(set(info["floor_seeds"])) == 16
    assert len({tuple(p) for p in obs["pose"]}) == 16 and len({tuple(g) for g in obs["goal"]}) == 16
    for i in (0, 7):
        alone = floornav.factory_floor(template(), int(info["floor_seeds"][i]))
        assert tuple(obs["pose"][i]) == tuple(alone.robots[0]["start"])
    frames = floornav.VecEnv(template(), 2, seed=1, render_mode="rgb_array",
                             randomize={"floor": "factory_floor"})
    frames.reset()
    f0 = frames.render()
    frames.reset()
    f1 = frames.render()
    assert not np.array_equal(f0, f1)  # drawn on the new floors, not the first ones


def test_an_episode_equals_its_floor_run_alone():
    env = floor_env(3, seed=11, floor_seeds=range(100, 110))
    obs, info = env.reset()
    floors = info["floor_seeds"]
    assert all(100 <= f < 110 for f in floors)
    seeds = info["seeds"]
    for i in range(3):
        scenario = floornav.factory_floor(template(), int(floors[i])).with_seed(int(seeds[i]))
        sim = floornav.Simulation(scenario)
        o = sim.observe()
        np.testing.assert_array_equal(o["pose"], obs["pose"][i])
        np.testing.assert_array_equal(o["ranges"], obs["ranges"][i])
    # The controllers drive; each copy's run equals its floor's Simulation, step for step.
    sims = [floornav.Simulation(floornav.factory_floor(template(), int(floors[i]))
                                .with_seed(int(seeds[i]))) for i in range(3)]
    for _ in range(50):
        obs, *_ = env.step(None)
        for i, sim in enumerate(sims):
            sim.step()
            np.testing.assert_array_equal(sim.observe()["pose"], obs["pose"][i])


def test_floor_seeds_choose_the_floors():
    env = floor_env(32, seed=3, floor_seeds=[7, 8])
    _, info = env.reset()
    assert set(info["floor_seeds"]) == {7, 8}
    env = floor_env(32, seed=3, floor_seeds=range(30, 0, -10))  # 30, 20, 10
    _, info = env.reset()
    assert set(info["floor_seeds"]) <= {10, 20, 30} and len(set(info["floor_seeds"])) > 1


def test_floors_combine_with_drawn_starts_and_goals():
    env = floor_env(8, seed=2, floor_seeds=[4], start="free", goal="free")
    obs, info = env.reset()
    assert set(info["floor_seeds"]) == {4}
    assert len({tuple(p) for p in obs["pose"]}) == 8  # one floor, starts drawn on it


@pytest.mark.parametrize("randomize, match", [
    ({"floor": "warehouse"}, "randomize\\['floor'\\] is one of"),
    ({"floor_seeds": [1]}, "needs randomize\\['floor'\\]"),
    ({"floor": "factory_floor", "floor_seeds": []}, "empty"),
    ({"floor": "factory_floor", "floor_seeds": range(0)}, "empty"),
    ({"floor": "factory_floor", "floor_seeds": [1, -2]}, "floor seed is an integer"),
    ({"floor": "factory_floor", "floor_seeds": [1.5]}, "floor seed is an integer"),
    ({"floor": "factory_floor", "floor_seeds": "12"}, "a range or a sequence"),
])
def test_bad_floor_settings_are_value_errors(randomize, match):
    with pytest.raises(ValueError, match=match):
        floornav.VecEnv(template(), 2, randomize=randomize)


def test_a_generated_floor_is_no_template():
    with pytest.raises(ValueError, match="already generated floor 3"):
        floornav.VecEnv(floornav.factory_floor(template(), 3), 2,
                        randomize={"floor": "factory_floor"})


def test_parallel_env_refuses_floor_draws():
    with pytest.raises(ValueError, match="shared_floor"):
        floornav.ParallelEnv(floornav.shared_floor(SCENARIOS / "shared_floor_template.yaml", 1),
                             randomize={"floor": "factory_floor"})
