"""The examples' machinery: an Optuna study over the neck's gains resumes
where it stopped (trials kept in SQLite)."""

import importlib.util
import pathlib

import pytest

EXAMPLES = pathlib.Path(__file__).resolve().parents[1] / "examples"


def load(name):
    spec = importlib.util.spec_from_file_location(name, EXAMPLES / f"{name}.py")
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
