//! One simulation: the world plus the VH's brain, stepped at a fixed rate
//! in simulation time. [`Sim::step`] runs the pipeline of gaze.md 1 as
//! named stages: timeline -> sense (vision) -> decide (behaviour) ->
//! attend (attention) -> move the gaze (oculomotor) -> face -> arms ->
//! actuate and integrate (PD joints, physics) -> record a [`Sample`].
//!
//! The static description lives in a [`Model`]; `Sim` holds only what
//! evolves.

pub mod blows;
pub mod expect;
pub mod model;
mod sample;
pub mod timeline;
pub mod track;

use glam::{DVec2, DVec3, Quat, Vec3};
use rand::SeedableRng;
use rand::rngs::StdRng;

use crate::agent::attention::{Attention, GazeChoice, Source};
use crate::agent::behaviour::{ActionKind, Behaviour, EYES_ON_TARGET, OpponentView, TopDown};
use crate::agent::oculomotor::head::Amount;
use crate::agent::oculomotor::{GazeInput, GazeOutput, Oculomotor};
use crate::agent::vision::{Seen, see};
use crate::face::FaceState;
use crate::physics::body::{Shape, arm_ik, seg};
use crate::physics::control::JointTarget;
use crate::physics::world::opp;
use crate::physics::world::{PropSpec, World};
use crate::util::delay::DelayLine;
use crate::util::math::{JointAngles, angle_between, yaw_pitch_of};
use blows::{Blows, Tally};
pub use model::{BodySpec, DT, Model, Params, Profile, PropShape};
pub use sample::Sample;
use timeline::{Event, Timeline};
use track::Track;

/// Largest reference angular speed of an arm joint, rad/s (elbow extension
/// in a punch peaks around 20-40 rad/s).
const ARM_MAX_RATE: f32 = 40.0;

/// Angular speed (rad/s) of a VH segment taken as a physics explosion.
pub const BLOW_UP_ANGVEL: f32 = 200.0;

/// The VH counts as sparring (for its blink rate) until this long after
/// it last guarded or attacked, s: longer than the gaps between actions in
/// a bout (attacks come every few seconds), shorter than a pause.
const SPARRING_HOLD: f64 = 5.0;

/// Independent random streams, one per consumer, all derived from the
/// scene seed, so adding draws to one never shifts another.
struct Streams {
    behaviour: StdRng,
    oculomotor: StdRng,
    face: StdRng,
}

impl Streams {
    fn new(seed: u64) -> Self {
        let derive = |k: u64| StdRng::seed_from_u64(seed ^ k.wrapping_mul(0x9E37_79B9_7F4A_7C15));
        Streams {
            behaviour: derive(1),
            oculomotor: derive(2),
            face: derive(3),
        }
    }
}

/// A running simulation: the evolving state of one [`Model`].
pub struct Sim {
    model: Model,
    /// The physics world.
    pub world: World,
    tick: u64,
    timeline: Timeline,
    /// Attention state.
    pub attention: Attention,
    /// Action planner state.
    pub behaviour: Behaviour,
    /// Eye and head control state.
    pub oculomotor: Oculomotor,
    /// The face's evolving state (expression, blinks).
    pub face_state: crate::face::FaceState,
    /// What the eyes see this tick.
    sight: Vec<Seen>,
    /// What the stages act on: the sight of `vision.latency` ago.
    seen: Vec<Seen>,
    percept: DelayLine<Vec<Seen>>,
    /// When the VH last guarded or attacked, s.
    last_action: f64,
    targets: Vec<JointTarget>,
    rng: Streams,
    names: Vec<String>,
    /// The gaze target both eyes were on (line of sight within
    /// [`EYES_ON_TARGET`]) at the end of the last tick.
    fixated: Option<String>,
    /// Times the VH was reset after a physics explosion.
    pub resets: u32,
    /// Hits and blocks both ways.
    blows: Blows,
    last: Option<Sample>,
}

/// What the move-the-gaze stage produced, for the stages after it.
struct GazeStep {
    choice: GazeChoice,
    out: GazeOutput,
    eye_angles: [DVec2; 2],
}

