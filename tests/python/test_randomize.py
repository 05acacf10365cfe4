"""VecEnv(randomize=...): every reset and autoreset draws each copy's start and goal anew, from
the env's seed, over the free poses of the world's bounds (or a region); bad settings are
ValueErrors, a region with no free pose an InputError naming `randomize`."""

from __future__ import annotations

import numpy as np
import pytest

import floornav
from conftest import SCENARIOS

FREE = {"start": "free", "goal": "free"}
BOUNDS = (-0.5, -1.2, 3.0, 1.2)          # rectangle.yaml's world
OBSTACLE = (1.0, -0.5, 1.4, 0.5)         # its one rectangle


def rect(**sets):
    return floornav.load_scenario(SCENARIOS / "rectangle.yaml", sets or None)


def inside(p, box, margin=0.0):
    return box[0] - margin <= p[0] <= box[2] + margin and box[1] - margin <= p[1] <= box[3] + margin


def test_copies_start_and_aim_at_different_free_places():
    env = floornav.VecEnv(rect(), 64, seed=0, randomize=FREE)
    obs, _ = env.reset()
    pose, goal = obs["pose"], obs["goal"]
    assert len({tuple(p) for p in pose}) == 64 and len({tuple(g) for g in goal}) == 64
    r = 0.075  # the QuickBot's body: inside the bounds, off the rectangle
    for p, g in zip(pose, goal):
        assert inside(p, (BOUNDS[0] + r, BOUNDS[1] + r, BOUNDS[2] - r, BOUNDS[3] - r))
        assert inside(g, (BOUNDS[0] + r, BOUNDS[1] + r, BOUNDS[2] - r, BOUNDS[3] - r))
        assert not inside(p, OBSTACLE, margin=r) or not inside(p, OBSTACLE)
        assert not inside(g, OBSTACLE)
        assert -np.pi <= p[2] < np.pi
    # Spread over the floor, not bunched at the scenario's start.
    assert pose[:, 0].min() < 0.5 and pose[:, 0].max() > 2.0
    assert not np.any(np.all(pose[:, :2] == 0.0, axis=1))


def test_no_copy_starts_in_a_collision():
    env = floornav.VecEnv(rect(), 256, seed=1, randomize=FREE)
    env.reset()
    _, _, terminated, _, info = env.step(np.zeros((256, 2)))
    assert not np.any(info["status"] == floornav.STATUS_NAMES.index("collision"))


def test_the_same_seed_draws_the_same_episodes():
    a = floornav.VecEnv(rect(), 8, seed=0, randomize=FREE)
    b = floornav.VecEnv(rect(), 8, seed=0, randomize=FREE)
    oa, _ = a.reset(seed=11)
    ob, _ = b.reset(seed=11)
    assert np.array_equal(oa["pose"], ob["pose"]) and np.array_equal(oa["goal"], ob["goal"])
    again, _ = a.reset(seed=11)
    assert np.array_equal(again["pose"], oa["pose"])
    other, _ = a.reset(seed=12)
    assert not np.any(np.all(other["pose"] == oa["pose"], axis=1))


def test_reset_without_a_seed_goes_on_to_new_episodes():
    # Gymnasium's convention: reset() without a seed continues the episode stream, it does not
    # repeat the last episodes; the stream itself is reproducible from the first seed.
    a = floornav.VecEnv(rect(), 8, seed=3, randomize=FREE)
    b = floornav.VecEnv(rect(), 8, seed=3, randomize=FREE)
    first, info_a = a.reset()
    second, info_b = a.reset()
    assert not np.any(np.all(second["pose"] == first["pose"], axis=1))
    assert not np.any(info_a["seeds"] == info_b["seeds"])
    b.reset()
    again, _ = b.reset()
    assert np.array_equal(again["pose"], second["pose"])
    reseeded, _ = a.reset(seed=3)
    assert np.array_equal(reseeded["pose"], first["pose"])


def test_autoreset_draws_a_new_episode():
    env = floornav.VecEnv(rect(**{"sim.t_max": 0.05}), 4, seed=0, randomize=FREE)
    obs, _ = env.reset()
    first = obs["pose"].copy()
    for _ in range(5):
        obs, _, _, truncated, info = env.step(np.zeros((4, 2)))
    assert truncated.all() and "final_obs" in info
    assert np.array_equal(info["final_obs"]["pose"][:, :2], first[:, :2])  # it stood still
    assert not np.any(np.all(obs["pose"] == first, axis=1))  # the new episodes start elsewhere
    assert np.all(obs["t"] == 0.0)


def test_only_the_start_or_only_the_goal():
    env = floornav.VecEnv(rect(), 5, randomize={"start": "free"})
    obs, _ = env.reset()
    assert np.all(obs["goal"] == [2.4, 0.0]) and len({tuple(p) for p in obs["pose"]}) == 5
    env = floornav.VecEnv(rect(), 5, randomize={"goal": "free"})
    obs, _ = env.reset()
    assert np.all(obs["pose"] == 0.0) and len({tuple(g) for g in obs["goal"]}) == 5


def test_regions_and_goal_distances_hold():
    env = floornav.VecEnv(rect(), 32, randomize={"start": [-0.4, -1.0, 0.5, 1.0],
                                                 "goal": [1.6, -1.0, 2.9, 1.0],
                                                 "goal_distance": (1.5, 3.0), "clearance": 0.05})
    obs, _ = env.reset()
    for p, g in zip(obs["pose"], obs["goal"]):
        assert inside(p, (-0.4, -1.0, 0.5, 1.0)) and inside(g, (1.6, -1.0, 2.9, 1.0))
        assert 1.5 <= np.hypot(*(g - p[:2])) <= 3.0


@pytest.mark.parametrize("bad", [
    "free", {"start": "anywhere"}, {"start": [0, 0, 1]}, {"start": [1, 0, 0, 1]},
    {"goal": [0, 0, 1, float("nan")]}, {"clearance": -1}, {"goal_distance": 2},
    {"goal_distance": (3, 1)}, {"max_tries": 0}, {"where": "free"}])
def test_bad_settings_are_value_errors(bad):
    with pytest.raises(ValueError):
        floornav.VecEnv(rect(), 2, randomize=bad)


def test_a_region_with_no_free_pose_is_an_input_error():
    env = floornav.VecEnv(rect(), 2, randomize={"start": [1.05, -0.4, 1.35, 0.4], "max_tries": 200})
    with pytest.raises(floornav.InputError, match="randomize.*no free start pose"):
        env.reset()
