//! The binary side of a glTF file: buffer views and accessors ([`Builder`]), the GLB
//! container and base64 for embedded buffers.

use glam::DVec3;
use serde_json::{Value, json};

use super::GltfExportError;

const ARRAY_BUFFER: u32 = 34962;
const ELEMENT_ARRAY_BUFFER: u32 = 34963;
const FLOAT: u32 = 5126;
const UNSIGNED_INT: u32 = 5125;
const UNSIGNED_SHORT: u32 = 5123;

/// How a buffer view is compressed with `EXT_meshopt_compression` ([`super::meshopt`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Codec {
    /// Mode ATTRIBUTES: elements of `stride` bytes; with `exp_bits`, f32 data through the
    /// EXPONENTIAL filter keeping that many mantissa bits.
    Attributes {
        stride: usize,
        exp_bits: Option<i32>,
    },
    /// Mode TRIANGLES: triangle-list indices of `stride` (2 or 4) bytes.
    Triangles { stride: usize },
    /// Mode INDICES: other indices (a sparse accessor's) of `stride` (2 or 4) bytes.
    Indices { stride: usize },
    /// Not compressed (an embedded image: PNG and JPEG are compressed already).
    Raw,
}

// Mantissa bits `--compress` keeps (EXPONENTIAL filter, one exponent per axis of a view, see
// `super::meshopt`): a value is within 2^(1−K) of its axis's largest magnitude.

/// Neutral positions: within 2⁻¹⁹ of the largest coordinate, 0.6 µm on a 0.3 m head.
pub(super) const POSITION_BITS: i32 = 20;
/// Morph-target position deltas: within 2⁻¹⁵ of the target's largest, 0.3 µm on a 10 mm
/// motion.
pub(super) const DELTA_BITS: i32 = 16;
/// Normals and normal deltas: within 2⁻¹¹ (0.03°) on a unit normal.
pub(super) const NORMAL_BITS: i32 = 12;
/// Texture coordinates: within 2⁻¹⁵ in [0, 1], 0.1 texel of a 4096² texture.
pub(super) const UV_BITS: i32 = 16;

#[derive(Default)]
pub(super) struct Builder {
    pub(super) bin: Vec<u8>,
    pub(super) views: Vec<Value>,
    pub(super) accessors: Vec<Value>,
    /// Per view, how `--compress` encodes it.
    pub(super) codecs: Vec<Codec>,
    /// The file is compressed (`EXT_meshopt_compression`): float data is rounded to what its
    /// EXPONENTIAL filter keeps before it is written (so bounds and the fallback hold exactly
    /// what decodes), and morph-target deltas are dense (zero runs cost nothing there).
    pub(super) compress: bool,
}

impl Builder {
    pub(super) fn view(&mut self, bytes: &[u8], target: Option<u32>, codec: Codec) -> usize {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        let mut v = json!({ "buffer": 0, "byteOffset": self.bin.len(), "byteLength": bytes.len() });
        if let Some(t) = target {
            v["target"] = json!(t);
        }
        self.bin.extend_from_slice(bytes);
        self.views.push(v);
        self.codecs.push(codec);
        self.views.len() - 1
    }

    /// A VEC3 float accessor kept to `bits` mantissa bits by `--compress`; a NaN or infinity
    /// is an error.
    pub(super) fn vec3_accessor(
        &mut self,
        what: &str,
        data: &[DVec3],
        with_bounds: bool,
        bits: i32,
    ) -> Result<usize, GltfExportError> {
        let mut values: Vec<[f32; 3]> = data.iter().map(|p| p.as_vec3().to_array()).collect();
        check_finite(what, values.iter().map(|v| v.iter().all(|c| c.is_finite())))?;
        if self.compress {
            values = super::meshopt::exp_round_trip(&values, bits);
        }
        let mut bytes = Vec::with_capacity(data.len() * 12);
        let mut min = [f32::INFINITY; 3];
        let mut max = [f32::NEG_INFINITY; 3];
        for q in &values {
            for i in 0..3 {
                min[i] = min[i].min(q[i]);
                max[i] = max[i].max(q[i]);
                bytes.extend_from_slice(&q[i].to_le_bytes());
            }
        }
        let codec = Codec::Attributes {
            stride: 12,
            exp_bits: Some(bits),
        };
        let view = self.view(&bytes, Some(ARRAY_BUFFER), codec);
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
        let rounded;
        let data = if self.compress {
            rounded = super::meshopt::exp_round_trip(data, UV_BITS);
            &rounded
        } else {
            data
        };
        let bytes: Vec<u8> = data
            .iter()
            .flatten()
            .flat_map(|x| x.to_le_bytes())
            .collect();
        let codec = Codec::Attributes {
            stride: 8,
            exp_bits: Some(UV_BITS),
        };
        let view = self.view(&bytes, Some(ARRAY_BUFFER), codec);
        self.accessors.push(json!({
            "bufferView": view, "componentType": FLOAT, "count": data.len(), "type": "VEC2",
        }));
        Ok(self.accessors.len() - 1)
    }

