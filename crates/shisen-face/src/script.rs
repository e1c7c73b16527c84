//! Emotion scripts in the thesis's plain format (face.md 9, thesis 4.2.1).
//!
//! One step per line: `emotion duration_seconds speed`, e.g.
//!
//! ```text
//! # the mountain witch, scene 1
//! neutral   30 1
//! worry      3 1
//! 決断       5 1
//! ```
//!
//! * `emotion`: a table A emotion, by its English name in any case with or
//!   without underscores (`hidden_anger`, `HiddenAnger`) or by the thesis's
//!   Japanese name (`喜び`, `疑問と驚き`). A name may contain spaces (the
//!   last two fields are the numbers), which are ignored.
//! * `duration_seconds`: how long the step lasts, > 0: the change to the
//!   emotion starts at the step's start and the next step starts
//!   `duration_seconds` later (the transition is part of the step).
//! * `speed`: 1 fast, 2 typical, 3 slow (tables 5.9 / 5.10 bounds).
//!
//! `#` starts a comment anywhere on a line; blank lines are allowed. Steps
//! play in order from time 0 (or a chosen start, [`to_events`]).

use std::path::Path;

use super::tables::Emotion;
use super::timing::Speed;
use shisen_gaze::util::ron::LoadError;

/// Longest step of a script, s: a day, the longest run a scene may have.
pub const MAX_STEP_S: f64 = 86_400.0;

/// One timed emotion change of a script.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScriptStep {
    /// Start of the step, seconds from the start of the script.
    pub at: f64,
    /// Target emotion.
    pub emotion: Emotion,
    /// Onset / offset speed.
    pub speed: Speed,
    /// How long the step lasts (until the next step starts), seconds.
    pub hold: f64,
}

/// The thesis's Japanese emotion names (table A; face.md) for the emotions
/// that have one. The compound surprise + fear rows have none in the
/// thesis; `驚きと恐怖` (surprise and fear, as its story script writes it)
/// maps to the fear-stronger row.
const JAPANESE: [(&str, Emotion); 34] = [
    ("中立", Emotion::Neutral),
    ("驚き", Emotion::Surprise),
    ("疑問", Emotion::Questioning),
    ("興味", Emotion::Interest),
    ("惚け", Emotion::Dazed),
    ("疑問と驚き", Emotion::QuestioningSurprise),
    ("仰天", Emotion::Astonishment),
    ("麻痺", Emotion::Stunned),
    ("恐怖", Emotion::Fear),
    ("心配", Emotion::Worry),
    ("抑制された恐怖", Emotion::RestrainedFear),
    ("驚きと恐怖", Emotion::SurpriseFearFearStronger),
    ("怯え", Emotion::Frightened),
    ("嫌悪", Emotion::Disgust),
    ("軽蔑", Emotion::Contempt),
    ("不信", Emotion::Disbelief),
    ("怒り", Emotion::Anger),
    ("抑制された怒り", Emotion::RestrainedAnger),
    ("怒りと嫌悪", Emotion::AngerDisgust),
    ("厭きれる", Emotion::Exasperation),
    ("当惑", Emotion::Perplexity),
    ("喜び", Emotion::Happiness),
    ("喜びと驚き", Emotion::HappySurprise),
    ("傲慢", Emotion::Arrogance),
    ("隠された怒り", Emotion::HiddenAnger),
    ("隠された恐怖", Emotion::HiddenFear),
    ("悲しみ", Emotion::Sadness),
    ("弱い悲しみ", Emotion::MildSadness),
    ("抑制された悲しみ", Emotion::RestrainedSadness),
    ("悲しみと恐怖", Emotion::SadnessFear),
    ("悲しみと怒り", Emotion::SadnessAnger),
    ("決断", Emotion::Determination),
    ("悲しみと嫌悪", Emotion::SadnessDisgust),
    ("隠された悲しみ", Emotion::HiddenSadness),
];

/// An emotion by English (see [`Emotion::parse`]) or Japanese name.
pub fn parse_emotion(name: &str) -> Option<Emotion> {
    Emotion::parse(name).or_else(|| JAPANESE.iter().find(|(n, _)| *n == name).map(|(_, e)| *e))
}

