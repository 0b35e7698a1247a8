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
//! - accessors: component type and element type, `count` against
//!   [`InputLimits`](crate::InputLimits), `byteStride` at least the element size, the last
//!   element inside its buffer view, the view inside its buffer; sparse accessors' counts,
//!   indices and views likewise;
//! - buffers are loaded only when an accessor needs them: the GLB binary chunk, a `data:` URI
//!   (base64), or a relative path inside the glTF's own folder (no `..`, no absolute path, no
//!   scheme such as `file:` or `http:`, symlinks resolved and required to stay inside), which
//!   must be a regular file (a FIFO or device is refused before it is opened) at least as long
//!   as the buffer's `byteLength`; exactly `byteLength` bytes are read.

mod accessors;
mod buffers;
mod document;
mod external;
mod glb;
mod looks;
mod meshes;
mod pack;

#[doc(inline)]
pub use crate::error::GltfError;
pub use buffers::decode_base64;
pub(crate) use document::Document;
pub use document::MAX_NODE_DEPTH;
pub use external::files_read_by;
pub use glb::split_glb;
pub use looks::{MaterialLook, material_looks};
pub(crate) use meshes::{attribute, mesh_labels, primitives};
pub use pack::pack_glb;
