//! The VH's personality (gaze.md 5, 9): how strongly each action's
//! top-down request pulls the gaze, and the amounts between which the head
//! law (M8) goes from barely turning to facing the target.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// The personality amounts (gaze.md 5, 9): top-down attention per action
/// and the head-movement law's A1, A2.
///
/// Attention amounts are on the scale of bottom-up saliency (M1), whose
/// scores are speeds in m/s and rad/s, rarely above 20; the seed's amounts
/// are 1.5 and 3. Every amount is bounded at 100, five times any saliency
/// a body reaches.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize, JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct Personality {
    /// Top-down amount while idle (look at the opponent's face), 0-100.
    /// Default 1.5; a strong boxer's 4, a weak one's 0.5.
    #[schemars(range(min = 0.0, max = 100.0))]
    pub a_face: f64,
    /// Top-down amount of the attack target, 0-100. Default 3.
    #[schemars(range(min = 0.0, max = 100.0))]
    pub a_attack: f64,
    /// Top-down amount of the guarded point, 0-100. Default 3.
    #[schemars(range(min = 0.0, max = 100.0))]
    pub a_guard: f64,
    /// Attention amount at which the head moves least (M8), 0-100.
    /// Default 0.
    #[schemars(range(min = 0.0, max = 100.0))]
    pub a1: f64,
    /// Attention amount at which the head moves most (M8), 0-100; must
    /// exceed `a1`. Default 3.
    #[schemars(range(min = 0.0, max = 100.0))]
    pub a2: f64,
    /// Share of punches at the head the VH evades (slips, ducks, leans
    /// away from) rather than blocks, 0-1. Default 0.7. A strong boxer
    /// slips and counters; a weak one covers up. A probability.
    #[schemars(range(min = 0.0, max = 1.0))]
    pub evade: f64,
    /// Chance the VH counters out of a slip or a block, 0-1 (a probability).
    /// Default 0.3.
    #[schemars(range(min = 0.0, max = 1.0))]
    pub counter: f64,
    /// Top-down amount of the visual anchor through an evasion: the
    /// opponent's head, held while the evaded glove passes and watched in
    /// the periphery, 0-100. Martial-arts experts anchor the gaze on the
    /// opponent's head and read the limbs peripherally (Ripoll et al.
    /// 1995, Hum. Mov. Sci. 14:545; Hausegger, Vater & Hossner 2019, J.
    /// Sport Exerc. Psychol. 41:137); a glove passing a slipping head
    /// sweeps across the view faster than an eye can follow. Arbitrated
    /// like every amount (gaze.md 6): below a punch's saliency (about 3-6
    /// for 5-7 m/s jabs) the eyes chase the glove, as a novice's do.
    /// Default 6; a novice's 1, a pro's 8 (our amounts: the studies report
    /// the expert strategy, not amounts).
    #[schemars(range(min = 0.0, max = 100.0))]
    pub a_anchor: f64,
    /// Share of the opponent's body cues (its head stepping in behind a
    /// punch: `behaviour.cue_speed`) the VH acts on before the glove
    /// flies: the guard raised on the side the cue predicts and, from
    /// long range, a step back. 0-1, a probability. Default 0: the seed
    /// reacts to gloves only. Experts anticipate from a body's early
    /// movement, near-experts only once the attack has started, novices
    /// only with the whole action in view (Rosalie & Mueller 2013, Q. J.
    /// Exp. Psychol. 66:1951, karate); the levels set 0 (novice), 0.5
    /// (amateur) and 0.85 (pro), our amounts.
    #[serde(default)]
    #[schemars(range(min = 0.0, max = 1.0))]
    pub anticipation: f64,
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
            a_anchor: 6.0,
            anticipation: 0.0,
        }
    }
}
