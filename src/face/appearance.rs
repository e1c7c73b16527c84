//! What the skin looks like where it is not plain skin: hair, brows, lips,
//! the lash line, a flush over the cheeks. Each is a colour painted on the
//! rest mesh's vertices from its landmarks, once, so it moves with every
//! muscle as the skin carrying it does: a brow painted on the skin over the
//! brow ridge rises with frontalis and knits with corrugator, exactly as
//! far as the skin moves (docs/model/face.md "Appearance").
//!
//! Colours are linear RGB. Regions are soft-edged (a few millimetres of
//! blend) so no vertex-sized steps show at any resolution.

use glam::{Vec2, Vec3};

use super::mesh::{HeadMesh, Landmarks, dims, mirror};

/// The colours of a face (linear RGB).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FaceStyle {
    /// Skin.
    pub skin: [f32; 3],
    /// Hair (a short crop) and brows' base.
    pub hair: [f32; 3],
    /// Brows.
    pub brow: [f32; 3],
    /// Lips' vermilion.
    pub lips: [f32; 3],
    /// The lash line along the lid margins.
    pub lashes: [f32; 3],
    /// Cheek flush (mixed into the skin over the cheekbones).
    pub flush: [f32; 3],
}

impl Default for FaceStyle {
    fn default() -> Self {
        Self::DEFAULT
    }
}

impl FaceStyle {
    /// The default face: a light-brown skin, dark short hair.
    pub const DEFAULT: FaceStyle = FaceStyle {
        skin: [0.62, 0.40, 0.30],
        hair: [0.035, 0.025, 0.02],
        brow: [0.05, 0.032, 0.024],
        lips: [0.44, 0.16, 0.15],
        lashes: [0.02, 0.015, 0.015],
        flush: [0.66, 0.30, 0.26],
    };
}

/// Hairline height above the eye centres (m) by azimuth about the head's
/// vertical axis (deg; 0 = straight ahead, 180 = the back): high on the
/// forehead, receding at the temples, above the ears, down to the nape.
const HAIRLINE: [(f32, f32); 9] = [
    (0.0, 0.080),
    (30.0, 0.071),
    (50.0, 0.052),
    (65.0, 0.036),
    (80.0, 0.026),
    (105.0, 0.024),
    (125.0, -0.035),
    (150.0, -0.075),
    (180.0, -0.088),
];

/// Width of every region's soft edge, m.
const EDGE: f32 = 0.0025;

