//! Procedural head mesh (face.md 8 proportions), deterministic, resolution
//! a parameter.
//!
//! Construction: a latitude/longitude grid (rows of constant height, columns
//! denser at the front) over a head whose horizontal sections are
//! superellipses (half-width, front and back depth interpolated over height,
//! rounded into poles at the top of the head and under the jaw). The front
//! half is a height field over (x, y) to which smooth analytic features are
//! added (brow ridge, nose ridge and alar wings, cheeks, lips, chin); ears
//! are bumps along x. Each eye opening and the mouth is a slit cut along one
//! grid row (its interior vertices duplicated: originals form the upper rim,
//! copies the lower rim, the two end vertices are the shared corners), then
//! opened by a smooth vertical warp. Around each eye the surface blends into
//! an ellipsoidal lid shell that encloses the eyeball (11 mm radius) with
//! margin, so the lids lie over it. Two grid rows are placed exactly at the
//! eye-centre height and the mouth line.
//!
//! Frame: metres, +Z forward, +Y up, +X the agent's left, origin between
//! the eyeball centres (at (+/-0.03095, 0, 0)).

use super::muscle::lid_margin;
use glam::Vec3;
use shisen_gaze::util::math::{gauss, hermite, smoothstep};
use std::collections::HashMap;

/// Head proportions used by the generator (metres; face.md 8).
pub mod dims {
    use shisen_gaze::anatomy::eye;
    /// Half the interpupillary distance.
    pub const EYE_X: f32 = (eye::IPD / 2.0) as f32;
    /// Eyeball radius.
    pub const EYEBALL_R: f32 = eye::RADIUS as f32;
    /// Top of the head above the eye centres.
    pub const TOP_Y: f32 = eye::BELOW_TOP as f32;
    /// Bottom pole (under the jaw).
    pub const BOTTOM_Y: f32 = -0.14;
    /// Nasion height.
    pub const NASION_Y: f32 = 0.008;
    /// Mouth line (nasion - 75 mm).
    pub const MOUTH_Y: f32 = NASION_Y - 0.075;
    /// Nose base (nasion - 54 mm).
    pub const NOSE_BASE_Y: f32 = NASION_Y - 0.054;
    /// Chin (nasion - 120 mm).
    pub const CHIN_Y: f32 = NASION_Y - 0.120;
    /// Half the mouth width (52 mm).
    pub const MOUTH_HALF_W: f32 = 0.026;
    /// Half the eye fissure length (31 mm).
    pub const FISSURE_HALF_W: f32 = 0.0155;
    /// Half the alar width (35 mm).
    pub const ALAR_HALF_W: f32 = 0.0175;
    /// Section centre depth.
    pub const Z_C: f32 = -0.075;
    /// Upper lid rim height above the eye centre at rest.
    pub const UPPER_LID_H: f32 = 0.0046;
    /// Lower lid rim depth below the eye centre at rest.
    pub const LOWER_LID_H: f32 = 0.0042;
    /// Lid shell semi-axes (x, y, z) around each eye centre; all exceed the
    /// eyeball radius, so the shell encloses the eyeball.
    pub const SHELL: [f32; 3] = [0.018, 0.015, 0.0125];
}
use dims::*;

/// Generation parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshParams {
    /// Number of latitude bands; columns are `2 * rows`. Vertices ~ 2 rows^2
    /// (rows = 32: ~2k, rows = 160: ~51k). At least 24.
    pub rows: usize,
}

/// Named landmarks produced by generation. Bilateral landmarks are given for
/// the agent's left (+X); mirror x for the right ([`mirror`]).
#[derive(Clone, Debug, PartialEq)]
#[allow(missing_docs)]
pub struct Landmarks {
    pub nasion: Vec3,
    pub glabella: Vec3,
    pub nasal_bone: Vec3,
    pub nose_tip: Vec3,
    pub nostril_wing: Vec3,
    pub brow_inner: Vec3,
    pub brow_mid: Vec3,
    pub brow_outer: Vec3,
    pub forehead_inner: Vec3,
    pub forehead_mid: Vec3,
    pub forehead_outer: Vec3,
    pub orbit_inner_upper: Vec3,
    pub orbit_inner_lower: Vec3,
    pub orbit_lower: Vec3,
    pub cheekbone: Vec3,
    pub face_side: Vec3,
    pub eye_inner_corner: Vec3,
    pub eye_outer_corner: Vec3,
    pub upper_lid_mid: Vec3,
    pub lower_lid_mid: Vec3,
    /// Centre of the left eyeball.
    pub eye_centre: Vec3,
    pub mouth_corner: Vec3,
    pub mouth_centre: Vec3,
    pub upper_lip: Vec3,
    pub lower_lip: Vec3,
    pub jaw_lower_edge: Vec3,
    pub jaw_outer: Vec3,
    pub chin: Vec3,
    pub jaw_pivot: Vec3,
    pub ear_lobe: Vec3,
    /// Midline to the jaw's outer edge (F7's L).
    pub jaw_half_width: f32,
}

/// Mirror a left landmark to the right side.
pub fn mirror(p: Vec3) -> Vec3 {
    Vec3::new(-p.x, p.y, p.z)
}

