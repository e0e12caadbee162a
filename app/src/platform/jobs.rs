//! Background work with progress and cancel, so the UI thread never waits on a load, an index
//! build, a boolean or a file dialog.
//!
//! A [`Job`] is a worker thread plus a shared [`Progress`]. The UI polls it once per frame; the
//! worker asks for a repaint when it finishes so a finished job is noticed without mouse motion.
//! Cancelling sets a flag the worker checks between steps (files of a directory, models of a
//! scene); work inside one step cannot be interrupted, so a cancelled job's late result is
//! dropped rather than applied. The progress window appears only for jobs running longer than
//! [`Job::SHOW_AFTER`] (quick loads never flash a dialog).

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::mpsc::{Receiver, TryRecvError, channel};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// Progress shared between a worker and the UI. All methods are cheap and lock-free except the
/// message, which the UI reads at most once per frame.
#[derive(Debug, Default)]
pub struct Progress {
    /// Units of work finished; never more than `total` when `total` is non-zero.
    done: AtomicU64,
    /// Units of work in all; 0 when unknown (the bar then spins).
    total: AtomicU64,
    cancelled: AtomicBool,
    /// What the worker is doing right now, e.g. the file being read.
    message: Mutex<String>,
}

impl Progress {
    /// Records `done` of `total` units.
    pub fn set(&self, done: u64, total: u64) {
        self.total.store(total, Ordering::Relaxed);
        self.done.store(
            if total > 0 { done.min(total) } else { done },
            Ordering::Relaxed,
        );
    }

    /// Sets the line shown under the bar.
    pub fn set_message(&self, message: impl Into<String>) {
        if let Ok(mut m) = self.message.lock() {
            *m = message.into();
        }
    }

    /// The line shown under the bar.
    pub fn message(&self) -> String {
        self.message.lock().map(|m| m.clone()).unwrap_or_default()
    }

    /// Fraction done in 0..=1, or `None` when the total is unknown.
    pub fn fraction(&self) -> Option<f32> {
        let total = self.total.load(Ordering::Relaxed);
        (total > 0)
            .then(|| (self.done.load(Ordering::Relaxed) as f64 / total as f64).min(1.0) as f32)
    }

    /// Asks the worker to stop at its next check.
    pub fn cancel(&self) {
        self.cancelled.store(true, Ordering::Relaxed);
    }

    /// True once [`Progress::cancel`] was called; workers check it between steps.
    pub fn is_cancelled(&self) -> bool {
        self.cancelled.load(Ordering::Relaxed)
    }

    /// `Err` when cancelled, for `?` in workers.
    pub fn check(&self) -> anyhow::Result<()> {
        if self.is_cancelled() {
            anyhow::bail!(Cancelled);
        }
        Ok(())
    }
}

/// The error a cancelled job ends with; the UI drops it silently.
#[derive(Debug, thiserror::Error)]
#[error("cancelled")]
pub struct Cancelled;

/// True when `error` is (or wraps) [`Cancelled`].
pub fn is_cancelled(error: &anyhow::Error) -> bool {
    error.downcast_ref::<Cancelled>().is_some()
}

/// One background computation producing a `T`.
pub struct Job<T> {
    /// What the progress window says, e.g. "Loading knee.obj".
    pub label: String,
    pub started: Instant,
    pub progress: Arc<Progress>,
    result: Receiver<anyhow::Result<T>>,
    /// False once the result was taken (or the worker died).
    running: bool,
}

