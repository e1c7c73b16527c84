//! Muscle placement on the generated head and the precomputed sparse
//! displacement fields (face.md 3-5).
//!
//! (F1) and (F6) are linear in k, so each muscle channel stores its
//! displacement at k = 1 for the vertices it moves; a linear muscle's is
//! first spread through the skin (S1, docs/model/face.md), which keeps it
//! linear in k. The jaw (F7) is a
//! rotation: per vertex we store `alpha / theta` and the rest offset from
//! the jaw axis, and rotate at frame time with 7th-order sin / 6th-order cos
//! polynomials (error < a^7/5040: below 1e-7 rad-equivalent for a < 0.35 rad
//! = 20 deg, i.e. exact for practical purposes, without a sin/cos per vertex).
//!
//! Eyelids: the upper palpebral part uses lid-specific geometry
//! ([`LidSphincter`]): (F5)-(F6) along each vertical line of the fissure,
//! centred on the lower margin, sized so the blink contraction (AU45, 2.9)
//! lays the whole upper margin onto the lower one, corner to corner. The
//! lower palpebral part is a Waters half ellipse (F5)-(F6) acting below the
//! eye centre, with the eye corners at rho >= 2 (corners fixed). After
//! summing, lid-zone vertices are pushed out of a sphere of `LID_CLEARANCE`
//! around each eyeball centre, so the lids slide over the eyeball rather
//! than through it (a documented non-linear post-step). Both lids follow
//! the eye's pitch through their sphincter channel ([`Rig::lid_follow_k`]).

use super::emotion::{Activation, MuscleId, N_CHANNELS, Side, channels};
use super::mesh::{HeadMesh, Landmarks, dims, mirror};
use super::muscle::{
    Jaw, LidSphincter, LinearMuscle, Sphincter, SphincterPart, jaw_rotation, lid_margin,
};
use super::params::FaceParams;
use super::tables::MuscleKind;
use crate::util::math::smoothstep;
use glam::Vec3;

fn eye_centre(l: &Landmarks, side: Side) -> Vec3 {
    if side == Side::Right {
        mirror(l.eye_centre)
    } else {
        l.eye_centre
    }
}

/// Radius around each eyeball centre that lid vertices are kept outside of.
pub const LID_CLEARANCE: f32 = dims::EYEBALL_R + 0.0006;

/// Muscle geometry of one channel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MuscleGeometry {
    /// Waters linear muscle.
    Linear(LinearMuscle),
    /// Waters sphincter, with an optional rest-height mask (palpebral parts:
    /// act only above / below the eye centre).
    Sphincter(Sphincter),
    /// Upper palpebral part on lid-specific geometry.
    Lid(LidSphincter),
}

impl MuscleGeometry {
    /// Displacement of rest point `p` at contraction `k` (F1 / F6).
    pub fn displacement(&self, p: Vec3, k: f32) -> Vec3 {
        match self {
            MuscleGeometry::Linear(m) => m.displacement(p, k),
            MuscleGeometry::Sphincter(s) => s.displacement(p, k),
            MuscleGeometry::Lid(s) => s.displacement(p, k),
        }
    }
}

/// Displacement per unit contraction of the vertices a channel moves.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct SparseField {
    /// Vertex indices.
    pub index: Vec<u32>,
    /// Displacement at k = 1 of each listed vertex.
    pub delta: Vec<Vec3>,
}

/// Precomputed jaw data (F7).
#[derive(Clone, Debug, PartialEq, Default)]
pub struct JawField {
    /// Vertex indices below the mouth-ear line with alpha > 0.
    pub index: Vec<u32>,
    /// Rest position minus the pivot (the axis is +X).
    pub offset: Vec<Vec3>,
    /// alpha / theta.
    pub fraction: Vec<f32>,
}

