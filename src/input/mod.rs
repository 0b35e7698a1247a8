//! Conveniences for applications: open a face file or a saved rig, compute-and-cache a face,
//! the bundled default face.

pub mod heads;

use std::path::{Path, PathBuf};

use face_prep::{FaceMesh, InputLimits};

use crate::cache::{self, CacheError};
use crate::control::Control;
use crate::model::{FaceModel, PipelineError, PipelineParams};
use crate::pipeline::build_face_model;

/// File name of the bundled default face (the smallest asset, MediaPipe canonical face).
pub const DEFAULT_FACE_NAME: &str = "mediapipe_canonical_4loop.obj";

/// File names, under the repository's `assets/`, of the four bundled faces the tests and the
/// measuring examples run on: MediaPipe's canonical face (the default), the decimated and the
/// full ICT-FaceKit face, and the Lee Perry-Smith scan.
///
/// ```
/// assert_eq!(facebem::input::BUNDLED_FACES[0], facebem::input::DEFAULT_FACE_NAME);
/// ```
pub const BUNDLED_FACES: [&str; 4] = [
    DEFAULT_FACE_NAME,
    "ict_narrow_face_dec2500_4loop.obj",
    "leeperrysmith_face_open_4loop.obj",
    "ict_narrow_face_4loop.obj",
];

/// The faces a measuring tool runs on: the face files among `args` (those ending in `.obj`), or,
/// when there are none, `default_faces` under `assets_dir`.
///
/// ```
/// use std::path::{Path, PathBuf};
/// use facebem::input::{BUNDLED_FACES, faces_from_args};
/// let args = ["--only".to_owned(), "happy".to_owned(), "me.obj".to_owned()];
/// assert_eq!(faces_from_args(&args, Path::new("assets"), &BUNDLED_FACES), vec![PathBuf::from("me.obj")]);
/// let bundled = faces_from_args(&[], Path::new("assets"), &BUNDLED_FACES);
/// assert_eq!(bundled.len(), 4);
/// assert_eq!(bundled[0], Path::new("assets").join(BUNDLED_FACES[0]));
/// ```
pub fn faces_from_args(args: &[String], assets_dir: &Path, default_faces: &[&str]) -> Vec<PathBuf> {
    let given: Vec<PathBuf> = args
        .iter()
        .filter(|a| a.ends_with(".obj"))
        .map(PathBuf::from)
        .collect();
    if given.is_empty() {
        default_faces.iter().map(|f| assets_dir.join(f)).collect()
    } else {
        given
    }
}

/// OBJ text of the bundled default face, compiled into the library.
pub const DEFAULT_FACE_OBJ: &str = include_str!("../../assets/mediapipe_canonical_4loop.obj");

