//! The uniforms' layouts in memory and on the GPU, and the buffers that
//! grow with a frame's draws and lines.

use std::num::NonZeroU64;

/// The uniforms every draw shares (`Globals` in `shader.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
pub(super) struct Globals {
    pub(super) view_proj: [[f32; 4]; 4],
    pub(super) camera: [f32; 4],
    pub(super) key_dir: [f32; 4],
    pub(super) fill_dir: [f32; 4],
    /// x: the floor's light, the same at every point of it.
    pub(super) floor_light: [f32; 4],
    /// The face's lips, brows and hair, and the inside of the mouth
    /// (linear RGB).
    pub(super) face_regions: [[f32; 4]; 4],
    /// The lips' shape (`LipShape`): half-width, mouth line, upper and
    /// lower border at the middle; the depth in front of which it is lip.
    pub(super) lips: [[f32; 4]; 2],
    /// World to the top light's clip space (its shadow map).
    pub(super) light_view_proj: [[f32; 4]; 4],
    /// The top light's direction of travel.
    pub(super) top_dir: [f32; 4],
    /// x: the top light's strength; y: shadows on (1) or off (0); z: the
    /// normal offset of a shadow lookup, m (a texel and a half).
    pub(super) shadow: [f32; 4],
    /// The rim light's direction of travel (xyz) and strength (w).
    pub(super) rim_dir: [f32; 4],
}

/// One draw's uniforms (`Instance` in `shader.wgsl`), at a dynamic
/// offset of [`super::INSTANCE_STRIDE`] bytes a draw.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
pub(super) struct Instance {
    pub(super) model: [[f32; 4]; 4],
    pub(super) normal: [[f32; 4]; 4],
    pub(super) color: [f32; 4],
    pub(super) params: [f32; 4],
}

/// A grown-on-demand GPU buffer.
pub(super) struct Growable {
    pub(super) buffer: wgpu::Buffer,
    capacity: u64,
    usage: wgpu::BufferUsages,
    label: &'static str,
}

impl Growable {
    pub(super) fn new(
        device: &wgpu::Device,
        label: &'static str,
        usage: wgpu::BufferUsages,
    ) -> Self {
        let capacity = 64 * 1024;
        Growable {
            buffer: Self::alloc(device, label, usage, capacity),
            capacity,
            usage,
            label,
        }
    }

    fn alloc(
        device: &wgpu::Device,
        label: &str,
        usage: wgpu::BufferUsages,
        size: u64,
    ) -> wgpu::Buffer {
        device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size,
            usage: usage | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        })
    }

    /// Make room for `size` bytes; true if the buffer was replaced.
    pub(super) fn reserve(&mut self, device: &wgpu::Device, size: u64) -> bool {
        if size <= self.capacity {
            return false;
        }
        self.capacity = size.next_power_of_two();
        self.buffer = Self::alloc(device, self.label, self.usage, self.capacity);
        true
    }
}

/// A bind group layout of one uniform buffer of `size` bytes (at a
/// dynamic offset if `dynamic`).
pub(super) fn uniform_layout(
    device: &wgpu::Device,
    dynamic: bool,
    size: u64,
) -> wgpu::BindGroupLayout {
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("shisen uniforms"),
        entries: &[wgpu::BindGroupLayoutEntry {
            binding: 0,
            visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: dynamic,
                min_binding_size: NonZeroU64::new(size),
            },
            count: None,
        }],
    })
}

/// A bind group of the first `size` bytes of `buffer` under `layout`.
pub(super) fn bind(
    device: &wgpu::Device,
    layout: &wgpu::BindGroupLayout,
    buffer: &wgpu::Buffer,
    size: u64,
) -> wgpu::BindGroup {
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("shisen uniforms"),
        layout,
        entries: &[wgpu::BindGroupEntry {
            binding: 0,
            resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                buffer,
                offset: 0,
                size: NonZeroU64::new(size),
            }),
        }],
    })
}
