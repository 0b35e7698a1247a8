//! The wgpu side of the 3D viewport: an egui_wgpu paint callback that draws the posed mesh,
//! its wireframe and the overlay lines into an offscreen colour + depth target, then blits the
//! image into egui's render pass. (egui's own pass has no depth buffer, neither in eframe nor in
//! egui_kittest, so the 3D scene gets its own.)

use std::sync::Arc;

use egui_wgpu::wgpu;
use egui_wgpu::wgpu::util::DeviceExt;

use crate::posed_mesh::MeshVertex;

mod pipelines;
mod surface_gpu;

pub use surface_gpu::SurfaceFrame;

/// Depth format of the offscreen pass.
const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// One vertex of an overlay line (muscles, boxes, selection): position and RGBA colour.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct LineVertex {
    /// World position (the basis' user frame).
    pub position: [f32; 3],
    /// Linear RGBA colour as written to the target.
    pub color: [f32; 4],
}

/// Uniform block shared by the mesh, wireframe and line shaders (matches `viewport.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct SceneUniforms {
    /// `clip_from_world`, column major.
    pub clip_from_world: [[f32; 4]; 4],
    /// Eye position (w unused).
    pub eye: [f32; 4],
    /// Colour of the muscle-less preview's skin (kept for the layout; the surface's parts carry
    /// their own colours).
    pub base_color: [f32; 4],
    /// Wireframe colour.
    pub wire_color: [f32; 4],
}

/// Everything one frame of the viewport needs. Buffers are shared (`Arc`) and re-uploaded
/// only when their generation number changes.
#[derive(Clone, Debug)]
pub struct SceneFrame {
    /// Identity of the triangle/edge topology; changes when another face is loaded.
    pub topology_id: u64,
    /// Line-list indices of the unique edges (wireframe).
    pub edges: Arc<Vec<u32>>,
    /// Generation of [`SceneFrame::vertices`] (see [`crate::posed_mesh::PosedMesh::generation`]).
    pub pose_generation: u64,
    /// Posed vertices.
    pub vertices: Arc<Vec<MeshVertex>>,
    /// Generation of [`SceneFrame::lines`].
    pub lines_generation: u64,
    /// Overlay line list.
    pub lines: Arc<Vec<LineVertex>>,
    /// The shaded surface (user layout, materials, heat); with its neutral vertices the
    /// viewport is split: neutral on the left, posed on the right, same camera.
    pub surface: Option<SurfaceFrame>,
    /// Camera and colours.
    pub uniforms: SceneUniforms,
    /// Draw the shaded surface.
    pub shaded: bool,
    /// Draw the wireframe.
    pub wireframe: bool,
    /// Clear colour of the viewport.
    pub background: wgpu::Color,
}

/// The paint callback put into egui's shape list for the viewport rectangle.
pub struct ViewportCallback {
    /// The frame to draw.
    pub frame: SceneFrame,
    /// Size of the viewport in physical pixels.
    pub size_px: [u32; 2],
}

struct OffscreenTarget {
    size: [u32; 2],
    color_view: wgpu::TextureView,
    depth_view: wgpu::TextureView,
    blit_bind_group: wgpu::BindGroup,
}

#[derive(Default)]
struct GpuBuffer {
    buffer: Option<wgpu::Buffer>,
    len: u32,
}

impl GpuBuffer {
    fn upload(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        usage: wgpu::BufferUsages,
        bytes: &[u8],
        len: usize,
        label: &str,
    ) {
        self.len = u32::try_from(len).unwrap_or(u32::MAX);
        if bytes.is_empty() {
            return;
        }
        match &self.buffer {
            Some(b) if b.size() >= bytes.len() as u64 => queue.write_buffer(b, 0, bytes),
            _ => {
                self.buffer = Some(
                    device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                        label: Some(label),
                        contents: bytes,
                        // COPY_SRC: tests read the uploaded vertices back (read_back_vertices).
                        usage: usage | wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
                    }),
                );
            }
        }
    }
}

/// GPU state kept in egui_wgpu's callback resources between frames.
struct GpuScene {
    color_format: wgpu::TextureFormat,
    surface: surface_gpu::GpuSurface,
    wire_pipeline: wgpu::RenderPipeline,
    line_pipeline: wgpu::RenderPipeline,
    blit_pipeline: wgpu::RenderPipeline,
    blit_layout: wgpu::BindGroupLayout,
    uniform_buffer: wgpu::Buffer,
    uniform_bind_group: wgpu::BindGroup,
    vertices: GpuBuffer,
    edges: GpuBuffer,
    lines: GpuBuffer,
    uploaded: Option<(u64, u64, u64)>,
    target: Option<OffscreenTarget>,
}

