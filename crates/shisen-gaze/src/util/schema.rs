//! The input files' types as JSON Schema, and every value checked against
//! it once a file is read.
//!
//! A field's range is written once, on the field
//! (`#[schemars(range(min = 0.0, max = 1.0))]`, unit and source in its doc
//! comment). The schema made from the types carries it to the generated
//! reference (`docs/scene-format.md`, `shisen schema`) and to editors; the
//! loader checks every value read against the same schema, so the
//! documentation and the check cannot disagree. Errors name the file,
//! line and column of the field ([`super::locate`]).

use std::collections::HashMap;
use std::path::Path;
use std::sync::{Arc, LazyLock, Mutex};

use schemars::JsonSchema;
use serde::Serialize;
use serde_json::Value;

use super::load_error::LoadError;
use super::locate::{Locations, dotted, segments};

/// The JSON Schema (draft 2020-12) of `T`: doc comments as descriptions,
/// ranges as `minimum`/`maximum`, defaults, `additionalProperties: false`
/// where unknown fields are refused.
pub fn schema_of<T: JsonSchema>() -> Value {
    serde_json::to_value(schemars::schema_for!(T)).expect("a schema is JSON")
}

type Cache = Mutex<HashMap<&'static str, Arc<jsonschema::Validator>>>;
static VALIDATORS: LazyLock<Cache> = LazyLock::new(Default::default);

fn validator<T: JsonSchema>() -> Arc<jsonschema::Validator> {
    let name = std::any::type_name::<T>();
    let mut cache = VALIDATORS.lock().unwrap_or_else(|e| e.into_inner());
    cache
        .entry(name)
        .or_insert_with(|| {
            Arc::new(
                jsonschema::draft202012::new(&schema_of::<T>())
                    .expect("the types' schema is a valid JSON Schema"),
            )
        })
        .clone()
}

/// One value outside what its type's schema allows.
#[derive(Clone, Debug, PartialEq)]
pub struct Violation {
    /// Dotted path of the field (`vh.neck.kp`, `timeline[2].do.Punch.speed`).
    pub field: String,
    /// What is wrong, for a person.
    pub message: String,
}

/// Every value in `value` that its type's schema refuses, innermost
/// first; empty if all are in range.
pub fn violations<T: Serialize + JsonSchema>(value: &T) -> Vec<Violation> {
    let instance = match serde_json::to_value(value) {
        Ok(v) => v,
        Err(e) => {
            return vec![Violation {
                field: "-".into(),
                message: e.to_string(),
            }];
        }
    };
    let v = validator::<T>();
    let mut out = Vec::new();
    for e in v.iter_errors(&instance) {
        collect(&e, &mut out);
    }
    out
}

/// Check `value`, read from `text` in `file`, against its type's schema;
/// the first violation becomes a [`LoadError`] at the field's place.
pub fn check<T: Serialize + JsonSchema>(
    value: &T,
    text: &str,
    file: &Path,
) -> Result<(), LoadError> {
    let places = Locations::scan(text);
    let invalid = |at, field: String, message: String| LoadError::invalid(file, at, field, message);
    // Serialised for the check, NaN and the infinities become `null`,
    // which an optional number allows: refused where they are written.
    if let Some((field, line, col)) = places.non_finite() {
        return Err(invalid(
            (line, col),
            field,
            "must be a finite number".into(),
        ));
    }
    match violations(value).into_iter().next() {
        None => Ok(()),
        Some(v) => Err(invalid(places.find(&v.field), v.field, v.message)),
    }
}

/// A number as a person writes it (`86400`, `0.5`, `1e300`, `1e-6`),
/// for messages and the reference.
pub fn num(v: &Value) -> String {
    if v.is_u64() || v.is_i64() {
        return v.to_string();
    }
    match v.as_f64() {
        Some(x) if x.fract() == 0.0 && x.abs() < 1e15 => format!("{x:.0}"),
        Some(x) if x != 0.0 && (x.abs() < 1e-4 || x.abs() >= 1e15) => format!("{x:e}"),
        Some(x) => format!("{x}"),
        None => v.to_string(),
    }
}

