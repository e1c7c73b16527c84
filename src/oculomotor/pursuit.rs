//! Smooth pursuit, vergence and the rotational VOR: Zhang & Wakamatsu's
//! binocular model (gaze.md section 8, equation M7), on both axes.
//!
//! # Model and sign convention
//! Per axis (yaw, and pitch likewise) and per eye `i` in {L, R}: `e_i` is the
//! retinal position error (target angle minus eye angle, head frame, seen
//! from that eye's centre), `v_i` the retinal slip, `w` the head angular
//! rate on that axis. With every angle in the crate's convention (yaw +
//! left, pitch + up), (M7) is used exactly as printed:
//!
//! ```text
//! dI_L/dt = -(sigma e_L + nu v_L) - (kappa e_R + eta v_R) + alpha w
//! dI_R/dt =  (sigma e_R + nu v_R) + (kappa e_L + eta v_L) - alpha w
//! theta_L = theta_L0 - rho1 I_L + rho2 I_R
//! theta_R = theta_R0 - rho2 I_L + rho1 I_R
//! ```
//!
//! A conjugate error (`e_L = e_R = e`) gives `theta_dot = (rho1+rho2)(sigma+kappa) e`
//! on both eyes (toward the target, 300/s); a vergence error (`e_L = -e_R`)
//! gives `+-(rho1-rho2)(sigma-kappa) e` (50/s); the head term gives
//! `theta_dot = -alpha (rho1+rho2) w = -w` on both eyes: the VOR, gain 1,
//! eyes counter-rotating.
//!
//! # Retinal slip and the algebraic loop
//! The slip is the image's velocity on the retina, `v_i = u_i - theta_dot_i`,
//! where `u_i` is the rate of the target direction seen from eye `i` in the
//! head frame ([`EyeInput::target_rate`]). During a perfect VOR `u = -w` and
//! `theta_dot = -w`, so `v = 0`: the head rotation is counted once, by the
//! `alpha` term. Because `v` contains the eye velocity that (M7) produces,
//! the slip cannot be fed from the previous step's eye velocity (the
//! conjugate slip loop gain `(rho1+rho2)(nu+eta) = 1.4 > 1` makes that
//! one-step-delayed loop diverge). The model is linear, so each step solves
//! the 2x2 linear system for the eye velocities exactly (an efference copy
//! of the motor command, available to the brain at no delay): no loop, no
//! delay, nothing iterated.
//!
//! # Discretisation
//! Backward (implicit) Euler: the position error used over a step is the
//! one predicted at the step's end, `e + dt (u - theta_dot)`, solved
//! jointly with the slip. The update is unconditionally stable, so the
//! stiff loop (300/s) is safe at dt = 1 ms and at render rates alike; the
//! integrators `I_L`, `I_R` are then advanced by (M7) with that solution, so
//! `theta = theta0 + P I` holds exactly. Outputs are clamped to the eye's
//! range (gaze.md section 2), with the integrators back-computed
//! (anti-windup).
//!
//! # The occluded eye
//! With its inputs simply zeroed, the occluded eye follows the seeing one
//! through the `kappa`, `eta` cross terms *conjugately* (at 125/175 of its
//! speed): on a midline approach it turns the wrong way. Humans do not: the
//! covered eye converges by accommodative vergence, the seeing eye's focus
//! giving the distance and its line of sight the direction (Hering's law
//! gives the version). We model exactly that: while one eye is occluded,
//! its error input is *estimated* as the direction, from its own centre,
//! of the agent's 3-D fixation estimate, i.e. the point on the seeing eye's
//! line of sight to the target ([`EyeInput::error`] + the seeing eye's angle)
//! at the estimated fixation distance. The distance is triangulated from
//! both lines of sight whenever both eyes see (disparity), taken from the
//! seeing eye's focus ([`EyeInput::focus_distance`], accommodation) while
//! one eye is covered, and otherwise held at its last value. The occluded
//! eye gets no slip (no image moves on its retina). The cross terms still
//! act, so the result is (M7) with a physiologically motivated input, not a
//! different law. Without any distance estimate yet, the occluded eye's
//! inputs are zero (plain M7).

use glam::{DMat2, DVec2, DVec3};
use serde::{Deserialize, Serialize};

use crate::math::{dir_from_yaw_pitch, yaw_pitch_of};

