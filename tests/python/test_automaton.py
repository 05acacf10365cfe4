"""The hybrid-automaton engine from Python (guards in order, resets on a Python memory, dwell,
chatter, the log, validation) and the chapter's behaviours, against values worked by hand."""

from __future__ import annotations

import math

import numpy as np
import pytest

import floornav
from floornav import AutomatonBuilder, Turn


class Memory:
    def __init__(self):
        self.entered = []


def thermostat(min_dwell=0.0):
    """heat <-> cool on a temperature input with hysteresis; 'off' when told to stop."""
    b = AutomatonBuilder()
    heat = b.add_mode("heat", lambda x, m: +1.0)
    cool = b.add_mode("cool", lambda x, m: -1.0)
    off = b.add_mode("off", lambda x, m: 0.0, terminal=True)
    b.add_edge_from_every_mode("off", "stop", lambda x, m: x["stop"])
    b.add_edge(heat, cool, "too_warm", lambda x, m: x["temp"] > 22,
               lambda x, m: m.entered.append(("cool", x["temp"])), min_dwell=min_dwell)
    b.add_edge("cool", "heat", "too_cold", lambda x, m: x["temp"] < 18,
               lambda x, m: m.entered.append(("heat", x["temp"])), min_dwell=min_dwell)
    b.set_initial("heat")
    b.set_chatter_rule(3, 1.0)
    return b.build()


def test_guards_resets_and_the_log():
    a = thermostat()
    assert a.mode_names == ["heat", "cool", "off"]
    assert a.guard_names == ["stop", "stop", "too_warm", "too_cold"]
    assert a.terminal_modes == [2] and a.find_mode("cool") == 1 and a.find_mode("x") == -1
    s = a.initial_state(Memory())
    assert s.mode == 0 and a.flow({"temp": 20}, s) == 1.0
    assert a.step({"temp": 21, "stop": False}, s, 0.1, 0.1) is None
    tr = a.step({"temp": 23, "stop": False}, s, 0.2, 0.1)
    assert (tr.from_mode, tr.to_mode, tr.guard, tr.time) == (0, 1, "too_warm", 0.2)
    assert s.mode == 1 and a.flow({"temp": 23}, s) == -1.0
    assert s.memory.entered == [("cool", 23)]  # the reset wrote the memory
    assert a.step({"temp": 20, "stop": False}, s, 0.3, 0.1) is None  # hysteresis: stays
    assert a.step({"temp": 17, "stop": False}, s, 0.4, 0.1).guard == "too_cold"
    # Edges are tried in the order they were added: 'stop' before 'too_warm'.
    tr = a.step({"temp": 30, "stop": True}, s, 0.5, 0.1)
    assert tr.guard == "stop" and a.is_terminal(s)
    assert [t.guard for t in s.transitions] == ["too_warm", "too_cold", "stop"]
    assert s.switches == 3


def test_chatter_is_detected():
    a = thermostat()
    s = a.initial_state(Memory())
    temps = [25, 15, 25, 15]
    for k, temp in enumerate(temps):
        a.step({"temp": temp, "stop": False}, s, 0.1 * (k + 1), 0.1)
    assert s.chatter_episodes == 1 and s.chattering
    assert s.first_chatter_time == pytest.approx(0.3)  # the third switch within 1 s


def test_min_dwell_holds_a_mode():
    a = thermostat(min_dwell=0.25)
    s = a.initial_state(Memory())
    assert a.step({"temp": 30, "stop": False}, s, 0.1, 0.1) is None  # held 0.1 s < 0.25 s
    assert a.step({"temp": 30, "stop": False}, s, 0.2, 0.1) is None
    assert a.step({"temp": 30, "stop": False}, s, 0.3, 0.1).guard == "too_warm"
    assert s.time_in_mode == 0.0


def test_a_reset_may_return_a_new_memory_and_state_copies_are_snapshots():
    b = AutomatonBuilder()
    a_mode = b.add_mode("a", lambda x, m: m)
    stop = b.add_mode("stop", lambda x, m: None, terminal=True)
    b.add_edge(a_mode, a_mode, "tick", lambda x, m: True, lambda x, m: m + 1)
    b.add_edge(a_mode, stop, "never", lambda x, m: False)
    a = b.build()
    s = a.initial_state(0)
    snap = s.copy()
    for k in range(3):
        a.step(None, s, k, 1.0)
    assert s.memory == 3 and a.flow(None, s) == 3 and snap.memory == 0


@pytest.mark.parametrize("build, message", [
    (lambda b: None, "no modes"),
    (lambda b: b.add_mode("a", lambda x, m: 0), "no terminal"),
    (lambda b: (b.add_mode("a", lambda x, m: 0), b.add_mode("s", lambda x, m: 0, True),
                b.add_mode("island", lambda x, m: 0)), "unreachable"),
    (lambda b: (b.add_mode("a", lambda x, m: 0), b.add_mode("s", lambda x, m: 0, True),
                b.add_edge(0, 7, "g", lambda x, m: True)), "names no mode"),
    (lambda b: (b.add_mode("a", lambda x, m: 0), b.add_mode("s", lambda x, m: 0, True),
                b.add_edge(1, 0, "back", lambda x, m: True)), "leaves a terminal"),
])
def test_the_builder_refuses_bad_structures(build, message):
    b = AutomatonBuilder()
    build(b)
    with pytest.raises(ValueError, match=message):
        b.build()


