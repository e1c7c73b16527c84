//! The action plan (boxing.md): guard, evade, attack, idle. It decides
//! what the VH wants to look at (the top-down request, gaze.md 5), where its
//! gloves go (minimum-jerk reaches, tracked through the arm joints by the
//! body plan's inverse kinematics) and, in [`body`], how its body moves:
//! evasions, footwork, the trunk's turn in a punch.

mod body;

use glam::{DQuat, DVec3};
use rand::{Rng, RngExt};
use rand_distr::{Distribution, Normal};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::personality::Personality;
use crate::target::{BodyId, Spot, TargetId};
use crate::util::math::min_jerk;
use crate::vision::Seen;
use body::BodyPlan;
pub use body::{Evasion, Posture, choose_evasion};

/// The eyes are "on" a target when both lines of sight are within this
/// angle of it (rad): the planner's cue that the attack target has been
/// looked at, and the telegraph expectation's test.
pub const EYES_ON_TARGET: f64 = 2f64.to_radians();

/// The VH's current action (boxing.md).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize, JsonSchema)]
pub enum ActionKind {
    /// Guard stance, looking at the opponent's face.
    Idle,
    /// Intercepting an incoming glove.
    Guard,
    /// Looking at the target, then punching.
    Attack,
    /// Slipping a punch (head off its line sideways).
    Slip,
    /// Ducking a punch from the side.
    Duck,
    /// Leaning back out of a punch's reach.
    LeanBack,
}

impl ActionKind {
    /// Whether the action meets a seen punch (a guard or an evasion).
    pub fn defends(self) -> bool {
        !matches!(self, ActionKind::Idle | ActionKind::Attack)
    }
}

impl From<Evasion> for ActionKind {
    fn from(e: Evasion) -> Self {
        match e {
            Evasion::Slip => ActionKind::Slip,
            Evasion::Duck => ActionKind::Duck,
            Evasion::LeanBack => ActionKind::LeanBack,
        }
    }
}

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
    /// How far the guard's gloves sit below the stance, m (fatigue lowers
    /// it), 0-0.3. Default 0; 0.3 m is arms hanging, as between rounds.
    #[schemars(range(min = 0.0, max = 0.3))]
    pub guard_drop: f64,
}

/// How far the gloves come down between rounds, m (arms hanging).
const REST_DROP: f64 = 0.3;
/// How fast the guard's height changes, m/s.
const DROP_RATE: f64 = 0.5;

fn default_max_lunge() -> f64 {
    0.3
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
            max_step: 0.3,
            turn_tolerance_deg: 15.0,
            circle_after: None,
            step_time: 0.4,
            jab_share: 0.5,
            guard_drop: 0.0,
        }
    }
}

/// Where the action wants the gaze (top-down request).
#[derive(Clone, Debug, PartialEq)]
pub struct TopDown {
    /// Name of the target ("head", "left_glove", "opponent_body", ...).
    pub name: String,
    /// Body the target rides on, if any.
    pub body: Option<BodyId>,
    /// Where on that body.
    pub spot: Spot,
    /// Offset from that body's centre (or the world point if no body), m.
    pub offset: DVec3,
    /// Attention amount.
    pub amount: f64,
}

impl TopDown {
    /// Whether a target on `body` at `spot` is the one this request asks
    /// for (whoever chose it).
    pub fn aims_at(&self, body: Option<BodyId>, spot: Spot) -> bool {
        self.body == body && self.spot == spot
    }
}

/// The stronger of two top-down requests (the action's wins ties).
fn strongest(action: TopDown, face: TopDown) -> TopDown {
    if face.amount > action.amount {
        face
    } else {
        action
    }
}

/// What the opponent looks like to the planner this tick.
pub struct OpponentView<'a> {
    /// Everything the VH sees.
    pub seen: &'a [Seen],
    /// Names of all bodies, by index.
    pub names: &'a [String],
    /// The gaze target the eyes are physically on (line of sight within
    /// 2 deg at the end of the last tick), if any.
    pub eyes_on: Option<TargetId>,
    /// The opponent's head, left glove and right glove.
    pub parts: [BodyId; 3],
    /// The VH's head, torso and centre-of-mass positions (threat directions).
    pub vh_points: [DVec3; 3],
}

