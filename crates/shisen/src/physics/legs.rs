//! The physical lower body: pelvis, thighs, shanks and feet as dynamic
//! rigid bodies under a dynamic trunk, standing on the canvas with
//! friction (docs/model/balance.md, B1). What keeps them up is the balance
//! controller ([`crate::physics::balance`]); nothing here moves a body
//! except through forces.
//!
//! Each part is built at its rest pose (the stance of
//! [`LowerBody::new`]) with the identity rotation, as the upper body's
//! segments are, so a part's world rotation is its turn from rest. The
//! joints: the waist (pelvis to trunk) and the hips and ankles are ball
//! joints, the knees hinges about the leg's plane normal.

use glam::{DVec3, Mat3, Quat, Vec3};
use rapier3d::prelude::*;

use crate::physics::lower::{BodyParams, Leg, LowerBody, WAIST_REST, anthro};
use crate::physics::motor;

/// Segment masses as shares of body mass: de Leva (1996, J. Biomech.
/// 29:1223, table 4, males): pelvis (lower trunk) 11.17 %, thigh 14.16 %,
/// shank 4.33 %, foot 1.37 %; the trunk above the pelvis (middle and
/// upper trunk) 32.29 %.
pub mod share {
    /// Pelvis (de Leva's lower trunk).
    pub const PELVIS: f32 = 0.1117;
    /// One thigh.
    pub const THIGH: f32 = 0.1416;
    /// One shank.
    pub const SHANK: f32 = 0.0433;
    /// One foot.
    pub const FOOT: f32 = 0.0137;
    /// The trunk above the pelvis (the torso segment).
    pub const TRUNK: f32 = 0.3229;
}

/// A part of the lower body.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Part {
    /// The pelvis: the free root.
    Pelvis,
    /// Thigh `k` (0 the lead/left leg).
    Thigh(usize),
    /// Shank `k`.
    Shank(usize),
    /// Foot `k`.
    Foot(usize),
}

impl Part {
    /// Every part, in storage order.
    pub const ALL: [Part; 7] = [
        Part::Pelvis,
        Part::Thigh(0),
        Part::Thigh(1),
        Part::Shank(0),
        Part::Shank(1),
        Part::Foot(0),
        Part::Foot(1),
    ];

    /// Its place in [`Part::ALL`].
    pub const fn index(self) -> usize {
        match self {
            Part::Pelvis => 0,
            Part::Thigh(k) => 1 + k,
            Part::Shank(k) => 3 + k,
            Part::Foot(k) => 5 + k,
        }
    }

    /// Its name in traces and errors.
    pub fn name(self) -> &'static str {
        [
            "vh_pelvis",
            "vh_left_thigh",
            "vh_right_thigh",
            "vh_left_shank",
            "vh_right_shank",
            "vh_left_foot",
            "vh_right_foot",
        ][self.index()]
    }
}

/// A joint of the lower body (the waist carries the trunk).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Joint {
    /// Pelvis to trunk.
    Waist,
    /// Pelvis to thigh `k`.
    Hip(usize),
    /// Thigh to shank `k` (a hinge).
    Knee(usize),
    /// Shank to foot `k`.
    Ankle(usize),
}

impl Joint {
    /// Every joint, in storage order.
    pub const ALL: [Joint; 7] = [
        Joint::Waist,
        Joint::Hip(0),
        Joint::Hip(1),
        Joint::Knee(0),
        Joint::Knee(1),
        Joint::Ankle(0),
        Joint::Ankle(1),
    ];

    /// Its place in [`Joint::ALL`].
    pub const fn index(self) -> usize {
        match self {
            Joint::Waist => 0,
            Joint::Hip(k) => 1 + k,
            Joint::Knee(k) => 3 + k,
            Joint::Ankle(k) => 5 + k,
        }
    }

    /// The leg it belongs to, if any.
    pub fn leg(self) -> Option<usize> {
        match self {
            Joint::Waist => None,
            Joint::Hip(k) | Joint::Knee(k) | Joint::Ankle(k) => Some(k),
        }
    }

