//! The precomputed muscle basis and exact posing: `v = v0 + Σ_k s_k · D_k`.

use glam::DVec3;
use serde::{Deserialize, Serialize};

/// Per-muscle displacement fields of every vertex of the user's front-face mesh, for slider = 1,
/// in the user's own coordinate frame and vertex order.
///
/// Because the BEM problem is linear, any pose is an exact linear combination of these fields.
///
/// ```
/// use facebem::MuscleBasis;
/// use glam::DVec3;
/// let basis = MuscleBasis {
///     muscle_ids: vec!["m0".into()],
///     neutral: vec![DVec3::ZERO, DVec3::X],
///     triangles: vec![],
///     displacements: vec![vec![DVec3::Y, DVec3::Z]],
/// };
/// let posed = basis.pose(&[-0.5]).unwrap();
/// assert_eq!(posed[1], DVec3::new(1.0, 0.0, -0.5));
/// ```
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MuscleBasis {
    /// Stable identifier of each muscle (e.g. `zygomaticus_major_l`), one per slider.
    pub muscle_ids: Vec<String>,
    /// Neutral vertex positions (user frame, user vertex order).
    pub neutral: Vec<DVec3>,
    /// Triangles of the front-face mesh, indexing [`MuscleBasis::neutral`].
    pub triangles: Vec<[u32; 3]>,
    /// `displacements[k][v]`: displacement of vertex `v` for slider `k` = 1 (positive = relax).
    pub displacements: Vec<Vec<DVec3>>,
}

/// Errors from posing a basis.
#[derive(Debug, thiserror::Error, PartialEq)]
#[non_exhaustive]
pub enum PoseError {
    /// The slider vector does not have one value per muscle.
    #[error("expected {expected} slider values (one per muscle), got {got}")]
    SliderCount {
        /// Number of muscles in the basis.
        expected: usize,
        /// Number of sliders given.
        got: usize,
    },
    /// A slider value is outside [−1, 1] or not finite.
    #[error("slider {index} ({id}) = {value} is outside [-1, 1]")]
    SliderRange {
        /// Slider index.
        index: usize,
        /// Muscle identifier.
        id: String,
        /// The offending value.
        value: f64,
    },
}

impl MuscleBasis {
    /// Number of muscles (sliders).
    pub fn muscle_count(&self) -> usize {
        self.muscle_ids.len()
    }

    /// Index of the muscle with identifier `id`, if any.
    pub fn muscle_index(&self, id: &str) -> Option<usize> {
        self.muscle_ids
            .iter()
            .position(|m| m.eq_ignore_ascii_case(id))
    }

    /// Checks that `sliders` has one finite value in [−1, 1] per muscle.
    pub fn check_sliders(&self, sliders: &[f64]) -> Result<(), PoseError> {
        if sliders.len() != self.muscle_count() {
            return Err(PoseError::SliderCount {
                expected: self.muscle_count(),
                got: sliders.len(),
            });
        }
        for (index, &value) in sliders.iter().enumerate() {
            if !(-1.0..=1.0).contains(&value) {
                return Err(PoseError::SliderRange {
                    index,
                    id: self.muscle_ids[index].clone(),
                    value,
                });
            }
        }
        Ok(())
    }

    /// Writes the posed positions into `out` (resized to the vertex count). Exact: linear blend.
    pub fn pose_into(&self, sliders: &[f64], out: &mut Vec<DVec3>) -> Result<(), PoseError> {
        self.check_sliders(sliders)?;
        out.clear();
        out.extend_from_slice(&self.neutral);
        for (field, &s) in self.displacements.iter().zip(sliders) {
            if s == 0.0 {
                continue;
            }
            for (p, d) in out.iter_mut().zip(field) {
                *p += s * *d;
            }
        }
        Ok(())
    }

    /// Returns the posed positions for `sliders` (one value in [−1, 1] per muscle).
    pub fn pose(&self, sliders: &[f64]) -> Result<Vec<DVec3>, PoseError> {
        let mut out = Vec::with_capacity(self.neutral.len());
        self.pose_into(sliders, &mut out)?;
        Ok(out)
    }
}
