//! Size limits for untrusted input files, checked before anything proportional to a count read
//! from the file is allocated.
//!
//! A face file is untrusted input (downloaded meshes, files dropped on the viewer): every
//! loader checks the file's size and the counts it declares against an [`InputLimits`] before
//! reading or allocating, so a small file cannot ask for gigabytes.
//!
//! ```
//! use face_prep::InputLimits;
//! let limits = InputLimits::default();
//! assert!(limits.check_count("triangles", 13_120, limits.max_triangles).is_ok());
//! assert!(limits.check_count("triangles", 1 << 40, limits.max_triangles).is_err());
//! ```

use crate::error::PrepError;

#[doc(inline)]
pub use crate::error::MAX_COORDINATE;

/// Size limits of input files. The defaults are far above any face the dense BEM can use
/// (faces above 1500 triangles are simulated on a simplified copy) and far below what a
/// machine can allocate.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct InputLimits {
    /// Bytes of one input file (OBJ, glTF/GLB with its buffers, rig, muscle file). Default
    /// 256 MiB.
    pub max_file_bytes: u64,
    /// Vertex positions of a face mesh (OBJ `v` lines, glTF POSITION elements). Default 2 M.
    pub max_positions: usize,
    /// Triangles of a face mesh (after triangulation). Default 2 M.
    pub max_triangles: usize,
    /// Muscles in a muscle file. Default 256 (the standard rig has 10).
    pub max_muscles: usize,
}

impl Default for InputLimits {
    fn default() -> Self {
        InputLimits {
            max_file_bytes: 256 << 20,
            max_positions: 2_000_000,
            max_triangles: 2_000_000,
            max_muscles: 256,
        }
    }
}

impl InputLimits {
    /// `Err(PrepError::TooLarge)` if `count` of `what` exceeds `limit`.
    pub fn check_count(
        &self,
        what: &'static str,
        count: u64,
        limit: usize,
    ) -> Result<(), PrepError> {
        if count > limit as u64 {
            return Err(PrepError::TooLarge {
                what,
                count,
                limit: limit as u64,
            });
        }
        Ok(())
    }

    /// `Err(PrepError::TooLarge)` if a file of `bytes` bytes exceeds [`InputLimits::max_file_bytes`].
    pub(crate) fn check_file_bytes(&self, bytes: u64) -> Result<(), PrepError> {
        if bytes > self.max_file_bytes {
            return Err(PrepError::TooLarge {
                what: "file bytes",
                count: bytes,
                limit: self.max_file_bytes,
            });
        }
        Ok(())
    }
}

/// Reads a whole input file safely: only a regular file (a FIFO, device or directory is refused
/// without being opened, so it cannot block), at most `limits.max_file_bytes` bytes (checked
/// from its size before reading, and again while reading in case it grows).
///
/// ```
/// let err = face_prep::limits::read_input_file(
///     "/dev/zero".as_ref(),
///     &face_prep::InputLimits::default(),
/// )
/// .unwrap_err();
/// assert!(err.to_string().contains("not a regular file"), "{err}");
/// ```
pub fn read_input_file(path: &std::path::Path, limits: &InputLimits) -> Result<Vec<u8>, PrepError> {
    use std::io::Read;
    let io = |source| PrepError::Io {
        path: path.to_owned(),
        source,
    };
    let meta = std::fs::metadata(path).map_err(io)?;
    if !meta.is_file() {
        return Err(PrepError::NotAFile {
            path: path.to_owned(),
        });
    }
    limits.check_file_bytes(meta.len())?;
    let file = std::fs::File::open(path).map_err(io)?;
    let mut bytes = Vec::new();
    file.take(limits.max_file_bytes.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(io)?;
    limits.check_file_bytes(bytes.len() as u64)?;
    Ok(bytes)
}

/// A position must be finite and within [`MAX_COORDINATE`] of the origin.
pub(crate) fn check_coordinates(input_index: usize, p: glam::DVec3) -> Result<(), PrepError> {
    if !p.is_finite() {
        return Err(PrepError::NonFiniteVertex {
            input_index,
            position: p.to_array(),
        });
    }
    if p.abs().max_element() > MAX_COORDINATE {
        return Err(PrepError::CoordinateTooLarge {
            input_index,
            position: p.to_array(),
        });
    }
    Ok(())
}
