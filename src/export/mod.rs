//! Exports: OBJ of any pose ([`obj`]) and glTF 2.0 with one morph target per muscle action and
//! preset ([`gltf`]), in the user's own vertex layout ([`layout`]) and with the source's
//! licence ([`attribution`]); a whole head's GLB or VRM comes back as itself with the targets
//! added ([`user_gltf`]). Files are written atomically.

pub mod attribution;
pub mod gltf;
pub mod head;
pub mod layout;
pub mod material;
pub mod obj;
pub mod user_gltf;

use glam::DVec3;
use std::path::Path;

pub use gltf::{
    ArkitNaming, GltfExportError, GltfFormat, GltfParams, GltfSummary, MATERIAL_NAME, build_gltf,
    export_gltf, export_gltf_layout,
};
pub use layout::{ExportLayout, LayoutError};
pub use obj::ObjExportError;

use crate::MuscleBasis;
use crate::atomic_write::{WriteError, write_atomic};

/// Errors from writing an export file.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ExportError {
    /// Building the glTF failed.
    #[error(transparent)]
    Gltf(#[from] GltfExportError),
    /// Building the OBJ failed.
    #[error(transparent)]
    Obj(#[from] ObjExportError),
    /// The user's OBJ could not be laid out as glTF vertices.
    #[error(transparent)]
    Layout(#[from] LayoutError),
    /// The pose's sliders were invalid.
    #[error(transparent)]
    Pose(#[from] crate::PoseError),
    /// Writing the file failed.
    #[error(transparent)]
    Write(#[from] WriteError),
}

/// Writes `basis` as glTF to `path` (atomically); the container follows the extension
/// (`.gltf` → embedded JSON, otherwise binary `.glb`), overriding `params.format`. Returns
/// what the file holds.
pub fn write_gltf(
    path: &Path,
    basis: &MuscleBasis,
    params: &GltfParams,
) -> Result<GltfSummary, ExportError> {
    let params = GltfParams {
        format: GltfFormat::from_path(path),
        ..params.clone()
    };
    let layout = ExportLayout::welded(&basis.neutral, &basis.triangles);
    let (bytes, summary) = build_gltf(basis, &layout, &params)?;
    write_atomic(path, &bytes)?;
    Ok(summary)
}

impl crate::FaceModel {
    /// OBJ text of the pose `sliders`: the user's own OBJ with only `v` lines replaced when the
    /// face came from an OBJ file, otherwise a plain OBJ of the welded mesh.
    pub fn obj_text(&self, sliders: &[f64]) -> Result<String, ExportError> {
        let posed = self.basis.pose(sliders)?;
        Ok(match &self.obj_source {
            Some(text) => self.pose_obj_text(text, &posed)?,
            None => obj::plain_obj(&posed, &self.basis.triangles)?,
        })
    }

    /// The face's OBJ text `text` with every `v` line moved as the vertex it takes moves from
    /// the neutral to `posed` (the face mesh's vertices posed, its frame and units): each line
    /// keeps its own position plus that motion (a line drawn exactly at its vertex gets the posed
    /// position itself), so lines that follow another vertex (a mouth bag taken off the
    /// simulated face, [`face_prep::frame::contact::bag`]) move with it and stay where they are
    /// drawn. Unused lines are kept as written.
    ///
    /// ```no_run
    /// let (model, _) = facebem::input::default_model(None, &facebem::Control::new()).unwrap();
    /// let text = model.obj_source.clone().unwrap();
    /// let neutral = model.pose_obj_text(&text, &model.mesh.vertices).unwrap();
    /// assert_eq!(neutral.lines().count(), text.lines().count());
    /// ```
    pub fn pose_obj_text(&self, text: &str, posed: &[DVec3]) -> Result<String, ExportError> {
        let layout = ExportLayout::from_obj_for(text, &self.mesh)?;
        let n = layout.input_count;
        let mut lines = Vec::with_capacity(n);
        let mut index = Vec::with_capacity(n);
        for k in 0..n {
            let own = layout.positions[k];
            match layout.welded[k] {
                Some(w) => {
                    let (p, v) = posed
                        .get(w as usize)
                        .zip(self.mesh.vertices.get(w as usize))
                        .ok_or(obj::ObjExportError::VertexOutOfRange {
                            line: k + 1,
                            vertex: w as usize,
                            count: posed.len().min(self.mesh.vertices.len()),
                        })?;
                    // A line drawn at its vertex gets the posed position exactly.
                    lines.push(if own == *v { *p } else { own + (*p - *v) });
                    index.push(Some(k as u32));
                }
                None => {
                    lines.push(own);
                    index.push(None);
                }
            }
        }
        Ok(obj::pose_from_template(text, &index, &lines)?)
    }

    /// Per `v` line of the face's OBJ text `text`, the vertex of the face mesh its pose takes:
    /// [`face_prep::FaceMesh::input_to_vertex`], except that a `v` line only the lower lip of
    /// a cut lip line uses takes the lower lip's vertex ([`ExportLayout::from_obj_for`]).
    pub fn input_vertices(&self, text: &str) -> Result<Vec<Option<u32>>, ExportError> {
        if self.mesh.lip_line.is_none() && self.mesh.lid_lines.is_empty() {
            return Ok(self.mesh.input_to_vertex.clone());
        }
        let layout = ExportLayout::from_obj_for(text, &self.mesh)?;
        Ok(layout.welded[..layout.input_count].to_vec())
    }

    /// Writes the pose `sliders` as OBJ to `path` (atomically).
    pub fn write_obj(&self, path: &Path, sliders: &[f64]) -> Result<(), ExportError> {
        write_atomic(path, self.obj_text(sliders)?.as_bytes())?;
        Ok(())
    }

    /// The glTF vertices of this face: the user's OBJ layout when the face came from an OBJ
    /// file ([`ExportLayout::from_obj`]), otherwise the welded vertices.
    pub fn export_layout(&self) -> Result<ExportLayout, ExportError> {
        Ok(match &self.obj_source {
            Some(text) => ExportLayout::from_obj_for(text, &self.mesh)?,
            None => ExportLayout::welded(&self.basis.neutral, &self.basis.triangles),
        })
    }

    /// `params` completed with what the model knows: metres per input unit (the rig's length
    /// unit, also named in `asset.extras.inputUnit`), the bundled source's attribution and
    /// licence, the OBJ's header comments.
    pub fn gltf_params(&self, params: &GltfParams) -> GltfParams {
        let mut params = params.clone();
        params.metres_per_unit = self.metres_per_unit();
        params
            .asset_extras
            .insert("inputUnit".into(), self.rig.unit.to_string().into());
        if let Some(known) = attribution::identify(&self.mesh) {
            params.copyright = Some(known.copyright.to_string());
            params
                .asset_extras
                .insert("licence".into(), known.licence.into());
            params
                .asset_extras
                .insert("source".into(), known.file.into());
        }
        if let Some(text) = &self.obj_source {
            let header = attribution::obj_header(text);
            if !header.is_empty() {
                params
                    .asset_extras
                    .insert("sourceHeader".into(), header.into());
            }
        }
        params
    }

    /// Metres per unit of the input positions: the rig's length unit
    /// ([`face_prep::FaceRig::unit`], given with `--units` or detected from the eye distance).
    pub fn metres_per_unit(&self) -> f64 {
        self.rig.unit.metres()
    }

    /// glTF bytes of this face (see [`crate::FaceModel::write_gltf`]).
    pub fn gltf_bytes(&self, params: &GltfParams) -> Result<Vec<u8>, ExportError> {
        Ok(self.gltf_bytes_and_summary(params)?.0)
    }

    /// glTF bytes of this face and what they hold ([`build_gltf`]).
    pub fn gltf_bytes_and_summary(
        &self,
        params: &GltfParams,
    ) -> Result<(Vec<u8>, GltfSummary), ExportError> {
        let layout = self.export_layout()?;
        Ok(build_gltf(&self.basis, &layout, &self.gltf_params(params))?)
    }

    /// Writes the glTF morph-target export to `path` (atomically; `.gltf` or `.glb`, whatever
    /// `params.format` says): the user's vertex layout, positions in metres, the source's
    /// attribution ([`crate::FaceModel::gltf_params`]). Returns what the file holds.
    pub fn write_gltf(&self, path: &Path, params: &GltfParams) -> Result<GltfSummary, ExportError> {
        let params = GltfParams {
            format: GltfFormat::from_path(path),
            ..params.clone()
        };
        let (bytes, summary) = self.gltf_bytes_and_summary(&params)?;
        write_atomic(path, &bytes)?;
        Ok(summary)
    }
}
