//! The 3D viewport: input (camera navigation or editor events), the right-click context menu, the
//! gesture recorder, and the paint callback that lets the renderer draw offscreen in `prepare` and
//! composite in `paint`.
//!
//! Read in the order size → allocate → interact → paint. Pixel coordinates handed to the camera
//! and the editor are physical pixels of the viewport (origin top-left, y down), the same
//! convention as the gesture format, so a recorded gesture replays identically in `cutaway
//! extrude`.

pub mod cut_view;
pub mod live_cut;
pub mod navigation;
pub mod orientation_marker;
pub mod ruler;
pub mod scalpel_mode;
pub mod view_menu;

use glam::{DVec2, DVec3};

use cutter::Camera;
use cutter::events::{EditorEvent, Key};

use crate::gui::action::{Action, Mode};
use crate::gui::state::AppState;
use crate::gui::state::viewport::Drag;
pub use crate::gui::state::viewport::{CursorWarp, Recording, ViewportState};
use crate::view::camera_controls;

/// The viewport panel: fills the remaining space.
pub fn viewport_ui(ui: &mut egui::Ui, app: &mut AppState) -> Vec<Action> {
    let mut actions = Vec::new();
    // Size.
    let size = ui.available_size().max(egui::vec2(16.0, 16.0));
    let ppp = ui.ctx().pixels_per_point() as f64;
    // Allocate.
    let (rect, response) = ui.allocate_exact_size(size, egui::Sense::click_and_drag());
    app.viewport.rect = rect;
    app.viewport.size_px = DVec2::new(
        (rect.width() as f64 * ppp).round(),
        (rect.height() as f64 * ppp).round(),
    );
    let to_px = |p: egui::Pos2| {
        DVec2::new(
            (p.x - rect.left()) as f64 * ppp,
            (p.y - rect.top()) as f64 * ppp,
        )
    };

    // Interact: the image window drag (Shift + right drag, every mode), then navigation and
    // selection (every mode), then the mode's own input.
    let windowing = crate::gui::panels::image_panel::window_drag(app, &response, ui);
    let navigating = windowing
        || crate::gui::viewport::navigation::navigation_input(
            ui,
            &response,
            app,
            ppp,
            to_px,
            &mut actions,
        );
    if !navigating && app.ruler.active {
        // The Ruler tool takes clicks; drags keep turning the camera.
        if !crate::gui::viewport::ruler::ruler_input(&response, app, to_px) {
            camera_input(ui, &response, app, ppp);
        }
    } else if !navigating {
        match app.mode {
            Mode::Camera | Mode::Preview => camera_input(ui, &response, app, ppp),
            Mode::Scalpel => {
                crate::gui::viewport::scalpel_mode::scalpel_input(ui, &response, app, ppp, to_px)
            }
            Mode::Edit => edit_input(ui, &response, app, to_px, &mut actions),
        }
    }
    response.context_menu(|ui| {
        actions.extend(context_menu_ui(ui, app));
    });

    // Paint.
    let painter = ui.painter_at(rect);
    if !crate::gui::bridge::paint_scene(ui, rect, app) {
        crate::gui::bridge::paint_fallback(&painter, rect, app);
    }
    crate::gui::viewport::ruler::paint_rulers(&painter, rect, app);
    crate::gui::panels::metrics_panel::paint_closest_points(&painter, rect, app);
    if app.viewport.show_marker && !app.scene.models.is_empty() {
        crate::gui::viewport::orientation_marker::orientation_marker_ui(&painter, rect, &app.scene);
    }
    if app.scene.models.is_empty() && !app.busy() {
        painter.text(
            rect.center(),
            egui::Align2::CENTER_CENTER,
            "Drop meshes, folders or a session here, or use File > Load Model",
            egui::FontId::proportional(18.0),
            egui::Color32::from_gray(90),
        );
    }
    if let Some(r) = &app.viewport.recording {
        painter.text(
            rect.left_top() + egui::vec2(12.0, 12.0),
            egui::Align2::LEFT_TOP,
            format!("REC gesture ({} events)", r.events.len()),
            egui::FontId::proportional(14.0),
            egui::Color32::from_rgb(220, 40, 40),
        );
    }
    let hovering_files = ui.input(|i| !i.raw.hovered_files.is_empty());
    if hovering_files {
        painter.rect_filled(rect, 0.0, egui::Color32::from_black_alpha(90));
        painter.text(
            rect.center(),
            egui::Align2::CENTER_CENTER,
            "Drop to load",
            egui::FontId::proportional(22.0),
            egui::Color32::WHITE,
        );
    }
    actions
}

