//! The versioned binary container of a cache file.
//!
//! Layout (all integers little-endian):
//!
//! | bytes | content |
//! |---|---|
//! | 8  | magic `FACEBEM\x1a` |
//! | 4  | format version ([`FORMAT_VERSION`]) |
//! | 32 | BLAKE3 hash of the input face mesh (welded geometry) |
//! | 32 | BLAKE3 hash of all pipeline parameters (postcard encoding) |
//! | 8  | payload length |
//! | 32 | BLAKE3 checksum of the payload |
//! | n  | payload: postcard encoding of the model |

use serde::Serialize;
use serde::de::DeserializeOwned;

/// First bytes of every facebem cache file.
pub const MAGIC: [u8; 8] = *b"FACEBEM\x1a";
/// Version of the cache format; bumped whenever the payload's layout changes (3: the
/// parameters gained `LargeFaceParams::normal_weight`; 4: `border_spacing` and
/// `PipelineParams::peel_rolled_in`; 5: `RigParams::units`, `muscle_model`, `anatomical` and
/// `FaceRig::unit`; 6: `PrecomputeReport::condition_estimate`; 7: `quadrature_unconverged` and
/// `quadrature_worst_error`, `QuadratureParams::tolerance`; 8: the control table's rows, the
/// force-driven `cheek_puff`; 9: the anatomical rig's eyelid controls, `Generator::Lid`, and lid
/// back elements no longer skull; 10: the force-driven brow muscles, `Generator::Force`; 11: the
/// teeth (sliding deep layer), a force-driven zygomaticus, the mouth's muscles and
/// `Generator::Sphincter`; 12: the jaw opening as the chord of its arc, 0.5 rad, 6 mm glide; 13: large faces simplified in
/// their canonical frame and, when mirror-symmetric, as a mirrored half,
/// [`crate::copy::simplify`](mod@crate::copy::simplify); 14: squints that keep the lids from crossing,
/// `lid_closure::keep_squints_open`; 15: the input mouth corners a copy does not hold follow
/// its margin instead of hanging between the lips; 16: a large face's copy keeps the input
/// mouth corners it holds and resamples the mouth loop from them; 17: the lips relaxed where a
/// response would turn them over, [`crate::settle::untangle`]; 18: turned triangles evened out
/// ([`crate::settle::untangle::relax_inversions`]' second stage) and a large face's carried-over
/// vertices relaxed after the lid closure; 19: the lids relaxed after the lid closure; 20: turned
/// patches smoothed (the third stage) and `mouthPucker`'s two sphincter halves relaxed as a sum; 21: the mid and lower face
/// relaxed beyond the lips and lids; 22: each corrugator relaxed in its `browDown*`
/// combination; 23: the mid and lower face relaxed for the lengthened direction too; 25: `LargeFaceParams::method`, remeshed copies; 26:
/// `PrecomputeReport::force_peak_ratio`; 27: the modiolus muscles pin the modiolus,
/// [`face_prep::modiolus`]; 28: the zygomaticus's origin further out, the pins along the skin;
/// 29: the report says why a large face's edge-collapse copy was replaced by a remeshed one;
/// 30: closed mouths and eyes cut open; 31: the jaw carries the skin down to its lower border and
/// the neck stays, [`face_prep::jaw::Jaw::carried`]; 32: the lip seal, a 38th control,
/// [`face_prep::lip_seal`]; 33: the cheek raiser, `orbicularis_oculi_malar_l/_r`, controls 39 and 40;
/// 34: the lips' marginal orbicularis oris, `orbicularis_oris_marginal_upper/_lower`, controls 41
/// and 42; 35: the orbicularis oculi's part over the brow, `orbicularis_oculi_superior_l/_r`,
/// controls 43 and 44).
pub const FORMAT_VERSION: u32 = 35;
/// Size of the fixed header in bytes.
pub const HEADER_LEN: usize = 8 + 4 + 32 + 32 + 8 + 32;

/// Errors reading a cache container.
#[derive(Debug, thiserror::Error, PartialEq)]
#[non_exhaustive]
pub enum ContainerError {
    /// The file is shorter than the header or than its declared payload.
    #[error("cache file is truncated: {len} bytes, expected {expected}")]
    Truncated {
        /// Bytes present.
        len: usize,
        /// Bytes the header promises.
        expected: usize,
    },
    /// The file does not start with the facebem magic.
    #[error("not a facebem cache file (wrong magic bytes)")]
    NotACache,
    /// The file was written by another format version.
    #[error("cache format version {found}, this facebem reads version {expected}")]
    Version {
        /// Version in the file.
        found: u32,
        /// Version this build reads.
        expected: u32,
    },
    /// The payload checksum does not match: the file is corrupt.
    #[error("cache file is corrupt: payload checksum mismatch")]
    Checksum,
    /// The payload passed the checksum but does not decode (written by an incompatible build).
    #[error("cache payload does not decode: {0}")]
    Decode(String),
    /// The payload could not be encoded.
    #[error("cannot encode cache payload: {0}")]
    Encode(String),
}

