//! A whole head's glTF (issue 32): an OBJ head as a GLB with one mesh per part, its own
//! vertices, texture coordinates and materials; a GLB or VRM head as the user's own file with
//! the targets added to every mesh that moves (a `.gltf` with separate files as that file
//! packed into one GLB, [`face_prep::gltf_read::pack_glb`]). The command line's `export` and the viewer's
//! glTF button both write this.
//!
//! ```no_run
//! use std::path::Path;
//! use facebem::export::head::head_gltf;
//! # fn rigged() -> (facebem::input::heads::WholeFile, facebem::FaceModel, facebem::transfer::head::HeadBasis) { unimplemented!() }
//! let (whole, model, head) = rigged();
//! let path = Path::new("head.obj");
//! let out = head_gltf(path, Path::new("head.glb"), &whole, &model, &head, &Default::default())
//!     .unwrap();
//! std::fs::write("head.glb", &out.bytes).unwrap();
//! println!("{}", out.line);
//! ```

use std::path::{Path, PathBuf};

use crate::FaceModel;
use crate::export::gltf::MeshSplit;
use crate::export::{ExportLayout, GltfFormat, GltfParams};
use crate::input::heads::WholeFile;
use crate::transfer::head::HeadBasis;

/// A head's glTF, built in memory.
#[derive(Clone, Debug)]
pub struct HeadGltf {
    /// The file's bytes.
    pub bytes: Vec<u8>,
    /// What it holds, one line (for the command line's and the viewer's status).
    pub line: String,
    /// What of the user's materials could not be used, one line each.
    pub warnings: Vec<String>,
    /// The input files read besides the head itself (an OBJ's material libraries, textures).
    pub files_read: Vec<PathBuf>,
}

/// Why a head's glTF could not be built; each names the problem in one line.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum HeadGltfError {
    /// The head file could not be read again.
    #[error("{0}")]
    Read(String),
    /// The OBJ's materials.
    #[error(transparent)]
    Materials(#[from] crate::export::material::MaterialError),
    /// The OBJ's layout.
    #[error(transparent)]
    Layout(#[from] crate::export::LayoutError),
    /// Building the glTF.
    #[error(transparent)]
    Gltf(#[from] crate::export::GltfExportError),
    /// Writing the targets into the user's GLB or VRM.
    #[error(transparent)]
    UserFile(#[from] crate::export::user_gltf::UserGltfError),
}

/// The glTF of the head `whole` (read from `path`, rigged as `model` and carried to every
/// part as `head`) to be written at `out` (its extension picks GLB or glTF JSON for an OBJ
/// head): every ARKit and VRM target kept off the eyeballs, plus `params`' other choices.
pub fn head_gltf(
    path: &Path,
    out: &Path,
    whole: &WholeFile,
    model: &FaceModel,
    head: &HeadBasis,
    params: &GltfParams,
) -> Result<HeadGltf, HeadGltfError> {
    let limits = face_prep::InputLimits::default();
    let bytes = face_prep::limits::read_input_file(path, &limits)
        .map_err(|e| HeadGltfError::Read(e.to_string()))?;
    let plain = model.gltf_params(params);
    let named_fields = head.named_fields_for(plain.names);
    // Where the file's own references (buffers, images, material libraries) are read.
    let folder = match path.parent() {
        Some(f) if !f.as_os_str().is_empty() => f,
        _ => Path::new("."),
    };
    if !is_obj(path) {
        // A .gltf with separate files comes back as one GLB.
        let glb = face_prep::gltf_read::pack_glb(&bytes, folder, &limits)
            .map_err(|e| HeadGltfError::Read(e.to_string()))?;
        let params = GltfParams {
            named_fields,
            ..plain
        };
        let named = crate::export::gltf::named_targets(&head.basis, &params)?;
        let (glb, added) = crate::export::user_gltf::add_targets(
            &glb,
            &whole.scene,
            &named.targets,
            &named.same_as,
        )?;
        let line = format!(
            "{} morph targets added to {} of its meshes{}, {:.0} KB",
            named.targets.len(),
            added.meshes.len(),
            if added.vrm_expressions.is_empty() {
                String::new()
            } else {
                format!(", {} VRM expressions bound", added.vrm_expressions.len())
            },
            glb.len() as f64 / 1000.0
        );
        return Ok(HeadGltf {
            bytes: glb,
            line,
            warnings: Vec::new(),
            files_read: Vec::new(),
        });
    }
    let text = String::from_utf8_lossy(&bytes).into_owned();
    let materials = crate::export::material::ObjMaterials::load(&text, folder)?;
    let identity: Vec<Option<u32>> = (0..whole.scene.positions.len() as u32).map(Some).collect();
    let layout = ExportLayout::from_obj(&text, &identity)?;
    let mut warnings = materials.warnings.clone();
    let files_read = materials.files_read.clone();
    let params = GltfParams {
        format: GltfFormat::from_path(out),
        materials: Some(materials),
        named_fields,
        mesh_split: Some(mesh_per_part(whole)),
        ..plain
    };
    let (bytes, summary) = crate::export::build_gltf(&head.basis, &layout, &params)?;
    warnings.extend(summary.warnings);
    let line = format!(
        "{} morph targets on all {} vertices of the head, {:.0} KB",
        summary.target_names.len(),
        head.basis.neutral.len(),
        summary.bytes as f64 / 1000.0
    );
    Ok(HeadGltf {
        bytes,
        line,
        warnings,
        files_read,
    })
}

/// Whether `path` names an OBJ file (by its extension, any case).
pub fn is_obj(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("obj"))
}

/// One mesh per part of the head (skin, each eyeball, each row of teeth, gums and tongue, lid
/// parts, other), by the scene's triangles (an OBJ's export layout has the same triangles in
/// the same order).
pub fn mesh_per_part(whole: &WholeFile) -> MeshSplit {
    use face_prep::parts::{PartKind, Side};
    const NAMES: [&str; 8] = [
        "skin",
        "eyeball_left",
        "eyeball_right",
        "upper_teeth",
        "lower_teeth",
        "gums_and_tongue",
        "lid_parts",
        "other",
    ];
    let mut triangle_mesh = vec![7u32; whole.scene.triangles.len()];
    for (c, kind) in whole.parts.components.iter().zip(&whole.parts.kinds) {
        let mesh = match kind {
            PartKind::Skin => 0,
            PartKind::Eyeball(Side::Left) => 1,
            PartKind::Eyeball(Side::Right) => 2,
            PartKind::UpperTooth => 3,
            PartKind::LowerTooth => 4,
            PartKind::GumsAndTongue => 5,
            PartKind::LidPart => 6,
            _ => 7,
        };
        for &t in &c.triangles {
            if let Some(slot) = triangle_mesh.get_mut(t as usize) {
                *slot = mesh;
            }
        }
    }
    MeshSplit {
        names: NAMES.iter().map(|n| n.to_string()).collect(),
        triangle_mesh,
    }
}
