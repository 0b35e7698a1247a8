//! Exports: when they are allowed, the folder they go to (shown relative to the home folder)
//! and writing them in the background.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use eframe::egui;

use super::{ExportKind, ViewerApp};
use crate::export::{ExportRequest, write_export};
use crate::job::Job;

impl ViewerApp {
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
        let head = face.head.as_ref().and_then(|h| {
            Some(crate::export::HeadExport {
                source: Arc::clone(&h.source),
                basis: Arc::clone(h.basis.as_ref()?),
            })
        });
        let job = Job::spawn(kind.label(), Some(ctx.clone()), move |ctl| {
            ctl.report("writing", 0.0);
            let request = ExportRequest {
                dir,
                stem,
                basis,
                model,
                sliders,
                head,
            };
            let path = write_export(kind, &request).map_err(|e| e.to_string())?;
            Ok(format!("Exported {}", path.display()))
        });
        self.exporting = Some(job);
    }
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
