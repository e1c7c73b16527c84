//! The timeline: what happens to the opponent, the props and the VH's
//! overrides at given times (scene `timeline`, live input), and how each
//! event changes the running simulation.

use std::path::PathBuf;

use glam::{DVec2, DVec3};
use serde::{Deserialize, Serialize};

use super::track::Track;
use crate::physics::body::{OpponentPart, Seg};
use crate::physics::world::World;
use shisen_face::{Face, FaceState};
use shisen_gaze::oculomotor::{AxisCommand, GazeShiftLaw};
use shisen_gaze::util::math::{min_jerk, min_jerk_d, min_jerk_dd};
use shisen_gaze::vision::BodyId;

/// The opponent's hands.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
pub enum Hand {
    /// The opponent's left glove ("left_glove").
    Left,
    /// The opponent's right glove ("right_glove").
    Right,
}

/// A script-movable body: an opponent part or a kinematic prop.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
pub enum Part {
    /// Opponent's head.
    Head,
    /// Opponent's left glove.
    LeftGlove,
    /// Opponent's right glove.
    RightGlove,
    /// A kinematic prop declared in `bodies`.
    Body(String),
}

/// The VH's left or right (eyes).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
pub enum Side {
    /// The VH's left.
    Left,
    /// The VH's right.
    Right,
}

/// Where an opponent punch is aimed.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
pub enum PunchTarget {
    /// The VH's head (where it is when the punch starts).
    Head,
    /// The VH's torso.
    Body,
    /// A world point.
    Point(#[serde(deserialize_with = "shisen_gaze::util::check::position")] DVec3),
}

/// Something that happens at a time in the scene.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
pub enum Action {
    /// Move a part to a point along a minimum-jerk path.
    Move {
        /// What moves.
        part: Part,
        /// Destination, world metres.
        #[serde(deserialize_with = "shisen_gaze::util::check::position")]
        to: DVec3,
        /// Duration, seconds.
        #[serde(deserialize_with = "shisen_gaze::util::check::positive")]
        duration: f64,
    },
    /// Throw a punch at the VH and bring the glove back.
    Punch {
        /// Which glove.
        hand: Hand,
        /// Aim.
        target: PunchTarget,
        /// Peak glove speed, m/s.
        #[serde(deserialize_with = "shisen_gaze::util::check::positive")]
        speed: f64,
        /// How far behind the contact point the punch is aimed, m
        /// (`Head` and `Body` targets; default [`FOLLOW_THROUGH`]): a
        /// committed punch is thrown deeper and lands harder.
        #[serde(
            default,
            deserialize_with = "shisen_gaze::util::check::opt_non_negative",
            skip_serializing_if = "Option::is_none"
        )]
        through: Option<f64>,
    },
    /// Wave a part sinusoidally about its current position.
    Wave {
        /// What waves.
        part: Part,
        /// Peak displacement along each axis, metres.
        #[serde(deserialize_with = "shisen_gaze::util::check::position")]
        amplitude: DVec3,
        /// Frequency, Hz.
        #[serde(deserialize_with = "shisen_gaze::util::check::positive")]
        frequency: f64,
        /// Duration, seconds.
        #[serde(deserialize_with = "shisen_gaze::util::check::positive")]
        duration: f64,
    },
    /// Change the facial expression (face.md 7): from the current values to
    /// `emotion` at `intensity`, over the table 5.9/5.10 duration at `speed`.
    Emotion {
        /// One of the 35 emotions of table A (`Neutral`, `Happiness`, ...).
        emotion: shisen_face::tables::Emotion,
        /// Intensity, 0-1.
        #[serde(
            default = "one",
            deserialize_with = "shisen_gaze::util::check::unit_interval"
        )]
        intensity: f64,
        /// `Fast`, `Typical` or `Slow` (the thesis's speeds 1, 2, 3).
        #[serde(default)]
        speed: shisen_face::timing::Speed,
        /// Onset/offset shape `I`..`V` (default `III`, the thesis's choice).
        #[serde(default)]
        pattern: shisen_face::timing::Pattern,
    },
    /// Play a script in the thesis's plain format (`emotion duration
    /// speed` per line, face.md 9) from this time; the file is relative to
    /// the scene and is expanded into `Emotion` events when the scene loads.
    EmotionScript {
        /// The script file.
        file: PathBuf,
    },
    /// Override the gaze: look at a world point until a time.
    LookAt {
        /// The point, world metres.
        #[serde(deserialize_with = "shisen_gaze::util::check::position")]
        point: DVec3,
        /// End of the override, seconds.
        #[serde(deserialize_with = "shisen_gaze::util::check::non_negative")]
        until: f64,
        /// Attention amount A for the head law (M8); default the
        /// personality's `a2` (the head faces the point).
        #[serde(
            default,
            deserialize_with = "shisen_gaze::util::check::opt_non_negative",
            skip_serializing_if = "Option::is_none"
        )]
        amount: Option<f64>,
        /// How to shift the gaze there (default: the scene's law).
        #[serde(default)]
        style: Option<shisen_gaze::oculomotor::GazeShiftLaw>,
    },
    /// Override the gaze: follow a body (by name) until a time.
    Track {
        /// Body name (`head`, `left_glove`, a prop...).
        body: String,
        /// End of the override, seconds.
        #[serde(deserialize_with = "shisen_gaze::util::check::non_negative")]
        until: f64,
    },
    /// Move a part at constant angular speed on a horizontal circle about
    /// a centre (a pursuit target).
    Orbit {
        /// What moves.
        part: Part,
        /// Centre of the circle, world metres.
        #[serde(deserialize_with = "shisen_gaze::util::check::position")]
        centre: DVec3,
        /// Angular speed about +Y (positive: toward the VH's left), deg/s.
        #[serde(deserialize_with = "shisen_gaze::util::check::finite")]
        rate_deg: f64,
        /// Duration, seconds.
        #[serde(deserialize_with = "shisen_gaze::util::check::positive")]
        duration: f64,
    },
    /// Shut or cover one eye (`Some(Left)`, `Some(Right)`) or none (`None`).
    Occlude {
        /// The covered eye.
        eye: Option<Side>,
    },
    /// Impose a sinusoidal neck motion (overriding the head law), e.g. to
    /// measure the VOR: yaw and pitch amplitudes in degrees.
    ShakeHead {
        /// Yaw amplitude, deg.
        #[serde(deserialize_with = "shisen_gaze::util::check::non_negative")]
        yaw_deg: f64,
        /// Pitch amplitude, deg.
        #[serde(default, deserialize_with = "shisen_gaze::util::check::non_negative")]
        pitch_deg: f64,
        /// Frequency, Hz.
        #[serde(deserialize_with = "shisen_gaze::util::check::positive")]
        frequency: f64,
        /// Duration, s.
        #[serde(deserialize_with = "shisen_gaze::util::check::positive")]
        duration: f64,
    },
    /// Impose a quick minimum-jerk neck turn by `yaw_deg` / `pitch_deg`
    /// over `duration` s and hold it for `hold` s (overriding the head law):
    /// a passive head impulse, e.g. to measure the VOR's latency.
    TurnHead {
        /// Yaw, deg (positive: to the VH's left).
        #[serde(deserialize_with = "shisen_gaze::util::check::finite")]
        yaw_deg: f64,
        /// Pitch, deg (positive: up).
        #[serde(default, deserialize_with = "shisen_gaze::util::check::finite")]
        pitch_deg: f64,
        /// Duration of the turn, s.
        #[serde(deserialize_with = "shisen_gaze::util::check::positive")]
        duration: f64,
        /// How long the turned head is held afterwards, s.
        #[serde(default, deserialize_with = "shisen_gaze::util::check::non_negative")]
        hold: f64,
    },
}

