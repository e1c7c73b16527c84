//! Muscle laws (face.md sections 3-5): pure functions giving the displacement
//! of one rest skin point. Nothing here knows about meshes or time.
//!
//! * linear muscle (Waters 1987): (F1)-(F4), with the influence table of
//!   face.md section 3 (cone half-angle B and rf / rs per muscle);
//! * sphincter (Waters ellipse): (F5)-(F6), and the upper lid's version of
//!   it on lid-specific geometry ([`LidSphincter`]);
//! * jaw rotation (Parke & Waters): (F7).
//!
//! (F1) and (F6) are linear in the contraction `k`, so callers may evaluate
//! them once at `k = 1` and scale (see `rig.rs`). (F7) is a rotation and is
//! not linear in the jaw angle.

use glam::Vec3;
use std::f32::consts::FRAC_PI_2;

/// A Waters linear muscle: bone attachment `v1`, skin attachment `v2`,
/// influence cone of half-angle `cone_half_angle` (radians) about the axis
/// `v1 -> v2`, and fall-off radius `rf = rf_ratio * rs` measured from `v1`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LinearMuscle {
    /// Fixed (bone) attachment V1.
    pub v1: Vec3,
    /// Skin attachment V2.
    pub v2: Vec3,
    /// Cone half-angle B in radians (face.md influence table).
    pub cone_half_angle: f32,
    /// rf / rs (face.md influence table); must be > 1.
    pub rf_ratio: f32,
}

/// Angular fall-off `a` of (F2): `cos((A / B) pi/2)` for `0 <= A <= B`, else 0.
pub fn angular_falloff(angle: f32, half_angle: f32) -> f32 {
    if !(0.0..=half_angle).contains(&angle) || half_angle <= 0.0 {
        return 0.0;
    }
    ((angle / half_angle) * FRAC_PI_2).cos() // (F2)
}

/// Radial fall-off `r` of (F3) for a point at distance `d` from V1.
pub fn radial_falloff(d: f32, rs: f32, rf: f32) -> f32 {
    if d < 0.0 || d > rf || rs <= 0.0 {
        0.0
    } else if d <= rs {
        ((1.0 - d / rs) * FRAC_PI_2).cos() // (F3), inner branch
    } else {
        ((d - rs) / (rf - rs) * FRAC_PI_2).cos() // (F3), outer branch
    }
}

impl LinearMuscle {
    /// Rest length rs = |V1 V2|.
    pub fn rest_length(&self) -> f32 {
        self.v1.distance(self.v2)
    }

    /// Fall-off radius rf = rf_ratio * rs.
    pub fn influence_radius(&self) -> f32 {
        self.rf_ratio * self.rest_length()
    }

    /// Product `a r` of (F2) and (F3) for rest point `p` (0 outside the
    /// cone, at V1 itself and beyond rf).
    pub fn influence(&self, p: Vec3) -> f32 {
        let v1p = p - self.v1;
        let d = v1p.length();
        let axis = self.v2 - self.v1;
        let rs = axis.length();
        if d <= f32::EPSILON || rs <= f32::EPSILON {
            return 0.0;
        }
        let angle = (v1p.dot(axis) / (d * rs)).clamp(-1.0, 1.0).acos();
        angular_falloff(angle, self.cone_half_angle) * radial_falloff(d, rs, self.rf_ratio * rs)
    }

    /// Displacement `P' - P` of rest point `p` at contraction ratio `k` (F4):
    /// `-a r k rs V1P/|V1P|` (F1, with the rs correction). Positive `k`
    /// pulls towards V1; V2 moves exactly `k rs`.
    pub fn displacement(&self, p: Vec3, k: f32) -> Vec3 {
        let ar = self.influence(p);
        if ar == 0.0 {
            return Vec3::ZERO;
        }
        let dir = (p - self.v1).normalize();
        -ar * k * self.rest_length() * dir // (F1)
    }
}

/// Which part of a sphincter's ellipse acts on the skin. The orbital part
/// of orbicularis oculi is a half ellipse (thesis fig. 3.14); the palpebral
/// parts are also used as half ellipses here (each acts on its own lid).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SphincterPart {
    /// The whole ellipse.
    Full,
    /// Only points with local `y > 0` (above the centre), fading in over
    /// [`HALF_FEATHER`] `ly` from the centre line.
    Upper,
    /// Only points with local `y < 0` (below the centre), likewise.
    Lower,
}

