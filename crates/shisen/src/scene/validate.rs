//! Checks of a scene that need more than one field: references between
//! its parts (bodies named by the timeline), ordered windows, the law
//! parameters' cross-field constraints. Errors name the file, line and field.

use std::path::Path;

use super::format::Scene;
use crate::physics::body::BodyPlan;
use crate::physics::body::OpponentPart;
use crate::physics::plausible::check_gains;
use crate::sim::DT;
use crate::sim::expect::Expect;
use crate::sim::timeline::{Action, Part};
use shisen_gaze::util::ron::{LoadError, line_of};

/// Cross-field checks that need the whole scene.
pub(super) fn validate(scene: &Scene, text: &str, file: &Path) -> Result<(), LoadError> {
    let err = |needle: &str, field: String, message: String| {
        let (line, col) = line_of(text, needle);
        LoadError::Invalid {
            file: file.display().to_string(),
            line,
            col,
            field,
            message,
        }
    };
    if scene.gains.is_some() && scene.gains_file.is_some() {
        return Err(err(
            "gains_file",
            "gains_file".into(),
            "give either `gains` or `gains_file`, not both".into(),
        ));
    }
    if let Some(g) = &scene.gains
        && let Err(m) = check_gains(g)
    {
        return Err(err("gains", format!("gains.{}", m.field), m.message));
    }
    if let Err(m) = check_duration(scene, scene.duration, true) {
        return Err(err(m.needle, m.field, m.message));
    }
    let p = &scene.vh.personality;
    if p.a2 <= p.a1 {
        return Err(err(
            "a2",
            "vh.personality.a2".into(),
            format!("must exceed a1 ({}), got {}", p.a1, p.a2),
        ));
    }
    if let Err(m) = scene.vh.oculomotor.pursuit.validate() {
        return Err(err("pursuit", "vh.oculomotor.pursuit".into(), m));
    }
    if let Err(m) = scene.vh.neck.validate() {
        return Err(err("neck", "vh.neck".into(), m));
    }
    let mut names: Vec<&str> = OpponentPart::ALL.map(OpponentPart::name).to_vec();
    for (i, b) in scene.bodies.iter().enumerate() {
        // `point` and `opponent_body` name gaze targets that are no body
        // (a fixed point, the opponent's trunk).
        if names.contains(&b.name.as_str())
            || b.name.starts_with("vh_")
            || ["point", "opponent_body"].contains(&b.name.as_str())
        {
            return Err(err(
                &format!("\"{}\"", b.name),
                format!("bodies[{i}].name"),
                format!("name `{}` is taken or reserved", b.name),
            ));
        }
        names.push(&b.name);
    }
    for (i, e) in scene.timeline.iter().enumerate() {
        let part = match &e.action {
            Action::Move { part, .. } | Action::Wave { part, .. } | Action::Orbit { part, .. } => {
                Some(part)
            }
            _ => None,
        };
        if let Action::Track { body, until } = &e.action {
            if !names.contains(&body.as_str()) {
                return Err(err(
                    &format!("\"{body}\""),
                    format!("timeline[{i}].do.Track.body"),
                    format!(
                        "no body named `{body}` (opponent parts or `bodies`){}",
                        suggest(body, &names)
                    ),
                ));
            }
            if *until < e.at {
                return Err(err(
                    "until",
                    format!("timeline[{i}].do.Track.until"),
                    format!("must not precede `at` ({}), got {until}", e.at),
                ));
            }
        }
        if let Some(Part::Body(name)) = part
            && !scene.bodies.iter().any(|b| &b.name == name && b.kinematic)
        {
            let kinematic: Vec<&str> = scene
                .bodies
                .iter()
                .filter(|b| b.kinematic)
                .map(|b| b.name.as_str())
                .collect();
            return Err(err(
                &format!("\"{name}\""),
                format!("timeline[{i}].do.part"),
                format!(
                    "no kinematic body named `{name}` in `bodies`{}",
                    suggest(name, &kinematic)
                ),
            ));
        }
        if let Action::LookAt { until, .. } = e.action
            && until < e.at
        {
            return Err(err(
                "until",
                format!("timeline[{i}].do.LookAt.until"),
                format!("must not precede `at` ({}), got {until}", e.at),
            ));
        }
    }
    // Gaze targets an expectation names: the bodies, a fixed point, or
    // (when the VH sees itself) its own segments.
    let plan = BodyPlan::default();
    let mut targets = names.clone();
    targets.push("point");
    targets.extend(plan.segments.iter().map(|g| g.name));
    for (i, x) in scene.expect.iter().enumerate() {
        if let Expect::GazeShare { target, .. }
        | Expect::GazeShareAtMost { target, .. }
        | Expect::GazeReaches { target, .. } = x
            && !targets.contains(&target.as_str())
        {
            return Err(err(
                &format!("\"{target}\""),
                format!("expect[{i}].target"),
                format!(
                    "no gaze target named `{target}` (bodies, `point`, the VH's segments){}",
                    suggest(target, &targets)
                ),
            ));
        }
    }
    // Counts that bound nothing could never fail.
    for (i, x) in scene.expect.iter().enumerate() {
        let vacuous = match x {
            Expect::Blows {
                at_least, at_most, ..
            } => {
                if at_most.is_some_and(|m| m < *at_least) {
                    return Err(err(
                        "at_most",
                        format!("expect[{i}].at_most"),
                        format!("must be at least at_least ({at_least})"),
                    ));
                }
                *at_least == 0 && at_most.is_none()
            }
            Expect::Blinks { at_least, .. } => *at_least == 0,
            Expect::Fatigue {
                at_least, at_most, ..
            } => {
                if at_most < at_least {
                    return Err(err(
                        "Fatigue(",
                        format!("expect[{i}].at_most"),
                        format!("must be at least at_least ({at_least})"),
                    ));
                }
                // Fatigue is 0-1: [0, 1] bounds nothing.
                if *at_least == 0.0 && *at_most >= 1.0 {
                    return Err(err(
                        "Fatigue(",
                        format!("expect[{i}].at_most"),
                        "must be under 1, or at_least over 0: fatigue is 0-1, so as written \
                         it cannot fail"
                            .into(),
                    ));
                }
                false
            }
            _ => false,
        };
        if vacuous {
            let needle = if matches!(x, Expect::Blows { .. }) {
                "Blows("
            } else {
                "Blinks("
            };
            return Err(err(
                needle,
                format!("expect[{i}].at_least"),
                "must be at least 1 (or, for Blows, give at_most): as written it cannot fail"
                    .into(),
            ));
        }
    }
    Ok(())
}

