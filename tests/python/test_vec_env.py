"""floornav.VecEnv: every copy runs exactly as a Simulation with its seed, on any number of
threads; same-step autoreset with the final observation in info; the documented reward."""

from __future__ import annotations

import numpy as np
import pytest

import floornav
from conftest import SCENARIOS

NOISY = {"robot.sensors.noise": 0.01}


def load(name="rectangle.yaml", **sets):
    return floornav.load_scenario(SCENARIOS / name, {**NOISY, **sets})


def actions(n, k):
    """Varied (v, omega) per copy and step."""
    i = np.arange(n)[:, None]
    return np.hstack([0.05 + 0.02 * (i % 5), 0.6 * np.sin(0.05 * k + i)])


def test_shapes_and_types():
    env = floornav.VecEnv(load(), 6, seed=10)
    obs, info = env.reset()
    assert env.num_envs == env.n_envs == 6
    shapes = {k: v.shape for k, v in obs.items()}
    assert shapes == {"t": (6,), "pose": (6, 3), "goal": (6, 2), "goal_index": (6,),
                      "ranges": (6, 5), "points": (6, 5, 2)}
    assert {k: (6,) + s for k, s in env.single_observation_shapes.items()} == shapes
    assert info["seeds"].tolist() == list(range(10, 16))
    assert (info["status"] == 0).all()
    o, r, te, tr, info = env.step(np.zeros((6, 2)))
    assert r.shape == te.shape == tr.shape == (6,)
    assert r.dtype == np.float64 and te.dtype == tr.dtype == np.bool_
    assert {"status", "progress", "goal_distance", "goals_reached", "episode_return",
            "episode_steps"} <= set(info)
    assert env.action_high[0] == pytest.approx(0.4424, abs=1e-4)
    assert np.all(o["t"] == 0.01)


def test_each_copy_equals_a_simulation_with_its_seed():
    s = load()
    n, steps = 5, 700
    env = floornav.VecEnv(s, n, seed=40, threads=2)
    obs, _ = env.reset()
    sims = [floornav.Simulation(s.with_seed(40 + i)) for i in range(n)]
    for sim, i in zip(sims, range(n)):
        o = sim.reset()
        assert np.array_equal(o["ranges"], obs["ranges"][i])
    for k in range(steps):
        a = actions(n, k)
        obs, _, te, tr, _ = env.step(a)
        assert not (te | tr).any()
        for i, sim in enumerate(sims):
            o = sim.step(tuple(a[i]))
            assert np.array_equal(o["pose"], obs["pose"][i]), (k, i)
            assert np.array_equal(o["ranges"], obs["ranges"][i])
    # Per-beam points: Simulation's, the returns in beam order (the end of the range where a
    # beam saw nothing).
    for i, sim in enumerate(sims):
        o = sim.observe()
        assert np.array_equal(obs["points"][i], o["points"])
        hit = o["ranges"] < 0.3
        assert np.array_equal(obs["points"][i][hit], o["sensed"])
    assert np.all(np.isfinite(obs["points"]))
    assert any(len(sim.observe()["sensed"]) for sim in sims)  # the test saw obstacles


def test_the_same_run_on_one_thread_or_two():
    s = load()
    runs = []
    for threads in (1, 2):
        env = floornav.VecEnv(s, 64, seed=3, threads=threads)
        assert env.threads == threads
        obs, _ = env.reset()
        trace = []
        for k in range(300):
            obs, r, te, tr, info = env.step(actions(64, k))
            trace.append((obs["pose"].copy(), obs["ranges"].copy(), r.copy()))
        runs.append(trace)
    for (pa, ra, wa), (pb, rb, wb) in zip(*runs):
        assert np.array_equal(pa, pb) and np.array_equal(ra, rb) and np.array_equal(wa, wb)


def test_controllers_drive_when_actions_are_none():
    s = load()
    env = floornav.VecEnv(s, 3, seed=1)
    env.reset()
    sims = [floornav.Simulation(s.with_seed(1 + i)) for i in range(3)]
    for sim in sims:
        sim.reset()
    for _ in range(500):
        obs, *_ = env.step(None)
        for i, sim in enumerate(sims):
            assert np.array_equal(sim.step()["pose"], obs["pose"][i])


