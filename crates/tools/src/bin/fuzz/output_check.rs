//! Checks of what a case wrote: every number of an OBJ's `v`/`vt`/`vn` lines is finite, every
//! FLOAT (componentType 5126) of a glTF/GLB's accessors is finite (GLB BIN chunk, data URI or
//! external `.bin`), a muscle file's sizes and element indices are integers, and a rig file
//! re-opens with `facebem::input::open`. A PNG (`sheet`) is an image without numbers to check.

use std::path::Path;

/// The problems of the files under `dir` (recursively, symlinks not followed), leaving out the
/// inputs the case wrote there that are still unchanged (`inputs`: name and bytes).
pub(crate) fn check_dir(dir: &Path, inputs: &[(&str, &[u8])]) -> Vec<String> {
    let mut problems = Vec::new();
    walk(dir, dir, inputs, 0, &mut problems);
    problems
}

fn walk(root: &Path, dir: &Path, inputs: &[(&str, &[u8])], depth: usize, out: &mut Vec<String>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        let Ok(meta) = std::fs::symlink_metadata(&path) else {
            continue;
        };
        if meta.is_dir() && depth < 4 {
            walk(root, &path, inputs, depth + 1, out);
            continue;
        }
        if !meta.is_file() {
            continue;
        }
        let rel = path
            .strip_prefix(root)
            .map(|p| p.to_string_lossy().into_owned())
            .unwrap_or_default();
        let Ok(bytes) = std::fs::read(&path) else {
            out.push(format!("{rel}: written but unreadable"));
            continue;
        };
        if inputs
            .iter()
            .any(|(name, b)| *name == rel && *b == bytes.as_slice())
        {
            continue;
        }
        if let Err(e) = check_file(&path, &bytes) {
            out.push(format!("{rel}: {e}"));
        }
    }
}

/// Checks one output file by its extension (unknown extensions pass).
pub(crate) fn check_file(path: &Path, bytes: &[u8]) -> Result<(), String> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    match ext.as_str() {
        "obj" => check_obj(bytes),
        "gltf" | "glb" => check_gltf(bytes, path.parent()),
        "muscles" => check_muscles(bytes),
        "rig" => match facebem::input::open(path) {
            Ok(facebem::input::Opened::Model(_)) => Ok(()),
            Ok(facebem::input::Opened::Face { .. }) => {
                Err("the rig file written opens as a face mesh".into())
            }
            Err(e) => Err(format!("the rig file written does not re-open: {e}")),
        },
        _ => Ok(()),
    }
}

/// Every number of the `v`, `vt` and `vn` lines parses and is finite.
pub(crate) fn check_obj(bytes: &[u8]) -> Result<(), String> {
    let text = String::from_utf8_lossy(bytes);
    for (i, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        let Some(kind @ ("v" | "vt" | "vn")) = words.next() else {
            continue;
        };
        for w in words {
            match w.parse::<f64>() {
                Ok(x) if x.is_finite() => {}
                Ok(_) => return Err(format!("line {}: non-finite {kind}: {line:.120}", i + 1)),
                Err(_) => return Err(format!("line {}: {kind} not a number: {line:.120}", i + 1)),
            }
        }
    }
    Ok(())
}

/// Every line of a `[Size]`, `[Data]`, `[BackSize]` or `[BackData]` block is an integer.
pub(crate) fn check_muscles(bytes: &[u8]) -> Result<(), String> {
    let text = String::from_utf8_lossy(bytes);
    let mut numeric = false;
    for (i, line) in text.lines().enumerate() {
        let t = line.trim();
        if t.starts_with('[') {
            numeric = matches!(t, "[Size]" | "[Data]" | "[BackSize]" | "[BackData]");
        } else if numeric && !t.is_empty() && t.parse::<u64>().is_err() {
            return Err(format!("line {}: not an index: {t:.80}", i + 1));
        }
    }
    Ok(())
}

