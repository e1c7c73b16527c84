//! Bouts for learning agents: `n` simulations of one scene stepped together
//! in Rust threads (the interpreter lock released), each driven by two
//! agents' actions, the opponent's and (optionally) the VH's. The Gymnasium
//! environment, the native vector environment and the two-agent PettingZoo
//! environment in `shisen.env` are all built on it, so what an agent sees
//! and what its actions do have one home: here.
//!
//! Frames and units: positions m, world frame (y up; the VH stands at the
//! origin facing +z, your avatar faces it from +z), unless a field says
//! "head frame": the VH's head's axes (x its left, y up, z where it faces).

use glam::DVec3;
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyArray2, PyReadonlyArray2};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use rayon::prelude::*;

use shisen::gaze::behaviour::{ActionKind, Command, Control, Evasion, Look};
use shisen::physics::body::{OpponentPart, Seg};
use shisen::scene::LoadedScene;
use shisen::sim::blows::Tally;
use shisen::sim::timeline::{Action, Event, Part};
use shisen::sim::{Model, Sim};

/// How far each opponent part may be moved from its guard position, m per
/// unit of action (head; gloves), on the x (sideways), y (up) and z (toward
/// the VH) axes. A glove's 0.45 m forward is a full reach to the VH's head.
pub const HEAD_REACH: [f64; 3] = [0.15, 0.15, 0.15];
/// See [`HEAD_REACH`].
pub const GLOVE_REACH: [f64; 3] = [0.30, 0.30, 0.45];
/// The fastest a glove goes, m/s at the peak of a control step's
/// minimum-jerk move: Olympic boxers' hands reach 6-9 m/s (Walilko, Viano
/// & Bir 2005, Br. J. Sports Med. 39:710). Without it a policy learns to
/// strike at 40 m/s, which no arm can.
pub const GLOVE_PEAK: f64 = 9.0;
/// The fastest the head goes, m/s at the peak: the VH's own slip (about
/// 0.16 m in `evade_time` 0.15 s, a minimum-jerk peak near 2 m/s).
pub const HEAD_PEAK: f64 = 2.0;
/// A minimum-jerk move's peak speed over its mean (15/8).
const MIN_JERK_PEAK: f64 = 1.875;
/// The VH's actions in the order of the one-hot observations. A feint
/// reads as an attack: it is the start of one, and what it shows is that.
pub const ACTIONS: [ActionKind; 6] = [
    ActionKind::Idle,
    ActionKind::Guard,
    ActionKind::Attack,
    ActionKind::Slip,
    ActionKind::Duck,
    ActionKind::LeanBack,
];
/// The action as the one-hot shows it ([`ACTIONS`]).
fn shown(a: ActionKind) -> ActionKind {
    if a == ActionKind::Feint {
        ActionKind::Attack
    } else {
        a
    }
}

/// The opponent's observation's length.
pub const OPPONENT_OBS: usize = 30;
/// The VH's observation's length.
pub const VH_OBS: usize = 37;
/// The VH agent's decisions, in the order of its first action component.
pub const COMMANDS: [&str; 11] = [
    "nothing",
    "jab_head",
    "jab_body",
    "cross_head",
    "cross_body",
    "guard_left",
    "guard_right",
    "slip_left",
    "slip_right",
    "duck",
    "lean_back",
];
/// Where the VH agent asks its gaze to go, its second action component.
pub const LOOKS: [&str; 5] = ["own", "head", "left_glove", "right_glove", "body"];

/// The VH agent's action `[command, look]` as the planner's types.
fn vh_command(command: i64, look: i64) -> (Command, Look) {
    let punch = |hand, to_body| Command::Punch { hand, to_body };
    let evade = |kind, right| Command::Evade { kind, right };
    let command = match command {
        1 => punch(0, false),
        2 => punch(0, true),
        3 => punch(1, false),
        4 => punch(1, true),
        5 => Command::Guard { hand: 0 },
        6 => Command::Guard { hand: 1 },
        7 => evade(Evasion::Slip, false),
        8 => evade(Evasion::Slip, true),
        9 => evade(Evasion::Duck, false),
        10 => evade(Evasion::LeanBack, false),
        _ => Command::Nothing,
    };
    let look = match look {
        1 => Look::Head,
        2 => Look::LeftGlove,
        3 => Look::RightGlove,
        4 => Look::Body,
        _ => Look::Own,
    };
    (command, look)
}