def test_same_step_autoreset_puts_the_final_observation_in_info():
    env = floornav.VecEnv(load(**{"sim.t_max": 0.5}), 4, seed=0)
    obs, _ = env.reset()
    a = np.tile([0.1, 0.0], (4, 1))
    for k in range(49):
        obs, r, te, tr, info = env.step(a)
        assert "final_obs" not in info
    obs, r, te, tr, info = env.step(a)  # t = 0.5: every copy times out
    assert tr.all() and not te.any()
    assert (info["status"] == floornav.STATUS_NAMES.index("timeout")).all()
    assert info["_final_obs"].all()
    final = info["final_obs"]
    assert np.allclose(final["t"], 0.5)
    assert np.allclose(final["pose"][:, 0], 0.05)  # 0.1 m/s for 0.5 s
    assert np.all(obs["t"] == 0.0) and np.all(obs["pose"] == 0.0)  # restarted at once
    assert info["episode_steps"].tolist() == [50] * 4
    assert info["episode_return"] == pytest.approx([0.05] * 4)  # progress along x towards (2.4, 0)
    # The next episode draws new sensor noise: episode e of copy i has seed seed + i + e n.
    obs, r, te, tr, info = env.step(a)
    assert info["episode_steps"].tolist() == [1] * 4 and not (te | tr).any()


def test_copies_that_end_are_restarted_alone():
    s = load(**{"robot.start": [0.85, 0.0, 0.0], "controller.safety": "off"})
    env = floornav.VecEnv(s, 3, seed=0)
    env.reset()
    a = np.array([[0.3, 0.0], [-0.1, 0.0], [0.0, 0.0]])  # copy 0 drives into the rectangle
    ended_at = None
    for k in range(200):
        obs, r, te, tr, info = env.step(a)
        if te[0]:
            ended_at = k
            break
        assert not te[1:].any()
    assert ended_at is not None
    assert info["status"][0] == floornav.STATUS_NAMES.index("collision")
    assert info["_final_obs"].tolist() == [True, False, False]
    assert info["final_obs"]["pose"][0, 0] > 0.85 and np.all(info["final_obs"]["pose"][1:] == 0)
    assert obs["pose"][0].tolist() == [0.85, 0.0, 0.0]  # copy 0 starts again
    assert obs["pose"][1, 0] < 0.85 and obs["t"][1] > 0  # the others go on


def test_the_default_reward():
    # Straight at the goal (2.4, 0) from (0.85, 0): progress is the distance driven, and the
    # collision with the rectangle's face at x = 1.0 costs 1.
    env = floornav.VecEnv(load(**{"robot.start": [0.85, 0.0, 0.0], "controller.safety": "off"}), 1, seed=0)
    obs, _ = env.reset()
    x0 = obs["pose"][0, 0]
    obs, r, te, tr, info = env.step(np.array([[0.1, 0.0]]))
    assert r[0] == pytest.approx(obs["pose"][0, 0] - x0, abs=1e-15)
    assert info["progress"][0] == r[0] and info["goal_distance"][0] == pytest.approx(2.4 - obs["pose"][0, 0])
    total = r[0]
    while not te[0]:
        obs, r, te, tr, info = env.step(np.array([[0.1, 0.0]]))
        total += r[0]
    x_end = info["final_obs"]["pose"][0, 0]
    assert r[0] == pytest.approx((info["final_obs"]["pose"][0, 0] - 0.85) - (total - r[0]) - 1.0)
    assert total == pytest.approx((x_end - 0.85) - 1.0)
    assert info["episode_return"][0] == pytest.approx(total)


def test_reaching_the_goal_earns_the_goal_bonus():
    s = load(**{"goal": [0.3, 0.0]})
    env = floornav.VecEnv(s, 1, seed=0, reward={"progress": 0.0, "goal": 5.0, "collision": 1.0})
    env.reset()
    rewards = []
    te = [False]
    while not te[0]:
        _, r, te, tr, info = env.step(np.array([[0.15, 0.0]]))
        rewards.append(r[0])
    assert rewards[-1] == 5.0 and sum(rewards) == 5.0
    assert info["status"][0] == floornav.STATUS_NAMES.index("reached")


def test_time_penalty_and_reward_params():
    p = floornav.RewardParams(progress=0.0, goal=0.0, collision=0.0, time=2.0)
    env = floornav.VecEnv(load(), 2, reward=p)
    env.reset()
    _, r, *_ = env.step(np.zeros((2, 2)))
    assert r.tolist() == [-0.02, -0.02]


