//! Measuring: each sample of a run folded into every expectation's
//! accumulator, in constant memory.

use super::{Expect, JointName};
use crate::physics::balance::Stance;
use crate::sim::Sample;
use crate::sim::blows::BlowKind;
use shisen_gaze::behaviour::{ActionKind, EYES_ON_TARGET};

/// What one expectation has measured so far (each expectation uses the
/// fields it needs).
#[derive(Clone, Debug, Default)]
pub(super) struct Acc {
    pub(super) n: u64,
    pub(super) hits: u64,
    pub(super) max: f64,
    pub(super) min: Option<f64>,
    pub(super) first: Option<f64>,
    pub(super) bad: bool,
    /// Telegraph: when the gaze last went onto the attack target.
    pub(super) since: Option<f64>,
    pub(super) punching: bool,
    /// Blinks: whether the lids were more than half shut last tick.
    pub(super) shut: bool,
    /// HeadRotation: the head's world direction at the window's start.
    pub(super) origin: Option<glam::DVec2>,
    /// Evades: the head's position when the evasion under way began,
    /// whether it got far enough, whether it was touched.
    pub(super) evasion: Option<(glam::DVec3, bool, bool)>,
    /// Knockdowns: the body's state last tick.
    pub(super) stance: Stance,
}

fn angle(s: &Sample, j: JointName) -> f64 {
    match j {
        JointName::NeckYaw => s.neck_actual.yaw,
        JointName::NeckPitch => s.neck_actual.pitch,
        JointName::NeckRoll => s.neck_actual.roll,
        JointName::LeftEyeYaw => s.eye_actual[0].x,
        JointName::LeftEyePitch => s.eye_actual[0].y,
        JointName::RightEyeYaw => s.eye_actual[1].x,
        JointName::RightEyePitch => s.eye_actual[1].y,
    }
}

fn inside(t: f64, from: f64, to: f64) -> bool {
    // Samples are stamped at the end of their tick; half-open on the left.
    t > from + 1e-9 && t <= to + 1e-9
}

