//! The plan under way (idle, guard, evade, attack) and what each of its
//! arms does in a tick, as [`Behaviour`]'s methods: the evasion weighed
//! when a punch starts, the guard raised against an aimed glove, the
//! attack decided, looked at, thrown.

use glam::DVec3;
use rand::{Rng, RngExt};
use rand_distr::{Distribution, Normal};

use super::reach::Reach;
use super::threat::{aimed_glove, glove_onset};
use super::{
    AIM_DEPTH, Behaviour, BehaviourParams, CONTACT, Evasion, OpponentView, TopDown, choose_evasion,
};
use crate::anatomy::arm;
use crate::personality::Personality;
use crate::target::{BodyId, Spot};
use crate::vision::Seen;

/// The action under way, with what it needs to go on.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Plan {
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
    Feint {
        hand: usize,
        until: f64,
    },
}

/// The punches still to come in a combination, in order: (glove, at the
/// body).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct Combo {
    queue: [(usize, bool); 2],
    len: usize,
}

impl Combo {
    /// The follow-ups of an attack opening with `first`: after each punch,
    /// one more with chance `p.combination`, three punches at most. After
    /// a jab, the cross (or a second jab, one time in four); after the rear
    /// hand, the lead hook; after a body shot, the head (boxing's 1-1, 1-2,
    /// 1-2-3, body-head).
    fn after(first: (usize, bool), p: &BehaviourParams, rng: &mut impl Rng) -> Combo {
        let mut c = Combo::default();
        let mut last = first;
        // No draw at all when combinations are off: the seed's random
        // stream, and so its traces, stay as they were.
        while p.combination > 0.0 && c.len < c.queue.len() && rng.random::<f64>() < p.combination {
            let hand = if last.0 == 0 && rng.random::<f64>() >= 0.25 {
                1
            } else {
                0
            };
            let body = !last.1 && rng.random::<f64>() < 0.5 * p.body_shot_share;
            last = (hand, body);
            c.queue[c.len] = last;
            c.len += 1;
        }
        c
    }

    fn peek(&self) -> Option<(usize, bool)> {
        (self.len > 0).then_some(self.queue[0])
    }

    fn pop(&mut self) {
        if self.len > 0 {
            self.queue.rotate_left(1);
            self.len -= 1;
        }
    }
}

/// How long after its decision an attack waits for its first punch to
/// come within reach (a step in and the eyes' landing take about 0.6 s),
/// s; then it is given up.
const PATIENCE: f64 = 1.5;

/// How long a combination's punches take after the first, at most, s
/// (three punches half a punch apart, and a step in).
const COMBO_TIME: f64 = 1.0;

/// Where on the opponent a punch at the head or body (`to_body`) aims,
/// from the head's centre, before the aim's random spread: the body shot
/// at the chest under the head.
fn aim_offset(to_body: bool) -> DVec3 {
    if to_body {
        DVec3::new(0.0, -0.35, 0.05)
    } else {
        DVec3::ZERO
    }
}

/// A feint's glove twitch toward the target, m: the start of a punch
/// (the user's feint twitches 5 cm; sim/punch.rs).
const FEINT_GLOVE: f64 = 0.08;

/// A feint's shoulder travel toward the target, m: the trunk's first
/// tenth of a second of a punch's lunge.
const FEINT_LUNGE: f64 = 0.08;

/// A feint out and back, s (a punch's first half is about a quarter of a
/// second).
const FEINT_TIME: f64 = 0.3;

/// The gaze on the incoming glove `threat` (guard and evasion).
fn on_threat(threat: BodyId, view: &OpponentView, pers: &Personality) -> TopDown {
    TopDown {
        name: view.names[threat.index()].clone(),
        body: Some(threat),
        spot: Spot::Centre,
        offset: DVec3::ZERO,
        amount: pers.a_guard,
    }
}

impl Behaviour {
    /// A punch seen starting at the head may be evaded: decided once per
    /// punch, on its first sight, by the personality's share.
    pub(super) fn consider_evasion(
        &mut self,
        p: &BehaviourParams,
        pers: &Personality,
        view: &OpponentView,
        opponent_head: Option<&Seen>,
        t: f64,
        rng: &mut impl Rng,
    ) {
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
    }

