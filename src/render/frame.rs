//! What to draw for one state of the simulation: a list of shaded primitives,
//! the deformed face, overlay lines and labels. Built on the CPU from a
//! [`Sim`] and independent of the GPU, so it is deterministic and testable.

use glam::{DVec3, Mat4, Quat, Vec3};
use rapier3d::prelude::TypedShape;

use shisen::physics::body::{BodyPlan, OpponentPart, Seg};
use shisen::physics::world::Owner;
use shisen::sim::Sim;
use shisen_face::appearance::LipShape;
use shisen_face::mesh::compute_normals;
use shisen_gaze::util::math::{dir_from_yaw_pitch, yaw_pitch_of};

use super::body::{BodyMesh, BodyStyle, LEVELS, Piece, Pose, SKIN, avatar_pose, vh_pose};
use super::camera::{Camera, View};
use super::draw::{Draw, Label, LineVertex, Material, MeshKey, TOP_DIR};
use super::face_parts::{caruncles, hair_shell, lashes, lid_shadows, mouth};
use super::geometry::Vertex;

/// Overlay toggles.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Overlays {
    /// Each eye's line of sight up to the gaze point, and the gaze point.
    pub gaze_rays: bool,
    /// Each eye's field of view.
    pub fov_cones: bool,
    /// Saliency of every visible body as a label.
    pub saliency_labels: bool,
    /// Local axes of every VH segment.
    pub joint_frames: bool,
}

/// Everything needed to draw one picture.
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    /// The camera.
    pub camera: Camera,
    /// Shaded instances.
    pub draws: Vec<Draw>,
    /// Deformed face vertices in the face frame (drawn with [`MeshKey::Face`]).
    pub face: Vec<Vertex>,
    /// Eyelashes on the deformed lid rims, face frame, a triangle list
    /// ([`MeshKey::Lashes`]).
    pub lashes: Vec<Vertex>,
    /// The VH's hair standing off its scalp, face frame, and the
    /// triangles' indices into it at the face's fine and middle levels of
    /// detail ([`MeshKey::HairShell`]).
    pub hair: (Vec<Vertex>, [Vec<u32>; 2]),
    /// The VH's posed body, world frame ([`MeshKey::Body`], indexed by
    /// `Looks::indices`).
    pub body: Vec<Vertex>,
    /// Your posed body, world frame ([`MeshKey::Avatar`], indexed by
    /// [`Frame::avatar_indices`]).
    pub avatar: Vec<Vertex>,
    /// Which of your body's triangles to draw: all of it, or the arms
    /// alone from your own eyes.
    pub avatar_indices: AvatarPart,
    /// The body plan the bodies were posed on (`Looks::of` gives their
    /// triangles).
    pub plan: BodyPlan,
    /// Overlay lines (pairs of vertices).
    pub lines: Vec<LineVertex>,
    /// Overlay labels.
    pub labels: Vec<Label>,
    /// What the top light's shadow map covers: a sphere (centre, radius)
    /// round both fighters and the shadows they cast.
    pub shadow_focus: (Vec3, f32),
    /// Where the face's lips are, for their border drawn per pixel.
    pub lips: LipShape,
}

/// Which part of your body is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AvatarPart {
    /// The whole body (orbit views).
    Whole,
    /// Forearms and gloves (first person).
    Arms,
}

/// The bodies' skinned meshes, built once from the body plan (a pure
/// function of it): the VH's and yours, which differ in colour.
#[derive(Clone)]
pub struct Looks {
    /// The VH's body.
    pub vh: BodyMesh,
    /// Your body.
    pub you: BodyMesh,
}

