//! Soak runs: spar against a seeded random opponent for a long simulated
//! time, checking invariants every tick (finite state, joints inside their
//! limits, a defined gaze point, memory not growing), and summarise.

use glam::DVec3;
use rand::rngs::StdRng;
use rand::{RngExt, SeedableRng};
use rand_distr::{Distribution, StandardNormal};

use crate::physics::body::{HARD_STOP_MARGIN_DEG, OpponentPart, Seg};
use crate::scene::LoadedScene;
use crate::scene::opponent::Opponent;
use crate::sim::blows::Fighter;
use crate::sim::bout::BoutParams;
use crate::sim::timeline::{Action, Event, Hand, Part, PunchTarget};
use crate::sim::{DT, Sample, Sim};
use shisen_face::tables::Emotion;
use shisen_face::timing::{Pattern, Speed};

/// The sparring partner's punches a minute by default: an elite
/// amateur's output (about 20-26 a minute: Davis et al. 2018, J. Strength
/// Cond. Res.; the 2012 Olympics about 20); the partner once threw 48,
/// twice that.
pub const PARTNER_PUNCHES_PER_MIN: f64 = 22.0;

/// The share of the VH's punches, seen coming, that the sparring partner
/// defends against by default (our choice: with its guard, a pro's
/// punches then land 30-40 %, elite boxers' accuracy, Davis et al. 2018).
pub const PARTNER_DEFENCE: f64 = 0.6;

/// The random opponent's event rates, per second.
#[derive(Clone, Copy, Debug)]
pub struct BotRates {
    /// Punches (default [`PARTNER_PUNCHES_PER_MIN`] a minute).
    pub punch: f64,
    /// Glove repositioning moves.
    pub glove_move: f64,
    /// Waves.
    pub wave: f64,
    /// Head dodges.
    pub dodge: f64,
    /// Emotion changes of the VH's face.
    pub emotion: f64,
    /// Share of the VH's punches, seen coming, that the partner defends
    /// against, 0-1 ([`SparringBot`]'s defence; 0: it never defends, as
    /// the partner did before it had a guard). Default
    /// [`PARTNER_DEFENCE`].
    pub defend: f64,
}

impl Default for BotRates {
    fn default() -> Self {
        BotRates {
            punch: PARTNER_PUNCHES_PER_MIN / 60.0,
            glove_move: 0.6,
            wave: 0.1,
            dodge: 0.3,
            emotion: 0.1,
            defend: PARTNER_DEFENCE,
        }
    }
}

/// A seeded random sparring partner: it pushes timeline events into the
/// simulation as it runs, exactly as live input does.
///
/// It defends as a sparring partner does, from what it sees: a VH glove
/// coming at its head faster than [`SEEN_SPEED`] is a punch seen; it
/// answers a share of them ([`BotRates::defend`]) after a human reaction
/// time ([`REACTION_S`]), covering up (both gloves to its face: the shell)
/// or slipping its head aside. Half its idle glove moves are back to its
/// guard, in front of its chin. So the VH's punches meet a guard and a
/// moving head, and their accuracy is a boxer's, not a punch bag's.
pub struct SparringBot {
    rng: StdRng,
    rates: BotRates,
    /// Events pushed so far.
    pub events: u64,
    /// Per VH glove (left, right): a punch of it already seen.
    seen: [bool; 2],
    /// Defences decided, and when they start (s).
    pending: Vec<(f64, Defence)>,
}

/// A defence the partner answers a punch with.
#[derive(Clone, Copy, Debug)]
enum Defence {
    /// Both gloves to the face.
    Cover,
    /// The head aside, toward +x (true) or -x.
    Slip(bool),
}

