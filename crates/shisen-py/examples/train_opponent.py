"""A short training run against the VH: the cross-entropy method over a
linear policy for the opponent (its 9 actions from the 27 observations of
shisen.env.BoxingEnv), episodes of a few simulated seconds, the learning
curve plotted.

    pip install "./crates/shisen-py[test]" matplotlib
    python3 crates/shisen-py/examples/train_opponent.py [--out docs/python/learning_curve.png]
"""

import argparse
import pathlib
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from shisen.env import BoxingEnv

ROOT = pathlib.Path(__file__).resolve().parents[3]


def episode(weights, seed, seconds):
    env = BoxingEnv(episode_seconds=seconds)
    obs, _ = env.reset(seed=seed)
    w = weights[:-9].reshape(9, 27)
    b = weights[-9:]
    total, done = 0.0, False
    while not done:
        action = np.tanh(w @ obs + b).astype(np.float32)
        obs, r, term, trunc, _ = env.step(action)
        total += r
        done = term or trunc
    return total


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", default=str(ROOT / "docs/python/learning_curve.png"))
    ap.add_argument("--iterations", type=int, default=12)
    ap.add_argument("--population", type=int, default=16)
    ap.add_argument("--seconds", type=float, default=4.0)
    args = ap.parse_args()

    rng = np.random.default_rng(0)
    dim = 9 * 27 + 9
    mean, std = np.zeros(dim), np.full(dim, 0.3)
    elite = max(2, args.population // 4)
    curve = []
    # Simulations release the interpreter lock: threads use every core.
    with ThreadPoolExecutor() as pool:
        for it in range(args.iterations):
            pop = mean + std * rng.standard_normal((args.population, dim))
            seeds = [it * 1000 + k for k in range(args.population)]
            scores = np.array(list(pool.map(lambda a: episode(a[0], a[1], args.seconds), zip(pop, seeds))))
            best = pop[np.argsort(scores)[-elite:]]
            mean, std = best.mean(axis=0), best.std(axis=0) + 0.02
            curve.append((scores.mean(), scores.max()))
            print(f"iteration {it:2d}: mean return {scores.mean():+.2f}, best {scores.max():+.2f}")

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    c = np.array(curve)
    fig, ax = plt.subplots(figsize=(7, 4))
    ax.plot(c[:, 0], marker="o", label="population mean")
    ax.plot(c[:, 1], marker="s", label="best")
    ax.set_xlabel("iteration (cross-entropy method)")
    ax.set_ylabel(f"return per {args.seconds:.0f} s episode (hits landed - taken)")
    ax.set_title("An opponent policy learning against the VH")
    ax.legend()
    fig.tight_layout()
    pathlib.Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(args.out, dpi=110)
    print("plot:", args.out)


if __name__ == "__main__":
    main()
