"""The Gymnasium environments: they pass Gymnasium's own checks, are
deterministic under reset(seed=...), reward blows, and the native vector
environment steps the same bouts as the single one."""

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
    t = env.tally()
    assert t["opponent_hits"] + t["opponent_blocked"] + t["opponent_guarded"] >= 1, t
    assert total == pytest.approx(t["opponent_hits"] - t["vh_hits"])


def test_the_registered_id():
    import shisen.env  # noqa: F401

    env = gym.make("shisen/Boxing-v0", episode_seconds=0.2)
    obs, _ = env.reset(seed=0)
    assert obs.shape == (30,)


def test_the_vector_env_steps_the_bouts_the_single_env_steps():
    """Bout i of the native vector env, seeded s, is BoxingEnv seeded s:
    same observations and rewards, step for step (threads change
    nothing)."""
    rng = np.random.default_rng(5)
    actions = rng.uniform(-1, 1, (30, 3, 9)).astype(np.float32)
    vec = make_vec(3, episode_seconds=10.0)
    obs, _ = vec.reset(seed=[4, 5, 6])
    singles = [BoxingEnv(episode_seconds=10.0) for _ in range(3)]
    firsts = [e.reset(seed=s)[0] for e, s in zip(singles, [4, 5, 6])]
    assert np.array_equal(obs, np.array(firsts))
    for a in actions:
        obs, r, term, trunc, _ = vec.step(a)
        for i, env in enumerate(singles):
            o, ri, *_ = env.step(a[i])
            assert np.array_equal(obs[i], o)
            assert r[i] == ri
    assert vec.observation_space.shape == (3, 30)


def test_the_vector_env_starts_an_ended_bout_again_at_the_next_step():
    vec = make_vec(2, episode_seconds=0.1)
    first, _ = vec.reset(seed=7)
    zeros = np.zeros((2, 9), dtype=np.float32)
    for k in range(5):
        obs, r, term, trunc, _ = vec.step(zeros)
    assert trunc.all() and not term.any()
    # The next step starts both again: a first observation, no reward, not
    # done; the bouts are new ones (their clocks back at the start).
    obs, r, term, trunc, _ = vec.step(zeros)
    assert not trunc.any() and (r == 0).all()
    assert (vec.arena.times() == 0.0).all()
    assert obs.shape == first.shape
    obs, r, term, trunc, _ = vec.step(zeros)
    assert (vec.arena.times() > 0.0).all()
