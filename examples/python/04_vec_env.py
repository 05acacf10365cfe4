"""A VecEnv loop: many robots stepped together in C++, a policy in numpy.

floornav.VecEnv has the shape of a Gymnasium vector environment (reset -> obs, info; step ->
obs, reward, terminated, truncated, info) without depending on Gymnasium, so an RL library's
rollout loop can drive it. Here a hand-written numpy policy stands in for a learned one: head for
the goal, pushed away from the nearest returns of the range sensors (a vectorised blend of
go-to-goal and avoid-obstacle, eq. 5.21), for every copy at once. Copies start from different
places (a list of scenarios, one per copy); copies whose run ends restart at once ("same-step"
autoreset) and report their final observation in info["final_obs"].

Run: PYTHONPATH=build/python /usr/bin/python3 examples/python/04_vec_env.py
"""

from __future__ import annotations

import argparse
import pathlib
import time

import numpy as np

import floornav

HERE = pathlib.Path(__file__).resolve().parent
WORLD = HERE.parents[1] / "scenarios" / "circle_obstacle.yaml"


def policy(obs, v_max=0.2, k_heading=3.0, reach=0.25):
    """(v, omega) per copy: the goal direction plus a repulsion from every sensed point nearer
    than `reach`, then a heading controller (eqs. 5.12-5.15, P only)."""
    x, y, theta = obs["pose"].T
    to_goal = obs["goal"] - obs["pose"][:, :2]
    u = to_goal / np.maximum(np.linalg.norm(to_goal, axis=1, keepdims=True), 1e-9)
    away = obs["pose"][:, None, :2] - obs["points"]  # (n, beams, 2): beam ends, max range if no return
    dist = np.linalg.norm(away, axis=2)
    weight = np.where(dist < reach, (reach - dist) / (reach * np.maximum(dist, 1e-3)), 0.0)
    weight = np.nan_to_num(weight)
    u = u + 2.0 * np.sum(np.nan_to_num(away) * weight[..., None], axis=1)
    error = np.arctan2(u[:, 1], u[:, 0]) - theta
    error = np.arctan2(np.sin(error), np.cos(error))
    v = v_max * np.clip(np.cos(error), 0.0, None)
    return np.stack([v, k_heading * error], axis=1)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default="out/examples", help="(unused: prints only)")
    ap.add_argument("--quick", action="store_true", help="32 copies, 400 steps (for CI)")
    ap.add_argument("--envs", type=int, default=256)
    ap.add_argument("--steps", type=int, default=3000)
    args = ap.parse_args(argv)
    n = 32 if args.quick else args.envs
    steps = 400 if args.quick else args.steps

    # One scenario per copy: the chapter's disc, with starts spread over the space before it.
    rng = np.random.default_rng(0)
    starts = [[float(rng.uniform(-0.3, 0.3)), float(rng.uniform(-0.6, 0.6)),
               float(rng.uniform(-0.5, 0.5))] for _ in range(n)]
    scenarios = [floornav.load_scenario(WORLD, {"robot.start": s, "robot.sensors.noise": 0.005})
                 for s in starts]
    env = floornav.VecEnv(scenarios, seed=1)
    print(env, f"actions within {env.action_low} .. {env.action_high}")

    obs, info = env.reset(seed=1)
    ended = {name: 0 for name in floornav.STATUS_NAMES[1:]}
    returns = []
    t0 = time.perf_counter()
    for _ in range(steps):
        actions = np.clip(policy(obs), env.action_low, env.action_high)
        obs, reward, terminated, truncated, info = env.step(actions)
        done = terminated | truncated
        if done.any():
            for code in info["status"][done]:
                ended[floornav.STATUS_NAMES[code]] += 1
            returns.extend(info["episode_return"][done])
            # info["final_obs"] holds where the ended copies stopped; obs already restarted them
            assert np.all(obs["t"][done] == 0.0)
    wall = time.perf_counter() - t0
    episodes = sum(ended.values())
    print(f"{n} copies x {steps} steps = {n * steps:,} robot-steps in {wall:.2f} s "
          f"({n * steps / wall:,.0f} robot-steps/s with the numpy policy)")
    print(f"{episodes} episodes ended: " + ", ".join(f"{k} {v}" for k, v in ended.items()))
    if returns:
        print(f"mean return {np.mean(returns):.3f} (progress in metres, +1 per goal, -1 per collision)")
    return ended


if __name__ == "__main__":
    main()
