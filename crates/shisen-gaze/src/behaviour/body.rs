//! The body's share of the plan (boxing.md; docs/model/body.md): which
//! evasion meets a seen punch, the waist's turn and bend and the knees'
//! dip that carry it out, the footwork that holds the fighting range, and
//! the trunk's turn in the VH's own punches. The plan is kinematic
//! (minimum-jerk paths); the physical waist follows it through its PD law.

use glam::{DQuat, DVec3};
use rand::{Rng, RngExt};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::{BehaviourParams, Reach};
use crate::anatomy::trunk;
use crate::personality::Personality;
use crate::vision::Seen;

/// A way out of a punch's path, chosen from what vision reports.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize, JsonSchema)]
pub enum Evasion {
    /// The head off the punch line sideways: a lateral bend and turn at
    /// the waist, knees slightly bent, to the side the punching glove is
    /// on (outside the arm, where a counter is open).
    Slip,
    /// Under a punch that comes from the side (a hook): knees bend, the
    /// trunk bends forward.
    Duck,
    /// The head back out of reach: the trunk leans back at the waist.
    LeanBack,
}

/// The waist's turn and bend (yaw, pitch, roll from neutral, rad; pitch
/// positive back) and the knees' dip (m) that carry out an evasion.
/// Slip: 12 deg of lateral bend and 9 deg of turn take the head about
/// 15 cm sideways; duck: 16 cm of knee bend and 17 deg forward; lean back
/// 13 deg. Magnitudes are ours, sized so each takes the head at least a
/// head's width (15 cm) off its line.
fn evasion_posture(e: Evasion, right: bool) -> (DVec3, f64) {
    let s = if right { 1.0 } else { -1.0 };
    match e {
        Evasion::Slip => (DVec3::new(-0.15 * s, 0.0, 0.26 * s), 0.05),
        Evasion::Duck => (DVec3::new(0.0, -0.3, 0.0), 0.16),
        Evasion::LeanBack => (DVec3::new(0.0, 0.23, 0.0), 0.0),
    }
}

/// The planned posture at a time.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Posture {
    /// Ground point under the waist joint, world, m.
    pub pelvis: DVec3,
    /// Waist turn and bend from neutral (yaw, pitch, roll), rad.
    pub waist: DVec3,
    /// Knee dip, m.
    pub crouch: f64,
    /// The body's heading (turn about +Y from facing +Z), rad.
    pub facing: f64,
}

/// The body's plan: minimum-jerk paths for the pelvis, the waist and the
/// knees (each holds its end until replaced), and where the trunk is.
#[derive(Clone, Debug, Default)]
pub(super) struct BodyPlan {
    step: Option<Reach>,
    turn: Option<Reach>,
    bend: Option<Reach>,
    dip: Option<Reach>,
    /// The trunk as it is: the waist joint's offset from rest and the
    /// trunk's rotation (the guard's stance rides on it).
    pub trunk: (DVec3, DQuat),
    /// Footwork moves started.
    pub steps: u32,
    /// Since when the feet have been still (for circling), s.
    still_since: f64,
    /// The side the last circling step went to (+1 the VH's left).
    circled: f64,
}

fn at(r: &Option<Reach>, t: f64) -> DVec3 {
    r.as_ref().map_or(DVec3::ZERO, |r| r.at(t))
}

impl BodyPlan {
    /// The planned posture at `t`.
    pub fn posture(&self, t: f64) -> Posture {
        Posture {
            pelvis: at(&self.step, t),
            waist: at(&self.bend, t),
            crouch: at(&self.dip, t).y,
            facing: at(&self.turn, t).x,
        }
    }

    /// A point given in the trunk's rest frame, where the trunk is now.
    pub fn on_trunk(&self, rest: DVec3) -> DVec3 {
        let waist = DVec3::from_array(trunk::WAIST);
        self.trunk.0 + waist + self.trunk.1 * (rest - waist)
    }

    /// A new waist path from where the waist is planned now (`t`), held
    /// there until `t0`.
    fn bend_to(&mut self, to: DVec3, t: f64, t0: f64, dur: f64) {
        let from = at(&self.bend, t);
        self.bend = Some(Reach {
            from,
            to,
            t0,
            dur,
            back: false,
        });
    }

    fn dip_to(&mut self, crouch: f64, t: f64, t0: f64, dur: f64) {
        let from = at(&self.dip, t);
        self.dip = Some(Reach {
            from,
            to: DVec3::new(0.0, crouch, 0.0),
            t0,
            dur,
            back: false,
        });
    }

