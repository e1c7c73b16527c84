//! Your punches thrown by a body (docs/model/boxing.md "Ranges" and
//! "Cues"): how far your arm reaches, the step your body takes behind a
//! punch beyond it, and the order of the kinetic chain (the body first,
//! the glove after), which is what the VH can read before a glove flies.
//! A feint is the body's part without the punch.

use glam::DVec3;

use shisen_gaze::behaviour::{AIM_DEPTH, CONTACT, Ranges};

/// How long the body's part of a stepping punch leads the glove, s: in a
/// straight punch thrown with a step the front foot steps or slides toward
/// the target and the body moves before the arm extends (the initiation
/// phase, Lenetsky et al. 2020, J. Strength Cond. Res. 34:1040), and the
/// whole delivery takes longer than the hand's flight (Piorkowski, Lees &
/// Barton 2011, Sports Biomech. 10:1: "a defender may have more evasion
/// time than previously reported"). 0.2 s is our estimate: about the
/// first two thirds of a 0.3 m step, the glove leaving to land with the
/// foot.
pub const KINETIC_LEAD: f64 = 0.2;
/// How far a rear-hand punch carries the head toward the lead side, m:
/// the rear hip and shoulder turn forward and the head moves over the
/// lead leg (our estimate from the shoulders' 40-deg turn, behaviour/range.rs).
pub const CROSS_SHIFT: f64 = 0.06;
/// A feint's step, m: half a step in, and back.
pub const FEINT_STEP: f64 = 0.15;
/// A feint's glove twitch toward the target, m, out and back.
pub const FEINT_TWITCH: f64 = 0.05;

/// A punch as the body throws it: where the glove goes, the body's step
/// (the head's offset, out and back) and how long the step leads the glove.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Throw {
    /// The glove's end point, world.
    pub to: DVec3,
    /// The head's step behind the punch, world (zero: none).
    pub step: DVec3,
    /// How long the step starts before the glove, s.
    pub lead: f64,
}

/// The punch thrown at `to` (the glove's aimed end point, `through` m
/// behind the contact) by a body whose head is at `head`, with the rear
/// hand (`rear`) or the lead. The arm with the shoulder's travel reaches
/// `Ranges::mid - CONTACT` from the head to the contact, measured on the
/// ground; beyond that the body steps in (at most a step), leading the
/// glove by [`KINETIC_LEAD`], and a target farther still is punched short
/// (the glove stops at full reach, with its follow-through). A rear-hand
/// punch that steps carries the head [`CROSS_SHIFT`] toward the lead
/// side. `body: false` throws the glove alone, as the seed did: no reach,
/// no step, no lead (a scripted step or the benchmark without cues).
pub fn throw(head: DVec3, to: DVec3, through: f64, rear: bool, body: bool) -> Throw {
    let arm = Ranges::HUMAN.mid - CONTACT;
    let full = Ranges::HUMAN.glove_reach();
    let r = DVec3::new(to.x - head.x, 0.0, to.z - head.z);
    let d = r.length();
    // How far the contact is: the follow-through is not reach.
    let contact = (d - through.max(0.0)).max(0.0);
    let none = Throw {
        to,
        step: DVec3::ZERO,
        lead: 0.0,
    };
    if !body || contact <= arm {
        return none;
    }
    let dir = r / d;
    let to = to - dir * (contact - contact.min(full));
    let by = contact.min(full) - arm;
    if by <= AIM_DEPTH {
        return Throw { to, ..none };
    }
    let shift = if rear { CROSS_SHIFT } else { 0.0 };
    Throw {
        to,
        step: dir * by + lead_side(dir) * shift,
        lead: KINETIC_LEAD,
    }
}

/// A feint toward `target` by a body whose head is at `head`: the head's
/// half step (toward the lead side for the rear hand) and the direction
/// of the glove's twitch.
pub fn feint(head: DVec3, target: DVec3, rear: bool) -> (DVec3, DVec3) {
    let dir = DVec3::new(target.x - head.x, 0.0, target.z - head.z).normalize_or(DVec3::NEG_Z);
    let shift = if rear { CROSS_SHIFT } else { 0.0 };
    (dir * FEINT_STEP + lead_side(dir) * shift, dir)
}

/// The lead (left) side of a fighter facing `dir` (horizontal): up x
/// forward.
fn lead_side(dir: DVec3) -> DVec3 {
    DVec3::Y.cross(dir)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Within the arm nothing steps; from long range the body steps in
    /// and leads; beyond a step the glove stops short; a glove alone goes
    /// wherever it is sent.
    #[test]
    fn the_body_steps_behind_a_punch_beyond_the_arm() {
        let head = DVec3::new(0.0, 1.7, 1.0);
        let near = throw(head, DVec3::new(0.0, 1.7, 0.4), 0.0, false, true);
        assert_eq!((near.step, near.lead), (DVec3::ZERO, 0.0));
        let long = throw(head, DVec3::new(0.0, 1.7, 0.0), 0.0, false, true);
        assert!((long.step.z + (1.0 - 0.78)).abs() < 1e-9, "{long:?}");
        assert_eq!(long.lead, KINETIC_LEAD);
        let far = throw(head, DVec3::new(0.0, 1.7, -1.0), 0.0, false, true);
        assert!((far.to.z - (1.0 - Ranges::HUMAN.glove_reach())).abs() < 1e-9);
        let cross = throw(head, DVec3::new(0.0, 1.7, 0.0), 0.0, true, true);
        // Facing -Z, the lead (left) side is -X.
        assert!((cross.step.x + CROSS_SHIFT).abs() < 1e-9, "{cross:?}");
        let alone = throw(head, DVec3::new(0.0, 1.7, -1.0), 0.0, false, false);
        // The follow-through is not reach: aimed 0.3 m through a head in
        // reach of the arm, no step.
        let deep = throw(head, DVec3::new(0.0, 1.7, 0.0), 0.3, false, true);
        assert_eq!((deep.step, deep.lead), (DVec3::ZERO, 0.0));
        assert_eq!(alone.to.z, -1.0);
        assert_eq!(alone.lead, 0.0);
    }
}
