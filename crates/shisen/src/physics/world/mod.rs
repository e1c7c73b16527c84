//! The physics world: rapier bodies and joints built from a [`BodyPlan`],
//! joint read-out in yaw/pitch/roll, and application of the PD torques.
//!
//! The world owns no behaviour; each tick the simulation hands it one
//! [`JointTarget`] per controlled segment and the kinematic poses of the
//! opponent and props, then calls [`World::step`]. Bodies are named by
//! typed handles: [`BodyId`] for any body, [`Seg`] for the VH's segments
//! (the first bodies, in plan order), [`OpponentPart`] for the opponent's.

use glam::{DQuat, DVec3, Mat3, Quat, Vec3};
use rapier3d::prelude::*;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::physics::body::{BodyPlan, Group, JointKind, OpponentPart, Seg, Shape};
use crate::physics::control::{
    Gains, JointState, JointTarget, end_range_torque, feedforward, pd_torque,
};
mod build;
mod soles;
pub use soles::SoleSlip;

pub use build::HEAD_RESTITUTION;

use crate::physics::legs::{Legs, Part, share};
use crate::physics::lower::{BodyParams, Pelvis};
use crate::physics::motor;
use crate::physics::neck::{NeckParams, NeckState, neck_torque};
use crate::physics::opponent::{DriveState, drive_impulse};
use build::{add_opponent, add_segments, collider_for, empty_world, join_segments, subtrees};
use shisen_gaze::util::math::JointAngles;
use shisen_gaze::vision::{BodyId, Motion, Scenery};

/// Who a body belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Owner {
    /// A segment of the virtual human.
    Vh(Seg),
    /// The opponent avatar (head, left glove, right glove).
    Opponent(OpponentPart),
    /// A scene prop.
    Prop,
}

/// A named body in the world, as vision and the trace know it.
#[derive(Clone, Debug)]
pub struct BodyInfo {
    /// Unique name ("head", "left_glove", "vh_head", "ball", ...).
    pub name: String,
    /// rapier handle.
    pub handle: RigidBodyHandle,
    /// Its collider.
    pub collider: ColliderHandle,
    /// Owner.
    pub owner: Owner,
    /// Moved exactly by script (kinematic) rather than by forces.
    pub kinematic: bool,
    /// Where the part sits in its rigid body's frame: zero for a body of
    /// its own; a welded segment (a glove) is a collider on its parent's
    /// body, here.
    pub offset: Vec3,
}

/// A part of the VH that a push (the scene's `Push` event) acts on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
pub enum PushPart {
    /// The trunk, at its centre of mass.
    Trunk,
    /// The pelvis.
    Pelvis,
    /// The head.
    Head,
}

/// A scene prop to add to the world.
#[derive(Clone, Debug)]
pub struct PropSpec {
    /// Unique name.
    pub name: String,
    /// Collision shape.
    pub shape: Shape,
    /// Initial position, world.
    pub position: Vec3,
    /// Initial linear velocity (dynamic props).
    pub velocity: Vec3,
    /// Initial angular velocity (dynamic props).
    pub angvel: Vec3,
    /// Mass, kg.
    pub mass: f32,
    /// Moved by the script instead of by forces.
    pub kinematic: bool,
    /// Whether gravity acts on it (dynamic props).
    pub gravity: bool,
}

/// Solver substeps per step (rapier's `num_solver_iterations`; its
/// default is 4). At the 1 kHz step one substep is enough, as for MuJoCo,
/// which takes one solver step per 1 ms step: every fidelity row stays
/// where four substeps put it, at half the cost (docs/performance.md).
pub const SOLVER_SUBSTEPS: usize = 1;
/// Velocity iterations within the substep (rapier's
/// `num_internal_pgs_iterations`; default 1). Two keep the joints as
/// tight under blows as four substeps did: the widest gap in a 10-minute
/// soak (seed 11) 1.3 mm, as with four substeps (three iterations:
/// 0.6 mm for 5 % more cost; one substep of one iteration: 5.6 mm).
pub const SOLVER_ITERATIONS: usize = 2;

/// Velocity iterations with a physical pelvis (the balanced body's feet
/// on the canvas need them; see [`World::with_body`]).
pub const BALANCED_ITERATIONS: usize = 8;

