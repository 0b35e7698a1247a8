//! The eframe application: panels, sliders, presets, viewport interaction, background loading.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::{Duration, Instant};

use eframe::egui;
use facebem::MuscleBasis;
use glam::{DVec3, Vec2};

use crate::camera::OrbitCamera;
use crate::job::Job;
use crate::picking::{TriangleHit, pick_triangle};
use crate::posed_mesh::{MeshVertex, PosedMesh, bounding_sphere, edge_indices};
use crate::renderer::{LineVertex, SceneFrame, SceneUniforms, ViewportCallback};
use crate::source::{self, OpenError};

/// Viewport clear colour (sRGB-ish display values, written as is).
pub const BACKGROUND: [f32; 3] = [0.11, 0.12, 0.14];
const SKIN: [f32; 4] = [0.86, 0.72, 0.62, 1.0];
const SELECTION: [f32; 4] = [1.0, 0.85, 0.1, 1.0];

/// Start-up options (from the command line).
#[derive(Clone, Debug, Default)]
pub struct ViewerOptions {
    /// Face file to open; `None` opens the bundled default face.
    pub open: Option<PathBuf>,
    /// Written (atomically) once a face has been drawn, for scripts and the Xvfb test.
    pub ready_file: Option<PathBuf>,
    /// Close the window this long after the ready point.
    pub exit_after_ready: Option<Duration>,
    /// Start with no face and no loading job (tests that install a basis themselves).
    pub start_empty: bool,
}

/// A face file read by a background job.
#[derive(Debug)]
pub struct LoadedFace {
    /// Name shown in the title area (file name).
    pub name: String,
    /// The file it came from.
    pub path: PathBuf,
    /// Its basis (no muscles until the rig is solved).
    pub basis: MuscleBasis,
}

/// The face currently displayed.
#[derive(Clone, Debug)]
struct Face {
    name: String,
    basis: MuscleBasis,
    topology_id: u64,
    triangles: Arc<Vec<u32>>,
    edges: Arc<Vec<u32>>,
}

/// A status line shown under the toolbar.
#[derive(Clone, Debug, PartialEq)]
pub struct StatusMessage {
    /// The text.
    pub text: String,
    /// Whether it reports a failure (drawn in red).
    pub is_error: bool,
}

/// What an export button writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ExportKind {
    /// `<name>_pose.obj`: the current pose as a plain OBJ.
    ObjPose,
    /// `<name>.glb`: glTF 2.0 with one morph target per muscle and preset.
    Gltf,
}

impl ExportKind {
    /// Button label.
    pub fn label(self) -> &'static str {
        match self {
            ExportKind::ObjPose => "Export OBJ pose",
            ExportKind::Gltf => "Export glTF",
        }
    }
}

/// The viewer application state.
pub struct ViewerApp {
    options: ViewerOptions,
    face: Option<Face>,
    next_topology_id: u64,
    sliders: Vec<f64>,
    posed: PosedMesh,
    uploaded_vertices: Arc<Vec<MeshVertex>>,
    uploaded_generation: u64,
    lines: Arc<Vec<LineVertex>>,
    lines_generation: u64,
    camera: OrbitCamera,
    shaded: bool,
    wireframe: bool,
    open_path: String,
    message: Option<StatusMessage>,
    loading: Option<Job<LoadedFace>>,
    exporting: Option<Job<String>>,
    export_dir: String,
    selected: Option<TriangleHit>,
    has_wgpu: bool,
    frames_with_face: u32,
    ready_at: Option<Instant>,
}

impl ViewerApp {
    /// Creates the app; installs the wgpu renderer if eframe runs on wgpu and starts loading
    /// `options.open` (or the bundled default face) in the background.
    pub fn new(cc: &eframe::CreationContext<'_>, options: ViewerOptions) -> Self {
        let has_wgpu = match &cc.wgpu_render_state {
            Some(rs) => {
                crate::renderer::install(rs);
                true
            }
            None => false,
        };
        let start = (!options.start_empty).then(|| {
            options
                .open
                .clone()
                .unwrap_or_else(source::default_face_path)
        });
        let mut app = ViewerApp {
            options,
            face: None,
            next_topology_id: 1,
            sliders: Vec::new(),
            posed: PosedMesh::default(),
            uploaded_vertices: Arc::default(),
            uploaded_generation: 0,
            lines: Arc::default(),
            lines_generation: 0,
            camera: OrbitCamera::framing(glam::Vec3::ZERO, 1.0),
            shaded: true,
            wireframe: false,
            open_path: String::new(),
            message: None,
            loading: None,
            exporting: None,
            export_dir: std::env::current_dir()
                .map(|d| d.display().to_string())
                .unwrap_or_else(|_| ".".to_owned()),
            selected: None,
            has_wgpu,
            frames_with_face: 0,
            ready_at: None,
        };
        if let Some(path) = start {
            app.open(&cc.egui_ctx, path);
        }
        app
    }

