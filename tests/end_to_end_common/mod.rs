//! Helpers shared by the end-to-end tests (`tests/end_to_end.rs`, `tests/pipeline_runs.rs`):
//! the thesis parameters and canonical-frame measures of a model.
#![allow(dead_code)] // each test binary uses some of them

use face_prep::MuscleKind;
use facebem::{FaceModel, PipelineParams};
use glam::{DMat3, DVec3};

/// Default parameters with the thesis muscle model.
pub fn thesis_params() -> PipelineParams {
    let mut params = PipelineParams::default();
    params.rig.muscle_model = face_prep::muscle_model::MuscleModel::Thesis;
    params
}

/// Index of muscle `kind` in the model's basis.
pub fn muscle(model: &FaceModel, kind: MuscleKind) -> usize {
    model
        .basis
        .muscle_index(kind.id())
        .unwrap_or_else(|| panic!("muscle {} missing", kind.id()))
}

/// Linear part of canonical_from_input (displacements are vectors).
pub fn to_canonical(model: &FaceModel) -> DMat3 {
    model.rig.canonical_from_input.matrix3
}

/// Canonical positions of the user's vertices.
pub fn canonical_positions(model: &FaceModel) -> Vec<DVec3> {
    model
        .mesh
        .vertices
        .iter()
        .map(|&p| model.rig.canonical_from_input.transform_point3(p))
        .collect()
}

/// Index of the user vertex closest to canonical point `p`.
pub fn nearest(points: &[DVec3], p: DVec3) -> usize {
    (0..points.len())
        .min_by(|&a, &b| {
            points[a]
                .distance_squared(p)
                .total_cmp(&points[b].distance_squared(p))
        })
        .unwrap_or(0)
}

/// Canonical displacement of user vertex `v` for slider `s` of muscle `k`.
pub fn canon_disp(model: &FaceModel, k: usize, v: usize, s: f64) -> DVec3 {
    to_canonical(model) * (s * model.basis.displacements[k][v])
}
