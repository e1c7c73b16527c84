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
