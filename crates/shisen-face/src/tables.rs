//! The categorical tables A, B, C of face.md: emotions -> region
//! expressions -> Action Units -> muscles.
//!
//! They are Rust consts, not data: they are the structure of the model
//! (FACS definitions and the thesis's emotion classification), not measured
//! values, and as consts the compiler checks that every emotion, AU and
//! muscle is covered. The measured numbers (table D, influence parameters,
//! blink and durations) are data in `scenes/face/muscles.ron` (see `params.rs`).

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Face regions (face.md 2).
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize, JsonSchema,
)]
pub enum Region {
    /// Brows and forehead.
    Upper,
    /// Eyes and root of the nose.
    Middle,
    /// Mouth, cheeks and jaw.
    Lower,
}

impl Region {
    /// All regions, top to bottom.
    pub const ALL: [Region; 3] = [Region::Upper, Region::Middle, Region::Lower];
}

/// The basic expressions shown by one region (table A letters).
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize, JsonSchema,
)]
pub enum Expression {
    /// Neutral (N in table A): no muscle driven.
    Neutral,
    /// Happiness (H).
    Happiness,
    /// Surprise (Su).
    Surprise,
    /// Fear (F).
    Fear,
    /// Sadness (Sa).
    Sadness,
    /// Disgust (D).
    Disgust,
    /// Anger (A).
    Anger,
}

impl Expression {
    /// The six non-neutral basic expressions (table D column order).
    pub const BASIC: [Expression; 6] = [
        Expression::Happiness,
        Expression::Surprise,
        Expression::Fear,
        Expression::Sadness,
        Expression::Disgust,
        Expression::Anger,
    ];
}

/// Facial Action Units used by the model (tables B, C).
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize, JsonSchema,
)]
pub enum ActionUnit {
    /// Inner brow raiser.
    Au1,
    /// Outer brow raiser.
    Au2,
    /// Brow lowerer.
    Au4,
    /// Upper lid raiser.
    Au5,
    /// Cheek raiser.
    Au6,
    /// Lid tightener.
    Au7,
    /// Nose wrinkler.
    Au9,
    /// Upper lip raiser.
    Au10,
    /// Lip corner puller.
    Au12,
    /// Lip corner depressor.
    Au15,
    /// Lower lip depressor.
    Au16,
    /// Lip stretcher.
    Au20,
    /// Lip tightener.
    Au23,
    /// Jaw drop.
    Au26,
    /// Blink.
    Au45,
}

impl ActionUnit {
    /// All AUs in FACS order.
    pub const ALL: [ActionUnit; 15] = [
        ActionUnit::Au1,
        ActionUnit::Au2,
        ActionUnit::Au4,
        ActionUnit::Au5,
        ActionUnit::Au6,
        ActionUnit::Au7,
        ActionUnit::Au9,
        ActionUnit::Au10,
        ActionUnit::Au12,
        ActionUnit::Au15,
        ActionUnit::Au16,
        ActionUnit::Au20,
        ActionUnit::Au23,
        ActionUnit::Au26,
        ActionUnit::Au45,
    ];

    /// FACS number.
    pub fn number(self) -> u8 {
        use ActionUnit::*;
        match self {
            Au1 => 1,
            Au2 => 2,
            Au4 => 4,
            Au5 => 5,
            Au6 => 6,
            Au7 => 7,
            Au9 => 9,
            Au10 => 10,
            Au12 => 12,
            Au15 => 15,
            Au16 => 16,
            Au20 => 20,
            Au23 => 23,
            Au26 => 26,
            Au45 => 45,
        }
    }

    /// Region the AU belongs to (thesis tables 3.8-3.10).
    pub fn region(self) -> Region {
        use ActionUnit::*;
        match self {
            Au1 | Au2 | Au4 => Region::Upper,
            Au5 | Au6 | Au7 | Au45 => Region::Middle,
            _ => Region::Lower,
        }
    }

    /// Table C: the muscle channels the AU drives.
    pub fn muscles(self) -> &'static [MuscleKind] {
        use ActionUnit::*;
        use MuscleKind::*;
        match self {
            Au1 => &[FrontalisInner],
            Au2 => &[FrontalisMiddle, FrontalisOuter],
            Au4 => &[Corrugator, Procerus],
            Au5 | Au45 => &[OculiUpperPalpebral],
            Au6 => &[OculiOrbital],
            Au7 => &[OculiLowerPalpebral],
            Au9 => &[LevatorAlaequeNasi],
            Au10 => &[LevatorLabiiSuperioris],
            Au12 => &[ZygomaticMajor],
            Au15 => &[DepressorAnguliOris],
            Au16 => &[DepressorLabiiInferioris],
            Au20 => &[Risorius],
            Au23 => &[OrbicularisOris],
            Au26 => &[Jaw],
        }
    }

    /// True for AUs with separate left and right muscles.
    pub fn bilateral(self) -> bool {
        self.muscles().iter().any(|m| m.bilateral())
    }
}