fn camera_input(ui: &egui::Ui, response: &egui::Response, app: &mut AppState, ppp: f64) {
    let shift = ui.input(|i| i.modifiers.shift);
    if response.drag_started_by(egui::PointerButton::Primary) {
        app.viewport.drag = Some(if shift { Drag::Pan } else { Drag::Orbit });
    } else if response.drag_started_by(egui::PointerButton::Middle) {
        app.viewport.drag = Some(Drag::Pan);
    }
    if response.dragged() {
        let delta = response.drag_delta();
        let delta_px = DVec2::new(delta.x as f64 * ppp, delta.y as f64 * ppp);
        match app.viewport.drag {
            Some(Drag::Orbit) => camera_controls::orbit(&mut app.scene.camera, delta_px),
            Some(Drag::Pan) => {
                camera_controls::pan(&mut app.scene.camera, delta_px, app.viewport.size_px)
            }
            _ => {}
        }
    }
    if response.drag_stopped() {
        app.viewport.drag = None;
    }
    if response.hovered() {
        let (notches, _) = crate::gui::viewport::navigation::wheel_notches(ui);
        if notches != 0.0 {
            let min = app.scene.bbox().diagonal().max(1e-6) * 1e-3;
            camera_controls::zoom(&mut app.scene.camera, notches, min);
        }
    }
}

fn edit_input(
    ui: &egui::Ui,
    response: &egui::Response,
    app: &mut AppState,
    to_px: impl Fn(egui::Pos2) -> DVec2,
    actions: &mut Vec<Action>,
) {
    let (shift, ctrl) = ui.input(|i| (i.modifiers.shift, i.modifiers.command || i.modifiers.ctrl));
    let Some(pos) = ui.input(|i| i.pointer.latest_pos()) else {
        return;
    };
    let raw_px = to_px(pos);
    let px = if app.viewport.drag == Some(Drag::Editor) {
        app.viewport.warp.observe(raw_px)
    } else {
        raw_px
    };
    let inside = response.rect.contains(pos);
    let pressed = ui.input(|i| i.pointer.primary_pressed()) && inside && response.hovered();
    let released = ui.input(|i| i.pointer.primary_released());
    let mut changed = false;

    if pressed && app.viewport.editor.is_active() && !app.viewport.editor_dragging() {
        // Hover first so the press is judged where it happens; a press off the cutter being
        // edited starts a new cutter instead of only deselecting its plane.
        app.viewport.last_pointer = Some(px);
        changed |= app.viewport.editor_event(
            &mut app.scene,
            EditorEvent::Move {
                x: px.x,
                y: px.y,
                shift,
                ctrl,
            },
        );
        if app.viewport.editor.active_cutter().is_some()
            && app.viewport.editor.hovered_plane().is_none()
        {
            let ray = app.scene.camera.ray_through_pixel(app.viewport.size_px, px);
            let selected = app
                .selected_model
                .and_then(|i| app.scene.models.get(i))
                .map(|m| m.mesh.clone());
            let on_target = selected.is_some_and(|m| app.viewport.picks.hits(&m, &ray));
            let hit = app.viewport.picks.pick(&app.scene, &ray).map(|(i, _)| i);
            if on_target || hit.is_some() {
                if !on_target {
                    app.selected_model = hit;
                }
                app.viewport.editor.finish();
            }
        }
    }
    if pressed && !app.viewport.editor.is_active() {
        // The first press decides the target: the selected model, else the one under the pointer.
        let target = app.selected_model.or_else(|| {
            let ray = app.scene.camera.ray_through_pixel(app.viewport.size_px, px);
            app.viewport.picks.pick(&app.scene, &ray).map(|(i, _)| i)
        });
        let Some(target) = target else {
            app.say("Press on a model to start a cutter (or double-click one in Camera mode to make it the target)");
            return;
        };
        app.selected_model = Some(target);
        if !app
            .viewport
            .editor
            .ensure(&app.scene, target, app.viewport.size_px, &app.cutter_init)
        {
            actions.push(Action::IndexModel(target));
            return;
        }
    }
    if !app.viewport.editor.is_active() {
        return;
    }
    if pressed {
        app.viewport.drag = Some(Drag::Editor);
        app.viewport.last_pointer = Some(px);
        changed |= app.viewport.editor_event(
            &mut app.scene,
            EditorEvent::Press {
                x: px.x,
                y: px.y,
                shift,
                ctrl,
            },
        );
        app.viewport.warp = CursorWarp::default();
        if let Some(handle) = app.viewport.editor.warp.take() {
            app.viewport.warp.requested(handle, px);
            let ppp = ui.ctx().pixels_per_point();
            let to = response.rect.min + egui::vec2(handle.x as f32 / ppp, handle.y as f32 / ppp);
            ui.ctx()
                .send_viewport_cmd(egui::ViewportCommand::CursorPosition(to));
        }
    } else if app.viewport.last_pointer != Some(px)
        && (inside || app.viewport.drag == Some(Drag::Editor))
    {
        app.viewport.last_pointer = Some(px);
        changed |= app.viewport.editor_event(
            &mut app.scene,
            EditorEvent::Move {
                x: px.x,
                y: px.y,
                shift,
                ctrl,
            },
        );
    }
    if released && app.viewport.drag == Some(Drag::Editor) {
        app.viewport.drag = None;
        app.viewport.warp = CursorWarp::default();
        changed |= app.viewport.editor_event(
            &mut app.scene,
            EditorEvent::Release {
                x: px.x,
                y: px.y,
                shift,
                ctrl,
            },
        );
    }
    if response.hovered() {
        let (notches, wheel_ctrl) = crate::gui::viewport::navigation::wheel_notches(ui);
        if notches != 0.0 && crate::gui::viewport::navigation::wheel_goes_to_editor(app, wheel_ctrl)
        {
            changed |= app.viewport.editor_event(
                &mut app.scene,
                EditorEvent::Wheel {
                    x: px.x,
                    y: px.y,
                    delta: notches,
                    ctrl: wheel_ctrl,
                },
            );
        }
        let keys: Vec<Key> = ui.input(|i| {
            let mut keys = Vec::new();
            if i.key_pressed(egui::Key::Delete) || i.key_pressed(egui::Key::Backspace) {
                keys.push(Key::Delete);
            }
            if i.key_pressed(egui::Key::Escape) {
                keys.push(Key::Escape);
            }
            keys
        });
        for key in keys {
            changed |= app.viewport.editor_event(
                &mut app.scene,
                EditorEvent::Key {
                    key,
                    x: px.x,
                    y: px.y,
                },
            );
        }
        let icon = match app.viewport.editor.cursor {
            cutter::CursorHint::Default => egui::CursorIcon::Default,
            cutter::CursorHint::Crosshair => egui::CursorIcon::Crosshair,
            cutter::CursorHint::Grab => egui::CursorIcon::Grab,
            cutter::CursorHint::Grabbing => egui::CursorIcon::Grabbing,
            cutter::CursorHint::Move => egui::CursorIcon::Move,
            cutter::CursorHint::PointingHand => egui::CursorIcon::PointingHand,
        };
        ui.ctx().set_cursor_icon(icon);
    }
    if changed {
        app.cutters_changed();
    }
}

