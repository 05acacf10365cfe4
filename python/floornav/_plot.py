"""Pictures of runs with matplotlib: :func:`plot` draws what trajectory.svg shows (the world, the
path coloured by mode, the switch points, start and goals); :func:`animate` replays the run."""

from __future__ import annotations

from typing import Any, Optional

import numpy as np

# The colours of trajectory.svg (src/render/trajectory_svg.cpp), so pictures match.
MODE_COLOURS = {
    "go_to_goal": "#1f77b4",
    "follow_boundary_cw": "#ff7f0e",
    "follow_boundary_ccw": "#2ca02c",
    "avoid_obstacle": "#d62728",
    "blended": "#9467bd",
    "stop": "#000000",
}
SPARE_COLOURS = ["#8c564b", "#e377c2", "#17becf", "#bcbd22", "#7f7f7f"]
OBSTACLE_FILL = "#c9ccd1"
OBSTACLE_EDGE = "#6b7079"
WALL = "#37474f"
GOAL_FILL = "#f4b400"
GOAL_EDGE = "#8a6d00"
PERSON = "#7b3fa0"
FORKLIFT = "#b35900"


def robot_colour(index: int) -> str:
    """Robot ``index``'s colour in trajectory.svg (a fleet's picture colours by robot)."""
    from . import _floornav

    return _floornav._robot_colour(index)


def _switch_rows(mode: np.ndarray) -> np.ndarray:
    """Rows where the mode changes (the state after the first step of the new mode)."""
    return np.flatnonzero(mode[1:] != mode[:-1]) + 1 if len(mode) else np.array([], int)


def _forklift_corners(x: float, y: float, th: float, size) -> list:
    length, width = size
    c, s = np.cos(th), np.sin(th)
    return [(x + c * a - s * b, y + s * a + c * b)
            for a, b in ((length / 2, width / 2), (-length / 2, width / 2),
                         (-length / 2, -width / 2), (length / 2, -width / 2))]


def draw_crowd(ax: Any, crowd: dict, last: bool = True) -> list:
    """The people's tracks and where they ended (discs), the forklifts' tracks and where they
    ended (rectangles); returns legend handles for what was drawn."""
    from matplotlib.lines import Line2D
    from matplotlib.patches import Circle, Polygon

    handles = []
    for p in crowd["people"]:
        xy = p["samples"]
        if len(xy) == 0:
            continue
        ax.plot(xy[:, 1], xy[:, 2], color=PERSON, linewidth=0.8, alpha=0.45, zorder=2)
        if last:
            ax.add_patch(Circle((xy[-1, 1], xy[-1, 2]), p["size"][0] / 2, facecolor=PERSON,
                                edgecolor="white", linewidth=0.6, alpha=0.9, zorder=5))
    if crowd["people"]:
        handles.append(Line2D([0], [0], marker="o", linestyle="-", color=PERSON, markersize=7,
                              label="person (track, last position)"))
    for f in crowd["forklifts"]:
        xy = f["samples"]
        if len(xy) == 0:
            continue
        ax.plot(xy[:, 1], xy[:, 2], color=FORKLIFT, linewidth=0.8, alpha=0.45, zorder=2)
        if last:
            ax.add_patch(Polygon(_forklift_corners(xy[-1, 1], xy[-1, 2], xy[-1, 3], f["size"]),
                                 closed=True, facecolor=FORKLIFT, edgecolor="white",
                                 linewidth=0.6, alpha=0.9, zorder=5))
    if crowd["forklifts"]:
        handles.append(Line2D([0], [0], marker="s", linestyle="-", color=FORKLIFT, markersize=7,
                              label="forklift (track, last position)"))
    return handles


def mode_colours(names) -> dict:
    """A colour per mode name: the SVG's for floornav's modes, spare ones for others."""
    out, spare = {}, 0
    for n in names:
        if n in MODE_COLOURS:
            out[n] = MODE_COLOURS[n]
        elif n not in out:
            out[n] = SPARE_COLOURS[spare % len(SPARE_COLOURS)]
            spare += 1
    return out


