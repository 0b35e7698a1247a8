//! The eframe application: panels, sliders, presets, viewport interaction, background opening,
//! rig computation (cached) and exports.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::{Duration, Instant};

use eframe::egui;
use face_prep::{Box2, FaceMesh};
use facebem::Control;
use facebem::MuscleBasis;
use facebem::open::{CacheStatus, Opened};
use facebem::{FaceModel, PipelineParams};
use glam::DVec3;

use crate::camera::OrbitCamera;
pub use crate::export::ExportKind;
use crate::export::{ExportRequest, write_export};
use crate::job::Job;
use crate::overlay::{OverlayOptions, RigGeometry, overlay_lines};
use crate::picking::TriangleHit;
use crate::posed_mesh::{MeshVertex, PosedMesh, bounding_sphere, edge_indices};
use crate::renderer::{LineVertex, ReadBackError};
use crate::source;

mod box_drag;
mod dialogs;
mod panels;
mod rig_editing;
mod viewport;

/// Viewport clear colour (display values, written as is).
pub const BACKGROUND: [f32; 3] = [0.11, 0.12, 0.14];
const SKIN: [f32; 4] = [0.86, 0.72, 0.62, 1.0];
const SELECTION: [f32; 4] = [1.0, 0.85, 0.1, 1.0];

/// Start-up options (from the command line).
#[derive(Clone, Debug, Default)]
pub struct ViewerOptions {
    /// Face or rig file to open; `None` opens the bundled default face.
    pub open: Option<PathBuf>,
    /// Rig cache folder; `None` = [`facebem::open::default_cache_dir`]
    /// (`$XDG_CACHE_HOME/facebem` or `~/.cache/facebem`).
    pub cache_dir: Option<PathBuf>,
    /// Written (atomically) once a face has been drawn, for scripts and the Xvfb test.
    pub ready_file: Option<PathBuf>,
    /// Close the window this long after the ready point.
    pub exit_after_ready: Option<Duration>,
    /// Preset applied as soon as the rig is available (e.g. for screenshots).
    pub preset: Option<String>,
    /// Start with no face and no job (tests that install a basis themselves).
    pub start_empty: bool,
}

/// The face currently displayed.
#[derive(Clone, Debug)]
struct Face {
    name: String,
    basis: MuscleBasis,
    topology_id: u64,
    triangles: Arc<Vec<u32>>,
    edges: Arc<Vec<u32>>,
    /// The mesh and its OBJ text, for (re)building the rig.
    source: Option<Arc<(FaceMesh, Option<String>)>>,
    /// The solved model, once available.
    model: Option<Arc<FaceModel>>,
    rig_geometry: Option<Arc<RigGeometry>>,
}

/// A status line shown under the toolbar.
#[derive(Clone, Debug, PartialEq)]
pub struct StatusMessage {
    /// The text.
    pub text: String,
    /// Whether it reports a failure (drawn in red).
    pub is_error: bool,
}

/// What the user picked in the viewport.
#[derive(Clone, Debug, PartialEq)]
pub struct Selection {
    /// The hit on the displayed mesh (triangle of the user's mesh).
    pub hit: TriangleHit,
    /// The rig's shell element under the click (front elements; `None` without a rig).
    pub element: Option<u32>,
    /// Muscles containing that element.
    pub muscles: Vec<String>,
}

struct RigJob {
    job: Job<(FaceModel, CacheStatus)>,
    control: Control,
    topology_id: u64,
    /// When the job started (elapsed time and estimate in the status bar).
    started: Instant,
    /// Largest overall fraction shown so far (the bar never goes back).
    shown_fraction: f32,
}

/// The viewer application state.
pub struct ViewerApp {
    options: ViewerOptions,
    face: Option<Face>,
    next_topology_id: u64,
    sliders: Vec<f64>,
    /// The preset the sliders were last set to, until a slider moves.
    active_preset: Option<&'static str>,
    posed: PosedMesh,
    uploaded_vertices: Arc<Vec<MeshVertex>>,
    uploaded_generation: u64,
    lines: Arc<Vec<LineVertex>>,
    lines_generation: u64,
    camera: OrbitCamera,
    shaded: bool,
    wireframe: bool,
    overlays: OverlayOptions,
    params: PipelineParams,
    open_path: String,
    message: Option<StatusMessage>,
    loading: Option<Job<(String, Opened)>>,
    rigging: Option<RigJob>,
    exporting: Option<Job<String>>,
    dialog: Option<dialogs::PendingDialog>,
    export_dir: String,
    selection: Option<Selection>,
    edit_target: usize,
    box_edit: Option<[Box2; 4]>,
    box_drag: Option<(usize, box_drag::BoxHandle)>,
    viewport_rect: Option<egui::Rect>,
    render_state: Option<egui_wgpu::RenderState>,
    has_wgpu: bool,
    frames_with_face: u32,
    ready_at: Option<Instant>,
}

