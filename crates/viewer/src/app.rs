//! The eframe application: panels, sliders, presets, viewport interaction, background opening,
//! rig computation (cached) and exports.

use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Duration, Instant};

use eframe::egui;
use face_prep::{Box2, FaceMesh};
use facebem::Control;
use facebem::MuscleBasis;
use facebem::input::CacheStatus;
use facebem::{FaceModel, PipelineParams};

use crate::camera::OrbitCamera;
pub use crate::export::ExportKind;
use crate::head::HeadSource;
use crate::job::Job;
use crate::overlay::{OverlayOptions, RigGeometry};
use crate::picking::TriangleHit;
use crate::posed_mesh::{MeshVertex, PosedMesh, bounding_sphere, edge_indices};
use crate::renderer::{LineVertex, ReadBackError};
use crate::surface::{Looks, Surface, SurfaceVertex};

mod box_drag;
pub mod browser;
mod dialogs;
mod exports;
mod history;
mod jobs;
mod panels;
mod pose;
mod rig_editing;
pub mod timeline;
mod viewport;

pub use exports::{expand_home, home_relative};
use jobs::{OpenedFile, default_face_opened, open_file};
pub use pose::preset_label;

/// Viewport clear colour (display values, written as is).
pub const BACKGROUND: [f32; 3] = [0.11, 0.12, 0.14];
const SKIN: [f32; 4] = [0.86, 0.72, 0.62, 1.0];
const SELECTION: [f32; 4] = [1.0, 0.85, 0.1, 1.0];

/// Start-up options (from the command line).
#[derive(Clone, Debug, Default)]
pub struct ViewerOptions {
    /// Face or rig file to open; `None` opens the bundled default face.
    pub open: Option<PathBuf>,
    /// Rig cache folder; `None` = [`facebem::input::default_cache_dir`]
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
    edges: Arc<Vec<u32>>,
    /// What the shaded view draws: the user's layout and materials.
    surface: Arc<Surface>,
    /// The neutral surface (compare mode's left half).
    neutral_surface: Arc<Vec<SurfaceVertex>>,
    /// The mesh and its OBJ text, for (re)building the rig.
    source: Option<Arc<(FaceMesh, Option<String>)>>,
    /// The solved model, once available.
    model: Option<Arc<FaceModel>>,
    rig_geometry: Option<Arc<RigGeometry>>,
    /// A whole head: its parts and front face, and the rig carried to it once computed.
    head: Option<HeadView>,
}

