//! Effort over a bout (scene `vh.effort`): stamina spent by punching,
//! evading and the work of a round, recovered at the rest; damage
//! accumulated from blows taken, which a bout does not recover from; and
//! what the two do to the fighter (E1-E3 in docs/model/effort.md).
//!
//! - **E1, fatigue**: `f = clamp((1 - stamina) + damage_weight * damage, 0, 1)`.
//! - **E2, what fatigue changes**, each linear in `f` up to its value at
//!   `f = 1`: the attack rate falls, punches slow, the guard drops, guard
//!   and evasion reactions lengthen, saccades' peak velocity falls.
//! - **E3, breathing**: the rate follows effort from rest to exertion;
//!   the face shows the strain (brow lowered, AU 4) and breathes through
//!   the open mouth (AU 26) with each breath.
//!
//! A head blow of `stagger_impulse` or more staggers the VH: it gives
//! ground, and neither attacks nor defends, for `stagger_time`.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use shisen_face::emotion::AuLevels;
use shisen_face::tables::ActionUnit;
use shisen_gaze::behaviour::BehaviourParams;
use shisen_gaze::oculomotor::OculomotorParams;

/// How effort builds, recovers and shows (scene `vh.effort`).
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize, JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct EffortParams {
    /// Whether effort is followed at all (default true; `profile: Seed`
    /// turns it off).
    pub on: bool,
    /// Stamina a punch thrown costs (of 1). Our choice: 0.004, so a pro's
    /// 55.6 punches a round (CompuBox averages, all weight classes) cost
    /// 0.22 of it, and three busy rounds with their rests leave a boxer
    /// visibly tired. 0-1: at most, one punch spends all of it.
    #[schemars(range(min = 0.0, max = 1.0))]
    pub punch_cost: f64,
    /// Stamina an evasion costs (of 1); our choice, half a punch's
    /// (0.002). 0-1, as a punch's.
    #[schemars(range(min = 0.0, max = 1.0))]
    pub evade_cost: f64,
    /// Stamina spent per second of a round by moving and holding the
    /// guard, 1/s; our choice (0.1 over a 3-min round). 0-0.1: at most
    /// the whole of it in 10 s.
    #[schemars(range(min = 0.0, max = 0.1))]
    pub round_drain: f64,
    /// Time constant of stamina's recovery in the rest, s. Oxygen uptake
    /// falls half way back in 0.64 min after a 3-min all-out effort
    /// (a half time of 38 s, a time constant of 55 s). 1-100000 s (from
    /// a second to more than a day: no recovery).
    #[schemars(range(min = 1.0, max = 100_000.0))]
    pub rest_recovery: f64,
    /// Time constant of stamina's recovery while fighting, s (slow: the
    /// work goes on); our choice, 600 s. 1-100000 s, as at the rest.
    #[schemars(range(min = 1.0, max = 100_000.0))]
    pub round_recovery: f64,
    /// Damage a blow to the head adds per N s of impulse (of 1); blows to
    /// the body count half. Our choice: ten clean 15 N s head shots (the
    /// jab of scenes/jab_snaps_head.ron) give 0.45. 0-1 per N s: at most
    /// one 1 N s touch does all the damage a bout can do.
    #[schemars(range(min = 0.0, max = 1.0))]
    pub damage_per_impulse: f64,
    /// How much damage weighs in fatigue (E1), a factor (default 0.5).
    /// 0-2: at 2, half the damage a bout can do exhausts the VH.
    #[schemars(range(min = 0.0, max = 2.0))]
    pub damage_weight: f64,
    /// A head blow of at least this impulse staggers the VH, N s; our
    /// choice, 18, above the 10-21 N s of a clean jab. 1-1000 N s: 1000
    /// is far beyond any punch (in effect, never staggered).
    #[schemars(range(min = 1.0, max = 1000.0))]
    pub stagger_impulse: f64,
    /// How long a stagger lasts, s (default 1.2). 0.2-5: from a stumble
    /// to a count's worth of wobbling.
    #[schemars(range(min = 0.2, max = 5.0))]
    pub stagger_time: f64,
    /// E2 at full fatigue: the attack rate falls by this share. De La
    /// Hoya's output fell from over 100 punches in a first round to 54 in
    /// rounds 7-12 (CompuBox, reported by BoxingScene): about half; 0.4.
    /// A share, 0-1 (1: an exhausted VH does not attack).
    #[schemars(range(min = 0.0, max = 1.0))]
    pub attack_rate_drop: f64,
    /// E2: punches take this share longer. Punch force fell significantly
    /// after simulated bouts (Dunn et al. 2022, Eur. J. Sport Sci.
    /// 22:964), with no figure in the abstract; our 0.12. A share, 0-1
    /// (1: twice as long).
    #[schemars(range(min = 0.0, max = 1.0))]
    pub punch_slowing: f64,
    /// E2: the guard's gloves sit this much lower, m. Guard drops grew
    /// from round 1 to 2 in elite bouts (Dunn et al. 2017, PLoS ONE
    /// 12:e0188675); our 0.06 m (a glove's height off the chin). 0-0.3 m:
    /// from the chin to the chest.
    #[schemars(range(min = 0.0, max = 0.3))]
    pub guard_drop: f64,
    /// E2: guard and evasion reactions lengthen by this share: choice
    /// reaction time rose 9.5 % after high-intensity exercise (395.8 to
    /// 433.5 ms; Smith et al. 2016, J. Hum. Kinet. 51:27). A share, 0-1
    /// (1: twice as long).
    #[schemars(range(min = 0.0, max = 1.0))]
    pub reaction_rise: f64,
    /// E2: saccades' peak velocity falls by this share: 8 % after 3 h of
    /// exhausting cycling (Connell et al. 2016, Sci. Rep. 6:26614; 8 +- 11
    /// % for prosaccades, Connell et al. 2017, Sci. Rep. 7:42726), as it
    /// does with time on task (Di Stasi et al. 2013, Neurosci. Biobehav.
    /// Rev. 37:968). A share, 0-0.5: at most half as fast.
    #[schemars(range(min = 0.0, max = 0.5))]
    pub saccade_slowing: f64,
    /// E2: saccade latency lengthens by this share. Exercise fatigue left
    /// latency unchanged (Connell et al. 2013, poster; 2017) where sleep
    /// loss lengthens it (De Gennaro et al. 2000); default 0. A share,
    /// 0-1 (1: twice as long).
    #[schemars(range(min = 0.0, max = 1.0))]
    pub saccade_latency_rise: f64,
    /// E3: breaths a minute at rest and at full exertion: 12-20 at rest,
    /// 40-60 at maximal exercise (Nicolò et al. 2017, Front. Physiol.
    /// 8:922, a review of respiratory frequency in exercise); 15 and 45.
    /// Each 0-100 breaths a minute (past the fastest panting).
    #[schemars(inner(range(min = 0.0, max = 100.0)))]
    pub breathing: [f64; 2],
}

