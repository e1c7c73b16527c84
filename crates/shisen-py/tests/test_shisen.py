"""The Python package against the simulator: scenes load and fail as the
command line does, runs come back as arrays, a Sim steps deterministically,
the opponent can be driven, and the Gymnasium environment is well formed
and deterministic."""

import pathlib
import threading

import numpy as np
import pytest

import shisen

ROOT = pathlib.Path(__file__).resolve().parents[3]
SCENES = ROOT / "scenes"


def test_a_scene_loads_and_round_trips():
    s = shisen.Scene.load(SCENES / "wave.ron")
    assert s.duration > 0
    again = shisen.Scene.from_str(s.to_ron(), "again.ron")
    assert again.to_ron() == s.to_ron()


def test_a_bad_scene_names_file_line_column_and_field():
    text = "Scene(duration: 2.0, timeline: [(at: 0.5, do: Punch(hand: Left, target: Head, speed: -3.0))])"
    with pytest.raises(shisen.SceneError) as e:
        shisen.Scene.from_str(text, "bad.ron")
    err = e.value
    assert err.file == "bad.ron"
    assert err.line == 1 and err.column > 1
    assert "speed" in err.field
    assert str(err).startswith("bad.ron:1:")
    with pytest.raises(OSError):
        shisen.Scene.load(SCENES / "no_such_scene.ron")


def test_a_scene_is_edited_by_field_paths_and_validated():
    base = shisen.Scene.default()
    edited = base.edit({"vh.personality.a_face": 2.5}, seed=11)
    assert edited.seed == 11
    assert "a_face: 2.5" in edited.to_ron()
    assert "a_face: 2.5" not in base.to_ron()
    with pytest.raises(ValueError, match="no_such_field"):
        base.edit({"vh.no_such_field": 1.0})
    with pytest.raises(ValueError):
        base.edit({"duration": -1.0})


def test_run_gives_every_trace_column_as_arrays():
    cols = shisen.Scene.load(SCENES / "look_sequence.ron").run(duration=0.5)
    assert list(cols) == shisen.columns()
    t = cols["t"]
    assert isinstance(t, np.ndarray) and t.dtype == np.float64
    assert len(t) == 500 and abs(t[-1] - 0.5) < 1e-9
    assert isinstance(cols["gaze_target"], list) and len(cols["gaze_target"]) == 500
    # Angles in degrees, as in the CSV: the eyes move in this scene.
    assert np.ptp(cols["eye_l_yaw"]) > 1.0


def test_same_seed_same_samples_other_seed_other_samples():
    scene = shisen.Scene.default()
    a = scene.run(duration=2.0, seed=5)["eye_l_yaw"]
    b = scene.run(duration=2.0, seed=5)["eye_l_yaw"]
    c = scene.run(duration=2.0, seed=6)["eye_l_yaw"]
    assert np.array_equal(a, b)
    assert not np.array_equal(a, c)


def test_sim_steps_and_the_opponent_can_be_driven():
    sim = shisen.Scene.default().sim(seed=1)
    assert sim.sample() is None
    sim.step(100)
    assert abs(sim.time - 0.1) < 1e-9
    before = sim.positions()["left_glove"]
    sim.move_part("left_glove", (before[0], before[1] + 0.1, before[2]), 0.2)
    sim.step(300)
    after = sim.positions()["left_glove"]
    assert after[1] - before[1] > 0.08
    sim.punch("right", "head", 7.0)
    sim.step(500)
    t = sim.tally()
    assert t["opponent_hits"] + t["opponent_blocked"] + t["opponent_guarded"] >= 1
    with pytest.raises(ValueError):
        sim.punch("middle")
    with pytest.raises(shisen.SceneError) as e:
        sim.move_part("left_glove", (0.0, 1.5, 0.5), -1.0)
    assert "duration" in e.value.field
    with pytest.raises(shisen.SceneError):
        sim.punch("left", "head", float("nan"))
    with pytest.raises(ValueError):
        sim.move_part("no_such_prop", (0.0, 1.5, 0.5), 0.5)


def test_threads_step_simulations_side_by_side():
    scene = shisen.Scene.default()
    serial = [scene.run(duration=1.0, seed=k)["neck_yaw"] for k in range(2)]
    out = [None, None]

    def work(k):
        out[k] = scene.run(duration=1.0, seed=k)["neck_yaw"]

    threads = [threading.Thread(target=work, args=(k,)) for k in range(2)]
    for th in threads:
        th.start()
    for th in threads:
        th.join()
    for k in range(2):
        assert np.array_equal(serial[k], out[k])


def test_scene_files_run_as_shisen_test_does():
    runs = shisen.test([SCENES / "wave.ron", SCENES / "jab_lands.ron"], jobs=1)
    assert [r["name"] for r in runs] == ["wave", "jab_lands"]
    assert all(r["passed"] for r in runs), runs
    assert all(r["verdicts"] for r in runs)


def test_a_study_runs_as_shisen_study_does(tmp_path):
    (tmp_path / "s.ron").write_text(
        'Study(scene: "%s", vary: [(field: "vh.personality.a_face", values: [0.5, 2.0])], seeds: Range(from: 1, to: 2))'
        % (SCENES / "wave.ron")
    )
    runs = shisen.study(tmp_path / "s.ron", jobs=2)
    assert len(runs) == 4
    assert sorted({r["vh.personality.a_face"] for r in runs}) == [0.5, 2.0]
    assert sorted({r["seed"] for r in runs}) == [1, 2]
    assert all(r["verdicts"] for r in runs)
    pd = pytest.importorskip("pandas")
    df = shisen.study_frame(tmp_path / "s.ron", jobs=1)
    assert len(df) == 4 and "expect0" in df.columns
    with pytest.raises(shisen.SceneError):
        (tmp_path / "bad.ron").write_text('Study(scene: "x.ron", vary: [], seeds: Bogus)')
        shisen.study(tmp_path / "bad.ron")


def test_to_frame_gives_a_dataframe():
    pd = pytest.importorskip("pandas")
    df = shisen.to_frame(shisen.Scene.load(SCENES / "wave.ron").run(duration=0.2))
    assert isinstance(df, pd.DataFrame) and len(df) == 200
    assert df.index.name == "t"
