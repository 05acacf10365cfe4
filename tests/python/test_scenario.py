"""load_scenario: overrides exactly like --set, and every bad input the command line reports
raises floornav.InputError with the command line's one line."""

from __future__ import annotations

import json
import pathlib

import pytest

import floornav
from conftest import BAD, ROOT, SCENARIOS, run_cli


def test_loads_a_scenario_and_describes_it():
    s = floornav.load_scenario(SCENARIOS / "rectangle.yaml")
    assert s.name == "rectangle"
    assert s.source == str(SCENARIOS / "rectangle.yaml")
    assert not s.is_fleet and s.controller_kind == "hybrid"
    (robot,) = s.robots
    assert robot["preset"] == "quickbot" and robot["sensor_count"] == 5
    assert robot["goals"] == [(2.4, 0.0)]
    w = s.world
    assert w["bounds"] == (-0.5, -1.2, 3.0, 1.2)
    assert len(w["polygons"]) == 1 and w["polygons"][0].shape == (4, 2)
    assert w["segments"].shape[1] == 4 and w["segments"].shape[0] >= 4
    assert s.params.v0 > 0 and s.params.epsilon == pytest.approx(0.05)


def test_overrides_change_the_scenario_like_set():
    s = floornav.load_scenario(
        SCENARIOS / "rectangle.yaml",
        {"controller.kind": "blended", "sim.dt": 0.02, "robot.start": [0, 0, 1.57],
         "controller.d_o": 0.2},
    )
    assert s.controller_kind == "blended"
    assert s.dt == 0.02
    assert s.robots[0]["start"] == (0.0, 0.0, 1.57)
    assert s.params.d_o == 0.2
    assert s.overrides == ["controller.kind=blended", "sim.dt=0.02", "robot.start=[0, 0, 1.57]",
                           "controller.d_o=0.2"]


def test_override_values_are_written_as_the_yaml_one_would_type():
    r = floornav.render_value
    assert r(0.02) == "0.02"
    assert r(1e-5) == "1e-05"
    assert r(3) == "3"
    assert r(True) == "true" and r(False) == "false"
    assert r(None) == "null"
    assert r(float("nan")) == ".nan" and r(float("-inf")) == "-.inf"
    assert r((1, 2.5)) == "[1, 2.5]"
    assert r([[0, 0], [1, 1]]) == "[[0, 0], [1, 1]]"
    assert r({"beams": 16, "fov": 6.0}) == "{beams: 16, fov: 6.0}"
    assert r("blended") == "blended"  # a top-level string is the --set text itself
    assert r(["a b", "c"]) == '["a b", c]'
    import numpy as np
    assert r(np.array([0.0, 1.5])) == "[0.0, 1.5]"
    assert r(np.float64(0.25)) == "0.25"
    with pytest.raises(TypeError):
        r(object())
    with pytest.raises(TypeError):
        floornav.load_scenario(SCENARIOS / "rectangle.yaml", {1: 2})
    with pytest.raises(TypeError):
        floornav.load_scenario(SCENARIOS / "rectangle.yaml", "sim.dt=0.1")


def test_an_override_gives_the_same_run_as_the_cli(tmp_path):
    sets = {"controller.kind": "hard_switch", "sim.dt": 0.02, "robot.start": [0, 0, 0.3]}
    s = floornav.load_scenario(SCENARIOS / "rectangle.yaml", sets)
    r = floornav.run(s)
    args = []
    for k, v in sets.items():
        args += ["--set", f"{k}={floornav.render_value(v)}"]
    p = run_cli("run", SCENARIOS / "rectangle.yaml", "--out", tmp_path, "--quiet", *args)
    assert p.returncode == 0, p.stderr
    cli = json.loads((tmp_path / "summary.json").read_text())
    ours = dict(r.summary)
    cli.pop("wall_time"), ours.pop("wall_time")
    assert ours == cli
    assert cli["mode_switches"] > 10  # hard switching chatters here: a run worth comparing


def _cli_error_line(*args: str) -> str:
    p = run_cli("run", *args, "--out", "/nonexistent/never-written", "--quiet")
    assert p.returncode == 2, (args, p.stdout, p.stderr)
    lines = p.stderr.splitlines()
    assert len(lines) == 1, lines
    return lines[0]


BAD_SCENARIOS = sorted((BAD / "scenario").glob("*.yaml"))


@pytest.mark.parametrize("path", BAD_SCENARIOS, ids=[p.name for p in BAD_SCENARIOS])
def test_every_bad_scenario_of_the_corpus_gives_the_cli_line(path: pathlib.Path, cli):
    rel = path.relative_to(ROOT)
    with pytest.raises(floornav.InputError) as e:
        s = floornav.load_scenario(rel)  # relative, as the CLI is given it (cwd: the repository)
        floornav.run(s)  # what a run would record is refused when it starts, before a step
    assert str(e.value) == _cli_error_line(str(rel))
    assert isinstance(e.value, ValueError)
    assert e.value.file and e.value.file in str(e.value) and e.value.detail  # names the file
    assert "\n" not in str(e.value)  # one line, whatever the input quoted


def _set_values() -> list[str]:
    lines = (BAD / "set_values.txt").read_text(errors="surrogateescape").splitlines()
    return [l for l in lines if l.strip() and not l.startswith("#")]


@pytest.mark.parametrize("assignment", _set_values())
def test_every_bad_set_value_gives_the_cli_line(assignment: str, cli):
    rel = "scenarios/rectangle.yaml"
    expected = _cli_error_line(rel, "--set", assignment)
    with pytest.raises(floornav.InputError) as e:
        floornav.load_scenario(rel, [assignment])
    assert str(e.value) == expected
    if "=" in assignment and not assignment.startswith("="):
        key, value = assignment.split("=", 1)
        with pytest.raises(floornav.InputError) as e2:  # the dict form: the same text
            floornav.load_scenario(rel, {key: value})
        assert str(e2.value) == expected


def test_a_missing_file_and_a_typo_in_an_override(cli):
    with pytest.raises(floornav.InputError) as e:
        floornav.load_scenario("scenarios/no_such_file.yaml")
    assert str(e.value) == _cli_error_line("scenarios/no_such_file.yaml")
    assert e.value.file == "scenarios/no_such_file.yaml"
    with pytest.raises(floornav.InputError) as e:
        floornav.load_scenario("scenarios/rectangle.yaml", {"controler.kind": "blended"})
    assert str(e.value) == _cli_error_line("scenarios/rectangle.yaml", "--set",
                                           "controler.kind=blended")
    assert str(e.value).startswith("floornav: error: ")
    with pytest.raises(floornav.InputError) as e:
        floornav.load_scenario("scenarios/rectangle.yaml", {"sim.dt": float("nan")})
    assert str(e.value) == _cli_error_line("scenarios/rectangle.yaml", "--set", "sim.dt=.nan")


def test_parse_scenario_from_text():
    text = (SCENARIOS / "week7_pocket.yaml").read_text()
    s = floornav.parse_scenario(text, {"sim.t_max": 5}, origin=SCENARIOS / "week7_pocket.yaml")
    assert s.name == "week7-pocket" and s.t_max == 5.0
    with pytest.raises(floornav.InputError) as e:
        floornav.parse_scenario("world: [", origin="inline.yaml")
    assert str(e.value).startswith("floornav: error: inline.yaml:")
