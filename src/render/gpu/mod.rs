//! The wgpu renderer: draws a [`Frame`] into its own colour texture (4x
//! MSAA resolved into an sRGB texture), which is read back for PNGs or
//! copied into the window by [`super::Blit`]. The same code path serves both.
//!
//! Built once (`pipelines`: the shader, layouts, shadow map and
//! pipelines); every frame, `passes` uploads its meshes (`meshes`), writes
//! its uniforms (`uniforms`) and draws the shadow and the scene into the
//! `target`.

mod meshes;
mod passes;
mod pipelines;
mod target;
mod uniforms;

use std::collections::HashMap;

use glam::Mat4;

use shisen_face::mesh::HeadMesh;

use super::draw::{Material, MeshKey};
use super::frame::Frame;
use super::geometry;
use meshes::GpuMesh;
use target::Target;
use uniforms::{Globals, Growable, Instance, bind, uniform_layout};

/// Rendering errors.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// No wgpu adapter (no GPU and no software Vulkan/GL driver).
    #[error(
        "no graphics adapter: {0} (on a machine without a GPU install Mesa's \
         lavapipe: apt-get install mesa-vulkan-drivers libvulkan1)"
    )]
    NoAdapter(String),
    /// The adapter refused to create a device (its error in the message,
    /// not as a cause: a report of the chain says it once).
    #[error("cannot create a device: {0}")]
    Device(wgpu::RequestDeviceError),
    /// Reading the picture back failed.
    #[error("reading the picture back failed: {0}")]
    Readback(String),
    /// Read-back was asked for before anything was rendered.
    #[error("nothing rendered yet")]
    NothingRendered,
    /// Writing the PNG failed.
    #[error("cannot write {path}: {error}")]
    Write {
        /// Output path.
        path: String,
        /// What went wrong.
        error: image::ImageError,
    },
}

impl From<wgpu::RequestDeviceError> for RenderError {
    fn from(e: wgpu::RequestDeviceError) -> Self {
        RenderError::Device(e)
    }
}

/// Format of the resolved colour texture (PNG bytes are its raw contents).
pub const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;
/// The same texture viewed without sRGB decoding, as egui samples its images.
pub const COLOR_FORMAT_UNORM: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;
const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
/// Shadow map side, texels: on a GPU, and on a software rasteriser,
/// where a depth pass over the bodies costs in proportion (the map covers
/// both fighters and their shadows: about 4 m, 2 mm a texel at 2048).
const SHADOW_SIZE: [u32; 2] = [2048, 1024];
/// Dynamic-offset stride of the per-instance uniforms.
const INSTANCE_STRIDE: u64 = 256;
/// Background (linear RGB).
const CLEAR: wgpu::Color = wgpu::Color {
    r: 0.035,
    g: 0.04,
    b: 0.05,
    a: 1.0,
};

/// The renderer and its GPU resources.
pub struct Renderer {
    device: wgpu::Device,
    queue: wgpu::Queue,
    samples: u32,
    /// A software rasteriser (lavapipe, llvmpipe).
    software: bool,
    /// A pipeline per material and culling (back faces skipped for
    /// closed meshes).
    pipelines: HashMap<(Material, bool), wgpu::RenderPipeline>,
    line_pipeline: wgpu::RenderPipeline,
    /// Depth from the top light.
    shadow_pipeline: wgpu::RenderPipeline,
    shadow_view: wgpu::TextureView,
    shadow_size: u32,
    /// The shadow map is drawn every this many frames (the window on a
    /// software rasteriser: every other frame), and its light's matrix
    /// and texel size as last drawn.
    shadow_every: u64,
    shadow_light: Option<(Mat4, f32)>,
    frames: u64,
    /// The globals alone (the shadow pass: its map is not bound there).
    shadow_globals_bind: wgpu::BindGroup,
    globals: wgpu::Buffer,
    globals_bind: wgpu::BindGroup,
    instance_layout: wgpu::BindGroupLayout,
    instances: Growable,
    instance_bind: wgpu::BindGroup,
    lines: Growable,
    meshes: HashMap<MeshKey, GpuMesh>,
    /// Meshes whose vertices change every frame (face, bodies), with
    /// their vertex count.
    dynamic: HashMap<MeshKey, (GpuMesh, usize)>,
    target: Option<Target>,
}

impl Renderer {
    /// Build the pipelines on `device` (a clone of the handle is kept),
    /// with 4x multisampling where the adapter has it.
    pub fn new(adapter: &wgpu::Adapter, device: &wgpu::Device, queue: &wgpu::Queue) -> Self {
        Self::with_samples(adapter, device, queue, 4)
    }

    /// The renderer for an interactive window: multisampling off on a
    /// software rasteriser (lavapipe, llvmpipe), where 4x costs three
    /// times a frame (measured 13 against 20 frames per second at
    /// 1280x720 on two cores); 4x on a GPU.
    pub fn for_window(adapter: &wgpu::Adapter, device: &wgpu::Device, queue: &wgpu::Queue) -> Self {
        let software = adapter.get_info().device_type == wgpu::DeviceType::Cpu;
        let mut r = Self::with_samples(adapter, device, queue, if software { 1 } else { 4 });
        // The depth pass over the bodies costs a software rasteriser a
        // sixth of a frame; at 30 updates a second a shadow trails a
        // fighter moving at 1 m/s by 3 cm.
        if software {
            r.shadow_every = 2;
        }
        r
    }

