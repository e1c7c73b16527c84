//! What a tick leaves behind: one [`Sample`] (a trace row), measured from
//! the world after the physics step.

use glam::{DVec2, DVec3, Vec3};

use super::Sim;
use crate::agent::attention::{GazeChoice, Source};
use crate::agent::behaviour::ActionKind;
use crate::face::tables::Emotion;
use crate::physics::body::seg;
use crate::physics::world::opp;
use crate::util::math::{JointAngles, angle_between, yaw_pitch_of};

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
    /// Each eye's line of sight minus its direction to the gaze point, as
    /// world (yaw, pitch) differences, rad: the signed gaze error.
    pub gaze_error: [DVec2; 2],
    /// Neck target angles.
    pub neck_target: JointAngles,
    /// Neck angles.
    pub neck_actual: JointAngles,
    /// Head forward direction in the world as (yaw, pitch), rad.
    pub head_world: DVec2,
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
}

impl Sim {
    /// Record stage: measure the tick's outcome.
    pub(super) fn sample(
        &self,
        choice: &GazeChoice,
        eye_target: &[DVec2; 2],
        neck_target: JointAngles,
    ) -> Sample {
        let w = &self.world;
        let mut los_error = [0.0; 2];
        let mut gaze_error = [DVec2::ZERO; 2];
        let mut eye_actual = [DVec2::ZERO; 2];
        for (k, s) in [seg::EYE_L, seg::EYE_R].into_iter().enumerate() {
            let rb = w.seg(s);
            let los = (*rb.rotation() * Vec3::Z).as_dvec3();
            let to = (choice.point - rb.translation().as_dvec3()).normalize_or(DVec3::Z);
            los_error[k] = angle_between(los, to);
            let (ly, lp) = yaw_pitch_of(los);
            let (ty, tp) = yaw_pitch_of(to);
            gaze_error[k] = DVec2::new(ly - ty, lp - tp);
            let a = w.joint_angles(s);
            eye_actual[k] = DVec2::new(a.yaw, a.pitch);
        }
        let head_fwd = (*w.seg(seg::HEAD).rotation() * Vec3::Z).as_dvec3();
        let (hy, hp) = yaw_pitch_of(head_fwd);
        let mut top: Vec<(String, f64)> = self
            .seen
            .iter()
            .map(|s| (self.names[s.body].clone(), self.attention.scores[s.body]))
            .collect();
        top.sort_by(|a, b| b.1.total_cmp(&a.1).then_with(|| a.0.cmp(&b.0)));
        top.truncate(3);
        let head_body = seg::HEAD;
        let head_hit = [opp::LEFT_GLOVE, opp::RIGHT_GLOVE]
            .iter()
            .any(|&g| w.in_contact(w.opponent[g], head_body));
        Sample {
            t: self.time(),
            action: self.behaviour.action(),
            action_target: self.behaviour.target_name(&self.names).map(String::from),
            gaze_target: choice.name.clone(),
            gaze_point: choice.point,
            source: choice.source,
            amount: choice.amount,
            eye_target: *eye_target,
            eye_actual,
            los_error,
            gaze_error,
            neck_target,
            neck_actual: w.joint_angles(seg::HEAD),
            head_world: DVec2::new(hy, hp),
            top_saliency: top,
            finite: w.is_finite(),
            punching: self.behaviour.punching(),
            head_hit,
            emotion: self.face_state.emotion,
            blink: self.face_state.blink.closure(&self.model.face.params.blink),
            reset: false,
        }
    }
}