/// Static parameters of the binocular model (gaze.md section 8). The gains
/// are Zhang & Wakamatsu's, with the 2006 implementation's values.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct BinocularParams {
    /// `sigma`: own-eye position-error gain (1/s). Default 100.
    #[serde(deserialize_with = "crate::check::non_negative")]
    pub sigma: f64,
    /// `kappa`: other-eye position-error gain (1/s). Default 50.
    #[serde(deserialize_with = "crate::check::non_negative")]
    pub kappa: f64,
    /// `nu`: own-eye slip gain. Default 0.5.
    #[serde(deserialize_with = "crate::check::non_negative")]
    pub nu: f64,
    /// `eta`: other-eye slip gain. Default 0.2.
    #[serde(deserialize_with = "crate::check::non_negative")]
    pub eta: f64,
    /// `rho1`: same-side integrator-to-eye gain. Default 1.5.
    #[serde(deserialize_with = "crate::check::non_negative")]
    pub rho1: f64,
    /// `rho2`: cross integrator-to-eye gain. Default 0.5.
    #[serde(deserialize_with = "crate::check::non_negative")]
    pub rho2: f64,
    /// `alpha`: vestibular gain; the VOR gain is `alpha (rho1 + rho2)`. Default 0.5.
    #[serde(deserialize_with = "crate::check::non_negative")]
    pub alpha: f64,
    /// Distance between the eye centres (m). Default 0.0619 (gaze.md table).
    #[serde(deserialize_with = "crate::check::positive")]
    pub interpupillary: f64,
    /// Eye yaw range, +- (rad). Default 55 deg.
    #[serde(deserialize_with = "crate::check::positive")]
    pub yaw_range: f64,
    /// Eye pitch range, +- (rad). Default 45 deg.
    #[serde(deserialize_with = "crate::check::positive")]
    pub pitch_range: f64,
    /// Nearest fixation distance the estimate accepts (m). Default 0.05.
    #[serde(deserialize_with = "crate::check::positive")]
    pub min_distance: f64,
    /// Farthest fixation distance the estimate accepts (m); parallel lines of
    /// sight give this. Default 100.
    #[serde(deserialize_with = "crate::check::positive")]
    pub max_distance: f64,
}

impl Default for BinocularParams {
    fn default() -> Self {
        Self {
            sigma: 100.0,
            kappa: 50.0,
            nu: 0.5,
            eta: 0.2,
            rho1: 1.5,
            rho2: 0.5,
            alpha: 0.5,
            interpupillary: 0.0619,
            yaw_range: 55f64.to_radians(),
            pitch_range: 45f64.to_radians(),
            min_distance: 0.05,
            max_distance: 100.0,
        }
    }
}

impl BinocularParams {
    /// Cross-field checks the field deserialisers cannot make: the vergence
    /// loop needs `rho1 > rho2` and `sigma > kappa`; the distance bounds
    /// must be ordered and beyond the eyes.
    pub fn validate(&self) -> Result<(), String> {
        if self.rho1 <= self.rho2 {
            return Err(format!(
                "rho1 ({}) must exceed rho2 ({})",
                self.rho1, self.rho2
            ));
        }
        if self.sigma <= self.kappa {
            return Err(format!(
                "sigma ({}) must exceed kappa ({})",
                self.sigma, self.kappa
            ));
        }
        if self.min_distance <= 0.5 * self.interpupillary || self.max_distance <= self.min_distance
        {
            return Err("need interpupillary/2 < min_distance < max_distance".into());
        }
        Ok(())
    }

    /// Conjugate (version) position loop gain `(rho1 + rho2)(sigma + kappa)` (1/s).
    pub fn version_gain(&self) -> f64 {
        (self.rho1 + self.rho2) * (self.sigma + self.kappa)
    }

    /// Vergence position loop gain `(rho1 - rho2)(sigma - kappa)` (1/s).
    pub fn vergence_gain(&self) -> f64 {
        (self.rho1 - self.rho2) * (self.sigma - self.kappa)
    }

    /// VOR gain `alpha (rho1 + rho2)` (1 with the defaults).
    pub fn vor_gain(&self) -> f64 {
        self.alpha * (self.rho1 + self.rho2)
    }

    /// Eye centres (left, right) in the head frame used here: origin midway
    /// between the eyes, +X to the agent's left, so the left eye is at +X.
    pub fn eye_centres(&self) -> (DVec3, DVec3) {
        let h = 0.5 * self.interpupillary;
        (DVec3::new(h, 0.0, 0.0), DVec3::new(-h, 0.0, 0.0))
    }

    fn clamp(&self, a: DVec2) -> DVec2 {
        DVec2::new(
            a.x.clamp(-self.yaw_range, self.yaw_range),
            a.y.clamp(-self.pitch_range, self.pitch_range),
        )
    }
}

/// (yaw, pitch) of `point` seen from `centre`, both in the head frame.
pub fn angles_to(centre: DVec3, point: DVec3) -> DVec2 {
    let (yaw, pitch) = yaw_pitch_of(point - centre);
    DVec2::new(yaw, pitch)
}

/// Head angular velocity `omega` (head frame, rad/s) as (yaw rate, pitch
/// rate) for the VOR: yaw is about +Y, pitch up is about -X. Roll is not
/// compensated (no torsion in this model).
pub fn head_rate_from_angular_velocity(omega: DVec3) -> DVec2 {
    DVec2::new(omega.y, -omega.x)
}

/// What one eye reports to the brainstem in one step.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct EyeInput {
    /// Retinal position error: target direction minus this state's eye angle
    /// (yaw, pitch), head frame, seen from this eye's centre (rad).
    pub error: DVec2,
    /// Rate of the target direction seen from this eye in the head frame
    /// (rad/s); includes the effect of head rotation and translation. The
    /// retinal slip `target_rate - eye rate` is formed inside
    /// [`BinocularState::step`].
    pub target_rate: DVec2,
    /// False when the eye is shut or occluded: its error and rate are ignored.
    pub visible: bool,
    /// Distance (m) from the head-frame origin to the target as judged by this
    /// eye's accommodation, if known; used only while the *other* eye is
    /// occluded.
    pub focus_distance: Option<f64>,
}

