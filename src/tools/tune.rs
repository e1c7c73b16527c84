//! PD gain tuning: step and trajectory experiments on one joint group in
//! the physics (no brain), their metrics (one code path: [`crate::tools::metrics`]),
//! a physically based starting guess, automatic improvement against a
//! stated objective, and parallel sweeps.

use std::path::Path;

use glam::{DVec2, Vec3};
use rayon::prelude::*;
use serde::Serialize;

use crate::agent::oculomotor::AxisCommand;
use crate::agent::oculomotor::head::HeadParams;
use crate::agent::oculomotor::saccade::{SaccadeParams, SaccadeProfile};
use crate::physics::body::{BodyPlan, Group, seg};
use crate::physics::control::{Gains, JointGains, JointTarget};
use crate::physics::world::World;
use crate::tools::metrics::{Instability, StepMetrics, instability, step_metrics, tracking_error};
use crate::tools::plot::{Panel, Series, Stroke, chart};

/// A reference motion for one joint, on its main axis.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub enum Experiment {
    /// A step of the target (no velocity reference), degrees.
    Step {
        /// Step size, deg.
        amplitude_deg: f64,
    },
    /// The planned saccade of this amplitude (M2-M6), degrees.
    Saccade {
        /// Amplitude, deg.
        amplitude_deg: f64,
    },
    /// A minimum-jerk head-style move (M9 with Pejsa's duration), degrees.
    MinJerk {
        /// Amplitude, deg.
        amplitude_deg: f64,
    },
    /// A constant-velocity ramp (pursuit), deg/s, for 0.4 s.
    Ramp {
        /// Rate, deg/s.
        rate_deg_s: f64,
    },
}

/// The joint a group is tuned on and its main axis.
fn joint_of(group: Group) -> usize {
    match group {
        Group::Eye => seg::EYE_L,
        Group::Neck => seg::HEAD,
        Group::Shoulder => seg::UPPER_ARM_L,
        Group::Elbow => seg::FOREARM_L,
    }
}

/// Angle on the group's main axis: yaw for the eyes; pitch for the neck
/// (its larger, gravity-loaded inertia: yaw, 8x lighter, is then simply
/// better damped) and flexion for shoulder and elbow.
fn main_axis(group: Group) -> usize {
    match group {
        Group::Eye => 0,
        Group::Neck | Group::Shoulder | Group::Elbow => 1,
    }
}

/// One experiment's record: time, reference and measured angle (rad).
#[derive(Clone, Debug, Default)]
pub struct Response {
    /// Sample times, s (from the start of the motion).
    pub t: Vec<f64>,
    /// Reference angle, rad.
    pub reference: Vec<f64>,
    /// Measured angle, rad.
    pub actual: Vec<f64>,
}

/// Metrics of one experiment.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Report {
    /// The experiment.
    pub experiment: Experiment,
    /// Step metrics (steps only): rise s, overshoot fraction, settling s, sse rad.
    pub rise_time: f64,
    /// Overshoot fraction (steps), or of the final value (trajectories).
    pub overshoot: f64,
    /// 2 % settling time, s (NaN if it never settles).
    pub settling_time: f64,
    /// Steady-state error, deg.
    pub steady_state_deg: f64,
    /// RMS tracking error against the reference, deg.
    pub rms_deg: f64,
    /// Peak tracking error, deg.
    pub peak_deg: f64,
    /// Instability found, if any.
    #[serde(skip)]
    pub unstable: Option<Instability>,
}

impl Report {
    /// A one-line summary.
    pub fn line(&self) -> String {
        let stab = match self.unstable {
            None => "stable".to_string(),
            Some(i) => format!("UNSTABLE ({i:?})"),
        };
        format!(
            "{:<34} rise {:>6.1} ms  overshoot {:>5.1} %  settle {:>6.1} ms  sse {:>6.3} deg  rms {:>6.3} deg  peak {:>6.3} deg  {stab}",
            format!("{:?}", self.experiment),
            self.rise_time * 1e3,
            self.overshoot * 100.0,
            self.settling_time * 1e3,
            self.steady_state_deg,
            self.rms_deg,
            self.peak_deg
        )
    }
}

