//! A procedural, linear-blend-skinned upper body (torso in a sleeveless
//! vest, neck, arms, boxing gloves) drawn for the VH and for your avatar in
//! place of the collision shapes. The head is the face mesh, drawn apart.
//!
//! Construction: every part is a grid of rings (a tube) in the rest pose of
//! [`BodyPlan`] (arms hanging, forearms forward), closed by poles. The torso's
//! rings are superellipses (flatter at the back, pectorals added) that close
//! over the shoulders into the neck; the neck is a tube leaning forward whose
//! top sits inside the head; each arm starts with a ball around the shoulder
//! pivot (the deltoid, sunk into the torso, so the shoulder stays closed
//! whatever the arm does), runs down the upper arm, bends round the elbow
//! about an axis on the crook's side and ends inside the glove; the glove is
//! a padded superellipse fist with a thumb along its inner side and a cuff.
//! Parts overlap instead of sharing vertices. Weights blend torso and head
//! along the neck; upper arm and forearm across the elbow (on the crook's
//! side by the length along the crook, on the outer side across the plane
//! bisecting the bend, so that neither side folds, tears or sinks from
//! straight to fully bent); torso and upper arm around the shoulder. Gloves
//! are rigid on their forearm.
//!
//! A [`Pose`] holds each bone's current world transform times its rest world
//! transform's inverse: all identity is the rest pose.

use std::f32::consts::{FRAC_PI_2, FRAC_PI_4, TAU};

use crate::face::mesh::compute_normals;
use crate::util::math::{gauss, smoothstep};
use glam::{Mat4, Quat, Vec3};

use super::geometry::Vertex;
use crate::physics::body::{BodyPlan, Shape, arm_ik, seg};

/// A skinning bone; each glove rides its forearm.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[repr(u8)]
pub enum Bone {
    /// The torso (root).
    Torso,
    /// The head (the neck's upper part follows it).
    Head,
    /// Left (+X) upper arm.
    UpperArmL,
    /// Left forearm and glove.
    ForearmL,
    /// Right upper arm.
    UpperArmR,
    /// Right forearm and glove.
    ForearmR,
}

impl Bone {
    /// Number of bones.
    pub const COUNT: usize = 6;
    /// Every bone, in index order.
    pub const ALL: [Bone; Bone::COUNT] = {
        use Bone::*;
        [Torso, Head, UpperArmL, ForearmL, UpperArmR, ForearmR]
    };

    /// Upper arm of `side` (0 = left).
    pub fn upper_arm(side: usize) -> Bone {
        [Bone::UpperArmL, Bone::UpperArmR][side]
    }

    /// Forearm (and glove) of `side` (0 = left).
    pub fn forearm(side: usize) -> Bone {
        [Bone::ForearmL, Bone::ForearmR][side]
    }

    /// The physics segment ([`seg`]) that drives the bone.
    pub fn segment(self) -> usize {
        use seg::*;
        [TORSO, HEAD, UPPER_ARM_L, FOREARM_L, UPPER_ARM_R, FOREARM_R][self as usize]
    }
}

/// Each bone's world transform relative to its rest (current * rest^-1),
/// indexed by `Bone as usize`.
pub type Pose = [Mat4; Bone::COUNT];

/// The rest pose.
pub const REST_POSE: Pose = [Mat4::IDENTITY; Bone::COUNT];

/// Colours of the body's regions, linear RGBA.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BodyStyle {
    /// Neck, shoulders, arms.
    pub skin: [f32; 4],
    /// The sleeveless vest on the torso.
    pub shirt: [f32; 4],
    /// Gloves.
    pub glove: [f32; 4],
    /// The stripe round each glove's cuff.
    pub cuff: [f32; 4],
}

impl BodyStyle {
    /// The VH: the face's skin, a navy vest, red gloves, white cuff stripes.
    pub const VH: BodyStyle = BodyStyle {
        skin: SKIN,
        shirt: [0.16, 0.22, 0.40, 1.0],
        glove: [0.70, 0.06, 0.05, 1.0],
        cuff: CUFF,
    };
    /// You: the same skin, a grey vest, blue gloves.
    pub const YOU: BodyStyle = BodyStyle {
        skin: SKIN,
        shirt: [0.30, 0.31, 0.33, 1.0],
        glove: [0.08, 0.22, 0.75, 1.0],
        cuff: CUFF,
    };
}