/// Parse a script; errors name the file, line, column and field
/// (`emotion`, `duration`, `speed`).
pub fn parse_script(text: &str, file: &Path) -> Result<Vec<ScriptStep>, LoadError> {
    let mut steps = Vec::new();
    let mut at = 0.0;
    for (n, raw) in text.lines().enumerate() {
        let line = raw.split('#').next().unwrap_or("");
        // Fields with their 1-based character columns.
        let mut fields: Vec<(usize, &str)> = Vec::new();
        let mut start = None;
        for (i, (b, c)) in line.char_indices().enumerate() {
            match (c.is_whitespace(), start) {
                (false, None) => start = Some((i, b)),
                (true, Some((col, sb))) => {
                    fields.push((col + 1, &line[sb..b]));
                    start = None;
                }
                _ => {}
            }
        }
        if let Some((col, sb)) = start {
            fields.push((col + 1, &line[sb..]));
        }
        if fields.is_empty() {
            continue;
        }
        let err = |col: usize, field: &str, message: String| {
            LoadError::invalid(file, (n + 1, col), field, message)
        };
        if fields.len() < 3 {
            return Err(err(
                fields[0].0,
                "-",
                format!(
                    "expected `emotion duration_seconds speed`, found {} field(s)",
                    fields.len()
                ),
            ));
        }
        let (speed_f, dur_f) = (fields[fields.len() - 1], fields[fields.len() - 2]);
        let name: String = fields[..fields.len() - 2].iter().map(|f| f.1).collect();
        let emotion = parse_emotion(&name)
            .ok_or_else(|| err(fields[0].0, "emotion", format!("unknown emotion `{name}`")))?;
        let hold: f64 = dur_f
            .1
            .parse()
            .ok()
            .filter(|d: &f64| d.is_finite() && *d > 0.0 && *d <= MAX_STEP_S)
            .ok_or_else(|| {
                err(
                    dur_f.0,
                    "duration",
                    format!(
                        "must be a number of seconds > 0 and at most {MAX_STEP_S} (a day), got `{}`",
                        dur_f.1
                    ),
                )
            })?;
        let speed = speed_f
            .1
            .parse()
            .ok()
            .and_then(Speed::from_number)
            .ok_or_else(|| {
                err(
                    speed_f.0,
                    "speed",
                    format!(
                        "must be 1 (fast), 2 (typical) or 3 (slow), got `{}`",
                        speed_f.1
                    ),
                )
            })?;
        steps.push(ScriptStep {
            at,
            emotion,
            speed,
            hold,
        });
        at += hold;
    }
    Ok(steps)
}

/// Read and parse a script file.
pub fn load_script(path: &Path) -> Result<Vec<ScriptStep>, LoadError> {
    let text = shisen_gaze::util::ron::read_text(path)?;
    parse_script(&text, path)
}

/// The script as timeline events `(at, emotion, speed)`, shifted to start at
/// `start` seconds.
pub fn to_events(steps: &[ScriptStep], start: f64) -> Vec<(f64, Emotion, Speed)> {
    steps
        .iter()
        .map(|s| (start + s.at, s.emotion, s.speed))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_the_thesis_format_with_comments_and_japanese_names() {
        let text = "# story\n\n中立 30 1\nworry 3 1   # she hears a cry\n\
                    疑問と 驚き 2 2\nhidden_anger 1.5 3\n";
        let s = parse_script(text, Path::new("story.txt")).unwrap();
        let got: Vec<_> = s
            .iter()
            .map(|s| (s.at, s.emotion, s.speed, s.hold))
            .collect();
        assert_eq!(
            got,
            vec![
                (0.0, Emotion::Neutral, Speed::Fast, 30.0),
                (30.0, Emotion::Worry, Speed::Fast, 3.0),
                (33.0, Emotion::QuestioningSurprise, Speed::Typical, 2.0),
                (35.0, Emotion::HiddenAnger, Speed::Slow, 1.5),
            ]
        );
        let ev = to_events(&s, 10.0);
        assert_eq!(ev[1], (40.0, Emotion::Worry, Speed::Fast));
        assert_eq!(ev.len(), 4);
        assert_eq!(JAPANESE.len(), 34);
        assert!(JAPANESE.iter().all(|(n, e)| parse_emotion(n) == Some(*e)));
    }

    #[test]
    fn errors_name_file_line_column_and_field() {
        let cases = [
            ("neutral 1 1\nglee 2 1\n", 2, 1, "emotion"),
            ("neutral 1 1\n\n  anger -2 1\n", 3, 9, "duration"),
            ("neutral 1e300 1\n", 1, 9, "duration"),
            ("anger 2 4", 1, 9, "speed"),
            ("anger 2 x", 1, 9, "speed"),
            ("# c\n  anger 2\n", 2, 3, "-"),
        ];
        for (text, line, col, field) in cases {
            let e = parse_script(text, Path::new("s.txt")).unwrap_err();
            match &e {
                LoadError::Invalid {
                    file,
                    line: l,
                    col: c,
                    field: f,
                    ..
                } => {
                    assert_eq!(
                        (file.as_str(), *l, *c, f.as_str()),
                        ("s.txt", line, col, field)
                    );
                }
                other => panic!("{other}"),
            }
            assert!(
                e.to_string()
                    .starts_with(&format!("s.txt:{line}:{col}: {field}: "))
            );
        }
    }
}
