"""floornav.ParallelEnv: a fleet among people and forklifts in PettingZoo's Parallel API shape.
The conformance checks mirror PettingZoo's parallel_api_test (agents, dict keys, spaces that
contain what is returned, agents leaving when done, seeding determinism) without PettingZoo; the
physics is `floornav run`'s; bad actions are ValueErrors that move nothing."""

from __future__ import annotations

import copy

import numpy as np
import pytest

import floornav
from conftest import SCENARIOS

FACTORY = SCENARIOS / "crowd" / "factory_people.yaml"  # 6 robots, 10 people, 2 forklifts


def factory(**sets):
    return floornav.load_scenario(FACTORY, {"sim.t_max": 1.0, **sets})


TWO = """
name: two
world: {bounds: [-1, -1, 4, 1]}
robot: {preset: quickbot}
robots:
  - {name: near, start: [0, 0.5, 0], goals: [[0.3, 0.5]]}
  - {name: far, start: [0, -0.5, 0], goals: [[3.5, -0.5]]}
controller: {kind: hybrid}
sim: {dt: 0.01, t_max: 30}
"""


def check_step_keys(env, before, out):
    obs, rewards, terms, truncs, infos = out
    for d in out:
        assert set(d) == set(before)  # every agent live when the step began, no other
    for a in before:
        assert env.observation_space(a).contains(obs[a]), a
        assert isinstance(rewards[a], float) and np.isfinite(rewards[a])
        assert isinstance(terms[a], bool) and isinstance(truncs[a], bool)
        assert (terms[a] or truncs[a]) == (a not in env.agents)
        assert infos[a]["status"] in floornav.STATUS_NAMES


def test_the_parallel_api_shape():
    env = floornav.ParallelEnv(factory(), seed=3)
    assert env.possible_agents == [f"amr{i}" for i in range(6)]
    assert env.agents == [] and env.max_num_agents == 6
    obs, infos = env.reset(seed=3)
    assert env.agents == env.possible_agents and env.num_agents == 6
    assert set(obs) == set(infos) == set(env.agents)
    for a in env.agents:
        assert env.observation_space(a) is env.observation_space(a)  # cached, as PettingZoo asks
        assert env.action_space(a).shape == (2,)
        assert env.observation_space(a).contains(obs[a])
        assert set(obs[a]) == {"t", "pose", "goal", "goal_index", "ranges", "points"}
        assert obs[a]["ranges"].shape == (16,) and obs[a]["points"].shape == (16, 2)
        env.action_space(a).seed(7)
    steps = 0
    while env.agents:
        before = list(env.agents)
        out = env.step({a: env.action_space(a).sample() for a in env.agents})
        check_step_keys(env, before, out)
        steps += 1
    assert steps == 100  # t_max = 1 s of 0.01 s steps: all time out together
    with pytest.raises(ValueError, match="call reset"):
        env.step({})


def test_the_same_seed_gives_the_same_episode():
    def episode(seed):
        env = floornav.ParallelEnv(factory(), randomize={"start": "free", "goal": "free"})
        obs, _ = env.reset(seed=seed)
        rng = np.random.default_rng(0)
        poses = [np.array([obs[a]["pose"] for a in env.agents])]
        for _ in range(40):
            obs, rewards, *_ = env.step({a: rng.uniform(-0.1, 0.1, 2) for a in env.agents})
            poses.append(np.array([obs[a]["pose"] for a in obs]))
        return np.array(poses)

    a, b, c = episode(5), episode(5), episode(6)
    assert np.array_equal(a, b) and not np.array_equal(a[0], c[0])


def test_controllers_drive_as_in_floornav_run():
    s = factory(**{"sim.t_max": 3.0})
    env = floornav.ParallelEnv(s)
    env.reset(seed=s.seed)
    while env.agents:
        env.step({a: None for a in env.agents})
    whole = dict(floornav.run(s).summary, wall_time=0)
    mine = dict(env.result.summary, wall_time=0)
    assert mine == whole  # every robot's path, the people's and forklifts' statistics, ...
    assert len(mine["robots"]) == 6 and mine["crowd"]


