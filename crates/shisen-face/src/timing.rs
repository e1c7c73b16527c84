//! Onset and offset timing (face.md 7): the five position patterns I-V,
//! durations from tables 5.9 / 5.10 at speed 1/2/3, and transitions between
//! any two activations, starting from the current values.

use super::emotion::Activation;
use super::params::FaceParams;
use super::tables::Expression;

/// Onset/offset velocity patterns of face.md 7.
#[derive(
    Clone,
    Copy,
    Debug,
    PartialEq,
    Eq,
    Default,
    serde::Deserialize,
    serde::Serialize,
    schemars::JsonSchema,
)]
pub enum Pattern {
    /// Constant velocity.
    I,
    /// Increasing velocity.
    II,
    /// Decreasing velocity (the thesis's choice; the default).
    #[default]
    III,
    /// Increasing then decreasing from the middle.
    IV,
    /// Decreasing to 0 at the middle, then increasing.
    V,
}

impl Pattern {
    /// Position p(s) for normalised time s (clamped to [0, 1]) (face.md 7 table).
    pub fn position(self, s: f64) -> f64 {
        let s = s.clamp(0.0, 1.0);
        match self {
            Pattern::I => s,
            Pattern::II => s * s,
            Pattern::III => 1.0 - (1.0 - s) * (1.0 - s),
            Pattern::IV if s < 0.5 => 2.0 * s * s,
            Pattern::IV => 1.0 - 2.0 * (1.0 - s) * (1.0 - s),
            Pattern::V if s < 0.5 => 2.0 * s - 2.0 * s * s,
            Pattern::V => 0.5 + 2.0 * (s - 0.5) * (s - 0.5),
        }
    }
}

/// Playback speed: 1 fast (lower bound), 2 typical, 3 slow (upper bound).
#[derive(
    Clone,
    Copy,
    Debug,
    PartialEq,
    Eq,
    Default,
    serde::Deserialize,
    serde::Serialize,
    schemars::JsonSchema,
)]
pub enum Speed {
    /// Speed 1: the lower (fast) bound.
    Fast,
    /// Speed 2: the geometric mean.
    #[default]
    Typical,
    /// Speed 3: the upper (slow) bound.
    Slow,
}

impl Speed {
    /// From the script number 1, 2 or 3.
    pub fn from_number(n: u8) -> Option<Speed> {
        match n {
            1 => Some(Speed::Fast),
            2 => Some(Speed::Typical),
            3 => Some(Speed::Slow),
            _ => None,
        }
    }
}

/// Which viewer group of table 5.10 to use for the offsets that split.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum OffsetGroup {
    /// Group 1 (default).
    #[default]
    One,
    /// Group 2.
    Two,
}

fn pick(b: &super::params::DurationBounds, speed: Speed) -> f64 {
    match speed {
        Speed::Fast => b.lower,
        Speed::Typical => b.typical(),
        Speed::Slow => b.upper,
    }
}

/// Duration of neutral -> `e` (table 5.9); 0 for neutral.
pub fn onset_duration(p: &FaceParams, e: Expression, speed: Speed) -> f64 {
    p.onset.get(&e).map_or(0.0, |b| pick(b, speed))
}

/// Duration of `e` -> neutral (table 5.10); 0 for neutral.
pub fn offset_duration(p: &FaceParams, e: Expression, speed: Speed, group: OffsetGroup) -> f64 {
    let b = match group {
        OffsetGroup::Two => p.offset_group2.get(&e).or_else(|| p.offset.get(&e)),
        OffsetGroup::One => p.offset.get(&e),
    };
    b.map_or(0.0, |b| pick(b, speed))
}

/// Duration of a whole-face change from region expressions `from` to `to`.
///
/// Every region that changes contributes the offset of what it leaves (if
/// not neutral) and the onset of what it enters (if not neutral); the face
/// uses the longest of these (face.md 7: a blend uses its longest region
/// duration; a direct X -> Y change takes as long as the slower of leaving X
/// and entering Y). If no region changes (an intensity change) the onsets
/// of the target's regions are used.
pub fn transition_duration(
    p: &FaceParams,
    from: [Expression; 3],
    to: [Expression; 3],
    speed: Speed,
    group: OffsetGroup,
) -> f64 {
    let changed: Vec<usize> = (0..3).filter(|&i| from[i] != to[i]).collect();
    let idx: Vec<usize> = if changed.is_empty() {
        (0..3).collect()
    } else {
        changed
    };
    idx.into_iter()
        .map(|i| {
            let off = if from[i] != to[i] {
                offset_duration(p, from[i], speed, group)
            } else {
                0.0
            };
            off.max(onset_duration(p, to[i], speed))
        })
        .fold(0.0, f64::max)
}

/// A timed change of every channel from a start activation to a target.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transition {
    /// Values at the start (the face's values when the change began).
    pub from: Activation,
    /// Target values.
    pub to: Activation,
    /// Duration T, seconds (0 = jump).
    pub duration: f64,
    /// Time since the start, seconds.
    pub elapsed: f64,
    /// Position pattern.
    pub pattern: Pattern,
}

impl Transition {
    /// A finished transition resting at `a`.
    pub fn at_rest(a: Activation) -> Self {
        Self {
            from: a,
            to: a,
            duration: 0.0,
            elapsed: 0.0,
            pattern: Pattern::III,
        }
    }

