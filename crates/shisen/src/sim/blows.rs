//! Blows, not touches: every contact between a glove and the other
//! fighter's head, torso or arms is followed as an episode, and its contact
//! impulse (from the physics' solver) is summed over the first
//! [`WINDOW`] s. An episode whose impulse reaches [`BLOW_IMPULSE`] is a
//! blow: a **hit** when it struck the head or torso, a **block** when it
//! struck a glove or forearm (the guard). Lighter contacts (a glove resting
//! against a cheek, a guard pushed aside slowly) are touches and count for
//! nothing.

use glam::DVec3;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::physics::body::{OpponentPart, Seg};
use crate::physics::world::World;
use shisen_gaze::vision::BodyId;

/// Smallest contact impulse of a blow, N s: a punch's effective mass
/// (2.9 kg: Walilko, Viano & Bir 2005, Br. J. Sports Med. 39:710) stopped
/// from about 1 m/s; real punches carry five times that (Olympic boxers'
/// hands reach 6-9 m/s).
pub const BLOW_IMPULSE: f32 = 3.0;

/// The part of a contact that decides whether it was a blow, s: the impact
/// itself (a punch's contact lasts 10-30 ms), not the push that may follow.
pub const WINDOW: f64 = 0.03;

/// A contact episode ends after this long without contact, s.
const GAP: f64 = 0.02;

/// Who threw a blow.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize, JsonSchema)]
pub enum Fighter {
    /// The virtual human.
    Vh,
    /// The user's avatar (or the scripted opponent).
    Opponent,
}

impl Fighter {
    /// Name in traces.
    pub fn name(self) -> &'static str {
        match self {
            Fighter::Vh => "vh",
            Fighter::Opponent => "opponent",
        }
    }
}

/// Hit or block.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize, JsonSchema)]
pub enum BlowKind {
    /// The glove landed on the head or torso.
    Hit,
    /// The glove was stopped by the other's guard (glove or forearm).
    Block,
}

/// One blow, reported on the tick it is decided.
#[derive(Clone, Debug, PartialEq)]
pub struct Blow {
    /// Hit or block.
    pub kind: BlowKind,
    /// Who threw it.
    pub by: Fighter,
    /// The thrower's glove: 0 its left, 1 its right.
    pub hand: usize,
    /// The part struck (`head`, `torso`, `left_glove`, `forearm_r`...).
    pub part: &'static str,
    /// Contact impulse over the first [`WINDOW`] s, N s.
    pub impulse: f32,
    /// When the contact began, s: the impact itself, [`WINDOW`] before
    /// the tick that reports the blow (what a listener hears, and when).
    pub started: f64,
    /// Where the glove was when the contact began, world m.
    pub at: DVec3,
}

/// Running totals.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Tally {
    /// Hits the VH landed.
    pub vh_hits: u32,
    /// Hits the opponent landed on the VH.
    pub opponent_hits: u32,
    /// The VH's punches the opponent's guard stopped.
    pub vh_blocked: u32,
    /// The opponent's punches the VH's guard stopped.
    pub opponent_blocked: u32,
    /// The opponent's punches stopped dead on the way out by the VH's guard
    /// (the glove lost over half its speed against a glove or forearm).
    pub opponent_guarded: u32,
}

impl Tally {
    fn add(&mut self, b: &Blow) {
        let n = match (b.by, b.kind) {
            (Fighter::Vh, BlowKind::Hit) => &mut self.vh_hits,
            (Fighter::Opponent, BlowKind::Hit) => &mut self.opponent_hits,
            (Fighter::Vh, BlowKind::Block) => &mut self.vh_blocked,
            (Fighter::Opponent, BlowKind::Block) => &mut self.opponent_blocked,
        };
        *n += 1;
    }
}

/// A followed contact.
#[derive(Clone, Debug)]
struct Episode {
    started: f64,
    at: DVec3,
    last_contact: f64,
    impulse: f32,
    decided: bool,
}

/// One glove-part pair to watch.
#[derive(Clone, Debug)]
struct Pair {
    glove: BodyId,
    /// 0: the thrower's left glove, 1: its right.
    hand: usize,
    part: BodyId,
    by: Fighter,
    kind: BlowKind,
    name: &'static str,
    /// The part guards (a glove or forearm): the contact is this glove's
    /// blow only if the glove was the one closing in (a punching arm
    /// running into a glove held still is not that glove's punch).
    guard_part: bool,
    episode: Option<Episode>,
}

/// The blow detector's evolving state.
#[derive(Clone, Debug)]
pub struct Blows {
    pairs: Vec<Pair>,
    /// Gloves touching the other fighter this step, with what they touch
    /// (a hit target, or the guard).
    touching: Vec<(BodyId, BlowKind)>,
    /// Whether an opponent glove touches the VH's head this step.
    head_contact: bool,

    /// Totals so far.
    pub tally: Tally,
}

