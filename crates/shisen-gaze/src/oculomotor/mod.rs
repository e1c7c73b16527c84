//! Oculomotor control (gaze.md sections 7-10): from a gaze point to eye and
//! neck joint targets.
//!
//! The laws live in the submodules, one place each: [`saccade`] (M2-M6),
//! [`pursuit`] (M7: pursuit, vergence, VOR), [`head`] (start rule, M8, M9),
//! [`takagi`] (T1), [`fixation`] (microsaccades) and [`otolith`] (the
//! translational VOR and counter-roll, H8-H9). This file composes
//! them into one controller:
//!
//! - **eyes**: while the retinal error stays small the binocular model (M7)
//!   runs; a new target, or an error above the start threshold (5 deg),
//!   starts a saccade planned from the current command to each eye's goal
//!   (hysteresis of gaze.md 8); when it ends, M7 resumes from where the
//!   saccade left the eyes;
//! - **head**: the start rule (beyond 30 deg; 20 ms after eye onset, or at
//!   once for top-down targets) plans a minimum-jerk move (M9) to the
//!   (M8) amplitude; the eyes counter-rotate through M7's VOR term, so the
//!   gaze stays on target;
//! - **expressive shifts**: with [`GazeShiftLaw::Takagi`] a new target is
//!   reached along Takagi & Takeda's sigmoid head and gaze tracks (T1), the
//!   eyes getting gaze - head, then M7 takes over.
//!
//! Conventions: `f64`, radians, seconds; a 2-D angle is
//! `DVec2 { x: yaw, y: pitch }` with yaw positive to the left and pitch
//! positive up (see [`crate::util::math::dir_from_yaw_pitch`]). Static parameters
//! (`*Params`) are kept apart from evolving state.

pub mod fixation;
pub mod head;
pub mod otolith;
pub mod pursuit;
pub mod saccade;
pub mod takagi;
pub mod timing;

use glam::{DQuat, DVec2, DVec3};
use rand::Rng;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::target::TargetId;
use crate::util::math::JointAngles;
use crate::util::math::{angle_between, dir_from_yaw_pitch, yaw_pitch_of};

use fixation::{FixationParams, FixationState};
use head::{HeadMove, HeadParams};
use otolith::{Otolith, OtolithParams};
use pursuit::{
    BinocularParams, BinocularState, EyeInput, angles_to, head_rate_from_angular_velocity,
};
use saccade::{Saccade, SaccadeParams};
use takagi::{GazeShift, Preset};
use timing::{Aim, TimingParams};

/// Largest eye velocity the laws may ask for, rad/s (about 1150 deg/s,
/// above any human eye movement: the largest saccades peak near 700 deg/s,
/// Bahill, Clark & Stark 1975, Math. Biosci. 24:191). A target
/// passing over an eye's pole (straight up or down in the head frame, e.g.
/// a glove above a ducking VH's eyes) swings its yaw through 180 deg within
/// a few ticks; the pursuit law (M7) then asked for hundreds of rad/s and
/// the eye was flung (a soak blow-up). Applied to the eyes' velocity
/// references, the command the joints receive.
const MAX_EYE_RATE: f64 = 20.0;

/// How the VH shifts its gaze to a new target.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, Serialize, JsonSchema)]
pub enum GazeShiftLaw {
    /// The reflexive laws: saccade (M2-M6), head start rule and (M8)/(M9).
    #[default]
    Reflex,
    /// A deliberate, expressive shift along Takagi & Takeda's sigmoid
    /// trajectories (T1) with a named preset; eye = gaze - head.
    Takagi(Preset),
    /// The same timing as the preset with constant angular velocity (the
    /// paper's linear baseline).
    Linear(Preset),
}

/// All oculomotor parameters (scene `vh.oculomotor`).
#[derive(Clone, Debug, Default, PartialEq, Deserialize, Serialize, JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct OculomotorParams {
    /// Saccade law and trigger thresholds.
    pub saccade: SaccadeParams,
    /// Binocular pursuit / vergence / VOR model.
    pub pursuit: BinocularParams,
    /// Head movement law.
    pub head: HeadParams,
    /// Microsaccades and drift while fixating (idle gaze).
    pub fixation: FixationParams,
    /// Law for shifts to new targets (commands may override it).
    pub gaze_shift: GazeShiftLaw,
    /// Human reaction times and pursuit limits in front of the laws
    /// ([`timing`]).
    pub timing: TimingParams,
    /// The otolith reflexes: translational VOR and counter-roll
    /// ([`otolith`]).
    pub otolith: OtolithParams,
}

