"""A Gymnasium environment in which the agent is the VH's opponent.

Each step the agent sets where its head and gloves go (offsets from their
guard position, scaled to arm's reach); the simulation then runs
``control_dt`` seconds at 1 kHz, the VH seeing, attending, guarding and
punching as it always does. Observations are what the opponent would see
of the VH (its head, gloves, torso, where it looks and what it does) and
where its own parts are. The reward counts blows: ``hit_reward`` for each
hit the opponent lands, ``-taken_penalty`` for each hit it takes.

Deterministic: ``reset(seed=s)`` seeds the simulation, so the same seed
and actions give the same episode.

    import gymnasium as gym
    import shisen.env  # registers "shisen/Boxing-v0"
    env = gym.make("shisen/Boxing-v0")

Vectorised: ``gymnasium.vector.SyncVectorEnv([lambda: BoxingEnv()] * n)``,
or :func:`make_vec`.
"""

from __future__ import annotations

from typing import Optional, Union

import gymnasium as gym
import numpy as np
from gymnasium import spaces

from . import Scene

#: How far each part may be moved from its guard position, m per unit of
#: action (head; gloves), on the x (sideways), y (up) and z (toward the
#: VH) axes. A glove's 0.45 m forward is a full reach to the VH's head.
HEAD_REACH = np.array([0.15, 0.15, 0.15])
GLOVE_REACH = np.array([0.30, 0.30, 0.45])
ACTIONS = ("idle", "guard", "attack", "slip", "duck", "leanback")
PARTS = ("head", "left_glove", "right_glove")


class BoxingEnv(gym.Env):
    """Box against the VH as its opponent (see the module's docstring)."""

    metadata = {"render_modes": []}

    def __init__(
        self,
        scene: Optional[Union[str, Scene]] = None,
        control_dt: float = 0.02,
        episode_seconds: float = 10.0,
        hit_reward: float = 1.0,
        taken_penalty: float = 1.0,
    ):
        if isinstance(scene, Scene):
            self.scene = scene
        elif scene is None:
            self.scene = Scene.default()
        else:
            self.scene = Scene.load(scene)
        if not 0.001 <= control_dt <= 1.0:
            raise ValueError(f"control_dt: 0.001-1 s (one tick to a second), got {control_dt}")
        if not 0.0 < episode_seconds <= 3600.0:
            raise ValueError(f"episode_seconds: 0-3600 s, got {episode_seconds}")
        self.control_dt = control_dt
        self.ticks = max(1, round(control_dt / 0.001))
        self.episode_seconds = episode_seconds
        self.hit_reward = hit_reward
        self.taken_penalty = taken_penalty
        self.action_space = spaces.Box(-1.0, 1.0, shape=(9,), dtype=np.float32)
        # Positions within 5 m of the ring's centre; the action one-hot in [0, 1].
        self.observation_space = spaces.Box(-5.0, 5.0, shape=(30,), dtype=np.float32)
        self.sim = None
        self._rest = None
        self._tally = None

    def _observe(self) -> np.ndarray:
        p = self.sim.positions()
        s = self.sim.sample()
        gaze = (s["gaze_x"], s["gaze_y"], s["gaze_z"]) if s else p["vh_head"]
        action = s["action"] if s else "idle"
        onehot = [1.0 if action == a else 0.0 for a in ACTIONS]
        obs = [
            *p["vh_head"],
            *p["vh_left_glove"],
            *p["vh_right_glove"],
            *p["vh_torso"],
            *gaze,
            *onehot,
            *p["head"],
            *p["left_glove"],
            *p["right_glove"],
        ]
        return np.asarray(obs, dtype=np.float32)

    def reset(self, *, seed: Optional[int] = None, options: Optional[dict] = None):
        super().reset(seed=seed)
        sim_seed = seed if seed is not None else int(self.np_random.integers(0, 2**31))
        self.sim = self.scene.sim(seed=sim_seed)
        p = self.sim.positions()
        self._rest = {k: np.asarray(p[k]) for k in PARTS}
        self._tally = self.sim.tally()
        return self._observe(), {}

    def step(self, action):
        if self.sim is None:
            raise RuntimeError("call reset() first")
        a = np.clip(np.asarray(action, dtype=np.float64).reshape(3, 3), -1.0, 1.0)
        # Your avatar faces the VH from +z: forward is toward -z.
        toward = np.array([1.0, 1.0, -1.0])
        for k, part in enumerate(PARTS):
            reach = HEAD_REACH if part == "head" else GLOVE_REACH
            to = self._rest[part] + a[k] * reach * toward
            self.sim.move_part(part, tuple(float(x) for x in to), self.control_dt)
        self.sim.step(self.ticks)
        t = self.sim.tally()
        landed = t["opponent_hits"] - self._tally["opponent_hits"]
        taken = t["vh_hits"] - self._tally["vh_hits"]
        self._tally = t
        reward = self.hit_reward * landed - self.taken_penalty * taken
        truncated = self.sim.time >= self.episode_seconds - 1e-9
        info = {"landed": landed, "taken": taken, "time": self.sim.time}
        return self._observe(), float(reward), False, truncated, info


def make_vec(n: int, **kwargs) -> gym.vector.SyncVectorEnv:
    """``n`` independent environments stepped together."""
    return gym.vector.SyncVectorEnv([lambda: BoxingEnv(**kwargs) for _ in range(n)])


gym.register(id="shisen/Boxing-v0", entry_point="shisen.env:BoxingEnv")