    /// A body cue (the opponent's head stepping in) is weighed once: with
    /// the personality's `anticipation`, while idle or only deciding an
    /// attack, the guard goes up on the side the cue predicts (the rear
    /// hand's punch arrives on the VH's left) before a glove is seen and,
    /// from long range, the feet step back so a stepping punch falls
    /// short. A feint draws the same answer.
    pub(super) fn read_cue(
        &mut self,
        p: &BehaviourParams,
        pers: &Personality,
        view: &OpponentView,
        t: f64,
        rng: &mut impl Rng,
    ) {
        let Some((head, rear)) = super::body_cue(p, view) else {
            self.cued = false;
            return;
        };
        if self.cued {
            return;
        }
        self.cued = true;
        let free = matches!(self.plan, Plan::Idle | Plan::Attack { thrown: false, .. });
        if pers.anticipation <= 0.0 || !free || rng.random::<f64>() >= pers.anticipation {
            return;
        }
        self.cue_reads += 1;
        let (threat, hand) = if rear {
            (view.parts[2], 0)
        } else {
            (view.parts[1], 1)
        };
        let me = view.vh_points[0];
        let toward = DVec3::new(head.position.x - me.x, 0.0, head.position.z - me.z);
        let d = toward.length();
        let toward = toward.normalize_or_zero();
        // The VH's left is up x its forward.
        let side = DVec3::Y.cross(toward) * if hand == 0 { 1.0 } else { -1.0 };
        let point = me + toward * 0.25 + side * 0.08;
        self.raise_guard((threat, hand, point, 0.15), p, t);
        if d > super::Ranges::HUMAN.mid {
            self.body.step_in(p, head.position, -p.max_step, t);
        }
    }

    /// A threat seen now pre-empts everything but an evasion of it: the
    /// glove on its side goes to meet it.
    pub(super) fn meet_threat(&mut self, p: &BehaviourParams, view: &OpponentView, t: f64) {
        let Some((threat, point, ttc)) = aimed_glove(p, view) else {
            return;
        };
        // The VH's glove on the side the punch comes from (the opponent's
        // left glove arrives on the VH's right).
        let hand = if threat == view.parts[1] { 1 } else { 0 };
        let met = match self.plan {
            Plan::Guard { threat: th, .. } | Plan::Evade { threat: th, .. } => th == threat,
            _ => false,
        };
        if !met {
            self.raise_guard((threat, hand, point, (0.3 * ttc).max(0.05)), p, t);
        } else if matches!(self.plan, Plan::Guard { .. }) {
            self.plan = Plan::Guard {
                threat,
                hand,
                point,
                until: t + p.guard_hold,
            };
        }
    }

    /// Glove `hand` to `point` against `threat`, taking `dur` s once the
    /// reaction time is over (the reach holds its start point until then);
    /// an evasion under way is given up; held `guard_hold`.
    pub(super) fn raise_guard(
        &mut self,
        (threat, hand, point, dur): (BodyId, usize, DVec3, f64),
        p: &BehaviourParams,
        t: f64,
    ) {
        let from = self.glove(hand, t);
        self.reaches[hand] = Some(Reach {
            from,
            to: point,
            t0: t + p.guard_reaction,
            dur,
            back: false,
        });
        if let Plan::Evade { .. } = self.plan {
            self.body.recover(t);
        }
        self.plan = Plan::Guard {
            threat,
            hand,
            point,
            until: t + p.guard_hold,
        };
    }

    /// An evasion of `threat` of `kind` under way until `until`: the gaze
    /// is anchored on the opponent's head (`a_anchor`); once it is over,
    /// idle, or (a strong boxer) a counter out of a slip. The action's
    /// request; `None` once idle.
    pub(super) fn evading(
        &mut self,
        (kind, until): (Evasion, f64),
        p: &BehaviourParams,
        pers: &Personality,
        view: &OpponentView,
        t: f64,
        rng: &mut impl Rng,
    ) -> Option<TopDown> {
        if t >= until {
            let own = self.control == super::Control::Own;
            self.body.recover(t);
            self.plan = Plan::Idle;
            // A strong boxer counters out of a slip, with the hand on the
            // side it slipped to (the planner's decision: an agent in its
            // place decides its own counters).
            if own && p.attacks && kind == Evasion::Slip && rng.random::<f64>() < pers.counter {
                let right = self.body.posture(t).waist.z > 0.0;
                return Some(self.start_attack((usize::from(right), false), p, pers, view, t, rng));
            }
            None
        } else {
            // The visual anchor: the opponent's head; the evaded glove
            // competes bottom-up (a weak anchor lets the eyes chase it).
            let head = view.parts[0];
            Some(TopDown {
                name: view.names[head.index()].clone(),
                body: Some(head),
                spot: Spot::Centre,
                offset: DVec3::ZERO,
                amount: pers.a_anchor,
            })
        }
    }

