//! Run a scene with the full simulation (physics, brain, face) and read
//! its samples: where the VH looked, for how long, and how many times it
//! blinked.
//!
//! Run: `cargo run --example run_scene [-- scenes/wave.ron]`
//! (the embedded default scene without an argument).

use std::collections::BTreeMap;

use shisen::LoadedScene;

fn main() -> anyhow::Result<()> {
    let loaded = match std::env::args().nth(1) {
        Some(path) => LoadedScene::load(path.as_ref())?,
        None => LoadedScene::default_scene(),
    };
    let mut sim = loaded.sim();
    let mut looked: BTreeMap<String, f64> = BTreeMap::new();
    let mut blinks = 0;
    let mut was_shut = false;
    while sim.time() < loaded.scene.duration {
        let s = sim.step();
        *looked.entry(s.gaze_target.clone()).or_default() += shisen::DT;
        let shut = s.blink > 0.9;
        blinks += u32::from(shut && !was_shut);
        was_shut = shut;
    }
    println!(
        "{}: {:.1} s simulated, {} saccades, {blinks} blinks",
        loaded.scene.name,
        sim.time(),
        sim.oculomotor.saccades
    );
    for (target, secs) in &looked {
        println!("  looked at {target:12} {secs:6.2} s");
    }
    Ok(())
}
