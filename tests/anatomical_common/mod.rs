//! Helpers shared by the anatomical muscle tests (`tests/anatomical_muscles.rs`,
//! `tests/anatomical_symmetry.rs`): each test binary computes each bundled face's default model
//! once and shares it between its tests.

use std::sync::OnceLock;

use face_prep::MuscleKind;
use facebem::report::measure::FaceLandmarks;
use facebem::{Control, FaceModel, PipelineParams, build_face_model};
use glam::DVec3;

use crate::support;

static MODELS: [OnceLock<FaceModel>; 4] = [const { OnceLock::new() }; 4];

/// The default model of bundled face `face` ([`support::FACES`]), computed once per test binary.
pub fn model(face: usize) -> &'static FaceModel {
    MODELS[face].get_or_init(|| {
        let mesh = face_prep::load_face(&support::asset(support::FACES[face])).unwrap();
        build_face_model(&mesh, &PipelineParams::default(), &Control::new()).unwrap()
    })
}

/// The landmarks of a model.
pub fn landmarks(m: &FaceModel) -> FaceLandmarks {
    FaceLandmarks::of(m).expect("four loops")
}

/// Displacement field (input frame) of muscle `kind` at full contraction (slider −1).
pub fn contraction(m: &FaceModel, kind: MuscleKind) -> Vec<DVec3> {
    let k = m.basis.muscle_index(kind.id()).unwrap();
    m.basis.displacements[k].iter().map(|d| -*d).collect()
}

/// Largest displacement of a field in mm.
pub fn max_mm(lm: &FaceLandmarks, field: &[DVec3]) -> f64 {
    field.iter().map(|d| d.length()).fold(0.0, f64::max) * lm.mm_per_unit
}