/// Run one experiment on a group with `gains`, at step `dt`. Every other
/// joint holds its rest pose; the group's left joint follows the reference
/// on its main axis (plus a 0.1 s lead-in and a hold afterwards).
pub fn run(group: Group, exp: Experiment, gains: &Gains, dt: f64) -> Response {
    let mut world = World::new(BodyPlan::default(), dt);
    let joint = joint_of(group);
    let axis = main_axis(group);
    let n = world.plan.segments.len();
    let mut targets = vec![JointTarget::default(); n];
    let reference = reference_fn(exp);
    let (lead, total) = (0.1, 0.1 + reference.1 + 0.4);
    let steps = (total / dt).round() as usize;
    let mut r = Response::default();
    for i in 0..steps {
        let t = i as f64 * dt;
        let s = t - lead;
        let cmd = if s < 0.0 {
            AxisCommand::default()
        } else {
            (reference.0)(s)
        };
        let mut c = cmd;
        if axis == 1 {
            c.angles = DVec2::new(0.0, cmd.angles.x);
            c.rates = DVec2::new(0.0, cmd.rates.x);
            c.accel = DVec2::new(0.0, cmd.accel.x);
        }
        targets[joint] = JointTarget::yaw_pitch(c.angles, c.rates, c.accel);
        world.apply_control(gains, &targets);
        world.step();
        if s >= 0.0 {
            let a = world.joint_angles(joint);
            let v = if axis == 0 { a.yaw } else { a.pitch };
            r.t.push(s + dt);
            r.reference.push(((reference.0)(s + dt)).angles.x);
            r.actual.push(v);
        }
    }
    r
}

/// The reference command as a function of time, and the motion's length.
type Reference = (Box<dyn Fn(f64) -> AxisCommand>, f64);

fn reference_fn(exp: Experiment) -> Reference {
    let one = |a: f64, v: f64, acc: f64| AxisCommand {
        angles: DVec2::new(a, 0.0),
        rates: DVec2::new(v, 0.0),
        accel: DVec2::new(acc, 0.0),
    };
    match exp {
        Experiment::Step { amplitude_deg } => {
            let a = amplitude_deg.to_radians();
            (Box::new(move |_| one(a, 0.0, 0.0)), 0.0)
        }
        Experiment::Saccade { amplitude_deg } => {
            let p = SaccadeProfile::plan(&SaccadeParams::default(), amplitude_deg.to_radians());
            let d = p.duration();
            (
                Box::new(move |t| one(p.position(t), p.velocity(t), p.acceleration(t))),
                d,
            )
        }
        Experiment::MinJerk { amplitude_deg } => {
            let a = amplitude_deg.to_radians();
            let hp = HeadParams::default();
            let mv = crate::agent::oculomotor::head::HeadMove::plan(
                &hp,
                DVec2::ZERO,
                DVec2::new(a, 0.0),
            );
            let d = mv.duration();
            (
                Box::new(move |t| {
                    let s = mv.sample(t);
                    one(s.angles.x, s.rate.x, s.accel.x)
                }),
                d,
            )
        }
        Experiment::Ramp { rate_deg_s } => {
            let w = rate_deg_s.to_radians();
            (
                Box::new(move |t| {
                    let t = t.min(0.4);
                    one(w * t, if t < 0.4 { w } else { 0.0 }, 0.0)
                }),
                0.4,
            )
        }
    }
}

/// Metrics of a response (one code path with the CLI, tests and panel).
pub fn evaluate(exp: Experiment, r: &Response) -> Report {
    let target = *r.reference.last().unwrap_or(&0.0);
    let step = target - r.actual.first().copied().unwrap_or(0.0);
    let unstable = instability(&r.actual, target, step.abs().max(1e-3));
    let (rms, peak) = tracking_error(&r.reference, &r.actual);
    let m = if r.t.is_empty() || unstable.is_some() {
        StepMetrics {
            rise_time: f64::NAN,
            overshoot: f64::NAN,
            settling_time: f64::NAN,
            steady_state_error: f64::NAN,
        }
    } else {
        step_metrics(&r.t, &r.actual, target)
    };
    let is_step = matches!(exp, Experiment::Step { .. });
    Report {
        experiment: exp,
        rise_time: m.rise_time,
        overshoot: m.overshoot,
        settling_time: m.settling_time,
        steady_state_deg: m.steady_state_error.to_degrees(),
        // A step's reference is the target itself: its "tracking error" is
        // the response, so only trajectories report RMS and peak.
        rms_deg: if is_step { f64::NAN } else { rms.to_degrees() },
        peak_deg: if is_step { f64::NAN } else { peak.to_degrees() },
        unstable,
    }
}

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

