use super::*;
use crate::oculomotor::head::Amount;
use crate::oculomotor::{GazeInput, GazeShiftLaw, Oculomotor, OculomotorParams};
use crate::target::{BodyId, TargetId};
use crate::util::math::{JointAngles, min_jerk, yaw_pitch_of};
use glam::DVec2;
use rand::SeedableRng;
use rand::rngs::StdRng;

const DT: f64 = 0.001;

/// The translational VOR measured as Ramat & Zee 2003 did, with a perfect
/// plant (each eye command taken as the eye's new angle).
#[derive(Clone, Copy, Debug, PartialEq)]
struct TvorResponse {
    /// Delay of the eyes' velocity behind the ideal one, s (the lag of
    /// best fit).
    latency: f64,
    /// Eye velocity over the ideal one at that lag (least squares).
    gain: f64,
    /// The eyes' peak conjugate yaw velocity, rad/s.
    peak_rate: f64,
}

/// Ramat & Zee's paradigm: the head, facing +Z, is carried interaurally
/// (toward the VH's left, +X) by `shift` m along a 200 ms minimum-jerk path,
/// without turning, while the gaze laws `p` fixate a point `distance` m
/// straight ahead; measured from the onset to the head's peak velocity
/// (100 ms, where Ramat & Zee took the gain) and the reflex's latency
/// after it, before vision adds to the reflex. The eyes' ideal velocity is
/// the rate of the target's direction from the moving cyclopean eye.
fn interaural_translation(p: &OculomotorParams, distance: f64, shift: f64) -> TvorResponse {
    const ONSET: f64 = 0.5;
    let head0 = DVec3::new(0.0, 1.6, 0.0);
    let mut rng = StdRng::seed_from_u64(3);
    let mut oc = Oculomotor::new(p, &mut rng);
    let target = head0 + DVec3::new(0.0, 0.0, distance);
    let mut eyes = [DVec2::ZERO; 2];
    let (mut actual, mut ideal) = (Vec::new(), Vec::new());
    let (mut last_ideal, mut settled) = (None, None);
    for k in 0..1000 {
        let t = f64::from(k) * DT;
        let head = head0 + DVec3::X * shift * min_jerk((t - ONSET) / 0.2);
        let half = 0.5 * p.pursuit.interpupillary;
        let input = GazeInput {
            point: target,
            target: TargetId::body(BodyId::new(1)),
            amount: Amount {
                value: 1.0,
                least: 1.5,
                most: 3.0,
            },
            top_down: false,
            head_pos: head,
            head_rot: DQuat::IDENTITY,
            head_angvel: DVec3::ZERO,
            torso_rot: DQuat::IDENTITY,
            eye_pos: [1.0, -1.0].map(|s| head + DVec3::X * s * half),
            eye_angles: eyes,
            neck_angles: JointAngles::default(),
            visible: [true, true],
            style: GazeShiftLaw::Reflex,
            neck_override: None,
        };
        let before = (eyes[0].x + eyes[1].x) / 2.0;
        let out = oc.step(p, &input, t, DT, &mut rng);
        eyes = out.eyes.map(|e| e.angles);
        let (yaw, _) = yaw_pitch_of(target - head);
        if t >= ONSET && settled.is_none() {
            settled = Some(oc.saccades);
        }
        if (ONSET..ONSET + 0.12).contains(&t) && settled == Some(oc.saccades) {
            actual.push(((eyes[0].x + eyes[1].x) / 2.0 - before) / DT);
            ideal.push(last_ideal.map_or(0.0, |l| (yaw - l) / DT));
        }
        last_ideal = Some(yaw);
    }
    let (latency, gain) = lag_fit(&actual, &ideal, DT);
    TvorResponse {
        latency,
        gain,
        peak_rate: actual.iter().fold(0.0, |m, v| m.max(v.abs())),
    }
}

/// The human oculomotor parameters with the idle gaze's microsaccades and
/// drift off (they would add noise to the velocities measured).
fn quiet() -> OculomotorParams {
    let mut p = OculomotorParams::default();
    p.fixation.enabled = false;
    p
}

