"""Steps per second from Python against the native binary, same scene, one
run side by side. The learning environments (single, native vector,
SyncVectorEnv): benches/python_envs.py.

    pip install "./crates/shisen-py[test]"
    cargo build --release
    python3 benches/python_steps.py
"""

import os
import subprocess
import time


import shisen

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


if __name__ == "__main__":
    n = native()
    r = python_run()
    s = python_step()
    print(f"native binary:          {n:9.0f} steps/s")
    print(f"Python Scene.run:       {r:9.0f} steps/s ({r / n:.2f} of native)")
    print(f"Python Sim.step(1000):  {s:9.0f} steps/s ({s / n:.2f} of native)")