/// Skin, as the face's ([`crate::face::appearance::FaceStyle`]).
pub const SKIN: [f32; 4] = {
    let s = crate::face::appearance::FaceStyle::DEFAULT.skin;
    [s[0], s[1], s[2], 1.0]
};
const CUFF: [f32; 4] = [0.92, 0.92, 0.88, 1.0];

/// A rest-pose vertex with its skinning weights.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SkinVertex {
    /// Rest position, world metres.
    pub pos: [f32; 3],
    /// Rest unit normal, world frame.
    pub normal: [f32; 3],
    /// Linear RGBA colour.
    pub color: [f32; 4],
    /// A painted border: signed distance inside it (in its soft
    /// half-widths) and the colour there ([`Vertex::paint`]).
    pub paint: [f32; 4],
    /// Bones (`Bone as u8`) of the weights; unused slots have weight 0.
    pub bones: [u8; 4],
    /// Weights, non-negative, summing to 1.
    pub weights: [f32; 4],
}

/// Which part a vertex belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Part {
    Torso,
    Neck,
    Arm(usize),
    Cuff(usize),
    Fist(usize),
}

/// The skinned upper-body mesh.
#[derive(Clone, Debug, PartialEq)]
pub struct BodyMesh {
    vertices: Vec<SkinVertex>,
    /// Triangle list (counter-clockwise seen from outside) of the whole body.
    pub indices: Vec<u32>,
    arm_indices: Vec<u32>,
    parts: Vec<Part>,
}

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

/// A vertex under construction: position, colour, weights, part, painted
/// border ([`Vertex::paint`]).
#[derive(Clone, Copy)]
struct Pt(Vec3, [f32; 4], Weights, Part, [f32; 4]);

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
    main: Vec<u32>,
    arm: Vec<u32>,
    all: Vec<u32>,
}

impl Builder {
    fn push(&mut self, &Pt(p, color, (bones, weights), part, paint): &Pt) -> u32 {
        let (pos, normal) = (p.to_array(), [0.0; 3]);
        let v = SkinVertex {
            pos,
            normal,
            color,
            paint,
            bones,
            weights,
        };
        self.verts.push(v);
        self.parts.push(part);
        self.verts.len() as u32 - 1
    }

    fn tri(&mut self, t: [u32; 3], band: usize, dest: Dest) {
        self.all.extend(t);
        match dest {
            Dest::Main => self.main.extend(t),
            Dest::MainAndArm(first) => {
                self.main.extend(t);
                if band >= first {
                    self.arm.extend(t);
                }
            }
            Dest::ArmOnly => self.arm.extend(t),
        }
    }

    /// Quads between consecutive rings (each ring's points wind
    /// counter-clockwise about the direction from one ring to the next, seen
    /// from that direction's tip), fans to the optional start and end poles.
    fn grid(&mut self, rings: &[Vec<Pt>], poles: [Option<Pt>; 2], dest: Dest) {
        let cols = rings[0].len();
        let base = self.verts.len() as u32;
        for pt in rings.iter().flatten() {
            self.push(pt);
        }
        let at = |k: usize, j: usize| base + (k * cols + j % cols) as u32;
        for k in 0..rings.len() - 1 {
            for j in 0..cols {
                let (a, b, c, d) = (at(k, j), at(k, j + 1), at(k + 1, j), at(k + 1, j + 1));
                self.tri([a, b, c], k, dest);
                self.tri([b, d, c], k, dest);
            }
        }
        if let Some(p) = poles[0] {
            let i = self.push(&p);
            for j in 0..cols {
                self.tri([i, at(0, j + 1), at(0, j)], 0, dest);
            }
        }
        if let Some(p) = poles[1] {
            let (i, l) = (self.push(&p), rings.len() - 1);
            for j in 0..cols {
                self.tri([at(l, j), at(l, j + 1), i], l, dest);
            }
        }
    }
}

