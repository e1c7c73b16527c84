//! The lip seal (O1, docs/model/face.md): a contracted orbicularis oris
//! presses the lips together over a small jaw opening. Built once on the
//! mesh (which rim column each vertex of the lower lip closes, and how
//! much), applied after the muscles each frame.

use glam::Vec3;

use crate::emotion::{MuscleId, Side};
use crate::mesh::HeadMesh;
use crate::params::FaceParams;
use crate::tables::MuscleKind;
use shisen_gaze::util::math::smoothstep;

/// Precomputed data of the lip seal (O1): the vertices of the lower lip and
/// the skin below it, each with the rim column whose opening it closes and
/// how much of it, and the law's constants.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct LipSeal {
    /// Orbicularis oris channel.
    pub channel: usize,
    /// Contraction that presses the lips fully together (`None`: no seal).
    pub seal_k: Option<f32>,
    /// Widest opening the pressed lips close, m.
    pub max_gap: f32,
    /// Rim columns: (upper lip rim vertex, lower lip rim vertex).
    pub columns: Vec<(u32, u32)>,
    /// Region vertices.
    pub index: Vec<u32>,
    /// Column of each region vertex.
    pub column: Vec<u32>,
    /// Weight of each region vertex: 1 on the lower lip's margin, 0 at
    /// `SEAL_REACH` below it and at the mouth's corners.
    pub weight: Vec<f32>,
}

/// How far below the lower lip's margin the seal's pull reaches, m: the
/// lower lip's height down to the labiomental fold (about 15 mm in adults;
/// Farkas 1994, Anthropometry of the Head and Face, 2nd ed.).
const SEAL_REACH: f32 = 0.015;

/// Opening over which the seal takes hold, m: it closes a column whose
/// upper margin has risen from the lower by this much or more, none whose
/// lips press into each other (a smooth onset, so neighbouring columns
/// move alike).
const SEAL_SOFT: f32 = 0.001;

impl LipSeal {
    pub(crate) fn build(mesh: &HeadMesh, params: &FaceParams) -> LipSeal {
        let (upper, lower) = (&mesh.rims.upper_lip, &mesh.rims.lower_lip);
        let pos = |i: u32| mesh.positions[i as usize];
        // Each lower rim vertex paired with the upper one nearest across.
        let columns: Vec<(u32, u32)> = lower
            .iter()
            .filter_map(|&l| {
                let u = upper.iter().copied().min_by(|&a, &b| {
                    let d = |i: u32| (pos(i).x - pos(l).x).abs();
                    d(a).total_cmp(&d(b))
                })?;
                Some((u, l))
            })
            .collect();
        let mut seal = LipSeal {
            channel: MuscleId {
                kind: MuscleKind::OrbicularisOris,
                side: Side::Centre,
            }
            .index()
            .expect("orbicularis oris channel"),
            seal_k: params.lips.seal_k.map(|k| k as f32),
            max_gap: params.lips.seal_max_gap_m as f32,
            columns,
            ..LipSeal::default()
        };
        if seal.columns.is_empty() {
            return seal;
        }
        let half_w = mesh.landmarks.mouth_corner.x;
        let front = mesh.landmarks.mouth_corner.z - 0.01;
        for (i, &p) in mesh.positions.iter().enumerate() {
            if p.x.abs() > half_w || p.z < front {
                continue;
            }
            let (c, rim) = seal
                .columns
                .iter()
                .enumerate()
                .map(|(c, &(_, l))| (c, pos(l)))
                .min_by(|a, b| (a.1.x - p.x).abs().total_cmp(&(b.1.x - p.x).abs()))
                .expect("columns");
            let below = rim.y - p.y;
            if !(0.0..SEAL_REACH).contains(&below) {
                continue;
            }
            seal.index.push(i as u32);
            seal.column.push(c as u32);
            // Tapered to nothing at the mouth's corners, beyond which the
            // skin is not moved: a coarse mesh would fold there.
            let across = 1.0 - smoothstep(0.6 * half_w, half_w, p.x.abs());
            seal.weight
                .push((1.0 - smoothstep(0.0, SEAL_REACH, below)) * across);
        }
        // The rims' vertices last (see `apply`).
        let on_rim = |i: u32| seal.columns.iter().any(|&(u, l)| u == i || l == i);
        let mut order: Vec<usize> = (0..seal.index.len()).collect();
        order.sort_by_key(|&n| on_rim(seal.index[n]));
        seal.index = order.iter().map(|&n| seal.index[n]).collect();
        seal.column = order.iter().map(|&n| seal.column[n]).collect();
        seal.weight = order.iter().map(|&n| seal.weight[n]).collect();
        seal
    }

    /// Move the lower lip's region so its margin closes the opening the
    /// lips have gained over their rest, in each column, by the seal's
    /// share of it, at most `max_gap` (O1).
    pub(crate) fn apply(&self, mesh: &HeadMesh, k: f32, out: &mut [Vec3]) {
        let Some(seal_k) = self.seal_k else {
            return;
        };
        let s = (k / seal_k).clamp(0.0, 1.0); // (O1)
        if s == 0.0 {
            return;
        }
        // The rims' own vertices come last in the region, so every
        // column's opening is read before its margins move.
        for ((&i, &c), &w) in self.index.iter().zip(&self.column).zip(&self.weight) {
            let (u, l) = self.columns[c as usize];
            let moved = |v: u32| out[v as usize] - mesh.positions[v as usize];
            let gap = moved(u) - moved(l);
            // Only an opening is closed (the upper margin risen from the
            // lower); lips pressed into each other are left as they are.
            let opening = smoothstep(0.0, SEAL_SOFT, gap.y);
            let close = gap * (s * opening * (self.max_gap / gap.length().max(1e-9)).min(1.0)); // (O1)
            out[i as usize] += w * close;
        }
    }
}