def draw_world(ax: Any, world: dict) -> None:
    """Obstacles (circles, polygons, an occupancy map) and the bounding walls."""
    from matplotlib.patches import Circle, Polygon, Rectangle

    grid = world.get("grid")
    if grid is not None:
        occ = np.asarray(grid["occupied"])
        res = grid["resolution"]
        ox, oy, _ = grid["origin"]
        h, w = occ.shape
        rgba = np.zeros((h, w, 4))
        rgba[occ] = (0.66, 0.68, 0.70, 1.0)
        ax.imshow(rgba, origin="lower", extent=(ox, ox + w * res, oy, oy + h * res),
                  interpolation="nearest", zorder=0)
    for x, y, r in world["circles"]:
        ax.add_patch(Circle((x, y), max(r, 0.01), facecolor=OBSTACLE_FILL, edgecolor=OBSTACLE_EDGE,
                            linewidth=0.8, zorder=1))
    for poly in world["polygons"]:
        ax.add_patch(Polygon(np.asarray(poly), closed=True, facecolor=OBSTACLE_FILL,
                             edgecolor=OBSTACLE_EDGE, linewidth=0.8, zorder=1))
    b = world.get("bounds")
    if b is not None:
        x0, y0, x1, y1 = b
        ax.add_patch(Rectangle((x0, y0), x1 - x0, y1 - y0, fill=False, edgecolor=WALL,
                               linewidth=2.0, zorder=2))


def _runs(result: Any) -> list:
    """(robot name, rows) per robot: the trajectory split by its `robot` column for a fleet."""
    traj = result.trajectory
    if "robot" not in traj:
        return [(None, traj)]
    out = []
    names = traj["robot"]
    for name in dict.fromkeys(names.tolist()):
        keep = names == name
        out.append((name, {k: v[keep] for k, v in traj.items()}))
    return out


def _segments_by_mode(t: dict):
    """Consecutive rows of one mode as polylines: (mode, xs, ys) in order."""
    x, y, mode = t["x"], t["y"], t["mode"]
    if len(x) == 0:
        return []
    cuts = np.flatnonzero(mode[1:] != mode[:-1]) + 1
    starts = np.concatenate(([0], cuts))
    ends = np.concatenate((cuts, [len(x)]))
    # Row k is the state after the step driven in mode[k]: that stretch runs from row k-1 to k.
    return [(mode[s], x[max(s - 1, 0):e], y[max(s - 1, 0):e]) for s, e in zip(starts, ends)]


def plot(result: Any, ax: Any = None, *, title: Optional[str] = None, legend: bool = True,
         switches: bool = True, crowd_positions: bool = True) -> Any:
    """Draws ``result`` (a floornav.RunResult with its trajectory recorded) on ``ax`` (a new
    figure if None): the world, a lone robot's path coloured by mode (a fleet's: a colour per
    robot, trajectory.svg's), a circle at every mode switch, the start poses and the goals, the
    people's and forklifts' tracks and where they ended; the legend beside the axes. Returns the
    Axes."""
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D

    if ax is None:
        _, ax = plt.subplots(figsize=(7, 6))
    scenario = result.scenario
    draw_world(ax, scenario.world)
    runs = _runs(result)
    fleet = result.is_fleet and len(scenario.robots) > 1
    names = []
    handles = []
    if fleet:  # a colour per robot; mode switches as dots in the robot's colour
        index = {r["name"]: i for i, r in enumerate(scenario.robots)}
        for name, t in runs:
            colour = robot_colour(index.get(name, 0))
            ax.plot(t["x"], t["y"], color=colour, linewidth=1.6, solid_capstyle="round", zorder=3)
            if switches:
                rows = _switch_rows(t["mode"])
                ax.plot(t["x"][rows], t["y"][rows], "o", markersize=4, markerfacecolor="white",
                        markeredgecolor=colour, markeredgewidth=1.0, zorder=4)
            handles.append(Line2D([0], [0], color=colour, linewidth=2.5, label=name))
        if len(handles) > 12:  # a legend of 100 robots covers everything: say how many
            handles = [Line2D([0], [0], color="#555555", linewidth=2.5,
                              label=f"{len(runs)} robots, a colour each")]
        if switches and any(len(_switch_rows(t["mode"])) for _, t in runs):
            handles.append(Line2D([0], [0], marker="o", linestyle="", markerfacecolor="white",
                                  markeredgecolor="#222222", label="mode switch"))
    else:
        for _, t in runs:
            names.extend(n for n in dict.fromkeys(t["mode"].tolist()) if n not in names)
        colours = mode_colours(names)
        for _, t in runs:
            for mode, xs, ys in _segments_by_mode(t):
                ax.plot(xs, ys, color=colours[mode], linewidth=1.8, solid_capstyle="round", zorder=3)
        if switches:
            if result.transitions:
                points = [(tr["x"], tr["y"]) for tr in result.transitions]
            else:  # a robot among people runs as a fleet of one: switches from the mode column
                points = [(t["x"][k], t["y"][k]) for _, t in runs for k in _switch_rows(t["mode"])]
            for x, y in points:
                ax.plot(x, y, "o", markersize=5, markerfacecolor="white",
                        markeredgecolor="#222222", markeredgewidth=0.9, zorder=4)
        handles = [Line2D([0], [0], color=colours[n], linewidth=2.5, label=n) for n in names]
        if switches and (result.transitions or any(len(_switch_rows(t["mode"])) for _, t in runs)):
            handles.append(Line2D([0], [0], marker="o", linestyle="", markerfacecolor="white",
                                  markeredgecolor="#222222", label="mode switch"))
    handles += draw_crowd(ax, result.crowd, last=crowd_positions)
    for robot in scenario.robots:
        x, y, th = robot["start"]
        r = robot["body_radius"]
        ax.add_patch(plt.Circle((x, y), r, facecolor="white", edgecolor="#333333", zorder=5))
        ax.plot([x, x + r * np.cos(th)], [y, y + r * np.sin(th)], color="#333333", zorder=6)
        for k, (gx, gy) in enumerate(robot["goals"]):
            ax.plot(gx, gy, marker="*", markersize=14, markerfacecolor=GOAL_FILL,
                    markeredgecolor=GOAL_EDGE, zorder=5)
            if len(robot["goals"]) > 1:
                ax.annotate(str(k + 1), (gx, gy), xytext=(5, 5), textcoords="offset points",
                            fontsize=8, color="#5c4800")
        if scenario.is_fleet:
            ax.annotate(robot["name"], (x, y), xytext=(6, -10), textcoords="offset points",
                        fontsize=7, color="#333333")
    for name, t in runs:
        if len(t["x"]):
            ax.plot(t["x"][-1], t["y"][-1], "o", markersize=6,
                    color="#d62728" if result.status == "collision" else "#90a4ae", zorder=5)
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    s = result.summary
    ax.set_title(title if title is not None else
                 f"{s['scenario']}: {s['status']} in {s['sim_time']:.1f} s, "
                 f"{s['mode_switches']} switches")
    if legend and handles:
        # Beside the scene, not on it: a legend over a floor hides robots and people.
        ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8,
                  framealpha=0.9, borderaxespad=0.0)
    ax.autoscale_view()
    return ax


