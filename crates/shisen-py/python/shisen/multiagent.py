"""A two-agent PettingZoo environment: the opponent and the VH, both agents.

The opponent is :class:`shisen.env.BoxingEnv`'s agent (same observation and
action). The VH's agent takes over the VH's decisions at a chosen level,
the rest of the pipeline (vision, attention, the gaze laws, the PD joints,
the face, the physics) staying the simulator's:

* ``vh_control="decisions"``: when to punch, with which hand, at the head
  or the body; when to raise which glove; when to slip, duck or lean back.
  The planner carries each decision out as it would its own (an attack
  looks at its target before the punch, an evasion waits its reaction
  time); it starts none of its own.
* ``vh_control="gaze"``: the same, and where the action plan asks the gaze
  to go (attention still weighs that against what draws the eye).
* ``vh_control="own"``: the seeds' perception-driven VH decides; the VH
  agent's actions are ignored (the baseline a learned VH is compared with).

    from shisen.multiagent import parallel_env
    env = parallel_env(vh_control="decisions")
    obs, infos = env.reset(seed=0)
    obs, rewards, terms, truncs, infos = env.step(
        {a: env.action_space(a).sample() for a in env.agents})

**The VH's observation** (37 float32) is what its own vision perceived,
with its latency, and what it feels of itself. Head frame: the VH's head's
axes (x its left, y up, z where it faces).

====== ==================================================================
0-7    the opponent's head: seen (1/0), direction (head frame, unit),
       distance (m), velocity (head frame, m/s); zeros when not seen
8-15   the opponent's left glove, the same
16-23  the opponent's right glove, the same
24-26  the VH's own left glove from its head (head frame, m)
27-29  its right glove
30-35  its action now, one-hot: idle, guard, attack, slip, duck, lean back
36     staggered by a blow (1/0: it cannot act)
====== ==================================================================

**The VH's action** is ``[command, look]`` (MultiDiscrete ``[11, 5]``):
``command`` one of :data:`VH_COMMANDS` (``nothing``, ``jab_head``,
``jab_body``, ``cross_head``, ``cross_body``, ``guard_left``,
``guard_right``, ``slip_left``, ``slip_right``, ``duck``, ``lean_back``),
taken at once if the VH is free to (an attack only while idle with both
gloves home); ``look`` one of :data:`VH_LOOKS` (``own``: where the planner
would ask; ``head``, ``left_glove``, ``right_glove``, ``body``: the
opponent's), used with ``vh_control="gaze"`` only.

**Rewards** are zero-sum: each hit the opponent lands is ``+hit_reward``
for it and ``-taken_penalty`` for the VH, and the other way round.
"""

from __future__ import annotations

import functools
from typing import Optional, Union

import numpy as np
from gymnasium import spaces
from pettingzoo import ParallelEnv

from . import Scene
from ._shisen import VH_COMMANDS, VH_LOOKS, VH_OBS, Arena
from .env import _check, _scene, opponent_spaces, reward

#: The bound of the VH's observation (directions, m and m/s); values
#: beyond are clipped (a glove faster than 50 m/s is not a punch).
VH_OBS_BOUND = 50.0

__all__ = ["BoxingParallelEnv", "VH_COMMANDS", "VH_LOOKS", "parallel_env"]


class BoxingParallelEnv(ParallelEnv):
    """The opponent and the VH as two agents (see the module's docstring)."""

    metadata = {"name": "shisen_boxing_v0", "render_modes": [], "is_parallelizable": True}

    def __init__(
        self,
        scene: Optional[Union[str, Scene]] = None,
        vh_control: str = "decisions",
        control_dt: float = 0.02,
        episode_seconds: float = 10.0,
        hit_reward: float = 1.0,
        taken_penalty: float = 1.0,
    ):
        _check(control_dt, episode_seconds)
        if vh_control not in ("own", "decisions", "gaze"):
            raise ValueError(f"vh_control: `own`, `decisions` or `gaze`, got `{vh_control}`")
        self.scene = _scene(scene)
        self.vh_control = vh_control
        self.control_dt = control_dt
        self.episode_seconds = episode_seconds
        self.hit_reward = hit_reward
        self.taken_penalty = taken_penalty
        self.possible_agents = ["opponent", "vh"]
        self.agents: list[str] = []
        self.render_mode = None
        self.arena: Optional[Arena] = None
        self._rng = np.random.default_rng()

    @functools.lru_cache(maxsize=None)
    def observation_space(self, agent: str) -> spaces.Space:
        if agent == "opponent":
            return opponent_spaces()[0]
        return spaces.Box(-VH_OBS_BOUND, VH_OBS_BOUND, shape=(VH_OBS,), dtype=np.float32)

    @functools.lru_cache(maxsize=None)
    def action_space(self, agent: str) -> spaces.Space:
        if agent == "opponent":
            return opponent_spaces()[1]
        return spaces.MultiDiscrete([len(VH_COMMANDS), len(VH_LOOKS)])

    def _observations(self, opp, vh) -> dict:
        return {
            "opponent": np.clip(opp[0], -5.0, 5.0),
            "vh": np.clip(vh[0], -VH_OBS_BOUND, VH_OBS_BOUND),
        }

    def reset(self, seed: Optional[int] = None, options: Optional[dict] = None):
        if seed is not None:
            self._rng = np.random.default_rng(seed)
        sim_seed = seed if seed is not None else int(self._rng.integers(0, 2**31))
        self.arena = Arena(self.scene, 1, self.control_dt, self.vh_control, sim_seed)
        self.agents = list(self.possible_agents)
        opp, vh = self.arena.observe()
        return self._observations(opp, vh), {a: {} for a in self.agents}

    def step(self, actions: dict):
        if self.arena is None or not self.agents:
            raise RuntimeError("call reset() first")
        a = np.asarray(actions["opponent"], dtype=np.float64).reshape(1, 9)
        v = np.asarray(actions["vh"], dtype=np.int64).reshape(1, 2)
        opp, vh, landed, taken = self.arena.step(a, v)
        landed, taken = int(landed[0]), int(taken[0])
        rewards = {
            "opponent": float(reward(landed, taken, self.hit_reward, self.taken_penalty)),
            "vh": float(reward(taken, landed, self.hit_reward, self.taken_penalty)),
        }
        time = float(self.arena.times()[0])
        over = time >= self.episode_seconds - 1e-9
        terminations = {a: False for a in self.agents}
        truncations = {a: over for a in self.agents}
        infos = {
            "opponent": {"landed": landed, "taken": taken, "time": time},
            "vh": {"landed": taken, "taken": landed, "time": time},
        }
        observations = self._observations(opp, vh)
        if over:
            self.agents = []
        return observations, rewards, terminations, truncations, infos

    def tally(self) -> dict:
        """Blows so far, both ways (``Sim.tally``)."""
        if self.arena is None:
            raise RuntimeError("call reset() first")
        return self.arena.tally(0)

    def render(self):
        return None

    def close(self):
        pass


def parallel_env(**kwargs) -> BoxingParallelEnv:
    """The two-agent environment (:class:`BoxingParallelEnv`'s arguments)."""
    return BoxingParallelEnv(**kwargs)
