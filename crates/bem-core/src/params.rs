//! Parameters of a solve: quadrature, rigid modes, condition limit, memory budget, precision.

use crate::QuadratureParams;

/// Default of [`SolveParams::max_condition`]: solves whose estimated condition number (columns
/// scaled to unit 1-norm, [`crate::DenseLu::condition_estimate`]) exceeds 1e8 are refused.
///
/// Measured: healthy problems 3e2 (two held spheres) to 8e3 (the bundled faces: MediaPipe 2.5e3,
/// ICT 2500 7.8e3, Lee Perry-Smith 6.3e3); a paper-thin face shell (MediaPipe at offset 0.0005,
/// responses 27× the muscles' motion) 8.9e5; ICT simulated with its rolled-in lids and lips
/// 4.9e4; a sphere that nothing holds next to a fixed one 1.5e9 (at 80 elements each; the
/// finer the mesh the more exactly singular). At κ = 1e8 the LU alone may cost 8 of 16 digits
/// and the discretisation error is amplified accordingly.
pub const DEFAULT_MAX_CONDITION: f64 = 1e8;

/// Parameters of a solve.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct SolveParams {
    /// Quadrature of the off-diagonal blocks.
    pub quadrature: QuadratureParams,
    /// Pure-traction problems: reject (default) or fix the rigid modes.
    pub rigid_modes: RigidModes,
    /// Largest accepted condition estimate ([`crate::DenseLu::condition_estimate`]) of K; above
    /// it the solve fails with [`BemError::IllConditioned`](crate::BemError::IllConditioned).
    /// Default [`DEFAULT_MAX_CONDITION`]; `f64::INFINITY` accepts anything.
    pub max_condition: f64,
    /// Memory the assembly and solve may use, in bytes ([`crate::MemoryEstimate`]); above it
    /// [`LinearSystem::assemble`](crate::LinearSystem::assemble) fails with
    /// [`BemError::OverBudget`](crate::BemError::OverBudget) before allocating K.
    /// `None` (default): the memory the operating system reports available (Linux
    /// `MemAvailable`; unchecked where unknown).
    pub memory_budget_bytes: Option<u64>,
    /// Precision of the LU ([`Precision::Mixed`] by default).
    pub precision: Precision,
}

/// Precision of the dense LU.
///
/// ```
/// assert_eq!(bem_core::SolveParams::default().precision, bem_core::Precision::Mixed);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[non_exhaustive]
pub enum Precision {
    /// The LU in f32 with the answer refined to f64 accuracy ([`crate::MixedLu`]), falling
    /// back to [`Precision::Double`] where that does not converge or the f32 copy does not fit
    /// the memory budget: about half the factorisation time, 1.5 times K's memory.
    #[default]
    Mixed,
    /// The LU in f64, in place ([`crate::DenseLu`]).
    Double,
}

impl Default for SolveParams {
    fn default() -> Self {
        Self {
            quadrature: QuadratureParams::default(),
            rigid_modes: RigidModes::default(),
            max_condition: DEFAULT_MAX_CONDITION,
            memory_budget_bytes: None,
            precision: Precision::Mixed,
        }
    }
}

/// What to do with a problem that prescribes no displacement anywhere (rigid-body modes).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[non_exhaustive]
pub enum RigidModes {
    /// Reject it with [`BemError::PureTraction`](crate::BemError::PureTraction).
    #[default]
    Reject,
    /// Fix the gauge: the six rigid modes are removed from the displacement by six Lagrange
    /// multipliers (area-weighted mean translation and rotation of the boundary are zero).
    /// Only used when no displacement is prescribed.
    Fix,
}
