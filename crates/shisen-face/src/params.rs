//! Measured, user-editable parameters: table D, the influence table, the
//! blink constants and the onset/offset durations, read from RON
//! (`scenes/face/muscles.ron`, embedded as the default).

use super::tables::{ActionUnit, Expression, MuscleKind};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Errors of the face subsystem.
#[derive(Debug, thiserror::Error)]
pub enum FaceError {
    /// The RON parameter file did not parse (file, line, field included).
    #[error("{0}")]
    Parse(#[from] shisen_gaze::util::ron::LoadError),
    /// A parameter value is out of range or inconsistent.
    #[error("invalid parameters: {0}")]
    Invalid(String),
    /// A head mesh or landmark file could not be imported (file named).
    #[error("import: {0}")]
    Import(String),
}

/// The default parameter file, embedded at compile time.
pub const DEFAULT_RON: &str = include_str!("../../../scenes/face/muscles.ron");

/// Influence parameters of one linear muscle (face.md influence table).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Influence {
    /// Cone half-angle B in degrees.
    #[serde(deserialize_with = "shisen_gaze::util::check::positive")]
    pub cone_deg: f64,
    /// rf / rs (> 1).
    #[serde(deserialize_with = "shisen_gaze::util::check::positive")]
    pub rf_ratio: f64,
}

/// Blink constants (face.md 6 and table D note).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BlinkParams {
    /// AU45 upper palpebral contraction at full closure (2.9).
    #[serde(deserialize_with = "shisen_gaze::util::check::positive")]
    pub contraction: f64,
    /// Closing time, seconds (0.080).
    #[serde(deserialize_with = "shisen_gaze::util::check::positive")]
    pub close_s: f64,
    /// Opening time, seconds (0.120).
    #[serde(deserialize_with = "shisen_gaze::util::check::positive")]
    pub open_s: f64,
    /// Inverse Gaussian mean mu, seconds (4.0).
    #[serde(deserialize_with = "shisen_gaze::util::check::positive")]
    pub mean_interval_s: f64,
    /// Inverse Gaussian shape lambda, seconds (13.94).
    #[serde(deserialize_with = "shisen_gaze::util::check::positive")]
    pub shape_s: f64,
    /// Spontaneous blinks only while the face is neutral (the thesis's
    /// rule). Off by default: people blink whatever they feel.
    #[serde(default)]
    pub neutral_only: bool,
    /// Gaze shifts smaller than this never trigger a blink (degrees).
    #[serde(deserialize_with = "shisen_gaze::util::check::non_negative")]
    pub gaze_trigger_min_deg: f64,
    /// Gaze shifts at least this large always trigger a blink (degrees).
    #[serde(deserialize_with = "shisen_gaze::util::check::positive")]
    pub gaze_trigger_max_deg: f64,
    /// Upper-lid vertical travel per unit of eyeball vertical travel
    /// (lid follows the eye's pitch).
    #[serde(deserialize_with = "shisen_gaze::util::check::non_negative")]
    pub lid_follow_gain: f64,
    /// Lower-lid vertical travel per unit of eyeball vertical travel
    /// (0.3 if absent: the lower lid follows the pitch less than the upper).
    #[serde(
        default = "default_lower_lid_follow_gain",
        deserialize_with = "shisen_gaze::util::check::non_negative"
    )]
    pub lower_lid_follow_gain: f64,
    /// How far the lower lid's middle rises per unit contraction of the
    /// orbital orbicularis (AU 6), m: the cheek the muscle raises pushes
    /// the lower lid up and narrows the eye from below, the mark of a
    /// felt smile (Ekman, Friesen & Hager 2002, FACS Manual, AU 6;
    /// Duchenne's smile). Default 0.008: happiness's orbital contraction
    /// (0.25) lifts it 2 mm more than the sphincter's own field does, the
    /// opening closing by about two fifths (our choice); 0 leaves the lid
    /// to the sphincter's field (the seed profile).
    /// At most 2 cm per unit contraction (the eye's whole opening is
    /// about 1 cm).
    #[serde(
        default = "default_cheek_lid_rise",
        deserialize_with = "cheek_lid_rise"
    )]
    pub cheek_lid_rise_m: f64,
    /// Gain of the upper lid's raise on a relaxation of the upper
    /// palpebral orbicularis (an expression's negative contraction, AU 5;
    /// face.md L1). The thesis codes AU 5 as that muscle relaxing, so the
    /// lid can only travel back along the muscle's own closing path, and
    /// fear's -0.18 lifts it half a millimetre, under the iris's top edge;
    /// the lid is in fact raised by levator palpebrae, which lifts it
    /// 12-17 mm from down- to upgaze (Beard 1981, Ptosis, 3rd ed.). The
    /// raise the relaxation gives on its own is multiplied by this gain
    /// (then bounded by `levator_max_raise_m`). Default 6 (our choice: fear
    /// shows white above the iris, as face.md section 4 asks); 1 is the
    /// thesis's lid.
    #[serde(
        default = "default_levator_gain",
        deserialize_with = "shisen_gaze::util::check::positive"
    )]
    pub levator_gain: f64,
    /// Highest the upper lid's mid margin rises above its rest, metres
    /// (L1: the raise saturates smoothly towards it), or `None` for the
    /// thesis's unbounded, linear lid. A lid at rest covers the iris's top
    /// 1-2 mm, its margin 4-5 mm above the corneal reflex (MRD1; the
    /// clinical norm in AAO's Basic and Clinical Science Course, section 7,
    /// Orbit, Eyelids and Lacrimal System); the default
    /// `Some(0.0045)` lets the widest eyes show about 3 mm of white above
    /// the iris (our choice), and keeps a relaxation near -1 (a value the
    /// thesis's subjects chose, appendix A) from folding the lid.
    #[serde(
        default = "default_levator_max_raise",
        deserialize_with = "shisen_gaze::util::check::opt_positive"
    )]
    pub levator_max_raise_m: Option<f64>,
    /// Blink intervals are stretched by this factor while the VH is
    /// engaged (guarding or attacking): the spontaneous blink rate drops
    /// under visual demand (17 /min at rest against 4.5 /min while
    /// reading, a factor of 3.8: Bentivoglio et al. 1997, Mov. Disord.
    /// 12:1028). Default 3 (gaze-evoked blinks come on top, so the rate
    /// while sparring stays near 10 /min); 1 turns the effect off.
    #[serde(
        default = "default_engaged_scale",
        deserialize_with = "shisen_gaze::util::check::positive"
    )]
    pub engaged_interval_scale: f64,
    /// Blink rate rises with arousal: the rate is multiplied by
    /// `1 + arousal_gain x arousal x intensity` (arousal of the emotion,
    /// 0-1, [`crate::tables::Emotion::arousal`]). Spontaneous blink
    /// rate goes up with arousal, anxiety and stress (Stern, Walrath &
    /// Goldstein 1984, Psychophysiology 21:22, a review). Default 0.5
    /// (our choice within that trend); 0 turns it off.
    #[serde(
        default = "default_arousal_gain",
        deserialize_with = "shisen_gaze::util::check::non_negative"
    )]
    pub arousal_gain: f64,
}

