//! Background jobs: opening files (the Open button, dropped files, start-up), acting on the
//! jobs that finished (a face, a rig, an export), and the start-up automation (ready file,
//! closing after it).

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::{Duration, Instant};

use eframe::egui;
use facebem::PipelineParams;
use facebem::input::{CacheStatus, Opened};

use super::ViewerApp;
use crate::head::HeadSource;
use crate::job::Job;
use crate::source;

impl ViewerApp {
    /// Starts opening `path` (face or saved rig) in the background; the current face stays
    /// usable meanwhile. A face without rig is shown at once and its rig computed (or loaded
    /// from the cache) by a second job.
    pub fn open(&mut self, ctx: &egui::Context, path: PathBuf) {
        let job = Job::spawn(
            format!("Opening {}", file_name(&path)),
            Some(ctx.clone()),
            move |ctl| {
                ctl.report("reading", 0.0);
                let opened = open_file(&path);
                ctl.report("read", 1.0);
                opened
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

    pub(super) fn poll_jobs(&mut self, ctx: &egui::Context) {
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
                Ok((model, status, head)) => {
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
                    let distrust = facebem::model::distrust(&model);
                    let text = match &head {
                        Some(h) => format!(
                            "{text}; carried to all {} vertices of the head",
                            h.basis.neutral.len()
                        ),
                        None => text,
                    };
                    match head {
                        Some(head) => self.set_head_model(name, model, head),
                        None => self.set_model(name, model),
                    }
                    if !distrust.is_empty() {
                        // In red: the command line refuses to write this rig without --force.
                        let mut message = format!("{text}. {}", untrustworthy(&distrust));
                        if !warnings.is_empty() {
                            message += &format!(". Warning: {}", warnings.join("; "));
                        }
                        self.error(message);
                    } else if warnings.is_empty() {
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
    pub(super) fn opened(&mut self, ctx: &egui::Context, result: Result<OpenedFile, String>) {
        let (name, opened) = match result {
            Ok(file) => {
                self.looks = Arc::new(file.looks);
                (file.name, file.opened)
            }
            Err(e) => return self.error(format!("Could not open: {e}")),
        };
        let looks_warning = (self.looks.warnings.first())
            .map(|w| format!("Opened {name}, drawn without part of its look: {w}"));
        match opened {
            Contents::Head(head) => {
                self.info(format!(
                    "Opened {name}: a head ({}); rigging its front face ({} triangles)…",
                    head.whole.summary(),
                    head.mesh.triangles.len()
                ));
                let basis = head.preview_basis();
                self.params = PipelineParams::default();
                let head = super::HeadView {
                    source: Arc::new(*head),
                    basis: None,
                };
                self.install_face(name, basis, None, None, true, Some(head));
                self.rebuild_rig(ctx);
            }
            Contents::File(Opened::Model(model)) => {
                let text = format!(
                    "Opened the saved rig {name} ({} triangles, {} muscles)",
                    model.basis.triangles.len(),
                    model.basis.muscle_count()
                );
                let distrust = facebem::model::distrust(&model);
                if distrust.is_empty() {
                    self.info(text);
                } else {
                    self.error(format!("{text}. {}", untrustworthy(&distrust)));
                }
                self.cancel_rig();
                self.rigging = None;
                self.set_model(name, *model);
            }
            Contents::File(Opened::Face { mesh, obj_source }) => {
                self.info(format!(
                    "Opened {name} ({} triangles); computing its muscle rig…",
                    mesh.triangles.len()
                ));
                let basis = source::preview_basis(&mesh);
                let source = Arc::new((mesh, obj_source));
                self.params = PipelineParams::default();
                self.install_face(name, basis, Some(source), None, true, None);
                self.rebuild_rig(ctx);
            }
        }
        if let Some(w) = looks_warning {
            self.error(w);
        }
    }

    pub(super) fn automation(&mut self, ctx: &egui::Context) {
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

    pub(super) fn dropped_files(&mut self, ctx: &egui::Context) {
        let dropped = ctx.input(|i| i.raw.dropped_files.first().map(|f| f.path().to_path_buf()));
        if let Some(path) = dropped {
            self.open(ctx, path);
        }
    }
}

/// What a file held: a face or a saved rig ([`Opened`]), or a whole head.
pub(crate) enum Contents {
    /// A face or a saved rig.
    File(Opened),
    /// A head or an avatar, read whole.
    Head(Box<HeadSource>),
}

/// A file read by [`open_file`]: its name, what it holds and its materials.
pub(crate) struct OpenedFile {
    name: String,
    opened: Contents,
    looks: crate::surface::Looks,
}

/// Reads `path` (face, head or saved rig) and the materials it names.
pub(crate) fn open_file(path: &Path) -> Result<OpenedFile, String> {
    let opened = match facebem::input::open(path) {
        Ok(opened) => opened,
        Err(e) => {
            // A head or an avatar is read whole; anything else says what it holds.
            return match (&e, facebem::input::heads::WholeFile::examine(path)) {
                (facebem::input::OpenError::Face { .. }, Some(Ok(whole))) => Ok(OpenedFile {
                    name: file_name(path),
                    opened: Contents::Head(Box::new(HeadSource::new(path, whole)?)),
                    looks: crate::surface::Looks::default(),
                }),
                (facebem::input::OpenError::Face { .. }, Some(Err(refusal))) => Err(refusal),
                _ => Err(e.to_string()),
            };
        }
    };
    let text = match &opened {
        Opened::Face { obj_source, .. } => obj_source.as_deref(),
        Opened::Model(m) => m.obj_source.as_deref(),
    };
    let mut looks = crate::surface::Looks::load(path, text);
    if matches!(opened, Opened::Model(_)) {
        // A rig file carries its face's OBJ text, not the folder of its material libraries:
        // what is found beside it is used, what is not is no news.
        looks.warnings.clear();
    }
    Ok(OpenedFile {
        name: file_name(path),
        opened: Contents::File(opened),
        looks,
    })
}

/// The bundled default face, as [`open_file`] would return it.
pub(super) fn default_face_opened() -> Result<OpenedFile, String> {
    let mesh = facebem::input::default_face().map_err(|e| e.to_string())?;
    let obj_source = Some(facebem::input::DEFAULT_FACE_OBJ.to_owned());
    Ok(OpenedFile {
        name: facebem::input::DEFAULT_FACE_NAME.to_owned(),
        opened: Contents::File(Opened::Face { mesh, obj_source }),
        looks: crate::surface::Looks::default(),
    })
}

pub(super) fn file_name(path: &Path) -> String {
    path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    )
}

/// The status line of a rig past the trust thresholds ([`facebem::model::distrust`]).
fn untrustworthy(causes: &[String]) -> String {
    format!(
        "This rig is not trustworthy (the command line refuses to write it without --force): {}",
        causes.join("; ")
    )
}
