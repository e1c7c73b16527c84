//! Checking a scene's expectations against the samples of a run, online
//! (constant memory, whatever the run's length).

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::sim::Sample;
use crate::sim::blows::{BlowKind, Fighter};
use shisen_gaze::behaviour::{ActionKind, EYES_ON_TARGET};

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
    /// Every state value stays finite (no NaN) for the whole run.
    Finite,
}

fn default_offset() -> f64 {
    0.08
}

/// The verdict on one expectation.
#[derive(Clone, Debug, PartialEq)]
pub struct Verdict {
    /// What was expected, in words.
    pub what: String,
    /// What was measured, in words.
    pub measured: String,
    /// The measured number (share, degrees, seconds...).
    pub value: f64,
    /// Whether it holds.
    pub pass: bool,
}

#[derive(Clone, Debug, Default)]
struct Acc {
    n: u64,
    hits: u64,
    max: f64,
    min: Option<f64>,
    first: Option<f64>,
    bad: bool,
    /// Telegraph: when the gaze last went onto the attack target.
    since: Option<f64>,
    punching: bool,
    /// Blinks: whether the lids were more than half shut last tick.
    shut: bool,
    /// HeadRotation: the head's world direction at the window's start.
    origin: Option<glam::DVec2>,
    /// Evades: the head's position when the evasion under way began,
    /// whether it got far enough, whether it was touched.
    evasion: Option<(glam::DVec3, bool, bool)>,
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

fn angle(s: &Sample, j: JointName) -> f64 {
    match j {
        JointName::NeckYaw => s.neck_actual.yaw,
        JointName::NeckPitch => s.neck_actual.pitch,
        JointName::NeckRoll => s.neck_actual.roll,
        JointName::LeftEyeYaw => s.eye_actual[0].x,
        JointName::LeftEyePitch => s.eye_actual[0].y,
        JointName::RightEyeYaw => s.eye_actual[1].x,
        JointName::RightEyePitch => s.eye_actual[1].y,
    }
}

fn inside(t: f64, from: f64, to: f64) -> bool {
    // Samples are stamped at the end of their tick; half-open on the left.
    t > from + 1e-9 && t <= to + 1e-9
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
            match e {
                Expect::GazeShare {
                    target, from, to, ..
                }
                | Expect::GazeShareAtMost {
                    target, from, to, ..
                } => {
                    if inside(s.t, *from, *to) {
                        a.n += 1;
                        a.hits += (s.gaze_target == *target) as u64;
                    }
                }
                Expect::GazeReaches { target, from, to } => {
                    if inside(s.t, *from, *to) && a.first.is_none() && s.gaze_target == *target {
                        a.first = Some(s.t);
                    }
                }
                Expect::AngleBelow {
                    joint, from, to, ..
                } => {
                    if inside(s.t, from.unwrap_or(0.0), to.unwrap_or(self.duration)) {
                        let v = angle(s, *joint).abs().to_degrees();
                        a.n += 1;
                        a.max = if v.is_nan() { f64::NAN } else { a.max.max(v) };
                    }
                }
                Expect::AngleReaches {
                    joint, from, to, ..
                } => {
                    if inside(s.t, *from, *to) {
                        a.n += 1;
                        a.max = a.max.max(angle(s, *joint).abs().to_degrees());
                    }
                }
                Expect::Telegraph { .. } => {
                    // The eyes are physically on the target (within EYES_ON_TARGET).
                    let on_target = s.action == ActionKind::Attack
                        && s.source == shisen_gaze::attention::Source::TopDown
                        && s.los_error[0].max(s.los_error[1]) < EYES_ON_TARGET;
                    if !on_target {
                        a.since = None;
                    } else if a.since.is_none() {
                        a.since = Some(s.t);
                    }
                    if s.punching && !a.punching {
                        a.n += 1;
                        let lead = a.since.map_or(0.0, |t0| s.t - t0);
                        a.min = Some(a.min.map_or(lead, |m: f64| m.min(lead)));
                    }
                    a.punching = s.punching;
                }
                Expect::LineOfSight { from, to, .. }
                | Expect::LineOfSightReaches { from, to, .. } => {
                    if inside(s.t, *from, *to) {
                        let v = s.los_error[0].max(s.los_error[1]).to_degrees();
                        a.n += 1;
                        a.max = if v.is_nan() { f64::NAN } else { a.max.max(v) };
                    }
                }
                Expect::ActionShare {
                    action, from, to, ..
                } => {
                    if inside(s.t, *from, *to) {
                        a.n += 1;
                        a.hits += (s.action == *action) as u64;
                    }
                }
                Expect::Blinks { from, to, .. } => {
                    let shut = s.blink > 0.5;
                    if inside(s.t, *from, *to) && shut && !a.shut {
                        a.hits += 1;
                    }
                    a.shut = shut;
                }
                Expect::HeadHit { from, to, .. } => {
                    if inside(s.t, *from, *to) && s.head_hit && a.first.is_none() {
                        a.first = Some(s.t);
                    }
                }
                Expect::Blows {
                    kind, by, from, to, ..
                } => {
                    if inside(s.t, *from, *to) {
                        a.hits += s
                            .blows
                            .iter()
                            .filter(|b| b.kind == *kind && b.by == *by)
                            .count() as u64;
                    }
                }
                Expect::HeadRotation { from, to, .. } => {
                    if inside(s.t, *from, *to) {
                        let o = *a.origin.get_or_insert(s.head_world);
                        a.n += 1;
                        a.max = a.max.max((s.head_world - o).length().to_degrees());
                    }
                }
                Expect::HeadSpeed { from, to, .. } => {
                    if inside(s.t, *from, *to) {
                        a.n += 1;
                        a.max = a.max.max(s.head_speed);
                    }
                }
                Expect::BlowMomentum { by, from, to, .. } => {
                    if inside(s.t, *from, *to) {
                        for b in s
                            .blows
                            .iter()
                            .filter(|b| b.kind == BlowKind::Hit && b.by == *by)
                        {
                            let j = f64::from(b.impulse);
                            a.hits += 1;
                            a.max = a.max.max(j);
                            a.min = Some(a.min.map_or(j, |m: f64| m.min(j)));
                        }
                    }
                }
                Expect::Evades {
                    kind,
                    from,
                    to,
                    offset,
                    ..
                } => {
                    let evading = match kind {
                        Some(k) => s.action == *k,
                        None => s.action.defends() && s.action != ActionKind::Guard,
                    };
                    match (&mut a.evasion, evading) {
                        (None, true) if inside(s.t, *from, *to) => {
                            a.evasion = Some((s.head, false, s.head_hit));
                            a.n += 1;
                        }
                        (Some((start, far, touched)), true) => {
                            *far |= (s.head - *start).length() >= *offset;
                            *touched |= s.head_hit;
                        }
                        (Some((_, far, touched)), false) => {
                            a.hits += u64::from(*far && !*touched);
                            a.evasion = None;
                        }
                        _ => {}
                    }
                }
                Expect::Range { from, to, .. } | Expect::Fatigue { from, to, .. } => {
                    if inside(s.t, *from, *to) {
                        let v = match e {
                            Expect::Range { .. } => s.range,
                            _ => s.fatigue,
                        };
                        a.n += 1;
                        a.max = a.max.max(v);
                        a.min = Some(a.min.map_or(v, |m: f64| m.min(v)));
                    }
                }
                Expect::Finite => {
                    a.n += 1;
                    a.bad |= !s.finite
                        || !s.gaze_point.is_finite()
                        || !s.eye_actual[0].is_finite()
                        || !s.eye_actual[1].is_finite();
                }
            }
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

fn share(a: &Acc) -> f64 {
    if a.n == 0 {
        0.0
    } else {
        a.hits as f64 / a.n as f64
    }
}

fn judge(e: &Expect, a: &Acc, duration: f64) -> Verdict {
    match e {
        Expect::GazeShare {
            target,
            from,
            to,
            at_least,
        } => {
            let v = share(a);
            Verdict {
                what: format!(
                    "gaze on `{target}` >= {:.0}% of [{from}, {to}] s",
                    at_least * 100.0
                ),
                measured: format!("{:.1}%", v * 100.0),
                value: v,
                pass: a.n > 0 && v >= *at_least,
            }
        }
        Expect::GazeShareAtMost {
            target,
            from,
            to,
            at_most,
        } => {
            let v = share(a);
            Verdict {
                what: format!(
                    "gaze on `{target}` <= {:.0}% of [{from}, {to}] s",
                    at_most * 100.0
                ),
                measured: format!("{:.1}%", v * 100.0),
                value: v,
                pass: a.n > 0 && v <= *at_most,
            }
        }
        Expect::GazeReaches { target, from, to } => Verdict {
            what: format!("gaze reaches `{target}` within [{from}, {to}] s"),
            measured: a.first.map_or("never".into(), |t| {
                format!("at {t:.3} s ({:.0} ms after {from})", (t - from) * 1e3)
            }),
            value: a.first.map_or(f64::INFINITY, |t| t - from),
            pass: a.first.is_some(),
        },
        Expect::AngleBelow {
            joint,
            max_deg,
            from,
            to,
        } => Verdict {
            what: format!(
                "|{joint:?}| < {max_deg} deg over [{}, {}] s",
                from.unwrap_or(0.0),
                to.unwrap_or(duration)
            ),
            measured: format!("max {:.2} deg", a.max),
            value: a.max,
            pass: a.n > 0 && a.max < *max_deg,
        },
        Expect::AngleReaches {
            joint,
            min_deg,
            from,
            to,
        } => Verdict {
            what: format!("|{joint:?}| reaches {min_deg} deg within [{from}, {to}] s"),
            measured: format!("max {:.2} deg", a.max),
            value: a.max,
            pass: a.n > 0 && a.max >= *min_deg,
        },
        Expect::Telegraph { min_lead } => Verdict {
            what: format!(
                "eyes on the attack target (< {} deg) >= {:.0} ms before every VH punch",
                EYES_ON_TARGET.to_degrees(),
                min_lead * 1e3
            ),
            measured: match a.min {
                Some(m) => format!("{} punches, shortest lead {:.0} ms", a.n, m * 1e3),
                None => "no punch thrown".into(),
            },
            value: a.min.unwrap_or(0.0),
            pass: a.min.is_some_and(|m| m >= *min_lead),
        },
        Expect::LineOfSight { max_deg, from, to } => Verdict {
            what: format!("line-of-sight error < {max_deg} deg over [{from}, {to}] s"),
            measured: format!("max {:.3} deg", a.max),
            value: a.max,
            pass: a.n > 0 && a.max < *max_deg,
        },
        Expect::ActionShare {
            action,
            from,
            to,
            at_least,
        } => {
            let v = share(a);
            Verdict {
                what: format!(
                    "action {action:?} >= {:.0}% of [{from}, {to}] s",
                    at_least * 100.0
                ),
                measured: format!("{:.1}%", v * 100.0),
                value: v,
                pass: a.n > 0 && v >= *at_least,
            }
        }
        Expect::Blinks { from, to, at_least } => Verdict {
            what: format!("at least {at_least} blinks in [{from}, {to}] s"),
            measured: format!("{} blinks", a.hits),
            value: a.hits as f64,
            pass: a.hits >= u64::from(*at_least),
        },
        Expect::HeadHit { from, to, hit } => Verdict {
            what: format!(
                "the head is {}hit in [{from}, {to}] s",
                if *hit { "" } else { "not " }
            ),
            measured: a
                .first
                .map_or("no hit".into(), |t| format!("hit at {t:.3} s")),
            value: a.first.map_or(0.0, |_| 1.0),
            pass: a.first.is_some() == *hit,
        },
        Expect::Blows {
            kind,
            by,
            from,
            to,
            at_least,
            at_most,
        } => Verdict {
            what: format!(
                "{kind:?} by {by:?}: at least {at_least}{} in [{from}, {to}] s",
                at_most.map_or(String::new(), |m| format!(", at most {m}"))
            ),
            measured: format!("{}", a.hits),
            value: a.hits as f64,
            pass: a.hits >= u64::from(*at_least) && at_most.is_none_or(|m| a.hits <= u64::from(m)),
        },
        Expect::HeadRotation {
            at_least_deg,
            at_most_deg,
            from,
            to,
        } => Verdict {
            what: format!(
                "the head turns >= {at_least_deg}{} deg in [{from}, {to}] s",
                at_most_deg.map_or(String::new(), |m| format!(" and <= {m}"))
            ),
            measured: format!("peak {:.2} deg", a.max),
            value: a.max,
            pass: a.n > 0 && a.max >= *at_least_deg && at_most_deg.is_none_or(|m| a.max <= m),
        },
        Expect::HeadSpeed {
            at_least,
            at_most,
            from,
            to,
        } => Verdict {
            what: format!(
                "the head's peak speed in [{at_least}, {at_most}] rad/s in [{from}, {to}] s"
            ),
            measured: format!("peak {:.2} rad/s", a.max),
            value: a.max,
            pass: a.n > 0 && a.max >= *at_least && a.max <= *at_most,
        },
        Expect::BlowMomentum {
            by,
            at_least,
            at_most,
            from,
            to,
        } => {
            let lo = a.min.unwrap_or(f64::NAN);
            Verdict {
                what: format!(
                    "hits by {by:?} in [{from}, {to}] s carry [{at_least}, {at_most}] N s"
                ),
                measured: if a.hits == 0 {
                    "no hit".into()
                } else {
                    format!("{} hits, {lo:.2}-{:.2} N s", a.hits, a.max)
                },
                value: a.max,
                pass: a.hits > 0 && lo >= *at_least && a.max <= *at_most,
            }
        }
        Expect::LineOfSightReaches { min_deg, from, to } => Verdict {
            what: format!("line-of-sight error reaches {min_deg} deg in [{from}, {to}] s"),
            measured: format!("max {:.3} deg", a.max),
            value: a.max,
            pass: a.n > 0 && a.max >= *min_deg,
        },
        Expect::Evades {
            kind,
            from,
            to,
            at_least,
            at_most,
            offset,
        } => {
            // An evasion still under way at the end counts if it worked.
            let open = a
                .evasion
                .map_or(0, |(_, far, touched)| u64::from(far && !touched));
            let ok = a.hits + open;
            Verdict {
                what: format!(
                    "at least {at_least} {} in [{from}, {to}] s take the head {offset} m off its line untouched{}",
                    kind.map_or("evasions".to_string(), |k| format!("{k:?}")),
                    at_most.map_or(String::new(), |m| format!(", at most {m} started"))
                ),
                measured: format!("{ok} of {} evasions", a.n),
                value: ok as f64,
                pass: ok >= u64::from(*at_least) && at_most.is_none_or(|m| a.n <= u64::from(m)),
            }
        }
        Expect::Range {
            at_least,
            at_most,
            from,
            to,
        }
        | Expect::Fatigue {
            at_least,
            at_most,
            from,
            to,
        } => {
            let (what, unit) = match e {
                Expect::Range { .. } => ("the range", " m"),
                _ => ("the VH's fatigue", ""),
            };
            let lo = a.min.unwrap_or(f64::NAN);
            Verdict {
                what: format!("{what} stays in [{at_least}, {at_most}]{unit} in [{from}, {to}] s"),
                measured: format!("{lo:.3}-{:.3}{unit}", a.max),
                value: a.max,
                pass: a.n > 0 && lo >= *at_least && a.max <= *at_most,
            }
        }
        Expect::Finite => Verdict {
            what: "state finite throughout (no NaN)".into(),
            measured: if a.bad {
                "non-finite state".into()
            } else {
                format!("{} ticks finite", a.n)
            },
            value: if a.bad { 1.0 } else { 0.0 },
            pass: !a.bad && a.n > 0,
        },
    }
}
