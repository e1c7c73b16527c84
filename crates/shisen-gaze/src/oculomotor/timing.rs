//! Human timing and limits in front of the gaze laws (docs/model/gaze.md
//! section "Human timing"): the eyes do not go to a new target the moment
//! attention picks it, and smooth pursuit neither starts at once nor keeps
//! up with a fast target.
//!
//! The laws (M2-M9) are untouched; this front end decides *where* they
//! aim. It keeps an **aim point** (world) that the saccade, pursuit and
//! head laws are given in place of the target itself:
//!
//! - **saccadic reaction** (H1): a new target is aimed at only after a
//!   reaction time drawn from the LATER model (Carpenter & Williams 1995,
//!   Nature 377:59): the reciprocal of the time is normal, `1/T ~
//!   N(1/median, sigma)`. Until then the eyes stay on the old aim;
//! - **pursuit onset and gain** (H2): between saccades the aim point moves
//!   with the target's velocity as it was `pursuit_onset` ago (human
//!   pursuit starts about 100 ms after the target does: Carl & Gellman
//!   1987, J. Neurophysiol. 57:1446), scaled by a gain that falls with the
//!   target's angular speed (about 0.98 at 10 deg/s, 0.75 at 60 deg/s:
//!   Meyer, Lasker & Robinson 1985, J. Physiol. 368:251);
//! - **catch-up saccades** (H3): when the aim falls behind the target by
//!   more than `catch_up_threshold` the aim jumps to the target and a
//!   saccade takes the eyes there (position errors of a degree or two
//!   trigger them: de Brouwer et al. 2002, J. Neurophysiol. 87:1646);
//! - **VOR latency** (H4): the vestibular signal reaches the VOR term of
//!   (M7) `vor_latency` late (7-10 ms in head impulses: Aw et al. 1996,
//!   J. Neurophysiol. 76:4009; Collewijn & Smeets 2000, J. Neurophysiol.
//!   84:376);
//! - **VOR saturation** (H6): at the head accelerations of a blow the VOR
//!   falls short (median gains 0.61-0.83 at 1900-7100 deg/s^2: Maas et al.
//!   1989, Brain Res. 499:153), so the head's felt orientation, on which
//!   the eyes' goals are computed, misses part of the rotation and the
//!   line of sight is knocked off the target;
//! - **corrective saccade** (H7): once the eyes have been off the target,
//!   as vision sees it, for `corrective_latency`, a saccade brings them
//!   back (catch-up saccades 135 +- 36 ms after a head impulse's onset:
//!   Tian et al. 2007, Exp. Brain Res. 182:143), and the felt orientation
//!   is anchored again to the world.
//!
//! With [`TimingParams::seed`] (all zero, no limits) the aim point is the
//! target itself every tick and nothing is drawn from the random stream:
//! the seed's laws exactly.

use glam::{DQuat, DVec3};
use rand::Rng;
use rand_distr::{Distribution, Normal};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::target::TargetId;
use crate::util::delay::DelayLine;
use crate::util::math::angle_between;

/// A LATER reaction-time distribution: `1/T ~ N(1/median, rate_sd)`
/// (Carpenter & Williams 1995). Draws are kept within
/// [`Later::SHORTEST`], [`Later::LONGEST`] (express saccades are about
/// 100 ms in all; "no response" draws are taken as the longest).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Later {
    /// Median time, s (0: react at once), 0-1: no draw exceeds 1 s
    /// (`Later::LONGEST`).
    #[schemars(range(min = 0.0, max = 1.0))]
    pub median: f64,
    /// Standard deviation of the rate `1/T`, 1/s, 0-20 (human: about 0.2 x
    /// the mean rate, near 1/s; at 20 most draws already fall on the
    /// 20 ms or 1 s clamps).
    #[schemars(range(min = 0.0, max = 20.0))]
    pub rate_sd: f64,
}

impl Later {
    /// Shortest time a draw gives, s.
    pub const SHORTEST: f64 = 0.02;
    /// Longest time a draw gives, s.
    pub const LONGEST: f64 = 1.0;

    /// No delay.
    pub const ZERO: Later = Later {
        median: 0.0,
        rate_sd: 0.0,
    };

