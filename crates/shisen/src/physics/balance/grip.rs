//! The soles' static friction (docs/model/balance.md, B1).
//!
//! Rapier solves friction at the velocity level, in a few iterations: a
//! planted foot under a working leg keeps a small residual slip that
//! nothing pulls back, so over minutes the feet creep and twist on the
//! canvas (a centimetre and a few degrees a minute), which no shoe on a
//! canvas does. A force cannot pull them back: the friction solver
//! cancels it as it cancels any other. What is missing is static
//! friction's memory of where the contact began, the anchor of the
//! bristle models (Dahl 1968; Canudas de Wit et al. 1995, IEEE Trans.
//! Autom. Control 40:419) and of game engines' friction anchors. Each
//! planted sole keeps one, set where it touched down, and the contact
//! asks the friction solver for the sliding velocity that returns the
//! sole to it within `TAU`:
//!
//! ```text
//! v*(p) = (a - r) / TAU + (psi_a - psi) / TAU  y^ x (p - r)   at each contact point p
//! ```
//!
//! `a` and `psi_a` are the anchor's place and heading, `r` and `psi` the
//! sole's. The friction solver still caps the force at mu N, so a foot
//! pushed hard enough slides; the anchor then slides with it, never more
//! than `SLIP` from the sole (the bristle's largest deflection).

use glam::{DVec3, Vec3};

use crate::physics::legs::Legs;
use crate::physics::world::{SoleSlip, World};

/// The time within which the friction returns a crept sole to its anchor,
/// s (our choice: slow beside the balance's own motion, 0.1 s, fast beside
/// the creep's millimetres a minute).
const TAU: f32 = 0.1;
/// The bristle's largest deflection, m, and its twist's, rad: a sole
/// farther from its anchor has slid (our choice: shoe soles deflect some
/// millimetres in shear before they slip).
const SLIP: f32 = 0.005;
const SLIP_TWIST: f32 = 0.05;

/// One sole's anchor: where, and at which heading, it holds.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Anchor {
    at: Vec3,
    heading: f32,
}

/// The two soles' anchors.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Grip {
    anchors: [Option<Anchor>; 2],
}

impl Grip {
    /// Hold the soles through the next step: sole `k` is anchored while
    /// `planted[k]`; a sole that lifts or swings lets go, and is anchored
    /// anew where it next stands.
    pub fn hold(&mut self, world: &mut World, legs: &Legs, planted: [bool; 2]) {
        for (k, &held) in planted.iter().enumerate() {
            let slip = if held {
                let (mid, heading) = legs.foot_ground(&world.phys, k);
                let (mid, heading) = (mid.as_vec3().with_y(0.0), heading as f32);
                let a = self.anchors[k].get_or_insert(Anchor { at: mid, heading });
                let e = (a.at - mid).clamp_length_max(SLIP);
                a.at = mid + e;
                let psi = wrap(a.heading - heading).clamp(-SLIP_TWIST, SLIP_TWIST);
                a.heading = wrap(heading + psi);
                Some(SoleSlip {
                    centre: mid,
                    velocity: e / TAU,
                    spin: psi / TAU,
                })
            } else {
                self.anchors[k] = None;
                None
            };
            world.set_sole_slip(k, slip);
        }
    }

    /// Where sole `k` is anchored, if it is.
    pub fn anchor(&self, k: usize) -> Option<DVec3> {
        self.anchors[k].map(|a| a.at.as_dvec3())
    }
}

/// An angle into [-pi, pi).
fn wrap(a: f32) -> f32 {
    use std::f32::consts::{PI, TAU};
    (a + PI).rem_euclid(TAU) - PI
}
