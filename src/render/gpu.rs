//! The wgpu renderer: draws a [`Frame`] into its own colour texture (4x
//! MSAA resolved into an sRGB texture), which is read back for PNGs or
//! copied into the window by [`super::Blit`]. The same code path serves both.

use std::collections::HashMap;
use std::num::NonZeroU64;

use glam::{Mat3, Mat4, Vec3};
use wgpu::util::DeviceExt;

use shisen_face::mesh::HeadMesh;

use super::draw::{
    FILL_DIR, KEY_DIR, LineVertex, Material, MeshKey, TOP_DIR, TOP_LIGHT, key_fill_light,
};
use super::frame::{AvatarPart, Frame, Looks};
use super::geometry::{self, MeshData, Vertex};
use super::lod::{self, Sight};

/// Rendering errors.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// No wgpu adapter (no GPU and no software Vulkan/GL driver).
    #[error(
        "no graphics adapter: {0} (on a machine without a GPU install Mesa's \
         lavapipe: apt-get install mesa-vulkan-drivers libvulkan1)"
    )]
    NoAdapter(String),
    /// The adapter refused to create a device.
    #[error("cannot create a device: {0}")]
    Device(#[from] wgpu::RequestDeviceError),
    /// Reading the picture back failed.
    #[error("reading the picture back failed: {0}")]
    Readback(String),
    /// Read-back was asked for before anything was rendered.
    #[error("nothing rendered yet")]
    NothingRendered,
    /// Writing the PNG failed.
    #[error("cannot write {path}: {source}")]
    Write {
        /// Output path.
        path: String,
        /// Cause.
        source: image::ImageError,
    },
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

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct Globals {
    view_proj: [[f32; 4]; 4],
    camera: [f32; 4],
    key_dir: [f32; 4],
    fill_dir: [f32; 4],
    /// x: the floor's light, the same at every point of it.
    floor_light: [f32; 4],
    /// The face's lips, brows and hair, and the inside of the mouth
    /// (linear RGB).
    face_regions: [[f32; 4]; 4],
    /// The lips' shape (`LipShape`): half-width, mouth line, upper and
    /// lower border at the middle; the depth in front of which it is lip.
    lips: [[f32; 4]; 2],
    /// World to the top light's clip space (its shadow map).
    light_view_proj: [[f32; 4]; 4],
    /// The top light's direction of travel.
    top_dir: [f32; 4],
    /// x: the top light's strength; y: shadows on (1) or off (0); z: the
    /// normal offset of a shadow lookup, m (a texel and a half).
    shadow: [f32; 4],
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct Instance {
    model: [[f32; 4]; 4],
    normal: [[f32; 4]; 4],
    color: [f32; 4],
    params: [f32; 4],
}

struct GpuMesh {
    vertices: wgpu::Buffer,
    indices: wgpu::Buffer,
    count: u32,
    /// Coarser levels of detail over the same vertices, finer first (each
    /// its indices and their count); the coarsest casts the shadow.
    coarser: Vec<(wgpu::Buffer, u32)>,
}

impl GpuMesh {
    /// The index buffer of level of detail `level` (0 the fine one) and
    /// its index count, if the mesh has it.
    fn level(&self, level: usize) -> Option<(&wgpu::Buffer, u32)> {
        match level {
            0 => Some((&self.indices, self.count)),
            l => self.coarser.get(l - 1).map(|(indices, n)| (indices, *n)),
        }
    }
}

struct Target {
    size: (u32, u32),
    color: wgpu::Texture,
    color_view: wgpu::TextureView,
    msaa_view: Option<wgpu::TextureView>,
    depth_view: wgpu::TextureView,
}

/// A grown-on-demand GPU buffer.
struct Growable {
    buffer: wgpu::Buffer,
    capacity: u64,
    usage: wgpu::BufferUsages,
    label: &'static str,
}

impl Growable {
    fn new(device: &wgpu::Device, label: &'static str, usage: wgpu::BufferUsages) -> Self {
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
    fn reserve(&mut self, device: &wgpu::Device, size: u64) -> bool {
        if size <= self.capacity {
            return false;
        }
        self.capacity = size.next_power_of_two();
        self.buffer = Self::alloc(device, self.label, self.usage, self.capacity);
        true
    }
}

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

fn uniform_layout(device: &wgpu::Device, dynamic: bool, size: u64) -> wgpu::BindGroupLayout {
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

fn bind(
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
            source: wgpu::ShaderSource::Wgsl(shader_source().into()),
        });
        let globals_size = size_of::<Globals>() as u64;
        let instance_size = size_of::<Instance>() as u64;
        let shadow_globals_layout = uniform_layout(device, false, globals_size);
        let globals_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("shisen globals"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: false,
                        min_binding_size: NonZeroU64::new(globals_size),
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 1,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Depth,
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 2,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Comparison),
                    count: None,
                },
            ],
        });
        let instance_layout = uniform_layout(device, true, instance_size);
        let shadow_view = device
            .create_texture(&wgpu::TextureDescriptor {
                label: Some("shisen shadow map"),
                size: wgpu::Extent3d {
                    width: shadow_size,
                    height: shadow_size,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: DEPTH_FORMAT,
                usage: wgpu::TextureUsages::RENDER_ATTACHMENT
                    | wgpu::TextureUsages::TEXTURE_BINDING,
                view_formats: &[],
            })
            .create_view(&Default::default());
        let shadow_sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("shisen shadow"),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            compare: Some(wgpu::CompareFunction::LessEqual),
            ..Default::default()
        });
        let globals = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("shisen globals"),
            size: globals_size,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let shadow_globals_bind = bind(device, &shadow_globals_layout, &globals, globals_size);
        let globals_bind = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("shisen globals"),
            layout: &globals_layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                        buffer: &globals,
                        offset: 0,
                        size: NonZeroU64::new(globals_size),
                    }),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(&shadow_view),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: wgpu::BindingResource::Sampler(&shadow_sampler),
                },
            ],
        });
        let instances = Growable::new(device, "shisen instances", wgpu::BufferUsages::UNIFORM);
        let instance_bind = bind(device, &instance_layout, &instances.buffer, instance_size);
        let lines = Growable::new(device, "shisen lines", wgpu::BufferUsages::VERTEX);

        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("shisen"),
            bind_group_layouts: &[Some(&globals_layout), Some(&instance_layout)],
            immediate_size: 0,
        });
        let mesh_attrs = wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32x4, 3 => Float32x4, 4 => Float32x4, 5 => Float32x2];
        let line_attrs = wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x4];
        let pipeline = |vs: &str,
                        fs: &str,
                        attrs: &[wgpu::VertexAttribute],
                        stride: usize,
                        topology: wgpu::PrimitiveTopology,
                        depth_write: bool,
                        compare: wgpu::CompareFunction,
                        cull_mode: Option<wgpu::Face>| {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(vs),
                layout: Some(&layout),
                vertex: wgpu::VertexState {
                    module: &shader,
                    entry_point: Some(vs),
                    compilation_options: Default::default(),
                    buffers: &[Some(wgpu::VertexBufferLayout {
                        array_stride: stride as u64,
                        step_mode: wgpu::VertexStepMode::Vertex,
                        attributes: attrs,
                    })],
                },
                primitive: wgpu::PrimitiveState {
                    topology,
                    cull_mode,
                    ..Default::default()
                },
                depth_stencil: Some(wgpu::DepthStencilState {
                    format: DEPTH_FORMAT,
                    depth_write_enabled: Some(depth_write),
                    depth_compare: Some(compare),
                    stencil: Default::default(),
                    bias: Default::default(),
                }),
                multisample: wgpu::MultisampleState {
                    count: samples,
                    ..Default::default()
                },
                fragment: Some(wgpu::FragmentState {
                    module: &shader,
                    entry_point: Some(fs),
                    compilation_options: Default::default(),
                    targets: &[Some(wgpu::ColorTargetState {
                        format: COLOR_FORMAT,
                        blend: Some(wgpu::BlendState::ALPHA_BLENDING),
                        write_mask: wgpu::ColorWrites::ALL,
                    })],
                }),
                multiview_mask: None,
                cache: None,
            })
        };
        let mesh = |vs, fs, cull_mode| {
            pipeline(
                vs,
                fs,
                &mesh_attrs,
                size_of::<Vertex>(),
                wgpu::PrimitiveTopology::TriangleList,
                true,
                wgpu::CompareFunction::Less,
                cull_mode,
            )
        };
        // Each material its own fragment stage, which no other pays for;
        // closed meshes wound counter-clockwise seen from outside (the
        // bodies, spheres, capsules, boxes) never show their inside: their
        // back faces are skipped, half their triangles.
        let mut pipelines = HashMap::new();
        for m in Material::ALL {
            let (vs, fs) = m.stages();
            for closed in [false, true] {
                let cull = closed.then_some(wgpu::Face::Back);
                pipelines.insert((m, closed), mesh(vs, fs, cull));
            }
        }
        // Overlays are drawn over everything so rays inside the head show.
        let line_pipeline = pipeline(
            "vs_line",
            "fs_line",
            &line_attrs,
            size_of::<LineVertex>(),
            wgpu::PrimitiveTopology::LineList,
            false,
            wgpu::CompareFunction::Always,
            None,
        );
        // Depth from the top light: the vertex stage alone, back faces
        // culled (the lit side's depth is what shadows, and half the
        // triangles), biased by slope.
        let shadow_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("shisen shadow"),
            bind_group_layouts: &[Some(&shadow_globals_layout), Some(&instance_layout)],
            immediate_size: 0,
        });
        let shadow_pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("shisen shadow"),
            layout: Some(&shadow_layout),
            vertex: wgpu::VertexState {
                module: &shader,
                entry_point: Some("vs_shadow"),
                compilation_options: Default::default(),
                buffers: &[Some(wgpu::VertexBufferLayout {
                    array_stride: size_of::<Vertex>() as u64,
                    step_mode: wgpu::VertexStepMode::Vertex,
                    attributes: &mesh_attrs[..1],
                })],
            },
            primitive: wgpu::PrimitiveState {
                cull_mode: Some(wgpu::Face::Back),
                ..Default::default()
            },
            depth_stencil: Some(wgpu::DepthStencilState {
                format: DEPTH_FORMAT,
                depth_write_enabled: Some(true),
                depth_compare: Some(wgpu::CompareFunction::Less),
                stencil: Default::default(),
                bias: wgpu::DepthBiasState {
                    constant: 2,
                    slope_scale: 2.0,
                    clamp: 0.0,
                },
            }),
            multisample: Default::default(),
            fragment: None,
            multiview_mask: None,
            cache: None,
        });
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
        // Crowns: boxy, with edges rounded over about a fifth of their size.
        r.upload(MeshKey::Tooth, &geometry::rounded_box(5.0));
        r.upload(MeshKey::Blob, &geometry::rounded_box(2.0));
        r
    }

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

    fn upload(&mut self, key: MeshKey, data: &MeshData) {
        let mesh = self.make_mesh(data, wgpu::BufferUsages::empty(), &[]);
        self.meshes.insert(key, mesh);
    }

    /// Whether the adapter is a software rasteriser.
    pub fn software(&self) -> bool {
        self.software
    }

    /// MSAA sample count in use (4 where the adapter supports it).
    pub fn samples(&self) -> u32 {
        self.samples
    }

    fn ensure_target(&mut self, size: (u32, u32)) {
        if self.target.as_ref().is_some_and(|t| t.size == size) {
            return;
        }
        let extent = wgpu::Extent3d {
            width: size.0.max(1),
            height: size.1.max(1),
            depth_or_array_layers: 1,
        };
        let texture = |label, format, samples, usage, view_formats: &[wgpu::TextureFormat]| {
            self.device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: extent,
                mip_level_count: 1,
                sample_count: samples,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage,
                view_formats,
            })
        };
        let attach = wgpu::TextureUsages::RENDER_ATTACHMENT;
        let color = texture(
            "shisen colour",
            COLOR_FORMAT,
            1,
            attach | wgpu::TextureUsages::COPY_SRC | wgpu::TextureUsages::TEXTURE_BINDING,
            &[COLOR_FORMAT_UNORM],
        );
        let msaa_view = (self.samples > 1).then(|| {
            texture("shisen msaa", COLOR_FORMAT, self.samples, attach, &[])
                .create_view(&Default::default())
        });
        let depth_view = texture("shisen depth", DEPTH_FORMAT, self.samples, attach, &[])
            .create_view(&Default::default());
        self.target = Some(Target {
            size,
            color_view: color.create_view(&Default::default()),
            color,
            msaa_view,
            depth_view,
        });
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

    /// Upload this frame's vertices of a dynamic mesh; its buffers are
    /// rebuilt (with `indices`) only when the vertex or index count
    /// changes.
    fn dynamic_mesh(&mut self, key: MeshKey, vertices: &[Vertex], levels: &[&[u32]]) {
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

    /// Draw `frame` at `size` pixels; `face`'s triangles (and its coarse
    /// shell, for the shadow) index [`Frame::face`]. Submits the work; the
    /// result is in [`Renderer::color_texture`].
    pub fn render(&mut self, frame: &Frame, face: &HeadMesh, size: (u32, u32)) {
        self.render_then(frame, face, size, |_, _| ());
    }

    /// [`Renderer::render`], with `then` recording more work after the
    /// frame's into the same submission (given the encoder and the
    /// picture): on lavapipe a second submission waits for the first to
    /// finish, one does not.
    pub fn render_then(
        &mut self,
        frame: &Frame,
        face: &HeadMesh,
        size: (u32, u32),
        then: impl FnOnce(&mut wgpu::CommandEncoder, &wgpu::Texture),
    ) -> wgpu::SubmissionIndex {
        self.ensure_target(size);
        for d in &frame.draws {
            if let MeshKey::Capsule {
                half_height,
                radius,
            } = d.mesh
                && !self.meshes.contains_key(&d.mesh)
            {
                let data = geometry::capsule(f32::from_bits(half_height), f32::from_bits(radius));
                self.upload(d.mesh, &data);
            }
        }
        self.dynamic_mesh(
            MeshKey::Face,
            &frame.face,
            &[
                face.triangles.as_flattened(),
                face.medium.as_flattened(),
                face.coarse.as_flattened(),
            ],
        );
        let lashes: Vec<u32> = (0..frame.lashes.len() as u32).collect();
        self.dynamic_mesh(MeshKey::Lashes, &frame.lashes, &[&lashes]);
        let [hair, hair_medium] = &frame.hair.1;
        self.dynamic_mesh(MeshKey::HairShell, &frame.hair.0, &[hair, hair_medium]);
        // The bodies by pieces: those in view, each at its level of detail.
        let looks = Looks::of(&frame.plan);
        let cam = &frame.camera;
        let sight = Sight::new(cam.view_proj(), cam.eye, cam.fov_y, size.1);
        // The head (the face and its hair) at its middle level of detail
        // where that departs from the fine one by under a pixel.
        let head_level = frame
            .draws
            .iter()
            .find(|d| d.mesh == MeshKey::Face)
            .map_or(0, |d| {
                let (centre, radius) = bounding_sphere(&face.positions);
                sight.level(face.medium_error, d.model.transform_point3(centre), radius)
            });
        let mut body_runs = Vec::new();
        for (key, vertices, part) in [
            (MeshKey::Body, &frame.body, AvatarPart::Whole),
            (MeshKey::Avatar, &frame.avatar, frame.avatar_indices),
        ] {
            let (levels, pieces) = looks.levels(key, part);
            self.dynamic_mesh(key, vertices, &levels);
            body_runs.push((key, lod::runs(pieces, vertices, &sight)));
        }
        let (key, fill) = (KEY_DIR.normalize(), FILL_DIR.normalize());
        // The shader's plain lighting on the floor's upward normal.
        let floor_light = key_fill_light(Vec3::Y);
        let redo_shadow =
            self.shadow_light.is_none() || self.frames.is_multiple_of(self.shadow_every);
        self.frames += 1;
        if redo_shadow {
            self.shadow_light = Some(shadow_frustum(frame.shadow_focus, self.shadow_size));
        }
        let (light_view_proj, texel) = self.shadow_light.expect("set above");
        let globals = Globals {
            light_view_proj: light_view_proj.to_cols_array_2d(),
            top_dir: TOP_DIR.normalize().extend(0.0).to_array(),
            shadow: [TOP_LIGHT, 1.0, 1.5 * texel, 0.0],
            view_proj: cam.view_proj().to_cols_array_2d(),
            camera: cam.eye.extend(1.0).to_array(),
            key_dir: key.extend(0.0).to_array(),
            fill_dir: fill.extend(0.0).to_array(),
            floor_light: [floor_light, 0.0, 0.0, 0.0],
            lips: {
                let l = &frame.lips;
                [
                    [l.half_w, l.mouth_y, l.top, l.bottom],
                    [l.front_z, 0.0, 0.0, 0.0],
                ]
            },
            face_regions: {
                let s = &shisen_face::appearance::FaceStyle::DEFAULT;
                [s.lips, s.brow, s.hair, s.inside].map(|c| [c[0], c[1], c[2], 1.0])
            },
        };
        self.queue
            .write_buffer(&self.globals, 0, bytemuck::bytes_of(&globals));
        let mut bytes = vec![0u8; frame.draws.len() * INSTANCE_STRIDE as usize];
        for (d, chunk) in frame
            .draws
            .iter()
            .zip(bytes.chunks_mut(INSTANCE_STRIDE as usize))
        {
            let normal = Mat4::from_mat3(Mat3::from_mat4(d.model).inverse().transpose());
            let inst = Instance {
                model: d.model.to_cols_array_2d(),
                normal: normal.to_cols_array_2d(),
                color: d.color,
                params: [d.material as u32 as f32, 0.0, 0.0, 0.0],
            };
            chunk[..size_of::<Instance>()].copy_from_slice(bytemuck::bytes_of(&inst));
        }
        if self.instances.reserve(&self.device, bytes.len() as u64) {
            self.instance_bind = bind(
                &self.device,
                &self.instance_layout,
                &self.instances.buffer,
                size_of::<Instance>() as u64,
            );
        }
        self.queue.write_buffer(&self.instances.buffer, 0, &bytes);
        let line_bytes: &[u8] = bytemuck::cast_slice(&frame.lines);
        self.lines.reserve(&self.device, line_bytes.len() as u64);
        if !line_bytes.is_empty() {
            self.queue.write_buffer(&self.lines.buffer, 0, line_bytes);
        }

        let target = self.target.as_ref().expect("ensured");
        let mut enc = self
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("shisen frame"),
            });
        if redo_shadow {
            let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("shisen shadow"),
                color_attachments: &[],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &self.shadow_view,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(1.0),
                        store: wgpu::StoreOp::Store,
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&self.shadow_pipeline);
            pass.set_bind_group(0, &self.shadow_globals_bind, &[]);
            for (i, d) in frame.draws.iter().enumerate() {
                if !d.material.casts(d.mesh) {
                    continue;
                }
                let Some((vertices, indices, count)) = self.caster(d.mesh) else {
                    continue;
                };
                pass.set_bind_group(
                    1,
                    &self.instance_bind,
                    &[(i as u64 * INSTANCE_STRIDE) as u32],
                );
                pass.set_vertex_buffer(0, vertices.slice(..));
                pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint32);
                pass.draw_indexed(0..count, 0, 0..1);
            }
        }
        {
            let (view, resolve) = match &target.msaa_view {
                Some(m) => (m, Some(&target.color_view)),
                None => (&target.color_view, None),
            };
            let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("shisen scene"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view,
                    depth_slice: None,
                    resolve_target: resolve,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(CLEAR),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &target.depth_view,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(1.0),
                        store: wgpu::StoreOp::Discard,
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_bind_group(0, &self.globals_bind, &[]);
            for (i, d) in frame.draws.iter().enumerate() {
                let key = match d.mesh {
                    MeshKey::Sphere if sight.coarse_sphere(d.model) => MeshKey::Blob,
                    key => key,
                };
                let Some(mesh) = self.mesh_of(key) else {
                    continue;
                };
                // The skinned bodies are closed (their keys are dynamic).
                let closed = d.mesh.is_closed() || d.material == Material::Body;
                pass.set_pipeline(&self.pipelines[&(d.material, closed)]);
                pass.set_bind_group(
                    1,
                    &self.instance_bind,
                    &[(i as u64 * INSTANCE_STRIDE) as u32],
                );
                pass.set_vertex_buffer(0, mesh.vertices.slice(..));
                let runs = body_runs.iter().find(|(k, _)| *k == d.mesh);
                let Some((_, runs)) = runs else {
                    let level = match d.mesh {
                        MeshKey::Face | MeshKey::HairShell => head_level,
                        _ => 0,
                    };
                    let Some((indices, count)) = mesh.level(level) else {
                        continue;
                    };
                    pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint32);
                    pass.draw_indexed(0..count, 0, 0..1);
                    continue;
                };
                for run in runs {
                    let Some((indices, _)) = mesh.level(run.level) else {
                        continue;
                    };
                    pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint32);
                    pass.draw_indexed(run.range.clone(), 0, 0..1);
                }
            }
            if !frame.lines.is_empty() {
                pass.set_pipeline(&self.line_pipeline);
                pass.set_bind_group(1, &self.instance_bind, &[0]);
                pass.set_vertex_buffer(0, self.lines.buffer.slice(..line_bytes.len() as u64));
                pass.draw(0..frame.lines.len() as u32, 0..1);
            }
        }
        if let Some(target) = &self.target {
            then(&mut enc, &target.color);
        }
        self.queue.submit([enc.finish()])
    }

    /// The GPU mesh of a key (a dynamic one once uploaded).
    /// The mesh a draw names, if it has anything to draw (a head without
    /// lid rims has no lashes, one without a hairline no hair shell).
    fn mesh_of(&self, key: MeshKey) -> Option<&GpuMesh> {
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
    fn caster(&self, key: MeshKey) -> Option<(&wgpu::Buffer, &wgpu::Buffer, u32)> {
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

    /// Block until the GPU has finished the submitted work.
    pub fn wait(&self) {
        if let Err(e) = self.device.poll(wgpu::PollType::wait_indefinitely()) {
            tracing::warn!(error = %e, "device poll failed");
        }
    }

    /// Copy the last render back to the CPU (blocks until the GPU is done).
    pub fn read_rgba(&self) -> Result<image::RgbaImage, RenderError> {
        let target = self.target.as_ref().ok_or(RenderError::NothingRendered)?;
        self.read_texture(&target.color)
    }

    /// Copy a picture of this renderer's device (in its colour format,
    /// with `COPY_SRC` use) back to the CPU (blocks until the GPU is done).
    pub fn read_texture(&self, texture: &wgpu::Texture) -> Result<image::RgbaImage, RenderError> {
        let (w, h) = (texture.width(), texture.height());
        let row = w * 4;
        let padded =
            row.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
        let buffer = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("shisen readback"),
            size: padded as u64 * h as u64,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut enc = self
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("shisen readback"),
            });
        enc.copy_texture_to_buffer(
            texture.as_image_copy(),
            wgpu::TexelCopyBufferInfo {
                buffer: &buffer,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(padded),
                    rows_per_image: None,
                },
            },
            wgpu::Extent3d {
                width: w,
                height: h,
                depth_or_array_layers: 1,
            },
        );
        self.queue.submit([enc.finish()]);
        let slice = buffer.slice(..);
        let (tx, rx) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |r| {
            let _ = tx.send(r);
        });
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| RenderError::Readback(e.to_string()))?;
        rx.recv()
            .map_err(|e| RenderError::Readback(e.to_string()))?
            .map_err(|e| RenderError::Readback(e.to_string()))?;
        let data = slice
            .get_mapped_range()
            .map_err(|e| RenderError::Readback(e.to_string()))?;
        let mut pixels = Vec::with_capacity((row * h) as usize);
        for r in data.chunks(padded as usize) {
            pixels.extend_from_slice(&r[..row as usize]);
        }
        drop(data);
        buffer.unmap();
        image::RgbaImage::from_raw(w, h, pixels)
            .ok_or_else(|| RenderError::Readback("short image".into()))
    }
}

