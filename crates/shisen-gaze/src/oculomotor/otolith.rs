//! The otolith-driven eye reflexes (docs/model/gaze.md "Human timing", H8
//! and H9): the translational VOR and ocular counter-roll.
//!
//! - **Translational VOR** (H8). Where the eyes must point to hold a target
//!   while the head translates is geometry: gaze.md's M7 note says it
//!   "falls out" when each eye's error is taken from the target's direction
//!   seen from the moving eye, and the seed does exactly that, at once and
//!   in full. A person does not: the otoliths report the head's translation
//!   about 20 ms late (19 +- 5 ms at 15 cm, 20 +- 12 ms at 30 cm: Ramat &
//!   Zee 2003, J. Neurophysiol. 90:887), and the eyes turn only about 0.6 of
//!   what the geometry asks (median velocity gains 0.52 at 15 cm and 0.62
//!   at 30 cm, Ramat & Zee 2003; about 0.6 for near and far targets, Liao
//!   et al. 2008, Exp. Brain Res. 185:553). Since the ideal rotation is the
//!   translation across the line of sight over the viewing distance, that
//!   fraction scales with 1/distance, as the human tVOR does with vergence.
//!   Here the laws compute each eye's goal from where the eye is *felt*
//!   to be: its position `tvor_latency` ago, less the part of the
//!   translation since then that the reflex misses,
//!
//!   ```text
//!   felt_k(t) = c_k(t - L) - m(t)
//!   dm/dt     = (1 - g) dc(t - L)/dt - m(t - L_v) / tau_v
//!   ```
//!
//!   with `c_k` eye `k`'s centre, `g` the tVOR gain; vision makes the
//!   shortfall up once it sees it, `L_v` later (smooth pursuit's latency,
//!   about 100 ms: Carl & Gellman 1987), over `tau_v`. A saccade
//!   re-anchors the gaze (`m = 0`), and one starts when the error outlives
//!   the corrective latency (H7; Ramat & Zee's compensatory saccades came
//!   145-165 ms after onset).
//!
//! - **Ocular counter-roll** (H9). A head rolled about the line of sight
//!   turns the eyes the other way about it: during the roll by 40-70 % of
//!   the head's motion, and held at about 10 % of a steady tilt (Collewijn
//!   et al. 1985, Exp. Brain Res. 59:185),
//!
//!   ```text
//!   d tau/dt = -g_dyn w_roll - (tau + g_static phi) / T
//!   ```
//!
//!   with `phi` the head's roll from upright, `w_roll` its rate about the
//!   naso-occipital axis (both as the vestibular signal reports them, H4),
//!   and the torsion `tau` kept within `torsion_range`. Torsion turns the
//!   eye about its own line of sight, so it moves no line of sight: the
//!   yaw and pitch goals are already computed in the (felt, rolled) head
//!   frame, which is where a roll changes where the eyes must point. The
//!   torsion is an output (the trace's `torsion`) for renderers and
//!   measurements; the eye joints have two degrees of freedom.
//!
//! With [`OtolithParams::seed`] the eyes are felt where they are and there
//! is no counter-roll: the seed's laws exactly.

use glam::{DQuat, DVec3};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::util::delay::DelayLine;

/// Parameters of the otolith reflexes (scene `vh.oculomotor.otolith`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct OtolithParams {
    /// Delay of the otolith signal into the translational VOR (H8), s.
    /// Default 0.019 (Ramat & Zee 2003: 19 +- 5 ms). 0-0.2 s, ten times
    /// the human latency.
    #[schemars(range(min = 0.0, max = 0.2))]
    pub tvor_latency: f64,
    /// Share of the geometrically required eye rotation the translational
    /// VOR delivers (H8), 0-1. Default 0.6 (Ramat & Zee 2003: 0.52-0.62;
    /// Liao et al. 2008: about 0.6); 1 is the geometric ideal.
    #[schemars(range(min = 0.0, max = 1.0))]
    pub tvor_gain: f64,
    /// How late vision sees what the translational VOR missed (H8), s.
    /// Default 0.1 (smooth pursuit's latency, about 100 ms: Carl & Gellman
    /// 1987, J. Neurophysiol. 57:1446). 0-1 s.
    #[schemars(range(min = 0.0, max = 1.0))]
    pub visual_latency: f64,
    /// Time constant over which vision then takes the shortfall up (H8),
    /// s. Default 0.2 (our choice: at most a fifth of it per 40 ms, a
    /// well-damped loop behind the 100 ms latency). Above 0, at most 10 s,
    /// and above `visual_latency` / (pi/2), where the delayed loop turns
    /// unstable.
    #[schemars(range(max = 10.0), extend("exclusiveMinimum" = 0.0))]
    pub tvor_visual: f64,
    /// Counter-roll held at a steady head tilt, a share of the tilt (H9),
    /// 0-1. Default 0.1 (Collewijn et al. 1985: about 10 % up to 20 deg).
    #[schemars(range(min = 0.0, max = 1.0))]
    pub counter_roll_static: f64,
    /// Counter-roll while the head rolls, a share of the roll rate (H9),
    /// 0-1. Default 0.5 (Collewijn et al. 1985: 40 % to over 70 % during
    /// voluntary roll at 0.16-1.33 Hz).
    #[schemars(range(min = 0.0, max = 1.0))]
    pub counter_roll_dynamic: f64,
    /// Time constant with which the torsion settles to its static share
    /// once the roll stops (H9), s. Default 0.3 (our choice: Collewijn et
    /// al. found little torsion left once the head had come to rest).
    /// Above 0, at most 10 s.
    #[schemars(range(max = 10.0), extend("exclusiveMinimum" = 0.0))]
    pub counter_roll_settle: f64,
    /// Largest torsion either way, rad. Default 10 deg (static counter-roll
    /// peaks near 6 deg at a 60-90 deg tilt: Miller 1962, Acta
    /// Otolaryngol. 54:479). 0-0.5 rad (29 deg).
    #[schemars(range(min = 0.0, max = 0.5))]
    pub torsion_range: f64,
}