/// Vertex index loops along the openings (ordered from corner to corner,
/// both ends being the shared corner vertices). Index 0 = left (+X) eye.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Rims {
    /// Upper lid rim per eye.
    pub upper_lid: [Vec<u32>; 2],
    /// Lower lid rim per eye.
    pub lower_lid: [Vec<u32>; 2],
    /// Upper lip rim.
    pub upper_lip: Vec<u32>,
    /// Lower lip rim.
    pub lower_lip: Vec<u32>,
}

/// A generated head mesh.
#[derive(Clone, Debug, PartialEq)]
pub struct HeadMesh {
    /// Rest positions.
    pub positions: Vec<Vec3>,
    /// Unit vertex normals (area weighted).
    pub normals: Vec<Vec3>,
    /// Counter-clockwise (outward) triangles.
    pub triangles: Vec<[u32; 3]>,
    /// A middle level of detail over the same vertices: every other row
    /// and column of the grid away from the eyes and brows, the mouth,
    /// the nose and the ears' bumps, which keep the fine grid (their
    /// openings, lids, lips and painted borders hang on it, and the grid
    /// bends most there), the two meeting without cracks; about half the
    /// triangles. An imported mesh's own triangles.
    pub medium: Vec<[u32; 3]>,
    /// How far the middle level departs from the fine one at rest: the
    /// largest distance of a vertex it skips from the point of its
    /// surface that stands for it, metres (0 for an imported mesh). Its
    /// coarse blocks (cheeks, jaw, scalp) deform with the face, and the
    /// paint interpolated over them is not counted.
    pub medium_error: f32,
    /// A coarse level of detail over the same vertices: the head's closed
    /// shell (its openings spanned) through every third row and column of
    /// the grid, about a ninth of the triangles; for what needs the head's
    /// shape but not its detail, such as casting a shadow. An imported
    /// mesh's own triangles.
    pub coarse: Vec<[u32; 3]>,
    /// Landmarks.
    pub landmarks: Landmarks,
    /// Opening rims.
    pub rims: Rims,
    /// Vertices of each eye's lid shell zone (kept outside the eyeball).
    pub lid_zone: [Vec<u32>; 2],
}

/// Interpolation ([`hermite`]) through knots given with y descending;
/// constant outside.
fn table(knots: &[(f32, f32)], y: f32) -> f32 {
    hermite(knots.len(), |i| knots[i], y)
}

const EXPO: f32 = 2.4; // section superellipse exponent

/// Rounding into the poles.
fn dome(y: f32) -> f32 {
    let top = if y > 0.06 {
        (1.0 - ((y - 0.06) / (TOP_Y - 0.06)).powi(2))
            .max(0.0)
            .sqrt()
    } else {
        1.0
    };
    let bot = if y < -0.10 {
        (1.0 - ((y + 0.10) / (-0.10 - BOTTOM_Y)).powi(2))
            .max(0.0)
            .sqrt()
    } else {
        1.0
    };
    top * bot
}

/// Section half-width, front depth, back depth at height y.
fn section(y: f32) -> (f32, f32, f32) {
    let a = table(
        &[
            (TOP_Y, 0.070),
            (0.10, 0.073),
            (0.06, 0.075),
            (0.02, 0.076),
            (-0.02, 0.072),
            (-0.06, 0.064),
            (-0.09, 0.053),
            (-0.112, 0.046),
            (BOTTOM_Y, 0.040),
        ],
        y,
    );
    let f = table(
        &[
            (TOP_Y, 0.085),
            (0.10, 0.085),
            (0.06, 0.087),
            (0.02, 0.095),
            (-0.02, 0.091),
            (-0.06, 0.093),
            (-0.09, 0.089),
            (-0.112, 0.080),
            (BOTTOM_Y, 0.070),
        ],
        y,
    );
    let b = table(
        &[
            (TOP_Y, 0.095),
            (0.06, 0.095),
            (0.02, 0.095),
            (-0.02, 0.090),
            (-0.06, 0.075),
            (-0.09, 0.062),
            (-0.112, 0.055),
            (BOTTOM_Y, 0.050),
        ],
        y,
    );
    let d = dome(y);
    (a * d, f * d, b * d)
}

/// Which side of a slit a vertex is on.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum SlitSide {
    Upper,
    Lower,
}

/// Vertical opening warp for a point (x, y) on the given side (eyes and mouth).
fn opening_warp(x: f32, y: f32, side: SlitSide, corners: &[(f32, f32); 3]) -> f32 {
    let mut dy = 0.0;
    // Eyes: slit at y = 0.
    for (k, &(xa, xb)) in corners.iter().take(2).enumerate() {
        let (lo, hi) = if k == 0 { (xa, xb) } else { (-xb, -xa) };
        if x > lo && x < hi {
            let c = 0.5 * (lo + hi);
            let w = 0.5 * (hi - lo);
            let u = 1.0 - ((x - c) / w).powi(2);
            let (amp, r) = match side {
                SlitSide::Upper => (UPPER_LID_H * lid_margin(u, true), 0.010),
                SlitSide::Lower => (-LOWER_LID_H * lid_margin(u, false), 0.008),
            };
            dy += amp * (1.0 - y.abs() / r).max(0.0);
        }
    }
    // Mouth: tiny gap between the lips.
    let xm = corners[2].1;
    if x.abs() < xm {
        let u = 1.0 - (x / xm).powi(2);
        let amp = match side {
            SlitSide::Upper => 0.0006,
            SlitSide::Lower => -0.0006,
        } * u;
        dy += amp * (1.0 - (y - MOUTH_Y).abs() / 0.004).max(0.0);
    }
    dy
}

