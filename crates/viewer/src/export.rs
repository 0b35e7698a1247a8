//! Export buttons: what they write and where.

use std::path::PathBuf;
use std::sync::Arc;

use facebem::{FaceModel, MuscleBasis};

/// What an export button writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ExportKind {
    /// `<name>_pose.obj`: the current pose (in the user's own OBJ layout when the face came
    /// from an OBJ file).
    ObjPose,
    /// `<name>.glb`: glTF 2.0 with one morph target per muscle and preset.
    Gltf,
    /// `<name>.muscles`: the rig's muscle file (thesis format).
    MuscleFile,
}

impl ExportKind {
    /// Button label.
    pub fn label(self) -> &'static str {
        match self {
            ExportKind::ObjPose => "Export OBJ pose",
            ExportKind::Gltf => "Export glTF",
            ExportKind::MuscleFile => "Save muscle file",
        }
    }
}

/// Why an export failed.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    /// A muscle file needs the rig, which is not computed yet.
    #[error("the rig is not computed yet: there are no muscles to save")]
    NoRig,
    /// The slider values do not fit the basis.
    #[error(transparent)]
    Pose(#[from] facebem::PoseError),
    /// The user's OBJ could not be used as a template.
    #[error(transparent)]
    Obj(#[from] facebem::export::ObjExportError),
    /// Building or writing the glTF failed.
    #[error(transparent)]
    Gltf(#[from] facebem::export::ExportError),
    /// Writing the file failed.
    #[error(transparent)]
    Write(#[from] facebem::WriteError),
    /// Writing the muscle file failed.
    #[error(transparent)]
    MuscleFile(#[from] face_prep::MuscleFileError),
}

/// Everything an export needs, moved into its background job.
#[derive(Clone, Debug)]
pub struct ExportRequest {
    /// Folder the file goes to.
    pub dir: PathBuf,
    /// File name stem (the face's file name without extension).
    pub stem: String,
    /// The displayed basis.
    pub basis: MuscleBasis,
    /// The solved model, if any (user OBJ layout, muscles).
    pub model: Option<Arc<FaceModel>>,
    /// Current slider values.
    pub sliders: Vec<f64>,
}

/// Writes the export `kind` of `request` atomically; returns the file written.
pub fn write_export(kind: ExportKind, request: &ExportRequest) -> Result<PathBuf, ExportError> {
    Ok(match kind {
        ExportKind::ObjPose => {
            let path = request.dir.join(format!("{}_pose.obj", request.stem));
            let posed = request.basis.pose(&request.sliders)?;
            let text = match request.model.as_deref() {
                Some(FaceModel {
                    obj_source: Some(obj),
                    mesh,
                    ..
                }) => facebem::export::obj::pose_from_template(obj, &mesh.input_to_vertex, &posed)?,
                _ => facebem::export::obj::plain_obj(&posed, &request.basis.triangles),
            };
            facebem::write_atomic(&path, text.as_bytes())?;
            path
        }
        ExportKind::Gltf => {
            let path = request.dir.join(format!("{}.glb", request.stem));
            let params = facebem::export::GltfParams::default();
            facebem::export::write_gltf(&path, &request.basis, &params)?;
            path
        }
        ExportKind::MuscleFile => {
            let path = request.dir.join(format!("{}.muscles", request.stem));
            let model = request.model.as_deref().ok_or(ExportError::NoRig)?;
            face_prep::muscle_file::save(&path, &model.rig.muscles)?;
            path
        }
    })
}