def test_a_custom_reward_function_sees_the_final_observation():
    seen = {}

    def reward(obs, actions, info):
        seen["t"] = obs["t"].copy()
        seen["actions"] = actions
        return -obs["pose"][:, 0]

    env = floornav.VecEnv(load(**{"sim.t_max": 0.05}), 2, reward=reward)
    env.reset()
    a = np.tile([0.2, 0.0], (2, 1))
    for _ in range(5):
        obs, r, te, tr, info = env.step(a)
    assert tr.all()
    assert np.allclose(seen["t"], 0.05)  # the observation where they ended, before the reset
    assert seen["actions"] is a
    assert r == pytest.approx(-info["final_obs"]["pose"][:, 0])
    assert np.all(obs["t"] == 0)

    env = floornav.VecEnv(load(), 2, reward=lambda o, a, i: np.zeros(3))
    env.reset()
    with pytest.raises(ValueError, match="shape"):
        env.step(np.zeros((2, 2)))


@pytest.mark.parametrize("bad, match", [
    (np.zeros((3, 2)), "shape"), (np.zeros((4, 3)), "shape"), (np.zeros(8), "shape"),
    (np.zeros((4, 2), dtype=np.int64), "dtype"), (np.zeros((4, 2), dtype=bool), "dtype"),
    (np.array([["a", "b"]] * 4), "dtype"), ([[0, 0]] * 4, "dtype"),
    (np.array([[0.1, 0.0]] * 3 + [[np.nan, 0.0]]), "actions\\[3\\]"),
    (np.array([[0.1, 0.0]] * 3 + [[0.0, np.inf]]), "not finite"),
])
def test_bad_actions_are_value_errors(bad, match):
    env = floornav.VecEnv(load(), 4)
    env.reset()
    with pytest.raises(ValueError, match=match):
        env.step(bad)
    obs, *_ = env.step(np.zeros((4, 2), dtype=np.float32))  # float32 is fine
    assert np.all(obs["t"] == 0.01)


def test_bad_set_ups_are_value_errors():
    s = load()
    with pytest.raises(ValueError, match="reset"):
        floornav.VecEnv(s, 2).step(np.zeros((2, 2)))
    with pytest.raises(ValueError):
        floornav.VecEnv(s, 0)
    with pytest.raises(ValueError):
        floornav.VecEnv(s)
    with pytest.raises(ValueError):
        floornav.VecEnv(s, 2, seed=-1)
    with pytest.raises(ValueError, match="fleet"):
        floornav.VecEnv(floornav.load_scenario(SCENARIOS / "fleet_crossing.yaml"), 2)
    lidar = floornav.load_scenario(SCENARIOS / "coppeliasim_pioneer.yaml")
    with pytest.raises(ValueError, match="sensors"):
        floornav.VecEnv([s, lidar])


def test_a_list_of_scenarios_one_per_copy():
    a = load()
    b = load(**{"robot.start": [0.0, 0.5, 0.0]})
    env = floornav.VecEnv([a, b, a])
    obs, _ = env.reset()
    assert env.num_envs == 3
    assert obs["pose"][:, 1].tolist() == [0.0, 0.5, 0.0]


def test_copy_false_reuses_the_arrays():
    env = floornav.VecEnv(load(), 2, copy=False)
    o1, _ = env.reset()
    o2, *_ = env.step(np.zeros((2, 2)))
    assert o1["pose"] is o2["pose"]
    env = floornav.VecEnv(load(), 2)
    o1, _ = env.reset()
    o2, *_ = env.step(np.zeros((2, 2)))
    assert o1["t"][0] == 0.0 and o2["t"][0] == 0.01


def test_a_python_controller_drives_the_copies_on_one_thread():
    import threading

    seen = set()

    def steer(obs):
        seen.add(threading.get_ident())
        return (0.1, 0.2)

    s = load().with_controller(steer)
    env = floornav.VecEnv(s, 4, threads=2)
    assert env.threads == 1
    env.reset()
    for _ in range(10):
        obs, *_ = env.step(None)
    assert seen == {threading.get_ident()}
    sim = floornav.Simulation(s.with_seed(0))
    sim.reset()
    for _ in range(10):
        o = sim.step()
    assert np.array_equal(o["pose"], obs["pose"][0])


def test_a_reward_function_that_changes_its_dict_changes_nothing():
    def reward(obs, actions, info):
        obs["ranges"] = obs["ranges"][:, :1]  # replaces an entry of its own dict
        return np.ones(2)

    env = floornav.VecEnv(load(**{"sim.t_max": 0.02}), 2, reward=reward)
    env.reset()
    a = np.zeros((2, 2))
    env.step(a)
    obs, r, te, tr, info = env.step(a)  # both copies time out and restart
    assert tr.all() and obs["ranges"].shape == (2, 5) and np.all(obs["t"] == 0)
    assert r.tolist() == [1.0, 1.0]
    with pytest.raises(ValueError, match="not the array the last step returned"):
        env._core.reset_ended({k: v.copy() for k, v in obs.items()}, tr, tr)