/// Height-field features of the front face (added to z).
fn features(x: f32, y: f32) -> f32 {
    let ax = x.abs();
    // Brow ridge.
    let brow = 0.003 * gauss(y - 0.02, 0.009) * (1.0 - smoothstep(0.04, 0.06, ax));
    // Nose ridge from the nasion to the tip, then the columella to the base.
    let tip_y = NOSE_BASE_Y + 0.010;
    let ridge_h = if y > NASION_Y + 0.004 {
        0.0
    } else if y > tip_y {
        let s = (NASION_Y + 0.004 - y) / (NASION_Y + 0.004 - tip_y);
        0.019 * s.powf(1.3)
    } else {
        0.019 * (1.0 - smoothstep(0.0, 1.0, (tip_y - y) / 0.011))
    };
    let ridge_w = 0.0045 + 0.005 * smoothstep(NASION_Y, tip_y, y);
    let nose = ridge_h * gauss(ax, ridge_w);
    // Alar wings.
    let wing = 0.008 * gauss(ax - 0.0115, 0.0055) * gauss(y - (NOSE_BASE_Y + 0.005), 0.007);
    // Cheeks.
    let cheek = 0.006 * gauss(ax - 0.045, 0.018) * gauss(y + 0.03, 0.02);
    // Lips.
    let lip_shape = (1.0 - (ax / 0.03).powi(2)).max(0.0);
    let upper_lip = 0.0055 * lip_shape * gauss(y - (MOUTH_Y + 0.0065), 0.0055);
    let lower_lip = 0.005 * lip_shape * gauss(y - (MOUTH_Y - 0.008), 0.0055);
    // Chin.
    let chin = 0.006 * gauss(ax, 0.014) * gauss(y - (CHIN_Y + 0.014), 0.011);
    brow + nose + wing + cheek + upper_lip + lower_lip + chin
}

/// Front height field z(x, y) with features and the eye sockets/lid shells.
fn front_z(x: f32, y: f32) -> f32 {
    let (a, f, _) = section(y);
    let s = (x.abs() / a).min(1.0);
    let base = Z_C + f * (1.0 - s.powf(EXPO)).max(0.0).powf(1.0 / EXPO);
    let fade = 1.0 - smoothstep(0.8, 0.95, s);
    let mut z = base + features(x, y) * fade;
    for ex in [EYE_X, -EYE_X] {
        let q = ((x - ex) / SHELL[0]).powi(2) + (y / SHELL[1]).powi(2);
        let shell = SHELL[2] * (1.0 - q).max(0.0).sqrt();
        let w = 1.0 - smoothstep(0.55, 1.0, q);
        z = z + (shell - z) * w;
    }
    z
}

/// Point on the head surface for grid angle `phi` (0 = front, > 0 to +X)
/// at height `y`, on `side` of a slit (warp) if in the front.
fn surface(phi: f32, y: f32, side: SlitSide, corners: &[(f32, f32); 3]) -> Vec3 {
    let (a, _, b) = section(y);
    let (s, c) = phi.sin_cos();
    let pw = 2.0 / EXPO;
    let x = a * s.signum() * s.abs().powf(pw);
    let mut p = if c > 0.0 {
        let yw = y + opening_warp(x, y, side, corners);
        Vec3::new(x, yw, front_z(x, yw))
    } else {
        Vec3::new(x, y, Z_C - b * c.abs().powf(pw))
    };
    // Ears: bumps along x on the sides.
    let ear = 0.011 * gauss(p.y + 0.015, 0.024) * gauss(p.z + 0.085, 0.011);
    p.x += p.x.signum() * ear;
    p
}

/// Front surface point at chart position (x, y) (no slit warp).
pub fn surface_at(x: f32, y: f32) -> Vec3 {
    let ear = 0.0;
    Vec3::new(x, y, front_z(x, y) + ear)
}

/// Column angles: dense at the front. `cols` even, phi(j) antisymmetric.
fn column_phi(j: usize, cols: usize) -> f32 {
    let t = 2.0 * j as f32 / cols as f32; // 0..2
    let t = if t > 1.0 { t - 2.0 } else { t }; // (-1, 1]
    let c = 0.45;
    std::f32::consts::PI * (c * t + (1.0 - c) * t * t * t)
}

