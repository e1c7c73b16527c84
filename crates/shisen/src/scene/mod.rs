//! Scene files (RON): the VH's parameters, the opponent's timeline, props,
//! gaze overrides and the expectations a headless run is judged by.
//!
//! Every struct denies unknown fields and every number is validated while
//! it is read (see [`shisen_gaze::util::check`]), so a bad file fails with
//! `file:line:col: field.path: message` and nothing runs.

//!
//! [`format`](mod@format) holds the types of a file, [`validate`] the checks that need
//! the whole scene, [`load`] the resolution of what a scene refers to and
//! the [`Model`](crate::sim::Model) it describes.

pub mod format;
pub mod load;
pub mod opponent;
pub mod validate;

pub use format::{FaceConfig, Scene, VhParams};
pub use load::{DEFAULT_SCENE_RON, LoadedScene};

#[cfg(test)]
mod tests {
    use super::*;
    use shisen_gaze::util::ron::LoadError;
    use std::path::Path;

    fn load(text: &str) -> Result<LoadedScene, LoadError> {
        LoadedScene::from_str(text, Path::new("t.ron"), None)
    }

    #[test]
    fn every_shipped_scene_round_trips_through_serde() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes");
        let mut n = 0;
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.extension().is_none_or(|e| e != "ron") {
                continue;
            }
            let scene = Scene::parse(&std::fs::read_to_string(&path).unwrap(), &path).unwrap();
            let text = scene.to_ron();
            let back = Scene::parse(&text, Path::new("saved.ron"))
                .unwrap_or_else(|e| panic!("{}: {e}\n{text}", path.display()));
            assert_eq!(back, scene, "{}", path.display());
            n += 1;
        }
        assert!(n >= 5, "found {n} scenes");
    }

    #[test]
    fn a_loaded_scene_with_edited_params_round_trips() {
        let loaded = LoadedScene::default_scene();
        let mut params = loaded.model().params;
        params.personality.a_face = 2.25;
        params.gains.neck.kp *= 1.5;
        params.oculomotor.head.steepness = 5.5;
        let mut scene = loaded.scene.clone();
        scene.set_params(&params);
        let back = Scene::parse(&scene.to_ron(), Path::new("saved.ron")).unwrap();
        assert_eq!(back, scene);
        assert_eq!(back.gains.as_ref(), Some(&params.gains));
        assert_eq!(back.vh.personality.a_face, 2.25);
    }

    #[test]
    fn embedded_default_scene_is_valid() {
        let s = LoadedScene::default_scene();
        assert!(s.scene.duration > 0.0);
    }

    #[test]
    fn bouts_opponents_and_fatigue_checks_are_refused_when_bad() {
        for (text, line, field) in [
            (
                "Scene(\n  duration: 1.0,\n  bout: Some((rounds: 2.5)),\n)",
                3,
                "rounds",
            ),
            (
                "Scene(\n  duration: 1.0,\n  vh: (effort: (stagger_time: 9.0)),\n)",
                3,
                "stagger_time",
            ),
            (
                "Scene(\n  duration: 1.0,\n  vh: (opponent: Some((level: Champion))),\n)",
                3,
                "Champion",
            ),
            (
                "Scene(\n  duration: 1.0,\n  expect: [\n    Fatigue(at_least: 0.0, at_most: 1.0, from: 0.0, to: 1.0),\n  ],\n)",
                4,
                "cannot fail",
            ),
            (
                "Scene(\n  duration: 1.0,\n  expect: [\n    Fatigue(at_least: 0.5, at_most: 0.2, from: 0.0, to: 1.0),\n  ],\n)",
                4,
                "at_most",
            ),
            (
                "Scene(\n  duration: 1.0,\n  expect: [\n    GazeShare(target: \"head\", from: 0.0, to: 1.0, at_least: 0.0),\n  ],\n)",
                4,
                "share of at least 0",
            ),
            (
                "Scene(\n  duration: 1.0,\n  expect: [\n    GazeShareAtMost(target: \"head\", from: 0.0, to: 1.0, at_most: 1.0),\n  ],\n)",
                4,
                "must be under 1",
            ),
            (
                "Scene(\n  duration: 1.0,\n  expect: [\n    Evades(from: 0.0, to: 1.0, at_least: 0),\n  ],\n)",
                4,
                "cannot fail",
            ),
            (
                "Scene(\n  duration: 1.0,\n  expect: [\n    Knockdowns(from: 0.0, to: 1.0),\n  ],\n)",
                4,
                "cannot fail",
            ),
            (
                "Scene(\n  duration: 1.0,\n  expect: [\n    Knockdowns(from: 0.0, to: 1.0, at_least: 1),\n  ],\n)",
                4,
                "needs a physical body",
            ),
            (
                "Scene(\n  duration: 1.0,\n  vh: (body: (pelvis: Balanced)),\n  expect: [\n    Knockdowns(from: 0.0, to: 1.0, at_least: 2, at_most: Some(1)),\n  ],\n)",
                5,
                "at_most",
            ),
            (
                "Scene(\n  duration: 2.0,\n  timeline: [\n    (at: 0.5, do: Punch(hand: Left, target: Head, speed: 5.0)),\n    (at: 0.5, do: Punch(hand: Left, target: Body, speed: 5.0)),\n  ],\n)",
                5,
                "one punch at a time",
            ),
        ] {
            let e = load(text).unwrap_err().to_string();
            assert!(e.starts_with(&format!("t.ron:{line}:")), "{e}");
            assert!(e.contains(field), "{e}");
        }
    }

    #[test]
    fn unknown_field_names_line_and_field() {
        let e =
            load("Scene(\n  duration: 1.0,\n  vh: (personality: (a_face: 1.0, bogus: 2.0)),\n)")
                .unwrap_err()
                .to_string();
        assert!(e.starts_with("t.ron:3:"), "{e}");
        assert!(e.contains("bogus"), "{e}");
    }

    #[test]
    fn nan_is_rejected_at_its_field() {
        let e = load("Scene(\n duration: 1.0,\n timeline: [\n  (at: 0.5, do: Punch(hand: Left, target: Head, speed: NaN)),\n ],\n)")
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("t.ron:4:"), "{e}");
        assert!(e.contains("timeline[0].do.Punch.speed"), "{e}");
        assert!(e.contains("finite"), "{e}");
    }

    #[test]
    fn negative_gain_is_rejected() {
        let e = load(
            "Scene(\n duration: 1.0,\n gains: Some(Gains(\n  eye: (kp: 1.0, kd: 0.1),\n  neck: (kp: -3.0, kd: 1.0),\n  shoulder: (kp: 1.0, kd: 1.0),\n  elbow: (kp: 1.0, kd: 1.0),\n )),\n)",
        )
        .unwrap_err()
        .to_string();
        assert!(e.starts_with("t.ron:5:"), "{e}");
        assert!(e.contains("gains.neck.kp"), "{e}");
        assert!(e.contains(">= 0"), "{e}");
    }

    #[test]
    fn syntax_error_has_position() {
        let e = load("Scene(\n duration: 1.0,\n timeline: [ (at: 1.0 ]\n)").unwrap_err();
        match e {
            LoadError::Invalid { line, .. } => assert_eq!(line, 3),
            other => panic!("{other}"),
        }
    }

    #[test]
    fn cross_field_checks_name_their_fields() {
        let e = load("Scene(\n duration: 1.0,\n vh: (personality: (a1: 2.0, a2: 1.0)),\n)")
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("t.ron:3:") && e.contains("vh.personality.a2"),
            "{e}"
        );
        let e = load(
            "Scene(\n duration: 1.0,\n vh: (oculomotor: (pursuit: (rho1: 0.5, rho2: 1.5))),\n)",
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.starts_with("t.ron:3:") && e.contains("vh.oculomotor.pursuit"),
            "{e}"
        );
        assert!(e.contains("rho1"), "{e}");
    }

    #[test]
    fn undeclared_body_is_named() {
        let e = load(
            "Scene(\n duration: 1.0,\n timeline: [\n  (at: 0.0, do: Move(part: Body(\"ghost\"), to: (0.0, 1.0, 1.0), duration: 1.0)),\n ],\n)",
        )
        .unwrap_err()
        .to_string();
        assert!(e.starts_with("t.ron:4:"), "{e}");
        assert!(
            e.contains("ghost") && e.contains("timeline[0].do.part"),
            "{e}"
        );
    }

    fn err(text: &str) -> String {
        load(text).unwrap_err().to_string()
    }

    #[test]
    fn misspelled_names_are_load_errors_with_a_suggestion() {
        let e = err(
            "Scene(\n duration: 2.0,\n expect: [GazeShareAtMost(target: \"haed\", from: 0.0, to: 1.0, at_most: 0.5)],\n)",
        );
        assert!(
            e.starts_with("t.ron:3:") && e.contains("expect[0].target"),
            "{e}"
        );
        assert!(e.contains("did you mean `head`"), "{e}");
        let e = err(
            "Scene(\n duration: 2.0,\n timeline: [(at: 0.0, do: Track(body: \"left_glvoe\", until: 1.0))],\n)",
        );
        assert!(e.contains("did you mean `left_glove`"), "{e}");
        // Far from every name: no suggestion.
        let e = err(
            "Scene(duration: 2.0, expect: [GazeReaches(target: \"xyzzy\", from: 0.0, to: 1.0)])",
        );
        assert!(!e.contains("did you mean"), "{e}");
    }

    #[test]
    fn events_after_the_end_and_double_gains_are_refused() {
        let e = err("Scene(\n duration: 1.0,\n timeline: [(at: 1.5, do: Occlude(eye: None))],\n)");
        assert!(
            e.contains("timeline[0].at") && e.contains("after the end"),
            "{e}"
        );
        let e = err(
            "Scene(\n duration: 1.0,\n gains_file: \"g.ron\",\n gains: Gains(eye: (kp: 1.0, kd: 0.1), neck: (kp: 1.0, kd: 1.0), shoulder: (kp: 1.0, kd: 1.0), elbow: (kp: 1.0, kd: 1.0)),\n)",
        );
        assert!(e.starts_with("t.ron:3:") && e.contains("not both"), "{e}");
        let e = err("Scene(duration: 1e12)");
        assert!(e.contains("duration: must be <= 86400"), "{e}");
        // A window no tick falls in, and a body with no name (issue 50).
        let e = err(
            "Scene(duration: 2.0, expect: [GazeReaches(target: \"head\", from: 1.0, to: 1.0)])",
        );
        assert!(e.contains("expect[0]") && e.contains("is empty"), "{e}");
        let e = err(
            "Scene(duration: 2.0, bodies: [(name: \"\", shape: Ball(0.05), position: (0.0, 1.0, 1.0))])",
        );
        assert!(e.contains("bodies[0].name") && e.contains("empty"), "{e}");
    }

    #[test]
    fn implausible_sizes_and_amounts_are_refused() {
        for (text, field) in [
            (
                "Scene(duration: 1.0, vh: (vision: (field: (temporal_deg: 400.0))))",
                "temporal_deg",
            ),
            (
                "Scene(duration: 1.0, vh: (personality: (a_face: 1e30)))",
                "a_face",
            ),
            (
                "Scene(duration: 1.0, timeline: [(at: 0.0, do: Move(part: LeftGlove, to: (1e6, 1.0, 1.0), duration: 0.5))])",
                "timeline[0].do.Move.to",
            ),
            (
                "Scene(duration: 1.0, vh: (vision: (max_distance: 1e9)))",
                "max_distance",
            ),
            (
                "Scene(duration: 1.0, bodies: [(name: \"b\", shape: Ball(1e6), position: (0.0, 1.0, 1.0))])",
                "shape",
            ),
        ] {
            let e = err(text);
            assert!(e.contains(field) && e.contains("must be"), "{e}");
        }
    }

    #[test]
    fn shipped_gains_are_plausible_and_absurd_ones_are_not() {
        crate::physics::plausible::check_gains(&crate::physics::control::Gains::default()).unwrap();
        let e = err(
            "Scene(\n duration: 1.0,\n gains: Gains(eye: (kp: 1.0, kd: 0.1), neck: (kp: 1.0, kd: 1.0), shoulder: (kp: 1.0, kd: 1.0), elbow: (kp: 1.0, kd: 1.0)),\n)",
        );
        assert!(
            e.starts_with("t.ron:3:") && e.contains("gains.eye.kp"),
            "{e}"
        );
        assert!(e.contains("natural frequency"), "{e}");
    }

    #[test]
    fn syntax_errors_name_the_field_and_the_likely_cause() {
        let e = err("Scene(\n    duration: 1.0,\n    seed: 1.5,\n)");
        assert!(
            e.starts_with("t.ron:3:") && e.contains("seed:") && e.contains("whole number"),
            "{e}"
        );
        let e = err(
            "Scene(\n duration: 1.0,\n timeline: [\n  (at: 0.5, do: Occlude(eye: None),\n ],\n)",
        );
        assert!(
            e.contains("timeline[0]:") && !e.contains(".?") && e.contains("missing"),
            "{e}"
        );
    }
}
