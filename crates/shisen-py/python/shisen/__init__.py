"""shisen (視線, "line of sight") for Python.

A physically simulated virtual human (VH) that boxes and looks where a
person would. From Python you can:

* load, validate and edit scenes: ``Scene.load(path)``, ``Scene.from_str(text)``
  (a bad scene raises :class:`SceneError` naming its file, line, column and
  field, as the command line does);
* run them headless and get every trace column as a numpy array:
  ``Scene.run()`` (or a pandas DataFrame: :func:`to_frame`);
* step a :class:`Sim` yourself, drive the opponent (``move_part``,
  ``punch``) and read samples, positions and the blow tally;
* run scene files as ``shisen test`` does (:func:`test`), studies
  (:func:`study`, :func:`study_frame`) and the fidelity battery
  (:func:`fidelity`);
* train a policy as the VH's opponent: :mod:`shisen.env` (Gymnasium, and a
  native vector env stepping bouts in Rust threads), :mod:`shisen.sb3`
  (Stable-Baselines3's vector env); or the VH's decisions too, against it:
  :mod:`shisen.multiagent` (PettingZoo, two agents).

The interpreter lock is released while a simulation steps, so threads
stepping different simulations run in parallel.
"""

from ._shisen import DT, Scene, SceneError, Sim, columns, fidelity, study, test

__all__ = [
    "DT",
    "Scene",
    "SceneError",
    "Sim",
    "columns",
    "fidelity",
    "study",
    "study_frame",
    "test",
    "to_frame",
]


def to_frame(samples):
    """The columns of ``Scene.run`` / ``Sim.run`` as a pandas DataFrame
    (needs pandas), indexed by time ``t``."""
    import pandas as pd

    return pd.DataFrame(samples, columns=columns()).set_index("t")


def study_frame(path, jobs=0):
    """A study file's runs (:func:`study`) as a pandas DataFrame, one row per
    run, each expectation's measured value as ``expectN`` (needs pandas)."""
    import pandas as pd

    rows = []
    for r in study(path, jobs):
        row = {k: v for k, v in r.items() if k != "verdicts"}
        for i, v in enumerate(r["verdicts"]):
            row[f"expect{i}"] = v["value"]
            row[f"expect{i}_pass"] = v["pass"]
        rows.append(row)
    return pd.DataFrame(rows).set_index("run")
