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

mod lod;
mod surface;
#[cfg(test)]
mod tests;

pub use surface::surface_at;

use glam::Vec3;
use lod::{coarse_shell, detailed, medium_level};
use std::collections::HashMap;
use surface::{SlitSide, column_phi, row_heights, section, surface};

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
