//! Balance: the controller that keeps the physical body up, and its
//! states when it cannot (docs/model/balance.md, B2-B5).
//!
//! ```text
//! xi = c + v / w0,  w0 = sqrt(g / h_c)                               (B2)
//!   the capture point (Hof, Gazendam & Sinke 2005, J. Biomech. 38:1;
//!   their "extrapolated centre of mass")
//! small errors: every joint tracks the planned posture by stable PD; the
//!   stance legs carry the body's weight, shared by the centre of mass's
//!   place between the feet: tau_j = (p_j - c) x (s_k M g y^)          (B3)
//!   (the ankle strategy, and the hips' when the trunk is pushed)
//! large ones: xi outside the feet's polygon by `step_margin`: the foot
//!   the capture point loads less steps to where xi will be at touchdown,
//!   xi_T = p + (xi - p) e^(w0 T), p the other foot, T the step's time
//!   (the linear inverted pendulum's capture step), no farther than
//!   `max_step`; meanwhile the stance leg no longer pulls the centre of
//!   mass back                                                          (B4)
//! too large: the trunk past `fall_tilt`, or the hips lower than
//!   `fall_height`, or a blow that turns the head faster than
//!   `stun_head_speed` (the legs go): the body falls (muscle tone
//!   `down_tone`), lies for a time that grows with the damage, and
//!   rises (B5)
//! ```
//!
//! The state machine: Standing -> Falling (a knockdown) -> Down (on the
//! canvas) -> Rising -> Standing (a get-up).

use glam::{DVec3, Quat, Vec3};
use rand::Rng;
use rand_distr::{Distribution, StandardNormal};

use crate::physics::body::Seg;
use crate::physics::legs::{Joint, Legs, Part};
use crate::physics::lower::{BodyParams, LowerBody, anthro};
use crate::physics::world::World;

pub mod grip;
pub mod params;
use grip::Grip;
use params::BalanceParams;

/// Where the body is in the balance states.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Stance {
    /// Up: tracking the planned posture, stepping to recover.
    #[default]
    Standing,
    /// Going down (a knockdown).
    Falling,
    /// On the canvas.
    Down,
    /// Getting up.
    Rising,
}

impl Stance {
    /// Its name in traces.
    pub fn name(self) -> &'static str {
        match self {
            Stance::Standing => "standing",
            Stance::Falling => "falling",
            Stance::Down => "down",
            Stance::Rising => "rising",
        }
    }

    /// Whether the body is up and fighting.
    pub fn up(self) -> bool {
        self == Stance::Standing
    }
}

/// What the balance measured this tick.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BalanceState {
    /// The whole body's centre of mass, world.
    pub com: DVec3,
    /// Its velocity.
    pub com_velocity: DVec3,
    /// The capture point on the ground (B2).
    pub capture: DVec3,
    /// How far the capture point is outside the feet's polygon, m
    /// (negative: inside).
    pub outside: f64,
    /// The trunk's tilt from upright, rad.
    pub tilt: f64,
    /// The hips' height (the pelvis's centre), m.
    pub hips: f64,
    /// The head's angular speed, rad/s.
    pub head_speed: f64,
}

/// The balance controller's evolving state.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Balance {
    /// The state now.
    pub stance: Stance,
    /// When it began, s.
    since: f64,
    /// How long this knockdown keeps the body down, s.
    down_for: f64,
    /// Knockdowns and get-ups, counted.
    pub knockdowns: u32,
    /// Get-ups counted.
    pub get_ups: u32,
    /// Recovery steps taken (B4), counted.
    pub recovery_steps: u32,
    /// The recovery step under way: until when it swings.
    recovering_until: f64,
    /// Each ankle's distance from its planned place a tick ago.
    swing_err: [Option<Vec3>; 2],
    /// The last measurement.
    pub last: BalanceState,
    /// The planted soles' static friction (B1).
    pub grip: Grip,
    /// The motor noise's force now, x and z, N (B3).
    sway: [f64; 2],
    /// The hips' height goal, m: getting up, it moves toward the planned
    /// height at no more than `HIPS_SPEED` (B5), from where the hips were
    /// when the stance last changed.
    hips_goal: Option<f32>,
    /// Where a rise stands up: the centre of mass's ground point when it
    /// began (B5).
    rise_at: DVec3,
}

