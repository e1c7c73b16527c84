//! The bout's soundtrack, made from the simulation as it runs: the bell,
//! gloves on heads, bodies and guards (loud as the blow's impulse), feet on
//! the canvas, the VH's breathing (with its effort) and the exhale of its
//! punches, a knocked-down body landing, the referee's count, the corners,
//! and the crowd, which murmurs and reacts to blows and knockdowns.
//!
//! A [`Soundtrack`] listens to a [`Sim`] after each tick and writes stereo
//! samples in simulation time, heard from your avatar's head: each sound
//! is panned by its direction, delayed between the ears and by its
//! distance, and quieter with distance. It has its own random stream (from
//! the scene's seed), and only reads the simulation: the same scene and
//! seed give the same samples, and listening changes no trace.
//!
//! Samples are written [`LAG`] behind the simulation's clock, so a blow,
//! reported once its contact's first 30 ms are summed, is heard when the
//! glove struck, not when the blow was judged.

pub mod synth;

use std::f32::consts::FRAC_PI_4;

use glam::DVec3;
use rand::rngs::StdRng;
use rand::{RngExt, SeedableRng};

use crate::physics::balance::Stance;
use crate::physics::body::{OpponentPart, Seg};
use crate::sim::Sim;
use crate::sim::blows::{BlowKind, Fighter, WINDOW};
use crate::sim::bout::{self, Bell, Phase};
use synth::{Noise, Struck, Syllable, Voice};

/// Samples a second of every soundtrack.
pub const RATE: u32 = 48_000;

/// How far the samples run behind the simulation, s: longer than a blow
/// takes to be judged ([`WINDOW`]).
pub const LAG: f64 = WINDOW + 0.01;

/// Half the distance between the ears over the speed of sound, s: the
/// spherical head of Woodworth's interaural time difference,
/// ITD = a/c (theta + sin theta), radius 8.75 cm (Kuhn 1977, J. Acoust.
/// Soc. Am. 62:157), at most 0.66 ms.
const HEAD_RADIUS: f64 = 0.0875;

/// Distance at which a source is heard at its own level, m; nearer it is
/// no louder (it is at the ear), farther it falls as 1/r.
const REFERENCE: f64 = 1.0;

/// A blow's impulse heard at full level, N s (a solid power punch).
const LOUD_BLOW: f32 = 25.0;

/// A foot is off the canvas above this height, m, and down again below
/// [`FOOT_DOWN`].
const FOOT_UP: f64 = 0.012;
const FOOT_DOWN: f64 = 0.004;

/// Breaths a minute at rest and at the hardest effort (Nicolò et al.
/// 2017, Front. Physiol. 8:922: 12-20 at rest, 50-60 at exhaustion): the
/// breath's loudness follows its rate between them.
const BREATH_REST: f64 = 14.0;
const BREATH_HARD: f64 = 50.0;

/// Syllables a second of running speech, about 4-5 (Greenberg 1999,
/// Speech Commun. 29:159).
const SYLLABLE_RATE: f64 = 4.5;

/// Where the listener's head is and which way it faces.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Listener {
    /// Centre of the head, world m.
    pub at: DVec3,
    /// Forward (horizontal unit vector).
    pub forward: DVec3,
}

impl Listener {
    /// Your avatar's head, facing the VH's.
    pub fn avatar(sim: &Sim) -> Self {
        let at = sim
            .world
            .position(sim.world.part(OpponentPart::Head))
            .as_dvec3();
        let vh = sim.world.position(Seg::Head.body()).as_dvec3();
        Listener {
            at,
            forward: (vh - at).with_y(0.0).normalize_or(DVec3::NEG_Z),
        }
    }

    /// Gains (left, right) and delays (samples, left, right) of a sound at
    /// `p`: constant-power panning by its side, Woodworth's interaural
    /// delay, distance's delay and 1/r fall.
    fn place(&self, p: DVec3) -> ([f32; 2], [u64; 2]) {
        let rel = p - self.at;
        let r = rel.length().max(0.05);
        let right = self.forward.cross(DVec3::Y).normalize_or(DVec3::X);
        let side = (rel.dot(right) / r).clamp(-1.0, 1.0);
        let pan = (side as f32 + 1.0) * FRAC_PI_4;
        let g = (REFERENCE / r).min(1.0) as f32;
        let lateral = side.abs().asin();
        let itd = HEAD_RADIUS / synth::SPEED_OF_SOUND * (lateral + lateral.sin());
        let travel = r / synth::SPEED_OF_SOUND;
        let far = travel + itd;
        let (l, rr) = if side > 0.0 {
            (far, travel)
        } else {
            (travel, far)
        };
        let rate = f64::from(RATE);
        (
            [g * pan.cos(), g * pan.sin()],
            [(l * rate).round() as u64, (rr * rate).round() as u64],
        )
    }
}

