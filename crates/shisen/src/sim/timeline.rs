//! The timeline: what happens to the opponent, the props and the VH's
//! overrides at given times (scene `timeline`, live input), and how each
//! event changes the running simulation.

use std::collections::VecDeque;
use std::path::PathBuf;

use glam::{DVec2, DVec3, Vec3};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::track::Track;
use crate::physics::body::{OpponentPart, Seg, trunk_under};
use crate::physics::world::{PushPart, World};
use shisen_face::{Face, FaceState};
use shisen_gaze::oculomotor::{AxisCommand, GazeShiftLaw};
use shisen_gaze::util::math::{min_jerk, min_jerk_d, min_jerk_dd};
use shisen_gaze::vision::BodyId;

/// The opponent's hands.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize, JsonSchema)]
pub enum Hand {
    /// The opponent's left glove ("left_glove").
    Left,
    /// The opponent's right glove ("right_glove").
    Right,
}

impl Hand {
    /// The glove of this hand.
    pub fn glove(self) -> Part {
        match self {
            Hand::Left => Part::LeftGlove,
            Hand::Right => Part::RightGlove,
        }
    }
}

/// A script-movable body: an opponent part or a kinematic prop.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize, JsonSchema)]
pub enum Part {
    /// The opponent's head.
    Head,
    /// The opponent's left glove.
    LeftGlove,
    /// The opponent's right glove.
    RightGlove,
    /// A kinematic prop declared in `bodies`, by name (`Body("ball")`).
    Body(String),
}

/// The VH's left or right (eyes).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize, JsonSchema)]
pub enum Side {
    /// The VH's left.
    Left,
    /// The VH's right.
    Right,
}

/// Where an opponent punch is aimed.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize, JsonSchema)]
pub enum PunchTarget {
    /// The VH's head (where it is when the punch starts).
    Head,
    /// The VH's torso (where it is when the punch starts).
    Body,
    /// A world point `(x, y, z)`, m; each coordinate within +-100 m of
    /// the origin (the room is a few metres across).
    Point(
        #[schemars(with = "[f64; 3]", inner(range(min = -shisen_gaze::util::check::MAX_POSITION, max = shisen_gaze::util::check::MAX_POSITION)))]
         DVec3,
    ),
}

