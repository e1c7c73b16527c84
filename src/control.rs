//! PD joint control: the gains file and the one PD law every VH joint uses.
//!
//! ## Why explicit torques, not rapier's joint motors
//! Measured on this stack (rust-stack notes, and `tests/joints.rs`):
//! rapier's default acceleration-based motors scale stiffness by the body's
//! inertia about its own centre of mass rather than the pivot, so a
//! motor-held head sagged ~26 deg under gravity, and spherical-joint motors
//! drive `2 asin(q.imag)` per axis rather than our yaw/pitch/roll. Explicit
//! torques let us write the law once, in physical units, with gravity
//! compensation and an inertia feed-forward of the planned acceleration,
//! and apply the reaction to the parent (so a saccade really pushes the
//! head). Their cost is an explicit-integration stability bound: with a
//! 7.5 g eyeball (I = 3.6e-7 kg m^2) and omega_n = 300 rad/s the step must
//! satisfy omega_n dt << 1: unstable at 60 Hz, comfortable at the 1 kHz
//! control rate we run (omega_n dt = 0.3, 2 zeta omega_n dt = 0.6 < 2).

use std::path::Path;

use glam::{Mat3, Quat, Vec3};
use serde::{Deserialize, Serialize};

use crate::body::Group;
use crate::scene::{LoadError, parse_ron};

/// Gains of one joint group, in physical units.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JointGains {
    /// Proportional gain, N m / rad.
    #[serde(deserialize_with = "crate::check::non_negative")]
    pub kp: f64,
    /// Derivative gain, N m s / rad.
    #[serde(deserialize_with = "crate::check::non_negative")]
    pub kd: f64,
    /// Scale of the inertia feed-forward of the planned acceleration (0 = pure PD).
    #[serde(default = "one", deserialize_with = "crate::check::unit_interval")]
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
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
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
pub const DEFAULT_GAINS_RON: &str = include_str!("../scenes/gains/default.ron");

impl Default for Gains {
    fn default() -> Self {
        parse_ron(DEFAULT_GAINS_RON, Path::new("<embedded gains>"))
            .expect("embedded default gains parse")
    }
}

impl Gains {
    /// Load a gains file, validating every number.
    pub fn load(path: &Path) -> Result<Gains, LoadError> {
        let text = std::fs::read_to_string(path).map_err(|e| LoadError::Io {
            file: path.display().to_string(),
            source: e,
        })?;
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

/// Whether explicit PD torques with these gains are stable on an inertia
/// `inertia` (kg m^2) at step `dt`: for the semi-implicit Euler that rapier
/// integrates, x'' = -(kp x + kd x') / I is stable when
/// `kp dt^2 / I + 2 kd dt / I < 4`.
pub fn explicit_stable(g: &JointGains, inertia: f64, dt: f64) -> bool {
    g.kp * dt * dt / inertia + 2.0 * g.kd * dt / inertia < 4.0
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
/// receives its negative).
///
/// `tau = kp * e + kd * (w_ref - w) + ff * I * a_ref`, where `e` is the
/// rotation vector taking the current relative rotation to the target.
/// Gravity compensation is added by the caller ([`crate::world`]), which
/// knows the subtree masses.
pub fn pd_torque(g: &JointGains, target: &JointTarget, s: &JointState) -> Vec3 {
    let q_rel = s.parent_rot.inverse() * s.child_rot;
    let mut q_err = target.rotation * q_rel.inverse();
    if q_err.w < 0.0 {
        q_err = -q_err; // shortest way round
    }
    let e = s.parent_rot * q_err.to_scaled_axis();
    let w_ref = s.parent_rot * target.velocity;
    let a_ref = s.parent_rot * target.acceleration;
    let kp = g.kp as f32;
    let kd = g.kd as f32;
    let ff = g.feedforward as f32;
    kp * e + kd * (w_ref - s.rel_angvel) + ff * (s.inertia * a_ref)
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
        let tau = pd_torque(&g, &target, &s);
        // the error axis is the parent's Y axis, expressed in world
        let axis = Quat::from_rotation_x(0.3) * Vec3::Y;
        assert!((tau - axis * 2.0).length() < 1e-5, "{tau}");
        let moving = JointState {
            rel_angvel: Vec3::X,
            child_rot: s.parent_rot * target.rotation,
            ..s
        };
        let tau = pd_torque(&g, &target, &moving);
        assert!(
            (tau + Vec3::X).length() < 1e-5,
            "pure damping at target: {tau}"
        );
    }

    #[test]
    fn stability_bound_separates_60hz_from_1khz_for_the_eye() {
        // The default eye gains (omega_n 300 rad/s, zeta 1) on a 7.5 g eyeball.
        let g = Gains::default().eye;
        let i = 0.4 * 0.0075 * 0.011 * 0.011;
        assert!(explicit_stable(&g, i, 0.001));
        assert!(!explicit_stable(&g, i, 1.0 / 60.0));
    }

    #[test]
    fn default_gains_load() {
        let g = Gains::default();
        assert!(g.eye.kp > 0.0 && g.neck.kd > 0.0);
    }
}
