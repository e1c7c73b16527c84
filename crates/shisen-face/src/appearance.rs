//! What the skin looks like where it is not plain skin: hair, brows, lips,
//! the lash line, a flush over the cheeks. Each is a colour painted on the
//! rest mesh's vertices from its landmarks, once, so it moves with every
//! muscle as the skin carrying it does: a brow painted on the skin over the
//! brow ridge rises with frontalis and knits with corrugator, exactly as
//! far as the skin moves (docs/model/face.md "Appearance").
//!
//! Colours are linear RGB. The skin's own colour (tone, flush, lash line)
//! is a colour per vertex; the three regions with sharp borders (lips,
//! brows, hair) are given as signed distances per vertex instead
//! ([`Regions`]), which the renderer interpolates and thresholds per pixel:
//! a border then runs straight through the triangles, sharp and
//! antialiased, at any mesh resolution, where interpolated colours would
//! blur it over a triangle and step it from vertex to vertex.

use glam::{Vec2, Vec3};

use shisen_gaze::util::math::smoothstep;

use super::mesh::{HeadMesh, Landmarks, dims};

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
    /// The inside of the mouth.
    pub inside: [f32; 3],
    /// A shaved beard's shadow over the jaw, chin and upper lip (the
    /// skin's colour through the stubble's dark roots).
    pub stubble: [f32; 3],
    /// The thin, darker skin under the eyes.
    pub under_eye: [f32; 3],
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
        lips: [0.47, 0.20, 0.18],
        lashes: [0.02, 0.015, 0.015],
        flush: [0.66, 0.30, 0.26],
        inside: [0.10, 0.015, 0.02],
        stubble: [0.48, 0.34, 0.28],
        under_eye: [0.44, 0.27, 0.24],
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

/// Half-width of each region's soft border, m: the vermilion's border is
/// sharp, a brow's hairs thin out over a millimetre or so, the hairline
/// over more.
const SOFT: [f32; 3] = [0.0012, 0.0018, 0.0015];

/// A back face of the skin (the head's inside) within this far of the lips
/// is seen through the parted lips and drawn as the mouth's inside, m (our
/// choice: past the mouth's corners, short of the eyes).
const MOUTH_INSIDE_REACH: f32 = 0.024;

/// `MOUTH_INSIDE_REACH` as the lips' painted signed distance (the first
/// of [`Regions`], in their soft border's units): the renderer draws a
/// back face whose value exceeds it in the mouth's inside colour.
pub const MOUTH_INSIDE_LIMIT: f32 = -MOUTH_INSIDE_REACH / SOFT[0];

/// The lips' colour reaches at least this far from the mouth's opening, m:
/// the opening's edge is lip all round, even at the corners, where the
/// vermilion's band narrows to nothing but a wide-open mouth stretches
/// the skin beside it into the opening.
pub const MOUTH_EDGE: f32 = 0.0025;

/// Distance from `p` to the nearest of `points`.
fn distance(p: Vec3, points: &[Vec3]) -> f32 {
    points
        .iter()
        .map(|q| q.distance(p))
        .fold(f32::MAX, f32::min)
}

/// Height above the hairline of a vertex with painted borders `r`, m
/// (negative below it).
pub fn hair_height(r: &Regions) -> f32 {
    r[2] * SOFT[2]
}

/// A point's place against the painted borders, in units of each
/// border's soft half-width: the signed distance inside the lips, the
/// height above the brow's middle line, the height above the hairline,
/// and the brow's half-width. The renderer (`render/shader.wgsl`) covers
/// the lips where the first is positive, the brow where
/// `half - |height|` is, the hair where the third is, each with
/// `smoothstep(-1, 1, u)` widened to a pixel where a pixel is wider.
pub type Regions = [f32; 4];

fn mix(a: [f32; 3], b: [f32; 3], t: f32) -> [f32; 3] {
    [0, 1, 2].map(|k| a[k] + (b[k] - a[k]) * t)
}

