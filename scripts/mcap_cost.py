#!/usr/bin/env python3
"""What writing run.mcap costs a run: whole `floornav run` processes without and with `--mcap`,
alternated (so that both sides share the machine's changes of speed), after a warm-up pair.

    python3 scripts/mcap_cost.py SCENARIO [--pairs 30] [--floornav build/floornav]

Prints, for wall time and for CPU time (user + sys of the process), the ratio of the two medians
and the median of the pair-by-pair ratios (docs/PERFORMANCE.md, "run.mcap's cost"). Outputs go to
a temporary directory that is removed at the end.
"""
import argparse
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path


def run_once(floornav, scenario, out, mcap):
    cmd = [floornav, "run", scenario, "--quiet", "--no-html", "--out", str(out)]
    if mcap:
        cmd.append("--mcap")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu


def ratios(plain, bag):
    medians = statistics.median(bag) / statistics.median(plain)
    pairs = statistics.median(b / a for a, b in zip(plain, bag))
    return medians, pairs


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("scenario")
    ap.add_argument("--pairs", type=int, default=30)
    ap.add_argument("--floornav", default="build/floornav")
    args = ap.parse_args()
    if args.pairs < 1:
        ap.error("--pairs must be at least 1")
    if not Path(args.floornav).is_file():
        ap.error(f"{args.floornav}: no such file (build first, or pass --floornav)")
    with tempfile.TemporaryDirectory(prefix="mcap_cost_") as tmp:
        run_once(args.floornav, args.scenario, Path(tmp) / "p", False)
        run_once(args.floornav, args.scenario, Path(tmp) / "m", True)
        plain, bag = [], []
        for _ in range(args.pairs):
            plain.append(run_once(args.floornav, args.scenario, Path(tmp) / "p", False))
            bag.append(run_once(args.floornav, args.scenario, Path(tmp) / "m", True))
    wall = ratios([p[0] for p in plain], [b[0] for b in bag])
    cpu = ratios([p[1] for p in plain], [b[1] for b in bag])
    print(f"{args.scenario}: {args.pairs} pairs; without the bag: wall "
          f"{statistics.median(p[0] for p in plain) * 1e3:.1f} ms, CPU "
          f"{statistics.median(p[1] for p in plain) * 1e3:.1f} ms")
    print(f"  wall ratio {wall[0]:.3f} (pairs {wall[1]:.3f}); CPU ratio {cpu[0]:.3f} "
          f"(pairs {cpu[1]:.3f})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
