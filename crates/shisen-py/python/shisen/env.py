"""Gymnasium environments in which the agent is the VH's opponent.

Each step the agent sets where its head and gloves go (offsets from their
guard position, scaled to arm's reach); the simulation then runs
``control_dt`` seconds at 1 kHz, the VH seeing, attending, guarding and
punching as it always does. The reward counts blows: ``hit_reward`` for
each hit the opponent lands, ``-taken_penalty`` for each hit it takes.

Deterministic: ``reset(seed=s)`` seeds the simulation, so the same seed
and actions give the same episode. The scene is :func:`ring` unless one is
given (a path or a :class:`shisen.Scene`; its timeline plays too).

    import gymnasium as gym
    import shisen.env  # registers "shisen/Boxing-v0"
    env = gym.make("shisen/Boxing-v0")

    vec = shisen.env.make_vec(8)  # 8 bouts stepped in Rust threads

**Observation** (30 float32; world frame, m: y up, the VH at the origin
facing +z, the opponent facing it from +z):

====== ==================================================================
0-2    the VH's head (centre)
3-5    the VH's left glove
6-8    the VH's right glove
9-11   the VH's torso (centre)
12-14  where the VH looks (its gaze point)
15-20  the VH's action, one-hot: idle, guard, attack, slip, duck, lean back
21-23  the opponent's own head
24-26  its left glove
27-29  its right glove
====== ==================================================================

**Action** (9 in [-1, 1]): the head's, left glove's and right glove's
offsets from their guard positions, each (x sideways, y up, z toward the
VH), times :data:`HEAD_REACH` or :data:`GLOVE_REACH` m: where each part
is sent. It goes there as fast as a person could move it and no faster (a
minimum-jerk move each control step, as live input is, peaking at most at
9 m/s for a glove, Olympic boxers' hand speeds, Walilko, Viano & Bir 2005;
2 m/s for the head, the VH's own slip).

The two-agent version, in which the VH is an agent too, is
:mod:`shisen.multiagent` (PettingZoo).
"""

from __future__ import annotations

from typing import Optional, Union

import gymnasium as gym
import numpy as np
from gymnasium import spaces

from . import Scene
from ._shisen import GLOVE_REACH as _GLOVE_REACH
from ._shisen import HEAD_REACH as _HEAD_REACH
from ._shisen import OPPONENT_OBS, Arena

#: How far each part may be moved from its guard position, m per unit of
#: action (head; gloves), on the x (sideways), y (up) and z (toward the
#: VH) axes (the simulator's own values, src/arena.rs).
HEAD_REACH = np.array(_HEAD_REACH)
GLOVE_REACH = np.array(_GLOVE_REACH)
#: The VH's actions in the order of the observation's one-hot.
ACTIONS = ("idle", "guard", "attack", "slip", "duck", "leanback")
PARTS = ("head", "left_glove", "right_glove")


#: The VH's personalities in :func:`ring` (scene ``vh.personality``
#: fields): a novice covers up and its eyes chase every glove; a strong
#: boxer slips, counters and keeps its eyes on your face (the amounts of
#: scenes/evasion_weak.ron and evasion_strong.ron; ``default`` is the
#: seeds' VH).
VH_LEVELS = {
    "novice": "evade: 0.1, counter: 0.0, a_face: 0.5, a_anchor: 1.0",
    "default": "",
    "strong": "evade: 0.95, counter: 0.6, a_face: 4.0, a_anchor: 8.0",
}


def ring(vh: str = "default", seed: int = 1) -> Scene:
    """The scene the environments use by default: you and the VH at boxing
    distance with nothing scripted (no timeline, no rounds), the VH's
    personality one of :data:`VH_LEVELS`."""
    if vh not in VH_LEVELS:
        raise ValueError(f"vh: one of {', '.join(VH_LEVELS)}, got `{vh}`")
    text = f"""Scene(
    name: "ring-{vh}",
    description: "Learning agents' ring: nothing scripted, a {vh} VH.",
    seed: {seed},
    duration: 3600.0,
    vh: (personality: ({VH_LEVELS[vh]})),
)"""
    return Scene.from_str(text, name=f"<ring {vh}>")


def _scene(scene: Optional[Union[str, Scene]]) -> Scene:
    if isinstance(scene, Scene):
        return scene
    return ring() if scene is None else Scene.load(scene)


def _check(control_dt: float, episode_seconds: float, num_envs: int = 1) -> None:
    """The environments' shared arguments, checked (ValueError naming one)."""
    if not 1 <= num_envs <= 4096:
        raise ValueError(f"num_envs: 1-4096, got {num_envs}")
    if not 0.001 <= control_dt <= 1.0:
        raise ValueError(f"control_dt: 0.001-1 s (one tick to a second), got {control_dt}")
    if not 0.0 < episode_seconds <= 3600.0:
        raise ValueError(f"episode_seconds: 0-3600 s, got {episode_seconds}")


def reward(landed, taken, hit_reward: float, taken_penalty: float):
    """The opponent's reward for hits `landed` and `taken` (numbers or
    arrays): ``hit_reward * landed - taken_penalty * taken``; the VH's is
    the same with the two swapped."""
    return hit_reward * np.asarray(landed, dtype=np.float64) - taken_penalty * np.asarray(
        taken, dtype=np.float64
    )


