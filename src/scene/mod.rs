//! Scene files (RON): the VH's parameters, the opponent's timeline, props,
//! gaze overrides and the expectations a headless run is judged by.
//!
//! Every struct denies unknown fields and every number is validated while
//! it is read (see [`crate::util::check`]), so a bad file fails with
//! `file:line:col: field.path: message` and nothing runs.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::agent::behaviour::BehaviourParams;
use crate::agent::personality::Personality;
use crate::physics::control::Gains;
use crate::sim::expect::Expect;
use crate::sim::timeline::{Action, Event};
use crate::sim::{BodySpec, Model, Params, Sim};
use crate::util::ron::{LoadError, line_of, parse_ron};

mod validate;
use validate::validate;

/// Parameters of the virtual human.
#[derive(Clone, Debug, Default, PartialEq, Deserialize, Serialize)]
#[serde(default, deny_unknown_fields)]
pub struct VhParams {
    /// Attention amounts.
    pub personality: Personality,
    /// Action planner.
    pub behaviour: BehaviourParams,
    /// Field of view and saliency options.
    pub vision: crate::agent::vision::VisionParams,
    /// Arbitration, habituation, minimum fixation.
    pub attention: crate::agent::attention::AttentionParams,
    /// Saccade, pursuit and head laws.
    pub oculomotor: crate::agent::oculomotor::OculomotorParams,
    /// The face.
    pub face: FaceConfig,
}

impl VhParams {
    /// Take a running simulation's stage parameters (not the gains, not the face).
    pub fn set_params(&mut self, p: &Params) {
        self.personality = p.personality.clone();
        self.behaviour = p.behaviour.clone();
        self.vision = p.vision.clone();
        self.attention = p.attention.clone();
        self.oculomotor = p.oculomotor.clone();
    }
}

/// Face settings of a scene (`vh.face`).
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(default, deny_unknown_fields)]
pub struct FaceConfig {
    /// Mesh resolution of the generated head: latitude bands (vertices ~
    /// 2 rows^2; 32 ~ 2k, 160 ~ 51k).
    #[serde(deserialize_with = "face_rows")]
    pub rows: usize,
    /// A muscle database (RON) replacing the shipped one, relative to the
    /// scene file (e.g. the output of `shisen face calibrate`).
    pub database: Option<PathBuf>,
    /// A user's head mesh (OBJ or GLB) instead of the generated one ...
    pub mesh: Option<PathBuf>,
    /// ... with the landmark file that places its muscles (RON).
    pub landmarks: Option<PathBuf>,
}

impl Default for FaceConfig {
    fn default() -> Self {
        FaceConfig {
            rows: 48,
            database: None,
            mesh: None,
            landmarks: None,
        }
    }
}

fn face_rows<'de, D: serde::Deserializer<'de>>(d: D) -> Result<usize, D::Error> {
    crate::util::check::in_range(d, 24.0, 400.0).map(|v| v as usize)
}

/// A scene file.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// Short name (defaults to the file stem).
    #[serde(default)]
    pub name: String,
    /// What the scene shows.
    #[serde(default)]
    pub description: String,
    /// Seed of every random stream.
    #[serde(default)]
    pub seed: u64,
    /// Length of the run, seconds.
    #[serde(deserialize_with = "crate::util::check::positive")]
    pub duration: f64,
    /// Gains file, relative to the scene file's folder.
    #[serde(default)]
    pub gains_file: Option<PathBuf>,
    /// Inline gains (override `gains_file`).
    #[serde(default)]
    pub gains: Option<Gains>,
    /// The virtual human's parameters.
    #[serde(default)]
    pub vh: VhParams,
    /// Props.
    #[serde(default)]
    pub bodies: Vec<BodySpec>,
    /// The timeline.
    #[serde(default)]
    pub timeline: Vec<Event>,
    /// Expectations for headless runs.
    #[serde(default)]
    pub expect: Vec<Expect>,
}

impl Scene {
    /// Parse and validate scene text without touching any other file (the
    /// first half of [`LoadedScene::from_str`]; also the fuzzing entry).
    pub fn parse(text: &str, file: &Path) -> Result<Scene, LoadError> {
        let mut scene: Scene = parse_ron(text, file)?;
        if scene.name.is_empty() {
            scene.name = file
                .file_stem()
                .map_or("scene".into(), |s| s.to_string_lossy().into_owned());
        }
        validate(&scene, text, file)?;
        Ok(scene)
    }

    /// The scene as RON text that [`Scene::parse`] reads back to an equal
    /// scene (used to record sessions).
    pub fn to_ron(&self) -> String {
        let pretty = ron::ser::PrettyConfig::new()
            .depth_limit(4)
            .indentor("  ".to_string())
            .extensions(ron::extensions::Extensions::IMPLICIT_SOME);
        ron::ser::to_string_pretty(self, pretty).expect("scene types serialise")
    }

    /// Take the parameters a running simulation has (after live edits) as
    /// this scene's: gains inline, the VH's stage parameters.
    pub fn set_params(&mut self, p: &Params) {
        self.gains = Some(p.gains.clone());
        self.gains_file = None;
        self.vh.set_params(p);
    }
}

