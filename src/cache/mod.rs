//! On-disk cache of a computed [`FaceModel`]: rig + muscle basis + parameters, in a versioned,
//! checksummed binary file ([`container`]) written atomically.
//!
//! [`load`] checks integrity only (magic, version, length, checksum, decoding); [`load_for`]
//! also checks that the file was computed from the given mesh with the given parameters, so a
//! caller can fall back to recomputing on any error.
//!
//! ```no_run
//! use facebem::{cache, FaceModel};
//! # fn demo(model: &FaceModel) -> Result<(), cache::CacheError> {
//! cache::save("face.rig".as_ref(), model)?;
//! let back = cache::load_for("face.rig".as_ref(), &model.mesh, &model.params)?;
//! assert_eq!(back.basis, model.basis);
//! # Ok(()) }
//! ```

pub mod container;
mod validate;

use std::path::{Path, PathBuf};

use face_prep::FaceMesh;

use crate::atomic_write::{WriteError, write_atomic};
use crate::model::{FaceModel, PipelineParams};
pub use container::{ContainerError, FORMAT_VERSION, Header, MAGIC};
pub use validate::validate_model;

/// Largest rig file read (1 GiB; a rig of the 13 120-triangle face is a few MB).
pub const MAX_RIG_BYTES: u64 = 1 << 30;

/// Errors saving or loading a cache file.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum CacheError {
    /// The file could not be read.
    #[error("cannot read cache {path}: {source}")]
    Read {
        /// The cache file.
        path: PathBuf,
        /// Underlying I/O error.
        #[source]
        source: std::io::Error,
    },
    /// The file could not be written.
    #[error(transparent)]
    Write(#[from] WriteError),
    /// The file is damaged, of another version, or not a cache at all.
    #[error("{path}: {source}")]
    Container {
        /// The cache file.
        path: PathBuf,
        /// What is wrong with it.
        #[source]
        source: ContainerError,
    },
    /// The file decodes but its content is inconsistent (crafted or from a broken build).
    #[error("{path} is not a valid rig: {reason}")]
    Invalid {
        /// The cache file.
        path: PathBuf,
        /// What is wrong.
        reason: String,
    },
    /// The rig would be larger than a rig file may be ([`MAX_RIG_BYTES`]), so it could not be
    /// read back.
    #[error("{path}: the rig would be {} MiB, over the {} MiB a rig file may hold; simplify the face mesh first", bytes >> 20, MAX_RIG_BYTES >> 20)]
    TooLarge {
        /// The cache file.
        path: PathBuf,
        /// Its size (estimated before computing, or encoded).
        bytes: u64,
    },
    /// The cache was computed for another face mesh.
    #[error("{path} was computed for another face mesh (mesh hash differs)")]
    OtherMesh {
        /// The cache file.
        path: PathBuf,
    },
    /// The cache was computed with other parameters, or by a build whose rig or physics code
    /// differs ([`BUILD_ID`]).
    #[error("{path} was computed with other parameters or by another facebem build")]
    OtherParams {
        /// The cache file.
        path: PathBuf,
    },
}

/// BLAKE3 hash of a face mesh's geometry (positions bit-exact, triangles, input order map).
pub fn mesh_hash(mesh: &FaceMesh) -> [u8; 32] {
    let mut h = blake3::Hasher::new();
    h.update(b"facebem mesh v1");
    h.update(&(mesh.vertices.len() as u64).to_le_bytes());
    for v in &mesh.vertices {
        for c in v.to_array() {
            h.update(&c.to_bits().to_le_bytes());
        }
    }
    h.update(&(mesh.triangles.len() as u64).to_le_bytes());
    for t in &mesh.triangles {
        for i in t {
            h.update(&i.to_le_bytes());
        }
    }
    h.update(&(mesh.input_to_vertex.len() as u64).to_le_bytes());
    for i in &mesh.input_to_vertex {
        h.update(&i.map_or(u32::MAX, |i| i).to_le_bytes());
    }
    *h.finalize().as_bytes()
}

/// Identifies the code that computes a model: a hash of the pipeline's, face-prep's and
/// bem-core's source files, made at build time. Two builds with the same id compute the same
/// model from the same mesh and parameters.
pub const BUILD_ID: &str = env!("FACEBEM_BUILD_ID");

/// BLAKE3 hash of all pipeline parameters (of their postcard encoding) and of [`BUILD_ID`]:
/// a cache is reused only by a build whose rig and physics code is the same.
pub fn params_hash(params: &PipelineParams) -> [u8; 32] {
    let bytes = postcard::to_stdvec(params).unwrap_or_default();
    let mut h = blake3::Hasher::new();
    h.update(&bytes);
    h.update(BUILD_ID.as_bytes());
    *h.finalize().as_bytes()
}

/// Encodes a model as the bytes of a cache file.
pub fn to_bytes(model: &FaceModel) -> Result<Vec<u8>, ContainerError> {
    let header = Header {
        input_hash: mesh_hash(&model.mesh),
        params_hash: params_hash(&model.params),
    };
    container::encode(&header, model)
}

