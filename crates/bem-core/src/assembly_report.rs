//! Quadrature accuracy of an assembly: the off-diagonal blocks that did not reach the tolerance.

/// An element pair whose off-diagonal block did not reach the requested accuracy.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct UnconvergedBlock {
    /// Element whose collocation node is the load point (block row).
    pub row_element: usize,
    /// Element integrated over (block column).
    pub column_element: usize,
    /// Estimated relative error of the block.
    pub estimated_error: f64,
}

/// Quadrature accuracy of an assembly: blocks whose estimated relative error exceeds
/// [`QuadratureParams::tolerance`](crate::QuadratureParams::tolerance) (the collocation point
/// closer to the element than the subdivision's depth limit resolves, e.g. surfaces that nearly
/// touch or cross).
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize, serde::Deserialize)]
pub struct AssemblyReport {
    /// Number of unconverged off-diagonal blocks.
    pub unconverged_blocks: usize,
    /// The one with the largest estimated error (first in column-then-row order on ties).
    pub worst: Option<UnconvergedBlock>,
}

impl AssemblyReport {
    pub(crate) fn note(&mut self, block: UnconvergedBlock) {
        self.unconverged_blocks += 1;
        if self
            .worst
            .is_none_or(|w| block.estimated_error > w.estimated_error)
        {
            self.worst = Some(block);
        }
    }

    pub(crate) fn merge(&mut self, other: &AssemblyReport) {
        self.unconverged_blocks += other.unconverged_blocks;
        if let Some(b) = other.worst
            && self
                .worst
                .is_none_or(|w| b.estimated_error > w.estimated_error)
        {
            self.worst = Some(b);
        }
    }
}
