//! Levels of detail and culling. Each grid of a skinned body ([`Piece`])
//! is left out where it lies wholly outside the view, and drawn at the
//! coarsest of its levels ([`LEVELS`]) that departs from the fine one by
//! less than [`LOD_PIXELS`] at its distance (the screen-space error of a
//! level of detail); a sphere likewise at the coarse sphere's. On a
//! software rasteriser every triangle costs, whether it covers a pixel or
//! none.

use std::ops::Range;

use glam::{Mat4, Vec3, Vec4};

use super::body::{LEVELS, Piece};
use super::geometry::{BLOB_ERROR, Vertex};

/// The largest screen-space error of a piece drawn coarse, pixels: one,
/// the usual bound of a level of detail's error (a silhouette moves by at
/// most a pixel where the coarse level takes over).
pub const LOD_PIXELS: f32 = 1.0;

/// A range of one level's index list to draw.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Run {
    /// The level of detail ([`super::body::Lists::level`]).
    pub level: usize,
    /// Its indices.
    pub range: Range<u32>,
}

/// What a camera sees: its clip planes and how many pixels a radian spans.
#[derive(Clone, Copy, Debug)]
pub struct Sight {
    planes: [Vec4; 6],
    eye: Vec3,
    px_per_radian: f32,
}

impl Sight {
    /// The view of `view_proj` (clip depth 0 to 1, as wgpu's) from `eye`,
    /// `fov_y` radians high over `height_px` pixels.
    pub fn new(view_proj: Mat4, eye: Vec3, fov_y: f32, height_px: u32) -> Sight {
        let [r0, r1, r2, r3] = [0, 1, 2, 3].map(|i| view_proj.row(i));
        Sight {
            planes: [r3 + r0, r3 - r0, r3 + r1, r3 - r1, r2, r3 - r2],
            eye,
            px_per_radian: height_px as f32 / (2.0 * (fov_y / 2.0).tan()),
        }
    }

    /// Whether a coarse level `error` metres off the fine one may stand in
    /// for it over a sphere: under [`LOD_PIXELS`] at the sphere's nearest.
    fn coarse_enough(&self, error: f32, centre: Vec3, radius: f32) -> bool {
        let distance = (centre.distance(self.eye) - radius).max(0.05);
        error / distance * self.px_per_radian < LOD_PIXELS
    }

    /// The level of detail of a mesh with a middle level `error` metres
    /// off its fine one (as measured at rest), within a sphere: 1 (the
    /// middle one) where that is under [`LOD_PIXELS`] at the sphere's
    /// nearest, else 0.
    pub fn level(&self, error: f32, centre: Vec3, radius: f32) -> usize {
        usize::from(self.coarse_enough(error, centre, radius))
    }

    /// Whether a unit sphere drawn with `model` may be drawn as the coarse
    /// sphere ([`BLOB_ERROR`] of its radius off).
    pub fn coarse_sphere(&self, model: Mat4) -> bool {
        let radius = [model.x_axis, model.y_axis, model.z_axis]
            .map(|a| a.truncate().length())
            .into_iter()
            .fold(0.0, f32::max);
        self.coarse_enough(BLOB_ERROR * radius, model.w_axis.truncate(), radius)
    }

    /// Whether a sphere lies wholly outside the view.
    fn outside(&self, centre: Vec3, radius: f32) -> bool {
        self.planes
            .iter()
            .any(|p| p.truncate().dot(centre) + p.w < -radius * p.truncate().length())
    }
}

