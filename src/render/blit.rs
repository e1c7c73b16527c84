//! The window's copy of the rendered picture, and the HUD's flat panels
//! composited in the same pass.
//!
//! The window renders its 3D view below its own resolution (the viewport's
//! render scale) and scales it up here, bilinear, in one full-window
//! triangle. Showing the picture as an egui image instead would cost
//! egui's textured, colour-converting shader on every window pixel (20 ms
//! a frame at 1280x720 on a software Vulkan, more than the scene itself).
//!
//! The HUD's dark panels are drawn here too, a quad each with a shader
//! that only blends a flat colour, not by egui: on a software rasteriser
//! egui's shader costs about 45 ns a pixel (a texture fetch with sRGB
//! decoding and three `pow`s), so the scoreboard's panels (about 80,000
//! pixels) took 5 ms of CPU a frame and 2.5 ms of the frame time at
//! 1280x720 on two cores (lavapipe). egui still draws the text on top.

use eframe::egui::{Color32, Rgba};

/// At most this many panels a frame (more are dropped: the scoreboard
/// uses up to seven). The shader's array is this long (prepended to
/// `blit.wgsl`).
pub const MAX_PANELS: usize = 12;

/// A flat rectangle with rounded corners laid over the picture, in the
/// window's physical pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Panel {
    /// Top-left corner, pixels.
    pub min: [f32; 2],
    /// Bottom-right corner, pixels.
    pub max: [f32; 2],
    /// Corner radius, pixels.
    pub radius: f32,
    /// Colour, premultiplied by its alpha, sRGB-encoded (egui's `Color32`).
    pub color: [u8; 4],
}

/// The panels as the shader reads them: the view's rectangle in window
/// pixels (min, size), their count, then per panel its rectangle,
/// premultiplied colour and radius (three `vec4`s).
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct PanelsUniform {
    view: [f32; 4],
    count: [u32; 4],
    items: [[[f32; 4]; 3]; MAX_PANELS],
}

/// Draws the renderer's last picture into another render pass (the
/// window's), scaled to it with bilinear filtering, with the HUD's panels
/// over it.
pub struct Blit {
    pipeline: wgpu::RenderPipeline,
    panel_pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    sampler: wgpu::Sampler,
    panels: wgpu::Buffer,
    /// The target decodes sRGB itself (so it is handed linear texels and
    /// colours).
    srgb_target: bool,
    /// The window's device and queue (clones of the handles).
    device: wgpu::Device,
    queue: wgpu::Queue,
}

impl Blit {
    /// A blit into passes on targets of `format` on `device`.
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue, format: wgpu::TextureFormat) -> Blit {
        let shader = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("shisen blit"),
            source: wgpu::ShaderSource::Wgsl(
                format!(
                    "const MAX_PANELS: u32 = {MAX_PANELS}u;\n{}",
                    include_str!("blit.wgsl")
                )
                .into(),
            ),
        });
        let entry = |binding, ty| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
            ty,
            count: None,
        };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("shisen blit"),
            entries: &[
                entry(
                    0,
                    wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Float { filterable: true },
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                ),
                entry(
                    1,
                    wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                ),
                entry(
                    2,
                    wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
                ),
            ],
        });
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("shisen blit"),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        let panels = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("shisen blit panels"),
            size: size_of::<PanelsUniform>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("shisen blit"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = |vs: &str, fs: &str, topology, blend| {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some("shisen blit"),
                layout: Some(&pipeline_layout),
                vertex: wgpu::VertexState {
                    module: &shader,
                    entry_point: Some(vs),
                    compilation_options: Default::default(),
                    buffers: &[],
                },
                primitive: wgpu::PrimitiveState {
                    topology,
                    ..Default::default()
                },
                depth_stencil: None,
                multisample: wgpu::MultisampleState::default(),
                fragment: Some(wgpu::FragmentState {
                    module: &shader,
                    entry_point: Some(fs),
                    compilation_options: Default::default(),
                    targets: &[Some(wgpu::ColorTargetState {
                        format,
                        blend,
                        write_mask: wgpu::ColorWrites::ALL,
                    })],
                }),
                multiview_mask: None,
                cache: None,
            })
        };
        Blit {
            pipeline: pipeline(
                "vs_blit",
                "fs_blit",
                wgpu::PrimitiveTopology::TriangleList,
                None,
            ),
            panel_pipeline: pipeline(
                "vs_panel",
                "fs_panel",
                wgpu::PrimitiveTopology::TriangleStrip,
                Some(wgpu::BlendState::PREMULTIPLIED_ALPHA_BLENDING),
            ),
            layout,
            sampler,
            panels,
            srgb_target: format.is_srgb(),
            device: device.clone(),
            queue: queue.clone(),
        }
    }

    /// Lay `panels` over the picture from the next submission on (the
    /// first [`MAX_PANELS`]), drawn into a view covering `view` (min, max,
    /// window pixels).
    pub fn set_panels(&self, view: [[f32; 2]; 2], panels: &[Panel]) {
        let [min, max] = view;
        let mut u = PanelsUniform {
            view: [
                min[0],
                min[1],
                (max[0] - min[0]).max(1.0),
                (max[1] - min[1]).max(1.0),
            ],
            count: [panels.len().min(MAX_PANELS) as u32, 0, 0, 0],
            items: [[[0.0; 4]; 3]; MAX_PANELS],
        };
        for (item, p) in u.items.iter_mut().zip(panels) {
            let [r, g, b, a] = p.color;
            // The target blends in the encoding it stores: sRGB bytes as
            // they are, or linear (egui's decoding, premultiplied again).
            let rgba = if self.srgb_target {
                Rgba::from(Color32::from_rgba_premultiplied(r, g, b, a)).to_array()
            } else {
                p.color.map(|c| f32::from(c) / 255.0)
            };
            *item = [
                [p.min[0], p.min[1], p.max[0], p.max[1]],
                rgba,
                [p.radius, 0.0, 0.0, 0.0],
            ];
        }
        self.queue
            .write_buffer(&self.panels, 0, bytemuck::bytes_of(&u));
    }

    /// What [`BlitBind::draw`] needs to draw `color` (a picture of the
    /// renderer's colour format on the blit's device).
    pub fn bind(&self, color: &wgpu::Texture) -> BlitBind {
        let view = color.create_view(&wgpu::TextureViewDescriptor {
            // The target encodes sRGB itself, or takes the bytes as they are.
            format: Some(if self.srgb_target {
                super::COLOR_FORMAT
            } else {
                super::COLOR_FORMAT_UNORM
            }),
            ..Default::default()
        });
        let group = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("shisen blit"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(&view),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::Sampler(&self.sampler),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: self.panels.as_entire_binding(),
                },
            ],
        });
        BlitBind {
            pipeline: self.pipeline.clone(),
            panel_pipeline: self.panel_pipeline.clone(),
            group,
        }
    }
}

/// A bound blit, ready to draw into a pass (cheap to clone).
#[derive(Clone)]
pub struct BlitBind {
    pipeline: wgpu::RenderPipeline,
    panel_pipeline: wgpu::RenderPipeline,
    group: wgpu::BindGroup,
}

impl BlitBind {
    /// Cover the pass's viewport with the picture and the panels.
    pub fn draw(&self, pass: &mut wgpu::RenderPass<'_>) {
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &self.group, &[]);
        pass.draw(0..3, 0..1);
        pass.set_pipeline(&self.panel_pipeline);
        pass.draw(0..4, 0..MAX_PANELS as u32);
    }
}