impl EyeInput {
    /// A seeing eye.
    pub fn seen(error: DVec2, target_rate: DVec2) -> Self {
        Self {
            error,
            target_rate,
            visible: true,
            focus_distance: None,
        }
    }

    /// An occluded (or shut) eye.
    pub fn occluded() -> Self {
        Self::default()
    }

    /// Adds an accommodation distance cue.
    pub fn with_focus(mut self, distance: f64) -> Self {
        self.focus_distance = Some(distance);
        self
    }
}

/// Evolving state of the binocular model: integrators, offsets, last outputs
/// and the fixation-distance estimate.
#[derive(Clone, Debug, PartialEq)]
pub struct BinocularState {
    theta0_l: DVec2,
    theta0_r: DVec2,
    int_l: DVec2,
    int_r: DVec2,
    theta_l: DVec2,
    theta_r: DVec2,
    rate_l: DVec2,
    rate_r: DVec2,
    distance: Option<f64>,
}

/// Row-major 2x2 matrix.
fn m2(a00: f64, a01: f64, a10: f64, a11: f64) -> DMat2 {
    DMat2::from_cols(DVec2::new(a00, a10), DVec2::new(a01, a11))
}

/// One axis of one step: eye velocities (L, R) from (M7) with the slip and the
/// end-of-step error solved implicitly, and the integrator increments.
struct AxisStep {
    theta_dot: DVec2,
    d_int: DVec2,
}

fn axis_step(
    p: &BinocularParams,
    dt: f64,
    err: DVec2,
    rate: DVec2,
    err_mask: DVec2,
    slip_mask: DVec2,
    w: f64,
) -> AxisStep {
    // theta = theta0 + P I; dI/dt = Ce e+ + Cv v + a w                      (M7)
    let pm = m2(-p.rho1, p.rho2, -p.rho2, p.rho1);
    let ce = m2(-p.sigma, -p.kappa, p.kappa, p.sigma);
    let cv = m2(-p.nu, -p.eta, p.eta, p.nu);
    let a = DVec2::new(p.alpha, -p.alpha);
    let mm = DMat2::from_diagonal(err_mask);
    let sm = DMat2::from_diagonal(slip_mask);
    // e+ = M (err + dt rate - dt theta_dot), v = S (rate - theta_dot), theta_dot = P dI/dt:
    // (I + P (dt Ce M + Cv S)) theta_dot = P (Ce M (err + dt rate) + Cv S rate + a w)
    let lhs = DMat2::IDENTITY + pm * (ce * mm * dt + cv * sm);
    let rhs = pm * (ce * mm * (err + rate * dt) + cv * sm * rate + a * w);
    let theta_dot = lhs.inverse() * rhs;
    let e_plus = mm * (err + (rate - theta_dot) * dt);
    let v = sm * (rate - theta_dot);
    let d_int = (ce * e_plus + cv * v + a * w) * dt; // (M7) integrators
    AxisStep { theta_dot, d_int }
}

impl BinocularState {
    /// Starts with the eyes at `theta_l`, `theta_r` (yaw, pitch), integrators
    /// empty, no distance estimate.
    pub fn new(theta_l: DVec2, theta_r: DVec2) -> Self {
        Self {
            theta0_l: theta_l,
            theta0_r: theta_r,
            int_l: DVec2::ZERO,
            int_r: DVec2::ZERO,
            theta_l,
            theta_r,
            rate_l: DVec2::ZERO,
            rate_r: DVec2::ZERO,
            distance: None,
        }
    }

    /// Re-seats the model at new eye angles (used when a saccade ends): the
    /// offsets `theta0` take the angles and the integrators are emptied.
    /// The distance estimate is kept.
    pub fn reset(&mut self, theta_l: DVec2, theta_r: DVec2) {
        let distance = self.distance;
        *self = Self::new(theta_l, theta_r);
        self.distance = distance;
    }

    /// Current eye angle targets (left, right).
    pub fn angles(&self) -> (DVec2, DVec2) {
        (self.theta_l, self.theta_r)
    }

    /// Eye angular rates of the last step (left, right), rad/s.
    pub fn rates(&self) -> (DVec2, DVec2) {
        (self.rate_l, self.rate_r)
    }

    /// Triangulates the fixation distance from both lines of sight.
    fn triangulate(&self, p: &BinocularParams, dir_l: DVec2, dir_r: DVec2) -> f64 {
        let (cl, cr) = p.eye_centres();
        let (dl, dr) = (
            dir_from_yaw_pitch(dir_l.x, dir_l.y),
            dir_from_yaw_pitch(dir_r.x, dir_r.y),
        );
        let w0 = cl - cr;
        let b = dl.dot(dr);
        let (d, e) = (dl.dot(w0), dr.dot(w0));
        let denom = 1.0 - b * b;
        if denom < 1e-12 {
            return p.max_distance;
        }
        let (s, t) = ((b * e - d) / denom, (e - b * d) / denom);
        if s <= 0.0 || t <= 0.0 {
            return p.max_distance; // diverging lines of sight: "far"
        }
        let mid = 0.5 * ((cl + dl * s) + (cr + dr * t));
        mid.length().clamp(p.min_distance, p.max_distance)
    }

