//! The body mesh's shape: each part a grid of rings in the rest pose of
//! [`BodyPlan`], closed by poles (see the module above for the design), and
//! the skinning weights each vertex gets.

use std::f32::consts::{FRAC_PI_2, FRAC_PI_4, TAU};

use glam::{Quat, Vec3};
use shisen::physics::body::{BodyPlan, Seg, Shape};
use shisen::util::math::{gauss, hermite, smoothstep};

use shisen_face::mesh::compute_normals;

use super::{
    BodyMesh, BodyStyle, Bone, Lists, Part, Piece, SkinVertex, arm_frame, rest_legs, waist_rest,
};

type Weights = ([u8; 4], [f32; 4]);

/// Weights from (bone, weight) pairs, normalised; zeros dropped.
fn weights(pairs: &[(Bone, f32)]) -> Weights {
    let (mut bones, mut w, mut n) = ([0u8; 4], [0f32; 4], 0);
    for &(b, x) in pairs {
        if x > 1e-4 && n < 4 {
            (bones[n], w[n]) = (b as u8, x);
            n += 1;
        }
    }
    let sum: f32 = w.iter().sum();
    (bones, w.map(|x| x / sum))
}

/// A vertex under construction: position, colour, weights, part, design
/// point for the vest's openings ([`SkinVertex::vest`]).
#[derive(Clone, Copy)]
struct Pt(Vec3, [f32; 4], Weights, Part, Vec3);

/// Where a grid's triangles go: the whole body, also the first-person arm
/// list from a ring on, or the arm list only.
#[derive(Clone, Copy)]
enum Dest {
    Main,
    MainAndArm(usize),
    ArmOnly,
}

#[derive(Default)]
struct Builder {
    verts: Vec<SkinVertex>,
    parts: Vec<Part>,
    main: Lists,
    arm: Lists,
    all: Vec<u32>,
}

impl Builder {
    fn push(&mut self, &Pt(p, color, (bones, weights), part, vest): &Pt) -> u32 {
        let (pos, normal) = (p.to_array(), [0.0; 3]);
        let v = SkinVertex {
            pos,
            normal,
            color,
            vest: vest.to_array(),
            bones,
            weights,
        };
        self.verts.push(v);
        self.parts.push(part);
        self.verts.len() as u32 - 1
    }

    /// Add triangle `t` of ring band `band` to the lists `dest` names, at
    /// level of detail `level`.
    fn tri(&mut self, t: [u32; 3], band: usize, dest: Dest, level: usize) {
        if level == 0 {
            self.all.extend(t);
        }
        let (main, arm) = match dest {
            Dest::Main => (true, false),
            Dest::MainAndArm(first) => (true, band >= first),
            Dest::ArmOnly => (false, true),
        };
        if main {
            self.main.levels[level].extend(t);
        }
        if arm {
            self.arm.levels[level].extend(t);
        }
    }

