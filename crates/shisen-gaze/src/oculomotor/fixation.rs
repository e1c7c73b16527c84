//! Idle gaze while fixating: microsaccades plus a slow drift, as a small
//! (yaw, pitch) offset added to the fixation target (the eyes are never
//! perfectly still; a perfectly still eye reads as dead).
//!
//! # Statistics used (defaults)
//! - **Microsaccade amplitude**: log-normal, median 0.3 deg, log-sd 0.5,
//!   truncated at 1 deg (mean 0.34 deg = 20 arcmin). Recent video-based
//!   studies report mean microsaccade sizes of 13.7-38.4 arcmin
//!   (Martinez-Conde, Macknik, Troncoso & Hubel 2009, Trends Neurosci.
//!   32:463, as cited in J. Vision 2016 art. 2497929), and the 1 deg ceiling
//!   is the usual definition (Otero-Millan et al. 2008, J. Vision 8(14):21).
//!   The log-normal shape (a positive, right-skewed size distribution) is
//!   our choice.
//! - **Inter-microsaccadic interval** (end of one to onset of the next):
//!   gamma with shape 2 and mean 0.6 s, i.e. about 1.6 microsaccades per
//!   second including their ~22 ms duration; rates of 1-2 per second are the
//!   commonly reported range (Engbert & Kliegl 2003, Vision Res. 43:1035;
//!   Martinez-Conde et al. 2009). Shape 2 gives a unimodal distribution
//!   with few very short intervals (a soft refractory period); its exact
//!   value is our choice.
//! - **Microsaccade shape**: the main-sequence saccade profile of
//!   [`super::saccade`] (duration 21 ms + 2.2 ms/deg); microsaccades lie on
//!   the saccadic main sequence (Zuber, Stark & Cook 1965).
//! - **Direction**: microsaccades tend to correct fixation errors (Cornsweet
//!   1956; Engbert & Kliegl 2004): when the offset exceeds
//!   [`FixationParams::correction_threshold`] the microsaccade aims back at
//!   the target with a normal angular scatter, otherwise its direction is
//!   uniform.
//! - **Drift**: 2-D Brownian motion (`<|dx|^2> = 4 D t`) with D = 20
//!   arcmin^2/s, within the 10-40 arcmin^2/s range of modern high-resolution
//!   recordings (Kuang, Poletti, Victor & Rucci 2012, Curr. Biol. 22:510;
//!   Cherici et al. 2012, J. Vision 12(6):31). Drift pauses during a
//!   microsaccade; tremor (< 1 arcmin, 50-100 Hz) is below the eye joint's
//!   bandwidth and is omitted.
//!
//! The generator is stepped in simulation time with the caller's RNG; the
//! same seed gives the same sequence.

use glam::DVec2;
use rand::Rng;
use rand_distr::{Distribution, Gamma, LogNormal, Normal, StandardNormal, Uniform};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::saccade::{SaccadeLaw, SaccadeParams, SaccadeProfile};