/// Width of a half sphincter's feathered edge, as a fraction of `ly`.
pub const HALF_FEATHER: f32 = 0.3;

/// A Waters sphincter: ellipse with centre `centre`, unit in-plane axes
/// `axis_x`, `axis_y` (orthogonal) and semi-axes `lx`, `ly`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphincter {
    /// Centre O.
    pub centre: Vec3,
    /// Unit vector of the ellipse's x axis (semi-axis `lx`).
    pub axis_x: Vec3,
    /// Unit vector of the ellipse's y axis (semi-axis `ly`), orthogonal to `axis_x`.
    pub axis_y: Vec3,
    /// Semi-axis along `axis_x`.
    pub lx: f32,
    /// Semi-axis along `axis_y`.
    pub ly: f32,
    /// Active part of the ellipse.
    pub part: SphincterPart,
    /// Share of the pull along `axis_x` that moves the skin, 0-1: 1 is
    /// Waters's ring (F6), which shrinks equally in both axes; less holds
    /// the ring's ends in place (the mouth's corners, anchored at the
    /// modiolus: [`crate::params::LipParams::oris_width_share`]).
    pub x_share: f32,
}

impl Sphincter {
    /// Normalised elliptic radius rho of (F5) of `p` projected into the plane.
    pub fn rho(&self, p: Vec3) -> f32 {
        let op = p - self.centre;
        let (px, py) = (op.dot(self.axis_x), op.dot(self.axis_y));
        ((px / self.lx).powi(2) + (py / self.ly).powi(2)).sqrt() // (F5)
    }

    /// Displacement `P' - P` of rest point `p` at contraction `k` (F6):
    /// `-2 k f OP` with `f = 1 - rho/2` on `0 <= rho <= 2`, OP projected
    /// into the muscle's plane. A point on the ring (rho = 1) moves `k |OP|`.
    pub fn displacement(&self, p: Vec3, k: f32) -> Vec3 {
        let op = p - self.centre;
        let (px, py) = (op.dot(self.axis_x), op.dot(self.axis_y));
        // A half ellipse's straight edge is feathered over HALF_FEATHER ly:
        // cut hard, it would shear the skin along a line (a crease the
        // wrinkle law would draw across the nose's root).
        let side = match self.part {
            SphincterPart::Full => 1.0,
            SphincterPart::Upper => py / (HALF_FEATHER * self.ly),
            SphincterPart::Lower => -py / (HALF_FEATHER * self.ly),
        };
        if side <= 0.0 {
            return Vec3::ZERO;
        }
        let rho = self.rho(p);
        if rho >= 2.0 {
            return Vec3::ZERO;
        }
        let f = 1.0 - 0.5 * rho; // (F6)
        let op_plane = px * self.x_share * self.axis_x + py * self.axis_y;
        -2.0 * k * f * side.min(1.0) * op_plane // (F6), (O2)
    }
}

/// Shape of a lid margin between the eye corners: height (as a fraction of
/// the mid-lid height) at `u = 1 - xi^2`, `xi` in [-1, 1] from corner to
/// corner. Upper lid `u^0.6`, lower lid `u^0.8` (rounder upper lid). The
/// generated head's openings and the lid sphincter share this one law.
pub fn lid_margin(u: f32, upper: bool) -> f32 {
    u.max(0.0).powf(if upper { 0.6 } else { 0.8 })
}

/// The upper palpebral orbicularis oculi on lid-specific geometry
/// (face.md 4, eyelids).
///
/// Its fibres run along the lid margin, so it closes the fissure along the
/// fissure's vertical, not towards one point (a Waters ellipse centred in
/// the eye pulls the margin into a V and leaves the corners open). Each
/// vertical line of the fissure at chart position `xi` carries the (F5)-(F6)
/// law with the ellipse reduced to its vertical axis: centre O on the lower
/// margin below P, semi-axis `ly = gap(xi) / rho_rim`, where `gap` is the
/// local opening; `rho_rim = 2 - 1 / k_blink` puts the whole upper margin on
/// the ring radius at which the blink contraction `k_blink` (2.9) moves it
/// exactly onto the lower margin, corner to corner. Points below the lower
/// margin or outside the corners do not move.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LidSphincter {
    /// Midpoint between the eye corners.
    pub centre: Vec3,
    /// Unit vector from the inner to the outer corner (chart xi axis).
    pub axis_x: Vec3,
    /// Unit in-face vector perpendicular to `axis_x`, pointing up.
    pub axis_y: Vec3,
    /// Half the corner-to-corner distance.
    pub half_width: f32,
    /// Upper margin height above the corner line at mid-fissure (u = 1).
    pub upper_h: f32,
    /// Lower margin depth below the corner line at mid-fissure (u = 1).
    pub lower_h: f32,
    /// Elliptic radius of the upper margin in (F5).
    pub rho_rim: f32,
}

