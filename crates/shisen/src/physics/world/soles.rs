//! The soles' contacts with the canvas as the balance's grip asks for
//! them (docs/model/balance.md, B1): a planted sole's friction is given
//! a sliding velocity that brings it back to where it stood
//! ([`crate::physics::balance::grip`]).

use glam::Vec3;
use rapier3d::prelude::*;

/// What one sole's contact is asked for through the next step.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct SoleSlip {
    /// The sole's centre, on the canvas, world.
    pub centre: Vec3,
    /// The velocity the friction is to give the sole's centre, m/s.
    pub velocity: Vec3,
    /// Its turn about the vertical, rad/s.
    pub spin: f32,
}

impl SoleSlip {
    /// The velocity asked for at contact point `p`.
    fn at(&self, p: Vec3) -> Vec3 {
        (self.velocity + Vec3::Y.cross(p - self.centre) * self.spin).with_y(0.0)
    }
}

/// The physics hooks that give the soles' contacts their slip.
pub(super) struct Soles {
    /// Each foot's collider and what its contact is asked for.
    pub feet: [(ColliderHandle, Option<SoleSlip>); 2],
}

impl PhysicsHooks for Soles {
    fn modify_solver_contacts(&self, context: &mut ContactModificationContext) {
        let (c1, c2) = (context.collider1, context.collider2);
        let Some((sign, slip)) = self.feet.iter().find_map(|(c, s)| {
            let s = (*s)?;
            // The solver's tangent velocity is body 1's relative to body
            // 2's, the other way round from the surface's.
            (*c == c1)
                .then_some((-1.0, s))
                .or((*c == c2).then_some((1.0, s)))
        }) else {
            return;
        };
        if let ModifiableContacts::Rigid(m) = &mut context.contacts {
            for sc in m.solver_contacts.iter_mut() {
                let p = if sign < 0.0 { sc.anchor1 } else { sc.anchor2 };
                sc.tangent_velocity = slip.at(p) * sign;
            }
        }
    }
}