impl ViewerApp {
    /// Creates the app; installs the wgpu renderer if eframe runs on wgpu and starts opening
    /// `options.open` (or the bundled default face) in the background.
    pub fn new(cc: &eframe::CreationContext<'_>, options: ViewerOptions) -> Self {
        let has_wgpu = match &cc.wgpu_render_state {
            Some(rs) => {
                crate::renderer::install(rs);
                true
            }
            None => false,
        };
        let start = (!options.start_empty).then(|| options.open.clone());
        let mut app = ViewerApp {
            options,
            face: None,
            next_topology_id: 1,
            sliders: Vec::new(),
            active_preset: None,
            posed: PosedMesh::default(),
            uploaded_vertices: Arc::default(),
            uploaded_generation: 0,
            lines: Arc::default(),
            lines_generation: 0,
            camera: OrbitCamera::framing(glam::Vec3::ZERO, 1.0),
            shaded: true,
            wireframe: false,
            overlays: OverlayOptions::default(),
            params: PipelineParams::default(),
            open_path: String::new(),
            message: None,
            loading: None,
            rigging: None,
            exporting: None,
            dialog: None,
            export_dir: std::env::current_dir()
                .map(|d| home_relative(&d))
                .unwrap_or_else(|_| ".".to_owned()),
            selection: None,
            edit_target: 0,
            box_edit: None,
            box_drag: None,
            viewport_rect: None,
            render_state: cc.wgpu_render_state.clone(),
            has_wgpu,
            frames_with_face: 0,
            ready_at: None,
        };
        // Opened before the first frame, so the face is drawn at once (the rig follows in the
        // background); the Open button reads files in the background instead.
        let opened = match start {
            Some(Some(path)) => {
                app.open_path = path.display().to_string();
                Some(
                    facebem::open::open(&path)
                        .map(|o| (file_name(&path), o))
                        .map_err(|e| e.to_string()),
                )
            }
            Some(None) => Some(default_face_opened()),
            None => None,
        };
        if let Some(result) = opened {
            app.opened(&cc.egui_ctx, result);
        }
        app
    }

    /// Starts opening `path` (face or saved rig) in the background; the current face stays
    /// usable meanwhile. A face without rig is shown at once and its rig computed (or loaded
    /// from the cache) by a second job.
    pub fn open(&mut self, ctx: &egui::Context, path: PathBuf) {
        let job = Job::spawn(
            format!("Opening {}", file_name(&path)),
            Some(ctx.clone()),
            move |ctl| {
                ctl.report("reading", 0.0);
                let opened = facebem::open::open(&path).map_err(|e| e.to_string())?;
                ctl.report("read", 1.0);
                Ok((file_name(&path), opened))
            },
        );
        self.loading = Some(job);
    }

    /// Starts opening the bundled default face (compiled into the program).
    pub fn open_default_face(&mut self, ctx: &egui::Context) {
        let job = Job::spawn("Opening the default face", Some(ctx.clone()), move |_| {
            default_face_opened()
        });
        self.loading = Some(job);
    }

    /// Displays `basis` without a rig (sliders reset to 0, camera framed on it).
    pub fn set_face(&mut self, name: impl Into<String>, basis: MuscleBasis) {
        self.install_face(name.into(), basis, None, None, true);
    }

