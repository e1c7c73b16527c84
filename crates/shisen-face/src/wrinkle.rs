//! Expression wrinkles from skin compression (docs/model/face.md,
//! "Expression wrinkles and thickening", W1-W4).
//!
//! Skin is a thin, nearly inextensible sheet on soft tissue: where the
//! muscles shorten it by more than its resting tension takes up, it does
//! not shrink but buckles into lines across the direction of compression,
//! keeping its length (Cerda & Mahadevan 2003, Phys. Rev. Lett. 90:074302).
//! That one law gives the forehead's lines when frontalis lifts the brows,
//! the vertical frown lines when corrugator draws them together, the lines
//! across the nose's root when procerus and the nose wrinkler pull, and
//! crow's feet when the orbital orbicularis squeezes: no line is placed by
//! hand and none belongs to an emotion.
//!
//! [`measure`] compares the deformed mesh with its rest shape and gives
//! each vertex the slope of the lines that take up its compression along
//! the face's two axes, and their phases; the renderer bends the shading
//! normal with them per pixel (`render/shader.wgsl`), so the lines are
//! finer than the mesh. It also thickens the tissue under skin that lost
//! area (W4): thin tissue where it is, a cheek's fat over its compartment,
//! so the cheek rises in a smile and stays down along the nasolabial
//! fold's line; the renderer takes its normals from those positions.

use super::mesh::HeadMesh;
use glam::{IVec3, Mat2, Vec2, Vec3};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use shisen_gaze::util::math::{gauss, smoothstep};
use std::collections::HashMap;

/// How the skin buckles (user-editable, `skin` in the muscle database).
/// Its lengths are at most 3 cm: a value given in millimetres rather
/// than metres (6.0 for 6 mm) would make every vertex average the whole
/// face.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SkinParams {
    /// Spacing of the expression lines, m, 0-0.03. Our choice, 6 mm: a
    /// raised adult forehead shows four to six lines over its 4-5 cm,
    /// frown and nose lines are as close or closer. 0 turns wrinkles off;
    /// at most 3 cm (five times the default, wider than any line's
    /// spacing on a face).
    #[schemars(range(min = 0.0, max = 0.03))]
    pub wrinkle_spacing_m: f64,
    /// Compressive strain the skin takes up without buckling (living skin
    /// is stretched over it at rest, and the fat under it thickens and
    /// bulges), a fraction, 0-1 (a strain is at most the whole length).
    /// Our choice, 0.25: Waters' fields compress the skin by
    /// up to 0.75 near a muscle's bony end (procerus, corrugator); only the
    /// strongest compressions fold (frown, raised forehead, wrinkled nose),
    /// the pull of a smile or a weak expression leaves the skin smooth.
    #[schemars(range(min = 0.0, max = 1.0))]
    pub wrinkle_onset_strain: f64,
    /// Distance over which the skin spreads a linear muscle's pull, m,
    /// 0-0.03 (the standard deviation of S1's diffusion). Waters' cone (F2, F3)
    /// moves the skin with a slope that jumps at the cone's edge and
    /// converges it onto the bony end, which creased the skin along a V
    /// from the nose's root in every frown; skin and the fat under it
    /// carry a pull over about their own depth, 5-7 mm at the glabella and
    /// the nose's root (De Greef et al. 2006, Forensic Sci. Int. 159S:S126,
    /// soft-tissue depths by ultrasound). Our choice within that, 5 mm;
    /// 0 keeps Waters' fields exactly (the seed profile). At most 3 cm,
    /// four times the deepest soft tissue of the face.
    #[serde(default = "default_pull_spread")]
    #[schemars(range(min = 0.0, max = 0.03))]
    pub pull_spread_m: f64,
    /// How much the soft tissue thickens where the skin over it loses
    /// area (W4), as a fraction of its depth per unit area lost, 0-1. 1:
    /// the layer keeps its volume (it cannot gain more); 0 leaves the
    /// surface where the muscles put it (the seed profile).
    #[serde(default = "default_thickening")]
    #[schemars(range(min = 0.0, max = 1.0))]
    pub thickening: f64,
    /// Width over which a muscle's field fades out toward the edges of
    /// the domain it is confined to (the orbital orbicularis's), m, 0-0.03
    /// (the eye's opening, which the orbital part rings, is about 3 cm
    /// wide). Cut off there, the field stepped the skin along a line down the
    /// cheek beside the eye in every smile. Default 0.012 (our choice); 0
    /// keeps the thesis's hard edge (the seed profile).
    #[serde(default = "default_domain_fade")]
    #[schemars(range(min = 0.0, max = 0.03))]
    pub domain_fade_m: f64,
}

