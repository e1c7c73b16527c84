//! The renderer's fixed GPU state, built once: the shader, the globals'
//! layout and bind group, the shadow map, and the pipelines of the scene,
//! the overlays and the shadow pass.

use std::collections::HashMap;
use std::num::NonZeroU64;

use super::{COLOR_FORMAT, DEPTH_FORMAT};
use crate::render::draw::{LineVertex, Material};
use crate::render::geometry::Vertex;

/// The mesh vertex's attributes (`Vertex`); the shadow pass reads the
/// first, the position, alone.
const MESH_ATTRS: [wgpu::VertexAttribute; 6] = wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32x4, 3 => Float32x4, 4 => Float32x4, 5 => Float32x2];

/// The globals' layout: the uniforms (`globals_size` bytes), the shadow
/// map and its comparison sampler.
pub(super) fn globals_layout(device: &wgpu::Device, globals_size: u64) -> wgpu::BindGroupLayout {
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
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
    })
}

/// The shadow map: a depth texture `size` texels square, drawn into by the
/// shadow pass and sampled by the scene's; its view.
pub(super) fn shadow_map(device: &wgpu::Device, size: u32) -> wgpu::TextureView {
    device
        .create_texture(&wgpu::TextureDescriptor {
            label: Some("shisen shadow map"),
            size: wgpu::Extent3d {
                width: size,
                height: size,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: DEPTH_FORMAT,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        })
        .create_view(&Default::default())
}

/// The globals' bind group under `layout`: the first `size` bytes of
/// `globals`, the shadow map's view and a comparison sampler of it.
pub(super) fn globals_bind(
    device: &wgpu::Device,
    layout: &wgpu::BindGroupLayout,
    globals: &wgpu::Buffer,
    size: u64,
    shadow_view: &wgpu::TextureView,
) -> wgpu::BindGroup {
    let shadow_sampler = device.create_sampler(&wgpu::SamplerDescriptor {
        label: Some("shisen shadow"),
        mag_filter: wgpu::FilterMode::Linear,
        min_filter: wgpu::FilterMode::Linear,
        compare: Some(wgpu::CompareFunction::LessEqual),
        ..Default::default()
    });
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("shisen globals"),
        layout,
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                    buffer: globals,
                    offset: 0,
                    size: NonZeroU64::new(size),
                }),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: wgpu::BindingResource::TextureView(shadow_view),
            },
            wgpu::BindGroupEntry {
                binding: 2,
                resource: wgpu::BindingResource::Sampler(&shadow_sampler),
            },
        ],
    })
}

/// The scene's pipelines, with `samples` samples a pixel: one per
/// material and culling (a closed mesh's back faces skipped), and the
/// overlays' lines.
pub(super) fn scene_pipelines(
    device: &wgpu::Device,
    shader: &wgpu::ShaderModule,
    globals_layout: &wgpu::BindGroupLayout,
    instance_layout: &wgpu::BindGroupLayout,
    samples: u32,
) -> (
    HashMap<(Material, bool), wgpu::RenderPipeline>,
    wgpu::RenderPipeline,
) {
    let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("shisen"),
        bind_group_layouts: &[Some(globals_layout), Some(instance_layout)],
        immediate_size: 0,
    });
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
                module: shader,
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
                module: shader,
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
            &MESH_ATTRS,
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
        "fs_flat",
        &line_attrs,
        size_of::<LineVertex>(),
        wgpu::PrimitiveTopology::LineList,
        false,
        wgpu::CompareFunction::Always,
        None,
    );
    (pipelines, line_pipeline)
}

/// Depth from the top light: the vertex stage alone, back faces
/// culled (the lit side's depth is what shadows, and half the
/// triangles), biased by slope.
pub(super) fn shadow_pipeline(
    device: &wgpu::Device,
    shader: &wgpu::ShaderModule,
    shadow_globals_layout: &wgpu::BindGroupLayout,
    instance_layout: &wgpu::BindGroupLayout,
) -> wgpu::RenderPipeline {
    let shadow_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("shisen shadow"),
        bind_group_layouts: &[Some(shadow_globals_layout), Some(instance_layout)],
        immediate_size: 0,
    });
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("shisen shadow"),
        layout: Some(&shadow_layout),
        vertex: wgpu::VertexState {
            module: shader,
            entry_point: Some("vs_shadow"),
            compilation_options: Default::default(),
            buffers: &[Some(wgpu::VertexBufferLayout {
                array_stride: size_of::<Vertex>() as u64,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: &MESH_ATTRS[..1],
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
    })
}

/// The main shader, with the eye's drawn proportions (`anatomy::eye`)
/// prepended as WGSL constants: one home for the iris's size, which the
/// face's lid tests measure against.
pub(super) fn shader_source() -> String {
    use crate::render::body::{VEST_ARMHOLE, VEST_HEM, VEST_NECK};
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
        concat!(include_str!("../shader.wgsl"), include_str!("../face.wgsl"))
    )
}