    /// Starts opening `path` in the background; the current face stays usable meanwhile.
    pub fn open(&mut self, ctx: &egui::Context, path: PathBuf) {
        self.open_path = path.display().to_string();
        let job = Job::spawn(
            format!("Opening {}", file_name(&path)),
            Some(ctx.clone()),
            move |ctl| {
                ctl.report("reading the mesh", 0.0);
                let basis = source::load_neutral(&path).map_err(|e: OpenError| e.to_string())?;
                ctl.report("done", 1.0);
                Ok(LoadedFace {
                    name: file_name(&path),
                    path,
                    basis,
                })
            },
        );
        self.loading = Some(job);
    }

    /// Displays `basis` (sliders reset to 0, camera framed on it).
    pub fn set_face(&mut self, name: impl Into<String>, basis: MuscleBasis) {
        let triangles: Vec<u32> = basis.triangles.iter().flatten().copied().collect();
        let edges = edge_indices(&basis.triangles);
        self.sliders = vec![0.0; basis.muscle_count()];
        if let Some((c, r)) = bounding_sphere(&basis.neutral) {
            self.camera = OrbitCamera::framing(c.as_vec3(), r as f32);
        }
        self.face = Some(Face {
            name: name.into(),
            basis,
            topology_id: self.next_topology_id,
            triangles: Arc::new(triangles),
            edges: Arc::new(edges),
        });
        self.next_topology_id += 1;
        self.selected = None;
        self.set_lines(Vec::new());
        self.repose();
    }

    /// The basis of the displayed face.
    pub fn basis(&self) -> Option<&MuscleBasis> {
        self.face.as_ref().map(|f| &f.basis)
    }

    /// Current slider values (one per muscle of [`ViewerApp::basis`]).
    pub fn sliders(&self) -> &[f64] {
        &self.sliders
    }

    /// Sets every slider at once (clamped to −1…1; extra or missing values are ignored) and
    /// re-blends the pose, as moving the sliders would.
    pub fn set_sliders(&mut self, values: &[f64]) {
        for (s, v) in self.sliders.iter_mut().zip(values) {
            *s = if v.is_finite() {
                v.clamp(-1.0, 1.0)
            } else {
                0.0
            };
        }
        self.repose();
    }

    /// The vertices handed to the renderer in the last frame (CPU blend of the basis).
    pub fn uploaded_vertices(&self) -> &[MeshVertex] {
        &self.uploaded_vertices
    }

    /// The status message, if any (e.g. why a file could not be opened).
    pub fn message(&self) -> Option<&StatusMessage> {
        self.message.as_ref()
    }

    /// Whether a background job is running.
    pub fn is_busy(&self) -> bool {
        self.loading.is_some() || self.exporting.is_some()
    }

    /// Sets the folder exports are written to.
    pub fn set_export_dir(&mut self, dir: &Path) {
        self.export_dir = dir.display().to_string();
    }

    /// Starts writing the current face in the background (`kind` says what); the outcome is
    /// reported in the status message.
    pub fn export(&mut self, ctx: &egui::Context, kind: ExportKind) {
        let Some(face) = &self.face else { return };
        let stem = Path::new(&face.name)
            .file_stem()
            .map_or_else(|| "face".to_owned(), |s| s.to_string_lossy().into_owned());
        let dir = PathBuf::from(self.export_dir.trim());
        let basis = face.basis.clone();
        let sliders = self.sliders.clone();
        let job = Job::spawn(kind.label(), Some(ctx.clone()), move |ctl| {
            ctl.report("writing", 0.0);
            let path = match kind {
                ExportKind::ObjPose => {
                    let path = dir.join(format!("{stem}_pose.obj"));
                    let posed = basis.pose(&sliders).map_err(|e| e.to_string())?;
                    let text = facebem::export::obj::plain_obj(&posed, &basis.triangles);
                    facebem::write_atomic(&path, text.as_bytes()).map_err(|e| e.to_string())?;
                    path
                }
                ExportKind::Gltf => {
                    let path = dir.join(format!("{stem}.glb"));
                    let params = facebem::export::GltfParams::default();
                    facebem::export::write_gltf(&path, &basis, &params)
                        .map_err(|e| e.to_string())?;
                    path
                }
            };
            Ok(format!("Exported {}", path.display()))
        });
        self.exporting = Some(job);
    }

