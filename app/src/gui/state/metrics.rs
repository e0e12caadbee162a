//! The Metrics panel's state: what it shows, what it measures next, and the measurement running.

use crate::metrics::{Metrics, MetricsOptions};
use crate::scene::Scene;

use crate::gui::jobs::Job;

/// What a measurement depends on; a new one starts when this changes.
#[derive(Clone, Debug, PartialEq)]
pub(in crate::gui) struct Request {
    preview: crate::cutting::scene_cuts::PreviewKey,
    focus: Option<String>,
    critical: Vec<String>,
    /// Eye and target, only when a focus is measured (exposure is seen from the camera).
    camera: Option<[f64; 6]>,
    /// Mesh, visibility and opacity of every model (they hide the focus or not).
    models: Vec<(usize, bool, u32)>,
}

impl Request {
    pub(in crate::gui) fn of(scene: &Scene, panel: &MetricsPanel) -> Request {
        let c = scene.camera;
        Request {
            preview: crate::cutting::scene_cuts::PreviewKey::of(scene),
            focus: panel.focus.clone(),
            critical: panel.critical.clone(),
            camera: panel.focus.as_ref().map(|_| {
                [
                    c.eye.x, c.eye.y, c.eye.z, c.target.x, c.target.y, c.target.z,
                ]
            }),
            models: scene
                .models
                .iter()
                .map(|m| {
                    (
                        std::sync::Arc::as_ptr(&m.model.mesh) as usize,
                        m.visible,
                        m.opacity.to_bits(),
                    )
                })
                .collect(),
        }
    }
}

/// A finished measurement.
pub struct Measured {
    pub metrics: Metrics,
    /// Wall time of the measurement on the worker, ms.
    pub ms: f64,
}

/// Which cut the removal table shows.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Scope {
    /// Every cutter together, per structure.
    #[default]
    Scene,
    /// One scene cutter.
    Cutter(usize),
}

/// The panel's state.
#[derive(Default)]
pub struct MetricsPanel {
    /// The panel is shown (and measurements run).
    pub open: bool,
    pub scope: Scope,
    /// Structure whose exposure is measured.
    pub focus: Option<String>,
    /// Structures whose distance to the cut walls is measured, in the order marked.
    pub critical: Vec<String>,
    /// The newest finished measurement, or why it failed.
    pub shown: Option<Result<Measured, String>>,
    pub(in crate::gui) shown_request: Option<Request>,
    pub(in crate::gui) job: Option<(Request, Job<Measured>)>,
}

impl MetricsPanel {
    /// True while a measurement runs.
    pub fn busy(&self) -> bool {
        self.job.is_some()
    }

    /// Whether the shown numbers describe the scene as it is now.
    pub fn is_current(&self, scene: &Scene) -> bool {
        self.shown_request.as_ref() == Some(&Request::of(scene, self))
    }

    /// Marks or unmarks `name` as critical.
    pub fn set_critical(&mut self, name: &str, critical: bool) {
        self.critical.retain(|n| n != name);
        if critical {
            self.critical.push(name.to_string());
        }
    }

    /// The options the measurement uses (the CLI's `--focus` and `--critical`).
    pub fn options(&self) -> MetricsOptions {
        MetricsOptions {
            focus: self.focus.clone(),
            critical: self.critical.clone(),
            ..MetricsOptions::default()
        }
    }
}