fn default_arousal_gain() -> f64 {
    0.5
}

fn default_engaged_scale() -> f64 {
    3.0
}

fn default_levator_gain() -> f64 {
    6.0
}

fn default_levator_max_raise() -> Option<f64> {
    Some(0.0045)
}

fn cheek_lid_rise<'de, D: serde::Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    shisen_gaze::util::check::in_range(d, 0.0, 0.02)
}

fn default_cheek_lid_rise() -> f64 {
    0.008
}

fn default_lower_lid_follow_gain() -> f64 {
    0.3
}

/// Slow and fast bounds of a duration (tables 5.9, 5.10), seconds.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct DurationBounds {
    /// Slow bound (speed 3).
    #[serde(deserialize_with = "shisen_gaze::util::check::positive")]
    pub upper: f64,
    /// Fast bound (speed 1).
    #[serde(deserialize_with = "shisen_gaze::util::check::positive")]
    pub lower: f64,
}

impl DurationBounds {
    /// Typical = exp((ln upper + ln lower) / 2) (face.md 7).
    pub fn typical(&self) -> f64 {
        (self.upper * self.lower).sqrt()
    }
}

/// All measured face parameters.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FaceParams {
    /// Table D: per expression, muscle -> contraction (Jaw in degrees).
    pub expressions: BTreeMap<Expression, BTreeMap<MuscleKind, f64>>,
    /// Influence table per linear muscle.
    pub influence: BTreeMap<MuscleKind, Influence>,
    /// Blink constants.
    pub blink: BlinkParams,
    /// Table 5.9: neutral -> expression.
    pub onset: BTreeMap<Expression, DurationBounds>,
    /// Table 5.10 (group 1): expression -> neutral.
    pub offset: BTreeMap<Expression, DurationBounds>,
    /// Table 5.10 group 2 where it differs.
    #[serde(default)]
    pub offset_group2: BTreeMap<Expression, DurationBounds>,
    /// How the skin wrinkles when compressed (defaults if absent).
    #[serde(default)]
    pub skin: super::wrinkle::SkinParams,
    /// How the lips hold together (defaults if absent).
    #[serde(default)]
    pub lips: LipParams,
    /// Reflex blinks and the wince at a blow (defaults if absent).
    #[serde(default)]
    pub reflex: crate::reflex::ReflexParams,
    /// The basic expressions as FACS prototypes (face.md F10): per
    /// expression, AU -> level 0-1; each AU drives its muscles at its table
    /// D reference ([`FaceParams::au_reference`]). The human profile's
    /// faces are made from these ([`FACS_PROTOTYPES`] if absent); `None`
    /// (`profile: Seed`) uses table D's expressions directly, as the
    /// thesis does.
    #[serde(default = "facs_prototypes")]
    pub prototypes: Option<BTreeMap<Expression, BTreeMap<ActionUnit, f64>>>,
}

