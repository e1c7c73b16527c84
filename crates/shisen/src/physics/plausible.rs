//! Whether PD gains are plausible for the body: each joint group's
//! natural frequency and damping rate on its effective inertia, within
//! what the 1 kHz step can integrate. The inertias come from the default
//! body plan's mass properties, computed once.

use glam::Vec3;

use crate::physics::body::{BodyPlan, Group};
use crate::physics::control::Gains;
use crate::physics::world::World;

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
    all[group.index()]
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
/// computed in single precision, and rapier blows up. The gains file's
/// schema bounds every group's gains by the stiffest group's limits
/// ([`crate::physics::control::JointGains`]); this check, which depends
/// on the group's inertia, is each group's own.
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