/// Row heights, top to bottom (rows + 1 values incl. the poles), with the
/// rows nearest the eye height and the mouth line moved exactly onto them.
fn row_heights(rows: usize) -> (Vec<f32>, usize, usize) {
    let (ymid, h) = (0.5 * (TOP_Y + BOTTOM_Y), 0.5 * (TOP_Y - BOTTOM_Y));
    let b = 0.45;
    let mut ys: Vec<f32> = (0..=rows)
        .map(|i| {
            let v = i as f32 / rows as f32;
            let th = std::f32::consts::PI
                * (v + b * (std::f32::consts::TAU * v).sin() / std::f32::consts::TAU);
            ymid + h * th.cos()
        })
        .collect();
    let nearest = |ys: &[f32], t: f32| {
        (1..rows)
            .min_by(|&i, &j| (ys[i] - t).abs().total_cmp(&(ys[j] - t).abs()))
            .unwrap()
    };
    let (ie, im) = (nearest(&ys, 0.0), nearest(&ys, MOUTH_Y));
    // Piecewise-linear monotone remap through (ys[ie] -> 0), (ys[im] -> MOUTH_Y).
    let knots = [
        (ys[0], ys[0]),
        (ys[ie], 0.0),
        (ys[im], MOUTH_Y),
        (ys[rows], ys[rows]),
    ];
    for y in ys.iter_mut() {
        for w in knots.windows(2) {
            if *y <= w[0].0 && *y >= w[1].0 {
                let t = (w[0].0 - *y) / (w[0].0 - w[1].0);
                *y = w[0].1 + (w[1].1 - w[0].1) * t;
                break;
            }
        }
    }
    (ys, ie, im)
}

impl HeadMesh {
    /// Generate the head. Deterministic.
    pub fn generate(params: MeshParams) -> HeadMesh {
        let rows = params.rows.max(24);
        let cols = 2 * rows;
        let (ys, row_eye, row_mouth) = row_heights(rows);
        let phis: Vec<f32> = (0..cols).map(|j| column_phi(j, cols)).collect();
        let base_x =
            |row: usize, j: usize| surface(phis[j], ys[row], SlitSide::Upper, &[(0.0, 0.0); 3]).x;
        // Slit columns: nearest to the wanted corners, on the slit rows.
        let nearest_col = |row: usize, x: f32| {
            (0..cols / 2)
                .filter(|&j| phis[j].cos() > 0.0)
                .min_by(|&a, &b| {
                    (base_x(row, a) - x)
                        .abs()
                        .total_cmp(&(base_x(row, b) - x).abs())
                })
                .unwrap()
        };
        let ji = nearest_col(row_eye, EYE_X - FISSURE_HALF_W);
        let jo = nearest_col(row_eye, EYE_X + FISSURE_HALF_W);
        let jm = nearest_col(row_mouth, MOUTH_HALF_W);
        let (xi, xo, xm) = (
            base_x(row_eye, ji),
            base_x(row_eye, jo),
            base_x(row_mouth, jm),
        );
        let corners = [(xi, xo), (xi, xo), (-xm, xm)];
        // Column runs (left to right in index order along +X) of each slit.
        let left_eye: Vec<usize> = (ji..=jo).collect();
        let right_eye: Vec<usize> = (cols - jo..=cols - ji).collect();
        let mouth: Vec<usize> = (cols - jm..cols).chain(0..=jm).collect();

        let idx = |row: usize, j: usize| -> u32 {
            if row == 0 {
                0
            } else if row == rows {
                (1 + (rows - 1) * cols) as u32
            } else {
                (1 + (row - 1) * cols + j % cols) as u32
            }
        };
        let mut positions = Vec::with_capacity(2 + (rows - 1) * cols + 64);
        positions.push(Vec3::new(0.0, ys[0], Z_C));
        for (row, &y) in ys.iter().enumerate().take(rows).skip(1) {
            for (j, &phi) in phis.iter().enumerate() {
                let on_slit_row = row == row_eye || row == row_mouth;
                let side = if y > 0.0 || (y > MOUTH_Y && y < -0.03) || on_slit_row {
                    SlitSide::Upper
                } else {
                    SlitSide::Lower
                };
                let _ = j;
                positions.push(surface(phi, y, side, &corners));
            }
        }
        positions.push(Vec3::new(0.0, ys[rows], Z_C));

        // Duplicate slit interiors (lower rims).
        let mut dup: HashMap<u32, u32> = HashMap::new();
        let mut rims = Rims::default();
        let mut slit =
            |row: usize, run: &[usize], positions: &mut Vec<Vec3>| -> (Vec<u32>, Vec<u32>) {
                let upper: Vec<u32> = run.iter().map(|&j| idx(row, j)).collect();
                let mut lower = upper.clone();
                for (n, &j) in run.iter().enumerate().skip(1).take(run.len() - 2) {
                    let new = positions.len() as u32;
                    positions.push(surface(phis[j], ys[row], SlitSide::Lower, &corners));
                    dup.insert(idx(row, j), new);
                    lower[n] = new;
                }
                (upper, lower)
            };
        let (u, l) = slit(row_eye, &left_eye, &mut positions);
        rims.upper_lid[0] = u;
        rims.lower_lid[0] = l;
        let (u, l) = slit(row_eye, &right_eye, &mut positions);
        rims.upper_lid[1] = u;
        rims.lower_lid[1] = l;
        let (u, l) = slit(row_mouth, &mouth, &mut positions);
        rims.upper_lip = u;
        rims.lower_lip = l;

        // Triangles.
        let mut triangles = Vec::with_capacity(2 * rows * cols);
        for j in 0..cols {
            triangles.push([0, idx(1, j), idx(1, j + 1)]);
            let bottom = idx(rows, 0);
            triangles.push([bottom, idx(rows - 1, j + 1), idx(rows - 1, j)]);
        }
        for row in 1..rows - 1 {
            let map = |v: u32| {
                if row == row_eye || row == row_mouth {
                    *dup.get(&v).unwrap_or(&v)
                } else {
                    v
                }
            };
            for j in 0..cols {
                let (a, b) = (map(idx(row, j)), map(idx(row, j + 1)));
                let (c, d) = (idx(row + 1, j), idx(row + 1, j + 1));
                // Column cols - j mirrors column j (phi antisymmetric), so
                // the quads' diagonals are mirrored too: the mesh's
                // connectivity, not only its shape, is left-right symmetric
                // and anything spread along it (rig S1) stays symmetric.
                if j < cols / 2 {
                    triangles.push([a, c, b]);
                    triangles.push([b, c, d]);
                } else {
                    triangles.push([a, c, d]);
                    triangles.push([a, d, b]);
                }
            }
        }
        let normals = compute_normals(&positions, &triangles);
        let coarse = coarse_shell(rows, cols, 3, idx);
        let kept: std::collections::HashSet<u32> = [
            &rims.upper_lid[0],
            &rims.lower_lid[0],
            &rims.upper_lid[1],
            &rims.lower_lid[1],
            &rims.upper_lip,
            &rims.lower_lip,
        ]
        .into_iter()
        .flatten()
        .copied()
        .collect();
        let (medium, medium_error) = medium_level(rows, cols, &positions, &triangles, idx, |v| {
            kept.contains(&v) || detailed(positions[v as usize])
        });

        let landmarks = landmarks(&positions, &rims);
        let lid_zone = lid_zone(&positions, landmarks.eye_centre);
        HeadMesh {
            positions,
            normals,
            triangles,
            medium,
            medium_error,
            coarse,
            landmarks,
            rims,
            lid_zone,
        }
    }
}

