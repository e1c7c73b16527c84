//! Tessellation of the primitive shapes the world is made of (spheres,
//! capsules along local +Y, boxes, the floor), in their own local frames.

use std::f32::consts::{PI, TAU};

use glam::Vec3;

/// One mesh vertex: position, unit normal (local frame), colour, and the
/// face's wrinkles and painted borders.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct Vertex {
    /// Position.
    pub pos: [f32; 3],
    /// Unit normal.
    pub normal: [f32; 3],
    /// Linear RGBA, multiplied by the instance's colour.
    pub color: [f32; 4],
    /// Skin wrinkles: the lines' slopes and phases along the face's axes
    /// ([`shisen_face::wrinkle::WrinkleVertex`]); zero elsewhere.
    pub wrinkle: [f32; 4],
    /// Painted borders, thresholded per pixel: the face's lips, brows and
    /// hair ([`shisen_face::appearance::Regions`]); on the bodies, the
    /// point's depth in the torso's design frame and the bare skin's RGB
    /// colour ([`super::body::SkinVertex::vest`]); unused elsewhere.
    pub paint: [f32; 4],
    /// The face's rest position (x, y in its own frame), from which the
    /// lips' border is drawn per pixel ([`shisen_face::appearance::LipShape`]);
    /// on the bodies, the point's x, y in the torso's design frame, from
    /// which the vest's openings are; zero elsewhere.
    pub rest: [f32; 2],
}

impl Vertex {
    /// A white vertex from glam vectors (the instance gives the colour).
    pub fn new(pos: Vec3, normal: Vec3) -> Self {
        Self::coloured(pos, normal, [1.0; 4])
    }

    /// A vertex with its own colour.
    pub fn coloured(pos: Vec3, normal: Vec3, color: [f32; 4]) -> Self {
        Vertex {
            pos: pos.to_array(),
            normal: normal.to_array(),
            color,
            wrinkle: [0.0; 4],
            paint: [0.0; 4],
            rest: [0.0; 2],
        }
    }
}

/// Indexed triangle mesh on the CPU.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MeshData {
    /// Vertices.
    pub vertices: Vec<Vertex>,
    /// Triangle list indices.
    pub indices: Vec<u32>,
}

/// Latitude bands of spheres and capsule caps.
const RINGS: u32 = 24;
/// Longitude segments.
const SEGMENTS: u32 = 32;

/// Surface of revolution about +Y from a profile of (radius, y, normal)
/// points ordered from the top pole to the bottom pole, with `segments`
/// steps of longitude.
fn lathe_with(profile: &[(f32, f32, Vec3)], segments: u32) -> MeshData {
    let mut m = MeshData::default();
    for &(r, y, n) in profile {
        for s in 0..=segments {
            let phi = TAU * s as f32 / segments as f32;
            let (sin, cos) = phi.sin_cos();
            let radial = Vec3::new(sin, 0.0, cos);
            let normal = (radial * n.x + Vec3::Y * n.y).normalize_or(Vec3::Y);
            m.vertices
                .push(Vertex::new(radial * r + Vec3::Y * y, normal));
        }
    }
    let row = segments + 1;
    for i in 0..profile.len() as u32 - 1 {
        for s in 0..segments {
            let a = i * row + s;
            let b = a + row;
            m.indices.extend_from_slice(&[a, b, a + 1, a + 1, b, b + 1]);
        }
    }
    m
}

/// Unit sphere (radius 1) centred at the origin; its +Z pole is where an
/// eyeball's pupil is drawn.
pub fn sphere() -> MeshData {
    capsule(0.0, 1.0)
}

/// Capsule along local Y: a cylinder of half-length `half_height` capped by
/// hemispheres of `radius` (the rapier/parry convention).
pub fn capsule(half_height: f32, radius: f32) -> MeshData {
    capsule_with(half_height, radius, RINGS, SEGMENTS)
}

