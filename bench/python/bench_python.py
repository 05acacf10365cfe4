"""Speed of floornav from Python, measured side by side with the C++ tool on the same machine.

Cases (robot-steps/s unless said otherwise):

  step_builtin     Simulation.step() from a Python loop, the scenario's own controller, one
                   QuickBot (5 IR) on a 20 x 20 m floor of 50 random polygons, the observation
                   dict built every step
  step_command     the same with step((v, omega))
  vec_quickbot     VecEnv, 1,024 QuickBots on that floor, actions (n, 2) from numpy, numpy
                   observations and rewards every step, all cores
  vec_lidar180     the same with 180-beam lidars (TurtleBot3 Burger, 3.5 m)
  vec_quickbot_rand, vec_lidar180_rand
                   the same with randomize={"start": "free", "goal": "free"} (draws at every
                   autoreset; episodes of 20 s so that copies reset often)
  render           VecEnv.render() of 1,024 QuickBot copies at 128 x 128 pixels: frames/s
  parallel100      ParallelEnv of 100 QuickBots on a 30 x 30 m floor, a dict of (v, omega) per
                   agent built by a Python loop every step
  cpp_reference    `floornav bench` (C++, one thread) on its QuickBot and 180-beam lidar cases,
                   run between the others: the machine's state at the time
  batch            floornav.batch against `floornav batch` on the same files and jobs: runs/s

Every case runs --repeat times; the median and the range are printed, with the load average
(other processes share the cores; say so when quoting). Rates per CPU-second (the process's CPU
time, all threads) are printed too: under load they show what an idle core would do.

Run: PYTHONPATH=build/python /usr/bin/python3 bench/python/bench_python.py [--json FILE]
"""

from __future__ import annotations

import argparse
import json
import math
import os
import pathlib
import platform
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

import floornav

ROOT = pathlib.Path(__file__).resolve().parents[2]


def bench_floor_yaml(robot: str, seed: int = 20261123) -> str:
    """A 20 x 20 m walled floor with 50 star-shaped polygons (3-8 vertices, radii 0.3-0.9 m,
    0.6 m apart), as `floornav bench` builds its floor, and a robot crossing it by four goals."""
    rng = np.random.default_rng(seed)
    side, gap, discs = 20.0, 0.6, []
    while len(discs) < 50:
        r = rng.uniform(0.3, 0.9)
        c = rng.uniform(r + 0.5, side - r - 0.5, 2)
        if all(math.dist(c, d[0]) >= r + d[1] + gap for d in discs):
            discs.append((c, r))
    polys = []
    for c, r in discs:
        n = int(rng.integers(3, 9))
        step = 2 * math.pi / n
        phase = rng.uniform(0, step)
        pts = []
        for i in range(n):
            a = phase + i * step + rng.uniform(-step / 3, step / 3)
            rr = r * rng.uniform(0.6, 1.0)
            pts.append(f"[{c[0] + rr * math.cos(a):.4f}, {c[1] + rr * math.sin(a):.4f}]")
        polys.append("    - polygon: [" + ", ".join(pts) + "]")

    def free(margin):
        while True:
            p = rng.uniform(1.0, side - 1.0, 2)
            if all(math.dist(p, d[0]) >= d[1] + margin for d in discs):
                return p

    start = free(0.5)
    goals, last = [], start
    while len(goals) < 4:
        g = free(0.5)
        if math.dist(g, last) >= side / 3:
            goals.append(g)
            last = g
    goal_text = ", ".join(f"[{g[0]:.3f}, {g[1]:.3f}]" for g in goals)
    return f"""name: bench-floor-{robot}
world:
  bounds: [0, 0, {side}, {side}]
  obstacles:
{chr(10).join(polys)}
robot:
{robot_section(robot)}
  start: [{start[0]:.3f}, {start[1]:.3f}, 0.3]
goals: [{goal_text}]
controller:
  kind: hybrid
sim: {{dt: 0.01, t_max: 100000, seed: 1, record_trajectory: false}}
"""


def robot_section(robot: str) -> str:
    if robot == "quickbot":
        return "  preset: quickbot"
    return ("  preset: turtlebot3_burger\n"
            "  sensors: {lidar: {beams: 180, fov: 6.283185307179586, min_range: 0.12, "
            "max_range: 3.5, mount: [-0.032, 0, 0]}}")