/// Something that happens at a time in the scene.
///
/// Durations and times are bounded by the longest run (a day, 86400 s);
/// the lower bounds of durations and the bounds of speeds, frequencies and
/// angles are what a person's hand and neck, or a prop in a boxing ring,
/// can do.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub enum Action {
    /// Move a part (the opponent's head or a glove, or a kinematic prop)
    /// from where it is to a point along a minimum-jerk path, arriving at
    /// rest after `duration`.
    Move {
        /// What moves.
        part: Part,
        /// Destination `(x, y, z)`, world m; each coordinate within +-100 m.
        #[schemars(with = "[f64; 3]", inner(range(min = -shisen_gaze::util::check::MAX_POSITION, max = shisen_gaze::util::check::MAX_POSITION)))]
        to: DVec3,
        /// Duration of the move, s: one step (0.001 s) to a day. Short
        /// moves are how a controller steers a part a little each control
        /// period (the Python environment moves the gloves every 20 ms);
        /// the distance, and so the speed, depends on where the part is
        /// when the move starts, which the scene does not know.
        #[schemars(range(min = 0.001, max = 86_400.0))]
        duration: f64,
    },
    /// Throw a punch with one of the opponent's gloves at the VH (its head,
    /// its body or a point) along a minimum-jerk path at a peak speed, and
    /// bring the glove back; the physics decides whether it lands.
    Punch {
        /// Which glove.
        hand: Hand,
        /// Aim.
        target: PunchTarget,
        /// Peak glove speed, m/s. 0.1-20: from a slow touch to twice the
        /// fastest measured punches (Olympic boxers' hands reach 6-9 m/s;
        /// Walilko, Viano & Bir 2005).
        #[schemars(range(min = 0.1, max = 20.0))]
        speed: f64,
        /// How far behind the contact point the punch is aimed, m
        /// (`Head` and `Body` targets; default 0.05, `FOLLOW_THROUGH`): a
        /// committed punch is thrown deeper and lands harder. 0-0.5: half
        /// an arm's length, deeper would aim through the far side of the head.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        #[schemars(range(min = 0.0, max = 0.5))]
        through: Option<f64>,
        /// Throw the glove alone (default false): no reach, no step
        /// behind it, no lead of the body, so nothing to read before the
        /// glove flies (the seed's punch; the benchmark without cues).
        /// Otherwise the body throws it (docs/model/boxing.md "Cues").
        #[serde(default, skip_serializing_if = "std::ops::Not::not")]
        glove_only: bool,
    },
    /// A feint with one hand: the body's part of a punch without the
    /// punch: a half step in (the head leading, toward the lead side for
    /// the rear hand) and a twitch of the glove, out and back.
    Feint {
        /// Which hand the feint shows.
        hand: Hand,
    },
    /// Push the VH: an impulse on one of its parts, as a shove or a blow
    /// of known size would give (push-recovery tests). It moves the body
    /// only where the body is physical: the trunk and pelvis need
    /// `vh.body.pelvis: Balanced`.
    Push {
        /// Where the impulse acts: `Trunk` (at its centre of mass),
        /// `Pelvis` or `Head`.
        part: PushPart,
        /// The impulse `(x, y, z)`, world, N s. Each within +-300 N s: a
        /// 75 kg body at 4 m/s, past any shove or punch (a straight
        /// punch's momentum is at most about 26 N s: Walilko, Viano & Bir
        /// 2005, Br. J. Sports Med. 39:710).
        #[schemars(with = "[f64; 3]", inner(range(min = -300.0, max = 300.0)))]
        impulse: DVec3,
    },
    /// Wave a part (a glove, the head or a kinematic prop) sinusoidally
    /// about its current position, along each axis by its amplitude, for
    /// `duration`.
    Wave {
        /// What waves.
        part: Part,
        /// Peak displacement along each axis `(x, y, z)`, m (the sign sets
        /// the phase). Each within +-2 m: a glove swings at most an arm's
        /// length (0.7 m) each way; a prop may sweep wider, but not beyond
        /// the ring (5.5 m across).
        #[schemars(with = "[f64; 3]", inner(range(min = -2.0, max = 2.0)))]
        amplitude: DVec3,
        /// Frequency, Hz. 0.01-10: from a 100 s period to above the
        /// fastest voluntary alternating hand movements (about 5-7 Hz) and
        /// far above where smooth pursuit keeps up (its gain falls above
        /// about 1 Hz; Barnes 1993).
        #[schemars(range(min = 0.01, max = 10.0))]
        frequency: f64,
        /// Duration, s: one step (0.001 s) to a day.
        #[schemars(range(min = 0.001, max = 86_400.0))]
        duration: f64,
    },
    /// Change the VH's facial expression (face.md 7): from the current
    /// values to `emotion` at `intensity`, over the table 5.9/5.10 duration
    /// at `speed`.
    Emotion {
        /// One of the 35 emotions of table A (`Neutral`, `Happiness`, ...).
        emotion: shisen_face::tables::Emotion,
        /// Intensity, 0 (none) to 1 (full; default).
        #[serde(default = "one")]
        #[schemars(range(min = 0.0, max = 1.0))]
        intensity: f64,
        /// `Fast`, `Typical` or `Slow` (the thesis's speeds 1, 2, 3).
        #[serde(default)]
        speed: shisen_face::timing::Speed,
        /// Onset/offset shape `I`..`V` (default `III`, the thesis's choice).
        #[serde(default)]
        pattern: shisen_face::timing::Pattern,
    },
    /// Play a script of expressions in the thesis's plain format (`emotion
    /// duration speed` per line, face.md 9) from this time; the file is
    /// expanded into `Emotion` events when the scene loads.
    EmotionScript {
        /// The script file, relative to the scene file.
        file: PathBuf,
    },
    /// Override the VH's gaze: look at a world point until a time (the
    /// action planner's choice of target resumes after it).
    LookAt {
        /// The point `(x, y, z)`, world m; each coordinate within +-100 m.
        #[schemars(with = "[f64; 3]", inner(range(min = -shisen_gaze::util::check::MAX_POSITION, max = shisen_gaze::util::check::MAX_POSITION)))]
        point: DVec3,
        /// End of the override, s from the run's start (not before `at`;
        /// at most a day).
        #[schemars(range(min = 0.0, max = 86_400.0))]
        until: f64,
        /// Attention amount A for the head law (M8), 0-100 like the
        /// personality's amounts (the seed's are 1.5 and 3); default the
        /// personality's `a2` (the head faces the point).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        #[schemars(range(min = 0.0, max = 100.0))]
        amount: Option<f64>,
        /// How to shift the gaze there (default: the scene's law).
        #[serde(default)]
        style: Option<shisen_gaze::oculomotor::GazeShiftLaw>,
    },
    /// Override the VH's gaze: follow a body (by name) until a time.
    Track {
        /// Body name (`head`, `left_glove`, `right_glove`, `torso`, a prop of
        /// `bodies`).
        body: String,
        /// End of the override, s from the run's start (not before `at`;
        /// at most a day).
        #[schemars(range(min = 0.0, max = 86_400.0))]
        until: f64,
    },
    /// Move a part (the opponent's head or a glove, or a kinematic prop)
    /// at constant angular speed on a horizontal circle about a centre,
    /// from where it is (a pursuit target, an opponent circling).
    Orbit {
        /// What moves.
        part: Part,
        /// Centre of the circle `(x, y, z)`, world m; each coordinate
        /// within +-100 m.
        #[schemars(with = "[f64; 3]", inner(range(min = -shisen_gaze::util::check::MAX_POSITION, max = shisen_gaze::util::check::MAX_POSITION)))]
        centre: DVec3,
        /// Angular speed about +Y, deg/s (positive: toward the VH's left).
        /// -720 to 720 (two turns a second): far past what smooth pursuit
        /// follows (about 100 deg/s) or a fighter circles.
        #[schemars(range(min = -720.0, max = 720.0))]
        rate_deg: f64,
        /// Duration, s: one step (0.001 s) to a day.
        #[schemars(range(min = 0.001, max = 86_400.0))]
        duration: f64,
    },
    /// Shut or cover one of the VH's eyes (`Some(Left)`, `Some(Right)`) or
    /// uncover both (`None`), from this time on.
    Occlude {
        /// The covered eye, or `None`.
        eye: Option<Side>,
    },
    /// Impose a sinusoidal neck motion on the VH (overriding the head
    /// law) for `duration`, e.g. to measure the VOR: yaw and pitch
    /// oscillate about straight ahead at `frequency`.
    ShakeHead {
        /// Yaw amplitude, deg. 0-90: the neck turns 70-80 deg each way
        /// (active cervical rotation; Youdas et al. 1992, Phys. Ther.
        /// 72:770).
        #[schemars(range(min = 0.0, max = 90.0))]
        yaw_deg: f64,
        /// Pitch amplitude, deg (default 0). 0-90: the neck bends about
        /// 50-60 deg forward and 60-80 back (Youdas et al. 1992).
        #[serde(default)]
        #[schemars(range(min = 0.0, max = 90.0))]
        pitch_deg: f64,
        /// Frequency, Hz. 0.01-6: active head rotation tests run to 6 Hz,
        /// about the fastest a person shakes the head (O'Leary &
        /// Davis-O'Leary 1990).
        #[schemars(range(min = 0.01, max = 6.0))]
        frequency: f64,
        /// Duration, s: one step (0.001 s) to a day.
        #[schemars(range(min = 0.001, max = 86_400.0))]
        duration: f64,
    },
    /// Impose a quick minimum-jerk neck turn on the VH by `yaw_deg` /
    /// `pitch_deg` over `duration` and hold it for `hold` (overriding the
    /// head law): a passive head impulse, e.g. to measure the VOR's
    /// latency.
    TurnHead {
        /// Yaw, deg (positive: to the VH's left). -90 to 90: the neck
        /// turns 70-80 deg each way (Youdas et al. 1992, Phys. Ther.
        /// 72:770).
        #[schemars(range(min = -90.0, max = 90.0))]
        yaw_deg: f64,
        /// Pitch, deg (positive: up; default 0). -90 to 90: the neck
        /// bends about 50-60 deg forward and 60-80 back (Youdas et al.
        /// 1992).
        #[serde(default)]
        #[schemars(range(min = -90.0, max = 90.0))]
        pitch_deg: f64,
        /// Duration of the turn, s. At least 0.05 s: a clinical head
        /// impulse turns 10-20 deg in 100-200 ms (peaks 150-300 deg/s);
        /// 90 deg in 0.05 s already peaks near 3400 deg/s (59 rad/s),
        /// several times a jab's snap of the head (9-21 rad/s,
        /// scenes/jab_snaps_head.ron). At most a day.
        #[schemars(range(min = 0.05, max = 86_400.0))]
        duration: f64,
        /// How long the turned head is held afterwards, s (default 0; at
        /// most a day).
        #[serde(default)]
        #[schemars(range(min = 0.0, max = 86_400.0))]
        hold: f64,
    },
    /// Carry the VH's trunk (and the head on it) by `offset` along a
    /// minimum-jerk path over `duration`, then hold it there, as the sled
    /// of a translational-VOR study carries a person: an imposed
    /// translation, without turning, e.g. to measure the tVOR from the
    /// joints. It carries a driven body (`vh.body.pelvis: Driven`, the
    /// default); a balanced one is moved by `Push`.
    Carry {
        /// The displacement `(x, y, z)`, world m; each within +-0.5 m (a
        /// sled's travel in such studies is a few cm to some tens).
        #[schemars(with = "[f64; 3]", inner(range(min = -0.5, max = 0.5)))]
        offset: DVec3,
        /// Duration of the move, s. 0.05 s (Ramat & Zee 2003's abrupt
        /// translations took about 200 ms) to a day.
        #[schemars(range(min = 0.05, max = 86_400.0))]
        duration: f64,
    },
}

