//! An outside agent in the planner's place: a learning controller (the
//! Python package's two-agent environment) takes over the VH's decisions,
//! and optionally where its action plan asks the gaze to go, while the rest
//! of the pipeline (the plan's execution: reaches, evasion postures,
//! footwork; attention, the gaze laws, the joints, the face) stays the
//! simulator's.
//!
//! What is taken over is what the planner itself decides (boxing.md): when
//! to attack and with which hand at which target (the Poisson decision and
//! the counter out of a slip), whether and how to evade a punch seen
//! starting, and which glove meets an aimed one. The agent's command is
//! carried out exactly as the planner's own decision would be: an attack
//! still looks at its target before the punch, an evasion still waits
//! `evade_reaction`, a guard's glove still moves after `guard_reaction`.

use glam::DVec3;
use rand::Rng;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::plan::Plan;
use super::threat::aimed_glove;
use super::{Behaviour, BehaviourParams, Evasion, OpponentView, TopDown};
use crate::personality::Personality;
use crate::target::{BodyId, Spot};

/// How much of the VH's planning an outside agent has taken over.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, Serialize, JsonSchema)]
pub enum Control {
    /// The planner decides everything (the seeds' VH; the default).
    #[default]
    Own,
    /// The agent's [`Command`]s decide attacks, evasions and guards; the
    /// planner no longer starts any of its own.
    Decisions,
    /// As `Decisions`, and the agent's [`Look`] is the action plan's
    /// top-down request (attention still weighs it against what draws the
    /// eye bottom-up, M1-M3).
    DecisionsAndGaze,
}

/// One decision of an outside agent, taken at the next tick if the VH is
/// free to act on it (not staggered, not between rounds; an attack only
/// while idle with both gloves home, an evasion not during another).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Command {
    /// Go on with what is under way.
    #[default]
    Nothing,
    /// Attack with glove `hand` (0 left, the lead; 1 right) at the
    /// opponent's head, or its body (`to_body`).
    Punch {
        /// 0 left (lead), 1 right (rear).
        hand: usize,
        /// At the body rather than the head.
        to_body: bool,
    },
    /// Raise glove `hand` to meet the opponent glove aimed at the VH if
    /// one is seen, else to cover the face on that side.
    Guard {
        /// 0 left, 1 right.
        hand: usize,
    },
    /// Evade: slip (to the right if `right`), duck or lean back.
    Evade {
        /// Which evasion.
        kind: Evasion,
        /// A slip's side (the VH's right).
        right: bool,
    },
}

/// Where the agent asks the gaze to go (with [`Control::DecisionsAndGaze`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Look {
    /// Where the planner would ask.
    #[default]
    Own,
    /// The opponent's head.
    Head,
    /// The opponent's left glove.
    LeftGlove,
    /// The opponent's right glove.
    RightGlove,
    /// The opponent's body (upper chest, below the head).
    Body,
}

/// How far in front of the face a covering glove goes, m (a high guard:
/// the glove a fist's width before the cheek).
const COVER_AHEAD: f64 = 0.18;
/// How long a guard's glove takes to get there when no glove is aimed, s
/// (as the planner's guard against a glove a third of a second away).
const COVER_TIME: f64 = 0.1;

impl Behaviour {
    /// Hand the decisions over to an outside agent (or take them back with
    /// [`Control::Own`]). What is under way runs its course.
    pub fn take_over(&mut self, control: Control) {
        self.control = control;
        if control == Control::Own {
            self.command = Command::Nothing;
            self.look = Look::Own;
        }
    }

    /// Who decides now.
    pub fn control(&self) -> Control {
        self.control
    }

    /// The agent's decision for the next tick and where it asks the gaze
    /// to go (kept until changed). Ignored while the planner decides.
    pub fn command(&mut self, command: Command, look: Look) {
        if self.control != Control::Own {
            self.command = command;
            self.look = look;
        }
    }