/// A capsule with `rings` latitude bands over its two caps and `segments`
/// around: coarse ones for long, thin scenery (a software rasteriser pays
/// for every long, thin triangle across the picture).
pub fn capsule_with(half_height: f32, radius: f32, rings: u32, segments: u32) -> MeshData {
    let mut profile = Vec::new();
    let half = rings / 2;
    for i in 0..=half {
        let theta = PI / 2.0 * (1.0 - i as f32 / half as f32); // pi/2 .. 0
        let n = Vec3::new(theta.cos(), theta.sin(), 0.0);
        profile.push((radius * n.x, half_height + radius * n.y, n));
    }
    for i in 0..=half {
        let theta = -PI / 2.0 * i as f32 / half as f32; // 0 .. -pi/2
        let n = Vec3::new(theta.cos(), theta.sin(), 0.0);
        profile.push((radius * n.x, -half_height + radius * n.y, n));
    }
    lathe_with(&profile, segments)
}

/// How far inside the unit sphere [`rounded_box`]`(2.0)` (the coarse
/// sphere: 30 deg round, 22.5 deg in latitude) can be, as a fraction of the
/// radius: the middle of a quad's diagonal, 1 - cos(37.5 deg / 2).
pub const BLOB_ERROR: f32 = 0.054;

/// Rounded box of half extent 1: the superellipsoid
/// `|x|^p + |y|^p + |z|^p = 1` (a sphere at `p = 2`, nearer a cube as `p`
/// grows), a coarse sphere's vertices carried onto it with its exact
/// normals.
pub fn rounded_box(p: f32) -> MeshData {
    // A coarse sphere: a crown covers a few pixels, and a mouth shows up
    // to twenty of them.
    let profile: Vec<(f32, f32, Vec3)> = (0..=8)
        .map(|i| {
            let theta = PI / 2.0 - PI * i as f32 / 8.0; // pi/2 .. -pi/2
            let n = Vec3::new(theta.cos(), theta.sin(), 0.0);
            (n.x, n.y, n)
        })
        .collect();
    let mut m = lathe_with(&profile, 12);
    let carry = |v: f32, e: f32| v.signum() * v.abs().powf(e);
    for v in &mut m.vertices {
        let s = Vec3::from_array(v.pos);
        let q = Vec3::new(
            carry(s.x, 2.0 / p),
            carry(s.y, 2.0 / p),
            carry(s.z, 2.0 / p),
        );
        // The surface's gradient: sign(q) |q|^(p - 1) per axis.
        let n = Vec3::new(
            carry(q.x, p - 1.0),
            carry(q.y, p - 1.0),
            carry(q.z, p - 1.0),
        );
        v.pos = q.to_array();
        v.normal = n.normalize_or(s).to_array();
    }
    m
}

/// Unit cube (half extent 1) with flat faces.
pub fn cube() -> MeshData {
    let mut m = MeshData::default();
    for axis in [Vec3::X, Vec3::Y, Vec3::Z] {
        for sign in [1.0, -1.0] {
            let n = axis * sign;
            let u = if axis == Vec3::Y { Vec3::Z } else { Vec3::Y };
            let v = n.cross(u);
            let base = m.vertices.len() as u32;
            for (a, b) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
                m.vertices.push(Vertex::new(n + u * a + v * b, n));
            }
            m.indices
                .extend_from_slice(&[base, base + 1, base + 2, base, base + 2, base + 3]);
        }
    }
    m
}

/// Square in the XZ plane, half extent 1, normal +Y.
pub fn floor() -> MeshData {
    let v = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .map(|(x, z)| Vertex::new(Vec3::new(x, 0.0, z), Vec3::Y));
    MeshData {
        vertices: v.to_vec(),
        indices: vec![0, 2, 1, 0, 3, 2],
    }
}

