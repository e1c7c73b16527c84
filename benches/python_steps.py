"""Steps per second from Python against the native binary, same scene, one
run side by side; and a vector of Gymnasium environments on every core.

    pip install "./crates/shisen-py[test]"
    cargo build --release
    python3 benches/python_steps.py
"""

import os
import subprocess
import threading
import time

import numpy as np

import shisen
from shisen.env import BoxingEnv

SECONDS = 60.0
STEPS = int(SECONDS / shisen.DT)
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def native():
    exe = os.path.join(os.environ.get("CARGO_TARGET_DIR", os.path.join(ROOT, "target")), "release", "shisen")
    t0 = time.perf_counter()
    subprocess.run([exe, "run", "scenes/default.ron", "--headless", "--duration", str(SECONDS)],
                   cwd=ROOT, check=True, capture_output=True)
    return STEPS / (time.perf_counter() - t0)


def python_run():
    scene = shisen.Scene.load(os.path.join(ROOT, "scenes/default.ron"))
    t0 = time.perf_counter()
    cols = scene.run(duration=SECONDS)
    assert len(cols["t"]) == STEPS
    return STEPS / (time.perf_counter() - t0)


def python_step():
    sim = shisen.Scene.load(os.path.join(ROOT, "scenes/default.ron")).sim()
    t0 = time.perf_counter()
    for _ in range(int(SECONDS)):
        sim.step(1000)
    return STEPS / (time.perf_counter() - t0)


def env_throughput(n_envs, threads):
    envs = [BoxingEnv(episode_seconds=1e9) for _ in range(n_envs)]
    for k, e in enumerate(envs):
        e.reset(seed=k)
    actions = np.zeros(9, dtype=np.float32)
    per_env = 250  # env steps of 20 ms each: 5 simulated seconds

    def work(e):
        for _ in range(per_env):
            e.step(actions)

    t0 = time.perf_counter()
    if threads:
        ts = [threading.Thread(target=work, args=(e,)) for e in envs]
        [t.start() for t in ts]
        [t.join() for t in ts]
    else:
        for e in envs:
            work(e)
    wall = time.perf_counter() - t0
    return n_envs * per_env / wall, n_envs * per_env * 20 / wall


if __name__ == "__main__":
    n = native()
    r = python_run()
    s = python_step()
    print(f"native binary:          {n:9.0f} steps/s")
    print(f"Python Scene.run:       {r:9.0f} steps/s ({r / n:.2f} of native)")
    print(f"Python Sim.step(1000):  {s:9.0f} steps/s ({s / n:.2f} of native)")
    for n_envs, threads in [(1, False), (2, False), (2, True)]:
        eps, sps = env_throughput(n_envs, threads)
        how = "threads" if threads else "one thread"
        print(f"BoxingEnv x{n_envs} ({how}): {eps:7.0f} env steps/s = {sps:7.0f} sim steps/s")