/// A glove reach in progress, in world coordinates.
#[derive(Clone, Debug, PartialEq)]
struct Reach {
    from: DVec3,
    to: DVec3,
    t0: f64,
    dur: f64,
    back: bool,
}

impl Reach {
    fn at(&self, t: f64) -> DVec3 {
        let s = (t - self.t0) / self.dur;
        // Out and back uses one min-jerk profile per half.
        if self.back {
            let half = self.dur / 2.0;
            if t - self.t0 < half {
                self.from + (self.to - self.from) * min_jerk((t - self.t0) / half)
            } else {
                self.to + (self.from - self.to) * min_jerk((t - self.t0 - half) / half)
            }
        } else {
            self.from + (self.to - self.from) * min_jerk(s)
        }
    }

    fn done(&self, t: f64) -> bool {
        t >= self.t0 + self.dur
    }
}

#[derive(Clone, Debug, PartialEq)]
enum Plan {
    Idle,
    Guard {
        threat: BodyId,
        hand: usize,
        point: DVec3,
        until: f64,
    },
    Evade {
        threat: BodyId,
        kind: Evasion,
        until: f64,
    },
    Attack {
        hand: usize,
        target: TopDown,
        /// Decision time; the punch waits for the eyes to land.
        decided: f64,
        /// When the eyes landed on the target.
        looked: Option<f64>,
        thrown: bool,
    },
}

/// The planner's evolving state.
#[derive(Clone, Debug)]
pub struct Behaviour {
    plan: Plan,
    reaches: [Option<Reach>; 2],
    /// The torso's step into a punch (an offset from rest, out and back
    /// with the punch).
    lunge: Option<Reach>,
    /// Guard-stance glove positions (world), left and right.
    stance: [DVec3; 2],
    /// The body's plan: evasions, footwork, the trunk's turn.
    body: BodyPlan,
    /// Punches the VH has thrown.
    pub punches_thrown: u32,
    /// Evasions the VH has started.
    pub evasions: u32,
    /// The glove whose punch was last weighed for an evasion.
    considered: Option<BodyId>,
    /// How far the guard sits below its stance now, m.
    drop: f64,
    /// Between rounds: the corner to stand in and the point to face.
    corner: Option<(DVec3, DVec3)>,
    /// Staggered by a blow (neither attacking nor defending) until, s.
    staggered_until: f64,
}

impl Default for Behaviour {
    fn default() -> Self {
        Self::new()
    }
}

impl Behaviour {
    /// Idle, gloves in the guard stance.
    pub fn new() -> Self {
        Behaviour {
            plan: Plan::Idle,
            reaches: [None, None],
            lunge: None,
            stance: [DVec3::new(0.11, 1.56, 0.27), DVec3::new(-0.11, 1.56, 0.27)],
            body: BodyPlan::default(),
            punches_thrown: 0,
            evasions: 0,
            considered: None,
            drop: 0.0,
            corner: None,
            staggered_until: f64::NEG_INFINITY,
        }
    }

    /// Between rounds (`Some`): go to the corner `.0` and face `.1`, the
    /// gloves down, neither attacking nor defending; `None`: fight. `t`:
    /// now.
    pub fn set_corner(&mut self, corner: Option<(DVec3, DVec3)>, t: f64) {
        // A lunge under way runs its course, out and back: the trunk rides
        // on it, and cutting it short would move the physics' root in one
        // tick.
        if corner.is_some() && self.corner.is_none() {
            self.plan = Plan::Idle;
            self.body.recover(t);
        }
        self.corner = corner;
    }

    /// Staggered by a blow at `t` until `until`: the VH gives ground from
    /// `from` (the opponent), its actions called off.
    pub fn stagger(&mut self, p: &BehaviourParams, from: DVec3, t: f64, until: f64) {
        self.plan = Plan::Idle;
        self.body.give_ground(p, from, t);
        self.staggered_until = until;
    }

