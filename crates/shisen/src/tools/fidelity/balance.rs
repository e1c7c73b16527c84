//! The physical body's balance (docs/model/balance.md): how much it sways
//! standing still, and how hard a shove must be before it steps.

use glam::DVec3;

use super::Row;
use crate::physics::lower::Pelvis;
use crate::physics::world::PushPart;
use crate::sim::timeline::{Action, Event};
use crate::sim::{Model, Sim};

const WUEHR: &str = "quiet stance, eyes open: centre-of-pressure RMS 5.0 +- 2.5 mm front-back, 3.3 +- 1.1 mm sideways (Wuehr et al. 2014, Physiol. Rep. 2:e00232); the centre of mass sways less than the centre of pressure";
const STEP: &str = "young adults step once the centre of mass is pushed to about 0.3-0.8 m/s (Pai & Patton 1997, J. Biomech. 30:347, feasible stability region; Mille et al. 2003, J. Neurophysiol. 90:666, waist pulls)";

/// Body mass, kg (anthro::MASS).
const MASS: f64 = crate::physics::lower::anthro::MASS;

/// A physical VH of this model, standing alone (no opponent in reach),
/// shoved on the trunk at 1 s by `impulse` (N s, world).
fn standing(model: &Model, impulse: DVec3) -> Sim {
    let mut m = model.clone();
    m.params.body.pelvis = Pelvis::Balanced;
    m.params.personality.evade = 0.0;
    let push = Event {
        at: 1.0,
        action: Action::Push {
            part: PushPart::Trunk,
            impulse,
        },
    };
    Sim::new(m, &[push])
}

/// The centre of mass's RMS sway front-back and sideways over a minute
/// of standing still (after 5 s to settle), m.
fn sway(model: &Model) -> (f64, f64) {
    let mut sim = standing(model, DVec3::ZERO);
    let mut com = Vec::new();
    while sim.time() < 65.0 {
        sim.step();
        if sim.time() > 5.0 {
            com.push(sim.balance.last.com);
        }
    }
    let n = com.len().max(1) as f64;
    let mean = com.iter().fold(DVec3::ZERO, |a, c| a + *c) / n;
    let rms =
        |f: fn(DVec3) -> f64| (com.iter().map(|c| f(*c - mean).powi(2)).sum::<f64>() / n).sqrt();
    (rms(|d| d.z), rms(|d| d.x))
}

/// The least shove from the front (toward -Z) that makes the VH step, as
/// the centre of mass's velocity it gives, m/s (NaN if none up to 1 m/s).
fn step_threshold(model: &Model) -> f64 {
    (1..=20)
        .map(|k| f64::from(k) * 0.05)
        .find(|v| {
            let mut sim = standing(model, DVec3::new(0.0, 0.0, -v * MASS));
            while sim.time() < 3.0 {
                sim.step();
            }
            sim.balance.recovery_steps > 0
        })
        .unwrap_or(f64::NAN)
}

/// The balance rows.
pub(super) fn balance(model: &Model, rows: &mut Vec<Row>) {
    let (ap, ml) = sway(model);
    rows.push(Row {
        name: "standing sway, centre of mass RMS, front-back".into(),
        value: ap * 1e3,
        band: (0.3, 7.5),
        unit: "mm",
        source: WUEHR,
    });
    rows.push(Row {
        name: "standing sway, centre of mass RMS, sideways (boxer's stance)".into(),
        value: ml * 1e3,
        band: (0.3, 5.5),
        unit: "mm",
        source: WUEHR,
    });
    rows.push(Row {
        name: "a shove from the front: least centre-of-mass speed that makes it step".into(),
        value: step_threshold(model),
        band: (0.3, 0.8),
        unit: "m/s",
        source: STEP,
    });
}