    /// Draw one reaction time (s). A zero median draws nothing.
    pub fn draw(&self, rng: &mut impl Rng) -> f64 {
        if self.median <= 0.0 {
            return 0.0;
        }
        let mean_rate = 1.0 / self.median;
        let rate = match Normal::new(mean_rate, self.rate_sd) {
            Ok(n) => n.sample(rng),
            Err(_) => mean_rate,
        };
        if rate <= 1.0 / Self::LONGEST {
            Self::LONGEST
        } else {
            (1.0 / rate).max(Self::SHORTEST)
        }
    }
}

/// Human timing and limits of the gaze controller (scene
/// `vh.oculomotor.timing`). Seconds and radians.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct TimingParams {
    /// Time from attention's choice of a new target to the saccade's onset
    /// (H1). The whole reaction adds vision's latency. Default median
    /// 0.13 s, rate sd 1.5/s: with the 60 ms visual latency a median
    /// saccadic reaction time near 200 ms with the skewed spread of
    /// Carpenter & Williams 1995 (their subjects: median 170-250 ms, rate
    /// sd about 0.2 x the mean rate).
    pub saccade_latency: Later,
    /// Delay of the pursuit drive behind the target's motion (H2), s
    /// (with `pursuit_limits`). Default 0.1 (Carl & Gellman 1987: about
    /// 100 ms). 0-1 s, ten times the human delay.
    #[schemars(range(min = 0.0, max = 1.0))]
    pub pursuit_onset: f64,
    /// Whether pursuit gain falls with target speed and catch-up saccades
    /// make up the difference (H2, H3). Off: the aim is the target itself
    /// (gain 1, no onset delay), as in the seed.
    pub pursuit_limits: bool,
    /// Target angular speed up to which pursuit gain is 1, deg/s. Default
    /// 5.7, with `gain_slope` the line through Meyer et al.'s 0.98 at
    /// 10 deg/s and 0.75 at 60 deg/s. 0-500 deg/s: human pursuit
    /// saturates near 100 deg/s; at 500 the gain never falls.
    #[schemars(range(min = 0.0, max = 500.0))]
    pub gain_knee_deg_s: f64,
    /// Loss of pursuit gain per deg/s above the knee, per deg/s, 0-1
    /// (at 1 the gain reaches its floor within a deg/s). Default 0.0046.
    #[schemars(range(min = 0.0, max = 1.0))]
    pub gain_slope: f64,
    /// Lowest pursuit gain, a fraction, 0-1. Default 0.4.
    #[schemars(range(min = 0.0, max = 1.0))]
    pub gain_floor: f64,
    /// Aim-to-target angle that triggers a catch-up saccade (H3), rad.
    /// Default 1.5 deg. Above 0, at most 0.5 rad (29 deg; humans trigger
    /// at errors of a degree or two).
    #[schemars(range(max = 0.5), extend("exclusiveMinimum" = 0.0))]
    pub catch_up_threshold: f64,
    /// Delay of the vestibular signal into the VOR (H4), s. Default 0.01.
    /// 0-0.2 s, twenty times the human 7-10 ms.
    #[schemars(range(min = 0.0, max = 0.2))]
    pub vor_latency: f64,
    /// Head acceleration up to which the VOR's gain holds (H6), deg/s^2.
    /// Default 4000: head impulses of 3000-4000 deg/s^2 keep a gain near
    /// 0.95 (Aw et al. 1996). Above 0, at most 100000 deg/s^2 (beyond any
    /// blow's head acceleration: the VOR then never saturates).
    #[schemars(range(max = 100000.0), extend("exclusiveMinimum" = 0.0))]
    pub vor_knee_accel: f64,
    /// Head acceleration at which the gain has fallen to `vor_min_gain`
    /// (H6), deg/s^2. Default 8000 (the top of Maas et al.'s range).
    /// Above 0, at most 100000 deg/s^2, as `vor_knee_accel`.
    #[schemars(range(max = 100000.0), extend("exclusiveMinimum" = 0.0))]
    pub vor_saturated_accel: f64,
    /// The VOR's gain at and beyond `vor_saturated_accel` (H6). Default
    /// 0.72, the middle of Maas et al. 1989's 0.61-0.83; 1 turns the
    /// saturation off. A gain, 0-1.
    #[schemars(range(min = 0.0, max = 1.0))]
    pub vor_min_gain: f64,
    /// Time constant of the gain's return after a saturating transient
    /// (H6), s. Default 0.1 (our choice: the length of a blow's head
    /// transient). Above 0, at most 10 s.
    #[schemars(range(max = 10.0), extend("exclusiveMinimum" = 0.0))]
    pub vor_gain_recovery: f64,
    /// Time constant over which the felt head orientation drifts back to
    /// the true one without a saccade (proprioception, H6), s. Default 0.5
    /// (our choice). Above 0, at most 60 s (a minute: the felt
    /// orientation then barely returns between saccades).
    #[schemars(range(max = 60.0), extend("exclusiveMinimum" = 0.0))]
    pub vestibular_recalibration: f64,
    /// How long the eyes must be off the target, as vision sees it (by more
    /// than `catch_up_threshold`), before a corrective saccade starts
    /// (H7), s. Default 0.1 (Tian et al. 2007: 135 +- 36 ms from a head
    /// impulse's onset, which comes a few tens of ms before the error).
    /// 0-1 s, several times the human latency.
    #[schemars(range(min = 0.0, max = 1.0))]
    pub corrective_latency: f64,
}