    /// Start an evasion: the waist and knees move once the reaction time
    /// is over; `right` is the side (the VH's) a slip goes to.
    pub fn evade(&mut self, e: Evasion, right: bool, t: f64, p: &BehaviourParams) {
        let (waist, crouch) = evasion_posture(e, right);
        let t0 = t + p.evade_reaction;
        self.bend_to(waist, t, t0, p.evade_time);
        self.dip_to(crouch, t, t0, p.evade_time);
    }

    /// Back to the neutral posture, from where the plan is now.
    pub fn recover(&mut self, t: f64) {
        self.bend_to(DVec3::ZERO, t, t, 0.35);
        self.dip_to(0.0, t, t, 0.35);
    }

    /// The trunk's turn in a punch of `hand` (0 left, the lead hand of an
    /// orthodox stance) lasting `dur`, out and back (to where the waist
    /// was; the attack's end recovers from there): the cross turns the rear
    /// shoulder through, the jab the lead shoulder a little.
    pub fn punch(&mut self, hand: usize, t: f64, dur: f64) {
        let yaw = if hand == 1 { 0.35 } else { -0.12 };
        self.bend = Some(Reach {
            from: at(&self.bend, t),
            to: DVec3::new(yaw, -0.05, 0.0),
            t0: t,
            dur,
            back: true,
        });
    }

    /// Footwork: step to hold the fighting range to the opponent's seen
    /// head (horizontal distance from the waist joint), when it will be off
    /// by more than the tolerance by the time a step is taken (the
    /// opponent's approach extrapolated, as much as `approach_read`
    /// says) and no step is under way.
    pub fn keep_range(&mut self, p: &BehaviourParams, head: Option<&Seen>, t: f64) {
        if !p.footwork || self.step.as_ref().is_some_and(|s| !s.done(t)) {
            return;
        }
        let Some(head) = head else { return };
        let pelvis = at(&self.step, t);
        let waist = DVec3::from_array(trunk::WAIST);
        let to = head.position - (pelvis + DVec3::new(waist.x, 0.0, waist.z));
        let to = DVec3::new(to.x, 0.0, to.z);
        let range = to.length();
        if range < 1e-6 {
            return;
        }
        // Where the range will be once a step decided now has been taken,
        // at the opponent's present closing speed.
        let opening = head.velocity.dot(to / range);
        let off = range - p.range + p.approach_read * opening * (p.guard_reaction + p.step_time);
        // Turn to face the opponent as it circles (the feet step round).
        let bearing = to.x.atan2(to.z);
        let facing = at(&self.turn, t).x;
        if (bearing - facing).abs() > p.turn_tolerance_deg.to_radians()
            && self.turn.as_ref().is_none_or(|r| r.done(t))
        {
            self.turn = Some(Reach {
                from: DVec3::new(facing, 0.0, 0.0),
                to: DVec3::new(bearing, 0.0, 0.0),
                t0: t + p.guard_reaction,
                dur: p.step_time,
                back: false,
            });
        }
        if off.abs() <= p.range_tolerance {
            self.circle(p, pelvis, head.position, t);
            return;
        }
        let by = off.clamp(-p.max_step, p.max_step);
        self.step = Some(Reach {
            from: pelvis,
            to: pelvis + to / range * by,
            t0: t + p.guard_reaction,
            dur: p.step_time,
            back: false,
        });
        self.steps += 1;
        self.still_since = t + p.guard_reaction + p.step_time;
    }

    /// Whether a footwork step is under way at `t`.
    pub fn stepping(&self, t: f64) -> bool {
        self.step.as_ref().is_some_and(|s| !s.done(t))
    }

    /// Step `by` m toward `point` (world; the opponent; away if `by` is
    /// negative), at most `max_step`, unless a step is under way: in to
    /// attack from long range, out from a read punch. Returns when the
    /// foot lands (now, if no step is taken).
    pub fn step_in(&mut self, p: &BehaviourParams, point: DVec3, by: f64, t: f64) -> f64 {
        if !p.footwork || by.abs() < 1e-3 || self.stepping(t) {
            return t;
        }
        let pelvis = at(&self.step, t);
        let toward = DVec3::new(point.x - pelvis.x, 0.0, point.z - pelvis.z).normalize_or_zero();
        self.step = Some(Reach {
            from: pelvis,
            to: pelvis + toward * by.clamp(-p.max_step, p.max_step),
            t0: t,
            dur: p.step_time,
            back: false,
        });
        self.steps += 1;
        self.still_since = t + p.step_time;
        t + p.step_time
    }

