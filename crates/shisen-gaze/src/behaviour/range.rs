//! Ranges as boxers use them (boxing.md; docs/model/boxing.md "Ranges"):
//! out of range, long (jab) range, mid (power) range and the clinch,
//! worked out from a fighter's reach and step, not tuned. Both fighters
//! are built to the same anatomy ([`crate::anatomy::arm`]), so one table
//! serves the VH's footwork, the opponent's punches and the bout's
//! report.
//!
//! Distance is measured as the `range` trace column is: horizontally from
//! the ground point under one fighter's waist to the other's head (the
//! head sits over the waist in the guard, so this is also the distance
//! between the heads in a square stance).

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::anatomy::arm;

/// How far a punch carries its shoulder forward, m: the shoulder girdle's
/// protraction and the trunk's turn into the punch. A cross is a forward
/// translation and turn of the whole body (Dinu & Louis 2020, Front.
/// Sports Act. Living 2:598861); a 40-deg turn takes a shoulder 0.19 m
/// from the spine about 0.12 m forward, and the scapula protracts some
/// 5-8 cm more (our estimates from the geometry). 0.20 m in all.
pub const SHOULDER_TRAVEL: f64 = 0.20;
/// The gap a landing glove closes beyond its centre, m: the glove's
/// radius (0.06, a 10-oz glove) and the target head's (0.10).
pub const CONTACT: f64 = 0.16;
/// How deep behind the contact a punch is aimed, m: a punch that falls
/// this much short of its aim still touches, so it needs no step for it.
pub const AIM_DEPTH: f64 = 0.05;
/// A step into a punch, m: the lead foot's step in a stepping jab or an
/// attack from long range: our estimate, about the footwork's longest
/// step (`BehaviourParams::max_step`) and the punch's lunge
/// (`max_lunge`), 0.3 m each.
pub const STEP_IN: f64 = 0.30;

/// A distance between fighters, named as boxers name it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Deserialize, Serialize, JsonSchema)]
pub enum Zone {
    /// Chest to chest: too close to extend an arm; the bodies push.
    Clinch,
    /// Mid (power) range: both hands land without a step (hooks,
    /// crosses, uppercuts).
    Mid,
    /// Long (jab) range: a punch lands only with a step in.
    Long,
    /// Out of range: nothing lands, even with a step.
    Out,
}

impl Zone {
    /// Every zone, closest first.
    pub const ALL: [Zone; 4] = [Zone::Clinch, Zone::Mid, Zone::Long, Zone::Out];

    /// Lower-case name (trace column `zone`, the report).
    pub fn name(self) -> &'static str {
        match self {
            Zone::Clinch => "clinch",
            Zone::Mid => "mid",
            Zone::Long => "long",
            Zone::Out => "out",
        }
    }

    /// Its place in per-zone tables (closest first).
    pub fn index(self) -> usize {
        self as usize
    }
}

/// The boundaries between the zones, m (distance as the module says).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ranges {
    /// Closer than this is the clinch: the forearm and the contact, the
    /// elbow cannot open.
    pub clinch: f64,
    /// Closer than this (and not the clinch) is mid range: a straight arm
    /// with the shoulder's travel and the contact.
    pub mid: f64,
    /// Closer than this (and not mid) is long range: mid range plus a
    /// step; beyond is out of range.
    pub long: f64,
}

impl Ranges {
    /// The ranges of a fighter of the model's anatomy.
    pub const HUMAN: Ranges = {
        let mid = arm::UPPER + arm::FOREARM + SHOULDER_TRAVEL + CONTACT;
        Ranges {
            clinch: arm::FOREARM + CONTACT,
            mid,
            long: mid + STEP_IN,
        }
    };

    /// The zone at distance `d`, m.
    pub fn zone(&self, d: f64) -> Zone {
        if d < self.clinch {
            Zone::Clinch
        } else if d < self.mid {
            Zone::Mid
        } else if d < self.long {
            Zone::Long
        } else {
            Zone::Out
        }
    }

    /// The farthest a fighter's glove centre reaches from its shoulder
    /// with a step in, m: the straight arm and the shoulder's travel, and
    /// a step.
    pub fn glove_reach(&self) -> f64 {
        self.long - CONTACT
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The zones follow the arm: the scenes' 0.92 m is mid range (a
    /// cross lands without a step), 1.5 m is out of range, and each
    /// boundary is the one before plus what the arm or a step adds.
    #[test]
    fn zones_follow_the_reach() {
        let r = Ranges::HUMAN;
        assert!(r.clinch < r.mid && r.mid < r.long);
        assert_eq!(r.zone(0.3), Zone::Clinch);
        assert_eq!(r.zone(0.92), Zone::Mid);
        assert_eq!(r.zone(1.1), Zone::Long);
        assert_eq!(r.zone(1.5), Zone::Out);
        assert!((r.long - r.mid - STEP_IN).abs() < 1e-12);
        assert!((r.mid - r.clinch - arm::UPPER - SHOULDER_TRAVEL).abs() < 1e-12);
        for (k, z) in Zone::ALL.into_iter().enumerate() {
            assert_eq!(z.index(), k);
        }
    }
}
