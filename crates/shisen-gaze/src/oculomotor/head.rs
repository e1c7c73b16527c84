//! Head movement during gaze shifts (gaze.md section 9): when the head
//! starts, how far it turns (M8, with the Correction), and its
//! minimum-jerk sub-target (M9) timed by Pejsa et al.'s peak-velocity law,
//! within the neck's range of motion.
//!
//! Angles are neck joint angles (yaw, pitch) of the head relative to the
//! torso, whose forward axis is "straight ahead" for (M8). The 2-D move is a
//! straight line in (yaw, pitch) joint space: the neck is driven per joint
//! by PD control (gaze.md section 1, step 7) and (M9) is a per-joint law, so
//! both joints start and stop together with the same minimum-jerk shape.

use glam::DVec2;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::util::math::{
    MIN_JERK_PEAK, angle_between, dir_from_yaw_pitch, min_jerk, min_jerk_d, min_jerk_dd,
    yaw_pitch_of,
};

/// Neck range of motion (gaze.md section 9, from Takagi & Takeda 2.1). Radians.
/// Each limit is above 0 and at most 1.6 rad (92 deg), beyond any human
/// neck's active range (rotation about 80 deg, flexion 60-80 deg).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct NeckLimits {
    /// Rotation left/right, +- (rad). Default 70 deg. Above 0, at most 1.6.
    #[schemars(range(max = 1.6), extend("exclusiveMinimum" = 0.0))]
    pub yaw: f64,
    /// Extension (looking up) limit (rad). Default 50 deg. Above 0, at most 1.6.
    #[schemars(range(max = 1.6), extend("exclusiveMinimum" = 0.0))]
    pub pitch_up: f64,
    /// Flexion (looking down) limit, as a positive angle (rad). Default 60 deg.
    /// Above 0, at most 1.6.
    #[schemars(range(max = 1.6), extend("exclusiveMinimum" = 0.0))]
    pub pitch_down: f64,
    /// Lateral bend, +- (rad). Default 50 deg. Above 0, at most 1.6.
    #[schemars(range(max = 1.6), extend("exclusiveMinimum" = 0.0))]
    pub roll: f64,
}

impl Default for NeckLimits {
    fn default() -> Self {
        use crate::anatomy::neck;
        Self {
            yaw: neck::YAW_DEG.to_radians(),
            pitch_up: neck::PITCH_UP_DEG.to_radians(),
            pitch_down: neck::PITCH_DOWN_DEG.to_radians(),
            roll: neck::ROLL_DEG.to_radians(),
        }
    }
}

impl NeckLimits {
    /// Clamps a (yaw, pitch) head target into the range of motion.
    pub fn clamp(&self, angles: DVec2) -> DVec2 {
        DVec2::new(
            angles.x.clamp(-self.yaw, self.yaw),
            angles.y.clamp(-self.pitch_down, self.pitch_up),
        )
    }

    /// Clamps a roll (lateral bend) angle.
    pub fn clamp_roll(&self, roll: f64) -> f64 {
        roll.clamp(-self.roll, self.roll)
    }
}

/// An attention amount `A` with the personality's `A1` (head moves least)
/// and `A2` (head moves most, `A2 > A1`) it is judged against (M8).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Amount {
    /// `A`.
    pub value: f64,
    /// `A1`.
    pub least: f64,
    /// `A2`.
    pub most: f64,
}

/// Static head-movement parameters (gaze.md section 9). Radians and seconds.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct HeadParams {
    /// The head moves only for gaze points farther than this from the face's
    /// forward axis (rad). Default 30 deg. 0-3.15 rad: no gaze point lies
    /// more than a half turn away.
    #[schemars(range(min = 0.0, max = 3.15))]
    pub start_angle: f64,
    /// Delay after eye onset before a bottom-up head movement (s). Default 0.020.
    /// 0-1 s.
    #[schemars(range(min = 0.0, max = 1.0))]
    pub eye_lead: f64,
    /// Largest stop-short angle of (M8) (rad). Default 30 deg. 0-1.6 rad
    /// (about 90 deg, beyond the eyes' range that must make up the rest).
    #[schemars(range(min = 0.0, max = 1.6))]
    pub max_short_fall: f64,
    /// Steepness of the (M8) sigmoid. Default 7. Above 0, at most 100 (a
    /// step).
    #[schemars(range(max = 100.0), extend("exclusiveMinimum" = 0.0))]
    pub steepness: f64,
    /// Peak head speed at zero amplitude (rad/s). Default 40 deg/s (Pejsa et al.).
    /// 0.05-20 rad/s (3-1150 deg/s; the fastest head turns peak at a few
    /// hundred deg/s).
    #[schemars(range(min = 0.05, max = 20.0))]
    pub peak_speed_base: f64,
    /// Peak head speed per radian of amplitude (1/s). Default 8/3 (Pejsa et al.:
    /// `Vp = (4/3 A_deg/50 + 2/5) 100 deg/s`). 0-20 1/s, seven times
    /// the default.
    #[schemars(range(min = 0.0, max = 20.0))]
    pub peak_speed_gain: f64,
    /// Shortest head movement (s); Pejsa's law tends to zero for tiny moves.
    /// Default 0.15 (our choice). 0.01-5 s: head movements last
    /// 0.2-1 s.
    #[schemars(range(min = 0.01, max = 5.0))]
    pub min_duration: f64,
    /// Neck range of motion.
    pub limits: NeckLimits,
}