/// Errors opening a face or rig.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum OpenError {
    /// The file could not be read.
    #[error("cannot read {path}: {source}")]
    Read {
        /// The file.
        path: PathBuf,
        /// Underlying I/O error.
        #[source]
        source: std::io::Error,
    },
    /// The face mesh is invalid.
    #[error("{path}: {source}")]
    Face {
        /// The file.
        path: PathBuf,
        /// What is wrong with it.
        #[source]
        source: Box<face_prep::PrepError>,
    },
    /// The rig/cache file is invalid.
    #[error(transparent)]
    Cache(#[from] CacheError),
    /// Computing the model failed.
    #[error(transparent)]
    Pipeline(#[from] PipelineError),
}

/// What a file turned out to hold.
#[derive(Debug)]
// Exhaustive on purpose: a caller handles every outcome (a new one must not be ignored).
pub enum Opened {
    /// A face mesh that still needs [`build_face_model`]; `obj_source` is its layout as OBJ
    /// text (see [`read_face`]).
    Face {
        /// The validated mesh.
        mesh: FaceMesh,
        /// The OBJ text (for exports in the user's own layout), `None` for glTF input.
        obj_source: Option<String>,
    },
    /// A saved rig (cache file) with its basis, ready to pose.
    Model(Box<FaceModel>),
}

/// Opens `path`: a facebem rig/cache file (recognised by its magic bytes, whatever its name),
/// an OBJ, or a glTF/GLB face.
///
/// Only a regular file is opened (a FIFO or device is refused without blocking on it), and
/// face meshes are held to the default [`InputLimits`]; see [`OpenOptions`] for others.
pub fn open(path: &Path) -> Result<Opened, OpenError> {
    OpenOptions::default().open(path)
}

/// How [`open`] reads a file: the size limits for face meshes (rig files are read up to
/// [`cache::MAX_RIG_BYTES`], or the face limit if that is larger).
///
/// ```
/// use facebem::input::{OpenError, OpenOptions};
/// use face_prep::InputLimits;
/// let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
///     .join("assets/mediapipe_canonical_4loop.obj");
/// let small = OpenOptions { limits: InputLimits { max_triangles: 100, ..InputLimits::default() } };
/// assert!(matches!(small.open(&path), Err(OpenError::Face { .. })));
/// assert!(OpenOptions::default().open(&path).is_ok());
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct OpenOptions {
    /// Size limits of a face mesh file and its mesh.
    pub limits: InputLimits,
}

impl OpenOptions {
    /// Opens `path` (see [`open`]).
    pub fn open(&self, path: &Path) -> Result<Opened, OpenError> {
        let limits = &self.limits;
        let rig_limits = InputLimits {
            max_file_bytes: limits.max_file_bytes.max(cache::MAX_RIG_BYTES),
            ..*limits
        };
        let bytes = read_bytes(path, &rig_limits)?;
        if cache::is_cache(&bytes) {
            return Ok(Opened::Model(Box::new(cache::from_bytes(path, &bytes)?)));
        }
        let (mesh, obj_source) = face_from_bytes(path, &bytes, limits)?;
        Ok(Opened::Face { mesh, obj_source })
    }
}

/// Reads a face mesh file (OBJ, glTF, GLB), keeping its layout as OBJ text for exports: the
/// file itself for OBJ, an equivalent OBJ (`v`/`vt`/`vn`/`f` in the glTF's vertex order,
/// [`crate::export::layout::obj_text_of_gltf`]) for glTF.
pub fn read_face(path: &Path) -> Result<(FaceMesh, Option<String>), OpenError> {
    let limits = InputLimits::default();
    let bytes = read_bytes(path, &limits)?;
    face_from_bytes(path, &bytes, &limits)
}

fn read_bytes(path: &Path, limits: &InputLimits) -> Result<Vec<u8>, OpenError> {
    face_prep::limits::read_input_file(path, limits).map_err(|e| match e {
        face_prep::PrepError::Io { source, .. } => OpenError::Read {
            path: path.to_path_buf(),
            source,
        },
        face_prep::PrepError::NotAFile { .. } => OpenError::Read {
            path: path.to_path_buf(),
            source: std::io::Error::other("not a regular file"),
        },
        other => OpenError::Face {
            path: path.to_path_buf(),
            source: Box::new(other),
        },
    })
}

fn face_from_bytes(
    path: &Path,
    bytes: &[u8],
    limits: &InputLimits,
) -> Result<(FaceMesh, Option<String>), OpenError> {
    let face_err = |source| OpenError::Face {
        path: path.to_path_buf(),
        source: Box::new(source),
    };
    let is_obj = path
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("obj"));
    if is_obj {
        let mesh = FaceMesh::from_obj_bytes(bytes, limits).map_err(face_err)?;
        Ok((mesh, Some(String::from_utf8_lossy(bytes).into_owned())))
    } else {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .unwrap_or("")
            .to_ascii_lowercase();
        if ext != "gltf" && ext != "glb" {
            return Err(face_err(face_prep::PrepError::UnsupportedExtension {
                path: path.to_path_buf(),
                extension: ext,
            }));
        }
        // Kept as an equivalent OBJ text (the glTF's vertex order, TEXCOORD_0 and normals), so
        // poses and glTF exports keep the user's layout as they do for OBJ input.
        let data =
            face_prep::gltf_face_data(bytes, path.parent(), None, limits).map_err(face_err)?;
        let mesh = FaceMesh::from_triangles(&data.positions, &data.triangles).map_err(face_err)?;
        Ok((mesh, Some(crate::export::layout::obj_text_of_gltf(&data))))
    }
}

