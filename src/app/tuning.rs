//! The step-response test of the gains panel: one joint of a group is
//! asked for a step while everything else holds its rest pose, in a fresh
//! physics world with the gains under test; [`step_metrics`] judges it.

use crate::body::{BodyPlan, Group, seg};
use crate::control::{Gains, JointTarget};
use crate::metrics::{StepMetrics, step_metrics};
use crate::sim::{DT, hold};
use crate::world::{JointAngles, World};

/// Settling before the step, s.
const SETTLE_S: f64 = 0.2;
/// Recorded response, s.
const RECORD_S: f64 = 0.8;

/// A measured step response.
#[derive(Clone, Debug, PartialEq)]
pub struct StepResponse {
    /// Which group.
    pub group: Group,
    /// What was stepped ("left eye yaw", ...).
    pub what: &'static str,
    /// Time since the step, s.
    pub t: Vec<f64>,
    /// Joint angle, degrees.
    pub y: Vec<f64>,
    /// Step target, degrees.
    pub target: f64,
    /// Rise, overshoot, settling.
    pub metrics: StepMetrics,
}

/// The joint, axis (true: yaw, false: pitch) and step size (deg) tested for a group.
fn probe(group: Group) -> (usize, bool, f64, &'static str) {
    match group {
        Group::Eye => (seg::EYE_L, true, 10.0, "left eye yaw"),
        Group::Neck => (seg::HEAD, true, 20.0, "neck yaw"),
        Group::Shoulder => (seg::UPPER_ARM_L, false, 30.0, "left shoulder pitch"),
        Group::Elbow => (seg::FOREARM_L, false, 30.0, "left elbow flexion"),
    }
}

/// Step one joint of `group` with `gains` and measure the response.
pub fn step_response(gains: &Gains, group: Group) -> StepResponse {
    let plan = BodyPlan::default();
    let n = plan.segments.len();
    let mut world = World::new(plan, DT);
    let mut targets = vec![JointTarget::default(); n];
    let (joint, yaw, step_deg, what) = probe(group);
    let read = |w: &World| {
        let a = w.joint_angles(joint);
        if yaw { a.yaw } else { a.pitch }.to_degrees()
    };
    for _ in 0..(SETTLE_S / DT) as usize {
        world.apply_control(gains, &targets);
        world.step();
    }
    let start = read(&world);
    let target = start + step_deg;
    let mut angles = JointAngles::default();
    if yaw {
        angles.yaw = target.to_radians();
    } else {
        angles.pitch = target.to_radians();
    }
    targets[joint] = hold(angles.to_quat());
    let (mut t, mut y) = (vec![0.0], vec![start]);
    for i in 1..=(RECORD_S / DT) as usize {
        world.apply_control(gains, &targets);
        world.step();
        t.push(i as f64 * DT);
        y.push(read(&world));
    }
    StepResponse {
        group,
        what,
        metrics: step_metrics(&t, &y, target),
        t,
        y,
        target,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_neck_gains_step_cleanly() {
        let r = step_response(&Gains::default(), Group::Neck);
        assert!(r.metrics.rise_time.is_finite(), "{:?}", r.metrics);
        assert!(r.metrics.overshoot < 0.3, "{:?}", r.metrics);
        assert!((r.y.last().unwrap() - r.target).abs() < 3.0);
    }
}