/// How far behind the contact point a scripted punch at the head or body
/// is aimed, m. A punch is thrown through its target, so the glove meets
/// the surface still moving (at about half its peak speed with a
/// minimum-jerk path) and the physics, not the path, stops it: it lands a
/// blow (`sim::blows`). Kept short for now: the glove's drive is a stiff
/// spring toward the path, and a deeper aim would push it through a guard
/// that has met it.
pub const FOLLOW_THROUGH: f64 = 0.05;

/// A timeline entry.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Event {
    /// Start time, seconds.
    #[serde(deserialize_with = "shisen_gaze::util::check::non_negative")]
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
    events: Vec<Event>,
    next: usize,
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
}

impl Timeline {
    /// A timeline of `events` (sorted here; events at equal times keep
    /// their order) moving the scripted `bodies` (body, start position).
    pub fn new(events: &[Event], bodies: &[(BodyId, DVec3)]) -> Self {
        let mut events = events.to_vec();
        events.sort_by(|a, b| a.at.total_cmp(&b.at)); // stable: file order at equal times
        Timeline {
            events,
            next: 0,
            tracks: bodies
                .iter()
                .map(|&(b, p)| (b, Track::new(p), [p; 2]))
                .collect(),
            look_at: None,
            occluded: [false; 2],
            shake: None,
            thrown: Vec::new(),
        }
    }

    /// Schedule an event while running: it runs after the events already
    /// scheduled for its time, exactly as if it had been appended to the
    /// scene's timeline. Events in the past run at the next tick.
    pub fn push(&mut self, ev: Event) {
        let at = self.next + self.events[self.next..].partition_point(|e| e.at <= ev.at);
        self.events.insert(at, ev);
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
    pub fn drive(&mut self, world: &mut World, t: f64, dt: f64) {
        for (b, tr, hist) in &mut self.tracks {
            let p = tr.position(t + dt);
            let [p1, p2] = *hist;
            let v = (p - p1) / dt;
            let a = (p - 2.0 * p1 + p2) / (dt * dt);
            *hist = [p, p1];
            world.drive(*b, p.as_vec3(), v.as_vec3(), a.as_vec3());
        }
    }

    /// Run every event due by `t`, in time order.
    pub fn run(&mut self, t: f64, world: &World, face: &Face, face_state: &mut FaceState) {
        self.thrown.clear();
        while self.next < self.events.len() && self.events[self.next].at <= t + 1e-12 {
            let ev = self.events[self.next].clone();
            self.next += 1;
            match ev.action {
                Action::Move { part, to, duration } => {
                    let b = part_body(world, &part);
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
                    let part = match hand {
                        Hand::Left => Part::LeftGlove,
                        Hand::Right => Part::RightGlove,
                    };
                    let b = part_body(world, &part);
                    let from = world.position(b).as_dvec3();
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
}
