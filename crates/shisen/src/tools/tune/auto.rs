//! Tuning objectives, a physically based first guess and automatic
//! improvement of one group's gains.

use rayon::prelude::*;

use super::experiment::*;
use crate::physics::body::Group;
use crate::physics::control::{Gains, JointGains};

/// The tuning objective of a group: the trajectory it must track and the
/// bounds (RMS tracking error, step overshoot).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Objective {
    /// The trajectory experiment.
    pub trajectory: Experiment,
    /// Maximum RMS tracking error, deg.
    pub max_rms_deg: f64,
    /// The step experiment.
    pub step: Experiment,
    /// Maximum step overshoot, fraction.
    pub max_overshoot: f64,
    /// Maximum 2 % settling time of the step, s.
    pub max_settling: f64,
}

impl Objective {
    /// The stated objective per group: eyes track a 20 deg saccade with RMS
    /// < 0.5 deg and a 10 deg step settles within 40 ms with < 5 %
    /// overshoot; the neck tracks a 30 deg minimum-jerk pitch move with RMS
    /// < 0.5 deg and a 20 deg step settles within 300 ms with < 5 %
    /// overshoot; the arms track 30 deg moves with RMS < 1 deg and settle
    /// 20 deg steps within 350 ms with < 5 % overshoot.
    pub fn for_group(g: Group) -> Objective {
        match g {
            Group::Eye => Objective {
                trajectory: Experiment::Saccade {
                    amplitude_deg: 20.0,
                },
                max_rms_deg: 0.5,
                step: Experiment::Step {
                    amplitude_deg: 10.0,
                },
                max_overshoot: 0.05,
                max_settling: 0.040,
            },
            Group::Neck => Objective {
                trajectory: Experiment::MinJerk {
                    amplitude_deg: 30.0,
                },
                max_rms_deg: 0.5,
                step: Experiment::Step {
                    amplitude_deg: 20.0,
                },
                max_overshoot: 0.05,
                max_settling: 0.300,
            },
            Group::Shoulder | Group::Elbow => Objective {
                trajectory: Experiment::MinJerk {
                    amplitude_deg: 30.0,
                },
                max_rms_deg: 1.0,
                step: Experiment::Step {
                    amplitude_deg: 20.0,
                },
                max_overshoot: 0.05,
                max_settling: 0.350,
            },
        }
    }
}

/// How a set of gains does against an objective.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Score {
    /// Trajectory metrics.
    pub trajectory: Report,
    /// Step metrics.
    pub step: Report,
    /// Scalar cost (lower is better; infinite when unstable).
    pub cost: f64,
    /// Whether all three bounds hold.
    pub meets: bool,
}

/// Evaluate `gains` for `group` against its objective at step `dt`.
pub fn score(group: Group, gains: &Gains, dt: f64) -> Score {
    let o = Objective::for_group(group);
    let tr = evaluate(o.trajectory, &run(group, o.trajectory, gains, dt));
    let st = evaluate(o.step, &run(group, o.step, gains, dt));
    let unstable = tr.unstable.is_some() || st.unstable.is_some();
    // The worst of the normalised bounds (below 1 meets all three), floored
    // at 0.7 (a 30 % margin is good enough), plus a small pull toward the
    // physically based gains: among gains that meet the objective with
    // margin, the search prefers the least stiff, not the fastest at the
    // edge of the explicit-integration stability bound.
    let worst = if unstable {
        f64::INFINITY
    } else {
        let settle = if st.settling_time.is_finite() {
            st.settling_time
        } else {
            10.0
        };
        (tr.rms_deg / o.max_rms_deg)
            .max(st.overshoot / o.max_overshoot)
            .max(settle / o.max_settling)
    };
    let guess = initial_guess(group);
    let g = gains.group(group);
    let stiffness = (g.kp / guess.kp).ln().abs() + (g.kd / guess.kd).ln().abs();
    let cost = worst.max(0.7) + 0.02 * stiffness;
    let meets = worst < 1.0;
    Score {
        trajectory: tr,
        step: st,
        cost,
        meets,
    }
}

/// The physically based starting guess: critically damped gains for the
/// group's target bandwidth on its effective inertia.
pub fn initial_guess(group: Group) -> JointGains {
    static GUESS: std::sync::OnceLock<[JointGains; 4]> = std::sync::OnceLock::new();
    let all = GUESS.get_or_init(|| {
        Group::ALL.map(|g| {
            // Target bandwidths: eyes fast (saccades), neck and arms slower.
            let omega = match g {
                Group::Eye => 300.0,
                Group::Neck => 40.0,
                Group::Shoulder => 25.0,
                Group::Elbow => 30.0,
            };
            JointGains::from_bandwidth(crate::physics::plausible::group_inertia(g), omega, 1.0)
        })
    });
    all[group.index()]
}

/// One tuning iteration's record.
#[derive(Clone, Copy, Debug)]
pub struct TuneStep {
    /// The gains tried.
    pub gains: JointGains,
    /// Their score.
    pub score: Score,
}

/// Improve a group's gains from `start` (or from the physically based
/// guess, if that scores better) by a pattern search in (log kp, log kd)
/// (neighbours evaluated in parallel) until no neighbour improves the cost
/// at the finest step, or `max_evals` evaluations are spent. Returns the
/// history: the first entry is `start`, the last the best.
pub fn auto_tune(
    group: Group,
    base: &Gains,
    start: JointGains,
    dt: f64,
    max_evals: usize,
) -> Vec<TuneStep> {
    let eval = |g: JointGains| {
        let mut all = base.clone();
        *all.group_mut(group) = g;
        TuneStep {
            gains: g,
            score: score(group, &all, dt),
        }
    };
    // Start from the better of the given gains and the physically based
    // guess: the explicit-PD landscape is rough where omega_n dt nears 1,
    // so a search started deep in it can stall on a local minimum.
    let first = eval(start);
    let guess = eval(initial_guess(group));
    let mut history = vec![first];
    let mut best = first;
    if guess.score.cost < first.score.cost {
        best = guess;
        history.push(guess);
    }
    let mut step = 1.0f64; // natural-log step: a factor e per move
    let mut evals = 2;
    while evals < max_evals && step > 0.02 {
        // The 8 neighbours in (log kp, log kd): axis moves, and diagonals
        // that keep or change the damping ratio (zeta ~ kd / sqrt(kp)).
        let candidates: Vec<JointGains> = [
            (1.0, 0.0),
            (-1.0, 0.0),
            (0.0, 1.0),
            (0.0, -1.0),
            (1.0, 0.5),
            (-1.0, -0.5),
            (-1.0, 0.5),
            (1.0, -0.5),
        ]
        .iter()
        .map(|(a, b)| JointGains {
            kp: best.gains.kp * (a * step).exp(),
            kd: best.gains.kd * (b * step).exp(),
            feedforward: best.gains.feedforward,
        })
        .collect();
        evals += candidates.len();
        let tried: Vec<TuneStep> = candidates.into_par_iter().map(eval).collect();
        let winner = tried
            .into_iter()
            .min_by(|a, b| a.score.cost.total_cmp(&b.score.cost))
            .expect("candidates");
        if winner.score.cost < best.score.cost - 1e-9 {
            best = winner;
            history.push(best);
        } else {
            step *= 0.5;
        }
    }
    history
}
