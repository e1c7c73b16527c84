//! Record and replay: a session driven by a synthetic input stream (gloves
//! following a pointer, throws, dodges, an emotion, uneven frame lengths)
//! is recorded as a scene; running that scene headless gives the live
//! session's trace byte for byte.

use std::path::Path;

use glam::Vec3;
use shisen::face::tables::Emotion;
use shisen::face::timing::{Pattern, Speed};
use shisen::scene::LoadedScene;
use shisen::sim::timeline::{Action, Event};
use shisen::tools::trace::TraceWriter;
use shisen_app::app::session::{SceneSource, Session};
use shisen_app::input::Intent;

/// A deterministic input for frame `f`.
fn synthetic(f: u32) -> Intent {
    let t = f as f32 * 0.016;
    let mut i = Intent::default();
    i.glove_offset[0] = Vec3::new(0.12 * (t * 2.1).sin(), 0.08 * (t * 1.3).cos(), 0.0);
    i.glove_offset[1] = Vec3::new(
        -0.05,
        0.1 * (t * 0.7).sin(),
        -0.1 * (t * 0.9).sin().max(0.0),
    );
    i.throw = [f % 47 == 5, f % 61 == 30];
    if (f / 40) % 3 == 1 {
        i.head_offset = Vec3::new(-0.15, 0.0, 0.0);
    }
    i
}

#[test]
fn a_recorded_session_replays_byte_for_byte() {
    let mut s = Session::new(LoadedScene::default_scene(), SceneSource::default_scene());
    // Tuning before the recording: the gains carry over (inlined in the
    // recording), the personality goes back to the scene's.
    let mut gains = s.sim.params().gains.clone();
    gains.neck.kp *= 1.3;
    s.sim.edit_params(|m| m.gains = gains.clone());
    let mut p = s.sim.params().personality.clone();
    p.a_face = 2.5;
    s.sim.edit_params(|m| m.personality = p);
    s.start_recording();
    assert_eq!(s.sim.params().gains, gains);
    let mut live = TraceWriter::new(Vec::new(), 1).unwrap();
    for f in 0..150u32 {
        s.apply(&synthetic(f));
        if f == 60 {
            s.push(Event {
                at: 0.0,
                action: Action::Emotion {
                    emotion: Emotion::Surprise,
                    intensity: 0.7,
                    speed: Speed::Fast,
                    pattern: Pattern::III,
                },
            });
        }
        // Uneven frames, as wall time gives them: 13-21 ticks.
        for _ in 0..(13 + (f * 7) % 9) {
            s.step();
            live.push(s.sim.last().unwrap()).unwrap();
        }
    }
    let live = live.finish().unwrap();
    assert!(
        s.recorder.as_ref().unwrap().len() > 100,
        "input was recorded"
    );
    let text = s.stop_recording().unwrap().unwrap();
    let loaded = LoadedScene::from_str(&text, Path::new("recorded.ron"), None)
        .unwrap_or_else(|e| panic!("{e}\n{text}"));
    let mut replay = Vec::new();
    let report = shisen::tools::headless::run(&loaded, None, Some(&mut replay), 1).unwrap();
    assert!(report.passed());
    assert_eq!(live.len(), replay.len(), "same number of rows");
    assert!(live == replay, "replayed trace differs from the live one");
}

/// Input-to-eye latency: from the frame a throw is input to the first tick
/// the VH's eyes have moved 2 deg (a saccade toward the glove, not fixation
/// noise). The app adds nothing: input
/// is applied before the frame's ticks and the frame renders their result.
/// Measured on the seed's timing, so the VH's own (human) reaction time
/// does not hide what the app would add.
#[test]
fn eyes_react_to_a_throw_within_a_fifth_of_a_second() {
    let text = "Scene(duration: 3.0, vh: (profile: Seed, behaviour: (attacks: false)))";
    let loaded = LoadedScene::from_str(text, Path::new("quiet.ron"), None).unwrap();
    let mut s = Session::new(loaded, SceneSource::default_scene());
    while s.sim.time() < 1.0 {
        s.step();
    }
    let before = s.sim.last().unwrap().eye_actual[0];
    let mut throw = Intent::default();
    throw.throw[0] = true;
    s.apply(&throw);
    let t0 = s.sim.time();
    let latency = loop {
        s.step();
        let now = s.sim.last().unwrap();
        if (now.eye_actual[0] - before).length().to_degrees() > 2.0 {
            break now.t - t0;
        }
        assert!(now.t - t0 < 1.0, "eyes never moved");
    };
    eprintln!(
        "input-to-eye latency: {:.0} ms = {:.1} frames at 60 Hz (gaze on {})",
        latency * 1e3,
        latency * 60.0,
        s.sim.last().unwrap().gaze_target
    );
    assert!(latency < 0.2, "latency {latency} s");
}
