//! Computes `FACEBEM_BUILD_ID`: a hash of the source code that computes a face model (this
//! package's `src/`, and `crates/bem-core/src` and `crates/face-prep/src` when built in the
//! workspace). The cache mixes it into its parameter hash, so a cache written by a build whose
//! physics or rig code differs is recomputed instead of silently reused.

use std::hash::{Hash, Hasher};
use std::path::{Path, PathBuf};

fn collect(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            collect(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

fn main() {
    let root = PathBuf::from(std::env::var_os("CARGO_MANIFEST_DIR").unwrap_or_default());
    let dirs = [
        root.join("src"),
        root.join("crates/bem-core/src"),
        root.join("crates/face-prep/src"),
    ];
    let mut files = Vec::new();
    for dir in &dirs {
        println!("cargo:rerun-if-changed={}", dir.display());
        collect(dir, &mut files);
    }
    files.retain(|f| !f.starts_with(root.join("src/bin")));
    files.sort();
    // SipHash with fixed keys: stable for a given toolchain, which is all a cache key needs.
    #[allow(deprecated)]
    let mut hasher = std::hash::SipHasher::new();
    for file in &files {
        file.strip_prefix(&root).unwrap_or(file).hash(&mut hasher);
        std::fs::read(file).unwrap_or_default().hash(&mut hasher);
    }
    println!("cargo:rustc-env=FACEBEM_BUILD_ID={:016x}", hasher.finish());
}
