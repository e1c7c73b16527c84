//! Punch statistics, kept the way boxing broadcasts show them (CompuBox's
//! categories): punches thrown and landed, total, jabs and power punches,
//! with landed punches split by head and body; plus what the guard
//! stopped, what missed, and the VH's evasions. Each punch thrown is
//! followed until it lands, is blocked, or its time is up (a miss).
//!
//! Jabs are the lead hand's punches: both fighters stand orthodox, left
//! foot and left glove forward, so glove 0 (the left) jabs and glove 1
//! (the right) throws the power punches (crosses, hooks).

use serde::Serialize;

use super::blows::{Blow, BlowKind, Fighter};

/// A punch not met by a blow this long after it was thrown missed, s: a
/// punch lands within 0.15-0.3 s, and a retracting glove that touches
/// later is not its blow.
const PUNCH_WINDOW: f64 = 0.6;

/// Thrown and landed.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Count {
    /// Punches thrown.
    pub thrown: u32,
    /// Punches that landed.
    pub landed: u32,
}

impl Count {
    /// Landed over thrown, percent (0 when none were thrown).
    pub fn percent(&self) -> u32 {
        (100 * self.landed).checked_div(self.thrown).unwrap_or(0)
    }

    /// "12/40 (30%)".
    pub fn show(&self) -> String {
        format!("{}/{} ({}%)", self.landed, self.thrown, self.percent())
    }

    fn add(&mut self, o: &Count) {
        self.thrown += o.thrown;
        self.landed += o.landed;
    }
}

/// One fighter's punches.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct FighterStats {
    /// Lead-hand punches.
    pub jabs: Count,
    /// Rear-hand punches.
    pub power: Count,
    /// Landed punches that struck the head.
    pub head: u32,
    /// Landed punches that struck the body.
    pub body: u32,
    /// Punches the other's guard stopped.
    pub blocked: u32,
    /// Punches that met nothing.
    pub missed: u32,
    /// Punches evaded (slipped, ducked, leant away from): the VH's only.
    pub evasions: u32,
    /// Feints made (the VH's; yours are not counted).
    pub feints: u32,
    /// Times this fighter was knocked down (a physical body only:
    /// `vh.body.pelvis: Balanced`).
    pub knockdowns: u32,
}

impl FighterStats {
    /// All punches.
    pub fn total(&self) -> Count {
        let mut c = self.jabs;
        c.add(&self.power);
        c
    }

    fn add(&mut self, o: &FighterStats) {
        self.jabs.add(&o.jabs);
        self.power.add(&o.power);
        self.head += o.head;
        self.body += o.body;
        self.blocked += o.blocked;
        self.missed += o.missed;
        self.evasions += o.evasions;
        self.feints += o.feints;
        self.knockdowns += o.knockdowns;
    }
}

/// Both fighters' statistics.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Card {
    /// The virtual human's.
    pub vh: FighterStats,
    /// Yours (the avatar's, or the scripted opponent's).
    pub you: FighterStats,
    /// Ticks fought at each range: clinch, mid, long, out
    /// (`shisen_gaze::behaviour::Zone`).
    pub at_range: [u32; 4],
}

impl Card {
    fn of_mut(&mut self, f: Fighter) -> &mut FighterStats {
        match f {
            Fighter::Vh => &mut self.vh,
            Fighter::Opponent => &mut self.you,
        }
    }

    fn add(&mut self, o: &Card) {
        self.vh.add(&o.vh);
        self.you.add(&o.you);
        for (a, b) in self.at_range.iter_mut().zip(o.at_range) {
            *a += b;
        }
    }

    /// The share of the fighting time spent at each range (clinch, mid,
    /// long, out), 0-1; all 0 before any.
    pub fn range_shares(&self) -> [f64; 4] {
        let all: u32 = self.at_range.iter().sum();
        self.at_range.map(|n| f64::from(n) / f64::from(all.max(1)))
    }
}

/// A punch in flight, waiting for its outcome.
#[derive(Clone, Copy, Debug)]
struct Open {
    by: Fighter,
    hand: usize,
    at: f64,
    /// The round it was thrown in: its outcome counts there.
    round: u32,
}

/// The bout's statistics: per round and in total.
#[derive(Clone, Debug, Default)]
pub struct Stats {
    /// One card per round (index 0: round 1; a run without rounds has one).
    pub rounds: Vec<Card>,
    open: Vec<Open>,
}

impl Stats {
    /// The totals over all rounds.
    pub fn total(&self) -> Card {
        let mut c = Card::default();
        for r in &self.rounds {
            c.add(r);
        }
        c
    }

    fn card(&mut self, round: u32) -> &mut Card {
        let i = round.max(1) as usize - 1;
        if self.rounds.len() <= i {
            self.rounds.resize(i + 1, Card::default());
        }
        &mut self.rounds[i]
    }