/// Fold the sample `s` into `a`, the accumulator of `e`, in a run of
/// `duration` seconds.
pub(super) fn measure(e: &Expect, a: &mut Acc, s: &Sample, duration: f64) {
    match e {
        Expect::GazeShare {
            target, from, to, ..
        }
        | Expect::GazeShareAtMost {
            target, from, to, ..
        } => {
            if inside(s.t, *from, *to) {
                a.n += 1;
                a.hits += (s.gaze_target == *target) as u64;
            }
        }
        Expect::GazeReaches { target, from, to } => {
            if inside(s.t, *from, *to) && a.first.is_none() && s.gaze_target == *target {
                a.first = Some(s.t);
            }
        }
        Expect::AngleBelow {
            joint, from, to, ..
        } => {
            if inside(s.t, from.unwrap_or(0.0), to.unwrap_or(duration)) {
                let v = angle(s, *joint).abs().to_degrees();
                a.n += 1;
                a.max = if v.is_nan() { f64::NAN } else { a.max.max(v) };
            }
        }
        Expect::AngleReaches {
            joint, from, to, ..
        } => {
            if inside(s.t, *from, *to) {
                a.n += 1;
                a.max = a.max.max(angle(s, *joint).abs().to_degrees());
            }
        }
        Expect::Telegraph { .. } => {
            // The eyes are physically on the target (within EYES_ON_TARGET).
            let on_target = s.action == ActionKind::Attack
                && s.source == shisen_gaze::attention::Source::TopDown
                && s.los_error[0].max(s.los_error[1]) < EYES_ON_TARGET;
            if !on_target {
                a.since = None;
            } else if a.since.is_none() {
                a.since = Some(s.t);
            }
            if s.punching && !a.punching {
                a.n += 1;
                let lead = a.since.map_or(0.0, |t0| s.t - t0);
                a.min = Some(a.min.map_or(lead, |m: f64| m.min(lead)));
            }
            a.punching = s.punching;
        }
        Expect::LineOfSight { from, to, .. } | Expect::LineOfSightReaches { from, to, .. } => {
            if inside(s.t, *from, *to) {
                let v = s.los_error[0].max(s.los_error[1]).to_degrees();
                a.n += 1;
                a.max = if v.is_nan() { f64::NAN } else { a.max.max(v) };
            }
        }
        Expect::ActionShare {
            action, from, to, ..
        } => {
            if inside(s.t, *from, *to) {
                a.n += 1;
                a.hits += (s.action == *action) as u64;
            }
        }
        Expect::Blinks { from, to, .. } => {
            let shut = s.blink > 0.5;
            if inside(s.t, *from, *to) && shut && !a.shut {
                a.hits += 1;
            }
            a.shut = shut;
        }
        Expect::HeadHit { from, to, .. } => {
            if inside(s.t, *from, *to) && s.head_hit && a.first.is_none() {
                a.first = Some(s.t);
            }
        }
        Expect::Blows {
            kind, by, from, to, ..
        } => {
            if inside(s.t, *from, *to) {
                a.hits += s
                    .blows
                    .iter()
                    .filter(|b| b.kind == *kind && b.by == *by)
                    .count() as u64;
            }
        }
        Expect::HeadRotation { from, to, .. } => {
            if inside(s.t, *from, *to) {
                let o = *a.origin.get_or_insert(s.head_world);
                a.n += 1;
                a.max = a.max.max((s.head_world - o).length().to_degrees());
            }
        }
        Expect::HeadSpeed { from, to, .. } => {
            if inside(s.t, *from, *to) {
                a.n += 1;
                a.max = a.max.max(s.head_speed);
            }
        }
        Expect::BlowMomentum { by, from, to, .. } => {
            if inside(s.t, *from, *to) {
                for b in s
                    .blows
                    .iter()
                    .filter(|b| b.kind == BlowKind::Hit && b.by == *by)
                {
                    let j = f64::from(b.impulse);
                    a.hits += 1;
                    a.max = a.max.max(j);
                    a.min = Some(a.min.map_or(j, |m: f64| m.min(j)));
                }
            }
        }
        Expect::Evades {
            kind,
            from,
            to,
            offset,
            ..
        } => {
            let evading = match kind {
                Some(k) => s.action == *k,
                None => s.action.defends() && s.action != ActionKind::Guard,
            };
            match (&mut a.evasion, evading) {
                (None, true) if inside(s.t, *from, *to) => {
                    a.evasion = Some((s.head, false, s.head_hit));
                    a.n += 1;
                }
                (Some((start, far, touched)), true) => {
                    *far |= (s.head - *start).length() >= *offset;
                    *touched |= s.head_hit;
                }
                (Some((_, far, touched)), false) => {
                    a.hits += u64::from(*far && !*touched);
                    a.evasion = None;
                }
                _ => {}
            }
        }
        Expect::Range { from, to, .. } | Expect::Fatigue { from, to, .. } => {
            if inside(s.t, *from, *to) {
                let v = match e {
                    Expect::Range { .. } => s.range,
                    _ => s.fatigue,
                };
                a.n += 1;
                a.max = a.max.max(v);
                a.min = Some(a.min.map_or(v, |m: f64| m.min(v)));
            }
        }
        Expect::Knockdowns { from, to, .. } => {
            // Knockdowns in `hits`, get-ups in `n`.
            if inside(s.t, *from, *to) {
                a.hits += u64::from(a.stance == Stance::Standing && s.stance == Stance::Falling);
                a.n += u64::from(a.stance == Stance::Rising && s.stance == Stance::Standing);
            }
            a.stance = s.stance;
        }
        Expect::Finite => {
            a.n += 1;
            a.bad |= !s.finite
                || !s.gaze_point.is_finite()
                || !s.eye_actual[0].is_finite()
                || !s.eye_actual[1].is_finite();
        }
    }
}
