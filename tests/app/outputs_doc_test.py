#!/usr/bin/env python3
"""docs/OUTPUTS.md names every key floornav writes.

Runs the built tool (a lone robot with every --record column, a fleet, a fleet with people and
forklifts, a batch of files, a .scen batch, a sweep, a partial merge), reads every summary.json,
results.jsonl line, aggregate.json, sweep.json and CSV header, and fails listing each key, column,
mode or guard name the page does not name (in backticks, or inside a `{a, b}` list).

    outputs_doc_test.py FLOORNAV REPO_ROOT
"""
import csv
import json
import re
import subprocess
import sys
import tempfile
from pathlib import Path

# Objects whose keys are data, not names: mode names (checked as modes), the scenario (keys in
# SCENARIOS.md, checked by the scenario tests), the swept keys (the user's), the optimum sources
# (checked as values), controller kinds (their values are checked as aggregates).
DATA_KEYS = {"mode_time", "config", "swept", "optimal_sources", "by_controller"}


def documented(doc: str):
    """The names the page gives: every backticked span, and the names in `{a, b, c}` lists."""
    spans = set(re.findall(r"`([^`]+)`", doc))
    names = set(spans)
    for span in spans:
        for inner in re.findall(r"\{([^}]*)\}", span):
            names.update(n.strip() for n in inner.split(","))
    return names


def undocumented_keys(obj, names, where, prefix=""):
    """Keys of a summary-like object that the page does not name: top-level keys by name,
    keys of a nested object as `parent.key`, keys of a list's objects by name."""
    missing = []
    for key, value in obj.items():
        path = prefix + key
        if path not in names:
            missing.append(f"{where}: key '{path}'")
        if key in DATA_KEYS:
            continue
        if isinstance(value, dict):
            missing += undocumented_keys(value, names, where, path + ".")
        elif isinstance(value, list):
            for item in value:
                if isinstance(item, dict):
                    if key == "robots":  # a fleet's robots: lone-robot summaries
                        missing += undocumented_keys(item, names, where + " robots[]")
                    else:
                        missing += [f"{where}: key '{path}[].{k}'" for k in item
                                    if k not in names]
    return missing


def modes_and_guards(summary):
    for t in summary.get("transitions", []):
        yield t["from"]
        yield t["to"]
        yield t["guard"]
    yield from summary.get("mode_time", {})
    for r in summary.get("robots", []):
        yield from modes_and_guards(r)


def header(path: Path):
    with path.open(newline="") as f:
        return next(csv.reader(f))


