"""floornav.VecEnv: many copies of a scenario stepped together in C++, shaped like a Gymnasium
vector environment (without depending on Gymnasium)."""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from typing import Any, Callable, Optional, Union

import numpy as np

from . import _floornav
from ._floornav import RewardParams, Scenario
from ._spaces import Box, Dict, batch_space

#: The codes of ``info["status"]``: index -> name.
STATUS_NAMES: tuple = ("running", "reached", "collision", "timeout", "stuck")

RewardFn = Callable[[dict, Optional[np.ndarray], dict], Any]

#: The render modes of VecEnv and ParallelEnv.
RENDER_MODES: tuple = ("rgb_array",)


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

    ``randomize`` (see :func:`episode_draw` and :func:`floor_draw`) draws per episode, from its
    seed: the start and goal (``"start"``, ``"goal"``: ``"free"`` or a region), and with
    ``"floor": "factory_floor"`` a generated floor (``floornav.factory_floor(scenario, f)``, the
    scenario being the template) from ``"floor_seeds"`` (a range or a sequence; absent: any
    seed). ``info["floor_seeds"]`` then names the floor each copy is on, at reset and every step.
    """

    metadata: dict = {"autoreset_mode": "same-step", "render_modes": list(RENDER_MODES)}

    def __init__(
        self,
        scenario: Union[Scenario, str, "os.PathLike[str]", Sequence[Scenario]],
        n_envs: Optional[int] = None,
        seed: int = 0,
        randomize: Optional[Mapping[str, Any]] = None,
        render_mode: Optional[str] = None,
        *,
        threads: Optional[int] = None,
        reward: Union[None, RewardParams, Mapping[str, float], RewardFn] = None,
        copy: bool = True,
        render_shape: Sequence[int] = (256, 256),
    ) -> None:
        if isinstance(scenario, (str, os.PathLike)):
            scenario = _floornav_module().load_scenario(scenario)
        if isinstance(scenario, Scenario):
            if n_envs is None:
                raise ValueError("VecEnv(scenario, n_envs): how many copies?")
            scenarios = [scenario] * _positive(n_envs, "n_envs", MAX_ENVS)
        else:
            scenarios = list(scenario)
            if not scenarios or not all(isinstance(s, Scenario) for s in scenarios):
                raise ValueError("VecEnv needs a Scenario or a non-empty list of Scenarios")
            if n_envs is not None and n_envs != len(scenarios):
                raise ValueError(f"n_envs={n_envs} but {len(scenarios)} scenarios were given")
            if len(scenarios) > MAX_ENVS:
                raise ValueError(f"at most {MAX_ENVS} scenarios, got {len(scenarios)}")
        if threads is not None:
            _positive(threads, "threads", MAX_THREADS)
        self._reward_fn: Optional[RewardFn] = None
        if callable(reward) and not isinstance(reward, (RewardParams, Mapping)):
            params = RewardParams()
            self._reward_fn = reward
        else:
            params = reward_params(reward, "RewardParams, a dict of its weights or a callable")
        self.render_mode: Optional[str] = _render_mode(render_mode)
        self.render_shape: tuple = _render_shape(render_shape)
        #: What each reset draws anew (None: nothing; every episode starts as the scenario says).
        self.randomize: Optional[dict] = None if randomize is None else dict(randomize)
        draw = episode_draw(randomize)
        floors = floor_draw(randomize)
        self.reward_params: RewardParams = params
        self.scenarios: list = scenarios
        self._core = _floornav._VecCore(scenarios, threads or 0, copy, params, draw, floors)
        self._floors = bool(floors.generator)
        self.num_envs: int = self._core.n_envs
        self.seed: int = _seed(seed)
        self._started = False
        self._return = np.zeros(self.num_envs)
        self._steps = np.zeros(self.num_envs, dtype=np.int64)
        robot = scenarios[0].robots[0]
        #: Per-copy action bounds: |v| <= the robot's top speed, |omega| <= its top turn rate.
        self.action_low: np.ndarray = np.array([-robot["max_speed"], -robot["max_turn_rate"]])
        self.action_high: np.ndarray = np.array([robot["max_speed"], robot["max_turn_rate"]])
        self.single_action_space: Box = Box(self.action_low, self.action_high, (2,), np.float64)
        self.action_space: Box = batch_space(self.single_action_space, self.num_envs)
        # On generated floors, the route is a floor's (a tour of its goals), not the template's.
        self.single_observation_space: Dict = observation_space(
            scenarios + [_floornav_module().factory_floor(scenarios[0], 0)] if self._floors
            else scenarios)
        self.observation_space: Dict = batch_space(self.single_observation_space, self.num_envs)
        #: Shapes of one copy's observation entries (without the leading n_envs).
        self.single_observation_shapes: dict = {
            k: s.shape for k, s in self.single_observation_space.spaces.items()}
        self.robot_name: str = robot["name"]
        self.metadata = dict(VecEnv.metadata, render_fps=int(round(1.0 / scenarios[0].dt)))

    @property
    def n_envs(self) -> int:
        return self.num_envs

    @property
    def threads(self) -> int:
        """Threads stepping the copies (1 when a Python controller drives them)."""
        return self._core.threads

    def reset(self, seed: Optional[int] = None, options: Optional[dict] = None) -> tuple:
        """Starts every copy afresh and returns ``(obs, info)``. With ``seed``, episode 0 of copy
        i has seed ``seed + i``; without, every copy goes on to its next episode, as Gymnasium's
        ``reset()`` does (the first reset starts from the seed the env was made with)."""
        if options:
            raise ValueError(f"reset(options=...): VecEnv takes no options, got {options!r} "
                             "(randomize is set when the env is made)")
        if seed is not None:
            self.seed = _seed(seed)
        obs = self._core.reset(None if seed is None and self._started else self.seed)
        self._started = True
        self._return[:] = 0.0
        self._steps[:] = 0
        info = {"status": self._core.statuses(), "seeds": np.array(self._core.seeds(), dtype=np.uint64)}
        if self._floors:
            info["floor_seeds"] = self._core.floor_seeds()
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
        if self._floors:
            info["floor_seeds"] = self._core.floor_seeds()
        self._return += reward
        self._steps += 1
        info["episode_return"] = self._return.copy()
        info["episode_steps"] = self._steps.copy()
        ended = terminated | truncated
        if ended.any():
            self._return[ended] = 0.0
            self._steps[ended] = 0
        return obs, reward, terminated, truncated, info

    def render(self, env_ids: Optional[Sequence[int]] = None) -> np.ndarray:
        """Frames of every copy (or of ``env_ids``) as they stand now, drawn in C++: uint8
        ``(n, height, width, 3)`` (``render_shape`` is (height, width)): the world, the robot
        (its body, heading, goal as a cross, this step's sensor returns as dots), people and
        forklifts. Needs ``render_mode="rgb_array"``."""
        if self.render_mode != "rgb_array":
            raise ValueError("render() needs VecEnv(..., render_mode='rgb_array')")
        if not self._started:
            raise ValueError("call reset() before render()")
        return self._core.render(None if env_ids is None else list(env_ids), *self.render_shape)

    def close(self) -> None:
        """Nothing to release (Gymnasium's signature)."""

    def __repr__(self) -> str:
        return (f"<floornav.VecEnv {self.num_envs} x '{self.scenarios[0].name}', "
                f"{self._core.beam_count} beams, {self.threads} threads>")


#: The most copies a VecEnv holds (as many as a fleet may have robots), and the most threads
#: that step them (as the command line's --threads): bounds checked before anything is allocated
#: or started.
MAX_ENVS: int = 100_000
MAX_THREADS: int = 1024


def _positive(n: Any, what: str, most: Optional[int] = None) -> int:
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise ValueError(f"{what} must be a positive integer, got {n!r}")
    if most is not None and n > most:
        raise ValueError(f"{what} must be at most {most}, got {n!r}")
    return int(n)


def _seed(seed: Any) -> int:
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
        raise ValueError(f"seed must be a non-negative integer, got {seed!r}")
    if seed > 2**64 - 1:
        raise ValueError(f"seed must be below 2**64, got {seed!r}")
    return int(seed)


def reward_params(reward: Any, what: str = "RewardParams or a dict of its weights") -> RewardParams:
    """The default reward's weights from None (the defaults), RewardParams or a dict of them."""
    if reward is None:
        return RewardParams()
    if isinstance(reward, RewardParams):
        return reward
    if isinstance(reward, Mapping):
        unknown = set(reward) - {"progress", "goal", "collision", "time"}
        if unknown:
            raise ValueError(f"unknown reward weight(s) {sorted(unknown)}: the weights are "
                             "progress, goal, collision and time")
        return RewardParams(**reward)
    raise ValueError(f"reward is {what}, got {reward!r}")


def _floornav_module() -> Any:
    import floornav  # the package, for load_scenario (imported late: it imports this module)

    return floornav


def _render_mode(mode: Optional[str]) -> Optional[str]:
    if mode is not None and mode not in RENDER_MODES:
        raise ValueError(f"render_mode is None or one of {list(RENDER_MODES)}, got {mode!r}")
    return mode


def _render_shape(shape: Sequence[int]) -> tuple:
    try:
        h, w = (int(v) for v in shape)
    except (TypeError, ValueError):
        raise ValueError(f"render_shape is (height, width) in pixels, got {shape!r}") from None
    if not (8 <= h <= 8192 and 8 <= w <= 8192):
        raise ValueError(f"render_shape: 8 to 8192 pixels on each side, got {shape!r}")
    return (h, w)


_RANDOMIZE_KEYS = ("start", "goal", "clearance", "goal_distance", "max_tries", "floor",
                   "floor_seeds")

#: The floor generators ``randomize["floor"]`` may name.
FLOOR_GENERATORS: tuple = ("factory_floor",)


def floor_draw(randomize: Optional[Mapping[str, Any]]) -> Any:
    """``randomize["floor"]`` and ``randomize["floor_seeds"]`` (VecEnv) checked and turned into
    the C++ floor draw: ``floor`` names the generator (``"factory_floor"``: the floors of
    :func:`floornav.factory_floor`); ``floor_seeds`` the floors an episode draws from, uniformly
    (a ``range`` or a sequence of seeds; absent or None: any 64-bit seed, a new floor almost
    surely every episode)."""
    draw = _floornav._FloorDraw()
    if randomize is None or randomize.get("floor") is None:
        if randomize is not None and randomize.get("floor_seeds") is not None:
            raise ValueError("randomize['floor_seeds'] needs randomize['floor'] "
                             f"(one of {list(FLOOR_GENERATORS)})")
        return draw
    generator = randomize["floor"]
    if generator not in FLOOR_GENERATORS:
        raise ValueError(f"randomize['floor'] is one of {list(FLOOR_GENERATORS)}, got {generator!r}")
    draw.generator = generator
    seeds = randomize.get("floor_seeds")
    if seeds is None:
        return draw
    if isinstance(seeds, range):
        if len(seeds) == 0:
            raise ValueError(f"randomize['floor_seeds'] is empty: {seeds!r}")
        if seeds.step < 0:
            seeds = seeds[::-1]
        _seed_in_range(seeds[0], "floor_seeds")
        _seed_in_range(seeds[-1], "floor_seeds")
        draw.start, draw.step, draw.count = seeds.start, seeds.step, len(seeds)
        return draw
    if isinstance(seeds, (str, bytes, Mapping)) or not isinstance(seeds, (Sequence, np.ndarray)):
        raise ValueError("randomize['floor_seeds'] is a range or a sequence of floor seeds, "
                         f"got {seeds!r}")
    values = [_seed_in_range(v, "floor_seeds") for v in seeds]
    if not values:
        raise ValueError("randomize['floor_seeds'] is empty")
    draw.seeds = values
    return draw


def _seed_in_range(value: Any, key: str) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) \
            or not 0 <= value < 2**64:
        raise ValueError(f"randomize[{key!r}]: a floor seed is an integer in [0, 2**64), got {value!r}")
    return int(value)


def episode_draw(randomize: Optional[Mapping[str, Any]]) -> Any:
    """``randomize`` (VecEnv, ParallelEnv) checked and turned into the C++ draw settings:
    ``start`` and ``goal``: ``"free"`` (uniform over the collision-free poses inside the world's
    bounds) or a region ``[x_min, y_min, x_max, y_max]`` (the free poses in it); ``clearance``
    (m the body keeps from everything at both, default 0); ``goal_distance`` ``(min, max)`` m
    between the start and a drawn goal; ``max_tries`` (draws before a reset gives up)."""
    draw = _floornav._EpisodeDraw()
    if randomize is None:
        return draw
    if not isinstance(randomize, Mapping):
        raise ValueError(f"randomize is a dict such as {{'start': 'free', 'goal': 'free'}}, got {randomize!r}")
    for key in randomize:
        if key not in _RANDOMIZE_KEYS:
            raise ValueError(f"randomize: unknown key {key!r} (known: {', '.join(_RANDOMIZE_KEYS)})")
    for key in ("start", "goal"):
        value = randomize.get(key)
        if value is None or value is False:
            continue
        if isinstance(value, str):
            if value != "free":
                raise ValueError(f"randomize[{key!r}] is 'free' or a region [x_min, y_min, x_max, y_max], got {value!r}")
        else:
            region = _region(value, key)
            setattr(draw, f"{key}_region", region)
        setattr(draw, key, True)
    if "clearance" in randomize:
        c = _number(randomize["clearance"], "clearance")
        if c < 0:
            raise ValueError(f"randomize['clearance'] must be >= 0 m, got {c}")
        draw.clearance = c
    if "goal_distance" in randomize:
        value = randomize["goal_distance"]
        try:
            lo, hi = value
        except (TypeError, ValueError):
            raise ValueError(f"randomize['goal_distance'] is (min, max) in m, got {value!r}") from None
        lo, hi = _number(lo, "goal_distance"), float(hi) if hi is not None else np.inf
        if not (0 <= lo <= hi) or np.isnan(hi):
            raise ValueError(f"randomize['goal_distance']: 0 <= min <= max, got {value!r}")
        draw.min_goal_distance, draw.max_goal_distance = lo, hi
    if "max_tries" in randomize:
        draw.max_tries = _positive(randomize["max_tries"], "randomize['max_tries']")
    return draw


def _number(value: Any, key: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)) \
            or not np.isfinite(value):
        raise ValueError(f"randomize[{key!r}] must be a finite number, got {value!r}")
    return float(value)


