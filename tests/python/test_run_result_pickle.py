"""RunResult pickles and copies: the result's data comes back bit for bit (every field the summary,
the trajectory, the transition log, the crowd's tracks and the files it writes are made of),
without running the scenario again; a copy equals the original; a result of a Python controller
pickles without the controller."""

from __future__ import annotations

import copy
import filecmp
import math
import pickle

import numpy as np
import pytest

import floornav
from conftest import SCENARIOS


def same_values(a, b):
    """Equal, NaN equal to NaN (a summary's NaN-free, but be strict about arrays)."""
    if isinstance(a, dict):
        return isinstance(b, dict) and list(a) == list(b) and all(same_values(a[k], b[k]) for k in a)
    if isinstance(a, (list, tuple)):
        return type(a) is type(b) and len(a) == len(b) and all(map(same_values, a, b))
    if isinstance(a, np.ndarray):
        return a.dtype == b.dtype and a.shape == b.shape and (
            np.array_equal(a, b, equal_nan=a.dtype.kind == "f"))
    if isinstance(a, float) and math.isnan(a):
        return isinstance(b, float) and math.isnan(b)
    return type(a) is type(b) and a == b


def everything(r):
    """Every public field of a result."""
    return {"summary": r.summary, "trajectory": r.trajectory, "transitions": r.transitions,
            "status": r.status, "mode_names": r.mode_names, "is_fleet": r.is_fleet,
            "crowd": r.crowd, "repr": repr(r), "scenario": r.scenario.name}


def assert_same_files(a, b, tmp_path, mcap=False):
    """The files both write are equal byte for byte (summary.json, trajectory.csv, run.mcap ...)."""
    da, db = tmp_path / "a", tmp_path / "b"
    a.write(da, mcap=mcap)
    b.write(db, mcap=mcap)
    names = sorted(p.name for p in da.iterdir())
    assert names == sorted(p.name for p in db.iterdir()) and "summary.json" in names
    match, mismatch, errors = filecmp.cmpfiles(da, db, names, shallow=False)
    assert mismatch == [] and errors == [] and match == names


@pytest.fixture(scope="module")
def lone():
    # The week-7 supervisor: mode switches, a transition log, a trajectory, recorded ranges.
    return floornav.run(SCENARIOS / "week7_pocket.yaml", mcap=True)


def test_a_pickled_run_comes_back_bit_for_bit(lone, tmp_path):
    assert lone.transitions and len(lone.trajectory["t"]) > 100  # something to compare
    back = pickle.loads(pickle.dumps(lone))
    assert back is not lone and same_values(everything(back), everything(lone))
    assert back == lone
    assert_same_files(lone, back, tmp_path, mcap=True)  # the ranges, wall_time, optimum too


def test_unpickling_does_not_run_the_scenario_again(lone):
    # The wall time is the original run's (a second run would have its own), at every protocol.
    for protocol in range(2, pickle.HIGHEST_PROTOCOL + 1):
        back = pickle.loads(pickle.dumps(lone, protocol=protocol))
        assert back.summary["wall_time"] == lone.summary["wall_time"]
        assert back == lone


def test_a_fleet_among_people_pickles_with_its_crowd(tmp_path):
    r = floornav.run(floornav.load_scenario(SCENARIOS / "crowd" / "factory_hunav.yaml",
                                           {"sim.t_max": 3}))
    assert r.is_fleet and r.crowd["people"]
    back = pickle.loads(pickle.dumps(r))
    assert same_values(everything(back), everything(r)) and back == r
    assert_same_files(r, back, tmp_path)


def test_copies_equal_the_original(lone):
    assert copy.copy(lone) is lone  # immutable: itself, as a Scenario
    deep = copy.deepcopy(lone)
    assert deep is not lone and deep == lone and same_values(everything(deep), everything(lone))
    # Its arrays are its own: changing them changes nothing in the original.
    deep.trajectory["x"][:] = 0.0
    assert not np.array_equal(lone.trajectory["x"], deep.trajectory["x"])


def test_results_of_other_runs_are_not_equal(lone):
    other = floornav.run(floornav.load_scenario(SCENARIOS / "week7_pocket.yaml", {"sim.seed": 2}))
    assert other != lone and lone != "a result"
    shorter = floornav.run(floornav.load_scenario(SCENARIOS / "week7_pocket.yaml", {"sim.t_max": 1}))
    assert shorter != lone


def test_a_python_controllers_result_pickles_without_the_controller():
    s = floornav.load_scenario(SCENARIOS / "rectangle.yaml", {"sim.t_max": 2}).with_controller(
        lambda o: (0.1, 0.0), kind="mine")
    r = floornav.run(s)
    back = pickle.loads(pickle.dumps(r))
    assert same_values(back.summary, r.summary) and back.summary["controller"] == "mine"
    assert back.scenario.python_controller
    with pytest.raises(ValueError, match="without its Python controller 'mine'"):
        floornav.run(back.scenario)


def test_a_damaged_pickle_is_a_clear_error(lone):
    state = lone.__getstate__()
    broken = (state[0], state[1], state[2][:-7])
    with pytest.raises(ValueError, match="pickled RunResult"):
        type(lone).__new__(type(lone)).__setstate__(broken)
