//! Background jobs (loading, rig preparation, BEM solve) that never block the UI thread:
//! a worker thread, a progress value, a cancel flag and a one-shot result channel.

use std::sync::atomic::{AtomicBool, AtomicU32, Ordering};
use std::sync::mpsc::{self, Receiver, TryRecvError};
use std::sync::{Arc, Mutex};

/// Shared between the worker and the UI: progress (0…1), current stage and cancellation.
#[derive(Debug, Default)]
pub struct JobControl {
    fraction_bits: AtomicU32,
    stage: Mutex<String>,
    cancelled: AtomicBool,
    repaint: Mutex<Option<egui::Context>>,
}

impl JobControl {
    /// Reports progress `fraction` (clamped to 0…1) in stage `stage`, and asks for a repaint.
    pub fn report(&self, stage: &str, fraction: f32) {
        let f = if fraction.is_finite() {
            fraction.clamp(0.0, 1.0)
        } else {
            0.0
        };
        self.fraction_bits.store(f.to_bits(), Ordering::Relaxed);
        if let Ok(mut s) = self.stage.lock()
            && *s != stage
        {
            stage.clone_into(&mut s);
        }
        self.request_repaint();
    }

    /// Last reported fraction (0…1).
    pub fn fraction(&self) -> f32 {
        f32::from_bits(self.fraction_bits.load(Ordering::Relaxed))
    }

    /// Last reported stage.
    pub fn stage(&self) -> String {
        self.stage.lock().map(|s| s.clone()).unwrap_or_default()
    }

    /// Asks the worker to stop at its next check.
    pub fn cancel(&self) {
        self.cancelled.store(true, Ordering::Relaxed);
    }

    /// Whether [`JobControl::cancel`] was called.
    pub fn is_cancelled(&self) -> bool {
        self.cancelled.load(Ordering::Relaxed)
    }

    fn request_repaint(&self) {
        if let Ok(ctx) = self.repaint.lock()
            && let Some(ctx) = ctx.as_ref()
        {
            ctx.request_repaint();
        }
    }
}

/// Outcome of a finished job.
pub type JobResult<T> = Result<T, String>;

/// A running background job producing a `T`.
///
/// ```
/// use viewer::job::Job;
/// let mut job = Job::spawn("add", None, |ctl| {
///     ctl.report("adding", 0.5);
///     Ok(1 + 1)
/// });
/// let result = loop {
///     if let Some(r) = job.poll() { break r; }
///     std::thread::yield_now();
/// };
/// assert_eq!(result, Ok(2));
/// ```
#[derive(Debug)]
pub struct Job<T> {
    label: String,
    control: Arc<JobControl>,
    receiver: Receiver<JobResult<T>>,
}

impl<T: Send + 'static> Job<T> {
    /// Starts `work` on a new thread. `repaint` (if given) is asked to repaint whenever progress
    /// is reported and when the job finishes, so the UI notices without polling in a busy loop.
    pub fn spawn(
        label: impl Into<String>,
        repaint: Option<egui::Context>,
        work: impl FnOnce(&Arc<JobControl>) -> JobResult<T> + Send + 'static,
    ) -> Self {
        let control = Arc::new(JobControl {
            repaint: Mutex::new(repaint),
            ..JobControl::default()
        });
        let (sender, receiver) = mpsc::channel();
        let worker_control = Arc::clone(&control);
        let label = label.into();
        let spawned = std::thread::Builder::new()
            .name(format!("facebem job: {label}"))
            .spawn(move || {
                let result = work(&worker_control);
                // The receiver may be gone (job replaced); nothing to do then.
                let _ = sender.send(result);
                worker_control.request_repaint();
            });
        if let Err(e) = spawned {
            let (sender, failed) = mpsc::channel();
            let _ = sender.send(Err(format!("could not start a worker thread: {e}")));
            return Job {
                label,
                control,
                receiver: failed,
            };
        }
        Job {
            label,
            control,
            receiver,
        }
    }

    /// The result, once the worker is done (never blocks). A worker that panicked yields an error.
    pub fn poll(&mut self) -> Option<JobResult<T>> {
        match self.receiver.try_recv() {
            Ok(r) => Some(r),
            Err(TryRecvError::Empty) => None,
            Err(TryRecvError::Disconnected) => Some(Err(format!(
                "{}: the worker stopped unexpectedly",
                self.label
            ))),
        }
    }

    /// What the job does (shown next to its progress bar).
    pub fn label(&self) -> &str {
        &self.label
    }

    /// Progress, stage and cancellation shared with the worker.
    pub fn control(&self) -> &JobControl {
        &self.control
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn wait<T: Send + 'static>(job: &mut Job<T>) -> JobResult<T> {
        loop {
            if let Some(r) = job.poll() {
                return r;
            }
            std::thread::sleep(std::time::Duration::from_millis(1));
        }
    }

    #[test]
    fn cancellation_reaches_the_worker_and_progress_is_clamped() {
        let (go_tx, go_rx) = mpsc::channel::<()>();
        let mut job = Job::spawn("spin", None, move |ctl| {
            ctl.report("waiting", 7.0);
            let _ = go_rx.recv();
            if ctl.is_cancelled() {
                Err("cancelled".to_owned())
            } else {
                Ok(())
            }
        });
        job.control().cancel();
        go_tx.send(()).unwrap();
        assert_eq!(wait(&mut job), Err("cancelled".to_owned()));
        assert_eq!(job.control().fraction(), 1.0);
        assert_eq!(job.control().stage(), "waiting");
    }

    #[test]
    fn a_panicking_worker_is_reported_as_an_error() {
        let mut job: Job<()> = Job::spawn("boom", None, |_| panic!("worker bug"));
        let err = wait(&mut job).unwrap_err();
        assert!(err.contains("boom"), "{err}");
    }
}