    /// Build the pipelines with at most `max_samples` samples a pixel (4,
    /// else 2, else 1, as the adapter supports; lavapipe has 4 and 1).
    pub fn with_samples(
        adapter: &wgpu::Adapter,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        max_samples: u32,
    ) -> Self {
        let flags = adapter.get_texture_format_features(COLOR_FORMAT).flags;
        let samples = [4, 2]
            .into_iter()
            .find(|&n| n <= max_samples && flags.sample_count_supported(n))
            .unwrap_or(1);
        let software = adapter.get_info().device_type == wgpu::DeviceType::Cpu;
        let shadow_size = SHADOW_SIZE[usize::from(software)];
        let shader = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("shisen shader"),
            source: wgpu::ShaderSource::Wgsl(pipelines::shader_source().into()),
        });
        let globals_size = size_of::<Globals>() as u64;
        let instance_size = size_of::<Instance>() as u64;
        let shadow_globals_layout = uniform_layout(device, false, globals_size);
        let globals_layout = pipelines::globals_layout(device, globals_size);
        let instance_layout = uniform_layout(device, true, instance_size);
        let shadow_view = pipelines::shadow_map(device, shadow_size);
        let globals = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("shisen globals"),
            size: globals_size,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let shadow_globals_bind = bind(device, &shadow_globals_layout, &globals, globals_size);
        let globals_bind = pipelines::globals_bind(
            device,
            &globals_layout,
            &globals,
            globals_size,
            &shadow_view,
        );
        let instances = Growable::new(device, "shisen instances", wgpu::BufferUsages::UNIFORM);
        let instance_bind = bind(device, &instance_layout, &instances.buffer, instance_size);
        let lines = Growable::new(device, "shisen lines", wgpu::BufferUsages::VERTEX);
        let (pipelines, line_pipeline) =
            pipelines::scene_pipelines(device, &shader, &globals_layout, &instance_layout, samples);
        let shadow_pipeline =
            pipelines::shadow_pipeline(device, &shader, &shadow_globals_layout, &instance_layout);
        let mut r = Renderer {
            device: device.clone(),
            queue: queue.clone(),
            samples,
            software,
            pipelines,
            line_pipeline,
            shadow_pipeline,
            shadow_view,
            shadow_size,
            shadow_every: 1,
            shadow_light: None,
            frames: 0,
            shadow_globals_bind,
            globals,
            globals_bind,
            instance_layout,
            instances,
            instance_bind,
            lines,
            meshes: HashMap::new(),
            dynamic: HashMap::new(),
            target: None,
        };
        r.upload(MeshKey::Sphere, &geometry::sphere());
        r.upload(MeshKey::Cube, &geometry::cube());
        r.upload(MeshKey::Floor, &geometry::floor());
        r.upload(MeshKey::Ear, &geometry::ear());
        r.upload(MeshKey::Ring, &super::ring::mesh());
        r.upload(MeshKey::Lamps, &super::ring::lamps());
        r.upload(MeshKey::Hall, &super::hall::mesh());
        for group in 0..super::hall::GROUPS {
            for standing in [false, true] {
                let key = MeshKey::Crowd {
                    group: group as u8,
                    standing,
                };
                r.upload(key, &super::hall::crowd(group, standing));
            }
        }
        // Crowns: boxy, with edges rounded over about a fifth of their size.
        r.upload(MeshKey::Tooth, &geometry::rounded_box(5.0));
        r.upload(MeshKey::Blob, &geometry::rounded_box(2.0));
        r
    }

    /// Whether the adapter is a software rasteriser.
    pub fn software(&self) -> bool {
        self.software
    }

    /// MSAA sample count in use (4 where the adapter supports it).
    pub fn samples(&self) -> u32 {
        self.samples
    }

    /// The queue the renderer submits to.
    pub fn queue(&self) -> &wgpu::Queue {
        &self.queue
    }

    /// The device the renderer draws with.
    pub(super) fn device(&self) -> &wgpu::Device {
        &self.device
    }

    /// The resolved colour texture of the last render (sRGB).
    pub fn color_texture(&self) -> Option<&wgpu::Texture> {
        self.target.as_ref().map(|t| &t.color)
    }

    /// Draw `frame` at `size` pixels; `face`'s triangles (and its coarse
    /// shell, for the shadow) index [`Frame::face`]. Submits the work; the
    /// result is in [`Renderer::color_texture`].
    pub fn render(&mut self, frame: &Frame, face: &HeadMesh, size: (u32, u32)) {
        self.render_then(frame, face, size, |_, _| ());
    }

    /// Block until the GPU has finished the submitted work.
    pub fn wait(&self) {
        if let Err(e) = self.device.poll(wgpu::PollType::wait_indefinitely()) {
            tracing::warn!(error = %e, "device poll failed");
        }
    }
}
