//! The scene file's types: what a file may say, with every number's
//! range declared on its field (the loader checks each value read against
//! it, and the scene format reference is generated from it), and the way
//! back to text.

use std::path::PathBuf;

use schemars::JsonSchema;
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
#[derive(Clone, Debug, Default, PartialEq, Deserialize, Serialize, JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct VhParams {
    /// Human (default) or the seed's timing and perception; `Seed` sets
    /// the fields [`Profile::Seed`] lists, overriding values given here.
    pub profile: Profile,
    /// A level and style of opponent (`Some((level: Pro, style:
    /// Brawler))`); sets the fields it names over the ones given here.
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
    /// The face: mesh resolution, muscle database, an imported head.
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
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize, JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct FaceConfig {
    /// Mesh resolution of the generated head, latitude bands, a whole
    /// number (vertices ~ 2 rows^2: 32 ~ 2k, 48 (default) ~ 4.6k, 160 ~
    /// 51k). 24-400: fewer bands cannot carry the lips and lids, more
    /// (over 300k vertices) is far past what the eye sees on screen.
    #[schemars(range(min = 24, max = 400))]
    pub rows: usize,
    /// A muscle database (RON) replacing the shipped one, relative to the
    /// scene file (e.g. the output of `shisen face calibrate`).
    pub database: Option<PathBuf>,
    /// A user's head mesh (OBJ or GLB) instead of the generated one, relative
    /// to the scene file; needs `landmarks` too.
    pub mesh: Option<PathBuf>,
    /// The landmark file (RON) that places the muscles on `mesh`, relative
    /// to the scene file.
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

/// A scene file.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// Short name (defaults to the file stem).
    #[serde(default)]
    pub name: String,
    /// What the scene shows.
    #[serde(default)]
    pub description: String,
    /// Seed of every random stream: any whole number from 0 to 2^64 - 1;
    /// the same seed gives the same run.
    #[serde(default)]
    #[schemars(range(min = 0, max = u64::MAX))]
    pub seed: u64,
    /// Length of the run, s: at least one step (0.001 s), at most a day
    /// (86400 s; `scene::validate::MAX_DURATION`): longer is a typo, not
    /// a bout.
    #[schemars(range(min = 0.001, max = 86_400.0))]
    pub duration: f64,
    /// Gains file, relative to the scene file's folder.
    #[serde(default)]
    pub gains_file: Option<PathBuf>,
    /// Inline gains (give these or `gains_file`, not both).
    #[serde(default)]
    pub gains: Option<Gains>,
    /// The virtual human's parameters.
    #[serde(default)]
    pub vh: VhParams,
    /// Rounds and rests: the run is a bout (the VH goes to its corner
    /// in the rests).
    #[serde(default)]
    pub bout: Option<BoutParams>,
    /// Props: balls and boxes, scripted or simulated.
    #[serde(default)]
    pub bodies: Vec<BodySpec>,
    /// The timeline: what the opponent, the props and the VH's overrides
    /// do, and when.
    #[serde(default)]
    pub timeline: Vec<Event>,
    /// Expectations a headless run (`shisen test`) judges the run by.
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

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    /// What the bad-input probe found accepted (issue 31) is refused, at
    /// the field: turns and waves faster than a neck or a hand, props
    /// thrown at 1e300 m/s or weighing 1e+-300 kg, a fractional mesh.
    #[test]
    fn implausible_actions_props_and_rows_are_refused_at_their_field() {
        let scene = |body: &str| format!("Scene(\n duration: 2.0,\n {body}\n)");
        let ball = |extra: &str| {
            scene(&format!(
                "bodies: [(name: \"b\", shape: Ball(0.05), position: (0.0, 1.0, 1.0), {extra})],"
            ))
        };
        for (text, field) in [
            (
                scene("timeline: [(at: 0.5, do: TurnHead(yaw_deg: 3600.0, duration: 0.15))],"),
                "timeline[0].do.TurnHead.yaw_deg",
            ),
            (
                scene("timeline: [(at: 0.5, do: TurnHead(yaw_deg: 15.0, duration: 0.01))],"),
                "timeline[0].do.TurnHead.duration",
            ),
            (
                scene(
                    "timeline: [(at: 0.5, do: Wave(part: LeftGlove, amplitude: (0.1, 0.0, 0.0), frequency: 1e9, duration: 1.0))],",
                ),
                "timeline[0].do.Wave.frequency",
            ),
            (
                scene(
                    "timeline: [(at: 0.5, do: Punch(hand: Left, target: Head, speed: 5.0, through: 3.0))],",
                ),
                "timeline[0].do.Punch.through",
            ),
            (
                scene(
                    "timeline: [(at: 0.5, do: Punch(hand: Left, target: Point((0.0, 1e9, 0.0)), speed: 5.0))],",
                ),
                "timeline[0].do.Punch.target.Point[1]",
            ),
            (ball("velocity: (1e300, 0.0, 0.0)"), "bodies[0].velocity[0]"),
            (ball("mass: 1e300"), "bodies[0].mass"),
            (ball("mass: 1e-300"), "bodies[0].mass"),
            (
                scene(
                    "bodies: [(name: \"b\", shape: Box((0.1, 0.0, 0.1)), position: (0.0, 1.0, 1.0))],",
                ),
                "bodies[0].shape.Box[1]",
            ),
            (
                scene("expect: [AngleBelow(joint: NeckYaw, max_deg: 1000.0)],"),
                "expect[0].AngleBelow.max_deg",
            ),
            // A fraction where a whole number goes is a syntax error,
            // placed at the number.
            (scene("vh: (face: (rows: 48.5)),"), "vh.face.rows"),
            (scene("vh: (face: (rows: 4000)),"), "vh.face.rows"),
            (
                scene("vh: (effort: (breathing: (15.0, 1e6))),"),
                "vh.effort.breathing[1]",
            ),
            (scene("bout: Some((rounds: 2, round: 1e9)),"), "bout.round"),
        ] {
            let e = Scene::parse(&text, Path::new("t.ron"))
                .unwrap_err()
                .to_string();
            assert!(e.starts_with("t.ron:"), "{e}");
            assert!(e.contains(&format!("{field}:")), "want {field}: {e}");
        }
        let ok = scene("vh: (face: (rows: 48)),");
        assert_eq!(
            Scene::parse(&ok, Path::new("t.ron")).unwrap().vh.face.rows,
            48
        );
    }

    /// Every default of the scene's own types lies inside its range.
    #[test]
    fn defaults_are_inside_their_ranges() {
        use shisen_gaze::util::schema::violations;
        assert_eq!(violations(&FaceConfig::default()), vec![]);
        assert_eq!(violations(&VhParams::default()), vec![]);
        assert_eq!(violations(&BoutParams::default()), vec![]);
        assert_eq!(violations(&EffortParams::default()), vec![]);
    }
}
