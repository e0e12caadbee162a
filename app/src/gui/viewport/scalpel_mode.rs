//! Scalpel mode in the window: maps the pointer to the scalpel session and draws its panel.
//!
//! The cutting itself (the stroke, the layers below, undo, the opening, the delta the view
//! draws) is egui-free in [`crate::scalpel_session`], which `cutaway scalpel` drives too, so a
//! stroke cuts the same in both. This file keeps what only a window has: which button does
//! what (primary drag cuts; Alt or right drag orbits, Shift or middle drag pans, the wheel
//! zooms), the status line, asking for the selected model's scalpel ahead of the press, and the
//! panel's controls.

use glam::DVec2;

use crate::gui::state::AppState;
use crate::scalpel_session::Released;
use crate::view::camera_controls;
use cutter::scalpel::Tool;

use crate::gui::state::viewport::CameraDrag;
pub use crate::gui::state::viewport::ScalpelSlot;
pub use crate::scalpel_session::ScalpelSettings;

/// Viewport input in Scalpel mode: primary drag cuts; Alt+drag or right drag orbits,
/// Shift+drag or middle drag pans, the wheel zooms (the camera stays usable while cutting).
pub fn scalpel_input(
    ui: &egui::Ui,
    response: &egui::Response,
    app: &mut AppState,
    ppp: f64,
    to_px: impl Fn(egui::Pos2) -> DVec2,
) {
    app.viewport.scalpel.rect = response.rect;
    // The selected model's scalpel is made off this thread before the user presses on it.
    let selected = app.selected_model;
    app.viewport.scalpel.session.prepare(&app.scene, selected);
    // Depth and opening follow the selected model until the user sets them.
    let slot = &mut app.viewport.scalpel;
    slot.sizing
        .follow(&app.scene, selected, &mut slot.session.settings);
    let (shift, alt) = ui.input(|i| (i.modifiers.shift, i.modifiers.alt));
    let viewport = app.viewport.size_px;

    // Camera.
    if response.drag_started_by(egui::PointerButton::Primary) && (shift || alt) {
        app.viewport.scalpel.camera_drag = Some(if shift {
            CameraDrag::Pan
        } else {
            CameraDrag::Orbit
        });
    } else if response.drag_started_by(egui::PointerButton::Middle) {
        app.viewport.scalpel.camera_drag = Some(CameraDrag::Pan);
    } else if response.drag_started_by(egui::PointerButton::Secondary) {
        app.viewport.scalpel.camera_drag = Some(CameraDrag::Orbit);
    }
    if response.dragged()
        && let Some(drag) = app.viewport.scalpel.camera_drag
    {
        let d = response.drag_delta();
        let delta = DVec2::new(d.x as f64 * ppp, d.y as f64 * ppp);
        match drag {
            CameraDrag::Orbit => camera_controls::orbit(&mut app.scene.camera, delta),
            CameraDrag::Pan => camera_controls::pan(&mut app.scene.camera, delta, viewport),
        }
    }
    if response.drag_stopped() {
        app.viewport.scalpel.camera_drag = None;
    }
    if response.hovered() {
        let (notches, _) = crate::gui::viewport::navigation::wheel_notches(ui);
        if notches != 0.0 {
            let min = crate::scalpel_session::target::defaults_for(&app.scene, selected)
                .min_camera_distance;
            crate::gui::viewport::navigation::wheel_zoom(ui, app, notches, min);
        }
    }

    // Cutting.
    let Some(pos) = ui.input(|i| i.pointer.latest_pos()) else {
        return;
    };
    let px = to_px(pos);
    let pressed = ui.input(|i| i.pointer.primary_pressed())
        && response.rect.contains(pos)
        && response.hovered()
        && !(shift || alt);
    let released = ui.input(|i| i.pointer.primary_released());
    if pressed {
        // The model the stroke starts on becomes the target, as a new cutter's does, so the
        // blade starts with that model's depth and opening.
        let ray = app.scene.camera.ray_through_pixel(viewport, px);
        if let Some((hit, _)) = app.viewport.picks.pick(&app.scene, &ray)
            && app.selected_model != Some(hit)
        {
            app.selected_model = Some(hit);
            let slot = &mut app.viewport.scalpel;
            slot.sizing
                .follow(&app.scene, Some(hit), &mut slot.session.settings);
        }
        match app.viewport.scalpel.press(&app.scene, viewport, px) {
            Ok(Some(_)) => {}
            Ok(None) => app.say("Press on a model to cut it"),
            Err(e) if e.starts_with(crate::scalpel_session::prepare::NOT_READY) => app.say(e),
            Err(e) => app.complain(&anyhow::anyhow!(e)),
        }
    } else if app.viewport.scalpel.is_cutting() {
        match app.viewport.scalpel.drag(&mut app.scene, viewport, px) {
            Ok(_) if app.viewport.scalpel.off_surface => {
                app.say("The blade left the surface: the cut ends there until it comes back");
            }
            Ok(_) => {}
            Err(e) => app.complain(&anyhow::anyhow!("{e} (the mesh is unchanged)")),
        }
    }
    if released && app.viewport.scalpel.is_cutting() {
        finish_stroke(app);
    }
    if response.hovered() {
        ui.ctx().set_cursor_icon(egui::CursorIcon::Crosshair);
    }
}