    /// A guard against `threat` with glove `hand` held until `until`: the
    /// gaze on the incoming glove (gaze.md 5), then the glove back to its
    /// stance, and (a strong boxer, as out of a slip) a counter with the
    /// other hand while the opponent's glove is still on its way back: the
    /// block-and-counter. The action's request; `None` once idle.
    pub(super) fn guarding(
        &mut self,
        (threat, hand, until): (BodyId, usize, f64),
        p: &BehaviourParams,
        pers: &Personality,
        view: &OpponentView,
        t: f64,
        rng: &mut impl Rng,
    ) -> Option<TopDown> {
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
            let own = self.control == super::Control::Own;
            if own && p.attacks && rng.random::<f64>() < pers.counter {
                return Some(self.start_attack((1 - hand, false), p, pers, view, t, rng));
            }
            None
        } else {
            Some(on_threat(threat, view, pers))
        }
    }

    /// An attack with glove `hand` at `target`, decided at `decided`: the
    /// eyes go to the target, the punch follows, and the attack ends when
    /// the glove is back. The action's request (the target); `None` once
    /// idle.
    pub(super) fn attacking(
        &mut self,
        (hand, target, decided, mut looked, thrown): (usize, TopDown, f64, Option<f64>, bool),
        p: &BehaviourParams,
        pers: &Personality,
        view: &OpponentView,
        t: f64,
        rng: &mut impl Rng,
    ) -> Option<TopDown> {
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
        // A step in from long range: the punch lands as the foot does.
        let punch_at = looked
            .map_or(decided + p.punch_delay + 0.3, |l| l + p.punch_delay)
            .max(self.lands - 0.5 * p.punch_time);
        if let Plan::Attack { looked: l, .. } = &mut self.plan {
            *l = looked;
        }
        if !thrown && t >= punch_at {
            let to = self.punch_reach(hand, &target, view, t, p).map(|r| r.to);
            if to.is_none_or(|to| self.in_reach(hand, to, t, p)) {
                self.throw(hand, target.clone(), (decided, looked), view, t, p);
            } else if t > decided + PATIENCE {
                // The opponent stayed out of reach: no punch.
                self.combo = Combo::default();
                self.plan = Plan::Idle;
            }
        } else if thrown {
            // A combination: the next punch starts as the one before comes
            // back (the other hand), or once it is back (the same hand),
            // and once it can reach (the feet may step in first).
            let next = self.combo.peek().filter(|&(h, _)| {
                let back = self.reaches[hand]
                    .as_ref()
                    .is_none_or(|r| t >= r.t0 + 0.5 * r.dur);
                self.reaches[h].is_none() && back
            });
            let aim = |body: bool| {
                let head = view.seen.iter().find(|s| s.body == view.parts[0]);
                head.map(|s| s.position + aim_offset(body))
            };
            if let Some((h, body)) = next {
                if aim(body).is_none_or(|to| self.in_reach(h, to, t, p)) {
                    self.combo.pop();
                    let target = self.attack_target(body, p, pers, view, rng);
                    self.throw(h, target, (decided, looked), view, t, p);
                } else if t > decided + PATIENCE + COMBO_TIME {
                    self.combo = Combo::default();
                }
            } else if self.combo.peek().is_none() && self.reaches[hand].is_none() {
                self.body.recover(t);
                self.plan = Plan::Idle;
            }
        }
        match &self.plan {
            Plan::Attack { target, .. } => Some(target.clone()),
            _ => None,
        }
    }

    /// Throw glove `hand` at `target` now (the attack decided and looked
    /// at as `when` says), with the lunge the distance needs if that
    /// glove's trunk travel is not already under way; called off if the
    /// target is out of view.
    fn throw(
        &mut self,
        hand: usize,
        target: TopDown,
        (decided, looked): (f64, Option<f64>),
        view: &OpponentView,
        t: f64,
        p: &BehaviourParams,
    ) {
        match self.punch_reach(hand, &target, view, t, p) {
            Some(r) => {
                if self.lunge[hand].is_none() {
                    self.lunge[hand] = self.lunge_for(hand, r.to, t, p);
                }
                self.body.punch(hand, t, p.punch_time);
                self.reaches[hand] = Some(r);
                self.punches_thrown += 1;
                self.plan = Plan::Attack {
                    hand,
                    target,
                    decided,
                    looked,
                    thrown: true,
                };
            }
            // The target went out of view: call the attack off.
            None => {
                self.combo = Combo::default();
                self.plan = Plan::Idle;
            }
        }
    }

    /// Idle: maybe decide to attack (a Poisson decision while both gloves
    /// are free). The attack's request if one starts.
    pub(super) fn idle(
        &mut self,
        p: &BehaviourParams,
        pers: &Personality,
        view: &OpponentView,
        t: f64,
        dt: f64,
        rng: &mut impl Rng,
    ) -> Option<TopDown> {
        let free = self.reaches.iter().all(Option::is_none);
        if p.attacks
            && free
            && rng.random::<f64>() < crate::util::math::poisson_step(p.attack_rate, dt)
        {
            let hand = usize::from(rng.random::<f64>() >= p.jab_share);
            let to_body = rng.random::<f64>() < p.body_shot_share;
            // No draw without feints: the seed's random stream stays.
            if p.feint > 0.0 && rng.random::<f64>() < p.feint {
                return self.feint(hand, pers, view, t);
            }
            return Some(self.start_attack((hand, to_body), p, pers, view, t, rng));
        }
        None
    }

    /// A feint with glove `hand`: a punch's start without the punch (the
    /// eyes on the opponent's head, the glove and shoulder a few
    /// centimetres toward it, out and back), to draw a reaction to punch
    /// into. The request (the head); `None` with the head out of view.
    fn feint(
        &mut self,
        hand: usize,
        pers: &Personality,
        view: &OpponentView,
        t: f64,
    ) -> Option<TopDown> {
        let head = view.seen.iter().find(|s| s.body == view.parts[0])?;
        let from = self.glove(hand, t);
        let dir = (head.position - from).normalize_or_zero();
        self.reaches[hand] = Some(Reach {
            from,
            to: from + dir * FEINT_GLOVE,
            t0: t,
            dur: FEINT_TIME,
            back: true,
        });
        let flat = DVec3::new(dir.x, 0.0, dir.z).normalize_or_zero();
        self.lunge[hand] = Some(Reach {
            from: DVec3::ZERO,
            to: flat * FEINT_LUNGE,
            t0: t,
            dur: FEINT_TIME,
            back: true,
        });
        self.feints += 1;
        self.plan = Plan::Feint {
            hand,
            until: t + FEINT_TIME,
        };
        Some(self.on_head(pers, view))
    }

    /// The gaze on the opponent's head, as an attack's.
    fn on_head(&self, pers: &Personality, view: &OpponentView) -> TopDown {
        TopDown {
            name: "head".into(),
            body: Some(view.parts[0]),
            spot: Spot::Centre,
            offset: DVec3::ZERO,
            amount: pers.a_attack,
        }
    }

    /// A feint with glove `hand` under way until `until`: the eyes on the
    /// head; once it is over, idle or (with the chance of a combination's
    /// next punch) the real punch with the other hand, into the reaction
    /// it drew. The action's request; `None` once idle.
    pub(super) fn feinting(
        &mut self,
        (hand, until): (usize, f64),
        p: &BehaviourParams,
        pers: &Personality,
        view: &OpponentView,
        t: f64,
        rng: &mut impl Rng,
    ) -> Option<TopDown> {
        if t < until {
            return Some(self.on_head(pers, view));
        }
        self.plan = Plan::Idle;
        (p.attacks && rng.random::<f64>() < p.combination)
            .then(|| self.start_attack((1 - hand, false), p, pers, view, t, rng))
    }

    /// Decide to punch with glove `hand` at the opponent's head or body
    /// (`to_body`), with the aim's random spread, maybe as the first of a
    /// combination; from long range, with a step in. The eyes go to the
    /// target first. The attack's request (the target).
    pub(super) fn start_attack(
        &mut self,
        (hand, to_body): (usize, bool),
        p: &BehaviourParams,
        pers: &Personality,
        view: &OpponentView,
        t: f64,
        rng: &mut impl Rng,
    ) -> TopDown {
        let target = self.attack_target(to_body, p, pers, view, rng);
        self.combo = Combo::after((hand, to_body), p, rng);
        // What the punch needs beyond the lunge, the feet cover.
        self.lands = t;
        if let Some(r) = self.punch_reach(hand, &target, view, t, p) {
            let need = self.need(hand, r.to, t, p);
            if need > AIM_DEPTH {
                self.step_toward(r.to, need, t, p);
            }
        }
        self.plan = Plan::Attack {
            hand,
            target: target.clone(),
            decided: t,
            looked: None,
            thrown: false,
        };
        target
    }

    /// The point a punch at the opponent's head or body (`to_body`) aims
    /// at, with the aim's random spread.
    fn attack_target(
        &self,
        to_body: bool,
        p: &BehaviourParams,
        pers: &Personality,
        view: &OpponentView,
        rng: &mut impl Rng,
    ) -> TopDown {
        let n = Normal::new(0.0, p.target_spread.max(1e-12)).expect("valid sd");
        let offset = aim_offset(to_body) + DVec3::new(n.sample(rng), n.sample(rng), 0.0);
        let (name, spot) = if to_body {
            ("opponent_body", Spot::Trunk)
        } else {
            ("head", Spot::Centre)
        };
        TopDown {
            name: name.into(),
            body: Some(view.parts[0]),
            spot,
            offset,
            amount: pers.a_attack,
        }
    }

    /// How far glove `hand` falls short of `to` at `t` beyond what the
    /// trunk's lunge gives, m (the lunges under way not counted: the one
    /// before in a combination is on its way back). The glove lands a
    /// contact's width before the target's centre, aimed `AIM_DEPTH`
    /// deep: a punch that needs no more than `AIM_DEPTH` still touches.
    fn need(&self, hand: usize, to: DVec3, t: f64, p: &BehaviourParams) -> f64 {
        let short = self.shortfall(hand, to + self.torso_offset(t)).0;
        short - p.max_lunge - (CONTACT - AIM_DEPTH)
    }

    /// Step in toward `to` by `need` (a step at most): the feet belong to
    /// the attack until the foot lands (`lands`). A step that closes the
    /// gap times the punch to land with the foot (`timed`); a longer way
    /// is stepped first and looked at again. Whether a step was taken
    /// (none without footwork, as in the seed).
    fn step_toward(&mut self, to: DVec3, need: f64, t: f64, p: &BehaviourParams) -> bool {
        self.lands = self.body.step_in(p, to, need, t);
        self.timed = need <= p.max_step + AIM_DEPTH;
        self.lands > t
    }

    /// Whether glove `hand` can throw at `to` now: within reach with the
    /// trunk's lunge, or in the last half punch of a step in that brings
    /// it there. When it cannot and the feet are free, they step in
    /// ([`Behaviour::step_toward`]) and the punch waits; without footwork
    /// the punch goes regardless.
    fn in_reach(&mut self, hand: usize, to: DVec3, t: f64, p: &BehaviourParams) -> bool {
        if t < self.lands {
            return self.timed && t >= self.lands - 0.5 * p.punch_time;
        }
        let need = self.need(hand, to, t, p);
        if need <= AIM_DEPTH {
            return true;
        }
        !self.body.stepping(t) && !self.step_toward(to, need, t, p)
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

    /// How far glove `hand`'s straight arm (less 5 %) falls short of `to`
    /// from where its shoulder is now (the body may have stepped and
    /// turned), m, negative within reach; and that shoulder.
    fn shortfall(&self, hand: usize, to: DVec3) -> (f64, DVec3) {
        let shoulder = self.body.on_trunk(DVec3::from_array(arm::shoulder(hand)));
        let short = (to - shoulder).length() - 0.95 * (arm::UPPER + arm::FOREARM);
        (short, shoulder)
    }

    /// The lunge a punch at `to` with glove `hand` needs: the part of the
    /// shoulder-to-target distance beyond the straight arm (less 5 %),
    /// horizontally toward the target, at most `max_lunge`. Measured from
    /// the shoulder without the lunges under way: in a combination the
    /// punch before's travel is on its way back as this one's goes out.
    fn lunge_for(&self, hand: usize, to: DVec3, t: f64, p: &BehaviourParams) -> Option<Reach> {
        let (short, shoulder) = self.shortfall(hand, to + self.torso_offset(t));
        let len = short.clamp(0.0, p.max_lunge);
        let dir = DVec3::new(to.x - shoulder.x, 0.0, to.z - shoulder.z).normalize_or_zero();
        (len > 0.0).then(|| Reach {
            from: DVec3::ZERO,
            to: dir * len,
            t0: t,
            dur: p.punch_time,
            back: true,
        })
    }
}