/// A smooth curve through the points `(x, y)` (x increasing) at `x`:
/// cubic Hermite, each inner point's slope that of the chord between its
/// neighbours, the ends' that of their own chord, or `start_slope` at the
/// first point; clamped to the ends' segments outside.
fn smooth_curve(points: &[(f32, f32)], x: f32, start_slope: Option<f32>) -> f32 {
    let n = points.len();
    let k = points.windows(2).position(|w| x <= w[1].0).unwrap_or(n - 2);
    let slope = |i: usize| match (i, start_slope) {
        (0, Some(m)) => m,
        _ => {
            let (u, v) = (points[i.saturating_sub(1)], points[(i + 1).min(n - 1)]);
            (v.1 - u.1) / (v.0 - u.0)
        }
    };
    let ((x0, y0), (x1, y1)) = (points[k], points[k + 1]);
    let dx = x1 - x0;
    let f = ((x - x0) / dx).clamp(0.0, 1.0);
    let (f2, f3) = (f * f, f * f * f);
    y0 * (2.0 * f3 - 3.0 * f2 + 1.0)
        + slope(k) * dx * (f3 - 2.0 * f2 + f)
        + y1 * (3.0 * f2 - 2.0 * f3)
        + slope(k + 1) * dx * (f3 - f2)
}

/// The hairline's height at an azimuth: level where it crosses the
/// midline (no corner there), smooth all round.
fn hairline(azimuth_deg: f32) -> f32 {
    smooth_curve(&HAIRLINE, azimuth_deg.abs().min(180.0), Some(0.0))
}

/// Signed height of the point above the hairline, m.
fn hair(p: Vec3) -> f32 {
    let azimuth = p.x.atan2(p.z - dims::Z_C).to_degrees();
    p.y - hairline(azimuth)
}

/// Where the point is across the brow on its side, m: its height above the
/// brow's middle line, and the brow's half-width there (negative past the
/// brow's ends and behind the face); the point is inside the brow where
/// `|height| < half`. The middle line runs through the brow landmarks as a
/// height over the distance from the face's midline, so both values are
/// smooth over the whole face: the renderer interpolates them linearly
/// and takes the height's magnitude per pixel, and the band stays whole
/// even where it passes between the vertices of a coarse mesh. The brow
/// is thickest at its head and tapers to the tail; `min_half` (half the
/// mesh's spacing) keeps it from thinning below what that mesh can show.
fn brow(p: Vec3, l: &Landmarks, min_half: f32) -> (f32, f32) {
    let line = [
        l.brow_inner - Vec3::new(0.002, 0.0, 0.0),
        l.brow_inner + Vec3::new(0.003, 0.001, 0.0),
        l.brow_mid + Vec3::new(0.0, 0.001, 0.0),
        l.brow_outer,
        l.brow_outer + Vec3::new(0.006, -0.005, 0.0),
    ];
    let (x0, x1) = (line[0].x, line[4].x);
    let x = p.x.abs();
    // A smooth arch through the points: a brow has no corner at its peak.
    let height = p.y - smooth_curve(&line.map(|q| (q.x, q.y)), x, None);
    let t = ((x - x0) / (x1 - x0)).clamp(0.0, 1.0);
    // Half-width at the head, tapering toward the tail.
    let widest = 0.0058;
    // The head ends bluntly, an elliptic cap over its last 3 mm (a brow's
    // head is its broadest, squarest part); the tail tapers to a point.
    let d = ((x - x0 + 0.002) / 0.003).clamp(0.0, 1.0);
    let head = widest * (d * (2.0 - d)).sqrt() - (x0 - 0.002 - x).max(0.0);
    let half = (widest - 0.0032 * t)
        .max(min_half)
        .min(head)
        .min(x1 - x + 0.0015)
        // Only the front of the face (not the inside of the lid shells).
        .min(p.z - l.brow_outer.z + 0.015);
    (height, half)
}

/// The lips' taper toward the corners: the band's height goes as
/// `(1 - u^2)^LIP_TAPER` over the fraction `u` of the half-width.
pub const LIP_TAPER: f32 = 0.4;
/// The Cupid's bow: a rise of the upper border by this fraction, centred
/// this far out (fraction of the half-width), this wide.
pub const LIP_BOW: [f32; 3] = [0.18, 0.28, 0.12];
/// The philtrum's dip in the upper border at the midline: depth, width
/// (fractions).
pub const LIP_DIP: [f32; 2] = [0.15, 0.08];
/// The soft half-width of the vermilion border, m (the lips' entry of
/// the regions' soft borders).
pub const LIP_SOFT: f32 = SOFT[0];

/// Where the lips' vermilion lies on a head, from its landmarks (m, the
/// head's frame): the mouth's half-width and line, how far the upper and
/// lower borders stand from that line at the middle, and the depth in
/// front of which the face is (the head's back at the same height is not
/// lip). The renderer draws the border per pixel from the same numbers
/// (`fs_face` in `render/shader.wgsl`, which mirrors [`LipShape::band`]
/// and [`LipShape::inside`]), so it is a smooth curve at any mesh
/// resolution; the per-vertex regions serve everything else.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LipShape {
    /// Half the mouth's width.
    pub half_w: f32,
    /// The mouth line's height.
    pub mouth_y: f32,
    /// The upper border's height above the line at the middle.
    pub top: f32,
    /// The lower border's depth below the line at the middle.
    pub bottom: f32,
    /// Only points in front of this depth are lip.
    pub front_z: f32,
}

