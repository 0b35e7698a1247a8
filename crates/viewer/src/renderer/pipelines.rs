//! The GPU objects made once, when the renderer is installed: bind group layouts, pipeline
//! layouts, the render pipelines, and the uniform buffer with its bind group.

use egui_wgpu::wgpu;

use super::{DEPTH_FORMAT, LineVertex, SceneUniforms};
use crate::posed_mesh::MeshVertex;
use crate::surface::SurfaceVertex;

const MESH_LAYOUT: [wgpu::VertexAttribute; 2] =
    wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3];
const LINE_LAYOUT: [wgpu::VertexAttribute; 2] =
    wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x4];
const SURFACE_LAYOUT: [wgpu::VertexAttribute; 4] =
    wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32x2, 3 => Float32x4];

/// The bind group layout of a surface part's material: texture, sampler, colour factor.
pub(super) fn material_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("facebem material"),
        entries: &[
            wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Texture {
                    sample_type: wgpu::TextureSampleType::Float { filterable: true },
                    view_dimension: wgpu::TextureViewDimension::D2,
                    multisampled: false,
                },
                count: None,
            },
            wgpu::BindGroupLayoutEntry {
                binding: 1,
                visibility: wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                count: None,
            },
            wgpu::BindGroupLayoutEntry {
                binding: 2,
                visibility: wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            },
        ],
    })
}

/// The surface pipeline (user layout, material, heat; depth-tested, writes depth).
pub(super) fn surface_pipeline(
    device: &wgpu::Device,
    shader: &wgpu::ShaderModule,
    uniform_layout: &wgpu::BindGroupLayout,
    material_layout: &wgpu::BindGroupLayout,
    color_format: wgpu::TextureFormat,
) -> wgpu::RenderPipeline {
    let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("facebem surface"),
        bind_group_layouts: &[Some(uniform_layout), Some(material_layout)],
        immediate_size: 0,
    });
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("facebem surface"),
        layout: Some(&layout),
        vertex: wgpu::VertexState {
            module: shader,
            entry_point: Some("vs_surface"),
            compilation_options: Default::default(),
            buffers: &[Some(wgpu::VertexBufferLayout {
                array_stride: size_of::<SurfaceVertex>() as u64,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: &SURFACE_LAYOUT,
            })],
        },
        primitive: wgpu::PrimitiveState::default(),
        depth_stencil: depth_state(true, wgpu::CompareFunction::LessEqual),
        multisample: wgpu::MultisampleState::default(),
        fragment: Some(wgpu::FragmentState {
            module: shader,
            entry_point: Some("fs_surface"),
            compilation_options: Default::default(),
            targets: &[Some(wgpu::ColorTargetState {
                format: color_format,
                blend: None,
                write_mask: wgpu::ColorWrites::ALL,
            })],
        }),
        multiview_mask: None,
        cache: None,
    })
}

/// The bind group layouts of the scene uniforms and of the blit's source texture.
pub(super) fn bind_group_layouts(
    device: &wgpu::Device,
) -> (wgpu::BindGroupLayout, wgpu::BindGroupLayout) {
    let uniform_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("facebem uniforms"),
        entries: &[wgpu::BindGroupLayoutEntry {
            binding: 0,
            visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        }],
    });
    let blit_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("facebem blit"),
        entries: &[wgpu::BindGroupLayoutEntry {
            binding: 0,
            visibility: wgpu::ShaderStages::FRAGMENT,
            ty: wgpu::BindingType::Texture {
                sample_type: wgpu::TextureSampleType::Float { filterable: false },
                view_dimension: wgpu::TextureViewDimension::D2,
                multisampled: false,
            },
            count: None,
        }],
    });
    (uniform_layout, blit_layout)
}

/// The pipeline layouts of the scene (uniforms) and of the blit (source texture).
pub(super) fn pipeline_layouts(
    device: &wgpu::Device,
    uniform_layout: &wgpu::BindGroupLayout,
    blit_layout: &wgpu::BindGroupLayout,
) -> (wgpu::PipelineLayout, wgpu::PipelineLayout) {
    let scene_pl = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("facebem scene"),
        bind_group_layouts: &[Some(uniform_layout)],
        immediate_size: 0,
    });
    let blit_pl = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("facebem blit"),
        bind_group_layouts: &[Some(blit_layout)],
        immediate_size: 0,
    });
    (scene_pl, blit_pl)
}