/// A VH glove coming at the partner's head faster than this is a punch
/// seen, m/s (a guard's adjustments move the gloves at under 2 m/s; a
/// punch's peak is 5-9 m/s).
const SEEN_SPEED: f32 = 3.0;
/// The partner's reaction time to a punch it sees: mean and standard
/// deviation, and its bounds, s. Simple visual reaction times of adults
/// are about 0.19-0.25 s (Welford 1980, Reaction Times, ch. 3); a choice
/// between defences costs a little more.
const REACTION_S: (f64, f64, f64, f64) = (0.22, 0.04, 0.15, 0.35);
/// The partner's guard relative to its head: each glove this far to its
/// side, below the eyes and toward the VH, m (gloves beside the chin,
/// as boxers hold them).
const GUARD: (f64, f64, f64) = (0.09, -0.06, 0.16);
/// The share of the partner's defences that cover up; the rest slip
/// (our choice: the shell is the sparring novice's first defence).
const COVER_SHARE: f64 = 0.7;
/// A cover: the gloves closer in, higher, m.
const COVER: (f64, f64, f64) = (0.06, -0.01, 0.12);

impl SparringBot {
    /// A bot with its own random stream.
    pub fn new(seed: u64, rates: BotRates) -> Self {
        SparringBot {
            rng: StdRng::seed_from_u64(seed ^ 0x05EE_DB0B),
            rates,
            events: 0,
            seen: [false; 2],
            pending: Vec::new(),
        }
    }

    /// Where the partner's glove `side` (-1 left, +1 right, in x) goes for
    /// a guard `g` (across, up, toward the VH), world: about its head,
    /// toward the VH's head.
    fn about_head(sim: &Sim, side: f64, g: (f64, f64, f64)) -> DVec3 {
        let w = &sim.world;
        let head = w.position(w.part(OpponentPart::Head)).as_dvec3();
        let vh = w.position(Seg::Head).as_dvec3();
        let to_vh = DVec3::new(vh.x - head.x, 0.0, vh.z - head.z).normalize_or_zero();
        head + DVec3::new(side * g.0, g.1, 0.0) + to_vh * g.2
    }

    /// See the VH's punches coming and decide the defences (after the
    /// reaction time), and start those whose time has come.
    fn defend(&mut self, sim: &Sim) -> Vec<Action> {
        let mut out = Vec::new();
        let w = &sim.world;
        let head = w.position(w.part(OpponentPart::Head));
        for (k, glove) in [Seg::GloveL, Seg::GloveR].into_iter().enumerate() {
            let to = head - w.position(glove);
            let approach = w.velocity(glove).dot(to.normalize_or_zero());
            if approach < 1.0 {
                self.seen[k] = false;
            } else if approach > SEEN_SPEED && !self.seen[k] {
                self.seen[k] = true;
                if self.rng.random::<f64>() < self.rates.defend {
                    let (mean, sd, lo, hi) = REACTION_S;
                    let z: f64 = StandardNormal.sample(&mut self.rng);
                    let at = sim.time() + (mean + sd * z).clamp(lo, hi);
                    let how = if self.rng.random::<f64>() < COVER_SHARE {
                        Defence::Cover
                    } else {
                        Defence::Slip(self.rng.random::<bool>())
                    };
                    self.pending.push((at, how));
                }
            }
        }
        let now = sim.time();
        while let Some(i) = self.pending.iter().position(|(at, _)| *at <= now) {
            let (_, how) = self.pending.swap_remove(i);
            match how {
                Defence::Cover => {
                    for (part, side) in [(Part::LeftGlove, -1.0), (Part::RightGlove, 1.0)] {
                        let to = Self::about_head(sim, side, COVER);
                        out.push(Action::Move {
                            part,
                            to,
                            duration: 0.1,
                        });
                    }
                }
                Defence::Slip(right) => {
                    let head = head.as_dvec3();
                    let side = if right { 1.0 } else { -1.0 };
                    let to = head + DVec3::new(side * 0.12, -0.04, 0.0);
                    let part = Part::Head;
                    out.push(Action::Move {
                        part,
                        to,
                        duration: 0.15,
                    });
                }
            }
        }
        out
    }

    fn happens(&mut self, rate: f64) -> bool {
        self.rng.random::<f64>() < shisen_gaze::util::math::poisson_step(rate, DT)
    }

