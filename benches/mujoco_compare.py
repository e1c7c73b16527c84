#!/usr/bin/env python3
"""Peer comparison: shisen's full control step against MuJoCo's
physics-only step, on the same bodies and joints, in one run.

The MJCF model is generated from shisen's own body description
(`shisen export-mjcf`), never written by hand. MuJoCo steps it at the same
1 kHz with the opponent's gloves (mocap bodies) punching at the VH so that
contacts happen; shisen runs its default sparring scene headless (physics +
vision + attention + behaviour + oculomotor + PD control + face). Both are
timed here, one after the other, on this machine.

Two pairs are timed: the default body (a driven pelvis: torso, head,
eyes, arms) and the whole physical body (`vh.body.pelvis: Balanced`:
`export-mjcf --balanced` adds a free pelvis, legs and the canvas; shisen
runs `soak --balanced`, sparring with the physical body). MuJoCo's body is
uncontrolled, so its physical VH falls and lies on the canvas: its
contacts are those of a body lying down.

Usage:  pip install mujoco && python3 benches/mujoco_compare.py [seconds]
        SHISEN_BIN=/path/to/shisen python3 benches/mujoco_compare.py
        (another build of shisen, e.g. a before-and-after pair; not rebuilt)
"""

import math
import os
import re
import subprocess
import sys
import tempfile
import time

import mujoco

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SIM_SECONDS = float(sys.argv[1]) if len(sys.argv) > 1 else 20.0
BIN = os.environ.get("SHISEN_BIN") or os.path.join(ROOT, "target", "release", "shisen")


def build():
    subprocess.run(["cargo", "build", "--release", "--quiet"], cwd=ROOT, check=True)


def mujoco_rate(xml_path):
    model = mujoco.MjModel.from_xml_path(xml_path)
    data = mujoco.MjData(model)
    steps = int(round(SIM_SECONDS / model.opt.timestep))
    gloves = [model.body("left_glove").mocapid[0], model.body("right_glove").mocapid[0]]
    rest = [data.mocap_pos[g].copy() for g in gloves]
    start = time.perf_counter()
    for i in range(steps):
        t = i * model.opt.timestep
        for k, g in enumerate(gloves):
            # jab toward the VH (MuJoCo's -y is our +z) twice a second
            phase = max(0.0, math.sin(2 * math.pi * (t + 0.25 * k)))
            data.mocap_pos[g] = rest[k] + [0.0, 0.45 * phase, 0.05 * phase]
        mujoco.mj_step(model, data)
    wall = time.perf_counter() - start
    return steps / wall, steps, data.ncon


def shisen_rate():
    out = subprocess.run(
        [BIN, "run", "default", "--headless", "--duration", str(SIM_SECONDS)],
        cwd=ROOT, check=False, capture_output=True, text=True,
    ).stdout
    m = re.search(r"in (\d+) ticks, ([0-9.]+) s wall", out)
    if not m:
        sys.exit("could not read shisen's timing from:\n" + out)
    ticks, wall = int(m.group(1)), float(m.group(2))
    return ticks / wall, ticks


def shisen_balanced_rate():
    out = subprocess.run(
        [BIN, "soak", "--balanced", "--minutes", str(SIM_SECONDS / 60.0)],
        cwd=ROOT, check=False, capture_output=True, text=True,
    ).stdout
    m = re.search(r"\((\d+) ticks\) in ([0-9.]+) s wall", out)
    if not m:
        sys.exit("could not read shisen's timing from:\n" + out)
    ticks, wall = int(m.group(1)), float(m.group(2))
    return ticks / wall, ticks


def main():
    if "SHISEN_BIN" not in os.environ:
        build()
    with tempfile.TemporaryDirectory() as tmp:
        xml = os.path.join(tmp, "shisen.xml")
        subprocess.run([BIN, "export-mjcf", "--out", xml], check=True)
        mj, mj_steps, ncon = mujoco_rate(xml)
        full = os.path.join(tmp, "shisen_balanced.xml")
        subprocess.run([BIN, "export-mjcf", "--balanced", "--out", full], check=True)
        mjb, mjb_steps, nconb = mujoco_rate(full)
    ours, ticks = shisen_rate()
    oursb, ticksb = shisen_balanced_rate()
    print(f"MuJoCo {mujoco.__version__} physics-only, driven body: {mj:,.0f} steps/s ({mj_steps} steps, {ncon} contacts at the end)")
    print(f"shisen full control step, driven body:   {ours:,.0f} steps/s ({ticks} ticks)")
    print(f"ratio: one shisen step costs {mj / ours:.2f} MuJoCo physics steps "
          f"(shisen runs {ours / 1000:.1f}x real time at 1 kHz)")
    print(f"MuJoCo physics-only, whole physical body: {mjb:,.0f} steps/s ({mjb_steps} steps, {nconb} contacts at the end)")
    print(f"shisen full control step, physical body:  {oursb:,.0f} steps/s ({ticksb} ticks)")
    print(f"ratio: one shisen step costs {mjb / oursb:.2f} MuJoCo physics steps "
          f"(shisen runs {oursb / 1000:.1f}x real time at 1 kHz)")


if __name__ == "__main__":
    main()
