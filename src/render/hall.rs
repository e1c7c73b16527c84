//! The hall round the ring: its floor, twelve rows of seats rising on
//! four sides, walls and a roof with its lighting grid, and the crowd in
//! the seats, who rise, cheer and throw their arms up as the bout excites
//! them ([`shisen::sim::crowd`]). Static scenery baked once, lit on the CPU
//! by the lamps over the ring: bright near it, falling off into the dark
//! of the far rows, as an arena is lit for television (the ring at several
//! times the stands' light).
//!
//! The crowd is drawn in [`GROUPS`] groups, each a mesh seated and a mesh
//! standing with its arms up: a group stands when the crowd's excitement
//! passes its own threshold, and bounces while it cheers. A software
//! rasteriser pays per triangle: a seated person is two boxes (trunk and
//! head), a standing one four.

use glam::{Mat4, Quat, Vec3};

use super::draw::{Draw, Material, MeshKey};
use super::geometry::{MeshData, Vertex};
use super::ring::{CENTRE, HALF, PLATFORM, bake_with, bar};

/// Rows of seats on each side.
pub const ROWS: usize = 12;
/// Depth and rise of a row, m.
const ROW_DEPTH: f32 = 1.0;
const ROW_RISE: f32 = 0.5;
/// The first row's distance from the ring's centre, m (2.5 m beyond the
/// apron: the ringside tables and the press).
const FIRST_ROW: f32 = HALF + 0.6 + 2.5;
/// Seat pitch along a row, m.
const SEAT: f32 = 0.7;
/// The roof's height above the hall's floor, m.
const ROOF: f32 = 10.0;
/// The crowd's groups: each half of each side's rows (the camera sees at
/// most three of the eight halves), in four moods.
pub const GROUPS: usize = 32;

const FLOOR: [f32; 4] = [0.05, 0.045, 0.05, 1.0];
const STAND: [f32; 4] = [0.09, 0.05, 0.06, 1.0];
const WALL: [f32; 4] = [0.06, 0.065, 0.08, 1.0];
const STEEL: [f32; 4] = [0.15, 0.15, 0.16, 1.0];

/// The hall's floor level, world y.
fn floor_y() -> f32 {
    CENTRE.y - PLATFORM
}

/// The lamps' light on the hall at `p` with normal `n`: the rig over the
/// ring as a point source 5 m above the canvas, Lambert, falling off with
/// the square of the distance beyond 5 m, over a dim ambient (the
/// house lights down during a bout).
fn hall_light(p: Vec3, n: Vec3) -> f32 {
    let lamp = CENTRE + Vec3::Y * 5.0;
    let d = lamp - p;
    let r = d.length().max(0.1);
    let lambert = n.dot(d / r).max(0.0);
    let falloff = 1.0 / (1.0 + (r / 5.0).powi(2));
    0.08 + 1.2 * lambert * falloff
}

/// A small deterministic random number in [0, 1) from a counter: the
/// crowd's and the panels' variety, the same every run.
fn hash(k: u32) -> f32 {
    let mut x = k.wrapping_mul(0x9E37_79B9) ^ 0x85EB_CA6B;
    x ^= x >> 15;
    x = x.wrapping_mul(0x2C1B_3C6D);
    x ^= x >> 12;
    x = x.wrapping_mul(0x297A_2D39);
    x ^= x >> 15;
    (x >> 8) as f32 / (1u32 << 24) as f32
}

/// A colour scaled by `k` (a panel's own shade).
fn shade(c: [f32; 4], k: f32) -> [f32; 4] {
    [c[0] * k, c[1] * k, c[2] * k, 1.0]
}

/// The turn of side `k` (0-3) of the hall about the ring's centre.
fn side(k: usize) -> Quat {
    Quat::from_rotation_y(k as f32 * std::f32::consts::FRAC_PI_2)
}

/// One face of the hall on side `k`: centre `c` (the side's frame), half
/// axes `u` and `v` (its normal is `u x v`), lit where it is.
fn quad(out: &mut MeshData, k: usize, c: Vec3, u: Vec3, v: Vec3, color: [f32; 4], light: f32) {
    let q = side(k);
    let normal = q * u.cross(v).normalize();
    let base = out.vertices.len() as u32;
    for (a, b) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
        let p = CENTRE + q * (c + u * a + v * b);
        let l = light * hall_light(p, normal);
        let rgb = [color[0] * l, color[1] * l, color[2] * l, 1.0];
        out.vertices.push(Vertex::coloured(p, normal, rgb));
    }
    out.indices
        .extend([base, base + 1, base + 2, base, base + 2, base + 3]);
}

