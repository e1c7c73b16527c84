//! A procedural, linear-blend-skinned body (torso in a sleeveless vest,
//! neck, arms, boxing gloves; trunks, legs and boxing shoes) drawn for the
//! VH and for your avatar in place of the collision shapes. The head is the
//! face mesh, drawn apart. The legs' bones follow the lower body's joint
//! centres ([`shisen::physics::lower::Leg`]).
//!
//! Construction: every part is a grid of rings (a tube) in the rest pose of
//! [`BodyPlan`] (arms hanging, forearms forward), closed by poles. The torso's
//! rings are superellipses (flatter at the back, pectorals added) that close
//! over the shoulders into the neck; the neck is a tube leaning forward whose
//! top sits inside the head; each arm starts with a ball around the shoulder
//! pivot (the deltoid, sunk into the torso, so the shoulder stays closed
//! whatever the arm does), runs down the upper arm, bends round the elbow
//! about an axis on the crook's side and ends inside the glove; the glove is
//! a padded superellipse fist with a thumb along its inner side and a cuff.
//! Parts overlap instead of sharing vertices. Weights blend torso and head
//! along the neck; upper arm and forearm across the elbow (on the crook's
//! side by the length along the crook, on the outer side across the plane
//! bisecting the bend, so that neither side folds, tears or sinks from
//! straight to fully bent); torso and upper arm around the shoulder. Gloves
//! are rigid on their forearm.
//!
//! A [`Pose`] holds each bone's current world transform times its rest world
//! transform's inverse: all identity is the rest pose.

mod shape;

pub use shape::{VEST_ARMHOLE, VEST_HEM, VEST_NECK};

use glam::{Mat3, Mat4, Quat, Vec3};
use shisen::physics::body::{BodyPlan, Seg, arm_ik};
use shisen::physics::lower::{BodyParams, Carried, Leg, LowerBody, WAIST_REST};

use super::geometry::Vertex;

/// A skinning bone; each glove rides its forearm.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[repr(u8)]
pub enum Bone {
    /// The torso (root).
    Torso,
    /// The head (the neck's upper part follows it).
    Head,
    /// Left (+X) upper arm.
    UpperArmL,
    /// Left forearm and glove.
    ForearmL,
    /// Right upper arm.
    UpperArmR,
    /// Right forearm and glove.
    ForearmR,
    /// The pelvis (trunks), under the waist joint.
    Pelvis,
    /// Left thigh.
    ThighL,
    /// Left shank.
    ShinL,
    /// Left foot.
    FootL,
    /// Right thigh.
    ThighR,
    /// Right shank.
    ShinR,
    /// Right foot.
    FootR,
}

impl Bone {
    /// Number of bones.
    pub const COUNT: usize = 13;
    /// Every bone, in index order.
    pub const ALL: [Bone; Bone::COUNT] = {
        use Bone::*;
        [
            Torso, Head, UpperArmL, ForearmL, UpperArmR, ForearmR, Pelvis, ThighL, ShinL, FootL,
            ThighR, ShinR, FootR,
        ]
    };

    /// Thigh, shank and foot of `side` (0 = left).
    pub fn leg(side: usize) -> [Bone; 3] {
        [
            [Bone::ThighL, Bone::ShinL, Bone::FootL],
            [Bone::ThighR, Bone::ShinR, Bone::FootR],
        ][side]
    }

    /// Upper arm of `side` (0 = left).
    pub fn upper_arm(side: usize) -> Bone {
        [Bone::UpperArmL, Bone::UpperArmR][side]
    }

    /// Forearm (and glove) of `side` (0 = left).
    pub fn forearm(side: usize) -> Bone {
        [Bone::ForearmL, Bone::ForearmR][side]
    }

    /// The physics segment that drives the bone (the legs' are not
    /// physical).
    pub fn segment(self) -> Option<Seg> {
        [
            Seg::Torso,
            Seg::Head,
            Seg::UpperArmL,
            Seg::ForearmL,
            Seg::UpperArmR,
            Seg::ForearmR,
        ]
        .get(self as usize)
        .copied()
    }
}

/// Each bone's world transform relative to its rest (current * rest^-1),
/// indexed by `Bone as usize`.
pub type Pose = [Mat4; Bone::COUNT];

/// The rest pose.
pub const REST_POSE: Pose = [Mat4::IDENTITY; Bone::COUNT];

