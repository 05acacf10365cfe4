#!/usr/bin/env python3
"""Times floornav against Stage and RVO2 on the same work, interleaved, and prints the ratios.

    bench/peers/build_stage.sh && bench/peers/build_rvo2.sh     # once: peers into $PEERS_DIR
    python3 bench/peers/run.py [--pairs 5] [--only stage|rvo2] [--json OUT]

Each case runs as pairs A B A B ... (floornav, then the peer), so that both sides see the same
machine load; the table gives each side's median and range over the pairs, the ratio of the
medians and the range of the per-pair ratios. Nothing is timed but the simulation loops:

  cave_1, cave_100   floornav: `floornav batch <scenario> --jobs 1 --no-optimum`, steps (robot
                     steps) over the wall_time of results.jsonl, which times the simulation only
                     (loading and writing excluded); one thread. Stage: stage_driver, the world
                     loaded, then N calls of World::Update() timed (Stage's own headless loop
                     calls it once per step), one thread (world `threads 1`). The unit is a robot
                     step: one 180-beam 8 m scan, a decision and a move of one robot.
  fleet_1000         floornav: BM_Fleet_QuickBotWarehouse/1000/T (1,000 QuickBots, 5 IR each,
                     sensing each other, contacts checked) on T = 1 and 2 threads. RVO2:
                     rvo2_driver, its Circle example with 1,000 agents, run to the end as the
                     example runs (and Blocks, 1,000 agents, a fixed number of steps), on
                     OMP_NUM_THREADS = T. Unit: robot (agent) steps per second.
  circle_N           like for like (issue 33), N = 20, 100, 300, 1,000: floornav on RVO2's Circle
                     as shipped (scenarios/circle/circle_N.yaml: the automaton, ORCA and the safety
                     layer, every robot casting its IR rays), whole runs of `floornav run
                     --threads T` without recording (robot-steps over the summary's wall_time, the
                     simulation alone), against rvo2_driver's Circle with N agents, to the end or
                     5,000 steps (its 20 agents never all arrive), on T = 1 and 2 threads.

--pin CPU runs both sides of the one-thread circle cases on that CPU (taskset).
Paths: --floornav (default build/floornav), --bench (build/bench/floornav_bench), --peers
($PEERS_DIR or /tmp/floornav-peers, where the build scripts put Stage, RVO2 and the drivers).
"""
import argparse
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
SCENARIOS = os.path.join(HERE, "..", "..", "scenarios", "circle")


# --pin: the CPU that one-thread cases run on (None: wherever the scheduler puts them).
PIN = None


def run(cmd, env=None, threads=None):
    if PIN is not None and threads == 1:
        cmd = ["taskset", "-c", str(PIN)] + cmd
    p = subprocess.run(cmd, capture_output=True, text=True, env=env)
    if p.returncode != 0:
        sys.exit(f"failed ({p.returncode}): {' '.join(cmd)}\n{p.stderr[-2000:]}")
    return p.stdout


def floornav_batch(floornav, scenario, tmp):
    out = os.path.join(tmp, "batch")
    run([floornav, "batch", scenario, "--jobs", "1", "--no-optimum", "--out", out])
    line = json.loads(open(os.path.join(out, "results.jsonl")).readline())
    steps = line.get("fleet", {}).get("robot_steps", line["steps"])
    return steps / line["wall_time"]


def floornav_fleet_run(floornav, scenario, threads, tmp):
    out = os.path.join(tmp, "run")
    run([floornav, "run", scenario, "--threads", str(threads), "--set",
         "sim.record_trajectory=false", "--quiet", "--no-html", "--out", out], threads=threads)
    summary = json.load(open(os.path.join(out, "summary.json")))
    return summary["fleet"]["robot_steps"] / summary["wall_time"]


def stage(peers, world, updates, robots):
    d = os.path.join(peers, "stage")
    env = dict(os.environ, STAGEPATH=os.path.join(d, "install", "lib", "Stage-4.3"))
    out = run([os.path.join(d, "stage_driver"), world, str(updates), "5", str(robots)], env)
    return float(re.search(r"robot_updates_per_s=([0-9.]+)", out).group(1))


def fleet_bench(bench, threads, seconds, case="QuickBotWarehouse/1000"):
    out = run([bench, f"--benchmark_filter=^BM_Fleet_{case}/{threads}/",
               f"--benchmark_min_time={seconds}", "--benchmark_format=json"])
    return json.loads(out)["benchmarks"][0]["items_per_second"]


def rvo2(peers, scenario, steps, threads, agents=1000, pinnable=False):
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    out = run([os.path.join(peers, "rvo2", "rvo2_driver"), scenario, str(agents), str(steps)], env,
              threads if pinnable else None)
    return float(re.search(r"agent_steps_per_s=([0-9.]+)", out).group(1))


