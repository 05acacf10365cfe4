"""floornav.VecEnv: many copies of a scenario stepped together in C++, shaped like a Gymnasium
vector environment (without depending on Gymnasium)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any, Callable, Optional, Union

import numpy as np

from . import _floornav
from ._floornav import RewardParams, Scenario

#: The codes of ``info["status"]``: index -> name.
STATUS_NAMES: tuple = ("running", "reached", "collision", "timeout", "stuck")

RewardFn = Callable[[dict, Optional[np.ndarray], dict], Any]


class VecEnv:
    """``n_envs`` copies of ``scenario``'s robot, each alone in its world, stepped together in
    C++ on ``threads`` threads (None: all cores).

    The interface is Gymnasium's vector environment (``gymnasium.vector.VectorEnv``) without the
    dependency:

    - ``reset(seed=None)`` returns ``(obs, info)``;
    - ``step(actions)`` with a float array of shape ``(n_envs, 2)`` of (v, omega) in m/s and
      rad/s returns ``(obs, reward, terminated, truncated, info)``. The commands go through the
      same wheel mapping and saturation as the built-in controllers. ``actions=None`` lets every
      copy's own controller drive (the scenario's ``controller.kind``).

    ``obs`` is a dict of arrays, each with leading dimension ``n_envs``: ``t`` (s), ``pose``
    (x, y, theta), ``goal`` (x, y: the current goal), ``goal_index``, ``ranges`` (n_envs, beams)
    in metres, one per beam of every sensor, and ``points`` (n_envs, beams, 2): each beam's
    return in the world frame, NaN where the beam saw nothing (range at its maximum).

    ``terminated``: the run reached its last goal or collided; ``truncated``: it timed out
    (``sim.t_max``) or was stuck. **Autoreset is "same-step"** (Gymnasium's
    ``AutoresetMode.SAME_STEP``, as Stable-Baselines3 does): a copy whose run ended in this step
    is restarted at once; ``obs`` holds its new episode's first observation, and
    ``info["final_obs"]`` (a dict of arrays like ``obs``; rows where ``info["_final_obs"]`` is
    True) holds the observation where it ended. Reward, terminated and truncated are those of
    the step that ended it.

    **Reward.** By default, per copy and step (:class:`RewardParams`)::

        reward = progress * (d_before - d_after)      # metres gained towards the goal
               + goal * (goals reached in the step)   # +1 per goal
               - collision * (the step collided)      # -1
               - time * dt                            # 0 by default

    where d is the distance to the goal that was current when the step began. Replace it with
    ``reward=RewardParams(...)``, a dict of those four weights, or a callable
    ``reward(obs, actions, info) -> array (n_envs,)`` called after every step with the
    observation where each copy stands after the step (the final one for copies that ended,
    before their reset), the actions, and ``info`` (``status``, ``progress``,
    ``goal_distance``, ``goals_reached``, ``default_reward``).

    ``info`` also has ``status`` (codes into :data:`STATUS_NAMES`), ``progress`` (m),
    ``goal_distance`` (m, to the current goal), ``goals_reached`` (this episode),
    ``episode_return`` and ``episode_steps`` (so far; for copies that ended, their totals).

    Seeds: episode e of copy i draws its sensor noise with seed ``seed + i + e * n_envs``.
    With ``copy=False`` the same observation arrays are reused (and overwritten) by every step.

    ``scenario`` may be a list of scenarios (one per copy; ``n_envs`` then defaults to its
    length), all with the same number of sensors.
    """

    metadata: dict = {"autoreset_mode": "same-step", "render_modes": []}

    def __init__(
        self,
        scenario: Union[Scenario, Sequence[Scenario]],
        n_envs: Optional[int] = None,
        seed: int = 0,
        *,
        threads: Optional[int] = None,
        reward: Union[None, RewardParams, Mapping[str, float], RewardFn] = None,
        copy: bool = True,
    ) -> None:
        if isinstance(scenario, Scenario):
            if n_envs is None:
                raise ValueError("VecEnv(scenario, n_envs): how many copies?")
            scenarios = [scenario] * _positive(n_envs, "n_envs")
        else:
            scenarios = list(scenario)
            if not scenarios or not all(isinstance(s, Scenario) for s in scenarios):
                raise ValueError("VecEnv needs a Scenario or a non-empty list of Scenarios")
            if n_envs is not None and n_envs != len(scenarios):
                raise ValueError(f"n_envs={n_envs} but {len(scenarios)} scenarios were given")
        if threads is not None:
            _positive(threads, "threads")
        self._reward_fn: Optional[RewardFn] = None
        if reward is None:
            params = RewardParams()
        elif isinstance(reward, RewardParams):
            params = reward
        elif isinstance(reward, Mapping):
            params = RewardParams(**reward)
        elif callable(reward):
            params = RewardParams()
            self._reward_fn = reward
        else:
            raise ValueError(f"reward is RewardParams, a dict of its weights or a callable, got {reward!r}")
        self.reward_params: RewardParams = params
        self.scenarios: list = scenarios
        self._core = _floornav._VecCore(scenarios, threads or 0, copy, params)
        self.num_envs: int = self._core.n_envs
        self.seed: int = _seed(seed)
        self._started = False
        self._return = np.zeros(self.num_envs)
        self._steps = np.zeros(self.num_envs, dtype=np.int64)
        robot = scenarios[0].robots[0]
        #: Per-copy action bounds: |v| <= the robot's top speed, |omega| <= its top turn rate.
        self.action_low: np.ndarray = np.array([-robot["max_speed"], -robot["max_turn_rate"]])
        self.action_high: np.ndarray = np.array([robot["max_speed"], robot["max_turn_rate"]])
        #: Shapes of one copy's observation entries (without the leading n_envs).
        beams = self._core.beam_count
        self.single_observation_shapes: dict = {
            "t": (), "pose": (3,), "goal": (2,), "goal_index": (), "ranges": (beams,),
            "points": (beams, 2),
        }
        self.robot_name: str = robot["name"]

    @property
    def n_envs(self) -> int:
        return self.num_envs

    @property
    def threads(self) -> int:
        """Threads stepping the copies (1 when a Python controller drives them)."""
        return self._core.threads

    def reset(self, seed: Optional[int] = None, options: Optional[dict] = None) -> tuple:
        """Starts every copy afresh (episode 0 of copy i: seed ``seed + i``; without ``seed``,
        the one given before) and returns ``(obs, info)``."""
        del options  # Gymnasium's signature
        if seed is not None:
            self.seed = _seed(seed)
        obs = self._core.reset(self.seed)
        self._started = True
        self._return[:] = 0.0
        self._steps[:] = 0
        info = {"status": self._core.statuses(), "seeds": np.array(self._core.seeds(), dtype=np.uint64)}
        return obs, info

    def step(self, actions: Optional[np.ndarray]) -> tuple:
        """One step of every copy; see the class documentation."""
        if not self._started:
            raise ValueError("call reset() before step()")
        if self._reward_fn is None:
            obs, reward, terminated, truncated, info = self._core.step(actions, True)
        else:
            obs, reward, terminated, truncated, info = self._core.step(actions, False)
            # A copy of the dict: the function may change it; the arrays are the step's own.
            custom = np.asarray(self._reward_fn(dict(obs), actions, info), dtype=np.float64)
            if custom.shape != (self.num_envs,):
                raise ValueError(f"the reward function returned shape {custom.shape}, not ({self.num_envs},)")
            reward = custom
            final = self._core.reset_ended(obs, terminated, truncated)
            if final is not None:
                info["final_obs"] = final
                info["_final_obs"] = self._core.ended_mask(terminated, truncated)
        self._return += reward
        self._steps += 1
        info["episode_return"] = self._return.copy()
        info["episode_steps"] = self._steps.copy()
        ended = terminated | truncated
        if ended.any():
            self._return[ended] = 0.0
            self._steps[ended] = 0
        return obs, reward, terminated, truncated, info

    def close(self) -> None:
        """Nothing to release (Gymnasium's signature)."""

    def __repr__(self) -> str:
        return (f"<floornav.VecEnv {self.num_envs} x '{self.scenarios[0].name}', "
                f"{self._core.beam_count} beams, {self.threads} threads>")


def _positive(n: Any, what: str) -> int:
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise ValueError(f"{what} must be a positive integer, got {n!r}")
    return int(n)


def _seed(seed: Any) -> int:
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
        raise ValueError(f"seed must be a non-negative integer, got {seed!r}")
    return int(seed)
