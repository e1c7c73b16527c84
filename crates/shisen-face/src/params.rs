//! Measured, user-editable parameters: table D, the influence table, the
//! blink constants and the onset/offset durations, read from RON
//! (`scenes/face/muscles.ron`, embedded as the default).

use super::tables::{ActionUnit, Expression, MuscleKind};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Errors of the face subsystem.
#[derive(Debug, thiserror::Error)]
pub enum FaceError {
    /// The RON parameter file did not parse, or a value in it is out of
    /// range or inconsistent (file, line, column and field included).
    #[error("{0}")]
    Parse(#[from] shisen_gaze::util::ron::LoadError),
    /// A parameter value of a database not read from a file (a
    /// calibration's result, parameters built in code) is out of range or
    /// inconsistent.
    #[error("invalid parameters: {field}: {message}")]
    Invalid {
        /// Dotted path of the field at fault (`blink.gaze_trigger_max_deg`,
        /// `onset.Fear.upper`, `expressions.Neutral`).
        field: String,
        /// What is wrong.
        message: String,
    },
    /// A head mesh or landmark file could not be imported (file named).
    #[error("import: {0}")]
    Import(String),
}

impl FaceError {
    /// A value at `field` that is out of range or inconsistent.
    pub fn invalid(field: impl Into<String>, message: impl Into<String>) -> FaceError {
        FaceError::Invalid {
            field: field.into(),
            message: message.into(),
        }
    }

    /// An [`FaceError::Invalid`] about a database read from `text` in
    /// `file`: the same error at the field's line and column
    /// ([`shisen_gaze::util::locate`]), as a [`FaceError::Parse`]. Other
    /// errors are returned unchanged.
    pub fn located(self, text: &str, file: &std::path::Path) -> FaceError {
        match self {
            FaceError::Invalid { field, message } => {
                let (line, col) = shisen_gaze::util::locate::locate(text, &field);
                FaceError::Parse(shisen_gaze::util::ron::LoadError::Invalid {
                    file: file.display().to_string(),
                    line,
                    col,
                    field,
                    message,
                })
            }
            other => other,
        }
    }
}

/// The default parameter file, embedded at compile time.
pub const DEFAULT_RON: &str = include_str!("../../../scenes/face/muscles.ron");

/// Influence parameters of one linear muscle (face.md influence table).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Influence {
    /// Cone half-angle B, degrees, 1-90 (thesis table 4.2: 23-50): the
    /// angle off the muscle's axis at which its pull fades to 0; wider
    /// than 90 the cone would reach behind the muscle's bony end.
    #[schemars(range(min = 1.0, max = 90.0))]
    pub cone_deg: f64,
    /// rf / rs, the fall-off radius over the muscle's rest length, more
    /// than 1 and at most 5 (thesis table 4.2: 1.3-2.0): the pull fades
    /// from the muscle's skin end to rf; five rest lengths reach across
    /// the face.
    #[schemars(range(max = 5.0), extend("exclusiveMinimum" = 1.0))]
    pub rf_ratio: f64,
}

