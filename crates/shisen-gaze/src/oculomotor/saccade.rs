//! Saccades: the minimum-jerk profile capped at a maximum eye speed
//! (gaze.md section 7, equations M2-M6), an optional main-sequence timing,
//! and the 2-D saccade along the great circle between two directions.
//!
//! # The two timing laws
//! - [`SaccadeLaw::Seed`] is the paper's law: a saccade of amplitude
//!   `A < A' = L T / 1.875` is a plain minimum-jerk move of duration `T`
//!   (M5); a larger one accelerates along the first half of a minimum-jerk
//!   move of amplitude `A'`, cruises at `L`, and decelerates along the second
//!   half (M6). Duration `T` below `A'`, `(A - A')/L + T` above.
//! - [`SaccadeLaw::MainSequence`] takes the duration from the human main
//!   sequence, `D = 21 ms + 2.2 ms/deg * A`, with the same minimum-jerk shape.
//!   **Reconciling the cap**: a minimum-jerk move of duration `D` peaks at
//!   `1.875 A / D`, which passes `L = 500 deg/s` above about 13.5 deg. There
//!   the profile becomes the (M6) construction with the ramp time `T`
//!   replaced by the `T_r` for which the total still equals `D`:
//!   `D = A/L + T_r (1 - 1/1.875)`. The duration stays on the main sequence
//!   and the peak speed is exactly `L` (a short cruise), position and
//!   velocity continuous. Only if the main sequence asked for a mean speed
//!   above `L` (not with the defaults) would the cap win and the saccade be
//!   lengthened.

use glam::{DVec2, DVec3};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::util::math::{
    MIN_JERK_PEAK, angle_between, dir_from_yaw_pitch, min_jerk, min_jerk_d, min_jerk_dd,
    yaw_pitch_of,
};

/// Shortest ramp a capped main-sequence saccade may use (s); only reached
/// when the main sequence asks for more speed than the cap allows.
const MIN_RAMP_TIME: f64 = 0.005;

/// Which timing law plans a saccade.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
pub enum SaccadeLaw {
    /// The seed paper's law (M5, M6): duration `T` below `A'`, else `(A - A')/L + T`.
    #[default]
    Seed,
    /// Main-sequence duration `21 ms + 2.2 ms/deg`, minimum-jerk shape, capped at `L`.
    MainSequence,
}

/// Static saccade parameters (gaze.md section 7). Radians and seconds.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct SaccadeParams {
    /// `L`, maximum eye angular speed (rad/s). Default 500 deg/s = 8.7266 rad/s.
    /// 0.5-20 rad/s: the largest human saccades peak near 700 deg/s
    /// (Bahill, Clark & Stark 1975), 20 rad/s (1150 deg/s) is the
    /// controller's cap on any eye velocity; 0.5 rad/s (29 deg/s) is
    /// below the slowest pathological saccades.
    #[schemars(range(min = 0.5, max = 20.0))]
    pub max_speed: f64,
    /// `T`, the shortest saccade duration of the seed law (s). Default 0.05.
    /// 0.005-1 s: human saccades last 20-200 ms; the floor is the
    /// shortest ramp the profile uses.
    #[schemars(range(min = 0.005, max = 1.0))]
    pub min_duration: f64,
    /// Timing law.
    pub law: SaccadeLaw,
    /// Main-sequence duration at zero amplitude (s). Default 0.021 (21 ms).
    /// 0.005-0.5 s, many times the human intercept either way.
    #[schemars(range(min = 0.005, max = 0.5))]
    pub main_sequence_intercept: f64,
    /// Main-sequence duration per radian (s/rad). Default 2.2 ms/deg = 0.12605 s/rad.
    /// 0-1 s/rad (up to 17 ms/deg, eight times the human slope).
    #[schemars(range(min = 0.0, max = 1.0))]
    pub main_sequence_slope: f64,
    /// A saccade starts when either eye's error exceeds this (rad). Default 5 deg.
    /// Above 0, at most 1.6 rad (about 90 deg, beyond the eye's 55 deg
    /// range: only new targets then draw saccades).
    #[schemars(range(max = 1.6), extend("exclusiveMinimum" = 0.0))]
    pub start_threshold: f64,
    /// A new target (or a catch-up) draws a saccade when an eye's error to
    /// it exceeds this (rad); nearer, pursuit glides there. Default 0.5 deg.
    /// (The seed's "pursuit resumes below 0.1 deg" end rule is not needed:
    /// a saccade ends when its planned profile does, at the goal; see
    /// docs/model/gaze.md section 8.) Above 0, at most 1.6 rad (about
    /// 90 deg, beyond the eye's range: pursuit then glides everywhere).
    #[schemars(range(max = 1.6), extend("exclusiveMinimum" = 0.0))]
    pub new_target_threshold: f64,
}

