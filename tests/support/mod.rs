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

/// Outcome of running a node tool (the Khronos glTF-Validator, three.js).
pub enum Validation {
    /// node is not installed: the caller skips with a message (CI has node).
    NodeMissing,
    /// The tool's JSON report.
    Report(serde_json::Value),
}

/// Serialises the one-time `npm ci` between test threads of one binary.
static VALIDATOR_INSTALL: std::sync::Mutex<()> = std::sync::Mutex::new(());

/// Runs the Khronos glTF-Validator (npm `gltf-validator`, pinned by
/// `tests/gltf-validator/package-lock.json`) on `file`. `.ci/run` installs it with `npm ci`;
/// elsewhere the first test that needs it does (or set `$GLTF_VALIDATOR_DIR` to a directory
/// holding `node_modules/gltf-validator`). With `FACEBEM_REQUIRE_GLTF_VALIDATOR=1` (CI) a
/// missing node is a failure instead of a skip.
pub fn validate_gltf(file: &Path) -> Validation {
    run_node_script("validate_gltf.cjs", file)
}

/// Loads `file` with three.js's GLTFLoader in node (npm `three`, pinned by the same
/// `tests/gltf-validator/package-lock.json`) and returns what a three.js app gets (see
/// `tests/support/three_load.mjs`).
pub fn load_with_threejs(file: &Path) -> Validation {
    run_node_script("three_load.mjs", file)
}

/// Runs `tests/support/<script> <npm dir> <file>` with node and parses its JSON output.
fn run_node_script(script: &str, file: &Path) -> Validation {
    if Command::new("node").arg("--version").output().is_err() {
        assert!(
            std::env::var_os("FACEBEM_REQUIRE_GLTF_VALIDATOR").is_none(),
            "FACEBEM_REQUIRE_GLTF_VALIDATOR is set but node is not installed"
        );
        return Validation::NodeMissing;
    }
    let dir = std::env::var_os("GLTF_VALIDATOR_DIR").map_or_else(
        || Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/gltf-validator"),
        PathBuf::from,
    );
    {
        let _guard = VALIDATOR_INSTALL
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner());
        let installed = ["gltf-validator", "three"].iter().all(|p| {
            dir.join("node_modules")
                .join(p)
                .join("package.json")
                .exists()
        });
        if !installed {
            let status = Command::new("npm")
                .args(["ci", "--no-audit", "--no-fund"])
                .current_dir(&dir)
                .status()
                .expect("node is installed but npm is not");
            assert!(status.success(), "npm ci in {} failed", dir.display());
        }
    }
    let script = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/support")
        .join(script);
    let out = Command::new("node")
        .arg(&script)
        .arg(&dir)
        .arg(file)
        .output()
        .expect("cannot run node");
    assert!(
        out.status.success(),
        "{} failed: {}",
        script.display(),
        String::from_utf8_lossy(&out.stderr)
    );
    Validation::Report(serde_json::from_slice(&out.stdout).expect("node script output is JSON"))
}

/// Asserts that a validator report has no errors and no warnings, printing its messages
/// otherwise (infos and hints are allowed).
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
            assert_eq!(
                report["issues"]["numWarnings"].as_u64(),
                Some(0),
                "{}: glTF-Validator warnings: {}",
                file.display(),
                report["issues"]["messages"]
            );
        }
    }
}
