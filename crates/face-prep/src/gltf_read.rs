//! glTF 2.0 / GLB reading that cannot panic, hang, exhaust memory or read outside the file's
//! folder, whatever the file holds.
//!
//! The JSON is deserialised into `gltf_json` types WITHOUT the gltf crate's validation (which
//! itself indexes unchecked, e.g. a POSITION accessor index out of range panics in gltf-json's
//! `mesh.rs`), and only what a face needs is read, with every index, count, offset and stride
//! checked here before use:
//!
//! - the GLB container (header, chunk lengths) is parsed by hand;
//! - the node hierarchy is walked iteratively, with a visited set (a cycle or a node with two
//!   parents is an error) and a depth limit ([`MAX_NODE_DEPTH`]);
//! - accessors: component type and element type, `count` against [`InputLimits`], `byteStride`
//!   at least the element size, the last element inside its buffer view, the view inside its
//!   buffer; sparse accessors' counts, indices and views likewise;
//! - buffers are loaded only when an accessor needs them: the GLB binary chunk, a `data:` URI
//!   (base64), or a relative path inside the glTF's own folder (no `..`, no absolute path, no
//!   scheme such as `file:` or `http:`, symlinks resolved and required to stay inside), which
//!   must be a regular file (a FIFO or device is refused before it is opened) at least as long
//!   as the buffer's `byteLength`; exactly `byteLength` bytes are read.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use glam::{DMat4, DQuat, DVec3};
use gltf::json;
use json::validation::Checked;

use crate::limits::InputLimits;

/// Deepest node nesting accepted (scene root = depth 0).
pub const MAX_NODE_DEPTH: usize = 256;

/// Node visits over all scenes before the hierarchy is declared too large.
const MAX_NODE_VISITS: usize = 10_000_000;

/// What is wrong with a glTF/GLB file.
#[derive(Debug, thiserror::Error)]
pub enum GltfError {
    /// The GLB container is malformed.
    #[error("GLB container: {0}")]
    Glb(String),
    /// The JSON does not parse as a glTF document.
    #[error("glTF JSON: {0}")]
    Json(String),
    /// A buffer cannot be loaded.
    #[error("buffer {index} (uri {uri}): {reason}")]
    Buffer {
        /// Buffer index.
        index: usize,
        /// Its URI, shortened for display (`<GLB binary chunk>` when it has none).
        uri: String,
        /// What is wrong.
        reason: String,
    },
    /// An object of the document is invalid (index out of range, bad type, out of bounds...).
    #[error("{what} {index}: {reason}")]
    Invalid {
        /// Kind of object (`accessor`, `bufferView`, `node`, `scene`, `mesh`).
        what: &'static str,
        /// Its index.
        index: usize,
        /// What is wrong.
        reason: String,
    },
}

fn invalid(what: &'static str, index: usize, reason: impl Into<String>) -> GltfError {
    GltfError::Invalid {
        what,
        index,
        reason: reason.into(),
    }
}

/// A URI shortened for messages (data URIs can be megabytes).
fn short_uri(uri: &str) -> String {
    const MAX: usize = 60;
    let mut s: String = uri.chars().take(MAX).collect();
    if uri.chars().nth(MAX).is_some() {
        s.push('…');
    }
    format!("{s:?}")
}

/// A parsed document: JSON root and the GLB binary chunk if any.
pub(crate) struct Document {
    pub(crate) root: json::Root,
    blob: Option<Vec<u8>>,
    base: Option<PathBuf>,
    buffers: Vec<Option<Vec<u8>>>,
    limits: InputLimits,
}

const GLB_MAGIC: &[u8; 4] = b"glTF";
const CHUNK_JSON: u32 = 0x4E4F_534A;
const CHUNK_BIN: u32 = 0x004E_4942;

fn le_u32(b: &[u8], at: usize) -> Option<u32> {
    let s = b.get(at..at.checked_add(4)?)?;
    Some(u32::from_le_bytes([s[0], s[1], s[2], s[3]]))
}