/// Muscle kinds of table D (plus the jaw rotation channel).
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize, JsonSchema,
)]
pub enum MuscleKind {
    /// Frontalis, outer part (linear).
    FrontalisOuter,
    /// Frontalis, middle part (linear).
    FrontalisMiddle,
    /// Frontalis, inner part (linear).
    FrontalisInner,
    /// Corrugator supercilii (linear).
    Corrugator,
    /// Procerus (linear, single, centred).
    Procerus,
    /// Orbicularis oculi, upper palpebral part (sphincter, per eye).
    OculiUpperPalpebral,
    /// Orbicularis oculi, orbital part (half-ellipse sphincter, per eye).
    OculiOrbital,
    /// Orbicularis oculi, lower palpebral part (sphincter, per eye).
    OculiLowerPalpebral,
    /// Levator labii superioris alaeque nasi (linear).
    LevatorAlaequeNasi,
    /// Levator labii superioris (linear).
    LevatorLabiiSuperioris,
    /// Zygomatic major (linear).
    ZygomaticMajor,
    /// Depressor anguli oris (linear).
    DepressorAnguliOris,
    /// Depressor labii inferioris (linear).
    DepressorLabiiInferioris,
    /// Risorius (linear).
    Risorius,
    /// Orbicularis oris (sphincter, single, centred).
    OrbicularisOris,
    /// Jaw rotation in degrees, positive = chin down (not a muscle).
    Jaw,
}

impl MuscleKind {
    /// All kinds in table D order.
    pub const ALL: [MuscleKind; 16] = [
        MuscleKind::FrontalisOuter,
        MuscleKind::FrontalisMiddle,
        MuscleKind::FrontalisInner,
        MuscleKind::Corrugator,
        MuscleKind::Procerus,
        MuscleKind::OculiUpperPalpebral,
        MuscleKind::OculiOrbital,
        MuscleKind::OculiLowerPalpebral,
        MuscleKind::LevatorAlaequeNasi,
        MuscleKind::LevatorLabiiSuperioris,
        MuscleKind::ZygomaticMajor,
        MuscleKind::DepressorAnguliOris,
        MuscleKind::DepressorLabiiInferioris,
        MuscleKind::Risorius,
        MuscleKind::OrbicularisOris,
        MuscleKind::Jaw,
    ];

    /// Left and right copies? (procerus, orbicularis oris and the jaw are single;
    /// the orbicularis oculi parts exist once per eye.)
    pub fn bilateral(self) -> bool {
        !matches!(
            self,
            MuscleKind::Procerus | MuscleKind::OrbicularisOris | MuscleKind::Jaw
        )
    }

    /// True for the Waters linear muscles (the ones with influence parameters).
    pub fn is_linear(self) -> bool {
        !matches!(
            self,
            MuscleKind::OculiUpperPalpebral
                | MuscleKind::OculiOrbital
                | MuscleKind::OculiLowerPalpebral
                | MuscleKind::OrbicularisOris
                | MuscleKind::Jaw
        )
    }

    /// Region of table D.
    pub fn region(self) -> Region {
        use MuscleKind::*;
        match self {
            FrontalisOuter | FrontalisMiddle | FrontalisInner | Corrugator | Procerus => {
                Region::Upper
            }
            OculiUpperPalpebral | OculiOrbital | OculiLowerPalpebral => Region::Middle,
            _ => Region::Lower,
        }
    }
}

/// Table B (Gosselin set) as printed: AUs per basic expression.
pub fn gosselin_aus(e: Expression) -> &'static [ActionUnit] {
    use ActionUnit::*;
    match e {
        Expression::Neutral => &[],
        Expression::Surprise => &[Au1, Au2, Au5, Au26],
        Expression::Fear => &[Au4, Au5, Au7, Au26],
        Expression::Disgust => &[Au4, Au5, Au9, Au10, Au12, Au26],
        Expression::Anger => &[Au4, Au5, Au16, Au20, Au23, Au26],
        Expression::Happiness => &[Au6, Au12, Au26],
        Expression::Sadness => &[Au1, Au4, Au7, Au15, Au26],
    }
}