fn default_domain_fade() -> f64 {
    0.012
}

fn default_thickening() -> f64 {
    1.0
}

fn default_pull_spread() -> f64 {
    0.005
}

impl Default for SkinParams {
    fn default() -> Self {
        SkinParams {
            wrinkle_spacing_m: 0.006,
            wrinkle_onset_strain: 0.25,
            pull_spread_m: default_pull_spread(),
            thickening: default_thickening(),
            domain_fade_m: default_domain_fade(),
        }
    }
}

/// Rest-shape data the measurement needs, computed once per mesh.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct WrinkleBasis {
    /// Per triangle: its rest frame's two in-plane axes.
    axes: Vec<[Vec3; 2]>,
    /// Per triangle: inverse of the rest edge matrix in that frame.
    inv_edges: Vec<Mat2>,
    /// Per vertex `v`, `gather[start[v]..start[v + 1]]`: the triangles whose
    /// strain it averages, with weights summing to 1.
    start: Vec<u32>,
    gather: Vec<(u32, f32)>,
    /// Per vertex: the face's horizontal and vertical axes projected into
    /// the rest surface (unit), and how much of each the averaged
    /// triangles' planes hold (`t . P t`, 0 where the surface faces along
    /// the axis).
    tangents: Vec<[(Vec3, f32); 2]>,
    /// Per vertex: the depth of soft tissue that thickens under it (W4),
    /// m, times the skin's `thickening`; 0 on the folds' tethers.
    depth: Vec<f32>,
    /// Per vertex: the share of its compression W2 folds into lines, 0-1:
    /// 1 over thin tissue (which also thickens, W4), 0 over the cheeks'
    /// deep fat, which thickens instead.
    line_share: Vec<f32>,
    /// The two cheeks' fat compartments (W4).
    cheeks: [Vec<Cheek>; 2],
}

/// A vertex over a cheek's fat compartment (W4).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
struct Cheek {
    vertex: u32,
    /// The fat's volume under the vertex's share of skin at rest, per unit
    /// area lost, m^3 (times the skin's `thickening`).
    volume: f32,
    /// Thickness per unit volume gathered, 1/m^2.
    profile: f32,
}

