"""The two-agent PettingZoo environment: the VH's agent takes over its
decisions (and optionally its gaze requests), the rest of the pipeline
stays the simulator's."""

import numpy as np
import pytest

pytest.importorskip("pettingzoo")

from pettingzoo.test import parallel_api_test  # noqa: E402

from shisen._shisen import VH_COMMANDS  # noqa: E402
from shisen.multiagent import parallel_env  # noqa: E402

STILL = np.zeros(9, dtype=np.float32)
ACTIONS = ("idle", "guard", "attack", "slip", "duck", "leanback")


def play(env, vh_command, seconds, look=0, seed=1):
    """Run `seconds` with the opponent still and the VH agent giving
    `vh_command` every step; the VH's actions seen (from the opponent's
    observation) and the rewards."""
    obs, _ = env.reset(seed=seed)
    cmd = VH_COMMANDS.index(vh_command)
    actions, rewards = set(), {"opponent": 0.0, "vh": 0.0}
    for _ in range(round(seconds / env.control_dt)):
        obs, r, term, trunc, _ = env.step(
            {"opponent": STILL, "vh": np.array([cmd, look])}
        )
        actions.add(ACTIONS[int(np.argmax(obs["opponent"][15:21]))])
        for a in r:
            rewards[a] += r[a]
    return actions, rewards, obs


@pytest.mark.parametrize("control", ["decisions", "gaze", "own"])
def test_the_environment_passes_pettingzoos_api_test(control):
    parallel_api_test(parallel_env(vh_control=control, episode_seconds=1.0), num_cycles=120)


def test_a_vh_agent_that_does_nothing_never_attacks_and_one_that_jabs_lands():
    env = parallel_env(vh_control="decisions", episode_seconds=60.0)
    actions, rewards, _ = play(env, "nothing", 6.0)
    assert "attack" not in actions
    assert rewards["vh"] == 0.0
    actions, rewards, _ = play(env, "jab_head", 6.0)
    assert "attack" in actions
    # A still opponent takes the jabs: zero-sum rewards.
    assert rewards["vh"] >= 3.0, rewards
    assert rewards["opponent"] == -rewards["vh"]


def test_the_vh_agent_s_evasions_are_carried_out():
    env = parallel_env(vh_control="decisions")
    for cmd, action in [("slip_left", "slip"), ("duck", "duck"), ("lean_back", "leanback")]:
        actions, _, _ = play(env, cmd, 0.6)
        assert action in actions, (cmd, actions)


def test_the_vh_sees_the_opponent_with_its_own_eyes():
    env = parallel_env(vh_control="decisions")
    obs, _ = env.reset(seed=2)
    for _ in range(10):
        obs, *_ = env.step({"opponent": STILL, "vh": np.array([0, 0])})
    vh = obs["vh"]
    # The opponent's head seen, ahead (head frame +z), about a metre away.
    assert vh[0] == 1.0
    assert vh[3] > 0.9, vh[1:4]
    assert 0.6 < vh[4] < 2.0, vh[4]
    # Its own gloves in front of its face, left on its left (+x).
    assert vh[26] > 0.1 and vh[24] > vh[27]


def test_the_vh_agent_s_gaze_request_moves_its_eyes():
    """With the gaze taken over, asking for the opponent's body brings the
    gaze point down from the face; with decisions only, the same request
    changes nothing."""

    def gaze_height(control, look):
        env = parallel_env(vh_control=control)
        _, _, obs = play(env, "nothing", 1.5, look=look)
        return obs["opponent"][13]

    face = gaze_height("gaze", 1)
    body = gaze_height("gaze", 4)
    assert body < face - 0.15, (face, body)
    assert gaze_height("decisions", 4) == pytest.approx(gaze_height("decisions", 1))


def test_same_seed_same_two_agent_episode():
    def episode():
        env = parallel_env(vh_control="gaze", episode_seconds=1.0)
        obs, _ = env.reset(seed=9)
        rng = np.random.default_rng(0)
        out = [obs["vh"]]
        while env.agents:
            acts = {
                "opponent": rng.uniform(-1, 1, 9).astype(np.float32),
                "vh": rng.integers(0, [11, 5]),
            }
            obs, *_ = env.step(acts)
            out.append(obs["vh"])
        return np.array(out)

    assert np.array_equal(episode(), episode())
