//! Scene, gains and muscle-database parsing plus validation must never
//! panic, whatever the bytes: every failure is a `LoadError`.
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let file = Path::new("fuzz.ron");
    if let Err(e) = shisen::scene::Scene::parse(text, file) {
        let _ = e.to_string();
    }
    let _ = shisen::util::ron::parse_ron::<shisen::physics::control::Gains>(text, file);
    let _ = shisen::face::params::FaceParams::parse(text, file);
    let _ = shisen::face::script::parse_script(text, file);
});
