//! The soundtrack's instruments, synthesised (no recordings, so nothing to
//! license): filters, noise, the one-shot sounds of a bout (gloves on
//! heads, bodies and guards, feet on the canvas, the bell, a punch's
//! exhale, a body landing) and the voices (corners, referee, crowd).
//!
//! Every sound is made from noise and resonances shaped by envelopes, the
//! way foley synthesis does it (Farnell 2010, *Designing Sound*, MIT
//! Press): an impact is a short burst through the struck thing's
//! resonance; a voice is a glottal pulse train through three formants.

use std::f32::consts::TAU;

/// Speed of sound in air at 20 C, m/s.
pub const SPEED_OF_SOUND: f64 = 343.0;

/// A fast, seeded white-noise source (xorshift32): audio noise needs
/// speed and repeatability, not statistical quality.
#[derive(Clone, Debug)]
pub struct Noise(u32);

impl Noise {
    /// A source from `seed` (any value; zero is moved off).
    pub fn new(seed: u64) -> Self {
        let s = (seed ^ (seed >> 32)) as u32;
        Noise(if s == 0 { 0x9E37_79B9 } else { s })
    }

    /// Uniform in [-1, 1).
    pub fn white(&mut self) -> f32 {
        let mut x = self.0;
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        self.0 = x;
        (x as f32 / u32::MAX as f32) * 2.0 - 1.0
    }

    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f32 {
        (self.white() + 1.0) * 0.5
    }
}

/// A second-order filter section, coefficients from R. Bristow-Johnson's
/// *Audio EQ Cookbook* (W3C note, 2021), transposed direct form II.
#[derive(Clone, Copy, Debug, Default)]
pub struct Biquad {
    b: [f32; 3],
    a: [f32; 2],
    z: [f32; 2],
}

impl Biquad {
    fn with(b: [f32; 3], a0: f32, a: [f32; 2]) -> Self {
        Biquad {
            b: b.map(|x| x / a0),
            a: a.map(|x| x / a0),
            z: [0.0; 2],
        }
    }

    fn omega(rate: f32, f: f32, q: f32) -> (f32, f32) {
        let w = TAU * (f / rate).clamp(1e-5, 0.49);
        (w.cos(), w.sin() / (2.0 * q.max(0.05)))
    }

    /// Low-pass at `f` Hz.
    pub fn lowpass(rate: f32, f: f32, q: f32) -> Self {
        let (c, al) = Self::omega(rate, f, q);
        let b = (1.0 - c) / 2.0;
        Self::with([b, 1.0 - c, b], 1.0 + al, [-2.0 * c, 1.0 - al])
    }

    /// High-pass at `f` Hz.
    pub fn highpass(rate: f32, f: f32, q: f32) -> Self {
        let (c, al) = Self::omega(rate, f, q);
        let b = (1.0 + c) / 2.0;
        Self::with([b, -1.0 - c, b], 1.0 + al, [-2.0 * c, 1.0 - al])
    }

    /// Band-pass centred on `f` Hz, 0 dB at the peak.
    pub fn bandpass(rate: f32, f: f32, q: f32) -> Self {
        let (c, al) = Self::omega(rate, f, q);
        Self::with([al, 0.0, -al], 1.0 + al, [-2.0 * c, 1.0 - al])
    }

    /// Retune (new coefficients, the state kept: no click).
    pub fn retune(&mut self, other: Biquad) {
        self.b = other.b;
        self.a = other.a;
    }

    /// Filter one sample.
    pub fn run(&mut self, x: f32) -> f32 {
        let y = self.b[0] * x + self.z[0];
        self.z[0] = self.b[1] * x - self.a[0] * y + self.z[1];
        self.z[1] = self.b[2] * x - self.a[1] * y;
        y
    }
}

/// A decaying exponential with time constant `tau` s at sample `i`.
fn decay(i: usize, rate: f32, tau: f32) -> f32 {
    (-(i as f32) / (rate * tau)).exp()
}

/// What a glove met.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Struck {
    /// A head: a sharp leather smack over a short thump.
    Head,
    /// The trunk: a deep thud.
    Body,
    /// A glove or forearm (a blocked punch): a muffled pat.
    Guard,
}