/// The hall without its people, as one mesh: only the faces seen from the
/// ring (the rows' risers and treads, the walls' and roof's inner faces),
/// in panels so the light falls off across them.
pub fn mesh() -> MeshData {
    let mut m = MeshData::default();
    let y0 = floor_y() - CENTRE.y;
    let reach = FIRST_ROW + ROWS as f32 * ROW_DEPTH;
    let mut n = 0u32;
    let mut next = || {
        n += 1;
        0.85 + 0.3 * hash(n)
    };
    let (x, y, z) = (Vec3::X, Vec3::Y, Vec3::Z);
    let mut bars = Vec::new();
    for k in 0..4 {
        // The floor between the platform and the first row: a pinwheel,
        // each side's running on past one corner.
        let panels = 6;
        let apron = HALF + 0.6;
        let w = (FIRST_ROW + apron) / panels as f32;
        let depth = (FIRST_ROW - apron) / 2.0;
        for i in 0..panels {
            let c = Vec3::new(-apron + (i as f32 + 0.5) * w, y0, apron + depth);
            quad(
                &mut m,
                k,
                c,
                x * w / 2.0,
                -z * depth,
                shade(FLOOR, next()),
                1.0,
            );
        }
        // The rows: each a riser and a tread, in sections along it.
        for row in 0..ROWS {
            let d = FIRST_ROW + row as f32 * ROW_DEPTH;
            let h = ROW_RISE * (row + 1) as f32;
            let sections = 4;
            let w = (2.0 * d + ROW_DEPTH) / sections as f32;
            for i in 0..sections {
                let cx = -d + (i as f32 + 0.5) * w;
                let color = shade(STAND, next());
                let riser = Vec3::new(cx, y0 + h - ROW_RISE / 2.0, d);
                quad(
                    &mut m,
                    k,
                    riser,
                    -x * w / 2.0,
                    y * ROW_RISE / 2.0,
                    color,
                    1.0,
                );
                let tread = Vec3::new(cx, y0 + h, d + ROW_DEPTH / 2.0);
                quad(
                    &mut m,
                    k,
                    tread,
                    x * w / 2.0,
                    -z * ROW_DEPTH / 2.0,
                    color,
                    0.8,
                );
            }
        }
        // The wall behind the last row, up to the roof, in panels.
        let (cols, levels) = (6, 2);
        let top = y0 + ROWS as f32 * ROW_RISE;
        let (w, hh) = (
            (2.0 * reach + 0.4) / cols as f32,
            (ROOF + y0 - top) / levels as f32,
        );
        for i in 0..cols {
            for j in 0..levels {
                let c = Vec3::new(
                    -reach + (i as f32 + 0.5) * w,
                    top + (j as f32 + 0.5) * hh,
                    reach,
                );
                let (u, v) = (-x * w / 2.0, y * hh / 2.0);
                quad(&mut m, k, c, u, v, shade(WALL, next()), 1.0);
            }
        }
        // The lighting grid: steel trusses under the roof across the hall.
        for i in 0..5 {
            let x = -reach + (i as f32 + 0.5) * 2.0 * reach / 5.0;
            let a = CENTRE + side(k) * Vec3::new(x, y0 + ROOF - 1.5, 0.0);
            let b = CENTRE + side(k) * Vec3::new(x, y0 + ROOF - 1.5, reach);
            bars.push(bar(a, b, 0.12, STEEL));
        }
    }
    // The roof, in panels, facing down.
    let cols = 6;
    let w = 2.0 * (reach + 0.4) / cols as f32;
    for i in 0..cols {
        for j in 0..cols {
            let c = Vec3::new(
                -reach - 0.4 + (i as f32 + 0.5) * w,
                y0 + ROOF,
                -reach - 0.4 + (j as f32 + 0.5) * w,
            );
            quad(
                &mut m,
                0,
                c,
                x * w / 2.0,
                z * w / 2.0,
                shade(WALL, 0.6 * next()),
                1.0,
            );
        }
    }
    let mut append = |part: MeshData| {
        let base = m.vertices.len() as u32;
        m.vertices.extend(part.vertices);
        m.indices.extend(part.indices.iter().map(|i| i + base));
    };
    append(bake_with(bars, &hall_light));
    // The grid's lamps, faces down, as bright as they are.
    for p in grid_lamps() {
        let base = m.vertices.len() as u32;
        for (a, b) in [(-1.0, -1.0), (-1.0, 1.0), (1.0, 1.0), (1.0, -1.0)] {
            let v = p + Vec3::new(0.22 * a, -0.06, 0.22 * b);
            m.vertices
                .push(Vertex::coloured(v, Vec3::NEG_Y, [2.5, 2.4, 2.1, 1.0]));
        }
        m.indices
            .extend([base, base + 1, base + 2, base, base + 2, base + 3]);
    }
    m
}