impl WrinkleBasis {
    /// Precompute the rest frames of `mesh` and each vertex's averaging
    /// disk: the triangles within half a line spacing (at least the
    /// vertex's own), weighted by area and a smooth fall-off (W1).
    pub fn new(mesh: &HeadMesh, skin: &SkinParams) -> WrinkleBasis {
        let p = &mesh.positions;
        let mut b = WrinkleBasis::default();
        let mut area = Vec::with_capacity(mesh.triangles.len());
        let mut centroid = Vec::with_capacity(mesh.triangles.len());
        let mut adjacent = vec![Vec::new(); p.len()];
        let mut normal = Vec::with_capacity(mesh.triangles.len());
        for (ti, t) in mesh.triangles.iter().enumerate() {
            let [a, c1, c2] = t.map(|i| p[i as usize]);
            let (e1, e2) = (c1 - a, c2 - a);
            let n = e1.cross(e2);
            let t1 = e1.normalize_or(Vec3::X);
            let t2 = n.cross(t1).normalize_or(Vec3::Y);
            let edges = Mat2::from_cols(
                Vec2::new(e1.dot(t1), e1.dot(t2)),
                Vec2::new(e2.dot(t1), e2.dot(t2)),
            );
            let ok = edges.determinant().abs() > 1e-14;
            b.axes.push([t1, t2]);
            b.inv_edges
                .push(if ok { edges.inverse() } else { Mat2::ZERO });
            area.push(if ok { 0.5 * n.length() } else { 0.0 });
            centroid.push((a + c1 + c2) / 3.0);
            normal.push(n.normalize_or_zero());
            for &i in t {
                adjacent[i as usize].push(ti as u32);
            }
        }
        let half = 0.5 * skin.wrinkle_spacing_m.max(0.0) as f32;
        // Each vertex's disk reaches at least past its own triangles.
        let radius: Vec<f32> = adjacent
            .iter()
            .zip(p)
            .map(|(tris, &v)| {
                tris.iter()
                    .map(|&t| 1.01 * centroid[t as usize].distance(v))
                    .fold(half, f32::max)
            })
            .collect();
        let cell = radius.iter().copied().fold(1e-6, f32::max);
        let key = |q: Vec3| (q / cell).floor().as_ivec3();
        let mut grid: HashMap<IVec3, Vec<u32>> = HashMap::new();
        for (ti, c) in centroid.iter().enumerate() {
            grid.entry(key(*c)).or_default().push(ti as u32);
        }
        b.start.push(0);
        for (v, &r) in p.iter().zip(&radius) {
            let first = b.gather.len();
            let k = key(*v);
            let mut total = 0.0;
            for dz in -1..=1 {
                for dy in -1..=1 {
                    for dx in -1..=1 {
                        for &t in grid
                            .get(&(k + IVec3::new(dx, dy, dz)))
                            .into_iter()
                            .flatten()
                        {
                            let d2 = centroid[t as usize].distance_squared(*v) / (r * r);
                            if d2 < 1.0 && area[t as usize] > 0.0 {
                                let w = area[t as usize] * (1.0 - d2) * (1.0 - d2);
                                b.gather.push((t, w));
                                total += w;
                            }
                        }
                    }
                }
            }
            for g in &mut b.gather[first..] {
                g.1 /= total;
            }
            b.start.push(b.gather.len() as u32);
        }
        b.tangents = mesh
            .normals
            .iter()
            .enumerate()
            .map(|(v, &n)| {
                let gather = &b.gather[b.start[v] as usize..b.start[v + 1] as usize];
                [Vec3::X, Vec3::Y].map(|axis| {
                    let t = axis - n * n.dot(axis);
                    if t.length() < 0.3 {
                        return (Vec3::ZERO, 0.0);
                    }
                    let t = t.normalize();
                    let held: f32 = gather
                        .iter()
                        .map(|&(tri, w)| w * (1.0 - t.dot(normal[tri as usize]).powi(2)))
                        .sum();
                    (t, held)
                })
            })
            .collect();
        // Each vertex's share of the skin's area: a third of its triangles'.
        let mut vertex_area = vec![0.0f32; p.len()];
        for (t, a) in mesh.triangles.iter().zip(&area) {
            for &i in t {
                vertex_area[i as usize] += a / 3.0;
            }
        }
        let thickening = skin.thickening as f32;
        let l = &mesh.landmarks;
        let lids: std::collections::HashSet<u32> = mesh
            .lid_zone
            .iter()
            .flatten()
            .chain(mesh.rims.upper_lid.iter().flatten())
            .chain(mesh.rims.lower_lid.iter().flatten())
            .copied()
            .collect();
        for (i, (&v, &n)) in p.iter().zip(&mesh.normals).enumerate() {
            let (depth, cheek) = tissue(l, v, n);
            // The cheek's fat reaches beyond the compartment that bulges;
            // what the skin over it gathers goes to that compartment.
            let c = l.cheekbone.lerp(l.mouth_corner, 0.4);
            let d = Vec2::new(v.x.abs() - c.x.abs(), v.y - c.y).length() / CHEEK_RADIUS;
            let fat = if n.z > 0.2 {
                (1.0 - d * d).max(0.0).powi(2)
            } else {
                0.0
            };
            let (fat, profile) = match cheek {
                Some((_, profile)) => (1.0, profile),
                None => (fat, 0.0),
            };
            // The lids stay where the lid-clearance step put them, over
            // the eyeball; the lash line, lashes and caruncles sit on them.
            let lid = lids.contains(&(i as u32));
            b.depth.push(if lid {
                0.0
            } else {
                thickening * depth * (1.0 - fat)
            });
            let under = depth.max(CHEEK_DEPTH * fat);
            let folds = smoothstep(LINES_TO, LINES_FROM, under);
            // Without thickening, all of the compression folds (W1-W3).
            b.line_share.push(1.0 - thickening * (1.0 - folds));
            if fat > 0.0 {
                b.cheeks[usize::from(v.x < 0.0)].push(Cheek {
                    vertex: i as u32,
                    volume: thickening * SUPERFICIAL_FAT * fat * vertex_area[i],
                    profile,
                });
            }
        }
        // Normalise each compartment's profile to spread a unit volume.
        for cheek in &mut b.cheeks {
            let total: f32 = cheek
                .iter()
                .map(|c| c.profile * vertex_area[c.vertex as usize])
                .sum();
            for c in cheek.iter_mut() {
                c.profile /= total.max(1e-12);
            }
        }
        b
    }
}

