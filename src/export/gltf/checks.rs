//! The checks an export makes before anything is built: the basis, the layout, the named
//! fields and the parameters.

use super::{GltfExportError, GltfParams};
use crate::MuscleBasis;
use crate::export::layout::ExportLayout;

/// Checks the basis, the layout and the parameters before anything is built.
pub(super) fn check(
    basis: &MuscleBasis,
    layout: &ExportLayout,
    params: &GltfParams,
) -> Result<(), GltfExportError> {
    let n = basis.neutral.len();
    if n == 0 || basis.triangles.is_empty() {
        return Err(GltfExportError::EmptyMesh {
            vertices: n,
            triangles: basis.triangles.len(),
        });
    }
    let s = params.seconds_per_keyframe;
    // The clips' last keyframe is at 2 s.
    if !((2.0 * s).is_finite() && s > 0.0) {
        return Err(GltfExportError::BadKeyframeTime(
            params.seconds_per_keyframe,
        ));
    }
    if !(params.metres_per_unit.is_finite() && params.metres_per_unit > 0.0) {
        return Err(GltfExportError::BadUnit(params.metres_per_unit));
    }
    check_fields(basis, params)?;
    for (t, tri) in basis.triangles.iter().enumerate() {
        if let Some(&v) = tri.iter().find(|&&v| v as usize >= n) {
            return Err(GltfExportError::IndexOutOfRange {
                triangle: t,
                vertex: v,
                count: n,
            });
        }
    }
    check_layout(layout, n)
}

/// The controls' and the named fields' lengths and names.
pub(super) fn check_fields(
    basis: &MuscleBasis,
    params: &GltfParams,
) -> Result<(), GltfExportError> {
    let n = basis.neutral.len();
    for (name, field) in &params.named_fields {
        let standard = crate::expressions::arkit::NAMES.contains(&name.as_str())
            || crate::expressions::vrm::NAMES.contains(&name.as_str());
        if !standard {
            return Err(GltfExportError::NotANamedField(name.clone()));
        }
        if field.len() != n {
            return Err(GltfExportError::NamedFieldLength {
                name: name.clone(),
                len: field.len(),
                vertices: n,
            });
        }
    }
    for (id, field) in basis.muscle_ids.iter().zip(&basis.displacements) {
        if field.len() != n {
            return Err(GltfExportError::FieldLength {
                muscle: id.clone(),
                expected: n,
                got: field.len(),
            });
        }
    }
    Ok(())
}

/// The layout fits a basis of `n` vertices.
fn check_layout(layout: &ExportLayout, n: usize) -> Result<(), GltfExportError> {
    let m = layout.len();
    let lengths_fit = layout.positions.len() == m
        && layout.input_index.len() == m
        && layout.uvs.as_ref().is_none_or(|u| u.len() == m)
        && layout.normals.as_ref().is_none_or(|u| u.len() == m);
    if !lengths_fit || layout.triangles.is_empty() {
        return Err(GltfExportError::Layout(
            "per-vertex lists of different lengths, or no triangles".into(),
        ));
    }
    if let Some(w) = layout.welded.iter().flatten().find(|&&w| w as usize >= n) {
        return Err(GltfExportError::Layout(format!(
            "vertex {w} of {n} does not exist"
        )));
    }
    if let Some(t) = layout.triangles.iter().position(|t| {
        t.iter()
            .any(|&i| layout.welded.get(i as usize).is_none_or(Option::is_none))
    }) {
        return Err(GltfExportError::Layout(format!(
            "triangle {t} uses a vertex outside the mesh"
        )));
    }
    Ok(())
}
