//! The physics world: rapier bodies and joints built from a [`BodyPlan`],
//! joint read-out in yaw/pitch/roll, and application of the PD torques.
//!
//! The world owns no behaviour; each tick the simulation hands it one
//! [`JointTarget`] per controlled segment and the kinematic poses of the
//! opponent and props, then calls [`World::step`].

use glam::{DQuat, DVec3, Mat3, Quat, Vec3};
use rapier3d::prelude::*;

use crate::agent::vision::{Motion, Scenery};
use crate::physics::body::{BodyPlan, Group, HARD_STOP_MARGIN_DEG, JointKind, Shape, seg};
use crate::physics::control::{Gains, JointState, JointTarget, pd_torque};
use crate::util::math::JointAngles;

/// Who a body belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Owner {
    /// A segment of the virtual human (index into the plan).
    Vh(usize),
    /// The opponent avatar (head, left glove, right glove).
    Opponent,
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

/// Index of the opponent's parts in [`World::opponent`].
#[allow(missing_docs)]
pub mod opp {
    pub const HEAD: usize = 0;
    pub const LEFT_GLOVE: usize = 1;
    pub const RIGHT_GLOVE: usize = 2;
    pub const NAMES: [&str; 3] = ["head", "left_glove", "right_glove"];
}

/// Masses of the opponent's head and gloves (a glove carries the effective
/// mass of the arm behind it), kg.
pub const OPPONENT_MASS: [f32; 3] = [5.0, 1.5, 1.5];
/// Drive of the opponent's parts, per kg: natural frequency 40 rad/s,
/// critically damped (k = w^2, c = 2 w). A free glove tracks a 0.2 s
/// punch closely; a blocked one pushes with at most about k x.
const DRIVE_STIFFNESS: f32 = 1600.0;
/// The drive's force is capped at this acceleration of the part's mass,
/// m/s^2 (40 g; a fast punch's glove peaks near 16 g on a minimum-jerk
/// path). A scripted path that turns abruptly (a new move while the glove
/// is moving) differentiates to accelerations of 10^4 m/s^2; uncapped, that
/// feed-forward flung an opponent glove into the VH's at 40 m/s in one
/// step (the long soaks' arm blow-ups).
const DRIVE_MAX_ACCEL: f32 = 400.0;
const DRIVE_DAMPING: f32 = 80.0;

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
    /// Every named body; VH segments first, in plan order.
    pub bodies: Vec<BodyInfo>,
    /// Body index of each opponent part (head, left glove, right glove).
    pub opponent: [usize; 3],
    /// Pivot of each segment in its parent's local frame.
    anchor_parent: Vec<Vec3>,
    /// Segments of each segment's subtree (itself included).
    subtree: Vec<Vec<usize>>,
    /// Each segment's inertia tensor about its centre of mass, in its own
    /// frame (constant; rebuilding it from rapier's principal form every
    /// tick cost 4 % of a step).
    local_inertia: Vec<Mat3>,
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

