//! shisen for Python (`import shisen`): load, validate and edit scenes with
//! the same errors as the command line (as `shisen.SceneError` with the
//! file, line, column and field), run them headless, step a simulation and
//! read its samples as numpy arrays with no CSV in between, run scene files
//! as `shisen test` does, studies and the fidelity battery, and drive the opponent
//! from Python (the Gymnasium environment in `shisen.env` is built on it).
//!
//! The interpreter lock is released while the simulation steps, so Python
//! threads stepping different simulations run in parallel.

mod arena;

use std::path::{Path, PathBuf};

use glam::DVec3;
use numpy::IntoPyArray;
use pyo3::exceptions::{PyOSError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use shisen::LoadError;
use shisen::physics::body::{OpponentPart, Seg};
use shisen::scene::LoadedScene;
use shisen::sim::timeline::{Action, Event, Hand, Part, PunchTarget};
use shisen::sim::{Sample, Sim as CoreSim};
use shisen::tools::trace::{COLUMNS, Cell};

pyo3::create_exception!(
    _shisen,
    SceneError,
    PyValueError,
    "A scene that cannot be loaded: `file`, `line`, `column`, `field` and `message` say where and why."
);

/// A load error as a Python exception: `SceneError` for a bad scene (with
/// its place), `OSError` for a file that cannot be read.
fn scene_error(py: Python<'_>, e: LoadError) -> PyErr {
    match e {
        LoadError::Io { file, reason } => PyOSError::new_err(format!("{file}: {reason}")),
        LoadError::Invalid {
            ref file,
            line,
            col,
            ref field,
            ref message,
        } => {
            let err = SceneError::new_err(e.to_string());
            let v = err.value(py);
            let set = || -> PyResult<()> {
                v.setattr("file", file)?;
                v.setattr("line", line)?;
                v.setattr("column", col)?;
                v.setattr("field", field)?;
                v.setattr("message", message)?;
                Ok(())
            };
            match set() {
                Ok(()) => err,
                Err(e) => e,
            }
        }
    }
}

/// A scene: the world, the VH's parameters, the timeline and the
/// expectations, loaded and validated.
#[pyclass(module = "shisen._shisen", frozen)]
struct Scene {
    inner: LoadedScene,
}

#[pymethods]
impl Scene {
    /// Load a scene file (RON). Raises `SceneError` naming the file, line,
    /// column and field of what is wrong.
    #[staticmethod]
    fn load(py: Python<'_>, path: PathBuf) -> PyResult<Scene> {
        let inner = py
            .detach(|| LoadedScene::load(&path))
            .map_err(|e| scene_error(py, e))?;
        Ok(Scene { inner })
    }

    /// A scene from RON text; `name` is the file name its errors carry, and
    /// relative paths in it are read from `dir` (default: none).
    #[staticmethod]
    #[pyo3(signature = (text, name = "<string>", dir = None))]
    fn from_str(py: Python<'_>, text: &str, name: &str, dir: Option<PathBuf>) -> PyResult<Scene> {
        let inner = py
            .detach(|| LoadedScene::from_str(text, Path::new(name), dir.as_deref()))
            .map_err(|e| scene_error(py, e))?;
        Ok(Scene { inner })
    }

    /// The embedded default scene (what `shisen` opens in the window).
    #[staticmethod]
    fn default() -> Scene {
        Scene {
            inner: LoadedScene::default_scene(),
        }
    }

    /// Length of the scene, s.
    #[getter]
    fn duration(&self) -> f64 {
        self.inner.scene.duration
    }

    /// The scene's random seed.
    #[getter]
    fn seed(&self) -> u64 {
        self.inner.scene.seed
    }

    /// The scene as RON text (loads back to the same scene).
    fn to_ron(&self) -> String {
        self.inner.scene.to_ron()
    }

    /// A copy with numbers at dotted field paths set (as a study varies
    /// them): `scene.edit({"vh.personality.a_face": 1.2, "gains.neck.kp":
    /// 40.0})`, and the seed if given; validated like a file. Raises
    /// `ValueError` naming the field, or `SceneError` for a value the scene
    /// refuses.
    #[pyo3(signature = (fields, seed = None))]
    fn edit(
        &self,
        py: Python<'_>,
        fields: std::collections::BTreeMap<String, f64>,
        seed: Option<u64>,
    ) -> PyResult<Scene> {
        let label = format!("{} (edited)", self.inner.source);
        let fields: Vec<(&str, f64)> = fields.iter().map(|(f, x)| (f.as_str(), *x)).collect();
        let inner = py
            .detach(|| shisen::tools::study::edit_scene(&self.inner, &fields, seed, &label))
            .map_err(|e| PyValueError::new_err(e.to_string()))?;
        Ok(Scene { inner })
    }

    /// A simulation of the scene at its start, with the scene's seed or `seed`.
    #[pyo3(signature = (seed = None))]
    fn sim(&self, seed: Option<u64>) -> Sim {
        Sim::of(&self.inner, seed)
    }

    /// Run the scene headless for its duration (or `duration` s) and return
    /// the samples as columns: numpy float arrays for the numeric trace
    /// columns (same names and units as the CSV trace), lists of str for
    /// the others. `every` keeps every Nth tick.
    #[pyo3(signature = (duration = None, seed = None, every = 1))]
    fn run<'py>(
        &self,
        py: Python<'py>,
        duration: Option<f64>,
        seed: Option<u64>,
        every: usize,
    ) -> PyResult<Bound<'py, PyDict>> {
        let mut sim = Sim::of(&self.inner, seed);
        let until = duration.unwrap_or(self.inner.scene.duration);
        sim.run_until(py, until, every.max(1))
    }

    fn __repr__(&self) -> String {
        format!(
            "Scene('{}', duration={} s, seed={})",
            self.inner.source, self.inner.scene.duration, self.inner.scene.seed
        )
    }
}

