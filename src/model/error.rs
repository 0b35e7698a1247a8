//! The pipeline's error: one variant per stage that can fail.

use crate::frame::FrameError;
use crate::solve::SolveError;
use crate::transfer::TransferError;

/// Errors of the pipeline.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PipelineError {
    /// Rig building failed (invalid face, features not found, ...).
    #[error("rig: {0}")]
    Prep(#[from] face_prep::PrepError),
    /// The BEM solve failed.
    #[error("BEM solve: {0}")]
    Bem(#[from] bem_core::BemError),
    /// The shell is not a valid closed surface for the BEM.
    #[error("shell: {0}")]
    Shell(#[from] bem_core::MeshError),
    /// Simplifying the large face failed.
    #[error("simplifying the large face: {0}")]
    Simplify(#[from] crate::copy::SimplifyError),
    /// The face's loops or canonical frame could not be found on the input mesh.
    #[error("frame: {0}")]
    Frame(#[from] FrameError),
    /// The simulated copy's responses could not be carried to the input mesh.
    #[error("transfer: {0}")]
    Transfer(#[from] TransferError),
    /// A parameter is outside its documented range ([`crate::PipelineParams::validate`]).
    #[error("parameter {0}")]
    Param(#[from] crate::model::params::ParamError),
    /// The rig has no muscles.
    #[error("the rig has no muscles")]
    NoMuscles,
    /// The caller cancelled the computation.
    #[error("cancelled")]
    Cancelled,
}

impl From<SolveError> for PipelineError {
    /// The solve stage's errors keep the pipeline's variants callers already match on.
    fn from(e: SolveError) -> PipelineError {
        match e {
            SolveError::Bem(e) => PipelineError::Bem(e),
            SolveError::Shell(e) => PipelineError::Shell(e),
            SolveError::Cancelled => PipelineError::Cancelled,
        }
    }
}