/// The JSON and binary chunks of a glTF: a GLB's two chunks, or a `.gltf`'s text.
fn split_glb(bytes: &[u8]) -> Result<(&[u8], Option<&[u8]>), String> {
    if !bytes.starts_with(b"glTF") {
        return Ok((bytes, None));
    }
    let word = |at: usize| -> Result<usize, String> {
        let b = bytes
            .get(at..at + 4)
            .ok_or_else(|| format!("GLB cut short at byte {at}"))?;
        Ok(u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize)
    };
    if word(8)? != bytes.len() {
        return Err(format!(
            "GLB header length {} for {} bytes",
            word(8)?,
            bytes.len()
        ));
    }
    let jlen = word(12)?;
    if bytes.get(16..20) != Some(b"JSON") {
        return Err("GLB's first chunk is not JSON".into());
    }
    let json = bytes.get(20..20 + jlen).ok_or("GLB JSON chunk cut short")?;
    let at = 20 + jlen;
    if at == bytes.len() {
        return Ok((json, None));
    }
    let blen = word(at)?;
    if bytes.get(at + 4..at + 8) != Some(b"BIN\0") {
        return Err("GLB's second chunk is not BIN".into());
    }
    let bin = bytes
        .get(at + 8..at + 8 + blen)
        .ok_or("GLB BIN chunk cut short")?;
    Ok((json, Some(bin)))
}

/// Every FLOAT accessor (and sparse values), every `min`/`max` and every mesh `weights` entry
/// is finite.
pub(crate) fn check_gltf(bytes: &[u8], dir: Option<&Path>) -> Result<(), String> {
    use serde_json::Value;
    let (json, bin) = split_glb(bytes)?;
    let doc: Value = serde_json::from_slice(json).map_err(|e| format!("glTF JSON: {e}"))?;
    let list = |key: &str| doc.get(key).and_then(Value::as_array).cloned();
    let buffers: Vec<Vec<u8>> = list("buffers")
        .unwrap_or_default()
        .iter()
        .enumerate()
        .map(|(i, b)| buffer_bytes(i, b, bin, dir))
        .collect::<Result<_, _>>()?;
    let views = list("bufferViews").unwrap_or_default();
    for (i, acc) in list("accessors").unwrap_or_default().iter().enumerate() {
        for key in ["min", "max"] {
            if let Some(v) = acc.get(key).and_then(Value::as_array)
                && v.iter().any(|x| !x.as_f64().is_some_and(f64::is_finite))
            {
                return Err(format!("accessor {i}: {key} is not finite: {v:?}"));
            }
        }
        if acc.get("componentType").and_then(Value::as_u64) != Some(5126) {
            continue;
        }
        let n = match acc.get("type").and_then(Value::as_str) {
            Some("SCALAR") => 1,
            Some("VEC2") => 2,
            Some("VEC3") => 3,
            Some("VEC4" | "MAT2") => 4,
            Some("MAT3") => 9,
            Some("MAT4") => 16,
            other => return Err(format!("accessor {i}: type {other:?}")),
        };
        let count = acc.get("count").and_then(Value::as_u64).unwrap_or(0) as usize;
        if let Some(view) = acc.get("bufferView") {
            let offset = acc.get("byteOffset").and_then(Value::as_u64).unwrap_or(0);
            check_floats(&buffers, &views, view, offset, count, n)
                .map_err(|e| format!("accessor {i}: {e}"))?;
        }
        if let Some(sparse) = acc.get("sparse") {
            let scount = sparse.get("count").and_then(Value::as_u64).unwrap_or(0) as usize;
            let values = sparse.get("values").ok_or("sparse without values")?;
            let view = values.get("bufferView").ok_or("sparse without a view")?;
            let offset = values
                .get("byteOffset")
                .and_then(Value::as_u64)
                .unwrap_or(0);
            check_floats(&buffers, &views, view, offset, scount, n)
                .map_err(|e| format!("accessor {i} (sparse values): {e}"))?;
        }
    }
    for (i, mesh) in list("meshes").unwrap_or_default().iter().enumerate() {
        if let Some(w) = mesh.get("weights").and_then(Value::as_array)
            && w.iter().any(|x| !x.as_f64().is_some_and(f64::is_finite))
        {
            return Err(format!("mesh {i}: weights are not finite"));
        }
    }
    Ok(())
}