/// An imposed translation of the VH's trunk (`Carry`): where it is at a time.
#[derive(Clone, Copy, Debug)]
pub(super) struct Carry {
    from: DVec3,
    by: DVec3,
    t0: f64,
    duration: f64,
}

impl Carry {
    /// The trunk's imposed offset at `t`, world m.
    pub fn offset(&self, t: f64) -> DVec3 {
        self.from + self.by * min_jerk((t - self.t0) / self.duration)
    }
}

/// How far behind the contact point a scripted punch at the head or body
/// is aimed, m. A punch is thrown through its target, so the glove meets
/// the surface still moving (at about half its peak speed with a
/// minimum-jerk path) and the physics, not the path, stops it: it lands a
/// blow (`sim::blows`). Kept short for now: the glove's drive is a stiff
/// spring toward the path, and a deeper aim would push it through a guard
/// that has met it.
pub const FOLLOW_THROUGH: f64 = 0.05;

/// A timeline entry: at a time, an action.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Event {
    /// Start time, s from the run's start: 0 to a day (86400 s), and not
    /// after the run's `duration`.
    #[schemars(range(min = 0.0, max = 86_400.0))]
    pub at: f64,
    /// What happens.
    #[serde(rename = "do")]
    pub action: Action,
}

fn one() -> f64 {
    1.0
}

