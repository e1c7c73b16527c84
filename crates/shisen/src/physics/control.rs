//! PD joint control: the gains file and the one PD law every VH joint uses.
//!
//! ## Why our own torques, not rapier's joint motors
//! Measured on this stack (rust-stack notes): rapier's default
//! acceleration-based motors scale stiffness by the body's inertia about
//! its own centre of mass rather than the pivot, so a motor-held head
//! sagged ~26 deg under gravity, and spherical-joint motors drive
//! `2 asin(q.imag)` per axis rather than our yaw/pitch/roll. Torques we
//! compute let us write the law once, in physical units, with gravity
//! compensation and an inertia feed-forward of the planned acceleration,
//! and apply the reaction to the parent (so a saccade really pushes the
//! head).
//!
//! ## Why the stable (semi-implicit) form
//! Plain explicit PD torques have a stability bound, `kp dt^2/I + 2 kd
//! dt/I < 4` per axis. At our 1 kHz step the 7.5 g eyeball is fine
//! (omega_n dt = 0.3) but a ball joint also has a *twist* axis of tiny
//! inertia (an arm about its own length, ~2e-3 kg m^2) on which the same
//! damping gives `2 kd dt / I` of about 12: a 30 s random sparring soak blew
//! the arm up. We therefore use stable PD (Tan, Liu & Turk 2011): the
//! spring acts on the error predicted one step ahead and the damping is
//! solved implicitly against the joint subtree's inertia tensor,
//! `tau = I (I + kd dt)^-1 [kp (e + dt w_err) + kd w_err] + ff I a_ref`,
//! which is stable for any non-negative gains and step and equals plain PD
//! as dt -> 0.

use std::path::Path;

use glam::{DVec2, Mat3, Quat, Vec3};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::physics::body::{Group, Limits};
use shisen_gaze::util::math::JointAngles;
use shisen_gaze::util::ron::{LoadError, parse_ron};

/// Gains of one joint group, in physical units.
///
/// The schema's bounds are those of the stiffest group (the shoulder,
/// about 0.25 kg m^2 about its pivot) at the fastest the 1 kHz step can
/// integrate (natural frequency 1000 rad/s, damping rate 2000 1/s); each
/// group's own, smaller limits follow from its inertia
/// ([`crate::physics::plausible::check_gains`]: the eye's kp at most
/// about 0.36).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct JointGains {
    /// Proportional gain, N m / rad (0-250000: the shoulder's 0.25 kg m^2
    /// at 1000 rad/s; the shipped gains are 0.03 for the eye to 305 for
    /// the neck).
    #[schemars(range(min = 0.0, max = 250_000.0))]
    pub kp: f64,
    /// Derivative gain, N m s / rad (0-500: the shoulder's 0.25 kg m^2 at
    /// a damping rate of 2000 1/s; shipped 0.0002-15).
    #[schemars(range(min = 0.0, max = 500.0))]
    pub kd: f64,
    /// Scale of the inertia feed-forward of the planned acceleration, 0-1
    /// (0 = pure PD, 1 = the whole planned torque).
    #[serde(default = "one")]
    #[schemars(range(min = 0.0, max = 1.0))]
    pub feedforward: f64,
}

fn one() -> f64 {
    1.0
}

impl JointGains {
    /// Critically damped gains for natural frequency `omega` (rad/s) on an
    /// effective inertia `inertia` (kg m^2): kp = I w^2, kd = 2 zeta I w.
    pub fn from_bandwidth(inertia: f64, omega: f64, zeta: f64) -> Self {
        JointGains {
            kp: inertia * omega * omega,
            kd: 2.0 * zeta * inertia * omega,
            feedforward: 1.0,
        }
    }
}

/// Gains per joint group (the gains file, RON). Replaceable while running.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Gains {
    /// Eyeballs (2-DOF; torsion held at zero).
    pub eye: JointGains,
    /// Neck (yaw, pitch, roll).
    pub neck: JointGains,
    /// Shoulders (3-DOF).
    pub shoulder: JointGains,
    /// Elbows (hinge).
    pub elbow: JointGains,
    /// Add the static gravity torque of each joint's subtree (tonic muscle activity).
    #[serde(default = "yes")]
    pub gravity_compensation: bool,
}

fn yes() -> bool {
    true
}

/// The default gains file, embedded (also shipped as `scenes/gains/default.ron`).
pub const DEFAULT_GAINS_RON: &str = include_str!("../../../../scenes/gains/default.ron");

