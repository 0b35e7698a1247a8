//! The files a face file reads besides itself, so that no output can overwrite them: a glTF's
//! external buffers and images, an OBJ's material libraries and their texture maps.

use std::path::{Path, PathBuf};

use gltf::json;

use super::buffers::resolve_relative;
use super::glb::{GLB_MAGIC, split_glb};
use crate::input::limits::InputLimits;

/// Files `path` refers to that exist inside its folder: for a `.gltf`, `.glb` or `.vrm`, the
/// relative URIs of its buffers and images; for an `.obj`, its `mtllib` files and the `map_*`
/// textures they name. Nothing for other files, or for a file that cannot be read or parsed
/// (it is then refused when it is opened). References that would leave the folder are left
/// out: they are never read either. Regression (issue 36): `facebem rig face.gltf -o buf.rig`
/// overwrote the glTF's external buffer `buf.rig`, because only the main input was compared
/// with the output path.
///
/// ```
/// let dir = tempfile::tempdir().unwrap();
/// let gltf = dir.path().join("face.gltf");
/// std::fs::write(dir.path().join("face.bin"), [0u8; 12]).unwrap();
/// std::fs::write(&gltf, r#"{"asset":{"version":"2.0"},"buffers":[{"uri":"face.bin","byteLength":12}]}"#).unwrap();
/// let read = face_prep::input::files_read_by(&gltf);
/// assert_eq!(read.len(), 1);
/// assert!(read[0].ends_with("face.bin"));
/// ```
pub fn files_read_by(path: &Path) -> Vec<PathBuf> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    let base = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let Some(bytes) = read_bounded(path) else {
        return Vec::new();
    };
    let uris = match ext.as_str() {
        "gltf" | "glb" | "vrm" => gltf_uris(&bytes),
        "obj" => {
            let mut uris = Vec::new();
            for lib in obj_statements(&bytes, &["mtllib"]) {
                uris.push(lib.clone());
                let Ok(lib_path) = resolve_relative(&lib, Some(base)) else {
                    continue;
                };
                if let Some(mtl) = read_bounded(&lib_path) {
                    uris.extend(obj_statements(
                        &mtl,
                        &["map_", "bump", "disp", "decal", "refl"],
                    ));
                }
            }
            uris
        }
        _ => Vec::new(),
    };
    let mut out: Vec<PathBuf> = uris
        .iter()
        .filter(|u| !u.starts_with("data:"))
        .filter_map(|u| resolve_relative(u, Some(base)).ok())
        .collect();
    out.sort();
    out.dedup();
    out
}

/// The whole file if it is a regular file within the default input size limit.
fn read_bounded(path: &Path) -> Option<Vec<u8>> {
    let meta = std::fs::metadata(path).ok()?;
    if !meta.is_file() || meta.len() > InputLimits::default().max_file_bytes {
        return None;
    }
    std::fs::read(path).ok()
}

/// The URIs of a glTF's or GLB's buffers and images.
fn gltf_uris(bytes: &[u8]) -> Vec<String> {
    let json_bytes = if bytes.starts_with(GLB_MAGIC) {
        match split_glb(bytes) {
            Ok((json, _)) => json,
            Err(_) => return Vec::new(),
        }
    } else {
        bytes
    };
    let Ok(root) = json::deserialize::from_slice::<json::Root>(json_bytes) else {
        return Vec::new();
    };
    let buffers = root.buffers.iter().filter_map(|b| b.uri.clone());
    let images = root.images.iter().filter_map(|i| i.uri.clone());
    buffers.chain(images).collect()
}

/// The last word of every line of an OBJ or MTL text whose keyword starts with one of
/// `keywords` (a texture statement's options come before its file name; file names with
/// spaces are not resolved).
fn obj_statements(bytes: &[u8], keywords: &[&str]) -> Vec<String> {
    let text = String::from_utf8_lossy(bytes);
    text.lines()
        .filter_map(|line| {
            let mut words = line.split_whitespace();
            let keyword = words.next()?;
            if !keywords.iter().any(|k| keyword.starts_with(k)) {
                return None;
            }
            words.last().map(str::to_string)
        })
        .collect()
}