    /// The guard-stance position of glove `hand` (trunk rest frame),
    /// lowered by fatigue or the rest.
    fn guard(&self, hand: usize) -> DVec3 {
        self.stance[hand] - DVec3::Y * self.drop
    }

    /// The current action.
    pub fn action(&self) -> ActionKind {
        match self.plan {
            Plan::Idle => ActionKind::Idle,
            Plan::Guard { .. } => ActionKind::Guard,
            Plan::Evade { kind, .. } => kind.into(),
            Plan::Attack { .. } => ActionKind::Attack,
        }
    }

    /// What the current action is about: the attack target or the
    /// incoming glove (body name or point name); `None` while idle.
    pub fn target_name<'a>(&'a self, names: &'a [String]) -> Option<&'a str> {
        match &self.plan {
            Plan::Idle => None,
            Plan::Guard { threat, .. } | Plan::Evade { threat, .. } => Some(&names[threat.index()]),
            Plan::Attack { target, .. } => Some(&target.name),
        }
    }

    /// The glove of the attack under way (0 left, the lead), if any.
    pub fn attack_hand(&self) -> Option<usize> {
        match self.plan {
            Plan::Attack { hand, .. } => Some(hand),
            _ => None,
        }
    }

    /// True while the VH's punch is in flight (after the telegraph).
    pub fn punching(&self) -> bool {
        matches!(self.plan, Plan::Attack { thrown: true, .. })
    }

    fn glove(&self, hand: usize, t: f64) -> DVec3 {
        self.reaches[hand]
            .as_ref()
            .map_or_else(|| self.body.on_trunk(self.guard(hand)), |r| r.at(t))
    }