def opponent_spaces() -> tuple[spaces.Box, spaces.Box]:
    """The opponent's (observation, action) spaces."""
    # Positions within 5 m of the ring's centre; the action one-hot in [0, 1].
    obs = spaces.Box(-5.0, 5.0, shape=(OPPONENT_OBS,), dtype=np.float32)
    return obs, spaces.Box(-1.0, 1.0, shape=(9,), dtype=np.float32)


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
        _check(control_dt, episode_seconds)
        self.scene = _scene(scene)
        self.control_dt = control_dt
        self.episode_seconds = episode_seconds
        self.hit_reward = hit_reward
        self.taken_penalty = taken_penalty
        self.observation_space, self.action_space = opponent_spaces()
        self.arena: Optional[Arena] = None

    def reset(self, *, seed: Optional[int] = None, options: Optional[dict] = None):
        super().reset(seed=seed)
        sim_seed = seed if seed is not None else int(self.np_random.integers(0, 2**31))
        self.arena = Arena(self.scene, 1, self.control_dt, "own", sim_seed)
        obs, _ = self.arena.observe()
        return np.clip(obs[0], -5.0, 5.0), {}

    def step(self, action):
        if self.arena is None:
            raise RuntimeError("call reset() first")
        a = np.asarray(action, dtype=np.float64).reshape(1, 9)
        obs, _, landed, taken = self.arena.step(a)
        r = reward(landed[0], taken[0], self.hit_reward, self.taken_penalty)
        time = float(self.arena.times()[0])
        truncated = time >= self.episode_seconds - 1e-9
        info = {"landed": int(landed[0]), "taken": int(taken[0]), "time": time}
        return np.clip(obs[0], -5.0, 5.0), float(r), False, truncated, info

    def tally(self) -> dict:
        """Blows so far, both ways (``Sim.tally``)."""
        if self.arena is None:
            raise RuntimeError("call reset() first")
        return self.arena.tally(0)


class BoxingVectorEnv(gym.vector.VectorEnv):
    """``num_envs`` bouts stepped together in Rust threads, the interpreter
    lock released: Gymnasium's vector API over the same observations,
    actions and rewards as :class:`BoxingEnv`. A bout whose episode ends
    starts again at the next step (``AutoresetMode.NEXT_STEP``: that step's
    observation is the new episode's first, its reward 0)."""

    metadata = {"render_modes": [], "autoreset_mode": gym.vector.AutoresetMode.NEXT_STEP}

    def __init__(
        self,
        num_envs: int,
        scene: Optional[Union[str, Scene]] = None,
        control_dt: float = 0.02,
        episode_seconds: float = 10.0,
        hit_reward: float = 1.0,
        taken_penalty: float = 1.0,
    ):
        _check(control_dt, episode_seconds, num_envs)
        self.scene = _scene(scene)
        self.num_envs = num_envs
        self.control_dt = control_dt
        self.episode_seconds = episode_seconds
        self.hit_reward = hit_reward
        self.taken_penalty = taken_penalty
        self.single_observation_space, self.single_action_space = opponent_spaces()
        self.observation_space = gym.vector.utils.batch_space(
            self.single_observation_space, num_envs
        )
        self.action_space = gym.vector.utils.batch_space(self.single_action_space, num_envs)
        self.arena: Optional[Arena] = None
        self._done = np.zeros(num_envs, dtype=bool)
        self._rng = np.random.default_rng()

    def reset(self, *, seed=None, options=None):
        if isinstance(seed, int):
            seeds = [seed + i for i in range(self.num_envs)]
        elif seed is None:
            seeds = [None] * self.num_envs
        else:
            seeds = list(seed)
            if len(seeds) != self.num_envs:
                raise ValueError(f"seed: {self.num_envs} seeds, got {len(seeds)}")
        if seeds[0] is not None:
            self._rng = np.random.default_rng(seeds[0])
        seeds = [int(self._rng.integers(0, 2**31)) if s is None else s for s in seeds]
        if self.arena is None:
            self.arena = Arena(self.scene, self.num_envs, self.control_dt, "own", 0)
        for i, s in enumerate(seeds):
            self.arena.reset(i, s)
        self._done[:] = False
        obs, _ = self.arena.observe()
        return np.clip(obs, -5.0, 5.0), {}

    def step(self, actions):
        if self.arena is None:
            raise RuntimeError("call reset() first")
        hold = self._done.copy()
        for i in np.flatnonzero(hold):
            self.arena.reset(int(i), int(self._rng.integers(0, 2**31)))
        a = np.asarray(actions, dtype=np.float64).reshape(self.num_envs, 9)
        obs, _, landed, taken = self.arena.step(a, None, hold.tolist())
        rewards = reward(landed, taken, self.hit_reward, self.taken_penalty)
        truncated = (self.arena.times() >= self.episode_seconds - 1e-9) & ~hold
        self._done = truncated.copy()
        terminated = np.zeros(self.num_envs, dtype=bool)
        info = {"landed": landed.astype(np.int64), "taken": taken.astype(np.int64)}
        return np.clip(obs, -5.0, 5.0), rewards, terminated, truncated, info


def make_vec(n: int, **kwargs) -> BoxingVectorEnv:
    """``n`` bouts stepped together in Rust threads (:class:`BoxingVectorEnv`);
    the keyword arguments are :class:`BoxingEnv`'s."""
    return BoxingVectorEnv(n, **kwargs)


gym.register(id="shisen/Boxing-v0", entry_point="shisen.env:BoxingEnv")
