//! Ring craft (docs/model/boxing.md "Cues"): a VH that reads the body's
//! cue defends a stepping jab better than one that waits for the glove,
//! and loses that edge when the same jab comes without its cue; feints
//! draw its defence. Run with `--nocapture` for the tables.

use std::path::Path;

use shisen::scene::LoadedScene;

const JABS: usize = 10;

/// A VH of `level` (boxer, attacks off: it holds its long range) facing
/// ten 7 m/s jabs 1.6 s apart from where you stand, thrown by the body
/// (a step in leading the glove) or with the glove alone; or, with
/// `feint`, ten feints instead. Returns (hits, punches blocked, cues or
/// feints it acted on, defensive actions started within 0.5 s of each,
/// fixations: gaze-target changes).
fn bout(level: &str, glove_only: bool, feint: bool) -> (u32, u32, u32, usize, u32) {
    let events: String = (0..JABS)
        .map(|k| {
            let at = 2.0 + 1.6 * k as f64;
            if feint {
                format!("(at: {at}, do: Feint(hand: Left)),")
            } else {
                format!(
                    "(at: {at}, do: Punch(hand: Left, target: Head, speed: 7.0, glove_only: {glove_only})),"
                )
            }
        })
        .collect();
    let text = format!(
        "Scene(name: \"cues\", seed: 9, duration: {}, \
         vh: (opponent: Some((level: {level})), behaviour: (attacks: false)), \
         timeline: [{events}])",
        2.0 + 1.6 * JABS as f64
    );
    let loaded = LoadedScene::from_str(&text, Path::new("<cues>"), None).expect("a valid scene");
    let mut sim = loaded.sim();
    let ticks = (loaded.scene.duration / shisen::sim::DT).round() as usize;
    let mut defended = [false; JABS];
    let (mut fixations, mut on) = (0, String::new());
    for _ in 0..ticks {
        let s = sim.step().clone();
        if s.gaze_target != on {
            fixations += 1;
            on = s.gaze_target.clone();
        }
        let k = ((s.t - 2.0) / 1.6).floor();
        if k >= 0.0 && (s.t - 2.0 - 1.6 * k) < 0.5 && s.action.defends() {
            defended[k as usize] = true;
        }
    }
    let t = sim.tally();
    (
        t.opponent_hits,
        t.opponent_blocked,
        sim.behaviour.cue_reads,
        defended.iter().filter(|&&d| d).count(),
        fixations,
    )
}

#[test]
fn reading_the_body_defends_a_stepping_jab_and_feints_draw_it() {
    println!("| level | cues | hits | blocked | cues read | defended share | fixations |");
    println!("|---|---|---|---|---|---|---|");
    let mut share = std::collections::HashMap::new();
    let mut looks = Vec::new();
    for level in ["Novice", "Amateur", "Pro"] {
        for glove_only in [false, true] {
            let (hits, blocked, read, _, fix) = bout(level, glove_only, false);
            let s = 1.0 - f64::from(hits) / JABS as f64;
            if !glove_only {
                looks.push(fix);
            }
            println!(
                "| {level} | {} | {hits} | {blocked} | {read} | {s:.1} | {fix} |",
                if glove_only {
                    "none (glove only)"
                } else {
                    "body"
                }
            );
            share.insert((level, glove_only), s);
        }
    }
    println!("\n| level | feints | cues acted on | defensive reactions within 0.5 s |");
    println!("|---|---|---|---|");
    let mut drawn = Vec::new();
    for level in ["Novice", "Amateur", "Pro"] {
        let (_, _, read, reacted, _) = bout(level, false, true);
        println!("| {level} | {JABS} | {read} | {reacted} |");
        drawn.push(reacted);
    }
    // The pro's edge comes from the cue: with it, it is hit clearly less
    // than without it, and than the novice with it.
    assert!(
        share[&("Pro", false)] >= share[&("Pro", true)] + 0.3,
        "{share:?}"
    );
    assert!(
        share[&("Pro", false)] >= share[&("Novice", false)] + 0.3,
        "{share:?}"
    );
    // The pro's eyes hold the head; the novice's chase the gloves.
    assert!(looks[2] < looks[0], "fixations by level: {looks:?}");
    // Feints draw the pro's defence more often than the novice's, and
    // not every time.
    assert!(drawn[2] > drawn[0], "{drawn:?}");
}