impl Looks {
    /// The meshes for `plan`: built on first use for the standard plan and
    /// kept; any other plan builds its own (a few milliseconds).
    pub fn of(plan: &BodyPlan) -> std::borrow::Cow<'static, Looks> {
        static STANDARD: std::sync::OnceLock<(BodyPlan, Looks)> = std::sync::OnceLock::new();
        let (standard, looks) = STANDARD.get_or_init(|| {
            let plan = BodyPlan::default();
            let looks = Looks::build(&plan);
            (plan, looks)
        });
        if plan == standard {
            std::borrow::Cow::Borrowed(looks)
        } else {
            std::borrow::Cow::Owned(Looks::build(plan))
        }
    }

    fn build(plan: &BodyPlan) -> Looks {
        Looks {
            vh: BodyMesh::new(plan, &BodyStyle::VH),
            you: BodyMesh::new(plan, &BodyStyle::YOU),
        }
    }

    /// Triangles of a body mesh key at each of its levels of detail, the
    /// fine first ([`Lists::level`](super::body::Lists::level)), and the pieces they are made of.
    pub fn levels(&self, key: MeshKey, part: AvatarPart) -> (Vec<&[u32]>, &[Piece]) {
        let (mesh, arms) = match key {
            MeshKey::Avatar => (&self.you, part == AvatarPart::Arms),
            _ => (&self.vh, false),
        };
        let lists = if arms { mesh.arms() } else { mesh.whole() };
        (
            (0..LEVELS).map(|l| lists.level(l)).collect(),
            lists.pieces(),
        )
    }
}

fn posed(mesh: &BodyMesh, pose: &Pose) -> Vec<Vertex> {
    let mut out = Vec::new();
    mesh.skin(pose, &mut out);
    out
}

const HAIR: [f32; 4] = {
    let h = shisen_face::appearance::FaceStyle::DEFAULT.hair;
    [h[0], h[1], h[2], 1.0]
};
const PROP: [f32; 4] = [0.85, 0.65, 0.12, 1.0];
const WHITE: [f32; 4] = [1.0, 1.0, 1.0, 1.0];
/// Ears are redder than the face: thin, the blood in them shows (the ear
/// and the cheek are the face's reddest parts: Yamamoto et al. 2008,
/// Skin Res. Technol. 14:26).
const EAR: [f32; 4] = [SKIN[0] * 1.02, SKIN[1] * 0.86, SKIN[2] * 0.84, 1.0];
/// Length of drawn field-of-view edges and joint axes, m.
const FOV_LEN: f32 = 0.5;
const AXIS_LEN: f32 = 0.06;

/// Offset of the face frame's origin (midway between the eyes at rest) from
/// the head body's centre, in the head body's frame.
pub fn face_offset(plan: &BodyPlan) -> Vec3 {
    BodyPlan::eyes_midpoint().as_vec3() - plan.segments[Seg::Head.index()].centre
}

/// The shadow map's sphere round two fighters whose heads are at `a` and
/// `b`: centred between them half way up, reaching a body's half width
/// (0.3 m) and the shadow of a 1.8 m head cast down the top light beyond
/// each head.
fn shadow_focus(a: Vec3, b: Vec3) -> (Vec3, f32) {
    let mid = (a + b) / 2.0;
    let centre = Vec3::new(mid.x, 0.8, mid.z);
    let half = Vec3::new(a.x - b.x, 0.0, a.z - b.z).length() / 2.0;
    let spread = 1.8 * Vec3::new(TOP_DIR.x, 0.0, TOP_DIR.z).length() / -TOP_DIR.y;
    (centre, half + 0.3 + spread)
}