/// Static parameters of the fixational eye-movement generator. Radians, seconds.
///
/// Microsaccades are at most about 1 deg by definition (2 deg in some
/// studies); angles are bounded at 0.1 rad (5.7 deg), beyond which the
/// movements are ordinary saccades.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct FixationParams {
    /// Off: [`FixationState::step`] returns a zero offset.
    pub enabled: bool,
    /// Median microsaccade amplitude (rad). Default 0.3 deg. Above 0, at
    /// most 0.1 rad.
    #[schemars(range(max = 0.1), extend("exclusiveMinimum" = 0.0))]
    pub amplitude_median: f64,
    /// Standard deviation of ln(amplitude), 0.001-3. Default 0.5; 3 spreads
    /// the sizes over several decades.
    #[schemars(range(min = 0.001, max = 3.0))]
    pub amplitude_log_sd: f64,
    /// Largest microsaccade (rad); larger draws are redrawn. Default 1 deg.
    /// Above 0, at most 0.1 rad.
    #[schemars(range(max = 0.1), extend("exclusiveMinimum" = 0.0))]
    pub amplitude_max: f64,
    /// Mean inter-microsaccadic interval, end to next onset (s). Default 0.6
    /// (1-2 microsaccades a second). Above 0, at most 10 s (far rarer than
    /// any reported rate).
    #[schemars(range(max = 10.0), extend("exclusiveMinimum" = 0.0))]
    pub interval_mean: f64,
    /// Gamma shape of the interval. Default 2. Above 0, at most 100 (nearly
    /// periodic).
    #[schemars(range(max = 100.0), extend("exclusiveMinimum" = 0.0))]
    pub interval_shape: f64,
    /// Drift diffusion coefficient D (rad^2/s), `<|dx|^2> = 4 D t`.
    /// Default 20 arcmin^2/s = 1.692e-6 rad^2/s (human 10-40 arcmin^2/s).
    /// 0-1e-4 rad^2/s: about 60 times the default, a drift of a degree a
    /// second.
    #[schemars(range(min = 0.0, max = 1e-4))]
    pub drift_diffusion: f64,
    /// Offsets beyond this make the next microsaccade corrective (rad). Default 0.1 deg.
    /// 0-0.1 rad.
    #[schemars(range(min = 0.0, max = 0.1))]
    pub correction_threshold: f64,
    /// Angular scatter (sd) of a corrective microsaccade's direction (rad). Default 30 deg.
    /// 0-3.15 rad: beyond half a turn the direction is uniform anyway.
    #[schemars(range(min = 0.0, max = 3.15))]
    pub direction_scatter: f64,
    /// The offset never exceeds this (rad); drift is stopped at it. Default 1 deg.
    /// Above 0, at most 0.1 rad.
    #[schemars(range(max = 0.1), extend("exclusiveMinimum" = 0.0))]
    pub max_offset: f64,
    /// Saccade timing for microsaccades. Its `law` is ignored: microsaccades
    /// always use the main sequence (they lie on it, Zuber, Stark & Cook 1965).
    pub saccade: SaccadeParams,
}

impl Default for FixationParams {
    fn default() -> Self {
        let arcmin2 = (1.0f64 / 60.0).to_radians().powi(2);
        Self {
            enabled: true,
            amplitude_median: 0.3f64.to_radians(),
            amplitude_log_sd: 0.5,
            amplitude_max: 1f64.to_radians(),
            interval_mean: 0.6,
            interval_shape: 2.0,
            drift_diffusion: 20.0 * arcmin2,
            correction_threshold: 0.1f64.to_radians(),
            direction_scatter: 30f64.to_radians(),
            max_offset: 1f64.to_radians(),
            saccade: SaccadeParams {
                law: SaccadeLaw::MainSequence,
                ..SaccadeParams::default()
            },
        }
    }
}

/// Draws of a microsaccade's amplitude before the maximum is taken.
const MAX_AMPLITUDE_DRAWS: usize = 64;

impl FixationParams {
    fn draw_amplitude<R: Rng + ?Sized>(&self, rng: &mut R) -> f64 {
        let d = LogNormal::new(self.amplitude_median.ln(), self.amplitude_log_sd)
            .expect("validated log-normal parameters");
        // A log-normal truncated at the maximum, by rejection. The tries
        // are bounded so that a maximum far in the lower tail cannot spin
        // (at the shipped values a draw is seldom refused):
        // past them the amplitude is the maximum.
        for _ in 0..MAX_AMPLITUDE_DRAWS {
            let a = d.sample(rng);
            if a <= self.amplitude_max {
                return a;
            }
        }
        self.amplitude_max
    }

    fn draw_interval<R: Rng + ?Sized>(&self, rng: &mut R) -> f64 {
        let scale = self.interval_mean / self.interval_shape;
        Gamma::new(self.interval_shape, scale)
            .expect("validated gamma parameters")
            .sample(rng)
    }
}

/// A microsaccade that has just begun.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Microsaccade {
    /// Amplitude (rad).
    pub amplitude: f64,
    /// Unit direction (yaw, pitch).
    pub direction: DVec2,
    /// Duration (s).
    pub duration: f64,
}

