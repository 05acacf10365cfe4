"""floornav: reactive navigation of wheeled mobile robots, from Python.

The C++ library and its simulator behind a small Python interface:

- :func:`load_scenario` reads a scenario file (with ``--set``-style overrides);
- :func:`run` simulates it (summary dict, trajectory as numpy arrays, the transition log);
- :func:`batch` runs many scenarios on all cores (the command line's ``results.jsonl`` lines);
- :class:`Simulation` steps one robot from Python (``reset`` / ``step`` / ``observe``);
- :class:`VecEnv` steps many copies together in C++, shaped like a Gymnasium vector env, with
  spaces (:class:`Box`, :class:`Dict`), randomized episodes and frames;
- :class:`ParallelEnv` steps a fleet among people and forklifts, shaped like PettingZoo's
  Parallel API;
- controllers written in Python (a callable ``observation -> command``, or an object with
  ``decide``) drive robots in all of the above: :meth:`Scenario.with_controller`;
- the chapter's behaviours and the hybrid-automaton engine to build them from
  (:class:`AutomatonBuilder`, :mod:`floornav.chapter`);
- :func:`plot` and :func:`animate` draw a run with matplotlib.

Everything the command line reports as bad input raises :class:`InputError` (a ``ValueError``)
whose message is the command line's one line. See docs/PYTHON.md.
"""

from __future__ import annotations

import hashlib
import numbers
import os
import pathlib
from collections.abc import Iterable, Mapping, Sequence
from typing import Any, Callable, Optional, Union

from . import _floornav
from ._floornav import (
    AutomatonBuilder,
    AutomatonState,
    Command,
    ControllerConfig,
    Decision,
    DwaParams,
    HybridAutomaton,
    InputError,
    NavigationInput,
    NavigationParams,
    PidGains,
    PlannerParams,
    RewardParams,
    RobotAvoidanceParams,
    RunResult,
    SafetyParams,
    Scenario,
    SimConfig,
    Simulation,
    Transition,
    Turn,
    avoid_obstacle_velocity,
    blend_velocities,
    blend_weight,
    choose_turn,
    controller_kinds,
    follow_boundary_tangent,
    follow_boundary_velocity,
    go_to_goal_velocity,
    make_navigation_input,
    navigation_input,
)
from ._overrides import encode_text, render_overrides, render_value
from ._parallel_env import ParallelEnv
from ._spaces import Box, Dict
from ._vec_env import STATUS_NAMES, VecEnv
from . import chapter  # noqa: E402  (floornav.chapter as an attribute, as the docs use it)

__version__: str = _floornav.__version__

__all__ = [
    "AutomatonBuilder",
    "AutomatonState",
    "BatchResults",
    "Box",
    "Command",
    "ControllerConfig",
    "Decision",
    "Dict",
    "DwaParams",
    "HybridAutomaton",
    "InputError",
    "NavigationInput",
    "NavigationParams",
    "ParallelEnv",
    "PidGains",
    "PlannerParams",
    "RewardParams",
    "RobotAvoidanceParams",
    "RunResult",
    "STATUS_NAMES",
    "SafetyParams",
    "Scenario",
    "SimConfig",
    "Simulation",
    "Transition",
    "Turn",
    "VecEnv",
    "animate",
    "avoid_obstacle_velocity",
    "batch",
    "factory_floor",
    "blend_velocities",
    "blend_weight",
    "chapter",
    "choose_turn",
    "controller_kinds",
    "follow_boundary_tangent",
    "follow_boundary_velocity",
    "go_to_goal_velocity",
    "load_scenario",
    "make_navigation_input",
    "navigation_input",
    "parse_scenario",
    "plot",
    "render_overrides",
    "run",
    "shared_floor",
]

PathLike = Union[str, "os.PathLike[str]"]
Overrides = Union[Mapping[str, Any], Iterable[str], None]


def load_scenario(path: PathLike, overrides: Overrides = None) -> Scenario:
    """Loads and validates the scenario file at ``path``.

    ``overrides`` is a dict of dotted keys to values, applied exactly like the command line's
    ``--set KEY=VALUE`` (``{"controller.kind": "blended", "sim.dt": 0.02, "robot.start":
    [0, 0, 1.57]}``): each value is written as YAML text (a string as it is, numbers, lists,
    dicts) and set in the file's YAML before it is read. A list of ``"key=value"`` texts works
    too. Bad input raises :class:`InputError` with the command line's one-line message.
    """
    file = os.fspath(path)
    sets = render_overrides(overrides)
    return _floornav._load_scenario(
        encode_text(file, "", file), [encode_text(o, "--set " + o) for o in sets]
    )