fn smooth(edge0: f32, edge1: f32, x: f32) -> f32 {
    let t = ((x - edge0) / (edge1 - edge0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

fn mix(a: [f32; 3], b: [f32; 3], t: f32) -> [f32; 3] {
    [0, 1, 2].map(|k| a[k] + (b[k] - a[k]) * t)
}

fn hairline(azimuth_deg: f32) -> f32 {
    let a = azimuth_deg.abs().min(180.0);
    let k = HAIRLINE
        .windows(2)
        .position(|w| a <= w[1].0)
        .unwrap_or(HAIRLINE.len() - 2);
    let ((a0, h0), (a1, h1)) = (HAIRLINE[k], HAIRLINE[k + 1]);
    h0 + (h1 - h0) * (a - a0) / (a1 - a0)
}

/// How much of the hair covers the point (0..1); `soft` is the half-width
/// of the hairline's blend (wider on a coarse mesh).
fn hair(p: Vec3, soft: f32) -> f32 {
    let azimuth = p.x.atan2(p.z - dims::Z_C).to_degrees();
    smooth(-soft, soft, p.y - hairline(azimuth))
}

/// Distance from `p` to the polyline `pts`, and where along it (0..1).
fn to_polyline(p: Vec3, pts: &[Vec3]) -> (f32, f32) {
    let total: f32 = pts.windows(2).map(|w| w[0].distance(w[1])).sum();
    let (mut best, mut at, mut run) = (f32::MAX, 0.0, 0.0);
    for w in pts.windows(2) {
        let (a, b) = (w[0], w[1]);
        let len = a.distance(b);
        let t = ((p - a).dot(b - a) / (len * len)).clamp(0.0, 1.0);
        let d = p.distance(a + (b - a) * t);
        if d < best {
            best = d;
            at = (run + t * len) / total;
        }
        run += len;
    }
    (best, at)
}

/// How much brow covers the point (0..1): a band along the brow
/// landmarks, thick at the head and tapering to the tail. `soft` is the
/// half-width of its soft edge (wider on a coarse mesh, so the band never
/// falls between vertices and breaks into dashes).
fn brow(p: Vec3, l: &Landmarks, soft: f32) -> f32 {
    let side = |f: fn(Vec3) -> Vec3| {
        let pts = [
            f(l.brow_inner - Vec3::new(0.002, 0.0, 0.0)),
            f(l.brow_inner + Vec3::new(0.003, 0.001, 0.0)),
            f(l.brow_mid + Vec3::new(0.0, 0.001, 0.0)),
            f(l.brow_outer),
            f(l.brow_outer + Vec3::new(0.006, -0.005, -0.004)),
        ];
        let (d, t) = to_polyline(p, &pts);
        let half = (0.0058 - 0.0032 * t).max(soft);
        smooth(half + soft, half - soft, d)
    };
    // Only the front of the face (not the inside of the lid shells).
    let front = smooth(-0.01, 0.0, p.z - l.brow_outer.z + 0.01);
    side(|v| v).max(side(mirror)) * front
}

/// How much lip covers the point (0..1): the vermilion, an ellipse-like
/// band above and below the mouth line, widest at the middle (with a
/// Cupid's bow) and closing at the corners.
fn lips(p: Vec3, l: &Landmarks, soft: f32) -> f32 {
    let half_w = l.mouth_corner.x;
    let u = (p.x / half_w).abs();
    if u >= 1.0 || p.z < l.mouth_corner.z - 0.012 {
        return 0.0;
    }
    let taper = (1.0 - u * u).max(0.0).sqrt();
    let bow =
        1.0 + 0.18 * (-((u - 0.28) / 0.12).powi(2)).exp() - 0.15 * (-(u / 0.08).powi(2)).exp();
    let top = dims::MOUTH_Y + (l.upper_lip.y - dims::MOUTH_Y + 0.0025) * taper * bow;
    let bottom = dims::MOUTH_Y - (dims::MOUTH_Y - l.lower_lip.y + 0.0035) * taper;
    smooth(top + soft, top - soft, p.y) * smooth(bottom - soft, bottom + soft, p.y)
}

/// How dark the lash line is at the point (0..1): within a millimetre or
/// two of a lid rim, the upper one darker.
fn lashes(p: Vec3, upper: &[Vec3], lower: &[Vec3]) -> f32 {
    let near = |rim: &[Vec3], width: f32| {
        let d = rim.iter().map(|r| r.distance(p)).fold(f32::MAX, f32::min);
        smooth(width, width * 0.4, d)
    };
    near(upper, 0.0022).max(0.45 * near(lower, 0.0013))
}

/// The flush over each cheekbone (0..1).
fn flush(p: Vec3, l: &Landmarks) -> f32 {
    let c = l.cheekbone + Vec3::new(-0.012, -0.012, 0.006);
    let d = Vec2::new(p.x.abs() - c.x, p.y - c.y).length();
    0.35 * smooth(0.024, 0.0, d) * smooth(-0.03, 0.0, p.z - c.z)
}

/// Each vertex's mean edge length (the mesh's local resolution), m.
fn edge_length(mesh: &HeadMesh) -> Vec<f32> {
    let mut sum = vec![(0.0, 0u32); mesh.positions.len()];
    for t in &mesh.triangles {
        for k in 0..3 {
            let (a, b) = (t[k] as usize, t[(k + 1) % 3] as usize);
            let len = mesh.positions[a].distance(mesh.positions[b]);
            for i in [a, b] {
                sum[i].0 += len;
                sum[i].1 += 1;
            }
        }
    }
    sum.into_iter()
        .map(|(s, n)| if n == 0 { 0.0 } else { s / n as f32 })
        .collect()
}

/// Paint the rest mesh: one linear RGBA colour per vertex.
pub fn paint(mesh: &HeadMesh, style: &FaceStyle) -> Vec<[f32; 4]> {
    let l = &mesh.landmarks;
    let rim = |loops: &[Vec<u32>; 2]| -> Vec<Vec3> {
        loops
            .iter()
            .flatten()
            .map(|&i| mesh.positions[i as usize])
            .collect()
    };
    let (upper, lower) = (rim(&mesh.rims.upper_lid), rim(&mesh.rims.lower_lid));
    let spacing = edge_length(mesh);
    mesh.positions
        .iter()
        .zip(spacing)
        .map(|(&p, spacing)| {
            let mut c = mix(style.skin, style.flush, flush(p, l));
            c = mix(c, style.lips, lips(p, l, (0.8 * spacing).max(0.002)));
            c = mix(c, style.brow, brow(p, l, (0.5 * spacing).max(0.002)));
            c = mix(c, style.lashes, lashes(p, &upper, &lower));
            c = mix(c, style.hair, hair(p, (0.8 * spacing).max(2.0 * EDGE)));
            [c[0], c[1], c[2], 1.0]
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::face::mesh::MeshParams;

    fn close(a: [f32; 4], b: [f32; 3]) -> bool {
        (0..3).all(|k| (a[k] - b[k]).abs() < 0.02)
    }

    /// Each region lands where its landmark says, and only there: the
    /// vertex nearest each landmark takes the region's colour; the nose
    /// tip and the chin stay skin.
    #[test]
    fn regions_sit_on_their_landmarks() {
        let mesh = HeadMesh::generate(MeshParams { rows: 64 });
        let s = FaceStyle::default();
        let colours = paint(&mesh, &s);
        let at = |p: Vec3| {
            let i = (0..mesh.positions.len())
                .min_by(|&a, &b| {
                    mesh.positions[a]
                        .distance(p)
                        .total_cmp(&mesh.positions[b].distance(p))
                })
                .expect("vertices");
            colours[i]
        };
        let l = &mesh.landmarks;
        assert!(close(at(l.brow_mid), s.brow), "{:?}", at(l.brow_mid));
        assert!(close(at(mirror(l.brow_mid)), s.brow));
        assert!(close(at(l.upper_lip), s.lips), "{:?}", at(l.upper_lip));
        assert!(close(at(l.lower_lip), s.lips), "{:?}", at(l.lower_lip));
        assert!(close(at(Vec3::new(0.0, dims::TOP_Y, dims::Z_C)), s.hair));
        assert!(close(at(l.nose_tip), s.skin));
        assert!(close(at(l.chin), s.skin));
        assert!(
            close(at(l.forehead_mid), s.skin),
            "{:?}",
            at(l.forehead_mid)
        );
    }

    #[test]
    fn hairline_is_continuous_and_falls_to_the_nape() {
        let mut last = hairline(0.0);
        for k in 1..=360 {
            let h = hairline(k as f32 * 0.5);
            assert!((h - last).abs() < 0.003, "step at {} deg", k as f32 * 0.5);
            last = h;
        }
        assert!(hairline(0.0) > hairline(90.0) && hairline(90.0) > hairline(180.0));
        assert_eq!(hairline(-40.0), hairline(40.0));
    }
}
