//! Ring craft (docs/model/boxing.md "Ranges", "Cues"): when a pro's
//! defence starts against a stepping jab it reads from the body, and how
//! many punches a minute a pro throws sparring.

use super::Row;
use crate::scene::opponent::{Level, Opponent, Style};
use crate::sim::timeline::{Action, Event, Hand, PunchTarget};
use crate::sim::{DT, Model, Sim};
use crate::tools::soak::{BotRates, SparringBot};

const ANTICIPATION: &str = "experts anticipate an attack from the body's movement before the attacking limb's, near-experts once it has started, novices only with the whole action in view (Rosalie & Mueller 2013, Q. J. Exp. Psychol. 66:1951); a reaction to the hand alone comes 0.2-0.25 s after it (Welford 1980). Band: from 0.2 s before the glove leaves to 0.05 s after";
const OUTPUT: &str = "elite amateurs throw about 20-26 punches a minute (Davis et al. 2018, J. Strength Cond. Res.; 2012 Olympics about 20); a pro's band 15-26";

/// `model` as a pro of `style`.
fn pro(model: &Model, style: Style) -> Model {
    let mut m = model.clone();
    Opponent {
        level: Level::Pro,
        style,
    }
    .apply(&mut m.params);
    m
}

/// A pro boxer (holding long range, attacks off) facing five 7 m/s
/// stepping jabs 2 s apart from 3 s: when its defensive decision comes,
/// from each glove's start (after the body's lead), s, the median; a jab
/// it never answers within 0.5 s counts as 0.5 s late.
fn defence_lead(model: &Model) -> f64 {
    let mut m = pro(model, Style::Boxer);
    m.params.behaviour.attacks = false;
    let starts: Vec<f64> = (0..5).map(|k| 3.0 + 2.0 * f64::from(k)).collect();
    let jabs: Vec<Event> = starts
        .iter()
        .map(|&at| Event {
            at,
            action: Action::Punch {
                hand: Hand::Left,
                target: PunchTarget::Head,
                speed: 7.0,
                through: None,
                glove_only: false,
            },
        })
        .collect();
    let mut sim = Sim::new(m, &jabs);
    let lead = crate::sim::punch::KINETIC_LEAD;
    let mut found = vec![0.5; starts.len()];
    let mut was = false;
    while sim.time() < 12.0 {
        let s = sim.step();
        let defends = s.action.defends();
        if defends && !was {
            let t = s.t;
            if let Some(k) = starts.iter().position(|&a| t >= a && t < a + 0.5 + lead) {
                found[k] = f64::min(found[k], t - starts[k] - lead);
            }
        }
        was = defends;
    }
    found.sort_by(f64::total_cmp);
    found[found.len() / 2]
}

/// A pro boxer's punches a minute sparring with the soak's random partner:
/// three two-minute bouts on the battery's own seeds, so that a scene's
/// seed does not move a statistical row (one bout's count varies by about
/// 3 a minute from seed to seed).
fn output(model: &Model) -> f64 {
    const BOUTS: [u64; 3] = [1, 2, 3];
    const MINUTES: f64 = 2.0;
    let mut thrown = 0u32;
    for seed in BOUTS {
        let mut m = pro(model, Style::Boxer);
        m.params.behaviour.attacks = true;
        m.seed = seed;
        let mut sim = Sim::new(m, &[]);
        let mut bot = SparringBot::new(seed, BotRates::default());
        let ticks = (MINUTES * 60.0 / DT).round() as usize;
        for _ in 0..ticks {
            bot.step(&mut sim);
            sim.step();
        }
        thrown += sim.behaviour.punches_thrown;
    }
    f64::from(thrown) / (MINUTES * BOUTS.len() as f64)
}

/// The ring-craft rows.
pub(super) fn ring(model: &Model, rows: &mut Vec<Row>) {
    rows.push(Row {
        name: "pro, a stepping jab read from the body: its defence decided, from the glove's start"
            .into(),
        value: defence_lead(model),
        band: (-0.2, 0.05),
        unit: "s",
        source: ANTICIPATION,
    });
    rows.push(Row {
        name: "pro boxer sparring (3 bouts of 2 min): punches thrown a minute".into(),
        value: output(model),
        band: (15.0, 26.0),
        unit: "/min",
        source: OUTPUT,
    });
}
