//! Rebuilding the rig in the background (new offset/thickness, edited muscles or feature boxes,
//! a muscle file), with the displayed rig usable until the new one is ready.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use eframe::egui;
use face_prep::{Box2, FeatureBoxes};
use facebem::Control;

use super::{RigJob, ViewerApp, muscle_label};
use crate::job::Job;
use crate::overlay::RigGeometry;
use crate::source;

impl ViewerApp {
    pub(super) fn cache_dir(&self) -> PathBuf {
        self.options
            .cache_dir
            .clone()
            .unwrap_or_else(facebem::input::default_cache_dir)
    }

    /// Computes (or loads from the cache) the rig of the displayed face with the current
    /// parameters, in the background. The displayed rig stays usable until the new one is ready.
    pub fn rebuild_rig(&mut self, ctx: &egui::Context) {
        self.rebuild_rig_with_boxes(ctx, None);
    }

    /// Like [`ViewerApp::rebuild_rig`], with user-edited feature boxes (canonical frame): the
    /// pipeline places the ten standard muscles and the skull in them (edited muscles are
    /// replaced by the standard ones placed in the new boxes). The boxes stay in the parameters
    /// for later rebuilds (offset, thickness).
    pub fn rebuild_rig_with_boxes(&mut self, ctx: &egui::Context, boxes: Option<FeatureBoxes>) {
        let Some(face) = &self.face else { return };
        let head = face.head.as_ref().map(|h| Arc::clone(&h.source));
        let source = face.source.clone();
        if source.is_none() && head.is_none() {
            self.error("This face has no source mesh to build a rig from".to_owned());
            return;
        }
        if let Some(old) = self.rigging.take() {
            old.control.cancel();
            old.job.control().cancel();
        }
        let dir = self.cache_dir();
        if let Some(boxes) = boxes {
            self.params.boxes = Some(boxes);
            self.params.muscles = None;
        }
        let params = self.params.clone();
        let control = Control::new();
        let worker_control = control.clone();
        let name = face.name.clone();
        let job = Job::spawn(format!("Rig of {name}"), Some(ctx.clone()), move |ctl| {
            let progress_ctl = Arc::clone(ctl);
            let cancel = worker_control.clone();
            let control = worker_control.with_progress(move |p| {
                if progress_ctl.is_cancelled() {
                    cancel.cancel();
                }
                progress_ctl.report(p.stage.label(), source::overall_fraction(p));
            });
            ctl.report("cache", 0.0);
            if let Err(e) = std::fs::create_dir_all(&dir) {
                // Not fatal: the model is still computed; saving it will report the problem.
                ctl.report(&format!("cache folder: {e}"), 0.0);
            }
            if let Some(head) = head {
                let rigged = head.rig(&params, &dir, &control)?;
                return Ok((rigged.model, rigged.status, Some(rigged.head)));
            }
            let Some((mesh, obj)) = source.as_deref() else {
                return Err("no source mesh".to_owned());
            };
            let cache_path = source::cache_file_for(&dir, mesh, &params);
            facebem::input::load_or_build(mesh, obj.clone(), &params, &cache_path, &control)
                .map(|(model, status)| (model, status, None))
                .map_err(|e| e.to_string())
        });
        self.rigging = Some(RigJob {
            job,
            control,
            topology_id: face.topology_id,
            started: std::time::Instant::now(),
            shown_fraction: 0.0,
        });
    }

    /// Cancels the running rig computation, if any (the displayed face stays).
    pub fn cancel_rig(&mut self) {
        if let Some(r) = &self.rigging {
            r.control.cancel();
            r.job.control().cancel();
        }
    }