/// What the controller needs to know this tick.
#[derive(Clone, Debug)]
pub struct GazeInput {
    /// Gaze point, world.
    pub point: DVec3,
    /// Identity of the gaze target (changes when attention switches).
    pub target: TargetId,
    /// Its attention amount A, with the personality's A1, A2 (M8).
    pub amount: head::Amount,
    /// Chosen top-down (or by override): the head may lead.
    pub top_down: bool,
    /// Head centre, world.
    pub head_pos: DVec3,
    /// Head orientation, world.
    pub head_rot: DQuat,
    /// Head angular velocity, world (the vestibular signal).
    pub head_angvel: DVec3,
    /// Torso orientation, world (the neck's parent).
    pub torso_rot: DQuat,
    /// Eye centres, world (left, right).
    pub eye_pos: [DVec3; 2],
    /// Measured eye angles (left, right).
    pub eye_angles: [DVec2; 2],
    /// Measured neck angles.
    pub neck_angles: JointAngles,
    /// Whether each eye sees the target (false: shut or occluded).
    pub visible: [bool; 2],
    /// The law for a shift to a new target.
    pub style: GazeShiftLaw,
    /// An imposed neck command (replaces the head law while present).
    pub neck_override: Option<AxisCommand>,
}

/// A 2-DOF (yaw, pitch) command with its rates and accelerations.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct AxisCommand {
    /// (yaw, pitch), rad.
    pub angles: DVec2,
    /// Rates, rad/s.
    pub rates: DVec2,
    /// Accelerations, rad/s^2.
    pub accel: DVec2,
}

/// The controller's output.
#[derive(Clone, Copy, Debug, Default)]
pub struct GazeOutput {
    /// Eye commands (left, right), relative to the head.
    pub eyes: [AxisCommand; 2],
    /// Neck command, relative to the torso.
    pub neck: AxisCommand,
    /// Ocular torsion (counter-roll, H9), rad, both eyes; about the line
    /// of sight, so it moves no line of sight (see [`otolith`]).
    pub torsion: f64,
}

/// A gaze saccade: each eye's plan lives in the *world* frame (the line of
/// sight in space), so a head that turns during the saccade is subtracted
/// (eye = gaze - head) instead of throwing the eye off target.
#[derive(Clone, Debug)]
enum EyeMode {
    Pursuit,
    Saccade {
        plans: Box<[Saccade; 2]>,
        t0: f64,
    },
    /// A Takagi/linear shift: head and gaze follow (T1) tracks from where
    /// they started; the eyes get gaze - head.
    Scripted {
        shift: Box<GazeShift>,
        t0: f64,
        eyes: [DVec2; 2],
        neck: DVec2,
    },
}

/// Where the laws aim this tick (step 1 of [`Oculomotor::step`]).
struct AimNow {
    /// The aimed point, world.
    point: DVec3,
    /// The cyclopean eye (midpoint of the eyes), world.
    cyclops: DVec3,
    /// Each eye's goal (yaw, pitch) in the felt head frame, within range.
    goal: [DVec2; 2],
    /// How fast the goals move, rad/s (zero on a new target).
    goal_rate: [DVec2; 2],
    /// The aim moved to a new target this tick.
    new_target: bool,
    /// The aim jumped to a target it had fallen behind (H3).
    catch_up: bool,
    /// The eyes have been off the target, as vision sees it, long enough
    /// for a corrective saccade (H7).
    corrective: bool,
    /// The inverse of the head's orientation as the vestibular signal reports it.
    felt_inv: DQuat,
    /// The head's angular velocity as reported, world.
    head_angvel: DVec3,
    /// The eyes' range (yaw, pitch), rad.
    range: DVec2,
}

/// The world direction of eye angles `a` (head frame) with the head as it is.
fn world_dir(input: &GazeInput, a: DVec2) -> DVec3 {
    input.head_rot * dir_from_yaw_pitch(a.x, a.y)
}

/// The controller's evolving state.
#[derive(Clone, Debug)]
pub struct Oculomotor {
    mode: EyeMode,
    pursuit: BinocularState,
    head: Option<(HeadMove, f64)>,
    aim: Aim,
    eye_onset: f64,
    prev_goal: Option<[DVec2; 2]>,
    fixation: FixationState,
    otolith: Otolith,
    out: GazeOutput,
    /// Saccades started so far.
    pub saccades: u32,
    started: Option<f64>,
    /// Head movements started so far.
    pub head_moves: u32,
    /// Time the last head movement was planned (its onset), s.
    pub head_onset: f64,
}

