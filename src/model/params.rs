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
    /// The face's outer contour is a cut facebem made through a head's triangles (a head's
    /// front face, [`face_prep::parts::front_face`]): the mirror-symmetry test of
    /// [`crate::copy::symmetrize`] leaves the outer contour's vertices out, because where such
    /// a cut runs is the head's triangulation (one triangle more or less on either side), not
    /// the face's shape. Default false: a user's own outline is part of the face's shape.
    #[serde(default)]
    pub outline_is_cut: bool,
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
            outline_is_cut: false,
        }
    }
}

/// A pipeline parameter outside its documented range ([`PipelineParams::validate`]).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{name} = {value} is out of range: must be in {range}")]
pub struct ParamError {
    /// The field's path in [`PipelineParams`], e.g. `large_face.target_triangles` or `rig.offset`.
    pub name: String,
    /// Its value as given.
    pub value: String,
    /// The documented range.
    pub range: String,
}

impl PipelineParams {
    /// Documented range of [`PipelineParams::poisson`]: compressible to nearly incompressible
    /// tissue. At 0.5 the Kelvin kernel divides by zero, and close to it the dense system is
    /// ill-conditioned.
    pub const POISSON_RANGE: std::ops::RangeInclusive<f64> = 0.0..=0.49;

    /// Checks every numeric parameter against its documented range before any work:
    /// [`PipelineParams::POISSON_RANGE`], [`LargeFaceParams::validate`],
    /// [`RigParams::validate`] and the quadrature's near factor in [0, 16], depth in [0, 60]
    /// and tolerance in [1e-12, 1]. [`crate::build_face_model`] and [`crate::prepare`] call it
    /// first; a command line calls it before reading the face.
    ///
    /// ```
    /// use facebem::PipelineParams;
    /// assert!(PipelineParams::default().validate().is_ok());
    /// let p = PipelineParams { poisson: 0.5, ..PipelineParams::default() };
    /// assert_eq!(p.validate().unwrap_err().name, "poisson");
    /// ```
    pub fn validate(&self) -> Result<(), ParamError> {
        let err = |name: &str, value: String, range: String| ParamError {
            name: name.to_string(),
            value,
            range,
        };
        let poisson = Self::POISSON_RANGE;
        if !poisson.contains(&self.poisson) {
            let range = format!("[{}, {}]", poisson.start(), poisson.end());
            return Err(err("poisson", format!("{:?}", self.poisson), range));
        }
        self.large_face
            .validate()
            .map_err(|(name, value, range)| err(&format!("large_face.{name}"), value, range))?;
        if let Err(face_prep::PrepError::InvalidParam {
            name,
            value,
            reason,
        }) = self.rig.validate()
        {
            let range = reason.trim_start_matches("must be in ").to_string();
            return Err(err(&format!("rig.{name}"), format!("{value:?}"), range));
        }
        let q = &self.quadrature;
        if !(0.0..=16.0).contains(&q.near_factor) {
            let value = format!("{:?}", q.near_factor);
            return Err(err("quadrature.near_factor", value, "[0, 16]".into()));
        }
        if q.max_depth > 60 {
            let value = q.max_depth.to_string();
            return Err(err("quadrature.max_depth", value, "[0, 60]".into()));
        }
        if !(1e-12..=1.0).contains(&q.tolerance) {
            let value = format!("{:?}", q.tolerance);
            return Err(err("quadrature.tolerance", value, "[1e-12, 1]".into()));
        }
        Ok(())
    }
}