/// Placed muscles and their fields.
#[derive(Clone, Debug, PartialEq)]
pub struct Rig {
    /// Geometry per channel (index: [`channels`]).
    pub muscles: Vec<(MuscleId, MuscleGeometry)>,
    /// Field per channel.
    pub fields: Vec<SparseField>,
    /// Jaw law parameters.
    pub jaw: Jaw,
    /// Jaw per-vertex data.
    pub jaw_field: JawField,
    /// Eyeball centres (0 left, 1 right).
    pub eye_centres: [Vec3; 2],
    /// Vertical displacement of the mid upper and lower lid margins per
    /// unit contraction of their palpebral channel, per eye: `[upper, lower]`.
    pub lid_y_per_k: [[f32; 2]; 2],
    /// The lower lip's region, held to the upper lip by orbicularis oris (O1).
    pub lip_seal: LipSeal,
}

/// Precomputed data of the lip seal (O1): the vertices of the lower lip and
/// the skin below it, each with the rim column whose opening it closes and
/// how much of it, and the law's constants.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct LipSeal {
    /// Orbicularis oris channel.
    pub channel: usize,
    /// Contraction that presses the lips fully together (`None`: no seal).
    pub seal_k: Option<f32>,
    /// Widest opening the pressed lips close, m.
    pub max_gap: f32,
    /// Rim columns: (upper lip rim vertex, lower lip rim vertex).
    pub columns: Vec<(u32, u32)>,
    /// Region vertices.
    pub index: Vec<u32>,
    /// Column of each region vertex.
    pub column: Vec<u32>,
    /// Weight of each region vertex: 1 on the lower lip's margin, 0 at
    /// [`SEAL_REACH`] below it and at the mouth's corners.
    pub weight: Vec<f32>,
}

/// How far below the lower lip's margin the seal's pull reaches, m: the
/// lower lip's height down to the labiomental fold (about 15 mm in adults;
/// Farkas 1994, Anthropometry of the Head and Face, 2nd ed.).
const SEAL_REACH: f32 = 0.015;

/// Opening over which the seal takes hold, m: it closes a column whose
/// upper margin has risen from the lower by this much or more, none whose
/// lips press into each other (a smooth onset, so neighbouring columns
/// move alike).
const SEAL_SOFT: f32 = 0.001;

impl LipSeal {
    fn build(mesh: &HeadMesh, params: &FaceParams) -> LipSeal {
        let (upper, lower) = (&mesh.rims.upper_lip, &mesh.rims.lower_lip);
        let pos = |i: u32| mesh.positions[i as usize];
        // Each lower rim vertex paired with the upper one nearest across.
        let columns: Vec<(u32, u32)> = lower
            .iter()
            .filter_map(|&l| {
                let u = upper.iter().copied().min_by(|&a, &b| {
                    let d = |i: u32| (pos(i).x - pos(l).x).abs();
                    d(a).total_cmp(&d(b))
                })?;
                Some((u, l))
            })
            .collect();
        let mut seal = LipSeal {
            channel: MuscleId {
                kind: MuscleKind::OrbicularisOris,
                side: Side::Centre,
            }
            .index()
            .expect("orbicularis oris channel"),
            seal_k: params.lips.seal_k.map(|k| k as f32),
            max_gap: params.lips.seal_max_gap_m as f32,
            columns,
            ..LipSeal::default()
        };
        if seal.columns.is_empty() {
            return seal;
        }
        let half_w = mesh.landmarks.mouth_corner.x;
        let front = mesh.landmarks.mouth_corner.z - 0.01;
        for (i, &p) in mesh.positions.iter().enumerate() {
            if p.x.abs() > half_w || p.z < front {
                continue;
            }
            let (c, rim) = seal
                .columns
                .iter()
                .enumerate()
                .map(|(c, &(_, l))| (c, pos(l)))
                .min_by(|a, b| (a.1.x - p.x).abs().total_cmp(&(b.1.x - p.x).abs()))
                .expect("columns");
            let below = rim.y - p.y;
            if !(0.0..SEAL_REACH).contains(&below) {
                continue;
            }
            seal.index.push(i as u32);
            seal.column.push(c as u32);
            // Tapered to nothing at the mouth's corners, beyond which the
            // skin is not moved: a coarse mesh would fold there.
            let across = 1.0 - smoothstep(0.6 * half_w, half_w, p.x.abs());
            seal.weight
                .push((1.0 - smoothstep(0.0, SEAL_REACH, below)) * across);
        }
        // The rims' vertices last (see `apply`).
        let on_rim = |i: u32| seal.columns.iter().any(|&(u, l)| u == i || l == i);
        let mut order: Vec<usize> = (0..seal.index.len()).collect();
        order.sort_by_key(|&n| on_rim(seal.index[n]));
        seal.index = order.iter().map(|&n| seal.index[n]).collect();
        seal.column = order.iter().map(|&n| seal.column[n]).collect();
        seal.weight = order.iter().map(|&n| seal.weight[n]).collect();
        seal
    }

