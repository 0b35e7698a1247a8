//! The surface on the GPU: one index buffer and one material bind group (texture, sampler,
//! colour factor) per part, made when another surface arrives; the posed vertices re-uploaded
//! when the pose changes, the neutral ones (compare mode) once per surface.

use std::sync::Arc;

use egui_wgpu::wgpu;
use egui_wgpu::wgpu::util::DeviceExt;

use super::GpuBuffer;
use crate::surface::{Surface, SurfaceVertex, TextureImage};

/// What the viewport needs of the surface in one frame.
#[derive(Clone, Debug)]
pub struct SurfaceFrame {
    /// Identity of [`SurfaceFrame::surface`]; parts and textures are re-made when it changes.
    pub id: u64,
    /// Layout, parts and textures.
    pub surface: Arc<Surface>,
    /// Generation of [`SurfaceFrame::vertices`].
    pub generation: u64,
    /// The posed vertices.
    pub vertices: Arc<Vec<SurfaceVertex>>,
    /// The neutral vertices, drawn beside the posed ones in compare mode (`None`: no compare).
    pub neutral: Option<Arc<Vec<SurfaceVertex>>>,
}

struct GpuPart {
    indices: wgpu::Buffer,
    count: u32,
    material: wgpu::BindGroup,
}

/// GPU state of the surface.
pub(super) struct GpuSurface {
    pub(super) pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    sampler: wgpu::Sampler,
    white: wgpu::TextureView,
    parts: Vec<GpuPart>,
    pub(super) posed: GpuBuffer,
    pub(super) neutral: GpuBuffer,
    uploaded: Option<(u64, u64)>,
    neutral_uploaded: Option<u64>,
}

fn texture_view(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    image: &TextureImage,
) -> wgpu::TextureView {
    let texture = device.create_texture_with_data(
        queue,
        &wgpu::TextureDescriptor {
            label: Some("facebem material texture"),
            size: wgpu::Extent3d {
                width: image.width.max(1),
                height: image.height.max(1),
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            // Texels are display values (see surface.rs): no sRGB decoding on sampling.
            format: wgpu::TextureFormat::Rgba8Unorm,
            usage: wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::LayerMajor,
        &image.rgba,
    );
    texture.create_view(&wgpu::TextureViewDescriptor::default())
}

impl GpuSurface {
    pub(super) fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        pipeline: wgpu::RenderPipeline,
        layout: wgpu::BindGroupLayout,
    ) -> Self {
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("facebem material sampler"),
            // glTF's default wrapping.
            address_mode_u: wgpu::AddressMode::Repeat,
            address_mode_v: wgpu::AddressMode::Repeat,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        let white = TextureImage {
            width: 1,
            height: 1,
            rgba: vec![255; 4],
        };
        GpuSurface {
            pipeline,
            layout,
            sampler,
            white: texture_view(device, queue, &white),
            parts: Vec::new(),
            posed: GpuBuffer::default(),
            neutral: GpuBuffer::default(),
            uploaded: None,
            neutral_uploaded: None,
        }
    }

    pub(super) fn upload(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        frame: &SurfaceFrame,
    ) {
        let old = self.uploaded;
        if old.map(|o| o.0) != Some(frame.id) {
            self.make_parts(device, queue, &frame.surface);
            self.neutral_uploaded = None;
        }
        if old != Some((frame.id, frame.generation)) {
            let bytes = bytemuck::cast_slice(&frame.vertices);
            let usage = wgpu::BufferUsages::VERTEX;
            let n = frame.vertices.len();
            self.posed.upload(device, queue, usage, bytes, n, "surface");
        }
        self.uploaded = Some((frame.id, frame.generation));
        if let Some(neutral) = &frame.neutral
            && self.neutral_uploaded != Some(frame.id)
        {
            let bytes = bytemuck::cast_slice(neutral);
            let usage = wgpu::BufferUsages::VERTEX;
            let n = neutral.len();
            self.neutral
                .upload(device, queue, usage, bytes, n, "neutral surface");
            self.neutral_uploaded = Some(frame.id);
        }
    }

    fn make_parts(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, surface: &Surface) {
        let views: Vec<wgpu::TextureView> = surface
            .textures
            .iter()
            .map(|t| texture_view(device, queue, t))
            .collect();
        self.parts = surface
            .parts
            .iter()
            .filter(|p| !p.indices.is_empty())
            .map(|p| {
                let indices = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("facebem surface part"),
                    contents: bytemuck::cast_slice(&p.indices),
                    usage: wgpu::BufferUsages::INDEX,
                });
                let color = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("facebem material colour"),
                    contents: bytemuck::cast_slice(&p.base_color),
                    usage: wgpu::BufferUsages::UNIFORM,
                });
                let view = p.texture.and_then(|t| views.get(t)).unwrap_or(&self.white);
                let material = device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("facebem material"),
                    layout: &self.layout,
                    entries: &[
                        wgpu::BindGroupEntry {
                            binding: 0,
                            resource: wgpu::BindingResource::TextureView(view),
                        },
                        wgpu::BindGroupEntry {
                            binding: 1,
                            resource: wgpu::BindingResource::Sampler(&self.sampler),
                        },
                        wgpu::BindGroupEntry {
                            binding: 2,
                            resource: color.as_entire_binding(),
                        },
                    ],
                });
                GpuPart {
                    indices,
                    count: u32::try_from(p.indices.len()).unwrap_or(u32::MAX),
                    material,
                }
            })
            .collect();
    }

    /// Draws every part from `vertices` (the posed or the neutral buffer); the caller has bound
    /// the scene uniforms at group 0.
    pub(super) fn draw(&self, pass: &mut wgpu::RenderPass<'_>, neutral: bool) {
        let vertices = if neutral { &self.neutral } else { &self.posed };
        let Some(vb) = vertices.buffer.as_ref().filter(|_| vertices.len > 0) else {
            return;
        };
        pass.set_pipeline(&self.pipeline);
        pass.set_vertex_buffer(0, vb.slice(..));
        for part in &self.parts {
            pass.set_bind_group(1, &part.material, &[]);
            pass.set_index_buffer(part.indices.slice(..), wgpu::IndexFormat::Uint32);
            pass.draw_indexed(0..part.count, 0, 0..1);
        }
    }
}