    /// Applies `edit` to the muscles used for the next rebuild (a copy of the rig's muscles at
    /// first) and says so; "Rebuild rig" solves with them.
    pub(super) fn edit_muscles(
        &mut self,
        edit: impl FnOnce(&mut Vec<face_prep::Muscle>, &RigGeometry, &face_prep::FaceRig),
    ) {
        let Some(face) = &self.face else { return };
        let (Some(model), Some(geo)) = (&face.model, &face.rig_geometry) else {
            return;
        };
        let mut muscles = self
            .params
            .muscles
            .clone()
            .unwrap_or_else(|| model.rig.muscles.clone());
        edit(&mut muscles, geo, &model.rig);
        let summary: Vec<String> = muscles
            .iter()
            .map(|m| format!("{} {}", muscle_label(m), m.front_chain.len()))
            .collect();
        if let Some(sel) = &mut self.selection
            && let Some(e) = sel.element
        {
            sel.muscles = crate::overlay::muscles_of_element(&muscles, e);
        }
        self.params.muscles = Some(muscles);
        self.refresh_overlays();
        self.info(format!(
            "Muscles edited (front elements: {}); press Rebuild rig to solve with them",
            summary.join(", ")
        ));
    }

    /// The four measured feature boxes being edited (face, eye L, eye R, mouth; canonical
    /// frame), if the box editor is open.
    pub fn box_edit_mut(&mut self) -> Option<&mut [Box2; 4]> {
        self.box_edit.as_mut()
    }

    /// Opens the box editor on the rig's current boxes (no-op without a rig).
    pub fn start_box_edit(&mut self) {
        if self.box_edit.is_none()
            && let Some(m) = self.model()
        {
            let b = m.rig.boxes;
            self.box_edit = Some([b.face, b.eye_l, b.eye_r, b.mouth]);
        }
        self.refresh_overlays();
    }

    /// The edited boxes with the derived nose and skull boxes, or why they are invalid.
    pub fn edited_boxes(&self) -> Option<Result<FeatureBoxes, String>> {
        self.box_edit
            .map(|[f, l, r, m]| FeatureBoxes::derive(f, l, r, m).map_err(|e| e.to_string()))
    }

    /// Rebuilds the rig with the edited boxes (see [`ViewerApp::rebuild_rig_with_boxes`]).
    pub fn apply_box_edit(&mut self, ctx: &egui::Context) {
        match self.edited_boxes() {
            Some(Ok(b)) => self.rebuild_rig_with_boxes(ctx, Some(b)),
            Some(Err(e)) => self.error(format!("Feature boxes: {e}")),
            None => {}
        }
    }

    /// The muscles the next rebuild will use (edited ones, or the rig's).
    pub fn pending_muscles(&self) -> Option<&[face_prep::Muscle]> {
        match &self.params.muscles {
            Some(m) => Some(m),
            None => self.model().map(|m| m.rig.muscles.as_slice()),
        }
    }

    /// The muscle file the viewer saves and loads by default: `<Export folder>/<face>.muscles`.
    pub fn default_muscle_file(&self) -> Option<PathBuf> {
        let face = self.face.as_ref()?;
        let stem = Path::new(&face.name)
            .file_stem()
            .map_or_else(|| "face".to_owned(), |s| s.to_string_lossy().into_owned());
        Some(self.export_dir().join(format!("{stem}.muscles")))
    }

    /// Reads the muscle file `path` (thesis format) and rebuilds the rig with it.
    pub fn load_muscle_file_from(&mut self, ctx: &egui::Context, path: &Path) {
        let Some(model) = self.model() else {
            self.error("Load muscle file: the rig is not computed yet".to_owned());
            return;
        };
        match face_prep::muscle_file::load(path, model.rig.shell.triangles.len()) {
            Ok(muscles) => {
                self.params.muscles = Some(muscles);
                self.refresh_overlays();
                self.info(format!("Loaded {}; rebuilding the rig", path.display()));
                self.rebuild_rig(ctx);
            }
            Err(e) => self.error(format!(
                "Could not load the muscle file {}: {e}",
                path.display()
            )),
        }
    }
}
