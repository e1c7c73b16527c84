//! The file-format reference (docs/scene-format.md) is the one the types
//! make, and its examples read back.

use std::path::Path;

const DOC: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/scene-format.md");

#[test]
fn the_reference_in_docs_is_the_one_the_types_make() {
    let want = shisen_app::schema::reference();
    let have = std::fs::read_to_string(DOC).unwrap_or_default();
    if have != want {
        if std::env::var_os("SHISEN_BLESS").is_some() {
            std::fs::write(DOC, &want).unwrap();
            return;
        }
        panic!(
            "docs/scene-format.md is behind the types: run\n  cargo run -- schema --markdown > docs/scene-format.md"
        );
    }
}

#[test]
fn every_action_and_expectation_example_reads_back() {
    use shisen::sim::expect::Expect;
    use shisen::sim::timeline::Event;
    use shisen::util::ron::parse_ron;
    let examples = shisen_app::schema::scene_examples();
    let (mut actions, mut expects) = (0, 0);
    for (ty, variant, text) in &examples {
        let r = match ty.as_str() {
            "Action" => {
                actions += 1;
                parse_ron::<Event>(&format!("(at: 0.0, do: {text})"), Path::new("example"))
                    .map(drop)
            }
            "Expect" => {
                expects += 1;
                parse_ron::<Expect>(text, Path::new("example")).map(drop)
            }
            _ => Ok(()),
        };
        if let Err(e) = r {
            panic!("the reference's example of {ty}::{variant}, `{text}`, is refused: {e}");
        }
    }
    assert!(
        actions >= 10 && expects >= 5,
        "{actions} actions, {expects} expectations"
    );
}

/// Every number of every input file kind has a documented range (both
/// bounds) and every field and variant a description.
#[test]
fn every_number_has_a_range_and_every_field_a_description() {
    use serde_json::Value;
    fn walk(v: &Value, path: &str, out: &mut Vec<String>, numbers: &mut usize) {
        let Value::Object(m) = v else {
            if let Value::Array(a) = v {
                for (i, x) in a.iter().enumerate() {
                    walk(x, &format!("{path}[{i}]"), out, numbers);
                }
            }
            return;
        };
        let types: Vec<&str> = match m.get("type") {
            Some(Value::String(t)) => vec![t.as_str()],
            Some(Value::Array(a)) => a.iter().filter_map(Value::as_str).collect(),
            _ => vec![],
        };
        if types.iter().any(|t| *t == "number" || *t == "integer") {
            *numbers += 1;
            let lo = m.contains_key("minimum") || m.contains_key("exclusiveMinimum");
            let hi = m.contains_key("maximum") || m.contains_key("exclusiveMaximum");
            if !(lo && hi) {
                out.push(format!("{path}: a number without both bounds"));
            }
        }
        if let Some(Value::Object(props)) = m.get("properties") {
            for (name, p) in props {
                // A variant's body is described by its variant.
                let described = p.get("description").is_some()
                    || p.get("$ref").is_some() && m.get("description").is_some()
                    || name.starts_with(|c: char| c.is_ascii_uppercase());
                if !described {
                    out.push(format!("{path}.{name}: no description"));
                }
            }
        }
        for (k, x) in m {
            walk(x, &format!("{path}/{k}"), out, numbers);
        }
    }
    let (mut problems, mut numbers) = (Vec::new(), 0);
    for kind in shisen_app::schema::FileKind::ALL {
        walk(
            &kind.schema(),
            &format!("{kind:?}"),
            &mut problems,
            &mut numbers,
        );
    }
    assert!(
        numbers > 300,
        "only {numbers} numbers found: is the walk reading the schema?"
    );
    assert!(
        problems.is_empty(),
        "{} problems:\n{}",
        problems.len(),
        problems.join("\n")
    );
}
