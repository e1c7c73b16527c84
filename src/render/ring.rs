//! The boxing ring: canvas, apron and platform, corner posts and pads,
//! four ropes, under a rig of lamps, in a dim hall: its floor, banks of
//! seats on four sides, dark beyond (the clear colour). Static scenery,
//! drawn with the shared primitives (no physics: the fighters do not reach
//! the ropes). The ring's size and corners are the bout's
//! (`shisen::sim::bout`).
//!
//! Sizes follow amateur rules (AIBA Technical & Competition Rules): a
//! ring 4.9-6.1 m square inside the ropes (here 5.5 m), four ropes 40.6,
//! 71.1, 101.6 and 132.1 cm above the canvas, 3-5 cm thick, an apron of
//! at least 0.5 m outside them, the platform 0.91-1.22 m above the floor
//! (here 1.0 m).

use glam::{Mat3, Mat4, Quat, Vec3};

use super::draw::{Draw, Material, MeshKey, TOP_DIR, key_fill_light, plain_light};
use super::geometry::{self, MeshData};
use shisen::sim::bout;

/// Half the ring's side inside the ropes, m.
pub(super) const HALF: f32 = bout::RING_HALF as f32;
/// Centre of the ring, world (midway between the fighters at rest).
pub(super) const CENTRE: Vec3 = Vec3::new(
    bout::RING_CENTRE.x as f32,
    bout::RING_CENTRE.y as f32,
    bout::RING_CENTRE.z as f32,
);
/// The lamp rig's height above the canvas, m.
const RIG: f32 = 3.6;
const LAMP: [f32; 4] = [3.0, 2.8, 2.4, 1.0];
/// Heights of the ropes above the canvas, m.
const ROPES: [f32; 4] = [0.406, 0.711, 1.016, 1.321];
/// Rope radius, m.
const ROPE_R: f32 = 0.02;
/// Corner post: height above the canvas and radius, m.
const POST: (f32, f32) = (1.40, 0.045);
/// The platform's height above the hall's floor, m.
pub(super) const PLATFORM: f32 = 1.0;
/// The apron's width outside the posts, m.
const APRON: f32 = 0.6;

const CANVAS: [f32; 4] = [0.42, 0.50, 0.62, 1.0];
const SKIRT: [f32; 4] = [0.05, 0.07, 0.16, 1.0];
const ROPE: [f32; 4] = [0.85, 0.85, 0.85, 1.0];
const ROPE_RED: [f32; 4] = [0.70, 0.06, 0.06, 1.0];
const POST_METAL: [f32; 4] = [0.12, 0.12, 0.13, 1.0];
/// Corner pads, in the order of [`pieces`]' corners: the VH's corner
/// (behind it on its left) red, yours blue, the neutral corners white.
const PADS: [[f32; 4]; 4] = [
    [0.85, 0.85, 0.85, 1.0],
    [0.70, 0.05, 0.05, 1.0],
    [0.85, 0.85, 0.85, 1.0],
    [0.06, 0.16, 0.70, 1.0],
];

/// One piece of the ring (or the hall): a mesh placed by `model`, in one
/// colour.
pub(super) struct Piece {
    mesh: fn() -> MeshData,
    capsule: Option<(f32, f32)>,
    pub(super) model: Mat4,
    color: [f32; 4],
}

/// A box of half extents `half` centred at `at` (the cube mesh spans +-1).
pub(super) fn cube(at: Vec3, half: Vec3, color: [f32; 4]) -> Piece {
    Piece {
        mesh: geometry::cube,
        capsule: None,
        model: Mat4::from_scale_rotation_translation(half, Quat::IDENTITY, at),
        color,
    }
}

/// A capsule from `a` to `b` of radius `r`.
pub(super) fn bar(a: Vec3, b: Vec3, r: f32, color: [f32; 4]) -> Piece {
    let d = b - a;
    let half = (d.length() / 2.0 - r).max(0.001);
    Piece {
        mesh: geometry::cube,
        capsule: Some((half, r)),
        model: Mat4::from_rotation_translation(
            Quat::from_rotation_arc(Vec3::Y, d.normalize()),
            (a + b) / 2.0,
        ),
        color,
    }
}

/// The ring but its canvas as one mesh with its colours in the vertices:
/// static scenery in a single draw call.
pub fn mesh() -> MeshData {
    let mut m = bake(pieces(), true);
    // The shadows the ropes and posts cast on the canvas from the lamps
    // (static, so drawn once: the canvas in the key and fill light only).
    let s = bake_with(rope_shadows(), &|_, _| key_fill_light(Vec3::Y));
    let base = m.vertices.len() as u32;
    m.vertices.extend(s.vertices);
    m.indices.extend(s.indices.iter().map(|i| i + base));
    m
}

