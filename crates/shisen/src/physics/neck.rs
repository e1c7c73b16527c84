//! The neck under impact: how much of the gaze controller's stiff PD law
//! the neck's muscles can actually deliver when a blow arrives.
//!
//! The neck's PD gains ([`crate::physics::control::Gains::neck`]) are tuned
//! for fast voluntary head movements (40 rad/s bandwidth): feedback that
//! strong, applied at once, makes the head immovable by a punch (a 6 N s
//! jab rocked it 3 deg). A person's neck is not like that. At the instant
//! of a blow only its **intrinsic** impedance acts: passive tissue and the
//! muscles' present activation, a spring that stiffens toward the end of
//! its range (N1). The rest of the feedback needs muscle force that is not
//! there yet: it is bounded by the muscles' **tone** (more when braced)
//! until the **stretch reflex** arrives, about 60-75 ms after the stretch
//! began, and raises the bound toward the neck's maximal torque (N2). So a
//! clean jab snaps the head back, and the reflex and the voluntary law
//! bring it home within a fraction of a second; in ordinary head
//! movements the bound is never reached and the law is the PD law exactly.
//!
//! ```text
//! tau = tau_int + clamp(tau_pd - tau_int, B(t)) + ff I a_ref        (N2)
//! tau_int = k e (1 + |e|^2 / e_s^2) + b w_err                       (N1)
//! B(t) = tone(brace) + (max - tone(brace)) r(t)
//! ```
//!
//! `e` is the rotation vector from the head's posture to the commanded
//! one, `w_err` the commanded minus actual relative angular velocity,
//! `tau_pd` the stable PD feedback ([`pd_feedback`]) and `r` the reflex's
//! activation, 0 to 1. Bracing (the VH sees a punch coming and guards,
//! with its perception's latencies) raises tone and intrinsic impedance
//! with the muscles' activation time constant.

use glam::Vec3;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::physics::control::{
    JointGains, JointState, JointTarget, feedforward, joint_errors, pd_feedback,
};

/// The neck's impact response (scene `vh.neck`). Torques in N m, angles
/// in rad, times in s. Tone above the maximal torque is refused
/// ([`NeckParams::validate`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct NeckParams {
    /// Whether the neck's feedback is bounded by its muscles (the human
    /// neck, default) or is the PD law at once, however hard the blow (the
    /// seed's stiff neck, `profile: Seed`).
    pub human: bool,
    /// Intrinsic stiffness near neutral, relaxed, N m/rad. Default 12: the
    /// cervical spine's seven motion segments in series, each about
    /// 59-86 N m/rad (Voo et al. 1998, J. Biomech. Eng. 120:693), with
    /// resting muscle tone. At most 1000 (over ten times one segment's, as
    /// stiff as a neck in a brace).
    #[schemars(range(min = 0.0, max = 1000.0))]
    pub stiffness: f64,
    /// Rotation at which the intrinsic spring has doubled its stiffness
    /// (N1's `e_s`), rad. Default 0.2 (11 deg): neck tissue stiffens
    /// steeply beyond its neutral zone (Voo et al. 1998 report the
    /// segments' nonlinear, stiffening moment-angle curves). 0.01-3.2 rad
    /// (0.6-180 deg: from a spring stiff at once to one that never
    /// stiffens within a head's turn).
    #[schemars(range(min = 0.01, max = 3.2))]
    pub stiffening_angle: f64,
    /// Intrinsic damping, relaxed, N m s/rad. Default 0.8 (our choice: a
    /// relaxed neck barely slows a blow while the glove is on the head;
    /// Kuo et al. 2019, J. R. Soc. Interface 16:20190086, find muscles
    /// take under a third of the impulse while it is applied). At most 100
    /// (a head of 0.19 kg m^2 critically damped at 260 rad/s).
    #[schemars(range(min = 0.0, max = 100.0))]
    pub damping: f64,
    /// Factor on the intrinsic stiffness and damping when fully braced.
    /// Default 2.5: co-contraction before a known impact cuts the head's
    /// peak angular velocity by 18-29 % (Simoneau, Denninger & Hain 2008,
    /// J. Biomech. 41:2097; Homayounpour et al. 2021, J. Biomech.
    /// 119:110732). 1-20 (1: bracing adds nothing; 20, eight times
    /// the measured effect, covers any co-contraction).
    #[schemars(range(min = 1.0, max = 20.0))]
    pub braced_factor: f64,
    /// Feedback torque the muscles' tone gives before the reflex, relaxed,
    /// N m. Default 2 (about 5 % of the maximal torque). 0-500 N m, like
    /// [`NeckParams::max_torque`], and at most it.
    #[schemars(range(min = 0.0, max = 500.0))]
    pub tone: f64,
    /// The same when fully braced, N m. Default 8 (about 20 %). 0-500 N m,
    /// and at most [`NeckParams::max_torque`].
    #[schemars(range(min = 0.0, max = 500.0))]
    pub braced_tone: f64,
    /// Most torque the neck's muscles give, N m. Default 30: maximal
    /// isometric neck moments are about 20-50 N m across directions
    /// (Vasavada, Li & Delp 1998, Spine 23:412). 0-500 N m (ten times the
    /// strongest direction: room for a helmeted or mechanical neck).
    #[schemars(range(min = 0.0, max = 500.0))]
    pub max_torque: f64,
    /// Relative angular speed of the head on the torso, beyond the
    /// commanded one, that stretches the neck muscles enough to start the
    /// reflex, rad/s. Default 1.5 (86 deg/s; voluntary head movements
    /// track their command far closer than this). 0.01-100 rad/s (a
    /// reflex at any twitch to one that no blow starts).
    #[schemars(range(min = 0.01, max = 100.0))]
    pub stretch_threshold: f64,
    /// From the stretch to the reflex's onset, s. Default 0.065:
    /// sternocleidomastoid EMG onset 67-75 ms after a sudden perturbation
    /// (Siegmund et al. 2003, J. Biomech. 36:473), 59 ms in O'Driscoll et
    /// al. 2019 (Chin. J. Traumatol. 22:80). 0-0.5 s (past a voluntary
    /// reaction's 0.2-0.3 s: slower than any subject's reflex).
    #[schemars(range(min = 0.0, max = 0.5))]
    pub reflex_latency: f64,
    /// Time constant of the muscles' activation (reflex rise, bracing),
    /// s. Default 0.03 (excitation-contraction dynamics of 10-40 ms are
    /// usual in muscle models; our choice within them). 0.001-1 s (one
    /// step to a very slow muscle; it divides the step).
    #[schemars(range(min = 0.001, max = 1.0))]
    pub activation_time: f64,
    /// The reflex fades this long after the last stretch, s. Default 0.3.
    /// 0-10 s (a reflex held through a whole exchange of blows).
    #[schemars(range(min = 0.0, max = 10.0))]
    pub reflex_hold: f64,
}

