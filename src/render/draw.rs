//! The draw list's primitives: which mesh a draw uses, how it is shaded,
//! and the overlay lines and labels. The frame builds them; the GPU
//! renderer draws them.

use glam::{Mat4, Vec3};

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
    /// The deformed face ([`Frame::face`](crate::render::Frame::face)).
    Face,
    /// The VH's skinned body ([`Frame::body`](crate::render::Frame::body)).
    Body,
    /// Your skinned body ([`Frame::avatar`](crate::render::Frame::avatar); only its arms in the
    /// first-person view).
    Avatar,
    /// The VH's eyelashes ([`Frame::lashes`](crate::render::Frame::lashes), a triangle list in the face
    /// frame).
    Lashes,
    /// The VH's hair standing off its scalp ([`Frame::hair`](crate::render::Frame::hair),
    /// indexed, in the face frame).
    HairShell,
    /// The boxing ring and the hall round it, one static mesh coloured
    /// per vertex ([`super::ring::mesh`]).
    Ring,
    /// The lamps over the ring, unlit ([`super::ring::lamps`]).
    Lamps,
    /// The hall round the ring, its walls, roof and lighting grid, one
    /// static mesh lit once ([`super::hall::mesh`]).
    Hall,
    /// A group of the crowd, seated or standing ([`super::hall::crowd`]).
    Crowd {
        /// Which group, 0 to [`super::hall::GROUPS`] - 1.
        group: u8,
        /// On its feet, arms up.
        standing: bool,
    },
    /// A left ear ([`super::geometry::ear`]; mirrored for the right).
    Ear,
    /// A tooth's crown: a rounded box of half extent 1
    /// ([`super::geometry::rounded_box`]).
    Tooth,
    /// A coarse unit sphere for small parts a few pixels across (the
    /// caruncles, the tongue): a software rasteriser pays for every
    /// triangle, however small.
    Blob,
}

impl MeshKey {
    /// Whether the mesh is closed and wound counter-clockwise seen from
    /// outside (the hair's shell meets the skin at the hairline, so its
    /// inside is never seen), so its back faces can be skipped (the skinned bodies are
    /// too, and their own pipeline skips them: [`Material::Body`]).
    pub fn is_closed(self) -> bool {
        matches!(
            self,
            MeshKey::Sphere
                | MeshKey::Cube
                | MeshKey::Tooth
                | MeshKey::Blob
                | MeshKey::HairShell
                | MeshKey::Capsule { .. }
                | MeshKey::Ring
                | MeshKey::Lamps
                | MeshKey::Hall
                | MeshKey::Crowd { .. }
        )
    }
}

/// The key light's direction of travel: from in front of the VH, above
/// and to its left (your right), the light that models its face.
pub const KEY_DIR: Vec3 = Vec3::new(-0.9, -1.0, -1.1);
/// The fill light's direction of travel, from the other side.
pub const FILL_DIR: Vec3 = Vec3::new(0.9, -0.15, -1.0);
/// The top light: the lamps over the ring, from above, behind you and to
/// your right (about 40 deg off the vertical), so the fighters' and the
/// ropes' shadows fall ahead and to the left of you, where first person
/// sees them.
pub const TOP_DIR: Vec3 = Vec3::new(-0.45, -1.0, -0.75);
/// The top light's strength, against the key's 0.85 and the fill's 0.35.
pub const TOP_LIGHT: f32 = 0.35;
/// The rim light's direction of travel: from behind the VH, above and to
/// its right, toward you (the third lamp of a portrait's three-point
/// rig: it draws the edge of the cheek, jaw and ear against the dark hall).
/// Only skin takes it (`skin()` in shader.wgsl), at grazing angles.
pub const RIM_DIR: Vec3 = Vec3::new(0.6, -0.7, 1.0);
/// The rim light's strength.
pub const RIM_LIGHT: f32 = 0.55;

/// The plain material's light on a surface of normal `n` with nothing
/// shadowing it (ambient 0.22, key 0.85, fill 0.35, top): what the
/// shader computes for it, for surfaces lit once on the CPU (the ground,
/// the static scenery).
pub fn plain_light(n: Vec3) -> f32 {
    key_fill_light(n) + TOP_LIGHT * lambert(n, TOP_DIR)
}

