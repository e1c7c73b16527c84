"""Stable-Baselines3's vector environment over the native bouts: ``n``
opponents' bouts stepped together in Rust threads (the interpreter lock
released), with the observations, actions and rewards of
:class:`shisen.env.BoxingEnv`. A bout whose episode ends starts again at
once, its last observation in ``info["terminal_observation"]`` (SB3's
convention).

    from stable_baselines3 import PPO
    from stable_baselines3.common.vec_env import VecMonitor
    from shisen.sb3 import BoxingVecEnv
    env = VecMonitor(BoxingVecEnv(8, episode_seconds=5.0))
    PPO("MlpPolicy", env).learn(100_000)
"""

from __future__ import annotations

from typing import Optional, Union

import numpy as np
from stable_baselines3.common.vec_env.base_vec_env import VecEnv

from . import Scene
from ._shisen import Arena
from .env import _check, _scene, opponent_spaces, reward


class BoxingVecEnv(VecEnv):
    """``num_envs`` bouts as one SB3 ``VecEnv`` (see the module's docstring)."""

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
        obs_space, act_space = opponent_spaces()
        self.render_mode = None
        super().__init__(num_envs, obs_space, act_space)
        self.scene = _scene(scene)
        self.episode_seconds = episode_seconds
        self.hit_reward = hit_reward
        self.taken_penalty = taken_penalty
        self.arena = Arena(self.scene, num_envs, control_dt, "own", 0)
        self._rng = np.random.default_rng()
        self._actions: Optional[np.ndarray] = None

    def _seed(self, i: int) -> int:
        s = self._seeds[i]
        return int(self._rng.integers(0, 2**31)) if s is None else int(s)

    def reset(self):
        if self._seeds[0] is not None:
            self._rng = np.random.default_rng(self._seeds[0])
        for i in range(self.num_envs):
            self.arena.reset(i, self._seed(i))
        self._reset_seeds()
        self._reset_options()
        obs, _ = self.arena.observe()
        return np.clip(obs, -5.0, 5.0)

    def step_async(self, actions: np.ndarray) -> None:
        self._actions = np.asarray(actions, dtype=np.float64).reshape(self.num_envs, 9)

    def step_wait(self):
        if self._actions is None:
            raise RuntimeError("step_async first")
        obs, _, landed, taken = self.arena.step(self._actions)
        obs = np.clip(obs, -5.0, 5.0)
        rewards = reward(landed, taken, self.hit_reward, self.taken_penalty).astype(np.float32)
        dones = self.arena.times() >= self.episode_seconds - 1e-9
        infos = [{"landed": int(landed[i]), "taken": int(taken[i])} for i in range(self.num_envs)]
        for i in np.flatnonzero(dones):
            infos[i]["terminal_observation"] = obs[i].copy()
            infos[i]["TimeLimit.truncated"] = True
            self.arena.reset(int(i), int(self._rng.integers(0, 2**31)))
        if dones.any():
            fresh, _ = self.arena.observe()
            obs[dones] = np.clip(fresh[dones], -5.0, 5.0)
        return obs, rewards, dones, infos

    def close(self) -> None:
        pass

    def get_attr(self, attr_name, indices=None):
        return [getattr(self, attr_name) for _ in self._get_indices(indices)]

    def set_attr(self, attr_name, value, indices=None) -> None:
        setattr(self, attr_name, value)

    def env_method(self, method_name, *method_args, indices=None, **method_kwargs):
        raise AttributeError(f"BoxingVecEnv's bouts have no method `{method_name}`")

    def env_is_wrapped(self, wrapper_class, indices=None):
        return [False for _ in self._get_indices(indices)]