/// Creates the pipelines and registers them with egui_wgpu; call once from the app's
/// constructor with `cc.wgpu_render_state`.
pub fn install(render_state: &egui_wgpu::RenderState) {
    let scene = GpuScene::new(
        &render_state.device,
        &render_state.queue,
        render_state.target_format,
    );
    render_state
        .renderer
        .write()
        .callback_resources
        .insert(scene);
}

impl GpuScene {
    fn new(device: &wgpu::Device, queue: &wgpu::Queue, color_format: wgpu::TextureFormat) -> Self {
        let shader = device.create_shader_module(wgpu::include_wgsl!("viewport.wgsl"));
        let blit_shader = device.create_shader_module(wgpu::include_wgsl!("blit.wgsl"));
        let (uniform_layout, blit_layout) = pipelines::bind_group_layouts(device);
        let (scene_pl, blit_pl) =
            pipelines::pipeline_layouts(device, &uniform_layout, &blit_layout);
        let [wire_pipeline, line_pipeline] =
            pipelines::scene_pipelines(device, &shader, &scene_pl, color_format);
        let material_layout = pipelines::material_layout(device);
        let surface_pipeline = pipelines::surface_pipeline(
            device,
            &shader,
            &uniform_layout,
            &material_layout,
            color_format,
        );
        let surface =
            surface_gpu::GpuSurface::new(device, queue, surface_pipeline, material_layout);
        let blit_pipeline = pipelines::blit_pipeline(device, &blit_shader, &blit_pl, color_format);
        let (uniform_buffer, uniform_bind_group) = pipelines::uniforms(device, &uniform_layout);
        GpuScene {
            color_format,
            surface,
            wire_pipeline,
            line_pipeline,
            blit_pipeline,
            blit_layout,
            uniform_buffer,
            uniform_bind_group,
            vertices: GpuBuffer::default(),
            edges: GpuBuffer::default(),
            lines: GpuBuffer::default(),
            uploaded: None,
            target: None,
        }
    }

    fn ensure_target(&mut self, device: &wgpu::Device, size: [u32; 2]) {
        if self.target.as_ref().is_some_and(|t| t.size == size) {
            return;
        }
        let extent = wgpu::Extent3d {
            width: size[0],
            height: size[1],
            depth_or_array_layers: 1,
        };
        let texture = |label: &str, format: wgpu::TextureFormat, usage: wgpu::TextureUsages| {
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: extent,
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage,
                view_formats: &[],
            })
        };
        let color = texture(
            "facebem viewport colour",
            self.color_format,
            wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
        );
        let depth = texture(
            "facebem viewport depth",
            DEPTH_FORMAT,
            wgpu::TextureUsages::RENDER_ATTACHMENT,
        );
        let color_view = color.create_view(&wgpu::TextureViewDescriptor::default());
        let depth_view = depth.create_view(&wgpu::TextureViewDescriptor::default());
        let blit_bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("facebem blit"),
            layout: &self.blit_layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::TextureView(&color_view),
            }],
        });
        self.target = Some(OffscreenTarget {
            size,
            color_view,
            depth_view,
            blit_bind_group,
        });
    }

    fn upload(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, frame: &SceneFrame) {
        let key = (
            frame.topology_id,
            frame.pose_generation,
            frame.lines_generation,
        );
        let old = self.uploaded;
        if old.map(|o| o.0) != Some(key.0) {
            let usage = wgpu::BufferUsages::INDEX;
            let edges = bytemuck::cast_slice(&frame.edges);
            self.edges
                .upload(device, queue, usage, edges, frame.edges.len(), "edges");
        }
        if old.map(|o| (o.0, o.1)) != Some((key.0, key.1)) {
            let bytes = bytemuck::cast_slice(&frame.vertices);
            let usage = wgpu::BufferUsages::VERTEX;
            let n = frame.vertices.len();
            self.vertices
                .upload(device, queue, usage, bytes, n, "vertices");
        }
        if old.map(|o| o.2) != Some(key.2) {
            let bytes = bytemuck::cast_slice(&frame.lines);
            let usage = wgpu::BufferUsages::VERTEX;
            self.lines
                .upload(device, queue, usage, bytes, frame.lines.len(), "lines");
        }
        self.uploaded = Some(key);
        if let Some(surface) = &frame.surface {
            self.surface.upload(device, queue, surface);
        }
        queue.write_buffer(&self.uniform_buffer, 0, bytemuck::bytes_of(&frame.uniforms));
    }

    fn draw(&self, encoder: &mut wgpu::CommandEncoder, frame: &SceneFrame) {
        let Some(target) = &self.target else { return };
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("facebem viewport"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &target.color_view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(frame.background),
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
        pass.set_bind_group(0, &self.uniform_bind_group, &[]);
        let [w, h] = target.size.map(|s| s as f32);
        let compare = frame.surface.as_ref().is_some_and(|s| s.neutral.is_some());
        if compare {
            // Neutral on the left half, posed on the right, one camera (its aspect is a half's).
            pass.set_viewport(0.0, 0.0, (w / 2.0).floor(), h, 0.0, 1.0);
            if frame.shaded {
                self.surface.draw(&mut pass, true);
            }
            let x = (w / 2.0).floor();
            pass.set_viewport(x, 0.0, w - x, h, 0.0, 1.0);
        }
        if frame.shaded && frame.surface.is_some() {
            self.surface.draw(&mut pass, false);
        }
        if let (true, Some(vb), Some(eb)) = (
            frame.wireframe && self.vertices.len > 0 && self.edges.len > 0,
            &self.vertices.buffer,
            &self.edges.buffer,
        ) {
            pass.set_pipeline(&self.wire_pipeline);
            pass.set_vertex_buffer(0, vb.slice(..));
            pass.set_index_buffer(eb.slice(..), wgpu::IndexFormat::Uint32);
            pass.draw_indexed(0..self.edges.len, 0, 0..1);
        }
        if let (true, Some(lb)) = (self.lines.len > 0, &self.lines.buffer) {
            pass.set_pipeline(&self.line_pipeline);
            pass.set_vertex_buffer(0, lb.slice(..));
            pass.draw(0..self.lines.len, 0..1);
        }
    }
}