/// Samples gathered column by column.
struct Columns {
    numbers: Vec<Vec<f64>>,
    texts: Vec<Vec<String>>,
}

impl Columns {
    fn new() -> Self {
        let (mut numbers, mut texts) = (Vec::new(), Vec::new());
        for (_, cell) in COLUMNS {
            match cell {
                Cell::Num(..) => numbers.push(Vec::new()),
                Cell::Text(_) => texts.push(Vec::new()),
            }
        }
        Columns { numbers, texts }
    }

    fn push(&mut self, s: &Sample) {
        let (mut n, mut t) = (0, 0);
        for (_, cell) in COLUMNS {
            match cell {
                Cell::Num(get, _) => {
                    self.numbers[n].push(get(s));
                    n += 1;
                }
                Cell::Text(_) => {
                    let mut out = String::new();
                    cell.write(s, &mut out);
                    self.texts[t].push(out);
                    t += 1;
                }
            }
        }
    }

    fn into_dict(self, py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
        let d = PyDict::new(py);
        let (mut numbers, mut texts) = (self.numbers.into_iter(), self.texts.into_iter());
        for (name, cell) in COLUMNS {
            match cell {
                Cell::Num(..) => {
                    let v = numbers.next().expect("one vector per numeric column");
                    d.set_item(name, v.into_pyarray(py))?;
                }
                Cell::Text(_) => {
                    d.set_item(name, texts.next().expect("one vector per text column"))?;
                }
            }
        }
        Ok(d)
    }
}

/// A running simulation: the VH, your avatar (the opponent) and the props,
/// stepped at 1 kHz in simulation time.
#[pyclass(module = "shisen._shisen")]
struct Sim {
    inner: CoreSim,
}

impl Sim {
    fn of(scene: &LoadedScene, seed: Option<u64>) -> Sim {
        let mut model = scene.model();
        if let Some(s) = seed {
            model.seed = s;
        }
        Sim {
            inner: CoreSim::new(model, &scene.scene.timeline),
        }
    }