/// Blink constants (face.md 6 and table D note).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BlinkParams {
    /// AU45 upper palpebral contraction at full closure, more than 0 and
    /// at most 10 (2.9, the thesis's value, table D note; an expression's
    /// contractions are at most 1, and 10 is over three times the
    /// thesis's).
    #[schemars(range(max = 10.0), extend("exclusiveMinimum" = 0.0))]
    pub contraction: f64,
    /// Closing time, s, 0.01-1 (0.080; a spontaneous blink's lid closes
    /// in about a tenth of a second: Evinger, Manning & Sibony 1991,
    /// Invest. Ophthalmol. Vis. Sci. 32:387). The bounds are a frame and
    /// a slow, drowsy blink (our choice).
    #[schemars(range(min = 0.01, max = 1.0))]
    pub close_s: f64,
    /// Opening time, s, 0.01-2 (0.120; the lid reopens more slowly than
    /// it closes: Evinger et al. 1991). The bounds are a frame and a
    /// slow, drowsy reopening (our choice).
    #[schemars(range(min = 0.01, max = 2.0))]
    pub open_s: f64,
    /// Inverse Gaussian mean mu of the spontaneous blink interval, s,
    /// 0.5-60 (4.0). People at rest blink 17 times a minute (3.5 s), in
    /// conversation 26 (2.3 s), reading 4.5 (13 s): Bentivoglio et al.
    /// 1997, Mov. Disord. 12:1028. Half a second (120 a minute) is beyond
    /// any reported mean rate; a minute, a subject who hardly blinks.
    #[schemars(range(min = 0.5, max = 60.0))]
    pub mean_interval_s: f64,
    /// Inverse Gaussian shape lambda, s, 0.5-1000 (13.94). The intervals'
    /// coefficient of variation is sqrt(mu / lambda): 0.54 by default;
    /// the bounds allow a CV from 0.02 to 11 at the default mean.
    #[schemars(range(min = 0.5, max = 1000.0))]
    pub shape_s: f64,
    /// Spontaneous blinks only while the face is neutral (the thesis's
    /// rule). Off by default: people blink whatever they feel.
    #[serde(default)]
    pub neutral_only: bool,
    /// Gaze shifts smaller than this never trigger a blink, degrees,
    /// 0-180 (20: Evinger et al. 1994, Exp. Brain Res. 100:337; 180 is
    /// the largest turn of the gaze there is).
    #[schemars(range(min = 0.0, max = 180.0))]
    pub gaze_trigger_min_deg: f64,
    /// Gaze shifts at least this large always trigger a blink, degrees,
    /// more than 0 and at most 180 (60), and more than
    /// `gaze_trigger_min_deg`.
    #[schemars(range(max = 180.0), extend("exclusiveMinimum" = 0.0))]
    pub gaze_trigger_max_deg: f64,
    /// Upper-lid vertical travel per unit of eyeball vertical travel
    /// (lid follows the eye's pitch), 0-2 (0.8; the upper lid follows the
    /// eye about one to one in vertical saccades: Becker & Fuchs 1988,
    /// J. Neurophysiol. 60:1227).
    #[schemars(range(min = 0.0, max = 2.0))]
    pub lid_follow_gain: f64,
    /// Lower-lid vertical travel per unit of eyeball vertical travel,
    /// 0-2 (0.3 if absent: the lower lid follows the pitch less than the
    /// upper).
    #[serde(default = "default_lower_lid_follow_gain")]
    #[schemars(range(min = 0.0, max = 2.0))]
    pub lower_lid_follow_gain: f64,
    /// How far the lower lid's middle rises per unit contraction of the
    /// orbital orbicularis (AU 6), m: the cheek the muscle raises pushes
    /// the lower lid up and narrows the eye from below, the mark of a
    /// felt smile (Ekman, Friesen & Hager 2002, FACS Manual, AU 6;
    /// Duchenne's smile). Default 0.008: happiness's orbital contraction
    /// (0.25) lifts it 2 mm more than the sphincter's own field does, the
    /// opening closing by about two fifths (our choice); 0 leaves the lid
    /// to the sphincter's field (the seed profile).
    /// 0-0.02: at most 2 cm per unit contraction (the eye's whole opening
    /// is about 1 cm).
    #[serde(default = "default_cheek_lid_rise")]
    #[schemars(range(min = 0.0, max = 0.02))]
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
    /// thesis's lid. More than 0 and at most 30 (five times the default).
    #[serde(default = "default_levator_gain")]
    #[schemars(range(max = 30.0), extend("exclusiveMinimum" = 0.0))]
    pub levator_gain: f64,
    /// Highest the upper lid's mid margin rises above its rest, metres
    /// (L1: the raise saturates smoothly towards it), or `None` for the
    /// thesis's unbounded, linear lid. A lid at rest covers the iris's top
    /// 1-2 mm, its margin 4-5 mm above the corneal reflex (MRD1; the
    /// clinical norm in AAO's Basic and Clinical Science Course, section 7,
    /// Orbit, Eyelids and Lacrimal System); the default
    /// `Some(0.0045)` lets the widest eyes show about 3 mm of white above
    /// the iris (our choice), and keeps a relaxation near -1 (a value the
    /// thesis's subjects chose, appendix A) from folding the lid. More
    /// than 0 and at most 0.02 (the levator's whole excursion, 12-17 mm).
    #[serde(default = "default_levator_max_raise")]
    #[schemars(range(max = 0.02), extend("exclusiveMinimum" = 0.0))]
    pub levator_max_raise_m: Option<f64>,
    /// Blink intervals are stretched by this factor while the VH is
    /// engaged (guarding or attacking): the spontaneous blink rate drops
    /// under visual demand (17 /min at rest against 4.5 /min while
    /// reading, a factor of 3.8: Bentivoglio et al. 1997, Mov. Disord.
    /// 12:1028). Default 3 (gaze-evoked blinks come on top, so the rate
    /// while sparring stays near 10 /min); 1 turns the effect off.
    /// 0.25-10: from four times more blinks (conversation raises the rate
    /// by half, 26 /min: Bentivoglio et al. 1997) to ten times fewer
    /// (more than twice the reading factor).
    #[serde(default = "default_engaged_scale")]
    #[schemars(range(min = 0.25, max = 10.0))]
    pub engaged_interval_scale: f64,
    /// Blink rate rises with arousal: the rate is multiplied by
    /// `1 + arousal_gain x arousal x intensity` (arousal of the emotion,
    /// 0-1, [`crate::tables::Emotion::arousal`]). Spontaneous blink
    /// rate goes up with arousal, anxiety and stress (Stern, Walrath &
    /// Goldstein 1984, Psychophysiology 21:22, a review). Default 0.5
    /// (our choice within that trend); 0 turns it off. 0-3: at most four
    /// times the rate at full arousal (six times the default's rise).
    #[serde(default = "default_arousal_gain")]
    #[schemars(range(min = 0.0, max = 3.0))]
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

