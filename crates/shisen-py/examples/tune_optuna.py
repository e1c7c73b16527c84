"""Tune the neck's PD gains with Optuna against a gaze objective, resuming
where it stopped: trials are kept in a database (SQLite here), so a killed
run started again carries on, and several processes (a Slurm array, a
Kubernetes Indexed Job) given the same database URL share one study.

Objective: the line-of-sight error over `scenes/look_sequence.ron` (the
eyes' angle off the gaze point, degrees, both eyes, the whole run), plus a
heavy penalty for a run in which the physics blew up.

    pip install "./crates/shisen-py[test]" optuna
    python3 crates/shisen-py/examples/tune_optuna.py --trials 20 --storage sqlite:///neck.db
    # on a cluster, every task:  ... --storage postgresql://user@host/db --trials 10

See docs/cluster/README.md for the cluster recipes.
"""

import argparse
import math
import pathlib

import numpy as np
import optuna

import shisen

ROOT = pathlib.Path(__file__).resolve().parents[3]


def objective_for(base):
    def objective(trial):
        kp = trial.suggest_float("gains.neck.kp", 5.0, 500.0, log=True)
        kd = trial.suggest_float("gains.neck.kd", 0.1, 50.0, log=True)
        try:
            scene = base.edit({"gains.neck.kp": kp, "gains.neck.kd": kd})
        except ValueError as e:  # gains the body cannot integrate
            raise optuna.TrialPruned(str(e))
        cols = scene.run(every=5)
        err = np.concatenate([cols["los_err_l"], cols["los_err_r"]])
        resets = cols["reset"].sum()
        value = float(np.mean(err)) + 100.0 * float(resets)
        return value if math.isfinite(value) else 1e9

    return objective


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--trials", type=int, default=20)
    ap.add_argument("--storage", default="sqlite:///shisen-neck.db")
    ap.add_argument("--study", default="neck-gains")
    ap.add_argument("--seed", type=int, default=0)
    args = ap.parse_args()

    base = shisen.Scene.load(ROOT / "scenes/look_sequence.ron")
    study = optuna.create_study(
        study_name=args.study,
        storage=args.storage,
        load_if_exists=True,  # resume
        direction="minimize",
        sampler=optuna.samplers.TPESampler(seed=args.seed),
    )
    done = len([t for t in study.trials if t.state.is_finished()])
    study.optimize(objective_for(base), n_trials=max(0, args.trials - done))
    print(f"{len(study.trials)} trials; best {study.best_value:.3f} deg at {study.best_params}")


if __name__ == "__main__":
    main()