/// Colours of the body's regions, linear RGBA.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BodyStyle {
    /// Neck, shoulders, arms.
    pub skin: [f32; 4],
    /// The sleeveless vest on the torso.
    pub shirt: [f32; 4],
    /// Gloves.
    pub glove: [f32; 4],
    /// The stripe round each glove's cuff.
    pub cuff: [f32; 4],
    /// Boxing trunks.
    pub trunks: [f32; 4],
    /// Boxing shoes.
    pub shoes: [f32; 4],
}

impl BodyStyle {
    /// The VH: the face's skin, a navy vest, red gloves, white cuff stripes.
    pub const VH: BodyStyle = BodyStyle {
        skin: SKIN,
        shirt: [0.16, 0.22, 0.40, 1.0],
        glove: [0.70, 0.06, 0.05, 1.0],
        cuff: CUFF,
        trunks: [0.55, 0.05, 0.06, 1.0],
        shoes: [0.05, 0.05, 0.06, 1.0],
    };
    /// You: the same skin, a grey vest, blue gloves.
    pub const YOU: BodyStyle = BodyStyle {
        skin: SKIN,
        shirt: [0.30, 0.31, 0.33, 1.0],
        glove: [0.08, 0.22, 0.75, 1.0],
        cuff: CUFF,
        trunks: [0.06, 0.14, 0.45, 1.0],
        shoes: [0.85, 0.85, 0.82, 1.0],
    };
}

/// Skin, as the face's ([`shisen_face::appearance::FaceStyle`]).
pub const SKIN: [f32; 4] = {
    let s = shisen_face::appearance::FaceStyle::DEFAULT.skin;
    [s[0], s[1], s[2], 1.0]
};
const CUFF: [f32; 4] = [0.92, 0.92, 0.88, 1.0];

/// A rest-pose vertex with its skinning weights.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SkinVertex {
    /// Rest position, world metres.
    pub pos: [f32; 3],
    /// Rest unit normal, world frame.
    pub normal: [f32; 3],
    /// Linear RGBA colour.
    pub color: [f32; 4],
    /// The point's position in the torso's design frame, from which the
    /// renderer draws the vest's neckline and armholes per pixel
    /// ([`VEST_NECK`], [`VEST_ARMHOLE`]); far outside them off the torso.
    pub vest: [f32; 3],
    /// Bones (`Bone as u8`) of the weights; unused slots have weight 0.
    pub bones: [u8; 4],
    /// Weights, non-negative, summing to 1.
    pub weights: [f32; 4],
}

/// Which part a vertex belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Part {
    Torso,
    Neck,
    Arm(usize),
    Cuff(usize),
    Fist(usize),
    Leg,
}

/// Levels of detail of a body's triangles, the same vertices: 0 the fine
/// mesh; 1 each grid over every other ring or every other column,
/// whichever departs less from the fine surface (half the triangles); 2
/// over both (a quarter).
pub const LEVELS: usize = 3;

/// One grid of the body (a part, or a cap): its triangles at each level of
/// detail ([`Lists::level`]), the vertices they use, and how far each
/// level departs from the fine one. Pieces overlap rather than share
/// vertices, so each can be drawn at any level, or left out, without
/// opening a crack.
#[derive(Clone, Debug, PartialEq)]
pub struct Piece {
    /// Its range of each level's triangle list.
    pub ranges: [std::ops::Range<u32>; LEVELS],
    /// Its vertices.
    pub vertices: std::ops::Range<u32>,
    /// The largest distance of a point a level skips from that level's
    /// surface, m (its geometric error; 0 at the fine level).
    pub errors: [f32; LEVELS],
}

/// A triangle list (counter-clockwise seen from outside) at each level of
/// detail, over the same vertices, and the grids it is made of.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Lists {
    levels: [Vec<u32>; LEVELS],
    pieces: Vec<Piece>,
}

impl Lists {
    /// The triangle list at level of detail `level` (below [`LEVELS`]; 0
    /// is the fine one).
    pub fn level(&self, level: usize) -> &[u32] {
        &self.levels[level]
    }

    /// The grids the lists are made of, in order.
    pub fn pieces(&self) -> &[Piece] {
        &self.pieces
    }
}

/// The skinned upper-body mesh.
#[derive(Clone, Debug, PartialEq)]
pub struct BodyMesh {
    vertices: Vec<SkinVertex>,
    whole: Lists,
    arms: Lists,
    parts: Vec<Part>,
    /// The colour of bare skin in the vest's openings, linear RGB.
    skin: [f32; 3],
}