impl Sim {
    /// Start a simulation of `model` with a timeline (sorted here; events
    /// at equal times keep their order).
    pub fn new(model: Model, timeline: &[Event]) -> Self {
        let mut world = World::new(model.plan.clone(), model.dt);
        let blows = Blows::new(&world);
        let mut scripted = Vec::new();
        for k in 0..3 {
            let b = world.opponent[k];
            scripted.push((b, world.position(b).as_dvec3()));
        }
        for b in &model.props {
            let shape = match b.shape {
                PropShape::Ball(r) => Shape::Ball { radius: r as f32 },
                PropShape::Box(h) => Shape::Cuboid { half: h.as_vec3() },
            };
            let idx = world.add_prop(&PropSpec {
                name: b.name.clone(),
                shape,
                position: b.position.as_vec3(),
                velocity: b.velocity.as_vec3(),
                angvel: b.angular_velocity.as_vec3(),
                mass: b.mass as f32,
                kinematic: b.kinematic,
                gravity: b.gravity,
            });
            if b.kinematic {
                scripted.push((idx, b.position));
            }
        }
        let names: Vec<String> = world.bodies.iter().map(|b| b.name.clone()).collect();
        let mut targets = vec![JointTarget::default(); model.plan.segments.len()];
        let behaviour = Behaviour::new();
        for (k, q) in arm_rotations(behaviour.glove_targets(0.0)) {
            targets[k].rotation = q;
        }
        let mut rng = Streams::new(model.seed);
        Sim {
            face_state: FaceState::default(),
            oculomotor: Oculomotor::new(&model.params.oculomotor, &mut rng.oculomotor),
            rng,
            model,
            world,
            tick: 0,
            timeline: Timeline::new(timeline, &scripted),
            attention: Attention::new(names.clone()),
            behaviour,
            sight: Vec::new(),
            seen: Vec::new(),
            percept: DelayLine::new(),
            last_action: f64::NEG_INFINITY,
            targets,
            names,
            fixated: None,
            resets: 0,
            blows,
            last: None,
        }
    }

    /// The static description being simulated.
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// The parameters in force.
    pub fn params(&self) -> &Params {
        &self.model.params
    }

    /// Change parameters while running: the one path for live edits (app
    /// sliders, tuning). Every stage reads the new values from the next
    /// tick on; nothing is derived from them at construction, so nothing
    /// goes stale.
    pub fn edit_params(&mut self, edit: impl FnOnce(&mut Params)) {
        edit(&mut self.model.params);
    }

    /// Simulation time now, s.
    pub fn time(&self) -> f64 {
        self.tick as f64 * self.model.dt
    }

    /// Hits landed and punches blocked so far, both ways.
    pub fn tally(&self) -> Tally {
        self.blows.tally
    }

    /// The last recorded sample.
    pub fn last(&self) -> Option<&Sample> {
        self.last.as_ref()
    }

    /// Bodies in view as the VH's stages perceived them in the last tick
    /// (the sight of `vision.latency` ago).
    pub fn seen(&self) -> &[Seen] {
        &self.seen
    }

    /// The kinematic track of a body, if it has one.
    pub fn track_mut(&mut self, body: usize) -> Option<&mut Track> {
        self.timeline.track_mut(body)
    }

    /// Recover from a physics explosion: the VH back at rest in its rest
    /// pose, its controllers restarted; the opponent, props and the scene's
    /// timeline carry on. Counted in [`Sim::resets`].
    pub fn reset_vh(&mut self, why: &str) {
        if self.resets.is_power_of_two() || self.resets == 0 {
            tracing::warn!(
                t = self.time(),
                resets = self.resets + 1,
                "physics blew up ({why}): VH reset to rest"
            );
        }
        self.world.reset_vh();
        self.oculomotor = Oculomotor::new(&self.model.params.oculomotor, &mut self.rng.oculomotor);
        self.behaviour = Behaviour::new();
        for t in &mut self.targets {
            *t = JointTarget::default();
        }
        self.resets += 1;
    }

    /// Schedule a timeline event while running (live input). It runs in
    /// the tick at its time, after the scene's own events of that time,
    /// exactly as if it had been appended to the scene's timeline, so a
    /// recorded session replays tick for tick. Events in the past run in
    /// the next tick.
    pub fn push_event(&mut self, ev: Event) {
        self.timeline.push(ev);
    }

    /// Advance one tick and return its sample.
    pub fn step(&mut self) -> &Sample {
        let t = self.time();
        let dt = self.model.dt;
        self.timeline
            .run(t, &self.world, &self.model.face, &mut self.face_state);
        self.timeline.drive(&mut self.world, t, dt);
        self.sense();
        let top_down = self.decide(t);
        let choice = self.attend(&top_down, t);
        let gaze = self.move_gaze(choice, t);
        self.animate_face(&gaze);
        self.plan_arms(t);
        let reset = self.actuate_and_integrate();
        self.record(&gaze, reset)
    }