/// A scene's gaze override in force.
#[derive(Clone, Debug)]
pub(super) struct Override {
    /// Body to follow, or a fixed point.
    pub body: Option<BodyId>,
    pub point: DVec3,
    pub until: f64,
    pub amount: Option<f64>,
    pub style: Option<GazeShiftLaw>,
}

/// An imposed neck motion: a sinusoid (`ShakeHead`) or a minimum-jerk
/// turn (`TurnHead`).
#[derive(Clone, Copy, Debug)]
pub(super) struct Shake {
    amplitude: DVec2,
    kind: ShakeKind,
    t0: f64,
    pub until: f64,
}

#[derive(Clone, Copy, Debug)]
enum ShakeKind {
    /// `amplitude sin(2 pi freq (t - t0))`.
    Sine { freq: f64 },
    /// `amplitude min_jerk((t - t0) / duration)`.
    Turn { duration: f64 },
}

impl Shake {
    pub fn command(&self, t: f64) -> AxisCommand {
        match self.kind {
            ShakeKind::Sine { freq } => {
                let w = std::f64::consts::TAU * freq;
                let ph = w * (t - self.t0);
                AxisCommand {
                    angles: self.amplitude * ph.sin(),
                    rates: self.amplitude * (w * ph.cos()),
                    accel: self.amplitude * (-w * w * ph.sin()),
                }
            }
            ShakeKind::Turn { duration } => {
                let s = (t - self.t0) / duration;
                AxisCommand {
                    angles: self.amplitude * min_jerk(s),
                    rates: self.amplitude * (min_jerk_d(s) / duration),
                    accel: self.amplitude * (min_jerk_dd(s) / (duration * duration)),
                }
            }
        }
    }
}