/// The basic emotions' FACS prototypes (F10): EMFACS (Ekman & Friesen;
/// as tabulated in Ekman, Friesen & Hager 2002, FACS Investigator's
/// Guide): happiness 6+12, surprise 1+2+5+26, fear 1+2+4+5+7+20+26, anger
/// 4+5+7+23, sadness 1+4+15, disgust 9+10+15+16 (9 or 10 with 15 or 16;
/// Du, Tao & Martinez 2014, PNAS 111:E1454, find 9 and 10 in people's
/// disgust). Levels are apex intensities, FACS's C-E (0.6-1.0), our
/// reading; jaw drop 26 is small in happiness (lips parted, 25, which the
/// rig has no channel for).
pub const FACS_PROTOTYPES: [(Expression, &[(ActionUnit, f64)]); 6] = {
    use ActionUnit::*;
    [
        (
            Expression::Happiness,
            &[(Au6, 0.8), (Au12, 1.0), (Au26, 0.25)],
        ),
        (
            Expression::Surprise,
            &[(Au1, 1.0), (Au2, 1.0), (Au5, 0.8), (Au26, 0.8)],
        ),
        (
            Expression::Fear,
            &[
                (Au1, 1.0),
                (Au2, 0.7),
                (Au4, 0.45),
                (Au5, 1.0),
                (Au7, 0.3),
                (Au20, 1.0),
                (Au26, 0.45),
            ],
        ),
        (
            Expression::Anger,
            &[(Au4, 1.0), (Au5, 0.6), (Au7, 0.9), (Au23, 1.0)],
        ),
        (Expression::Sadness, &[(Au1, 1.0), (Au4, 0.35), (Au15, 1.0)]),
        (
            Expression::Disgust,
            &[(Au9, 1.0), (Au10, 1.0), (Au15, 0.6), (Au16, 0.5)],
        ),
    ]
};

fn facs_prototypes() -> Option<BTreeMap<Expression, BTreeMap<ActionUnit, f64>>> {
    Some(
        FACS_PROTOTYPES
            .iter()
            .map(|(e, aus)| (*e, aus.iter().copied().collect()))
            .collect(),
    )
}

/// How the lips hold together over an opening jaw (O1,
/// docs/model/face.md; user-editable, `lips` in the muscle database).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct LipParams {
    /// Orbicularis oris contraction at which the lips are pressed fully
    /// together (AU 24, the lip presser, is that muscle's marginal part:
    /// Ekman, Friesen & Hager 2002, FACS Manual), or `None` for the
    /// thesis's lips, which part with the jaw whatever the muscle does.
    /// Default `Some(0.4)` (our choice: the thesis's anger, 0.46, presses
    /// them shut).
    #[serde(
        default = "default_seal_k",
        deserialize_with = "shisen_gaze::util::check::opt_positive"
    )]
    pub seal_k: Option<f64>,
    /// Widest opening between the lips' middles that pressed lips close,
    /// metres: the lips stretch over some millimetres of the jaw's
    /// opening and no more (a relaxed interlabial gap up to about 4 mm
    /// still counts as competent lips, closed with light effort: Burstone
    /// 1967, Am. J. Orthod. 53:262). Default 0.008 (our choice: twice
    /// that, under a strong contraction); a wider opening parts them by
    /// the rest, so a pursed mouth still opens round.
    #[serde(
        default = "default_seal_max_gap",
        deserialize_with = "shisen_gaze::util::check::positive"
    )]
    pub seal_max_gap_m: f64,
}

