//! One joint of an articulation (rapier's reduced-coordinate multibody,
//! as MuJoCo's bodies are) driven toward a target rotation by its motors:
//! the physical body's legs and, with them, its arms. Each motor is a
//! velocity servo, `w* = w_target + (kp / kd) e`, with damping `kd`,
//! solved implicitly against the articulation's whole inertia, so the
//! torque it gives is `kp e + kd (w_target - w)` at the end of the step,
//! stable however stiff (docs/model/balance.md, B1).

use glam::{Quat, Vec3};
use rapier3d::prelude::*;

/// How a linked joint turns: a ball joint's three axes, or a hinge about
/// its frame's X axis (the hinge's frame on the child, `frame2`, turns
/// the target's rotation vector onto it).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Turn {
    /// A ball joint (shoulder, hip, ankle, waist).
    Ball,
    /// A hinge whose frame on the child is this rotation (knee, elbow).
    Hinge(Quat),
}

/// A joint's drive for one step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Drive {
    /// Target relative rotation, parent to child (identity at rest).
    pub target: Quat,
    /// Target relative angular velocity, parent frame, rad/s.
    pub velocity: Vec3,
    /// Spring, N m/rad.
    pub kp: f32,
    /// Damper, N m s/rad.
    pub kd: f32,
    /// Largest torque, N m.
    pub max: f32,
}

/// Drive the multibody joint `joint` (whose child was built with the
/// identity rotation, as every body of ours is, so its joint rotation is
/// the child's turn from rest relative to its parent) as `d` says.
pub fn drive(phys: &mut PhysicsWorld, joint: MultibodyJointHandle, turn: Turn, d: &Drive) {
    let Some((mb, link)) = phys.multibody_joints.get_mut(joint) else {
        return;
    };
    let Some(link) = mb.link_mut(link) else {
        return;
    };
    let rate = if d.kd > 0.0 { d.kp / d.kd } else { 0.0 };
    let joint = &mut link.joint;
    match turn {
        Turn::Hinge(frame2) => {
            let axis = frame2 * Vec3::X;
            let t = d.target;
            let v = Vec3::new(t.x, t.y, t.z);
            let twist = Quat::from_xyzw(0.0, 0.0, 0.0, t.w)
                + Quat::from_vec4((axis * v.dot(axis)).extend(0.0));
            let (ax, angle) = twist.normalize().to_axis_angle();
            let angle = if ax.dot(axis) < 0.0 { -angle } else { angle };
            let angle = (angle + std::f32::consts::PI).rem_euclid(std::f32::consts::TAU)
                - std::f32::consts::PI;
            let now = joint.coords()[3];
            let w = d.velocity.dot(axis) + rate * (angle - now);
            joint.data.set_motor_velocity(JointAxis::AngX, w, d.kd);
            joint.data.set_motor_max_force(JointAxis::AngX, d.max);
        }
        Turn::Ball => {
            let mut err = d.target * joint.joint_rot().inverse();
            if err.w < 0.0 {
                err = -err;
            }
            let w = d.velocity + err.to_scaled_axis() * rate;
            for (axis, v) in BALL_AXES.into_iter().zip([w.x, w.y, w.z]) {
                joint.data.set_motor_velocity(axis, v, d.kd);
                joint.data.set_motor_max_force(axis, d.max);
            }
        }
    }
}

/// A ball joint's motorised axes.
pub const BALL_AXES: [JointAxis; 3] = [JointAxis::AngX, JointAxis::AngY, JointAxis::AngZ];

/// Make `joint`'s motors force-based velocity servos at rest (before its
/// first [`drive`]).
pub fn prepare(joint: &mut GenericJoint, turn: Turn) {
    let axes: &[JointAxis] = match turn {
        Turn::Ball => &BALL_AXES,
        Turn::Hinge(_) => &[JointAxis::AngX],
    };
    for &axis in axes {
        joint.set_motor_model(axis, MotorModel::ForceBased);
        joint.set_motor_velocity(axis, 0.0, 0.0);
    }
}
