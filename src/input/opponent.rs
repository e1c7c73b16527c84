//! From what you want ([`Intent`]) to timeline events on your avatar:
//! `Move` for gloves and head following the input, `Punch` for throws.
//! Going through the timeline (not poking the tracks) is what makes a
//! recorded session replay tick for tick.

use glam::{DVec3, Vec3};

use shisen::physics::body::BodyPlan;
use shisen::sim::timeline::{Action, Event, Hand, Part, PunchTarget};
use shisen::sim::track::Track;

/// What you want your avatar to do this frame, in world metres.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Intent {
    /// Offset of each glove (your left, right) from its guard position;
    /// negative z pushes it toward the VH.
    pub glove_offset: [Vec3; 2],
    /// Throw this glove now.
    pub throw: [bool; 2],
    /// Offset of your head from where it stands (dodges).
    pub head_offset: Vec3,
    /// A step: +1 in toward the VH, -1 back, 0 none.
    pub step: f32,
    /// Feint with the lead hand now.
    pub feint: bool,
}

/// How far a dodge moves your head, m: sideways, down (duck), back.
pub const DODGE: Vec3 = Vec3::new(0.15, 0.12, 0.12);
/// One step of your footwork, m: the VH's ranges differ by a step
/// (`shisen_gaze::behaviour::STEP_IN`).
pub const STEP: f64 = shisen_gaze::behaviour::STEP_IN;
/// You stand at most this far in front of or behind where you began, m.
const STEP_SPAN: f64 = 0.9;
/// Peak glove speed of a throw, m/s (a fast jab).
pub const PUNCH_SPEED: f64 = 6.0;
/// A glove or head follows the input over this minimum-jerk time, s.
const FOLLOW_S: f64 = 0.08;
/// Head dodges take this long, s.
const DODGE_S: f64 = 0.15;
/// Input changes smaller than this send no event, m.
const EPS: f64 = 0.002;

/// Turns intents into events, remembering what was last asked for.
#[derive(Clone, Debug)]
pub struct OpponentControl {
    /// Rest positions: head, left glove, right glove.
    rest: [DVec3; 3],
    /// Last commanded positions.
    sent: [DVec3; 3],
    /// A glove's punch is in flight until then (sim time).
    busy_until: [f64; 2],
    /// Throw distance, m (the mouse wheel sets it).
    pub reach: f64,
    /// Where your head stood at the start, z (footwork's span).
    start_z: f64,
}

impl OpponentControl {
    /// Control of the avatar of `plan`, standing at rest.
    pub fn new(plan: &BodyPlan) -> Self {
        let rest = [
            plan.opponent_head,
            plan.opponent_gloves[0],
            plan.opponent_gloves[1],
        ]
        .map(|v| v.as_dvec3());
        OpponentControl {
            rest,
            sent: rest,
            busy_until: [f64::NEG_INFINITY; 2],
            reach: 0.5,
            start_z: rest[0].z,
        }
    }

    /// Guard position of a glove (0 your left, 1 right), world.
    pub fn glove_rest(&self, k: usize) -> DVec3 {
        self.rest[1 + k]
    }

    /// Whether a glove's punch is in flight at `t`.
    pub fn punching(&self, k: usize, t: f64) -> bool {
        t < self.busy_until[k]
    }

    /// The events that carry out `intent` at simulation time `t`.
    pub fn update(&mut self, t: f64, intent: &Intent) -> Vec<Event> {
        let mut out = Vec::new();
        // Footwork: the head, and the gloves' guard with it, a step toward
        // the VH (-Z: you face it) or away, within a span of the start.
        if intent.step != 0.0 {
            let by = -f64::from(intent.step.signum()) * STEP;
            let z = (self.rest[0].z + by).clamp(self.start_z - STEP_SPAN, self.start_z + STEP_SPAN);
            let dz = z - self.rest[0].z;
            for r in &mut self.rest {
                r.z += dz;
            }
        }
        let head = self.rest[0] + intent.head_offset.as_dvec3();
        if head.distance(self.sent[0]) > EPS {
            self.sent[0] = head;
            out.push(Event {
                at: t,
                action: Action::Move {
                    part: Part::Head,
                    to: head,
                    duration: DODGE_S,
                },
            });
        }
        if intent.feint && !self.punching(0, t) {
            out.push(Event {
                at: t,
                action: Action::Feint { hand: Hand::Left },
            });
        }
        for k in 0..2 {
            if self.punching(k, t) {
                continue;
            }
            let (part, hand) = [
                (Part::LeftGlove, Hand::Left),
                (Part::RightGlove, Hand::Right),
            ][k]
                .clone();
            if intent.throw[k] {
                let from = self.sent[1 + k];
                let to = from + DVec3::NEG_Z * self.reach;
                // Same timing as the track will use (out, then back).
                let out_s = Track::new(from).punch(t, to, PUNCH_SPEED);
                self.busy_until[k] = t + 2.0 * out_s;
                out.push(Event {
                    at: t,
                    action: Action::Punch {
                        hand,
                        target: PunchTarget::Point(to),
                        speed: PUNCH_SPEED,
                        through: None,
                        glove_only: false,
                    },
                });
                continue;
            }
            let want = self.rest[1 + k] + intent.glove_offset[k].as_dvec3();
            if want.distance(self.sent[1 + k]) > EPS {
                self.sent[1 + k] = want;
                out.push(Event {
                    at: t,
                    action: Action::Move {
                        part,
                        to: want,
                        duration: FOLLOW_S,
                    },
                });
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn moves_only_on_change_and_punch_blocks_following() {
        let mut c = OpponentControl::new(&BodyPlan::default());
        assert!(c.update(0.0, &Intent::default()).is_empty());
        let mut i = Intent::default();
        i.glove_offset[0] = Vec3::new(0.1, 0.0, 0.0);
        assert_eq!(c.update(0.1, &i).len(), 1);
        assert!(c.update(0.2, &i).is_empty(), "no change, no event");
        i.throw[0] = true;
        let ev = c.update(0.3, &i);
        assert!(matches!(ev[0].action, Action::Punch { .. }));
        assert!(c.punching(0, 0.31));
        i.throw[0] = false;
        i.glove_offset[0] = Vec3::ZERO;
        assert!(c.update(0.32, &i).is_empty(), "glove busy punching");
        assert_eq!(c.update(1.0, &i).len(), 1, "follows again after the punch");
    }
}
