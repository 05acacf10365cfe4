"""Never crash, never lie, from Python (docs/RELIABILITY.md): the classes issue 37 closed. Each
bad call raises the one exception it should (ValueError, floornav.InputError, RuntimeError),
at once, and leaves nothing half done."""

from __future__ import annotations

import json
import math

import pytest

import floornav
from conftest import ROOT, SCENARIOS, run_cli

RECT = SCENARIOS / "rectangle.yaml"


def _short(**sets):
    return floornav.load_scenario(RECT, {"sim.t_max": 2.0, **sets})


# ---- a controller that calls back into its own simulation ----------------------------------------

@pytest.mark.parametrize("call", ["reset", "step", "observe"])
def test_a_controller_cannot_reset_or_step_its_own_simulation(call):
    holder = {}

    def controller(obs):
        getattr(holder["sim"], call)()  # would free (or re-enter) the run under way
        return (0.1, 0.0)

    sim = floornav.Simulation(_short().with_controller(controller))
    holder["sim"] = sim
    sim.reset()
    with pytest.raises(RuntimeError, match="from inside this simulation's own step"):
        sim.step()
    # The simulation is whole afterwards: it resets and runs with a well-behaved controller.
    sim2 = floornav.Simulation(_short())
    obs = sim2.reset()
    assert obs["status"] == "running" and sim.reset()["status"] == "running"


# ---- bounds that hold before anything is allocated or started -----------------------------------

def test_vec_env_bounds_its_threads_and_copies():
    s = _short()
    with pytest.raises(ValueError, match="threads must be at most 1024"):
        floornav.VecEnv(s, 2, threads=100000)
    with pytest.raises(ValueError, match="n_envs must be at most 100000"):
        floornav.VecEnv(s, 10**9)
    with pytest.raises(ValueError, match="seed must be below 2\\*\\*64"):
        floornav.VecEnv(s, 2, seed=2**64)


@pytest.mark.parametrize("weights", [{"progress": math.nan}, {"goal": math.inf},
                                     {"collision": -math.inf}, {"time": 1e300}])
def test_reward_weights_are_finite(weights):
    with pytest.raises(ValueError, match="a reward weight is a finite number"):
        floornav.RewardParams(**weights)
    with pytest.raises(ValueError, match="a reward weight is a finite number"):
        floornav.VecEnv(_short(), 2, reward=weights)
    r = floornav.RewardParams()
    key, value = next(iter(weights.items()))
    with pytest.raises(ValueError):
        setattr(r, key, value)
    assert getattr(r, key) == getattr(floornav.RewardParams(), key)  # unchanged
    with pytest.raises(ValueError, match="unknown reward weight"):
        floornav.VecEnv(_short(), 2, reward={"progres": 1.0})


@pytest.mark.parametrize("seed", [2**64, 2**100, -1, 1.5, True, "3"])
def test_seeds_out_of_range_are_value_errors(seed):
    sim = floornav.Simulation(_short())
    with pytest.raises(ValueError, match="seed"):
        sim.reset(seed=seed)
    with pytest.raises(ValueError, match="seed"):
        _short().with_seed(seed)
    assert sim.reset(seed=2**64 - 1)["status"] == "running"


# ---- text that is not UTF-8, and lone surrogates --------------------------------------------------

def test_lone_surrogates_are_input_errors_not_unicode_errors():
    # Surrogate escapes of undecodable bytes (os.fsdecode) are those bytes: the CLI's message.
    with pytest.raises(floornav.InputError, match="byte 0xe9 is not UTF-8") as e:
        floornav.load_scenario(RECT, {"name": "caf\udce9"})
    assert e.value.where == "--set name=caf\udce9"
    with pytest.raises(floornav.InputError, match="byte 0xe9 is not UTF-8"):
        floornav.parse_scenario("name: caf\udce9\n" + RECT.read_text())
    # Any other lone surrogate is no text at all.
    for bad in ({"name": "a\ud800b"}, ["robot.start=[0, 0, \udfff]"]):
        with pytest.raises(floornav.InputError, match="lone surrogate"):
            floornav.load_scenario(RECT, bad)
    with pytest.raises(floornav.InputError, match="U\\+D800"):
        floornav.load_scenario("scenarios/\ud800.yaml")
    with pytest.raises(floornav.InputError, match="lone surrogate"):
        floornav.parse_scenario("name: a\ud83db\n" + RECT.read_text())


# ---- batch: ids, shards and the folder merge checks ------------------------------------------------

PATHS = [f"scenarios/{n}.yaml" for n in ["rectangle", "circle_obstacle", "point_obstacle"]]


def test_batch_ids_are_each_case_once_and_in_range(tmp_path):
    with pytest.raises(ValueError, match="case 4 is given twice"):
        floornav.batch(PATHS, ids=[4, 1, 4])
    for bad in (2**64, -1, 1.5, True):
        with pytest.raises(ValueError, match="a case number is an integer"):
            floornav.batch(PATHS, ids=[0, 1, bad])
    with pytest.raises(ValueError, match="out= with ids="):
        floornav.batch(PATHS, ids=[0, 1, 2], out=tmp_path / "o")
    assert not (tmp_path / "o").exists()
    for bad in ((0, 2), (3, 2), (1, 2, 3), "1/2", (1, 2_000_000)):
        with pytest.raises(ValueError, match="shard is"):
            floornav.batch(PATHS, shard=bad)


def test_python_shards_merge_with_the_command_line(tmp_path):
    for k in (1, 2):
        floornav.batch(PATHS, timing=False, shard=(k, 2), out=tmp_path / f"s{k}")
        sweep = json.loads((tmp_path / f"s{k}" / "sweep.json").read_text())
        assert (sweep["shard"], sweep["shards"], sweep["cases"]) == (k, 2, 3)
    p = run_cli("merge", tmp_path / "s1", tmp_path / "s2", "--out", tmp_path / "merged")
    assert p.returncode == 0, p.stderr
    whole = floornav.batch(PATHS, timing=False, out=tmp_path / "whole")
    assert (tmp_path / "merged" / "results.jsonl").read_text() == \
        (tmp_path / "whole" / "results.jsonl").read_text()
    # Another sweep's shard (other overrides: another fingerprint) does not merge with these.
    other = [floornav.load_scenario(p, {"sim.seed": 7}) for p in PATHS]
    floornav.batch(other, timing=False, shard=(2, 2), out=tmp_path / "other")
    p = run_cli("merge", tmp_path / "s1", tmp_path / "other", "--out", tmp_path / "mixed")
    assert p.returncode == 2 and "mixed sweeps cannot be merged" in p.stderr, p.stderr
    # A Python folder is resumed by the command line only as its own sweep: refused.
    p = run_cli("batch", *PATHS, "--no-timing", "--resume", "--out", tmp_path / "whole")
    assert p.returncode == 2 and "not shard 1/1 of this sweep" in p.stderr, p.stderr


def test_a_batch_into_a_read_only_place_is_an_os_error(tmp_path):
    with pytest.raises(OSError, match="cannot write"):
        floornav.batch(PATHS[:1], out="/proc/floornav-cannot-write-here")