/// The largest torque of a linked joint's motors, N m: no cap of its own
/// (the arms' PD torques are not capped either); a bound on a runaway.
const LINK_MAX_TORQUE: f32 = 1.0e4;

/// Collision group of the VH (it does not collide with itself).
const VH_GROUP: Group32 = Group32::GROUP_1;
type Group32 = rapier3d::geometry::Group;

/// The physics world and its bookkeeping.
pub struct World {
    /// rapier state (public for queries; mutate through [`World`] methods).
    pub phys: PhysicsWorld,
    /// The static description it was built from.
    pub plan: BodyPlan,
    /// Fixed step, seconds.
    pub dt: f64,
    /// Every named body, indexed by [`BodyId`]; VH segments first, in plan
    /// order, then the opponent's parts, then props.
    pub bodies: Vec<BodyInfo>,
    /// The body of each opponent part ([`OpponentPart::EVERY`] order).
    opponent: [BodyId; 4],
    /// Each segment's joint as a link of the physical body's articulation
    /// (a free root's shoulders and elbows), driven by its motors;
    /// `None`: a joint of its own, driven by torques.
    links: Vec<Option<build::Link>>,
    /// Pivot of each segment in its parent's local frame.
    anchor_parent: Vec<Vec3>,
    /// Segments of each segment's subtree (itself included), with a body
    /// of their own (welded segments' mass is in their carrier's).
    subtree: Vec<Vec<Seg>>,
    /// Each segment's inertia tensor about its centre of mass, in its own
    /// frame (constant; rebuilding it from rapier's principal form every
    /// tick cost 4 % of a step).
    local_inertia: Vec<Mat3>,
    /// Where each driven body was last asked to be ([`World::drive`]).
    driven: Vec<(BodyId, Vec3)>,
    /// The root's offsets from rest: two steps ago, last step, next step
    /// (its planned acceleration, for the joints' feed-forward).
    root_path: [Vec3; 3],
    /// The physical lower body, when the pelvis is free
    /// ([`Pelvis::Balanced`]): the trunk is then a dynamic body on it.
    pub legs: Option<Legs>,
    /// The physical soles' contacts, as the balance's grip asks for them.
    soles: Option<soles::Soles>,
}

impl World {
    /// Build the world at rest from a plan, stepping at `dt` seconds: the
    /// solver, the VH's segments, their joints, the constant inertias and
    /// subtrees, the opponent's parts.
    pub fn new(plan: BodyPlan, dt: f64) -> Self {
        Self::with_body(plan, dt, None)
    }

    /// Build the world at rest as [`World::new`] does, with the lower
    /// body `body` describes: for a standing VH whose pelvis is
    /// [`Pelvis::Balanced`], the trunk becomes a dynamic body of its
    /// share of the mass, carried by a physical pelvis and legs on the
    /// canvas ([`Legs`]).
    pub fn with_body(mut plan: BodyPlan, dt: f64, body: Option<&BodyParams>) -> Self {
        let free = body.is_some_and(|b| b.human && b.pelvis == Pelvis::Balanced);
        if free {
            plan.segments[Seg::Torso.index()].mass =
                share::TRUNK * crate::physics::lower::anthro::MASS as f32;
        }
        assert_eq!(
            plan.segments.len(),
            Seg::ALL.len(),
            "a body plan has one segment per Seg, in order"
        );
        let mut phys = empty_world(dt);
        let mut bodies = Vec::new();
        if free {
            // Feet on the canvas under a body's weight creep and twist with
            // two velocity iterations (1-2 cm and 0.01 rad a second), with
            // four by 3 mm a second; eight hold them to about a centimetre
            // a minute (docs/model/balance.md).
            phys.integration_parameters.num_internal_pgs_iterations = BALANCED_ITERATIONS;
        }
        add_segments(&mut phys, &plan, &mut bodies, free);
        let (anchor_parent, links) = join_segments(&mut phys, &plan, &bodies, free);
        let legs = body.filter(|_| free).map(|b| {
            let torso = &plan.segments[Seg::Torso.index()];
            let groups =
                InteractionGroups::new(VH_GROUP, Group32::ALL ^ VH_GROUP, Default::default());
            Legs::build(
                &mut phys,
                b,
                bodies[Seg::Torso.index()].handle,
                torso.centre,
                groups,
                Seg::Torso.index() as u128,
            )
        });
        let local_inertia = bodies
            .iter()
            .map(|b| {
                phys.bodies[b.handle]
                    .mass_properties()
                    .local_mprops
                    .reconstruct_inertia_matrix()
            })
            .collect();
        let subtree = subtrees(&plan);
        let opponent = add_opponent(&mut phys, &plan, &mut bodies);
        World {
            phys,
            plan,
            dt,
            bodies,
            opponent,
            links,
            anchor_parent,
            subtree,
            local_inertia,
            driven: Vec::new(),
            root_path: [Vec3::ZERO; 3],
            soles: legs.as_ref().map(|l| soles::Soles {
                feet: [0, 1].map(|k| (l.colliders[Part::Foot(k).index()], None)),
            }),
            legs,
        }
    }

