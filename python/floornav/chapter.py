"""The chapter's navigation automata written in Python, from floornav's behaviours and its
hybrid-automaton engine: a port of ``src/nav/navigation_automaton.cpp`` (the same modes, guards,
resets and edge order) that drives a robot exactly as the built-in controller kinds do.

``hybrid`` is the complete automaton of Fig 5.11::

    any   -> STOP   |x - x_g| < epsilon
    GTG   -> AO     clearance < d_unsafe
    GTG   -> FB-c   clearance < d_o, no clear shot, <u_GTG, u_FB^c> > 0 (eq. 5.23); d_tau := |x - x_g|
    GTG   -> FB-cc  the same with eq. 5.24
    FB    -> AO     clearance < d_unsafe
    FB    -> GTG    progress |x - x_g| < d_tau - delta (5.25/5.26) and clear shot (5.27); or boundary lost
    AO    -> FB     clearance >= d_unsafe + hysteresis, back in the direction it left
    AO    -> GTG    clearance >= d_unsafe + hysteresis

Use it as a controller::

    s = floornav.load_scenario("scenarios/rectangle.yaml")
    r = floornav.run(s, factory=floornav.chapter.factory("hybrid"), kind="hybrid")

The velocity u of each mode goes through the simulator's differential-drive pipeline (Fig 5.12),
as the built-in kinds' does, so the trajectory is the built-in one (tests/python asserts it).
"""

from __future__ import annotations

import math
from typing import Any, Callable

from ._floornav import (
    AutomatonBuilder,
    Command,
    Decision,
    HybridAutomaton,
    NavigationInput,
    NavigationParams,
    Turn,
    choose_turn,
    follow_boundary_velocity,
    navigation_input,
)

KINDS = ("go_to_goal", "hard_switch", "blended", "hybrid")

CW = Turn.CLOCKWISE
CCW = Turn.COUNTER_CLOCKWISE


class NavigationMemory:
    """The automaton's memory, written only by resets."""

    __slots__ = ("d_tau", "turn", "following")

    def __init__(self) -> None:
        self.d_tau: float = math.inf  # |x - x_g| when FB was entered (Fig 5.11's reset)
        self.turn: Turn = CW  # the direction FB took
        self.following: bool = False  # inside a boundary-following episode (FB, or AO from FB)

    def __deepcopy__(self, memo: dict) -> "NavigationMemory":
        m = NavigationMemory()
        m.d_tau, m.turn, m.following = self.d_tau, self.turn, self.following
        return m

    def __repr__(self) -> str:
        return f"NavigationMemory(d_tau={self.d_tau}, turn={self.turn}, following={self.following})"


def _dot(a: tuple, b: tuple) -> float:
    return a[0] * b[0] + a[1] * b[1]


def make_navigation_automaton(kind: str, p: NavigationParams) -> HybridAutomaton:
    """The automaton of ``kind`` (go_to_goal, hard_switch, blended, hybrid) with parameters
    ``p``, over :class:`NavigationInput` inputs and a :class:`NavigationMemory`."""
    from ._floornav import blend_velocities, blend_weight

    b = AutomatonBuilder()
    b.set_chatter_rule(p.chatter_switches, p.chatter_window)

    def gtg_flow(i: NavigationInput, m: Any) -> tuple:
        return i.u_gtg

    def ao_flow(i: NavigationInput, m: Any) -> tuple:
        return i.u_ao

    def stop_flow(i: NavigationInput, m: Any) -> tuple:
        return (0.0, 0.0)

    eps = p.epsilon

    def at_goal(i: NavigationInput, m: Any) -> bool:
        return i.goal_distance < eps

    corridor = p.clear_shot_corridor > 0.0

    def clear_shot(i: NavigationInput) -> bool:
        # Eq. 5.27, <u_AO, u_GTG> > 0; or, with the corridor extension on, a free corridor.
        return (not i.corridor_blocked) if corridor else _dot(i.u_ao, i.u_gtg) > 0.0

    if kind == "go_to_goal":
        gtg = b.add_mode("go_to_goal", gtg_flow)
        stop = b.add_mode("stop", stop_flow, terminal=True)
        b.add_edge(gtg, stop, "at_goal", at_goal)
        b.set_initial(gtg)
    elif kind == "blended":
        near, far = p.blend_near, p.blend_far

        def blend_flow(i: NavigationInput, m: Any) -> tuple:
            return blend_velocities(i.u_gtg, i.u_ao, blend_weight(i.clearance, near, far))  # 5.21

        blend = b.add_mode("blended", blend_flow)
        stop = b.add_mode("stop", stop_flow, terminal=True)
        b.add_edge(blend, stop, "at_goal", at_goal)
        b.set_initial(blend)
    elif kind == "hard_switch":  # Fig 5.7
        d_o = p.d_o
        gtg = b.add_mode("go_to_goal", gtg_flow)
        ao = b.add_mode("avoid_obstacle", ao_flow)
        stop = b.add_mode("stop", stop_flow, terminal=True)
        b.add_edge_from_every_mode(stop, "at_goal", at_goal)
        b.add_edge(gtg, ao, "obstacle_within_d_o", lambda i, m: i.clearance < d_o)
        b.add_edge(ao, gtg, "obstacle_beyond_d_o", lambda i, m: i.clearance >= d_o)
        b.set_initial(gtg)
    elif kind == "hybrid":  # Fig 5.11
        _add_hybrid(b, p, gtg_flow, ao_flow, stop_flow, at_goal, clear_shot)
    else:
        raise ValueError(f"unknown kind {kind!r}; one of {', '.join(KINDS)}")
    return b.build()