/// Output of one step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FixationSample {
    /// Offset to add to the fixation target (yaw, pitch), rad.
    pub offset: DVec2,
    /// Its mean rate over the step, rad/s.
    pub rate: DVec2,
    /// Set on the step in which a microsaccade began.
    pub onset: Option<Microsaccade>,
    /// True on the step in which a microsaccade ended.
    pub ended: bool,
}

#[derive(Clone, Copy, Debug, PartialEq)]
struct Running {
    from: DVec2,
    direction: DVec2,
    profile: SaccadeProfile,
    elapsed: f64,
}

/// Evolving state of the generator.
#[derive(Clone, Debug, PartialEq)]
pub struct FixationState {
    offset: DVec2,
    until_onset: f64,
    running: Option<Running>,
}

impl FixationState {
    /// Starts at zero offset with a freshly drawn first interval.
    pub fn new<R: Rng + ?Sized>(params: &FixationParams, rng: &mut R) -> Self {
        Self {
            offset: DVec2::ZERO,
            until_onset: params.draw_interval(rng),
            running: None,
        }
    }

    /// Current offset (rad).
    pub fn offset(&self) -> DVec2 {
        self.offset
    }

    /// Back to zero offset, e.g. after a real saccade landed on a new target.
    pub fn reset<R: Rng + ?Sized>(&mut self, params: &FixationParams, rng: &mut R) {
        *self = Self::new(params, rng);
    }

    /// Advances by `dt` (s).
    pub fn step<R: Rng + ?Sized>(
        &mut self,
        params: &FixationParams,
        dt: f64,
        rng: &mut R,
    ) -> FixationSample {
        if !params.enabled {
            self.offset = DVec2::ZERO;
            self.running = None;
            return FixationSample {
                offset: DVec2::ZERO,
                rate: DVec2::ZERO,
                onset: None,
                ended: false,
            };
        }
        let before = self.offset;
        let mut onset = None;
        let mut ended = false;
        if self.running.is_none() {
            self.until_onset -= dt;
            if self.until_onset <= 0.0 {
                let amplitude = params.draw_amplitude(rng);
                let direction = self.direction(params, rng);
                let timing = SaccadeParams {
                    law: SaccadeLaw::MainSequence,
                    ..params.saccade.clone()
                };
                let profile = SaccadeProfile::plan(&timing, amplitude);
                onset = Some(Microsaccade {
                    amplitude,
                    direction,
                    duration: profile.duration(),
                });
                self.running = Some(Running {
                    from: self.offset,
                    direction,
                    profile,
                    elapsed: 0.0,
                });
            } else {
                // Drift: Brownian, per-axis variance 2 D dt.
                let sd = (2.0 * params.drift_diffusion * dt).sqrt();
                let dx: f64 = StandardNormal.sample(rng);
                let dy: f64 = StandardNormal.sample(rng);
                let next = self.offset + DVec2::new(dx, dy) * sd;
                self.offset = next.clamp_length_max(params.max_offset);
            }
        }
        if let Some(run) = &mut self.running {
            run.elapsed += dt;
            self.offset = run.from + run.direction * run.profile.position(run.elapsed);
            if run.elapsed >= run.profile.duration() {
                self.running = None;
                self.until_onset = params.draw_interval(rng);
                ended = true;
            }
        }
        FixationSample {
            offset: self.offset,
            rate: (self.offset - before) / dt,
            onset,
            ended,
        }
    }