/// A scene with everything it refers to resolved and validated: gains,
/// the face model (shared, static), expanded emotion scripts.
#[derive(Clone, Debug)]
pub struct LoadedScene {
    /// The scene.
    pub scene: Scene,
    /// Gains in force at start.
    pub gains: Gains,
    /// The face model (mesh, muscles, database), shared by every run.
    pub face: std::sync::Arc<crate::face::Face>,
    /// Where it came from (for messages).
    pub source: String,
}

/// The default scene, compiled into the binary.
pub const DEFAULT_SCENE_RON: &str = include_str!("../../scenes/default.ron");

impl LoadedScene {
    /// Load and validate a scene file.
    pub fn load(path: &Path) -> Result<LoadedScene, LoadError> {
        let text = crate::util::ron::read_text(path)?;
        Self::from_str(&text, path, path.parent())
    }

    /// The embedded default scene.
    pub fn default_scene() -> LoadedScene {
        Self::from_str(DEFAULT_SCENE_RON, Path::new("<embedded default.ron>"), None)
            .expect("embedded default scene is valid")
    }

    /// Parse and validate scene text; `dir` resolves `gains_file`.
    pub fn from_str(text: &str, file: &Path, dir: Option<&Path>) -> Result<LoadedScene, LoadError> {
        let mut scene = Scene::parse(text, file)?;
        let resolve = |rel: &Path| dir.map_or(rel.to_path_buf(), |d| d.join(rel));
        let gains = match (&scene.gains, &scene.gains_file) {
            (Some(g), _) => g.clone(),
            (None, Some(rel)) => Gains::load(&resolve(rel))?,
            (None, None) => Gains::default(),
        };
        expand_scripts(&mut scene, &resolve)?;
        let face = load_face(&scene.vh.face, &resolve, text, file)?;
        Ok(LoadedScene {
            scene,
            gains,
            face: std::sync::Arc::new(face),
            source: file.display().to_string(),
        })
    }

    /// The simulation model this scene describes.
    pub fn model(&self) -> Model {
        let vh = &self.scene.vh;
        let params = Params {
            gains: self.gains.clone(),
            personality: vh.personality.clone(),
            behaviour: vh.behaviour.clone(),
            vision: vh.vision.clone(),
            attention: vh.attention.clone(),
            oculomotor: vh.oculomotor.clone(),
        };
        Model {
            props: self.scene.bodies.clone(),
            ..Model::new(self.face.clone(), params, self.scene.seed)
        }
    }

    /// A simulation of this scene, at its start.
    pub fn sim(&self) -> Sim {
        Sim::new(self.model(), &self.scene.timeline)
    }
}

/// Replace each `EmotionScript` event by the `Emotion` events it holds.
fn expand_scripts(scene: &mut Scene, resolve: &dyn Fn(&Path) -> PathBuf) -> Result<(), LoadError> {
    let mut out = Vec::with_capacity(scene.timeline.len());
    for e in scene.timeline.drain(..) {
        match &e.action {
            Action::EmotionScript { file } => {
                let steps = crate::face::script::load_script(&resolve(file))?;
                for (at, emotion, speed) in crate::face::script::to_events(&steps, e.at) {
                    out.push(Event {
                        at,
                        action: Action::Emotion {
                            emotion,
                            intensity: 1.0,
                            speed,
                            pattern: Default::default(),
                        },
                    });
                }
            }
            _ => out.push(e),
        }
    }
    scene.timeline = out;
    Ok(())
}

/// Build the face model a scene asks for.
fn load_face(
    c: &FaceConfig,
    resolve: &dyn Fn(&Path) -> PathBuf,
    text: &str,
    file: &Path,
) -> Result<crate::face::Face, LoadError> {
    use crate::face::{Face, FaceError, mesh::MeshParams, params::FaceParams};
    let face_err = |e: FaceError| match e {
        FaceError::Parse(l) => l,
        other => {
            let (line, col) = line_of(text, "face");
            LoadError::Invalid {
                file: file.display().to_string(),
                line,
                col,
                field: "vh.face".into(),
                message: other.to_string(),
            }
        }
    };
    let params = match &c.database {
        Some(rel) => {
            let p = resolve(rel);
            let t = crate::util::ron::read_text(&p)?;
            FaceParams::parse(&t, &p).map_err(face_err)?
        }
        None => FaceParams::default_params(),
    };
    match (&c.mesh, &c.landmarks) {
        #[cfg(feature = "mesh-io")]
        (Some(m), Some(l)) => {
            crate::face::import::import(&resolve(m), &resolve(l), params).map_err(face_err)
        }
        #[cfg(not(feature = "mesh-io"))]
        (Some(_), Some(_)) => {
            let (line, col) = line_of(text, "mesh");
            Err(LoadError::Invalid {
                file: file.display().to_string(),
                line,
                col,
                field: "vh.face.mesh".into(),
                message: "this build has no mesh import (enable the `mesh-io` feature)".into(),
            })
        }
        (None, None) => Ok(Face::new(MeshParams { rows: c.rows }, params)),
        _ => {
            let (line, col) = line_of(text, "mesh");
            Err(LoadError::Invalid {
                file: file.display().to_string(),
                line,
                col,
                field: "vh.face".into(),
                message: "`mesh` and `landmarks` go together".into(),
            })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn load(text: &str) -> Result<LoadedScene, LoadError> {
        LoadedScene::from_str(text, Path::new("t.ron"), None)
    }

    #[test]
    fn every_shipped_scene_round_trips_through_serde() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
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
}
