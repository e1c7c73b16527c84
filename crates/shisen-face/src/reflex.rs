//! The face's defensive reflexes: a blink when the head is struck or a
//! glove arrives at the eyes, and a wince after a blow (F9).
//!
//! A blow to the head starts a reflex blink `blink_latency` later (the
//! blink reflex's late, bilateral R2 component comes 23-46 ms after a tap
//! on the glabella: Rushworth 1962, J. Neurol. Neurosurg. Psychiatry
//! 25:93; a sudden fall or noise blinks at about 30 ms: Bisdorff et al.
//! 1994, Electroencephalogr. Clin. Neurophysiol., doi
//! 10.1016/0168-5597(94)90146-5), and a wince: the
//! brow lowered, the lids tightened and the cheeks raised, the nose
//! wrinkled and the lips stretched (AU 4, 6, 7, 9, 10, 20, the actions
//! that make up the pain face: Prkachin 1992, Pain 51:297), rising over
//! `wince_rise` after `wince_onset` (eye tightening, brow lowering and lip
//! stretching come within 200 ms of a startling shot: Ekman, Friesen &
//! Simons 1985, J. Pers. Soc. Psychol. 49:1416), held, then released over
//! `wince_release` (the startle pattern is over in about half a second:
//! Landis & Hunt 1939, The Startle Pattern). Its strength grows with the
//! blow's impulse. A glove closing on the eyes, seen, blinks after
//! `threat_blink_latency`.
//!
//! ```text
//! w(s) = W min(1, s'/rise)                 0 <= s' = s - onset <= rise + hold   (F9)
//! w(s) = W (1 - min_jerk((s' - rise - hold) / release))     after that
//! W = min(1, J / full_impulse)
//! ```

use crate::emotion::{Activation, AuLevels};
use crate::params::FaceParams;
use crate::tables::ActionUnit;

// The reflexes' parameters live with the muscle database's other types
// (`crate::params`); re-exported here, where they are used.
pub use crate::params::ReflexParams;

/// The AUs of the wince and their levels at full strength (Prkachin 1992's
/// pain actions; the lids tighten hardest).
const WINCE: [(ActionUnit, f32); 6] = [
    (ActionUnit::Au4, 0.8),
    (ActionUnit::Au6, 0.7),
    (ActionUnit::Au7, 1.0),
    (ActionUnit::Au9, 0.5),
    (ActionUnit::Au10, 0.4),
    (ActionUnit::Au20, 0.5),
];

/// The reflexes' evolving state.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ReflexState {
    /// Time left until a pending reflex blink, s.
    blink_in: Option<f64>,
    /// Time since the last blow, s, and that blow's strength (0-1).
    wince: Option<(f64, f64)>,
    /// Reflex blinks started so far.
    pub blinks: u64,
    /// Time since the last reflex blink, s (none yet: `None`).
    since_blink: Option<f64>,
}

impl ReflexState {
    /// A blow of `impulse` N s struck the head: a reflex blink and a wince.
    pub fn struck(&mut self, p: &ReflexParams, impulse: f64) {
        if !p.enabled {
            return;
        }
        self.schedule_blink(p.blink_latency);
        let w = (impulse / p.full_impulse).clamp(0.0, 1.0);
        let stronger = self
            .wince
            .is_none_or(|(_, old)| w >= old * self.level_factor(p));
        if stronger {
            self.wince = Some((0.0, w));
        }
    }

    /// A glove seen closing on the eyes: a reflex blink (if none is due).
    pub fn threat(&mut self, p: &ReflexParams) {
        let rested = self.since_blink.is_none_or(|s| s >= p.threat_refractory);
        if p.enabled && rested {
            self.schedule_blink(p.threat_blink_latency);
        }
    }

    fn schedule_blink(&mut self, latency: f64) {
        let due = self.blink_in.map_or(latency, |d| d.min(latency));
        self.blink_in = Some(due);
    }

    /// Advance by `dt`; true when a reflex blink is due now.
    pub fn step(&mut self, p: &ReflexParams, dt: f64) -> bool {
        if let Some(s) = self.since_blink.as_mut() {
            *s += dt;
        }
        if let Some((s, _)) = self.wince.as_mut() {
            *s += dt;
            if *s > p.wince_onset + p.wince_rise + p.wince_hold + p.wince_release {
                self.wince = None;
            }
        }
        match self.blink_in.as_mut() {
            Some(d) if *d <= dt => {
                self.blink_in = None;
                self.blinks += 1;
                self.since_blink = Some(0.0);
                true
            }
            Some(d) => {
                *d -= dt;
                false
            }
            None => false,
        }
    }

    /// The wince's present level relative to its strength, 0-1 (F9).
    fn level_factor(&self, p: &ReflexParams) -> f64 {
        let Some((s, _)) = self.wince else {
            return 0.0;
        };
        let s = s - p.wince_onset;
        if s < 0.0 {
            0.0
        } else if s < p.wince_rise {
            s / p.wince_rise
        } else if s < p.wince_rise + p.wince_hold {
            1.0
        } else {
            let r = (s - p.wince_rise - p.wince_hold) / p.wince_release;
            1.0 - shisen_gaze::util::math::min_jerk(r.min(1.0))
        }
    }

    /// The wince's level now, 0-1.
    pub fn wince(&self, p: &ReflexParams) -> f64 {
        self.wince.map_or(0.0, |(_, w)| w * self.level_factor(p))
    }

    /// The wince's contractions, to add to the expression's.
    pub fn activation(&self, params: &FaceParams) -> Option<Activation> {
        let w = self.wince(&params.reflex) as f32;
        if w <= 0.0 {
            return None;
        }
        let mut au = AuLevels::default();
        for (unit, level) in WINCE {
            au.set(unit, level * w);
        }
        Some(au.activation(params))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(st: &mut ReflexState, p: &ReflexParams, until: f64) -> Option<f64> {
        let dt = 0.001;
        let mut t = 0.0;
        let mut blink = None;
        while t < until {
            if st.step(p, dt) && blink.is_none() {
                blink = Some(t + dt);
            }
            t += dt;
        }
        blink
    }

    /// A blow blinks at the reflex latency and winces, rising then fading.
    #[test]
    fn a_blow_blinks_and_winces() {
        let p = ReflexParams::default();
        let mut st = ReflexState::default();
        st.struck(&p, 15.0);
        let blink = run(&mut st, &p, 0.2).expect("a reflex blink");
        assert!((blink - p.blink_latency).abs() < 0.0015, "{blink}");
        let peak = st.wince(&p);
        assert!((peak - 1.0).abs() < 1e-9, "{peak}");
        run(&mut st, &p, 0.8);
        assert_eq!(st.wince(&p), 0.0, "released");
        assert_eq!(st.blinks, 1);
    }

    /// A light blow winces less; the seed's face does neither.
    #[test]
    fn strength_follows_the_impulse_and_the_seed_is_still() {
        let p = ReflexParams::default();
        let mut st = ReflexState::default();
        st.struck(&p, 3.0);
        run(&mut st, &p, 0.25);
        assert!((st.wince(&p) - 0.2).abs() < 1e-9);
        let off = ReflexParams {
            enabled: false,
            ..p
        };
        let mut st = ReflexState::default();
        st.struck(&off, 15.0);
        st.threat(&off);
        assert_eq!(run(&mut st, &off, 0.5), None);
        assert_eq!(st.wince(&off), 0.0);
    }
}
