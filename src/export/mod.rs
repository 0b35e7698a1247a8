//! Exports: OBJ of any pose ([`obj`]) and glTF 2.0 with one morph target per muscle action and
//! preset ([`gltf`]). Files are written atomically.

pub mod gltf;
pub mod obj;

use std::path::Path;

pub use gltf::{GltfExportError, GltfFormat, GltfParams, export_gltf};
pub use obj::ObjExportError;

use crate::MuscleBasis;
use crate::atomic_write::{WriteError, write_atomic};

/// Errors from writing an export file.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    /// Building the glTF failed.
    #[error(transparent)]
    Gltf(#[from] GltfExportError),
    /// Building the OBJ failed.
    #[error(transparent)]
    Obj(#[from] ObjExportError),
    /// The pose's sliders were invalid.
    #[error(transparent)]
    Pose(#[from] crate::PoseError),
    /// Writing the file failed.
    #[error(transparent)]
    Write(#[from] WriteError),
}

/// Writes `basis` as glTF to `path` (atomically); the container follows the extension
/// (`.gltf` → embedded JSON, otherwise binary `.glb`), overriding `params.format`.
pub fn write_gltf(
    path: &Path,
    basis: &MuscleBasis,
    params: &GltfParams,
) -> Result<(), ExportError> {
    let params = GltfParams {
        format: GltfFormat::from_path(path),
        ..params.clone()
    };
    let bytes = export_gltf(basis, &params)?;
    write_atomic(path, &bytes)?;
    Ok(())
}

impl crate::FaceModel {
    /// OBJ text of the pose `sliders`: the user's own OBJ with only `v` lines replaced when the
    /// face came from an OBJ file, otherwise a plain OBJ of the welded mesh.
    pub fn obj_text(&self, sliders: &[f64]) -> Result<String, ExportError> {
        let posed = self.basis.pose(sliders)?;
        Ok(match &self.obj_source {
            Some(text) => obj::pose_from_template(text, &self.mesh.input_to_vertex, &posed)?,
            None => obj::plain_obj(&posed, &self.basis.triangles),
        })
    }

    /// Writes the pose `sliders` as OBJ to `path` (atomically).
    pub fn write_obj(&self, path: &Path, sliders: &[f64]) -> Result<(), ExportError> {
        write_atomic(path, self.obj_text(sliders)?.as_bytes())?;
        Ok(())
    }

    /// Writes the glTF morph-target export to `path` (atomically; `.gltf` or `.glb`).
    pub fn write_gltf(&self, path: &Path, params: &GltfParams) -> Result<(), ExportError> {
        write_gltf(path, &self.basis, params)
    }
}
