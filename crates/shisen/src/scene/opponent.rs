//! Opponents: a level and a style for the VH, each a set of the model's
//! own parameters (reaction times, attack rate, aim, evasions, counters,
//! range, hand and target choice, fitness). Scene `vh.opponent`, the
//! command line's `--opponent level-style`, or the window's menu. Like a
//! profile, an opponent sets the fields it names over the scene's.

use std::fmt;
use std::str::FromStr;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::sim::Params;

/// How good the VH is.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, Serialize, JsonSchema)]
pub enum Level {
    /// Slow to react (a visual reaction near 0.25 s with vision's
    /// latency, an untrained adult's: Welford 1980), seldom evades, never
    /// counters, punches rarely and wide, tires fast.
    Novice,
    /// A club amateur: the model's defaults (reactions near 0.2 s, trained
    /// people's), punching about 18 times a minute (elite amateurs throw
    /// about 20: Davis et al. 2015, IJSPP 10:e1).
    #[default]
    Amateur,
    /// Quick (reactions near 0.18 s), evades most punches it reads and
    /// counters half its slips and blocks, accurate, fit; near a
    /// professional's 55.6 punches a round (CompuBox averages).
    Pro,
}

/// How the VH fights.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, Serialize, JsonSchema)]
pub enum Style {
    /// Balanced: the level's values as they are.
    #[default]
    Boxer,
    /// Keeps long range, circles, leads with the jab, evades.
    OutFighter,
    /// Comes close, punches often and hard (the rear hand, the body),
    /// takes punches rather than evading them.
    Brawler,
    /// Waits, evades and counters: few leads of its own.
    CounterPuncher,
}

/// A level and a style (scene `vh.opponent: Some((level: Pro, style:
/// Brawler))`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Opponent {
    /// How good: `Novice`, `Amateur` (default) or `Pro`.
    #[serde(default)]
    pub level: Level,
    /// How it fights: `Boxer` (default), `OutFighter`, `Brawler` or
    /// `CounterPuncher`.
    #[serde(default)]
    pub style: Style,
}

impl Level {
    /// Every level, easiest first.
    pub const ALL: [Level; 3] = [Level::Novice, Level::Amateur, Level::Pro];

    /// Lower-case name.
    pub fn name(self) -> &'static str {
        match self {
            Level::Novice => "novice",
            Level::Amateur => "amateur",
            Level::Pro => "pro",
        }
    }
}

impl Style {
    /// Every style.
    pub const ALL: [Style; 4] = [
        Style::Boxer,
        Style::OutFighter,
        Style::Brawler,
        Style::CounterPuncher,
    ];

    /// Lower-case name.
    pub fn name(self) -> &'static str {
        match self {
            Style::Boxer => "boxer",
            Style::OutFighter => "out-fighter",
            Style::Brawler => "brawler",
            Style::CounterPuncher => "counter-puncher",
        }
    }
}

impl fmt::Display for Opponent {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}-{}", self.level.name(), self.style.name())
    }
}

impl FromStr for Opponent {
    type Err = String;

    /// `level` or `level-style`, e.g. `pro`, `novice-brawler`,
    /// `amateur-out-fighter`.
    fn from_str(s: &str) -> Result<Self, String> {
        let s = s.trim().to_ascii_lowercase();
        let (level, rest) = s.split_once('-').unwrap_or((&s, "boxer"));
        let level = Level::ALL
            .into_iter()
            .find(|l| l.name() == level)
            .ok_or_else(|| format!("unknown level '{level}' (novice, amateur, pro)"))?;
        let style = Style::ALL
            .into_iter()
            .find(|st| st.name() == rest)
            .ok_or_else(|| {
                format!("unknown style '{rest}' (boxer, out-fighter, brawler, counter-puncher)")
            })?;
        Ok(Opponent { level, style })
    }
}

impl Opponent {
    /// Set the fields this opponent fixes, to values that do not depend
    /// on what they were (choosing again never compounds): the level's,
    /// then the style's changes to them.
    pub fn apply(&self, p: &mut Params) {
        let l = self.level.values();
        let b = &mut p.behaviour;
        let pers = &mut p.personality;
        b.guard_reaction = l.reaction;
        b.evade_reaction = l.reaction;
        b.attack_rate = l.attack_rate;
        b.punch_time = l.punch_time;
        b.target_spread = l.spread;
        pers.evade = l.evade;
        pers.counter = l.counter;
        pers.a_anchor = l.a_anchor;
        let fresh = crate::sim::effort::EffortParams::default();
        p.effort.punch_cost = fresh.punch_cost * l.costs;
        p.effort.round_drain = fresh.round_drain * l.costs;
        b.combination = l.combination;
        b.feint = l.feint;
        pers.anticipation = l.anticipation;
        b.approach_read = l.approach_read;
        pers.a_face = l.a_face;
        // Where each style fights (behaviour/range.rs): an out-fighter
        // just out of range, stepping in to punch and out again; a boxer
        // and a counter-puncher at long range, where the other must step
        // in to land; a brawler at mid range, in the exchanges.
        let r = shisen_gaze::behaviour::Ranges::HUMAN;
        let (range, jab_share, body_shot_share, circle_after) = match self.style {
            Style::Boxer => (r.long - 0.1, 0.5, 0.3, Some(3.0)),
            Style::OutFighter => {
                pers.evade = (l.evade + 0.1).min(1.0);
                (r.long + 0.04, 0.65, 0.15, Some(2.0))
            }
            Style::Brawler => {
                b.attack_rate = l.attack_rate * 1.4;
                pers.evade = l.evade * 0.4;
                pers.counter = l.counter * 0.5;
                (r.mid - 0.1, 0.3, 0.45, Some(3.0))
            }
            Style::CounterPuncher => {
                b.attack_rate = l.attack_rate * 0.5;
                pers.evade = l.evade.max(0.8);
                pers.counter = (l.counter + 0.4).min(1.0);
                (r.long - 0.14, 0.5, 0.3, Some(3.0))
            }
        };
        b.range = range;
        b.jab_share = jab_share;
        b.body_shot_share = body_shot_share;
        b.circle_after = circle_after;
    }
}

