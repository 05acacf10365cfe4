#!/usr/bin/env python3
"""Fuzz driver of the Python entry points (docs/RELIABILITY.md, "Fuzzing"): scenario YAML text and
``--set`` overrides, mutated from the repository's own scenarios, the fuzz corpus and the bad-input
corpus by Hypothesis (Debian's python3-hypothesis), go through ``floornav.parse_scenario``; what
loads is run for a few steps by ``floornav.run`` and, for one robot, by ``floornav.Simulation``.

The contract checked on every input: it loads, or it raises ``floornav.InputError`` whose message
is one line ``floornav: error: ...`` with a detail. Any other exception, a crash, a hang (60 s:
faulthandler ends the process with every thread's stack), or a NaN or inf where a finite number
is promised (trajectory, crowd samples, observations, the summary's numbers) is a finding.

Two ways to run it:

- ``tests/python/test_fuzz_python.py``: a fixed number of inputs from a fixed seed (the Python
  tests in ctest run it; ``FLOORNAV_PY_FUZZ_EXAMPLES`` sets how many, default 400).
- ``fuzz/fuzz_python.py SECONDS [FINDINGS_DIR]`` (``scripts/fuzz.sh``'s ``python`` target): runs
  of 100 inputs each, seeds 0, 1, 2, ..., until SECONDS have passed. Each finding, shrunk by
  Hypothesis, is written to FINDINGS_DIR as ``finding-N``: the YAML text, a NUL byte, then one
  ``--set`` per line, the input format of ``fuzz_scenario`` (so the C++ target reproduces it too),
  with ``finding-N.txt`` beside it holding the origin and the error. Exit status 1 on a finding.

Run it against a build: ``PYTHONPATH=build/python /usr/bin/python3 fuzz/fuzz_python.py 60``.
"""

from __future__ import annotations

import faulthandler
import math
import os
import pathlib
import sys
import time
import traceback
from typing import Any, NamedTuple, Optional, Union

import numpy as np
from hypothesis import HealthCheck, Phase, given, seed, settings
from hypothesis import strategies as st

import floornav

ROOT = pathlib.Path(__file__).resolve().parents[1]
HANG_SECONDS = 60  # an input that takes longer is a hang
STEPS = 20  # steps simulated of what loads (as fuzz_scenario)


class FuzzInput(NamedTuple):
    text: str  # the scenario's YAML text
    overrides: Union[list, dict]  # --set texts, or a dict of dotted keys to Python values
    origin: str  # the file name it is given (errors name it; relative paths start from its folder)


# ---- the seeds: the repository's scenarios, the fuzz corpus, the bad-input corpus ----------------

def _read(path: pathlib.Path) -> str:
    return path.read_bytes().decode("utf-8", "surrogateescape")


def _seeds(files: list) -> list:
    seeds = []
    for f in files:
        if f.stat().st_size <= 64 * 1024:
            yaml, _, sets = _read(f).partition("\0")  # the fuzz corpus: --sets after a NUL
            seeds.append(FuzzInput(yaml, [s for s in sets.split("\n") if s], str(f)))
    return seeds


def _set_values() -> list:
    lines = _read(ROOT / "tests/data/bad/set_values.txt").splitlines()
    return [line for line in lines if line.strip() and not line.startswith("#")]


def _dictionary() -> list:
    words = []
    for line in _read(ROOT / "fuzz/dict/scenario.dict").splitlines():
        line = line.strip()
        if line.startswith('"') and line.endswith('"'):
            words.append(line[1:-1].encode("latin-1", "backslashreplace").decode("unicode_escape"))
    return words


# Scenarios that load (the shipped ones, the fuzz corpus) and the bad-input corpus's, drawn as
# often as each other.
GOOD_SEEDS = _seeds(sorted(ROOT.glob("scenarios/*.yaml")) + sorted(ROOT.glob("scenarios/crowd/*"))
                    + [ROOT / "scenarios/ros/depot_1.yaml"]
                    + sorted((ROOT / "fuzz/corpus/scenario").iterdir()))