/// The ropes' and posts' shadows on the canvas: each projected down the
/// top light ([`TOP_DIR`]) onto it, as a thin dark strip just above it,
/// clipped to the canvas, widened by the penumbra of lamps a few metres
/// up.
fn rope_shadows() -> Vec<Piece> {
    let side = HALF + APRON;
    let d = TOP_DIR / -TOP_DIR.y;
    let onto = |p: Vec3| Vec3::new(p.x + p.y * d.x, CENTRE.y + 0.003, p.z + p.y * d.z);
    let inside = |p: Vec3| (p.x - CENTRE.x).abs() <= side && (p.z - CENTRE.z).abs() <= side;
    let mut out = Vec::new();
    let mut strip = |a: Vec3, b: Vec3, width: f32| {
        let (a, b) = (onto(a), onto(b));
        // Clip to the canvas by bisection from each inside end (a strip
        // outside it falls on the apron's skirt, unseen).
        let clip = |from: Vec3, to: Vec3| {
            let (mut lo, mut hi) = (0.0f32, 1.0f32);
            if inside(to) {
                return to;
            }
            for _ in 0..20 {
                let mid = (lo + hi) / 2.0;
                if inside(from.lerp(to, mid)) {
                    lo = mid
                } else {
                    hi = mid
                }
            }
            from.lerp(to, lo)
        };
        let (a, b) = match (inside(a), inside(b)) {
            (true, _) => (a, clip(a, b)),
            (false, true) => (clip(b, a), b),
            (false, false) => return,
        };
        let len = (b - a).length();
        if len < 0.01 {
            return;
        }
        let dir = (b - a) / len;
        let mut p = cube(Vec3::ZERO, Vec3::ONE, CANVAS);
        p.model = Mat4::from_translation((a + b) / 2.0)
            * Mat4::from_quat(Quat::from_rotation_arc(Vec3::X, dir))
            * Mat4::from_scale(Vec3::new(len / 2.0, 0.001, width / 2.0));
        out.push(p);
    };
    let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .map(|(x, z)| CENTRE + Vec3::new(x * HALF, 0.0, z * HALF));
    for (k, &c) in corners.iter().enumerate() {
        let next = corners[(k + 1) % 4];
        for h in ROPES {
            strip(c + Vec3::Y * h, next + Vec3::Y * h, 2.0 * ROPE_R + 0.03 * h);
        }
        strip(c, c + Vec3::Y * POST.0, 2.0 * POST.1 + 0.04);
    }
    out
}

/// The pieces as one mesh, in world coordinates, with their colours in
/// the vertices, `lit` by the scene's lights once here (static scenery
/// under static lights: the software rasteriser shades it at the cost of a
/// copy; the fighters' shadows fall on the canvas, not on it).
fn bake(pieces: Vec<Piece>, lit: bool) -> MeshData {
    if lit {
        bake_with(pieces, &|_, n| plain_light(n))
    } else {
        bake_with(pieces, &|_, _| 1.0)
    }
}

/// The pieces as one mesh, in world coordinates, each vertex coloured by
/// its piece's colour times `light(position, normal)`.
pub(super) fn bake_with(pieces: Vec<Piece>, light: &dyn Fn(Vec3, Vec3) -> f32) -> MeshData {
    let mut out = MeshData::default();
    for p in pieces {
        let m = match p.capsule {
            // Ropes and posts a few pixels wide: six sides are round enough.
            Some((h, r)) => geometry::capsule_with(h, r, 2, 6),
            None => (p.mesh)(),
        };
        let normal = Mat3::from_mat4(p.model).inverse().transpose();
        let base = out.vertices.len() as u32;
        out.vertices.extend(m.vertices.iter().map(|v| {
            let mut v = *v;
            let at = p.model.transform_point3(Vec3::from(v.pos));
            v.pos = at.to_array();
            let n = (normal * Vec3::from(v.normal)).normalize();
            v.normal = n.to_array();
            let light = light(at, n);
            v.color = [
                p.color[0] * light,
                p.color[1] * light,
                p.color[2] * light,
                1.0,
            ];
            v
        }));
        out.indices.extend(m.indices.iter().map(|i| i + base));
    }
    out
}