/// The right-click menu of the viewport (thesis 3.5 G).
pub fn context_menu_ui(ui: &mut egui::Ui, app: &AppState) -> Vec<Action> {
    let mut actions = Vec::new();
    if ui.button("Switch to Camera").clicked() {
        actions.push(Action::SetMode(Mode::Camera));
    }
    if ui.button("Switch to Edit").clicked() {
        actions.push(Action::SetMode(Mode::Edit));
    }
    if ui.button("Switch to Preview").clicked() {
        actions.push(Action::SetMode(Mode::Preview));
    }
    ui.separator();
    let selected = app.selected_model.and_then(|i| app.scene.models.get(i));
    let label = match selected {
        Some(m) => format!("Expose {} (X)", m.name),
        None => "Expose Selected (X)".to_string(),
    };
    if ui
        .add_enabled(selected.is_some(), egui::Button::new(label))
        .on_hover_text(crate::gui::panels::models_panel::EXPOSE_HINT)
        .on_disabled_hover_text("Double-click a structure to select it first")
        .clicked()
    {
        actions.push(Action::ExposeSelected);
    }
    if ui.button("Remove All Cut Geometry").clicked() {
        actions.push(Action::RemoveAllCutGeometry);
    }
    let label = if app.cutters_hidden {
        "Show Current Cutters"
    } else {
        "Hide Current Cutters"
    };
    if ui.button(label).clicked() {
        actions.push(Action::ToggleCutters);
    }
    if ui
        .button("New Cutter")
        .on_hover_text("Keep the current cutter; the next drag starts another")
        .clicked()
    {
        actions.push(Action::NewCutter);
    }
    ui.separator();
    if ui.button("Reset Camera").clicked() {
        actions.push(Action::ResetCamera);
    }
    actions
}

/// World-space point under pixel `px` on the pick plane through the camera target (for tools
/// that need a 3D point where nothing is hit); see [`camera_controls::point_on_target_plane`].
pub fn point_on_target_plane(camera: &Camera, viewport: DVec2, px: DVec2) -> DVec3 {
    camera_controls::point_on_target_plane(camera, viewport, px)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn target_plane_point_is_on_the_plane() {
        let camera = Camera {
            eye: DVec3::new(0.0, -300.0, 0.0),
            target: DVec3::ZERO,
            up: DVec3::Z,
            fov_y_deg: 30.0,
        };
        let p = point_on_target_plane(&camera, DVec2::new(800.0, 600.0), DVec2::new(100.0, 50.0));
        assert!(p.y.abs() < 1e-9);
    }
}