impl<T: Send + 'static> Job<T> {
    /// Jobs shorter than this never show a progress window.
    pub const SHOW_AFTER: Duration = Duration::from_millis(500);

    /// Runs `work` on a new thread. `repaint` is called when the job ends (pass
    /// `egui::Context::request_repaint` wrapped in a closure; tests may pass a no-op).
    pub fn spawn(
        label: impl Into<String>,
        repaint: impl Fn() + Send + 'static,
        work: impl FnOnce(&Progress) -> anyhow::Result<T> + Send + 'static,
    ) -> Job<T> {
        let progress = Arc::new(Progress::default());
        let (tx, rx) = channel();
        let worker_progress = progress.clone();
        let label = label.into();
        let thread_name = format!("cutaway job: {label}");
        let spawned = std::thread::Builder::new()
            .name(thread_name)
            .spawn(move || {
                let result = work(&worker_progress);
                // The receiver is gone when the UI dropped the job (cancel or exit): nothing to do.
                let _ = tx.send(result);
                repaint();
            });
        if let Err(e) = spawned {
            let (tx, rx2) = channel();
            let _ = tx.send(Err(anyhow::anyhow!("could not start a worker thread: {e}")));
            return Job {
                label,
                started: Instant::now(),
                progress,
                result: rx2,
                running: true,
            };
        }
        Job {
            label,
            started: Instant::now(),
            progress,
            result: rx,
            running: true,
        }
    }

    /// The result once the worker finished; `None` while it runs and after the result was taken.
    /// A job cancelled before its result is taken ends [`Cancelled`] even when the worker
    /// finished its last step anyway: Cancel never lets a late result into the scene.
    pub fn poll(&mut self) -> Option<anyhow::Result<T>> {
        if !self.running {
            return None;
        }
        match self.result.try_recv() {
            Ok(_) if self.progress.is_cancelled() => {
                self.running = false;
                Some(Err(Cancelled.into()))
            }
            Ok(result) => {
                self.running = false;
                Some(result)
            }
            Err(TryRecvError::Empty) => None,
            Err(TryRecvError::Disconnected) => {
                self.running = false;
                Some(Err(anyhow::anyhow!(
                    "{}: the worker stopped unexpectedly",
                    self.label
                )))
            }
        }
    }

    /// Blocks until the job ends (tests and exit paths only; never called from the UI loop).
    pub fn wait(mut self, timeout: Duration) -> anyhow::Result<T> {
        match self.result.recv_timeout(timeout) {
            Ok(result) => {
                self.running = false;
                result
            }
            Err(_) => anyhow::bail!("{}: no result within {:?}", self.label, timeout),
        }
    }

    /// True while the result has not been taken.
    pub fn is_running(&self) -> bool {
        self.running
    }

    /// True when the job has run long enough to deserve a progress window.
    pub fn wants_progress_window(&self) -> bool {
        self.running && self.started.elapsed() >= Self::SHOW_AFTER
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_job_delivers_its_result_and_progress() {
        let mut job = Job::spawn(
            "sum",
            || {},
            |p| {
                p.set(1, 2);
                p.set_message("half");
                Ok(21 * 2)
            },
        );
        let deadline = Instant::now() + Duration::from_secs(10);
        let result = loop {
            if let Some(r) = job.poll() {
                break r;
            }
            assert!(Instant::now() < deadline, "job never finished");
            std::thread::sleep(Duration::from_millis(2));
        };
        assert_eq!(result.unwrap(), 42);
        assert_eq!(job.progress.fraction(), Some(0.5));
        assert_eq!(job.progress.message(), "half");
        assert!(job.poll().is_none(), "the result is delivered once");
    }

    #[test]
    fn cancel_stops_a_worker_between_steps() {
        let (go_tx, go_rx) = channel::<()>();
        let job = Job::spawn(
            "steps",
            || {},
            move |p| {
                let _ = go_rx.recv();
                for i in 0..1000u64 {
                    p.check()?;
                    p.set(i, 1000);
                    std::thread::sleep(Duration::from_millis(1));
                }
                Ok(())
            },
        );
        job.progress.cancel();
        go_tx.send(()).unwrap();
        let err = job.wait(Duration::from_secs(10)).unwrap_err();
        assert!(is_cancelled(&err), "{err:#}");
    }

    /// The race a fast index build hits: the worker finishes its only step, then the user
    /// presses Cancel before the UI takes the result. The result must not be applied.
    #[test]
    fn a_result_that_arrives_after_cancel_is_dropped() {
        let (done_tx, done_rx) = channel::<()>();
        let mut job = Job::spawn(
            "one step",
            move || {
                let _ = done_tx.send(());
            },
            |_| Ok(42u32),
        );
        done_rx
            .recv_timeout(Duration::from_secs(10))
            .expect("the worker finished");
        job.progress.cancel();
        let result = job.poll().expect("the job has ended");
        let err = result.expect_err("a cancelled job's late result was delivered");
        assert!(is_cancelled(&err), "{err:#}");
        assert!(!job.is_running());
        assert!(job.poll().is_none());
    }

    #[test]
    fn a_panicking_worker_reports_an_error() {
        let job: Job<()> = Job::spawn(
            "boom",
            || {},
            |_| panic!("worker panic (expected in this test)"),
        );
        let mut job = job;
        let deadline = Instant::now() + Duration::from_secs(10);
        loop {
            if let Some(r) = job.poll() {
                assert!(r.is_err());
                break;
            }
            assert!(Instant::now() < deadline);
            std::thread::sleep(Duration::from_millis(2));
        }
    }
}
