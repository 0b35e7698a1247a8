//! Safe output files: atomic writes that never destroy an input or replace anything but a
//! regular file, and the checks a command makes on its output path before computing anything.
//!
//! [`write_atomic`] writes a temporary `.facebem-<pid>-<random>.tmp` next to the target,
//! flushes it to disk and renames it over the target, so readers (and a process killed at any
//! moment) see either the old file or the complete new one. The new file gets the replaced
//! file's mode, or the mode the umask gives (0644 under umask 022). A symlink, FIFO, device or
//! folder at the target is refused and left untouched. Temporary files of ours left behind by a
//! killed writer (their process is gone and they have not changed for ten minutes, or they are
//! older than a day) are removed from the folder on the next write there.
//!
//! ```
//! let dir = tempfile::tempdir().unwrap();
//! let out = dir.path().join("a.txt");
//! face_prep::atomic_write::write_atomic(&out, b"hello").unwrap();
//! assert_eq!(std::fs::read(&out).unwrap(), b"hello");
//! ```

use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::{Duration, SystemTime};

/// Failure to write a file atomically.
#[derive(Debug, thiserror::Error)]
#[error("cannot write {path}: {source}")]
pub struct WriteError {
    /// The file that could not be written.
    pub path: PathBuf,
    /// The underlying I/O error.
    #[source]
    pub source: std::io::Error,
}

/// Prefix of our temporary files.
const TMP_PREFIX: &str = ".facebem-";
/// Suffix of our temporary files.
const TMP_SUFFIX: &str = ".tmp";
/// Temporary files of ours older than this are stale even if their process id is alive again.
const STALE_AFTER: Duration = Duration::from_secs(24 * 3600);
/// A temporary file whose process id is not visible here is stale only once it has not changed
/// for this long: a writer in another PID namespace (a container sharing the folder) is not
/// visible in our `/proc`, but a live writer changes its file continuously (regression
/// `a_fresh_temporary_of_an_unseen_process_is_kept`, issue 36).
const QUIET_AFTER: Duration = Duration::from_secs(600);

/// What kind of thing is at `path` if it is not a regular file (`None`: a regular file or
/// nothing).
fn non_regular_kind(meta: &std::fs::Metadata) -> Option<&'static str> {
    let t = meta.file_type();
    if t.is_file() {
        return None;
    }
    if t.is_symlink() {
        return Some("a symbolic link");
    }
    if t.is_dir() {
        return Some("a folder");
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return Some("a FIFO");
        }
        if t.is_block_device() || t.is_char_device() {
            return Some("a device");
        }
        if t.is_socket() {
            return Some("a socket");
        }
    }
    Some("not a regular file")
}

/// Writes `bytes` to `path` atomically (see the module docs): readers see either the old file
/// or the complete new one; the new file keeps the replaced file's mode, or gets the umask's;
/// anything at `path` that is not a regular file is refused and left untouched.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), WriteError> {
    let wrap = |source| WriteError {
        path: path.to_path_buf(),
        source,
    };
    let existing = match std::fs::symlink_metadata(path) {
        Ok(meta) => {
            if let Some(kind) = non_regular_kind(&meta) {
                return Err(wrap(std::io::Error::other(format!(
                    "it is {kind}; only a regular file is replaced"
                ))));
            }
            Some(meta.permissions())
        }
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => None,
        Err(e) => return Err(wrap(e)),
    };
    let dir = folder_of(path);
    let prefix = format!("{TMP_PREFIX}{}-", std::process::id());
    let mut builder = tempfile::Builder::new();
    builder.prefix(&prefix).suffix(TMP_SUFFIX);
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        // open(2) applies the umask to 0666, as for any new file.
        builder.permissions(std::fs::Permissions::from_mode(0o666));
    }
    let mut tmp = builder.tempfile_in(dir).map_err(wrap)?;
    remove_stale_temporaries(dir, tmp.path());
    if let Some(perm) = existing {
        tmp.as_file().set_permissions(perm).map_err(wrap)?;
    }
    tmp.write_all(bytes).map_err(wrap)?;
    tmp.as_file().sync_all().map_err(wrap)?;
    // On any error above, dropping `tmp` removes the temporary file.
    tmp.persist(path).map_err(|e| wrap(e.error))?;
    Ok(())
}

fn folder_of(path: &Path) -> &Path {
    match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    }
}

