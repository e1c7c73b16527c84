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

/// The planner alone with `p` for `secs` at 1 kHz against a still
/// opponent whose head is `range` m in front (gloves at its sides),
/// calling `each` after every tick.
fn run_plan(p: &BehaviourParams, range: f64, secs: f64, mut each: impl FnMut(&Behaviour, f64)) {
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
    let pers = Personality::default();
    let mut b = Behaviour::new();
    let mut rng = rand::rngs::StdRng::seed_from_u64(5);
    let dt = 0.001;
    for i in 0..(secs / dt) as usize {
        let t = i as f64 * dt;
        b.step(p, &pers, &view, t, dt, &mut rng);
        each(&b, t);
    }
}

/// An eager attacker whose every attack is a combination.
fn eager() -> BehaviourParams {
    BehaviourParams {
        attack_rate: 2.0,
        combination: 1.0,
        ..BehaviourParams::default()
    }
}

/// Each punch's throw time and the trunk's travel toward the opponent at
/// that punch's peak, over `secs` against a head `range` m away.
fn punches_at(range: f64, secs: f64) -> Vec<(f64, f64)> {
    let p = eager();
    let half = 0.5 * p.punch_time;
    let mut thrown: Vec<(f64, f64)> = Vec::new();
    let mut n = 0;
    run_plan(&p, range, secs, |b, t| {
        if b.punches_thrown > n {
            n = b.punches_thrown;
            thrown.push((t, f64::NAN));
        }
        for (at, travel) in &mut thrown {
            if travel.is_nan() && t >= *at + half {
                *travel = b.torso_offset(t).z;
            }
        }
    });
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

#[test]
fn a_feint_is_a_punch_s_start_without_the_punch() {
    // Every attack a feint, none followed by a punch.
    let p = BehaviourParams {
        feint: 1.0,
        combination: 0.0,
        ..eager()
    };
    let (mut feinting, mut reach, mut punches, mut feints) = (0, 0.0_f64, 0, 0);
    run_plan(&p, 0.8, 4.0, |b, t| {
        if b.action() == ActionKind::Feint {
            feinting += 1;
            reach = reach.max(b.torso_offset(t).z);
        }
        (punches, feints) = (b.punches_thrown, b.feints);
    });
    assert_eq!(punches, 0);
    assert!(feints >= 3, "{feints} feints");
    // The shoulder goes a few centimetres toward the head, not a punch's
    // lunge.
    assert!((0.05..0.1).contains(&reach), "trunk travel {reach}");
    assert!(feinting >= 3 * 250, "{feinting} ms feinting");
    // With a combination's chance 1 the real punch follows each feint.
    let p = BehaviourParams {
        feint: 1.0,
        ..eager()
    };
    let mut after = (0, 0);
    run_plan(&p, 0.8, 4.0, |b, _| after = (b.feints, b.punches_thrown));
    assert!(after.0 >= 2 && after.1 >= after.0, "{after:?}");
}
