"""floornav.plot draws what trajectory.svg shows; floornav.animate writes a GIF with Pillow."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from PIL import Image  # noqa: E402

import floornav  # noqa: E402
from conftest import SCENARIOS  # noqa: E402


def path_lines(ax):
    return [l for l in ax.lines if l.get_linewidth() == 1.8]


def test_plot_draws_the_world_the_path_by_mode_and_the_switches():
    r = floornav.run(floornav.load_scenario(SCENARIOS / "rectangle.yaml"))
    ax = floornav.plot(r)
    # go_to_goal, follow_boundary_cw, go_to_goal: one line per stretch of one mode
    lines = path_lines(ax)
    modes = r.trajectory["mode"]
    stretches = 1 + int(np.count_nonzero(modes[1:] != modes[:-1]))
    assert len(lines) == stretches == 3
    assert lines[0].get_color() == "#1f77b4" and lines[1].get_color() == "#ff7f0e"
    # the lines together hold the whole path
    xs = np.concatenate([l.get_xdata() for l in lines])
    assert xs.min() == r.trajectory["x"].min() and xs.max() == r.trajectory["x"].max()
    switches = [l for l in ax.lines if l.get_marker() == "o" and l.get_markerfacecolor() == "white"]
    assert len(switches) == len(r.transitions) == 3
    assert len(ax.patches) >= 3  # the rectangle, the bounds, the robot
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert labels == ["go_to_goal", "follow_boundary_cw", "mode switch"]
    assert "rectangle: reached" in ax.get_title()
    plt.close("all")


def test_plot_a_fleet_on_given_axes():
    r = floornav.run(floornav.load_scenario(SCENARIOS / "fleet_crossing.yaml"))
    fig, ax = plt.subplots()
    assert floornav.plot(r, ax=ax) is ax
    names = [t.get_text() for t in ax.texts]
    assert len([n for n in names if n]) >= 4  # every robot named at its start
    plt.close("all")


def test_plot_a_fleet_among_people_and_forklifts():
    s = floornav.load_scenario(SCENARIOS / "crowd" / "factory_people.yaml", {"sim.t_max": 6})
    r = floornav.run(s)
    ax = floornav.plot(r)
    colours = [floornav._plot.robot_colour(i) for i in range(6)]
    assert len(set(colours)) == 6
    paths = [l for l in ax.lines if l.get_linewidth() == 1.6]
    assert [l.get_color() for l in paths] == colours  # a colour per robot, not per mode
    for name, line in zip([f"amr{i}" for i in range(6)], paths):
        keep = r.trajectory["robot"] == name
        assert np.array_equal(line.get_xdata(), r.trajectory["x"][keep])
    # Mode switches, from each robot's mode column, as dots edged in its colour.
    switches = [l for l in ax.lines if l.get_marker() == "o" and l.get_markerfacecolor() == "white"
                and l.get_markeredgecolor() in colours]
    expected = sum(int(np.count_nonzero(m[1:] != m[:-1])) for m in
                   (r.trajectory["mode"][r.trajectory["robot"] == f"amr{i}"] for i in range(6)))
    assert expected > 0 and sum(len(l.get_xdata()) for l in switches) == expected
    # People and forklifts: a track each and where they ended.
    crowd = r.crowd
    assert len(crowd["people"]) == 10 and len(crowd["forklifts"]) == 2
    assert crowd["people"][0]["samples"].shape[1] == 4
    purple = [l for l in ax.lines if l.get_color() == "#7b3fa0"]
    orange = [l for l in ax.lines if l.get_color() == "#b35900"]
    assert len(purple) == 10 and len(orange) == 2
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert labels[:6] == [f"amr{i}" for i in range(6)]
    assert "mode switch" in labels and any("person" in l for l in labels)
    assert any("forklift" in l for l in labels)
    # The legend sits beside the axes, not over the floor.
    fig = ax.figure
    fig.canvas.draw()
    legend_box = ax.get_legend().get_window_extent()
    assert legend_box.x0 >= ax.get_window_extent().x1
    plt.close("all")


def test_animate_writes_a_gif(tmp_path):
    r = floornav.run(floornav.load_scenario(SCENARIOS / "week7_pocket.yaml"))
    from floornav._plot import frame_times

    # 28 s at 4x speed and 5 frames/s: 36 frames, the first included ...
    times = frame_times(r, fps=5, speed=4.0, max_frames=40)
    assert len(times) == 36 and times[0] == 0.0 and times[-1] == r.summary["sim_time"]
    # ... or at most max_frames, spread over the whole run
    frames = floornav.animate(r, tmp_path / "run.gif", fps=5, speed=4.0, max_frames=8, dpi=30)
    with Image.open(tmp_path / "run.gif") as im:
        assert im.format == "GIF"
        assert im.n_frames == frames == 8


def test_animate_a_fleet_with_people_and_forklifts_moving(tmp_path):
    s = floornav.load_scenario(SCENARIOS / "crowd" / "factory_people.yaml", {"sim.t_max": 4})
    r = floornav.run(s)
    frames = floornav.animate(r, tmp_path / "fleet.gif", fps=5, speed=4.0, max_frames=4, dpi=40)
    assert frames == 4
    pictures = []
    with Image.open(tmp_path / "fleet.gif") as im:
        for k in range(im.n_frames):
            im.seek(k)
            pictures.append(np.asarray(im.convert("RGB")).astype(int))

    def near(picture, rgb):  # pixels within a GIF palette's rounding of a colour
        return np.all(np.abs(picture - np.array(rgb)) <= 12, axis=2)

    person = [near(p, (123, 63, 160)) for p in pictures]
    assert all(m.sum() > 20 for m in person)        # people drawn in every frame ...
    assert not np.array_equal(person[0], person[-1])  # ... where they walk
    first_robot = floornav._plot.robot_colour(0)
    rgb = tuple(int(first_robot[i:i + 2], 16) for i in (1, 3, 5))
    assert near(pictures[-1], rgb).sum() > 0          # robot amr0 in its colour
    plt.close("all")


def test_animate_refuses_a_run_without_trajectory(tmp_path):
    r = floornav.run(floornav.load_scenario(SCENARIOS / "week7_pocket.yaml",
                                            {"sim.record_trajectory": False}))
    with pytest.raises(ValueError, match="no trajectory"):
        floornav.animate(r, tmp_path / "x.gif")
    assert not (tmp_path / "x.gif").exists()