/// Splits a GLB into its JSON chunk and optional binary chunk.
fn split_glb(bytes: &[u8]) -> Result<(&[u8], Option<&[u8]>), GltfError> {
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

impl Document {
    /// Parses a `.gltf` (JSON) or `.glb` (binary container) document; `base` is the folder
    /// relative buffer URIs resolve in (`None`: only GLB and `data:` buffers can be read).
    pub(crate) fn parse(
        bytes: &[u8],
        base: Option<&Path>,
        limits: &InputLimits,
    ) -> Result<Document, GltfError> {
        let (json_bytes, blob) = if bytes.starts_with(GLB_MAGIC) {
            split_glb(bytes)?
        } else {
            (bytes, None)
        };
        let root: json::Root = json::deserialize::from_slice(json_bytes)
            .map_err(|e| GltfError::Json(e.to_string()))?;
        let buffers = vec![None; root.buffers.len()];
        Ok(Document {
            root,
            blob: blob.map(<[u8]>::to_vec),
            base: base.map(Path::to_path_buf),
            buffers,
            limits: *limits,
        })
    }

    /// The bytes of buffer `index` (loaded on first use).
    fn buffer(&mut self, index: usize) -> Result<&[u8], GltfError> {
        let Some(buffer) = self.root.buffers.get(index) else {
            return Err(invalid(
                "buffer",
                index,
                format!("does not exist ({} buffers)", self.root.buffers.len()),
            ));
        };
        if self.buffers[index].is_none() {
            let uri_label = buffer
                .uri
                .as_deref()
                .map_or_else(|| "<GLB binary chunk>".to_owned(), short_uri);
            let err = |reason: String| GltfError::Buffer {
                index,
                uri: uri_label.clone(),
                reason,
            };
            let len = buffer.byte_length.0;
            if len > self.limits.max_file_bytes {
                return Err(err(format!(
                    "byteLength {len} is above the input limit of {} bytes",
                    self.limits.max_file_bytes
                )));
            }
            let data = load_buffer(
                buffer.uri.as_deref(),
                index,
                len as usize,
                self.blob.as_deref(),
                self.base.as_deref(),
            )
            .map_err(err)?;
            self.buffers[index] = Some(data);
        }
        Ok(self.buffers[index].as_deref().unwrap_or(&[]))
    }

    /// The world transform of the first node instantiating `mesh` (default scene first, then
    /// every scene in order, depth-first), or `None` if no scene instantiates it.
    pub(crate) fn mesh_world_transform(&self, mesh: usize) -> Result<Option<DMat4>, GltfError> {
        let root = &self.root;
        let scenes = root
            .scene
            .map(|s| s.value())
            .into_iter()
            .chain(0..root.scenes.len());
        let mut visits = 0usize;
        for s in scenes {
            let scene = root.scenes.get(s).ok_or_else(|| {
                invalid(
                    "scene",
                    s,
                    format!("does not exist ({} scenes)", root.scenes.len()),
                )
            })?;
            let mut visited = vec![false; root.nodes.len()];
            let mut stack: Vec<(usize, DMat4, usize)> = scene
                .nodes
                .iter()
                .rev()
                .map(|n| (n.value(), DMat4::IDENTITY, 0))
                .collect();
            while let Some((n, parent, depth)) = stack.pop() {
                visits += 1;
                if visits > MAX_NODE_VISITS {
                    return Err(invalid(
                        "scene",
                        s,
                        format!("node hierarchy above {MAX_NODE_VISITS} visits"),
                    ));
                }
                let node = root.nodes.get(n).ok_or_else(|| {
                    invalid(
                        "node",
                        n,
                        format!("does not exist ({} nodes)", root.nodes.len()),
                    )
                })?;
                if std::mem::replace(&mut visited[n], true) {
                    return Err(invalid(
                        "node",
                        n,
                        "is reached twice in the hierarchy (a cycle, or a node with two parents)",
                    ));
                }
                if depth > MAX_NODE_DEPTH {
                    return Err(invalid(
                        "node",
                        n,
                        format!("is nested deeper than {MAX_NODE_DEPTH} levels"),
                    ));
                }
                let world = parent * local_transform(node);
                if node.mesh.map(|m| m.value()) == Some(mesh) {
                    if !world.is_finite() {
                        return Err(invalid("node", n, "world transform is not finite"));
                    }
                    return Ok(Some(world));
                }
                for c in node.children.iter().flatten().rev() {
                    stack.push((c.value(), world, depth + 1));
                }
            }
        }
        Ok(None)
    }

    /// Reads a FLOAT VEC3 accessor (POSITION) as f64 points.
    pub(crate) fn read_vec3(&mut self, index: usize) -> Result<Vec<DVec3>, GltfError> {
        let (acc, comp) = self.accessor_layout(index, self.limits.max_positions)?;
        if acc.mult != 3 || comp != json::accessor::ComponentType::F32 {
            return Err(invalid(
                "accessor",
                index,
                format!(
                    "POSITION must be FLOAT VEC3, found {comp:?} with {} components",
                    acc.mult
                ),
            ));
        }
        let values = self.read_components(index, &acc, comp)?;
        Ok(values
            .chunks_exact(3)
            .map(|c| DVec3::new(c[0], c[1], c[2]))
            .collect())
    }

    /// Reads a TEXCOORD accessor (VEC2 FLOAT, or normalized UNSIGNED_BYTE/SHORT).
    pub(crate) fn read_texcoords(&mut self, index: usize) -> Result<Vec<[f32; 2]>, GltfError> {
        use json::accessor::ComponentType as C;
        let (acc, comp) = self.accessor_layout(index, self.limits.max_positions)?;
        let normalized = self.root.accessors[index].normalized;
        let scale = match comp {
            C::F32 => 1.0,
            C::U8 if normalized => 1.0 / 255.0,
            C::U16 if normalized => 1.0 / 65535.0,
            _ => 0.0,
        };
        if acc.mult != 2 || scale == 0.0 {
            return Err(invalid(
                "accessor",
                index,
                format!(
                    "TEXCOORD must be VEC2 FLOAT or normalized UNSIGNED_BYTE/SHORT, found \
                     {comp:?} with {} components",
                    acc.mult
                ),
            ));
        }
        let values = self.read_components(index, &acc, comp)?;
        Ok(values
            .chunks_exact(2)
            .map(|c| [(c[0] * scale) as f32, (c[1] * scale) as f32])
            .collect())
    }

    /// Reads an index accessor (SCALAR, UNSIGNED_BYTE/SHORT/INT).
    pub(crate) fn read_indices(&mut self, index: usize) -> Result<Vec<u32>, GltfError> {
        use json::accessor::ComponentType as C;
        let limit = self.limits.max_triangles.saturating_mul(3);
        let (acc, comp) = self.accessor_layout(index, limit)?;
        if acc.mult != 1 || !matches!(comp, C::U8 | C::U16 | C::U32) {
            return Err(invalid(
                "accessor",
                index,
                format!(
                    "indices must be SCALAR UNSIGNED_BYTE/SHORT/INT, found {comp:?} with {} components",
                    acc.mult
                ),
            ));
        }
        // Integers up to 2^32 are exact in f64.
        Ok(self
            .read_components(index, &acc, comp)?
            .into_iter()
            .map(|x| x as u32)
            .collect())
    }

    fn accessor_layout(
        &self,
        index: usize,
        limit: usize,
    ) -> Result<(Layout, json::accessor::ComponentType), GltfError> {
        let acc = self.root.accessors.get(index).ok_or_else(|| {
            invalid(
                "accessor",
                index,
                format!("does not exist ({} accessors)", self.root.accessors.len()),
            )
        })?;
        let comp = match acc.component_type {
            Checked::Valid(c) => c.0,
            Checked::Invalid => return Err(invalid("accessor", index, "invalid componentType")),
        };
        let mult = match acc.type_ {
            Checked::Valid(t) => t.multiplicity(),
            Checked::Invalid => return Err(invalid("accessor", index, "invalid type")),
        };
        if acc.count.0 > limit as u64 {
            return Err(invalid(
                "accessor",
                index,
                format!("count {} is above the input limit of {limit}", acc.count.0),
            ));
        }
        Ok((
            Layout {
                count: acc.count.0 as usize,
                mult,
            },
            comp,
        ))
    }

    /// Components of every element of accessor `index` as f64 (`count × mult` values), with
    /// sparse substitution applied.
    fn read_components(
        &mut self,
        index: usize,
        layout: &Layout,
        comp: json::accessor::ComponentType,
    ) -> Result<Vec<f64>, GltfError> {
        let acc = self.root.accessors[index].clone();
        let Layout { count, mult } = *layout;
        let elem = comp.size() * mult;
        let mut out = match acc.buffer_view {
            None => vec![0.0; count * mult],
            Some(view) => {
                let offset = acc.byte_offset.map_or(0, |o| o.0);
                let (bytes, stride) = self.view_bytes(view.value(), index, elem)?;
                read_strided(bytes, offset, stride, count, elem, comp, mult)
                    .map_err(|r| invalid("accessor", index, r))?
            }
        };
        if let Some(sparse) = &acc.sparse {
            let n = sparse.count.0;
            if n == 0 || n > count as u64 {
                return Err(invalid(
                    "accessor",
                    index,
                    format!("sparse count {n} must be in 1..={count}"),
                ));
            }
            let n = n as usize;
            let icomp = match sparse.indices.component_type {
                Checked::Valid(c) => c.0,
                Checked::Invalid => {
                    return Err(invalid("accessor", index, "invalid sparse index type"));
                }
            };
            let (ibytes, _) = self.view_bytes(sparse.indices.buffer_view.value(), index, 1)?;
            let ibytes = ibytes.to_vec();
            let positions = read_strided(
                &ibytes,
                sparse.indices.byte_offset.0,
                icomp.size(),
                n,
                icomp.size(),
                icomp,
                1,
            )
            .map_err(|r| invalid("accessor", index, format!("sparse indices: {r}")))?;
            let (vbytes, _) = self.view_bytes(sparse.values.buffer_view.value(), index, 1)?;
            let values = read_strided(
                vbytes,
                sparse.values.byte_offset.0,
                elem,
                n,
                elem,
                comp,
                mult,
            )
            .map_err(|r| invalid("accessor", index, format!("sparse values: {r}")))?;
            for (k, &p) in positions.iter().enumerate() {
                let p = p as usize;
                if p >= count {
                    return Err(invalid(
                        "accessor",
                        index,
                        format!("sparse index {p} is not below count {count}"),
                    ));
                }
                out[p * mult..(p + 1) * mult].copy_from_slice(&values[k * mult..(k + 1) * mult]);
            }
        }
        Ok(out)
    }

    /// The bytes of buffer view `view` and its stride (`byteStride`, or `elem` if absent).
    fn view_bytes(
        &mut self,
        view: usize,
        accessor: usize,
        elem: usize,
    ) -> Result<(&[u8], usize), GltfError> {
        let v = self.root.buffer_views.get(view).cloned().ok_or_else(|| {
            invalid(
                "accessor",
                accessor,
                format!(
                    "bufferView {view} does not exist ({} views)",
                    self.root.buffer_views.len()
                ),
            )
        })?;
        let stride = v.byte_stride.map_or(elem, |s| s.0);
        if stride < elem {
            return Err(invalid(
                "bufferView",
                view,
                format!(
                    "byteStride {stride} is smaller than the element size {elem} of accessor {accessor}"
                ),
            ));
        }
        let data = self.buffer(v.buffer.value())?;
        let start = v.byte_offset.map_or(0, |o| o.0);
        let end = start.checked_add(v.byte_length.0);
        match end {
            Some(end) if end <= data.len() as u64 => {
                Ok((&data[start as usize..end as usize], stride))
            }
            _ => Err(invalid(
                "bufferView",
                view,
                format!(
                    "bytes {start}+{} lie beyond its buffer's {} bytes",
                    v.byte_length.0,
                    data.len()
                ),
            )),
        }
    }
}

#[derive(Clone, Copy)]
struct Layout {
    count: usize,
    mult: usize,
}

/// `count` elements of `mult` components each, the first at `offset`, `stride` bytes apart.
fn read_strided(
    bytes: &[u8],
    offset: u64,
    stride: usize,
    count: usize,
    elem: usize,
    comp: json::accessor::ComponentType,
    mult: usize,
) -> Result<Vec<f64>, String> {
    use json::accessor::ComponentType as C;
    if count == 0 {
        return Ok(Vec::new());
    }
    let last_end = (stride as u64)
        .checked_mul(count as u64 - 1)
        .and_then(|x| x.checked_add(offset))
        .and_then(|x| x.checked_add(elem as u64));
    match last_end {
        Some(e) if e <= bytes.len() as u64 => {}
        _ => {
            return Err(format!(
                "{count} elements of {elem} bytes (stride {stride}, offset {offset}) do not fit in \
                 its buffer view of {} bytes",
                bytes.len()
            ));
        }
    }
    let size = comp.size();
    let mut out = Vec::with_capacity(count * mult);
    for i in 0..count {
        let at = offset as usize + i * stride;
        for k in 0..mult {
            let b = &bytes[at + k * size..at + (k + 1) * size];
            out.push(match comp {
                C::I8 => f64::from(b[0] as i8),
                C::U8 => f64::from(b[0]),
                C::I16 => f64::from(i16::from_le_bytes([b[0], b[1]])),
                C::U16 => f64::from(u16::from_le_bytes([b[0], b[1]])),
                C::U32 => f64::from(u32::from_le_bytes([b[0], b[1], b[2], b[3]])),
                C::F32 => f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]])),
            });
        }
    }
    Ok(out)
}