/// Where a rest point `p` lies on the face's soft tissue (W4): the depth
/// that thickens under it, m, and, over a cheek's fat compartment, which
/// cheek and how much of the compartment's gathered volume it takes
/// (unnormalised).
///
/// Depths: about 5 mm over the forehead, temples and glabella, 9 mm under
/// the eyes (De Greef et al. 2006, Forensic Sci. Int. 159S:S126, adult
/// means by ultrasound). The cheek's fat (about 15 mm deep, the same
/// source) lies in compartments bounded by ligaments (Rohrich & Pessa
/// 2007, Plast. Reconstr. Surg. 119:2219); the nasolabial one ends
/// medially at the nasolabial fold's line, from beside the nose's wing to
/// beside the mouth's corner. What a smile gathers of a compartment's
/// skin thickens the whole compartment, most just beside that line (the
/// fat is held back by it), nothing on it: the fold is the bulge's edge.
fn tissue(l: &super::mesh::Landmarks, p: Vec3, n: Vec3) -> (f32, Option<(usize, f32)>) {
    let q = Vec2::new(p.x.abs(), p.y);
    let under_eye = if n.z > 0.2 {
        let d = Vec2::new(l.orbit_lower.x.abs(), l.orbit_lower.y).distance(q) / 0.015;
        (1.0 - d * d).max(0.0).powi(2)
    } else {
        0.0
    };
    let depth = 0.005 + 0.004 * under_eye;
    // Distance lateral of the fold's line (negative medial of it).
    let [a, b] = fold_line(l);
    let along = (b - a).normalize();
    let normal = Vec2::new(-along.y, along.x);
    let lateral = normal * normal.x.signum();
    let s = (q - a).dot(lateral);
    let t = (q - a).dot(along) / (b - a).length();
    let (top, bottom) = (l.orbit_lower.y - 0.006, l.mouth_corner.y - 0.012);
    let inside = s > 0.0
        && n.z > 0.2
        && (bottom..top).contains(&p.y)
        && q.x < l.cheekbone.x.abs() + 0.02
        && (-0.4..1.1).contains(&t);
    if !inside {
        return (depth, None);
    }
    let ends = smoothstep(0.0, 0.008, top - p.y) * smoothstep(0.0, 0.008, p.y - bottom);
    let profile = smoothstep(0.0, FOLD_RISE, s) * gauss(s, CHEEK_REACH) * ends;
    (0.0, Some((usize::from(p.x < 0.0), profile)))
}