    /// Quads between consecutive rings (each ring's points wind
    /// counter-clockwise about the direction from one ring to the next, seen
    /// from that direction's tip), fans to the optional start and end poles;
    /// at each coarser level of detail the same over every other ring or
    /// column (level 1: whichever departs less from the fine surface), then
    /// both (level 2), the first and last rings always. Rings have an even
    /// number of points.
    fn grid(&mut self, rings: &[Vec<Pt>], poles: [Option<Pt>; 2], dest: Dest) {
        let cols = rings[0].len();
        debug_assert!(cols.is_multiple_of(2), "{cols} columns");
        let base = self.verts.len() as u32;
        let starts = self.main.levels.each_ref().map(|l| l.len() as u32);
        let arm_starts = self.arm.levels.each_ref().map(|l| l.len() as u32);
        for pt in rings.iter().flatten() {
            self.push(pt);
        }
        let at = |k: usize, j: usize| base + (k * cols + j % cols) as u32;
        let last = rings.len() - 1;
        let pole = [
            poles[0].map(|p| self.push(&p)),
            poles[1].map(|p| self.push(&p)),
        ];
        // How far the points each coarser grid skips stand off it: each
        // from the middle of its neighbours across the rings, or along its
        // ring.
        let p = |k: usize, j: usize| rings[k][j % cols].0;
        let (mut across, mut along) = (0.0f32, 0.0f32);
        for k in 0..=last {
            for j in 0..cols {
                if j % 2 == 1 {
                    along = along.max(p(k, j).distance((p(k, j - 1) + p(k, j + 1)) / 2.0));
                } else if k % 2 == 1 && k < last {
                    across = across.max(p(k, j).distance((p(k - 1, j) + p(k + 1, j)) / 2.0));
                }
            }
        }
        // (ring step, column step) of each level.
        let half = if across <= along { (2, 1) } else { (1, 2) };
        let errors = [0.0, across.min(along), across.max(along)];
        for (level, (rs, cs)) in [(1, 1), half, (2, 2)].into_iter().enumerate() {
            let mut ks: Vec<usize> = (0..last).step_by(rs).collect();
            ks.push(last);
            for w in ks.windows(2) {
                let (k0, k1) = (w[0], w[1]);
                for j in (0..cols).step_by(cs) {
                    let (a, b) = (at(k0, j), at(k0, j + cs));
                    let (c, d) = (at(k1, j), at(k1, j + cs));
                    // The band of the quad's last fine band: a coarse
                    // quad across the first-person cut is kept.
                    self.tri([a, b, c], k1 - 1, dest, level);
                    self.tri([b, d, c], k1 - 1, dest, level);
                }
            }
            for j in (0..cols).step_by(cs) {
                if let Some(i) = pole[0] {
                    self.tri([i, at(0, j + cs), at(0, j)], 0, dest, level);
                }
                if let Some(i) = pole[1] {
                    self.tri([at(last, j), at(last, j + cs), i], last, dest, level);
                }
            }
        }
        // The grid's piece of each list it added to (the first-person
        // arms take part of a grid: the whole grid's errors bound theirs).
        let vertices = base..self.verts.len() as u32;
        for (lists, starts) in [(&mut self.main, starts), (&mut self.arm, arm_starts)] {
            let ends = lists.levels.each_ref().map(|l| l.len() as u32);
            if ends[0] > starts[0] {
                lists.pieces.push(Piece {
                    ranges: [0, 1, 2].map(|l| starts[l]..ends[l]),
                    vertices: vertices.clone(),
                    errors,
                });
            }
        }
    }
}

fn ring(cols: usize, f: impl Fn(f32) -> Pt) -> Vec<Pt> {
    (0..cols).map(|j| f(TAU * j as f32 / cols as f32)).collect()
}

/// Column `col` of `rows` against column 0 (ascending), interpolated
/// ([`hermite`]); constant outside.
fn table<const N: usize>(rows: &[[f32; N]], col: usize, x: f32) -> f32 {
    hermite(rows.len(), |i| (rows[i][0], rows[i][col]), x)
}

/// Torso sections, design metres for the default plan: height, half-width,
/// front depth, back depth; from the waist up over the shoulders to the neck.
#[rustfmt::skip]
const TORSO: [[f32; 4]; 13] = [
    [1.000, 0.138, 0.088, 0.086], [1.080, 0.140, 0.090, 0.088], [1.160, 0.146, 0.094, 0.090],
    [1.240, 0.156, 0.098, 0.093], [1.310, 0.165, 0.100, 0.096], [1.370, 0.170, 0.100, 0.098],
    [1.420, 0.178, 0.097, 0.099], [1.455, 0.182, 0.090, 0.096], [1.478, 0.170, 0.080, 0.090],
    [1.495, 0.145, 0.066, 0.082], [1.507, 0.115, 0.056, 0.072], [1.516, 0.085, 0.048, 0.062],
    [1.523, 0.055, 0.040, 0.050],
];
/// Neck sections: height above the neck pivot, half-width, half-depth.
/// Above the chin the neck is inside the head, slimmed so it stays behind
/// the mouth's cavity (it would show through parted lips).
#[rustfmt::skip]
const NECK: [[f32; 3]; 6] = [
    [-0.06, 0.066, 0.057], [-0.02, 0.062, 0.055], [0.01, 0.057, 0.054], [0.05, 0.056, 0.052],
    [0.08, 0.050, 0.038], [0.10, 0.040, 0.030],
];
/// Upper arm: distance below the shoulder, radii toward the front and across.
#[rustfmt::skip]
const UPPER_ARM: [[f32; 3]; 4] =
    [[0.0, 0.055, 0.055], [0.05, 0.051, 0.052], [0.10, 0.046, 0.045], [0.20, 0.044, 0.041]];