/// What a level sets.
struct LevelValues {
    /// Guard and evasion reaction, s.
    reaction: f64,
    /// Attack decisions a second.
    attack_rate: f64,
    /// A punch out and back, s.
    punch_time: f64,
    /// Aim's spread, m.
    spread: f64,
    /// Shares of seen punches evaded, and of slips and blocks countered.
    evade: f64,
    counter: f64,
    /// The gaze anchor's amount through an evasion.
    a_anchor: f64,
    /// What a punch and a round cost, against the default's.
    costs: f64,
    /// Chance of each follow-up punch (a combination).
    combination: f64,
    /// Share of attacks that open with a feint.
    feint: f64,
    /// Share of body cues acted on before the glove flies.
    anticipation: f64,
    /// How much of the opponent's approach the footwork reads ahead.
    approach_read: f64,
    /// The pull of the opponent's face, the visual pivot: above the
    /// guard's (3) the eyes stay on it while the gloves are watched in
    /// the periphery; below a glove's saliency they chase the gloves.
    /// Experts fixate fewer places for longer (Mann et al. 2007, J.
    /// Sport Exerc. Psychol. 29:457, meta-analysis), martial-arts experts
    /// on the head (Ripoll et al. 1995; Hausegger et al. 2019); the
    /// seed's strong and weak boxers' amounts.
    a_face: f64,
}

impl Level {
    fn values(self) -> LevelValues {
        match self {
            Level::Novice => LevelValues {
                reaction: 0.18,
                attack_rate: 0.15,
                punch_time: 0.6,
                spread: 0.06,
                evade: 0.15,
                counter: 0.0,
                a_anchor: 1.0,
                costs: 1.5,
                combination: 0.15,
                feint: 0.0,
                anticipation: 0.0,
                approach_read: 0.0,
                a_face: 0.5,
            },
            Level::Amateur => LevelValues {
                reaction: 0.13,
                attack_rate: 0.3,
                punch_time: 0.5,
                spread: 0.03,
                evade: 0.7,
                counter: 0.3,
                a_anchor: 6.0,
                costs: 1.0,
                combination: 0.45,
                feint: 0.1,
                anticipation: 0.5,
                approach_read: 1.0,
                a_face: 1.5,
            },
            Level::Pro => LevelValues {
                reaction: 0.11,
                attack_rate: 0.24,
                punch_time: 0.45,
                spread: 0.02,
                evade: 0.8,
                counter: 0.5,
                a_anchor: 8.0,
                costs: 0.75,
                combination: 0.6,
                feint: 0.2,
                anticipation: 0.85,
                approach_read: 1.0,
                a_face: 4.0,
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    impl Opponent {
        /// Every combination.
        fn all() -> impl Iterator<Item = Opponent> {
            Level::ALL.into_iter().flat_map(|level| {
                Style::ALL
                    .into_iter()
                    .map(move |style| Opponent { level, style })
            })
        }
    }

    #[test]
    fn names_read_back() {
        for o in Opponent::all() {
            assert_eq!(o.to_string().parse::<Opponent>(), Ok(o));
        }
        assert_eq!(
            "Pro".parse::<Opponent>(),
            Ok(Opponent {
                level: Level::Pro,
                style: Style::Boxer
            })
        );
        assert!("pro-dancer".parse::<Opponent>().is_err());
        assert!("champion".parse::<Opponent>().is_err());
    }

    #[test]
    fn levels_order_reactions_and_evasions() {
        let of = |level| {
            let mut p = Params::default();
            Opponent {
                level,
                style: Style::Boxer,
            }
            .apply(&mut p);
            p
        };
        let (n, a, pro) = (of(Level::Novice), of(Level::Amateur), of(Level::Pro));
        assert!(n.behaviour.guard_reaction > a.behaviour.guard_reaction);
        assert!(a.behaviour.guard_reaction > pro.behaviour.guard_reaction);
        assert!(n.personality.evade < a.personality.evade);
        assert!(a.personality.evade < pro.personality.evade);
        assert!(n.behaviour.attack_rate < pro.behaviour.attack_rate);
    }

    #[test]
    fn choosing_again_does_not_compound() {
        for o in Opponent::all() {
            let mut once = Params::default();
            o.apply(&mut once);
            let mut twice = once.clone();
            Opponent::all().last().unwrap().apply(&mut twice);
            o.apply(&mut twice);
            assert_eq!(twice, once, "{o}");
        }
    }

    #[test]
    fn styles_keep_their_ranges_valid() {
        for o in Opponent::all() {
            let mut p = Params::default();
            o.apply(&mut p);
            let b = &p.behaviour;
            assert!((0.3..=3.0).contains(&b.range), "{o}");
            assert!((0.0..=1.0).contains(&p.personality.evade), "{o}");
            assert!((0.0..=1.0).contains(&b.jab_share), "{o}");
        }
    }
}
