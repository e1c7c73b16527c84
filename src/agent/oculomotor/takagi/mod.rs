//! Takagi & Takeda's sigmoid head and gaze trajectories (gaze.md section 10,
//! equation T1): a parametric, expressive alternative to the reflexive laws.
//!
//! Per axis (yaw, pitch; roll = 0) a trajectory waits `T1`, moves along a
//! shifted logistic curve for `T2` reaching exactly `a`, and holds for `T3`.
//! The gaze (line of sight) uses the same form with its own parameters and
//! the eye-in-head angle is gaze minus head. Yaw depends only on the
//! horizontal target angle and pitch only on the vertical one (their table 2).
//! The "linear model" (constant angular velocity over the same interval) is
//! the baseline they compared against.
//!
//! In code the angles are radians and times seconds; the fitted tables are
//! kept as printed (degrees) and converted when used.

mod presets;
mod tables;

use glam::DVec2;
use serde::{Deserialize, Serialize};

use crate::util::check::non_negative;
pub use presets::Preset;
pub use tables::{Axis, HeadFitRow, TABLE_TEST2, TABLE1_HEAD_FITS, TEST2_B, TEST2_C, Test2Row};

/// One sigmoid move (T1), without offset. `a` in rad, `c` in 1/s, times in s.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Sigmoid {
    /// Final angle `a` (rad).
    #[serde(deserialize_with = "crate::util::check::finite")]
    pub a: f64,
    /// Asymmetry `b`: 1 symmetric, < 1 slow start / fast end, > 1 the reverse.
    #[serde(deserialize_with = "crate::util::check::positive")]
    pub b: f64,
    /// Steepness `c` (1/s); small is nearly linear.
    #[serde(deserialize_with = "crate::util::check::positive")]
    pub c: f64,
    /// `T1`, wait before moving (s).
    #[serde(deserialize_with = "non_negative")]
    pub wait: f64,
    /// `T2`, moving time (s).
    #[serde(deserialize_with = "crate::util::check::positive")]
    pub moving: f64,
    /// `T3`, hold after arriving (s).
    #[serde(deserialize_with = "non_negative")]
    pub hold: f64,
}

impl Default for Sigmoid {
    fn default() -> Self {
        Self {
            a: 0.0,
            b: 1.0,
            c: 8.0,
            wait: 0.0,
            moving: 1.6,
            hold: 0.0,
        }
    }
}

impl Sigmoid {
    /// Builds from degrees (as the tables print them) and seconds.
    pub fn from_deg(a_deg: f64, b: f64, c: f64, wait: f64, moving: f64, hold: f64) -> Self {
        Self {
            a: a_deg.to_radians(),
            b,
            c,
            wait,
            moving,
            hold,
        }
    }

    fn exps(&self) -> (f64, f64) {
        let h = 0.5 * self.c * self.moving;
        (h.exp(), (-h).exp())
    }

    /// `Amp = (a/b)(1 + b e^{cT2/2})(1 + b e^{-cT2/2}) / (e^{cT2/2} - e^{-cT2/2})` (T1).
    pub fn amp(&self) -> f64 {
        let (ep, em) = self.exps();
        self.a / self.b * (1.0 + self.b * ep) * (1.0 + self.b * em) / (ep - em) // (T1)
    }

    /// `D = (a/b)(1 + b e^{-cT2/2}) / (e^{cT2/2} - e^{-cT2/2})` (T1).
    pub fn d(&self) -> f64 {
        let (ep, em) = self.exps();
        self.a / self.b * (1.0 + self.b * em) / (ep - em) // (T1)
    }

    /// `t1 = T1`.
    pub fn t1(&self) -> f64 {
        self.wait
    }

    /// `t2 = T1 + T2`.
    pub fn t2(&self) -> f64 {
        self.wait + self.moving
    }

    /// `t3 = T1 + T2 + T3`, the end of the hold.
    pub fn t3(&self) -> f64 {
        self.t2() + self.hold
    }

    /// `f(t)` (rad): 0 until `t1`, the logistic piece until `t2`, then `a` (T1).
    pub fn position(&self, t: f64) -> f64 {
        if t <= self.t1() {
            0.0
        } else if t >= self.t2() {
            self.a
        } else {
            let tau = t - self.wait - 0.5 * self.moving;
            self.amp() / (1.0 + self.b * (-self.c * tau).exp()) - self.d() // (T1) middle piece
        }
    }