/// Whether a cache was used or the model was computed.
#[derive(Clone, Debug, PartialEq)]
// Exhaustive on purpose: a caller handles every outcome (a new one must not be ignored).
pub enum CacheStatus {
    /// The cache file matched and was loaded.
    Loaded,
    /// The model was computed and saved; `reason` says why the cache was not used.
    Computed {
        /// Why the cache could not be used (missing, corrupt, other mesh or parameters).
        reason: String,
        /// Set if saving the new cache failed (the model is still returned).
        save_error: Option<String>,
    },
}

/// Loads `cache_path` if it holds the model of `mesh` with `params`; otherwise computes the
/// model and saves it there (atomically). A failure to save does not fail the call.
pub fn load_or_build(
    mesh: &FaceMesh,
    obj_source: Option<String>,
    params: &PipelineParams,
    cache_path: &Path,
    control: &Control,
) -> Result<(FaceModel, CacheStatus), PipelineError> {
    let reason = match cache::load_for(cache_path, mesh, params) {
        Ok(mut model) => {
            // The cache is keyed by geometry: the layout (UVs, normals, comments) is this file's.
            model.obj_source = obj_source;
            // Used now: the last to be pruned.
            let _ = std::fs::File::options()
                .append(true)
                .open(cache_path)
                .and_then(|f| f.set_modified(std::time::SystemTime::now()));
            return Ok((model, CacheStatus::Loaded));
        }
        Err(e) => e.to_string(),
    };
    let mut model = build_face_model(mesh, params, control)?;
    model.obj_source = obj_source;
    let save_error = cache::save(cache_path, &model).err().map(|e| e.to_string());
    if save_error.is_none()
        && let Some(dir) = cache_path.parent()
    {
        prune_cache(dir, CACHE_KEEP);
    }
    Ok((model, CacheStatus::Computed { reason, save_error }))
}

/// Where the rig of `mesh` computed with `params` is cached in `dir`: one file per mesh and
/// parameter set, `<dir>/<mesh hash>-<params hash>.rig` (so going back to earlier parameters
/// reloads instantly). The viewer and the command line share it; `dir` is normally
/// [`default_cache_dir`].
///
/// ```
/// use facebem::input::{cache_file_for, default_face};
/// let mesh = default_face().unwrap();
/// let p = facebem::PipelineParams::default();
/// let path = cache_file_for(std::path::Path::new("/tmp"), &mesh, &p);
/// assert!(facebem::input::is_cache_file_name(path.file_name().unwrap().to_str().unwrap()));
/// ```
pub fn cache_file_for(dir: &Path, mesh: &FaceMesh, params: &PipelineParams) -> PathBuf {
    let hex = |bytes: &[u8]| bytes.iter().map(|b| format!("{b:02x}")).collect::<String>();
    let mesh_hash = cache::mesh_hash(mesh);
    let params_hash = cache::params_hash(params);
    dir.join(format!(
        "{}-{}.rig",
        hex(&mesh_hash[..12]),
        hex(&params_hash[..6])
    ))
}

/// Whether `name` is a cache file's name ([`cache_file_for`]): 24 hex digits, `-`, 12 hex
/// digits, `.rig`. Only such files are ever pruned.
pub fn is_cache_file_name(name: &str) -> bool {
    let hex = |s: &str, n: usize| s.len() == n && s.bytes().all(|b| b.is_ascii_hexdigit());
    name.strip_suffix(".rig")
        .and_then(|stem| stem.split_once('-'))
        .is_some_and(|(mesh, params)| hex(mesh, 24) && hex(params, 12))
}