    /// Sense: the bodies in view through the open eyes, with saliency (M1);
    /// the later stages get them `vision.latency` late.
    fn sense(&mut self) {
        let open = self.timeline.occluded.map(|o| !o);
        let vision = &self.model.params.vision;
        see(&self.world, vision, open, &mut self.sight);
        if vision.latency > 0.0 {
            self.seen = self
                .percept
                .push(self.sight.clone(), vision.latency, self.model.dt);
        } else {
            std::mem::swap(&mut self.seen, &mut self.sight);
        }
    }

    /// Decide: the action planner's top-down request and glove plans.
    fn decide(&mut self, t: f64) -> TopDown {
        let head_c = self.world.seg(seg::HEAD).translation().as_dvec3();
        let torso_c = self.world.seg(seg::TORSO).translation().as_dvec3();
        let view = OpponentView {
            seen: &self.seen,
            names: &self.names,
            eyes_on: self.fixated.as_ref(),
            parts: self.world.opponent,
            vh_points: [head_c, torso_c, (head_c + torso_c) / 2.0],
        };
        let p = &self.model.params;
        self.behaviour.step(
            &p.behaviour,
            &p.personality,
            &view,
            t,
            self.model.dt,
            &mut self.rng.behaviour,
        )
    }

    /// Attend: attention's choice, or the scene's override while in force.
    /// Attention always runs (its scores and habituation stay live).
    fn attend(&mut self, top_down: &TopDown, t: f64) -> GazeChoice {
        let world = &self.world;
        let body_pos = |b: usize| world.position(b).as_dvec3();
        let p = &self.model.params;
        let chosen = self.attention.step(
            &p.attention,
            &self.seen,
            top_down,
            body_pos,
            t,
            self.model.dt,
        );
        match &self.timeline.look_at {
            Some(o) if t < o.until => {
                let c = GazeChoice {
                    name: o.body.map_or("point".into(), |b| self.names[b].clone()),
                    body: o.body,
                    point: o.body.map_or(o.point, body_pos),
                    amount: o.amount.unwrap_or(p.personality.a2),
                    source: Source::Override,
                };
                self.attention.force(c.clone(), t);
                c
            }
            _ => chosen,
        }
    }

    /// Move the gaze: the oculomotor's eye and neck commands, set as the
    /// eye and neck joint targets.
    fn move_gaze(&mut self, choice: GazeChoice, t: f64) -> GazeStep {
        let dt = self.model.dt;
        let p = &self.model.params;
        let head = self.world.seg(seg::HEAD);
        let input = GazeInput {
            point: choice.point,
            target_id: target_id(&choice),
            amount: Amount {
                value: choice.amount,
                least: p.personality.a1,
                most: p.personality.a2,
            },
            top_down: choice.source != Source::BottomUp,
            head_pos: head.translation().as_dvec3(),
            head_rot: head.rotation().as_dquat(),
            head_angvel: head.angvel().as_dvec3(),
            torso_rot: self.world.seg(seg::TORSO).rotation().as_dquat(),
            eye_pos: [seg::EYE_L, seg::EYE_R].map(|e| self.world.seg(e).translation().as_dvec3()),
            eye_angles: [seg::EYE_L, seg::EYE_R].map(|e| {
                let a = self.world.joint_angles(e);
                DVec2::new(a.yaw, a.pitch)
            }),
            neck_angles: self.world.joint_angles(seg::HEAD),
            visible: self.timeline.occluded.map(|o| !o),
            style: self
                .timeline
                .look_at
                .as_ref()
                .filter(|o| t < o.until)
                .and_then(|o| o.style)
                .unwrap_or(p.oculomotor.gaze_shift),
            neck_override: self
                .timeline
                .shake
                .filter(|s| t < s.until)
                .map(|s| s.command(t + dt)),
        };
        let out = self
            .oculomotor
            .step(&p.oculomotor, &input, t, dt, &mut self.rng.oculomotor);
        for (k, s) in [seg::EYE_L, seg::EYE_R].into_iter().enumerate() {
            let e = out.eyes[k];
            self.targets[s] = JointTarget::yaw_pitch(e.angles, e.rates, e.accel);
        }
        let n = out.neck;
        self.targets[seg::HEAD] = JointTarget::yaw_pitch(n.angles, n.rates, n.accel);
        GazeStep {
            choice,
            out,
            eye_angles: input.eye_angles,
        }
    }