/// Where the middle level of detail keeps the fine grid (rest positions):
/// round each eye with its lids and brow, round the mouth with its lips,
/// along the nose (whose ridge is a few columns wide), and over the ears'
/// bumps (where the grid bends most).
fn detailed(p: Vec3) -> bool {
    let eye = ((p.x.abs() - EYE_X) / 0.026).powi(2) + ((p.y - 0.008) / 0.030).powi(2);
    let mouth = (p.x / 0.040).powi(2) + ((p.y - MOUTH_Y) / 0.018).powi(2);
    let nose = p.x.abs() < 0.024 && p.y < NASION_Y + 0.008 && p.y > NOSE_BASE_Y - 0.008;
    let ear = ((p.y + 0.015) / 0.036).powi(2) + ((p.z + 0.085) / 0.022).powi(2);
    (p.z > Z_C && (eye < 1.0 || mouth < 1.0 || nose)) || ear < 1.0
}

/// The middle level of detail of a grid of `rows` bands and `cols`
/// columns whose fine `triangles` are the poles' fans, then two a cell
/// row by row (as [`HeadMesh::generate`] lays them): cells in blocks of two
/// by two, a block drawn as two triangles through its corners where none
/// of its nine vertices is `kept`, else as its fine cells. A coarse block
/// beside fine cells takes the midpoint of the side they share, fanned
/// from its centre, so that no edge ends in the middle of another (no
/// crack). Returns the triangles and the level's error: the largest
/// distance of a skipped vertex from the midpoint of the coarse edge that
/// stands for it.
fn medium_level(
    rows: usize,
    cols: usize,
    positions: &[Vec3],
    triangles: &[[u32; 3]],
    idx: impl Fn(usize, usize) -> u32,
    kept: impl Fn(u32) -> bool,
) -> (Vec<[u32; 3]>, f32) {
    debug_assert_eq!(
        triangles.len(),
        2 * cols * (rows - 1),
        "the fine grid's layout"
    );
    // Cell (band b, column j), b in 1..rows - 1: its two fine triangles.
    let cell = |b: usize, j: usize| {
        let k = 2 * cols + 2 * ((b - 1) * cols + j);
        [triangles[k], triangles[k + 1]]
    };
    // Blocks: bands b0, b0 + 1 (b0 odd) and columns j0, j0 + 1 (j0 even).
    let coarse = |b0: usize, j0: usize| {
        b0 % 2 == 1
            && b0 + 1 < rows - 1
            && (0..3).all(|r| (0..3).all(|c| !kept(idx(b0 + r, (j0 + c) % cols))))
    };
    // The poles' fans as they are.
    let mut out: Vec<[u32; 3]> = triangles[..2 * cols].to_vec();
    let mut error = 0.0f32;
    let at = |r: usize, c: usize| positions[idx(r, c) as usize];
    for b0 in (1..rows - 1).step_by(2) {
        for j0 in (0..cols).step_by(2) {
            if !coarse(b0, j0) {
                for b in b0..(b0 + 2).min(rows - 1) {
                    for j in j0..j0 + 2 {
                        out.extend(cell(b, j));
                    }
                }
                continue;
            }
            let (r1, r2, c1, c2) = (b0 + 1, b0 + 2, j0 + 1, j0 + 2);
            // Corners, the sides' midpoints, the centre.
            let (a, b, c, d) = (idx(b0, j0), idx(b0, c2), idx(r2, j0), idx(r2, c2));
            let (top, bottom, left, right, centre) = (
                idx(b0, c1),
                idx(r2, c1),
                idx(r1, j0),
                idx(r1, c2),
                idx(r1, c1),
            );
            // A side takes its midpoint where a fine neighbour shares it.
            let fine_top = b0 < 2 || !coarse(b0 - 2, j0);
            let fine_bottom = !coarse(b0 + 2, j0);
            let fine_left = !coarse(b0, (j0 + cols - 2) % cols);
            let fine_right = !coarse(b0, (j0 + 2) % cols);
            let mid = |p: Vec3, q: Vec3, m: Vec3| m.distance((p + q) / 2.0);
            let (pa, pb, pc, pd) = (at(b0, j0), at(b0, c2), at(r2, j0), at(r2, c2));
            for (fine, m, p, q) in [
                (fine_top, at(b0, c1), pa, pb),
                (fine_bottom, at(r2, c1), pc, pd),
                (fine_left, at(r1, j0), pa, pc),
                (fine_right, at(r1, c2), pb, pd),
            ] {
                if !fine {
                    error = error.max(mid(p, q, m));
                }
            }
            if !(fine_top || fine_bottom || fine_left || fine_right) {
                // Two triangles, the diagonal mirrored across the midline
                // as the fine grid's is.
                let x = at(r1, c1);
                if j0 < cols / 2 {
                    error = error.max(mid(pb, pc, x));
                    out.extend([[a, c, b], [b, c, d]]);
                } else {
                    error = error.max(mid(pa, pd, x));
                    out.extend([[a, c, d], [a, d, b]]);
                }
                continue;
            }
            // A fan from the centre round the block, in the fine
            // triangles' turning sense: down the left, along the bottom,
            // up the right, back along the top.
            let ring: Vec<u32> = [
                (a, true),
                (left, fine_left),
                (c, true),
                (bottom, fine_bottom),
                (d, true),
                (right, fine_right),
                (b, true),
                (top, fine_top),
            ]
            .into_iter()
            .filter_map(|(v, on)| on.then_some(v))
            .collect();
            for k in 0..ring.len() {
                out.push([centre, ring[k], ring[(k + 1) % ring.len()]]);
            }
        }
    }
    (out, error)
}