    /// The camera (for tests and scripted views).
    pub fn camera_mut(&mut self) -> &mut OrbitCamera {
        &mut self.camera
    }

    /// The picked triangle, if any.
    pub fn selected(&self) -> Option<TriangleHit> {
        self.selected
    }

    fn set_lines(&mut self, lines: Vec<LineVertex>) {
        self.lines = Arc::new(lines);
        self.lines_generation += 1;
    }

    fn repose(&mut self) {
        let Some(face) = &self.face else { return };
        if let Err(e) = self.posed.update(&face.basis, &self.sliders) {
            self.message = Some(StatusMessage {
                text: format!("Cannot pose {}: {e}", face.name),
                is_error: true,
            });
        }
    }

    fn poll_jobs(&mut self) {
        if let Some(job) = &mut self.exporting
            && let Some(result) = job.poll()
        {
            let label = job.label().to_owned();
            self.exporting = None;
            self.message = Some(match result {
                Ok(text) => StatusMessage {
                    text,
                    is_error: false,
                },
                Err(e) => StatusMessage {
                    text: format!("{label} failed: {e}"),
                    is_error: true,
                },
            });
        }
        let Some(job) = &mut self.loading else { return };
        let Some(result) = job.poll() else { return };
        let label = job.label().to_owned();
        self.loading = None;
        match result {
            Ok(face) => {
                self.message = Some(StatusMessage {
                    text: format!(
                        "Opened {} ({} triangles, {} muscles)",
                        face.path.display(),
                        face.basis.triangles.len(),
                        face.basis.muscle_count()
                    ),
                    is_error: false,
                });
                self.set_face(face.name, face.basis);
            }
            Err(e) => {
                self.message = Some(StatusMessage {
                    text: format!("Could not open: {e}"),
                    is_error: true,
                });
                let _ = label;
            }
        }
    }

    fn toolbar(&mut self, ui: &mut egui::Ui) {
        ui.horizontal(|ui| {
            ui.label("File:");
            let edit = egui::TextEdit::singleline(&mut self.open_path)
                .hint_text("face.obj / face.glb / rig")
                .desired_width(320.0);
            let r = ui.add(edit).labelled_by(ui.label("Path").id);
            let enter = r.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
            if ui.button("Open").clicked() || enter {
                let path = PathBuf::from(self.open_path.trim());
                self.open(ui.ctx(), path);
            }
            if ui.button("Open default face").clicked() {
                self.open(ui.ctx(), source::default_face_path());
            }
        });
        if let Some(m) = &self.message {
            let color = if m.is_error {
                egui::Color32::from_rgb(235, 90, 80)
            } else {
                ui.visuals().text_color()
            };
            ui.colored_label(color, &m.text);
        }
    }

