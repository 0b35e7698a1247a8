//! The input stage: reading a face from OBJ ([`obj_text`]) or glTF/GLB ([`gltf_read`]),
//! welding and triangulating it into a [`FaceMesh`](crate::FaceMesh), the size limits every
//! untrusted file is held to ([`limits`]), stray vertices ([`stray`]) and the length unit
//! ([`units`]).

pub(crate) mod face_mesh;
pub(crate) mod gltf_face;
pub mod gltf_read;
pub mod limits;
pub mod obj_text;
pub mod stray;
pub mod units;

pub use gltf_read::files_read_by;
