"""The controller section in Python: every key docs/SCENARIOS.md documents is bound (as the same
name, in the same section), every bound key is documented and declared in the type stub, and
the kinds Python lists are the ones the docs name. The bindings come from the C++ listing the
scenario reader uses, so a key that is read is bound; these tests catch the docs and the stub
falling behind."""

from __future__ import annotations

import ast
import re

import pytest

import floornav
from conftest import ROOT, SCENARIOS

SECTIONS = {"planner": "PlannerParams", "dwa": "DwaParams", "safety": "SafetyParams",
            "pid": "PidGains"}


def documented_controller_keys() -> tuple[set[str], str]:
    """The dotted keys of the `controller` tables of docs/SCENARIOS.md, and the `kind` row."""
    keys: set[str] = set()
    kind_row = ""
    inside, prefix = False, ""
    for line in (ROOT / "docs" / "SCENARIOS.md").read_text().splitlines():
        if line.startswith("## "):
            inside, prefix = line == "## `controller`", ""
            continue
        if not inside:
            continue
        heading = re.match(r"### `controller\.(\w+)`", line)
        if heading:
            prefix = heading.group(1) + "."
            continue
        if line.startswith("| `"):
            first = line.split("|")[1]
            keys |= {prefix + k for k in re.findall(r"`([a-z_0-9.]+)`", first)}
            if not prefix and "`kind`" in first:
                kind_row = line
    return keys, kind_row


def bound_keys(obj, prefix: str = "") -> set[str]:
    keys: set[str] = set()
    for name, value in obj.to_dict().items():
        if isinstance(value, dict):
            keys |= bound_keys(getattr(obj, name), f"{prefix}{name}.")
        else:
            keys.add(prefix + name)
    return keys


def test_every_documented_key_is_bound_and_every_bound_key_documented():
    documented, _ = documented_controller_keys()
    bound = bound_keys(floornav.ControllerConfig())
    assert len(bound) > 60
    assert bound - documented == set(), "bound but not in docs/SCENARIOS.md"
    assert documented - bound - {"kind", "preset"} == set(), "documented but not bound"


def test_the_sections_are_their_own_types_and_the_chapter_keys_stand_alone():
    c = floornav.ControllerConfig()
    for section, type_name in SECTIONS.items():
        assert type(getattr(c, section)).__name__ == type_name
    assert c.planner.kind == "none" and c.dwa.horizon > 0 and c.safety.enabled
    assert c.robot_avoidance == "orca"
    chapter = set(floornav.NavigationParams.fields)
    assert {"v0", "d_o", "epsilon", "pid"} <= chapter
    # What the chapter's supervisor does not read is not handed to every user controller.
    assert chapter.isdisjoint({"planner", "dwa", "safety", "robot_avoidance", "avoidance_range"})
    assert set(floornav.RobotAvoidanceParams.fields) == {
        "robot_avoidance", "avoidance_range", "avoidance_horizon", "avoidance_margin",
        "avoidance_neighbours"}


def test_a_section_is_reached_by_reference_and_an_enum_by_name():
    c = floornav.ControllerConfig()
    c.planner.kind = "astar"
    c.avoidance_margin = 0.1
    assert c.planner.kind == "astar" and c.to_dict()["planner"]["kind"] == "astar"
    assert c.to_dict()["avoidance_margin"] == 0.1
    with pytest.raises(ValueError, match="expected none or orca"):
        c.robot_avoidance = "sideways"
    assert c.robot_avoidance == "orca"


def test_a_scenario_hands_out_its_controller_section():
    s = floornav.load_scenario(SCENARIOS / "rectangle.yaml",
                               {"controller.planner.kind": "astar", "controller.dwa.v_samples": 5})
    c = s.controller
    assert c.kind == s.controller_kind
    assert c.planner.kind == "astar" and c.dwa.v_samples == 5
    assert c.v0 == s.params.v0 and c.pid == s.params.pid


def test_the_kinds_are_the_documented_ones():
    _, kind_row = documented_controller_keys()
    kinds = floornav.controller_kinds()
    assert list(kinds) == ["hybrid", "hard_switch", "blended", "go_to_goal", "dwa"]
    for name, summary in kinds.items():
        assert f"`{name}`" in kind_row
        assert len(summary) > 20


def test_the_chapter_ports_registered_kinds():
    """floornav.chapter ports the chapter's kinds, each a registered C++ kind (not dwa)."""
    from floornav import chapter
    kinds = floornav.controller_kinds()
    assert set(chapter.KINDS) == set(kinds) - {"dwa"}


def test_the_stub_declares_every_bound_field():
    tree = ast.parse((ROOT / "python" / "floornav" / "_floornav.pyi").read_text())
    declared: dict[str, set[str]] = {}
    for node in tree.body:  # a class's names, its (stub-only) bases' included
        if isinstance(node, ast.ClassDef):
            names = {n.target.id for n in node.body if isinstance(n, ast.AnnAssign)}
            names |= {n.name for n in node.body if isinstance(n, ast.FunctionDef)}
            for base in node.bases:
                names |= declared.get(getattr(base, "id", ""), set())
            declared[node.name] = names
    for cls in (floornav.ControllerConfig, floornav.NavigationParams,
                floornav.RobotAvoidanceParams, floornav.PlannerParams, floornav.DwaParams,
                floornav.SafetyParams, floornav.PidGains, floornav.SimConfig):
        missing = set(cls.fields) - declared[cls.__name__]
        assert missing == set(), f"{cls.__name__}: {missing} not in _floornav.pyi"