impl World {
    /// Build the world at rest from a plan, stepping at `dt` seconds.
    pub fn new(plan: BodyPlan, dt: f64) -> Self {
        let mut phys = PhysicsWorld::new();
        phys.integration_parameters.dt = dt as f32;
        phys.integration_parameters.num_solver_iterations = SOLVER_SUBSTEPS;
        phys.integration_parameters.num_internal_pgs_iterations = SOLVER_ITERATIONS;
        let mut bodies: Vec<BodyInfo> = Vec::new();
        let mut handles = Vec::new();
        let vh_groups =
            InteractionGroups::new(VH_GROUP, Group32::ALL ^ VH_GROUP, Default::default());
        for (i, s) in plan.segments.iter().enumerate() {
            // A welded segment is not a body of its own but a collider on
            // its parent's (as MuJoCo merges a body without joints): no
            // joint to solve, nothing to drift apart.
            let welded = match (s.joint, s.parent) {
                (JointKind::Weld, Some(p)) => Some(p),
                _ => None,
            };
            let (h, offset) = match welded {
                Some(p) => (
                    handles[p],
                    bodies[p].offset + s.centre - plan.segments[p].centre,
                ),
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
            if i == seg::EYE_L || i == seg::EYE_R {
                // Eyes sit inside the head: they carry mass but touch nothing.
                cb = cb.collision_groups(InteractionGroups::none());
            }
            let c = phys.insert_collider(cb.user_data(i as u128), Some(h));
            handles.push(h);
            bodies.push(BodyInfo {
                name: s.name.to_string(),
                handle: h,
                collider: c,
                owner: Owner::Vh(i),
                kinematic: false,
                offset,
            });
        }
        let mut anchor_parent = vec![Vec3::ZERO; plan.segments.len()];
        for (i, s) in plan.segments.iter().enumerate() {
            let Some(p) = s.parent else { continue };
            let a1 = s.pivot - plan.segments[p].centre;
            let a2 = s.pivot - s.centre;
            anchor_parent[i] = a1;
            let joint: GenericJoint = match s.joint {
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
                JointKind::Weld | JointKind::Root => continue,
            };
            phys.insert_impulse_joint(handles[p], handles[i], joint);
        }
        let n = plan.segments.len();
        let local_inertia = handles
            .iter()
            .map(|h| {
                phys.bodies[*h]
                    .mass_properties()
                    .local_mprops
                    .reconstruct_inertia_matrix()
            })
            .collect();
        let mut subtree = vec![Vec::new(); n];
        // Welded segments' mass is in their carrier body's.
        for i in (0..n).filter(|&i| plan.segments[i].joint != JointKind::Weld) {
            let mut j = Some(i);
            while let Some(k) = j {
                subtree[k].push(i);
                j = plan.segments[k].parent;
            }
        }
        let opp_groups = InteractionGroups::all();
        let mut opponent = [0; 3];
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
        for k in 0..3 {
            let idx = bodies.len();
            // Dynamic, driven by a spring-damper toward the scripted or live
            // target (see `drive`): finite mass and strength, so a punch
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
                    .collision_groups(opp_groups)
                    .user_data(idx as u128),
                Some(h),
            );
            opponent[k] = idx;
            bodies.push(BodyInfo {
                name: opp::NAMES[k].to_string(),
                handle: h,
                collider: c,
                owner: Owner::Opponent,
                kinematic: false,
                offset: Vec3::ZERO,
            });
        }
        World {
            phys,
            plan,
            dt,
            bodies,
            opponent,
            anchor_parent,
            subtree,
            local_inertia,
        }
    }

    /// Add a prop; returns its body index.
    pub fn add_prop(&mut self, p: &PropSpec) -> usize {
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
        idx
    }

    /// Find a body by name.
    pub fn body_index(&self, name: &str) -> Option<usize> {
        self.bodies.iter().position(|b| b.name == name)
    }

    /// The rapier body carrying a body index (for a welded segment, its
    /// parent's: use [`World::position`] and [`World::velocity`] for the
    /// part itself).
    pub fn rb(&self, body: usize) -> &RigidBody {
        &self.phys.bodies[self.bodies[body].handle]
    }

    /// The rapier body of a VH segment (see [`World::rb`]).
    pub fn seg(&self, s: usize) -> &RigidBody {
        self.rb(s)
    }

    /// World pose of a body: (translation, rotation).
    pub fn pose(&self, body: usize) -> (Vec3, Quat) {
        let rb = self.rb(body);
        (
            rb.position().transform_point(self.bodies[body].offset),
            *rb.rotation(),
        )
    }

    /// World position of a body.
    pub fn position(&self, body: usize) -> Vec3 {
        self.pose(body).0
    }

    /// World velocity of a body (of its point, for a welded part).
    pub fn velocity(&self, body: usize) -> Vec3 {
        self.rb(body).velocity_at_point(self.position(body))
    }

    /// Rotation of a segment relative to its parent (identity at rest).
    pub fn joint_rotation(&self, s: usize) -> Quat {
        let p = self.plan.segments[s].parent.expect("joint has a parent");
        self.seg(p).rotation().inverse() * *self.seg(s).rotation()
    }

    /// Angles of a segment's joint.
    pub fn joint_angles(&self, s: usize) -> JointAngles {
        JointAngles::from_quat(self.joint_rotation(s))
    }