    /// Face: lids follow the eyes' pitch; a large gaze shift may blink.
    fn animate_face(&mut self, gaze: &GazeStep) {
        let face = &self.model.face;
        if let Some(amplitude) = self.oculomotor.saccade_started() {
            self.face_state
                .gaze_shift(face, amplitude.to_degrees(), &mut self.rng.face);
        }
        self.face_state.eye_pitch = gaze.eye_angles.map(|a| a.y as f32);
        let t = self.time();
        if self.behaviour.action() != ActionKind::Idle {
            self.last_action = t;
        }
        self.face_state.engaged = t - self.last_action < SPARRING_HOLD;
        self.face_state
            .step(face, self.model.dt, &mut self.rng.face);
    }

    /// Arms: inverse kinematics of the planned glove positions; the
    /// velocity reference comes from differencing the IK solution.
    fn plan_arms(&mut self, t: f64) {
        let dt = self.model.dt;
        // The torso's lunge moves the shoulders: the arms' inverse
        // kinematics works from where the torso will be.
        let lunge = self.behaviour.torso_offset(t + dt);
        self.world.set_root_offset(lunge.as_vec3());
        let gloves = self.behaviour.glove_targets(t + dt).map(|g| g - lunge);
        for (k, q) in arm_rotations(gloves) {
            let prev = self.targets[k].rotation;
            let mut d = q * prev.inverse();
            if d.w < 0.0 {
                d = -d;
            }
            // Capped at a fast human limb's rate: where the IK solution
            // jumps (a new reach, a swivel flip) the difference is not a
            // velocity, and a huge reference would fling the arm.
            let velocity = (d.to_scaled_axis() / dt as f32).clamp_length_max(ARM_MAX_RATE);
            self.targets[k] = JointTarget {
                rotation: q,
                velocity,
                acceleration: Vec3::ZERO,
            };
        }
    }

    /// Actuate and integrate: PD torques toward the targets, one physics
    /// step, and recovery if it blew up. Returns whether the VH was reset.
    fn actuate_and_integrate(&mut self) -> bool {
        self.world
            .apply_control(&self.model.params.gains, &self.targets);
        self.world.step();
        self.tick += 1;
        let blow_up = self.world.blow_up(BLOW_UP_ANGVEL);
        let reset = blow_up.is_some();
        if let Some(why) = blow_up {
            self.reset_vh(&why);
        }
        reset
    }

    /// Record: measure the tick into a [`Sample`], and note which target
    /// the eyes are on for the next tick's planner.
    fn record(&mut self, gaze: &GazeStep, reset: bool) -> &Sample {
        let neck_target = JointAngles {
            yaw: gaze.out.neck.angles.x,
            pitch: gaze.out.neck.angles.y,
            roll: 0.0,
        };
        let mut sample = self.sample(&gaze.choice, &gaze.out.eyes.map(|e| e.angles), neck_target);
        sample.reset = reset;
        let t = self.time();
        sample.blows = self.blows.step(&self.world, t);
        for (g, on) in self.blows.touching().to_vec() {
            let (at, v) = (
                self.world.position(g).as_dvec3(),
                self.world.velocity(g).as_dvec3(),
            );
            if self.timeline.recoil(g, t, at, v, self.model.dt) {
                self.blows.opponent_punch_stopped(on);
            }
        }
        self.fixated = (sample.los_error[0].max(sample.los_error[1]) < EYES_ON_TARGET)
            .then(|| sample.gaze_target.clone());
        self.last = Some(sample);
        self.last.as_ref().expect("just set")
    }

    /// Measure the tick's outcome (part of the record stage).
    fn sample(
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
            blows: Vec::new(),
        }
    }
}

/// Shoulder and elbow joint rotations (segment, rotation) that put the
/// gloves at the planned positions (inverse kinematics, left then right).
fn arm_rotations(gloves: [DVec3; 2]) -> [(usize, Quat); 4] {
    let (ls, le) = arm_ik(0, gloves[0]);
    let (rs, re) = arm_ik(1, gloves[1]);
    [
        (seg::UPPER_ARM_L, ls),
        (seg::FOREARM_L, le),
        (seg::UPPER_ARM_R, rs),
        (seg::FOREARM_R, re),
    ]
}

/// A stable identity for "the same target" across ticks (a body, or a
/// fixed point), so the oculomotor can tell a new target from a moving one.
fn target_id(c: &GazeChoice) -> u64 {
    let kind = match c.source {
        Source::BottomUp => 1u64,
        Source::TopDown => 2,
        Source::Override => 3,
    };
    let body = c.body.map_or(0xFFFF, |b| b as u64);
    let mut h = kind << 48 | body << 16;
    for byte in c.name.bytes() {
        h = h.rotate_left(5) ^ byte as u64;
    }
    h
}