/// A head shown whole ([`crate::head`]).
#[derive(Clone, Debug)]
struct HeadView {
    source: Arc<HeadSource>,
    basis: Option<Arc<facebem::transfer::head::HeadBasis>>,
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

/// A computed rig: the face's model, where it came from, and for a head its fields on every
/// part.
type RigOutcome = (
    FaceModel,
    CacheStatus,
    Option<facebem::transfer::head::HeadBasis>,
);

struct RigJob {
    job: Job<RigOutcome>,
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
    /// Undo and redo of the sliders.
    history: history::PoseHistory,
    /// The named expressions mixed into the sliders, with their weights ([`browser`]).
    mix: Vec<(&'static str, f64)>,
    browser_tab: browser::BrowserTab,
    browser_query: String,
    posed: PosedMesh,
    uploaded_vertices: Arc<Vec<MeshVertex>>,
    uploaded_generation: u64,
    /// The materials of the file opened last ([`crate::surface`]).
    looks: Arc<Looks>,
    /// The drawn surface's posed vertices and the (pose generation, heat) they were made for.
    surface_vertices: Arc<Vec<SurfaceVertex>>,
    surface_key: Option<(u64, bool)>,
    /// Heat map of displacement over the surface.
    heat: bool,
    /// Neutral and posed side by side.
    compare: bool,
    timeline: timeline::Timeline,
    lines: Arc<Vec<LineVertex>>,
    lines_generation: u64,
    /// The drawn muscle lines (user frame) and their names, for the name on hover.
    muscle_paths: Vec<(String, Vec<glam::DVec3>)>,
    camera: OrbitCamera,
    shaded: bool,
    wireframe: bool,
    overlays: OverlayOptions,
    params: PipelineParams,
    open_path: String,
    message: Option<StatusMessage>,
    loading: Option<Job<OpenedFile>>,
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
            history: history::PoseHistory::default(),
            mix: Vec::new(),
            browser_tab: browser::BrowserTab::default(),
            browser_query: String::new(),
            posed: PosedMesh::default(),
            uploaded_vertices: Arc::default(),
            uploaded_generation: 0,
            looks: Arc::default(),
            surface_vertices: Arc::default(),
            surface_key: None,
            heat: false,
            compare: false,
            timeline: timeline::Timeline::default(),
            lines: Arc::default(),
            lines_generation: 0,
            muscle_paths: Vec::new(),
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
                Some(open_file(&path))
            }
            Some(None) => Some(default_face_opened()),
            None => None,
        };
        if let Some(result) = opened {
            app.opened(&cc.egui_ctx, result);
        }
        app
    }

    /// Displays `basis` without a rig (sliders reset to 0, camera framed on it).
    pub fn set_face(&mut self, name: impl Into<String>, basis: MuscleBasis) {
        self.install_face(name.into(), basis, None, None, true, None);
    }

    /// Displays `basis` (a face read from `source`: its mesh and OBJ text) without a rig, drawn
    /// in the user's layout with `looks` (the viewer reads them itself when it opens a file;
    /// benchmarks and scripts set them here).
    pub fn set_face_with_looks(
        &mut self,
        name: impl Into<String>,
        basis: MuscleBasis,
        source: (FaceMesh, String),
        looks: Looks,
    ) {
        self.looks = Arc::new(looks);
        let (mesh, text) = source;
        self.install_face(
            name.into(),
            basis,
            Some(Arc::new((mesh, Some(text)))),
            None,
            true,
            None,
        );
    }

    fn install_face(
        &mut self,
        name: String,
        basis: MuscleBasis,
        source: Option<Arc<(FaceMesh, Option<String>)>>,
        model: Option<Arc<FaceModel>>,
        reframe: bool,
        head: Option<HeadView>,
    ) {
        let edges = edge_indices(&basis.triangles);
        let surface = match &head {
            Some(head) => {
                let (surface, looks) = head.source.surface(&basis, SKIN);
                self.looks = Arc::new(looks);
                surface
            }
            None => {
                let text_source = source
                    .as_deref()
                    .and_then(|(mesh, text)| Some((mesh, text.as_deref()?)));
                Surface::new(&basis, text_source, &self.looks, SKIN)
            }
        };
        let mut neutral = PosedMesh::default();
        let mut neutral_surface = Vec::new();
        if neutral
            .update(&basis, &vec![0.0; basis.muscle_count()])
            .is_ok()
        {
            surface.fill(neutral.vertices(), None, &mut neutral_surface);
        }
        self.sliders = vec![0.0; basis.muscle_count()];
        self.active_preset = None;
        self.mix.clear();
        self.history = history::PoseHistory::default();
        self.record_pose();
        if (self.timeline.keys().first()).is_some_and(|k| k.sliders.len() != basis.muscle_count()) {
            self.timeline = timeline::Timeline::default();
        }
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
            edges: Arc::new(edges),
            surface: Arc::new(surface),
            neutral_surface: Arc::new(neutral_surface),
            source,
            model,
            rig_geometry,
            head,
        });
        self.next_topology_id += 1;
        self.surface_key = None;
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
            None,
        );
    }

    /// Installs the rig of the displayed head: `model` of its front face, `head` its fields on
    /// every part (the sliders move the whole head; [`crate::head::display_basis`]).
    pub fn set_head_model(
        &mut self,
        name: impl Into<String>,
        model: FaceModel,
        head: facebem::transfer::head::HeadBasis,
    ) {
        let Some(source) = self.face.as_ref().and_then(|f| f.head.clone()) else {
            return self.error("No head is displayed to carry this rig to".to_owned());
        };
        let basis = crate::head::display_basis(&head);
        let view = HeadView {
            source: source.source,
            basis: Some(Arc::new(head)),
        };
        self.install_face(
            name.into(),
            basis,
            None,
            Some(Arc::new(model)),
            false,
            Some(view),
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

    /// Shows the heat map of displacement (mm) over the surface.
    pub fn set_heat_map(&mut self, on: bool) {
        self.heat = on;
    }

    /// Shows the neutral face beside the posed one.
    pub fn set_compare(&mut self, on: bool) {
        self.compare = on;
    }

    /// The drawn surface of the displayed face (layout, materials, textures).
    pub fn surface(&self) -> Option<&Surface> {
        self.face.as_ref().map(|f| &*f.surface)
    }

    /// The surface vertices handed to the renderer in the last frame.
    pub fn surface_vertices(&self) -> &[SurfaceVertex] {
        &self.surface_vertices
    }

    /// Which overlays are drawn.
    pub fn set_overlays(&mut self, overlays: OverlayOptions) {
        self.overlays = overlays;
        self.refresh_overlays();
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

    /// Draws one frame of the UI (what `eframe::App::ui` calls).
    pub fn show(&mut self, ui: &mut egui::Ui) {
        let ctx = ui.ctx().clone();
        self.poll_jobs(&ctx);
        self.poll_dialog(&ctx);
        self.dropped_files(&ctx);
        self.history_shortcuts(&ctx);
        egui::Panel::top("toolbar").show(ui, |ui| self.toolbar(ui));
        egui::Panel::bottom("status").show(ui, |ui| self.status_bar(ui));
        egui::Panel::left("controls")
            .default_size(320.0)
            .show(ui, |ui| {
                egui::ScrollArea::vertical().show(ui, |ui| {
                    self.sliders_ui(ui);
                    ui.separator();
                    self.browser_ui(ui);
                    ui.separator();
                    self.timeline_ui(ui);
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
        self.play_timeline(&ctx);
        // A change is one undo step once no button is held (a whole drag is one step); a
        // playing timeline is not a change of the user's.
        if !ctx.input(|i| i.pointer.any_down()) && !self.timeline.playing() {
            self.record_pose();
        }
    }
}

impl eframe::App for ViewerApp {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        self.show(ui);
    }
}

/// Display name of a muscle (thesis name for the standard ones).
pub(crate) fn muscle_label(m: &face_prep::Muscle) -> String {
    m.kind
        .map_or_else(|| m.name.clone(), |k| k.display_name().to_owned())
}
