//! The law itself (T1): one sigmoid move, the linear baseline, an axis
//! track of pieces, and a whole head-and-gaze shift.

use glam::DVec2;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// One sigmoid move (T1), without offset. `a` in rad, `c` in 1/s, times in s.
///
/// Bounds: angles within a half turn; `c` and `T2` small enough that
/// `exp(c T2 / 2)` stays finite (at most exp(500)); times up to 10 s
/// (Takagi & Takeda's moves take 0.4-2.5 s).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct Sigmoid {
    /// Final angle `a` (rad), -3.15 to 3.15 (a half turn either way).
    #[schemars(range(min = -3.15, max = 3.15))]
    pub a: f64,
    /// Asymmetry `b`: 1 symmetric, < 1 slow start / fast end, > 1 the
    /// reverse; 0.01-100 (the published fits use 0.5-4).
    #[schemars(range(min = 0.01, max = 100.0))]
    pub b: f64,
    /// Steepness `c` (1/s); small is nearly linear. 0.01-100 (the
    /// published fits use 1.5-16).
    #[schemars(range(min = 0.01, max = 100.0))]
    pub c: f64,
    /// `T1`, wait before moving (s), 0-10.
    #[schemars(range(min = 0.0, max = 10.0))]
    pub wait: f64,
    /// `T2`, moving time (s), 0.01-10.
    #[schemars(range(min = 0.01, max = 10.0))]
    pub moving: f64,
    /// `T3`, hold after arriving (s), 0-10.
    #[schemars(range(min = 0.0, max = 10.0))]
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

/// Takagi & Takeda's "linear model": constant angular velocity from `t1`
/// to `t2`. Bounds as `Sigmoid`'s.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct Linear {
    /// Final angle (rad), -3.15 to 3.15 (a half turn either way).
    #[schemars(range(min = -3.15, max = 3.15))]
    pub a: f64,
    /// Wait (s), 0-10.
    #[schemars(range(min = 0.0, max = 10.0))]
    pub wait: f64,
    /// Moving time (s), 0.01-10.
    #[schemars(range(min = 0.01, max = 10.0))]
    pub moving: f64,
    /// Hold (s), 0-10.
    #[schemars(range(min = 0.0, max = 10.0))]
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
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
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
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct AxisTrack {
    /// Angle added throughout (rad), -3.15 to 3.15 (a half turn either way).
    #[schemars(range(min = -3.15, max = 3.15))]
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
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
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