    /// Move the lower lip's region so its margin closes the opening the
    /// lips have gained over their rest, in each column, by the seal's
    /// share of it, at most `max_gap` (O1).
    fn apply(&self, mesh: &HeadMesh, k: f32, out: &mut [Vec3]) {
        let Some(seal_k) = self.seal_k else {
            return;
        };
        let s = (k / seal_k).clamp(0.0, 1.0); // (O1)
        if s == 0.0 {
            return;
        }
        // The rims' own vertices come last in the region, so every
        // column's opening is read before its margins move.
        for ((&i, &c), &w) in self.index.iter().zip(&self.column).zip(&self.weight) {
            let (u, l) = self.columns[c as usize];
            let moved = |v: u32| out[v as usize] - mesh.positions[v as usize];
            let gap = moved(u) - moved(l);
            // Only an opening is closed (the upper margin risen from the
            // lower); lips pressed into each other are left as they are.
            let opening = smoothstep(0.0, SEAL_SOFT, gap.y);
            let close = gap * (s * opening * (self.max_gap / gap.length().max(1e-9)).min(1.0)); // (O1)
            out[i as usize] += w * close;
        }
    }
}

fn place(id: MuscleId, l: &Landmarks, p: &FaceParams) -> MuscleGeometry {
    use MuscleKind::*;
    let m = |v: Vec3| if id.side == Side::Right { mirror(v) } else { v };
    let ec = m(l.eye_centre);
    let gap = l.upper_lid_mid.y - l.lower_lid_mid.y;
    let fissure = l.eye_outer_corner.x - l.eye_inner_corner.x;
    let sph = |centre: Vec3, lx: f32, ly: f32, part| {
        MuscleGeometry::Sphincter(Sphincter {
            centre,
            axis_x: Vec3::X,
            axis_y: Vec3::Y,
            lx,
            ly,
            part,
        })
    };
    let (v1, v2) = match id.kind {
        FrontalisInner => (l.forehead_inner, l.brow_inner),
        FrontalisMiddle => (l.forehead_mid, l.brow_mid),
        FrontalisOuter => (l.forehead_outer, l.brow_outer),
        Corrugator => (l.orbit_inner_upper, l.brow_mid),
        Procerus => (l.nasal_bone, l.glabella),
        LevatorAlaequeNasi => (l.orbit_inner_lower, l.nostril_wing),
        LevatorLabiiSuperioris => (l.orbit_lower, l.upper_lip),
        ZygomaticMajor => (l.cheekbone, l.mouth_corner),
        Risorius => (l.face_side, l.mouth_corner),
        DepressorAnguliOris => (l.jaw_lower_edge, l.mouth_corner),
        DepressorLabiiInferioris => (l.jaw_outer, l.lower_lip),
        OculiUpperPalpebral => return MuscleGeometry::Lid(lid(id.side, l, p)),
        OculiLowerPalpebral => {
            return sph(
                Vec3::new(ec.x, l.upper_lid_mid.y, ec.z),
                0.25 * fissure,
                gap / 1.65,
                SphincterPart::Lower,
            );
        }
        OculiOrbital => return sph(ec, 0.020, 0.016, SphincterPart::Lower),
        OrbicularisOris => return sph(l.mouth_centre, 0.022, 0.013, SphincterPart::Full),
        Jaw => unreachable!("the jaw is not a channel"),
    };
    let inf = p.influence[&id.kind];
    MuscleGeometry::Linear(LinearMuscle {
        v1: m(v1),
        v2: m(v2),
        cone_half_angle: (inf.cone_deg as f32).to_radians(),
        rf_ratio: inf.rf_ratio as f32,
    })
}