    /// Progress p(t / T) in [0, 1].
    pub fn progress(&self) -> f64 {
        if self.duration <= 0.0 {
            1.0
        } else {
            self.pattern.position(self.elapsed / self.duration)
        }
    }

    /// Current values: from + (to - from) p(t / T).
    pub fn value(&self) -> Activation {
        self.from.lerp(&self.to, self.progress() as f32)
    }

    /// True once t >= T.
    pub fn done(&self) -> bool {
        self.elapsed >= self.duration
    }

    /// Advance by `dt` seconds.
    pub fn advance(&mut self, dt: f64) {
        self.elapsed = (self.elapsed + dt).min(self.duration.max(0.0));
    }

    /// Start a new change towards `to` from the current values.
    pub fn retarget(&mut self, to: Activation, duration: f64, pattern: Pattern) {
        *self = Self {
            from: self.value(),
            to,
            duration,
            elapsed: 0.0,
            pattern,
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tables::Expression::*;

    #[test]
    fn pattern_shapes() {
        for p in [
            Pattern::I,
            Pattern::II,
            Pattern::III,
            Pattern::IV,
            Pattern::V,
        ] {
            assert_eq!(p.position(0.0), 0.0);
            assert_eq!(p.position(1.0), 1.0);
            assert!(
                (p.position(0.5)
                    - if p == Pattern::II {
                        0.25
                    } else if p == Pattern::III {
                        0.75
                    } else {
                        0.5
                    })
                .abs()
                    < 1e-12
            );
        }
        assert!((Pattern::I.position(0.3) - 0.3).abs() < 1e-12);
        assert!((Pattern::II.position(0.3) - 0.09).abs() < 1e-12);
        assert!((Pattern::III.position(0.3) - 0.51).abs() < 1e-12);
        assert!((Pattern::IV.position(0.25) - 0.125).abs() < 1e-12);
        assert!((Pattern::IV.position(0.75) - 0.875).abs() < 1e-12);
        assert!((Pattern::V.position(0.25) - 0.375).abs() < 1e-12);
        assert!((Pattern::V.position(0.75) - 0.625).abs() < 1e-12);
        // Velocity profiles by finite difference: III decreasing, II increasing,
        // IV peaks at the middle, V vanishes there.
        let v = |p: Pattern, s: f64| (p.position(s + 1e-6) - p.position(s - 1e-6)) / 2e-6;
        assert!(v(Pattern::III, 0.1) > v(Pattern::III, 0.9));
        assert!(v(Pattern::II, 0.1) < v(Pattern::II, 0.9));
        assert!((v(Pattern::IV, 0.5) - 2.0).abs() < 1e-4 && v(Pattern::IV, 0.1) < 2.0);
        assert!(v(Pattern::V, 0.5).abs() < 1e-4 && (v(Pattern::V, 0.0 + 1e-5) - 2.0).abs() < 1e-3);
    }

    #[test]
    fn durations_from_tables() {
        let p = FaceParams::default_params();
        let n = [Neutral; 3];
        let g = OffsetGroup::One;
        assert_eq!(
            transition_duration(&p, n, [Surprise; 3], Speed::Fast, g),
            0.16
        );
        assert_eq!(
            transition_duration(&p, n, [Surprise; 3], Speed::Slow, g),
            1.00
        );
        assert!((transition_duration(&p, n, [Surprise; 3], Speed::Typical, g) - 0.4).abs() < 1e-12);
        assert_eq!(transition_duration(&p, [Anger; 3], n, Speed::Slow, g), 3.00);
        assert_eq!(
            transition_duration(&p, [Sadness; 3], n, Speed::Fast, OffsetGroup::Two),
            3.12
        );
        // Blend: happy surprise (Su, Su, H) at speed 1 uses the longest: happiness 0.36.
        assert_eq!(
            transition_duration(&p, n, [Surprise, Surprise, Happiness], Speed::Fast, g),
            0.36
        );
        // Direct anger -> happiness (N, H, H) at speed 1: max(offset anger 0.96, onset happiness 0.36).
        assert_eq!(
            transition_duration(
                &p,
                [Anger; 3],
                [Neutral, Happiness, Happiness],
                Speed::Fast,
                g
            ),
            0.96
        );
        assert_eq!(transition_duration(&p, n, n, Speed::Fast, g), 0.0);
    }

    #[test]
    fn transition_starts_from_current_values() {
        let a = Activation {
            jaw_deg: 10.0,
            ..Activation::default()
        };
        let mut t = Transition::at_rest(Activation::default());
        t.retarget(a, 1.0, Pattern::I);
        t.advance(0.25);
        assert!((t.value().jaw_deg - 2.5).abs() < 1e-6);
        // Interrupt: go back to 0 from 2.5 with pattern III over 2 s.
        t.retarget(Activation::default(), 2.0, Pattern::III);
        assert!((t.value().jaw_deg - 2.5).abs() < 1e-6);
        t.advance(1.0);
        assert!((t.value().jaw_deg - 2.5 * 0.25).abs() < 1e-6);
        t.advance(5.0);
        assert!(t.done() && t.value().jaw_deg == 0.0);
    }
}