/// Gravity, m/s^2.
const G: f64 = 9.81;
/// The rise's help turning the pelvis and trunk upright (B5): stiffness
/// N m/rad, damping N m s/rad, and its largest, N m. Our calibration: at
/// 600 / 80 / 400 the trunk was whipped upright fast enough that the head
/// lagged past the neck's range (17 deg in a sparring soak) and the body
/// overshot and fell again; at 300 / 80 / 250, over six 3-minute
/// `soak --balanced` runs (seeds 1-6), 53 knockdowns instead of 127 and
/// the neck at most 13.6 deg past its range.
const UPRIGHT_KP: f32 = 300.0;
const UPRIGHT_KD: f32 = 80.0;
const UPRIGHT_MAX: f32 = 250.0;
/// How long a body that got up settles on its feet before it steps or
/// fights, s (our choice: a boxer up from a knockdown stands through the
/// rest of the count).
const SETTLE: f64 = 1.5;
/// A rise has stood up once the capture point is at most this far
/// outside the feet, m (within the margin that would make a recovery
/// step, `step_margin`'s default).
const RISEN: f64 = 0.03;
/// The rise's pull of the centre of mass over the feet (B5): stiffness
/// as a share of g per metre, and its largest, a share of the weight (our
/// calibration: a body up 0.4 m off its feet is carried over them within
/// the rise's time).
const OVER_FEET_K: f32 = 4.0;
const OVER_FEET_MAX: f32 = 0.5;

impl Balance {
    /// A fresh controller (a physics reset), its counts of knockdowns,
    /// get-ups and recovery steps running on (the soak reports them).
    pub fn restarted(&self) -> Balance {
        Balance {
            knockdowns: self.knockdowns,
            get_ups: self.get_ups,
            recovery_steps: self.recovery_steps,
            ..Balance::default()
        }
    }

    /// Measure the body: centre of mass, capture point, tilt, and how far
    /// the capture point is outside the planted feet's polygon.
    pub fn measure(world: &World, legs: &Legs) -> BalanceState {
        let phys = &world.phys;
        let (mut moment, mut momentum, mut mass) = legs.mass_moment(phys);
        for seg in world.vh_bodies() {
            let rb = world.rb(seg);
            moment += rb.center_of_mass() * rb.mass();
            momentum += rb.linvel() * rb.mass();
            mass += rb.mass();
        }
        let com = (moment / mass).as_dvec3();
        let v = (momentum / mass).as_dvec3();
        let w0 = (G / com.y.max(0.2)).sqrt();
        let capture = DVec3::new(com.x + v.x / w0, 0.0, com.z + v.z / w0);
        let trunk_up = *world.rb(Seg::Torso).rotation() * Vec3::Y;
        let tilt = f64::from(trunk_up.y.clamp(-1.0, 1.0).acos());
        let hips = f64::from(legs.rb(phys, Part::Pelvis).translation().y);
        // The support polygon: the soles of the feet on the canvas, as
        // their corners (the hull's distance is approximated by the
        // distance to the segment between the feet's centres, widened by
        // half a foot).
        let feet: Vec<(DVec3, f64)> = (0..2)
            .filter(|&k| legs.on_canvas(phys, Part::Foot(k)))
            .map(|k| legs.foot_ground(phys, k))
            .collect();
        let outside = match feet.as_slice() {
            [] => f64::INFINITY,
            [(a, _)] => (capture - a.with_y(0.0)).length() - 0.1,
            [(a, _), (b, _), ..] => {
                let (a, b) = (a.with_y(0.0), b.with_y(0.0));
                let ab = b - a;
                let u = ((capture - a).dot(ab) / ab.length_squared().max(1e-9)).clamp(0.0, 1.0);
                (capture - (a + ab * u)).length() - 0.1
            }
        };
        BalanceState {
            com,
            com_velocity: v,
            capture,
            outside,
            tilt,
            hips,
            head_speed: f64::from(world.rb(Seg::Head).angvel().length()),
        }
    }

