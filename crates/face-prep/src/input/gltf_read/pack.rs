//! A `.gltf` (JSON, its buffers and images in separate files or `data:` URIs) packed into one
//! GLB: every buffer placed one after the other (8-aligned) in the binary chunk, its buffer
//! views re-pointed, every image with a URI moved into a buffer view of its own. Nothing else
//! of the JSON changes (unknown members, extensions and extras are kept as they are), and every
//! buffer view's bytes are the same bytes. Files are read as the reader reads them: inside the
//! glTF's folder, regular files only, within the input limits.

use std::path::Path;

use serde_json::Value;

use super::buffers::{load_buffer, resolve_relative};
use super::glb::{CHUNK_BIN, CHUNK_JSON, GLB_MAGIC};
use crate::error::GltfError;
use crate::input::limits::InputLimits;

/// The `.gltf` document `json` (read from a file in `folder`) as GLB bytes; a GLB is returned
/// as it is.
///
/// ```
/// use face_prep::gltf_read::{pack_glb, split_glb};
/// let dir = tempfile::tempdir().unwrap();
/// std::fs::write(dir.path().join("a.bin"), [1u8, 2, 3, 4]).unwrap();
/// let json = br#"{"asset":{"version":"2.0"},"buffers":[{"uri":"a.bin","byteLength":4}],
///   "bufferViews":[{"buffer":0,"byteLength":4}]}"#;
/// let glb = pack_glb(json, dir.path(), &Default::default()).unwrap();
/// let (json, bin) = split_glb(&glb).unwrap();
/// let root: serde_json::Value = serde_json::from_slice(json).unwrap();
/// assert_eq!(root["buffers"][0].get("uri"), None);
/// assert_eq!(&bin.unwrap()[..4], &[1, 2, 3, 4]);
/// ```
pub fn pack_glb(json: &[u8], folder: &Path, limits: &InputLimits) -> Result<Vec<u8>, GltfError> {
    if json.starts_with(GLB_MAGIC) {
        return Ok(json.to_vec());
    }
    let mut root: Value =
        serde_json::from_slice(json).map_err(|e| GltfError::Json(e.to_string()))?;
    let max = limits.max_file_bytes as usize;
    let mut bin: Vec<u8> = Vec::new();
    let append = |bin: &mut Vec<u8>, data: &[u8]| -> Result<usize, String> {
        while !bin.len().is_multiple_of(8) {
            bin.push(0);
        }
        if bin.len().saturating_add(data.len()) > max {
            return Err(format!(
                "the packed buffers exceed the input limit of {max} bytes"
            ));
        }
        let at = bin.len();
        bin.extend_from_slice(data);
        Ok(at)
    };
    // Buffers, in order.
    let buffers = root["buffers"].as_array().cloned().unwrap_or_default();
    let mut starts = Vec::with_capacity(buffers.len());
    for (index, buffer) in buffers.iter().enumerate() {
        let uri = buffer["uri"].as_str();
        let err = |reason: String| GltfError::Buffer {
            index,
            uri: uri.unwrap_or("<none>").chars().take(60).collect(),
            reason,
        };
        let len = buffer["byteLength"]
            .as_u64()
            .filter(|&l| l <= limits.max_file_bytes)
            .ok_or_else(|| err("byteLength missing or above the input limit".into()))?;
        let data = load_buffer(uri, index, len as usize, None, Some(folder)).map_err(err)?;
        starts.push(append(&mut bin, &data).map_err(err)?);
    }
    // Buffer views: into the one buffer.
    if let Some(views) = root["bufferViews"].as_array_mut() {
        for (index, view) in views.iter_mut().enumerate() {
            let start = (view["buffer"].as_u64())
                .and_then(|b| starts.get(b as usize).copied())
                .ok_or_else(|| invalid("bufferView", index, "its buffer does not exist"))?;
            let offset = view["byteOffset"].as_u64().unwrap_or(0) as usize;
            view["buffer"] = Value::from(0);
            view["byteOffset"] = Value::from(start + offset);
        }
    }
    // Images with a URI: into buffer views of their own.
    let mut new_views = Vec::new();
    let view_count = root["bufferViews"].as_array().map_or(0, Vec::len);
    if let Some(images) = root["images"].as_array_mut() {
        for (index, image) in images.iter_mut().enumerate() {
            let Some(uri) = image["uri"].as_str().map(str::to_owned) else {
                continue;
            };
            let (data, mime) = image_bytes(&uri, folder, limits)
                .map_err(|reason| invalid("image", index, reason))?;
            let at = append(&mut bin, &data).map_err(|reason| invalid("image", index, reason))?;
            let object = image
                .as_object_mut()
                .ok_or_else(|| invalid("image", index, "not an object"))?;
            object.remove("uri");
            object.insert(
                "bufferView".into(),
                Value::from(view_count + new_views.len()),
            );
            object.insert("mimeType".into(), Value::from(mime));
            new_views.push(serde_json::json!({
                "buffer": 0, "byteOffset": at, "byteLength": data.len()
            }));
        }
    }
    if !new_views.is_empty() {
        match root["bufferViews"].as_array_mut() {
            Some(views) => views.extend(new_views),
            None => root["bufferViews"] = Value::from(new_views),
        }
    }
    if bin.is_empty() && buffers.is_empty() {
        if let Some(object) = root.as_object_mut() {
            object.remove("buffers");
        }
    } else {
        root["buffers"] = serde_json::json!([{ "byteLength": bin.len() }]);
    }
    let json = serde_json::to_vec(&root).map_err(|e| GltfError::Json(e.to_string()))?;
    Ok(glb(json, bin))
}