/// A lamp of the lighting grid: where it hangs, world.
pub fn grid_lamps() -> Vec<Vec3> {
    let reach = FIRST_ROW + ROWS as f32 * ROW_DEPTH;
    let y = floor_y() + ROOF - 1.7;
    let mut out = Vec::new();
    for k in 0..4 {
        for i in 0..5 {
            let x = -reach + (i as f32 + 0.5) * 2.0 * reach / 5.0;
            for j in 1..4 {
                let z = j as f32 * reach / 4.0;
                out.push(CENTRE + side(k) * Vec3::new(x, y - CENTRE.y, z));
            }
        }
    }
    out
}

/// Clothes, skin and hair, linear RGB: a crowd in dark winter clothes
/// with some colour, people of every complexion.
const CLOTHES: [[f32; 3]; 10] = [
    [0.02, 0.02, 0.025],
    [0.05, 0.06, 0.12],
    [0.15, 0.15, 0.16],
    [0.5, 0.5, 0.48],
    [0.35, 0.03, 0.03],
    [0.03, 0.12, 0.05],
    [0.08, 0.05, 0.03],
    [0.6, 0.45, 0.2],
    [0.02, 0.1, 0.3],
    [0.25, 0.02, 0.1],
];
const SKIN: [[f32; 3]; 5] = [
    [0.75, 0.5, 0.38],
    [0.6, 0.38, 0.26],
    [0.42, 0.24, 0.15],
    [0.25, 0.13, 0.08],
    [0.12, 0.06, 0.04],
];
const HAIR: [[f32; 3]; 4] = [
    [0.01, 0.008, 0.006],
    [0.08, 0.04, 0.02],
    [0.4, 0.3, 0.15],
    [0.35, 0.35, 0.35],
];

fn rgba(c: [f32; 3]) -> [f32; 4] {
    [c[0], c[1], c[2], 1.0]
}

/// The seats of the crowd: (side, position in the side's frame, seat
/// number), most seats taken.
fn seats() -> Vec<(usize, Vec3, u32)> {
    let y0 = floor_y() - CENTRE.y;
    let mut out = Vec::new();
    let mut n = 0u32;
    for k in 0..4 {
        for row in 0..ROWS {
            let d = FIRST_ROW + row as f32 * ROW_DEPTH + 0.5;
            let y = y0 + ROW_RISE * (row + 1) as f32;
            // Along the row, short of the corners (the next side's rows).
            let count = ((2.0 * (d - 0.6)) / SEAT) as i32;
            for i in 0..count {
                n += 1;
                // A fight night's house: a third of the seats empty.
                if hash(n ^ 0xA5A5) < 0.33 {
                    continue;
                }
                let x = -(d - 0.6) + (i as f32 + 0.5) * SEAT;
                out.push((k, Vec3::new(x, y, d), n));
            }
        }
    }
    out
}

/// Groups of the crowd in each half side (each stands at its own
/// excitement).
const MOODS: usize = 4;

/// A box of the crowd on side `k`, centred `at` (the side's frame) with
/// half extents `half`: only the faces seen from the ring (the front, the
/// top in `top`'s colour, and with `flank` the side toward the ring's
/// middle), the front in bands from the bottom up (`front`: where each
/// band ends, 0-1, and its colour).
fn open_box(
    out: &mut MeshData,
    k: usize,
    at: Vec3,
    half: Vec3,
    front: &[(f32, [f32; 4])],
    top: [f32; 4],
    flank: bool,
) {
    let (x, y, z) = (Vec3::X, Vec3::Y, Vec3::Z);
    front_only(out, k, at, half, front);
    let body = front[0].1;
    quad(out, k, at + y * half.y, x * half.x, -z * half.z, top, 0.65);
    // The camera is near the ring's middle: a person left of it (x < 0)
    // shows the right side (+x), and the other way round (far away, a
    // sliver: `flank` false leaves it out).
    if !flank {
        return;
    }
    if at.x < 0.0 {
        quad(out, k, at + x * half.x, -z * half.z, y * half.y, body, 0.65);
    } else {
        quad(out, k, at - x * half.x, z * half.z, y * half.y, body, 0.65);
    }
}