impl Oculomotor {
    /// Eyes and head straight ahead.
    pub fn new(p: &OculomotorParams, rng: &mut impl Rng) -> Self {
        Oculomotor {
            fixation: FixationState::new(&p.fixation, rng),
            mode: EyeMode::Pursuit,
            pursuit: BinocularState::new(DVec2::ZERO, DVec2::ZERO),
            head: None,
            aim: Aim::default(),
            eye_onset: f64::NEG_INFINITY,
            prev_goal: None,
            otolith: Otolith::default(),
            out: GazeOutput::default(),
            saccades: 0,
            started: None,
            head_moves: 0,
            head_onset: f64::NEG_INFINITY,
        }
    }

    /// The amplitude (rad) of a saccade that started in the last step.
    pub fn saccade_started(&self) -> Option<f64> {
        self.started
    }

    /// Time the last eye movement (saccade or scripted shift) began, s.
    pub fn eye_onset(&self) -> f64 {
        self.eye_onset
    }

    /// Advance one tick, in named steps: where to aim (reaction time,
    /// pursuit drive, vestibular signal), a scripted gaze shift or a
    /// saccade to start, the eyes' command in the current mode, the head's
    /// (start rule, M8, M9), and an imposed neck motion over it all.
    pub fn step(
        &mut self,
        p: &OculomotorParams,
        input: &GazeInput,
        t: f64,
        dt: f64,
        rng: &mut impl Rng,
    ) -> GazeOutput {
        let aim = self.aim_step(p, input, t, dt, rng);
        let prev = self.out;
        self.started = None;
        if aim.new_target
            && let GazeShiftLaw::Takagi(preset) | GazeShiftLaw::Linear(preset) = input.style
        {
            self.begin_scripted_shift(input, &aim, preset, t);
        }
        if let EyeMode::Pursuit = self.mode {
            self.maybe_start_saccade(p, input, &aim, t);
        }
        let (mut eyes, mut neck, scripted_neck) = self.eye_commands(p, input, &aim, t, dt, rng);
        for (eye, before) in eyes.iter_mut().zip(prev.eyes) {
            eye.rates = eye.rates.clamp_length_max(MAX_EYE_RATE);
            eye.accel = (eye.rates - before.rates) / dt;
        }
        if !scripted_neck {
            self.head_step(p, input, aim.point, &mut neck, t, dt);
        }
        if let Some(imposed) = input.neck_override {
            // The head is moved from outside (a test's shake): the laws
            // above keep running and the eyes must compensate (VOR).
            neck = imposed;
            self.head = None;
        }
        let torsion =
            self.otolith
                .counter_roll(&p.otolith, aim.felt_inv.inverse(), aim.head_angvel, dt); // (H9)
        self.out = GazeOutput {
            eyes,
            neck,
            torsion,
        };
        self.out
    }

    /// Step 1, where the laws aim: the target once its reaction time is
    /// over, moved by the pursuit drive between saccades (timing.rs,
    /// H1-H3); each eye's goal in the head frame as the vestibular signal
    /// reports it (H4), seen from where the otoliths report the eyes (H8),
    /// and how fast the goals move.
    fn aim_step(
        &mut self,
        p: &OculomotorParams,
        input: &GazeInput,
        t: f64,
        dt: f64,
        rng: &mut impl Rng,
    ) -> AimNow {
        let range = DVec2::new(p.pursuit.yaw_range, p.pursuit.pitch_range);
        let cyclops = (input.eye_pos[0] + input.eye_pos[1]) / 2.0;
        let aim = self
            .aim
            .step(&p.timing, input.point, input.target, cyclops, t, dt, rng);
        let target = aim.point;
        let (felt_rot, head_angvel) =
            self.aim
                .vestibular(&p.timing, input.head_rot, input.head_angvel, dt); // (H4)
        let felt_inv = felt_rot.inverse();
        let point = felt_inv * target;
        let felt_eyes = self.otolith.felt_eyes(&p.otolith, input.eye_pos, dt); // (H8)
        let goal = felt_eyes.map(|c| angles_to(felt_inv * c, point).clamp(-range, range));
        let goal_rate = match self.prev_goal {
            Some(prev) if !aim.new_target => [(goal[0] - prev[0]) / dt, (goal[1] - prev[1]) / dt],
            _ => [DVec2::ZERO; 2],
        };
        self.prev_goal = Some(goal);
        // (H7): where the eyes point against where the target is, with the
        // head as it really is (what the retina reports), while pursuing.
        let corrective = matches!(self.mode, EyeMode::Pursuit) && {
            let (l, r) = self.pursuit.angles();
            let true_inv = input.head_rot.inverse();
            let off = [l, r]
                .into_iter()
                .zip(input.eye_pos)
                .map(|(e, c)| {
                    let seen = angles_to(true_inv * c, true_inv * target).clamp(-range, range);
                    (seen - e).length()
                })
                .fold(0.0, f64::max);
            self.aim.corrective(&p.timing, off, t)
        };
        AimNow {
            point: target,
            cyclops,
            goal,
            goal_rate,
            new_target: aim.new_target,
            catch_up: aim.catch_up,
            corrective,
            felt_inv,
            head_angvel,
            range,
        }
    }

