"""The examples run, short: an Optuna study over the neck's gains resumes
where it stopped (trials kept in SQLite); PPO (Stable-Baselines3) and
RLlib self-play train; the environment bench measures every row."""

import importlib.util
import pathlib

import pytest

EXAMPLES = pathlib.Path(__file__).resolve().parents[1] / "examples"
BENCHES = pathlib.Path(__file__).resolve().parents[3] / "benches"


def load(name, folder=EXAMPLES):
    spec = importlib.util.spec_from_file_location(name, folder / f"{name}.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_the_optuna_study_resumes_from_its_database(tmp_path, monkeypatch):
    pytest.importorskip("optuna")
    tune = load("tune_optuna")
    db = f"sqlite:///{tmp_path / 'neck.db'}"
    monkeypatch.setattr("sys.argv", ["tune_optuna", "--trials", "3", "--storage", db])
    tune.main()
    monkeypatch.setattr("sys.argv", ["tune_optuna", "--trials", "5", "--storage", db])
    tune.main()
    import optuna

    study = optuna.load_study(study_name="neck-gains", storage=db)
    assert len(study.trials) == 5
    assert study.best_value < 5.0  # degrees: the eyes stay on their targets


def test_ppo_trains_the_opponent_on_the_native_bouts(tmp_path):
    """A short PPO run through SB3's vector env over the Rust bouts: it
    learns without error, and its report and curve are written."""
    pytest.importorskip("stable_baselines3")
    ppo = load("train_ppo")
    out = tmp_path / "curve.png"
    report = ppo.main(["--steps", "2048", "--envs", "4", "--seconds", "1", "--out", str(out)])
    assert out.stat().st_size > 1000
    assert report["steps_per_second"] > 0
    assert report["first_reward"] is not None


def test_rllib_self_play_runs_on_a_local_ray_cluster(tmp_path):
    pytest.importorskip("ray.rllib")
    selfplay = load("selfplay_rllib")
    out = tmp_path / "curve.png"
    report = selfplay.main(
        ["--iterations", "1", "--batch", "400", "--seconds", "1", "--out", str(out)]
    )
    assert out.stat().st_size > 1000
    row = report["curve"][0]
    # Zero-sum: what one agent lands the other takes.
    assert row["opponent"] == pytest.approx(-row["vh"])


def test_the_environment_bench_measures_every_row():
    bench = load("python_envs", BENCHES)
    rows = bench.main(["--seconds", "0.2"])
    assert len(rows) == 8
    assert all(r > 0 for _, _, r in rows)
