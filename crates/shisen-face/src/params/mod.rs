//! Measured, user-editable parameters: table D, the influence table, the
//! blink constants and the onset/offset durations, read from RON
//! (`scenes/face/muscles.ron`, embedded as the default).

mod blink;
mod lips;
mod prototypes;
mod reflex;
mod rows;
#[cfg(test)]
mod tests;

pub use blink::BlinkParams;
pub use lips::LipParams;
pub use prototypes::FACS_PROTOTYPES;
pub use reflex::ReflexParams;

use super::tables::{ActionUnit, Expression, MuscleKind};
use prototypes::facs_prototypes;
use rows::{PrototypeRow, TableDRow};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Errors of the face subsystem.
#[derive(Debug, thiserror::Error)]
pub enum FaceError {
    /// The RON parameter file did not parse, or a value in it is out of
    /// range or inconsistent (file, line, column and field included).
    #[error(transparent)]
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
            FaceError::Invalid { field, message } => FaceError::Parse(
                shisen_gaze::util::ron::LoadError::at_field(file, text, field, message),
            ),
            other => other,
        }
    }
}

/// The default parameter file, embedded at compile time.
pub const DEFAULT_RON: &str = include_str!("../../../../scenes/face/muscles.ron");

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
    pub reflex: ReflexParams,
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
            ("lips.oris_width_share", self.lips.oris_width_share),
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