/// A glove's impact, `level` 0-1.5 (from the blow's impulse).
pub fn impact(rate: f32, noise: &mut Noise, struck: Struck, level: f32) -> Vec<f32> {
    // (thump Hz, its decay s, the smack's band Hz, its decay s, smack share)
    let (f0, t0, band, t1, smack) = match struck {
        Struck::Head => (170.0, 0.035, 2200.0, 0.010, 0.8),
        Struck::Body => (85.0, 0.070, 700.0, 0.025, 0.45),
        Struck::Guard => (140.0, 0.030, 500.0, 0.020, 0.5),
    };
    let n = (rate * 0.25) as usize;
    let mut bp = Biquad::bandpass(rate, band, 0.9);
    let mut out = Vec::with_capacity(n);
    let mut phase = 0.0f32;
    for i in 0..n {
        // The thump's pitch drops as the struck tissue gives.
        let f = f0 * (1.0 + 0.6 * decay(i, rate, 0.015));
        phase += TAU * f / rate;
        let thump = phase.sin() * decay(i, rate, t0);
        let crack = bp.run(noise.white()) * decay(i, rate, t1) * 3.0;
        let attack = (i as f32 / (rate * 0.0008)).min(1.0);
        out.push(level * attack * ((1.0 - smack) * thump + smack * crack));
    }
    out
}

/// A foot landing on the canvas at `level` 0-1.
pub fn footfall(rate: f32, noise: &mut Noise, level: f32) -> Vec<f32> {
    let n = (rate * 0.12) as usize;
    let mut lp = Biquad::lowpass(rate, 450.0, 0.7);
    let mut hp = Biquad::highpass(rate, 2500.0, 0.7);
    let mut phase = 0.0f32;
    (0..n)
        .map(|i| {
            phase += TAU * 65.0 / rate;
            let thump = phase.sin() * decay(i, rate, 0.035);
            let scuff = 0.5 * lp.run(noise.white()) * decay(i, rate, 0.03)
                + 0.15 * hp.run(noise.white()) * decay(i, rate, 0.012);
            level * (0.6 * thump + scuff)
        })
        .collect()
}

/// A body landing on the canvas (a knockdown), `level` 0-1.5.
pub fn body_fall(rate: f32, noise: &mut Noise, level: f32) -> Vec<f32> {
    let n = (rate * 0.5) as usize;
    let mut lp = Biquad::lowpass(rate, 300.0, 0.8);
    let mut phase = 0.0f32;
    (0..n)
        .map(|i| {
            phase += TAU * 48.0 / rate;
            let boom = phase.sin() * decay(i, rate, 0.12);
            let slap = lp.run(noise.white()) * decay(i, rate, 0.06) * 2.0;
            level * (0.7 * boom + 0.3 * slap)
        })
        .collect()
}

/// The ring's bell struck once: a bronze bell's inharmonic partials
/// (hum, prime, tierce, quint, nominal: Rossing 2000, *Science of
/// Percussion Instruments*, ch. 12), each decaying at its own rate.
pub fn bell(rate: f32, noise: &mut Noise) -> Vec<f32> {
    const F0: f32 = 880.0;
    // (ratio, amplitude, decay s)
    const PARTIALS: [(f32, f32, f32); 6] = [
        (0.5, 0.25, 2.2),
        (1.0, 0.5, 1.8),
        (1.2, 0.35, 1.2),
        (1.5, 0.2, 0.9),
        (2.0, 0.4, 1.0),
        (2.51, 0.2, 0.5),
    ];
    let n = (rate * 2.5) as usize;
    let mut hp = Biquad::highpass(rate, 3000.0, 0.7);
    (0..n)
        .map(|i| {
            let t = i as f32 / rate;
            let ring: f32 = PARTIALS
                .iter()
                .map(|&(r, a, tau)| a * (TAU * F0 * r * t).sin() * (-t / tau).exp())
                .sum();
            let strike = hp.run(noise.white()) * decay(i, rate, 0.004);
            ring + 0.6 * strike
        })
        .collect()
}

