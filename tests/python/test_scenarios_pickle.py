"""Scenarios pickle and copy: a scenario back from pickle runs to the same summary; a copy is the
(immutable) scenario itself; one with a Python controller refuses with a clear TypeError."""

from __future__ import annotations

import copy
import pickle

import pytest

import floornav
from conftest import SCENARIOS


def same_run(a, b):
    return dict(floornav.run(a).summary, wall_time=0) == dict(floornav.run(b).summary, wall_time=0)


def test_a_pickled_scenario_runs_to_the_same_summary():
    s = floornav.load_scenario(SCENARIOS / "rectangle.yaml",
                               {"controller.kind": "blended", "sim.t_max": 20}).with_seed(9)
    back = pickle.loads(pickle.dumps(s))
    assert back.name == s.name and back.seed == 9 and back.overrides == s.overrides
    assert back.source == s.source and back.controller_kind == "blended"
    assert same_run(s, back)


def test_a_fleet_with_a_map_and_people_pickles():
    s = floornav.load_scenario(SCENARIOS / "crowd" / "factory_hunav.yaml", {"sim.t_max": 2})
    back = pickle.loads(pickle.dumps(s))
    assert back.world["extent"] == s.world["extent"] and same_run(s, back)


def test_parsed_text_pickles_and_copies_are_the_scenario():
    s = floornav.parse_scenario((SCENARIOS / "rectangle.yaml").read_text(), {"sim.t_max": 5},
                                origin=str(SCENARIOS / "rectangle.yaml"))
    assert same_run(s, pickle.loads(pickle.dumps(s)))
    assert copy.copy(s) is s and copy.deepcopy(s) is s


def test_a_python_controller_is_not_pickled():
    s = floornav.load_scenario(SCENARIOS / "rectangle.yaml").with_controller(lambda o: (0.1, 0.0))
    with pytest.raises(TypeError, match="Python controller"):
        pickle.dumps(s)
