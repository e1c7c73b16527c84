//! Checks of a scene that need more than one field: references between
//! its parts (bodies named by the timeline), ordered windows, the law
//! parameters' cross-field constraints. Errors name the file, line and field.

use std::path::Path;

use super::format::Scene;
use crate::sim::expect::Expect;
use crate::sim::timeline::{Action, Part};
use crate::util::ron::{LoadError, line_of};

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
    let mut names: Vec<&str> = vec!["head", "left_glove", "right_glove"];
    for (i, b) in scene.bodies.iter().enumerate() {
        if names.contains(&b.name.as_str()) || b.name.starts_with("vh_") || b.name == "point" {
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
                    format!("no body named `{body}` (opponent parts or `bodies`)"),
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
            return Err(err(
                &format!("\"{name}\""),
                format!("timeline[{i}].do.part"),
                format!("no kinematic body named `{name}` in `bodies`"),
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
    for (i, x) in scene.expect.iter().enumerate() {
        let window = match x {
            Expect::GazeShare { from, to, .. }
            | Expect::GazeShareAtMost { from, to, .. }
            | Expect::GazeReaches { from, to, .. }
            | Expect::LineOfSight { from, to, .. }
            | Expect::AngleReaches { from, to, .. }
            | Expect::ActionShare { from, to, .. } => Some((*from, *to)),
            Expect::AngleBelow { from, to, .. } => {
                Some((from.unwrap_or(0.0), to.unwrap_or(scene.duration)))
            }
            Expect::Finite | Expect::Telegraph { .. } => None,
        };
        if let Some((from, to)) = window
            && (to < from || to > scene.duration + 1e-9)
        {
            return Err(err(
                "expect",
                format!("expect[{i}]"),
                format!(
                    "window [{from}, {to}] must be ordered and inside the run (0, {})",
                    scene.duration
                ),
            ));
        }
    }
    Ok(())
}