fn ring(cols: usize, f: impl Fn(f32) -> Pt) -> Vec<Pt> {
    (0..cols).map(|j| f(TAU * j as f32 / cols as f32)).collect()
}

/// Cubic Hermite interpolation (finite-difference tangents) of column
/// `col` of `rows` against column 0 (ascending); constant outside.
fn table<const N: usize>(rows: &[[f32; N]], col: usize, x: f32) -> f32 {
    let n = rows.len();
    if x <= rows[0][0] {
        return rows[0][col];
    }
    let slope = |i: usize| {
        let (a, b) = (rows[i.saturating_sub(1)], rows[(i + 1).min(n - 1)]);
        (b[col] - a[col]) / (b[0] - a[0])
    };
    for i in 0..n - 1 {
        let (x0, v0, x1, v1) = (rows[i][0], rows[i][col], rows[i + 1][0], rows[i + 1][col]);
        if x <= x1 {
            let (h, t) = (x1 - x0, (x - x0) / (x1 - x0));
            let (t2, t3) = (t * t, t * t * t);
            return (2.0 * t3 - 3.0 * t2 + 1.0) * v0
                + (t3 - 2.0 * t2 + t) * h * slope(i)
                + (-2.0 * t3 + 3.0 * t2) * v1
                + (t3 - t2) * h * slope(i + 1);
        }
    }
    rows[n - 1][col]
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

/// The vest's neckline and armholes at a torso point (design frame): the
/// signed distance inside them (bare skin), in units of the hem's soft
/// half-width, as the border of a [`Vertex::paint`] (the renderer
/// thresholds it per pixel, so the hem stays sharp on the coarse torso).
fn vest(d: Vec3) -> f32 {
    let arm = ((d.x.abs() - 0.215) / 0.085).powi(2) + ((d.y - 1.47) / 0.15).powi(2);
    let depth = 0.035 + 0.05 * smoothstep(-0.02, 0.04, d.z);
    let neck = (d.x / 0.09).powi(2) + ((d.y - 1.535) / depth).powi(2);
    // Elliptic radius 1 on the hem; about 8.5 cm per unit of it there.
    (1.0 - arm.min(neck).sqrt()) * 0.085 / HEM_SOFT
}

/// Half-width of the vest hem's soft edge, m.
const HEM_SOFT: f32 = 0.0015;

/// A vertex's painted border: none.
const NO_BORDER: [f32; 4] = [-1e3, 0.0, 0.0, 0.0];

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
    let t = &plan.segments[seg::TORSO];
    let half = match t.shape {
        Shape::Cuboid { half } => half,
        _ => Vec3::new(0.16, 0.25, 0.10),
    };
    let k = half / Vec3::new(0.16, 0.25, 0.10);
    let origin = t.centre - Vec3::Y * half.y;
    let shoulders = [0, 1].map(|s| plan.segments[Bone::upper_arm(s).segment()].pivot);
    let point = |d: Vec3| {
        let p = origin + (d - Vec3::Y) * k;
        let arm = shoulders.map(|s| 0.5 * (1.0 - smoothstep(0.03, 0.085, p.distance(s))));
        let w = [(Bone::UpperArmL, arm[0]), (Bone::UpperArmR, arm[1])];
        let w = weights(&[(Bone::Torso, 1.0 - arm[0] - arm[1]), w[0], w[1]]);
        let skin = [vest(d), style.skin[0], style.skin[1], style.skin[2]];
        Pt(p, style.shirt, w, Part::Torso, skin)
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
    let pivot = plan.segments[seg::HEAD].pivot;
    let point = |dy: f32, th: f32| {
        let (s, c) = th.sin_cos();
        let (a, d) = (table(&NECK, 1, dy), table(&NECK, 2, dy));
        let centre = pivot + Vec3::new(0.0, dy, -0.012 + 0.11 * (dy + 0.06));
        let head = smoothstep(-0.03, 0.1, dy);
        let w = weights(&[(Bone::Torso, 1.0 - head), (Bone::Head, head)]);
        let p = centre + Vec3::new(a * s, 0.0, d * c);
        Pt(p, style.skin, w, Part::Neck, NO_BORDER)
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

/// Rest landmarks of one arm: shoulder, elbow, glove centre, unit
/// directions of upper arm and forearm.
fn arm_frame(plan: &BodyPlan, side: usize) -> (Vec3, Vec3, Vec3, Vec3, Vec3) {
    let s = plan.segments[Bone::upper_arm(side).segment()].pivot;
    let e = plan.segments[Bone::forearm(side).segment()].pivot;
    let g = plan.segments[seg::GLOVE_L + 3 * side].centre;
    (s, e, g, (e - s).normalize(), (g - e).normalize())
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
        Pt(p, style.skin, w, Part::Arm(side), NO_BORDER)
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
    let torso_x = plan.segments[seg::TORSO].centre.x;
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
        Pt(p, c, w, part, NO_BORDER)
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
        let positions: Vec<Vec3> = b.verts.iter().map(|v| Vec3::from_array(v.pos)).collect();
        let normals = compute_normals(&positions, b.all.as_chunks::<3>().0);
        for (v, n) in b.verts.iter_mut().zip(normals) {
            v.normal = n.to_array();
        }
        BodyMesh {
            vertices: b.verts,
            indices: b.main,
            arm_indices: b.arm,
            parts: b.parts,
        }
    }

    /// Rest vertices with their weights.
    pub fn vertices(&self) -> &[SkinVertex] {
        &self.vertices
    }

    /// Triangles of the forearms, gloves and the lower half of the upper
    /// arms, with a cap closing each upper arm's cut, for the first-person
    /// view (index the same skinned vertices as [`BodyMesh::indices`]).
    pub fn arm_indices(&self) -> &[u32] {
        &self.arm_indices
    }

    /// Linear blend skinning: `out` is cleared and filled with one posed
    /// vertex per rest vertex, world frame (allocates only while `out`
    /// grows).
    pub fn skin(&self, pose: &Pose, out: &mut Vec<Vertex>) {
        out.clear();
        out.extend(self.vertices.iter().map(|v| {
            let (p, n) = (Vec3::from_array(v.pos), Vec3::from_array(v.normal));
            let (mut sp, mut sn) = (Vec3::ZERO, Vec3::ZERO);
            for (&b, &w) in v.bones.iter().zip(&v.weights) {
                if w > 0.0 {
                    let m = &pose[b as usize];
                    sp += w * m.transform_point3(p);
                    sn += w * m.transform_vector3(n);
                }
            }
            Vertex {
                paint: v.paint,
                ..Vertex::coloured(sp, sn.normalize_or(n), v.color)
            }
        }));
    }
}

/// The VH's pose from its physics segments: `world_poses(segment)` gives a
/// segment's current world position (its centre, where [`BodyPlan`] puts it
/// at rest) and rotation (identity at rest).
pub fn vh_pose(world_poses: impl Fn(usize) -> (Vec3, Quat), plan: &BodyPlan) -> Pose {
    Bone::ALL.map(|b| {
        let (p, q) = world_poses(b.segment());
        Mat4::from_rotation_translation(q, p)
            * Mat4::from_translation(-plan.segments[b.segment()].centre)
    })
}

/// Upper arm and forearm transforms (rest frame) of `side` for the joint
/// rotations of [`arm_ik`]: shoulder relative to the torso, elbow relative
/// to the upper arm.
fn arm_mats(plan: &BodyPlan, side: usize, shoulder: Quat, elbow: Quat) -> [Mat4; 2] {
    let about = |q: Quat, p: Vec3| {
        Mat4::from_translation(p) * Mat4::from_quat(q) * Mat4::from_translation(-p)
    };
    let (s, e, ..) = arm_frame(plan, side);
    let upper = about(shoulder, s);
    [upper, upper * about(elbow, e)]
}

/// Your avatar's pose: the body turned to face the VH (looking along -Z, its
/// left on world -X), hung upright from its head centre `head` (the head
/// bone's rest centre is the plan's head centre), arms solved with
/// [`arm_ik`] so the glove centres reach `gloves` (`gloves[0]` your left).
pub fn avatar_pose(plan: &BodyPlan, head: Vec3, gloves: [Vec3; 2]) -> Pose {
    let root = Mat4::from_translation(head)
        * Mat4::from_rotation_y(std::f32::consts::PI)
        * Mat4::from_translation(-plan.segments[seg::HEAD].centre);
    let inv = root.inverse();
    let mut pose = [root; Bone::COUNT];
    for side in 0..2 {
        let target = inv.transform_point3(gloves[side]);
        let (qs, qe) = arm_ik(side, target.as_dvec3());
        let [upper, fore] = arm_mats(plan, side, qs, qe);
        pose[Bone::upper_arm(side) as usize] = root * upper;
        pose[Bone::forearm(side) as usize] = root * fore;
    }
    pose
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mesh() -> (BodyPlan, BodyMesh) {
        let plan = BodyPlan::default();
        let m = BodyMesh::new(&plan, &BodyStyle::VH);
        (plan, m)
    }

    fn posed(m: &BodyMesh, pose: &Pose) -> Vec<Vec3> {
        let mut out = Vec::new();
        m.skin(pose, &mut out);
        out.iter().map(|v| Vec3::from_array(v.pos)).collect()
    }

    fn tris<'a>(
        m: &'a BodyMesh,
        p: &'a [Vec3],
    ) -> impl Iterator<Item = ([u32; 3], [Vec3; 3])> + 'a {
        m.indices
            .as_chunks::<3>()
            .0
            .iter()
            .map(|t| (*t, t.map(|i| p[i as usize])))
    }

    /// Area-weighted centroid of the fist's surface of `side`.
    fn fist(m: &BodyMesh, p: &[Vec3], side: usize) -> Vec3 {
        let (mut sum, mut area) = (Vec3::ZERO, 0.0);
        for (t, [a, b, c]) in tris(m, p) {
            if t.iter().all(|&i| m.parts[i as usize] == Part::Fist(side)) {
                let s = (b - a).cross(c - a).length();
                (sum, area) = (sum + s * (a + b + c) / 3.0, area + s);
            }
        }
        sum / area
    }

    /// The VH's arms at the given shoulder and elbow rotations, or reaching
    /// for glove targets.
    fn arms(plan: &BodyPlan, rot: impl Fn(usize) -> (Quat, Quat)) -> Pose {
        let mut pose = REST_POSE;
        for side in 0..2 {
            let (qs, qe) = rot(side);
            let [u, f] = arm_mats(plan, side, qs, qe);
            (
                pose[Bone::upper_arm(side) as usize],
                pose[Bone::forearm(side) as usize],
            ) = (u, f);
        }
        pose
    }

    fn reach(plan: &BodyPlan, targets: [Vec3; 2]) -> Pose {
        arms(plan, |side| arm_ik(side, targets[side].as_dvec3()))
    }

    /// Largest edge stretch, and the number of triangles whose skinned
    /// normal opposes their rest normal carried by their vertices' bones.
    fn distortion(m: &BodyMesh, pose: &Pose, keep: impl Fn(Part) -> bool) -> (f32, usize) {
        let (p0, p1) = (posed(m, &REST_POSE), posed(m, pose));
        let (mut stretch, mut flips) = (0.0f32, 0);
        for ((t, [a, b, c]), (_, [a1, b1, c1])) in tris(m, &p0).zip(tris(m, &p1)) {
            if !t.iter().all(|&i| keep(m.parts[i as usize])) {
                continue;
            }
            for (e0, e1) in [(b - a, b1 - a1), (c - b, c1 - b1), (a - c, a1 - c1)] {
                stretch = stretch.max(e1.length() / e0.length());
            }
            let n0 = (b - a).cross(c - a);
            let carried: Vec3 = (t.iter())
                .flat_map(|&i| {
                    m.vertices[i as usize]
                        .bones
                        .into_iter()
                        .zip(m.vertices[i as usize].weights)
                })
                .map(|(b, w)| w * pose[b as usize].transform_vector3(n0))
                .sum();
            flips += usize::from((b1 - a1).cross(c1 - a1).dot(carried) <= 0.0);
        }
        (stretch, flips)
    }

    #[test]
    fn weights_are_normalised() {
        let (_, m) = mesh();
        for v in &m.vertices {
            assert!(v.weights.iter().all(|&w| w >= 0.0), "{v:?}");
            assert!((v.weights.iter().sum::<f32>() - 1.0).abs() < 1e-5, "{v:?}");
            assert!(v.bones.iter().all(|&b| (b as usize) < Bone::COUNT));
        }
    }

    #[test]
    fn mesh_is_well_formed() {
        let (plan, m) = mesh();
        let n = m.vertices.len();
        assert!((3000..=8000).contains(&n), "{n} vertices");
        assert_eq!(m, BodyMesh::new(&plan, &BodyStyle::VH), "deterministic");
        let p = posed(&m, &REST_POSE);
        for list in [&m.indices, &m.arm_indices] {
            assert!(!list.is_empty() && list.len() % 3 == 0);
            assert!(list.iter().all(|&i| (i as usize) < n));
            for t in list.as_chunks::<3>().0 {
                let [a, b, c] = t.map(|i| p[i as usize]);
                assert!(
                    (b - a).cross(c - a).length() > 2e-8,
                    "degenerate {t:?}: {a} {b} {c}"
                );
            }
        }
        assert!(
            m.vertices
                .iter()
                .all(|v| (Vec3::from_array(v.normal).length() - 1.0).abs() < 1e-4)
        );
        // Outward winding: a positive enclosed volume, about the torso's.
        let o = Vec3::new(0.0, 1.25, 0.0);
        let vol: f32 = tris(&m, &p)
            .map(|(_, [a, b, c])| (a - o).dot((b - o).cross(c - o)) / 6.0)
            .sum();
        assert!(vol > 0.015, "volume {vol}");
    }

    #[test]
    fn rest_pose_reproduces_rest_vertices() {
        let (_, m) = mesh();
        let mut out = Vec::new();
        m.skin(&REST_POSE, &mut out);
        assert_eq!(out.len(), m.vertices.len());
        for (s, v) in out.iter().zip(&m.vertices) {
            assert!(Vec3::from_array(s.pos).distance(Vec3::from_array(v.pos)) < 1e-6);
            assert!(Vec3::from_array(s.normal).distance(Vec3::from_array(v.normal)) < 1e-5);
            assert_eq!(s.color, v.color);
        }
    }

    #[test]
    fn glove_follows_the_forearm() {
        let (plan, m) = mesh();
        let rest_fist = [0, 1].map(|s| fist(&m, &posed(&m, &REST_POSE), s));
        for targets in [
            [Vec3::new(0.11, 1.56, 0.27), Vec3::new(-0.11, 1.56, 0.27)],
            [Vec3::new(0.0, 1.55, 0.5), Vec3::new(-0.3, 1.3, 0.3)],
        ] {
            // Through vh_pose, from the segments' world poses, torso lunging.
            let lunge = Mat4::from_translation(Vec3::new(0.02, 0.0, 0.1));
            let pose = reach(&plan, targets).map(|m| lunge * m);
            let world = |s: usize| {
                let m = pose[Bone::ALL.iter().position(|b| b.segment() == s).unwrap()];
                (
                    m.transform_point3(plan.segments[s].centre),
                    m.to_scale_rotation_translation().1,
                )
            };
            let from_physics = vh_pose(world, &plan);
            for (a, b) in from_physics.iter().zip(&pose) {
                assert!(a.abs_diff_eq(*b, 1e-5), "{a} vs {b}");
            }
            let p = posed(&m, &from_physics);
            for side in 0..2 {
                let target = lunge.transform_point3(targets[side]);
                let fore = from_physics[Bone::forearm(side) as usize];
                let got = fist(&m, &p, side);
                assert!(got.distance(fore.transform_point3(rest_fist[side])) < 1e-4);
                assert!(got.distance(target) < 0.01, "{got} vs {target}");
            }
        }
    }

    #[test]
    fn arms_stay_continuous_when_bent() {
        let (plan, m) = mesh();
        let flex = |deg: f32| Quat::from_rotation_x(-deg.to_radians());
        let not_neck = |p: Part| p != Part::Neck;
        // Shoulder flexion, and the elbow's from its rest bend of 90 deg:
        // -90 a straight arm, +30 a 120 deg flexion.
        for (shoulder, elbow) in [(90.0, 30.0), (90.0, -90.0), (0.0, 45.0), (45.0, -60.0)] {
            let pose = arms(&plan, |_| (flex(shoulder), flex(elbow)));
            let (stretch, flips) = distortion(&m, &pose, not_neck);
            assert!(
                stretch < 3.0 && flips == 0,
                "{shoulder}/{elbow}: {stretch} {flips}"
            );
        }
        for targets in [
            [Vec3::new(0.11, 1.56, 0.27), Vec3::new(-0.11, 1.56, 0.27)],
            [Vec3::new(0.05, 1.55, 0.55), Vec3::new(-0.2, 1.6, 0.45)],
        ] {
            let (stretch, flips) = distortion(&m, &reach(&plan, targets), not_neck);
            assert!(
                stretch < 3.0 && flips == 0,
                "{targets:?}: {stretch} {flips}"
            );
        }
        // Straightened, the elbow keeps most of its girth (no collapse).
        let p = posed(&m, &arms(&plan, |_| (Quat::IDENTITY, flex(-90.0))));
        let elbow = plan.segments[seg::FOREARM_L].pivot;
        for (i, q) in p.iter().enumerate() {
            if m.parts[i] == Part::Arm(0) && (q.y - elbow.y).abs() < 0.08 {
                let r = (*q - elbow).with_y(0.0).length();
                assert!(r > 0.03, "girth {r} at {}", q.y - elbow.y);
            }
        }
    }

    #[test]
    fn neck_follows_the_head() {
        let (plan, m) = mesh();
        let (pivot, head_c) = (
            plan.segments[seg::HEAD].pivot,
            plan.segments[seg::HEAD].centre,
        );
        for (yaw, pitch) in [
            (70.0f32, 0.0f32),
            (-70.0, 0.0),
            (0.0, -60.0),
            (0.0, 50.0),
            (50.0, -40.0),
        ] {
            let q = Quat::from_rotation_y(yaw.to_radians())
                * Quat::from_rotation_x(-pitch.to_radians());
            let mut pose = REST_POSE;
            pose[Bone::Head as usize] =
                Mat4::from_translation(pivot) * Mat4::from_quat(q) * Mat4::from_translation(-pivot);
            let (stretch, flips) = distortion(&m, &pose, |p| p == Part::Neck);
            assert!(
                stretch < 3.0 && flips == 0,
                "{yaw}/{pitch}: {stretch} {flips}"
            );
            // The neck's top stays inside the head.
            let head = pose[Bone::Head as usize].transform_point3(head_c);
            for (i, p) in posed(&m, &pose).iter().enumerate() {
                if m.parts[i] == Part::Neck && m.vertices[i].pos[1] > pivot.y + 0.09 {
                    assert!(p.distance(head) < 0.1, "{yaw}/{pitch}: {p}");
                }
            }
        }
    }

    #[test]
    fn avatar_gloves_reach_the_targets() {
        let (plan, m) = mesh();
        let head = Vec3::new(0.03, 1.70, 0.92);
        let rest = posed(&m, &REST_POSE);
        let more = [Vec3::new(-0.05, 1.6, 0.45), Vec3::new(0.2, 1.45, 0.7)];
        for gloves in [plan.opponent_gloves, more] {
            let pose = avatar_pose(&plan, head, gloves);
            let h = pose[Bone::Head as usize].transform_point3(plan.segments[seg::HEAD].centre);
            assert!(h.distance(head) < 1e-5);
            let p = posed(&m, &pose);
            for side in 0..2 {
                let (fore, got) = (pose[Bone::forearm(side) as usize], fist(&m, &p, side));
                assert!(got.distance(gloves[side]) < 0.01, "{got} vs {gloves:?}");
                assert!(got.distance(fore.transform_point3(fist(&m, &rest, side))) < 1e-4);
            }
            // Facing the VH: the avatar's left arm is on world -X.
            let mean_x = |side| {
                let arm: Vec<f32> = (0..p.len())
                    .filter(|&i| m.parts[i] == Part::Arm(side))
                    .map(|i| p[i].x)
                    .collect();
                arm.iter().sum::<f32>() / arm.len() as f32
            };
            assert!(mean_x(0) < mean_x(1));
        }
    }
}