/// The upper palpebral part's lid geometry from the eye landmarks: corner
/// line, margin heights fitted through the mid-lid landmarks with the
/// [`lid_margin`] shapes, and `rho_rim = 2 - 1 / k_blink` (see [`LidSphincter`]).
fn lid(side: Side, l: &Landmarks, p: &FaceParams) -> LidSphincter {
    let m = |v: Vec3| if side == Side::Right { mirror(v) } else { v };
    let (inner, outer) = (m(l.eye_inner_corner), m(l.eye_outer_corner));
    let axis_x = Vec3::new(outer.x - inner.x, outer.y - inner.y, 0.0).normalize();
    let axis_y = Vec3::new(-axis_x.y, axis_x.x, 0.0) * axis_x.x.signum();
    let s = LidSphincter {
        centre: 0.5 * (inner + outer),
        axis_x,
        axis_y,
        half_width: 0.5 * (outer - inner).dot(axis_x),
        upper_h: 1.0,
        lower_h: 1.0,
        rho_rim: (2.0 - 1.0 / p.blink.contraction) as f32,
    };
    let height = |v: Vec3, upper: bool| {
        let (xi, eta) = s.chart(m(v));
        eta.abs() / lid_margin(1.0 - xi * xi, upper).max(0.05)
    };
    let (upper_h, lower_h) = (
        height(l.upper_lid_mid, true),
        height(l.lower_lid_mid, false),
    );
    LidSphincter {
        upper_h,
        lower_h,
        ..s
    }
}

/// S1, the skin's spread of a muscle's pull: a field diffused along the
/// mesh (never across an opening it leaves, lips or lids) by the explicit
/// cotangent heat flow (Desbrun et al. 1999, SIGGRAPH, "Implicit fairing
/// of irregular meshes"), for a time `sigma^2 / 2`: a standard deviation
/// `sigma` along the skin, the same in every direction at any resolution.
/// The lids (each eye's lid zone) keep their own values: their margins are
/// held by the tarsal plates, and a brow's pull must not leak into them
/// (face.md table 4.1: frontalis does not move the lids).
/// Displacements per unit contraction smaller than this (20 um, a
/// fortieth of a pixel of the face filling a 1080-pixel picture) are left
/// out of a spread field: the spread's far tail, a sixth of its entries,
/// which every deformation would otherwise pay for.
const SPREAD_FLOOR: f32 = 2e-5;

struct Spread {
    /// Per vertex: its neighbours and their cotangent weights.
    neighbours: Vec<Vec<(u32, f32)>>,
    /// Per vertex: `min(1, dt W_i / A_i)`, the fraction of the way to its
    /// neighbours' weighted mean a step moves it (0: held).
    rate: Vec<f32>,
    steps: usize,
}

impl Spread {
    fn new(mesh: &HeadMesh, sigma: f32) -> Spread {
        let p = &mesh.positions;
        let n = p.len();
        let mut neighbours: Vec<Vec<(u32, f32)>> = vec![Vec::new(); n];
        let mut area = vec![0.0f32; n];
        for t in &mesh.triangles {
            let [a, b, c] = t.map(|i| p[i as usize]);
            let twice = (b - a).cross(c - a).length();
            if twice <= 0.0 {
                continue;
            }
            for &i in t {
                area[i as usize] += twice / 6.0;
            }
            // Each edge gets half the cotangent of the angle opposite it.
            for k in 0..3 {
                let (i, j, o) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
                let (u, v) = (p[i as usize] - p[o as usize], p[j as usize] - p[o as usize]);
                let cot = u.dot(v) / u.cross(v).length();
                for (x, y) in [(i, j), (j, i)] {
                    let list = &mut neighbours[x as usize];
                    match list.iter_mut().find(|(q, _)| *q == y) {
                        Some(e) => e.1 += 0.5 * cot,
                        None => list.push((y, 0.5 * cot)),
                    }
                }
            }
        }
        // Obtuse triangles can make a weight negative; keep the flow a
        // mean of the neighbours.
        for list in &mut neighbours {
            list.retain(|e| e.1 > 0.0);
        }
        let total: Vec<f32> = neighbours
            .iter()
            .map(|l| l.iter().map(|e| e.1).sum())
            .collect();
        // dt: half the median vertex's own stability limit A_i / W_i; the
        // few smaller cells (the poles, where no muscle reaches) move at
        // most to their neighbours' mean per step.
        let mut limits: Vec<f32> = (0..n)
            .filter(|&i| total[i] > 0.0 && area[i] > 0.0)
            .map(|i| area[i] / total[i])
            .collect();
        if limits.is_empty() {
            return Spread {
                neighbours,
                rate: vec![0.0; n],
                steps: 0,
            };
        }
        let mid = limits.len() / 2;
        let dt_max = 0.5 * *limits.select_nth_unstable_by(mid, f32::total_cmp).1;
        let time = 0.5 * sigma * sigma; // (S1) per-axis variance 2 t = sigma^2
        let steps = (time / dt_max).ceil() as usize;
        let dt = time / steps as f32;
        let mut rate: Vec<f32> = (0..n)
            .map(|i| {
                if area[i] > 0.0 {
                    (dt * total[i] / area[i]).min(1.0)
                } else {
                    0.0
                }
            })
            .collect();
        for &i in mesh.lid_zone.iter().flatten() {
            rate[i as usize] = 0.0;
        }
        Spread {
            neighbours,
            rate,
            steps,
        }
    }