fn default_cheek_lid_rise() -> f64 {
    0.008
}

fn default_lower_lid_follow_gain() -> f64 {
    0.3
}

/// Slow and fast bounds of a duration (tables 5.9, 5.10), seconds, each
/// 0.01-30: the thesis's are 0.16-5 s; an expression's change takes from
/// a frame (10 ms) to half a minute (a very slow fade); `upper` at least
/// `lower`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct DurationBounds {
    /// Slow bound (speed 3), s, 0.01-30.
    #[schemars(range(min = 0.01, max = 30.0))]
    pub upper: f64,
    /// Fast bound (speed 1), s, 0.01-30.
    #[schemars(range(min = 0.01, max = 30.0))]
    pub lower: f64,
}

impl DurationBounds {
    /// Typical = exp((ln upper + ln lower) / 2) (face.md 7).
    pub fn typical(&self) -> f64 {
        (self.upper * self.lower).sqrt()
    }
}

/// All measured face parameters (the muscle database,
/// `scenes/face/muscles.ron`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FaceParams {
    /// Table D: per expression, muscle -> contraction, -1 to 1 (a
    /// fraction of the muscle's full pull, negative relaxed below rest
    /// tone), and `Jaw` in degrees, 0-30. `Neutral` drives no muscle.
    #[schemars(with = "BTreeMap<Expression, TableDRow>")]
    pub expressions: BTreeMap<Expression, BTreeMap<MuscleKind, f64>>,
    /// Influence table per linear muscle (every linear muscle must have
    /// one).
    pub influence: BTreeMap<MuscleKind, Influence>,
    /// Blink constants.
    pub blink: BlinkParams,
    /// Table 5.9: neutral -> expression, for every basic expression.
    pub onset: BTreeMap<Expression, DurationBounds>,
    /// Table 5.10 (group 1): expression -> neutral, for every basic
    /// expression.
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
    #[schemars(with = "Option<BTreeMap<Expression, PrototypeRow>>")]
    pub prototypes: Option<BTreeMap<Expression, BTreeMap<ActionUnit, f64>>>,
}