/// Removes `.facebem-<pid>-*.tmp` files in `dir` owned by the owner of `ours` whose process is
/// gone (Linux: no `/proc/<pid>`) and that have not changed for [`QUIET_AFTER`], or that are
/// older than a day. Best effort: errors are ignored.
fn remove_stale_temporaries(dir: &Path, ours: &Path) {
    let Ok(our_meta) = std::fs::metadata(ours) else {
        return;
    };
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    let now = SystemTime::now();
    for entry in entries.flatten().take(100_000) {
        let path = entry.path();
        if path == ours {
            continue;
        }
        let name = entry.file_name();
        let Some(name) = name.to_str() else { continue };
        let Some(pid) = name
            .strip_prefix(TMP_PREFIX)
            .and_then(|r| r.strip_suffix(TMP_SUFFIX))
            .and_then(|r| r.split_once('-'))
            .and_then(|(pid, _)| pid.parse::<u32>().ok())
        else {
            continue;
        };
        let Ok(meta) = entry.metadata() else { continue };
        if !meta.is_file() || !same_owner(&meta, &our_meta) {
            continue;
        }
        let age = meta
            .modified()
            .ok()
            .and_then(|m| now.duration_since(m).ok())
            .unwrap_or_default();
        if age > STALE_AFTER || (age > QUIET_AFTER && !process_alive(pid)) {
            let _ = std::fs::remove_file(&path);
        }
    }
}

#[cfg(unix)]
fn same_owner(a: &std::fs::Metadata, b: &std::fs::Metadata) -> bool {
    use std::os::unix::fs::MetadataExt;
    a.uid() == b.uid()
}

#[cfg(not(unix))]
fn same_owner(_: &std::fs::Metadata, _: &std::fs::Metadata) -> bool {
    true
}

/// Whether process `pid` exists (Linux `/proc`; elsewhere assumed alive, so only age counts).
fn process_alive(pid: u32) -> bool {
    if pid == std::process::id() {
        return true;
    }
    let proc = Path::new("/proc");
    if proc.join("self").exists() {
        proc.join(pid.to_string()).exists()
    } else {
        true
    }
}

/// Why an output path is refused by [`check_output`].
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum OutputPathError {
    /// The extension does not match the format that is written.
    #[error("output {path}: {what} must end in {}", expected.join(" or "))]
    Extension {
        /// The output path.
        path: PathBuf,
        /// What is written (e.g. "a pose OBJ").
        what: &'static str,
        /// Accepted extensions, with the dot.
        expected: Vec<String>,
    },
    /// The output's folder does not exist.
    #[error("output {path}: folder {} does not exist", folder.display())]
    NoFolder {
        /// The output path.
        path: PathBuf,
        /// Its folder.
        folder: PathBuf,
    },
    /// The output's folder exists but a file cannot be created in it (read-only, no permission).
    #[error("output {path}: cannot write in folder {}: {source}", folder.display())]
    NotWritable {
        /// The output path.
        path: PathBuf,
        /// Its folder.
        folder: PathBuf,
        /// Why a file cannot be created there.
        #[source]
        source: std::io::Error,
    },
    /// The path itself cannot name a file (too long, or ending in a separator).
    #[error("output {path} cannot be written: {source}")]
    Unusable {
        /// The output path.
        path: PathBuf,
        /// Why.
        #[source]
        source: std::io::Error,
    },
    /// Something that is not a regular file is at the output path.
    #[error("output {path} is {kind}; only a regular file is replaced")]
    NotRegular {
        /// The output path.
        path: PathBuf,
        /// What is there.
        kind: &'static str,
    },
    /// The output is one of the inputs (same file, possibly through a hard link).
    #[error("output {path} is the input {}: it would be destroyed", input.display())]
    IsInput {
        /// The output path.
        path: PathBuf,
        /// The input it coincides with.
        input: PathBuf,
    },
}

