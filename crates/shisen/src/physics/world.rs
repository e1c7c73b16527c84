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

use crate::physics::body::{
    BodyPlan, Group, HARD_STOP_MARGIN_DEG, JointKind, OpponentPart, Seg, Segment, Shape,
};
use crate::physics::control::{Gains, JointState, JointTarget, pd_torque};
use crate::physics::neck::{NeckParams, NeckState, neck_torque};
use crate::physics::opponent::{DriveState, OPPONENT_MASS, drive_impulse};
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
    /// The body of each opponent part ([`OpponentPart`] order).
    opponent: [BodyId; 3],
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
}

fn collider_for(shape: Shape, axis_to: Vec3, at: Vec3) -> ColliderBuilder {
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
fn head_surface(cb: ColliderBuilder) -> ColliderBuilder {
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
fn empty_world(dt: f64) -> PhysicsWorld {
    let mut phys = PhysicsWorld::new();
    phys.integration_parameters.dt = dt as f32;
    phys.integration_parameters.num_solver_iterations = SOLVER_SUBSTEPS;
    phys.integration_parameters.num_internal_pgs_iterations = SOLVER_ITERATIONS;
    phys
}

/// Build step 2: one body and collider per VH segment, in plan order (a
/// welded segment is a collider on its parent's body).
fn add_segments(phys: &mut PhysicsWorld, plan: &BodyPlan, bodies: &mut Vec<BodyInfo>) {
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
                let rb = if s.parent.is_none() {
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

/// Build step 3: the joints between segments (ball, hinge; eyes and neck
/// with a hard stop beyond the controller's range). Returns each
/// segment's pivot in its parent's frame.
fn join_segments(phys: &mut PhysicsWorld, plan: &BodyPlan, bodies: &[BodyInfo]) -> Vec<Vec3> {
    let mut anchor_parent = vec![Vec3::ZERO; plan.segments.len()];
    for (i, s) in plan.segments.iter().enumerate() {
        let Some(p) = s.parent else { continue };
        let a1 = s.pivot - plan.segments[p.index()].centre;
        let a2 = s.pivot - s.centre;
        anchor_parent[i] = a1;
        let Some(joint) = joint_for(s, a1, a2) else {
            continue;
        };
        phys.insert_impulse_joint(bodies[p.index()].handle, bodies[i].handle, joint);
    }
    anchor_parent
}

/// The rapier joint of a segment with anchors `a1` (parent frame) and
/// `a2` (own frame); `None` for the root and welded segments.
fn joint_for(s: &Segment, a1: Vec3, a2: Vec3) -> Option<GenericJoint> {
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
fn subtrees(plan: &BodyPlan) -> Vec<Vec<Seg>> {
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
fn add_opponent(
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
    })
}

impl World {
    /// Build the world at rest from a plan, stepping at `dt` seconds: the
    /// solver, the VH's segments, their joints, the constant inertias and
    /// subtrees, the opponent's parts.
    pub fn new(plan: BodyPlan, dt: f64) -> Self {
        assert_eq!(
            plan.segments.len(),
            Seg::ALL.len(),
            "a body plan has one segment per Seg, in order"
        );
        let mut phys = empty_world(dt);
        let mut bodies = Vec::new();
        add_segments(&mut phys, &plan, &mut bodies);
        let anchor_parent = join_segments(&mut phys, &plan, &bodies);
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
            anchor_parent,
            subtree,
            local_inertia,
            driven: Vec::new(),
            root_path: [Vec3::ZERO; 3],
        }
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
        self.opponent
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
        let pivot = self.pivot(s);
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
            let mut tau = match group {
                Group::Neck => neck_torque(gains.group(group), neck.0, neck.1, target, &state, dt),
                _ => pd_torque(gains.group(group), target, &state, dt),
            };
            if gains.gravity_compensation {
                tau += self.gravity_torque(s, root_accel);
            }
            impulses.push((p, s, tau * dt));
        }
        for (p, s, imp) in impulses {
            let hs = self.info(s).handle;
            self.phys.bodies[hs].apply_torque_impulse(imp, true);
            let hp = self.info(p).handle;
            if self.phys.bodies[hp].is_dynamic() {
                self.phys.bodies[hp].apply_torque_impulse(-imp, true);
            }
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
        self.phys.step();
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
}

#[cfg(test)]
mod tests {
    use super::*;

    /// However abrupt the scripted path, a driven glove gains at most
    /// `DRIVE_MAX_ACCEL dt` of speed in a step.
    #[test]
    fn a_driven_glove_is_capped() {
        let mut w = World::new(BodyPlan::default(), 0.001);
        let g = w.part(OpponentPart::LeftGlove);
        let p = w.rb(g).translation();
        w.drive(g, p + Vec3::X * 0.05, Vec3::X * 50.0, Vec3::X * 1e5);
        w.step();
        let v = w.rb(g).linvel().length();
        let cap = crate::physics::opponent::DRIVE_MAX_ACCEL * 0.001;
        assert!(v > 0.1 && v <= cap * 1.001, "{v}");
    }

    #[test]
    fn joint_angles_round_trip() {
        let a = JointAngles {
            yaw: 0.4,
            pitch: -0.3,
            roll: 0.1,
        };
        let b = JointAngles::from_quat(a.to_quat());
        assert!((a.yaw - b.yaw).abs() < 1e-6);
        assert!((a.pitch - b.pitch).abs() < 1e-6);
        assert!((a.roll - b.roll).abs() < 1e-6);
        // positive pitch turns the forward axis up, positive yaw to the left (+X)
        let f = a.to_quat() * Vec3::Z;
        assert!(f.x > 0.0);
        let up = JointAngles {
            pitch: 0.3,
            ..Default::default()
        }
        .to_quat()
            * Vec3::Z;
        assert!(up.y > 0.0);
    }

    /// A welded glove is a collider on its forearm's body: it keeps its
    /// place on the forearm however the arm swings, and its mass is the
    /// forearm body's.
    #[test]
    fn a_welded_glove_rides_its_forearm() {
        let plan = BodyPlan::default();
        let (f, g) = (Seg::ForearmL, Seg::GloveL);
        let reach = (plan.segments[g.index()].centre - plan.segments[f.index()].pivot).length();
        let mass = plan.segments[f.index()].mass + plan.segments[g.index()].mass;
        let mut w = World::new(plan, 0.001);
        assert_eq!(w.info(g).handle, w.info(f).handle);
        assert!((w.rb(g).mass() - mass).abs() < 1e-4, "{}", w.rb(g).mass());
        let h = w.info(f).handle;
        w.phys.bodies[h].set_angvel(Vec3::new(3.0, 1.0, 0.0), true);
        for _ in 0..50 {
            w.step();
        }
        let elbow = w.pivot(f);
        let d = (w.position(g) - elbow).length();
        assert!((d - reach).abs() < 2e-3, "{d} vs {reach}");
        // The part's velocity is its point's, not the body centre's.
        let rb = w.rb(g);
        let lever = w.position(g) - rb.center_of_mass();
        let expect = rb.linvel() + rb.angvel().cross(lever);
        assert!((w.velocity(g) - expect).length() < 1e-4);
        assert!(w.joint_gap() < 2e-3, "{}", w.joint_gap());
    }

    #[test]
    fn world_builds_at_rest() {
        let w = World::new(BodyPlan::default(), 0.001);
        assert_eq!(w.info(w.part(OpponentPart::LeftGlove)).name, "left_glove");
        let a = w.joint_angles(Seg::Head);
        assert!(a.yaw.abs() < 1e-9 && a.pitch.abs() < 1e-9);
        let i = w.subtree_inertia(Seg::EyeL, w.pivot(Seg::EyeL));
        let expect = shisen_gaze::anatomy::eye::INERTIA as f32;
        assert!(
            (i.x_axis.x - expect).abs() / expect < 1e-3,
            "{}",
            i.x_axis.x
        );
    }
}