    /// The field after S1's steps (dense while diffusing, sparse again).
    fn apply(&self, f: &SparseField) -> SparseField {
        let n = self.neighbours.len();
        let mut d = vec![Vec3::ZERO; n];
        for (&i, &v) in f.index.iter().zip(&f.delta) {
            d[i as usize] = v;
        }
        let mut next = d.clone();
        for _ in 0..self.steps {
            for (i, out) in next.iter_mut().enumerate() {
                let rate = self.rate[i];
                if rate == 0.0 {
                    continue;
                }
                let (mut sum, mut w) = (Vec3::ZERO, 0.0);
                for &(j, wj) in &self.neighbours[i] {
                    sum += wj * d[j as usize];
                    w += wj;
                }
                // (S1) d_i += min(1, dt W_i / A_i) (mean_j d_j - d_i)
                *out = d[i] + rate * (sum / w - d[i]);
            }
            std::mem::swap(&mut d, &mut next);
        }
        let mut out = SparseField::default();
        for (i, v) in d.into_iter().enumerate() {
            if v.length_squared() > SPREAD_FLOOR * SPREAD_FLOOR {
                out.index.push(i as u32);
                out.delta.push(v);
            }
        }
        out
    }
}

impl Rig {
    /// Place every muscle on the mesh's landmarks and precompute the fields.
    pub fn build(mesh: &HeadMesh, params: &FaceParams) -> Rig {
        let l = &mesh.landmarks;
        let mut muscles = Vec::with_capacity(N_CHANNELS);
        let mut fields = Vec::with_capacity(N_CHANNELS);
        for id in channels() {
            let g = place(id, l, params);
            let mut f = SparseField::default();
            let ec = eye_centre(l, id.side);
            for (i, &p) in mesh.positions.iter().enumerate() {
                // Sphincters act on the face only; the palpebral parts on
                // their own lid (the upper one's law has its own domain).
                let masked = match id.kind {
                    MuscleKind::OculiUpperPalpebral => p.z < ec.z,
                    MuscleKind::OculiLowerPalpebral => p.y >= ec.y || p.z < ec.z,
                    MuscleKind::OculiOrbital => p.z < ec.z || (p.x - ec.x).abs() > 0.05,
                    MuscleKind::OrbicularisOris => p.z < ec.z - 0.02,
                    _ => false,
                };
                if masked {
                    continue;
                }
                let d = g.displacement(p, 1.0);
                if d != Vec3::ZERO {
                    f.index.push(i as u32);
                    f.delta.push(d);
                }
            }
            muscles.push((id, g));
            fields.push(f);
        }
        let sigma = params.skin.pull_spread_m as f32;
        if sigma > 0.0 {
            let spread = Spread::new(mesh, sigma);
            for ((_, g), f) in muscles.iter().zip(&mut fields) {
                if matches!(g, MuscleGeometry::Linear(_)) {
                    *f = spread.apply(f);
                }
            }
        }
        let jaw = Jaw {
            pivot: Vec3::new(0.0, l.jaw_pivot.y, l.jaw_pivot.z),
            mouth_corner: l.mouth_corner,
            ear_lobe: l.ear_lobe,
            half_mouth_width: l.mouth_corner.x,
            jaw_half_width: l.jaw_half_width,
        };
        let mut jaw_field = JawField::default();
        for (i, &p) in mesh.positions.iter().enumerate() {
            let fr = jaw.fraction(p);
            if fr > 0.0 {
                jaw_field.index.push(i as u32);
                jaw_field.offset.push(p - jaw.pivot);
                jaw_field.fraction.push(fr);
            }
        }
        let mut lid_y_per_k = [[0.0; 2]; 2];
        for (e, side) in [Side::Left, Side::Right].into_iter().enumerate() {
            let m = |v: Vec3| if side == Side::Right { mirror(v) } else { v };
            let lids = [
                (MuscleKind::OculiUpperPalpebral, l.upper_lid_mid),
                (MuscleKind::OculiLowerPalpebral, l.lower_lid_mid),
            ];
            for (j, (kind, mid)) in lids.into_iter().enumerate() {
                let ch = MuscleId { kind, side }.index().expect("channel");
                lid_y_per_k[e][j] = muscles[ch].1.displacement(m(mid), 1.0).y;
            }
        }
        Rig {
            muscles,
            fields,
            jaw,
            jaw_field,
            eye_centres: [eye_centre(l, Side::Left), eye_centre(l, Side::Right)],
            lid_y_per_k,
            lip_seal: LipSeal::build(mesh, params),
        }
    }