BAD_SEEDS = _seeds(sorted((ROOT / "tests/data/bad/scenario").glob("*.yaml")))
SET_VALUES = _set_values()
# Values that have broken parsers before: non-finite and huge numbers, wrong shapes, YAML
# aliases and merge keys, text that is not UTF-8 (a surrogate escape stands for the byte), lone
# surrogates, control characters, quotes, comments, long runs.
VALUES = [
    ".nan", "-.inf", ".inf", "1e400", "1e9", "1e300", "-1", "0", "0.0", "-0", "1", "2147483648",
    "18446744073709551616", "[]", "{}", "[0, 0]", "[0, 0, 0]", "[1, 2, 3, 4]", "[[0, 0], [1, 0]]",
    "null", "~", "true", "maybe", "&a [0, 0]", "*a", "<<: *a", '"caf\\xe9"', "caf\udce9",
    "\udcff\udcfe", "\ud800", "\u00e9\u0301", "\t", "\n", ": ", "- ", " #", "'", '"', "\\", "{",
    "[", "9" * 400, "a" * 3000, "x, y", "w1.world #2.world", "a: b", "%YAML 1.2", "---", "...",
    "!!binary AAAA", "!!python/object:os.system", "\x00", "\r\n", "\u2028", "\ufeff",
]
DICTIONARY = _dictionary() + VALUES
KEYS = [
    "name", "sim.dt", "sim.t_max", "sim.seed", "sim.record_trajectory", "robot.start",
    "robot.preset", "robot.footprint", "robot.sensors", "goal", "goals", "world.bounds",
    "world.obstacles", "world.map", "controller.kind", "controller.v0", "controller.safety",
    "controller.robot_avoidance", "controller.planner.kind", "controller.planner.max_samples",
    "controller.planner.window", "controller.dwa.v_samples", "controller.dwa.horizon", "robots",
    "robots[0].start", "people", "people[0].start", "people[0].radius", "forklifts",
    "random_people", "people_file", "sim", "robot", "world", "controller",
]

# ---- the strategies -------------------------------------------------------------------------------

# Any code point, lone surrogates included (Hypothesis leaves them out by default).
_any_text = st.text(st.characters(blacklist_categories=()), max_size=12)


@st.composite
def _mutate(draw: Any, text: str) -> str:
    op = draw(st.sampled_from(["word", "value", "text", "delete_line", "copy_line", "swap_lines",
                               "truncate", "repeat"]))
    lines = text.split("\n")
    at = draw(st.integers(0, len(text)))
    if op == "word":  # a dictionary word in place of up to 8 characters
        cut = draw(st.integers(0, 8))
        return text[:at] + draw(st.sampled_from(DICTIONARY)) + text[at + cut:]
    if op == "value":  # the value of a `key: value` line replaced
        keyed = [i for i, line in enumerate(lines) if ": " in line]
        if keyed:
            i = draw(st.sampled_from(keyed))
            lines[i] = lines[i][: lines[i].index(": ") + 2] + draw(st.sampled_from(VALUES))
        return "\n".join(lines)
    if op == "text":
        return text[:at] + draw(_any_text) + text[at:]
    i = draw(st.integers(0, len(lines) - 1))
    if op == "delete_line":
        return "\n".join(lines[:i] + lines[i + 1:])
    if op == "copy_line":  # a key given twice, or a list entry more
        return "\n".join(lines[: i + 1] + lines[i:])
    if op == "swap_lines":
        j = draw(st.integers(0, len(lines) - 1))
        lines[i], lines[j] = lines[j], lines[i]
        return "\n".join(lines)
    if op == "truncate":
        return text[:at]
    # repeat: a line many times (long lists, many obstacles or people)
    return "\n".join(lines[: i + 1] + [lines[i]] * draw(st.integers(2, 200)) + lines[i + 1:])


_python_values = st.recursive(
    st.none() | st.booleans() | st.integers(-(2**70), 2**70)
    | st.floats(allow_nan=True, allow_infinity=True) | _any_text,
    lambda inner: st.lists(inner, max_size=4) | st.dictionaries(_any_text, inner, max_size=3),
    max_leaves=8,
)

