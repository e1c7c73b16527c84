//! Muscle channels and the emotion / AU pipeline (face.md 1, tables A-D):
//! emotion + intensity -> region expressions -> AUs -> muscles -> contractions.

use super::params::FaceParams;
use super::tables::{ActionUnit, Emotion, Expression, MuscleKind, Region, expression_aus};

/// Which copy of a muscle.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Side {
    /// Agent's left (+X).
    Left,
    /// Agent's right (-X).
    Right,
    /// Single, centred muscle.
    Centre,
}

/// One muscle channel of the rig.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct MuscleId {
    /// Muscle kind (never `MuscleKind::Jaw`).
    pub kind: MuscleKind,
    /// Copy.
    pub side: Side,
}

/// Number of muscle channels: 13 bilateral kinds x 2 + procerus + orbicularis oris.
pub const N_CHANNELS: usize = 28;

/// All channels in index order (table D order; left before right).
pub fn channels() -> [MuscleId; N_CHANNELS] {
    let mut out = [MuscleId {
        kind: MuscleKind::Procerus,
        side: Side::Centre,
    }; N_CHANNELS];
    let mut i = 0;
    for kind in MuscleKind::ALL
        .into_iter()
        .filter(|k| *k != MuscleKind::Jaw)
    {
        if kind.bilateral() {
            out[i] = MuscleId {
                kind,
                side: Side::Left,
            };
            out[i + 1] = MuscleId {
                kind,
                side: Side::Right,
            };
            i += 2;
        } else {
            out[i] = MuscleId {
                kind,
                side: Side::Centre,
            };
            i += 1;
        }
    }
    out
}

impl MuscleId {
    /// Channel index in [`channels`]; `None` for the jaw or a side the kind lacks.
    pub fn index(self) -> Option<usize> {
        channels().iter().position(|c| *c == self)
    }

    /// The channels of a kind: two for bilateral kinds, one otherwise.
    pub fn of_kind(kind: MuscleKind) -> impl Iterator<Item = MuscleId> {
        channels().into_iter().filter(move |c| c.kind == kind)
    }
}

/// Muscle contractions of every channel plus the jaw angle: what the skin
/// deformation consumes. Plain data; linear operations for blending.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Activation {
    /// Contraction ratio k per channel (index: [`channels`]).
    pub k: [f32; N_CHANNELS],
    /// Jaw rotation in degrees, positive = chin down.
    pub jaw_deg: f32,
}

impl Default for Activation {
    fn default() -> Self {
        Self {
            k: [0.0; N_CHANNELS],
            jaw_deg: 0.0,
        }
    }
}

impl Activation {
    /// Contraction of a channel (0 for an invalid id).
    pub fn get(&self, id: MuscleId) -> f32 {
        id.index().map_or(0.0, |i| self.k[i])
    }

    /// Set every channel of `kind` (both sides) or the jaw to `value`.
    pub fn set_kind(&mut self, kind: MuscleKind, value: f32) {
        if kind == MuscleKind::Jaw {
            self.jaw_deg = value;
        } else {
            for id in MuscleId::of_kind(kind) {
                self.k[id.index().expect("valid channel")] = value;
            }
        }
    }

    /// `self + (other - self) * t`, channel by channel.
    pub fn lerp(&self, other: &Activation, t: f32) -> Activation {
        let mut out = *self;
        for (o, b) in out.k.iter_mut().zip(other.k.iter()) {
            *o += (b - *o) * t;
        }
        out.jaw_deg += (other.jaw_deg - out.jaw_deg) * t;
        out
    }

    /// Channel-wise sum.
    pub fn add(&self, other: &Activation) -> Activation {
        let mut out = *self;
        for (o, b) in out.k.iter_mut().zip(other.k.iter()) {
            *o += b;
        }
        out.jaw_deg += other.jaw_deg;
        out
    }
}

/// Muscle kinds driven by `expression` shown in `region`: its AUs (table B,
/// as corrected in [`expression_aus`]) that belong to the region, through
/// table C, keeping the muscles table D gives a value for.
pub fn region_muscles(
    params: &FaceParams,
    region: Region,
    expression: Expression,
) -> Vec<(MuscleKind, f64)> {
    let mut out = Vec::new();
    for au in expression_aus(expression)
        .iter()
        .filter(|a| a.region() == region)
    {
        for &m in au.muscles() {
            if let Some(k) = params.table_d(expression, m)
                && !out.iter().any(|(x, _)| *x == m)
            {
                out.push((m, k));
            }
        }
    }
    out
}

