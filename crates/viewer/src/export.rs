//! Export buttons: what they write and where. An export never replaces an existing file: it
//! writes the first free name of `<stem>.glb`, `<stem> (2).glb`, `<stem> (3).glb`, …
//! ([`free_path`]).

use std::path::{Path, PathBuf};
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
    /// Building a head's glTF failed.
    #[error(transparent)]
    Head(#[from] facebem::export::head::HeadGltfError),
}

/// A head's export: the file it was read from and its rig carried to every part.
#[derive(Clone, Debug)]
pub struct HeadExport {
    /// The head as read.
    pub source: Arc<crate::head::HeadSource>,
    /// Its fields on every part.
    pub basis: Arc<facebem::transfer::head::HeadBasis>,
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
    /// For a head: its file and rig (the glTF is the user's own file back with the targets).
    pub head: Option<HeadExport>,
}

/// The first of `dir/<stem><ext>`, `dir/<stem> (2)<ext>`, `dir/<stem> (3)<ext>`, … that does not
/// exist (`ext` with its dot, e.g. `".glb"`).
///
/// ```
/// let dir = tempfile::tempdir().unwrap();
/// let first = viewer::export::free_path(dir.path(), "face", ".glb");
/// assert_eq!(first, dir.path().join("face.glb"));
/// std::fs::write(&first, b"x").unwrap();
/// assert_eq!(viewer::export::free_path(dir.path(), "face", ".glb"), dir.path().join("face (2).glb"));
/// ```
pub fn free_path(dir: &Path, stem: &str, ext: &str) -> PathBuf {
    let first = dir.join(format!("{stem}{ext}"));
    if !first.exists() {
        return first;
    }
    (2u64..)
        .map(|k| dir.join(format!("{stem} ({k}){ext}")))
        .find(|p| !p.exists())
        .unwrap_or(first)
}

/// Writes the export `kind` of `request` atomically, under a free name ([`free_path`]);
/// returns the file written.
pub fn write_export(kind: ExportKind, request: &ExportRequest) -> Result<PathBuf, ExportError> {
    let path_for = |suffix: &str| free_path(&request.dir, &request.stem, suffix);
    Ok(match kind {
        ExportKind::ObjPose => {
            let path = path_for("_pose.obj");
            let posed = request.basis.pose(&request.sliders)?;
            let head_text = request.head.as_ref().map(|h| h.source.obj_text.as_deref());
            let text = match (head_text, request.model.as_deref()) {
                // An OBJ head in its own layout: its scene has one vertex per `v` line.
                (Some(Some(obj)), _) => {
                    let identity: Vec<Option<u32>> = (0..posed.len() as u32).map(Some).collect();
                    facebem::export::obj::pose_from_template(obj, &identity, &posed)?
                }
                (Some(None), _) => {
                    facebem::export::obj::plain_obj(&posed, &request.basis.triangles)?
                }
                (None, model) => match model {
                    Some(
                        model @ FaceModel {
                            obj_source: Some(obj),
                            ..
                        },
                    ) => model.pose_obj_text(obj, &posed)?,
                    _ => facebem::export::obj::plain_obj(&posed, &request.basis.triangles)?,
                },
            };
            facebem::write_atomic(&path, text.as_bytes())?;
            path
        }
        ExportKind::Gltf if request.head.is_some() => {
            let (Some(head), Some(model)) = (&request.head, request.model.as_deref()) else {
                return Err(ExportError::NoRig);
            };
            // The user's own file back: a VRM stays a VRM, anything else becomes a GLB.
            let is_vrm =
                (head.source.path.extension()).is_some_and(|e| e.eq_ignore_ascii_case("vrm"));
            let path = path_for(if is_vrm { ".vrm" } else { ".glb" });
            let params = facebem::export::GltfParams::default();
            let built = facebem::export::head::head_gltf(
                &head.source.path,
                &path,
                &head.source.whole,
                model,
                &head.basis,
                &params,
            )?;
            facebem::write_atomic(&path, &built.bytes)?;
            path
        }
        ExportKind::Gltf => {
            let path = path_for(".glb");
            let params = facebem::export::GltfParams::default();
            let _summary = match request.model.as_deref() {
                // The user's vertex layout, metres, attribution.
                Some(model) => model.write_gltf(&path, &params)?,
                None => facebem::export::write_gltf(&path, &request.basis, &params)?,
            };
            path
        }
        ExportKind::MuscleFile => {
            let path = path_for(".muscles");
            let model = request.model.as_deref().ok_or(ExportError::NoRig)?;
            face_prep::muscle_file::save(&path, &model.rig.muscles)?;
            path
        }
    })
}