impl Default for SaccadeParams {
    fn default() -> Self {
        Self {
            max_speed: 500f64.to_radians(),
            min_duration: 0.05,
            law: SaccadeLaw::Seed,
            main_sequence_intercept: 0.021,
            main_sequence_slope: 0.0022f64.to_degrees(),
            start_threshold: 5f64.to_radians(),
            new_target_threshold: 0.5f64.to_radians(),
        }
    }
}

impl SaccadeParams {
    /// `A' = L T / f'(T/2) = L T / 1.875` (M3, with the Correction), the
    /// largest amplitude a plain minimum-jerk move of duration `T` can cover
    /// without exceeding `L`. 0.2327 rad = 13.3 deg with the defaults.
    pub fn cap_amplitude(&self) -> f64 {
        self.max_speed * self.min_duration / MIN_JERK_PEAK // (M3)
    }

    /// Main-sequence duration `21 ms + 2.2 ms/deg * |A|` (before the cap).
    pub fn main_sequence_duration(&self, amplitude: f64) -> f64 {
        self.main_sequence_intercept + self.main_sequence_slope * amplitude.abs()
    }

    /// Hysteresis start test: true when the largest eye error (rad) exceeds
    /// [`Self::start_threshold`].
    pub fn should_start(&self, max_error: f64) -> bool {
        max_error > self.start_threshold
    }
}

/// A planned 1-D saccade profile of signed amplitude `A` (rad), evaluated at
/// time `t` (s) since onset: position, velocity and acceleration.
///
/// Internally every profile is "ramp up along the first half of a
/// minimum-jerk move of amplitude `A_r` and duration `T_r`, cruise at `L`,
/// ramp down along its second half" (M6); a short saccade is the special
/// case with no cruise, `A_r = A` and `T_r` = the duration (M5).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SaccadeProfile {
    sign: f64,
    amplitude: f64,
    ramp_amplitude: f64,
    ramp_time: f64,
    cruise_speed: f64,
    cruise_time: f64,
    duration: f64,
}

impl SaccadeProfile {
    /// Plans a saccade of signed amplitude `amplitude` (rad) with `params`' law.
    pub fn plan(params: &SaccadeParams, amplitude: f64) -> Self {
        let a = amplitude.abs();
        let l = params.max_speed;
        let sign = if amplitude < 0.0 { -1.0 } else { 1.0 };
        let pure = |duration: f64| Self {
            sign,
            amplitude: a,
            ramp_amplitude: a,
            ramp_time: duration,
            cruise_speed: l,
            cruise_time: 0.0,
            duration,
        };
        let capped = |ramp_time: f64| {
            let ramp_amplitude = l * ramp_time / MIN_JERK_PEAK; // (M3) with T -> T_r
            let cruise_time = (a - ramp_amplitude) / l; // (M4): t_f - 0.5 T
            Self {
                sign,
                amplitude: a,
                ramp_amplitude,
                ramp_time,
                cruise_speed: l,
                cruise_time,
                duration: cruise_time + ramp_time, // t_f + 0.5 T
            }
        };
        match params.law {
            SaccadeLaw::Seed => {
                if a < params.cap_amplitude() {
                    pure(params.min_duration) // (M5)
                } else {
                    capped(params.min_duration) // (M6)
                }
            }
            SaccadeLaw::MainSequence => {
                let d = params.main_sequence_duration(a);
                if MIN_JERK_PEAK * a / d <= l {
                    pure(d)
                } else {
                    // D = A/L + T_r (1 - 1/1.875): keep D, cap the peak at L.
                    let tr = ((d - a / l) / (1.0 - 1.0 / MIN_JERK_PEAK)).max(MIN_RAMP_TIME);
                    capped(tr.min(d))
                }
            }
        }
    }

