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
    /// The boxing ring, one static mesh coloured per vertex
    /// ([`super::ring::mesh`]).
    Ring,
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
    /// Flat ground lit from above (the ring's canvas): the instance colour
    /// at one light, nothing computed per pixel.
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
