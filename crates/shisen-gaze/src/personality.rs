//! The VH's personality (gaze.md 5, 9): how strongly each action's
//! top-down request pulls the gaze, and the amounts between which the head
//! law (M8) goes from barely turning to facing the target.

use serde::{Deserialize, Serialize};

/// The personality amounts (gaze.md 5, 9): top-down attention per action
/// and the head-movement law's A1, A2.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(default, deny_unknown_fields)]
pub struct Personality {
    /// Top-down amount while idle (look at the opponent's face).
    #[serde(deserialize_with = "amount")]
    pub a_face: f64,
    /// Top-down amount of the attack target.
    #[serde(deserialize_with = "amount")]
    pub a_attack: f64,
    /// Top-down amount of the guarded point.
    #[serde(deserialize_with = "amount")]
    pub a_guard: f64,
    /// Attention amount at which the head moves least (M8).
    #[serde(deserialize_with = "amount")]
    pub a1: f64,
    /// Attention amount at which the head moves most (M8); must exceed `a1`.
    #[serde(deserialize_with = "amount")]
    pub a2: f64,
    /// Share of punches at the head the VH evades (slips, ducks, leans
    /// away from) rather than blocks, 0-1. Default 0.7. A strong boxer
    /// slips and counters; a weak one covers up.
    #[serde(deserialize_with = "share")]
    pub evade: f64,
    /// Chance the VH counters out of a slip, 0-1. Default 0.3.
    #[serde(deserialize_with = "share")]
    pub counter: f64,
}

fn share<'de, D: serde::Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    crate::util::check::in_range(d, 0.0, 1.0)
}

/// An attention amount: 0-100 (the seed's amounts are 1.5 and 3; saliency
/// scores are m/s and rad/s, rarely above 20).
fn amount<'de, D: serde::Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    crate::util::check::in_range(d, 0.0, 100.0)
}

impl Default for Personality {
    /// The original implementation's amounts (gaze.md 11): face 1.5,
    /// attack and guard 3.0. With A1 = 0 and A2 = 3, (M8) turns the head
    /// fully toward attack and guard points and stops it 15 deg short of
    /// the face.
    fn default() -> Self {
        Personality {
            a_face: 1.5,
            a_attack: 3.0,
            a_guard: 3.0,
            a1: 0.0,
            a2: 3.0,
            evade: 0.7,
            counter: 0.3,
        }
    }
}