    /// Error estimate for the occluded eye (`occ_*`) from the seeing eye's
    /// line of sight to the target and the fixation distance (see module docs).
    fn estimated_error(
        &self,
        distance: f64,
        see_centre: DVec3,
        see_target: DVec2,
        occ_centre: DVec3,
        occ_theta: DVec2,
    ) -> DVec2 {
        let u = dir_from_yaw_pitch(see_target.x, see_target.y);
        // point on the seeing ray at `distance` from the origin: |c + s u| = D
        let b = u.dot(see_centre);
        let disc = (b * b - see_centre.length_squared() + distance * distance).max(0.0);
        let s = -b + disc.sqrt();
        angles_to(occ_centre, see_centre + u * s) - occ_theta
    }

    /// Advances the model by `dt` (s) and returns the eye angle targets
    /// (left, right), each (yaw, pitch), clamped to the eye range.
    ///
    /// `head_rate` is the head angular rate (yaw rate, pitch rate), see
    /// [`head_rate_from_angular_velocity`]. Errors must be relative to the
    /// angles this state returned last (the eye is assumed to track them).
    pub fn step(
        &mut self,
        p: &BinocularParams,
        dt: f64,
        left: &EyeInput,
        right: &EyeInput,
        head_rate: DVec2,
    ) -> (DVec2, DVec2) {
        let (cl, cr) = p.eye_centres();
        let target_l = self.theta_l + left.error;
        let target_r = self.theta_r + right.error;
        // Fixation-distance estimate: disparity, else the seeing eye's focus, else hold.
        match (left.visible, right.visible) {
            (true, true) => self.distance = Some(self.triangulate(p, target_l, target_r)),
            (true, false) => self.distance = left.focus_distance.or(self.distance),
            (false, true) => self.distance = right.focus_distance.or(self.distance),
            (false, false) => {}
        }
        let mut err = [left.error, right.error];
        let mut rate = [left.target_rate, right.target_rate];
        let mut err_mask = [
            f64::from(u8::from(left.visible)),
            f64::from(u8::from(right.visible)),
        ];
        let slip_mask = err_mask;
        if let Some(dist) = self
            .distance
            .map(|d| d.clamp(p.min_distance, p.max_distance))
        {
            if left.visible && !right.visible {
                err[1] = self.estimated_error(dist, cl, target_l, cr, self.theta_r);
                rate[1] = DVec2::ZERO; // held over the step; no slip
                err_mask[1] = 1.0;
            } else if right.visible && !left.visible {
                err[0] = self.estimated_error(dist, cr, target_r, cl, self.theta_l);
                rate[0] = DVec2::ZERO;
                err_mask[0] = 1.0;
            }
        }
        for i in 0..2 {
            if err_mask[i] == 0.0 {
                err[i] = DVec2::ZERO;
                rate[i] = DVec2::ZERO;
            }
        }
        let pick = |v: [DVec2; 2], yaw: bool| {
            if yaw {
                DVec2::new(v[0].x, v[1].x)
            } else {
                DVec2::new(v[0].y, v[1].y)
            }
        };
        let mask = |m: [f64; 2]| DVec2::new(m[0], m[1]);
        let yaw = axis_step(
            p,
            dt,
            pick(err, true),
            pick(rate, true),
            mask(err_mask),
            mask(slip_mask),
            head_rate.x,
        );
        let pitch = axis_step(
            p,
            dt,
            pick(err, false),
            pick(rate, false),
            mask(err_mask),
            mask(slip_mask),
            head_rate.y,
        );
        self.int_l += DVec2::new(yaw.d_int.x, pitch.d_int.x);
        self.int_r += DVec2::new(yaw.d_int.y, pitch.d_int.y);
        let (prev_l, prev_r) = (self.theta_l, self.theta_r);
        // (M7) output equations
        let raw_l = self.theta0_l - self.int_l * p.rho1 + self.int_r * p.rho2;
        let raw_r = self.theta0_r - self.int_l * p.rho2 + self.int_r * p.rho1;
        self.theta_l = p.clamp(raw_l);
        self.theta_r = p.clamp(raw_r);
        if self.theta_l != raw_l || self.theta_r != raw_r {
            // Anti-windup: back-compute the integrators from the clamped outputs.
            // [dL; dR] = P [I_L; I_R] per axis, P = [[-rho1, rho2], [-rho2, rho1]].
            let inv = m2(-p.rho1, p.rho2, -p.rho2, p.rho1).inverse();
            let (dl, dr) = (self.theta_l - self.theta0_l, self.theta_r - self.theta0_r);
            let iy = inv * DVec2::new(dl.x, dr.x);
            let ip = inv * DVec2::new(dl.y, dr.y);
            self.int_l = DVec2::new(iy.x, ip.x);
            self.int_r = DVec2::new(iy.y, ip.y);
        }
        self.rate_l = (self.theta_l - prev_l) / dt;
        self.rate_r = (self.theta_r - prev_r) / dt;
        debug_assert!(
            (raw_l - prev_l - DVec2::new(yaw.theta_dot.x, pitch.theta_dot.x) * dt).length() < 1e-9
        );
        (self.theta_l, self.theta_r)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DQuat;

    const DT: f64 = 0.001;
    const IPD: f64 = 0.0619;

    fn params() -> BinocularParams {
        BinocularParams::default()
    }

    /// Head pose as a function of time: yaw (about +Y) then pitch up (about -X).
    fn head_quat(yaw: f64, pitch: f64) -> DQuat {
        DQuat::from_rotation_y(yaw) * DQuat::from_rotation_x(-pitch)
    }

    struct World<'a> {
        target: &'a dyn Fn(f64) -> DVec3,
        /// head (yaw, pitch) as a function of time
        head: &'a dyn Fn(f64) -> DVec2,
        left_visible: &'a dyn Fn(f64) -> bool,
        /// Accommodation cue = true distance times this factor (None: no cue).
        focus_gain: Option<f64>,
    }

