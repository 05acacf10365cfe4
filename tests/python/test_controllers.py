"""Controllers written in Python: callables and objects, every command form, modes and guards in
the summary and the log, fleets (one per robot), errors that propagate and write nothing."""

from __future__ import annotations

import math
import traceback

import numpy as np
import pytest

import floornav
from conftest import SCENARIOS


def load(name="rectangle.yaml", **sets):
    return floornav.load_scenario(SCENARIOS / name, sets or None)


def test_a_plain_function_drives_the_robot():
    seen = []

    def circle(obs):
        seen.append(obs)
        return (0.1, 0.5)

    r = floornav.run(load(**{"sim.t_max": 1.0}), circle, kind="circler")
    assert r.summary["steps"] == 100 and r.status == "timeout"
    assert r.summary["mode_time"] == {"circler": pytest.approx(1.0)}
    assert [o["t"] for o in seen[:3]] == pytest.approx([0.0, 0.01, 0.02])
    o = seen[-1]
    assert set(o) >= {"t", "dt", "pose", "goal", "ranges", "points", "obstacles", "sensed",
                      "status", "robot",
                      "params", "goal_index", "goal_count"}
    assert o["status"] == "running" and tuple(o["goal"]) == (2.4, 0.0)
    # the last observation is of the pose before the last step
    t = r.trajectory
    assert tuple(o["pose"]) == (t["x"][-2], t["y"][-2], t["theta"][-2])
    assert np.allclose(t["omega"][1:], 0.5) and np.allclose(t["v"][1:], 0.1)


def test_a_velocity_command_goes_through_the_heading_pid():
    # u straight along +y from heading 0: the PID turns the robot first (slow_when_turning).
    r = floornav.run(load(**{"sim.t_max": 0.5}), lambda obs: floornav.Command.velocity((0.0, 0.1)))
    t = r.trajectory
    kp = 4.0  # the QuickBot preset's heading gain
    assert t["omega"][1] == pytest.approx(kp * math.pi / 2)
    assert t["v"][1] == pytest.approx(0.0, abs=1e-12)  # cos(pi/2): turn before driving
    assert t["theta"][-1] > 1.0


def test_the_goal_reached_command_ends_the_route():
    def go(obs):
        if math.dist(obs["pose"][:2], obs["goal"]) < 0.05:
            return {"goal_reached": True}
        dx, dy = obs["goal"][0] - obs["pose"][0], obs["goal"][1] - obs["pose"][1]
        return {"u": (0.15 * dx / math.hypot(dx, dy), 0.15 * dy / math.hypot(dx, dy))}

    r = floornav.run(load(**{"goal": [0.5, 0.3]}), go)
    assert r.status == "reached" and r.summary["goals_reached"] == 1


class Supervisor:
    """Two modes with named guards; a transition is reported with its guard's name."""

    mode_names = ["drive", "turn"]
    guard_names = ["timer", "timer_done"]

    def __init__(self):
        self.resets = 0
        self.reset()

    def reset(self):
        self.resets += 1
        self.m = "drive"
        self.k = 0

    @property
    def mode(self):
        return self.m

    def decide(self, obs):
        self.k += 1
        guard = None
        if self.k % 50 == 0:
            self.m = "turn" if self.m == "drive" else "drive"
            guard = "timer" if self.m == "turn" else 1
        return floornav.Decision((0.1, 0.0) if self.m == "drive" else (0.0, 1.0), self.m, guard)


def test_modes_and_guards_reach_the_summary_and_the_log():
    ctl = Supervisor()
    r = floornav.run(load(**{"sim.t_max": 2.0}), ctl, kind="timer")
    assert r.mode_names == ["drive", "turn"]
    assert r.summary["mode_switches"] == 4  # at steps 50, 100, 150, 200
    assert [(tr["from"], tr["to"], tr["guard"]) for tr in r.transitions] == [
        ("drive", "turn", "timer"), ("turn", "drive", "timer_done"), ("drive", "turn", "timer"),
        ("turn", "drive", "timer_done")]
    assert r.transitions[0]["t"] == pytest.approx(0.5)
    assert set(r.trajectory["mode"].tolist()) == {"drive", "turn"}
    assert r.summary["mode_time"]["turn"] == pytest.approx(1.0)
    assert ctl.resets == 2  # constructed, then reset by the run


def test_reset_is_called_for_every_goal_of_a_route():
    ctl = Supervisor()

    def decide(obs):
        return {"goal_reached": True} if obs["goal_index"] < 2 else (0.1, 0.0)

    ctl.decide = decide
    r = floornav.run(load(**{"goals": [[0.2, 0], [0.3, 0], [0.4, 0]], "sim.t_max": 0.1}), ctl)
    assert r.summary["goals_reached"] == 2
    assert ctl.resets == 1 + 1 + 2  # made, run start, two goals


