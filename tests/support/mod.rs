//! Helpers shared by the end-to-end tests.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::Command;

/// The bundled faces, smallest first.
pub const FACES: [&str; 4] = [
    "mediapipe_canonical_4loop.obj",
    "ict_narrow_face_dec2500_4loop.obj",
    "leeperrysmith_face_open_4loop.obj",
    "ict_narrow_face_4loop.obj",
];

/// Path of a bundled face.
pub fn asset(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("assets")
        .join(name)
}

/// Outcome of running the Khronos glTF-Validator.
pub enum Validation {
    /// node is not installed: the caller skips with a message (CI has node).
    NodeMissing,
    /// The validator's JSON report.
    Report(serde_json::Value),
}

/// Runs the Khronos glTF-Validator (npm `gltf-validator`) on `file`, installing it with npm
/// into `target/gltf-validator` (or `$GLTF_VALIDATOR_DIR`) on first use.
pub fn validate_gltf(file: &Path) -> Validation {
    if Command::new("node").arg("--version").output().is_err() {
        return Validation::NodeMissing;
    }
    let dir = std::env::var_os("GLTF_VALIDATOR_DIR").map_or_else(
        || Path::new(env!("CARGO_MANIFEST_DIR")).join("target/gltf-validator"),
        PathBuf::from,
    );
    if !dir
        .join("node_modules/gltf-validator/package.json")
        .exists()
    {
        std::fs::create_dir_all(&dir).unwrap();
        let status = Command::new("npm")
            .args(["install", "--no-audit", "--no-fund", "--prefix"])
            .arg(&dir)
            .arg("gltf-validator")
            .status()
            .expect("node is installed but npm is not");
        assert!(status.success(), "npm install gltf-validator failed");
    }
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/support/validate_gltf.cjs");
    let out = Command::new("node")
        .arg(script)
        .arg(&dir)
        .arg(file)
        .output()
        .expect("cannot run node");
    assert!(
        out.status.success(),
        "validator failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    Validation::Report(serde_json::from_slice(&out.stdout).expect("validator output is JSON"))
}

/// Asserts that a validator report has no errors, printing its messages otherwise.
pub fn assert_valid(file: &Path) {
    match validate_gltf(file) {
        Validation::NodeMissing => {
            eprintln!(
                "SKIPPED glTF-Validator check of {}: node is not installed",
                file.display()
            );
        }
        Validation::Report(report) => {
            let errors = report["issues"]["numErrors"].as_u64();
            assert_eq!(
                errors,
                Some(0),
                "{}: glTF-Validator errors: {}",
                file.display(),
                report["issues"]["messages"]
            );
        }
    }
}