/// Longest run a scene may ask for, s of simulated time (a day; anything
/// longer is a typo, not a bout).
pub const MAX_DURATION: f64 = 86_400.0;

/// What is wrong with a run length, and where.
pub struct DurationError {
    /// Text to find the line by.
    pub needle: &'static str,
    /// The field.
    pub field: String,
    /// What is wrong.
    pub message: String,
}

/// Whether `duration` (the scene's, or an override) is a sensible length
/// for the scene: at least one tick, at most [`MAX_DURATION`], every
/// expectation window inside it, and (with `events`, for the file's own
/// duration) every timeline event too. An override may cut the timeline
/// short, but not a window it is judged by.
pub fn check_duration(scene: &Scene, duration: f64, events: bool) -> Result<(), DurationError> {
    let bad = |needle, field: String, message| {
        Err(DurationError {
            needle,
            field,
            message,
        })
    };
    if !duration.is_finite() || duration < DT {
        return bad(
            "duration",
            "duration".into(),
            format!("must be at least one step ({DT} s), got {duration}"),
        );
    }
    if duration > MAX_DURATION {
        return bad(
            "duration",
            "duration".into(),
            format!("must be at most {MAX_DURATION} s (a day), got {duration}"),
        );
    }
    for (i, e) in scene.timeline.iter().enumerate() {
        if events && e.at > duration {
            return bad(
                "at",
                format!("timeline[{i}].at"),
                format!("{} s is after the end of the run ({duration} s)", e.at),
            );
        }
    }
    for (i, x) in scene.expect.iter().enumerate() {
        let window = x.window(duration);
        if let Some((from, to)) = window
            && (to < from || to > duration + 1e-9)
        {
            return bad(
                "expect",
                format!("expect[{i}]"),
                format!("window [{from}, {to}] must be ordered and inside the run (0, {duration})"),
            );
        }
    }
    Ok(())
}

/// ", did you mean `x`?" for the candidate nearest `name` (edit distance
/// at most a third of its length), or "" if none is near.
fn suggest(name: &str, candidates: &[&str]) -> String {
    let best = candidates
        .iter()
        .map(|c| (edit_distance(name, c), *c))
        .min();
    match best {
        Some((d, c)) if d > 0 && d <= (name.len().max(3)) / 3 + 1 => {
            format!(", did you mean `{c}`?")
        }
        _ => String::new(),
    }
}

/// Levenshtein distance between two strings (by characters).
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut prev = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let cur = row[j + 1];
            row[j + 1] = (prev + usize::from(ca != cb)).min(row[j] + 1).min(cur + 1);
            prev = cur;
        }
    }
    row[b.len()]
}
