//! Sparse displacement fields (a muscle's displacement per unit
//! contraction on the vertices it moves), and the skin's spread of a
//! linear muscle's pull (S1, docs/model/face.md): each field diffused along
//! the mesh once, when the rig is built.

use glam::Vec3;

use crate::mesh::HeadMesh;

/// Displacement per unit contraction of the vertices a channel moves.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct SparseField {
    /// Vertex indices.
    pub index: Vec<u32>,
    /// Displacement at k = 1 of each listed vertex.
    pub delta: Vec<Vec3>,
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

pub(crate) struct Spread {
    /// Per vertex: its neighbours and their cotangent weights.
    neighbours: Vec<Vec<(u32, f32)>>,
    /// Per vertex: `min(1, dt W_i / A_i)`, the fraction of the way to its
    /// neighbours' weighted mean a step moves it (0: held).
    rate: Vec<f32>,
    steps: usize,
}

impl Spread {
    pub(crate) fn new(mesh: &HeadMesh, sigma: f32) -> Spread {
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
    pub(crate) fn apply(&self, f: &SparseField) -> SparseField {
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
