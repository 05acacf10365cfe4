"""floornav.ParallelEnv: a fleet (with its people and forklifts) shaped like PettingZoo's Parallel
API, without depending on PettingZoo."""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from typing import Any, Optional, Union

import numpy as np

from . import _floornav
from ._floornav import RewardParams, Scenario
from ._spaces import Box, Dict
from ._vec_env import (RENDER_MODES, _floornav_module, _render_mode, _render_shape, _seed,
                       episode_draw, observation_space, reward_params)


class ParallelEnv:
    """Every robot of a fleet scenario (``robots:``) as an agent, stepped together in C++ with
    the scenario's people and forklifts moving as in ``floornav run``: PettingZoo's Parallel API
    shape.

    - ``possible_agents``: the robots' names, in the scenario's order; ``agents``: those still
      running. An agent whose run ends (reached, collision, timeout, stuck) leaves ``agents``
      after the step that ended it (that step still reports it).
    - ``reset(seed=None, options=None) -> (observations, infos)``; ``step(actions) ->
      (observations, rewards, terminations, truncations, infos)``, each a dict keyed by the
      agents that were in ``agents`` when the step began. ``actions`` maps every agent in
      ``agents`` to ``(v, omega)`` (a float array of shape (2,), a tuple or list of two numbers)
      or to None (its own controller, ``controller.kind``, drives it this step).
    - ``observation_space(agent)``, ``action_space(agent)``: that robot's spaces (Box/Dict, as
      VecEnv's single spaces); an observation holds ``t, pose, goal, goal_index, ranges,
      points`` (the layout of Simulation, VecEnv and Python controllers; docs/PYTHON.md).
    - ``terminations``: reached its last goal or collided; ``truncations``: timed out or stuck.
      ``infos[agent]``: ``status`` (a name of STATUS_NAMES), ``goals_reached``, ``progress``.
    - Rewards as VecEnv's default (RewardParams): progress to the goal, +goal per goal reached,
      -collision for a collision, -time * dt.
    - ``randomize`` as VecEnv's: each reset draws every robot's start and/or goal anew (robot
      after robot, clear of the robots drawn before it and of where the people and forklifts
      start).
    - Episode k after ``reset(seed=s)`` runs with ``sim.seed = s + k`` (sensor noise, the
      people's and forklifts' draws); ``reset()`` without a seed starts the next episode.

    Bad actions (a missing or unknown agent, an agent that has finished, a wrong shape or dtype,
    NaN): ``ValueError`` naming the agent and what is wrong; no robot moves.
    """

    metadata: dict = {"render_modes": list(RENDER_MODES), "name": "floornav_parallel_v0",
                      "is_parallelizable": True}

    def __init__(
        self,
        scenario: Union[Scenario, str, "os.PathLike[str]"],
        seed: int = 0,
        randomize: Optional[Mapping[str, Any]] = None,
        render_mode: Optional[str] = None,
        *,
        reward: Union[None, RewardParams, Mapping[str, float]] = None,
        render_shape: Sequence[int] = (384, 384),
    ) -> None:
        if isinstance(scenario, (str, os.PathLike)):
            scenario = _floornav_module().load_scenario(scenario)
        if not isinstance(scenario, Scenario):
            raise ValueError(f"ParallelEnv needs a Scenario or a path to one, got {scenario!r}")
        params = reward_params(reward)
        self.scenario: Scenario = scenario
        self.reward_params: RewardParams = params
        self.render_mode: Optional[str] = _render_mode(render_mode)
        self.render_shape: tuple = _render_shape(render_shape)
        self.randomize: Optional[dict] = None if randomize is None else dict(randomize)
        if randomize is not None and isinstance(randomize, Mapping) and \
                (randomize.get("floor") is not None or randomize.get("floor_seeds") is not None):
            raise ValueError("randomize['floor']: ParallelEnv steps the fleet of its scenario; for "
                             "another floor, make a ParallelEnv of floornav.shared_floor(template, seed)")
        self._core = _floornav._ParallelCore(scenario, episode_draw(randomize), params)
        self.possible_agents: list = list(self._core.names())
        self.agents: list = []
        self._seed: int = _seed(seed)
        self._episode = 0
        self._started = False
        robots = scenario.robots
        self._observation_spaces: dict = {}
        self._action_spaces: dict = {}
        for i, name in enumerate(self.possible_agents):
            self._observation_spaces[name] = observation_space([scenario], robot=i)
            r = robots[i]
            high = np.array([r["max_speed"], r["max_turn_rate"]])
            self._action_spaces[name] = Box(-high, high, (2,), np.float64)
        self.observation_spaces: dict = dict(self._observation_spaces)
        self.action_spaces: dict = dict(self._action_spaces)
        self.metadata = dict(ParallelEnv.metadata, render_fps=int(round(1.0 / scenario.dt)))

    @property
    def num_agents(self) -> int:
        return len(self.agents)

    @property
    def max_num_agents(self) -> int:
        return len(self.possible_agents)

    def observation_space(self, agent: str) -> Dict:
        """The space of ``agent``'s observation (the same object at every call)."""
        return self._observation_spaces[self._known(agent)]

    def action_space(self, agent: str) -> Box:
        """``(v, omega)`` within the robot's top speed and turn rate."""
        return self._action_spaces[self._known(agent)]

    def reset(self, seed: Optional[int] = None, options: Optional[dict] = None) -> tuple:
        """Starts an episode; returns ``(observations, infos)`` keyed by every agent."""
        if options:
            raise ValueError(f"reset(options=...): ParallelEnv takes no options, got {options!r} "
                             "(randomize is set when the env is made)")
        if seed is not None:
            self._seed = _seed(seed)
            self._episode = 0
        elif self._started:
            self._episode += 1
        obs, infos = self._core.reset(self._seed + self._episode)
        self._started = True
        self.agents = list(self.possible_agents)
        return obs, infos

    def step(self, actions: Mapping[str, Any]) -> tuple:
        """One step of every robot still running; see the class documentation."""
        if not self._started:
            raise ValueError("call reset() before step()")
        if not self.agents:
            raise ValueError("every agent has finished: call reset() to start another episode")
        out = self._core.step(actions)
        self.agents = list(self._core.live())
        return out

    def render(self) -> np.ndarray:
        """The floor now as uint8 ``(height, width, 3)``, drawn in C++: the world, every robot in
        its colour (body, heading, goal as a cross, this step's sensor returns), people and
        forklifts. Needs ``render_mode="rgb_array"``."""
        if self.render_mode != "rgb_array":
            raise ValueError("render() needs ParallelEnv(..., render_mode='rgb_array')")
        if not self._started:
            raise ValueError("call reset() before render()")
        return self._core.render(*self.render_shape)

    @property
    def result(self) -> Any:
        """The episode so far as a fleet's RunResult (summary, per-robot runs), as floornav.run
        gives it."""
        return self._core.result()

    @property
    def t(self) -> float:
        """Simulated time of the episode (s)."""
        return self._core.t

    def close(self) -> None:
        """Nothing to release (PettingZoo's signature)."""

    def _known(self, agent: str) -> str:
        if agent not in self._observation_spaces:
            raise ValueError(f"unknown agent {agent!r} (the agents are {self.possible_agents})")
        return agent