/// Forearm: distance from the elbow, radii toward the top and across.
#[rustfmt::skip]
const FOREARM: [[f32; 3]; 5] = [
    [0.05, 0.041, 0.041], [0.09, 0.040, 0.044], [0.13, 0.035, 0.038], [0.17, 0.031, 0.032],
    [0.23, 0.028, 0.029],
];
/// Glove: distance ahead of the glove centre, half-height above (back of
/// the hand) and below (palm), half-width; the cuff, then the fist.
#[rustfmt::skip]
const GLOVE: [[f32; 4]; 10] = [
    [-0.135, 0.027, 0.027, 0.027], [-0.131, 0.041, 0.041, 0.041], [-0.126, 0.046, 0.046, 0.046],
    [-0.09, 0.048, 0.048, 0.048], [-0.07, 0.049, 0.0485, 0.049], [-0.052, 0.054, 0.049, 0.051],
    [-0.03, 0.058, 0.0495, 0.052], [0.0, 0.06, 0.05, 0.052], [0.02, 0.059, 0.049, 0.052],
    [0.03, 0.059, 0.049, 0.052],
];
const TORSO_COLS: usize = 56;
const NECK_COLS: usize = 24;
const ARM_COLS: usize = 24;
const GLOVE_COLS: usize = 32;
/// Radius of the ball round each shoulder pivot (the deltoid).
const DELTOID_R: f32 = 0.055;
/// Radius of the arm at the elbow.
const ELBOW_R: f32 = 0.041;
/// Radius of the elbow's bend in the rest pose, about an axis on the
/// crook's side (greater than `ELBOW_R`, so the crook does not fold).
const ELBOW_BEND: f32 = 0.052;
/// Half-length of the elbow's weight blend along the crook.
const ELBOW_BLEND: f32 = 0.05;
/// First-person arm list: the upper arm from this far below the shoulder.
const FIRST_PERSON_FROM: f32 = 0.12;

/// The vest's armholes, in the torso's design frame (m): ellipses in x, y
/// centred at |x| = `[0]`, y = `[1]`, half-axes `[2]` across and `[3]` up.
/// The shader draws the vest's openings per pixel from each torso point's
/// design position ([`SkinVertex::vest`]; `fs_body` in `shader.wgsl`, to
/// which these numbers are prepended), so the hem is a smooth curve on any
/// level of detail.
pub const VEST_ARMHOLE: [f32; 4] = [0.215, 1.47, 0.085, 0.15];
/// The vest's neckline: an ellipse in x, y centred at x = 0, y = `[0]`,
/// half-width `[1]`, half-height `[2]` at the back, `[3]` more at the front
/// (blended between z = `[4]` and `[5]`): a scoop.
pub const VEST_NECK: [f32; 6] = [1.535, 0.09, 0.035, 0.05, -0.02, 0.04];
/// Metres per unit of elliptic radius near the hem (to turn the ellipses'
/// radius into a distance), and the half-width of its soft edge, m.
pub const VEST_HEM: [f32; 2] = [0.085, 0.0015];

/// A vertex outside the vest's openings whatever its part: no border.
const NO_VEST: Vec3 = Vec3::new(0.0, 100.0, 0.0);