    /// Geometric target direction for each eye at time t (head frame).
    fn geometry(w: &World, t: f64) -> (DVec2, DVec2, f64) {
        let h = (w.head)(t);
        let p_head = head_quat(h.x, h.y).inverse() * (w.target)(t);
        let half = 0.5 * IPD;
        let l = angles_to(DVec3::new(half, 0.0, 0.0), p_head);
        let r = angles_to(DVec3::new(-half, 0.0, 0.0), p_head);
        (l, r, p_head.length())
    }

    struct Trace {
        t: Vec<f64>,
        eye_l: Vec<DVec2>,
        eye_r: Vec<DVec2>,
        geo_l: Vec<DVec2>,
        geo_r: Vec<DVec2>,
        head: Vec<DVec2>,
    }

    /// Closed loop: the eyes follow their targets exactly; errors and target
    /// rates come from the 3-D geometry.
    fn simulate(w: &World, duration: f64) -> Trace {
        let p = params();
        let (l0, r0, _) = geometry(w, 0.0);
        let mut s = BinocularState::new(l0, r0);
        let n = (duration / DT).round() as usize;
        let mut tr = Trace {
            t: vec![],
            eye_l: vec![],
            eye_r: vec![],
            geo_l: vec![],
            geo_r: vec![],
            head: vec![],
        };
        for k in 0..n {
            let t = k as f64 * DT;
            let (gl, gr, dist) = geometry(w, t);
            let (gl1, gr1, _) = geometry(w, t + DT);
            let h_rate = ((w.head)(t + DT) - (w.head)(t)) / DT;
            let (el, er) = s.angles();
            let right = {
                let inp = EyeInput::seen(gr - er, (gr1 - gr) / DT);
                match w.focus_gain {
                    Some(g) => inp.with_focus(g * dist),
                    None => inp,
                }
            };
            let left = if (w.left_visible)(t) {
                EyeInput::seen(gl - el, (gl1 - gl) / DT)
            } else {
                EyeInput::occluded()
            };
            let (nl, nr) = s.step(&p, DT, &left, &right, h_rate);
            let (gl1b, gr1b, _) = geometry(w, t + DT);
            tr.t.push(t + DT);
            tr.eye_l.push(nl);
            tr.eye_r.push(nr);
            tr.geo_l.push(gl1b);
            tr.geo_r.push(gr1b);
            tr.head.push((w.head)(t + DT));
        }
        tr
    }

    fn always(_: f64) -> bool {
        true
    }
    fn still(_: f64) -> DVec2 {
        DVec2::ZERO
    }

    #[test]
    fn gains_from_parameters() {
        let p = params();
        assert_eq!(p.version_gain(), 300.0);
        assert_eq!(p.vergence_gain(), 50.0);
        assert_eq!(p.vor_gain(), 1.0);
        assert!(p.validate().is_ok());
        assert!(
            BinocularParams {
                rho2: 2.0,
                ..params()
            }
            .validate()
            .is_err()
        );
    }

    #[test]
    fn sign_convention_single_step() {
        // Conjugate error to the left (+yaw) and up (+pitch): both eyes move that way.
        let p = params();
        let mut s = BinocularState::new(DVec2::ZERO, DVec2::ZERO);
        let e = DVec2::new(0.01, 0.01);
        let (l, r) = s.step(
            &p,
            DT,
            &EyeInput::seen(e, DVec2::ZERO),
            &EyeInput::seen(e, DVec2::ZERO),
            DVec2::ZERO,
        );
        assert!(l.x > 0.0 && r.x > 0.0 && l.y > 0.0 && r.y > 0.0);
        assert!((l - r).length() < 1e-15);
        // Converging error (left eye's target to its right): eyes turn toward each other.
        let mut s = BinocularState::new(DVec2::ZERO, DVec2::ZERO);
        let e = DVec2::new(0.01, 0.0);
        let (l, r) = s.step(
            &p,
            DT,
            &EyeInput::seen(-e, DVec2::ZERO),
            &EyeInput::seen(e, DVec2::ZERO),
            DVec2::ZERO,
        );
        assert!(l.x < 0.0 && r.x > 0.0 && (l.x + r.x).abs() < 1e-15);
    }