    /// The VH's segments that are bodies of their own (not welded).
    pub fn vh_bodies(&self) -> impl Iterator<Item = Seg> + '_ {
        Seg::ALL
            .into_iter()
            .zip(&self.plan.segments)
            .filter(|(_, s)| s.joint != JointKind::Weld)
            .map(|(seg, _)| seg)
    }

    /// Add a prop; returns its body.
    pub fn add_prop(&mut self, p: &PropSpec) -> BodyId {
        let idx = self.bodies.len();
        let rb = if p.kinematic {
            RigidBodyBuilder::kinematic_position_based()
        } else {
            RigidBodyBuilder::dynamic()
                .linvel(p.velocity)
                .angvel(p.angvel)
                .gravity_scale(if p.gravity { 1.0 } else { 0.0 })
                .can_sleep(false)
        }
        .translation(p.position)
        .user_data(idx as u128);
        let h = self.phys.insert_body(rb);
        let c = self.phys.insert_collider(
            collider_for(p.shape, Vec3::Y, Vec3::ZERO)
                .mass(p.mass)
                .user_data(idx as u128),
            Some(h),
        );
        self.bodies.push(BodyInfo {
            name: p.name.clone(),
            handle: h,
            collider: c,
            owner: Owner::Prop,
            kinematic: p.kinematic,
            offset: Vec3::ZERO,
        });
        BodyId::new(idx)
    }

    /// Every body, in order.
    pub fn body_ids(&self) -> impl Iterator<Item = BodyId> + use<> {
        BodyId::all(self.bodies.len())
    }

    /// A body's name, owner and handles.
    pub fn info(&self, body: impl Into<BodyId>) -> &BodyInfo {
        &self.bodies[body.into().index()]
    }

    /// Find a body by name.
    pub fn body_named(&self, name: &str) -> Option<BodyId> {
        self.bodies
            .iter()
            .position(|b| b.name == name)
            .map(BodyId::new)
    }

    /// The body of an opponent part.
    pub fn part(&self, p: OpponentPart) -> BodyId {
        self.opponent[p.index()]
    }

    /// The opponent's bodies: head, left glove, right glove.
    pub fn parts(&self) -> [BodyId; 3] {
        OpponentPart::ALL.map(|p| self.part(p))
    }

    /// The rapier body carrying a body (for a welded segment, its
    /// parent's: use [`World::position`] and [`World::velocity`] for the
    /// part itself).
    pub fn rb(&self, body: impl Into<BodyId>) -> &RigidBody {
        &self.phys.bodies[self.info(body).handle]
    }

    /// World pose of a body: (translation, rotation).
    pub fn pose(&self, body: impl Into<BodyId>) -> (Vec3, Quat) {
        let body = body.into();
        let rb = self.rb(body);
        (
            rb.position().transform_point(self.info(body).offset),
            *rb.rotation(),
        )
    }

    /// World position of a body.
    pub fn position(&self, body: impl Into<BodyId>) -> Vec3 {
        self.pose(body).0
    }

    /// World velocity of a body (of its point, for a welded part).
    pub fn velocity(&self, body: impl Into<BodyId>) -> Vec3 {
        let body = body.into();
        self.rb(body).velocity_at_point(self.position(body))
    }

    /// The parent of a jointed segment.
    fn parent(&self, s: Seg) -> Seg {
        self.plan.segments[s.index()]
            .parent
            .expect("joint has a parent")
    }

    /// Rotation of a segment relative to its parent (identity at rest).
    pub fn joint_rotation(&self, s: Seg) -> Quat {
        self.rb(self.parent(s)).rotation().inverse() * *self.rb(s).rotation()
    }

    /// Angles of a segment's joint.
    pub fn joint_angles(&self, s: Seg) -> JointAngles {
        JointAngles::from_quat(self.joint_rotation(s))
    }

    /// Child-minus-parent angular velocity in the parent's frame.
    pub fn joint_angvel(&self, s: Seg) -> Vec3 {
        let pr = self.rb(self.parent(s));
        pr.rotation().inverse() * (self.rb(s).angvel() - pr.angvel())
    }

    /// World position of a segment's pivot.
    pub fn pivot(&self, s: Seg) -> Vec3 {
        self.rb(self.parent(s))
            .position()
            .transform_point(self.anchor_parent[s.index()])
    }

    /// How far apart the two halves of the widest-open joint are, m: the
    /// pivot as the parent carries it against the pivot as the child
    /// carries it. A rigid joint keeps this near zero; the solver lets it
    /// open under large impulses and closes it again.
    pub fn joint_gap(&self) -> f32 {
        Seg::ALL
            .into_iter()
            .zip(&self.plan.segments)
            .filter(|(_, s)| s.parent.is_some() && s.joint != JointKind::Weld)
            .map(|(seg, s)| {
                let child = self.rb(seg).position().transform_point(s.pivot - s.centre);
                (child - self.pivot(seg)).length()
            })
            .fold(0.0, f32::max)
    }

    /// Inertia tensor of segment `s`'s subtree about `point`, world frame.
    pub fn subtree_inertia(&self, s: Seg, point: Vec3) -> Mat3 {
        let mut total = Mat3::ZERO;
        for &b in &self.subtree[s.index()] {
            let rb = self.rb(b);
            let r = Mat3::from_quat(*rb.rotation());
            let i_local = self.local_inertia[b.index()];
            let d = rb.center_of_mass() - point;
            let m = rb.mass();
            let parallel = m
                * (Mat3::from_diagonal(Vec3::splat(d.length_squared()))
                    - Mat3::from_cols(d * d.x, d * d.y, d * d.z));
            total += r * i_local * r.transpose() + parallel;
        }
        total
    }

    /// Torque that holds segment `s`'s subtree against gravity about its
    /// pivot while the root moves with acceleration `root_accel`: the
    /// subtree is held against the effective gravity `g - a` of the
    /// accelerating trunk (the root's own movement, planned, is known to
    /// the controller as a person's own movement is: its postural
    /// adjustment is feed-forward, not a reflex to the head lagging).
    pub fn gravity_torque(&self, s: Seg, root_accel: Vec3) -> Vec3 {
        self.gravity_torque_about(s, self.pivot(s), root_accel)
    }

    /// [`World::gravity_torque`] about any point (the trunk's, about the
    /// waist of a physical pelvis).
    pub fn gravity_torque_about(&self, s: Seg, pivot: Vec3, root_accel: Vec3) -> Vec3 {
        let g = self.phys.gravity - root_accel;
        let mut tau = Vec3::ZERO;
        for &b in &self.subtree[s.index()] {
            let rb = self.rb(b);
            tau -= (rb.center_of_mass() - pivot).cross(g * rb.mass());
        }
        tau
    }

    /// The root's planned acceleration over the next step (from the
    /// offsets given to [`World::set_root_offset`]), m/s^2.
    pub fn root_accel(&self) -> Vec3 {
        let dt = self.dt as f32;
        let [a, b, c] = self.root_path;
        (c - 2.0 * b + a) / (dt * dt)
    }

    /// The measured state of segment `s`'s joint (it must have a parent).
    pub fn joint_state(&self, s: Seg) -> JointState {
        let p = self.parent(s);
        JointState {
            parent_rot: *self.rb(p).rotation(),
            child_rot: *self.rb(s).rotation(),
            rel_angvel: self.rb(s).angvel() - self.rb(p).angvel(),
            inertia: self.subtree_inertia(s, self.pivot(s)),
        }
    }

    /// Apply one tick of joint torques (as impulses over `dt`) to every
    /// controlled joint: the PD law, the neck's through its muscles'
    /// present bounds ([`neck_torque`]). `targets` is indexed by segment
    /// ([`Seg::index`]).
    pub fn apply_control(
        &mut self,
        gains: &Gains,
        targets: &[JointTarget],
        neck: (&NeckParams, &NeckState),
    ) {
        let dt = self.dt as f32;
        let root_accel = self.root_accel();
        let mut impulses = Vec::with_capacity(self.plan.segments.len());
        for (s, segm) in Seg::ALL.into_iter().zip(&self.plan.segments) {
            let (Some(p), Some(group)) = (segm.parent, segm.group) else {
                continue;
            };
            let state = self.joint_state(s);
            let target = &targets[s.index()];
            let g = gains.group(group);
            let link = self.links[s.index()];
            let mut tau = match (group, link) {
                // A link's spring and damper are its motors'; the
                // feed-forward is a torque.
                (_, Some((joint, turn))) => {
                    let d = motor::Drive {
                        target: target.rotation,
                        velocity: target.velocity,
                        kp: g.kp as f32,
                        kd: g.kd as f32,
                        max: LINK_MAX_TORQUE,
                    };
                    motor::drive(&mut self.phys, joint, turn, &d);
                    feedforward(g, target, &state)
                }
                (Group::Neck, None) => neck_torque(g, neck.0, neck.1, target, &state, dt),
                (_, None) => pd_torque(g, target, &state, dt),
            };
            // The eyes' and the neck's soft limits (their targets stay
            // inside; blows can carry them past).
            if let (Group::Eye | Group::Neck, Some(limits)) = (group, &segm.limits) {
                tau += end_range_torque(g, limits, &state, dt);
            }
            if gains.gravity_compensation {
                tau += self.gravity_torque(s, root_accel);
            }
            impulses.push((p, s, tau * dt));
        }
        for (p, s, imp) in impulses {
            let hs = self.info(s).handle;
            self.torque_impulse(hs, imp);
            let hp = self.info(p).handle;
            if self.phys.bodies[hp].is_dynamic() {
                self.torque_impulse(hp, -imp);
            }
        }
    }

    /// Give body `h` a torque impulse over the next step. A link of an
    /// articulation (the physical lower body and the trunk it carries)
    /// moves by its joints' coordinates, so it takes the impulse as a
    /// torque held through the step (cleared after it, [`World::step`]).
    pub fn torque_impulse(&mut self, h: RigidBodyHandle, imp: Vec3) {
        let linked = self.phys.multibody_joints.rigid_body_link(h).is_some();
        let rb = &mut self.phys.bodies[h];
        if linked {
            rb.add_torque(imp / self.dt as f32, true);
        } else {
            rb.apply_torque_impulse(imp, true);
        }
    }

    /// [`World::torque_impulse`] for a linear impulse at the centre of
    /// mass.
    pub fn impulse(&mut self, h: RigidBodyHandle, imp: Vec3) {
        let linked = self.phys.multibody_joints.rigid_body_link(h).is_some();
        let rb = &mut self.phys.bodies[h];
        if linked {
            rb.add_force(imp / self.dt as f32, true);
        } else {
            rb.apply_impulse(imp, true);
        }
    }

    /// Move a scripted body toward `position` (with the target's velocity
    /// and acceleration): kinematic props go exactly there at the end of
    /// the next step; the opponent's dynamic parts are pulled by the
    /// bounded spring-damper of [`drive_impulse`].
    pub fn drive(&mut self, body: BodyId, position: Vec3, velocity: Vec3, accel: Vec3) {
        match self.driven.iter_mut().find(|d| d.0 == body) {
            Some(d) => d.1 = position,
            None => self.driven.push((body, position)),
        }
        let h = self.info(body).handle;
        let dt = self.dt as f32;
        let rb = &mut self.phys.bodies[h];
        if rb.is_kinematic() {
            rb.set_next_kinematic_translation(position);
            return;
        }
        let state = DriveState {
            mass: rb.mass(),
            at: (rb.translation(), rb.linvel()),
            target: (position, velocity, accel),
        };
        rb.apply_impulse(drive_impulse(&state, dt), true);
    }

    /// Give the VH's part `part` an impulse (N s, world) at its centre of
    /// mass; a kinematic part (the trunk of a driven pelvis) is not moved.
    pub fn push(&mut self, part: PushPart, impulse: Vec3) {
        let h = match (part, &self.legs) {
            (PushPart::Pelvis, Some(legs)) => legs.handles[Part::Pelvis.index()],
            (PushPart::Pelvis | PushPart::Trunk, _) => self.info(Seg::Torso).handle,
            (PushPart::Head, _) => self.info(Seg::Head).handle,
        };
        if self.phys.bodies[h].is_dynamic() {
            self.impulse(h, impulse);
        }
    }

    /// Where a driven body was last asked to be, if it is driven: a part
    /// pushed off its path (an avatar's head that took a blow) is that
    /// far from it.
    pub fn drive_target(&self, body: BodyId) -> Option<Vec3> {
        self.driven.iter().find(|d| d.0 == body).map(|d| d.1)
    }

    /// Put the VH's root (torso) at `offset` from its rest position by the
    /// end of the next step (a lunge; the joints carry the rest along).
    pub fn set_root_offset(&mut self, offset: Vec3) {
        self.set_root_pose(offset, Quat::IDENTITY);
    }

    /// Put the VH's root (the trunk) by the end of the next step: its pivot
    /// (the waist joint) moved by `offset` from rest and the trunk turned
    /// by `rotation` about it (the lower body's stepping, the waist's turn
    /// and bend; the joints carry the rest along).
    pub fn set_root_pose(&mut self, offset: Vec3, rotation: Quat) {
        self.root_path = [self.root_path[1], self.root_path[2], offset];
        let s = &self.plan.segments[Seg::Torso.index()];
        let at = s.pivot + offset + rotation * (s.centre - s.pivot);
        let h = self.info(Seg::Torso).handle;
        self.phys.bodies[h].set_next_kinematic_position(Pose::from_parts(at, rotation));
    }

    /// Advance the physics by one fixed step.
    pub fn step(&mut self) {
        match &self.soles {
            Some(soles) => self.phys.step_with_events(soles, &()),
            None => self.phys.step(),
        }
        // A link's torques were held through the step (World::torque_impulse):
        // cleared, every link's.
        if let Some(legs) = &self.legs {
            let upper = self.links.iter().zip(&self.bodies);
            let upper = upper.filter(|(l, _)| l.is_some()).map(|(_, b)| &b.handle);
            for h in legs.handles.iter().chain([&legs.trunk]).chain(upper) {
                self.phys.bodies[*h].reset_forces(false);
                self.phys.bodies[*h].reset_torques(false);
            }
        }
    }

    /// Ask sole `k`'s contact for `slip` through the next step (none: plain
    /// friction).
    pub fn set_sole_slip(&mut self, k: usize, slip: Option<SoleSlip>) {
        if let Some(s) = &mut self.soles {
            s.feet[k].1 = slip;
        }
    }

    /// True if every dynamic body's pose and velocity are finite.
    pub fn is_finite(&self) -> bool {
        self.phys.bodies.iter().all(|(_, rb)| {
            rb.translation().is_finite()
                && rb.rotation().is_finite()
                && rb.linvel().is_finite()
                && rb.angvel().is_finite()
        })
    }

    /// A physics explosion, described: non-finite state (rapier
    /// quarantined a body), or a VH segment spinning faster than
    /// `max_angvel` rad/s (a saccade peaks near 9 rad/s; absurd gains or an
    /// integration blow-up give thousands).
    pub fn blow_up(&self, max_angvel: f32) -> Option<String> {
        if !self.phys.quarantine().is_empty() || !self.is_finite() {
            return Some("non-finite state".into());
        }
        Seg::ALL
            .into_iter()
            .zip(&self.plan.segments)
            .find_map(|(seg, s)| {
                let w = self.rb(seg).angvel().length();
                (!w.is_finite() || w > max_angvel).then(|| {
                    let mut why = format!("{} spinning at {w:.0} rad/s", s.name);
                    // What the VH was touching (the usual cause).
                    let n = self.plan.segments.len();
                    for a in self.body_ids().skip(n) {
                        for b in self.body_ids().take(n) {
                            if let Some(j) = self.contact_impulse(a, b) {
                                why += &format!(
                                    "; {} on {} ({j:.2} N s)",
                                    self.info(a).name,
                                    self.info(b).name
                                );
                            }
                        }
                    }
                    why
                })
            })
    }

    /// Put the VH back in its rest pose, at rest: every segment re-enabled
    /// (rapier disables quarantined bodies), its pose reset, velocities and
    /// user forces zeroed, joint warm-start impulses cleared.
    pub fn reset_vh(&mut self) {
        for (i, s) in self.plan.segments.iter().enumerate() {
            if s.joint == JointKind::Weld {
                continue;
            }
            let h = self.bodies[i].handle;
            let rb = &mut self.phys.bodies[h];
            rb.set_enabled(true);
            rb.set_position(Pose::from_parts(s.centre, Quat::IDENTITY), true);
            rb.set_linvel(Vec3::ZERO, true);
            rb.set_angvel(Vec3::ZERO, true);
            rb.reset_forces(true);
            rb.reset_torques(true);
        }
        if let Some(legs) = &self.legs {
            legs.reset(&mut self.phys);
        }
        for (_, j) in self.phys.impulse_joints.iter_mut() {
            j.impulses = Default::default();
        }
    }

    /// Whether two bodies are touching now.
    pub fn in_contact(&self, a: impl Into<BodyId>, b: impl Into<BodyId>) -> bool {
        self.contact_impulse(a, b).is_some()
    }

    /// The contact impulse between bodies `a` and `b` in the last step,
    /// N s (the solver's normal impulses, summed as vectors), or `None`
    /// if they are not touching.
    pub fn contact_impulse(&self, a: impl Into<BodyId>, b: impl Into<BodyId>) -> Option<f32> {
        self.phys
            .contact_pair(self.info(a).collider, self.info(b).collider)
            .filter(|p| p.has_any_active_contact())
            .map(|p| p.total_impulse().length())
    }

    /// The body a collider belongs to (colliders carry their body's number).
    fn collider_body(&self, c: &Collider) -> Option<&BodyInfo> {
        self.bodies.get(c.user_data as usize)
    }
}