    fn run_until<'py>(
        &mut self,
        py: Python<'py>,
        until: f64,
        every: usize,
    ) -> PyResult<Bound<'py, PyDict>> {
        let sim = &mut self.inner;
        let cols = py.detach(|| {
            let mut cols = Columns::new();
            let dt = sim.model().dt;
            let mut n = 0usize;
            while sim.time() + dt / 2.0 < until {
                let s = sim.step();
                if n.is_multiple_of(every) {
                    cols.push(s);
                }
                n += 1;
            }
            cols
        });
        cols.into_dict(py)
    }
}

impl Sim {
    /// Schedule `action` now, checked by the scene format's own rules (the
    /// ranges and messages of a scene file's timeline): the event goes
    /// through the same validating reader.
    fn push(&mut self, py: Python<'_>, action: Action) -> PyResult<()> {
        let event = Event {
            at: self.inner.time(),
            action,
        };
        let text = ron::to_string(&event).map_err(|e| PyValueError::new_err(e.to_string()))?;
        let event: Event = shisen::util::ron::parse_ron(&text, Path::new("<python event>"))
            .map_err(|e| scene_error(py, e))?;
        self.inner.push_event(event);
        Ok(())
    }
}

/// A blow tally as a dict (its field names).
fn tally_dict<'py>(py: Python<'py>, t: &shisen::sim::blows::Tally) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("vh_hits", t.vh_hits)?;
    d.set_item("opponent_hits", t.opponent_hits)?;
    d.set_item("vh_blocked", t.vh_blocked)?;
    d.set_item("opponent_blocked", t.opponent_blocked)?;
    d.set_item("opponent_guarded", t.opponent_guarded)?;
    Ok(d)
}

fn vec3(v: DVec3) -> (f64, f64, f64) {
    (v.x, v.y, v.z)
}

fn part_of(name: &str) -> Part {
    match name {
        "head" => Part::Head,
        "left_glove" => Part::LeftGlove,
        "right_glove" => Part::RightGlove,
        other => Part::Body(other.to_string()),
    }
}

#[pymethods]
impl Sim {
    /// Simulation time, s.
    #[getter]
    fn time(&self) -> f64 {
        self.inner.time()
    }

    /// The fixed step, s.
    #[getter]
    fn dt(&self) -> f64 {
        self.inner.model().dt
    }

    /// Advance `ticks` steps (the interpreter lock released meanwhile).
    #[pyo3(signature = (ticks = 1))]
    fn step(&mut self, py: Python<'_>, ticks: usize) {
        let sim = &mut self.inner;
        py.detach(|| {
            for _ in 0..ticks {
                sim.step();
            }
        });
    }