/// The bytes of buffer `i`: the GLB's BIN chunk, a base64 data URI or a file next to the glTF.
fn buffer_bytes(
    i: usize,
    b: &serde_json::Value,
    bin: Option<&[u8]>,
    dir: Option<&Path>,
) -> Result<Vec<u8>, String> {
    match b.get("uri").and_then(serde_json::Value::as_str) {
        None => Ok(bin
            .ok_or(format!("buffer {i} has no uri and there is no BIN chunk"))?
            .to_vec()),
        Some(uri) if uri.starts_with("data:") => {
            let (_, data) = uri
                .split_once(";base64,")
                .ok_or(format!("buffer {i}: data URI not base64"))?;
            facebem::face_prep::gltf_read::decode_base64(data)
                .map_err(|e| format!("buffer {i}: {e}"))
        }
        Some(uri) => {
            let dir = dir.ok_or(format!("buffer {i}: external {uri:?} without a folder"))?;
            std::fs::read(dir.join(uri)).map_err(|e| format!("buffer {i} {uri:?}: {e}"))
        }
    }
}

/// Reads `count` elements of `n` f32 each through buffer view `view` and checks they are
/// finite.
fn check_floats(
    buffers: &[Vec<u8>],
    views: &[serde_json::Value],
    view: &serde_json::Value,
    offset: u64,
    count: usize,
    n: usize,
) -> Result<(), String> {
    use serde_json::Value;
    let vi = view.as_u64().ok_or("bufferView is not an index")? as usize;
    let v = views.get(vi).ok_or(format!("no bufferView {vi}"))?;
    let bi = v.get("buffer").and_then(Value::as_u64).unwrap_or(u64::MAX) as usize;
    let buf = buffers.get(bi).ok_or(format!("no buffer {bi}"))?;
    let start = v.get("byteOffset").and_then(Value::as_u64).unwrap_or(0) as usize;
    let len = v.get("byteLength").and_then(Value::as_u64).unwrap_or(0) as usize;
    let data = buf
        .get(start..start.saturating_add(len))
        .ok_or(format!("bufferView {vi} outside buffer {bi}"))?;
    let stride = v
        .get("byteStride")
        .and_then(Value::as_u64)
        .map_or(4 * n, |s| s as usize);
    for k in 0..count {
        let at = offset as usize + k * stride;
        let elem = data
            .get(at..at + 4 * n)
            .ok_or(format!("element {k} outside bufferView {vi}"))?;
        for (c, f) in elem.chunks_exact(4).enumerate() {
            let x = f32::from_le_bytes([f[0], f[1], f[2], f[3]]);
            if !x.is_finite() {
                return Err(format!("element {k} component {c} is {x}"));
            }
        }
    }
    Ok(())
}

/// The words of a program's standard output that are non-finite numbers as Rust prints them
/// (`NaN`, `inf`, `-inf`), e.g. in `info`'s sizes.
pub(crate) fn non_finite_words(text: &str) -> Vec<String> {
    text.split(|c: char| c.is_whitespace() || ",;:()[]=".contains(c))
        .filter(|w| matches!(*w, "NaN" | "-NaN" | "inf" | "-inf" | "+inf"))
        .map(str::to_owned)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_non_finite_numbers() {
        assert!(check_obj(b"v 1 2 3\nvt 0.5 0.5\nf 1 1 1\n").is_ok());
        assert!(check_obj(b"v 1 2 3\nvt NaN 0.5\n").is_err());
        assert!(check_obj(b"vn inf 0 0\n").is_err());
        assert!(check_muscles(b"[Name]\nA\n[Size]\n1\n[Data]\n7\n").is_ok());
        assert!(check_muscles(b"[Name]\nA\n[Size]\n1\n[Data]\nNaN\n").is_err());
        assert_eq!(
            facebem::face_prep::gltf_read::decode_base64("AAAAAA==").unwrap(),
            vec![0, 0, 0, 0]
        );
        let nan = facebem::face_prep::gltf_read::decode_base64("AADAfw==").unwrap();
        assert!(f32::from_le_bytes([nan[0], nan[1], nan[2], nan[3]]).is_nan());
        assert_eq!(non_finite_words("size: NaN mm, inf.obj"), vec!["NaN"]);
    }
}
