//! The planner's parameters (scene `vh.behaviour`).

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Planner parameters (scene `vh.behaviour`).
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize, JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct BehaviourParams {
    /// Attack decisions per second while both arms are free. The original
    /// drew with probability 0.004 per step; as a rate it does not depend on
    /// the step (Poisson: p = 1 - exp(-rate dt)). Per s, 0-10. Default
    /// 0.25; professionals throw about one punch a second (CompuBox), and
    /// a punch takes half a second out and back.
    #[schemars(range(min = 0.0, max = 10.0))]
    pub attack_rate: f64,
    /// Delay between the eyes landing on the target and the punch
    /// (the telegraph), s, 0-2. Default 0.2.
    #[schemars(range(min = 0.0, max = 2.0))]
    pub punch_delay: f64,
    /// Duration of the punch, out and back, s, 0.05-3. Default 0.5; a
    /// jab's out-and-back is about 0.3-0.5 s, and a 3 s punch is a slow
    /// demonstration.
    #[schemars(range(min = 0.05, max = 3.0))]
    pub punch_time: f64,
    /// Standard deviation of the random offset added to the attack target,
    /// m, 0-0.5. Default 0.03; half a metre misses the head by a head's
    /// width several times over.
    #[schemars(range(min = 0.0, max = 0.5))]
    pub target_spread: f64,
    /// Probability of aiming at the body rather than the head, 0-1.
    /// Default 0.3.
    #[schemars(range(min = 0.0, max = 1.0))]
    pub body_shot_share: f64,
    /// A glove is "aimed" above this speed, m/s, 0-1000. Default 2.
    /// Punches peak near 10-15 m/s, so a threshold above that switches the
    /// guard off (scenes that let a punch land use 1000).
    #[schemars(range(min = 0.0, max = 1000.0))]
    pub guard_speed: f64,
    /// ... heading within this angle of the head, torso or centre of mass,
    /// deg, 0-180 (a half turn: every heading). Default 22.5.
    #[schemars(range(min = 0.0, max = 180.0))]
    pub guard_angle_deg: f64,
    /// ... with time to contact under this, s, > 0 and at most 5.
    /// Default 0.5; a punch crosses the ring's fighting range in well
    /// under a second.
    #[schemars(range(max = 5.0), extend("exclusiveMinimum" = 0.0))]
    pub guard_ttc: f64,
    /// Time from seeing a threat to the guarding glove starting to move,
    /// s. Default 0.13: with vision's 70 ms latency a reaction near 200 ms,
    /// the simple visual reaction time of fast, trained people (Welford
    /// 1980, "Reaction Times"; elite boxers react to a punch in well over
    /// 150 ms). The seed: 0. 0-1 s: a second covers slowed or fatigued
    /// subjects.
    #[schemars(range(min = 0.0, max = 1.0))]
    pub guard_reaction: f64,
    /// Hold the guard this long after the threat is gone, s, 0-5.
    /// Default 0.25.
    #[schemars(range(min = 0.0, max = 5.0))]
    pub guard_hold: f64,
    /// Whether the VH attacks at all (scenes that test gaze switch it off).
    pub attacks: bool,
    /// Farthest the VH steps its torso toward a punch's target, m: a punch
    /// whose target lies beyond the arm's reach from the shoulder is
    /// thrown with a lunge of the difference, up to this (boxers step
    /// into a jab; the stand slides). Not a human figure: the 0.24 m the
    /// VH's arm falls short of the avatar's head at the default distance,
    /// with room to spare. 0 keeps the torso still (the seed). 0-1 m: a
    /// lunge longer than a metre is no longer a step. Default 0.3.
    #[serde(default = "default_max_lunge")]
    #[schemars(range(min = 0.0, max = 1.0))]
    pub max_lunge: f64,
    /// Time from seeing a punch to the waist starting an evasion, s.
    /// Default 0.13, the guard's: the same decision on the same sight.
    /// 0-1 s, as the guard's.
    #[schemars(range(min = 0.0, max = 1.0))]
    pub evade_reaction: f64,
    /// Time to carry an evasion out (the minimum-jerk path of the waist and
    /// knees), s, 0.05-2. Default 0.15. Faster than 50 ms no body moves;
    /// 2 s is a slow-motion demonstration.
    #[schemars(range(min = 0.05, max = 2.0))]
    pub evade_time: f64,
    /// An opponent glove closing on the head faster than this, its path
    /// passing within 15 cm of the head, is a punch starting, m/s: the
    /// moment an evasion is decided. Default 0.6: skilled fighters read a
    /// punch from its first movement (Rosalie & Mueller 2013, Q. J. Exp.
    /// Psychol. 66:1951; Petri, Droste & Witte 2020, J. Martial Arts Res.
    /// 3(3): punches are mostly recognised in their first stages).
    /// 0.1-20 m/s: slower is a glove drifting, not a punch; 20 m/s is
    /// above the fastest punch.
    #[schemars(range(min = 0.1, max = 20.0))]
    pub evade_speed: f64,
    /// How long an evasion is held once carried out, before recovering, s.
    /// Default 0.25: the punch has gone by. 0.05-2 s, as `evade_time`.
    #[schemars(range(min = 0.05, max = 2.0))]
    pub evade_hold: f64,
    /// Whether the VH steps to hold its fighting range (footwork).
    pub footwork: bool,
    /// Fighting range held by the footwork: horizontal distance from the
    /// waist joint to the opponent's head, m. Default 0.92, the distance
    /// the scenes start at (a jab's reach with a short step in). 0.3-3 m:
    /// nearer the bodies overlap; 3 m is beyond any punch's reach.
    #[schemars(range(min = 0.3, max = 3.0))]
    pub range: f64,
    /// The range may drift this far before the VH steps, m, 0-1.
    /// Default 0.1.
    #[schemars(range(min = 0.0, max = 1.0))]
    pub range_tolerance: f64,
    /// How much of the opponent's approach the footwork reads ahead, 0-1:
    /// the range it holds is judged where the opponent's closing speed
    /// will have brought it once a step decided now is taken (1), or
    /// where the opponent is now (0), so that a step in catches it before
    /// it steps back. Default 1. Experts read a body's movement early,
    /// near-experts once the attack has started (an approach is its
    /// start), novices only once it has happened (Rosalie & Mueller 2013,
    /// Q. J. Exp. Psychol. 66:1951); the levels set 0 (novice) and 1
    /// (amateur, pro).
    #[serde(default = "one")]
    #[schemars(range(min = 0.0, max = 1.0))]
    pub approach_read: f64,
    /// Longest footwork step of the pelvis, m, 0-1 (a long stride).
    /// Default 0.3.
    #[schemars(range(min = 0.0, max = 1.0))]
    pub max_step: f64,
    /// Circle the opponent: once the feet have been still this long in
    /// range, the VH steps round it (alternating sides), s; `None` (the
    /// default) never. The default sparring scene circles every 3 s.
    /// Above 0 and at most 600 s (longer than a round).
    #[serde(default)]
    #[schemars(range(max = 600.0), extend("exclusiveMinimum" = 0.0))]
    pub circle_after: Option<f64>,
    /// The VH turns to face the opponent when its bearing is more than
    /// this off the body's heading, deg (the feet step round), 1-90.
    /// Default 15; beyond 90 deg the opponent would be behind the VH's
    /// shoulder.
    #[schemars(range(min = 1.0, max = 90.0))]
    pub turn_tolerance_deg: f64,
    /// Duration of one footwork step of the pelvis, s, 0.05-2.
    /// Default 0.4.
    #[schemars(range(min = 0.05, max = 2.0))]
    pub step_time: f64,
    /// Share of punches thrown with the lead (left) glove, the jabs; the
    /// rest are the rear hand's power punches. Default 0.5. Professionals'
    /// jabs are 41.5 % of their punches (CompuBox averages). A share, 0-1.
    #[schemars(range(min = 0.0, max = 1.0))]
    pub jab_share: f64,
    /// The opponent's head closing faster than this is a body cue, m/s
    /// (a step in behind a punch, or a feint): read by a VH whose
    /// `personality.anticipation` is above 0. Default 0.5: a stepping
    /// punch's head peaks near 2 m/s, a feint's near 1; the sway of a
    /// guard stays well under. 0.1-20 m/s, as `evade_speed`.
    #[serde(default = "default_cue_speed")]
    #[schemars(range(min = 0.1, max = 20.0))]
    pub cue_speed: f64,
    /// Chance that an attack goes on with one more punch (a combination:
    /// 1-1, 1-2, 1-2-3, body-head), asked after each punch, at most three
    /// punches in all; a probability, 0-1. Default 0: the seed's single
    /// punches. Elite amateurs throw about 20-26 punches a minute (Davis et
    /// al. 2018, J. Strength Cond. Res., the figure), mostly in
    /// flurries of two and three; a punch in a combination starts as the
    /// one before comes back (Piorkowski, Lees & Barton 2011, Sports
    /// Biomech. 10:1). The levels set 0.15 (novice) to 0.6 (pro).
    #[serde(default)]
    #[schemars(range(min = 0.0, max = 1.0))]
    pub combination: f64,
    /// Share of the VH's attack decisions that open with a feint: the
    /// start of a punch without the punch (eyes on your head, glove and
    /// shoulder 8 cm toward it, out and back in 0.3 s), then, with the
    /// chance of a combination's next punch, the real punch with the
    /// other hand into the reaction it drew. A probability, 0-1. Default
    /// 0: the seed does not feint. The levels set 0 (novice), 0.1
    /// (amateur) and 0.2 (pro): our amounts, as we found no published
    /// count of boxers' feints.
    #[serde(default)]
    #[schemars(range(min = 0.0, max = 1.0))]
    pub feint: f64,
    /// How far the guard's gloves sit below the stance, m (fatigue lowers
    /// it), 0-0.3. Default 0; 0.3 m is arms hanging, as between rounds.
    #[schemars(range(min = 0.0, max = 0.3))]
    pub guard_drop: f64,
}

