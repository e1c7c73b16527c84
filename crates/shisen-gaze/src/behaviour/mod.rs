//! The action plan (boxing.md): guard, evade, attack, idle. It decides
//! what the VH wants to look at (the top-down request, gaze.md 5), where its
//! gloves go (minimum-jerk reaches, tracked through the arm joints by the
//! body plan's inverse kinematics) and, in [`body`], how its body moves:
//! evasions, footwork, the trunk's turn in a punch.

mod agent;
mod body;
mod params;
mod plan;
mod range;
mod reach;
#[cfg(test)]
mod tests;
mod threat;

use glam::{DQuat, DVec3};
use rand::Rng;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::personality::Personality;
use crate::target::{BodyId, Spot, TargetId};
use crate::vision::Seen;
pub use agent::{Command, Control, Look};
use body::BodyPlan;
pub use body::{Evasion, Posture, choose_evasion};
pub use params::BehaviourParams;
use plan::{Combo, Plan};
pub use range::{AIM_DEPTH, CONTACT, Ranges, STEP_IN, Zone};
use reach::Reach;
pub use threat::{aimed_glove, body_cue, glove_onset};

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
    /// The start of a punch without the punch, to draw a reaction.
    Feint,
}

impl ActionKind {
    /// Whether the action meets a seen punch (a guard or an evasion).
    pub fn defends(self) -> bool {
        !matches!(
            self,
            ActionKind::Idle | ActionKind::Attack | ActionKind::Feint
        )
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

/// How far the gloves come down between rounds, m (arms hanging).
const REST_DROP: f64 = 0.3;
/// How fast the guard's height changes, m/s.
const DROP_RATE: f64 = 0.5;

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

/// The planner's evolving state.
#[derive(Clone, Debug)]
pub struct Behaviour {
    plan: Plan,
    reaches: [Option<Reach>; 2],
    /// The torso's travel into each glove's punch (an offset from rest,
    /// out and back with the punch): the trunk rides on their sum, so in
    /// a combination the next punch's shoulder goes forward as the one
    /// before comes back.
    lunge: [Option<Reach>; 2],
    /// Guard-stance glove positions (world), left and right.
    stance: [DVec3; 2],
    /// The body's plan: evasions, footwork, the trunk's turn.
    body: BodyPlan,
    /// Punches the VH has thrown.
    pub punches_thrown: u32,
    /// Evasions the VH has started.
    pub evasions: u32,
    /// Feints the VH has made.
    pub feints: u32,
    /// The glove whose punch was last weighed for an evasion.
    considered: Option<BodyId>,
    /// How far the guard sits below its stance now, m.
    drop: f64,
    /// Between rounds: the corner to stand in and the point to face.
    corner: Option<(DVec3, DVec3)>,
    /// Staggered by a blow (neither attacking nor defending) until, s.
    staggered_until: f64,
    /// Who decides: the planner or an outside agent ([`agent`]).
    control: Control,
    /// The agent's pending decision.
    command: Command,
    /// Where the agent asks the gaze to go.
    look: Look,
    /// The punches still to come in the combination under way.
    combo: Combo,
    /// When the step into the attack under way lands, s.
    lands: f64,
    /// Whether that step brings the target within reach (the punch is
    /// timed to land with the foot) or only nearer.
    timed: bool,
    /// The body cue in view has been weighed (once per cue).
    cued: bool,
    /// Body cues the VH acted on.
    pub cue_reads: u32,
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
            lunge: [None, None],
            stance: [DVec3::new(0.11, 1.56, 0.27), DVec3::new(-0.11, 1.56, 0.27)],
            body: BodyPlan::default(),
            punches_thrown: 0,
            evasions: 0,
            considered: None,
            drop: 0.0,
            corner: None,
            staggered_until: f64::NEG_INFINITY,
            control: Control::Own,
            command: Command::Nothing,
            look: Look::Own,
            combo: Combo::default(),
            lands: f64::NEG_INFINITY,
            timed: false,
            cued: false,
            cue_reads: 0,
            feints: 0,
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

    /// Staggered by a blow at `t` until `until`: its actions called off,
    /// and, given `from` (the opponent), a planned step of ground away
    /// from it (a physical body gives ground by the blow itself).
    pub fn stagger(&mut self, p: &BehaviourParams, from: Option<DVec3>, t: f64, until: f64) {
        self.plan = Plan::Idle;
        if let Some(from) = from {
            self.body.give_ground(p, from, t);
        }
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
            Plan::Feint { .. } => ActionKind::Feint,
        }
    }

    /// What the current action is about: the attack target or the
    /// incoming glove (body name or point name); `None` while idle.
    pub fn target_name<'a>(&'a self, names: &'a [String]) -> Option<&'a str> {
        match &self.plan {
            Plan::Idle => None,
            Plan::Guard { threat, .. } | Plan::Evade { threat, .. } => Some(&names[threat.index()]),
            Plan::Attack { target, .. } => Some(&target.name),
            Plan::Feint { .. } => Some("head"),
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
        for r in self.reaches.iter_mut().chain(self.lunge.iter_mut()) {
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
            self.command = Command::Nothing;
            return face;
        }
        // An attack owns the feet from its decision (its steps in, its
        // punches); then the range again (stepping out).
        let attacking = matches!(self.plan, Plan::Attack { .. });
        if !attacking {
            self.body.keep_range(p, opponent_head, t);
        }
        let own = self.control == Control::Own;
        if own {
            self.read_cue(p, pers, view, t, rng);
            self.consider_evasion(p, pers, view, opponent_head, t, rng);
            self.meet_threat(p, view, t);
        } else {
            self.obey(p, pers, view, t, rng);
        }
        // The plan under way: the action's request, or `None` once it is
        // over; then, idle, maybe an attack.
        let request = match self.plan.clone() {
            Plan::Evade { kind, until, .. } => self.evading((kind, until), p, pers, view, t, rng),
            Plan::Guard {
                threat,
                hand,
                until,
                ..
            } => self.guarding((threat, hand, until), p, pers, view, t, rng),
            Plan::Attack {
                hand,
                target,
                decided,
                looked,
                thrown,
            } => self.attacking(
                (hand, target, decided, looked, thrown),
                p,
                pers,
                view,
                t,
                rng,
            ),
            Plan::Feint { hand, until } => self.feinting((hand, until), p, pers, view, t, rng),
            Plan::Idle => None,
        };
        let request = if own {
            request.or_else(|| self.idle(p, pers, view, t, dt, rng))
        } else {
            request
        };
        if let Some(look) = self.agent_look(pers, view) {
            return look;
        }
        match request {
            Some(request) => strongest(request, face),
            None => face,
        }
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

    /// Plan the feet from where the body's pelvis is (`pelvis`, a ground
    /// point) at `t`, unless a footwork step is under way: a physical
    /// body that a blow moved, or that fell and got up, fights on from
    /// where it stands.
    pub fn place(&mut self, pelvis: DVec3, t: f64) {
        self.body.place(pelvis, t);
    }

    /// Footwork steps started.
    pub fn footwork_steps(&self) -> u32 {
        self.body.steps
    }

    /// Where the torso is stepped to now (offset from its rest position).
    pub fn torso_offset(&self, t: f64) -> DVec3 {
        self.lunge.iter().flatten().map(|r| r.at(t)).sum()
    }

    /// Desired world positions of the VH's left and right gloves now.
    pub fn glove_targets(&self, t: f64) -> [DVec3; 2] {
        [self.glove(0, t), self.glove(1, t)]
    }
}
