//! The opponent avatar in the physics: its head and gloves are dynamic
//! balls driven toward their scripted (or live) targets by a bounded
//! spring-damper, so a punch that lands transfers momentum and a blocked
//! glove pushes with a finite force. Scene props that are scripted move
//! through the same [`World::drive`].

use glam::Vec3;
use rapier3d::prelude::*;

use crate::physics::body::{BodyPlan, OpponentPart};
use crate::physics::world::{BodyInfo, Owner, World};
use shisen_gaze::vision::BodyId;

/// Masses of the opponent's head and gloves (a glove carries the effective
/// mass of the arm behind it), kg, in [`OpponentPart`] order.
pub const OPPONENT_MASS: [f32; 3] = [5.0, 1.5, 1.5];
/// Drive of the opponent's parts, per kg: natural frequency 40 rad/s,
/// critically damped (k = w^2, c = 2 w). A free glove tracks a 0.2 s
/// punch closely; a blocked one pushes with at most about k x.
const DRIVE_STIFFNESS: f32 = 1600.0;
const DRIVE_DAMPING: f32 = 80.0;
/// The drive's force is capped at this acceleration of the part's mass,
/// m/s^2 (40 g; a fast punch's glove peaks near 16 g on a minimum-jerk
/// path). A scripted path that turns abruptly (a new move while the glove
/// is moving) differentiates to accelerations of 10^4 m/s^2; uncapped, that
/// feed-forward flung an opponent glove into the VH's at 40 m/s in one
/// step (the long soaks' arm blow-ups).
const DRIVE_MAX_ACCEL: f32 = 400.0;

/// World build step: the opponent's head and gloves, after the VH's
/// segments. Returns their bodies in [`OpponentPart`] order.
pub(crate) fn add_opponent(
    phys: &mut PhysicsWorld,
    plan: &BodyPlan,
    bodies: &mut Vec<BodyInfo>,
) -> [BodyId; 3] {
    let positions = [
        plan.opponent_head,
        plan.opponent_gloves[0],
        plan.opponent_gloves[1],
    ];
    let radii = [
        plan.opponent_head_radius,
        plan.glove_radius,
        plan.glove_radius,
    ];
    OpponentPart::ALL.map(|part| {
        let k = part.index();
        let idx = bodies.len();
        // Dynamic, driven by a spring-damper toward the scripted or live
        // target (see `World::drive`): finite mass and strength, so a punch
        // that lands transfers momentum, and an arm caught between a
        // glove and the torso is pushed, not crushed.
        let h = phys.insert_body(
            RigidBodyBuilder::dynamic()
                .translation(positions[k])
                .gravity_scale(0.0)
                .lock_rotations()
                .can_sleep(false)
                .user_data(idx as u128),
        );
        let c = phys.insert_collider(
            ColliderBuilder::ball(radii[k])
                .mass(OPPONENT_MASS[k])
                .collision_groups(InteractionGroups::all())
                .user_data(idx as u128),
            Some(h),
        );
        bodies.push(BodyInfo {
            name: part.name().to_string(),
            handle: h,
            collider: c,
            owner: Owner::Opponent(part),
            kinematic: false,
            offset: Vec3::ZERO,
        });
        BodyId::new(idx)
    })
}

impl World {
    /// Move a scripted body toward `position` (with the target's velocity
    /// and acceleration): kinematic props go exactly there at the end of
    /// the next step; the opponent's dynamic parts are pulled by a
    /// spring-damper with feed-forward, `F = m a + c (v - v_b) + k (p - p_b)`,
    /// whose stiffness bounds the force a blocked glove can push with.
    pub fn drive(&mut self, body: BodyId, position: Vec3, velocity: Vec3, accel: Vec3) {
        let h = self.info(body).handle;
        let dt = self.dt as f32;
        let rb = &mut self.phys.bodies[h];
        if rb.is_kinematic() {
            rb.set_next_kinematic_translation(position);
            return;
        }
        let m = rb.mass();
        let (k, c) = (DRIVE_STIFFNESS * m, DRIVE_DAMPING * m);
        let f = m * accel + c * (velocity - rb.linvel()) + k * (position - rb.translation());
        rb.apply_impulse(f.clamp_length_max(m * DRIVE_MAX_ACCEL) * dt, true);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// However abrupt the scripted path, a driven part gains at most
    /// `DRIVE_MAX_ACCEL dt` of speed in a step.
    #[test]
    fn the_drive_force_is_capped() {
        let mut w = World::new(BodyPlan::default(), 0.001);
        let g = w.part(OpponentPart::LeftGlove);
        let p = w.rb(g).translation();
        w.drive(g, p + Vec3::X * 0.05, Vec3::X * 50.0, Vec3::X * 1e5);
        w.step();
        let v = w.rb(g).linvel().length();
        assert!(v > 0.1 && v <= DRIVE_MAX_ACCEL * 0.001 * 1.001, "{v}");
    }
}