    /// Step until time `until` s and return the samples as columns (see
    /// `Scene.run`).
    #[pyo3(signature = (until, every = 1))]
    fn run<'py>(
        &mut self,
        py: Python<'py>,
        until: f64,
        every: usize,
    ) -> PyResult<Bound<'py, PyDict>> {
        self.run_until(py, until, every.max(1))
    }

    /// The last tick's sample as a dict (trace column names), or None
    /// before the first step.
    fn sample<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        let Some(s) = self.inner.last() else {
            return Ok(None);
        };
        let d = PyDict::new(py);
        for (name, cell) in COLUMNS {
            match cell {
                Cell::Num(get, _) => d.set_item(name, get(s))?,
                Cell::Text(_) => {
                    let mut out = String::new();
                    cell.write(s, &mut out);
                    d.set_item(name, out)?
                }
            }
        }
        Ok(Some(d))
    }

    /// Blows so far, both ways: hits and blocks of each fighter.
    fn tally<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        tally_dict(py, &self.inner.tally())
    }

    /// World positions (x, y, z), m, of the VH's head, eyes midpoint and
    /// gloves, and of the opponent's head and gloves.
    fn positions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let w = &self.inner.world;
        let p = |b| vec3(w.position(b).as_dvec3());
        let d = PyDict::new(py);
        d.set_item("vh_head", p(Seg::Head.body()))?;
        d.set_item("vh_left_glove", p(Seg::GloveL.body()))?;
        d.set_item("vh_right_glove", p(Seg::GloveR.body()))?;
        d.set_item("vh_torso", p(Seg::Torso.body()))?;
        for part in OpponentPart::ALL {
            d.set_item(part.name(), p(w.part(part)))?;
        }
        Ok(d)
    }

    /// Move a part of the opponent (`head`, `left_glove`, `right_glove`)
    /// or a kinematic prop (by name) to `to` over `duration` s, starting
    /// now: the timeline event live input uses, so it replays exactly.
    fn move_part(
        &mut self,
        py: Python<'_>,
        part: &str,
        to: (f64, f64, f64),
        duration: f64,
    ) -> PyResult<()> {
        let part = part_of(part);
        if let Part::Body(name) = &part
            && !self
                .inner
                .world
                .body_named(name)
                .is_some_and(|b| self.inner.world.info(b).kinematic)
        {
            return Err(PyValueError::new_err(format!(
                "part: no opponent part or kinematic body named `{name}`"
            )));
        }
        let to = DVec3::new(to.0, to.1, to.2);
        self.push(py, Action::Move { part, to, duration })
    }

    /// Throw a punch with the opponent's `hand` (`left`, `right`) at the
    /// VH's `head` or `body`, peak glove speed `speed` m/s, starting now.
    #[pyo3(signature = (hand, target = "head", speed = 7.0))]
    fn punch(&mut self, py: Python<'_>, hand: &str, target: &str, speed: f64) -> PyResult<()> {
        let hand = match hand {
            "left" => Hand::Left,
            "right" => Hand::Right,
            h => {
                return Err(PyValueError::new_err(format!(
                    "hand: `left` or `right`, got `{h}`"
                )));
            }
        };
        let target = match target {
            "head" => PunchTarget::Head,
            "body" => PunchTarget::Body,
            t => {
                return Err(PyValueError::new_err(format!(
                    "target: `head` or `body`, got `{t}`"
                )));
            }
        };
        self.push(
            py,
            Action::Punch {
                hand,
                target,
                speed,
                through: None,
                glove_only: false,
            },
        )
    }
}

/// Run scene files as `shisen test` does (in parallel on `jobs` threads)
/// and return one dict per scene: `name`, `path`, `passed`, `error` (why it
/// could not be loaded, or None) and `verdicts` (`what`, `measured`,
/// `value`, `pass` per expectation).
#[pyfunction]
#[pyo3(signature = (paths, jobs = 0))]
fn test<'py>(
    py: Python<'py>,
    paths: Vec<PathBuf>,
    jobs: usize,
) -> PyResult<Vec<Bound<'py, PyDict>>> {
    let files = shisen::tools::batch::scene_files(&paths).map_err(PyValueError::new_err)?;
    let runs = py.detach(|| {
        shisen::tools::batch::run_scenes(&files, jobs, shisen::tools::table::Shard::ALL, None)
    });
    let mut out = Vec::new();
    for r in runs {
        let d = PyDict::new(py);
        d.set_item("name", &r.name)?;
        d.set_item("path", &r.path)?;
        d.set_item("passed", r.passed())?;
        match &r.outcome {
            Err(e) => {
                d.set_item("error", e)?;
                d.set_item("verdicts", Vec::<Bound<'py, PyDict>>::new())?;
            }
            Ok(report) => {
                d.set_item("error", py.None())?;
                d.set_item("verdicts", verdicts(py, &report.verdicts)?)?;
            }
        }
        out.push(d);
    }
    Ok(out)
}