    /// Walk to `to` (a ground point, world) a footwork step at a time,
    /// facing the way it goes while more than a step away and then
    /// `look` (between rounds: to the corner, then facing the ring).
    pub fn walk_to(&mut self, p: &BehaviourParams, to: DVec3, look: DVec3, t: f64) {
        if self.step.as_ref().is_some_and(|s| !s.done(t)) {
            return;
        }
        let pelvis = at(&self.step, t);
        let d = DVec3::new(to.x - pelvis.x, 0.0, to.z - pelvis.z);
        let far = d.length() > p.max_step + p.range_tolerance;
        let toward = if far { d } else { look - pelvis };
        if toward.length() > 1e-6 {
            self.turn_to(toward.x.atan2(toward.z), p, t);
        }
        if d.length() <= p.range_tolerance {
            return;
        }
        let by = d.length().min(p.max_step);
        self.step = Some(Reach {
            from: pelvis,
            to: pelvis + d.normalize() * by,
            t0: t,
            dur: p.step_time,
            back: false,
        });
        self.steps += 1;
        self.still_since = t + p.step_time;
    }

    /// Plan the feet from `pelvis` (a ground point) at `t`, unless a step
    /// is under way.
    pub fn place(&mut self, pelvis: DVec3, t: f64) {
        if self.step.as_ref().is_some_and(|s| !s.done(t)) {
            return;
        }
        self.step = Some(Reach {
            from: pelvis,
            to: pelvis,
            t0: t,
            dur: 1e-3,
            back: false,
        });
    }

    /// Give ground from a blow: a step straight away from `from` (a
    /// world point, the opponent), with the trunk thrown back.
    pub fn give_ground(&mut self, p: &BehaviourParams, from: DVec3, t: f64) {
        let pelvis = at(&self.step, t);
        let away = DVec3::new(pelvis.x - from.x, 0.0, pelvis.z - from.z).normalize_or(DVec3::NEG_Z);
        self.step = Some(Reach {
            from: pelvis,
            to: pelvis + away * p.max_step,
            t0: t,
            dur: p.step_time,
            back: false,
        });
        self.steps += 1;
        self.still_since = t + p.step_time;
        // The trunk thrown back and brought up again.
        self.bend = Some(Reach {
            from: at(&self.bend, t),
            to: DVec3::new(0.0, 0.15, 0.0),
            t0: t,
            dur: 0.8,
            back: true,
        });
    }

    /// Turn the body to `heading` (rad about +Y from +Z) if it is more
    /// than the tolerance off and no turn is under way, by the shorter way.
    fn turn_to(&mut self, heading: f64, p: &BehaviourParams, t: f64) {
        let facing = at(&self.turn, t).x;
        let off = (heading - facing + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)
            - std::f64::consts::PI;
        if off.abs() > p.turn_tolerance_deg.to_radians()
            && self.turn.as_ref().is_none_or(|r| r.done(t))
        {
            self.turn = Some(Reach {
                from: DVec3::new(facing, 0.0, 0.0),
                to: DVec3::new(facing + off, 0.0, 0.0),
                t0: t,
                dur: p.step_time.max(off.abs() / 4.0),
                back: false,
            });
        }
    }

    /// Circling: once the feet have been still `circle_after` seconds in
    /// range, a step of `max_step` round the opponent, to alternate sides,
    /// kept within about a step of square to it (the turn to face
    /// follows).
    fn circle(&mut self, p: &BehaviourParams, pelvis: DVec3, opponent: DVec3, t: f64) {
        let Some(after) = p.circle_after else { return };
        if t < self.still_since + after {
            return;
        }
        let centre = DVec3::new(opponent.x, 0.0, opponent.z);
        let arm = pelvis - centre;
        let r = arm.length().max(1e-6);
        // Alternate sides while square to the opponent; once round to one
        // side, back toward square (a circle that wanders round the
        // opponent would leave it facing empty canvas).
        let facing = at(&self.turn, t).x;
        self.circled = if facing.abs() > 0.15 {
            -facing.signum()
        } else if self.circled > 0.0 {
            -1.0
        } else {
            1.0
        };
        let turn = DQuat::from_rotation_y(self.circled * p.max_step / r);
        self.step = Some(Reach {
            from: pelvis,
            to: centre + turn * arm,
            t0: t,
            dur: p.step_time,
            back: false,
        });
        self.steps += 1;
        self.still_since = t + p.step_time;
    }
}

