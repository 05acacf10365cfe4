#!/usr/bin/env python3
"""Writes the same cave worlds for Stage and for floornav (bench/peers/README.md).

    python3 bench/peers/make_worlds.py STAGE_SRC OUT_DIR

STAGE_SRC is Stage's source tree (build_stage.sh extracts it to $PEERS_DIR/stage/src). From it:
worlds/bitmaps/cave.png (500 x 500 pixels, black = rock) and the 100 robot poses of Stage's own
benchmark, worlds/benchmark/cave.world. Nothing of Stage's is copied into the repository; OUT_DIR
(scratch) gets:

  cave.png                     the bitmap, Stage's floorplan (with `boundary 1`: Stage closes it
                               with a wall 0.01 m thick around its 16 x 16 m bounding box)
  cave.pgm, cave.yaml          floornav's ROS map_server map of it: the bitmap with its outermost
                               ring of pixels set to rock (Stage's boundary; 1,642 of the 1,996
                               border pixels are open, so without it floornav's robots could leave
                               the cave where Stage's cannot), 0.032 m cells, origin (-8, -8), so
                               both simulators share one frame
  stage_cave_{1,100}.world     Stage: the bitmap as its floorplan (16 x 16 m, centred), robots
                               (0.44 x 0.38 m boxes, differential drive) with a 180-sample, 180 deg,
                               8 m laser, driven by Stage's example `wander` controller
  floornav_cave_{1,100}.yaml   floornav: the map, Pioneer 3-DX bodies (r = 0.26 m) with a 180-beam,
                               180 deg, 0-8 m lidar, the hybrid controller, tours of four free goals
  poses.txt                    the starts used: x y theta_deg

1 robot starts at the first pose of Stage's benchmark, 100 robots at all of them (the same poses on
both sides), except that a start closer to an earlier one than two Pioneer bodies and floornav's
protective field (which floornav refuses as bad input) is moved straight away from it until it
is clear by 2 cm: of Stage's poses, the 93rd lies 1.6 mm from the 91st. Stage's raytrace resolution is that of its benchmark world (0.02 m); it runs one
thread (`threads 1`, the main one) unless THREADS is given in the environment.
"""
import math
import os
import random
import re
import shutil
import struct
import sys
import zlib


def read_gray_png(path):
    """8-bit greyscale, non-interlaced PNG -> list of rows (top row first) of ints 0-255."""
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", path
    pos, idat, width, height = 8, b"", 0, 0
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert depth == 8 and colour == 0 and interlace == 0, "expected 8-bit grey"
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw, rows, prev = zlib.decompress(idat), [], [0] * width
    for y in range(height):
        f, line = raw[y * (width + 1)], list(raw[y * (width + 1) + 1:(y + 1) * (width + 1)])
        for x in range(width):
            a = line[x - 1] if x else 0
            b, c = prev[x], prev[x - 1] if x else 0
            if f == 1:
                line[x] = (line[x] + a) & 255
            elif f == 2:
                line[x] = (line[x] + b) & 255
            elif f == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line)
        prev = line
    return rows


def with_boundary(rows):
    """The bitmap with its outermost ring of pixels black: Stage's `boundary 1` as map cells."""
    h, w = len(rows), len(rows[0])
    return [[0 if x in (0, w - 1) or y in (0, h - 1) else v for x, v in enumerate(row)]
            for y, row in enumerate(rows)]


def write_pgm(path, rows):
    """Binary 8-bit greyscale PGM (P5), top row first, as ROS map_server reads it."""
    with open(path, "wb") as f:
        f.write(b"P5\n%d %d\n255\n" % (len(rows[0]), len(rows)))
        f.write(bytes(v for row in rows for v in row))


class Cave:
    """The bitmap as cells: 0.032 m, world frame x right, y up, origin (-8, -8)."""

    def __init__(self, rows, res=0.032, origin=(-8.0, -8.0)):
        self.res, self.origin, self.h, self.w = res, origin, len(rows), len(rows[0])
        # ROS map_server (negate 0): occupancy = (255 - v) / 255 > 0.65 is occupied.
        self.occ = [[(255 - v) / 255.0 > 0.65 for v in row] for row in reversed(rows)]

    def free_disc(self, x, y, r):
        cx, cy = (x - self.origin[0]) / self.res, (y - self.origin[1]) / self.res
        k = int(math.ceil(r / self.res)) + 1
        for iy in range(int(cy) - k, int(cy) + k + 1):
            for ix in range(int(cx) - k, int(cx) + k + 1):
                if not (0 <= ix < self.w and 0 <= iy < self.h) or self.occ[iy][ix]:
                    # distance from the point to the cell's square
                    dx = max(ix - cx, 0.0, cx - ix - 1)
                    dy = max(iy - cy, 0.0, cy - iy - 1)
                    if math.hypot(dx, dy) * self.res <= r:
                        return False
        return True


PIONEER_RADIUS = 0.26  # m, floornav's pioneer_p3dx preset
CLEAR_GAP = 0.03  # m: floornav's default protective field (0.01 m) and 2 cm


