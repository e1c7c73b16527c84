//! Reading every input file kind must never panic, hang or accept a value
//! outside its documented range, whatever the bytes: scenes, gains,
//! muscle databases, landmark files, studies and emotion scripts; every
//! failure is a `LoadError` naming a place in the text. A scene that
//! parses is also checked against every run length an override could ask
//! for (the cross-reference checks of `--duration`), and what any kind
//! accepts is inside its schema.
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let file = Path::new("fuzz.ron");
    match shisen::scene::Scene::parse(text, file) {
        Err(e) => {
            let _ = e.to_string();
        }
        Ok(scene) => {
            for d in [0.0, 1e-4, 0.5, scene.duration, 1e6, f64::NAN] {
                let _ = shisen::scene::validate::check_duration(&scene, d, false);
            }
            // A valid scene writes back to text that reads to the same scene.
            let again = shisen::scene::Scene::parse(&scene.to_ron(), file);
            assert_eq!(again.ok().as_ref(), Some(&scene));
        }
    }
    if let Ok(g) = shisen::util::ron::parse_ron::<shisen::physics::control::Gains>(text, file) {
        assert!(shisen::util::schema::violations(&g).is_empty());
    }
    let _ = shisen::face::params::FaceParams::parse(text, file);
    let _ = shisen::face::script::parse_script(text, file);
    let _ = shisen::face::import::LandmarkFile::parse(text, file);
    let _ = shisen::util::ron::parse_ron::<shisen::tools::study::Study>(text, file);
    // Placing an error never panics, whatever the path asked for.
    let places = shisen::util::locate::Locations::scan(text);
    let _ = places.find("vh.personality.a2");
    let _ = places.find("/timeline/0/do/Punch/speed");
    let _ = places.non_finite();
});