    /// `f'(t)` (rad/s): `Amp b c e^{-c tau} / (1 + b e^{-c tau})^2` while moving.
    pub fn velocity(&self, t: f64) -> f64 {
        if t <= self.t1() || t >= self.t2() {
            return 0.0;
        }
        let tau = t - self.wait - 0.5 * self.moving;
        let e = self.b * (-self.c * tau).exp();
        self.amp() * self.c * e / ((1.0 + e) * (1.0 + e)) // d/dt of (T1)
    }

    /// The linear-model baseline over the same interval and end angle.
    pub fn linear(&self) -> Linear {
        Linear {
            a: self.a,
            wait: self.wait,
            moving: self.moving,
            hold: self.hold,
        }
    }
}

/// Takagi & Takeda's "linear model": constant angular velocity from `t1` to `t2`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Linear {
    /// Final angle (rad).
    #[serde(deserialize_with = "crate::util::check::finite")]
    pub a: f64,
    /// Wait (s).
    #[serde(deserialize_with = "non_negative")]
    pub wait: f64,
    /// Moving time (s).
    #[serde(deserialize_with = "crate::util::check::positive")]
    pub moving: f64,
    /// Hold (s).
    #[serde(deserialize_with = "non_negative")]
    pub hold: f64,
}

impl Default for Linear {
    fn default() -> Self {
        Self {
            a: 0.0,
            wait: 0.0,
            moving: 1.6,
            hold: 0.0,
        }
    }
}

impl Linear {
    /// Angle at `t` (rad).
    pub fn position(&self, t: f64) -> f64 {
        self.a * ((t - self.wait) / self.moving).clamp(0.0, 1.0)
    }

    /// Rate at `t` (rad/s).
    pub fn velocity(&self, t: f64) -> f64 {
        if t > self.wait && t < self.wait + self.moving {
            self.a / self.moving
        } else {
            0.0
        }
    }

    /// End of the hold (s).
    pub fn t3(&self) -> f64 {
        self.wait + self.moving + self.hold
    }
}

/// One piece of an axis trajectory.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum Segment {
    /// A (T1) sigmoid.
    Sigmoid(Sigmoid),
    /// The linear baseline.
    Linear(Linear),
}

impl Segment {
    fn position(&self, t: f64) -> f64 {
        match self {
            Segment::Sigmoid(s) => s.position(t),
            Segment::Linear(l) => l.position(t),
        }
    }
    fn velocity(&self, t: f64) -> f64 {
        match self {
            Segment::Sigmoid(s) => s.velocity(t),
            Segment::Linear(l) => l.velocity(t),
        }
    }
    fn end(&self) -> f64 {
        match self {
            Segment::Sigmoid(s) => s.t3(),
            Segment::Linear(l) => l.t3(),
        }
    }
    fn to_linear(self) -> Self {
        match self {
            Segment::Sigmoid(s) => Segment::Linear(s.linear()),
            l => l,
        }
    }
}

/// One axis: an offset (the starting angle) plus a sum of segments; two
/// sigmoids make the wind-up.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct AxisTrack {
    /// Angle added throughout (rad).
    #[serde(deserialize_with = "crate::util::check::finite")]
    pub offset: f64,
    /// Segments, summed.
    pub segments: Vec<Segment>,
}

impl AxisTrack {
    /// A single sigmoid, no offset.
    pub fn sigmoid(s: Sigmoid) -> Self {
        Self {
            offset: 0.0,
            segments: vec![Segment::Sigmoid(s)],
        }
    }

    /// Angle at `t` (rad).
    pub fn position(&self, t: f64) -> f64 {
        self.offset + self.segments.iter().map(|s| s.position(t)).sum::<f64>()
    }

    /// Rate at `t` (rad/s).
    pub fn velocity(&self, t: f64) -> f64 {
        self.segments.iter().map(|s| s.velocity(t)).sum()
    }

    /// End time (s).
    pub fn end(&self) -> f64 {
        self.segments.iter().map(Segment::end).fold(0.0, f64::max)
    }

    /// The same track with every sigmoid replaced by its linear baseline.
    pub fn linear_baseline(&self) -> Self {
        Self {
            offset: self.offset,
            segments: self.segments.iter().map(|s| s.to_linear()).collect(),
        }
    }
}

/// Head, gaze and eye (= gaze - head) at one instant; (yaw, pitch) rad and rad/s.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GazeShiftSample {
    /// Head angles.
    pub head: DVec2,
    /// Gaze (line of sight) angles.
    pub gaze: DVec2,
    /// Eye-in-head angles, `gaze - head`.
    pub eye: DVec2,
    /// Head rates.
    pub head_rate: DVec2,
    /// Gaze rates.
    pub gaze_rate: DVec2,
    /// Eye rates.
    pub eye_rate: DVec2,
}