impl BodyMesh {
    /// Rest vertices with their weights.
    pub fn vertices(&self) -> &[SkinVertex] {
        &self.vertices
    }

    /// The whole body's triangles.
    pub fn whole(&self) -> &Lists {
        &self.whole
    }

    /// Triangles of the forearms, gloves and the lower half of the upper
    /// arms, with a cap closing each upper arm's cut, for the first-person
    /// view (indexing the same skinned vertices as [`BodyMesh::whole`]).
    pub fn arms(&self) -> &Lists {
        &self.arms
    }

    /// Linear blend skinning: `out` is cleared and filled with one posed
    /// vertex per rest vertex, world frame (allocates only while `out`
    /// grows).
    pub fn skin(&self, pose: &Pose, out: &mut Vec<Vertex>) {
        out.clear();
        out.extend(self.vertices.iter().map(|v| {
            let (p, n) = (Vec3::from_array(v.pos), Vec3::from_array(v.normal));
            let (mut sp, mut sn) = (Vec3::ZERO, Vec3::ZERO);
            for (&b, &w) in v.bones.iter().zip(&v.weights) {
                if w > 0.0 {
                    let m = &pose[b as usize];
                    sp += w * m.transform_point3(p);
                    sn += w * m.transform_vector3(n);
                }
            }
            // The shader reads the vest's design point from `rest` (x, y)
            // and `paint` (z, then the bare skin's colour).
            let [x, y, z] = v.vest;
            Vertex {
                rest: [x, y],
                paint: [z, self.skin[0], self.skin[1], self.skin[2]],
                ..Vertex::coloured(sp, sn.normalize_or(n), v.color)
            }
        }));
    }
}

/// The VH's pose from its physics segments: `world_poses(segment)` gives a
/// segment's current world position (its centre, where [`BodyPlan`] puts it
/// at rest) and rotation (identity at rest); `legs` are the lower body's
/// joint centres now (`None`: the legs stay at rest).
pub fn vh_pose(
    world_poses: impl Fn(Seg) -> (Vec3, Quat),
    plan: &BodyPlan,
    legs: Option<&[Leg; 2]>,
) -> Pose {
    let mut pose = REST_POSE;
    for b in Bone::ALL {
        if let Some(s) = b.segment() {
            let (p, q) = world_poses(s);
            pose[b as usize] = Mat4::from_rotation_translation(q, p)
                * Mat4::from_translation(-plan.segments[s.index()].centre);
        }
    }
    if let Some(legs) = legs {
        set_legs(&mut pose, legs);
    }
    pose
}

/// The legs at rest (the default stance), the mesh's rest pose.
pub fn rest_legs() -> [Leg; 2] {
    let p = BodyParams::default();
    LowerBody::new(&p).legs(&p)
}

/// A bone's frame: origin `a`, first axis along `a -> b`, third axis
/// normal to the plane it shares with `toward`.
fn bone_frame(a: Vec3, b: Vec3, toward: Vec3) -> Mat4 {
    let u = (b - a).normalize();
    let w = u.cross(toward - a).normalize_or(Vec3::X);
    let v = w.cross(u);
    Mat4::from_mat3_translation(Mat3::from_cols(u, v, w), a)
}

/// Set the pelvis and legs' bones from the legs' joint centres now.
fn set_legs(pose: &mut Pose, legs: &[Leg; 2]) {
    let rest = rest_legs();
    // The pelvis: through its hip joints, upright.
    let pelvis = |l: &[Leg; 2]| {
        let [r, l] = [l[1].hip, l[0].hip].map(|v| v.as_vec3());
        bone_frame(r, l, r + Vec3::Y)
    };
    pose[Bone::Pelvis as usize] = pelvis(legs) * pelvis(&rest).inverse();
    for side in 0..2 {
        let frames = |l: &Leg| {
            let [h, k, a, t] = [l.hip, l.knee, l.ankle, l.toe].map(|v| v.as_vec3());
            [
                bone_frame(h, k, a),
                bone_frame(k, a, h),
                bone_frame(l.heel.as_vec3(), t, l.heel.as_vec3() + Vec3::Y),
            ]
        };
        let (now, then) = (frames(&legs[side]), frames(&rest[side]));
        for (i, b) in Bone::leg(side).into_iter().enumerate() {
            pose[b as usize] = now[i] * then[i].inverse();
        }
    }
}