/// The ring's draws: the canvas, flat-lit but for the fighters' shadows
/// (it covers a third of the picture), then the rest as one mesh lit once
/// on the CPU ([`MeshKey::Ring`], uploaded once), and the lamps.
/// The canvas goes first so the platform's top face under it fails the
/// depth test before it is shaded: drawn the other way round, a software
/// rasteriser lit that hidden face at every canvas pixel (a seventh of the
/// frame rate).
pub fn draws() -> [Draw; 3] {
    let side = HALF + APRON;
    [
        Draw {
            mesh: MeshKey::Floor,
            model: Mat4::from_scale_rotation_translation(
                Vec3::new(side, 1.0, side),
                Quat::IDENTITY,
                CENTRE,
            ),
            color: CANVAS,
            material: Material::Floor,
        },
        Draw {
            mesh: MeshKey::Ring,
            model: Mat4::IDENTITY,
            color: [1.0; 4],
            material: Material::Emissive,
        },
        Draw {
            mesh: MeshKey::Lamps,
            model: Mat4::IDENTITY,
            color: [1.0; 4],
            material: Material::Emissive,
        },
    ]
}

/// The lamps under the rig: two rows of four over each side of the
/// ring, facing down.
fn lamp_pieces() -> Vec<Piece> {
    let mut out = Vec::new();
    for i in 0..4 {
        for side in [-1.0, 1.0] {
            let x = (i as f32 - 1.5) * HALF * 0.5;
            for (a, b) in [(x, side * HALF * 0.8), (side * HALF * 0.8, x)] {
                out.push(cube(
                    CENTRE + Vec3::new(a, RIG - 0.08, b),
                    Vec3::new(0.14, 0.03, 0.14),
                    LAMP,
                ));
            }
        }
    }
    out
}

/// The lamps as one mesh.
pub fn lamps() -> MeshData {
    bake(lamp_pieces(), false)
}

/// The ring's pieces.
fn pieces() -> Vec<Piece> {
    let mut out = Vec::new();
    let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .map(|(x, z)| CENTRE + Vec3::new(x * HALF, 0.0, z * HALF));
    for (k, &c) in corners.iter().enumerate() {
        out.push(bar(c, c + Vec3::Y * POST.0, POST.1, POST_METAL));
        // The pad: a padded column over the ropes' corner, facing the ring.
        let inward = (CENTRE - c).normalize() * 0.08;
        out.push(cube(
            c + inward + Vec3::Y * 0.86,
            Vec3::new(0.08, 0.52, 0.08),
            PADS[k],
        ));
        let next = corners[(k + 1) % 4];
        for (i, h) in ROPES.into_iter().enumerate() {
            let up = Vec3::Y * h;
            let color = if i == ROPES.len() - 1 { ROPE_RED } else { ROPE };
            out.push(bar(c + up, next + up, ROPE_R, color));
        }
    }
    let side = HALF + APRON;
    // The platform's skirt below the canvas (drawn apart: [`canvas`]).
    out.push(cube(
        CENTRE - Vec3::Y * (0.04 + (PLATFORM - 0.04) / 2.0),
        Vec3::new(side, (PLATFORM - 0.04) / 2.0, side),
        SKIRT,
    ));
    // The lamp rig: a square truss on four columns outside the apron.
    let r = HALF * 0.95;
    let rig = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .map(|(x, z)| CENTRE + Vec3::new(x * r, RIG, z * r));
    for (k, &c) in rig.iter().enumerate() {
        out.push(bar(c, rig[(k + 1) % 4], 0.05, POST_METAL));
        let foot = CENTRE + (c - CENTRE) * ((side + 1.0) / r) * Vec3::new(1.0, 0.0, 1.0);
        out.push(bar(
            foot - Vec3::Y * PLATFORM,
            foot + Vec3::Y * (RIG + 0.05),
            0.06,
            POST_METAL,
        ));
        out.push(bar(foot + Vec3::Y * RIG, c, 0.05, POST_METAL));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fighters stand inside the ropes, on the canvas; four posts, four
    /// ropes a side.
    #[test]
    fn the_ring_holds_the_fighters() {
        let d = pieces();
        let bars = d.iter().filter(|x| x.capsule.is_some()).count();
        assert_eq!(bars, 4 + 16 + 12, "four posts, sixteen ropes, the rig");
        let m = mesh();
        assert!(m.indices.iter().all(|&i| (i as usize) < m.vertices.len()));
        let top = m.vertices.iter().map(|v| v.pos[1]).fold(f32::MIN, f32::max);
        assert!((top - RIG).abs() < 0.15, "the rig's top: {top}");
        // Every lamp hangs over the canvas, under the rig.
        for v in lamps().vertices {
            let p = Vec3::from(v.pos) - CENTRE;
            assert!(p.x.abs() < HALF && p.z.abs() < HALF && p.y < RIG, "{p}");
        }
        for fighter in [Vec3::ZERO, Vec3::new(0.0, 0.0, 0.92)] {
            let off = (fighter - CENTRE).abs();
            assert!(off.x < HALF - 1.0 && off.z < HALF - 1.0);
        }
    }
}
