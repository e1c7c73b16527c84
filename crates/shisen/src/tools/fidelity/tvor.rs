//! The gaze through the VH's own motion: the translational VOR measured
//! from the joints as Ramat & Zee 2003 measured it (an abrupt interaural
//! translation on a sled while fixating a near target), and the line of
//! sight's error while the VH slips jabs (docs/model/gaze.md H8).

use glam::DVec3;
use shisen_gaze::behaviour::ActionKind;
use shisen_gaze::oculomotor::otolith::lag_fit;
use shisen_gaze::util::math::yaw_pitch_of;

use super::{Row, at, hold_head, median, point, run};
use std::path::Path;

use crate::physics::body::BodyPlan;
use crate::scene::format::Scene;
use crate::sim::timeline::Action;
use crate::sim::{Model, Sample, Sim};

const RAMAT_ZEE: &str = "Ramat & Zee 2003, J. Neurophysiol. 90:887 (latency 19 +- 5 ms at 15 cm, 20 +- 12 ms at 30 cm; velocity gain 0.52 and 0.62)";

/// The run starts the carry here, s.
const ONSET: f64 = 1.0;

/// A VH on a stand (only the carry moves it), head held still, fixating a
/// dot `distance` m straight ahead, carried 2 cm to its left over 200 ms
/// from [`ONSET`]: the tVOR's latency (s) and gain against the ideal eye
/// velocity (the rate of the dot's direction from the moving eyes), from
/// the onset to the head's peak velocity (100 ms; Ramat & Zee's gain is
/// taken there), before vision could add to the reflex.
fn carried(model: &Model, distance: f64) -> (f64, f64) {
    let mut m = model.clone();
    m.params.body.human = false;
    m.params.oculomotor.fixation.enabled = false;
    let dot = point(0.0, distance);
    let tl = [
        hold_head(ONSET + 0.5),
        at(
            0.0,
            Action::LookAt {
                point: dot,
                until: ONSET + 0.5,
                amount: Some(0.0),
                style: None,
            },
        ),
        at(
            ONSET,
            Action::Carry {
                offset: DVec3::new(0.02, 0.0, 0.0),
                duration: 0.2,
            },
        ),
    ];
    let s = run(&m, dot, &tl, ONSET + 0.4);
    let eyes0 = BodyPlan::eyes_midpoint();
    let Some(head0) = s.iter().find(|x| x.t >= ONSET).map(|x| x.head) else {
        return (f64::NAN, f64::NAN);
    };
    let yaw = |x: &Sample| yaw_pitch_of(dot - (eyes0 + x.head - head0)).0;
    let eye = |x: &Sample| (x.eye_actual[0].x + x.eye_actual[1].x) / 2.0;
    let (mut actual, mut ideal) = (Vec::new(), Vec::new());
    for w in s.windows(2) {
        let (a, b) = (&w[0], &w[1]);
        if b.t <= ONSET || b.t > ONSET + 0.1 + 0.02 {
            continue;
        }
        // Up to the first saccade (an eye faster than 100 deg/s).
        let v = (eye(b) - eye(a)) / (b.t - a.t);
        if v.abs().to_degrees() > 100.0 {
            break;
        }
        actual.push(v);
        ideal.push((yaw(b) - yaw(a)) / (b.t - a.t));
    }
    lag_fit(&actual, &ideal, model.dt)
}

/// The tVOR's latency and gain at 15 and 30 cm, and the line of sight
/// through slips.
pub(super) fn tvor(model: &Model, rows: &mut Vec<Row>) {
    // Ramat & Zee's means +- 2 SD at 15 cm, +- 1 SD at 30 cm (2 SD would
    // take in no latency at all).
    for (d, band) in [(0.15, (9.0, 29.0)), (0.3, (8.0, 32.0))] {
        let (latency, gain) = carried(model, d);
        let cm = (d * 100.0).round();
        rows.push(Row {
            name: format!("tVOR latency, 2 cm interaural translation, target at {cm} cm"),
            value: latency * 1e3,
            band,
            unit: "ms",
            source: RAMAT_ZEE,
        });
        rows.push(Row {
            name: format!("tVOR velocity gain, target at {cm} cm"),
            value: gain,
            band: (0.4, 0.8),
            unit: "",
            source: RAMAT_ZEE,
        });
    }
    let (median_err, max_err) = slips(model);
    const SLIP: &str = "Ramat & Zee 2003: 23-32 % of a translation uncompensated at its end (an 18 cm slip at 1.25 m: 2-3 deg); the gaze anchored on the head (Hausegger et al. 2019, J. Sport Exerc. Psychol. 41:137)";
    rows.push(Row {
        name: "line-of-sight error while slipping jabs, median".into(),
        value: median_err,
        band: (0.0, 3.0),
        unit: "deg",
        source: SLIP,
    });
    rows.push(Row {
        name: "line-of-sight error while slipping jabs, largest".into(),
        value: max_err,
        band: (0.0, 10.0),
        unit: "deg",
        source: SLIP,
    });
}

/// The six-jab scene the slip row replays (one home for its timeline).
const SLIP_JABS: &str = include_str!("../../../../../scenes/slip_jabs.ron");

/// Six 5 m/s jabs thrown stepping in from 1.5 m (scenes/slip_jabs.ron's
/// timeline and range, on this model's VH): the median and largest
/// line-of-sight error (deg) over the ticks the VH evades.
fn slips(model: &Model) -> (f64, f64) {
    let scene = Scene::parse(SLIP_JABS, Path::new("scenes/slip_jabs.ron"))
        .expect("the shipped slip_jabs scene parses");
    let mut m = model.clone();
    m.params.behaviour.range = scene.vh.behaviour.range;
    let tl = scene.timeline;
    let mut sim = Sim::new(m, &tl);
    let mut errs = Vec::new();
    while sim.time() < scene.duration - 1e-9 {
        let s = sim.step();
        if matches!(
            s.action,
            ActionKind::Slip | ActionKind::Duck | ActionKind::LeanBack
        ) {
            errs.push(s.los_error[0].max(s.los_error[1]).to_degrees());
        }
    }
    let most = errs.iter().fold(f64::NAN, |m, &e| m.max(e));
    (median(&mut errs), most)
}
