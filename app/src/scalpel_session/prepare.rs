//! Scalpels made off the UI thread before the user presses.
//!
//! A [`ModelCut`] costs time proportional to its model's mesh (the scalpel's half-edge mesh,
//! the index that finds where a stroke starts, the rest mesh's indexes): about a second on two
//! million triangles. The window asks for one when a model is selected in Scalpel mode
//! ([`super::ScalpelSession::prepare`]); the press then takes it ready. A model below
//! [`INLINE_TRIANGLES`] is made at the press (tens of milliseconds at most); a larger one
//! whose scalpel is still being made refuses the press with a message saying so, instead of
//! freezing the window, unless the session waits ([`Prepared::waiting`], the command line).

use std::sync::Arc;
use std::thread::JoinHandle;

use csg::Mesh;

use super::model_cut::ModelCut;

/// Models with fewer triangles get their scalpel at the press, on the calling thread.
pub const INLINE_TRIANGLES: usize = 200_000;

/// At most this many scalpels are made ahead (the selected model and the one before it).
const MAX_JOBS: usize = 2;

/// A scalpel being made for `model` showing `mesh`.
struct Job {
    model: usize,
    mesh: Arc<Mesh>,
    handle: JoinHandle<Result<ModelCut, String>>,
}

/// Scalpels being made ahead (see the module doc).
#[derive(Default)]
pub struct Prepared {
    jobs: Vec<Job>,
    /// Wait for a scalpel being made instead of refusing the press (no UI thread to keep free).
    wait: bool,
}

impl Prepared {
    /// A set that waits for the scalpels it makes (the command line, tests).
    pub fn waiting() -> Prepared {
        Prepared {
            jobs: Vec::new(),
            wait: true,
        }
    }

    /// Starts making the scalpel of `model` showing `mesh` on a thread of its own, unless it is
    /// made already or small enough to be made at the press.
    pub fn start(&mut self, model: usize, mesh: &Arc<Mesh>) {
        if mesh.triangles.len() < INLINE_TRIANGLES
            || self
                .jobs
                .iter()
                .any(|j| j.model == model && Arc::ptr_eq(&j.mesh, mesh))
        {
            return;
        }
        // A job for an older mesh of the model is useless now (its thread finishes unheard).
        self.jobs.retain(|j| j.model != model);
        if self.jobs.len() >= MAX_JOBS {
            self.jobs.remove(0);
        }
        let job = {
            let mesh = mesh.clone();
            std::thread::Builder::new()
                .name("cutaway scalpel prepare".into())
                .spawn(move || {
                    ModelCut::new(model, &mesh).map(|mut cut| {
                        cut.build_faces();
                        cut
                    })
                })
        };
        if let Ok(handle) = job {
            self.jobs.push(Job {
                model,
                mesh: mesh.clone(),
                handle,
            });
        }
    }

    /// Whether the scalpel of `model` showing `mesh` is being made and not ready yet.
    pub fn pending(&self, model: usize, mesh: &Arc<Mesh>) -> bool {
        self.jobs
            .iter()
            .any(|j| j.model == model && Arc::ptr_eq(&j.mesh, mesh) && !j.handle.is_finished())
    }

    /// The scalpel of `model` showing `mesh`: the one made ahead, or made now for a small mesh
    /// (or when waiting). Err: it cannot be cut, or (large, not waiting) it is not ready yet.
    pub(crate) fn take(&mut self, model: usize, mesh: &Arc<Mesh>) -> Result<ModelCut, String> {
        if let Some(k) = self
            .jobs
            .iter()
            .position(|j| j.model == model && Arc::ptr_eq(&j.mesh, mesh))
        {
            if !self.wait && !self.jobs[k].handle.is_finished() {
                return Err(not_ready(mesh));
            }
            let job = self.jobs.remove(k);
            return job
                .handle
                .join()
                .unwrap_or_else(|_| Err("making the scalpel failed".to_string()));
        }
        if self.wait || mesh.triangles.len() < INLINE_TRIANGLES {
            return ModelCut::new(model, mesh);
        }
        self.start(model, mesh);
        Err(not_ready(mesh))
    }
}

/// How the message of a press refused because the scalpel is not ready yet begins.
pub const NOT_READY: &str = "The scalpel is still being prepared";

fn not_ready(mesh: &Mesh) -> String {
    format!(
        "{NOT_READY} for this model ({} triangles); press again in a moment",
        mesh.triangles.len()
    )
}