/// The same without the top light: ambient, key and fill (the canvas's
/// light, to which the shader adds the top light where nothing shadows it).
pub fn key_fill_light(n: Vec3) -> f32 {
    0.22 + 0.85 * lambert(n, KEY_DIR) + 0.35 * lambert(n, FILL_DIR)
}

fn lambert(n: Vec3, dir: Vec3) -> f32 {
    n.dot(-dir.normalize()).max(0.0)
}

/// How a surface is shaded.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Material {
    /// Lit with the instance colour.
    Plain = 0,
    /// Eyeball: sclera, iris and pupil around the local +Z pole. Its
    /// colour is not a colour: red and green carry the upper lid's margin
    /// height in the eyeball's unit frame, at its middle and its corners
    /// (`face_parts::lid_shadows`), for the lid's shadow.
    Eye = 1,
    /// Flat ground lit from above (the ring's canvas): the instance colour
    /// at one light, nothing computed per pixel.
    Floor = 2,
    /// Skin: diffuse wrapped past the terminator, red furthest; sky and
    /// bounce ambient; two weak specular lobes; the rim light.
    Skin = 3,
    /// The face: skin with its painted borders and wrinkles.
    Face = 4,
    /// A skinned body (closed; its back faces are skipped): skin light,
    /// the vest's neckline and armholes drawn per pixel.
    Body = 5,
    /// Hair seen as strands (the lashes): lit with the instance colour,
    /// matte (a highlight on strands thinner than a pixel greys them).
    Hair = 6,
    /// A light source: its colour as it is, unlit, casting nothing.
    Emissive = 7,
    /// A head of hair: strands combed back over the scalp, their
    /// highlight drawn across them (Kajiya & Kay 1989).
    Scalp = 8,
    /// A tooth's crown: enamel over dentine, yellower at the neck and
    /// translucent grey-blue toward the biting edge. Its colour's alpha
    /// gives the crown's frame the way to that edge: +1 up its local y
    /// (a lower tooth), -1 down (an upper one).
    Tooth = 9,
}

impl Material {
    /// Every material.
    pub const ALL: [Material; 10] = [
        Material::Plain,
        Material::Eye,
        Material::Floor,
        Material::Skin,
        Material::Face,
        Material::Body,
        Material::Hair,
        Material::Emissive,
        Material::Scalp,
        Material::Tooth,
    ];

    /// Its vertex and fragment stages (`shader.wgsl`).
    pub fn stages(self) -> (&'static str, &'static str) {
        match self {
            Material::Plain => ("vs_mesh", "fs_plain"),
            Material::Eye => ("vs_mesh", "fs_eye"),
            Material::Floor => ("vs_mesh", "fs_floor"),
            Material::Skin => ("vs_mesh", "fs_skin"),
            Material::Face => ("vs_painted", "fs_face"),
            Material::Body => ("vs_painted", "fs_body"),
            Material::Hair => ("vs_mesh", "fs_hair"),
            Material::Emissive => ("vs_flat", "fs_flat"),
            Material::Scalp => ("vs_mesh", "fs_scalp"),
            Material::Tooth => ("vs_mesh", "fs_tooth"),
        }
    }

    /// Whether a draw of this material casts a shadow: not the ground,
    /// the lamps or the scenery (lit once, they take no shadow and the
    /// fighters are far from them); not the eyes, ears, teeth or lashes
    /// (the head around them casts their shadow; the lashes are thinner
    /// than a texel).
    pub fn casts(self, mesh: MeshKey) -> bool {
        !matches!(
            self,
            Material::Floor | Material::Emissive | Material::Hair | Material::Eye
        ) && !matches!(
            mesh,
            MeshKey::Ring
                | MeshKey::Hall
                | MeshKey::Crowd { .. }
                | MeshKey::Ear
                | MeshKey::Tooth
                | MeshKey::Blob
                | MeshKey::HairShell
        )
    }
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