/// Torso section point (design frame) at angle `th` (0 front, +X at pi/2).
fn torso_point(y: f32, a: f32, f: f32, b: f32, th: f32) -> Vec3 {
    let (s, c) = th.sin_cos();
    let e = 2.0 / if c >= 0.0 { 2.6 } else { 3.2 };
    let x = a * s.signum() * s.abs().powf(e);
    let mut z = c.signum() * c.abs().powf(e) * if c >= 0.0 { f } else { b };
    let (front, back) = (smoothstep(0.0, 0.6, c), smoothstep(0.0, 0.6, -c));
    let ax = x.abs();
    let pec_y = if y < 1.375 { 0.03 } else { 0.07 };
    let pec = 0.013 * gauss(ax - 0.075, 0.05) * gauss(y - 1.375, pec_y);
    let sternum = -0.004 * gauss(x, 0.015) * gauss(y - 1.33, 0.08);
    let blades = 0.006 * gauss(ax - 0.085, 0.04) * gauss(y - 1.38, 0.05);
    let spine = -0.004 * gauss(x, 0.012) * smoothstep(1.0, 1.1, y);
    z += front * (pec + sternum) - back * (blades + spine);
    Vec3::new(x, y, z)
}

fn torso(b: &mut Builder, plan: &BodyPlan, style: &BodyStyle) {
    let t = &plan.segments[Seg::Torso.index()];
    let half = match t.shape {
        Shape::Cuboid { half } => half,
        _ => Vec3::new(0.16, 0.25, 0.10),
    };
    let k = half / Vec3::new(0.16, 0.25, 0.10);
    let origin = t.centre - Vec3::Y * half.y;
    let shoulders = [0, 1]
        .map(|s| plan.segments[Bone::upper_arm(s).segment().expect("physical").index()].pivot);
    let point = |d: Vec3| {
        let p = origin + (d - Vec3::Y) * k;
        let arm = shoulders.map(|s| 0.5 * (1.0 - smoothstep(0.03, 0.085, p.distance(s))));
        let w = [(Bone::UpperArmL, arm[0]), (Bone::UpperArmR, arm[1])];
        let w = weights(&[(Bone::Torso, 1.0 - arm[0] - arm[1]), w[0], w[1]]);
        Pt(p, style.shirt, w, Part::Torso, d)
    };
    // Four rings per knot interval.
    let rings: Vec<Vec<Pt>> = (0..=(TORSO.len() - 1) * 4)
        .map(|i| {
            let (r0, r1) = (TORSO[i / 4], TORSO[(i / 4 + 1).min(TORSO.len() - 1)]);
            let y = r0[0] + (r1[0] - r0[0]) * (i % 4) as f32 / 4.0;
            let [a, f, bk] = [1, 2, 3].map(|c| table(&TORSO, c, y));
            ring(TORSO_COLS, |th| point(torso_point(y, a, f, bk, th)))
        })
        .collect();
    let top = point(Vec3::new(0.0, TORSO[TORSO.len() - 1][0] + 0.004, 0.0));
    b.grid(&rings, [None, Some(top)], Dest::Main);
    // The waist's cap (its own ring, so its normals point down).
    let waist = point(Vec3::new(0.0, TORSO[0][0], 0.0));
    b.grid(&rings[..1], [Some(waist), None], Dest::Main);
}

