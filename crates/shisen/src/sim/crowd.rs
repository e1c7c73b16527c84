//! The crowd round the ring: how excited it is, from the bout's blows and
//! knockdowns. The hall's people (rising from their seats) and the
//! soundtrack's crowd (its roar) both follow it. It only watches: nothing
//! in the bout depends on it.

use super::blows::{Blow, BlowKind};

/// A hit's impulse that brings the crowd half way to its feet, N s (a
/// solid power punch is 20-30).
const STIRRING: f64 = 30.0;

/// How long excitement takes to fall by e, s: an arena's cheer after a
/// big punch lasts a second or two.
const CALMS: f64 = 1.5;

/// The crowd's state.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Crowd {
    /// 0 seated and murmuring, 1 on its feet roaring.
    pub excitement: f64,
}

impl Crowd {
    /// A blow: a hit stirs it by its impulse; a blocked punch does not.
    pub fn blow(&mut self, b: &Blow) {
        if b.kind == BlowKind::Hit {
            self.excitement = (self.excitement + 0.5 * f64::from(b.impulse) / STIRRING).min(1.0);
        }
    }

    /// A knockdown: everyone is up.
    pub fn knockdown(&mut self) {
        self.excitement = 1.0;
    }

    /// Calm down over `dt` s.
    pub fn tick(&mut self, dt: f64) {
        self.excitement *= (-dt / CALMS).exp();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A hard hit stirs it more than a light one, a block not at all, and
    /// it calms within a few seconds.
    #[test]
    fn the_crowd_rises_with_the_blow_and_calms() {
        let hit = |impulse, kind| Blow {
            kind,
            by: super::super::blows::Fighter::Opponent,
            hand: 0,
            part: "head",
            impulse,
            started: 0.0,
            at: glam::DVec3::ZERO,
        };
        let mut c = Crowd::default();
        c.blow(&hit(25.0, BlowKind::Block));
        assert_eq!(c.excitement, 0.0);
        c.blow(&hit(6.0, BlowKind::Hit));
        let light = c.excitement;
        c.blow(&hit(25.0, BlowKind::Hit));
        assert!(c.excitement - light > 3.0 * light);
        for _ in 0..5000 {
            c.tick(0.001);
        }
        assert!(c.excitement < 0.1 * (light + 0.42));
        c.knockdown();
        assert_eq!(c.excitement, 1.0);
    }
}
