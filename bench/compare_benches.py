#!/usr/bin/env python3
"""Two builds of floornav_bench, alternated: the ratio B/A of every benchmark, pair by pair.

    python3 bench/compare_benches.py A_BENCH B_BENCH [--filter REGEX] [--pairs 5] [--min-time 2]

Runs A B, B A, A B, ... (the order alternates, so a machine that slows down during the call
weighs on both), each run one process of Google Benchmark with --benchmark_filter and
--benchmark_min_time, and prints for every benchmark the median of the per-pair ratios of
items_per_second (1 / real_time where a benchmark sets no items) and their range. A ratio above
1 means B is faster. Quote medians; a wide range means the machine was noisy.
"""
import argparse
import collections
import json
import statistics
import subprocess


def rates(binary, pattern, min_time):
    out = subprocess.run([binary, f"--benchmark_filter={pattern}",
                          f"--benchmark_min_time={min_time}", "--benchmark_format=json"],
                         capture_output=True, text=True, check=True).stdout
    return {b["name"]: b.get("items_per_second") or 1.0 / b["real_time"]
            for b in json.loads(out)["benchmarks"]}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("a", help="the baseline floornav_bench")
    ap.add_argument("b", help="the floornav_bench compared with it")
    ap.add_argument("--filter", default="^BM_Fleet_QuickBotWarehouse/1000/2/")
    ap.add_argument("--pairs", type=int, default=5)
    ap.add_argument("--min-time", default="2")
    args = ap.parse_args()
    seen = {"a": collections.defaultdict(list), "b": collections.defaultdict(list)}
    for pair in range(args.pairs):
        for side in ("a", "b") if pair % 2 == 0 else ("b", "a"):
            for name, rate in rates(getattr(args, side), args.filter, args.min_time).items():
                seen[side][name].append(rate)
    print(f"B/A over {args.pairs} alternated pairs (A = {args.a}, B = {args.b})")
    for name, a_rates in seen["a"].items():
        ratios = [b / a for a, b in zip(a_rates, seen["b"][name])]
        print(f"{name:60s} {statistics.median(ratios):6.3f}x  "
              f"({min(ratios):.3f}-{max(ratios):.3f})")


if __name__ == "__main__":
    main()