    /// Total duration (s): `T` or `t_f + 0.5 T` (M4-M6), or the main-sequence duration.
    pub fn duration(&self) -> f64 {
        self.duration
    }

    /// Signed amplitude (rad).
    pub fn amplitude(&self) -> f64 {
        self.sign * self.amplitude
    }

    /// Peak speed reached (rad/s): `1.875 A / T` for a short saccade, `L` for a capped one.
    pub fn peak_speed(&self) -> f64 {
        MIN_JERK_PEAK * self.ramp_amplitude / self.ramp_time
    }

    /// Position `theta_eye(t)` (rad): 0 before onset, `A` after the end.
    pub fn position(&self, t: f64) -> f64 {
        let (ar, tr, l, tc) = (
            self.ramp_amplitude,
            self.ramp_time,
            self.cruise_speed,
            self.cruise_time,
        );
        let p = if t <= 0.0 {
            0.0
        } else if t >= self.duration {
            self.amplitude
        } else if t < 0.5 * tr {
            ar * min_jerk(t / tr) // (M6) first piece, (M5) when tc = 0
        } else if t < 0.5 * tr + tc {
            l * t + 0.5 * ar - 0.5 * l * tr // (M6) second piece
        } else {
            ar * min_jerk((t - tc) / tr) + (self.amplitude - ar) // (M6) third piece
        };
        self.sign * p
    }

    /// Velocity `d theta_eye / dt` (rad/s).
    pub fn velocity(&self, t: f64) -> f64 {
        let (ar, tr, tc) = (self.ramp_amplitude, self.ramp_time, self.cruise_time);
        let v = if t <= 0.0 || t >= self.duration {
            0.0
        } else if t < 0.5 * tr {
            ar / tr * min_jerk_d(t / tr) // d/dt of (M6) first piece
        } else if t < 0.5 * tr + tc {
            self.cruise_speed // d/dt of (M6) second piece
        } else {
            ar / tr * min_jerk_d((t - tc) / tr) // d/dt of (M6) third piece
        };
        self.sign * v
    }

    /// Acceleration (rad/s^2).
    pub fn acceleration(&self, t: f64) -> f64 {
        let (ar, tr, tc) = (self.ramp_amplitude, self.ramp_time, self.cruise_time);
        let a = if t <= 0.0 || t >= self.duration {
            0.0
        } else if t < 0.5 * tr {
            ar / (tr * tr) * min_jerk_dd(t / tr) // d2/dt2 of (M6) first piece
        } else if t < 0.5 * tr + tc {
            0.0
        } else {
            ar / (tr * tr) * min_jerk_dd((t - tc) / tr) // d2/dt2 of (M6) third piece
        };
        self.sign * a
    }
}

/// Yaw/pitch rates (rad/s) of a unit direction `d` moving at `d_dot`
/// (time derivative of [`yaw_pitch_of`]).
pub fn yaw_pitch_rates(d: DVec3, d_dot: DVec3) -> DVec2 {
    let rho2 = d.x * d.x + d.z * d.z;
    let rho = rho2.sqrt();
    let yaw_rate = (d.z * d_dot.x - d.x * d_dot.z) / rho2;
    let rho_dot = (d.x * d_dot.x + d.z * d_dot.z) / rho;
    let pitch_rate = (rho * d_dot.y - d.y * rho_dot) / d.length_squared();
    DVec2::new(yaw_rate, pitch_rate)
}

/// Target angles and angular rates of a 2-D saccade at one instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SaccadeSample {
    /// Eye joint target (yaw, pitch), rad.
    pub angles: DVec2,
    /// Its rate (yaw rate, pitch rate), rad/s.
    pub rates: DVec2,
}

/// A 2-D saccade from one (yaw, pitch) direction to another: the 1-D
/// profile applied to the angle along the great circle joining the two
/// directions (gaze.md section 7), the direction obtained by rotating the
/// start direction about the circle's pole (a slerp).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Saccade {
    start: DVec2,
    goal: DVec2,
    from: DVec3,
    pole: DVec3,
    profile: SaccadeProfile,
}