    /// Advance the states (B5): `damage` (0-1) sets how long a knockdown
    /// keeps the body down. Returns `true` on the tick it is up again.
    pub fn update(&mut self, p: &BalanceParams, s: &BalanceState, damage: f64, t: f64) -> bool {
        self.last = *s;
        let since = t - self.since;
        let next = match self.stance {
            Stance::Standing
                if s.tilt > p.fall_tilt_deg.to_radians()
                    || s.hips < p.fall_height
                    || s.head_speed > p.stun_head_speed =>
            {
                self.knockdowns += 1;
                Some(Stance::Falling)
            }
            Stance::Falling if s.hips < 0.45 && s.com_velocity.length() < 0.3 || since > 2.0 => {
                self.down_for = p.down_time + p.down_per_damage * damage.clamp(0.0, 1.0);
                Some(Stance::Down)
            }
            Stance::Down if since > self.down_for => Some(Stance::Rising),
            Stance::Rising
                if since > p.rise_time && s.tilt < 0.5 && s.hips > 0.8 && s.outside < RISEN =>
            {
                self.get_ups += 1;
                Some(Stance::Standing)
            }
            // A rise that fails goes down again and tries once more.
            Stance::Rising if since > 3.0 * p.rise_time => Some(Stance::Down),
            _ => None,
        };
        if let Some(n) = next {
            self.stance = n;
            self.since = t;
            self.hips_goal = None;
            self.rise_at = s.com.with_y(0.0);
        }
        next == Some(Stance::Standing)
    }

    /// How the planned pelvis is sent this tick: within the leash of
    /// where the body is (the posture is re-planned from the body), and
    /// held where the body is through a recovery step (B4).
    pub fn steer(&self, p: &BalanceParams, planned: DVec3, body: DVec3, t: f64) -> DVec3 {
        if self.recovering(t) {
            return body.with_y(0.0);
        }
        let d = (planned - body).with_y(0.0);
        let d = d.clamp_length_max(p.leash);
        body.with_y(0.0) + d
    }

    /// Where the body stands up while rising: over the ground point its
    /// centre of mass had when the rise began, the feet gathered under it
    /// (B5).
    pub fn rise_at(&self) -> DVec3 {
        self.rise_at
    }

    /// Whether the body is settling on its feet after getting up: for
    /// `SETTLE` s it holds its weight over its feet where they are, and
    /// neither steps nor follows the plan (B5).
    pub fn settling(&self, t: f64) -> bool {
        self.stance == Stance::Standing && self.get_ups > 0 && t - self.since < SETTLE
    }

    /// Whether a recovery step is under way (B4).
    pub fn recovering(&self, t: f64) -> bool {
        t < self.recovering_until
    }