impl Default for EffortParams {
    fn default() -> Self {
        EffortParams {
            on: true,
            punch_cost: 0.004,
            evade_cost: 0.002,
            round_drain: 0.1 / 180.0,
            rest_recovery: 55.0,
            round_recovery: 600.0,
            damage_per_impulse: 0.003,
            damage_weight: 0.5,
            stagger_impulse: 18.0,
            stagger_time: 1.2,
            attack_rate_drop: 0.4,
            punch_slowing: 0.12,
            guard_drop: 0.06,
            reaction_rise: 0.095,
            saccade_slowing: 0.08,
            saccade_latency_rise: 0.0,
            breathing: [15.0, 45.0],
        }
    }
}

/// What happened this tick that costs or hurts.
#[derive(Clone, Copy, Debug, Default)]
pub struct Exertion {
    /// Punches the VH threw.
    pub punches: u32,
    /// Evasions it started.
    pub evasions: u32,
    /// Impulse of blows taken on the head, N s (the largest, and the sum).
    pub head: (f64, f64),
    /// Impulse of blows taken on the body, N s (sum).
    pub body: f64,
    /// Whether a round is being fought (else a rest, or the bout is over).
    pub fighting: bool,
}

/// The VH's effort state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Effort {
    /// Stamina, 1 fresh to 0 spent.
    pub stamina: f64,
    /// Damage taken, 0 to 1.
    pub damage: f64,
    /// Breathing phase, cycles (fractional part used).
    pub breath: f64,
    /// Breaths a minute now.
    pub breath_rate: f64,
    /// Staggered until this time, s.
    pub staggered_until: f64,
}