_set_text = st.one_of(
    st.sampled_from(SET_VALUES),
    st.builds(lambda k, v: f"{k}={v}", st.sampled_from(KEYS), st.sampled_from(VALUES)),
    st.builds(lambda k, v: f"{k}={v}", st.sampled_from(KEYS), _any_text),
    _any_text,
)


@st.composite
def fuzz_inputs(draw: Any) -> FuzzInput:
    """A seed, up to 4 mutations of its text, its own overrides plus up to 3 more (or, about one
    time in four, a dict of dotted keys to Python values), and, about one time in eight, an odd
    file name in its folder."""
    base = draw(st.sampled_from(GOOD_SEEDS) | st.sampled_from(BAD_SEEDS))
    text = base.text
    for _ in range(draw(st.integers(0, 4))):
        text = draw(_mutate(text))
    if draw(st.integers(0, 3)) == 2:
        overrides: Union[list, dict] = draw(
            st.dictionaries(st.sampled_from(KEYS), _python_values, max_size=3))
    else:
        overrides = list(base.overrides) + draw(st.lists(_set_text, max_size=3))
    origin = base.origin
    if draw(st.integers(0, 7)) == 5:
        origin = str(pathlib.Path(origin).parent / (draw(_any_text) + " #1: x.yaml"))
    return FuzzInput(text, overrides, origin)


# ---- the contract ---------------------------------------------------------------------------------

class Finding(AssertionError):
    """The contract broken: a wrong message, a non-finite number where a finite one is promised."""


def _check_message(e: floornav.InputError) -> None:
    msg = str(e)
    if not msg.startswith("floornav: error: ") or "\n" in msg or "\r" in msg:
        raise Finding(f"an InputError that is not one 'floornav: error:' line: {msg!r}")
    if not getattr(e, "detail", ""):
        raise Finding(f"an InputError without a detail: {msg!r}")


def _check_numbers(value: Any, where: str, allow_inf: bool = False) -> None:
    """No NaN anywhere in `value` (dicts, lists, numpy arrays), nor inf unless allowed."""
    if isinstance(value, dict):
        for k, v in value.items():
            _check_numbers(v, f"{where}.{k}", allow_inf)
    elif isinstance(value, (list, tuple)):
        for i, v in enumerate(value):
            _check_numbers(v, f"{where}[{i}]", allow_inf)
    elif isinstance(value, np.ndarray) and value.dtype.kind == "f":
        bad = np.isnan(value) if allow_inf else ~np.isfinite(value)
        if bad.any():
            raise Finding(f"{where} holds {value[bad][0]} at {int(np.argmax(bad))}")
    elif isinstance(value, float) and (math.isnan(value) or (not allow_inf and math.isinf(value))):
        raise Finding(f"{where} is {value}")


# The trajectory columns that are always finite (the --record columns may hold NaN by design: on
# the first row nothing was asked yet).
TRAJECTORY = ("t", "x", "y", "theta", "v", "omega", "w_left", "w_right")


def _check_result(result: floornav.RunResult) -> None:
    trajectory = result.trajectory
    robots = trajectory if isinstance(trajectory, list) else [trajectory]
    for i, tr in enumerate(robots):
        for column in TRAJECTORY:
            if column in tr:
                _check_numbers(np.asarray(tr[column], dtype=float), f"trajectory[{i}].{column}")
    # summary: no NaN (min_clearance and the like may be inf where nothing was measured)
    _check_numbers(result.summary, "summary", allow_inf=True)
    if result.is_fleet:
        _check_numbers(result.crowd, "crowd")


def _too_big(s: floornav.Scenario) -> bool:
    # Valid, but too slow to be worth a fuzzer's time (as fuzz_scenario skips them).
    robots = s.robots
    return len(robots) > 64 or sum(r["sensor_count"] for r in robots) > 1024


def check_input(inp: FuzzInput) -> str:
    """Checks the contract on one input; returns "refused", "loaded" or "ran"."""
    faulthandler.dump_traceback_later(HANG_SECONDS, exit=True)
    try:
        return _check_input(inp)
    finally:
        faulthandler.cancel_dump_traceback_later()


