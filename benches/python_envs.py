"""Environment steps a second, measured side by side in one run: the
simulator headless, one Gymnasium env, the native vector env (n bouts in
Rust threads) and Gymnasium's SyncVectorEnv over the same single env, for
n = 1, 2, 8. One environment step is 20 ms of simulation (20 ticks).

    pip install "./crates/shisen-py[test]"
    python3 benches/python_envs.py [--seconds 3] [--json out.json]
"""

import argparse
import json
import time

import gymnasium as gym
import numpy as np

from shisen.env import BoxingEnv, make_vec, ring


def rate(step, batch: int, seconds: float) -> float:
    """Environment steps a second of `step()` (each `batch` steps), run
    for about `seconds` after a short warm-up."""
    for _ in range(5):
        step()
    n, start = 0, time.perf_counter()
    while time.perf_counter() - start < seconds:
        step()
        n += batch
    return n / (time.perf_counter() - start)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seconds", type=float, default=3.0, help="wall time per measurement")
    ap.add_argument("--json", default=None, help="write the table here too")
    args = ap.parse_args(argv)
    rng = np.random.default_rng(0)
    rows = []

    scene = ring()
    sim = scene.sim(seed=1)
    rows.append(("headless (Sim.step, 20 ticks)", 1, rate(lambda: sim.step(20), 1, args.seconds)))

    env = BoxingEnv(episode_seconds=3600.0)
    env.reset(seed=0)
    rows.append(
        ("BoxingEnv", 1, rate(lambda: env.step(rng.uniform(-1, 1, 9)), 1, args.seconds))
    )
    for n in (1, 2, 8):
        vec = make_vec(n, episode_seconds=3600.0)
        vec.reset(seed=0)
        rows.append(
            (
                "make_vec (native)",
                n,
                rate(lambda: vec.step(rng.uniform(-1, 1, (n, 9))), n, args.seconds),
            )
        )
        sync = gym.vector.SyncVectorEnv(
            [lambda: BoxingEnv(episode_seconds=3600.0) for _ in range(n)]
        )
        sync.reset(seed=0)
        rows.append(
            (
                "SyncVectorEnv",
                n,
                rate(lambda: sync.step(rng.uniform(-1, 1, (n, 9))), n, args.seconds),
            )
        )

    print(f"{'environment':32} {'n':>3} {'steps/s':>9} {'x real time':>12}")
    for name, n, r in rows:
        print(f"{name:32} {n:>3} {r:>9.0f} {r * 0.02:>12.1f}")
    if args.json:
        with open(args.json, "w") as f:
            json.dump([{"env": a, "n": n, "steps_per_second": r} for a, n, r in rows], f, indent=2)
    return rows


if __name__ == "__main__":
    main()
