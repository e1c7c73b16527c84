//! Headless runs: a scene stepped to its end, traced and judged.

use std::io::Write;

use crate::scene::LoadedScene;
use crate::sim::expect::{Checker, Verdict};
use crate::sim::{DT, Sim};
use crate::tools::trace::TraceWriter;

/// The outcome of a headless run.
#[derive(Clone, Debug)]
pub struct Report {
    /// One verdict per expectation, in file order.
    pub verdicts: Vec<Verdict>,
    /// Ticks simulated.
    pub ticks: u64,
    /// Simulated time, s.
    pub sim_time: f64,
    /// Physics explosions recovered from (VH resets).
    pub resets: u32,
    /// Saccades the VH made.
    pub saccades: u32,
    /// Head movements it started.
    pub head_moves: u32,
    /// The run was stopped before its end (the verdicts judge what ran).
    pub interrupted: bool,
}

impl Report {
    /// True if every expectation holds.
    pub fn passed(&self) -> bool {
        self.verdicts.iter().all(|v| v.pass)
    }
}

/// Run `scene` for `duration` seconds (the scene's own if `None`), writing
/// every `every`-th sample to `trace` if given.
pub fn run(
    scene: &LoadedScene,
    duration: Option<f64>,
    trace: Option<&mut dyn Write>,
    every: u64,
) -> std::io::Result<Report> {
    run_watched(scene, duration, trace, every, &mut |_| true, None)
}

/// Called with the simulation after every tick of a run (a soundtrack
/// listening, say); an error stops the run.
pub type EachTick<'a> = &'a mut dyn FnMut(&Sim) -> std::io::Result<()>;

/// [`run`], calling `keep_going(t)` every simulated second; it returns
/// false to stop the run there (Ctrl-C), with the trace written so far
/// intact and the report marked interrupted. Every run also stops there
/// once [`super::request_stop`] was called. `each` sees every tick.
pub fn run_watched(
    scene: &LoadedScene,
    duration: Option<f64>,
    trace: Option<&mut dyn Write>,
    every: u64,
    keep_going: &mut dyn FnMut(f64) -> bool,
    mut each: Option<EachTick>,
) -> std::io::Result<Report> {
    let duration = duration.unwrap_or(scene.scene.duration);
    let mut sim = scene.sim();
    let mut checker = Checker::new(&scene.scene.expect, duration);
    let mut writer = match trace {
        Some(w) => Some(TraceWriter::new(w, every)?),
        None => None,
    };
    let planned = (duration / DT).round() as u64;
    let (mut ticks, mut interrupted) = (planned, false);
    for k in 0..planned {
        if k % 1000 == 0 && k > 0 && (super::stop_requested() || !keep_going(sim.time())) {
            (ticks, interrupted) = (k, true);
            break;
        }
        let s = sim.step();
        checker.push(s);
        if let Some(w) = writer.as_mut() {
            w.push(s)?;
        }
        if let Some(f) = each.as_mut() {
            f(&sim)?;
        }
    }
    if let Some(w) = writer {
        w.finish()?;
    }
    Ok(Report {
        verdicts: checker.verdicts(),
        ticks,
        sim_time: ticks as f64 * DT,
        resets: sim.resets,
        saccades: sim.oculomotor.saccades,
        head_moves: sim.oculomotor.head_moves,
        interrupted,
    })
}
