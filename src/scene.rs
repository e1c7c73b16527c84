//! Scene files (RON): the VH's parameters, the opponent's timeline, props,
//! gaze overrides and the expectations a headless run is judged by.
//!
//! Every struct denies unknown fields and every number is validated while
//! it is read (see [`crate::check`]), so a bad file fails with
//! `file:line:col: field.path: message` and nothing runs.

use std::path::{Path, PathBuf};

use glam::DVec3;
use serde::Deserialize;
use serde::de::DeserializeOwned;
use thiserror::Error;

use crate::behaviour::BehaviourParams;
use crate::control::Gains;

/// A scene or gains file that could not be loaded.
#[derive(Debug, Error)]
pub enum LoadError {
    /// The file could not be read.
    #[error("{file}: {source}")]
    Io {
        /// The file.
        file: String,
        /// The OS error.
        source: std::io::Error,
    },
    /// Syntax error, unknown field or invalid value.
    #[error("{file}:{line}:{col}: {field}: {message}")]
    Invalid {
        /// The file.
        file: String,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        col: usize,
        /// Dotted path of the field (`timeline[2].do.Punch.speed`), or `-` for syntax errors.
        field: String,
        /// What is wrong.
        message: String,
    },
}

/// Parse RON text into `T`, reporting the file, line, column and field path.
pub fn parse_ron<T: DeserializeOwned>(text: &str, file: &Path) -> Result<T, LoadError> {
    let file_s = file.display().to_string();
    let invalid = |line, col, field: String, message: String| LoadError::Invalid {
        file: file_s.clone(),
        line,
        col,
        field,
        message,
    };
    // Optional fields are written plainly (`gains: Gains(...)`, not `Some(...)`).
    let options =
        ron::Options::default().with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME);
    let mut de = ron::Deserializer::from_str_with_options(text, &options).map_err(|e| {
        invalid(
            e.span.start.line,
            e.span.start.col,
            "-".into(),
            e.code.to_string(),
        )
    })?;
    let value = match serde_path_to_error::deserialize::<_, T>(&mut de) {
        Ok(v) => v,
        Err(err) => {
            let path = err.path().to_string();
            let spanned = de.span_error(err.into_inner());
            let field = if path == "." { "-".to_string() } else { path };
            return Err(invalid(
                spanned.span.start.line,
                spanned.span.start.col,
                field,
                spanned.code.to_string(),
            ));
        }
    };
    de.end().map_err(|e| {
        let s = de.span_error(e);
        invalid(
            s.span.start.line,
            s.span.start.col,
            "-".into(),
            s.code.to_string(),
        )
    })?;
    Ok(value)
}

/// 1-based line of the first occurrence of `needle` in `text` (for errors
/// found after parsing, such as a reference to an undeclared body).
pub fn line_of(text: &str, needle: &str) -> (usize, usize) {
    match text.find(needle) {
        Some(pos) => {
            let before = &text[..pos];
            let line = before.matches('\n').count() + 1;
            let col = pos - before.rfind('\n').map_or(0, |i| i + 1) + 1;
            (line, col)
        }
        None => (1, 1),
    }
}

/// The personality amounts (gaze.md 5, 9): top-down attention per action
/// and the head-movement law's A1, A2.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Personality {
    /// Top-down amount while idle (look at the opponent's face).
    #[serde(deserialize_with = "crate::check::non_negative")]
    pub a_face: f64,
    /// Top-down amount of the attack target.
    #[serde(deserialize_with = "crate::check::non_negative")]
    pub a_attack: f64,
    /// Top-down amount of the guarded point.
    #[serde(deserialize_with = "crate::check::non_negative")]
    pub a_guard: f64,
    /// Attention amount at which the head moves least (M8).
    #[serde(deserialize_with = "crate::check::non_negative")]
    pub a1: f64,
    /// Attention amount at which the head moves most (M8); must exceed `a1`.
    #[serde(deserialize_with = "crate::check::non_negative")]
    pub a2: f64,
}

impl Default for Personality {
    /// The original implementation's amounts (gaze.md 11): face 1.5,
    /// attack and guard 3.0. With A1 = 0 and A2 = 3, (M8) turns the head
    /// fully toward attack and guard points and stops it 15 deg short of
    /// the face.
    fn default() -> Self {
        Personality {
            a_face: 1.5,
            a_attack: 3.0,
            a_guard: 3.0,
            a1: 0.0,
            a2: 3.0,
        }
    }
}

