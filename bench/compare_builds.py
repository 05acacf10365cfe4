#!/usr/bin/env python3
"""Times several floornav builds on one scenario, interleaved, and prints their speed ratios.

Usage: compare_builds.py [--rounds N] SCENARIO.yaml BASE_FLOORNAV OTHER_FLOORNAV...

Each round runs `floornav batch SCENARIO --jobs 1 --no-optimum` once with every build (in turn,
the order reversed every other round) and reads the robot-steps per second from results.jsonl
(robot steps over its wall_time, which times the simulation alone). A build's ratio is the
median over the rounds of its rate over the base's rate in the same round: a round's runs are a
second or two apart, so the ratio holds when the machine's speed drifts between rounds.
"""
import argparse
import json
import os
import statistics
import subprocess
import tempfile


def rate(floornav, scenario, out):
    subprocess.run([floornav, "batch", scenario, "--jobs", "1", "--no-optimum", "--out", out],
                   cwd=os.path.dirname(os.path.abspath(scenario)), check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    steps = seconds = 0.0
    with open(os.path.join(out, "results.jsonl")) as f:
        for line in f:
            case = json.loads(line)
            steps += case.get("fleet", {}).get("robot_steps", case["steps"])
            seconds += case["wall_time"]
    return steps / seconds


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rounds", type=int, default=15)
    ap.add_argument("scenario")
    ap.add_argument("builds", nargs="+", help="floornav executables, the first the base")
    a = ap.parse_args()
    rates = {b: [] for b in a.builds}
    with tempfile.TemporaryDirectory() as tmp:
        for r in range(a.rounds):
            for b in a.builds if r % 2 == 0 else reversed(a.builds):
                rates[b].append(rate(os.path.abspath(b), a.scenario, tempfile.mkdtemp(dir=tmp)))
    base = rates[a.builds[0]]
    print(f"{a.rounds} rounds of {a.scenario}, robot-steps/s")
    for b in a.builds:
        ratios = [x / y for x, y in zip(rates[b], base)]
        print(f"{b:40} median {statistics.median(rates[b]) / 1e3:7.1f} k (max "
              f"{max(rates[b]) / 1e3:.1f} k)  ratio to the base {statistics.median(ratios):.3f} "
              f"(quartiles {statistics.quantiles(ratios, n=4)[0]:.3f}-"
              f"{statistics.quantiles(ratios, n=4)[2]:.3f})")


if __name__ == "__main__":
    main()