/// AUs the model actually drives per expression: table B, except disgust.
///
/// **Correction** (documented here, checked by a test against table D):
/// the thesis's own working tables 3.8-3.10 and its muscle database (table D)
/// give disgust AU 7 (lower palpebral, 0.43) and no AU 12 (no zygomatic
/// value), while the printed Gosselin row lists 12 and omits 7. We follow
/// the working tables: disgust = 4, 5, 7, 9, 10, 26. For every other
/// expression this equals [`gosselin_aus`].
pub fn expression_aus(e: Expression) -> &'static [ActionUnit] {
    use ActionUnit::*;
    match e {
        Expression::Disgust => &[Au4, Au5, Au7, Au9, Au10, Au26],
        other => gosselin_aus(other),
    }
}

/// The 35 emotions of table A, each shown by its three regions'
/// expressions (upper: brows and forehead; middle: eyes; lower: mouth,
/// cheeks and jaw), written here as (upper, middle, lower).
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize, JsonSchema,
)]
pub enum Emotion {
    /// Neutral: neutral brows, neutral eyes, neutral mouth (N, N, N).
    Neutral,
    /// Surprise: surprised brows, surprised eyes, surprised mouth (Su, Su, Su).
    Surprise,
    /// Questioning: surprised brows, neutral eyes, neutral mouth (Su, N, N).
    Questioning,
    /// Interest: neutral brows, surprised eyes, neutral mouth (N, Su, N).
    Interest,
    /// Dazed: neutral brows, neutral eyes, surprised mouth (N, N, Su).
    Dazed,
    /// Questioning surprise: surprised brows, surprised eyes, neutral mouth (Su, Su, N).
    QuestioningSurprise,
    /// Astonishment: neutral brows, surprised eyes, surprised mouth (N, Su, Su).
    Astonishment,
    /// Stunned: surprised brows, neutral eyes, surprised mouth (Su, N, Su).
    Stunned,
    /// Fear: fearful brows, fearful eyes, fearful mouth (F, F, F).
    Fear,
    /// Worry: fearful brows, neutral eyes, neutral mouth (F, N, N).
    Worry,
    /// Restrained fear: neutral brows, fearful eyes, neutral mouth (N, F, N).
    RestrainedFear,
    /// Surprise fear fear stronger: surprised brows, fearful eyes, fearful mouth (Su, F, F).
    SurpriseFearFearStronger,
    /// Surprise fear surprise stronger: surprised brows, surprised eyes, fearful mouth (Su, Su, F).
    SurpriseFearSurpriseStronger,
    /// Frightened: fearful brows, fearful eyes, surprised mouth (F, F, Su).
    Frightened,
    /// Disgust: disgusted brows, disgusted eyes, disgusted mouth (D, D, D).
    Disgust,
    /// Contempt: neutral brows, neutral eyes, disgusted mouth (N, N, D).
    Contempt,
    /// Disbelief: surprised brows, disgusted eyes, disgusted mouth (Su, D, D).
    Disbelief,
    /// Anger: angry brows, angry eyes, angry mouth (A, A, A).
    Anger,
    /// Restrained anger: angry brows, neutral eyes, neutral mouth (A, N, N).
    RestrainedAnger,
    /// Anger disgust: angry brows, disgusted eyes, disgusted mouth (A, D, D).
    AngerDisgust,
    /// Exasperation: angry brows, angry eyes, surprised mouth (A, A, Su).
    Exasperation,
    /// Perplexity: angry brows, angry eyes, fearful mouth (A, A, F).
    Perplexity,
    /// Happiness: neutral brows, happy eyes, happy mouth (N, H, H).
    Happiness,
    /// Happy surprise: surprised brows, surprised eyes, happy mouth (Su, Su, H).
    HappySurprise,
    /// Arrogance: neutral brows, happy eyes, disgusted mouth (N, H, D).
    Arrogance,
    /// Hidden anger: neutral brows, happy eyes, angry mouth (N, H, A).
    HiddenAnger,
    /// Hidden fear: neutral brows, happy eyes, fearful mouth (N, H, F).
    HiddenFear,
    /// Sadness: sad brows, sad eyes, sad mouth (Sa, Sa, Sa).
    Sadness,
    /// Mild sadness: sad brows, sad eyes, neutral mouth (Sa, Sa, N).
    MildSadness,
    /// Restrained sadness: sad brows, neutral eyes, neutral mouth (Sa, N, N).
    RestrainedSadness,
    /// Sadness fear: sad brows, sad eyes, fearful mouth (Sa, Sa, F).
    SadnessFear,
    /// Sadness anger: angry brows, angry eyes, sad mouth (A, A, Sa).
    SadnessAnger,
    /// Determination: sad brows, sad eyes, angry mouth (Sa, Sa, A).
    Determination,
    /// Sadness disgust: sad brows, sad eyes, disgusted mouth (Sa, Sa, D).
    SadnessDisgust,
    /// Hidden sadness: sad brows, sad eyes, surprised mouth (Sa, Sa, Su).
    HiddenSadness,
}