/// The grid's closed shell through every `step`-th row and column (the
/// last row and the column wrap always): outward triangles between the
/// grid vertices `idx(row, column)` (the upper rim of each opening), poles
/// fanned.
fn coarse_shell(
    rows: usize,
    cols: usize,
    step: usize,
    idx: impl Fn(usize, usize) -> u32,
) -> Vec<[u32; 3]> {
    let mut rs: Vec<usize> = (0..rows).step_by(step).collect();
    rs.push(rows);
    let mut js: Vec<usize> = (0..cols).step_by(step).collect();
    js.push(cols);
    let mut out = Vec::new();
    for r in rs.windows(2) {
        for j in js.windows(2) {
            let (a, b) = (idx(r[0], j[0]), idx(r[0], j[1]));
            let (c, d) = (idx(r[1], j[0]), idx(r[1], j[1]));
            if a != b {
                out.push([a, c, b]);
            }
            if c != d {
                out.push([b, c, d]);
            }
        }
    }
    out
}

/// Vertices of each eye's lid zone (0 left, 1 right): in front of the
/// eyeball centre (`eye_centre` is the left one; the right is its mirror)
/// and inside the lid shell's outline. The rig keeps them off the eyeball.
pub fn lid_zone(positions: &[Vec3], eye_centre: Vec3) -> [Vec<u32>; 2] {
    [eye_centre, mirror(eye_centre)].map(|c| {
        (0..positions.len() as u32)
            .filter(|&i| {
                let d = positions[i as usize] - c;
                d.z > 0.0 && (d.x / SHELL[0]).powi(2) + (d.y / SHELL[1]).powi(2) < 1.0
            })
            .collect()
    })
}

/// Area-weighted unit vertex normals.
pub fn compute_normals(positions: &[Vec3], triangles: &[[u32; 3]]) -> Vec<Vec3> {
    let mut n = vec![Vec3::ZERO; positions.len()];
    for t in triangles {
        let [a, b, c] = t.map(|i| positions[i as usize]);
        let f = (b - a).cross(c - a);
        for &i in t {
            n[i as usize] += f;
        }
    }
    n.into_iter().map(|v| v.normalize_or(Vec3::Z)).collect()
}

