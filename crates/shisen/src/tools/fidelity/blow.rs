//! Blows: the head's, the gaze's and the lids' response to a punch and to
//! a padded impactor, against published human figures (docs/model/neck.md).

use glam::DVec3;

use super::{Row, at};
use crate::physics::body::Seg;
use crate::sim::blows::{BlowKind, Fighter};
use crate::sim::timeline::{Action, Hand, PunchTarget};
use crate::sim::{BodySpec, Model, PropShape, Sample, Sim};

/// A committed jab at `speed` m/s to the head of a VH that does not guard
/// and keeps its eyes on the opponent's face; the run from 1 s before the
/// punch to 1 s after.
fn jab(model: &Model, speed: f64) -> Vec<Sample> {
    let mut m = model.clone();
    m.params.behaviour.attacks = false;
    m.params.behaviour.guard_speed = 1e3; // never sees a threat: unguarded
    let tl = [
        at(
            0.0,
            Action::Track {
                body: "head".into(),
                until: 2.0,
            },
        ),
        at(
            1.0,
            Action::Punch {
                hand: Hand::Left,
                target: PunchTarget::Head,
                speed,
                through: Some(0.15),
                glove_only: false,
            },
        ),
    ];
    collect(Sim::new(m, &tl), 2.0)
}

/// Reynier et al. 2020's test: a 3.7 kg padded impactor at 2 m/s into the
/// side of the head at its centre's height (started 2 cm away, so the
/// blow comes before vision could see it).
fn impactor(model: &Model) -> Vec<Sample> {
    let mut m = model.clone();
    m.params.behaviour.attacks = false;
    let head = m.plan.segments[Seg::Head.index()].centre.as_dvec3();
    let radius = 0.06;
    m.props.push(BodySpec {
        name: "impactor".into(),
        shape: PropShape::Ball(radius),
        position: head + DVec3::X * (0.10 + radius + 0.02),
        velocity: DVec3::new(-2.0, 0.0, 0.0),
        angular_velocity: DVec3::ZERO,
        mass: 3.7,
        kinematic: false,
        gravity: false,
    });
    collect(Sim::new(m, &[]), 1.0)
}

fn collect(mut sim: Sim, duration: f64) -> Vec<Sample> {
    let n = (duration / sim.model().dt).round() as usize;
    (0..n).map(|_| sim.step().clone()).collect()
}

/// Index of the first sample with the head touched (by a glove or prop),
/// or where the head starts to move.
fn contact(s: &[Sample]) -> Option<usize> {
    s.iter()
        .position(|x| x.head_hit)
        .or_else(|| s.iter().position(|x| x.head_speed > 0.5))
}

/// The head's rotation from its direction at sample `i0`, deg, per sample.
fn rotation(s: &[Sample], i0: usize) -> Vec<f64> {
    let o = s[i0].head_world;
    s.iter()
        .map(|x| (x.head_world - o).length().to_degrees())
        .collect()
}

/// First time after `from` (index) that `f` holds, s after sample `i0`.
fn first_after(s: &[Sample], i0: usize, from: usize, f: impl Fn(&Sample) -> bool) -> f64 {
    s[from..]
        .iter()
        .find(|x| f(x))
        .map_or(f64::NAN, |x| x.t - s[i0].t)
}

