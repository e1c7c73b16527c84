//! The physical body's balance (docs/model/balance.md): how much it sways
//! standing still, and how hard a shove must be before it steps.

use glam::DVec3;
use rayon::prelude::*;

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
            stepped(&sim) > 0
        })
        .unwrap_or(f64::NAN)
}

/// Steps the body took: recovery steps (B4) and the footwork's steps
/// under the capture point.
fn stepped(sim: &Sim) -> u32 {
    sim.balance.recovery_steps + sim.lower.steps
}

/// The sides a shove comes from, and the way it pushes (the VH faces +Z,
/// its left foot leads at +X).
const SIDES: [(&str, DVec3); 4] = [
    ("from the front", DVec3::NEG_Z),
    ("from behind", DVec3::Z),
    ("from its left", DVec3::NEG_X),
    ("from its right", DVec3::X),
];

/// The seeds each shove is tried with (the body's sway and the stepping
/// that follows differ from seed to seed).
const PUSH_SEEDS: [u64; 3] = [1, 2, 3];

/// Shoves on the trunk, N s.
const SHOVES: [f64; 6] = [15.0, 30.0, 45.0, 60.0, 75.0, 90.0];

/// The push-recovery table (docs/model/balance.md, "Pushes, measured"):
/// a physical VH of this model shoved on the trunk at 1 s from each side
/// with rising impulses, and what it did in the next 4 s, over three
/// seeds: held with its feet in place, stepped (in how many runs), or fell
/// (in how many). Markdown. A stop request ([`crate::tools::request_stop`])
/// cuts the runs short: the caller must not print the table then.
pub fn push_table(model: &Model) -> String {
    let mut out = String::from("| shove | ");
    let heads: Vec<String> = SHOVES
        .iter()
        .map(|j| format!("{j:.0} N s ({:.2} m/s)", j / MASS))
        .collect();
    out += &heads.join(" | ");
    out += " |\n|---|";
    out += &"---|".repeat(SHOVES.len());
    out += "\n";
    // Every run at once: (side, shove, seed) -> (fell, steps).
    let jobs: Vec<(DVec3, f64, u64)> = SIDES
        .iter()
        .flat_map(|&(_, dir)| SHOVES.iter().map(move |&j| (dir, j)))
        .flat_map(|(dir, j)| PUSH_SEEDS.iter().map(move |&s| (dir, j, s)))
        .collect();
    let results: Vec<(bool, u32)> = jobs
        .par_iter()
        .map(|&(dir, j, seed)| {
            let mut m = model.clone();
            m.seed = seed;
            let mut sim = standing(&m, dir * j);
            while sim.time() < 5.0 && !crate::tools::stop_requested() {
                sim.step();
            }
            (sim.balance.knockdowns > 0, stepped(&sim))
        })
        .collect();
    let mut runs = results.chunks(PUSH_SEEDS.len());
    for (name, _) in SIDES {
        let cells: Vec<String> = SHOVES
            .iter()
            .map(|_| {
                let runs = runs.next().expect("one result per run");
                let n = PUSH_SEEDS.len();
                let falls = runs.iter().filter(|r| r.0).count();
                let stepped = runs.iter().filter(|r| r.1 > 0).count();
                match (falls, stepped) {
                    (0, 0) => "held".to_string(),
                    (0, s) if s == n => "steps".to_string(),
                    (0, s) => format!("steps {s}/{n}"),
                    (f, _) if f == n => "falls".to_string(),
                    (f, _) => format!("falls {f}/{n}"),
                }
            })
            .collect();
        out += &format!("| {name} | {} |\n", cells.join(" | "));
    }
    out += &format!("\nPeople: {STEP}.\n");
    out
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