impl Default for Effort {
    fn default() -> Self {
        Effort {
            stamina: 1.0,
            damage: 0.0,
            breath: 0.0,
            breath_rate: 15.0,
            staggered_until: f64::NEG_INFINITY,
        }
    }
}

impl Effort {
    /// E1: fatigue, 0 fresh to 1 exhausted.
    pub fn fatigue(&self, p: &EffortParams) -> f64 {
        if !p.on {
            return 0.0;
        }
        ((1.0 - self.stamina) + p.damage_weight * self.damage).clamp(0.0, 1.0)
    }

    /// Whether the VH is staggered at `t`.
    pub fn staggered(&self, t: f64) -> bool {
        t < self.staggered_until
    }

    /// Advance by `dt` at time `t`; returns true when a blow staggered the
    /// VH this tick.
    pub fn step(&mut self, p: &EffortParams, x: &Exertion, t: f64, dt: f64) -> bool {
        if !p.on {
            return false;
        }
        let spent = x.punches as f64 * p.punch_cost
            + x.evasions as f64 * p.evade_cost
            + if x.fighting { p.round_drain * dt } else { 0.0 };
        let tau = if x.fighting {
            p.round_recovery
        } else {
            p.rest_recovery
        };
        self.stamina += (1.0 - self.stamina) * (dt / tau).min(1.0) - spent;
        self.stamina = self.stamina.clamp(0.0, 1.0);
        self.damage =
            (self.damage + p.damage_per_impulse * (x.head.1 + 0.5 * x.body)).clamp(0.0, 1.0);
        // E3: breathing follows effort: exertion while fighting (the work
        // and the fatigue), easing toward rest in the rest.
        let f = self.fatigue(p);
        let drive = if x.fighting { 0.6 + 0.4 * f } else { 0.6 * f };
        let want = p.breathing[0] + (p.breathing[1] - p.breathing[0]) * drive;
        self.breath_rate += (want - self.breath_rate) * (dt / 20.0).min(1.0);
        self.breath = (self.breath + self.breath_rate / 60.0 * dt).fract();
        if x.head.0 >= p.stagger_impulse && !self.staggered(t) {
            self.staggered_until = t + p.stagger_time;
            return true;
        }
        false
    }

    /// E2 on the action planner's parameters.
    pub fn behaviour(&self, p: &EffortParams, b: &BehaviourParams) -> BehaviourParams {
        let f = self.fatigue(p);
        let mut b = b.clone();
        if f > 0.0 {
            b.attack_rate *= 1.0 - p.attack_rate_drop * f;
            b.punch_time *= 1.0 + p.punch_slowing * f;
            b.guard_drop += p.guard_drop * f;
            b.guard_reaction *= 1.0 + p.reaction_rise * f;
            b.evade_reaction *= 1.0 + p.reaction_rise * f;
        }
        b
    }

    /// E2 on the saccades' law and latency.
    pub fn oculomotor(&self, p: &EffortParams, o: &OculomotorParams) -> OculomotorParams {
        let f = self.fatigue(p);
        let mut o = o.clone();
        if f > 0.0 {
            // Every saccade slower by the same share: the main sequence's
            // durations longer, its cap lower.
            let slow = 1.0 - p.saccade_slowing * f;
            o.saccade.max_speed *= slow;
            o.saccade.main_sequence_intercept /= slow;
            o.saccade.main_sequence_slope /= slow;
            o.timing.saccade_latency.median *= 1.0 + p.saccade_latency_rise * f;
        }
        o
    }