/// The effective inertia of a group's joint about its main axis at rest,
/// kg m^2 (from the physics model's mass properties).
pub fn effective_inertia(group: Group) -> f64 {
    let world = World::new(BodyPlan::default(), 0.001);
    let j = joint_of(group);
    let i = world.subtree_inertia(j, world.pivot(j));
    let axis = if main_axis(group) == 0 {
        Vec3::Y
    } else {
        Vec3::X
    };
    (axis.dot(i * axis)) as f64
}

/// The physically based starting guess: critically damped gains for the
/// group's target bandwidth on its effective inertia.
pub fn initial_guess(group: Group) -> JointGains {
    static GUESS: std::sync::OnceLock<Vec<JointGains>> = std::sync::OnceLock::new();
    let all = GUESS.get_or_init(|| {
        Group::ALL
            .iter()
            .map(|&g| {
                // Target bandwidths: eyes fast (saccades), neck and arms slower.
                let omega = match g {
                    Group::Eye => 300.0,
                    Group::Neck => 40.0,
                    Group::Shoulder => 25.0,
                    Group::Elbow => 30.0,
                };
                JointGains::from_bandwidth(effective_inertia(g), omega, 1.0)
            })
            .collect()
    });
    all[Group::ALL.iter().position(|&g| g == group).expect("group")]
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

/// Write a response as CSV (`t,reference_deg,actual_deg`).
pub fn write_response_csv(path: &Path, r: &Response) -> std::io::Result<()> {
    let mut out = String::from("t,reference_deg,actual_deg\n");
    for i in 0..r.t.len() {
        out.push_str(&format!(
            "{:.4},{:.5},{:.5}\n",
            r.t[i],
            r.reference[i].to_degrees(),
            r.actual[i].to_degrees()
        ));
    }
    std::fs::write(path, out)
}

/// Plot a group's trajectory and step responses (reference dashed).
pub fn plot_responses(
    path: &Path,
    group: Group,
    runs: &[(Experiment, Response)],
) -> anyhow::Result<()> {
    let panels: Vec<Panel> = runs
        .iter()
        .map(|(e, r)| {
            let pts = |v: &[f64]| {
                r.t.iter()
                    .zip(v)
                    .map(|(t, y)| (*t, y.to_degrees()))
                    .collect()
            };
            Panel {
                title: format!("{group:?}: {e:?}"),
                y_label: "deg".into(),
                series: vec![
                    Series {
                        label: "reference".into(),
                        points: pts(&r.reference),
                        style: Stroke::Dashed,
                    },
                    Series {
                        label: "joint".into(),
                        points: pts(&r.actual),
                        style: Stroke::Solid,
                    },
                ],
            }
        })
        .collect();
    chart(
        path,
        (1200, 400 * panels.len() as u32),
        "time (s)",
        &panels,
        &[],
    )
}

/// One run of a sweep.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SweepPoint {
    /// Run number (stable across resumes).
    pub id: usize,
    /// Proportional gain.
    pub kp: f64,
    /// Derivative gain.
    pub kd: f64,
    /// Step size, s.
    pub dt: f64,
}

/// The points of a sweep around the physically based guess: a grid
/// (`grid = true`: kp x kd x dt) or seeded random samples, `runs` of them.
/// kp and kd range over a factor 5 either side of the guess (log scale);
/// dt over 0.5, 1 and 2 ms.
pub fn sweep_points(group: Group, runs: usize, grid: bool, seed: u64) -> Vec<SweepPoint> {
    use rand::{RngExt, SeedableRng};
    let g = initial_guess(group);
    let dts = [0.0005, 0.001, 0.002];
    let span = 5f64.ln();
    if grid {
        let per = ((runs as f64 / dts.len() as f64).sqrt().ceil() as usize).max(2);
        let lin = |i: usize| -span + 2.0 * span * i as f64 / (per - 1) as f64;
        let mut v = Vec::new();
        for &dt in &dts {
            for i in 0..per {
                for j in 0..per {
                    v.push(SweepPoint {
                        id: v.len(),
                        kp: g.kp * lin(i).exp(),
                        kd: g.kd * lin(j).exp(),
                        dt,
                    });
                }
            }
        }
        v
    } else {
        let mut rng = rand::rngs::StdRng::seed_from_u64(seed);
        (0..runs)
            .map(|id| SweepPoint {
                id,
                kp: g.kp * rng.random_range(-span..span).exp(),
                kd: g.kd * rng.random_range(-span..span).exp(),
                dt: dts[rng.random_range(0..dts.len())],
            })
            .collect()
    }
}