/// Rig files kept in a cache folder ([`prune_cache`]): a large face's rig is tens of MB.
pub const CACHE_KEEP: usize = 32;

/// Deletes all but the `keep` most recently written or used cache files
/// ([`is_cache_file_name`]) in `dir`; returns how many were deleted. Other files are never
/// touched; errors are ignored (it is a cache).
pub fn prune_cache(dir: &Path, keep: usize) -> usize {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return 0;
    };
    let mut files: Vec<(std::time::SystemTime, PathBuf)> = entries
        .flatten()
        .filter(|e| e.file_name().to_str().is_some_and(is_cache_file_name))
        .filter_map(|e| Some((e.metadata().ok()?.modified().ok()?, e.path())))
        .collect();
    files.sort_by_key(|f| std::cmp::Reverse(f.0));
    files
        .iter()
        .skip(keep)
        .filter(|(_, path)| std::fs::remove_file(path).is_ok())
        .count()
}

/// Where the default face's cache lives: `$XDG_CACHE_HOME/facebem/` or `~/.cache/facebem/`
/// (the system temporary directory if neither is set).
pub fn default_cache_dir() -> PathBuf {
    if let Some(dir) = std::env::var_os("XDG_CACHE_HOME").filter(|d| !d.is_empty()) {
        return PathBuf::from(dir).join("facebem");
    }
    if let Some(home) = std::env::var_os("HOME").filter(|d| !d.is_empty()) {
        return PathBuf::from(home).join(".cache").join("facebem");
    }
    std::env::temp_dir().join("facebem")
}

/// The bundled default face mesh.
pub fn default_face() -> Result<FaceMesh, OpenError> {
    FaceMesh::from_obj_str(DEFAULT_FACE_OBJ).map_err(|source| OpenError::Face {
        path: PathBuf::from(DEFAULT_FACE_NAME),
        source: Box::new(source),
    })
}

/// The default face's model with default parameters: loaded from `cache_dir` (default:
/// [`default_cache_dir`]) or computed and cached there.
pub fn default_model(
    cache_dir: Option<&Path>,
    control: &Control,
) -> Result<(FaceModel, CacheStatus), OpenError> {
    let mesh = default_face()?;
    let dir = cache_dir.map_or_else(default_cache_dir, Path::to_path_buf);
    // Best effort: if the directory cannot be created, saving reports it in CacheStatus.
    let _ = std::fs::create_dir_all(&dir);
    let path = dir.join("mediapipe_canonical.rig");
    Ok(load_or_build(
        &mesh,
        Some(DEFAULT_FACE_OBJ.to_string()),
        &PipelineParams::default(),
        &path,
        control,
    )?)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The rig cache keeps the newest [`CACHE_KEEP`] cache files and never touches a file
    /// whose name is not a cache file's.
    #[test]
    fn pruning_keeps_the_newest_cache_files_and_nothing_else_is_touched() {
        let dir = tempfile::tempdir().unwrap();
        let now = std::time::SystemTime::now();
        let mut names = vec![];
        for k in 0..5u64 {
            let name = format!("{:024x}-{:012x}.rig", k, k);
            let path = dir.path().join(&name);
            let file = std::fs::File::create(&path).unwrap();
            // File k was used k minutes ago.
            file.set_modified(now - std::time::Duration::from_secs(60 * k))
                .unwrap();
            names.push(name);
        }
        for other in ["face.rig", "notes.txt", "0123-45.rig"] {
            std::fs::write(dir.path().join(other), b"x").unwrap();
        }
        assert_eq!(prune_cache(dir.path(), 2), 3);
        let mut left: Vec<String> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        left.sort();
        let mut want = vec![
            names[0].clone(),
            names[1].clone(),
            "0123-45.rig".into(),
            "face.rig".into(),
            "notes.txt".into(),
        ];
        want.sort();
        assert_eq!(left, want);
        assert!(!is_cache_file_name("face.rig") && is_cache_file_name(&names[3]));
    }
}
