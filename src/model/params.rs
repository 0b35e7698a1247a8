//! What determines a [`FaceModel`](super::FaceModel) besides the mesh: the pipeline's parameters.

use face_prep::RigParams;
use serde::{Deserialize, Serialize};

use crate::copy::LargeFaceParams;

/// Everything that determines a [`FaceModel`](super::FaceModel) besides the mesh. Part of the cache key.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PipelineParams {
    /// Rig building: shell offset and thickness, feature boxes, muscle placement.
    pub rig: RigParams,
    /// Poisson ratio ν of the face tissue (nearly incompressible: 0.45 by default). Only ν
    /// matters: with every boundary displacement- or zero-traction-prescribed, displacements
    /// do not depend on the shear modulus.
    pub poisson: f64,
    /// Simulate without the eyelids and lips that roll in behind the eye and mouth contours
    /// ([`crate::copy::rolled_in`]); their vertices follow the nearest simulated point. Default true.
    pub peel_rolled_in: bool,
    /// Simplification of faces too large for a dense solve.
    pub large_face: LargeFaceParams,
    /// Quadrature of the BEM's off-diagonal blocks (adaptive subdivision of near pairs).
    pub quadrature: bem_core::QuadratureParams,
    /// Muscles to use instead of the automatically placed ones (e.g. read from an edited
    /// muscle file; their element indices refer to the shell [`prep_rig`](crate::prep_rig) builds).
    pub muscles: Option<Vec<face_prep::Muscle>>,
    /// Feature boxes to use instead of the automatic ones (canonical frame, see
    /// [`face_prep::FeatureBoxes`]): muscles and skull are placed from them. With `muscles`
    /// set too, the boxes decide the skull and `muscles` the muscles.
    pub boxes: Option<face_prep::FeatureBoxes>,
}

impl Default for PipelineParams {
    fn default() -> Self {
        PipelineParams {
            rig: RigParams::default(),
            poisson: 0.45,
            peel_rolled_in: true,
            large_face: LargeFaceParams::default(),
            quadrature: bem_core::QuadratureParams::default(),
            muscles: None,
            boxes: None,
        }
    }
}