def test_a_factory_makes_one_controller_per_robot_of_a_fleet():
    made = []

    def factory(ctx):
        made.append((ctx["robot_index"], ctx["robot_name"], ctx["robot"].body_radius))
        target = None

        def decide(obs):
            gx, gy = obs["goal"]
            x, y, th = obs["pose"]
            err = math.atan2(gy - y, gx - x) - th
            err = math.atan2(math.sin(err), math.cos(err))
            return (0.1 * max(0.0, math.cos(err)), 3.0 * err)

        return decide

    s = load("fleet_crossing.yaml", **{"sim.t_max": 3.0})
    r = floornav.run(s, factory=factory, kind="p-steer")
    assert [m[0] for m in made] == [0, 1, 2, 3]
    assert len({m[1] for m in made}) == 4
    assert r.summary["fleet"]["robots"] == 4
    assert all(rob["status"] in ("timeout", "collision", "reached") for rob in r.summary["robots"])
    # Each robot steered at its own goal: every path got shorter to its goal.
    for rob, spec in zip(r.summary["robots"], s.robots):
        start = spec["start"][:2]
        goal = spec["goals"][0]
        assert math.dist(rob["final_pose"][:2], goal) < math.dist(start, goal)


class Boom(Exception):
    pass


def test_an_exception_propagates_with_its_traceback_and_writes_nothing(tmp_path):
    def failing_controller(obs):
        if obs["t"] > 1.0:
            raise Boom("sensor fusion diverged")
        return (0.1, 0.0)

    with pytest.raises(Boom, match="sensor fusion diverged") as e:
        floornav.run(load(), failing_controller, out=tmp_path / "out")
    frames = [f.name for f in e.traceback]
    assert "failing_controller" in frames
    assert "raise Boom" in "".join(traceback.format_exception(e.value))
    assert not (tmp_path / "out").exists()

    sim = floornav.Simulation(load().with_controller(failing_controller))
    sim.reset()
    with pytest.raises(Boom):
        for _ in range(200):
            sim.step()


@pytest.mark.parametrize("result, match", [
    (None, "a command is"), ("left", "a command is"), ((1.0, float("nan")), "not finite"),
    ({"v": 1.0}, "a command is"),
    (floornav.Decision((0.1, 0.0), mode="flying"), "not one of its mode_names"),
    (floornav.Decision((0.1, 0.0), mode=3), "mode 3"),
    (floornav.Decision((0.1, 0.0), guard="fired"), "not one of its guard_names"),
])
def test_a_bad_result_is_a_value_error(result, match):
    with pytest.raises(ValueError, match=match):
        floornav.run(load(), lambda obs: result)


def test_not_a_controller():
    with pytest.raises(TypeError):
        load().with_controller(42)
    with pytest.raises(ValueError):
        load().with_controller(lambda o: (0, 0), factory=lambda c: None)
    with pytest.raises(ValueError, match="factory returned None"):
        floornav.run(load(), factory=lambda ctx: None)


def test_navigation_input_equals_what_the_builtin_sees():
    inputs = []

    def spy(obs):
        inputs.append(floornav.navigation_input(obs))
        return floornav.Command.velocity(inputs[-1].u_gtg)

    floornav.run(load(**{"sim.t_max": 6.0}), spy)
    i = inputs[-1]
    assert i.obstacle_sensed and i.clearance < 0.3
    assert i.goal_distance == pytest.approx(math.dist(i.x, i.goal))
    p = floornav.NavigationParams()
    assert i.u_gtg == floornav.go_to_goal_velocity(i.x, i.goal, p.v0, p.gtg_a)


def test_a_python_controller_run_ends_reached_on_the_goal():
    # The docs' `steer`: it never asks to stop, yet within controller.epsilon the goal is
    # reached, as with the built-in kinds and with commands given to Simulation.step.
    s = floornav.parse_scenario("""
name: open
world: {bounds: [-1, -1, 2, 1]}
robot: {preset: quickbot, start: [0, 0, 0]}
goal: [1.0, 0.3]
controller: {kind: hybrid}
sim: {dt: 0.01, t_max: 30}
""")

    def steer(obs):
        gx, gy = obs["goal"]
        x, y, th = obs["pose"]
        err = math.atan2(gy - y, gx - x) - th
        return (0.1, 2.0 * math.atan2(math.sin(err), math.cos(err)))

    r = floornav.run(s, steer, kind="p-steer")
    assert r.status == "reached" and r.summary["sim_time"] < 15.0
    end = np.array([r.trajectory["x"][-1], r.trajectory["y"][-1]])
    assert np.linalg.norm(end - [1.0, 0.3]) < s.params.epsilon + 0.1 * 0.01
    obs = floornav.Simulation(s.with_controller(steer)).reset()
    assert obs["status"] == "running"  # it does not start reached