    /// Child-minus-parent angular velocity in the parent's frame.
    pub fn joint_angvel(&self, s: usize) -> Vec3 {
        let p = self.plan.segments[s].parent.expect("joint has a parent");
        let pr = self.seg(p);
        pr.rotation().inverse() * (self.seg(s).angvel() - pr.angvel())
    }

    /// World position of a segment's pivot.
    pub fn pivot(&self, s: usize) -> Vec3 {
        let p = self.plan.segments[s].parent.expect("joint has a parent");
        self.seg(p)
            .position()
            .transform_point(self.anchor_parent[s])
    }

    /// How far apart the two halves of the widest-open joint are, m: the
    /// pivot as the parent carries it against the pivot as the child
    /// carries it. A rigid joint keeps this near zero; the solver lets it
    /// open under large impulses and closes it again.
    pub fn joint_gap(&self) -> f32 {
        self.plan
            .segments
            .iter()
            .enumerate()
            .filter(|(_, s)| s.parent.is_some() && s.joint != JointKind::Weld)
            .map(|(i, s)| {
                let child = self.seg(i).position().transform_point(s.pivot - s.centre);
                (child - self.pivot(i)).length()
            })
            .fold(0.0, f32::max)
    }

    /// Inertia tensor of segment `s`'s subtree about `point`, world frame.
    pub fn subtree_inertia(&self, s: usize, point: Vec3) -> Mat3 {
        let mut total = Mat3::ZERO;
        for &b in &self.subtree[s] {
            let rb = self.seg(b);
            let r = Mat3::from_quat(*rb.rotation());
            let i_local = self.local_inertia[b];
            let d = rb.center_of_mass() - point;
            let m = rb.mass();
            let parallel = m
                * (Mat3::from_diagonal(Vec3::splat(d.length_squared()))
                    - Mat3::from_cols(d * d.x, d * d.y, d * d.z));
            total += r * i_local * r.transpose() + parallel;
        }
        total
    }

    /// Torque that holds segment `s`'s subtree against gravity about its pivot.
    pub fn gravity_torque(&self, s: usize) -> Vec3 {
        let pivot = self.pivot(s);
        let g = self.phys.gravity;
        let mut tau = Vec3::ZERO;
        for &b in &self.subtree[s] {
            let rb = self.seg(b);
            tau -= (rb.center_of_mass() - pivot).cross(g * rb.mass());
        }
        tau
    }

    /// Apply one tick of PD torques (as impulses over `dt`) to every
    /// controlled joint. `targets` is indexed by segment.
    pub fn apply_control(&mut self, gains: &Gains, targets: &[JointTarget]) {
        let dt = self.dt as f32;
        let mut impulses = Vec::with_capacity(self.plan.segments.len());
        for (s, segm) in self.plan.segments.iter().enumerate() {
            let (Some(p), Some(group)) = (segm.parent, segm.group) else {
                continue;
            };
            let pivot = self.pivot(s);
            let state = JointState {
                parent_rot: *self.seg(p).rotation(),
                child_rot: *self.seg(s).rotation(),
                rel_angvel: self.seg(s).angvel() - self.seg(p).angvel(),
                inertia: self.subtree_inertia(s, pivot),
            };
            let mut tau = pd_torque(gains.group(group), &targets[s], &state, dt);
            if gains.gravity_compensation {
                tau += self.gravity_torque(s);
            }
            impulses.push((p, s, tau * dt));
        }
        for (p, s, imp) in impulses {
            let hs = self.bodies[s].handle;
            self.phys.bodies[hs].apply_torque_impulse(imp, true);
            let hp = self.bodies[p].handle;
            if self.phys.bodies[hp].is_dynamic() {
                self.phys.bodies[hp].apply_torque_impulse(-imp, true);
            }
        }
    }