/// Saves `model` to `path` atomically.
pub fn save(path: &Path, model: &FaceModel) -> Result<(), CacheError> {
    let bytes = to_bytes(model).map_err(|source| CacheError::Container {
        path: path.to_path_buf(),
        source,
    })?;
    // What is written can always be read back (issue 36).
    if bytes.len() as u64 > MAX_RIG_BYTES {
        return Err(CacheError::TooLarge {
            path: path.to_path_buf(),
            bytes: bytes.len() as u64,
        });
    }
    write_atomic(path, &bytes)?;
    Ok(())
}

/// A lower bound of the size of `mesh`'s rig file, known before computing it: the neutral
/// positions, the triangles and one displacement per vertex per muscle
/// ([`face_prep::MuscleKind::ALL`]), 8-byte coordinates.
///
/// ```
/// let mesh = facebem::input::default_face().unwrap();
/// let bytes = facebem::cache::rig_size_lower_bound(&mesh);
/// assert!(bytes > 468 * 37 * 24 && bytes < facebem::cache::MAX_RIG_BYTES);
/// ```
pub fn rig_size_lower_bound(mesh: &FaceMesh) -> u64 {
    let per_vertex = 24 * (1 + face_prep::MuscleKind::ALL.len() as u64);
    mesh.vertices.len() as u64 * per_vertex + 12 * mesh.triangles.len() as u64
}

/// Refuses, before computing, a face whose rig file would exceed [`MAX_RIG_BYTES`]
/// ([`rig_size_lower_bound`]).
pub fn check_rig_size(path: &Path, mesh: &FaceMesh) -> Result<(), CacheError> {
    let bytes = rig_size_lower_bound(mesh);
    if bytes > MAX_RIG_BYTES {
        return Err(CacheError::TooLarge {
            path: path.to_path_buf(),
            bytes,
        });
    }
    Ok(())
}

/// Reads a rig file's bytes: a regular file only (a FIFO or device is refused unopened), at
/// most [`MAX_RIG_BYTES`].
fn read_rig_bytes(path: &Path) -> Result<Vec<u8>, CacheError> {
    let limits = face_prep::InputLimits {
        max_file_bytes: MAX_RIG_BYTES,
        ..Default::default()
    };
    face_prep::limits::read_input_file(path, &limits).map_err(|e| CacheError::Read {
        path: path.to_path_buf(),
        source: match e {
            face_prep::PrepError::Io { source, .. } => source,
            other => std::io::Error::other(other.to_string()),
        },
    })
}

/// Loads a cache file, checking magic, version, length and checksum, then the decoded content
/// ([`validate_model`]).
pub fn load(path: &Path) -> Result<FaceModel, CacheError> {
    let bytes = read_rig_bytes(path)?;
    from_bytes(path, &bytes)
}

/// Decodes and checks the bytes of a rig file (`path` is only used in messages).
pub fn from_bytes(path: &Path, bytes: &[u8]) -> Result<FaceModel, CacheError> {
    let (header, model) = decode_checked(path, bytes)?;
    // The header's hashes must describe the payload (else the file was spliced together).
    if header.input_hash != mesh_hash(&model.mesh) {
        return Err(CacheError::OtherMesh {
            path: path.to_path_buf(),
        });
    }
    Ok(model)
}

/// Loads a cache file and checks that it was computed for `mesh` with `params`.
pub fn load_for(
    path: &Path,
    mesh: &FaceMesh,
    params: &PipelineParams,
) -> Result<FaceModel, CacheError> {
    let bytes = read_rig_bytes(path)?;
    // Cheap header check first: a cache for another mesh is rejected without decoding it.
    let header = container::read_header(&bytes).map_err(|source| CacheError::Container {
        path: path.to_path_buf(),
        source,
    })?;
    if header.input_hash != mesh_hash(mesh) {
        return Err(CacheError::OtherMesh {
            path: path.to_path_buf(),
        });
    }
    if header.params_hash != params_hash(params) {
        return Err(CacheError::OtherParams {
            path: path.to_path_buf(),
        });
    }
    let (_, model) = decode_checked(path, &bytes)?;
    if model.mesh != *mesh {
        return Err(CacheError::OtherMesh {
            path: path.to_path_buf(),
        });
    }
    Ok(model)
}

/// Whether `bytes` start like a facebem cache file.
pub fn is_cache(bytes: &[u8]) -> bool {
    bytes.starts_with(&MAGIC)
}

fn decode_checked(path: &Path, bytes: &[u8]) -> Result<(Header, FaceModel), CacheError> {
    let (header, model): (Header, FaceModel) =
        container::decode(bytes).map_err(|source| CacheError::Container {
            path: path.to_path_buf(),
            source,
        })?;
    validate_model(&model).map_err(|reason| CacheError::Invalid {
        path: path.to_path_buf(),
        reason,
    })?;
    Ok((header, model))
}
