//! The head's surface: superellipse sections over height, the front's
//! analytic features, the openings' warp, and the grid's rows and columns
//! laid over it.

use super::dims::*;
use crate::muscle::lid_margin;
use glam::Vec3;
use shisen_gaze::util::math::{gauss, hermite, smoothstep};

/// Interpolation ([`hermite`]) through knots given with y descending;
/// constant outside.
fn table(knots: &[(f32, f32)], y: f32) -> f32 {
    hermite(knots.len(), |i| knots[i], y)
}

const EXPO: f32 = 2.4; // section superellipse exponent

/// Rounding into the poles.
fn dome(y: f32) -> f32 {
    let top = if y > 0.06 {
        (1.0 - ((y - 0.06) / (TOP_Y - 0.06)).powi(2))
            .max(0.0)
            .sqrt()
    } else {
        1.0
    };
    let bot = if y < -0.10 {
        (1.0 - ((y + 0.10) / (-0.10 - BOTTOM_Y)).powi(2))
            .max(0.0)
            .sqrt()
    } else {
        1.0
    };
    top * bot
}

/// Section half-width, front depth, back depth at height y.
pub(super) fn section(y: f32) -> (f32, f32, f32) {
    let a = table(
        &[
            (TOP_Y, 0.070),
            (0.10, 0.073),
            (0.06, 0.075),
            (0.02, 0.076),
            (-0.02, 0.072),
            (-0.06, 0.064),
            (-0.09, 0.053),
            (-0.112, 0.046),
            (BOTTOM_Y, 0.040),
        ],
        y,
    );
    let f = table(
        &[
            (TOP_Y, 0.085),
            (0.10, 0.085),
            (0.06, 0.087),
            (0.02, 0.095),
            (-0.02, 0.091),
            (-0.06, 0.093),
            (-0.09, 0.089),
            (-0.112, 0.080),
            (BOTTOM_Y, 0.070),
        ],
        y,
    );
    let b = table(
        &[
            (TOP_Y, 0.095),
            (0.06, 0.095),
            (0.02, 0.095),
            (-0.02, 0.090),
            (-0.06, 0.075),
            (-0.09, 0.062),
            (-0.112, 0.055),
            (BOTTOM_Y, 0.050),
        ],
        y,
    );
    let d = dome(y);
    (a * d, f * d, b * d)
}

/// Which side of a slit a vertex is on.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(super) enum SlitSide {
    Upper,
    Lower,
}

/// Vertical opening warp for a point (x, y) on the given side (eyes and mouth).
fn opening_warp(x: f32, y: f32, side: SlitSide, corners: &[(f32, f32); 3]) -> f32 {
    let mut dy = 0.0;
    // Eyes: slit at y = 0.
    for (k, &(xa, xb)) in corners.iter().take(2).enumerate() {
        let (lo, hi) = if k == 0 { (xa, xb) } else { (-xb, -xa) };
        if x > lo && x < hi {
            let c = 0.5 * (lo + hi);
            let w = 0.5 * (hi - lo);
            let u = 1.0 - ((x - c) / w).powi(2);
            let (amp, r) = match side {
                SlitSide::Upper => (UPPER_LID_H * lid_margin(u, true), 0.010),
                SlitSide::Lower => (-LOWER_LID_H * lid_margin(u, false), 0.008),
            };
            dy += amp * (1.0 - y.abs() / r).max(0.0);
        }
    }
    // Mouth: tiny gap between the lips.
    let xm = corners[2].1;
    if x.abs() < xm {
        let u = 1.0 - (x / xm).powi(2);
        let amp = match side {
            SlitSide::Upper => 0.0006,
            SlitSide::Lower => -0.0006,
        } * u;
        dy += amp * (1.0 - (y - MOUTH_Y).abs() / 0.004).max(0.0);
    }
    dy
}

/// Height-field features of the front face (added to z).
fn features(x: f32, y: f32) -> f32 {
    let ax = x.abs();
    // Brow ridge.
    let brow = 0.003 * gauss(y - 0.02, 0.009) * (1.0 - smoothstep(0.04, 0.06, ax));
    // Nose ridge from the nasion to the tip, then the columella to the base.
    let tip_y = NOSE_BASE_Y + 0.010;
    let ridge_h = if y > NASION_Y + 0.004 {
        0.0
    } else if y > tip_y {
        let s = (NASION_Y + 0.004 - y) / (NASION_Y + 0.004 - tip_y);
        0.019 * s.powf(1.3)
    } else {
        0.019 * (1.0 - smoothstep(0.0, 1.0, (tip_y - y) / 0.011))
    };
    let ridge_w = 0.0045 + 0.005 * smoothstep(NASION_Y, tip_y, y);
    let nose = ridge_h * gauss(ax, ridge_w);
    // Alar wings.
    let wing = 0.008 * gauss(ax - 0.0115, 0.0055) * gauss(y - (NOSE_BASE_Y + 0.005), 0.007);
    // Cheeks.
    let cheek = 0.006 * gauss(ax - 0.045, 0.018) * gauss(y + 0.03, 0.02);
    // Lips.
    let lip_shape = (1.0 - (ax / 0.03).powi(2)).max(0.0);
    let upper_lip = 0.0055 * lip_shape * gauss(y - (MOUTH_Y + 0.0065), 0.0055);
    let lower_lip = 0.005 * lip_shape * gauss(y - (MOUTH_Y - 0.008), 0.0055);
    // Chin.
    let chin = 0.006 * gauss(ax, 0.014) * gauss(y - (CHIN_Y + 0.014), 0.011);
    brow + nose + wing + cheek + upper_lip + lower_lip + chin
}