impl Default for HeadParams {
    fn default() -> Self {
        Self {
            start_angle: 30f64.to_radians(),
            eye_lead: 0.020,
            max_short_fall: 30f64.to_radians(),
            steepness: 7.0,
            peak_speed_base: 40f64.to_radians(),
            peak_speed_gain: 8.0 / 3.0,
            min_duration: 0.15,
            limits: NeckLimits::default(),
        }
    }
}

impl HeadParams {
    /// Start rule (gaze.md 9): the gaze point is more than [`Self::start_angle`]
    /// from the face's forward axis (`gaze_from_face`, rad) AND either
    /// [`Self::eye_lead`] has passed since the eye movement began
    /// (`since_eye_onset`, s) or the gaze point is top-down (the head may lead).
    pub fn should_start(&self, gaze_from_face: f64, since_eye_onset: f64, top_down: bool) -> bool {
        gaze_from_face.abs() > self.start_angle && (top_down || since_eye_onset >= self.eye_lead)
    }

    /// `x = (2A - 2A1)/(A2 - A1) - 1` clamped to [-1, 1] (M8).
    pub fn importance(&self, attention: Amount) -> f64 {
        let (attention, a1, a2) = (attention.value, attention.least, attention.most);
        (2.0 * (attention - a1) / (a2 - a1) - 1.0).clamp(-1.0, 1.0) // (M8)
    }

    /// How far short of the gaze point the head stops (rad):
    /// `30 deg / (1 + exp(7 x))` (M8 with the Correction: least important
    /// targets, x = -1, stop about 30 deg short; most important, x = 1, face it).
    pub fn short_fall(&self, attention: Amount) -> f64 {
        self.max_short_fall / (1.0 + (self.steepness * self.importance(attention)).exp()) // (M8)
    }

    /// (M8) on one axis: `theta_head = theta_att - sign(theta_att) * short_fall`,
    /// never past straight ahead (a gaze point nearer than the short fall
    /// gives 0, not a turn away). Not clamped to the neck range.
    pub fn amplitude_1d(&self, theta_att: f64, attention: Amount) -> f64 {
        let m = (theta_att.abs() - self.short_fall(attention)).max(0.0); // (M8)
        theta_att.signum() * m
    }

    /// (M8) for a 2-D gaze point `gaze` (yaw, pitch from straight ahead): the
    /// law acts on the great-circle angle from straight ahead, the head aims
    /// along the same great circle, and the result is clamped to the neck range.
    pub fn target(&self, gaze: DVec2, attention: Amount) -> DVec2 {
        let fwd = dir_from_yaw_pitch(0.0, 0.0);
        let d = dir_from_yaw_pitch(gaze.x, gaze.y);
        let angle = angle_between(fwd, d);
        if angle < 1e-12 {
            return DVec2::ZERO;
        }
        let head = self.amplitude_1d(angle, attention);
        let h = fwd.slerp(d, head / angle);
        let (yaw, pitch) = yaw_pitch_of(h);
        self.limits.clamp(DVec2::new(yaw, pitch))
    }

    /// Peak head speed for amplitude `a` (rad): `Vp = (4/3 A_deg/50 + 2/5) 100 deg/s`.
    pub fn peak_speed(&self, amplitude: f64) -> f64 {
        self.peak_speed_base + self.peak_speed_gain * amplitude.abs()
    }

    /// Duration `t_f = 1.875 A / Vp` (M9 timing, Pejsa et al.), at least
    /// [`Self::min_duration`].
    pub fn duration(&self, amplitude: f64) -> f64 {
        (MIN_JERK_PEAK * amplitude.abs() / self.peak_speed(amplitude)).max(self.min_duration)
    }
}