/// The front of a box of the crowd, in bands (see [`open_box`]).
fn front_only(out: &mut MeshData, k: usize, at: Vec3, half: Vec3, front: &[(f32, [f32; 4])]) {
    let mut from = 0.0;
    for &(to, color) in front {
        let (lo, hi) = (
            at.y - half.y + 2.0 * half.y * from,
            at.y - half.y + 2.0 * half.y * to,
        );
        let c = Vec3::new(at.x, (lo + hi) / 2.0, at.z - half.z);
        quad(
            out,
            k,
            c,
            -Vec3::X * half.x,
            Vec3::Y * (hi - lo) / 2.0,
            color,
            0.65,
        );
        from = to;
    }
}

/// Rows from which people are drawn as one flat front, trunk, face and
/// hair in bands: above your eyes (their tops unseen), and small enough
/// that the neck's step is a pixel or two.
const FAR_ROW: f32 = 6.0;

/// Group `g`'s side (0-3), half of it (0: x < 0 in the side's frame, 1:
/// x >= 0) and mood.
fn group(g: usize) -> (usize, usize, usize) {
    (g / (2 * MOODS), (g / MOODS) % 2, g % MOODS)
}

/// Group `g`'s people, seated or standing with their arms up, as one mesh
/// lit where they sit.
pub fn crowd(g: usize, standing: bool) -> MeshData {
    let mut out = MeshData::default();
    let (k, half, mood) = group(g);
    let far = FIRST_ROW + FAR_ROW * ROW_DEPTH;
    for (_, at, n) in seats()
        .into_iter()
        .filter(|s| s.0 == k && usize::from(s.1.x >= 0.0) == half)
        .filter(|s| (hash(s.2 + 31) * MOODS as f32) as usize == mood)
    {
        let (r1, r2, r3, r4) = (hash(n), hash(n + 7919), hash(n + 104_729), hash(n + 3));
        let cloth = rgba(CLOTHES[(r1 * CLOTHES.len() as f32) as usize]);
        let skin = rgba(SKIN[(r2 * SKIN.len() as f32) as usize]);
        let hair = rgba(HAIR[(r3 * HAIR.len() as f32) as usize]);
        let tall = 0.9 + 0.2 * r4;
        let lift = if standing { 0.42 } else { 0.0 };
        // Not in a grid: each sits a little off the seat's centre, broad
        // or slight.
        let at = at + Vec3::new(0.16 * (r3 - 0.5), 0.0, 0.12 * (r1 - 0.5));
        let broad = 0.85 + 0.3 * hash(n + 17);
        if at.z > far {
            // Above your eyes: only a front is seen. Trunk and face as
            // bands of one (a few pixels: the hair is under one).
            let half = Vec3::new(0.17 * broad, 0.42 * tall, 0.11 * broad);
            let centre = at + Vec3::Y * (0.46 * tall + lift);
            let bands = [(0.66, cloth), (1.0, skin)];
            front_only(&mut out, k, centre, half, &bands);
        } else {
            let trunk = Vec3::new(0.2 * broad, 0.27 * tall, 0.12 * broad);
            let centre = at + Vec3::Y * (0.32 * tall + lift);
            open_box(&mut out, k, centre, trunk, &[(1.0, cloth)], cloth, true);
            let head = Vec3::new(0.085, 0.12, 0.1);
            let centre = at + Vec3::new(0.0, 0.71 * tall + lift, -0.02);
            open_box(&mut out, k, centre, head, &[(1.0, skin)], hair, false);
        }
        if standing {
            for s in [-1.0, 1.0] {
                let arm = Vec3::new(s * 0.26 * broad, 0.88 * tall + lift, -0.02);
                let half = Vec3::new(0.05, 0.26, 0.05);
                open_box(
                    &mut out,
                    k,
                    at + arm,
                    half,
                    &[(0.85, cloth), (1.0, skin)],
                    skin,
                    false,
                );
            }
        }
    }
    out
}

/// The excitement at which a group of mood `m` stands.
fn threshold(m: usize) -> f32 {
    0.15 + 0.75 * m as f32 / (MOODS - 1) as f32
}

/// Whether the box `lo`-`hi` (side `k`'s frame) is wholly outside the view
/// of `view_proj` (all its corners beyond one of the clip planes).
fn unseen(view_proj: Mat4, k: usize, lo: Vec3, hi: Vec3) -> bool {
    let corners: [glam::Vec4; 8] = std::array::from_fn(|i| {
        let p = Vec3::new(
            if i & 1 == 0 { lo.x } else { hi.x },
            if i & 2 == 0 { lo.y } else { hi.y },
            if i & 4 == 0 { lo.z } else { hi.z },
        );
        view_proj * (CENTRE + side(k) * p).extend(1.0)
    });
    let all = |f: &dyn Fn(&glam::Vec4) -> bool| corners.iter().all(f);
    all(&|c| c.x < -c.w)
        || all(&|c| c.x > c.w)
        || all(&|c| c.y < -c.w)
        || all(&|c| c.y > c.w)
        || all(&|c| c.z < 0.0)
        || all(&|c| c.z > c.w)
}