def parse_scenario(text: str, overrides: Overrides = None, origin: PathLike = "scenario.yaml") -> Scenario:
    """A scenario from YAML text; ``origin`` names it in errors and anchors relative paths."""
    name = os.fspath(origin)
    sets = render_overrides(overrides)
    return _floornav._parse_scenario(
        encode_text(text, "", name), encode_text(name, "", name),
        [encode_text(o, "--set " + o) for o in sets],
    )


def _template(template: Union[Scenario, PathLike], overrides: Overrides) -> Scenario:
    if isinstance(template, Scenario):
        if overrides:
            raise ValueError("overrides apply to a template file; a Scenario is already loaded "
                             "(load it with overrides instead)")
        return template
    return load_scenario(template, overrides)


def factory_floor(template: Union[Scenario, PathLike], seed: int, overrides: Overrides = None) -> Scenario:
    """The template's robot, controller and sim on the generated factory floor ``seed``: a walled
    20 x 20 m hall of 50 random star-shaped obstacles and a tour of four goals across it, drawn
    from ``seed`` (the case ``floornav batch TEMPLATE --floors N`` runs for that seed). Floors
    with other seeds are other floors: train on some, hold others out. The result pickles (as
    the template and the seed). Bad input raises :class:`InputError`."""
    return _floornav._generated_floor(_template(template, overrides), "factory_floor", seed)


def shared_floor(template: Union[Scenario, PathLike], seed: int, overrides: Overrides = None) -> Scenario:
    """A fleet on the generated shared floor ``seed``: a hall with pillars and boxes, 4 to 12
    robots (each the template's robot and controller) on routes of 1 to 3 goals, people and a
    forklift on some floors; the template's sim with ``sim.seed = seed`` (the case ``floornav
    batch TEMPLATE --shared-floors N`` runs for that seed). For :class:`ParallelEnv`."""
    return _floornav._generated_floor(_template(template, overrides), "shared_floor", seed)


def _as_scenario(s: Union[Scenario, PathLike]) -> Scenario:
    return s if isinstance(s, Scenario) else load_scenario(s)


def run(
    scenario: Union[Scenario, PathLike],
    controller: Any = None,
    *,
    factory: Optional[Callable[[dict], Any]] = None,
    kind: str = "python",
    threads: int = 0,
    out: Optional[PathLike] = None,
    mcap: bool = False,
) -> RunResult:
    """Simulates ``scenario`` to the end and returns its :class:`RunResult`: ``.summary`` (the
    summary.json keys), ``.trajectory`` (one numpy array per trajectory.csv column),
    ``.transitions`` (the transition log with guard names).

    ``controller`` (a callable ``observation -> command`` or an object with ``decide``) or
    ``factory`` (``context -> controller``, one per robot) replaces the scenario's controller,
    reported as ``kind``. A fleet runs on ``threads`` threads (0: all cores; a Python controller:
    one). With ``out``, the command line's files are written there once the run has finished
    (an exception in a controller leaves no file). ``mcap=True`` records what a ROS 2 bag needs
    (the trajectory, the sensor ranges: the same run, bit for bit) and, with ``out``, writes
    ``run.mcap`` too (``RunResult.write(out, mcap=True)`` later does the same).
    """
    s = _as_scenario(scenario)
    if controller is not None or factory is not None:
        s = s.with_controller(controller, factory=factory, kind=kind)
    result = _floornav._run(s, threads, mcap)
    if out is not None:
        result.write(os.fspath(out), mcap=mcap)
    return result


class BatchResults(list):
    """The summary dicts of a batch, in case order (each equal to a line of the command line's
    ``results.jsonl``); ``.aggregate`` holds ``aggregate.json``."""

    aggregate: dict

    def __init__(self, lines: list, aggregate: dict) -> None:
        super().__init__(lines)
        self.aggregate = aggregate