/// Head target angles, rates and accelerations at one instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HeadSample {
    /// (yaw, pitch), rad.
    pub angles: DVec2,
    /// (yaw, pitch) rates, rad/s.
    pub rate: DVec2,
    /// (yaw, pitch) accelerations, rad/s^2.
    pub accel: DVec2,
}

/// A planned head movement: the minimum-jerk sub-target (M9) from `start` to
/// `target` along a straight line in (yaw, pitch) joint space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HeadMove {
    start: DVec2,
    target: DVec2,
    duration: f64,
}

impl HeadMove {
    /// Plans the move; `target` is clamped to the neck range and the duration
    /// follows [`HeadParams::duration`] of the joint-space distance.
    pub fn plan(params: &HeadParams, start: DVec2, target: DVec2) -> Self {
        let target = params.limits.clamp(target);
        let amplitude = (target - start).length();
        Self {
            start,
            target,
            duration: params.duration(amplitude),
        }
    }

    /// Start angles.
    pub fn start(&self) -> DVec2 {
        self.start
    }

    /// Target angles (clamped).
    pub fn target(&self) -> DVec2 {
        self.target
    }

    /// `t_f` (s).
    pub fn duration(&self) -> f64 {
        self.duration
    }

    /// Samples the move at `t` (s since head onset).
    pub fn sample(&self, t: f64) -> HeadSample {
        let s = t / self.duration;
        let delta = self.target - self.start;
        HeadSample {
            angles: self.start + delta * min_jerk(s), // (M9)
            rate: delta * (min_jerk_d(s) / self.duration),
            accel: delta * (min_jerk_dd(s) / (self.duration * self.duration)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An amount on the original implementation's span (A1 = 0, A2 = 3).
    fn amount(value: f64) -> Amount {
        Amount {
            value,
            least: 0.0,
            most: 3.0,
        }
    }

    fn p() -> HeadParams {
        HeadParams::default()
    }

    fn deg(v: f64) -> f64 {
        v.to_radians()
    }

    #[test]
    fn m8_values_at_x_minus_one_zero_one() {
        let params = p();
        let att = deg(60.0);
        // A = A1 -> x = -1; A midway -> x = 0; A = A2 -> x = 1
        let cases = [
            (0.0, 30.0 / (1.0 + (-7f64).exp())),
            (1.5, 15.0),
            (3.0, 30.0 / (1.0 + 7f64.exp())),
        ];
        for (a, short_deg) in cases {
            let got = params.amplitude_1d(att, amount(a)).to_degrees();
            assert!((got - (60.0 - short_deg)).abs() < 1e-9, "A={a}: {got}");
            let got = params.amplitude_1d(-att, amount(a)).to_degrees();
            assert!((got + (60.0 - short_deg)).abs() < 1e-9, "mirror A={a}");
        }
        // least important: ~30 deg short; most important: faces the target
        assert!((params.amplitude_1d(att, amount(-5.0)).to_degrees() - 30.027).abs() < 1e-3);
        assert!((params.amplitude_1d(att, amount(10.0)).to_degrees() - 59.973).abs() < 1e-3);
    }

    #[test]
    fn m8_interpolates_monotonically() {
        let params = p();
        let mut last = f64::NEG_INFINITY;
        for i in 0..=300 {
            let a = 3.0 * i as f64 / 300.0;
            let h = params.amplitude_1d(deg(50.0), amount(a));
            assert!(h > last, "not increasing at A={a}");
            last = h;
        }
    }

    #[test]
    fn m8_never_turns_away() {
        assert_eq!(p().amplitude_1d(deg(20.0), amount(0.0)), 0.0);
    }

    #[test]
    fn m8_in_2d_acts_on_the_magnitude() {
        let params = p();
        let gaze = DVec2::new(deg(40.0), deg(30.0));
        let h = params.target(gaze, amount(1.5));
        let ang = |v: DVec2| {
            let (a, b) = (dir_from_yaw_pitch(0.0, 0.0), dir_from_yaw_pitch(v.x, v.y));
            angle_between(a, b)
        };
        let m = ang(gaze);
        assert!((ang(h) - (m - deg(15.0))).abs() < 1e-9);
        // same great circle: forward, head and gaze directions coplanar
        let (f, dh, dg) = (
            dir_from_yaw_pitch(0.0, 0.0),
            dir_from_yaw_pitch(h.x, h.y),
            dir_from_yaw_pitch(gaze.x, gaze.y),
        );
        assert!(f.cross(dg).normalize().dot(dh).abs() < 1e-12);
    }

    #[test]
    fn start_rule() {
        let params = p();
        assert!(
            !params.should_start(deg(15.0), 1.0, false),
            "15 deg: no head"
        );
        assert!(
            !params.should_start(deg(15.0), 1.0, true),
            "15 deg top-down: no head"
        );
        assert!(params.should_start(deg(50.0), 0.030, false), "50 deg: head");
        assert!(
            !params.should_start(deg(50.0), 0.010, false),
            "bottom-up waits 20 ms"
        );
        assert!(params.should_start(deg(50.0), 0.020, false));
        assert!(
            params.should_start(deg(50.0), 0.0, true),
            "top-down may lead"
        );
        assert!(params.should_start(deg(-50.0), 0.03, false));
    }

    #[test]
    fn duration_law_figures() {
        let params = p();
        let d20 = params.duration(deg(20.0));
        let d40 = params.duration(deg(40.0));
        // closed form: t_f = 1.875 A / ((4/3 A/50 + 2/5) 100)
        let tf = |a: f64| 1.875 * a / ((4.0 / 3.0 * a / 50.0 + 0.4) * 100.0);
        assert!((d20 - tf(20.0)).abs() < 1e-12 && (d40 - tf(40.0)).abs() < 1e-12);
        println!("head duration 20 deg {d20:.3} s, 40 deg {d40:.3} s");
        assert!((d20 - 0.4).abs() < 0.01 && (d40 - 0.5).abs() < 0.02);
        assert_eq!(params.duration(deg(1.0)), params.min_duration);
    }

    #[test]
    fn head_move_follows_m9() {
        let params = p();
        let (a, b) = (
            DVec2::new(deg(-10.0), deg(5.0)),
            DVec2::new(deg(30.0), deg(-20.0)),
        );
        let mv = HeadMove::plan(&params, a, b);
        assert_eq!(mv.sample(0.0).angles, a);
        assert!((mv.sample(mv.duration()).angles - b).length() < 1e-15);
        assert_eq!(
            mv.sample(mv.duration() + 1.0).angles,
            mv.sample(mv.duration()).angles
        );
        // peak speed at the midpoint equals Vp
        let amp = (b - a).length();
        let vp = mv.sample(0.5 * mv.duration()).rate.length();
        assert!((vp - params.peak_speed(amp)).abs() < 1e-9);
        // rate and acceleration are derivatives
        let h = 1e-6;
        for i in 1..100 {
            let t = mv.duration() * i as f64 / 100.0;
            let fd = (mv.sample(t + h).angles - mv.sample(t - h).angles) / (2.0 * h);
            assert!((fd - mv.sample(t).rate).length() < 1e-6);
            let fdd = (mv.sample(t + h).rate - mv.sample(t - h).rate) / (2.0 * h);
            assert!((fdd - mv.sample(t).accel).length() < 1e-4);
        }
    }

    #[test]
    fn limits_clamp() {
        let l = NeckLimits::default();
        let c = l.clamp(DVec2::new(deg(100.0), deg(80.0)));
        assert!((c - DVec2::new(deg(70.0), deg(50.0))).length() < 1e-12);
        let c = l.clamp(DVec2::new(deg(-100.0), deg(-80.0)));
        assert!((c - DVec2::new(deg(-70.0), deg(-60.0))).length() < 1e-12);
        assert_eq!(l.clamp_roll(deg(60.0)), deg(50.0));
        let mv = HeadMove::plan(&p(), DVec2::ZERO, DVec2::new(deg(120.0), 0.0));
        assert!((mv.target().x - deg(70.0)).abs() < 1e-12);
        let t = p().target(DVec2::new(deg(110.0), 0.0), amount(3.0));
        assert!((t.x - deg(70.0)).abs() < 1e-12);
    }

    #[test]
    fn params_deserialise() {
        let h: HeadParams = crate::util::ron::parse_ron(
            "(limits: (yaw: 1.0), eye_lead: 0.04)",
            std::path::Path::new("t.ron"),
        )
        .unwrap();
        assert_eq!(h.limits.yaw, 1.0);
        assert_eq!(h.limits.pitch_up, NeckLimits::default().pitch_up);
        assert!(
            crate::util::ron::parse_ron::<HeadParams>(
                "(min_duration: 0.0)",
                std::path::Path::new("t.ron")
            )
            .is_err()
        );
        assert!(
            crate::util::ron::parse_ron::<HeadParams>(
                "(attention_most: 5.0)",
                std::path::Path::new("t.ron")
            )
            .is_err(),
            "A2 lives in the personality"
        );
    }
}