/// Ends the stroke in progress and records it for undo.
pub fn finish_stroke(app: &mut AppState) {
    let editor = &app.viewport.editor;
    let released = app
        .viewport
        .scalpel
        .release_with(&mut app.scene, &|mesh| editor.index_for(mesh));
    match released {
        Released::Nothing => {}
        Released::Committed {
            before,
            label,
            message,
            ..
        } => {
            app.record(&label, *before);
            // The cutter editor's target mesh changed: it must not keep using the old one.
            app.viewport.editor.sync_from_scene(&app.scene);
            app.say(message);
        }
        Released::Failed(e) => app.complain(&anyhow::anyhow!(e)),
    }
}

/// The Scalpel panel: tool, depth and opening width of the next strokes.
pub fn scalpel_panel_ui(ui: &mut egui::Ui, app: &mut AppState) {
    // Lengths are edited in millimetres whatever the file's unit (metre-scale bodies too).
    let unit = app.scene.unit;
    let s = &mut app.viewport.scalpel.settings;
    let mm = |ui: &mut egui::Ui, length: &mut f64, tip: &str| {
        let mut value = unit.to_mm(*length);
        let edit = egui::DragValue::new(&mut value)
            .speed(0.1)
            .range(0.0..=1000.0)
            .suffix(" mm")
            .max_decimals(2);
        if ui.add(edit).on_hover_text(tip).changed() {
            *length = unit.from_mm(value);
        }
    };
    ui.horizontal(|ui| {
        ui.label("Tool");
        ui.selectable_value(&mut s.tool, Tool::Scalpel, "Scalpel")
            .on_hover_text("An open cut along the path");
        ui.selectable_value(&mut s.tool, Tool::Loop, "Loop")
            .on_hover_text("A closed path that cuts through and detaches what it encloses");
    });
    ui.horizontal(|ui| {
        ui.label("Depth");
        let tip = "Blade depth; 0 cuts a slit, more cuts a groove with walls";
        mm(ui, &mut s.depth, tip);
    });
    ui.horizontal(|ui| {
        ui.label("Opening");
        let tip = "Width the incision opens to (DFFD), over a trailing window of the tool";
        mm(ui, &mut s.opening, tip);
    });
    ui.checkbox(&mut s.layers, "Cut layers below").on_hover_text(
        "A groove also cuts the other models the blade meets below the surface, down to its depth",
    );
    ui.label(
        egui::RichText::new(
            "Drag on a model to cut; Alt+drag or right drag orbits, Shift+drag pans",
        )
        .small()
        .weak(),
    );
    if let Some(report) = &app.viewport.scalpel.last_report {
        ui.label(egui::RichText::new(report).small());
    }
}

#[cfg(test)]
mod tests;