/// Parameters of the virtual human.
#[derive(Clone, Debug, Default, PartialEq, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct VhParams {
    /// Attention amounts.
    pub personality: Personality,
    /// Action planner.
    pub behaviour: BehaviourParams,
    /// Field of view and saliency options.
    pub vision: crate::vision::VisionParams,
    /// Arbitration, habituation, minimum fixation.
    pub attention: crate::attention::AttentionParams,
    /// Saccade, pursuit and head laws.
    pub oculomotor: crate::oculomotor::OculomotorParams,
    /// The face.
    pub face: FaceConfig,
}

/// Face settings of a scene (`vh.face`).
#[derive(Clone, Debug, PartialEq, Deserialize)]
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
    crate::check::in_range(d, 24.0, 400.0).map(|v| v as usize)
}

/// The opponent's hands.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
pub enum Hand {
    /// The opponent's left glove ("left_glove").
    Left,
    /// The opponent's right glove ("right_glove").
    Right,
}

/// A script-movable body: an opponent part or a kinematic prop.
#[derive(Clone, Debug, PartialEq, Deserialize)]
pub enum Part {
    /// Opponent's head.
    Head,
    /// Opponent's left glove.
    LeftGlove,
    /// Opponent's right glove.
    RightGlove,
    /// A kinematic prop declared in `bodies`.
    Body(String),
}

/// The VH's left or right (eyes).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
pub enum Side {
    /// The VH's left.
    Left,
    /// The VH's right.
    Right,
}

fn opt_non_negative<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Option<f64>, D::Error> {
    crate::check::non_negative(d).map(Some)
}

/// Where an opponent punch is aimed.
#[derive(Clone, Debug, PartialEq, Deserialize)]
pub enum PunchTarget {
    /// The VH's head (where it is when the punch starts).
    Head,
    /// The VH's torso.
    Body,
    /// A world point.
    Point(#[serde(deserialize_with = "crate::check::vec3")] DVec3),
}

/// Something that happens at a time in the scene.
#[derive(Clone, Debug, PartialEq, Deserialize)]
pub enum Action {
    /// Move a part to a point along a minimum-jerk path.
    Move {
        /// What moves.
        part: Part,
        /// Destination, world metres.
        #[serde(deserialize_with = "crate::check::vec3")]
        to: DVec3,
        /// Duration, seconds.
        #[serde(deserialize_with = "crate::check::positive")]
        duration: f64,
    },
    /// Throw a punch at the VH and bring the glove back.
    Punch {
        /// Which glove.
        hand: Hand,
        /// Aim.
        target: PunchTarget,
        /// Peak glove speed, m/s.
        #[serde(deserialize_with = "crate::check::positive")]
        speed: f64,
    },
    /// Wave a part sinusoidally about its current position.
    Wave {
        /// What waves.
        part: Part,
        /// Peak displacement along each axis, metres.
        #[serde(deserialize_with = "crate::check::vec3")]
        amplitude: DVec3,
        /// Frequency, Hz.
        #[serde(deserialize_with = "crate::check::positive")]
        frequency: f64,
        /// Duration, seconds.
        #[serde(deserialize_with = "crate::check::positive")]
        duration: f64,
    },
    /// Change the facial expression (face.md 7): from the current values to
    /// `emotion` at `intensity`, over the table 5.9/5.10 duration at `speed`.
    Emotion {
        /// One of the 35 emotions of table A (`Neutral`, `Happiness`, ...).
        emotion: crate::face::tables::Emotion,
        /// Intensity, 0-1.
        #[serde(default = "one", deserialize_with = "crate::check::unit_interval")]
        intensity: f64,
        /// `Fast`, `Typical` or `Slow` (the thesis's speeds 1, 2, 3).
        #[serde(default)]
        speed: crate::face::timing::Speed,
        /// Onset/offset shape `I`..`V` (default `III`, the thesis's choice).
        #[serde(default)]
        pattern: crate::face::timing::Pattern,
    },
    /// Play a script in the thesis's plain format (`emotion duration
    /// speed` per line, face.md 9) from this time; the file is relative to
    /// the scene and is expanded into `Emotion` events when the scene loads.
    EmotionScript {
        /// The script file.
        file: PathBuf,
    },
    /// Override the gaze: look at a world point until a time.
    LookAt {
        /// The point, world metres.
        #[serde(deserialize_with = "crate::check::vec3")]
        point: DVec3,
        /// End of the override, seconds.
        #[serde(deserialize_with = "crate::check::non_negative")]
        until: f64,
        /// Attention amount A for the head law (M8); default the
        /// personality's `a2` (the head faces the point).
        #[serde(default, deserialize_with = "opt_non_negative")]
        amount: Option<f64>,
        /// How to shift the gaze there (default: the scene's law).
        #[serde(default)]
        style: Option<crate::oculomotor::GazeShiftLaw>,
    },
    /// Override the gaze: follow a body (by name) until a time.
    Track {
        /// Body name (`head`, `left_glove`, a prop...).
        body: String,
        /// End of the override, seconds.
        #[serde(deserialize_with = "crate::check::non_negative")]
        until: f64,
    },
    /// Move a part at constant angular speed on a horizontal circle about
    /// a centre (a pursuit target).
    Orbit {
        /// What moves.
        part: Part,
        /// Centre of the circle, world metres.
        #[serde(deserialize_with = "crate::check::vec3")]
        centre: DVec3,
        /// Angular speed about +Y (positive: toward the VH's left), deg/s.
        #[serde(deserialize_with = "crate::check::finite")]
        rate_deg: f64,
        /// Duration, seconds.
        #[serde(deserialize_with = "crate::check::positive")]
        duration: f64,
    },
    /// Shut or cover one eye (`Some(Left)`, `Some(Right)`) or none (`None`).
    Occlude {
        /// The covered eye.
        eye: Option<Side>,
    },
    /// Impose a sinusoidal neck motion (overriding the head law), e.g. to
    /// measure the VOR: yaw and pitch amplitudes in degrees.
    ShakeHead {
        /// Yaw amplitude, deg.
        #[serde(deserialize_with = "crate::check::non_negative")]
        yaw_deg: f64,
        /// Pitch amplitude, deg.
        #[serde(default, deserialize_with = "crate::check::non_negative")]
        pitch_deg: f64,
        /// Frequency, Hz.
        #[serde(deserialize_with = "crate::check::positive")]
        frequency: f64,
        /// Duration, s.
        #[serde(deserialize_with = "crate::check::positive")]
        duration: f64,
    },
}

/// A timeline entry.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Event {
    /// Start time, seconds.
    #[serde(deserialize_with = "crate::check::non_negative")]
    pub at: f64,
    /// What happens.
    #[serde(rename = "do")]
    pub action: Action,
}

