"""The Python fuzz driver (fuzz/fuzz_python.py) for a bounded run: a fixed number of mutated
scenario texts and --set overrides from a fixed seed, each of which must load or raise
floornav.InputError with one clear line (never another exception, a crash, a hang or a NaN).
FLOORNAV_PY_FUZZ_EXAMPLES sets how many (default 400); scripts/fuzz.sh runs it for a time."""

from __future__ import annotations

import os
import sys

import numpy as np
import pytest

from conftest import ROOT

sys.path.insert(0, str(ROOT / "fuzz"))
import fuzz_python  # noqa: E402

import floornav  # noqa: E402

EXAMPLES = int(os.environ.get("FLOORNAV_PY_FUZZ_EXAMPLES", "400"))


def test_mutated_scenario_texts_and_overrides_keep_the_contract():
    outcomes: dict = {}
    fuzz_python.property_test(EXAMPLES, 0, outcomes)()
    assert sum(outcomes.values()) >= EXAMPLES
    # The mutations are mild enough that some inputs still load and run, and wild enough that
    # others are refused: both sides of the contract are exercised.
    assert outcomes.get("ran", 0) > 0, outcomes
    assert outcomes.get("refused", 0) > 0, outcomes


# The driver's checks catch what they must: the contract's breaches are findings, not passes.

def test_a_nan_or_an_inf_where_a_finite_number_is_promised_is_a_finding():
    with pytest.raises(fuzz_python.Finding, match=r"trajectory\.x holds nan at 1"):
        fuzz_python._check_numbers({"x": np.array([1.0, np.nan])}, "trajectory")
    with pytest.raises(fuzz_python.Finding, match=r"summary\.robots\[1\] is nan"):
        fuzz_python._check_numbers({"robots": [1.0, float("nan")]}, "summary")
    with pytest.raises(fuzz_python.Finding, match="crowd"):
        fuzz_python._check_numbers([float("inf")], "crowd")
    fuzz_python._check_numbers({"min_clearance": float("inf")}, "summary", allow_inf=True)
    with pytest.raises(fuzz_python.Finding):
        fuzz_python._check_numbers({"min_clearance": float("nan")}, "summary", allow_inf=True)


def test_an_input_error_of_more_than_one_line_is_a_finding():
    e = floornav.InputError("floornav: error: a.yaml:name: two\nlines")
    e.detail = "two\nlines"
    with pytest.raises(fuzz_python.Finding, match="one 'floornav: error:' line"):
        fuzz_python._check_message(e)


def test_a_refused_input_and_a_good_one_as_the_driver_sees_them():
    rect = (ROOT / "scenarios" / "rectangle.yaml").read_text()
    origin = str(ROOT / "scenarios" / "rectangle.yaml")
    assert fuzz_python.check_input(fuzz_python.FuzzInput(rect, ["sim.dt=.nan"], origin)) == "refused"
    assert fuzz_python.check_input(fuzz_python.FuzzInput(rect, [], origin)) == "ran"
    # Another exception than InputError is no refusal: it escapes as a finding would.
    with pytest.raises(TypeError):
        fuzz_python.check_input(fuzz_python.FuzzInput(rect, [3], origin))
