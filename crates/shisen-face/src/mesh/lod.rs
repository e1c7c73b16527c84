//! The coarser levels of detail over the fine grid's vertices: the middle
//! level (blocks of two by two cells away from the face's detail) and the
//! coarse closed shell.

use super::dims::*;
use glam::Vec3;

/// Where the middle level of detail keeps the fine grid (rest positions):
/// round each eye with its lids and brow, round the mouth with its lips,
/// along the nose (whose ridge is a few columns wide), and over the ears'
/// bumps (where the grid bends most).
pub(super) fn detailed(p: Vec3) -> bool {
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
pub(super) fn medium_level(
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
pub(super) fn coarse_shell(
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