fn neck(b: &mut Builder, plan: &BodyPlan, style: &BodyStyle) {
    let pivot = plan.segments[Seg::Head.index()].pivot;
    let point = |dy: f32, th: f32| {
        let (s, c) = th.sin_cos();
        let (a, d) = (table(&NECK, 1, dy), table(&NECK, 2, dy));
        let centre = pivot + Vec3::new(0.0, dy, -0.012 + 0.11 * (dy + 0.06));
        let head = smoothstep(-0.03, 0.1, dy);
        let w = weights(&[(Bone::Torso, 1.0 - head), (Bone::Head, head)]);
        let p = centre + Vec3::new(a * s, 0.0, d * c);
        Pt(p, style.skin, w, Part::Neck, NO_VEST)
    };
    // From inside the torso to inside the head.
    let rings: Vec<Vec<Pt>> = (0..=10)
        .map(|i| ring(NECK_COLS, |th| point(-0.058 + 0.0156 * i as f32, th)))
        .collect();
    let (mut bottom, mut top) = (point(-0.066, 0.0), point(0.106, 0.0));
    bottom.0 = pivot + Vec3::new(0.0, -0.066, -0.013);
    top.0 = pivot + Vec3::new(0.0, 0.106, 0.007);
    b.grid(&rings, [Some(bottom), Some(top)], Dest::Main);
}

/// An arm's ring: centre, turn about the elbow (its frame), radii toward U
/// and V, bulges on the crook's and the outer side, length along the crook.
type ArmRing = (Vec3, f32, [f32; 2], [f32; 2], f32);

fn arm(b: &mut Builder, plan: &BodyPlan, style: &BodyStyle, side: usize) {
    let (s, e, g, d1, d2) = arm_frame(plan, side);
    let (l1, l2) = (s.distance(e), e.distance(g));
    let axis = d1.cross(d2).normalize();
    let (ua, fa) = (Bone::upper_arm(side), Bone::forearm(side));
    // Ring frame after turning `alpha` round the elbow: U toward the crook
    // (front of the upper arm, top of the forearm), V = T x U.
    let frame = |alpha: f32| {
        let q = Quat::from_axis_angle(axis, alpha);
        let (t, u) = (q * d1, q * d2);
        (u, t.cross(u))
    };
    // Forearm weight: on the crook's side it grows with the length along
    // the crook over a long span (the crook opens without tearing); on the
    // outer side it grows across the plane bisecting the bend, over about
    // the elbow's diameter (the back of the elbow neither folds nor sinks
    // when the arm straightens).
    let crook = ELBOW_BEND - ELBOW_R;
    let elbow_at = l1 - ELBOW_BEND + crook * FRAC_PI_4;
    let bisector = (d1 + d2).normalize();
    let pt = |p: Vec3, cs: f32, along: f32| {
        let by_length = smoothstep(elbow_at - ELBOW_BLEND, elbow_at + ELBOW_BLEND, along);
        let by_side = smoothstep(-0.07, 0.07, (p - e).dot(bisector));
        let f = by_side + (by_length - by_side) * smoothstep(-0.3, 0.6, cs);
        // The deltoid's top partly stays with the torso.
        let t = 0.25 * smoothstep(0.3, 1.0, (s - p).dot(d1) / DELTOID_R);
        let w = weights(&[(Bone::Torso, t), (ua, 1.0 - t - f), (fa, f)]);
        Pt(p, style.skin, w, Part::Arm(side), NO_VEST)
    };
    let mut specs: Vec<ArmRing> = Vec::new();
    // The deltoid: a ball round the shoulder pivot.
    for k in 1..=6 {
        let (sin, cos) = (FRAC_PI_2 * (1.0 - k as f32 / 6.0)).sin_cos();
        let (c, r, along) = (s - d1 * DELTOID_R * sin, DELTOID_R * cos, -DELTOID_R * sin);
        specs.push((c, 0.0, [r, r], [0.0; 2], along));
    }
    for i in 1..=9 {
        let t = (l1 - ELBOW_BEND) * i as f32 / 10.0;
        let (ru, rv) = (table(&UPPER_ARM, 1, t), table(&UPPER_ARM, 2, t));
        let ru = ru + (ELBOW_R - ru) * smoothstep(l1 - 0.1, l1 - ELBOW_BEND, t);
        let bulge = [0.005 * gauss(t - 0.15, 0.045), 0.003 * gauss(t - 0.1, 0.05)];
        specs.push((s + d1 * t, 0.0, [ru, rv.max(ELBOW_R)], bulge, t));
    }
    // The elbow: rings turning about an axis on the crook's side, the outer
    // side filled out toward the sharp corner (the olecranon) so that it
    // keeps the arm's girth when straightened.
    let q = e - d1 * ELBOW_BEND + d2 * ELBOW_BEND;
    for k in 0..=12 {
        let alpha = FRAC_PI_2 * k as f32 / 12.0;
        let (sn, cs) = alpha.sin_cos();
        let corner = (ELBOW_BEND + ELBOW_R) * ((sn.powi(8) + cs.powi(8)).powf(-0.125) - 1.0);
        let (c, along) = (
            q - frame(alpha).0 * ELBOW_BEND,
            l1 - ELBOW_BEND + crook * alpha,
        );
        specs.push((c, alpha, [ELBOW_R; 2], [0.0, corner], along));
    }
    // The forearm, on into the glove's cuff.
    let end = l2 - 0.075;
    for i in 1..=9 {
        let t = ELBOW_BEND + (end - ELBOW_BEND) * i as f32 / 9.0;
        let r = [table(&FOREARM, 1, t), table(&FOREARM, 2, t)];
        let (along, bulge) = (
            l1 - 2.0 * ELBOW_BEND + crook * FRAC_PI_2 + t,
            0.004 * gauss(t - 0.08, 0.04),
        );
        specs.push((e + d2 * t, FRAC_PI_2, r, [bulge, 0.0], along));
    }
    let rings: Vec<Vec<Pt>> = specs
        .iter()
        .map(|&(c, alpha, r, bulge, along)| {
            let (u, v) = frame(alpha);
            ring(ARM_COLS, |th| {
                let (sn, cs) = th.sin_cos();
                let out = bulge[0] * cs.max(0.0).powi(2) + bulge[1] * (-cs).max(0.0).powi(2);
                let p = c + u * (r[0] * cs) + v * (r[1] * sn) + (u * cs + v * sn) * out;
                pt(p, cs, along)
            })
        })
        .collect();
    let cut = specs
        .iter()
        .position(|r| r.4 >= FIRST_PERSON_FROM)
        .unwrap_or(0);
    let pole = pt(s - d1 * DELTOID_R, 0.0, -1.0);
    let tip = pt(e + d2 * (end + 0.01), 0.0, 1.0);
    b.grid(&rings, [Some(pole), Some(tip)], Dest::MainAndArm(cut));
    // Close the first-person cut (drawn only in that view).
    let mut centre = rings[cut][0];
    centre.0 = specs[cut].0;
    b.grid(&rings[cut..=cut], [Some(centre), None], Dest::ArmOnly);
}

