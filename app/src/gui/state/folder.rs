//! A folder of masks while its structures arrive (see `gui/folder_arrival.rs`).

use std::path::PathBuf;
use std::sync::Mutex;
use std::sync::mpsc::{Receiver, Sender};
use std::time::Duration;

use crate::gui::jobs::{Job, Progress};
use crate::io::Model;
use crate::scene::Scene;
use crate::scene::arrivals::InOrder;

/// One file's outcome from the worker: its number and its structure (None: an empty mask).
pub type Outcome = (usize, Option<Model>);

/// What surfaces a folder's masks on the worker: it sends each file's outcome through the
/// function it is given and returns how many structures there were.
pub trait FolderWork:
    FnOnce(&Progress, &(dyn Fn(Outcome) + Sync)) -> anyhow::Result<usize> + Send + 'static
{
}

impl<F> FolderWork for F where
    F: FnOnce(&Progress, &(dyn Fn(Outcome) + Sync)) -> anyhow::Result<usize> + Send + 'static
{
}

/// The mask folder being opened, if any.
#[derive(Default)]
pub struct FolderArrival {
    pub(in crate::gui) job: Option<Job<usize>>,
    pub(in crate::gui) outcomes: Option<Receiver<Outcome>>,
    pub(in crate::gui) order: InOrder,
    pub(in crate::gui) folder: PathBuf,
    /// The scene the user had before the first structure replaced it (before an earlier
    /// folder's, when this one replaced that opening), restored by Cancel or an error.
    pub(in crate::gui) before: Option<Box<Scene>>,
    /// This folder's first structures replaced the scene.
    pub(in crate::gui) replaced: bool,
    /// The folder is added to the scene (File → Add Model…), not opened: the number of its undo step
    /// ([`crate::session::undo::History::last_number`]).
    pub(in crate::gui) adding: Option<u64>,
    /// The camera the arrivals last framed; while the user has not moved it, every arrival
    /// frames the structures shown so far.
    pub(in crate::gui) framed: Option<cutter::Camera>,
    /// When the first structure was shown, after the job started.
    pub(in crate::gui) first_shown: Option<Duration>,
}

impl FolderArrival {
    /// Starts surfacing `folder` on a worker (a running one is cancelled first); `work` sends
    /// each file's outcome through the sender it is given.
    pub fn start_with(
        &mut self,
        ctx: &egui::Context,
        folder: PathBuf,
        label: String,
        work: impl FolderWork,
    ) {
        let before = self.cancel();
        let (send, receive) = std::sync::mpsc::channel::<Outcome>();
        let send: Mutex<Sender<Outcome>> = Mutex::new(send);
        let repaint = ctx.clone();
        let notify = ctx.clone();
        self.job = Some(Job::spawn(
            label,
            move || repaint.request_repaint(),
            move |progress| {
                work(progress, &|outcome| {
                    let _ = send.lock().unwrap_or_else(|e| e.into_inner()).send(outcome);
                    notify.request_repaint();
                })
            },
        ));
        *self = FolderArrival {
            job: self.job.take(),
            outcomes: Some(receive),
            folder,
            before,
            ..FolderArrival::default()
        };
    }

    /// True while the folder's structures are being made.
    pub fn busy(&self) -> bool {
        self.job.as_ref().is_some_and(Job::is_running)
    }

    /// Fraction of the folder's files done, while the job runs.
    pub fn fraction(&self) -> Option<f32> {
        let job = self.job.as_ref().filter(|j| j.is_running())?;
        Some(job.progress.fraction().unwrap_or(0.0))
    }

    /// Stops the job, if any, and forgets what has not been shown; the scene as it was before
    /// the first structure, if one was shown, is handed back for the caller to restore.
    pub fn cancel(&mut self) -> Option<Box<Scene>> {
        if let Some(job) = &self.job {
            job.progress.cancel();
        }
        let before = self.before.take();
        *self = FolderArrival::default();
        before
    }
}
