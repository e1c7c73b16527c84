//! The opponent avatar's physical description: its parts' masses and the
//! bounded spring-damper that drives them toward their scripted (or live)
//! targets, so a punch that lands transfers momentum and a blocked glove
//! pushes with a finite force. The world builds the parts from it
//! ([`crate::physics::world::World::new`]) and applies the drive
//! ([`crate::physics::world::World::drive`]).

use glam::Vec3;

/// Masses of the opponent's head, gloves and trunk, kg, in
/// [`crate::physics::body::OpponentPart`] order. A glove carries the
/// effective mass of the arm and body behind the punch: 2.9 kg, the mean
/// of Olympic boxers' straight punches (2.9 +- 2.0 kg, Walilko, Viano &
/// Bir 2005, Br. J. Sports Med. 39:710), so a 7 m/s jab stopped by a head
/// delivers 10-20 N s as theirs did. The trunk, which a body shot meets,
/// is the thorax and abdomen, 0.355 of a 75 kg body (Dempster's segment
/// fractions, in Winter 2009, Biomechanics and Motor Control of Human
/// Movement, table 4.1).
pub const OPPONENT_MASS: [f32; 4] = [5.0, 2.9, 2.9, 27.0];
/// Drive of the opponent's parts, per kg: natural frequency 40 rad/s,
/// critically damped (k = w^2, c = 2 w). A free glove tracks a 0.2 s
/// punch closely; a blocked one pushes with at most about k x.
const DRIVE_STIFFNESS: f32 = 1600.0;
const DRIVE_DAMPING: f32 = 80.0;
/// The drive's force is capped at this acceleration of the part's mass,
/// m/s^2 (40 g; a fast punch's glove peaks near 16 g on a minimum-jerk
/// path). A scripted path that turns abruptly (a new move while the glove
/// is moving) differentiates to accelerations of 10^4 m/s^2; uncapped, that
/// feed-forward flung an opponent glove into the VH's at 40 m/s in one
/// step (the long soaks' arm blow-ups).
pub const DRIVE_MAX_ACCEL: f32 = 400.0;

/// A driven part's state and its target's: the part's mass, position
/// and velocity, and where its path is, how fast and how fast speeding up.
#[derive(Clone, Copy, Debug)]
pub struct DriveState {
    /// The part's mass, kg.
    pub mass: f32,
    /// The part's position and velocity now.
    pub at: (Vec3, Vec3),
    /// The target's position, velocity and acceleration.
    pub target: (Vec3, Vec3, Vec3),
}

/// The impulse over a step of `dt` s that drives a part toward its
/// target: a spring-damper with feed-forward,
/// `F = m a + c (v - v_b) + k (p - p_b)`, its force capped at
/// [`DRIVE_MAX_ACCEL`] times the mass.
pub fn drive_impulse(s: &DriveState, dt: f32) -> Vec3 {
    let m = s.mass;
    let (k, c) = (DRIVE_STIFFNESS * m, DRIVE_DAMPING * m);
    let (p, v, a) = s.target;
    let f = m * a + c * (v - s.at.1) + k * (p - s.at.0);
    f.clamp_length_max(m * DRIVE_MAX_ACCEL) * dt
}

#[cfg(test)]
mod tests {
    use super::*;

    /// However abrupt the scripted path, a driven part gains at most
    /// `DRIVE_MAX_ACCEL dt` of speed in a step; a gentle one is not capped.
    #[test]
    fn the_drive_force_is_capped() {
        let s = DriveState {
            mass: 1.5,
            at: (Vec3::ZERO, Vec3::ZERO),
            target: (Vec3::X * 0.05, Vec3::X * 50.0, Vec3::X * 1e5),
        };
        let dv = drive_impulse(&s, 0.001).length() / s.mass;
        assert!((dv - DRIVE_MAX_ACCEL * 0.001).abs() < 1e-6, "{dv}");
        let gentle = DriveState {
            target: (Vec3::X * 0.001, Vec3::ZERO, Vec3::ZERO),
            ..s
        };
        let dv = drive_impulse(&gentle, 0.001).length() / s.mass;
        assert!((dv - 1600.0 * 0.001 * 0.001).abs() < 1e-7, "{dv}");
    }
}
