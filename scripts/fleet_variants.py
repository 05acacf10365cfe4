#!/usr/bin/env python3
"""Writes generated variants of the fleet benchmarks (docs/BENCHMARKS.md): the 20-robot warehouse
(scenarios/fleet_warehouse.yaml is seed 4) and the factory floor with people and forklifts
(scenarios/crowd/factory_people.yaml is seed 3). The same layout each time; the seed draws the
picks, drops, docks, the people's routes and speeds.

    python3 scripts/fleet_variants.py warehouse|factory OUT_DIR [SEED ...]   (default seeds 1-10)
"""
import os
import random
import sys


def warehouse(seed):
    random.seed(seed)
    rows = [2.2, 3.7, 5.2]
    aisles = [2.95, 4.45]
    out = []
    out.append("""# Twenty QuickBots (16-beam 0.4 m rings) in a 12 x 8 m warehouse, three rows of shelving in two
# blocks with a cross aisle between them. Each robot leaves the staging line at the south wall,
# picks in an aisle, drops at one of four docks by the north wall and parks in its own bay on the
# north wall: 60 deliveries, robots meeting head on in the aisles, in the cross aisle and at the
# docks. Other robots are avoided by the reciprocal-velocity layer (controller.robot_avoidance).
name: fleet-warehouse
world:
  bounds: [0, 0, 12, 8]
  obstacles:""")
    for y in rows:
        for x in (3.0, 9.0):
            out.append(f"    - rectangle: {{center: [{x}, {y}], size: [4.0, 0.4]}}")
    for c in [(6.0, 2.95), (6.0, 4.45)]:
        out.append(f"    - circle: {{center: [{c[0]}, {c[1]}], radius: 0.15}}   # pillar")
    out.append("""robot:
  preset: quickbot
  sensors: {lidar: {beams: 16, fov: 6.283185307, min_range: 0.02, max_range: 0.4}}
robots:""")
    docks = [(2.0, 6.4), (4.5, 6.4), (7.5, 6.4), (10.0, 6.4)]
    for k in range(20):
        sx = 0.5 + 0.55 * k
        aisle = aisles[k % 2]
        block = (k // 2) % 2
        px = (1.5 + 3.0 * random.random()) + (6.0 if block else 0.0)
        pick = (round(px, 2), aisle)
        dock = docks[(k * 3) % 4]
        dock = (round(dock[0] + random.uniform(-0.6, 0.6), 2), dock[1])
        park = (round(sx, 2), 7.6)
        out.append(f"  - {{name: r{k:02d}, start: [{sx:.2f}, 0.4, 1.5708], goals: [[{pick[0]}, {pick[1]}], [{dock[0]}, {dock[1]}], [{park[0]}, {park[1]}]]}}")
    out.append("""controller:
  kind: hybrid
  robot_avoidance: orca
sim:
  dt: 0.01
  t_max: 600""")
    return "\n".join(out) + "\n"


def factory(seed, preset="quickbot"):
    random.seed(seed)
    out = []
    out.append("""# A 16 x 10 m factory floor shared with people and forklifts. Two rows of machines (north and
# south) face a main aisle where two forklifts loop (1.8 x 0.9 m, 1 m/s, stopping for anyone in
# the metre ahead of them). Ten people walk by the social force model between workstations,
# across the aisle and along it. Six robots (QuickBots with 16-beam rings, which see people as
# discs and forklifts as rectangles) each carry parts to a machine, fetch more from the stores by
# the west wall, deliver them to another machine and park by the east wall: 24 deliveries. They
# avoid each other with the reciprocal-velocity layer; people avoid them (social force).
name: factory-people
world:
  bounds: [0, 0, 16, 10]
  obstacles:""")
    machines = []
    for y in (2.2, 7.8):
        for x in (4.0, 7.5, 11.0):
            out.append(f"    - rectangle: {{center: [{x}, {y}], size: [2.0, 1.2]}}   # machine")
            machines.append((x, y))
    out.append("    - rectangle: {center: [1.0, 8.5], size: [1.2, 2.0]}      # stores, north")
    out.append("    - rectangle: {center: [1.0, 1.5], size: [1.2, 2.0]}      # stores, south")
    out.append("    - circle: {center: [14.0, 5.0], radius: 0.2}             # pillar")
    if preset == "quickbot":
        out.append("""robot:
  preset: quickbot
  sensors: {lidar: {beams: 16, fov: 6.283185307, min_range: 0.02, max_range: 0.4}}""")
    else:
        out.append(f"""robot:
  preset: {preset}""")
    out.append("robots:")
    # pick-up points by the stores, drop points at machine faces (toward the aisle or the sides)
    picks = [(2.0, 8.0), (2.0, 2.0), (1.6, 5.0)]
    faces = []
    for (x, y) in machines:
        fy = round(y - 0.9 if y > 5 else y + 0.9, 2)
        faces.append((x, fy))
    for k in range(6):
        sx, sy = 0.5, 3.6 + 0.55 * k
        goals = []
        for d in range(3):
            p = picks[(k + d) % 3]
            goals.append((round(p[0] + random.uniform(-0.3, 0.3), 2), round(p[1] + random.uniform(-0.4, 0.4), 2)))
            f = faces[random.randrange(len(faces))]
            goals.append((round(f[0] + random.uniform(-0.7, 0.7), 2), f[1]))
        goals = goals[1:4]  # pick, drop, pick
        goals.append((15.4, 2.5 + 1.0 * k))  # park
        g = ", ".join(f"[{a}, {b}]" for a, b in goals)
        out.append(f"  - {{name: amr{k}, start: [{sx}, {sy:.2f}, 0], goals: [{g}]}}")
    out.append("people:")
    spots = [(4.0, 3.4), (7.5, 3.4), (11.0, 3.4), (4.0, 6.6), (7.5, 6.6), (11.0, 6.6),
             (5.75, 1.0), (9.25, 1.0), (5.75, 9.0), (9.25, 9.0), (13.5, 8.5), (13.5, 1.5), (2.5, 5.0)]
    for a in range(10):
        s = spots[a % len(spots)]
        wps = random.sample([p for p in spots if p != s], 3)
        w = ", ".join(f"[{x}, {y}]" for x, y in wps)
        out.append(f"  - {{name: worker{a}, start: [{s[0]}, {s[1]}], waypoints: [{w}], speed: {round(random.uniform(0.9, 1.3), 2)}, radius: 0.25}}")
    out.append("""forklifts:
  - {name: fork1, route: [[3.6, 4.55], [12.5, 4.55], [12.5, 5.45], [3.6, 5.45]], speed: 1.0, size: [1.8, 0.9]}
  - {name: fork2, route: [[12.5, 5.45], [3.6, 5.45], [3.6, 4.55], [12.5, 4.55]], speed: 1.0, size: [1.8, 0.9]}
controller:
  kind: hybrid
  robot_avoidance: orca
sim:
  dt: 0.01
  t_max: 600""")
    return "\n".join(out) + "\n"


def main():
    if len(sys.argv) < 3 or sys.argv[1] not in ("warehouse", "factory"):
        sys.exit(__doc__)
    kind, out = sys.argv[1], sys.argv[2]
    seeds = [int(s) for s in sys.argv[3:]] or list(range(1, 11))
    os.makedirs(out, exist_ok=True)
    make = warehouse if kind == "warehouse" else factory
    for seed in seeds:
        with open(os.path.join(out, f"{kind}_{seed:02d}.yaml"), "w") as f:
            f.write(make(seed))


if __name__ == "__main__":
    main()
