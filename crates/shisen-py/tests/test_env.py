"""The Gymnasium environment: it passes Gymnasium's own checks, is
deterministic under reset(seed=...), and rewards blows."""

import numpy as np
import pytest

gym = pytest.importorskip("gymnasium")

from gymnasium.utils.env_checker import check_env  # noqa: E402

from shisen.env import BoxingEnv, make_vec  # noqa: E402


def test_the_environment_passes_gymnasiums_checks():
    check_env(BoxingEnv(episode_seconds=0.5), skip_render_check=True)


def test_same_seed_same_episode():
    def episode(seed):
        env = BoxingEnv(episode_seconds=1.0)
        obs, _ = env.reset(seed=seed)
        rng = np.random.default_rng(0)
        seen = [obs]
        done = False
        while not done:
            obs, r, term, trunc, _ = env.step(rng.uniform(-1, 1, 9).astype(np.float32))
            seen.append(obs)
            done = term or trunc
        return np.array(seen)

    a, b = episode(3), episode(3)
    assert np.array_equal(a, b)
    assert len(a) == 51


def test_a_straight_punch_at_the_head_is_rewarded_or_blocked():
    env = BoxingEnv(episode_seconds=2.0)
    env.reset(seed=1)
    total, landed_or_met = 0.0, 0
    # Left glove straight at the VH's head for 0.2 s, then back, twice.
    for k in range(100):
        a = np.zeros(9, dtype=np.float32)
        if k % 50 < 10:
            a[3:6] = (0.4, 0.3, 1.0)
        obs, r, term, trunc, info = env.step(a)
        total += r
        landed_or_met += info["landed"]
    t = env.sim.tally()
    assert t["opponent_hits"] + t["opponent_blocked"] + t["opponent_guarded"] >= 1, t
    assert total == pytest.approx(t["opponent_hits"] - t["vh_hits"])


def test_the_registered_id_and_a_vector_of_envs():
    import shisen.env  # noqa: F401

    env = gym.make("shisen/Boxing-v0", episode_seconds=0.2)
    obs, _ = env.reset(seed=0)
    assert obs.shape == (30,)
    vec = make_vec(2, episode_seconds=0.2)
    obs, _ = vec.reset(seed=[0, 1])
    assert obs.shape == (2, 30)
    obs, r, term, trunc, _ = vec.step(np.zeros((2, 9), dtype=np.float32))
    assert r.shape == (2,)