/// The nasolabial fold's line on the left of the face, from beside the
/// nose's wing to beside and below the mouth's corner (x, y), m.
fn fold_line(l: &super::mesh::Landmarks) -> [Vec2; 2] {
    [
        Vec2::new(l.nostril_wing.x.abs() + 0.003, l.nostril_wing.y),
        Vec2::new(l.mouth_corner.x.abs() + 0.005, l.mouth_corner.y - 0.010),
    ]
}

/// Reach of the cheek's fat about its middle, m (our reading of the
/// cheek's extent: from the nasolabial fold to in front of the ear, from
/// under the eye to the jaw).
const CHEEK_RADIUS: f32 = 0.035;

/// Depth of the cheek's fat, m (De Greef et al. 2006: 14-18 mm over the
/// cheek's middle in adults; our round figure).
const CHEEK_DEPTH: f32 = 0.015;
/// Depth of the superficial fat over the cheek that the skin's pull
/// gathers, m: the fat above the face's fibrous layer (SMAS), which moves
/// with the skin; the deep fat under it stays on the bone (our choice,
/// about 6 mm of the cheek's 15).
const SUPERFICIAL_FAT: f32 = 0.006;

/// Over this width lateral of its line the fold rises to the bulge, m;
/// and the bulge falls off over `CHEEK_REACH` further out (our choices: an
/// adult's fold is a few millimetres wide, the nasolabial mound about
/// 1.5 cm).
const FOLD_RISE: f32 = 0.005;
const CHEEK_REACH: f32 = 0.011;

/// Skin over less soft tissue than `LINES_FROM` folds its whole
/// compression into lines (forehead, glabella, the nose's root, the eyes'
/// corners); over more than `LINES_TO` (the cheeks' fat pads) none, the
/// fat thickens instead (W4), m. A stiff film buckles into lines on a thin
/// compliant layer and not on a deep one that can take up the squeeze
/// (Cerda & Mahadevan 2003); the bounds are our choice between the depths
/// of the forehead (5 mm) and the cheeks (15 mm).
const LINES_FROM: f32 = 0.007;
const LINES_TO: f32 = 0.011;

/// Highest bulge of a cheek's compartment, m (our bound, two fifths of its
/// depth; a broad smile lifts the cheek's mound by a few millimetres).
const MAX_CHEEK_BULGE: f32 = 0.006;

/// Thickening is bounded at this fraction of the tissue's depth (W4): the
/// fat bulges by its own depth's part that the skin's pull gathers, no more.
const MAX_THICKENING: f32 = 0.35;

/// Per-vertex wrinkle data for the renderer: `[s_x, s_y, x / L, y / L]`,
/// the peak slopes (W2) of the lines taking up the skin's compression along
/// the face's horizontal (`x`) and vertical (`y`) axes, and their phases in
/// wavelengths of spacing `L` (W3). Zero slope where the skin along that
/// axis is not compressed past onset.
pub type WrinkleVertex = [f32; 4];

/// Compression of the skin along unit tangent `t` under the averaged Green
/// strain `e[..6]` and area ratio `e[6]` (W1): `1 - stretch` along `t`,
/// but no more than the area lost, `1 - J`. The triangles averaged lie in
/// slightly different planes, so `t` lies only partly in them: the strain
/// is divided by `held = t . P t`, the part of `t` their planes hold (a
/// uniform shrink then reads the same on a curved face as on a flat one).
/// A shear shortens one diagonal as much as it stretches the other and
/// keeps the area: the skin slides on its fat rather than folding.
fn compression(e: &[f32; 7], t: Vec3, held: f32) -> f32 {
    let et = Vec3::new(
        e[0] * t.x + e[3] * t.y + e[4] * t.z,
        e[3] * t.x + e[1] * t.y + e[5] * t.z,
        e[4] * t.x + e[5] * t.y + e[2] * t.z,
    );
    let along = 1.0 - (1.0 + 2.0 * t.dot(et) / held).max(0.0).sqrt();
    along.min(1.0 - e[6]) // (W1)
}

