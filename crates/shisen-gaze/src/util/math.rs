//! Small shared numerical pieces used by several laws.
//!
//! The minimum-jerk polynomial appears in the saccade (gaze.md M2), the
//! head sub-target (M9) and the arm reaches (boxing.md); it lives here once.

/// Minimum-jerk position profile on normalised time `s` in [0, 1]:
/// `f(s) = 6 s^5 - 15 s^4 + 10 s^3` (gaze.md M2, M9). Clamped outside [0, 1].
pub fn min_jerk(s: f64) -> f64 {
    let s = s.clamp(0.0, 1.0);
    s * s * s * (10.0 + s * (-15.0 + 6.0 * s))
}

/// Peak of [`min_jerk_d`] (at `s = 1/2`): a minimum-jerk move of amplitude
/// `A` and duration `T` peaks at `1.875 A / T` (gaze.md M3, M9).
pub const MIN_JERK_PEAK: f64 = 1.875;

/// First derivative of [`min_jerk`] with respect to `s`: `30 s^4 - 60 s^3 + 30 s^2`.
/// Zero outside [0, 1]. Its peak, at `s = 1/2`, is 1.875.
pub fn min_jerk_d(s: f64) -> f64 {
    if !(0.0..=1.0).contains(&s) {
        return 0.0;
    }
    30.0 * s * s * (s - 1.0) * (s - 1.0)
}

/// Second derivative of [`min_jerk`] with respect to `s`: `120 s^3 - 180 s^2 + 60 s`.
/// Zero outside [0, 1].
pub fn min_jerk_dd(s: f64) -> f64 {
    if !(0.0..=1.0).contains(&s) {
        return 0.0;
    }
    60.0 * s * (2.0 * s - 1.0) * (s - 1.0)
}

use glam::DVec3;

/// Unit direction for a yaw/pitch pair in the head (or eye-socket) frame.
///
/// Frame convention used throughout shisen: +Z forward, +Y up, +X to the
/// agent's left. Yaw is positive to the left (about +Y), pitch positive up
/// (gaze.md, "Angles"). This is Fick's gimbal: yaw outer, pitch inner.
pub fn dir_from_yaw_pitch(yaw: f64, pitch: f64) -> DVec3 {
    let (sy, cy) = yaw.sin_cos();
    let (sp, cp) = pitch.sin_cos();
    DVec3::new(cp * sy, sp, cp * cy)
}

/// Great-circle angle (rad, in [0, pi]) between two directions of any
/// length: `atan2(|a x b|, a . b)`, accurate near 0 and pi where `acos` of
/// the dot product is not. The one angle-between-directions in the crate.
pub fn angle_between(a: DVec3, b: DVec3) -> f64 {
    a.cross(b).length().atan2(a.dot(b))
}

/// Probability that a Poisson process of `rate` (1/s) fires within one
/// step of `dt` seconds: `1 - exp(-rate dt)`.
pub fn poisson_step(rate: f64, dt: f64) -> f64 {
    1.0 - (-rate * dt).exp()
}

/// Inverse of [`dir_from_yaw_pitch`] for any non-zero direction.
/// Returns `(yaw, pitch)` in radians; yaw in (-pi, pi], pitch in [-pi/2, pi/2].
pub fn yaw_pitch_of(dir: DVec3) -> (f64, f64) {
    let yaw = dir.x.atan2(dir.z);
    let pitch = dir.y.atan2((dir.x * dir.x + dir.z * dir.z).sqrt());
    (yaw, pitch)
}

/// Yaw (about up, + left), pitch (+ up), roll (about forward) of a joint
/// rotation `q = Ry(yaw) Rx(-pitch) Rz(roll)`, radians.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct JointAngles {
    /// Yaw, radians.
    pub yaw: f64,
    /// Pitch, radians.
    pub pitch: f64,
    /// Roll, radians.
    pub roll: f64,
}

impl JointAngles {
    /// Decompose a relative rotation.
    pub fn from_quat(q: glam::Quat) -> Self {
        let (y, x, z) = q.to_euler(glam::EulerRot::YXZ);
        JointAngles {
            yaw: y as f64,
            pitch: -x as f64,
            roll: z as f64,
        }
    }

    /// Compose the rotation these angles describe.
    pub fn to_quat(self) -> glam::Quat {
        glam::Quat::from_euler(
            glam::EulerRot::YXZ,
            self.yaw as f32,
            -self.pitch as f32,
            self.roll as f32,
        )
    }
}

