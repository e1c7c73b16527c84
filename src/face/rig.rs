//! Muscle placement on the generated head and the precomputed sparse
//! displacement fields (face.md 3-5).
//!
//! (F1) and (F6) are linear in k, so each muscle channel stores its
//! displacement at k = 1 for the vertices it moves. The jaw (F7) is a
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

    /// Deformed positions: rest + sum k_m field_m (F1, F6 linear in k) +
    /// jaw rotation (F7), then the lid clearance step. `out.len()` must
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
        for (zone, &centre) in mesh.lid_zone.iter().zip(&self.eye_centres) {
            for &i in zone {
                let p = &mut out[i as usize];
                let r = *p - centre;
                let len = r.length();
                if len < LID_CLEARANCE && len > 0.0 {
                    *p = centre + r * (LID_CLEARANCE / len);
                }
            }
        }
    }
}
