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
use glam::Vec3;
use shisen_gaze::util::math::smoothstep;

pub use crate::lip_seal::LipSeal;
pub use crate::spread::SparseField;
use crate::spread::Spread;

fn eye_centre(l: &Landmarks, side: Side) -> Vec3 {
    if side == Side::Right {
        mirror(l.eye_centre)
    } else {
        l.eye_centre
    }
}

/// How far to either side of the eye's centre the orbital part of
/// orbicularis oculi moves the skin, m.
const ORBITAL_REACH: f32 = 0.05;

/// The factor on channel `kind`'s field at rest point `p` (eye centre
/// `ec`): the orbital part's field fades out over `width` toward its
/// mask's edges (`skin.domain_fade_m`; cut off, it stepped the skin along
/// a line down the cheek beside the eye in every smile); 1 for every
/// other channel, and everywhere when `width` is 0.
fn mask_fade(kind: MuscleKind, p: Vec3, ec: Vec3, width: f32) -> f32 {
    if kind != MuscleKind::OculiOrbital || width <= 0.0 {
        return 1.0;
    }
    let side = (ORBITAL_REACH - (p.x - ec.x).abs()) / width;
    // The skin in front of the eye's centre is only millimetres deep:
    // the fade toward that plane is a quarter as wide.
    let back = (p.z - ec.z) / (0.25 * width);
    smoothstep(0.0, 1.0, side) * smoothstep(0.0, 1.0, back)
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

fn place(id: MuscleId, l: &Landmarks, p: &FaceParams) -> MuscleGeometry {
    use MuscleKind::*;
    let m = |v: Vec3| if id.side == Side::Right { mirror(v) } else { v };
    let ec = m(l.eye_centre);
    let gap = l.upper_lid_mid.y - l.lower_lid_mid.y;
    let fissure = l.eye_outer_corner.x - l.eye_inner_corner.x;
    let sph = |centre: Vec3, lx: f32, ly: f32, part, x_share: f32| {
        MuscleGeometry::Sphincter(Sphincter {
            centre,
            axis_x: Vec3::X,
            axis_y: Vec3::Y,
            lx,
            ly,
            part,
            x_share,
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
                1.0,
            );
        }
        OculiOrbital => return sph(ec, 0.020, 0.016, SphincterPart::Lower, 1.0),
        OrbicularisOris => {
            let share = p.lips.oris_width_share.unwrap_or(1.0) as f32;
            return sph(l.mouth_centre, 0.022, 0.013, SphincterPart::Full, share);
        }
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
        let fade = params.skin.domain_fade_m as f32;
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
                    MuscleKind::OculiOrbital => p.z < ec.z || (p.x - ec.x).abs() > ORBITAL_REACH,
                    MuscleKind::OrbicularisOris => p.z < ec.z - 0.02,
                    _ => false,
                };
                if masked {
                    continue;
                }
                let d = mask_fade(id.kind, p, ec, fade) * g.displacement(p, 1.0);
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
    /// upper, 1 lower) of eye `e` (0 left, 1 right) up by `rise` metres;
    /// 0 if the channel cannot move that margin.
    pub fn lid_k(&self, e: usize, lid: usize, rise: f32) -> f32 {
        let c = self.lid_y_per_k[e][lid];
        if c.abs() < 1e-6 { 0.0 } else { rise / c }
    }

    /// Palpebral contraction by which lid `lid` of eye `e` follows the
    /// eye's vertical rotation (pitch positive up): its mid margin moves
    /// `gain * eyeball radius * sin(pitch)`.
    pub fn lid_follow_k(&self, e: usize, lid: usize, pitch: f32, gain: f32) -> f32 {
        self.lid_k(e, lid, gain * dims::EYEBALL_R * pitch.sin())
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
    use crate::emotion::emotion_activation;
    use crate::mesh::MeshParams;
    use crate::params::FaceParams;
    use crate::tables::Emotion;

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

    /// With no spread the fields are Waters' own (F1, F6 at k = 1), the
    /// orbital part's faded at its mask.
    #[test]
    fn no_spread_keeps_waters_fields() {
        let mut params = FaceParams::default_params();
        params.skin.pull_spread_m = 0.0;
        let mesh = HeadMesh::generate(MeshParams { rows: 32 });
        let rig = Rig::build(&mesh, &params);
        for ((id, g), f) in rig.muscles.iter().zip(&rig.fields) {
            let ec = eye_centre(&mesh.landmarks, id.side);
            for (&i, d) in f.index.iter().zip(&f.delta) {
                let p = mesh.positions[i as usize];
                assert_eq!(
                    *d,
                    mask_fade(id.kind, p, ec, params.skin.domain_fade_m as f32)
                        * g.displacement(p, 1.0)
                );
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
            let a = emotion_activation(&FaceParams::thesis_params(), Emotion::Anger, 1.0);
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

    /// AU 23 (orbicularis oris at anger's 0.46) narrows the lips and holds
    /// the mouth's width (the corners anchored at the modiolus,
    /// `oris_width_share` 0.3: each corner in by about 3 mm); the thesis's
    /// ring draws them in as far as it closes the lips (about 10 mm, a
    /// pucker).
    #[test]
    fn the_lip_tightener_keeps_the_mouth_wide() {
        let mesh = HeadMesh::generate(MeshParams { rows: 48 });
        let corner = mesh.rims.upper_lip[0] as usize;
        let inward = |share: Option<f64>| {
            let mut params = FaceParams::default_params();
            params.lips.oris_width_share = share;
            let rig = Rig::build(&mesh, &params);
            let mut a = Activation::default();
            a.k[rig.lip_seal.channel] = 0.46;
            let mut out = vec![Vec3::ZERO; mesh.positions.len()];
            rig.deform(&mesh, &a, &mut out);
            mesh.positions[corner].x.abs() - out[corner].x.abs()
        };
        let (human, thesis) = (inward(Some(0.3)), inward(None));
        assert!((0.001..0.0045).contains(&human), "{human}");
        assert!(thesis > 0.008, "{thesis}");
    }
}
