//! The default scene in two steps, so its first frame never waits on the label surfaces: the
//! skin is read at once (milliseconds) and drawn, and the atlas's label surfaces arrive from a
//! background [`Job`](crate::gui::jobs::Job) with their progress and a Cancel in the status bar. While they surface the
//! window works as usual; the user may already orbit, select the skin and cut into it.
//!
//! Arriving structures are appended after the skin (no cutter's target index moves) and to every
//! undo snapshot of the same scene, so that undoing an edit made while they surfaced does not
//! take them away again; their arrival is no undo step of its own. Opening anything that replaces
//! the scene cancels the job ([`AtlasArrival::cancel`]), so a late result never lands in another
//! scene. Cancel keeps the skin.

use std::time::Duration;

use crate::gui::jobs::is_cancelled;
use crate::gui::state::AppState;
pub use crate::gui::state::atlas::AtlasArrival;
use crate::io::Model;

/// Takes the finished job's result, once per frame: the structures join the scene and every
/// undo snapshot; a failure is said in the status bar, the skin stays.
pub fn poll(app: &mut AppState) {
    let Some(job) = app.atlas.job.as_mut() else {
        return;
    };
    let Some(result) = job.poll() else {
        return;
    };
    let took = job.started.elapsed();
    app.atlas.job = None;
    match result {
        Ok(models) => add_structures(app, models, took),
        Err(e) if is_cancelled(&e) => {}
        Err(e) => app.complain(&e.context("head atlas labels")),
    }
}

fn add_structures(app: &mut AppState, models: Vec<Model>, took: Duration) {
    let count = models.len();
    app.append_arrived(models);
    app.say(format!(
        "Loaded the head atlas: {count} structures in {:.1} s, {} triangles",
        took.as_secs_f64(),
        crate::gui::panels::status_bar::grouped(crate::gui::app::triangle_count(&app.scene))
    ));
}

/// The status bar's line while the structures surface: a bar with the fraction done and Cancel.
pub fn status_ui(ui: &mut egui::Ui, app: &mut AppState) {
    let Some(fraction) = app.atlas.fraction() else {
        return;
    };
    let label = format!("{}…", AtlasArrival::LABEL);
    if crate::gui::jobs::arrival_line_ui(ui, &label, fraction) {
        app.atlas.cancel();
        app.say("Head atlas labels cancelled: the skin stays");
    }
}
