"""Ray RLlib: the opponent and the VH learn against each other.

Multi-agent PPO on the two-agent environment (:mod:`shisen.multiagent`):
one policy for the opponent, one for the VH's decisions (``--vh-control
decisions``, or ``gaze`` to learn where it looks too), the rest of the VH
(vision, attention, gaze laws, joints, face, physics) the simulator's.
Each training iteration prints both agents' mean episode returns; the
curve is plotted.

On this machine Ray starts a local cluster (``ray.init``); on many
machines, start Ray there (``ray start --head`` on one, ``ray start
--address=HEAD:6379`` on the others, each with ``pip install
"shisen[rl]"`` from the wheel) and pass ``--address auto`` from the head:
the same code spreads its environment runners over the cluster
(docs/python.md).

    pip install "./crates/shisen-py[rl]"
    python3 crates/shisen-py/examples/selfplay_rllib.py                  # about 5 minutes on 2 cores
    python3 crates/shisen-py/examples/selfplay_rllib.py --iterations 1   # a smoke run
"""

import argparse
import json
import pathlib
import time

ROOT = pathlib.Path(__file__).resolve().parents[3]


def make_env(config):
    from ray.rllib.env.wrappers.pettingzoo_env import ParallelPettingZooEnv

    from shisen.env import ring
    from shisen.multiagent import parallel_env

    config = dict(config)
    vh = config.pop("vh", "default")
    return ParallelPettingZooEnv(parallel_env(scene=ring(vh), **config))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--iterations", type=int, default=15)
    ap.add_argument("--batch", type=int, default=4000, help="environment steps per iteration")
    ap.add_argument("--seconds", type=float, default=5.0, help="episode length, simulated s")
    ap.add_argument("--vh-control", default="decisions", choices=["decisions", "gaze"])
    ap.add_argument("--vh", default="default", help="the VH's personality: novice, default, strong")
    ap.add_argument("--runners", type=int, default=1, help="environment runners (processes)")
    ap.add_argument("--address", default=None, help="a running Ray cluster (`auto`), else a local one")
    ap.add_argument("--out", default=str(ROOT / "docs/python/selfplay_curve.png"))
    args = ap.parse_args(argv)

    import ray
    from ray.rllib.algorithms.ppo import PPOConfig
    from ray.rllib.core.rl_module.multi_rl_module import MultiRLModuleSpec
    from ray.rllib.core.rl_module.rl_module import RLModuleSpec
    from ray.tune.registry import register_env

    if args.address:
        ray.init(address=args.address)
    else:
        ray.init(num_cpus=2, include_dashboard=False, log_to_driver=False)
    register_env("shisen-boxing", make_env)
    env_config = {
        "vh_control": args.vh_control,
        "episode_seconds": args.seconds,
        "vh": args.vh,
    }
    config = (
        PPOConfig()
        .environment("shisen-boxing", env_config=env_config)
        .env_runners(num_env_runners=args.runners, num_cpus_per_env_runner=1)
        .multi_agent(
            policies={"opponent", "vh"},
            policy_mapping_fn=lambda agent_id, episode, **kwargs: agent_id,
        )
        .rl_module(
            rl_module_spec=MultiRLModuleSpec(
                rl_module_specs={"opponent": RLModuleSpec(), "vh": RLModuleSpec()}
            )
        )
        .training(
            train_batch_size_per_learner=args.batch,
            minibatch_size=min(256, args.batch),
            num_epochs=4,
            lr=3e-4,
        )
        .debugging(seed=0)
    )
    algo = config.build_algo()
    curve = []
    start = time.perf_counter()
    steps = 0
    for i in range(args.iterations):
        result = algo.train()
        runners = result["env_runners"]
        returns = runners.get("agent_episode_returns_mean", {})
        steps = runners.get("num_env_steps_sampled_lifetime", steps)
        row = {
            "iteration": i + 1,
            "env_steps": steps,
            "opponent": returns.get("opponent"),
            "vh": returns.get("vh"),
        }
        curve.append(row)
        print(json.dumps(row))
    wall = time.perf_counter() - start
    algo.stop()
    ray.shutdown()
    report = {"iterations": args.iterations, "env_steps_per_second": steps / wall, "curve": curve}
    if args.out:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(6.4, 3.6), dpi=110)
        x = [r["env_steps"] for r in curve]
        for agent, colour in (("opponent", "tab:red"), ("vh", "tab:blue")):
            ax.plot(x, [r[agent] for r in curve], color=colour, label=agent)
        ax.axhline(0.0, color="grey", lw=0.6)
        ax.set_xlabel("environment steps (20 ms each)")
        ax.set_ylabel(f"episode return ({args.seconds:g} s):\nhits landed - hits taken")
        ax.set_title(f"RLlib self-play: opponent vs VH ({args.vh_control})", fontsize=9)
        ax.legend()
        fig.tight_layout()
        pathlib.Path(args.out).parent.mkdir(parents=True, exist_ok=True)
        fig.savefig(args.out)
    return report


if __name__ == "__main__":
    main()