    /// A recovery step, if one is due (B4): the capture point outside the
    /// feet by more than `step_margin`, standing, no step under way. Of
    /// the two feet on the canvas at `feet` (ground points), the one the
    /// capture point loads less (of two loaded about evenly, the one whose
    /// step is shortest) goes to where the capture point will be when it
    /// lands after `step_time`, the other foot bearing the weight
    /// meanwhile, shifted to its own side of the body by `side[k]` (so
    /// the legs do not cross), no farther than `max_step` from where it
    /// is. Returns the foot and where it lands.
    pub fn recovery(
        &mut self,
        p: &BalanceParams,
        feet: [Option<DVec3>; 2],
        side: [DVec3; 2],
        step_time: f64,
        t: f64,
    ) -> Option<(usize, DVec3)> {
        let s = &self.last;
        if self.stance != Stance::Standing || self.recovering(t) || s.outside <= p.step_margin {
            return None;
        }
        let w0 = (G / s.com.y.max(0.2)).sqrt();
        let grow = (w0 * step_time).exp();
        let target = |k: usize| {
            let at = feet[k]?.with_y(0.0);
            let pivot = feet[1 - k].map_or(s.com.with_y(0.0), |f| f.with_y(0.0));
            let xi = pivot + (s.capture - pivot) * grow + side[k];
            Some(at + (xi - at).clamp_length_max(p.max_step))
        };
        // The foot the capture point loads less steps: a loaded foot
        // cannot leave the canvas (its swing would be called off, and the
        // other foot would be pushed from under the weight). Of two feet
        // loaded about evenly, the shorter step. (With one foot on the
        // canvas it is the only one that can step.)
        let load = shares(feet.map(|f| f.map(DVec3::as_vec3)), s.capture.as_vec3());
        let (k, to) = [0, 1]
            .into_iter()
            .filter_map(|k| target(k).map(|to| (k, to)))
            .min_by(|a, b| {
                let d = |(k, to): &(usize, DVec3)| (*to - feet[*k].unwrap_or(*to)).length();
                let (la, lb) = (load[a.0], load[b.0]);
                if (la - lb).abs() > EVEN_LOAD {
                    la.total_cmp(&lb)
                } else {
                    d(a).total_cmp(&d(b))
                }
            })?;
        self.recovering_until = t + step_time;
        self.recovery_steps += 1;
        Some((k, to))
    }

    /// Muscle tone now: 1 up, `down_tone` falling and down, a ramp back
    /// while rising.
    pub fn tone(&self, p: &BalanceParams, t: f64) -> f64 {
        match self.stance {
            Stance::Standing => 1.0,
            Stance::Falling | Stance::Down => p.down_tone,
            Stance::Rising => {
                let u = ((t - self.since) / (0.4 * p.rise_time)).clamp(0.0, 1.0);
                p.down_tone + (1.0 - p.down_tone) * u
            }
        }
    }

    /// The share of the rise's push still given (1 at the start, 0 by its
    /// end).
    fn push(&self, p: &BalanceParams, t: f64) -> f64 {
        if self.stance != Stance::Rising {
            return 0.0;
        }
        let mut u = (t - self.since) / p.rise_time;
        // Not let go of before the weight is over the feet.
        if self.last.outside >= RISEN {
            u = u.min(0.6);
        }
        (1.0 - (u - 0.6).max(0.0) / 0.4).clamp(0.0, 1.0)
    }

