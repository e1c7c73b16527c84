//! The static side of a simulation, as MuJoCo separates `mjModel` from
//! `mjData`: the body plan, the props, the face and every stage's
//! parameters, built once (by the scene layer from a scene file, or by
//! hand); the simulation holds only what evolves.
//!
//! Live edits (the app's sliders, the tuning panel) change [`Params`]
//! through `Sim::edit_params`, the one documented path: the
//! new values are read from the next tick on. The rest of the model (plan,
//! props, face, step, seed) shapes the world when the simulation is built
//! and is fixed afterwards.

use std::sync::Arc;

use glam::DVec3;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::bout::BoutParams;
use super::effort::EffortParams;
use crate::physics::body::BodyPlan;
use crate::physics::control::Gains;
use crate::physics::lower::BodyParams;
use crate::physics::neck::NeckParams;
use shisen_face::Face;
use shisen_gaze::attention::AttentionParams;
use shisen_gaze::behaviour::BehaviourParams;
use shisen_gaze::oculomotor::OculomotorParams;
use shisen_gaze::personality::Personality;
use shisen_gaze::vision::VisionParams;

/// Physics and control rate. 1 kHz: explicit PD on a 7.5 g eyeball needs
/// omega_n dt << 1 (see physics/control.rs), a 500 deg/s saccade moves
/// 0.5 deg a step, and rapier still runs this model several times faster
/// than real time (see benches/step.rs).
pub const DT: f64 = 0.001;

/// Every parameter a running simulation may change between ticks.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Params {
    /// PD gains of the joint groups.
    pub gains: Gains,
    /// Attention amounts (top-down requests, head law's A1 and A2).
    pub personality: Personality,
    /// Action planner.
    pub behaviour: BehaviourParams,
    /// Field of view and saliency options.
    pub vision: VisionParams,
    /// Arbitration, habituation, minimum fixation.
    pub attention: AttentionParams,
    /// Saccade, pursuit and head laws.
    pub oculomotor: OculomotorParams,
    /// The neck under impact.
    pub neck: NeckParams,
    /// The lower body: stance, stepping, the waist.
    pub body: BodyParams,
    /// Effort over a bout: stamina, damage, what they change.
    pub effort: EffortParams,
}

/// Which defaults the VH's timing and perception follow (scene
/// `vh.profile`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, Serialize, JsonSchema)]
pub enum Profile {
    /// Human reaction times, pursuit limits, onset capture and blinking,
    /// each default citing its human source (docs/model/gaze.md "Human
    /// timing").
    #[default]
    Human,
    /// The seed papers' laws as printed, for their figures: no latencies
    /// (vision, saccades, pursuit, VOR, guard), pursuit gain 1, an ideal
    /// translational VOR and no counter-roll, no onset
    /// capture, blinks only in the neutral face at the thesis's rate, and
    /// the thesis's face: its linear lid, Waters' fields unspread, no
    /// wrinkles, lips that part with the jaw; a trunk on a stand that
    /// neither steps nor bends, and meets every punch with its guard.
    Seed,
}

impl Params {
    /// Set what `profile` fixes: for [`Profile::Seed`] the fields listed
    /// there, overriding any value given for them; [`Profile::Human`]
    /// changes nothing (the defaults are the human ones).
    pub fn apply_profile(&mut self, profile: Profile) {
        if profile == Profile::Seed {
            self.vision.latency = 0.0;
            self.oculomotor.timing = shisen_gaze::oculomotor::timing::TimingParams::seed();
            self.oculomotor.otolith = shisen_gaze::oculomotor::otolith::OtolithParams::seed();
            self.behaviour.guard_reaction = 0.0;
            self.attention.onset_gain = 0.0;
            self.neck.human = false;
            self.body.human = false;
            self.behaviour.footwork = false;
            self.personality.evade = 0.0;
            self.personality.counter = 0.0;
            self.effort.on = false;
        }
    }
}

/// The static description of one simulation.
#[derive(Clone, Debug)]
pub struct Model {
    /// Physics and control step, s.
    pub dt: f64,
    /// Seed of every random stream.
    pub seed: u64,
    /// The VH's segments and joints and the opponent's parts.
    pub plan: BodyPlan,
    /// Props added to the world.
    pub props: Vec<BodySpec>,
    /// The face (mesh, muscles, database), shared between runs.
    pub face: Arc<Face>,
    /// The stages' parameters (live-editable).
    pub params: Params,
    /// Rounds and rests, if the run is a bout (scene `bout`).
    pub bout: Option<BoutParams>,
}

