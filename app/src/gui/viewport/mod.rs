//! The 3D viewport: input (camera navigation or editor events), the right-click context menu, the
//! gesture recorder, the edited cutter's depth label, and the paint callback that lets the renderer draw offscreen in `prepare` and
//! composite in `paint`.
//!
//! Read in the order size → allocate → interact → paint. Pixel coordinates handed to the camera
//! and the editor are physical pixels of the viewport (origin top-left, y down), the same
//! convention as the gesture format, so a recorded gesture replays identically in `cutaway
//! extrude`.

pub mod cut_view;
pub mod depth_label;
pub mod live_cut;
pub mod navigation;
pub mod orientation_marker;
pub mod risk_legend;
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
    if let Some(held) = &app.viewport.held {
        paint_held(&painter, rect, ppp, held);
    }
    crate::gui::viewport::ruler::paint_rulers(&painter, rect, app);
    crate::gui::viewport::depth_label::paint_depth_label(&painter, rect, app, ppp as f32);
    crate::gui::panels::metrics_panel::paint_closest_points(&painter, rect, app);
    crate::gui::viewport::risk_legend::paint_risk_legend(&painter, rect, app);
    if app.viewport.show_marker && !app.scene.models.is_empty() {
        crate::gui::viewport::orientation_marker::orientation_marker_ui(&painter, rect, &app.scene);
    }
    if let Some(hint) = first_use_hint(app) {
        paint_hint(&painter, rect, &hint);
    }
    if app.scene.models.is_empty() && !app.busy() {
        painter.text(
            rect.center(),
            egui::Align2::CENTER_CENTER,
            "Drop meshes, folders or a session here, or use File > Open…",
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
            crate::gui::viewport::navigation::wheel_zoom(ui, app, notches, min);
        }
    }
}

/// The one line that tells a newcomer how to make the first cut, while the view has none:
/// what to do next from where they are (nothing selected, a structure selected, Edit mode).
pub fn first_use_hint(app: &AppState) -> Option<String> {
    let cut = !app.scene.cutters.is_empty()
        || app.scene.models.iter().any(|m| !m.wall_faces().is_empty());
    if app.scene.models.is_empty() || cut || app.viewport.held.is_some() {
        return None;
    }
    let selected = app
        .selected_model
        .and_then(|i| app.scene.models.get(i))
        .map(|m| m.model.name.as_str());
    Some(match (app.mode, selected) {
        (Mode::Camera | Mode::Preview, None) => {
            "Select a structure (double-click it), press E, drag across it".to_string()
        }
        (Mode::Camera | Mode::Preview, Some(name)) => {
            format!("Press E, then drag across {name} to cut into it")
        }
        (Mode::Edit, None) => "Drag across a structure to cut into it".to_string(),
        (Mode::Edit, Some(name)) => format!("Drag across {name} to cut into it"),
        (Mode::Scalpel, _) => "Drag across a structure to cut along your path".to_string(),
    })
}

/// The hint, centred at the top of the view on a dark plate so it reads on any background.
fn paint_hint(painter: &egui::Painter, rect: egui::Rect, hint: &str) {
    let font = egui::FontId::proportional(16.0);
    let galley = painter.layout_no_wrap(hint.to_string(), font, egui::Color32::WHITE);
    let size = galley.size() + egui::vec2(28.0, 14.0);
    let plate = egui::Rect::from_center_size(
        rect.center_top() + egui::vec2(0.0, 18.0 + size.y / 2.0),
        size,
    );
    painter.rect_filled(plate, 8.0, egui::Color32::from_black_alpha(170));
    painter.galley(
        plate.center() - galley.size() / 2.0,
        galley,
        egui::Color32::WHITE,
    );
}

/// A held drag's path, so the user sees the drag was taken while the target is prepared.
fn paint_held(
    painter: &egui::Painter,
    rect: egui::Rect,
    ppp: f64,
    held: &crate::gui::state::viewport::HeldGesture,
) {
    let points: Vec<egui::Pos2> = held
        .path()
        .iter()
        .map(|p| rect.min + egui::vec2((p.x / ppp) as f32, (p.y / ppp) as f32))
        .collect();
    let colour = egui::Color32::from_rgb(240, 140, 40);
    painter.add(egui::Shape::dashed_line(
        &points,
        egui::Stroke::new(3.0, colour),
        8.0,
        5.0,
    ));
    if let Some(&first) = points.first() {
        painter.circle_filled(first, 4.0, colour);
    }
}

