"""PPO trains a range-sensor policy on floornav.VecEnv, on a new generated floor every episode.

A short, readable PPO (clipped surrogate, GAE, one Gaussian policy and a value head in PyTorch,
Debian's python3-torch). Every episode of every copy runs on a factory floor generated for it
(randomize={"floor": "factory_floor"}: a 20 x 20 m hall of 50 random obstacles, drawn from the
training floors' seeds) with its start and a goal a few metres away drawn anew. The policy sees
the robot's ranges (scaled to [0, 1]) and its goal in its own frame; it outputs (v, omega)
within the robot's limits. Every few iterations it is evaluated greedily on held-out floors
(seeds never trained on, the same episodes each time): the share of episodes that reach the
goal. Writes a learning curve and the figures as JSON.

Run: PYTHONPATH=build/python /usr/bin/python3 examples/python/05_train_ppo.py [--minutes 30]
(--quick: a few small iterations, the CI's smoke test.)
"""

from __future__ import annotations

import argparse
import json
import pathlib
import time

import numpy as np
import torch
from torch import nn

import floornav

ROOT = pathlib.Path(__file__).resolve().parents[2]
TEMPLATE = ROOT / "scenarios" / "floor_template.yaml"  # a QuickBot, its 5 IR sensors
SETTINGS = {"sim.dt": 0.05, "sim.t_max": 30, "robot.sensors.noise": 0.0}
EPISODE = {"start": "free", "goal": "free", "clearance": 0.02, "goal_distance": (0.3, 2.5)}
TRAIN_FLOORS = range(0, 1_000_000)            # each episode: one of these floors
HELD_OUT_FLOORS = range(1_000_000, 1_000_064)  # never trained on


def make_env(n, seed, floors):
    return floornav.VecEnv(floornav.load_scenario(TEMPLATE, SETTINGS), n, seed=seed,
                           randomize={"floor": "factory_floor", "floor_seeds": floors, **EPISODE})


def features(obs, max_range):
    """(n, beams + 3): ranges / max range, goal distance (capped at 3 m, / 3), and the goal's
    bearing in the robot's frame as cos and sin."""
    d = obs["goal"] - obs["pose"][:, :2]
    dist = np.linalg.norm(d, axis=1)
    bearing = np.arctan2(d[:, 1], d[:, 0]) - obs["pose"][:, 2]
    return np.column_stack([obs["ranges"] / max_range, np.minimum(dist, 3.0) / 3.0,
                            np.cos(bearing), np.sin(bearing)]).astype(np.float32)


class Policy(nn.Module):
    def __init__(self, n_in, high):
        super().__init__()
        self.body = nn.Sequential(nn.Linear(n_in, 64), nn.Tanh(), nn.Linear(64, 64), nn.Tanh())
        self.mean = nn.Linear(64, 2)
        self.value = nn.Linear(64, 1)
        self.log_std = nn.Parameter(torch.full((2,), -0.5))
        self.register_buffer("high", torch.tensor(np.array(high), dtype=torch.float32))

    def forward(self, x):
        h = self.body(x)
        return self.mean(h), self.value(h).squeeze(-1)

    def dist(self, x):
        mean, value = self(x)
        return torch.distributions.Normal(mean, self.log_std.exp()), value

    def command(self, a):
        """Actions in [-1, 1]^2 (clipped) scaled to the robot's (v, omega) limits."""
        return (np.clip(a, -1.0, 1.0) * self.high.numpy()).astype(np.float64)


def evaluate(policy, n=32, seed=10_000):
    """Greedy episodes on the held-out floors: the share that reach their goal."""
    env = make_env(n, seed, HELD_OUT_FLOORS)
    max_range = env.single_observation_space["ranges"].high
    obs, _ = env.reset()
    done = np.zeros(n, bool)
    reached = np.zeros(n, bool)
    for _ in range(int(SETTINGS["sim.t_max"] / SETTINGS["sim.dt"]) + 1):
        with torch.no_grad():
            mean, _ = policy(torch.as_tensor(features(obs, max_range)))
        obs, _, term, trunc, info = env.step(policy.command(mean.numpy()))
        ended = (term | trunc) & ~done
        reached |= ended & (info["status"] == floornav.STATUS_NAMES.index("reached"))
        done |= ended
        if done.all():
            break
    return float(reached.mean())