fn landmarks(positions: &[Vec3], rims: &Rims) -> Landmarks {
    let s = surface_at;
    let mid = |r: &[u32]| positions[r[r.len() / 2] as usize];
    let jaw_half_width = section(-0.09).0 * 1.02;
    Landmarks {
        nasion: s(0.0, NASION_Y),
        glabella: s(0.0, 0.018),
        nasal_bone: s(0.0, -0.012),
        nose_tip: s(0.0, NOSE_BASE_Y + 0.010),
        nostril_wing: s(ALAR_HALF_W, NOSE_BASE_Y + 0.005),
        brow_inner: s(0.016, 0.024),
        brow_mid: s(0.031, 0.028),
        brow_outer: s(0.046, 0.024),
        forehead_inner: s(0.016, 0.062),
        forehead_mid: s(0.031, 0.064),
        forehead_outer: s(0.046, 0.060),
        orbit_inner_upper: s(0.012, 0.013),
        orbit_inner_lower: s(0.013, -0.013),
        orbit_lower: s(0.028, -0.018),
        cheekbone: s(0.058, -0.014),
        face_side: s(0.066, -0.062),
        eye_inner_corner: positions[rims.upper_lid[0][0] as usize],
        eye_outer_corner: positions[*rims.upper_lid[0].last().unwrap() as usize],
        upper_lid_mid: mid(&rims.upper_lid[0]),
        lower_lid_mid: mid(&rims.lower_lid[0]),
        eye_centre: Vec3::new(EYE_X, 0.0, 0.0),
        mouth_corner: positions[*rims.upper_lip.last().unwrap() as usize],
        mouth_centre: s(0.0, MOUTH_Y),
        upper_lip: s(0.010, MOUTH_Y + 0.007),
        lower_lip: s(0.010, MOUTH_Y - 0.008),
        jaw_lower_edge: s(0.040, -0.100),
        jaw_outer: s(0.024, -0.098),
        chin: s(0.0, CHIN_Y + 0.004),
        jaw_pivot: Vec3::new(section(-0.022).0 - 0.008, -0.022, -0.066),
        ear_lobe: Vec3::new(section(-0.048).0, -0.048, -0.078),
        jaw_half_width,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashMap;

    fn edge_use(tris: &[[u32; 3]]) -> HashMap<(u32, u32), (u32, u32)> {
        // (undirected edge) -> (uses as a->b, uses as b->a)
        let mut m: HashMap<(u32, u32), (u32, u32)> = HashMap::new();
        for t in tris {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                let e = m.entry((a.min(b), a.max(b))).or_default();
                if a < b { e.0 += 1 } else { e.1 += 1 }
            }
        }
        m
    }

    #[test]
    fn watertight_except_openings_and_oriented() {
        for (rows, level) in [32, 47, 60].into_iter().flat_map(|r| [(r, 0), (r, 1)]) {
            let mut m = HeadMesh::generate(MeshParams { rows });
            // The middle level of detail too: no crack where its coarse
            // blocks meet the fine cells, its openings the fine ones.
            if level == 1 {
                m.triangles = m.medium.clone();
            }
            let eu = edge_use(&m.triangles);
            let mut boundary = Vec::new();
            for (e, (f, b)) in &eu {
                match (f, b) {
                    (1, 1) => {}
                    (1, 0) | (0, 1) => boundary.push(*e),
                    _ => panic!("non-manifold edge {e:?}: {f} {b}"),
                }
            }
            // The boundary edges are exactly the rims of the three openings.
            let rim_edges: usize = [
                &m.rims.upper_lid[0],
                &m.rims.lower_lid[0],
                &m.rims.upper_lid[1],
                &m.rims.lower_lid[1],
                &m.rims.upper_lip,
                &m.rims.lower_lip,
            ]
            .iter()
            .map(|r| r.len() - 1)
            .sum();
            assert_eq!(boundary.len(), rim_edges, "rows {rows}");
            // Outward orientation: positive enclosed volume.
            let vol: f32 = m
                .triangles
                .iter()
                .map(|t| {
                    let [a, b, c] = t.map(|i| m.positions[i as usize]);
                    a.dot(b.cross(c)) / 6.0
                })
                .sum();
            assert!(vol > 0.002 && vol < 0.006, "volume {vol} m^3");
            assert!(
                m.triangles
                    .iter()
                    .all(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
            );
        }
    }

    #[test]
    fn middle_level_keeps_the_openings_and_halves_the_rest() {
        for rows in [32, 47, 60] {
            let m = HeadMesh::generate(MeshParams { rows });
            let n = m.medium.len() as f32 / m.triangles.len() as f32;
            assert!((0.3..0.7).contains(&n), "rows {rows}: {n} of the triangles");
            // Every fine triangle round the eyes, brows and mouth is kept.
            let kept: std::collections::HashSet<[u32; 3]> = m.medium.iter().copied().collect();
            let near = m
                .triangles
                .iter()
                .filter(|t| t.iter().all(|&i| detailed(m.positions[i as usize])));
            for t in near {
                assert!(kept.contains(t), "rows {rows}: {t:?} not kept");
            }
            // The error is the skipped vertices' distance, a few mm on a
            // grid of this size (the coarse edges are chords of a curved
            // surface), none where nothing is skipped.
            assert!(
                m.medium_error > 1e-4 && m.medium_error < 0.01,
                "rows {rows}: error {} m",
                m.medium_error
            );
            // Left-right symmetric, as the fine grid is: each triangle's
            // mirror image (by vertex position) is a triangle too. (With
            // an odd row count one block straddles the back's midline and
            // its diagonal cannot be mirrored.)
            let key = |p: Vec3| {
                (
                    (p.x * 1e5).round() as i64,
                    (p.y * 1e5).round() as i64,
                    (p.z * 1e5).round() as i64,
                )
            };
            let by_pos: HashMap<_, u32> = m
                .positions
                .iter()
                .enumerate()
                .map(|(i, p)| (key(*p), i as u32))
                .collect();
            let mirrored = m.medium.iter().filter(|t| {
                let [a, b, c] =
                    t.map(|i| by_pos.get(&key(mirror(m.positions[i as usize]))).copied());
                match (a, b, c) {
                    (Some(a), Some(b), Some(c)) => [[a, c, b], [c, b, a], [b, a, c]]
                        .iter()
                        .any(|u| kept.contains(u)),
                    _ => false,
                }
            });
            let share = mirrored.count() as f32 / m.medium.len() as f32;
            assert!(share > 0.97, "rows {rows}: {share} mirrored");
        }
    }

    #[test]
    fn coarse_shell_is_closed_and_holds_the_head() {
        let volume = |tris: &[[u32; 3]], p: &[Vec3]| -> f32 {
            tris.iter()
                .map(|t| {
                    let [a, b, c] = t.map(|i| p[i as usize]);
                    a.dot(b.cross(c)) / 6.0
                })
                .sum()
        };
        for rows in [32, 48, 61] {
            let m = HeadMesh::generate(MeshParams { rows });
            // Closed and consistently oriented: every edge used once each way.
            for (e, uses) in edge_use(&m.coarse) {
                assert_eq!(uses, (1, 1), "rows {rows}: edge {e:?}");
            }
            assert!(
                m.coarse
                    .iter()
                    .all(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
            );
            let n = m.coarse.len() as f32 / m.triangles.len() as f32;
            assert!(
                (0.08..0.16).contains(&n),
                "rows {rows}: {n} of the triangles"
            );
            // Chords inside the curved surface: a little less volume.
            let (fine, coarse) = (
                volume(&m.triangles, &m.positions),
                volume(&m.coarse, &m.positions),
            );
            assert!(
                coarse < fine * 1.01 && coarse > fine * 0.9,
                "rows {rows}: {coarse} vs {fine} m^3"
            );
        }
    }

    #[test]
    fn vertex_count_scales_and_is_deterministic() {
        let mut counts = Vec::new();
        for rows in [32, 64, 100, 160] {
            let m = HeadMesh::generate(MeshParams { rows });
            counts.push(m.positions.len());
        }
        println!("vertex counts (rows 32, 64, 100, 160): {counts:?}");
        assert!(counts[0] > 1800 && counts[0] < 2600);
        assert!(counts[3] >= 50_000);
        assert!(counts.windows(2).all(|w| w[1] > w[0]));
        assert_eq!(
            HeadMesh::generate(MeshParams { rows: 40 }),
            HeadMesh::generate(MeshParams { rows: 40 })
        );
    }

    #[test]
    fn landmarks_follow_proportions() {
        for (rows, tol) in [(32, 0.005), (120, 0.0015)] {
            let m = HeadMesh::generate(MeshParams { rows });
            let l = &m.landmarks;
            let mouth_w = 2.0 * l.mouth_corner.x;
            assert!((mouth_w - 0.052).abs() < 2.0 * tol, "mouth width {mouth_w}");
            let fissure = l.eye_outer_corner.x - l.eye_inner_corner.x;
            assert!((fissure - 0.031).abs() < 2.0 * tol, "fissure {fissure}");
            assert!((l.mouth_corner.y - MOUTH_Y).abs() < 1e-4);
            assert!((l.nasion.y - l.mouth_centre.y - 0.075).abs() < 1e-6);
            assert!(
                (l.upper_lid_mid.y - UPPER_LID_H).abs() < tol
                    && (l.lower_lid_mid.y + LOWER_LID_H).abs() < tol
            );
            // Mouth corners roughly below the pupils' inner edges (pupil x ~ 31 mm).
            assert!(l.mouth_corner.x < EYE_X && l.mouth_corner.x > EYE_X - 0.008);
            // Head size.
            let (min, max) = m
                .positions
                .iter()
                .fold((Vec3::MAX, Vec3::MIN), |(a, b), p| (a.min(*p), b.max(*p)));
            let breadth = max.x - min.x;
            assert!((breadth - 0.152).abs() < 0.02, "breadth {breadth}");
            assert!((max.y - TOP_Y).abs() < 1e-4);
            let length = l.glabella.z - min.z;
            assert!((length - 0.195).abs() < 0.01, "length {length}");
            // Nose in front of the face, lids in front of the eyeballs.
            assert!(l.nose_tip.z > l.nasion.z + 0.01);
            for &i in &m.lid_zone[0] {
                let p = m.positions[i as usize];
                assert!(
                    p.distance(Vec3::new(EYE_X, 0.0, 0.0)) > EYEBALL_R + 0.0005,
                    "lid vertex inside eyeball: {p}"
                );
            }
        }
    }
}
