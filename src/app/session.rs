//! The state of a sparring session, independent of the window: the
//! simulation, the clock that steps it in simulation time, your avatar's
//! control, hits, the optional recording and trace. The window drives it
//! once per frame; tests drive it with synthetic input.

use std::collections::VecDeque;
use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};

use crate::input::{Intent, OpponentControl};
use shisen::scene::LoadedScene;
use shisen::sim::blows::Blow;
use shisen::sim::timeline::Event;
use shisen::sim::{DT, Sample, Sim};
use shisen::sound::{RATE, Soundtrack};
use shisen::tools::trace::TraceWriter;

use super::bout::{BoutLog, Replay};
use super::record::Recorder;
use shisen::scene::opponent::Opponent;
use shisen::sim::bout::BoutParams;

/// At most this much simulation time is stepped per frame, s; a slow frame
/// makes the simulation fall behind wall time instead of stalling the UI.
pub const MAX_STEP_PER_FRAME: f64 = 0.1;
/// Slow-motion factor.
pub const SLOW_MOTION: f64 = 0.1;
/// Samples kept for the live plots (every 10th tick), s.
const HISTORY_S: f64 = 4.0;
const HISTORY_EVERY: u64 = 10;

/// Where a scene came from: its text (for recordings) and folder (for its
/// gains file).
#[derive(Clone, Debug)]
pub struct SceneSource {
    /// The scene file's text.
    pub text: String,
    /// Its path, `None` for the embedded default.
    pub path: Option<PathBuf>,
}

impl SceneSource {
    /// The embedded default scene.
    pub fn default_scene() -> Self {
        SceneSource {
            text: shisen::scene::DEFAULT_SCENE_RON.to_string(),
            path: None,
        }
    }

    /// Read and validate a scene file.
    pub fn load(path: &Path) -> anyhow::Result<(SceneSource, LoadedScene)> {
        let loaded = LoadedScene::load(path)?;
        let text = shisen::util::ron::read_text(path)?;
        Ok((
            SceneSource {
                text,
                path: Some(path.to_path_buf()),
            },
            loaded,
        ))
    }
}

/// Pause and slow motion.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Clock {
    /// Not stepping.
    pub paused: bool,
    /// Running at [`SLOW_MOTION`].
    pub slow: bool,
    /// Simulation time owed to wall time, s.
    debt: f64,
}

impl Clock {
    /// Ticks to step for `wall_dt` seconds of wall time.
    pub fn ticks(&mut self, wall_dt: f64) -> u64 {
        if self.paused {
            self.debt = 0.0;
            return 0;
        }
        let scale = if self.slow { SLOW_MOTION } else { 1.0 };
        self.debt = (self.debt + wall_dt.max(0.0) * scale).min(MAX_STEP_PER_FRAME);
        let n = (self.debt / DT + 1e-9).floor();
        self.debt -= n * DT;
        n as u64
    }
}

/// The last blow (hit or block, either way) and when it came.
#[derive(Clone, Debug, PartialEq)]
pub struct LastBlow {
    /// Simulation time, s.
    pub t: f64,
    /// The blow.
    pub blow: Blow,
}

/// A running session.
pub struct Session {
    /// The simulation.
    pub sim: Sim,
    /// The scene as loaded (restart starts it again).
    pub loaded: LoadedScene,
    /// Its text and path.
    pub source: SceneSource,
    /// Your avatar.
    pub control: OpponentControl,
    /// Pause / slow motion.
    pub clock: Clock,
    /// Hit counts.
    pub last_blow: Option<LastBlow>,
    /// Recent samples for the plots (every 10th tick).
    pub history: VecDeque<Sample>,
    /// Recording in progress.
    pub recorder: Option<Recorder>,
    /// The opponent the VH plays (kept across restarts, which carry its
    /// parameters over as the VH's own), for labels.
    pub opponent: Option<Opponent>,
    /// The bout so far, for the round report.
    pub log: BoutLog,
    /// Your input since the start, for replays.
    pub events: Vec<Event>,
    /// A replay being watched (the live bout is paused meanwhile).
    pub replay: Option<Replay>,
    trace: Option<(PathBuf, TraceWriter<BufWriter<File>>)>,
    /// The bout's soundtrack, heard from your head.
    pub sound: Soundtrack,
    /// Samples heard and not yet played (at most a second is kept).
    pub heard: Vec<[f32; 2]>,
}

impl Session {
    /// A session on `loaded` (from `source`), at time 0.
    pub fn new(loaded: LoadedScene, source: SceneSource) -> Self {
        let sim = loaded.sim();
        let loaded_opponent = loaded.scene.vh.opponent;
        let loaded_seed = loaded.scene.seed;
        Session {
            control: OpponentControl::new(&sim.world.plan),
            sim,
            loaded,
            source,
            clock: Clock::default(),
            last_blow: None,
            history: VecDeque::new(),
            recorder: None,
            opponent: loaded_opponent,
            log: BoutLog::default(),
            events: Vec::new(),
            replay: None,
            trace: None,
            sound: Soundtrack::new(loaded_seed),
            heard: Vec::new(),
        }
    }

    /// Start again against `opponent` (`None`: the scene's own VH) in a
    /// bout of `bout` (`None`: no rounds), keeping the gains.
    pub fn restart_with(&mut self, opponent: Option<Opponent>, bout: Option<BoutParams>) {
        self.loaded.scene.vh.opponent = opponent;
        self.loaded.scene.bout = bout;
        self.reset(false);
        self.opponent = opponent;
    }

