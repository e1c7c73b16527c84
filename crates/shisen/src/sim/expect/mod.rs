//! Checking a scene's expectations against the samples of a run, online
//! (constant memory, whatever the run's length).

mod measure;
mod verdict;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::sim::Sample;
use crate::sim::blows::{BlowKind, Fighter};
use measure::{Acc, measure};
use shisen_gaze::behaviour::ActionKind;
pub use verdict::Verdict;
use verdict::judge;

/// A named angle of the VH for expectations.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize, JsonSchema)]
pub enum JointName {
    /// Neck yaw (turning the head left or right).
    NeckYaw,
    /// Neck pitch (nodding up or down).
    NeckPitch,
    /// Neck roll (tilting an ear toward a shoulder).
    NeckRoll,
    /// Left eye yaw in its orbit.
    LeftEyeYaw,
    /// Left eye pitch in its orbit.
    LeftEyePitch,
    /// Right eye yaw in its orbit.
    RightEyeYaw,
    /// Right eye pitch in its orbit.
    RightEyePitch,
}

/// A predicate over a time window, checked by a headless run.
///
/// Windows `[from, to]` are s from the run's start, ordered and inside the
/// run; shares are fractions of the window's ticks, 0-1.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub enum Expect {
    /// The VH's gaze target is `target` for at least a share `at_least`
    /// of the window.
    GazeShare {
        /// Target name (`head`, `left_glove`, `point`, a prop, a VH segment).
        target: String,
        /// Window start, s from the run's start (0 to a day, 86400 s).
        #[schemars(range(min = 0.0, max = 86_400.0))]
        from: f64,
        /// Window end, s (not before `from`, not after the run's end).
        #[schemars(range(min = 0.0, max = 86_400.0))]
        to: f64,
        /// Least share of the window, 0-1.
        #[schemars(range(min = 0.0, max = 1.0))]
        at_least: f64,
    },
    /// The VH's gaze target is `target` for at most a share `at_most` of
    /// the window.
    GazeShareAtMost {
        /// Target name.
        target: String,
        /// Window start, s from the run's start (0 to a day, 86400 s).
        #[schemars(range(min = 0.0, max = 86_400.0))]
        from: f64,
        /// Window end, s (not before `from`, not after the run's end).
        #[schemars(range(min = 0.0, max = 86_400.0))]
        to: f64,
        /// Most share of the window, 0-1.
        #[schemars(range(min = 0.0, max = 1.0))]
        at_most: f64,
    },
    /// The VH's gaze target becomes `target` at some time in the window.
    GazeReaches {
        /// Target name.
        target: String,
        /// Window start, s from the run's start (0 to a day, 86400 s).
        #[schemars(range(min = 0.0, max = 86_400.0))]
        from: f64,
        /// Window end, s (not before `from`, not after the run's end).
        #[schemars(range(min = 0.0, max = 86_400.0))]
        to: f64,
    },
    /// The angle's magnitude stays below `max_deg` throughout the window
    /// (the whole run if `from` and `to` are omitted).
    AngleBelow {
        /// Which angle.
        joint: JointName,
        /// Bound on |angle|, deg. 0-180: no angle is larger.
        #[schemars(range(min = 0.0, max = 180.0))]
        max_deg: f64,
        /// Window start, s (default 0; at most a day).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        #[schemars(range(min = 0.0, max = 86_400.0))]
        from: Option<f64>,
        /// Window end, s (default the run's end; at most a day).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        #[schemars(range(min = 0.0, max = 86_400.0))]
        to: Option<f64>,
    },
    /// The angle's magnitude reaches at least `min_deg` at some time in
    /// the window.
    AngleReaches {
        /// Which angle.
        joint: JointName,
        /// Least peak |angle|, deg. 0-180: no angle is larger.
        #[schemars(range(min = 0.0, max = 180.0))]
        min_deg: f64,
        /// Window start, s from the run's start (0 to a day, 86400 s).
        #[schemars(range(min = 0.0, max = 86_400.0))]
        from: f64,
        /// Window end, s (not before `from`, not after the run's end).
        #[schemars(range(min = 0.0, max = 86_400.0))]
        to: f64,
    },
    /// Before every punch the VH throws, its eyes have been on the attack
    /// target (chosen top-down during the attack, line-of-sight error under
    /// 2 deg) for at least `min_lead`: the telegraph. Fails if no punch is
    /// thrown.
    Telegraph {
        /// Least lead, s. 0-10: a telegraph lasts a fraction of a second;
        /// ten seconds would be a stare, not a tell.
        #[schemars(range(min = 0.0, max = 10.0))]
        min_lead: f64,
    },
    /// Both eyes' line-of-sight error to the gaze point stays below
    /// `max_deg` throughout the window.
    LineOfSight {
        /// Bound on the error, deg. 0-180: no angle is larger.
        #[schemars(range(min = 0.0, max = 180.0))]
        max_deg: f64,
        /// Window start, s from the run's start (0 to a day, 86400 s).
        #[schemars(range(min = 0.0, max = 86_400.0))]
        from: f64,
        /// Window end, s (not before `from`, not after the run's end).
        #[schemars(range(min = 0.0, max = 86_400.0))]
        to: f64,
    },
    /// The VH's action is `action` for at least a share `at_least` of the
    /// window.
    ActionShare {
        /// The action (`Guard`, `Attack`, `Slip`, ...).
        action: ActionKind,
        /// Window start, s from the run's start (0 to a day, 86400 s).
        #[schemars(range(min = 0.0, max = 86_400.0))]
        from: f64,
        /// Window end, s (not before `from`, not after the run's end).
        #[schemars(range(min = 0.0, max = 86_400.0))]
        to: f64,
        /// Least share of the window, 0-1.
        #[schemars(range(min = 0.0, max = 1.0))]
        at_least: f64,
    },
    /// The VH blinks (lids more than half shut) at least `at_least` times
    /// in the window.
    Blinks {
        /// Window start, s from the run's start (0 to a day, 86400 s).
        #[schemars(range(min = 0.0, max = 86_400.0))]
        from: f64,
        /// Window end, s (not before `from`, not after the run's end).
        #[schemars(range(min = 0.0, max = 86_400.0))]
        to: f64,
        /// Fewest blinks, a whole number, 0-100000 (a day at more than one a second); at least 1 (0
        /// could not fail).
        #[schemars(range(min = 0, max = 100_000))]
        at_least: u32,
    },
    /// An opponent glove touches the VH's head in the window (`hit: true`),
    /// or never does (`hit: false`).
    HeadHit {
        /// Window start, s from the run's start (0 to a day, 86400 s).
        #[schemars(range(min = 0.0, max = 86_400.0))]
        from: f64,
        /// Window end, s (not before `from`, not after the run's end).
        #[schemars(range(min = 0.0, max = 86_400.0))]
        to: f64,
        /// Whether the head is hit.
        hit: bool,
    },
    /// Blows of a kind (hits landed, punches blocked: see `sim::blows`)
    /// thrown by one side in the window number at least `at_least`, and
    /// at most `at_most` if given.
    Blows {
        /// `Hit` or `Block`.
        kind: BlowKind,
        /// Who threw them: `Vh` or `Opponent`.
        by: Fighter,
        /// Window start, s from the run's start (0 to a day, 86400 s).
        #[schemars(range(min = 0.0, max = 86_400.0))]
        from: f64,
        /// Window end, s (not before `from`, not after the run's end).
        #[schemars(range(min = 0.0, max = 86_400.0))]
        to: f64,
        /// Fewest blows (default 0), a whole number, 0-100000 (a day at more than one a second).
        #[serde(default)]
        #[schemars(range(min = 0, max = 100_000))]
        at_least: u32,
        /// Most blows, if bounded: a whole number, 0-100000 (a day at more than one a second), not
        /// below `at_least`.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        #[schemars(range(min = 0, max = 100_000))]
        at_most: Option<u32>,
    },
    /// The head's direction in the world turns at least `at_least_deg`
    /// (and at most `at_most_deg`, if given) away from where it pointed at
    /// the start of the window (a hit rocks the head).
    HeadRotation {
        /// Least peak rotation, deg: above 0 (0 could not fail), at most 180.
        #[schemars(range(max = 180.0), extend("exclusiveMinimum" = 0.0))]
        at_least_deg: f64,
        /// Most peak rotation, deg, if bounded: 0-180.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        #[schemars(range(min = 0.0, max = 180.0))]
        at_most_deg: Option<f64>,
        /// Window start, s from the run's start (0 to a day, 86400 s).
        #[schemars(range(min = 0.0, max = 86_400.0))]
        from: f64,
        /// Window end, s (not before `from`, not after the run's end).
        #[schemars(range(min = 0.0, max = 86_400.0))]
        to: f64,
    },
    /// The head's peak angular speed in the world over the window lies in
    /// [at_least, at_most] (a blow snaps the head).
    HeadSpeed {
        /// Least peak speed, rad/s. 0-200: a jab snaps the head at 9-21
        /// rad/s (scenes/jab_snaps_head.ron); 200 is several times the
        /// hardest blows'.
        #[schemars(range(min = 0.0, max = 200.0))]
        at_least: f64,
        /// Most peak speed, rad/s, 0-200.
        #[schemars(range(min = 0.0, max = 200.0))]
        at_most: f64,
        /// Window start, s from the run's start (0 to a day, 86400 s).
        #[schemars(range(min = 0.0, max = 86_400.0))]
        from: f64,
        /// Window end, s (not before `from`, not after the run's end).
        #[schemars(range(min = 0.0, max = 86_400.0))]
        to: f64,
    },
    /// Every hit one side lands in the window (at least one) carries an
    /// impulse in [at_least, at_most].
    BlowMomentum {
        /// Who threw them: `Vh` or `Opponent`.
        by: Fighter,
        /// Least impulse, N s. 0-500: a clean jab carries 10-21 N s
        /// (a 2.9 kg effective mass at 6-9 m/s; Walilko, Viano & Bir
        /// 2005); 500 is many times the hardest punch.
        #[schemars(range(min = 0.0, max = 500.0))]
        at_least: f64,
        /// Most impulse, N s, 0-500.
        #[schemars(range(min = 0.0, max = 500.0))]
        at_most: f64,
        /// Window start, s from the run's start (0 to a day, 86400 s).
        #[schemars(range(min = 0.0, max = 86_400.0))]
        from: f64,
        /// Window end, s (not before `from`, not after the run's end).
        #[schemars(range(min = 0.0, max = 86_400.0))]
        to: f64,
    },
    /// An eye's line-of-sight error to the gaze point reaches at least
    /// `min_deg` at some time in the window (a blow knocks the gaze off).
    LineOfSightReaches {
        /// Least peak error, deg. 0-180: no angle is larger.
        #[schemars(range(min = 0.0, max = 180.0))]
        min_deg: f64,
        /// Window start, s from the run's start (0 to a day, 86400 s).
        #[schemars(range(min = 0.0, max = 86_400.0))]
        from: f64,
        /// Window end, s (not before `from`, not after the run's end).
        #[schemars(range(min = 0.0, max = 86_400.0))]
        to: f64,
    },
    /// At least `at_least` evasions of `kind` (any evasion if `None`:
    /// `Slip`, `Duck`, `LeanBack`) start in the window and work: during the
    /// evasion the head gets at least `offset` from where it was when it
    /// began (off the punch's line) and no opponent glove touches the
    /// head.
    Evades {
        /// `Slip`, `Duck` or `LeanBack`; `None` (default) for any.
        #[serde(default)]
        kind: Option<ActionKind>,
        /// Window start, s from the run's start (0 to a day, 86400 s).
        #[schemars(range(min = 0.0, max = 86_400.0))]
        from: f64,
        /// Window end, s (not before `from`, not after the run's end).
        #[schemars(range(min = 0.0, max = 86_400.0))]
        to: f64,
        /// Least number of working evasions, a whole number, 0-100000 (a
        /// day at more than one a second).
        #[schemars(range(min = 0, max = 100_000))]
        at_least: u32,
        /// Most evasions started (working or not), if given: a whole
        /// number, 0-100000 (a day at more than one a second).
        #[serde(default)]
        #[schemars(range(min = 0, max = 100_000))]
        at_most: Option<u32>,
        /// How far the head must get off its line, m (default 0.08). 0-1:
        /// a slip or duck moves the head 0.1-0.3 m; a metre is a step away.
        #[serde(default = "default_offset")]
        #[schemars(range(min = 0.0, max = 1.0))]
        offset: f64,
    },
    /// The fighting range (horizontal distance from the VH's pelvis, under
    /// its waist joint, to the opponent's head) stays within
    /// [at_least, at_most] throughout the window.
    Range {
        /// Least range, m. 0-10: the ring's diagonal is under 8 m.
        #[schemars(range(min = 0.0, max = 10.0))]
        at_least: f64,
        /// Most range, m, 0-10.
        #[schemars(range(min = 0.0, max = 10.0))]
        at_most: f64,
        /// Window start, s from the run's start (0 to a day, 86400 s).
        #[schemars(range(min = 0.0, max = 86_400.0))]
        from: f64,
        /// Window end, s (not before `from`, not after the run's end).
        #[schemars(range(min = 0.0, max = 86_400.0))]
        to: f64,
    },
    /// The VH's fatigue (E1, 0 fresh to 1 exhausted) stays within
    /// [at_least, at_most] throughout the window.
    Fatigue {
        /// Least fatigue, 0-1.
        #[schemars(range(min = 0.0, max = 1.0))]
        at_least: f64,
        /// Most fatigue, 0-1, not below `at_least`.
        #[schemars(range(min = 0.0, max = 1.0))]
        at_most: f64,
        /// Window start, s from the run's start (0 to a day, 86400 s).
        #[schemars(range(min = 0.0, max = 86_400.0))]
        from: f64,
        /// Window end, s (not before `from`, not after the run's end).
        #[schemars(range(min = 0.0, max = 86_400.0))]
        to: f64,
    },
    /// The VH is knocked down (its physical body falls: it needs
    /// `vh.body.pelvis: Balanced`) at least `at_least` and at most
    /// `at_most` times in the window, and gets up at least `get_ups` times
    /// in it.
    Knockdowns {
        /// Window start, s from the run's start (0 to a day, 86400 s).
        #[schemars(range(min = 0.0, max = 86_400.0))]
        from: f64,
        /// Window end, s (not before `from`, not after the run's end).
        #[schemars(range(min = 0.0, max = 86_400.0))]
        to: f64,
        /// Least knockdowns, a whole number, 0-10000.
        #[serde(default)]
        #[schemars(range(min = 0, max = 10_000))]
        at_least: u32,
        /// Most knockdowns, if given: a whole number, 0-10000.
        #[serde(default)]
        #[schemars(range(min = 0, max = 10_000))]
        at_most: Option<u32>,
        /// Least get-ups, a whole number, 0-10000 (default 0).
        #[serde(default)]
        #[schemars(range(min = 0, max = 10_000))]
        get_ups: u32,
    },
    /// Every state value stays finite (no NaN) for the whole run.
    Finite,
}

