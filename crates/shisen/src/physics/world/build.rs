//! Building the world: the VH's segments and joints from the plan, the
//! opponent's parts.

use glam::{Quat, Vec3};
use rapier3d::prelude::*;

use super::{BodyInfo, Group32, Owner, SOLVER_ITERATIONS, SOLVER_SUBSTEPS, VH_GROUP};
use crate::physics::body::{
    BodyPlan, Group, HARD_STOP_MARGIN_DEG, JointKind, OpponentPart, Seg, Segment, Shape,
    TRUNK_HALF_HEIGHT, TRUNK_RADIUS, trunk_under,
};
use crate::physics::motor::{self, Turn};
use crate::physics::opponent::OPPONENT_MASS;
use shisen_gaze::vision::BodyId;

pub(super) fn collider_for(shape: Shape, axis_to: Vec3, at: Vec3) -> ColliderBuilder {
    let rot = Quat::from_rotation_arc(Vec3::Y, axis_to.normalize());
    let b = match shape {
        Shape::Ball { radius } => ColliderBuilder::ball(radius),
        Shape::Capsule {
            half_height,
            radius,
        } => ColliderBuilder::capsule_y(half_height, radius),
        Shape::Cuboid { half } => ColliderBuilder::cuboid(half.x, half.y, half.z),
    };
    b.position(Pose::from_parts(at, rot))
}

/// A head's surface: whatever strikes it (a glove, a padded impactor)
/// rebounds with [`HEAD_RESTITUTION`] of its closing speed.
pub(super) fn head_surface(cb: ColliderBuilder) -> ColliderBuilder {
    cb.restitution(HEAD_RESTITUTION)
        .restitution_combine_rule(CoefficientCombineRule::Max)
}

/// Restitution of a blow to the head: 0.5. Our calibration, not a
/// measured figure: with it a padded 3.7 kg impactor at 2 m/s turns the
/// head at Reynier et al. 2020's 6.5-7.3 rad/s (Ann. Biomed. Eng., doi
/// 10.1007/s10439-020-02609-7); with none (rapier's default) at 4.4 rad/s,
/// too little for the momentum it carries.
pub const HEAD_RESTITUTION: f32 = 0.5;

/// Build step 1: an empty rapier world with the solver's settings.
pub(super) fn empty_world(dt: f64) -> PhysicsWorld {
    let mut phys = PhysicsWorld::new();
    phys.integration_parameters.dt = dt as f32;
    phys.integration_parameters.num_solver_iterations = SOLVER_SUBSTEPS;
    phys.integration_parameters.num_internal_pgs_iterations = SOLVER_ITERATIONS;
    phys
}

/// Build step 2: one body and collider per VH segment, in plan order (a
/// welded segment is a collider on its parent's body).
pub(super) fn add_segments(
    phys: &mut PhysicsWorld,
    plan: &BodyPlan,
    bodies: &mut Vec<BodyInfo>,
    free_root: bool,
) {
    let vh_groups = InteractionGroups::new(VH_GROUP, Group32::ALL ^ VH_GROUP, Default::default());
    for (i, s) in plan.segments.iter().enumerate() {
        let seg = Seg::from_index(i).expect("a plan's segments are Seg::ALL, in order");
        // A welded segment is not a body of its own but a collider on
        // its parent's (as MuJoCo merges a body without joints): no
        // joint to solve, nothing to drift apart.
        let welded = match (s.joint, s.parent) {
            (JointKind::Weld, Some(p)) => Some(p),
            _ => None,
        };
        let (h, offset) = match welded {
            Some(p) => {
                let carrier = &bodies[p.index()];
                let offset = carrier.offset + s.centre - plan.segments[p.index()].centre;
                (carrier.handle, offset)
            }
            None => {
                // The root stands on a stand that slides (kinematically)
                // when the VH steps into a punch.
                let rb = if s.parent.is_none() && !free_root {
                    RigidBodyBuilder::kinematic_position_based()
                } else {
                    RigidBodyBuilder::dynamic()
                }
                .translation(s.centre)
                .can_sleep(false)
                .user_data(i as u128);
                (phys.insert_body(rb), Vec3::ZERO)
            }
        };
        let mut cb = collider_for(s.shape, s.axis_to, offset).collision_groups(vh_groups);
        if s.mass > 0.0 {
            cb = cb.mass(s.mass);
        }
        if Seg::EYES.contains(&seg) {
            // Eyes sit inside the head: they carry mass but touch nothing.
            cb = cb.collision_groups(InteractionGroups::none());
        }
        if seg == Seg::Head {
            cb = head_surface(cb);
        }
        let c = phys.insert_collider(cb.user_data(i as u128), Some(h));
        bodies.push(BodyInfo {
            name: s.name.to_string(),
            handle: h,
            collider: c,
            owner: Owner::Vh(seg),
            kinematic: false,
            offset,
        });
    }
}

/// A segment's joint as a link of the physical body's articulation, and
/// how it turns.
pub(super) type Link = (MultibodyJointHandle, Turn);