def floor(robot: str) -> floornav.Scenario:
    return floornav.parse_scenario(bench_floor_yaml(robot), origin=f"bench_floor_{robot}.yaml")


def timed(fn, seconds: float):
    """Calls fn() (which returns the robot-steps it did) until `seconds` have passed; returns
    (steps per wall second, steps per CPU second)."""
    steps, w0, c0 = 0, time.perf_counter(), time.process_time()
    while True:
        steps += fn()
        w = time.perf_counter() - w0
        if w >= seconds:
            return steps / w, steps / max(time.process_time() - c0, 1e-9)


def case_step(command, seconds):
    s = floor("quickbot")
    sim = floornav.Simulation(s, record=False)
    sim.reset()

    def burst():
        nonlocal sim
        for _ in range(2000):
            if sim.finished:
                sim.reset()
            sim.step(command)
        return 2000

    return timed(burst, seconds)


def time_vec_steps(env, n, seconds):
    """Robot-steps a second of `env` (n copies) driven by fixed random actions."""
    env.reset()
    rng = np.random.default_rng(1)
    actions = np.column_stack([np.full(n, 0.1), rng.uniform(-0.5, 0.5, n)])

    def burst():
        for _ in range(10):
            env.step(actions)
        return 10 * n

    burst()
    return timed(burst, seconds)


def case_vec(robot, seconds, n=1024):
    return time_vec_steps(floornav.VecEnv(floor(robot), n, seed=1), n, seconds)


def case_vec_rand(robot, seconds, n=1024):
    s = floornav.parse_scenario(bench_floor_yaml(robot), {"sim.t_max": 20},
                                origin=f"bench_floor_{robot}.yaml")
    env = floornav.VecEnv(s, n, seed=1, randomize={"start": "free", "goal": "free"})
    return time_vec_steps(env, n, seconds)


def case_render(seconds, n=1024):
    env = floornav.VecEnv(floor("quickbot"), n, seed=1, render_mode="rgb_array",
                          render_shape=(128, 128))
    env.reset()
    env.render()  # the world's raster, drawn once

    def burst():
        env.render()
        return n

    return timed(burst, seconds)