impl Model {
    /// Set what `profile` fixes, in the parameters
    /// ([`Params::apply_profile`]) and the face's blinks (the seed blinks
    /// only when neutral, at the thesis's rate whatever the situation), lids
    /// (the thesis's linear lid), skin (it never wrinkles nor spreads a
    /// pull), lips (they part with the jaw whatever orbicularis oris
    /// does), reflexes (none: no blink or wince at a blow) and expressions
    /// (table D's, not the FACS prototypes).
    pub fn apply_profile(&mut self, profile: Profile) {
        self.params.apply_profile(profile);
        if profile != Profile::Seed {
            return;
        }
        let mut seed = self.face.params.clone();
        seed.blink.neutral_only = true;
        seed.blink.engaged_interval_scale = 1.0;
        seed.blink.arousal_gain = 0.0;
        seed.blink.levator_gain = 1.0;
        seed.blink.levator_max_raise_m = None;
        seed.blink.cheek_lid_rise_m = 0.0;
        seed.skin.wrinkle_spacing_m = 0.0;
        seed.skin.pull_spread_m = 0.0;
        seed.skin.thickening = 0.0;
        seed.skin.domain_fade_m = 0.0;
        seed.lips.seal_k = None;
        seed.lips.oris_width_share = None;
        seed.reflex.enabled = false;
        seed.prototypes = None;
        if seed != self.face.params {
            // The face is shared: rebuilt once here, not per run (the scene
            // loader applies the profile to the face it shares). The rig's
            // fields and the wrinkles' rest frames depend on the skin and
            // lip parameters, so the whole face is rebuilt on its mesh.
            let mesh = self.face.mesh.clone();
            self.face = Arc::new(Face::from_mesh(mesh, seed));
        }
    }

    /// A model with the default body plan, the generated face and default
    /// parameters at the standard step ([`DT`]).
    pub fn new(face: Arc<Face>, params: Params, seed: u64) -> Model {
        Model {
            dt: DT,
            seed,
            plan: BodyPlan::default(),
            props: Vec::new(),
            face,
            params,
            bout: None,
        }
    }
}

/// Shape of a prop.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize, JsonSchema)]
pub enum PropShape {
    /// Sphere of this radius, m. 0.001-5: from a bead to a wall, not a
    /// planet.
    Ball(#[schemars(range(min = 0.001, max = 5.0))] f64),
    /// Box with these half extents `(x, y, z)`, m; each 0.001-5, as a
    /// ball's radius.
    Box(#[schemars(with = "[f64; 3]", inner(range(min = 0.001, max = 5.0)))] DVec3),
}

/// A prop declared by the scene: a ball or a box, moved by the timeline
/// (`kinematic`) or by the physics.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BodySpec {
    /// Unique name (not an opponent part's, not `point` or
    /// `opponent_body`, not starting with `vh_`).
    pub name: String,
    /// Shape.
    pub shape: PropShape,
    /// Initial position `(x, y, z)`, world m; each coordinate within +-100 m
    /// of the origin (the room is a few metres across).
    #[schemars(with = "[f64; 3]", inner(range(min = -shisen_gaze::util::check::MAX_POSITION, max = shisen_gaze::util::check::MAX_POSITION)))]
    pub position: DVec3,
    /// Initial velocity `(x, y, z)` of a dynamic prop, m/s (default 0).
    /// Each within +-50 m/s: the fastest thrown balls (a pitched baseball)
    /// reach about 45 m/s.
    #[serde(default)]
    #[schemars(with = "[f64; 3]", inner(range(min = -50.0, max = 50.0)))]
    pub velocity: DVec3,
    /// Initial angular velocity `(x, y, z)` of a dynamic prop, rad/s
    /// (default 0). Each within +-500 rad/s: a pitched ball spins at up
    /// to about 300 rad/s (2900 rpm).
    #[serde(default)]
    #[schemars(with = "[f64; 3]", inner(range(min = -500.0, max = 500.0)))]
    pub angular_velocity: DVec3,
    /// Mass, kg (default 0.5). 0.001-200: from a 1 g bead to about twice a
    /// heavy bag (30-70 kg) or a heavyweight boxer.
    #[serde(default = "default_mass")]
    #[schemars(range(min = 0.001, max = 200.0))]
    pub mass: f64,
    /// Scripted (moved by `Move`, `Wave`, `Orbit`) rather than simulated
    /// (default false).
    #[serde(default)]
    pub kinematic: bool,
    /// Whether gravity acts on a dynamic prop (default true).
    #[serde(default = "yes")]
    pub gravity: bool,
}

fn default_mass() -> f64 {
    0.5
}

fn yes() -> bool {
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use shisen_face::mesh::MeshParams;
    use shisen_face::params::FaceParams;

    /// The seed profile's face is the thesis's all through: the rig is
    /// rebuilt without the skin's spread (S1) and the lip seal (O1), not
    /// only its parameters changed.
    #[test]
    fn the_seed_profile_rebuilds_the_face() {
        let face = Arc::new(Face::new(
            MeshParams { rows: 32 },
            FaceParams::default_params(),
        ));
        assert!(face.rig.lip_seal.seal_k.is_some());
        let mut model = Model::new(face, Params::default(), 0);
        model.apply_profile(Profile::Seed);
        let f = &model.face;
        assert_eq!(f.rig.lip_seal.seal_k, None);
        for ((_, g), field) in f.rig.muscles.iter().zip(&f.rig.fields) {
            for (&i, d) in field.index.iter().zip(&field.delta) {
                assert_eq!(*d, g.displacement(f.mesh.positions[i as usize], 1.0));
            }
        }
    }
}
