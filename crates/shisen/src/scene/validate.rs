//! Checks of a scene that need more than one field: references between
//! its parts (bodies named by the timeline), ordered windows, the law
//! parameters' cross-field constraints. Errors name the file, line and field.

use std::path::Path;

use super::format::Scene;
use crate::physics::body::BodyPlan;
use crate::physics::body::OpponentPart;
use crate::physics::lower::Pelvis;
use crate::physics::plausible::check_gains;
use crate::sim::DT;
use crate::sim::expect::Expect;
use crate::sim::timeline::{Action, Part};
use shisen_gaze::util::locate::Locations;
use shisen_gaze::util::ron::LoadError;

/// Cross-field checks that need the whole scene.
pub(super) fn validate(scene: &Scene, text: &str, file: &Path) -> Result<(), LoadError> {
    // Errors are placed at the field they name, as the parser's are.
    let places = Locations::scan(text);
    let err = |field: String, message: String| {
        let at = places.find(&field);
        LoadError::invalid(file, at, field, message)
    };
    if scene.gains.is_some() && scene.gains_file.is_some() {
        return Err(err(
            "gains_file".into(),
            "give either `gains` or `gains_file`, not both".into(),
        ));
    }
    if let Some(g) = &scene.gains
        && let Err(m) = check_gains(g)
    {
        return Err(err(format!("gains.{}", m.field), m.message));
    }
    if let Err(m) = check_duration(scene, scene.duration, true) {
        return Err(err(m.field, m.message));
    }
    let p = &scene.vh.personality;
    if p.a2 <= p.a1 {
        return Err(err(
            "vh.personality.a2".into(),
            format!("must exceed a1 ({}), got {}", p.a1, p.a2),
        ));
    }
    if let Err(m) = scene.vh.oculomotor.pursuit.validate() {
        return Err(err("vh.oculomotor.pursuit".into(), m));
    }
    if let Err(m) = scene.vh.oculomotor.otolith.validate() {
        return Err(err("vh.oculomotor.otolith.tvor_visual".into(), m));
    }
    if let Err(m) = scene.vh.neck.validate() {
        return Err(err("vh.neck".into(), m));
    }
    let fix = &scene.vh.oculomotor.fixation;
    if fix.amplitude_max <= fix.amplitude_median {
        return Err(err(
            "vh.oculomotor.fixation.amplitude_max".into(),
            format!(
                "must exceed amplitude_median ({}), got {}: microsaccade amplitudes are drawn below it",
                fix.amplitude_median, fix.amplitude_max
            ),
        ));
    }
    let mut names: Vec<&str> = OpponentPart::EVERY.map(OpponentPart::name).to_vec();
    for (i, b) in scene.bodies.iter().enumerate() {
        // `point` and `opponent_body` name gaze targets that are no body
        // (a fixed point, the opponent's trunk).
        if b.name.trim().is_empty() {
            return Err(err(
                format!("bodies[{i}].name"),
                "must not be empty: traces, expectations and gaze targets name bodies by it".into(),
            ));
        }
        if names.contains(&b.name.as_str())
            || b.name.starts_with("vh_")
            || ["point", "opponent_body"].contains(&b.name.as_str())
        {
            return Err(err(
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
                    format!("timeline[{i}].do.Track.body"),
                    format!(
                        "no body named `{body}` (opponent parts or `bodies`){}",
                        suggest(body, &names)
                    ),
                ));
            }
            if *until < e.at {
                return Err(err(
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
                format!("timeline[{i}].do.part"),
                format!(
                    "no kinematic body named `{name}` in `bodies`{}",
                    suggest(name, &kinematic)
                ),
            ));
        }
        // Motions whose parts are each in range but whose speed is not a
        // person's (or a ring's props'): checked as a whole.
        match e.action {
            Action::TurnHead {
                yaw_deg,
                pitch_deg,
                duration,
                ..
            } => {
                // The turn follows a minimum-jerk profile: its peak rate
                // is 1.875 times the mean.
                let peak = 1.875 * yaw_deg.abs().max(pitch_deg.abs()) / duration;
                if peak > MAX_HEAD_TURN_DEG_S {
                    return Err(err(
                        format!("timeline[{i}].do.TurnHead.duration"),
                        format!(
                            "a {:.0} deg turn in {duration} s peaks at {peak:.0} deg/s; at most {MAX_HEAD_TURN_DEG_S} deg/s (lengthen the turn)",
                            yaw_deg.abs().max(pitch_deg.abs())
                        ),
                    ));
                }
            }
            Action::Wave {
                amplitude,
                frequency,
                ..
            } => {
                let peak = std::f64::consts::TAU * frequency * amplitude.length();
                if peak > MAX_WAVE_SPEED {
                    return Err(err(
                        format!("timeline[{i}].do.Wave.frequency"),
                        format!(
                            "peaks at {peak:.1} m/s (2 pi x frequency x amplitude); at most {MAX_WAVE_SPEED} m/s"
                        ),
                    ));
                }
            }
            _ => {}
        }
        if let Action::LookAt { until, .. } = e.action
            && until < e.at
        {
            return Err(err(
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
                format!("expect[{i}].target"),
                format!(
                    "no gaze target named `{target}` (bodies, `point`, the VH's segments){}",
                    suggest(target, &targets)
                ),
            ));
        }
    }
    // Bounds given the wrong way round could never hold.
    for (i, x) in scene.expect.iter().enumerate() {
        if let Expect::HeadSpeed {
            at_least, at_most, ..
        }
        | Expect::BlowMomentum {
            at_least, at_most, ..
        }
        | Expect::Range {
            at_least, at_most, ..
        } = x
            && at_most < at_least
        {
            return Err(err(
                format!("expect[{i}].at_most"),
                format!("must be at least at_least ({at_least}), got {at_most}"),
            ));
        }
    }
    let [rest, exertion] = scene.vh.effort.breathing;
    if exertion < rest {
        return Err(err(
            "vh.effort.breathing".into(),
            format!("the rate at exertion ({exertion}) must be at least the rate at rest ({rest})"),
        ));
    }
    // Counts that bound nothing could never fail.
    for (i, x) in scene.expect.iter().enumerate() {
        let vacuous = match x {
            Expect::Blows {
                at_least, at_most, ..
            } => {
                if at_most.is_some_and(|m| m < *at_least) {
                    return Err(err(
                        format!("expect[{i}].at_most"),
                        format!("must be at least at_least ({at_least})"),
                    ));
                }
                *at_least == 0 && at_most.is_none()
            }
            Expect::Blinks { at_least, .. } => *at_least == 0,
            Expect::Knockdowns {
                at_least,
                at_most,
                get_ups,
                ..
            } => {
                if at_most.is_some_and(|m| m < *at_least) {
                    return Err(err(
                        format!("expect[{i}].at_most"),
                        format!("must be at least at_least ({at_least})"),
                    ));
                }
                if (*at_least > 0 || *get_ups > 0) && scene.vh.body.pelvis != Pelvis::Balanced {
                    return Err(err(
                        format!("expect[{i}]"),
                        "a knockdown needs a physical body: set vh.body.pelvis: Balanced (a driven \
                         pelvis never falls, so as written it cannot pass)"
                            .into(),
                    ));
                }
                *at_least == 0 && at_most.is_none() && *get_ups == 0
            }
            Expect::Fatigue {
                at_least, at_most, ..
            } => {
                if at_most < at_least {
                    return Err(err(
                        format!("expect[{i}].at_most"),
                        format!("must be at least at_least ({at_least})"),
                    ));
                }
                // Fatigue is 0-1: [0, 1] bounds nothing.
                if *at_least == 0.0 && *at_most >= 1.0 {
                    return Err(err(
                        format!("expect[{i}].at_most"),
                        "must be under 1, or at_least over 0: fatigue is 0-1, so as written \
                         it cannot fail"
                            .into(),
                    ));
                }
                false
            }
            Expect::Evades {
                at_least, at_most, ..
            } => *at_least == 0 && at_most.is_none(),
            Expect::GazeShare { at_least, .. } | Expect::ActionShare { at_least, .. }
                if *at_least <= 0.0 =>
            {
                return Err(err(
                    format!("expect[{i}].at_least"),
                    "must be over 0: every window holds a share of at least 0, so as written \
                     it cannot fail"
                        .into(),
                ));
            }
            Expect::GazeShareAtMost { at_most, .. } if *at_most >= 1.0 => {
                return Err(err(
                    format!("expect[{i}].at_most"),
                    "must be under 1: no share exceeds the whole window, so as written it \
                     cannot fail"
                        .into(),
                ));
            }
            _ => false,
        };
        if vacuous {
            return Err(err(
                format!("expect[{i}].at_least"),
                "must be at least 1 (or, for Blows, Evades and Knockdowns, give at_most): as \
                 written it cannot fail"
                    .into(),
            ));
        }
    }
    overlaps(scene).map_err(|m| err(m.field, m.message))
}

