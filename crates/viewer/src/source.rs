//! Opening face files for the viewer (the neutral mesh shown while the rig is being built).

use std::path::{Path, PathBuf};

use facebem::MuscleBasis;
use glam::DVec3;

/// Why a face file could not be opened. Shown to the user; the app keeps running.
#[derive(Debug, thiserror::Error)]
pub enum OpenError {
    /// The file does not exist or cannot be read.
    #[error("cannot read {path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The extension is none of the supported formats.
    #[error("{path}: unsupported file type (expected .obj, .gltf, .glb or a saved rig)")]
    UnsupportedType {
        /// The file.
        path: PathBuf,
    },
    /// The OBJ parser rejected the file.
    #[error("{path}: not a valid OBJ file: {message}")]
    Obj {
        /// The file.
        path: PathBuf,
        /// The parser's message.
        message: String,
    },
    /// The file parsed but holds no triangle.
    #[error("{path}: contains no triangles")]
    NoTriangles {
        /// The file.
        path: PathBuf,
    },
    /// A vertex coordinate is NaN or infinite.
    #[error("{path}: vertex {vertex} has a non-finite coordinate")]
    NonFinite {
        /// The file.
        path: PathBuf,
        /// Index of the vertex (0-based, after merging objects).
        vertex: usize,
    },
}

/// The bundled default face (MediaPipe canonical face, 852 triangles).
pub fn default_face_path() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/mediapipe_canonical_4loop.obj")
}

/// Reads the triangles of a face file as a muscle-less [`MuscleBasis`] (the neutral mesh), so
/// the face can be shown before its rig is solved.
pub fn load_neutral(path: &Path) -> Result<MuscleBasis, OpenError> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
        .unwrap_or_default();
    match ext.as_str() {
        "obj" => load_obj(path),
        _ => Err(OpenError::UnsupportedType {
            path: path.to_owned(),
        }),
    }
}

fn load_obj(path: &Path) -> Result<MuscleBasis, OpenError> {
    std::fs::metadata(path).map_err(|source| OpenError::Io {
        path: path.to_owned(),
        source,
    })?;
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ignore_points: true,
        ignore_lines: true,
    };
    let (models, _materials) = tobj::load_obj(path, &options).map_err(|e| OpenError::Obj {
        path: path.to_owned(),
        message: e.to_string(),
    })?;
    let mut neutral = Vec::new();
    let mut triangles = Vec::new();
    for model in &models {
        let base = neutral.len() as u32;
        let m = &model.mesh;
        neutral.extend(
            m.positions
                .chunks_exact(3)
                .map(|p| DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64)),
        );
        triangles.extend(
            m.indices
                .chunks_exact(3)
                .map(|t| [t[0] + base, t[1] + base, t[2] + base]),
        );
    }
    if let Some(vertex) = neutral.iter().position(|p| !p.is_finite()) {
        return Err(OpenError::NonFinite {
            path: path.to_owned(),
            vertex,
        });
    }
    if triangles.is_empty() {
        return Err(OpenError::NoTriangles {
            path: path.to_owned(),
        });
    }
    Ok(MuscleBasis {
        muscle_ids: Vec::new(),
        neutral,
        triangles,
        displacements: Vec::new(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_face_loads_with_its_852_triangles() {
        let basis = load_neutral(&default_face_path()).unwrap();
        assert_eq!(basis.triangles.len(), 852);
        let n = basis.neutral.len() as u32;
        assert!(basis.triangles.iter().flatten().all(|&i| i < n));
    }

    #[test]
    fn garbage_and_missing_files_are_errors_naming_the_file() {
        let dir = tempfile::tempdir().unwrap();
        let bad = dir.path().join("bad.obj");
        std::fs::write(&bad, "v 1 2 3\nf 1 2 9\n").unwrap();
        let err = load_neutral(&bad).unwrap_err().to_string();
        assert!(err.contains("bad.obj"), "{err}");
        let missing = dir.path().join("missing.obj");
        assert!(matches!(load_neutral(&missing), Err(OpenError::Io { .. })));
        let txt = dir.path().join("face.txt");
        assert!(matches!(
            load_neutral(&txt),
            Err(OpenError::UnsupportedType { .. })
        ));
    }
}