/// Checks an output path before any computation: its extension is one of `extensions`
/// (case-insensitive, without the dot), its folder exists and a file can be created in it,
/// nothing but a regular file is there, and it is not (a hard link of) any of `inputs` or any
/// file they read ([`crate::input::files_read_by`]: a glTF's external buffers and images).
///
/// ```
/// use face_prep::atomic_write::{OutputPathError, check_output};
/// let dir = tempfile::tempdir().unwrap();
/// let input = dir.path().join("face.rig");
/// std::fs::write(&input, b"rig").unwrap();
/// let same = check_output(&input, &[&input], &["rig"], "a rig file");
/// assert!(matches!(same, Err(OutputPathError::IsInput { .. })));
/// let wrong = check_output(&dir.path().join("out.obj"), &[&input], &["glb", "gltf"], "glTF");
/// assert!(matches!(wrong, Err(OutputPathError::Extension { .. })));
/// assert!(check_output(&dir.path().join("out.glb"), &[&input], &["glb", "gltf"], "glTF").is_ok());
/// ```
pub fn check_output(
    path: &Path,
    inputs: &[&Path],
    extensions: &[&str],
    what: &'static str,
) -> Result<(), OutputPathError> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    if !extensions.iter().any(|e| e.eq_ignore_ascii_case(&ext)) {
        return Err(OutputPathError::Extension {
            path: path.to_path_buf(),
            what,
            expected: extensions.iter().map(|e| format!(".{e}")).collect(),
        });
    }
    let folder = folder_of(path);
    if !folder.is_dir() {
        return Err(OutputPathError::NoFolder {
            path: path.to_path_buf(),
            folder: folder.to_path_buf(),
        });
    }
    // A probe file, removed on drop: a read-only folder is found now, not after the solve
    // (regression `a_read_only_output_folder_is_refused_before_computing`, issue 36).
    let probe = tempfile::Builder::new()
        .prefix(&format!("{TMP_PREFIX}{}-", std::process::id()))
        .suffix(TMP_SUFFIX)
        .tempfile_in(folder);
    if let Err(source) = probe {
        return Err(OutputPathError::NotWritable {
            path: path.to_path_buf(),
            folder: folder.to_path_buf(),
            source,
        });
    }
    // A path naming a folder (`out.glb/`) or one the system cannot use (a name over 255
    // bytes) is refused now, not when the file is written after the solve (issue 36).
    if path.as_os_str().as_encoded_bytes().ends_with(b"/") {
        return Err(OutputPathError::Unusable {
            path: path.to_path_buf(),
            source: std::io::Error::other("it ends in a path separator"),
        });
    }
    let meta = match std::fs::symlink_metadata(path) {
        Ok(meta) => meta,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(()),
        Err(source) => {
            return Err(OutputPathError::Unusable {
                path: path.to_path_buf(),
                source,
            });
        }
    };
    if let Some(kind) = non_regular_kind(&meta) {
        return Err(OutputPathError::NotRegular {
            path: path.to_path_buf(),
            kind,
        });
    }
    let read: Vec<PathBuf> = inputs
        .iter()
        .flat_map(|input| crate::input::files_read_by(input))
        .collect();
    let all = inputs
        .iter()
        .copied()
        .chain(read.iter().map(PathBuf::as_path));
    for input in all {
        if let Ok(im) = std::fs::metadata(input)
            && same_file(&meta, &im, path, input)
        {
            return Err(OutputPathError::IsInput {
                path: path.to_path_buf(),
                input: input.to_path_buf(),
            });
        }
    }
    Ok(())
}

#[cfg(unix)]
fn same_file(a: &std::fs::Metadata, b: &std::fs::Metadata, _: &Path, _: &Path) -> bool {
    use std::os::unix::fs::MetadataExt;
    a.dev() == b.dev() && a.ino() == b.ino()
}

#[cfg(not(unix))]
fn same_file(_: &std::fs::Metadata, _: &std::fs::Metadata, a: &Path, b: &Path) -> bool {
    match (std::fs::canonicalize(a), std::fs::canonicalize(b)) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn replaces_existing_file_and_leaves_no_temporaries() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.txt");
        write_atomic(&path, b"first").unwrap();
        write_atomic(&path, b"second").unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"second");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    #[test]
    fn missing_directory_is_an_error_naming_the_path() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("no/such/dir/out.txt");
        let err = write_atomic(&path, b"x").unwrap_err();
        assert!(err.to_string().contains("out.txt"), "{err}");
    }

    #[cfg(unix)]
    #[test]
    fn stale_temporaries_of_dead_processes_are_removed_live_ones_kept() {
        let dir = tempfile::tempdir().unwrap();
        // pid 0 never names a user process; our own pid is alive.
        let dead = dir.path().join(".facebem-0-abc.tmp");
        let fresh_dead = dir.path().join(".facebem-0-fresh.tmp");
        let alive = dir
            .path()
            .join(format!(".facebem-{}-abc.tmp", std::process::id()));
        let foreign = dir.path().join(".other-0-abc.tmp");
        for p in [&dead, &fresh_dead, &alive, &foreign] {
            std::fs::write(p, b"partial").unwrap();
        }
        let quiet = SystemTime::now() - QUIET_AFTER - Duration::from_secs(60);
        for p in [&dead, &alive, &foreign] {
            let file = std::fs::File::options().write(true).open(p).unwrap();
            file.set_modified(quiet).unwrap();
        }
        write_atomic(&dir.path().join("out.bin"), b"x").unwrap();
        assert!(!dead.exists());
        assert!(alive.exists());
        assert!(foreign.exists());
        assert!(
            fresh_dead.exists(),
            "a file changed a moment ago may be written now"
        );
    }

    /// Regression (issue 36): a temporary file of a writer in another PID namespace (its pid
    /// not in our `/proc`) was removed while it was still being written. Recently changed, it
    /// is kept whatever its pid.
    #[test]
    fn a_fresh_temporary_of_an_unseen_process_is_kept() {
        let dir = tempfile::tempdir().unwrap();
        let writing = dir.path().join(".facebem-999999999-abc.tmp");
        std::fs::write(&writing, b"still being written").unwrap();
        write_atomic(&dir.path().join("out.bin"), b"x").unwrap();
        assert_eq!(std::fs::read(&writing).unwrap(), b"still being written");
    }
}