#[test]
fn tvor_latency_and_gain_are_ramat_and_zees_at_15_and_30_cm() {
    for d in [0.15, 0.3] {
        let r = interaural_translation(&quiet(), d, 0.02);
        // Ramat & Zee 2003: 19 +- 5 ms and 20 +- 12 ms; velocity gains 0.52
        // and 0.62 (medians).
        assert!((0.014..=0.026).contains(&r.latency), "{d} m: {r:?}");
        assert!((0.5..=0.7).contains(&r.gain), "{d} m: {r:?}");
    }
}

#[test]
fn tvor_eye_velocity_scales_with_the_inverse_of_the_viewing_distance() {
    let peak = |d: f64| interaural_translation(&quiet(), d, 0.02).peak_rate;
    let near = peak(0.2);
    for (d, want) in [(0.4, 2.0), (0.8, 4.0)] {
        let ratio = near / peak(d);
        assert!(
            (ratio / want - 1.0).abs() < 0.1,
            "{d} m: peak eye velocity {ratio:.2} x smaller, want {want}"
        );
    }
}

#[test]
fn a_far_target_needs_no_translational_vor() {
    let most = interaural_translation(&quiet(), 30.0, 0.02).peak_rate;
    assert!(most.to_degrees() < 0.5, "{} deg/s", most.to_degrees());
}

#[test]
fn the_seed_turns_the_eyes_with_the_geometry_at_once_and_in_full() {
    let mut p = quiet();
    p.otolith = OtolithParams::seed();
    p.timing = crate::oculomotor::timing::TimingParams::seed();
    let r = interaural_translation(&p, 0.3, 0.02);
    assert!(r.latency <= 0.003, "{r:?}");
    assert!((r.gain - 1.0).abs() < 0.05, "{r:?}");
}

#[test]
fn vision_takes_up_the_shortfall_after_its_latency_without_overshoot() {
    let p = OtolithParams::default();
    let mut o = Otolith::default();
    let eyes = |x: f64| {
        [
            DVec3::new(x + 0.03, 0.0, 0.0),
            DVec3::new(x - 0.03, 0.0, 0.0),
        ]
    };
    let mut missed = Vec::new();
    for k in 0..1500 {
        // A 5 cm shift in 100 ms, then still.
        let x = 0.05 * min_jerk(f64::from(k) * DT / 0.1);
        o.felt_eyes(&p, eyes(x), DT);
        missed.push(o.missed().x);
    }
    let full = (1.0 - p.tvor_gain) * 0.05;
    let peak = missed.iter().fold(0.0f64, |m, &v| m.max(v));
    // Nothing is taken up before vision sees it (100 ms + 19 ms).
    assert!(peak > 0.95 * full, "peak {peak} of {full}");
    assert!(missed[1499].abs() < 0.02 * full, "left {}", missed[1499]);
    let under = missed.iter().fold(0.0f64, |m, &v| m.min(v));
    assert!(under > -0.1 * full, "overshoot {under}");
}

#[test]
fn counter_roll_follows_a_roll_dynamically_and_holds_a_tenth_of_a_tilt() {
    let p = OtolithParams::default();
    let mut o = Otolith::default();
    let roll_at = |t: f64| 10f64.to_radians() * (std::f64::consts::TAU * t).sin();
    // 1 Hz, +-10 deg roll: the torsion swings against it by 40-70 %.
    let mut swing = 0.0f64;
    for k in 0..3000 {
        let t = f64::from(k) * DT;
        let rate = (roll_at(t + DT) - roll_at(t)) / DT;
        let tau = o.counter_roll(&p, DQuat::from_rotation_z(roll_at(t)), DVec3::Z * rate, DT);
        if t > 1.0 {
            swing = swing.max(-tau * roll_at(t).signum());
        }
    }
    let gain = swing / 10f64.to_radians();
    assert!((0.3..=0.7).contains(&gain), "dynamic gain {gain}");
    // A held 20 deg tilt: about 10 % of it stays (Collewijn et al. 1985).
    let mut tau = 0.0;
    for _ in 0..3000 {
        tau = o.counter_roll(&p, DQuat::from_rotation_z(0.35), DVec3::ZERO, DT);
    }
    assert!(
        (tau / -0.35 - 0.1).abs() < 0.01,
        "static share {}",
        tau / -0.35
    );
    assert_eq!(
        Otolith::default().counter_roll(
            &OtolithParams::seed(),
            DQuat::from_rotation_z(0.3),
            DVec3::Z,
            DT
        ),
        0.0
    );
}
