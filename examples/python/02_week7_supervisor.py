"""A student's supervisor for the course's week-7 pocket, written in Python.

Week 7 of the course (Sim.I.Am / pySimiam, worlds/week7.xml: scenarios/week7_pocket.yaml) asks
for a supervisor that gets a QuickBot out of a U-shaped pocket that opens away from the goal,
within 30 s. This one is built the way the course builds it, as a hybrid automaton on
floornav's engine (floornav.AutomatonBuilder) over floornav's behaviours:

  go_to_goal -> follow_wall_{left,right}  an obstacle is near (d_at_obs) and go-to-goal would
                                          slide along it that way ("sliding": u_gtg is a positive
                                          combination of u_fw and u_ao), remembering d_progress
  follow_wall -> go_to_goal               progress was made (closer than d_progress) and u_gtg no
                                          longer slides along the wall
  any -> avoid_obstacle -> go_to_goal     too close (d_unsafe), then clear again
  any -> stop                             at the goal

The controller hands floornav a velocity u each step; the simulator turns it into wheel speeds
through the chapter's pipeline (Fig 5.12). Prints the run and its transitions (with the guard
names), and writes a picture and an animated GIF.

Run: PYTHONPATH=build/python /usr/bin/python3 examples/python/02_week7_supervisor.py
"""

from __future__ import annotations

import argparse
import math
import pathlib

import floornav
from floornav import Turn

HERE = pathlib.Path(__file__).resolve().parent
POCKET = HERE.parents[1] / "scenarios" / "week7_pocket.yaml"


class Progress:
    """The supervisor's memory: the distance to the goal when wall following began."""

    def __init__(self):
        self.d_progress = math.inf


def sliding(u_fw, u_gtg, u_ao):
    """The course's sliding condition: u_fw = s1 u_gtg + s2 u_ao with s1, s2 > 0, i.e. the wall
    direction lies between go-to-goal and avoid-obstacle, so switching between those two would
    chatter along the wall that way (the induced mode): follow the wall instead."""
    det = u_gtg[0] * u_ao[1] - u_gtg[1] * u_ao[0]
    if abs(det) < 1e-12:
        return False
    s1 = (u_fw[0] * u_ao[1] - u_fw[1] * u_ao[0]) / det
    s2 = (u_gtg[0] * u_fw[1] - u_gtg[1] * u_fw[0]) / det
    return s1 > 0 and s2 > 0


class StudentSupervisor:
    """A controller object: floornav calls decide(observation) every step."""

    def __init__(self, d_at_obs=0.10, d_unsafe=0.03, d_fw=0.07, margin=0.05):
        self.d_at_obs, self.d_unsafe, self.d_fw, self.margin = d_at_obs, d_unsafe, d_fw, margin
        self.params = None
        self.automaton = None

    def build(self, p: floornav.NavigationParams) -> floornav.HybridAutomaton:
        d_at_obs, d_unsafe, d_fw, margin = self.d_at_obs, self.d_unsafe, self.d_fw, self.margin

        def follow(turn):
            def flow(i, m):
                if not i.obstacle_sensed:
                    return i.u_gtg
                return floornav.follow_boundary_velocity(i.away, i.clearance, turn, d_fw, p.k_fb, p.v0)
            return flow

        def slides(turn):
            return lambda i, m: (i.obstacle_sensed and i.clearance < d_at_obs and sliding(
                floornav.follow_boundary_tangent(i.u_ao, turn), i.u_gtg, i.u_ao))

        def remember(i, m):
            m.d_progress = i.goal_distance

        def progress_made(turn):
            return lambda i, m: (i.goal_distance < m.d_progress - margin and not sliding(
                floornav.follow_boundary_tangent(i.u_ao, turn), i.u_gtg, i.u_ao))

        b = floornav.AutomatonBuilder()
        b.add_mode("go_to_goal", lambda i, m: i.u_gtg)
        b.add_mode("follow_wall_right", follow(Turn.CLOCKWISE))
        b.add_mode("follow_wall_left", follow(Turn.COUNTER_CLOCKWISE))
        b.add_mode("avoid_obstacle", lambda i, m: i.u_ao)
        b.add_mode("stop", lambda i, m: (0.0, 0.0), terminal=True)
        b.add_edge_from_every_mode("stop", "at_goal", lambda i, m: i.goal_distance < p.epsilon)
        for mode in ["go_to_goal", "follow_wall_right", "follow_wall_left"]:
            b.add_edge(mode, "avoid_obstacle", "unsafe", lambda i, m: i.clearance < d_unsafe)
        b.add_edge("go_to_goal", "follow_wall_right", "sliding_right", slides(Turn.CLOCKWISE), remember)
        b.add_edge("go_to_goal", "follow_wall_left", "sliding_left", slides(Turn.COUNTER_CLOCKWISE), remember)
        b.add_edge("follow_wall_right", "go_to_goal", "progress_made", progress_made(Turn.CLOCKWISE))
        b.add_edge("follow_wall_left", "go_to_goal", "progress_made", progress_made(Turn.COUNTER_CLOCKWISE))
        b.add_edge("avoid_obstacle", "go_to_goal", "safe", lambda i, m: i.clearance > 2 * d_unsafe)
        b.set_initial("go_to_goal")
        return b.build()

    # --- the controller protocol -------------------------------------------------------------
    @property
    def mode_names(self):
        return self._automaton().mode_names

    @property
    def guard_names(self):
        return self._automaton().guard_names

    def _automaton(self):
        if self.automaton is None:
            self.automaton = self.build(self.params or floornav.NavigationParams())
        return self.automaton

    def reset(self):
        self.state = self._automaton().initial_state(Progress())

    @property
    def mode(self):
        return self.state.mode

    def decide(self, obs):
        a = self._automaton()
        i = floornav.navigation_input(obs)
        tr = a.step(i, self.state, obs["t"] + obs["dt"], obs["dt"])
        guard = None if tr is None else tr.edge
        if a.is_terminal(self.state):
            return floornav.Decision(floornav.Command.goal_reached(), self.state.mode, guard)
        return floornav.Decision({"u": a.flow(i, self.state)}, self.state.mode, guard)


def factory(context):
    sup = StudentSupervisor()
    sup.params = context["params"]
    return sup


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default="out/examples", help="folder for the picture and the GIF")
    ap.add_argument("--quick", action="store_true", help="a short GIF (for CI)")
    args = ap.parse_args(argv)
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    pocket = floornav.load_scenario(POCKET)
    r = floornav.run(pocket, factory=factory, kind="student")
    s = r.summary
    print(f"{s['scenario']} with the student supervisor: {s['status']} in {s['sim_time']:.1f} s "
          f"(the course asks for 30 s), path {s['path_length']:.2f} m, "
          f"min clearance {s['min_clearance']:.3f} m")
    for tr in r.transitions:
        print(f"  t = {tr['t']:5.2f} s  {tr['from']:>17s} -> {tr['to']:<17s} ({tr['guard']})")
    builtin = floornav.run(pocket)
    print(f"floornav's built-in hybrid: {builtin.status} in {builtin.summary['sim_time']:.1f} s")

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    ax = floornav.plot(r)
    ax.figure.savefig(out / "02_week7_supervisor.png", dpi=90)
    plt.close(ax.figure)
    frames = floornav.animate(r, out / "02_week7_supervisor.gif", fps=10, speed=3.0,
                              max_frames=12 if args.quick else 120, dpi=60)
    print(f"-> {out / '02_week7_supervisor.png'}, {out / '02_week7_supervisor.gif'} ({frames} frames)")
    return r


if __name__ == "__main__":
    main()