impl Frame {
    /// The picture of `sim` now from `view`, for an image of aspect `aspect`.
    pub fn build(sim: &Sim, view: View, overlays: Overlays, aspect: f32) -> Frame {
        let camera = Camera::of(view, sim, aspect);
        let w = &sim.world;
        // Nearest first, the floor last: a software rasteriser then skips
        // shading the floor behind the bodies (early depth test).
        let mut draws = Vec::new();
        let looks = Looks::of(&w.plan);
        let legs = sim.params().body.human.then(|| sim.legs());
        let body = posed(&looks.vh, &vh_pose(|s| w.pose(s), &w.plan, legs.as_ref()));
        let (you_head, you_gloves) = (
            w.position(w.part(OpponentPart::Head)),
            [OpponentPart::LeftGlove, OpponentPart::RightGlove].map(|g| w.position(w.part(g))),
        );
        let avatar_frame = glam::DMat4::from(sim.avatar_frame());
        let avatar = posed(
            &looks.you,
            &avatar_pose(
                &w.plan,
                Mat4::from_cols_array(&avatar_frame.to_cols_array().map(|v| v as f32)),
                &sim.avatar,
                &sim.params().body.standing(),
                you_gloves,
            ),
        );
        for d in [MeshKey::Avatar, MeshKey::Body] {
            draws.push(Draw {
                mesh: d,
                model: Mat4::IDENTITY,
                color: WHITE,
                material: Material::Body,
            });
        }
        if view != View::First {
            // Your head: a skin-coloured head under a short crop.
            let (p, r) = (you_head, w.plan.opponent_head_radius);
            for (centre, half, color) in [
                (p, Vec3::new(0.88, 1.12, 1.0) * r, SKIN),
                (
                    p + Vec3::new(0.0, 0.035, 0.012),
                    Vec3::new(0.93, 1.0, 0.98) * r,
                    HAIR,
                ),
            ] {
                draws.push(Draw {
                    mesh: MeshKey::Sphere,
                    model: Mat4::from_scale_rotation_translation(half, Quat::IDENTITY, centre),
                    color,
                    material: Material::Skin,
                });
            }
        }
        for (i, b) in w.body_ids().zip(&w.bodies) {
            match b.owner {
                Owner::Vh(Seg::EyeL | Seg::EyeR) => {
                    let (p, q) = w.pose(i);
                    let r = shisen::physics::body::eye::RADIUS;
                    draws.push(Draw {
                        mesh: MeshKey::Sphere,
                        model: Mat4::from_scale_rotation_translation(Vec3::splat(r), q, p),
                        color: WHITE,
                        material: Material::Eye,
                    });
                    continue;
                }
                // The skinned bodies and the face stand for the VH's other
                // segments and your head and gloves.
                Owner::Vh(_) | Owner::Opponent(_) => continue,
                Owner::Prop => {}
            }
            let c = &w.phys.colliders[b.collider];
            let pose = c.position();
            let at = Mat4::from_rotation_translation(pose.rotation, pose.translation);
            let (mesh, local) = match c.shape().as_typed_shape() {
                TypedShape::Ball(s) => (MeshKey::Sphere, Mat4::from_scale(Vec3::splat(s.radius))),
                TypedShape::Cuboid(s) => (MeshKey::Cube, Mat4::from_scale(s.half_extents)),
                TypedShape::Capsule(s) => {
                    let (a, bb) = (s.segment.a, s.segment.b);
                    let axis = Quat::from_rotation_arc(Vec3::Y, (bb - a).normalize_or(Vec3::Y));
                    (
                        capsule_key(a.distance(bb) / 2.0, s.radius),
                        Mat4::from_rotation_translation(axis, (a + bb) / 2.0),
                    )
                }
                _ => continue,
            };
            draws.push(Draw {
                mesh,
                model: at * local,
                color: PROP,
                material: Material::Plain,
            });
        }
        let (head_p, head_q) = w.pose(Seg::Head);
        let face_frame = Mat4::from_rotation_translation(head_q, head_p)
            * Mat4::from_translation(face_offset(&w.plan));
        let face = face_vertices(sim);
        draws.extend(mouth(sim, &face, face_frame));
        let lashes = lashes(&sim.model().face.mesh.rims, &face);
        draws.extend(caruncles(&sim.model().face.mesh.rims, &face, face_frame));
        lid_shadows(&sim.model().face.mesh.rims, &face, face_frame, &mut draws);
        // Ears, rooted in the head just in front of where the face mesh's
        // ear bumps stand (the lobe landmark), the right one mirrored.
        let lobe = sim.model().face.mesh.landmarks.ear_lobe;
        for side in [1.0f32, -1.0] {
            let root = Vec3::new(side * (lobe.x + 0.010), lobe.y + 0.030, lobe.z + 0.008);
            draws.push(Draw {
                mesh: MeshKey::Ear,
                model: face_frame
                    * Mat4::from_translation(root)
                    * Mat4::from_scale(Vec3::new(side, 1.0, 1.0)),
                color: EAR,
                material: Material::Skin,
            });
        }
        draws.push(Draw {
            mesh: MeshKey::Lashes,
            model: face_frame,
            color: WHITE,
            material: Material::Hair,
        });
        let mesh = &sim.model().face.mesh;
        let hair = hair_shell([&mesh.triangles, &mesh.medium], &face);
        draws.push(Draw {
            mesh: MeshKey::HairShell,
            model: face_frame,
            color: WHITE,
            material: Material::Scalp,
        });
        // The face after the hair over it: the skin under the hair fails
        // the depth test before it is shaded.
        draws.push(Draw {
            mesh: MeshKey::Face,
            model: face_frame,
            color: WHITE,
            material: Material::Face,
        });
        // The ring and the hall, last (behind the fighters).
        draws.extend(super::ring::draws());
        draws.extend(super::hall::draws(
            sim.crowd.excitement as f32,
            sim.time() as f32,
            camera.view_proj(),
        ));
        let mut frame = Frame {
            camera,
            draws,
            face,
            lashes,
            hair,
            body,
            avatar,
            plan: w.plan.clone(),
            avatar_indices: if view == View::First {
                AvatarPart::Arms
            } else {
                AvatarPart::Whole
            },
            lines: Vec::new(),
            labels: Vec::new(),
            shadow_focus: shadow_focus(w.position(Seg::Head), you_head),
            lips: LipShape::of(&sim.model().face.mesh.landmarks),
        };
        frame.add_overlays(sim, overlays);
        frame
    }