def spread_apart(poses):
    """Each start closer to an earlier one than two bodies and CLEAR_GAP, moved straight away
    from it until it is that far (Stage's benchmark has one such pair)."""
    out = []
    for x, y, t in poses:
        for px, py, _ in out:
            d = math.hypot(x - px, y - py)
            want = 2.0 * PIONEER_RADIUS + CLEAR_GAP
            if 0.0 < d < want:
                x, y = px + (x - px) * want / d, py + (y - py) * want / d
        out.append((round(x, 3), round(y, 3), t))
    return out


def stage_world(path, poses, threads):
    lines = [
        "# Written by floornav bench/peers/make_worlds.py: Stage's cave bitmap, robots with a",
        "# 180-sample 8 m laser driven by Stage's example wander controller.",
        "resolution 0.02", "interval_sim 100", "speedup -1", "paused 0", f"threads {threads}",
        "define laser180 ranger", "(", "  sensor( range [ 0.0 8.0 ] fov 180 samples 180 )",
        "  size [ 0.156 0.155 0.19 ]", ")",
        "define bot position", "(", "  size [ 0.44 0.38 0.22 ]", "  origin [ -0.04 0 0 0 ]",
        '  drive "diff"', "  laser180( pose [ 0.13 0 0 0 ] )", '  ctrl "wander"', ")",
        "model", "(", '  name "cave"', "  size [ 16.000 16.000 0.600 ]", "  pose [ 0 0 0 0 ]",
        '  bitmap "cave.png"', "  boundary 1", "  gui_nose 0", "  obstacle_return 1",
        "  ranger_return 1", ")"]
    lines += [f"bot( pose [ {x:.3f} {y:.3f} 0 {t:.3f} ] )" for x, y, t in poses]
    open(path, "w").write("\n".join(lines) + "\n")


def floornav_scenario(path, name, poses, cave, rng, t_max):
    lines = [f"# Written by floornav bench/peers/make_worlds.py: Stage's cave, {len(poses)} robot(s).",
             f"name: {name}", "world:", "  map: cave.yaml", "robot:", "  preset: pioneer_p3dx",
             "  sensors:", "    lidar: {beams: 180, fov: 3.141592653589793, min_range: 0.0, "
             "max_range: 8.0}", "controller:", "  kind: hybrid", "sim:", "  dt: 0.01",
             f"  t_max: {t_max}", "  seed: 1", "robots:"]
    for i, (x, y, t) in enumerate(poses):
        goals, prev = [], (x, y)
        while len(goals) < 4:
            g = (rng.uniform(-7.5, 7.5), rng.uniform(-7.5, 7.5))
            if math.dist(g, prev) > 5.0 and cave.free_disc(g[0], g[1], 0.4):
                goals.append(g)
                prev = g
        lines.append(f"  - {{name: r{i}, start: [{x:.3f}, {y:.3f}, {math.radians(t):.6f}], "
                     "goals: [" + ", ".join(f"[{gx:.3f}, {gy:.3f}]" for gx, gy in goals) + "]}")
    open(path, "w").write("\n".join(lines) + "\n")


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    src, out = sys.argv[1], sys.argv[2]
    os.makedirs(out, exist_ok=True)
    png = os.path.join(src, "worlds", "bitmaps", "cave.png")
    shutil.copyfile(png, os.path.join(out, "cave.png"))
    rows = with_boundary(read_gray_png(png))
    write_pgm(os.path.join(out, "cave.pgm"), rows)
    cave = Cave(rows)
    open(os.path.join(out, "cave.yaml"), "w").write(
        "image: cave.pgm\nresolution: 0.032\norigin: [-8.0, -8.0, 0.0]\nnegate: 0\n"
        "occupied_thresh: 0.65\nfree_thresh: 0.196\n")
    text = open(os.path.join(src, "worlds", "benchmark", "cave.world")).read()
    poses = [tuple(float(v) for v in m.split()[0:2] + [m.split()[3]])
             for m in re.findall(r"rob\(\s*pose\s*\[([^\]]*)\]", text)]
    assert len(poses) == 100, f"expected Stage's 100 benchmark poses, found {len(poses)}"
    poses = spread_apart(poses)
    bad = [p for p in poses if not cave.free_disc(p[0], p[1], 0.26)]
    with open(os.path.join(out, "poses.txt"), "w") as f:
        f.writelines(f"{x} {y} {t}\n" for x, y, t in poses)
    threads = int(os.environ.get("THREADS", "1"))
    rng = random.Random(20261129)
    for n, t_max in ((1, 60.0), (100, 10.0)):
        stage_world(os.path.join(out, f"stage_cave_{n}.world"), poses[:n], threads)
        floornav_scenario(os.path.join(out, f"floornav_cave_{n}.yaml"), f"cave-{n}", poses[:n],
                          cave, rng, t_max)
    print(f"worlds in {out}; starts not clear of rock by 0.26 m: {len(bad)}")


if __name__ == "__main__":
    main()
