"""floornav.batch: the command line's results.jsonl lines, in order, on any number of threads;
Python controllers on one thread; an exception ends the batch and writes nothing."""

from __future__ import annotations

import json
import threading

import pytest

import floornav
from conftest import SCENARIOS, run_cli

PATHS = [f"scenarios/{n}.yaml" for n in
         ["rectangle", "week7_pocket", "circle_obstacle", "concave_obstacle", "point_obstacle",
          "practice2_pillars", "fleet_crossing"]]


def cli_batch(tmp_path, *args):
    out = tmp_path / "cli"
    p = run_cli("batch", *args, "--out", out)
    assert p.returncode == 0, p.stderr
    lines = [json.loads(l) for l in (out / "results.jsonl").read_text().splitlines()]
    return out, lines, json.loads((out / "aggregate.json").read_text())


def test_batch_lines_equal_the_cli_results(tmp_path):
    out, cli_lines, cli_aggregate = cli_batch(tmp_path, *PATHS, "--no-timing")
    ours = floornav.batch(PATHS, timing=False)
    assert isinstance(ours, list) and len(ours) == len(PATHS)
    assert list(ours) == cli_lines
    # A Python batch has no sweep id (its inputs are objects, not files); every other key agrees.
    assert ours.aggregate.pop("sweep_id") is None and cli_aggregate.pop("sweep_id")
    assert ours.aggregate == cli_aggregate
    assert [l["case"] for l in ours] == list(range(len(PATHS)))
    assert [l["source"] for l in ours] == PATHS
    assert ours[-1]["fleet"]["robots"] == 4  # the fleet case is a fleet line


def test_batch_with_timing_differs_only_in_wall_time(tmp_path):
    _, cli_lines, _ = cli_batch(tmp_path, *PATHS[:3])
    ours = floornav.batch([floornav.load_scenario(p) for p in PATHS[:3]], jobs=2)
    for a, b in zip(ours, cli_lines):
        assert a["wall_time"] > 0 and b["wall_time"] > 0
        a.pop("wall_time"), b.pop("wall_time")
        assert a == b


def test_batch_with_overrides_equals_the_cli_with_set(tmp_path):
    sets = {"controller.kind": "blended", "sim.dt": 0.02}
    _, cli_lines, _ = cli_batch(tmp_path, *PATHS[:4], "--no-timing", "--set", "controller.kind=blended",
                                "--set", "sim.dt=0.02")
    ours = floornav.batch([floornav.load_scenario(p, sets) for p in PATHS[:4]], timing=False)
    assert list(ours) == cli_lines
    assert all(l["controller"] == "blended" for l in ours)


def test_any_number_of_jobs_gives_the_same_lines():
    one = floornav.batch(PATHS, jobs=1, timing=False)
    two = floornav.batch(PATHS, jobs=2, timing=False)
    many = floornav.batch(PATHS, jobs=16, timing=False)
    assert list(one) == list(two) == list(many)


def test_out_writes_the_cli_files_byte_for_byte(tmp_path):
    cli_out, _, _ = cli_batch(tmp_path, *PATHS, "--no-timing")
    floornav.batch(PATHS, timing=False, out=tmp_path / "py")
    name = "results.jsonl"
    assert (tmp_path / "py" / name).read_bytes() == (cli_out / name).read_bytes(), name
    # aggregate.json: the same but for the sweep id (Python's fingerprints its scenarios).
    ours = json.loads((tmp_path / "py" / "aggregate.json").read_text())
    cli = json.loads((cli_out / "aggregate.json").read_text())
    assert ours.pop("sweep_id").startswith("py") and cli.pop("sweep_id")
    assert ours == cli
    sweep = json.loads((tmp_path / "py" / "sweep.json").read_text())
    assert (sweep["shard"], sweep["shards"], sweep["cases"]) == (1, 1, len(PATHS))


def test_no_optimum_skips_the_grid_astar(tmp_path):
    _, cli_lines, _ = cli_batch(tmp_path, *PATHS[:2], "--no-timing", "--no-optimum")
    ours = floornav.batch(PATHS[:2], timing=False, optimum=False)
    assert list(ours) == cli_lines
    assert "optimal_length" not in ours[0]


class Circle:
    """A stateful Python controller: drives a circle and records on which thread it runs."""

    def __init__(self):
        self.threads = set()
        self.calls = 0

    def reset(self):
        self.calls = 0

    def decide(self, obs):
        self.threads.add(threading.get_ident())
        self.calls += 1
        return (0.1, 0.4)


def test_python_controllers_run_on_one_thread_in_order():
    ctl = Circle()
    scenarios = [floornav.load_scenario(p, {"sim.t_max": 2}).with_controller(ctl, kind="circle")
                 for p in PATHS[:4]]
    lines = floornav.batch(scenarios, jobs=2)
    assert len(ctl.threads) == 1  # one worker thread ran every case
    assert [l["controller"] for l in lines] == ["circle"] * 4
    assert [l["status"] for l in lines] == ["timeout"] * 4
    assert all(l["steps"] == 200 for l in lines)
    assert all(l["mode_time"] == {"circle": pytest.approx(2.0)} for l in lines)


def test_an_exception_in_a_controller_ends_the_batch_and_writes_nothing(tmp_path):
    calls = []

    def explode(obs):
        calls.append(obs["t"])
        if len(calls) == 52:
            raise ZeroDivisionError("controller failed at t = %.2f" % obs["t"])
        return (0.1, 0.0)

    scenarios = [floornav.load_scenario(p).with_controller(explode) for p in PATHS[:3]]
    with pytest.raises(ZeroDivisionError, match="controller failed at t = 0.51") as e:
        floornav.batch(scenarios, out=tmp_path / "out")
    assert any(f.name == "explode" for f in e.traceback)  # the controller's frame is kept
    assert not (tmp_path / "out").exists()


def test_bad_arguments():
    with pytest.raises(ValueError):
        floornav.batch(PATHS[:1], jobs=0)
    with pytest.raises(floornav.InputError):
        floornav.batch(["scenarios/no_such.yaml"])
    assert floornav.batch([]) == []


def test_ctrl_c_stops_a_batch_and_a_run():
    import os
    import signal

    def far(goal_x):
        return floornav.load_scenario("scenarios/rectangle.yaml",
                                      {"sim.t_max": 1e6, "goal": [goal_x, 0],
                                       "world.bounds": [-30000, -30000, 30000, 30000],
                                       "sim.record_trajectory": False})

    # A batch takes no new case once interrupted (those under way finish): many medium cases.
    # A run stops within a few thousand steps: one very long run (13 million steps).
    calls = [lambda: floornav.batch([far(300)] * 200, jobs=2), lambda: floornav.run(far(20000))]
    for call in calls:
        timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
        timer.start()
        try:
            with pytest.raises(KeyboardInterrupt):
                call()
        finally:
            timer.cancel()