impl LipShape {
    /// The lips of a head with landmarks `l`.
    pub fn of(l: &Landmarks) -> LipShape {
        let mouth_y = l.mouth_centre.y;
        LipShape {
            half_w: l.mouth_corner.x,
            mouth_y,
            top: l.upper_lip.y - mouth_y + 0.0025,
            bottom: mouth_y - l.lower_lip.y + 0.0035,
            front_z: l.mouth_corner.z - 0.012,
        }
    }

    /// Signed distance of the point inside the vermilion's band, m: above
    /// and below the mouth line, widest at the middle (with a Cupid's bow)
    /// and closing at the corners.
    pub fn band(&self, p: Vec3) -> f32 {
        let u = (p.x / self.half_w).abs().min(1.0);
        let taper = (1.0 - u * u).powf(LIP_TAPER);
        let [bow_a, bow_u, bow_w] = LIP_BOW;
        let [dip_a, dip_w] = LIP_DIP;
        let bow = 1.0 + bow_a * (-((u - bow_u) / bow_w).powi(2)).exp()
            - dip_a * (-(u / dip_w).powi(2)).exp();
        let top = self.mouth_y + self.top * taper * bow;
        let bottom = self.mouth_y - self.bottom * taper;
        (top - p.y)
            .min(p.y - bottom)
            .min(self.half_w - p.x.abs())
            .min(p.z - self.front_z)
    }

    /// Signed distance inside the lips' colour, m: the band, and within
    /// [`MOUTH_EDGE`] of the mouth's opening all round, on the front of
    /// the face. The opening is taken as the mouth line between the
    /// corners (the renderer's per-pixel border); the per-vertex regions
    /// ([`paint`]) measure to the lip rims' vertices instead, which lie on
    /// that line at rest on a generated head.
    pub fn inside(&self, p: Vec3) -> f32 {
        let to_line = Vec2::new((p.x.abs() - self.half_w).max(0.0), p.y - self.mouth_y).length();
        self.band(p)
            .max((MOUTH_EDGE - to_line).min(p.z - self.front_z))
    }
}

/// Signed distance of the point inside the lips' vermilion band, m.
fn lips(p: Vec3, l: &Landmarks) -> f32 {
    LipShape::of(l).band(p)
}

/// How dark the lash line is at the point (0..1): within a millimetre or
/// two of a lid rim, the upper one darker.
fn lashes(p: Vec3, upper: &[Vec3], lower: &[Vec3]) -> f32 {
    let near = |rim: &[Vec3], width: f32| smoothstep(width, width * 0.4, distance(p, rim));
    near(upper, 0.0022).max(0.45 * near(lower, 0.0013))
}

/// The flush over each cheekbone (0..1).
fn flush(p: Vec3, l: &Landmarks) -> f32 {
    let c = l.cheekbone + Vec3::new(-0.012, -0.012, 0.006);
    let d = Vec2::new(p.x.abs() - c.x, p.y - c.y).length();
    0.35 * smoothstep(0.024, 0.0, d) * smoothstep(-0.03, 0.0, p.z - c.z)
}

/// How red the skin is over the nose's tip and wings (0..1): the nose is
/// among the face's reddest parts, with the cheeks (Yamamoto et al. 2008,
/// Skin Res. Technol. 14:26, a* by region).
fn nose_red(p: Vec3, l: &Landmarks) -> f32 {
    let tip = smoothstep(0.014, 0.0, p.distance(l.nose_tip));
    let wing = l.nostril_wing;
    let wing = smoothstep(0.009, 0.0, Vec3::new(p.x.abs(), p.y, p.z).distance(wing));
    0.4 * tip.max(wing)
}

/// How much of the darker skin under an eye shows at the point (0..1): a
/// crescent from the lower lid down to the lid-cheek junction, about
/// 1.5 cm (the infraorbital hollow, where the skin is thin).
fn under_eye(p: Vec3, l: &Landmarks) -> f32 {
    let c = l.lower_lid_mid;
    let across = (p.x.abs() - c.x.abs()) / 0.017;
    let down = (c.y - p.y) / 0.016;
    if down < -0.1 {
        return 0.0;
    }
    let r = (across * across + (down - 0.35) * (down - 0.35) / 0.45).sqrt();
    0.55 * smoothstep(1.0, 0.4, r) * smoothstep(-0.1, 0.15, down)
}

