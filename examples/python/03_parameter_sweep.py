"""A parameter sweep with floornav.batch, to a CSV (no pandas) and a plot.

How far ahead should the robot start following a wall (d_o, the distance at which the hybrid
automaton of Fig 5.11 meets an obstacle), and how fast may it cruise (v0)? Every combination
runs on every chapter scenario, on all cores (floornav.batch releases the GIL); each result is a
line of the command line's results.jsonl, so the CSV holds exactly what `floornav batch` reports.

Run: PYTHONPATH=build/python /usr/bin/python3 examples/python/03_parameter_sweep.py
"""

from __future__ import annotations

import argparse
import csv
import itertools
import pathlib
import time

import floornav

HERE = pathlib.Path(__file__).resolve().parent
SCENARIOS = HERE.parents[1] / "scenarios"
CHAPTER = ["rectangle", "convex_obstacle", "concave_obstacle", "circle_obstacle",
           "week7_pocket", "factory_delivery"]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default="out/examples", help="folder for the CSV and the plot")
    ap.add_argument("--quick", action="store_true", help="a 2 x 2 grid on two scenarios (for CI)")
    ap.add_argument("--jobs", type=int, default=None, help="threads (default: all cores)")
    args = ap.parse_args(argv)
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    d_o = [0.10, 0.16] if args.quick else [0.09, 0.10, 0.12, 0.16, 0.20, 0.25]  # > d_fb (0.08)
    v0 = [0.10, 0.20] if args.quick else [0.08, 0.12, 0.15, 0.20, 0.25]
    names = CHAPTER[:2] if args.quick else CHAPTER

    grid = list(itertools.product(d_o, v0, names))
    scenarios = [floornav.load_scenario(SCENARIOS / f"{n}.yaml",
                                        {"controller.kind": "hybrid", "controller.d_o": a,
                                         "controller.v0": b})
                 for a, b, n in grid]
    t0 = time.perf_counter()
    lines = floornav.batch(scenarios, jobs=args.jobs, optimum=False)
    wall = time.perf_counter() - t0
    print(f"{len(lines)} runs in {wall:.2f} s; success {100 * lines.aggregate['success_rate']:.0f} %")

    columns = ["d_o", "v0", "scenario", "status", "sim_time", "path_length", "min_clearance",
               "mode_switches"]
    table = out / "03_parameter_sweep.csv"
    with open(table, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(columns)
        for (a, b, _), line in zip(grid, lines):
            w.writerow([a, b] + [line[c] for c in columns[2:]])
    print(f"-> {table}")

    # Per (d_o, v0): the share of scenarios reached and the mean time of those reached.
    cells = {}
    for (a, b, _), line in zip(grid, lines):
        c = cells.setdefault((a, b), [0, 0, 0.0])
        c[0] += 1
        if line["status"] == "reached":
            c[1] += 1
            c[2] += line["sim_time"]
    print("   d_o    v0  reached  mean time (s)")
    for (a, b), (n, ok, t) in sorted(cells.items()):
        print(f"  {a:4.2f}  {b:4.2f}  {ok}/{n}      {t / ok if ok else float('nan'):6.1f}")

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    success = np.array([[cells[(a, b)][1] / cells[(a, b)][0] for a in d_o] for b in v0])
    fig, ax = plt.subplots(figsize=(6, 4.5))
    im = ax.imshow(success, origin="lower", cmap="viridis", vmin=0, vmax=1, aspect="auto")
    ax.set_xticks(range(len(d_o)), [f"{a:.2f}" for a in d_o])
    ax.set_yticks(range(len(v0)), [f"{b:.2f}" for b in v0])
    ax.set_xlabel("d_o (m): where an obstacle is met")
    ax.set_ylabel("v0 (m/s): cruise speed")
    ax.set_title(f"hybrid automaton: share of {len(names)} chapter scenarios reached")
    for (j, b), (k, a) in itertools.product(enumerate(v0), enumerate(d_o)):
        n, ok, t = cells[(a, b)]
        ax.text(k, j, f"{ok}/{n}\n{t / ok:.0f} s" if ok else f"0/{n}", ha="center", va="center",
                fontsize=7, color="white" if success[j, k] < 0.6 else "black")
    fig.colorbar(im, ax=ax, label="reached")
    picture = out / "03_parameter_sweep.png"
    fig.savefig(picture, dpi=90, bbox_inches="tight")
    plt.close(fig)
    print(f"-> {picture}")
    return lines


if __name__ == "__main__":
    main()