    /// Advance one tick: choose the action, return the top-down request.
    pub fn step(
        &mut self,
        p: &BehaviourParams,
        pers: &Personality,
        view: &OpponentView,
        t: f64,
        dt: f64,
        rng: &mut impl Rng,
    ) -> TopDown {
        for r in self.reaches.iter_mut().chain([&mut self.lunge]) {
            if r.as_ref().is_some_and(|r| r.done(t)) {
                *r = None;
            }
        }
        // Watching the opponent's face is a standing top-down interest of a
        // boxer (A_face); the action's request competes with it, so a boxer
        // whose A_face exceeds A_guard keeps watching the face while it
        // guards (the seed's "strong boxer").
        let face = TopDown {
            name: "head".into(),
            body: Some(view.parts[0]),
            spot: Spot::Centre,
            offset: DVec3::ZERO,
            amount: pers.a_face,
        };
        let opponent_head = view.seen.iter().find(|s| s.body == view.parts[0]);
        let drop = p.guard_drop
            + if self.corner.is_some() {
                REST_DROP
            } else {
                0.0
            };
        self.drop += (drop - self.drop).clamp(-DROP_RATE * dt, DROP_RATE * dt);
        if let Some((corner, look)) = self.corner {
            self.body.walk_to(p, corner, look, t);
            return face;
        }
        if t < self.staggered_until {
            return face;
        }
        if !matches!(self.plan, Plan::Attack { thrown: true, .. }) {
            self.body.keep_range(p, opponent_head, t);
        }
        // A punch seen starting at the head may be evaded: decided once per
        // punch, on its first sight, by the personality's share.
        let onset = glove_onset(p, view);
        if let Some(g) = onset.filter(|g| self.considered != Some(g.body)) {
            self.considered = Some(g.body);
            let evading = matches!(self.plan, Plan::Evade { .. });
            let head = view.vh_points[0];
            let opp = opponent_head.map(|h| h.position);
            if let Some((kind, right)) =
                choose_evasion(pers, g, head, opp, rng).filter(|_| !evading)
            {
                self.body.evade(kind, right, t, p);
                self.evasions += 1;
                self.plan = Plan::Evade {
                    threat: g.body,
                    kind,
                    until: t + p.evade_reaction + p.evade_time + p.evade_hold,
                };
            }
        }
        if onset.is_none() {
            self.considered = None;
        }
        // A threat seen now pre-empts everything but an evasion of it.
        if let Some((threat, point, ttc)) = aimed_glove(p, view) {
            // The VH's glove on the side the punch comes from (the opponent's
            // left glove arrives on the VH's right).
            let hand = if threat == view.parts[1] { 1 } else { 0 };
            let met = match self.plan {
                Plan::Guard { threat: th, .. } | Plan::Evade { threat: th, .. } => th == threat,
                _ => false,
            };
            if !met || matches!(self.plan, Plan::Guard { .. }) {
                if !met {
                    let from = self.glove(hand, t);
                    // The glove moves once the reaction time is over (the
                    // reach holds its start point until t0).
                    self.reaches[hand] = Some(Reach {
                        from,
                        to: point,
                        t0: t + p.guard_reaction,
                        dur: (0.3 * ttc).max(0.05),
                        back: false,
                    });
                    if let Plan::Evade { .. } = self.plan {
                        self.body.recover(t);
                    }
                }
                self.plan = Plan::Guard {
                    threat,
                    hand,
                    point,
                    until: t + p.guard_hold,
                };
            }
        }
        match self.plan.clone() {
            Plan::Evade {
                threat,
                kind,
                until,
            } => {
                if t >= until {
                    self.body.recover(t);
                    self.plan = Plan::Idle;
                    // A strong boxer counters out of a slip, with the hand
                    // on the side it slipped to.
                    if p.attacks && kind == Evasion::Slip && rng.random::<f64>() < pers.counter {
                        let right = self.body.posture(t).waist.z > 0.0;
                        return self.start_attack(
                            (usize::from(right), false),
                            p,
                            pers,
                            view,
                            t,
                            rng,
                        );
                    }
                } else {
                    return strongest(
                        TopDown {
                            name: view.names[threat.index()].clone(),
                            body: Some(threat),
                            spot: Spot::Centre,
                            offset: DVec3::ZERO,
                            amount: pers.a_guard,
                        },
                        face,
                    );
                }
            }
            Plan::Guard {
                threat,
                hand,
                until,
                ..
            } => {
                if t >= until {
                    let from = self.glove(hand, t);
                    self.reaches[hand] = Some(Reach {
                        from,
                        to: self.guard(hand),
                        t0: t,
                        dur: 0.3,
                        back: false,
                    });
                    self.plan = Plan::Idle;
                } else {
                    // gaze.md 5: guard looks at the incoming glove.
                    return strongest(
                        TopDown {
                            name: view.names[threat.index()].clone(),
                            body: Some(threat),
                            spot: Spot::Centre,
                            offset: DVec3::ZERO,
                            amount: pers.a_guard,
                        },
                        face,
                    );
                }
            }
            Plan::Attack {
                hand,
                target,
                decided,
                mut looked,
                thrown,
            } => {
                if looked.is_none()
                    && view
                        .eyes_on
                        .is_some_and(|on| target.aims_at(on.body, on.spot))
                {
                    looked = Some(t);
                }
                // "Looks at the target at once, and after 200 ms throws the
                // punch" (boxing.md): timed from when the eyes land, with a
                // deadline in case they never do (a distraction won).
                let punch_at = looked.map_or(decided + p.punch_delay + 0.3, |l| l + p.punch_delay);
                if let Plan::Attack { looked: l, .. } = &mut self.plan {
                    *l = looked;
                }
                if !thrown && t >= punch_at {
                    match self.punch_reach(hand, &target, view, t, p) {
                        Some(r) => {
                            self.lunge = self.lunge_for(hand, r.to, t, p);
                            self.body.punch(hand, t, p.punch_time);
                            self.reaches[hand] = Some(r);
                            self.punches_thrown += 1;
                            self.plan = Plan::Attack {
                                hand,
                                target: target.clone(),
                                decided,
                                looked,
                                thrown: true,
                            };
                        }
                        // The target went out of view: call the attack off.
                        None => self.plan = Plan::Idle,
                    }
                } else if thrown && self.reaches[hand].is_none() {
                    self.body.recover(t);
                    self.plan = Plan::Idle;
                }
                if self.plan != Plan::Idle {
                    return strongest(target, face);
                }
            }
            Plan::Idle => {}
        }
        // Idle: maybe decide to attack (Poisson decision).
        let free = self.reaches.iter().all(Option::is_none);
        if p.attacks
            && free
            && rng.random::<f64>() < crate::util::math::poisson_step(p.attack_rate, dt)
        {
            let hand = usize::from(rng.random::<f64>() >= p.jab_share);
            let to_body = rng.random::<f64>() < p.body_shot_share;
            return self.start_attack((hand, to_body), p, pers, view, t, rng);
        }
        face
    }