def test_an_agent_leaves_when_done_and_cannot_be_stepped():
    env = floornav.ParallelEnv(floornav.parse_scenario(TWO))
    env.reset()
    left_at = None
    for k in range(1000):
        before = list(env.agents)
        obs, rewards, terms, truncs, infos = env.step({a: None for a in env.agents})
        if "near" not in env.agents:
            left_at = k
            assert terms["near"] and infos["near"]["status"] == "reached"
            assert rewards["near"] > 0.5  # the goal's +1
            assert before == ["near", "far"]
            break
    assert left_at is not None and env.agents == ["far"]
    t = env.t
    with pytest.raises(ValueError, match="'near'.*finished"):
        env.step({"near": (0.1, 0.0), "far": (0.1, 0.0)})
    assert env.t == t  # nothing moved
    obs, *_ = env.step({"far": (0.1, 0.0)})
    assert set(obs) == {"far"}


@pytest.mark.parametrize("bad, match", [
    ({"amr0": (0.1, 0.0)}, "no entry for agent 'amr1'"),
    (dict({f"amr{i}": None for i in range(6)}, ghost=(0, 0)), "unknown agent 'ghost'"),
    (dict({f"amr{i}": None for i in range(6)}, amr2=(0.1, float("nan"))), "amr2.*not finite"),
    (dict({f"amr{i}": None for i in range(6)}, amr3=np.zeros(3)), "amr3.*shape"),
    (dict({f"amr{i}": None for i in range(6)}, amr4=np.zeros(2, dtype=np.int64)), "amr4.*dtype"),
    (dict({f"amr{i}": None for i in range(6)}, amr5="fast"), "amr5"),
    (dict({f"amr{i}": None for i in range(6)}, amr0=(True, 0.0)), "amr0.*numbers"),
    ([(0.1, 0.0)] * 6, "dict"),
])
def test_bad_actions_are_value_errors_that_move_nothing(bad, match):
    env = floornav.ParallelEnv(factory())
    obs, _ = env.reset()
    with pytest.raises(ValueError, match=match):
        env.step(bad)
    assert env.t == 0.0
    after, *_ = env.step({a: (0.0, 0.0) for a in env.agents})
    assert np.array_equal(after["amr0"]["pose"], obs["amr0"]["pose"])


def test_unknown_agents_in_space_queries_and_options_are_value_errors():
    env = floornav.ParallelEnv(factory())
    with pytest.raises(ValueError, match="unknown agent"):
        env.observation_space("nobody")
    with pytest.raises(ValueError, match="options"):
        env.reset(options={"randomize": {}})
    with pytest.raises(ValueError, match="reset"):
        env.step({})


def test_people_and_forklifts_are_sensed():
    # A person 0.125 m ahead of a lone robot's body: Simulation, VecEnv and ParallelEnv see it.
    text = """
name: person-ahead
world: {bounds: [-1, -1, 3, 1]}
robot: {preset: quickbot}
robots: [{name: r, start: [0, 0, 0], goals: [[2.5, 0]]}]
people: [{name: p, start: [0.4, 0], waypoints: [[0.41, 0]], speed: 0.01, radius: 0.2}]
controller: {kind: hybrid}
sim: {dt: 0.01, t_max: 5}
"""
    s = floornav.parse_scenario(text)
    sim_obs = floornav.Simulation(s).reset()
    assert sim_obs["ranges"][2] < 0.3
    vec_obs, _ = floornav.VecEnv(s, 2).reset()
    assert np.array_equal(vec_obs["ranges"][0], sim_obs["ranges"])
    par_obs, _ = floornav.ParallelEnv(s).reset()
    assert np.array_equal(par_obs["r"]["ranges"], sim_obs["ranges"])