    fn controls(&mut self, ui: &mut egui::Ui) {
        let Some(face) = &self.face else {
            ui.label("No face loaded.");
            return;
        };
        ui.heading(&face.name);
        ui.label(format!(
            "{} vertices, {} triangles",
            face.basis.neutral.len(),
            face.basis.triangles.len()
        ));
        ui.separator();
        ui.strong("Muscles (−1 contracts … +1 relaxes)");
        let ids = face.basis.muscle_ids.clone();
        if ids.is_empty() {
            ui.label("The muscle rig is not solved yet.");
        }
        let mut changed = false;
        for (id, value) in ids.iter().zip(self.sliders.iter_mut()) {
            let name = face_prep::MuscleKind::from_id(id).map_or(id.as_str(), |m| m.display_name());
            changed |= ui
                .add(egui::Slider::new(value, -1.0..=1.0).text(name))
                .changed();
        }
        ui.horizontal_wrapped(|ui| {
            if ui
                .add_enabled(!ids.is_empty(), egui::Button::new("Reset muscles"))
                .clicked()
            {
                self.sliders.iter_mut().for_each(|s| *s = 0.0);
                changed = true;
            }
            for preset in facebem::presets::ALL.iter().filter(|p| p.name != "neutral") {
                let button = egui::Button::new(preset_label(preset.name));
                let r = ui
                    .add_enabled(!ids.is_empty(), button)
                    .on_hover_text(format!("{} ({})", preset.description, preset.action_units));
                if r.clicked() {
                    self.sliders = preset.sliders_for(&ids);
                    changed = true;
                }
            }
        });
        if changed {
            self.repose();
        }
        ui.separator();
        ui.strong("View");
        ui.checkbox(&mut self.shaded, "Shaded");
        ui.checkbox(&mut self.wireframe, "Wireframe");
        if ui.button("Reset view").clicked() {
            self.camera.reset();
        }
        ui.label("Drag: orbit · right/middle drag or shift-drag: pan · wheel: zoom · click: pick");
        if let Some(hit) = self.selected {
            ui.separator();
            ui.label(format!("Selected triangle {}", hit.triangle));
        }
        ui.separator();
        ui.strong("Export");
        ui.horizontal(|ui| {
            let label = ui.label("Export folder");
            ui.add(egui::TextEdit::singleline(&mut self.export_dir).desired_width(180.0))
                .labelled_by(label.id);
        });
        ui.horizontal_wrapped(|ui| {
            let idle = self.exporting.is_none();
            for kind in [ExportKind::ObjPose, ExportKind::Gltf] {
                if ui
                    .add_enabled(idle, egui::Button::new(kind.label()))
                    .clicked()
                {
                    self.export(ui.ctx(), kind);
                }
            }
        });
    }

    fn status_bar(&mut self, ui: &mut egui::Ui) {
        if let Some(job) = &self.exporting {
            ui.horizontal(|ui| {
                ui.spinner();
                ui.label(job.label());
            });
        }
        let Some(job) = &self.loading else {
            ui.label(if self.has_wgpu {
                "Ready"
            } else {
                "No wgpu device: 3D view disabled"
            });
            return;
        };
        ui.horizontal(|ui| {
            let ctl = job.control();
            ui.label(job.label());
            ui.add(
                egui::ProgressBar::new(ctl.fraction())
                    .text(ctl.stage())
                    .desired_width(260.0),
            );
            if ui.button("Cancel").clicked() {
                ctl.cancel();
            }
        });
    }

    fn viewport(&mut self, ui: &mut egui::Ui) {
        let size = ui.available_size();
        let (rect, response) = ui.allocate_exact_size(size, egui::Sense::click_and_drag());
        let aspect = rect.width() / rect.height().max(1.0);
        let delta = response.drag_delta();
        let pan = response.dragged_by(egui::PointerButton::Secondary)
            || response.dragged_by(egui::PointerButton::Middle)
            || (response.dragged_by(egui::PointerButton::Primary)
                && ui.input(|i| i.modifiers.shift));
        if pan {
            self.camera.pan(Vec2::new(delta.x, delta.y), rect.height());
        } else if response.dragged_by(egui::PointerButton::Primary) {
            self.camera.orbit(-delta.x * 0.01, delta.y * 0.01);
        }
        if response.hovered() {
            let scroll = ui.input(|i| i.smooth_scroll_delta.y);
            if scroll != 0.0 {
                self.camera.zoom((-scroll * 0.002).exp());
            }
        }
        if response.clicked()
            && let Some(pos) = response.interact_pointer_pos()
        {
            let ndc = Vec2::new(
                (pos.x - rect.left()) / rect.width() * 2.0 - 1.0,
                1.0 - (pos.y - rect.top()) / rect.height() * 2.0,
            );
            self.pick(ndc, aspect);
        }
        let Some(face) = &self.face else { return };
        if self.uploaded_generation != self.posed.generation() {
            self.uploaded_vertices = Arc::new(self.posed.vertices().to_vec());
            self.uploaded_generation = self.posed.generation();
        }
        if !self.has_wgpu {
            return;
        }
        let ppp = ui.ctx().pixels_per_point();
        let size_px = [
            (rect.width() * ppp).round().max(1.0) as u32,
            (rect.height() * ppp).round().max(1.0) as u32,
        ];
        let wire_color = if self.shaded {
            [0.15, 0.1, 0.08, 0.55]
        } else {
            [0.85, 0.85, 0.9, 1.0]
        };
        let frame = SceneFrame {
            topology_id: face.topology_id,
            triangles: Arc::clone(&face.triangles),
            edges: Arc::clone(&face.edges),
            pose_generation: self.uploaded_generation,
            vertices: Arc::clone(&self.uploaded_vertices),
            lines_generation: self.lines_generation,
            lines: Arc::clone(&self.lines),
            uniforms: SceneUniforms {
                clip_from_world: self.camera.clip_from_world(aspect).to_cols_array_2d(),
                eye: self.camera.eye().extend(1.0).to_array(),
                base_color: SKIN,
                wire_color,
            },
            shaded: self.shaded,
            wireframe: self.wireframe || !self.shaded,
            background: egui_wgpu::wgpu::Color {
                r: BACKGROUND[0] as f64,
                g: BACKGROUND[1] as f64,
                b: BACKGROUND[2] as f64,
                a: 1.0,
            },
        };
        ui.painter().add(egui_wgpu::Callback::new_paint_callback(
            rect,
            ViewportCallback { frame, size_px },
        ));
        self.frames_with_face += 1;
    }