/// Front height field z(x, y) with features and the eye sockets/lid shells.
fn front_z(x: f32, y: f32) -> f32 {
    let (a, f, _) = section(y);
    let s = (x.abs() / a).min(1.0);
    let base = Z_C + f * (1.0 - s.powf(EXPO)).max(0.0).powf(1.0 / EXPO);
    let fade = 1.0 - smoothstep(0.8, 0.95, s);
    let mut z = base + features(x, y) * fade;
    for ex in [EYE_X, -EYE_X] {
        let q = ((x - ex) / SHELL[0]).powi(2) + (y / SHELL[1]).powi(2);
        let shell = SHELL[2] * (1.0 - q).max(0.0).sqrt();
        let w = 1.0 - smoothstep(0.55, 1.0, q);
        z = z + (shell - z) * w;
    }
    z
}

/// Point on the head surface for grid angle `phi` (0 = front, > 0 to +X)
/// at height `y`, on `side` of a slit (warp) if in the front.
pub(super) fn surface(phi: f32, y: f32, side: SlitSide, corners: &[(f32, f32); 3]) -> Vec3 {
    let (a, _, b) = section(y);
    let (s, c) = phi.sin_cos();
    let pw = 2.0 / EXPO;
    let x = a * s.signum() * s.abs().powf(pw);
    let mut p = if c > 0.0 {
        let yw = y + opening_warp(x, y, side, corners);
        Vec3::new(x, yw, front_z(x, yw))
    } else {
        Vec3::new(x, y, Z_C - b * c.abs().powf(pw))
    };
    // Ears: bumps along x on the sides.
    let ear = 0.011 * gauss(p.y + 0.015, 0.024) * gauss(p.z + 0.085, 0.011);
    p.x += p.x.signum() * ear;
    p
}

/// Front surface point at chart position (x, y) (no slit warp).
pub fn surface_at(x: f32, y: f32) -> Vec3 {
    let ear = 0.0;
    Vec3::new(x, y, front_z(x, y) + ear)
}

/// Column angles: dense at the front. `cols` even, phi(j) antisymmetric.
pub(super) fn column_phi(j: usize, cols: usize) -> f32 {
    let t = 2.0 * j as f32 / cols as f32; // 0..2
    let t = if t > 1.0 { t - 2.0 } else { t }; // (-1, 1]
    let c = 0.45;
    std::f32::consts::PI * (c * t + (1.0 - c) * t * t * t)
}

/// Row heights, top to bottom (rows + 1 values incl. the poles), with the
/// rows nearest the eye height and the mouth line moved exactly onto them.
pub(super) fn row_heights(rows: usize) -> (Vec<f32>, usize, usize) {
    let (ymid, h) = (0.5 * (TOP_Y + BOTTOM_Y), 0.5 * (TOP_Y - BOTTOM_Y));
    let b = 0.45;
    let mut ys: Vec<f32> = (0..=rows)
        .map(|i| {
            let v = i as f32 / rows as f32;
            let th = std::f32::consts::PI
                * (v + b * (std::f32::consts::TAU * v).sin() / std::f32::consts::TAU);
            ymid + h * th.cos()
        })
        .collect();
    let nearest = |ys: &[f32], t: f32| {
        (1..rows)
            .min_by(|&i, &j| (ys[i] - t).abs().total_cmp(&(ys[j] - t).abs()))
            .unwrap()
    };
    let (ie, im) = (nearest(&ys, 0.0), nearest(&ys, MOUTH_Y));
    // Piecewise-linear monotone remap through (ys[ie] -> 0), (ys[im] -> MOUTH_Y).
    let knots = [
        (ys[0], ys[0]),
        (ys[ie], 0.0),
        (ys[im], MOUTH_Y),
        (ys[rows], ys[rows]),
    ];
    for y in ys.iter_mut() {
        for w in knots.windows(2) {
            if *y <= w[0].0 && *y >= w[1].0 {
                let t = (w[0].0 - *y) / (w[0].0 - w[1].0);
                *y = w[0].1 + (w[1].1 - w[0].1) * t;
                break;
            }
        }
    }
    (ys, ie, im)
}