/// One expression's row of table D, as the muscle database writes it
/// (`{ ZygomaticMajor: 0.19, Jaw: 8.1 }`): the muscles it uses, each a
/// contraction from -1 (fully relaxed below rest tone) to 1 (the
/// muscle's full pull), the jaw's opening in degrees. (The schema of
/// [`FaceParams::expressions`]' rows; the rows themselves are maps.
/// Each entry is absent or a finite number, never null: the schema
/// check sees a NaN as null.)
#[derive(JsonSchema)]
#[serde(deny_unknown_fields, rename_all = "PascalCase")]
#[allow(dead_code)]
struct TableDRow {
    /// Frontalis, outer part (linear), -1 to 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "f64", range(min = -1.0, max = 1.0))]
    frontalis_outer: Option<f64>,
    /// Frontalis, middle part (linear), -1 to 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "f64", range(min = -1.0, max = 1.0))]
    frontalis_middle: Option<f64>,
    /// Frontalis, inner part (linear), -1 to 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "f64", range(min = -1.0, max = 1.0))]
    frontalis_inner: Option<f64>,
    /// Corrugator supercilii (linear), -1 to 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "f64", range(min = -1.0, max = 1.0))]
    corrugator: Option<f64>,
    /// Procerus (linear), -1 to 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "f64", range(min = -1.0, max = 1.0))]
    procerus: Option<f64>,
    /// Orbicularis oculi, upper palpebral part, -1 to 1 (negative: the
    /// lid raised, AU 5).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "f64", range(min = -1.0, max = 1.0))]
    oculi_upper_palpebral: Option<f64>,
    /// Orbicularis oculi, orbital part, -1 to 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "f64", range(min = -1.0, max = 1.0))]
    oculi_orbital: Option<f64>,
    /// Orbicularis oculi, lower palpebral part, -1 to 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "f64", range(min = -1.0, max = 1.0))]
    oculi_lower_palpebral: Option<f64>,
    /// Levator labii superioris alaeque nasi (linear), -1 to 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "f64", range(min = -1.0, max = 1.0))]
    levator_alaeque_nasi: Option<f64>,
    /// Levator labii superioris (linear), -1 to 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "f64", range(min = -1.0, max = 1.0))]
    levator_labii_superioris: Option<f64>,
    /// Zygomatic major (linear), -1 to 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "f64", range(min = -1.0, max = 1.0))]
    zygomatic_major: Option<f64>,
    /// Depressor anguli oris (linear), -1 to 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "f64", range(min = -1.0, max = 1.0))]
    depressor_anguli_oris: Option<f64>,
    /// Depressor labii inferioris (linear), -1 to 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "f64", range(min = -1.0, max = 1.0))]
    depressor_labii_inferioris: Option<f64>,
    /// Risorius (linear), -1 to 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "f64", range(min = -1.0, max = 1.0))]
    risorius: Option<f64>,
    /// Orbicularis oris, -1 to 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "f64", range(min = -1.0, max = 1.0))]
    orbicularis_oris: Option<f64>,
    /// Jaw rotation, degrees, 0-30, positive chin down (about 30: a
    /// wide-open mouth; the thesis's widest, surprise, is 14.4).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "f64", range(min = 0.0, max = 30.0))]
    jaw: Option<f64>,
}