    /// The part it moves (the distal one), `None` for the waist (the trunk).
    pub fn child(self) -> Option<Part> {
        match self {
            Joint::Waist => None,
            Joint::Hip(k) => Some(Part::Thigh(k)),
            Joint::Knee(k) => Some(Part::Shank(k)),
            Joint::Ankle(k) => Some(Part::Foot(k)),
        }
    }

    /// The part it hangs from (the proximal one).
    pub fn parent(self) -> Part {
        match self {
            Joint::Waist | Joint::Hip(_) => Part::Pelvis,
            Joint::Knee(k) => Part::Thigh(k),
            Joint::Ankle(k) => Part::Shank(k),
        }
    }

    /// The lower-body parts it carries, itself's child first (the waist's
    /// are the trunk's, which the world knows).
    pub fn distal(self) -> &'static [Part] {
        match self {
            Joint::Waist => &[],
            Joint::Hip(0) => &[Part::Thigh(0), Part::Shank(0), Part::Foot(0)],
            Joint::Hip(_) => &[Part::Thigh(1), Part::Shank(1), Part::Foot(1)],
            Joint::Knee(0) => &[Part::Shank(0), Part::Foot(0)],
            Joint::Knee(_) => &[Part::Shank(1), Part::Foot(1)],
            Joint::Ankle(0) => &[Part::Foot(0)],
            Joint::Ankle(_) => &[Part::Foot(1)],
        }
    }
}

/// The foot's box: half its width, half its height (the sole to the
/// ankle's underside), m.
pub const FOOT_HALF_WIDTH: f32 = 0.045;
pub const FOOT_HALF_HEIGHT: f32 = 0.025;
/// Thigh and shank radii, m (a capsule round the bone, as drawn).
pub const THIGH_RADIUS: f32 = 0.07;
pub const SHANK_RADIUS: f32 = 0.05;
/// The pelvis box's half extents, m (hip width, depth).
pub const PELVIS_HALF: Vec3 = Vec3::new(0.15, 0.07, 0.1);
/// Friction of a shoe's sole on the canvas (rubber on canvas; boxing
/// shoes are made to grip and pivot: about 0.6-0.9, our choice 0.8).
pub const SOLE_FRICTION: f32 = 0.8;

/// The rigid bodies of the lower body and its joints, in the world.
#[derive(Clone, Debug)]
pub struct Legs {
    /// Each part's body ([`Part::index`] order).
    pub handles: [RigidBodyHandle; 7],
    /// Each part's collider.
    pub colliders: [ColliderHandle; 7],
    /// The canvas.
    pub ground: ColliderHandle,
    /// The trunk's body (the waist's child).
    pub trunk: RigidBodyHandle,
    /// Each joint's pivot in its parent's frame ([`Joint::index`] order).
    anchor_parent: [Vec3; 7],
    /// Each joint in rapier: its motors drive the relative rotation of
    /// its two frames to the identity, and [`Legs::drive`] turns the
    /// parent's frame to the target each tick.
    pub joints: [MultibodyJointHandle; 7],
    /// Each joint's frame on its child at build (its frame on the parent
    /// is this turned by the target).
    frame2: [Quat; 7],
    /// The joints' pivots at rest, world.
    pub rest_pivots: [Vec3; 7],
    /// The legs at rest (joint centres), left then right.
    pub rest: [Leg; 2],
    /// Each part's inertia tensor about its centre of mass, own frame.
    local_inertia: [Mat3; 7],
    /// Each part's mass, kg.
    pub mass: [f32; 7],
    /// Each part's rest-pose frame ([`frame`] of its bone), for turning
    /// a posed leg into rotations.
    rest_frames: [Mat3; 7],
    /// The articulation's joints as built (at rest), in its links' order.
    rest_joints: Vec<MultibodyJoint>,
}

/// An orthonormal frame from a bone's axis and a side direction: columns
/// (side, axis, side x axis).
pub fn frame(axis: Vec3, side: Vec3) -> Mat3 {
    let u = axis.normalize_or(Vec3::Y);
    let s = (side - u * side.dot(u)).normalize_or(u.any_orthonormal_vector());
    Mat3::from_cols(s, u, s.cross(u))
}