/// Cubic Hermite interpolation through `n` knots `(x, value)` given by
/// `knot(i)`, their `x` strictly ascending or strictly descending; each
/// knot's tangent is the chord between its neighbours (a one-sided
/// difference at the ends); constant outside the knots. Shape tables (the
/// body's sections, the head's profile) are read through it.
pub fn hermite(n: usize, knot: impl Fn(usize) -> (f32, f32), x: f32) -> f32 {
    let s = if knot(n - 1).0 >= knot(0).0 {
        1.0
    } else {
        -1.0
    };
    if s * x <= s * knot(0).0 {
        return knot(0).1;
    }
    let slope = |i: usize| {
        let (a, b) = (knot(i.saturating_sub(1)), knot((i + 1).min(n - 1)));
        (b.1 - a.1) / (b.0 - a.0)
    };
    for i in 0..n - 1 {
        let ((x0, v0), (x1, v1)) = (knot(i), knot(i + 1));
        if s * x <= s * x1 {
            let h = x1 - x0;
            let t = (x - x0) / h;
            let (t2, t3) = (t * t, t * t * t);
            return (2.0 * t3 - 3.0 * t2 + 1.0) * v0
                + (t3 - 2.0 * t2 + t) * h * slope(i)
                + (-2.0 * t3 + 3.0 * t2) * v1
                + (t3 - t2) * h * slope(i + 1);
        }
    }
    knot(n - 1).1
}

/// Smooth Hermite step: 0 at or below `e0`, 1 at or beyond `e1`, with zero
/// slope at both ends (`e1 < e0` runs the step downward).
pub fn smoothstep(e0: f32, e1: f32, x: f32) -> f32 {
    let t = ((x - e0) / (e1 - e0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// Gaussian bump `exp(-(d / s)^2)`: 1 at `d = 0`, 1/e at `d = s`.
pub fn gauss(d: f32, s: f32) -> f32 {
    (-(d / s) * (d / s)).exp()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn min_jerk_end_points_and_peak() {
        assert_eq!(min_jerk(0.0), 0.0);
        assert!((min_jerk(1.0) - 1.0).abs() < 1e-15);
        assert!((min_jerk(0.5) - 0.5).abs() < 1e-15);
        assert!((min_jerk_d(0.5) - 1.875).abs() < 1e-12);
        assert_eq!(min_jerk_d(0.0), 0.0);
        assert_eq!(min_jerk_d(1.0), 0.0);
    }

    #[test]
    fn yaw_pitch_round_trip_and_signs() {
        let d = dir_from_yaw_pitch(0.3, 0.0);
        assert!(d.x > 0.0, "positive yaw looks to the left (+X)");
        assert!(
            dir_from_yaw_pitch(0.0, 0.2).y > 0.0,
            "positive pitch looks up"
        );
        for &(y, p) in &[(0.0, 0.0), (0.5, -0.3), (-1.2, 0.7), (2.0, 1.0)] {
            let (y2, p2) = yaw_pitch_of(dir_from_yaw_pitch(y, p));
            assert!((y - y2).abs() < 1e-12 && (p - p2).abs() < 1e-12);
        }
    }

    #[test]
    fn derivatives_match_finite_differences() {
        let h = 1e-6;
        for i in 1..100 {
            let s = i as f64 / 100.0;
            let fd = (min_jerk(s + h) - min_jerk(s - h)) / (2.0 * h);
            assert!((fd - min_jerk_d(s)).abs() < 1e-6, "s={s}");
            let fdd = (min_jerk_d(s + h) - min_jerk_d(s - h)) / (2.0 * h);
            assert!((fdd - min_jerk_dd(s)).abs() < 1e-5, "s={s}");
        }
    }

    #[test]
    fn angle_between_is_accurate_near_zero_and_for_unnormalised_input() {
        // A line of sight computed in single precision is unit only to
        // about 1e-7; `acos` of its dot product has a noise floor near
        // sqrt(2e-7) ~ 4e-4 rad there, the atan2 form does not.
        let a = DVec3::new(0.0, 0.0, 1.0 + 1e-7);
        let b = dir_from_yaw_pitch(1e-6, 0.0);
        assert!((angle_between(a, b) - 1e-6).abs() < 1e-12);
        assert!((angle_between(b, -b) - std::f64::consts::PI).abs() < 1e-12);
        assert!(
            (angle_between(DVec3::X * 3.0, DVec3::Y * 0.5) - std::f64::consts::FRAC_PI_2).abs()
                < 1e-15
        );
    }

    #[test]
    fn hermite_passes_through_its_knots_either_way_round() {
        let up = [(0.0f32, 1.0f32), (1.0, 3.0), (2.0, 2.0), (4.0, 5.0)];
        let down: Vec<_> = up.iter().rev().copied().collect();
        for (x, v) in up {
            assert!((hermite(4, |i| up[i], x) - v).abs() < 1e-6);
            assert!((hermite(4, |i| down[i], x) - v).abs() < 1e-6);
        }
        // Constant outside; the same curve whichever way the knots run.
        assert_eq!(hermite(4, |i| up[i], -1.0), 1.0);
        assert_eq!(hermite(4, |i| down[i], 9.0), 5.0);
        let (a, b) = (hermite(4, |i| up[i], 2.7), hermite(4, |i| down[i], 2.7));
        assert!((a - b).abs() < 1e-5, "{a} {b}");
        // A straight line stays straight.
        let line = [(0.0f32, 0.0f32), (1.0, 2.0), (3.0, 6.0)];
        assert!((hermite(3, |i| line[i], 2.0) - 4.0).abs() < 1e-5);
    }
}