/// The waist joint at rest, single precision.
fn waist_rest() -> Vec3 {
    WAIST_REST.as_vec3()
}

/// Rest landmarks of one arm: shoulder, elbow, glove centre, unit
/// directions of upper arm and forearm.
fn arm_frame(plan: &BodyPlan, side: usize) -> (Vec3, Vec3, Vec3, Vec3, Vec3) {
    let s = plan.segments[Bone::upper_arm(side).segment().expect("physical").index()].pivot;
    let e = plan.segments[Bone::forearm(side).segment().expect("physical").index()].pivot;
    let g = plan.segments[[Seg::GloveL, Seg::GloveR][side].index()].centre;
    (s, e, g, (e - s).normalize(), (g - e).normalize())
}
/// Upper arm and forearm transforms (rest frame) of `side` for the joint
/// rotations of [`arm_ik`]: shoulder relative to the torso, elbow relative
/// to the upper arm.
fn arm_mats(plan: &BodyPlan, side: usize, shoulder: Quat, elbow: Quat) -> [Mat4; 2] {
    let about = |q: Quat, p: Vec3| {
        Mat4::from_translation(p) * Mat4::from_quat(q) * Mat4::from_translation(-p)
    };
    let (s, e, ..) = arm_frame(plan, side);
    let upper = about(shoulder, s);
    [upper, upper * about(elbow, e)]
}