    /// Carry out the agent's pending command (taken once).
    pub(super) fn obey(
        &mut self,
        p: &BehaviourParams,
        pers: &Personality,
        view: &OpponentView,
        t: f64,
        rng: &mut impl Rng,
    ) {
        match std::mem::take(&mut self.command) {
            Command::Nothing => {}
            Command::Punch { hand, to_body } => {
                let free = self.reaches.iter().all(Option::is_none);
                if matches!(self.plan, Plan::Idle) && free {
                    self.start_attack((hand.min(1), to_body), p, pers, view, t, rng);
                }
            }
            Command::Guard { hand } => self.guard_with(hand.min(1), p, view, t),
            Command::Evade { kind, right } => {
                if !matches!(
                    self.plan,
                    Plan::Evade { .. } | Plan::Attack { thrown: true, .. }
                ) {
                    self.body.evade(kind, right, t, p);
                    self.evasions += 1;
                    self.plan = Plan::Evade {
                        threat: nearest_glove(view),
                        kind,
                        until: t + p.evade_reaction + p.evade_time + p.evade_hold,
                    };
                }
            }
        }
    }

    /// Glove `hand` to meet the aimed glove, or to cover the face.
    fn guard_with(&mut self, hand: usize, p: &BehaviourParams, view: &OpponentView, t: f64) {
        if matches!(self.plan, Plan::Attack { thrown: true, .. }) {
            return;
        }
        let head = view.vh_points[0];
        let (threat, point, dur) = match aimed_glove(p, view) {
            Some((threat, point, ttc)) => (threat, point, (0.3 * ttc).max(0.05)),
            None => {
                let toward =
                    view.seen
                        .iter()
                        .find(|s| s.body == view.parts[0])
                        .map_or(DVec3::Z, |s| {
                            DVec3::new(s.position.x - head.x, 0.0, s.position.z - head.z)
                                .normalize_or(DVec3::Z)
                        });
                // The VH's left is +x when it faces +z; a glove covers its
                // own side of the face.
                let side = toward.cross(DVec3::Y).normalize_or_zero()
                    * if hand == 0 { -0.07 } else { 0.07 };
                let threat = view.parts[2 - hand];
                (threat, head + toward * COVER_AHEAD + side, COVER_TIME)
            }
        };
        self.raise_guard((threat, hand, point, dur), p, t);
    }

    /// The agent's gaze request, if it asks for one.
    pub(super) fn agent_look(&self, pers: &Personality, view: &OpponentView) -> Option<TopDown> {
        if self.control != Control::DecisionsAndGaze {
            return None;
        }
        let head = view.parts[0];
        let (body, spot, offset) = match self.look {
            Look::Own => return None,
            Look::Head => (head, Spot::Centre, DVec3::ZERO),
            Look::LeftGlove => (view.parts[1], Spot::Centre, DVec3::ZERO),
            Look::RightGlove => (view.parts[2], Spot::Centre, DVec3::ZERO),
            Look::Body => (head, Spot::Trunk, DVec3::new(0.0, -0.35, 0.05)),
        };
        let name = if self.look == Look::Body {
            "opponent_body".to_string()
        } else {
            view.names[body.index()].clone()
        };
        Some(TopDown {
            name,
            body: Some(body),
            spot,
            offset,
            amount: pers.a_attack,
        })
    }
}

/// The opponent glove nearest the VH's head (seen or not: the evasion's
/// record of what it meets; the plan's threat).
fn nearest_glove(view: &OpponentView) -> BodyId {
    let head = view.vh_points[0];
    let dist = |b: BodyId| {
        view.seen
            .iter()
            .find(|s| s.body == b)
            .map_or(f64::INFINITY, |s| s.position.distance(head))
    };
    if dist(view.parts[2]) < dist(view.parts[1]) {
        view.parts[2]
    } else {
        view.parts[1]
    }
}

#[cfg(test)]
mod tests {
    use rand::SeedableRng;
    use rand::rngs::StdRng;

    use super::*;
    use crate::behaviour::ActionKind;
    use crate::vision::Seen;

    /// The opponent 1.2 m in front (+z), its head and two gloves seen
    /// still; the VH's head at the origin's height.
    fn scene() -> (Vec<Seen>, Vec<String>) {
        let at = |body: usize, position: DVec3| Seen {
            body: BodyId::new(body),
            position,
            ..Seen::test_default()
        };
        let seen = vec![
            at(4, DVec3::new(0.0, 1.68, 0.8)),
            at(5, DVec3::new(0.12, 1.5, 0.9)),
            at(6, DVec3::new(-0.12, 1.5, 0.9)),
        ];
        let names = (0..7).map(|i| format!("b{i}")).collect();
        (seen, names)
    }