    #[test]
    fn perfect_vor_means_zero_slip_and_no_double_count() {
        // Fixating, head turning left at w: the target drifts right at -w in the
        // head frame. The eyes must turn at exactly -w (slip 0), not -w(1 + 1.4/...).
        let p = params();
        let w = DVec2::new(1.0, -0.5);
        let mut s = BinocularState::new(DVec2::ZERO, DVec2::ZERO);
        let inp = EyeInput::seen(DVec2::ZERO, -w);
        s.step(&p, DT, &inp, &inp, w);
        let (rl, rr) = s.rates();
        assert!(
            (rl + w).length() < 1e-12 && (rr + w).length() < 1e-12,
            "{rl} {rr}"
        );
        // In the dark (no image) the vestibular path alone gives gain alpha (rho1 + rho2) = 1.
        let mut s = BinocularState::new(DVec2::ZERO, DVec2::ZERO);
        s.step(&p, DT, &EyeInput::occluded(), &EyeInput::occluded(), w);
        let (rl, rr) = s.rates();
        assert!((rl + w).length() < 1e-12 && (rr + w).length() < 1e-12);
    }

    #[test]
    fn slip_path_matches_closed_form() {
        // One implicit step from rest with zero error and target rate u:
        // conjugate: theta_dot = u (Gv + dt Ge) / (1 + Gv + dt Ge),
        // Ge = (rho1+rho2)(sigma+kappa), Gv = (rho1+rho2)(nu+eta); vergence likewise
        // with (rho1-rho2)(sigma-kappa) and (rho1-rho2)(nu-eta).
        let p = params();
        let u = 0.3;
        let expect = |ge: f64, gv: f64| u * (gv + DT * ge) / (1.0 + gv + DT * ge);
        let conj = expect(2.0 * 150.0, 2.0 * 0.7);
        let verg = expect(1.0 * 50.0, 1.0 * 0.3);
        for (ul, ur, want_l, want_r) in [(u, u, conj, conj), (u, -u, verg, -verg)] {
            let mut s = BinocularState::new(DVec2::ZERO, DVec2::ZERO);
            let l = EyeInput::seen(DVec2::ZERO, DVec2::new(ul, ul));
            let r = EyeInput::seen(DVec2::ZERO, DVec2::new(ur, ur));
            s.step(&p, DT, &l, &r, DVec2::ZERO);
            let (rl, rr) = s.rates();
            for (got, want) in [
                (rl.x, want_l),
                (rl.y, want_l),
                (rr.x, want_r),
                (rr.y, want_r),
            ] {
                assert!((got - want).abs() < 1e-12, "{got} vs {want}");
            }
        }
    }

    #[test]
    fn conjugate_step_converges() {
        for dir in [
            DVec2::new(1.0, 0.0),
            DVec2::new(0.0, 1.0),
            DVec2::new(-0.6, 0.8),
        ] {
            let step = dir * 3f64.to_radians();
            let target = move |t: f64| {
                let a = if t < 0.05 { DVec2::ZERO } else { step };
                dir_from_yaw_pitch(a.x, a.y) * 2.0
            };
            let w = World {
                target: &target,
                head: &still,
                left_visible: &always,
                focus_gain: None,
            };
            let tr = simulate(&w, 0.3);
            let last = tr.t.len() - 1;
            for (e, g) in [(&tr.eye_l, &tr.geo_l), (&tr.eye_r, &tr.geo_r)] {
                let err = (e[last] - g[last]).length().to_degrees();
                assert!(err < 0.01, "{dir}: final error {err} deg");
                // no overshoot beyond 1 % of the step
                let overshoot = e
                    .iter()
                    .zip(g)
                    .map(|(a, b)| (a - b).dot(dir))
                    .fold(0.0, f64::max);
                assert!(overshoot.to_degrees() < 0.03, "overshoot {overshoot}");
            }
        }
    }

    /// Pursuit of a target moving at `speed` (deg/s) along yaw or pitch at 1 m.
    fn pursuit_gain(speed_deg: f64, vertical: bool) -> f64 {
        let speed = speed_deg.to_radians();
        let start = -20f64.to_radians();
        let t0 = 0.2;
        let target = move |t: f64| {
            let a = start + speed * (t - t0).max(0.0);
            if vertical {
                dir_from_yaw_pitch(0.0, a)
            } else {
                dir_from_yaw_pitch(a, 0.0)
            }
        };
        let dur = t0 + 40f64.to_radians() / speed;
        let w = World {
            target: &target,
            head: &still,
            left_visible: &always,
            focus_gain: None,
        };
        let tr = simulate(&w, dur);
        // steady state: from 0.3 s after the ramp onset to the end
        let i0 = tr.t.iter().position(|&t| t > t0 + 0.3).unwrap();
        let i1 = tr.t.len() - 1;
        let comp = |v: DVec2| if vertical { v.y } else { v.x };
        let mut gains = vec![];
        for (e, g) in [(&tr.eye_l, &tr.geo_l), (&tr.eye_r, &tr.geo_r)] {
            let eye_v = comp(e[i1] - e[i0]);
            let tgt_v = comp(g[i1] - g[i0]);
            gains.push(eye_v / tgt_v);
            let lag = comp(g[i1] - e[i1]).to_degrees();
            assert!(lag.abs() < 0.5, "steady lag {lag} deg");
        }
        gains.into_iter().fold(f64::INFINITY, f64::min)
    }