/// A sphere round `points`: the centre of their box and the farthest
/// point's distance from it.
fn bounding_sphere(points: &[Vec3]) -> (Vec3, f32) {
    let (min, max) = points
        .iter()
        .fold((Vec3::MAX, Vec3::MIN), |(a, b), p| (a.min(*p), b.max(*p)));
    let centre = (min + max) / 2.0;
    let radius = points
        .iter()
        .map(|p| p.distance(centre))
        .fold(0.0, f32::max);
    (centre, radius)
}

/// The top light's view and orthographic projection over a sphere of
/// `focus` (centre, radius), snapped to whole texels of a `size`-texel map
/// so the shadows do not shimmer as the fighters move; and the world size
/// of a texel.
fn shadow_frustum((centre, radius): (Vec3, f32), size: u32) -> (Mat4, f32) {
    let dir = TOP_DIR.normalize();
    let view = glam::camera::rh::view::look_at_mat4(Vec3::ZERO, dir, Vec3::Z);
    let texel = 2.0 * radius / size as f32;
    let c = view.transform_point3(centre);
    let snap = |v: f32| (v / texel).round() * texel;
    let (x, y) = (snap(c.x), snap(c.y));
    // The light looks down -Z of its view: the near plane well above the
    // rig, the far plane below the hall's floor.
    let proj = glam::camera::rh::proj::directx::orthographic(
        x - radius,
        x + radius,
        y - radius,
        y + radius,
        -c.z - 12.0,
        -c.z + 6.0,
    );
    (proj * view, texel)
}