/// One bout.
struct Bout {
    sim: Sim,
    /// The opponent's parts' guard positions (head, left glove, right glove).
    rest: [DVec3; 3],
    /// Where each part was last sent.
    aim: [DVec3; 3],
    tally: Tally,
}

/// What one control step did to one bout.
#[derive(Clone, Copy, Default)]
struct Outcome {
    landed: u32,
    taken: u32,
}

impl Bout {
    fn new(model: &Model, timeline: &[Event], seed: u64, control: Control) -> Self {
        let mut model = model.clone();
        model.seed = seed;
        let mut sim = Sim::new(model, timeline);
        sim.behaviour.take_over(control);
        let rest = OpponentPart::ALL.map(|p| sim.world.position(sim.world.part(p)).as_dvec3());
        let tally = sim.tally();
        Bout {
            sim,
            rest,
            aim: rest,
            tally,
        }
    }

    /// Apply the actions, run `ticks`, count the blows.
    fn step(
        &mut self,
        opponent: &[f64; 9],
        vh: Option<[i64; 2]>,
        ticks: usize,
        dt: f64,
    ) -> Outcome {
        let now = self.sim.time();
        for (k, part) in [Part::Head, Part::LeftGlove, Part::RightGlove]
            .into_iter()
            .enumerate()
        {
            let (reach, peak) = if k == 0 {
                (HEAD_REACH, HEAD_PEAK)
            } else {
                (GLOVE_REACH, GLOVE_PEAK)
            };
            // Your avatar faces the VH from +z: forward is toward -z.
            let a = |i: usize| {
                let x = opponent[3 * k + i];
                if x.is_finite() {
                    x.clamp(-1.0, 1.0)
                } else {
                    0.0
                }
            };
            let want =
                self.rest[k] + DVec3::new(a(0) * reach[0], a(1) * reach[1], -a(2) * reach[2]);
            // Toward the target no faster than a person moves it.
            let step = (want - self.aim[k]).clamp_length_max(peak / MIN_JERK_PEAK * dt);
            self.aim[k] += step;
            self.sim.push_event(Event {
                at: now,
                action: Action::Move {
                    part,
                    to: self.aim[k],
                    duration: dt,
                },
            });
        }
        if let Some([command, look]) = vh {
            let (command, look) = vh_command(command, look);
            self.sim.behaviour.command(command, look);
        }
        for _ in 0..ticks {
            self.sim.step();
        }
        let t = self.sim.tally();
        let out = Outcome {
            landed: t.opponent_hits - self.tally.opponent_hits,
            taken: t.vh_hits - self.tally.vh_hits,
        };
        self.tally = t;
        out
    }

    /// The opponent's observation (see `shisen.env`'s docs): the VH's head,
    /// gloves and torso, where it looks, its action one-hot, and the
    /// opponent's own head and gloves; world frame, m.
    fn observe_opponent(&self, out: &mut [f32]) {
        let w = &self.sim.world;
        let at = |b| w.position(b).as_dvec3();
        let s = self.sim.last();
        let head = at(Seg::Head.body());
        let gaze = s.map_or(head, |s| s.gaze_point);
        let action = s.map_or(ActionKind::Idle, |s| shown(s.action));
        let mut v: Vec<f64> = Vec::with_capacity(OPPONENT_OBS);
        for p in [head, at(Seg::GloveL.body()), at(Seg::GloveR.body())] {
            v.extend(p.to_array());
        }
        v.extend(at(Seg::Torso.body()).to_array());
        v.extend(gaze.to_array());
        v.extend(ACTIONS.map(|a| f64::from(u8::from(a == action))));
        for p in OpponentPart::ALL {
            v.extend(at(w.part(p)).to_array());
        }
        for (o, x) in out.iter_mut().zip(v) {
            *o = x as f32;
        }
    }

