//! What to draw for one state of the simulation: a list of shaded primitives,
//! the deformed face, overlay lines and labels. Built on the CPU from a
//! [`Sim`] and independent of the GPU, so it is deterministic and testable.

use glam::{DVec3, Mat4, Quat, Vec3};
use rapier3d::prelude::TypedShape;

use crate::face::mesh::compute_normals;
use crate::physics::body::{BodyPlan, seg};
use crate::physics::world::{Owner, opp};
use crate::sim::Sim;
use crate::util::math::{dir_from_yaw_pitch, yaw_pitch_of};

use super::body::{BodyMesh, BodyStyle, Pose, SKIN, avatar_pose, vh_pose};
use super::camera::{Camera, View};
use super::geometry::Vertex;

/// Which mesh a draw uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MeshKey {
    /// Unit sphere.
    Sphere,
    /// Unit cube.
    Cube,
    /// The floor square.
    Floor,
    /// A capsule, by the bits of its half height and radius.
    Capsule {
        /// `f32::to_bits` of the half height.
        half_height: u32,
        /// `f32::to_bits` of the radius.
        radius: u32,
    },
    /// The deformed face ([`Frame::face`]).
    Face,
    /// The VH's skinned body ([`Frame::body`]).
    Body,
    /// Your skinned body ([`Frame::avatar`]; only its arms in the
    /// first-person view).
    Avatar,
    /// The VH's eyelashes ([`Frame::lashes`], a triangle list in the face
    /// frame).
    Lashes,
    /// A left ear ([`super::geometry::ear`]; mirrored for the right).
    Ear,
    /// A tooth's crown: a rounded box of half extent 1
    /// ([`super::geometry::rounded_box`]).
    Tooth,
}

impl MeshKey {
    /// Whether the mesh is closed and wound counter-clockwise seen from
    /// outside, so its back faces can be skipped (the skinned bodies are
    /// too, and their own pipeline skips them: [`Material::Body`]).
    pub fn is_closed(self) -> bool {
        matches!(
            self,
            MeshKey::Sphere | MeshKey::Cube | MeshKey::Tooth | MeshKey::Capsule { .. }
        )
    }
}

/// How a surface is shaded.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Material {
    /// Lit with the instance colour.
    Plain = 0,
    /// Eyeball: sclera, iris and pupil around the local +Z pole.
    Eye = 1,
    /// Checkered floor.
    Floor = 2,
    /// Skin: wrapped, reddened diffuse and a weak sheen.
    Skin = 3,
    /// The face: skin with its painted borders and wrinkles.
    Face = 4,
    /// A skinned body (closed; its back faces are skipped): skin light,
    /// one painted border (the vest's hem).
    Body = 5,
    /// Hair seen as strands (the lashes): lit with the instance colour,
    /// matte (a highlight on strands thinner than a pixel greys them).
    Hair = 6,
}

/// One mesh instance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Draw {
    /// Mesh.
    pub mesh: MeshKey,
    /// Local to world.
    pub model: Mat4,
    /// Linear RGBA base colour.
    pub color: [f32; 4],
    /// Shading.
    pub material: Material,
}

/// Overlay line vertex (world position, linear RGBA).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct LineVertex {
    /// Position, world.
    pub pos: [f32; 3],
    /// Colour.
    pub color: [f32; 4],
}

/// A text label at a world point (drawn by the window, not offscreen).
#[derive(Clone, Debug, PartialEq)]
pub struct Label {
    /// Anchor, world.
    pub at: Vec3,
    /// Text.
    pub text: String,
}

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

    /// Triangles of a body mesh key.
    pub fn indices(&self, key: MeshKey, part: AvatarPart) -> &[u32] {
        match (key, part) {
            (MeshKey::Avatar, AvatarPart::Arms) => self.you.arm_indices(),
            (MeshKey::Avatar, AvatarPart::Whole) => &self.you.indices,
            _ => &self.vh.indices,
        }
    }
}

fn posed(mesh: &BodyMesh, pose: &Pose) -> Vec<Vertex> {
    let mut out = Vec::new();
    mesh.skin(pose, &mut out);
    out
}

