"""docs/PYTHON.md's pattern for floornav.batch shards on Dask's distributed scheduler (Debian's
python3-distributed), run as written on a local cluster: the merged lines equal one CLI batch."""

from __future__ import annotations

import json

import pytest

import floornav
from conftest import ROOT, run_cli

distributed = pytest.importorskip("distributed")

PATHS = [f"scenarios/{n}.yaml" for n in
         ["rectangle", "week7_pocket", "circle_obstacle", "concave_obstacle", "point_obstacle",
          "convex_obstacle", "practice2_pillars"]]


def run_shard(paths, ids, overrides):
    """One task: a shard of the sweep on one worker, its lines numbered as in the whole sweep."""
    import floornav

    scenarios = [floornav.load_scenario(p, overrides) for p in paths]
    return list(floornav.batch(scenarios, jobs=1, timing=False, ids=ids))


def test_shards_on_a_local_dask_cluster_equal_one_cli_batch(tmp_path, monkeypatch):
    monkeypatch.chdir(ROOT)  # the workers read the scenario paths relative to here
    overrides = {"controller.kind": "blended"}
    shards = 3
    ids = list(range(len(PATHS)))
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        futures = [client.submit(run_shard, PATHS[k::shards], ids[k::shards], overrides)
                   for k in range(shards)]
        lines = sorted((l for shard in client.gather(futures) for l in shard),
                       key=lambda l: l["case"])
    p = run_cli("batch", *PATHS, "--no-timing", "--set", "controller.kind=blended",
                "--out", tmp_path)
    assert p.returncode == 0, p.stderr
    cli = [json.loads(l) for l in (tmp_path / "results.jsonl").read_text().splitlines()]
    assert lines == cli
    assert [l["case"] for l in lines] == ids


def test_ids_number_the_lines():
    lines = floornav.batch(PATHS[:2], ids=[10, 4], timing=False)
    assert [l["case"] for l in lines] == [10, 4]
    with pytest.raises(ValueError):
        floornav.batch(PATHS[:2], ids=[1])
