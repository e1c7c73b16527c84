//! The reflexes' timing and strength (`reflex` in the muscle database);
//! the reflexes themselves run in [`crate::reflex`].

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Timing and strength of the reflexes (`reflex` in the muscle database).
/// Latencies are at most 1 s (a reflex's are tens of milliseconds; a
/// second covers a slowed or distracted subject), the wince's phases at
/// most 5 s (ten times the startle pattern's half second).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct ReflexParams {
    /// Whether the face reacts to blows and threats at all (off in the
    /// seed's face).
    pub enabled: bool,
    /// From a blow to the head to the reflex blink's start, s, 0-1.
    /// Default 0.03 (Rushworth 1962: the late response, R2, at 23-46 ms).
    #[schemars(range(min = 0.0, max = 1.0))]
    pub blink_latency: f64,
    /// From a glove seen closing on the eyes to the blink's start, s, 0-1.
    /// Default 0.05 (visually evoked blinks' earliest components come at
    /// about 50 ms: Rushworth 1962).
    #[schemars(range(min = 0.0, max = 1.0))]
    pub threat_blink_latency: f64,
    /// A seen glove is a threat to the eyes when it would reach the head
    /// within this long at its closing speed, s, 0-1. Default 0.15 (our
    /// choice: a blink must start before contact to matter; a punch
    /// crosses its reach in a few tenths of a second).
    #[schemars(range(min = 0.0, max = 1.0))]
    pub threat_time_to_contact: f64,
    /// A threat blinks only this long after the last reflex blink, s,
    /// 0-60. Default 5: the blink reflex's late response is depressed for
    /// seconds after a preceding one (its recovery cycle to paired
    /// stimuli: Kimura 1973, Brain 96:87), and repeated threats habituate;
    /// a minute, a round's third, covers slow habituation.
    #[schemars(range(min = 0.0, max = 60.0))]
    pub threat_refractory: f64,
    /// From a blow to the wince's start, s, 0-1. Default 0.08 (within
    /// 200 ms: Ekman, Friesen & Simons 1985).
    #[schemars(range(min = 0.0, max = 1.0))]
    pub wince_onset: f64,
    /// The wince's rise to its peak, s, 0.001-5 (it divides the wince's
    /// level, so not 0). Default 0.1.
    #[schemars(range(min = 0.001, max = 5.0))]
    pub wince_rise: f64,
    /// How long the peak is held, s, 0-5. Default 0.25.
    #[schemars(range(min = 0.0, max = 5.0))]
    pub wince_hold: f64,
    /// The wince's release, s, 0.001-5 (it divides the wince's level, so
    /// not 0). Default 0.5 (the startle pattern lasts about 0.5 s: Landis
    /// & Hunt 1939).
    #[schemars(range(min = 0.001, max = 5.0))]
    pub wince_release: f64,
    /// Blow impulse that gives a full wince, N s, 0.1-1000. Default 15 (a
    /// committed jab: Walilko, Viano & Bir 2005's punch mass at 7 m/s);
    /// the bounds are a touch and some sixty committed jabs at once.
    #[schemars(range(min = 0.1, max = 1000.0))]
    pub full_impulse: f64,
}

impl Default for ReflexParams {
    fn default() -> Self {
        ReflexParams {
            enabled: true,
            blink_latency: 0.03,
            threat_blink_latency: 0.05,
            threat_time_to_contact: 0.15,
            threat_refractory: 5.0,
            wince_onset: 0.08,
            wince_rise: 0.1,
            wince_hold: 0.25,
            wince_release: 0.5,
            full_impulse: 15.0,
        }
    }
}