impl Default for TimingParams {
    fn default() -> Self {
        TimingParams {
            saccade_latency: Later {
                median: 0.13,
                rate_sd: 1.5,
            },
            pursuit_onset: 0.1,
            pursuit_limits: true,
            gain_knee_deg_s: 5.7,
            gain_slope: 0.0046,
            gain_floor: 0.4,
            catch_up_threshold: 1.5f64.to_radians(),
            vor_latency: 0.01,
            vor_knee_accel: 4000.0,
            vor_saturated_accel: 8000.0,
            vor_min_gain: 0.72,
            vor_gain_recovery: 0.1,
            vestibular_recalibration: 0.5,
            corrective_latency: 0.1,
        }
    }
}

impl TimingParams {
    /// The seed's timing: every latency zero, pursuit gain 1, no catch-up
    /// saccades (the laws as the papers state them).
    pub fn seed() -> Self {
        TimingParams {
            saccade_latency: Later::ZERO,
            pursuit_onset: 0.0,
            pursuit_limits: false,
            vor_latency: 0.0,
            vor_min_gain: 1.0,
            ..Default::default()
        }
    }

    /// The VOR's gain at a head acceleration (rad/s^2) (H6): 1 up to the
    /// knee, then falling linearly to the floor at `vor_saturated_accel`.
    pub fn vor_gain(&self, accel: f64) -> f64 {
        let a = accel.abs().to_degrees();
        let span = (self.vor_saturated_accel - self.vor_knee_accel).max(1e-9);
        let over = ((a - self.vor_knee_accel) / span).clamp(0.0, 1.0);
        1.0 - (1.0 - self.vor_min_gain) * over
    }

    /// Pursuit gain at a target angular speed (rad/s) (H2): 1 up to the
    /// knee, then falling linearly to the floor.
    pub fn pursuit_gain(&self, speed: f64) -> f64 {
        if !self.pursuit_limits {
            return 1.0;
        }
        let over = (speed.abs().to_degrees() - self.gain_knee_deg_s).max(0.0);
        (1.0 - self.gain_slope * over).max(self.gain_floor)
    }
}

/// What the front end decided this tick.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AimStep {
    /// Where the laws aim, world.
    pub point: DVec3,
    /// The aim moved to a new target this tick (its reaction time is over).
    pub new_target: bool,
    /// The aim jumped to a target it had fallen behind (catch-up, H3).
    pub catch_up: bool,
}

/// The front end's evolving state.
#[derive(Clone, Debug, Default)]
pub struct Aim {
    current: Option<TargetId>,
    pending: Option<(TargetId, f64)>,
    point: DVec3,
    last_target: Option<DVec3>,
    drive: DelayLine<DVec3>,
    vestibular: DelayLine<(DQuat, DVec3)>,
    /// The reported angular velocity a tick ago (for the acceleration).
    last_angvel: Option<DVec3>,
    /// The VOR's present shortfall, 1 - gain (H6).
    vor_loss: f64,
    /// The rotation the felt orientation has missed, world (H6).
    missed: DQuat,
    /// Since when the eyes have been off the target as vision sees it (H7).
    off_since: Option<f64>,
}

