//! # shisen-gaze: the virtual human's gaze, alone
//!
//! The bottom two layers of shisen, with no physics engine and no graphics:
//! helpers ([`util`]: math, value checks, RON loading; [`anatomy`]: the
//! human measurements the body, the laws and the face share) and the VH's
//! brain, one stage per module, in pipeline order:
//! [`vision`] (what is in view, bottom-up saliency M1) -> [`behaviour`]
//! (guard / attack / idle and its top-down request) -> [`attention`]
//! (which target wins) -> [`oculomotor`] (saccades M2-M6,
//! pursuit/vergence/VOR M7, head M8-M9). [`personality`] holds the amounts
//! the stages share.
//!
//! No stage knows the physics engine or the scene format: vision reads the
//! world through [`vision::Scenery`], and the oculomotor's outputs are
//! joint-space commands ([`oculomotor::AxisCommand`]). The gaze controller
//! (attention + oculomotor) runs on its own; see `examples/gaze_without_physics.rs`.

pub mod anatomy;
pub mod attention;
pub mod behaviour;
pub mod oculomotor;
pub mod personality;
pub mod target;
pub mod util;
pub mod vision;

#[cfg(test)]
mod tests {
    use crate::util::ron::parse_ron;
    use crate::util::schema::violations;
    use std::path::Path;

    /// Every default, preset and seed value lies inside the range its field
    /// documents (the loader would refuse them otherwise).
    #[test]
    fn defaults_are_inside_their_documented_ranges() {
        use crate::oculomotor::timing::TimingParams;
        let mut o = crate::oculomotor::OculomotorParams::default();
        assert_eq!(violations(&o), vec![]);
        o.timing = TimingParams::seed();
        o.otolith = crate::oculomotor::otolith::OtolithParams::seed();
        assert_eq!(violations(&o), vec![]);
        let b = crate::behaviour::BehaviourParams {
            circle_after: Some(3.0),
            guard_speed: 1000.0,
            ..Default::default()
        };
        assert_eq!(violations(&b), vec![]);
        assert_eq!(
            violations(&crate::personality::Personality::default()),
            vec![]
        );
        assert_eq!(violations(&crate::vision::VisionParams::default()), vec![]);
        assert_eq!(
            violations(&crate::attention::AttentionParams::default()),
            vec![]
        );
        for p in [
            crate::oculomotor::takagi::Preset::Dialogue,
            crate::oculomotor::takagi::Preset::WindUp,
            crate::oculomotor::takagi::Preset::Eerie,
        ] {
            let s = p.build(glam::DVec2::new(40.0, -20.0));
            assert_eq!(violations(&s), vec![]);
        }
    }

    /// Ranges on optional numbers apply to the number; `None` passes.
    #[test]
    fn out_of_range_values_are_refused_where_written() {
        let t = Path::new("t.ron");
        type B = crate::behaviour::BehaviourParams;
        assert!(parse_ron::<B>("(circle_after: None)", t).is_ok());
        assert!(parse_ron::<B>("(circle_after: Some(3.0))", t).is_ok());
        let e = parse_ron::<B>("(\n  circle_after: Some(0.0),\n)", t).unwrap_err();
        let e = e.to_string();
        assert!(
            e.starts_with("t.ron:2:") && e.contains("circle_after: must be > 0"),
            "{e}"
        );
        let e = parse_ron::<B>("(attack_rate: 1e300)", t)
            .unwrap_err()
            .to_string();
        assert!(e.contains("attack_rate: must be <= 10"), "{e}");
        type O = crate::oculomotor::OculomotorParams;
        let e = parse_ron::<O>("(head: (limits: (yaw: 0.0)))", t)
            .unwrap_err()
            .to_string();
        assert!(e.contains("head.limits.yaw: must be > 0"), "{e}");
        let e = parse_ron::<O>(
            "(timing: (saccade_latency: (median: 5.0, rate_sd: 1.0)))",
            t,
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("timing.saccade_latency.median: must be <= 1"),
            "{e}"
        );
    }

    /// Walks a schema: every field and variant has a description, every
    /// number a lower and an upper bound. Returns what lacks one.
    fn undocumented(v: &serde_json::Value, at: &str, out: &mut Vec<String>) {
        use serde_json::Value;
        let Value::Object(m) = v else {
            if let Value::Array(a) = v {
                for (i, x) in a.iter().enumerate() {
                    undocumented(x, &format!("{at}[{i}]"), out);
                }
            }
            return;
        };
        let is_number = |t: &Value| match t {
            Value::String(s) => s == "number" || s == "integer",
            Value::Array(a) => a.iter().any(|x| x == "number" || x == "integer"),
            _ => false,
        };
        if m.get("type").is_some_and(is_number)
            && !(m.contains_key("maximum")
                && (m.contains_key("minimum") || m.contains_key("exclusiveMinimum")))
        {
            out.push(format!("{at}: a number without both bounds"));
        }
        // An enum's newtype variant `{ Name: value }` carries its
        // description on the variant, not on the one property.
        let newtype_variant = m.contains_key("description")
            && m.get("properties")
                .and_then(Value::as_object)
                .is_some_and(|p| p.len() == 1);
        if let Some(Value::Object(props)) = m.get("properties")
            && !newtype_variant
        {
            for (k, p) in props {
                if p.get("description")
                    .and_then(Value::as_str)
                    .is_none_or(str::is_empty)
                {
                    out.push(format!("{at}.{k}: no description"));
                }
            }
        }
        for key in ["oneOf", "anyOf"] {
            if let Some(Value::Array(alts)) = m.get(key) {
                for (i, a) in alts.iter().enumerate() {
                    let null = a.get("type").is_some_and(|t| t == "null");
                    if !null && a.get("description").is_none() && a.get("$ref").is_none() {
                        out.push(format!("{at}.{key}[{i}]: a variant without a description"));
                    }
                }
            }
        }
        for (k, x) in m {
            undocumented(x, &format!("{at}/{k}"), out);
        }
    }

    /// The reference documents every field, variant and range.
    #[test]
    fn every_field_is_documented_and_every_number_bounded() {
        use crate::util::schema::schema_of;
        let mut out = Vec::new();
        for (name, s) in [
            (
                "personality",
                schema_of::<crate::personality::Personality>(),
            ),
            (
                "behaviour",
                schema_of::<crate::behaviour::BehaviourParams>(),
            ),
            ("vision", schema_of::<crate::vision::VisionParams>()),
            (
                "attention",
                schema_of::<crate::attention::AttentionParams>(),
            ),
            (
                "oculomotor",
                schema_of::<crate::oculomotor::OculomotorParams>(),
            ),
            (
                "gaze shift",
                schema_of::<crate::oculomotor::takagi::GazeShift>(),
            ),
            ("action", schema_of::<crate::behaviour::ActionKind>()),
            ("evasion", schema_of::<crate::behaviour::Evasion>()),
        ] {
            undocumented(&s, name, &mut out);
        }
        assert!(out.is_empty(), "{out:#?}");
    }
}
