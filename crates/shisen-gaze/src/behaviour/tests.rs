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
