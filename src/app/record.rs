//! Recording a sparring session as a scene file: the scene it started
//! from, with the seed and gains inlined, the duration of the bout, and
//! your input appended to its timeline as the `Move` / `Punch` / `Emotion`
//! events the live session pushed into the simulation. Running the file
//! headless (`shisen run rec.ron --headless`) replays the bout tick for tick.
//!
//! Scene types only deserialise, so the file is written by editing the
//! original scene text: its top-level fields are kept verbatim except the
//! ones the recording sets. No scene-format change was needed.

use crate::control::Gains;
use crate::scene::{Action, Event, PunchTarget};

/// Errors of recording.
#[derive(Debug, thiserror::Error)]
pub enum RecordError {
    /// The base scene text has no `Scene(...)` struct the splicer understands.
    #[error("cannot edit the scene text: {0}")]
    SceneText(String),
    /// An event kind live input never produces.
    #[error("event at {0} s cannot be recorded (only Move, Punch at a point, Emotion)")]
    Unrecordable(f64),
}

/// A session being recorded (from the scene's start).
#[derive(Clone, Debug)]
pub struct Recorder {
    base: String,
    seed: u64,
    gains: Gains,
    events: Vec<Event>,
}

impl Recorder {
    /// Start recording a run of the scene `base_text` with `seed` and `gains`.
    pub fn new(base_text: &str, seed: u64, gains: Gains) -> Self {
        Recorder {
            base: base_text.to_string(),
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

    /// The scene file text of the session, `duration` seconds long.
    pub fn scene_text(&self, duration: f64) -> Result<String, RecordError> {
        let fields = top_level_fields(&self.base)?;
        let mut out = String::from(
            "// Recorded sparring session (shisen). Replays the bout exactly:\n\
             //   shisen run THIS_FILE --headless --trace trace.csv\n\
             Scene(\n",
        );
        let mut timeline = String::new();
        let mut name = "session".to_string();
        for (key, value) in &fields {
            match key.as_str() {
                "timeline" => {
                    let inner = value.trim();
                    let inner = inner
                        .strip_prefix('[')
                        .and_then(|v| v.strip_suffix(']'))
                        .ok_or_else(|| RecordError::SceneText("timeline is not a list".into()))?
                        .trim()
                        .trim_end_matches(',');
                    if !inner.is_empty() {
                        timeline.push_str("        ");
                        timeline.push_str(inner);
                        timeline.push_str(",\n");
                    }
                }
                "name" => name = value.trim().trim_matches('"').to_string(),
                "seed" | "gains" | "gains_file" | "duration" | "expect" | "description" => {}
                _ => out.push_str(&format!("    {key}: {},\n", value.trim())),
            }
        }
        let gains = ron::ser::to_string(&self.gains).expect("gains serialise");
        out.push_str(&format!("    name: {:?},\n", format!("{name}_recorded")));
        out.push_str(&format!(
            "    description: \"A sparring session recorded from {name}.\",\n"
        ));
        out.push_str(&format!("    seed: {},\n", self.seed));
        out.push_str(&format!("    duration: {:?},\n", duration));
        out.push_str(&format!("    gains: Gains{gains},\n"));
        out.push_str("    timeline: [\n");
        out.push_str(&timeline);
        for ev in &self.events {
            out.push_str("        ");
            out.push_str(&event_ron(ev)?);
            out.push_str(",\n");
        }
        out.push_str("    ],\n    expect: [Finite],\n)\n");
        Ok(out)
    }
}

fn vec3(v: glam::DVec3) -> String {
    format!("({:?}, {:?}, {:?})", v.x, v.y, v.z)
}

/// One timeline entry as RON (floats in shortest round-trip form, so they
/// read back bit for bit).
fn event_ron(ev: &Event) -> Result<String, RecordError> {
    let action = match &ev.action {
        Action::Move { part, to, duration } => format!(
            "Move(part: {part:?}, to: {}, duration: {duration:?})",
            vec3(*to)
        ),
        Action::Punch {
            hand,
            target: PunchTarget::Point(p),
            speed,
        } => format!(
            "Punch(hand: {hand:?}, target: Point({}), speed: {speed:?})",
            vec3(*p)
        ),
        Action::Emotion {
            emotion,
            intensity,
            speed,
            pattern,
        } => format!(
            "Emotion(emotion: {emotion:?}, intensity: {intensity:?}, speed: {speed:?}, pattern: {pattern:?})"
        ),
        _ => return Err(RecordError::Unrecordable(ev.at)),
    };
    Ok(format!("(at: {:?}, do: {action})", ev.at))
}

/// The `(name, value text)` pairs of the top-level struct `Scene(...)` in
/// RON text (comments dropped, values verbatim).
fn top_level_fields(text: &str) -> Result<Vec<(String, String)>, RecordError> {
    let bad = |m: &str| RecordError::SceneText(m.to_string());
    let clean = strip_comments(text);
    let open = clean
        .find("Scene(")
        .map(|i| i + "Scene(".len())
        .or_else(|| {
            // An anonymous struct: the first '(' that is not part of `#![...]`.
            let body = clean.trim_start();
            body.starts_with('(').then(|| clean.len() - body.len() + 1)
        });
    let open = open.ok_or_else(|| bad("no Scene( ... )"))?;
    let bytes: Vec<char> = clean[open..].chars().collect();
    let mut fields = Vec::new();
    let (mut depth, mut start, mut in_str, mut esc) = (0i32, 0usize, false, false);
    for (i, &c) in bytes.iter().enumerate() {
        if in_str {
            match (esc, c) {
                (true, _) => esc = false,
                (false, '\\') => esc = true,
                (false, '"') => in_str = false,
                _ => {}
            }
            continue;
        }
        match c {
            '"' => in_str = true,
            '(' | '[' | '{' => depth += 1,
            ')' | ']' | '}' if depth > 0 => depth -= 1,
            ')' | ',' if depth == 0 => {
                let field: String = bytes[start..i].iter().collect();
                if let Some((k, v)) = field.split_once(':') {
                    fields.push((k.trim().to_string(), v.trim().to_string()));
                } else if !field.trim().is_empty() {
                    return Err(bad("a field without a name"));
                }
                start = i + 1;
                if c == ')' {
                    return Ok(fields);
                }
            }
            _ => {}
        }
    }
    Err(bad("unbalanced brackets"))
}

/// The text with `//` and `/* */` comments blanked (strings kept).
fn strip_comments(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut chars = text.chars().peekable();
    let (mut in_str, mut esc) = (false, false);
    while let Some(c) = chars.next() {
        if in_str {
            out.push(c);
            match (esc, c) {
                (true, _) => esc = false,
                (false, '\\') => esc = true,
                (false, '"') => in_str = false,
                _ => {}
            }
            continue;
        }
        match (c, chars.peek()) {
            ('"', _) => {
                in_str = true;
                out.push(c);
            }
            ('/', Some('/')) => {
                for c in chars.by_ref() {
                    if c == '\n' {
                        out.push('\n');
                        break;
                    }
                }
            }
            ('/', Some('*')) => {
                chars.next();
                let mut prev = ' ';
                for c in chars.by_ref() {
                    if prev == '*' && c == '/' {
                        break;
                    }
                    prev = c;
                }
                out.push(' ');
            }
            _ => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Hand, LoadedScene, Part};
    use glam::DVec3;
    use std::path::Path;

    #[test]
    fn recorded_scene_parses_with_the_events_appended() {
        let base = crate::scene::DEFAULT_SCENE_RON;
        let mut r = Recorder::new(base, 42, Gains::default());
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
            },
        });
        let text = r.scene_text(2.5).unwrap();
        let loaded = LoadedScene::from_str(&text, Path::new("rec.ron"), None).unwrap();
        let s = &loaded.scene;
        assert_eq!(s.seed, 42);
        assert_eq!(s.duration, 2.5);
        let original = LoadedScene::default_scene().scene.timeline.len();
        assert_eq!(s.timeline.len(), original + 2);
        let last = &s.timeline[original];
        assert_eq!(last.at, 0.123);
        match &last.action {
            Action::Move { to, .. } => assert_eq!(to.z, 1.0 / 3.0, "bit-exact floats"),
            other => panic!("{other:?}"),
        }
        assert_eq!(loaded.gains, Gains::default());
    }

    #[test]
    fn fields_survive_comments_and_strings() {
        let f = top_level_fields(
            "// c\nScene(\n name: \"a, b\", /* x) */ vh: (p: (a: 1)), timeline: [(at: 1.0)],\n)",
        )
        .unwrap();
        let keys: Vec<_> = f.iter().map(|(k, _)| k.as_str()).collect();
        assert_eq!(keys, ["name", "vh", "timeline"]);
        assert_eq!(f[0].1, "\"a, b\"");
    }
}
