//! Expose in the window: the cutters are planned on a worker (with the exact cut that measures
//! what they remove), then added to the scene as one undo step, and the status line says what
//! was opened. The plan is [`crate::expose`]'s, the same as `cutaway expose`.

use std::sync::Arc;

use crate::cutting::scene_cuts::PreviewKey;
use crate::expose::{Exposed, apply, plan, report::removed_volume_mm3, summary};
use crate::gui::app::CutawayApp;
use crate::gui::job_output::JobOutput;
use crate::scene::Scene;

/// What an exposure was planned on: the cutters and every model's mesh. A result whose scene
/// changed meanwhile is dropped (its cutters were aimed at models as they were).
#[derive(Clone, Debug, PartialEq)]
pub struct ExposeKey {
    cutters: PreviewKey,
    meshes: Vec<usize>,
}

impl ExposeKey {
    pub fn of(scene: &Scene) -> ExposeKey {
        ExposeKey {
            cutters: PreviewKey::of(scene),
            meshes: scene
                .models
                .iter()
                .map(|m| Arc::as_ptr(&m.model.mesh) as usize)
                .collect(),
        }
    }
}

/// Label prefix of the expose job (one runs at a time).
const LABEL: &str = "Exposing";

impl CutawayApp {
    /// Plans the exposure of model `focus` from the current view on a worker.
    pub(super) fn start_expose_job(&mut self, ctx: &egui::Context, focus: usize) {
        let Some(name) = self
            .state
            .scene
            .models
            .get(focus)
            .map(|m| m.model.name.clone())
        else {
            return;
        };
        if self.state.jobs.iter().any(|j| j.label.starts_with(LABEL)) {
            self.state.say("An exposure is already being built");
            return;
        }
        let scene = self.state.scene.clone();
        let settings = self.state.expose;
        self.state.say(format!("{LABEL} {name}…"));
        self.spawn(ctx, format!("{LABEL} {name}"), move |progress| {
            progress.set_message("finding what hides it");
            let exposed = plan(&scene, focus, &settings, progress)?;
            let removed_mm3 = if exposed.cutters.is_empty() {
                None
            } else {
                progress.set_message("cutting");
                let mut after = scene.clone();
                apply(&mut after, &exposed);
                removed_volume_mm3(&after, scene.cutters.len())?
            };
            Ok(JobOutput::Exposed {
                key: ExposeKey::of(&scene),
                exposed: Box::new(exposed),
                removed_mm3,
            })
        });
    }

    /// Adds a finished exposure's cutters to the scene (one undo step) and says what they open.
    pub(super) fn finish_expose(
        &mut self,
        key: ExposeKey,
        exposed: &Exposed,
        removed: Option<f64>,
    ) {
        if key != ExposeKey::of(&self.state.scene) {
            self.state
                .say("The scene changed while Expose ran; nothing was added (press X again)");
            return;
        }
        let line = summary(&self.state.scene, exposed, removed);
        if exposed.cutters.is_empty() {
            self.state.say(line);
            return;
        }
        let before = self.state.scene.clone();
        let first = self.state.scene.cutters.len();
        apply(&mut self.state.scene, exposed);
        self.state.viewport.editor.finish();
        self.state.selected_model = Some(exposed.focus);
        self.state.selected_cutter = first;
        let name = self.state.scene.models[exposed.focus].model.name.clone();
        self.state.record(&format!("expose {name}"), before);
        self.state.say(line);
    }
}