def train(args):
    torch.manual_seed(args.seed)
    env = make_env(args.envs, args.seed, TRAIN_FLOORS)
    max_range = env.single_observation_space["ranges"].high
    n, T = env.num_envs, args.horizon
    policy = Policy(len(max_range) + 3, env.single_action_space.high)
    optim = torch.optim.Adam(policy.parameters(), lr=3e-4)
    obs, _ = env.reset()
    x = features(obs, max_range)
    # Before training: the untrained policy on the held-out floors (the curve's first point).
    curve = [{"iteration": 0, "minutes": 0.0, "steps": 0, "train_success": 0.0, "episodes": 0,
              "held_out_success": evaluate(policy, n=args.eval_envs)}]
    print(json.dumps(curve[0]), flush=True)
    t0 = time.perf_counter()
    it = 0
    while True:
        it += 1
        xs = np.zeros((T, n, x.shape[1]), np.float32)
        acts = np.zeros((T, n, 2), np.float32)
        logps = np.zeros((T, n), np.float32)
        values = np.zeros((T + 1, n), np.float32)
        rewards = np.zeros((T, n), np.float32)
        ends = np.zeros((T, n), np.float32)
        finished, successes = 0, 0
        for t in range(T):
            with torch.no_grad():
                d, v = policy.dist(torch.as_tensor(x))
                a = d.sample()
            xs[t], acts[t], logps[t], values[t] = x, a.numpy(), d.log_prob(a).sum(-1).numpy(), v.numpy()
            obs, r, term, trunc, info = env.step(policy.command(a.numpy()))
            rewards[t] = r
            ends[t] = term  # a timeout is not the end of the task: bootstrap through it
            x = features(obs, max_range)
            ended = term | trunc
            if trunc.any():  # the value where a truncated episode stopped
                with torch.no_grad():
                    _, v_final = policy(torch.as_tensor(features(info["final_obs"], max_range)))
                rewards[t][trunc] += args.gamma * v_final.numpy()[trunc]
                ends[t][trunc] = 1.0
            finished += int(ended.sum())
            successes += int((info["status"][ended] == 1).sum())
        with torch.no_grad():
            values[T] = policy(torch.as_tensor(x))[1].numpy()
        adv = np.zeros((T, n), np.float32)
        last = np.zeros(n, np.float32)
        for t in reversed(range(T)):  # GAE(lambda)
            keep = 1.0 - ends[t]
            delta = rewards[t] + args.gamma * values[t + 1] * keep - values[t]
            last = delta + args.gamma * args.lam * keep * last
            adv[t] = last
        ret = adv + values[:T]
        b_x, b_a = torch.as_tensor(xs.reshape(T * n, -1)), torch.as_tensor(acts.reshape(T * n, 2))
        b_logp, b_adv = torch.as_tensor(logps.reshape(-1)), torch.as_tensor(adv.reshape(-1))
        b_ret = torch.as_tensor(ret.reshape(-1))
        b_adv = (b_adv - b_adv.mean()) / (b_adv.std() + 1e-8)
        for _ in range(args.epochs):
            for idx in torch.randperm(T * n).split(args.minibatch):
                d, v = policy.dist(b_x[idx])
                ratio = (d.log_prob(b_a[idx]).sum(-1) - b_logp[idx]).exp()
                surrogate = torch.min(ratio * b_adv[idx],
                                      ratio.clamp(1 - args.clip, 1 + args.clip) * b_adv[idx])
                loss = (-surrogate.mean() + 0.5 * (v - b_ret[idx]).pow(2).mean()
                        - 0.001 * d.entropy().sum(-1).mean())
                optim.zero_grad()
                loss.backward()
                nn.utils.clip_grad_norm_(policy.parameters(), 0.5)
                optim.step()
        minutes = (time.perf_counter() - t0) / 60
        row = {"iteration": it, "minutes": minutes, "steps": it * T * n,
               "train_success": successes / max(finished, 1), "episodes": finished}
        if it % args.eval_every == 0 or it == args.iterations:
            row["held_out_success"] = evaluate(policy, n=args.eval_envs)
        curve.append(row)
        print(json.dumps(row), flush=True)
        if (args.iterations and it >= args.iterations) or minutes >= args.minutes:
            return policy, curve


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--envs", type=int, default=128)
    ap.add_argument("--horizon", type=int, default=128, help="steps of 0.05 s per iteration")
    ap.add_argument("--epochs", type=int, default=4)
    ap.add_argument("--minibatch", type=int, default=2048)
    ap.add_argument("--gamma", type=float, default=0.99)
    ap.add_argument("--lam", type=float, default=0.95)
    ap.add_argument("--clip", type=float, default=0.2)
    ap.add_argument("--minutes", type=float, default=30.0)
    ap.add_argument("--iterations", type=int, default=0, help="stop after these (0: --minutes)")
    ap.add_argument("--eval-every", type=int, default=10)
    ap.add_argument("--eval-envs", type=int, default=64)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--quick", action="store_true", help="3 small iterations (smoke test)")
    ap.add_argument("--out", default=str(ROOT / "out" / "examples"))
    args = ap.parse_args(argv)
    if args.quick:
        args.envs, args.horizon, args.iterations, args.eval_every = 16, 32, 3, 3
        args.minibatch, args.eval_envs, args.epochs = 256, 8, 2
    torch.set_num_threads(1)  # the VecEnv's threads do the simulation
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    policy, curve = train(args)
    (out / "05_train_ppo.json").write_text(json.dumps(curve, indent=1) + "\n")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6, 3.5))
    ax.plot([r["minutes"] for r in curve], [r["train_success"] for r in curve], label="training floors")
    ev = [r for r in curve if "held_out_success" in r]
    ax.plot([r["minutes"] for r in ev], [r["held_out_success"] for r in ev], "o-",
            label="held-out floors (greedy)")
    ax.set_xlabel("minutes")
    ax.set_ylabel("episodes reaching the goal")
    ax.set_ylim(0, 1)
    ax.legend(loc="upper left")
    fig.tight_layout()
    fig.savefig(out / "05_train_ppo.png", dpi=100)
    torch.save(policy.state_dict(), out / "05_train_ppo.pt")
    print(f"held-out success {ev[-1]['held_out_success']:.2f} after {curve[-1]['minutes']:.1f} min")


if __name__ == "__main__":
    main()
