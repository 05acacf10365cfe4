#!/usr/bin/env python3
"""Writes N small generated floors as scenario files, for timing `floornav batch`.

    python3 bench/make_batch_floors.py OUT_DIR [--floors 40] [--side 10] [--polygons 12]

Each floor is built the way app/bench_cases.cpp builds the bench floor (make_bench_floor): a
walled square [0, side]^2 with random star-shaped polygons (3-8 vertices, circumscribed radii
0.3-0.9 m, discs 0.6 m apart and 0.3 m off the walls), at the bench floor's density (50 polygons
on 20 x 20 m is 12.5 per 100 m^2). A QuickBot (hybrid controller) starts at a free point and
visits two free goals across the floor. Fixed seeds: the same files on every machine (Python's
own generator, so not the C++ floors' coordinates). Writes floor_01.yaml ... floor_NN.yaml.

    floornav batch OUT_DIR/floor_*.yaml --jobs 1 --no-timing --out out/floors
"""
import argparse
import math
import os
import random


def star_polygon(cx, cy, radius, vertices, rng):
    step = 2 * math.pi / vertices
    phase = rng.uniform(0, step)
    poly = []
    for i in range(vertices):
        a = phase + i * step + rng.uniform(-step / 3, step / 3)
        r = radius * rng.uniform(0.6, 1.0)
        poly.append((round(cx + r * math.cos(a), 4), round(cy + r * math.sin(a), 4)))
    return poly


def inside(poly, x, y):
    c = False
    for i in range(len(poly)):
        (x1, y1), (x2, y2) = poly[i], poly[i - 1]
        if (y1 > y) != (y2 > y) and x < x1 + (y - y1) * (x2 - x1) / (y2 - y1):
            c = not c
    return c


def seg_dist(px, py, ax, ay, bx, by):
    dx, dy = bx - ax, by - ay
    t = max(0.0, min(1.0, ((px - ax) * dx + (py - ay) * dy) / (dx * dx + dy * dy)))
    return math.hypot(px - ax - t * dx, py - ay - t * dy)


def clearance(polys, side, x, y):
    c = min(x, y, side - x, side - y)
    for p in polys:
        if inside(p, x, y):
            return -1.0
        for i in range(len(p)):
            c = min(c, seg_dist(x, y, *p[i - 1], *p[i]))
    return c


def make_floor(seed, side, polygons):
    rng = random.Random(seed)
    discs = []
    for _ in range(1000 * (polygons + 10)):
        if len(discs) == polygons:
            break
        r = rng.uniform(0.3, 0.9)
        lo, hi = r + 0.3, side - r - 0.3
        d = (rng.uniform(lo, hi), rng.uniform(lo, hi), r)
        if all(math.hypot(d[0] - o[0], d[1] - o[1]) >= d[2] + o[2] + 0.6 for o in discs):
            discs.append(d)
    polys = [star_polygon(x, y, r, rng.randint(3, 8), rng) for x, y, r in discs]

    def free_point():
        while True:
            x, y = rng.uniform(0, side), rng.uniform(0, side)
            if clearance(polys, side, x, y) >= 0.375:
                return (round(x, 3), round(y, 3))

    start = free_point()
    goals, prev = [], start
    while len(goals) < 2:
        g = free_point()
        if math.hypot(g[0] - prev[0], g[1] - prev[1]) >= side / 2:
            goals.append(g)
            prev = g
    return polys, start, round(rng.uniform(-math.pi, math.pi), 3), goals


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out_dir")
    ap.add_argument("--floors", type=int, default=40)
    ap.add_argument("--side", type=float, default=10.0)
    ap.add_argument("--polygons", type=int, default=12)
    a = ap.parse_args()
    os.makedirs(a.out_dir, exist_ok=True)
    for k in range(1, a.floors + 1):
        polys, start, theta, goals = make_floor(20261129 + k, a.side, a.polygons)
        lines = [f"name: floor-{k:02d}", "world:", f"  bounds: [0, 0, {a.side:g}, {a.side:g}]",
                 "  obstacles:"]
        lines += ["    - polygon: [" + ", ".join(f"[{x}, {y}]" for x, y in p) + "]" for p in polys]
        lines += ["robot:", "  preset: quickbot", f"  start: [{start[0]}, {start[1]}, {theta}]",
                  "goals: [" + ", ".join(f"[{x}, {y}]" for x, y in goals) + "]",
                  "controller:", "  kind: hybrid", "sim:", "  dt: 0.01", "  t_max: 300",
                  "  seed: 1", ""]
        with open(os.path.join(a.out_dir, f"floor_{k:02d}.yaml"), "w") as f:
            f.write("\n".join(lines))


if __name__ == "__main__":
    main()