    fn install_face(
        &mut self,
        name: String,
        basis: MuscleBasis,
        source: Option<Arc<(FaceMesh, Option<String>)>>,
        model: Option<Arc<FaceModel>>,
        reframe: bool,
    ) {
        let triangles: Vec<u32> = basis.triangles.iter().flatten().copied().collect();
        let edges = edge_indices(&basis.triangles);
        self.sliders = vec![0.0; basis.muscle_count()];
        self.active_preset = None;
        if reframe && let Some((c, r)) = bounding_sphere(&basis.neutral) {
            self.camera = OrbitCamera::framing(c.as_vec3(), r as f32);
        }
        let rig_geometry = model.as_ref().map(|m| Arc::new(RigGeometry::new(&m.rig)));
        if let Some(m) = &model {
            self.params = m.params.clone();
        }
        self.face = Some(Face {
            name,
            basis,
            topology_id: self.next_topology_id,
            triangles: Arc::new(triangles),
            edges: Arc::new(edges),
            source,
            model,
            rig_geometry,
        });
        self.next_topology_id += 1;
        self.selection = None;
        if reframe {
            self.box_edit = None;
        }
        self.refresh_overlays();
        self.repose();
        if let Some(name) = self.options.preset.clone()
            && self
                .face
                .as_ref()
                .is_some_and(|f| f.basis.muscle_count() > 0)
        {
            self.apply_preset(&name);
        }
    }

    /// Installs a solved model (rig + basis) as the displayed face.
    pub fn set_model(&mut self, name: impl Into<String>, model: FaceModel) {
        let same_mesh = self
            .face
            .as_ref()
            .and_then(|f| f.source.as_ref())
            .is_some_and(|s| s.0 == model.mesh);
        let source = Arc::new((model.mesh.clone(), model.obj_source.clone()));
        let basis = model.basis.clone();
        self.install_face(
            name.into(),
            basis,
            Some(source),
            Some(Arc::new(model)),
            !same_mesh,
        );
    }

    /// The basis of the displayed face.
    pub fn basis(&self) -> Option<&MuscleBasis> {
        self.face.as_ref().map(|f| &f.basis)
    }

    /// The solved model of the displayed face, once available.
    pub fn model(&self) -> Option<&FaceModel> {
        self.face.as_ref().and_then(|f| f.model.as_deref())
    }

    /// Current slider values (one per muscle of [`ViewerApp::basis`]).
    pub fn sliders(&self) -> &[f64] {
        &self.sliders
    }

    /// Sets every slider at once (clamped to −1…1; extra or missing values are ignored) and
    /// re-blends the pose, as moving the sliders would.
    pub fn set_sliders(&mut self, values: &[f64]) {
        self.active_preset = None;
        for (s, v) in self.sliders.iter_mut().zip(values) {
            *s = if v.is_finite() {
                v.clamp(-1.0, 1.0)
            } else {
                0.0
            };
        }
        self.repose();
    }

    /// Applies the preset called `name`: a facebem preset ([`facebem::presets::find`]) or an
    /// ARKit / VRM 1.0 name ([`facebem::expression_sets::find`], from the controls the rig has);
    /// false if unknown or the rig has none of its controls.
    pub fn apply_preset(&mut self, name: &str) -> bool {
        let Some(face) = &self.face else { return false };
        let ids = &face.basis.muscle_ids;
        let (sliders, name) = if let Some(p) = facebem::presets::find(name) {
            (p.sliders_for(ids), p.name)
        } else if let Some(e) = facebem::expression_sets::find(name) {
            let Some(r) = e.resolve(ids) else {
                return false;
            };
            (r.sliders, e.name)
        } else {
            return false;
        };
        self.sliders = sliders;
        self.active_preset = Some(name);
        self.repose();
        true
    }

