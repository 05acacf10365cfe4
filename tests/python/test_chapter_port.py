"""The chapter's automaton written in Python (floornav.chapter, from the behaviours and the
HybridAutomaton engine) drives every chapter scenario along the built-in kind's trajectory, to
1e-9 m, with the same modes and the same transitions: the Python door is complete."""

from __future__ import annotations

import numpy as np
import pytest

import floornav
import floornav.chapter
from conftest import SCENARIOS

CHAPTER = ["rectangle", "factory_delivery", "week7_pocket", "concave_obstacle", "convex_obstacle",
           "circle_obstacle", "point_obstacle", "practice2_pillars", "coppeliasim_pioneer"]


def compare(scenario, kind):
    builtin = floornav.run(scenario)
    port = floornav.run(scenario, factory=floornav.chapter.factory(kind), kind=kind)
    a, b = builtin.trajectory, port.trajectory
    assert len(a["x"]) == len(b["x"]) > 100
    assert np.max(np.abs(a["x"] - b["x"])) <= 1e-9
    assert np.max(np.abs(a["y"] - b["y"])) <= 1e-9
    assert np.max(np.abs(a["theta"] - b["theta"])) <= 1e-9
    assert a["mode"].tolist() == b["mode"].tolist()
    assert builtin.transitions == port.transitions
    sa, sb = dict(builtin.summary), dict(port.summary)
    sa.pop("wall_time"), sb.pop("wall_time")
    assert sa == sb
    return builtin


@pytest.mark.parametrize("name", CHAPTER)
def test_the_python_hybrid_automaton_reproduces_the_builtin_one(name):
    s = floornav.load_scenario(SCENARIOS / f"{name}.yaml", {"controller.kind": "hybrid"})
    r = compare(s, "hybrid")
    assert r.status == "reached"


@pytest.mark.parametrize("kind", ["go_to_goal", "hard_switch", "blended"])
def test_the_other_kinds_too(kind):
    compare(floornav.load_scenario(SCENARIOS / "rectangle.yaml", {"controller.kind": kind}), kind)


def test_with_sensor_noise_and_obstacle_memory_off():
    s = floornav.load_scenario(SCENARIOS / "factory_delivery.yaml",
                               {"robot.sensors.noise": 0.005, "controller.obstacle_memory": 0})
    compare(s, "hybrid")


def test_the_port_has_the_builtin_structure():
    p = floornav.load_scenario(SCENARIOS / "rectangle.yaml").params
    a = floornav.chapter.make_navigation_automaton("hybrid", p)
    assert a.mode_names == ["go_to_goal", "follow_boundary_cw", "follow_boundary_ccw",
                            "avoid_obstacle", "stop"]
    assert a.guard_names[:4] == ["at_goal"] * 4
    assert "progress_and_clear_shot" in a.guard_names and "safe_again_cw" in a.guard_names
    with pytest.raises(ValueError):
        floornav.chapter.make_navigation_automaton("teleport", p)
