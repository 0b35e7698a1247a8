//! Shared by the real-face tests: the four faces of `assets/` and their rigs.

use face_prep::{FaceMesh, FaceRig, RigParams, load_face};
use std::path::PathBuf;

/// (file, vertices, triangles) as listed in `assets/README.md`.
pub const FACES: [(&str, usize, usize); 4] = [
    ("mediapipe_canonical_4loop.obj", 468, 852),
    ("ict_narrow_face_dec2500_4loop.obj", 1297, 2500),
    ("leeperrysmith_face_open_4loop.obj", 2395, 4595),
    ("ict_narrow_face_4loop.obj", 6706, 13120),
];

/// Path of a file of `assets/`.
pub fn asset(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets")
        .join(name)
}

/// Default rig parameters with the thesis muscle model: these tests pin the thesis's chains
/// (scale-free, so a similarity transform keeps them); the anatomical model is tested in the
/// root crate's `tests/anatomical_muscles.rs`.
pub fn thesis() -> RigParams {
    RigParams {
        muscle_model: face_prep::muscle_model::MuscleModel::Thesis,
        ..RigParams::default()
    }
}

/// Face `name` of `assets/` and its rig with [`thesis`] parameters.
pub fn rig_of(name: &str) -> (FaceMesh, FaceRig) {
    let face = load_face(&asset(name)).unwrap();
    let rig = FaceRig::build(&face, &thesis()).unwrap();
    (face, rig)
}