    #[test]
    fn pursuit_gain_at_10_20_30_deg_s() {
        for v in [10.0, 20.0, 30.0] {
            let g = pursuit_gain(v, false);
            println!("pursuit yaw {v} deg/s: gain {g:.4}");
            assert!((0.9..=1.05).contains(&g), "yaw {v}: gain {g}");
            let g = pursuit_gain(v, true);
            println!("pursuit pitch {v} deg/s: gain {g:.4}");
            assert!((0.9..=1.05).contains(&g), "pitch {v}: gain {g}");
        }
    }

    /// Fixating a far target while the head oscillates at 1 Hz, 100 deg/s peak.
    fn vor(vertical: bool, dark: bool) -> (f64, f64) {
        let peak = 100f64.to_radians();
        let f = 1.0;
        let amp = peak / (2.0 * std::f64::consts::PI * f);
        let head = move |t: f64| {
            let a = amp * (2.0 * std::f64::consts::PI * f * t).sin();
            if vertical {
                DVec2::new(0.0, a)
            } else {
                DVec2::new(a, 0.0)
            }
        };
        let target = |_: f64| DVec3::new(0.0, 0.0, 10.0);
        let never = |_: f64| false;
        let w = World {
            target: &target,
            head: &head,
            left_visible: if dark { &never } else { &always },
            focus_gain: None,
        };
        let mut tr = simulate(&w, 3.0);
        if dark {
            // The right eye "sees" in `simulate`; for the dark case rerun with both shut.
            let p = params();
            let mut s = BinocularState::new(DVec2::ZERO, DVec2::ZERO);
            tr.eye_l.clear();
            tr.eye_r.clear();
            for k in 0..tr.t.len() {
                let t = k as f64 * DT;
                let (l, r) = s.step(
                    &p,
                    DT,
                    &EyeInput::occluded(),
                    &EyeInput::occluded(),
                    (head(t + DT) - head(t)) / DT,
                );
                tr.eye_l.push(l);
                tr.eye_r.push(r);
            }
        }
        let comp = |v: DVec2| if vertical { v.y } else { v.x };
        let (mut sxy, mut sxx, mut max_err) = (0.0, 0.0, 0.0f64);
        for k in 1000..tr.t.len() {
            let hv = comp(tr.head[k] - tr.head[k - 1]) / DT;
            let ev = comp(tr.eye_l[k] - tr.eye_l[k - 1]) / DT;
            sxy += ev * hv;
            sxx += hv * hv;
            if !dark {
                for (e, g) in [(&tr.eye_l, &tr.geo_l), (&tr.eye_r, &tr.geo_r)] {
                    max_err = max_err.max((e[k] - g[k]).length());
                }
            }
        }
        (-sxy / sxx, max_err.to_degrees())
    }

    #[test]
    fn vor_gain_is_one_and_gaze_stays_on_target() {
        for vertical in [false, true] {
            let (gain, err) = vor(vertical, false);
            println!(
                "VOR light vertical={vertical}: gain {gain:.5}, max line-of-sight error {err:.4} deg"
            );
            assert!((0.95..=1.05).contains(&gain), "gain {gain}");
            assert!(err < 1.0, "error {err} deg");
            let (gain, _) = vor(vertical, true);
            println!("VOR dark vertical={vertical}: gain {gain:.5}");
            assert!((0.95..=1.05).contains(&gain), "dark gain {gain}");
        }
    }

    /// Midline approach from 1 m to 0.25 m over 1.5 s, then 0.5 s hold.
    /// Returns the final errors (left, right) and the worst errors after 0.3 s, deg.
    fn approach(occluded: bool, focus_gain: Option<f64>) -> (f64, f64, f64, f64) {
        let target = |t: f64| {
            let s = (t / 1.5).min(1.0);
            DVec3::new(0.0, 0.0, 1.0 - 0.75 * s)
        };
        let never = |_: f64| false;
        let w = World {
            target: &target,
            head: &still,
            left_visible: if occluded { &never } else { &always },
            focus_gain,
        };
        let tr = simulate(&w, 2.0);
        let k = tr.t.len() - 1;
        let worst = |e: &[DVec2], g: &[DVec2]| {
            (300..=k)
                .map(|i| (e[i] - g[i]).length())
                .fold(0.0, f64::max)
                .to_degrees()
        };
        let (wl, wr) = (worst(&tr.eye_l, &tr.geo_l), worst(&tr.eye_r, &tr.geo_r));
        // geometric angle at 0.25 m, independent of the helpers
        let geo = (0.5 * IPD / 0.25).atan();
        let el = (tr.eye_l[k].x + geo)
            .abs()
            .max(tr.eye_l[k].y.abs())
            .to_degrees();
        let er = (tr.eye_r[k].x - geo)
            .abs()
            .max(tr.eye_r[k].y.abs())
            .to_degrees();
        (el, er, wl, wr)
    }

