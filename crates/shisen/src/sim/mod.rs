//! One simulation: the world plus the VH's brain, stepped at a fixed rate
//! in simulation time. [`Sim::step`] runs the pipeline of gaze.md 1 as
//! named stages: timeline -> sense (vision) -> decide (behaviour) ->
//! attend (attention) -> move the gaze (oculomotor) -> face -> arms ->
//! actuate and integrate (PD joints, physics) -> resolve contacts (blows,
//! a stopped punch's recoil) -> record a [`Sample`].
//!
//! The static description lives in a [`Model`]; `Sim` holds only what
//! evolves.

pub mod blows;
mod body;
pub mod bout;
pub mod crowd;
pub mod effort;
pub mod expect;
pub mod model;
pub mod punch;
mod sample;
pub mod stats;
mod streams;
pub mod timeline;
pub mod track;

use glam::{DVec2, DVec3, Quat, Vec3};

use streams::Streams;

use crate::physics::balance::Balance;
use crate::physics::body::{OpponentPart, Seg, Shape, arm_ik};
use crate::physics::control::JointTarget;
use crate::physics::lower::{Carried, LowerBody};
use crate::physics::neck::{self, NeckState};
use crate::physics::world::{PropSpec, World};
use blows::{Blow, BlowKind, Blows, Fighter, Tally};
use bout::{Bell, Phase};
use effort::{Effort, Exertion};
pub use model::{BodySpec, DT, Model, Params, Profile, PropShape};
pub use sample::Sample;
use shisen_face::FaceState;
use shisen_gaze::attention::{Attention, GazeChoice, Source};
use shisen_gaze::behaviour::{ActionKind, Behaviour, EYES_ON_TARGET, OpponentView, TopDown};
use shisen_gaze::oculomotor::head::Amount;
use shisen_gaze::oculomotor::{GazeInput, GazeOutput, Oculomotor};
use shisen_gaze::target::{Spot, TargetId};
use shisen_gaze::util::delay::DelayLine;
use shisen_gaze::util::math::{JointAngles, angle_between, yaw_pitch_of};
use shisen_gaze::vision::BodyId;
use shisen_gaze::vision::{Scenery, Seen, see};
use stats::Stats;
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