def _check_input(inp: FuzzInput) -> str:
    try:
        s = floornav.parse_scenario(inp.text, inp.overrides, inp.origin)
    except floornav.InputError as e:
        _check_message(e)
        return "refused"
    # What loaded reads back as text and numbers (a name that is not UTF-8 once raised here).
    repr(s), s.name, s.source, s.overrides, s.world, s.controller_kind, s.input_files
    _check_numbers([s.dt, s.t_max], "scenario")
    if _too_big(s):
        return "loaded"
    # The same scenario, STEPS steps long: an InputError here would be a lie of the first load.
    short = floornav.render_overrides(inp.overrides) + [f"sim.t_max={STEPS * s.dt!r}"]
    _check_result(floornav.run(floornav.parse_scenario(inp.text, short, inp.origin)))
    if len(s.robots) == 1:
        sim = floornav.Simulation(s)
        obs = sim.reset()
        for _ in range(STEPS):
            if sim.finished:
                break
            obs = sim.step()
        _check_numbers(obs, "observation", allow_inf=True)
        _check_numbers([sim.t, *sim.pose], "simulation")
    return "ran"


# ---- the fixed-seed run and the timed campaign ---------------------------------------------------

def fuzz_settings(examples: int) -> settings:
    return settings(max_examples=examples, deadline=None, database=None, derandomize=False,
                    suppress_health_check=list(HealthCheck), print_blob=False,
                    phases=[Phase.generate, Phase.shrink])


def property_test(examples: int, run_seed: int, outcomes: Optional[dict] = None,
                  seen: Optional[list] = None):
    """The contract as a Hypothesis test of `examples` inputs drawn from `run_seed`; `outcomes`
    counts what became of them, `seen` holds the last input checked (after a failure, the shrunk
    one: Hypothesis replays it last)."""

    @seed(run_seed)
    @fuzz_settings(examples)
    @given(fuzz_inputs())
    def contract(inp: FuzzInput) -> None:
        if seen is not None:
            seen[:] = [inp]
        outcome = check_input(inp)
        if outcomes is not None:
            outcomes[outcome] = outcomes.get(outcome, 0) + 1

    return contract


def _bytes(text: str) -> bytes:
    # Surrogate escapes back to the bytes they stand for; any other lone surrogate as it is.
    try:
        return text.encode("utf-8", "surrogateescape")
    except UnicodeEncodeError:
        return text.encode("utf-8", "surrogatepass")


def _write_finding(findings: pathlib.Path, inp: FuzzInput, error: BaseException) -> pathlib.Path:
    findings.mkdir(parents=True, exist_ok=True)
    n = len(list(findings.glob("finding-*.txt")))
    path = findings / f"finding-{n}"
    sets = floornav.render_overrides(inp.overrides)
    path.write_bytes(_bytes(inp.text) + b"\0" + _bytes("\n".join(sets)))
    path.with_suffix(".txt").write_text(
        f"origin: {inp.origin!r}\noverrides: {inp.overrides!r}\n\n"
        + "".join(traceback.format_exception(type(error), error, error.__traceback__)),
        errors="backslashreplace")
    return path


def main(argv: list) -> int:
    seconds = float(argv[1]) if len(argv) > 1 else 30.0
    findings = pathlib.Path(argv[2]) if len(argv) > 2 else ROOT / "build-fuzz/fuzz-findings/python"
    end = time.monotonic() + seconds
    outcomes: dict = {}
    run_seed, found = 0, 0
    last: list = []
    while time.monotonic() < end:
        try:
            property_test(100, run_seed, outcomes, last)()
        except Exception as e:  # noqa: BLE001 - every other exception is a finding
            path = _write_finding(findings, last[0], e) if last else None
            print(f"finding (seed {run_seed}): {type(e).__name__}: {e}\n  written to {path}",
                  file=sys.stderr)
            found += 1
        run_seed += 1
    executions = sum(outcomes.values())
    print(f"stat::number_of_executed_units: {executions}")
    print(f"inputs: {executions} ({', '.join(f'{k} {v}' for k, v in sorted(outcomes.items()))}), "
          f"{run_seed} seeds, {found} findings")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