fn glove(b: &mut Builder, plan: &BodyPlan, style: &BodyStyle, side: usize) {
    let (_, _, g, d1, d2) = arm_frame(plan, side);
    // The fist's surface centred on the glove centre (its knuckle face just
    // inside the collision ball).
    let g = g - d2 * 0.009;
    let (u, v) = (-d1, d2.cross(-d1));
    let torso_x = plan.segments[Seg::Torso.index()].centre.x;
    let medial = Vec3::X * -(g.x - torso_x).signum();
    let thumb = (medial - 0.3 * u).normalize();
    let w = weights(&[(Bone::forearm(side), 1.0)]);
    let size = |t: f32| Vec3::from_array([1, 2, 3].map(|c| table(&GLOVE, c, t)));
    let point = |t: f32, scale: f32, th: f32| {
        let (sn, cs) = th.sin_cos();
        let e = 2.0 / (2.0 + 0.6 * smoothstep(-0.075, -0.045, t));
        let sz = size(t.min(0.02)) * scale;
        let dir = u * cs + v * sn;
        let thumb_amp =
            0.017 * smoothstep(-0.068, -0.045, t) * (1.0 - smoothstep(-0.005, 0.025, t));
        let ang = dir.dot(thumb).clamp(-1.0, 1.0).acos();
        let crease = -0.005 * gauss(t - 0.004, 0.008) * smoothstep(0.6, 0.95, -cs);
        let p = g
            + d2 * t
            + u * (cs.signum() * cs.abs().powf(e) * if cs >= 0.0 { sz.x } else { sz.y })
            + v * (sn.signum() * sn.abs().powf(e) * sz.z)
            + dir * (thumb_amp * gauss(ang, 0.42) + crease);
        let c = if (-0.112..=-0.092).contains(&t) {
            style.cuff
        } else {
            style.glove
        };
        let part = if t < -0.058 {
            Part::Cuff(side)
        } else {
            Part::Fist(side)
        };
        Pt(p, c, w, part, NO_VEST)
    };
    let mut rings: Vec<Vec<Pt>> = [
        -0.135, -0.131, -0.126, -0.117, -0.113, -0.109, -0.095, -0.091, -0.087, -0.078, -0.066,
        -0.052, -0.04, -0.027, -0.013, 0.0, 0.01, 0.02,
    ]
    .iter()
    .map(|&t| ring(GLOVE_COLS, |th| point(t, 1.0, th)))
    .collect();
    // The knuckle face: a superellipse dome (exponent 3) in front.
    let (front, depth) = (0.02, 0.046);
    for k in 1..7 {
        let phi = FRAC_PI_2 * k as f32 / 7.0;
        let (sn, cs) = phi.sin_cos();
        let (t, scale) = (front + depth * sn.powf(2.0 / 3.0), cs.powf(2.0 / 3.0));
        rings.push(ring(GLOVE_COLS, |th| point(t, scale, th)));
    }
    let mut pole = point(front + depth, 0.0, 0.0);
    pole.0 = g + d2 * (front + depth) + u * 0.004;
    b.grid(&rings, [None, Some(pole)], Dest::MainAndArm(0));
}