/// Table A rows: (emotion, [upper, middle, lower]).
pub const TABLE_A: [(Emotion, [Expression; 3]); 35] = {
    use Emotion as E;
    use Expression::{
        Anger as A, Disgust as D, Fear as F, Happiness as H, Neutral as N, Sadness as Sa,
        Surprise as Su,
    };
    [
        (E::Neutral, [N, N, N]),
        (E::Surprise, [Su, Su, Su]),
        (E::Questioning, [Su, N, N]),
        (E::Interest, [N, Su, N]),
        (E::Dazed, [N, N, Su]),
        (E::QuestioningSurprise, [Su, Su, N]),
        (E::Astonishment, [N, Su, Su]),
        (E::Stunned, [Su, N, Su]),
        (E::Fear, [F, F, F]),
        (E::Worry, [F, N, N]),
        (E::RestrainedFear, [N, F, N]),
        (E::SurpriseFearFearStronger, [Su, F, F]),
        (E::SurpriseFearSurpriseStronger, [Su, Su, F]),
        (E::Frightened, [F, F, Su]),
        (E::Disgust, [D, D, D]),
        (E::Contempt, [N, N, D]),
        (E::Disbelief, [Su, D, D]),
        (E::Anger, [A, A, A]),
        (E::RestrainedAnger, [A, N, N]),
        (E::AngerDisgust, [A, D, D]),
        (E::Exasperation, [A, A, Su]),
        (E::Perplexity, [A, A, F]),
        (E::Happiness, [N, H, H]),
        (E::HappySurprise, [Su, Su, H]),
        (E::Arrogance, [N, H, D]),
        (E::HiddenAnger, [N, H, A]),
        (E::HiddenFear, [N, H, F]),
        (E::Sadness, [Sa, Sa, Sa]),
        (E::MildSadness, [Sa, Sa, N]),
        (E::RestrainedSadness, [Sa, N, N]),
        (E::SadnessFear, [Sa, Sa, F]),
        (E::SadnessAnger, [A, A, Sa]),
        (E::Determination, [Sa, Sa, A]),
        (E::SadnessDisgust, [Sa, Sa, D]),
        (E::HiddenSadness, [Sa, Sa, Su]),
    ]
};

impl Expression {
    /// Arousal of the expression, 0 (calm) to 1 (most aroused): the
    /// arousal axis of Russell's circumplex (Russell 1980, J. Pers. Soc.
    /// Psychol. 39:1161; placements of Russell & Barrett 1999), rounded.
    pub fn arousal(self) -> f64 {
        match self {
            Expression::Neutral => 0.0,
            Expression::Sadness => 0.2,
            Expression::Happiness => 0.5,
            Expression::Disgust => 0.5,
            Expression::Anger => 0.8,
            Expression::Fear => 0.9,
            Expression::Surprise => 0.9,
        }
    }
}

impl Emotion {
    /// Arousal of the emotion, 0-1: the mean over its three regions'
    /// expressions ([`Expression::arousal`]).
    pub fn arousal(self) -> f64 {
        self.regions().iter().map(|e| e.arousal()).sum::<f64>() / 3.0
    }

    /// Region expressions [upper, middle, lower] (table A).
    pub fn regions(self) -> [Expression; 3] {
        TABLE_A[self as usize].1
    }

    /// All 35 emotions.
    pub fn all() -> impl Iterator<Item = Emotion> {
        TABLE_A.iter().map(|r| r.0)
    }

    /// Parse a script name: the variant name, case-insensitive, with or
    /// without underscores (`hidden_anger`, `HiddenAnger`).
    pub fn parse(name: &str) -> Option<Emotion> {
        let norm: String = name
            .chars()
            .filter(|c| *c != '_' && *c != '-')
            .collect::<String>()
            .to_lowercase();
        Emotion::all().find(|e| format!("{e:?}").to_lowercase() == norm)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_a_is_indexed_by_discriminant() {
        for (i, (e, _)) in TABLE_A.iter().enumerate() {
            assert_eq!(*e as usize, i);
        }
        assert_eq!(
            Emotion::Contempt.regions(),
            [
                Expression::Neutral,
                Expression::Neutral,
                Expression::Disgust
            ]
        );
        assert_eq!(Emotion::parse("hidden_anger"), Some(Emotion::HiddenAnger));
        assert_eq!(Emotion::parse("nope"), None);
    }
}
