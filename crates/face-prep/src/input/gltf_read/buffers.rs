//! Loading a buffer's bytes: the GLB binary chunk, a base64 `data:` URI, or a file inside the
//! glTF's own folder (nothing that could leave it, nothing but a regular file).

use std::path::{Path, PathBuf};

/// Loads a buffer's bytes (exactly `len`) from the GLB chunk, a data URI or a file in `base`.
pub(super) fn load_buffer(
    uri: Option<&str>,
    index: usize,
    len: usize,
    blob: Option<&[u8]>,
    base: Option<&Path>,
) -> Result<Vec<u8>, String> {
    let Some(uri) = uri else {
        let blob = match (index, blob) {
            (0, Some(b)) => b,
            (0, None) => return Err("no uri and the file has no GLB binary chunk".into()),
            _ => return Err("no uri (only buffer 0 may be the GLB binary chunk)".into()),
        };
        return blob.get(..len).map(<[u8]>::to_vec).ok_or_else(|| {
            format!(
                "byteLength {len} exceeds the GLB binary chunk's {} bytes",
                blob.len()
            )
        });
    };
    if let Some(rest) = uri.strip_prefix("data:") {
        let (_, payload) = rest
            .split_once(";base64,")
            .ok_or("data URI is not base64-encoded")?;
        let data = decode_base64(payload)?;
        if data.len() < len {
            return Err(format!(
                "data URI holds {} bytes, byteLength is {len}",
                data.len()
            ));
        }
        return Ok(data[..len].to_vec());
    }
    let path = resolve_relative(uri, base)?;
    read_prefix(&path, len)
}

/// Resolves a relative URI inside `base`, refusing anything that could leave it.
pub(super) fn resolve_relative(uri: &str, base: Option<&Path>) -> Result<PathBuf, String> {
    const ONLY: &str = "only data: URIs and relative paths inside the glTF's folder are read";
    let scheme_end = uri.find(':');
    let first_sep = uri.find(['/', '\\', '?', '#']);
    if scheme_end.is_some_and(|c| first_sep.is_none_or(|s| c < s)) {
        return Err(format!("has a scheme or drive; {ONLY}"));
    }
    let decoded = percent_decode(uri)?;
    if decoded.starts_with('/') || decoded.contains('\\') || decoded.contains('\0') {
        return Err(format!("is absolute or has backslashes; {ONLY}"));
    }
    if decoded.split('/').any(|c| c == "..") {
        return Err(format!("leaves the folder ('..'); {ONLY}"));
    }
    let base =
        base.ok_or("refers to an external file, but the document was given without its folder")?;
    let base = if base.as_os_str().is_empty() {
        Path::new(".")
    } else {
        base
    };
    let base = std::fs::canonicalize(base)
        .map_err(|e| format!("cannot resolve the glTF's folder: {e}"))?;
    let path = std::fs::canonicalize(base.join(&decoded))
        .map_err(|e| format!("cannot open {decoded:?}: {e}"))?;
    if !path.starts_with(&base) {
        return Err(format!(
            "resolves (through a symlink) outside the folder; {ONLY}"
        ));
    }
    Ok(path)
}

/// Reads the first `len` bytes of a regular file (anything else is refused unopened).
fn read_prefix(path: &Path, len: usize) -> Result<Vec<u8>, String> {
    use std::io::Read;
    let meta =
        std::fs::metadata(path).map_err(|e| format!("cannot open {}: {e}", path.display()))?;
    if !meta.is_file() {
        return Err(format!("{} is not a regular file", path.display()));
    }
    if meta.len() < len as u64 {
        return Err(format!(
            "file {} has {} bytes, byteLength is {len}",
            path.display(),
            meta.len()
        ));
    }
    let file =
        std::fs::File::open(path).map_err(|e| format!("cannot open {}: {e}", path.display()))?;
    let mut data = Vec::with_capacity(len);
    file.take(len as u64)
        .read_to_end(&mut data)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    if data.len() < len {
        return Err(format!(
            "file {} ended after {} bytes, byteLength is {len}",
            path.display(),
            data.len()
        ));
    }
    Ok(data)
}

/// RFC 3986 percent-decoding to UTF-8; a malformed escape or invalid UTF-8 is an error.
fn percent_decode(s: &str) -> Result<String, String> {
    let b = s.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        if b[i] == b'%' {
            let hex = b
                .get(i + 1..i + 3)
                .and_then(|h| std::str::from_utf8(h).ok())
                .and_then(|h| u8::from_str_radix(h, 16).ok())
                .ok_or_else(|| format!("malformed percent escape at byte {i}"))?;
            out.push(hex);
            i += 3;
        } else {
            out.push(b[i]);
            i += 1;
        }
    }
    String::from_utf8(out).map_err(|_| "percent-decodes to invalid UTF-8".to_owned())
}

/// Standard base64 (RFC 4648, `=` padding optional, whitespace not allowed), as in glTF
/// `data:` URIs.
///
/// ```
/// use face_prep::gltf_read::decode_base64;
/// assert_eq!(decode_base64("Zm9vYg==").unwrap(), b"foob");
/// assert!(decode_base64("Zm9v!").is_err());
/// ```
pub fn decode_base64(s: &str) -> Result<Vec<u8>, String> {
    let s = s.trim_end_matches('=');
    let mut out = Vec::with_capacity(s.len() / 4 * 3 + 3);
    let (mut acc, mut bits) = (0u32, 0u32);
    for (i, c) in s.bytes().enumerate() {
        let v = match c {
            b'A'..=b'Z' => c - b'A',
            b'a'..=b'z' => c - b'a' + 26,
            b'0'..=b'9' => c - b'0' + 52,
            b'+' | b'-' => 62,
            b'/' | b'_' => 63,
            _ => return Err(format!("invalid base64 character at position {i}")),
        };
        acc = (acc << 6) | u32::from(v);
        bits += 6;
        if bits >= 8 {
            bits -= 8;
            out.push((acc >> bits) as u8);
            acc &= (1 << bits) - 1;
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_round_trip_of_every_length() {
        let table = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        for n in 0..10usize {
            let data: Vec<u8> = (0..n as u8).map(|i| i.wrapping_mul(37) ^ 0xA5).collect();
            let mut enc = String::new();
            for chunk in data.chunks(3) {
                let b = [
                    chunk[0],
                    *chunk.get(1).unwrap_or(&0),
                    *chunk.get(2).unwrap_or(&0),
                ];
                let v = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
                for k in 0..=chunk.len() {
                    enc.push(table[(v >> (18 - 6 * k) & 63) as usize] as char);
                }
            }
            assert_eq!(decode_base64(&enc).unwrap(), data, "{enc}");
        }
        assert!(decode_base64("ab$d").is_err());
    }

    #[test]
    fn uris_that_leave_the_folder_are_refused_before_any_file_access() {
        let base = Path::new("/nonexistent-folder");
        for uri in [
            "file:///etc/passwd",
            "/etc/passwd",
            "../secret.bin",
            "a/../../secret.bin",
            "%2e%2e/secret.bin",
            "C:\\x.bin",
            "http://example.com/x.bin",
            "%FF.bin",
            "a\\b.bin",
        ] {
            let err = resolve_relative(uri, Some(base)).unwrap_err();
            assert!(!err.contains("cannot resolve"), "{uri}: {err}");
        }
    }
}