impl Default for Gains {
    fn default() -> Self {
        parse_ron(DEFAULT_GAINS_RON, Path::new("<embedded gains>"))
            .expect("embedded default gains parse")
    }
}

impl Gains {
    /// Load a gains file, validating every number.
    pub fn load(path: &Path) -> Result<Gains, LoadError> {
        let text = shisen_gaze::util::ron::read_text(path)?;
        parse_ron(&text, path)
    }

    /// Gains of one group.
    pub fn group(&self, g: Group) -> &JointGains {
        match g {
            Group::Eye => &self.eye,
            Group::Neck => &self.neck,
            Group::Shoulder => &self.shoulder,
            Group::Elbow => &self.elbow,
        }
    }

    /// Mutable gains of one group (tuning).
    pub fn group_mut(&mut self, g: Group) -> &mut JointGains {
        match g {
            Group::Eye => &mut self.eye,
            Group::Neck => &mut self.neck,
            Group::Shoulder => &mut self.shoulder,
            Group::Elbow => &mut self.elbow,
        }
    }
}

/// What a joint is asked to do this tick, relative to its parent.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointTarget {
    /// Target rotation of the child relative to the parent (from rest).
    pub rotation: Quat,
    /// Target relative angular velocity, parent frame (rad/s).
    pub velocity: Vec3,
    /// Target relative angular acceleration, parent frame (rad/s^2).
    pub acceleration: Vec3,
}

impl JointTarget {
    /// The target of a yaw/pitch joint (eye, neck; roll zero) moving at
    /// `angles` (rad) with `rates` and `accel`: rotation `Ry(yaw) Rx(-pitch)`
    /// and the matching angular velocity and acceleration in the parent
    /// frame (yaw about +Y, pitch about the yawed -X axis; the
    /// velocity-product term of the acceleration is neglected).
    pub fn yaw_pitch(angles: DVec2, rates: DVec2, accel: DVec2) -> JointTarget {
        let q = JointAngles {
            yaw: angles.x,
            pitch: angles.y,
            roll: 0.0,
        }
        .to_quat();
        let pitch_axis = Quat::from_rotation_y(angles.x as f32) * Vec3::NEG_X;
        let w = |v: DVec2| Vec3::Y * v.x as f32 + pitch_axis * v.y as f32;
        JointTarget {
            rotation: q,
            velocity: w(rates),
            acceleration: w(accel),
        }
    }
}

impl Default for JointTarget {
    fn default() -> Self {
        JointTarget {
            rotation: Quat::IDENTITY,
            velocity: Vec3::ZERO,
            acceleration: Vec3::ZERO,
        }
    }
}

/// Measured state of a joint, world frame.
#[derive(Clone, Copy, Debug)]
pub struct JointState {
    /// Parent's world rotation.
    pub parent_rot: Quat,
    /// Child's world rotation.
    pub child_rot: Quat,
    /// Child minus parent angular velocity, world frame.
    pub rel_angvel: Vec3,
    /// Inertia tensor of the child's subtree about the pivot, world frame.
    pub inertia: Mat3,
}

/// The PD law, in one place: world-frame torque on the child (the parent
/// receives its negative), in the stable-PD form described in the module
/// docs, for a step of `dt` seconds:
///
/// `tau = I (I + kd dt)^-1 [kp (e + dt w_err) + kd w_err] + ff I a_ref`,
///
/// where `e` is the rotation vector taking the current relative rotation to
/// the target, `w_err = w_ref - w` and `I` the subtree's inertia about the
/// pivot. Gravity compensation is added by the caller ([`crate::physics::world`]),
/// which knows the subtree masses.
pub fn pd_torque(g: &JointGains, target: &JointTarget, s: &JointState, dt: f32) -> Vec3 {
    pd_feedback(g, target, s, dt) + feedforward(g, target, s)
}

/// The feedback part of [`pd_torque`]: the stable-PD spring and damper,
/// `I (I + kd dt)^-1 [kp (e + dt w_err) + kd w_err]`, world frame.
pub fn pd_feedback(g: &JointGains, target: &JointTarget, s: &JointState, dt: f32) -> Vec3 {
    let (e, w_err) = joint_errors(target, s);
    let kp = g.kp as f32;
    let kd = g.kd as f32;
    let pd = kp * (e + dt * w_err) + kd * w_err;
    let implicit = s.inertia + Mat3::from_diagonal(Vec3::splat(kd * dt));
    if implicit.determinant().abs() > f32::MIN_POSITIVE {
        s.inertia * (implicit.inverse() * pd)
    } else {
        pd // no inertia to speak of: plain PD
    }
}

