//! Progress reporting and cancellation.

use std::sync::atomic::{AtomicBool, Ordering};

use crate::BemError;

/// Stage of a solve.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Stage {
    /// Column-block assembly of K and the right-hand sides (`done`/`total` = element columns).
    Assembly,
    /// Dense LU factorisation (`done`/`total` = columns factorised, reported per panel).
    Factorisation,
    /// Triangular solves for all right-hand sides (`total` = number of right-hand sides).
    Solve,
}

/// One progress report.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Progress {
    /// Current stage.
    pub stage: Stage,
    /// Work units done in this stage.
    pub done: usize,
    /// Work units of this stage.
    pub total: usize,
}

/// Progress callback and cancellation flag for long computations. `Control::default()` does neither.
///
/// The callback may be called from worker threads; cancellation is checked between column blocks of
/// the assembly, between panels of the LU (every [`crate::dense::LU_PANEL`] columns) and between
/// stages.
#[derive(Clone, Copy, Default)]
pub struct Control<'a> {
    /// When set to `true`, the computation stops and returns [`BemError::Cancelled`].
    pub cancel: Option<&'a AtomicBool>,
    /// Called with progress reports.
    pub progress: Option<&'a (dyn Fn(Progress) + Sync)>,
}

impl std::fmt::Debug for Control<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Control")
            .field("cancel", &self.cancel)
            .field("progress", &self.progress.map(|_| "callback"))
            .finish()
    }
}

impl Control<'_> {
    /// Whether cancellation was requested.
    pub fn is_cancelled(&self) -> bool {
        self.cancel.is_some_and(|c| c.load(Ordering::Relaxed))
    }

    /// `Err(Cancelled)` when cancellation was requested.
    pub fn check(&self) -> Result<(), BemError> {
        if self.is_cancelled() {
            Err(BemError::Cancelled)
        } else {
            Ok(())
        }
    }

    /// Sends a progress report, if a callback is set.
    pub fn report(&self, stage: Stage, done: usize, total: usize) {
        if let Some(p) = self.progress {
            p(Progress { stage, done, total });
        }
    }
}