impl LidSphincter {
    /// Chart coordinates of `p`: (xi, height above the corner line).
    pub fn chart(&self, p: Vec3) -> (f32, f32) {
        let d = p - self.centre;
        (d.dot(self.axis_x) / self.half_width, d.dot(self.axis_y))
    }

    /// Heights of the upper and lower margins at chart position `xi`.
    pub fn margins(&self, xi: f32) -> (f32, f32) {
        let u = 1.0 - xi * xi;
        (
            self.upper_h * lid_margin(u, true),
            -self.lower_h * lid_margin(u, false),
        )
    }

    /// Displacement `P' - P` of rest point `p` at contraction `k`: (F5)
    /// `rho = s / ly` with `s` the height above the lower margin, (F6)
    /// `-2 k f s` along `axis_y`, `f = 1 - rho/2` on `0 <= rho <= 2`.
    pub fn displacement(&self, p: Vec3, k: f32) -> Vec3 {
        let (xi, eta) = self.chart(p);
        if xi.abs() >= 1.0 {
            return Vec3::ZERO;
        }
        let (up, low) = self.margins(xi);
        let (s, gap) = (eta - low, up - low);
        if s <= 0.0 || gap <= 0.0 {
            return Vec3::ZERO;
        }
        let rho = self.rho_rim * s / gap; // (F5), ly = gap / rho_rim
        if rho >= 2.0 {
            return Vec3::ZERO;
        }
        -2.0 * k * (1.0 - 0.5 * rho) * s * self.axis_y // (F6)
    }
}

/// Jaw rotation fraction `alpha / theta` of (F7) at distance `d` from the
/// face's vertical midline; `l` = half the mouth width, `big_l` = midline to
/// the jaw's outer edge (`big_l > l`). 1 at the midline, 1/3 at `d = l`,
/// 0 at and beyond `d = L`.
pub fn jaw_fraction(d: f32, l: f32, big_l: f32) -> f32 {
    let d = d.abs();
    if d < l {
        (1.0 - 8.0 * d * d / (9.0 * l * l)).sqrt() // (F7), inner branch
    } else if d <= big_l {
        (d - big_l) / (3.0 * (l - big_l)) // (F7), outer branch
    } else {
        0.0
    }
}

/// The mandible: rotation about the axis through the two jaw joints,
/// applied to skin below the mouth-corner-to-ear-lobe lines (face.md 5).
/// The midline is the plane `x = 0` of the head frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Jaw {
    /// A point on the rotation axis (midpoint of the two jaw joints); the
    /// axis is the head's +X (positive angle = chin down).
    pub pivot: Vec3,
    /// Left mouth corner (+X side); the right one is its mirror.
    pub mouth_corner: Vec3,
    /// Left ear lobe (+X side); the right one is its mirror.
    pub ear_lobe: Vec3,
    /// l: half the mouth width.
    pub half_mouth_width: f32,
    /// L: distance from the midline to the jaw's outer edge.
    pub jaw_half_width: f32,
}

impl Jaw {
    /// True when `p` lies below the boundary line: in side view (y-z), the
    /// line from the mouth corner to the ear lobe, continued horizontally
    /// forward of the mouth corner (the mouth line).
    pub fn below_boundary(&self, p: Vec3) -> bool {
        let (c, e) = (self.mouth_corner, self.ear_lobe);
        let y_line = if p.z >= c.z {
            c.y
        } else if p.z <= e.z {
            e.y
        } else {
            c.y + (e.y - c.y) * (p.z - c.z) / (e.z - c.z)
        };
        p.y < y_line
    }

    /// `alpha / theta` for rest point `p`: (F7) below the boundary, else 0.
    pub fn fraction(&self, p: Vec3) -> f32 {
        if self.below_boundary(p) {
            jaw_fraction(p.x, self.half_mouth_width, self.jaw_half_width)
        } else {
            0.0
        }
    }

