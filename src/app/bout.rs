//! What the window keeps of a bout beyond the simulation: the log behind
//! the round report (where the VH looked, what it did, the blows, the
//! bells), and replays of the bout from its recorded input with a time
//! scrubber.

use shisen::scene::LoadedScene;
use shisen::sim::blows::Blow;
use shisen::sim::bout::Bell;
use shisen::sim::timeline::Event;
use shisen::sim::{DT, Sample, Sim};
use shisen_gaze::behaviour::ActionKind;

/// What the VH's gaze was on, as the report groups targets.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Look {
    /// Your face (head).
    Face,
    /// Your gloves.
    Gloves,
    /// Your body.
    Body,
    /// Anything else (a prop, a point).
    Elsewhere,
}

impl Look {
    /// Every group, in the report's order.
    pub const ALL: [Look; 4] = [Look::Face, Look::Gloves, Look::Body, Look::Elsewhere];

    /// The group of a gaze target's name.
    pub fn of(target: &str) -> Look {
        match target {
            "head" => Look::Face,
            "left_glove" | "right_glove" => Look::Gloves,
            "opponent_body" => Look::Body,
            _ => Look::Elsewhere,
        }
    }

    /// Label.
    pub fn name(self) -> &'static str {
        match self {
            Look::Face => "face",
            Look::Gloves => "gloves",
            Look::Body => "body",
            Look::Elsewhere => "elsewhere",
        }
    }
}

/// A stretch of time with one value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Span<T> {
    /// Start, s.
    pub from: f64,
    /// End, s (the latest sample's time while it lasts).
    pub to: f64,
    /// The value.
    pub what: T,
}

/// Run-length spans of a value sampled each tick.
#[derive(Clone, Debug)]
pub struct Spans<T>(pub Vec<Span<T>>);

impl<T> Default for Spans<T> {
    fn default() -> Self {
        Spans(Vec::new())
    }
}

impl<T: PartialEq + Copy> Spans<T> {
    fn push(&mut self, t: f64, what: T) {
        match self.0.last_mut() {
            Some(s) if s.what == what => s.to = t,
            _ => self.0.push(Span {
                from: t - DT,
                to: t,
                what,
            }),
        }
    }

    /// The spans overlapping `[from, to]`, clipped to it.
    pub fn within(&self, from: f64, to: f64) -> impl Iterator<Item = Span<T>> + '_ {
        self.0
            .iter()
            .filter(move |s| s.to > from && s.from < to)
            .map(move |s| Span {
                from: s.from.max(from),
                to: s.to.min(to),
                what: s.what,
            })
    }

    /// Total time each value held within `[from, to]`.
    pub fn share(&self, from: f64, to: f64, what: T) -> f64 {
        self.within(from, to)
            .filter(|s| s.what == what)
            .map(|s| s.to - s.from)
            .sum()
    }
}

/// The log of a bout, for the round report.
#[derive(Clone, Debug, Default)]
pub struct BoutLog {
    /// Where the VH looked.
    pub looks: Spans<Look>,
    /// What it did.
    pub actions: Spans<ActionKind>,
    /// Blows, both ways, with their times.
    pub blows: Vec<(f64, Blow)>,
    /// Bells rung.
    pub bells: Vec<(f64, Bell)>,
    /// The VH's fatigue every second (time, fatigue).
    pub fatigue: Vec<(f64, f64)>,
}

impl BoutLog {
    /// Note a tick.
    pub fn push(&mut self, s: &Sample) {
        self.looks.push(s.t, Look::of(&s.gaze_target));
        self.actions.push(s.t, s.action);
        self.blows.extend(s.blows.iter().map(|b| (s.t, b.clone())));
        if let Some(b) = s.bell {
            self.bells.push((s.t, b));
        }
        let tick = (s.t / DT).round() as u64;
        if tick.is_multiple_of(1000) {
            self.fatigue.push((s.t, s.fatigue));
        }
    }
}

/// Ticks a replay steps at most per frame while seeking (about 60 ms of
/// CPU at the simulation's usual speed): the window stays responsive.
const SEEK_BUDGET: u64 = 5000;

/// A replay of the bout from its start: the scene as it started and the
/// input recorded since, re-simulated (the simulation is deterministic, so
/// the replay is the bout tick for tick). Seeking back starts again from
/// the beginning; seeking forward steps on, a budget of ticks a frame.
pub struct Replay {
    loaded: LoadedScene,
    events: Vec<Event>,
    /// The replayed simulation.
    pub sim: Sim,
    /// Where the scrubber wants the replay, s.
    pub target: f64,
    /// Playing at real speed (else held at `target`).
    pub playing: bool,
    /// The length of what was recorded, s.
    pub length: f64,
    /// Whether the bout was paused before the replay (it is again after).
    pub bout_paused: bool,
}

impl Replay {
    /// A replay of `events` on `loaded`, `length` seconds long, of a bout
    /// that was paused (`bout_paused`) or running.
    pub fn new(bout_paused: bool, loaded: LoadedScene, events: Vec<Event>, length: f64) -> Replay {
        let sim = Self::start(&loaded, &events);
        Replay {
            loaded,
            events,
            sim,
            target: 0.0,
            playing: true,
            length,
            bout_paused,
        }
    }

    fn start(loaded: &LoadedScene, events: &[Event]) -> Sim {
        let mut sim = loaded.sim();
        for e in events {
            sim.push_event(e.clone());
        }
        sim
    }

    /// Move toward the scrubber's time; `wall_dt` advances it while playing.
    pub fn advance(&mut self, wall_dt: f64) {
        if self.playing {
            self.target = (self.target + wall_dt).min(self.length);
        }
        self.target = self.target.clamp(0.0, self.length);
        if self.target + 0.5 * DT < self.sim.time() {
            self.sim = Self::start(&self.loaded, &self.events);
        }
        let mut n = 0;
        while self.sim.time() + 0.5 * DT < self.target && n < SEEK_BUDGET {
            self.sim.step();
            n += 1;
        }
    }

    /// Whether the replay is still catching up with the scrubber.
    pub fn seeking(&self) -> bool {
        self.target - self.sim.time() > 0.05
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spans_merge_and_clip() {
        let mut s = Spans::default();
        for i in 1..=10 {
            s.push(
                i as f64 * DT,
                if i <= 4 { Look::Face } else { Look::Gloves },
            );
        }
        assert_eq!(s.0.len(), 2);
        assert!((s.share(0.0, 1.0, Look::Face) - 0.004).abs() < 1e-9);
        assert!((s.share(0.0, 0.007, Look::Gloves) - 0.003).abs() < 1e-9);
        assert_eq!(Look::of("right_glove"), Look::Gloves);
        assert_eq!(Look::of("opponent_body"), Look::Body);
    }

    #[test]
    fn a_replay_is_the_run_tick_for_tick_and_seeks_back() {
        let loaded = LoadedScene::default_scene();
        let mut live = loaded.sim();
        for _ in 0..300 {
            live.step();
        }
        let mut r = Replay::new(false, loaded, Vec::new(), 0.3);
        r.playing = false;
        r.target = 0.3;
        r.advance(0.0);
        assert_eq!(r.sim.time(), live.time());
        assert_eq!(r.sim.last().map(|s| s.head), live.last().map(|s| s.head));
        r.target = 0.1;
        r.advance(0.0);
        assert!(
            (r.sim.time() - 0.1).abs() < 1e-9,
            "sought back to {}",
            r.sim.time()
        );
    }
}
