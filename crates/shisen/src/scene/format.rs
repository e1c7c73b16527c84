//! The scene file's types: what a file may say, with every number checked
//! as it is read, and the way back to text.

use std::path::PathBuf;

use serde::{Deserialize, Serialize};

use super::opponent::Opponent;
use crate::physics::control::Gains;
use crate::physics::lower::BodyParams;
use crate::physics::neck::NeckParams;
use crate::sim::bout::BoutParams;
use crate::sim::effort::EffortParams;
use crate::sim::expect::Expect;
use crate::sim::timeline::Event;
use crate::sim::{BodySpec, Params, Profile};
use shisen_gaze::attention::AttentionParams;
use shisen_gaze::behaviour::BehaviourParams;
use shisen_gaze::oculomotor::OculomotorParams;
use shisen_gaze::personality::Personality;
use shisen_gaze::vision::VisionParams;

/// Parameters of the virtual human.
#[derive(Clone, Debug, Default, PartialEq, Deserialize, Serialize)]
#[serde(default, deny_unknown_fields)]
pub struct VhParams {
    /// Human (default) or the seed's timing and perception; `Seed` sets
    /// the fields [`Profile::Seed`] lists, overriding values given here.
    pub profile: Profile,
    /// A level and style of opponent; sets the fields it names over the
    /// ones given here (`scene::opponent`).
    pub opponent: Option<Opponent>,
    /// Attention amounts.
    pub personality: Personality,
    /// Action planner.
    pub behaviour: BehaviourParams,
    /// Field of view and saliency options.
    pub vision: VisionParams,
    /// Arbitration, habituation, minimum fixation.
    pub attention: AttentionParams,
    /// Saccade, pursuit and head laws.
    pub oculomotor: OculomotorParams,
    /// The neck under impact: intrinsic impedance, tone, bracing, reflex.
    pub neck: NeckParams,
    /// The lower body: stance, stepping, the waist's law and strength.
    pub body: BodyParams,
    /// Effort over a bout: stamina, damage, fatigue's effects.
    pub effort: EffortParams,
    /// The face.
    pub face: FaceConfig,
}

impl VhParams {
    /// Take a running simulation's stage parameters (not the gains, not the face).
    pub fn set_params(&mut self, p: &Params) {
        // The parameters now say all the opponent did.
        self.opponent = None;
        self.personality = p.personality.clone();
        self.behaviour = p.behaviour.clone();
        self.vision = p.vision.clone();
        self.attention = p.attention.clone();
        self.oculomotor = p.oculomotor.clone();
        self.neck = p.neck.clone();
        self.body = p.body.clone();
        self.effort = p.effort.clone();
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
    shisen_gaze::util::check::in_range(d, 24.0, 400.0).map(|v| v as usize)
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
    #[serde(deserialize_with = "shisen_gaze::util::check::positive")]
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
    /// Rounds and rests: the run is a bout (the VH goes to its corner
    /// in the rests).
    #[serde(default)]
    pub bout: Option<BoutParams>,
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
