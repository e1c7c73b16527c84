//! Spontaneous blinks (face.md 6): the Wiener first-passage model (F8)
//! stepped at the caller's dt, with the threshold overshoot corrected, and
//! the AU45 closing/opening profile.
//!
//! Behaviour (documented choices):
//! * the blink potential always runs; when it reaches the threshold while
//!   blinking is not allowed (by default: the face is not neutral, as in the
//!   thesis) the blink is skipped and the potential resets;
//! * a gaze shift of amplitude A triggers a blink with probability
//!   `(A - A0) / (A1 - A0)` clamped to [0, 1] (A0, A1 from the parameters,
//!   20 and 60 deg by default: the chance that a blink goes with a gaze
//!   shift grows with its size and is high only for large eye-head shifts,
//!   Evinger et al. 1994, Exp. Brain Res. 100:337); a triggered blink
//!   resets the potential;
//! * the lid's following of the eye's pitch is done in `rig.rs`.

use super::params::BlinkParams;
use rand::{Rng, RngExt};
use rand_distr::{Distribution, Normal};

/// Complementary error function, |relative error| < 1.2e-7
/// (Chebyshev fit, Numerical Recipes `erfcc`).
pub fn erfc(x: f64) -> f64 {
    let z = x.abs();
    let t = 1.0 / (1.0 + 0.5 * z);
    let poly = -z * z - 1.265_512_23
        + t * (1.000_023_68
            + t * (0.374_091_96
                + t * (0.096_784_18
                    + t * (-0.186_288_06
                        + t * (0.278_868_07
                            + t * (-1.135_203_98
                                + t * (1.488_515_87 + t * (-0.822_152_23 + t * 0.170_872_77))))))));
    let r = t * poly.exp();
    if x >= 0.0 { r } else { 2.0 - r }
}

/// Standard normal CDF, `Phi(x) = erfc(-x / sqrt 2) / 2`.
pub fn normal_cdf(x: f64) -> f64 {
    0.5 * erfc(-x / std::f64::consts::SQRT_2)
}

/// Inverse Gaussian CDF with mean `mu` and shape `lambda`:
/// `Phi(sqrt(l/x)(x/mu - 1)) + exp(2 l/mu) Phi(-sqrt(l/x)(x/mu + 1))`.
pub fn inverse_gaussian_cdf(x: f64, mu: f64, lambda: f64) -> f64 {
    if x <= 0.0 {
        return 0.0;
    }
    let s = (lambda / x).sqrt();
    normal_cdf(s * (x / mu - 1.0)) + (2.0 * lambda / mu).exp() * normal_cdf(-s * (x / mu + 1.0))
}

/// Shortest interval between two spontaneous blinks counted inside one
/// step, s. A blink lasts 0.2 s (80 ms closing, 120 ms opening, face.md
/// 6), so a second cannot begin this soon after one anyway; the floor
/// bounds the step's loop over threshold crossings (a mean interval of
/// 1e-300 s once made it spin for ever). At the shipped parameters
/// (mu 4 s, lambda 13.94 s) an interval this short has a probability of
/// about 1e-30.
pub const MIN_BLINK_INTERVAL_S: f64 = 0.1;

/// Evolving blink state: potential Y of (F8) and the current lid closure.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct BlinkProcess {
    /// Normalised blink potential Y (blink at 1).
    pub potential: f64,
    /// Time since the current blink began, if one is in progress.
    pub blink_time: Option<f64>,
    /// Number of blinks started (spontaneous and gaze-triggered).
    pub count: u64,
}