    fn line(&mut self, a: Vec3, b: Vec3, color: [f32; 4]) {
        self.lines.push(LineVertex {
            pos: a.to_array(),
            color,
        });
        self.lines.push(LineVertex {
            pos: b.to_array(),
            color,
        });
    }

    fn add_overlays(&mut self, sim: &Sim, o: Overlays) {
        let w = &sim.world;
        let eyes = [Seg::EyeL, Seg::EyeR].map(|e| w.pose(e));
        let head_q = w.pose(Seg::Head).1;
        if o.gaze_rays
            && let Some(s) = sim.last()
        {
            let gp = s.gaze_point.as_vec3();
            for (k, (p, q)) in eyes.iter().enumerate() {
                let colour = [[0.1, 1.0, 0.2, 1.0], [0.1, 0.9, 1.0, 1.0]][k];
                self.line(*p, *p + *q * Vec3::Z * p.distance(gp), colour);
            }
            let yellow = [1.0, 0.9, 0.1, 1.0];
            for d in [Vec3::X, Vec3::Y, Vec3::Z] {
                self.line(gp - d * 0.02, gp + d * 0.02, yellow);
            }
        }
        if o.fov_cones {
            let f = &sim.params().vision.field;
            for (k, (p, q)) in eyes.iter().enumerate() {
                // The field is a yaw/pitch rectangle about the eye's line of
                // sight in the head frame (vision::in_field).
                let los = (head_q.inverse() * *q * Vec3::Z).as_dvec3();
                let (ly, lp) = yaw_pitch_of(los);
                let (temporal, nasal) = if k == 0 {
                    (f.temporal_deg, f.nasal_deg)
                } else {
                    (f.nasal_deg, f.temporal_deg)
                };
                let (y0, y1) = (ly - nasal.to_radians(), ly + temporal.to_radians());
                let (p0, p1) = (lp - f.down_deg.to_radians(), lp + f.up_deg.to_radians());
                let edge =
                    |a: f64, b: f64| *p + head_q * dir_from_yaw_pitch(a, b).as_vec3() * FOV_LEN;
                let colour = [1.0, 0.5, 0.1, 0.8];
                let corners = [(y0, p0), (y1, p0), (y1, p1), (y0, p1)];
                for (n, &(a, b)) in corners.iter().enumerate() {
                    self.line(*p, edge(a, b), colour);
                    let (c, d) = corners[(n + 1) % 4];
                    const STEPS: usize = 8;
                    for i in 0..STEPS {
                        let t0 = i as f64 / STEPS as f64;
                        let t1 = (i + 1) as f64 / STEPS as f64;
                        let lerp = |t: f64| (a + (c - a) * t, b + (d - b) * t);
                        let (u0, v0) = lerp(t0);
                        let (u1, v1) = lerp(t1);
                        self.line(edge(u0, v0), edge(u1, v1), colour);
                    }
                }
            }
        }
        if o.joint_frames {
            for (i, b) in w.body_ids().zip(&w.bodies) {
                if let Owner::Vh(_) = b.owner {
                    let (p, q) = w.pose(i);
                    self.line(p, p + q * Vec3::X * AXIS_LEN, [1.0, 0.1, 0.1, 1.0]);
                    self.line(p, p + q * Vec3::Y * AXIS_LEN, [0.1, 1.0, 0.1, 1.0]);
                    self.line(p, p + q * Vec3::Z * AXIS_LEN, [0.2, 0.3, 1.0, 1.0]);
                }
            }
        }
        if o.saliency_labels {
            let winner = sim.attention.current().and_then(|c| c.body);
            for s in sim.seen() {
                let mark = if Some(s.body) == winner { " *" } else { "" };
                self.labels.push(Label {
                    at: (s.position + DVec3::Y * 0.08).as_vec3(),
                    text: format!(
                        "{} {:.2}{mark}",
                        w.info(s.body).name,
                        sim.attention.scores[s.body.index()]
                    ),
                });
            }
        }
    }
}

