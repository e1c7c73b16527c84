//! What a tick leaves behind: one [`Sample`] (a trace row), measured from
//! the world after the physics step by the record stage.

use glam::{DVec2, DVec3};

use super::blows::Blow;
use super::bout::{Bell, Phase};
use crate::physics::balance::Stance;
use shisen_face::tables::Emotion;
use shisen_gaze::attention::Source;
use shisen_gaze::behaviour::ActionKind;
use shisen_gaze::util::math::JointAngles;

/// Everything recorded about one tick (one trace row).
#[derive(Clone, Debug, PartialEq)]
pub struct Sample {
    /// Simulation time at the end of the tick, s.
    pub t: f64,
    /// The VH's action.
    pub action: ActionKind,
    /// What the action is about (attack target, incoming glove), if any.
    pub action_target: Option<String>,
    /// Gaze target name.
    pub gaze_target: String,
    /// Gaze point, world.
    pub gaze_point: DVec3,
    /// Who chose it.
    pub source: Source,
    /// Its attention amount.
    pub amount: f64,
    /// Eye joint targets (yaw, pitch), rad, left then right.
    pub eye_target: [DVec2; 2],
    /// Eye joint angles (yaw, pitch), rad.
    pub eye_actual: [DVec2; 2],
    /// Angle between each eye's line of sight and the gaze point, rad.
    pub los_error: [f64; 2],
    /// Ocular torsion (counter-roll, H9), rad, both eyes.
    pub torsion: f64,
    /// Each eye's line of sight minus its direction to the gaze point, as
    /// world (yaw, pitch) differences, rad: the signed gaze error.
    pub gaze_error: [DVec2; 2],
    /// Neck target angles.
    pub neck_target: JointAngles,
    /// Neck angles.
    pub neck_actual: JointAngles,
    /// Head forward direction in the world as (yaw, pitch), rad.
    pub head_world: DVec2,
    /// The head's angular speed in the world, rad/s.
    pub head_speed: f64,
    /// The head's centre, world, m.
    pub head: DVec3,
    /// The ground point under the waist joint (the pelvis), world, m.
    pub pelvis: DVec3,
    /// The waist's turn and bend, the trunk relative to the pelvis, rad
    /// (pitch positive back, roll positive toward the VH's right).
    pub waist: JointAngles,
    /// The fighting range: horizontal distance from the pelvis to the
    /// opponent's head, m.
    pub range: f64,
    /// The VH's heading (its body's turn about +Y from facing +Z), rad.
    pub heading: f64,
    /// Top saliency scores (body name, score), highest first.
    pub top_saliency: Vec<(String, f64)>,
    /// True if every body state is finite.
    pub finite: bool,
    /// True while the VH's punch is in flight.
    pub punching: bool,
    /// Opponent gloves touching the VH's head this tick.
    pub head_hit: bool,
    /// The face's current (target) emotion.
    pub emotion: Emotion,
    /// Upper-lid closure of the blink, 0 open to 1 shut.
    pub blink: f64,
    /// The physics blew up this tick and the VH was reset to rest.
    pub reset: bool,
    /// Blows (hits and blocks, both ways) decided this tick.
    pub blows: Vec<Blow>,
    /// Where the bout is (`None`: the run is no bout).
    pub phase: Option<Phase>,
    /// The bell rung this tick.
    pub bell: Option<Bell>,
    /// The VH's fatigue, 0 fresh to 1 exhausted (E1).
    pub fatigue: f64,
    /// Whether a blow has it staggered.
    pub staggered: bool,
    /// Up, falling, down or rising (B5; always up with a driven pelvis).
    pub stance: Stance,
    /// The whole body's centre of mass, world, m (with a driven pelvis:
    /// zero, not measured).
    pub com: DVec3,
}