def test_builder_argument_errors():
    b = AutomatonBuilder()
    b.add_mode("a", lambda x, m: 0)
    with pytest.raises(ValueError, match="exists already"):
        b.add_mode("a", lambda x, m: 0)
    with pytest.raises(ValueError, match="no mode 'b'"):
        b.add_edge("a", "b", "g", lambda x, m: True)
    with pytest.raises(TypeError):
        b.add_edge("a", "a", "g", 3)
    with pytest.raises(TypeError):
        b.add_mode("c", "not a function")
    with pytest.raises(ValueError):
        b.set_chatter_rule(0, 1.0)


def test_an_exception_in_a_guard_propagates():
    b = AutomatonBuilder()
    b.add_mode("a", lambda x, m: 0)
    b.add_mode("s", lambda x, m: 0, True)
    b.add_edge("a", "s", "g", lambda x, m: 1 / 0)
    a = b.build()
    with pytest.raises(ZeroDivisionError):
        a.step(None, a.initial_state(), 0.0, 0.1)


# --- behaviours, by hand ----------------------------------------------------------------------

def test_go_to_goal_velocity_eq_5_19():
    v0, a = 0.15, 40.0
    u = floornav.go_to_goal_velocity((0.0, 0.0), (2.0, 0.0), v0, a)
    assert u == pytest.approx((v0 * (1 - math.exp(-a * 4.0)), 0.0), abs=1e-15)
    e = (0.03, 0.04)  # |e| = 0.05: K = v0 (1 - exp(-a |e|^2)) / |e|
    k = v0 * (1 - math.exp(-a * 0.0025)) / 0.05
    assert floornav.go_to_goal_velocity((1.0, 1.0), (1.03, 1.04), v0, a) == pytest.approx(
        (k * e[0], k * e[1]), rel=1e-9)


def test_avoid_obstacle_velocity_eq_5_20():
    u = floornav.avoid_obstacle_velocity((0.0, 0.0), np.array([[0.2, 0.0]]), 0.15)
    assert u == pytest.approx((-0.15, 0.0))
    assert floornav.avoid_obstacle_velocity((0, 0), np.zeros((0, 2)), 0.15) == (0.0, 0.0)
    # Two points symmetric about the x axis push straight back along -x.
    u = floornav.avoid_obstacle_velocity((0, 0), [[0.1, 0.1], [0.1, -0.1]], 0.15)
    assert u[1] == pytest.approx(0.0, abs=1e-15) and u[0] == pytest.approx(-0.15)
    with pytest.raises(ValueError, match="shape"):
        floornav.avoid_obstacle_velocity((0, 0), [1, 2, 3], 0.15)


def test_blend_and_follow_boundary():
    assert floornav.blend_weight(0.03, 0.03, 0.15) == 1.0
    assert floornav.blend_weight(0.15, 0.03, 0.15) == 0.0
    assert floornav.blend_weight(0.09, 0.03, 0.15) == pytest.approx(0.5)  # smoothstep middle
    assert floornav.blend_velocities((1, 0), (0, 1), 0.25) == (0.75, 0.25)
    # away = (-1, 0): the obstacle is towards +x. Clockwise round it is the tangent
    # R(-pi/2)(-1, 0) = (0, 1); counter-clockwise R(+pi/2)(-1, 0) = (0, -1).
    assert floornav.follow_boundary_tangent((-1.0, 0.0), Turn.CLOCKWISE) == pytest.approx((0.0, 1.0))
    assert floornav.follow_boundary_tangent((-1.0, 0.0), "ccw") == pytest.approx((0.0, -1.0))
    # At the held clearance the velocity is the tangent at v0.
    u = floornav.follow_boundary_velocity((-1.0, 0.0), 0.08, Turn.CLOCKWISE, 0.08, 10.0, 0.15)
    assert u == pytest.approx((0.0, 0.15))
    # Eq. 5.23: the goal ahead and up, the obstacle ahead: clockwise (tangent (0, 1)).
    assert floornav.choose_turn((0.1, 0.05), (-0.1, 0.0)) == Turn.CLOCKWISE
    assert floornav.choose_turn((0.1, -0.05), (-0.1, 0.0)) == Turn.COUNTER_CLOCKWISE
    with pytest.raises(ValueError):
        floornav.choose_turn((1, 2, 3), (0, 0))


def test_make_navigation_input():
    p = floornav.NavigationParams()
    i = floornav.make_navigation_input((0, 0), (1, 0), np.array([[0.3, 0.0]]), 0.075, p)
    assert i.clearance == pytest.approx(0.3 - 0.075)
    assert i.obstacle_sensed and i.goal_distance == 1.0
    assert i.away == pytest.approx((-1.0, 0.0))
    assert i.u_ao == pytest.approx((-p.v0, 0.0))
    none = floornav.make_navigation_input((0, 0), (1, 0), None, 0.075, p)
    assert not none.obstacle_sensed and none.clearance == math.inf


def test_parameters_are_plain_objects():
    p = floornav.NavigationParams()
    assert "d_o" in p.fields and p.d_o == 0.12
    p.d_o = 0.2
    assert p.to_dict()["d_o"] == 0.2 and p.to_dict()["pid"]["kp"] == 4.0
    p.pid.kp = 2.0
    assert p.pid.kp == 2.0
    assert p != floornav.NavigationParams()