/// A seen glove threatens the eyes when its path passes this close to
/// them, m (about a glove's width).
const EYE_THREAT_MISS: f64 = 0.12;

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
    pub face_state: shisen_face::FaceState,
    /// What the eyes see this tick.
    sight: Vec<Seen>,
    /// What the stages act on: the sight of `vision.latency` ago.
    seen: Vec<Seen>,
    percept: DelayLine<Vec<Seen>>,
    /// When the VH last guarded or attacked, s.
    last_action: f64,
    /// Whether the VH is sparring (guarded or attacked within
    /// [`SPARRING_HOLD`]): decided each tick, shown by the face.
    sparring: bool,
    targets: Vec<JointTarget>,
    rng: Streams,
    names: Vec<String>,
    /// The gaze target both eyes were on (line of sight within
    /// [`EYES_ON_TARGET`]) at the end of the last tick.
    fixated: Option<TargetId>,
    /// Times the VH was reset after a physics explosion.
    pub resets: u32,
    /// Hits and blocks both ways.
    blows: Blows,
    /// The neck muscles' activation (tone, bracing, reflex).
    pub neck: NeckState,
    /// Legs, feet and waist as planned (with a physical pelvis, the
    /// posture the body's joints track).
    pub lower: LowerBody,
    /// The physical body's balance: its state, knockdowns and get-ups
    /// (idle while the pelvis is driven).
    pub balance: Balance,
    /// When the VH was last knocked down (the referee's count, [`Sim::count`]).
    knocked_at: Option<f64>,
    /// Your avatar's legs, feet and waist, carried under its head (in its
    /// own frame: see [`Sim::avatar_frame`]).
    pub avatar: Carried,
    /// Bodies other than the VH's touching its head at the last step.
    head_touch: Vec<BodyId>,
    /// Effort over the bout: stamina, damage, breathing.
    pub effort: Effort,
    /// Punch statistics, per round.
    pub stats: Stats,
    /// The crowd round the ring (it reacts; nothing depends on it).
    pub crowd: crowd::Crowd,
    /// The VH's punches, evasions and feints already counted.
    counted: (u32, u32, u32),
    /// The bell rung this tick, if any.
    bell: Option<Bell>,
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
        let mut world = World::with_body(model.plan.clone(), model.dt, Some(&model.params.body));
        let blows = Blows::new(&world);
        let mut scripted: Vec<(BodyId, DVec3)> = world
            .parts()
            .iter()
            .map(|&b| (b, world.position(b).as_dvec3()))
            .collect();
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
        for (s, q) in arm_rotations(behaviour.glove_targets(0.0)) {
            targets[s.index()].rotation = q;
        }
        let mut rng = Streams::new(model.seed);
        let lower = LowerBody::new(&model.params.body);
        let avatar = Carried::new(&model.params.body.standing());
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
            sparring: false,
            targets,
            names,
            fixated: None,
            resets: 0,
            blows,
            neck: NeckState::default(),
            lower,
            balance: Balance::default(),
            knocked_at: None,
            avatar,
            head_touch: Vec::new(),
            effort: Effort::default(),
            stats: Stats::default(),
            crowd: crowd::Crowd::default(),
            counted: (0, 0, 0),
            bell: None,
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
    pub fn track_mut(&mut self, body: BodyId) -> Option<&mut Track> {
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
        // Who decides survives the reset (an agent keeps the VH).
        let control = self.behaviour.control();
        self.behaviour = Behaviour::new();
        self.behaviour.take_over(control);
        for t in &mut self.targets {
            *t = JointTarget::default();
        }
        self.neck = NeckState::default();
        self.lower = self.lower.restarted(&self.model.params.body);
        self.balance = self.balance.restarted();
        self.knocked_at = None;
        self.counted = (0, 0, 0);
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
        self.referee(t);
        self.play_timeline(t);
        self.sense();
        let top_down = self.decide(t);
        let choice = self.attend(&top_down, t);
        let gaze = self.move_gaze(choice, t);
        self.animate_face(&gaze);
        let trunk = self.plan_body(t);
        self.plan_arms(t, trunk);
        self.carry_avatar(t);
        let reset = self.actuate_and_integrate();
        let blows = self.resolve_contacts();
        self.keep_score(&blows);
        self.record(&gaze, reset, blows)
    }

    /// The bout's phase at `t` (`None`: the run is no bout).
    pub fn phase(&self, t: f64) -> Option<(Phase, f64)> {
        self.model.bout.map(|b| b.phase_at(t))
    }

    /// The round being fought (or just fought) at `t`; 1 outside a bout.
    fn round(&self, t: f64) -> u32 {
        self.model.bout.map_or(1, |b| b.phase_at(t).0.round(&b))
    }

    /// Referee: the bell, and between rounds the VH sent to its corner
    /// (it faces the ring's centre there).
    fn referee(&mut self, t: f64) {
        let Some(b) = self.model.bout else { return };
        self.bell = if self.tick == 0 {
            Some(Bell::Start(1))
        } else {
            bout::bell(&b, t - self.model.dt, t)
        };
        let fighting = b.phase_at(t).0.fighting();
        let corner = (!fighting).then(|| (bout::vh_corner(), bout::RING_CENTRE));
        self.behaviour.set_corner(corner, t);
    }

    /// Keep score: punches thrown and how they ended (statistics), and
    /// what the tick cost the VH (effort, E1-E3); a hard enough blow
    /// staggers it.
    fn keep_score(&mut self, blows: &[Blow]) {
        let t = self.time();
        let round = self.round(t);
        let b = &self.behaviour;
        let (punches, evasions, feints) = (
            b.punches_thrown.saturating_sub(self.counted.0),
            b.evasions.saturating_sub(self.counted.1),
            b.feints.saturating_sub(self.counted.2),
        );
        self.counted = (b.punches_thrown, b.evasions, b.feints);
        if punches > 0
            && let Some(hand) = b.attack_hand()
        {
            self.stats.thrown(Fighter::Vh, hand, t, round);
        }
        for &h in &self.timeline.thrown {
            let hand = usize::from(h == timeline::Hand::Right);
            self.stats.thrown(Fighter::Opponent, hand, t, round);
        }
        for _ in 0..evasions {
            self.stats.evaded(round);
        }
        for _ in 0..feints {
            self.stats.feinted(round);
        }
        let mut x = Exertion {
            punches,
            evasions,
            fighting: self.model.bout.is_none_or(|b| b.phase_at(t).0.fighting()),
            ..Default::default()
        };
        if x.fighting {
            self.stats.at_range(round, self.zone().index());
        }
        self.crowd.tick(self.model.dt);
        for blow in blows {
            self.stats.blow(blow);
            self.crowd.blow(blow);
            if blow.by == Fighter::Opponent && blow.kind == BlowKind::Hit {
                let j = f64::from(blow.impulse);
                if blow.part == "head" {
                    x.head = (x.head.0.max(j), x.head.1 + j);
                } else {
                    x.body += j;
                }
            }
        }
        self.stats.tick(t);
        let p = &self.model.params;
        if self.effort.step(&p.effort, &x, t, self.model.dt) {
            let from = self
                .world
                .position(self.world.part(OpponentPart::Head))
                .as_dvec3();
            let tired = self.effort.behaviour(&p.effort, &p.behaviour);
            // A physical body gives ground by the blow itself (B5).
            let from = (self.world.legs.is_none()).then_some(from);
            self.behaviour
                .stagger(&tired, from, t, self.effort.staggered_until);
        }
        self.face_state.effort = self.effort.face(&p.effort);
    }

    /// Timeline: the scene's events due now (and live input's), then the
    /// scripted bodies driven along their tracks.
    fn play_timeline(&mut self, t: f64) {
        self.timeline
            .run(t, &self.world, &self.model.face, &mut self.face_state);
        self.timeline.drive(&mut self.world, t, self.model.dt);
        for (part, impulse) in std::mem::take(&mut self.timeline.pushes) {
            self.world.push(part, impulse.as_vec3());
        }
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

    /// Decide: the action planner's top-down request and glove plans, and
    /// whether the VH is sparring.
    fn decide(&mut self, t: f64) -> TopDown {
        let head_c = self.world.rb(Seg::Head).translation().as_dvec3();
        let torso_c = self.world.rb(Seg::Torso).translation().as_dvec3();
        let view = OpponentView {
            seen: &self.seen,
            names: &self.names,
            eyes_on: self.fixated,
            parts: self.world.parts(),
            vh_points: [head_c, torso_c, (head_c + torso_c) / 2.0],
        };
        let p = &self.model.params;
        // E2: the planner works with what fatigue leaves of its parameters.
        let tired = self.effort.behaviour(&p.effort, &p.behaviour);
        let top_down = self.behaviour.step(
            &tired,
            &p.personality,
            &view,
            t,
            self.model.dt,
            &mut self.rng.behaviour,
        );
        if self.behaviour.action() != ActionKind::Idle {
            self.last_action = t;
        }
        self.sparring = t - self.last_action < SPARRING_HOLD;
        top_down
    }

    /// Attend: attention's choice, or the scene's override while in force.
    /// Attention always runs (its scores and habituation stay live).
    fn attend(&mut self, top_down: &TopDown, t: f64) -> GazeChoice {
        let world = &self.world;
        let body_pos = |b: BodyId| world.position(b).as_dvec3();
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
                    name: o
                        .body
                        .map_or("point".into(), |b| self.names[b.index()].clone()),
                    body: o.body,
                    spot: Spot::Centre,
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
        let head = self.world.rb(Seg::Head);
        let input = GazeInput {
            point: choice.point,
            target: choice.id(),
            amount: Amount {
                value: choice.amount,
                least: p.personality.a1,
                most: p.personality.a2,
            },
            top_down: choice.source != Source::BottomUp,
            head_pos: head.translation().as_dvec3(),
            head_rot: head.rotation().as_dquat(),
            head_angvel: head.angvel().as_dvec3(),
            torso_rot: self.world.rb(Seg::Torso).rotation().as_dquat(),
            eye_pos: Seg::EYES.map(|e| self.world.rb(e).translation().as_dvec3()),
            eye_angles: Seg::EYES.map(|e| {
                let a = self.world.joint_angles(e);
                DVec2::new(a.yaw, a.pitch)
            }),
            neck_angles: self.world.joint_angles(Seg::Head),
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
        // E2: fatigue slows the saccades.
        let tired = self.effort.oculomotor(&p.effort, &p.oculomotor);
        let out = self
            .oculomotor
            .step(&tired, &input, t, dt, &mut self.rng.oculomotor);
        for (s, e) in Seg::EYES.into_iter().zip(out.eyes) {
            self.targets[s.index()] = JointTarget::yaw_pitch(e.angles, e.rates, e.accel);
        }
        let n = out.neck;
        self.targets[Seg::Head.index()] = JointTarget::yaw_pitch(n.angles, n.rates, n.accel);
        GazeStep {
            choice,
            out,
            eye_angles: input.eye_angles,
        }
    }

    /// Face: lids follow the eyes' pitch; a large gaze shift may blink;
    /// sparring changes the blink rate.
    fn animate_face(&mut self, gaze: &GazeStep) {
        let face = &self.model.face;
        if self.glove_threatens_eyes() {
            self.face_state.threat(face);
        }
        if let Some(amplitude) = self.oculomotor.saccade_started() {
            self.face_state
                .gaze_shift(face, amplitude.to_degrees(), &mut self.rng.face);
        }
        self.face_state.eye_pitch = gaze.eye_angles.map(|a| a.y as f32);
        self.face_state.engaged = self.sparring;
        self.face_state
            .step(face, self.model.dt, &mut self.rng.face);
    }

    /// Whether an opponent glove, as the VH perceives it, would reach its
    /// face within the reflex's time to contact.
    fn glove_threatens_eyes(&self) -> bool {
        let eyes = Seg::EYES.map(|e| self.world.position(e).as_dvec3());
        let eyes = (eyes[0] + eyes[1]) / 2.0;
        let ttc = self.model.face.params.reflex.threat_time_to_contact;
        let gloves = OpponentPart::GLOVES.map(|g| self.world.part(g));
        self.seen
            .iter()
            .filter(|s| gloves.contains(&s.body))
            .any(|s| {
                let to = eyes - s.position;
                let d = to.length();
                let closing = s.velocity.dot(to / d.max(1e-9));
                // Heading for the eyes: its path passes within a glove's
                // width of them.
                let heading = s.velocity.normalize_or_zero();
                let miss = (to - to.dot(heading) * heading).length();
                closing > 0.5 && miss < EYE_THREAT_MISS && (d - 0.1).max(0.0) / closing < ttc
            })
    }

    /// Arms: inverse kinematics of the planned glove positions, in the
    /// trunk's frame; the velocity reference comes from differencing the
    /// IK solution.
    fn plan_arms(&mut self, t: f64, (offset, rotation): (DVec3, glam::DQuat)) {
        let dt = self.model.dt;
        // The trunk's movement carries the shoulders: the arms' inverse
        // kinematics works from where the trunk will be.
        let waist = DVec3::from_array(shisen_gaze::anatomy::trunk::WAIST);
        let inv = rotation.inverse();
        let gloves = self
            .behaviour
            .glove_targets(t + dt)
            .map(|g| waist + inv * (g - waist - offset));
        for (s, q) in arm_rotations(gloves) {
            let k = s.index();
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
        let p = &self.model.params;
        let head = &self.targets[Seg::Head.index()];
        let stretch = neck::stretch(head, &self.world.joint_state(Seg::Head));
        // The VH braces while it guards (it has seen the punch coming,
        // through vision's and the guard's latencies) and while it attacks:
        // postural muscles are set before a voluntary movement of one's own
        // (anticipatory postural adjustments), so its lunge into a punch
        // does not throw its head back. A staggered VH covers up and tucks
        // its chin as boxers are drilled to (it stays braced while it gives
        // ground): unbraced, a second hard blow on an exhausted, staggered
        // VH drove its neck 20 deg past its range in a 3-hour soak.
        let bracing =
            self.behaviour.action() != ActionKind::Idle || self.effort.staggered(self.time());
        self.neck
            .step(&p.neck, stretch, bracing, self.time(), self.model.dt);
        self.world
            .apply_control(&p.gains, &self.targets, (&p.neck, &self.neck));
        self.world.step();
        self.tick += 1;
        let blow_up = self.world.blow_up(BLOW_UP_ANGVEL);
        let reset = blow_up.is_some();
        if let Some(why) = blow_up {
            self.reset_vh(&why);
        }
        reset
    }

    /// Resolve contacts: the blows this step's contacts decided, and a
    /// scripted glove stopped by what it hit comes back from there.
    fn resolve_contacts(&mut self) -> Vec<Blow> {
        let t = self.time();
        let blows = self.blows.step(&self.world, t);
        // A touch is not a blow: only a body arriving with a blow's
        // momentum makes the face react.
        if let Some(momentum) = self
            .head_struck()
            .filter(|&m| m >= f64::from(blows::BLOW_IMPULSE))
        {
            self.face_state.struck(&self.model.face, momentum);
        }
        for (g, on) in self.blows.touching().to_vec() {
            let (at, v) = (
                self.world.position(g).as_dvec3(),
                self.world.velocity(g).as_dvec3(),
            );
            if self.timeline.recoil(g, t, at, v, self.model.dt) {
                self.blows.opponent_punch_stopped(on);
            }
        }
        blows
    }

    /// A body (a glove, a prop) that began to touch the VH's head this
    /// step: the moment a blow is felt, before its impulse is known. Its
    /// momentum toward the head, N s.
    fn head_struck(&mut self) -> Option<f64> {
        let w = &self.world;
        let touching: Vec<BodyId> = w
            .body_ids()
            .filter(|&b| !w.is_own(b) && w.in_contact(Seg::Head, b))
            .collect();
        let new = touching
            .iter()
            .filter(|b| !self.head_touch.contains(b))
            .map(|&b| {
                let to_head = (w.position(Seg::Head) - w.position(b)).normalize_or_zero();
                let closing = (w.velocity(b) - w.velocity(Seg::Head)).dot(to_head);
                f64::from(w.rb(b).mass() * closing.max(0.0))
            })
            .reduce(f64::max);
        self.head_touch = touching;
        new
    }

    /// Record: measure the tick into a [`Sample`], and note which target
    /// the eyes are on for the next tick's planner.
    fn record(&mut self, gaze: &GazeStep, reset: bool, blows: Vec<Blow>) -> &Sample {
        let neck_target = JointAngles {
            yaw: gaze.out.neck.angles.x,
            pitch: gaze.out.neck.angles.y,
            roll: 0.0,
        };
        let mut sample = self.sample(&gaze.choice, &gaze.out.eyes.map(|e| e.angles), neck_target);
        sample.reset = reset;
        sample.torsion = gaze.out.torsion;
        sample.blows = blows;
        self.fixated = (sample.los_error[0].max(sample.los_error[1]) < EYES_ON_TARGET)
            .then(|| gaze.choice.id());
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
        for (k, s) in Seg::EYES.into_iter().enumerate() {
            let rb = w.rb(s);
            let los = (*rb.rotation() * Vec3::Z).as_dvec3();
            let to = (choice.point - rb.translation().as_dvec3()).normalize_or(DVec3::Z);
            los_error[k] = angle_between(los, to);
            let (ly, lp) = yaw_pitch_of(los);
            let (ty, tp) = yaw_pitch_of(to);
            gaze_error[k] = DVec2::new(ly - ty, lp - tp);
            let a = w.joint_angles(s);
            eye_actual[k] = DVec2::new(a.yaw, a.pitch);
        }
        let head_fwd = (*w.rb(Seg::Head).rotation() * Vec3::Z).as_dvec3();
        let (hy, hp) = yaw_pitch_of(head_fwd);
        let mut top: Vec<(String, f64)> = self
            .seen
            .iter()
            .map(|s| {
                let i = s.body.index();
                (self.names[i].clone(), self.attention.scores[i])
            })
            .collect();
        top.sort_by(|a, b| b.1.total_cmp(&a.1).then_with(|| a.0.cmp(&b.0)));
        top.truncate(3);
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
            torsion: 0.0,
            gaze_error,
            neck_target,
            neck_actual: w.joint_angles(Seg::Head),
            head_world: DVec2::new(hy, hp),
            head_speed: f64::from(w.rb(Seg::Head).angvel().length()),
            head: w.position(Seg::Head).as_dvec3(),
            pelvis: self.pelvis(),
            waist: self.lower.waist(&self.model.params.body),
            heading: self.lower.facing(),
            range: self.distance(),
            top_saliency: top,
            finite: w.is_finite(),
            punching: self.behaviour.punching(),
            head_hit: self.blows.head_contact(),
            emotion: self.face_state.emotion,
            blink: self.face_state.blink.closure(&self.model.face.params.blink),
            reset: false,
            blows: Vec::new(),
            phase: self.phase(self.time()).map(|p| p.0),
            bell: self.bell,
            fatigue: self.effort.fatigue(&self.model.params.effort),
            staggered: self.effort.staggered(self.time()),
            stance: self.balance.stance,
            com: self.balance.last.com,
        }
    }
}

/// Shoulder and elbow joint rotations (segment, rotation) that put the
/// gloves at the planned positions (inverse kinematics, left then right).
fn arm_rotations(gloves: [DVec3; 2]) -> [(Seg, Quat); 4] {
    let (ls, le) = arm_ik(0, gloves[0]);
    let (rs, re) = arm_ik(1, gloves[1]);
    [
        (Seg::UpperArmL, ls),
        (Seg::ForearmL, le),
        (Seg::UpperArmR, rs),
        (Seg::ForearmR, re),
    ]
}