impl Blows {
    /// Watch every glove against every part of the other fighter.
    pub fn new(world: &World) -> Self {
        let mut pairs = Vec::new();
        let vh_parts: [(Seg, BlowKind, &'static str); 6] = [
            (Seg::Head, BlowKind::Hit, "head"),
            (Seg::Torso, BlowKind::Hit, "torso"),
            (Seg::GloveL, BlowKind::Block, "left_glove"),
            (Seg::GloveR, BlowKind::Block, "right_glove"),
            (Seg::ForearmL, BlowKind::Block, "forearm_l"),
            (Seg::ForearmR, BlowKind::Block, "forearm_r"),
        ];
        for (hand, g) in OpponentPart::GLOVES.into_iter().enumerate() {
            for (part, kind, name) in vh_parts {
                pairs.push(Pair {
                    glove: world.part(g),
                    hand,
                    part: part.body(),
                    by: Fighter::Opponent,
                    kind,
                    name,
                    guard_part: kind == BlowKind::Block,
                    episode: None,
                });
            }
        }
        let opp_parts = [
            (OpponentPart::Head, BlowKind::Hit),
            (OpponentPart::Trunk, BlowKind::Hit),
            (OpponentPart::LeftGlove, BlowKind::Block),
            (OpponentPart::RightGlove, BlowKind::Block),
        ];
        for (hand, g) in [Seg::GloveL, Seg::GloveR].into_iter().enumerate() {
            for (k, kind) in opp_parts {
                pairs.push(Pair {
                    glove: g.body(),
                    hand,
                    part: world.part(k),
                    by: Fighter::Vh,
                    kind,
                    name: k.name(),
                    guard_part: kind == BlowKind::Block,
                    episode: None,
                });
            }
        }
        Blows {
            pairs,
            touching: Vec::new(),
            head_contact: false,
            tally: Tally::default(),
        }
    }

    /// Gloves touching the other fighter this step, each with `Hit` if it
    /// touches the head or torso, else `Block`.
    pub fn touching(&self) -> &[(BodyId, BlowKind)] {
        &self.touching
    }

    /// Whether an opponent glove touches the VH's head this step (any
    /// contact, a blow or not: the trace's `head_hit`).
    pub fn head_contact(&self) -> bool {
        self.head_contact
    }

    /// An opponent's punch was stopped on the way out (see
    /// `Timeline::recoil`) while touching `on`: the guard, or the target.
    pub fn opponent_punch_stopped(&mut self, on: BlowKind) {
        if on == BlowKind::Block {
            self.tally.opponent_guarded += 1;
        }
    }

    /// Read this step's contacts at time `t`; returns the blows decided
    /// now (usually none).
    pub fn step(&mut self, world: &World, t: f64) -> Vec<Blow> {
        let mut out = Vec::new();
        self.touching.clear();
        self.head_contact = false;
        let head = Seg::Head.body();
        for p in &mut self.pairs {
            if p.episode
                .as_ref()
                .is_some_and(|e| e.decided && t - e.last_contact > GAP)
            {
                p.episode = None;
            }
            if let Some(j) = world.contact_impulse(p.glove, p.part) {
                self.head_contact |= p.by == Fighter::Opponent && p.part == head;
                let striker = !p.guard_part || closing(world, p.glove, p.part);
                match self.touching.iter_mut().find(|g| g.0 == p.glove) {
                    // A hit target outranks the guard.
                    Some(g) if p.kind == BlowKind::Hit => g.1 = BlowKind::Hit,
                    Some(_) => {}
                    None => self.touching.push((p.glove, p.kind)),
                }
                let e = p.episode.get_or_insert_with(|| Episode {
                    started: t,
                    at: world.position(p.glove).as_dvec3(),
                    last_contact: t,
                    impulse: 0.0,
                    // Not this glove's blow: followed, never reported.
                    decided: !striker,
                });
                e.last_contact = t;
                if t - e.started < WINDOW - 1e-9 {
                    e.impulse += j;
                }
            }
            // Decided once its window is over, whether or not the contact
            // lasted that long.
            if let Some(e) = p.episode.as_mut().filter(|e| !e.decided)
                && t - e.started >= WINDOW - 1e-9
            {
                e.decided = true;
                if e.impulse >= BLOW_IMPULSE {
                    let blow = Blow {
                        kind: p.kind,
                        by: p.by,
                        hand: p.hand,
                        part: p.name,
                        impulse: e.impulse,
                        started: e.started,
                        at: e.at,
                    };
                    self.tally.add(&blow);
                    out.push(blow);
                }
            }
        }
        out
    }
}

/// Whether glove `a` closed in on `b` faster than `b` on `a` (which of a
/// glove and the guard it meets was moving into the other).
fn closing(world: &World, a: BodyId, b: BodyId) -> bool {
    let n = (world.position(b) - world.position(a)).normalize_or_zero();
    world.velocity(a).dot(n) >= -world.velocity(b).dot(n)
}
