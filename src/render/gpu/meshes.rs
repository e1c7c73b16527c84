//! The meshes on the GPU: uploaded once (the shapes) or every frame (the
//! face, the bodies, the lashes and the hair), and the level of detail a
//! draw or its shadow uses.

use wgpu::util::DeviceExt;

use super::Renderer;
use crate::render::draw::MeshKey;
use crate::render::geometry::{MeshData, Vertex};

/// A mesh on the GPU: its vertices and its levels of detail.
pub(super) struct GpuMesh {
    pub(super) vertices: wgpu::Buffer,
    pub(super) indices: wgpu::Buffer,
    pub(super) count: u32,
    /// Coarser levels of detail over the same vertices, finer first (each
    /// its indices and their count); the coarsest casts the shadow.
    pub(super) coarser: Vec<(wgpu::Buffer, u32)>,
}

impl GpuMesh {
    /// The index buffer of level of detail `level` (0 the fine one) and
    /// its index count, if the mesh has it.
    pub(super) fn level(&self, level: usize) -> Option<(&wgpu::Buffer, u32)> {
        match level {
            0 => Some((&self.indices, self.count)),
            l => self.coarser.get(l - 1).map(|(indices, n)| (indices, *n)),
        }
    }
}

impl Renderer {
    /// A mesh's buffers: its vertices (with `usage` besides `VERTEX`), its
    /// fine indices and each of its `coarser` levels' indices.
    fn make_mesh(&self, data: &MeshData, usage: wgpu::BufferUsages, coarser: &[&[u32]]) -> GpuMesh {
        let vertices = self
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("shisen vertices"),
                contents: bytemuck::cast_slice(&data.vertices),
                usage: wgpu::BufferUsages::VERTEX | usage,
            });
        let indices = self
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("shisen indices"),
                contents: bytemuck::cast_slice(&data.indices),
                usage: wgpu::BufferUsages::INDEX,
            });
        let coarser = coarser
            .iter()
            .map(|level| {
                let buffer = self
                    .device
                    .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                        label: Some("shisen coarser indices"),
                        contents: bytemuck::cast_slice(level),
                        usage: wgpu::BufferUsages::INDEX,
                    });
                (buffer, level.len() as u32)
            })
            .collect();
        GpuMesh {
            vertices,
            indices,
            count: data.indices.len() as u32,
            coarser,
        }
    }

    /// Upload a mesh that does not change, under `key`.
    pub(super) fn upload(&mut self, key: MeshKey, data: &MeshData) {
        let mesh = self.make_mesh(data, wgpu::BufferUsages::empty(), &[]);
        self.meshes.insert(key, mesh);
    }

    /// Upload this frame's vertices of a dynamic mesh; its buffers are
    /// rebuilt (with `indices`) only when the vertex or index count
    /// changes.
    pub(super) fn dynamic_mesh(&mut self, key: MeshKey, vertices: &[Vertex], levels: &[&[u32]]) {
        let (indices, coarser) = levels.split_first().expect("a fine level");
        match self.dynamic.get(&key) {
            Some((m, n))
                if *n == vertices.len()
                    && m.count as usize == indices.len()
                    && m.coarser.len() == coarser.len()
                    && m.coarser
                        .iter()
                        .zip(coarser)
                        .all(|(m, c)| m.1 as usize == c.len()) =>
            {
                self.queue
                    .write_buffer(&m.vertices, 0, bytemuck::cast_slice(vertices));
            }
            _ => {
                let data = MeshData {
                    vertices: vertices.to_vec(),
                    indices: indices.to_vec(),
                };
                let mesh = self.make_mesh(&data, wgpu::BufferUsages::COPY_DST, coarser);
                self.dynamic.insert(key, (mesh, vertices.len()));
            }
        }
    }

    /// The GPU mesh of a key (a dynamic one once uploaded).
    /// The mesh a draw names, if it has anything to draw (a head without
    /// lid rims has no lashes, one without a hairline no hair shell).
    pub(super) fn mesh_of(&self, key: MeshKey) -> Option<&GpuMesh> {
        match key {
            MeshKey::Face
            | MeshKey::Body
            | MeshKey::Avatar
            | MeshKey::Lashes
            | MeshKey::HairShell => self.dynamic.get(&key).map(|(m, _)| m),
            key => self.meshes.get(&key),
        }
        .filter(|m| m.count > 0)
    }

    /// What a draw of `key` casts its shadow with: the mesh's coarse level
    /// of detail where it has one (the bodies, the head), the coarse sphere
    /// for a sphere, else the mesh (vertices, indices, index count). A
    /// shadow map's texel (2-4 mm) is coarser than the fine meshes' detail,
    /// and on a software rasteriser every triangle costs, however small.
    pub(super) fn caster(&self, key: MeshKey) -> Option<(&wgpu::Buffer, &wgpu::Buffer, u32)> {
        let key = if key == MeshKey::Sphere {
            MeshKey::Blob
        } else {
            key
        };
        let mesh = self.mesh_of(key)?;
        Some(match mesh.coarser.last() {
            Some((indices, count)) => (&mesh.vertices, indices, *count),
            None => (&mesh.vertices, &mesh.indices, mesh.count),
        })
    }
}