/// Depth test of a scene pipeline. Overlays (write_depth = false and not the wireframe) are
/// drawn "x-ray": always on top.
fn depth_state(write: bool, compare: wgpu::CompareFunction) -> Option<wgpu::DepthStencilState> {
    Some(wgpu::DepthStencilState {
        format: DEPTH_FORMAT,
        depth_write_enabled: Some(write),
        depth_compare: Some(compare),
        stencil: wgpu::StencilState::default(),
        bias: wgpu::DepthBiasState::default(),
    })
}

/// The wireframe and overlay-line pipelines, in that order.
pub(super) fn scene_pipelines(
    device: &wgpu::Device,
    shader: &wgpu::ShaderModule,
    scene_pl: &wgpu::PipelineLayout,
    color_format: wgpu::TextureFormat,
) -> [wgpu::RenderPipeline; 2] {
    let mesh_buffers = [Some(wgpu::VertexBufferLayout {
        array_stride: size_of::<MeshVertex>() as u64,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes: &MESH_LAYOUT,
    })];
    let line_buffers = [Some(wgpu::VertexBufferLayout {
        array_stride: size_of::<LineVertex>() as u64,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes: &LINE_LAYOUT,
    })];
    let targets = [Some(wgpu::ColorTargetState {
        format: color_format,
        blend: Some(wgpu::BlendState::ALPHA_BLENDING),
        write_mask: wgpu::ColorWrites::ALL,
    })];
    let make = |label: &str,
                vs: &str,
                fs: &str,
                buffers: &[Option<wgpu::VertexBufferLayout>],
                topology: wgpu::PrimitiveTopology,
                write_depth: bool,
                compare: wgpu::CompareFunction| {
        device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some(label),
            layout: Some(scene_pl),
            vertex: wgpu::VertexState {
                module: shader,
                entry_point: Some(vs),
                compilation_options: Default::default(),
                buffers,
            },
            primitive: wgpu::PrimitiveState {
                topology,
                ..Default::default()
            },
            depth_stencil: depth_state(write_depth, compare),
            multisample: wgpu::MultisampleState::default(),
            fragment: Some(wgpu::FragmentState {
                module: shader,
                entry_point: Some(fs),
                compilation_options: Default::default(),
                targets: &targets,
            }),
            multiview_mask: None,
            cache: None,
        })
    };
    let wire_pipeline = make(
        "facebem wire",
        "vs_wire",
        "fs_wire",
        &mesh_buffers,
        wgpu::PrimitiveTopology::LineList,
        false,
        wgpu::CompareFunction::LessEqual,
    );
    let line_pipeline = make(
        "facebem lines",
        "vs_line",
        "fs_line",
        &line_buffers,
        wgpu::PrimitiveTopology::LineList,
        false,
        wgpu::CompareFunction::Always,
    );
    [wire_pipeline, line_pipeline]
}

/// The pipeline copying the offscreen colour target into egui's render pass.
pub(super) fn blit_pipeline(
    device: &wgpu::Device,
    blit_shader: &wgpu::ShaderModule,
    blit_pl: &wgpu::PipelineLayout,
    color_format: wgpu::TextureFormat,
) -> wgpu::RenderPipeline {
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("facebem blit"),
        layout: Some(blit_pl),
        vertex: wgpu::VertexState {
            module: blit_shader,
            entry_point: Some("vs_blit"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        primitive: wgpu::PrimitiveState::default(),
        depth_stencil: None,
        multisample: wgpu::MultisampleState::default(),
        fragment: Some(wgpu::FragmentState {
            module: blit_shader,
            entry_point: Some("fs_blit"),
            compilation_options: Default::default(),
            targets: &[Some(wgpu::ColorTargetState {
                format: color_format,
                blend: None,
                write_mask: wgpu::ColorWrites::ALL,
            })],
        }),
        multiview_mask: None,
        cache: None,
    })
}

/// The uniform buffer ([`SceneUniforms`]) and its bind group.
pub(super) fn uniforms(
    device: &wgpu::Device,
    uniform_layout: &wgpu::BindGroupLayout,
) -> (wgpu::Buffer, wgpu::BindGroup) {
    let uniform_buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("facebem uniforms"),
        size: size_of::<SceneUniforms>() as u64,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let uniform_bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("facebem uniforms"),
        layout: uniform_layout,
        entries: &[wgpu::BindGroupEntry {
            binding: 0,
            resource: uniform_buffer.as_entire_binding(),
        }],
    });
    (uniform_buffer, uniform_bind_group)
}