    /// E3 on the face: the brow lowered in strain (AU 4), eyes narrowed a
    /// little (AU 7), and the jaw dropping with each breath (AU 26) once
    /// the breathing is fast, at `t`-independent phase `breath`.
    pub fn face(&self, p: &EffortParams) -> AuLevels {
        let mut au = AuLevels::default();
        if !p.on {
            return au;
        }
        let [rest, most] = p.breathing;
        let hard = ((self.breath_rate - rest) / (most - rest).max(1e-9)).clamp(0.0, 1.0) as f32;
        let f = self.fatigue(p) as f32;
        let inhale = (0.5 - 0.5 * (std::f64::consts::TAU * self.breath).cos()) as f32;
        au.set(ActionUnit::Au4, 0.5 * f);
        au.set(ActionUnit::Au7, 0.3 * f);
        au.set(ActionUnit::Au26, hard * (0.15 + 0.35 * inhale));
        au
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(e: &mut Effort, p: &EffortParams, x: Exertion, secs: f64) {
        let dt = 0.001;
        let n = (secs / dt) as usize;
        for i in 0..n {
            let mut x = x;
            // One punch every 3 s (a pro throws 55.6 a round).
            x.punches *= u32::from(i % 3000 == 0);
            e.step(p, &x, i as f64 * dt, dt);
        }
    }

    #[test]
    fn a_busy_round_tires_and_the_rest_recovers() {
        let p = EffortParams::default();
        let mut e = Effort::default();
        let round = Exertion {
            punches: 1,
            fighting: true,
            ..Default::default()
        };
        run(&mut e, &p, round, 180.0);
        let tired = e.fatigue(&p);
        assert!((0.2..0.5).contains(&tired), "fatigue after a round {tired}");
        assert!(e.breath_rate > 35.0, "blowing hard: {}", e.breath_rate);
        run(&mut e, &p, Exertion::default(), 60.0);
        let rested = e.fatigue(&p);
        assert!(rested < 0.5 * tired, "{tired} -> {rested}");
        assert!(e.breath_rate < 30.0, "{}", e.breath_rate);
    }

    #[test]
    fn fatigue_slows_and_lowers_and_is_off_in_the_seed() {
        let p = EffortParams::default();
        let e = Effort {
            stamina: 0.0,
            ..Default::default()
        };
        let b0 = BehaviourParams::default();
        let b = e.behaviour(&p, &b0);
        assert!((b.attack_rate / b0.attack_rate - 0.6).abs() < 1e-9);
        assert!((b.guard_reaction / b0.guard_reaction - 1.095).abs() < 1e-9);
        assert!((b.guard_drop - 0.06).abs() < 1e-9);
        let o0 = OculomotorParams::default();
        let o = e.oculomotor(&p, &o0);
        assert!((o.saccade.max_speed / o0.saccade.max_speed - 0.92).abs() < 1e-9);
        let off = EffortParams {
            on: false,
            ..Default::default()
        };
        assert_eq!(e.behaviour(&off, &b0), b0);
        assert_eq!(e.fatigue(&off), 0.0);
    }

    #[test]
    fn a_hard_head_blow_staggers_once() {
        let p = EffortParams::default();
        let mut e = Effort::default();
        let hit = Exertion {
            head: (30.0, 30.0),
            fighting: true,
            ..Default::default()
        };
        assert!(e.step(&p, &hit, 1.0, 0.001));
        assert!(e.staggered(1.5));
        assert!(!e.step(&p, &hit, 1.5, 0.001), "already staggered");
        assert!(!e.staggered(1.0 + p.stagger_time + 0.01));
        assert!(e.damage > 0.0);
        let light = Exertion {
            head: (12.0, 12.0),
            ..Default::default()
        };
        assert!(!Effort::default().step(&p, &light, 0.0, 0.001));
    }
}
