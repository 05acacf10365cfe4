"""The chapter's simulation, redone with floornav.

The chapter closes with a Python script that drives a Pioneer P3-DX in CoppeliaSim around a 3 m
cylinder in a 35 m arena: go-to-goal, avoid-obstacle and wall following. Here the same loop runs
on floornav's simulator (scenarios/coppeliasim_pioneer.yaml, the same scene): every step it reads
the range sensors, computes the behaviour's velocity u with floornav's behaviours (eqs. 5.16-5.27),
turns u into (v, omega) with the heading controller of eqs. 5.12-5.15, and sends that to the robot,
whose wheels saturate as the real ones do.

Three supervisors, as in the chapter: go-to-goal alone (it drives into the cylinder), hard
switching between go-to-goal and avoid-obstacle (it gets round, chattering at the switch), and
wall following with the progress rule (Fig 5.11). The built-in `hybrid` kind runs last for
comparison. Writes a picture of the four paths.

Run: PYTHONPATH=build/python /usr/bin/python3 examples/python/01_chapter_simulation.py
"""

from __future__ import annotations

import argparse
import math
import pathlib

import floornav

HERE = pathlib.Path(__file__).resolve().parent
SCENE = HERE.parents[1] / "scenarios" / "coppeliasim_pioneer.yaml"


def heading_control(u, theta, v_max, kp=1.5):
    """(v, omega) that tracks the velocity u from heading theta (eqs. 5.12-5.15, P only)."""
    speed = math.hypot(*u)
    if speed < 1e-9:
        return (0.0, 0.0)
    error = math.atan2(u[1], u[0]) - theta
    error = math.atan2(math.sin(error), math.cos(error))  # wrapped, eq. 5.14
    return (min(speed, v_max) * max(0.0, math.cos(error)), kp * error)


def drive(scenario, supervisor):
    """The chapter's loop: sense, decide, command, until the run ends. Returns the path,
    the modes and the status."""
    sim = floornav.Simulation(scenario)
    obs = sim.reset()
    p = obs["params"]
    radius = obs["robot"].body_radius
    mode, d_tau = "gtg", math.inf
    path, modes, switches = [obs["pose"][:2]], [], 0
    while obs["status"] == "running":
        x = obs["pose"][:2]
        i = floornav.make_navigation_input(x, obs["goal"], obs["points"], radius, p)
        if i.goal_distance < p.epsilon:
            obs = sim.step({"goal_reached": True})
            break
        new, d_tau = supervisor(mode, i, p, d_tau)
        switches += new != mode
        mode = new
        if mode == "gtg":
            u = i.u_gtg
        elif mode == "ao":
            u = i.u_ao
        else:  # follow the wall, clockwise or counter-clockwise
            turn = floornav.Turn.CLOCKWISE if mode == "fw_cw" else floornav.Turn.COUNTER_CLOCKWISE
            u = floornav.follow_boundary_velocity(i.away, i.clearance, turn, p.d_fb, p.k_fb, p.v0)
        obs = sim.step(heading_control(u, obs["pose"][2], p.v0))
        path.append(obs["pose"][:2])
        modes.append(mode)
    return path, modes, switches, obs["status"], obs["t"]


def go_to_goal_only(mode, i, p, d_tau):
    return "gtg", d_tau


def hard_switch(mode, i, p, d_tau):  # Fig 5.7
    return ("ao" if i.clearance < p.d_o else "gtg"), d_tau


def wall_following(mode, i, p, d_tau):  # Fig 5.11 without the avoid-obstacle safety mode
    clear_shot = i.u_ao[0] * i.u_gtg[0] + i.u_ao[1] * i.u_gtg[1] > 0  # eq. 5.27
    if mode == "gtg" and i.clearance < p.d_o and not clear_shot:
        turn = floornav.choose_turn(i.u_gtg, i.u_ao)  # eqs. 5.23/5.24
        return ("fw_cw" if turn == floornav.Turn.CLOCKWISE else "fw_ccw"), i.goal_distance
    if mode.startswith("fw"):
        progress = i.goal_distance < d_tau - p.progress_margin  # eqs. 5.25/5.26
        if (progress and clear_shot) or not i.obstacle_sensed:
            return "gtg", math.inf
    return mode, d_tau


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default="out/examples", help="folder for the picture")
    ap.add_argument("--quick", action="store_true", help="(for CI) nothing is skipped here: ~2 s")
    args = ap.parse_args(argv)
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    # The chapter's robot has no safety layer under its supervisor, and go-to-goal alone must be
    # seen to drive into the cylinder: the three supervisors run with it off. The built-in hybrid
    # runs as shipped (docs/SAFETY.md).
    scene = floornav.load_scenario(SCENE, {"controller.safety": "off"})
    print(f"{scene.name}: {scene.robots[0]['preset']} from {scene.robots[0]['start'][:2]} "
          f"to {scene.robots[0]['goals'][0]}")
    runs = {}
    for name, sup in [("go to goal", go_to_goal_only), ("GTG + AO (hard switch)", hard_switch),
                      ("wall following", wall_following)]:
        path, modes, switches, status, t = drive(scene, sup)
        runs[name] = path
        print(f"  {name:24s} {status:9s} t = {t:6.1f} s, {switches:4d} switches")
    builtin = floornav.run(floornav.load_scenario(SCENE))  # floornav's own Fig 5.11 automaton
    s = builtin.summary
    print(f"  {'built-in hybrid':24s} {s['status']:9s} t = {s['sim_time']:6.1f} s, "
          f"{s['mode_switches']:4d} switches")

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    ax = floornav.plot(builtin, title="CoppeliaSim scene: three supervisors and the built-in hybrid")
    for (name, path), style in zip(runs.items(), ["--", ":", "-."]):
        xs, ys = zip(*path)
        ax.plot(xs, ys, style, color="#555555", linewidth=1.2, label=name)
    ax.legend(fontsize=7, loc="lower left")
    picture = out / "01_chapter_simulation.png"
    ax.figure.savefig(picture, dpi=90)
    plt.close(ax.figure)
    print(f"-> {picture}")


if __name__ == "__main__":
    main()
