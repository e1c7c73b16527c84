//! A bout: rounds of fighting with rests between them (scene `bout`), in
//! the ring both fighters stand in. The round clock is a pure function of
//! simulation time, so a paused window pauses it and a replay or a
//! headless run sees the same bells at the same ticks.
//!
//! Default format: three rounds of three minutes with a minute's rest, as
//! in elite amateur and most professional bouts (AIBA Technical &
//! Competition Rules 2019, rule 13: 3 x 3 min, 1 min between rounds).

use glam::DVec3;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// The ring: half its side inside the ropes, m. AIBA rules ask 4.9-6.1 m
/// square inside the ropes; 5.5 m here.
pub const RING_HALF: f64 = 2.75;
/// The ring's centre, world m: midway between the fighters at the start
/// (the VH's waist at the origin facing +Z, you about 0.9 m in front).
pub const RING_CENTRE: DVec3 = DVec3::new(0.0, 0.0, 0.46);
/// Where a fighter stands in its corner: this far in from the ropes on
/// each side, m (a stool's depth).
const CORNER_INSET: f64 = 0.55;

/// The VH's corner (red), on the canvas: behind it and to its left.
pub fn vh_corner() -> DVec3 {
    let d = RING_HALF - CORNER_INSET;
    RING_CENTRE + DVec3::new(d, 0.0, -d)
}

/// Your corner (blue), diagonally across from the VH's.
pub fn your_corner() -> DVec3 {
    let d = RING_HALF - CORNER_INSET;
    RING_CENTRE + DVec3::new(-d, 0.0, d)
}

/// How a bout is timed (scene `bout`).
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, Serialize, JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct BoutParams {
    /// Rounds, a whole number, 1-15 (default 3; professional title bouts
    /// were 15 rounds until the 1980s, 12 since).
    #[schemars(range(min = 1, max = 15))]
    pub rounds: u32,
    /// Length of a round, s (default 180). 5-600: short rounds for tests,
    /// up to 10 minutes (rules use 2-3).
    #[schemars(range(min = 5.0, max = 600.0))]
    pub round: f64,
    /// Rest between rounds, s (default 60). 0-300: none to five minutes
    /// (rules use one).
    #[schemars(range(min = 0.0, max = 300.0))]
    pub rest: f64,
}

impl Default for BoutParams {
    fn default() -> Self {
        BoutParams {
            rounds: 3,
            round: 180.0,
            rest: 60.0,
        }
    }
}

/// Where a bout is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum Phase {
    /// Round `n` (from 1) is being fought.
    Round(u32),
    /// The rest after round `n`.
    Rest(u32),
    /// The last round is over.
    Over,
}

impl Phase {
    /// The round being fought or just fought.
    pub fn round(self, params: &BoutParams) -> u32 {
        match self {
            Phase::Round(n) | Phase::Rest(n) => n,
            Phase::Over => params.rounds,
        }
    }

    /// Whether the fighters fight now.
    pub fn fighting(self) -> bool {
        matches!(self, Phase::Round(_))
    }
}

impl BoutParams {
    /// The whole bout's length, s.
    pub fn length(&self) -> f64 {
        self.rounds as f64 * self.round + (self.rounds - 1) as f64 * self.rest
    }

    /// The phase at time `t`, and the time left in it, s (0 once over).
    pub fn phase_at(&self, t: f64) -> (Phase, f64) {
        let period = self.round + self.rest;
        let t = t.max(0.0);
        if t >= self.length() {
            return (Phase::Over, 0.0);
        }
        let k = (t / period).floor();
        let n = k as u32 + 1;
        let into = t - k * period;
        if into < self.round {
            (Phase::Round(n), self.round - into)
        } else {
            (Phase::Rest(n), period - into)
        }
    }
}

/// A bell: the phase changed between two ticks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Bell {
    /// Round `n` starts.
    Start(u32),
    /// Round `n` ends (the rest, or the end of the bout, starts).
    End(u32),
}

/// The bell rung between `t0` and `t1` (the end of the previous tick and
/// of this one), if any.
pub fn bell(params: &BoutParams, t0: f64, t1: f64) -> Option<Bell> {
    let (a, _) = params.phase_at(t0);
    let (b, _) = params.phase_at(t1);
    if a == b {
        return None;
    }
    match (a, b) {
        (Phase::Round(n), _) => Some(Bell::End(n)),
        (_, Phase::Round(n)) => Some(Bell::Start(n)),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn three_by_three_with_a_minute_between() {
        let b = BoutParams::default();
        assert_eq!(b.length(), 660.0);
        assert_eq!(b.phase_at(0.0), (Phase::Round(1), 180.0));
        assert_eq!(b.phase_at(179.0).0, Phase::Round(1));
        assert_eq!(b.phase_at(180.0), (Phase::Rest(1), 60.0));
        assert_eq!(b.phase_at(240.0), (Phase::Round(2), 180.0));
        assert_eq!(b.phase_at(600.0).0, Phase::Round(3));
        assert_eq!(b.phase_at(660.0), (Phase::Over, 0.0));
        assert_eq!(bell(&b, 179.9995, 180.0005), Some(Bell::End(1)));
        assert_eq!(bell(&b, 239.9995, 240.0005), Some(Bell::Start(2)));
        assert_eq!(bell(&b, 659.9995, 660.0005), Some(Bell::End(3)));
        assert_eq!(bell(&b, 10.0, 10.001), None);
    }

    #[test]
    fn no_rest_runs_rounds_back_to_back() {
        let b = BoutParams {
            rounds: 2,
            round: 10.0,
            rest: 0.0,
        };
        assert_eq!(b.phase_at(10.0).0, Phase::Round(2));
        assert_eq!(bell(&b, 9.9995, 10.0005), Some(Bell::End(1)));
        assert_eq!(b.phase_at(20.0).0, Phase::Over);
    }

    #[test]
    fn a_bout_reads_whole_rounds_in_range() {
        let read = |text: &str| {
            shisen_gaze::util::ron::parse_ron::<BoutParams>(text, std::path::Path::new("b.ron"))
        };
        let ok = read("(rounds: 2, round: 60.0, rest: 0.0)").unwrap();
        assert_eq!((ok.rounds, ok.round, ok.rest), (2, 60.0, 0.0));
        for bad in [
            "(rounds: 2.5)",
            "(rounds: 0)",
            "(rounds: 16)",
            "(round: 1.0)",
            "(rest: -1.0)",
            "(bell: 1)",
        ] {
            assert!(read(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn corners_are_inside_the_ropes_and_opposite() {
        for c in [vh_corner(), your_corner()] {
            let d = c - RING_CENTRE;
            assert!(d.x.abs() < RING_HALF && d.z.abs() < RING_HALF);
        }
        assert!((vh_corner() + your_corner() - 2.0 * RING_CENTRE).length() < 1e-12);
        assert!(vh_corner().z < 0.0, "behind the VH, which faces +Z");
    }
}