/// A complete expressive gaze shift: head and gaze tracks per axis.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct GazeShift {
    /// Head yaw.
    pub head_yaw: AxisTrack,
    /// Head pitch.
    pub head_pitch: AxisTrack,
    /// Gaze yaw.
    pub gaze_yaw: AxisTrack,
    /// Gaze pitch.
    pub gaze_pitch: AxisTrack,
}

impl GazeShift {
    /// Samples at `t` (s since the shift began).
    pub fn sample(&self, t: f64) -> GazeShiftSample {
        let head = DVec2::new(self.head_yaw.position(t), self.head_pitch.position(t));
        let gaze = DVec2::new(self.gaze_yaw.position(t), self.gaze_pitch.position(t));
        let head_rate = DVec2::new(self.head_yaw.velocity(t), self.head_pitch.velocity(t));
        let gaze_rate = DVec2::new(self.gaze_yaw.velocity(t), self.gaze_pitch.velocity(t));
        GazeShiftSample {
            head,
            gaze,
            eye: gaze - head,
            head_rate,
            gaze_rate,
            eye_rate: gaze_rate - head_rate,
        }
    }

    /// End time (s).
    pub fn end(&self) -> f64 {
        [
            &self.head_yaw,
            &self.head_pitch,
            &self.gaze_yaw,
            &self.gaze_pitch,
        ]
        .iter()
        .map(|a| a.end())
        .fold(0.0, f64::max)
    }