def _region(value: Any, key: str) -> list:
    try:
        box = [float(v) for v in value]
    except (TypeError, ValueError):
        box = []
    if len(box) != 4 or not np.all(np.isfinite(box)) or box[0] >= box[2] or box[1] >= box[3]:
        raise ValueError(f"randomize[{key!r}]: a region is [x_min, y_min, x_max, y_max] with "
                         f"x_min < x_max and y_min < y_max, got {value!r}")
    return box


def observation_space(scenarios: Sequence[Scenario], robot: int = 0) -> Dict:
    """The space of one robot's observation (robot ``robot`` of the scenarios; VecEnv's copies
    may have different scenarios with as many beams): the fields every observation has."""
    first = scenarios[0].robots[robot]
    beams = first["sensor_count"]
    sensors = first["sensors"]
    low = np.array([s[3] for s in sensors], dtype=np.float64)
    high = np.array([s[4] for s in sensors], dtype=np.float64)
    goals = 0
    for s in scenarios:
        r = s.robots[robot]
        lo = np.array([x[3] for x in r["sensors"]])
        hi = np.array([x[4] for x in r["sensors"]])
        low, high = np.minimum(low, lo), np.maximum(high, hi)
        goals = max(goals, len(r["goals"]), 1)
    inf = np.inf
    return Dict({
        "t": Box(0.0, inf, (), np.float64),
        "pose": Box([-inf, -inf, -np.pi], [inf, inf, np.pi], (3,), np.float64),
        "goal": Box(-inf, inf, (2,), np.float64),
        "goal_index": Box(0, goals, (), np.int32),
        "ranges": Box(low, high, (beams,), np.float64),
        "points": Box(-inf, inf, (beams, 2), np.float64),
    })