    /// The preset the sliders are set to, until a slider moves (highlighted in the UI).
    pub fn active_preset(&self) -> Option<&'static str> {
        self.active_preset
    }

    /// Whether the export buttons are enabled: a rig is displayed (the face has muscles), and
    /// no rig computation or export is running. `Err` says why not (the buttons' tooltip).
    pub fn exports_ready(&self) -> Result<(), &'static str> {
        match &self.face {
            None => Err("No face is open"),
            Some(_) if self.rigging.is_some() => {
                Err("The muscle rig is being computed; exports are enabled when it is ready")
            }
            Some(f) if f.basis.muscle_count() == 0 => {
                Err("The face has no muscle rig yet: exports are enabled when it is ready")
            }
            Some(_) if self.exporting.is_some() => Err("An export is being written"),
            Some(_) => Ok(()),
        }
    }

    /// The vertices handed to the renderer in the last frame (CPU blend of the basis).
    pub fn uploaded_vertices(&self) -> &[MeshVertex] {
        &self.uploaded_vertices
    }

    /// Reads the vertex buffer back from the GPU (blocking; tests and diagnostics only).
    pub fn read_back_gpu_vertices(&self) -> Result<Vec<MeshVertex>, ReadBackError> {
        let rs = self
            .render_state
            .as_ref()
            .ok_or(ReadBackError::NotInstalled)?;
        crate::renderer::read_back_vertices(rs)
    }

    /// The overlay lines handed to the renderer.
    pub fn overlay_line_vertices(&self) -> &[LineVertex] {
        &self.lines
    }

    /// The status message, if any (e.g. why a file could not be opened).
    pub fn message(&self) -> Option<&StatusMessage> {
        self.message.as_ref()
    }

    /// Removes the status message.
    pub fn clear_message(&mut self) {
        self.message = None;
    }

    /// Whether a background job is running.
    pub fn is_busy(&self) -> bool {
        self.loading.is_some() || self.rigging.is_some() || self.exporting.is_some()
    }

    /// Whether the rig is being computed (or loaded from the cache).
    pub fn is_rigging(&self) -> bool {
        self.rigging.is_some()
    }

    /// The pipeline parameters used for the next rebuild.
    pub fn params_mut(&mut self) -> &mut PipelineParams {
        &mut self.params
    }

    /// Which overlays are drawn.
    pub fn set_overlays(&mut self, overlays: OverlayOptions) {
        self.overlays = overlays;
        self.refresh_overlays();
    }

    /// Sets the folder exports are written to (shown relative to the home folder, `~/…`).
    pub fn set_export_dir(&mut self, dir: &Path) {
        self.export_dir = home_relative(dir);
    }

    /// The export folder as the UI shows it (`~/…` under the home folder).
    pub fn export_dir_text(&self) -> &str {
        &self.export_dir
    }

    /// The export folder as a path (`~` expanded).
    pub fn export_dir(&self) -> PathBuf {
        expand_home(self.export_dir.trim())
    }

    /// The camera (for tests and scripted views).
    pub fn camera_mut(&mut self) -> &mut OrbitCamera {
        &mut self.camera
    }

    /// Where the 3D viewport was drawn in the last frame (egui points).
    pub fn viewport_rect(&self) -> Option<egui::Rect> {
        self.viewport_rect
    }

    /// The picked triangle, if any.
    pub fn selected(&self) -> Option<TriangleHit> {
        self.selection.as_ref().map(|s| s.hit)
    }

    /// The full selection (triangle, rig element, muscles), if any.
    pub fn selection(&self) -> Option<&Selection> {
        self.selection.as_ref()
    }

    /// Starts writing the current face in the background (`kind` says what); the outcome is
    /// reported in the status message.
    pub fn export(&mut self, ctx: &egui::Context, kind: ExportKind) {
        if let Err(why) = self.exports_ready() {
            self.error(format!("{}: {why}", kind.label()));
            return;
        }
        let Some(face) = &self.face else { return };
        let stem = Path::new(&face.name)
            .file_stem()
            .map_or_else(|| "face".to_owned(), |s| s.to_string_lossy().into_owned());
        let dir = self.export_dir();
        let basis = face.basis.clone();
        let model = face.model.clone();
        let sliders = self.sliders.clone();
        let job = Job::spawn(kind.label(), Some(ctx.clone()), move |ctl| {
            ctl.report("writing", 0.0);
            let request = ExportRequest {
                dir,
                stem,
                basis,
                model,
                sliders,
            };
            let path = write_export(kind, &request).map_err(|e| e.to_string())?;
            Ok(format!("Exported {}", path.display()))
        });
        self.exporting = Some(job);
    }

    fn error(&mut self, text: String) {
        self.message = Some(StatusMessage {
            text,
            is_error: true,
        });
    }

    fn info(&mut self, text: String) {
        self.message = Some(StatusMessage {
            text,
            is_error: false,
        });
    }

    fn set_lines(&mut self, lines: Vec<LineVertex>) {
        self.lines = Arc::new(lines);
        self.lines_generation += 1;
    }

    fn refresh_overlays(&mut self) {
        let mut lines = Vec::new();
        let selected_element = self.selection.as_ref().and_then(|s| s.element);
        if let Some(face) = &self.face {
            if let (Some(model), Some(geo)) = (&face.model, &face.rig_geometry) {
                let edited = self.edited_boxes().and_then(Result::ok);
                // Overlays follow the pose: every shell vertex moves by its own response
                // (the simulated surface's, also on a reduced copy), in the user's frame.
                let response = &model.shell_vertex_response;
                let posed_geo = (response.len() == self.sliders.len()
                    && response.iter().all(|r| r.len() == geo.vertices.len()))
                .then(|| {
                    let linear = geo.input_from_canonical.matrix3;
                    let mut g = (**geo).clone();
                    for (k, &s) in self.sliders.iter().enumerate() {
                        if s != 0.0 {
                            for (p, u) in g.vertices.iter_mut().zip(&response[k]) {
                                *p += linear * (s * *u);
                            }
                        }
                    }
                    g
                });
                lines = overlay_lines(
                    &model.rig,
                    posed_geo.as_ref().unwrap_or(geo),
                    &self.overlays,
                    selected_element,
                    self.params.muscles.as_deref(),
                    edited.as_ref(),
                );
            }
            // Without a rig element, outline the picked triangle of the displayed mesh.
            if let Some(sel) = &self.selection
                && sel.element.is_none()
                && let Some(t) = face.basis.triangles.get(sel.hit.triangle)
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
        }
        self.set_lines(lines);
    }

    fn repose(&mut self) {
        let Some(face) = &self.face else { return };
        if let Err(e) = self.posed.update(&face.basis, &self.sliders) {
            let text = format!("Cannot pose {}: {e}", face.name);
            self.error(text);
        }
        if self.face.as_ref().is_some_and(|f| f.model.is_some()) {
            self.refresh_overlays();
        }
    }

    fn poll_jobs(&mut self, ctx: &egui::Context) {
        if let Some(job) = &mut self.exporting
            && let Some(result) = job.poll()
        {
            let label = job.label().to_owned();
            self.exporting = None;
            match result {
                Ok(text) => self.info(text),
                Err(e) => self.error(format!("{label} failed: {e}")),
            }
        }
        if let Some(job) = &mut self.loading
            && let Some(result) = job.poll()
        {
            self.loading = None;
            self.opened(ctx, result);
        }
        if let Some(r) = &mut self.rigging
            && let Some(result) = r.job.poll()
        {
            let topology_id = r.topology_id;
            self.rigging = None;
            let same_face = self
                .face
                .as_ref()
                .is_some_and(|f| f.topology_id == topology_id);
            match result {
                // A rig for a face that was replaced meanwhile is dropped.
                Ok(_) if !same_face => {}
                Ok((model, status)) => {
                    let name = self
                        .face
                        .as_ref()
                        .map(|f| f.name.clone())
                        .unwrap_or_default();
                    let text = match &status {
                        CacheStatus::Loaded => format!(
                            "Rig of {name} loaded from the cache ({} muscles)",
                            model.basis.muscle_count()
                        ),
                        CacheStatus::Computed { save_error, .. } => format!(
                            "Rig of {name} computed in {:.1} s ({} elements{}){}",
                            model.report.prep_seconds
                                + model.report.solve_seconds
                                + model.report.transfer_seconds,
                            model.report.shell_elements,
                            model
                                .report
                                .simplify_path
                                .map(|p| format!(
                                    "; {} triangles simulated, simplified {}",
                                    model.report.simulated_triangles,
                                    p.describe()
                                ))
                                .unwrap_or_default(),
                            save_error
                                .as_ref()
                                .map(|e| format!("; not cached: {e}"))
                                .unwrap_or_default()
                        ),
                    };
                    let warnings = model.report.warnings();
                    self.set_model(name, model);
                    if warnings.is_empty() {
                        self.info(text);
                    } else {
                        // Shown as an error: these responses are not trustworthy.
                        self.error(format!("{text}. Warning: {}", warnings.join("; ")));
                    }
                }
                Err(e) => self.error(format!("Rig computation stopped: {e}")),
            }
        }
    }

    /// Shows what a file turned out to hold: a saved rig at once, a face as its preview with
    /// its rig computed (or loaded from the cache) in the background.
    fn opened(&mut self, ctx: &egui::Context, result: Result<(String, Opened), String>) {
        match result {
            Ok((name, Opened::Model(model))) => {
                self.info(format!(
                    "Opened the saved rig {name} ({} triangles, {} muscles)",
                    model.basis.triangles.len(),
                    model.basis.muscle_count()
                ));
                self.cancel_rig();
                self.rigging = None;
                self.set_model(name, *model);
            }
            Ok((name, Opened::Face { mesh, obj_source })) => {
                self.info(format!(
                    "Opened {name} ({} triangles); computing its muscle rig…",
                    mesh.triangles.len()
                ));
                let basis = source::preview_basis(&mesh);
                let source = Arc::new((mesh, obj_source));
                self.params = PipelineParams::default();
                self.install_face(name, basis, Some(source), None, true);
                self.rebuild_rig(ctx);
            }
            Err(e) => self.error(format!("Could not open: {e}")),
        }
    }

    fn automation(&mut self, ctx: &egui::Context) {
        if self.ready_at.is_none() && self.frames_with_face >= 3 {
            let wait_for_preset = self.options.preset.is_some() && self.model().is_none();
            if !wait_for_preset {
                self.ready_at = Some(Instant::now());
                if let Some(path) = &self.options.ready_file
                    && let Err(e) = facebem::write_atomic(path, b"ready\n")
                {
                    self.error(format!("Cannot write the ready file: {e}"));
                }
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
        let ctx = ui.ctx().clone();
        self.poll_jobs(&ctx);
        self.poll_dialog(&ctx);
        self.dropped_files(&ctx);
        egui::Panel::top("toolbar").show(ui, |ui| self.toolbar(ui));
        egui::Panel::bottom("status").show(ui, |ui| self.status_bar(ui));
        egui::Panel::left("controls")
            .default_size(320.0)
            .show(ui, |ui| {
                egui::ScrollArea::vertical().show(ui, |ui| {
                    self.sliders_ui(ui);
                    ui.separator();
                    self.view_ui(ui);
                    ui.separator();
                    self.rig_ui(ui);
                    ui.separator();
                    self.export_ui(ui);
                });
            });
        egui::CentralPanel::default()
            .frame(egui::Frame::NONE)
            .show(ui, |ui| self.viewport(ui));
        self.automation(&ctx);
    }
}

impl eframe::App for ViewerApp {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        self.show(ui);
    }
}