impl BlinkProcess {
    /// Advance the potential for `dt` seconds (F8). Returns true when the
    /// threshold was reached during the step (whether or not the blink was
    /// allowed). A blink is started only if `allowed`.
    ///
    /// Overshoot correction: the threshold crossing time inside the step is
    /// estimated by linear interpolation, and a crossing between two samples
    /// below the threshold is detected with the Brownian-bridge probability
    /// `exp(-2 (1 - Y0)(1 - Y1) / (dt / lambda))`. The new interval starts at
    /// the crossing, so the remainder of the step is spent accumulating the
    /// next potential; the mean interval is then mu at any dt.
    ///
    /// `interval_scale` stretches the process in time (mu and lambda both
    /// scale, so intervals scale exactly and keep their inverse-Gaussian
    /// shape): 1 at rest, [`BlinkParams::engaged_interval_scale`] while the
    /// VH is busy sparring.
    ///
    /// A step fires at most once per [`MIN_BLINK_INTERVAL_S`] of its
    /// `dt` (after its first crossing, each further one inside the step
    /// is counted at least that long after the one before), so the loop
    /// over the step's crossings ends after at most
    /// `dt / MIN_BLINK_INTERVAL_S + 1` passes whatever the parameters.
    pub fn step(
        &mut self,
        p: &BlinkParams,
        dt: f64,
        allowed: bool,
        interval_scale: f64,
        rng: &mut impl Rng,
    ) -> bool {
        if let Some(t) = self.blink_time.as_mut() {
            *t += dt;
            if *t >= p.close_s + p.open_s {
                self.blink_time = None;
            }
        }
        let (mu, lambda) = (
            p.mean_interval_s * interval_scale,
            p.shape_s * interval_scale,
        );
        // A step that is not a finite, positive time advances nothing.
        let mut remaining = if dt.is_finite() { dt.max(0.0) } else { 0.0 };
        let mut fired = false;
        while remaining > 0.0 {
            let y0 = self.potential;
            let y1 = y0 + draw(rng, remaining, mu, lambda); // (F8)
            let sigma2 = remaining / lambda;
            let frac = if y1 >= 1.0 {
                Some(
                    refine_crossing(rng, y0, y1, remaining / lambda)
                        .unwrap_or((1.0 - y0) / (y1 - y0)),
                )
            } else if rng.random::<f64>() < (-2.0 * (1.0 - y0) * (1.0 - y1) / sigma2).exp() {
                // Crossed and came back inside the step (Brownian bridge).
                Some(
                    refine_crossing(rng, y0, y1, sigma2)
                        .unwrap_or((1.0 - y0) / ((1.0 - y0) + (1.0 - y1))),
                )
            } else {
                None
            };
            match frac {
                Some(f) => {
                    // The time up to this crossing; after the step's
                    // first, at least the minimum interval.
                    let mut used = remaining * f.clamp(0.0, 1.0);
                    if fired {
                        used = used.max(MIN_BLINK_INTERVAL_S);
                    }
                    fired = true;
                    self.potential = 0.0;
                    remaining = (remaining - used).max(0.0);
                }
                None => {
                    self.potential = y1;
                    remaining = 0.0;
                }
            }
        }
        if fired && allowed {
            self.begin();
        }
        fired
    }

    /// Begin a blink now (AU45) and reset the potential.
    pub fn start_blink(&mut self) {
        self.begin();
        self.potential = 0.0;
    }

    /// Begin a reflex blink now: the lids close, but the spontaneous
    /// process's potential runs on (the reflex arc is not the central
    /// blink generator).
    pub fn reflex_blink(&mut self) {
        self.begin();
    }

    fn begin(&mut self) {
        self.blink_time = Some(0.0);
        self.count += 1;
    }

    /// Report a gaze shift of `amplitude_deg`; may trigger a blink (see the
    /// module doc). Returns true if it did.
    pub fn gaze_shift(&mut self, p: &BlinkParams, amplitude_deg: f64, rng: &mut impl Rng) -> bool {
        let prob = ((amplitude_deg.abs() - p.gaze_trigger_min_deg)
            / (p.gaze_trigger_max_deg - p.gaze_trigger_min_deg))
            .clamp(0.0, 1.0);
        let trigger = prob > 0.0 && rng.random::<f64>() < prob;
        if trigger {
            self.start_blink();
        }
        trigger
    }

    /// AU45 level in [0, 1]: minimum-jerk closing over `close_s`, then
    /// minimum-jerk opening over `open_s` (80 / 120 ms).
    pub fn closure(&self, p: &BlinkParams) -> f64 {
        match self.blink_time {
            None => 0.0,
            Some(t) if t < p.close_s => shisen_gaze::util::math::min_jerk(t / p.close_s),
            Some(t) => 1.0 - shisen_gaze::util::math::min_jerk((t - p.close_s) / p.open_s),
        }
    }
}