/// The joint's errors, world frame: the rotation vector taking the
/// child's relative rotation to the target's (the shortest way round),
/// and the target's relative angular velocity minus the child's.
pub fn joint_errors(target: &JointTarget, s: &JointState) -> (Vec3, Vec3) {
    let q_rel = s.parent_rot.inverse() * s.child_rot;
    let mut q_err = target.rotation * q_rel.inverse();
    if q_err.w < 0.0 {
        q_err = -q_err; // shortest way round
    }
    let e = s.parent_rot * q_err.to_scaled_axis();
    let w_err = s.parent_rot * target.velocity - s.rel_angvel;
    (e, w_err)
}

/// How much stiffer than the joint's own PD the soft limit past its range
/// is (spring and damper alike). It stands for the ligaments and capsule
/// that stop a joint beyond its active range; it is a model of their
/// effect (an excursion that stays within a few degrees under a blow), not
/// a measured tissue stiffness.
pub const END_RANGE_FACTOR: f64 = 10.0;

/// The soft limit of a joint with `limits` (degrees): past its range, a
/// spring-damper [`END_RANGE_FACTOR`] times the group's gains, along the
/// axis that leads back to the nearest angle inside only (the joint's own
/// motion within its range is untouched), in the stable-PD form of
/// [`pd_feedback`] on the inertia about that axis. World-frame torque on
/// the child; zero inside the range.
pub fn end_range_torque(g: &JointGains, limits: &Limits, s: &JointState, dt: f32) -> Vec3 {
    let a = JointAngles::from_quat(s.parent_rot.inverse() * s.child_rot);
    let clamp =
        |v: f64, r: [f32; 2]| v.clamp(f64::from(r[0]).to_radians(), f64::from(r[1]).to_radians());
    let inside = JointAngles {
        yaw: clamp(a.yaw, limits.yaw),
        pitch: clamp(a.pitch, limits.pitch),
        // A joint with no roll range (the eyes: torsion is the PD's to
        // hold at zero) has no roll stop.
        roll: if limits.roll[0] < limits.roll[1] {
            clamp(a.roll, limits.roll)
        } else {
            a.roll
        },
    };
    if inside == a {
        return Vec3::ZERO;
    }
    let target = JointTarget {
        rotation: inside.to_quat(),
        ..JointTarget::default()
    };
    let (e, _) = joint_errors(&target, s);
    let angle = e.length();
    if angle <= f32::EPSILON {
        return Vec3::ZERO;
    }
    let axis = e / angle;
    let (k, c) = (
        (g.kp * END_RANGE_FACTOR) as f32,
        (g.kd * END_RANGE_FACTOR) as f32,
    );
    // Speed back toward the range (negative: still going out).
    let w = s.rel_angvel.dot(axis);
    let inertia = axis.dot(s.inertia * axis);
    let pd = k * (angle - dt * w) - c * w;
    let implicit = inertia + c * dt;
    if inertia > f32::MIN_POSITIVE && implicit > f32::MIN_POSITIVE {
        axis * (inertia / implicit * pd)
    } else {
        axis * pd
    }
}