    /// `by` threw a punch with glove `hand` (0 lead, 1 rear) at time `t`
    /// in round `round`.
    pub fn thrown(&mut self, by: Fighter, hand: usize, t: f64, round: u32) {
        let c = self.card(round).of_mut(by);
        if hand == 0 {
            c.jabs.thrown += 1;
        } else {
            c.power.thrown += 1;
        }
        // A second punch with the same glove ends one still out: a miss.
        if let Some(i) = self.open.iter().position(|o| o.by == by && o.hand == hand) {
            let old = self.open.swap_remove(i);
            self.card(old.round).of_mut(by).missed += 1;
        }
        self.open.push(Open {
            by,
            hand,
            at: t,
            round,
        });
    }

    /// The VH was knocked down.
    pub fn knocked_down(&mut self, round: u32) {
        self.card(round).vh.knockdowns += 1;
    }

    /// The VH feinted.
    pub fn feinted(&mut self, round: u32) {
        self.card(round).vh.feints += 1;
    }

    /// The VH evaded a punch.
    pub fn evaded(&mut self, round: u32) {
        self.card(round).vh.evasions += 1;
    }

    /// A blow was decided; it settles the punch it came from, if one is
    /// out (a guard driven into a face is a blow but no punch), in the
    /// round the punch was thrown in.
    pub fn blow(&mut self, b: &Blow) {
        let Some(i) = self
            .open
            .iter()
            .position(|o| o.by == b.by && o.hand == b.hand)
        else {
            return;
        };
        let open = self.open.swap_remove(i);
        let c = self.card(open.round).of_mut(b.by);
        match b.kind {
            BlowKind::Hit => {
                if b.hand == 0 {
                    c.jabs.landed += 1;
                } else {
                    c.power.landed += 1;
                }
                if b.part == "head" {
                    c.head += 1;
                } else {
                    c.body += 1;
                }
            }
            BlowKind::Block => c.blocked += 1,
        }
    }

    /// A tick fought in round `round` at range `zone` (its index).
    pub fn at_range(&mut self, round: u32, zone: usize) {
        self.card(round).at_range[zone] += 1;
    }

    /// Close the punches whose time is up at `t` as misses.
    pub fn tick(&mut self, t: f64) {
        while let Some(i) = self.open.iter().position(|o| t - o.at > PUNCH_WINDOW) {
            let o = self.open.swap_remove(i);
            self.card(o.round).of_mut(o.by).missed += 1;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn blow(by: Fighter, hand: usize, kind: BlowKind, part: &'static str) -> Blow {
        Blow {
            kind,
            by,
            hand,
            part,
            impulse: 10.0,
            started: 0.0,
            at: glam::DVec3::ZERO,
        }
    }

    #[test]
    fn a_punch_lands_is_blocked_or_misses_once() {
        let mut s = Stats::default();
        s.thrown(Fighter::Opponent, 0, 1.0, 1);
        s.blow(&blow(Fighter::Opponent, 0, BlowKind::Hit, "head"));
        // A second contact of the same punch counts for nothing more.
        s.blow(&blow(Fighter::Opponent, 0, BlowKind::Hit, "head"));
        s.thrown(Fighter::Opponent, 1, 2.0, 1);
        s.blow(&blow(Fighter::Opponent, 1, BlowKind::Block, "left_glove"));
        s.thrown(Fighter::Vh, 1, 3.0, 1);
        s.tick(3.5);
        assert_eq!(s.total().vh.missed, 0, "still in flight");
        s.tick(3.7);
        s.thrown(Fighter::Vh, 0, 4.0, 2);
        s.blow(&blow(Fighter::Vh, 0, BlowKind::Hit, "torso"));
        // A punch thrown in round 2 that lands after the bell counts there;
        // one replaced by the same glove's next punch missed.
        s.thrown(Fighter::Opponent, 0, 5.0, 2);
        s.thrown(Fighter::Opponent, 0, 5.2, 2);
        s.blow(&blow(Fighter::Opponent, 0, BlowKind::Hit, "head"));
        assert_eq!(
            s.rounds[1].you.jabs,
            Count {
                thrown: 2,
                landed: 1
            }
        );
        assert_eq!(s.rounds[1].you.missed, 1);
        let t = s.total();
        assert_eq!(
            t.you.jabs,
            Count {
                thrown: 3,
                landed: 2
            }
        );
        assert_eq!(
            t.you.power,
            Count {
                thrown: 1,
                landed: 0
            }
        );
        assert_eq!((t.you.head, t.you.blocked), (2, 1));
        assert_eq!(t.vh.missed, 1);
        assert_eq!((t.vh.jabs.landed, t.vh.body), (1, 1));
        assert_eq!(s.rounds.len(), 2);
        assert_eq!(
            s.rounds[1].vh.total(),
            Count {
                thrown: 1,
                landed: 1
            }
        );
        assert_eq!(t.you.total().show(), "2/4 (50%)");
    }

    #[test]
    fn a_blow_without_a_punch_is_not_a_punch_landed() {
        let mut s = Stats::default();
        s.blow(&blow(Fighter::Opponent, 1, BlowKind::Hit, "head"));
        assert_eq!(s.total(), Card::default());
    }
}