/// The frames of a posed leg's thigh, shank and foot: each bone along its
/// length, turned about it by the leg's plane (hip, knee, ankle); the foot
/// heel to toe, turned about it by the sole's up.
pub fn leg_frames(leg: &Leg) -> [Mat3; 3] {
    let (hip, knee, ankle) = (leg.hip.as_vec3(), leg.knee.as_vec3(), leg.ankle.as_vec3());
    let (heel, toe) = (leg.heel.as_vec3(), leg.toe.as_vec3());
    let along = (toe - heel).normalize_or(Vec3::Z);
    // The leg's plane normal (the knee's axis); a straight leg takes the
    // foot's side.
    let n = (knee - hip)
        .cross(ankle - knee)
        .try_normalize()
        .unwrap_or_else(|| Vec3::Y.cross(along).normalize_or(Vec3::X));
    let up = (ankle - heel) - along * (ankle - heel).dot(along);
    [
        frame(knee - hip, n),
        frame(ankle - knee, n),
        frame(along, up.cross(along)),
    ]
}

impl Legs {
    /// Build the lower body at rest under the trunk `trunk` (whose centre
    /// is at `trunk_centre` at rest), for a body of [`anthro::MASS`], with
    /// the canvas; the VH's parts collide with no VH part (`groups`).
    pub fn build(
        phys: &mut PhysicsWorld,
        p: &BodyParams,
        trunk: RigidBodyHandle,
        trunk_centre: Vec3,
        groups: InteractionGroups,
        user_data: u128,
    ) -> Legs {
        let m = anthro::MASS as f32;
        let rest = LowerBody::new(p).legs(p);
        let waist = WAIST_REST.as_vec3();
        let pelvis_centre = waist - Vec3::Y * anthro::HIP_BELOW_WAIST as f32;
        let mut handles = Vec::with_capacity(7);
        let mut colliders = Vec::with_capacity(7);
        let mut mass = [0.0; 7];
        let mut centres = [Vec3::ZERO; 7];
        for part in Part::ALL {
            let (centre, shape, rot, share) = match part {
                Part::Pelvis => (
                    pelvis_centre,
                    SharedShape::cuboid(PELVIS_HALF.x, PELVIS_HALF.y, PELVIS_HALF.z),
                    Quat::from_rotation_y(p.hip_turn_deg.to_radians() as f32),
                    share::PELVIS,
                ),
                Part::Thigh(k) => bone(rest[k].hip, rest[k].knee, THIGH_RADIUS, share::THIGH),
                Part::Shank(k) => bone(rest[k].knee, rest[k].ankle, SHANK_RADIUS, share::SHANK),
                Part::Foot(k) => {
                    let (heel, toe) = (rest[k].heel.as_vec3(), rest[k].toe.as_vec3());
                    let along = (toe - heel).normalize();
                    let length = anthro::FOOT_LENGTH as f32;
                    let centre = heel + along * length / 2.0 + Vec3::Y * FOOT_HALF_HEIGHT;
                    (
                        centre,
                        SharedShape::cuboid(FOOT_HALF_WIDTH, FOOT_HALF_HEIGHT, length / 2.0),
                        Quat::from_rotation_arc(Vec3::Z, along),
                        share::FOOT,
                    )
                }
            };
            let h = phys.insert_body(
                RigidBodyBuilder::dynamic()
                    .translation(centre)
                    .can_sleep(false),
            );
            let mut cb = ColliderBuilder::new(shape)
                .position(Pose::from_parts(Vec3::ZERO, rot))
                .mass(m * share)
                .collision_groups(groups)
                .user_data(user_data);
            if matches!(part, Part::Foot(_)) {
                cb = cb
                    .friction(SOLE_FRICTION)
                    .friction_combine_rule(CoefficientCombineRule::Max)
                    // The grip's anchors (B1, balance::grip).
                    .active_hooks(ActiveHooks::MODIFY_SOLVER_CONTACTS);
            }
            colliders.push(phys.insert_collider(cb, Some(h)));
            handles.push(h);
            mass[part.index()] = m * share;
            centres[part.index()] = centre;
        }
        let handles: [RigidBodyHandle; 7] = handles.try_into().expect("seven parts");
        let colliders: [ColliderHandle; 7] = colliders.try_into().expect("seven parts");
        let local_inertia = handles.map(|h| {
            phys.bodies[h]
                .mass_properties()
                .local_mprops
                .reconstruct_inertia_matrix()
        });
        // The joints.
        let rest_pivots = Joint::ALL.map(|j| match j {
            Joint::Waist => waist,
            Joint::Hip(k) => rest[k].hip.as_vec3(),
            Joint::Knee(k) => rest[k].knee.as_vec3(),
            Joint::Ankle(k) => rest[k].ankle.as_vec3(),
        });
        let mut anchor_parent = [Vec3::ZERO; 7];
        let mut joints = Vec::with_capacity(7);
        let mut frame2 = [Quat::IDENTITY; 7];
        for j in Joint::ALL {
            let pivot = rest_pivots[j.index()];
            let parent = j.parent();
            let (child_h, child_c) = match j.child() {
                Some(c) => (handles[c.index()], centres[c.index()]),
                None => (trunk, trunk_centre),
            };
            let a1 = pivot - centres[parent.index()];
            let a2 = pivot - child_c;
            anchor_parent[j.index()] = a1;
            let mut joint: GenericJoint = match j {
                Joint::Knee(k) => {
                    let [thigh, _, _] = leg_frames(&rest[k]);
                    RevoluteJointBuilder::new(thigh.x_axis)
                        .local_anchor1(a1)
                        .local_anchor2(a2)
                        .contacts_enabled(false)
                        .build()
                        .into()
                }
                _ => SphericalJointBuilder::new()
                    .local_anchor1(a1)
                    .local_anchor2(a2)
                    .contacts_enabled(false)
                    .build()
                    .into(),
            };
            frame2[j.index()] = joint.local_frame2.rotation;
            motor::prepare(&mut joint, turn(j, &frame2));
            let h = phys
                .multibody_joints
                .insert(handles[parent.index()], child_h, joint, true)
                .expect("the lower body is a tree");
            joints.push(h);
        }
        let joints: [MultibodyJointHandle; 7] = joints.try_into().expect("seven joints");
        let rest_joints = phys
            .multibody_joints
            .get(joints[0])
            .map(|(mb, _)| mb.links().map(|l| l.joint).collect())
            .unwrap_or_default();
        // The canvas: a slab whose top is the ground (y = 0), wider than
        // any ring.
        let ground = phys.insert_collider(
            ColliderBuilder::cuboid(20.0, 0.5, 20.0)
                .translation(Vec3::new(0.0, -0.5, 0.0))
                .friction(SOLE_FRICTION)
                .user_data(u128::MAX),
            None,
        );
        let rest_frames = {
            let mut f = [Mat3::IDENTITY; 7];
            for k in 0..2 {
                let [t, s, ft] = leg_frames(&rest[k]);
                f[Part::Thigh(k).index()] = t;
                f[Part::Shank(k).index()] = s;
                f[Part::Foot(k).index()] = ft;
            }
            f
        };
        Legs {
            handles,
            colliders,
            ground,
            trunk,
            anchor_parent,
            joints,
            frame2,
            rest_pivots,
            rest,
            local_inertia,
            mass,
            rest_frames,
            rest_joints,
        }
    }

