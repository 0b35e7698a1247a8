//! Opening faces and rigs for the viewer: the neutral preview, the rig cache location and the
//! mapping of pipeline progress to one progress bar.

use std::path::{Path, PathBuf};

use face_prep::FaceMesh;
use facebem::MuscleBasis;
use facebem::input::OpenError;
use facebem::{Progress, Stage};

/// The bundled default face's file in the source tree (MediaPipe canonical face, 852 triangles).
/// The app itself opens the copy compiled into `facebem` ([`facebem::input::DEFAULT_FACE_OBJ`]).
pub fn default_face_path() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/mediapipe_canonical_4loop.obj")
}

/// A muscle-less [`MuscleBasis`] of `mesh`: what the viewer shows while the rig is computed.
/// Same vertices and triangles as the pipeline's basis, so the view does not jump when the
/// rig arrives.
pub fn preview_basis(mesh: &FaceMesh) -> MuscleBasis {
    MuscleBasis {
        muscle_ids: Vec::new(),
        neutral: mesh.vertices.clone(),
        triangles: mesh.triangles.clone(),
        displacements: Vec::new(),
    }
}

/// Reads a face file (OBJ, glTF, GLB) as its neutral preview basis.
pub fn load_neutral(path: &Path) -> Result<MuscleBasis, Box<OpenError>> {
    let (mesh, _) = facebem::input::read_face(path).map_err(Box::new)?;
    Ok(preview_basis(&mesh))
}

/// Where the viewer caches the model of `mesh` computed with `params` (shared with the command
/// line): [`facebem::input::cache_file_for`].
pub use facebem::input::cache_file_for;

/// One 0…1 progress value over all pipeline stages, weighted by their typical share of the time
/// (assembly and LU dominate).
///
/// ```
/// use facebem::{Progress, Stage};
/// use viewer::source::overall_fraction;
/// let start = overall_fraction(Progress { stage: Stage::Prep, done: 0, total: 1 });
/// let mid = overall_fraction(Progress { stage: Stage::Factorisation, done: 1, total: 2 });
/// let end = overall_fraction(Progress { stage: Stage::Settle, done: 1, total: 1 });
/// assert!(start == 0.0 && start < mid && mid < end && end == 1.0);
/// ```
pub fn overall_fraction(p: Progress) -> f32 {
    let (start, end) = match p.stage {
        Stage::Prep => (0.0, 0.05),
        Stage::Assembly => (0.05, 0.55),
        Stage::Factorisation => (0.55, 0.9),
        Stage::Solves => (0.9, 0.97),
        Stage::Transfer => (0.97, 0.98),
        Stage::Settle => (0.98, 1.0),
        // A stage added later: shown as done.
        _ => (1.0, 1.0),
    };
    let f = p.done as f32 / p.total.max(1) as f32;
    start + (end - start) * f.clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_face_loads_with_its_852_triangles() {
        let basis = load_neutral(&default_face_path()).unwrap();
        assert_eq!(basis.triangles.len(), 852);
        let n = basis.neutral.len() as u32;
        assert!(basis.triangles.iter().flatten().all(|&i| i < n));
    }

    #[test]
    fn garbage_and_missing_files_are_errors_naming_the_file() {
        let dir = tempfile::tempdir().unwrap();
        let bad = dir.path().join("bad.obj");
        std::fs::write(&bad, "v 1 2 3\nf 1 2 9\n").unwrap();
        let err = load_neutral(&bad).unwrap_err().to_string();
        assert!(err.contains("bad.obj"), "{err}");
        let missing = dir.path().join("missing.obj");
        assert!(matches!(
            load_neutral(&missing).map_err(|e| *e),
            Err(OpenError::Read { .. })
        ));
    }

    #[test]
    fn cache_file_name_depends_on_mesh_and_parameters() {
        let (mesh, _) = facebem::input::read_face(&default_face_path()).unwrap();
        let dir = Path::new("/cache");
        let p = facebem::PipelineParams::default();
        let a = cache_file_for(dir, &mesh, &p);
        assert_eq!(a, cache_file_for(dir, &mesh, &p));
        let mut q = p.clone();
        q.rig.offset *= 2.0;
        assert_ne!(a, cache_file_for(dir, &mesh, &q));
        assert!(a.starts_with(dir) && a.extension().is_some_and(|e| e == "rig"));
    }
}