/// The hall's draws: the hall, and each group of the crowd seated or on
/// its feet (cheering: bouncing on its toes at about 2 Hz) for the crowd's
/// `excitement` 0-1 at time `t` s; the crowd outside the view of
/// `view_proj` is left out (behind you, it would cost a software
/// rasteriser as much as in front).
pub fn draws(excitement: f32, t: f32, view_proj: Mat4) -> Vec<Draw> {
    let mut out = Vec::new();
    let y0 = floor_y() - CENTRE.y;
    let reach = FIRST_ROW + ROWS as f32 * ROW_DEPTH;
    let top = y0 + ROWS as f32 * ROW_RISE + 2.0;
    for g in 0..GROUPS {
        let (k, half, mood) = group(g);
        let (x0, x1) = if half == 0 {
            (-reach, 0.0)
        } else {
            (0.0, reach)
        };
        let (lo, hi) = (Vec3::new(x0, y0, FIRST_ROW), Vec3::new(x1, top, reach));
        if unseen(view_proj, k, lo, hi) {
            continue;
        }
        let standing = excitement > threshold(mood);
        let bounce = if standing {
            let phase = g as f32 * 1.7;
            0.06 * (std::f32::consts::TAU * 2.1 * t + phase).sin().abs()
        } else {
            0.0
        };
        out.push(Draw {
            mesh: MeshKey::Crowd {
                group: g as u8,
                standing,
            },
            model: Mat4::from_translation(Vec3::Y * bounce),
            color: [1.0; 4],
            material: Material::Emissive,
        });
    }
    // The hall behind its people: a software rasteriser then skips the
    // seats and walls they hide (early depth test).
    out.push(Draw {
        mesh: MeshKey::Hall,
        model: Mat4::IDENTITY,
        color: [1.0; 4],
        material: Material::Emissive,
    });
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Over a thousand people fill the rows, in every group; the hall
    /// closes over the ring (nothing of the clear colour shows above the
    /// stands); and an excited crowd stands, group by group.
    #[test]
    fn the_hall_is_full_and_rises_with_the_bout() {
        let seats = seats();
        assert!(seats.len() > 1000, "{}", seats.len());
        for g in 0..GROUPS {
            assert!(!crowd(g, false).indices.is_empty());
        }
        let everything =
            glam::camera::rh::proj::directx::orthographic(-50.0, 50.0, -50.0, 50.0, -100.0, 100.0);
        let m = mesh();
        let top = m.vertices.iter().map(|v| v.pos[1]).fold(f32::MIN, f32::max);
        assert!(top >= floor_y() + ROOF - 0.01, "{top}");
        let standing = |e| {
            draws(e, 0.0, everything)
                .iter()
                .filter(|d| matches!(d.mesh, MeshKey::Crowd { standing: true, .. }))
                .count()
        };
        assert_eq!(standing(0.0), 0);
        assert!(standing(0.5) > 0 && standing(0.5) < GROUPS);
        assert_eq!(standing(1.0), GROUPS);
        // Lit from the ring: the front rows brighter than the back.
        let front = hall_light(CENTRE + Vec3::new(0.0, 0.0, FIRST_ROW), -Vec3::Z);
        let back = hall_light(CENTRE + Vec3::new(0.0, 5.0, FIRST_ROW + 12.0), -Vec3::Z);
        assert!(front > 2.0 * back, "{front} {back}");
    }

    /// From your place in the ring, facing the VH (toward -Z), the crowd
    /// behind you is not drawn; the crowd in front is.
    #[test]
    fn the_crowd_behind_you_is_not_drawn() {
        let eye = Vec3::new(0.0, 1.6, 0.9);
        let view = glam::camera::rh::view::look_at_mat4(eye, eye - Vec3::Z, Vec3::Y);
        let proj = glam::camera::rh::proj::directx::perspective(
            58f32.to_radians(),
            16.0 / 9.0,
            0.02,
            30.0,
        );
        let sides: Vec<usize> = draws(0.0, 0.0, proj * view)
            .iter()
            .filter_map(|d| match d.mesh {
                MeshKey::Crowd { group, .. } => Some(super::group(group as usize).0),
                _ => None,
            })
            .collect();
        assert!(sides.contains(&2), "in front: {sides:?}");
        assert!(!sides.contains(&0), "behind: {sides:?}");
    }
}