/// Run a sweep in parallel on all cores, appending one CSV row per run to
/// `csv` (resumable: runs already in the file are skipped), with a progress
/// bar. Returns every row (old and new) as (point, score cost, meets).
pub fn sweep(
    group: Group,
    points: &[SweepPoint],
    base: &Gains,
    csv: &Path,
) -> anyhow::Result<Vec<(SweepPoint, f64, bool)>> {
    use std::io::Write;
    let mut done = std::collections::BTreeMap::new();
    if let Ok(text) = std::fs::read_to_string(csv) {
        for line in text.lines().skip(1) {
            let f: Vec<&str> = line.split(',').collect();
            if let [id, kp, kd, dt, cost, meets, ..] = f[..]
                && let (Ok(id), Ok(kp), Ok(kd), Ok(dt), Ok(cost)) = (
                    id.parse(),
                    kp.parse(),
                    kd.parse(),
                    dt.parse(),
                    cost.parse::<f64>(),
                )
            {
                done.insert(id, (SweepPoint { id, kp, kd, dt }, cost, meets == "1"));
            }
        }
    }
    let fresh = !csv.exists();
    let file = std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(csv)?;
    let file = std::sync::Mutex::new(std::io::BufWriter::new(file));
    if fresh {
        writeln!(
            file.lock().expect("lock"),
            "id,kp,kd,dt,cost,meets,traj_rms_deg,step_overshoot,step_settling_s"
        )?;
    }
    let todo: Vec<SweepPoint> = points
        .iter()
        .copied()
        .filter(|p| !done.contains_key(&p.id))
        .collect();
    let bar = indicatif::ProgressBar::new(todo.len() as u64);
    bar.set_style(
        indicatif::ProgressStyle::with_template(
            "{bar:40} {pos}/{len} runs, {elapsed} elapsed, eta {eta}",
        )
        .expect("template"),
    );
    let rows: Vec<(SweepPoint, f64, bool)> = todo
        .par_iter()
        .map(|p| {
            let mut g = base.clone();
            *g.group_mut(group) = JointGains {
                kp: p.kp,
                kd: p.kd,
                feedforward: base.group(group).feedforward,
            };
            let s = score(group, &g, p.dt);
            let line = format!(
                "{},{:.6e},{:.6e},{},{:.5},{},{:.5},{:.5},{:.5}",
                p.id,
                p.kp,
                p.kd,
                p.dt,
                s.cost,
                u8::from(s.meets),
                s.trajectory.rms_deg,
                s.step.overshoot,
                s.step.settling_time
            );
            let _ = writeln!(file.lock().expect("lock"), "{line}");
            bar.inc(1);
            (*p, s.cost, s.meets)
        })
        .collect();
    bar.finish();
    file.into_inner().expect("lock").flush()?;
    let mut all: Vec<_> = done.into_values().chain(rows).collect();
    all.sort_by_key(|r| r.0.id);
    Ok(all)
}

/// Plot a sweep: cost against kp (one dot series per dt), log-kp axis.
pub fn plot_sweep(
    path: &Path,
    group: Group,
    rows: &[(SweepPoint, f64, bool)],
) -> anyhow::Result<()> {
    let mut dts: Vec<f64> = rows.iter().map(|r| r.0.dt).collect();
    dts.sort_by(f64::total_cmp);
    dts.dedup();
    let series = dts
        .iter()
        .map(|&dt| Series {
            label: format!("dt {} ms", dt * 1e3),
            points: rows
                .iter()
                .filter(|r| r.0.dt == dt && r.1.is_finite())
                .map(|r| (r.0.kp.log10(), r.1.min(20.0)))
                .collect(),
            style: Stroke::Dots,
        })
        .collect();
    chart(
        path,
        (1200, 600),
        "log10 kp",
        &[Panel {
            title: format!("{group:?} gain sweep: cost (unstable runs omitted)"),
            y_label: "cost".into(),
            series,
        }],
        &[],
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_gains_meet_the_eye_objective() {
        let s = score(Group::Eye, &Gains::default(), 0.001);
        assert!(s.meets, "{}\n{}", s.trajectory.line(), s.step.line());
    }

    #[test]
    fn effective_inertia_of_the_eye_is_a_solid_sphere() {
        let i = effective_inertia(Group::Eye);
        let expect = 0.4 * 0.0075 * 0.011 * 0.011;
        assert!((i - expect).abs() / expect < 1e-3, "{i}");
    }
}