/// Locate the first threshold crossing inside a step whose path is known
/// to cross: sample the Brownian bridge from `y0` to `y1` (variance
/// `sigma2` over the step) on 64 sub-steps and return the crossing time as
/// a fraction of the step (linear interpolation within the sub-step, with
/// the bridge test for excursions between sub-samples). `None` if the
/// sampled bridge does not cross (the caller then interpolates).
fn refine_crossing(rng: &mut impl Rng, y0: f64, y1: f64, sigma2: f64) -> Option<f64> {
    const M: usize = 64;
    let h = 1.0 / M as f64;
    let mut y = y0;
    for i in 0..M {
        let left = 1.0 - i as f64 * h; // remaining fraction of the step
        let next = if i + 1 == M {
            y1
        } else {
            let mean = y + (y1 - y) * h / left;
            let var = sigma2 * h * (left - h) / left;
            Normal::new(mean, var.sqrt()).expect("finite").sample(rng)
        };
        let hit = next >= 1.0
            || rng.random::<f64>() < (-2.0 * (1.0 - y) * (1.0 - next) / (sigma2 * h)).exp();
        if hit {
            let within = if next >= 1.0 {
                (1.0 - y) / (next - y)
            } else {
                0.5
            };
            return Some((i as f64 + within.clamp(0.0, 1.0)) * h);
        }
        y = next;
    }
    None
}

