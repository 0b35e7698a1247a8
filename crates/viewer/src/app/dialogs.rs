//! Native file dialogs (rfd: the XDG desktop portal on Linux, zenity as fallback) for Open,
//! the export folder and the muscle file. A dialog runs in a background job so the window keeps
//! drawing; the path fields stay for scripts and tests.

use std::path::PathBuf;

use eframe::egui;

use super::ViewerApp;
use crate::job::Job;

/// What a dialog's answer is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum DialogPurpose {
    /// A face or rig file to open.
    Open,
    /// The folder exports go to.
    ExportFolder,
    /// A muscle file to rebuild the rig with.
    MuscleFile,
}

/// A dialog being shown.
pub(super) struct PendingDialog {
    pub(super) purpose: DialogPurpose,
    pub(super) job: Job<Option<PathBuf>>,
}

impl ViewerApp {
    /// Shows the native dialog for `purpose` (in the background; the answer is acted on when
    /// it arrives). Nothing happens when the user cancels or no dialog service is available.
    pub(super) fn show_dialog(&mut self, ctx: &egui::Context, purpose: DialogPurpose) {
        if self.dialog.is_some() {
            return;
        }
        let start = self.export_dir();
        let job = Job::spawn("File dialog", Some(ctx.clone()), move |_| {
            let dialog = rfd::FileDialog::new().set_directory(&start);
            Ok(match purpose {
                DialogPurpose::Open => dialog
                    .set_title("Open a face or rig")
                    .add_filter("face or rig", &["obj", "gltf", "glb", "rig"])
                    .add_filter("any file", &["*"])
                    .pick_file(),
                DialogPurpose::ExportFolder => dialog.set_title("Export folder").pick_folder(),
                DialogPurpose::MuscleFile => dialog
                    .set_title("Load a muscle file")
                    .add_filter("muscle file", &["muscles", "txt"])
                    .add_filter("any file", &["*"])
                    .pick_file(),
            })
        });
        self.dialog = Some(PendingDialog { purpose, job });
    }

    pub(super) fn poll_dialog(&mut self, ctx: &egui::Context) {
        let Some(d) = &mut self.dialog else { return };
        let Some(result) = d.job.poll() else { return };
        let purpose = d.purpose;
        self.dialog = None;
        let Ok(Some(path)) = result else { return };
        match purpose {
            DialogPurpose::Open => {
                self.open_path = path.display().to_string();
                self.open(ctx, path);
            }
            DialogPurpose::ExportFolder => self.set_export_dir(&path),
            DialogPurpose::MuscleFile => self.load_muscle_file_from(ctx, &path),
        }
    }
}
