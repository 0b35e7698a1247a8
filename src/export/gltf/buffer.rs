//! The binary side of a glTF file: buffer views and accessors ([`Builder`]), the GLB
//! container and base64 for embedded buffers.

use glam::DVec3;
use serde_json::{Value, json};

use super::GltfExportError;

const ARRAY_BUFFER: u32 = 34962;
const ELEMENT_ARRAY_BUFFER: u32 = 34963;
const FLOAT: u32 = 5126;
const UNSIGNED_INT: u32 = 5125;

#[derive(Default)]
pub(super) struct Builder {
    pub(super) bin: Vec<u8>,
    pub(super) views: Vec<Value>,
    pub(super) accessors: Vec<Value>,
}

impl Builder {
    pub(super) fn view(&mut self, bytes: &[u8], target: Option<u32>) -> usize {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        let mut v = json!({ "buffer": 0, "byteOffset": self.bin.len(), "byteLength": bytes.len() });
        if let Some(t) = target {
            v["target"] = json!(t);
        }
        self.bin.extend_from_slice(bytes);
        self.views.push(v);
        self.views.len() - 1
    }

    pub(super) fn vec3_accessor(
        &mut self,
        what: &str,
        data: &[DVec3],
        with_bounds: bool,
    ) -> Result<usize, GltfExportError> {
        let mut bytes = Vec::with_capacity(data.len() * 12);
        let mut min = [f32::INFINITY; 3];
        let mut max = [f32::NEG_INFINITY; 3];
        for (vertex, p) in data.iter().enumerate() {
            let q = p.as_vec3().to_array();
            if !q.iter().all(|c| c.is_finite()) {
                return Err(GltfExportError::NonFinite {
                    what: what.to_string(),
                    vertex,
                });
            }
            for i in 0..3 {
                min[i] = min[i].min(q[i]);
                max[i] = max[i].max(q[i]);
                bytes.extend_from_slice(&q[i].to_le_bytes());
            }
        }
        let view = self.view(&bytes, Some(ARRAY_BUFFER));
        let mut a = json!({
            "bufferView": view, "componentType": FLOAT, "count": data.len(), "type": "VEC3",
        });
        if with_bounds {
            a["min"] = json!(min);
            a["max"] = json!(max);
        }
        self.accessors.push(a);
        Ok(self.accessors.len() - 1)
    }

    /// A VEC2 float accessor (texture coordinates); a NaN or infinity is an error.
    pub(super) fn vec2_accessor(
        &mut self,
        what: &str,
        data: &[[f32; 2]],
    ) -> Result<usize, GltfExportError> {
        check_finite(what, data.iter().map(|t| t.iter().all(|c| c.is_finite())))?;
        let bytes: Vec<u8> = data
            .iter()
            .flatten()
            .flat_map(|x| x.to_le_bytes())
            .collect();
        let view = self.view(&bytes, Some(ARRAY_BUFFER));
        self.accessors.push(json!({
            "bufferView": view, "componentType": FLOAT, "count": data.len(), "type": "VEC2",
        }));
        Ok(self.accessors.len() - 1)
    }

    pub(super) fn indices_accessor(&mut self, triangles: &[[u32; 3]]) -> usize {
        let bytes: Vec<u8> = triangles
            .iter()
            .flatten()
            .flat_map(|i| i.to_le_bytes())
            .collect();
        let view = self.view(&bytes, Some(ELEMENT_ARRAY_BUFFER));
        self.accessors.push(json!({
            "bufferView": view, "componentType": UNSIGNED_INT, "count": triangles.len() * 3,
            "type": "SCALAR",
        }));
        self.accessors.len() - 1
    }

    /// A SCALAR float accessor (animation times and weights); a NaN or infinity is an error.
    pub(super) fn scalar_accessor(
        &mut self,
        what: &str,
        data: &[f32],
        with_bounds: bool,
    ) -> Result<usize, GltfExportError> {
        check_finite(what, data.iter().map(|x| x.is_finite()))?;
        let bytes: Vec<u8> = data.iter().flat_map(|x| x.to_le_bytes()).collect();
        let view = self.view(&bytes, None);
        let mut a = json!({
            "bufferView": view, "componentType": FLOAT, "count": data.len(), "type": "SCALAR",
        });
        if with_bounds {
            let min = data.iter().copied().fold(f32::INFINITY, f32::min);
            let max = data.iter().copied().fold(f32::NEG_INFINITY, f32::max);
            a["min"] = json!([min]);
            a["max"] = json!([max]);
        }
        self.accessors.push(a);
        Ok(self.accessors.len() - 1)
    }
}

/// `Err(GltfExportError::NonFinite)` naming the first element of `what` that is not finite
/// (`finite`: per element, whether all its components are).
fn check_finite(what: &str, finite: impl Iterator<Item = bool>) -> Result<(), GltfExportError> {
    let mut finite = finite;
    match finite.position(|ok| !ok) {
        Some(vertex) => Err(GltfExportError::NonFinite {
            what: what.to_string(),
            vertex,
        }),
        None => Ok(()),
    }
}

/// Binary glTF container: 12-byte header, JSON chunk (space-padded), BIN chunk (zero-padded).
pub(super) fn glb(root: &Value, bin: &[u8]) -> Vec<u8> {
    let mut json = serde_json::to_vec(root).unwrap_or_default();
    while !json.len().is_multiple_of(4) {
        json.push(b' ');
    }
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(json.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&json);
    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(bin);
    out
}

/// Standard base64 (RFC 4648, with padding) for the embedded buffer's data URI.
pub(super) fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            chunk.get(1).copied().unwrap_or(0),
            chunk.get(2).copied().unwrap_or(0),
        ];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(ALPHABET[((n >> (18 - 6 * k)) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn accessors_refuse_non_finite_numbers() {
        let mut b = Builder::default();
        let err = b
            .vec2_accessor("texture coordinates", &[[0.0, 1.0], [f32::NAN, 0.5]])
            .unwrap_err();
        assert!(
            matches!(&err, GltfExportError::NonFinite { what, vertex: 1 } if what == "texture coordinates"),
            "{err}"
        );
        let err = b
            .scalar_accessor("times", &[0.0, f32::INFINITY], true)
            .unwrap_err();
        assert!(
            matches!(err, GltfExportError::NonFinite { vertex: 1, .. }),
            "{err}"
        );
        let err = b
            .vec3_accessor("normals", &[DVec3::new(0.0, 0.0, f64::NAN)], false)
            .unwrap_err();
        assert!(
            matches!(err, GltfExportError::NonFinite { vertex: 0, .. }),
            "{err}"
        );
        // Nothing was written by the refused calls.
        assert!(b.bin.is_empty() && b.accessors.is_empty());
        assert_eq!(b.vec2_accessor("uv", &[[0.25, 0.5]]).unwrap(), 0);
    }

    #[test]
    fn base64_matches_rfc4648_vectors() {
        let cases = [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ];
        for (plain, encoded) in cases {
            assert_eq!(base64(plain.as_bytes()), encoded);
        }
    }
}