    /// Decide to punch with glove `hand` at the opponent's head or body
    /// (`to_body`), with the aim's random spread; the eyes go to the target
    /// first.
    fn start_attack(
        &mut self,
        (hand, to_body): (usize, bool),
        p: &BehaviourParams,
        pers: &Personality,
        view: &OpponentView,
        t: f64,
        rng: &mut impl Rng,
    ) -> TopDown {
        let n = Normal::new(0.0, p.target_spread.max(1e-12)).expect("valid sd");
        let offset = DVec3::new(n.sample(rng), n.sample(rng), 0.0);
        let target = if to_body {
            TopDown {
                name: "opponent_body".into(),
                body: Some(view.parts[0]),
                spot: Spot::Trunk,
                offset: DVec3::new(0.0, -0.35, 0.05) + offset,
                amount: pers.a_attack,
            }
        } else {
            TopDown {
                name: "head".into(),
                body: Some(view.parts[0]),
                spot: Spot::Centre,
                offset,
                amount: pers.a_attack,
            }
        };
        self.plan = Plan::Attack {
            hand,
            target: target.clone(),
            decided: t,
            looked: None,
            thrown: false,
        };
        let face = TopDown {
            name: "head".into(),
            body: Some(view.parts[0]),
            spot: Spot::Centre,
            offset: DVec3::ZERO,
            amount: pers.a_face,
        };
        strongest(target, face)
    }

    fn punch_reach(
        &self,
        hand: usize,
        target: &TopDown,
        view: &OpponentView,
        t: f64,
        p: &BehaviourParams,
    ) -> Option<Reach> {
        let base = view
            .seen
            .iter()
            .find(|s| Some(s.body) == target.body)
            .map(|s| s.position)?;
        Some(Reach {
            from: self.glove(hand, t),
            to: base + target.offset,
            t0: t,
            dur: p.punch_time,
            back: true,
        })
    }

    /// The lunge a punch at `to` with glove `hand` needs: the part of the
    /// shoulder-to-target distance beyond the straight arm (less 5 %),
    /// horizontally toward the target, at most `max_lunge`.
    fn lunge_for(&self, hand: usize, to: DVec3, t: f64, p: &BehaviourParams) -> Option<Reach> {
        use crate::anatomy::arm;
        // Where the shoulder is now: the body may have stepped and turned.
        let shoulder = self.body.on_trunk(DVec3::from_array(arm::shoulder(hand)));
        let reach = 0.95 * (arm::UPPER + arm::FOREARM);
        let len = ((to - shoulder).length() - reach).clamp(0.0, p.max_lunge);
        let dir = DVec3::new(to.x - shoulder.x, 0.0, to.z - shoulder.z).normalize_or_zero();
        (len > 0.0).then(|| Reach {
            from: DVec3::ZERO,
            to: dir * len,
            t0: t,
            dur: p.punch_time,
            back: true,
        })
    }

    /// The body's planned posture at `t`: footwork, evasions, the trunk's
    /// turn in a punch (the lunge is [`Behaviour::torso_offset`]).
    pub fn posture(&self, t: f64) -> Posture {
        self.body.posture(t)
    }

    /// Tell the planner where the trunk is (the waist joint's offset from
    /// rest, the trunk's rotation): the guard's stance rides on it.
    pub fn set_trunk(&mut self, offset: DVec3, rotation: DQuat) {
        self.body.trunk = (offset, rotation);
    }

    /// Footwork steps started.
    pub fn footwork_steps(&self) -> u32 {
        self.body.steps
    }

