#!/usr/bin/env python3
"""Steps/s and rays/s against obstacle edges, from one Google Benchmark JSON file.

    build/bench/floornav_bench --benchmark_filter='BM_StepEdges|BM_World' \\
        --benchmark_out=out/bench/edges.json --benchmark_out_format=json
    python3 bench/plot_scaling.py out/bench/edges.json docs/images/scaling_edges.svg

Writes a plain SVG (no plotting library needed) with two log-log panels: robot-steps/s of one
Simulation::step (QuickBot 5 IR, 180-beam lidar), and rays/s of World::cast_ray with the grid
index and by brute force. Prints the brute-force / indexed time ratios measured in the same run.
"""

import json
import math
import sys

W = 960
PANEL_W, PANEL_H = 380, 280
LEFT, TOP = 80, 72
GAP = 80
COLOURS = ["#1f77b4", "#d62728", "#2ca02c", "#ff7f0e"]


def series(benchmarks, prefix):
    """[(edges, items_per_second)] of the benchmarks named prefix/N, in edge order."""
    points = []
    for b in benchmarks:
        name = b.get("name", "")
        if b.get("run_type", "iteration") != "iteration" or not name.startswith(prefix + "/"):
            continue
        if "error_occurred" in b and b["error_occurred"]:
            continue
        edges = b.get("edges", float(name.split("/")[1]))
        points.append((edges, b["items_per_second"]))
    return sorted(points)


def nice_ticks(lo, hi):
    """Powers of ten covering [lo, hi]."""
    # A little tolerance: 10,004 edges should not open a decade of empty axis.
    a, b = math.floor(math.log10(lo) + 0.01), math.ceil(math.log10(hi) - 0.01)
    return [10.0**k for k in range(a, b + 1)]


def label(v):
    for unit, div in (("M", 1e6), ("k", 1e3)):
        if v >= div:
            return f"{v / div:g}{unit}"
    return f"{v:g}"


def panel(x0, y0, title, ylabel, lines, xlabel="obstacle edges"):
    """SVG elements of one log-log panel at (x0, y0); lines = [(name, colour, points)]."""
    xs = [p[0] for _, _, pts in lines for p in pts]
    ys = [p[1] for _, _, pts in lines for p in pts]
    if not xs:
        return [f'<text x="{x0}" y="{y0 + 20}">{title}: no data</text>']
    xt, yt = nice_ticks(min(xs), max(xs)), nice_ticks(min(ys), max(ys))
    lx0, lx1 = math.log10(xt[0]), math.log10(xt[-1])
    ly0, ly1 = math.log10(yt[0]), math.log10(yt[-1])

    def px(x):
        return x0 + (math.log10(x) - lx0) / (lx1 - lx0) * PANEL_W

    def py(y):
        return y0 + PANEL_H - (math.log10(y) - ly0) / (ly1 - ly0) * PANEL_H

    out = [f'<text x="{x0 + PANEL_W / 2}" y="{y0 - 14}" text-anchor="middle" '
           f'font-weight="bold">{title}</text>',
           f'<rect x="{x0}" y="{y0}" width="{PANEL_W}" height="{PANEL_H}" fill="none" '
           f'stroke="#444"/>']
    for t in xt:
        out.append(f'<line x1="{px(t):.1f}" y1="{y0}" x2="{px(t):.1f}" y2="{y0 + PANEL_H}" '
                   f'stroke="#ddd"/>')
        out.append(f'<text x="{px(t):.1f}" y="{y0 + PANEL_H + 16}" text-anchor="middle">'
                   f'{label(t)}</text>')
    for t in yt:
        out.append(f'<line x1="{x0}" y1="{py(t):.1f}" x2="{x0 + PANEL_W}" y2="{py(t):.1f}" '
                   f'stroke="#ddd"/>')
        out.append(f'<text x="{x0 - 6}" y="{py(t) + 4:.1f}" text-anchor="end">{label(t)}</text>')
    out.append(f'<text x="{x0 + PANEL_W / 2}" y="{y0 + PANEL_H + 36}" text-anchor="middle">'
               f'{xlabel}</text>')
    out.append(f'<text transform="translate({x0 - 58},{y0 + PANEL_H / 2}) rotate(-90)" '
               f'text-anchor="middle">{ylabel}</text>')
    for i, (name, colour, pts) in enumerate(lines):
        if not pts:
            continue
        path = " ".join(f"{px(x):.1f},{py(y):.1f}" for x, y in pts)
        out.append(f'<polyline points="{path}" fill="none" stroke="{colour}" stroke-width="2"/>')
        for x, y in pts:
            out.append(f'<circle cx="{px(x):.1f}" cy="{py(y):.1f}" r="3" fill="{colour}"/>')
        ly = y0 + PANEL_H + 56 + 16 * i
        out.append(f'<line x1="{x0}" y1="{ly - 4}" x2="{x0 + 24}" y2="{ly - 4}" '
                   f'stroke="{colour}" stroke-width="2"/>')
        out.append(f'<text x="{x0 + 30}" y="{ly}">{name}</text>')
    return out


def main(argv):
    if len(argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    with open(argv[1]) as f:
        data = json.load(f)
    bms = data["benchmarks"]
    steps = [("QuickBot, 5 IR", COLOURS[0], series(bms, "BM_StepEdges_QuickBot5Ir")),
             ("180-beam lidar", COLOURS[1], series(bms, "BM_StepEdges_Lidar180"))]
    indexed = series(bms, "BM_WorldCastRay_Indexed")
    brute = series(bms, "BM_WorldCastRay_BruteForce")
    rays = [("World::cast_ray (grid index)", COLOURS[2], indexed),
            ("brute force (every edge)", COLOURS[3], brute)]

    ctx = data.get("context", {})
    caption = (f"{ctx.get('date', '')}, {ctx.get('num_cpus', '?')} CPUs @ "
               f"{ctx.get('mhz_per_cpu', '?')} MHz, one thread; floors at the density of the "
               f"50-polygon 20 x 20 m floor")
    H_total = TOP + PANEL_H + 100
    svg = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H_total}" '
           f'font-family="sans-serif" font-size="12">',
           f'<rect width="{W}" height="{H_total}" fill="white"/>',
           f'<text x="{W / 2}" y="20" text-anchor="middle" font-size="14">'
           f'floornav: speed against obstacle edges (log-log)</text>',
           f'<text x="{W / 2}" y="36" text-anchor="middle" fill="#555">{caption}</text>']
    svg += panel(LEFT, TOP, "Simulation::step", "robot-steps/s", steps)
    svg += panel(LEFT + PANEL_W + GAP, TOP, "one ray, 3.5 m", "rays/s", rays)
    svg.append("</svg>")
    with open(argv[2], "w") as f:
        f.write("\n".join(svg) + "\n")

    print("edges   indexed rays/s   brute rays/s   brute/indexed time")
    brute_by_edges = dict(brute)
    for e, r in indexed:
        b = brute_by_edges.get(e)
        if b:
            print(f"{int(e):6d} {r:16,.0f} {b:14,.0f} {r / b:20.1f}")
    for name, _, pts in steps:
        if pts:
            print(f"{name}: {pts[0][1]:,.0f} steps/s at {int(pts[0][0])} edges, "
                  f"{pts[-1][1]:,.0f} at {int(pts[-1][0])}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