/// Timeline entries that ask one hand for two things at once: two punches
/// at the same moment (which would be thrown is an accident of order). A
/// move of a part while an earlier one still moves it is allowed: it
/// starts from where the part is, which is how live input steers a glove
/// (recorded sessions are full of them).
fn overlaps(scene: &Scene) -> Result<(), FieldError> {
    let mut punches: Vec<(usize, f64, crate::sim::timeline::Hand)> = Vec::new();
    for (i, e) in scene.timeline.iter().enumerate() {
        if let Action::Punch { hand, .. } = &e.action {
            if let Some((j, ..)) = punches
                .iter()
                .find(|(_, at, h)| h == hand && (at - e.at).abs() < DT / 2.0)
            {
                return Err(FieldError {
                    field: format!("timeline[{i}].at"),
                    message: format!(
                        "a second {hand:?} punch at {} s, the moment timeline[{j}] throws one: a hand throws one punch at a time",
                        e.at
                    ),
                });
            }
            punches.push((i, e.at, *hand));
        }
    }
    Ok(())
}

/// Fastest scripted head turn, deg/s: above a jab's snap of the head
/// (9-21 rad/s, 500-1200 deg/s; scenes/jab_snaps_head.ron) and far above
/// clinical head impulses (150-300 deg/s; Halmagyi & Curthoys 1988).
pub const MAX_HEAD_TURN_DEG_S: f64 = 1500.0;