fn default_seal_k() -> Option<f64> {
    Some(0.4)
}

fn default_seal_max_gap() -> f64 {
    0.008
}

impl Default for LipParams {
    fn default() -> Self {
        Self {
            seal_k: default_seal_k(),
            seal_max_gap_m: default_seal_max_gap(),
        }
    }
}

impl FaceParams {
    /// Parse and validate a RON parameter file.
    pub fn from_ron(text: &str) -> Result<Self, FaceError> {
        Self::parse(text, std::path::Path::new("<muscle database>"))
    }

    /// Parse and validate a muscle database file; errors name the file,
    /// line, column and field.
    pub fn parse(text: &str, file: &std::path::Path) -> Result<Self, FaceError> {
        let p: FaceParams = shisen_gaze::util::ron::parse_ron(text, file)?;
        p.validate()?;
        Ok(p)
    }

    /// The database as a RON file that [`FaceParams::parse`] reads back
    /// (e.g. a recalibrated `muscles.ron`, see `calibrate.rs`).
    pub fn to_ron(&self) -> String {
        let cfg = ron::ser::PrettyConfig::new().indentor("    ".to_string());
        let body = ron::ser::to_string_pretty(self, cfg).expect("plain data serialises");
        format!(
            "// Face muscle database for shisen (face.md), written by \
             FaceParams::to_ron.\n{body}\n"
        )
    }

    /// The embedded default (`scenes/face/muscles.ron`).
    pub fn default_params() -> Self {
        Self::from_ron(DEFAULT_RON).expect("embedded scenes/face/muscles.ron is valid")
    }

    /// The shipped database with the thesis's expressions (table D, no
    /// FACS prototypes): what `profile: Seed` and the table's own tests use.
    pub fn thesis_params() -> FaceParams {
        FaceParams {
            prototypes: None,
            ..Self::default_params()
        }
    }

    /// Check every value against its plausible range and the tables for
    /// completeness (files and calibration results alike).
    pub fn validate(&self) -> Result<(), FaceError> {
        let bad = |m: String| Err(FaceError::Invalid(m));
        for e in Expression::BASIC {
            if !self.onset.contains_key(&e) || !self.offset.contains_key(&e) {
                return bad(format!("missing onset/offset durations for {e:?}"));
            }
        }
        for (e, row) in &self.expressions {
            if *e == Expression::Neutral && !row.is_empty() {
                return bad("Neutral must not drive muscles".into());
            }
            for (m, k) in row {
                // Contractions are fractions of the muscle's full pull
                // (negative: relaxed below rest tone); the jaw opens by
                // degrees, up to about 30 (a wide-open mouth).
                let (lo, hi) = if *m == MuscleKind::Jaw {
                    (0.0, 30.0)
                } else {
                    (-1.0, 1.0)
                };
                if !(lo..=hi).contains(k) {
                    return bad(format!("{e:?}.{m:?}: must be in [{lo}, {hi}], got {k}"));
                }
            }
        }
        for m in MuscleKind::ALL.iter().filter(|m| m.is_linear()) {
            match self.influence.get(m) {
                None => return bad(format!("influence: missing {m:?}")),
                Some(i) if i.rf_ratio <= 1.0 => {
                    return bad(format!("influence.{m:?}.rf_ratio must be > 1"));
                }
                Some(i) if i.cone_deg >= 180.0 => {
                    return bad(format!("influence.{m:?}.cone_deg must be < 180"));
                }
                _ => {}
            }
        }
        if self.blink.gaze_trigger_max_deg <= self.blink.gaze_trigger_min_deg {
            return bad("blink.gaze_trigger_max_deg must exceed gaze_trigger_min_deg".into());
        }
        Ok(())
    }

    /// Table D value, if the expression uses the muscle.
    pub fn table_d(&self, e: Expression, m: MuscleKind) -> Option<f64> {
        self.expressions
            .get(&e)
            .and_then(|row| row.get(&m))
            .copied()
    }