    /// Where the torso is stepped to now (offset from its rest position).
    pub fn torso_offset(&self, t: f64) -> DVec3 {
        self.lunge.as_ref().map_or(DVec3::ZERO, |r| r.at(t))
    }

    /// Desired world positions of the VH's left and right gloves now.
    pub fn glove_targets(&self, t: f64) -> [DVec3; 2] {
        [self.glove(0, t), self.glove(1, t)]
    }
}

/// A punch at the head seen starting: the opponent glove closing fastest
/// on the VH's head, faster than `evade_speed`, on a path that passes
/// within 15 cm of it.
pub fn glove_onset<'a>(p: &BehaviourParams, view: &OpponentView<'a>) -> Option<&'a Seen> {
    let head = view.vh_points[0];
    view.seen
        .iter()
        .filter(|s| s.body == view.parts[1] || s.body == view.parts[2])
        .filter_map(|s| {
            let to = head - s.position;
            let dir = to.normalize_or_zero();
            let closing = s.velocity.dot(dir);
            let heading = s.velocity.normalize_or_zero();
            let miss = (to - to.dot(heading) * heading).length();
            (closing > p.evade_speed && miss < 0.15).then_some((s, closing))
        })
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(s, _)| s)
}

/// The aimed-glove test (boxing.md, Guard): the fastest opponent glove that
/// is seen, faster than `guard_speed`, heading within `guard_angle_deg` of
/// the VH's head, torso or centre of mass, with time to contact under
/// `guard_ttc`. Returns (body, interception point at 0.4 ttc, ttc).
pub fn aimed_glove(p: &BehaviourParams, view: &OpponentView) -> Option<(BodyId, DVec3, f64)> {
    let cos_max = p.guard_angle_deg.to_radians().cos();
    let mut best: Option<(BodyId, DVec3, f64)> = None;
    for s in view.seen {
        if s.body != view.parts[1] && s.body != view.parts[2] {
            continue;
        }
        let speed = s.velocity.length();
        if speed <= p.guard_speed {
            continue;
        }
        let heading = s.velocity / speed;
        for aim in view.vh_points {
            let to = aim - s.position;
            let dist = to.length();
            if dist < 1e-9 || heading.dot(to / dist) < cos_max {
                continue;
            }
            let ttc = dist / speed;
            if ttc < p.guard_ttc && best.as_ref().is_none_or(|b| ttc < b.2) {
                best = Some((s.body, s.position + s.velocity * (0.4 * ttc), ttc));
            }
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    fn seen(body: usize, position: DVec3, velocity: DVec3) -> Seen {
        Seen {
            body: BodyId::new(body),
            position,
            velocity,
            ..Seen::test_default()
        }
    }

    #[test]
    fn aimed_glove_test_follows_the_three_rules() {
        let p = BehaviourParams::default();
        let head = DVec3::new(0.0, 1.68, 0.0);
        let vh_points = [head, DVec3::new(0.0, 1.25, 0.0), DVec3::new(0.0, 1.4, 0.0)];
        let glove = DVec3::new(-0.1, 1.6, 0.7);
        let towards = (head - glove).normalize();
        let check = |v: DVec3| {
            let s = [seen(5, glove, v)];
            let names: Vec<String> = (0..7).map(|i| format!("b{i}")).collect();
            let view = OpponentView {
                seen: &s,
                names: &names,
                eyes_on: None,
                parts: [4, 5, 6].map(BodyId::new),
                vh_points,
            };
            aimed_glove(&p, &view)
        };
        assert!(check(towards * 4.0).is_some(), "fast and aimed");
        assert!(check(towards * 1.5).is_none(), "too slow");
        let sideways = DVec3::new(1.0, 0.0, -0.3).normalize() * 4.0;
        assert!(check(sideways).is_none(), "not aimed");
        // 0.7 m at 1.2 m/s... slow; at 2.1 m/s ttc = 0.34 s < 0.5: aimed
        assert!(check(towards * 2.1).is_some());
        let (_, point, ttc) = check(towards * 4.0).unwrap();
        assert!((point - (glove + towards * 4.0 * 0.4 * ttc)).length() < 1e-9);
    }
}
