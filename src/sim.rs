//! One simulation: the world plus the VH's brain, stepped at a fixed rate
//! in simulation time. Each tick runs the pipeline of gaze.md 1:
//! script -> vision -> behaviour -> attention -> oculomotor -> joints ->
//! physics, and records a [`Sample`].

use glam::{DVec2, DVec3, Quat, Vec3};
use rand::SeedableRng;
use rand::rngs::StdRng;

use crate::attention::{Attention, GazeChoice, Source};
use crate::behaviour::{Behaviour, OpponentView, arm_ik};
use crate::body::{BodyPlan, Shape, seg};
use crate::control::{Gains, JointTarget};
use crate::face::tables::Emotion;
use crate::face::{Face, FaceState};
use crate::oculomotor::{AxisCommand, GazeInput, GazeShiftLaw, Oculomotor};
use crate::scene::{
    Action, ActionKind, Hand, LoadedScene, Part, PropShape, PunchTarget, Scene, Side,
};
use crate::script::Track;
use crate::vision::{Seen, see};
use crate::world::{JointAngles, PropSpec, World, opp};

/// Physics and control rate. 1 kHz: explicit PD on a 7.5 g eyeball needs
/// omega_n dt << 1 (see control.rs), a 500 deg/s saccade moves 0.5 deg a
/// step, and rapier still runs this model several times faster than real
/// time (see benches/step.rs).
pub const DT: f64 = 0.001;

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

/// Largest reference angular speed of an arm joint, rad/s (elbow extension
/// in a punch peaks around 20-40 rad/s).
const ARM_MAX_RATE: f32 = 40.0;

/// Angular speed (rad/s) of a VH segment taken as a physics explosion.
pub const BLOW_UP_ANGVEL: f32 = 200.0;

/// A scene's gaze override in force.
#[derive(Clone, Debug)]
struct Override {
    /// Body to follow, or a fixed point.
    body: Option<usize>,
    point: DVec3,
    until: f64,
    amount: Option<f64>,
    style: Option<GazeShiftLaw>,
}

/// An imposed sinusoidal neck motion.
#[derive(Clone, Copy, Debug)]
struct Shake {
    amplitude: DVec2,
    freq: f64,
    t0: f64,
    until: f64,
}

impl Shake {
    fn command(&self, t: f64) -> AxisCommand {
        let w = std::f64::consts::TAU * self.freq;
        let ph = w * (t - self.t0);
        AxisCommand {
            angles: self.amplitude * ph.sin(),
            rates: self.amplitude * (w * ph.cos()),
            accel: self.amplitude * (-w * w * ph.sin()),
        }
    }
}

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

/// A running simulation.
pub struct Sim {
    /// The scene (static).
    pub scene: Scene,
    /// Gains in force (replaceable while running).
    pub gains: Gains,
    /// The physics world.
    pub world: World,
    tick: u64,
    next_event: usize,
    events: Vec<crate::scene::Event>,
    /// Scripted bodies: body, track, its last two positions.
    tracks: Vec<(usize, Track, [DVec3; 2])>,
    /// Attention state.
    pub attention: Attention,
    /// Action planner state.
    pub behaviour: Behaviour,
    /// Eye and head control state.
    pub oculomotor: Oculomotor,
    /// The face model (mesh, muscles, database), shared and static.
    pub face: std::sync::Arc<Face>,
    /// The face's evolving state (expression, blinks).
    pub face_state: FaceState,
    look_at: Option<Override>,
    occluded: [bool; 2],
    shake: Option<Shake>,
    seen: Vec<Seen>,
    targets: Vec<JointTarget>,
    rng: Streams,
    names: Vec<String>,
    /// Times the VH was reset after a physics explosion.
    pub resets: u32,
    last: Option<Sample>,
}