impl Default for OtolithParams {
    fn default() -> Self {
        OtolithParams {
            tvor_latency: 0.019,
            tvor_gain: 0.6,
            visual_latency: 0.1,
            tvor_visual: 0.2,
            counter_roll_static: 0.1,
            counter_roll_dynamic: 0.5,
            counter_roll_settle: 0.3,
            torsion_range: 10f64.to_radians(),
        }
    }
}

impl OtolithParams {
    /// The cross-field check the ranges cannot make: the delayed visual
    /// loop (H8) is stable only while `tvor_visual` exceeds `visual_latency`
    /// over pi/2.
    pub fn validate(&self) -> Result<(), String> {
        let least = self.visual_latency / std::f64::consts::FRAC_PI_2;
        if self.tvor_visual <= least {
            return Err(format!(
                "must exceed visual_latency / (pi/2) = {least:.3} s (a shorter time constant behind that latency makes the eyes oscillate), got {}",
                self.tvor_visual
            ));
        }
        Ok(())
    }

    /// The seed's geometry: the eyes felt where they are (an ideal,
    /// instantaneous translational VOR) and no counter-roll.
    pub fn seed() -> Self {
        OtolithParams {
            tvor_latency: 0.0,
            tvor_gain: 1.0,
            counter_roll_static: 0.0,
            counter_roll_dynamic: 0.0,
            ..Default::default()
        }
    }
}

/// The otolith reflexes' evolving state.
#[derive(Clone, Debug, Default)]
pub struct Otolith {
    eyes: DelayLine<[DVec3; 2]>,
    /// The cyclopean eye as reported a tick ago.
    last: Option<DVec3>,
    /// The translation the tVOR has missed so far, world (H8).
    missed: DVec3,
    /// What vision sees of it, `visual_latency` late.
    seen_missed: DelayLine<DVec3>,
    /// Ocular torsion, rad (H9).
    torsion: f64,
}

impl Otolith {
    /// Where the eyes are felt to be this tick (H8), world (left, right),
    /// from where they are.
    pub fn felt_eyes(&mut self, p: &OtolithParams, eye_pos: [DVec3; 2], dt: f64) -> [DVec3; 2] {
        let seen = self.eyes.push(eye_pos, p.tvor_latency, dt);
        let mid = (seen[0] + seen[1]) / 2.0;
        if let Some(last) = self.last {
            self.missed += (1.0 - p.tvor_gain) * (mid - last);
        }
        self.last = Some(mid);
        let seen_missed = self.seen_missed.push(self.missed, p.visual_latency, dt);
        self.missed -= seen_missed * (dt / p.tvor_visual).min(1.0);
        seen.map(|c| c - self.missed)
    }

    /// Ocular torsion after this tick (H9), rad, positive about the line of
    /// sight in the sense of a positive head roll (about the head's +Z,
    /// forward); `rot` and `angvel` are the head's as the vestibular signal
    /// reports them (world).
    pub fn counter_roll(&mut self, p: &OtolithParams, rot: DQuat, angvel: DVec3, dt: f64) -> f64 {
        let (left, up, fwd) = (rot * DVec3::X, rot * DVec3::Y, rot * DVec3::Z);
        let roll = left.y.atan2(up.y);
        let rate = angvel.dot(fwd);
        let held = -p.counter_roll_static * roll;
        let d = -p.counter_roll_dynamic * rate - (self.torsion - held) / p.counter_roll_settle;
        self.torsion = (self.torsion + d * dt).clamp(-p.torsion_range, p.torsion_range);
        self.torsion
    }

    /// A saccade re-anchored the gaze to the world: the tVOR has missed
    /// nothing since (H7, H8).
    pub fn anchor(&mut self) {
        self.missed = DVec3::ZERO;
        self.seen_missed.clear();
    }

    /// What the tVOR has missed and vision not yet made up, world m (H8).
    pub fn missed(&self) -> DVec3 {
        self.missed
    }
}

/// How an eye velocity record `actual` follows an `ideal` one sampled
/// every `dt`: the delay (s, up to 100 ticks and half the record) at which
/// they correlate best,
/// and the gain (least squares) at that delay.
pub fn lag_fit(actual: &[f64], ideal: &[f64], dt: f64) -> (f64, f64) {
    let n = actual.len().min(ideal.len());
    let fit = |lag: usize| {
        let (mut ai, mut ii) = (0.0, 0.0);
        for k in lag..n {
            ai += actual[k] * ideal[k - lag];
            ii += ideal[k - lag] * ideal[k - lag];
        }
        (ai / ii.sqrt().max(1e-12), ai / ii.max(1e-12))
    };
    let lag = (0..100.min(n / 2))
        .max_by(|&a, &b| fit(a).0.total_cmp(&fit(b).0))
        .unwrap_or(0);
    (lag as f64 * dt, fit(lag).1)
}

#[cfg(test)]
mod tests;
