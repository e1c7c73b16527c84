"""Stable-Baselines3 PPO learns to box as the VH's opponent.

The opponent's policy (an MLP over :class:`shisen.env.BoxingEnv`'s 30
observations to its 9 actions) trains against a VH of the chosen level,
``--envs`` bouts stepped together in Rust threads (:mod:`shisen.sb3`).
The learning curve (mean episode reward: hits landed minus hits taken,
and hits landed and taken a minute) is plotted; the trained policy is
compared with random actions on the same seeds.

    pip install "./crates/shisen-py[rl]"
    python3 crates/shisen-py/examples/train_ppo.py               # about 4 minutes on 2 cores
    python3 crates/shisen-py/examples/train_ppo.py --steps 4096  # a smoke run
"""

import argparse
import json
import pathlib
import time

import numpy as np

from shisen.env import ring
from shisen.sb3 import BoxingVecEnv

ROOT = pathlib.Path(__file__).resolve().parents[3]


def evaluate(policy, vh: str, seconds: float, seeds: range) -> dict:
    """Hits landed and taken a minute by `policy` (obs -> action) over
    one episode per seed."""
    env = BoxingVecEnv(len(seeds), scene=ring(vh), episode_seconds=seconds)
    env.seed(seeds.start)
    obs = env.reset()
    landed = taken = 0
    for _ in range(round(seconds / 0.02)):
        obs, _, _, infos = env.step(policy(obs))
        landed += sum(i["landed"] for i in infos)
        taken += sum(i["taken"] for i in infos)
    minutes = len(seeds) * seconds / 60.0
    return {"landed_per_min": landed / minutes, "taken_per_min": taken / minutes}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--steps", type=int, default=200_000, help="environment steps to train")
    ap.add_argument("--envs", type=int, default=8, help="bouts stepped together")
    ap.add_argument("--seconds", type=float, default=5.0, help="episode length, simulated s")
    ap.add_argument("--vh", default="novice", help="the VH's level: novice, default, strong")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--out", default=str(ROOT / "docs/python/ppo_curve.png"))
    args = ap.parse_args(argv)

    import torch
    from stable_baselines3 import PPO
    from stable_baselines3.common.callbacks import BaseCallback
    from stable_baselines3.common.vec_env import VecMonitor

    # Two cores: torch's own threads would fight the bouts' for them.
    torch.set_num_threads(1)
    env = VecMonitor(BoxingVecEnv(args.envs, scene=ring(args.vh), episode_seconds=args.seconds))
    env.seed(args.seed)
    model = PPO(
        "MlpPolicy",
        env,
        n_steps=max(16, 2048 // args.envs),
        batch_size=256,
        learning_rate=3e-4,
        ent_coef=0.0,
        seed=args.seed,
        device="cpu",
        verbose=0,
    )

    curve = []

    class Curve(BaseCallback):
        def _on_rollout_end(self) -> None:
            eps = list(self.model.ep_info_buffer)
            if eps:
                curve.append((self.num_timesteps, float(np.mean([e["r"] for e in eps]))))

        def _on_step(self) -> bool:
            return True

    start = time.perf_counter()
    model.learn(args.steps, callback=Curve())
    wall = time.perf_counter() - start
    seeds = range(1000, 1000 + args.envs)
    trained = evaluate(lambda o: model.predict(o)[0], args.vh, args.seconds, seeds)
    rng = np.random.default_rng(1)
    random = evaluate(lambda o: rng.uniform(-1, 1, (len(o), 9)), args.vh, args.seconds, seeds)
    report = {
        "steps": args.steps,
        "envs": args.envs,
        "vh": args.vh,
        "steps_per_second": args.steps / wall,
        "first_reward": curve[0][1] if curve else None,
        "last_reward": curve[-1][1] if curve else None,
        "trained": trained,
        "random": random,
    }
    print(json.dumps(report, indent=2))
    if args.out:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(6.4, 3.6), dpi=110)
        if curve:
            x, y = zip(*curve)
            ax.plot(x, y, color="tab:red")
        ax.axhline(0.0, color="grey", lw=0.6)
        ax.set_xlabel("environment steps (20 ms each)")
        ax.set_ylabel(f"episode reward ({args.seconds:g} s):\nhits landed - hits taken")
        ax.set_title(
            f"PPO opponent vs {args.vh} VH: lands {trained['landed_per_min']:.0f}/min, "
            f"takes {trained['taken_per_min']:.0f}/min (random: {random['landed_per_min']:.0f}, "
            f"{random['taken_per_min']:.0f})",
            fontsize=9,
        )
        fig.tight_layout()
        pathlib.Path(args.out).parent.mkdir(parents=True, exist_ok=True)
        fig.savefig(args.out)
    return report


if __name__ == "__main__":
    main()