/// A boxer's sharp exhale through the teeth with a punch ("tss"),
/// `level` 0-1.
pub fn exhale(rate: f32, noise: &mut Noise, level: f32) -> Vec<f32> {
    let n = (rate * 0.2) as usize;
    let mut bp = Biquad::bandpass(rate, 3800.0, 1.4);
    (0..n)
        .map(|i| {
            let t = i as f32 / rate;
            let env = (t / 0.012).min(1.0) * (-(t - 0.012).max(0.0) / 0.05).exp();
            level * 1.6 * bp.run(noise.white()) * env
        })
        .collect()
}

/// One clap of a hand (applause is many, at random).
pub fn clap(rate: f32, noise: &mut Noise, centre: f32) -> Vec<f32> {
    let n = (rate * 0.03) as usize;
    let mut bp = Biquad::bandpass(rate, centre, 1.2);
    (0..n)
        .map(|i| 2.0 * bp.run(noise.white()) * decay(i, rate, 0.006))
        .collect()
}

/// Vowel formants F1-F3, Hz: the averages of men's vowels in Peterson &
/// Barney 1952 (J. Acoust. Soc. Am. 24:175), for /a/ /e/ /i/ /o/ /u/.
pub const VOWELS: [[f32; 3]; 5] = [
    [730.0, 1090.0, 2440.0],
    [530.0, 1840.0, 2480.0],
    [270.0, 2290.0, 3010.0],
    [570.0, 840.0, 2410.0],
    [300.0, 870.0, 2240.0],
];

/// One syllable a voice is to say.
#[derive(Clone, Copy, Debug)]
pub struct Syllable {
    /// Its start, samples from the voice's clock.
    pub start: u64,
    /// Length, samples.
    pub len: u64,
    /// Index into [`VOWELS`].
    pub vowel: usize,
    /// Loudness, 0-1.
    pub level: f32,
    /// Pitch, Hz.
    pub pitch: f32,
}

/// A voice (a corner man, the referee): a glottal pulse train through
/// three formant resonators (Klatt 1980, J. Acoust. Soc. Am. 67:971),
/// syllable by syllable, each opened by a consonant's noise burst.
#[derive(Clone, Debug)]
pub struct Voice {
    rate: f32,
    clock: u64,
    phase: f32,
    formants: [Biquad; 3],
    fricative: Biquad,
    glottis: Biquad,
    queue: std::collections::VecDeque<Syllable>,
}

impl Voice {
    /// A silent voice.
    pub fn new(rate: f32) -> Self {
        Voice {
            rate,
            clock: 0,
            phase: 0.0,
            formants: VOWELS[0].map(|f| Biquad::bandpass(rate, f, 8.0)),
            fricative: Biquad::bandpass(rate, 4500.0, 1.5),
            glottis: Biquad::lowpass(rate, 1500.0, 0.7),
            queue: std::collections::VecDeque::new(),
        }
    }

    /// The voice's clock, samples.
    pub fn clock(&self) -> u64 {
        self.clock
    }

    /// Whether it has nothing left to say.
    pub fn quiet(&self) -> bool {
        self.queue.is_empty()
    }

    /// Say a syllable (appended; its start is on the voice's clock).
    pub fn say(&mut self, s: Syllable) {
        self.queue.push_back(s);
    }

    /// The next sample.
    pub fn next(&mut self, noise: &mut Noise) -> f32 {
        let now = self.clock;
        self.clock += 1;
        while self.queue.front().is_some_and(|s| s.start + s.len <= now) {
            self.queue.pop_front();
        }
        let Some(&s) = self.queue.front().filter(|s| s.start <= now) else {
            return 0.0;
        };
        let i = (now - s.start) as f32;
        if i == 0.0 {
            for (f, hz) in self.formants.iter_mut().zip(VOWELS[s.vowel]) {
                f.retune(Biquad::bandpass(self.rate, hz, 8.0));
            }
        }
        let len = s.len as f32;
        let (rise, fall) = (0.02 * self.rate, 0.05 * self.rate);
        let env = (i / rise).min(1.0) * ((len - i) / fall).clamp(0.0, 1.0);
        // Pitch falls over the syllable (declination) with some jitter.
        let f0 = s.pitch * (1.0 - 0.12 * i / len) * (1.0 + 0.01 * noise.white());
        self.phase = (self.phase + f0 / self.rate).fract();
        let pulse = self.glottis.run(1.0 - 2.0 * self.phase);
        let voiced: f32 = self
            .formants
            .iter_mut()
            .zip([1.0, 0.6, 0.25])
            .map(|(f, g)| g * f.run(pulse))
            .sum();
        let burst = if i < 0.03 * self.rate {
            self.fricative.run(noise.white()) * (1.0 - i / (0.03 * self.rate))
        } else {
            0.0
        };
        s.level * env * (3.0 * voiced + 0.6 * burst)
    }
}

