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
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::util::math::{dir_from_yaw_pitch, yaw_pitch_of};

/// Static parameters of the binocular model (gaze.md section 8). The gains
/// are Zhang & Wakamatsu's, with the 2006 implementation's values. Each
/// gain is bounded at ten to twenty times its default: the loop is solved
/// implicitly, so it stays stable, but larger gains are no model of an eye.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct BinocularParams {
    /// `sigma`: own-eye position-error gain (1/s), 0-1000. Default 100.
    #[schemars(range(min = 0.0, max = 1000.0))]
    pub sigma: f64,
    /// `kappa`: other-eye position-error gain (1/s), 0-1000. Default 50.
    #[schemars(range(min = 0.0, max = 1000.0))]
    pub kappa: f64,
    /// `nu`: own-eye slip gain, 0-10. Default 0.5.
    #[schemars(range(min = 0.0, max = 10.0))]
    pub nu: f64,
    /// `eta`: other-eye slip gain, 0-10. Default 0.2.
    #[schemars(range(min = 0.0, max = 10.0))]
    pub eta: f64,
    /// `rho1`: same-side integrator-to-eye gain, 0-10. Default 1.5.
    #[schemars(range(min = 0.0, max = 10.0))]
    pub rho1: f64,
    /// `rho2`: cross integrator-to-eye gain, 0-10. Default 0.5.
    #[schemars(range(min = 0.0, max = 10.0))]
    pub rho2: f64,
    /// `alpha`: vestibular gain; the VOR gain is `alpha (rho1 + rho2)`,
    /// 0-10. Default 0.5.
    #[schemars(range(min = 0.0, max = 10.0))]
    pub alpha: f64,
    /// Distance between the eye centres (m). Default 0.0619 (gaze.md table).
    /// 0.02-0.2 m: adults' are 0.054-0.074 m, a child's about 0.045; the
    /// bounds leave room for stylised heads.
    #[schemars(range(min = 0.02, max = 0.2))]
    pub interpupillary: f64,
    /// Eye yaw range, +- (rad). Default 55 deg. Above 0, at most 1.5 rad
    /// (86 deg; at 90 deg the pupil would face sideways).
    #[schemars(range(max = 1.5), extend("exclusiveMinimum" = 0.0))]
    pub yaw_range: f64,
    /// Eye pitch range, +- (rad). Default 45 deg. Above 0, at most 1.5 rad
    /// (86 deg), as the yaw range.
    #[schemars(range(max = 1.5), extend("exclusiveMinimum" = 0.0))]
    pub pitch_range: f64,
    /// Nearest fixation distance the estimate accepts (m). Default 0.05.
    /// 0.01-10 m; it must also exceed half the interpupillary distance.
    #[schemars(range(min = 0.01, max = 10.0))]
    pub min_distance: f64,
    /// Farthest fixation distance the estimate accepts (m); parallel lines of
    /// sight give this. Default 100. 0.01-1000 m (vision's farthest
    /// sight); it must exceed `min_distance`.
    #[schemars(range(min = 0.01, max = 1000.0))]
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
            interpupillary: crate::anatomy::eye::IPD,
            yaw_range: crate::anatomy::eye::YAW_RANGE_DEG.to_radians(),
            pitch_range: crate::anatomy::eye::PITCH_RANGE_DEG.to_radians(),
            min_distance: 0.05,
            max_distance: 100.0,
        }
    }
}

impl BinocularParams {
    /// Cross-field checks the fields' ranges cannot make: the vergence
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
mod tests;