/// A one-shot sound placed in the mix.
struct Shot {
    samples: Vec<f32>,
    /// First sample of each ear, on the soundtrack's clock.
    start: [u64; 2],
    gain: [f32; 2],
}

impl Shot {
    fn end(&self) -> u64 {
        self.start[0].max(self.start[1]) + self.samples.len() as u64
    }
}

/// A voice at a place (a corner man, the referee).
struct Speaker {
    voice: Voice,
    at: DVec3,
    pitch: f32,
}

/// A foot's contact with the canvas, for its footfalls.
#[derive(Clone, Copy, Default)]
struct Foot {
    up: bool,
    height: f64,
}

/// What the soundtrack remembers of the last tick.
#[derive(Default)]
struct Last {
    stance: Stance,
    count: Option<u32>,
    punching: bool,
    feet: [[Foot; 2]; 2],
}

/// The bout's soundtrack: see the module's docs.
pub struct Soundtrack {
    /// Samples written so far.
    written: u64,
    shots: Vec<Shot>,
    noise: Noise,
    rng: StdRng,
    listener: Listener,
    last: Last,
    /// The crowd's excitement (the simulation's, [`crate::sim::crowd`]).
    excitement: f32,
    crowd: Crowd,
    breath: Breath,
    /// The VH's corner, yours, and the referee.
    speakers: [Speaker; 3],
    /// Applause still to come, claps a second, until this time s.
    applause: (f32, f64),
}

/// The crowd's murmur: noise in the voices' band, two decorrelated
/// channels (it surrounds you), swelling as groups talk, louder and
/// brighter with excitement, with the "ooh" of a heavy blow.
struct Crowd {
    bands: [[synth::Biquad; 2]; 2],
    murmur: synth::Murmur,
    ooh: [synth::Biquad; 2],
    ooh_level: f32,
}

/// The VH's breathing at its mouth.
struct Breath {
    filter: synth::Biquad,
    /// The VH's mouth, world m.
    at: DVec3,
    phase: f64,
    rate: f64,
}

impl Soundtrack {
    /// A silent soundtrack for a run with `seed`.
    pub fn new(seed: u64) -> Self {
        let rate = RATE as f32;
        let mut rng = StdRng::seed_from_u64(seed ^ 0x50_55_4E_44);
        let mut noise = Noise::new(rng.random());
        let band = |f| synth::Biquad::bandpass(rate, f, 0.7);
        let crowd = Crowd {
            bands: [[band(450.0), band(1400.0)], [band(470.0), band(1350.0)]],
            murmur: synth::Murmur::new(&mut noise),
            ooh: [
                synth::Biquad::bandpass(rate, synth::VOWELS[4][0], 4.0),
                synth::Biquad::bandpass(rate, synth::VOWELS[4][1], 4.0),
            ],
            ooh_level: 0.0,
        };
        let corner = |at: DVec3, pitch| Speaker {
            voice: Voice::new(rate),
            // Standing on the apron steps behind the corner post.
            at: at + (at - bout::RING_CENTRE).with_y(0.0).normalize() * 1.2 + DVec3::Y * 1.5,
            pitch,
        };
        Soundtrack {
            written: 0,
            shots: Vec::new(),
            listener: Listener {
                at: DVec3::Y * 1.6,
                forward: DVec3::NEG_Z,
            },
            last: Last::default(),
            excitement: 0.0,
            crowd,
            breath: Breath {
                filter: synth::Biquad::bandpass(rate, 1100.0, 0.6),
                at: DVec3::new(0.0, 1.55, 0.0),
                phase: 0.0,
                rate: BREATH_REST,
            },
            speakers: [
                corner(bout::vh_corner(), 115.0),
                corner(bout::your_corner(), 130.0),
                Speaker {
                    voice: Voice::new(rate),
                    at: bout::RING_CENTRE + DVec3::new(0.8, 1.7, 0.0),
                    pitch: 105.0,
                },
            ],
            applause: (0.0, 0.0),
            noise,
            rng,
        }
    }

    /// Samples written so far.
    pub fn written(&self) -> u64 {
        self.written
    }

    /// Listen to `sim` after its tick: start what it makes heard, and
    /// append the stereo samples up to [`LAG`] before its clock to `out`.
    pub fn hear(&mut self, sim: &Sim, out: &mut Vec<[f32; 2]>) {
        self.listener = Listener::avatar(sim);
        self.cues(sim);
        let until = ((sim.time() - LAG).max(0.0) * f64::from(RATE)).floor() as u64;
        self.render(until, out);
    }

    /// Append the samples still held back (at the end of a run).
    pub fn finish(&mut self, sim: &Sim, out: &mut Vec<[f32; 2]>) {
        let until = (sim.time() * f64::from(RATE)).round() as u64;
        self.render(until, out);
    }

