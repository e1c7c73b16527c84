//! Loading a scene: parse and validate its text, then resolve what it
//! refers to (gains file, emotion scripts, face database and mesh) and
//! build the simulation model.

use std::path::{Path, PathBuf};

use super::format::{FaceConfig, Scene};
use super::validate::validate;
use crate::physics::control::Gains;
use crate::sim::timeline::{Action, Event};
use crate::sim::{Model, Params, Sim};
use shisen_gaze::util::ron::{LoadError, parse_ron};

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
    pub face: std::sync::Arc<shisen_face::Face>,
    /// Where it came from (for messages).
    pub source: String,
}

/// The default scene, compiled into the binary.
pub const DEFAULT_SCENE_RON: &str = include_str!("../../../../scenes/default.ron");

impl LoadedScene {
    /// Load and validate a scene file.
    pub fn load(path: &Path) -> Result<LoadedScene, LoadError> {
        let text = shisen_gaze::util::ron::read_text(path)?;
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
            (None, Some(rel)) => {
                let path = resolve(rel);
                let gains_text = shisen_gaze::util::ron::read_text(&path)
                    .map_err(|e| e.named_by(file, text, "gains_file"))?;
                let g: Gains = parse_ron(&gains_text, &path)?;
                if let Err(m) = crate::physics::plausible::check_gains(&g) {
                    return Err(LoadError::at_field(&path, &gains_text, m.field, m.message));
                }
                g
            }
            (None, None) => Gains::default(),
        };
        expand_scripts(&mut scene, &resolve, text, file)?;
        let face = load_face(&scene.vh.face, &resolve, text, file)?;
        let mut loaded = LoadedScene {
            scene,
            gains,
            face: std::sync::Arc::new(face),
            source: file.display().to_string(),
        };
        // The profile's face part once, on the face every run shares
        // (`model` applies the profile).
        loaded.face = loaded.model().face;
        Ok(loaded)
    }

    /// The files this scene reads besides itself (gains, face database,
    /// mesh and landmarks), resolved against its folder: inputs no
    /// command may write over.
    pub fn files(&self) -> Vec<PathBuf> {
        let dir = Path::new(&self.source).parent().unwrap_or(Path::new("."));
        let f = &self.scene.vh.face;
        [&self.scene.gains_file, &f.database, &f.mesh, &f.landmarks]
            .into_iter()
            .flatten()
            .map(|p| dir.join(p))
            .collect()
    }

    /// The simulation model this scene describes.
    pub fn model(&self) -> Model {
        let vh = &self.scene.vh;
        let mut params = Params {
            gains: self.gains.clone(),
            personality: vh.personality.clone(),
            behaviour: vh.behaviour.clone(),
            vision: vh.vision.clone(),
            attention: vh.attention.clone(),
            oculomotor: vh.oculomotor.clone(),
            neck: vh.neck.clone(),
            body: vh.body.clone(),
            effort: vh.effort.clone(),
        };
        if let Some(o) = vh.opponent {
            o.apply(&mut params);
        }
        let mut model = Model {
            props: self.scene.bodies.clone(),
            bout: self.scene.bout,
            ..Model::new(self.face.clone(), params, self.scene.seed)
        };
        model.apply_profile(vh.profile);
        model
    }

    /// A simulation of this scene, at its start.
    pub fn sim(&self) -> Sim {
        Sim::new(self.model(), &self.scene.timeline)
    }
}

/// Replace each `EmotionScript` event by the `Emotion` events it holds.
fn expand_scripts(
    scene: &mut Scene,
    resolve: &dyn Fn(&Path) -> PathBuf,
    text: &str,
    source: &Path,
) -> Result<(), LoadError> {
    let mut out = Vec::with_capacity(scene.timeline.len());
    for (i, e) in scene.timeline.drain(..).enumerate() {
        match &e.action {
            Action::EmotionScript { file } => {
                let steps = shisen_face::script::load_script(&resolve(file)).map_err(|err| {
                    err.named_by(
                        source,
                        text,
                        &format!("timeline[{i}].do.EmotionScript.file"),
                    )
                })?;
                for (at, emotion, speed) in shisen_face::script::to_events(&steps, e.at) {
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
) -> Result<shisen_face::Face, LoadError> {
    use shisen_face::{Face, FaceError, mesh::MeshParams, params::FaceParams};
    let face_err = |e: FaceError| match e {
        FaceError::Parse(l) => l,
        other => LoadError::at_field(file, text, "vh.face", other.to_string()),
    };
    let params = match &c.database {
        Some(rel) => {
            let p = resolve(rel);
            let t = shisen_gaze::util::ron::read_text(&p)
                .map_err(|e| e.named_by(file, text, "vh.face.database"))?;
            FaceParams::parse(&t, &p).map_err(face_err)?
        }
        None => FaceParams::default_params(),
    };
    match (&c.mesh, &c.landmarks) {
        #[cfg(feature = "mesh-io")]
        (Some(m), Some(l)) => {
            shisen_face::import::import(&resolve(m), &resolve(l), params).map_err(face_err)
        }
        #[cfg(not(feature = "mesh-io"))]
        (Some(_), Some(_)) => Err(LoadError::at_field(
            file,
            text,
            "vh.face.mesh",
            "this build has no mesh import (enable the `mesh-io` feature)",
        )),
        (None, None) => Ok(Face::new(MeshParams { rows: c.rows }, params)),
        _ => Err(LoadError::at_field(
            file,
            text,
            "vh.face",
            "`mesh` and `landmarks` go together",
        )),
    }
}