/// Increment of Y over `dt`: N(dt / mu, dt / lambda) (F8).
fn draw(rng: &mut impl Rng, dt: f64, mu: f64, lambda: f64) -> f64 {
    Normal::new(dt / mu, (dt / lambda).sqrt())
        .expect("finite positive sd")
        .sample(rng)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::params::FaceParams;
    use rand::SeedableRng;
    use rand::rngs::StdRng;

    #[test]
    fn erfc_accuracy() {
        for (x, v) in [
            (0.0, 1.0),
            (0.5, 0.479_500_122_186_953_5),
            (1.0, 0.157_299_207_050_285_13),
            (2.0, 0.004_677_734_981_047_266),
            (3.0, 2.209_049_699_858_544e-5),
            (-1.0, 1.842_700_792_949_715),
        ] {
            assert!(
                ((erfc(x) - v) / v).abs() < 2e-7,
                "erfc({x}) = {} vs {v}",
                erfc(x)
            );
        }
        assert!((normal_cdf(1.959_963_984_540_054) - 0.975).abs() < 1e-7);
        // IG CDF: monotone to 1, median of IG(4, 13.94) is below the mean.
        assert!(inverse_gaussian_cdf(4.0, 4.0, 13.94) > 0.5);
        assert!((inverse_gaussian_cdf(200.0, 4.0, 13.94) - 1.0).abs() < 1e-9);
    }

    /// Blink intervals at `dt`: returns (intervals, n).
    fn intervals(dt: f64, n: usize, seed: u64) -> Vec<f64> {
        intervals_scaled(dt, n, seed, 1.0)
    }

    fn intervals_scaled(dt: f64, n: usize, seed: u64, scale: f64) -> Vec<f64> {
        let p = FaceParams::default_params().blink;
        let mut rng = StdRng::seed_from_u64(seed);
        let mut b = BlinkProcess::default();
        let mut out = Vec::with_capacity(n);
        let (mut steps, mut last) = (0u64, 0u64);
        while out.len() < n {
            steps += 1;
            if b.step(&p, dt, true, scale, &mut rng) {
                out.push((steps - last) as f64 * dt);
                last = steps;
            }
        }
        out
    }

    fn ks_statistic(mut x: Vec<f64>, mu: f64, lambda: f64) -> f64 {
        x.sort_by(f64::total_cmp);
        let n = x.len() as f64;
        x.iter()
            .enumerate()
            .map(|(i, &v)| {
                let f = inverse_gaussian_cdf(v, mu, lambda);
                (f - i as f64 / n).abs().max(((i + 1) as f64 / n - f).abs())
            })
            .fold(0.0, f64::max)
    }

    #[test]
    fn blink_intervals_are_inverse_gaussian_at_control_rate() {
        let n = 2500;
        let x = intervals(0.001, n, 7);
        let mean = x.iter().sum::<f64>() / n as f64;
        let d = ks_statistic(x, 4.0, 13.94);
        let crit = 1.628 / (n as f64).sqrt(); // KS 1 % critical value
        println!("dt=1ms: mean {mean:.4} s, KS D = {d:.4} (crit {crit:.4})");
        assert!((mean - 4.0).abs() < 0.15, "mean {mean}");
        assert!(d < crit, "KS D {d} >= {crit}");
    }

    #[test]
    fn overshoot_correction_holds_at_coarse_dt() {
        // Uncorrected, dt = 0.1 s gives ~4.21 s (face.md 6).
        let n = 4000;
        let x = intervals(0.1, n, 11);
        let mean = x.iter().sum::<f64>() / n as f64;
        println!("dt=100ms: mean {mean:.4} s");
        assert!((mean - 4.0).abs() < 0.1, "mean {mean}");
    }

    #[test]
    fn closure_profile_and_gaze_trigger() {
        let p = FaceParams::default_params().blink;
        let mut b = BlinkProcess::default();
        b.start_blink();
        let mut rng = StdRng::seed_from_u64(1);
        assert_eq!(b.closure(&p), 0.0);
        // Step at 1 kHz with a potential that cannot fire: keep it at 0.
        let mut max_t = 0.0;
        for i in 1..=201 {
            b.potential = -1e9;
            b.step(&p, 0.001, false, 1.0, &mut rng);
            let c = b.closure(&p);
            if (c - 1.0).abs() < 1e-9 {
                max_t = i as f64 * 0.001;
            }
        }
        assert!(
            (max_t - 0.080).abs() < 1.5e-3,
            "fully closed at 80 ms, got {max_t}"
        );
        assert!(
            b.blink_time.is_none() && b.closure(&p) == 0.0,
            "open again after 200 ms"
        );
        assert!(!b.gaze_shift(&p, 10.0, &mut rng));
        assert!(b.gaze_shift(&p, p.gaze_trigger_max_deg + 5.0, &mut rng));
    }

    /// The step's loop over threshold crossings ends for any parameters,
    /// in range or not (a mean interval of 1e-300 s once spun it for
    /// ever), and any step: the extremes the ranges allow, with the
    /// engaged and arousal factors at their ends, and absurd values set
    /// in code.
    #[test]
    fn a_step_ends_whatever_the_parameters() {
        let mut p = FaceParams::default_params().blink;
        let mut rng = StdRng::seed_from_u64(3);
        // Shortest: engaged 0.25, arousal gain 3 at full arousal.
        let fastest = 0.25 / 4.0;
        for (mu, lambda, scale) in [
            (0.5, 0.5, fastest),
            (0.5, 1000.0, fastest),
            (60.0, 1000.0, 10.0),
            (1e-300, 1e-300, 1.0),
            (1e300, 1e-300, 1.0),
        ] {
            p.mean_interval_s = mu;
            p.shape_s = lambda;
            let mut b = BlinkProcess::default();
            for dt in [1e-3, 0.1, 2.0, 100.0, 0.0, -1.0, f64::NAN, f64::INFINITY] {
                b.step(&p, dt, true, scale, &mut rng);
                assert!(b.potential.is_finite(), "{mu} {lambda} {dt}");
            }
        }
    }

    /// While engaged (sparring) the intervals stretch by the documented
    /// factor: mean 4.0 s x 3 = 12 s (1500 blinks, standard error about
    /// 0.17 s at that scale; the bound is about 2 %, some 3 standard errors).
    #[test]
    fn engaged_blinks_come_less_often() {
        let k = FaceParams::default_params().blink.engaged_interval_scale;
        let v = intervals_scaled(0.01, 1500, 9, k);
        let mean = v.iter().sum::<f64>() / v.len() as f64;
        assert!(
            (mean - 4.0 * k).abs() < 0.02 * 4.0 * k,
            "mean {mean} vs {}",
            4.0 * k
        );
    }
}