    /// The VH's observation, from its own vision (what it perceived, with
    /// its latency): per opponent part (head, left glove, right glove) seen
    /// (1/0), the direction (head frame, unit), distance (m) and velocity
    /// (head frame, m/s; zeros where unseen); its own gloves from its head
    /// (head frame, m); its action one-hot; staggered (1/0).
    fn observe_vh(&self, out: &mut [f32]) {
        let w = &self.sim.world;
        let (head, rot) = w.pose(Seg::Head.body());
        let (head, inv) = (head.as_dvec3(), rot.as_dquat().inverse());
        let mut v: Vec<f64> = Vec::with_capacity(VH_OBS);
        for part in w.parts() {
            match self.sim.seen().iter().find(|s| s.body == part) {
                Some(s) => {
                    v.push(1.0);
                    v.extend(s.dir_head.to_array());
                    v.push(s.distance);
                    v.extend(s.rel_velocity.to_array());
                }
                None => v.extend([0.0; 8]),
            }
        }
        for g in [Seg::GloveL, Seg::GloveR] {
            v.extend((inv * (w.position(g.body()).as_dvec3() - head)).to_array());
        }
        let s = self.sim.last();
        let action = s.map_or(ActionKind::Idle, |s| shown(s.action));
        v.extend(ACTIONS.map(|a| f64::from(u8::from(a == action))));
        v.push(f64::from(u8::from(s.is_some_and(|s| s.staggered))));
        for (o, x) in out.iter_mut().zip(v) {
            *o = x as f32;
        }
    }
}

/// `n` bouts of one scene stepped together (see the module's docs).
#[pyclass(module = "shisen._shisen")]
pub struct Arena {
    model: Model,
    timeline: Vec<Event>,
    bouts: Vec<Bout>,
    ticks: usize,
    control: Control,
}

impl Arena {
    fn observations<'py>(
        &self,
        py: Python<'py>,
    ) -> (Bound<'py, PyArray2<f32>>, Bound<'py, PyArray2<f32>>) {
        let n = self.bouts.len();
        let mut opp = Array2::<f32>::zeros((n, OPPONENT_OBS));
        let mut vh = Array2::<f32>::zeros((n, VH_OBS));
        for (i, b) in self.bouts.iter().enumerate() {
            b.observe_opponent(opp.row_mut(i).as_slice_mut().expect("row-major"));
            b.observe_vh(vh.row_mut(i).as_slice_mut().expect("row-major"));
        }
        (opp.into_pyarray(py), vh.into_pyarray(py))
    }
}

#[pymethods]
impl Arena {
    /// `n` bouts of `scene`, each control step `control_dt` s (a whole
    /// number of ticks), the VH's decisions its own (`vh_control="own"`),
    /// an agent's (`"decisions"`) or an agent's with its gaze requests too
    /// (`"gaze"`). Every bout starts with seed `seed + i`; `reset` reseeds
    /// one.
    #[new]
    #[pyo3(signature = (scene, n = 1, control_dt = 0.02, vh_control = "own", seed = 0))]
    fn new(
        scene: &crate::Scene,
        n: usize,
        control_dt: f64,
        vh_control: &str,
        seed: u64,
    ) -> PyResult<Self> {
        if !(1..=4096).contains(&n) {
            return Err(PyValueError::new_err(format!("n: 1-4096 bouts, got {n}")));
        }
        if !(0.001..=1.0).contains(&control_dt) {
            return Err(PyValueError::new_err(format!(
                "control_dt: 0.001-1 s (one tick to a second), got {control_dt}"
            )));
        }
        let control = match vh_control {
            "own" => Control::Own,
            "decisions" => Control::Decisions,
            "gaze" => Control::DecisionsAndGaze,
            c => {
                return Err(PyValueError::new_err(format!(
                    "vh_control: `own`, `decisions` or `gaze`, got `{c}`"
                )));
            }
        };
        let loaded: &LoadedScene = &scene.inner;
        let model = loaded.model();
        let ticks = ((control_dt / model.dt).round() as usize).max(1);
        let timeline = loaded.scene.timeline.clone();
        let bouts = (0..n as u64)
            .map(|i| Bout::new(&model, &timeline, seed.wrapping_add(i), control))
            .collect();
        Ok(Arena {
            model,
            timeline,
            bouts,
            ticks,
            control,
        })
    }

    /// How many bouts.
    fn __len__(&self) -> usize {
        self.bouts.len()
    }

    /// Ticks in one control step.
    #[getter]
    fn ticks(&self) -> usize {
        self.ticks
    }

