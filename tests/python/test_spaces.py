"""floornav's spaces (Box, Dict) behave as Gymnasium's do without gymnasium: shape, dtype, bounds,
seeded sample(), contains(); and VecEnv's spaces describe exactly what it returns and accepts."""

from __future__ import annotations

import numpy as np
import pytest

import floornav
from floornav._spaces import Box, Dict, batch_space
from conftest import SCENARIOS


def rect(**sets):
    return floornav.load_scenario(SCENARIOS / "rectangle.yaml", sets or None)


def test_a_box_has_its_shape_dtype_and_bounds():
    b = Box(-1.0, [1.0, 2.0], (2,), np.float32)
    assert b.shape == (2,) and b.dtype == np.float32
    assert b.low.tolist() == [-1.0, -1.0] and b.high.tolist() == [1.0, 2.0]
    assert not b.low.flags.writeable  # bounds cannot be changed behind the space's back
    with pytest.raises(ValueError):
        Box(1.0, 0.0, (1,))


def test_samples_lie_in_the_box_and_repeat_with_the_seed():
    b = Box([-1.0, 0.0, -np.inf, -np.inf], [1.0, np.inf, 5.0, np.inf], (4,), np.float64, seed=3)
    draws = [b.sample() for _ in range(200)]
    assert all(b.contains(x) for x in draws)
    assert len({tuple(x) for x in draws}) == 200  # not a constant
    again = Box(b.low, b.high, (4,), np.float64, seed=3)
    assert all(np.array_equal(x, again.sample()) for x in draws)
    other = Box(b.low, b.high, (4,), np.float64, seed=4)
    assert not np.array_equal(other.sample(), draws[0])


def test_an_integer_box_samples_integers_between_its_bounds():
    b = Box(0, 3, (), np.int32, seed=0)
    draws = {int(b.sample()) for _ in range(100)}
    assert draws == {0, 1, 2, 3} and b.sample().dtype == np.int32
    assert b.contains(np.int32(2)) and not b.contains(np.int32(4))


def test_contains_refuses_what_the_box_does_not_hold():
    b = Box(-1.0, 1.0, (2,))
    assert b.contains(np.array([0.5, -0.5])) and np.array([1.0, -1.0]) in b
    assert not b.contains(np.array([1.5, 0.0]))        # out of bounds
    assert not b.contains(np.array([0.0, np.nan]))     # NaN is in no box
    assert not b.contains(np.zeros(3))                 # wrong shape
    assert not b.contains(np.zeros((1, 2)))
    assert not b.contains("ab")


def test_a_dict_space_samples_and_contains_by_key():
    d = Dict({"a": Box(0.0, 1.0, (2,)), "b": Box(0, 5, (), np.int32)}, seed=1)
    x = d.sample()
    assert set(x) == {"a", "b"} and d.contains(x)
    assert not d.contains({"a": x["a"]})                        # a key missing
    assert not d.contains(dict(x, c=1))                         # a key too many
    assert not d.contains({"a": np.array([2.0, 0.0]), "b": x["b"]})
    d2 = Dict({"a": Box(0.0, 1.0, (2,)), "b": Box(0, 5, (), np.int32)}, seed=1)
    y = d2.sample()
    assert np.array_equal(x["a"], y["a"]) and x["b"] == y["b"]
    assert d["a"] is d.spaces["a"] and list(d) == ["a", "b"] and len(d) == 2


def test_batch_space_stacks_copies():
    b = batch_space(Box([-1.0, -2.0], [1.0, 2.0], (2,)), 4)
    assert b.shape == (4, 2) and b.high[3].tolist() == [1.0, 2.0]
    d = batch_space(Dict({"x": Box(0.0, 1.0, (3,))}), 5)
    assert d.spaces["x"].shape == (5, 3)


def test_vec_env_spaces_describe_its_observations_and_actions():
    env = floornav.VecEnv(rect(), 6, seed=0)
    assert env.single_action_space.shape == (2,) and env.action_space.shape == (6, 2)
    assert env.single_action_space.high[0] == env.action_high[0] > 0
    assert env.single_action_space.low.tolist() == env.action_low.tolist()
    obs, _ = env.reset(seed=0)
    assert set(obs) == set(env.single_observation_space.spaces)
    for key, space in env.single_observation_space.spaces.items():
        assert obs[key].shape == (6,) + space.shape, key
        assert obs[key].dtype == space.dtype, key
        assert env.observation_space.spaces[key].shape == (6,) + space.shape
    env.action_space.seed(5)
    for _ in range(300):
        assert env.observation_space.contains(obs)
        for i in range(6):
            assert env.single_observation_space.contains({k: v[i] for k, v in obs.items()})
        obs, *_ = env.step(env.action_space.sample())


def test_the_range_bounds_are_the_sensors():
    env = floornav.VecEnv(rect(), 2)
    r = env.single_observation_space.spaces["ranges"]
    assert r.shape == (5,) and np.all(r.high == 0.3) and np.all(r.low >= 0.0)