    /// A one-shot `samples` at `p`, struck at time `t`.
    fn shoot(&mut self, samples: Vec<f32>, t: f64, p: DVec3) {
        let (gain, delay) = self.listener.place(p);
        let at = (t.max(0.0) * f64::from(RATE)).round() as u64;
        let at = at.max(self.written);
        self.shots.push(Shot {
            samples,
            start: [at + delay[0], at + delay[1]],
            gain,
        });
    }

    /// Read the tick's events and start their sounds.
    fn cues(&mut self, sim: &Sim) {
        let rate = RATE as f32;
        let t = sim.time();
        let Some(s) = sim.last() else { return };
        for b in &s.blows {
            let struck = match (b.kind, b.part) {
                (BlowKind::Block, _) => Struck::Guard,
                (BlowKind::Hit, "torso") => Struck::Body,
                _ => Struck::Head,
            };
            let level = (b.impulse / LOUD_BLOW).powf(0.6).clamp(0.05, 1.5);
            let x = synth::impact(rate, &mut self.noise, struck, level);
            self.shoot(x, b.started, b.at);
            if b.kind == BlowKind::Hit {
                if b.impulse > 0.5 * LOUD_BLOW {
                    self.crowd.ooh_level = self.crowd.ooh_level.max(level.min(1.0));
                }
                // The hitter's corner shouts now and then.
                if self.rng.random::<f64>() < 0.35 {
                    let k = usize::from(b.by == Fighter::Opponent);
                    self.shout(k, 2, 0.5, t + 0.15);
                }
            }
        }
        match s.bell {
            Some(Bell::Start(_)) => self.ring(t, 1),
            Some(Bell::End(_)) => {
                self.ring(t, 3);
                self.applause = (30.0, t + 4.0);
            }
            None => {}
        }
        // A knockdown: the crowd rises, the body lands, the referee counts.
        let pelvis = sim.pelvis() + DVec3::Y * 0.2;
        if s.stance == Stance::Falling && self.last.stance != Stance::Falling {
            self.crowd.ooh_level = 1.0;
        }
        if s.stance == Stance::Down && self.last.stance == Stance::Falling {
            let x = synth::body_fall(rate, &mut self.noise, 1.0);
            self.shoot(x, t, pelvis);
        }
        if s.stance == Stance::Rising && self.last.stance == Stance::Down {
            self.applause = (40.0, t + 3.0);
        }
        self.last.stance = s.stance;
        let count = sim.count();
        if count.is_some() && count != self.last.count {
            self.shout(2, 2, 0.8, t);
        }
        self.last.count = count;
        // The VH's exhale with each punch it throws.
        if s.punching && !self.last.punching {
            let x = synth::exhale(rate, &mut self.noise, 0.25 + 0.5 * s.fatigue as f32);
            self.shoot(x, t, s.head - DVec3::Y * 0.08);
        }
        self.last.punching = s.punching;
        self.footfalls(sim);
        // Between rounds the corners talk to their fighters.
        if matches!(s.phase, Some(Phase::Rest(_))) {
            for k in 0..2 {
                if self.speakers[k].voice.quiet() && self.rng.random::<f64>() < 0.002 {
                    let n = self.rng.random_range(3..9);
                    self.shout(k, n, 0.35, t);
                }
            }
        }
        self.excitement = sim.crowd.excitement as f32;
        self.breath.at = s.head - DVec3::Y * 0.08;
        self.breath.rate = sim.effort.breath_rate;
        self.breath.phase = sim.effort.breath;
    }

    /// Ring the bell `n` times from the timekeeper's table.
    fn ring(&mut self, t: f64, n: u32) {
        let table = bout::RING_CENTRE + DVec3::new(bout::RING_HALF + 1.6, 0.0, 0.0);
        for k in 0..n {
            let x = synth::bell(RATE as f32, &mut self.noise);
            self.shoot(x, t + 0.3 * f64::from(k), table);
        }
    }

    /// Speaker `k` says `n` syllables at `level`, starting at `t`.
    fn shout(&mut self, k: usize, n: u32, level: f32, t: f64) {
        let rate = f64::from(RATE);
        let sp = &mut self.speakers[k];
        let clock = sp.voice.clock();
        // The voice's clock runs with the samples written.
        let mut start = clock + ((t - self.written as f64 / rate).max(0.0) * rate) as u64;
        for _ in 0..n {
            let len = (rate / SYLLABLE_RATE * (0.7 + 0.6 * self.rng.random::<f64>())) as u64;
            sp.voice.say(Syllable {
                start,
                len,
                vowel: self.rng.random_range(0..synth::VOWELS.len()),
                level,
                pitch: sp.pitch * (1.0 + 0.3 * level),
            });
            start += len + (rate * 0.03) as u64;
        }
    }

