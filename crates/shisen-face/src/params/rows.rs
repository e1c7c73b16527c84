//! The schema of the muscle database's rows: table D's (muscle ->
//! contraction) and the FACS prototypes' (AU -> level). The rows
//! themselves are maps; these types only describe them.

use schemars::JsonSchema;

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
pub(super) struct TableDRow {
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
pub(super) struct PrototypeRow {
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