impl Default for NeckParams {
    fn default() -> Self {
        NeckParams {
            human: true,
            stiffness: 12.0,
            stiffening_angle: 0.2,
            damping: 0.8,
            braced_factor: 2.5,
            tone: 2.0,
            braced_tone: 8.0,
            max_torque: 30.0,
            stretch_threshold: 1.5,
            reflex_latency: 0.065,
            activation_time: 0.03,
            reflex_hold: 0.3,
        }
    }
}

impl NeckParams {
    /// The seed's neck: the PD law at once, unbounded.
    pub fn stiff() -> Self {
        NeckParams {
            human: false,
            ..Default::default()
        }
    }

    /// Cross-field check: tone cannot exceed the maximal torque.
    pub fn validate(&self) -> Result<(), String> {
        if self.tone > self.max_torque || self.braced_tone > self.max_torque {
            return Err(format!(
                "tone ({}) and braced_tone ({}) must not exceed max_torque ({})",
                self.tone, self.braced_tone, self.max_torque
            ));
        }
        Ok(())
    }
}

/// The neck muscles' evolving activation.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct NeckState {
    /// When the present stretch began, s.
    stretch_since: Option<f64>,
    /// When the neck was last stretched, s.
    last_stretch: f64,
    /// Reflex activation, 0-1.
    pub reflex: f64,
    /// Bracing activation, 0-1.
    pub brace: f64,
}

impl NeckState {
    /// Advance the muscles' activation by `dt` at time `t`: `stretch` is
    /// the neck's angular speed beyond its command (rad/s), `bracing`
    /// whether the VH braces for a blow.
    pub fn step(&mut self, p: &NeckParams, stretch: f64, bracing: bool, t: f64, dt: f64) {
        if stretch > p.stretch_threshold {
            self.stretch_since.get_or_insert(t);
            self.last_stretch = t;
        } else if t - self.last_stretch > p.reflex_hold {
            self.stretch_since = None;
        }
        let reflex_on = self
            .stretch_since
            .is_some_and(|s| t - s >= p.reflex_latency);
        let follow = |a: &mut f64, on: bool| {
            let goal = if on { 1.0 } else { 0.0 };
            *a += (goal - *a) * (dt / p.activation_time).min(1.0);
        };
        follow(&mut self.reflex, reflex_on);
        follow(&mut self.brace, bracing);
    }

    /// The bound on the feedback beyond the intrinsic impedance, N m (N2).
    pub fn bound(&self, p: &NeckParams) -> f64 {
        let tone = p.tone + (p.braced_tone - p.tone) * self.brace;
        tone + (p.max_torque - tone) * self.reflex
    }

    /// The intrinsic impedance's scale for the present bracing.
    fn scale(&self, p: &NeckParams) -> f64 {
        1.0 + (p.braced_factor - 1.0) * self.brace
    }
}

