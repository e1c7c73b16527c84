use super::*;

fn seen(body: usize, position: DVec3, velocity: DVec3) -> Seen {
    Seen {
        body: BodyId::new(body),
        position,
        velocity,
        ..Seen::test_default()
    }
}

#[test]
fn aimed_glove_test_follows_the_three_rules() {
    let p = BehaviourParams::default();
    let head = DVec3::new(0.0, 1.68, 0.0);
    let vh_points = [head, DVec3::new(0.0, 1.25, 0.0), DVec3::new(0.0, 1.4, 0.0)];
    let glove = DVec3::new(-0.1, 1.6, 0.7);
    let towards = (head - glove).normalize();
    let check = |v: DVec3| {
        let s = [seen(5, glove, v)];
        let names: Vec<String> = (0..7).map(|i| format!("b{i}")).collect();
        let view = OpponentView {
            seen: &s,
            names: &names,
            eyes_on: None,
            parts: [4, 5, 6].map(BodyId::new),
            vh_points,
        };
        aimed_glove(&p, &view)
    };
    assert!(check(towards * 4.0).is_some(), "fast and aimed");
    assert!(check(towards * 1.5).is_none(), "too slow");
    let sideways = DVec3::new(1.0, 0.0, -0.3).normalize() * 4.0;
    assert!(check(sideways).is_none(), "not aimed");
    // 0.7 m at 1.2 m/s... slow; at 2.1 m/s ttc = 0.34 s < 0.5: aimed
    assert!(check(towards * 2.1).is_some());
    let (_, point, ttc) = check(towards * 4.0).unwrap();
    assert!((point - (glove + towards * 4.0 * 0.4 * ttc)).length() < 1e-9);
}

/// The planner alone for `secs` at 1 kHz against a still opponent whose
/// head is `range` m in front (gloves at its sides), attacking eagerly
/// with every attack a combination: each punch's throw time and the
/// trunk's travel toward the opponent at that punch's peak.
fn punches_at(range: f64, secs: f64) -> Vec<(f64, f64)> {
    use rand::SeedableRng;
    let head = DVec3::new(0.0, 1.68, range);
    let s = [
        seen(4, head, DVec3::ZERO),
        seen(5, head + DVec3::new(0.25, -0.3, -0.1), DVec3::ZERO),
        seen(6, head + DVec3::new(-0.25, -0.3, -0.1), DVec3::ZERO),
    ];
    let names: Vec<String> = (0..7).map(|i| format!("b{i}")).collect();
    let view = OpponentView {
        seen: &s,
        names: &names,
        eyes_on: None,
        parts: [4, 5, 6].map(BodyId::new),
        vh_points: [
            DVec3::new(0.0, 1.68, 0.0),
            DVec3::new(0.0, 1.25, 0.0),
            DVec3::new(0.0, 1.4, 0.0),
        ],
    };
    let p = BehaviourParams {
        attack_rate: 2.0,
        combination: 1.0,
        ..BehaviourParams::default()
    };
    let pers = Personality::default();
    let mut b = Behaviour::new();
    let mut rng = rand::rngs::StdRng::seed_from_u64(5);
    let dt = 0.001;
    let half = 0.5 * p.punch_time;
    let mut thrown: Vec<(f64, f64)> = Vec::new();
    for i in 0..(secs / dt) as usize {
        let t = i as f64 * dt;
        let n = b.punches_thrown;
        b.step(&p, &pers, &view, t, dt, &mut rng);
        if b.punches_thrown > n {
            thrown.push((t, f64::NAN));
        }
        for (at, travel) in &mut thrown {
            if travel.is_nan() && t >= *at + half {
                *travel = b.torso_offset(t).z;
            }
        }
    }
    thrown.retain(|(_, travel)| !travel.is_nan());
    thrown
}

#[test]
fn every_punch_of_a_combination_carries_the_trunk_to_its_target() {
    // 0.95 m: a straight arm falls short by about the whole lunge.
    let punches = punches_at(0.95, 4.0);
    assert!(punches.len() >= 4, "{punches:?}");
    for (t, travel) in &punches {
        // The punch before's travel is back by the next's peak; each
        // punch has its own, the follow-ups as the first.
        assert!(*travel > 0.25, "punch at {t:.3} s: trunk {travel:.3} m");
    }
}

#[test]
fn a_punch_waits_for_its_target_to_come_within_reach() {
    // Out of reach even with a step and a lunge, and this body never
    // gets there (no physics moves the trunk): the planner steps in and
    // calls the attack off, rather than punch the air.
    assert_eq!(punches_at(2.5, 4.0), vec![]);
    // In reach: punches flow.
    assert!(!punches_at(0.8, 4.0).is_empty());
}