/// Smooth saturation to (-1, 1) (a rational tanh), so a loud moment is
/// squashed, not clipped.
pub fn soft_clip(x: f32) -> f32 {
    let x = x.clamp(-3.0, 3.0);
    x * (27.0 + x * x) / (27.0 + 9.0 * x * x)
}

/// A slow random swell in 0-1 (sum of slow sines): the murmur of a crowd
/// rises and falls as groups talk.
#[derive(Clone, Debug)]
pub struct Murmur {
    rates: [f32; 6],
    phases: [f32; 6],
}

impl Murmur {
    /// Six groups at rates 0.2-2 Hz with random phases.
    pub fn new(noise: &mut Noise) -> Self {
        Murmur {
            rates: std::array::from_fn(|_| 0.2 + 1.8 * noise.unit()),
            phases: std::array::from_fn(|_| TAU * noise.unit()),
        }
    }

    /// The swell at time `t` s.
    pub fn at(&self, t: f32) -> f32 {
        let s: f32 = self
            .rates
            .iter()
            .zip(self.phases)
            .map(|(r, p)| (TAU * r * t + p).sin())
            .sum();
        (0.5 + 0.3 * s / 3.0_f32.sqrt()).clamp(0.0, 1.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rms(x: &[f32]) -> f32 {
        (x.iter().map(|v| v * v).sum::<f32>() / x.len() as f32).sqrt()
    }

    /// A band-pass passes its centre and stops a tone far from it.
    #[test]
    fn the_band_pass_passes_its_band() {
        let rate = 48_000.0;
        let tone = |f: f32| {
            let mut bp = Biquad::bandpass(rate, 1000.0, 2.0);
            let y: Vec<f32> = (0..48_000)
                .map(|i| bp.run((TAU * f * i as f32 / rate).sin()))
                .collect();
            rms(&y[24_000..])
        };
        assert!((tone(1000.0) - 0.707).abs() < 0.02, "{}", tone(1000.0));
        assert!(tone(100.0) < 0.05 && tone(10_000.0) < 0.05);
    }

    /// A harder blow is louder; a head smack is brighter than a body thud.
    #[test]
    fn impacts_scale_with_the_blow() {
        let mut n = Noise::new(1);
        let soft = impact(48_000.0, &mut n, Struck::Head, 0.2);
        let hard = impact(48_000.0, &mut n, Struck::Head, 1.0);
        assert!(rms(&hard) > 4.0 * rms(&soft));
        let zero_crossings = |x: &[f32]| x.windows(2).filter(|w| w[0] * w[1] < 0.0).count();
        let body = impact(48_000.0, &mut n, Struck::Body, 1.0);
        assert!(zero_crossings(&hard[..2400]) > 2 * zero_crossings(&body[..2400]));
    }

    /// A voice speaks its syllables and is silent between them.
    #[test]
    fn a_voice_says_its_syllables() {
        let mut n = Noise::new(2);
        let mut v = Voice::new(48_000.0);
        v.say(Syllable {
            start: 4800,
            len: 9600,
            vowel: 0,
            level: 0.5,
            pitch: 120.0,
        });
        let y: Vec<f32> = (0..24_000).map(|_| v.next(&mut n)).collect();
        assert!(rms(&y[..4800]) == 0.0);
        assert!(rms(&y[6000..13_000]) > 0.05, "{}", rms(&y[6000..13_000]));
        assert!(rms(&y[15_000..]) == 0.0 && v.quiet());
    }
}