/// The body a part names.
fn part_body(world: &World, part: &Part) -> BodyId {
    match part {
        Part::Head => world.part(OpponentPart::Head),
        Part::LeftGlove => world.part(OpponentPart::LeftGlove),
        Part::RightGlove => world.part(OpponentPart::RightGlove),
        Part::Body(name) => world
            .body_named(name)
            .expect("scene validation checked body names"),
    }
}

/// The running timeline: the events still to come, and what past events
/// set in motion (scripted tracks, gaze override, covered eye, imposed
/// neck motion).
#[derive(Clone, Debug)]
pub struct Timeline {
    /// The events still to come, in time order (a run's past events are
    /// dropped: a long session's pushed input keeps no memory).
    events: VecDeque<Event>,
    /// Scripted bodies: body, track, its last two positions.
    tracks: Vec<(BodyId, Track, [DVec3; 2])>,
    /// The gaze override in force, if any.
    pub(super) look_at: Option<Override>,
    /// Covered or shut eyes (left, right).
    pub(super) occluded: [bool; 2],
    /// The imposed neck motion, if any.
    pub(super) shake: Option<Shake>,
    /// The opponent's punches started in the last `run`.
    pub(super) thrown: Vec<Hand>,
    /// The pushes due in the last `run`.
    pub(super) pushes: Vec<(PushPart, DVec3)>,
    /// The imposed translation of the trunk, if any.
    pub(super) carry: Option<Carry>,
}

impl Timeline {
    /// A timeline of `events` (sorted here; events at equal times keep
    /// their order) moving the scripted `bodies` (body, start position).
    pub fn new(events: &[Event], bodies: &[(BodyId, DVec3)]) -> Self {
        let mut events = events.to_vec();
        events.sort_by(|a, b| a.at.total_cmp(&b.at)); // stable: file order at equal times
        Timeline {
            events: events.into(),
            tracks: bodies
                .iter()
                .map(|&(b, p)| (b, Track::new(p), [p; 2]))
                .collect(),
            look_at: None,
            occluded: [false; 2],
            shake: None,
            thrown: Vec::new(),
            pushes: Vec::new(),
            carry: None,
        }
    }

    /// Schedule an event while running: it runs after the events already
    /// scheduled for its time, exactly as if it had been appended to the
    /// scene's timeline. Events in the past run at the next tick.
    pub fn push(&mut self, ev: Event) {
        let at = self.events.partition_point(|e| e.at <= ev.at);
        self.events.insert(at, ev);
    }

    /// Events still to come.
    pub fn pending(&self) -> usize {
        self.events.len()
    }

    /// The kinematic track of a body, if it has one.
    pub fn track_mut(&mut self, body: BodyId) -> Option<&mut Track> {
        self.tracks
            .iter_mut()
            .find(|(b, ..)| *b == body)
            .map(|(_, t, _)| t)
    }