/// Your avatar's pose: its body ([`Carried`], in its own frame, placed in
/// the world by `frame`: facing the VH) with the trunk on its waist and the
/// legs stepping; arms solved with [`arm_ik`] so the glove centres reach
/// `gloves` (`gloves[0]` your left).
pub fn avatar_pose(
    plan: &BodyPlan,
    frame: Mat4,
    body: &Carried,
    params: &BodyParams,
    gloves: [Vec3; 2],
) -> Pose {
    let lower = &body.lower;
    let waist = waist_rest();
    let root = frame
        * Mat4::from_translation(waist + lower.waist_offset().as_vec3())
        * Mat4::from_quat(lower.trunk_rotation().as_quat())
        * Mat4::from_translation(-waist);
    let inv = root.inverse();
    let mut pose = [root; Bone::COUNT];
    let legs = lower.legs(params).map(|l| {
        let f = frame.as_dmat4();
        let at = |v: glam::DVec3| f.transform_point3(v);
        Leg {
            hip: at(l.hip),
            knee: at(l.knee),
            ankle: at(l.ankle),
            toe: at(l.toe),
            heel: at(l.heel),
        }
    });
    set_legs(&mut pose, &legs);
    for side in 0..2 {
        let target = inv.transform_point3(gloves[side]);
        let (qs, qe) = arm_ik(side, target.as_dvec3());
        let [upper, fore] = arm_mats(plan, side, qs, qe);
        pose[Bone::upper_arm(side) as usize] = root * upper;
        pose[Bone::forearm(side) as usize] = root * fore;
    }
    pose
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f32::consts::PI;

    fn mesh() -> (BodyPlan, BodyMesh) {
        let plan = BodyPlan::default();
        let m = BodyMesh::new(&plan, &BodyStyle::VH);
        (plan, m)
    }

    fn posed(m: &BodyMesh, pose: &Pose) -> Vec<Vec3> {
        let mut out = Vec::new();
        m.skin(pose, &mut out);
        out.iter().map(|v| Vec3::from_array(v.pos)).collect()
    }

    fn tris<'a>(
        m: &'a BodyMesh,
        p: &'a [Vec3],
    ) -> impl Iterator<Item = ([u32; 3], [Vec3; 3])> + 'a {
        m.whole()
            .level(0)
            .as_chunks::<3>()
            .0
            .iter()
            .map(|t| (*t, t.map(|i| p[i as usize])))
    }

    /// Area-weighted centroid of the fist's surface of `side`.
    fn fist(m: &BodyMesh, p: &[Vec3], side: usize) -> Vec3 {
        let (mut sum, mut area) = (Vec3::ZERO, 0.0);
        for (t, [a, b, c]) in tris(m, p) {
            if t.iter().all(|&i| m.parts[i as usize] == Part::Fist(side)) {
                let s = (b - a).cross(c - a).length();
                (sum, area) = (sum + s * (a + b + c) / 3.0, area + s);
            }
        }
        sum / area
    }

    /// The VH's arms at the given shoulder and elbow rotations, or reaching
    /// for glove targets.
    fn arms(plan: &BodyPlan, rot: impl Fn(usize) -> (Quat, Quat)) -> Pose {
        let mut pose = REST_POSE;
        for side in 0..2 {
            let (qs, qe) = rot(side);
            let [u, f] = arm_mats(plan, side, qs, qe);
            (
                pose[Bone::upper_arm(side) as usize],
                pose[Bone::forearm(side) as usize],
            ) = (u, f);
        }
        pose
    }

    fn reach(plan: &BodyPlan, targets: [Vec3; 2]) -> Pose {
        arms(plan, |side| arm_ik(side, targets[side].as_dvec3()))
    }

    /// Largest edge stretch, and the number of triangles whose skinned
    /// normal opposes their rest normal carried by their vertices' bones.
    fn distortion(m: &BodyMesh, pose: &Pose, keep: impl Fn(Part) -> bool) -> (f32, usize) {
        let (p0, p1) = (posed(m, &REST_POSE), posed(m, pose));
        let (mut stretch, mut flips) = (0.0f32, 0);
        for ((t, [a, b, c]), (_, [a1, b1, c1])) in tris(m, &p0).zip(tris(m, &p1)) {
            if !t.iter().all(|&i| keep(m.parts[i as usize])) {
                continue;
            }
            for (e0, e1) in [(b - a, b1 - a1), (c - b, c1 - b1), (a - c, a1 - c1)] {
                stretch = stretch.max(e1.length() / e0.length());
            }
            let n0 = (b - a).cross(c - a);
            let carried: Vec3 = (t.iter())
                .flat_map(|&i| {
                    m.vertices[i as usize]
                        .bones
                        .into_iter()
                        .zip(m.vertices[i as usize].weights)
                })
                .map(|(b, w)| w * pose[b as usize].transform_vector3(n0))
                .sum();
            flips += usize::from((b1 - a1).cross(c1 - a1).dot(carried) <= 0.0);
        }
        (stretch, flips)
    }

    #[test]
    fn weights_are_normalised() {
        let (_, m) = mesh();
        for v in &m.vertices {
            assert!(v.weights.iter().all(|&w| w >= 0.0), "{v:?}");
            assert!((v.weights.iter().sum::<f32>() - 1.0).abs() < 1e-5, "{v:?}");
            assert!(v.bones.iter().all(|&b| (b as usize) < Bone::COUNT));
        }
    }

    #[test]
    fn mesh_is_well_formed() {
        let (plan, m) = mesh();
        let n = m.vertices.len();
        assert!((3000..=10_000).contains(&n), "{n} vertices");
        assert_eq!(m, BodyMesh::new(&plan, &BodyStyle::VH), "deterministic");
        let p = posed(&m, &REST_POSE);
        for list in [m.whole().level(0), m.arms().level(0)] {
            assert!(!list.is_empty() && list.len() % 3 == 0);
            assert!(list.iter().all(|&i| (i as usize) < n));
            for t in list.as_chunks::<3>().0 {
                let [a, b, c] = t.map(|i| p[i as usize]);
                assert!(
                    (b - a).cross(c - a).length() > 2e-8,
                    "degenerate {t:?}: {a} {b} {c}"
                );
            }
        }
        assert!(
            m.vertices
                .iter()
                .all(|v| (Vec3::from_array(v.normal).length() - 1.0).abs() < 1e-4)
        );
        // Outward winding: a positive enclosed volume, about the torso's.
        let o = Vec3::new(0.0, 1.25, 0.0);
        let vol: f32 = tris(&m, &p)
            .map(|(_, [a, b, c])| (a - o).dot((b - o).cross(c - o)) / 6.0)
            .sum();
        assert!(vol > 0.015, "volume {vol}");
    }

    #[test]
    fn rest_pose_reproduces_rest_vertices() {
        let (_, m) = mesh();
        let mut out = Vec::new();
        m.skin(&REST_POSE, &mut out);
        assert_eq!(out.len(), m.vertices.len());
        for (s, v) in out.iter().zip(&m.vertices) {
            assert!(Vec3::from_array(s.pos).distance(Vec3::from_array(v.pos)) < 1e-6);
            assert!(Vec3::from_array(s.normal).distance(Vec3::from_array(v.normal)) < 1e-5);
            assert_eq!(s.color, v.color);
        }
    }

    #[test]
    fn glove_follows_the_forearm() {
        let (plan, m) = mesh();
        let rest_fist = [0, 1].map(|s| fist(&m, &posed(&m, &REST_POSE), s));
        for targets in [
            [Vec3::new(0.11, 1.56, 0.27), Vec3::new(-0.11, 1.56, 0.27)],
            [Vec3::new(0.0, 1.55, 0.5), Vec3::new(-0.3, 1.3, 0.3)],
        ] {
            // Through vh_pose, from the segments' world poses, torso lunging.
            let lunge = Mat4::from_translation(Vec3::new(0.02, 0.0, 0.1));
            let pose = reach(&plan, targets).map(|m| lunge * m);
            let world = |s: Seg| {
                let m = pose[Bone::ALL
                    .iter()
                    .position(|b| b.segment() == Some(s))
                    .unwrap()];
                (
                    m.transform_point3(plan.segments[s.index()].centre),
                    m.to_scale_rotation_translation().1,
                )
            };
            let from_physics = vh_pose(world, &plan, None);
            for (bone, (a, b)) in Bone::ALL.iter().zip(from_physics.iter().zip(&pose)) {
                if bone.segment().is_some() {
                    assert!(a.abs_diff_eq(*b, 1e-5), "{a} vs {b}");
                }
            }
            let p = posed(&m, &from_physics);
            for side in 0..2 {
                let target = lunge.transform_point3(targets[side]);
                let fore = from_physics[Bone::forearm(side) as usize];
                let got = fist(&m, &p, side);
                assert!(got.distance(fore.transform_point3(rest_fist[side])) < 1e-4);
                assert!(got.distance(target) < 0.01, "{got} vs {target}");
            }
        }
    }

    #[test]
    fn shoes_stand_on_the_canvas_and_follow_the_feet() {
        use glam::DVec3;
        use shisen::physics::lower::BodyCommand;
        let (plan, m) = mesh();
        let shoes = |pose: &Pose| {
            let p = posed(&m, pose);
            let v: Vec<Vec3> = p
                .iter()
                .zip(&m.vertices)
                .filter(|(_, v)| v.color == BodyStyle::VH.shoes)
                .map(|(p, _)| *p)
                .collect();
            let low = v.iter().map(|p| p.y).fold(f32::MAX, f32::min);
            let mean = v.iter().copied().sum::<Vec3>() / v.len() as f32;
            (low, mean)
        };
        let (low, rest_mean) = shoes(&REST_POSE);
        assert!(low.abs() < 0.01, "soles on the canvas at rest: {low}");
        // The lower body walks 0.3 m back; the shoes go with the feet.
        let p = BodyParams::default();
        let mut lb = LowerBody::new(&p);
        for i in 0..2000 {
            let t = f64::from(i) * 1e-3;
            let cmd = BodyCommand {
                pelvis: DVec3::new(0.0, 0.0, -0.3 * (t / 0.5).min(1.0)),
                ..Default::default()
            };
            lb.step(&p, &cmd, t, 1e-3);
        }
        let legs = lb.legs(&p);
        let pose = vh_pose(
            |s| (plan.segments[s.index()].centre, Quat::IDENTITY),
            &plan,
            Some(&legs),
        );
        let (low, mean) = shoes(&pose);
        assert!(
            low.abs() < 0.01,
            "soles on the canvas after stepping: {low}"
        );
        assert!(
            ((mean - rest_mean).z + 0.3).abs() < 0.09,
            "shoes moved back: {}",
            mean - rest_mean
        );
    }

    #[test]
    fn arms_stay_continuous_when_bent() {
        let (plan, m) = mesh();
        let flex = |deg: f32| Quat::from_rotation_x(-deg.to_radians());
        let not_neck = |p: Part| p != Part::Neck;
        // Shoulder flexion, and the elbow's from its rest bend of 90 deg:
        // -90 a straight arm, +30 a 120 deg flexion.
        for (shoulder, elbow) in [(90.0, 30.0), (90.0, -90.0), (0.0, 45.0), (45.0, -60.0)] {
            let pose = arms(&plan, |_| (flex(shoulder), flex(elbow)));
            let (stretch, flips) = distortion(&m, &pose, not_neck);
            assert!(
                stretch < 3.0 && flips == 0,
                "{shoulder}/{elbow}: {stretch} {flips}"
            );
        }
        for targets in [
            [Vec3::new(0.11, 1.56, 0.27), Vec3::new(-0.11, 1.56, 0.27)],
            [Vec3::new(0.05, 1.55, 0.55), Vec3::new(-0.2, 1.6, 0.45)],
        ] {
            let (stretch, flips) = distortion(&m, &reach(&plan, targets), not_neck);
            assert!(
                stretch < 3.0 && flips == 0,
                "{targets:?}: {stretch} {flips}"
            );
        }
        // Straightened, the elbow keeps most of its girth (no collapse).
        let p = posed(&m, &arms(&plan, |_| (Quat::IDENTITY, flex(-90.0))));
        let elbow = plan.segments[Seg::ForearmL.index()].pivot;
        for (i, q) in p.iter().enumerate() {
            if m.parts[i] == Part::Arm(0) && (q.y - elbow.y).abs() < 0.08 {
                let r = (*q - elbow).with_y(0.0).length();
                assert!(r > 0.03, "girth {r} at {}", q.y - elbow.y);
            }
        }
    }

    #[test]
    fn neck_follows_the_head() {
        let (plan, m) = mesh();
        let (pivot, head_c) = (
            plan.segments[Seg::Head.index()].pivot,
            plan.segments[Seg::Head.index()].centre,
        );
        for (yaw, pitch) in [
            (70.0f32, 0.0f32),
            (-70.0, 0.0),
            (0.0, -60.0),
            (0.0, 50.0),
            (50.0, -40.0),
        ] {
            let q = Quat::from_rotation_y(yaw.to_radians())
                * Quat::from_rotation_x(-pitch.to_radians());
            let mut pose = REST_POSE;
            pose[Bone::Head as usize] =
                Mat4::from_translation(pivot) * Mat4::from_quat(q) * Mat4::from_translation(-pivot);
            let (stretch, flips) = distortion(&m, &pose, |p| p == Part::Neck);
            assert!(
                stretch < 3.0 && flips == 0,
                "{yaw}/{pitch}: {stretch} {flips}"
            );
            // The neck's top stays inside the head.
            let head = pose[Bone::Head as usize].transform_point3(head_c);
            for (i, p) in posed(&m, &pose).iter().enumerate() {
                if m.parts[i] == Part::Neck && m.vertices[i].pos[1] > pivot.y + 0.09 {
                    assert!(p.distance(head) < 0.1, "{yaw}/{pitch}: {p}");
                }
            }
        }
    }

    #[test]
    fn avatar_gloves_reach_the_targets() {
        let (plan, m) = mesh();
        let head = Vec3::new(0.03, 1.62, 0.80);
        let rest = posed(&m, &REST_POSE);
        // Your avatar's frame: facing the VH from 0.92 m.
        let frame = Mat4::from_translation(Vec3::new(0.0, 0.0, 0.92)) * Mat4::from_rotation_y(PI);
        let p = BodyParams::default();
        let mut body = Carried::new(&p);
        let local = frame.inverse().transform_point3(head).as_dvec3();
        for i in 0..1000 {
            let vh = glam::DVec3::new(0.0, 1.685, 0.92);
            body.step(&p, local, vh, f64::from(i) * 1e-3, 1e-3);
        }
        let more = [Vec3::new(-0.05, 1.6, 0.45), Vec3::new(0.2, 1.45, 0.7)];
        for gloves in [plan.opponent_gloves, more] {
            let pose = avatar_pose(&plan, frame, &body, &p, gloves);
            // The trunk meets the head (ducked 6 cm, leaning 12 cm in).
            let h =
                pose[Bone::Head as usize].transform_point3(plan.segments[Seg::Head.index()].centre);
            assert!(h.distance(head) < 0.01, "{h} vs {head}");
            let p = posed(&m, &pose);
            for side in 0..2 {
                let (fore, got) = (pose[Bone::forearm(side) as usize], fist(&m, &p, side));
                assert!(got.distance(gloves[side]) < 0.01, "{got} vs {gloves:?}");
                assert!(got.distance(fore.transform_point3(fist(&m, &rest, side))) < 1e-4);
            }
            // Facing the VH: the avatar's left arm is on world -X.
            let mean_x = |side| {
                let arm: Vec<f32> = (0..p.len())
                    .filter(|&i| m.parts[i] == Part::Arm(side))
                    .map(|i| p[i].x)
                    .collect();
                arm.iter().sum::<f32>() / arm.len() as f32
            };
            assert!(mean_x(0) < mean_x(1));
        }
    }
}
