//! A parsed glTF document: its JSON root, lazily loaded buffers, and the walk of its node
//! hierarchy to a mesh's world transform.

use std::path::{Path, PathBuf};

use glam::{DMat4, DQuat, DVec3};
use gltf::json;

use super::buffers::load_buffer;
use super::glb::{GLB_MAGIC, split_glb};
use crate::error::GltfError;
use crate::input::limits::InputLimits;

/// Deepest node nesting accepted (scene root = depth 0).
pub const MAX_NODE_DEPTH: usize = 256;

/// Node visits over all scenes before the hierarchy is declared too large.
const MAX_NODE_VISITS: usize = 10_000_000;

pub(super) fn invalid(what: &'static str, index: usize, reason: impl Into<String>) -> GltfError {
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
    pub(super) blob: Option<Vec<u8>>,
    base: Option<PathBuf>,
    buffers: Vec<Option<Vec<u8>>>,
    pub(super) limits: InputLimits,
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
    pub(super) fn buffer(&mut self, index: usize) -> Result<&[u8], GltfError> {
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