/// Vision's view of the physics world: rapier bodies, eye segments and ray
/// queries.
impl Scenery for World {
    fn head_rotation(&self) -> DQuat {
        self.rb(Seg::Head).rotation().as_dquat()
    }

    fn eye(&self, k: usize) -> (Vec3, DVec3) {
        let rb = self.rb(Seg::EYES[k]);
        (rb.translation(), (*rb.rotation() * Vec3::Z).as_dvec3())
    }

    fn body_count(&self) -> usize {
        self.bodies.len()
    }

    fn is_own(&self, b: BodyId) -> bool {
        matches!(self.info(b).owner, Owner::Vh(_))
    }

    fn position(&self, b: BodyId) -> DVec3 {
        World::position(self, b).as_dvec3()
    }

    fn motion(&self, b: BodyId) -> Motion {
        let rb = self.rb(b);
        Motion {
            orientation: rb.rotation().as_dquat(),
            velocity: self.velocity(b).as_dvec3(),
            angvel: rb.angvel().as_dvec3(),
        }
    }

    fn first_hit(&self, from: Vec3, dir: DVec3, target: BodyId) -> bool {
        let len = dir.length() as f32;
        let ray = Ray::new(from, (dir / dir.length()).as_vec3());
        let target = target.index() as u128;
        let is_vh =
            |c: &Collider| matches!(self.collider_body(c).map(|b| b.owner), Some(Owner::Vh(_)));
        let pred = |_h, c: &Collider| !is_vh(c) || c.user_data == target;
        let filter = QueryFilter::default().predicate(&pred);
        match self.phys.cast_ray(&ray, len + 1.0, true, filter) {
            Some((h, _)) => self.phys.colliders[h].user_data == target,
            None => false,
        }
    }

    fn radius(&self, b: BodyId) -> f64 {
        // The narrowest half extent of the body's colliders' box: a
        // sphere's radius, a capsule's or a glove's half width.
        let rb = self.rb(b);
        rb.colliders()
            .iter()
            .map(|&h| {
                let aabb = self.phys.colliders[h].compute_aabb();
                let half = aabb.half_extents();
                half.x.min(half.y).min(half.z)
            })
            .fold(0.0f32, f32::max)
            .into()
    }
}

#[cfg(test)]
mod tests;
