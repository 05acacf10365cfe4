"""floornav.run: the summary, trajectory and transition log equal the command line's files."""

from __future__ import annotations

import csv
import json

import numpy as np
import pytest

import floornav
from conftest import SCENARIOS, run_cli

CONTRACT_KEYS = ["scenario", "status", "reached_goal", "collided", "sim_time", "path_length",
                 "min_clearance", "mode_switches", "mode_time", "steps", "wall_time"]
COLUMNS = ["t", "x", "y", "theta", "v", "omega", "w_left", "w_right", "mode"]


def cli_run(tmp_path, name, *sets):
    out = tmp_path / "cli"
    p = run_cli("run", SCENARIOS / name, "--out", out, "--quiet", *sets)
    assert p.returncode == 0, p.stderr
    summary = json.loads((out / "summary.json").read_text())
    with open(out / "trajectory.csv", newline="") as f:
        rows = list(csv.reader(f))
    return summary, rows


def without_wall_time(d):
    d = dict(d)
    d.pop("wall_time")
    return d


@pytest.mark.parametrize("name", ["rectangle.yaml", "factory_delivery.yaml", "week7_pocket.yaml"])
def test_run_equals_the_cli(tmp_path, name):
    r = floornav.run(floornav.load_scenario(SCENARIOS / name))
    summary, rows = cli_run(tmp_path, name)
    assert list(r.summary)[: len(CONTRACT_KEYS)] == CONTRACT_KEYS
    assert without_wall_time(r.summary) == without_wall_time(summary)
    assert r.summary["status"] == "reached" and r.status == "reached"
    assert r.summary["wall_time"] > 0
    header, body = rows[0], rows[1:]
    assert header == COLUMNS
    t = r.trajectory
    assert list(t) == COLUMNS
    assert len(t["x"]) == len(body) == r.summary["steps"] + 1
    for j, col in enumerate(COLUMNS[:-1]):
        # The CSV holds the shortest text that reads back to the same double: exact equality.
        assert np.array_equal(t[col], np.array([float(row[j]) for row in body])), col
        assert t[col].dtype == np.float64
    assert t["mode"].tolist() == [row[8] for row in body]


def test_the_transition_log_has_guard_names_and_matches_the_summary():
    r = floornav.run(floornav.load_scenario(SCENARIOS / "rectangle.yaml"))
    log = r.transitions
    assert [tr["guard"] for tr in log] == ["obstacle_ahead_cw", "progress_and_clear_shot", "at_goal"]
    assert [(tr["from"], tr["to"]) for tr in log] == [
        ("go_to_goal", "follow_boundary_cw"), ("follow_boundary_cw", "go_to_goal"),
        ("go_to_goal", "stop")]
    assert log == r.summary["transitions"]
    assert r.mode_names == ["go_to_goal", "follow_boundary_cw", "follow_boundary_ccw",
                            "avoid_obstacle", "stop"]


def test_a_chattering_run_keeps_its_whole_log():
    r = floornav.run(floornav.load_scenario(SCENARIOS / "rectangle.yaml",
                                            {"controller.kind": "hard_switch"}))
    assert r.summary["chatter_episodes"] >= 1
    assert len(r.transitions) == r.summary["mode_switches"] > 100  # Fig 5.9: Zeno chatter
    guards = [tr["guard"] for tr in r.transitions]
    assert set(guards[:-1]) == {"obstacle_within_d_o", "obstacle_beyond_d_o"}
    assert guards[-1] == "at_goal"
    times = [tr["t"] for tr in r.transitions]
    assert times == sorted(times)


def test_write_gives_the_cli_files(tmp_path):
    r = floornav.run(floornav.load_scenario(SCENARIOS / "rectangle.yaml"))
    r.write(tmp_path / "py")
    summary, rows = cli_run(tmp_path, "rectangle.yaml")
    assert (tmp_path / "py" / "trajectory.csv").read_text().splitlines() == [",".join(x) for x in rows]
    ours = json.loads((tmp_path / "py" / "summary.json").read_text())
    assert without_wall_time(ours) == without_wall_time(summary)
    assert (tmp_path / "py" / "trajectory.svg").read_text().startswith("<svg")
    # run(out=...) writes the same files
    floornav.run(SCENARIOS / "rectangle.yaml", out=tmp_path / "py2")
    assert (tmp_path / "py2" / "trajectory.csv").read_text() == (tmp_path / "py" / "trajectory.csv").read_text()


def test_a_fleet_run_equals_the_cli(tmp_path):
    s = floornav.load_scenario(SCENARIOS / "fleet_crossing.yaml")
    assert s.is_fleet and len(s.robots) == 4
    r = floornav.run(s, threads=2)
    summary, rows = cli_run(tmp_path, "fleet_crossing.yaml")
    assert without_wall_time(r.summary) == without_wall_time(summary)
    for a, b in zip(r.summary["robots"], summary["robots"]):
        assert without_wall_time(a) == without_wall_time(b)
    t = r.trajectory
    assert list(t) == COLUMNS + ["robot"]
    assert rows[0] == COLUMNS + ["robot"]
    assert t["robot"].tolist() == [row[9] for row in rows[1:]]
    assert np.array_equal(t["x"], np.array([float(row[1]) for row in rows[1:]]))
    assert r.transitions == []  # fleets count switches only


def test_run_without_recording_has_an_empty_trajectory():
    r = floornav.run(floornav.load_scenario(SCENARIOS / "rectangle.yaml",
                                            {"sim.record_trajectory": False}))
    assert r.status == "reached"
    assert all(len(v) == 0 for v in r.trajectory.values())


def test_an_empty_unbounded_world_runs_and_its_clearance_is_none():
    # The chapter's go-to-goal with no obstacle: nothing bounds the clearance, so the summary has
    # None (summary.json's null), never inf or NaN, and the run reaches the goal.
    s = floornav.parse_scenario("name: open-floor\nworld: {}\n"
                                "robot: {preset: quickbot, start: [0, 0, 0]}\ngoal: [2, 1]\n")
    r = floornav.run(s)
    assert r.summary["status"] == "reached"
    assert "min_clearance" in r.summary and r.summary["min_clearance"] is None