fn local_transform(node: &json::Node) -> DMat4 {
    if let Some(m) = node.matrix {
        return DMat4::from_cols_array(&m.map(f64::from));
    }
    let t = node.translation.unwrap_or([0.0; 3]).map(f64::from);
    let r = node
        .rotation
        .map_or([0.0, 0.0, 0.0, 1.0], |q| q.0)
        .map(f64::from);
    let s = node.scale.unwrap_or([1.0; 3]).map(f64::from);
    DMat4::from_scale_rotation_translation(DVec3::from(s), DQuat::from_array(r), DVec3::from(t))
}

/// Loads a buffer's bytes (exactly `len`) from the GLB chunk, a data URI or a file in `base`.
fn load_buffer(
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
fn resolve_relative(uri: &str, base: Option<&Path>) -> Result<PathBuf, String> {
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

/// Standard base64 (RFC 4648, `=` padding optional, whitespace not allowed).
fn decode_base64(s: &str) -> Result<Vec<u8>, String> {
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

/// Labels of the meshes (name, or `#index` when unnamed).
pub(crate) fn mesh_labels(root: &json::Root) -> Vec<String> {
    root.meshes
        .iter()
        .enumerate()
        .map(|(i, m)| m.name.clone().unwrap_or_else(|| format!("#{i}")))
        .collect()
}

/// Accessor index of attribute `semantic` of primitive `primitive` of `mesh`, if it has one.
pub(crate) fn attribute(
    root: &json::Root,
    mesh: usize,
    primitive: usize,
    semantic: json::mesh::Semantic,
) -> Option<usize> {
    let p = root.meshes.get(mesh)?.primitives.get(primitive)?;
    p.attributes
        .get(&Checked::Valid(semantic))
        .map(|a| a.value())
}

/// Accessor indices of POSITION and indices, and the mode, of every primitive of `mesh`.
pub(crate) fn primitives(
    root: &json::Root,
    mesh: usize,
) -> Vec<(Option<usize>, Option<usize>, Checked<json::mesh::Mode>)> {
    root.meshes[mesh]
        .primitives
        .iter()
        .map(|p| {
            let attrs: &BTreeMap<_, _> = &p.attributes;
            let pos = attrs
                .get(&Checked::Valid(json::mesh::Semantic::Positions))
                .map(|a| a.value());
            (pos, p.indices.map(|i| i.value()), p.mode)
        })
        .collect()
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

    #[test]
    fn strided_reads_check_the_last_element() {
        use json::accessor::ComponentType as C;
        let bytes = [0u8; 24];
        assert!(read_strided(&bytes, 0, 12, 2, 12, C::F32, 3).is_ok());
        assert!(read_strided(&bytes, 4, 12, 2, 12, C::F32, 3).is_err());
        assert!(read_strided(&bytes, u64::MAX, 12, 2, 12, C::F32, 3).is_err());
        assert!(read_strided(&bytes, 0, usize::MAX, 3, 12, C::F32, 3).is_err());
    }
}