/// The intrinsic torque (N1), world frame: the stiffening spring toward
/// the commanded posture and the damping of the velocity error.
pub fn intrinsic(p: &NeckParams, st: &NeckState, target: &JointTarget, s: &JointState) -> Vec3 {
    let k = (p.stiffness * st.scale(p)) as f32;
    let b = (p.damping * st.scale(p)) as f32;
    let (e, w_err) = joint_errors(target, s);
    let es = p.stiffening_angle as f32;
    k * e * (1.0 + e.length_squared() / (es * es)) + b * w_err
}

/// The neck's torque on the head, world frame (N2): the PD law's feedback
/// bounded by what the muscles can give now, over the intrinsic torque,
/// plus the planned motion's feed-forward. With `p.human` off, the PD
/// law itself.
pub fn neck_torque(
    g: &JointGains,
    p: &NeckParams,
    st: &NeckState,
    target: &JointTarget,
    s: &JointState,
    dt: f32,
) -> Vec3 {
    let fb = pd_feedback(g, target, s, dt);
    let ff = feedforward(g, target, s);
    if !p.human {
        return fb + ff;
    }
    let int = intrinsic(p, st, target, s);
    int + (fb - int).clamp_length_max(st.bound(p) as f32) + ff
}

/// The neck's stretch: its relative angular speed beyond the command's, rad/s.
pub fn stretch(target: &JointTarget, s: &JointState) -> f64 {
    f64::from(joint_errors(target, s).1.length())
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{Mat3, Quat};

    fn at_rest(w: Vec3) -> JointState {
        JointState {
            parent_rot: Quat::IDENTITY,
            child_rot: Quat::IDENTITY,
            rel_angvel: w,
            inertia: Mat3::from_diagonal(Vec3::splat(0.19)),
        }
    }

    /// Small errors: the bound is not reached and the neck is the PD law.
    #[test]
    fn ordinary_motion_is_the_pd_law() {
        let g = JointGains::from_bandwidth(0.19, 40.0, 1.0);
        let p = NeckParams::default();
        let st = NeckState::default();
        let target = JointTarget {
            rotation: Quat::from_rotation_y(0.005),
            ..Default::default()
        };
        let s = at_rest(Vec3::ZERO);
        let pd = pd_feedback(&g, &target, &s, 0.001) + feedforward(&g, &target, &s);
        assert!((neck_torque(&g, &p, &st, &target, &s, 0.001) - pd).length() < 1e-5);
    }

    /// A blow's speed: before the reflex only intrinsic torque and tone
    /// resist (far less than the PD law would); after it, up to the max.
    #[test]
    fn a_blow_meets_tone_then_the_reflex() {
        let g = JointGains::from_bandwidth(0.19, 40.0, 1.0);
        let p = NeckParams::default();
        let target = JointTarget::default();
        let s = at_rest(Vec3::X * 10.0);
        let pd = pd_feedback(&g, &target, &s, 0.001).length();
        let mut st = NeckState::default();
        let early = neck_torque(&g, &p, &st, &target, &s, 0.001).length();
        assert!(early < 0.2 * pd, "{early} vs {pd}");
        let (mut t, dt) = (0.0, 0.001);
        while t < 0.2 {
            st.step(&p, stretch(&target, &s), false, t, dt);
            t += dt;
        }
        let late = neck_torque(&g, &p, &st, &target, &s, 0.001).length();
        assert!(late > 0.9 * p.max_torque as f32 && late < pd, "{late}");
        // The reflex did not start before its latency.
        let mut st = NeckState::default();
        let mut t = 0.0;
        while t < p.reflex_latency - 0.002 {
            st.step(&p, 10.0, false, t, dt);
            t += dt;
        }
        assert_eq!(st.reflex, 0.0);
    }

    /// Bracing raises the bound and the intrinsic impedance.
    #[test]
    fn bracing_stiffens() {
        let p = NeckParams::default();
        let mut st = NeckState::default();
        for k in 0..300 {
            st.step(&p, 0.0, true, k as f64 * 0.001, 0.001);
        }
        assert!((st.bound(&p) - p.braced_tone).abs() < 0.01);
        let target = JointTarget::default();
        let s = at_rest(Vec3::X);
        let relaxed = intrinsic(&p, &NeckState::default(), &target, &s).length();
        let braced = intrinsic(&p, &st, &target, &s).length();
        assert!((braced / relaxed - p.braced_factor as f32).abs() < 0.01);
    }

    /// The spring stiffens: at twice `e_s` it gives five times the linear torque.
    #[test]
    fn the_spring_stiffens() {
        let p = NeckParams::default();
        let target = JointTarget {
            rotation: Quat::from_rotation_x(0.4),
            ..Default::default()
        };
        let tau = intrinsic(&p, &NeckState::default(), &target, &at_rest(Vec3::ZERO));
        let linear = p.stiffness as f32 * 0.4;
        assert!((tau.length() / linear - 5.0).abs() < 0.01, "{tau}");
    }
}