    /// A scripted glove at `at` moving at `v` touches the other fighter:
    /// if the contact has stopped it (its speed along its path has fallen
    /// below half the path's), a punch on its way out comes back from
    /// where the glove really is ([`Track::recoil`]). A glove that only
    /// grazes a guard keeps going.
    /// Returns whether it did.
    pub fn recoil(&mut self, body: BodyId, t: f64, at: DVec3, v: DVec3, dt: f64) -> bool {
        if let Some((_, tr, hist)) = self.tracks.iter_mut().find(|(b, ..)| *b == body)
            && let path = (hist[0] - hist[1]) / dt
            && path.length() > 0.5
            && v.dot(path.normalize()) < 0.5 * path.length()
            && tr.recoil(t, at)
        {
            // Restart the finite differences at the real position.
            *hist = [at, at];
            return true;
        }
        false
    }

    /// Drive the scripted bodies to where their tracks are at `t + dt`,
    /// with the track's velocity and acceleration (finite differences of
    /// its last three positions).
    /// The opponent's trunk goes where its head goes, under it
    /// ([`trunk_under`]).
    pub fn drive(&mut self, world: &mut World, t: f64, dt: f64) {
        let head = world.part(OpponentPart::Head);
        let mut carried = None;
        for (b, tr, hist) in &mut self.tracks {
            let p = tr.position(t + dt);
            let [p1, p2] = *hist;
            let v = (p - p1) / dt;
            let a = (p - 2.0 * p1 + p2) / (dt * dt);
            *hist = [p, p1];
            let (p, v, a) = (p.as_vec3(), v.as_vec3(), a.as_vec3());
            world.drive(*b, p, v, a);
            if *b == head {
                carried = Some((p, v, a));
            }
        }
        let (p, v, a) = carried.unwrap_or((world.position(head), Vec3::ZERO, Vec3::ZERO));
        let trunk = world.part(OpponentPart::Trunk);
        world.drive(trunk, trunk_under(p), v, a);
    }