fn invalid(what: &'static str, index: usize, reason: impl Into<String>) -> GltfError {
    GltfError::Invalid {
        what,
        index,
        reason: reason.into(),
    }
}

/// An image's bytes and MIME type, from a `data:` URI or a PNG or JPEG file in `folder`.
fn image_bytes(
    uri: &str,
    folder: &Path,
    limits: &InputLimits,
) -> Result<(Vec<u8>, String), String> {
    if let Some(rest) = uri.strip_prefix("data:") {
        let (mime, payload) = rest
            .split_once(";base64,")
            .ok_or("data URI is not base64-encoded")?;
        return Ok((super::decode_base64(payload)?, mime.to_owned()));
    }
    let path = resolve_relative(uri, Some(folder))?;
    let ext = (path.extension().and_then(|e| e.to_str()))
        .unwrap_or("")
        .to_ascii_lowercase();
    let mime = match ext.as_str() {
        "png" => "image/png",
        "jpg" | "jpeg" => "image/jpeg",
        _ => {
            return Err(format!(
                "{uri:?} is neither PNG nor JPEG (what a GLB may hold)"
            ));
        }
    };
    let data = crate::input::limits::read_input_file(&path, limits).map_err(|e| e.to_string())?;
    Ok((data, mime.to_owned()))
}

/// The GLB container of `json` and `bin` (chunks padded to 4 bytes: spaces, zeros).
fn glb(mut json: Vec<u8>, mut bin: Vec<u8>) -> Vec<u8> {
    while !json.len().is_multiple_of(4) {
        json.push(b' ');
    }
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let bin_chunk = if bin.is_empty() { 0 } else { 8 + bin.len() };
    let total = 12 + 8 + json.len() + bin_chunk;
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(GLB_MAGIC);
    out.extend(2u32.to_le_bytes());
    out.extend((total as u32).to_le_bytes());
    out.extend((json.len() as u32).to_le_bytes());
    out.extend(CHUNK_JSON.to_le_bytes());
    out.extend(json);
    if !bin.is_empty() {
        out.extend((bin.len() as u32).to_le_bytes());
        out.extend(CHUNK_BIN.to_le_bytes());
        out.extend(bin);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_buffers_and_a_png_file_become_one_binary_chunk() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("a.bin"), [1u8, 2, 3]).unwrap();
        std::fs::write(dir.path().join("b.bin"), [9u8, 8, 7, 6, 5]).unwrap();
        std::fs::write(dir.path().join("t.png"), b"\x89PNG....").unwrap();
        let json = br#"{"asset":{"version":"2.0"},"extras":{"keep":1},
            "buffers":[{"uri":"a.bin","byteLength":3},{"uri":"b.bin","byteLength":5}],
            "bufferViews":[{"buffer":1,"byteOffset":1,"byteLength":3},{"buffer":0,"byteLength":3}],
            "images":[{"uri":"t.png"}]}"#;
        let glb = pack_glb(json, dir.path(), &InputLimits::default()).unwrap();
        let (json, bin) = super::super::split_glb(&glb).unwrap();
        let (root, bin): (Value, &[u8]) = (serde_json::from_slice(json).unwrap(), bin.unwrap());
        assert_eq!(root["extras"]["keep"], 1);
        assert_eq!(root["buffers"].as_array().unwrap().len(), 1);
        let view = |k: usize| {
            let v = &root["bufferViews"][k];
            assert_eq!(v["buffer"], 0);
            let o = v["byteOffset"].as_u64().unwrap() as usize;
            bin[o..o + v["byteLength"].as_u64().unwrap() as usize].to_vec()
        };
        assert_eq!(view(0), [8, 7, 6]);
        assert_eq!(view(1), [1, 2, 3]);
        assert_eq!(root["images"][0]["bufferView"], 2);
        assert_eq!(root["images"][0]["mimeType"], "image/png");
        assert_eq!(view(2), b"\x89PNG....");
    }

    #[test]
    fn files_outside_the_folder_and_unknown_images_are_refused() {
        let dir = tempfile::tempdir().unwrap();
        let limits = InputLimits::default();
        let outside =
            br#"{"asset":{"version":"2.0"},"buffers":[{"uri":"../x.bin","byteLength":1}]}"#;
        let err = pack_glb(outside, dir.path(), &limits)
            .unwrap_err()
            .to_string();
        assert!(err.contains("leaves the folder"), "{err}");
        std::fs::write(dir.path().join("t.bmp"), b"BM").unwrap();
        let bmp = br#"{"asset":{"version":"2.0"},"images":[{"uri":"t.bmp"}]}"#;
        let err = pack_glb(bmp, dir.path(), &limits).unwrap_err().to_string();
        assert!(err.contains("neither PNG nor JPEG"), "{err}");
        let view = br#"{"asset":{"version":"2.0"},"bufferViews":[{"buffer":3,"byteLength":1}]}"#;
        let err = pack_glb(view, dir.path(), &limits).unwrap_err().to_string();
        assert!(err.contains("bufferView 0"), "{err}");
    }
}
