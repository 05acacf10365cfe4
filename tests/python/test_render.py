"""render_mode="rgb_array": frames drawn in C++ show the world, each robot where it stands (in its
colour), people and forklifts; render() without the mode or before reset() is a ValueError."""

from __future__ import annotations

import numpy as np
import pytest

import floornav
from conftest import SCENARIOS

PERSON = (123, 63, 160)   # trajectory.svg's colours
FORKLIFT = (179, 89, 0)
OBSTACLE = (201, 204, 209)


def rect(**sets):
    return floornav.load_scenario(SCENARIOS / "rectangle.yaml", sets or None)


def pixel_of(x, y, bounds, shape):
    """Where the frame draws world point (x, y): the bounds with a 3 % margin, fitted and
    centred (FrameRaster)."""
    h, w = shape
    x0, y0, x1, y1 = bounds
    m = 0.03 * max(x1 - x0, y1 - y0)
    x0, y0, x1, y1 = x0 - m, y0 - m, x1 + m, y1 + m
    scale = min(w / (x1 - x0), h / (y1 - y0))
    left = (x0 + x1) / 2 - w / 2 / scale
    top = (y0 + y1) / 2 + h / 2 / scale
    return int(top * scale - y * scale), int((x - left) * scale)


def colours(frame):
    return {tuple(c) for c in frame.reshape(-1, 3)}


def test_vec_env_frames_show_each_copy_where_it_stands():
    env = floornav.VecEnv(rect(), 3, render_mode="rgb_array", render_shape=(120, 200),
                          randomize={"start": "free"})
    assert "rgb_array" in env.metadata["render_modes"] and env.metadata["render_fps"] == 100
    obs, _ = env.reset(seed=2)
    frames = env.render()
    assert frames.shape == (3, 120, 200, 3) and frames.dtype == np.uint8
    robot = tuple(frames[0][pixel_of(*obs["pose"][0][:2], (-0.5, -1.2, 3.0, 1.2), (120, 200))])
    assert robot not in {(255, 255, 255), OBSTACLE}  # the body is drawn there
    for i in range(3):  # each copy's robot at its own start
        r, c = pixel_of(*obs["pose"][i][:2], (-0.5, -1.2, 3.0, 1.2), (120, 200))
        assert tuple(frames[i][r, c]) == robot
    r, c = pixel_of(1.2, 0.0, (-0.5, -1.2, 3.0, 1.2), (120, 200))
    assert tuple(frames[0][r, c]) == OBSTACLE  # the rectangle's middle
    one = env.render([1])
    assert one.shape == (1, 120, 200, 3) and np.array_equal(one[0], frames[1])
    for _ in range(50):
        env.step(np.tile([0.2, 0.0], (3, 1)))
    assert not np.array_equal(env.render(), frames)  # the robots moved


def test_render_needs_the_mode_and_a_reset():
    with pytest.raises(ValueError, match="rgb_array"):
        floornav.VecEnv(rect(), 1).render()
    with pytest.raises(ValueError, match="reset"):
        floornav.VecEnv(rect(), 1, render_mode="rgb_array").render()
    with pytest.raises(ValueError, match="render_mode"):
        floornav.VecEnv(rect(), 1, render_mode="human")
    with pytest.raises(ValueError, match="render_shape"):
        floornav.VecEnv(rect(), 1, render_mode="rgb_array", render_shape=(4, 4))
    env = floornav.VecEnv(rect(), 2, render_mode="rgb_array")
    env.reset()
    with pytest.raises(ValueError, match="copy 2 of 2"):
        env.render([2])


def test_parallel_env_frames_show_people_forklifts_and_every_robot():
    s = floornav.load_scenario(SCENARIOS / "crowd" / "factory_people.yaml", {"sim.t_max": 1.0})
    env = floornav.ParallelEnv(s, render_mode="rgb_array", render_shape=(200, 320))
    env.reset()
    frame = env.render()
    assert frame.shape == (200, 320, 3) and frame.dtype == np.uint8
    seen = colours(frame)
    assert PERSON in seen and FORKLIFT in seen and OBSTACLE in seen
    assert len(seen) >= 3 + 6  # a colour per robot besides the floor's
    env.step({a: None for a in env.agents})
    assert not np.array_equal(env.render(), frame)  # people and forklifts move