/// Inside of the mouth, and teeth.
const MOUTH: [f32; 4] = {
    let c = crate::face::appearance::FaceStyle::DEFAULT.inside;
    [c[0], c[1], c[2], 1.0]
};
const TEETH: [f32; 4] = [0.80, 0.78, 0.70, 1.0];
const HAIR: [f32; 4] = {
    let h = crate::face::appearance::FaceStyle::DEFAULT.hair;
    [h[0], h[1], h[2], 1.0]
};
const PROP: [f32; 4] = [0.85, 0.65, 0.12, 1.0];
const STAND: [f32; 4] = [0.30, 0.30, 0.32, 1.0];
const WHITE: [f32; 4] = [1.0, 1.0, 1.0, 1.0];
/// Length of drawn field-of-view edges and joint axes, m.
const FOV_LEN: f32 = 0.5;
const AXIS_LEN: f32 = 0.06;

/// Offset of the face frame's origin (midway between the eyes at rest) from
/// the head body's centre, in the head body's frame.
pub fn face_offset(plan: &BodyPlan) -> Vec3 {
    (BodyPlan::eye_centre(0) + BodyPlan::eye_centre(1)) / 2.0 - plan.segments[seg::HEAD].centre
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
        let body = posed(&looks.vh, &vh_pose(|s| w.pose(s), &w.plan));
        let (you_head, you_gloves) = (
            w.position(w.opponent[opp::HEAD]),
            [opp::LEFT_GLOVE, opp::RIGHT_GLOVE].map(|g| w.position(w.opponent[g])),
        );
        let avatar = posed(&looks.you, &avatar_pose(&w.plan, you_head, you_gloves));
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
        for (i, b) in w.bodies.iter().enumerate() {
            match b.owner {
                Owner::Vh(s) if s == seg::EYE_L || s == seg::EYE_R => {
                    let (p, q) = w.pose(i);
                    let r = crate::physics::body::eye::RADIUS;
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
                Owner::Vh(_) | Owner::Opponent => continue,
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
        let (head_p, head_q) = w.pose(seg::HEAD);
        let face_frame = Mat4::from_rotation_translation(head_q, head_p)
            * Mat4::from_translation(face_offset(&w.plan));
        draws.push(Draw {
            mesh: MeshKey::Face,
            model: face_frame,
            color: WHITE,
            material: Material::Face,
        });
        let face = face_vertices(sim);
        draws.extend(mouth(sim, &face, face_frame));
        let lashes = lashes(&sim.model().face.mesh.rims, &face);
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
        draws.extend([
            Draw {
                mesh: MeshKey::Floor,
                model: Mat4::from_scale(Vec3::splat(4.0)),
                color: WHITE,
                material: Material::Floor,
            },
            // The rigid stand the VH's torso sits on (not a physics body).
            Draw {
                mesh: capsule_key(0.5, 0.035),
                model: Mat4::from_translation(Vec3::new(0.0, 0.5, 0.0)),
                color: STAND,
                material: Material::Plain,
            },
        ]);
        let mut frame = Frame {
            camera,
            draws,
            face,
            lashes,
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
        let eyes = [seg::EYE_L, seg::EYE_R].map(|e| w.pose(e));
        let head_q = w.pose(seg::HEAD).1;
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
            for (i, b) in w.bodies.iter().enumerate() {
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
                        w.bodies[s.body].name, sim.attention.scores[s.body]
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

/// The mouth's inside, seen when the lips part: a dark cavity behind the
/// lips, placed from the middle of the lips' deformed edges, and the teeth,
/// fixed to the bones: the upper incisors to the skull, the lower ones to
/// the jaw, turning with it (F7), all in the face frame `face_frame`. The
/// lips move over the teeth: a raised upper lip bares the upper teeth, a
/// lowered lower lip the lower ones. Teeth are drawn only when the lips
/// are apart (closed lips hide them; drawn, they would show through the
/// seam).
fn mouth(sim: &Sim, face: &[Vertex], face_frame: Mat4) -> Vec<Draw> {
    let model = &sim.model().face;
    let (mesh, l) = (&model.mesh, &model.mesh.landmarks);
    let mid = |rim: &[u32]| rim[rim.len() / 2] as usize;
    let (ui, li) = (mid(&mesh.rims.upper_lip), mid(&mesh.rims.lower_lip));
    let (upper, lower) = (
        Vec3::from_array(face[ui].pos),
        Vec3::from_array(face[li].pos),
    );
    let gap = upper.distance(lower);
    let w = l.mouth_corner.x;
    let ellipsoid = |centre: Vec3, half: Vec3, color| Draw {
        mesh: MeshKey::Sphere,
        model: face_frame * Mat4::from_scale_rotation_translation(half, Quat::IDENTITY, centre),
        color,
        material: Material::Plain,
    };
    // The cavity is dark and reaches past the mouth's corners, which lie
    // well behind its middle, so the neck inside the head never shows
    // through the opening; with the teeth showing, its front stands behind
    // the canines (the head's inside between is drawn dark, shader.wgsl).
    // Behind closed lips it only darkens the seam and stays within the
    // mouth's width: that close to the lips a wider one would come out
    // through the cheeks beside the corners.
    let cavity = |front: f32, reach: f32| {
        let half_d = 0.026;
        ellipsoid(
            Vec3::new(0.0, (upper.y + lower.y) / 2.0, front - half_d),
            Vec3::new(w * reach, 0.02 + gap * 0.6, half_d),
            MOUTH,
        )
    };
    let lips_back = upper.z.min(lower.z) - 0.006;
    if gap < TEETH_SHOW_GAP {
        return vec![cavity(lips_back, 1.0)];
    }
    // Incisal edges at rest: the upper one a little below the upper lip's
    // rest edge and behind it; the lower one overlapped by the upper
    // (overbite) and behind it (overjet).
    let rest_lip = mesh.positions[ui];
    let upper_edge = Vec3::new(0.0, rest_lip.y - INCISOR_SHOW, rest_lip.z - INCISOR_DEPTH);
    let lower_rest = upper_edge + Vec3::new(0.0, OVERBITE, -OVERJET);
    let jaw = &model.rig.jaw;
    let theta = sim.face_state.activation.jaw_deg.to_radians();
    let lower_edge = lower_rest + crate::face::muscle::jaw_rotation(lower_rest - jaw.pivot, theta);
    // Lips bunched in front of the teeth (a tightened mouth pulls the skin
    // above and below the lips over them) must still cover them: the teeth
    // go back behind the nearest skin in front of them, if it is nearer
    // than their place on the bones (the surface has no lip thickness).
    let half_w = w * 0.62;
    let (y0, y1) = (lower_edge.y - 0.01, upper_edge.y + 0.01);
    let skin = face
        .iter()
        .map(|v| Vec3::from_array(v.pos))
        .filter(|p| p.x.abs() < half_w && (y0..y1).contains(&p.y))
        .filter(|p| p.z > rest_lip.z - LIP_REACH)
        .fold(f32::INFINITY, |z, p| z.min(p.z));
    let push = (upper_edge.z - (skin - 0.001)).max(0.0);
    // Light reaches teeth behind the lips only through the opening: the
    // open fraction of their view out of a slit of width `gap` at the
    // lips' depth `d` is about g / (g + 2 d); scaled so a wide-open mouth
    // is fully lit.
    let lit = (1.2 * gap / (gap + 2.0 * INCISOR_DEPTH)).clamp(0.3, 1.0);
    // The cavity stands behind the upper canines and behind the lower
    // ones, which the jaw carries back as it opens (about 6 mm behind the
    // lower incisors round their smaller arch).
    let front = (upper_edge.z - CAVITY_BEHIND_TEETH).min(lower_edge.z - 0.007) - push;
    let mut draws = vec![cavity(lips_back.min(front), 1.6)];
    // Each arch's teeth, midline outward, along a circle through the
    // incisal midpoint; the lower arch turns with the jaw.
    let arches = [
        (upper_edge, &UPPER_TEETH, UPPER_ARCH_R, 1.0, 0.0),
        (lower_rest, &LOWER_TEETH, LOWER_ARCH_R, -1.0, theta),
    ];
    for (edge, teeth, radius, up, turn) in arches {
        let mut s = 0.0;
        for &(width, height) in teeth.iter() {
            let phi = (s + width / 2.0) / radius;
            s += width;
            let back = radius * (1.0 - phi.cos());
            // Teeth further round the arch sit deeper in the mouth's shade.
            let shade = lit * (1.0 - back / 0.02).clamp(0.45, 1.0);
            let colour = [TEETH[0] * shade, TEETH[1] * shade, TEETH[2] * shade, 1.0];
            for side in [-1.0f32, 1.0] {
                let local = Vec3::new(
                    side * radius * phi.sin(),
                    up * height / 2.0,
                    -back - TOOTH_HALF_DEPTH,
                );
                let root = edge + local;
                let centre = root + crate::face::muscle::jaw_rotation(root - jaw.pivot, turn)
                    - Vec3::Z * push;
                let rotation = Quat::from_rotation_x(turn) * Quat::from_rotation_y(side * phi);
                // A crown is a flat-fronted, rounded block; the narrow gaps
                // between them show the cavity as the lines between teeth.
                draws.push(Draw {
                    mesh: MeshKey::Tooth,
                    model: face_frame
                        * Mat4::from_scale_rotation_translation(
                            Vec3::new(width * 0.46, height / 2.0, TOOTH_HALF_DEPTH),
                            rotation,
                            centre,
                        ),
                    color: colour,
                    material: Material::Plain,
                });
            }
        }
    }
    draws
}

/// Crown width (along the arch) and height of each tooth from the midline
/// out to the second premolar, m (Wheeler's mean crown dimensions: Nelson
/// 2015, Wheeler's Dental Anatomy, 10th ed.). Only what the lips' opening
/// frames is seen; molars never are.
const UPPER_TEETH: [(f32, f32); 5] = [
    (0.0085, 0.0105),
    (0.0065, 0.0090),
    (0.0075, 0.0100),
    (0.0070, 0.0085),
    (0.0065, 0.0080),
];
const LOWER_TEETH: [(f32, f32); 5] = [
    (0.0050, 0.0090),
    (0.0055, 0.0095),
    (0.0070, 0.0110),
    (0.0070, 0.0085),
    (0.0070, 0.0080),
];
/// Radii of the circles the front teeth follow, m: the upper canines'
/// tips lie about 17 mm either side of the midline and 9 mm behind the
/// incisors (intercanine width about 34 mm, lower about 26 mm: Bishara et
/// al. 1997, Am. J. Orthod. 111:401), a circle of radius 21 mm (16 mm).
const UPPER_ARCH_R: f32 = 0.021;
const LOWER_ARCH_R: f32 = 0.016;
/// Half the thickness drawn of a crown, front to back, m (our choice:
/// only the front face shows).
const TOOTH_HALF_DEPTH: f32 = 0.003;

/// How far the cavity's front stands behind the upper incisors' when the
/// teeth show, m: behind the canines' crowns (about 8 mm back round the
/// arch, 6 mm thick), so the upper front teeth are all seen.
const CAVITY_BEHIND_TEETH: f32 = 0.014;

/// How far the upper incisors reach below the upper lip's rest edge, m:
/// about 2 mm in young men with the lips apart at rest (Vig & Brundo 1978,
/// J. Prosthet. Dent. 39:502: 1-3.5 mm, more in women and the young).
const INCISOR_SHOW: f32 = 0.002;

/// How far the upper incisors' front sits behind the upper lip's edge, m
/// (the lip's thickness at its edge; our choice).
const INCISOR_DEPTH: f32 = 0.004;

/// Vertical overlap and horizontal step of the lower incisors behind the
/// upper ones in a closed bite, m: the orthodontic norm of about 2 mm each.
const OVERBITE: f32 = 0.002;
const OVERJET: f32 = 0.0025;

/// Skin up to this far behind the upper lip's rest edge can lie in front
/// of the teeth (the lips and the skin around them), m.
const LIP_REACH: f32 = 0.015;

/// Lips further apart than this show the teeth, m.
const TEETH_SHOW_GAP: f32 = 0.003;

/// Ears are a little redder than the face.
const EAR: [f32; 4] = [SKIN[0] * 1.04, SKIN[1] * 0.95, SKIN[2] * 0.95, 1.0];

/// Lashes, m: upper and lower length at mid-lid (Thibaut et al. 2010,
/// Br. J. Dermatol. 163:1023: upper 8-12 mm, lower 6-8 mm; shorter here,
/// seen curled).
const LASH_LENGTH: [f32; 2] = [0.006, 0.0018];
/// Thickness of the lid at its margin, m (our choice: a thin ledge that
/// reads as the lid's edge).
const LID_THICKNESS: f32 = 0.0018;
/// The lid margin's moist, pinker skin.
const LID_MARGIN: [f32; 4] = [0.55, 0.30, 0.27, 1.0];
const LASH: [f32; 4] = {
    let l = crate::face::appearance::FaceStyle::DEFAULT.lashes;
    [l[0], l[1], l[2], 1.0]
};

/// Lashes along each lid, spaced this far apart at the root, m (people
/// have 90-160 upper and 70-80 lower lashes in several rows; one row of
/// strands this close, each a fraction of a pixel wide at sparring
/// distance, reads as the same soft dark fringe).
const LASH_SPACING: f32 = 0.0008;
/// Width of a lash at its root, m (a lash is about 0.1 mm thick; drawn
/// wider, as several lashes of a row overlap).
const LASH_WIDTH: f32 = 0.0008;
/// Depth of the upper lashes' dense roots along the lid's edge, m (our
/// choice: about a millimetre, where the lashes stand in two or three rows,
/// and the lid's edge reads dark in any light).
const LASH_ROOT: f32 = 0.0013;

/// Eyelashes and lid margins: a curled fringe of thin tapered strands on
/// each lid rim and a narrow ledge behind it (the lid's thickness), rooted
/// on the deformed rim so they ride every lid movement and blink. The
/// strands are spaced along the rim's length, not per mesh vertex, so the
/// fringe is as dense at every mesh resolution; each strand's length and
/// lean vary a little (a fixed pattern, no randomness), the outer ones
/// lean out towards the eye's corner. The upper fringe sweeps forward and
/// up, the lower forward and down; both taper to nothing at the corners.
/// A triangle list, face frame.
fn lashes(rims: &crate::face::mesh::Rims, face: &[Vertex]) -> Vec<Vertex> {
    let mut out = Vec::new();
    let vertex = |i: u32| {
        let v = &face[i as usize];
        (Vec3::from_array(v.pos), Vec3::from_array(v.normal))
    };
    for (rim, len, lift) in rims
        .upper_lid
        .iter()
        .map(|r| (r, LASH_LENGTH[0], 1.0))
        .chain(rims.lower_lid.iter().map(|r| (r, LASH_LENGTH[1], -1.0)))
    {
        let n = rim.len();
        if n < 2 {
            continue;
        }
        // The lid's margin: a ledge from the rim back toward the eyeball,
        // the lid's thickness, seen from below (upper lid) or above.
        let ledge = |i: usize| {
            let (p, nrm) = vertex(rim[i]);
            [p, p - nrm * LID_THICKNESS]
        };
        for i in 0..n - 1 {
            let (a, b) = (ledge(i), ledge(i + 1));
            let quad = [a[0], b[0], b[1], a[0], b[1], a[1]];
            let normal = Vec3::Y * -lift;
            out.extend(quad.map(|p| Vertex::coloured(p, normal, LID_MARGIN)));
        }
        // Arc length along the deformed rim.
        let mut at = vec![0.0f32; n];
        for i in 1..n {
            at[i] = at[i - 1] + vertex(rim[i]).0.distance(vertex(rim[i - 1]).0);
        }
        let total = at[n - 1];
        // The upper lashes' roots: dense enough to read as one dark line
        // along the lid's edge (what the eye's outline is at a distance),
        // thinning to the corners.
        if lift > 0.0 {
            let band = |i: usize| {
                let (p, nrm) = vertex(rim[i]);
                let xi = 2.0 * at[i] / total.max(1e-9) - 1.0;
                let out_dir = (nrm + Vec3::Z).normalize_or(Vec3::Z);
                let width = LASH_ROOT * (1.0 - xi * xi).max(0.0).sqrt().sqrt();
                [p, p + (out_dir + Vec3::Y).normalize_or(Vec3::Y) * width]
            };
            for i in 0..n - 1 {
                let (a, b) = (band(i), band(i + 1));
                let quad = [a[0], b[0], b[1], a[0], b[1], a[1]];
                let normal = (b[0] - a[0]).cross(a[1] - a[0]).normalize_or(Vec3::Z);
                out.extend(quad.map(|p| Vertex::coloured(p, normal, LASH)));
            }
        }
        let outer_last = vertex(rim[n - 1]).0.x.abs() > vertex(rim[0]).0.x.abs();
        let count = (total / LASH_SPACING) as usize;
        let mut seg = 0;
        for k in 0..count {
            let s = (k as f32 + 0.5) / count as f32 * total;
            while seg + 2 < n && at[seg + 1] < s {
                seg += 1;
            }
            let f = ((s - at[seg]) / (at[seg + 1] - at[seg]).max(1e-9)).clamp(0.0, 1.0);
            let ((p0, n0), (p1, n1)) = (vertex(rim[seg]), vertex(rim[seg + 1]));
            let root = p0.lerp(p1, f);
            let along = (p1 - p0).normalize_or(Vec3::X);
            let nrm = n0.lerp(n1, f);
            // xi in [-1, 1] from one corner to the other; `outer` is +1 at
            // the outer corner (the rim end farther from the midline).
            let xi = 2.0 * s / total - 1.0;
            let outer = if outer_last { xi } else { -xi };
            let outward = if outer_last { along } else { -along };
            // A fixed, irregular pattern of length and lean.
            let jitter = |m: f32| (k as f32 * m).sin();
            let l = len * (1.0 - xi * xi).max(0.0).sqrt() * (0.85 + 0.15 * jitter(12.9898));
            if l <= 0.0 {
                continue;
            }
            let lean = outward * (0.25 * outer.max(0.0) + 0.08 * jitter(78.233));
            let out_dir = (nrm + Vec3::Z).normalize_or(Vec3::Z);
            let mid = root + (out_dir * 0.6 + lean * 0.3) * l + Vec3::Y * lift * l * 0.08;
            // Curled: out from the lid, then up (down for the lower lid).
            let tip = root + (out_dir * 0.7 + lean) * l + Vec3::Y * lift * l * 0.6;
            let w = along * (0.5 * LASH_WIDTH);
            let strand = [
                [root - w, root + w, mid + w * 0.5],
                [root - w, mid + w * 0.5, mid - w * 0.5],
                [mid - w * 0.5, mid + w * 0.5, tip],
            ];
            for t in strand {
                let normal = (t[1] - t[0]).cross(t[2] - t[0]).normalize_or(Vec3::Z);
                out.extend(t.map(|p| Vertex::coloured(p, normal, LASH)));
            }
        }
    }
    out
}

/// The face deformed by the current face state, with recomputed normals
/// and the wrinkles of its compressed skin.
fn face_vertices(sim: &Sim) -> Vec<Vertex> {
    let face = &sim.model().face;
    let mesh = &face.mesh;
    let mut pos = vec![Vec3::ZERO; mesh.positions.len()];
    crate::face::deform(face, &sim.face_state, &mut pos);
    let normals = compute_normals(&pos, &mesh.triangles);
    let mut wrinkles = Vec::new();
    crate::face::wrinkle::measure(
        mesh,
        &face.wrinkle_basis,
        &face.params.skin,
        &pos,
        &mut wrinkles,
    );
    pos.iter()
        .zip(&normals)
        .zip(&face.paint.colours)
        .zip(&face.paint.regions)
        .zip(&wrinkles)
        .map(|((((p, n), c), r), w)| Vertex {
            wrinkle: *w,
            paint: *r,
            ..Vertex::coloured(*p, *n, *c)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::LoadedScene;

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
        assert_eq!(
            first.draws.len() + 2,
            f.draws.len(),
            "no own head (skin and hair) in first person"
        );
        assert_eq!(first.avatar_indices, AvatarPart::Arms);
    }
}
