"""examples/python/adapters/gymnasium_adapter.py maps floornav's spaces one to one. Gymnasium is
not in Debian 12: a stand-in module records what the adapter builds (the real one has the same
constructors: Box(low, high, shape, dtype), Dict(mapping))."""

from __future__ import annotations

import importlib
import sys
import types

import numpy as np
import pytest

import floornav
from conftest import EXAMPLES, SCENARIOS


class FakeBox:
    def __init__(self, low, high, shape, dtype):
        self.low, self.high, self.shape, self.dtype = low, high, shape, dtype


class FakeDict:
    def __init__(self, spaces):
        self.spaces = spaces


@pytest.fixture()
def adapter(monkeypatch):
    gym = types.ModuleType("gymnasium")
    gym.spaces = types.SimpleNamespace(Box=FakeBox, Dict=FakeDict, Space=object)
    monkeypatch.setitem(sys.modules, "gymnasium", gym)
    monkeypatch.syspath_prepend(str(EXAMPLES / "adapters"))
    sys.modules.pop("gymnasium_adapter", None)
    yield importlib.import_module("gymnasium_adapter")
    sys.modules.pop("gymnasium_adapter", None)


def test_the_adapter_maps_every_space_one_to_one(adapter):
    env = floornav.VecEnv(SCENARIOS / "rectangle.yaml", 3)
    spaces = {k: getattr(env, k) for k in ("observation_space", "action_space",
                                           "single_observation_space", "single_action_space")}
    adapter.wrap_vec_env(env)
    for name, mine in spaces.items():
        theirs = getattr(env, name)
        if isinstance(mine, floornav.Box):
            assert isinstance(theirs, FakeBox) and theirs.shape == mine.shape
            assert np.array_equal(theirs.low, mine.low) and theirs.dtype == mine.dtype
        else:
            assert isinstance(theirs, FakeDict) and set(theirs.spaces) == set(mine.spaces)
            for k, s in mine.spaces.items():
                assert theirs.spaces[k].shape == s.shape and np.array_equal(theirs.spaces[k].high, s.high)
    with pytest.raises(TypeError):
        adapter.to_gymnasium("not a space")