/// One primary-button pointer event of this frame, at the position it happened.
#[derive(Clone, Copy, Debug, PartialEq)]
enum PointerStep {
    Press(egui::Pos2),
    Move(egui::Pos2),
    Release(egui::Pos2),
}

/// This frame's primary-button presses, releases and pointer moves, in the order they came. A
/// slow frame (a software renderer, a big scene) gathers a press and several moves: each reaches
/// the editor at its own position, so a fast first drag starts where it was pressed.
fn pointer_steps(ui: &egui::Ui) -> Vec<PointerStep> {
    ui.input(|i| {
        i.events
            .iter()
            .filter_map(|e| match *e {
                egui::Event::PointerMoved(p) => Some(PointerStep::Move(p)),
                egui::Event::PointerButton {
                    pos,
                    button: egui::PointerButton::Primary,
                    pressed,
                    ..
                } => Some(if pressed {
                    PointerStep::Press(pos)
                } else {
                    PointerStep::Release(pos)
                }),
                _ => None,
            })
            .collect()
    })
}

fn edit_input(
    ui: &egui::Ui,
    response: &egui::Response,
    app: &mut AppState,
    to_px: impl Fn(egui::Pos2) -> DVec2,
    actions: &mut Vec<Action>,
) {
    let (shift, ctrl) = ui.input(|i| (i.modifiers.shift, i.modifiers.command || i.modifiers.ctrl));
    let mut changed = replay_held(app);
    // A frame laid out twice (a discarded sizing pass) brings the same events twice.
    let frame = ui.ctx().cumulative_frame_nr();
    let steps = if app.viewport.input_frame == Some(frame) {
        Vec::new()
    } else {
        app.viewport.input_frame = Some(frame);
        pointer_steps(ui)
    };
    for step in steps {
        changed |= edit_step(ui, response, app, &to_px, step, (shift, ctrl), actions);
    }
    let Some(pos) = ui.input(|i| i.pointer.latest_pos()) else {
        if changed {
            app.cutters_changed();
        }
        return;
    };
    let px = if app.viewport.drag == Some(Drag::Editor) {
        app.viewport.warp.observe(to_px(pos))
    } else {
        to_px(pos)
    };
    if response.hovered() && app.viewport.editor.is_active() {
        changed |= edit_keys(ui, app, px);
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

/// One pointer step in Edit mode; true when the scene's cutters changed.
fn edit_step(
    ui: &egui::Ui,
    response: &egui::Response,
    app: &mut AppState,
    to_px: &impl Fn(egui::Pos2) -> DVec2,
    step: PointerStep,
    (shift, ctrl): (bool, bool),
    actions: &mut Vec<Action>,
) -> bool {
    let (PointerStep::Press(pos) | PointerStep::Move(pos) | PointerStep::Release(pos)) = step;
    let dragging = app.viewport.drag == Some(Drag::Editor);
    let px = if dragging {
        app.viewport.warp.observe(to_px(pos))
    } else {
        to_px(pos)
    };
    let inside = response.rect.contains(pos);
    let modifiers = (shift, ctrl);
    // A drag waiting for its target's index keeps every step until the index is there.
    if let Some(held) = &mut app.viewport.held
        && !held.released()
    {
        match step {
            PointerStep::Move(_) => held.events.push(editor_move(px, modifiers)),
            PointerStep::Release(_) | PointerStep::Press(_) => {
                held.events.push(EditorEvent::Release {
                    x: px.x,
                    y: px.y,
                    shift,
                    ctrl,
                });
            }
        }
        return false;
    }
    let mut changed = false;
    match step {
        PointerStep::Press(_) if inside && response.hovered() => {
            changed |= press_on_view(ui, response, app, px, modifiers, actions);
        }
        PointerStep::Press(_) => {}
        PointerStep::Move(_) => {
            if (inside || dragging)
                && app.viewport.editor.is_active()
                && app.viewport.last_pointer != Some(px)
            {
                app.viewport.last_pointer = Some(px);
                changed |= app
                    .viewport
                    .editor_event(&mut app.scene, editor_move(px, modifiers));
            }
        }
        PointerStep::Release(_) => {
            if dragging {
                app.viewport.drag = None;
                app.viewport.warp = CursorWarp::default();
                let made = app.viewport.editor_event(
                    &mut app.scene,
                    EditorEvent::Release {
                        x: px.x,
                        y: px.y,
                        shift,
                        ctrl,
                    },
                );
                changed |= made;
                if made {
                    // The depth a new or rolled cutter has, and what it reaches.
                    app.say_depth();
                }
            }
        }
    }
    changed
}

fn editor_move(px: DVec2, (shift, ctrl): (bool, bool)) -> EditorEvent {
    EditorEvent::Move {
        x: px.x,
        y: px.y,
        shift,
        ctrl,
    }
}

/// A primary press on the view in Edit mode: on the cutter being edited it edits it; elsewhere it
/// starts a new cutter on the target (the selected model, else the one under the pointer), or,
/// while that target's index is still being built, holds the drag until it is.
fn press_on_view(
    ui: &egui::Ui,
    response: &egui::Response,
    app: &mut AppState,
    px: DVec2,
    modifiers: (bool, bool),
    actions: &mut Vec<Action>,
) -> bool {
    let (shift, ctrl) = modifiers;
    let mut changed = false;
    if app.viewport.editor.is_active() {
        // Hover first so the press is judged where it happens; a press off the cutter being
        // edited starts a new cutter instead of only deselecting its plane.
        app.viewport.last_pointer = Some(px);
        changed |= app
            .viewport
            .editor_event(&mut app.scene, editor_move(px, modifiers));
        if app.viewport.editor.active_cutter().is_some()
            && app.viewport.editor.hovered_plane().is_none()
        {
            let ray = app.scene.camera.ray_through_pixel(app.viewport.size_px, px);
            let selected = app
                .selected_model
                .and_then(|i| app.scene.models.get(i))
                .map(|m| m.model.mesh.clone());
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
    if !app.viewport.editor.is_active() {
        // The first press decides the target: the selected model, else the one under the pointer.
        let target = app.selected_model.or_else(|| {
            let ray = app.scene.camera.ray_through_pixel(app.viewport.size_px, px);
            app.viewport.picks.pick(&app.scene, &ray).map(|(i, _)| i)
        });
        let Some(target) = target else {
            app.say("Press on a model to start a cutter (or double-click one in Camera mode to make it the target)");
            return changed;
        };
        app.selected_model = Some(target);
        if !app.viewport.editor.ensure(
            &app.scene,
            target,
            app.viewport.size_px,
            &app.cutter_init,
            &mut app.viewport.picks,
        ) {
            actions.push(Action::IndexModel(target));
            let name = app.scene.models[target].model.name.clone();
            app.viewport.held = Some(crate::gui::state::viewport::HeldGesture {
                target,
                camera: app.scene.camera,
                events: vec![EditorEvent::Press {
                    x: px.x,
                    y: px.y,
                    shift,
                    ctrl,
                }],
            });
            app.say(format!(
                "Preparing {name} for cutting; your drag is kept and cuts as soon as it is ready"
            ));
            return changed;
        }
    }
    app.viewport
        .editor
        .refresh_obstacles(&app.scene, &mut app.viewport.picks);
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
    changed
}

/// Replays a held drag once its target's index is there (true when the cutters changed); drops
/// it when the view or the scene moved on under it.
fn replay_held(app: &mut AppState) -> bool {
    let Some(held) = &app.viewport.held else {
        return false;
    };
    if held.camera != app.scene.camera || held.target >= app.scene.models.len() {
        app.viewport.held = None;
        app.say("The view moved while the structure was prepared: drag again to cut");
        return false;
    }
    if app
        .viewport
        .editor
        .needs_background_index(&app.scene, held.target)
    {
        return false;
    }
    let Some(held) = app.viewport.held.take() else {
        return false;
    };
    if !app.viewport.editor.ensure(
        &app.scene,
        held.target,
        app.viewport.size_px,
        &app.cutter_init,
        &mut app.viewport.picks,
    ) {
        return false;
    }
    app.viewport
        .editor
        .refresh_obstacles(&app.scene, &mut app.viewport.picks);
    let mut changed = false;
    for event in &held.events {
        if let EditorEvent::Move { x, y, .. } | EditorEvent::Press { x, y, .. } = *event {
            app.viewport.last_pointer = Some(DVec2::new(x, y));
        }
        changed |= app.viewport.editor_event(&mut app.scene, *event);
    }
    app.viewport.warp = CursorWarp::default();
    app.viewport.drag = (!held.released()).then_some(Drag::Editor);
    if changed {
        if held.released() {
            app.say_depth();
        } else {
            let name = app.scene.models[held.target].model.name.clone();
            app.say(format!("Cutter started on {name}"));
        }
    }
    changed
}

/// The keys over the view while a cutter is edited (the wheel goes to the cutter in
/// [`crate::gui::viewport::navigation`]); true when the cutters changed.
fn edit_keys(ui: &egui::Ui, app: &mut AppState, px: DVec2) -> bool {
    let mut changed = false;
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
    changed
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
        Some(m) => format!("Expose {} (X)", m.model.name),
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
