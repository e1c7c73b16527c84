//! Step and trajectory experiments on one joint group in the physics (no
//! brain): the reference motions, the response, its metrics, CSV and plot.

use std::path::Path;

use glam::DVec2;
use serde::Serialize;

use crate::physics::body::{BodyPlan, Group};
use crate::physics::control::{Gains, JointTarget};
use crate::physics::neck::{NeckParams, NeckState};
use crate::physics::world::World;
use crate::tools::metrics::{Instability, StepMetrics, instability, step_metrics, tracking_error};
use crate::tools::plot::{Panel, Series, Stroke, chart};
use shisen_gaze::oculomotor::AxisCommand;
use shisen_gaze::oculomotor::head::HeadParams;
use shisen_gaze::oculomotor::saccade::{SaccadeParams, SaccadeProfile};

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

impl std::fmt::Display for Experiment {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            Experiment::Step { amplitude_deg } => write!(f, "step {amplitude_deg} deg"),
            Experiment::Saccade { amplitude_deg } => write!(f, "saccade {amplitude_deg} deg"),
            Experiment::MinJerk { amplitude_deg } => write!(f, "min-jerk {amplitude_deg} deg"),
            Experiment::Ramp { rate_deg_s } => write!(f, "ramp {rate_deg_s} deg/s"),
        }
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
        // Tracking errors are measured on trajectories only; a step has none.
        let deg = |x: f64| {
            if x.is_nan() {
                format!("{:>6}    ", "-")
            } else {
                format!("{x:>6.3} deg")
            }
        };
        format!(
            "{:<20} rise {:>6.1} ms  overshoot {:>5.1} %  settle {:>6.1} ms  sse {:>6.3} deg  rms {}  peak {}  {stab}",
            self.experiment.to_string(),
            self.rise_time * 1e3,
            self.overshoot * 100.0,
            self.settling_time * 1e3,
            self.steady_state_deg,
            deg(self.rms_deg),
            deg(self.peak_deg)
        )
    }
}

/// Run one experiment on a group with `gains`, at step `dt`. Every other
/// joint holds its rest pose; the group's left joint follows the reference
/// on its main axis (plus a 0.1 s lead-in and a hold afterwards).
pub fn run(group: Group, exp: Experiment, gains: &Gains, dt: f64) -> Response {
    let mut world = World::new(BodyPlan::default(), dt);
    let joint = group.joint();
    let axis = group.main_axis();
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
        targets[joint.index()] = JointTarget::yaw_pitch(c.angles, c.rates, c.accel);
        // The PD law itself is what is tuned: the neck unbounded.
        world.apply_control(
            gains,
            &targets,
            (&NeckParams::stiff(), &NeckState::default()),
        );
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
            let mv =
                shisen_gaze::oculomotor::head::HeadMove::plan(&hp, DVec2::ZERO, DVec2::new(a, 0.0));
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