/// Slopes of the two families of lines from the compressions `cx`, `cy`
/// along the face's axes past the onset `c0` (W2). A sheet squeezed both
/// ways buckles across the stronger squeeze only, as far as it exceeds the
/// weaker; squeezed alike both ways it does not fold but thickens (the
/// fat under the skin bulges). Lines of spacing `L` and amplitude `A` keep
/// the skin's length when `(pi A / L)^2` equals the excess left, so their
/// peak slope `2 pi A / L` is `2 sqrt(excess)`, whatever the spacing.
pub fn buckle(cx: f32, cy: f32, c0: f32) -> [f32; 2] {
    let (ex, ey) = ((cx - c0).max(0.0), (cy - c0).max(0.0));
    [(ex - ey).max(0.0), (ey - ex).max(0.0)].map(|e| 2.0 * e.sqrt()) // (W2)
}

/// Measure the compression of `deformed` against the rest shape (W1),
/// write each vertex's wrinkle data into `out`, and thicken the tissue
/// under skin that lost area (W4): each vertex moves out along its rest
/// normal by its tissue depth times the area lost, at most
/// [`MAX_THICKENING`] of the depth. The cheeks bulge in a smile, the skin
/// under the eyes in a squint, the glabella between frown lines; the
/// normals taken from these positions shade the bulges.
///
/// The strain is resolved on the face's two axes rather than followed
/// along its principal direction: expression lines run across the
/// forehead, up the glabella, across the nose's root and out from the
/// eye corners, along these axes, and two fixed families of lines stay
/// straight and continuous where a principal direction would swing from
/// vertex to vertex and break them up.
pub fn measure(
    mesh: &HeadMesh,
    basis: &WrinkleBasis,
    skin: &SkinParams,
    deformed: &mut [Vec3],
    out: &mut Vec<WrinkleVertex>,
) {
    let n = mesh.positions.len();
    out.clear();
    out.resize(n, [0.0; 4]);
    let lines = skin.wrinkle_spacing_m > 0.0;
    if !lines && skin.thickening <= 0.0 {
        return;
    }
    // Green strain E = (F^T F - I) / 2 of each triangle, as a symmetric
    // 3x3 tensor [xx, yy, zz, xy, xz, yz], and its area ratio J.
    let strain: Vec<[f32; 7]> = mesh
        .triangles
        .iter()
        .enumerate()
        .map(|(ti, t)| {
            let [a, c1, c2] = t.map(|i| deformed[i as usize]);
            let inv = basis.inv_edges[ti];
            // Deformation gradient F (3x2): deformed edges times the
            // inverse rest edges; its columns are the images of the rest
            // frame's axes.
            let fa = (c1 - a) * inv.x_axis.x + (c2 - a) * inv.x_axis.y;
            let fb = (c1 - a) * inv.y_axis.x + (c2 - a) * inv.y_axis.y;
            let e00 = 0.5 * (fa.dot(fa) - 1.0);
            let e01 = 0.5 * fa.dot(fb);
            let e11 = 0.5 * (fb.dot(fb) - 1.0);
            let [t1, t2] = basis.axes[ti];
            let m = |i: usize, j: usize| {
                e00 * t1[i] * t1[j] + e01 * (t1[i] * t2[j] + t2[i] * t1[j]) + e11 * t2[i] * t2[j]
            };
            let j = fa.cross(fb).length();
            [m(0, 0), m(1, 1), m(2, 2), m(0, 1), m(0, 2), m(1, 2), j]
        })
        .collect();
    let spacing = skin.wrinkle_spacing_m as f32;
    let onset = skin.wrinkle_onset_strain as f32;
    // Each vertex's area lost (W4), for the cheeks' compartments.
    let mut lost = vec![0.0f32; n];
    for (i, out) in out.iter_mut().enumerate() {
        // W1: the strain averaged over the vertex's disk.
        let mut e = [0.0f32; 7];
        let range = basis.start[i] as usize..basis.start[i + 1] as usize;
        for &(t, w) in &basis.gather[range] {
            for (ek, sk) in e.iter_mut().zip(&strain[t as usize]) {
                *ek += w * sk;
            }
        }
        let along = |(t, held): (Vec3, f32)| {
            if held < 0.1 {
                0.0
            } else {
                compression(&e, t, held)
            }
        };
        let p = deformed[i];
        // W3: phases in wavelengths along each axis, of the skin's present
        // place (lines run straight across the squeeze that makes them).
        let [tx, ty] = basis.tangents[i];
        if lines {
            let share = basis.line_share[i];
            let [sx, sy] = buckle(along(tx), along(ty), onset);
            *out = [share * sx, share * sy, p.x / spacing, p.y / spacing];
        }
        lost[i] = (1.0 - e[6]).clamp(0.0, MAX_THICKENING);
        let depth = basis.depth[i];
        if depth > 0.0 && lost[i] > 0.0 {
            deformed[i] += mesh.normals[i] * (depth * lost[i]); // (W4)
        }
    }
    // W4 over the cheeks: the volume a compartment's skin gathers spreads
    // over the compartment.
    for cheek in &basis.cheeks {
        let gathered: f32 = cheek
            .iter()
            .map(|c| c.volume * lost[c.vertex as usize])
            .sum();
        if gathered > 0.0 {
            for c in cheek {
                let i = c.vertex as usize;
                deformed[i] += mesh.normals[i] * (gathered * c.profile).min(MAX_CHEEK_BULGE);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Face;
    use crate::mesh::MeshParams;
    use crate::params::FaceParams;

    fn face() -> Face {
        Face::new(MeshParams { rows: 32 }, FaceParams::default_params())
    }

    #[test]
    fn rest_and_rigid_motion_make_no_wrinkles() {
        let f = face();
        let skin = SkinParams::default();
        let mut out = Vec::new();
        measure(
            &f.mesh,
            &f.wrinkle_basis,
            &skin,
            &mut f.mesh.positions.clone(),
            &mut out,
        );
        assert!(out.iter().all(|w| w[0] == 0.0 && w[1] == 0.0));
        let r = glam::Quat::from_rotation_y(0.7) * glam::Quat::from_rotation_x(-0.3);
        let mut moved: Vec<Vec3> = f
            .mesh
            .positions
            .iter()
            .map(|&p| r * p + Vec3::new(0.1, -0.2, 0.3))
            .collect();
        measure(&f.mesh, &f.wrinkle_basis, &skin, &mut moved, &mut out);
        assert!(out.iter().all(|w| w[0] == 0.0 && w[1] == 0.0));
    }

    #[test]
    fn uniform_shrink_thickens_the_skin_without_lines() {
        // Shrinking the whole head by 35 % compresses every direction by
        // 0.35, past the 25 % onset both ways alike: no family dominates,
        // the skin bulges rather than folds (W2), everywhere on the head.
        let f = face();
        let skin = SkinParams::default();
        for scale in [0.65, 0.8] {
            let mut shrunk: Vec<Vec3> = f.mesh.positions.iter().map(|&p| scale * p).collect();
            let mut out = Vec::new();
            measure(&f.mesh, &f.wrinkle_basis, &skin, &mut shrunk, &mut out);
            let front = f.mesh.normals.iter().zip(&out).filter(|(n, _)| n.z > 0.8);
            for (_, w) in front {
                assert!(w[0] < 0.05 && w[1] < 0.05, "{scale}: {w:?}");
            }
        }
    }

    /// W4: a smile (AU 6 + 12) thickens the cheek by millimetres and
    /// leaves the forehead where it was; the nasolabial fold's tether
    /// stays down while the cheek beside it bulges, which is the fold.
    #[test]
    fn a_smile_bulges_the_cheek_over_the_fold() {
        let f = Face::new(MeshParams { rows: 64 }, FaceParams::default_params());
        let a =
            crate::emotion::emotion_activation(&f.params, crate::tables::Emotion::Happiness, 1.0);
        let mut pos = vec![Vec3::ZERO; f.mesh.positions.len()];
        f.rig.deform(&f.mesh, &a, &mut pos);
        let before = pos.clone();
        let mut out = Vec::new();
        measure(
            &f.mesh,
            &f.wrinkle_basis,
            &f.params.skin,
            &mut pos,
            &mut out,
        );
        let lift = |i: usize| (pos[i] - before[i]).dot(f.mesh.normals[i]);
        let l = &f.mesh.landmarks;
        let near = |c: Vec3| {
            (0..pos.len())
                .min_by(|&a, &b| {
                    let d = |i: usize| f.mesh.positions[i].distance_squared(c);
                    d(a).total_cmp(&d(b))
                })
                .unwrap()
        };
        let forehead = lift(near(l.forehead_mid));
        let [a, b] = fold_line(l);
        let mid = (a + b) / 2.0;
        let along = (b - a).normalize();
        let beside = mid + Vec2::new(-along.y, along.x).abs() * 0.008;
        let rest = &f.mesh.positions;
        let at = |c: Vec2, r: f32| -> Vec<f32> {
            (0..pos.len())
                .filter(|&i| rest[i].z > 0.0 && Vec2::new(rest[i].x, rest[i].y).distance(c) < r)
                .map(lift)
                .collect()
        };
        let fold = at(mid, 0.003).into_iter().fold(f32::INFINITY, f32::min);
        let cheek = at(beside, 0.004).into_iter().fold(0.0f32, f32::max);
        println!(
            "bulge: cheek {:.2} mm, fold {:.2} mm, forehead {:.2} mm",
            cheek * 1e3,
            fold * 1e3,
            forehead * 1e3
        );
        assert!(cheek > 0.0015, "cheek {cheek}");
        assert!(forehead.abs() < 1e-4, "forehead {forehead}");
        assert!(fold < 0.5 * cheek, "fold {fold} vs cheek {cheek}");
    }

    /// W2: the stronger squeeze's lines take up its excess over the
    /// weaker one's, with the length-keeping slope; below onset, nothing.
    #[test]
    fn the_stronger_squeeze_buckles_by_its_excess() {
        let want = |e: f32| 2.0 * e.sqrt();
        assert_eq!(buckle(0.35, 0.0, 0.25), [want(0.10), 0.0]);
        assert_eq!(buckle(0.0, 0.35, 0.25), [0.0, want(0.10)]);
        let [x, y] = buckle(0.45, 0.30, 0.25);
        assert!((x - want(0.15)).abs() < 1e-6 && y == 0.0);
        assert_eq!(buckle(0.4, 0.4, 0.25), [0.0, 0.0]);
        assert_eq!(buckle(0.2, 0.1, 0.25), [0.0, 0.0]);
    }

    #[test]
    fn one_way_squeeze_buckles_across_it() {
        // Squeezing vertically by 40 %: on the forehead the vertical family
        // (lines across the brow) takes it up, the horizontal one is idle.
        let f = face();
        let skin = SkinParams::default();
        let mut squeezed: Vec<Vec3> = f
            .mesh
            .positions
            .iter()
            .map(|&p| Vec3::new(p.x, 0.6 * p.y, p.z))
            .collect();
        let mut out = Vec::new();
        measure(&f.mesh, &f.wrinkle_basis, &skin, &mut squeezed, &mut out);
        let (i, p) = f
            .mesh
            .positions
            .iter()
            .enumerate()
            .filter(|(_, p)| p.x.abs() < 0.01 && p.z > 0.0)
            .min_by(|a, b| (a.1.y - 0.05).abs().total_cmp(&(b.1.y - 0.05).abs()))
            .unwrap();
        let w = out[i];
        assert_eq!(w[0], 0.0);
        assert!(w[1] > 2.0 * (0.35f32 - 0.25).sqrt(), "{w:?}");
        // W3: the phase is of the skin's present place.
        assert!((w[3] - 0.6 * p.y / 0.006).abs() < 1e-3);
    }
}