    /// Palpebral contraction that moves the mid margin of lid `lid` (0
    /// upper, 1 lower) of eye `e` (0 left, 1 right) by `gain * eyeball
    /// radius * sin(pitch)`: the lids follow the eye's vertical rotation
    /// (pitch positive up). 0 if the channel cannot move that margin.
    pub fn lid_follow_k(&self, e: usize, lid: usize, pitch: f32, gain: f32) -> f32 {
        let c = self.lid_y_per_k[e][lid];
        if c.abs() < 1e-6 {
            0.0
        } else {
            gain * dims::EYEBALL_R * pitch.sin() / c
        }
    }

    /// Upper palpebral contraction standing for levator palpebrae's lift of
    /// eye `e`'s upper lid when an expression relaxes that channel (AU 5,
    /// `k < 0`): the relaxation alone would raise the mid margin by `u`;
    /// the lid rises `g u`, or `R tanh(g u / R)` when bounded by the
    /// highest raise `R` (L1). Contractions (`k >= 0`: a lowered lid, a
    /// blink) pass unchanged, as does a channel that cannot move the margin.
    pub fn levator_k(&self, e: usize, k: f32, gain: f32, max_raise: Option<f32>) -> f32 {
        let c = self.lid_y_per_k[e][0];
        if k >= 0.0 || c.abs() < 1e-6 {
            return k;
        }
        let u = gain * k * c; // (L1) the linear raise, metres
        let rise = max_raise.map_or(u, |r| r * (u / r).tanh()); // (L1)
        rise / c
    }