    /// Drive the lower body for one tick (B3): each joint's motor toward
    /// the posture `reference` plans, the stance legs' weight and the
    /// hanging parts' as feed-forward torques, and while rising the push
    /// that lifts the hips (B5).
    pub fn actuate(
        &mut self,
        world: &mut World,
        reference: &LowerBody,
        body: &BodyParams,
        t: f64,
        rng: &mut impl Rng,
    ) {
        let Some(legs) = world.legs.clone() else {
            return;
        };
        let p = &body.balance;
        let dt = world.dt as f32;
        let tone = self.tone(p, t) as f32;
        let planned = reference.legs(body);
        // Desired world rotations: the pelvis turned with the body, the
        // trunk as the waist law has it, each leg as posed.
        let pelvis_rot = Quat::from_rotation_y(reference.facing() as f32);
        let trunk_rot = reference.trunk_rotation().as_quat();
        let leg_rot = [0, 1].map(|k| legs.leg_rotations(k, &planned[k]));
        let total_mass = anthro::MASS as f32;
        let com = self.last.com.as_vec3();
        let up = matches!(self.stance, Stance::Standing | Stance::Rising);
        // A foot the plan swings carries no weight, whether or not it has
        // left the canvas yet: its leg lifts it.
        let on = [0, 1].map(|k| reference.planted(k) && legs.on_canvas(&world.phys, Part::Foot(k)));
        let shares = shares(
            [0, 1].map(|k| on[k].then(|| legs.foot_ground(&world.phys, k).0.as_vec3())),
            com,
        );
        // The planted soles hold where they stand (B1).
        let held = on.map(|o| o && self.stance == Stance::Standing);
        self.grip.hold(world, &legs, held);
        let weight = total_mass * G as f32;
        // The ground's push the stance legs ask for: the weight, and a
        // horizontal spring-damper on the centre of mass toward the
        // planned pelvis (the ankle strategy, B3).
        let planned_com = reference.pelvis().as_vec3();
        let v = self.last.com_velocity.as_vec3();
        // Through a recovery step the body is let fall toward where the
        // foot lands: no spring pulls it back (B4).
        let stiffness = if self.recovering(t) {
            0.0
        } else {
            p.com_stiffness
        };
        let k_com = stiffness as f32 * weight / com.y.max(0.3);
        let d_com = p.com_damping as f32 * 2.0 * (k_com * total_mass).sqrt();
        // Motor noise (B3): an Ornstein-Uhlenbeck force, what makes the
        // body sway.
        let decay = (-f64::from(dt) / p.sway_time).exp();
        let kick = p.sway_force * (1.0 - decay * decay).sqrt();
        for s in &mut self.sway {
            let n: f64 = StandardNormal.sample(rng);
            *s = *s * decay + kick * n;
        }
        let noise = Vec3::new(self.sway[0] as f32, 0.0, self.sway[1] as f32);
        let horizontal = (-(com - planned_com) * k_com - v * d_com).with_y(0.0) + noise;
        // ... and the hips held at their planned height.
        let pelvis_rb = legs.rb(&world.phys, Part::Pelvis);
        let planned_hips = 0.5 * (planned[0].hip.y + planned[1].hip.y) as f32;
        // Getting up, the hips rise at a person's pace (B5); standing,
        // they go where the plan puts them (a duck is quicker).
        let rising = self.stance == Stance::Rising || self.settling(t);
        let goal = self.hips_goal.get_or_insert(pelvis_rb.translation().y);
        *goal = if rising {
            *goal + (planned_hips - *goal).clamp(-HIPS_SPEED * dt, HIPS_SPEED * dt)
        } else {
            planned_hips
        };
        let hips = *goal;
        let k_h = 10.0 * weight;
        let vertical = k_h * (hips - pelvis_rb.translation().y)
            - 2.0 * (k_h * total_mass).sqrt() * pelvis_rb.linvel().y;
        let support = Vec3::Y * (weight + vertical.clamp(-0.5 * weight, weight))
            + horizontal.clamp_length_max(0.5 * weight);
        // The pelvis kept turned as planned, against the trunk's weight on
        // it: a moment the stance legs give (virtual model control: Pratt
        // et al. 2001, Int. J. Robot. Res. 20:129).
        let waist_pivot = legs.pivot(&world.phys, Joint::Waist);
        let mut turn_err = pelvis_rot * pelvis_rb.rotation().inverse();
        if turn_err.w < 0.0 {
            turn_err = -turn_err;
        }
        let moment = turn_err.to_scaled_axis() * PELVIS_KP - pelvis_rb.angvel() * PELVIS_KD
            + world.gravity_torque_about(Seg::Torso, waist_pivot, Vec3::ZERO);
        // Not about the vertical: a sole's friction holds little twist (the
        // feet spun on the canvas when asked to), so the hips' servos keep
        // the pelvis's heading.
        let moment = moment.with_y(0.0);
        let swing_force = [0, 1].map(|k| {
            let err = planned[k].ankle.as_vec3() - legs.pivot(&world.phys, Joint::Ankle(k));
            let last = self.swing_err[k].replace(err);
            (up && !reference.planted(k)).then(|| {
                let rate = last.map_or(Vec3::ZERO, |l| (err - l) / dt);
                (err * SWING_K + rate * SWING_D).clamp_length_max(SWING_MAX)
            })
        });
        let mut impulses = Vec::with_capacity(8);
        for j in Joint::ALL {
            let parent_des = match j.parent() {
                Part::Pelvis => pelvis_rot,
                Part::Thigh(k) => leg_rot[k][0],
                Part::Shank(k) => leg_rot[k][1],
                Part::Foot(k) => leg_rot[k][2],
            };
            let child_des = match j {
                Joint::Waist => trunk_rot,
                Joint::Hip(k) => leg_rot[k][0],
                Joint::Knee(k) => leg_rot[k][1],
                Joint::Ankle(k) => leg_rot[k][2],
            };
            let (gains, max) = match j {
                Joint::Waist => (&p.waist, body.waist_max_torque[1] as f32),
                Joint::Hip(_) => (&p.hip, MAX_HIP),
                Joint::Knee(_) => (&p.knee, MAX_KNEE),
                Joint::Ankle(_) => (&p.ankle, MAX_ANKLE),
            };
            let target = (parent_des.inverse() * child_des).normalize();
            // A stance leg's posture is held by the force it gives (below);
            // its joints' own servos keep only a share of their gains.
            let posture = 1.0 - 0.8 * j.leg().map_or(0.0, |k| shares[k]);
            let (kp, kd) = (
                gains.kp as f32 * tone * posture,
                gains.kd as f32 * tone * posture,
            );
            legs.drive(&mut world.phys, j, target, kp, kd, max * tone.max(0.05));
            if !up {
                continue;
            }
            // Feed-forward: a stance leg carries its share of the weight,
            // the ground's push under its foot (B3); the waist and a
            // swinging leg hold what hangs on them.
            let pivot = legs.pivot(&world.phys, j);
            let stance = j.leg().map_or(0.0, |k| shares[k]);
            let tau = if let (true, Some(k)) = (stance > 0.0, j.leg()) {
                // The leg's share of the weight, pushed up from under its
                // foot (the sole's centre): each joint holds its moment.
                let sole = legs.foot_ground(&world.phys, k).0.as_vec3();
                (pivot - sole).cross(support * stance) - moment * stance
            } else {
                let hang = match j {
                    Joint::Waist => world.gravity_torque_about(Seg::Torso, pivot, Vec3::ZERO),
                    _ => hang_torque(&legs, &world.phys, j.distal(), pivot),
                };
                // A swinging foot is carried along its path by a force at
                // the ankle, given by the hip and knee (J^T F).
                match (j, swing_force[j.leg().unwrap_or(0)]) {
                    (Joint::Hip(k) | Joint::Knee(k), Some(f)) => {
                        let ankle = legs.pivot(&world.phys, Joint::Ankle(k));
                        hang + (ankle - pivot).cross(f)
                    }
                    _ => hang,
                }
            }
            .clamp_length_max(max);
            let child_h = j.child().map_or(legs.trunk, |c| legs.handles[c.index()]);
            impulses.push((legs.handles[j.parent().index()], child_h, tau * dt));
        }
        let push = self.push(p, t) as f32;
        let lift = (push > 0.0).then(|| {
            // The rise's help (B5): the hips lifted to standing height and
            // the pelvis and trunk turned upright, as the arms pushing off
            // the canvas and then the knees would.
            let phys = &world.phys;
            let pelvis = legs.rb(phys, Part::Pelvis);
            let err = hips - pelvis.translation().y;
            let f = (weight * (1.0 + 4.0 * err) - 2.0 * total_mass * pelvis.linvel().y)
                .clamp(0.0, p.rise_push as f32 * weight);
            let upright = |rb: &rapier3d::prelude::RigidBody, want: Quat| {
                let mut e = want * rb.rotation().inverse();
                if e.w < 0.0 {
                    e = -e;
                }
                (e.to_scaled_axis() * UPRIGHT_KP - rb.angvel() * UPRIGHT_KD)
                    .clamp_length_max(UPRIGHT_MAX)
            };
            // ... and the weight carried over the feet, as the hands and
            // knees push the body forward onto them: a critically damped
            // pull of the centre of mass toward the feet's midpoint.
            let (sum, n) = (0..2)
                .filter(|&k| legs.on_canvas(phys, Part::Foot(k)))
                .fold((Vec3::ZERO, 0.0), |(sum, n), k| {
                    (sum + legs.foot_ground(phys, k).0.as_vec3(), n + 1.0)
                });
            let over = if n == 0.0 {
                Vec3::ZERO
            } else {
                let mid = sum / n;
                let k = G as f32 * OVER_FEET_K;
                (((mid - com) * k - v * 2.0 * k.sqrt()) * total_mass)
                    .with_y(0.0)
                    .clamp_length_max(OVER_FEET_MAX * weight)
            };
            let trunk = &phys.bodies[legs.trunk];
            (
                (Vec3::Y * f + over) * push,
                upright(pelvis, pelvis_rot) * push,
                upright(trunk, trunk_rot) * push,
            )
        });
        for (ph, ch, imp) in impulses {
            world.torque_impulse(ch, imp);
            world.torque_impulse(ph, -imp);
        }
        if let Some((force, pelvis_torque, trunk_torque)) = lift {
            let pelvis_h = legs.handles[Part::Pelvis.index()];
            world.impulse(pelvis_h, force * dt);
            world.torque_impulse(pelvis_h, pelvis_torque * dt);
            world.torque_impulse(legs.trunk, trunk_torque * dt);
        }
    }
}