    /// Step 2a, a Takagi or linear shift to a new target (T1): head and gaze
    /// follow the preset's tracks from where they are now.
    fn begin_scripted_shift(&mut self, input: &GazeInput, aim: &AimNow, preset: Preset, t: f64) {
        let prev = self.out;
        // Target relative to the current line of sight, torso frame
        // (yaw and pitch of the cyclopean direction), in degrees.
        let torso_inv = input.torso_rot.inverse();
        let mean = (prev.eyes[0].angles + prev.eyes[1].angles) / 2.0;
        let (ly, lp) = yaw_pitch_of(torso_inv * world_dir(input, mean));
        let (ty, tp) = yaw_pitch_of(torso_inv * (aim.point - aim.cyclops));
        let delta = DVec2::new(ty - ly, tp - lp);
        let mut shift = preset.build(delta * (180.0 / std::f64::consts::PI));
        if let GazeShiftLaw::Linear(_) = input.style {
            shift = shift.linear_baseline();
        }
        self.mode = EyeMode::Scripted {
            shift: Box::new(shift),
            t0: t,
            eyes: [prev.eyes[0].angles, prev.eyes[1].angles],
            neck: prev.neck.angles,
        };
        self.head = None;
        self.eye_onset = t;
    }

    /// Step 2b, from pursuit: a saccade when the aim jumped (a new target,
    /// a catch-up) or the eyes fell too far behind it, planned in world
    /// (yaw, pitch) from where each eye points now to the gaze point as
    /// seen from that eye (M2-M6 along the great circle).
    fn maybe_start_saccade(
        &mut self,
        p: &OculomotorParams,
        input: &GazeInput,
        aim: &AimNow,
        t: f64,
    ) {
        let (l, r) = self.pursuit.angles();
        let err = [aim.goal[0] - l, aim.goal[1] - r];
        let max_err = err[0].length().max(err[1].length());
        let jump = (aim.new_target || aim.catch_up) && max_err > p.saccade.new_target_threshold;
        if !(jump || aim.corrective || p.saccade.should_start(max_err)) {
            return;
        }
        self.aim.anchor();
        self.otolith.anchor();
        let prev = self.out;
        let plans = [0, 1].map(|k| {
            let (sy, sp) = yaw_pitch_of(world_dir(input, prev.eyes[k].angles));
            let (gy, gp) = yaw_pitch_of(aim.point - input.eye_pos[k]);
            Saccade::plan(&p.saccade, DVec2::new(sy, sp), DVec2::new(gy, gp))
        });
        self.mode = EyeMode::Saccade {
            plans: Box::new(plans),
            t0: t,
        };
        self.eye_onset = t;
        self.saccades += 1;
        self.started = Some(plans[0].amplitude().max(plans[1].amplitude()));
    }