/// Which evasion meets a punch seen as `glove` heading for `head`, if
/// the VH evades it at all (the personality's `evade` share; the rest are
/// blocked). A glove that comes from the side (more than 25 cm off the
/// line between the fighters' heads) is a hook, ducked; a straight punch
/// is slipped, or leant away from one time in four. Returns the evasion
/// and whether it goes to the VH's right.
pub fn choose_evasion(
    pers: &Personality,
    glove: &Seen,
    head: DVec3,
    opponent_head: Option<DVec3>,
    rng: &mut impl Rng,
) -> Option<(Evasion, bool)> {
    // Only punches at the head can be evaded by moving the head.
    let heading = glove.velocity.normalize_or_zero();
    let to = head - glove.position;
    let miss = (to - to.dot(heading) * heading).length();
    if miss > 0.15 || rng.random::<f64>() >= pers.evade {
        return None;
    }
    // The glove's side, seen from the VH: -X is its right.
    let right = glove.position.x < head.x;
    let from_side = opponent_head.is_some_and(|o| {
        let line = DVec3::new(o.x - head.x, 0.0, o.z - head.z).normalize_or_zero();
        let g = glove.position - head;
        let g = DVec3::new(g.x, 0.0, g.z);
        (g - line * g.dot(line)).length() > 0.25
    });
    let e = if from_side {
        Evasion::Duck
    } else if rng.random::<f64>() < 0.75 {
        Evasion::Slip
    } else {
        Evasion::LeanBack
    };
    Some((e, right))
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand::rngs::StdRng;

    const HEAD: DVec3 = DVec3::new(0.0, 1.685, 0.0);
    const OPPONENT: DVec3 = DVec3::new(0.0, 1.685, 1.3);

    fn glove(at: DVec3, toward: DVec3, speed: f64) -> Seen {
        Seen {
            position: at,
            velocity: (toward - at).normalize() * speed,
            ..Seen::test_default()
        }
    }

    fn choose(pers: &Personality, g: &Seen, seed: u64) -> Option<(Evasion, bool)> {
        choose_evasion(
            pers,
            g,
            HEAD,
            Some(OPPONENT),
            &mut StdRng::seed_from_u64(seed),
        )
    }

    #[test]
    fn evasions_follow_the_punch_seen() {
        let always = Personality {
            evade: 1.0,
            ..Personality::default()
        };
        // A jab from the opponent's left glove (on the VH's right, -X):
        // slipped to that side, or leant away from.
        let jab = glove(DVec3::new(-0.13, 1.55, 1.05), HEAD, 2.0);
        let mut kinds = Vec::new();
        for seed in 0..40 {
            let (e, right) = choose(&always, &jab, seed).expect("evaded");
            assert!(right, "outside the jab: the VH's right");
            kinds.push(e);
        }
        let slips = kinds.iter().filter(|&&e| e == Evasion::Slip).count();
        assert!((20..40).contains(&slips), "mostly slips: {slips} of 40");
        assert!(
            kinds.iter().all(|&e| e != Evasion::Duck),
            "a straight punch is not ducked"
        );
        // A wide punch (a hook) is ducked.
        let hook = glove(DVec3::new(0.55, 1.62, 1.05), HEAD, 2.0);
        assert_eq!(choose(&always, &hook, 1).map(|c| c.0), Some(Evasion::Duck));
        // A punch at the body is not evaded by moving the head.
        let body = glove(
            DVec3::new(-0.13, 1.55, 1.05),
            DVec3::new(0.0, 1.25, 0.0),
            2.0,
        );
        assert_eq!(choose(&always, &body, 1), None);
        // A boxer that never evades covers up.
        let never = Personality {
            evade: 0.0,
            ..Personality::default()
        };
        assert_eq!(choose(&never, &jab, 1), None);
    }

    #[test]
    fn footwork_steps_back_as_the_opponent_comes_in_and_holds_still_in_range() {
        let p = BehaviourParams::default();
        let head = |z: f64, vz: f64| Seen {
            position: DVec3::new(0.0, 1.685, z),
            velocity: DVec3::new(0.0, 0.0, vz),
            ..Seen::test_default()
        };
        let mut plan = BodyPlan::default();
        plan.keep_range(&p, Some(&head(p.range, 0.0)), 0.0);
        assert_eq!(plan.steps, 0, "in range: no step");
        // Coming in at 0.4 m/s, not yet out of range: it steps already.
        plan.keep_range(&p, Some(&head(p.range - 0.05, -0.4)), 0.0);
        assert_eq!(plan.steps, 1);
        let end = plan.posture(10.0).pelvis;
        assert!(end.z < -0.1 && end.z >= -p.max_step, "stepped back: {end}");
        // No second step while one is under way.
        plan.keep_range(&p, Some(&head(0.5, -0.4)), 0.1);
        assert_eq!(plan.steps, 1);
        // A novice's feet answer where the opponent is, not where it is
        // going: the same approach takes no step yet.
        let novice = BehaviourParams {
            approach_read: 0.0,
            ..p.clone()
        };
        let mut plan = BodyPlan::default();
        plan.keep_range(&novice, Some(&head(p.range - 0.05, -0.4)), 0.0);
        assert_eq!(plan.steps, 0, "not yet out of range");
        plan.keep_range(&novice, Some(&head(p.range - 0.2, -0.4)), 0.0);
        assert_eq!(plan.steps, 1, "out of range now");
    }
}
