"""floornav.Simulation: stepping from Python gives the run floornav.run gives; (v, omega)
commands go through the robot's saturation; one sensing per step; bad commands are ValueErrors."""

from __future__ import annotations

import math

import numpy as np
import pytest

import floornav
from conftest import SCENARIOS

NOISY = {"robot.sensors.noise": 0.01}  # sensor noise: a second sensing per step would show


def load(name="rectangle.yaml", **sets):
    return floornav.load_scenario(SCENARIOS / name, sets or None)


def test_the_observation_holds_the_contract_keys():
    sim = floornav.Simulation(load())
    obs = sim.reset()
    assert obs["t"] == 0.0 and obs["dt"] == 0.01
    assert obs["pose"].tolist() == [0.0, 0.0, 0.0] and obs["pose"].dtype == np.float64
    assert obs["goal"].tolist() == [2.4, 0.0]
    assert obs["status"] == "running"
    assert obs["ranges"].shape == (5,) and obs["ranges"].dtype == np.float64
    assert obs["points"].shape == (5, 2)  # one row per beam, as in VecEnv and ParallelEnv
    assert np.all(obs["ranges"] == 0.3)  # nothing within the QuickBot's IR range at the start
    assert obs["obstacles"].shape == (0, 2) and obs["sensed"].shape == (0, 2)
    assert obs["robot"].body_radius == 0.075 and obs["params"].epsilon == 0.05


def test_points_are_the_beams_returns_in_the_world_frame():
    sim = floornav.Simulation(load())
    for _ in range(480):  # 0.72 m towards the rectangle's face at x = 1.0
        obs = sim.step((0.15, 0.0))
    assert len(obs["points"]) > 0 and obs["ranges"][2] == pytest.approx(1.0 - 0.72 - 0.0664)
    hits = obs["ranges"] < 0.3
    assert len(obs["sensed"]) == hits.sum()
    # Per-beam points: the returns in beam order, the end of the range where nothing was seen.
    assert np.array_equal(obs["points"][hits], obs["sensed"])
    assert np.all(np.isfinite(obs["points"]))
    # Every sensed point lies on the rectangle's face x = 1.0 (|y| <= 0.5).
    assert np.allclose(obs["sensed"][:, 0], 1.0, atol=1e-9)
    # ... at its beam's range from the robot's sensor.
    x, y, th = obs["pose"]
    mounts = [s for s, h in zip(obs["robot"].sensors, hits) if h]
    for (mx, my, mth, _, _), r, p in zip(mounts, obs["ranges"][hits], obs["sensed"]):
        ox = x + math.cos(th) * mx - math.sin(th) * my
        oy = y + math.sin(th) * mx + math.cos(th) * my
        assert math.hypot(p[0] - ox, p[1] - oy) == pytest.approx(r, abs=1e-12)


def test_stepping_with_the_controller_equals_run():
    s = load()
    sim = floornav.Simulation(s)
    obs = sim.reset()
    while obs["status"] == "running":
        obs = sim.step()
    whole = floornav.run(s)
    assert obs["status"] == "reached" and sim.finished
    # The run's clock (obs["t"], what controllers read) adds dt up; reported times count steps
    # (sim_time = steps * dt, with no drift in the last digits).
    assert obs["t"] == pytest.approx(whole.summary["sim_time"], abs=1e-9)
    assert whole.summary["sim_time"] == whole.summary["steps"] * whole.summary["config"]["sim"]["dt"]
    assert list(obs["pose"]) == whole.summary["final_pose"]
    mine = dict(sim.result.summary)
    ref = dict(whole.summary)
    mine.pop("wall_time"), ref.pop("wall_time")
    assert mine == ref
    assert np.array_equal(sim.result.trajectory["x"], whole.trajectory["x"])


def poses(sim, steps, observe_times=0, command=None):
    out = []
    sim.reset()
    for _ in range(steps):
        for _ in range(observe_times):
            sim.observe()
        out.append(tuple(sim.step(command)["pose"]))
    return out