/// One expression's FACS prototype, as the muscle database writes it
/// (`{ Au6: 0.8, Au12: 1.0 }`): the AUs it uses, each at a level from 0
/// (absent) to 1 (FACS's maximum intensity, E). (The schema of
/// [`FaceParams::prototypes`]' rows; the rows themselves are maps;
/// each entry absent or a finite number.)
#[derive(JsonSchema)]
#[serde(deny_unknown_fields, rename_all = "PascalCase")]
#[allow(dead_code)]
struct PrototypeRow {
    /// AU 1, inner brow raiser, 0-1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "f64", range(min = 0.0, max = 1.0))]
    au1: Option<f64>,
    /// AU 2, outer brow raiser, 0-1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "f64", range(min = 0.0, max = 1.0))]
    au2: Option<f64>,
    /// AU 4, brow lowerer, 0-1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "f64", range(min = 0.0, max = 1.0))]
    au4: Option<f64>,
    /// AU 5, upper lid raiser, 0-1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "f64", range(min = 0.0, max = 1.0))]
    au5: Option<f64>,
    /// AU 6, cheek raiser, 0-1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "f64", range(min = 0.0, max = 1.0))]
    au6: Option<f64>,
    /// AU 7, lid tightener, 0-1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "f64", range(min = 0.0, max = 1.0))]
    au7: Option<f64>,
    /// AU 9, nose wrinkler, 0-1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "f64", range(min = 0.0, max = 1.0))]
    au9: Option<f64>,
    /// AU 10, upper lip raiser, 0-1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "f64", range(min = 0.0, max = 1.0))]
    au10: Option<f64>,
    /// AU 12, lip corner puller, 0-1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "f64", range(min = 0.0, max = 1.0))]
    au12: Option<f64>,
    /// AU 15, lip corner depressor, 0-1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "f64", range(min = 0.0, max = 1.0))]
    au15: Option<f64>,
    /// AU 16, lower lip depressor, 0-1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "f64", range(min = 0.0, max = 1.0))]
    au16: Option<f64>,
    /// AU 20, lip stretcher, 0-1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "f64", range(min = 0.0, max = 1.0))]
    au20: Option<f64>,
    /// AU 23, lip tightener, 0-1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "f64", range(min = 0.0, max = 1.0))]
    au23: Option<f64>,
    /// AU 26, jaw drop, 0-1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "f64", range(min = 0.0, max = 1.0))]
    au26: Option<f64>,
    /// AU 45, blink, 0-1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "f64", range(min = 0.0, max = 1.0))]
    au45: Option<f64>,
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