    /// The triangles' indices: 16-bit when every index fits (below 65 535, which glTF keeps
    /// for primitive restart), else 32-bit.
    pub(super) fn indices_accessor(&mut self, triangles: &[[u32; 3]]) -> usize {
        let (bytes, component) = indices_bytes(triangles.iter().flatten().copied());
        let stride = bytes.len() / (3 * triangles.len()).max(1);
        let view = self.view(
            &bytes,
            Some(ELEMENT_ARRAY_BUFFER),
            Codec::Triangles { stride },
        );
        self.accessors.push(json!({
            "bufferView": view, "componentType": component, "count": triangles.len() * 3,
            "type": "SCALAR",
        }));
        self.accessors.len() - 1
    }

    /// An embedded image's buffer view (PNG or JPEG bytes).
    pub(super) fn image_view(&mut self, bytes: &[u8]) -> usize {
        self.view(bytes, None, Codec::Raw)
    }

    /// A morph target's VEC3 delta accessor (with bounds, which glTF requires of a POSITION
    /// delta): sparse — only the vertices whose delta is not exactly zero — when that is
    /// smaller than dense, as glTF 2.0 §3.6.2.3 provides for morph targets; a NaN or infinity
    /// is an error.
    pub(super) fn delta_accessor(
        &mut self,
        what: &str,
        data: &[DVec3],
        bits: i32,
    ) -> Result<usize, GltfExportError> {
        let values: Vec<[f32; 3]> = data.iter().map(|d| d.as_vec3().to_array()).collect();
        check_finite(what, values.iter().map(|v| v.iter().all(|c| c.is_finite())))?;
        let moved: Vec<u32> = (0..values.len() as u32)
            .filter(|&i| values[i as usize] != [0.0; 3])
            .collect();
        let index_bytes = if values.len() <= 65_535 { 2 } else { 4 };
        if self.compress || moved.len() * (index_bytes + 12) >= values.len() * 12 {
            return self.vec3_accessor(what, data, true, bits);
        }
        let mut min = [0.0f32; 3];
        let mut max = [0.0f32; 3];
        if moved.len() == values.len() {
            (min, max) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
        }
        let mut value_bytes = Vec::with_capacity(moved.len() * 12);
        for &i in &moved {
            for (k, c) in values[i as usize].into_iter().enumerate() {
                min[k] = min[k].min(c);
                max[k] = max[k].max(c);
                value_bytes.extend_from_slice(&c.to_le_bytes());
            }
        }
        let mut a = json!({
            "componentType": FLOAT, "count": data.len(), "type": "VEC3", "min": min, "max": max,
        });
        // No moved vertex at all: an accessor without a buffer view is all zeros.
        if !moved.is_empty() {
            let (bytes, component) = indices_bytes(moved.iter().copied());
            let stride = bytes.len() / moved.len();
            let indices = self.view(&bytes, None, Codec::Indices { stride });
            let codec = Codec::Attributes {
                stride: 12,
                exp_bits: Some(bits),
            };
            let values = self.view(&value_bytes, None, codec);
            a["sparse"] = json!({
                "count": moved.len(),
                "indices": { "bufferView": indices, "componentType": component },
                "values": { "bufferView": values },
            });
        }
        self.accessors.push(a);
        Ok(self.accessors.len() - 1)
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
        // Animation times and weights exactly (the extension's advice for times).
        let codec = Codec::Attributes {
            stride: 4,
            exp_bits: None,
        };
        let view = self.view(&bytes, None, codec);
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

/// Little-endian bytes of `indices` as 16-bit integers when all are below 65 535, else
/// 32-bit; with the glTF component type.
fn indices_bytes(indices: impl Iterator<Item = u32> + Clone) -> (Vec<u8>, u32) {
    if indices.clone().all(|i| i < 65_535) {
        let bytes = indices.flat_map(|i| (i as u16).to_le_bytes()).collect();
        (bytes, UNSIGNED_SHORT)
    } else {
        (
            indices.flat_map(|i| i.to_le_bytes()).collect(),
            UNSIGNED_INT,
        )
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
            .vec3_accessor("normals", &[DVec3::new(0.0, 0.0, f64::NAN)], false, 12)
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