impl Saccade {
    /// Plans the saccade from `start` to `goal` (yaw, pitch in rad).
    pub fn plan(params: &SaccadeParams, start: DVec2, goal: DVec2) -> Self {
        let from = dir_from_yaw_pitch(start.x, start.y);
        let to = dir_from_yaw_pitch(goal.x, goal.y);
        let cross = from.cross(to);
        let angle = angle_between(from, to);
        let pole = if cross.length() > 1e-12 {
            cross.normalize()
        } else {
            // Zero (or, impossibly for an eye, 180 deg) amplitude: any pole
            // perpendicular to the start direction.
            from.any_orthonormal_vector()
        };
        Self {
            start,
            goal,
            from,
            pole,
            profile: SaccadeProfile::plan(params, angle),
        }
    }

    /// The 1-D profile along the great circle.
    pub fn profile(&self) -> &SaccadeProfile {
        &self.profile
    }

    /// Great-circle amplitude (rad).
    pub fn amplitude(&self) -> f64 {
        self.profile.amplitude()
    }

    /// Duration (s).
    pub fn duration(&self) -> f64 {
        self.profile.duration()
    }

    /// Start direction (yaw, pitch).
    pub fn start(&self) -> DVec2 {
        self.start
    }

    /// Goal direction (yaw, pitch).
    pub fn goal(&self) -> DVec2 {
        self.goal
    }

    /// Unit direction at time `t` (s since onset).
    pub fn direction(&self, t: f64) -> DVec3 {
        let (s, c) = self.profile.position(t).sin_cos();
        // Rodrigues' rotation of `from` about `pole` (pole is perpendicular to `from`).
        self.from * c + self.pole.cross(self.from) * s
    }