def main():
    floornav, repo = str(Path(sys.argv[1]).resolve()), Path(sys.argv[2]).resolve()
    names = documented((repo / "docs" / "OUTPUTS.md").read_text())
    scen = repo / "scenarios"

    # The checker itself: an unnamed key, nested key, list entry key or mode is reported.
    fake = {"scenario": "x", "no_such_key": 1, "fleet": {"robots": 1, "no_such_count": 2},
            "transitions": [{"t": 0, "no_such_field": 1}]}
    flagged = undocumented_keys(fake, names, "self-test")
    expected = ["self-test: key 'no_such_key'", "self-test: key 'fleet.no_such_count'",
                "self-test: key 'transitions[].no_such_field'"]
    if flagged != expected:
        print(f"the checker is broken: {flagged} != {expected}")
        return 1

    missing = []
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)

        def tool(*args):
            subprocess.run([floornav, *map(str, args)], check=True, cwd=tmp,
                           stdout=subprocess.DEVNULL)

        def check_summary(path):
            s = json.loads(path.read_text())
            missing.extend(undocumented_keys(s, names, str(path.relative_to(tmp))))
            for name in modes_and_guards(s):
                if name and name not in names:
                    missing.append(f"{path.relative_to(tmp)}: mode or guard '{name}'")

        def check_csv(path):
            for column in header(path):
                shown = re.sub(r"^range_\d+$", "range_0", column)
                if shown not in names:
                    missing.append(f"{path.relative_to(tmp)}: column '{column}'")

        def check_transitions(path):
            if ",".join(header(path)) not in names:
                missing.append(f"{path.relative_to(tmp)}: header {header(path)}")
            with path.open(newline="") as f:
                for row in csv.DictReader(f):
                    for name in (row["from"], row["to"], row["guard"]):
                        if name and name not in names:
                            missing.append(f"{path.relative_to(tmp)}: mode or guard '{name}'")

        # A lone robot with every extra column; hard switching and the hybrid automaton.
        for kind in ("hybrid", "hard_switch", "blended", "go_to_goal", "dwa"):
            out = tmp / f"rect-{kind}"
            tool("run", scen / "rectangle.yaml", "--out", out, "--record", "all", "--no-html",
                 "-q", "--set", f"controller.kind={kind}")
            check_summary(out / "summary.json")
            check_csv(out / "trajectory.csv")
            check_transitions(out / "transitions.csv")
        # The planner's own modes and guards.
        out = tmp / "planner"
        tool("run", scen / "week7_pocket.yaml", "--out", out, "--no-html", "-q",
             "--set", "controller.planner.kind=astar")
        check_summary(out / "summary.json")
        # A fleet, and a fleet among people and forklifts.
        for name, path in (("fleet", scen / "fleet_crossing.yaml"),
                           ("crowd", scen / "crowd" / "factory_people.yaml")):
            out = tmp / name
            tool("run", path, "--out", out, "--no-html", "-q", "--record", "all")
            check_summary(out / "summary.json")
            check_csv(out / "trajectory.csv")
            check_transitions(out / "transitions.csv")
        crowd_csv = tmp / "crowd" / "crowd.csv"
        if ",".join(header(crowd_csv)) not in names:
            missing.append(f"crowd.csv: header {header(crowd_csv)}")

        # Batches: files (a lone robot and a fleet), a .scen file, a sweep, a partial merge.
        batches = {
            "files": ["batch", scen / "rectangle.yaml", scen / "fleet_crossing.yaml"],
            "scen": ["batch", scen / "movingai_template.yaml", "--scen",
                     repo / "tests/data/maps/movingai-mapf/room-32-32-4-random-1.scen",
                     "--limit", "2"],
            "sweep": ["sweep", scen / "point_obstacle.yaml", "--grid",
                      "controller.kind=hybrid,blended"],
            "shard": ["batch", scen / "rectangle.yaml", scen / "point_obstacle.yaml",
                      "--shard", "1/2"],
        }
        for name, args in batches.items():
            tool(*args, "--out", tmp / name, "--jobs", "1")
        tool("merge", tmp / "shard", "--allow-partial", "--out", tmp / "merged")
        for name in [*batches, "merged"]:
            out = tmp / name
            for n, line in enumerate((out / "results.jsonl").read_text().splitlines()):
                missing.extend(undocumented_keys(json.loads(line), names,
                                                 f"{name}/results.jsonl line {n + 1}"))
            aggregate = json.loads((out / "aggregate.json").read_text())
            missing.extend(undocumented_keys(aggregate, names, f"{name}/aggregate.json"))
            for kind, values in aggregate["by_controller"].items():
                missing.extend(undocumented_keys(values, names,
                                                 f"{name}/aggregate.json by_controller.{kind}"))
            for source in aggregate.get("optimal_sources", {}):
                if source not in names:
                    missing.append(f"{name}/aggregate.json: optimal source '{source}'")
            sweep = json.loads((out / "sweep.json").read_text())
            missing.extend(undocumented_keys(sweep, names, f"{name}/sweep.json"))

    if missing:
        print("docs/OUTPUTS.md does not name:")
        for m in dict.fromkeys(missing):
            print("  " + m)
        return 1
    print("docs/OUTPUTS.md names every key, column, mode and guard written")
    return 0


if __name__ == "__main__":
    sys.exit(main())