    /// Maybe act this tick.
    pub fn step(&mut self, sim: &mut Sim) {
        let mut out = self.defend(sim);
        if self.happens(self.rates.punch) {
            let hand = if self.rng.random::<bool>() {
                Hand::Left
            } else {
                Hand::Right
            };
            let target = if self.rng.random::<f64>() < 0.7 {
                PunchTarget::Head
            } else {
                PunchTarget::Body
            };
            let speed = self.rng.random_range(2.5..7.5);
            out.push(Action::Punch {
                hand,
                target,
                speed,
                through: None,
                glove_only: false,
            });
        }
        if self.happens(self.rates.glove_move) {
            let part = if self.rng.random::<bool>() {
                Part::LeftGlove
            } else {
                Part::RightGlove
            };
            // Half the time back to the guard, else anywhere in front.
            let to = if self.rng.random::<bool>() {
                let side = if part == Part::LeftGlove { -1.0 } else { 1.0 };
                Self::about_head(sim, side, GUARD)
            } else {
                DVec3::new(
                    self.rng.random_range(-0.35..0.35),
                    self.rng.random_range(1.25..1.85),
                    self.rng.random_range(0.45..0.8),
                )
            };
            let duration = self.rng.random_range(0.2..1.0);
            out.push(Action::Move { part, to, duration });
        }
        if self.happens(self.rates.wave) {
            let part = if self.rng.random::<bool>() {
                Part::LeftGlove
            } else {
                Part::RightGlove
            };
            let amplitude = DVec3::new(
                self.rng.random_range(0.05..0.25),
                self.rng.random_range(0.0..0.1),
                0.0,
            );
            let frequency = self.rng.random_range(1.0..3.0);
            let duration = self.rng.random_range(0.5..2.0);
            out.push(Action::Wave {
                part,
                amplitude,
                frequency,
                duration,
            });
        }
        if self.happens(self.rates.dodge) {
            // A dodge, and a step in or out (the bot's feet: it stands
            // between mid and long range of where it began).
            let to = DVec3::new(
                self.rng.random_range(-0.15..0.15),
                self.rng.random_range(1.6..1.75),
                self.rng.random_range(0.8..1.1),
            );
            let duration = self.rng.random_range(0.15..0.5);
            out.push(Action::Move {
                part: Part::Head,
                to,
                duration,
            });
        }
        if self.happens(self.rates.emotion) {
            let all: Vec<Emotion> = Emotion::all().collect();
            let emotion = all[self.rng.random_range(0..all.len())];
            let speed = [Speed::Fast, Speed::Typical, Speed::Slow][self.rng.random_range(0..3)];
            let intensity = self.rng.random_range(0.3..1.0);
            out.push(Action::Emotion {
                emotion,
                intensity,
                speed,
                pattern: Pattern::III,
            });
        }
        let at = sim.time();
        for action in out {
            self.events += 1;
            sim.push_event(Event { at, action });
        }
    }
}

/// What a soak run found.
#[derive(Clone, Debug, Default)]
pub struct SoakReport {
    /// The bout's card over the whole run: punches by both, time at each
    /// range.
    pub card: crate::sim::stats::Card,
    /// Simulated time, s.
    pub sim_time: f64,
    /// Ticks.
    pub ticks: u64,
    /// Opponent events.
    pub events: u64,
    /// Punches the VH threw.
    pub vh_punches: u32,
    /// Evasions (slips, ducks, lean-backs) the VH started.
    pub evasions: u32,
    /// Footwork moves the VH started, and steps its feet took.
    pub steps: (u32, u32),
    /// Farthest the VH's pelvis got from where it started, m.
    pub farthest: f64,
    /// Times a blow staggered the VH, and its fatigue at the end (E1).
    pub staggers: (u32, f64),
    /// Ticks an opponent glove touched the VH's head.
    pub head_hit_ticks: u64,
    /// Times the VH was knocked down, and got up (a physical body only).
    pub knockdowns: (u32, u32),
    /// Knockdowns with no blow of the opponent's (a hit or a blocked
    /// punch) in the [`PROVOKED`] s before: falls of the body's own making.
    pub unprovoked: u32,
    /// Physics explosions recovered from.
    pub resets: u32,
    /// Blows both ways (hits landed and punches blocked, `sim::blows`).
    pub tally: crate::sim::blows::Tally,
    /// Largest excursion of an eye or neck angle beyond its range, deg.
    pub worst_limit_excess_deg: f64,
    /// Widest any VH joint opened (`World::joint_gap`), mm.
    pub worst_joint_gap_mm: f64,
    /// Resident memory at the first and last check, KiB (0 where /proc is missing).
    pub rss_kib: (u64, u64),
    /// Invariant violations (first few).
    pub failures: Vec<String>,
}