    fn direction<R: Rng + ?Sized>(&self, params: &FixationParams, rng: &mut R) -> DVec2 {
        let angle = if self.offset.length() > params.correction_threshold {
            let back = (-self.offset).to_angle();
            let scatter = Normal::new(0.0, params.direction_scatter).expect("validated scatter");
            back + scatter.sample(rng)
        } else {
            Uniform::new(-std::f64::consts::PI, std::f64::consts::PI)
                .expect("valid range")
                .sample(rng)
        };
        DVec2::from_angle(angle)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand::rngs::StdRng;

    const DT: f64 = 0.001;

    /// Complementary error function (Numerical Recipes' erfcc, |rel err| < 1.2e-7).
    fn erfc(x: f64) -> f64 {
        let z = x.abs();
        let t = 1.0 / (1.0 + 0.5 * z);
        let poly = -z * z - 1.26551223
            + t * (1.00002368
                + t * (0.37409196
                    + t * (0.09678418
                        + t * (-0.18628806
                            + t * (0.27886807
                                + t * (-1.13520398
                                    + t * (1.48851587 + t * (-0.82215223 + t * 0.17087277))))))));
        let r = t * poly.exp();
        if x >= 0.0 { r } else { 2.0 - r }
    }

    fn lognormal_cdf(x: f64, median: f64, s: f64) -> f64 {
        0.5 * erfc(-(x / median).ln() / (s * std::f64::consts::SQRT_2))
    }

    /// Gamma(shape 2, scale th) CDF in closed form.
    fn gamma2_cdf(x: f64, th: f64) -> f64 {
        1.0 - (-x / th).exp() * (1.0 + x / th)
    }

    fn ks(mut xs: Vec<f64>, cdf: impl Fn(f64) -> f64) -> f64 {
        xs.sort_by(f64::total_cmp);
        let n = xs.len() as f64;
        xs.iter()
            .enumerate()
            .map(|(i, &x)| {
                let f = cdf(x);
                (f - i as f64 / n).abs().max(((i + 1) as f64 / n - f).abs())
            })
            .fold(0.0, f64::max)
    }

    struct Run {
        amplitudes: Vec<f64>,
        intervals: Vec<f64>,
        durations: Vec<f64>,
        drift_sq: Vec<f64>,
        max_offset: f64,
        offsets: Vec<DVec2>,
    }

    /// Simulates `seconds` of fixation and measures the generator's *output*.
    fn run(seed: u64, seconds: f64) -> Run {
        let p = FixationParams::default();
        let mut rng = StdRng::seed_from_u64(seed);
        let mut s = FixationState::new(&p, &mut rng);
        let mut r = Run {
            amplitudes: vec![],
            intervals: vec![],
            durations: vec![],
            drift_sq: vec![],
            max_offset: 0.0,
            offsets: vec![],
        };
        let (mut t, mut start_offset, mut onset_t, mut last_end) =
            (0.0, DVec2::ZERO, 0.0, None::<f64>);
        let mut in_ms = false;
        let n = (seconds / DT) as usize;
        for _ in 0..n {
            let before = s.offset();
            let smp = s.step(&p, DT, &mut rng);
            t += DT;
            if smp.onset.is_some() {
                // onset happens within this step: the step began at t - DT
                start_offset = before;
                onset_t = t - DT;
                if let Some(end) = last_end {
                    r.intervals.push(onset_t - end);
                }
                in_ms = true;
            } else if !in_ms {
                r.drift_sq.push((smp.offset - before).length_squared());
            }
            if smp.ended {
                r.amplitudes.push((smp.offset - start_offset).length());
                r.durations.push(t - onset_t);
                last_end = Some(t);
                in_ms = false;
            }
            r.max_offset = r.max_offset.max(smp.offset.length());
            r.offsets.push(smp.offset);
        }
        r
    }

    #[test]
    fn ten_minutes_match_the_distributions() {
        let p = FixationParams::default();
        let r = run(2024, 600.0);
        let n_a = r.amplitudes.len() as f64;
        let n_i = r.intervals.len() as f64;
        // amplitude: truncated log-normal
        let trunc = lognormal_cdf(p.amplitude_max, p.amplitude_median, p.amplitude_log_sd);
        let d_a = ks(r.amplitudes.clone(), |x| {
            lognormal_cdf(x, p.amplitude_median, p.amplitude_log_sd) / trunc
        });
        // interval: gamma(2, mean/2), end to next onset; 1 ms steps quantise it
        let d_i = ks(r.intervals.clone(), |x| {
            gamma2_cdf(x, p.interval_mean / 2.0)
        });
        let crit = |n: f64| 1.628 / n.sqrt(); // KS 1 % critical value
        let mut amps = r.amplitudes.clone();
        amps.sort_by(f64::total_cmp);
        let median = amps[amps.len() / 2].to_degrees();
        let mean_amp = r.amplitudes.iter().sum::<f64>() / n_a;
        let mean_int = r.intervals.iter().sum::<f64>() / n_i;
        let rate = n_a / 600.0;
        let d_est = r.drift_sq.iter().sum::<f64>() / r.drift_sq.len() as f64 / (4.0 * DT);
        let arcmin2 = (1.0f64 / 60.0).to_radians().powi(2);
        println!(
            "microsaccades: n={n_a}, rate {rate:.3}/s, median {median:.3} deg, mean {:.3} deg, KS D={d_a:.4} (crit {:.4}); \
             intervals mean {mean_int:.3} s, KS D={d_i:.4} (crit {:.4}); drift D={:.2} arcmin^2/s; max offset {:.3} deg; \
             mean duration {:.1} ms",
            mean_amp.to_degrees(),
            crit(n_a),
            crit(n_i),
            d_est / arcmin2,
            r.max_offset.to_degrees(),
            1e3 * r.durations.iter().sum::<f64>() / r.durations.len() as f64,
        );
        assert!(d_a < crit(n_a), "amplitude KS {d_a}");
        assert!(d_i < crit(n_i), "interval KS {d_i}");
        assert!((median - 0.3).abs() < 0.03, "median {median}");
        assert!((1.0..=2.0).contains(&rate), "rate {rate}");
        assert!(
            (d_est / arcmin2 - 20.0).abs() < 1.0,
            "drift D {}",
            d_est / arcmin2
        );
        assert!(r.max_offset <= p.max_offset + p.amplitude_max);
        // main-sequence durations: 21 ms + 2.2 ms/deg (within a step)
        for (a, d) in r.amplitudes.iter().zip(&r.durations) {
            assert!((d - (0.021 + 0.0022 * a.to_degrees())).abs() <= DT + 1e-9);
        }
        // the offset stays small: corrective microsaccades keep it near the target
        let rms = (r.offsets.iter().map(|o| o.length_squared()).sum::<f64>()
            / r.offsets.len() as f64)
            .sqrt();
        println!("rms offset {:.3} deg", rms.to_degrees());
        assert!(rms.to_degrees() < 0.5);
    }

    #[test]
    fn same_seed_same_sequence() {
        let (a, b, c) = (run(5, 20.0), run(5, 20.0), run(6, 20.0));
        assert_eq!(a.offsets, b.offsets);
        assert_ne!(a.offsets, c.offsets);
    }

    #[test]
    fn disabled_is_still() {
        let p = FixationParams {
            enabled: false,
            ..FixationParams::default()
        };
        let mut rng = StdRng::seed_from_u64(1);
        let mut s = FixationState::new(&p, &mut rng);
        for _ in 0..5000 {
            assert_eq!(s.step(&p, DT, &mut rng).offset, DVec2::ZERO);
        }
    }

    #[test]
    fn params_deserialise() {
        let p: FixationParams = crate::util::ron::parse_ron(
            "(enabled: false, interval_mean: 0.5)",
            std::path::Path::new("t.ron"),
        )
        .unwrap();
        assert!(!p.enabled && p.interval_mean == 0.5);
        assert!(
            crate::util::ron::parse_ron::<FixationParams>(
                "(amplitude_log_sd: 9.0)",
                std::path::Path::new("t.ron")
            )
            .is_err()
        );
    }

    #[test]
    fn a_maximum_far_below_the_median_cannot_spin() {
        let p = FixationParams {
            amplitude_median: 0.1,
            amplitude_max: 1e-6,
            amplitude_log_sd: 0.001,
            ..FixationParams::default()
        };
        let mut rng = rand::rngs::StdRng::seed_from_u64(1);
        assert_eq!(p.draw_amplitude(&mut rng), 1e-6);
    }
}