fn one() -> f64 {
    1.0
}

fn default_max_lunge() -> f64 {
    0.3
}

fn default_cue_speed() -> f64 {
    0.5
}

impl Default for BehaviourParams {
    /// The original's rules (boxing.md): guard at 2 m/s, pi/8, 0.5 s; punch
    /// 200 ms after the look, a ~0.5 s reach out and back.
    fn default() -> Self {
        BehaviourParams {
            attack_rate: 0.25,
            punch_delay: 0.2,
            punch_time: 0.5,
            target_spread: 0.03,
            body_shot_share: 0.3,
            guard_speed: 2.0,
            guard_angle_deg: 22.5,
            guard_ttc: 0.5,
            guard_reaction: 0.13,
            guard_hold: 0.25,
            attacks: true,
            max_lunge: default_max_lunge(),
            evade_reaction: 0.13,
            evade_time: 0.15,
            evade_speed: 0.6,
            evade_hold: 0.25,
            footwork: true,
            range: 0.92,
            range_tolerance: 0.1,
            approach_read: 1.0,
            max_step: 0.3,
            turn_tolerance_deg: 15.0,
            circle_after: None,
            step_time: 0.4,
            jab_share: 0.5,
            cue_speed: default_cue_speed(),
            combination: 0.0,
            feint: 0.0,
            guard_drop: 0.0,
        }
    }
}
