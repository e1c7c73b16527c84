//! `shisen fidelity`'s battery: with the human defaults every row lies in
//! its human band; with the seed's timing the reaction time and the fast
//! pursuit gain do not (the seed reacts at once and pursues with gain 1).

use shisen::scene::LoadedScene;
use shisen::sim::Profile;
use shisen::tools::fidelity::{Row, battery, model_of};

fn row<'a>(rows: &'a [Row], name: &str) -> &'a Row {
    rows.iter()
        .find(|r| r.name.starts_with(name))
        .unwrap_or_else(|| panic!("no row {name}"))
}

#[test]
fn human_defaults_pass_every_row_and_the_seed_timing_does_not() {
    let scene = LoadedScene::default_scene();
    let (human, seed) = (
        model_of(&scene, None),
        model_of(&scene, Some(Profile::Seed)),
    );
    // The two batteries side by side: most of each runs on one core.
    let ((human, _), (seed, _)) = std::thread::scope(|s| {
        let seed = s.spawn(|| battery(&seed));
        (
            battery(&human),
            seed.join().expect("the seed's battery ran"),
        )
    });
    print!("{}", shisen::tools::fidelity::table(&human));
    let failed: Vec<_> = human.iter().filter(|r| !r.pass()).collect();
    assert!(failed.is_empty(), "{failed:?}");
    assert!(!row(&seed, "saccadic reaction time").pass());
    assert!(row(&seed, "saccadic reaction time").value < 100.0);
    assert!(!row(&seed, "pursuit gain, 60").pass());
    assert!(row(&seed, "pursuit gain, 60").value > 0.95);
}