fn collect(e: &jsonschema::ValidationError, out: &mut Vec<Violation>) {
    use jsonschema::error::ValidationErrorKind as K;
    let field = dotted(
        segments(e.instance_path().as_str())
            .iter()
            .map(String::as_str),
    );
    let message = match e.kind() {
        // An enum's variants (and an optional value's `null`) are
        // alternatives: report the errors of the one that names this
        // variant, i.e. whose errors are all inside the value.
        K::OneOfNotValid { context } | K::AnyOf { context } => {
            let here = e.instance_path().as_str();
            // A branch of another form fails on the value's kind, tag or
            // fields here; the one of the value's form fails deeper, or
            // on a nested choice (an optional enum) here.
            let other_form = |x: &jsonschema::ValidationError| {
                x.instance_path().as_str() == here
                    && !matches!(x.kind(), K::OneOfNotValid { .. } | K::AnyOf { .. })
            };
            if let Some(branch) = context
                .iter()
                .find(|b| !b.is_empty() && !b.iter().any(other_form))
            {
                for x in branch {
                    collect(x, out);
                }
                return;
            }
            "is none of the allowed forms".to_string()
        }
        K::Minimum { limit } => format!("must be >= {}, got {}", num(limit), num(e.instance())),
        K::Maximum { limit } => format!("must be <= {}, got {}", num(limit), num(e.instance())),
        K::ExclusiveMinimum { limit } => {
            format!("must be > {}, got {}", num(limit), num(e.instance()))
        }
        K::ExclusiveMaximum { limit } => {
            format!("must be < {}, got {}", num(limit), num(e.instance()))
        }
        // serde_json writes NaN and the infinities as `null`.
        K::Type { .. } if e.instance().is_null() => "must be a finite number".to_string(),
        K::MinItems { limit } => format!("needs at least {limit} entries"),
        K::MaxItems { limit } => format!("takes at most {limit} entries"),
        K::MinLength { limit } => format!("needs at least {limit} characters"),
        K::MaxLength { limit } => format!("takes at most {limit} characters"),
        _ => e.to_string(),
    };
    out.push(Violation { field, message });
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde::Deserialize;

    /// A test input.
    #[derive(JsonSchema, Serialize, Deserialize)]
    #[serde(deny_unknown_fields)]
    struct Input {
        /// A latency, s.
        #[schemars(range(min = 0.0, max = 1.0))]
        latency: f64,
        /// Actions.
        actions: Vec<Act>,
        /// Optional gain.
        #[schemars(range(min = 0.0, max = 10.0))]
        gain: Option<f64>,
    }

    /// An action.
    #[derive(JsonSchema, Serialize, Deserialize)]
    #[serde(deny_unknown_fields)]
    enum Act {
        /// Punch.
        Punch {
            /// Speed, m/s.
            #[schemars(range(min = 0.0, max = 15.0))]
            speed: f64,
        },
        /// Nothing.
        Idle,
    }

    const TEXT: &str = "(\n  latency: 0.2,\n  actions: [Idle, Punch(speed: 99.0)],\n  gain: 3,\n)";

    #[test]
    fn a_value_out_of_range_inside_a_variant_is_named_and_placed() {
        let v = Input {
            latency: 0.2,
            actions: vec![Act::Idle, Act::Punch { speed: 99.0 }],
            gain: Some(3.0),
        };
        let err = check(&v, TEXT, Path::new("x.ron")).unwrap_err().to_string();
        assert_eq!(
            err,
            "x.ron:3:25: actions[1].Punch.speed: must be <= 15, got 99"
        );
    }

    #[test]
    fn nan_optional_and_top_level_values_are_checked() {
        let v = Input {
            latency: f64::NAN,
            actions: vec![],
            gain: Some(11.0),
        };
        let got = violations(&v);
        assert_eq!(got.len(), 2, "{got:?}");
        assert_eq!(got[0].field, "gain");
        assert_eq!(got[1].field, "latency");
        assert_eq!(got[1].message, "must be a finite number");
        let ok = Input {
            latency: 1.0,
            actions: vec![],
            gain: None,
        };
        assert!(violations(&ok).is_empty());
    }

    /// Optional enums nest one choice in another.
    #[derive(JsonSchema, Serialize, Deserialize)]
    #[serde(deny_unknown_fields)]
    struct WithSeeds {
        /// Seeds.
        seeds: Option<Seeds>,
    }

    /// Seeds.
    #[derive(JsonSchema, Serialize, Deserialize)]
    #[serde(deny_unknown_fields)]
    enum Seeds {
        /// A list.
        List(Vec<u64>),
        /// A range.
        Range {
            /// Last seed.
            #[schemars(range(min = 0, max = 1000))]
            to: u64,
        },
    }

    #[test]
    fn a_value_inside_an_optional_enum_is_named() {
        let v = WithSeeds {
            seeds: Some(Seeds::Range { to: 5000 }),
        };
        let got = violations(&v);
        assert_eq!(got.len(), 1, "{got:?}");
        assert_eq!(got[0].field, "seeds.Range.to");
        assert_eq!(got[0].message, "must be <= 1000, got 5000");
    }
}
