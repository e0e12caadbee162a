//! The default scene's label surfaces while they arrive (see `gui/atlas_arrival.rs`).

use crate::gui::jobs::{Job, Progress};
use crate::io::Model;

/// The label surfaces of the default scene while they are made.
#[derive(Default)]
pub struct AtlasArrival {
    pub(in crate::gui) job: Option<Job<Vec<Model>>>,
}

impl AtlasArrival {
    /// What the status bar says while the surfaces are made.
    pub const LABEL: &'static str = "Surfacing the head atlas";

    /// Starts surfacing the atlas's labels (a running job is cancelled first).
    pub fn start(&mut self, ctx: &egui::Context) {
        self.start_with(ctx, |progress| {
            crate::anatomy::default_scene::load_structures(&|fraction| {
                progress.set((fraction.clamp(0.0, 1.0) * 1000.0) as u64, 1000);
                !progress.is_cancelled()
            })
        });
    }

    /// [`AtlasArrival::start`] with the structures made by `work` (tests hold the job open
    /// with it, whatever the machine's speed).
    pub fn start_with(
        &mut self,
        ctx: &egui::Context,
        work: impl FnOnce(&Progress) -> anyhow::Result<Vec<Model>> + Send + 'static,
    ) {
        self.cancel();
        let ctx = ctx.clone();
        self.job = Some(Job::spawn(Self::LABEL, move || ctx.request_repaint(), work));
    }

    /// True while the surfaces are being made.
    pub fn busy(&self) -> bool {
        self.job.as_ref().is_some_and(Job::is_running)
    }

    /// Fraction of the labels' voxels done, while the job runs.
    pub fn fraction(&self) -> Option<f32> {
        let job = self.job.as_ref().filter(|j| j.is_running())?;
        Some(job.progress.fraction().unwrap_or(0.0))
    }

    /// Stops the job, if any; its result, if it still comes, is dropped. True when one ran.
    pub fn cancel(&mut self) -> bool {
        match self.job.take() {
            Some(job) => {
                job.progress.cancel();
                job.is_running()
            }
            None => false,
        }
    }
}
