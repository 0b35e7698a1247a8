//! Progress reporting and cancellation of a precompute, shared between the caller's thread
//! (UI, CLI progress bar) and the worker.

use std::fmt;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

/// The stages of [`crate::build_face_model`], in order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Stage {
    /// Simplification (large faces), orientation, features, shell, muscles and skull.
    Prep,
    /// Assembly of the dense BEM matrix K.
    Assembly,
    /// LU factorisation of K.
    Factorisation,
    /// One solve per muscle (all right-hand sides together).
    Solves,
    /// Frame change and transfer of the simulated copy's responses to the user's mesh.
    Transfer,
    /// The passes that settle the responses on the user's mesh ([`crate::settle`]).
    Settle,
}

impl Stage {
    /// Short lower-case label for progress bars.
    pub fn label(self) -> &'static str {
        match self {
            Stage::Prep => "prep",
            Stage::Assembly => "assembly",
            Stage::Factorisation => "factorisation",
            Stage::Solves => "solves",
            Stage::Transfer => "transfer",
            Stage::Settle => "settle",
        }
    }
}

impl fmt::Display for Stage {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.label())
    }
}

/// One progress report: `done` of `total` units of `stage` are finished.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Progress {
    /// The running stage.
    pub stage: Stage,
    /// Units done.
    pub done: u64,
    /// Units in this stage (≥ 1).
    pub total: u64,
}

type ProgressFn = dyn Fn(Progress) + Send + Sync;

/// Progress callback + cancellation flag. Cheap to clone; clones share the flag.
///
/// ```
/// use facebem::{Control, Stage};
/// use std::sync::{Arc, Mutex};
/// let seen = Arc::new(Mutex::new(Vec::new()));
/// let log = seen.clone();
/// let control = Control::new().with_progress(move |p| log.lock().unwrap().push(p.stage));
/// control.report(Stage::Prep, 0, 1);
/// assert_eq!(*seen.lock().unwrap(), vec![Stage::Prep]);
/// assert!(!control.is_cancelled());
/// control.clone().cancel();
/// assert!(control.is_cancelled());
/// ```
#[derive(Clone, Default)]
pub struct Control {
    cancelled: Arc<AtomicBool>,
    progress: Option<Arc<ProgressFn>>,
}

impl fmt::Debug for Control {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Control")
            .field("cancelled", &self.is_cancelled())
            .field("progress", &self.progress.is_some())
            .finish()
    }
}

impl Control {
    /// A control without progress callback, not cancelled.
    pub fn new() -> Control {
        Control::default()
    }

    /// Sets the progress callback (called from worker threads).
    pub fn with_progress(mut self, f: impl Fn(Progress) + Send + Sync + 'static) -> Control {
        self.progress = Some(Arc::new(f));
        self
    }

    /// Asks the running precompute to stop; it returns [`crate::PipelineError::Cancelled`] at
    /// its next check.
    pub fn cancel(&self) {
        self.cancelled.store(true, Ordering::Relaxed);
    }

    /// Whether [`Control::cancel`] was called.
    pub fn is_cancelled(&self) -> bool {
        self.cancelled.load(Ordering::Relaxed)
    }

    /// The shared cancellation flag (handed to bem-core's own control).
    pub(crate) fn flag(&self) -> &AtomicBool {
        &self.cancelled
    }

    /// Reports progress to the callback, if any.
    pub fn report(&self, stage: Stage, done: u64, total: u64) {
        if let Some(f) = &self.progress {
            f(Progress {
                stage,
                done: done.min(total.max(1)),
                total: total.max(1),
            });
        }
    }
}
