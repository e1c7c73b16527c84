//! Recording a sparring session as a scene file: the scene it started
//! from, with the seed and gains inlined, the duration of the bout, and
//! your input appended to its timeline as the events the live session
//! pushed into the simulation. Running the file headless
//! (`shisen run rec.ron --headless`) replays the bout tick for tick.
//!
//! The file is written through serde ([`Scene::to_ron`]); floats are
//! written in shortest round-trip form, so they read back bit for bit.

use shisen::physics::control::Gains;
use shisen::scene::Scene;
use shisen::sim::expect::Expect;
use shisen::sim::timeline::Event;

/// A session being recorded (from the scene's start).
#[derive(Clone, Debug)]
pub struct Recorder {
    base: Scene,
    seed: u64,
    gains: Gains,
    events: Vec<Event>,
}

impl Recorder {
    /// Start recording a run of the scene `base` with `seed` and `gains`.
    pub fn new(base: &Scene, seed: u64, gains: Gains) -> Self {
        Recorder {
            base: base.clone(),
            seed,
            gains,
            events: Vec::new(),
        }
    }

    /// Note an event pushed into the simulation.
    pub fn push(&mut self, ev: &Event) {
        self.events.push(ev.clone());
    }

    /// Number of events recorded.
    pub fn len(&self) -> usize {
        self.events.len()
    }

    /// True if nothing has been recorded yet.
    pub fn is_empty(&self) -> bool {
        self.events.is_empty()
    }

    /// The scene of the session, `duration` seconds long.
    pub fn scene(&self, duration: f64) -> Scene {
        let mut s = self.base.clone();
        s.description = format!("A sparring session recorded from {}.", s.name);
        s.name = format!("{}_recorded", s.name);
        s.seed = self.seed;
        s.duration = duration;
        s.gains = Some(self.gains.clone());
        s.gains_file = None;
        // The scene's own events after the bout ended never happened.
        s.timeline.retain(|e| e.at <= duration);
        s.timeline.extend(self.events.iter().cloned());
        s.expect = vec![Expect::Finite];
        s
    }

    /// The scene file text of the session, `duration` seconds long.
    pub fn scene_text(&self, duration: f64) -> String {
        format!(
            "// Recorded sparring session (shisen). Replays the bout exactly:\n\
             //   shisen run THIS_FILE --headless --trace trace.csv\n{}",
            self.scene(duration).to_ron()
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;
    use shisen::scene::LoadedScene;
    use shisen::sim::timeline::{Action, Hand, Part, PunchTarget};
    use std::path::Path;

    #[test]
    fn recorded_scene_parses_with_the_events_appended() {
        let base = LoadedScene::default_scene().scene;
        let mut r = Recorder::new(&base, 42, Gains::default());
        r.push(&Event {
            at: 0.123,
            action: Action::Move {
                part: Part::LeftGlove,
                to: DVec3::new(0.1, 1.5, 1.0 / 3.0),
                duration: 0.08,
            },
        });
        r.push(&Event {
            at: 0.5,
            action: Action::Punch {
                hand: Hand::Right,
                target: PunchTarget::Point(DVec3::new(0.13, 1.55, 0.16)),
                speed: 6.0,
                through: None,
                glove_only: false,
            },
        });
        let text = r.scene_text(2.5);
        let loaded = LoadedScene::from_str(&text, Path::new("rec.ron"), None).unwrap();
        let s = &loaded.scene;
        assert_eq!(s.seed, 42);
        assert_eq!(s.duration, 2.5);
        let original = (LoadedScene::default_scene().scene.timeline.iter())
            .filter(|e| e.at <= 2.5)
            .count();
        assert_eq!(s.timeline.len(), original + 2);
        let last = &s.timeline[original];
        assert_eq!(last.at, 0.123);
        match &last.action {
            Action::Move { to, .. } => assert_eq!(to.z, 1.0 / 3.0, "bit-exact floats"),
            other => panic!("{other:?}"),
        }
        assert_eq!(loaded.gains, Gains::default());
    }
}