/// The head-response rows.
pub(super) fn blows(model: &Model, rows: &mut Vec<Row>) {
    let s = jab(model, 7.0);
    let momentum = s
        .iter()
        .flat_map(|x| &x.blows)
        .find(|b| b.by == Fighter::Opponent && b.kind == BlowKind::Hit && b.part == "head")
        .map_or(f64::NAN, |b| f64::from(b.impulse));
    rows.push(Row {
        name: "blow momentum, committed 7 m/s jab to the head".into(),
        value: momentum,
        band: (10.0, 21.0),
        unit: "N s",
        source: "Walilko, Viano & Bir 2005, Br. J. Sports Med. 39:710: punch mass 2.9 +- 2.0 kg; 1.5-3 kg at 7 m/s",
    });
    let Some(i0) = contact(&s) else {
        return;
    };
    let peak_speed = s.iter().map(|x| x.head_speed).fold(0.0, f64::max);
    rows.push(Row {
        name: "head peak angular velocity, 7 m/s jab".into(),
        value: peak_speed,
        band: (9.0, 21.0),
        unit: "rad/s",
        source: "Reynier et al. 2020's 6.5-7.3 rad/s for a 7.4 N s impactor, scaled to a jab's 10-21 N s (angular velocity in proportion to impulse)",
    });
    let rot = rotation(&s, i0);
    let (ipk, peak) = rot
        .iter()
        .enumerate()
        .skip(i0)
        .fold((i0, 0.0), |b, (i, &r)| if r > b.1 { (i, r) } else { b });
    rows.push(Row {
        name: "head peak rotation, 7 m/s jab".into(),
        value: peak,
        band: (8.0, 45.0),
        unit: "deg",
        source: "estimate, no direct measurement found: Reynier et al. 2020's 6.5-7.3 rad/s per 7 N s over a head-neck resonance of 2.1-2.9 Hz (Peng, Hain & Peterson 1996, Biol. Cybern. 75:309)",
    });
    let back = first_after(&s, i0, ipk, |x| {
        (x.head_world - s[i0].head_world).length().to_degrees() < 2.0
    });
    rows.push(Row {
        name: "head back within 2 deg, 7 m/s jab".into(),
        value: back * 1e3,
        band: (100.0, 600.0),
        unit: "ms",
        source: "Peng, Hain & Peterson 1996, Biol. Cybern. 75:309: reflexes damp the head-neck resonance (2.9 Hz) within about a period",
    });
    // VOR gain while the head is knocked back: the eyes' counter-rotation
    // in the head over the head's rotation, from the VOR's latency to the
    // head's peak speed.
    let ispeed = (i0..s.len().min(i0 + 100))
        .max_by(|&a, &b| s[a].head_speed.total_cmp(&s[b].head_speed))
        .unwrap_or(i0);
    let (a, b) = (i0 + 10, ispeed.max(i0 + 20));
    let eye = |x: &Sample| (x.eye_actual[0] + x.eye_actual[1]) / 2.0;
    let dh = s[b].head_world - s[a].head_world;
    let de = eye(&s[b]) - eye(&s[a]);
    let gain = -de.dot(dh) / dh.length_squared().max(1e-12);
    rows.push(Row {
        name: "VOR gain while a 7 m/s jab knocks the head".into(),
        value: gain,
        band: (0.61, 0.83),
        unit: "",
        source: "Maas et al. 1989, Brain Res. 499:153 (median gains at 1900-7100 deg/s^2)",
    });
    let los = |x: &Sample| x.los_error[0].max(x.los_error[1]).to_degrees();
    let iworst = (i0..s.len().min(i0 + 300))
        .max_by(|&a, &b| los(&s[a]).total_cmp(&los(&s[b])))
        .unwrap_or(i0);
    let recover = first_after(&s, i0, iworst, |x| los(x) < 1.5);
    rows.push(Row {
        name: format!(
            "gaze back on target (< 1.5 deg) after a 7 m/s jab ({:.1} deg off)",
            los(&s[iworst])
        ),
        value: recover * 1e3,
        band: (60.0, 250.0),
        unit: "ms",
        source: "Tian et al. 2007, Exp. Brain Res. 182:143: catch-up saccades 135 +- 36 ms after a head impulse",
    });

    let s = impactor(model);
    let peak_speed = s.iter().map(|x| x.head_speed).fold(0.0, f64::max);
    rows.push(Row {
        name: "head peak angular velocity, 3.7 kg impactor at 2 m/s".into(),
        value: peak_speed,
        band: (5.8, 7.8),
        unit: "rad/s",
        source: "Reynier et al. 2020, Ann. Biomed. Eng., doi 10.1007/s10439-020-02609-7: 6.5-7.3 rad/s (+-0.5-0.7) relaxed to braced",
    });
    let blink = contact(&s).map_or(f64::NAN, |i0| {
        first_after(&s, i0, i0, |x| x.blink >= 0.1) * 1e3
    });
    rows.push(Row {
        name: "blink reflex to a blow, lids 10 % shut".into(),
        value: blink,
        band: (25.0, 80.0),
        unit: "ms",
        source: "Rushworth 1962, J. Neurol. Neurosurg. Psychiatry 25:93: R2 23-46 ms after a tap, then the lid's travel",
    });
}