def parallel_floor_yaml(n=100, side=30.0):
    k = int(math.ceil(math.sqrt(n)))
    gap = side / (k + 1)
    robots = []
    for i in range(n):
        x, y = gap * (1 + i % k), gap * (1 + i // k)
        robots.append(f"  - {{name: r{i}, start: [{x}, {y}, 0], goals: [[{side - x}, {side - y}]]}}")
    return (f"name: parallel{n}\nworld: {{bounds: [0, 0, {side}, {side}]}}\n"
            "robot: {preset: quickbot}\nrobots:\n" + "\n".join(robots) +
            "\ncontroller: {kind: hybrid}\nsim: {dt: 0.01, t_max: 600}\n")


def case_parallel(seconds, n=100):
    env = floornav.ParallelEnv(floornav.parse_scenario(parallel_floor_yaml(n)))
    env.reset(seed=1)
    rng = np.random.default_rng(1)
    turn = {a: float(w) for a, w in zip(env.possible_agents, rng.uniform(-0.5, 0.5, n))}

    def burst():
        steps = 0
        for _ in range(20):
            if not env.agents:
                env.reset()
            steps += len(env.agents)
            env.step({a: (0.1, turn[a]) for a in env.agents})
        return steps

    burst()
    return timed(burst, seconds)


def cpp_reference(cli, seconds):
    out = {}
    for case in ["quickbot_5ir_50_polygons", "lidar180_50_polygons"]:
        p = subprocess.run([str(cli), "bench", "--json", "--seconds", str(seconds), "--filter", case],
                           capture_output=True, text=True, check=True)
        for c in json.loads(p.stdout)["cases"]:
            if c["name"] == case:
                out[case] = c["robot_steps_per_s"]
    return out


def case_batch(cli, jobs, copies):
    names = ["rectangle", "factory_delivery", "week7_pocket", "concave_obstacle",
             "convex_obstacle", "circle_obstacle", "point_obstacle", "practice2_pillars"]
    files = [f"scenarios/{n}.yaml" for n in names] * copies
    with tempfile.TemporaryDirectory() as d:
        t0 = time.perf_counter()
        subprocess.run([str(cli), "batch", *files, "--jobs", str(jobs), "--no-timing", "--out", d],
                       cwd=ROOT, check=True, capture_output=True)
        t_cli = time.perf_counter() - t0
    here = os.getcwd()
    os.chdir(ROOT)
    try:
        t0 = time.perf_counter()
        floornav.batch(files, jobs=jobs, timing=False)
        t_py = time.perf_counter() - t0
    finally:
        os.chdir(here)
    return len(files) / t_cli, len(files) / t_py


def summary(values):
    return {"median": statistics.median(values), "min": min(values), "max": max(values),
            "runs": len(values)}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--seconds", type=float, default=2.0, help="per repetition")
    ap.add_argument("--cases", default="cpp_reference,step_builtin,step_command,vec_quickbot,"
                                       "vec_lidar180,vec_quickbot_rand,vec_lidar180_rand,render,"
                                       "parallel100,batch")
    ap.add_argument("--cli", default=str(ROOT / "build" / "floornav"))
    ap.add_argument("--batch-copies", type=int, default=40, help="copies of the 8 scenarios")
    ap.add_argument("--json", help="write the results here")
    args = ap.parse_args(argv)
    cases = args.cases.split(",")
    results = {"date": time.strftime("%Y-%m-%d %H:%M"), "cpu": platform.processor() or platform.machine(),
               "cores": os.cpu_count(), "python": sys.version.split()[0],
               "floornav": floornav.__version__, "load_before": os.getloadavg()[0], "cases": {}}
    print(f"floornav {floornav.__version__}, Python {results['python']}, {results['cores']} cores, "
          f"load average {results['load_before']:.1f}")

    def record(name, walls, cpus=None, unit="robot-steps/s"):
        entry = {"wall": summary(walls), "unit": unit}
        if cpus:
            entry["per_cpu_second"] = summary(cpus)
        results["cases"][name] = entry
        line = (f"{name:16s} {entry['wall']['median']:>12,.0f} {unit} "
                f"(range {entry['wall']['min']:,.0f}-{entry['wall']['max']:,.0f})")
        if cpus:
            line += f"; per CPU-second {entry['per_cpu_second']['median']:,.0f}"
        print(line, flush=True)

    for name in cases:
        walls, cpus = [], []
        if name == "cpp_reference":
            runs = [cpp_reference(args.cli, 1.0) for _ in range(args.repeat)]
            for key in runs[0]:
                record(f"cpp {key.split('_')[0]}", [r[key] for r in runs])
            continue
        if name == "batch":
            pairs = [case_batch(args.cli, 2, args.batch_copies) for _ in range(args.repeat)]
            record("batch cli", [p[0] for p in pairs], unit="runs/s")
            record("batch python", [p[1] for p in pairs], unit="runs/s")
            ratios = [p[1] / p[0] for p in pairs]
            results["cases"]["batch ratio"] = summary(ratios)
            print(f"{'batch ratio':16s} python/cli median {statistics.median(ratios):.3f} "
                  f"(range {min(ratios):.3f}-{max(ratios):.3f})")
            continue
        for _ in range(args.repeat):
            if name == "step_builtin":
                w, c = case_step(None, args.seconds)
            elif name == "step_command":
                w, c = case_step((0.12, 0.3), args.seconds)
            elif name == "vec_quickbot":
                w, c = case_vec("quickbot", args.seconds)
            elif name == "vec_lidar180":
                w, c = case_vec("lidar180", args.seconds)
            elif name == "vec_quickbot_rand":
                w, c = case_vec_rand("quickbot", args.seconds)
            elif name == "vec_lidar180_rand":
                w, c = case_vec_rand("lidar180", args.seconds)
            elif name == "render":
                w, c = case_render(args.seconds)
            elif name == "parallel100":
                w, c = case_parallel(args.seconds)
            else:
                raise SystemExit(f"unknown case {name}")
            walls.append(w)
            cpus.append(c)
        record(name, walls, cpus, unit="frames/s" if name == "render" else "robot-steps/s")
    results["load_after"] = os.getloadavg()[0]
    print(f"load average after: {results['load_after']:.1f}")
    if args.json:
        pathlib.Path(args.json).write_text(json.dumps(results, indent=2) + "\n")


if __name__ == "__main__":
    main()