/// A left ear (outer surface, two-sided), in its own frame: metres, +X
/// out of the head, +Y up, +Z forward, the origin where its front edge
/// joins the head. About 62 mm tall and 34 mm wide (adult pinna, Sforza et
/// al. 2009, Int. J. Pediatr. Otorhinolaryngol. 73:1331), set back 15 deg,
/// flaring out at the back, with a deep concha, a rim rolled forward (the
/// helix) round its top and back, the antihelix's ridge inside it, and a
/// lobe narrower than the top.
pub fn ear() -> MeshData {
    const AROUND: u32 = 40;
    const ACROSS: u32 = 16;
    let (half_h, half_w) = (0.031, 0.017);
    let tilt = 15f32.to_radians();
    let point = |theta: f32, v: f32| {
        // Outline: an ellipse, narrower at the lobe (bottom).
        let lobe = 1.0 - 0.25 * (-theta.sin()).max(0.0);
        let (a, b) = (half_w * theta.cos() * lobe, half_h * theta.sin());
        // Back part (theta near pi) stands off the head most.
        let back = 0.5 * (1.0 - theta.cos());
        let flare = 0.002 + 0.013 * back * v;
        // The concha: a deep bowl before the ear canal, in the ear's
        // lower middle.
        let cup = -0.008 * (1.0 - (v / 0.6).min(1.0)).powi(2) * (1.0 - 0.6 * back);
        // The helix: a rim rolled forward over the ear's edge, round its
        // top and back (not at the lobe).
        let upper = (theta.sin() + 0.3).clamp(0.0, 1.0);
        let rim = 0.004 * (-((v - 0.86) / 0.06).powi(2)).exp()
            - 0.005 * ((v - 0.93) / 0.07).max(0.0).powi(2);
        let helix = rim * (0.35 + 0.65 * upper) * back.max(0.3);
        // The antihelix: a ridge inside the helix over the upper back,
        // with a hollow (the scapha) between them.
        let antihelix = (0.0028 * (-((v - 0.62) / 0.07).powi(2)).exp()
            - 0.0015 * (-((v - 0.76) / 0.05).powi(2)).exp())
            * upper
            * back;
        let x = flare + cup + helix + antihelix;
        let (y, z) = (b * v, a * v - half_w);
        // Set back: rotate about X (the ear's top leans back).
        Vec3::new(
            x,
            y * tilt.cos() + z * tilt.sin(),
            -y * tilt.sin() + z * tilt.cos(),
        )
    };
    let mut vertices = Vec::new();
    for i in 0..=ACROSS {
        for j in 0..AROUND {
            let (v, theta) = (i as f32 / ACROSS as f32, j as f32 / AROUND as f32 * TAU);
            let p = point(theta, v.max(0.02));
            let du = point(theta + 0.01, v.max(0.02)) - p;
            // A forward difference, backward at the rim (v = 1).
            let dv = if v + 0.01 <= 1.0 {
                point(theta, (v + 0.01).max(0.03)) - p
            } else {
                p - point(theta, v - 0.01)
            };
            let n = dv.cross(du).normalize_or(Vec3::X);
            vertices.push(Vertex::new(p, if n.x < 0.0 { -n } else { n }));
        }
    }
    let mut indices = Vec::new();
    for i in 0..ACROSS {
        for j in 0..AROUND {
            let a = i * AROUND + j;
            let b = i * AROUND + (j + 1) % AROUND;
            let (c, d) = (a + AROUND, b + AROUND);
            indices.extend([a, c, b, b, c, d]);
        }
    }
    MeshData { vertices, indices }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn capsule_spans_its_half_height_plus_radius() {
        let m = capsule(0.1, 0.05);
        let (lo, hi) = m.vertices.iter().fold((f32::MAX, f32::MIN), |(lo, hi), v| {
            (lo.min(v.pos[1]), hi.max(v.pos[1]))
        });
        assert!((hi - 0.15).abs() < 1e-6 && (lo + 0.15).abs() < 1e-6);
        assert!(m.indices.iter().all(|&i| (i as usize) < m.vertices.len()));
        for v in &m.vertices {
            assert!((Vec3::from(v.normal).length() - 1.0).abs() < 1e-5);
        }
    }

    #[test]
    fn sphere_and_cube_are_closed_index_lists() {
        for m in [sphere(), cube(), floor(), rounded_box(6.0)] {
            assert_eq!(m.indices.len() % 3, 0);
            assert!(m.indices.iter().all(|&i| (i as usize) < m.vertices.len()));
        }
    }
}