impl SoakReport {
    /// True when every invariant held.
    pub fn passed(&self) -> bool {
        self.failures.is_empty()
    }
}

fn rss_kib() -> u64 {
    std::fs::read_to_string("/proc/self/statm")
        .ok()
        .and_then(|s| {
            s.split_whitespace()
                .nth(1)
                .and_then(|v| v.parse::<u64>().ok())
        })
        .map_or(0, |pages| pages * 4)
}

/// Check one sample's invariants, recording violations; returns how far
/// an angle strayed past its range (deg) and how wide a joint opened (mm).
fn check(s: &Sample, sim: &Sim, failures: &mut Vec<String>) -> (f64, f64) {
    let mut fail = |m: String| {
        if failures.len() < 20 {
            failures.push(format!("t = {:.3} s: {m}", s.t));
        }
    };
    if !s.finite {
        fail("non-finite body state".into());
    }
    if !s.gaze_point.is_finite() {
        fail("gaze point undefined".into());
    }
    let mut worst: f64 = 0.0;
    for i in [Seg::Head, Seg::EyeL, Seg::EyeR] {
        let Some(l) = sim.world.plan.segments[i.index()].limits else {
            continue;
        };
        let a = sim.world.joint_angles(i);
        let excess = |v: f64, r: [f32; 2]| {
            let v = v.to_degrees();
            (r[0] as f64 - v).max(v - r[1] as f64).max(0.0)
        };
        let e = excess(a.yaw, l.yaw).max(excess(a.pitch, l.pitch));
        worst = worst.max(e);
        if e > MAX_EXCURSION_DEG {
            let name = sim.world.plan.segments[i.index()].name;
            fail(format!(
                "{name} beyond its range by {e:.1} deg (the body {})",
                s.stance.name()
            ));
        }
    }
    let gap_mm = f64::from(sim.world.joint_gap()) * 1000.0;
    if gap_mm > MAX_JOINT_GAP_MM {
        fail(format!("a joint opened {gap_mm:.1} mm"));
    }
    (worst, gap_mm)
}

/// The farthest an eye or the neck may go past its range, deg: clear of
/// rapier's hard stop (`2 * HARD_STOP_MARGIN_DEG` past the range) by 2
/// deg. The soft limits (`physics::control::end_range_torque`) hold blows
/// well inside it: the driven body's worst in ten-minute soaks 2.1-2.4 deg,
/// in a ten-hour soak (seed 7) 5.6 deg once; 6.7-6.9 and 12.8 over an hour
/// before them. A physical body falling on its head still passes it
/// (13-16 deg, issue 44).
const MAX_EXCURSION_DEG: f64 = 2.0 * HARD_STOP_MARGIN_DEG as f64 - 2.0;

/// The most resident memory may grow past the warm-up, KiB.
const MAX_GROWTH_KIB: u64 = 1024;

/// A knockdown this soon after a blow of the opponent's is the blow's, s
/// (our choice: a struck body that staggers and falls is down within about
/// a second).
const PROVOKED: f64 = 1.0;

/// A joint opening wider than this is a solver failure, mm: a segment
/// visibly detaching (the eyeball is 22 mm across). Under the hardest
/// blows the solver lets a joint open a few millimetres for a tick or two
/// and closes it (10-hour soak, seed 11: widest 5.0 mm once).
const MAX_JOINT_GAP_MM: f64 = 10.0;

/// How a soak is fought.
#[derive(Clone, Copy, Debug, Default)]
pub struct SoakSetup {
    /// The VH's whole body in the physics (`vh.body.pelvis: Balanced`).
    pub balanced: bool,
    /// The VH as this level and style (its range, output and defence);
    /// `None`: the default scene's VH.
    pub opponent: Option<Opponent>,
    /// In rounds, as a bout is fought ([`BoutParams`]' default: three
    /// minutes, a minute's rest), as many as the soak's length holds; the
    /// partner rests too. Otherwise open sparring without a pause.
    pub rounds: bool,
    /// The random partner's rates and its defence.
    pub partner: BotRates,
}