    /// Simulation time of each bout, s.
    fn times<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let t: Vec<f64> = self.bouts.iter().map(|b| b.sim.time()).collect();
        t.into_pyarray(py)
    }

    /// Start bout `i` again with `seed`.
    fn reset(&mut self, i: usize, seed: u64) -> PyResult<()> {
        let n = self.bouts.len();
        let bout = self
            .bouts
            .get_mut(i)
            .ok_or_else(|| PyValueError::new_err(format!("i: 0-{} (bouts), got {i}", n - 1)))?;
        *bout = Bout::new(&self.model, &self.timeline, seed, self.control);
        Ok(())
    }

    /// Bout `i`'s blows so far, both ways (as `Sim.tally`).
    fn tally<'py>(&self, py: Python<'py>, i: usize) -> PyResult<Bound<'py, pyo3::types::PyDict>> {
        let b = self
            .bouts
            .get(i)
            .ok_or_else(|| PyValueError::new_err(format!("i: no bout {i}")))?;
        crate::tally_dict(py, &b.sim.tally())
    }

    /// Both agents' observations, `(opponent (n, 30), vh (n, 37))` float32.
    fn observe<'py>(
        &self,
        py: Python<'py>,
    ) -> (Bound<'py, PyArray2<f32>>, Bound<'py, PyArray2<f32>>) {
        self.observations(py)
    }

    /// One control step of every bout in parallel: the opponent's actions
    /// `(n, 9)` in [-1, 1] (head, left glove, right glove: x, y, z), the
    /// VH agent's `(n, 2)` integers `[command, look]` (ignored when the VH
    /// decides for itself; None: nothing new). Bouts whose `hold` is true
    /// stay as they are (a vector environment's bouts just reset). Returns
    /// `(opponent_obs, vh_obs, landed, taken)`: hits the opponent landed
    /// and took this step.
    #[pyo3(signature = (opponent, vh = None, hold = None))]
    #[allow(clippy::type_complexity)]
    fn step<'py>(
        &mut self,
        py: Python<'py>,
        opponent: PyReadonlyArray2<'py, f64>,
        vh: Option<PyReadonlyArray2<'py, i64>>,
        hold: Option<Vec<bool>>,
    ) -> PyResult<(
        Bound<'py, PyArray2<f32>>,
        Bound<'py, PyArray2<f32>>,
        Bound<'py, PyArray1<u32>>,
        Bound<'py, PyArray1<u32>>,
    )> {
        let n = self.bouts.len();
        let opp = opponent.as_array();
        if opp.shape() != [n, 9] {
            return Err(PyValueError::new_err(format!(
                "opponent: shape ({n}, 9), got {:?}",
                opp.shape()
            )));
        }
        let opp: Vec<[f64; 9]> = opp
            .rows()
            .into_iter()
            .map(|r| std::array::from_fn(|k| r[k]))
            .collect();
        let vh: Option<Vec<[i64; 2]>> = match vh {
            None => None,
            Some(a) => {
                let a = a.as_array();
                if a.shape() != [n, 2] {
                    return Err(PyValueError::new_err(format!(
                        "vh: shape ({n}, 2), got {:?}",
                        a.shape()
                    )));
                }
                Some(a.rows().into_iter().map(|r| [r[0], r[1]]).collect())
            }
        };
        let hold = hold.unwrap_or_else(|| vec![false; n]);
        if hold.len() != n {
            return Err(PyValueError::new_err(format!(
                "hold: {n} flags, got {}",
                hold.len()
            )));
        }
        let (ticks, dt) = (self.ticks, self.ticks as f64 * self.model.dt);
        let bouts = &mut self.bouts;
        let outcomes: Vec<Outcome> = py.detach(|| {
            let go = |(i, b): (usize, &mut Bout)| {
                if hold[i] {
                    Outcome::default()
                } else {
                    b.step(&opp[i], vh.as_ref().map(|v| v[i]), ticks, dt)
                }
            };
            // A thread per bout pays off only past one bout.
            if bouts.len() == 1 {
                bouts.iter_mut().enumerate().map(go).collect()
            } else {
                bouts.par_iter_mut().enumerate().map(go).collect()
            }
        });
        let (o, v) = self.observations(py);
        let landed: Vec<u32> = outcomes.iter().map(|o| o.landed).collect();
        let taken: Vec<u32> = outcomes.iter().map(|o| o.taken).collect();
        Ok((o, v, landed.into_pyarray(py), taken.into_pyarray(py)))
    }
}