    /// The linear-model baseline: same waits, durations and end angles.
    pub fn linear_baseline(&self) -> Self {
        Self {
            head_yaw: self.head_yaw.linear_baseline(),
            head_pitch: self.head_pitch.linear_baseline(),
            gaze_yaw: self.gaze_yaw.linear_baseline(),
            gaze_pitch: self.gaze_pitch.linear_baseline(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn every_row_sigmoid() -> Vec<Sigmoid> {
        let mut v: Vec<Sigmoid> = TABLE1_HEAD_FITS.iter().map(HeadFitRow::sigmoid).collect();
        for r in TABLE_TEST2 {
            v.extend(r.sigmoids());
        }
        v
    }

    /// (T1) middle piece written out from gaze.md as the oracle.
    fn spec_t1(a: f64, b: f64, c: f64, t1: f64, t2: f64, t: f64) -> f64 {
        let (ep, em) = ((c * t2 / 2.0).exp(), (-c * t2 / 2.0).exp());
        let amp = (a / b) * (1.0 + b * ep) * (1.0 + b * em) / (ep - em);
        let d = (a / b) * (1.0 + b * em) / (ep - em);
        amp / (1.0 + b * (-c * (t - t1 - t2 / 2.0)).exp()) - d
    }

    #[test]
    fn ends_exact_for_every_table_row() {
        let rows = every_row_sigmoid();
        assert_eq!(rows.len(), 8 + 16);
        for s in rows {
            // the middle piece itself evaluated at its ends
            let mid = |t: f64| {
                let tau = t - s.wait - 0.5 * s.moving;
                s.amp() / (1.0 + s.b * (-s.c * tau).exp()) - s.d()
            };
            assert!(mid(s.t1()).abs() < 1e-9, "{s:?}: f(t1) = {}", mid(s.t1()));
            assert!((mid(s.t2()) - s.a).abs() < 1e-9, "{s:?}: f(t2)");
            assert!(s.position(s.t1()).abs() < 1e-9 && (s.position(s.t2()) - s.a).abs() < 1e-9);
            assert!(s.position(s.t1() + 1e-9).abs() < 1e-6);
            assert!((s.position(s.t2() - 1e-9) - s.a).abs() < 1e-6);
            assert_eq!(s.position(s.t3()), s.a);
            // and the implementation equals the printed formula inside
            for i in 1..100 {
                let t = s.t1() + s.moving * i as f64 / 100.0;
                let want = spec_t1(s.a, s.b, s.c, s.wait, s.moving, t);
                assert!((s.position(t) - want).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn symmetric_when_b_is_one() {
        for s in every_row_sigmoid().into_iter().filter(|s| s.b == 1.0) {
            let mid = s.wait + 0.5 * s.moving;
            for i in 0..=50 {
                let u = 0.5 * s.moving * i as f64 / 50.0;
                let sum = s.position(mid + u) + s.position(mid - u);
                assert!((sum - s.a).abs() < 1e-9, "{s:?} u={u}");
            }
        }
    }

    #[test]
    fn monotone_and_velocity_is_derivative() {
        for s in every_row_sigmoid() {
            let sign = s.a.signum();
            let mut last = f64::NEG_INFINITY;
            for i in 0..=1000 {
                let t = s.t3() * i as f64 / 1000.0;
                let p = sign * s.position(t);
                assert!(p >= last - 1e-15, "{s:?} not monotone at {t}");
                last = p;
                assert!(sign * s.velocity(t) >= 0.0);
            }
            let h = 1e-6;
            for i in 1..100 {
                let t = s.t1() + s.moving * i as f64 / 100.0;
                let fd = (s.position(t + h) - s.position(t - h)) / (2.0 * h);
                assert!((fd - s.velocity(t)).abs() < 1e-6);
            }
        }
    }

    #[test]
    fn eye_is_gaze_minus_head() {
        for r in TABLE_TEST2 {
            let g = r.gaze_shift();
            for i in 0..=200 {
                let t = g.end() * i as f64 / 200.0;
                let s = g.sample(t);
                assert_eq!(s.eye, s.gaze - s.head);
                assert_eq!(s.eye_rate, s.gaze_rate - s.head_rate);
            }
            let end = g.sample(g.end());
            let want = DVec2::new(r.target_deg.0, r.target_deg.1);
            assert!((end.gaze - want * std::f64::consts::PI / 180.0).length() < 1e-12);
        }
    }

    #[test]
    fn linear_baseline_endpoints_and_constant_speed() {
        for s in every_row_sigmoid() {
            let l = s.linear();
            assert_eq!(l.position(s.t1()), 0.0);
            assert!((l.position(s.t2()) - s.a).abs() < 1e-15);
            assert_eq!(l.position(s.t3()), s.a);
            let mid = s.t1() + 0.3 * s.moving;
            assert!((l.velocity(mid) - s.a / s.moving).abs() < 1e-15);
            assert!((l.position(mid) - 0.3 * s.a).abs() < 1e-12);
        }
        let g = TABLE_TEST2[1].gaze_shift();
        let lin = g.linear_baseline();
        let (a, b) = (g.sample(g.end()), lin.sample(lin.end()));
        assert!((a.head - b.head).length() < 1e-12 && (a.gaze - b.gaze).length() < 1e-12);
        assert_eq!(lin.sample(0.0).head, DVec2::ZERO);
    }

    #[test]
    fn offset_is_added() {
        let r = TABLE1_HEAD_FITS[0];
        let tr = r.track();
        assert!((tr.position(0.0) - 2.6f64.to_radians()).abs() < 1e-15);
        assert!((tr.position(tr.end()) - (2.6f64 - 17.3).to_radians()).abs() < 1e-12);
    }

    #[test]
    fn presets_reach_their_targets() {
        let target = DVec2::new(30.0, 20.0);
        let rad = target * std::f64::consts::PI / 180.0;
        for p in [
            Preset::Dialogue,
            Preset::UpwardGlance,
            Preset::Surprised,
            Preset::Eerie,
            Preset::WindUp,
            Preset::LookUpFromDesk,
        ] {
            let g = p.build(target);
            let end = g.sample(g.end());
            assert!(
                (end.gaze - rad).length() < 1e-9,
                "{p:?} gaze ends on target"
            );
            assert!(
                end.head.x.abs() <= rad.x.abs() + 1e-12,
                "{p:?} head does not overshoot"
            );
            assert!((end.eye - (end.gaze - end.head)).length() < 1e-15);
        }
        // wind-up turns away first
        let w = Preset::WindUp.build(target);
        assert!(w.sample(0.3).head.x < 0.0 && w.sample(0.3).gaze.x < 0.0);
        // upward glance: the eyes carry most of the elevation
        let u = Preset::UpwardGlance.build(target).sample(2.0);
        assert!(u.eye.y > u.head.y);
        // look up from desk: the eyes first counter-rotate, then lead
        let d = Preset::LookUpFromDesk.build(target);
        assert!(d.sample(0.35).eye.y < 0.0 && d.sample(0.9).eye.y > 0.0);
    }

    #[test]
    fn sigmoid_deserialises() {
        let s: Sigmoid = ron::from_str("(a: 0.5, c: 4.0)").unwrap();
        assert_eq!((s.a, s.b, s.c), (0.5, 1.0, 4.0));
        assert!(ron::from_str::<Sigmoid>("(b: 0.0)").is_err());
        let g: GazeShift = ron::from_str("(head_yaw: (segments: [Sigmoid((a: 0.3))]))").unwrap();
        assert_eq!(g.head_yaw.segments.len(), 1);
    }
}