    #[test]
    fn vergence_binocular_within_half_degree() {
        let (el, er, wl, wr) = approach(false, None);
        println!(
            "vergence binocular: final left {el:.4} deg, right {er:.4} deg; worst during approach {wl:.4}, {wr:.4}"
        );
        assert!(el < 0.5 && er < 0.5);
        assert!(
            wl < 0.5 && wr < 0.5,
            "tracks within 0.5 deg during the approach too"
        );
    }

    #[test]
    fn vergence_with_left_eye_occluded_within_two_degrees() {
        for g in [1.0, 1.1, 0.9] {
            let (el, er, wl, wr) = approach(true, Some(g));
            println!(
                "vergence, left occluded, focus x{g}: final occluded {el:.4} deg, seeing {er:.4} deg; worst {wl:.4}, {wr:.4}"
            );
            assert!(wl < 2.0 && wr < 0.5);
            assert!(er < 0.5, "seeing eye {er}");
            assert!(el < 2.0, "occluded eye {el} deg (focus x{g})");
        }
    }

    #[test]
    fn plain_m7_occluded_eye_would_fail() {
        // Documents why the estimate exists: with zeroed inputs and no distance
        // cue the occluded eye moves conjugately and misses by far more than 2 deg.
        let (el, _, _, _) = approach(true, None);
        assert!(el > 2.0, "{el}");
    }

    #[test]
    fn occluded_eye_keeps_following_and_is_on_target_when_it_opens() {
        // Lateral pursuit at 20 deg/s, 0.8 m; left eye covered from 0.3 s to 1.5 s.
        let speed = 20f64.to_radians();
        let target = move |t: f64| dir_from_yaw_pitch(-0.3 + speed * t, 0.1 * t) * 0.8;
        let vis = |t: f64| !(0.3..1.5).contains(&t);
        let w = World {
            target: &target,
            head: &still,
            left_visible: &vis,
            focus_gain: Some(1.0),
        };
        let tr = simulate(&w, 1.5);
        let k = tr.t.len() - 2; // just before it opens
        let err = (tr.eye_l[k] - tr.geo_l[k]).length().to_degrees();
        println!("occluded eye error at reopening: {err:.4} deg");
        assert!(err < 1.0, "{err}");
    }

    #[test]
    fn clamped_to_eye_range() {
        let p = params();
        let mut s = BinocularState::new(DVec2::ZERO, DVec2::ZERO);
        let e = DVec2::new(2.0, -2.0);
        for _ in 0..2000 {
            let (el, er) = s.angles();
            s.step(
                &p,
                DT,
                &EyeInput::seen(e - el, DVec2::ZERO),
                &EyeInput::seen(e - er, DVec2::ZERO),
                DVec2::ZERO,
            );
        }
        let (l, _) = s.angles();
        assert!((l.x - p.yaw_range).abs() < 1e-12 && (l.y + p.pitch_range).abs() < 1e-12);
        // and comes straight back (no wind-up)
        s.step(
            &p,
            DT,
            &EyeInput::seen(-l, DVec2::ZERO),
            &EyeInput::seen(-l, DVec2::ZERO),
            DVec2::ZERO,
        );
        assert!(s.angles().0.x < p.yaw_range);
    }

    #[test]
    fn stable_at_large_time_steps() {
        let p = params();
        for dt in [0.001, 1.0 / 60.0, 0.05] {
            let mut s = BinocularState::new(DVec2::ZERO, DVec2::ZERO);
            let target = DVec2::new(0.05, 0.02);
            for _ in 0..((1.0 / dt) as usize) {
                let (l, r) = s.angles();
                s.step(
                    &p,
                    dt,
                    &EyeInput::seen(target - l, DVec2::ZERO),
                    &EyeInput::seen(target - r, DVec2::ZERO),
                    DVec2::ZERO,
                );
            }
            let (l, r) = s.angles();
            assert!(
                (l - target).length() < 1e-6 && (r - target).length() < 1e-6,
                "dt {dt}"
            );
        }
    }

    #[test]
    fn reset_reseats_without_jump() {
        let p = params();
        let mut s = BinocularState::new(DVec2::ZERO, DVec2::ZERO);
        let a = DVec2::new(0.2, -0.1);
        s.reset(a, a);
        let (l, r) = s.step(
            &p,
            DT,
            &EyeInput::seen(DVec2::ZERO, DVec2::ZERO),
            &EyeInput::seen(DVec2::ZERO, DVec2::ZERO),
            DVec2::ZERO,
        );
        assert_eq!((l, r), (a, a));
    }

    #[test]
    fn params_deserialise() {
        let p: BinocularParams = ron::from_str("(sigma: 120.0)").unwrap();
        assert_eq!(p.sigma, 120.0);
        assert_eq!(p.kappa, 50.0);
        assert!(ron::from_str::<BinocularParams>("(nu: -0.1)").is_err());
    }
}
