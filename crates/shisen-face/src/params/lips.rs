//! How the lips hold together (`lips` in the muscle database).

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// How the lips hold together over an opening jaw (O1,
/// docs/model/face.md; user-editable, `lips` in the muscle database).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LipParams {
    /// Orbicularis oris contraction at which the lips are pressed fully
    /// together (AU 24, the lip presser, is that muscle's marginal part:
    /// Ekman, Friesen & Hager 2002, FACS Manual), or `None` for the
    /// thesis's lips, which part with the jaw whatever the muscle does.
    /// Default `Some(0.4)` (our choice: the thesis's anger, 0.46, presses
    /// them shut). More than 0 and at most 1 (a contraction is a
    /// fraction of the muscle's full pull).
    #[serde(default = "default_seal_k")]
    #[schemars(range(max = 1.0), extend("exclusiveMinimum" = 0.0))]
    pub seal_k: Option<f64>,
    /// Widest opening between the lips' middles that pressed lips close,
    /// metres: the lips stretch over some millimetres of the jaw's
    /// opening and no more (a relaxed interlabial gap up to about 4 mm
    /// still counts as competent lips, closed with light effort: Burstone
    /// 1967, Am. J. Orthod. 53:262). Default 0.008 (our choice: twice
    /// that, under a strong contraction); a wider opening parts them by
    /// the rest, so a pursed mouth still opens round. More than 0 and at
    /// most 0.03 (seven times Burstone's gap).
    #[serde(default = "default_seal_max_gap")]
    #[schemars(range(max = 0.03), extend("exclusiveMinimum" = 0.0))]
    pub seal_max_gap_m: f64,
    /// Share of orbicularis oris's pull across the mouth's width that
    /// moves the lips, 0-1, or `None` for the thesis's ring (F6), which
    /// draws the corners in as far as it presses the lips together, so
    /// that its anger (0.46) purses the mouth to half its width. The
    /// corners are held at the modiolus, where the cheek's muscles meet the
    /// ring (Standring 2016, Gray's Anatomy 41st ed., ch. 30); pulling them
    /// in is the lip pucker, AU 18, of the incisivus muscles, while the
    /// lip tightener, AU 23, narrows the red of the lips and leaves the
    /// mouth's width nearly as it was (Ekman, Friesen & Hager 2002, FACS
    /// Manual). Default `Some(0.3)` (our choice: a full AU 23 then brings
    /// each corner in about 3 mm).
    #[serde(default = "default_oris_width_share")]
    #[schemars(range(min = 0.0, max = 1.0))]
    pub oris_width_share: Option<f64>,
}

fn default_seal_k() -> Option<f64> {
    Some(0.4)
}

fn default_seal_max_gap() -> f64 {
    0.008
}

fn default_oris_width_share() -> Option<f64> {
    Some(0.3)
}

impl Default for LipParams {
    fn default() -> Self {
        Self {
            seal_k: default_seal_k(),
            seal_max_gap_m: default_seal_max_gap(),
            oris_width_share: default_oris_width_share(),
        }
    }
}
