//! The basic expressions as FACS prototypes (face.md F10), the human
//! profile's default.

use std::collections::BTreeMap;

use crate::tables::{ActionUnit, Expression};

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

pub(super) fn facs_prototypes() -> Option<BTreeMap<Expression, BTreeMap<ActionUnit, f64>>> {
    Some(
        FACS_PROTOTYPES
            .iter()
            .map(|(e, aus)| (*e, aus.iter().copied().collect()))
            .collect(),
    )
}