/// Strongest joint torques, N m: ankle plantarflexion about 150-250 in
/// young men (Anderson, Madigan & Nussbaum 2007, J. Biomech. 40:3105),
/// knee extension and hip extension about 250-300 (same source).
const MAX_ANKLE: f32 = 200.0;
/// The fastest the hips' height goal moves, m/s: rising from the canvas
/// or a crouch (our choice, near the centre of mass's peak vertical speed
/// standing up from a chair, about 0.5-0.6 m/s).
const HIPS_SPEED: f32 = 0.6;
/// The pelvis's turn held by the stance legs: stiffness N m/rad and
/// damping N m s/rad (our calibration: the trunk and pelvis, about 4 kg
/// m^2, at about 20 rad/s).
const PELVIS_KP: f32 = 1600.0;
const PELVIS_KD: f32 = 160.0;
const MAX_KNEE: f32 = 300.0;
/// The swinging foot's carrying force toward its planned path (B4):
/// stiffness N/m, damping N s/m (on the error's rate), and its largest, N
/// (our calibration: a 12 kg leg tracks a 0.25 s step within about 5 cm,
/// where the joints' servos alone lagged 15 cm).
const SWING_K: f32 = 3000.0;
const SWING_D: f32 = 300.0;
const SWING_MAX: f32 = 500.0;
const MAX_HIP: f32 = 300.0;

