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