    /// Deformed positions: rest + sum k_m field_m (F1, F6 linear in k) +
    /// jaw rotation (F7), then the lip seal (O1) and the lid clearance step. `out.len()` must
    /// equal the vertex count. No allocation.
    pub fn deform(&self, mesh: &HeadMesh, a: &Activation, out: &mut [Vec3]) {
        out.copy_from_slice(&mesh.positions);
        for (k, f) in a.k.iter().zip(&self.fields) {
            if *k == 0.0 {
                continue;
            }
            for (&i, d) in f.index.iter().zip(&f.delta) {
                out[i as usize] += *k * *d;
            }
        }
        let theta = a.jaw_deg.to_radians();
        if theta != 0.0 {
            let jf = &self.jaw_field;
            for ((&i, r), fr) in jf.index.iter().zip(&jf.offset).zip(&jf.fraction) {
                out[i as usize] += jaw_rotation(*r, theta * fr); // (F7)
            }
        }
        self.lip_seal.apply(mesh, a.k[self.lip_seal.channel], out);
        for (zone, &centre) in mesh.lid_zone.iter().zip(&self.eye_centres) {
            for &i in zone {
                let p = &mut out[i as usize];
                let r = *p - centre;
                // Squared first: most of the zone is clear, no root taken.
                let len2 = r.length_squared();
                if len2 < LID_CLEARANCE * LID_CLEARANCE && len2 > 0.0 {
                    *p = centre + r * (LID_CLEARANCE / len2.sqrt());
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::face::emotion::emotion_activation;
    use crate::face::mesh::MeshParams;
    use crate::face::params::FaceParams;
    use crate::face::tables::Emotion;

    /// S1 spreads a point pull over the requested standard deviation,
    /// alike across and along the skin, at any resolution: a unit
    /// displacement at one forehead vertex ends with a per-axis spread
    /// within 20 % of `sigma`.
    #[test]
    fn spread_reaches_sigma_at_any_resolution() {
        let sigma = 0.005;
        for rows in [48, 100, 160] {
            let mesh = HeadMesh::generate(MeshParams { rows });
            let forehead = Vec3::new(0.0, 0.05, 0.2);
            let centre = (0..mesh.positions.len())
                .min_by(|&a, &b| {
                    let d = |i: usize| mesh.positions[i].distance_squared(forehead);
                    d(a).total_cmp(&d(b))
                })
                .unwrap();
            let f = SparseField {
                index: vec![centre as u32],
                delta: vec![Vec3::X],
            };
            let s = Spread::new(&mesh, sigma).apply(&f);
            let total: f32 = s.delta.iter().map(|d| d.x).sum();
            let p0 = mesh.positions[centre];
            let (mut vx, mut vy) = (0.0, 0.0);
            for (&i, d) in s.index.iter().zip(&s.delta) {
                let q = mesh.positions[i as usize] - p0;
                vx += d.x / total * q.x * q.x;
                vy += d.x / total * q.y * q.y;
            }
            let (sx, sy) = (vx.sqrt(), vy.sqrt());
            println!("rows {rows}: sd x {:.2} mm, y {:.2} mm", sx * 1e3, sy * 1e3);
            for sd in [sx, sy] {
                assert!((sd / sigma - 1.0).abs() < 0.2, "rows {rows}: {sx} x {sy}");
            }
        }
    }

    /// With no spread the fields are Waters' own (F1, F6 at k = 1).
    #[test]
    fn no_spread_keeps_waters_fields() {
        let mut params = FaceParams::default_params();
        params.skin.pull_spread_m = 0.0;
        let mesh = HeadMesh::generate(MeshParams { rows: 32 });
        let rig = Rig::build(&mesh, &params);
        for ((_, g), f) in rig.muscles.iter().zip(&rig.fields) {
            for (&i, d) in f.index.iter().zip(&f.delta) {
                assert_eq!(*d, g.displacement(mesh.positions[i as usize], 1.0));
            }
        }
    }

    /// What S1 is for: Waters' procerus shears the skin along its cone's
    /// edges, most near the nasal bone (the V up from the nose's root in
    /// every frown). The shear shows as the ratio of a triangle's two
    /// principal stretches: around the glabella in anger Waters' own field
    /// reaches 17 (3.6 spread); spread, it must stay under a quarter of it.
    #[test]
    fn spread_skin_is_not_sheared_at_the_glabella() {
        let worst = |spread: f64| {
            let mut params = FaceParams::default_params();
            params.skin.pull_spread_m = spread;
            let mesh = HeadMesh::generate(MeshParams { rows: 48 });
            let rig = Rig::build(&mesh, &params);
            let a = emotion_activation(&params, Emotion::Anger, 1.0);
            let mut d = vec![Vec3::ZERO; mesh.positions.len()];
            rig.deform(&mesh, &a, &mut d);
            let p = &mesh.positions;
            let root = mesh.landmarks.nasal_bone;
            mesh.triangles
                .iter()
                .filter(|t| p[t[0] as usize].distance(root) < 0.025)
                .map(|t| {
                    let [a, b, c] = t.map(|i| i as usize);
                    // Principal stretches of the 2x2 right Cauchy-Green
                    // tensor in the rest triangle's frame.
                    let (e1, e2) = (p[b] - p[a], p[c] - p[a]);
                    let u = e1.normalize();
                    let v = e1.cross(e2).cross(u).normalize();
                    let rest =
                        glam::Mat2::from_cols_array(&[e1.dot(u), e1.dot(v), e2.dot(u), e2.dot(v)]);
                    let inv = rest.inverse();
                    let (f1, f2) = (d[b] - d[a], d[c] - d[a]);
                    let fa = f1 * inv.x_axis.x + f2 * inv.x_axis.y;
                    let fb = f1 * inv.y_axis.x + f2 * inv.y_axis.y;
                    let (c11, c12, c22) = (fa.dot(fa), fa.dot(fb), fb.dot(fb));
                    let (m, r) = (
                        0.5 * (c11 + c22),
                        (0.25 * (c11 - c22).powi(2) + c12 * c12).sqrt(),
                    );
                    ((m + r) / (m - r).max(1e-9)).sqrt()
                })
                .fold(0.0f32, f32::max)
        };
        let (waters, spread) = (worst(0.0), worst(0.005));
        println!("stretch ratio at the glabella: {waters:.2} unspread, {spread:.2} spread");
        assert!(waters > 10.0, "{waters}");
        assert!(spread < 0.25 * waters, "{spread} vs {waters}");
    }

    /// Opening between the lips' middles of `rig` deformed by `a`, m.
    fn mid_gap(mesh: &HeadMesh, rig: &Rig, a: &Activation) -> f32 {
        let mut out = vec![Vec3::ZERO; mesh.positions.len()];
        rig.deform(mesh, a, &mut out);
        let mid = |rim: &[u32]| rim[rim.len() / 2] as usize;
        out[mid(&mesh.rims.upper_lip)].distance(out[mid(&mesh.rims.lower_lip)])
    }

    fn rig_with(mesh: &HeadMesh, seal_k: Option<f64>) -> Rig {
        let mut params = FaceParams::default_params();
        params.lips.seal_k = seal_k;
        Rig::build(mesh, &params)
    }

    /// O1: anger's orbicularis oris (0.46, past the default seal's 0.4)
    /// presses the lips together over its 3.5 degree jaw and its lower
    /// lip depressor, which part them without the seal; at every mesh
    /// resolution.
    #[test]
    fn pressed_lips_close_over_a_small_opening() {
        for rows in [32, 48, 100] {
            let mesh = HeadMesh::generate(MeshParams { rows });
            let a = emotion_activation(&FaceParams::default_params(), Emotion::Anger, 1.0);
            let rest = mid_gap(&mesh, &rig_with(&mesh, None), &Activation::default());
            let open = mid_gap(&mesh, &rig_with(&mesh, None), &a);
            let sealed = mid_gap(&mesh, &rig_with(&mesh, Some(0.4)), &a);
            assert!(open > rest + 0.001, "{rows}: {open} vs rest {rest}");
            assert!(sealed < rest + 0.0005, "{rows}: {sealed} vs rest {rest}");
        }
    }

    /// O1: pressed lips close no more than `seal_max_gap_m` of a wide
    /// opening (a pursed mouth with the jaw dropped still opens round),
    /// and a relaxed orbicularis oris leaves the lips as the thesis has
    /// them.
    #[test]
    fn the_seal_is_bounded_and_needs_the_muscle() {
        let mesh = HeadMesh::generate(MeshParams { rows: 48 });
        let (free, sealed) = (rig_with(&mesh, None), rig_with(&mesh, Some(0.4)));
        let oo = sealed.lip_seal.channel;
        let mut a = Activation {
            jaw_deg: 15.0,
            ..Activation::default()
        };
        assert_eq!(mid_gap(&mesh, &free, &a), mid_gap(&mesh, &sealed, &a));
        a.k[oo] = 0.8;
        let (open, closed) = (mid_gap(&mesh, &free, &a), mid_gap(&mesh, &sealed, &a));
        assert!(open > 0.015, "{open}");
        let max = FaceParams::default_params().lips.seal_max_gap_m as f32;
        assert!(
            (open - closed - max).abs() < 0.1 * max,
            "{open} -> {closed}"
        );
    }
}