def batch(
    scenarios: Iterable[Union[Scenario, PathLike]],
    jobs: Optional[int] = None,
    *,
    timing: bool = True,
    optimum: bool = True,
    out: Optional[PathLike] = None,
    ids: Optional[Sequence[int]] = None,
    shard: Optional[tuple] = None,
) -> BatchResults:
    """Runs every scenario (a :class:`Scenario` or a path) on ``jobs`` threads (None: all
    cores), with the GIL released, and returns one summary dict per scenario, in order: the
    lines the command line's ``floornav batch`` writes to ``results.jsonl`` (``case`` numbers
    from 0, ``source`` the path the scenario was loaded from). ``timing=False`` writes
    ``wall_time`` as 0 (``--no-timing``); ``optimum=False`` skips the grid optimum
    (``--no-optimum``). ``ids`` numbers the cases (default 0, 1, ...; each once): a shard of a
    bigger sweep keeps the sweep's numbers, and its lines merge by them (docs/PYTHON.md: Dask).

    ``shard=(k, n)`` runs shard k of n of the sweep ``scenarios`` (cases k - 1, k - 1 + n, ...,
    as ``--shard K/N``). With ``out``, ``results.jsonl``, ``aggregate.json`` and ``sweep.json``
    are written there, together, once every case has run: ``sweep.json`` carries a fingerprint
    of every scenario of the sweep (its source, overrides, resolved settings and the content of
    the files it read), so that ``floornav merge`` joins the shards of one sweep and ``--resume``
    checks it. A folder is the whole sweep or a ``shard`` of it: ``ids`` with ``out`` is refused
    (merge could not check such a folder).

    Scenarios driven by a Python controller run on one thread (each step takes the GIL). An
    exception in a controller ends the batch and is raised here; nothing is written.
    Ctrl-C stops it (the cases under way finish first) and raises KeyboardInterrupt.
    """
    items = [_as_scenario(s) for s in scenarios]
    if jobs is not None and (not isinstance(jobs, int) or isinstance(jobs, bool) or jobs < 1):
        raise ValueError(f"jobs must be a positive integer or None, got {jobs!r}")
    if ids is not None and shard is not None:
        raise ValueError("give ids or shard, not both (a shard numbers its own cases)")
    if ids is not None:
        ids = [_case_id(i) for i in ids]
        if len(ids) != len(items):
            raise ValueError(f"ids: one non-negative case number per scenario ({len(items)})")
        if len(set(ids)) != len(ids):
            twice = sorted(i for i in set(ids) if ids.count(i) > 1)[0]
            raise ValueError(f"ids: case {twice} is given twice (each case once)")
        if out is not None:
            raise ValueError("out= with ids=: a folder holds a whole sweep or a shard of it; "
                             "pass every scenario of the sweep and shard=(k, n)")
    sweep = None
    run_items = items
    if shard is not None:
        k, n = _shard(shard)
        ids = list(range(k - 1, len(items), n))
        run_items = [items[i] for i in ids]
    if out is not None:
        k, n = (1, 1) if shard is None else _shard(shard)
        sweep = (_sweep_id(items, timing, optimum), k, n, len(items))
    lines, aggregate = _floornav._batch(
        run_items, jobs or 0, timing, optimum, None if out is None else os.fspath(out), ids, sweep
    )
    return BatchResults(lines, aggregate)


def _case_id(i: Any) -> int:
    if isinstance(i, bool) or not isinstance(i, (int, numbers.Integral)) or not 0 <= i < 2**63:
        raise ValueError(f"ids: a case number is an integer in [0, 2**63), got {i!r}")
    return int(i)


def _shard(shard: Any) -> tuple:
    try:
        k, n = shard
    except (TypeError, ValueError):
        raise ValueError(f"shard is (k, n) with 1 <= k <= n, got {shard!r}") from None
    if not all(isinstance(v, (int, numbers.Integral)) and not isinstance(v, bool) for v in (k, n)) \
            or not 1 <= k <= n <= 1_000_000:
        raise ValueError(f"shard is (k, n) with 1 <= k <= n <= 1000000, got {shard!r}")
    return int(k), int(n)


def _sweep_id(items: list, timing: bool, optimum: bool) -> str:
    """A fingerprint of a Python sweep, as the command line's of its inputs: every scenario's
    source, overrides and resolved settings, and the content of every file it read."""
    h = hashlib.sha256()

    def add(label: str, data: bytes) -> None:
        h.update(f"{len(label)}:{label}:{len(data)}:".encode())
        h.update(data)

    add("format", b"floornav-python-sweep-1")
    add("floornav_version", __version__.encode())
    add("timing", b"on" if timing else b"off")
    add("optimum", b"on" if optimum else b"off")
    contents: dict = {}
    for s in items:
        add("source", s.source.encode())
        for o in s.overrides:
            add("--set", o.encode())
        add("config", s._config_yaml.encode())
        for f in s.input_files:
            if f not in contents:
                try:
                    contents[f] = hashlib.sha256(pathlib.Path(f).read_bytes()).digest()
                except OSError:
                    contents[f] = b""
            add("reads", contents[f])
    return "py" + h.hexdigest()[:14]


def plot(result: RunResult, ax: Any = None, **kwargs: Any) -> Any:
    """Draws a run with matplotlib, as trajectory.svg does: the world, the path coloured by mode,
    the switch points, start and goals. Returns the Axes. See :func:`floornav._plot.plot`."""
    from ._plot import plot as _plot_run

    return _plot_run(result, ax=ax, **kwargs)


def animate(result: RunResult, path: PathLike, **kwargs: Any) -> Any:
    """Writes an animation of the run (a GIF with Pillow, or any format matplotlib's writers
    know) to ``path``. See :func:`floornav._plot.animate`."""
    from ._plot import animate as _animate_run

    return _animate_run(result, os.fspath(path), **kwargs)