def test_observe_senses_once_per_step():
    s = load(**NOISY)
    plain = poses(floornav.Simulation(s), 1500)
    observed = poses(floornav.Simulation(s), 1500, observe_times=3)
    assert plain == observed  # observe() before a step shares its sensing (and its noise draw)
    other_seed = poses(floornav.Simulation(s.with_seed(2)), 1500)
    assert other_seed != plain  # the noise matters here, so a second draw would have shown


def test_observe_returns_the_same_sensing_until_the_next_step():
    sim = floornav.Simulation(load(**NOISY))
    sim.reset()
    for _ in range(450):
        sim.step()
    a, b = sim.observe(), sim.observe()
    assert np.array_equal(a["ranges"], b["ranges"]) and (a["ranges"] < 0.3).any()


def test_a_unicycle_command_goes_through_the_wheel_saturation():
    # The QuickBot's wheels top out at 13.61 rad/s: v = R w_max = 0.4424 m/s at most.
    sim = floornav.Simulation(load())
    sim.reset()
    obs = sim.step((10.0, 0.0))
    r = obs["robot"]
    v_max = r.wheel_radius * r.max_wheel_speed
    assert obs["pose"][0] == pytest.approx(v_max * 0.01, rel=1e-12)
    assert obs["pose"][1] == 0.0
    # Asking for both a turn and more speed than the wheels give: the turn is kept (eq. 5.11).
    sim.reset()
    obs = sim.step((10.0, 2.0))
    traj = sim.result.trajectory
    assert traj["omega"][-1] == pytest.approx(2.0, rel=1e-12)
    assert traj["v"][-1] == pytest.approx(v_max - 2.0 * r.track_width / 2, rel=1e-12)


def test_commands_equal_a_python_controller_giving_them():
    cmds = [(0.1, 0.5 * math.sin(k / 50)) for k in range(600)]
    sim = floornav.Simulation(load())
    sim.reset()
    stepped = [tuple(sim.step(c)["pose"]) for c in cmds]
    it = iter(cmds)
    r = floornav.run(load(**{"sim.t_max": 6.0}), lambda obs: next(it))
    t = r.trajectory
    assert stepped == list(zip(t["x"][1:], t["y"][1:], t["theta"][1:]))


def test_every_command_form():
    s = load()
    forms = [
        ((0.1, 0.2), floornav.Command.unicycle(0.1, 0.2)),
        ([0.1, 0.2], {"v": 0.1, "omega": 0.2}),
        (np.array([0.1, 0.2]), {"v": 0.1, "omega": 0.2}),
        ({"u": (0.1, 0.05)}, floornav.Command.velocity((0.1, 0.05))),
        ({"wheels": (3.0, 4.0)}, floornav.Command.wheels(3.0, 4.0)),
    ]
    for a, b in forms:
        sa, sb = floornav.Simulation(s), floornav.Simulation(s)
        pa = [sa.step(a)["pose"] for _ in range(50)]
        pb = [sb.step(b)["pose"] for _ in range(50)]
        assert np.array_equal(pa, pb), a
    sim = floornav.Simulation(s)
    obs = sim.step({"goal_reached": True})  # the only goal: the run ends reached
    assert obs["status"] == "reached" and sim.finished


@pytest.mark.parametrize("bad", [
    (float("nan"), 0.0), (0.1, float("inf")), {"u": (float("nan"), 0)},
    floornav.Command.unicycle(0.1, float("nan")),
    (1, 2, 3), (0.1,), "fast", {"v": 0.1}, {"v": 0.1, "omega": 0.0, "x": 1}, {"speed": 1},
    ("a", "b"), np.zeros(3), {"goal_reached": False}, (True, 0.0)])
def test_bad_commands_are_value_errors_and_change_nothing(bad):
    sim = floornav.Simulation(load())
    before = sim.reset()
    with pytest.raises(ValueError):
        sim.step(bad)
    assert np.array_equal(sim.observe()["pose"], before["pose"]) and sim.steps == 0
    sim.step((0.1, 0.0))  # still usable
    assert sim.steps == 1


