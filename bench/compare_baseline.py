#!/usr/bin/env python3
"""A new run against a figure of record: the ratio now/record of every case and benchmark in both.

    python3 bench/compare_baseline.py RECORD.json NOW.json

Either file may be a record (bench/baselines/<machine>/<date>.json), the output of
`floornav bench --json` (its `cases`: robot_steps_per_s) or of Google Benchmark's
`--benchmark_format=json` / `--benchmark_out` (its `benchmarks`: items_per_second, else
1 / cpu_time or real_time in time_unit; the same measure on both sides, so a record kept as a
time is read against the new run's time). A ratio above 1 means NOW is faster. A record is a
reading of another day: a ratio within ~15 % of 1 says nothing on a virtual machine whose speed
drifts; to compare two builds, alternate them (bench/compare_benches.py, compare_builds.py).
"""
import argparse
import json
import sys

SECONDS = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}
# Name parts Google Benchmark appends for options (UseRealTime, MinTime, ...): not the case's.
OPTION_PARTS = ("real_time", "process_time", "manual_time")


def base_name(name):
    parts = [p for p in name.split("/") if p and p not in OPTION_PARTS and ":" not in p]
    return "/".join(parts)


def measures(path):
    """name -> {"items": per second, "time": 1 / s per iteration}, whichever the file gives."""
    with open(path) as f:
        data = json.load(f)
    out = {}
    for c in data.get("cases", []):
        if "robot_steps_per_s" in c:
            out[c["name"]] = {"items": c["robot_steps_per_s"]}
    for b in data.get("benchmarks", []):
        name = b.get("name", "")
        if b.get("run_type") == "aggregate":
            if b.get("aggregate_name") != "median":
                continue  # of --benchmark_repetitions, the median only
            name = b.get("run_name", name)
        m = {}
        if b.get("items_per_second"):
            m["items"] = b["items_per_second"]
        for key in ("cpu_time", "real_time"):
            if b.get(key):
                m["time"] = 1.0 / (b[key] * SECONDS[b.get("time_unit", "ns")])
                break
        if m:
            out[base_name(name)] = m
    return out, data.get("machine")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("record", help="the figures of record (or any run's JSON)")
    ap.add_argument("now", help="the new run's JSON")
    a = ap.parse_args()
    record, record_machine = measures(a.record)
    now, now_machine = measures(a.now)
    rows = []
    for name, r in record.items():
        # The same measure on both sides: items per second where both have it, else 1 / time.
        kind = next((k for k in ("items", "time") if k in r and k in now.get(name, {})), None)
        if kind:
            rows.append((name, kind, r[kind], now[name][kind]))
    if not rows:
        print(f"{a.record} and {a.now} share no case or benchmark name", file=sys.stderr)
        return 2
    for label, machine in (("record", record_machine), ("now", now_machine)):
        if machine:
            print(f"{label}: {machine.get('cpu', '?')}, {machine.get('cores', '?')} cores")
    print(f"{'name':50s} {'per s, record':>14s} {'now':>12s}  now/record")
    for name, kind, r, n in rows:
        unit = "" if kind == "items" else " (1/time)"
        print(f"{name + unit:50s} {r:14.4g} {n:12.4g}  {n / r:.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