/// Shape of a prop.
#[derive(Clone, Debug, PartialEq, Deserialize)]
pub enum PropShape {
    /// Sphere.
    Ball(#[serde(deserialize_with = "crate::check::positive")] f64),
    /// Box with half extents.
    Box(#[serde(deserialize_with = "crate::check::vec3")] DVec3),
}

/// A prop declared by the scene.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodySpec {
    /// Unique name.
    pub name: String,
    /// Shape.
    pub shape: PropShape,
    /// Initial position, world metres.
    #[serde(deserialize_with = "crate::check::vec3")]
    pub position: DVec3,
    /// Initial velocity (dynamic props), m/s.
    #[serde(default, deserialize_with = "crate::check::vec3")]
    pub velocity: DVec3,
    /// Initial angular velocity (dynamic props), rad/s.
    #[serde(default, deserialize_with = "crate::check::vec3")]
    pub angular_velocity: DVec3,
    /// Mass, kg.
    #[serde(default = "default_mass", deserialize_with = "crate::check::positive")]
    pub mass: f64,
    /// Scripted (moved by `Move`/`Wave`) rather than simulated.
    #[serde(default)]
    pub kinematic: bool,
    /// Whether gravity acts on a dynamic prop.
    #[serde(default = "yes")]
    pub gravity: bool,
}

fn one() -> f64 {
    1.0
}

fn default_mass() -> f64 {
    0.5
}

fn yes() -> bool {
    true
}

/// A named angle of the VH for expectations.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
pub enum JointName {
    /// Neck yaw.
    NeckYaw,
    /// Neck pitch.
    NeckPitch,
    /// Neck roll.
    NeckRoll,
    /// Left eye yaw.
    LeftEyeYaw,
    /// Left eye pitch.
    LeftEyePitch,
    /// Right eye yaw.
    RightEyeYaw,
    /// Right eye pitch.
    RightEyePitch,
}

/// The VH's current action (boxing.md).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, serde::Serialize)]
pub enum ActionKind {
    /// Guard stance, looking at the opponent's face.
    Idle,
    /// Intercepting an incoming glove.
    Guard,
    /// Looking at the target, then punching.
    Attack,
}

/// A predicate over a time window, checked by a headless run.
#[derive(Clone, Debug, PartialEq, Deserialize)]
pub enum Expect {
    /// The gaze target is `target` for at least `share` of [from, to].
    GazeShare {
        /// Target name ("head", "left_glove", "point", ...).
        target: String,
        /// Window start, s.
        #[serde(deserialize_with = "crate::check::non_negative")]
        from: f64,
        /// Window end, s.
        #[serde(deserialize_with = "crate::check::non_negative")]
        to: f64,
        /// Minimum share, 0-1.
        #[serde(deserialize_with = "crate::check::unit_interval")]
        at_least: f64,
    },
    /// The gaze target is `target` for at most `share` of [from, to].
    GazeShareAtMost {
        /// Target name.
        target: String,
        /// Window start, s.
        #[serde(deserialize_with = "crate::check::non_negative")]
        from: f64,
        /// Window end, s.
        #[serde(deserialize_with = "crate::check::non_negative")]
        to: f64,
        /// Maximum share, 0-1.
        #[serde(deserialize_with = "crate::check::unit_interval")]
        at_most: f64,
    },
    /// The gaze target becomes `target` at some time in [from, to].
    GazeReaches {
        /// Target name.
        target: String,
        /// Window start, s.
        #[serde(deserialize_with = "crate::check::non_negative")]
        from: f64,
        /// Window end, s.
        #[serde(deserialize_with = "crate::check::non_negative")]
        to: f64,
    },
    /// |angle| stays below `max_deg` over [from, to] (whole run if omitted).
    AngleBelow {
        /// Which angle.
        joint: JointName,
        /// Bound, degrees.
        #[serde(deserialize_with = "crate::check::non_negative")]
        max_deg: f64,
        /// Window start, s.
        #[serde(default, deserialize_with = "opt_time")]
        from: Option<f64>,
        /// Window end, s.
        #[serde(default, deserialize_with = "opt_time")]
        to: Option<f64>,
    },
    /// |angle| reaches at least `min_deg` at some time in [from, to].
    AngleReaches {
        /// Which angle.
        joint: JointName,
        /// Bound, degrees.
        #[serde(deserialize_with = "crate::check::non_negative")]
        min_deg: f64,
        /// Window start, s.
        #[serde(deserialize_with = "crate::check::non_negative")]
        from: f64,
        /// Window end, s.
        #[serde(deserialize_with = "crate::check::non_negative")]
        to: f64,
    },
    /// Before every punch the VH throws, its eyes have been on the attack
    /// target (chosen top-down during the attack, line-of-sight error under
    /// 2 deg) for at least `min_lead` seconds: the telegraph. Fails if no
    /// punch is thrown.
    Telegraph {
        /// Minimum lead, s.
        #[serde(deserialize_with = "crate::check::non_negative")]
        min_lead: f64,
    },
    /// Both eyes' line-of-sight error to the gaze point stays below
    /// `max_deg` over [from, to].
    LineOfSight {
        /// Bound, degrees.
        #[serde(deserialize_with = "crate::check::non_negative")]
        max_deg: f64,
        /// Window start, s.
        #[serde(deserialize_with = "crate::check::non_negative")]
        from: f64,
        /// Window end, s.
        #[serde(deserialize_with = "crate::check::non_negative")]
        to: f64,
    },
    /// The VH's action is `action` for at least `at_least` of [from, to].
    ActionShare {
        /// The action.
        action: ActionKind,
        /// Window start, s.
        #[serde(deserialize_with = "crate::check::non_negative")]
        from: f64,
        /// Window end, s.
        #[serde(deserialize_with = "crate::check::non_negative")]
        to: f64,
        /// Minimum share, 0-1.
        #[serde(deserialize_with = "crate::check::unit_interval")]
        at_least: f64,
    },
    /// Every state value stays finite for the whole run.
    Finite,
}

fn opt_time<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Option<f64>, D::Error> {
    crate::check::non_negative(d).map(Some)
}

/// A scene file.
#[derive(Clone, Debug, PartialEq, Deserialize)]
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
    #[serde(deserialize_with = "crate::check::positive")]
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
pub const DEFAULT_SCENE_RON: &str = include_str!("../scenes/default.ron");

impl LoadedScene {
    /// Load and validate a scene file.
    pub fn load(path: &Path) -> Result<LoadedScene, LoadError> {
        let text = std::fs::read_to_string(path).map_err(|e| LoadError::Io {
            file: path.display().to_string(),
            source: e,
        })?;
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
            let t = std::fs::read_to_string(&p).map_err(|e| LoadError::Io {
                file: p.display().to_string(),
                source: e,
            })?;
            FaceParams::parse(&t, &p).map_err(face_err)?
        }
        None => FaceParams::default_params(),
    };
    match (&c.mesh, &c.landmarks) {
        (Some(m), Some(l)) => {
            crate::face::import::import(&resolve(m), &resolve(l), params).map_err(face_err)
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

/// Cross-field checks that need the whole scene.
fn validate(scene: &Scene, text: &str, file: &Path) -> Result<(), LoadError> {
    let err = |needle: &str, field: String, message: String| {
        let (line, col) = line_of(text, needle);
        LoadError::Invalid {
            file: file.display().to_string(),
            line,
            col,
            field,
            message,
        }
    };
    let p = &scene.vh.personality;
    if p.a2 <= p.a1 {
        return Err(err(
            "a2",
            "vh.personality.a2".into(),
            format!("must exceed a1 ({}), got {}", p.a1, p.a2),
        ));
    }
    if let Err(m) = scene.vh.oculomotor.pursuit.validate() {
        return Err(err("pursuit", "vh.oculomotor.pursuit".into(), m));
    }
    let mut names: Vec<&str> = vec!["head", "left_glove", "right_glove"];
    for (i, b) in scene.bodies.iter().enumerate() {
        if names.contains(&b.name.as_str()) || b.name.starts_with("vh_") || b.name == "point" {
            return Err(err(
                &format!("\"{}\"", b.name),
                format!("bodies[{i}].name"),
                format!("name `{}` is taken or reserved", b.name),
            ));
        }
        names.push(&b.name);
    }
    for (i, e) in scene.timeline.iter().enumerate() {
        let part = match &e.action {
            Action::Move { part, .. } | Action::Wave { part, .. } | Action::Orbit { part, .. } => {
                Some(part)
            }
            _ => None,
        };
        if let Action::Track { body, until } = &e.action {
            if !names.contains(&body.as_str()) {
                return Err(err(
                    &format!("\"{body}\""),
                    format!("timeline[{i}].do.Track.body"),
                    format!("no body named `{body}` (opponent parts or `bodies`)"),
                ));
            }
            if *until < e.at {
                return Err(err(
                    "until",
                    format!("timeline[{i}].do.Track.until"),
                    format!("must not precede `at` ({}), got {until}", e.at),
                ));
            }
        }
        if let Some(Part::Body(name)) = part
            && !scene.bodies.iter().any(|b| &b.name == name && b.kinematic)
        {
            return Err(err(
                &format!("\"{name}\""),
                format!("timeline[{i}].do.part"),
                format!("no kinematic body named `{name}` in `bodies`"),
            ));
        }
        if let Action::LookAt { until, .. } = e.action
            && until < e.at
        {
            return Err(err(
                "until",
                format!("timeline[{i}].do.LookAt.until"),
                format!("must not precede `at` ({}), got {until}", e.at),
            ));
        }
    }
    for (i, x) in scene.expect.iter().enumerate() {
        let window = match x {
            Expect::GazeShare { from, to, .. }
            | Expect::GazeShareAtMost { from, to, .. }
            | Expect::GazeReaches { from, to, .. }
            | Expect::LineOfSight { from, to, .. }
            | Expect::AngleReaches { from, to, .. }
            | Expect::ActionShare { from, to, .. } => Some((*from, *to)),
            Expect::AngleBelow { from, to, .. } => {
                Some((from.unwrap_or(0.0), to.unwrap_or(scene.duration)))
            }
            Expect::Finite | Expect::Telegraph { .. } => None,
        };
        if let Some((from, to)) = window
            && (to < from || to > scene.duration + 1e-9)
        {
            return Err(err(
                "expect",
                format!("expect[{i}]"),
                format!(
                    "window [{from}, {to}] must be ordered and inside the run (0, {})",
                    scene.duration
                ),
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn load(text: &str) -> Result<LoadedScene, LoadError> {
        LoadedScene::from_str(text, Path::new("t.ron"), None)
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