/// Run a study file (`shisen study`): every run's scene is built and
/// validated first, then the runs go in parallel on `jobs` threads (0: one
/// per core). One dict per run: `run`, `seed`, each varied field by its
/// path, `passed`, `resets`, `saccades`, `head_moves`, and `verdicts` (as
/// in `test`). `shisen.study_frame` turns it into a DataFrame.
#[pyfunction]
#[pyo3(signature = (path, jobs = 0))]
fn study<'py>(py: Python<'py>, path: PathBuf, jobs: usize) -> PyResult<Vec<Bound<'py, PyDict>>> {
    use rayon::prelude::*;
    use shisen::tools::study::LoadedStudy;
    let loaded = py
        .detach(|| LoadedStudy::load(&path))
        .map_err(|e| scene_error(py, e))?;
    let scenes: Vec<LoadedScene> = py
        .detach(|| {
            (0..loaded.runs.len())
                .map(|k| loaded.scene(k))
                .collect::<Result<_, _>>()
        })
        .map_err(|e| scene_error(py, e))?;
    let reports = py.detach(|| {
        shisen::tools::parallel::pool(jobs).install(|| {
            scenes
                .par_iter()
                .map(|s| shisen::tools::headless::run(s, None, None, 1).map_err(|e| e.to_string()))
                .collect::<Vec<_>>()
        })
    });
    let mut out = Vec::new();
    for (k, report) in reports.into_iter().enumerate() {
        let report = report.map_err(PyValueError::new_err)?;
        let (values, seed) = &loaded.runs[k];
        let d = PyDict::new(py);
        d.set_item("run", k)?;
        d.set_item("seed", seed)?;
        for (f, x) in loaded.fields.iter().zip(values) {
            d.set_item(f, x)?;
        }
        d.set_item("passed", report.passed())?;
        d.set_item("resets", report.resets)?;
        d.set_item("saccades", report.saccades)?;
        d.set_item("head_moves", report.head_moves)?;
        d.set_item("verdicts", verdicts(py, &report.verdicts)?)?;
        out.push(d);
    }
    Ok(out)
}

/// Expectations' verdicts as dicts.
fn verdicts<'py>(
    py: Python<'py>,
    list: &[shisen::sim::expect::Verdict],
) -> PyResult<Vec<Bound<'py, PyDict>>> {
    list.iter()
        .map(|v| {
            let vd = PyDict::new(py);
            vd.set_item("what", &v.what)?;
            vd.set_item("measured", &v.measured)?;
            vd.set_item("value", v.value)?;
            vd.set_item("pass", v.pass)?;
            Ok(vd)
        })
        .collect()
}

/// The fidelity battery (`shisen fidelity`) on the default scene's VH: one
/// dict per row, `name`, `value`, `band` (low, high), `unit`, `source`,
/// `pass`.
#[pyfunction]
fn fidelity<'py>(py: Python<'py>) -> PyResult<Vec<Bound<'py, PyDict>>> {
    let rows = py.detach(|| {
        let scene = LoadedScene::default_scene();
        let model = shisen::tools::fidelity::model_of(&scene, None);
        shisen::tools::fidelity::battery(&model).0
    });
    let mut out = Vec::new();
    for r in rows {
        let d = PyDict::new(py);
        d.set_item("name", &r.name)?;
        d.set_item("value", r.value)?;
        d.set_item("band", r.band)?;
        d.set_item("unit", r.unit)?;
        d.set_item("source", r.source)?;
        d.set_item("pass", r.pass())?;
        out.push(d);
    }
    Ok(out)
}

/// The trace's column names, in order (the keys `Scene.run` returns).
#[pyfunction]
fn columns() -> Vec<&'static str> {
    COLUMNS.iter().map(|c| c.0).collect()
}

#[pymodule]
fn _shisen(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Scene>()?;
    m.add_class::<Sim>()?;
    m.add_class::<arena::Arena>()?;
    m.add("VH_COMMANDS", arena::COMMANDS.to_vec())?;
    m.add("HEAD_REACH", arena::HEAD_REACH.to_vec())?;
    m.add("GLOVE_REACH", arena::GLOVE_REACH.to_vec())?;
    m.add("VH_LOOKS", arena::LOOKS.to_vec())?;
    m.add("OPPONENT_OBS", arena::OPPONENT_OBS)?;
    m.add("VH_OBS", arena::VH_OBS)?;
    m.add("SceneError", m.py().get_type::<SceneError>())?;
    m.add_function(wrap_pyfunction!(test, m)?)?;
    m.add_function(wrap_pyfunction!(fidelity, m)?)?;
    m.add_function(wrap_pyfunction!(study, m)?)?;
    m.add_function(wrap_pyfunction!(columns, m)?)?;
    m.add("DT", shisen::DT)?;
    Ok(())
}