/// Emotion pipeline (face.md 1): contractions for `emotion` at `intensity`
/// in [0, 1] (clamped), both sides. With FACS prototypes (F10, the human
/// profile) each region takes the AUs acting in it from its expression's
/// prototype, times intensity; without (the seed), table D's values times
/// intensity.
pub fn emotion_activation(params: &FaceParams, emotion: Emotion, intensity: f32) -> Activation {
    let s = intensity.clamp(0.0, 1.0);
    if let Some(protos) = &params.prototypes {
        let mut au = AuLevels::default();
        for (region, expr) in Region::ALL.into_iter().zip(emotion.regions()) {
            for (&unit, &level) in protos.get(&expr).into_iter().flatten() {
                if unit.region() == region {
                    au.set(unit, level as f32 * s);
                }
            }
        }
        return au.activation(params);
    }
    let mut a = Activation::default();
    for (region, expr) in Region::ALL.into_iter().zip(emotion.regions()) {
        for (m, k) in region_muscles(params, region, expr) {
            a.set_kind(m, k as f32 * s);
        }
    }
    a
}

/// Direct AU control: intensity in [0, 1] per AU and side. Single muscles
/// (procerus, orbicularis oris, jaw) take the mean of the two sides.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct AuLevels {
    /// Left-side level per AU (index: position in `ActionUnit::ALL`).
    pub left: [f32; 15],
    /// Right-side level per AU.
    pub right: [f32; 15],
}

impl AuLevels {
    /// Set both sides of `au` to `level`.
    pub fn set(&mut self, au: ActionUnit, level: f32) {
        self.set_sides(au, level, level);
    }

    /// Set left and right levels of `au` separately.
    pub fn set_sides(&mut self, au: ActionUnit, left: f32, right: f32) {
        let i = ActionUnit::ALL
            .iter()
            .position(|a| *a == au)
            .expect("known AU");
        self.left[i] = left.clamp(0.0, 1.0);
        self.right[i] = right.clamp(0.0, 1.0);
    }

