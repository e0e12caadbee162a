//! Camera navigation and selection that work the same in every mode, so the user never switches
//! mode just to turn the model or pick another one:
//!
//! - right-drag orbits, middle-drag pans (Scalpel mode has the same drags of its own);
//! - in Edit mode Alt+drag orbits too, and the wheel zooms unless the pointer is over the cutter
//!   (there it sets the whole cutter's depth, with Alt only the plane under the pointer's) or Ctrl
//!   is held (rotates a plane);
//! - a double-click selects the model under the pointer (Camera and Preview also centre on it);
//!   on nothing it clears the selection.
//!
//! Camera and Preview keep their own left-drag orbit and Shift+drag pan in `viewport.rs`.

use glam::DVec2;

use cutter::EditorEvent;

use crate::gui::action::{Action, Mode};
use crate::gui::state::AppState;
pub use crate::gui::state::viewport::NavDrag;
use crate::view::camera_controls;

/// Wheel notches of this frame (positive = wheel up, away from the user), and whether Ctrl/Cmd
/// was held.
pub fn wheel_notches(ui: &egui::Ui) -> (f64, bool) {
    let (notches, ctrl, _) = wheel_input(ui);
    (notches, ctrl)
}

/// Wheel notches of this frame and whether Ctrl/Cmd and Alt were held.
pub fn wheel_input(ui: &egui::Ui) -> (f64, bool, bool) {
    // A frame laid out again (a discarded first pass) sees the same wheel events: they count
    // once, in the first pass.
    if ui.ctx().current_pass_index() > 0 {
        return (0.0, false, false);
    }
    ui.input(|i| {
        let mut notches = 0.0;
        let mut ctrl = false;
        let mut alt = false;
        for event in &i.events {
            if let egui::Event::MouseWheel {
                unit,
                delta,
                modifiers,
                ..
            } = event
            {
                let d = delta.y as f64;
                notches += match unit {
                    egui::MouseWheelUnit::Point => d / 50.0,
                    egui::MouseWheelUnit::Line => d,
                    egui::MouseWheelUnit::Page => d * 10.0,
                };
                ctrl |= modifiers.command || modifiers.ctrl;
                alt |= modifiers.alt;
            }
        }
        (notches, ctrl, alt)
    })
}

/// Handles navigation for this frame. True when it owns the pointer (a navigation drag, or Alt
/// held in Edit mode), so the mode's own input must not see it.
pub fn navigation_input(
    ui: &egui::Ui,
    response: &egui::Response,
    app: &mut AppState,
    ppp: f64,
    to_px: impl Fn(egui::Pos2) -> DVec2,
    actions: &mut Vec<Action>,
) -> bool {
    if response.double_clicked()
        && let Some(pos) = response.interact_pointer_pos()
    {
        let ray = app
            .scene
            .camera
            .ray_through_pixel(app.viewport.size_px, to_px(pos));
        actions.push(match app.viewport.picks.pick(&app.scene, &ray) {
            Some((index, _)) if matches!(app.mode, Mode::Camera | Mode::Preview) => {
                Action::FocusModel(index)
            }
            Some((index, _)) => Action::SelectModel(Some(index)),
            None => Action::SelectModel(None),
        });
    }
    if app.mode == Mode::Scalpel {
        return false;
    }
    let alt = ui.input(|i| i.modifiers.alt);
    let edit = app.mode == Mode::Edit;
    if response.drag_started_by(egui::PointerButton::Secondary)
        || (edit && alt && response.drag_started_by(egui::PointerButton::Primary))
    {
        app.viewport.nav = Some(NavDrag::Orbit);
    } else if response.drag_started_by(egui::PointerButton::Middle) {
        app.viewport.nav = Some(NavDrag::Pan);
    }
    let Some(nav) = app.viewport.nav else {
        if edit
            && response.hovered()
            && let Some(pos) = ui.input(|i| i.pointer.latest_pos())
        {
            edit_wheel(ui, app, to_px(pos));
        }
        return edit && alt && !app.viewport.editor_dragging();
    };
    if response.dragged() {
        let delta = response.drag_delta();
        let delta_px = DVec2::new(delta.x as f64 * ppp, delta.y as f64 * ppp);
        match nav {
            NavDrag::Orbit => camera_controls::orbit(&mut app.scene.camera, delta_px),
            NavDrag::Pan => {
                camera_controls::pan(&mut app.scene.camera, delta_px, app.viewport.size_px)
            }
        }
    }
    if response.drag_stopped() || !ui.input(|i| i.pointer.any_down()) {
        app.viewport.nav = None;
    }
    true
}

/// True when the wheel in Edit mode at pixel `px` goes to the cutter editor: over the active
/// cutter (its depth), or with Ctrl (rotate the selected plane) while a cutter is edited.
pub fn wheel_goes_to_editor(app: &AppState, px: DVec2, ctrl: bool) -> bool {
    app.viewport.editor.is_over_cutter(px)
        || (ctrl && app.viewport.editor.active_cutter().is_some())
}

/// The wheel in Edit mode: to the editor over the cutter (depth of the whole cutter, with Alt of
/// the plane under the pointer; Ctrl rotates a plane), else a zoom of the camera. A depth change
/// says the new depth and what it reaches in the status line.
fn edit_wheel(ui: &egui::Ui, app: &mut AppState, px: DVec2) {
    let (notches, ctrl, alt) = wheel_input(ui);
    if notches == 0.0 {
        return;
    }
    if !wheel_goes_to_editor(app, px, ctrl) {
        let min = crate::scalpel_session::target::defaults_for(&app.scene, app.selected_model)
            .min_camera_distance;
        wheel_zoom(ui, app, notches, min);
        return;
    }
    let event = EditorEvent::Wheel {
        x: px.x,
        y: px.y,
        delta: notches,
        ctrl,
        alt,
    };
    if app.viewport.editor_event(&mut app.scene, event) {
        app.cutters_changed();
        app.say_depth();
    }
}

/// Zooms by `notches` toward what is under the pointer (the nearest visible surface there, else
/// the point on the plane through the camera target), keeping it under the pointer.
pub fn wheel_zoom(ui: &egui::Ui, app: &mut AppState, notches: f64, min_distance: f64) {
    let rect = app.viewport.rect;
    let ppp = ui.ctx().pixels_per_point() as f64;
    let anchor = ui
        .input(|i| i.pointer.latest_pos())
        .filter(|p| rect.contains(*p))
        .map(|p| {
            let px = DVec2::new(
                (p.x - rect.left()) as f64 * ppp,
                (p.y - rect.top()) as f64 * ppp,
            );
            let camera = &app.scene.camera;
            let ray = camera.ray_through_pixel(app.viewport.size_px, px);
            // Never wait for a pick tree still being built: the plane point does then.
            let hit = app
                .viewport
                .picks
                .ready_for(&app.scene)
                .then(|| app.viewport.picks.pick(&app.scene, &ray))
                .flatten();
            match hit {
                Some((_, t)) => ray.at(t),
                None => camera_controls::point_on_target_plane(camera, app.viewport.size_px, px),
            }
        });
    match anchor {
        Some(anchor) => {
            camera_controls::zoom_at(&mut app.scene.camera, notches, min_distance, anchor)
        }
        None => camera_controls::zoom(&mut app.scene.camera, notches, min_distance),
    }
}
