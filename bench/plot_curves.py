#!/usr/bin/env python3
"""Steps/s against lidar beams and robot-steps/s against fleet size, from one Google Benchmark JSON.

    build/bench/floornav_bench --benchmark_filter='BM_StepBeams|BM_Fleet_QuickBotWarehouse' \\
        --benchmark_out=out/bench/curves.json --benchmark_out_format=json
    python3 bench/plot_curves.py out/bench/curves.json docs/images/scaling_beams_robots.svg

Two log-log panels in a plain SVG (the drawing code of plot_scaling.py): one robot's
Simulation::step against the beams of its 360-degree lidar (5 to 720), and a warehouse fleet of
QuickBots that sense each other (1 to 100,000 robots) on one and on two threads. Prints the table.
"""

import json
import sys

from plot_scaling import COLOURS, GAP, LEFT, PANEL_H, PANEL_W, TOP, W, panel


def runs(benchmarks, prefix):
    """{name: benchmark} of the iteration runs named prefix/..."""
    return {b["name"]: b for b in benchmarks
            if b.get("run_type", "iteration") == "iteration" and b["name"].startswith(prefix + "/")
            and not b.get("error_occurred")}


def main(argv):
    if len(argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    with open(argv[1]) as f:
        data = json.load(f)
    bms = data["benchmarks"]
    beams = sorted((float(n.split("/")[1]), b["items_per_second"])
                   for n, b in runs(bms, "BM_StepBeams_Lidar").items())
    fleet = runs(bms, "BM_Fleet_QuickBotWarehouse")
    by_threads = {}
    for n, b in fleet.items():
        robots, threads = int(n.split("/")[1]), int(n.split("/")[2])
        by_threads.setdefault(threads, []).append((float(robots), b["items_per_second"]))
    fleet_lines = [(f"{t} thread{'s' if t > 1 else ''}", COLOURS[i], sorted(pts))
                   for i, (t, pts) in enumerate(sorted(by_threads.items()))]

    ctx = data.get("context", {})
    caption = (f"{ctx.get('date', '')}, {ctx.get('num_cpus', '?')} CPUs @ "
               f"{ctx.get('mhz_per_cpu', '?')} MHz")
    h = TOP + PANEL_H + 100
    svg = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{h}" '
           f'font-family="sans-serif" font-size="12">',
           f'<rect width="{W}" height="{h}" fill="white"/>',
           f'<text x="{W / 2}" y="20" text-anchor="middle" font-size="14">'
           f'floornav: speed against lidar beams and fleet size (log-log)</text>',
           f'<text x="{W / 2}" y="36" text-anchor="middle" fill="#555">{caption}</text>']
    svg += panel(LEFT, TOP, "one robot, 50-polygon floor, one thread", "robot-steps/s",
                 [("360-degree lidar", COLOURS[1], beams)], xlabel="lidar beams")
    svg += panel(LEFT + PANEL_W + GAP, TOP, "QuickBot fleet sensing each other, warehouse",
                 "robot-steps/s", fleet_lines, xlabel="robots")
    svg.append("</svg>")
    with open(argv[2], "w") as f:
        f.write("\n".join(svg) + "\n")

    print("beams  steps/s")
    for x, y in beams:
        print(f"{int(x):5d} {y:12,.0f}")
    print("robots " + " ".join(f"{name:>14}" for name, _, _ in fleet_lines))
    robots = sorted({x for _, _, pts in fleet_lines for x, _ in pts})
    for r in robots:
        cells = [dict(pts).get(r) for _, _, pts in fleet_lines]
        print(f"{int(r):6d} " + " ".join(f"{c:14,.0f}" if c else " " * 14 for c in cells))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