def test_stepping_a_finished_simulation_is_a_value_error():
    sim = floornav.Simulation(load(**{"sim.t_max": 0.05}))
    obs = sim.reset()
    while obs["status"] == "running":
        obs = sim.step()
    assert obs["status"] == "timeout" and sim.steps == 5
    with pytest.raises(ValueError, match="the run has ended .timeout"):
        sim.step()
    with pytest.raises(ValueError):
        sim.step((0.1, 0.0))
    assert sim.reset()["status"] == "running" and sim.steps == 0


def test_the_final_observation_is_sensed_where_the_robot_stopped():
    # Without the safety layer, so that the robot can drive into the rectangle.
    sim = floornav.Simulation(load(**{"robot.start": [0.85, 0.0, 0.0], "controller.safety": "off"}))
    obs = sim.reset()
    while obs["status"] == "running":
        obs = sim.step((0.2, 0.0))  # straight into the rectangle
    assert obs["status"] == "collision"
    x = obs["pose"][0]
    front = obs["ranges"][2]  # the front IR sensor, 0.0664 m ahead of the centre
    assert front == pytest.approx(max(0.04, 1.0 - (x + 0.0664)), abs=1e-9)


def test_reset_with_a_seed_and_the_mode_property():
    s = load(**NOISY)
    sim = floornav.Simulation(s)
    a = poses(sim, 800)
    sim.reset(seed=7)
    b = [tuple(sim.step()["pose"]) for _ in range(800)]
    c = poses(floornav.Simulation(s.with_seed(7)), 800)
    assert b == c and a != b
    assert sim.mode in ("go_to_goal", "follow_boundary_cw", "follow_boundary_ccw", "avoid_obstacle")


def test_the_safety_layer_stops_a_command_short_of_the_rectangle():
    # The same command straight at the rectangle's face at x = 1.0, the safety layer on (the
    # default): the robot stops 1 cm (its margin) short and never touches; the run ends stuck.
    sim = floornav.Simulation(load(**{"robot.start": [0.85, 0.0, 0.0]}))
    obs = sim.reset()
    while obs["status"] == "running":
        obs = sim.step((0.2, 0.0))
    assert obs["status"] == "stuck"
    assert obs["pose"][0] + 0.075 == pytest.approx(1.0 - 0.01, abs=2e-3)
    assert sim.result.summary["min_clearance"] >= 0.01 - 1e-9
    assert sim.result.summary["safety_time"] > 0


def test_a_copy_and_a_pickle_step_exactly_as_the_original():
    import copy
    import pickle

    s = load(**NOISY)
    sim = floornav.Simulation(s)
    sim.reset(seed=4)
    for k in range(300):
        sim.step() if k % 2 else sim.step((0.1, 0.3))
    twins = [sim.copy(), copy.copy(sim), copy.deepcopy(sim), pickle.loads(pickle.dumps(sim))]
    for twin in twins:
        assert twin.steps == sim.steps == 300 and twin.seed == 4
        assert np.array_equal(twin.observe()["ranges"], sim.observe()["ranges"])
    mine = [tuple(sim.step()["pose"]) for _ in range(400)]
    for twin in twins:
        assert [tuple(twin.step()["pose"]) for _ in range(400)] == mine
    # Independent: stepping a copy moves only the copy.
    c = sim.copy()
    c.step((0.2, 0.0))
    assert c.steps == sim.steps + 1


def test_simulation_takes_a_path_and_refuses_fleets():
    sim = floornav.Simulation(SCENARIOS / "rectangle.yaml")
    assert sim.reset()["goal"].tolist() == [2.4, 0.0]
    with pytest.raises(floornav.InputError, match="ParallelEnv"):
        floornav.Simulation(SCENARIOS / "crowd" / "factory_people.yaml")
    with pytest.raises(floornav.InputError, match="ParallelEnv"):
        floornav.VecEnv(SCENARIOS / "crowd" / "factory_people.yaml", 2)