    /// Target angles and rates at time `t` (s since onset). Returns exactly
    /// `start` before onset and exactly `goal` from the end on.
    pub fn sample(&self, t: f64) -> SaccadeSample {
        if t <= 0.0 {
            return SaccadeSample {
                angles: self.start,
                rates: DVec2::ZERO,
            };
        }
        if t >= self.duration() {
            return SaccadeSample {
                angles: self.goal,
                rates: DVec2::ZERO,
            };
        }
        let d = self.direction(t);
        let d_dot = self.pole.cross(d) * self.profile.velocity(t);
        let (yaw, pitch) = yaw_pitch_of(d);
        SaccadeSample {
            angles: DVec2::new(yaw, pitch),
            rates: yaw_pitch_rates(d, d_dot),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::rngs::StdRng;
    use rand::{RngExt, SeedableRng};

    const L: f64 = 500.0; // deg/s, gaze.md section 7
    const T: f64 = 0.05; // s

    fn seed() -> SaccadeParams {
        SaccadeParams::default()
    }

    /// (M3)-(M6) written straight from gaze.md, in degrees, as the oracle.
    fn spec_m6(a_deg: f64, t: f64) -> f64 {
        let a_cap = L * T / MIN_JERK_PEAK;
        let f = |t: f64| min_jerk(t / T);
        if a_deg < a_cap {
            return a_deg * f(t);
        }
        let tf = (a_deg - a_cap) / L + 0.5 * T;
        if t < 0.5 * T {
            a_cap * f(t)
        } else if t < tf {
            L * t + 0.5 * a_cap - 0.5 * L * T
        } else {
            a_cap * f(t - (a_deg - a_cap) / L) + (a_deg - a_cap)
        }
    }

    #[test]
    fn cap_amplitude_is_13_3_deg() {
        assert!((seed().cap_amplitude().to_degrees() - 13.333).abs() < 1e-3);
    }

    #[test]
    fn seed_durations_match_closed_form() {
        let a_cap = L * T / MIN_JERK_PEAK;
        for a in [5.0, 10.0, 20.0, 30.0, 40.0] {
            let expected = if a < a_cap { T } else { (a - a_cap) / L + T };
            let got = SaccadeProfile::plan(&seed(), f64::to_radians(a)).duration();
            println!("seed saccade {a} deg: {:.2} ms", 1e3 * got);
            assert!(
                (got - expected).abs() < 1e-12,
                "{a} deg: {got} vs {expected}"
            );
        }
        let d40 = SaccadeProfile::plan(&seed(), 40f64.to_radians()).duration();
        assert!(
            (d40 - 0.1033).abs() < 1e-4,
            "40 deg is about 103 ms, got {d40}"
        );
    }

    #[test]
    fn seed_profile_equals_spec_pieces() {
        for a in [3.0, 13.0, 13.5, 20.0, 40.0, 60.0] {
            let p = SaccadeProfile::plan(&seed(), f64::to_radians(a));
            for i in 0..=2000 {
                let t = p.duration() * i as f64 / 2000.0;
                let want = spec_m6(a, t);
                let got = p.position(t).to_degrees();
                assert!((got - want).abs() < 1e-9, "A={a} t={t}: {got} vs {want}");
            }
        }
    }

    #[test]
    fn continuous_at_both_joints() {
        let eps = 1e-9;
        for a in [20.0, 30.0, 40.0, 60.0] {
            let p = SaccadeProfile::plan(&seed(), f64::to_radians(a));
            let a_cap = seed().cap_amplitude();
            let tf = (a.to_radians() - a_cap) / seed().max_speed + 0.5 * T; // (M4)
            for tj in [0.5 * T, tf] {
                let (l, r) = (tj - eps, tj + eps);
                assert!(
                    (p.position(l) - p.position(r)).abs() < 1e-7,
                    "pos A={a} at {tj}"
                );
                assert!(
                    (p.velocity(l) - p.velocity(r)).abs() < 1e-5,
                    "vel A={a} at {tj}"
                );
                // and the joint is at full speed
                assert!((p.velocity(l) - seed().max_speed).abs() < 1e-5);
            }
        }
    }

    #[test]
    fn peak_velocity_never_exceeds_cap() {
        let lmax = seed().max_speed;
        for law in [SaccadeLaw::Seed, SaccadeLaw::MainSequence] {
            let params = SaccadeParams { law, ..seed() };
            for a in [0.5, 5.0, 13.0, 13.4, 13.6, 20.0, 40.0, 60.0] {
                let p = SaccadeProfile::plan(&params, f64::to_radians(a));
                let n = 20_000;
                let h = p.duration() / n as f64;
                let mut peak: f64 = 0.0;
                for i in 0..=n {
                    let t = i as f64 * h;
                    peak = peak.max(p.velocity(t).abs());
                    if i > 0 {
                        // finite differences of position obey the cap too
                        let fd = (p.position(t) - p.position(t - h)) / h;
                        assert!(fd <= lmax * (1.0 + 1e-9), "{law:?} A={a}: fd {fd}");
                    }
                }
                assert!(peak <= lmax * (1.0 + 1e-12), "{law:?} A={a}: {peak}");
                if a > 14.0 {
                    assert!(peak > 0.999 * lmax, "large saccades reach the cap");
                }
            }
        }
    }

    #[test]
    fn starts_at_zero_and_ends_at_amplitude() {
        for law in [SaccadeLaw::Seed, SaccadeLaw::MainSequence] {
            let params = SaccadeParams { law, ..seed() };
            for a in [-30.0, -2.0, 0.0, 2.0, 13.3, 45.0] {
                let p = SaccadeProfile::plan(&params, f64::to_radians(a));
                assert_eq!(p.position(0.0), 0.0);
                assert_eq!(p.velocity(0.0), 0.0);
                assert!((p.position(p.duration()) - a.to_radians()).abs() < 1e-15);
                assert!((p.position(p.duration() - 1e-12) - a.to_radians()).abs() < 1e-9);
                assert!(p.velocity(p.duration() - 1e-12).abs() < 1e-6);
            }
        }
    }

    #[test]
    fn velocity_and_acceleration_are_derivatives() {
        for law in [SaccadeLaw::Seed, SaccadeLaw::MainSequence] {
            let params = SaccadeParams { law, ..seed() };
            for a in [8.0, 25.0, -50.0] {
                let p = SaccadeProfile::plan(&params, f64::to_radians(a));
                let h = 1e-7;
                for i in 1..200 {
                    let t = p.duration() * i as f64 / 200.0;
                    let fd = (p.position(t + h) - p.position(t - h)) / (2.0 * h);
                    assert!((fd - p.velocity(t)).abs() < 1e-5, "v A={a} t={t}");
                    let fdd = (p.velocity(t + h) - p.velocity(t - h)) / (2.0 * h);
                    assert!((fdd - p.acceleration(t)).abs() < 1e-2 * (1.0 + fdd.abs()));
                }
            }
        }
    }

    #[test]
    fn main_sequence_duration_within_ten_percent() {
        let params = SaccadeParams {
            law: SaccadeLaw::MainSequence,
            ..seed()
        };
        for a in [0.3, 1.0, 5.0, 10.0, 13.0, 15.0, 20.0, 30.0, 40.0, 60.0] {
            let want = 0.021 + 0.0022 * a;
            let prof = SaccadeProfile::plan(&params, f64::to_radians(a));
            let got = prof.duration();
            println!(
                "main-sequence saccade {a} deg: {:.2} ms (want {:.2}), peak {:.1} deg/s",
                1e3 * got,
                1e3 * want,
                prof.peak_speed().to_degrees()
            );
            assert!((got - want).abs() <= 0.1 * want, "{a} deg: {got} vs {want}");
        }
    }

    #[test]
    fn great_circle_path_stays_on_circle() {
        let mut rng = StdRng::seed_from_u64(7);
        for law in [SaccadeLaw::Seed, SaccadeLaw::MainSequence] {
            let params = SaccadeParams { law, ..seed() };
            for _ in 0..200 {
                let r = |rng: &mut StdRng, lim: f64| rng.random_range(-lim..lim).to_radians();
                let a = DVec2::new(r(&mut rng, 55.0), r(&mut rng, 45.0));
                let b = DVec2::new(r(&mut rng, 55.0), r(&mut rng, 45.0));
                let s = Saccade::plan(&params, a, b);
                let (u, v) = (dir_from_yaw_pitch(a.x, a.y), dir_from_yaw_pitch(b.x, b.y));
                let n = u.cross(v).normalize();
                let total = angle_between(u, v);
                assert!((s.amplitude() - total).abs() < 1e-9);
                for i in 0..=50 {
                    let t = s.duration() * i as f64 / 50.0;
                    let smp = s.sample(t);
                    let d = dir_from_yaw_pitch(smp.angles.x, smp.angles.y);
                    assert!(d.dot(n).abs() < 1e-9, "off the great circle");
                    // the angle travelled from the start (and left to the goal) sum to the total
                    let (ga, gb) = (angle_between(u, d), angle_between(d, v));
                    assert!((ga + gb - total).abs() < 1e-7);
                    assert!((ga - s.profile().position(t)).abs() < 1e-7);
                    // rates are the time derivative of the angles
                    if i > 0 && i < 50 {
                        let h = 1e-7;
                        let fd = (s.sample(t + h).angles - s.sample(t - h).angles) / (2.0 * h);
                        assert!((fd - smp.rates).length() < 1e-4 * (1.0 + fd.length()));
                    }
                }
                assert_eq!(s.sample(s.duration()).angles, b);
                assert_eq!(s.sample(0.0).angles, a);
            }
        }
    }

    #[test]
    fn start_threshold() {
        let p = seed();
        assert!(p.should_start(6f64.to_radians()) && !p.should_start(4f64.to_radians()));
    }

    #[test]
    fn params_deserialise_and_validate() {
        let p: SaccadeParams =
            crate::util::ron::parse_ron("(law: MainSequence)", std::path::Path::new("t.ron"))
                .unwrap();
        assert_eq!(p.law, SaccadeLaw::MainSequence);
        assert_eq!(p.max_speed, seed().max_speed);
        assert!(
            crate::util::ron::parse_ron::<SaccadeParams>(
                "(max_speed: -1.0)",
                std::path::Path::new("t.ron")
            )
            .is_err()
        );
        assert!(
            crate::util::ron::parse_ron::<SaccadeParams>(
                "(bogus: 1.0)",
                std::path::Path::new("t.ron")
            )
            .is_err()
        );
    }
}