    /// Footfalls of both fighters' feet on the canvas.
    fn footfalls(&mut self, sim: &Sim) {
        let avatar = sim.avatar_frame();
        let yours = sim.avatar.lower.legs(&sim.params().body);
        let mut landed = Vec::new();
        for (who, legs) in [sim.legs(), yours].into_iter().enumerate() {
            for (k, leg) in legs.iter().enumerate() {
                let (mut heel, mut toe) = (leg.heel, leg.toe);
                if who == 1 {
                    heel = avatar.transform_point3(heel);
                    toe = avatar.transform_point3(toe);
                }
                let h = heel.y.min(toe.y);
                let f = &mut self.last.feet[who][k];
                let speed = (f.height - h).max(0.0) / sim.model().dt;
                if f.up && h < FOOT_DOWN {
                    landed.push(((0.2 + speed as f32).min(1.0), (heel + toe) / 2.0));
                }
                f.up = if f.up { h >= FOOT_DOWN } else { h > FOOT_UP };
                f.height = h;
            }
        }
        let t = sim.time();
        for (level, at) in landed {
            let x = synth::footfall(RATE as f32, &mut self.noise, 0.35 * level);
            self.shoot(x, t, at);
        }
    }

    /// Write samples up to `until`.
    fn render(&mut self, until: u64, out: &mut Vec<[f32; 2]>) {
        let rate = RATE as f32;
        let n = until.saturating_sub(self.written);
        let breath_gain = self.listener.place(self.breath.at).0;
        let effort =
            ((self.breath.rate - BREATH_REST) / (BREATH_HARD - BREATH_REST)).clamp(0.0, 1.0);
        let places = self
            .speakers
            .each_ref()
            .map(|s| self.listener.place(s.at).0);
        for _ in 0..n {
            let i = self.written;
            let time = i as f32 / rate;
            let mut mix = [0.0f32; 2];
            // The crowd.
            let swell = self.crowd.murmur.at(time);
            let level = 0.11 * (0.6 + 0.4 * swell) + 0.25 * self.excitement;
            for (ch, m) in mix.iter_mut().enumerate() {
                let w = self.noise.white();
                let [lo, hi] = &mut self.crowd.bands[ch];
                *m += level * (lo.run(w) + (0.3 + self.excitement) * hi.run(w));
            }
            if self.crowd.ooh_level > 1e-3 {
                let w = self.noise.white();
                let [f1, f2] = &mut self.crowd.ooh;
                let v = 0.25 * self.crowd.ooh_level * (f1.run(w) + 0.6 * f2.run(w));
                mix[0] += v;
                mix[1] += v;
                self.crowd.ooh_level *= (-1.0 / (0.9 * rate)).exp();
            }
            // Applause: claps at random across the hall.
            if f64::from(time) < self.applause.1 && self.noise.unit() < self.applause.0 / rate {
                let centre = 900.0 + 900.0 * self.noise.unit();
                let x = synth::clap(rate, &mut self.noise, centre);
                let g = 0.12 * self.noise.unit();
                let pan = self.noise.unit() * std::f32::consts::FRAC_PI_2;
                self.shots.push(Shot {
                    samples: x,
                    start: [i, i],
                    gain: [g * pan.cos(), g * pan.sin()],
                });
            }
            // The VH's breath: inhale 40 % of the cycle, quieter; the
            // exhale louder, both louder with its rate.
            let p = self.breath.phase.fract() as f32;
            let env = if p < 0.4 {
                0.4 * (p / 0.4 * std::f32::consts::PI).sin()
            } else {
                ((p - 0.4) / 0.6 * std::f32::consts::PI).sin()
            };
            let b =
                self.breath.filter.run(self.noise.white()) * env * (0.01 + 0.06 * effort as f32);
            mix[0] += b * breath_gain[0];
            mix[1] += b * breath_gain[1];
            // Voices.
            for (sp, g) in self.speakers.iter_mut().zip(&places) {
                let v = sp.voice.next(&mut self.noise);
                mix[0] += v * g[0];
                mix[1] += v * g[1];
            }
            // One-shots.
            for s in &self.shots {
                for (ch, m) in mix.iter_mut().enumerate() {
                    if let Some(k) = i.checked_sub(s.start[ch])
                        && let Some(x) = s.samples.get(k as usize)
                    {
                        *m += x * s.gain[ch];
                    }
                }
            }
            out.push(mix.map(synth::soft_clip));
            self.written += 1;
            if self.written.is_multiple_of(512) {
                let now = self.written;
                self.shots.retain(|s| s.end() > now);
            }
        }
    }
}

#[cfg(test)]
mod tests;