/// Rings along `a -> b` (`n` + 1 of them, `cols` points each), elliptic
/// with half-axes `radius(f)` (along `side`, and across) at the fraction
/// `f` along, each point made by `pt(position, f)`; poles close both ends.
#[allow(clippy::too_many_arguments)]
fn tube(
    b: &mut Builder,
    a: Vec3,
    e: Vec3,
    side: Vec3,
    n: usize,
    cols: usize,
    radius: impl Fn(f32) -> (f32, f32),
    pt: impl Fn(Vec3, f32) -> Pt,
) {
    let d = (e - a).normalize();
    let u = (side - d * side.dot(d)).normalize();
    let v = d.cross(u);
    let rings: Vec<Vec<Pt>> = (0..=n)
        .map(|i| {
            let f = i as f32 / n as f32;
            let (ru, rv) = radius(f);
            let c = a + (e - a) * f;
            ring(cols, |th| pt(c + u * th.cos() * ru + v * th.sin() * rv, f))
        })
        .collect();
    let (r0, r1) = (radius(0.0).0, radius(1.0).0);
    let poles = [pt(a - d * r0 * 0.5, 0.0), pt(e + d * r1 * 0.5, 1.0)];
    b.grid(&rings, poles.map(Some), Dest::Main);
}

/// Trunks over the pelvis (their waistband follows the trunk), thighs,
/// shanks with high boxing shoes, in the lower body's rest stance.
fn legs(b: &mut Builder, style: &BodyStyle) {
    let waist = waist_rest();
    let legs = rest_legs();
    // The trunks: an elliptic tube from inside the vest down to the crotch.
    let top = waist + Vec3::Y * 0.07;
    let bottom = waist - Vec3::Y * 0.2;
    tube(
        b,
        top,
        bottom,
        Vec3::X,
        8,
        TORSO_COLS,
        |f| {
            let hips = 0.138 + 0.04 * smoothstep(0.0, 0.5, f);
            (hips, 0.1 + 0.01 * smoothstep(0.2, 0.6, f))
        },
        |p, f| {
            let trunk = 0.8 * (1.0 - smoothstep(0.15, 0.45, f));
            let w = weights(&[(Bone::Torso, trunk), (Bone::Pelvis, 1.0 - trunk)]);
            Pt(p, style.trunks, w, Part::Leg, NO_VEST)
        },
    );
    for (side, leg) in legs.iter().enumerate() {
        let [hip, knee, ankle, toe, heel] =
            [leg.hip, leg.knee, leg.ankle, leg.toe, leg.heel].map(|v| v.as_vec3());
        let [thigh, shin, foot] = Bone::leg(side);
        let fwd = (toe - heel).normalize();
        // Thigh: trunks over its upper part, the knee blends into the shank.
        let along = (knee - hip).length();
        tube(
            b,
            hip + (hip - knee).normalize() * 0.02,
            knee,
            fwd,
            10,
            ARM_COLS,
            |f| {
                let r = 0.085 - 0.03 * smoothstep(0.1, 1.0, f);
                let shorts = if f < 0.42 { 0.008 } else { 0.0 };
                (r + shorts, r * 0.95 + shorts)
            },
            |p, f| {
                let k = smoothstep(0.8, 1.0, f);
                let pel = 0.5 * (1.0 - smoothstep(0.0, 0.2, f));
                let w = weights(&[(Bone::Pelvis, pel), (thigh, 1.0 - pel - k), (shin, k)]);
                let colour = if f * along < 0.42 * along {
                    style.trunks
                } else {
                    style.skin
                };
                Pt(p, colour, w, Part::Leg, NO_VEST)
            },
        );
        // Shank with the calf, into a high shoe above the ankle.
        tube(
            b,
            knee,
            ankle,
            fwd,
            10,
            ARM_COLS,
            |f| {
                let calf = 0.012 * gauss(f - 0.3, 0.2);
                let r = 0.054 - 0.02 * smoothstep(0.2, 0.9, f) + calf;
                let shoe = if f > 0.72 { 0.006 } else { 0.0 };
                (r + shoe, r * 1.05 + calf + shoe)
            },
            |p, f| {
                let k = 1.0 - smoothstep(0.0, 0.15, f);
                let w = weights(&[(thigh, k), (shin, 1.0 - k)]);
                let colour = if f > 0.72 { style.shoes } else { style.skin };
                Pt(p, colour, w, Part::Leg, NO_VEST)
            },
        );
        // The shoe: a rounded box along the foot on the sole.
        let up = Vec3::Y;
        let sole = 0.045;
        tube(
            b,
            heel - fwd * 0.01 + up * sole,
            toe + fwd * 0.055 + up * sole * 0.8,
            fwd.cross(up),
            8,
            ARM_COLS,
            |f| {
                let w = 0.036 + 0.012 * smoothstep(0.0, 0.7, f) - 0.015 * smoothstep(0.85, 1.0, f);
                let h = 0.044 - 0.012 * smoothstep(0.5, 1.0, f);
                (w, h)
            },
            |p, _| Pt(p, style.shoes, weights(&[(foot, 1.0)]), Part::Leg, NO_VEST),
        );
    }
}

impl BodyMesh {
    /// Build the body for `plan`'s rest pose, coloured by `style`.
    /// Deterministic.
    pub fn new(plan: &BodyPlan, style: &BodyStyle) -> BodyMesh {
        let mut b = Builder::default();
        torso(&mut b, plan, style);
        neck(&mut b, plan, style);
        for side in 0..2 {
            arm(&mut b, plan, style, side);
            glove(&mut b, plan, style, side);
        }
        legs(&mut b, style);
        let positions: Vec<Vec3> = b.verts.iter().map(|v| Vec3::from_array(v.pos)).collect();
        let normals = compute_normals(&positions, b.all.as_chunks::<3>().0);
        for (v, n) in b.verts.iter_mut().zip(normals) {
            v.normal = n.to_array();
        }
        BodyMesh {
            vertices: b.verts,
            whole: b.main,
            arms: b.arm,
            parts: b.parts,
            skin: [style.skin[0], style.skin[1], style.skin[2]],
        }
    }
}