/// How much of a shaved beard's shadow shows at the point (0..1): over
/// the upper lip below the nose, the chin and the jaw, up the lower cheek
/// to a line from the nose's base to the sideburn, fading into the
/// neck (our reading of the male beard's extent); the lips are painted
/// over it.
fn stubble(p: Vec3, l: &Landmarks) -> f32 {
    let x = p.x.abs();
    let (a, b) = (l.nostril_wing, l.ear_lobe);
    let t = ((x - a.x) / (b.x - a.x)).clamp(0.0, 1.0);
    // From just under the nose's base up to the sideburn at mid-ear.
    let cheek_line = a.y + 0.002 + (b.y + 0.028 - a.y) * t;
    let below = smoothstep(0.0, 0.008, cheek_line - p.y);
    let neck = smoothstep(l.jaw_lower_edge.y - 0.035, l.jaw_lower_edge.y - 0.005, p.y);
    // Only on the face and the jaw's side, fading toward the back of the
    // head (more than 1-4 cm behind the mouth's corners).
    let front = smoothstep(-0.04, -0.01, p.z - l.mouth_corner.z);
    0.4 * below * neck * front
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

/// The painted rest mesh.
#[derive(Clone, Debug, PartialEq)]
pub struct Paint {
    /// Skin colour per vertex (tone, flush, lash line, stubble's shadow,
    /// under-eye), linear RGB; alpha: the stubble's density (0-1), whose
    /// cut hairs the renderer draws per pixel.
    pub colours: Vec<[f32; 4]>,
    /// Borders of the lips, brows and hair per vertex ([`Regions`]).
    pub regions: Vec<Regions>,
}

/// Paint the rest mesh.
pub fn paint(mesh: &HeadMesh, style: &FaceStyle) -> Paint {
    let l = &mesh.landmarks;
    let rim = |loops: &[Vec<u32>; 2]| -> Vec<Vec3> {
        loops
            .iter()
            .flatten()
            .map(|&i| mesh.positions[i as usize])
            .collect()
    };
    let (upper, lower) = (rim(&mesh.rims.upper_lid), rim(&mesh.rims.lower_lid));
    let mouth: Vec<Vec3> = [&mesh.rims.upper_lip, &mesh.rims.lower_lip]
        .into_iter()
        .flatten()
        .map(|&i| mesh.positions[i as usize])
        .collect();
    let spacing = edge_length(mesh);
    let colours = mesh
        .positions
        .iter()
        .map(|&p| {
            let c = mix(style.skin, style.flush, flush(p, l).max(nose_red(p, l)));
            let beard = stubble(p, l);
            let c = mix(c, style.stubble, beard);
            let c = mix(c, style.under_eye, under_eye(p, l));
            let c = mix(c, style.lashes, lashes(p, &upper, &lower));
            [c[0], c[1], c[2], beard]
        })
        .collect();
    let regions = mesh
        .positions
        .iter()
        .zip(spacing)
        .map(|(&p, spacing)| {
            let (height, half) = brow(p, l, 0.5 * spacing);
            [
                lips(p, l).max(MOUTH_EDGE - distance(p, &mouth)) / SOFT[0],
                height / SOFT[1],
                hair(p) / SOFT[2],
                half / SOFT[1],
            ]
        })
        .collect();
    Paint { colours, regions }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{MeshParams, mirror};

    /// The lips' colour as the renderer draws it per pixel: on both lips
    /// and along the opening's edge to the corners, not beyond the
    /// corners, not on the chin or under the nose, and not on the back of
    /// the head at the mouth's height (the opening's edge term is for the
    /// face's front only).
    #[test]
    fn lip_shape_covers_the_lips_and_only_the_front() {
        let mesh = HeadMesh::generate(MeshParams { rows: 32 });
        let l = &mesh.landmarks;
        let lips = LipShape::of(l);
        let z = l.mouth_corner.z;
        for p in [l.upper_lip, l.lower_lip] {
            assert!(lips.inside(p) > 0.0, "{p}");
        }
        // The opening's edge, at the middle and near a corner.
        let edge = Vec3::new(0.9 * lips.half_w, lips.mouth_y, z + 0.002);
        assert!(lips.inside(edge) > 0.0, "{edge}");
        assert!(lips.inside(l.mouth_centre + Vec3::Z * 0.01) > 0.0);
        for p in [
            Vec3::new(lips.half_w + 0.006, lips.mouth_y, z),
            l.chin,
            Vec3::new(0.0, lips.mouth_y + lips.top + 0.006, z + 0.01),
            Vec3::new(0.0, lips.mouth_y, dims::Z_C - 0.07),
        ] {
            assert!(lips.inside(p) < 0.0, "{p} is not lip");
        }
    }

    /// Each region lands where its landmark says, and only there: each
    /// landmark is inside its region (and no other); the nose tip, the
    /// chin and the forehead are in none. And `paint` gives every vertex
    /// exactly these values, in soft half-widths.
    #[test]
    fn regions_sit_on_their_landmarks() {
        let mesh = HeadMesh::generate(MeshParams { rows: 48 });
        let l = &mesh.landmarks;
        let at = |p: Vec3| {
            let (height, half) = brow(p, l, 0.0);
            [lips(p, l) > 0.0, height.abs() < half, hair(p) > 0.0]
        };
        let (lips_, brow_, hair_) = (
            [true, false, false],
            [false, true, false],
            [false, false, true],
        );
        assert_eq!(at(l.brow_mid), brow_);
        assert_eq!(at(mirror(l.brow_mid)), brow_);
        assert_eq!(at(l.upper_lip), lips_);
        assert_eq!(at(l.lower_lip), lips_);
        assert_eq!(at(Vec3::new(0.0, dims::TOP_Y, dims::Z_C)), hair_);
        for skin in [l.nose_tip, l.chin, l.forehead_mid] {
            assert_eq!(at(skin), [false; 3], "{skin}");
        }
        let painted = paint(&mesh, &FaceStyle::default());
        let spacing = edge_length(&mesh);
        for (i, &p) in mesh.positions.iter().enumerate().step_by(97) {
            let (height, half) = brow(p, l, 0.5 * spacing[i]);
            let r = painted.regions[i];
            assert!((r[1] * SOFT[1] - height).abs() < 1e-6 && (r[3] * SOFT[1] - half).abs() < 1e-6);
            assert!((r[2] * SOFT[2] - hair(p)).abs() < 1e-6);
            assert!(r[0] * SOFT[0] >= lips(p, l) - 1e-6);
        }
    }

    /// Across the whole width of each brow, on the coarse mesh, some vertex
    /// in every column of the mesh is inside the brow: the band never
    /// breaks into dashes. Between the brows and past their tails is
    /// outside.
    #[test]
    fn brows_are_unbroken_on_a_coarse_mesh() {
        let mesh = HeadMesh::generate(MeshParams { rows: 32 });
        let l = &mesh.landmarks;
        let spacing = edge_length(&mesh);
        for k in 0..=20 {
            let x = l.brow_inner.x + (l.brow_outer.x - l.brow_inner.x) * k as f32 / 20.0;
            let inside = mesh.positions.iter().zip(&spacing).any(|(v, s)| {
                let (height, half) = brow(*v, l, 0.5 * s);
                (v.x - x).abs() < 0.5 * s && v.z > 0.0 && height.abs() < half
            });
            assert!(inside, "x {x}");
        }
        for p in [l.glabella, l.brow_outer + Vec3::new(0.015, 0.0, 0.0)] {
            assert!(brow(p, l, 0.0).1 < 0.0, "{p}");
        }
    }

    /// The skin's tone varies as a face's does: a beard's shadow on the
    /// chin, the jaw and over the upper lip, not on the forehead, the nose
    /// or the cheekbones; the nose's tip redder than the forehead; the
    /// skin under the eyes darker than the cheek below it.
    #[test]
    fn the_skin_tone_varies_where_a_face_does() {
        let mesh = HeadMesh::generate(MeshParams { rows: 48 });
        let l = &mesh.landmarks;
        let upper_lip_skin = (l.nose_tip + l.upper_lip) / 2.0 - Vec3::Z * 0.004;
        for p in [l.chin, upper_lip_skin, l.jaw_outer] {
            assert!(stubble(p, l) > 0.2, "no stubble at {p}: {}", stubble(p, l));
        }
        for p in [l.forehead_mid, l.nose_tip, l.cheekbone, l.glabella] {
            assert!(stubble(p, l) < 0.05, "stubble at {p}: {}", stubble(p, l));
        }
        assert!(nose_red(l.nose_tip, l) > 0.3 && nose_red(l.forehead_mid, l) == 0.0);
        let below = l.lower_lid_mid - Vec3::Y * 0.006;
        assert!(under_eye(below, l) > 0.3, "{}", under_eye(below, l));
        assert_eq!(under_eye(l.cheekbone - Vec3::Y * 0.03, l), 0.0);
        assert_eq!(under_eye(l.upper_lid_mid, l), 0.0);
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