    /// Run every event due by `t`, in time order.
    pub fn run(&mut self, t: f64, world: &World, face: &Face, face_state: &mut FaceState) {
        self.thrown.clear();
        self.pushes.clear();
        while let Some(ev) = self.events.pop_front() {
            if ev.at > t + 1e-12 {
                self.events.push_front(ev);
                break;
            }
            match ev.action {
                Action::Move { part, to, duration } => {
                    let b = part_body(world, &part);
                    if let Some(tr) = self.track_mut(b) {
                        tr.reach(t, to, duration);
                    }
                }
                Action::Push { part, impulse } => self.pushes.push((part, impulse)),
                Action::Carry { offset, duration } => {
                    let from = self.carry.map_or(DVec3::ZERO, |c| c.offset(t));
                    self.carry = Some(Carry {
                        from,
                        by: offset,
                        t0: t,
                        duration,
                    });
                }
                Action::Wave {
                    part,
                    amplitude,
                    frequency,
                    duration,
                } => {
                    let b = part_body(world, &part);
                    if let Some(tr) = self.track_mut(b) {
                        tr.wave(t, amplitude, frequency, duration);
                    }
                }
                Action::Punch {
                    hand,
                    target,
                    speed,
                    through,
                    glove_only,
                } => {
                    self.thrown.push(hand);
                    let through = through.unwrap_or(FOLLOW_THROUGH);
                    let glove_r = world.plan.glove_radius as f64;
                    // Aimed through the target (follow-through):
                    // the path ends `through` behind the point where the
                    // glove's surface meets the target's, so the glove
                    // arrives at speed and the physics stops it.
                    let (aim, radius) = match target {
                        PunchTarget::Head => (
                            world.rb(Seg::Head).translation().as_dvec3(),
                            0.10 + glove_r - through,
                        ),
                        PunchTarget::Body => (
                            world.rb(Seg::Torso).translation().as_dvec3()
                                + DVec3::new(0.0, 0.1, 0.1),
                            glove_r - through,
                        ),
                        PunchTarget::Point(p) => (p, 0.0),
                    };
                    let b = part_body(world, &hand.glove());
                    let from = world.position(b).as_dvec3();
                    let dir = (aim - from).normalize_or(DVec3::NEG_Z);
                    // Thrown by the body from where it is going: a head
                    // already moving (a scripted step) is not moved again.
                    let head_b = world.part(OpponentPart::Head);
                    let moving = self.track_mut(head_b).and_then(|tr| tr.destination());
                    let head = moving.unwrap_or_else(|| world.position(head_b).as_dvec3());
                    let rear = hand == Hand::Right;
                    let depth = if matches!(target, PunchTarget::Point(_)) {
                        0.0
                    } else {
                        through
                    };
                    let mut th =
                        super::punch::throw(head, aim - dir * radius, depth, rear, !glove_only);
                    if moving.is_some() {
                        (th.step, th.lead) = (DVec3::ZERO, 0.0);
                    }
                    let out = self
                        .track_mut(b)
                        .map(|tr| tr.punch_after(t, th.lead, th.to, speed));
                    if let (Some(dur), Some(tr)) = (out, self.track_mut(head_b))
                        && th.step.length() > 1e-3
                    {
                        tr.lunge(t, head + th.step, th.lead + dur);
                    }
                }
                Action::Feint { hand } => {
                    let head_b = world.part(OpponentPart::Head);
                    let head = world.position(head_b).as_dvec3();
                    let target = world.rb(Seg::Head).translation().as_dvec3();
                    let (step, dir) = super::punch::feint(head, target, hand == Hand::Right);
                    let dur = super::punch::KINETIC_LEAD + 0.12;
                    if let Some(tr) = self.track_mut(head_b) {
                        tr.lunge(t, head + step, dur);
                    }
                    let b = part_body(world, &hand.glove());
                    let from = world.position(b).as_dvec3();
                    if let Some(tr) = self.track_mut(b) {
                        let twitch = from + dir * super::punch::FEINT_TWITCH;
                        tr.lunge(t + super::punch::KINETIC_LEAD, twitch, 0.06);
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
                    let b = world.body_named(&body).expect("validated body name");
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
                    let b = part_body(world, &part);
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
                        kind: ShakeKind::Sine { freq: frequency },
                        t0: t,
                        until: t + duration,
                    })
                }
                Action::TurnHead {
                    yaw_deg,
                    pitch_deg,
                    duration,
                    hold,
                } => {
                    self.shake = Some(Shake {
                        amplitude: DVec2::new(yaw_deg, pitch_deg) * (std::f64::consts::PI / 180.0),
                        kind: ShakeKind::Turn { duration },
                        t0: t,
                        until: t + duration + hold,
                    })
                }
                Action::Emotion {
                    emotion,
                    intensity,
                    speed,
                    pattern,
                } => face_state.set_emotion(face, emotion, intensity as f32, speed, pattern),
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A `TurnHead` starts and ends at rest, reaches its amplitude at the
    /// end of its duration, and peaks at 1.875 A / T halfway (minimum jerk).
    #[test]
    fn turn_head_is_a_minimum_jerk_impulse() {
        let amp = 15f64.to_radians();
        let s = Shake {
            amplitude: DVec2::new(amp, 0.0),
            kind: ShakeKind::Turn { duration: 0.15 },
            t0: 1.0,
            until: 1.45,
        };
        assert_eq!(s.command(1.0).angles.x, 0.0);
        assert_eq!(s.command(1.0).rates.x, 0.0);
        assert!((s.command(1.15).angles.x - amp).abs() < 1e-12);
        assert!(s.command(1.15).rates.x.abs() < 1e-9);
        assert!((s.command(1.3).angles.x - amp).abs() < 1e-12, "held");
        let peak = s.command(1.075).rates.x;
        assert!((peak - 1.875 * amp / 0.15).abs() < 1e-9, "{peak}");
    }

    /// Input pushed every tick for an hour keeps no memory: run events
    /// are dropped (a soak or a learning run pushes millions).
    #[test]
    fn run_events_are_not_kept() {
        let mut sim = crate::scene::LoadedScene::default_scene().sim();
        for k in 0..3000 {
            let to = DVec3::new(0.1 * (k % 3) as f64, 1.5, 0.7);
            sim.push_event(Event {
                at: sim.time(),
                action: Action::Move {
                    part: Part::LeftGlove,
                    to,
                    duration: 0.02,
                },
            });
            sim.step();
        }
        // Only the scene's own events still to come are left.
        assert!(sim.timeline.pending() <= 6, "{}", sim.timeline.pending());
    }
}