/// Fastest scripted wave, m/s: twice an Olympic boxer's straight punch
/// (9.1 +- 2.1 m/s; Walilko, Viano & Bir 2005).
pub const MAX_WAVE_SPEED: f64 = 20.0;

/// Longest run a scene may ask for, s of simulated time (a day; anything
/// longer is a typo, not a bout).
pub const MAX_DURATION: f64 = 86_400.0;

/// What is wrong with a field (a run length, a timeline entry), and where.
pub struct FieldError {
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
pub fn check_duration(scene: &Scene, duration: f64, events: bool) -> Result<(), FieldError> {
    let bad = |field: String, message| Err(FieldError { field, message });
    if !duration.is_finite() || duration < DT {
        return bad(
            "duration".into(),
            format!("must be at least one step ({DT} s), got {duration}"),
        );
    }
    if duration > MAX_DURATION {
        return bad(
            "duration".into(),
            format!("must be at most {MAX_DURATION} s (a day), got {duration}"),
        );
    }
    for (i, e) in scene.timeline.iter().enumerate() {
        if events && e.at > duration {
            return bad(
                format!("timeline[{i}].at"),
                format!("{} s is after the end of the run ({duration} s)", e.at),
            );
        }
    }
    for (i, x) in scene.expect.iter().enumerate() {
        let window = x.window(duration);
        if let Some((from, to)) = window
            && (to <= from || to > duration + 1e-9)
        {
            let why = if to <= from {
                "is empty: `to` must be after `from` (no tick falls in it)"
            } else {
                "must be inside the run"
            };
            return bad(
                format!("expect[{i}]"),
                format!("window [{from}, {to}] {why} (0, {duration})"),
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