/// The runs to draw of a body posed as `posed`, made of `pieces`, seen in
/// `sight`: pieces outside it left out, each of the others at the coarsest
/// level [`LOD_PIXELS`] allows, neighbours at the same level merged.
pub fn runs(pieces: &[Piece], posed: &[Vertex], sight: &Sight) -> Vec<Run> {
    let mut out: Vec<Run> = Vec::new();
    for piece in pieces {
        let points = posed[piece.vertices.start as usize..piece.vertices.end as usize]
            .iter()
            .map(|v| Vec3::from_array(v.pos));
        let (lo, hi) = points.fold((Vec3::MAX, Vec3::MIN), |(lo, hi), p| (lo.min(p), hi.max(p)));
        let (centre, radius) = ((lo + hi) / 2.0, (hi - lo).length() / 2.0);
        if !radius.is_finite() || sight.outside(centre, radius) {
            continue;
        }
        let level = (0..LEVELS)
            .rev()
            .find(|&l| sight.coarse_enough(piece.errors[l], centre, radius))
            .unwrap_or(0);
        let range = piece.ranges[level].clone();
        match out.last_mut() {
            Some(last) if last.level == level && last.range.end == range.start => {
                last.range.end = range.end;
            }
            _ => out.push(Run { level, range }),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::body::{BodyMesh, BodyStyle, REST_POSE};
    use crate::render::camera::Camera;
    use shisen::physics::body::BodyPlan;

    fn body() -> (BodyMesh, Vec<Vertex>) {
        let m = BodyMesh::new(&BodyPlan::default(), &BodyStyle::VH);
        let mut posed = Vec::new();
        m.skin(&REST_POSE, &mut posed);
        (m, posed)
    }

    fn sight(eye: Vec3, target: Vec3, height_px: u32) -> Sight {
        let cam = Camera {
            eye,
            target,
            fov_y: 50f32.to_radians(),
            aspect: 16.0 / 9.0,
        };
        Sight::new(cam.view_proj(), eye, cam.fov_y, height_px)
    }

    fn triangles(runs: &[Run], level: usize) -> u32 {
        runs.iter()
            .filter(|r| r.level == level)
            .map(|r| r.range.len() as u32 / 3)
            .sum()
    }

    #[test]
    fn the_coarse_sphere_stays_within_its_error() {
        let blob = crate::render::geometry::rounded_box(2.0);
        let p = |i: u32| Vec3::from_array(blob.vertices[i as usize].pos);
        let mut worst = 0.0f32;
        for t in blob.indices.as_chunks::<3>().0 {
            let [a, b, c] = t.map(p);
            for q in [
                (a + b + c) / 3.0,
                (a + b) / 2.0,
                (b + c) / 2.0,
                (c + a) / 2.0,
            ] {
                worst = worst.max(1.0 - q.length());
            }
        }
        assert!(worst <= BLOB_ERROR && worst > 0.8 * BLOB_ERROR, "{worst}");
        // An eyeball (12 mm) at sparring distance on a 720-pixel picture:
        // coarse; a head-sized ball 30 cm away: fine.
        let s = sight(Vec3::new(0.0, 1.6, 1.0), Vec3::new(0.0, 1.6, 0.0), 720);
        let ball = |r: f32, z: f32| {
            Mat4::from_scale_rotation_translation(
                Vec3::splat(r),
                glam::Quat::IDENTITY,
                Vec3::new(0.0, 1.6, z),
            )
        };
        assert!(s.coarse_sphere(ball(0.012, 0.0)));
        assert!(!s.coarse_sphere(ball(0.1, 0.6)));
    }

    #[test]
    fn pieces_tile_every_level_in_order() {
        let (m, _) = body();
        // The whole body's lists, and the first-person arms'.
        for lists in [m.whole(), m.arms()] {
            let (pieces, levels) = (
                lists.pieces(),
                (0..LEVELS).map(|l| lists.level(l)).collect::<Vec<_>>(),
            );
            assert!(!pieces.is_empty());
            let mut at = [0u32; LEVELS];
            for p in pieces {
                for (l, at) in at.iter_mut().enumerate() {
                    assert_eq!(p.ranges[l].start, *at, "level {l}: {p:?}");
                    *at = p.ranges[l].end;
                    // Every triangle of a piece uses only its vertices.
                    let list = &levels[l][p.ranges[l].start as usize..p.ranges[l].end as usize];
                    assert!(list.iter().all(|i| p.vertices.contains(i)), "{p:?}");
                }
                // Each level no finer, nor better, than the one before.
                let n = p.ranges.clone().map(|r| r.len());
                assert!(n[1] <= n[0] && n[2] <= n[1], "{p:?}");
                assert!(p.errors[0] == 0.0 && p.errors[1] <= p.errors[2], "{p:?}");
                // Sagging chords: centimetres at most (the elbow's
                // olecranon, the torso's boxy sections), not the metres of
                // a wrong range.
                assert!(p.errors[2] < 0.015, "{p:?}");
            }
            for (l, end) in at.iter().enumerate() {
                assert_eq!(*end as usize, levels[l].len());
            }
        }
        let ratio =
            [1, 2].map(|l| m.whole().level(0).len() as f32 / m.whole().level(l).len() as f32);
        assert!((1.8..2.2).contains(&ratio[0]), "{ratio:?}");
        assert!((3.0..4.5).contains(&ratio[1]), "{ratio:?}");
        // The torso's sections are boxy, its rings close: level 1 drops
        // every other ring and departs by a millimetre.
        let torso = &m.whole().pieces()[0];
        assert!(
            torso.errors[1] < 0.0015 && torso.errors[2] > 0.005,
            "{torso:?}"
        );
    }

    #[test]
    fn near_is_fine_far_is_coarse_behind_is_left_out() {
        let (m, posed) = body();
        let all = m.whole().level(0).len() as u32 / 3;
        let chest = Vec3::new(0.0, 1.3, 0.0);
        // Across a ring from the front, at a window's resolution: mostly
        // fine.
        let near = runs(
            m.whole().pieces(),
            &posed,
            &sight(Vec3::new(0.0, 1.5, 1.0), chest, 1080),
        );
        assert!(triangles(&near, 0) > all / 3, "{near:?}");
        // Across the hall, on a small picture: all coarsest, nothing left
        // out, in one run.
        let far = runs(
            m.whole().pieces(),
            &posed,
            &sight(Vec3::new(0.0, 1.5, 8.0), chest, 360),
        );
        assert_eq!(
            far,
            vec![Run {
                level: 2,
                range: 0..m.whole().level(2).len() as u32
            }]
        );
        // Looking away: nothing drawn.
        let away = runs(
            m.whole().pieces(),
            &posed,
            &sight(Vec3::new(0.0, 1.5, 1.0), Vec3::new(0.0, 1.5, 3.0), 720),
        );
        assert!(away.is_empty(), "{away:?}");
        // Looking at the face from close by: the legs and shoes left out.
        let face = runs(
            m.whole().pieces(),
            &posed,
            &sight(Vec3::new(0.0, 1.65, 0.6), Vec3::new(0.0, 1.65, 0.0), 720),
        );
        let drawn: u32 = (0..LEVELS).map(|l| triangles(&face, l)).sum();
        assert!(drawn < all * 3 / 4, "{drawn} of {all}");
    }
}