/// Why the GPU vertex buffer could not be read back.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum ReadBackError {
    /// [`install`] was not called on this render state.
    #[error("the viewport renderer is not installed on this wgpu device")]
    NotInstalled,
    /// No frame with a face has been rendered yet.
    #[error("no vertices have been uploaded yet")]
    NothingUploaded,
    /// Mapping the staging buffer failed.
    #[error("mapping the read-back buffer failed: {0}")]
    Map(String),
}

/// Reads back the vertex buffer the viewport last uploaded to the GPU. Blocks until the GPU is
/// done: for tests and diagnostics only, never called while drawing.
pub fn read_back_vertices(
    render_state: &egui_wgpu::RenderState,
) -> Result<Vec<MeshVertex>, ReadBackError> {
    let device = &render_state.device;
    let staging;
    {
        let renderer = render_state.renderer.read();
        let scene = renderer
            .callback_resources
            .get::<GpuScene>()
            .ok_or(ReadBackError::NotInstalled)?;
        let (Some(buffer), n) = (&scene.vertices.buffer, scene.vertices.len as u64) else {
            return Err(ReadBackError::NothingUploaded);
        };
        let size = n * size_of::<MeshVertex>() as u64;
        if size == 0 {
            return Err(ReadBackError::NothingUploaded);
        }
        staging = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("facebem vertex read-back"),
            size,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("facebem vertex read-back"),
        });
        encoder.copy_buffer_to_buffer(buffer, 0, &staging, 0, size);
        render_state.queue.submit([encoder.finish()]);
    }
    let (tx, rx) = std::sync::mpsc::channel();
    staging.map_async(wgpu::MapMode::Read, .., move |r| {
        let _ = tx.send(r);
    });
    device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(|e| ReadBackError::Map(e.to_string()))?;
    rx.recv()
        .map_err(|e| ReadBackError::Map(e.to_string()))?
        .map_err(|e| ReadBackError::Map(e.to_string()))?;
    let view = staging
        .get_mapped_range(..)
        .map_err(|e| ReadBackError::Map(e.to_string()))?;
    let vertices = bytemuck::cast_slice::<u8, MeshVertex>(&view).to_vec();
    drop(view);
    staging.unmap();
    Ok(vertices)
}

impl egui_wgpu::CallbackTrait for ViewportCallback {
    fn prepare(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        _screen_descriptor: &egui_wgpu::ScreenDescriptor,
        egui_encoder: &mut wgpu::CommandEncoder,
        resources: &mut egui_wgpu::CallbackResources,
    ) -> Vec<wgpu::CommandBuffer> {
        let Some(scene) = resources.get_mut::<GpuScene>() else {
            return Vec::new();
        };
        let size = [self.size_px[0].max(1), self.size_px[1].max(1)];
        scene.ensure_target(device, size);
        scene.upload(device, queue, &self.frame);
        scene.draw(egui_encoder, &self.frame);
        Vec::new()
    }

    fn paint(
        &self,
        _info: egui::PaintCallbackInfo,
        render_pass: &mut wgpu::RenderPass<'static>,
        resources: &egui_wgpu::CallbackResources,
    ) {
        let Some(scene) = resources.get::<GpuScene>() else {
            return;
        };
        let Some(target) = &scene.target else { return };
        render_pass.set_pipeline(&scene.blit_pipeline);
        render_pass.set_bind_group(0, &target.blit_bind_group, &[]);
        render_pass.draw(0..3, 0..1);
    }
}