impl Aim {
    /// Advance one tick: `target` is attention's gaze point with its
    /// identity `id`; `eye` the cyclopean eye, world.
    #[allow(clippy::too_many_arguments)]
    pub fn step(
        &mut self,
        p: &TimingParams,
        target: DVec3,
        id: TargetId,
        eye: DVec3,
        t: f64,
        dt: f64,
        rng: &mut impl Rng,
    ) -> AimStep {
        let mut step = AimStep {
            point: self.point,
            new_target: false,
            catch_up: false,
        };
        if self.current != Some(id) {
            // (H1): a new target waits for its reaction time.
            // (The very first target is where the VH starts out looking.)
            let due = match self.pending {
                _ if self.current.is_none() => t,
                Some((pid, due)) if pid == id => due,
                _ => {
                    let due = t + p.saccade_latency.draw(rng);
                    self.pending = Some((id, due));
                    due
                }
            };
            if t + 1e-12 >= due {
                self.current = Some(id);
                self.pending = None;
                self.point = target;
                self.last_target = Some(target);
                self.drive.clear();
                step.point = target;
                step.new_target = true;
            }
            return step;
        }
        self.pending = None;
        let velocity = self.last_target.map_or(DVec3::ZERO, |l| (target - l) / dt);
        self.last_target = Some(target);
        if !p.pursuit_limits {
            self.point = target;
        } else {
            // (H2): the drive is the target's velocity `pursuit_onset` ago,
            // scaled by the gain at its angular speed seen from the eye.
            let v = self.drive.push(velocity, p.pursuit_onset, dt);
            let to = self.point - eye;
            let r = to.length().max(1e-6);
            let across = v - v.dot(to / r) * (to / r);
            let g = p.pursuit_gain(across.length() / r);
            self.point += g * v * dt;
            // (H3): fallen behind: jump, and let a saccade take the eyes.
            if angle_between(self.point - eye, target - eye) > p.catch_up_threshold {
                self.point = target;
                step.catch_up = true;
            }
        }
        step.point = self.point;
        step
    }

    /// The head orientation and angular velocity the eyes act on now (H4):
    /// what the vestibular signal says, `vor_latency` late. A head moved
    /// from outside drags the eyes along for that long before they
    /// counter-rotate.
    ///
    /// At a blow's accelerations the signal saturates (H6): the angular
    /// velocity reaches the VOR scaled by the gain `g`, and the felt
    /// orientation misses the rest of the rotation,
    /// `missed <- R((1 - g) w dt) missed`, which drifts back to nothing
    /// over `vestibular_recalibration` (or at once at a saccade, H7).
    pub fn vestibular(
        &mut self,
        p: &TimingParams,
        rot: DQuat,
        angvel: DVec3,
        dt: f64,
    ) -> (DQuat, DVec3) {
        let (rot, w) = self.vestibular.push((rot, angvel), p.vor_latency, dt);
        let accel = self.last_angvel.map_or(0.0, |l| (w - l).length() / dt);
        self.last_angvel = Some(w);
        let loss = 1.0 - p.vor_gain(accel);
        // The loss sets in at once and fades over the recovery time.
        self.vor_loss -= self.vor_loss * (dt / p.vor_gain_recovery).min(1.0);
        self.vor_loss = self.vor_loss.max(loss);
        if self.vor_loss > 0.0 || self.missed != DQuat::IDENTITY {
            let miss = DQuat::from_scaled_axis(self.vor_loss * w * dt);
            let back = (dt / p.vestibular_recalibration).min(1.0);
            self.missed = (miss * self.missed)
                .normalize()
                .slerp(DQuat::IDENTITY, back);
        }
        (self.missed.inverse() * rot, (1.0 - self.vor_loss) * w)
    }

    /// The eyes are `error` rad off the target as vision sees it (H7):
    /// true once that has lasted `corrective_latency` (the caller then
    /// starts a corrective saccade and calls [`Aim::anchor`]).
    pub fn corrective(&mut self, p: &TimingParams, error: f64, t: f64) -> bool {
        if error <= p.catch_up_threshold {
            self.off_since = None;
            return false;
        }
        t - *self.off_since.get_or_insert(t) >= p.corrective_latency
    }