/// Mesh key of a capsule.
pub fn capsule_key(half_height: f32, radius: f32) -> MeshKey {
    MeshKey::Capsule {
        half_height: half_height.to_bits(),
        radius: radius.to_bits(),
    }
}

/// The face deformed by the current face state, its tissue thickened
/// where the skin bunches (W4), with normals recomputed from that shape
/// and the wrinkles of its compressed skin.
fn face_vertices(sim: &Sim) -> Vec<Vertex> {
    let face = &sim.model().face;
    let mesh = &face.mesh;
    let mut pos = vec![Vec3::ZERO; mesh.positions.len()];
    shisen_face::deform(face, &sim.face_state, &mut pos);
    let mut wrinkles = Vec::new();
    shisen_face::wrinkle::measure(
        mesh,
        &face.wrinkle_basis,
        &face.params.skin,
        &mut pos,
        &mut wrinkles,
    );
    let normals = smooth_normals(&compute_normals(&pos, &mesh.triangles), &mesh.triangles);
    pos.iter()
        .zip(&normals)
        .zip(&face.paint.colours)
        .zip(&face.paint.regions)
        .zip(&wrinkles)
        .zip(&mesh.positions)
        .map(|(((((p, n), c), r), w), rest)| Vertex {
            wrinkle: *w,
            paint: *r,
            rest: [rest.x, rest.y],
            ..Vertex::coloured(*p, *n, *c)
        })
        .collect()
}

/// The skin's normals, each blended half and half with its neighbours'
/// mean: the deformed mesh's cells are a few millimetres across, and where
/// the skin bunches (under a smiling eye, beside a tightened mouth) their
/// facets would catch the light as streaks; skin bends smoothly over them.
fn smooth_normals(normals: &[Vec3], triangles: &[[u32; 3]]) -> Vec<Vec3> {
    let mut sum = vec![Vec3::ZERO; normals.len()];
    for t in triangles {
        let [a, b, c] = t.map(|i| i as usize);
        sum[a] += normals[b] + normals[c];
        sum[b] += normals[a] + normals[c];
        sum[c] += normals[a] + normals[b];
    }
    normals
        .iter()
        .zip(sum)
        .map(|(n, s)| (*n + s.normalize_or(*n)).normalize_or(*n))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use shisen::scene::LoadedScene;

    #[test]
    fn frame_has_every_part_and_is_deterministic() {
        let mut sim = LoadedScene::default_scene().sim();
        // Past vision's latency, so the VH perceives the opponent.
        for _ in 0..150 {
            sim.step();
        }
        let all = Overlays {
            gaze_rays: true,
            fov_cones: true,
            saliency_labels: true,
            joint_frames: true,
        };
        let f = Frame::build(&sim, View::ORBIT, all, 1.5);
        let eyes = f
            .draws
            .iter()
            .filter(|d| d.material == Material::Eye)
            .count();
        assert_eq!(eyes, 2);
        assert!(f.draws.iter().any(|d| d.mesh == MeshKey::Face));
        assert_eq!(f.face.len(), sim.model().face.mesh.positions.len());
        assert!(!f.lines.is_empty() && f.lines.len().is_multiple_of(2));
        assert!(!f.labels.is_empty());
        assert_eq!(f, Frame::build(&sim, View::ORBIT, all, 1.5));
        assert_eq!(f.body.len(), Looks::of(&f.plan).vh.vertices().len());
        assert_eq!(f.avatar_indices, AvatarPart::Whole);
        let first = Frame::build(&sim, View::First, Overlays::default(), 1.5);
        // (The crowd drawn depends on what each view sees of the hall.)
        let fighters = |f: &Frame| {
            f.draws
                .iter()
                .filter(|d| !matches!(d.mesh, MeshKey::Crowd { .. }))
                .count()
        };
        assert_eq!(
            fighters(&first) + 2,
            fighters(&f),
            "no own head (skin and hair) in first person"
        );
        assert_eq!(first.avatar_indices, AvatarPart::Arms);
    }
}
