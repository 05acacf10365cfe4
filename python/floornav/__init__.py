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

import os
from collections.abc import Iterable, Mapping, Sequence
from typing import Any, Callable, Optional, Union

from . import _floornav
from ._floornav import (
    AutomatonBuilder,
    AutomatonState,
    Command,
    Decision,
    HybridAutomaton,
    InputError,
    NavigationInput,
    NavigationParams,
    PidGains,
    RewardParams,
    RunResult,
    Scenario,
    SimConfig,
    Simulation,
    Transition,
    Turn,
    avoid_obstacle_velocity,
    blend_velocities,
    blend_weight,
    choose_turn,
    follow_boundary_tangent,
    follow_boundary_velocity,
    go_to_goal_velocity,
    make_navigation_input,
    navigation_input,
)
from ._overrides import render_overrides, render_value
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
    "Decision",
    "Dict",
    "HybridAutomaton",
    "InputError",
    "NavigationInput",
    "NavigationParams",
    "ParallelEnv",
    "PidGains",
    "RewardParams",
    "RunResult",
    "STATUS_NAMES",
    "Scenario",
    "SimConfig",
    "Simulation",
    "Transition",
    "Turn",
    "VecEnv",
    "animate",
    "avoid_obstacle_velocity",
    "batch",
    "blend_velocities",
    "blend_weight",
    "chapter",
    "choose_turn",
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
    return _floornav._load_scenario(os.fspath(path), render_overrides(overrides))


def parse_scenario(text: str, overrides: Overrides = None, origin: PathLike = "scenario.yaml") -> Scenario:
    """A scenario from YAML text; ``origin`` names it in errors and anchors relative paths."""
    return _floornav._parse_scenario(text, os.fspath(origin), render_overrides(overrides))


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
) -> BatchResults:
    """Runs every scenario (a :class:`Scenario` or a path) on ``jobs`` threads (None: all
    cores), with the GIL released, and returns one summary dict per scenario, in order: the
    lines the command line's ``floornav batch`` writes to ``results.jsonl`` (``case`` numbers
    from 0, ``source`` the path the scenario was loaded from). ``timing=False`` writes
    ``wall_time`` as 0 (``--no-timing``); ``optimum=False`` skips the grid optimum
    (``--no-optimum``). With ``out``, ``results.jsonl`` and ``aggregate.json`` are written there
    once every case has run. ``ids`` numbers the cases (default 0, 1, ...): a shard of a
    bigger sweep keeps the sweep's numbers, and its lines merge by them (docs/PYTHON.md: Dask).

    Scenarios driven by a Python controller run on one thread (each step takes the GIL). An
    exception in a controller ends the batch and is raised here; nothing is written.
    Ctrl-C stops it (the cases under way finish first) and raises KeyboardInterrupt.
    """
    items = [_as_scenario(s) for s in scenarios]
    if jobs is not None and (not isinstance(jobs, int) or isinstance(jobs, bool) or jobs < 1):
        raise ValueError(f"jobs must be a positive integer or None, got {jobs!r}")
    if ids is not None:
        ids = [int(i) for i in ids]
        if len(ids) != len(items) or any(i < 0 for i in ids):
            raise ValueError(f"ids: one non-negative case number per scenario ({len(items)})")
    lines, aggregate = _floornav._batch(
        items, jobs or 0, timing, optimum, None if out is None else os.fspath(out), ids
    )
    return BatchResults(lines, aggregate)


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