    /// Move a scripted body toward `position` (with the target's velocity
    /// and acceleration): kinematic props go exactly there at the end of
    /// the next step; the opponent's dynamic parts are pulled by a
    /// spring-damper with feed-forward, `F = m a + c (v - v_b) + k (p - p_b)`,
    /// whose stiffness bounds the force a blocked glove can push with.
    pub fn drive(&mut self, body: usize, position: Vec3, velocity: Vec3, accel: Vec3) {
        let h = self.bodies[body].handle;
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

    /// Put the VH's root (torso) at `offset` from its rest position by the
    /// end of the next step (a lunge; the joints carry the rest along).
    pub fn set_root_offset(&mut self, offset: Vec3) {
        let rest = self.plan.segments[seg::TORSO].centre;
        let h = self.bodies[seg::TORSO].handle;
        self.phys.bodies[h].set_next_kinematic_translation(rest + offset);
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
        self.plan.segments.iter().enumerate().find_map(|(i, s)| {
            let w = self.seg(i).angvel().length();
            (!w.is_finite() || w > max_angvel).then(|| {
                let mut why = format!("{} spinning at {w:.0} rad/s", s.name);
                // What the VH was touching (the usual cause).
                let n = self.plan.segments.len();
                for a in n..self.bodies.len() {
                    for b in 0..n {
                        if let Some(j) = self.contact_impulse(a, b) {
                            why += &format!(
                                "; {} on {} ({j:.2} N s)",
                                self.bodies[a].name, self.bodies[b].name
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
    pub fn in_contact(&self, a: usize, b: usize) -> bool {
        self.contact_impulse(a, b).is_some()
    }

    /// The contact impulse between bodies `a` and `b` in the last step,
    /// N s (the solver's normal impulses, summed as vectors), or `None`
    /// if they are not touching.
    pub fn contact_impulse(&self, a: usize, b: usize) -> Option<f32> {
        self.phys
            .contact_pair(self.bodies[a].collider, self.bodies[b].collider)
            .filter(|p| p.has_any_active_contact())
            .map(|p| p.total_impulse().length())
    }
}

/// The effective inertia of a gain group's joint about its main axis at
/// rest, kg m^2, from the default body plan's mass properties.
pub fn group_inertia(group: Group) -> f64 {
    static INERTIA: std::sync::OnceLock<[f64; 4]> = std::sync::OnceLock::new();
    let all = INERTIA.get_or_init(|| {
        let world = World::new(BodyPlan::default(), 0.001);
        Group::ALL.map(|g| {
            let j = g.joint();
            let i = world.subtree_inertia(j, world.pivot(j));
            let axis = if g.main_axis() == 0 { Vec3::Y } else { Vec3::X };
            f64::from(axis.dot(i * axis))
        })
    });
    all[Group::ALL
        .iter()
        .position(|g| *g == group)
        .expect("every group is listed")]
}

/// Fastest natural frequency `sqrt(kp / I)` a joint's gains may ask for,
/// rad/s: the 1 kHz step itself. Human joints are far slower (a saccade's
/// eye plant is near 300 rad/s, a neck near 30).
pub const MAX_NATURAL_FREQUENCY: f64 = 1000.0;
/// Fastest damping rate `kd / I` a joint's gains may ask for, 1/s (twice
/// the critically damped rate at [`MAX_NATURAL_FREQUENCY`]).
pub const MAX_DAMPING_RATE: f64 = 2.0 * MAX_NATURAL_FREQUENCY;

/// Whether gains are plausible for the body: each group's natural
/// frequency and damping rate within the bounds above. The stable PD law
/// takes any non-negative gains, but past these a joint is a rigid weld
/// computed in single precision, and rapier blows up.
pub fn check_gains(gains: &Gains) -> Result<(), GainsError> {
    for g in Group::ALL {
        let (jg, i) = (gains.group(g), group_inertia(g));
        let group = format!("{g:?}").to_lowercase();
        let omega = (jg.kp / i).sqrt();
        if omega > MAX_NATURAL_FREQUENCY {
            return Err(GainsError {
                field: format!("{group}.kp"),
                message: format!(
                    "{} gives a natural frequency of {omega:.0} rad/s on the joint's {i:.3e} kg m^2; at most {MAX_NATURAL_FREQUENCY} (kp <= {:.4e})",
                    jg.kp,
                    i * MAX_NATURAL_FREQUENCY * MAX_NATURAL_FREQUENCY
                ),
            });
        }
        if jg.kd / i > MAX_DAMPING_RATE {
            return Err(GainsError {
                field: format!("{group}.kd"),
                message: format!(
                    "{} gives a damping rate of {:.0} 1/s on the joint's {i:.3e} kg m^2; at most {MAX_DAMPING_RATE} (kd <= {:.4e})",
                    jg.kd,
                    jg.kd / i,
                    i * MAX_DAMPING_RATE
                ),
            });
        }
    }
    Ok(())
}

/// Implausible gains: the field (`eye.kp`) and why.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{field}: {message}")]
pub struct GainsError {
    /// The field, relative to the gains (`eye.kp`).
    pub field: String,
    /// What is wrong.
    pub message: String,
}

/// Vision's view of the physics world: rapier bodies, eye segments and ray
/// queries.
impl Scenery for World {
    fn head_rotation(&self) -> DQuat {
        self.seg(seg::HEAD).rotation().as_dquat()
    }

    fn eye(&self, k: usize) -> (Vec3, DVec3) {
        let rb = self.seg([seg::EYE_L, seg::EYE_R][k]);
        (rb.translation(), (*rb.rotation() * Vec3::Z).as_dvec3())
    }

    fn body_count(&self) -> usize {
        self.bodies.len()
    }

    fn is_own(&self, i: usize) -> bool {
        matches!(self.bodies[i].owner, Owner::Vh(_))
    }

    fn position(&self, i: usize) -> DVec3 {
        World::position(self, i).as_dvec3()
    }

    fn motion(&self, i: usize) -> Motion {
        let rb = self.rb(i);
        Motion {
            orientation: rb.rotation().as_dquat(),
            velocity: self.velocity(i).as_dvec3(),
            angvel: rb.angvel().as_dvec3(),
        }
    }

    fn first_hit(&self, from: Vec3, dir: DVec3, target: usize) -> bool {
        let len = dir.length() as f32;
        let ray = Ray::new(from, (dir / dir.length()).as_vec3());
        let is_vh = |c: &rapier3d::prelude::Collider| {
            matches!(
                self.bodies.get(c.user_data as usize).map(|b| b.owner),
                Some(Owner::Vh(_))
            )
        };
        let pred =
            |_h, c: &rapier3d::prelude::Collider| !is_vh(c) || c.user_data as usize == target;
        let filter = QueryFilter::default().predicate(&pred);
        match self.phys.cast_ray(&ray, len + 1.0, true, filter) {
            Some((h, _)) => self.phys.colliders[h].user_data as usize == target,
            None => false,
        }
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
        let g = w.opponent[opp::LEFT_GLOVE];
        let p = w.rb(g).translation();
        w.drive(g, p + Vec3::X * 0.05, Vec3::X * 50.0, Vec3::X * 1e5);
        w.step();
        let v = w.rb(g).linvel().length();
        assert!(v > 0.1 && v <= DRIVE_MAX_ACCEL * 0.001 * 1.001, "{v}");
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
        let (f, g) = (seg::FOREARM_L, seg::GLOVE_L);
        let reach = (plan.segments[g].centre - plan.segments[f].pivot).length();
        let mass = plan.segments[f].mass + plan.segments[g].mass;
        let mut w = World::new(plan, 0.001);
        assert_eq!(w.bodies[g].handle, w.bodies[f].handle);
        assert!((w.rb(g).mass() - mass).abs() < 1e-4, "{}", w.rb(g).mass());
        let h = w.bodies[f].handle;
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
        assert_eq!(w.bodies[w.opponent[1]].name, "left_glove");
        let a = w.joint_angles(seg::HEAD);
        assert!(a.yaw.abs() < 1e-9 && a.pitch.abs() < 1e-9);
        let i = w.subtree_inertia(seg::EYE_L, w.pivot(seg::EYE_L));
        let expect = 0.4 * 0.0075 * 0.011f32 * 0.011;
        assert!(
            (i.x_axis.x - expect).abs() / expect < 1e-3,
            "{}",
            i.x_axis.x
        );
    }
}