    /// Full-strength value of muscle `m` under direct control of `au`: the
    /// table D value of largest magnitude among the expressions that use
    /// the AU (AU45: the blink contraction). `None` if no expression gives one.
    pub fn au_reference(&self, au: ActionUnit, m: MuscleKind) -> Option<f64> {
        if au == ActionUnit::Au45 {
            return Some(self.blink.contraction);
        }
        Expression::BASIC
            .iter()
            .filter(|e| super::tables::expression_aus(**e).contains(&au))
            .filter_map(|e| self.table_d(*e, m))
            .max_by(|a, b| a.abs().total_cmp(&b.abs()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_parses_and_typical_matches_printed() {
        let p = FaceParams::default_params();
        assert_eq!(
            p.table_d(Expression::Surprise, MuscleKind::OculiUpperPalpebral),
            Some(-0.48)
        );
        assert_eq!(p.table_d(Expression::Anger, MuscleKind::Jaw), Some(3.5));
        // Printed typical columns of tables 5.9 / 5.10.
        let on = [
            (Expression::Happiness, 0.60),
            (Expression::Surprise, 0.40),
            (Expression::Anger, 0.50),
            (Expression::Sadness, 0.78),
            (Expression::Fear, 0.63),
            (Expression::Disgust, 0.63),
        ];
        for (e, t) in on {
            assert!((p.onset[&e].typical() - t).abs() < 0.006, "{e:?}");
        }
        let off = [
            (Expression::Happiness, 0.63),
            (Expression::Surprise, 0.71),
            (Expression::Anger, 1.70),
            (Expression::Sadness, 1.31),
            (Expression::Fear, 1.43),
            (Expression::Disgust, 0.97),
        ];
        for (e, t) in off {
            assert!((p.offset[&e].typical() - t).abs() < 0.006, "{e:?}");
        }
        assert!((p.offset_group2[&Expression::Sadness].typical() - 3.95).abs() < 0.006);
        assert_eq!(
            p.au_reference(ActionUnit::Au5, MuscleKind::OculiUpperPalpebral),
            Some(-0.48)
        );
        assert_eq!(
            p.au_reference(ActionUnit::Au45, MuscleKind::OculiUpperPalpebral),
            Some(2.9)
        );
    }

    #[test]
    fn invalid_values_are_rejected_with_position() {
        let bad = DEFAULT_RON.replace("close_s: 0.080", "close_s: -0.080");
        let e = FaceParams::from_ron(&bad).unwrap_err().to_string();
        assert!(e.contains("must be > 0"), "{e}");
        assert!(e.contains("close_s"), "the field is named: {e}");
        let bad = DEFAULT_RON.replace("rf_ratio: 1.3)", "rf_ratio: 0.9)");
        assert!(FaceParams::from_ron(&bad).is_err());
        // The default database with one more top-level field.
        let with = |field: &str| {
            let end = DEFAULT_RON
                .trim_end()
                .strip_suffix(')')
                .expect("a RON struct");
            format!("{end}    {field},\n)\n")
        };
        // Skin fields after the two it needs: W4's are accepted; a
        // spacing in millimetres (not metres), a fade or thickening out of
        // range and a misspelt field are refused by name.
        let with_skin = |more: &str| {
            with(&format!(
                "skin: (wrinkle_onset_strain: 0.25, wrinkle_spacing_m: {more})"
            ))
        };
        assert!(
            FaceParams::from_ron(&with_skin("0.006, thickening: 0.5, domain_fade_m: 0.01")).is_ok()
        );
        for (more, named, why) in [
            ("6.0", "wrinkle_spacing_m", "must be in"),
            ("0.006, domain_fade_m: 12.0", "domain_fade_m", "must be in"),
            ("0.006, thickening: 1.5", "thickening", "must be in"),
            (
                "0.006, thickenning: 0.5",
                "skin.thickenning",
                "Unexpected field",
            ),
        ] {
            let e = FaceParams::from_ron(&with_skin(more))
                .unwrap_err()
                .to_string();
            assert!(e.contains(named) && e.contains(why), "{more}: {e}");
        }
        // The lip seal (O1): a negative or NaN bound is refused, named.
        let with_lips = |lips: &str| with(&format!("lips: ({lips})"));
        let ok = FaceParams::from_ron(&with_lips("seal_k: None")).unwrap();
        assert_eq!(ok.lips.seal_k, None);
        for bad in [
            "seal_max_gap_m: -0.006",
            "seal_k: Some(-0.4)",
            "seal_k: Some(NaN)",
        ] {
            let e = FaceParams::from_ron(&with_lips(bad))
                .unwrap_err()
                .to_string();
            let field = bad.split(':').next().unwrap();
            assert!(e.contains(field), "{bad}: {e}");
        }
    }
}