/// The feed-forward part of [`pd_torque`]: `ff I a_ref`, world frame.
pub fn feedforward(g: &JointGains, target: &JointTarget, s: &JointState) -> Vec3 {
    g.feedforward as f32 * (s.inertia * (s.parent_rot * target.acceleration))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bandwidth_gains_are_critically_damped() {
        let g = JointGains::from_bandwidth(2.0, 10.0, 1.0);
        assert_eq!(g.kp, 200.0);
        assert_eq!(g.kd, 40.0);
        // zeta = kd / (2 sqrt(kp I))
        assert!((g.kd / (2.0 * (g.kp * 2.0f64).sqrt()) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn pd_torque_points_toward_target_and_damps() {
        let g = JointGains {
            kp: 10.0,
            kd: 1.0,
            feedforward: 0.0,
        };
        let target = JointTarget {
            rotation: Quat::from_rotation_y(0.2),
            ..Default::default()
        };
        let s = JointState {
            parent_rot: Quat::from_rotation_x(0.3),
            child_rot: Quat::from_rotation_x(0.3),
            rel_angvel: Vec3::ZERO,
            inertia: Mat3::IDENTITY,
        };
        // dt = 0: the stable form reduces to plain PD
        let tau = pd_torque(&g, &target, &s, 0.0);
        // the error axis is the parent's Y axis, expressed in world
        let axis = Quat::from_rotation_x(0.3) * Vec3::Y;
        assert!((tau - axis * 2.0).length() < 1e-5, "{tau}");
        let moving = JointState {
            rel_angvel: Vec3::X,
            child_rot: s.parent_rot * target.rotation,
            ..s
        };
        let tau = pd_torque(&g, &target, &moving, 0.0);
        assert!(
            (tau + Vec3::X).length() < 1e-5,
            "pure damping at target: {tau}"
        );
    }

    #[test]
    fn the_soft_limit_acts_only_past_the_range_and_pulls_back_inside() {
        let g = JointGains {
            kp: 10.0,
            kd: 1.0,
            feedforward: 0.0,
        };
        let limits = Limits {
            yaw: [-40.0, 40.0],
            pitch: [-30.0, 30.0],
            roll: [-10.0, 10.0],
        };
        let at = |yaw_deg: f32| JointState {
            parent_rot: Quat::IDENTITY,
            child_rot: Quat::from_rotation_y(yaw_deg.to_radians()),
            rel_angvel: Vec3::ZERO,
            inertia: Mat3::IDENTITY,
        };
        assert_eq!(end_range_torque(&g, &limits, &at(39.0), 0.0), Vec3::ZERO);
        // 5 deg past the left stop: back toward it, ten times the PD's pull.
        let tau = end_range_torque(&g, &limits, &at(45.0), 0.0);
        let expected = -Vec3::Y * (10.0 * 10.0 * 5f32.to_radians());
        assert!((tau - expected).length() < 1e-3, "{tau} vs {expected}");
        let tau = end_range_torque(&g, &limits, &at(-45.0), 0.0);
        assert!(tau.y > 0.0 && tau.x.abs() < 1e-6, "{tau}");
    }

    #[test]
    fn stable_pd_stays_stable_where_explicit_pd_explodes() {
        // A stiff, heavily damped joint on a small inertia at 60 Hz:
        // 2 kd dt / I = 33 (explicit PD diverges at once).
        let g = JointGains {
            kp: 2.0,
            kd: 0.1,
            feedforward: 0.0,
        };
        let inertia = 1e-4f32;
        let dt = 1.0 / 60.0f32;
        let target = JointTarget::default();
        let (mut angle, mut w) = (0.5f32, 0.0f32);
        let (mut ex_angle, mut ex_w) = (0.5f32, 0.0f32);
        for _ in 0..200 {
            let s = JointState {
                parent_rot: Quat::IDENTITY,
                child_rot: Quat::from_rotation_z(angle),
                rel_angvel: Vec3::Z * w,
                inertia: Mat3::from_diagonal(Vec3::splat(inertia)),
            };
            w += pd_torque(&g, &target, &s, dt).z / inertia * dt;
            angle += w * dt;
            // explicit PD on the same joint
            ex_w += (-(g.kp as f32) * ex_angle - g.kd as f32 * ex_w) / inertia * dt;
            ex_angle += ex_w * dt;
        }
        assert!(angle.abs() < 1e-3, "stable PD settles: {angle}");
        assert!(
            ex_angle.is_nan() || ex_angle.abs() > 1.0,
            "explicit PD diverges: {ex_angle}"
        );
    }

    #[test]
    fn default_gains_load() {
        let g = Gains::default();
        assert!(g.eye.kp > 0.0 && g.neck.kd > 0.0);
    }

    /// Gains past what the step can integrate, or negative, are refused
    /// where they are written.
    #[test]
    fn gains_out_of_range_are_refused() {
        for (from, to, field) in [
            ("kp: 305.45", "kp: 1e300", "neck.kp"),
            ("kd: 12.402", "kd: -1.0", "shoulder.kd"),
            (
                "feedforward: 1.0),\n    elbow",
                "feedforward: 2.0),\n    elbow",
                "shoulder.feedforward",
            ),
        ] {
            let text = DEFAULT_GAINS_RON.replacen(from, to, 1);
            assert_ne!(text, DEFAULT_GAINS_RON, "{from}");
            let e = parse_ron::<Gains>(&text, Path::new("g.ron"))
                .unwrap_err()
                .to_string();
            assert!(e.contains(field), "{field}: {e}");
        }
    }
}