    /// Displacement of rest point `p` for jaw angle `theta` (radians,
    /// positive = chin down): rotation by `alpha` about the jaw axis (F7).
    pub fn displacement(&self, p: Vec3, theta: f32) -> Vec3 {
        let alpha = theta * self.fraction(p);
        if alpha == 0.0 {
            return Vec3::ZERO;
        }
        jaw_rotation(p - self.pivot, alpha)
    }
}

/// Displacement of a point at offset `r` from the jaw pivot rotated by
/// `alpha` (rad) about the head's +X axis (F7), with 7th-order sine and
/// 6th-order cosine series: below about 20 deg exact to single precision,
/// and no trigonometric call per vertex (the rig's hot loop uses it).
pub fn jaw_rotation(r: Vec3, alpha: f32) -> Vec3 {
    // Series coefficients as reciprocals: a float division by a constant
    // stays a division, several times a multiplication's cost.
    const S3: f32 = 1.0 / 6.0;
    const S5: f32 = 1.0 / 20.0;
    const S7: f32 = 1.0 / 42.0;
    const C4: f32 = 1.0 / 12.0;
    const C6: f32 = 1.0 / 30.0;
    let x2 = alpha * alpha;
    let s = alpha * (1.0 - x2 * S3 * (1.0 - x2 * S5 * (1.0 - x2 * S7)));
    let c = 1.0 - x2 * 0.5 * (1.0 - x2 * C4 * (1.0 - x2 * C6));
    Vec3::new(0.0, r.y * (c - 1.0) - r.z * s, r.y * s + r.z * (c - 1.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f32, b: f32, tol: f32) -> bool {
        (a - b).abs() <= tol
    }

    fn zyg() -> LinearMuscle {
        LinearMuscle {
            v1: Vec3::new(0.06, 0.0, 0.02),
            v2: Vec3::new(0.03, -0.05, 0.07),
            cone_half_angle: 25f32.to_radians(),
            rf_ratio: 1.4,
        }
    }

    #[test]
    fn linear_zero_at_v1_outside_cone_and_beyond_rf() {
        let m = zyg();
        assert_eq!(m.displacement(m.v1, 1.0), Vec3::ZERO);
        let axis = (m.v2 - m.v1).normalize();
        let rs = m.rest_length();
        // Beyond rf along the axis.
        assert_eq!(m.displacement(m.v1 + axis * rs * 1.41, 1.0), Vec3::ZERO);
        // Exactly at rf: cos(pi/2) ~ 0.
        assert!(m.displacement(m.v1 + axis * rs * 1.4, 1.0).length() < 1e-7);
        // Outside the cone: 30 deg off axis (B = 25 deg).
        let perp = axis.any_orthonormal_vector();
        let a = 30f32.to_radians();
        let p = m.v1 + (axis * a.cos() + perp * a.sin()) * rs * 0.8;
        assert_eq!(m.displacement(p, 1.0), Vec3::ZERO);
        // Behind V1.
        assert_eq!(m.displacement(m.v1 - axis * 0.01, 1.0), Vec3::ZERO);
    }

    #[test]
    fn linear_v2_moves_k_rs_towards_v1() {
        let m = zyg();
        let rs = m.rest_length();
        for k in [0.19f32, 0.5, -0.3] {
            let d = m.displacement(m.v2, k);
            assert!(close(d.length(), k.abs() * rs, 1e-6), "k={k}");
            // Direction: towards V1 for k > 0.
            let to_v1 = (m.v1 - m.v2).normalize();
            assert!(close(d.dot(to_v1), k * rs, 1e-6));
        }
    }

    #[test]
    fn linear_falloff_matches_f2_f3() {
        let m = zyg();
        let rs = m.rest_length();
        let rf = 1.4 * rs;
        let axis = (m.v2 - m.v1).normalize();
        let perp = axis.any_orthonormal_vector();
        let b = m.cone_half_angle;
        for &(af, df) in &[
            (0.0f32, 0.5f32),
            (0.5, 0.5),
            (0.3, 1.2),
            (0.9, 1.0),
            (0.5, 1.35),
        ] {
            let ang = af * b;
            let d = df * rs;
            let p = m.v1 + (axis * ang.cos() + perp * ang.sin()) * d;
            let a = (af * FRAC_PI_2).cos();
            let r = if d <= rs {
                ((1.0 - df) * FRAC_PI_2).cos()
            } else {
                ((d - rs) / (rf - rs) * FRAC_PI_2).cos()
            };
            let expect = a * r * 0.2 * rs;
            let got = m.displacement(p, 0.2);
            assert!(
                close(got.length(), expect, 2e-6),
                "af={af} df={df}: {} vs {expect}",
                got.length()
            );
            // Along V1P, towards V1.
            let dir = (p - m.v1).normalize();
            assert!(close(got.dot(dir), -expect, 2e-6));
        }
        // Hand values: A = B/2 and d = rs/2 gives a = r = cos(pi/4).
        assert!(close(angular_falloff(0.5, 1.0), 0.5f32.sqrt(), 1e-6));
        assert!(close(radial_falloff(0.5, 1.0, 1.5), 0.5f32.sqrt(), 1e-6));
        assert!(close(radial_falloff(1.25, 1.0, 1.5), 0.5f32.sqrt(), 1e-6));
        assert!(close(radial_falloff(1.0, 1.0, 1.5), 1.0, 1e-6));
    }

    fn oris() -> Sphincter {
        Sphincter {
            centre: Vec3::new(0.0, -0.07, 0.08),
            axis_x: Vec3::X,
            axis_y: Vec3::Y,
            lx: 0.02,
            ly: 0.012,
            part: SphincterPart::Full,
            x_share: 1.0,
        }
    }

    #[test]
    fn sphincter_ring_moves_k_op_and_zero_at_centre_and_boundary() {
        let s = oris();
        let k = 0.46;
        for i in 0..12 {
            let t = i as f32 / 12.0 * std::f32::consts::TAU;
            let p = s.centre + Vec3::new(s.lx * t.cos(), s.ly * t.sin(), 0.0);
            assert!(close(s.rho(p), 1.0, 1e-5));
            let d = s.displacement(p, k);
            let op = p - s.centre;
            assert!(close(d.length(), k * op.length(), 1e-6), "t={t}");
            assert!(d.dot(op) < 0.0, "pulled towards O");
            // At rho = 2 and beyond: nothing.
            let q = s.centre + 2.0 * op;
            assert!(s.displacement(q, k).length() < 1e-7);
            assert_eq!(s.displacement(s.centre + 2.2 * op, k), Vec3::ZERO);
            // rho = 1.5: f = 1/4, displacement 2 k f |OP| = k/2 * 1.5 |op|.
            let q = s.centre + 1.5 * op;
            assert!(close(
                s.displacement(q, k).length(),
                0.5 * k * 1.5 * op.length(),
                1e-6
            ));
        }
        assert_eq!(s.displacement(s.centre, k), Vec3::ZERO);
        // Out-of-plane offset does not change the in-plane displacement.
        let p = s.centre + Vec3::new(0.01, 0.005, 0.0);
        let d0 = s.displacement(p, k);
        let d1 = s.displacement(p + Vec3::Z * 0.003, k);
        assert!(d0.distance(d1) < 1e-7 && d0.z == 0.0);
    }

    #[test]
    fn half_sphincter_acts_on_its_half_only() {
        let s = Sphincter {
            part: SphincterPart::Upper,
            ..oris()
        };
        assert!(s.displacement(s.centre + Vec3::new(0.0, 0.01, 0.0), 0.5).y < 0.0);
        assert_eq!(
            s.displacement(s.centre + Vec3::new(0.0, -0.01, 0.0), 0.5),
            Vec3::ZERO
        );
        // The edge is continuous: nothing on the centre line, half of (F6)
        // halfway through the feather, all of it past the feather.
        let full = Sphincter {
            part: SphincterPart::Full,
            ..s
        };
        let at = |y: f32| s.centre + Vec3::new(0.012, y, 0.0);
        assert!(s.displacement(at(1e-7), 0.5).length() < 1e-6);
        let mid = 0.5 * HALF_FEATHER * s.ly;
        assert!(
            (s.displacement(at(mid), 0.5) - 0.5 * full.displacement(at(mid), 0.5)).length() < 1e-7
        );
        let past = 1.2 * HALF_FEATHER * s.ly;
        assert_eq!(
            s.displacement(at(past), 0.5),
            full.displacement(at(past), 0.5)
        );
    }

    #[test]
    fn lid_sphincter_lays_the_upper_margin_on_the_lower_at_blink() {
        let k45 = 2.9f32;
        let s = LidSphincter {
            centre: Vec3::new(0.031, 0.0, 0.01),
            axis_x: Vec3::X,
            axis_y: Vec3::Y,
            half_width: 0.0155,
            upper_h: 0.0046,
            lower_h: 0.0042,
            rho_rim: 2.0 - 1.0 / k45,
        };
        for i in 1..20 {
            let xi = -1.0 + i as f32 / 10.0;
            let (up, low) = s.margins(xi);
            let p = s.centre + Vec3::new(xi * s.half_width, up, 0.0);
            let moved = p + s.displacement(p, k45);
            assert!(close(moved.y - s.centre.y, low, 1e-6), "xi {xi}");
            assert!(close(moved.x, p.x, 1e-9), "vertical only");
            // Lower margin, below it, and rho >= 2 do not move.
            let q = s.centre + Vec3::new(xi * s.half_width, low, 0.0);
            assert_eq!(s.displacement(q - Vec3::Y * 1e-4, k45), Vec3::ZERO);
            let far = low + (up - low) * 2.0 / s.rho_rim + 1e-5;
            assert_eq!(
                s.displacement(s.centre + Vec3::new(p.x - s.centre.x, far, 0.0), k45),
                Vec3::ZERO
            );
        }
        let outside = s.centre + Vec3::new(1.01 * s.half_width, 0.001, 0.0);
        assert_eq!(s.displacement(outside, k45), Vec3::ZERO);
    }

    fn jaw() -> Jaw {
        Jaw {
            pivot: Vec3::new(0.0, -0.035, -0.01),
            mouth_corner: Vec3::new(0.026, -0.068, 0.07),
            ear_lobe: Vec3::new(0.07, -0.045, -0.01),
            half_mouth_width: 0.026,
            jaw_half_width: 0.06,
        }
    }

    #[test]
    fn jaw_fraction_closed_forms() {
        let (l, big_l) = (0.026, 0.06);
        assert!(close(jaw_fraction(0.0, l, big_l), 1.0, 1e-7));
        assert!(close(jaw_fraction(l, l, big_l), 1.0 / 3.0, 1e-6));
        // Inner branch just below l also tends to 1/3 (continuous).
        assert!(close(jaw_fraction(l * 0.9999, l, big_l), 1.0 / 3.0, 1e-3));
        assert!(close(jaw_fraction(big_l, l, big_l), 0.0, 1e-7));
        assert_eq!(jaw_fraction(0.07, l, big_l), 0.0);
        // d = l/2: sqrt(1 - 8/36).
        assert!(close(
            jaw_fraction(-l / 2.0, l, big_l),
            (1.0f32 - 8.0 / 36.0).sqrt(),
            1e-6
        ));
    }

    #[test]
    fn jaw_rotates_chin_by_theta_and_spares_upper_face() {
        let j = jaw();
        let theta = 14.4f32.to_radians();
        let chin = Vec3::new(0.0, -0.11, 0.06);
        let d = j.displacement(chin, theta);
        let (r0, r1) = (chin - j.pivot, chin + d - j.pivot);
        assert!(close(r0.length(), r1.length(), 1e-6));
        let ang = (r0.dot(r1) / (r0.length() * r1.length())).acos();
        assert!(close(ang, theta, 1e-4));
        assert!(d.y < 0.0, "chin goes down");
        // Corner-height point at d = l below the line: theta / 3.
        let p = Vec3::new(0.026, -0.08, 0.06);
        // Rotation angle about X: measure in the y-z plane.
        let r0 = (p - j.pivot) * Vec3::new(0.0, 1.0, 1.0);
        let r1 = (p + j.displacement(p, theta) - j.pivot) * Vec3::new(0.0, 1.0, 1.0);
        let ang = r0.cross(r1).length().atan2(r0.dot(r1));
        assert!(close(ang, theta / 3.0, 1e-4), "{ang} vs {}", theta / 3.0);
        // Above the mouth line / mouth-ear line: nothing.
        for p in [
            Vec3::new(0.0, -0.06, 0.08),
            Vec3::new(0.05, -0.05, 0.03),
            Vec3::new(0.03, 0.0, 0.05),
        ] {
            assert_eq!(j.displacement(p, theta), Vec3::ZERO);
        }
        // Beyond L: nothing.
        assert_eq!(
            j.displacement(Vec3::new(0.065, -0.1, 0.0), theta),
            Vec3::ZERO
        );
    }
}
