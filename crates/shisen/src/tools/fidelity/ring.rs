//! Ring craft (docs/model/boxing.md "Ranges", "Cues"): when a pro's
//! defence starts against a stepping jab it reads from the body, how
//! many punches a minute a pro throws sparring, and how its eyes fixate
//! against a novice's.

use super::Row;
use crate::scene::opponent::{Level, Opponent, Style};
use crate::sim::timeline::{Action, Event, Hand, PunchTarget};
use crate::sim::{DT, Model, Sim};
use crate::tools::soak::{BotRates, SparringBot};

const ANTICIPATION: &str = "experts anticipate an attack from the body's movement before the attacking limb's, near-experts once it has started, novices only with the whole action in view (Rosalie & Mueller 2013, Q. J. Exp. Psychol. 66:1951); a reaction to the hand alone comes 0.2-0.25 s after it (Welford 1980). Band: from 0.2 s before the glove leaves to 0.05 s after";
const FIXATIONS: &str = "experts use fewer fixations of longer duration than novices (Mann, Williams, Ward & Janelle 2007, J. Sport Exerc. Psychol. 29:457, meta-analysis of 42 studies); combat-sport experts anchor the gaze on the opponent's head (Ripoll et al. 1995, Hum. Mov. Sci. 14:325; Hausegger et al. 2019). Bands: the direction, pro below (count) or above (duration) the novice by 10 %";
const OUTPUT: &str = "elite amateurs throw about 20-26 punches a minute (Davis et al. 2018, J. Strength Cond. Res.; 2012 Olympics about 20); a pro's band 15-26";

/// `model` as a pro of `style`.
fn pro(model: &Model, style: Style) -> Model {
    fighter(model, Level::Pro, style)
}

/// `model` as a fighter of `level` and `style`.
fn fighter(model: &Model, level: Level, style: Style) -> Model {
    let mut m = model.clone();
    Opponent { level, style }.apply(&mut m.params);
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

/// A boxer of `level` sparring two minutes with the soak's partner (seed 1):
/// its fixations a minute and their mean duration, ms. Saccades are found
/// by the gaze's speed in space (the head's direction and the left eye's
/// in it) above 50 deg/s, the velocity threshold of fixation
/// identification (Salvucci & Goldberg 2000, ETRA); a fixation is the
/// time between two saccades, if at least 100 ms.
fn fixations(model: &Model, level: Level) -> (f64, f64) {
    const MINUTES: f64 = 2.0;
    let mut m = fighter(model, level, Style::Boxer);
    m.params.behaviour.attacks = true;
    m.seed = 1;
    let mut sim = Sim::new(m, &[]);
    let mut bot = SparringBot::new(1, BotRates::default());
    let ticks = (MINUTES * 60.0 / DT).round() as usize;
    let mut gaze = Vec::with_capacity(ticks);
    for _ in 0..ticks {
        bot.step(&mut sim);
        let s = sim.step();
        gaze.push(s.head_world + s.eye_actual[0]);
    }
    let fast: Vec<bool> = gaze
        .windows(2)
        .map(|w| (w[1] - w[0]).length().to_degrees() / DT > 50.0)
        .collect();
    let mut durations = Vec::new();
    let mut start = None;
    for (i, &f) in fast.iter().enumerate() {
        match (f, start) {
            (false, None) => start = Some(i),
            (true, Some(a)) => {
                let d = (i - a) as f64 * DT * 1e3;
                if d >= 100.0 {
                    durations.push(d);
                }
                start = None;
            }
            _ => {}
        }
    }
    let n = durations.len() as f64;
    (n / MINUTES, durations.iter().sum::<f64>() / n.max(1.0))
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
    let (pro, novice) = (
        fixations(model, Level::Pro),
        fixations(model, Level::Novice),
    );
    rows.push(Row {
        name: format!(
            "sparring, fixations a minute: pro / novice ({:.0} / {:.0})",
            pro.0, novice.0
        ),
        value: pro.0 / novice.0.max(1.0),
        band: (0.0, 0.9),
        unit: "",
        source: FIXATIONS,
    });
    rows.push(Row {
        name: format!(
            "sparring, mean fixation: pro / novice ({:.0} / {:.0} ms)",
            pro.1, novice.1
        ),
        value: pro.1 / novice.1.max(1.0),
        band: (1.1, 20.0),
        unit: "",
        source: FIXATIONS,
    });
}
