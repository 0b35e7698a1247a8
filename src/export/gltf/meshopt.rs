//! `EXT_meshopt_compression` (Khronos, ratified; `--compress`): every buffer view encoded with
//! meshoptimizer's codecs (the `meshopt` crate, the reference encoder's own bindings) in
//! bitstream version 0, the one the extension specifies; float data through its EXPONENTIAL
//! filter ([`super::buffer::POSITION_BITS`] and the other mantissa widths). The uncompressed
//! views stay described in a fallback buffer without data, so the extension is required.

use serde_json::{Value, json};

use super::GltfExportError;
use super::buffer::Codec;

/// Exponents shared per component over a whole view: each view keeps its mantissa bits of
/// its largest value of each axis (an absolute precision, like quantization: 2⁻¹⁵ of a
/// target's largest delta), which compresses far better than one exponent per value.
const EXP_MODE: meshopt::EncodeExpMode = meshopt::EncodeExpMode::SharedComponent;

/// `values` as the EXPONENTIAL filter with `bits` mantissa bits decodes them: what a compressed
/// file holds.
///
/// ```ignore
/// let v = exp_round_trip(&[[1.0f32 / 3.0, 0.0, -2.5]], 8);
/// assert!((v[0][0] - 1.0 / 3.0).abs() < 1.0 / 256.0 && v[0][2] == -2.5);
/// ```
pub(super) fn exp_round_trip<const N: usize>(values: &[[f32; N]], bits: i32) -> Vec<[f32; N]> {
    let mut encoded = meshopt::encode_filter_exp(values, bits, EXP_MODE);
    meshopt::decode_filter_exp(&mut encoded);
    encoded.into_iter().map(|v| v.map(f32::from_bits)).collect()
}

/// Encodes each view of `bin` with its codec: returns the compressed buffer, and points every
/// view at the fallback buffer (index 1) with the extension object naming its compressed bytes
/// in buffer 0.
pub(super) fn compress_views(
    bin: &[u8],
    views: &mut [Value],
    codecs: &[Codec],
) -> Result<Vec<u8>, GltfExportError> {
    let mut out = Vec::new();
    for (view, codec) in views.iter_mut().zip(codecs) {
        let offset = view["byteOffset"].as_u64().unwrap_or(0) as usize;
        let length = view["byteLength"].as_u64().unwrap_or(0) as usize;
        let bytes = bin
            .get(offset..offset + length)
            .ok_or_else(|| GltfExportError::Compress("a buffer view outside the buffer".into()))?;
        while !out.len().is_multiple_of(4) {
            out.push(0);
        }
        let Some((encoded, stride, mode, filter)) = encode(bytes, *codec)? else {
            // Kept as it is, in the compressed buffer (the fallback buffer holds no data).
            view["byteOffset"] = json!(out.len());
            out.extend_from_slice(bytes);
            continue;
        };
        let mut ext = json!({
            "buffer": 0,
            "byteOffset": out.len(),
            "byteLength": encoded.len(),
            "byteStride": stride,
            "count": length / stride,
            "mode": mode,
        });
        if let Some(f) = filter {
            ext["filter"] = json!(f);
        }
        out.extend_from_slice(&encoded);
        view["buffer"] = json!(1);
        view["extensions"] = json!({ "EXT_meshopt_compression": ext });
    }
    while !out.len().is_multiple_of(4) {
        out.push(0);
    }
    Ok(out)
}

type Encoded = (Vec<u8>, usize, &'static str, Option<&'static str>);

/// One view's bytes encoded: (bytes, stride, mode, filter); `None` for a view kept as it is
/// ([`Codec::Raw`]).
fn encode(bytes: &[u8], codec: Codec) -> Result<Option<Encoded>, GltfExportError> {
    let err = |e: meshopt::Error| GltfExportError::Compress(e.to_string());
    Ok(Some(match codec {
        Codec::Raw => return Ok(None),
        Codec::Attributes { stride, exp_bits } => {
            let encoded = match (stride, exp_bits) {
                (4, Some(bits)) => filtered::<1>(bytes, bits).map_err(err)?,
                (8, Some(bits)) => filtered::<2>(bytes, bits).map_err(err)?,
                (12, Some(bits)) => filtered::<3>(bytes, bits).map_err(err)?,
                (4, None) => {
                    let elements: Vec<[u8; 4]> = chunks(bytes);
                    meshopt::encode_vertex_buffer_level(&elements, 2, Some(0)).map_err(err)?
                }
                _ => {
                    return Err(GltfExportError::Compress(format!(
                        "no attribute codec for {stride}-byte elements"
                    )));
                }
            };
            let filter = exp_bits.map(|_| "EXPONENTIAL");
            (encoded, stride, "ATTRIBUTES", filter)
        }
        Codec::Triangles { stride } => {
            let indices = indices_of(bytes, stride);
            let count = indices.iter().max().map_or(0, |m| *m as usize + 1);
            let encoded = meshopt::encode_index_buffer(&indices, count).map_err(err)?;
            (encoded, stride, "TRIANGLES", None)
        }
        Codec::Indices { stride } => {
            let indices = indices_of(bytes, stride);
            let count = indices.iter().max().map_or(0, |m| *m as usize + 1);
            let encoded = meshopt::encode_index_sequence(&indices, count).map_err(err)?;
            (encoded, stride, "INDICES", None)
        }
    }))
}

/// f32 elements of `N` components, through the EXPONENTIAL filter, then the attribute codec
/// (version 0).
fn filtered<const N: usize>(bytes: &[u8], bits: i32) -> meshopt::Result<Vec<u8>> {
    let values: Vec<[f32; N]> = chunks::<4>(bytes)
        .into_iter()
        .map(f32::from_le_bytes)
        .collect::<Vec<f32>>()
        .chunks_exact(N)
        .map(|c| std::array::from_fn(|k| c[k]))
        .collect();
    let encoded = meshopt::encode_filter_exp(&values, bits, EXP_MODE);
    meshopt::encode_vertex_buffer_level(&encoded, 2, Some(0))
}

/// `bytes` as consecutive `K`-byte arrays (a trailing partial one dropped).
fn chunks<const K: usize>(bytes: &[u8]) -> Vec<[u8; K]> {
    bytes
        .chunks_exact(K)
        .map(|c| std::array::from_fn(|k| c[k]))
        .collect()
}

/// Little-endian indices of `stride` (2 or 4) bytes.
fn indices_of(bytes: &[u8], stride: usize) -> Vec<u32> {
    if stride == 2 {
        chunks::<2>(bytes)
            .into_iter()
            .map(|c| u32::from(u16::from_le_bytes(c)))
            .collect()
    } else {
        chunks::<4>(bytes)
            .into_iter()
            .map(u32::from_le_bytes)
            .collect()
    }
}