fn default_offset() -> f64 {
    0.08
}

impl Expect {
    /// The time window the expectation judges in a run of `duration`
    /// seconds (`AngleBelow` defaults to the whole run), if it has one.
    pub fn window(&self, duration: f64) -> Option<(f64, f64)> {
        match self {
            Expect::GazeShare { from, to, .. }
            | Expect::GazeShareAtMost { from, to, .. }
            | Expect::GazeReaches { from, to, .. }
            | Expect::LineOfSight { from, to, .. }
            | Expect::AngleReaches { from, to, .. }
            | Expect::Blinks { from, to, .. }
            | Expect::HeadHit { from, to, .. }
            | Expect::Blows { from, to, .. }
            | Expect::HeadRotation { from, to, .. }
            | Expect::HeadSpeed { from, to, .. }
            | Expect::BlowMomentum { from, to, .. }
            | Expect::LineOfSightReaches { from, to, .. }
            | Expect::Evades { from, to, .. }
            | Expect::Range { from, to, .. }
            | Expect::Fatigue { from, to, .. }
            | Expect::Knockdowns { from, to, .. }
            | Expect::ActionShare { from, to, .. } => Some((*from, *to)),
            Expect::AngleBelow { from, to, .. } => {
                Some((from.unwrap_or(0.0), to.unwrap_or(duration)))
            }
            Expect::Finite | Expect::Telegraph { .. } => None,
        }
    }
}

/// Accumulates samples for every expectation of a scene.
pub struct Checker {
    expects: Vec<Expect>,
    acc: Vec<Acc>,
    duration: f64,
}

impl Checker {
    /// A checker for these expectations over a run of `duration` seconds.
    pub fn new(expects: &[Expect], duration: f64) -> Self {
        Checker {
            expects: expects.to_vec(),
            acc: vec![Acc::default(); expects.len()],
            duration,
        }
    }

    /// Feed one sample.
    pub fn push(&mut self, s: &Sample) {
        for (e, a) in self.expects.iter().zip(&mut self.acc) {
            measure(e, a, s, self.duration);
        }
    }

    /// The verdicts.
    pub fn verdicts(&self) -> Vec<Verdict> {
        self.expects
            .iter()
            .zip(&self.acc)
            .map(|(e, a)| judge(e, a, self.duration))
            .collect()
    }
}