    /// Run `secs` of the plan at 1 kHz, giving `command` at `at` s.
    fn run(control: Control, command: Command, look: Look, at: f64, secs: f64) -> Behaviour {
        run_asking(control, command, look, at, secs).0
    }

    /// As [`run`], with the last tick's gaze request.
    fn run_asking(
        control: Control,
        command: Command,
        look: Look,
        at: f64,
        secs: f64,
    ) -> (Behaviour, TopDown) {
        let (seen, names) = scene();
        let view = OpponentView {
            seen: &seen,
            names: &names,
            eyes_on: None,
            parts: [4, 5, 6].map(BodyId::new),
            vh_points: [
                DVec3::new(0.0, 1.68, 0.0),
                DVec3::new(0.0, 1.25, 0.0),
                DVec3::new(0.0, 1.4, 0.0),
            ],
        };
        // An eager attacker: on its own it would attack about five times
        // a second.
        let p = BehaviourParams {
            attack_rate: 5.0,
            ..BehaviourParams::default()
        };
        let pers = Personality::default();
        let mut b = Behaviour::new();
        b.take_over(control);
        let mut rng = StdRng::seed_from_u64(3);
        let dt = 0.001;
        let mut last = None;
        for i in 0..(secs / dt) as usize {
            let t = i as f64 * dt;
            if (t - at).abs() < dt / 2.0 {
                b.command(command, look);
            }
            last = Some(b.step(&p, &pers, &view, t, dt, &mut rng));
        }
        (b, last.expect("at least one tick"))
    }

    #[test]
    fn the_planner_attacks_on_its_own_but_not_under_an_agent() {
        let own = run(Control::Own, Command::Nothing, Look::Own, 0.0, 3.0);
        assert!(own.punches_thrown >= 3, "{}", own.punches_thrown);
        let agent = run(Control::Decisions, Command::Nothing, Look::Own, 0.0, 3.0);
        assert_eq!(agent.punches_thrown, 0);
        assert_eq!(agent.evasions, 0);
    }

    #[test]
    fn an_agent_s_punch_is_looked_at_then_thrown_with_its_hand() {
        let punch = Command::Punch {
            hand: 1,
            to_body: false,
        };
        // Just decided: attacking, not yet thrown (the eyes go first).
        let b = run(Control::Decisions, punch, Look::Own, 0.1, 0.15);
        assert_eq!(b.action(), ActionKind::Attack);
        assert_eq!(b.attack_hand(), Some(1));
        assert_eq!(b.punches_thrown, 0);
        let b = run(Control::Decisions, punch, Look::Own, 0.1, 1.0);
        assert_eq!(b.punches_thrown, 1);
    }

    #[test]
    fn an_agent_s_evasion_and_guard_are_carried_out() {
        let slip = Command::Evade {
            kind: Evasion::Slip,
            right: true,
        };
        let b = run(Control::Decisions, slip, Look::Own, 0.1, 0.2);
        assert_eq!(b.action(), ActionKind::Slip);
        assert_eq!(b.evasions, 1);
        let b = run(
            Control::Decisions,
            Command::Guard { hand: 0 },
            Look::Own,
            0.1,
            0.3,
        );
        assert_eq!(b.action(), ActionKind::Guard);
        // The left glove has gone up in front of the face, on its side.
        let g = b.glove_targets(0.3)[0];
        assert!(g.z > 0.1 && g.x > 0.0 && (g.y - 1.68).abs() < 0.05, "{g}");
    }

    #[test]
    fn the_gaze_request_is_the_agent_s_only_when_it_has_the_gaze() {
        let look = Look::RightGlove;
        let (_, asked) = run_asking(Control::DecisionsAndGaze, Command::Nothing, look, 0.0, 0.1);
        assert_eq!(asked.body, Some(BodyId::new(6)));
        let (_, asked) = run_asking(Control::Decisions, Command::Nothing, look, 0.0, 0.1);
        assert_eq!(asked.body, Some(BodyId::new(4)));
        // Taken back: the planner attacks again.
        let mut b = run(Control::Decisions, Command::Nothing, look, 0.0, 0.1);
        b.take_over(Control::Own);
        assert_eq!(b.control(), Control::Own);
    }
}
