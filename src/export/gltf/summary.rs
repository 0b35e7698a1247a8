//! What a written glTF holds ([`GltfSummary`]), read back from the file's own JSON.

use serde_json::Value;

use super::{GltfExportError, GltfFormat, GltfParams, export_gltf_layout};
use crate::MuscleBasis;
use crate::export::layout::ExportLayout;

/// What a glTF export holds, besides its bytes ([`build_gltf`]).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct GltfSummary {
    /// The morph targets written, in file order.
    pub target_names: Vec<String>,
    /// Targets left out because an earlier one is exactly the same: (left out, written).
    pub same_as: Vec<(String, String)>,
    /// Targets left out because they are exactly −1 times an earlier one: (left out, written).
    pub negative_of: Vec<(String, String)>,
    /// Names left out, with the reason (not modelled, no controls, all zero).
    pub left_out: Vec<(String, String)>,
    /// Size of the file in bytes.
    pub bytes: u64,
    /// What of the user's materials could not be used (`mesh.extras.materialWarnings`).
    pub warnings: Vec<String>,
}

/// Like [`export_gltf_layout`], also saying what was written.
///
/// ```
/// use facebem::MuscleBasis;
/// use facebem::export::ExportLayout;
/// use facebem::export::gltf::{build_gltf, GltfParams};
/// use glam::DVec3;
/// let basis = MuscleBasis {
///     muscle_ids: vec!["zygomaticus_major_l".into()],
///     neutral: vec![DVec3::ZERO, DVec3::X, DVec3::Y],
///     triangles: vec![[0, 1, 2]],
///     displacements: vec![vec![DVec3::ZERO, DVec3::Z * 0.1, DVec3::ZERO]],
/// };
/// let layout = ExportLayout::welded(&basis.neutral, &basis.triangles);
/// let (glb, summary) = build_gltf(&basis, &layout, &GltfParams::default()).unwrap();
/// assert_eq!(summary.bytes, glb.len() as u64);
/// assert!(summary.target_names.iter().any(|n| n == "mouthSmileLeft"));
/// ```
pub fn build_gltf(
    basis: &MuscleBasis,
    layout: &ExportLayout,
    params: &GltfParams,
) -> Result<(Vec<u8>, GltfSummary), GltfExportError> {
    let bytes = export_gltf_layout(basis, layout, params)?;
    let summary = summarize(&bytes, params.format);
    Ok((bytes, summary))
}

/// The summary of a file this module wrote (read back from its JSON: one source of truth).
fn summarize(bytes: &[u8], format: GltfFormat) -> GltfSummary {
    let json: Value = match format {
        GltfFormat::Binary => {
            let len = bytes
                .get(12..16)
                .and_then(|b| <[u8; 4]>::try_from(b).ok())
                .map_or(0, |b| u32::from_le_bytes(b) as usize);
            bytes
                .get(20..20 + len)
                .and_then(|j| serde_json::from_slice(j).ok())
                .unwrap_or(Value::Null)
        }
        GltfFormat::Embedded => serde_json::from_slice(bytes).unwrap_or(Value::Null),
    };
    let extras = &json["meshes"][0]["extras"];
    let pairs = |key: &str| -> Vec<(String, String)> {
        extras[key]
            .as_object()
            .map(|m| {
                m.iter()
                    .map(|(k, v)| (k.clone(), v.as_str().unwrap_or_default().to_string()))
                    .collect()
            })
            .unwrap_or_default()
    };
    GltfSummary {
        target_names: extras["targetNames"]
            .as_array()
            .map(|a| {
                a.iter()
                    .filter_map(|n| n.as_str().map(str::to_string))
                    .collect()
            })
            .unwrap_or_default(),
        same_as: pairs("sameAs"),
        negative_of: pairs("negativeOf"),
        left_out: pairs("leftOutTargets"),
        bytes: bytes.len() as u64,
        warnings: extras["materialWarnings"]
            .as_array()
            .map(|a| {
                a.iter()
                    .filter_map(|w| w.as_str().map(str::to_string))
                    .collect()
            })
            .unwrap_or_default(),
    }
}