/// The bundled default face, as [`facebem::open::open`] would return it.
fn default_face_opened() -> Result<(String, Opened), String> {
    let mesh = facebem::open::default_face().map_err(|e| e.to_string())?;
    let obj_source = Some(facebem::open::DEFAULT_FACE_OBJ.to_owned());
    let name = facebem::open::DEFAULT_FACE_NAME.to_owned();
    Ok((name, Opened::Face { mesh, obj_source }))
}

/// The home folder (`$HOME`), if set.
fn home_dir() -> Option<PathBuf> {
    std::env::var_os("HOME")
        .filter(|h| !h.is_empty())
        .map(PathBuf::from)
}

/// `dir` as the UI shows it: `~` or `~/rest` under the home folder, else as is.
///
/// ```
/// use viewer::app::{expand_home, home_relative};
/// if let Some(home) = std::env::var_os("HOME").filter(|h| !h.is_empty()) {
///     let dir = std::path::Path::new(&home).join("faces");
///     assert_eq!(home_relative(&dir), "~/faces");
///     assert_eq!(expand_home("~/faces"), dir);
/// }
/// assert_eq!(home_relative("/nonexistent-root/x".as_ref()), "/nonexistent-root/x");
/// ```
pub fn home_relative(dir: &Path) -> String {
    match home_dir().and_then(|h| dir.strip_prefix(h).ok().map(Path::to_path_buf)) {
        Some(rest) if rest.as_os_str().is_empty() => "~".to_owned(),
        Some(rest) => format!("~/{}", rest.display()),
        None => dir.display().to_string(),
    }
}

/// The inverse of [`home_relative`]: a leading `~` or `~/` becomes the home folder.
pub fn expand_home(text: &str) -> PathBuf {
    let rest = match text.strip_prefix('~') {
        Some("") => Some(""),
        Some(r) if r.starts_with('/') => Some(&r[1..]),
        _ => None,
    };
    match (rest, home_dir()) {
        (Some(rest), Some(home)) => home.join(rest),
        _ => PathBuf::from(text),
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

/// Display name of a muscle (thesis name for the standard ones).
pub(crate) fn muscle_label(m: &face_prep::Muscle) -> String {
    m.kind
        .map_or_else(|| m.name.clone(), |k| k.display_name().to_owned())
}
