//! Automatic tuning reaches the objective from deliberately bad gains, for
//! the eyes and the neck; the test prints before and after.

use shisen::physics::body::Group;
use shisen::physics::control::{Gains, JointGains};
use shisen::tools::tune::{auto_tune, initial_guess, score};

fn check(group: Group, name: &str, bad: JointGains) {
    let mut base = Gains::default();
    *base.group_mut(group) = bad;
    let before = score(group, &base, 0.001);
    let history = auto_tune(group, &base, bad, 0.001, 150);
    let after = history.last().unwrap();
    println!(
        "{group:?} from {name} gains (kp {:.3e}, kd {:.3e}): cost {:.2}{} -> kp {:.3e}, kd {:.3e}, cost {:.3}; {}; {}",
        bad.kp,
        bad.kd,
        before.cost,
        if before.meets {
            ""
        } else {
            " (objective not met)"
        },
        after.gains.kp,
        after.gains.kd,
        after.score.cost,
        after.score.trajectory.line(),
        after.score.step.line()
    );
    assert!(!before.meets, "the bad gains were not bad");
    assert!(after.score.meets, "objective not reached");
}

#[test]
fn eyes_and_neck_tune_from_too_soft_and_too_stiff() {
    for group in [Group::Eye, Group::Neck] {
        let g = initial_guess(group);
        let soft = JointGains {
            kp: g.kp / 30.0,
            kd: g.kd / 30.0,
            feedforward: 1.0,
        };
        let stiff = JointGains {
            kp: g.kp * 10.0,
            kd: g.kd / 8.0,
            feedforward: 1.0,
        };
        check(group, "too soft", soft);
        check(group, "too stiff, oscillating", stiff);
    }
}
