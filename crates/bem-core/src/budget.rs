//! The memory a dense solve needs, checked up front against a budget.
//!
//! With overcommitting allocators a too-large K or set of right-hand sides is not refused when it
//! is allocated but kills the process when its pages are first touched, half-way through the
//! assembly. So [`crate::LinearSystem::assemble`] adds up what the assembly and the solve will
//! hold at their peak ([`MemoryEstimate`]) and refuses to start with
//! [`BemError::OverBudget`] when it exceeds [`crate::SolveParams::memory_budget_bytes`] (by
//! default the memory the system reports available, `MemAvailable` in `/proc/meminfo`).

use crate::BemError;

/// Right-hand sides solved per block: bounds the solve's scratch copy to 8 × rows × this bytes.
pub(crate) const SOLVE_BLOCK: usize = 256;

/// Peak heap of one assembly + factorisation + solve, in bytes, by part.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MemoryEstimate {
    /// K (factorised in place: the LU takes no more), 8·size².
    pub matrix: u64,
    /// The right-hand sides (overwritten by the solutions), 8·size·load cases.
    pub rhs: u64,
    /// Assembly accumulators alive at once: one per thread (row sums and right-hand-side
    /// contributions of one column range), or the solve's scratch copy of one block of
    /// right-hand sides, whichever is larger (they are not alive together).
    pub buffers: u64,
    /// The f32 copy of K the mixed-precision LU factorises ([`crate::MixedLu`]), 4·size²; 0
    /// for the f64 LU in place.
    pub factor32: u64,
}

impl MemoryEstimate {
    /// Estimate for `elements` elements (`size` unknowns, 3·elements or 3·elements + 6),
    /// `rhs_count` load cases and `threads` assembly threads.
    ///
    /// ```
    /// let e = bem_core::MemoryEstimate::new(3000, 9000, 10, 2);
    /// assert_eq!(e.matrix, 8 * 9000 * 9000);
    /// assert_eq!(e.rhs, 8 * 9000 * 10);
    /// assert!(e.total() < e.matrix + e.matrix / 100);
    /// ```
    pub fn new(elements: usize, size: usize, rhs_count: usize, threads: usize) -> Self {
        let (n, size, r, t) = (
            elements as u64,
            size as u64,
            rhs_count as u64,
            threads.max(1) as u64,
        );
        let dof = 3 * n;
        let per_thread = 72 * n + 8 * dof * r;
        let solve_scratch = 8 * size * r.min(SOLVE_BLOCK as u64);
        Self {
            matrix: 8u64.saturating_mul(size).saturating_mul(size),
            rhs: 8 * size * r,
            buffers: (t * per_thread).max(solve_scratch),
            factor32: 0,
        }
    }

    /// The estimate with the mixed-precision LU's f32 copy of K ([`crate::Precision::Mixed`]).
    ///
    /// ```
    /// let e = bem_core::MemoryEstimate::new(3000, 9000, 10, 2);
    /// assert_eq!(e.with_f32_factor().total() - e.total(), 4 * 9000 * 9000);
    /// ```
    pub fn with_f32_factor(self) -> Self {
        let size = (self.matrix / 8).isqrt();
        Self {
            factor32: 4u64.saturating_mul(size).saturating_mul(size),
            ..self
        }
    }

    /// Sum of the parts.
    pub fn total(&self) -> u64 {
        self.matrix
            .saturating_add(self.rhs)
            .saturating_add(self.buffers)
            .saturating_add(self.factor32)
    }

    /// Fails with [`BemError::OverBudget`] when the total exceeds `budget` (`None`: the memory
    /// the operating system reports available; no check where it reports nothing).
    pub(crate) fn check(&self, budget: Option<u64>) -> Result<(), BemError> {
        let Some(budget) = budget.or_else(available_bytes) else {
            return Ok(());
        };
        let needed = self.total();
        if needed > budget {
            return Err(BemError::OverBudget {
                needed_bytes: needed,
                budget_bytes: budget,
                matrix_bytes: self.matrix,
                rhs_bytes: self.rhs,
            });
        }
        Ok(())
    }
}

/// `MemAvailable` of `/proc/meminfo` in bytes (Linux), `None` elsewhere or when unreadable.
fn available_bytes() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib.saturating_mul(1024))
}