/// The main shader, with the eye's drawn proportions (`anatomy::eye`)
/// prepended as WGSL constants: one home for the iris's size, which the
/// face's lid tests measure against.
fn shader_source() -> String {
    use super::body::{VEST_ARMHOLE, VEST_HEM, VEST_NECK};
    use shisen_face::appearance::{LIP_BOW, LIP_DIP, LIP_SOFT, LIP_TAPER, MOUTH_EDGE};
    use shisen_gaze::anatomy::eye;
    let cos = |deg: f64| deg.to_radians().cos();
    format!(
        "const PUPIL_COS: f32 = {:.6};\nconst LIMBUS_COS: f32 = {:.6};\nconst IRIS_COS: f32 = {:.6};\n\
         const MOUTH_INSIDE_LIMIT: f32 = {:.6};\nconst LIP_TAPER: f32 = {:.6};\n\
         const LIP_BOW: vec3<f32> = vec3<f32>({:.6}, {:.6}, {:.6});\n\
         const LIP_DIP: vec2<f32> = vec2<f32>({:.6}, {:.6});\nconst LIP_SOFT: f32 = {:.6};\n\
         const MOUTH_EDGE: f32 = {:.6};\n\
         const VEST_ARMHOLE: vec4<f32> = vec4<f32>({:.6}, {:.6}, {:.6}, {:.6});\n\
         const VEST_NECK: array<f32, 6> = array<f32, 6>({:.6}, {:.6}, {:.6}, {:.6}, {:.6}, {:.6});\n\
         const VEST_HEM: vec2<f32> = vec2<f32>({:.6}, {:.6});\n{}",
        cos(eye::PUPIL_DEG),
        cos(eye::LIMBUS_DEG),
        cos(eye::IRIS_DEG),
        shisen_face::appearance::MOUTH_INSIDE_LIMIT,
        LIP_TAPER,
        LIP_BOW[0],
        LIP_BOW[1],
        LIP_BOW[2],
        LIP_DIP[0],
        LIP_DIP[1],
        LIP_SOFT,
        MOUTH_EDGE,
        VEST_ARMHOLE[0],
        VEST_ARMHOLE[1],
        VEST_ARMHOLE[2],
        VEST_ARMHOLE[3],
        VEST_NECK[0],
        VEST_NECK[1],
        VEST_NECK[2],
        VEST_NECK[3],
        VEST_NECK[4],
        VEST_NECK[5],
        VEST_HEM[0],
        VEST_HEM[1],
        include_str!("shader.wgsl")
    )
}