    /// Step 3, the eyes' command in the current mode: a scripted shift's
    /// tracks (T1, which also set the neck: the flag returned), a
    /// saccade's world plan seen from the head now, or pursuit, vergence
    /// and VOR (M7) with fixational eye movements on top.
    fn eye_commands(
        &mut self,
        p: &OculomotorParams,
        input: &GazeInput,
        aim: &AimNow,
        t: f64,
        dt: f64,
        rng: &mut impl Rng,
    ) -> ([AxisCommand; 2], AxisCommand, bool) {
        let prev = self.out;
        let range = aim.range;
        let mut eyes = prev.eyes;
        let mut neck = prev.neck;
        let mut scripted_neck = false;
        match &self.mode {
            EyeMode::Scripted {
                shift,
                t0,
                eyes: eye0,
                neck: neck0,
            } => {
                // (T1): head and gaze tracks (radians; the presets take
                // degrees); eye = gaze - head, on top of
                // where each eye started (their vergence is kept).
                let s = t + dt - t0;
                let smp = shift.sample(s);
                for k in 0..2 {
                    eyes[k].angles = (eye0[k] + smp.eye).clamp(-range, range);
                    eyes[k].rates = smp.eye_rate;
                }
                neck.angles = p.head.limits.clamp(*neck0 + smp.head);
                neck.rates = smp.head_rate;
                neck.accel = (neck.rates - prev.neck.rates) / dt;
                scripted_neck = true;
                if s >= shift.end() {
                    self.pursuit.reset(eyes[0].angles, eyes[1].angles);
                    self.fixation.reset(&p.fixation, rng);
                    self.mode = EyeMode::Pursuit;
                }
            }
            EyeMode::Saccade { plans, t0 } => {
                let s = t + dt - t0;
                let head_inv = input.head_rot.inverse();
                for k in 0..2 {
                    // eye = gaze - head: the world plan seen from the head now.
                    let d = head_inv * plans[k].direction(s.min(plans[k].duration()));
                    let (y, pt) = yaw_pitch_of(d);
                    let a = DVec2::new(y, pt).clamp(-range, range);
                    eyes[k].rates = (a - prev.eyes[k].angles) / dt;
                    eyes[k].angles = a;
                }
                if s >= plans[0].duration().max(plans[1].duration()) {
                    self.pursuit.reset(eyes[0].angles, eyes[1].angles);
                    self.fixation.reset(&p.fixation, rng);
                    self.mode = EyeMode::Pursuit;
                }
            }
            EyeMode::Pursuit => {
                let (l, r) = self.pursuit.angles();
                // Accommodation: each seeing eye knows how far it focuses,
                // which lets an occluded partner keep converging (pursuit.rs).
                // Focus distance from the head-frame origin, the midpoint
                // between the eyes (pursuit.rs's convention).
                let focus = (aim.point - aim.cyclops).length();
                let inputs = [(aim.goal[0] - l, 0), (aim.goal[1] - r, 1)].map(|(e, k)| {
                    if input.visible[k] {
                        EyeInput::seen(e, aim.goal_rate[k]).with_focus(focus)
                    } else {
                        EyeInput::occluded()
                    }
                });
                let w = head_rate_from_angular_velocity(aim.felt_inv * aim.head_angvel);
                let (l, r) = self.pursuit.step(&p.pursuit, dt, &inputs[0], &inputs[1], w);
                let (rl, rr) = self.pursuit.rates();
                // Idle gaze: conjugate microsaccades and drift on top.
                let fix = self.fixation.step(&p.fixation, dt, rng);
                eyes[0].angles = (l + fix.offset).clamp(-range, range);
                eyes[1].angles = (r + fix.offset).clamp(-range, range);
                eyes[0].rates = rl + fix.rate;
                eyes[1].rates = rr + fix.rate;
            }
        }
        (eyes, neck, scripted_neck)
    }

    /// Step 4, the head (when no scripted shift moves it): the start rule,
    /// then (M8) amplitude and (M9) trajectory toward `target`.
    fn head_step(
        &mut self,
        p: &OculomotorParams,
        input: &GazeInput,
        target: DVec3,
        neck: &mut AxisCommand,
        t: f64,
        dt: f64,
    ) {
        let torso_inv = input.torso_rot.inverse();
        let face_fwd = input.head_rot * DVec3::Z;
        let to_point = (target - input.head_pos).normalize_or(face_fwd);
        let from_face = angle_between(face_fwd, to_point);
        let moving = self
            .head
            .as_ref()
            .is_some_and(|(m, t0)| t < t0 + m.duration());
        if !moving
            && !matches!(self.mode, EyeMode::Scripted { .. })
            && p.head
                .should_start(from_face, t - self.eye_onset, input.top_down)
        {
            let (y, pt) = yaw_pitch_of(torso_inv * to_point);
            let goal = p.head.target(DVec2::new(y, pt), input.amount);
            // Re-planning toward where the head already is would be a no-op.
            if (goal - neck.angles).length() > p.saccade.start_threshold / 2.0 {
                let plan = HeadMove::plan(&p.head, neck.angles, goal);
                self.head = Some((plan, t));
                self.head_moves += 1;
                self.head_onset = t;
            }
        }
        if let Some((m, t0)) = &self.head {
            let smp = m.sample(t + dt - t0);
            neck.angles = smp.angles;
            neck.rates = smp.rate;
            neck.accel = smp.accel;
        }
    }
}