    /// Contractions produced by these levels: level times the AU's
    /// reference contraction ([`FaceParams::au_reference`]), summed over AUs.
    pub fn activation(&self, params: &FaceParams) -> Activation {
        let mut a = Activation::default();
        for (i, au) in ActionUnit::ALL.into_iter().enumerate() {
            let (l, r) = (self.left[i], self.right[i]);
            if l == 0.0 && r == 0.0 {
                continue;
            }
            for &m in au.muscles() {
                let Some(full) = params.au_reference(au, m) else {
                    continue;
                };
                let full = full as f32;
                if m == MuscleKind::Jaw {
                    a.jaw_deg += full * 0.5 * (l + r);
                    continue;
                }
                for id in MuscleId::of_kind(m) {
                    let level = match id.side {
                        Side::Left => l,
                        Side::Right => r,
                        Side::Centre => 0.5 * (l + r),
                    };
                    a.k[id.index().expect("valid")] += full * level;
                }
            }
        }
        a
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::BTreeSet;

    #[test]
    fn channel_layout() {
        let c = channels();
        assert_eq!(c.iter().filter(|m| m.side == Side::Centre).count(), 2);
        let set: BTreeSet<_> = c.iter().collect();
        assert_eq!(set.len(), N_CHANNELS);
        for (i, id) in c.iter().enumerate() {
            assert_eq!(id.index(), Some(i));
        }
    }

    #[test]
    fn tables_b_c_reach_exactly_table_d() {
        // Through the (corrected) AU sets and table C, every region
        // expression reaches exactly the muscles table D lists, and no AU
        // muscle lacks a table D value.
        let p = FaceParams::default_params();
        for e in Expression::BASIC {
            let via_aus: BTreeSet<MuscleKind> = expression_aus(e)
                .iter()
                .flat_map(|a| a.muscles().iter().copied())
                .collect();
            let in_d: BTreeSet<MuscleKind> = p.expressions[&e].keys().copied().collect();
            assert_eq!(via_aus, in_d, "{e:?}");
        }
    }

    /// F10: the human profile's basic expressions are their FACS
    /// prototypes: fear raises the brows (AU 1+2) where anger lowers them
    /// without raising; every channel is the AU level times its reference,
    /// scaled by intensity; a region takes only its own AUs.
    #[test]
    fn facs_prototypes_make_the_basic_expressions() {
        let p = FaceParams::default_params();
        let k = |a: &Activation, m: MuscleKind| {
            let side = if m.bilateral() {
                Side::Left
            } else {
                Side::Centre
            };
            a.get(MuscleId { kind: m, side })
        };
        let fear = emotion_activation(&p, Emotion::Fear, 1.0);
        let anger = emotion_activation(&p, Emotion::Anger, 1.0);
        assert!(k(&fear, MuscleKind::FrontalisInner) > 0.2);
        assert!(
            k(&fear, MuscleKind::Risorius) > 0.1,
            "fear stretches the lips (AU 20)"
        );
        assert_eq!(k(&anger, MuscleKind::FrontalisInner), 0.0);
        assert!(k(&anger, MuscleKind::Corrugator) > 0.3);
        let smile = emotion_activation(&p, Emotion::Happiness, 0.6);
        let full = p
            .au_reference(ActionUnit::Au12, MuscleKind::ZygomaticMajor)
            .unwrap();
        assert!((k(&smile, MuscleKind::ZygomaticMajor) - 0.6 * full as f32).abs() < 1e-6);
        // Hidden anger (table A: neutral brows, happy eyes, angry mouth):
        // each region takes only its own expression's AUs.
        let hidden = emotion_activation(&p, Emotion::HiddenAnger, 1.0);
        assert_eq!(k(&hidden, MuscleKind::Corrugator), 0.0);
        assert!(k(&hidden, MuscleKind::OculiOrbital) > 0.0);
        assert!(k(&hidden, MuscleKind::OrbicularisOris) > 0.0);
        // The seed's thesis table stays reachable.
        let thesis = emotion_activation(&FaceParams::thesis_params(), Emotion::Fear, 1.0);
        assert_eq!(k(&thesis, MuscleKind::FrontalisInner), 0.0);
    }

    #[test]
    fn all_35_emotions_drive_their_regions_muscles_at_table_d() {
        let p = FaceParams::thesis_params();
        for intensity in [1.0f32, 0.4] {
            for emo in Emotion::all() {
                let a = emotion_activation(&p, emo, intensity);
                // Expected, straight from tables A and D.
                let mut expect_k = [0.0f32; N_CHANNELS];
                let mut expect_jaw = 0.0f32;
                for (region, expr) in Region::ALL.into_iter().zip(emo.regions()) {
                    if let Some(row) = p.expressions.get(&expr) {
                        for (m, k) in row.iter().filter(|(m, _)| m.region() == region) {
                            if *m == MuscleKind::Jaw {
                                expect_jaw = *k as f32 * intensity;
                            } else {
                                for id in MuscleId::of_kind(*m) {
                                    expect_k[id.index().unwrap()] = *k as f32 * intensity;
                                }
                            }
                        }
                    }
                }
                assert_eq!(a.k, expect_k, "{emo:?}");
                assert_eq!(a.jaw_deg, expect_jaw, "{emo:?}");
            }
        }
        // Spot checks by hand: contempt moves only the lower face with disgust values.
        let a = emotion_activation(&p, Emotion::Contempt, 1.0);
        let nz: Vec<_> = channels()
            .into_iter()
            .filter(|c| a.get(*c) != 0.0)
            .map(|c| c.kind)
            .collect();
        assert_eq!(
            nz,
            [
                MuscleKind::LevatorAlaequeNasi,
                MuscleKind::LevatorAlaequeNasi,
                MuscleKind::LevatorLabiiSuperioris,
                MuscleKind::LevatorLabiiSuperioris
            ]
        );
        assert_eq!(a.jaw_deg, 0.7);
        assert_eq!(
            emotion_activation(&p, Emotion::Neutral, 1.0),
            Activation::default()
        );
    }

    #[test]
    fn direct_au_control_left_right() {
        let p = FaceParams::default_params();
        let mut au = AuLevels::default();
        au.set_sides(ActionUnit::Au12, 1.0, 0.0);
        au.set(ActionUnit::Au26, 0.5);
        let a = au.activation(&p);
        assert_eq!(
            a.get(MuscleId {
                kind: MuscleKind::ZygomaticMajor,
                side: Side::Left
            }),
            0.19
        );
        assert_eq!(
            a.get(MuscleId {
                kind: MuscleKind::ZygomaticMajor,
                side: Side::Right
            }),
            0.0
        );
        assert!((a.jaw_deg - 7.2).abs() < 1e-6);
        let mut au = AuLevels::default();
        au.set(ActionUnit::Au5, 1.0);
        let a = au.activation(&p);
        assert_eq!(
            a.get(MuscleId {
                kind: MuscleKind::OculiUpperPalpebral,
                side: Side::Right
            }),
            -0.48
        );
    }
}
