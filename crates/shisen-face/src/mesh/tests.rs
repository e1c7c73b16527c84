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
            let [a, b, c] = t.map(|i| by_pos.get(&key(mirror(m.positions[i as usize]))).copied());
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