    fn pick(&mut self, ndc: Vec2, aspect: f32) {
        let Some(face) = &self.face else { return };
        let (o, d) = self.camera.ray_through(ndc, aspect);
        let hit = pick_triangle(
            self.posed.positions_f64(),
            &face.basis.triangles,
            o.as_dvec3(),
            d.as_dvec3(),
        );
        self.selected = hit;
        let mut lines = Vec::new();
        if let Some(h) = hit
            && let Some(t) = face.basis.triangles.get(h.triangle)
        {
            let p: Vec<DVec3> = t
                .iter()
                .filter_map(|&i| self.posed.positions_f64().get(i as usize).copied())
                .collect();
            for k in 0..p.len() {
                for q in [p[k], p[(k + 1) % p.len()]] {
                    lines.push(LineVertex {
                        position: q.as_vec3().to_array(),
                        color: SELECTION,
                    });
                }
            }
        }
        self.set_lines(lines);
    }

    fn automation(&mut self, ctx: &egui::Context) {
        if self.ready_at.is_none() && self.frames_with_face >= 3 {
            self.ready_at = Some(Instant::now());
            if let Some(path) = &self.options.ready_file
                && let Err(e) = facebem::write_atomic(path, b"ready\n")
            {
                self.message = Some(StatusMessage {
                    text: format!("Cannot write the ready file {}: {e}", path.display()),
                    is_error: true,
                });
            }
        }
        if let Some(after) = self.options.exit_after_ready {
            match self.ready_at {
                Some(t) if t.elapsed() >= after => {
                    ctx.send_viewport_cmd(egui::ViewportCommand::Close)
                }
                _ => ctx.request_repaint_after(Duration::from_millis(50)),
            }
        }
        if self.options.ready_file.is_some() && self.ready_at.is_none() {
            ctx.request_repaint_after(Duration::from_millis(50));
        }
    }

    fn dropped_files(&mut self, ctx: &egui::Context) {
        let dropped = ctx.input(|i| i.raw.dropped_files.first().map(|f| f.path().to_path_buf()));
        if let Some(path) = dropped {
            self.open(ctx, path);
        }
    }

    /// Draws one frame of the UI (what `eframe::App::ui` calls).
    pub fn show(&mut self, ui: &mut egui::Ui) {
        self.poll_jobs();
        self.dropped_files(ui.ctx());
        egui::Panel::top("toolbar").show(ui, |ui| self.toolbar(ui));
        egui::Panel::bottom("status").show(ui, |ui| self.status_bar(ui));
        egui::Panel::left("controls")
            .default_size(300.0)
            .show(ui, |ui| {
                egui::ScrollArea::vertical().show(ui, |ui| self.controls(ui));
            });
        egui::CentralPanel::default()
            .frame(egui::Frame::NONE)
            .show(ui, |ui| self.viewport(ui));
        self.automation(&ui.ctx().clone());
    }
}

impl eframe::App for ViewerApp {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        self.show(ui);
    }
}

fn file_name(path: &Path) -> String {
    path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    )
}

/// Button label of a preset: its name with a capital first letter ("smile" → "Smile").
pub fn preset_label(name: &str) -> String {
    let mut c = name.chars();
    c.next()
        .map(|f| f.to_uppercase().chain(c).collect())
        .unwrap_or_default()
}