/// The hashes a container's header carries besides its payload.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Header {
    /// Hash of the input mesh.
    pub input_hash: [u8; 32],
    /// Hash of the parameters.
    pub params_hash: [u8; 32],
}

/// Encodes `payload` with its header.
pub fn encode<T: Serialize>(header: &Header, payload: &T) -> Result<Vec<u8>, ContainerError> {
    let body = postcard::to_stdvec(payload).map_err(|e| ContainerError::Encode(e.to_string()))?;
    let mut out = Vec::with_capacity(HEADER_LEN + body.len());
    out.extend_from_slice(&MAGIC);
    out.extend_from_slice(&FORMAT_VERSION.to_le_bytes());
    out.extend_from_slice(&header.input_hash);
    out.extend_from_slice(&header.params_hash);
    out.extend_from_slice(&(body.len() as u64).to_le_bytes());
    out.extend_from_slice(blake3::hash(&body).as_bytes());
    out.extend_from_slice(&body);
    Ok(out)
}

/// Reads only the header (magic, version, hashes), without checking the payload.
pub fn read_header(bytes: &[u8]) -> Result<Header, ContainerError> {
    if bytes.len() < 12 || bytes[..8] != MAGIC {
        return if bytes.len() >= 8 && bytes[..8] != MAGIC {
            Err(ContainerError::NotACache)
        } else {
            Err(ContainerError::Truncated {
                len: bytes.len(),
                expected: HEADER_LEN,
            })
        };
    }
    let found = u32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]]);
    if found != FORMAT_VERSION {
        return Err(ContainerError::Version {
            found,
            expected: FORMAT_VERSION,
        });
    }
    if bytes.len() < HEADER_LEN {
        return Err(ContainerError::Truncated {
            len: bytes.len(),
            expected: HEADER_LEN,
        });
    }
    Ok(Header {
        input_hash: array32(&bytes[12..44]),
        params_hash: array32(&bytes[44..76]),
    })
}

/// Checks magic, version, length and checksum, then decodes the payload.
pub fn decode<T: DeserializeOwned>(bytes: &[u8]) -> Result<(Header, T), ContainerError> {
    let header = read_header(bytes)?;
    let mut len = [0u8; 8];
    len.copy_from_slice(&bytes[76..84]);
    let declared = u64::from_le_bytes(len);
    let expected = usize::try_from(declared)
        .ok()
        .and_then(|n| n.checked_add(HEADER_LEN))
        .unwrap_or(usize::MAX);
    if bytes.len() != expected {
        return Err(ContainerError::Truncated {
            len: bytes.len(),
            expected,
        });
    }
    let body = &bytes[HEADER_LEN..];
    if blake3::hash(body).as_bytes() != &bytes[84..116] {
        return Err(ContainerError::Checksum);
    }
    let payload = postcard::from_bytes(body).map_err(|e| ContainerError::Decode(e.to_string()))?;
    Ok((header, payload))
}

fn array32(s: &[u8]) -> [u8; 32] {
    let mut a = [0u8; 32];
    a.copy_from_slice(s);
    a
}

#[cfg(test)]
mod tests {
    use super::*;

    const H: Header = Header {
        input_hash: [1; 32],
        params_hash: [2; 32],
    };

    #[test]
    fn round_trip_is_bit_exact() {
        let payload = vec![0.1f64, -0.0, f64::MIN_POSITIVE, 1.0 / 3.0];
        let bytes = encode(&H, &payload).unwrap();
        let (h, back): (Header, Vec<f64>) = decode(&bytes).unwrap();
        assert_eq!(h, H);
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&back), bits(&payload));
    }

    #[test]
    fn every_kind_of_damage_is_named() {
        let bytes = encode(&H, &vec![1.0f64; 16]).unwrap();
        let mut flipped = bytes.clone();
        flipped[HEADER_LEN + 5] ^= 0x10;
        assert_eq!(
            decode::<Vec<f64>>(&flipped).unwrap_err(),
            ContainerError::Checksum
        );
        let short = &bytes[..bytes.len() - 1];
        assert!(matches!(
            decode::<Vec<f64>>(short),
            Err(ContainerError::Truncated { .. })
        ));
        assert!(matches!(
            decode::<Vec<f64>>(&bytes[..20]),
            Err(ContainerError::Truncated { .. })
        ));
        let mut magic = bytes.clone();
        magic[0] = b'X';
        assert_eq!(
            decode::<Vec<f64>>(&magic).unwrap_err(),
            ContainerError::NotACache
        );
        let mut version = bytes.clone();
        version[8] = 99;
        assert_eq!(
            decode::<Vec<f64>>(&version).unwrap_err(),
            ContainerError::Version {
                found: 99,
                expected: FORMAT_VERSION
            }
        );
        // Right checksum, wrong type: a decode error, not a panic.
        assert!(matches!(
            decode::<Vec<String>>(&encode(&H, &vec![u64::MAX]).unwrap()),
            Err(ContainerError::Decode(_))
        ));
    }
}