/// Two feet whose shares of the capture point's weight differ by less
/// than this are loaded evenly; the shorter recovery step is taken (our
/// choice).
const EVEN_LOAD: f32 = 0.1;

/// The feet's shares of the weight, given the ground points of the feet
/// that carry it (`None`: off the canvas, or not standing): by where
/// `weight` lies between two feet; one foot carries it all.
pub fn shares(feet: [Option<Vec3>; 2], weight: Vec3) -> [f32; 2] {
    match feet {
        [Some(a), Some(b)] => share_between(a, b, weight),
        [Some(_), None] => [1.0, 0.0],
        [None, Some(_)] => [0.0, 1.0],
        [None, None] => [0.0, 0.0],
    }
}

/// Two feet's shares of the weight (ground points `a`, `b`) from where
/// `weight` (the centre of mass, or the capture point) lies between them
/// on the canvas: its place along the line from one foot to the other.
pub fn share_between(a: Vec3, b: Vec3, weight: Vec3) -> [f32; 2] {
    let (a, b) = (a.with_y(0.0), b.with_y(0.0));
    let ab = b - a;
    let u = ((weight.with_y(0.0) - a).dot(ab) / ab.length_squared().max(1e-6)).clamp(0.0, 1.0);
    [1.0 - u, u]
}

/// The torque that holds `parts` (hanging from `pivot`) against gravity.
fn hang_torque(
    legs: &Legs,
    phys: &rapier3d::prelude::PhysicsWorld,
    parts: &[Part],
    pivot: Vec3,
) -> Vec3 {
    let mut tau = Vec3::ZERO;
    for &part in parts {
        let rb = legs.rb(phys, part);
        tau -= (rb.center_of_mass() - pivot).cross(phys.gravity * rb.mass());
    }
    tau
}