/// Spar for `minutes` of simulated time against a seeded random opponent,
/// on the default scene's VH as `setup` says, checking invariants every
/// tick. `progress` is called about once per simulated second with the
/// fraction done; it returns false to stop the soak there (the report
/// covers what ran).
pub fn soak(
    minutes: f64,
    seed: u64,
    setup: SoakSetup,
    mut progress: impl FnMut(f64) -> bool,
) -> SoakReport {
    let SoakSetup {
        balanced,
        opponent,
        rounds,
        partner,
    } = setup;
    let mut loaded = LoadedScene::default_scene();
    loaded.scene.seed = seed;
    loaded.scene.vh.opponent = opponent;
    if balanced {
        loaded.scene.vh.body.pelvis = crate::physics::lower::Pelvis::Balanced;
    }
    loaded.scene.timeline.clear();
    loaded.scene.expect.clear();
    // Open sparring: no rounds (after the default's three the VH would
    // stand in its corner for the rest of the soak); or as many rounds as
    // the soak holds.
    loaded.scene.bout = rounds.then(|| {
        let b = BoutParams::default();
        let n = (minutes * 60.0 / (b.round + b.rest)).ceil().max(1.0);
        BoutParams {
            rounds: n as u32,
            ..b
        }
    });
    let mut sim = loaded.sim();
    let mut bot = SparringBot::new(seed, partner);
    let ticks = (minutes * 60.0 / DT).round() as u64;
    let mut r = SoakReport::default();
    // Memory is first measured after a warm-up (a minute, or half the run).
    let warm = (60_000.min(ticks / 2) / 1000) * 1000;
    let mut was_staggered = false;
    let mut last_blow = f64::NEG_INFINITY;
    for i in 0..ticks {
        // The partner rests between rounds.
        if sim.phase(sim.time()).is_none_or(|(p, _)| p.fighting()) {
            bot.step(&mut sim);
        }
        let down_before = sim.balance.knockdowns;
        let s = sim.step().clone();
        if s.blows.iter().any(|b| b.by == Fighter::Opponent) {
            last_blow = s.t;
        }
        if sim.balance.knockdowns > down_before && s.t - last_blow > PROVOKED {
            r.unprovoked += 1;
        }
        let (excess, gap_mm) = check(&s, &sim, &mut r.failures);
        r.worst_limit_excess_deg = r.worst_limit_excess_deg.max(excess);
        r.worst_joint_gap_mm = r.worst_joint_gap_mm.max(gap_mm);
        r.head_hit_ticks += u64::from(s.head_hit);
        r.farthest = r.farthest.max(s.pelvis.length());
        let staggered = s.staggered;
        r.staggers.0 += u32::from(staggered && !was_staggered);
        was_staggered = staggered;
        if i % 1000 == 0 {
            if !progress(i as f64 / ticks as f64) {
                break;
            }
            // Memory: measured after a warm-up minute, then at the end.
            if i == warm {
                r.rss_kib.0 = rss_kib();
            }
        }
    }
    r.rss_kib.1 = rss_kib();
    // Nothing the simulation keeps grows with time (past events are
    // dropped, statistics are counts): past the warm-up, resident memory
    // moves by the allocator's settling only, under a MiB however long the
    // run (a leak of 30 bytes a tick is 100 MiB over ten hours).
    if r.rss_kib.0 > 0 && r.rss_kib.1 > r.rss_kib.0 + MAX_GROWTH_KIB {
        r.failures.push(format!(
            "memory grew from {} to {} KiB",
            r.rss_kib.0, r.rss_kib.1
        ));
    }
    r.sim_time = sim.time();
    r.ticks = (sim.time() / DT).round() as u64;
    r.events = bot.events;
    r.vh_punches = sim.behaviour.punches_thrown;
    r.evasions = sim.behaviour.evasions;
    r.staggers.1 = sim.effort.fatigue(&sim.params().effort);
    r.steps = (sim.behaviour.footwork_steps(), sim.lower.steps);
    r.resets = sim.resets;
    r.knockdowns = (sim.balance.knockdowns, sim.balance.get_ups);
    r.tally = sim.tally();
    r.card = sim.stats.total();
    r
}
