//! The GLB binary container: header and chunks, parsed by hand.

use crate::error::GltfError;

pub(super) const GLB_MAGIC: &[u8; 4] = b"glTF";
pub(super) const CHUNK_JSON: u32 = 0x4E4F_534A;
pub(super) const CHUNK_BIN: u32 = 0x004E_4942;

fn le_u32(b: &[u8], at: usize) -> Option<u32> {
    let s = b.get(at..at.checked_add(4)?)?;
    Some(u32::from_le_bytes([s[0], s[1], s[2], s[3]]))
}

/// Splits a GLB into its JSON chunk and optional binary chunk (the header's declared length
/// bounds both; a truncated chunk is an error).
///
/// ```
/// use face_prep::gltf_read::split_glb;
/// let json = br#"{"asset":{"version":"2.0"}}    "#; // padded to 4 bytes
/// let mut glb = b"glTF".to_vec();
/// glb.extend(2u32.to_le_bytes());
/// glb.extend((12 + 8 + json.len() as u32).to_le_bytes());
/// glb.extend((json.len() as u32).to_le_bytes());
/// glb.extend(0x4E4F_534Au32.to_le_bytes());
/// glb.extend(json);
/// let (j, bin) = split_glb(&glb).unwrap();
/// assert_eq!(j, json);
/// assert!(bin.is_none());
/// ```
pub fn split_glb(bytes: &[u8]) -> Result<(&[u8], Option<&[u8]>), GltfError> {
    let glb = |m: &str| GltfError::Glb(m.to_owned());
    let version = le_u32(bytes, 4).ok_or_else(|| glb("file shorter than the 12-byte header"))?;
    if version != 2 {
        return Err(GltfError::Glb(format!("version {version}, expected 2")));
    }
    let declared = le_u32(bytes, 8).ok_or_else(|| glb("file shorter than the 12-byte header"))?;
    let total = (declared as usize).min(bytes.len());
    let bytes = &bytes[..total];
    let mut at = 12;
    let mut chunks = Vec::new();
    while at < bytes.len() && chunks.len() < 2 {
        let (Some(len), Some(kind)) = (le_u32(bytes, at), le_u32(bytes, at + 4)) else {
            return Err(glb("truncated chunk header"));
        };
        let start = at + 8;
        let end = start
            .checked_add(len as usize)
            .filter(|&e| e <= bytes.len())
            .ok_or_else(|| {
                GltfError::Glb(format!(
                    "chunk at byte {at} declares {len} bytes, only {} remain",
                    bytes.len().saturating_sub(start)
                ))
            })?;
        chunks.push((kind, &bytes[start..end]));
        at = end;
    }
    match chunks.as_slice() {
        [(CHUNK_JSON, json), rest @ ..] => {
            let bin = rest.iter().find(|c| c.0 == CHUNK_BIN).map(|c| c.1);
            Ok((json, bin))
        }
        _ => Err(glb("the first chunk is not JSON")),
    }
}