    /// A saccade re-anchored the gaze to the world: nothing is missed any
    /// more (H7).
    pub fn anchor(&mut self) {
        self.missed = DQuat::IDENTITY;
        self.off_since = None;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::target::BodyId;
    use rand::SeedableRng;
    use rand::rngs::StdRng;

    fn target(n: usize) -> TargetId {
        TargetId::body(BodyId::new(n))
    }

    #[test]
    fn later_draws_have_the_median_and_stay_in_bounds() {
        let l = Later {
            median: 0.13,
            rate_sd: 1.5,
        };
        let mut rng = StdRng::seed_from_u64(1);
        let mut v: Vec<f64> = (0..20001).map(|_| l.draw(&mut rng)).collect();
        v.sort_by(f64::total_cmp);
        let median = v[v.len() / 2];
        assert!((median - 0.13).abs() < 0.003, "median {median}");
        assert!(v[0] >= Later::SHORTEST && v[v.len() - 1] <= Later::LONGEST);
        // Right-skewed like human latencies: the mean exceeds the median.
        let mean = v.iter().sum::<f64>() / v.len() as f64;
        assert!(mean > median);
        assert_eq!(Later::ZERO.draw(&mut rng), 0.0);
    }

    #[test]
    fn pursuit_gain_passes_through_the_human_anchor_points() {
        let p = TimingParams::default();
        let g = |d: f64| p.pursuit_gain(d.to_radians());
        assert!((g(10.0) - 0.98).abs() < 0.005, "{}", g(10.0));
        assert!((g(60.0) - 0.75).abs() < 0.005, "{}", g(60.0));
        assert_eq!(g(2.0), 1.0);
        assert_eq!(g(1000.0), p.gain_floor);
        assert_eq!(TimingParams::seed().pursuit_gain(3.0), 1.0);
    }

    #[test]
    fn a_new_target_waits_for_its_reaction_time() {
        let p = TimingParams {
            saccade_latency: Later {
                median: 0.1,
                rate_sd: 0.0,
            },
            ..TimingParams::default()
        };
        let mut a = Aim::default();
        let mut rng = StdRng::seed_from_u64(1);
        let eye = DVec3::ZERO;
        let first = DVec3::new(0.0, 0.0, 1.0);
        let second = DVec3::new(0.5, 0.0, 1.0);
        let mut onset = None;
        for k in 0..400 {
            let t = k as f64 * 0.001;
            let (tgt, n) = if t < 0.2 { (first, 1) } else { (second, 2) };
            let s = a.step(&p, tgt, target(n), eye, t, 0.001, &mut rng);
            if s.new_target && n == 2 {
                onset = Some(t);
            }
            if n == 2 && onset.is_none() {
                assert_eq!(s.point, first, "still on the old aim at {t}");
            }
        }
        let onset = onset.expect("the new target was taken up");
        assert!((onset - 0.3).abs() < 0.0015, "onset {onset}");
    }

    #[test]
    fn seed_timing_aims_at_the_target_itself() {
        let p = TimingParams::seed();
        let mut a = Aim::default();
        let mut rng = StdRng::seed_from_u64(1);
        for k in 0..50 {
            let t = k as f64 * 0.001;
            let tgt = DVec3::new(t.sin(), 0.2, 1.0);
            let s = a.step(&p, tgt, target(7), DVec3::ZERO, t, 0.001, &mut rng);
            assert_eq!(s.point, tgt);
            assert_eq!(s.new_target, k == 0);
        }
    }

    #[test]
    fn a_fast_target_draws_catch_up_saccades_and_a_slow_one_does_not() {
        let p = TimingParams {
            saccade_latency: Later::ZERO,
            ..TimingParams::default()
        };
        let catch_ups = |deg_s: f64| {
            let mut a = Aim::default();
            let mut rng = StdRng::seed_from_u64(1);
            let mut n = 0;
            for k in 0..2000 {
                let t = k as f64 * 0.001;
                let ang = (deg_s * t).to_radians();
                let tgt = DVec3::new(ang.sin(), 0.0, ang.cos());
                n += a
                    .step(&p, tgt, target(1), DVec3::ZERO, t, 0.001, &mut rng)
                    .catch_up as u32;
            }
            n
        };
        // 2 deg/s: gain 1 after the onset; the 100 ms lag is 0.2 deg.
        assert_eq!(catch_ups(2.0), 0);
        // 60 deg/s: the aim loses 15 deg/s, a catch-up every ~100 ms.
        let fast = catch_ups(60.0);
        assert!((10..=25).contains(&fast), "{fast} catch-ups in 2 s");
    }
}
