//! The window's side of the live cut (the worker and its caches are [`crate::cutting::live_cut`]):
//! once per frame, take a finished cut and, in Edit mode, ask for the cut of the current cutters,
//! with a repaint of the window as the wake-up.

use std::sync::Arc;

/// Once per frame: takes a finished live cut (its time goes to the status line) and, in Edit
/// mode with "Live cut" on, asks for the cut of the current cutters.
pub fn update_live(app: &mut crate::gui::state::AppState, ctx: &egui::Context) {
    let live = &mut app.viewport.live;
    if live.poll()
        && let Some(r) = live.shown()
    {
        app.status.last_cut_ms = Some(r.ms);
    }
    if app.mode != crate::gui::action::Mode::Edit || !live.enabled {
        // Outside Edit mode the models may change under it (Remove All Cut Geometry, loads):
        // start afresh when Edit mode comes back.
        if live.holds_a_cut() {
            live.clear();
        }
        return;
    }
    if app.scene.cutters.is_empty() {
        live.clear();
        return;
    }
    let ctx = ctx.clone();
    live.request(&app.scene, Some(Arc::new(move || ctx.request_repaint())));
}
