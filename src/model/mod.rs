//! The data model every stage shares: the parameters ([`PipelineParams`]), the computed face
//! ([`FaceModel`]) with its per-vertex muscle basis ([`MuscleBasis`]), the precompute's report
//! ([`PrecomputeReport`]) and the pipeline's error ([`PipelineError`]). The stages import these
//! types; none of them imports the orchestration ([`crate::pipeline`]).

mod basis;
mod closed_eyes;
mod error;
mod params;
mod report;
mod trust;

use face_prep::{FaceMesh, FaceRig};
use glam::DVec3;
use serde::{Deserialize, Serialize};

use crate::copy::Simplified;
use crate::frame::InputFrame;
pub use crate::transfer::SimplifiedFace;

pub use basis::{MuscleBasis, PoseError};
pub use closed_eyes::{CLOSED_EYE_AREA_FRACTION, closed_eyes, eye_openings};
pub use error::PipelineError;
pub use params::{ParamError, PipelineParams};
pub use report::{PrecomputeReport, SUSPICIOUS_AMPLIFICATION, SUSPICIOUS_FORCE_PEAK};
pub use trust::{
    MAX_JAW_MOTION_MM, MAX_MOTION_OUTSIDE_JAW_MM, MAX_MOTION_PER_SHORTENING, distrust,
    shortening_mm,
};

/// A computed face: input mesh, rig, muscle basis and the parameters it was computed with.
///
/// ```no_run
/// use facebem::{build_face_model, Control, PipelineParams};
/// let mesh = face_prep::load_face("assets/mediapipe_canonical_4loop.obj".as_ref()).unwrap();
/// let model = build_face_model(&mesh, &PipelineParams::default(), &Control::new()).unwrap();
/// let happy = facebem::expressions::presets::find("happy").unwrap();
/// let posed = model.pose(&happy.sliders_for(&model.basis.muscle_ids)).unwrap();
/// assert_eq!(posed.len(), mesh.vertices.len());
/// ```
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct FaceModel {
    /// The user's face mesh (input frame, welded).
    pub mesh: FaceMesh,
    /// The original OBJ text when the face came from an OBJ file (for a glTF file, an
    /// equivalent OBJ in its vertex order, [`crate::export::layout::obj_text_of_gltf`]): poses
    /// are written by replacing only its `v` lines, keeping the user's vertex order, UVs and
    /// normals, and glTF exports use its layout.
    pub obj_source: Option<String>,
    /// The rig (canonical frame) the BEM was solved on: of the simplified mesh for a large face.
    pub rig: FaceRig,
    /// The reduced copy that was simulated (rolled-in parts peeled off and/or simplified), if
    /// it is not the whole input.
    pub simplified: Option<SimplifiedFace>,
    /// Per-muscle displacement of every vertex of [`FaceModel::mesh`] at slider = 1, user frame.
    pub basis: MuscleBasis,
    /// `shell_element_response[k][e]`: displacement of shell element `e` of [`FaceModel::rig`]
    /// (at its centroid, canonical frame) for muscle `k` at slider = 1. Skull elements are 0.
    pub shell_element_response: Vec<Vec<DVec3>>,
    /// `shell_vertex_response[k][v]`: the same per shell vertex (area-weighted average of the
    /// adjacent elements), canonical frame; for drawing the whole deformed shell.
    pub shell_vertex_response: Vec<Vec<DVec3>>,
    /// Parameters the model was computed with.
    pub params: PipelineParams,
    /// Sizes and timings.
    pub report: PrecomputeReport,
}

impl FaceModel {
    /// Posed vertex positions (user frame, user vertex order) for one slider per muscle.
    pub fn pose(&self, sliders: &[f64]) -> Result<Vec<DVec3>, PoseError> {
        self.basis.pose(sliders)
    }

    /// Identifiers of the muscles, in slider order.
    pub fn muscle_ids(&self) -> &[String] {
        &self.basis.muscle_ids
    }
}

/// The rig of a face as the pipeline simulates it, with the reduced copy when it is not the
/// whole input.
#[derive(Clone, Debug)]
pub struct PreparedRig {
    /// The front mesh that is simulated (the input mesh, or its reduced copy).
    pub simulated: FaceMesh,
    /// The reduced copy (rolled-in parts peeled off, and/or simplified for a large face), its
    /// vertices a subset of the input's (new points of its surface for a remeshed copy);
    /// `None` when the whole input is simulated.
    pub simplified: Option<Simplified>,
    /// The rig of [`PreparedRig::simulated`] (with `params.muscles` if given).
    pub rig: FaceRig,
    /// Input vertices peeled off with the rolled-in eyelids and lips (they follow the margin
    /// they hang from, [`crate::transfer::Transfer::snap_to_margins`]).
    pub peeled_vertices: Vec<u32>,
    /// How a large face was simplified; `None` when it was not.
    pub simplify_path: Option<crate::copy::simplify::SimplifyPath>,
    /// Why the edge-collapse copy was replaced by a remeshed one; `None` when it was not.
    pub copy_fallback: Option<String>,
    /// The input mesh's loops and canonical frame, found once ([`crate::frame`]).
    pub frame: InputFrame,
}