def frame_times(result: Any, *, fps: int = 20, speed: float = 1.0, max_frames: int = 400) -> np.ndarray:
    """The simulated times :func:`animate` shows: ``fps`` frames per second of animation at
    ``speed`` simulated seconds per second, the first at t = 0 and the last at the end of the
    run; at most ``max_frames``, spread over the whole run."""
    if fps < 1 or speed <= 0 or max_frames < 2:
        raise ValueError("fps >= 1, speed > 0 and max_frames >= 2 are needed")
    runs = _runs(result)
    if not any(len(t["t"]) for _, t in runs):
        raise ValueError("the run has no trajectory (sim.record_trajectory was off)")
    t_end = max(float(t["t"][-1]) for _, t in runs if len(t["t"]))
    frames = int(min(max_frames, max(2, np.ceil(t_end / speed * fps) + 1)))
    return np.linspace(0.0, t_end, frames)


def animate(result: Any, path: str, *, fps: int = 20, speed: float = 1.0,
            max_frames: int = 400, dpi: int = 80) -> int:
    """Writes an animation of ``result`` to ``path``: each robot (its body and heading) moving
    along its path, the path so far coloured by mode (a fleet's: a colour per robot), the people
    and forklifts moving along their tracks, the time. ``speed`` simulated seconds per
    second of animation; at most ``max_frames`` frames (sped up if needed). A ``.gif`` is written
    with Pillow; other suffixes with the matplotlib writer that knows them (ffmpeg for .mp4).
    Returns the number of frames."""
    import matplotlib

    if matplotlib.get_backend().lower() not in ("agg", "pdf", "svg", "ps", "cairo"):
        matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt
    from matplotlib.animation import FuncAnimation, PillowWriter

    runs = _runs(result)
    times = frame_times(result, fps=fps, speed=speed, max_frames=max_frames)
    frames = len(times)

    fig, ax = plt.subplots(figsize=(6, 5), dpi=dpi)
    plot(result, ax=ax, switches=False, crowd_positions=False)
    for line in list(ax.lines):  # the full paths come back frame by frame
        if line.get_linewidth() in (1.8, 1.6):
            line.remove()
    names = []
    for _, t in runs:
        names.extend(n for n in dict.fromkeys(t["mode"].tolist()) if n not in names)
    colours = mode_colours(names)
    # A fleet: each robot in its colour (trajectory.svg's), not by mode.
    fleet = result.is_fleet and len(result.scenario.robots) > 1
    index = {r["name"]: i for i, r in enumerate(result.scenario.robots)}
    # People and forklifts moving along their tracks.
    from matplotlib.patches import Polygon

    movers = []
    for p in result.crowd["people"]:
        if len(p["samples"]):
            disc = plt.Circle(tuple(p["samples"][0, 1:3]), p["size"][0] / 2, facecolor=PERSON,
                              edgecolor="white", linewidth=0.6, zorder=6)
            ax.add_patch(disc)
            movers.append((p, disc))
    for f in result.crowd["forklifts"]:
        if len(f["samples"]):
            x0, y0, th0 = f["samples"][0, 1:4]
            box = Polygon(_forklift_corners(x0, y0, th0, f["size"]), closed=True,
                          facecolor=FORKLIFT, edgecolor="white", linewidth=0.6, zorder=6)
            ax.add_patch(box)
            movers.append((f, box))
    radius = {r["name"]: r["body_radius"] for r in result.scenario.robots}
    default_r = result.scenario.robots[0]["body_radius"]
    bodies, headings, trails = [], [], []
    for name, t in runs:
        r = radius.get(name, default_r)
        body = plt.Circle((t["x"][0], t["y"][0]), r, facecolor="#ffffff", edgecolor="#222222",
                          zorder=7)
        ax.add_patch(body)
        (heading,) = ax.plot([], [], color="#222222", linewidth=1.5, zorder=8)
        bodies.append(body)
        headings.append(heading)
        # The path so far, coloured by mode: one line per stretch of one mode.
        pieces = []
        mode = t["mode"]
        cuts = np.flatnonzero(mode[1:] != mode[:-1]) + 1 if len(mode) else np.array([], int)
        starts = np.concatenate(([0], cuts)) if len(mode) else []
        ends = np.concatenate((cuts, [len(mode)])) if len(mode) else []
        if fleet:
            starts, ends = [0], [len(mode)]
        for s0, e0 in zip(starts, ends):
            colour = robot_colour(index.get(name, 0)) if fleet else colours.get(mode[s0], "#888888")
            (line,) = ax.plot([], [], color=colour, linewidth=1.8, zorder=3)
            pieces.append((max(s0 - 1, 0), e0, line))
        trails.append(pieces)
    clock = ax.text(0.02, 0.97, "", transform=ax.transAxes, va="top", fontsize=9,
                    bbox=dict(facecolor="white", alpha=0.8, edgecolor="none"))

    def draw(k: int):
        now = times[k]
        artists = [clock]
        for (name, t), body, heading, pieces in zip(runs, bodies, headings, trails):
            if not len(t["t"]):
                continue
            i = int(np.searchsorted(t["t"], now, side="right")) - 1
            i = max(0, min(i, len(t["t"]) - 1))
            x, y, th = t["x"][i], t["y"][i], t["theta"][i]
            r = body.get_radius()
            body.center = (x, y)
            body.set_facecolor(robot_colour(index.get(name, 0)) if fleet
                               else colours.get(t["mode"][i], "#ffffff"))
            heading.set_data([x, x + 1.4 * r * np.cos(th)], [y, y + 1.4 * r * np.sin(th)])
            for s0, e0, line in pieces:
                stop = min(e0, i + 1)
                line.set_data(t["x"][s0:stop], t["y"][s0:stop]) if stop > s0 else line.set_data([], [])
                artists.append(line)
            artists += [body, heading]
        for track, patch in movers:
            xy = track["samples"]
            i = max(0, min(int(np.searchsorted(xy[:, 0], now, side="right")) - 1, len(xy) - 1))
            if isinstance(patch, Polygon):
                patch.set_xy(_forklift_corners(xy[i, 1], xy[i, 2], xy[i, 3], track["size"]))
            else:
                patch.center = (xy[i, 1], xy[i, 2])
            artists.append(patch)
        clock.set_text(f"t = {now:.1f} s")
        return artists

    anim = FuncAnimation(fig, draw, frames=frames, interval=1000 / fps, blit=False)
    if path.lower().endswith(".gif"):
        anim.save(path, writer=PillowWriter(fps=fps), dpi=dpi)
    else:
        anim.save(path, fps=fps, dpi=dpi)
    plt.close(fig)
    return frames
