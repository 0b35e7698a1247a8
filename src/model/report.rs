//! What one precompute measured about the rig: sizes, timings and the health figures the CLI,
//! the viewer and the reports warn about.

use serde::{Deserialize, Serialize};

/// Sizes and timings of one precompute.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PrecomputeReport {
    /// Front triangles of the input face.
    pub input_triangles: usize,
    /// Front triangles simulated (fewer than the input for a simplified large face).
    pub simulated_triangles: usize,
    /// How a large face was simplified ([`crate::copy::simplify`](mod@crate::copy::simplify)); `None` when it was not.
    pub simplify_path: Option<crate::copy::simplify::SimplifyPath>,
    /// Why the edge-collapse copy of a large face was replaced by a remeshed one (it was not a
    /// valid surface, or the rig on it was not trustworthy while the remeshed copy's is);
    /// `None` when it was not. A warning.
    pub copy_fallback: Option<String>,
    /// Boundary elements of the closed shell.
    pub shell_elements: usize,
    /// Unknowns of the dense system (3 per element).
    pub dofs: usize,
    /// Pairs of shell elements that intersect each other. Non-zero means the elastic body is
    /// not a valid solid there (e.g. an input whose lips interpenetrate): the BEM is ill-posed
    /// and responses near those elements are unreliable.
    pub shell_self_intersections: usize,
    /// Largest ratio, over the muscles, of the largest element displacement of a muscle's
    /// response to the largest displacement its pattern prescribes. A linear elastic body held
    /// by its skull stays near 1 (1.00 on MediaPipe, Lee Perry-Smith and the simplified
    /// 2500-triangle ICT face, 1.05 on the simplified 13k ICT face, at default settings); far
    /// above [`SUSPICIOUS_AMPLIFICATION`] the system is near-singular and the responses are not
    /// physical (e.g. front and back surfaces nearly coincident: MediaPipe with offset 0.0005
    /// reaches 60; the ICT faces simulated with their rolled-in eyelids and lips, 3 to 1751).
    pub response_amplification: f64,
    /// Largest ratio, over the force-driven band muscles, of a muscle's largest front motion (the
    /// target its response is scaled to) to the mean motion of the tissue it pulls (traction-
    /// weighted, along the pull). Healthy rigs stay below [`SUSPICIOUS_FORCE_PEAK`]; far above
    /// it a few elements (a strip of slivers, a flap at the lips' knife edge) move much more
    /// than the muscle's own tissue and set its scale, so the rest of the expression is weak.
    pub force_peak_ratio: f64,
    /// The control of [`PrecomputeReport::force_peak_ratio`] (empty when there is none).
    pub force_peak_control: String,
    /// bem-core's estimate of the condition number of the BEM system (columns scaled to unit
    /// 1-norm, [`bem_core::DenseLu::condition_estimate`]); solves above
    /// [`bem_core::DEFAULT_MAX_CONDITION`] are refused.
    pub condition_estimate: f64,
    /// Off-diagonal BEM blocks whose quadrature could not reach the requested accuracy
    /// ([`bem_core::AssemblyReport`]): a collocation point closer to another element than
    /// 1e-4 of its size, i.e. the shell nearly touches or crosses itself there. 0 on the bundled
    /// faces at default settings.
    pub quadrature_unconverged: usize,
    /// Largest estimated relative error among those blocks (0 when there is none).
    pub quadrature_worst_error: f64,
    /// Seconds spent in prep (simplification, rig).
    pub prep_seconds: f64,
    /// Seconds spent in the BEM solve (assembly, factorisation, solves).
    pub solve_seconds: f64,
    /// Seconds spent mapping element results to the user's vertices.
    pub transfer_seconds: f64,
}

/// [`PrecomputeReport::force_peak_ratio`] above this flags a force-driven response whose scale a
/// few elements set. Measured: 0.5-2.6 on the four bundled faces at default settings (every
/// band muscle); ICT 2500 on an 1800-triangle copy, whose upper-lip slivers moved 7-14 mm
/// against the pull, 11 for its left zygomaticus and 15 for its left levator anguli oris.
pub const SUSPICIOUS_FORCE_PEAK: f64 = 4.0;

/// [`PrecomputeReport::response_amplification`] above this flags a near-singular, unphysical
/// solve (healthy rigs measured 1 to 3.2; broken ones 8 to 5000).
pub const SUSPICIOUS_AMPLIFICATION: f64 = 5.0;

impl PrecomputeReport {
    /// Human-readable warnings about the computed rig (empty when nothing is suspicious): shell
    /// self-intersections, near-singular responses and unconverged BEM quadrature. The CLI, the
    /// viewer and [`crate::report::describe`] show them.
    ///
    /// ```
    /// let mut report = facebem::PrecomputeReport::default();
    /// assert!(report.warnings().is_empty());
    /// report.shell_self_intersections = 3;
    /// report.response_amplification = 40.0;
    /// let w = report.warnings();
    /// assert!(w[0].contains("3 pairs of shell elements intersect"));
    /// assert!(w[1].contains("40 times"));
    /// report.quadrature_unconverged = 12;
    /// report.quadrature_worst_error = 0.03;
    /// assert!(report.warnings()[2].contains("12 BEM element pairs"));
    /// report.force_peak_ratio = 11.0;
    /// report.force_peak_control = "zygomaticus_major_l".into();
    /// assert!(report.warnings()[2].starts_with("zygomaticus_major_l's largest motion is 11.0 times"));
    /// ```
    pub fn warnings(&self) -> Vec<String> {
        let mut out = Vec::new();
        if let Some(reason) = &self.copy_fallback {
            out.push(format!("{reason}; simulated on a remeshed copy instead"));
        }
        if self.shell_self_intersections > 0 {
            out.push(format!(
                "{} pairs of shell elements intersect (does the face cross itself, e.g. at the \
                 lips?); responses near them are unreliable",
                self.shell_self_intersections
            ));
        }
        if self.response_amplification > SUSPICIOUS_AMPLIFICATION {
            out.push(format!(
                "a muscle response moves the face {:.0} times more than the muscle itself \
                 (healthy rigs: below {SUSPICIOUS_AMPLIFICATION:.0}); the BEM system is \
                 near-singular, e.g. front and back of the shell nearly touch (check the \
                 shell offset)",
                self.response_amplification
            ));
        }
        if self.force_peak_ratio > SUSPICIOUS_FORCE_PEAK {
            out.push(format!(
                "{}'s largest motion is {:.1} times the mean motion of the tissue it pulls \
                 (healthy rigs: below {SUSPICIOUS_FORCE_PEAK:.0}): a few elements, e.g. slivers \
                 or a flap at the lips, set its scale and the rest of its expression is weak; \
                 try another --target-triangles or --copy remesh",
                self.force_peak_control, self.force_peak_ratio
            ));
        }
        if self.quadrature_unconverged > 0 {
            out.push(format!(
                "{} BEM element pairs are closer than the quadrature resolves (estimated block \
                 error up to {:.1e}): the shell nearly touches itself there (check the shell \
                 offset); responses near them are less accurate",
                self.quadrature_unconverged, self.quadrature_worst_error
            ));
        }
        out
    }
}