def fmt(v):
    return f"{v / 1e6:.2f} M" if v >= 1e6 else f"{v / 1e3:.1f} k" if v >= 1e3 else f"{v:.0f}"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--pairs", type=int, default=5)
    ap.add_argument("--only", choices=["stage", "rvo2", "circle"])
    ap.add_argument("--floornav", default="build/floornav")
    ap.add_argument("--bench", default="build/bench/floornav_bench")
    ap.add_argument("--peers", default=os.environ.get("PEERS_DIR", "/tmp/floornav-peers"))
    ap.add_argument("--stage-updates", type=int, nargs=2, default=[5000, 60],
                    metavar=("ONE", "HUNDRED"), help="Stage updates timed for 1 and 100 robots")
    ap.add_argument("--rvo2-blocks-steps", type=int, default=1000)
    ap.add_argument("--fleet-seconds", type=float, default=2.0)
    ap.add_argument("--json", help="also write every measurement here")
    ap.add_argument("--pin", type=int, metavar="CPU",
                    help="run both sides of the one-thread circle cases on this CPU (taskset): "
                    "a virtual machine's vCPUs may change speed independently")
    a = ap.parse_args()
    global PIN
    PIN = a.pin
    worlds = os.path.join(a.peers, "worlds")
    cases = []  # (name, unit, floornav fn, peer name, peer fn)
    if a.only in (None, "stage"):
        run([sys.executable, os.path.join(HERE, "make_worlds.py"),
             os.path.join(a.peers, "stage", "src"), worlds])
        for n, updates in ((1, a.stage_updates[0]), (100, a.stage_updates[1])):
            scen = os.path.join(worlds, f"floornav_cave_{n}.yaml")
            world = os.path.join(worlds, f"stage_cave_{n}.world")
            cases.append((f"cave, {n} robot{'s' if n > 1 else ''}, 180-beam 8 m laser, 1 thread",
                          lambda tmp, s=scen: floornav_batch(a.floornav, s, tmp), "Stage",
                          lambda w=world, u=updates, n=n: stage(a.peers, w, u, n)))
    if a.only in (None, "rvo2"):
        for t in (1, 2):
            cases.append((f"1,000 robots, {t} thread{'s' if t > 1 else ''}: RVO2 Circle",
                          lambda tmp, t=t: fleet_bench(a.bench, t, a.fleet_seconds), "RVO2",
                          lambda t=t: rvo2(a.peers, "circle", 10**9, t)))
            cases.append((f"1,000 robots, {t} thread{'s' if t > 1 else ''}: RVO2 Blocks",
                          lambda tmp, t=t: fleet_bench(a.bench, t, a.fleet_seconds), "RVO2",
                          lambda t=t: rvo2(a.peers, "blocks", a.rvo2_blocks_steps, t)))
    if a.only == "circle":
        for n in (20, 100, 300, 1000):
            for t in (1, 2):
                cases.append((f"Circle, {n} robots, {t} thread{'s' if t > 1 else ''}",
                              lambda tmp, n=n, t=t: floornav_fleet_run(
                                  a.floornav, os.path.join(SCENARIOS, f"circle_{n}.yaml"), t, tmp),
                              "RVO2",
                              lambda n=n, t=t: rvo2(a.peers, "circle", 5000, t, n, True)))
    load = os.getloadavg()
    results = []
    with tempfile.TemporaryDirectory() as tmp:
        for name, ours, peer_name, theirs in cases:
            f, p = [], []
            for i in range(a.pairs):
                f.append(ours(tmp))
                p.append(theirs())
                print(f"  {name}: pair {i + 1}: floornav {fmt(f[-1])}, {peer_name} {fmt(p[-1])}",
                      file=sys.stderr)
            results.append({"case": name, "peer": peer_name, "floornav": f, "peer_rates": p,
                            "ratio_of_medians": statistics.median(f) / statistics.median(p),
                            "pair_ratios": [x / y for x, y in zip(f, p)]})
    load_after = os.getloadavg()
    print(f"floornav vs peers, robot-steps/s, {a.pairs} interleaved pairs per case; load average "
          f"{load[0]:.1f} before, {load_after[0]:.1f} after ({os.cpu_count()} cores)")
    # Two ratios: of the medians, and the median of the pairs' own ratios (a pair's two runs are
    # seconds apart, so it is the steadier when this virtual machine's speed changes mid-run).
    print(f"{'case':58} {'floornav median (range)':>26} {'peer median (range)':>26} "
          f"{'ratio':>6} {'pair ratios: median, range':>27}")
    for r in results:
        f, p, pr = r["floornav"], r["peer_rates"], r["pair_ratios"]
        print(f"{r['case']:58} {fmt(statistics.median(f)):>9} ({fmt(min(f))}-{fmt(max(f))})"
              f"{'':>1} {r['peer'] + ' ' + fmt(statistics.median(p)):>13} "
              f"({fmt(min(p))}-{fmt(max(p))}) {r['ratio_of_medians']:>5.2f}x "
              f"{statistics.median(pr):>5.2f}x, {min(pr):.2f}-{max(pr):.2f}")
    # Issue 14 also reads the fleet target as "a second thread that pays": floornav on two
    # threads against the peer on one, both medians from this run.
    cross = []
    for r in results:
        if " 2 threads: " in r["case"]:
            one = next((q for q in results
                        if q["case"] == r["case"].replace(" 2 threads: ", " 1 thread: ")), None)
            if one:
                cross.append({"case": r["case"], "floornav": statistics.median(r["floornav"]),
                              "peer_one_thread": statistics.median(one["peer_rates"])})
    for c in cross:
        print(f"{c['case'] + ', against the peer on 1 thread':58} {fmt(c['floornav']):>9} "
              f"{'':>14} {fmt(c['peer_one_thread']):>13} {'':>13} "
              f"{c['floornav'] / c['peer_one_thread']:>5.2f}x")
    if a.json:
        json.dump({"load": [load, load_after], "results": results, "cross": cross},
                  open(a.json, "w"), indent=1)


if __name__ == "__main__":
    main()