    /// Parse and validate a muscle database file; every error, a value
    /// out of its range or fields that disagree, is a
    /// [`FaceError::Parse`] naming the file, line, column and field.
    pub fn parse(text: &str, file: &std::path::Path) -> Result<Self, FaceError> {
        // Ranges are checked against the types' schema while reading.
        let p: FaceParams = shisen_gaze::util::ron::parse_ron(text, file)?;
        p.check_consistency().map_err(|e| e.located(text, file))?;
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

    /// Check every value against its documented range (the same schema a
    /// file is checked against when read) and the fields against each
    /// other, for parameters not read from a file (calibration results,
    /// parameters built in code). The error names the field at fault.
    pub fn validate(&self) -> Result<(), FaceError> {
        if let Some(v) = shisen_gaze::util::schema::violations(self)
            .into_iter()
            .next()
        {
            return Err(FaceError::invalid(v.field, v.message));
        }
        self.check_consistency()
    }

    /// The checks no single field's range makes: the tables are complete,
    /// neutral drives nothing, a slow bound is not faster than the fast
    /// one, the gaze's blink trigger rises with the shift's size.
    fn check_consistency(&self) -> Result<(), FaceError> {
        for (table, rows) in [("onset", &self.onset), ("offset", &self.offset)] {
            if let Some(e) = Expression::BASIC.iter().find(|e| !rows.contains_key(e)) {
                return Err(FaceError::invalid(
                    table,
                    format!("no durations for {e:?} (every basic expression needs them)"),
                ));
            }
        }
        for (table, rows) in [
            ("onset", &self.onset),
            ("offset", &self.offset),
            ("offset_group2", &self.offset_group2),
        ] {
            if let Some((e, b)) = rows.iter().find(|(_, b)| b.upper < b.lower) {
                return Err(FaceError::invalid(
                    format!("{table}.{e:?}.upper"),
                    format!(
                        "the slow bound must be at least the fast one (lower: {}), got {}",
                        b.lower, b.upper
                    ),
                ));
            }
        }
        if self
            .expressions
            .get(&Expression::Neutral)
            .is_some_and(|row| !row.is_empty())
        {
            return Err(FaceError::invalid(
                "expressions.Neutral",
                "Neutral must not drive muscles",
            ));
        }
        if let Some(m) = MuscleKind::ALL
            .iter()
            .find(|m| m.is_linear() && !self.influence.contains_key(m))
        {
            return Err(FaceError::invalid(
                "influence",
                format!("missing {m:?} (every linear muscle needs one)"),
            ));
        }
        // The schema check reads a value as JSON, where NaN and the
        // infinities are written null, which an optional field's `None`
        // also is: it cannot refuse `Some(NaN)`, so this does.
        for (field, v) in [
            ("lips.seal_k", self.lips.seal_k),
            ("blink.levator_max_raise_m", self.blink.levator_max_raise_m),
        ] {
            if let Some(x) = v.filter(|x| !x.is_finite()) {
                return Err(FaceError::invalid(
                    field,
                    format!("must be a finite number (or None), got {x}"),
                ));
            }
        }
        let b = &self.blink;
        if b.gaze_trigger_max_deg <= b.gaze_trigger_min_deg {
            return Err(FaceError::invalid(
                "blink.gaze_trigger_max_deg",
                format!(
                    "must exceed gaze_trigger_min_deg ({}), got {}",
                    b.gaze_trigger_min_deg, b.gaze_trigger_max_deg
                ),
            ));
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
        assert!(e.contains("must be >= 0.01"), "{e}");
        assert!(e.contains("blink.close_s"), "the field is named: {e}");
        let bad = DEFAULT_RON.replace("rf_ratio: 1.3)", "rf_ratio: 0.9)");
        let e = FaceParams::from_ron(&bad).unwrap_err().to_string();
        assert!(e.contains("rf_ratio: must be > 1"), "{e}");
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
            ("6.0", "skin.wrinkle_spacing_m", "must be <= 0.03"),
            (
                "0.006, domain_fade_m: 12.0",
                "skin.domain_fade_m",
                "must be <=",
            ),
            ("0.006, thickening: 1.5", "skin.thickening", "must be <= 1"),
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

    /// The error's `file:line:col: field` for a database with `from`
    /// replaced by `to`.
    fn refusal(from: &str, to: &str) -> String {
        assert!(DEFAULT_RON.contains(from), "{from}");
        let bad = DEFAULT_RON.replacen(from, to, 1);
        FaceParams::parse(&bad, std::path::Path::new("m.ron"))
            .unwrap_err()
            .to_string()
    }

    /// Line of the field at dotted `path` in the shipped database (1-based).
    fn line_of(path: &str) -> usize {
        shisen_gaze::util::locate::locate(DEFAULT_RON, path).0
    }

    /// Every number has a range, and the checks across fields name the
    /// field at fault, at its line.
    #[test]
    fn ranges_and_cross_field_checks_name_the_field() {
        // A blink interval of 1e-300 s once made the scheduler loop
        // forever; a human's is seconds.
        let e = refusal("mean_interval_s: 4.0", "mean_interval_s: 1e-300");
        let at = line_of("blink.mean_interval_s");
        assert!(
            e.starts_with(&format!("m.ron:{at}:"))
                && e.contains("blink.mean_interval_s: must be >= 0.5"),
            "{e}"
        );
        for (from, to, field) in [
            (
                "Jaw: 8.1",
                "Jaw: 80.0",
                "expressions.Happiness.Jaw: must be <= 30",
            ),
            (
                "ZygomaticMajor: 0.19",
                "ZygomaticMajor: 1.9",
                "expressions.Happiness.ZygomaticMajor: must be <= 1",
            ),
            (
                "cone_deg: 35.0",
                "cone_deg: 200.0",
                "cone_deg: must be <= 90",
            ),
            (
                "shape_s: 13.94",
                "shape_s: 1e300",
                "blink.shape_s: must be <= 1000",
            ),
            (
                "lid_follow_gain: 0.8",
                "lid_follow_gain: 1e9",
                "blink.lid_follow_gain: must be <= 2",
            ),
            (
                "Anger: (upper: 3.00",
                "Anger: (upper: 300.0",
                "offset.Anger.upper: must be <= 30",
            ),
        ] {
            let e = refusal(from, to);
            assert!(e.contains(field), "{to}: {e}");
        }
        // Across fields: the field at fault and its line, not line 1.
        let e = refusal("gaze_trigger_max_deg: 60.0", "gaze_trigger_max_deg: 10.0");
        let at = line_of("blink.gaze_trigger_max_deg");
        assert!(
            e.starts_with(&format!("m.ron:{at}:"))
                && e.contains("blink.gaze_trigger_max_deg: must exceed gaze_trigger_min_deg"),
            "{e}"
        );
        let e = refusal(
            "Happiness: {",
            "Neutral: { Jaw: 1.0 },\n        Happiness: {",
        );
        assert!(
            e.contains("expressions.Neutral: Neutral must not drive"),
            "{e}"
        );
        let e = refusal(
            "Surprise: (upper: 1.00, lower: 0.16)",
            "Surprise: (upper: 0.1, lower: 0.16)",
        );
        assert!(e.contains("onset.Surprise.upper: the slow bound"), "{e}");
        let e = refusal("Risorius: (cone_deg: 23.0, rf_ratio: 1.3),", "");
        assert!(e.contains("influence: missing Risorius"), "{e}");
        // Parameters built in code are checked against the same ranges.
        let mut p = FaceParams::default_params();
        assert!(p.validate().is_ok());
        p.blink.mean_interval_s = 1e-300;
        match p.validate().unwrap_err() {
            FaceError::Invalid { field, message } => {
                assert_eq!(field, "blink.mean_interval_s");
                assert!(message.contains(">= 0.5"), "{message}");
            }
            other => panic!("{other}"),
        }
        // A NaN is refused where a map or an option holds it.
        let e = refusal("Jaw: 8.1", "Jaw: NaN");
        assert!(
            e.contains("expressions.Happiness.Jaw: must be a finite number"),
            "{e}"
        );
        let e = refusal("mean_interval_s: 4.0", "mean_interval_s: inf");
        assert!(
            e.contains("blink.mean_interval_s: must be a finite number"),
            "{e}"
        );
        let e = refusal(
            "engaged_interval_scale: 3.0",
            "engaged_interval_scale: 3.0, levator_max_raise_m: Some(NaN)",
        );
        assert!(
            e.contains("blink.levator_max_raise_m: must be a finite number"),
            "{e}"
        );
        // The prototypes' AU levels are 0-1.
        let mut p = FaceParams::default_params();
        p.prototypes
            .as_mut()
            .unwrap()
            .get_mut(&Expression::Fear)
            .unwrap()
            .insert(ActionUnit::Au20, 3.0);
        let e = p.validate().unwrap_err().to_string();
        assert!(e.contains("prototypes.Fear.Au20: must be <= 1"), "{e}");
    }

    /// The schema's rows name exactly the muscles and AUs the tables
    /// define (the rows' keys are checked against them).
    #[test]
    fn schema_rows_match_the_tables() {
        let schema = shisen_gaze::util::schema::schema_of::<FaceParams>();
        let keys = |def: &str| -> Vec<String> {
            let mut k: Vec<String> = schema["$defs"][def]["properties"]
                .as_object()
                .unwrap_or_else(|| panic!("{def}: {schema:#}"))
                .keys()
                .cloned()
                .collect();
            k.sort();
            k
        };
        let names = |it: &mut dyn Iterator<Item = String>| {
            let mut v: Vec<String> = it.collect();
            v.sort();
            v
        };
        assert_eq!(
            keys("TableDRow"),
            names(&mut MuscleKind::ALL.iter().map(|m| format!("{m:?}")))
        );
        assert_eq!(
            keys("PrototypeRow"),
            names(&mut ActionUnit::ALL.iter().map(|a| format!("{a:?}")))
        );
    }
}