/// Build step 3: the joints between segments (ball, hinge; eyes and neck
/// with a hard stop beyond the controller's range). With a free root
/// (`linked`) the shoulders and elbows are links of the body's
/// articulation, as the legs' joints are, driven by its motors
/// (docs/model/balance.md, B1): an arm on a joint of its own to an
/// articulated trunk is solved apart from it, and under a fallen body's
/// weight it could spin up past 200 rad/s in a step. The neck and eyes
/// stay joints of their own (linked, the eyes were solved too loosely for
/// a saccade). Returns each segment's pivot in its parent's frame, and
/// each linked segment's link.
pub(super) fn join_segments(
    phys: &mut PhysicsWorld,
    plan: &BodyPlan,
    bodies: &[BodyInfo],
    linked: bool,
) -> (Vec<Vec3>, Vec<Option<Link>>) {
    let mut anchor_parent = vec![Vec3::ZERO; plan.segments.len()];
    let mut links = vec![None; plan.segments.len()];
    for (i, s) in plan.segments.iter().enumerate() {
        let Some(p) = s.parent else { continue };
        let a1 = s.pivot - plan.segments[p.index()].centre;
        let a2 = s.pivot - s.centre;
        anchor_parent[i] = a1;
        let Some(mut joint) = joint_for(s, a1, a2) else {
            continue;
        };
        let (h1, h2) = (bodies[p.index()].handle, bodies[i].handle);
        if linked && matches!(s.group, Some(Group::Shoulder | Group::Elbow)) {
            let turn = match s.joint {
                JointKind::Hinge { .. } => Turn::Hinge(joint.local_frame2.rotation),
                _ => Turn::Ball,
            };
            motor::prepare(&mut joint, turn);
            let h = phys
                .multibody_joints
                .insert(h1, h2, joint, true)
                .expect("the arms hang from the trunk as a tree");
            links[i] = Some((h, turn));
        } else {
            phys.insert_impulse_joint(h1, h2, joint);
        }
    }
    (anchor_parent, links)
}

/// The rapier joint of a segment with anchors `a1` (parent frame) and
/// `a2` (own frame); `None` for the root and welded segments.
pub(super) fn joint_for(s: &Segment, a1: Vec3, a2: Vec3) -> Option<GenericJoint> {
    Some(match s.joint {
        JointKind::Ball => {
            let mut j = SphericalJointBuilder::new()
                .local_anchor1(a1)
                .local_anchor2(a2)
                .contacts_enabled(false);
            if matches!(s.group, Some(Group::Eye | Group::Neck))
                && let Some(l) = s.limits
            {
                // rapier's per-axis limit is 2 asin(q.imag[axis]); close to
                // our angles, so a margin keeps it a pure safety stop.
                let m = HARD_STOP_MARGIN_DEG * 2.0;
                let r = |v: [f32; 2]| [(v[0] - m).to_radians(), (v[1] + m).to_radians()];
                let pitch = r(l.pitch);
                j = j
                    .limits(JointAxis::AngY, r(l.yaw))
                    .limits(JointAxis::AngX, [-pitch[1], -pitch[0]])
                    .limits(JointAxis::AngZ, r(l.roll));
            }
            j.build().into()
        }
        JointKind::Hinge { axis } => RevoluteJointBuilder::new(axis)
            .local_anchor1(a1)
            .local_anchor2(a2)
            .contacts_enabled(false)
            .build()
            .into(),
        JointKind::Weld | JointKind::Root => return None,
    })
}

/// Build step 4: each segment's subtree (the segments with a body of
/// their own that it carries, itself included).
pub(super) fn subtrees(plan: &BodyPlan) -> Vec<Vec<Seg>> {
    let mut subtree = vec![Vec::new(); plan.segments.len()];
    for seg in Seg::ALL.into_iter().take(plan.segments.len()) {
        if plan.segments[seg.index()].joint == JointKind::Weld {
            continue;
        }
        let mut j = Some(seg);
        while let Some(k) = j {
            subtree[k.index()].push(seg);
            j = plan.segments[k.index()].parent;
        }
    }
    subtree
}

/// Build step 5: the opponent's head and gloves, after the VH's
/// segments. Returns their bodies in [`OpponentPart`] order.
pub(super) fn add_opponent(
    phys: &mut PhysicsWorld,
    plan: &BodyPlan,
    bodies: &mut Vec<BodyInfo>,
) -> [BodyId; 4] {
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
    let parts = OpponentPart::ALL.map(|part| {
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
        let mut cb = ColliderBuilder::ball(radii[k]);
        if part == OpponentPart::Head {
            cb = head_surface(cb);
        }
        let c = phys.insert_collider(
            cb.mass(OPPONENT_MASS[k])
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
    });
    let [head, left, right] = parts;
    [head, left, right, add_trunk(phys, plan, bodies)]
}

/// The opponent's trunk, under its head: driven as the other parts are
/// (its target under the head's, [`trunk_under`]), upright, touching
/// only the VH (the gloves' own guard positions pass in front of it).
fn add_trunk(phys: &mut PhysicsWorld, plan: &BodyPlan, bodies: &mut Vec<BodyInfo>) -> BodyId {
    let idx = bodies.len();
    let h = phys.insert_body(
        RigidBodyBuilder::dynamic()
            .translation(trunk_under(plan.opponent_head))
            .gravity_scale(0.0)
            .lock_rotations()
            .can_sleep(false)
            .user_data(idx as u128),
    );
    let only_vh = InteractionGroups::new(Group32::GROUP_2, VH_GROUP, Default::default());
    let c = phys.insert_collider(
        ColliderBuilder::capsule_y(TRUNK_HALF_HEIGHT, TRUNK_RADIUS)
            .mass(OPPONENT_MASS[OpponentPart::Trunk.index()])
            .collision_groups(only_vh)
            .user_data(idx as u128),
        Some(h),
    );
    bodies.push(BodyInfo {
        name: OpponentPart::Trunk.name().to_string(),
        handle: h,
        collider: c,
        owner: Owner::Opponent(OpponentPart::Trunk),
        kinematic: false,
        offset: Vec3::ZERO,
    });
    BodyId::new(idx)
}