    /// Drive joint `j` toward the relative rotation `target` (parent to
    /// child, identity at rest) with a spring `kp` (N m/rad) and damper
    /// `kd` (N m s/rad), its torque at most `max` (N m). The lower body is
    /// one articulation (reduced coordinates, as MuJoCo's), and each
    /// joint's motor is a velocity servo, `w* = (kp / kd) e`, solved
    /// implicitly against the articulation's whole inertia: the torque it
    /// gives is `kp e - kd w` at the end of the step, stable however stiff.
    /// A knee takes only the part of `target` about its hinge.
    pub fn drive(
        &self,
        phys: &mut PhysicsWorld,
        j: Joint,
        target: Quat,
        kp: f32,
        kd: f32,
        max: f32,
    ) {
        let d = motor::Drive {
            target,
            velocity: Vec3::ZERO,
            kp,
            kd,
            max,
        };
        motor::drive(phys, self.joints[j.index()], turn(j, &self.frame2), &d);
    }

    /// A part's rigid body.
    pub fn rb<'a>(&self, phys: &'a PhysicsWorld, part: Part) -> &'a RigidBody {
        &phys.bodies[self.handles[part.index()]]
    }

    /// A joint's pivot, world (as its parent carries it).
    pub fn pivot(&self, phys: &PhysicsWorld, j: Joint) -> Vec3 {
        self.rb(phys, j.parent())
            .position()
            .transform_point(self.anchor_parent[j.index()])
    }

    /// The world rotations that pose a leg's thigh, shank and foot as
    /// `leg` does (rest: identity).
    pub fn leg_rotations(&self, k: usize, leg: &Leg) -> [Quat; 3] {
        let now = leg_frames(leg);
        let rest =
            [Part::Thigh(k), Part::Shank(k), Part::Foot(k)].map(|p| self.rest_frames[p.index()]);
        [0, 1, 2].map(|i| Quat::from_mat3(&(now[i] * rest[i].transpose())).normalize())
    }

    /// Inertia tensor of `parts` about `point`, world frame.
    pub fn inertia_about(&self, phys: &PhysicsWorld, parts: &[Part], point: Vec3) -> Mat3 {
        let mut total = Mat3::ZERO;
        for &part in parts {
            let rb = self.rb(phys, part);
            let r = Mat3::from_quat(*rb.rotation());
            let d = rb.center_of_mass() - point;
            let parallel = rb.mass()
                * (Mat3::from_diagonal(Vec3::splat(d.length_squared()))
                    - Mat3::from_cols(d * d.x, d * d.y, d * d.z));
            total += r * self.local_inertia[part.index()] * r.transpose() + parallel;
        }
        total
    }

    /// Mass-weighted sum of the parts' centres of mass and their total
    /// mass.
    pub fn mass_moment(&self, phys: &PhysicsWorld) -> (Vec3, Vec3, f32) {
        let mut sum = (Vec3::ZERO, Vec3::ZERO, 0.0);
        for part in Part::ALL {
            let rb = self.rb(phys, part);
            sum.0 += rb.center_of_mass() * rb.mass();
            sum.1 += rb.linvel() * rb.mass();
            sum.2 += rb.mass();
        }
        sum
    }

    /// The legs' joint centres as the bodies carry them now, left then
    /// right (for drawing and traces).
    pub fn posed(&self, phys: &PhysicsWorld) -> [Leg; 2] {
        [0, 1].map(|k| {
            let foot = self.rb(phys, Part::Foot(k)).position();
            let rest_foot = self.rest_foot_centre(k);
            let on_foot = |p: DVec3| foot.transform_point(p.as_vec3() - rest_foot).as_dvec3();
            Leg {
                hip: self.pivot(phys, Joint::Hip(k)).as_dvec3(),
                knee: self.pivot(phys, Joint::Knee(k)).as_dvec3(),
                ankle: self.pivot(phys, Joint::Ankle(k)).as_dvec3(),
                toe: on_foot(self.rest[k].toe),
                heel: on_foot(self.rest[k].heel),
            }
        })
    }

    /// Foot `k`'s centre at rest, world.
    fn rest_foot_centre(&self, k: usize) -> Vec3 {
        let (heel, toe) = (self.rest[k].heel.as_vec3(), self.rest[k].toe.as_vec3());
        let along = (toe - heel).normalize();
        heel + along * anthro::FOOT_LENGTH as f32 / 2.0 + Vec3::Y * FOOT_HALF_HEIGHT
    }

    /// Foot `k`'s heel-to-toe midpoint on its sole and its heading (yaw
    /// about +Y), as the body carries it now.
    pub fn foot_ground(&self, phys: &PhysicsWorld, k: usize) -> (DVec3, f64) {
        let rb = self.rb(phys, Part::Foot(k));
        let mid = rb.position().transform_point(-Vec3::Y * FOOT_HALF_HEIGHT);
        let rest_along = (self.rest[k].toe - self.rest[k].heel).as_vec3().normalize();
        let along = *rb.rotation() * rest_along;
        (mid.as_dvec3(), f64::from(along.x.atan2(along.z)))
    }

    /// Whether part `part` touches the canvas now.
    pub fn on_canvas(&self, phys: &PhysicsWorld, part: Part) -> bool {
        phys.contact_pair(self.colliders[part.index()], self.ground)
            .is_some_and(|p| p.has_any_active_contact())
    }

    /// Put every part back at rest, at rest.
    pub fn reset(&self, phys: &mut PhysicsWorld) {
        let pelvis = WAIST_REST.as_vec3() - Vec3::Y * anthro::HIP_BELOW_WAIST as f32;
        for (i, h) in self.handles.iter().enumerate() {
            let centre = match Part::ALL[i] {
                Part::Pelvis => pelvis,
                Part::Thigh(k) => mid(self.rest[k].hip, self.rest[k].knee),
                Part::Shank(k) => mid(self.rest[k].knee, self.rest[k].ankle),
                Part::Foot(k) => self.rest_foot_centre(k),
            };
            let rb = &mut phys.bodies[*h];
            rb.set_enabled(true);
            rb.set_position(Pose::from_parts(centre, Quat::IDENTITY), true);
            rb.set_linvel(Vec3::ZERO, true);
            rb.set_angvel(Vec3::ZERO, true);
            rb.reset_forces(true);
            rb.reset_torques(true);
        }
        // The articulation's own state is its joints' coordinates and
        // velocities, from which rapier poses the links on every step: the
        // bodies set alone came back on the next step where they had been,
        // still spinning (resets that blew up again tick after tick).
        let root_rest = Pose::from_parts(pelvis, Quat::IDENTITY);
        let Some((mb, _)) = phys.multibody_joints.get_mut(self.joints[0]) else {
            return;
        };
        for (l, rest) in mb.links_mut().zip(&self.rest_joints) {
            if l.is_root() {
                // The free root: displaced from where it is to rest.
                let j = &mut l.joint;
                let want = j.data.local_frame1.inverse() * root_rest * j.data.local_frame2;
                let c = j.coords();
                let turn = (want.rotation * j.joint_rot().inverse()).to_scaled_axis();
                let d = want.translation - Vec3::new(c[0], c[1], c[2]);
                j.apply_displacement(&[d.x, d.y, d.z, turn.x, turn.y, turn.z]);
            } else {
                l.joint = *rest;
            }
        }
        mb.generalized_velocity_mut().fill(0.0);
        mb.forward_kinematics(&phys.bodies, false);
        mb.update_rigid_bodies(&mut phys.bodies, true);
    }
}

/// How joint `j` turns: a knee is a hinge (its frame on the child in
/// `frame2`, [`Joint::index`] order), the others ball joints.
fn turn(j: Joint, frame2: &[Quat; 7]) -> motor::Turn {
    match j {
        Joint::Knee(_) => motor::Turn::Hinge(frame2[j.index()]),
        _ => motor::Turn::Ball,
    }
}

fn mid(a: DVec3, b: DVec3) -> Vec3 {
    ((a + b) / 2.0).as_vec3()
}

/// A bone's body from joint `a` to joint `b`: its centre, its capsule
/// along it, and its share of the body mass.
fn bone(a: DVec3, b: DVec3, radius: f32, share: f32) -> (Vec3, SharedShape, Quat, f32) {
    let (a, b) = (a.as_vec3(), b.as_vec3());
    let half = ((b - a).length() / 2.0 - radius).max(0.01);
    (
        (a + b) / 2.0,
        SharedShape::capsule_y(half, radius),
        Quat::from_rotation_arc(Vec3::Y, (b - a).normalize()),
        share,
    )
}