impl Sim {
    /// Build a simulation from a loaded scene.
    pub fn new(loaded: &LoadedScene) -> Self {
        let mut scene = loaded.scene.clone();
        // The personality's A1, A2 are the head law's (M8) amounts.
        let pers = &scene.vh.personality;
        scene.vh.oculomotor.head.attention_least = pers.a1;
        scene.vh.oculomotor.head.attention_most = pers.a2;
        let plan = BodyPlan::default();
        let mut world = World::new(plan.clone(), DT);
        let mut tracks = Vec::new();
        for k in 0..3 {
            let b = world.opponent[k];
            let p = world.rb(b).translation().as_dvec3();
            tracks.push((b, Track::new(p), [p; 2]));
        }
        for b in &scene.bodies {
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
                tracks.push((idx, Track::new(b.position), [b.position; 2]));
            }
        }
        let mut events = scene.timeline.clone();
        events.sort_by(|a, b| a.at.total_cmp(&b.at)); // stable: file order at equal times
        let names: Vec<String> = world.bodies.iter().map(|b| b.name.clone()).collect();
        let mut targets = vec![JointTarget::default(); plan.segments.len()];
        let behaviour = Behaviour::new();
        for (k, q) in arm_rotations(behaviour.glove_targets(0.0)) {
            targets[k].rotation = q;
        }
        let mut rng = Streams::new(scene.seed);
        Sim {
            face: loaded.face.clone(),
            face_state: FaceState::default(),
            oculomotor: Oculomotor::new(&scene.vh.oculomotor, &mut rng.oculomotor),
            rng,
            gains: loaded.gains.clone(),
            scene,
            world,
            tick: 0,
            next_event: 0,
            events,
            tracks,
            attention: Attention::new(names.clone()),
            behaviour,
            look_at: None,
            occluded: [false; 2],
            shake: None,
            seen: Vec::new(),
            targets,
            names,
            resets: 0,
            last: None,
        }
    }

    /// Simulation time now, s.
    pub fn time(&self) -> f64 {
        self.tick as f64 * DT
    }

    /// The last recorded sample.
    pub fn last(&self) -> Option<&Sample> {
        self.last.as_ref()
    }

    /// Bodies in view after the last tick.
    pub fn seen(&self) -> &[Seen] {
        &self.seen
    }

    /// The kinematic track of a body, if it has one.
    pub fn track_mut(&mut self, body: usize) -> Option<&mut Track> {
        self.tracks
            .iter_mut()
            .find(|(b, ..)| *b == body)
            .map(|(_, t, _)| t)
    }

    fn part_body(&self, part: &Part) -> usize {
        match part {
            Part::Head => self.world.opponent[opp::HEAD],
            Part::LeftGlove => self.world.opponent[opp::LEFT_GLOVE],
            Part::RightGlove => self.world.opponent[opp::RIGHT_GLOVE],
            Part::Body(name) => self
                .world
                .body_index(name)
                .expect("scene validation checked body names"),
        }
    }

    fn run_events(&mut self, t: f64) {
        while self.next_event < self.events.len() && self.events[self.next_event].at <= t + 1e-12 {
            let ev = self.events[self.next_event].clone();
            self.next_event += 1;
            match ev.action {
                Action::Move { part, to, duration } => {
                    let b = self.part_body(&part);
                    if let Some(tr) = self.track_mut(b) {
                        tr.reach(t, to, duration);
                    }
                }
                Action::Wave {
                    part,
                    amplitude,
                    frequency,
                    duration,
                } => {
                    let b = self.part_body(&part);
                    if let Some(tr) = self.track_mut(b) {
                        tr.wave(t, amplitude, frequency, duration);
                    }
                }
                Action::Punch {
                    hand,
                    target,
                    speed,
                } => {
                    let glove_r = self.world.plan.glove_radius as f64;
                    let (aim, radius) = match target {
                        PunchTarget::Head => (
                            self.world.seg(seg::HEAD).translation().as_dvec3(),
                            0.10 + glove_r - 0.02,
                        ),
                        PunchTarget::Body => (
                            self.world.seg(seg::TORSO).translation().as_dvec3()
                                + DVec3::new(0.0, 0.1, 0.1),
                            glove_r - 0.02,
                        ),
                        PunchTarget::Point(p) => (p, 0.0),
                    };
                    let part = match hand {
                        Hand::Left => Part::LeftGlove,
                        Hand::Right => Part::RightGlove,
                    };
                    let b = self.part_body(&part);
                    let from = self.world.rb(b).translation().as_dvec3();
                    // Stop where the glove's surface just meets the target's.
                    let dir = (aim - from).normalize_or(DVec3::NEG_Z);
                    let to = aim - dir * radius;
                    if let Some(tr) = self.track_mut(b) {
                        tr.punch(t, to, speed);
                    }
                }
                // Expanded into `Emotion` events when the scene loaded.
                Action::EmotionScript { .. } => {}
                Action::LookAt {
                    point,
                    until,
                    amount,
                    style,
                } => {
                    self.look_at = Some(Override {
                        body: None,
                        point,
                        until,
                        amount,
                        style,
                    })
                }
                Action::Track { body, until } => {
                    let b = self.world.body_index(&body).expect("validated body name");
                    self.look_at = Some(Override {
                        body: Some(b),
                        point: DVec3::ZERO,
                        until,
                        amount: None,
                        style: None,
                    });
                }
                Action::Orbit {
                    part,
                    centre,
                    rate_deg,
                    duration,
                } => {
                    let b = self.part_body(&part);
                    if let Some(tr) = self.track_mut(b) {
                        tr.orbit(t, centre, rate_deg.to_radians(), duration);
                    }
                }
                Action::Occlude { eye } => {
                    self.occluded = [eye == Some(Side::Left), eye == Some(Side::Right)];
                }
                Action::ShakeHead {
                    yaw_deg,
                    pitch_deg,
                    frequency,
                    duration,
                } => {
                    self.shake = Some(Shake {
                        amplitude: DVec2::new(yaw_deg, pitch_deg) * (std::f64::consts::PI / 180.0),
                        freq: frequency,
                        t0: t,
                        until: t + duration,
                    })
                }
                Action::Emotion {
                    emotion,
                    intensity,
                    speed,
                    pattern,
                } => self.face_state.set_emotion(
                    &self.face,
                    emotion,
                    intensity as f32,
                    speed,
                    pattern,
                ),
            }
        }
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
        self.oculomotor = Oculomotor::new(&self.scene.vh.oculomotor, &mut self.rng.oculomotor);
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
    pub fn push_event(&mut self, ev: crate::scene::Event) {
        let at =
            self.next_event + self.events[self.next_event..].partition_point(|e| e.at <= ev.at);
        self.events.insert(at, ev);
    }

    /// Replace the personality while running; its A1, A2 also set the
    /// head law's (M8) amounts, as at construction.
    pub fn set_personality(&mut self, p: crate::scene::Personality) {
        self.scene.vh.oculomotor.head.attention_least = p.a1;
        self.scene.vh.oculomotor.head.attention_most = p.a2;
        self.scene.vh.personality = p;
    }

    /// Replace the gains while running.
    pub fn set_gains(&mut self, gains: Gains) {
        self.gains = gains;
    }

    /// Advance one tick and return its sample.
    pub fn step(&mut self) -> &Sample {
        let t = self.time();
        let dt = DT;
        self.run_events(t);
        // Scripted bodies: where they should be at the end of this tick,
        // with the track's velocity and acceleration (finite differences
        // of its last three positions).
        let t_next = t + dt;
        for (b, tr, hist) in &mut self.tracks {
            let p = tr.position(t_next);
            let [p1, p2] = *hist;
            let v = (p - p1) / dt;
            let a = (p - 2.0 * p1 + p2) / (dt * dt);
            *hist = [p, p1];
            self.world.drive(*b, p.as_vec3(), v.as_vec3(), a.as_vec3());
        }

        // Vision.
        let open = self.occluded.map(|o| !o);
        see(&self.world, &self.scene.vh.vision, open, &mut self.seen);

        // Behaviour (top-down request, glove targets).
        let head_c = self.world.seg(seg::HEAD).translation().as_dvec3();
        let torso_c = self.world.seg(seg::TORSO).translation().as_dvec3();
        let eyes_on = self
            .last
            .as_ref()
            .filter(|s| s.los_error[0].max(s.los_error[1]) < 2f64.to_radians())
            .map(|s| &s.gaze_target);
        let view = OpponentView {
            seen: &self.seen,
            names: &self.names,
            eyes_on,
            parts: self.world.opponent,
            vh_points: [head_c, torso_c, (head_c + torso_c) / 2.0],
        };
        let top_down = self.behaviour.step(
            &self.scene.vh.behaviour,
            &self.scene.vh.personality,
            &view,
            t,
            dt,
            &mut self.rng.behaviour,
        );

        // Attention (or the scene's override).
        let world = &self.world;
        let body_pos = |b: usize| world.rb(b).translation().as_dvec3();
        // Attention always runs (its scores and habituation stay live); a
        // scene's override, while in force, replaces its choice.
        let chosen = self.attention.step(
            &self.scene.vh.attention,
            &self.seen,
            &top_down,
            body_pos,
            t,
            dt,
        );
        let choice = match &self.look_at {
            Some(o) if t < o.until => {
                let c = GazeChoice {
                    name: o.body.map_or("point".into(), |b| self.names[b].clone()),
                    body: o.body,
                    point: o.body.map_or(o.point, body_pos),
                    amount: o.amount.unwrap_or(self.scene.vh.personality.a2),
                    source: Source::Override,
                };
                self.attention.force(c.clone(), t);
                c
            }
            _ => chosen,
        };

        // Oculomotor: eye and neck targets.
        let head = self.world.seg(seg::HEAD);
        let input = GazeInput {
            point: choice.point,
            target_id: target_id(&choice),
            amount: choice.amount,
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
            visible: self.occluded.map(|o| !o),
            style: self
                .look_at
                .as_ref()
                .filter(|o| t < o.until)
                .and_then(|o| o.style)
                .unwrap_or(self.scene.vh.oculomotor.gaze_shift),
            neck_override: self
                .shake
                .filter(|s| t < s.until)
                .map(|s| s.command(t + dt)),
        };
        let out = self.oculomotor.step(
            &self.scene.vh.oculomotor,
            &input,
            t,
            dt,
            &mut self.rng.oculomotor,
        );
        for (k, s) in [seg::EYE_L, seg::EYE_R].into_iter().enumerate() {
            self.targets[s] = out.eyes[k].joint_target();
        }

        // Face: lids follow the eyes' pitch; a large gaze shift may blink.
        if let Some(amplitude) = self.oculomotor.saccade_started() {
            self.face_state
                .gaze_shift(&self.face, amplitude.to_degrees(), &mut self.rng.face);
        }
        self.face_state.eye_pitch = input.eye_angles.map(|a| a.y as f32);
        self.face_state.engaged = self.behaviour.action() != ActionKind::Idle;
        self.face_state.step(&self.face, dt, &mut self.rng.face);
        self.targets[seg::HEAD] = out.neck.joint_target();

        // Arms: inverse kinematics of the planned glove positions; the
        // velocity reference comes from differencing the IK solution.
        for (k, q) in arm_rotations(self.behaviour.glove_targets(t_next)) {
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

        // Joints and physics.
        self.world.apply_control(&self.gains, &self.targets);
        self.world.step();
        self.tick += 1;
        let blow_up = self.world.blow_up(BLOW_UP_ANGVEL);
        let reset = blow_up.is_some();
        if let Some(why) = blow_up {
            self.reset_vh(&why);
        }

        let neck_target = JointAngles {
            yaw: out.neck.angles.x,
            pitch: out.neck.angles.y,
            roll: 0.0,
        };
        let mut sample = self.sample(&choice, &out.eyes.map(|e| e.angles), neck_target);
        sample.reset = reset;
        self.last = Some(sample);
        self.last.as_ref().expect("just set")
    }

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
            los_error[k] = los.dot(to).clamp(-1.0, 1.0).acos();
            let (ly, lp) = crate::math::yaw_pitch_of(los);
            let (ty, tp) = crate::math::yaw_pitch_of(to);
            gaze_error[k] = DVec2::new(ly - ty, lp - tp);
            let a = w.joint_angles(s);
            eye_actual[k] = DVec2::new(a.yaw, a.pitch);
        }
        let head_fwd = (*w.seg(seg::HEAD).rotation() * Vec3::Z).as_dvec3();
        let (hy, hp) = crate::math::yaw_pitch_of(head_fwd);
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
            blink: self.face_state.blink.closure(&self.face.params.blink),
            reset: false,
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
