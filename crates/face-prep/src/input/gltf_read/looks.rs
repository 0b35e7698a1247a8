//! The look of a glTF document's materials: base colour factor and base colour texture, for a
//! viewer drawing the user's own face as it looks in their tool.
//!
//! Images are read like buffers (the GLB binary chunk through a buffer view, a `data:` URI, or
//! a regular file inside the glTF's own folder), never more than the input limit. What cannot
//! be read is a warning on that material, not an error: the face still opens, drawn in its
//! base colour.

use std::path::Path;

use super::buffers::{decode_base64, resolve_relative};
use super::document::Document;
use crate::error::GltfError;
use crate::input::limits::InputLimits;

/// One material's look.
#[derive(Clone, Debug, PartialEq)]
pub struct MaterialLook {
    /// The material's name, or `#index`.
    pub name: String,
    /// `pbrMetallicRoughness.baseColorFactor` (linear RGBA).
    pub base_color: [f32; 4],
    /// The encoded image of `baseColorTexture` (PNG, JPEG, ... as the file holds it).
    pub image: Option<Vec<u8>>,
    /// Why the texture could not be read, when it could not.
    pub warning: Option<String>,
}

/// The looks of every material of a glTF/GLB document, in material order; `base` is the
/// folder relative URIs resolve in.
///
/// ```
/// use face_prep::gltf_read::material_looks;
/// let gltf = br#"{"asset":{"version":"2.0"},"materials":[
///     {"name":"skin","pbrMetallicRoughness":{"baseColorFactor":[1,0.5,0.25,1]}},
///     {"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}],
///     "textures":[{"source":0}],
///     "images":[{"uri":"data:image/png;base64,iVBORw0K"}]}"#;
/// let looks = material_looks(gltf, None, &Default::default()).unwrap();
/// assert_eq!(looks[0].base_color, [1.0, 0.5, 0.25, 1.0]);
/// assert_eq!(looks[1].name, "#1");
/// assert_eq!(looks[1].image.as_deref(), Some(&b"\x89PNG\r\n"[..]));
/// ```
pub fn material_looks(
    bytes: &[u8],
    base: Option<&Path>,
    limits: &InputLimits,
) -> Result<Vec<MaterialLook>, GltfError> {
    let mut doc = Document::parse(bytes, base, limits)?;
    let materials = doc.root.materials.clone();
    Ok(materials
        .iter()
        .enumerate()
        .map(|(i, m)| {
            let pbr = &m.pbr_metallic_roughness;
            let (image, warning) = match &pbr.base_color_texture {
                None => (None, None),
                Some(info) => match texture_image(&mut doc, info.index.value(), base) {
                    Ok(bytes) => (Some(bytes), None),
                    Err(e) => (
                        None,
                        Some(format!("material {i}: base colour texture: {e}")),
                    ),
                },
            };
            MaterialLook {
                name: m.name.clone().unwrap_or_else(|| format!("#{i}")),
                base_color: pbr.base_color_factor.0,
                image,
                warning,
            }
        })
        .collect())
}

/// The encoded bytes of texture `texture`'s image.
fn texture_image(
    doc: &mut Document,
    texture: usize,
    base: Option<&Path>,
) -> Result<Vec<u8>, String> {
    let max = doc.limits.max_file_bytes;
    let source = (doc.root.textures.get(texture))
        .ok_or_else(|| format!("texture {texture} does not exist"))?
        .source
        .value();
    let image = (doc.root.images.get(source))
        .ok_or_else(|| format!("image {source} does not exist"))?
        .clone();
    if let Some(view) = image.buffer_view {
        let v = (doc.root.buffer_views.get(view.value()))
            .ok_or_else(|| format!("image {source}: bufferView {} does not exist", view.value()))?
            .clone();
        let data = doc.buffer(v.buffer.value()).map_err(|e| e.to_string())?;
        let start = v.byte_offset.map_or(0, |o| o.0);
        let end = start.saturating_add(v.byte_length.0);
        return (data.get(start as usize..end as usize))
            .map(<[u8]>::to_vec)
            .ok_or_else(|| format!("image {source}: its bufferView lies beyond its buffer"));
    }
    let uri = image
        .uri
        .ok_or_else(|| format!("image {source} has neither a uri nor a bufferView"))?;
    if let Some(rest) = uri.strip_prefix("data:") {
        let (_, payload) = rest
            .split_once(";base64,")
            .ok_or("data URI is not base64-encoded")?;
        if payload.len() as u64 / 4 * 3 > max {
            return Err(format!("data URI is above the input limit of {max} bytes"));
        }
        return decode_base64(payload);
    }
    let path = resolve_relative(&uri, base)?;
    let meta = std::fs::metadata(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    if !meta.is_file() {
        return Err(format!("{} is not a regular file", path.display()));
    }
    if meta.len() > max {
        return Err(format!(
            "{} has {} bytes, above the input limit of {max}",
            path.display(),
            meta.len()
        ));
    }
    std::fs::read(&path).map_err(|e| format!("{}: {e}", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn textures_are_read_from_the_folder_and_paths_leaving_it_are_warnings() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("skin.png"), b"not decoded here").unwrap();
        let gltf = br#"{"asset":{"version":"2.0"},
            "materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}},
                         {"pbrMetallicRoughness":{"baseColorTexture":{"index":1}}},
                         {"pbrMetallicRoughness":{"baseColorTexture":{"index":7}}}],
            "textures":[{"source":0},{"source":1}],
            "images":[{"uri":"skin.png"},{"uri":"../skin.png"}]}"#;
        let looks = material_looks(gltf, Some(dir.path()), &InputLimits::default()).unwrap();
        assert_eq!(looks[0].image.as_deref(), Some(&b"not decoded here"[..]));
        assert_eq!(looks[0].warning, None);
        assert_eq!(looks[1].image, None);
        assert!(
            looks[1]
                .warning
                .as_deref()
                .unwrap()
                .contains("leaves the folder")
        );
        assert!(
            looks[2]
                .warning
                .as_deref()
                .unwrap()
                .contains("texture 7 does not exist")
        );
        // Above the input limit: a warning, nothing read.
        let small = InputLimits {
            max_file_bytes: 4,
            ..InputLimits::default()
        };
        let looks = material_looks(gltf, Some(dir.path()), &small).unwrap();
        assert!(
            looks[0]
                .warning
                .as_deref()
                .unwrap()
                .contains("above the input limit")
        );
    }
}