def _add_hybrid(b: AutomatonBuilder, p: NavigationParams, gtg_flow: Callable, ao_flow: Callable,
                stop_flow: Callable, at_goal: Callable, clear_shot: Callable) -> None:
    v0, d_fb, k_fb = p.v0, p.d_fb, p.k_fb

    def fb_flow(turn: Turn) -> Callable:
        def flow(i: NavigationInput, m: NavigationMemory) -> tuple:
            if not i.obstacle_sensed:
                return i.u_gtg  # nothing to follow: head for the goal
            return follow_boundary_velocity(i.away, i.clearance, turn, d_fb, k_fb, v0)

        return flow

    gtg = b.add_mode("go_to_goal", gtg_flow)
    fb_cw = b.add_mode("follow_boundary_cw", fb_flow(CW))
    fb_ccw = b.add_mode("follow_boundary_ccw", fb_flow(CCW))
    ao = b.add_mode("avoid_obstacle", ao_flow)
    stop = b.add_mode("stop", stop_flow, terminal=True)

    d_unsafe = p.d_unsafe
    safe = p.d_unsafe + p.hysteresis  # the fat guard AO is left at
    d_o = p.d_o

    def too_close(i: NavigationInput, m: NavigationMemory) -> bool:
        return i.clearance < d_unsafe

    # GTG -> FB: met an obstacle that is in the way, direction by eqs. 5.23/5.24.
    def meets(i: NavigationInput, turn: Turn) -> bool:
        return i.clearance < d_o and not clear_shot(i) and choose_turn(i.u_gtg, i.u_ao) == turn

    def start_following(turn: Turn) -> Callable:
        def reset(i: NavigationInput, m: NavigationMemory) -> None:
            m.d_tau = i.goal_distance  # the reset of Fig 5.11
            m.turn = turn
            m.following = True

        return reset

    def stop_following(i: NavigationInput, m: NavigationMemory) -> None:
        m.following = False

    b.add_edge_from_every_mode(stop, "at_goal", at_goal)
    b.add_edge(gtg, ao, "too_close", too_close)
    b.add_edge(gtg, fb_cw, "obstacle_ahead_cw", lambda i, m: meets(i, CW), start_following(CW))
    b.add_edge(gtg, fb_ccw, "obstacle_ahead_ccw", lambda i, m: meets(i, CCW), start_following(CCW))

    delta = p.progress_margin

    def progress_and_clear_shot(i: NavigationInput, m: NavigationMemory) -> bool:
        return i.goal_distance < m.d_tau - delta and clear_shot(i)  # 5.26, 5.27

    def boundary_lost(i: NavigationInput, m: NavigationMemory) -> bool:
        return not i.obstacle_sensed

    for fb in (fb_cw, fb_ccw):
        b.add_edge(fb, ao, "too_close", too_close)
        b.add_edge(fb, gtg, "progress_and_clear_shot", progress_and_clear_shot, stop_following)
        b.add_edge(fb, gtg, "boundary_lost", boundary_lost, stop_following)

    # AO -> FB: back in the direction the episode took; a fresh episode picks its direction and
    # stores d_tau like GTG -> FB does.
    def resumes(turn: Turn) -> Callable:
        def guard(i: NavigationInput, m: NavigationMemory) -> bool:
            if not i.clearance >= safe:
                return False
            if m.following:
                return m.turn == turn
            return not clear_shot(i) and choose_turn(i.u_gtg, i.u_ao) == turn

        return guard

    def resume_reset(turn: Turn) -> Callable:
        def reset(i: NavigationInput, m: NavigationMemory) -> None:
            if not m.following:
                m.d_tau = i.goal_distance
            m.turn = turn
            m.following = True

        return reset

    b.add_edge(ao, fb_cw, "safe_again_cw", resumes(CW), resume_reset(CW))
    b.add_edge(ao, fb_ccw, "safe_again_ccw", resumes(CCW), resume_reset(CCW))
    b.add_edge(ao, gtg, "safe_again_clear_shot", lambda i, m: i.clearance >= safe)
    b.set_initial(gtg)


class AutomatonController:
    """A controller running a navigation automaton the way the built-in kinds do: each step,
    the supervisor's input from the observation (:func:`floornav.navigation_input`), at most one
    guarded transition at t + dt, then the mode's velocity u, handed to the pipeline of
    Fig 5.12; STOP reports the goal reached."""

    def __init__(self, automaton: HybridAutomaton,
                 memory: Callable[[], Any] = NavigationMemory) -> None:
        self.automaton = automaton
        self.mode_names = automaton.mode_names
        self.guard_names = automaton.guard_names
        self._memory = memory
        self.reset()

    def reset(self) -> None:
        self.state = self.automaton.initial_state(self._memory())

    @property
    def mode(self) -> int:
        return self.state.mode

    def decide(self, obs: dict) -> Decision:
        a = self.automaton
        i = navigation_input(obs)
        tr = a.step(i, self.state, obs["t"] + obs["dt"], obs["dt"])
        guard = None if tr is None else tr.edge
        if a.is_terminal(self.state):
            return Decision(Command.goal_reached(), self.state.mode, guard)
        return Decision(Command.velocity(a.flow(i, self.state)), self.state.mode, guard)


def factory(kind: str = "hybrid") -> Callable[[dict], AutomatonController]:
    """A controller factory (one AutomatonController per robot, built with that robot's
    ``controller:`` parameters) for Scenario.with_controller / floornav.run."""
    if kind not in KINDS:
        raise ValueError(f"unknown kind {kind!r}; one of {', '.join(KINDS)}")

    def make(context: dict) -> AutomatonController:
        return AutomatonController(make_navigation_automaton(kind, context["params"]))

    return make