    /// Watch the bout so far from its start (pausing it), or stop
    /// watching.
    pub fn toggle_replay(&mut self) {
        if let Some(r) = self.replay.take() {
            self.clock.paused = r.bout_paused;
            return;
        }
        let bout_paused = self.clock.paused;
        self.clock.paused = true;
        self.replay = Some(Replay::new(
            bout_paused,
            self.loaded.clone(),
            self.events.clone(),
            self.sim.time(),
        ));
    }

    /// Start the scene again, keeping the tuning (gains, personality,
    /// behaviour) in force.
    pub fn restart(&mut self) {
        self.reset(true);
    }

    /// Start the scene again with the gains in force and, unless
    /// `keep_vh`, the VH's parameters as the scene file has them.
    fn reset(&mut self, keep_vh: bool) {
        let mut loaded = self.loaded.clone();
        loaded.gains = self.sim.params().gains.clone();
        if keep_vh {
            loaded.scene.vh.set_params(self.sim.params());
        }
        let reach = self.control.reach;
        let clock = self.clock;
        let opponent = self.opponent;
        *self = Session {
            trace: self.trace.take(),
            ..Session::new(loaded, self.source.clone())
        };
        self.control.reach = reach;
        self.clock = clock;
        self.opponent = opponent;
    }

    /// Replace the scene (the old one stays if this fails).
    pub fn open(&mut self, path: &Path) -> anyhow::Result<()> {
        let (source, loaded) = SceneSource::load(path)?;
        *self = Session {
            trace: self.trace.take(),
            ..Session::new(loaded, source)
        };
        Ok(())
    }

    /// Push an event into the simulation now (and into the recording).
    pub fn push(&mut self, mut ev: Event) {
        ev.at = self.sim.time();
        tracing::debug!(at = ev.at, action = ?ev.action, "input event");
        if let Some(r) = &mut self.recorder {
            r.push(&ev);
        }
        self.events.push(ev.clone());
        self.sim.push_event(ev);
    }

    /// Apply your intent at the current simulation time.
    pub fn apply(&mut self, intent: &Intent) {
        for ev in self.control.update(self.sim.time(), intent) {
            self.push(ev);
        }
    }

    /// Step one tick.
    pub fn step(&mut self) {
        let s = self.sim.step();
        let sample = s.clone();
        self.sound.hear(&self.sim, &mut self.heard);
        let over = self.heard.len().saturating_sub(RATE as usize);
        self.heard.drain(..over);
        self.log.push(&sample);
        if let Some(b) = sample.blows.last() {
            self.last_blow = Some(LastBlow {
                t: sample.t,
                blow: b.clone(),
            });
        }
        if let Some((path, tw)) = &mut self.trace
            && let Err(e) = tw.push(&sample)
        {
            tracing::warn!(path = %path.display(), error = %e, "trace write failed; trace stopped");
            self.trace = None;
        }
        let tick = (sample.t / DT).round() as u64;
        if tick.is_multiple_of(HISTORY_EVERY) {
            self.history.push_back(sample);
            while self
                .history
                .front()
                .is_some_and(|f| self.sim.time() - f.t > HISTORY_S)
            {
                self.history.pop_front();
            }
        }
    }

    /// Advance by `wall_dt` seconds of wall time through the clock;
    /// returns the ticks stepped.
    pub fn advance(&mut self, wall_dt: f64) -> u64 {
        let n = self.clock.ticks(wall_dt);
        for _ in 0..n {
            self.step();
        }
        n
    }

    /// Start recording: restarts the scene so the recording replays from 0.
    /// The recording inlines the gains in force; the VH's other parameters
    /// go back to the scene file's (the file keeps its `vh` as written).
    pub fn start_recording(&mut self) {
        self.reset(false);
        self.recorder = Some(Recorder::new(
            &self.loaded.scene,
            self.loaded.scene.seed,
            self.sim.params().gains.clone(),
        ));
    }

    /// Stop recording and return the scene text of the bout.
    pub fn stop_recording(&mut self) -> anyhow::Result<Option<String>> {
        let Some(r) = self.recorder.take() else {
            return Ok(None);
        };
        Ok(Some(r.scene_text(self.sim.time().max(DT))))
    }

    /// Start writing the trace (CSV) to `path`.
    pub fn start_trace(&mut self, path: &Path) -> anyhow::Result<()> {
        let w = TraceWriter::new(BufWriter::new(File::create(path)?), 1)?;
        self.trace = Some((path.to_path_buf(), w));
        Ok(())
    }

    /// Stop the trace, flushing it.
    pub fn stop_trace(&mut self) -> anyhow::Result<Option<PathBuf>> {
        match self.trace.take() {
            Some((p, w)) => {
                use std::io::Write;
                w.finish()?.flush()?;
                Ok(Some(p))
            }
            None => Ok(None),
        }
    }

    /// Path of the trace being written.
    pub fn trace_path(&self) -> Option<&Path> {
        self.trace.as_ref().map(|(p, _)| p.as_path())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clock_steps_wall_time_capped_and_scaled() {
        let mut c = Clock::default();
        assert_eq!(c.ticks(0.0165), 16);
        assert_eq!(c.ticks(0.0005), 1, "carries the remainder");
        assert_eq!(c.ticks(1.0), 100, "capped");
        c.slow = true;
        assert_eq!(c.ticks(0.1), 10);
        c.paused = true;
        assert_eq!(c.ticks(0.1), 0);
    }
}
